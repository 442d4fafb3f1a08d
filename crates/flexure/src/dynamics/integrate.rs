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
//! Q_i = q_0 + c_ih\dot q_0 + h^2\sum_j (A^2)_{ij}\ddot Q_j,$$
//! and the equations are
//! $$M(Q_i)\ddot Q_i - f(Q_i, \dot Q_i, t_0 + c_ih) + G(Q_i)^T\Lambda_i = 0,
//! \qquad c(Q_i)/h^2 = 0.$$
//! A simplified Newton method solves them with the matrix frozen at the
//! start of a step, whose $(i, j)$ block is
//! $$\delta_{ij}M + h\thinspace a_{ij}D_t + h^2(A^2)_{ij}K_t\quad\text{with
//! closure rows } (A^2)_{ij}G \text{ and columns } \delta_{ij}G^T,$$
//! ($K_t = -\partial f/\partial q$, $D_t = -\partial f/\partial\dot q$):
//! regular when $M$ is singular as long as the stiffness holds the
//! massless directions, and at any step size. The new state is
//! $(q_1, \dot q_1) = (Q_3, \dot Q_3)$, as $c_3 = 1$. As in RADAU5, the
//! matrix's data $M$, $K_t$, $D_t$, $G$ are kept over the following steps
//! (and its factors while the step length stays) as long as Newton
//! contracts by at most 0.1 per iteration, and renewed after a rejected
//! step; a Newton failure with kept data retries the same step with fresh
//! data (CVODE's rule: kept data, not the step, is the likelier cause),
//! and with fresh data halves the step. Newton starts from the last step's collocation polynomial
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
//! them exactly), filtered so stiff components are not overestimated. Its root mean square, each coordinate weighted by
//! `absolute` + `tolerance` × its size (velocities times $h$ when there
//! are closures: they are index-2 variables there), must be at most 1; the
//! step then changes by $0.9\,\mathrm{err}^{-1/4}$ within $[1/8, 5]$.
//! In the first two steps only positions are weighed: the velocities of
//! massless directions at the start are not consistent with their motion
//! (and if the start could not be made consistent, the first step projects
//! it, its velocity jumping by the offset over $h$).
//! A step is also refused when it turns a section or body by more than
//! [`Settings::max_rotation_per_step`] ([`System::distance`]), and none
//! exceeds [`Settings::max_step`]. Steps land on the sample times exactly.
//!
//! **Bounded and honest.** Each step takes at most 7 simplified Newton
//! iterations; a contraction above 0.99 or a non-finite state ends them
//! early, and the step is retried as above. Increments that stop
//! shrinking at rounding's level (in an ill-conditioned mechanism), or
//! iterations that run out, are accepted when the estimated distance to the
//! solution is within 1 % of the tolerance; a refused step is retried shorter at most
//! [`Settings::max_rejections`] times in a row, at most
//! [`Settings::step_budget`] steps are tried in all (a run whose pace would
//! need more than [`PACE_MARGIN`] times the budget left stops as soon as it
//! knows, [`PACE_WINDOW`]), and no step falls to rounding's level: past any
//! of these the run stops with [`Error::IntegrationStalled`], saying the
//! time reached and why the last step failed; [`integrate_kept`] keeps the
//! samples reached before it. Every Newton iteration polls the hook of
//! [`crate::solver::with_interrupt`].

use super::System;
use crate::error::{Error, Result};
use crate::linalg;
use crate::solver::interrupted;

/// Settings of [`integrate`], checked by [`Settings::validate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Duration $T$ (s): the motion is integrated over $[0, T]$.
    pub duration: f64,
    /// Sample interval $\Delta t$ (s): states are reported at $0, \Delta t,
    /// 2\Delta t, \ldots$ and $T$.
    pub every: f64,
    /// Relative tolerance of each step's local error.
    pub tolerance: f64,
    /// Absolute tolerance of each step's local error, in the coordinates'
    /// units (rad, m) and those per second for velocities.
    pub absolute: f64,
    /// Largest step (s); `f64::INFINITY` for none.
    pub max_step: f64,
    /// Largest rotation (rad) of any section or body in one step.
    pub max_rotation_per_step: f64,
    /// Steps tried (accepted and rejected) before giving up; `None` (the
    /// default) follows the samples asked for: $10^6$ plus 10 per sample
    /// ([`Settings::step_budget`]).
    pub max_steps: Option<usize>,
    /// Successive rejections of one step before giving up.
    pub max_rejections: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            duration: 1.0,
            every: 0.01,
            tolerance: 1e-8,
            absolute: 1e-8,
            max_step: f64::INFINITY,
            max_rotation_per_step: 0.5,
            max_steps: None,
            max_rejections: 50,
        }
    }
}

thread_local! {
    static PROGRESS: std::cell::Cell<Option<fn(f64)>> = const { std::cell::Cell::new(None) };
}

/// Runs `work` with `report` called on this thread after every accepted
/// step of [`integrate`], with the fraction of the duration reached (from 0
/// to 1): a command line shows progress with it. The library itself prints
/// nothing.
///
/// # Example
/// ```
/// use flexure::dynamics::{integrate::with_progress, simulate, SimulationSettings, Start};
/// use std::sync::atomic::{AtomicU64, Ordering};
/// static LAST: AtomicU64 = AtomicU64::new(0);
/// // A sprung arm released from 0.1 rad, simulated for the default second.
/// let m = flexure::mechanism::file::from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n\
///      [[body]]\nname = \"arm\"\ninertia = 0.5\n[initial]\npin = 0.1\n",
/// )
/// .unwrap();
/// let report = |f: f64| LAST.store(f.to_bits(), Ordering::Relaxed);
/// let run = with_progress(report, || simulate(&m, &SimulationSettings::default(), Start::Equilibrium)).unwrap();
/// // The last report is the whole duration.
/// assert!(run.steps > 0 && f64::from_bits(LAST.load(Ordering::Relaxed)) == 1.0);
/// ```
pub fn with_progress<R>(report: fn(f64), work: impl FnOnce() -> R) -> R {
    /// Restores the previous hook on every exit, unwinding included.
    struct Restore(Option<fn(f64)>);
    impl Drop for Restore {
        fn drop(&mut self) {
            PROGRESS.with(|c| c.set(self.0));
        }
    }
    let _restore = Restore(PROGRESS.with(|c| c.replace(Some(report))));
    work()
}

/// The most samples a run may report.
pub const MAX_SAMPLES: usize = 1_000_000;

/// The largest step budget that may be set ([`Settings::max_steps`]).
pub const MAX_STEPS: usize = 1_000_000_000;

/// Every this many accepted steps, the run checks its pace: if the time
/// left would take more than [`PACE_MARGIN`] times the steps left in the
/// budget at the mean step of the last this many, it stops there, with the
/// samples reached, rather than spend the budget to fail at its end.
pub const PACE_WINDOW: usize = 1000;

/// See [`PACE_WINDOW`].
pub const PACE_MARGIN: f64 = 10.0;

/// Simplified Newton iterations per step before the step is retried shorter.
const NEWTON_ITERATIONS: usize = 7;

/// Newton increments (scaled, as fractions of the tolerance) that stop
/// shrinking below this are rounding's level, not divergence: the stage
/// solve is taken as converged there.
const NEWTON_FLOOR: f64 = 1e-2;

/// The Newton matrix's data are kept for the next step when the last
/// Newton contraction was at most this (RADAU5's `THET`, at the value its
/// authors advise for costly Jacobians); its factors while the step stays.
const REUSE: f64 = 0.1;

impl Settings {
    /// Checks every setting: a duration, interval or tolerance that is not a
    /// finite number greater than zero is an error naming it.
    ///
    /// # Example
    /// ```
    /// use flexure::{dynamics::integrate::Settings, Error};
    /// let bad = Settings { every: 0.0, ..Default::default() };
    /// assert!(matches!(bad.validate(), Err(Error::InvalidParameter { name: "every", .. })));
    /// ```
    pub fn validate(&self) -> Result<()> {
        use crate::error::positive;
        positive("duration", self.duration)?;
        if self.duration < 1e-12 {
            return Err(Error::invalid("duration", self.duration, "must be at least 1e-12 s"));
        }
        positive("every", self.every)?;
        positive("tolerance", self.tolerance)?;
        positive("absolute", self.absolute)?;
        if self.tolerance > 1.0 {
            return Err(Error::invalid("tolerance", self.tolerance, "must be at most 1 (a relative error)"));
        }
        if self.tolerance < 1e-14 {
            return Err(Error::invalid(
                "tolerance",
                self.tolerance,
                "must be at least 1e-14 (double-precision rounding)",
            ));
        }
        if self.max_step.is_nan() || self.max_step <= 0.0 {
            return Err(Error::invalid("max_step", self.max_step, "must be greater than zero (or infinite for none)"));
        }
        positive("max_rotation_per_step", self.max_rotation_per_step)?;
        if let Some(k) = self.max_steps {
            crate::error::count("max_steps", k, MAX_STEPS, "must be from 1 to 1000000000")?;
        }
        crate::error::count("max_rejections", self.max_rejections, 1000, "must be from 1 to 1000")?;
        if self.duration / self.every > MAX_SAMPLES as f64 {
            return Err(Error::invalid("every", self.every, "gives more than 1000000 samples over the duration"));
        }
        Ok(())
    }

    /// The steps a run may try: [`Settings::max_steps`], or $10^6$ plus 10
    /// per sample (a sample ends a step, so a run of $10^6$ samples is not
    /// cut short by a budget of $10^6$ steps).
    ///
    /// # Example
    /// ```
    /// use flexure::dynamics::integrate::Settings;
    /// let s = Settings { duration: 1.0, every: 1e-6, ..Default::default() };
    /// assert_eq!(s.step_budget(), 1_000_000 + 10 * 1_000_001);
    /// assert_eq!(Settings { max_steps: Some(500), ..s }.step_budget(), 500);
    /// ```
    pub fn step_budget(&self) -> usize {
        let samples = (self.duration / self.every).ceil().min(MAX_SAMPLES as f64) as usize + 1;
        self.max_steps.unwrap_or(1_000_000 + 10 * samples)
    }

    /// The sample times $0, \Delta t, 2\Delta t, \ldots, T$ (a last interval
    /// shorter than $10^{-9}\Delta t$ is merged into $T$).
    pub fn times(&self) -> Vec<f64> {
        let mut times = vec![0.0];
        let mut k = 1usize;
        while (k as f64) * self.every < self.duration - 1e-9 * self.every {
            times.push(k as f64 * self.every);
            k += 1;
        }
        times.push(self.duration);
        times
    }
}

/// A simulated motion, sampled at [`Settings::times`].
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// Number of coordinates $n$.
    pub dim: usize,
    /// Sample times (s).
    pub time: Vec<f64>,
    /// Coordinates $q$ at each sample, $n$ per sample.
    pub coordinates: Vec<f64>,
    /// Velocities $\dot q$ at each sample, $n$ per sample.
    pub velocities: Vec<f64>,
    /// [`System::energy`] at each sample (J).
    pub energy: Vec<f64>,
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps (error test, rotation bound or Newton failure).
    pub rejected: usize,
    /// Largest closure violation $\max_k\lvert c_k(q)\rvert$ over the
    /// start and every accepted step (0 without closures).
    pub violation: f64,
}

impl Trajectory {
    /// The coordinates at sample `k`.
    pub fn q(&self, k: usize) -> &[f64] {
        &self.coordinates[k * self.dim..(k + 1) * self.dim]
    }

    /// The velocities at sample `k`.
    pub fn v(&self, k: usize) -> &[f64] {
        &self.velocities[k * self.dim..(k + 1) * self.dim]
    }
}

/// The three-stage Radau IIA tableau and its error estimate's weights.
struct Radau {
    a: [[f64; 3]; 3],
    /// $A^2$.
    a2: [[f64; 3]; 3],
    c: [f64; 3],
    /// $d_i$ of the embedded estimate.
    d: [f64; 3],
    /// $\gamma_0$, the real eigenvalue of $A$.
    gamma: f64,
}

impl Radau {
    fn new() -> Self {
        let s6 = 6f64.sqrt();
        let a = [
            [(88.0 - 7.0 * s6) / 360.0, (296.0 - 169.0 * s6) / 1800.0, (-2.0 + 3.0 * s6) / 225.0],
            [(296.0 + 169.0 * s6) / 1800.0, (88.0 + 7.0 * s6) / 360.0, (-2.0 - 3.0 * s6) / 225.0],
            [(16.0 - s6) / 36.0, (16.0 + s6) / 36.0, 1.0 / 9.0],
        ];
        let mut a2 = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                a2[i][j] = (0..3).map(|k| a[i][k] * a[k][j]).sum();
            }
        }
        let c = [(4.0 - s6) / 10.0, (4.0 + s6) / 10.0, 1.0];
        let d = [-(13.0 + 7.0 * s6) / 3.0, (-13.0 + 7.0 * s6) / 3.0, -1.0 / 3.0];
        let gamma = (6.0 + 81f64.cbrt() - 9f64.cbrt()) / 30.0;
        Self { a, a2, c, d, gamma }
    }
}

/// Why a step was not taken.
enum Refusal {
    /// Its error estimate (scaled, > 1) or rotation asks for a step of this ratio.
    Shorter(f64, String),
    /// The state could not be evaluated: halve the step.
    Failed(String),
    /// Newton diverged or did not converge: retry with fresh matrix data
    /// if they were kept, else halve the step.
    Newton(String),
}

/// Buffers of one run; nothing is allocated per step.
struct Work {
    n: usize,
    m: usize,
    /// Start of the step: $M$ and $f$ at $(q_0, \dot q_0, t_0)$.
    m0: Vec<f64>,
    f0: Vec<f64>,
    /// The Newton matrix's data, kept over steps while Newton converges
    /// fast (RADAU5's reuse): $M$, $K_t$, $D_t$, $G$ at the start of the
    /// step where they were last evaluated.
    mj: Vec<f64>,
    k0: Vec<f64>,
    d0: Vec<f64>,
    g0: Vec<f64>,
    /// $G$ at the step's start, for the error estimate: the closure forces
    /// $G^T\lambda$ missing from $f$ there lie in its row space, so the
    /// estimate's multipliers absorb them exactly (with a kept $G$ they would
    /// leak, as a growing error in the directions without inertia).
    g_start: Vec<f64>,
    /// The step for which `matrix` and `e` hold their LU factors (NaN: none).
    factored: f64,
    /// The last accepted step's unknowns and length (0 before the first):
    /// its collocation polynomial extrapolated gives Newton's start.
    prev: Vec<f64>,
    prev_h: f64,
    /// The last Newton solve's contraction (0 when one iteration sufficed).
    theta: f64,
    /// Scratch for evaluations at the stages.
    mass: Vec<f64>,
    force: Vec<f64>,
    closure: Vec<f64>,
    jac: Vec<f64>,
    /// Newton matrix of the stages ($3(n+m)$ square), its pivots, unknowns
    /// $(\ddot Q_1, \ddot Q_2, \ddot Q_3, \Lambda_1, \Lambda_2, \Lambda_3)$, residual.
    matrix: Vec<f64>,
    pivots: Vec<usize>,
    x: Vec<f64>,
    r: Vec<f64>,
    /// Stage positions and velocities ($3n$ each).
    qs: Vec<f64>,
    vs: Vec<f64>,
    /// Error-estimate matrix ($n + m$ square), pivots, right side, and parts.
    e: Vec<f64>,
    epiv: Vec<usize>,
    erhs: Vec<f64>,
    rq: Vec<f64>,
    rs: Vec<f64>,
    eq: Vec<f64>,
    ev: Vec<f64>,
    qt: Vec<f64>,
    vt: Vec<f64>,
    /// Error scales of positions and velocities.
    sq: Vec<f64>,
    sv: Vec<f64>,
    /// Newton increments of the stage positions and velocities ($3n$ each).
    dq: Vec<f64>,
    dv: Vec<f64>,
    /// The previous Newton iteration's increments, for the rounding test.
    dq_prev: Vec<f64>,
    dv_prev: Vec<f64>,
}

impl Work {
    fn new(n: usize, m: usize) -> Self {
        let big = 3 * (n + m);
        let z = |k: usize| vec![0.0; k];
        Self {
            n,
            m,
            m0: z(n * n),
            f0: z(n),
            mj: z(n * n),
            factored: f64::NAN,
            prev: z(big),
            prev_h: 0.0,
            theta: 0.0,
            k0: z(n * n),
            d0: z(n * n),
            g0: z(m * n),
            g_start: z(m * n),
            mass: z(n * n),
            force: z(n),
            closure: z(m),
            jac: z(m * n),
            matrix: z(big * big),
            pivots: vec![0; big],
            x: z(big),
            r: z(big),
            qs: z(3 * n),
            vs: z(3 * n),
            e: z((n + m) * (n + m)),
            epiv: vec![0; n + m],
            erhs: z(n + m),
            rq: z(n),
            rs: z(n),
            eq: z(n),
            ev: z(n),
            qt: z(n),
            vt: z(n),
            sq: z(n),
            sv: z(n),
            dq: z(3 * n),
            dv: z(3 * n),
            dq_prev: z(3 * n),
            dv_prev: z(3 * n),
        }
    }
}

/// Errors that end the run at once rather than shortening the step.
fn fatal(e: &Error) -> bool {
    matches!(e, Error::InterruptedAt { .. } | Error::InvalidParameter { .. })
}

/// Largest $\lvert c_k(q)\rvert$.
fn violation<S: System + ?Sized>(system: &mut S, q: &[f64], w: &mut Work) -> Result<f64> {
    if w.m == 0 {
        return Ok(0.0);
    }
    system.closure(q, &mut w.closure, &mut w.jac)?;
    Ok(largest(&w.closure))
}

/// Largest $\lvert x_i\rvert$; NaN if any entry is.
fn largest(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |a: f64, x| if x.is_nan() { f64::NAN } else { a.max(x.abs()) })
}

/// Iterations of [`consistent_start`]'s Newton method.
const START_ITERATIONS: usize = 30;

/// Moves `q` onto the quasi-static equilibrium of the directions with
/// neither inertia nor damping ([`massless_directions`], a basis $N$),
/// keeping the others: it solves for $y$ and $\lambda$
/// $$r = N^T\bigl(G(q)^T\lambda - f(q, \dot q_0, 0)\bigr) = 0,\qquad c(q) = 0,
/// \qquad q = q_0 + Ny,$$
/// by Newton's method ([`start_step`]; closure forces acting only on
/// massive coordinates are left to the motion). These are the algebraic
/// equations of the system at $t = 0$: a start that violates them (a
/// massless flexure at its unloaded shape under a load) has no consistent
/// first step, the error of whichever jump the first step makes does not
/// shrink with the step, and at tight tolerances the run stalls there. DAE
/// codes compute consistent initial values the same way (IDA's
/// `IDACalcIC` for the algebraic components).
///
/// The answer is taken when the last correction is below $10^{-3}$ of the
/// tolerance (or rounding's level in the coordinates) and, evaluated there,
/// $r$ has fallen below $10^{-8}$ of its start's (or rounding's level) and
/// the closure violation is no larger than the start's (or `absolute`).
/// Otherwise, or after [`START_ITERATIONS`], `q` is left as it was and the
/// first step projects it.
fn consistent_start<S: System + ?Sized>(system: &mut S, q: &mut [f64], v: &[f64], settings: &Settings) -> Result<()> {
    use nalgebra::{DMatrix, DVector};
    let (n, m) = (system.dim(), system.closures());
    let (mut mass, mut force) = (vec![0.0; n * n], vec![0.0; n]);
    let (mut k, mut d) = (vec![0.0; n * n], vec![0.0; n * n]);
    let (mut c, mut g) = (vec![0.0; m], vec![0.0; m * n]);
    system.dynamics(q, v, 0.0, &mut mass, &mut force)?;
    system.tangent(q, v, 0.0, &mut k, &mut d)?;
    let basis = massless_directions(n, &mass, &d);
    if basis.ncols() == 0 {
        return Ok(());
    }
    let start = q.to_vec();
    let (mut start_violation, mut start_residual) = (0.0, 0.0);
    let mut lambda = DVector::<f64>::zeros(m);
    let mut converged = false;
    for iteration in 0..=START_ITERATIONS {
        // A state Newton moved to that cannot be evaluated ends the attempt.
        let evaluated = if iteration > 0 {
            system.dynamics(q, v, 0.0, &mut mass, &mut force).and_then(|()| system.tangent(q, v, 0.0, &mut k, &mut d))
        } else {
            Ok(())
        }
        .and_then(|()| if m > 0 { system.closure(q, &mut c, &mut g) } else { Ok(()) });
        match evaluated {
            Ok(()) => {}
            Err(e) if fatal(&e) => return Err(e),
            Err(_) => break,
        }
        // G is m × n, column-major.
        let g_matrix = DMatrix::from_column_slice(m, n, &g);
        let closure_force = g_matrix.transpose() * &lambda;
        let residual = basis.transpose() * DVector::from_fn(n, |r, _| closure_force[r] - force[r]);
        let stiffness = basis.transpose() * DMatrix::from_column_slice(n, n, &k) * &basis;
        if iteration == 0 {
            (start_violation, start_residual) = (largest(&c), residual.amax());
        }
        if converged {
            // Rounding's level of r: its terms' size, and the stiffness times the coordinates.
            let terms = (basis.transpose() * DVector::from_column_slice(&force)).amax().max(closure_force.amax());
            let noise = 1e3 * f64::EPSILON * terms.max(stiffness.amax() * largest(q));
            if largest(&c) <= start_violation.max(settings.absolute)
                && residual.amax() <= (1e-8 * start_residual).max(noise)
            {
                return Ok(());
            }
            break;
        }
        if iteration == START_ITERATIONS {
            break;
        }
        let Some((dy, dlambda)) =
            start_step(&stiffness, &(&g_matrix * &basis), &residual, &DVector::from_column_slice(&c))
        else {
            break;
        };
        let dq = &basis * dy;
        lambda += dlambda;
        let mut size: f64 = 0.0;
        for r in 0..n {
            q[r] += dq[r];
            let scale = settings.absolute + settings.tolerance * q[r].abs();
            size = size.max(dq[r].abs() / scale);
        }
        let floor = dq.iter().zip(q.iter()).all(|(x, y)| x.abs() <= 1e3 * f64::EPSILON * (1.0 + y.abs()));
        converged = (size <= 1e-3 || floor) && q.iter().all(|x| x.is_finite());
    }
    q.copy_from_slice(&start);
    Ok(())
}

/// A basis (columns) of the directions with neither inertia nor damping:
/// the null space of $M$ and $D_t$ stacked, each row over its largest
/// entry (a row is one coordinate's equation: this makes the test
/// independent of the coordinates' units), singular values below
/// $10^{-13}$ of the largest counting as zero: far above rounding (a
/// massless direction gives about $10^{-19}$) and below real mass ratios.
/// A massless direction with damping follows a first-order equation from
/// its start, and is not one of them.
fn massless_directions(n: usize, mass: &[f64], damping: &[f64]) -> nalgebra::DMatrix<f64> {
    let mut stacked = nalgebra::DMatrix::zeros(2 * n, n);
    for (block, values) in [(0, mass), (n, damping)] {
        for r in 0..n {
            let top = (0..n).fold(0.0, |a: f64, col| a.max(values[col * n + r].abs()));
            if top > 0.0 {
                for col in 0..n {
                    stacked[(block + r, col)] = values[col * n + r] / top;
                }
            }
        }
    }
    linalg::null_space_below(&stacked, 1e-13)
}

/// One Newton step of [`consistent_start`] by the null-space method, for
/// the stiffness $A = N^TK_tN$, $B = GN$, the residual $r$ and closures
/// $c$: $\delta y_p = -B^+c$ (least norm), then with $Z$ spanning the null
/// space of $B$, $Z^TAZ\,b = -Z^T(r + A\delta y_p)$,
/// $\delta y = \delta y_p + Zb$, and $\delta\lambda$ from
/// $B^T\delta\lambda = -(r + A\delta y)$ in least squares. Only redundant closures are cut off; $Z^TAZ$ is solved
/// down to $10^{-14}$ of its largest singular value, so a soft massless
/// flexure beside a stiff massless spring keeps its step. `None` when a
/// step is not finite.
fn start_step(
    a: &nalgebra::DMatrix<f64>,
    b: &nalgebra::DMatrix<f64>,
    r: &nalgebra::DVector<f64>,
    c: &nalgebra::DVector<f64>,
) -> Option<(nalgebra::DVector<f64>, nalgebra::DVector<f64>)> {
    let free = a.ncols();
    let (particular, z) = if b.nrows() == 0 {
        (nalgebra::DVector::zeros(free), nalgebra::DMatrix::identity(free, free))
    } else {
        (linalg::least_squares(b, &(-c)), linalg::null_space(b))
    };
    let reduced = z.transpose() * a * &z;
    let rhs = -(z.transpose() * (r + a * &particular));
    let svd = nalgebra::SVD::new(reduced, true, true);
    let cutoff = 1e-14 * svd.singular_values.amax();
    let coefficients = svd.solve(&rhs, cutoff).ok()?;
    let dy = particular + z * coefficients;
    let dlambda = if b.nrows() == 0 {
        nalgebra::DVector::zeros(0)
    } else {
        linalg::least_squares(&b.transpose(), &(-(r + a * &dy)))
    };
    let finite = dy.iter().chain(dlambda.iter()).all(|x| x.is_finite());
    finite.then_some((dy, dlambda))
}

/// Integrates `system` from the state (`q0`, `v0`) at $t = 0$ over
/// [`Settings::duration`], reporting the state and energy at
/// [`Settings::times`] (see the [module docs](self) for the method).
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
/// use flexure::dynamics::{integrate::{integrate, Settings}, System};
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
/// let s = Settings { duration: 3.0, every: 1.0, tolerance: 1e-10, absolute: 1e-10, ..Default::default() };
/// let run = integrate(&mut Spring, &[1.0], &[0.0], &s).unwrap();
/// assert_eq!(run.time, [0.0, 1.0, 2.0, 3.0]);
/// for (k, t) in run.time.iter().enumerate() {
///     assert!((run.q(k)[0] - t.cos()).abs() < 1e-8);
/// }
/// ```
pub fn integrate<S: System + ?Sized>(
    system: &mut S,
    q0: &[f64],
    v0: &[f64],
    settings: &Settings,
) -> Result<Trajectory> {
    let (run, stopped) = integrate_kept(system, q0, v0, settings)?;
    stopped.map_or(Ok(run), Err)
}

/// [`integrate`] that keeps its work: a run that stops after its first
/// sample (stalled, interrupted, or a state that cannot be evaluated) returns
/// the samples it reached with the error that stopped it. Bad settings or
/// states, and a start that cannot be made consistent, are still errors.
///
/// # Example
/// ```
/// use flexure::dynamics::integrate::{integrate_kept, Settings};
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
/// let s = Settings { duration: 3.0, every: 0.5, ..Default::default() };
/// let (run, stopped) = integrate_kept(&mut Brittle, &[1.0], &[0.0], &s).unwrap();
/// assert_eq!(run.time, [0.0, 0.5, 1.0, 1.5]);
/// assert!(matches!(stopped, Some(Error::IntegrationStalled { .. })));
/// ```
pub fn integrate_kept<S: System + ?Sized>(
    system: &mut S,
    q0: &[f64],
    v0: &[f64],
    settings: &Settings,
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
    };
    match advance(system, q0, v0, settings, &mut run) {
        Ok(()) => Ok((run, None)),
        Err(e) if run.time.is_empty() => Err(e),
        Err(e) => Ok((run, Some(e))),
    }
}

/// The steps of [`integrate_kept`], from the consistent start, recording into `run`.
fn advance<S: System + ?Sized>(
    system: &mut S,
    q0: &[f64],
    v0: &[f64],
    settings: &Settings,
    run: &mut Trajectory,
) -> Result<()> {
    let (n, m) = (system.dim(), system.closures());
    let rk = Radau::new();
    let mut w = Work::new(n, m);
    let times = settings.times();
    let duration = settings.duration;
    let (mut q, mut v) = (q0.to_vec(), v0.to_vec());
    consistent_start(system, &mut q, &v, settings)?;
    let (mut q1, mut v1) = (q.clone(), v.clone());
    let mut t = 0.0;
    run.violation = violation(system, &q, &mut w)?;
    record(system, run, 0.0, &q, &v)?;
    // A first step well inside the sample interval; the controller grows it
    // by up to 5 per step.
    let mut h = 1e-2 * settings.every.min(settings.max_step).min(duration);
    let mut eta = 1.0;
    let mut fresh = false;
    let mut last_rejected = false;
    let mut rejections = 0;
    let mut cause = String::new();
    // The Newton matrix's data must be evaluated anew; it was at this step's start.
    let (mut stale, mut current) = (true, false);
    let jumps = system.jumps();
    let budget = settings.step_budget();
    // The time and accepted steps at the start of the pace window (PACE_WINDOW).
    let (mut window_start, mut window_steps) = (0.0, 0);
    for &target in &times[1..] {
        while t < target {
            // The next jump of the loads up to this sample, landed on like a sample.
            let jump = jumps.iter().copied().find(|&j| j > t && j <= target);
            let stop = jump.unwrap_or(target);
            let stalled = |cause: &str, h: f64, run: &Trajectory| Error::IntegrationStalled {
                cause: cause.to_string(),
                time: t,
                duration,
                steps: run.steps,
                rejected: run.rejected,
                step: h,
            };
            if run.steps + run.rejected >= budget {
                // Many short steps that each passed or nearly passed: the
                // tolerance asks to resolve motion that fast, and lightly
                // damped stiff modes are what usually moves that fast.
                return Err(stalled(
                    &format!(
                        "{cause}; its limit of {} steps was reached, the steps near {h:.1e} s resolving \
                         motion that fast to the tolerance (lightly damped stiff modes, usually: material \
                         damping on the flexures lets the integrator step over them)",
                        budget
                    ),
                    h,
                    run,
                ));
            }
            if run.steps >= window_steps + PACE_WINDOW && run.rejected + run.steps < budget {
                let pace = (t - window_start) / (run.steps - window_steps) as f64;
                let needed = (duration - t) / pace;
                let left = (budget - run.steps - run.rejected) as f64;
                if needed > PACE_MARGIN * left {
                    return Err(stalled(
                        &format!(
                            "at the pace of the last {PACE_WINDOW} steps ({pace:.3e} s each) the {:.6e} s left would take \
                             about {needed:.2e} steps, more than {PACE_MARGIN} times the {left:.0} left of its budget of \
                             {budget} steps; stopped early rather than at the budget's end (a larger budget, a looser \
                             tolerance, damping on the flexures or a shorter duration)",
                            duration - t
                        ),
                        h,
                        run,
                    ));
                }
                (window_start, window_steps) = (t, run.steps);
            }
            if rejections > settings.max_rejections {
                return Err(stalled(&format!("{cause}; {rejections} successive rejections"), h, run));
            }
            let mut step = h.min(settings.max_step);
            let landing = t + 1.01 * step >= stop && stop - t <= settings.max_step;
            if landing {
                step = stop - t;
            }
            if step < 1e-14 * t.max(settings.every) || t + step == t {
                return Err(stalled(&format!("{cause}; the step fell to rounding's level"), step, run));
            }
            // Whether the last state passed to `dynamics` is this step's start.
            let mut at_start = false;
            if !fresh {
                // The step's start: M, f and G for the error estimate.
                system.dynamics(&q, &v, t, &mut w.m0, &mut w.f0)?;
                if m > 0 {
                    system.closure(&q, &mut w.closure, &mut w.g_start)?;
                }
                fresh = true;
                current = false;
                at_start = true;
            }
            if stale {
                // The tangents for the Newton matrix, at the state last
                // passed to `dynamics`: after a rejected attempt that was a stage.
                if !at_start {
                    system.dynamics(&q, &v, t, &mut w.mass, &mut w.force)?;
                }
                system.tangent(&q, &v, t, &mut w.k0, &mut w.d0)?;
                w.mj.copy_from_slice(&w.m0);
                if m > 0 {
                    system.closure(&q, &mut w.closure, &mut w.g0)?;
                }
                w.factored = f64::NAN;
                stale = false;
                current = true;
            }
            let attempt = attempt(
                system,
                &rk,
                &mut w,
                (t, step, duration, jump.filter(|_| landing)),
                (&q, &v),
                settings,
                &mut eta,
                (last_rejected || run.steps == 0, run.steps < 2),
            );
            let refusal = match attempt {
                Err(e) => return Err(e),
                Ok(Ok(ratio)) => {
                    let (qn, vn) = (&w.qs[2 * n..], &w.vs[2 * n..]);
                    let turn = system.distance(&q, qn);
                    if turn > settings.max_rotation_per_step || turn.is_nan() {
                        let r = 0.9 * settings.max_rotation_per_step / turn;
                        Some(Refusal::Shorter(
                            if r.is_nan() { 0.5 } else { r.min(0.5) },
                            format!("a step turned {turn:.3e} rad"),
                        ))
                    } else {
                        q1.copy_from_slice(qn);
                        v1.copy_from_slice(vn);
                        match violation(system, &q1, &mut w) {
                            Ok(c) if c.is_finite() => {
                                run.violation = run.violation.max(c);
                                // Accept; next step from the controller, within the rotation bound.
                                t = if landing { stop } else { t + step };
                                std::mem::swap(&mut q, &mut q1);
                                std::mem::swap(&mut v, &mut v1);
                                w.prev.copy_from_slice(&w.x);
                                w.prev_h = step;
                                run.steps += 1;
                                if let Some(report) = PROGRESS.with(|c| c.get()) {
                                    report(t / duration);
                                }
                                fresh = false;
                                // Past a jump the loads, and so the tangents, are new.
                                stale = w.theta > REUSE || (landing && jump.is_some());
                                let mut next = step * ratio.min(if last_rejected { 1.0 } else { 5.0 });
                                if turn > 0.0 {
                                    next = next.min(0.9 * step * settings.max_rotation_per_step / turn);
                                }
                                h = if landing && next >= step { next.max(h) } else { next };
                                last_rejected = false;
                                rejections = 0;
                                None
                            }
                            Ok(c) => Some(Refusal::Failed(format!("a closure violation of {c}"))),
                            Err(e) if fatal(&e) => return Err(e),
                            Err(e) => Some(Refusal::Failed(e.to_string())),
                        }
                    }
                }
                Ok(Err(r)) => Some(r),
            };
            if let Some(refusal) = refusal {
                let ratio = match refusal {
                    Refusal::Shorter(ratio, why) => {
                        cause = why;
                        ratio
                    }
                    Refusal::Failed(why) => {
                        cause = why;
                        0.5
                    }
                    Refusal::Newton(why) => {
                        cause = why;
                        if current { 0.5 } else { 1.0 }
                    }
                };
                h = step * ratio;
                // RADAU5: a matrix kept from an earlier step is renewed.
                stale = !current;
                run.rejected += 1;
                rejections += 1;
                last_rejected = true;
            }
        }
        record(system, run, target, &q, &v)?;
    }
    Ok(())
}

fn record<S: System + ?Sized>(system: &mut S, run: &mut Trajectory, t: f64, q: &[f64], v: &[f64]) -> Result<()> {
    // The energy first: a sample that cannot be evaluated is not half recorded.
    let energy = system.energy(q, v, t)?;
    run.time.push(t);
    run.coordinates.extend_from_slice(q);
    run.velocities.extend_from_slice(v);
    run.energy.push(energy);
    Ok(())
}

/// The stage positions and velocities from the stage accelerations in `w.x`.
fn stages(rk: &Radau, w: &mut Work, h: f64, q0: &[f64], v0: &[f64]) {
    let n = w.n;
    for i in 0..3 {
        for r in 0..n {
            let (mut dv, mut dq) = (0.0, 0.0);
            for j in 0..3 {
                dv += rk.a[i][j] * w.x[j * n + r];
                dq += rk.a2[i][j] * w.x[j * n + r];
            }
            w.vs[i * n + r] = v0[r] + h * dv;
            w.qs[i * n + r] = q0[r] + rk.c[i] * h * v0[r] + h * h * dq;
        }
    }
}

/// Root mean square of the position parts `dq` and velocity parts `dv`
/// (times `vw`) of `k` blocks, each entry over its scale.
fn scaled_norm(w: &Work, dq: &[f64], dv: &[f64], vw: f64) -> f64 {
    (scaled_dot(w, dq, dv, dq, dv, vw) / (2 * dq.len()).max(1) as f64).sqrt()
}

/// The scaled inner product of two increments (positions and velocities,
/// the latter times `vw`), each entry over its scale as in [`scaled_norm`].
fn scaled_dot(w: &Work, aq: &[f64], av: &[f64], bq: &[f64], bv: &[f64], vw: f64) -> f64 {
    let n = w.n;
    let mut sum = 0.0;
    for k in 0..aq.len() {
        let r = k % n;
        // Products of scaled entries: a vector with itself gives the sum of
        // its scaled squares, scaled_norm's.
        sum += (aq[k] / w.sq[r]) * (bq[k] / w.sq[r]) + (vw * av[k] / w.sv[r]) * (vw * bv[k] / w.sv[r]);
    }
    sum
}

/// Tries one step of length `h` from $(q_0, \dot q_0)$ at $t_0$: on success
/// the new state is the last stage in `w.qs`, `w.vs`, and the value is the
/// ratio of the next step to this one proposed by the error estimate.
#[allow(clippy::too_many_arguments)]
fn attempt<S: System + ?Sized>(
    system: &mut S,
    rk: &Radau,
    w: &mut Work,
    (t0, h, duration, jump): (f64, f64, f64, Option<f64>),
    (q0, v0): (&[f64], &[f64]),
    settings: &Settings,
    eta: &mut f64,
    (refine, start): (bool, bool),
) -> Result<std::result::Result<f64, Refusal>> {
    // A step that ends on a load's jump sees the load just before it.
    let stage_time = |i: usize| match jump {
        Some(j) => (t0 + rk.c[i] * h).min(j.next_down()),
        None => t0 + rk.c[i] * h,
    };
    let (n, m) = (w.n, w.m);
    let big = 3 * (n + m);
    let (rtol, atol) = (settings.tolerance, settings.absolute);
    // Velocities are index-2 variables of a constrained system: their
    // error is weighed by h (RADAU5's scaling). In the first two steps it
    // is not weighed at all: where a start off the quasi-static equilibrium
    // of a massless direction is projected onto it, that direction's
    // velocity jumps (by the jump over h), in the first step's estimate and
    // (through v0) the second's, and no step size would make it small. By
    // the third step the velocities derive from consistent positions.
    let vw = if start {
        0.0
    } else if m > 0 {
        h
    } else {
        1.0
    };
    for r in 0..n {
        w.sq[r] = atol + rtol * q0[r].abs();
        w.sv[r] = atol + rtol * v0[r].abs();
    }
    if w.factored != h && !factor(rk, w, h) {
        return Ok(Err(Refusal::Failed(
            "the Newton matrix is singular (a direction with neither mass nor stiffness, or dependent closures)".into(),
        )));
    }
    guess(rk, w, h);
    // Newton's stopping test (RADAU5): the estimated distance to the
    // solution at most kappa of the tolerance, above rounding.
    let kappa = (10.0 * f64::EPSILON / rtol).max(0.03f64.min(rtol.sqrt()));
    let mut previous = 0.0;
    let mut converged = false;
    w.theta = 0.0;
    for iteration in 0..NEWTON_ITERATIONS {
        if interrupted() {
            return Err(Error::InterruptedAt { time: t0, duration });
        }
        stages(rk, w, h, q0, v0);
        for i in 0..3 {
            let (qi, vi) = (&w.qs[i * n..(i + 1) * n], &w.vs[i * n..(i + 1) * n]);
            let evaluated = system
                .dynamics(qi, vi, stage_time(i), &mut w.mass, &mut w.force)
                .and_then(|()| if m > 0 { system.closure(qi, &mut w.closure, &mut w.jac) } else { Ok(()) });
            match evaluated {
                Ok(()) => {}
                Err(e) if fatal(&e) => return Err(e),
                Err(e) => return Ok(Err(Refusal::Failed(e.to_string()))),
            }
            for r in 0..n {
                let mut s = -w.force[r];
                for c in 0..n {
                    s += w.mass[c * n + r] * w.x[i * n + c];
                }
                for k in 0..m {
                    s += w.jac[r * m + k] * w.x[3 * n + i * m + k];
                }
                w.r[i * n + r] = -s;
            }
            for k in 0..m {
                w.r[3 * n + i * m + k] = -w.closure[k] / (h * h);
            }
        }
        if w.r.iter().any(|x| !x.is_finite()) {
            return Ok(Err(Refusal::Failed("a non-finite force or closure at a stage".into())));
        }
        linalg::lu_solve(&w.matrix, big, &w.pivots, &mut w.r);
        for i in 0..3 {
            for r in 0..n {
                let (mut a, mut b) = (0.0, 0.0);
                for j in 0..3 {
                    a += rk.a2[i][j] * w.r[j * n + r];
                    b += rk.a[i][j] * w.r[j * n + r];
                }
                w.dq[i * n + r] = h * h * a;
                w.dv[i * n + r] = h * b;
            }
        }
        for (x, d) in w.x.iter_mut().zip(&w.r) {
            *x += d;
        }
        let size = scaled_norm(w, &w.dq, &w.dv, vw);
        if !size.is_finite() {
            return Ok(Err(Refusal::Failed("a non-finite Newton step".into())));
        }
        if iteration > 0 {
            let theta = size / previous;
            if theta >= 0.99 {
                // Stalled at rounding's level, far below the tolerance? With
                // rho the last increment's component along the one before
                // (error e -> rho e), the distance to the solution is about
                // size * |rho| / |1 - rho|: near the last increment when they
                // alternate or are unrelated (noise), unbounded as they align.
                let rho = scaled_dot(w, &w.dq, &w.dv, &w.dq_prev, &w.dv_prev, vw)
                    / scaled_dot(w, &w.dq_prev, &w.dv_prev, &w.dq_prev, &w.dv_prev, vw);
                let distance = size * (rho.abs() / (1.0 - rho).abs()).max(1.0);
                if distance <= NEWTON_FLOOR {
                    w.theta = 1.0;
                    converged = true;
                    break;
                }
                return Ok(Err(Refusal::Newton(format!("Newton diverged (contraction {theta:.2})"))));
            }
            *eta = theta / (1.0 - theta);
            w.theta = theta;
        } else {
            *eta = eta.max(f64::EPSILON).powf(0.8);
        }
        if *eta * size <= kappa {
            converged = true;
            break;
        }
        previous = size;
        w.dq_prev.copy_from_slice(&w.dq);
        w.dv_prev.copy_from_slice(&w.dv);
    }
    // Out of iterations while creeping at rounding's level: the estimated
    // distance to the solution is still far below the tolerance.
    if !converged && *eta * previous <= NEWTON_FLOOR {
        w.theta = 1.0;
        converged = true;
    }
    if !converged {
        *eta = 1.0;
        return Ok(Err(Refusal::Newton(format!("Newton did not converge in {NEWTON_ITERATIONS} iterations"))));
    }
    stages(rk, w, h, q0, v0);
    // Error scales over the step's two ends.
    for r in 0..n {
        w.sq[r] = atol + rtol * q0[r].abs().max(w.qs[2 * n + r].abs());
        w.sv[r] = atol + rtol * v0[r].abs().max(w.vs[2 * n + r].abs());
    }
    let err = estimate(system, rk, w, t0, h, q0, v0, vw, false)?;
    let err = match err {
        Some(e) if e >= 1.0 && refine => estimate(system, rk, w, t0, h, q0, v0, vw, true)?,
        other => other,
    };
    let Some(err) = err else {
        return Ok(Err(Refusal::Failed(
            "the error estimate's matrix is singular or its state cannot be evaluated".into(),
        )));
    };
    let ratio = (0.9 / err.powf(0.25)).clamp(0.125, 5.0);
    if err > 1.0 {
        Ok(Err(Refusal::Shorter(ratio.min(0.9), format!("a local error of {err:.3e} times the tolerance"))))
    } else {
        Ok(Ok(ratio))
    }
}

/// Builds and factors the Newton matrix of the stages for a step `h` from
/// the kept data (`w.mj`, `w.k0`, `w.d0`, `w.g0`); false if it is singular.
fn factor(rk: &Radau, w: &mut Work, h: f64) -> bool {
    let (n, m) = (w.n, w.m);
    let big = 3 * (n + m);
    w.factored = f64::NAN;
    w.matrix.fill(0.0);
    for i in 0..3 {
        for j in 0..3 {
            let (ha, h2a) = (h * rk.a[i][j], h * h * rk.a2[i][j]);
            let diag = if i == j { 1.0 } else { 0.0 };
            for c in 0..n {
                for r in 0..n {
                    let k = c * n + r;
                    w.matrix[(j * n + c) * big + i * n + r] = diag * w.mj[k] + ha * w.d0[k] + h2a * w.k0[k];
                }
                for k in 0..m {
                    w.matrix[(j * n + c) * big + 3 * n + i * m + k] = rk.a2[i][j] * w.g0[c * m + k];
                }
            }
        }
        for k in 0..m {
            for r in 0..n {
                w.matrix[(3 * n + i * m + k) * big + i * n + r] = w.g0[r * m + k];
            }
        }
    }
    if !linalg::lu(&mut w.matrix, big, &mut w.pivots) {
        return false;
    }
    w.factored = h;
    true
}

/// Newton's start in `w.x`: the last accepted step's stage accelerations
/// and multipliers, the values at its nodes $c_j$ of a quadratic in time
/// (the derivative of the velocity's collocation polynomial), extrapolated
/// to this step's nodes $1 + c_ih/h_{prev}$; zero before the first step.
fn guess(rk: &Radau, w: &mut Work, h: f64) {
    let (n, m) = (w.n, w.m);
    if w.prev_h == 0.0 {
        w.x.fill(0.0);
        return;
    }
    for i in 0..3 {
        let tau = 1.0 + rk.c[i] * h / w.prev_h;
        let mut l = [1.0; 3];
        for (j, lj) in l.iter_mut().enumerate() {
            for k in (0..3).filter(|&k| k != j) {
                *lj *= (tau - rk.c[k]) / (rk.c[j] - rk.c[k]);
            }
        }
        for r in 0..n {
            w.x[i * n + r] = (0..3).map(|j| l[j] * w.prev[j * n + r]).sum();
        }
        for k in 0..m {
            w.x[3 * n + i * m + k] = (0..3).map(|j| l[j] * w.prev[3 * n + j * m + k]).sum();
        }
    }
}

/// The scaled norm of the embedded error estimate (module docs), leaving
/// $e_q$, $e_v$ in `w.eq`, `w.ev`. With `refine`, the force term is taken
/// at $y_0 + e$ (the last estimate) rather than $y_0$: RADAU5's second
/// estimate, for a step that failed the first at the start or after a
/// rejection, where stiff components are overestimated. `None` when the
/// matrix is singular or that state cannot be evaluated.
#[allow(clippy::too_many_arguments)]
fn estimate<S: System + ?Sized>(
    system: &mut S,
    rk: &Radau,
    w: &mut Work,
    t0: f64,
    h: f64,
    q0: &[f64],
    v0: &[f64],
    vw: f64,
    refine: bool,
) -> Result<Option<f64>> {
    let (n, m) = (w.n, w.m);
    let hg = h * rk.gamma;
    let size = n + m;
    if refine {
        for r in 0..n {
            w.qt[r] = q0[r] + w.eq[r];
            w.vt[r] = v0[r] + w.ev[r];
        }
        match system.dynamics(&w.qt, &w.vt, t0, &mut w.mass, &mut w.force) {
            Ok(()) => {}
            Err(e) if fatal(&e) => return Err(e),
            Err(_) => return Ok(None),
        }
    } else {
        w.force.copy_from_slice(&w.f0);
        w.vt.copy_from_slice(v0);
    }
    // R_q = hγ v + γ Σ d_i (Q_i − q0), and Σ d_i (V_i − v0).
    for r in 0..n {
        let (mut a, mut b) = (0.0, 0.0);
        for i in 0..3 {
            a += rk.d[i] * (w.qs[i * n + r] - q0[r]);
            b += rk.d[i] * (w.vs[i * n + r] - v0[r]);
        }
        w.rq[r] = hg * w.vt[r] + rk.gamma * a;
        w.rs[r] = b;
    }
    // Right side hγ R_v + (M + hγD) R_q, with R_v = hγ f + γ M Σ d_i (V_i − v0).
    for r in 0..n {
        let mut s = hg * hg * w.force[r];
        for c in 0..n {
            let k = c * n + r;
            s += hg * rk.gamma * w.m0[k] * w.rs[c] + (w.m0[k] + hg * w.d0[k]) * w.rq[c];
        }
        w.erhs[r] = s;
    }
    w.erhs[n..].fill(0.0);
    // The estimate's matrix takes this step's M and G, as its right side
    // does (a kept M would misjudge the error, a kept G would leak the
    // closure forces into the directions without inertia), and the kept tangents.
    w.e.fill(0.0);
    for c in 0..n {
        for r in 0..n {
            let k = c * n + r;
            w.e[c * size + r] = w.m0[k] + hg * w.d0[k] + hg * hg * w.k0[k];
        }
        for k in 0..m {
            w.e[c * size + n + k] = w.g_start[c * m + k];
            w.e[(n + k) * size + c] = w.g_start[c * m + k];
        }
    }
    if !linalg::lu(&mut w.e, size, &mut w.epiv) {
        return Ok(None);
    }
    linalg::lu_solve(&w.e, size, &w.epiv, &mut w.erhs);
    for r in 0..n {
        w.eq[r] = w.erhs[r];
        w.ev[r] = (w.erhs[r] - w.rq[r]) / hg;
    }
    let err = scaled_norm(w, &w.eq, &w.ev, vw);
    Ok(if err.is_finite() { Some(err) } else { None })
}
