//! The chain's geometry: pivots on the rest curve and the tip pose
//! (product of exponentials).

use super::model::PrbFit;
use crate::flexure::Flexure;
use crate::kinematics::{Pose, pose_root_tip};
use crate::quadrature::GaussLegendre;
use nalgebra::Point2;

/// Gauss–Legendre panels per unit of the flexure's length fraction in [`rest_pose_at`].
const PANELS: usize = 16;

/// The cross-section's pose at arc length $s$ of the flexure's *rest*
/// shape, in the root frame:
/// $$\phi(s) = \sum_i\kappa_i\psi_i(s/L),\quad x(s) = \int_0^s\cos\phi,\quad y(s) = \int_0^s\sin\phi,$$
/// integrated by 16 panels of a 5-point Gauss rule (exact to rounding
/// for the rest curve of a low-order flexure). `s` is clamped to $[0, L]$.
///
/// # Example
/// ```
/// use flexure::{Flexure, prb::rest_pose_at};
/// // A rest arc of angle 1 rad on L = 2: at mid-length, φ = 1/2 and x = 2 sin(1/2).
/// let f = Flexure::new(2.0, 1.0, 3)?.with_rest(&[1.0, 0.0, 0.0])?;
/// let p = rest_pose_at(&f, 1.0);
/// assert!((p.phi - 0.5).abs() < 1e-15 && (p.x - 2.0 * 0.5f64.sin()).abs() < 1e-14);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn rest_pose_at(f: &Flexure, s: f64) -> Pose {
    let t_end = (s / f.length()).clamp(0.0, 1.0);
    let mut psi = vec![0.0; f.order()];
    let mut angle = |t: f64| {
        f.angle_shapes(t, &mut psi);
        psi.iter().zip(f.rest()).map(|(p, k)| p * k).sum::<f64>()
    };
    let rule = GaussLegendre::new(5).expect("five points");
    let h = t_end / PANELS as f64;
    let (mut x, mut y) = (0.0, 0.0);
    if h > 0.0 {
        for panel in 0..PANELS {
            let t0 = panel as f64 * h;
            for (&t, &w) in rule.nodes().iter().zip(rule.weights()) {
                let (sn, c) = angle(t0 + t * h).sin_cos();
                x += w * h * f.length() * c;
                y += w * h * f.length() * sn;
            }
        }
    }
    Pose { phi: angle(t_end), x, y }
}

/// The rotation by `theta` about the point `p`: the pose
/// $(\theta, p - R(\theta)p)$.
pub(crate) fn rotation_about(p: &Point2<f64>, theta: f64) -> Pose {
    let (s, c) = theta.sin_cos();
    Pose { phi: theta, x: p.x - (c * p.x - s * p.y), y: p.y - (s * p.x + c * p.y) }
}

/// The chain's current pivots $q_i(\theta)$ (each rest pivot moved by the
/// joints before it) and its tip pose, written into `pivots`.
pub(crate) fn configuration(fit: &PrbFit, rest_tip: &Pose, theta: &[f64], pivots: &mut [Point2<f64>]) -> Pose {
    let mut g = Pose::default();
    for ((joint, &t), q) in fit.joints.iter().zip(theta).zip(pivots.iter_mut()) {
        *q = g.act(&joint.pivot);
        g = g.compose(&rotation_about(&joint.pivot, t));
    }
    g.compose(rest_tip)
}

/// The PRB chain's tip pose in the root frame at joint angles `theta`:
/// the product of exponentials
/// $$g(\theta) = R(p_1, \theta_1)\cdots R(p_n, \theta_n)\thinspace g_0,$$
/// $R(p, \theta)$ the rotation by $\theta$ about the rest pivot $p$ and
/// $g_0$ the flexure's rest tip pose, so $\theta = 0$ gives $g_0$ and the
/// tip angle is $\phi_0 + \sum_i\theta_i$.
///
/// # Panics
/// If `theta` does not have one angle per joint of `fit`.
///
/// # Example
/// ```
/// use flexure::prb::{PrbFit, PrbJoint, PrbKind, FitError, tip_pose};
/// use flexure::Flexure;
/// let f = Flexure::new(1.0, 1.0, 3)?;
/// // Howell's 1R with γ = 0.85: the pivot 0.15 L from the root.
/// let fit = PrbFit {
///     kind: PrbKind::OneR,
///     joints: vec![PrbJoint { pivot: nalgebra::Point2::new(0.15, 0.0), stiffness: [2.2, 0.0, 0.0] }],
///     gamma: vec![0.15, 0.85], k_theta: vec![2.6], error: FitError::default(), flagged: false, samples: 0,
/// };
/// let g = tip_pose(&fit, &f, &[std::f64::consts::FRAC_PI_2]);
/// assert!((g.x - 0.15).abs() < 1e-15 && (g.y - 0.85).abs() < 1e-15);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn tip_pose(fit: &PrbFit, f: &Flexure, theta: &[f64]) -> Pose {
    assert_eq!(theta.len(), fit.joints.len(), "one angle per joint of the PRB chain");
    let mut pivots = vec![Point2::origin(); theta.len()];
    configuration(fit, &pose_root_tip(f, f.rest()), theta, &mut pivots)
}
