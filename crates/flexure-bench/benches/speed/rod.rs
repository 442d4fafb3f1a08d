//! The exact Kirchhoff rod on the Bathe–Bolourchi 45° bend (R = 100, unit
//! square, E = 1e7, GJ = EI, 600 out of the plane), at the integrator
//! tolerance 1e-3 (the tip within 1e-9·L of the converged rod, far inside
//! issue 23's 1e-3·L) and at the defaults (path 1e-6, answer 1e-12): the
//! reference the spatial model is timed against.

use criterion::Criterion;
use flexure::reference::rod::{self, Rod, ShootingSettings};
use flexure::section::SpatialSection;
use flexure::spatial::SpatialLoad;
use std::hint::black_box;

pub fn run(c: &mut Criterion) {
    let (r, ei) = (100.0, 1e7 / 12.0);
    let bend = Rod::new(std::f64::consts::PI * r / 4.0, SpatialSection::uniform(ei, ei, ei).unwrap())
        .unwrap()
        .with_rest(move |_| [0.0, 0.0, 1.0 / r])
        .unwrap();
    let load = SpatialLoad { moment: [0.0; 3], force: [0.0, 0.0, 600.0] };
    let mut g = c.benchmark_group("rod");
    g.sample_size(10);
    let loose = ShootingSettings::with_tolerance(1e-3);
    g.bench_function("bathe_bolourchi_tol_1e-3", |b| b.iter(|| rod::deflect(&bend, black_box(&load), &loose).unwrap()));
    g.bench_function("bathe_bolourchi_default", |b| {
        b.iter(|| rod::deflect(&bend, black_box(&load), &ShootingSettings::default()).unwrap())
    });
    g.finish();
}
