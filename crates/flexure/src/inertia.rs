//! The inertia of a rigid body: what dynamics and gravity need of it.

use crate::error::{Error, Result};

/// The inertia of a rigid body (Pinocchio's `Inertia`): mass $m$ (kg),
/// rotary inertia $I_c$ (kg·m²) about its centre of mass, and that centre of
/// mass $c = (c_x, c_y)$ (m) in the body's frame; for a body carried at a
/// flexure's tip, the tip frame (x along the tip's tangent). A mechanism's
/// [`Body`](crate::mechanism::Body) is a named one
/// ([`Body::rigid_inertia`](crate::mechanism::Body::rigid_inertia)).
///
/// Its inertia about the frame's origin (the tip point) is
/// $I_{tip} = I_c + m\lvert c\rvert^2$.
///
/// # Example
/// ```
/// use flexure::inertia::RigidInertia;
/// let b = RigidInertia::new(0.005, 1e-7, [0.01, 0.0]).unwrap();
/// assert!((b.inertia_about_tip() - (1e-7 + 0.005 * 1e-4)).abs() < 1e-18);
/// let e = RigidInertia::new(-1.0, 0.0, [0.0, 0.0]).unwrap_err();
/// assert!(e.to_string().contains("mass"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct RigidInertia {
    /// Mass $m$ (kg), zero or more.
    pub mass: f64,
    /// Rotary inertia $I_c$ (kg·m²) about the centre of mass, zero or more.
    pub inertia: f64,
    /// Centre of mass $(c_x, c_y)$ (m) in the tip frame.
    pub com: [f64; 2],
}

impl RigidInertia {
    /// A validated inertia ([`RigidInertia::validate`]).
    pub fn new(mass: f64, inertia: f64, com: [f64; 2]) -> Result<Self> {
        let b = Self { mass, inertia, com };
        b.validate()?;
        Ok(b)
    }

    /// Checks that `mass` and `inertia` are finite and not negative and
    /// that `com` is finite, naming the field otherwise.
    pub fn validate(&self) -> Result<()> {
        for (name, v) in [("mass", self.mass), ("inertia", self.inertia)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::invalid(name, v, "must be a finite number, zero or greater"));
            }
        }
        if !self.com.iter().all(|c| c.is_finite()) {
            return Err(Error::invalid("com", format!("{:?}", self.com), "must be two finite numbers (m)"));
        }
        Ok(())
    }

    /// Whether the body has any inertia at all ($m > 0$ or $I_c > 0$).
    pub fn has_inertia(&self) -> bool {
        self.mass > 0.0 || self.inertia > 0.0
    }

    /// $I_{tip} = I_c + m\lvert c\rvert^2$ (kg·m²): the inertia about the tip point.
    pub fn inertia_about_tip(&self) -> f64 {
        self.inertia + self.mass * (self.com[0] * self.com[0] + self.com[1] * self.com[1])
    }
}
