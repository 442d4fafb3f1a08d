//! What `Flexure(...)` and `SpatialFlexure(...)` share, read once: the
//! order and rest coefficients into the library's [`FlexureSpec`] (the
//! section's arguments are [`crate::section::read`]), and the compliance at
//! rest both give through the library's door to one flexure ([`OneFlexure`]).

use crate::convert::count;
use crate::coordinates::{self, vector};
use crate::errors::to_py;
use crate::strict;
use flexure::FlexureSpec;
use flexure::model::OneFlexure;
use flexure::section::SectionSpec;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;

/// The flexure of `length` and `section`, of `order` (1 to 64, default 3)
/// with the rest coefficients `kappa` (one per order; `kappa.0` names the
/// argument that gave them), for the library to build.
pub fn spec(
    length: f64,
    section: SectionSpec,
    order: Option<&Bound<'_, PyAny>>,
    kappa: Option<(&'static str, &Bound<'_, PyAny>)>,
) -> PyResult<FlexureSpec> {
    let order = order.map(|o| count("order", o, flexure::flexure::MAX_ORDER)).transpose()?.unwrap_or(3);
    let kappa = kappa.map(|(name, k)| rest(name, k, order)).transpose()?;
    Ok(FlexureSpec { length, section, order, quadrature: None, kappa })
}

/// Rest coefficients given as `name`: one per order.
pub fn rest(name: &str, value: &Bound<'_, PyAny>, order: usize) -> PyResult<Vec<f64>> {
    vector(name, &coordinates::array_like(name, value)?, Some(order))
}

/// The tip's compliance at rest, square, as the door gives it (`name`
/// names the method in a non-finite answer's error).
pub fn rest_compliance<'py>(py: Python<'py>, f: OneFlexure, name: &str) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rows = f.compliance(false).map_err(to_py)?.compliance;
    strict::finite_slice(name, &rows.concat())?;
    Ok(array(&rows).into_pyarray(py))
}

/// A matrix given by rows (of equal length), as an array.
pub fn array(rows: &[Vec<f64>]) -> Array2<f64> {
    let columns = rows.first().map_or(0, Vec::len);
    Array2::from_shape_fn((rows.len(), columns), |(i, j)| rows[i][j])
}
