//! The chain's static equilibrium under a tip wrench.

use super::chain::configuration;
use super::model::PrbFit;
use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::kinematics::{Pose, pose_root_tip};
use crate::statics::TipLoad;
use nalgebra::{DMatrix, DVector, Point2};

/// Newton iterations allowed per load step.
const NEWTON_ITERATIONS: usize = 50;
/// Load steps (accepted or not) allowed in one solve.
const MAX_STEPS: usize = 200;
/// The smallest load step tried before giving up.
const MIN_STEP: f64 = 1e-6;
/// The largest Newton update of one joint angle (rad).
const MAX_UPDATE: f64 = 0.25;
/// The largest turn of a joint over one accepted load step (rad).
const MAX_TURN: f64 = 0.5;
/// Convergence: the largest torque residual, relative to the torque scale.
const TOLERANCE: f64 = 1e-12;

/// The chain's potential energy under the dead tip load $\lambda w$ at angles $\theta$:
/// $$V(\theta) = \sum_i E_i(\theta_i) - \lambda\left(M\phi(\theta) + F\cdot r(\theta)\right),$$
/// with $E_i = \int_0^{\theta_i}\tau_i$ the springs' energy and $(\phi, r)$ the
/// chain's tip pose, measured from the rest pose (J).
///
/// # Panics
/// If `theta` does not have one angle per joint of `fit`.
///
/// # Example
/// ```
/// use flexure::prb::{PrbFit, PrbJoint, PrbKind, FitError, potential};
/// use flexure::{Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3)?;
/// let fit = PrbFit {
///     kind: PrbKind::OneR,
///     joints: vec![PrbJoint { pivot: nalgebra::Point2::new(0.15, 0.0), stiffness: [2.0, 0.0, 0.0] }],
///     gamma: vec![0.15, 0.85], k_theta: vec![2.0 / 0.85], error: FitError::default(), flagged: false, samples: 0,
/// };
/// // A pure moment: V = θ² − Mθ.
/// let v = potential(&fit, &f, &TipLoad { moment: 0.5, fx: 0.0, fy: 0.0 }, &[0.3]);
/// assert!((v - (0.09 - 0.15)).abs() < 1e-15);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn potential(fit: &PrbFit, f: &Flexure, load: &TipLoad, theta: &[f64]) -> f64 {
    assert_eq!(theta.len(), fit.joints.len(), "one angle per joint of the PRB chain");
    let rest = pose_root_tip(f, f.rest());
    let mut pivots = vec![Point2::origin(); theta.len()];
    let tip = configuration(fit, &rest, theta, &mut pivots);
    let springs: f64 = fit.joints.iter().zip(theta).map(|(j, &t)| j.energy(t)).sum();
    springs - (load.moment * (tip.phi - rest.phi) + load.fx * (tip.x - rest.x) + load.fy * (tip.y - rest.y))
}

/// The gradient of [`potential`]: the torque left at each pivot,
/// $$\frac{\partial V}{\partial\theta_i} = \tau_i(\theta_i) - \left(M + (r - q_i)\times F\right),$$
/// $q_i$ the pivot where the joints before it moved it and $r$ the chain's
/// tip (N·m). Zero at an [`equilibrium`].
///
/// # Panics
/// If `theta` does not have one angle per joint of `fit`.
///
/// # Example
/// ```
/// use flexure::prb::{PrbFit, PrbJoint, PrbKind, FitError, gradient};
/// use flexure::{Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3)?;
/// let fit = PrbFit {
///     kind: PrbKind::OneR,
///     joints: vec![PrbJoint { pivot: nalgebra::Point2::new(0.15, 0.0), stiffness: [2.0, 0.0, 0.0] }],
///     gamma: vec![0.15, 0.85], k_theta: vec![2.0 / 0.85], error: FitError::default(), flagged: false, samples: 0,
/// };
/// // At rest a vertical force F turns the link with the torque 0.85 L F.
/// let g = gradient(&fit, &f, &TipLoad { moment: 0.0, fx: 0.0, fy: 1.0 }, &[0.0]);
/// assert!((g[0] + 0.85).abs() < 1e-15);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn gradient(fit: &PrbFit, f: &Flexure, load: &TipLoad, theta: &[f64]) -> Vec<f64> {
    assert_eq!(theta.len(), fit.joints.len(), "one angle per joint of the PRB chain");
    let rest = pose_root_tip(f, f.rest());
    let mut pivots = vec![Point2::origin(); theta.len()];
    let mut g = vec![0.0; theta.len()];
    residual(fit, &rest, load, 1.0, theta, &mut pivots, &mut g, None);
    g
}

/// The gradient of $V$ under $\lambda w$ into `g`, and with `hessian` its
/// Hessian $H_{ij} = \tau_i^{\prime}\delta_{ij} + \lambda(r - q_{\max(i,j)})\cdot F$.
#[allow(clippy::too_many_arguments)]
fn residual(
    fit: &PrbFit,
    rest: &Pose,
    load: &TipLoad,
    lambda: f64,
    theta: &[f64],
    pivots: &mut [Point2<f64>],
    g: &mut [f64],
    hessian: Option<&mut DMatrix<f64>>,
) {
    let tip = configuration(fit, rest, theta, pivots);
    let (m, fx, fy) = (lambda * load.moment, lambda * load.fx, lambda * load.fy);
    for ((gi, (j, &t)), q) in g.iter_mut().zip(fit.joints.iter().zip(theta)).zip(pivots.iter()) {
        let (dx, dy) = (tip.x - q.x, tip.y - q.y);
        *gi = j.torque(t) - (m + dx * fy - dy * fx);
    }
    if let Some(h) = hessian {
        let n = theta.len();
        for i in 0..n {
            for k in 0..n {
                let q = pivots[i.max(k)];
                h[(i, k)] = (tip.x - q.x) * fx + (tip.y - q.y) * fy;
            }
            h[(i, i)] += fit.joints[i].tangent_stiffness(theta[i]);
        }
    }
}

/// The PRB chain's static equilibrium angles $\theta$ under the dead tip
/// wrench `load` (root frame): torque balance at every pivot,
/// $$\tau_i(\theta_i) = M + (r(\theta) - q_i(\theta))\times F,$$
/// the stationary point of [`potential`], followed from rest ($\theta = 0$)
/// by load steps (at most 200, no joint turning more than 0.5 rad in one),
/// each corrected by Newton's method (at most 50 iterations, updates of at
/// most 0.25 rad) to a torque residual of $10^{-12}$ of
/// $\max_i k_{1,i} + |M| + L(|F_x| + |F_y|)$. Only stable states (a
/// positive definite Hessian of $V$) are accepted.
///
/// Errors: the load's component, if not finite; [`Error::Unstable`] where
/// the path loses stability (a spring too soft for the load);
/// [`Error::ContinuationStalled`] with the load fraction reached.
///
/// # Example
/// ```
/// use flexure::prb::{PrbFit, PrbJoint, PrbKind, FitError, equilibrium};
/// use flexure::{Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3)?;
/// let fit = PrbFit {
///     kind: PrbKind::OneR,
///     joints: vec![PrbJoint { pivot: nalgebra::Point2::new(0.15, 0.0), stiffness: [2.0, 0.0, 0.0] }],
///     gamma: vec![0.15, 0.85], k_theta: vec![2.0 / 0.85], error: FitError::default(), flagged: false, samples: 0,
/// };
/// // A pure moment turns a linear spring by M/k.
/// let theta = equilibrium(&fit, &f, &TipLoad { moment: 1.0, fx: 0.0, fy: 0.0 })?;
/// assert!((theta[0] - 0.5).abs() < 1e-12);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn equilibrium(fit: &PrbFit, f: &Flexure, load: &TipLoad) -> Result<Vec<f64>> {
    load.validate()?;
    let n = fit.joints.len();
    if n == 0 {
        return Err(Error::invalid("fit", "no joints", "must have at least one joint"));
    }
    for j in &fit.joints {
        if !j.stiffness.iter().chain([&j.pivot.x, &j.pivot.y]).all(|v| v.is_finite()) {
            return Err(Error::invalid("fit", format!("{:?}", j.stiffness), "must have finite pivots and stiffness"));
        }
    }
    let rest = pose_root_tip(f, f.rest());
    let k_max = fit.joints.iter().map(|j| j.stiffness[0].abs()).fold(0.0, f64::max);
    let scale = k_max + load.moment.abs() + f.length() * (load.fx.abs() + load.fy.abs());
    let mut work = Work::new(n);
    let mut theta = vec![0.0; n];
    let (mut lambda, mut step) = (0.0_f64, 1.0_f64);
    let mut residual_reached = 0.0;
    let mut cause = String::from("no step tried");
    for steps in 0..MAX_STEPS {
        if lambda >= 1.0 {
            return Ok(theta);
        }
        let target = (lambda + step).min(1.0);
        let mut trial = theta.clone();
        match newton(fit, &rest, load, target, &mut trial, scale, &mut work) {
            Ok(()) => {
                let turn = trial.iter().zip(&theta).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
                let stable = work.hessian.clone().cholesky().is_some();
                if stable && turn <= MAX_TURN {
                    theta = trial;
                    lambda = target;
                    step = (step * 2.0).min(1.0);
                    continue;
                }
                if !stable && step <= 1e-3 {
                    return Err(Error::Unstable { what: "prb equilibrium", load_fraction: lambda });
                }
                cause = if stable { "a joint turned too far".into() } else { "an unstable state".into() };
            }
            Err(r) => {
                residual_reached = r;
                cause = "Newton did not converge".into();
            }
        }
        step /= 2.0;
        if step < MIN_STEP {
            return Err(Error::ContinuationStalled {
                cause,
                rounding: false,
                solver: "prb equilibrium",
                load_fraction: lambda,
                steps,
                residual: residual_reached,
                unit: "N·m",
            });
        }
    }
    if lambda >= 1.0 {
        return Ok(theta);
    }
    Err(Error::ContinuationStalled {
        cause: format!("{MAX_STEPS} load steps ({cause})"),
        rounding: false,
        solver: "prb equilibrium",
        load_fraction: lambda,
        steps: MAX_STEPS,
        residual: residual_reached,
        unit: "N·m",
    })
}

/// Buffers of one solve.
/// The equilibrium under the full `load` nearest to `start`, by Newton's
/// method alone (bounded as in [`equilibrium`]); `None` if it does not
/// converge there. With `start` the chain's angles under the last of a
/// sequence of loads, this follows the loads' own path. It is a stationary
/// point, stable or not under the wrench held dead: a wrench that turns with
/// the links (a tendon's pull) holds states its dead copy would not, and
/// whether the mechanism holds them is the mechanism's question.
pub fn equilibrium_near(fit: &PrbFit, f: &Flexure, load: &TipLoad, start: &[f64]) -> Option<Vec<f64>> {
    let n = fit.joints.len();
    if n == 0 || start.len() != n || load.validate().is_err() {
        return None;
    }
    let rest = pose_root_tip(f, f.rest());
    let k_max = fit.joints.iter().map(|j| j.stiffness[0].abs()).fold(0.0, f64::max);
    let scale = k_max + load.moment.abs() + f.length() * (load.fx.abs() + load.fy.abs());
    let mut work = Work::new(n);
    let mut theta = start.to_vec();
    newton(fit, &rest, load, 1.0, &mut theta, scale, &mut work).ok()?;
    Some(theta)
}

struct Work {
    pivots: Vec<Point2<f64>>,
    g: Vec<f64>,
    hessian: DMatrix<f64>,
}

impl Work {
    fn new(n: usize) -> Self {
        Self { pivots: vec![Point2::origin(); n], g: vec![0.0; n], hessian: DMatrix::zeros(n, n) }
    }
}

/// Newton's method on $\nabla V = 0$ under $\lambda w$ from `theta`; on
/// failure, the last residual (N·m). Leaves the Hessian at the solution in `work`.
fn newton(
    fit: &PrbFit,
    rest: &Pose,
    load: &TipLoad,
    lambda: f64,
    theta: &mut [f64],
    scale: f64,
    work: &mut Work,
) -> std::result::Result<(), f64> {
    let mut last = f64::INFINITY;
    for _ in 0..NEWTON_ITERATIONS {
        residual(fit, rest, load, lambda, theta, &mut work.pivots, &mut work.g, Some(&mut work.hessian));
        last = work.g.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        if !last.is_finite() {
            return Err(last);
        }
        if last <= TOLERANCE * scale {
            return Ok(());
        }
        let rhs = DVector::from_iterator(theta.len(), work.g.iter().map(|v| -v));
        let Some(delta) = work.hessian.clone().lu().solve(&rhs) else {
            return Err(last);
        };
        let biggest = delta.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        let shrink = if biggest > MAX_UPDATE { MAX_UPDATE / biggest } else { 1.0 };
        for (t, d) in theta.iter_mut().zip(delta.iter()) {
            *t += shrink * d;
        }
    }
    Err(last)
}
