//! Static equilibrium, stiffness and compliance of a mechanism.
//!
//! Equilibrium makes the potential $V(q)$ ([`super::lagrangian`])
//! stationary subject to the closures $c(q) = 0$: the KKT conditions
//! $$\nabla V + G^T\mu = 0,\qquad c(q) = 0,\qquad G = \partial c/\partial q,$$
//! with Jacobian the KKT matrix $\begin{bmatrix}\nabla^2 L & G^T\cr G & 0\end{bmatrix}$,
//! $L = V + \mu^T c$, from exact Hessians. [`Kkt`] states them as a
//! [`solver::Problem`] in the load factor $\lambda$ (every load is linear
//! in its magnitude, so $\partial_\lambda r$ is the gradient of the load
//! potential of the load change), and the shared continuation
//! ([`crate::solver`]) follows them from the unloaded, assembled
//! configuration: it passes limit points and reports where stability was
//! lost. Each Newton step costs one dense $(n+m)\times(n+m)$ solve for $n$
//! coordinates and $m$ closure equations.
//!
//! **Stability** is the constrained stiffness $Z^T\nabla^2 L\thinspace Z$ positive
//! definite ([`linalg::positive_definite`]), where the columns of
//! $Z$ = [`linalg::null_space`]$(G)$ span the admissible motions, with a
//! margin: measured against the joints' own stiffness, every admissible
//! motion must keep a stiffness above $\sqrt{\text{tolerance}}$ ($10^{-6}$ by
//! default). An equilibrium converged to a residual $t$ is known only to
//! $t/\kappa$ along a mode of stiffness $\kappa$, so a softer mode is not
//! resolved: this is what makes a bifurcation visible. Rounding makes
//! every symmetric bifurcation slightly imperfect, and the continuation
//! would otherwise glide through its knee, where $\kappa$ dips to about
//! $t^{2/3}$ but stays positive, without a loss of stability to report.
//! The margin moves a reported limit load by about $10^{-6}$ of itself.
//!
//! **Redundant closures** (several legs welded to one stage) make rows of
//! $G$ dependent, so part of $\mu$ is statically indeterminate in these
//! inextensible joints. The null space comes from the singular values of
//! $G$ itself; the multiplier block of the Newton matrix carries a shift of
//! $10^{-10}$ (relative to its unit scaling), in the Jacobian only, so the
//! residual and every converged answer stay exact: where the equations fix
//! $\mu$ the shift is invisible, where they do not it keeps the free part
//! where it was. Stability and the reported multipliers then take the free
//! part with the least force through the flexures (see [`Solution::multipliers`]).

use super::indeterminate::{full_row_rank, settle};
use super::kinematics::{Frames, frames, frames_into, point};
use super::lagrangian::{Assembly, add_loads, assemble_into, check_sizes, closure_hessian, closures, lagrangian};
use super::tree::Tree;
use super::{Closure, Loads, Mechanism};
use crate::error::{Error, Result};
use crate::linalg;
use crate::solver;
use nalgebra::{DMatrix, DVector, Matrix3};
use std::cell::RefCell;

pub use crate::solver::Settings;

/// An equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Generalized coordinates.
    pub q: Vec<f64>,
    /// Closure multipliers (constraint forces in N and moments in N·m):
    /// $\mu^T(w_a - w_b)$ is their potential, so a weld or pin pushes body
    /// `a` with $-\mu$ and body `b` with $+\mu$. Where redundant closures
    /// (several legs welded to one stage) leave part of $\mu$ statically
    /// indeterminate, that part is the one that passes the least force
    /// through the flexures ($\min\sum_j L_j\lvert F_j\rvert^2$): the limit the
    /// model's own compatibility approaches as deflection vanishes.
    pub multipliers: Vec<f64>,
    /// The loads it carries.
    pub loads: Loads,
    /// Elastic energy stored in the joints (J).
    pub energy: f64,
    /// Whether the constrained stiffness is positive definite.
    pub stable: bool,
    /// Where the loading path to it lost stability before snapping through
    /// to this stable state: the fraction of the load change, if it did.
    pub limit: Option<f64>,
    /// Final KKT residual, relative ([`Kkt`]).
    pub residual: f64,
    /// Load-continuation steps.
    pub load_steps: usize,
    /// Newton iterations over all steps.
    pub iterations: usize,
}

/// Relative precision of a reported stability limit (a load fraction, or a sweep's swept value).
pub const LIMIT_PRECISION: f64 = 1e-6;

/// Most continuation steps of one bisection probe: a probe below the limit
/// is a short, smooth path; one beyond it has lost stability within its
/// first steps, and need not follow what comes after.
pub const PROBE_STEPS: usize = 100;

/// The shift of the multiplier block of the Newton matrix (see the module docs).
const MULTIPLIER_SHIFT: f64 = 1e-10;

/// The share of the joints' elastic stiffness a state must keep to count
/// as far from instability ([`solver::Problem::far_from_instability`]).
const FAR_MARGIN: f64 = 0.5;

/// The reusable buffers of a mechanism's equilibrium problem (the Data;
/// the [`Mechanism`] is the Model): frames, the assembled Lagrangian, the
/// load derivative and the stability test's matrices. Once made by
/// [`Workspace::new`], evaluating [`Kkt`] (residual, Jacobian, load
/// derivative) allocates nothing, and neither does its stability test
/// when the mechanism has no closures.
#[derive(Debug, Clone, Default)]
pub struct Workspace {
    dof: usize,
    constraints: usize,
    frames: Frames,
    assembly: Assembly,
    load_gradient: DVector<f64>,
    mu: Vec<f64>,
    loads: Loads,
    /// $n\times n$ column-major: the scaled stiffness and its Cholesky copy.
    stiffness: Vec<f64>,
    scratch: Vec<f64>,
    /// The closure test's $\tilde G^T$ ($n\times m$), its Householder
    /// reflections ($n\times m$), $\tilde Z$ and $\tilde H\tilde Z$ ($n\times(n-m)$),
    /// $\tilde H$ ($n\times n$), a Gram matrix ($m\times m$) and $\sqrt{1/k_i}$ ($n$).
    closure_t: Vec<f64>,
    reflections: Vec<f64>,
    basis: Vec<f64>,
    product: Vec<f64>,
    hessian: Vec<f64>,
    gram: Vec<f64>,
    /// $S = \operatorname{diag}(\sqrt{1/k_i})$, set with the row scales by `Kkt::fitted`.
    root_scale: Vec<f64>,
    /// Body angles of two states, for [`solver::Problem::distance`].
    angles: RefCell<[Vec<f64>; 2]>,
    /// The tree's $O(n)$ factorization of the Hessian ([`super::tree`]).
    tree: Tree,
    /// The joint of each coordinate.
    joint_of: Vec<usize>,
    /// The solver core's buffers, kept between solves.
    solver: Option<solver::Workspace<f64>>,
    /// The joints these buffers were made for.
    joints: Vec<super::JointSpec>,
    /// The last problem's scales and loads.
    spare: Spare,
    /// The loads of a [`solve_with`]: none, and the mechanism's.
    given: [Loads; 2],
    /// The unknowns of the assembled start of a [`solve_with`].
    start_x: Vec<f64>,
    /// The coordinates at which `frames` and the assembly's $c$ and $G$
    /// were last evaluated, if `assembled`.
    assembled_at: Vec<f64>,
    assembled: bool,
    /// The assembled start of the last [`solve_with`], for the next one.
    start: StartCache,
}

/// The assembled, unloaded start of a [`solve_with`] and what made it: it
/// depends on the joints, the closures and the settings, and on the loads
/// only through the Newton tolerance (tolerance × [`solver::Problem::scale`]),
/// since every load is zero at $\lambda = 0$.
#[derive(Debug, Clone, Default)]
struct StartCache {
    /// Whether the fields below hold a start.
    valid: bool,
    closures: Vec<Closure>,
    settings: Option<Settings>,
    /// The Newton tolerance it was converged to.
    tolerance: f64,
    report: Option<solver::NewtonReport>,
    stable: bool,
    /// The unknowns, the Jacobian and the frames there.
    x: Vec<f64>,
    jacobian: Vec<f64>,
    frames: Frames,
}

impl StartCache {
    /// Whether the start of `m` (whose joints the workspace was made for)
    /// under `settings`, converged to `tolerance`, is this one: the same
    /// closures and settings, and either the
    /// same tolerance or a start that was converged before any iteration
    /// to within `tolerance` (Newton would stop there again).
    fn holds(&self, m: &Mechanism, settings: &Settings, tolerance: f64) -> Option<(solver::NewtonReport, bool)> {
        let report = self.report.filter(|_| self.valid)?;
        let same_tolerance = tolerance == self.tolerance || (report.iterations == 0 && report.residual <= tolerance);
        (same_tolerance && self.settings == Some(*settings) && self.closures == m.closures)
            .then_some((report, self.stable))
    }

    /// Keeps the start `x` of `m` (Jacobian `jacobian`, frames `frames`)
    /// that Newton reached as `report` says, converged to `tolerance` under
    /// `settings`, with stability `stable`; allocates only the first time
    /// and where the closures changed.
    #[allow(clippy::too_many_arguments)]
    fn keep(
        &mut self,
        m: &Mechanism,
        settings: &Settings,
        tolerance: f64,
        report: solver::NewtonReport,
        stable: bool,
        x: &[f64],
        jacobian: &[f64],
        frames: &Frames,
    ) {
        if (self.frames.bodies.len(), self.frames.joints.len()) != (frames.bodies.len(), frames.joints.len()) {
            self.frames = frames.clone();
        } else {
            self.frames.copy_from(frames);
        }
        if self.closures != m.closures {
            self.closures.clone_from(&m.closures);
        }
        self.x.clear();
        self.x.extend_from_slice(x);
        self.jacobian.clear();
        self.jacobian.extend_from_slice(jacobian);
        self.settings = Some(*settings);
        self.tolerance = tolerance;
        self.report = Some(report);
        self.stable = stable;
        self.valid = true;
    }
}

impl Workspace {
    /// Buffers for `m`.
    pub fn new(m: &Mechanism) -> Self {
        let (n, rows) = (m.dof(), m.constraints());
        Workspace {
            dof: n,
            constraints: rows,
            frames: Frames::new(m),
            assembly: Assembly::new(m),
            load_gradient: DVector::zeros(n),
            mu: vec![0.0; rows],
            loads: m.loads(),
            stiffness: vec![0.0; n * n],
            scratch: vec![0.0; n * n],
            closure_t: vec![0.0; n * rows],
            reflections: vec![0.0; n * rows],
            basis: vec![0.0; n * n.saturating_sub(rows)],
            product: vec![0.0; n * n.saturating_sub(rows)],
            hessian: vec![0.0; n * n],
            gram: vec![0.0; rows * rows],
            root_scale: vec![0.0; n],
            angles: RefCell::new([vec![0.0; m.bodies.len()], vec![0.0; m.bodies.len()]]),
            tree: Tree::new(m),
            joint_of: m
                .joints
                .iter()
                .enumerate()
                .flat_map(|(i, j)| std::iter::repeat_n(i, j.kind.joint().dof()))
                .collect(),
            solver: None,
            joints: m.joints.clone(),
            spare: Spare::default(),
            given: Default::default(),
            start_x: vec![0.0; n + rows],
            assembled_at: vec![0.0; n],
            assembled: false,
            start: StartCache::default(),
        }
    }

    /// The solver core's buffers for `dim` unknowns, kept ones if they fit.
    fn solver(&mut self, dim: usize) -> solver::Workspace<f64> {
        self.solver.take().filter(|w| w.dim() == dim).unwrap_or_else(|| solver::Workspace::new(dim))
    }

    /// Whether these buffers were made for `m`'s joints (whose states
    /// carry each joint's constant stiffness and tables) and fit its shape.
    fn fits(&self, m: &Mechanism) -> bool {
        self.joints == m.joints
            && self.dof == m.dof()
            && self.constraints == m.constraints()
            && self.frames.bodies.len() == m.bodies.len()
            && self.frames.joints.len() == m.joints.len()
            && self.loads.tension.len() == m.tendons.len()
            && self.loads.force.len() == m.forces.len()
    }
}

/// The buffers a [`Kkt`] works in: its own, or a caller's, borrowed for
/// the problem's life (moving a [`Workspace`] copies a few kilobytes).
#[derive(Debug)]
enum Buffers<'a> {
    Owned(Box<Workspace>),
    Borrowed(&'a mut Workspace),
}

impl std::ops::Deref for Buffers<'_> {
    type Target = Workspace;
    fn deref(&self) -> &Workspace {
        match self {
            Buffers::Owned(w) => w,
            Buffers::Borrowed(w) => w,
        }
    }
}

impl std::ops::DerefMut for Buffers<'_> {
    fn deref_mut(&mut self) -> &mut Workspace {
        match self {
            Buffers::Owned(w) => w,
            Buffers::Borrowed(w) => w,
        }
    }
}

impl Clone for Buffers<'_> {
    fn clone(&self) -> Self {
        Buffers::Owned(Box::new(Workspace::clone(self)))
    }
}

/// A problem's scales and loads ([`Kkt`]), kept for the next problem.
#[derive(Debug, Clone, Default)]
struct Spare {
    vectors: [Vec<f64>; 4],
    loads: [Loads; 3],
}

/// `from` into `to`, in `to`'s buffers.
fn copy_loads(from: &Loads, to: &mut Loads) {
    to.tension.clear();
    to.tension.extend_from_slice(&from.tension);
    to.force.clear();
    to.force.extend_from_slice(&from.force);
    to.gravity = from.gravity;
}

/// The KKT conditions of a mechanism under the loads
/// $\text{from} + \lambda(\text{to} - \text{from})$, as a [`solver::Problem`].
///
/// Unknowns $x = (q, \nu)$ with the multipliers scaled to the joints,
/// $\mu_i = s_i\nu_i$ ($s_i = k/\ell$ for position rows, $k$ for angle
/// rows; $k$ the stiffest joint's diagonal stiffness in N·m/rad, a slider's
/// N/m times $\ell^2$; $\ell$ the mechanism's length). Residual: each
/// coordinate's row of $\nabla V + G^T\mu$ divided by that coordinate's
/// stiffness (radians, or metres, of the joint alone; a free joint's by
/// $k$), each closure row divided by $\ell$ (position) or 1 (angle):
/// dimensionless, unit "relative". Arc-length weights: 1 for angles,
/// $1/\ell$ for slider travel, 0 for multipliers.
#[derive(Debug, Clone)]
pub struct Kkt<'a> {
    mechanism: &'a Mechanism,
    from: Loads,
    to: Loads,
    change: Loads,
    /// $1/k_i$ per coordinate row.
    row_scale: Vec<f64>,
    /// $1/\ell$ or 1 per closure row.
    closure_scale: Vec<f64>,
    /// $s_i$ per closure row.
    multiplier_scale: Vec<f64>,
    weight: Vec<f64>,
    length: f64,
    scale: f64,
    /// Smallest relative stiffness of a stable state.
    margin: f64,
    /// Whether the Hessian has the tree's form ([`super::tree`]): no
    /// closures, no tendons. Then Newton steps, tangents and stability
    /// tests factor in $O(n)$.
    tree: bool,
    work: Buffers<'a>,
}

impl<'a> Kkt<'a> {
    /// The problem of moving `m` from `from` to `to` (both validated), for
    /// a solver run with `settings` (whose tolerance sets the stability margin).
    pub fn new(m: &'a Mechanism, from: &Loads, to: &Loads, settings: &Settings) -> Result<Self> {
        Self::with_workspace(m, from, to, settings, Workspace::new(m))
    }

    /// [`Kkt::new`] with the buffers `work` (made for `m` by [`Workspace::new`]).
    pub fn with_workspace(
        m: &'a Mechanism,
        from: &Loads,
        to: &Loads,
        settings: &Settings,
        work: Workspace,
    ) -> Result<Self> {
        if !work.fits(m) {
            return Err(Error::invalid("workspace", work.dof, "was made for another mechanism"));
        }
        Self::fitted(m, from, to, settings, Buffers::Owned(Box::new(work)))
    }

    /// [`Kkt::with_workspace`] with `work` known to fit `m`.
    fn fitted(m: &'a Mechanism, from: &Loads, to: &Loads, settings: &Settings, work: Buffers<'a>) -> Result<Self> {
        settings.validate()?;
        from.validate(m)?;
        to.validate(m)?;
        let n = m.dof();
        let length = m.size();
        // Diagonal stiffness of each coordinate (constant for every joint
        // kind, so any state's), and the factor to N·m/rad: 1 for angles,
        // ℓ² for slider travel; in the buffers of the last problem.
        let mut work = work;
        let Spare {
            vectors: [mut row_scale, mut weight, mut closure_scale, mut multiplier_scale],
            loads: [mut from_, mut to_, mut change],
        } = std::mem::take(&mut work.spare);
        let (stiffness, unit) = (&mut row_scale, &mut weight);
        stiffness.clear();
        stiffness.resize(n, 0.0);
        unit.clear();
        unit.resize(n, 1.0);
        for (j, s) in m.joints.iter().zip(&work.frames.joints) {
            for i in 0..s.gradient.len() {
                stiffness[j.offset + i] = s.stiffness[(i, i)];
            }
            if j.kind.joint().is_translation() {
                unit[j.offset] = length * length;
            }
        }
        let moments = || stiffness.iter().zip(unit.iter()).map(|(k, u)| k * u);
        let k_max = moments().fold(0.0, f64::max);
        let k_max = if k_max > 0.0 { k_max } else { 1.0 };
        let k_min = moments().filter(|&k| k > 0.0).fold(k_max, f64::min);
        // A free coordinate is measured against the stiffest joint.
        for (k, u) in row_scale.iter_mut().zip(weight.iter_mut()) {
            *k = if *k > 0.0 { 1.0 / *k } else { *u / k_max };
            *u = 1.0 / u.sqrt();
        }
        // S = diag(√(1/k_i)) of the stability tests, once per problem.
        work.root_scale.clear();
        work.root_scale.extend(row_scale.iter().map(|r| r.sqrt()));
        closure_scale.clear();
        multiplier_scale.clear();
        for c in &m.closures {
            for row in 0..c.equations() {
                let position = row < 2;
                closure_scale.push(if position { 1.0 / length } else { 1.0 });
                multiplier_scale.push(if position { k_max / length } else { k_max });
            }
        }
        // Largest load, as a moment, in radians of the softest joint.
        let magnitude = |l: &Loads| {
            let forces: f64 = l.force.iter().map(|f| f[0].hypot(f[1]) * length + f[2].abs()).sum();
            let tendons: f64 = l.tension.iter().map(|t| t * length).sum();
            let mass: f64 = m.bodies.iter().map(|b| b.mass).sum();
            forces + tendons + mass * l.gravity[0].hypot(l.gravity[1]) * length
        };
        let scale = 1.0 + (magnitude(from) + magnitude(to)) / k_min;
        if !scale.is_finite() {
            return Err(Error::invalid(
                "loads",
                format!("{:.3e}", scale - 1.0),
                "are too large for the joints' stiffness to be represented",
            ));
        }
        copy_loads(from, &mut from_);
        copy_loads(to, &mut to_);
        copy_loads(to, &mut change);
        change.tension.iter_mut().zip(&from.tension).for_each(|(b, a)| *b -= a);
        change.force.iter_mut().zip(&from.force).for_each(|(b, a)| (0..3).for_each(|i| b[i] -= a[i]));
        change.gravity = std::array::from_fn(|i| to.gravity[i] - from.gravity[i]);
        Ok(Self {
            mechanism: m,
            from: from_,
            to: to_,
            change,
            row_scale,
            closure_scale,
            multiplier_scale,
            weight,
            length,
            scale,
            margin: settings.tolerance.sqrt(),
            tree: m.closures.is_empty() && m.tendons.is_empty() && Tree::applies(m),
            work,
        })
    }

    /// The buffers, for the next problem on the same mechanism.
    pub fn into_workspace(self) -> Workspace {
        match self.release() {
            Buffers::Owned(w) => *w,
            Buffers::Borrowed(w) => std::mem::take(w),
        }
    }

    /// The buffers, with this problem's scales and loads put back for the next problem.
    fn release(self) -> Buffers<'a> {
        let mut work = self.work;
        work.spare = Spare {
            vectors: [self.row_scale, self.weight, self.closure_scale, self.multiplier_scale],
            loads: [self.from, self.to, self.change],
        };
        work
    }

    /// The unknowns $(q, \nu)$ of coordinates `q` and multipliers `mu`.
    pub fn state(&self, q: &[f64], mu: &[f64]) -> Vec<f64> {
        q.iter().copied().chain(mu.iter().zip(&self.multiplier_scale).map(|(m, s)| m / s)).collect()
    }

    /// The multipliers $\mu$ (N, N·m) of the unknowns `x`.
    pub fn multipliers(&self, x: &[f64]) -> Vec<f64> {
        x[self.mechanism.dof()..].iter().zip(&self.multiplier_scale).map(|(v, s)| v * s).collect()
    }

    /// The loads at load factor `lambda`.
    pub fn loads(&self, lambda: f64) -> Loads {
        self.from.lerp(&self.to, lambda)
    }

    /// $\partial_\lambda r$ into `d`, at the frames last evaluated, or at
    /// the kept start's ([`StartCache`]) if `at_start`: the gradient of the
    /// load change's potential, scaled as the residual.
    fn load_derivative(&mut self, d: &mut [f64], at_start: bool) -> Result<()> {
        let m = self.mechanism;
        let n = m.dof();
        let Workspace { frames, start, assembly: a, load_gradient, .. } = &mut *self.work;
        let f = if at_start { &start.frames } else { frames };
        load_gradient.as_mut_slice().fill(0.0);
        add_loads(m, f, &self.change, load_gradient, None, &mut a.points, &mut a.weights)?;
        for i in 0..n {
            d[i] = load_gradient[i] * self.row_scale[i];
        }
        d[n..].fill(0.0);
        Ok(())
    }

    /// [`solver::Problem::stable`] with closures on dense matrices, the
    /// null space by singular values: the test where $G$'s rows are not
    /// independent by a wide margin (redundant closures), and the
    /// reference of [`Kkt::constrained_definite`].
    fn stable_dense(&mut self, x: &[f64], lambda: f64, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        let g = DMatrix::from_fn(rows, n, |i, c| jacobian[c * size + n + i] / self.closure_scale[i]);
        let mut h = DMatrix::from_fn(n, n, |r, c| jacobian[c * size + r] / self.row_scale[r]);
        // settle changes nothing where G has full row rank: skip its frames.
        if rows > 0 && !full_row_rank(&g) {
            let mu = self.multipliers(x);
            let Workspace { frames: f, loads, assembled, .. } = &mut *self.work;
            *assembled = false;
            frames_into(m, &x[..n], f);
            self.from.lerp_into(&self.to, lambda, loads);
            let settled = settle(m, f, &g, &mu, loads);
            if settled != mu {
                let change: Vec<f64> = settled.iter().zip(&mu).map(|(a, b)| a - b).collect();
                h += closure_hessian(m, f, &change);
            }
        }
        // In joint-relative coordinates: H̃ = S H S, G̃ = G S, S = diag(1/√k_i).
        let s: Vec<f64> = self.row_scale.iter().map(|r| r.sqrt()).collect();
        let h = DMatrix::from_fn(n, n, |r, c| h[(r, c)] * s[r] * s[c]);
        let g = DMatrix::from_fn(rows, n, |i, c| g[(i, c)] * s[c]);
        let z = linalg::null_space(&g);
        let mut k = constrained(&h, &z);
        for i in 0..k.nrows() {
            k[(i, i)] -= self.margin;
        }
        linalg::is_positive_definite(&k)
    }

    /// Whether the rows of $G$ (read from `jacobian`) are independent by a
    /// wide margin ([`linalg::columns_independent`]), so that no multiplier
    /// is indeterminate; leaves $G^T$ ($n\times$ rows) in the workspace.
    fn closure_rows_independent(&mut self, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        if rows > n {
            return false;
        }
        let Workspace { closure_t: a, gram, .. } = &mut *self.work;
        for i in 0..rows {
            for c in 0..n {
                a[i * n + c] = jacobian[c * size + n + i] / self.closure_scale[i];
            }
        }
        linalg::columns_independent(a, n, rows, gram)
    }

    /// $\tilde Z^T\thinspace S(H - wK)S\thinspace\tilde Z - \text{margin}\thinspace I$ positive
    /// definite, on the workspace's buffers without allocating: $H$ the
    /// Hessian block of `jacobian`, $K$ the joints' elastic stiffness,
    /// $S = \operatorname{diag}(1/\sqrt{k_i})$ and $\tilde Z$ the null space of
    /// $\tilde G = GS$ by Householder reflections. For a $G$ whose rows
    /// [`Kkt::closure_rows_independent`] has just found independent (its
    /// $G^T$ is read from the workspace); `None` unless $\tilde G$'s rows are
    /// independent by a wide margin too ([`linalg::columns_independent`]):
    /// then no multiplier is indeterminate and this is the test of [`Kkt::stable_dense`].
    fn constrained_definite(&mut self, jacobian: &[f64], w: f64, margin: f64) -> Option<bool> {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        if rows > n {
            return None;
        }
        let p = n - rows;
        let Workspace {
            closure_t: a,
            reflections,
            basis,
            product,
            hessian,
            gram,
            root_scale: s,
            stiffness: k,
            scratch,
            frames,
            joint_of,
            ..
        } = &mut *self.work;
        // G̃ᵀ = S Gᵀ.
        for i in 0..rows {
            for c in 0..n {
                a[i * n + c] *= s[c];
            }
        }
        if !linalg::columns_independent(a, n, rows, gram) {
            return None;
        }
        linalg::null_space_of_transpose(a, n, rows, basis, reflections);
        let elastic = |r: usize, c: usize| {
            let j = joint_of[r];
            if w == 0.0 || joint_of[c] != j {
                return 0.0;
            }
            let o = m.joints[j].offset;
            w * frames.joints[j].stiffness[(r - o, c - o)]
        };
        // H̃ = S(H − wK)S, H̃ Z̃, then Z̃ᵀ H̃ Z̃ symmetrized.
        for c in 0..n {
            for r in 0..n {
                hessian[c * n + r] = (jacobian[c * size + r] / self.row_scale[r] - elastic(r, c)) * s[r] * s[c];
            }
        }
        for j in 0..p {
            let z = &basis[j * n..(j + 1) * n];
            let hz = &mut product[j * n..(j + 1) * n];
            hz.fill(0.0);
            for (c, zc) in z.iter().enumerate() {
                for (v, h) in hz.iter_mut().zip(&hessian[c * n..(c + 1) * n]) {
                    *v += h * zc;
                }
            }
        }
        let k = &mut k[..p * p];
        for j in 0..p {
            for i in 0..p {
                k[j * p + i] = (0..n).map(|r| basis[i * n + r] * product[j * n + r]).sum();
            }
        }
        for j in 0..p {
            for i in 0..j {
                let v = (k[j * p + i] + k[i * p + j]) * 0.5;
                k[j * p + i] = v;
                k[i * p + j] = v;
            }
            k[j * p + j] -= margin;
        }
        Some(linalg::positive_definite(k, p, &mut scratch[..p * p]))
    }

    /// A sufficient condition for the closure stability test, in $O(n)$ by
    /// the tree's pivots ([`super::tree`]): $\tilde H - (\text{margin} + \epsilon)I$
    /// positive definite on every motion, not only the admissible ones.
    /// The smallest eigenvalue of $\tilde Z^T\tilde H\tilde Z$ ($\tilde Z$
    /// orthonormal) is at least that of $\tilde H$ (a Rayleigh quotient over
    /// a subspace), and $\epsilon = 10^{-12}\sum_i(\tilde H_{ii} - \text{margin})^+$
    /// bounds the rounding threshold of [`linalg::positive_definite`] on the
    /// projected matrix ($10^{-12}$ of its largest diagonal entry, at most
    /// its trace), so `true` is the verdict of [`Kkt::constrained_definite`]
    /// too. Applies where the Hessian has the tree's form (the closures'
    /// terms are point terms; tendons couple branches) and the rows of
    /// $G$ are independent by a wide margin, so no multiplier is
    /// indeterminate and the Hessian at the solver's multipliers is the
    /// one stability is judged at (the caller's check,
    /// [`Kkt::closure_rows_independent`]); `false` leaves the decision to
    /// the projected test.
    fn hessian_definite(&mut self, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        if !m.tendons.is_empty() {
            return false;
        }
        let Workspace { tree, root_scale: s, .. } = &mut *self.work;
        let s: &[f64] = s;
        let scaled = |r: usize, c: usize| jacobian[c * size + r] / self.row_scale[r] * s[r] * s[c];
        let trace: f64 = (0..n).map(|i| (scaled(i, i) - self.margin).max(0.0)).sum();
        if !(trace > 0.0 && trace.is_finite()) {
            return false;
        }
        let shift = self.margin + 1e-12 * trace;
        tree.factor(|r, c| scaled(r, c) - if r == c { shift } else { 0.0 }, s, true) == Some(true)
    }
}

impl solver::Problem<f64> for Kkt<'_> {
    fn dim(&self) -> usize {
        self.mechanism.dof() + self.mechanism.constraints()
    }

    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        residual: &mut [f64],
        jacobian: Option<&mut [f64]>,
        dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        let q = &x[..n];
        let Workspace { frames: f, assembly: a, mu, loads, assembled_at, assembled, .. } = &mut *self.work;
        for ((m, v), s) in mu.iter_mut().zip(&x[n..]).zip(&self.multiplier_scale) {
            *m = v * s;
        }
        *assembled = false;
        frames_into(m, q, f);
        self.from.lerp_into(&self.to, lambda, loads);
        assemble_into(m, f, mu, loads, jacobian.is_some(), a)?;
        assembled_at.copy_from_slice(q);
        *assembled = true;
        // Column-major: G's column i holds coordinate i's closure rows.
        let g = a.closure_jacobian.as_slice();
        for i in 0..n {
            let mut force = a.gradient[i];
            for (gk, mu) in g[i * rows..(i + 1) * rows].iter().zip(mu.iter()) {
                force += gk * mu;
            }
            residual[i] = force * self.row_scale[i];
        }
        for i in 0..rows {
            residual[n + i] = a.closure[i] * self.closure_scale[i];
        }
        if !residual.iter().all(|r| r.is_finite()) {
            return Err(Error::Singular { what: "mechanism equilibrium: a non-finite generalized force".into() });
        }
        // (Column chunks of size 0 would panic; a mechanism without coordinates has no Jacobian.)
        if let Some(jac) = jacobian.filter(|_| size > 0) {
            let hessian = a.hessian.as_slice();
            let (left, right) = jac.split_at_mut(n * size);
            for (c, column) in left.chunks_exact_mut(size).enumerate() {
                let (top, bottom) = column.split_at_mut(n);
                for ((j, h), s) in top.iter_mut().zip(&hessian[c * n..(c + 1) * n]).zip(&self.row_scale) {
                    *j = h * s;
                }
                for ((j, g), s) in bottom.iter_mut().zip(&g[c * rows..(c + 1) * rows]).zip(&self.closure_scale) {
                    *j = g * s;
                }
            }
            for (i, column) in right.chunks_exact_mut(size).enumerate() {
                let (top, bottom) = column.split_at_mut(n);
                let s = self.multiplier_scale[i];
                for (c, (j, r)) in top.iter_mut().zip(&self.row_scale).enumerate() {
                    *j = g[c * rows + i] * s * r;
                }
                bottom.fill(0.0);
                bottom[i] = -MULTIPLIER_SHIFT;
            }
        }
        if let Some(d) = dlambda {
            self.load_derivative(d, false)?;
        }
        Ok(())
    }

    /// $Z^T\nabla^2 L\thinspace Z$ positive definite with the margin of the module
    /// docs: in coordinates $\tilde q_i = \sqrt{k_i}\thinspace q_i$ (each joint's own
    /// stiffness 1), $\tilde Z^T\tilde H\tilde Z - \sqrt{\text{tolerance}}\thinspace I$
    /// positive definite, $\tilde Z$ = [`linalg::null_space`]$(\tilde G)$.
    /// Where redundant closures leave part of $\mu$ indeterminate, that
    /// part is taken with the least transmitted force first (see [`Solution::multipliers`]).
    /// A whole Hessian that passes the test passes it on every subspace:
    /// that is tried first, by the tree's pivots in $O(n)$.
    fn stable(&mut self, x: &[f64], lambda: f64, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        if rows == 0 && self.tree {
            // Z = I, and the tree's pivots: positive_definite's test of the
            // matrix below, in O(n).
            let Workspace { tree, root_scale: s, .. } = &mut *self.work;
            let s: &[f64] = s;
            let scaled = |r: usize, c: usize| jacobian[c * size + r] / self.row_scale[r] * s[r] * s[c];
            let scale = (0..n).map(|i| scaled(i, i) - self.margin).fold(0.0_f64, f64::max);
            if n == 0 {
                return true;
            }
            if !(scale > 0.0 && scale.is_finite()) {
                return false;
            }
            let shift = self.margin + 1e-12 * scale;
            return tree.factor(|r, c| scaled(r, c) - if r == c { shift } else { 0.0 }, s, true) == Some(true);
        }
        if rows == 0 {
            // Z = I: the scaled, symmetrized Hessian itself, in the workspace.
            let Workspace { stiffness: k, scratch, root_scale: s, .. } = &mut *self.work;
            let scaled = |r: usize, c: usize| jacobian[c * size + r] / self.row_scale[r] * s[r] * s[c];
            for c in 0..n {
                for r in 0..n {
                    k[c * n + r] = (scaled(r, c) + scaled(c, r)) * 0.5;
                }
                k[c * n + c] -= self.margin;
            }
            return linalg::positive_definite(k, n, scratch);
        }
        if !self.closure_rows_independent(jacobian) {
            return self.stable_dense(x, lambda, jacobian);
        }
        if self.hessian_definite(jacobian) {
            return true;
        }
        if let Some(definite) = self.constrained_definite(jacobian, 0.0, self.margin) {
            return definite;
        }
        self.stable_dense(x, lambda, jacobian)
    }

    /// Without closures: $\nabla^2 V - \tfrac12 K$ positive definite, $K$
    /// the joints' elastic stiffness (as a single flexure's
    /// [`crate::statics`] does), by the tree's pivots or by Cholesky.
    fn far_from_instability(&mut self, _x: &[f64], _lambda: f64, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let n = m.dof();
        if m.constraints() > 0 || n == 0 {
            return false;
        }
        let Workspace { tree, frames, stiffness, joint_of, .. } = &mut *self.work;
        let elastic = |r: usize, c: usize| {
            let j = joint_of[r];
            if joint_of[c] != j {
                return 0.0;
            }
            let o = m.joints[j].offset;
            frames.joints[j].stiffness[(r - o, c - o)]
        };
        let entry = |r: usize, c: usize| jacobian[c * n + r] / self.row_scale[r] - FAR_MARGIN * elastic(r, c);
        if self.tree {
            return tree.factor(entry, &[], true) == Some(true);
        }
        for c in 0..n {
            for r in 0..n {
                stiffness[c * n + r] = entry(r, c);
            }
        }
        linalg::cholesky(stiffness, n)
    }

    fn factor(&mut self, jacobian: &[f64]) -> bool {
        let n = self.mechanism.dof();
        if !self.tree || n == 0 {
            return false;
        }
        let rows = &self.row_scale;
        self.work.tree.factor(|r, c| jacobian[c * n + r] / rows[r], &[], false).is_some()
    }

    fn solve_factored(&mut self, b: &mut [f64]) {
        // ∂r/∂q = diag(row_scale) ∇²V.
        for (b, r) in b.iter_mut().zip(&self.row_scale) {
            *b /= r;
        }
        self.work.tree.solve(b);
    }

    /// The largest rotation of a body, or of a flexure's cross-section
    /// relative to its root, and a slider's travel over the mechanism's length.
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        let n = self.mechanism.dof();
        let mut buffers = self.work.angles.borrow_mut();
        crate::mechanism::kinematics::distance(self.mechanism, &a[..n], &b[..n], self.length, &mut buffers)
    }

    fn scale(&self) -> f64 {
        self.scale
    }

    fn unit(&self) -> &'static str {
        "relative"
    }

    fn name(&self) -> &'static str {
        "mechanism equilibrium"
    }

    fn weight(&self, i: usize) -> f64 {
        self.weight.get(i).copied().unwrap_or(0.0)
    }
}

/// $Z^T H Z$, symmetrized.
pub(super) fn constrained(h: &DMatrix<f64>, z: &DMatrix<f64>) -> DMatrix<f64> {
    let k = z.transpose() * h * z;
    (&k + k.transpose()) * 0.5
}

/// The solution at the unknowns `x`, under the problem's loads at the
/// end of its path (`end`) or at its start, computed in the problem's
/// buffers: the frames and $G$ of the last evaluation if it was at `x`.
fn solution(problem: &mut Kkt, x: &[f64], end: bool, path: &solver::Path) -> Result<Solution> {
    let m = problem.mechanism;
    let n = m.dof();
    let (q, mu) = (&x[..n], problem.multipliers(x));
    let loads = if end { problem.to.clone() } else { problem.from.clone() };
    let Workspace { frames: f, assembly: a, assembled_at, assembled, closure_t, gram, .. } = &mut *problem.work;
    if !(*assembled && assembled_at[..] == *q) {
        *assembled = false;
        frames_into(m, q, f);
        a.closures_at(m, f);
    }
    // settle changes nothing where G has independent rows: it need not be called.
    let g = &a.closure_jacobian;
    let rows = g.nrows();
    for i in 0..rows {
        for c in 0..n {
            closure_t[i * n + c] = g[(i, c)];
        }
    }
    let multipliers =
        if linalg::columns_independent(closure_t, n, rows, gram) { mu } else { settle(m, f, g, &mu, &loads) };
    // + 0.0: an empty sum is −0.
    let energy = f.joints.iter().map(|s| s.energy).sum::<f64>() + 0.0;
    if !(energy.is_finite() && q.iter().chain(&multipliers).all(|v| v.is_finite())) {
        return Err(Error::Singular { what: "mechanism equilibrium: the solution is not finite".into() });
    }
    Ok(Solution {
        q: q.to_vec(),
        multipliers,
        loads,
        energy,
        stable: path.stable,
        limit: path.limit,
        residual: path.residual,
        load_steps: path.steps,
        iterations: path.iterations,
    })
}

/// Equilibrium under `to`, continued from `start` (an equilibrium under
/// `start.loads`) by the shared continuation.
///
/// A snap-through that ends in a stable state is an answer, with
/// [`Solution::limit`] the fraction of the load change where stability was
/// first lost. A path that loses stability and does not reach a stable
/// state at the full load (it ends unstable, or stops after the loss) is
/// [`Error::Unstable`] at that fraction. The fraction is the continuation's
/// ([`solver::Path::limit`]) refined by bisection to a relative
/// [`LIMIT_PRECISION`] (as [`super::sweep::sweep`] does between two values).
pub fn solve_between(m: &Mechanism, start: &Solution, to: &Loads, settings: &Settings) -> Result<Solution> {
    solve_between_in(m, start, to, settings, &mut Workspace::new(m))
}

fn solve_between_in(
    m: &Mechanism,
    start: &Solution,
    to: &Loads,
    settings: &Settings,
    work: &mut Workspace,
) -> Result<Solution> {
    let found = follow_in(m, start, to, settings, work);
    refine_limit(m, start, to, settings, found)
}

/// The path from `start` to `to` as [`solve_between`] reports it, from
/// what [`follow`] `found`: a lost stability's load fraction refined by bisection.
fn refine_limit(
    m: &Mechanism,
    start: &Solution,
    to: &Loads,
    settings: &Settings,
    found: Result<Solution>,
) -> Result<Solution> {
    if !lost(&found, start.stable) {
        return found;
    }
    let limit = first_loss(m, start, to, settings, |lo, hi| hi - lo <= LIMIT_PRECISION * hi)?;
    match found {
        Ok(s) => Ok(Solution { limit: Some(limit), ..s }),
        Err(_) => Err(Error::Unstable { what: "mechanism equilibrium", load_fraction: limit }),
    }
}

/// Whether the path that `found` ends lost stability on the way (from a
/// start that was `stable`), so that its limit is refined.
fn lost(found: &Result<Solution>, stable: bool) -> bool {
    match found {
        Ok(s) => s.limit.is_some(),
        Err(Error::Unstable { load_fraction, .. }) => *load_fraction > 0.0 || stable,
        Err(_) => false,
    }
}

/// Where a path starts: a solution, or the assembled state at $\lambda = 0$
/// of the problem itself (its unknowns in [`Workspace::start_x`], reached by `path`).
enum Start<'s> {
    Given(&'s Solution),
    Assembled(&'s solver::Path),
}

/// [`solve_between`] with the continuation's own limit, unrefined.
pub(super) fn follow(m: &Mechanism, start: &Solution, to: &Loads, settings: &Settings) -> Result<Solution> {
    follow_in(m, start, to, settings, &mut Workspace::new(m))
}

/// [`follow`] in the buffers `work` (made for `m`).
fn follow_in(
    m: &Mechanism,
    start: &Solution,
    to: &Loads,
    settings: &Settings,
    work: &mut Workspace,
) -> Result<Solution> {
    check_sizes(m, &start.q, &start.multipliers, &start.loads)?;
    if !work.fits(m) {
        return Err(Error::invalid("workspace", work.dof, "was made for another mechanism"));
    }
    let mut problem = Kkt::fitted(m, &start.loads, to, settings, Buffers::Borrowed(work))?;
    let dim = solver::Problem::dim(&problem);
    let mut ws = problem.work.solver(dim);
    ws.x.iter_mut().zip(&start.q).for_each(|(x, q)| *x = *q);
    let n = m.dof();
    for ((x, mu), s) in ws.x[n..].iter_mut().zip(&start.multipliers).zip(&problem.multiplier_scale) {
        *x = mu / s;
    }
    let found = follow_path(m, Start::Given(start), &mut problem, &mut ws, settings);
    let mut work = problem.release();
    work.solver = Some(ws);
    found
}

fn follow_path(
    m: &Mechanism,
    start: Start,
    problem: &mut Kkt,
    ws: &mut solver::Workspace<f64>,
    settings: &Settings,
) -> Result<Solution> {
    let unstable =
        |limit: Option<f64>| Error::Unstable { what: "mechanism equilibrium", load_fraction: limit.unwrap_or(0.0) };
    match solver::continuation(problem, ws, settings) {
        Ok(path) if path.stable => solution(problem, &ws.x, true, &path),
        Ok(path) => Err(unstable(path.limit)),
        Err(e @ (Error::Interrupted { .. } | Error::InvalidParameter { .. })) => Err(e),
        // The start has a zero-stiffness motion along the load: name it.
        Err(Error::Singular { what }) if ws.limit.is_none() => Err(Error::Singular {
            what: match match start {
                Start::Given(s) => free_motion(m, s),
                Start::Assembled(path) => {
                    let x0 = problem.work.start_x.clone();
                    solution(problem, &x0, false, path).ok().and_then(|s| free_motion(m, &s))
                }
            } {
                Some(joints) => format!(
                    "mechanism equilibrium: the mechanism moves freely at the start ({joints}) and the load drives that motion: no equilibrium can be followed; give a joint on it a stiffness, or hold it with a closure"
                ),
                None => what,
            },
        }),
        Err(e) => match ws.limit {
            Some(limit) => Err(unstable(Some(limit))),
            None => Err(e),
        },
    }
}

/// The joints that move in a zero-stiffness motion of `s` (the constrained
/// stiffness's softest mode, if it is singular), as "joint \"a\" and joint \"b\"".
pub(super) fn free_motion(m: &Mechanism, s: &Solution) -> Option<String> {
    let (z, k) = stiffness(m, s).ok()?;
    if k.nrows() == 0 || linalg::is_positive_definite(&k) {
        return None;
    }
    let (_, soft) = linalg::softest_mode(&k)?;
    let motion = &z * soft;
    let largest = motion.amax();
    let names: Vec<String> = m
        .joints
        .iter()
        .filter(|j| (0..j.kind.joint().dof()).any(|i| motion[j.offset + i].abs() > 0.1 * largest))
        .map(|j| format!("joint {:?}", j.name))
        .collect();
    (!names.is_empty()).then(|| names.join(" and "))
}

/// The fraction of the load change from `start.loads` to `to` where the
/// path from `start` first loses stability, by bisection until
/// `precise(lo, hi)`: each probe continues from the last stable state, for
/// at most [`PROBE_STEPS`] steps, and at most 64 probes are made.
pub(super) fn first_loss(
    m: &Mechanism,
    start: &Solution,
    to: &Loads,
    settings: &Settings,
    precise: impl Fn(f64, f64) -> bool,
) -> Result<f64> {
    let settings = Settings { max_steps: settings.max_steps.min(PROBE_STEPS), ..*settings };
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut at = start.clone();
    for _ in 0..64 {
        if precise(lo, hi) {
            break;
        }
        let mid = 0.5 * (lo + hi);
        match follow(m, &at, &start.loads.lerp(to, mid), &settings) {
            Ok(s) if s.limit.is_none() => {
                lo = mid;
                at = s;
            }
            Ok(_) | Err(Error::Unstable { .. }) => hi = mid,
            Err(e) => return Err(e),
        }
    }
    Ok(0.5 * (lo + hi))
}

/// The unloaded, assembled configuration: the rest coordinates moved, if
/// the closures require it, to the nearest configuration that closes them.
pub fn assemble_unloaded(m: &Mechanism, settings: &Settings) -> Result<Solution> {
    assemble_in(m, settings, &mut Workspace::new(m))
}

/// [`assemble_unloaded`] in the buffers `work` (made for `m`).
fn assemble_in(m: &Mechanism, settings: &Settings, work: &mut Workspace) -> Result<Solution> {
    let zero = m.loads().zero_like();
    if !work.fits(m) {
        return Err(Error::invalid("workspace", work.dof, "was made for another mechanism"));
    }
    let mut problem = Kkt::fitted(m, &zero, &zero, settings, Buffers::Borrowed(work))?;
    let dim = solver::Problem::dim(&problem);
    let mut ws = problem.work.solver(dim);
    let found = assemble(&mut problem, &mut ws, settings);
    let mut work = problem.release();
    work.solver = Some(ws);
    found
}

/// The unloaded, assembled configuration, by Newton from rest on the
/// problem at $\lambda = 0$ (whose loads there must be zero), left in `ws`.
fn assemble(problem: &mut Kkt, ws: &mut solver::Workspace<f64>, settings: &Settings) -> Result<Solution> {
    let path = assembled(problem, ws, settings)?;
    solution(problem, &ws.x, false, &path)
}

/// [`assemble`] without the solution: how the path to it went.
fn assembled(problem: &mut Kkt, ws: &mut solver::Workspace<f64>, settings: &Settings) -> Result<solver::Path> {
    let m = problem.mechanism;
    ws.x.fill(0.0);
    m.rest_into(&mut ws.x[..m.dof()]);
    match solver::newton(problem, ws, 0.0, settings) {
        Ok(report) => {
            let stable = solver::Problem::stable(problem, &ws.x, 0.0, &ws.jacobian);
            Ok(solver::Path { stable, limit: None, steps: 0, iterations: report.iterations, residual: report.residual })
        }
        Err(e @ (Error::NoConvergence { .. } | Error::Singular { .. })) => Err(unassembled(m, problem.length, e)),
        Err(e) => Err(e),
    }
}

/// [`assembled`] for [`solve_with`]: the start the workspace keeps if it
/// is this problem's ([`StartCache::holds`]), with the load derivative of
/// this problem's loads; else solved, and kept.
fn assembled_kept(problem: &mut Kkt, ws: &mut solver::Workspace<f64>, settings: &Settings) -> Result<solver::Path> {
    let m = problem.mechanism;
    // The tolerance of solver::newton.
    let tolerance = settings.tolerance * solver::Problem::scale(problem);
    let path = |report: solver::NewtonReport, stable: bool| solver::Path {
        stable,
        limit: None,
        steps: 0,
        iterations: report.iterations,
        residual: report.residual,
    };
    if let Some((report, stable)) = problem.work.start.holds(m, settings, tolerance) {
        let Workspace { start, assembled, .. } = &mut *problem.work;
        ws.x.copy_from_slice(&start.x);
        ws.jacobian.copy_from_slice(&start.jacobian);
        // The workspace's frames are not the start's: the next evaluation makes them.
        *assembled = false;
        problem.load_derivative(ws.dlambda_mut(), true)?;
        ws.restore_start(report, stable);
        return Ok(path(report, stable));
    }
    let found = assembled(problem, ws, settings)?;
    let report = solver::NewtonReport { iterations: found.iterations, residual: found.residual };
    let Workspace { start, frames, .. } = &mut *problem.work;
    start.keep(m, settings, tolerance, report, found.stable, &ws.x, &ws.jacobian, frames);
    Ok(path(report, found.stable))
}

/// The error for closures that Newton could not close from rest: placed at
/// the closure open widest at rest (position gap over the mechanism's
/// `length`, plus angle gap), or `e` itself if all are closed there.
fn unassembled(m: &Mechanism, length: f64, e: Error) -> Error {
    let rest = frames(m, &m.rest());
    let (c, _) = closures(m, &rest);
    let mut row = 0;
    let mut widest: Option<(usize, f64, f64, f64)> = None;
    for (i, closure) in m.closures.iter().enumerate() {
        let gap = c[row].hypot(c[row + 1]);
        let turn = if closure.equations() == 3 { c[row + 2].abs() } else { 0.0 };
        let size = gap / length + turn;
        if size > widest.map_or(1e-9, |w| w.1) {
            widest = Some((i, size, gap, turn));
        }
        row += closure.equations();
    }
    let Some((i, _, gap, turn)) = widest else { return e };
    let name = |b: usize| &m.bodies[b].name;
    let what = match m.closures[i] {
        Closure::Weld { a, b, .. } => format!("weld of {:?} and {:?}", name(a), name(b)),
        Closure::Pin { a, b, .. } => format!("pin of {:?} and {:?}", name(a), name(b)),
    };
    Error::File {
        place: m.closure_place(i).to_string(),
        message: format!(
            "{what}: the closures cannot be assembled; at rest this one is open widest ({gap:.3e} m, {turn:.3e} rad), and from there {e}"
        ),
    }
}

/// Equilibrium under the mechanism's loads, by continuation from the
/// unloaded, assembled shape (see [`solve_between`] for the policy).
///
/// # Example
/// ```
/// use flexure::mechanism::{file::from_toml, statics::{solve, Settings}};
/// let m = from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n\
///      [[force]]\nbody = \"arm\"\nat = [0.0, 0.0]\nmoment = 0.5\n",
/// )
/// .unwrap();
/// let s = solve(&m, &Settings::default()).unwrap();
/// assert!(s.stable && (s.q[0] - 0.25).abs() < 1e-12); // M/k
/// ```
pub fn solve(m: &Mechanism, settings: &Settings) -> Result<Solution> {
    solve_with(m, settings, &mut Workspace::new(m))
}

/// [`solve`] in the buffers `work`, kept for the next solve on the same
/// mechanism (a workspace made for other joints is replaced). The
/// workspace also keeps the assembled, unloaded start and its stability,
/// reused while the closures and settings stay the same: a solve from a
/// kept workspace equals a fresh one to the bit.
///
/// # Example
/// ```
/// use flexure::mechanism::{file::from_toml, statics::{solve_with, Settings, Workspace}};
/// let m = from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n\
///      [[force]]\nbody = \"arm\"\nat = [0.0, 0.0]\nmoment = 0.5\n",
/// )
/// .unwrap();
/// let mut work = Workspace::new(&m);
/// for _ in 0..2 {
///     let s = solve_with(&m, &Settings::default(), &mut work).unwrap();
///     assert!(s.stable && (s.q[0] - 0.25).abs() < 1e-12); // M/k
/// }
/// ```
pub fn solve_with(m: &Mechanism, settings: &Settings, work: &mut Workspace) -> Result<Solution> {
    if !work.fits(m) {
        *work = Workspace::new(m);
    }
    // One problem from no load to the full load: assembled at λ = 0, then
    // continued from there without a second solve or stability test.
    let [mut zero, mut to] = std::mem::take(&mut work.given);
    m.loads_into(&mut to);
    copy_loads(&to, &mut zero);
    zero.scale(0.0);
    let mut problem = Kkt::fitted(m, &zero, &to, settings, Buffers::Borrowed(work))?;
    let dim = solver::Problem::dim(&problem);
    let mut ws = problem.work.solver(dim);
    // The start as a solution only if the path lost stability: for the refinement.
    let found = assembled_kept(&mut problem, &mut ws, settings).and_then(|path| {
        problem.work.start_x.copy_from_slice(&ws.x);
        ws.start_stable = Some(path.stable);
        let found = follow_path(m, Start::Assembled(&path), &mut problem, &mut ws, settings);
        if !lost(&found, path.stable) {
            return Ok((None, found));
        }
        let x0 = problem.work.start_x.clone();
        Ok((Some(solution(&mut problem, &x0, false, &path)?), found))
    });
    let mut buffers = problem.release();
    buffers.solver = Some(ws);
    buffers.given = [zero, to];
    drop(buffers);
    match found? {
        (Some(start), found) => refine_limit(m, &start, &work.given[1], settings, found),
        (None, found) => found,
    }
}

/// Frames of the solution.
pub fn body_frames(m: &Mechanism, s: &Solution) -> Frames {
    frames(m, &s.q)
}

/// $Z$ and the generalized stiffness on the admissible motions,
/// $Z^T\nabla^2 L\thinspace Z$ (Eq. 27, projected), at a solution.
pub fn stiffness(m: &Mechanism, s: &Solution) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    let a = lagrangian(m, &s.q, &s.multipliers, &s.loads)?;
    let z = linalg::null_space(&a.closure_jacobian);
    let k = constrained(&a.hessian, &z);
    Ok((z, k))
}

/// Compliance of the frame at `at` on `body` to a small extra load
/// $(M, F_x, F_y)$ there: $C = J Z (Z^T\nabla^2 L Z)^{-1} Z^T J^T$, order $(\phi, x, y)$.
///
/// # Example
/// ```
/// use flexure::mechanism::{file::from_toml, statics::{assemble_unloaded, compliance, Settings}};
/// // A sprung arm (k = 2 N·m/rad): its tip, 0.1 m out, yields l²/k sideways.
/// let m = from_toml("[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n").unwrap();
/// let s = assemble_unloaded(&m, &Settings::default()).unwrap();
/// let c = compliance(&m, &s, m.body("arm").unwrap(), [0.1, 0.0]).unwrap();
/// assert!((c[(0, 0)] - 0.5).abs() < 1e-15 && (c[(2, 2)] - 0.005).abs() < 1e-15);
/// ```
pub fn compliance(m: &Mechanism, s: &Solution, body: usize, at: [f64; 2]) -> Result<Matrix3<f64>> {
    if body >= m.bodies.len() {
        return Err(Error::invalid("body", body, "names no body of the mechanism"));
    }
    if !at.iter().all(|v| v.is_finite()) {
        return Err(Error::invalid("at", format!("{at:?}"), "must be finite"));
    }
    let (z, k) = stiffness(m, s)?;
    let not_definite = || Error::Singular {
        what: "the constrained stiffness is not positive definite: the equilibrium is unstable or a joint is free"
            .into(),
    };
    if !linalg::is_positive_definite(&k) {
        return Err(not_definite());
    }
    let chol = k.cholesky().ok_or_else(not_definite)?;
    let jz = point(m, &frames(m, &s.q), body, at, false).jacobian * &z;
    let c = &jz * chol.solve(&jz.transpose());
    let c = Matrix3::from_fn(|i, j| c[(i, j)]);
    if c.iter().all(|v| v.is_finite()) {
        Ok(c)
    } else {
        Err(Error::Singular { what: "the compliance is not finite".into() })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::Problem;

    /// Seeded uniform numbers in [−1, 1) (xorshift64*).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    fn example(name: &str, push: [f64; 2]) -> Mechanism {
        let path = format!("{}/../../examples/{name}.toml", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(path).unwrap();
        let text = text.replace("force = [0.0, -1.0]", &format!("force = [{:?}, {:?}]", push[0], push[1]));
        super::super::file::from_toml(&text).unwrap()
    }

    /// The closure stability test on the workspace's buffers (Householder
    /// null space) against the dense one (singular values), on seeded
    /// random states (coordinates, multipliers, load factor) of the
    /// parallelogram pushed to twice its 16 N buckling load, of the
    /// four-bar linkage and of the parallelogram under its 1 N push (with
    /// smaller multipliers, near its equilibria): the same verdict wherever the smallest eigenvalue
    /// of the dense $Z^T\tilde HZ$ − margin is not within 1e-9 of the
    /// largest diagonal entry of zero (where rounding may decide either way),
    /// from the projected test and from `stable` (which tries the whole
    /// Hessian first); the whole-Hessian test alone, a sufficient one,
    /// never says stable where the dense test does not.
    #[test]
    fn closure_stability_matches_the_dense_test() {
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
        let settings = Settings::default();
        // (mechanism, spread of the coordinates, spread of the multipliers in N).
        let cases = [
            (example("parallelogram", [0.3, -32.0]), 0.05, 2.0),
            (example("four_bar", [0.0, -1.0]), 0.3, 2.0),
            (example("parallelogram", [0.5, -1.0]), 0.05, 0.5),
        ];
        let (mut compared, mut stable, mut unstable, mut sufficient) = (0, 0, 0, 0);
        for (m, spread, forces) in &cases {
            let (n, rows) = (m.dof(), m.constraints());
            let zero = m.loads().zero_like();
            let mut kkt = Kkt::new(m, &zero, &m.loads(), &settings).unwrap();
            let size = n + rows;
            let (mut r, mut jac) = (vec![0.0; size], vec![0.0; size * size]);
            for _ in 0..400 {
                let q: Vec<f64> = m.rest().iter().map(|q| q + spread * rng.next()).collect();
                let mu: Vec<f64> = (0..rows).map(|_| forces * rng.next()).collect();
                let lambda = 0.5 * (1.0 + rng.next());
                let x = kkt.state(&q, &mu);
                kkt.evaluate(&x, lambda, &mut r, Some(&mut jac), None).unwrap();
                assert!(kkt.closure_rows_independent(&jac), "independent closure rows");
                let fast = kkt.constrained_definite(&jac, 0.0, kkt.margin).expect("independent scaled closure rows");
                let everywhere = kkt.hessian_definite(&jac);
                let verdict = kkt.stable(&x, lambda, &jac);
                let dense = kkt.stable_dense(&x, lambda, &jac);
                // The dense matrix's distance from the verdict's boundary.
                let g = DMatrix::from_fn(rows, n, |i, c| jac[c * size + n + i] / kkt.closure_scale[i]);
                let s: Vec<f64> = kkt.row_scale.iter().map(|r| r.sqrt()).collect();
                let h = DMatrix::from_fn(n, n, |r, c| jac[c * size + r] / kkt.row_scale[r] * s[r] * s[c]);
                let z = linalg::null_space(&DMatrix::from_fn(rows, n, |i, c| g[(i, c)] * s[c]));
                let k = constrained(&h, &z);
                let (softest, _) = linalg::softest_mode(&k).unwrap();
                let size_k = (0..k.nrows()).map(|i| k[(i, i)].abs()).fold(0.0, f64::max);
                if (softest - kkt.margin).abs() > 1e-9 * size_k {
                    assert_eq!(fast, dense, "q = {q:?}, mu = {mu:?}, lambda = {lambda}: softest {softest}");
                    assert_eq!(verdict, dense, "q = {q:?}, mu = {mu:?}, lambda = {lambda}: softest {softest}");
                    // The sufficient test never calls an unstable state stable.
                    assert!(!everywhere || dense, "q = {q:?}, mu = {mu:?}, lambda = {lambda}: softest {softest}");
                    sufficient += usize::from(everywhere);
                    compared += 1;
                    if dense { stable += 1 } else { unstable += 1 }
                }
            }
        }
        assert!(
            compared > 1000 && stable > 100 && unstable > 100 && sufficient > 100 && sufficient < stable,
            "{compared} compared: {stable} stable ({sufficient} by the whole Hessian), {unstable} not"
        );
    }
}
