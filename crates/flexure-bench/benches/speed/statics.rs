//! Single-joint statics, and the exact references solving the same tasks.

use criterion::Criterion;
use flexure::connect::connect;
use flexure::reference::elastica;
use flexure::{Flexure, Pose, Settings, Statics, TipLoad, deflect};
use std::f64::consts::FRAC_PI_2;
use std::hint::black_box;

pub fn run(c: &mut Criterion) {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let load = TipLoad::polar(0.0, 3.8477, 45f64.to_radians());
    let mut data = Statics::new(&f);
    let settings = Settings { tolerance: 1e-12, ..Default::default() };
    let target = Pose { phi: FRAC_PI_2, x: 0.55, y: 0.65 };
    let mut g = c.benchmark_group("statics");
    g.bench_function("deflect_90", |b| b.iter(|| deflect(&f, black_box(&load), &mut data, &settings).unwrap()));
    g.bench_function("connect", |b| b.iter(|| connect(&f, black_box(&target)).unwrap()));
    g.finish();

    let mut g = c.benchmark_group("reference");
    g.sample_size(20);
    g.bench_function("elastica_90", |b| {
        b.iter(|| elastica::deflect(&f, black_box(&load), &Default::default()).unwrap())
    });
    let chain = Flexure::segments(1.0, 1.0, 22).unwrap();
    g.bench_function("segments_22", |b| b.iter(|| connect(&chain, black_box(&target)).unwrap()));
    g.finish();
}
