//! The equations of motion of a [`Mechanism`](crate::mechanism::Mechanism)
//! of either dimension ([`MechanismSystem`]) and its vibration modes
//! ([`modes`]), written once over [`Dynamics`]: what differs between the
//! plane and space is the mass elements' evaluation, below.
//!
//! # In the plane
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
//!
//! # In space
//!
//! Each body of mass $m$, centre of mass $c(q)$ and inertia $I_c$ (in the
//! world, $I_w = RI_cR^T$) turning at $\omega = J_\omega\dot q$ has
//! $T = \frac12 m\lvert J_c\dot q\rvert^2 + \frac12\omega\cdot I_w\omega$, so
//! $$M = \sum_b m J_c^TJ_c + J_\omega^TI_wJ_\omega,\qquad
//! h = \sum_b m J_c^T(\dot J_c\dot q) + J_\omega^T\big(I_w\dot J_\omega\dot q + \omega\times I_w\omega\big),$$
//! Newton–Euler's equations projected on the coordinates (which are
//! Lagrange's, $h = \dot M\dot q - \frac12\nabla(\dot q^TM\dot q)$). They are
//! evaluated by Newton–Euler's recursion: down the tree, each body's
//! angular velocity $\omega$, angular acceleration $\alpha$ and origin's
//! acceleration $a$ at $\ddot q = 0$; a joint of root frame $A$ fixed in its
//! parent $P$, whose output moves in $A$ at $(\omega_j, \dot p_j) = S\dot q_j$ with the bias
//! $b_j = \sum_{ab}\partial_bS_a\dot q_a\dot q_b$, gives its child $C$
//! $$\omega_C = \omega_P + R_A\omega_j,\quad
//!   \alpha_C = \alpha_P + \omega_P\times R_A\omega_j + R_Ab_j^{\omega},$$
//! $$a_C = a_P + \alpha_P\times r + \omega_P\times(\omega_P\times r) + 2\omega_P\times R_A\dot p_j + R_Ab_j^{p},\qquad r = o_C - o_P,$$
//! and a point $x$ of a body moves with $\dot J_x\dot q = a + \alpha\times(x - o) + \omega\times(\omega\times(x - o))$.
//! Each mass element's inertial force $F = m\dot J_c\dot q$ and moment
//! $\tau = I_w\alpha + \omega\times I_w\omega$ are summed up the tree into each
//! subtree's wrench $(F, M_O)$ about the world's origin, and a coordinate of
//! world twist $(\omega_a, v_a)$ (its joint's output origin $o$) takes
//! $h_a = v_a\cdot F + \omega_a\cdot(M_O - o\times F)$. A rigid joint's bias is
//! its $\partial S$ contracted; a spatial flexure's is carried through its
//! Magnus pass along the rate ([`crate::spatial::SpatialKinematics`]'s
//! recursion contracted with $\dot q_j$ twice, one jet a step), so that no
//! Hessian of the pass is formed.
//!
//! A spatial flexure with a density or mass per length adds its stations
//! ([`crate::spatial::MassQuadrature`]) as bodies: station $k$ of joint $j$,
//! at $x_k = o_A + R_Ap_k$ with axes $R_AR_k$ ($A$ the joint's root frame),
//! has $J_{v,k}$ of a point fixed in the parent body for the coordinates
//! upstream and $R_A\partial_ap_k$ for the joint's own, $J_{\omega,k}$ the
//! upstream $\omega_c$ and $R_A\omega_{k,a}$, so
//! $$M_f = \sum_k \mu_kw_k J_{v,k}^TJ_{v,k} + J_{\omega,k}^T\big(R\rho I_kR^T\big)J_{\omega,k}.$$
//! Its velocity products are the same recursion's: the station moves
//! with its parent $P$ and within the joint by $\dot p_k$, $\ddot p_k$, $\omega_k$
//! and $\dot\omega_k$ at $\ddot q = 0$, carried along the rate in the same
//! pass as its Jacobian ([`crate::spatial::stations_update`]'s, one more jet
//! a step), so its acceleration is $a_k = a_P + \alpha_P\times(x_k - o_P) + \omega_P\times(\omega_P\times(x_k - o_P)) + 2\omega_P\times R_A\dot p_k + R_A\ddot p_k$;
//! its force and moment project on the joint's own coordinates by its
//! Jacobian and go to $P$'s wrench for the rest. These are the exact
//! derivatives of the discrete $M_f$ (`tests/spatial_flexure_mass.rs`
//! checks them against Lagrange's equations of $T$ by differences).
//!
//! The generalized force is $f = -(\nabla V - Q_m) - h - D\dot q$, with the
//! potential and dead moments of [`crate::mechanism::lagrangian`]
//! and $D = \operatorname{diag}(\beta_jK_j, c_k)$. The tangent stiffness
//! adds $\partial h/\partial q$ by central differences of the exact $h$ (step
//! $10^{-6}(1 + \lvert q_i\rvert)$); exact, it would take the Magnus pass's third derivatives.

mod dimension;
mod distributed;
mod equations;
mod moments;
mod planar;
mod spatial;
mod vibration;

pub use dimension::{Dynamics, MassElements};
pub use equations::MechanismSystem;
pub use vibration::modes;
