//! The constant-curvature chain (Basis::Segments) against closed forms.

use flexure::reference::euler;
use flexure::{Flexure, TipConstraint, buckling_load, compliance_tip_rest, pose_root_tip};

/// Two segments of 0.4 and 0.8 rad over L = 2: two arcs joined tangentially.
#[test]
fn two_arcs() {
    let f = Flexure::segments(2.0, 1.0, 2).unwrap();
    let p = pose_root_tip(&f, &[0.4, 0.8]);
    // Arc 1: radius 1/0.4, arc 2 starts at angle 0.4 with radius 1/0.8.
    let (x1, y1) = (0.4f64.sin() / 0.4, (1.0 - 0.4f64.cos()) / 0.4);
    let x = x1 + (1.2f64.sin() - 0.4f64.sin()) / 0.8;
    let y = y1 + (0.4f64.cos() - 1.2f64.cos()) / 0.8;
    assert!((p.x - x).abs() < 1e-12 && (p.y - y).abs() < 1e-12 && (p.phi - 1.2).abs() < 1e-15);
}

/// A straight chain under a small tip force: each segment takes the mean
/// moment over it, so C_yy = (1/EI)·h·Σ(L − s_mid)², the midpoint rule of
/// ∫(L − s)² ds, which is L³/3 − L h²/12 in closed form.
#[test]
fn straight_chain_compliance() {
    let (l, ei, k) = (1.5_f64, 2.0, 10);
    let h = l / k as f64;
    let c = compliance_tip_rest(&Flexure::segments(l, ei, k).unwrap());
    assert!((c[(2, 2)] - (l.powi(3) / 3.0 - l * h * h / 12.0) / ei).abs() < 1e-12);
    assert!((c[(0, 0)] - l / ei).abs() < 1e-12, "rotation under a moment is exact");
}

/// Chains buckle above Euler's load, converging as O(1/K²).
#[test]
fn chain_buckling_converges_quadratically() {
    let exact = euler::buckling_load(TipConstraint::Free, 1.0, 1.0);
    let err = |k| {
        buckling_load(&Flexure::segments(1.0, 1.0, k).unwrap(), TipConstraint::Free).unwrap().critical_load / exact
            - 1.0
    };
    let (e10, e20) = (err(10), err(20));
    assert!(e10 > 0.0 && e20 > 0.0);
    assert!((e10 / e20 / 4.0 - 1.0).abs() < 0.05, "{}", e10 / e20);
}
