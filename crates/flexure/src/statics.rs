//! Equilibrium under tip loads (paper Eqs. 22 and 32).

use crate::energy::energy_gradient;
use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::kinematics::{self, Kinematics, Level, Pose};
use crate::limit::{self, PathEnd, StabilityLimit};
use crate::linalg;
use crate::scalar::Scalar;
use crate::solver;
use nalgebra::DMatrix;

/// A load at the tip, in the root frame: moment $M$ (N·m) and force
/// $(F_x, F_y)$ (N). The one planar [`Wrench`](crate::space::Wrench),
/// named for where it acts.
pub type TipLoad<T = f64> = crate::space::Wrench<T>;

pub use crate::solver::Settings;

pub use crate::space::MAX_LOAD;

/// Work buffers and results of [`deflect`] for one flexure (the Data).
#[derive(Debug, Clone)]
pub struct StaticsData<T: Scalar = f64> {
    /// Kinematics at the solution.
    pub kinematics: Kinematics<T>,
    /// Generalized stiffness $K$ at the solution (Eq. 32).
    pub stiffness: DMatrix<T>,
    solver: solver::SolverWorkspace<T>,
    scratch: Vec<T>,
}

impl<T: Scalar> StaticsData<T> {
    /// Buffers sized for `flexure`.
    pub fn new(flexure: &Flexure) -> Self {
        let n = flexure.order();
        Self {
            kinematics: Kinematics::new(flexure),
            stiffness: DMatrix::zeros(n, n),
            solver: solver::SolverWorkspace::new(n),
            scratch: vec![T::zero(); n * n],
        }
    }

    /// Joint coordinates $\alpha$ at the last equilibrium.
    pub fn alpha(&self) -> &[T] {
        &self.solver.x
    }

    /// Tip pose at the last equilibrium.
    pub fn pose_root_tip(&self) -> Pose<T> {
        self.kinematics.pose_root_tip
    }
}

/// What [`deflect`] found, beside the data left in [`StaticsData`];
/// serialized with `limit` as `limit_fraction`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Equilibrium {
    /// Whether $K$ is positive definite: a stable equilibrium.
    pub stable: bool,
    /// The load fraction at which the loading path first lost stability
    /// (a limit load passed by snap-through, or a bifurcation), if it did.
    #[serde(rename = "limit_fraction")]
    pub limit: Option<f64>,
    /// Final generalized-force residual (N·m).
    pub residual: f64,
    /// Newton iterations over all load steps.
    pub iterations: usize,
    /// Load-continuation steps taken.
    pub load_steps: usize,
}

impl Equilibrium {
    /// The equilibrium a continuation [`solver::Path`] reached.
    pub fn from_path(path: &solver::Path) -> Self {
        Self {
            stable: path.stable,
            limit: path.limit,
            residual: path.residual,
            iterations: path.iterations,
            load_steps: path.steps,
        }
    }
}

impl PathEnd for Equilibrium {
    fn ended_stable(&self) -> bool {
        self.stable
    }

    fn lost_at(&self) -> Option<f64> {
        self.limit
    }
}

/// The tip-load problem: $r(\alpha, \lambda) = \nabla U - \lambda\mathcal J^T(M, F_x, F_y)$
/// (Eq. 22) with Jacobian $K = \nabla\nabla U - \lambda(F_x\nabla\nabla x + F_y\nabla\nabla y)$ (Eq. 32).
struct TipLoadProblem<'a, T: Scalar> {
    flexure: &'a Flexure,
    kinematics: &'a mut Kinematics<T>,
    scratch: &'a mut [T],
    load: TipLoad<T>,
    scale: f64,
}

impl<T: Scalar> solver::Problem<T> for TipLoadProblem<'_, T> {
    fn dim(&self) -> usize {
        self.flexure.order()
    }

    fn evaluate(
        &mut self,
        alpha: &[T],
        lambda: f64,
        residual: &mut [T],
        jacobian: Option<&mut [T]>,
        dlambda: Option<&mut [T]>,
    ) -> Result<()> {
        let (f, k) = (self.flexure, &mut *self.kinematics);
        let level = if jacobian.is_some() { Level::Hessian } else { Level::Jacobian };
        kinematics::update(f, alpha, k, level);
        let l = T::c(lambda);
        let w = [self.load.moment, self.load.fx, self.load.fy];
        energy_gradient(f, alpha, residual);
        for (i, r) in residual.iter_mut().enumerate() {
            let j = k.jacobian_root_tip.column(i);
            *r -= l * (w[0] * j[0] + w[1] * j[1] + w[2] * j[2]);
        }
        if let Some(d) = dlambda {
            for (i, d) in d.iter_mut().enumerate() {
                let j = k.jacobian_root_tip.column(i);
                *d = -(w[0] * j[0] + w[1] * j[1] + w[2] * j[2]);
            }
        }
        if let Some(h) = jacobian {
            loaded_stiffness_into(f, k, [w[1], w[2]], l, h, f.order());
        }
        if residual.iter().all(|r| r.re().is_finite()) {
            Ok(())
        } else {
            Err(Error::Singular { what: "non-finite generalized force".into() })
        }
    }

    fn stable(&mut self, _alpha: &[T], _lambda: f64, jacobian: &[T]) -> bool {
        linalg::positive_definite(jacobian, self.flexure.order(), self.scratch)
    }

    fn far_from_instability(&mut self, _alpha: &[T], _lambda: f64, jacobian: &[T]) -> bool {
        far_from_instability(self.flexure, jacobian, self.scratch)
    }

    fn distance(&self, a: &[T], b: &[T]) -> f64 {
        rotation(self.flexure, a, Some(b))
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

/// The loaded stiffness of the flexure under a tip force $\lambda(F_x, F_y)$
/// (paper Eq. 32),
/// $$K = \nabla\nabla U - \lambda\left(F_x\nabla\nabla x + F_y\nabla\nabla y\right),$$
/// the Hessian of the potential $U - \lambda(M\phi + F_x x + F_y y)$ (the
/// moment drops out: $\nabla\nabla\phi = 0$), from the Hessians in
/// `kinematics` (filled to [`Level::Hessian`]). Written into the leading
/// $N\times N$ block of the column-major `out` of leading dimension `ld`
/// ($K_{rc}$ at `out[c * ld + r]`), so a bordered system takes it in place;
/// allocates nothing. The one assembly of Eq. 32: the tip-load solve, the
/// minimum-energy connection and [`loaded_stiffness`] call it.
///
/// # Panics
/// If `ld` < $N$ or `out` is shorter than $(N - 1)\thinspace\ell_d + N$ (with $\ell_d$ = `ld`).
///
/// # Example
/// ```
/// use flexure::kinematics::{self, Kinematics, Level};
/// use flexure::{statics::loaded_stiffness_into, Flexure};
/// let f = Flexure::new(1.0, 2.0, 2).unwrap();
/// let mut k = Kinematics::new(&f);
/// kinematics::update(&f, f.rest(), &mut k, Level::Hessian);
/// // Unloaded, K is the bending stiffness ∇∇U: EI/L on the diagonal (Eq. 28).
/// let mut out = [0.0; 4];
/// loaded_stiffness_into(&f, &k, [3.0, -1.0], 0.0, &mut out, 2);
/// assert_eq!(out, [2.0, 0.0, 0.0, 2.0 / 3.0]);
/// ```
pub fn loaded_stiffness_into<T: Scalar>(
    flexure: &Flexure,
    kinematics: &Kinematics<T>,
    [fx, fy]: [T; 2],
    lambda: T,
    out: &mut [T],
    ld: usize,
) {
    let n = flexure.order();
    assert!(ld >= n, "leading dimension {ld} is less than the order {n}");
    let (hx, hy) = (kinematics.hessian_root_tip_x.as_slice(), kinematics.hessian_root_tip_y.as_slice());
    let elastic = flexure.stiffness_matrix();
    for c in 0..n {
        let column = &mut out[c * ld..c * ld + n];
        for (r, o) in column.iter_mut().enumerate() {
            let idx = c * n + r;
            *o = -lambda * (fx * hx[idx] + fy * hy[idx]) + T::c(elastic[idx]);
        }
    }
}

/// [`loaded_stiffness_into`] under the full `load` ($\lambda = 1$), as a
/// matrix: the stiffness about an equilibrium under `load` (the moment
/// does not enter), for [`crate::compliance_tip`].
///
/// # Example
/// ```
/// use flexure::kinematics::{self, Kinematics, Level};
/// use flexure::{statics::loaded_stiffness, Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let mut k = Kinematics::new(&f);
/// kinematics::update(&f, f.rest(), &mut k, Level::Hessian);
/// // A compressive end force softens the straight flexure (Euler buckling, Eq. 39).
/// let unloaded = loaded_stiffness(&f, &k, &TipLoad::default());
/// let pushed = loaded_stiffness(&f, &k, &TipLoad { moment: 5.0, fx: -1.0, fy: 0.0 });
/// assert!(pushed[(0, 0)] < unloaded[(0, 0)]);
/// ```
pub fn loaded_stiffness(flexure: &Flexure, kinematics: &Kinematics<f64>, load: &TipLoad) -> DMatrix<f64> {
    let n = flexure.order();
    let mut k = DMatrix::zeros(n, n);
    loaded_stiffness_into(flexure, kinematics, [load.fx, load.fy], 1.0, k.as_mut_slice(), n);
    k
}

/// Equilibrium of the flexure under `load`: the $\alpha$ where
/// $\tau = \nabla U - M\nabla\phi - F_x\nabla x - F_y\nabla y = 0$ (Eq. 22),
/// with stiffness $K = \nabla\nabla U - F_x\nabla\nabla x - F_y\nabla\nabla y$ (Eq. 32).
///
/// The load is applied by the shared continuation ([`crate::solver`]) from
/// the rest shape, so the answer lies on the loading path: a snap-through
/// load reaches the stable equilibrium the path leads to, and
/// [`Equilibrium::limit`] names the load fraction where stability was lost.
/// Results stay in `data`; nothing is allocated.
///
/// # Example
/// ```
/// use flexure::{deflect, Flexure, StaticsData, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let mut data = StaticsData::new(&f);
/// // A pure moment bends the flexure into an arc of angle ML/EI.
/// let eq = deflect(&f, &TipLoad { moment: 1.2, fx: 0.0, fy: 0.0 }, &mut data, &Default::default()).unwrap();
/// assert!(eq.stable && (data.alpha()[0] - 1.2).abs() < 1e-12);
/// ```
pub fn deflect<T: Scalar>(
    flexure: &Flexure,
    load: &TipLoad<T>,
    data: &mut StaticsData<T>,
    settings: &Settings,
) -> Result<Equilibrium> {
    follow(flexure, load, data, settings, false)
}

/// [`deflect`], or with `while_stable` an [`Error::Unstable`] as soon as the path loses stability.
fn follow<T: Scalar>(
    flexure: &Flexure,
    load: &TipLoad<T>,
    data: &mut StaticsData<T>,
    settings: &Settings,
    while_stable: bool,
) -> Result<Equilibrium> {
    TipLoad { moment: load.moment.re(), fx: load.fx.re(), fy: load.fy.re() }.validate()?;
    if data.solver.dim() != flexure.order() {
        return Err(Error::invalid("data", data.solver.dim(), "was made for a flexure of another order"));
    }
    data.kinematics.check_fits(flexure)?;
    let l = flexure.length();
    let scale = flexure.ei() / l + load.moment.re().abs() + l * (load.fx.re().abs() + load.fy.re().abs());
    for (a, &k) in data.solver.x.iter_mut().zip(flexure.rest()) {
        *a = T::c(k);
    }
    let mut problem =
        TipLoadProblem { flexure, kinematics: &mut data.kinematics, scratch: &mut data.scratch, load: *load, scale };
    let path = if while_stable {
        solver::continuation_while_stable(&mut problem, &mut data.solver, settings)?
    } else {
        solver::continuation(&mut problem, &mut data.solver, settings)?
    };
    // The last evaluation was at the end state, with the Hessian level.
    data.stiffness.as_mut_slice().copy_from_slice(&data.solver.jacobian);
    Ok(Equilibrium::from_path(&path))
}

/// The equilibrium under the full `load` nearest to `alpha`: Newton alone,
/// with no continuation (for a good start, such as a lower order's answer).
/// Leaves the solution and its stiffness in `data`.
pub fn correct<T: Scalar>(
    flexure: &Flexure,
    load: &TipLoad<T>,
    alpha: &[T],
    data: &mut StaticsData<T>,
    settings: &Settings,
) -> Result<Equilibrium> {
    TipLoad { moment: load.moment.re(), fx: load.fx.re(), fy: load.fy.re() }.validate()?;
    flexure.check_coordinates("alpha", alpha)?;
    if data.solver.dim() != flexure.order() {
        return Err(Error::invalid("data", data.solver.dim(), "was made for a flexure of another order"));
    }
    data.kinematics.check_fits(flexure)?;
    let l = flexure.length();
    let scale = flexure.ei() / l + load.moment.re().abs() + l * (load.fx.re().abs() + load.fy.re().abs());
    data.solver.x.copy_from_slice(alpha);
    let mut problem =
        TipLoadProblem { flexure, kinematics: &mut data.kinematics, scratch: &mut data.scratch, load: *load, scale };
    let report = solver::newton(&mut problem, &mut data.solver, 1.0, settings)?;
    let stable = solver::Problem::stable(&mut problem, &data.solver.x, 1.0, &data.solver.jacobian);
    data.stiffness.as_mut_slice().copy_from_slice(&data.solver.jacobian);
    Ok(Equilibrium { stable, limit: None, residual: report.residual, iterations: report.iterations, load_steps: 0 })
}

/// How much of the elastic stiffness a load may take away, in every
/// direction, for a state to count as far from instability.
pub(crate) const MARGIN: f64 = 0.5;

/// Whether $\nabla\nabla E - \frac12 K$ is positive definite (`scratch`: $N^2$):
/// the load softens no direction by half its elastic stiffness $K$, so no
/// fold or bifurcation is near ([`solver::Problem::far_from_instability`]).
pub(crate) fn far_from_instability<T: Scalar>(flexure: &Flexure, hessian: &[T], scratch: &mut [T]) -> bool {
    for (s, (&h, &k)) in scratch.iter_mut().zip(hessian.iter().zip(flexure.stiffness_matrix())) {
        *s = h - T::c(MARGIN * k);
    }
    linalg::cholesky(scratch, flexure.order())
}

/// Largest cross-section rotation $\max_k\lvert\sum_i\psi_i(t_k)(a_i - b_i)\rvert$ (b = 0 if absent).
pub(crate) fn rotation<T: Scalar>(flexure: &Flexure, a: &[T], b: Option<&[T]>) -> f64 {
    flexure.psi_rows().fold(0.0_f64, |m, psi| {
        let d: f64 = psi.iter().enumerate().map(|(i, p)| p * (a[i].re() - b.map_or(0.0, |b| b[i].re()))).sum();
        m.max(d.abs())
    })
}

/// The smallest factor $\lambda$ for which the equilibrium under
/// $\lambda\cdot$`load`, followed from the rest shape, stops being stable:
/// $K$ (Eq. 32) stops being positive definite on the loading path (a
/// buckling or limit load); or the factor up to which it stays stable
/// (`max_factor`, or as far as the path can be followed). The search is
/// [`crate::limit`]'s, shared with the tendon joint.
///
/// # Example
/// ```
/// use flexure::{statics::stability_limit, Flexure, StabilityLimit, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // Axial compression: the model's free buckling load, Table I.
/// let l = stability_limit(&f, &TipLoad { moment: 0.0, fx: -1.0, fy: 0.0 }, 100.0).unwrap();
/// assert!(matches!(l, StabilityLimit::Lost { .. }) && (l.factor() - 2.4677).abs() < 1e-4);
/// // A pure moment never destabilizes the flexure.
/// let l = stability_limit(&f, &TipLoad { moment: 1.0, fx: 0.0, fy: 0.0 }, 10.0).unwrap();
/// assert_eq!(l, StabilityLimit::StableUpTo { factor: 10.0, stalled: None });
/// ```
pub fn stability_limit(flexure: &Flexure, load: &TipLoad, max_factor: f64) -> Result<StabilityLimit> {
    load.validate()?;
    let mut data = StaticsData::new(flexure);
    // Each probe stops where its path loses stability: only that is asked.
    limit::search(max_factor, |factor| {
        let scaled = TipLoad { moment: factor * load.moment, fx: factor * load.fx, fy: factor * load.fy };
        follow(flexure, &scaled, &mut data, &Settings::default(), true)
    })
}
