//! The reusable buffers of a mechanism's equilibrium problem.

#[cfg(doc)]
use super::Kkt;
use super::Settings;
use super::dimension::Statics;
use crate::mechanism::kinematics::Frames;
use crate::mechanism::lagrangian::Assembly;
use crate::mechanism::{Closure, JointSpec, Loads, Mechanism};
use crate::solver;
use crate::space::Planar;
use nalgebra::DVector;

/// The reusable buffers of a mechanism's equilibrium problem (the Data;
/// the [`Mechanism`] is the Model): frames, the assembled Lagrangian, the
/// load derivative and the stability test's matrices. Once made by
/// [`Workspace::new`], evaluating [`Kkt`] (residual, Jacobian, load
/// derivative) allocates nothing, and neither does its stability test
/// when the mechanism has no closures.
#[derive(Debug, Clone)]
pub struct Workspace<D: Statics = Planar> {
    pub(super) dof: usize,
    pub(super) constraints: usize,
    pub(crate) frames: Frames<D>,
    pub(crate) assembly: Assembly<D>,
    pub(super) load_gradient: DVector<f64>,
    pub(crate) mu: Vec<f64>,
    pub(crate) loads: Loads<D>,
    /// $n\times n$ column-major: the scaled stiffness and its Cholesky copy.
    pub(crate) stiffness: Vec<f64>,
    pub(crate) scratch: Vec<f64>,
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
    pub(crate) root_scale: Vec<f64>,
    /// The buffers only this dimension's problem uses ([`Statics::Own`]).
    pub(crate) own: D::Own,
    /// The joint of each coordinate.
    pub(super) joint_of: Vec<usize>,
    /// The solver core's buffers, kept between solves.
    pub(super) solver: Option<solver::SolverWorkspace<f64>>,
    /// The joints these buffers were made for.
    pub(super) joints: Vec<JointSpec<D>>,
    /// The last problem's scales and loads.
    pub(super) spare: Spare<D>,
    /// The loads of a [`solve_with`](super::solve_with): none, and the mechanism's.
    pub(super) given: [Loads<D>; 2],
    /// The unknowns of the assembled start of a [`solve_with`](super::solve_with).
    pub(super) start_x: Vec<f64>,
    /// The coordinates at which `frames` and the assembly's $c$ and $G$
    /// were last evaluated, if `assembled`.
    pub(super) assembled_at: Vec<f64>,
    pub(super) assembled: bool,
    /// The assembled start of the last [`solve_with`](super::solve_with), for the next one.
    pub(super) start: StartCache<D>,
    /// Whether the problem on these buffers solves the mechanism's contacts
    /// itself ([`super::contact`]): else a pair that may touch is refused.
    pub(super) touching: bool,
}

/// The assembled, unloaded start of a [`solve_with`](super::solve_with) and what made it: it
/// depends on the joints, the closures and the settings, and on the loads
/// only through the Newton tolerance (tolerance × [`solver::Problem::scale`]),
/// since every load is zero at $\lambda = 0$.
#[derive(Debug, Clone)]
pub(super) struct StartCache<D: Statics> {
    /// Whether the fields below hold a start.
    pub(super) valid: bool,
    pub(super) closures: Vec<Closure<D>>,
    pub(super) settings: Option<Settings>,
    /// The Newton tolerance it was converged to.
    pub(super) tolerance: f64,
    pub(super) report: Option<solver::NewtonReport>,
    pub(super) stable: bool,
    /// The unknowns, the Jacobian and the frames there.
    pub(super) x: Vec<f64>,
    pub(super) jacobian: Vec<f64>,
    pub(super) frames: Option<Frames<D>>,
}

impl<D: Statics> Default for StartCache<D> {
    fn default() -> Self {
        StartCache {
            valid: false,
            closures: Vec::new(),
            settings: None,
            tolerance: 0.0,
            report: None,
            stable: false,
            x: Vec::new(),
            jacobian: Vec::new(),
            frames: None,
        }
    }
}

impl<D: Statics> StartCache<D> {
    /// Whether the start of `m` (whose joints the workspace was made for)
    /// under `settings`, converged to `tolerance`, is this one: the same
    /// closures and settings, and either the
    /// same tolerance or a start that was converged before any iteration
    /// to within `tolerance` (Newton would stop there again).
    pub(super) fn holds(
        &self,
        m: &Mechanism<D>,
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
        m: &Mechanism<D>,
        settings: &Settings,
        tolerance: f64,
        report: solver::NewtonReport,
        stable: bool,
        x: &[f64],
        jacobian: &[f64],
        frames: &Frames<D>,
    ) {
        match &mut self.frames {
            Some(kept) => D::copy_frames(frames, kept),
            None => self.frames = Some(frames.clone()),
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

impl<D: Statics> Workspace<D> {
    /// Buffers for `m`.
    pub fn new(m: &Mechanism<D>) -> Self {
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
            own: D::new_own(m),
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
            touching: false,
        }
    }

    /// The solver core's buffers for `dim` unknowns, kept ones if they fit.
    pub(super) fn solver(&mut self, dim: usize) -> solver::SolverWorkspace<f64> {
        self.solver.take().filter(|w| w.dim() == dim).unwrap_or_else(|| solver::SolverWorkspace::new(dim))
    }

    /// Whether these buffers were made for `m`'s joints (whose states
    /// carry each joint's constant stiffness and tables) and fit its shape.
    pub(super) fn fits(&self, m: &Mechanism<D>) -> bool {
        self.joints == m.joints
            && self.dof == m.dof()
            && self.constraints == m.constraints()
            && self.joint_of.len() == m.dof()
            && self.frames.joints.len() == m.joints.len()
            && self.loads.tension.len() == m.tendons.len()
            && self.loads.force.len() == m.forces.len()
    }
}

/// The buffers a [`Kkt`] works in: its own, or a caller's, borrowed for
/// the problem's life (moving a [`Workspace`] copies a few kilobytes).
#[derive(Debug)]
pub(crate) enum Buffers<'a, D: Statics> {
    Owned(Box<Workspace<D>>),
    Borrowed(&'a mut Workspace<D>),
}

impl<D: Statics> std::ops::Deref for Buffers<'_, D> {
    type Target = Workspace<D>;
    fn deref(&self) -> &Workspace<D> {
        match self {
            Buffers::Owned(w) => w,
            Buffers::Borrowed(w) => w,
        }
    }
}

impl<D: Statics> std::ops::DerefMut for Buffers<'_, D> {
    fn deref_mut(&mut self) -> &mut Workspace<D> {
        match self {
            Buffers::Owned(w) => w,
            Buffers::Borrowed(w) => w,
        }
    }
}

impl<D: Statics> Clone for Buffers<'_, D> {
    fn clone(&self) -> Self {
        Buffers::Owned(Box::new(Workspace::clone(self)))
    }
}

/// A problem's scales and loads ([`Kkt`]), kept for the next problem.
#[derive(Debug, Clone)]
pub(super) struct Spare<D: Statics> {
    pub(super) vectors: [Vec<f64>; 4],
    pub(super) loads: [Loads<D>; 3],
}

impl<D: Statics> Default for Spare<D> {
    fn default() -> Self {
        Spare { vectors: Default::default(), loads: Default::default() }
    }
}
