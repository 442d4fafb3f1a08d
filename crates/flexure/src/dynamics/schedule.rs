//! The [`System`] that applies a mechanism's schedules: its loads at each
//! time it is evaluated, for either dimension ([`Scheduled`] over a
//! [`Loaded`] system). The schedules themselves are plain data of the
//! mechanism ([`crate::mechanism::schedule`], re-exported here).

use super::mechanism::MechanismSystem;
use super::spatial::SpatialSystem;
use super::system::System;
use crate::error::Result;
pub use crate::mechanism::schedule::{Schedule, Waveform};
use crate::mechanism::spatial::{SpatialLoads, SpatialMechanism};
use crate::mechanism::sweep::Parameter;
use crate::mechanism::sweep::SpatialParameter;
use crate::mechanism::{Loads, Mechanism};

/// A system whose loads a schedule sets: the planar [`MechanismSystem`]
/// and the [`SpatialSystem`].
pub trait Loaded: System {
    /// Its loads.
    type Loads: Clone;
    /// The one load a schedule sets.
    type Parameter;
    /// Takes `loads` from now on.
    fn set_loads(&mut self, loads: Self::Loads) -> Result<()>;
    /// Sets `parameter` of `loads` to `value`.
    fn set(parameter: &Self::Parameter, loads: &mut Self::Loads, value: f64);
}

impl Loaded for MechanismSystem {
    type Loads = Loads;
    type Parameter = Parameter;
    fn set_loads(&mut self, loads: Loads) -> Result<()> {
        MechanismSystem::set_loads(self, loads)
    }
    fn set(parameter: &Parameter, loads: &mut Loads, value: f64) {
        parameter.set(loads, value)
    }
}

impl Loaded for SpatialSystem<'_> {
    type Loads = SpatialLoads;
    type Parameter = SpatialParameter;
    fn set_loads(&mut self, loads: SpatialLoads) -> Result<()> {
        SpatialSystem::set_loads(self, loads)
    }
    fn set(parameter: &SpatialParameter, loads: &mut SpatialLoads, value: f64) {
        parameter.set(loads, value)
    }
}

/// The loads of `m` at time `t` (s): its own, each scheduled one replaced by
/// its [`Schedule::value`].
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
pub fn loads_at(m: &Mechanism, t: f64) -> Loads {
    let mut loads = m.loads();
    apply(&m.schedules, t, &mut loads, Parameter::set);
    loads
}

/// The loads of a spatial mechanism at time `t` (s), as [`loads_at`].
pub fn spatial_loads_at(m: &SpatialMechanism, t: f64) -> SpatialLoads {
    let mut loads = m.loads();
    apply(&m.schedules, t, &mut loads, SpatialParameter::set);
    loads
}

fn apply<P, L>(schedules: &[Schedule<P>], t: f64, loads: &mut L, set: impl Fn(&P, &mut L, f64)) {
    for s in schedules {
        set(&s.parameter, loads, s.value(t));
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
pub type ScheduledSystem = Scheduled<MechanismSystem>;

/// A [`Loaded`] system whose loads follow schedules: at each time it is
/// evaluated it sets the base loads with each scheduled one at its value then.
#[derive(Debug, Clone)]
pub struct Scheduled<S: Loaded> {
    system: S,
    schedules: Vec<Schedule<S::Parameter>>,
    /// The loads without schedules, and the time the system's loads were last set for.
    base: S::Loads,
    time: f64,
}

impl ScheduledSystem {
    /// The system of `m` ([`MechanismSystem::new`]) with its schedules.
    pub fn new(m: &Mechanism) -> Result<Self> {
        Scheduled::with(MechanismSystem::new(m)?, m.schedules.clone(), m.loads())
    }
}

impl<S: Loaded> Scheduled<S> {
    /// `system` under `base` with `schedules` applied, its loads set for t = 0.
    pub fn with(mut system: S, schedules: Vec<Schedule<S::Parameter>>, base: S::Loads) -> Result<Self> {
        let mut loads = base.clone();
        apply(&schedules, 0.0, &mut loads, S::set);
        system.set_loads(loads)?;
        Ok(Scheduled { system, schedules, base, time: 0.0 })
    }

    /// The system, with the loads of the last time evaluated.
    pub fn system(&mut self) -> &mut S {
        &mut self.system
    }

    fn at(&mut self, t: f64) -> Result<()> {
        if t != self.time && !self.schedules.is_empty() {
            let mut loads = self.base.clone();
            apply(&self.schedules, t, &mut loads, S::set);
            self.system.set_loads(loads)?;
            self.time = t;
        }
        Ok(())
    }
}

impl<S: Loaded> System for Scheduled<S> {
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

    fn jumps(&self) -> Vec<f64> {
        let mut times: Vec<f64> = self.schedules.iter().flat_map(Schedule::jumps).collect();
        times.sort_by(f64::total_cmp);
        times.dedup();
        times
    }
}
