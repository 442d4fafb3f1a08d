//! The tendon-driven joint (Sec. III-D, Eqs. 23–26, errata sign), against the
//! exact elastica loaded by the tendon's own force.

use flexure::reference::elastica;
use flexure::tendon::{TendonData, TendonOffsets, TendonPotential, pull, stability_limit, tendon_length};
use flexure::{Flexure, Kinematics, StabilityLimit, TipLoad, bending_stiffness};
use num_dual::Dual64;
use std::f64::consts::FRAC_PI_2;

fn steel() -> Flexure {
    Flexure::new(0.015, bending_stiffness(200e9, 0.01, 0.0002, Some(0.29)).unwrap(), 3).unwrap()
}
const PAPER: TendonOffsets = TendonOffsets { root_offset: 0.005, tip_offset: 0.005 };

fn angle_at(f: &Flexure, t: &TendonOffsets, force: f64) -> f64 {
    let mut d = TendonData::new(f);
    pull(f, t, force, &mut d).unwrap();
    d.alpha()[0]
}

/// Fig. 10: "approximately 28 N" turns the paper's steel flexure to 90°
/// (read off the figure: 28 ± 0.5 N).
#[test]
fn fig_10_right_angle_near_28_newtons() {
    let f = steel();
    let (mut lo, mut hi) = (20.0, 40.0);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if angle_at(&f, &PAPER, mid) < FRAC_PI_2 { lo = mid } else { hi = mid }
    }
    assert!((lo - 28.0).abs() < 0.5, "{lo} N");
}

/// Errata, Eq. 24: tension shortens the tendon, so the joint bends toward it.
#[test]
fn bends_toward_the_tendon() {
    let f = steel();
    assert!(angle_at(&f, &PAPER, 10.0) > 0.3);
    assert!(angle_at(&f, &TendonOffsets { root_offset: -0.005, tip_offset: -0.005 }, 10.0) < -0.3);
    let mut d = TendonData::new(&f);
    assert!(pull(&f, &PAPER, -1.0, &mut d).is_err(), "negative tension");
}

/// Gradient and Hessian of E(α) three ways: central differences (h = 1e-6,
/// error ~1e-9 relative), num-dual through the energy, symmetry.
#[test]
fn derivatives() {
    let f = steel();
    let tension = 12.0;
    let alpha = [0.7, -0.3, 0.2];
    let mut k = Kinematics::new(&f);
    let (mut g, mut h) = ([0.0; 3], [0.0; 9]);
    TendonPotential { flexure: &f, tendon: PAPER, tension, kinematics: &mut k }.evaluate(&alpha, &mut g, &mut h);
    let e = |a: &[f64]| flexure::energy(&f, a) + tension * tendon_length(&f, &PAPER, a);
    let step = 1e-6;
    for i in 0..3 {
        let (mut up, mut dn) = (alpha, alpha);
        up[i] += step;
        dn[i] -= step;
        let fd = (e(&up) - e(&dn)) / (2.0 * step);
        assert!((g[i] - fd).abs() < 1e-7 * g[i].abs().max(1e-2), "gradient {i}");
        let d: Vec<Dual64> = (0..3).map(|m| Dual64::new(alpha[m], (m == i) as u8 as f64)).collect();
        let ed = flexure::energy(&f, &d) + Dual64::from(tension) * tendon_length(&f, &PAPER, &d);
        assert!((g[i] - ed.eps).abs() < 1e-12, "gradient {i} vs num-dual");
        let mut kd = Kinematics::<Dual64>::new(&f);
        let (mut gd, mut hd) = ([Dual64::from(0.0); 3], [Dual64::from(0.0); 9]);
        TendonPotential { flexure: &f, tendon: PAPER, tension: Dual64::from(tension), kinematics: &mut kd }
            .evaluate(&d, &mut gd, &mut hd);
        for j in 0..3 {
            assert!((h[i * 3 + j] - gd[j].eps).abs() < 1e-10, "Hessian ({j},{i}) vs num-dual of the gradient");
            assert!((h[i * 3 + j] - h[j * 3 + i]).abs() < 1e-12, "symmetry");
        }
    }
}

/// The exact tendon joint, composed by hand: the tendon pulls the tip
/// attachment toward the root one with force f, so the elastica carries the
/// tip load F = −f·u, M = r × F with r the attachment offset, both set by
/// the exact pose itself; the model stays within 1 % of L and 1° of it up
/// to 90° (Sec. III-C's accuracy).
#[test]
fn agrees_with_the_exact_elastica() {
    let f = steel();
    let mut d = TendonData::new(&f);
    for force in [5.0, 15.0, 27.0] {
        pull(&f, &PAPER, force, &mut d).unwrap();
        let model = d.kinematics.pose_root_tip;
        let load_at = |phi: f64, x: f64, y: f64| {
            let [dx, dy] = PAPER.span(phi, x, y);
            let l = dx.hypot(dy);
            let (fx, fy) = (-force * dx / l, -force * dy / l);
            let (rx, ry) = (-PAPER.tip_offset * phi.sin(), PAPER.tip_offset * phi.cos());
            TipLoad { moment: rx * fy - ry * fx, fx, fy }
        };
        // Unknowns z = (M₀, φ, x, y): shooting from the root with moment M₀
        // under the tendon's load at pose p must end at p with tip moment M(p).
        // Solved locally from the model's state (beyond the Euler load a dead
        // load applied from rest can reach another equilibrium), by Newton
        // with central-difference Jacobian (h = 1e-8).
        let residual = |z: &nalgebra::Vector4<f64>| {
            let load = load_at(z[1], z[2], z[3]);
            let tip = elastica::shoot(&f, z[0], load.fx, load.fy, &Default::default(), |_, _| {}).unwrap();
            let tip_moment = z[0] - load.fy * tip[1] + load.fx * tip[2];
            nalgebra::Vector4::new(
                tip[0] - z[1],
                (tip[1] - z[2]) / 0.015,
                (tip[2] - z[3]) / 0.015,
                (tip_moment - load.moment) / 0.1,
            )
        };
        let start = load_at(model.phi, model.x, model.y);
        let mut z =
            nalgebra::Vector4::new(start.moment + model.x * start.fy - model.y * start.fx, model.phi, model.x, model.y);
        for _ in 0..30 {
            let r = residual(&z);
            if r.amax() < 1e-12 {
                break;
            }
            let h = 1e-8;
            let jac = nalgebra::Matrix4::from_fn(|row, col| {
                let mut d = nalgebra::Vector4::zeros();
                d[col] = h * if col == 0 {
                    0.1
                } else if col == 1 {
                    1.0
                } else {
                    0.015
                };
                (residual(&(z + d))[row] - residual(&(z - d))[row]) / (2.0 * d[col])
            });
            z -= jac.lu().solve(&r).unwrap();
        }
        assert!(residual(&z).amax() < 1e-10, "{force} N: exact tendon equilibrium found");
        let p = [z[1], z[2], z[3]];
        let pose = flexure::Pose { phi: p[0], x: p[1], y: p[2] };
        assert!((model.x - pose.x).hypot(model.y - pose.y) < 0.01 * 0.015, "{force} N position");
        assert!((model.phi - pose.phi).abs().to_degrees() < 1.0, "{force} N angle");
    }
}

/// The tendon's stability limit against its definition, checked by `pull`
/// alone: a bound that the path holds to, stable at 0.999 of it. A tendon
/// on one side, or crossing the flexure, pulls its tip attachment onto its
/// root attachment (the tendon 0.06 % of L long at 0.999 of the bound, under
/// 0.1 %), where $f\lvert\Delta x\rvert$ has a kink and the continuation
/// stops, which is reported as a bound, not as a loss. (The crossing one
/// used to be reported lost at 99.94 % of 22.9: a corrector had jumped from
/// $\lambda = 0.9994$ to $-1.2$ on a step of 0.0024, issue 39.)
#[test]
fn stability_limit_meets_its_definition() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    for tendon in
        [TendonOffsets { root_offset: 0.1, tip_offset: -0.05 }, TendonOffsets { root_offset: 0.1, tip_offset: 0.05 }]
    {
        let l = stability_limit(&f, &tendon, 1.0, 1000.0).unwrap();
        let StabilityLimit::StableUpTo { factor, stalled: Some(_) } = l else { panic!("{tendon:?}: {l:?}") };
        assert!(factor > 1.0 && factor < 1000.0, "{tendon:?}: {factor}");
        let mut data = TendonData::new(&f);
        let eq = pull(&f, &tendon, 0.999 * factor, &mut data).unwrap();
        assert!(eq.stable && eq.limit.is_none(), "{tendon:?}: {eq:?}");
        let length = flexure::tendon::tendon_length(&f, &tendon, data.alpha());
        assert!(length < 1e-3, "{tendon:?}: the tendon is {length} long at 0.999 of {factor}");
    }
}
