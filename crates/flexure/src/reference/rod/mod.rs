//! The exact Kirchhoff rod: inextensible, unshearable, clamped at the root,
//! under a dead tip wrench, solved by multiple shooting on the shared
//! solver core ([`crate::solver`]) and followed from rest.
//!
//! Frames and signs as for [`crate::section::SpatialSection`]: the root
//! frame's $x$ is the rest tangent at $s = 0$, $y$ the in-plane normal, $z$
//! out of the plane; the body-frame curvature is $u = (\tau, \kappa_y, \kappa_z)$,
//! and the planar model's $EI$ is $EI_z$. The cross-section at $s$ is the
//! rotation $R(s)$ (its columns are the section's axes in the root frame)
//! at $p(s)$. With the tip force $F$ and moment $M$ dead (fixed in the root
//! frame), the internal force is $n \equiv F$ and the internal moment $m(s)$
//! (what the part beyond $s$ exerts on the part before it, in the root
//! frame) satisfies $m(s) = M + (p(L) - p(s))\times F$, so
//! $$R^{\prime} = R\thinspace\hat u, \qquad u = K^{-1}R^Tm + u^0(s), \qquad p^{\prime} = R e_1, \qquad m^{\prime} = -p^{\prime}\times F,$$
//! with $K = \mathrm{diag}(GJ, EI_y, EI_z)$, $R(0) = I$, $p(0) = 0$ and $m(L) = M$.
//! The rotation is integrated as a quaternion, $q^{\prime} = \tfrac12 q\otimes(0, u)$,
//! and read through $q/|q|$, which is exactly a rotation.
//!
//! One concept a file:
//!
//! - `shot.rs`: the equations above along one stretch;
//! - `chain.rs`: multiple shooting, the solver core's problem, with its
//!   conjugate-point test;
//! - `compliance.rs`: the rest compliance by the linearized rod ([`compliance_rest`]).
//! - `sections.rs`: a solution's sections at arc lengths of one's choosing ([`sections()`]).
//!
//! **Multiple shooting.** The rod is cut into $N$ equal segments with
//! $N = \max\big(4, \lceil\int_0^L\sqrt{|F|/EI_{min}}\thinspace ds\rceil, \lceil\Theta/(\pi/2)\rceil\big)$,
//! at most [`MAX_SEGMENTS`], where $EI_{min}(s)$ is the least of the three
//! stiffnesses and $\Theta = \int_0^L|u^0|\thinspace ds + (|M| + L|F|)\int_0^L ds/EI_{min}$
//! bounds the turn of any section from the root frame. The first term keeps
//! each segment's sensitivity below $e$ where a force makes shooting grow
//! like $e^{L\sqrt{|F|/EI}}$ (a long rod); the second puts a node at
//! least every quarter turn of a wound rod, so that the nodes whose rotation
//! bounds the continuation's steps see every turn the rod takes.
//!
//! **Stability by conjugate points.** The Jacobi fields of the clamped
//! rod, $\delta R(0) = 0$, $\delta p(0) = 0$, $\delta m(0) = e_i$, are the
//! dual parts the shooting carries; their tip moments form
//! $N = \partial m(L)/\partial m(0)$, the identity at rest. $N$ is singular
//! exactly where the linearized clamped–loaded problem $\delta R(0) = 0$,
//! $\delta m(L) = 0$ has a solution: a conjugate point at the tip. Under a
//! dead force (a conservative load, energy $\int W\thinspace ds - F\cdot p(L)$)
//! that is where the second variation of the energy first stops being
//! positive along a path from rest. A state counts as stable while no real
//! eigenvalue of $N$ is zero or negative: the determinant's sign change
//! where one real eigenvalue passes zero, and also a double conjugate
//! point (a round column's two bending planes at once), where the
//! determinant touches zero without changing sign. The loading path is
//! stable until the first load factor where that fails, and stays
//! unstable after it ([`RodSolution::stable`] reads the whole path). So that
//! no continuation step passes two conjugate points where the shape
//! itself hardly changes (a straight column), the shooting carries the
//! load's phase $z = \lambda\omega L$ as an unknown, $\omega$ the fastest rate
//! of the Jacobi fields, $\max(\sqrt{|F|/EI_{min}}, (|M| + L|F|)/EI_{min})$,
//! and no step changes it by more than a section may turn. This is the
//! test at the tip along the path, not a count of conjugate points along
//! $s$ (Manning's Dirichlet–Neumann index): a state reached in one jump
//! past several conjugate points would not be judged by it.
//!
//! **Dead moments.** A moment of fixed direction is not conservative for
//! finite rotations in space (its work depends on the rotation's path, not
//! only its end), so there is no energy to be a minimum of. The same
//! determinant then marks where the equilibrium problem under dead loads
//! stops being locally unique (a bifurcation or a fold of the statics),
//! which is what is reported; dynamic (flutter-type) instability under the
//! non-conservative moment is not judged. Under a dead moment alone,
//! $m \equiv M$ and $\partial m(L)/\partial m(0) = I$: the equilibrium is
//! unique at every moment (the clamped rod under a dead twisting moment has
//! no static buckling load: Ziegler, *Principles of Structural Stability*,
//! 1968, §2.8), and the rod is reported stable. The spatial model answers
//! the same question under a dead moment ([`crate::spatial::StabilityTest`]),
//! and the two agree; with a dead thrust as well, no conjugate point
//! appears for any twisting moment, even past Euler's load (the closed
//! form is in [`crate::spatial`]'s statics docs): the static test sees no
//! branching there, which is not a verdict on flutter.

mod chain;
mod compliance;
mod sections;
mod shot;

pub use chain::{MAX_FORCE_GROWTH, MAX_INTEGRATION_PIECES, MAX_SEGMENTS};
pub use compliance::compliance_rest;
pub use sections::sections;

use crate::error::{Error, Result};
use crate::limit::StabilityLimit;
use crate::section::SpatialSection;
use crate::solver::{self, Problem};
use crate::spatial::SpatialLoad;
use chain::Chain;
use nalgebra::{Matrix3, Vector3};
use std::sync::Arc;

/// A rest curvature $u^0(s) = (\tau^0, \kappa_y^0, \kappa_z^0)$ (1/m) as a function of the arc length $s$ (m).
pub type RestCurvature = Arc<dyn Fn(f64) -> [f64; 3] + Send + Sync>;

/// The rod: its length, its section and its rest curvature (immutable;
/// validated when built).
///
/// # Example
/// ```
/// use flexure::reference::rod::Rod;
/// use flexure::section::SpatialSection;
/// // A quarter circle in the x–y plane: κ_z⁰ = π/2 over a unit length.
/// let rod = Rod::new(1.0, SpatialSection::uniform(0.8, 1.0, 1.0).unwrap())
///     .unwrap()
///     .with_rest(|_| [0.0, 0.0, std::f64::consts::FRAC_PI_2])
///     .unwrap();
/// assert_eq!(rod.rest_at(0.5), [0.0, 0.0, std::f64::consts::FRAC_PI_2]);
/// assert!(Rod::new(-1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap()).is_err());
/// ```
#[derive(Clone)]
pub struct Rod {
    length: f64,
    section: SpatialSection,
    rest: Option<RestCurvature>,
}

impl std::fmt::Debug for Rod {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Rod")
            .field("length", &self.length)
            .field("section", &self.section)
            .field("curved", &self.rest.is_some())
            .finish()
    }
}

/// How many points along the rod a rest curvature is checked at.
const REST_CHECKS: usize = 65;

impl Rod {
    /// A straight rod of `length` (m) and `section`; errors name `length`.
    pub fn new(length: f64, section: SpatialSection) -> Result<Self> {
        crate::error::positive("length", length)?;
        Ok(Self { length, section, rest: None })
    }

    /// The same rod with rest curvature $u^0(s)$, $s$ in metres from the root
    /// (1/m). It should be smooth between the section's breakpoints (the
    /// integrator lands on those, not on kinks of its own); it is checked
    /// finite at 65 evenly spaced points (`rest_curvature` names it).
    pub fn with_rest(mut self, rest: impl Fn(f64) -> [f64; 3] + Send + Sync + 'static) -> Result<Self> {
        for i in 0..REST_CHECKS {
            let s = self.length * i as f64 / (REST_CHECKS - 1) as f64;
            for v in rest(s) {
                if !v.is_finite() {
                    return Err(Error::invalid(
                        "rest_curvature",
                        format!("{v} at s = {s}"),
                        "must be finite along the rod",
                    ));
                }
            }
        }
        self.rest = Some(Arc::new(rest));
        Ok(self)
    }

    /// The length $L$ (m).
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The section.
    pub fn section(&self) -> &SpatialSection {
        &self.section
    }

    /// $u^0(s)$ (1/m); zero for a straight rod.
    pub fn rest_at(&self, s: f64) -> [f64; 3] {
        self.rest.as_ref().map_or([0.0; 3], |f| f(s))
    }
}

/// The tip wrench as the chain works with it: moment then force, root frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct TipWrench {
    /// $M$ (N·m).
    pub moment: Vector3<f64>,
    /// $F$ (N).
    pub force: Vector3<f64>,
}

impl TipWrench {
    /// The load `l` (checked: every component finite, named `mx` … `fz`), times `factor`.
    fn of(l: &SpatialLoad, factor: f64) -> Result<Self> {
        l.validate()?;
        Ok(TipWrench { moment: Vector3::from(l.moment) * factor, force: Vector3::from(l.force) * factor })
    }
}

// Settings of `deflect` and `stability_limit`: the elastica's, one type for both exact references.
pub use crate::reference::elastica::ShootingSettings;

/// One cross-section of a solved rod.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Arc length from the root (m).
    pub s: f64,
    /// $p(s)$ in the root frame (m).
    pub position: Vector3<f64>,
    /// $R(s)$: its columns are the section's axes in the root frame.
    pub rotation: Matrix3<f64>,
    /// The internal moment $m(s)$ in the root frame (N·m).
    pub moment: Vector3<f64>,
}

/// An exact solution.
#[derive(Debug, Clone, PartialEq)]
pub struct RodSolution {
    /// The tip's position in the root frame (m).
    pub position: Vector3<f64>,
    /// The tip's rotation: its columns are the tip axes in the root frame.
    pub rotation: Matrix3<f64>,
    /// The moment at the root, $m(0)$ (N·m, root frame).
    pub root_moment: Vector3<f64>,
    /// The shape: a frame at every accepted step of the integrator, root to tip.
    pub shape: Vec<Frame>,
    /// Whether the loading path stayed stable all the way (no conjugate
    /// point appeared: see the module docs).
    pub stable: bool,
    /// The load fraction where the path first lost stability, if it did.
    pub limit: Option<f64>,
    /// Load-continuation steps taken.
    pub load_steps: usize,
    /// The refined state's residual (N·m).
    pub residual: f64,
    /// Shooting segments used.
    pub segments: usize,
}

/// The exact rod under the dead tip wrench `load`, followed from rest.
///
/// The solver's residual is the moment mismatch at the nodes and the tip,
/// relative to $k + |M| + L|F|$ with $k = \min(GJ, EI_y, EI_z)/L$ at
/// mid-length; `settings` are the elastica's ([`ShootingSettings`]).
///
/// Pseudo-arclength continuation in the load factor ([`solver::continuation`])
/// from the rest shape, integrated to `settings.path_tolerance`, and the end
/// refined by Newton to `settings.ode`. No step turns a node's section by
/// more than `settings.solver.max_rotation_per_step`.
///
/// Errors: [`Error::InvalidParameter`] for a non-finite load, bad settings
/// or too large a force ([`MAX_FORCE_GROWTH`]); [`Error::ContinuationStalled`]
/// with the load fraction reached, also when the path's work passes
/// [`MAX_INTEGRATION_PIECES`] (the refinement of its end has an allowance
/// of its own), which is named; [`Error::Unstable`] when the path loses
/// stability at a limit load and does not come back to the full load;
/// integrator failures.
///
/// # Example
/// ```
/// use flexure::reference::rod::{self, Rod};
/// use flexure::section::SpatialSection;
/// use flexure::spatial::SpatialLoad;
/// use nalgebra::Vector3;
/// // Pure twist: the tip turns by TL/GJ about x and stays at (L, 0, 0).
/// let rod = Rod::new(2.0, SpatialSection::uniform(0.5, 1.0, 1.0).unwrap()).unwrap();
/// let load = SpatialLoad { moment: [0.1, 0.0, 0.0], force: [0.0; 3] };
/// let s = rod::deflect(&rod, &load, &Default::default()).unwrap();
/// assert!((s.rotation[(2, 1)] - (0.4f64).sin()).abs() < 1e-10);
/// assert!((s.position - Vector3::new(2.0, 0.0, 0.0)).norm() < 1e-10 && s.stable);
/// ```
pub fn deflect(rod: &Rod, load: &SpatialLoad, settings: &ShootingSettings) -> Result<RodSolution> {
    let load = TipWrench::of(load, 1.0)?;
    settings.validate()?;
    let mut chain = Chain::new(rod, load, settings.path_ode())?;
    let mut ws = solver::SolverWorkspace::new(chain.dim());
    // A rest shape that cannot even be shot (past the bound on its work) is a path that did not start.
    ws.x = chain.shot([0.0; 3], 0.0).map_err(|e| match e {
        Error::Singular { what } => Error::ContinuationStalled {
            cause: what,
            rounding: false,
            solver: solver::Problem::name(&chain),
            load_fraction: 0.0,
            steps: 0,
            residual: f64::NAN,
            unit: "N·m",
        },
        e => e,
    })?;
    let path = solver::continuation(&mut chain, &mut ws, &settings.solver)?;
    // The refinement is bounded by its own iterations: a fresh allowance.
    chain.integrations = 0;
    chain.ode = settings.ode;
    let report = solver::newton(&mut chain, &mut ws, 1.0, &settings.solver)?;
    let stable = path.limit.is_none() && chain.stable(&ws.x, 1.0, &ws.jacobian);
    let shape = chain.shape(&ws.x)?;
    let (root, tip) = (shape[0], shape[shape.len() - 1]);
    Ok(RodSolution {
        position: tip.position,
        rotation: tip.rotation,
        root_moment: root.moment,
        shape,
        stable,
        limit: path.limit,
        load_steps: path.steps,
        residual: report.residual,
        segments: chain.segments(),
    })
}

/// The most bisection steps of [`stability_limit`].
pub const MAX_BISECTIONS: usize = 60;

/// The factor on `load` at which the path from rest first meets a
/// conjugate point, searched up to `max_factor`.
///
/// One path to `max_factor` ([`solver::continuation`], stopping where
/// stability is lost, its steps down to $10^{-3}$ at least) places the loss within a step, $\lambda^{\ast}$; a second
/// path to $0.98\lambda^{\ast}$ gives a stable state just below it, and
/// bisection on the load, each probe a Newton solve from the last state
/// confirmed stable (so it stays on the path's branch; a probe that does
/// not converge, past a fold, counts as lost), brackets the first sign
/// change of $\det\thinspace\partial m(L)/\partial m(0)$ (a real eigenvalue through zero) to the
/// integrator's relative tolerance (at least $10^{-10}$), in at most
/// [`MAX_BISECTIONS`] probes. The answer, as
/// [`StabilityLimit::Lost`], is the largest factor confirmed stable.
/// Errors name `max_factor`; a first path that stalls answers
/// [`StabilityLimit::StableUpTo`] the factor it reached.
///
/// # Example
/// ```
/// use flexure::reference::rod::{self, Rod, ShootingSettings};
/// use flexure::section::SpatialSection;
/// use flexure::spatial::SpatialLoad;
/// // Euler's column, clamped and free, about its softer axis: π²EI_z/4L².
/// let rod = Rod::new(1.0, SpatialSection::uniform(1.0, 2.0, 1.0).unwrap()).unwrap();
/// let load = SpatialLoad { moment: [0.0; 3], force: [-1.0, 0.0, 0.0] };
/// let limit = rod::stability_limit(&rod, &load, 4.0, &ShootingSettings::with_tolerance(1e-9)).unwrap();
/// let euler = std::f64::consts::PI.powi(2) / 4.0;
/// assert!((limit.factor() - euler).abs() < 1e-8 * euler);
/// ```
pub fn stability_limit(
    rod: &Rod,
    load: &SpatialLoad,
    max_factor: f64,
    settings: &ShootingSettings,
) -> Result<StabilityLimit> {
    load.validate()?;
    settings.validate()?;
    crate::error::positive("max_factor", max_factor)?;
    let scaled = TipWrench::of(load, max_factor)?;
    let mut chain = Chain::new(rod, scaled, settings.ode)?;
    // The paths only place the loss for the bisection, which starts 2 %
    // either side of it: steps need not shrink below a thousandth.
    let coarse = solver::Settings { min_step: settings.solver.min_step.max(1e-3), ..settings.solver };
    let follow = |chain: &mut Chain, ws: &mut solver::SolverWorkspace<f64>| -> Result<solver::Path> {
        ws.x = chain.shot([0.0; 3], 0.0)?;
        solver::continuation_while_stable(chain, ws, &coarse)
    };
    let mut ws = solver::SolverWorkspace::new(chain.dim());
    let first = match follow(&mut chain, &mut ws) {
        Ok(path) if path.limit.is_none() && chain.stable(&ws.x, 1.0, &ws.jacobian) => {
            return Ok(StabilityLimit::StableUpTo { factor: max_factor, stalled: None });
        }
        Ok(path) => path.limit.unwrap_or(1.0),
        Err(Error::Unstable { load_fraction, .. }) => load_fraction,
        Err(e @ Error::ContinuationStalled { load_fraction, .. }) => {
            return Ok(StabilityLimit::StableUpTo { factor: load_fraction * max_factor, stalled: Some(e.to_string()) });
        }
        Err(e) => return Err(e),
    };
    // A stable state just below the loss, on the same path.
    let below = 0.98 * first;
    chain.set_load(TipWrench { moment: scaled.moment * below, force: scaled.force * below });
    if follow(&mut chain, &mut ws).is_err() || !chain.stable(&ws.x, 1.0, &ws.jacobian) {
        return Ok(StabilityLimit::Lost { factor: first * max_factor });
    }
    chain.set_load(scaled);
    let (mut lo, mut hi) = (below, (1.02 * first).min(1.0));
    let mut x_lo = ws.x.clone();
    // No finer than the integration can tell.
    let precision = settings.ode.relative.max(1e-10);
    for _ in 0..MAX_BISECTIONS {
        if hi - lo <= precision * hi {
            break;
        }
        let mid = 0.5 * (lo + hi);
        ws.x.copy_from_slice(&x_lo);
        let stable = solver::newton(&mut chain, &mut ws, mid, &settings.solver).is_ok()
            && chain.stable(&ws.x, mid, &ws.jacobian);
        if stable {
            (lo, x_lo) = (mid, ws.x.clone());
        } else {
            hi = mid;
        }
    }
    Ok(StabilityLimit::Lost { factor: lo * max_factor })
}
