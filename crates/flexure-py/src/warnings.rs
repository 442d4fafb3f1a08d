//! The warnings an answer carries: instability, a missed accuracy target,
//! an error that could not be estimated; their numbers written to 3 digits.

use crate::errors::{AccuracyWarning, StabilityWarning};
use flexure::estimate::{self, Accuracy, ErrorEstimate};
use flexure::{Error, TipLoad};
use pyo3::exceptions::PyDeprecationWarning;
use pyo3::prelude::*;

/// Warns `text` as `category` (`stacklevel` 1: the Python line that called the binding).
pub fn warn(py: Python<'_>, category: &Bound<'_, pyo3::types::PyType>, text: String, stacklevel: i32) -> PyResult<()> {
    // Built from fixed text, numbers and names; a NUL in a name is dropped rather than losing the warning.
    let message = std::ffi::CString::new(text.replace('\0', "")).unwrap_or_default();
    PyErr::warn(py, category.as_any(), &message, stacklevel)
}

/// Warns `DeprecationWarning` that the keyword or attribute `old` is deprecated for `new`,
/// the package's one word for it.
pub fn deprecated(py: Python<'_>, old: &str, new: &str, stacklevel: i32) -> PyResult<()> {
    let text = format!("{old} is deprecated: use {new}, its name across the package (the same value)");
    warn(py, &py.get_type::<PyDeprecationWarning>(), text, stacklevel)
}

/// Warns that the equilibrium `solver` found under `load` is unstable, and `why`.
pub fn warn_unstable(py: Python<'_>, solver: &str, load: &TipLoad, why: &str, stacklevel: i32) -> PyResult<()> {
    let (m, fx, fy) = (load.moment, load.fx, load.fy);
    let text = format!("{solver}: the equilibrium under (moment, fx, fy) = ({m}, {fx}, {fy}) is unstable: {why}");
    warn(py, &py.get_type::<StabilityWarning>(), text, stacklevel)
}

/// `x` to 3 significant digits, without trailing zeros; in exponent form when very small or large.
pub fn sig(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let e = x.abs().log10().floor() as i32;
    if !(-4..6).contains(&e) {
        return format!("{x:.2e}");
    }
    let plain = format!("{:.*}", (2 - e).max(0) as usize, x);
    if plain.contains('.') { plain.trim_end_matches('0').trim_end_matches('.').to_string() } else { plain }
}

/// Warns `AccuracyWarning` for each value of `e` that misses `target`:
/// `name(k)` names the value, `reference` the reference model.
#[allow(clippy::too_many_arguments)]
pub fn warn_values(
    py: Python<'_>,
    what: &str,
    e: &estimate::ValueEstimate,
    target: &Accuracy,
    name: impl Fn(usize) -> String,
    reference: &str,
    hint: &str,
    stacklevel: i32,
) -> PyResult<()> {
    if !e.flagged {
        return Ok(());
    }
    let goal = sig(100.0 * target.eigenvalue);
    let parts: Vec<String> = e
        .missed(target)
        .into_iter()
        .map(|k| match e.relative[k] {
            Some(r) => format!("{}: estimated error {} % misses the target of {goal} %", name(k), sig(100.0 * r)),
            None if !e.reference_stable => format!(
                "{}: no estimate, the reference model is unstable under this load (it buckles below it), so the answer is not to be trusted",
                name(k)
            ),
            None => format!("{}: no estimate, the reference model resolves no such mode", name(k)),
        })
        .collect();
    let text = format!("{what}: {} (estimated against {reference}); {hint}", parts.join("; "));
    warn(py, &py.get_type::<AccuracyWarning>(), text, stacklevel)
}

/// Warns that an answer of a flexure of length `length` (m) misses
/// `target` by the estimate `e`; `what` names the answer, `hint` says what
/// to do about it.
pub fn warn_inaccurate(
    py: Python<'_>,
    what: &str,
    length: f64,
    e: &ErrorEstimate,
    target: &Accuracy,
    hint: &str,
    stacklevel: i32,
) -> PyResult<()> {
    let peak = if e.stress.is_some() { "peak stress" } else { "peak curvature" };
    let reference = if e.exact {
        "the exact elastica, order 64 being the highest".to_string()
    } else {
        format!("order {} with {} quadrature points", e.reference_order, e.reference_quadrature)
    };
    let text = format!(
        "{what}: estimated error {} m ({} % of L) in position, {}° in angle and {} % in {peak} misses the target of \
         {} % of L, {}° and {} % (estimated against {reference}); {hint}",
        sig(e.position),
        sig(100.0 * e.position / length),
        sig(e.angle.to_degrees()),
        sig(100.0 * e.peak),
        sig(100.0 * target.position),
        sig(target.angle.to_degrees()),
        sig(100.0 * target.stress),
    );
    warn(py, &py.get_type::<AccuracyWarning>(), text, stacklevel)
}

/// Warns that the error of `what` could not be estimated, and why.
pub fn warn_unestimated(py: Python<'_>, what: &str, why: &Error, stacklevel: i32) -> PyResult<()> {
    let text = format!("{what}: the error could not be estimated, so the answer's accuracy is unknown: {why}");
    warn(py, &py.get_type::<AccuracyWarning>(), text, stacklevel)
}
