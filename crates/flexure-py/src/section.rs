//! Reading a flexure's cross-section from Python: `ei`, `width`,
//! `thickness` and `mass_per_length` as a number, a pair `(root, tip)` or a
//! table of `[t, value]` rows over $t = s/L$; `notch` as `(radius,
//! min_thickness)`. Every error names the Python parameter and the value it
//! got; the library builds the section and the flexure from them
//! ([`SectionSpec`], [`flexure::FlexureSpec::build`], as for the
//! CLI and mechanism files), checking signs, tables and notch depths, and
//! names them the same way.

use flexure::section::{Notch, Profile, SectionSpec};
use numpy::{PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyString};

/// What the forms of a quantity along the flexure are, for messages.
const FORMS: &str = "a number, a pair (root, tip) for a linear taper, or a table of [t, value] rows with t = s/L \
                     from 0 to 1 (an (m, 2) array or a list of pairs)";

/// `value`'s repr on one line (NumPy's spans several for a table).
fn shown(value: &Bound<'_, PyAny>) -> String {
    let text = value.repr().map(|r| r.to_string()).unwrap_or_else(|_| "an object without repr".into());
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Reads `name` as a number, a pair `(root, tip)` or an (m, 2) table.
pub fn profile(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Profile> {
    // NumPy would read "0.01" as a number: text is a type error, as for any float argument.
    if value.is_instance_of::<PyString>() || value.is_instance_of::<PyBytes>() {
        return Err(PyTypeError::new_err(format!(
            "argument '{name}': expected {FORMS}, got {}",
            value.get_type().name()?
        )));
    }
    crate::strict::no_bool(name, value)?;
    if let Ok(v) = value.extract::<f64>() {
        return Ok(Profile::Constant(finite(name, v)?));
    }
    let bad = |why: String| PyValueError::new_err(format!("{name} must be {FORMS}; got {}: {why}", shown(value)));
    let np = value.py().import("numpy")?;
    // Ragged lists are refused by NumPy (or become an object array): either way, not a profile.
    let array = np.getattr("asarray")?.call1((value,)).map_err(|e| bad(e.value(value.py()).to_string()))?;
    let kind: String = array.getattr("dtype")?.getattr("kind")?.extract()?;
    if !"iuf".contains(kind.as_str()) || kind.len() != 1 {
        return Err(bad(format!("its entries are not all numbers (NumPy dtype kind '{kind}')")));
    }
    let array = array.call_method1("astype", ("float64",))?;
    let array = array.cast::<PyArrayDyn<f64>>().map_err(|e| bad(e.to_string()))?;
    let shape = array.shape().to_vec();
    let values: Vec<f64> = array.readonly().as_array().iter().copied().collect();
    if let Some(v) = values.iter().find(|v| !v.is_finite()) {
        return Err(PyValueError::new_err(format!("{name} contains {v}: every entry must be a finite number")));
    }
    match shape[..] {
        [] => Ok(Profile::Constant(values[0])),
        [2] => Ok(Profile::Linear { root: values[0], tip: values[1] }),
        [_, 2] => Ok(Profile::Table(values.chunks_exact(2).map(|p| [p[0], p[1]]).collect())),
        [k] => Err(bad(format!("{k} values (shape ({k},)); a taper has two, (root, tip)"))),
        [m, k] => Err(bad(format!("a table's rows must be [t, value] pairs, got shape ({m}, {k})"))),
        _ => {
            let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
            Err(bad(format!("shape ({}) has too many dimensions", dims.join(", "))))
        }
    }
}

/// `p` as [`profile`] reads it: a float, a tuple `(root, tip)` or an
/// (m, 2) array of `[t, value]` rows.
pub fn profile_object<'py>(py: Python<'py>, p: &Profile) -> PyResult<Bound<'py, PyAny>> {
    match p {
        Profile::Constant(v) => Ok(v.into_pyobject(py)?.into_any()),
        Profile::Linear { root, tip } => Ok((*root, *tip).into_pyobject(py)?.into_any()),
        Profile::Table(rows) => {
            let table = numpy::ndarray::Array2::from_shape_fn((rows.len(), 2), |(i, j)| rows[i][j]);
            Ok(numpy::IntoPyArray::into_pyarray(table, py).into_any())
        }
    }
}

/// Reads `notch` as `(radius, min_thickness)` in metres.
fn notch(value: &Bound<'_, PyAny>) -> PyResult<Notch> {
    let bad = || {
        PyValueError::new_err(format!(
            "notch must be a pair (radius, min_thickness) in m: two circular cut-outs of that radius centred on \
             the flexure, leaving min_thickness at its middle; got {}",
            shown(value)
        ))
    };
    if value.is_instance_of::<PyString>() || value.is_instance_of::<PyBytes>() {
        return Err(bad());
    }
    crate::strict::no_bool("notch", value)?;
    let pair: Vec<f64> = value.extract().map_err(|_| bad())?;
    let [radius, min_thickness] = pair[..] else {
        return Err(bad());
    };
    Ok(Notch { radius: finite("notch radius", radius)?, min_thickness: finite("notch min_thickness", min_thickness)? })
}

fn finite(name: &str, v: f64) -> PyResult<f64> {
    if v.is_finite() { Ok(v) } else { Err(PyValueError::new_err(format!("{name} = {v}: must be a finite number"))) }
}

/// The section arguments of `Flexure(...)` (and those `SpatialFlexure(...)`
/// shares), each `None` when not given.
pub struct Arguments<'a, 'py> {
    pub ei: Option<&'a Bound<'py, PyAny>>,
    pub modulus: Option<f64>,
    pub width: Option<&'a Bound<'py, PyAny>>,
    pub thickness: Option<&'a Bound<'py, PyAny>>,
    pub poisson: Option<f64>,
    pub notch: Option<&'a Bound<'py, PyAny>>,
    pub density: Option<f64>,
    pub mass_per_length: Option<&'a Bound<'py, PyAny>>,
}

/// The section arguments read into the library's [`SectionSpec`], after the
/// checks whose messages speak Python (which arguments go together).
pub fn spec(a: &Arguments<'_, '_>) -> PyResult<SectionSpec> {
    match (a.ei, a.modulus) {
        (Some(_), Some(_)) => {
            return Err(PyValueError::new_err(
                "ei and modulus were both given: give ei, or modulus with width and thickness, not both",
            ));
        }
        (_, None) => {
            // Section options only count with a modulus: refuse them rather than ignore them.
            let unused: Vec<&str> = [
                ("width", a.width.is_some()),
                ("thickness", a.thickness.is_some()),
                ("poisson", a.poisson.is_some()),
                ("notch", a.notch.is_some()),
            ]
            .into_iter()
            .filter_map(|(name, given)| given.then_some(name))
            .collect();
            if !unused.is_empty() {
                return Err(PyValueError::new_err(format!(
                    "{} given without modulus would be ignored: give modulus (with width and thickness) to compute ei from the section, or leave them out",
                    unused.join(", ")
                )));
            }
        }
        (None, Some(_)) => {
            if a.width.is_none() || a.thickness.is_none() {
                let missing = match (a.width, a.thickness) {
                    (None, None) => "width and thickness",
                    (None, _) => "width",
                    _ => "thickness",
                };
                return Err(PyValueError::new_err(format!("modulus needs width and thickness: {missing} missing")));
            }
        }
    }
    if let (Some(rho), Some(_)) = (a.density, a.mass_per_length) {
        return Err(PyValueError::new_err(format!(
            "density = {rho} and mass_per_length were both given: give one (density with width and thickness, or mass_per_length)"
        )));
    }
    read(a)
}

/// The section arguments read, as they are, into the library's
/// [`SectionSpec`]: what `Flexure(...)` and `SpatialFlexure(...)` share.
pub fn read(a: &Arguments<'_, '_>) -> PyResult<SectionSpec> {
    let read = |name: &str, v: Option<&Bound<'_, PyAny>>| v.map(|v| profile(name, v)).transpose();
    Ok(SectionSpec {
        ei: read("ei", a.ei)?,
        modulus: a.modulus,
        width: read("width", a.width)?,
        thickness: read("thickness", a.thickness)?,
        poisson: a.poisson,
        notch: a.notch.map(notch).transpose()?,
        density: a.density,
        mass_per_length: read("mass_per_length", a.mass_per_length)?,
    })
}
