//! Spatial mechanisms: trees of rigid bodies in 3-D joined by spatial
//! flexures, hinges, sliders, ball joints and welds, closed into loops by
//! weld, pin and ball closures, loaded by tendons, point forces and
//! moments, and gravity.
//!
//! The same model as a planar [`crate::mechanism::Mechanism`], in SE(3)
//! ([`Spatial`]'s poses, twists and wrenches): bodies are created by the
//! joints that name them as `child`, body 0 is `ground`, each joint's
//! `origin` is the pose of its root frame in the parent body's frame, and
//! the child body's frame is the joint's output frame (a flexure's tip
//! frame). The joints are reached only through [`Joint<Spatial>`], so the
//! algorithms ([`kinematics`], [`lagrangian`], [`statics`]) are those of
//! any joint kind; the planar mechanism keeps its own, with the planar fast
//! paths (rotations that add, the tree's $O(n)$ factorization).

pub mod buckling;
pub mod findings;
pub mod joints;
pub mod kinematics;
pub mod lagrangian;
pub mod report;
pub mod statics;
pub mod sweep;

pub use joints::{Prismatic, Revolute, SpatialJointKind, Spherical};

use crate::error::{Error, Result};
#[cfg(doc)]
use crate::mechanism::Joint;
#[cfg(doc)]
use crate::space::Spatial;
use crate::spatial::SpatialFlexure;
use nalgebra::{Isometry3, Matrix3, Point3, Vector3, Vector6};

/// A rigid body: its name, mass, centre of mass and inertia.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialBody {
    /// Its name.
    pub name: String,
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass in the body frame (m).
    pub com: Point3<f64>,
    /// Inertia about the centre of mass, in the body frame's axes (kg·m²).
    pub inertia: Matrix3<f64>,
}

impl SpatialBody {
    /// A massless body.
    pub fn massless(name: &str) -> Self {
        SpatialBody { name: name.into(), mass: 0.0, com: Point3::origin(), inertia: Matrix3::zeros() }
    }
}

/// A joint between two bodies.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialJointSpec {
    /// Its name.
    pub name: String,
    /// What it is.
    pub kind: SpatialJointKind,
    /// Parent body index.
    pub parent: usize,
    /// Child body index.
    pub child: usize,
    /// Root frame in the parent body's frame (`pose_parent_root`).
    pub origin: Isometry3<f64>,
    /// Index of its first coordinate in $q$.
    pub offset: usize,
    /// Damping, for dynamics: $\beta$ (s) of $D = \beta K$ on a flexure,
    /// the viscous coefficient on a hinge, slider or ball.
    pub damping: f64,
}

/// A tendon of constant tension through via points; potential tension × length.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialTendon {
    /// Its name.
    pub name: String,
    /// Tension (N), not negative.
    pub tension: f64,
    /// Via points: (body, position in the body frame).
    pub path: Vec<(usize, Point3<f64>)>,
}

/// A force and moment applied at a point of a body, both fixed in the
/// ground frame (dead loads).
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialPointLoad {
    /// Its name (or its index, as text).
    pub name: String,
    /// The body.
    pub body: usize,
    /// Point of application in the body frame (m).
    pub at: Point3<f64>,
    /// Moment (N·m) and force (N) in the ground frame: $(m, f)$.
    pub wrench: Vector6<f64>,
}

/// A loop closure.
#[derive(Debug, Clone, PartialEq)]
pub enum SpatialClosure {
    /// Frame `a_origin` on body `a` coincides with frame `b_origin` on body
    /// `b`: 6 equations, the origins' difference and the frames' misalignment
    /// $\frac12\sum_i \hat b_i\times\hat a_i$ (zero when the axes coincide,
    /// with Jacobian $\omega_a - \omega_b$ there).
    Weld {
        /// First body.
        a: usize,
        /// Frame on it.
        a_origin: Isometry3<f64>,
        /// Second body.
        b: usize,
        /// Frame on it.
        b_origin: Isometry3<f64>,
    },
    /// A hinge: point `a_at` on body `a` coincides with `b_at` on `b` and
    /// axis `a_axis` (in `a`'s frame) stays along `b_axis` (in `b`'s): 5
    /// equations, the points' difference and the components of $a$'s axis
    /// along the two directions of `b_normals` normal to `b_axis`.
    Pin {
        /// First body.
        a: usize,
        /// Point on it.
        a_at: Point3<f64>,
        /// The hinge's axis in its frame (unit).
        a_axis: Vector3<f64>,
        /// Second body.
        b: usize,
        /// Point on it.
        b_at: Point3<f64>,
        /// The hinge's axis in its frame (unit).
        b_axis: Vector3<f64>,
        /// Two unit directions in `b`'s frame normal to `b_axis` and to each other.
        b_normals: [Vector3<f64>; 2],
    },
    /// Point `a_at` on body `a` coincides with `b_at` on `b`: 3 equations.
    Ball {
        /// First body.
        a: usize,
        /// Point on it.
        a_at: Point3<f64>,
        /// Second body.
        b: usize,
        /// Point on it.
        b_at: Point3<f64>,
    },
}

impl SpatialClosure {
    /// Number of scalar equations.
    pub fn equations(&self) -> usize {
        match self {
            SpatialClosure::Weld { .. } => 6,
            SpatialClosure::Pin { .. } => 5,
            SpatialClosure::Ball { .. } => 3,
        }
    }

    /// The two bodies it joins.
    pub fn bodies(&self) -> [usize; 2] {
        match self {
            SpatialClosure::Weld { a, b, .. }
            | SpatialClosure::Pin { a, b, .. }
            | SpatialClosure::Ball { a, b, .. } => [*a, *b],
        }
    }

    /// A pin whose axes are `a_axis` in `a`'s frame and `b_axis` in `b`'s,
    /// with `b`'s normals made from `b_axis`.
    pub fn pin(
        a: usize,
        a_at: Point3<f64>,
        a_axis: Vector3<f64>,
        b: usize,
        b_at: Point3<f64>,
        b_axis: Vector3<f64>,
    ) -> Result<Self> {
        let a_axis = joints::unit_axis("axis", a_axis)?.into_inner();
        let b_axis = joints::unit_axis("axis", b_axis)?.into_inner();
        let helper = if b_axis.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
        let u = b_axis.cross(&helper).normalize();
        let v = b_axis.cross(&u);
        Ok(SpatialClosure::Pin { a, a_at, a_axis, b, b_at, b_axis, b_normals: [u, v] })
    }
}

/// The magnitudes of every load, which continuation and sweeps scale.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SpatialLoads {
    /// Tendon tensions, in the order of [`SpatialMechanism::tendons`].
    pub tension: Vec<f64>,
    /// The wrench $(m, f)$ of each point load, in the order of [`SpatialMechanism::forces`].
    pub force: Vec<Vector6<f64>>,
    /// Gravity (m/s²).
    pub gravity: Vector3<f64>,
}

impl SpatialLoads {
    /// `(1 − s)·self + s·other`, into `out` (shaped like `self`).
    pub fn lerp_into(&self, other: &SpatialLoads, s: f64, out: &mut SpatialLoads) {
        out.tension.clear();
        out.tension.extend(self.tension.iter().zip(&other.tension).map(|(a, b)| a + s * (b - a)));
        out.force.clear();
        out.force.extend(self.force.iter().zip(&other.force).map(|(a, b)| a + (b - a) * s));
        out.gravity = self.gravity + (other.gravity - self.gravity) * s;
    }

    /// `other − self`: the loads' change, in which every load term is linear.
    pub fn difference(&self, other: &SpatialLoads) -> SpatialLoads {
        SpatialLoads {
            tension: self.tension.iter().zip(&other.tension).map(|(a, b)| b - a).collect(),
            force: self.force.iter().zip(&other.force).map(|(a, b)| b - a).collect(),
            gravity: other.gravity - self.gravity,
        }
    }

    /// No load, shaped like `self`.
    pub fn zero_like(&self) -> SpatialLoads {
        SpatialLoads {
            tension: vec![0.0; self.tension.len()],
            force: vec![Vector6::zeros(); self.force.len()],
            gravity: Vector3::zeros(),
        }
    }

    /// Checks that the loads fit `m` and are finite, and that no tension is negative.
    pub fn validate(&self, m: &SpatialMechanism) -> Result<()> {
        if self.tension.len() != m.tendons.len() || self.force.len() != m.forces.len() {
            return Err(Error::invalid(
                "loads",
                format!("{} tensions and {} forces", self.tension.len(), self.force.len()),
                "must have one tension per tendon and one wrench per force of the mechanism",
            ));
        }
        let wrenches = self.force.iter().flat_map(|w| w.iter().copied());
        let mut all = self.tension.iter().copied().chain(wrenches).chain(self.gravity.iter().copied());
        if let Some(v) = all.find(|v| !(v.is_finite() && v.abs() <= crate::mechanism::file::MAX_MAGNITUDE)) {
            return Err(Error::invalid("loads", v, "must be finite and at most 1e30 in magnitude"));
        }
        if let Some(t) = self.tension.iter().find(|t| **t < 0.0) {
            return Err(Error::invalid("tension", t, "a tendon's tension must not be negative"));
        }
        Ok(())
    }
}

/// An immutable spatial mechanism (the Model).
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialMechanism {
    /// Bodies; index 0 is `ground`.
    pub bodies: Vec<SpatialBody>,
    /// Joints in an order where every parent comes before its children.
    pub joints: Vec<SpatialJointSpec>,
    /// Tendons.
    pub tendons: Vec<SpatialTendon>,
    /// Point loads.
    pub forces: Vec<SpatialPointLoad>,
    /// Loop closures.
    pub closures: Vec<SpatialClosure>,
    /// Gravity (m/s²), zero if absent.
    pub gravity: Vector3<f64>,
    /// `[initial]`: (joint, coordinates) that override a simulation's start.
    pub initial: Vec<(usize, Vec<f64>)>,
    /// `[initial_velocity]`: (joint, coordinate rates) of a simulation's start.
    pub initial_velocity: Vec<(usize, Vec<f64>)>,
    /// Per joint, whether its spatial flexure's orders are automatic
    /// (`order = "auto"`): `buckle` and `modes` raise them until their
    /// error estimate meets its target
    /// ([`crate::estimate::spatial_mechanism::buckle_auto`]); other
    /// analyses take them as they are (3). Empty when none is.
    pub auto_order: Vec<bool>,
    /// `[[schedule]]`: loads given in time, for simulations
    /// ([`crate::mechanism::schedule`]); the other analyses take the loads as given.
    pub schedules: Vec<crate::mechanism::schedule::Schedule<sweep::SpatialParameter>>,
    /// "line L, column C" of each closure in its file, for errors (empty if built in code).
    pub closure_places: Vec<String>,
    /// Per closure, whether the file says `preload = true`: open at rest on
    /// purpose ([`findings::open_closures`] then notes it instead of warning).
    pub closure_preloads: Vec<bool>,
    /// `parent_joint[b]`: the joint whose child is body `b`.
    parent_joint: Vec<Option<usize>>,
    dof: usize,
}

impl SpatialMechanism {
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
    ///     parent: 0, child: 1, origin: nalgebra::Isometry3::identity(), offset: 0, damping: 0.0,
    /// };
    /// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), bob], vec![ball], vec![], vec![], vec![], nalgebra::Vector3::new(0.0, 0.0, -9.81)).unwrap();
    /// assert_eq!((m.dof(), m.constraints()), (3, 0));
    /// ```
    pub fn new(
        bodies: Vec<SpatialBody>,
        mut joints: Vec<SpatialJointSpec>,
        tendons: Vec<SpatialTendon>,
        forces: Vec<SpatialPointLoad>,
        closures: Vec<SpatialClosure>,
        gravity: Vector3<f64>,
    ) -> Result<Self> {
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
        Ok(SpatialMechanism {
            bodies,
            joints,
            tendons,
            forces,
            closures,
            gravity,
            initial: Vec::new(),
            initial_velocity: Vec::new(),
            schedules: Vec::new(),
            auto_order: Vec::new(),
            closure_preloads: Vec::new(),
            closure_places: Vec::new(),
            parent_joint,
            dof: offset,
        })
    }

    /// Number of generalized coordinates.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// Number of closure equations.
    pub fn constraints(&self) -> usize {
        self.closures.iter().map(SpatialClosure::equations).sum()
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
        for j in &self.joints {
            let joint = j.kind.joint();
            joint.rest_into(&mut q[j.offset..j.offset + joint.dof()]);
        }
        q
    }

    /// The loads as given.
    pub fn loads(&self) -> SpatialLoads {
        SpatialLoads {
            tension: self.tendons.iter().map(|t| t.tension).collect(),
            force: self.forces.iter().map(|f| f.wrench).collect(),
            gravity: self.gravity,
        }
    }

    /// Every point attached to body `b`, in its frame: its origin (not for
    /// the ground), the root of each joint it carries, its tendon via
    /// points, load points and closure points, and its centre of mass if it
    /// has mass (the planar [`crate::mechanism::Mechanism::attachments`] in
    /// space). `flexure draw` draws a rigid body as their hull, and
    /// [`findings::crossings`] takes that hull's edges as the link.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::spatial::{Spherical, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism};
    /// use nalgebra::{Isometry3, Point3, Vector3};
    /// let bob = SpatialBody { mass: 1.0, com: Point3::new(0.0, 0.0, -1.0), ..SpatialBody::massless("bob") };
    /// let ball = SpatialJointSpec {
    ///     name: "ball".into(), kind: SpatialJointKind::Spherical(Spherical { stiffness: 0.0, rest: [0.0; 3] }),
    ///     parent: 0, child: 1, origin: Isometry3::translation(0.0, 0.0, 2.0), offset: 0, damping: 0.0,
    /// };
    /// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), bob], vec![ball], vec![], vec![], vec![], Vector3::zeros()).unwrap();
    /// assert_eq!(m.attachments(0), [Point3::new(0.0, 0.0, 2.0)]);
    /// assert_eq!(m.attachments(1), [Point3::origin(), Point3::new(0.0, 0.0, -1.0)]);
    /// ```
    pub fn attachments(&self, b: usize) -> Vec<Point3<f64>> {
        let mut pts = Vec::new();
        if b != 0 {
            pts.push(Point3::origin());
        }
        pts.extend(self.joints.iter().filter(|j| j.parent == b).map(|j| Point3::from(j.origin.translation.vector)));
        pts.extend(self.tendons.iter().flat_map(|t| &t.path).filter(|v| v.0 == b).map(|v| v.1));
        pts.extend(self.forces.iter().filter(|f| f.body == b).map(|f| f.at));
        for c in &self.closures {
            let (a, ra, other, rb) = match c {
                SpatialClosure::Weld { a, a_origin, b, b_origin } => {
                    (*a, Point3::from(a_origin.translation.vector), *b, Point3::from(b_origin.translation.vector))
                }
                SpatialClosure::Pin { a, a_at, b, b_at, .. } | SpatialClosure::Ball { a, a_at, b, b_at } => {
                    (*a, *a_at, *b, *b_at)
                }
            };
            pts.extend([(a, ra), (other, rb)].into_iter().filter(|p| p.0 == b).map(|p| p.1));
        }
        if self.bodies[b].mass > 0.0 {
            pts.push(self.bodies[b].com);
        }
        pts
    }

    /// The mechanism's size (m): the sum of its joints' offsets and flexure
    /// lengths (1 m for a mechanism of points). Slider travel is measured
    /// against it, to compare with rotations.
    pub fn size(&self) -> f64 {
        let length: f64 = self
            .joints
            .iter()
            .map(|j| j.origin.translation.vector.norm() + j.kind.flexure().map_or(0.0, |f| f.length()))
            .sum();
        if length > 0.0 && length.is_finite() { length } else { 1.0 }
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

    /// The same mechanism with spatial flexure joint `j` replaced by
    /// `refine(j, flexure)` where it returns one (other orders or
    /// subintervals), as the planar
    /// [`Mechanism::with_flexures`](crate::mechanism::Mechanism::with_flexures):
    /// the coordinates are renumbered, and `[initial]` coordinates of a
    /// replaced joint padded with zeros or cut, component by component.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::spatial::{SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism};
    /// use flexure::{section::SpatialSection, spatial::SpatialFlexure};
    /// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [2, 2, 2]).unwrap();
    /// let joint = SpatialJointSpec { name: "f".into(), kind: SpatialJointKind::Flexure(Box::new(f)), parent: 0, child: 1, origin: nalgebra::Isometry3::identity(), offset: 0, damping: 0.0 };
    /// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), SpatialBody::massless("tip")], vec![joint], vec![], vec![], vec![], nalgebra::Vector3::zeros()).unwrap();
    /// let finer = m.with_flexures(|_, f| Ok(Some(SpatialFlexure::new(f.length(), f.section().clone(), [4, 4, 4])?))).unwrap();
    /// assert_eq!((m.dof(), finer.dof()), (6, 12));
    /// ```
    pub fn with_flexures(
        &self,
        mut refine: impl FnMut(usize, &SpatialFlexure) -> Result<Option<SpatialFlexure>>,
    ) -> Result<SpatialMechanism> {
        let mut m = self.clone();
        let mut offset = 0;
        let mut before = vec![None; m.joints.len()];
        for (j, spec) in m.joints.iter_mut().enumerate() {
            if let Some(f) = spec.kind.flexure()
                && let Some(g) = refine(j, f)?
            {
                before[j] = Some(f.orders());
                spec.kind = SpatialJointKind::Flexure(Box::new(g));
            }
            spec.offset = offset;
            offset += spec.kind.joint().dof();
        }
        m.dof = offset;
        for (j, q) in m.initial.iter_mut().chain(m.initial_velocity.iter_mut()) {
            if let (Some(old), Some(f)) = (before[*j], m.joints[*j].kind.flexure()) {
                let mut out = Vec::with_capacity(f.coordinates());
                let mut start = 0;
                for (n, k) in old.into_iter().zip(f.orders()) {
                    out.extend(q.iter().skip(start).take(n.min(k)));
                    out.resize(out.len() + k.saturating_sub(n), 0.0);
                    start += n;
                }
                *q = out;
            }
        }
        Ok(m)
    }
}
