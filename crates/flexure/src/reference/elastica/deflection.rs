//! The loaded elastica, followed from rest along its path.

use super::ShootingSettings;
use super::chain::Chain;
use super::trace::Trace;
use crate::error::Result;
use crate::flexure::Flexure;
use crate::kinematics::Pose;
use crate::solver::{self, Problem};
use crate::statics::TipLoad;

/// An exact solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticaSolution {
    /// Tip pose in the root frame.
    pub pose: Pose<f64>,
    /// Bending moment at the root, $M_0 = EI(\omega(0) - \omega_0(0))$ (N·m).
    pub root_moment: f64,
    /// Load-continuation steps taken.
    pub load_steps: usize,
    /// Whether the shape is a minimum of the potential energy under the
    /// (dead) tip load: see [`is_stable`](super::is_stable).
    pub stable: bool,
    /// The load fraction where the loading path first lost stability (a
    /// limit load passed by snap-through, or a bifurcation), if it did.
    pub limit: Option<f64>,
}

/// The exact tip pose under `load`: the elastica clamped at the root whose
/// moment at the tip equals $M$, i.e. $M_0 - F_y x_L + F_x y_L = M$.
///
/// Solved by multiple shooting on the shared pseudo-arclength continuation
/// ([`solver::continuation`]) from the rest shape, so the solution lies on
/// the loading path: a small imperfection decides which way a column
/// buckles, a snap-through load reaches the stable shape the path leads to
/// ([`ElasticaSolution::limit`] names the load fraction where stability was lost),
/// and no step turns a node's cross-section by more than
/// `settings.solver.max_rotation_per_step`. The path is integrated to
/// `settings.path_tolerance` and its end refined by Newton to `settings.ode`,
/// so that the cost grows little with the angle the tip turns. Newton's
/// derivatives come from dual numbers carried through the integrator;
/// [`ElasticaSolution::stable`] is the Jacobi test ([`is_stable`](super::is_stable)) of the refined state.
///
/// The beam is cut into $N = \lceil L\sqrt{|F|/EI}\rceil$ segments (at
/// least 4), so that shooting across one segment stays well conditioned and
/// the cost grows little with the load; a force with
/// $L\sqrt{|F|/EI} >$ [`MAX_FORCE_GROWTH`](super::MAX_FORCE_GROWTH) is refused.
///
/// Errors: [`Error::InvalidParameter`](crate::Error::InvalidParameter) for a non-finite load, bad settings or
/// too large a force; [`Error::ContinuationStalled`](crate::Error::ContinuationStalled) with the load fraction
/// reached; [`Error::Unstable`](crate::Error::Unstable) when the path loses stability and does not
/// come back to the full load; integrator failures.
///
/// # Example
/// ```
/// use flexure::{reference::elastica, Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // Bisshopp–Drucker: PL²/EI = 1 across the tip.
/// let s = elastica::deflect(&f, &TipLoad { moment: 0.0, fx: 0.0, fy: 1.0 }, &Default::default()).unwrap();
/// assert!((s.pose.x - 0.94357).abs() < 1e-5 && (s.pose.y - 0.30172).abs() < 1e-5);
/// ```
pub fn deflect(flexure: &Flexure, load: &TipLoad, settings: &ShootingSettings) -> Result<ElasticaSolution> {
    deflect_traced(flexure, load, settings).map(|(solution, _)| solution)
}

/// [`deflect`], with the [`Trace`] of the exact shape: its cross-sections,
/// bending moment and stress anywhere along the flexure.
///
/// # Example
/// ```
/// use flexure::{reference::elastica, Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // A pure tip moment bends an arc: m = M all along, curvature M/EI.
/// let load = TipLoad { moment: 0.5, fx: 0.0, fy: 0.0 };
/// let (s, trace) = elastica::deflect_traced(&f, &load, &Default::default()).unwrap();
/// assert!((s.pose.phi - 0.5).abs() < 1e-10);
/// let mid = trace.at(0.5).unwrap();
/// assert!((mid.moment - 0.5).abs() < 1e-9 && (mid.phi - 0.25).abs() < 1e-9);
/// ```
pub fn deflect_traced<'a>(
    flexure: &'a Flexure,
    load: &TipLoad,
    settings: &ShootingSettings,
) -> Result<(ElasticaSolution, Trace<'a>)> {
    load.validate()?;
    settings.validate()?;
    let mut chain = Chain::new(flexure, *load, settings.path_ode())?;
    let mut ws = solver::SolverWorkspace::new(chain.dim());
    // The rest shape: no moment anywhere, the nodes at their rest angles.
    ws.x = chain.shot(0.0, 0.0)?;
    let path = solver::continuation(&mut chain, &mut ws, &settings.solver)?;
    // The end state refined to `ode`: Newton starts within about
    // path_tolerance of it and converges in one or two iterations; the
    // stability verdict is the refined state's.
    chain.ode = settings.ode;
    solver::newton(&mut chain, &mut ws, 1.0, &settings.solver)?;
    let stable = chain.stable(&ws.x, 1.0, &ws.jacobian);
    let nodes = chain.states(&ws.x)?;
    let tip = nodes[nodes.len() - 1].1;
    let solution = ElasticaSolution {
        stable,
        pose: Pose { phi: tip[0], x: tip[2], y: tip[3] },
        root_moment: ws.x[0] * chain.stiffness,
        load_steps: path.steps,
        limit: path.limit,
    };
    let trace = Trace { flexure, fx: load.fx, fy: load.fy, stops: chain.stops, nodes, ode: settings.ode };
    Ok((solution, trace))
}
