//! The reusable buffers of a mechanism's equilibrium problem.

#[cfg(doc)]
use super::Kkt;
use super::Settings;
use crate::mechanism::kinematics::Frames;
use crate::mechanism::lagrangian::Assembly;
use crate::mechanism::tree::Tree;
use crate::mechanism::{Closure, Loads, Mechanism};
use crate::solver;
use nalgebra::DVector;
use std::cell::RefCell;

/// The reusable buffers of a mechanism's equilibrium problem (the Data;
/// the [`Mechanism`] is the Model): frames, the assembled Lagrangian, the
/// load derivative and the stability test's matrices. Once made by
/// [`Workspace::new`], evaluating [`Kkt`] (residual, Jacobian, load
/// derivative) allocates nothing, and neither does its stability test
/// when the mechanism has no closures.
#[derive(Debug, Clone, Default)]
pub struct Workspace {
    pub(super) dof: usize,
    pub(super) constraints: usize,
    pub(super) frames: Frames,
    pub(super) assembly: Assembly,
    pub(super) load_gradient: DVector<f64>,
    pub(super) mu: Vec<f64>,
    pub(super) loads: Loads,
    /// $n\times n$ column-major: the scaled stiffness and its Cholesky copy.
    pub(super) stiffness: Vec<f64>,
    pub(super) scratch: Vec<f64>,
    /// The closure test's $\tilde G^T$ ($n\times m$), its Householder
    /// reflections ($n\times m$), $\tilde Z$ and $\tilde H\tilde Z$ ($n\times(n-m)$),
    /// $\tilde H$ ($n\times n$), a Gram matrix ($m\times m$) and $\sqrt{1/k_i}$ ($n$).
    pub(super) closure_t: Vec<f64>,
    pub(super) reflections: Vec<f64>,
    pub(super) basis: Vec<f64>,
    pub(super) product: Vec<f64>,
    pub(super) hessian: Vec<f64>,
    pub(super) gram: Vec<f64>,
    /// $S = \operatorname{diag}(\sqrt{1/k_i})$, set with the row scales by `Kkt::fitted`.
    pub(super) root_scale: Vec<f64>,
    /// Body angles of two states, for [`solver::Problem::distance`].
    pub(super) angles: RefCell<[Vec<f64>; 2]>,
    /// The tree's $O(n)$ factorization of the Hessian ([`crate::mechanism::tree`]).
    pub(super) tree: Tree,
    /// The joint of each coordinate.
    pub(super) joint_of: Vec<usize>,
    /// The solver core's buffers, kept between solves.
    pub(super) solver: Option<solver::Workspace<f64>>,
    /// The joints these buffers were made for.
    pub(super) joints: Vec<crate::mechanism::JointSpec>,
    /// The last problem's scales and loads.
    pub(super) spare: Spare,
    /// The loads of a [`solve_with`](super::solve_with): none, and the mechanism's.
    pub(super) given: [Loads; 2],
    /// The unknowns of the assembled start of a [`solve_with`](super::solve_with).
    pub(super) start_x: Vec<f64>,
    /// The coordinates at which `frames` and the assembly's $c$ and $G$
    /// were last evaluated, if `assembled`.
    pub(super) assembled_at: Vec<f64>,
    pub(super) assembled: bool,
    /// The assembled start of the last [`solve_with`](super::solve_with), for the next one.
    pub(super) start: StartCache,
}

/// The assembled, unloaded start of a [`solve_with`](super::solve_with) and what made it: it
/// depends on the joints, the closures and the settings, and on the loads
/// only through the Newton tolerance (tolerance × [`solver::Problem::scale`]),
/// since every load is zero at $\lambda = 0$.
#[derive(Debug, Clone, Default)]
pub(super) struct StartCache {
    /// Whether the fields below hold a start.
    pub(super) valid: bool,
    pub(super) closures: Vec<Closure>,
    pub(super) settings: Option<Settings>,
    /// The Newton tolerance it was converged to.
    pub(super) tolerance: f64,
    pub(super) report: Option<solver::NewtonReport>,
    pub(super) stable: bool,
    /// The unknowns, the Jacobian and the frames there.
    pub(super) x: Vec<f64>,
    pub(super) jacobian: Vec<f64>,
    pub(super) frames: Frames,
}

impl StartCache {
    /// Whether the start of `m` (whose joints the workspace was made for)
    /// under `settings`, converged to `tolerance`, is this one: the same
    /// closures and settings, and either the
    /// same tolerance or a start that was converged before any iteration
    /// to within `tolerance` (Newton would stop there again).
    pub(super) fn holds(
        &self,
        m: &Mechanism,
        settings: &Settings,
        tolerance: f64,
    ) -> Option<(solver::NewtonReport, bool)> {
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
    pub(super) fn keep(
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
    pub(super) fn solver(&mut self, dim: usize) -> solver::Workspace<f64> {
        self.solver.take().filter(|w| w.dim() == dim).unwrap_or_else(|| solver::Workspace::new(dim))
    }

    /// Whether these buffers were made for `m`'s joints (whose states
    /// carry each joint's constant stiffness and tables) and fit its shape.
    pub(super) fn fits(&self, m: &Mechanism) -> bool {
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
pub(super) enum Buffers<'a> {
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
pub(super) struct Spare {
    pub(super) vectors: [Vec<f64>; 4],
    pub(super) loads: [Loads; 3],
}

/// `from` into `to`, in `to`'s buffers.
pub(super) fn copy_loads(from: &Loads, to: &mut Loads) {
    to.tension.clear();
    to.tension.extend_from_slice(&from.tension);
    to.force.clear();
    to.force.extend_from_slice(&from.force);
    to.gravity = from.gravity;
}
