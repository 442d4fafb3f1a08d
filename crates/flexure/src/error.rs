//! The one error type of the library.
//!
//! Every variant says what was reached, in named units, and what to try.

/// Everything that can go wrong: bad input (named, with the value received),
/// and numerical failure (reported with what was reached, never hidden).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A parameter is out of its domain.
    #[error("invalid {}: {reason}", assignment(name, value))]
    InvalidParameter {
        /// The parameter's name, as the CLI and Python bindings spell it.
        name: &'static str,
        /// The value received, formatted.
        value: String,
        /// What the parameter must satisfy.
        reason: &'static str,
    },
    /// An iterative solver stopped at its iteration limit (or on a
    /// non-finite residual) before meeting its tolerance. (Messages name
    /// what was reached, not settings to change: each front end offers its
    /// own, and a Rust caller has `Settings`.)
    #[error(
        "{solver} did not converge: {iterations} iterations reached a residual of {residual:.3e} {unit}; check that the problem has a solution"
    )]
    NoConvergence {
        /// Which solver.
        solver: &'static str,
        /// Iterations spent.
        iterations: usize,
        /// The last residual.
        residual: f64,
        /// The residual's unit (for example "N·m" or "relative").
        unit: &'static str,
    },
    /// Load continuation could not advance: its step fell below the
    /// smallest allowed step, or it ran out of steps. When the last step's
    /// corrector stopped at rounding (`rounding`), the state reached is an
    /// equilibrium and the message says so: it is the step that could not
    /// advance, not a residual that would not fall.
    #[error(
        "{solver}: load continuation stalled at {pct:.4} % of the load after {steps} steps {how}",
        pct = .load_fraction * 100.0,
        how = stalled_how(.cause, *.residual, .unit, *.rounding)
    )]
    ContinuationStalled {
        /// Why the last step failed: the corrector's non-convergence, a
        /// state that cannot be evaluated (for example a tendon of zero
        /// length), a step that turned too far, or the step limit.
        cause: String,
        /// Whether the last step's corrector came to within rounding of its
        /// tolerance (10 times it) and could get no closer: the load is
        /// then many orders beyond what the stiffness carries at this scale
        /// (often a unit slip), or the path turns there.
        rounding: bool,
        /// Which problem.
        solver: &'static str,
        /// Fraction of the load reached (0 to 1).
        load_fraction: f64,
        /// Accepted continuation steps.
        steps: usize,
        /// The last residual.
        residual: f64,
        /// The residual's unit.
        unit: &'static str,
    },
    /// Followed from rest, the equilibrium stops being stable: past a
    /// buckling or limit load, where no stable equilibrium is within reach.
    #[error(
        "{what}: the loading path loses stability at {pct:.4} % of the load (a buckling or limit load); no stable equilibrium is reachable beyond it by loading; try a load below that fraction",
        pct = .load_fraction * 100.0
    )]
    Unstable {
        /// Which problem.
        what: &'static str,
        /// Fraction of the load (0 to 1) at which stability is lost.
        load_fraction: f64,
    },
    /// The caller's interrupt check asked the solver to stop.
    #[error("interrupted at {pct:.4} % of the load", pct = .load_fraction * 100.0)]
    Interrupted {
        /// Fraction of the load reached.
        load_fraction: f64,
    },
    /// The caller's interrupt check asked the time integration to stop.
    #[error("interrupted at t = {time:.6e} s of {duration:.6e} s")]
    InterruptedAt {
        /// Time reached (s).
        time: f64,
        /// The duration asked for (s).
        duration: f64,
    },
    /// A mechanism file is malformed or inconsistent, at `place` (line and column).
    #[error("{place}: {message}")]
    File {
        /// "line L, column C".
        place: String,
        /// What is wrong there.
        message: String,
    },
    /// A matrix that must be positive definite or invertible is not.
    #[error("{what}")]
    Singular {
        /// What failed and why.
        what: String,
    },
    /// Time integration could not advance: its step fell to rounding, or
    /// it ran out of steps or of retries of one step.
    #[error(
        "time integration stalled at t = {time:.6e} s of {duration:.6e} s after {steps} steps and {rejected} rejected (step {step:.3e} s; last: {cause}); try a looser tolerance, or check that the motion stays where the model holds"
    )]
    IntegrationStalled {
        /// Why the last step failed.
        cause: String,
        /// Time reached (s).
        time: f64,
        /// The duration asked for (s).
        duration: f64,
        /// Accepted steps.
        steps: usize,
        /// Rejected steps.
        rejected: usize,
        /// The last step tried (s).
        step: f64,
    },
}

/// The rest of a [`Error::ContinuationStalled`] message: what was reached,
/// why the last step failed, and the advice that fits.
fn stalled_how(cause: &str, residual: f64, unit: &str, rounding: bool) -> String {
    if rounding {
        format!(
            "(last: {cause}): the state reached is in equilibrium, but no load step beyond it could be taken at double precision; the load is far beyond what the stiffness carries, or the path turns back there (a limit point): check the units (a modulus in Pa, lengths in metres), or try a smaller load"
        )
    } else {
        format!(
            "({}; last: {cause}); the load may be beyond what the solver can follow; try a smaller load",
            residual_reached(residual, unit)
        )
    }
}

/// "residual R unit", or, when no state tried could be evaluated to a
/// finite residual, that said in words (never "residual NaN").
fn residual_reached(residual: f64, unit: &str) -> String {
    if residual.is_finite() {
        format!("residual {residual:.3e} {unit}")
    } else {
        "no state tried could be evaluated to a finite residual".into()
    }
}

/// The library's result type.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// An [`Error::InvalidParameter`] for `name`, showing `value`.
    pub fn invalid(name: &'static str, value: impl std::fmt::Display, reason: &'static str) -> Self {
        // A number whose plain decimals run long (1e308, 5e-324) is shown
        // with an exponent, in the shortest form that reads back to it.
        let text = value.to_string();
        let value = match text.parse::<f64>() {
            Ok(x) if text.len() > 20 && x.is_finite() => format!("{x:e}"),
            _ => text,
        };
        Error::InvalidParameter { name, value, reason }
    }

    /// The same error placed at a mechanism's joint: a [`Error::Singular`]
    /// says which joint it is about; other kinds name their parameter already.
    ///
    /// # Example
    /// ```
    /// use flexure::Error;
    /// let e = Error::Singular { what: "no mass".into() }.in_joint("mcp");
    /// assert_eq!(e, Error::Singular { what: "joint \"mcp\": no mass".into() });
    /// ```
    pub fn in_joint(self, joint: &str) -> Self {
        match self {
            Error::Singular { what } => Error::Singular { what: format!("joint {joint:?}: {what}") },
            other => other,
        }
    }
}

/// Checks that `value` is finite, naming it otherwise.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() { Ok(value) } else { Err(Error::invalid(name, value, "must be a finite number")) }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(name, value, "must be a finite number greater than zero"))
    }
}

/// Checks that a count lies in `1..=max`.
pub(crate) fn count(name: &'static str, value: usize, max: usize, reason: &'static str) -> Result<usize> {
    if (1..=max).contains(&value) { Ok(value) } else { Err(Error::invalid(name, value, reason)) }
}

/// `name = value`, or the value alone where it names itself (`geom "floor"
/// (plane) and flexure "strip"`: a pair of parts, not a value given to a
/// parameter `geom`).
///
/// # Example
/// ```
/// use flexure::error::assignment;
/// assert_eq!(assignment("radius", "-1"), "radius = -1");
/// assert_eq!(assignment("geom", "geom \"floor\" (plane)"), "geom \"floor\" (plane)");
/// ```
pub fn assignment(name: &str, value: &str) -> String {
    match names_itself(name, value) {
        true => value.to_string(),
        false => format!("{name} = {value}"),
    }
}

/// Whether `value` begins with the parameter's own `name` and a space: it
/// names what it is about, and is shown alone ([`assignment`]).
///
/// # Example
/// ```
/// use flexure::error::names_itself;
/// assert!(names_itself("geom", "geom \"floor\" (plane)") && !names_itself("geom", "geoms"));
/// ```
pub fn names_itself(name: &str, value: &str) -> bool {
    value.strip_prefix(name).is_some_and(|rest| rest.starts_with(' '))
}
