//! The one solver core: a damped Newton method and a pseudo-arclength load
//! continuation over a [`Problem`], shared by every layer (tip loads,
//! tendons, minimum-energy connections, the exact elastica, mechanisms).
//!
//! A problem is a family of square systems $r(x, \lambda) = 0$ in the load
//! factor $\lambda \in [0, 1]$, with $r(x_0, 0) = 0$ at the rest state.
//! [`continuation`] follows the solution path from $(x_0, 0)$ to
//! $\lambda = 1$ in the arc length of $(x, \lambda)$, so it passes limit
//! points (snap-through): at a fold, where the path turns back in
//! $\lambda$, the tangent comes from the bordered system
//! $$\begin{bmatrix} \partial_x r & \partial_\lambda r \cr t_{prev}^T W & \end{bmatrix}
//! t = \begin{bmatrix} 0 \cr 1\end{bmatrix},$$
//! which stays regular there. Each step predicts along the tangent, then
//! Newton corrects on the hyperplane orthogonal to it; the last step lands
//! on $\lambda = 1$ exactly with $\lambda$ held fixed.
//!
//! Policies, shared by all problems:
//! - **Bounded**: at most [`Settings::max_steps`] steps of at least
//!   [`Settings::min_step`], each corrected by at most
//!   [`Settings::max_iterations`] Newton iterations of at most 30 halvings.
//! - **On the loading branch**: a step may turn no cross-section or body by
//!   more than [`Settings::max_rotation_per_step`] (the problem's
//!   [`Problem::distance`]), or [`FAR_STEP`] times that while the problem
//!   reports its state far from instability; its corrector must contract
//!   (the second Newton step at most half the first, no damping: Deuflhard's
//!   test that it stays in the branch's quadratic basin) and a step across
//!   a fold may turn sections by at most 0.35 rad, so the limit load is read
//!   off close points. A step whose stability differs from the
//!   last state's without a fold between them (a jump to another branch) is
//!   retried shorter. Only when no step down to `min_step` avoids it is the
//!   change accepted: a bifurcation on the path itself.
//! - **Honest**: the result says whether the end state is stable and the
//!   load fraction where stability was first lost ([`Path::limit`]).
//! - **Interruptible**: every step and iteration polls the hook set by
//!   [`with_interrupt`].

use crate::error::{Error, Result};
use crate::linalg;
use crate::scalar::Scalar;
use std::cell::Cell;

/// A family of square systems $r(x, \lambda) = 0$.
pub trait Problem<T: Scalar> {
    /// Number of unknowns $n$.
    fn dim(&self) -> usize;

    /// Writes $r(x, \lambda)$ and, when asked, the column-major
    /// $n\times n$ Jacobian $\partial_x r$ and the load derivative
    /// $\partial_\lambda r$. An `Err` marks a state that cannot be evaluated.
    fn evaluate(
        &mut self,
        x: &[T],
        lambda: f64,
        residual: &mut [T],
        jacobian: Option<&mut [T]>,
        dlambda: Option<&mut [T]>,
    ) -> Result<()>;

    /// Whether the state just evaluated (with its Jacobian) is stable.
    /// Potential problems, whose Jacobian is the Hessian of the potential,
    /// test its definiteness ([`linalg::positive_definite`]); problems with
    /// no notion of stability keep the default, `true`.
    fn stable(&mut self, _x: &[T], _lambda: f64, _jacobian: &[T]) -> bool {
        true
    }

    /// Whether the state just evaluated is far from any loss of stability:
    /// its Jacobian stays positive definite with a margin, so no fold or
    /// bifurcation is near and the continuation may take steps
    /// [`FAR_STEP`] times longer. The default, `false`, keeps every step
    /// within [`Settings::max_rotation_per_step`].
    fn far_from_instability(&mut self, _x: &[T], _lambda: f64, _jacobian: &[T]) -> bool {
        false
    }

    /// Factors $\partial_x r$ (the `jacobian` of the last evaluation) by
    /// the problem's own structure, for [`Problem::solve_factored`]; a
    /// mechanism's tree, for one, factors in $O(n)$ where dense LU costs
    /// $O(n^3)$. The default, `false`, leaves the solver to its dense LU,
    /// as does a `false` answer (a singular pivot). The solver checks
    /// every structured solve by its residual against the dense matrix
    /// (and falls back to LU if it is not accurate), solves bordered
    /// systems by block elimination with two such solves, and factors
    /// again before each use: [`Problem::stable`] and
    /// [`Problem::far_from_instability`] may use the same buffers.
    fn factor(&mut self, _jacobian: &[T]) -> bool {
        false
    }

    /// Solves $\partial_x r\thinspace y = b$ in place (`b` in, $y$ out) with
    /// the last factorization for which [`Problem::factor`] returned `true`.
    fn solve_factored(&mut self, _b: &mut [T]) {}

    /// How far apart two states are, in radians: the largest rotation of a
    /// cross-section or body between them. Bounds the continuation's steps.
    fn distance(&self, a: &[T], b: &[T]) -> f64;

    /// The residual's scale: Newton stops when $\max_i |r_i| \le$
    /// tolerance × scale.
    fn scale(&self) -> f64;

    /// The residual's unit, for messages.
    fn unit(&self) -> &'static str;

    /// The problem's name, for messages.
    fn name(&self) -> &'static str;

    /// Weight of unknown `i` in the arc length (default 1: radians and
    /// dimensionless coordinates).
    fn weight(&self, _i: usize) -> f64 {
        1.0
    }
}

/// Settings of [`newton`] and [`continuation`], validated by [`Settings::validate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Relative tolerance: converged when $\max_i|r_i| \le$ tolerance × [`Problem::scale`].
    pub tolerance: f64,
    /// Newton iterations per solve (per continuation step).
    pub max_iterations: usize,
    /// Continuation steps before giving up.
    pub max_steps: usize,
    /// Smallest continuation step, in the scaled arc length of $(x, \lambda)$
    /// (where a step carrying the whole load without turning measures 1).
    pub min_step: f64,
    /// Largest rotation (rad) of any cross-section or body in one step.
    pub max_rotation_per_step: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self { tolerance: 1e-12, max_iterations: 50, max_steps: 1000, min_step: 1e-6, max_rotation_per_step: 0.5 }
    }
}

/// The most iterations or steps a setting may ask for: enough for any
/// problem this library solves, small enough that a run always ends.
pub const MAX_COUNT: usize = 1_000_000;

impl Settings {
    /// Checks every setting: zero, negative or non-finite is an error naming it.
    ///
    /// # Example
    /// ```
    /// let bad = flexure::solver::Settings { min_step: 0.0, ..Default::default() };
    /// assert!(bad.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<()> {
        let positive = |name: &'static str, v: f64, max: f64| {
            if v.is_finite() && v > 0.0 && v <= max {
                Ok(())
            } else {
                Err(Error::invalid(name, v, "must be a finite number greater than zero (and at most 1 for min_step)"))
            }
        };
        positive("tolerance", self.tolerance, 1.0)?;
        if self.tolerance < 1e-15 {
            // Below rounding no residual can meet it: Newton would spin to its limit.
            return Err(Error::invalid(
                "tolerance",
                self.tolerance,
                "must be at least 1e-15 (double-precision rounding)",
            ));
        }
        positive("min_step", self.min_step, 1.0)?;
        positive("max_rotation_per_step", self.max_rotation_per_step, f64::MAX)?;
        crate::error::count("max_iterations", self.max_iterations, MAX_COUNT, "must be from 1 to 1000000")?;
        crate::error::count("max_steps", self.max_steps, MAX_COUNT, "must be from 1 to 1000000")?;
        Ok(())
    }
}

thread_local! {
    static INTERRUPT: Cell<Option<fn() -> bool>> = const { Cell::new(None) };
}

/// Runs `work` with `check` polled at every continuation step and Newton
/// iteration on this thread; when it returns `true` the solver stops with
/// [`Error::Interrupted`]. Bindings use it to honour Ctrl-C.
///
/// # Example
/// ```
/// use flexure::{deflect, solver::with_interrupt, Error, Flexure, Statics, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let mut data = Statics::new(&f);
/// let load = TipLoad { moment: 100.0, fx: 0.0, fy: 0.0 };
/// let r = with_interrupt(|| true, || deflect(&f, &load, &mut data, &Default::default()));
/// assert!(matches!(r, Err(Error::Interrupted { .. })));
/// ```
pub fn with_interrupt<R>(check: fn() -> bool, work: impl FnOnce() -> R) -> R {
    /// Restores the previous hook on every exit, unwinding included.
    struct Restore(Option<fn() -> bool>);
    impl Drop for Restore {
        fn drop(&mut self) {
            INTERRUPT.with(|c| c.set(self.0));
        }
    }
    let _restore = Restore(INTERRUPT.with(|c| c.replace(Some(check))));
    work()
}

/// Whether the hook set by [`with_interrupt`] asks to stop; also polled by
/// the time integrator ([`crate::dynamics::integrate`]).
pub(crate) fn interrupted() -> bool {
    INTERRUPT.with(|c| c.get()).is_some_and(|check| check())
}

/// Buffers for [`newton`] and [`continuation`] on an $n$-unknown problem;
/// nothing is allocated once they exist.
#[derive(Debug, Clone)]
pub struct Workspace<T: Scalar> {
    n: usize,
    /// The current state $x$: the start on entry, the solution on success.
    pub x: Vec<T>,
    /// $\lambda$ of the current state.
    pub lambda: f64,
    /// Where the last [`continuation`] first lost stability ([`Path::limit`]),
    /// kept when it stops with an error, so a caller can tell a path that
    /// failed after losing stability from one that failed before.
    pub limit: Option<f64>,
    /// Jacobian $\partial_x r$ at the solution (column-major $n\times n$).
    pub jacobian: Vec<T>,
    /// Set by a caller that has just converged `x` at $\lambda = 0$ by
    /// [`newton`] on the same problem and tested its stability (the value):
    /// the next [`continuation`] then starts from `x` as it stands, with the
    /// Jacobian and load derivative that solve left, instead of solving and
    /// testing again. Every continuation resets it; it is ignored unless
    /// the last call on this workspace was that [`newton`] at $\lambda = 0$.
    pub start_stable: Option<bool>,
    /// What the last [`newton`] reached, if it was at $\lambda = 0$.
    start: Option<NewtonReport>,
    dlambda: Vec<T>,
    /// Augmented $(n+1)$ system and its factors.
    matrix: Vec<T>,
    pivots: Vec<usize>,
    step: Vec<T>,
    trial: Vec<T>,
    trial_residual: Vec<T>,
    /// Tangent $(t_x, t_\lambda)$ and the previous one, in unscaled units.
    tangent: Vec<T>,
    previous_tangent: Vec<T>,
    anchor: Vec<T>,
    scratch: Vec<T>,
    /// Five vectors of length $n+1$ for structured solves ([`Problem::factor`]).
    aux: Vec<T>,
    /// A Jacobian, its LU factors and pivots, and whether they are valid
    /// and finite: kept for the first tangent of the next continuation
    /// from the same start ([`tangent_along_load`]).
    factored: Vec<T>,
    factors: Vec<T>,
    factor_pivots: Vec<usize>,
    factors_valid: bool,
}

impl<T: Scalar> Workspace<T> {
    /// Buffers for an `n`-unknown problem.
    pub fn new(n: usize) -> Self {
        let z = T::zero();
        let m = n + 1;
        Self {
            n,
            x: vec![z; n],
            lambda: 0.0,
            limit: None,
            jacobian: vec![z; n * n],
            start_stable: None,
            start: None,
            dlambda: vec![z; n],
            matrix: vec![z; m * m],
            pivots: vec![0; m],
            step: vec![z; m],
            trial: vec![z; m],
            trial_residual: vec![z; m],
            tangent: vec![z; m],
            previous_tangent: vec![z; m],
            anchor: vec![z; m],
            scratch: vec![z; m * m],
            aux: vec![z; 5 * m],
            factored: vec![z; n * n],
            factors: vec![z; n * n],
            factor_pivots: vec![0; n],
            factors_valid: false,
        }
    }

    /// Number of unknowns the buffers are sized for.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// $\partial_\lambda r$ at the current state, as left by the last
    /// evaluation: for a caller that restores a start ([`Workspace::restore_start`]).
    pub fn dlambda_mut(&mut self) -> &mut [T] {
        &mut self.dlambda
    }

    /// Declares `x` a start at $\lambda = 0$ that [`newton`] on the same
    /// problem reached as `report` says, with stability `stable`: what
    /// [`Workspace::start_stable`] does after that solve, for a caller that
    /// kept the solve's result and has put back `x`, [`Workspace::jacobian`]
    /// and [`Workspace::dlambda_mut`] exactly as that solve left them.
    pub fn restore_start(&mut self, report: NewtonReport, stable: bool) {
        self.lambda = 0.0;
        self.start = Some(report);
        self.start_stable = Some(stable);
    }
}

/// What a Newton solve achieved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonReport {
    /// Iterations taken.
    pub iterations: usize,
    /// Final $\max_i|r_i|$, in the problem's unit.
    pub residual: f64,
}

fn amax<T: Scalar>(v: &[T]) -> f64 {
    v.iter().fold(0.0, |m: f64, x| if x.re().is_nan() { f64::NAN } else { m.max(x.re().abs()) })
}

/// Which system a Newton solve works on.
#[derive(Clone, Copy)]
enum Mode {
    /// $r(x, \lambda) = 0$ at fixed $\lambda$.
    Fixed,
    /// $r(x, \lambda) = 0$ and $t^T W ((x,\lambda) - \text{anchor}) = 0$ (pseudo-arclength).
    Arclength,
}

/// Evaluates the residual (and the Newton matrix, if `matrix`) of the
/// system `mode` at the unknowns `z` ($x$, then $\lambda$ in arclength mode),
/// with the load derivative in arclength mode or if `load_derivative`.
#[allow(clippy::too_many_arguments)]
fn system<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    mode: Mode,
    z: &[T],
    lambda: f64,
    tangent: &[T],
    anchor: &[T],
    lambda_weight: f64,
    load_derivative: bool,
    residual: &mut [T],
    jacobian: Option<(&mut [T], &mut [T], &mut [T])>,
) -> Result<()> {
    let n = problem.dim();
    let lam = match mode {
        Mode::Fixed => lambda,
        Mode::Arclength => z[n].re(),
    };
    let (x, r) = (&z[..n], &mut residual[..n]);
    match jacobian {
        None => problem.evaluate(x, lam, r, None, None)?,
        Some((jac, dlambda, matrix)) => {
            let dlambda_wanted = load_derivative || matches!(mode, Mode::Arclength);
            problem.evaluate(x, lam, r, Some(&mut *jac), dlambda_wanted.then_some(&mut *dlambda))?;
            // In fixed mode the Newton matrix is the Jacobian itself, read
            // from `jac` ([`correct`]); only the bordered one is assembled.
            if let Mode::Arclength = mode {
                let m = n + 1;
                for c in 0..n {
                    matrix[c * m..c * m + n].copy_from_slice(&jac[c * n..c * n + n]);
                }
                matrix[n * m..n * m + n].copy_from_slice(dlambda);
                for c in 0..n {
                    matrix[c * m + n] = tangent[c] * T::c(problem.weight(c).powi(2));
                }
                matrix[n * m + n] = tangent[n] * T::c(lambda_weight * lambda_weight);
            }
        }
    }
    if let Mode::Arclength = mode {
        let mut s = T::zero();
        for c in 0..n {
            s += tangent[c] * T::c(problem.weight(c).powi(2)) * (z[c] - anchor[c]);
        }
        s += tangent[n] * T::c(lambda_weight * lambda_weight) * (z[n] - anchor[n]);
        residual[n] = s;
    }
    Ok(())
}

/// Damped Newton on `mode`'s system, from and into `ws.trial` (length $n$ or $n+1$).
/// In fixed mode `ws.dlambda` is left at the solution only if `load_derivative`.
#[allow(clippy::too_many_arguments)]
fn correct<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    ws: &mut Workspace<T>,
    mode: Mode,
    lambda: f64,
    lambda_weight: f64,
    settings: &Settings,
    min_iterations: usize,
    contraction: bool,
    load_derivative: bool,
) -> Result<NewtonReport> {
    let n = ws.n;
    let m = match mode {
        Mode::Fixed => n,
        Mode::Arclength => n + 1,
    };
    let tolerance = settings.tolerance * problem.scale();
    let (name, unit) = (problem.name(), problem.unit());
    let Workspace {
        trial, trial_residual, jacobian, dlambda, matrix, pivots, step, tangent, anchor, scratch, aux, ..
    } = ws;
    let matrix = &mut matrix[..m * m];
    let sys = |problem: &mut P, z: &[T], r: &mut [T], jac: Option<(&mut [T], &mut [T], &mut [T])>| {
        system(problem, mode, z, lambda, tangent, anchor, lambda_weight, load_derivative, r, jac)
    };
    sys(problem, &trial[..m], trial_residual, Some((jacobian, dlambda, matrix)))?;
    let mut residual = amax(&trial_residual[..m]);
    // Size of the first Newton step, for the contraction test.
    let mut first = 0.0;
    for iteration in 0..=settings.max_iterations {
        if interrupted() {
            return Err(Error::Interrupted { load_fraction: lambda });
        }
        if residual <= tolerance && iteration >= min_iterations {
            return Ok(NewtonReport { iterations: iteration, residual });
        }
        let fail = |iterations| Error::NoConvergence { solver: name, iterations, residual, unit };
        if iteration == settings.max_iterations || !residual.is_finite() {
            return Err(fail(iteration));
        }
        for (s, r) in step[..m].iter_mut().zip(&trial_residual[..m]) {
            *s = -*r;
        }
        // Newton step: by the problem's own factorization if it has one;
        // else by LU, where a singular matrix (a free motion, a bifurcation
        // point) is shifted along its diagonal until it factors. The Newton
        // matrix is ∂x r itself in fixed mode, else the bordered one.
        let newton: &[T] = match mode {
            Mode::Fixed => &jacobian[..m * m],
            Mode::Arclength => &matrix[..m * m],
        };
        if !(problem.factor(jacobian) && structured_solve(problem, newton, n, m, &mut step[..m], aux)) {
            // The shift, relative to the largest diagonal entry; that scale
            // is found only when the unshifted matrix does not factor.
            let (mut shift, mut diag) = (0.0, 0.0);
            loop {
                scratch_copy(newton, scratch, m, shift * diag);
                if linalg::lu(&mut scratch[..m * m], m, &mut pivots[..m]) {
                    break;
                }
                if shift == 0.0 {
                    diag = (0..m).map(|i| newton[i * m + i].re().abs()).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
                }
                shift = if shift == 0.0 { 1e-12 } else { shift * 100.0 };
                if shift > 1e2 {
                    return Err(Error::Singular {
                        what: format!(
                            "{name}: the Newton matrix is singular after {iteration} iterations (residual {residual:.3e} {unit}): a motion nothing resists, or constraints that cannot all be met"
                        ),
                    });
                }
            }
            for (s, r) in step[..m].iter_mut().zip(&trial_residual[..m]) {
                *s = -*r;
            }
            linalg::lu_solve(&scratch[..m * m], m, &pivots[..m], &mut step[..m]);
        }
        if contraction && iteration <= 1 {
            // A continuation step must land in the quadratic basin of the
            // branch it follows (Deuflhard's contraction test): the second
            // Newton step at most half the first, and no damping. Otherwise
            // the step is too long and is retried shorter. (Only the first
            // two steps' sizes are compared.)
            let size = (0..m)
                .map(|i| (step[i].re() * if i < n { problem.weight(i) } else { lambda_weight }).powi(2))
                .sum::<f64>()
                .sqrt();
            match iteration {
                0 => first = size,
                1 if size > CONTRACTION * first && first > 0.0 => {
                    return Err(Error::NoConvergence { solver: name, iterations: iteration, residual, unit });
                }
                _ => {}
            }
        }
        // Backtrack on the residual norm; near the tolerance accept a full
        // step that does not grow the residual much (rounding).
        let mut t = 1.0;
        loop {
            for i in 0..m {
                trial[i] += step[i] * T::c(t);
            }
            // The trial is evaluated with its Jacobian: accepted trials (most)
            // then need no second evaluation.
            let ok = sys(problem, &trial[..m], trial_residual, Some((jacobian, dlambda, matrix))).is_ok();
            let rt = amax(&trial_residual[..m]);
            if ok
                && (rt <= (1.0 - 1e-4 * t) * residual
                    || (t == 1.0 && residual < 1e3 * tolerance && rt < 10.0 * residual))
            {
                break;
            }
            // Undo this trial and halve.
            for i in 0..m {
                trial[i] -= step[i] * T::c(t);
            }
            t *= 0.5;
            if t < 1e-9 || contraction {
                return Err(fail(iteration));
            }
        }
        residual = amax(&trial_residual[..m]);
    }
    unreachable!("the loop returns at max_iterations")
}

/// The longest step (largest rotation, rad) across a fold: the limit load
/// is the peak of a cubic through the two points around the fold, accurate
/// to about $10^{-5}$ of the load at this spacing.
const FOLD_ROTATION: f64 = 0.35;

/// How many times [`Settings::max_rotation_per_step`] a step may turn a
/// section while the problem reports its state far from instability
/// ([`Problem::far_from_instability`]); the contraction test keeps such a
/// step on its branch.
pub const FAR_STEP: f64 = 4.0;

/// The largest ratio of the second Newton step to the first that a
/// continuation step accepts: Deuflhard's $\bar\Theta = 1/2$.
const CONTRACTION: f64 = 0.5;

/// The largest componentwise backward error (Oettli–Prager) a structured
/// solve may leave, after at most one step of iterative refinement, before
/// the solver falls back to dense LU: a Newton step this accurate still
/// cuts the residual by $10^{11}$, well past the default tolerance.
const STRUCTURED_ERROR: f64 = 1e-11;

/// Solves `matrix` $\cdot y$ = `y` in place ($m\times m$, column-major),
/// whose top-left $n\times n$ block is $\partial_x r$, just factored by
/// the problem: directly when $m = n$; when $m = n + 1$ by block
/// elimination of the border,
/// $$\begin{bmatrix} J & c\cr b^T & e\end{bmatrix}\begin{bmatrix} x\cr y_\lambda\end{bmatrix}
/// = \begin{bmatrix} f\cr g\end{bmatrix}:\quad J a = f,\ J w = c,\
/// y_\lambda = \frac{g - b^Ta}{e - b^Tw},\ x = a - y_\lambda w.$$
/// Block elimination loses accuracy near a fold, where $J$ is nearly
/// singular: the answer is checked against `matrix`, refined once if
/// needed, and refused (`false`, `y` unspecified) unless its
/// componentwise backward error is at most [`STRUCTURED_ERROR`]. `aux`
/// holds $5m$ values.
fn structured_solve<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    matrix: &[T],
    n: usize,
    m: usize,
    y: &mut [T],
    aux: &mut [T],
) -> bool {
    let (rhs, rest) = aux.split_at_mut(m);
    let (correction, rest) = rest.split_at_mut(m);
    let (bound, work) = rest.split_at_mut(m);
    rhs.copy_from_slice(&y[..m]);
    if !bordered(problem, matrix, n, m, y, work) {
        return false;
    }
    for refinement in 0..2 {
        // correction = rhs − M y, and the Oettli–Prager bound |M||y| + |rhs|.
        for i in 0..m {
            correction[i] = rhs[i];
            bound[i] = T::c(rhs[i].re().abs());
        }
        for c in 0..m {
            let yc = y[c];
            for r in 0..m {
                let a = matrix[c * m + r];
                correction[r] -= a * yc;
                bound[r] += T::c((a.re() * yc.re()).abs());
            }
        }
        let mut error = 0.0_f64;
        for i in 0..m {
            let (c, b) = (correction[i].re().abs(), bound[i].re());
            if !(c.is_finite() && b.is_finite()) {
                return false;
            }
            if c > 0.0 {
                error = error.max(c / b);
            }
        }
        if error <= STRUCTURED_ERROR {
            return true;
        }
        if refinement == 1 || !bordered(problem, matrix, n, m, correction, work) {
            return false;
        }
        for i in 0..m {
            y[i] += correction[i];
        }
    }
    false
}

/// One structured solve of [`structured_solve`]'s system, in place; `work` holds $2m$ values.
fn bordered<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    matrix: &[T],
    n: usize,
    m: usize,
    y: &mut [T],
    work: &mut [T],
) -> bool {
    if m == n {
        problem.solve_factored(&mut y[..n]);
        return y[..n].iter().all(|v| v.re().is_finite());
    }
    let (a, w) = work.split_at_mut(m);
    a[..n].copy_from_slice(&y[..n]);
    problem.solve_factored(&mut a[..n]);
    w[..n].copy_from_slice(&matrix[n * m..n * m + n]);
    problem.solve_factored(&mut w[..n]);
    let (mut ba, mut bw) = (T::zero(), T::zero());
    for i in 0..n {
        ba += matrix[i * m + n] * a[i];
        bw += matrix[i * m + n] * w[i];
    }
    let den = matrix[n * m + n] - bw;
    if !(den.re().is_finite() && den.re() != 0.0) {
        return false;
    }
    let last = (y[n] - ba) / den;
    for i in 0..n {
        y[i] = a[i] - w[i] * last;
    }
    y[n] = last;
    y[..m].iter().all(|v| v.re().is_finite())
}

fn scratch_copy<T: Scalar>(matrix: &[T], scratch: &mut [T], m: usize, shift: f64) {
    scratch[..m * m].copy_from_slice(matrix);
    if shift != 0.0 {
        for i in 0..m {
            scratch[i * m + i] += T::c(shift);
        }
    }
}

/// Damped Newton on $r(x, \lambda) = 0$ at fixed $\lambda$, from `ws.x`
/// (updated in place; `ws.jacobian` holds $\partial_x r$ at the solution).
///
/// Each step solves $\partial_x r\thinspace\delta = -r$ by LU (shifting a singular
/// matrix along its diagonal), then halves until $\max|r|$ decreases.
/// Stops with [`Error::NoConvergence`] at the iteration limit.
pub fn newton<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    ws: &mut Workspace<T>,
    lambda: f64,
    settings: &Settings,
) -> Result<NewtonReport> {
    settings.validate()?;
    check_dim(problem, ws)?;
    let n = ws.n;
    ws.start = None;
    ws.trial[..n].copy_from_slice(&ws.x);
    let min_iterations = if T::is_value() { 0 } else { 1 };
    let report = correct(problem, ws, Mode::Fixed, lambda, 1.0, settings, min_iterations, false, true)?;
    ws.x.copy_from_slice(&ws.trial[..n]);
    ws.lambda = lambda;
    ws.start = (lambda == 0.0).then_some(report);
    Ok(report)
}

fn check_dim<T: Scalar, P: Problem<T>>(problem: &P, ws: &Workspace<T>) -> Result<()> {
    if problem.dim() != ws.n {
        return Err(Error::invalid("workspace", ws.n, "was made for a problem of another size"));
    }
    Ok(())
}

/// What [`continuation`] reached.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Path {
    /// Whether the end state is stable ([`Problem::stable`]).
    pub stable: bool,
    /// The load fraction where stability was first lost along the path (a
    /// limit or bifurcation load), if it was.
    pub limit: Option<f64>,
    /// Accepted continuation steps.
    pub steps: usize,
    /// Newton iterations over all steps.
    pub iterations: usize,
    /// Final residual, in the problem's unit.
    pub residual: f64,
}

/// Follows the solution of $r(x, \lambda) = 0$ from `ws.x` at $\lambda = 0$
/// to $\lambda = 1$, leaving the end state in `ws.x` (see the module docs
/// for the policies).
///
/// Errors: [`Error::ContinuationStalled`] when the step falls below
/// `min_step` or the steps run out (with the load fraction reached);
/// [`Error::Unstable`] when the path loses stability at a limit load and
/// does not come back to $\lambda = 1$; [`Error::Interrupted`].
pub fn continuation<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    ws: &mut Workspace<T>,
    settings: &Settings,
) -> Result<Path> {
    follow(problem, ws, settings, false)
}

/// [`continuation`] that stops with [`Error::Unstable`] as soon as the path
/// loses stability, for callers that only ask whether it stays stable.
pub(crate) fn continuation_while_stable<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    ws: &mut Workspace<T>,
    settings: &Settings,
) -> Result<Path> {
    follow(problem, ws, settings, true)
}

fn follow<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    ws: &mut Workspace<T>,
    settings: &Settings,
    stop_when_unstable: bool,
) -> Result<Path> {
    settings.validate()?;
    check_dim(problem, ws)?;
    let n = ws.n;
    let mut path = Path { stable: true, limit: None, steps: 0, iterations: 0, residual: 0.0 };
    ws.limit = None;
    // The start: converge at λ = 0 (the rest state, or the assembled one),
    // unless the caller just did and says how stable it is.
    let known = ws.start_stable.take().zip(ws.start.take());
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
            return Err(Error::Interrupted { load_fraction: lambda });
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
            return Err(stalled(problem, lambda, &path, last_residual, "the step length overflowed"));
        }
        let t_lambda = ws.tangent[n].re();
        let landing = t_lambda > 0.0 && lambda + h * t_lambda >= 1.0 - 1e-12;
        let found = if landing {
            let hl = (1.0 - lambda) / t_lambda;
            for i in 0..n {
                ws.trial[i] = ws.x[i] + ws.tangent[i] * T::c(hl);
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
            Err(Error::Interrupted { .. }) => return Err(Error::Interrupted { load_fraction: lambda }),
            Err(Error::NoConvergence { iterations, residual, .. }) => {
                path.iterations += iterations;
                last_residual = residual;
                cause = Cause::Corrector;
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
                } else {
                    Some((report, new_lambda))
                }
            }
        };
        let Some((report, new_lambda)) = outcome else {
            h *= 0.5;
            if h < min_step {
                return Err(stalled(problem, lambda, &path, last_residual, &cause.to_string()));
            }
            continue;
        };
        // Stability of the new state, and the tangent there (to tell a fold).
        let stable = problem.stable(&ws.trial[..n], new_lambda, &ws.jacobian);
        let taken = if landing { (1.0 - lambda) / t_lambda } else { h };
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
            return Ok(path);
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
            ws.limit = path.limit;
            if stop_when_unstable {
                return Err(Error::Unstable { what: problem.name(), load_fraction: path.limit.unwrap_or(lambda) });
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
        if landing {
            return Ok(path);
        }
        if lambda < -1e-9 {
            return Err(Error::Unstable { what: problem.name(), load_fraction: path.limit.unwrap_or(0.0) });
        }
        rotation_rate = unit_rotation(problem, ws);
        // Grow the step; the rotation bound above keeps it on the branch.
        h *= 2.0;
    }
    match path.limit {
        Some(limit) if !path.stable => Err(Error::Unstable { what: problem.name(), load_fraction: limit }),
        _ => {
            let cause = format!("its limit of {} steps was reached", settings.max_steps);
            Err(stalled(problem, lambda, &path, last_residual, &cause))
        }
    }
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

/// Why a continuation step was rejected (formatted only when the continuation stalls).
enum Cause {
    /// Newton did not converge on the step.
    Corrector,
    /// The corrected state turned a section by more than the bound.
    Turned,
    /// The problem could not be evaluated there.
    Failed(Error),
}

impl std::fmt::Display for Cause {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Cause::Corrector => write!(f, "the Newton corrector did not converge"),
            Cause::Turned => write!(f, "every shorter step turned a section too far"),
            Cause::Failed(e) => write!(f, "{e}"),
        }
    }
}

fn stalled<T: Scalar, P: Problem<T>>(problem: &P, lambda: f64, path: &Path, residual: f64, cause: &str) -> Error {
    Error::ContinuationStalled {
        cause: cause.to_string(),
        solver: problem.name(),
        load_fraction: lambda.clamp(0.0, 1.0),
        steps: path.steps,
        residual,
        unit: problem.unit(),
    }
}

/// Rotation caused by a unit step along the tangent.
fn unit_rotation<T: Scalar, P: Problem<T>>(problem: &P, ws: &mut Workspace<T>) -> f64 {
    let n = ws.n;
    for i in 0..n {
        ws.step[i] = ws.x[i] + ws.tangent[i];
    }
    problem.distance(&ws.step[..n], &ws.x)
}

/// Scales the tangent to unit weighted length; returns the length it had.
fn normalize<T: Scalar, P: Problem<T>>(ws: &mut Workspace<T>, problem: &P, lambda_weight: f64) -> f64 {
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
/// other loads, [`Workspace::restore_start`]). Only plain values: the bit
/// comparison sees no derivative parts. Applies only where every factor
/// and the eliminated $\partial_\lambda r$ are finite (where zeros times
/// infinities would make the bordered LU differ).
fn tangent_along_load<T: Scalar>(ws: &mut Workspace<T>) -> bool {
    let n = ws.n;
    let m = n + 1;
    let Workspace { jacobian, dlambda, matrix, tangent, factored, factors, factor_pivots, factors_valid, .. } = ws;
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
fn load_derivative_at_trial<T: Scalar, P: Problem<T>>(problem: &mut P, ws: &mut Workspace<T>) -> bool {
    let n = ws.n;
    let Workspace { trial, trial_residual, jacobian, dlambda, .. } = ws;
    problem.evaluate(&trial[..n], 1.0, &mut trial_residual[..n], Some(jacobian), Some(dlambda)).is_ok()
}

/// The tangent at the state just evaluated (its Jacobian and load
/// derivative in `ws`), oriented along `ws.previous_tangent`:
/// $[\partial_x r,\ \partial_\lambda r;\ t_{prev}^T W]\thinspace t = (0, 1)$.
/// False where that bordered matrix is singular.
fn tangent<T: Scalar, P: Problem<T>>(ws: &mut Workspace<T>, problem: &mut P, lambda_weight: f64) -> bool {
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
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        let mut next = || {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        };
        let mut compared = 0;
        for n in 1..=12 {
            let m = n + 1;
            let mut ws = Workspace::<f64>::new(n);
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
