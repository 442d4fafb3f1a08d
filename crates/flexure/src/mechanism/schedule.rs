//! Loads in time: the `[[schedule]]` tables of a mechanism file, as plain
//! data that the file parser builds and the time integration evaluates.
//!
//! A schedule gives one load (named as sweeps name them:
//! `tendon.NAME.tension`, `force.NAME.fx|fy|moment`, `gravity.x|y`; in a
//! spatial file `force.NAME.mx|my|mz|fx|fy|fz` and `gravity.x|y|z`) in
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
//! ends the step before it with the load just before the jump (the
//! [`Schedule::jumps`]), so a step costs no accuracy.
//!
//! **Harmonic**: $v(t) = v_0 + A\sin(2\pi f t + \varphi)$, with offset
//! $v_0$, amplitude $A$, frequency $f$ (Hz) and phase $\varphi$ (rad).
//!
//! Loads without a schedule keep the file's value at all times.

use super::sweep::Parameter;

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
    /// use flexure::mechanism::schedule::{Schedule, Waveform};
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
