#![doc = include_str!("../../../README.md")]
//!
//! # The paper
//!
//! The model is that of L. U. Odhner and A. M. Dollar, "The Smooth Curvature
//! Model: An Efficient Representation of Euler–Bernoulli Flexures as Robot
//! Joints", *IEEE Transactions on Robotics* 28(4), 2012,
//! [doi:10.1109/TRO.2012.2193232](https://doi.org/10.1109/TRO.2012.2193232).
//! "Eq. N", "Sec. N" and "Table I" in these docs are that paper's. Where
//! its print is wrong the code follows the derivation; `ERRATA.md` in the
//! repository lists each correction and the test that checks it.
//!
//! # Conventions
//!
//! This section is the one place where units and signs are defined; every
//! module follows it.
//!
//! - **Units**: SI throughout: metres, newtons, N·m for moments, N·m² for
//!   the bending stiffness $EI$, joules for energy. Angles are in radians.
//! - **Frames**: the root frame has its x axis along the unbent flexure
//!   (tangent at $s = 0$). The tip frame is the root frame moved to
//!   $(x_{tip}, y_{tip})$ and turned by $\phi_{tip}$ (Eq. 7). A name such as
//!   `pose_root_tip` is the pose of the tip frame expressed in the root frame.
//! - **Ordering**: poses, Jacobian rows, loads and compliance rows/columns are
//!   ordered $(\phi, x, y)$; the matching load vector is $(M, F_x, F_y)$ (Eq. 33).
//! - **Loads**: a tip moment $M$ is counter-clockwise positive; a tip force
//!   $(F_x, F_y)$ is given in the root frame. The paper's polar form (Sec.
//!   III-C) is $F_x = -P\sin\theta$, $F_y = P\cos\theta$
//!   ([`TipLoad::polar`]). Buckling loads are compressive, along the root's
//!   $-x$ axis, and reported as positive numbers. In a mechanism file, forces
//!   are given in the ground frame and their points in the body's frame
//!   (`docs/mechanism-format.md`).
//! - **Coordinates**: joint coordinates $\alpha \in \mathbb R^N$ are the
//!   curvature coefficients in the shifted-Legendre basis (Eq. 8, any
//!   order): $\hat\omega(\alpha, s) = \frac1L\sum_i \alpha_i \tilde P_{i-1}(s/L)$.
//!   The rest shape $\kappa$ uses the same basis; $\alpha_1$ is the tip angle.
//! - **Sections**: a quantity along a flexure ([`section::Profile`]) is a
//!   function of $t = s/L \in [0, 1]$, measured from the root; a notch's
//!   radius and least thickness are in metres. Bending stress is the outer
//!   fibre's, $\sigma = E^{\prime}\frac h2\lvert\hat\omega - \hat\omega_0\rvert$, in pascals
//!   and never negative ([`stress`]); a peak's `at` is metres from the root.
//! - **Paper corrections** (`ERRATA.md`): the energy Hessian is
//!   $\frac{EI}{L}\mathrm{diag}(1, \frac13, \frac15, \dots)$; the clamped–pinned
//!   Euler load is $20.1907\thinspace EI/L^2$; a tendon's potential is
//!   $+f\lvert\Delta x\rvert$.
//!
//! # Layout
//!
//! An immutable [`Flexure`] (the model) and reusable buffers ([`Kinematics`],
//! [`Statics`]) that evaluations fill without allocating; algorithms are
//! plain functions over them. Kernels and solvers are generic over
//! [`Scalar`], so `num-dual` numbers differentiate through the same code.
//! For `f64`, the quadrature nodes' sines and cosines are computed all at
//! once by [`sincos`] (vectorized, within 1 ulp of libm), which is why an
//! evaluation can cost less than five calls of libm's `sin_cos`. The model's
//! solves (tip loads, tendons, minimum-energy connections, mechanisms) share
//! one solver core, [`solver`]; the exact elastica, a reference, shoots on
//! its own. `ARCHITECTURE.md` in the repository describes the layers, where
//! each of the paper's equations lives, and the solver's policies.

pub mod basis;
pub mod buckling;
pub mod compliance;
pub mod connect;
pub mod dynamics;
pub mod energy;
pub mod error;
pub mod estimate;
pub mod inertia;
pub mod joint;
pub mod kinematics;
pub mod limit;
pub mod linalg;
pub mod mass;
pub mod mechanism;
pub mod ode;
pub mod quadrature;
pub mod reference;
pub mod scalar;
pub mod section;
pub mod sincos;
pub mod solver;
pub mod statics;
pub mod stress;
pub mod tendon;

pub use buckling::{Buckling, TipConstraint, buckling_load};
pub use compliance::{compliance_tip, compliance_tip_rest};
pub use energy::{energy, energy_gradient};
pub use error::{Error, Result};
pub use joint::{Flexure, bending_stiffness};
pub use kinematics::{Kinematics, Level, Pose, pose_root_tip, update as update_kinematics};
pub use limit::StabilityLimit;
pub use scalar::Scalar;
pub use statics::{Equilibrium, Settings, Statics, TipLoad, deflect};
