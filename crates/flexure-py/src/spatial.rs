//! The `SpatialFlexure` class: a spatial flexure joint, two bendings and a
//! twist in SE(3) (issue 23), built by the library's `SpatialSpec` as the
//! CLI's `--spatial` builds it.

use crate::coordinates::{self, Coordinates, single, vector};
use crate::error_estimate::estimate_dict;
use crate::errors::{AccuracyWarning, StabilityWarning, to_py};
use crate::section::{profile, profile_object};
use crate::strict::{self, Real};
use crate::warnings::{sig, warn};
use crate::{one_flexure, section};
use flexure::estimate::Accuracy;
use flexure::model::{Deflect, OneFlexure, SpatialKeys};
use flexure::section::Profile;
use flexure::spatial::{self, MassQuadrature, SpatialLoad, StabilityTest};
use nalgebra::{Matrix3, Vector3};
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray2, PyArray3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A spatial flexure joint: a Kirchhoff rod (inextensible, unshearable) whose body-frame
/// curvature (twist, κ_y, κ_z) is a shifted-Legendre series per component (SI units, radians).
///
/// SpatialFlexure(length, ei, order, *, ei_y, gj, modulus, width, thickness, diameter,
/// poisson, shear_modulus, kappa, kappa_y, twist). Give the stiffnesses `ei` (EI_z, the planar
/// flexure's in-plane bending), `ei_y` and `gj` (N·m², each a number, a (root, tip) pair or
/// an (m, 2) table over t = s/L; `ei_y` and `gj` default to `ei`), or `modulus` (Pa) with a
/// strip's `width` (along z) and `thickness` (along y) or a rod's `diameter`, and `poisson`
/// (default 0.3) or `shear_modulus` for G. `order` is each component's number of
/// coefficients (default 3); coordinates are listed twist's, then κ_y's, then κ_z's.
/// `kappa`, `kappa_y` and `twist` are the rest coefficients of each component.
/// The flexure's own mass, as a mechanism file's keys give it: `density` (kg/m³, with a
/// rectangle's or circle's geometry: μ = ρA) or `mass_per_length` (kg/m, a number, pair or
/// table as `ei`), not both; `mass()` is its total. With `mass_per_length`,
/// `rotary_inertia_per_length` (kg·m, three numbers: twist, bending about y, about z) gives
/// the section's rotary inertia directly, as the file key of that name does.
#[pyclass(frozen, module = "flexure")]
pub struct SpatialFlexure {
    inner: flexure::spatial::SpatialFlexure,
    /// The `density` given (kg/m³), for its property.
    density: Option<f64>,
    /// The `mass_per_length` given (kg/m), for its property.
    mass_per_length: Option<Profile>,
    /// The `rotary_inertia_per_length` given (kg·m), for its property.
    rotary_inertia_per_length: Option<[f64; 3]>,
}

/// A rotation and position as a 4 × 4 homogeneous transform.
fn transform(r: &Matrix3<f64>, p: &Vector3<f64>) -> [[f64; 4]; 4] {
    let mut g = [[0.0; 4]; 4];
    for i in 0..3 {
        for j in 0..3 {
            g[i][j] = r[(i, j)];
        }
        g[i][3] = p[i];
    }
    g[3][3] = 1.0;
    g
}

/// A 3-vector argument (`force`, `moment`): three finite numbers, the `entries` named in its error.
fn triple(name: &str, entries: &str, value: Option<&Bound<'_, PyAny>>) -> PyResult<[f64; 3]> {
    let Some(v) = value else { return Ok([0.0; 3]) };
    let values = vector(name, &coordinates::array_like(name, v)?, None)?;
    <[f64; 3]>::try_from(values.as_slice()).map_err(|_| {
        pyo3::exceptions::PyValueError::new_err(format!("{name} must have 3 entries ({entries}), got {}", values.len()))
    })
}

#[pymethods]
impl SpatialFlexure {
    /// SpatialFlexure(length=1.0, ei=None, order=3, *, ei_y=None, gj=None, modulus=None, width=None, thickness=None, diameter=None, poisson=None, shear_modulus=None, kappa=None, kappa_y=None, twist=None, density=None, mass_per_length=None, rotary_inertia_per_length=None)
    #[new]
    #[pyo3(signature = (length=Real(1.0), ei=None, order=None, *, ei_y=None, gj=None, modulus=None, width=None, thickness=None, diameter=None, poisson=None, shear_modulus=None, kappa=None, kappa_y=None, twist=None, density=None, mass_per_length=None, rotary_inertia_per_length=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        length: Real,
        ei: Option<&Bound<'_, PyAny>>,
        order: Option<&Bound<'_, PyAny>>,
        ei_y: Option<&Bound<'_, PyAny>>,
        gj: Option<&Bound<'_, PyAny>>,
        modulus: Option<Real>,
        width: Option<&Bound<'_, PyAny>>,
        thickness: Option<&Bound<'_, PyAny>>,
        diameter: Option<&Bound<'_, PyAny>>,
        poisson: Option<Real>,
        shear_modulus: Option<Real>,
        kappa: Option<&Bound<'_, PyAny>>,
        kappa_y: Option<&Bound<'_, PyAny>>,
        twist: Option<&Bound<'_, PyAny>>,
        density: Option<Real>,
        mass_per_length: Option<&Bound<'_, PyAny>>,
        rotary_inertia_per_length: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let p = |name: &str, v: Option<&Bound<'_, PyAny>>| v.map(|v| profile(name, v)).transpose();
        // The arguments the planar flexure shares, read as it reads them; its mass comes after.
        let section = section::read(&section::Arguments {
            ei,
            modulus: modulus.map(|v| v.0),
            width,
            thickness,
            poisson: poisson.map(|v| v.0),
            notch: None,
            density: None,
            mass_per_length: None,
        })?;
        let spec = one_flexure::spec(length.0, section, order, kappa.map(|k| ("kappa", k)))?;
        let n = spec.order;
        let rest = |name: &str, v: Option<&Bound<'_, PyAny>>| v.map(|v| one_flexure::rest(name, v, n)).transpose();
        let keys = SpatialKeys {
            ei_y: p("ei_y", ei_y)?,
            gj: p("gj", gj)?,
            diameter: p("diameter", diameter)?,
            shear_modulus: shear_modulus.map(|v| v.0),
            kappa_y: rest("kappa_y", kappa_y)?,
            twist: rest("twist", twist)?,
        };
        let mut inner = OneFlexure::spatial(&spec, &keys).map_err(to_py)?;
        let density = density.map(|v| v.0);
        let mass_per_length = p("mass_per_length", mass_per_length)?;
        // As a mechanism file's flexure: one of the two, each checked by the library.
        match (density, &mass_per_length) {
            (Some(rho), Some(_)) => {
                return Err(pyo3::exceptions::PyValueError::new_err(format!(
                    "density = {rho} and mass_per_length were both given: give density or mass_per_length, not both"
                )));
            }
            (Some(rho), None) => inner = inner.with_density(rho).map_err(to_py)?,
            (None, Some(mu)) => inner = inner.with_mass_per_length(mu.clone()).map_err(to_py)?,
            (None, None) => {}
        }
        let rotary_inertia_per_length = match rotary_inertia_per_length {
            Some(v) => {
                let rotary = triple("rotary_inertia_per_length", "twist, y, z", Some(v))?;
                inner = inner.with_rotary_inertia_per_length(rotary).map_err(to_py)?;
                Some(rotary)
            }
            None => None,
        };
        Ok(Self { inner, density, mass_per_length, rotary_inertia_per_length })
    }

    /// The `density` given (kg/m³), or None.
    #[getter]
    fn density(&self) -> Option<f64> {
        self.density
    }

    /// The `mass_per_length` given (kg/m) as read: a float, a (root, tip) tuple or an (m, 2)
    /// table; None when not given (a `density` gives μ = ρA, see `mass_per_length_at`).
    #[getter]
    fn mass_per_length<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.mass_per_length.as_ref().map(|p| profile_object(py, p)).transpose()
    }

    /// The `rotary_inertia_per_length` given (kg·m: twist, about y, about z), or None.
    #[getter]
    fn rotary_inertia_per_length(&self) -> Option<(f64, f64, f64)> {
        self.rotary_inertia_per_length.map(|[t, y, z]| (t, y, z))
    }

    /// Mass per length μ(s) (kg/m) at arc length s (m): ρA(s) or the one given; a float, or an
    /// array like s. None without density or mass_per_length.
    fn mass_per_length_at<'py>(&self, py: Python<'py>, s: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let (section, l) = (self.inner.section(), self.inner.length());
        if !section.has_mass() {
            return Ok(None);
        }
        crate::convert::along(py, l, s, |s| section.mass_per_length(s / l).unwrap_or(0.0)).map(Some)
    }

    /// The flexure's mass (kg), ∫₀ᴸ μ ds by the quadrature its inertia and weight are carried
    /// with in a mechanism's modes and simulate (three Gauss points per Magnus subinterval:
    /// exact for a constant or tapered strip or rod); None without density or mass_per_length.
    fn mass(&self) -> Option<f64> {
        MassQuadrature::new(&self.inner).map(|q| q.mass())
    }

    /// Length L (m).
    #[getter]
    fn length(&self) -> f64 {
        self.inner.length()
    }

    /// The orders (n_twist, n_y, n_z).
    #[getter]
    fn orders(&self) -> [usize; 3] {
        self.inner.orders()
    }

    /// Number of coordinates, n_twist + n_y + n_z.
    #[getter]
    fn coordinates(&self) -> usize {
        self.inner.coordinates()
    }

    /// The tip's 4 × 4 transform in the root frame for alpha of shape (n,) (its rotation's
    /// columns are the tip frame's axes); (m, 4, 4) for shape (m, n), computed without the GIL.
    fn pose<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.inner.coordinates();
        match coordinates::read(n, alpha)? {
            Coordinates::One(a) => {
                let (r, p) = spatial::pose_root_tip(&self.inner, &a);
                let g = transform(&r, &p);
                strict::finite_slice("pose", g.as_flattened())?;
                Ok(Array2::from_shape_fn((4, 4), |(i, j)| g[i][j]).into_pyarray(py).into_any())
            }
            Coordinates::Many { count, rows } => {
                let alphas = rows.as_slice();
                let f = &self.inner;
                let poses: Vec<[[f64; 4]; 4]> = py.detach(|| {
                    alphas
                        .chunks_exact(n)
                        .map(|a| {
                            let (r, p) = spatial::pose_root_tip(f, a);
                            transform(&r, &p)
                        })
                        .collect()
                });
                let flat: Vec<f64> = poses.iter().flat_map(|g| g.as_flattened().iter().copied()).collect();
                strict::finite_slice("pose", &flat)?;
                let out: Bound<'py, PyArray3<f64>> = Array3::from_shape_vec((count, 4, 4), flat)
                    .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("pose: {e}")))?
                    .into_pyarray(py);
                Ok(out.into_any())
            }
        }
    }

    /// The body Jacobian (6, n): column a is the tip's twist per unit alpha_a, rows
    /// (rx, ry, rz, x, y, z) in the tip frame.
    fn jacobian<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let a = single(self.inner.coordinates(), alpha)?;
        let mut k = spatial::SpatialKinematics::new(&self.inner);
        spatial::update(&self.inner, &a, flexure::Level::Jacobian, &mut k);
        strict::finite_slice("jacobian", k.jacobian.as_slice())?;
        Ok(crate::convert::matrix(&k.jacobian).into_pyarray(py))
    }

    /// Equilibrium under a dead tip force (fx, fy, fz) and moment (mx, my, mz) in the root frame,
    /// followed from rest: a dict of alpha (n,), pose (4, 4), stable, stability_test ("energy"
    /// without a moment; "static" with one, which has no potential: no neighbouring equilibrium
    /// branched off the path, flutter not judged), stiffness (n, n), residual, limit_fraction
    /// (where the path lost stability, if it did), error_estimate and flagged (against
    /// `accuracy`, default 1 % of L and 1°; a miss warns `AccuracyWarning`).
    #[pyo3(signature = (force=None, moment=None, *, accuracy=None))]
    fn deflect<'py>(
        &self,
        py: Python<'py>,
        force: Option<&Bound<'py, PyAny>>,
        moment: Option<&Bound<'py, PyAny>>,
        accuracy: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let load =
            SpatialLoad { moment: triple("moment", "x, y, z", moment)?, force: triple("force", "x, y, z", force)? };
        let target: Accuracy = crate::accuracy::accuracy(accuracy)?;
        let f = OneFlexure::from(self.inner.clone());
        // Ctrl-C stops it, saying how far it got.
        let options = Deflect { load, target, ..Default::default() };
        let answer = crate::interrupt::interruptible(py, || f.deflect(&options))?;
        let (m, e) = (answer.model(), &answer.model().error_estimate);
        let alpha = m.alpha.flat();
        strict::finite_slice("deflect", &alpha)?;
        let d = PyDict::new(py);
        d.set_item("alpha", numpy::PyArray1::from_slice(py, &alpha))?;
        let g = m.pose.transform();
        d.set_item("pose", Array2::from_shape_fn((4, 4), |(i, j)| g[i][j]).into_pyarray(py))?;
        d.set_item("stable", m.stable)?;
        d.set_item("stability_test", load.stability_test().name())?;
        d.set_item("stiffness", one_flexure::array(&m.stiffness).into_pyarray(py))?;
        d.set_item("residual", m.residual)?;
        if let Some(l) = m.limit_fraction {
            d.set_item("limit_fraction", l)?;
        }
        d.set_item("error_estimate", estimate_dict(py, e)?)?;
        d.set_item("flagged", e.flagged)?;
        if !m.stable {
            let why = match load.stability_test() {
                StabilityTest::Energy => "the stiffness is not positive definite",
                StabilityTest::Static => {
                    "a neighbouring equilibrium branched off the loading path (a dead moment has no potential: Euler's static test)"
                }
            };
            let text = format!(
                "SpatialFlexure.deflect: the equilibrium under force {:?} and moment {:?} is unstable: {why}",
                load.force, load.moment
            );
            warn(py, &py.get_type::<StabilityWarning>(), text, 1)?;
        }
        if e.flagged {
            let text = format!(
                "SpatialFlexure.deflect: the estimated error exceeds the accuracy target: tip position {} % of L (target {} %), tip rotation {}° (target {}°)",
                sig(100.0 * e.position / m.length),
                sig(100.0 * target.position),
                sig(e.angle.to_degrees()),
                sig(target.angle.to_degrees())
            );
            warn(py, &py.get_type::<AccuracyWarning>(), text, 1)?;
        }
        Ok(d)
    }

    /// The tip's 6 × 6 compliance at rest, order (rx, ry, rz, x, y, z) in the root frame.
    fn compliance<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        one_flexure::rest_compliance(py, self.inner.clone().into(), "compliance")
    }

    /// The peak von Mises stress along the flexure at alpha: a dict of max (Pa), at (m),
    /// bending_y, bending_z, shear, von_mises and point (where on the section); None for a
    /// section given by its stiffnesses.
    fn stress<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let a = single(self.inner.coordinates(), alpha)?;
        let Ok(p) = spatial::peak_stress(&self.inner, &a) else { return Ok(None) };
        let d = crate::serialize::to_dict(py, &p.stress)?;
        // The section's point is `point`, as the CLI prints it; `at` is where along the flexure.
        d.set_item("point", d.get_item("at")?)?;
        d.set_item("max", p.stress.von_mises)?;
        d.set_item("at", p.at)?;
        Ok(Some(d))
    }

    /// The deformed flexure at `k` sections evenly spaced in arc length, ends included (2 to
    /// 10000): a NumPy structured array of fields `s` (m), `position` (3,) (m), `rotation`
    /// (3, 3) (its columns the section's axes in the root frame, as `pose`'s), `curvature` (3,)
    /// (twist, κ_y, κ_z, 1/m) and, for a section with a shape, `stress` (the peak von Mises over
    /// the section, Pa). The last row is the tip of `pose(alpha)`.
    fn shape<'py>(
        &self,
        py: Python<'py>,
        alpha: &Bound<'py, PyAny>,
        k: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let a = single(self.inner.coordinates(), alpha)?;
        let count = crate::convert::shape_points(k)?;
        let points = spatial::shape(&self.inner, &a, count).map_err(to_py)?;
        let stressed = points.iter().all(|p| p.stress.is_some());
        let dtype = pyo3::types::PyList::empty(py);
        dtype.append(("s", "f8"))?;
        dtype.append(("position", "f8", (3,)))?;
        dtype.append(("rotation", "f8", (3, 3)))?;
        dtype.append(("curvature", "f8", (3,)))?;
        if stressed {
            dtype.append(("stress", "f8"))?;
        }
        let n = points.len();
        let out = py.import("numpy")?.getattr("empty")?.call1((n, dtype))?;
        out.set_item("s", numpy::PyArray1::from_iter(py, points.iter().map(|p| p.s)))?;
        out.set_item("position", Array2::from_shape_fn((n, 3), |(i, j)| points[i].position[j]).into_pyarray(py))?;
        let rotation = Array3::from_shape_fn((n, 3, 3), |(i, r, c)| points[i].rotation[r][c]);
        out.set_item("rotation", rotation.into_pyarray(py))?;
        out.set_item("curvature", Array2::from_shape_fn((n, 3), |(i, j)| points[i].curvature[j]).into_pyarray(py))?;
        if stressed {
            out.set_item("stress", numpy::PyArray1::from_iter(py, points.iter().map(|p| p.stress.unwrap_or(0.0))))?;
        }
        strict::finite_slice("shape", &points.iter().flat_map(|p| p.position).collect::<Vec<f64>>())?;
        Ok(out)
    }

    /// The exact Kirchhoff rod of this flexure's length, section and rest shape under the dead
    /// tip force and moment (root frame), followed from rest by multiple shooting (what
    /// `flexure.exact.rod` calls): a dict of pose (4, 4), root_moment (3,), stable (its
    /// conjugate-point test), stability_test (as `deflect`'s) and limit_fraction (where the path
    /// lost stability, if it did).
    #[pyo3(signature = (force=None, moment=None))]
    fn exact_rod<'py>(
        &self,
        py: Python<'py>,
        force: Option<&Bound<'py, PyAny>>,
        moment: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        use flexure::reference::rod::{self, Rod};
        let w = SpatialLoad { moment: triple("moment", "x, y, z", moment)?, force: triple("force", "x, y, z", force)? };
        let f = self.inner.clone();
        // Bounded by its segment integrations; Ctrl-C stops it, saying how far it got.
        let solution = crate::interrupt::interruptible(py, || -> flexure::Result<_> {
            let rest = f.rest().to_vec();
            let shape = f.clone();
            let r = Rod::new(f.length(), f.section().clone())?.with_rest(move |s| shape.curvature(&rest, s))?;
            rod::deflect(&r, &w, &Default::default())
        })?;
        let g = transform(&solution.rotation, &solution.position);
        strict::finite_slice("exact_rod", g.as_flattened())?;
        let d = PyDict::new(py);
        d.set_item("pose", Array2::from_shape_fn((4, 4), |(i, j)| g[i][j]).into_pyarray(py))?;
        let m = solution.root_moment;
        d.set_item("root_moment", numpy::PyArray1::from_slice(py, &[m.x, m.y, m.z]))?;
        d.set_item("stable", solution.stable)?;
        d.set_item("stability_test", w.stability_test().name())?;
        if let Some(l) = solution.limit {
            d.set_item("limit_fraction", l)?;
        }
        Ok(d)
    }
}
