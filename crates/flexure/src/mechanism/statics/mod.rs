//! Static equilibrium, stiffness and compliance of a mechanism, in either
//! dimension: written once over [`Statics`], which the plane and space
//! implement side by side (`dimension.rs`) with what differs (frames,
//! Lagrangian assembly, loads' arithmetic, closure rows, and the planar
//! fast paths: the tree's $O(n)$ pivots and Householder stability tests).
//!
//! Equilibrium makes the potential $V(q)$ ([`crate::mechanism::lagrangian`])
//! stationary subject to the closures $c(q) = 0$: the KKT conditions
//! $$\nabla V + G^T\mu = 0,\qquad c(q) = 0,\qquad G = \partial c/\partial q,$$
//! with Jacobian the KKT matrix $\begin{bmatrix}\nabla^2 L & G^T\cr G & 0\end{bmatrix}$,
//! $L = V + \mu^T c$, from exact Hessians (in space, Newton's matrix
//! contracts each joint's second derivatives with the wrench it carries
//! instead, [`Statics::newton_frames`]; the residual stays exact). [`Kkt`] states them as a
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

mod assembly;
mod contact;
pub use contact::{Touched, follow_touching};
mod dimension;
mod kkt;
mod path;
mod solve;
mod stiffness;
mod workspace;

pub use assembly::assemble_unloaded;
pub use dimension::Statics;
pub(crate) use dimension::parts;
pub(crate) use kkt::FAR_MARGIN;
pub use kkt::Kkt;
pub(super) use kkt::constrained;
pub use path::solve_between;
pub(super) use path::{follow, free_motion};
pub use solve::{solve, solve_with};
pub use stiffness::{body_frames, compliance, stiffness};
pub use workspace::Workspace;

use crate::mechanism::{Dimension, Loads};
use crate::space::Planar;
#[cfg(doc)]
use crate::{linalg, solver};

pub use crate::solver::Settings;

/// An equilibrium of a mechanism in the dimension `D`; serialized without
/// its loads (the caller's input) and with `limit` as `limit_fraction` (absent when
/// stability was never lost).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(bound = "")]
pub struct Solution<D: Dimension = Planar> {
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
    #[serde(skip)]
    pub loads: Loads<D>,
    /// Elastic energy stored in the joints (J).
    pub energy: f64,
    /// Whether the constrained stiffness is positive definite.
    pub stable: bool,
    /// Where the loading path to it lost stability before snapping through
    /// to this stable state: the fraction of the load change, if it did.
    #[serde(rename = "limit_fraction", skip_serializing_if = "Option::is_none")]
    pub limit: Option<f64>,
    /// Final KKT residual, relative ([`Kkt`]).
    pub residual: f64,
    /// Load-continuation steps.
    pub load_steps: usize,
    /// Newton iterations over all steps.
    pub iterations: usize,
    /// The contacts with the mechanism's geoms ([`crate::mechanism::contact`]):
    /// each pair that touches, and each that touched on the way and opened.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub contacts: Vec<crate::mechanism::contact::Contact>,
    /// The loads the path went through before [`Solution::loads`], in
    /// order, from none: a sweep's earlier values, which friction
    /// remembers (empty for a path straight from no load).
    #[serde(skip)]
    pub path: Vec<Loads<D>>,
}

/// Relative precision of a reported stability limit (a load fraction, or a sweep's swept value).
pub const LIMIT_PRECISION: f64 = 1e-6;

/// Most continuation steps of one bisection probe: a probe below the limit
/// is a short, smooth path; one beyond it has lost stability within its
/// first steps, and need not follow what comes after.
pub const PROBE_STEPS: usize = 100;
