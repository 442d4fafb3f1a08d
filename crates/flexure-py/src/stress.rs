//! What the bindings report of a flexure's bending, as the CLI does: the
//! peak stress `{max (Pa), at (m)}` (or, for a section given by EI alone,
//! the peak change of curvature), the safety factor against a yield
//! strength with `flexure.YieldWarning` below 1, and the deformed shape;
//! of the model at coordinates alpha, or of the exact elastica from its trace.

use flexure::Flexure;
use flexure::reference::elastica::Point;
use flexure::report::{self, MaxAt, ShapePoint};
use flexure::stress::{Peak, peak_stress};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// Most points of a shape: the mechanism files' bound, shared with the CLI.
pub const MAX_SHAPE: usize = flexure::mechanism::file::MAX_SHAPE;

/// A peak as `{"max": value, "at": s}`: the library's [`MaxAt`], as the CLI prints it.
pub fn peak_dict<'py>(py: Python<'py>, p: &Peak) -> PyResult<Bound<'py, PyDict>> {
    crate::serialize::to_dict(py, &MaxAt::from(*p))
}

/// The safety factor $S/\sigma_{max}$ of `f` at `alpha` against the yield
/// strength `s` (Pa), and a `YieldWarning` naming `what` and `s` when it is
/// below 1. `None` when the flexure has no thickness or is unstressed (the
/// factor would be infinite).
pub fn safety_factor(
    py: Python<'_>,
    f: &Flexure,
    alpha: &[f64],
    s: f64,
    what: &str,
    stacklevel: i32,
) -> PyResult<Option<(Peak, f64)>> {
    safety_factor_of(py, peak_stress(f, alpha), s, what, stacklevel)
}

/// The safety factor against the yield strength `s` (Pa) of a peak stress,
/// the model's or the exact elastica's, warning as [`safety_factor`] does.
pub fn safety_factor_of(
    py: Python<'_>,
    peak: Option<Peak>,
    s: f64,
    what: &str,
    stacklevel: i32,
) -> PyResult<Option<(Peak, f64)>> {
    let Some(p) = peak.filter(|p| p.value > 0.0) else {
        return Ok(None);
    };
    let factor = s / p.value;
    if factor < 1.0 {
        let text = format!(
            "{what}: the peak bending stress {:.4e} Pa (at s = {:.4e} m) exceeds the yield strength {s:e} Pa: safety factor {factor:.3}",
            p.value, p.at
        );
        crate::warnings::warn(py, &py.get_type::<crate::errors::YieldWarning>(), text, stacklevel)?;
    }
    Ok(Some((p, factor)))
}

/// The deformed flexure at `count` (2 to [`MAX_SHAPE`], checked by the
/// caller) points evenly spaced in arc length, ends included, in its root
/// frame, as the library gives it ([`flexure::report::shape`]):
/// see [`shape_table`].
pub fn shape<'py>(py: Python<'py>, f: &Flexure, alpha: &[f64], count: usize) -> PyResult<Bound<'py, PyAny>> {
    shape_table(py, &report::shape(f, alpha, count), f.section().modulus().is_some())
}

/// A deformed shape as a NumPy structured array of fields `s, x, y, phi,
/// curvature` (m, m, m, rad, 1/m; the total curvature) and, when `stressed`
/// (the flexure has a thickness), `stress` (Pa).
pub fn shape_table<'py>(py: Python<'py>, points: &[ShapePoint], stressed: bool) -> PyResult<Bound<'py, PyAny>> {
    let column = |g: fn(&ShapePoint) -> f64| points.iter().map(g).collect::<Vec<f64>>();
    let mut columns: Vec<(&str, Vec<f64>)> = vec![
        ("s", column(|p| p.s)),
        ("x", column(|p| p.x)),
        ("y", column(|p| p.y)),
        ("phi", column(|p| p.phi)),
        ("curvature", column(|p| p.curvature)),
    ];
    if stressed {
        columns.push(("stress", column(|p| p.stress.unwrap_or(0.0))));
    }
    table(py, points.len(), columns)
}

/// The exact elastica's cross-sections `points` as the structured array
/// [`shape`] makes of the model's: fields `s, x, y, phi, curvature` and,
/// when `stressed` (the section has a thickness), `stress`.
pub fn exact_shape<'py>(py: Python<'py>, points: &[Point], stressed: bool) -> PyResult<Bound<'py, PyAny>> {
    let points: Vec<ShapePoint> = points
        .iter()
        .map(|p| ShapePoint { s: p.s, x: p.x, y: p.y, phi: p.phi, curvature: p.curvature, stress: p.stress })
        .collect();
    shape_table(py, &points, stressed)
}

/// A NumPy structured array of `n` rows, one float64 field per column.
fn table<'py>(py: Python<'py>, n: usize, columns: Vec<(&str, Vec<f64>)>) -> PyResult<Bound<'py, PyAny>> {
    let dtype = PyList::empty(py);
    for (name, _) in &columns {
        dtype.append((*name, "f8"))?;
    }
    let out = py.import("numpy")?.getattr("empty")?.call1((n, dtype))?;
    for (name, values) in columns {
        out.set_item(name, PyArray1::from_vec(py, values))?;
    }
    Ok(out)
}

/// A peak stress or curvature of `f` at `alpha`, as a dict, when it has one:
/// `stress` with a thickness, else `curvature_max`.
pub fn peak_item<'py>(
    py: Python<'py>,
    f: &flexure::Flexure,
    alpha: &[f64],
) -> PyResult<(&'static str, Bound<'py, PyDict>)> {
    match flexure::stress::peak_stress(f, alpha) {
        Some(p) => Ok(("stress", peak_dict(py, &p)?)),
        None => Ok(("curvature_max", peak_dict(py, &flexure::stress::peak_curvature(f, alpha))?)),
    }
}
