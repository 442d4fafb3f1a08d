//! The exact large-deflection elastica (paper Eq. 3), solved by shooting.

use crate::error::{Error, Result};
use crate::joint::Flexure;
use crate::kinematics::Pose;
use crate::newton::find_root;
use crate::ode::{Tolerance, integrate};
use crate::scalar::Scalar;
use crate::statics::TipLoad;
use nalgebra::{SMatrix, SVector};
use num_dual::Dual64;

/// Shooting settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Integrator tolerance.
    pub ode: Tolerance,
    /// Relative tolerance on the tip-moment mismatch, scaled by $EI/L + |M| + L|F|$.
    pub tolerance: f64,
    /// Newton iterations per load step.
    pub max_iterations: usize,
    /// Smallest load-continuation step before giving up.
    pub min_load_step: f64,
    /// Largest tip rotation (rad) one load step may cause. Bounding it keeps
    /// Newton on the branch that grows from the rest shape, as a quasi-static
    /// loading would, instead of jumping to a distant root.
    pub max_rotation_per_step: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            ode: Tolerance::default(),
            tolerance: 1e-11,
            max_iterations: 30,
            min_load_step: 1e-4,
            max_rotation_per_step: 0.5,
        }
    }
}

/// An exact solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solution {
    /// Tip pose in the root frame.
    pub pose: Pose<f64>,
    /// Bending moment at the root, $M_0 = EI(\omega(0) - \omega_0(0))$ (N·m).
    pub root_moment: f64,
    /// Load-continuation steps taken.
    pub load_steps: usize,
    /// Whether the shape is a minimum of the potential energy under the
    /// (dead) tip load: see [`is_stable`].
    pub stable: bool,
}

/// Integrates Eq. 3 from the clamped root, $\phi(0) = x(0) = y(0) = 0$, with
/// $\phi' = \omega_0(s) + (M_0 - F_y x + F_x y)/EI$: the internal moment of a
/// beam carrying tip force $(F_x, F_y)$ and root moment $M_0$.
/// Returns $(\phi, x, y)$ at $s = L$; `observe` sees every accepted step.
pub fn shoot<T: Scalar>(
    flexure: &Flexure,
    root_moment: T,
    fx: T,
    fy: T,
    tol: &Tolerance,
    observe: impl FnMut(f64, &[T; 3]),
) -> Result<[T; 3]> {
    let (l, ei, kappa) = (flexure.length(), T::c(flexure.ei()), flexure.rest());
    let rhs = |s: f64, y: &[T; 3]| {
        let (sn, cs) = y[0].sin_cos();
        [T::c(flexure.curvature(kappa, s)) + (root_moment - fy * y[1] + fx * y[2]) / ei, cs, sn]
    };
    integrate(rhs, 0.0, l, [T::zero(); 3], tol, observe)
}

/// The exact tip pose under `load`: shoots on the root moment $M_0$ until the
/// moment at the tip equals $M$, i.e. $M_0 - F_y x_L + F_x y_L = M$.
///
/// Newton's Jacobian comes from a dual number carried through the
/// integrator; the load is applied by continuation from the rest shape, so
/// the solution lies on the branch that grows from it. A step that lands on
/// an unstable shape ([`is_stable`]) is retried shorter while the path is
/// still stable; [`Solution::stable`] tells whether the final shape is.
///
/// # Example
/// ```
/// use flexure::{reference::elastica, Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // Bisshopp–Drucker: PL²/EI = 1 across the tip.
/// let s = elastica::deflect(&f, &TipLoad { moment: 0.0, fx: 0.0, fy: 1.0 }, &Default::default()).unwrap();
/// assert!((s.pose.x - 0.94357).abs() < 1e-5 && (s.pose.y - 0.30172).abs() < 1e-5);
/// ```
pub fn deflect(flexure: &Flexure, load: &TipLoad, settings: &Settings) -> Result<Solution> {
    load.validate()?;
    let l = flexure.length();
    let tolerance = settings.tolerance * (flexure.ei() / l + load.moment.abs() + l * (load.fx.abs() + load.fy.abs()));
    let rest = shoot(flexure, 0.0, 0.0, 0.0, &settings.ode, |_, _| {})?;
    let mut tip_now = rest;
    let (mut lambda, mut m0) = (0.0_f64, 0.0_f64);
    let mut history: Option<(f64, f64)> = None;
    let (mut step, mut load_steps, mut on_stable_path) = (1.0_f64, 0, true);
    loop {
        let target = (lambda + step).min(1.0);
        let guess = match history {
            Some((lp, mp)) => m0 + (m0 - mp) * (target - lambda) / (lambda - lp),
            // First order about the rest shape: the load's moment at the root.
            None => target * (load.moment + load.fy * rest[1] - load.fx * rest[2]),
        };
        let (m, fx, fy) = (target * load.moment, target * load.fx, target * load.fy);
        // The root finder's last evaluation is at the root it returns.
        let (mut tip_new, mut stable_new) = (tip_now, true);
        let residual = |x: &SVector<f64, 1>| -> Result<(SVector<f64, 1>, SMatrix<f64, 1, 1>)> {
            let shot = jacobi_shot(flexure, x[0], fx, fy, &settings.ode)?;
            (tip_new, stable_new) = (shot.tip, shot.stable());
            let r = shot.balance - m;
            Ok((SVector::from([r.re]), SMatrix::from([[r.eps]])))
        };
        let found = find_root(residual, SVector::from([guess]), tolerance, settings.max_iterations);
        let rotation = (tip_new[0] - tip_now[0]).abs();
        // From the stable rest shape, a quasi-static path stays stable: an
        // unstable root is another branch, reached by too long a step, unless
        // no shorter step finds a stable one (the path itself lost stability
        // at a bifurcation or limit point).
        let last_chance = step * 0.5 < settings.min_load_step;
        match found {
            Ok(root)
                if rotation <= settings.max_rotation_per_step && (stable_new || !on_stable_path || last_chance) =>
            {
                on_stable_path &= stable_new;
                history = Some((lambda, m0));
                lambda = target;
                m0 = root.x[0];
                tip_now = tip_new;
                load_steps += 1;
                if lambda >= 1.0 {
                    let pose = Pose { phi: tip_now[0], x: tip_now[1], y: tip_now[2] };
                    return Ok(Solution { pose, root_moment: m0, load_steps, stable: stable_new });
                }
                step = (2.0 * step).min(1.0 - lambda);
            }
            found => {
                // Newton's residual; or, when it converged on a root too far
                // away, how far (rad) that root would have turned the tip.
                let residual = match found {
                    Err(Error::NoConvergence { residual, .. }) => residual,
                    _ => rotation,
                };
                step *= 0.5;
                if step < settings.min_load_step {
                    return Err(Error::NoConvergence {
                        unit: "N·m",
                        solver: "elastica shooting (load continuation stalled: Newton failed, or the tip would turn by the residual, in rad, in one step)",
                        iterations: load_steps,
                        residual,
                    });
                }
            }
        }
    }
}

/// Whether the elastica shot from `root_moment` under the tip force
/// $(F_x, F_y)$ is stable, by the Jacobi (conjugate-point) test.
///
/// The second variation of the potential energy about the shape $\phi(s)$,
///
/// $$\delta^2 E = \int_0^L EI\,\delta\phi'^2 + (F_x\cos\phi + F_y\sin\phi)\,\delta\phi^2\,ds,
/// \qquad \delta\phi(0) = 0,$$
///
/// is positive definite exactly when the Jacobi field $h = \partial\phi/\partial M_0$
/// (which solves $(EI h')' = (F_x\cos\phi + F_y\sin\phi)h$, $h(0) = 0$,
/// $EI h'(0) = 1$) stays positive on $(0, L]$ and $EI h'(L) > 0$: the
/// Prüfer angle of $h$ then stays below $\pi/2$ at the free end. $h$ is the
/// dual part of $\phi$ when the shot carries a dual root moment, and
/// $EI h'(L)$ is the derivative of the tip-moment balance the shooting solves.
///
/// # Example
/// ```
/// use flexure::{reference::elastica, Flexure};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // A straight column, clamped and free, buckles at P = π²EI/4L² ≈ 2.467.
/// assert!(elastica::is_stable(&f, 0.0, -2.4, 0.0, &Default::default()).unwrap());
/// assert!(!elastica::is_stable(&f, 0.0, -2.5, 0.0, &Default::default()).unwrap());
/// ```
pub fn is_stable(flexure: &Flexure, root_moment: f64, fx: f64, fy: f64, tol: &Tolerance) -> Result<bool> {
    Ok(jacobi_shot(flexure, root_moment, fx, fy, tol)?.stable())
}

/// One shot carrying the Jacobi field $h = \partial\phi/\partial M_0$ as a dual part.
struct JacobiShot {
    /// $(\phi, x, y)$ at the tip.
    tip: [f64; 3],
    /// The tip-moment balance $M_0 - F_y x_L + F_x y_L$ with derivative $EI h'(L)$.
    balance: Dual64,
    /// Whether $h > 0$ at every accepted step on $(0, L]$.
    positive: bool,
}

impl JacobiShot {
    fn stable(&self) -> bool {
        self.positive && self.balance.eps > 0.0
    }
}

fn jacobi_shot(flexure: &Flexure, root_moment: f64, fx: f64, fy: f64, tol: &Tolerance) -> Result<JacobiShot> {
    let m0 = Dual64::from_re(root_moment).derivative();
    let (fx, fy) = (Dual64::from(fx), Dual64::from(fy));
    let mut positive = true;
    let tip = shoot(flexure, m0, fx, fy, tol, |s, y| positive &= s == 0.0 || y[0].eps > 0.0)?;
    let balance = m0 - tip[1] * fy + tip[2] * fx;
    Ok(JacobiShot { tip: [tip[0].re, tip[1].re, tip[2].re], balance, positive })
}

/// An exact minimum-energy shape between two poses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Connection {
    /// Bending energy $U^* = \int_0^L \frac{EI}{2}(\omega - \omega_0)^2 ds$ (J).
    pub energy: f64,
    /// Bending moment at the root, $M_0$ (N·m).
    pub root_moment: f64,
    /// The force carried along the beam, equal to the force on the tip (N).
    pub fx: f64,
    /// See `fx`.
    pub fy: f64,
}

/// Integrates Eq. 3 as [`shoot`] does, adding the energy $\int m^2/2EI\,ds$ as a fourth state.
fn shoot_with_energy<T: Scalar>(flexure: &Flexure, m0: T, fx: T, fy: T, tol: &Tolerance) -> Result<[T; 4]> {
    let (ei, kappa) = (T::c(flexure.ei()), flexure.rest());
    let rhs = |s: f64, y: &[T; 4]| {
        let (sn, cs) = y[0].sin_cos();
        let m = m0 - fy * y[1] + fx * y[2];
        [T::c(flexure.curvature(kappa, s)) + m / ei, cs, sn, m * m / (ei + ei)]
    };
    integrate(rhs, 0.0, flexure.length(), [T::zero(); 4], tol, |_, _| {})
}

/// The exact elastica through `target`, by shooting on the root moment and
/// both force components (three unknowns) until the tip pose matches.
///
/// `guess` is $(M_0, F_x, F_y)$; the model's [`crate::connect::connect`]
/// multipliers, moved to the root, make a good one. The Jacobian comes from
/// dual numbers through the integrator. The minimum energy $U^*$ of Eq. 16.
///
/// # Example
/// ```
/// use flexure::{reference::elastica, Flexure, Pose};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // An arc of angle 1 needs a pure moment 1: U* = 1/2.
/// let target = Pose { phi: 1.0, x: 1f64.sin(), y: 1.0 - 1f64.cos() };
/// let c = elastica::connect(&f, &target, [0.9, 0.0, 0.0], &Default::default()).unwrap();
/// assert!((c.energy - 0.5).abs() < 1e-10 && (c.root_moment - 1.0).abs() < 1e-9);
/// ```
pub fn connect(flexure: &Flexure, target: &Pose, guess: [f64; 3], settings: &Settings) -> Result<Connection> {
    crate::connect::check_pose(flexure, target)?;
    let l = flexure.length();
    let residual = |z: &SVector<f64, 3>| -> Result<(SVector<f64, 3>, SMatrix<f64, 3, 3>)> {
        let v = |i: usize| num_dual::DualSVec64::<3>::from_re(z[i]).derivative(i);
        let tip = shoot_with_energy(flexure, v(0), v(1), v(2), &settings.ode)?;
        let r = [(tip[0] - target.phi) * l, tip[1] - target.x, tip[2] - target.y];
        let jac = SMatrix::<f64, 3, 3>::from_fn(|row, col| r[row].eps.unwrap_generic(nalgebra::U3, nalgebra::U1)[col]);
        Ok((SVector::from([r[0].re, r[1].re, r[2].re]), jac))
    };
    let root = find_root(residual, SVector::from(guess), 1e-12 * l, settings.max_iterations)?;
    let tip = shoot_with_energy(flexure, root.x[0], root.x[1], root.x[2], &settings.ode)?;
    Ok(Connection { energy: tip[3], root_moment: root.x[0], fx: root.x[1], fy: root.x[2] })
}
