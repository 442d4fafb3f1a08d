//! Time integration of $M(q)\ddot q = f(q, \dot q, t) - G^T\lambda$,
//! $c(q) = 0$ ([`System`]) by the three-stage Radau IIA method, adaptive
//! and error-controlled.
//!
//! **Why Radau IIA.** Flexure models are stiff (a flexure's axial or
//! higher bending modes lie orders of magnitude above the motion of
//! interest), their mass matrix may be singular (massless flexures), and
//! closed loops add position constraints: a differential-algebraic system
//! of index 3. The three-stage Radau IIA collocation method is L-stable and
//! stiffly accurate, so unresolved stiff modes are damped rather than
//! amplified, massless directions follow their quasi-static equilibrium, and
//! the new state is the last stage, on which $c(q) = 0$ is solved exactly
//! (no drift). It is of order 5 for ordinary differential equations, so a
//! tight tolerance is met with few steps and its numerical dissipation,
//! $1 - \lvert R(i\omega h)\rvert = O((\omega h)^6)$, stays far below
//! $10^{-6}$ of the energy over a hundred periods at the step sizes a tight
//! tolerance selects (Newmark and generalized-α methods, of order 2, would
//! need $\sim 10^3$ times more steps for that). On the constrained
//! (index-3) system the positions keep order 5 and the velocities order 3
//! (Hairer, Lubich & Roche 1989). It needs no initial accelerations: the
//! stage equations use only $q_0$ and $\dot q_0$. Directions with neither
//! inertia nor damping obey algebraic equations (quasi-static equilibrium);
//! a start off them (a massless flexure at its unloaded shape under load)
//! is first moved onto them, as DAE codes compute consistent initial values
//! (IDA's `IDACalcIC`): Newton's method on those equations along the
//! null space of $M$ and $D_t$, the other coordinates kept; the run records
//! that state at $t = 0$.
//!
//! **Stage equations.** With the Butcher matrix $A = (a_{ij})$ and nodes
//! $c_i$, the unknowns are the stage accelerations $\ddot Q_i$ and
//! multipliers $\Lambda_i$ ($i = 1, 2, 3$); the stage velocities and
//! positions follow as
//! $$\dot Q_i = \dot q_0 + h\textstyle\sum_j a_{ij}\ddot Q_j,\qquad
//! Q_i = q_0 + c_ih\dot q_0 + h^2\sum_j (A^2)_ {ij}\ddot Q_j,$$
//! and the equations are
//! $$M(Q_i)\ddot Q_i - f(Q_i, \dot Q_i, t_0 + c_ih) + G(Q_i)^T\Lambda_i = 0,
//! \qquad c(Q_i)/h^2 = 0.$$
//! A simplified Newton method solves them with the matrix frozen at the
//! start of a step, whose $(i, j)$ block is
//! $$\delta_{ij}M + h\thinspace a_{ij}D_t + h^2(A^2)_ {ij}K_t\quad\text{with
//! closure rows } (A^2)_ {ij}G \text{ and columns } \delta_{ij}G^T,$$
//! ($K_t = -\partial f/\partial q$, $D_t = -\partial f/\partial\dot q$).
//! A closure row that holds velocities
//! ([`System::velocity_closures`]: a rolling contact) reads
//! $G_k(Q_i)\dot Q_i/h = 0$ instead, with the row $a_{ij}G_k$: an index-2
//! constraint, for which Radau IIA converges too (Hairer & Wanner, *Solving
//! ODEs II*, VII.4). The matrix is regular when $M$ is singular as long as the stiffness holds the
//! massless directions, and at any step size. The new state is
//! $(q_1, \dot q_1) = (Q_3, \dot Q_3)$, as $c_3 = 1$. As in RADAU5, the
//! matrix's data $M$, $K_t$, $D_t$, $G$ are kept over the following steps
//! (and its factors while the step length stays) as long as Newton
//! contracts by at most 0.1 per iteration, and renewed after a rejected
//! step; a Newton failure with kept data retries the same step with fresh
//! data (CVODE's rule: kept data, not the step, is the likelier cause).
//! A failure with fresh data retries the same step, and the run goes on,
//! with each stage's own mass matrix $M(Q_i)$ in place of $M$ on its
//! diagonal block, taken with the residual at every iteration and factored
//! there: where inertia is small and changes within a step by much of
//! itself (a spatial flexure's inner directions take it on from zero as
//! they deflect), the matrix with $M(q_0)$ contracts by no better than a
//! constant at any step size, and shortening the step does not cure it (a
//! tendon-ramped continuum robot: the spectral radius of
//! $N^{-1}(J - N)$, $J$ the stage equations' Jacobian, stayed at 0.4–0.5
//! from $h$ = 27 µs to 7 µs, 0.4 of it from $M(Q_i) - M(q_0)$; it stalled
//! at 1.84 ms). A failure with the stages' masses halves the step.
//! Newton starts from the last step's collocation polynomial
//! extrapolated to the new stages.
//!
//! **Error control** (Hairer & Wanner, *Solving ODEs II*, IV.8, the
//! estimate of RADAU5): with $Z_i = (Q_i - q_0, \dot Q_i - \dot q_0)$, the
//! embedded third-order solution differs from the step by
//! $$e = (\mathcal M - h\gamma_0 J)^{-1}\bigl(h\gamma_0F(y_0) +
//! \gamma_0\mathcal M\textstyle\sum_i d_iZ_i\bigr),$$
//! $\mathcal M = \operatorname{diag}(I, M)$, whose position part solves
//! $(M + h\gamma_0D_t + h^2\gamma_0^2K_t)e_q + G^T\mu = \ldots$, $Ge_q = 0$:
//! the Newton matrix of one stage (with the step's own $M$ and $G$ and the
//! kept $K_t$, $D_t$: $G$ must be the step's, since the closure forces
//! missing from $f$ lie in its row space and its multipliers must absorb
//! them exactly), filtered so stiff components are not overestimated. Its
//! root mean square must be at most 1, each coordinate's error $e_r$
//! measured as
//! $$\frac{w_re_r}{\texttt{absolute} + \texttt{tolerance}\cdot\max_{k\in
//! g(r)}w_k\lvert q_k\rvert}$$
//! (the size the larger over the step's two ends; velocities alike, and
//! times $h$ when there are closures or directions without inertia: they
//! are index-2 variables there), with the weights $w$ and groups $g$ of
//! [`System::error_weights`]. A mechanism's are its joints' section turns:
//! a flexure's coefficient $\alpha_n$ weighs the root mean square of its
//! angle shape $\psi_n$ over the length relative to $\psi_0$'s
//! ([`crate::basis::angle_shape_rms`], about $n^{-3/2}$), and its size is
//! the flexure's largest such turn. So the test is in radians of section
//! turn, and a high coefficient, whose top modes are the truncation's own
//! (their frequencies move with the order: what they add is the order's
//! error, not the motion's), is not resolved below what the sections'
//! angles need; unresolved, L-stability damps it. A release from a large
//! deflection excites those modes: on the strip of BENCHMARKS.md the steps
//! then stop growing with the order. Newton's stopping test keeps each
//! coordinate's own scale, unweighted, and a mechanism with geoms keeps
//! every weight 1 ([`crate::dynamics::contact::ContactSystem`]). The step then changes by $0.9\thinspace\mathrm{err}^{-1/4}$ within $[1/8, 5]$.
//! In the first two steps only positions are weighed: the velocities of
//! massless directions at the start are not consistent with their motion
//! (and if the start could not be made consistent, the first step projects
//! it, its velocity jumping by the offset over $h$).
//! A step is also refused when it turns a section or body by more than
//! [`MotionSettings::max_rotation_per_step`] ([`System::distance`]), and none
//! exceeds [`MotionSettings::max_step`]. Steps land on the sample times exactly.
//!
//! **Bounded and honest.** Each step takes at most 7 simplified Newton
//! iterations; a contraction above 0.99 or a non-finite state ends them
//! early, and the step is retried as above. Increments that stop
//! shrinking at rounding's level (in an ill-conditioned mechanism), or
//! iterations that run out, are accepted when the estimated distance to the
//! solution is within 1 % of the tolerance; a refused step is retried shorter at most
//! [`MotionSettings::max_rejections`] times in a row, at most
//! [`MotionSettings::step_budget`] steps are tried in all (a run whose pace would
//! need more than [`PACE_MARGIN`] times the budget left stops as soon as it
//! knows, [`PACE_WINDOW`]), at most [`MAX_SWITCHES_AT_ONCE`] plus two per
//! guard switches happen at one instant, and no step falls to rounding's level: past any
//! of these the run stops with [`Error::IntegrationStalled`], saying the
//! time reached and why the last step failed; [`integrate_kept`] keeps the
//! samples reached before it. Every Newton iteration polls the hook of
//! [`crate::solver::with_interrupt`].
//!
//! The parts live apart: [`MotionSettings`] and the progress hook; the consistent
//! start; the step loop and its control; the stage Newton method; the local
//! error estimate; the Radau IIA tableau.

mod event;
pub(crate) use event::consistent_multipliers;
mod local_error;
mod newton;
mod norm;
mod progress;
mod radau;
mod settings;
mod start;
mod step;
mod trajectory;
mod work;

pub use progress::{Sample, with_progress, with_samples};
pub use settings::{MAX_SAMPLES, MAX_STEPS, MotionSettings};
pub use step::{MAX_SWITCHES_AT_ONCE, PACE_MARGIN, PACE_WINDOW};
pub use trajectory::{Trajectory, TrajectoryStop};

use super::System;
use crate::error::{Error, Result};

/// Errors that end the run at once rather than shortening the step.
pub(super) fn fatal(e: &Error) -> bool {
    matches!(e, Error::InterruptedAt { .. } | Error::InvalidParameter { .. })
}

/// Largest $\lvert x_i\rvert$; NaN if any entry is.
pub(super) fn largest(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |a: f64, x| if x.is_nan() { f64::NAN } else { a.max(x.abs()) })
}

/// Integrates `system` from the state (`q0`, `v0`) at $t = 0$ over
/// [`MotionSettings::duration`], reporting the state and energy at
/// [`MotionSettings::times`] (see the [module docs](self) for the method).
///
/// Fails with [`Error::InvalidParameter`] naming a bad setting, or
/// `initial` / `initial_velocity` when a state has the wrong length or a
/// non-finite entry; with [`Error::IntegrationStalled`] (the time reached,
/// steps taken and the last cause) when the step falls to rounding or the
/// step or rejection limit is reached; with [`Error::InterruptedAt`] (the
/// fraction of the duration reached) when the hook of
/// [`crate::solver::with_interrupt`] asks; and with a [`System`]'s own error
/// when a sample's energy cannot be evaluated.
///
/// # Example
/// ```
/// use flexure::dynamics::{integrate::{integrate, MotionSettings}, System};
/// use flexure::Result;
/// /// A unit mass on a unit spring: q = cos t.
/// struct Spring;
/// impl System for Spring {
///     fn dim(&self) -> usize { 1 }
///     fn closures(&self) -> usize { 0 }
///     fn dynamics(&mut self, q: &[f64], _: &[f64], _: f64, m: &mut [f64], f: &mut [f64]) -> Result<()> {
///         m[0] = 1.0;
///         f[0] = -q[0];
///         Ok(())
///     }
///     fn tangent(&mut self, _: &[f64], _: &[f64], _: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
///         k[0] = 1.0;
///         d[0] = 0.0;
///         Ok(())
///     }
///     fn energy(&mut self, q: &[f64], v: &[f64], _: f64) -> Result<f64> { Ok(0.5 * (q[0] * q[0] + v[0] * v[0])) }
///     fn distance(&self, a: &[f64], b: &[f64]) -> f64 { (a[0] - b[0]).abs() }
/// }
/// let s = MotionSettings { duration: 3.0, every: 1.0, tolerance: 1e-10, absolute: 1e-10, ..Default::default() };
/// let run = integrate(&mut Spring, &[1.0], &[0.0], &s).unwrap();
/// assert_eq!(run.time, [0.0, 1.0, 2.0, 3.0]);
/// assert_eq!(run.stop, flexure::dynamics::integrate::TrajectoryStop::Reached);
/// for (k, t) in run.time.iter().enumerate() {
///     assert!((run.q(k)[0] - t.cos()).abs() < 1e-8);
/// }
/// ```
pub fn integrate<S: System + ?Sized>(
    system: &mut S,
    q0: &[f64],
    v0: &[f64],
    settings: &MotionSettings,
) -> Result<Trajectory> {
    let (run, stopped) = integrate_kept(system, q0, v0, settings)?;
    stopped.map_or(Ok(run), Err)
}

/// [`integrate`] that keeps its work: a run that stops after its first
/// sample (stalled, interrupted, or a state that cannot be evaluated) returns
/// the samples it reached with the error that stopped it, and says which
/// of these ended it in [`Trajectory::stop`]. Bad settings or
/// states, and a start that cannot be made consistent, are still errors.
///
/// # Example
/// ```
/// use flexure::dynamics::integrate::{integrate_kept, MotionSettings};
/// use flexure::dynamics::System;
/// use flexure::{Error, Result};
/// /// A unit mass on a unit spring, which cannot be evaluated past t = 1.5 s.
/// struct Brittle;
/// impl System for Brittle {
///     fn dim(&self) -> usize { 1 }
///     fn closures(&self) -> usize { 0 }
///     fn dynamics(&mut self, q: &[f64], _: &[f64], t: f64, m: &mut [f64], f: &mut [f64]) -> Result<()> {
///         if t > 1.5 { return Err(Error::Singular { what: "past 1.5 s".into() }); }
///         m[0] = 1.0;
///         f[0] = -q[0];
///         Ok(())
///     }
///     fn tangent(&mut self, _: &[f64], _: &[f64], _: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
///         k[0] = 1.0;
///         d[0] = 0.0;
///         Ok(())
///     }
///     fn energy(&mut self, q: &[f64], v: &[f64], _: f64) -> Result<f64> { Ok(0.5 * (q[0] * q[0] + v[0] * v[0])) }
///     fn distance(&self, a: &[f64], b: &[f64]) -> f64 { (a[0] - b[0]).abs() }
/// }
/// let s = MotionSettings { duration: 3.0, every: 0.5, ..Default::default() };
/// let (run, stopped) = integrate_kept(&mut Brittle, &[1.0], &[0.0], &s).unwrap();
/// assert_eq!(run.time, [0.0, 0.5, 1.0, 1.5]);
/// assert!(matches!(stopped, Some(Error::IntegrationStalled { .. })));
/// assert_eq!(run.stop, flexure::dynamics::integrate::TrajectoryStop::Stalled);
/// ```
pub fn integrate_kept<S: System + ?Sized>(
    system: &mut S,
    q0: &[f64],
    v0: &[f64],
    settings: &MotionSettings,
) -> Result<(Trajectory, Option<Error>)> {
    settings.validate()?;
    let n = system.dim();
    for (name, state) in [("initial", q0), ("initial_velocity", v0)] {
        if state.len() != n {
            return Err(Error::invalid(name, state.len(), "must have one entry per coordinate of the system"));
        }
        if let Some(x) = state.iter().find(|x| !x.is_finite()) {
            return Err(Error::invalid(name, x, "must be finite numbers"));
        }
    }
    let samples = settings.times().len();
    let mut run = Trajectory {
        dim: n,
        time: Vec::with_capacity(samples),
        coordinates: Vec::with_capacity(samples * n),
        velocities: Vec::with_capacity(samples * n),
        energy: Vec::with_capacity(samples),
        steps: 0,
        rejected: 0,
        violation: 0.0,
        stop: TrajectoryStop::Reached,
    };
    match step::advance(system, q0, v0, settings, &mut run) {
        Ok(()) => Ok((run, None)),
        Err(e) if run.time.is_empty() => Err(e),
        Err(e) => {
            run.stop = TrajectoryStop::of(&e);
            Ok((run, Some(e)))
        }
    }
}
