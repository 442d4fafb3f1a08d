//! The spatial flexure's SE(3) kinematics (6th-order Magnus over the
//! default subintervals), order 3 per component, against the planar
//! `joint/pose` of the same run.

use criterion::Criterion;
use flexure::Level;
use flexure::section::SpatialSection;
use flexure::spatial::{SpatialFlexure, SpatialKinematics, pose_root_tip, update};
use std::hint::black_box;

use crate::inputs;

pub fn run(c: &mut Criterion) {
    let f = SpatialFlexure::new(1.0, SpatialSection::uniform(0.8, 1.2, 1.0).unwrap(), [3, 3, 3]).unwrap();
    let alphas = inputs(1024, 9);
    let mut g = c.benchmark_group("spatial");
    let mut i = 0;
    g.bench_function("pose", |b| {
        b.iter(|| {
            i = (i + 9) % alphas.len();
            pose_root_tip(&f, black_box(&alphas[i..i + 9])).1.x
        })
    });
    let mut k = SpatialKinematics::new(&f);
    g.bench_function("pose_jacobian", |b| {
        b.iter(|| {
            i = (i + 9) % alphas.len();
            update(&f, black_box(&alphas[i..i + 9]), Level::Jacobian, &mut k);
            k.jacobian[(5, 8)]
        })
    });
    g.bench_function("pose_jacobian_hessian", |b| {
        b.iter(|| {
            i = (i + 9) % alphas.len();
            update(&f, black_box(&alphas[i..i + 9]), Level::Hessian, &mut k);
            k.hessian_position(8, 8).x
        })
    });
    g.finish();
}
