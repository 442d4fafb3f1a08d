//! The kernel against its floor: five sin/cos pairs.

use criterion::{BenchmarkId, Criterion};
use flexure::Flexure;
use flexure::kinematics::{Kinematics, Level, pose_root_tip, update};
use std::hint::black_box;

use crate::inputs;

pub fn run(c: &mut Criterion) {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let alphas = inputs(1024, 3);
    // The floor: the five sin/cos pairs one evaluation needs, of the very
    // angles φ(t_k) the kernel meets for the same α sequence (libm's cost
    // depends on the argument's range, so other arguments would be a
    // different floor).
    let mut psi = [0.0; 3];
    let angles: Vec<f64> = alphas
        .chunks_exact(3)
        .flat_map(|a| {
            f.nodes()
                .iter()
                .map(|&t| {
                    f.angle_shapes(t, &mut psi);
                    psi.iter().zip(a).map(|(p, x)| p * x).sum::<f64>()
                })
                .collect::<Vec<_>>()
        })
        .collect();
    let mut g = c.benchmark_group("limit");
    let mut i = 0;
    g.bench_function("sincos5", |b| {
        b.iter(|| {
            i = (i + 5) % angles.len();
            let mut acc = 0.0;
            for &x in black_box(&angles[i..i + 5]) {
                let (s, c) = x.sin_cos();
                acc += s + c;
            }
            acc
        })
    });
    g.finish();

    // The kernel's own node trigonometry on the same angles: all five at
    // once, vectorized (flexure::sincos), against the floor's libm calls.
    let mut g = c.benchmark_group("sincos");
    g.bench_function("nodes5", |b| {
        b.iter(|| {
            i = (i + 5) % angles.len();
            let x: [f64; 5] = black_box(angles[i..i + 5].try_into().expect("five angles"));
            let out = flexure::sincos::cos_sin(&x);
            out.iter().map(|[c, s]| c + s).sum::<f64>()
        })
    });
    g.finish();

    let mut g = c.benchmark_group("joint");
    let mut i = 0;
    g.bench_function("pose", |b| {
        b.iter(|| {
            i = (i + 3) % alphas.len();
            pose_root_tip(&f, black_box(&alphas[i..i + 3]))
        })
    });
    let mut k = Kinematics::new(&f);
    g.bench_function("pose_jacobian_hessian", |b| {
        b.iter(|| {
            i = (i + 3) % alphas.len();
            update(&f, black_box(&alphas[i..i + 3]), &mut k, Level::Hessian);
            k.hessian_root_tip_y[(2, 2)]
        })
    });
    g.finish();

    // Cost against the number of quadrature points (default N + 2).
    let mut g = c.benchmark_group("order");
    for n in [3, 6, 12] {
        let f = Flexure::new(1.0, 1.0, n).unwrap();
        let alphas = inputs(256, n);
        let mut k = Kinematics::new(&f);
        let mut i = 0;
        g.bench_with_input(BenchmarkId::new("pose", n), &n, |b, &n| {
            b.iter(|| {
                i = (i + n) % alphas.len();
                pose_root_tip(&f, black_box(&alphas[i..i + n]))
            })
        });
        g.bench_with_input(BenchmarkId::new("pose_jacobian_hessian", n), &n, |b, &n| {
            b.iter(|| {
                i = (i + n) % alphas.len();
                update(&f, black_box(&alphas[i..i + n]), &mut k, Level::Hessian);
                k.pose_root_tip.x
            })
        });
    }
    g.finish();

    // At a fixed order, cost against the number of quadrature points: linear.
    let mut g = c.benchmark_group("quadrature");
    for q in [5, 10, 20, 40] {
        let f = Flexure::new(1.0, 1.0, 3).unwrap().with_quadrature(q).unwrap();
        let mut k = Kinematics::new(&f);
        let mut i = 0;
        g.bench_with_input(BenchmarkId::new("pose_jacobian_hessian", q), &q, |b, _| {
            b.iter(|| {
                i = (i + 3) % alphas.len();
                update(&f, black_box(&alphas[i..i + 3]), &mut k, Level::Hessian);
                k.pose_root_tip.x
            })
        });
    }
    g.finish();
}
