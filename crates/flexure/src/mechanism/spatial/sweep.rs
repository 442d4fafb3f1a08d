//! The loads a spatial mechanism's sweep varies. The sweep itself is the
//! planar one, [`crate::mechanism::sweep::sweep`], written over
//! [`crate::mechanism::equilibria::Equilibria`]: each value continued from
//! the last, the first loss of stability found by bisection.

use super::statics::SpatialSolution;
use super::{SpatialLoads, SpatialMechanism};
use crate::error::{Error, Result};
pub use crate::mechanism::sweep::{Sweep, SweepLimit, sweep};

/// The one load a sweep varies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpatialParameter {
    /// Component 0..6 (`mx, my, mz, fx, fy, fz`) of point load `i`.
    Force(usize, usize),
    /// Tendon `i`'s tension.
    Tension(usize),
    /// Gravity's component 0..3 (`x, y, z`).
    Gravity(usize),
}

/// The components of a point load, by name.
pub const WRENCH_COMPONENTS: [&str; 6] = ["mx", "my", "mz", "fx", "fy", "fz"];

impl SpatialParameter {
    /// `force.NAME.mx|my|mz|fx|fy|fz`, `tendon.NAME.tension` or `gravity.x|y|z`.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::spatial::sweep::SpatialParameter;
    /// # use flexure::mechanism::spatial::{SpatialBody, SpatialMechanism};
    /// # let m = SpatialMechanism::new(vec![SpatialBody::massless("ground")], vec![], vec![], vec![], vec![], Default::default()).unwrap();
    /// assert_eq!(SpatialParameter::parse(&m, "gravity.z").unwrap(), SpatialParameter::Gravity(2));
    /// assert!(SpatialParameter::parse(&m, "force.none.fx").unwrap_err().to_string().contains("none"));
    /// ```
    pub fn parse(m: &SpatialMechanism, text: &str) -> Result<Self> {
        let bad = |why: &'static str| Error::invalid("sweep", text, why);
        let parts: Vec<&str> = text.split('.').collect();
        match parts.as_slice() {
            ["gravity", axis] => ["x", "y", "z"]
                .iter()
                .position(|a| a == axis)
                .map(SpatialParameter::Gravity)
                .ok_or_else(|| bad("gravity's component must be x, y or z")),
            ["force", name, component] => {
                let i = m
                    .forces
                    .iter()
                    .position(|f| f.name == *name)
                    .ok_or_else(|| bad("names no force of the mechanism"))?;
                let c = WRENCH_COMPONENTS
                    .iter()
                    .position(|c| c == component)
                    .ok_or_else(|| bad("a force's component must be mx, my, mz, fx, fy or fz"))?;
                Ok(SpatialParameter::Force(i, c))
            }
            ["tendon", name, "tension"] => {
                let i = m
                    .tendons
                    .iter()
                    .position(|t| t.name == *name)
                    .ok_or_else(|| bad("names no tendon of the mechanism"))?;
                Ok(SpatialParameter::Tension(i))
            }
            _ => Err(bad("must be force.NAME.mx|my|mz|fx|fy|fz, tendon.NAME.tension or gravity.x|y|z")),
        }
    }

    /// `loads` with this parameter set to `value`.
    pub fn apply(&self, loads: &SpatialLoads, value: f64) -> SpatialLoads {
        let mut out = loads.clone();
        self.set(&mut out, value);
        out
    }

    /// Sets this parameter of `loads` to `value`, in place.
    pub fn set(&self, loads: &mut SpatialLoads, value: f64) {
        match *self {
            SpatialParameter::Force(i, c) => loads.force[i][c] = value,
            SpatialParameter::Tension(i) => loads.tension[i] = value,
            SpatialParameter::Gravity(c) => loads.gravity[c] = value,
        }
    }
}

/// What a spatial [`sweep`] reached: the planar [`Sweep`]'s fields, with
/// spatial solutions.
pub type SpatialSweep = Sweep<SpatialSolution>;
