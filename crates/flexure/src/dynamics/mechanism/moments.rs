//! A flexure's mass moments in its root frame ([`Moments`]), summed over its
//! sections once per pass, and the quarter turn $E$ they are written with.

use nalgebra::Vector2;

/// One flexure's mass moments in its root frame, summed over its sections
/// $p$ (mass $m_p$, rotary inertia $i_p$, position $r_p$, $J_{r,p}$, local
/// velocity $u_p = J_{r,p}\dot\alpha$ and velocity-product acceleration
/// $a_p$; $E$ the quarter turn, $\omega$ the root's angular velocity): the
/// terms of $M$, $h$ and $Q_g$ ([`MechanismSystem`](super::MechanismSystem)'s pass).
#[derive(Debug, Clone, Default)]
pub(super) struct Moments {
    /// $\sum m_p$.
    pub(super) mass: f64,
    /// $S = \sum m_pr_p$.
    pub(super) first: Vector2<f64>,
    /// $\sum m_p\lvert r_p\rvert^2 + i_p$.
    pub(super) second: f64,
    /// $\sum m_pu_p$ and $\sum m_pa_p$.
    pub(super) velocity: Vector2<f64>,
    pub(super) acceleration: Vector2<f64>,
    /// $\sum m_p\thinspace r_p\cdot u_p$ and $\sum m_p\thinspace Er_p\cdot a_p$.
    pub(super) turning: f64,
    pub(super) swinging: f64,
    /// Per coordinate $i$: $A_i = \sum m_pJ_{r,p,i}$;
    /// $\sum m_p\thinspace Er_p\cdot J_{r,p,i} + i_p\psi_i$;
    /// $\sum m_pJ_{r,p,i}\cdot(-\omega^2r_p + 2\omega Eu_p + a_p)$.
    pub(super) along: Vec<Vector2<f64>>,
    pub(super) across: Vec<f64>,
    pub(super) product: Vec<f64>,
    /// $\sum m_pJ_{r,p,i}\cdot J_{r,p,j} + i_p\psi_i\psi_j$, upper triangle, `[i * k + j]`.
    pub(super) inertia: Vec<f64>,
}

impl Moments {
    pub(super) fn new(k: usize) -> Self {
        Moments {
            along: vec![Vector2::zeros(); k],
            across: vec![0.0; k],
            product: vec![0.0; k],
            inertia: vec![0.0; k * k],
            ..Default::default()
        }
    }

    /// Zeroes the moments of a flexure of order `k`.
    pub(super) fn clear(&mut self, k: usize) {
        (self.mass, self.second, self.turning, self.swinging) = (0.0, 0.0, 0.0, 0.0);
        (self.first, self.velocity, self.acceleration) = (Vector2::zeros(), Vector2::zeros(), Vector2::zeros());
        self.along[..k].fill(Vector2::zeros());
        self.across[..k].fill(0.0);
        self.product[..k].fill(0.0);
        self.inertia[..k * k].fill(0.0);
    }
}

/// $Ev$: the vector `v` turned a quarter turn counterclockwise.
pub(super) fn quarter(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v.y, v.x)
}
