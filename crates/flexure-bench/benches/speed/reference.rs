//! The exact references: the elastica's cost across the range of tip
//! angles, and the exact connection by 22 rigid segments.
//!
//! The elastica family is a tip moment with an axial compression,
//! $M = \sigma EI/L$ and $F_x = -\sigma EI/L^2$ on $L = EI = 1$ (a gripper
//! jaw closing on a part that pushes back): loaded from rest it stays
//! stable, without a limit point, as its tip turns past 270°. The four
//! load factors $\sigma$ give exact tip angles of 45°, 90°, 180° and 270°
//! (`crates/flexure/tests/elastica_speed.rs` checks them to 1e-6 rad).

use criterion::Criterion;
use flexure::connect::connect;
use flexure::reference::elastica;
use flexure::{Flexure, Pose, TipLoad};
use std::f64::consts::FRAC_PI_2;
use std::hint::black_box;

/// The load factors σ of the family and the exact tip angles (degrees) they give.
const SIGMA: [(u32, f64); 4] =
    [(45, 0.625533351650362), (90, 1.1040855403497616), (180, 2.4266552501655885), (270, 5.073997874961178)];

pub fn run(c: &mut Criterion) {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let mut g = c.benchmark_group("reference");
    g.sample_size(20);
    for (degrees, sigma) in SIGMA {
        let load = TipLoad { moment: sigma, fx: -sigma, fy: 0.0 };
        g.bench_function(format!("elastica_{degrees}"), |b| {
            b.iter(|| elastica::deflect(&f, black_box(&load), &Default::default()).unwrap())
        });
    }
    let target = Pose { phi: FRAC_PI_2, x: 0.55, y: 0.65 };
    let chain = Flexure::segments(1.0, 1.0, 22).unwrap();
    g.bench_function("segments_22", |b| b.iter(|| connect(&chain, black_box(&target)).unwrap()));
    g.finish();
}
