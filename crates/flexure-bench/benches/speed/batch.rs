//! Many poses at once.

use criterion::{Criterion, Throughput};
use flexure::kinematics::par_poses_root_tip;
use flexure::{Flexure, Pose};
use std::hint::black_box;

use crate::inputs;

pub fn run(c: &mut Criterion) {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let alphas = inputs(1_000_000, 3);
    let mut poses = vec![Pose::default(); 1_000_000];
    let mut g = c.benchmark_group("batch");
    g.sample_size(10);
    g.throughput(Throughput::Elements(1_000_000));
    g.bench_function("pose_1m", |b| b.iter(|| par_poses_root_tip(&f, black_box(&alphas), &mut poses).unwrap()));
    g.bench_function("pose_1m_serial", |b| {
        b.iter(|| flexure::kinematics::poses_root_tip(&f, black_box(&alphas), &mut poses).unwrap())
    });
    g.finish();
}
