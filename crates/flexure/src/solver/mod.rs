//! The one solver core: a damped Newton method and a pseudo-arclength load
//! continuation over a [`Problem`], shared by every layer (tip loads,
//! tendons, minimum-energy connections, the exact elastica, mechanisms).
//!
//! A problem is a family of square systems $r(x, \lambda) = 0$ in the load
//! factor $\lambda \in [0, 1]$, with $r(x_0, 0) = 0$ at the rest state.
//! [`continuation`](fn@continuation) follows the solution path from $(x_0, 0)$ to
//! $\lambda = 1$ in the arc length of $(x, \lambda)$, so it passes limit
//! points (snap-through): at a fold, where the path turns back in
//! $\lambda$, the tangent comes from the bordered system
//! $$\begin{bmatrix} \partial_x r & \partial_\lambda r \cr t_{prev}^T W & \end{bmatrix}
//! t = \begin{bmatrix} 0 \cr 1\end{bmatrix},$$
//! which stays regular there. Each step predicts along the tangent, then
//! Newton corrects on the hyperplane orthogonal to it; the last step lands
//! on $\lambda = 1$ exactly with $\lambda$ held fixed.
//!
//! Policies, shared by all problems:
//! - **Bounded**: at most [`Settings::max_steps`] steps of at least
//!   [`Settings::min_step`], each corrected by at most
//!   [`Settings::max_iterations`] Newton iterations of at most 30 halvings.
//! - **On the loading branch**: a step may turn no cross-section or body by
//!   more than [`Settings::max_rotation_per_step`] (the problem's
//!   [`Problem::distance`]), or [`FAR_STEP`] times that while the problem
//!   reports its state far from instability; its corrector must contract
//!   (the second Newton step at most half the first, no damping: Deuflhard's
//!   test that it stays in the branch's quadratic basin), and from a state
//!   far from instability it may move the step's prediction no further than
//!   the step is long (one that does has replaced the prediction, perhaps by
//!   a state of another branch); a step across
//!   a fold may turn sections by at most 0.35 rad, so the limit load is read
//!   off close points. A step whose stability differs from the
//!   last state's without a fold between them (a jump to another branch) is
//!   retried shorter. Only when no step down to `min_step` avoids it is the
//!   change accepted: a bifurcation on the path itself.
//! - **Honest**: the result says why the run stopped ([`Stop`]), how far
//!   it got, whether its last state is stable and the load fraction where
//!   stability was first lost ([`Path::limit`]): one value, [`Path`], for
//!   finished and partial runs alike ([`trace`]).
//! - **Interruptible**: every step and iteration polls the hook set by
//!   [`with_interrupt`].

mod continuation;
mod interrupt;
mod newton;
mod problem;
mod settings;
mod structured;
mod workspace;

pub(crate) use continuation::continuation_while_stable;
pub use continuation::{FAR_STEP, Path, Stop, continuation, trace};
pub(crate) use interrupt::interrupted;
pub use interrupt::with_interrupt;
pub use newton::{NewtonReport, NewtonStop, newton};
pub use problem::Problem;
#[cfg(test)]
pub(crate) use problem::assert_derivatives;
pub use settings::{MAX_COUNT, Settings};
pub use workspace::SolverWorkspace;
