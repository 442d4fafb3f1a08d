//! Single-joint statics (the exact references solving such tasks are in `reference.rs`).

use criterion::Criterion;
use flexure::connect::{ConnectData, connect_with};
use flexure::estimate::{Accuracy, Estimator};
use flexure::{Flexure, Pose, Settings, StaticsData, TipLoad, deflect};
use std::f64::consts::FRAC_PI_2;
use std::hint::black_box;

pub fn run(c: &mut Criterion) {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let load = TipLoad::polar(0.0, 3.8477, 45f64.to_radians());
    let mut data = StaticsData::new(&f);
    let settings = Settings { tolerance: 1e-12, ..Default::default() };
    let target = Pose { phi: FRAC_PI_2, x: 0.55, y: 0.65 };
    // Buffers made once, as for deflect_90: the solve itself is measured.
    let mut connect_data = ConnectData::new(&f);
    // As a user estimating every answer of one flexure: the estimator (its reference model and buffers) made once.
    let (mut estimator, accuracy) = (Estimator::new(), Accuracy::default());
    let mut g = c.benchmark_group("statics");
    g.bench_function("deflect_90", |b| b.iter(|| deflect(&f, black_box(&load), &mut data, &settings).unwrap()));
    g.bench_function("deflect_90_estimated", |b| {
        b.iter(|| {
            deflect(&f, black_box(&load), &mut data, &settings).unwrap();
            estimator.deflect_error(&f, &load, data.alpha(), &accuracy).unwrap()
        })
    });
    g.bench_function("connect", |b| b.iter(|| connect_with(&f, black_box(&target), &mut connect_data).unwrap()));
    g.finish();
}
