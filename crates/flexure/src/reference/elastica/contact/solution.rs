//! What [`contact`](super::contact) returns: the shape, its contacts, the
//! events along the load path and why the path stopped.

use crate::error::{Error, Result};

/// The state of a contact at the end of the path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactState {
    /// Frictionless and closed: gap zero, normal force $N \ge 0$, no tangential force.
    Closed,
    /// With friction, holding its place: $\lvert T\rvert \le \mu N$.
    Stick,
    /// With friction, sliding: $T = \pm\mu N$ against the motion.
    Slip,
}

/// One contact of a solved shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// Index of the obstacle touched.
    pub obstacle: usize,
    /// Arc length of the contact point (m): $L$ at the tip.
    pub s: f64,
    /// The centreline point there (m).
    pub point: [f64; 2],
    /// The obstacle's unit outward normal $\hat n$ there.
    pub normal: [f64; 2],
    /// $N = f\cdot\hat n$ (N), the normal force on the flexure: never
    /// negative beyond the event resolution.
    pub normal_force: f64,
    /// $T = f\cdot\hat t$ (N) along $\hat t = (-n_y, n_x)$: zero when frictionless.
    pub friction_force: f64,
    /// The gap there (m): zero to the solver's tolerance.
    pub gap: f64,
    /// Closed, stuck or slipping.
    pub state: ContactState,
}

impl ContactPoint {
    /// The force $f = N\hat n + T\hat t$ (N) the obstacle puts on the flexure.
    ///
    /// # Example
    /// ```
    /// use flexure::reference::elastica::contact::{ContactPoint, ContactState};
    /// let c = ContactPoint { obstacle: 0, s: 1.0, point: [1.0, 0.0], normal: [0.0, 1.0],
    ///     normal_force: 2.0, friction_force: 0.5, gap: 0.0, state: ContactState::Stick };
    /// assert_eq!(c.force(), [-0.5, 2.0]);
    /// ```
    pub fn force(&self) -> [f64; 2] {
        let (n, t) = (self.normal, [-self.normal[1], self.normal[0]]);
        [self.normal_force * n[0] + self.friction_force * t[0], self.normal_force * n[1] + self.friction_force * t[1]]
    }
}

/// What changed in the active set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EventKind {
    /// A gap closed: a new contact.
    Touch,
    /// A normal force fell to zero: the contact opened.
    Open,
    /// The tip's tangent turned away from the surface (the tip lifts): its
    /// contact moved into the span.
    Roll,
    /// A contact inside the span reached the tip and stays there: a tip contact again.
    Unroll,
    /// A stuck contact's friction reached $\mu N$: it slips.
    Slip,
    /// A slipping contact stopped and sticks again.
    Stick,
}

/// An event along the load path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEvent {
    /// The path parameter where it happened (leg $i$ runs from $i$ to $i + 1$).
    pub load: f64,
    /// What happened.
    pub kind: EventKind,
    /// The obstacle.
    pub obstacle: usize,
    /// Arc length of the contact (m).
    pub s: f64,
}

/// Why the path stopped, as argmin's termination reasons say.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactStop {
    /// The end of the path was reached.
    Reached,
    /// A step could not be taken (its error says what was reached).
    Stalled(Error),
    /// The path reached what this reference does not handle (named by the error):
    /// the shape returned is the last one it handles.
    Refused(Error),
}

/// An exact elastica with contacts, at the end of its load path (or where it stopped).
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSolution {
    /// The shape from root to tip, at the integrator's steps (the contact
    /// points twice: before and after the force's jump).
    pub shape: Vec<super::super::Point>,
    /// The closed contacts, by arc length.
    pub contacts: Vec<ContactPoint>,
    /// Bending moment at the root $m(0)$ (N·m).
    pub root_moment: f64,
    /// The force the clamp puts on the flexure (N): $-(F + \sum_c f_c)$.
    pub reaction: [f64; 2],
    /// The path parameter reached, from 0 to the number of legs.
    pub load: f64,
    /// Accepted load steps.
    pub steps: usize,
    /// The active-set changes along the path, in order.
    pub events: Vec<ContactEvent>,
    /// Why it stopped.
    pub stop: ContactStop,
}

impl ContactSolution {
    /// Whether the whole path was followed.
    ///
    /// # Example
    /// ```
    /// use flexure::reference::elastica::{contact, contact::ContactStop};
    /// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
    /// let s = contact(&f, &[], 0.0, &[flexure::TipLoad { moment: 0.5, fx: 0.0, fy: 0.0 }], &Default::default()).unwrap();
    /// assert!(s.reached() && s.stop == ContactStop::Reached);
    /// ```
    pub fn reached(&self) -> bool {
        self.stop == ContactStop::Reached
    }

    /// The solution if the path was followed to its end, else the error that stopped it.
    ///
    /// # Example
    /// ```
    /// use flexure::reference::elastica::contact::{contact, Obstacle};
    /// use flexure::{Flexure, TipLoad};
    /// let f = Flexure::new(1.0, 1.0, 3).unwrap();
    /// let floor = [Obstacle::half_plane([0.0, -0.5], [0.0, 1.0])];
    /// let load = [TipLoad { moment: -0.1, fx: 0.0, fy: 0.0 }];
    /// let s = contact(&f, &floor, 0.0, &load, &Default::default()).unwrap().into_result().unwrap();
    /// assert!(s.contacts.is_empty() && s.load == 1.0);
    /// ```
    pub fn into_result(self) -> Result<Self> {
        match self.stop {
            ContactStop::Reached => Ok(self),
            ContactStop::Stalled(e) | ContactStop::Refused(e) => Err(e),
        }
    }

    /// The smallest gap (m) to `obstacle` among the shape's points (the
    /// integrator's steps and the contact points).
    ///
    /// # Example
    /// ```
    /// use flexure::reference::elastica::{contact, contact::Obstacle};
    /// use flexure::{Flexure, TipLoad};
    /// let f = Flexure::new(1.0, 1.0, 3).unwrap();
    /// let floor = Obstacle::half_plane([0.0, -0.1], [0.0, 1.0]);
    /// let s = contact(&f, &[floor], 0.0, &[TipLoad { moment: 0.0, fx: 0.0, fy: -1.0 }], &Default::default()).unwrap();
    /// // Pressed onto the floor: the gap closes at the tip, never below zero.
    /// assert!(s.min_gap(&floor, 0.0).abs() < 1e-12 && s.contacts[0].s == 1.0);
    /// ```
    pub fn min_gap(&self, obstacle: &super::Obstacle, half_thickness: f64) -> f64 {
        self.shape.iter().fold(f64::INFINITY, |m, p| m.min(obstacle.gap([p.x, p.y], half_thickness)))
    }
}
