//! Loads in time: the `[[schedule]]` tables of a mechanism file, and the
//! [`System`] that applies them.
//!
//! A schedule gives one load (named as sweeps name them:
//! `tendon.NAME.tension`, `force.NAME.fx|fy|moment`, `gravity.x|y`) in
//! time, by one of two [`Waveform`]s.
//!
//! **Points** $(t_k, v_k)$ with $t_0 \le t_1 \le \dots$: between two points
//! the load is linear in time, before the first and after the last it stays
//! at the end value,
//!
//! $$v(t) = v_k + \frac{t - t_k}{t_{k+1} - t_k}(v_{k+1} - v_k),\quad t_k \le t \le t_{k+1};
//! \qquad v(t) = v_0,\ t < t_0;\qquad v(t) = v_K,\ t > t_K;$$
//!
//! two points at one time are a **step**: the load jumps there from the
//! first value to the second, and takes the second from that time on (it is
//! continuous from the right). The integrator lands on each step's time and
//! ends the step before it with the load just before the jump
//! ([`crate::dynamics::System::jumps`]), so a step costs no accuracy.
//!
//! **Harmonic**: $v(t) = v_0 + A\sin(2\pi f t + \varphi)$, with offset
//! $v_0$, amplitude $A$, frequency $f$ (Hz) and phase $\varphi$ (rad).
//!
//! Loads without a schedule keep the file's value at all times.

use super::mechanism::MechanismSystem;
use super::system::System;
use crate::error::Result;
use crate::mechanism::sweep::Parameter;
use crate::mechanism::{Loads, Mechanism};

/// How a scheduled load varies in time (module docs).
#[derive(Debug, Clone, PartialEq)]
pub enum Waveform {
    /// Points `[t (s), value]`, at least one, times not decreasing, at most
    /// two at one time (a step).
    Points(Vec<[f64; 2]>),
    /// $v_0 + A\sin(2\pi f t + \varphi)$.
    Harmonic {
        /// $A$, in the load's unit.
        amplitude: f64,
        /// $f$ (Hz).
        frequency: f64,
        /// $\varphi$ (rad).
        phase: f64,
        /// $v_0$, in the load's unit.
        offset: f64,
    },
}

/// One load given in time (module docs), checked by the file parser.
#[derive(Debug, Clone, PartialEq)]
pub struct Schedule {
    /// The load's name, as in the file (`tendon.flexor.tension`).
    pub load: String,
    /// The load it sets.
    pub parameter: Parameter,
    /// Its values in time.
    pub waveform: Waveform,
}

impl Schedule {
    /// The load's value at time `t` (s): linear between points (the later
    /// value at a step's time), constant outside them; or the harmonic.
    ///
    /// # Example
    /// ```
    /// use flexure::dynamics::schedule::{Waveform, Schedule};
    /// use flexure::mechanism::sweep::Parameter;
    /// let ramp = Waveform::Points(vec![[0.0, 0.0], [2.0, -10.0]]);
    /// let s = Schedule { load: "gravity.y".into(), parameter: Parameter::Gravity(1), waveform: ramp };
    /// assert_eq!((s.value(-1.0), s.value(0.5), s.value(3.0)), (0.0, -2.5, -10.0));
    /// // A step from 0 to 1 at t = 1: the new value from t = 1 on.
    /// let step = Waveform::Points(vec![[1.0, 0.0], [1.0, 1.0]]);
    /// let s = Schedule { waveform: step, ..s };
    /// assert_eq!((s.value(0.999), s.value(1.0), s.value(2.0)), (0.0, 1.0, 1.0));
    /// assert_eq!(s.jumps().collect::<Vec<_>>(), [1.0]);
    /// ```
    pub fn value(&self, t: f64) -> f64 {
        let p = match &self.waveform {
            Waveform::Points(p) => p,
            Waveform::Harmonic { amplitude, frequency, phase, offset } => {
                return offset + amplitude * (std::f64::consts::TAU * frequency * t + phase).sin();
            }
        };
        let (first, last) = (p[0], p[p.len() - 1]);
        if t < first[0] {
            return first[1];
        }
        if t >= last[0] {
            return last[1];
        }
        // The first point after t: 1 ≤ k < len; the one before is the last
        // at or before t (a step's second point at its time).
        let k = p.partition_point(|q| q[0] <= t);
        let (a, b) = (p[k - 1], p[k]);
        let s = (t - a[0]) / (b[0] - a[0]);
        a[1] + s * (b[1] - a[1])
    }

    /// The times of the steps: where two points share a time.
    pub fn jumps(&self) -> impl Iterator<Item = f64> + '_ {
        let points: &[[f64; 2]] = match &self.waveform {
            Waveform::Points(p) => p,
            Waveform::Harmonic { .. } => &[],
        };
        points.windows(2).filter(|w| w[0][0] == w[1][0]).map(|w| w[0][0])
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
/// assert_eq!(loads_at(&m, 0.05).force, [[0.0, 5.0, 1.0]]);
/// assert_eq!(loads_at(&m, 1.0).force, [[0.0, 5.0, 2.0]]);
/// ```
pub fn loads_at(m: &Mechanism, t: f64) -> Loads {
    let mut loads = m.loads();
    apply(&m.schedules, t, &mut loads);
    loads
}

fn apply(schedules: &[Schedule], t: f64, loads: &mut Loads) {
    for s in schedules {
        let v = s.value(t);
        match s.parameter {
            Parameter::Tension(i) => loads.tension[i] = v,
            Parameter::Force(k, c) => loads.force[k][c] = v,
            Parameter::Gravity(c) => loads.gravity[c] = v,
        }
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
pub struct ScheduledSystem {
    system: MechanismSystem,
    schedules: Vec<Schedule>,
    /// The loads without schedules, and the time the system's loads were last set for.
    base: Loads,
    time: f64,
}

impl ScheduledSystem {
    /// The system of `m` ([`MechanismSystem::new`]) with its schedules.
    pub fn new(m: &Mechanism) -> Result<Self> {
        let mut system = MechanismSystem::new(m)?;
        let base = m.loads();
        system.set_loads(loads_at(m, 0.0))?;
        Ok(ScheduledSystem { system, schedules: m.schedules.clone(), base, time: 0.0 })
    }

    /// The mechanism's system, with the loads of the last time evaluated.
    pub fn system(&mut self) -> &mut MechanismSystem {
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

impl System for ScheduledSystem {
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
