//! The `Mechanism` class: a mechanism read from its file, planar or spatial
//! (`dimension = 3`), as the door `flexure::model::Model`, and the analyses
//! it answers, each written once for both dimensions through the door:
//! `solve.rs`, `sweep.rs`, `buckle` and `modes` (`eigen.rs`), `compliance`
//! (`frame.rs`), `simulate` (`crate::simulate`) and `export` (`crate::export`,
//! MJCF only for a spatial file).

mod eigen;
mod frame;
mod solve;
mod sweep;

use crate::accuracy::eigen_accuracy;
use crate::errors::to_py;
use crate::simulate;
use crate::strict::{self, Real};
use flexure::model::Model;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A mechanism read from a TOML description, planar or spatial (`dimension = 3`).
#[pyclass(frozen, module = "flexure")]
pub struct Mechanism {
    model: Model,
}

impl Mechanism {
    /// The frame named by `body` and the point `at` on it (its origin when
    /// `None`), of the mechanism's dimension ([`frame::point`]).
    fn frame(&self, body: &str, at: Option<&Bound<'_, PyAny>>) -> PyResult<(usize, Vec<f64>)> {
        Ok((frame::body_named(&self.model, body)?, frame::point(at, self.model.dimension())?))
    }
}

#[pymethods]
impl Mechanism {
    /// Parses mechanism TOML text, planar or spatial (`dimension = 3`).
    #[staticmethod]
    fn from_text(text: &str) -> PyResult<Self> {
        Ok(Self { model: Model::from_toml(text).map_err(to_py)? })
    }

    /// Equilibrium as a dict: the library's solve report, as `flexure solve --json` prints it,
    /// with `error_estimate`: the estimated error of each flexure joint (a dict as
    /// `Flexure.error_estimate` returns). A joint that misses `accuracy` warns `AccuracyWarning`;
    /// one whose error could not be estimated warns so and raises, as the CLI fails.
    /// Per flexure joint, by name: `stress` {max, at} (or `curvature_max` for one given by ei),
    /// `safety_factor` for one with `yield_strength` (left out while unstressed; below 1 it warns
    /// `YieldWarning`) and `shape` (a structured array, as `Flexure.shape`) for one with `shape`;
    /// each map left out when empty.
    /// With `limit`, `stability_limit` as `flexure solve --limit`.
    #[pyo3(signature = (accuracy=None, limit=false))]
    fn solve<'py>(
        &self,
        py: Python<'py>,
        accuracy: Option<&Bound<'py, PyAny>>,
        limit: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let target = crate::accuracy::accuracy(accuracy)?;
        solve::solve(py, &self.model, &target, limit)
    }

    /// The motion over `duration` (s) as arrays: see `flexure.Mechanism.simulate`.
    #[pyo3(signature = (duration, every=None, tolerance=Real(1e-8), start="equilibrium", max_steps=None, accuracy=None))]
    #[allow(clippy::too_many_arguments)] // Python's keywords, each its own argument
    fn simulate<'py>(
        &self,
        py: Python<'py>,
        duration: Real,
        every: Option<Real>,
        tolerance: Real,
        start: &str,
        max_steps: Option<strict::Whole>,
        accuracy: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let times = (duration.0, every.map(|v| v.0));
        let target = crate::accuracy::accuracy(accuracy)?;
        let out = simulate::motion(py, &self.model, times, tolerance.0, (start, max_steps.map(|m| m.0)), &target)?;
        strict::finite_answer("Mechanism.simulate", out.as_any())?;
        Ok(out)
    }

    /// Vibration modes about the loaded equilibrium, closures respected: a dict of omega
    /// (rad/s, ascending), frequency (Hz), shapes {joint: array (modes, joint coordinates)}
    /// and quasi_static, as `Mechanism.modes` documents.
    #[pyo3(signature = (count=None, accuracy=None))]
    fn modes<'py>(
        &self,
        py: Python<'py>,
        count: Option<&Bound<'py, PyAny>>,
        accuracy: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        eigen::modes(py, &self.model, count, &eigen_accuracy(accuracy)?)
    }

    /// The mechanism as MJCF, SDFormat or URDF text with its fit report: see `flexure.Mechanism.export`.
    #[pyo3(signature = (to="mjcf", prb="3R", range=None, armature=Real(0.0), step=Real(0.002), name="mechanism"))]
    #[allow(clippy::too_many_arguments)]
    fn export<'py>(
        &self,
        py: Python<'py>,
        to: &str,
        prb: &str,
        range: Option<&Bound<'py, PyAny>>,
        armature: Real,
        step: Real,
        name: &str,
    ) -> PyResult<(String, Bound<'py, PyDict>)> {
        crate::export::export(py, &self.model, to, prb, range, armature, step, name)
    }

    /// Linear buckling about the unloaded configuration, as `flexure buckle --json`: see
    /// `flexure.Mechanism.buckle`.
    #[pyo3(signature = (accuracy=None))]
    fn buckle<'py>(&self, py: Python<'py>, accuracy: Option<&Bound<'py, PyAny>>) -> PyResult<Bound<'py, PyDict>> {
        eigen::buckle(py, &self.model, &eigen_accuracy(accuracy)?)
    }

    /// Compliance (3, 3), order (phi, x, y), of the frame at `at` (x, y; default the origin) on
    /// `body` at the loaded equilibrium, as `flexure solve --compliance BODY --at X,Y`; of a
    /// spatial mechanism (6, 6), order (rx, ry, rz, x, y, z), at `at` (x, y, z).
    #[pyo3(signature = (body, at=None))]
    fn compliance<'py>(
        &self,
        py: Python<'py>,
        body: &str,
        at: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        frame::body_named(&self.model, body)?;
        let at = frame::point(at, self.model.dimension())?;
        let c = crate::interrupt::interruptible(py, || self.model.compliance(body, &at))?;
        let out = numpy::ndarray::Array2::from_shape_fn((c.nrows(), c.ncols()), |(i, j)| c[(i, j)]);
        let out = numpy::IntoPyArray::into_pyarray(out, py).into_any();
        crate::strict::finite_answer("Mechanism.compliance", &out)?;
        Ok(out)
    }

    /// Equilibria along `values` of one load, as `flexure solve --sweep`: see `flexure.Mechanism.sweep`.
    #[pyo3(signature = (parameter, values, accuracy=None, compliance=None, at=None))]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        parameter: &str,
        values: &Bound<'py, PyAny>,
        accuracy: Option<&Bound<'py, PyAny>>,
        compliance: Option<&str>,
        at: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let target = crate::accuracy::accuracy(accuracy)?;
        let frame = match (compliance, at) {
            (Some(body), at) => Some((body, self.frame(body, at)?.1)),
            (None, None) => None,
            (None, Some(_)) => {
                return Err(PyValueError::new_err(
                    "at is given without compliance: at is the point on the body named by compliance whose compliance each row reports",
                ));
            }
        };
        sweep::sweep(py, &self.model, parameter, values, &target, frame)
    }

    /// Number of generalized coordinates.
    #[getter]
    fn dof(&self) -> usize {
        self.model.dof()
    }

    /// 2 for a planar mechanism, 3 for a spatial one (`dimension = 3` in its file).
    #[getter]
    fn dimension(&self) -> u8 {
        self.model.dimension()
    }
}
