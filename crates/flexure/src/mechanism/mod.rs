//! Mechanisms: trees of rigid bodies joined by flexures, pins, sliders and
//! welds, closed into loops by weld and pin closures, loaded by tendons,
//! point forces, moments and gravity.
//!
//! Bodies are created by the joints that name them as `child`; body 0 is
//! `ground`. Each joint's `origin` is the pose of its root frame in the
//! parent body's frame, and the child body's frame is the joint's output
//! frame (for a flexure, the tip frame of Eq. 7).

pub mod buckling;
pub mod equilibria;
pub mod file;
pub mod findings;
mod hints;
mod indeterminate;
pub mod joints;
pub mod kinematics;
pub mod lagrangian;
mod pencil;
pub mod schedule;
pub mod spatial;
pub mod statics;
pub mod sweep;
mod tree;

use crate::space::{Pose, Wrench};
pub use joints::{Fixed, Joint, JointKind, JointState, Prismatic, Revolute};
use nalgebra::{Point2, Vector2};

/// A rigid body: a name and its inertia ([`Body::rigid_inertia`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Its name.
    pub name: String,
    /// Mass (kg), for gravity and dynamics.
    pub mass: f64,
    /// Rotary inertia (kg·m²) about the centre of mass, for dynamics.
    pub inertia: f64,
    /// Centre of mass in the body frame (m).
    pub com: Point2<f64>,
}

impl Body {
    /// Its mass, rotary inertia and centre of mass: the
    /// [`RigidInertia`](crate::inertia::RigidInertia) that gravity and the
    /// dynamics use, as a flexure's tip body is.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::Body;
    /// let arm = Body { name: "arm".into(), mass: 0.2, inertia: 1e-4, com: nalgebra::Point2::new(0.05, 0.0) };
    /// // About the body frame's origin: I_c + m|c|².
    /// assert!((arm.rigid_inertia().inertia_about_tip() - (1e-4 + 0.2 * 0.05 * 0.05)).abs() < 1e-15);
    /// ```
    pub fn rigid_inertia(&self) -> crate::inertia::RigidInertia {
        crate::inertia::RigidInertia { mass: self.mass, inertia: self.inertia, com: [self.com.x, self.com.y] }
    }
}

/// A joint between two bodies.
#[derive(Debug, Clone, PartialEq)]
pub struct JointSpec {
    /// Its name.
    pub name: String,
    /// What it is.
    pub kind: JointKind,
    /// Parent body index.
    pub parent: usize,
    /// Child body index.
    pub child: usize,
    /// Root frame in the parent body's frame.
    pub origin: Pose,
    /// Index of its first coordinate in $q$.
    pub offset: usize,
    /// Damping, for dynamics: on a flexure the stiffness-proportional
    /// coefficient $\beta$ (s), $D = \beta K$; on a revolute or prismatic joint
    /// the viscous coefficient (N·m·s/rad or N·s/m); zero on a fixed joint.
    pub damping: f64,
    /// A flexure given `order = "auto"`: its order (3 to start) is raised
    /// until an analysis's error estimate meets its target
    /// ([`crate::estimate::buckle_auto`], [`crate::estimate::mechanism_modes_auto`]).
    pub auto_order: bool,
}

/// A tendon of constant tension through via points; potential tension × length.
#[derive(Debug, Clone, PartialEq)]
pub struct Tendon {
    /// Its name.
    pub name: String,
    /// Tension (N), not negative.
    pub tension: f64,
    /// Via points: (body, position in the body frame).
    pub path: Vec<(usize, Point2<f64>)>,
}

/// A force and moment applied to a point of a body.
#[derive(Debug, Clone, PartialEq)]
pub struct PointLoad {
    /// Its name (or its index, as text).
    pub name: String,
    /// The body.
    pub body: usize,
    /// Point of application in the body frame (m).
    pub at: Point2<f64>,
    /// Moment (N·m) and force (N, in the ground frame).
    pub wrench: Wrench,
}

/// A loop closure.
#[derive(Debug, Clone, PartialEq)]
pub enum Closure {
    /// Frame `a_origin` on body `a` coincides with frame `b_origin` on body `b` (3 equations).
    Weld {
        /// First body.
        a: usize,
        /// Frame on it.
        a_origin: Pose,
        /// Second body.
        b: usize,
        /// Frame on it.
        b_origin: Pose,
    },
    /// Point `a_at` on body `a` coincides with point `b_at` on body `b` (2 equations).
    Pin {
        /// First body.
        a: usize,
        /// Point on it.
        a_at: Point2<f64>,
        /// Second body.
        b: usize,
        /// Point on it.
        b_at: Point2<f64>,
    },
}

impl Closure {
    /// Number of scalar equations.
    pub fn equations(&self) -> usize {
        match self {
            Closure::Weld { .. } => 3,
            Closure::Pin { .. } => 2,
        }
    }
}

/// The magnitudes of every load, which continuation and sweeps scale.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Loads {
    /// Tendon tensions, in the order of [`Mechanism::tendons`].
    pub tension: Vec<f64>,
    /// The wrench of each point load, in the order of [`Mechanism::forces`].
    pub force: Vec<Wrench>,
    /// Gravity (m/s²).
    pub gravity: Vector2<f64>,
}

/// `(1 − s)·a + s·b`, each component.
fn mix_wrench(a: &Wrench, b: &Wrench, s: f64) -> Wrench {
    let (a, b) = (a.to_array(), b.to_array());
    Wrench::from_array(std::array::from_fn(|i| a[i] + s * (b[i] - a[i])))
}

impl Loads {
    /// `(1 − s)·self + s·other`.
    pub fn lerp(&self, other: &Loads, s: f64) -> Loads {
        let mix = |a: f64, b: f64| a + s * (b - a);
        Loads {
            tension: self.tension.iter().zip(&other.tension).map(|(a, b)| mix(*a, *b)).collect(),
            force: self.force.iter().zip(&other.force).map(|(a, b)| mix_wrench(a, b, s)).collect(),
            gravity: Vector2::from_fn(|i, _| mix(self.gravity[i], other.gravity[i])),
        }
    }

    /// [`Loads::lerp`] into `out` (shaped like `self`), without allocating.
    pub fn lerp_into(&self, other: &Loads, s: f64, out: &mut Loads) {
        let mix = |a: f64, b: f64| a + s * (b - a);
        for ((o, a), b) in out.tension.iter_mut().zip(&self.tension).zip(&other.tension) {
            *o = mix(*a, *b);
        }
        for ((o, a), b) in out.force.iter_mut().zip(&self.force).zip(&other.force) {
            *o = mix_wrench(a, b, s);
        }
        out.gravity = Vector2::from_fn(|i, _| mix(self.gravity[i], other.gravity[i]));
    }

    /// Checks that the loads fit `m` (a tension per tendon, a triple per
    /// point load), are finite, and that no tension is negative.
    pub fn validate(&self, m: &Mechanism) -> crate::Result<()> {
        use crate::Error;
        if self.tension.len() != m.tendons.len() || self.force.len() != m.forces.len() {
            return Err(Error::invalid(
                "loads",
                format!("{} tensions and {} forces", self.tension.len(), self.force.len()),
                "must have one tension per tendon and one wrench per force of the mechanism",
            ));
        }
        let wrenches = self.force.iter().flat_map(|w| w.to_array());
        let all = self.tension.iter().copied().chain(wrenches).chain(self.gravity.iter().copied());
        if let Some(v) = all.into_iter().find(|v| !(v.is_finite() && v.abs() <= file::MAX_MAGNITUDE)) {
            return Err(Error::invalid("loads", v, "must be finite and at most 1e30 in magnitude"));
        }
        if let Some(t) = self.tension.iter().find(|t| **t < 0.0) {
            return Err(Error::invalid("tension", t, "a tendon's tension must not be negative"));
        }
        Ok(())
    }

    /// No load at all.
    pub fn zero_like(&self) -> Loads {
        self.clone().scaled(0.0)
    }

    fn scaled(mut self, s: f64) -> Loads {
        self.scale(s);
        self
    }

    /// Every load times `s`, in place.
    pub(crate) fn scale(&mut self, s: f64) {
        self.tension.iter_mut().for_each(|t| *t *= s);
        self.force.iter_mut().for_each(|f| (0..3).for_each(|i| f[i] *= s));
        self.gravity.iter_mut().for_each(|g| *g *= s);
    }
}

/// An immutable mechanism (the Model): build it with [`file::from_toml`].
#[derive(Debug, Clone, PartialEq)]
pub struct Mechanism {
    /// Bodies; index 0 is `ground`.
    pub bodies: Vec<Body>,
    /// Joints in an order where every parent comes before its children.
    pub joints: Vec<JointSpec>,
    /// Tendons.
    pub tendons: Vec<Tendon>,
    /// Point loads.
    pub forces: Vec<PointLoad>,
    /// Loop closures.
    pub closures: Vec<Closure>,
    /// Gravity (m/s²), zero if absent.
    pub gravity: Vector2<f64>,
    /// Loads in time (`[[schedule]]`), for dynamics; statics use the loads as given.
    pub schedules: Vec<schedule::Schedule>,
    /// `[initial]`: (joint, coordinates) that override a simulation's start.
    pub initial: Vec<(usize, Vec<f64>)>,
    /// `[initial_velocity]`: (joint, coordinate rates) of a simulation's start.
    pub initial_velocity: Vec<(usize, Vec<f64>)>,
    /// `parent_joint[b]`: the joint whose child is body `b`.
    parent_joint: Vec<Option<usize>>,
    dof: usize,
    /// "line L, column C" of each closure in the file, for errors.
    closure_places: Vec<String>,
    /// `preload = true` of each closure: its gap at rest is meant.
    closure_preloads: Vec<bool>,
}

impl Mechanism {
    /// The mechanism's size (m): the sum of its joints' offsets and flexure
    /// lengths (1 m for a mechanism of points). Slider travel is measured
    /// against it, to compare with rotations.
    pub fn size(&self) -> f64 {
        let length = self
            .joints
            .iter()
            .map(|j| j.origin.x.hypot(j.origin.y) + j.kind.flexure().map_or(0.0, |f| f.length()))
            .sum::<f64>();
        if length > 0.0 && length.is_finite() { length } else { 1.0 }
    }

    /// Number of generalized coordinates.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// Number of closure equations.
    pub fn constraints(&self) -> usize {
        self.closures.iter().map(Closure::equations).sum()
    }

    /// The body's index by name.
    pub fn body(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// The joint with `body` as its child.
    pub fn parent_joint(&self, body: usize) -> Option<usize> {
        self.parent_joint[body]
    }

    /// Coordinates of the unloaded joints.
    pub fn rest(&self) -> Vec<f64> {
        self.joints.iter().flat_map(|j| j.kind.joint().rest()).collect()
    }

    /// [`Mechanism::rest`] into `q` (one value per coordinate), without allocating.
    pub(crate) fn rest_into(&self, q: &mut [f64]) {
        for j in &self.joints {
            let joint = j.kind.joint();
            joint.rest_into(&mut q[j.offset..j.offset + joint.dof()]);
        }
    }

    /// [`Mechanism::loads`] into `out`, in its buffers.
    pub(crate) fn loads_into(&self, out: &mut Loads) {
        out.tension.clear();
        out.tension.extend(self.tendons.iter().map(|t| t.tension));
        out.force.clear();
        out.force.extend(self.forces.iter().map(|f| f.wrench));
        out.gravity = self.gravity;
    }

    /// The loads as given.
    pub fn loads(&self) -> Loads {
        Loads {
            tension: self.tendons.iter().map(|t| t.tension).collect(),
            force: self.forces.iter().map(|f| f.wrench).collect(),
            gravity: self.gravity,
        }
    }

    /// Where closure `i` was given in the file ("line L, column C").
    pub fn closure_place(&self, i: usize) -> &str {
        self.closure_places.get(i).map_or("the file", String::as_str)
    }

    /// Whether closure `i` says `preload = true`: that it is meant to be
    /// open at rest, so that closing it preloads the mechanism
    /// ([`findings::open_closures`] then notes its gap instead of warning).
    pub fn closure_preload(&self, i: usize) -> bool {
        self.closure_preloads.get(i).copied().unwrap_or(false)
    }

    /// Every point attached to body `b`, in its frame: its origin (where
    /// its joint holds it; not for the ground), the roots of the joints it
    /// carries, tendon via points, load points, closure points and, if it
    /// has a mass, its centre of mass. `flexure draw` draws a rigid link as
    /// their hull, and [`findings::crossings`] takes that hull's edges as
    /// the link's segments.
    pub fn attachments(&self, b: usize) -> Vec<Point2<f64>> {
        let mut pts = Vec::new();
        if b != 0 {
            pts.push(Point2::origin());
        }
        pts.extend(self.joints.iter().filter(|j| j.parent == b).map(|j| j.origin.origin()));
        pts.extend(self.tendons.iter().flat_map(|t| &t.path).filter(|v| v.0 == b).map(|v| v.1));
        pts.extend(self.forces.iter().filter(|f| f.body == b).map(|f| f.at));
        for c in &self.closures {
            let (a, ra, other, rb) = match c {
                Closure::Weld { a, a_origin, b, b_origin } => (*a, a_origin.origin(), *b, b_origin.origin()),
                Closure::Pin { a, a_at, b, b_at } => (*a, *a_at, *b, *b_at),
            };
            pts.extend([(a, ra), (other, rb)].into_iter().filter(|p| p.0 == b).map(|p| p.1));
        }
        if self.bodies[b].mass > 0.0 {
            pts.push(self.bodies[b].com);
        }
        pts
    }

    /// Joints from the ground to `body`, root first.
    pub fn path(&self, body: usize) -> Vec<usize> {
        let mut path = Vec::new();
        let mut b = body;
        while let Some(j) = self.parent_joint[b] {
            path.push(j);
            b = self.joints[j].parent;
        }
        path.reverse();
        path
    }

    /// The same mechanism with flexure joint `j` replaced by `refine(j, flexure)`
    /// where it returns one (another order or quadrature: the coordinates
    /// are renumbered, and `[initial]` coordinates padded with zeros or cut).
    pub fn with_flexures(
        &self,
        mut refine: impl FnMut(usize, &crate::joint::Flexure) -> crate::Result<Option<crate::joint::Flexure>>,
    ) -> crate::Result<Mechanism> {
        let mut m = self.clone();
        let mut offset = 0;
        for (j, spec) in m.joints.iter_mut().enumerate() {
            if let Some(f) = spec.kind.flexure()
                && let Some(g) = refine(j, f)?
            {
                spec.kind = JointKind::Flexure(Box::new(g));
            }
            spec.offset = offset;
            offset += spec.kind.joint().dof();
        }
        m.dof = offset;
        for (j, q) in m.initial.iter_mut().chain(m.initial_velocity.iter_mut()) {
            q.resize(m.joints[*j].kind.joint().dof(), 0.0);
        }
        Ok(m)
    }
}
