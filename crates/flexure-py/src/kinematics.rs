//! The kinematics of one flexure as NumPy arrays: batch tip poses
//! computed in parallel without the GIL (Eqs. 7, 19–21, 29–31 are answered
//! by `Flexure.pose`, `jacobian`, `hessians` and `transform`).

use crate::coordinates::{self, Coordinates};
use crate::errors::to_py;
use crate::interrupt::{clear_raised, raised_during, signalled};
use crate::strict;
use flexure::kinematics::par_poses_root_tip;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError};
use pyo3::prelude::*;

/// Tip pose [phi, x, y] of `f` for alpha of shape (N,); (n, 3) for shape (n, N), computed in
/// parallel without the GIL, in chunks between which Ctrl-C is polled.
pub fn poses<'py>(py: Python<'py>, f: &flexure::Flexure, alpha: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let (count, rows) = match coordinates::read(f.order(), alpha)? {
        Coordinates::One(a) => {
            let p = <[f64; 3]>::from(flexure::pose_root_tip(f, &a));
            strict::finite_slice("pose", &p)?;
            return Ok(PyArray1::from_slice(py, &p).into_any());
        }
        Coordinates::Many { count, rows } => (count, rows),
    };
    let n = f.order();
    // Written in place: a fresh C-ordered (count, 3) array, one [phi, x, y] row per pose.
    let out = PyArray2::<f64>::zeros(py, [count, 3], false);
    let mut written = out.readwrite();
    let poses = written.as_slice_mut().map_err(|e| PyRuntimeError::new_err(format!("pose: {e}")))?;
    let poses = poses.as_chunks_mut::<3>().0;
    let alphas = rows.as_slice();
    // Chunks of about 2^24 node evaluations (milliseconds), between which Ctrl-C is polled.
    let rows_per_chunk = ((1usize << 24) / (n * f.quadrature_points())).max(1);
    clear_raised();
    let done = py
        .detach(|| {
            let mut done = 0;
            for (a, p) in alphas.chunks(rows_per_chunk * n).zip(poses.chunks_mut(rows_per_chunk)) {
                if signalled() {
                    break;
                }
                par_poses_root_tip(f, a, p)?;
                done += p.len();
            }
            Ok(done)
        })
        .map_err(to_py)?;
    let interrupted = || PyKeyboardInterrupt::new_err(format!("pose: interrupted after {done} of {count} rows"));
    if let Some(err) = raised_during(py, interrupted) {
        return Err(err);
    }
    strict::finite_slice("pose", written.as_slice().unwrap_or(&[]))?;
    drop(written);
    Ok(out.into_any())
}
