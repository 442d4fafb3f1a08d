//! The `Mechanism` class: a mechanism read from its file, and the analyses
//! it answers; its solve report is `solve.rs`, the others `analyses.rs`.

mod analyses;
mod solve;

use crate::accuracy::eigen_accuracy;
use crate::errors::to_py;
use crate::strict::{self, Real};
use crate::{modes, simulate};
use flexure::mechanism::file::{Report, from_toml, reports};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A mechanism read from a TOML description.
#[pyclass(frozen, module = "flexure")]
pub struct Mechanism {
    inner: flexure::mechanism::Mechanism,
    /// Each flexure joint's `yield_strength` and `shape`, by name.
    reports: Vec<(String, Report)>,
}

#[pymethods]
impl Mechanism {
    /// Parses mechanism TOML text.
    #[staticmethod]
    fn from_text(text: &str) -> PyResult<Self> {
        let inner = from_toml(text).map_err(to_py)?;
        Ok(Self { inner, reports: reports(text).map_err(to_py)? })
    }

    /// Equilibrium as a dict: the library's solve report, as `flexure solve --json` prints it,
    /// with `error_estimate`: the estimated error of each flexure joint (a dict as
    /// `Flexure.error_estimate` returns). A joint that misses `accuracy` warns `AccuracyWarning`;
    /// one whose error could not be estimated warns so and raises, as the CLI fails.
    /// Per flexure joint, by name: `stress` {max, at} (or `curvature_max` for one given by ei),
    /// `safety_factor` for one with `yield_strength` (left out while unstressed; below 1 it warns
    /// `YieldWarning`) and `shape` (a structured array, as `Flexure.shape`) for one with `shape`;
    /// each map left out when empty.
    #[pyo3(signature = (accuracy=None))]
    fn solve<'py>(&self, py: Python<'py>, accuracy: Option<&Bound<'py, PyAny>>) -> PyResult<Bound<'py, PyDict>> {
        let target = crate::accuracy::accuracy(accuracy)?;
        solve::solve(py, &self.inner, &self.reports, &target)
    }

    /// The motion over `duration` (s) as arrays: see `flexure.Mechanism.simulate`.
    #[pyo3(signature = (duration, every=None, tolerance=Real(1e-8), start="equilibrium", max_steps=None))]
    fn simulate<'py>(
        &self,
        py: Python<'py>,
        duration: Real,
        every: Option<Real>,
        tolerance: Real,
        start: &str,
        max_steps: Option<usize>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let out = simulate::motion(py, &self.inner, (duration.0, every.map(|v| v.0)), tolerance.0, start, max_steps)?;
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
        let target = eigen_accuracy(accuracy)?;
        modes::mechanism_modes(py, &self.inner, count, &target)
    }

    /// The mechanism as MJCF, SDFormat or URDF text with its fit report: see `flexure.Mechanism.export`.
    #[pyo3(signature = (to="mjcf", prb="1R", range=None, armature=Real(0.0), name="mechanism"))]
    fn export<'py>(
        &self,
        py: Python<'py>,
        to: &str,
        prb: &str,
        range: Option<&Bound<'py, PyAny>>,
        armature: Real,
        name: &str,
    ) -> PyResult<(String, Bound<'py, PyDict>)> {
        crate::export::export(py, &self.inner, to, prb, range, armature, name)
    }

    /// Linear buckling about the unloaded configuration, as `flexure buckle --json`: see
    /// `flexure.Mechanism.buckle`.
    #[pyo3(signature = (accuracy=None))]
    fn buckle<'py>(&self, py: Python<'py>, accuracy: Option<&Bound<'py, PyAny>>) -> PyResult<Bound<'py, PyDict>> {
        let target = eigen_accuracy(accuracy)?;
        analyses::buckle(py, &self.inner, &target)
    }

    /// Compliance (3, 3), order (phi, x, y), of the frame at `at` (x, y) on `body` at the loaded
    /// equilibrium, as `flexure solve --compliance BODY --at X,Y`.
    fn compliance<'py>(&self, py: Python<'py>, body: &str, at: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        analyses::compliance_at(py, &self.inner, body, at)
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
            (Some(body), Some(at)) => Some((body, at)),
            (None, None) => None,
            _ => {
                return Err(PyValueError::new_err(
                    "compliance and at go together: the body, and the point (x, y) on it whose compliance each row reports",
                ));
            }
        };
        analyses::sweep(py, &self.inner, parameter, values, &target, frame)
    }

    /// Number of generalized coordinates.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof()
    }
}
