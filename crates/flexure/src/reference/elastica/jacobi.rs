//! The stability of an elastica: the Jacobi (conjugate-point) test.

use super::chain::Chain;
use crate::error::Result;
use crate::flexure::Flexure;
use crate::ode::Tolerance;
use crate::solver::Problem;
use crate::statics::TipLoad;

/// The Jacobi test of the state the last derivatives were taken at.
#[derive(Debug, Clone, Default)]
pub(super) struct Jacobi {
    /// The unknowns and load factor of that state.
    pub(super) x: Vec<f64>,
    pub(super) lambda: f64,
    /// Whether $h = \partial\phi/\partial M_0$ stayed positive at every accepted step on $(0, L]$.
    pub(super) positive: bool,
    /// Whether $EI h^{\prime}(L) = \partial m(L)/\partial M_0 > 0$.
    pub(super) rising: bool,
}

impl Jacobi {
    pub(super) fn at(&self, x: &[f64], lambda: f64) -> bool {
        self.lambda == lambda && self.x == x
    }
}

/// Whether the elastica shot from `root_moment` under the tip force
/// $(F_x, F_y)$ is stable, by the Jacobi (conjugate-point) test.
///
/// The second variation of the potential energy about the shape $\phi(s)$,
///
/// $$\delta^2 E = \int_0^L \big[EI\thinspace\delta\phi^{\prime 2} +
/// (F_x\cos\phi + F_y\sin\phi)\thinspace\delta\phi^2\big]\thinspace ds,
/// \qquad \delta\phi(0) = 0,$$
///
/// is positive definite exactly when the Jacobi field $h = \partial\phi/\partial M_0$
/// (which solves $(EI h^{\prime})^{\prime} = (F_x\cos\phi + F_y\sin\phi)h$, $h(0) = 0$,
/// $EI h^{\prime}(0) = 1$) stays positive on $(0, L]$ and $EI h^{\prime}(L) > 0$: the
/// Prüfer angle of $h$ then stays below $\pi/2$ at the free end. $h$ is the
/// dual part of $\phi$ when the shot carries a dual root moment, and
/// $EI h^{\prime}(L)$ is the derivative of the tip-moment balance the shooting solves.
///
/// # Example
/// ```
/// use flexure::{reference::elastica, Flexure};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // A straight column, clamped and free, buckles at P = π²EI/4L² ≈ 2.467.
/// assert!(elastica::is_stable(&f, 0.0, -2.4, 0.0, &Default::default()).unwrap());
/// assert!(!elastica::is_stable(&f, 0.0, -2.5, 0.0, &Default::default()).unwrap());
/// ```
pub fn is_stable(flexure: &Flexure, root_moment: f64, fx: f64, fy: f64, tol: &Tolerance) -> Result<bool> {
    TipLoad { moment: root_moment, fx, fy }.validate()?;
    tol.validate()?;
    // The chain through the shot from the root (the tip moment that shot
    // carries does not enter the test).
    let mut chain = Chain::new(flexure, TipLoad { moment: 0.0, fx, fy }, *tol)?;
    let x = chain.shot(root_moment, 1.0)?;
    Ok(chain.stable(&x, 1.0, &[]))
}
