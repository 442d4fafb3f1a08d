//! Equilibrium of the spatial flexure under a tip wrench, its stability,
//! and the tip's 6 × 6 compliance and stiffness (Eqs. 22 and 32–36 in space).
//!
//! A dead wrench $(M, F)$ at the tip, fixed in the root frame, does the
//! virtual work $\delta W = M\cdot\delta\theta_s + F\cdot\delta p$, with
//! $\delta\theta_s = R\thinspace\omega_a\delta\alpha_a$ the spatial rotation
//! and $(\omega_a, v_a)$ column $a$ of the body Jacobian. Written along the
//! flexure it is $Q_a = \int_0^LP_a\thinspace d_c\cdot m\thinspace ds$, the
//! section moments $m(s)$ on the turn of each section (module `work`:
//! [`generalized_force`](super::generalized_force)), so equilibrium is
//! $$r_a = \partial_aU - \lambda Q_a = 0,$$
//! and $\partial_br_a = K_{ab} - \lambda\thinspace\partial_bQ_a$. Both
//! integrals are taken by Gauss quadrature on the Magnus subintervals, so
//! a Newton step costs $O(n^2)$ per node and no second derivative of the
//! Magnus exponential; the answer meets the equilibrium of the Magnus
//! product's own $J^Tw$ to the rule's $h^6$ (`tests/spatial_statics.rs`).
//! A force's part is the Hessian of its potential $-F\cdot p$, symmetric
//! (the quadrature's skew part, the rule's error alone, is dropped).
//! A dead moment has no potential once rotations do not commute (Ziegler's
//! non-conservative moment; Argyris, 1979), and its part is not symmetric.
//!
//! **Stability.** With no moment, the energy test: the Hessian of the total
//! potential $U - F\cdot p$ is positive definite. With one there is no
//! energy to be a minimum of, and `stable` is Euler's static test, the
//! exact rod's (`reference::rod`): no real eigenvalue of
//! $K^{-1}\partial r$ ($K$ the elastic stiffness; the identity at rest) has
//! reached zero along the path, so no neighbouring equilibrium branched
//! off. Flutter under the moment is a question of dynamics and is not
//! judged. The real parts of the eigenvalues of $\partial r$ itself are
//! no test: $\partial r$ maps coordinates to generalized forces, and with
//! the coordinates scaled ($\alpha = P\beta$, $P^T\partial r P$) they
//! change sign. Under a twisting moment $10\thinspace EI/L$ alone (orders 6) the
//! Legendre coordinates gave one at $-0.23$ and orthonormal ones none
//! below $+0.38$, of the same equilibrium (`tests/spatial_statics.rs`).
//! The closed form the static test meets: a straight clamped–free rod
//! under a dead axial torque $T$ and a dead thrust $P$ has the neighbouring
//! equilibria $w = y + iz$ of $EI\thinspace w^{\prime\prime} - iT w^{\prime} + Pw = Pw(L)$,
//! $w(0) = w^{\prime}(0) = 0$; with $a_{1,2} = \big(T \pm \sqrt{T^2 + 4EIP}\big)/2EI$
//! one exists only where $a_2/a_1 = e^{i(a_2 - a_1)L}$, so never for
//! $T \ne 0$ (no critical torque, and Euler's $\pi^2EI/4L^2$ is gone:
//! Ziegler, *Principles of Structural Stability*, 1968, the static method
//! failing for the non-conservative axial torque). Greenhill's
//! $T = 2\pi EI/L$ needs both ends held (a pinned shaft), which a tip
//! wrench cannot model.

use super::work::{self, Quadrature, Work};
use super::{SpatialFlexure, SpatialKinematics, energy_gradient, update};
use crate::error::{Error, Result};
use crate::kinematics::Level;
use crate::limit::{self, StabilityLimit};
use crate::linalg;
use crate::scalar::Scalar;
use crate::solver::{self, Settings};
use crate::space::MAX_LOAD;
use crate::statics::Equilibrium;
use nalgebra::{DMatrix, Matrix3, Matrix6, Vector3, Vector6};

/// A dead load at the spatial flexure's tip, in the root frame: moment
/// $(M_x, M_y, M_z)$ (N·m) and force $(F_x, F_y, F_z)$ (N). The planar
/// [`crate::TipLoad`] $(M, F_x, F_y)$ is $(0, 0, M, F_x, F_y, 0)$.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct SpatialLoad<T = f64> {
    /// Moment about the root frame's $x$, $y$, $z$ (N·m).
    pub moment: [T; 3],
    /// Force along the root frame's $x$, $y$, $z$ (N).
    pub force: [T; 3],
}

impl SpatialLoad {
    /// The names of the six components, in order, for messages.
    pub const NAMES: [&'static str; 6] = ["mx", "my", "mz", "fx", "fy", "fz"];

    /// The six components $(M_x, M_y, M_z, F_x, F_y, F_z)$: the wrench of [`crate::space::Spatial`].
    pub fn wrench(&self) -> Vector6<f64> {
        Vector6::new(self.moment[0], self.moment[1], self.moment[2], self.force[0], self.force[1], self.force[2])
    }

    /// Checks that every component is finite and of magnitude at most
    /// [`MAX_LOAD`]; the error names the component (`mx` … `fz`).
    ///
    /// # Example
    /// ```
    /// use flexure::spatial::SpatialLoad;
    /// assert!(SpatialLoad { moment: [0.0, 1.0, 0.0], force: [0.0; 3] }.validate().is_ok());
    /// let e = SpatialLoad { moment: [0.0; 3], force: [0.0, 0.0, f64::NAN] }.validate().unwrap_err();
    /// assert!(e.to_string().contains("fz"));
    /// ```
    pub fn validate(&self) -> Result<()> {
        for (name, v) in Self::NAMES.iter().zip(self.wrench().iter()) {
            if !(v.is_finite() && v.abs() <= MAX_LOAD) {
                return Err(Error::invalid(name, *v, "must be a finite load of magnitude at most 1e30"));
            }
        }
        Ok(())
    }

    /// The load times `factor`.
    pub fn scaled(&self, factor: f64) -> Self {
        SpatialLoad { moment: self.moment.map(|m| m * factor), force: self.force.map(|f| f * factor) }
    }

    /// Which question `stable` answers under this load (module docs):
    /// [`StabilityTest::Energy`] without a moment, [`StabilityTest::Static`]
    /// with one, which has no potential.
    ///
    /// # Example
    /// ```
    /// use flexure::spatial::{SpatialLoad, StabilityTest};
    /// let thrust = SpatialLoad { moment: [0.0; 3], force: [-1.0, 0.0, 0.0] };
    /// assert_eq!(thrust.stability_test(), StabilityTest::Energy);
    /// let twist = SpatialLoad { moment: [10.0, 0.0, 0.0], force: [0.0; 3] };
    /// assert_eq!(twist.stability_test(), StabilityTest::Static);
    /// ```
    pub fn stability_test(&self) -> StabilityTest {
        if self.moment.iter().any(|&m| m != 0.0) { StabilityTest::Static } else { StabilityTest::Energy }
    }

    fn lift<T: Scalar>(&self) -> SpatialLoad<T> {
        SpatialLoad { moment: self.moment.map(T::c), force: self.force.map(T::c) }
    }
}

/// The question a spatial equilibrium's `stable` answers, which the load
/// decides ([`SpatialLoad::stability_test`]); the exact rod
/// (`reference::rod`) answers the same one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StabilityTest {
    /// A conservative load (dead forces): the total potential's Hessian is
    /// positive definite, a minimum of the energy.
    Energy,
    /// A dead moment, which has no potential: Euler's static test, no
    /// neighbouring equilibrium has branched off the loading path. It is not
    /// an energy minimum, and flutter is not judged: a dead thrust past
    /// Euler's load with any twisting moment passes it.
    Static,
}

impl StabilityTest {
    /// Its name in answers: `energy` or `static` (the JSON's and Python's `stability_test`).
    ///
    /// # Example
    /// ```
    /// use flexure::spatial::StabilityTest;
    /// assert_eq!(StabilityTest::Static.name(), "static");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            StabilityTest::Energy => "energy",
            StabilityTest::Static => "static",
        }
    }
}

/// Sample points $t = s/L$ at which cross-sections' rotations bound a
/// continuation step (and the stress is not: see [`SpatialStatics`]).
const ROTATION_SAMPLES: usize = 17;

/// Work buffers and results of [`deflect`] for one spatial flexure (the Data).
#[derive(Debug, Clone)]
pub struct SpatialStatics<T: Scalar = f64> {
    /// Kinematics at the solution (filled to the Jacobian).
    pub kinematics: SpatialKinematics<T>,
    /// $\partial r/\partial\alpha$ at the solution: the loaded generalized
    /// stiffness (symmetric without a tip moment).
    pub stiffness: DMatrix<T>,
    solver: solver::SolverWorkspace<T>,
    quadrature: Quadrature,
    work: Work<T>,
    scratch: Vec<T>,
    /// The angle shapes $\psi_i(t)$ per sample and Legendre index, `[k * width + i]`.
    shapes: Vec<f64>,
}

impl<T: Scalar> SpatialStatics<T> {
    /// Buffers sized for `flexure`.
    pub fn new(flexure: &SpatialFlexure) -> Self {
        let n = flexure.coordinates();
        let shapes = angle_shapes(flexure);
        Self {
            kinematics: SpatialKinematics::new(flexure),
            stiffness: DMatrix::zeros(n, n),
            solver: solver::SolverWorkspace::new(n),
            quadrature: Quadrature::new(flexure),
            work: Work::new(flexure),
            scratch: vec![T::zero(); 2 * n * n],
            shapes,
        }
    }

    /// The coordinates $\alpha$ at the last equilibrium.
    pub fn alpha(&self) -> &[T] {
        &self.solver.x
    }

    /// The solver's loaded stiffness and the tip's kinematics at its answer.
    fn finish(&mut self, flexure: &SpatialFlexure) {
        self.stiffness.as_mut_slice().copy_from_slice(&self.solver.jacobian);
        update(flexure, &self.solver.x, Level::Jacobian, &mut self.kinematics);
    }

    fn fits(&self, flexure: &SpatialFlexure) -> Result<()> {
        if self.solver.dim() == flexure.coordinates()
            && self.kinematics.fits(flexure)
            && work::fits(flexure, &self.quadrature, &self.work)
        {
            Ok(())
        } else {
            Err(Error::invalid("data", self.solver.dim(), "was made for a flexure with another number of coordinates"))
        }
    }
}

/// The tip-wrench problem in the load factor $\lambda$ (module docs).
struct WrenchProblem<'a, T: Scalar> {
    flexure: &'a SpatialFlexure,
    quadrature: &'a Quadrature,
    work: &'a mut Work<T>,
    scratch: &'a mut [T],
    shapes: &'a [f64],
    load: SpatialLoad<T>,
    scale: f64,
}

impl<T: Scalar> WrenchProblem<'_, T> {
    fn has_moment(&self) -> bool {
        self.load.moment.iter().any(|m| m.re() != 0.0)
    }

    /// The symmetric part of the `jacobian` minus `margin` times the elastic stiffness, Cholesky-factored.
    fn definite(&mut self, jacobian: &[T], margin: f64) -> bool {
        let n = self.flexure.coordinates();
        let k = self.flexure.stiffness_matrix();
        let a = &mut self.scratch[..n * n];
        for c in 0..n {
            for r in 0..n {
                a[c * n + r] = T::c(0.5) * (jacobian[c * n + r] + jacobian[r * n + c]) - T::c(margin * k[c * n + r]);
            }
        }
        linalg::cholesky(a, n)
    }
}

impl<T: Scalar> solver::Problem<T> for WrenchProblem<'_, T> {
    fn dim(&self) -> usize {
        self.flexure.coordinates()
    }

    fn evaluate(
        &mut self,
        alpha: &[T],
        lambda: f64,
        residual: &mut [T],
        jacobian: Option<&mut [T]>,
        dlambda: Option<&mut [T]>,
    ) -> Result<()> {
        let f = self.flexure;
        let n = f.coordinates();
        let l = T::c(lambda);
        let moment = Vector3::new(self.load.moment[0], self.load.moment[1], self.load.moment[2]);
        let force = Vector3::new(self.load.force[0], self.load.force[1], self.load.force[2]);
        work::evaluate(f, self.quadrature, alpha, (moment, force), jacobian.is_some(), self.work);
        energy_gradient(f, alpha, residual);
        let mut dl = dlambda;
        for (a, r) in residual.iter_mut().enumerate() {
            let q = self.work.force[a];
            *r -= l * q;
            if let Some(d) = dl.as_deref_mut() {
                d[a] = -q;
            }
        }
        if let Some(h) = jacobian {
            let elastic = f.stiffness_matrix();
            for b in 0..n {
                for a in 0..n {
                    // Row a (the residual's entry), column b (the coordinate).
                    h[b * n + a] = T::c(elastic[a * n + b]) - l * self.work.derivative[b * n + a];
                }
            }
            if !self.has_moment() {
                // The Hessian of a potential: the quadrature's skew part is the rule's error alone.
                for b in 0..n {
                    for a in 0..b {
                        let mean = T::c(0.5) * (h[b * n + a] + h[a * n + b]);
                        (h[b * n + a], h[a * n + b]) = (mean, mean);
                    }
                }
            }
        }
        if residual.iter().all(|r| r.re().is_finite()) {
            Ok(())
        } else {
            Err(Error::Singular { what: "non-finite generalized force".into() })
        }
    }

    fn stable(&mut self, _alpha: &[T], _lambda: f64, jacobian: &[T]) -> bool {
        if !self.has_moment() {
            return self.definite(jacobian, 0.0);
        }
        let n = self.flexure.coordinates();
        let j = DMatrix::from_iterator(n, n, jacobian.iter().map(|v| v.re()));
        static_test(self.flexure.stiffness_matrix(), j)
    }

    fn far_from_instability(&mut self, _alpha: &[T], _lambda: f64, jacobian: &[T]) -> bool {
        self.definite(jacobian, crate::statics::MARGIN)
    }

    fn distance(&self, a: &[T], b: &[T]) -> f64 {
        rotation(self.flexure, self.shapes, a, b)
    }

    fn scale(&self) -> f64 {
        self.scale
    }

    fn unit(&self) -> &'static str {
        "N·m"
    }

    fn name(&self) -> &'static str {
        "deflect"
    }
}

/// Euler's static test under a load with no potential (module docs): no
/// real eigenvalue of $K^{-1}\partial r$ is zero or negative, $K$ the
/// elastic stiffness. It is the identity at rest, its eigenvalues do not
/// depend on the coordinates ($\alpha = P\beta$ makes it
/// $P^{-1}K^{-1}\partial r\thinspace P$), and a real one through zero is a
/// neighbouring equilibrium: the exact rod's conjugate-point test, with an
/// eigenvalue within $10^{-9}$ of the largest of being real counted as real
/// as the rod counts it. The eigenvalues are those of the similar, better
/// scaled $L^{-1}\partial r\thinspace L^{-T}$ ($K = LL^T$), by a Schur
/// decomposition of at most [`SCHUR_SWEEPS`] sweeps per coordinate; one
/// that does not converge (met on a round rod wound into a helix by a skew
/// moment, `tests/spatial_statics.rs`, whose eigenvalues cluster) falls
/// back on the sign of the determinant, the test of a single real
/// eigenvalue through zero.
fn static_test(elastic: &[f64], jacobian: DMatrix<f64>) -> bool {
    let n = jacobian.nrows();
    // K is symmetric positive definite (a validated section).
    let Some(k) = DMatrix::from_column_slice(n, n, elastic).cholesky() else {
        return false;
    };
    let l = k.l();
    let mut scaled = jacobian;
    l.solve_lower_triangular_mut(&mut scaled);
    // L⁻¹(L⁻¹∂r)ᵀ is the transpose of L⁻¹∂r L⁻ᵀ: the same eigenvalues.
    let mut scaled = scaled.transpose();
    l.solve_lower_triangular_mut(&mut scaled);
    let Some(schur) = nalgebra::linalg::Schur::try_new(scaled.clone(), f64::EPSILON, SCHUR_SWEEPS * n) else {
        return scaled.determinant() > 0.0;
    };
    let eigenvalues = schur.complex_eigenvalues();
    let size = eigenvalues.iter().map(|e| e.norm()).fold(0.0, f64::max);
    eigenvalues.iter().all(|e| e.im.abs() > 1e-9 * size || e.re > 0.0)
}

/// The most Schur sweeps per coordinate of [`static_test`] (LAPACK allows 30).
const SCHUR_SWEEPS: usize = 30;

/// The largest rotation between `a` and `b` of the sampled cross-sections
/// relative to the root, each component's $\sum_i\psi_i(t)\Delta\alpha_{c,i}$
/// taken as one rotation vector (exact while the curvature keeps its
/// direction, a bound for a step otherwise).
fn rotation<T: Scalar>(flexure: &SpatialFlexure, shapes: &[f64], a: &[T], b: &[T]) -> f64 {
    let orders = flexure.orders();
    let width = orders.into_iter().max().unwrap_or(0);
    let mut largest = 0.0_f64;
    for row in shapes.chunks_exact(width.max(1)) {
        let mut start = 0;
        let mut squares = 0.0;
        for n in orders {
            let turn: f64 = (0..n).map(|i| row[i] * (a[start + i].re() - b[start + i].re())).sum();
            squares += turn * turn;
            start += n;
        }
        largest = largest.max(squares.sqrt());
    }
    largest
}

/// The largest rotation (rad) of a sampled cross-section between
/// coordinates `a` and `b` (the continuation's step bound, with its table
/// of angle shapes made here).
pub fn rotation_between(flexure: &SpatialFlexure, a: &[f64], b: &[f64]) -> f64 {
    rotation(flexure, &angle_shapes(flexure), a, b)
}

/// $\psi_i(t_k)$ at the [`ROTATION_SAMPLES`] points, `[k * width + i]`.
fn angle_shapes(flexure: &SpatialFlexure) -> Vec<f64> {
    let width = flexure.orders().into_iter().max().unwrap_or(0);
    let mut shapes = vec![0.0; ROTATION_SAMPLES * width];
    for (k, row) in shapes.chunks_exact_mut(width.max(1)).enumerate().take(ROTATION_SAMPLES) {
        crate::basis::angle_shapes(k as f64 / (ROTATION_SAMPLES - 1) as f64, &mut row[..width]);
    }
    shapes
}

/// Residual scale: the largest stiffness over $L$ plus the load's moment and force times $L$.
fn scale(flexure: &SpatialFlexure, load: &SpatialLoad) -> f64 {
    let l = flexure.length();
    let k = flexure.section().stiffness(0.5).into_iter().fold(0.0, f64::max);
    k / l + load.moment.iter().map(|m| m.abs()).sum::<f64>() + l * load.force.iter().map(|f| f.abs()).sum::<f64>()
}

/// The tip-wrench problem on `data`'s buffers, with the solver's workspace
/// beside it, once `load` and the buffers are checked.
fn problem<'a, T: Scalar>(
    flexure: &'a SpatialFlexure,
    load: &SpatialLoad,
    data: &'a mut SpatialStatics<T>,
) -> Result<(WrenchProblem<'a, T>, &'a mut solver::SolverWorkspace<T>)> {
    load.validate()?;
    data.fits(flexure)?;
    let SpatialStatics { quadrature, work, solver, scratch, shapes, .. } = data;
    let problem =
        WrenchProblem { flexure, quadrature, work, scratch, shapes, load: load.lift(), scale: scale(flexure, load) };
    Ok((problem, solver))
}

/// Equilibrium of the spatial flexure under the dead tip `load` (root
/// frame), followed from the rest shape by the shared continuation
/// ([`crate::solver`]), so the answer lies on the loading path and
/// [`Equilibrium::limit`] names the load fraction where stability was lost.
/// Results stay in `data` (its `stiffness` is $\partial r/\partial\alpha$).
///
/// # Example
/// ```
/// use flexure::section::SpatialSection;
/// use flexure::spatial::{SpatialFlexure, SpatialLoad, SpatialStatics, deflect};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(0.5, 2.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
/// let mut data = SpatialStatics::new(&f);
/// // A pure twist TL/GJ: 0.3 N·m turns the tip by 0.6 rad about x.
/// let eq = deflect(&f, &SpatialLoad { moment: [0.3, 0.0, 0.0], force: [0.0; 3] }, &mut data, &Default::default())
///     .unwrap();
/// assert!(eq.stable && (data.alpha()[0] - 0.6).abs() < 1e-10);
/// ```
pub fn deflect(
    flexure: &SpatialFlexure,
    load: &SpatialLoad,
    data: &mut SpatialStatics,
    settings: &Settings,
) -> Result<Equilibrium> {
    follow(flexure, load, data, settings, false)
}

/// [`deflect`], or with `while_stable` an [`Error::Unstable`] as soon as the path loses stability.
fn follow<T: Scalar>(
    flexure: &SpatialFlexure,
    load: &SpatialLoad,
    data: &mut SpatialStatics<T>,
    settings: &Settings,
    while_stable: bool,
) -> Result<Equilibrium> {
    let (mut problem, ws) = problem(flexure, load, data)?;
    for (a, &k) in ws.x.iter_mut().zip(flexure.rest()) {
        *a = T::c(k);
    }
    let path = if while_stable {
        solver::continuation_while_stable(&mut problem, ws, settings)?
    } else {
        solver::continuation(&mut problem, ws, settings)?
    };
    data.finish(flexure);
    Ok(Equilibrium::from_path(&path))
}

/// The equilibrium under the full `load` nearest to `alpha`, by Newton
/// alone (a good start, such as a lower order's answer, embedded).
pub fn correct(
    flexure: &SpatialFlexure,
    load: &SpatialLoad,
    alpha: &[f64],
    data: &mut SpatialStatics,
    settings: &Settings,
) -> Result<Equilibrium> {
    flexure.check_coordinates("alpha", alpha)?;
    let (mut problem, ws) = problem(flexure, load, data)?;
    ws.x.copy_from_slice(alpha);
    let report = solver::newton(&mut problem, ws, 1.0, settings)?;
    let stable = solver::Problem::stable(&mut problem, &ws.x, 1.0, &ws.jacobian);
    data.finish(flexure);
    Ok(Equilibrium { stable, limit: None, residual: report.residual, iterations: report.iterations, load_steps: 0 })
}

/// The smallest factor on `load` at which the equilibrium followed from
/// rest stops being stable (a buckling, such as lateral-torsional
/// buckling, or a limit load), or the factor up to which it stays stable
/// (`max_factor`, or as far as the path can be followed); the search is
/// the planar flexure's ([`crate::statics::stability_limit`]).
///
/// # Example
/// ```
/// use flexure::section::SpatialSection;
/// use flexure::spatial::{SpatialFlexure, SpatialLoad, stability_limit};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
/// // Axial compression buckles it near Euler's π²EI/4L² = 2.4674 (the model's 2.4677, Table I).
/// let l = stability_limit(&f, &SpatialLoad { moment: [0.0; 3], force: [-1.0, 0.0, 0.0] }, 100.0).unwrap();
/// assert!((l.factor() - 2.4677).abs() < 1e-3);
/// ```
pub fn stability_limit(flexure: &SpatialFlexure, load: &SpatialLoad, max_factor: f64) -> Result<StabilityLimit> {
    load.validate()?;
    let mut data = SpatialStatics::<f64>::new(flexure);
    limit::search(max_factor, |factor| follow(flexure, &load.scaled(factor), &mut data, &Settings::default(), true))
}

/// The tip's compliance $C = \mathcal J K^{-1}\mathcal J^T$ (6 × 6, Eq. 33
/// in space) about the state in `data` (from [`deflect`] or [`correct`]):
/// the tip's small rotation and displacement in the root frame, $(r_x,
/// r_y, r_z, x, y, z)$, per unit of a small extra tip wrench $(M, F)$ in
/// the root frame; $\mathcal J = \mathrm{diag}(R, R)\thinspace J$ is the
/// Jacobian in the root frame. With a dead moment $K$ is not symmetric, nor
/// is $C$. Fails if $K$ is singular (at a buckling load).
///
/// # Example
/// ```
/// use flexure::section::SpatialSection;
/// use flexure::spatial::{SpatialFlexure, SpatialLoad, SpatialStatics, correct, compliance};
/// let (gj, ei_y, ei_z, l) = (0.5, 2.0, 1.0, 1.5);
/// let f = SpatialFlexure::new(l, SpatialSection::uniform(gj, ei_y, ei_z).unwrap(), [3, 3, 3]).unwrap();
/// let mut data = SpatialStatics::new(&f);
/// correct(&f, &SpatialLoad::default(), f.rest(), &mut data, &Default::default()).unwrap();
/// let c = compliance(&f, &data).unwrap();
/// // Twist L/GJ, bending L/EI, and a tip force's L³/3EI (Eqs. 34–36).
/// assert!((c[(0, 0)] - l / gj).abs() < 1e-12 && (c[(2, 2)] - l / ei_z).abs() < 1e-12);
/// assert!((c[(5, 5)] - l.powi(3) / (3.0 * ei_y)).abs() < 1e-12);
/// ```
pub fn compliance(flexure: &SpatialFlexure, data: &SpatialStatics) -> Result<Matrix6<f64>> {
    let n = flexure.coordinates();
    let r: Matrix3<f64> = data.kinematics.rotation;
    let mut jr = DMatrix::zeros(6, n);
    for a in 0..n {
        let c = data.kinematics.jacobian.column(a);
        let w = r * Vector3::new(c[0], c[1], c[2]);
        let v = r * Vector3::new(c[3], c[4], c[5]);
        for i in 0..3 {
            jr[(i, a)] = w[i];
            jr[(i + 3, a)] = v[i];
        }
    }
    let lu = data.stiffness.clone().lu();
    let x = lu
        .solve(&jr.transpose())
        .ok_or_else(|| Error::Singular { what: "the loaded stiffness (a buckling load)".into() })?;
    let c = &jr * x;
    if c.iter().all(|v| v.is_finite()) {
        Ok(Matrix6::from_iterator(c.iter().copied()))
    } else {
        Err(Error::Singular { what: "the loaded stiffness (a buckling load)".into() })
    }
}

/// The tip compliance at rest ([`compliance`] at the flexure's own rest
/// coordinates, unloaded): the export's springs and `compliance` fit it.
pub fn compliance_rest(flexure: &SpatialFlexure) -> Result<Matrix6<f64>> {
    let mut data = SpatialStatics::new(flexure);
    correct(flexure, &SpatialLoad::default(), flexure.rest(), &mut data, &Default::default())?;
    compliance(flexure, &data)
}

/// The tip's loaded stiffness, the inverse of [`compliance`] (6 × 6, N·m/rad … N/m).
pub fn tip_stiffness(flexure: &SpatialFlexure, data: &SpatialStatics) -> Result<Matrix6<f64>> {
    compliance(flexure, data)?
        .try_inverse()
        .ok_or_else(|| Error::Singular { what: "the tip compliance (fewer than six independent coordinates)".into() })
}
