//! Exact Euler–Bernoulli references, kept apart from the model so that
//! users (and our tests) can measure the model's error against them.
//! Each takes the section's bending stiffness $EI(s)$ and integrates
//! across its breakpoints (table points, notch edges) piece by piece.
//!
//! - [`elastica`]: the large-deflection elastica (Eq. 3) solved by shooting,
//!   with its shape and bending stress ([`elastica::Trace`]), and touching
//!   rigid obstacles ([`elastica::contact`](mod@elastica::contact));
//! - [`compliance`]: the compliance ODE (Eq. 34);
//! - [`mod@column`]: the linearized buckling load of a straight column by shooting;
//! - [`euler`]: Euler's closed-form buckling loads (uniform columns);
//! - [`vibration`]: linear vibration of the straight beam by shooting on the frequency;
//! - [`rod`]: the spatial Kirchhoff rod under a tip wrench by multiple shooting, with conjugate points.

pub mod column;
pub mod compliance;
pub mod elastica;
pub mod euler;
pub mod rod;
pub mod vibration;

use crate::error::Result;
use crate::flexure::Flexure;
use crate::ode::{Tolerance, integrate_through};

/// The section's breakpoints as arc lengths (m), increasing, inside $(0, L)$.
pub(crate) fn stops(flexure: &Flexure) -> Vec<f64> {
    let l = flexure.length();
    flexure.section().breakpoints(l).iter().map(|t| t * l).collect()
}

/// Integrals of the section along the flexure that scale and place the
/// shooting references' work.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Stretch {
    /// $\int_0^L ds/EI$ (1/(N·m)): the most a unit moment turns the tip.
    pub flexibility: f64,
    /// $(s, \tau(s))$ with $\tau = \int_0^s EI^{-1/2}\thinspace ds$ at
    /// increasing $s$ from 0 to $L$, linear between: a tip force $F$ grows
    /// a shot's sensitivity like $e^{\sqrt{|F|}\tau}$.
    pub tau: Vec<(f64, f64)>,
}

impl Stretch {
    /// The integrals of `flexure`'s section, in closed form when uniform.
    pub fn of(flexure: &Flexure) -> Result<Self> {
        let (l, ei) = (flexure.length(), flexure.ei());
        if flexure.section().is_uniform() {
            return Ok(Self { flexibility: l / ei, tau: vec![(0.0, 0.0), (l, l / ei.sqrt())] });
        }
        // Node placement and bounds need a few digits only.
        let tol = Tolerance { relative: 1e-9, absolute: 0.0, max_steps: 100_000 };
        let mut tau = Vec::new();
        let rhs = |s: f64, _: &[f64; 2]| {
            let ei = flexure.ei_at(s);
            [1.0 / ei.sqrt(), 1.0 / ei]
        };
        let end =
            integrate_through(rhs, 0.0, l, &stops(flexure), [0.0; 2], &tol, &mut 0.0, |s, y| tau.push((s, y[0])))?;
        Ok(Self { flexibility: end[1], tau })
    }

    /// $\tau(L)$.
    pub fn total(&self) -> f64 {
        self.tau.last().map_or(0.0, |p| p.1)
    }

    /// The nodes $0 = s_0 < \dots < s_N = L$ of `segments` shooting
    /// segments equal in $\tau$ (equal in $s$ when `uniform`), `length` $= L$.
    pub fn nodes(&self, length: f64, uniform: bool, segments: usize) -> Vec<f64> {
        (0..=segments)
            .map(|j| match j {
                0 => 0.0,
                _ if j == segments => length,
                _ if uniform => length * j as f64 / segments as f64,
                _ => self.at_fraction(j as f64 / segments as f64),
            })
            .collect()
    }

    /// The arc length where $\tau$ reaches `fraction` of $\tau(L)$ (linear between table points).
    pub fn at_fraction(&self, fraction: f64) -> f64 {
        let target = fraction * self.total();
        let k = self.tau.partition_point(|p| p.1 < target).clamp(1, self.tau.len() - 1);
        let ((s0, t0), (s1, t1)) = (self.tau[k - 1], self.tau[k]);
        if t1 > t0 { s0 + (target - t0) / (t1 - t0) * (s1 - s0) } else { s1 }
    }
}
