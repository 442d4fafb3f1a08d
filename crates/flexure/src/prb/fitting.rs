//! Fitting the chain to the Smooth Curvature Model's deflections.

use super::chain::{rest_pose_at, tip_pose};
use super::model::{FitError, PrbFit, PrbJoint, PrbKind};
use super::simplex;
use super::statics::{equilibrium, equilibrium_near};
use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::kinematics::{Pose, pose_root_tip};
use crate::space::MAX_LOAD;
use crate::statics::{Settings, StaticsData, TipLoad, deflect};
use nalgebra::{DMatrix, DVector, Point2};

/// A fit is [`PrbFit::flagged`] when its position error exceeds this fraction of $L$.
pub const FLAG_FRACTION: f64 = 0.01;

/// Howell's characteristic radius factor for a vertical end force ($n = 0$),
/// the 1R fit's $\gamma$ when the loads do not deflect the flexure.
pub const HOWELL_GAMMA: f64 = 0.8517;
/// Howell's stiffness coefficient for $n = 0$, the 1R spring when the loads
/// do not deflect the flexure.
pub const HOWELL_K_THETA: f64 = 2.676;

/// Su's 3R length fractions $\gamma_0, \dots, \gamma_3$ (Su 2009, Eq. 24), where the 3R length search starts.
pub const SU_GAMMA: [f64; 4] = [0.1, 0.35, 0.40, 0.15];
/// Su's 3R stiffness coefficients $K_{\Theta 1}, K_{\Theta 2}, K_{\Theta 3}$ (Su 2009, Table 1, averaged over load directions),
/// the 3R springs when the loads do not deflect the flexure.
pub const SU_K_THETA: [f64; 3] = [3.51, 2.99, 2.58];

/// Grid points of the 1R search for $\gamma$ before golden-section refinement.
const GRID: usize = 40;
/// Golden-section iterations refining $\gamma$.
const GOLDEN_ITERATIONS: usize = 60;
/// The shortest 3R link the length search accepts (fraction of $L$).
const MIN_LINK: f64 = 0.02;
/// The length search's first simplex: Su's lengths and steps of this size.
const SIMPLEX_STEP: f64 = 0.03;
/// The length search's iteration cap.
const SIMPLEX_ITERATIONS: usize = 120;
/// The length search stops when its vertices' errors agree to this fraction of $L$.
const LENGTH_TOLERANCE: f64 = 1e-7;
/// Points at which a fitted spring's tangent stiffness is checked.
const SPRING_CHECKS: usize = 64;
/// The range searched for the 1R $\gamma$.
const GAMMA_RANGE: (f64, f64) = (0.05, 1.0);

/// Fits a pseudo-rigid-body chain of `kind` to the flexure `f` under the
/// tip wrenches `loads` (each in the root frame, at the tip, as a
/// [`TipLoad`]).
///
/// The Smooth Curvature Model's equilibrium under each load is solved from
/// rest ([`deflect`], default settings, at `f`'s order), giving the tip
/// poses $g_k = (\phi_k, r_k)$. Then:
///
/// - **1R**: the pivot $p(\gamma)$ on the rest curve at $(1-\gamma)L$ is the
///   centre of the circle through the rest tip $r_0$ that the PRB tip
///   follows; $\gamma$ minimizes the largest distance of the model's tips
///   from that circle,
///   $$\max_k\bigl\lvert\lvert r_k - p\rvert - \lvert r_0 - p\rvert\bigr\rvert$$
///   (a 40-point grid on $[0.05, 1]$, then 60 golden-section steps). Each
///   sample's PRB angle $\Theta_k$ is the direction of $r_k - p$, and
///   the spring torque that holds the PRB tip $r^{\prime}_k$ there,
///   $\tau_k = M + (r^{\prime}_k - p)\times F$, is fitted by least squares
///   with $\tau = k_1\Theta + k_2\Theta^2 + k_3\Theta^3$ (as many terms as
///   there are deflected samples, up to three).
/// - **3R**: for lengths $\gamma_i$, each sample's joint angles put the
///   chain's tip exactly on $g_k$ (the two-link inverse kinematics between
///   the first and last pivots, on the branch that turns least), and each
///   joint's torque $\tau_{ik} = M + (r_k - q_i)\times F$ is fitted by least
///   squares with its own cubic ([`fit_three_r`]). The lengths are then
///   searched from Su's ([`SU_GAMMA`]) by Nelder–Mead (at most 120 steps,
///   links at least 2 % of $L$) for the smallest largest position error at
///   the chain's equilibria; Su's lengths are kept if nothing beats them.
///
/// The reported [`PrbFit::error`] is that of the fitted chain at its own
/// equilibrium under each load against $g_k$, the loads taken in their
/// order, each from the last one's angles ([`equilibrium_near`]; from rest,
/// [`equilibrium`], where that does not converge): the largest tip distance
/// (m) and the largest tip-angle difference (rad), which for 1R keeps
/// Howell's parametric angle mismatch ($\phi - \phi_0 \approx c_\theta\Theta$,
/// $c_\theta \approx 1.24$).
///
/// Errors: [`Error::InvalidParameter`] naming `loads` when there are none
/// or one is not finite or too large, or when the model cannot reach a
/// load stably from rest (the path passes a buckling or limit load); the
/// model's solver errors; an [`equilibrium`] the fitted chain cannot reach.
///
/// # Example
/// ```
/// use flexure::prb::{self, PrbKind};
/// use flexure::{Flexure, TipLoad};
/// let f = Flexure::new(0.05, 2e-3, 5)?;
/// let loads: Vec<TipLoad> = (1..=5).map(|i| TipLoad { moment: 0.0, fx: 0.0, fy: 0.2 * i as f64 }).collect();
/// let fit = prb::fit(&f, &loads, PrbKind::OneR)?;
/// let (gamma, k) = (fit.gamma[1], fit.joints[0].stiffness[0]);
/// // Howell's convention: k₁ = γ K_Θ EI/L.
/// assert!((k - gamma * fit.k_theta[0] * 2e-3 / 0.05).abs() < 1e-12 * k);
/// assert_eq!(fit.samples, 5);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn fit(f: &Flexure, loads: &[TipLoad], kind: PrbKind) -> Result<PrbFit> {
    let targets = model_tips(f, loads)?;
    fit_targets(f, loads, &targets, kind)
}

/// [`fit`] to the model's shapes `alphas` under `loads` as they were
/// reached (one coordinate vector per load: a mechanism's equilibria along
/// its load range), instead of solving each load from rest. A flexure
/// loaded by a tendon is the case: the tendon's pull turns with the link
/// and holds the flexure, while the same wrench held dead from rest would
/// buckle it another way. The chain's equilibria follow the loads in their
/// order, each from the last ([`super::equilibrium_near`]).
///
/// Errors: `alphas` not one finite coordinate vector per load (`alphas`);
/// those of [`fit`].
///
/// # Example
/// ```
/// use flexure::{deflect, Flexure, StaticsData, TipLoad, prb};
/// let f = Flexure::new(1.0, 1.0, 4)?;
/// let loads: Vec<TipLoad> = (1..=6).map(|i| TipLoad { moment: 0.0, fx: 0.0, fy: 0.5 * i as f64 }).collect();
/// let mut data = StaticsData::new(&f);
/// let alphas: Vec<Vec<f64>> = loads
///     .iter()
///     .map(|l| deflect(&f, l, &mut data, &Default::default()).map(|_| data.alpha().to_vec()))
///     .collect::<Result<_, _>>()?;
/// // The same shapes as `fit` solves for itself: the same fit.
/// let along = prb::fit_along(&f, &loads, &alphas, prb::PrbKind::OneR)?;
/// assert_eq!(along, prb::fit(&f, &loads, prb::PrbKind::OneR)?);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn fit_along(f: &Flexure, loads: &[TipLoad], alphas: &[Vec<f64>], kind: PrbKind) -> Result<PrbFit> {
    check_loads(loads)?;
    if alphas.len() != loads.len() {
        return Err(Error::invalid(
            "alphas",
            format!("{} shapes for {} loads", alphas.len(), loads.len()),
            "must hold one shape per load",
        ));
    }
    let mut targets = Vec::with_capacity(alphas.len());
    for a in alphas {
        f.check_coordinates("alphas", a)?;
        targets.push(pose_root_tip(f, a));
    }
    fit_targets(f, loads, &targets, kind)
}

/// [`fit`] to the model's tip poses `targets` under `loads`.
fn fit_targets(f: &Flexure, loads: &[TipLoad], targets: &[Pose], kind: PrbKind) -> Result<PrbFit> {
    let rest = pose_root_tip(f, f.rest());
    match kind {
        PrbKind::OneR => finish(one_r(f, loads, targets, &rest), f, loads, targets),
        PrbKind::ThreeR => {
            let su = finish(three_r(f, loads, targets, &rest, &SU_GAMMA), f, loads, targets)?;
            let mut objective = |x: &[f64]| match lengths(x) {
                Some(g) => finish(three_r(f, loads, targets, &rest, &g), f, loads, targets)
                    .map_or(f64::INFINITY, |fit| fit.error.position),
                None => f64::INFINITY,
            };
            let tolerance = LENGTH_TOLERANCE * f.length();
            let (x, best) =
                simplex::minimize(&mut objective, &SU_GAMMA[..3], SIMPLEX_STEP, SIMPLEX_ITERATIONS, tolerance);
            match lengths(&x) {
                Some(g) if best < su.error.position => finish(three_r(f, loads, targets, &rest, &g), f, loads, targets),
                _ => Ok(su),
            }
        }
    }
}

/// Fits Su's 3R chain with the given link lengths $\gamma_0, \dots, \gamma_3$
/// (fractions of $L$, positive, summing to 1) to the flexure `f` under
/// `loads`: the springs alone, as [`fit`] fits them (each joint's cubic
/// from the torques of the chain posed on the model's tips), and the
/// errors at the chain's equilibria. [`fit`] with [`PrbKind::ThreeR`]
/// searches the lengths too, from Su's ([`SU_GAMMA`]).
///
/// Errors: `gamma` not positive or not summing to 1 (within 1e-9); those of [`fit`].
///
/// # Example
/// ```
/// use flexure::prb::{self, SU_GAMMA};
/// use flexure::{Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 6)?;
/// let loads: Vec<TipLoad> = (1..=8).map(|i| TipLoad { moment: 0.0, fx: 0.0, fy: 0.5 * i as f64 }).collect();
/// let fit = prb::fit_three_r(&f, &loads, SU_GAMMA)?;
/// assert_eq!(fit.gamma, SU_GAMMA.to_vec());
/// assert!(fit.error.position < 1e-3 && fit.joints.len() == 3);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn fit_three_r(f: &Flexure, loads: &[TipLoad], gamma: [f64; 4]) -> Result<PrbFit> {
    if !gamma.iter().all(|g| g.is_finite() && *g > 0.0) || (gamma.iter().sum::<f64>() - 1.0).abs() > 1e-9 {
        return Err(Error::invalid("gamma", format!("{gamma:?}"), "must be four positive fractions summing to 1"));
    }
    let targets = model_tips(f, loads)?;
    let rest = pose_root_tip(f, f.rest());
    finish(three_r(f, loads, &targets, &rest, &gamma), f, loads, &targets)
}

/// The 3R lengths $(\gamma_0, \gamma_1, \gamma_2, 1 - \sum)$ of the search
/// point `x`, if every link is at least [`MIN_LINK`] long.
fn lengths(x: &[f64]) -> Option<[f64; 4]> {
    let g = [x[0], x[1], x[2], 1.0 - x[0] - x[1] - x[2]];
    g.iter().all(|v| *v >= MIN_LINK).then_some(g)
}

/// The fit with its errors measured and flagged.
fn finish(mut fit: PrbFit, f: &Flexure, loads: &[TipLoad], targets: &[Pose]) -> Result<PrbFit> {
    fit.error = fit_error(&fit, f, loads, targets)?;
    fit.flagged = fit.error.position > FLAG_FRACTION * f.length();
    Ok(fit)
}

/// The model's tip poses under each load, followed from rest.
fn model_tips(f: &Flexure, loads: &[TipLoad]) -> Result<Vec<Pose>> {
    check_loads(loads)?;
    let mut data = StaticsData::new(f);
    let settings = Settings::default();
    loads
        .iter()
        .enumerate()
        .map(|(k, l)| {
            let eq = deflect(f, l, &mut data, &settings)?;
            if !eq.stable || eq.limit.is_some() {
                return Err(Error::invalid(
                    "loads",
                    format!("load {k} = (M {}, Fx {}, Fy {})", l.moment, l.fx, l.fy),
                    "is not reached stably from rest by the Smooth Curvature Model (its path passes a buckling or limit load)",
                ));
            }
            Ok(data.pose_root_tip())
        })
        .collect()
}

/// At least one load, each finite and at most [`MAX_LOAD`]; errors name `loads`.
fn check_loads(loads: &[TipLoad]) -> Result<()> {
    if loads.is_empty() {
        return Err(Error::invalid("loads", "[]", "must hold at least one tip load"));
    }
    for (k, l) in loads.iter().enumerate() {
        if ![l.moment, l.fx, l.fy].iter().all(|v| v.is_finite() && v.abs() <= MAX_LOAD) {
            return Err(Error::invalid(
                "loads",
                format!("load {k} = (M {}, Fx {}, Fy {})", l.moment, l.fx, l.fy),
                "must be finite and at most 1e30 in magnitude (N·m, N, N)",
            ));
        }
    }
    Ok(())
}

/// The largest error of the chain's equilibria against the model's tips:
/// each load's equilibrium nearest the last one's ([`equilibrium_near`],
/// so loads in sequence are followed as they go), or else followed from
/// rest ([`equilibrium`]).
fn fit_error(fit: &PrbFit, f: &Flexure, loads: &[TipLoad], targets: &[Pose]) -> Result<FitError> {
    let mut e = FitError::default();
    let mut last = vec![0.0; fit.joints.len()];
    for (l, t) in loads.iter().zip(targets) {
        let theta = match equilibrium_near(fit, f, l, &last) {
            Some(theta) => theta,
            None => equilibrium(fit, f, l)?,
        };
        last.clone_from(&theta);
        let g = tip_pose(fit, f, &theta);
        e.position = e.position.max((g.x - t.x).hypot(g.y - t.y));
        e.angle = e.angle.max((g.phi - t.phi).abs());
    }
    Ok(e)
}

/// The rest pivot at arc length `s`.
fn pivot_at(f: &Flexure, s: f64) -> Point2<f64> {
    rest_pose_at(f, s).origin()
}

/// The signed angle from `a` to `b` (rad, in $(-\pi, \pi]$).
fn angle_between(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1])
}

/// $(r - q)\times F$ plus $M$: the torque of the tip load about `q`.
fn torque_about(load: &TipLoad, q: &Point2<f64>, r: [f64; 2]) -> f64 {
    load.moment + (r[0] - q.x) * load.fy - (r[1] - q.y) * load.fx
}

/// Howell's 1R: $\gamma$ by the minimax radial error, then the spring.
fn one_r(f: &Flexure, loads: &[TipLoad], targets: &[Pose], rest: &Pose) -> PrbFit {
    let l = f.length();
    let deflection = targets.iter().map(|t| (t.x - rest.x).hypot(t.y - rest.y)).fold(0.0, f64::max);
    let radial = |gamma: f64| {
        let p = pivot_at(f, (1.0 - gamma) * l);
        let r0 = (rest.x - p.x).hypot(rest.y - p.y);
        targets.iter().map(|t| ((t.x - p.x).hypot(t.y - p.y) - r0).abs()).fold(0.0, f64::max)
    };
    let gamma = if deflection <= 1e-12 * l { HOWELL_GAMMA } else { minimize(radial, GAMMA_RANGE) };
    let p = pivot_at(f, (1.0 - gamma) * l);
    let arm = [rest.x - p.x, rest.y - p.y];
    let (mut angles, mut torques) = (Vec::with_capacity(loads.len()), Vec::with_capacity(loads.len()));
    for (load, t) in loads.iter().zip(targets) {
        let theta = angle_between(arm, [t.x - p.x, t.y - p.y]);
        let (s, c) = theta.sin_cos();
        let tip = [p.x + c * arm[0] - s * arm[1], p.y + s * arm[0] + c * arm[1]];
        angles.push(theta);
        torques.push(torque_about(load, &p, tip));
    }
    let ei_l = f.ei() / l;
    let stiffness = spring(&angles, &torques).unwrap_or([gamma * HOWELL_K_THETA * ei_l, 0.0, 0.0]);
    PrbFit {
        kind: PrbKind::OneR,
        joints: vec![PrbJoint { pivot: p, stiffness }],
        gamma: vec![1.0 - gamma, gamma],
        k_theta: vec![stiffness[0] / (gamma * ei_l)],
        error: FitError::default(),
        flagged: false,
        samples: loads.len(),
    }
}

/// A 3R chain of lengths `gamma`: the joint angles that put its tip on each
/// model tip, then one cubic spring per joint.
fn three_r(f: &Flexure, loads: &[TipLoad], targets: &[Pose], rest: &Pose, gamma: &[f64; 4]) -> PrbFit {
    let l = f.length();
    let p = [
        pivot_at(f, gamma[0] * l),
        pivot_at(f, (gamma[0] + gamma[1]) * l),
        pivot_at(f, (gamma[0] + gamma[1] + gamma[2]) * l),
    ];
    let mut angles: [Vec<f64>; 3] = std::array::from_fn(|_| Vec::with_capacity(loads.len()));
    let mut torques: [Vec<f64>; 3] = std::array::from_fn(|_| Vec::with_capacity(loads.len()));
    for (load, t) in loads.iter().zip(targets) {
        let theta = inverse_kinematics(&p, rest, t);
        let q = [p[0], rotate_about(&p[0], theta[0], &p[1]), last_pivot(&p[2], rest, t)];
        for i in 0..3 {
            angles[i].push(theta[i]);
            torques[i].push(torque_about(load, &q[i], [t.x, t.y]));
        }
    }
    let ei_l = f.ei() / l;
    let joints: Vec<PrbJoint> = (0..3)
        .map(|i| PrbJoint {
            pivot: p[i],
            stiffness: spring(&angles[i], &torques[i]).unwrap_or([SU_K_THETA[i] * ei_l, 0.0, 0.0]),
        })
        .collect();
    let k_theta = joints.iter().map(|j| j.stiffness[0] / ei_l).collect();
    PrbFit {
        kind: PrbKind::ThreeR,
        joints,
        gamma: gamma.to_vec(),
        k_theta,
        error: FitError::default(),
        flagged: false,
        samples: loads.len(),
    }
}

/// The point `x` turned by `theta` about `p`.
fn rotate_about(p: &Point2<f64>, theta: f64, x: &Point2<f64>) -> Point2<f64> {
    let (s, c) = theta.sin_cos();
    let (dx, dy) = (x.x - p.x, x.y - p.y);
    Point2::new(p.x + c * dx - s * dy, p.y + s * dx + c * dy)
}

/// Where the last pivot goes when the last link carries the tip from
/// `rest` to `tip`: $g\thinspace g_0^{-1}p_3$.
fn last_pivot(p3: &Point2<f64>, rest: &Pose, tip: &Pose) -> Point2<f64> {
    tip.compose(&rest.inverse()).act(p3)
}

/// The 3R joint angles whose tip pose is `tip`: the last pivot follows the
/// tip rigidly, the first is fixed, and the middle one closes the two-link
/// triangle between them (the distance clamped to the reachable range), on
/// the branch with the smaller $\sum\theta_i^2$.
fn inverse_kinematics(p: &[Point2<f64>; 3], rest: &Pose, tip: &Pose) -> [f64; 3] {
    let q3 = last_pivot(&p[2], rest, tip);
    let a = (p[1] - p[0]).norm();
    let b = (p[2] - p[1]).norm();
    let d_vec = q3 - p[0];
    let d = d_vec.norm().clamp((a - b).abs(), a + b);
    // The angle at the first pivot between the chord q1→q3 and the first link.
    let cos_alpha = if a * d > 0.0 { ((a * a + d * d - b * b) / (2.0 * a * d)).clamp(-1.0, 1.0) } else { 1.0 };
    let alpha = cos_alpha.acos();
    let chord = d_vec.y.atan2(d_vec.x);
    let total = tip.phi - rest.phi;
    let rest_a = [p[1].x - p[0].x, p[1].y - p[0].y];
    let rest_b = [p[2].x - p[1].x, p[2].y - p[1].y];
    let mut best = [0.0; 3];
    let mut best_norm = f64::INFINITY;
    for sign in [1.0, -1.0] {
        let dir = chord + sign * alpha;
        let q2 = Point2::new(p[0].x + a * dir.cos(), p[0].y + a * dir.sin());
        let t1 = angle_between(rest_a, [q2.x - p[0].x, q2.y - p[0].y]);
        let t12 = angle_between(rest_b, [q3.x - q2.x, q3.y - q2.y]);
        // Unwrap the second link's turn near the first's.
        let t12 = t1 + wrap(t12 - t1);
        let theta = [t1, t12 - t1, total - t12];
        let norm: f64 = theta.iter().map(|t| t * t).sum();
        if norm < best_norm {
            best_norm = norm;
            best = theta;
        }
    }
    best
}

/// An angle moved into $(-\pi, \pi]$.
fn wrap(a: f64) -> f64 {
    let two_pi = 2.0 * std::f64::consts::PI;
    a - two_pi * ((a + std::f64::consts::PI) / two_pi).floor()
}

/// The largest hinge angle (rad) below which a spring is fitted by its
/// linear term alone.
const CURVED_ANGLE: f64 = 1e-6;

/// The least-squares cubic through the origin, $\tau = k_1\theta + k_2\theta^2 + k_3\theta^3$,
/// with as many terms as there are deflected samples (at most three), and
/// fewer when the fit would soften to a non-positive tangent stiffness
/// $\tau^{\prime}$ anywhere on the sampled range stretched by a quarter (a
/// spring that could not hold the chain); `None` when no sample is deflected.
/// Below [`CURVED_ANGLE`] the angles are rounding, not a curve: one term
/// (a centred axial load bends nothing, and a cubic through its noise is
/// $k_2 \sim 10^8$, a spring that softens to nothing a nanoradian away).
fn spring(angles: &[f64], torques: &[f64]) -> Option<[f64; 3]> {
    let scale = angles.iter().fold(0.0, |m: f64, t| m.max(t.abs()));
    let mut deflected = angles.iter().filter(|t| t.abs() > 1e-9 * scale.max(1e-300)).count();
    if scale <= 1e-14 || deflected == 0 {
        return None;
    }
    if scale < CURVED_ANGLE {
        deflected = 1;
    }
    let lo = 1.25 * angles.iter().fold(0.0, |m: f64, &t| m.min(t));
    let hi = 1.25 * angles.iter().fold(0.0, |m: f64, &t| m.max(t));
    let b = DVector::from_column_slice(torques);
    let mut last = None;
    for terms in (1..=deflected.min(3)).rev() {
        let a = DMatrix::from_fn(angles.len(), terms, |r, c| (angles[r] / scale).powi(c as i32 + 1));
        let Ok(x) = a.svd(true, true).solve(&b, 1e-13) else { continue };
        let mut k = [0.0; 3];
        for (c, v) in x.iter().enumerate() {
            k[c] = v / scale.powi(c as i32 + 1);
        }
        let stiff = (0..=SPRING_CHECKS).all(|i| {
            let t = lo + (hi - lo) * i as f64 / SPRING_CHECKS as f64;
            k[0] + t * (2.0 * k[1] + 3.0 * t * k[2]) > 0.0
        });
        if stiff {
            return Some(k);
        }
        last = Some(k);
    }
    last
}

/// The minimizer of `g` on `range`: the best of a grid, refined by golden
/// section between its neighbours.
fn minimize(g: impl Fn(f64) -> f64, (lo, hi): (f64, f64)) -> f64 {
    let h = (hi - lo) / (GRID - 1) as f64;
    let best = (0..GRID)
        .map(|i| (i, g(lo + i as f64 * h)))
        .fold((0, f64::INFINITY), |b, (i, v)| if v < b.1 { (i, v) } else { b });
    let (mut a, mut b) = (lo + best.0.saturating_sub(1) as f64 * h, (lo + (best.0 + 1) as f64 * h).min(hi));
    let r = (5f64.sqrt() - 1.0) / 2.0;
    let (mut c, mut d) = (b - r * (b - a), a + r * (b - a));
    let (mut gc, mut gd) = (g(c), g(d));
    for _ in 0..GOLDEN_ITERATIONS {
        if gc < gd {
            b = d;
            d = c;
            gd = gc;
            c = b - r * (b - a);
            gc = g(c);
        } else {
            a = c;
            c = d;
            gc = gd;
            d = a + r * (b - a);
            gd = g(d);
        }
    }
    (a + b) / 2.0
}
