//! Error estimates for model answers, and the order that meets a target.
//!
//! The model's two approximations are the truncated curvature basis (order
//! $N$) and the quadrature of the tip position (Eqs. 14–15, $Q$ points). An
//! answer's error is estimated against a **reference model** that refines
//! both: order $N_r = \min(2N, 64)$ (at least $N + 3$) and a rule of
//! $Q_r = N_r + 6 + \lceil V\rceil$ points, where $V = \sum_i|\alpha_i|$
//! bounds the total turning $\int_0^L|\phi^{\prime}|\thinspace ds$ of the answer's
//! shape ([`turning`]), so that $\cos\phi$ and $\sin\phi$ are integrated to
//! rounding however far the flexure winds.
//! The reference starts from the answer (its coordinates padded with zeros:
//! the shifted-Legendre basis is nested) and one Newton solve at the full
//! load corrects it, which costs a few evaluations at the higher order,
//! less than the continuation that produced the answer. The estimate is the
//! distance between the two answers: the error of the answer, to within the
//! reference's own error, which is far smaller wherever the basis converges.
//!
//! **At the order cap** ([`MAX_ORDER`](crate::flexure::MAX_ORDER) = 64) no model refines the answer's
//! order, and more points alone would leave a smooth answer unchanged: the
//! model against itself, an estimate of 0 whatever its true error (a steep
//! taper of $EI$ converges slowly in the basis). So an estimate at the cap
//! is never against order 64 itself. One rule: the reference is the most
//! independent one the library has for that answer. A tip load's answer
//! ([`deflect_error`], [`joint_error`], the last try of [`deflect_auto`])
//! is estimated against the exact elastica with the flexure's $EI(s)$
//! ([`crate::reference::elastica`], `ErrorEstimate::exact`), so the estimate
//! is its true error; answers the elastica module does not solve as such
//! (tendon joints, connections, buckling loads and frequencies,
//! [`eigen_reference`]) against order 32, whose change overstates the
//! order-64 answer's error where the basis converges, and flags it where it
//! does not.
//!
//! [`Estimator`] keeps the reference model and its buffers between
//! estimates of one flexure (Model and Data), so a repeated estimate costs
//! the reference's Newton solve and the peaks, not the reference's tables.

mod accuracy;
mod auto;
mod eigen;
mod mechanism;
mod refinement;
pub mod spatial;
mod statics;
mod value;

pub use accuracy::{Accuracy, ErrorEstimate};
pub use auto::{connect_auto, deflect_auto, tendon_auto};
pub use eigen::{buckling_auto, buckling_error, modes_auto, modes_error};
pub use mechanism::{
    Asked, Refined, Refinements, buckle_auto, buckle_error, contact_estimates, mechanism_modes_auto,
    mechanism_modes_error, raise_auto, reference_mechanism,
};
pub use refinement::{eigen_reference, reference, turning};
pub use statics::{Estimator, connect_error, deflect_error, joint_error, joint_error_and_load, tendon_error};
pub use value::ValueEstimate;
