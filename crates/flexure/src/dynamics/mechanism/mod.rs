//! The equations of motion of a [`Mechanism`](crate::mechanism::Mechanism) and its vibration modes.
//!
//! Every mass element of the mechanism (a body's mass $m$ at its centre of
//! mass, its inertia $I_c$; a flexure section's mass $\mu\thinspace ds$ and
//! rotary inertia $\rho I\thinspace ds$) sits at a world point $w(q)$ on a frame
//! of angle $\theta(q)$, so the kinetic energy is
//!
//! $$T = \tfrac12\sum_e m_e\lvert\dot w_e\rvert^2 + I_e\dot\theta_e^2 = \tfrac12\dot q^TM(q)\dot q,\qquad
//! M = \sum_e m_e J_e^TJ_e + I_e\thinspace g_e^Tg_e,$$
//!
//! with $J_e = \partial w_e/\partial q$ and $g_e = \partial\theta_e/\partial q$. Every
//! joint's angle is linear in its coordinates, so $g_e$ is constant and
//! Lagrange's velocity-product terms are
//! $h = \dot M\dot q - \frac12\nabla(\dot q^TM\dot q) = \sum_e m_eJ_e^T(\dot J_e\dot q)$,
//! where $\dot J_e\dot q = \dot q^T\nabla\nabla w_e\thinspace\dot q$ is the
//! acceleration of the point when $\ddot q = 0$. It is carried down the tree
//! with the angular velocity $\omega$ and velocity $v$ of each frame: a joint
//! whose root frame $A$ (origin $o_A$, rotation $R_A$) carries its output at
//! $p(q_j)$ gives its child's origin
//!
//! $$a_C = a_A - \omega_A^2R_Ap + 2\omega_A\mathrm E R_A\dot p + R_A\thinspace\dot q_j^T\nabla\nabla p\thinspace\dot q_j,$$
//!
//! and a point $w$ of a body moves with $a_w = a_b - \omega_b^2(w - o_b)$
//! ($\mathrm E$ the quarter turn). A flexure's sections are points in its root
//! frame at $r(s) = \int_0^s(\cos\phi, \sin\phi)\thinspace ds^{\prime}$, integrated by the
//! nested Gauss–Legendre rule of [`super::mass`] (the rule and refinement
//! its [`MassModel`](crate::mass::MassModel) chooses), so each section is as accurate as the tip;
//! their local acceleration $\dot J_r\dot\alpha = -\int_0^s\dot\phi^2(\cos\phi, \sin\phi)ds^{\prime}$
//! enters $a_w$ as $\ddot p$ does $a_C$. The discrete $h$ is the exact
//! derivative of the discrete $M$.
//!
//! The generalized force of [`System`](crate::dynamics::System) is $f = -\nabla V_{loads} - \nabla U + Q_g - h - D\dot q$:
//! the point loads and tendons of [`crate::mechanism::lagrangian`] at
//! constant magnitudes, the joints' elastic forces, gravity on every mass
//! element (bodies and flexure sections), and the damping
//! $D = \operatorname{diag}(\beta_jK_j, c_k)$ of the joints.

mod distributed;
mod equations;
mod moments;
mod vibration;

pub use equations::MechanismSystem;
pub use vibration::modes;
