//! The interface between a mechanical system and the time integrator.
//!
//! A system has $n$ generalized coordinates $q$ and $m$ closure equations
//! $c(q) = 0$ with Jacobian $G = \partial c/\partial q$. Its equations of motion are
//!
//! $$M(q)\ddot q = f(q, \dot q, t) - G^T\lambda, \qquad c(q) = 0,$$
//!
//! where the generalized force $f = Q(q, t) - h(q, \dot q) - \nabla U(q) - D\dot q$
//! collects the applied loads $Q$, the velocity-product terms
//! $h = \dot M\dot q - \frac12\nabla_q(\dot q^TM\dot q)$, the elastic and
//! gravitational forces and the damping. $M$ may be singular (massless
//! flexures carry no inertia in some directions): an integrator must not
//! invert it, only the Newton matrix $M - \gamma h\thinspace\partial_{\dot q}f -
//! \beta h^2\partial_qf$ (with the closure rows), which the elastic
//! stiffness keeps regular.
//!
//! Matrices are column-major: `a[j * rows + i]` is row $i$, column $j$.

use crate::error::Result;

/// A mechanical system for [`crate::dynamics`]'s time integration and modes.
pub trait System {
    /// Number of coordinates $n$.
    fn dim(&self) -> usize;

    /// Number of closure equations $m$ (0 for a tree).
    fn closures(&self) -> usize;

    /// Writes $M(q)$ ($n\times n$) and $f(q, \dot q, t)$ ($n$). An `Err`
    /// marks a state that cannot be evaluated.
    fn dynamics(&mut self, q: &[f64], v: &[f64], t: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()>;

    /// Writes $-\partial f/\partial q$ (the tangent stiffness) and
    /// $-\partial f/\partial\dot q$ (the tangent damping), each $n\times n$, at the
    /// state last passed to [`System::dynamics`]. They enter only the Newton
    /// matrix, so they need to be accurate enough for convergence, not exact.
    fn tangent(&mut self, q: &[f64], v: &[f64], t: f64, stiffness: &mut [f64], damping: &mut [f64]) -> Result<()>;

    /// Writes $c(q)$ ($m$) and $G(q)$ ($m\times n$). The default, for a tree, writes nothing.
    fn closure(&mut self, _q: &[f64], _c: &mut [f64], _g: &mut [f64]) -> Result<()> {
        Ok(())
    }

    /// Which closure rows hold velocities, not positions: for such a row $k$
    /// the integrator holds $G_k(q)\dot q = 0$ and ignores $c_k$ (a contact
    /// that rolls without slipping: its material points' relative velocity
    /// along the surface is zero, which no function of $q$ alone says in
    /// space). One entry per closure row, asked at the start and after each
    /// [`System::switch`]. The default: none.
    fn velocity_closures(&self) -> Vec<bool> {
        vec![false; self.closures()]
    }

    /// Writes $W$ ($m\times n$), the directions in which the closures'
    /// multipliers act: the equations of motion read
    /// $M\ddot q = f - W^T\lambda$. It is $G$ (given) for closures that do no
    /// work, the default; a contact sliding with friction pushes off its
    /// gap's gradient, its row $\nabla g - \mu\thinspace\hat s^T\Delta$ ($\hat s$ the
    /// sliding direction, $\Delta$ its point's Jacobian), which depends on the
    /// velocities.
    fn closure_forces(&mut self, _q: &[f64], _v: &[f64], g: &[f64], w: &mut [f64]) -> Result<()> {
        w.copy_from_slice(g);
        Ok(())
    }

    /// The total energy $T + U$ (kinetic, elastic and gravitational; J) at a
    /// state, for energy checks and reports. Work done by the applied loads
    /// $Q$ and by damping is not included.
    fn energy(&mut self, q: &[f64], v: &[f64], t: f64) -> Result<f64>;

    /// The largest rotation (rad) of any section or body between two
    /// configurations: bounds the integrator's step as it bounds the
    /// continuation's ([`crate::solver::Problem::distance`]).
    fn distance(&self, a: &[f64], b: &[f64]) -> f64;

    /// How the error test measures each coordinate ([`ErrorWeights`]), read
    /// once at the run's start. The default: each coordinate on its own,
    /// with weight 1 (a mechanism with geoms keeps it).
    fn error_weights(&self) -> ErrorWeights {
        ErrorWeights::unit(self.dim())
    }

    /// The times (s, ascending) at which the applied loads jump: at each,
    /// [`System::dynamics`] gives the new load from that time on, and the
    /// integrator lands on it and evaluates the step that ends there just
    /// before it. The default: none.
    fn jumps(&self) -> Vec<f64> {
        Vec::new()
    }

    /// Writes the system's guards at a state the integrator reached: the
    /// functions whose fall below zero is an event that changes its mode
    /// (a contact that touches, or one that pulls and opens), each scaled so
    /// that 1 is the resolution it asks ($\lvert g\rvert \le 1$ is on the
    /// event). `multipliers` are the closures' $\lambda$ there, as the
    /// stage equations solved them, or `None` where none were (the start, or
    /// just after a switch): a guard on them is then reported positive. `out`
    /// has [`System::guard_count`] entries. The default: none.
    fn guards(&mut self, _q: &[f64], _v: &[f64], _multipliers: Option<&[f64]>, _out: &mut [f64]) -> Result<()> {
        Ok(())
    }

    /// The number of guards in the current mode ([`System::guards`]).
    fn guard_count(&self) -> usize {
        0
    }

    /// The events of guards `ks` (of the current mode) at time `t` and the state
    /// $(q, \dot q)$ the integrator landed on: the mode changes, and
    /// [`System::closures`] and [`System::guard_count`] may change with it.
    /// The integrator then moves the state onto the new closures, the
    /// velocities by a perfectly inelastic impact.
    fn switch(&mut self, _ks: &[usize], _t: f64, _q: &[f64], _v: &[f64]) -> Result<()> {
        Ok(())
    }

    /// Why a step's end $q$, outside any event's bracket and clear of
    /// every guard, went through
    /// something between two states that no guard sees (two geoms edge
    /// across edge past each other), if it did: the step is refused and
    /// shortened, and the run stops with this cause only where it cannot
    /// shorten. The default: never.
    fn passed(&mut self, _q: &[f64]) -> Result<Option<String>> {
        Ok(None)
    }

    /// Told of each step the run accepts, at its end $(q, \dot q)$ (before
    /// any switch there): a system whose guards are measured from the state
    /// the run has reached takes it here (a slide's direction, which turns
    /// as it slides in space). Not told of steps refused, nor of steps taken
    /// within an event's bracket (its guards stay those it was bracketed
    /// with). The default: nothing.
    fn accepted(&mut self, _q: &[f64], _v: &[f64]) -> Result<()> {
        Ok(())
    }

    /// Told of each sample as it is recorded, with the closures' multipliers
    /// of the step that reached it (`None` at the start and just after a
    /// switch). An error ends the run there, as a sample's energy's does.
    fn sampled(&mut self, _t: f64, _q: &[f64], _v: &[f64], _multipliers: Option<&[f64]>) -> Result<()> {
        Ok(())
    }

    /// Numbers of its own at the sample it was last told of
    /// ([`System::sampled`]), reported beside the sample's
    /// ([`crate::dynamics::integrate::Sample::columns`]): none by default.
    fn sample_columns(&self) -> Vec<f64> {
        Vec::new()
    }
}

/// How the integrator's error test measures the coordinates
/// ([`System::error_weights`]; module docs of [`crate::dynamics::integrate`]).
/// A coordinate's error counts times its `weight` (greater than 0, at most
/// 1), and is measured against `absolute` plus `tolerance` times the largest
/// weighted size in its `group`. A mechanism groups each joint's
/// coordinates and weighs them by the section turn a unit of each makes
/// ([`crate::mechanism::Joint::error_weights`]): its error test is in
/// radians of turn, relative to the joint's own.
#[derive(Debug, Clone, PartialEq)]
pub struct ErrorWeights {
    /// Each coordinate's group (any labels; equal labels share a size).
    pub group: Vec<usize>,
    /// Each coordinate's weight.
    pub weight: Vec<f64>,
}

impl ErrorWeights {
    /// `n` coordinates each on its own, with weight 1: each measured
    /// against its own size.
    ///
    /// # Example
    /// ```
    /// let w = flexure::dynamics::system::ErrorWeights::unit(2);
    /// assert_eq!((w.group, w.weight), (vec![0, 1], vec![1.0, 1.0]));
    /// ```
    pub fn unit(n: usize) -> Self {
        ErrorWeights { group: (0..n).collect(), weight: vec![1.0; n] }
    }
}
