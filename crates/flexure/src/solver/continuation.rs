//! Pseudo-arclength load continuation from $\lambda = 0$ to $\lambda = 1$,
//! through folds, with the stability of every state it passes.

use super::interrupt::interrupted;
use super::newton::{Mode, check_dim, correct};
use super::structured::structured_solve;
use super::{NewtonReport, Problem, Settings, SolverWorkspace, newton};
use crate::error::{Error, Result};
use crate::linalg;
use crate::scalar::Scalar;

/// The longest step (largest rotation, rad) across a fold: the limit load
/// is the peak of a cubic through the two points around the fold, accurate
/// to about $10^{-5}$ of the load at this spacing.
const FOLD_ROTATION: f64 = 0.35;

/// How many times [`Settings::max_rotation_per_step`] a step may turn a
/// section while the problem reports its state far from instability
/// ([`Problem::far_from_instability`]); the contraction test keeps such a
/// step on its branch.
pub const FAR_STEP: f64 = 4.0;

/// Why a continuation stopped, as argmin's `TerminationReason` says why
/// an optimizer did: one value with the path ([`Path::stop`]) rather than
/// state left behind for the caller to read.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum Stop {
    /// It reached $\lambda = 1$.
    Reached,
    /// It stopped where stability was first lost, as asked
    /// ([`Path::limit`]; only a run that stops there ends so).
    Lost,
    /// After losing stability it turned back below $\lambda = 0$.
    TurnedBack,
    /// No step down to [`Settings::min_step`] was accepted: `cause` says
    /// why the last one failed, `residual` is its corrector's.
    Stalled {
        /// Why the last step was rejected.
        cause: String,
        /// The last residual reached, in the problem's unit.
        residual: f64,
        /// Whether the last corrector stopped within rounding of its
        /// tolerance ([`Error::ContinuationStalled`]'s `rounding`).
        #[serde(skip)]
        rounding: bool,
    },
    /// It took [`Settings::max_steps`] steps without reaching $\lambda = 1$.
    StepCap {
        /// The last residual reached, in the problem's unit.
        residual: f64,
    },
    /// It evaluated the problem's Jacobian [`Settings::max_evaluations`]
    /// times, over its steps tried and their Newton iterations, without
    /// reaching $\lambda = 1$: the bound on its work, whatever the steps'
    /// lengths and however costly each evaluation.
    WorkCap {
        /// The last residual reached, in the problem's unit.
        residual: f64,
        /// The bound reached.
        evaluations: usize,
    },
    /// The hook set by [`super::with_interrupt`] asked it to stop.
    Interrupted,
}

/// What a continuation reached, and why it stopped there (serialized with
/// `limit` as `limit_fraction`).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Path {
    /// Why it stopped: [`Stop::Reached`] for every `Ok` of [`continuation`](fn@continuation).
    pub stop: Stop,
    /// The load fraction $\lambda$ of the last accepted state (`ws.x`).
    pub load_fraction: f64,
    /// Whether the last accepted state is stable ([`Problem::stable`]).
    pub stable: bool,
    /// The load fraction where stability was first lost along the path (a
    /// limit or bifurcation load), if it was.
    #[serde(rename = "limit_fraction")]
    pub limit: Option<f64>,
    /// Accepted continuation steps.
    pub steps: usize,
    /// Newton iterations over all steps.
    pub iterations: usize,
    /// Residual of the last accepted state, in the problem's unit.
    pub residual: f64,
}

impl Path {
    /// A path of no steps: a start converged by [`newton`](fn@newton) as `report`
    /// says, whose stability is `stable`, for a problem whose load does not
    /// change (the assembly of a mechanism).
    pub fn at_start(report: NewtonReport, stable: bool) -> Self {
        Self {
            stop: Stop::Reached,
            load_fraction: 0.0,
            stable,
            limit: None,
            steps: 0,
            iterations: report.iterations,
            residual: report.residual,
        }
    }

    /// Whether the path reached $\lambda = 1$.
    pub fn reached(&self) -> bool {
        self.stop == Stop::Reached
    }

    /// The path if it reached $\lambda = 1$, else the [`Error`] its stop
    /// stands for ([`Path::error`]).
    pub fn into_result<T: Scalar, P: Problem<T>>(self, problem: &P) -> Result<Path> {
        match self.error(problem) {
            None => Ok(self),
            Some(e) => Err(e),
        }
    }

    /// The [`Error`] that [`continuation`](fn@continuation) returns for this path, `None` if
    /// it reached $\lambda = 1$: [`Error::Unstable`] at [`Path::limit`] for
    /// a path that lost stability and did not come back,
    /// [`Error::ContinuationStalled`], [`Error::Interrupted`].
    pub fn error<T: Scalar, P: Problem<T>>(&self, problem: &P) -> Option<Error> {
        let unstable = |load_fraction| Some(Error::Unstable { what: problem.name(), load_fraction });
        match &self.stop {
            Stop::Reached => None,
            Stop::Lost => unstable(self.limit.unwrap_or(self.load_fraction)),
            Stop::TurnedBack => unstable(self.limit.unwrap_or(0.0)),
            Stop::Interrupted => Some(Error::Interrupted { load_fraction: self.load_fraction }),
            Stop::StepCap { .. } | Stop::WorkCap { .. } if self.limit.is_some() && !self.stable => {
                unstable(self.limit.unwrap_or(0.0))
            }
            Stop::StepCap { residual } => {
                let cause = format!("its limit of {} steps was reached", self.steps);
                Some(stalled(problem, self, *residual, &cause))
            }
            Stop::WorkCap { residual, evaluations } => {
                let cause = format!(
                    "its limit of {evaluations} Newton evaluations (max_evaluations) was reached; each costs more the more coordinates the joints have: lower the flexures' orders, or raise max_evaluations"
                );
                Some(stalled(problem, self, *residual, &cause))
            }
            Stop::Stalled { cause, residual, rounding } => {
                let mut e = stalled(problem, self, *residual, cause);
                if let Error::ContinuationStalled { rounding: r, .. } = &mut e {
                    *r = *rounding;
                }
                Some(e)
            }
        }
    }
}

/// Follows the solution of $r(x, \lambda) = 0$ from `ws.x` at $\lambda = 0$
/// to $\lambda = 1$, leaving the end state in `ws.x` (see the module docs
/// for the policies).
///
/// Errors: [`Error::ContinuationStalled`] when the step falls below
/// `min_step` or the steps run out (with the load fraction reached);
/// [`Error::Unstable`] when the path loses stability at a limit load and
/// does not come back to $\lambda = 1$; [`Error::Interrupted`]. [`trace`]
/// returns the same runs as a [`Path`] that says where they stopped.
pub fn continuation<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    ws: &mut SolverWorkspace<T>,
    settings: &Settings,
) -> Result<Path> {
    trace(problem, ws, settings)?.into_result(problem)
}

/// [`continuation`](fn@continuation) that stops with [`Error::Unstable`] as soon as the path
/// loses stability, for callers that only ask whether it stays stable.
pub(crate) fn continuation_while_stable<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    ws: &mut SolverWorkspace<T>,
    settings: &Settings,
) -> Result<Path> {
    follow(problem, ws, settings, true)?.into_result(problem)
}

/// [`continuation`](fn@continuation) whose partial runs are answers too: the path, however
/// it ended ([`Path::stop`]), with the last accepted state in `ws.x`.
/// `Err` only where no path starts: invalid settings or workspace, a start
/// that does not converge (or is interrupted before it does) or has a
/// zero-stiffness mode along the load, or a problem that rejects its
/// parameters.
///
/// # Example
/// ```
/// use flexure::solver::{trace, Problem, Stop, SolverWorkspace};
/// /// $r = x - 2\lambda$.
/// struct Line;
/// impl Problem<f64> for Line {
///     fn dim(&self) -> usize { 1 }
///     fn evaluate(&mut self, x: &[f64], l: f64, r: &mut [f64], j: Option<&mut [f64]>, d: Option<&mut [f64]>) -> flexure::Result<()> {
///         r[0] = x[0] - 2.0 * l;
///         if let Some(j) = j { j[0] = 1.0 }
///         if let Some(d) = d { d[0] = -2.0 }
///         Ok(())
///     }
///     fn distance(&self, a: &[f64], b: &[f64]) -> f64 { (a[0] - b[0]).abs() }
///     fn scale(&self) -> f64 { 1.0 }
///     fn unit(&self) -> &'static str { "" }
///     fn name(&self) -> &'static str { "line" }
/// }
/// let mut ws = SolverWorkspace::new(1);
/// let path = trace(&mut Line, &mut ws, &Default::default()).unwrap();
/// assert_eq!(path.stop, Stop::Reached);
/// assert!(path.load_fraction == 1.0 && (ws.x[0] - 2.0).abs() < 1e-12);
/// ```
pub fn trace<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    ws: &mut SolverWorkspace<T>,
    settings: &Settings,
) -> Result<Path> {
    follow(problem, ws, settings, false)
}

fn follow<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    ws: &mut SolverWorkspace<T>,
    settings: &Settings,
    stop_when_unstable: bool,
) -> Result<Path> {
    settings.validate()?;
    check_dim(problem, ws)?;
    let n = ws.n;
    let mut path = Path {
        stop: Stop::Reached,
        load_fraction: 0.0,
        stable: true,
        limit: None,
        steps: 0,
        iterations: 0,
        residual: 0.0,
    };
    // The start: converge at λ = 0 (the rest state, or the assembled one),
    // unless the caller just did and says how stable it is.
    let known = ws.start_stable.take().zip(ws.start.take());
    let known_start = known.is_some();
    let before = ws.evaluations;
    let start = match known {
        Some((stable, report)) => {
            path.stable = stable;
            report
        }
        None => {
            let report = newton(problem, ws, 0.0, settings)?;
            path.stable = problem.stable(&ws.x, 0.0, &ws.jacobian);
            report
        }
    };
    ws.start = None;
    // The work bound counts from here (with the start's own solve, if it was made here).
    let spent = if known_start { ws.evaluations } else { before };
    path.iterations += start.iterations;
    path.residual = start.residual;
    let mut lambda = 0.0_f64;
    // The first tangent: dx/dλ = −J⁻¹ ∂r/∂λ, bordered with (0, …, 0, 1).
    ws.previous_tangent.fill(T::zero());
    ws.previous_tangent[n] = T::one();
    if !tangent(ws, &mut *problem, 1.0) {
        return Err(Error::Singular {
            what: format!("{}: the rest state has a zero-stiffness mode along the load", problem.name()),
        });
    }
    // λ's weight in the arc length: the rate at which x first moves, so
    // that both parts of the first tangent count alike.
    let rate = (0..n).map(|i| (ws.tangent[i].re() * problem.weight(i)).powi(2)).sum::<f64>().sqrt()
        / ws.tangent[n].re().abs().max(f64::MIN_POSITIVE);
    let lambda_weight = rate.max(1e-3);
    // The arc length of the whole load taken as one linear step: the unit
    // of the step length, so min_step is relative to the load.
    let full = normalize(ws, problem, lambda_weight);
    let min_step = settings.min_step * full;
    let mut h = full;
    let mut rotation_rate = unit_rotation(problem, ws);
    let mut far = path.stable && problem.far_from_instability(&ws.x, 0.0, &ws.jacobian);
    let mut last_residual = start.residual;
    // Why the last rejected step failed, for the error if the steps run out.
    let mut cause = Cause::Corrector;
    while path.steps < settings.max_steps {
        if interrupted() {
            return Ok(Path { stop: Stop::Interrupted, load_fraction: lambda, ..path });
        }
        if ws.evaluations - spent >= settings.max_evaluations {
            let stop = Stop::WorkCap { residual: last_residual, evaluations: settings.max_evaluations };
            return Ok(Path { stop, load_fraction: lambda, ..path });
        }
        // Step length: at most double the last, turning no section by more
        // than 70 % of the bound; the last step lands on λ = 1.
        let bound = (settings.max_rotation_per_step * if far { FAR_STEP } else { 1.0 }).min(f64::MAX);
        // The step the ordinary bound allows: a longer one must end far from instability too.
        let ordinary = if rotation_rate > 0.0 { 0.7 * settings.max_rotation_per_step / rotation_rate } else { h };
        if rotation_rate > 0.0 {
            h = h.min(0.7 * bound / rotation_rate);
        }
        if !h.is_finite() {
            // Only an overflowing tangent gets here; halving would never end.
            let cause = "the step length overflowed".to_string();
            let stop = Stop::Stalled { cause, residual: last_residual, rounding: false };
            return Ok(Path { stop, load_fraction: lambda, ..path });
        }
        let t_lambda = ws.tangent[n].re();
        let landing = t_lambda > 0.0 && lambda + h * t_lambda >= 1.0 - 1e-12;
        // The step's length along the tangent (negative landing from past λ = 1).
        let taken = if landing { (1.0 - lambda) / t_lambda } else { h };
        let found = if landing {
            for i in 0..n {
                ws.trial[i] = ws.x[i] + ws.tangent[i] * T::c(taken);
            }
            let min_iterations = if T::is_value() { 0 } else { 1 };
            // Without the load derivative: only a tangent after a change of stability needs it.
            correct(problem, ws, Mode::Fixed, 1.0, lambda_weight, settings, min_iterations, true, false)
                .map(|r| (r, 1.0))
        } else {
            // Predict along the tangent; correct on the hyperplane through
            // the prediction, orthogonal to the tangent.
            for i in 0..n {
                ws.trial[i] = ws.x[i] + ws.tangent[i] * T::c(h);
            }
            ws.trial[n] = T::c(lambda) + ws.tangent[n] * T::c(h);
            ws.anchor.copy_from_slice(&ws.trial);
            correct(problem, ws, Mode::Arclength, lambda, lambda_weight, settings, 0, true, true)
                .map(|r| (r, ws.trial[n].re()))
        };
        let outcome = match found {
            Err(Error::Interrupted { .. }) => {
                return Ok(Path { stop: Stop::Interrupted, load_fraction: lambda, ..path });
            }
            Err(Error::NoConvergence { iterations, residual, unit, .. }) => {
                path.iterations += iterations;
                last_residual = residual;
                // A residual within rounding of the tolerance that would go no
                // lower is no failure to converge: the step cannot advance.
                let tolerance = settings.tolerance * problem.scale();
                cause = if residual <= ROUNDING * tolerance {
                    Cause::Rounding { residual, tolerance, unit }
                } else {
                    Cause::Corrector
                };
                None
            }
            Err(e @ Error::InvalidParameter { .. }) => return Err(e),
            Err(e) => {
                cause = Cause::Failed(e);
                None
            }
            Ok((report, new_lambda)) => {
                path.iterations += report.iterations;
                let turned = problem.distance(&ws.trial[..n], &ws.x);
                if turned > bound {
                    cause = Cause::Turned;
                    None
                } else if far && strayed(problem, ws, lambda, new_lambda, taken, lambda_weight) > STRAY * taken.abs() {
                    cause = Cause::Strayed;
                    None
                } else {
                    Some((report, new_lambda))
                }
            }
        };
        let Some((report, new_lambda)) = outcome else {
            h *= 0.5;
            if h < min_step {
                let rounding = matches!(cause, Cause::Rounding { .. });
                let stop = Stop::Stalled { cause: cause.to_string(), residual: last_residual, rounding };
                return Ok(Path { stop, load_fraction: lambda, ..path });
            }
            continue;
        };
        // Stability of the new state, and the tangent there (to tell a fold).
        let stable = problem.stable(&ws.trial[..n], new_lambda, &ws.jacobian);
        // Far from instability matters for a long step and for the next one (none after landing).
        let next_far = (taken > ordinary || !landing)
            && stable
            && problem.far_from_instability(&ws.trial[..n], new_lambda, &ws.jacobian);
        if taken > ordinary && !next_far {
            // A long step may only cross ground far from instability.
            h = ordinary;
            continue;
        }
        if landing && stable == path.stable {
            // The end, on the same side of stability: no fold or limit to read, no next tangent.
            ws.x.copy_from_slice(&ws.trial[..n]);
            path.steps += 1;
            path.residual = report.residual;
            ws.lambda = 1.0;
            return Ok(Path { load_fraction: 1.0, ..path });
        }
        let old_tangent_lambda = ws.tangent[n].re();
        ws.previous_tangent.copy_from_slice(&ws.tangent);
        // The landing corrector left no load derivative: evaluate it at the landed state.
        let has_tangent =
            (!landing || load_derivative_at_trial(problem, ws)) && tangent(ws, &mut *problem, lambda_weight);
        let fold = has_tangent && ws.tangent[n].re() * old_tangent_lambda < 0.0;
        if fold && problem.distance(&ws.trial[..n], &ws.x) > FOLD_ROTATION && h * 0.5 >= min_step {
            // Long steps are fine along the path, but the limit load is
            // read off the two points around a fold: take them close.
            ws.tangent.copy_from_slice(&ws.previous_tangent);
            h *= 0.5;
            continue;
        }
        if path.stable != stable && (!fold || landing) && h * 0.5 >= min_step {
            // A change of stability without a fold: a jump to another branch
            // (onto the loading path behind a snap, or off it), or a
            // bifurcation on the path; shorter steps tell them apart.
            ws.tangent.copy_from_slice(&ws.previous_tangent);
            h *= 0.5;
            continue;
        }
        if !has_tangent {
            ws.tangent.copy_from_slice(&ws.previous_tangent);
        }
        let _ = normalize(ws, problem, lambda_weight);
        if path.stable && !stable && path.limit.is_none() {
            path.limit = Some(if fold {
                fold_peak(lambda, new_lambda, ws.previous_tangent[n].re(), ws.tangent[n].re(), h)
            } else {
                lambda
            });
            if stop_when_unstable {
                return Ok(Path { stop: Stop::Lost, load_fraction: lambda, ..path });
            }
        }
        ws.x.copy_from_slice(&ws.trial[..n]);
        lambda = new_lambda;
        path.steps += 1;
        path.stable = stable;
        far = next_far;
        path.residual = report.residual;
        last_residual = report.residual;
        ws.lambda = lambda;
        path.load_fraction = lambda;
        if landing {
            return Ok(path);
        }
        if lambda < -1e-9 {
            return Ok(Path { stop: Stop::TurnedBack, ..path });
        }
        rotation_rate = unit_rotation(problem, ws);
        // Grow the step; the rotation bound above keeps it on the branch.
        h *= 2.0;
    }
    Ok(Path { stop: Stop::StepCap { residual: last_residual }, load_fraction: lambda, ..path })
}

/// The largest distance a corrector may move a step's prediction, as a
/// fraction of the step's length (both in the weighted arc length), from a
/// state far from instability ([`Problem::far_from_instability`]). There no
/// fold or bifurcation is near, the path is smooth, and a corrector that
/// moves the prediction further than the step is long did not correct it
/// but replaced it: it may have converged on another branch of equilibria,
/// stable and far from instability too, that ends far from the loading
/// path's (issue 39: at order 6 under $M = -6.26$, $F = (-15.5, 5.02)$,
/// unit length and stiffness, a first step of 2.46 from rest was corrected
/// 3.47 away, to $\varphi = 0.744$ where the path reaches $-4.971$). Such a
/// step is halved, which brings the correction, of the order of the path's
/// curvature times the square of the step, under the bound. Near
/// instability a corrector may move further than its step (onto a branch
/// that bifurcates, as $\sqrt h$), and the stability policy tells jumps there.
///
/// Measured on random tip loads of unit flexures at orders 3, 4, 5, 6 and
/// 8, against the path followed in steps of 0.05 rad: up to 10 N·m and 20 N,
/// 45 of 100,000 answers were on another branch (half and twice those
/// loads: 36 and 5 of 50,000); with this bound none of 100,000 at each
/// scale. The steps that jumped moved 1.4 to 3.5 times their length.
const STRAY: f64 = 1.0;

/// How far the corrector moved the step's prediction
/// $(x, \lambda) + h\thinspace t$ to the state in `ws.trial` at `new_lambda`, in the weighted arc length.
fn strayed<T: Scalar, P: Problem<T>>(
    problem: &P,
    ws: &SolverWorkspace<T>,
    lambda: f64,
    new_lambda: f64,
    h: f64,
    lambda_weight: f64,
) -> f64 {
    let n = ws.n;
    let x: f64 =
        (0..n).map(|i| ((ws.trial[i].re() - ws.x[i].re() - ws.tangent[i].re() * h) * problem.weight(i)).powi(2)).sum();
    let l = (new_lambda - lambda - ws.tangent[n].re() * h) * lambda_weight;
    (x + l * l).sqrt()
}

/// The largest $\lambda$ between two points of a path that turns back
/// between them (a fold): the peak of the cubic Hermite through
/// $(0, \lambda_0)$ and $(h, \lambda_1)$ with slopes $d_0, d_1$ in the arc length.
fn fold_peak(l0: f64, l1: f64, d0: f64, d1: f64, h: f64) -> f64 {
    let (a, b, c) = (6.0 * (l0 - l1) + 3.0 * h * (d0 + d1), 6.0 * (l1 - l0) - h * (4.0 * d0 + 2.0 * d1), h * d0);
    let hermite = |t: f64| {
        let (t2, t3) = (t * t, t * t * t);
        (2.0 * t3 - 3.0 * t2 + 1.0) * l0
            + (t3 - 2.0 * t2 + t) * h * d0
            + (3.0 * t2 - 2.0 * t3) * l1
            + (t3 - t2) * h * d1
    };
    let disc = b * b - 4.0 * a * c;
    let roots = if a.abs() < 1e-300 {
        [-c / b, f64::NAN]
    } else if disc >= 0.0 {
        [(-b + disc.sqrt()) / (2.0 * a), (-b - disc.sqrt()) / (2.0 * a)]
    } else {
        [f64::NAN; 2]
    };
    roots.iter().filter(|t| (0.0..=1.0).contains(*t)).map(|&t| hermite(t)).fold(l0.max(l1), f64::max)
}

/// A corrector's residual at most this many times its tolerance, that would
/// fall no further, stopped at rounding (double precision's limit on the
/// problem's scale), not short of convergence.
const ROUNDING: f64 = 10.0;

/// Why a continuation step was rejected (formatted only when the continuation stalls).
enum Cause {
    /// Newton did not converge on the step.
    Corrector,
    /// Newton stopped within [`ROUNDING`] times its tolerance and got no closer.
    Rounding {
        /// Its last residual.
        residual: f64,
        /// Its tolerance.
        tolerance: f64,
        /// Their unit.
        unit: &'static str,
    },
    /// The corrected state turned a section by more than the bound.
    Turned,
    /// The corrector moved the prediction further than [`STRAY`] times the step.
    Strayed,
    /// The problem could not be evaluated there.
    Failed(Error),
}

impl std::fmt::Display for Cause {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Cause::Corrector => write!(f, "the Newton corrector did not converge"),
            Cause::Rounding { residual, tolerance, unit } => write!(
                f,
                "the next step could not advance: its corrector stopped at rounding, residual {residual:.3e} {unit} against a tolerance of {tolerance:.3e} {unit}"
            ),
            Cause::Turned => write!(f, "every shorter step turned a section too far"),
            Cause::Strayed => write!(
                f,
                "every shorter step's corrector moved the state further from its prediction than the step is long"
            ),
            Cause::Failed(e) => write!(f, "{e}"),
        }
    }
}

fn stalled<T: Scalar, P: Problem<T>>(problem: &P, path: &Path, residual: f64, cause: &str) -> Error {
    Error::ContinuationStalled {
        cause: cause.to_string(),
        rounding: false,
        solver: problem.name(),
        load_fraction: path.load_fraction.clamp(0.0, 1.0),
        steps: path.steps,
        residual,
        unit: problem.unit(),
    }
}

/// Rotation caused by a unit step along the tangent.
fn unit_rotation<T: Scalar, P: Problem<T>>(problem: &P, ws: &mut SolverWorkspace<T>) -> f64 {
    let n = ws.n;
    for i in 0..n {
        ws.step[i] = ws.x[i] + ws.tangent[i];
    }
    problem.distance(&ws.step[..n], &ws.x)
}

/// Scales the tangent to unit weighted length; returns the length it had.
fn normalize<T: Scalar, P: Problem<T>>(ws: &mut SolverWorkspace<T>, problem: &P, lambda_weight: f64) -> f64 {
    let n = ws.n;
    let norm = ((0..n).map(|i| (ws.tangent[i].re() * problem.weight(i)).powi(2)).sum::<f64>()
        + (ws.tangent[n].re() * lambda_weight).powi(2))
    .sqrt();
    if norm > 0.0 && norm.is_finite() {
        for t in ws.tangent.iter_mut() {
            *t /= T::c(norm);
        }
    }
    norm
}

/// [`tangent`]'s solve where the bordered matrix's last row is
/// $(0, \dots, 0, e)$ (the first tangent, along the load), `false` (leaving
/// `ws.matrix` as it was) where it does not apply. There the bordered LU
/// is the Jacobian's, with $\partial_\lambda r$ eliminated alongside and $e$
/// left as the last pivot, and its solve of $(0, \dots, 0, 1)$ is
/// $t_\lambda = 1/e$, $t_x = U^{-1}(0 - t_\lambda L^{-1}P\thinspace\partial_\lambda r)$: the
/// same operations, so the same tangent to the bit. The Jacobian's factors
/// are kept while it stays the same to the bit (a start restored for
/// other loads, [`SolverWorkspace::restore_start`]). Only plain values: the bit
/// comparison sees no derivative parts. Applies only where every factor
/// and the eliminated $\partial_\lambda r$ are finite (where zeros times
/// infinities would make the bordered LU differ).
fn tangent_along_load<T: Scalar>(ws: &mut SolverWorkspace<T>) -> bool {
    let n = ws.n;
    let m = n + 1;
    let SolverWorkspace { jacobian, dlambda, matrix, tangent, factored, factors, factor_pivots, factors_valid, .. } =
        ws;
    let same =
        *factors_valid && factored.iter().zip(jacobian.iter()).all(|(a, b)| a.re().to_bits() == b.re().to_bits());
    if !same {
        factored.copy_from_slice(jacobian);
        factors.copy_from_slice(jacobian);
        *factors_valid = linalg::lu(factors, n, factor_pivots) && factors.iter().all(|v| v.re().is_finite());
    }
    let e = matrix[n * m + n];
    if !(*factors_valid && e.re().is_finite() && e.re() != 0.0) {
        return false;
    }
    let y = &mut tangent[..n];
    y.copy_from_slice(dlambda);
    linalg::lu_forward(factors, n, factor_pivots, y);
    if !y.iter().all(|v| v.re().is_finite()) {
        return false;
    }
    let t_lambda = T::one() / e;
    for v in y.iter_mut() {
        let mut b = T::zero();
        b -= *v * t_lambda;
        *v = b;
    }
    linalg::lu_backward(factors, n, y);
    tangent[n] = t_lambda;
    true
}

/// Evaluates `ws.jacobian` and `ws.dlambda` at the landed state `ws.trial`
/// ($\lambda = 1$) again, with the load derivative; false if that fails.
fn load_derivative_at_trial<T: Scalar, P: Problem<T>>(problem: &mut P, ws: &mut SolverWorkspace<T>) -> bool {
    let n = ws.n;
    let SolverWorkspace { trial, trial_residual, jacobian, dlambda, evaluations, .. } = ws;
    *evaluations += 1;
    problem.evaluate(&trial[..n], 1.0, &mut trial_residual[..n], Some(jacobian), Some(dlambda)).is_ok()
}

/// The tangent at the state just evaluated (its Jacobian and load
/// derivative in `ws`), oriented along `ws.previous_tangent`:
/// $[\partial_x r,\ \partial_\lambda r;\ t_{prev}^T W]\thinspace t = (0, 1)$.
/// False where that bordered matrix is singular.
fn tangent<T: Scalar, P: Problem<T>>(ws: &mut SolverWorkspace<T>, problem: &mut P, lambda_weight: f64) -> bool {
    let n = ws.n;
    let m = n + 1;
    for c in 0..n {
        ws.matrix[c * m..c * m + n].copy_from_slice(&ws.jacobian[c * n..c * n + n]);
        ws.matrix[c * m + n] = ws.previous_tangent[c] * T::c(problem.weight(c).powi(2));
    }
    ws.matrix[n * m..n * m + n].copy_from_slice(&ws.dlambda);
    ws.matrix[n * m + n] = ws.previous_tangent[n] * T::c(lambda_weight * lambda_weight);
    ws.tangent.fill(T::zero());
    ws.tangent[n] = T::one();
    if problem.factor(&ws.jacobian)
        && structured_solve(problem, &ws.matrix[..m * m], n, m, &mut ws.tangent, &mut ws.aux)
    {
        return ws.tangent.iter().all(|t| t.re().is_finite());
    }
    if T::is_value() && (0..n).all(|c| ws.matrix[c * m + n].re().to_bits() == 0) && tangent_along_load(ws) {
        return ws.tangent.iter().all(|t| t.re().is_finite());
    }
    if !linalg::lu(&mut ws.matrix[..m * m], m, &mut ws.pivots[..m]) {
        return false;
    }
    ws.tangent.fill(T::zero());
    ws.tangent[n] = T::one();
    linalg::lu_solve(&ws.matrix[..m * m], m, &ws.pivots[..m], &mut ws.tangent);
    ws.tangent.iter().all(|t| t.re().is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`tangent_along_load`] against the LU of the whole bordered matrix
    /// (the general path of [`tangent`]), on seeded random systems of 1 to
    /// 12 unknowns: the same tangent to the bit, from fresh factors, from
    /// kept ones, and after the Jacobian changes (factors made again).
    #[test]
    fn tangent_along_load_is_the_bordered_solve_to_the_bit() {
        let mut next = crate::linalg::uniform(0x9E37_79B9_7F4A_7C15_u64);
        let mut compared = 0;
        for n in 1..=12 {
            let m = n + 1;
            let mut ws = SolverWorkspace::<f64>::new(n);
            for trial in 0..6 {
                // Every other trial keeps the Jacobian and changes only ∂λr.
                if trial % 2 == 0 {
                    ws.jacobian.iter_mut().for_each(|v| *v = next());
                }
                ws.dlambda.iter_mut().for_each(|v| *v = next());
                let e = if trial < 2 { 1.0 } else { 0.5 + next().abs() };
                for c in 0..n {
                    ws.matrix[c * m..c * m + n].copy_from_slice(&ws.jacobian[c * n..c * n + n]);
                    ws.matrix[c * m + n] = 0.0;
                }
                ws.matrix[n * m..n * m + n].copy_from_slice(&ws.dlambda);
                ws.matrix[n * m + n] = e;
                let mut bordered = ws.matrix[..m * m].to_vec();
                let mut pivots = vec![0; m];
                assert!(linalg::lu(&mut bordered, m, &mut pivots));
                let mut reference = vec![0.0; m];
                reference[n] = 1.0;
                linalg::lu_solve(&bordered, m, &pivots, &mut reference);
                assert!(tangent_along_load(&mut ws), "n = {n}, trial {trial}");
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&ws.tangent), bits(&reference), "n = {n}, trial {trial}");
                compared += 1;
            }
        }
        assert_eq!(compared, 72);
    }
}
