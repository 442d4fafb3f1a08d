//! Pseudo-rigid-body (PRB) models of a flexure: a chain of revolute joints
//! with torsion springs, fitted to the Smooth Curvature Model.
//!
//! A flexure bent by a tip load is replaced by rigid links joined by
//! revolute joints whose springs carry the bending (Howell, *Compliant
//! Mechanisms*, Wiley 2001, Ch. 5):
//!
//! - **1R** ([`PrbKind::OneR`]): one pivot at the *characteristic pivot*,
//!   a fraction $1-\gamma$ of the length from the root, and one rigid link
//!   of length $\gamma L$ from it to the tip. Howell's spring is
//!   $K = \gamma K_\Theta\thinspace EI/L$ (N·m/rad), with $\gamma$ the
//!   *characteristic radius factor* and $K_\Theta$ the nondimensional
//!   *stiffness coefficient*.
//! - **3R** ([`PrbKind::ThreeR`]): Su's chain (H.-J. Su, *J. Mechanisms
//!   Robotics* 1(2), 2009): four links of lengths $\gamma_0 L, \dots, \gamma_3 L$
//!   ($\sum\gamma_i = 1$) and three springs $k_i = K_{\Theta i}\thinspace EI/L$.
//!
//! **Conventions.** [`PrbFit::k_theta`] is nondimensional: Howell's
//! $K_\Theta$ for 1R (so $k_1 = \gamma K_\Theta\thinspace EI/L$), Su's
//! $K_{\Theta i}$ for 3R ($k_{1,i} = K_{\Theta i}\thinspace EI/L$), from the
//! linear coefficient of each spring and the flexure's mean $EI$
//! ([`Flexure::ei`](crate::Flexure::ei)). [`PrbJoint::stiffness`] is the
//! dimensional spring torque
//! $$\tau(\theta) = k_1\theta + k_2\theta^2 + k_3\theta^3$$
//! in N·m/rad, N·m/rad², N·m/rad³. [`PrbFit::gamma`] lists the links'
//! length fractions from root to tip: $[1-\gamma, \gamma]$ for 1R,
//! $[\gamma_0, \gamma_1, \gamma_2, \gamma_3]$ for 3R.
//!
//! **Geometry.** Pivot $i$ sits on the flexure's rest curve at arc length
//! $s_i$ ($s_1 = (1-\gamma)L$ for 1R; $s_i = L\sum_{j<i}\gamma_j$ for 3R),
//! and each link is rigid, carrying the rest shape's chord between
//! pivots, and the last one the rest tip frame. Joint $i$ turns everything
//! beyond it about its pivot by $\theta_i$ (the rest pivot, moved by the
//! joints before it), so the tip pose is the product of exponentials
//! $$g(\theta) = R(p_1, \theta_1)\cdots R(p_n, \theta_n)\thinspace g_0,$$
//! $R(p, \theta)$ the rotation by $\theta$ about the rest pivot $p$ and
//! $g_0$ the rest tip pose: $\theta = 0$ is the rest pose exactly, for a
//! straight or a rest-curved flexure alike ([`tip_pose`]).
//!
//! **Fit.** [`fit()`] solves the Smooth Curvature Model under each given
//! load from rest ([`crate::deflect`]), then fits the chain to those tip
//! poses: for 1R the $\gamma$ whose circle passes closest to the model's
//! tips (in the largest distance) and a cubic spring; for 3R the springs
//! of the chain posed exactly on the model's tips, with the link lengths
//! searched from Su's. It reports the largest error of the PRB model *at
//! its own equilibrium* ([`equilibrium()`]) under the same loads: tip
//! position (m) and tip angle (rad). A fit whose position error exceeds
//! 1 % of $L$ is [`PrbFit::flagged`]. The 1R angle error is Howell's
//! parametric angle mismatch (the tip turns $c_\theta \approx 1.24$ times the
//! PRB angle under an end force, 1.5 under a moment), which no choice of
//! constants removes; 3R reduces it by one to two orders of magnitude.
//!
//! **Howell's procedure** ([`howell`]) is the other fit: his constants for a
//! cantilever under an end force of one direction, with $\gamma$ maximizing
//! the PRB angle $\Theta_{max}$ up to which the tip stays within 0.5 % *of
//! its deflection*. It reproduces Howell's $\gamma = 0.8517$,
//! $\Theta_{max} = 64.3°$ and $K_\Theta = 2.676$ for a vertical force
//! (`VALIDATION.md`, *PRB*).
//!
//! # Example
//! ```
//! use flexure::prb::{self, PrbKind};
//! use flexure::{Flexure, TipLoad};
//! let f = Flexure::new(1.0, 1.0, 6)?;
//! // Vertical end forces up to PL²/EI = 2 (a tip angle of about 45°).
//! let loads: Vec<TipLoad> = (1..=10).map(|i| TipLoad { moment: 0.0, fx: 0.0, fy: 0.2 * i as f64 }).collect();
//! let fit = prb::fit(&f, &loads, PrbKind::OneR)?;
//! // Howell's characteristic radius factor is about 0.85, and the PRB tip
//! // stays within a fraction of a percent of L of the beam's.
//! assert!((fit.gamma[1] - 0.85).abs() < 0.02);
//! assert!(fit.error.position < 5e-3 && !fit.flagged);
//! # Ok::<(), flexure::Error>(())
//! ```

mod chain;
mod fitting;
pub mod howell;
mod model;
mod simplex;
mod statics;

pub use chain::{rest_pose_at, tip_pose};
pub use fitting::{FLAG_FRACTION, HOWELL_GAMMA, HOWELL_K_THETA, SU_GAMMA, SU_K_THETA, fit, fit_along, fit_three_r};
pub use model::{FitError, PrbFit, PrbJoint, PrbKind};
pub use statics::{equilibrium, equilibrium_near, gradient, potential};
