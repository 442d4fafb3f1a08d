//! The spatial flexure: a Kirchhoff rod (inextensible, unshearable) whose
//! body-frame curvature is a short shifted-Legendre series per component
//! (issue 23).
//!
//! Frames are the planar flexure's: the root frame has $x$ along the rest
//! tangent, $y$ the in-plane normal and $z$ out of the plane. The curvature
//! in the body frame is $u(s) = (\tau, \kappa_y, \kappa_z)$, twist about $x$
//! then bending about $y$ and $z$, each component a series of its own order
//! $n_c$ (Eq. 8 per component),
//! $$u_c(s) = \frac1L\sum_{i=0}^{n_c-1}\alpha_{c,i}\thinspace\tilde P_i(s/L),$$
//! so that $\alpha_{c,0}$ is the total rotation of component $c$ and, for
//! $\kappa_z$ alone, the coefficients are the planar flexure's (its
//! $\alpha_1$ is the tip angle, Eq. 11). The coordinates are ordered the
//! $\tau$-coefficients, then $\kappa_y$'s, then $\kappa_z$'s.
//!
//! - [`SpatialFlexure`]: the immutable model, its Gram (stiffness) matrix,
//!   [`energy()`], [`energy_gradient`];
//! - [`SpatialKinematics`] and [`update`]: the tip pose in SE(3), its body
//!   Jacobian and Hessians, by 6th-order Magnus over Gauss subintervals;
//! - [`deflect`], [`stability_limit`], [`compliance`]: equilibrium under a
//!   dead tip wrench [`SpatialLoad`], its stability (lateral-torsional
//!   buckling included) and the tip's 6 × 6 compliance, with the load's
//!   [`generalized_force`] taken by quadrature of the section moments;
//! - [`shape()`]: the sections along the deformed flexure;
//! - [`MassQuadrature`] and [`stations_update`]: its own mass's stations,
//!   their frames and Jacobians (for the spatial mechanism's dynamics and weight);
//! - its error estimate against a refined model, and the orders that meet
//!   an accuracy target, are [`crate::estimate::spatial`]'s;
//! - [`peak_stress`]: the peak von Mises stress along it; [`peak_curvature`], the peak change of bending curvature.

mod energy;
mod flexure;
mod kinematics;
mod magnus;
mod mass;
mod point;
mod shape;
mod spec;
mod statics;
mod step;
mod stress;
pub(crate) mod work;

pub use energy::{energy, energy_gradient};
pub use flexure::{DEFAULT_SUBINTERVALS, MAX_SUBINTERVALS, SpatialFlexure};
pub(crate) use kinematics::update_rate;
pub use kinematics::{SpatialKinematics, pose_root_tip, update};
pub(crate) use mass::stations_dynamics_update;
pub use mass::{MassQuadrature, MassStation, StationKinematics, stations_update};
pub use point::section_at;
pub use shape::{MAX_SHAPE_POINTS, SpatialPoint, shape, shape_at};
pub use spec::{DEFAULT_POISSON, SpatialSpec};
pub use statics::{
    SpatialLoad, SpatialStatics, StabilityTest, compliance, compliance_rest, correct, deflect, rotation_between,
    stability_limit, tip_stiffness,
};
pub use stress::{SpatialPeak, peak_curvature, peak_stress, stress};
pub use work::generalized_force;
