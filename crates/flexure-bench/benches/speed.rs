//! Speed against the floor: five sin/cos pairs, the cost of one evaluation's
//! trigonometry; and against exact beam theory solving the same task.
//!
//! `cargo bench -p flexure-bench --bench speed`; ratios are in BENCHMARKS.md.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use flexure::connect::connect;
use flexure::kinematics::{Kinematics, Level, par_poses_root_tip, pose_root_tip, update};
use flexure::mechanism::file::from_toml;
use flexure::mechanism::statics::{Settings as MechanismSettings, solve};
use flexure::reference::elastica;
use flexure::{Flexure, Pose, Settings, Statics, TipLoad, deflect};
use std::f64::consts::FRAC_PI_2;
use std::hint::black_box;

/// Seeded inputs, cycled so each call sees different arguments.
fn inputs(count: usize, width: usize) -> Vec<f64> {
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    (0..count * width)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

fn joint(c: &mut Criterion) {
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

fn mechanism(c: &mut Criterion) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/finger.toml");
    let m = from_toml(&std::fs::read_to_string(path).unwrap()).unwrap();
    let mut g = c.benchmark_group("mechanism");
    g.bench_function("finger_equilibrium", |b| b.iter(|| solve(black_box(&m), &MechanismSettings::default()).unwrap()));
    g.finish();
}

fn statics(c: &mut Criterion) {
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

fn batch(c: &mut Criterion) {
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

criterion_group!(benches, joint, statics, batch, mechanism);
criterion_main!(benches);
