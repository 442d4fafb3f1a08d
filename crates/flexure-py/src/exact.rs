//! The exact references on a Python `Flexure`, with its section $EI(s)$,
//! rest curvature and length: the elastica (its tip pose, and the stress,
//! curvature and shape along it), the compliance ODE and the column's
//! buckling load. `flexure.exact` wraps them.

use crate::convert::{finite, shape_points, tip_load};
use crate::coordinates::vector;
use crate::errors::to_py;
use crate::interrupt::interruptible;
use crate::joint::Flexure;
use crate::modes::{DEFAULT_COUNT, tip_body};
use crate::strict::Real;
use crate::warnings::warn_unstable;
use crate::{section, stress};
use flexure::FlexureSpec;
use flexure::reference::{column, compliance, elastica, euler, vibration};
use flexure::stress::Peak;
use flexure::{Error, TipConstraint, TipLoad};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::OnceLock;

/// The exact elastica of a flexure under a tip load (paper Eq. 3 with
/// EI(s)), solved by multiple shooting with load continuation.
///
/// Holds the tip pose, the root moment and the stability verdict; the peak
/// stress and curvature and the shape come from the exact shape, which is
/// solved again (deterministically, to the same answer) when first asked for.
#[pyclass(frozen, module = "flexure.exact", name = "Elastica")]
pub struct Elastica {
    flexure: Py<Flexure>,
    load: TipLoad,
    solution: elastica::ElasticaSolution,
    /// The peak stress (`None` without a thickness), once known.
    stress: OnceLock<Option<Peak>>,
    /// The largest change of curvature, once known.
    curvature: OnceLock<Peak>,
}

impl Elastica {
    /// `work` on the exact shape, solved again without the GIL (Ctrl-C stops it).
    fn traced<T: Send>(
        &self,
        py: Python<'_>,
        work: impl FnOnce(&elastica::Trace) -> flexure::Result<T> + Send,
    ) -> PyResult<T> {
        let (f, load) = (&self.flexure.get().inner, self.load);
        interruptible(py, || work(&elastica::deflect_traced(f, &load, &Default::default())?.1))
    }

    fn peak_stress(&self, py: Python<'_>) -> PyResult<Option<Peak>> {
        if let Some(p) = self.stress.get() {
            return Ok(*p);
        }
        let p = self.traced(py, |t| t.peak_stress())?;
        Ok(*self.stress.get_or_init(|| p))
    }
}

#[pymethods]
impl Elastica {
    /// Tip pose [phi, x, y] in the root frame.
    #[getter]
    fn pose<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let p = self.solution.pose;
        PyArray1::from_vec(py, vec![p.phi, p.x, p.y])
    }
    /// Bending moment at the root, M0 = EI(0)(ω(0) − ω0(0)) (N·m).
    #[getter]
    fn root_moment(&self) -> f64 {
        self.solution.root_moment
    }
    /// Whether the shape is a minimum of the potential energy (Jacobi test).
    #[getter]
    fn stable(&self) -> bool {
        self.solution.stable
    }
    /// The load fraction where the loading path first lost stability (snap-through), or None.
    #[getter]
    fn limit_fraction(&self) -> Option<f64> {
        self.solution.limit
    }
    /// `limit_fraction`'s deprecated name.
    #[getter]
    fn limit(&self, py: Python<'_>) -> PyResult<Option<f64>> {
        crate::warnings::deprecated(py, "Elastica.limit", "Elastica.limit_fraction", 1)?;
        Ok(self.solution.limit)
    }
    /// The tip load (moment, fx, fy) in the root frame.
    #[getter]
    fn load(&self) -> (f64, f64, f64) {
        (self.load.moment, self.load.fx, self.load.fy)
    }
    /// The flexure solved.
    #[getter]
    fn flexure(&self, py: Python<'_>) -> Py<Flexure> {
        self.flexure.clone_ref(py)
    }

    /// Peak bending stress σ(s) = E′ h(s)/2 |m(s)|/EI(s): {"max": Pa, "at": m from the root};
    /// None for a flexure given by ei (no thickness).
    fn stress<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        self.peak_stress(py)?.map(|p| stress::peak_dict(py, &p)).transpose()
    }

    /// Largest change of curvature from rest, |m(s)|/EI(s): {"max": 1/m, "at": m}.
    fn peak_curvature<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let p = match self.curvature.get() {
            Some(p) => *p,
            None => {
                let p = self.traced(py, |t| t.peak_curvature())?;
                *self.curvature.get_or_init(|| p)
            }
        };
        stress::peak_dict(py, &p)
    }

    /// Safety factor S/σmax against the flexure's yield strength (inf while unstressed);
    /// below 1 it warns YieldWarning.
    fn safety_factor(&self, py: Python<'_>) -> PyResult<f64> {
        let Some(s) = self.flexure.get().yield_strength else {
            return Err(PyValueError::new_err(
                "safety_factor needs the flexure's yield_strength: build it with Flexure(..., yield_strength=S)",
            ));
        };
        let peak = self.peak_stress(py)?;
        let factor = stress::safety_factor_of(py, peak, s, "Elastica.safety_factor", 1)?;
        Ok(factor.map_or(f64::INFINITY, |(_, f)| f))
    }

    /// The exact shape at k points evenly spaced in arc length, ends included, in the root
    /// frame: a structured array of fields s, x, y, phi, curvature and (with a thickness)
    /// stress, as `Flexure.shape`.
    fn shape<'py>(&self, py: Python<'py>, k: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let count = shape_points(k)?;
        let points = self.traced(py, |t| t.shape(count))?;
        let stressed = self.flexure.get().inner.section().modulus().is_some();
        stress::exact_shape(py, &points, stressed)
    }

    fn __repr__(&self) -> String {
        let (p, l) = (self.solution.pose, self.load);
        format!(
            "Elastica(load=({}, {}, {}), pose=[{}, {}, {}], root_moment={}, stable={})",
            l.moment,
            l.fx,
            l.fy,
            p.phi,
            p.x,
            p.y,
            self.solution.root_moment,
            if self.solution.stable { "True" } else { "False" }
        )
    }
}

/// The exact elastica of `flexure` under a tip load; `what` names the caller in warnings. Warns StabilityWarning when it is
/// unstable, and YieldWarning when the peak stress exceeds the flexure's yield strength;
/// both at stack level 2, the line calling `flexure.exact`'s wrapper.
#[pyfunction]
#[pyo3(signature = (flexure, moment=Real(0.0), fx=Real(0.0), fy=Real(0.0), *, what="exact.elastica"))]
pub fn exact_elastica(
    py: Python<'_>,
    flexure: Bound<'_, Flexure>,
    moment: Real,
    fx: Real,
    fy: Real,
    what: &str,
) -> PyResult<Elastica> {
    let load = tip_load(moment, fx, fy)?;
    let this = flexure.get();
    let (f, strength) = (&this.inner, this.yield_strength);
    let (solution, peak) = interruptible(py, || {
        let (solution, trace) = elastica::deflect_traced(f, &load, &Default::default())?;
        // Known now only when it is needed for the yield warning.
        let peak = if strength.is_some() { Some(trace.peak_stress()?) } else { None };
        Ok((solution, peak))
    })?;
    let p = solution.pose;
    crate::strict::finite_slice(&format!("{what} pose"), &[p.phi, p.x, p.y])?;
    crate::strict::finite_number(&format!("{what} root_moment"), solution.root_moment)?;
    if !solution.stable {
        warn_unstable(py, what, &load, "the elastica fails the Jacobi test", 2)?;
    }
    let stress = OnceLock::new();
    if let Some(peak) = peak {
        if let Some(s) = strength {
            stress::safety_factor_of(py, peak, s, what, 2)?;
        }
        let _ = stress.set(peak);
    }
    Ok(Elastica { flexure: flexure.unbind(), load, solution, stress, curvature: OnceLock::new() })
}

/// Exact tip compliance (3, 3) of `flexure` from the compliance ODE (Eq. 34, with EI(s)), order (phi, x, y).
#[pyfunction]
pub fn exact_compliance<'py>(py: Python<'py>, flexure: &Flexure) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let f = &flexure.inner;
    let c = interruptible(py, || compliance::compliance_tip(f, &Default::default()))?;
    crate::strict::finite_slice("exact.compliance", c.as_slice())?;
    Ok(Array2::from_shape_fn((3, 3), |(i, j)| c[(i, j)]).into_pyarray(py))
}

/// Exact buckling load (N) of `flexure` as a straight column clamped at the root, its tip
/// `tip`: Euler's closed form for a uniform section, shooting on the load for EI(s)
/// (as `flexure buckling --exact`).
#[pyfunction]
#[pyo3(signature = (flexure, tip="free"))]
pub fn exact_buckling_load(py: Python<'_>, flexure: &Flexure, tip: &str) -> PyResult<f64> {
    let f = &flexure.inner;
    let tip: TipConstraint = tip.parse().map_err(to_py)?;
    if f.rest().iter().any(|&k| k != 0.0) {
        let kappa = format!("{:?}", f.rest());
        return Err(to_py(Error::invalid("kappa", kappa, "the exact buckling load is for a straight flexure")));
    }
    let p = if f.section().is_uniform() {
        euler::buckling_load(tip, f.length(), f.ei())
    } else {
        interruptible(py, || column::buckling_load(f, tip, &Default::default()))?
    };
    crate::strict::finite_number("exact.buckling_load", p)
}

/// The flexure `flexure.exact` builds from `length`, `ei` (a number, a pair
/// (root, tip) or a table, as `Flexure`'s) and `kappa` (1 to 64 rest curvature
/// coefficients, any order; straight, order 3, without them), or `rest`, its
/// deprecated name, warned about at `stacklevel` (the caller of `flexure.exact`).
#[pyfunction]
#[pyo3(signature = (length=Real(1.0), ei=None, kappa=None, rest=None, stacklevel=1))]
pub fn exact_flexure(
    py: Python<'_>,
    length: Real,
    ei: Option<&Bound<'_, PyAny>>,
    kappa: Option<&Bound<'_, PyAny>>,
    rest: Option<&Bound<'_, PyAny>>,
    stacklevel: i32,
) -> PyResult<Flexure> {
    let given_kappa = crate::convert::kappa(py, kappa, rest, stacklevel)?;
    let given = section::Arguments {
        ei,
        modulus: None,
        width: None,
        thickness: None,
        poisson: None,
        notch: None,
        density: None,
        mass_per_length: None,
    };
    let section = section::spec(&given)?;
    let (name, kappa) = match given_kappa {
        Some((name, k)) => (name, vector(name, &crate::coordinates::array_like(name, k)?, None)?),
        None => ("kappa", vec![0.0; 3]),
    };
    let max = flexure::flexure::MAX_ORDER;
    if !(1..=max).contains(&kappa.len()) {
        return Err(PyValueError::new_err(format!(
            "{name} must have from 1 to {max} entries (rest curvature coefficients), got {}",
            kappa.len()
        )));
    }
    let spec = FlexureSpec { length: length.0, section, order: kappa.len(), quadrature: None, kappa: Some(kappa) };
    Ok(Flexure { inner: spec.build().map_err(to_py)?, yield_strength: None })
}

/// The exact natural frequencies of `flexure` as a straight Euler–Bernoulli
/// beam with rotary inertia (EI(s), mass per length μ(s), ρI(s)), clamped at
/// its root, carrying an optional tip body, under an axial `compression` (N;
/// negative for tension), counted by Wittrick–Williams and refined on the
/// dynamic stiffness: a dict of omega (rad/s), frequency (Hz), beta_l (the
/// scaled frequency, βL for a uniform beam) and mass_per_length (the reference
/// μ̄ of beta_l, kg/m). A compression at or past the buckling load raises
/// ValueError naming it; Ctrl-C raises KeyboardInterrupt saying how many
/// modes were found.
#[pyfunction]
#[pyo3(signature = (flexure, count=None, compression=0.0, tip_mass=None, tip_inertia=None, tip_com=None))]
pub fn exact_frequencies<'py>(
    py: Python<'py>,
    flexure: &Flexure,
    count: Option<&Bound<'py, PyAny>>,
    compression: f64,
    tip_mass: Option<f64>,
    tip_inertia: Option<f64>,
    tip_com: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let f = &flexure.inner;
    if let Some(k) = f.rest().iter().find(|&&k| k != 0.0) {
        return Err(PyValueError::new_err(format!(
            "invalid kappa: a rest curvature coefficient is {k}: the exact frequencies are those of a straight beam"
        )));
    }
    let compression = finite("compression", compression)?;
    let body = tip_body(tip_mass, tip_inertia, tip_com)?;
    let asked = match count.filter(|c| !c.is_none()) {
        None => DEFAULT_COUNT,
        Some(c) => match crate::convert::count("count", c, 64)? {
            k @ 1..=64 => k,
            k => return Err(PyValueError::new_err(format!("invalid count = {k}: must be from 1 to 64"))),
        },
    };
    // How far an interrupted search got (the fraction of the modes found), and
    // a panic kept from reaching Python (PanicException is no Exception).
    let mut reached = None;
    let search = std::panic::AssertUnwindSafe(|| {
        interruptible(py, || {
            let r = vibration::frequencies(f, body.as_ref(), compression, asked, &Default::default());
            if let Err(flexure::Error::Interrupted { load_fraction }) = &r {
                reached = Some(*load_fraction);
            }
            r
        })
    });
    let v = match std::panic::catch_unwind(search) {
        Ok(Ok(v)) => v,
        Ok(Err(e)) => {
            return Err(match reached {
                Some(fraction) if e.is_instance_of::<PyKeyboardInterrupt>(py) => {
                    let found = (fraction * asked as f64).round();
                    PyKeyboardInterrupt::new_err(format!(
                        "exact.frequencies: interrupted after {found} of {asked} modes"
                    ))
                }
                _ => e,
            });
        }
        Err(_) => {
            return Err(PyRuntimeError::new_err(
                "exact.frequencies: internal error (a panic in the exact vibration reference); please report it with the flexure and arguments",
            ));
        }
    };
    let out = PyDict::new(py);
    out.set_item("omega", PyArray1::from_vec(py, v.omega))?;
    out.set_item("frequency", PyArray1::from_vec(py, v.frequency))?;
    out.set_item("beta_l", PyArray1::from_vec(py, v.scaled))?;
    out.set_item("mass_per_length", v.mass_per_length)?;
    Ok(out)
}
