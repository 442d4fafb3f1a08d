//! The [`System`] that applies a mechanism's schedules: its loads at each
//! time it is evaluated, for either dimension ([`ScheduledSystem`]). The schedules themselves are plain data of the
//! mechanism ([`crate::mechanism::schedule`], re-exported here).

use super::mechanism::{Dynamics, MechanismSystem};
use super::system::System;
use crate::error::Result;
pub use crate::mechanism::schedule::{Schedule, Waveform};
use crate::mechanism::{Loads, Mechanism};
use crate::space::Planar;

/// The loads of `m` at time `t` (s): its own, each scheduled one replaced by
/// its [`Schedule::value`]; in either dimension.
///
/// # Example
/// ```
/// use flexure::dynamics::schedule::loads_at;
/// use flexure::mechanism::file::from_toml;
/// let m = from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 1.0\n\
///      [[force]]\nname = \"push\"\nbody = \"arm\"\nat = [0.1, 0.0]\nforce = [0.0, 5.0]\n\
///      [[schedule]]\nload = \"force.push.moment\"\npoints = [[0.0, 0.0], [0.1, 2.0]]\n",
/// )
/// .unwrap();
/// use flexure::space::Wrench;
/// assert_eq!(loads_at(&m, 0.05).force, [Wrench { moment: 1.0, fx: 0.0, fy: 5.0 }]);
/// assert_eq!(loads_at(&m, 1.0).force, [Wrench { moment: 2.0, fx: 0.0, fy: 5.0 }]);
/// ```
pub fn loads_at<D: Dynamics>(m: &Mechanism<D>, t: f64) -> Loads<D> {
    let mut loads = m.loads();
    apply(&m.schedules, t, &mut loads);
    loads
}

fn apply<D: Dynamics>(schedules: &[Schedule], t: f64, loads: &mut Loads<D>) {
    for s in schedules {
        s.parameter.set(loads, s.value(t));
    }
}

/// A [`MechanismSystem`] whose loads follow the mechanism's schedules: at
/// each time it is evaluated it sets [`loads_at`] that time
/// ([`MechanismSystem::set_loads`]).
///
/// # Example
/// ```
/// use flexure::dynamics::{schedule::ScheduledSystem, System};
/// use flexure::mechanism::file::from_toml;
/// // A massive arm on a pin, with a moment ramped from 0 to 2 N·m over 1 s.
/// let m = from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\n\
///      [[body]]\nname = \"arm\"\ninertia = 1.0\n[[force]]\nname = \"turn\"\nbody = \"arm\"\nat = [0.0, 0.0]\n\
///      [[schedule]]\nload = \"force.turn.moment\"\npoints = [[0.0, 0.0], [1.0, 2.0]]\n",
/// )
/// .unwrap();
/// let mut sys = ScheduledSystem::new(&m).unwrap();
/// let (mut mass, mut force) = ([0.0], [0.0]);
/// sys.dynamics(&[0.0], &[0.0], 0.25, &mut mass, &mut force).unwrap();
/// assert!((force[0] - 0.5).abs() < 1e-15);
/// ```
#[derive(Debug, Clone)]
pub struct ScheduledSystem<D: Dynamics = Planar> {
    system: MechanismSystem<D>,
    schedules: Vec<Schedule>,
    /// The loads without schedules, and the time the system's loads were last set for.
    base: Loads<D>,
    time: f64,
}

impl<D: Dynamics> ScheduledSystem<D> {
    /// The system of `m` ([`MechanismSystem::new`]) with its schedules, its loads set for t = 0.
    pub fn new(m: &Mechanism<D>) -> Result<Self> {
        let (mut system, base) = (MechanismSystem::new(m)?, m.loads());
        system.set_loads(loads_at(m, 0.0))?;
        Ok(ScheduledSystem { system, schedules: m.schedules.clone(), base, time: 0.0 })
    }

    /// The system, with the loads of the last time evaluated.
    pub fn system(&mut self) -> &mut MechanismSystem<D> {
        &mut self.system
    }

    fn at(&mut self, t: f64) -> Result<()> {
        if t != self.time && !self.schedules.is_empty() {
            let mut loads = self.base.clone();
            apply(&self.schedules, t, &mut loads);
            self.system.set_loads(loads)?;
            self.time = t;
        }
        Ok(())
    }
}

impl<D: Dynamics> System for ScheduledSystem<D> {
    fn dim(&self) -> usize {
        self.system.dim()
    }

    fn closures(&self) -> usize {
        self.system.closures()
    }

    fn dynamics(&mut self, q: &[f64], v: &[f64], t: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
        self.at(t)?;
        self.system.dynamics(q, v, t, mass, force)
    }

    fn tangent(&mut self, q: &[f64], v: &[f64], t: f64, stiffness: &mut [f64], damping: &mut [f64]) -> Result<()> {
        self.at(t)?;
        self.system.tangent(q, v, t, stiffness, damping)
    }

    fn closure(&mut self, q: &[f64], c: &mut [f64], g: &mut [f64]) -> Result<()> {
        self.system.closure(q, c, g)
    }

    fn energy(&mut self, q: &[f64], v: &[f64], t: f64) -> Result<f64> {
        self.at(t)?;
        self.system.energy(q, v, t)
    }

    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        self.system.distance(a, b)
    }

    fn error_weights(&self) -> crate::dynamics::system::ErrorWeights {
        self.system.error_weights()
    }

    fn jumps(&self) -> Vec<f64> {
        let mut times: Vec<f64> = self.schedules.iter().flat_map(Schedule::jumps).collect();
        times.sort_by(f64::total_cmp);
        times.dedup();
        times
    }
}
