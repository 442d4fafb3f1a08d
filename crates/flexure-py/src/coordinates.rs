//! Reading coordinates from Python: every `alpha` and `rest` argument goes
//! through here, so each names itself and says what it expected and got.
//!
//! One configuration is copied onto the stack ([`Row`]); the common forms (a
//! float64 vector, a list or tuple of numbers) skip NumPy's conversion, which
//! costs more than the pose itself. Rows of a C-contiguous
//! float64 array are read in place; other input is converted by NumPy once.

use numpy::{AllowTypeChange, PyArray1, PyArrayLikeDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

/// Orders up to this are held inline; higher ones (rare, and slower to
/// evaluate than an allocation) on the heap. Small, since a row is moved by value.
const INLINE: usize = 8;

/// One configuration: inline up to order [`INLINE`], so reading the usual
/// orders does not allocate.
pub enum Row {
    Inline([f64; INLINE], usize),
    Heap(Vec<f64>),
}

impl Row {
    /// A row of `values`, of which there are `len`.
    fn new(len: usize, values: impl IntoIterator<Item = f64>) -> Self {
        if len > INLINE {
            return Row::Heap(values.into_iter().collect());
        }
        let mut row = [0.0; INLINE];
        let mut count = 0;
        for (slot, v) in row.iter_mut().zip(values) {
            *slot = v;
            count += 1;
        }
        Row::Inline(row, count)
    }
}

impl std::ops::Deref for Row {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        match self {
            Row::Inline(values, len) => &values[..*len],
            Row::Heap(values) => values,
        }
    }
}

/// Rows of coordinates, row after row: borrowed from the caller's array when
/// it is C-contiguous float64, else NumPy's conversion copied once.
pub enum CoordinateRows<'py> {
    Borrowed(PyArrayLikeDyn<'py, f64, AllowTypeChange>),
    Copied(Vec<f64>),
}

impl CoordinateRows<'_> {
    pub fn as_slice(&self) -> &[f64] {
        match self {
            // Only made when `as_slice` succeeds (a C-contiguous array).
            CoordinateRows::Borrowed(a) => a.as_slice().unwrap_or(&[]),
            CoordinateRows::Copied(v) => v,
        }
    }
}

/// `alpha` as read: one configuration, or `count` of them.
pub enum Coordinates<'py> {
    One(Row),
    Many { count: usize, rows: CoordinateRows<'py> },
}

/// Reads `alpha` as an (N,) or (n, N) array of finite values for order `n`.
pub fn read<'py>(n: usize, alpha: &Bound<'py, PyAny>) -> PyResult<Coordinates<'py>> {
    if let Some(row) = fast_row(n, alpha) {
        all_finite("alpha", &row)?;
        return Ok(Coordinates::One(row));
    }
    // Booleans would become 0.0 and 1.0: refused, as for every float argument.
    crate::strict::no_bool("alpha", alpha)?;
    crate::strict::real_array("alpha", alpha)?;
    let array: PyArrayLikeDyn<'py, f64, AllowTypeChange> = alpha.extract().map_err(|e: PyErr| {
        // As pyo3 reports a failed argument conversion.
        if e.is_instance_of::<PyTypeError>(alpha.py()) {
            PyTypeError::new_err(format!("argument 'alpha': {}", e.value(alpha.py())))
        } else {
            e
        }
    })?;
    let shape = array.shape().to_vec();
    let count = match shape.as_slice() {
        [k] if *k == n => None,
        [r, k] if *k == n => Some(*r),
        [k] | [_, k] => {
            return Err(PyValueError::new_err(format!(
                "alpha must have {n} entries per row (the flexure's order), got {k} (shape {shape:?})"
            )));
        }
        _ => {
            return Err(PyValueError::new_err(format!(
                "alpha must have shape ({n},) or (n, {n}) for order {n}, got shape {shape:?}"
            )));
        }
    };
    let Some(count) = count else {
        let row = Row::new(n, array.as_array().iter().copied());
        all_finite("alpha", &row)?;
        return Ok(Coordinates::One(row));
    };
    // `as_slice` takes Fortran order too, which is not row after row.
    let rows = if array.is_c_contiguous() && array.as_slice().is_ok() {
        CoordinateRows::Borrowed(array)
    } else {
        // Not C-contiguous (a transposed or strided view): one copy, in row order.
        CoordinateRows::Copied(array.as_array().iter().copied().collect())
    };
    all_finite("alpha", rows.as_slice())?;
    Ok(Coordinates::Many { count, rows })
}

/// One configuration without NumPy's conversion, when `alpha` is a
/// float64 vector or a list or tuple of `n` numbers; `None` sends
/// anything else (and every error) through the general path.
fn fast_row(n: usize, alpha: &Bound<'_, PyAny>) -> Option<Row> {
    if let Ok(array) = alpha.cast::<PyArray1<f64>>() {
        if array.len() != n {
            return None;
        }
        // Element by element with the GIL held (any strides), as NumPy's own
        // copies do: cheaper than registering a borrow for three numbers.
        let mut values = [0.0; INLINE];
        if n > INLINE {
            return (0..n).map(|i| array.get_owned([i])).collect::<Option<Vec<f64>>>().map(Row::Heap);
        }
        for (i, slot) in values[..n].iter_mut().enumerate() {
            *slot = array.get_owned([i])?;
        }
        return Some(Row::Inline(values, n));
    }
    if let Ok(list) = alpha.cast_exact::<PyList>() {
        numbers(n, list.len(), list.iter())
    } else if let Ok(tuple) = alpha.cast_exact::<PyTuple>() {
        numbers(n, tuple.len(), tuple.iter())
    } else {
        None
    }
}

/// The `len` `items` of a list or tuple as a row, if there are `n` and each is a number.
fn numbers<'py>(n: usize, len: usize, items: impl Iterator<Item = Bound<'py, PyAny>>) -> Option<Row> {
    if len != n {
        return None;
    }
    let mut values = [0.0; INLINE];
    if n > INLINE {
        return items
            .map(|item| if crate::strict::is_bool(&item) { None } else { item.extract::<f64>().ok() })
            .collect::<Option<Vec<f64>>>()
            .map(Row::Heap);
    }
    for (slot, item) in values.iter_mut().zip(items) {
        // A boolean goes the general way, which refuses it.
        if crate::strict::is_bool(&item) {
            return None;
        }
        *slot = item.extract::<f64>().ok()?;
    }
    Some(Row::Inline(values, n))
}

/// Reads `alpha` as one configuration, shape (N,).
pub fn single(n: usize, alpha: &Bound<'_, PyAny>) -> PyResult<Row> {
    match read(n, alpha)? {
        Coordinates::One(row) => Ok(row),
        Coordinates::Many { count, .. } => Err(PyValueError::new_err(format!(
            "alpha must have shape ({n},) here (one configuration), got shape ({count}, {n})"
        ))),
    }
}

/// `value` as a float64 array, converted by NumPy; booleans (items of a
/// list or tuple, or a boolean array) are refused, naming `name`.
pub fn array_like<'py>(name: &str, value: &Bound<'py, PyAny>) -> PyResult<PyArrayLikeDyn<'py, f64, AllowTypeChange>> {
    crate::strict::no_bool(name, value)?;
    crate::strict::real_array(name, value)?;
    value.extract().map_err(|e: PyErr| {
        if e.is_instance_of::<PyTypeError>(value.py()) {
            PyTypeError::new_err(format!("argument '{name}': {}", e.value(value.py())))
        } else {
            e
        }
    })
}

/// Reads `name` as a 1-D array of `expected` finite values (any count if `None`).
pub fn vector(
    name: &str,
    array: &PyArrayLikeDyn<'_, f64, AllowTypeChange>,
    expected: Option<usize>,
) -> PyResult<Vec<f64>> {
    let shape = array.shape().to_vec();
    let got = match shape.as_slice() {
        [k] => *k,
        _ => return Err(PyValueError::new_err(format!("{name} must be one-dimensional, got shape {shape:?}"))),
    };
    if let Some(n) = expected.filter(|&n| n != got) {
        return Err(PyValueError::new_err(format!(
            "{name} must have {n} entries (one per coordinate, the flexure's order), got {got}"
        )));
    }
    let values: Vec<f64> = array.as_array().iter().copied().collect();
    all_finite(name, &values)?;
    Ok(values)
}

/// Refuses a value that is not finite, or (as the library and the CLI do)
/// of magnitude above [`flexure::flexure::MAX_COORDINATE`] (1e6 rad).
fn all_finite(name: &str, values: &[f64]) -> PyResult<()> {
    let max = flexure::flexure::MAX_COORDINATE;
    match values.iter().find(|v| !v.is_finite() || v.abs() > max) {
        Some(v) if !v.is_finite() => {
            Err(PyValueError::new_err(format!("{name} contains {v}: every entry must be a finite number")))
        }
        Some(v) => Err(PyValueError::new_err(format!(
            "{name} contains {v:e}: every entry must be a finite number of magnitude at most {max:e} rad (the library's bound)"
        ))),
        None => Ok(()),
    }
}
