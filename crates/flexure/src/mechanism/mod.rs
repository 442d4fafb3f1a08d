//! Mechanisms: trees of rigid bodies joined by flexures, pins, sliders and
//! welds, closed into loops by weld and pin closures, loaded by tendons,
//! point forces, moments and gravity.
//!
//! Bodies are created by the joints that name them as `child`; body 0 is
//! `ground`. Each joint's `origin` is the pose of its root frame in the
//! parent body's frame, and the child body's frame is the joint's output
//! frame (for a flexure, the tip frame of Eq. 7).

pub mod buckling;
pub mod contact;
mod dimension;
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
pub mod stability_limit;
pub mod statics;
pub mod sweep;
mod tree;

use crate::space::{Planar, Wrench};
pub use dimension::Dimension;
pub use joints::{Fixed, Joint, JointKind, JointState, Prismatic, Revolute};
use nalgebra::Vector2;

/// A rigid body: a name and its inertia ([`Body::rigid_inertia`]), in
/// the dimension `D` ([`Planar`] by default).
#[derive(Debug, Clone, PartialEq)]
pub struct Body<D: Dimension = Planar> {
    /// Its name.
    pub name: String,
    /// Mass (kg), for gravity and dynamics.
    pub mass: f64,
    /// Rotary inertia about the centre of mass, for dynamics: kg·m² in the
    /// plane, the 3 × 3 matrix in the body frame's axes in space.
    pub inertia: D::AngularInertia,
    /// Centre of mass in the body frame (m).
    pub com: D::Point,
}

impl<D: Dimension> Body<D> {
    /// A massless body.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::Body;
    /// let b: Body = Body::massless("arm");
    /// assert_eq!((b.mass, b.inertia), (0.0, 0.0));
    /// ```
    pub fn massless(name: &str) -> Self {
        Body { name: name.into(), mass: 0.0, inertia: D::AngularInertia::default(), com: D::origin(&D::identity()) }
    }
}

impl Body<Planar> {
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
pub struct JointSpec<D: Dimension = Planar> {
    /// Its name.
    pub name: String,
    /// What it is.
    pub kind: JointKind<D>,
    /// Parent body index.
    pub parent: usize,
    /// Child body index.
    pub child: usize,
    /// Root frame in the parent body's frame (`pose_parent_root`).
    pub origin: D::Pose,
    /// Index of its first coordinate in $q$.
    pub offset: usize,
    /// Damping, for dynamics: on a flexure the stiffness-proportional
    /// coefficient $\beta$ (s), $D = \beta K$; on a hinge, slider or ball
    /// the viscous coefficient (N·m·s/rad or N·s/m); zero on a fixed joint.
    pub damping: f64,
    /// A flexure given `order = "auto"`: its order (3 to start; in space
    /// each of its three) is raised until an analysis's error estimate
    /// meets its target ([`crate::estimate::buckle_auto`],
    /// [`crate::estimate::mechanism_modes_auto`] and their spatial twins);
    /// other analyses take it as it is.
    pub auto_order: bool,
    /// What the solve report adds about a flexure joint (its file's
    /// `yield_strength` and `shape`); the default for the other kinds.
    pub report: ReportOptions,
}

impl<D: Dimension> JointSpec<D> {
    /// A joint of `kind` from body `parent` to body `child`, its root frame
    /// at `origin` in the parent's: no damping, its order as given, the
    /// report's defaults, and its `offset` set by [`Mechanism::new`].
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::{JointKind, JointSpec, Revolute};
    /// use flexure::kinematics::Pose;
    /// let pin = JointKind::Revolute(Revolute { stiffness: 1.0, rest: 0.0 });
    /// let j: JointSpec = JointSpec::new("pin", pin, 0, 1, Pose { x: 0.1, y: 0.0, phi: 0.0 });
    /// assert_eq!((j.offset, j.damping, j.auto_order), (0, 0.0, false));
    /// ```
    pub fn new(name: &str, kind: JointKind<D>, parent: usize, child: usize, origin: D::Pose) -> Self {
        let (offset, damping, auto_order, report) = (0, 0.0, false, ReportOptions::default());
        Self { name: name.into(), kind, parent, child, origin, offset, damping, auto_order, report }
    }
}

/// What the solve report gives of a flexure joint beyond its coordinates.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ReportOptions {
    /// `yield_strength` (Pa): the safety factor is this over the peak stress.
    pub yield_strength: Option<f64>,
    /// `shape`: the number of points, evenly spaced in arc length, at which to give the deformed flexure.
    pub shape: Option<usize>,
}

/// A tendon of constant tension through via points; potential tension × length.
#[derive(Debug, Clone, PartialEq)]
pub struct Tendon<D: Dimension = Planar> {
    /// Its name.
    pub name: String,
    /// Tension (N), not negative.
    pub tension: f64,
    /// Via points: (body, position in the body frame).
    pub path: Vec<(usize, D::Point)>,
}

/// A force and moment applied to a point of a body, both fixed in the
/// ground frame (dead loads).
#[derive(Debug, Clone, PartialEq)]
pub struct PointLoad<D: Dimension = Planar> {
    /// Its name (or its index, as text).
    pub name: String,
    /// The body.
    pub body: usize,
    /// Point of application in the body frame (m).
    pub at: D::Point,
    /// Moment (N·m) and force (N, in the ground frame), moment first.
    pub wrench: D::Wrench,
}

/// What a closure holds of its two frames' relative motion (rapier's
/// locked axes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Holds {
    /// Everything: the two frames coincide.
    Weld,
    /// The origins and the z axes: a hinge about z. In the plane, where
    /// every rotation is about z, the origins alone.
    Pin,
    /// The origins alone: a ball joint.
    Ball,
}

impl Holds {
    /// Its name in the file: `weld`, `pin` or `ball`.
    pub fn name(self) -> &'static str {
        match self {
            Holds::Weld => "weld",
            Holds::Pin => "pin",
            Holds::Ball => "ball",
        }
    }
}

/// A loop closure: frame `a_origin` on body `a` and frame `b_origin` on
/// body `b`, of whose relative motion it holds what `holds` says: a weld
/// all of it, a pin the origins and the axis (the frames' z), a ball the
/// origins. The planar pin is the spatial pin about z.
///
/// # Example
/// ```
/// use flexure::mechanism::{Closure, Holds};
/// use flexure::space::Spatial;
/// use nalgebra::{Point2, Point3, Vector3};
/// let pin: Closure = Closure::at_points(Holds::Pin, 0, Point2::new(1.0, 0.0), 1, Point2::origin());
/// assert_eq!((pin.equations(), pin.bodies()), (2, [0, 1]));
/// let hinge = Closure::<Spatial>::pin(0, Point3::origin(), Vector3::y(), 1, Point3::origin(), Vector3::y()).unwrap();
/// assert_eq!(hinge.equations(), 5);
/// // Each frame's z is its axis: a's third, b's sixth.
/// assert!((hinge.axes()[2] - Vector3::y()).norm() < 1e-15 && (hinge.axes()[5] - Vector3::y()).norm() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Closure<D: Dimension = Planar> {
    /// What it holds.
    pub holds: Holds,
    /// First body.
    pub a: usize,
    /// The frame on it (`pose_a_closure`).
    pub a_origin: D::Pose,
    /// Second body.
    pub b: usize,
    /// The frame on it (`pose_b_closure`).
    pub b_origin: D::Pose,
}

impl<D: Dimension> Closure<D> {
    /// A closure of frames at points `a_at` on `a` and `b_at` on `b`,
    /// with the bodies' axes (a planar pin, or a ball).
    pub fn at_points(holds: Holds, a: usize, a_at: D::Point, b: usize, b_at: D::Point) -> Self {
        Closure { holds, a, a_origin: D::at(&a_at), b, b_origin: D::at(&b_at) }
    }

    /// Number of scalar equations: a weld holds every component of the
    /// relative motion ([`Space::TWIST_DIM`](crate::space::Space::TWIST_DIM)),
    /// a pin all but the turn about its axis, a ball the origins
    /// ([`Space::POINT_DIM`](crate::space::Space::POINT_DIM)).
    pub fn equations(&self) -> usize {
        match self.holds {
            Holds::Weld => D::TWIST_DIM,
            Holds::Pin => D::TWIST_DIM - 1,
            Holds::Ball => D::POINT_DIM,
        }
    }

    /// `weld of "a" and "b"`, `pin of …` or `ball of …`, with the bodies'
    /// names in `m`.
    pub fn name(&self, m: &Mechanism<D>) -> String {
        format!("{} of {:?} and {:?}", self.holds.name(), m.bodies[self.a].name, m.bodies[self.b].name)
    }

    /// The two bodies it joins.
    pub fn bodies(&self) -> [usize; 2] {
        [self.a, self.b]
    }

    /// Each body with the point on it that the closure holds.
    pub fn points(&self) -> [(usize, D::Point); 2] {
        [(self.a, D::origin(&self.a_origin)), (self.b, D::origin(&self.b_origin))]
    }
}

/// The magnitudes of every load, which continuation and sweeps scale.
#[derive(Debug, Clone, PartialEq)]
pub struct Loads<D: Dimension = Planar> {
    /// Tendon tensions, in the order of [`Mechanism::tendons`].
    pub tension: Vec<f64>,
    /// The wrench of each point load, in the order of [`Mechanism::forces`].
    pub force: Vec<D::Wrench>,
    /// Gravity (m/s²).
    pub gravity: D::Vector,
}

impl<D: Dimension> Default for Loads<D> {
    fn default() -> Self {
        Loads { tension: Vec::new(), force: Vec::new(), gravity: D::Vector::default() }
    }
}

/// `(1 − s)·a + s·b`, each component.
fn mix_wrench(a: &Wrench, b: &Wrench, s: f64) -> Wrench {
    let (a, b) = (a.to_array(), b.to_array());
    Wrench::from_array(std::array::from_fn(|i| a[i] + s * (b[i] - a[i])))
}

impl Loads<Planar> {
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

/// An immutable mechanism (the Model), in the dimension `D` ([`Planar`]
/// by default, [`Spatial`](crate::space::Spatial) for a spatial one): build
/// it with [`file::from_toml`] or [`Mechanism::new`].
#[derive(Debug, Clone, PartialEq)]
pub struct Mechanism<D: Dimension = Planar> {
    /// Bodies; index 0 is `ground`.
    pub bodies: Vec<Body<D>>,
    /// Joints in an order where every parent comes before its children.
    pub joints: Vec<JointSpec<D>>,
    /// Tendons.
    pub tendons: Vec<Tendon<D>>,
    /// Point loads.
    pub forces: Vec<PointLoad<D>>,
    /// Loop closures.
    pub closures: Vec<Closure<D>>,
    /// The shapes on the ground and on bodies that parts may touch
    /// (`[[geom]]`; [`contact`]).
    pub geoms: Vec<contact::Geom<D>>,
    /// Gravity (m/s²), zero if absent.
    pub gravity: D::Vector,
    /// Loads in time (`[[schedule]]`), for dynamics; statics use the loads as given.
    pub schedules: Vec<schedule::Schedule>,
    /// `[initial]`: (joint, coordinates) that override a simulation's start.
    pub initial: Vec<(usize, Vec<f64>)>,
    /// `[initial_velocity]`: (joint, coordinate rates) of a simulation's start.
    pub initial_velocity: Vec<(usize, Vec<f64>)>,
    /// `parent_joint[b]`: the joint whose child is body `b`.
    parent_joint: Vec<Option<usize>>,
    dof: usize,
    /// "line L, column C" of each closure in the file, for errors (empty if built in code).
    closure_places: Vec<String>,
    /// `preload = true` of each closure: its gap at rest is meant.
    closure_preloads: Vec<bool>,
    /// "line L, column C" of each `[initial]` entry, in its order (empty if built in code).
    initial_places: Vec<String>,
}

impl<D: Dimension> Mechanism<D> {
    /// The mechanism of these parts: numbers each joint's coordinates and
    /// checks that every body but the ground is the child of exactly one
    /// joint whose parent comes before it, and that every index is a body.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::spatial::{Spherical, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism};
    /// let bob = SpatialBody { mass: 1.0, com: nalgebra::Point3::new(0.0, 0.0, -1.0), ..SpatialBody::massless("bob") };
    /// let ball = SpatialJointSpec {
    ///     name: "ball".into(), kind: SpatialJointKind::Spherical(Spherical { stiffness: 0.0, rest: [0.0; 3] }),
    ///     parent: 0, child: 1, origin: nalgebra::Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default(),
    /// };
    /// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), bob], vec![ball], vec![], vec![], vec![], nalgebra::Vector3::new(0.0, 0.0, -9.81)).unwrap();
    /// assert_eq!((m.dof(), m.constraints()), (3, 0));
    /// ```
    pub fn new(
        bodies: Vec<Body<D>>,
        mut joints: Vec<JointSpec<D>>,
        tendons: Vec<Tendon<D>>,
        forces: Vec<PointLoad<D>>,
        closures: Vec<Closure<D>>,
        gravity: D::Vector,
    ) -> crate::Result<Self> {
        use crate::Error;
        let nb = bodies.len();
        if nb == 0 {
            return Err(Error::invalid("bodies", 0, "a mechanism needs its ground, body 0"));
        }
        let mut parent_joint = vec![None; nb];
        let mut placed = vec![false; nb];
        placed[0] = true;
        let mut offset = 0;
        for (i, j) in joints.iter_mut().enumerate() {
            if j.parent >= nb || j.child >= nb || j.child == 0 {
                return Err(Error::invalid(
                    "joint",
                    &j.name,
                    "names a body that is not there (or the ground as child)",
                ));
            }
            if !placed[j.parent] {
                return Err(Error::invalid("joint", &j.name, "comes before the joint that places its parent"));
            }
            if placed[j.child] {
                return Err(Error::invalid("joint", &j.name, "places a body that another joint places already"));
            }
            placed[j.child] = true;
            parent_joint[j.child] = Some(i);
            j.offset = offset;
            offset += j.kind.joint().dof();
        }
        if let Some(b) = placed.iter().position(|p| !p) {
            return Err(Error::invalid("body", &bodies[b].name, "is not the child of any joint"));
        }
        let within = |b: usize| b < nb;
        for t in &tendons {
            if t.path.len() < 2 || !t.path.iter().all(|p| within(p.0)) {
                return Err(Error::invalid(
                    "tendon",
                    &t.name,
                    "needs two or more via points on bodies of the mechanism",
                ));
            }
        }
        if let Some(f) = forces.iter().find(|f| !within(f.body)) {
            return Err(Error::invalid("force", &f.name, "names a body that is not there"));
        }
        if closures.iter().any(|c| !c.bodies().into_iter().all(within)) {
            return Err(Error::invalid("closure", "a body index", "names a body that is not there"));
        }
        Ok(Mechanism {
            bodies,
            joints,
            tendons,
            forces,
            closures,
            geoms: Vec::new(),
            gravity,
            schedules: Vec::new(),
            initial: Vec::new(),
            initial_velocity: Vec::new(),
            parent_joint,
            dof: offset,
            closure_places: Vec::new(),
            closure_preloads: Vec::new(),
            initial_places: Vec::new(),
        })
    }

    /// The same mechanism with the file's places (`"line L, column C"`)
    /// and `preload` flags of its closures, in their order.
    pub fn with_closure_places(mut self, places: Vec<String>, preloads: Vec<bool>) -> Self {
        self.closure_places = places;
        self.closure_preloads = preloads;
        self
    }

    /// The mechanism's size (m): the sum of its joints' offsets and flexure
    /// lengths (1 m for a mechanism of points). Slider travel is measured
    /// against it, to compare with rotations.
    pub fn size(&self) -> f64 {
        let length = self
            .joints
            .iter()
            .map(|j| D::reach(&j.origin) + j.kind.flexure().map_or(0.0, D::flexure_length))
            .sum::<f64>();
        if length > 0.0 && length.is_finite() { length } else { 1.0 }
    }

    /// Number of generalized coordinates.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// Each coordinate's weight in the integrator's error test, joint by
    /// joint ([`Joint::error_weights`]).
    pub fn error_weights(&self) -> Vec<f64> {
        let mut out = vec![1.0; self.dof];
        for j in &self.joints {
            let joint = j.kind.joint();
            joint.error_weights(&mut out[j.offset..j.offset + joint.dof()]);
        }
        out
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
        let mut q = vec![0.0; self.dof];
        self.rest_into(&mut q);
        q
    }

    /// [`Mechanism::rest`] into `q` (one value per coordinate), without allocating.
    pub(crate) fn rest_into(&self, q: &mut [f64]) {
        for j in &self.joints {
            let joint = j.kind.joint();
            joint.rest_into(&mut q[j.offset..j.offset + joint.dof()]);
        }
    }

    /// [`Mechanism::loads`] into `out`, in its buffers.
    pub(crate) fn loads_into(&self, out: &mut Loads<D>) {
        out.tension.clear();
        out.tension.extend(self.tendons.iter().map(|t| t.tension));
        out.force.clear();
        out.force.extend(self.forces.iter().map(|f| f.wrench));
        out.gravity = self.gravity;
    }

    /// The loads as given.
    pub fn loads(&self) -> Loads<D> {
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

    /// Where `[initial]` entry `k` (of [`Mechanism::initial`]) was given in
    /// the file ("line L, column C").
    pub fn initial_place(&self, k: usize) -> &str {
        self.initial_places.get(k).map_or("the file", String::as_str)
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
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::spatial::{Spherical, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism};
    /// use nalgebra::{Isometry3, Point3, Vector3};
    /// let bob = SpatialBody { mass: 1.0, com: Point3::new(0.0, 0.0, -1.0), ..SpatialBody::massless("bob") };
    /// let ball = SpatialJointSpec {
    ///     name: "ball".into(), kind: SpatialJointKind::Spherical(Spherical { stiffness: 0.0, rest: [0.0; 3] }),
    ///     parent: 0, child: 1, origin: Isometry3::translation(0.0, 0.0, 2.0), offset: 0, damping: 0.0, auto_order: false, report: Default::default(),
    /// };
    /// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), bob], vec![ball], vec![], vec![], vec![], Vector3::zeros()).unwrap();
    /// assert_eq!(m.attachments(0), [Point3::new(0.0, 0.0, 2.0)]);
    /// assert_eq!(m.attachments(1), [Point3::origin(), Point3::new(0.0, 0.0, -1.0)]);
    /// ```
    pub fn attachments(&self, b: usize) -> Vec<D::Point> {
        let mut pts = Vec::new();
        if b != 0 {
            pts.push(D::origin(&D::identity()));
        }
        pts.extend(self.joints.iter().filter(|j| j.parent == b).map(|j| D::origin(&j.origin)));
        pts.extend(self.tendons.iter().flat_map(|t| &t.path).filter(|v| v.0 == b).map(|v| v.1));
        pts.extend(self.forces.iter().filter(|f| f.body == b).map(|f| f.at));
        for c in &self.closures {
            pts.extend(c.points().into_iter().filter(|p| p.0 == b).map(|p| p.1));
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
}

impl Mechanism<Planar> {
    /// The same mechanism with flexure joint `j` replaced by `refine(j, flexure)`
    /// where it returns one (another order or quadrature: the coordinates
    /// are renumbered, and `[initial]` coordinates padded with zeros or cut).
    pub fn with_flexures(
        &self,
        mut refine: impl FnMut(usize, &crate::flexure::Flexure) -> crate::Result<Option<crate::flexure::Flexure>>,
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
