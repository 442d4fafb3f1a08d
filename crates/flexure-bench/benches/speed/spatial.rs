//! The spatial flexure's SE(3) kinematics (6th-order Magnus over the
//! default subintervals), order 3 per component, against the planar
//! `joint/pose` of the same run; its `deflect` under a 3-D tip wrench
//! against `pose_jacobian_hessian`; and the Bathe–Bolourchi bend at the
//! rod's parameters (GJ = EI), orders 3 (the tip within 2.4e-4 of L of the
//! rod, tests/spatial_validation.rs), at the default subintervals and at
//! the two that suffice for 1e-3 of L, against `rod/bathe_bolourchi_tol_1e-3`;
//! and the Jacobian and Hessian at the order cap, [64, 64, 64]; and
//! the door's `deflect` with its error estimate at orders [4, 4, 4], the
//! call Python's `SpatialFlexure.deflect` makes (issue 37 item 5: that call
//! is timed from Python against this one, `scripts/python_speed.py`).

use criterion::Criterion;
use flexure::Level;
use flexure::model::{Deflect, OneFlexure};
use flexure::section::SpatialSection;
use flexure::spatial::{
    SpatialFlexure, SpatialKinematics, SpatialLoad, SpatialStatics, deflect, pose_root_tip, update,
};
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
    // The order cap, [64, 64, 64] (n = 192): the Hessian's cost is that of
    // a solve's Newton iteration at the cap (issue 39: 16-45 s to solve).
    let cap = SpatialFlexure::new(1.0, SpatialSection::uniform(0.8, 1.2, 1.0).unwrap(), [64, 64, 64]).unwrap();
    let alpha_cap: Vec<f64> = (0..192).map(|a| 0.3 * alphas[a % alphas.len()] / (1 + a / 3) as f64).collect();
    let mut k_cap = SpatialKinematics::new(&cap);
    // The Jacobian at the cap: what each of a solve's Newton evaluations takes.
    g.bench_function("pose_jacobian_order_64", |b| {
        b.iter(|| {
            update(&cap, black_box(&alpha_cap), Level::Jacobian, &mut k_cap);
            k_cap.jacobian[(5, 191)]
        })
    });
    g.bench_function("pose_jacobian_hessian_order_64", |b| {
        b.iter(|| {
            update(&cap, black_box(&alpha_cap), Level::Hessian, &mut k_cap);
            k_cap.hessian_position(191, 191).x
        })
    });
    let load = SpatialLoad { moment: [0.1, 0.2, 0.3], force: [0.2, 0.5, 0.4] };
    let mut data = SpatialStatics::new(&f);
    g.bench_function("deflect", |b| {
        b.iter(|| deflect(&f, black_box(&load), &mut data, &Default::default()).unwrap().iterations)
    });
    let (r, ei) = (100.0, 1e7 / 12.0);
    let mut rest = vec![0.0; 9];
    rest[6] = std::f64::consts::FRAC_PI_4;
    let bend =
        SpatialFlexure::new(std::f64::consts::PI * r / 4.0, SpatialSection::uniform(ei, ei, ei).unwrap(), [3, 3, 3])
            .unwrap()
            .with_rest(&rest)
            .unwrap();
    let out_of_plane = SpatialLoad { moment: [0.0; 3], force: [0.0, 0.0, 600.0] };
    let mut bent = SpatialStatics::new(&bend);
    g.bench_function("bathe_bolourchi", |b| {
        b.iter(|| deflect(&bend, black_box(&out_of_plane), &mut bent, &Default::default()).unwrap().iterations)
    });
    // The fewest subintervals for 1e-3 of L: two put the tip 5e-6 L from eight's.
    let coarse = bend.clone().with_subintervals(2).unwrap();
    let mut data = SpatialStatics::new(&coarse);
    g.bench_function("bathe_bolourchi_1e-3", |b| {
        b.iter(|| deflect(&coarse, black_box(&out_of_plane), &mut data, &Default::default()).unwrap().iterations)
    });
    // EI_z = EI_y = GJ = 1, L = 1, orders 4: SpatialFlexure(1.0, ei=1.0, order=4, ei_y=1.0, gj=1.0) in Python.
    let four = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [4, 4, 4]).unwrap();
    let options =
        Deflect { load: SpatialLoad { moment: [0.2, 0.1, 0.3], force: [0.1, 0.2, 0.3] }, ..Default::default() };
    g.bench_function("deflect_with_estimate_order_4", |b| {
        b.iter(|| OneFlexure::from(black_box(&four).clone()).deflect(&options).unwrap().model().residual)
    });
    g.finish();
}
