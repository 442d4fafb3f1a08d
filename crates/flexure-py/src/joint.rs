//! The `Flexure` class: one flexure joint, its construction from a section,
//! its queries along the length, and the kinematics, statics and analyses it
//! answers (each in the file of its concept).

use crate::accuracy::{auto_order, eigen_accuracy};
use crate::convert::{MatrixPair, along, count, matrix, real, shape_points, tip_load};
use crate::coordinates::single;
use crate::error_estimate::estimate_dict;
use crate::errors::to_py;
use crate::interrupt::interruptible;
use crate::statics::loaded_stiffness;
use crate::strict::{self, Real};
use crate::{analyses, convert, kinematics, modes, one_flexure, section, statics, stress};
use flexure::estimate;
use flexure::{Kinematics, Level, Pose, compliance_tip, energy, update_kinematics};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// A planar flexure joint of the Smooth Curvature Model (SI units, radians).
///
/// Flexure(length, ei, order, quadrature, kappa, *, modulus, width, thickness, poisson,
/// notch, density, mass_per_length, yield_strength). `kappa` holds the rest curvature
/// coefficients κ (`rest`, its deprecated name, warns `DeprecationWarning`; both at once
/// raise `ValueError`). Give `ei` (N·m²), or `modulus` (Pa)
/// with `width` and `thickness` (m) and an optional `poisson`. `ei`, `width`, `thickness`
/// and `mass_per_length` may vary along the flexure, over t = s/L from the root (0) to the
/// tip (1): a number; a pair (root, tip), a linear taper; or a table of [t, value] rows
/// (an (m, 2) array or a list of pairs; t starts at 0, ends at 1 and increases strictly),
/// linear between rows. `notch=(R, h)` cuts two circular cut-outs of radius R centred on
/// the flexure, leaving thickness h at its middle. `density` (kg/m³) or `mass_per_length`
/// (kg/m) gives the mass per length, for dynamics. `yield_strength` S (Pa, with a
/// thickness) gives `safety_factor` S/σmax, and `deflect` warns `YieldWarning` below 1.
///
/// Read-only: `length`, `ei` (the mean for a non-uniform section), `order`, `quadrature`,
/// `kappa`, `modulus` (E′, None without a thickness), `yield_strength`, `uniform`; along
/// the flexure at s (m, a number or an array): `ei_at`, `thickness_at`, `width_at`,
/// `mass_per_length_at`. At coordinates alpha: `stress` {max, at} (None without a
/// thickness), `peak_curvature` {max, at}, `safety_factor`, and `shape(alpha, k)`, a
/// structured array of fields s, x, y, phi, curvature and (with a thickness) stress.
#[pyclass(frozen, module = "flexure")]
pub struct Flexure {
    pub inner: flexure::Flexure,
    /// Yield strength $S$ (Pa), for the safety factor; only with a thickness.
    pub yield_strength: Option<f64>,
}

#[pymethods]
impl Flexure {
    /// Flexure(length=1.0, ei=None, order=3, quadrature=None, kappa=None, *, modulus=None, width=None, thickness=None, poisson=None, notch=None, density=None, mass_per_length=None, yield_strength=None, rest=None)
    #[new]
    #[pyo3(
        signature = (length=Real(1.0), ei=None, order=None, quadrature=None, kappa=None, *, modulus=None, width=None, thickness=None, poisson=None, notch=None, density=None, mass_per_length=None, yield_strength=None, rest=None),
        text_signature = "(length=1.0, ei=None, order=3, quadrature=None, kappa=None, *, modulus=None, width=None, thickness=None, poisson=None, notch=None, density=None, mass_per_length=None, yield_strength=None, rest=None)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        length: Real,
        ei: Option<&Bound<'_, PyAny>>,
        order: Option<&Bound<'_, PyAny>>,
        quadrature: Option<&Bound<'_, PyAny>>,
        kappa: Option<&Bound<'_, PyAny>>,
        modulus: Option<Real>,
        width: Option<&Bound<'_, PyAny>>,
        thickness: Option<&Bound<'_, PyAny>>,
        poisson: Option<Real>,
        notch: Option<&Bound<'_, PyAny>>,
        density: Option<Real>,
        mass_per_length: Option<&Bound<'_, PyAny>>,
        yield_strength: Option<Real>,
        rest: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let kappa = convert::kappa(py, kappa, rest, 1)?;
        let (length, yield_strength) = (length.0, yield_strength.map(|s| s.0));
        let section = section::spec(&section::Arguments {
            ei,
            modulus: modulus.map(|v| v.0),
            width,
            thickness,
            poisson: poisson.map(|v| v.0),
            notch,
            density: density.map(|v| v.0),
            mass_per_length,
        })?;
        let mut spec = one_flexure::spec(length, section, order, kappa)?;
        spec.quadrature = quadrature.map(|q| count("quadrature", q, flexure::quadrature::MAX_POINTS)).transpose()?;
        // The library builds it, as for the CLI and mechanism files, and names what it refuses.
        let f = spec.build().map_err(to_py)?;
        if let Some(s) = yield_strength {
            if !(s.is_finite() && s > 0.0) {
                return Err(PyValueError::new_err(format!(
                    "invalid yield_strength = {s}: must be a finite number greater than zero (Pa)"
                )));
            }
            if f.section().modulus().is_none() {
                return Err(PyValueError::new_err(format!(
                    "invalid yield_strength = {s}: needs a thickness to give a stress: give modulus, width and thickness (a flexure given by ei alone has no stress)"
                )));
            }
        }
        Ok(Self { inner: f, yield_strength })
    }

    /// Length L (m).
    #[getter]
    fn length(&self) -> f64 {
        self.inner.length()
    }
    /// Bending stiffness EI (N·m²); for a non-uniform section, its mean (1/L)∫EI ds.
    #[getter]
    fn ei(&self) -> f64 {
        self.inner.ei()
    }
    /// Order N.
    #[getter]
    fn order(&self) -> usize {
        self.inner.order()
    }
    /// Gauss–Legendre points.
    #[getter]
    fn quadrature(&self) -> usize {
        self.inner.quadrature_points()
    }
    /// Rest curvature coefficients κ, shape (N,).
    #[getter]
    fn kappa<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.inner.rest().to_vec())
    }
    /// Rest curvature coefficients κ, shape (N,): `kappa`'s deprecated name.
    #[getter]
    fn rest<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        crate::warnings::deprecated(py, "Flexure.rest", "Flexure.kappa", 1)?;
        Ok(self.kappa(py))
    }
    /// Effective modulus E′ (Pa; E/(1−ν²) with a Poisson ratio), or None for a flexure given by ei (no stress).
    #[getter]
    fn modulus(&self) -> Option<f64> {
        self.inner.section().modulus()
    }
    /// Yield strength S (Pa), or None.
    #[getter]
    fn yield_strength(&self) -> Option<f64> {
        self.yield_strength
    }
    /// Whether EI is the same all along the flexure.
    #[getter]
    fn uniform(&self) -> bool {
        self.inner.section().is_uniform()
    }

    /// Bending stiffness EI(s) (N·m²) at arc length s (m) from the root: a float, or an array like s.
    fn ei_at<'py>(&self, py: Python<'py>, s: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        along(py, self.inner.length(), s, |s| self.inner.ei_at(s))
    }
    /// Thickness h(s) (m), notch included, at arc length s (m); None for a flexure given by ei.
    fn thickness_at<'py>(&self, py: Python<'py>, s: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let (f, l) = (&self.inner, self.inner.length());
        let section = f.section();
        if section.thickness(0.0, l).is_none() {
            return Ok(None);
        }
        along(py, l, s, |s| section.thickness(s / l, l).unwrap_or(0.0)).map(Some)
    }
    /// Width b(s) (m) at arc length s (m); None for a flexure given by ei.
    fn width_at<'py>(&self, py: Python<'py>, s: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let (f, l) = (&self.inner, self.inner.length());
        let section = f.section();
        if section.width(0.0).is_none() {
            return Ok(None);
        }
        along(py, l, s, |s| section.width(s / l).unwrap_or(0.0)).map(Some)
    }
    /// Mass per length μ(s) (kg/m) at arc length s (m); None without density or mass_per_length.
    fn mass_per_length_at<'py>(&self, py: Python<'py>, s: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let (f, l) = (&self.inner, self.inner.length());
        let section = f.section();
        if section.mass_per_length(0.0, l).is_none() {
            return Ok(None);
        }
        along(py, l, s, |s| section.mass_per_length(s / l, l).unwrap_or(0.0)).map(Some)
    }

    /// Peak bending stress at alpha (N,): {"max": σmax (Pa), "at": s (m from the root)},
    /// σ(s) = E′ h(s)/2 |ω̂(s) − ω̂₀(s)|; None for a flexure given by ei (no thickness).
    fn stress<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let a = single(self.inner.order(), alpha)?;
        let d = flexure::stress::peak_stress(&self.inner, &a).map(|p| stress::peak_dict(py, &p)).transpose()?;
        if let Some(d) = &d {
            strict::finite_answer("stress", d.as_any())?;
        }
        Ok(d)
    }

    /// Largest change of curvature from rest at alpha (N,): {"max": |ω̂ − ω̂₀| (1/m), "at": s (m)}.
    fn peak_curvature<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
        let a = single(self.inner.order(), alpha)?;
        let d = stress::peak_dict(py, &flexure::stress::peak_curvature(&self.inner, &a))?;
        strict::finite_answer("peak_curvature", d.as_any())?;
        Ok(d)
    }

    /// Safety factor S/σmax at alpha (N,) against the yield strength (inf while unstressed);
    /// below 1 it warns YieldWarning naming the yield strength.
    fn safety_factor(&self, py: Python<'_>, alpha: &Bound<'_, PyAny>) -> PyResult<f64> {
        let Some(s) = self.yield_strength else {
            return Err(PyValueError::new_err(
                "safety_factor needs the flexure's yield_strength: build it with Flexure(..., yield_strength=S)",
            ));
        };
        let a = single(self.inner.order(), alpha)?;
        Ok(stress::safety_factor(py, &self.inner, &a, s, "safety_factor", 1)?.map_or(f64::INFINITY, |(_, f)| f))
    }

    /// The deformed flexure at alpha (N,) at k points evenly spaced in arc length, ends included,
    /// in its root frame: a structured array of fields s, x, y, phi (m, m, m, rad), curvature
    /// (1/m, total) and, with a thickness, stress (Pa).
    fn shape<'py>(
        &self,
        py: Python<'py>,
        alpha: &Bound<'py, PyAny>,
        k: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let a = single(self.inner.order(), alpha)?;
        let out = stress::shape(py, &self.inner, &a, shape_points(k)?)?;
        strict::finite_answer("shape", &out)?;
        Ok(out)
    }

    /// Tip pose [phi, x, y] for alpha of shape (N,); (n, 3) for shape (n, N), computed in parallel without the GIL.
    fn pose<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        kinematics::poses(py, &self.inner, alpha)
    }

    /// Jacobian of the tip pose, shape (3, N), rows phi, x, y (Eqs. 19–21).
    fn jacobian<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let a = single(self.inner.order(), alpha)?;
        let mut k = Kinematics::new(&self.inner);
        update_kinematics(&self.inner, &a, &mut k, Level::Jacobian);
        strict::finite_slice("jacobian", k.jacobian_root_tip.as_slice())?;
        Ok(matrix(&k.jacobian_root_tip).into_pyarray(py))
    }

    /// Hessians (Hx, Hy) of the tip's x and y, each (N, N) (Eqs. 30–31).
    fn hessians<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<MatrixPair<'py>> {
        let a = single(self.inner.order(), alpha)?;
        let mut k = Kinematics::new(&self.inner);
        update_kinematics(&self.inner, &a, &mut k, Level::Hessian);
        strict::finite_slice("hessians", k.hessian_root_tip_x.as_slice())?;
        strict::finite_slice("hessians", k.hessian_root_tip_y.as_slice())?;
        Ok((matrix(&k.hessian_root_tip_x).into_pyarray(py), matrix(&k.hessian_root_tip_y).into_pyarray(py)))
    }

    /// Homogeneous transform of the tip in the root frame, (4, 4) (Eq. 7).
    fn transform<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let a = single(self.inner.order(), alpha)?;
        let g = flexure::pose_root_tip(&self.inner, &a).transform();
        strict::finite_slice("transform", g.as_slice())?;
        Ok(Array2::from_shape_fn((4, 4), |(i, j)| g[(i, j)]).into_pyarray(py))
    }

    /// Bending energy U(alpha) in joules (Eq. 9).
    fn energy(&self, alpha: &Bound<'_, PyAny>) -> PyResult<f64> {
        strict::finite_number("energy", energy(&self.inner, &single(self.inner.order(), alpha)?))
    }

    /// Equilibrium coordinates alpha (N,) under a tip moment and force in the root frame (Eq. 22),
    /// with its error estimated against a refined model: a miss of `accuracy` (position as a
    /// fraction of L, angle in rad; default 1 % and 1°) warns `AccuracyWarning`. With
    /// `order="auto"`, raises the order until the target is met and returns `(flexure_used, alpha)`.
    /// With a yield strength, a peak stress beyond it warns `YieldWarning`.
    #[pyo3(signature = (moment=Real(0.0), fx=Real(0.0), fy=Real(0.0), *, accuracy=None, order=None))]
    fn deflect<'py>(
        &self,
        py: Python<'py>,
        moment: Real,
        fx: Real,
        fy: Real,
        accuracy: Option<&Bound<'py, PyAny>>,
        order: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (used, alpha) =
            statics::deflect(py, (&self.inner, self.yield_strength), (moment, fx, fy), accuracy, order)?;
        match used {
            Some(inner) => {
                let used = Py::new(py, Flexure { inner, yield_strength: self.yield_strength })?;
                Ok(PyTuple::new(py, [used.into_any(), alpha.into_any().unbind()])?.into_any())
            }
            None => Ok(alpha.into_any()),
        }
    }

    /// The estimated error of `alpha` as the equilibrium under a tip load, against a refined
    /// model: a dict of position (m), angle (rad), flagged (whether it misses `accuracy`),
    /// reference_order and reference_quadrature.
    #[pyo3(signature = (alpha, moment=Real(0.0), fx=Real(0.0), fy=Real(0.0), accuracy=None))]
    fn error_estimate<'py>(
        &self,
        py: Python<'py>,
        alpha: &Bound<'py, PyAny>,
        moment: Real,
        fx: Real,
        fy: Real,
        accuracy: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let a = single(self.inner.order(), alpha)?;
        let load = tip_load(moment, fx, fy)?;
        let target = crate::accuracy::accuracy(accuracy)?;
        let f = &self.inner;
        let e = interruptible(py, || estimate::deflect_error(f, &load, &a, &target))?;
        let d = estimate_dict(py, &e)?;
        strict::finite_answer("error_estimate", d.as_any())?;
        Ok(d)
    }

    /// Generalized stiffness (N, N) at alpha under a tip load:
    /// K = ∇∇U − Fx∇∇x − Fy∇∇y (Eq. 32; the moment adds nothing, φ_tip being linear in alpha).
    #[pyo3(signature = (alpha, moment=Real(0.0), fx=Real(0.0), fy=Real(0.0)))]
    fn stiffness<'py>(
        &self,
        py: Python<'py>,
        alpha: &Bound<'py, PyAny>,
        moment: Real,
        fx: Real,
        fy: Real,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let load = tip_load(moment, fx, fy)?;
        let (_, k) = loaded_stiffness(&self.inner, &single(self.inner.order(), alpha)?, &load);
        strict::finite_slice("stiffness", k.as_slice())?;
        Ok(matrix(&k).into_pyarray(py))
    }

    /// Tip compliance (3, 3), order (phi, x, y), at alpha under a tip load: C = J K⁻¹ Jᵀ with the
    /// loaded stiffness K of Eq. 32 (Eq. 36 at a loaded equilibrium). At an equilibrium alpha for
    /// that load (from `deflect`) it is the response d(pose)/d(moment, fx, fy) to a small extra load.
    #[pyo3(signature = (alpha, moment=Real(0.0), fx=Real(0.0), fy=Real(0.0)))]
    fn compliance<'py>(
        &self,
        py: Python<'py>,
        alpha: &Bound<'py, PyAny>,
        moment: Real,
        fx: Real,
        fy: Real,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let load = tip_load(moment, fx, fy)?;
        let (k, stiffness) = loaded_stiffness(&self.inner, &single(self.inner.order(), alpha)?, &load);
        let c = compliance_tip(&k, &stiffness).map_err(to_py)?;
        strict::finite_slice("compliance", c.as_slice())?;
        Ok(Array2::from_shape_fn((3, 3), |(i, j)| c[(i, j)]).into_pyarray(py))
    }

    /// Tip compliance (3, 3) of the unloaded flexure at its rest shape (Eqs. 35–36).
    fn rest_compliance<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        one_flexure::rest_compliance(py, self.inner.clone().into(), "rest_compliance")
    }

    /// Vibration modes about the equilibrium under a tip load (moment, fx, fy; Eq. 32's loaded
    /// stiffness, so a frequency falls to zero at a buckling load), with the flexure's mass
    /// (density or mass_per_length) and an optional rigid tip body: tip_mass (kg), tip_inertia
    /// (kg·m² about its centre of mass) and tip_com (x, y) (m, in the tip frame). A dict of
    /// omega (rad/s, ascending), frequency (Hz), shapes (modes, order: each row a mode's
    /// coordinates, vᵀMv = 1) and quasi_static (directions without inertia, condensed out:
    /// a massless flexure's, which have no frequency). count: the lowest modes wanted, 1 to
    /// order (default 3, or the order); fewer are returned if fewer are finite. ValueError
    /// naming `mass` without any mass; ConvergenceError past a buckling load.
    #[pyo3(signature = (count=None, *, tip_mass=None, tip_inertia=None, tip_com=None, moment=Real(0.0), fx=Real(0.0), fy=Real(0.0), accuracy=None))]
    #[allow(clippy::too_many_arguments)]
    fn modes<'py>(
        &self,
        py: Python<'py>,
        count: Option<&Bound<'py, PyAny>>,
        tip_mass: Option<Real>,
        tip_inertia: Option<Real>,
        tip_com: Option<&Bound<'py, PyAny>>,
        moment: Real,
        fx: Real,
        fy: Real,
        accuracy: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let body = modes::tip_body(tip_mass.map(|v| v.0), tip_inertia.map(|v| v.0), tip_com)?;
        let target = eigen_accuracy(accuracy)?;
        modes::flexure_modes(py, &self.inner, count, body, tip_load(moment, fx, fy)?, &target)
    }

    /// Critical compressive tip load (N) under tip constraint "free", "guided", "pinned" or
    /// "clamped", with its error estimated against a refined model (the same load at a higher
    /// order): a miss of `accuracy` (a fraction of the load; default 0.01) warns `AccuracyWarning`.
    #[pyo3(signature = (tip="free", *, accuracy=None))]
    fn buckling_load(&self, py: Python<'_>, tip: &str, accuracy: Option<&Bound<'_, PyAny>>) -> PyResult<f64> {
        statics::buckling_load(py, &self.inner, tip, accuracy)
    }

    /// The tendon-driven joint (Sec. III-D, Eqs. 23–26) under a tendon of `tension` (N, not
    /// negative; `force`, its deprecated name, warns `DeprecationWarning`) attached `root_offset` and `tip_offset` (m) from the neutral axis at the root and
    /// the tip, followed from rest: a dict as `flexure tendon --json` gives it: alpha (N,), pose
    /// [phi, x, y] (an array, as `pose` returns), tendon_length (m), stable, error_estimate (a
    /// dict as `error_estimate` returns, or None where it could not be made) and flagged, stress
    /// {max, at} (or curvature_max for a flexure given by ei), safety_factor with a yield_strength
    /// (left out while unstressed). An unstable answer warns StabilityWarning; a miss of
    /// `accuracy` (as deflect's) warns AccuracyWarning; with `order="auto"` the order is raised
    /// until it is met (order and quadrature then say which). With `limit=True`, also the factor
    /// on the tension, up to `max_factor`, at which the path stops being stable: stability_limit
    /// {factor, status, stalled} (stalled, and a StabilityWarning, if the path could not be
    /// followed that far), as `tendon --limit`.
    #[pyo3(signature = (tension=None, root_offset=None, tip_offset=None, *, accuracy=None, order=None, limit=false, max_factor=Real(analyses::MAX_FACTOR), force=None))]
    #[allow(clippy::too_many_arguments)]
    fn tendon<'py>(
        &self,
        py: Python<'py>,
        tension: Option<Real>,
        root_offset: Option<Real>,
        tip_offset: Option<Real>,
        accuracy: Option<&Bound<'py, PyAny>>,
        order: Option<&Bound<'py, PyAny>>,
        limit: bool,
        max_factor: Real,
        force: Option<Real>,
    ) -> PyResult<Bound<'py, PyDict>> {
        // `tension` is optional only so that `force`, its deprecated name, can stand in for it.
        let (name, tension) = match (tension, force) {
            (Some(_), Some(_)) => {
                return Err(PyValueError::new_err(
                    "tension and force given together: force is tension's deprecated name; give tension alone",
                ));
            }
            (Some(t), None) => ("tension", t),
            (None, Some(f)) => {
                crate::warnings::deprecated(py, "force", "tension", 1)?;
                ("force", f)
            }
            (None, None) => return Err(missing("tension")),
        };
        let tension = real(name, tension)?;
        if tension < 0.0 {
            return Err(PyValueError::new_err(format!(
                "invalid {name} = {tension}: a tendon's tension must not be negative (N)"
            )));
        }
        let t = flexure::tendon::TendonOffsets {
            root_offset: real("root_offset", root_offset.ok_or_else(|| missing("root_offset"))?)?,
            tip_offset: real("tip_offset", tip_offset.ok_or_else(|| missing("tip_offset"))?)?,
        };
        let target = crate::accuracy::accuracy(accuracy)?;
        let auto = auto_order(order)?;
        let limit = limit.then_some(max_factor.0);
        analyses::tendon(py, &self.inner, self.yield_strength, tension, t, &target, auto, limit)
    }

    /// The minimum-energy shape whose tip reaches `pose` = (phi, x, y) in the root frame (rad,
    /// m, m; Sec. II-E, Eq. 16): a dict as `flexure connect --json` gives it: alpha (N,),
    /// energy (J), load {moment, fx, fy}, the tip load that holds the shape, error_estimate
    /// (the largest distance between the answer's backbone and a refined model's) and flagged,
    /// stress (or curvature_max) and safety_factor, as `tendon`'s. A pose out of reach raises
    /// ValueError naming pose; `accuracy`, `order="auto"`, `limit` and `max_factor` as `tendon`'s
    /// (the limit is that of the holding load applied from rest as a dead load). The CLI's
    /// `eta` (the energy against the exact elastica's) is left out: see `flexure.exact`.
    #[pyo3(signature = (pose, *, accuracy=None, order=None, limit=false, max_factor=Real(analyses::MAX_FACTOR)))]
    fn connect<'py>(
        &self,
        py: Python<'py>,
        pose: &Bound<'py, PyAny>,
        accuracy: Option<&Bound<'py, PyAny>>,
        order: Option<&Bound<'py, PyAny>>,
        limit: bool,
        max_factor: Real,
    ) -> PyResult<Bound<'py, PyDict>> {
        let bad = || {
            PyValueError::new_err(format!(
                "invalid pose = {}: must be three finite numbers (phi, x, y), the tip pose in the root frame (rad, m, m)",
                pose.repr().map(|r| r.to_string()).unwrap_or_default()
            ))
        };
        strict::no_bool("pose", pose)?;
        let v: Vec<f64> = pose.extract().map_err(|_| bad())?;
        let [phi, x, y] = v[..] else { return Err(bad()) };
        if !v.iter().all(|v| v.is_finite()) {
            return Err(bad());
        }
        let target = crate::accuracy::accuracy(accuracy)?;
        let auto = auto_order(order)?;
        let limit = limit.then_some(max_factor.0);
        analyses::connect(py, &self.inner, self.yield_strength, Pose { phi, x, y }, &target, auto, limit)
    }

    /// The factor on the tip load (moment, fx, fy) at which the equilibrium followed from rest
    /// stops being stable (a buckling or limit load), as `flexure deflect --limit`'s
    /// stability_limit: {"factor", "status": "lost"}, that factor (stable up to it, unstable
    /// within a relative 1e-10 above), or {"factor", "status": "stable_up_to", "stalled"}, the
    /// bound it stays stable to: `max_factor` (default 1000, stalled None), or as far as the
    /// path could be followed, with stalled (why) and a StabilityWarning. For axial
    /// compression fx = -1 the factor is the free column's buckling load, Euler's pi^2 EI/4L^2.
    #[pyo3(signature = (moment=Real(0.0), fx=Real(0.0), fy=Real(0.0), *, max_factor=Real(analyses::MAX_FACTOR)))]
    fn stability_limit<'py>(
        &self,
        py: Python<'py>,
        moment: Real,
        fx: Real,
        fy: Real,
        max_factor: Real,
    ) -> PyResult<Bound<'py, PyDict>> {
        let load = tip_load(moment, fx, fy)?;
        analyses::stability_limit(py, &self.inner, &load, max_factor.0)
    }

    fn __repr__(&self) -> String {
        format!(
            "Flexure(length={}, ei={}, order={}, quadrature={})",
            self.inner.length(),
            self.inner.ei(),
            self.inner.order(),
            self.inner.quadrature_points()
        )
    }
}

/// The `TypeError` Python raises for a required argument left out, for those
/// optional only so that a deprecated name can stand in for them.
fn missing(name: &str) -> PyErr {
    pyo3::exceptions::PyTypeError::new_err(format!("tendon() missing required argument '{name}'"))
}
