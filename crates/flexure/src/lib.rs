//! Elastic flexure joints for robots, by the Smooth Curvature Model.
//!
//! A flexure is a strip that bends where a robot would have a hinge. This
//! crate models one by the Smooth Curvature Model (Odhner and Dollar, 2012,
//! below): its curvature is a short sum of shifted Legendre polynomials,
//! whose coefficients $\alpha$ are the joint's coordinates. From them it
//! computes, without allocating in the hot paths:
//!
//! - where the flexure goes: the tip pose, its Jacobian and Hessians (Eqs. 7–31);
//! - where it goes under load: equilibrium under a tip load or a tendon,
//!   followed from rest so a snap-through lands where the path leads, with
//!   its stability and the load where stability is lost (Eqs. 22–26);
//! - how stiff it is and when it buckles: compliance and buckling loads
//!   under any tip constraint (Eqs. 32–44);
//! - the minimum-energy shape through a tip pose (Eq. 16);
//! - how far each answer is from the exact beam: an error estimate against
//!   a refined model, flagged against an accuracy target;
//! - the exact Euler–Bernoulli references it is measured against (the
//!   elastica, the compliance ODE, column buckling, beam vibration);
//! - mechanisms: trees of bodies joined by flexures and rigid joints,
//!   closed into loops, loaded by forces, tendons and gravity, in statics,
//!   buckling, modes and motion.
//!
//! The library does no I/O and prints nothing; the `flexure` command line
//! and the Python package print what it returns.
//!
//! # A first example
//!
//! A unit flexure under the Bisshopp–Drucker load (a tip force
//! $PL^2/EI = 1$ across it), its error estimate, and the exact elastica:
//!
//! ```
//! use flexure::estimate::{Accuracy, deflect_error};
//! use flexure::reference::elastica;
//! use flexure::{Flexure, StaticsData, TipLoad, deflect};
//!
//! // L = 1 m, EI = 1 N·m², three curvature coefficients (the paper's).
//! let f = Flexure::new(1.0, 1.0, 3)?;
//! let load = TipLoad { moment: 0.0, fx: 0.0, fy: 1.0 };
//! let mut data = StaticsData::new(&f);
//! let eq = deflect(&f, &load, &mut data, &Default::default())?;
//! let tip = data.pose_root_tip();
//! assert!(eq.stable);
//!
//! // How far that is from a refined model, at the tip and in the peak curvature.
//! let e = deflect_error(&f, &load, data.alpha(), &Accuracy::default())?;
//! assert!(e.position < 1e-3 && !e.flagged);
//!
//! // The exact elastica puts the tip at (0.94357, 0.30172).
//! let exact = elastica::deflect(&f, &load, &Default::default())?;
//! assert!((tip.x - exact.pose.x).abs() < 1e-3 && (tip.y - exact.pose.y).abs() < 1e-3);
//! # Ok::<(), flexure::Error>(())
//! ```
//!
//! A mechanism is read from its file format (`docs/mechanism-format.md` in
//! the repository) and solved:
//!
//! ```
//! use flexure::mechanism::{file, statics};
//!
//! // The paper's tendon joint (Sec. III-D): about 28 N turns it to 90°.
//! let m = file::from_toml(r#"
//! [[joint]]
//! name = "hinge"
//! kind = "flexure"
//! parent = "ground"
//! child = "link"
//! length = 0.015
//! modulus = 200e9
//! width = 0.01
//! thickness = 0.0002
//! poisson = 0.29
//!
//! [[tendon]]
//! name = "flexor"
//! tension = 28.0
//! path = [["ground", 0.0, 0.005], ["link", 0.0, 0.005]]
//! "#)?;
//! let s = statics::solve(&m, &Default::default())?;
//! // The hinge's first coordinate is its tip angle (Eq. 11).
//! assert!(s.stable && (s.q[0].to_degrees() - 90.0).abs() < 5.0);
//! # Ok::<(), flexure::Error>(())
//! ```
//!
//! # What is where
//!
//! | to | use |
//! |---|---|
//! | model one flexure: length, section, order, rest shape | [`Flexure`], [`section::Section`] |
//! | evaluate it: tip pose, Jacobian, Hessians | [`Kinematics`], [`update_kinematics`], [`Pose`] |
//! | its energy and gradient (Eqs. 9, 18) | [`energy()`], [`energy_gradient`] |
//! | equilibrium under a tip load (Eq. 22) | [`deflect`] with [`StaticsData`] and [`TipLoad`]; [`statics::stability_limit`] |
//! | a tendon-driven joint (Eqs. 23–26) | [`tendon::pull`], [`tendon::stability_limit`] |
//! | the shape through a tip pose (Eq. 16) | [`connect::connect`] |
//! | tip compliance (Eqs. 33–36) | [`compliance_tip_rest`], [`compliance_tip`] |
//! | buckling loads (Eqs. 39–44) | [`buckling_load`], [`TipConstraint`] |
//! | stress and peak curvature along it | [`mod@stress`] |
//! | error estimates, and the order that meets a target | [`estimate`] |
//! | exact references | [`mod@reference`] |
//! | mechanisms: file, statics, buckling, sweeps, findings | [`mechanism`] |
//! | modes and motion | [`dynamics`] |
//! | a spatial flexure: two bendings and a twist in SE(3), its statics, stability, compliance, stress | [`mod@spatial`], [`section::SpatialSection`], [`estimate::spatial`] |
//! | the exact Kirchhoff rod | [`reference::rod`] |
//! | pseudo-rigid-body fits | [`prb`] |
//! | the solver core every model solve shares | [`solver`] |
//!
//! An immutable [`Flexure`] (the model) and reusable buffers ([`Kinematics`],
//! [`StaticsData`]) that evaluations fill without allocating; algorithms are
//! plain functions over them. Kernels and solvers are generic over
//! [`Scalar`], so `num-dual` numbers differentiate through the same code.
//! For `f64`, the quadrature nodes' sines and cosines are computed all at
//! once by [`sincos`] (vectorized, within 1 ulp of libm), which is why an
//! evaluation can cost less than five calls of libm's `sin_cos`. Every
//! error is an [`Error`] that names what was reached in units; every loop
//! is bounded.
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
//!
//! ## Vocabulary
//!
//! One word for one thing, in Rust, the command line, Python, the mechanism
//! file and JSON alike. The older names in the last column keep working
//! where they were accepted (command-line options and file keys warn,
//! Python keywords warn with a `DeprecationWarning`); renamed JSON keys are
//! listed in `CHANGELOG.md`.
//!
//! | thing | the word | older names |
//! |---|---|---|
//! | rotation of a pose, frame, body or revolute joint | `phi` ($\phi$) | `Frame::angle`; $\theta$ for a revolute joint's coordinate |
//! | direction of a polar tip force (Sec. III-C, [`TipLoad::polar`]) | `angle` ($\theta$), `--angle` | — |
//! | rest curvature coefficients of a flexure | `kappa` ($\kappa$) | Python's `rest=` on a flexure (a file's `rest` is a spring's rest value) |
//! | tendon tension (N) | `tension` | `tendon --force` |
//! | load fraction where stability was first lost | `limit_fraction` | `limit_load_fraction` |
//! | the stability-limit search's result ([`StabilityLimit`]) | `stability_limit`: `{factor, status: "lost" \| "stable_up_to", stalled}` (`stalled` only when stable up to) | a bare number |
//! | per-joint error estimates of a mechanism's answer | `error_estimate`, joint name → estimate | Python's `estimates` |
//! | one error estimate ([`estimate::ErrorEstimate`]) | `{position, angle, curvature, …, stress}` everywhere, batch rows included (`stress` when a thickness is known) | — |
//!
//! # Further
//!
//! In the repository: `README.md` (the two commands, and a tour of the
//! command line and Python), `docs/cli.md` (every subcommand and option),
//! `docs/mechanism-format.md` (the mechanism file), `docs/python.md` (the
//! Python package), `ARCHITECTURE.md` (the layers, the solver's policies,
//! where each equation lives), `VALIDATION.md` (the error estimates against
//! the exact elastica), `BENCHMARKS.md` (speed), `ERRATA.md` (the paper's
//! misprints), `CHANGELOG.md` (what changed for users).

pub mod basis;
pub mod buckling;
pub mod compliance;
pub mod connect;
pub mod dynamics;
pub mod energy;
pub mod error;
pub mod estimate;
pub mod export;
pub mod flexure;
pub mod inertia;
pub mod kinematics;
pub mod limit;
pub mod linalg;
pub mod mass;
pub mod mechanism;
pub mod model;
pub mod ode;
pub mod prb;
pub mod quadrature;
pub mod reference;
pub mod report;
pub mod scalar;
pub mod section;
pub mod sincos;
pub mod solver;
pub mod space;
pub mod spatial;
pub mod statics;
pub mod stress;
pub mod tendon;

pub use buckling::{CriticalLoad, TipConstraint, buckling_load};
pub use compliance::{compliance_tip, compliance_tip_rest};
pub use energy::{energy, energy_gradient};
pub use error::{Error, Result};
pub use flexure::{Flexure, FlexureSpec};
pub use kinematics::{Kinematics, Level, Pose, pose_root_tip, update as update_kinematics};
pub use limit::StabilityLimit;
pub use scalar::Scalar;
pub use section::bending_stiffness;
pub use statics::{Equilibrium, Settings, StaticsData, TipLoad, deflect};
