//! The one error type of the library.

/// Everything that can go wrong: bad input (named, with the value received),
/// and numerical failure (reported with its residual, never hidden).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A parameter is out of its domain.
    #[error("invalid {name} = {value}: {reason}")]
    InvalidParameter {
        /// The parameter's name, as the CLI and Python bindings spell it.
        name: &'static str,
        /// The value received, formatted.
        value: String,
        /// What the parameter must satisfy.
        reason: &'static str,
    },
    /// An iterative solver stopped before meeting its tolerance.
    #[error("{solver} did not converge after {iterations} iterations: residual {residual:.3e}")]
    NoConvergence {
        /// Which solver.
        solver: &'static str,
        /// Iterations (or continuation steps) spent.
        iterations: usize,
        /// The last residual, in the solver's own units.
        residual: f64,
    },
    /// Followed from rest, the equilibrium stops being stable: past a
    /// buckling or limit load, where no stable equilibrium is within reach.
    #[error(
        "{what}: the loading path loses stability at {pct:.1} % of the load (past a buckling or limit load there is no stable equilibrium); residual {residual:.3e}",
        pct = .load_fraction * 100.0
    )]
    Unstable {
        /// Which problem.
        what: &'static str,
        /// Fraction of the load at the first unstable step.
        load_fraction: f64,
        /// The KKT residual there.
        residual: f64,
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
}

/// The library's result type.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// An [`Error::InvalidParameter`] for `name`, showing `value`.
    pub fn invalid(name: &'static str, value: impl std::fmt::Display, reason: &'static str) -> Self {
        Error::InvalidParameter { name, value: value.to_string(), reason }
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
