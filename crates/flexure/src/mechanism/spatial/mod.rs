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
//! algorithms ([`crate::mechanism::kinematics`], [`crate::mechanism::lagrangian`],
//! [`statics`]) are those of any joint kind, and the planar fast paths
//! (rotations that add, the tree's $O(n)$ factorization) sit behind them.

pub mod joints;
pub mod statics;

pub use joints::{PrismaticUnaligned, RevoluteUnaligned, SpatialJointKind, Spherical};

use crate::error::{Error, Result};
#[cfg(doc)]
use crate::mechanism::Joint;
use crate::mechanism::{Body, Closure, Holds, JointSpec, Loads, Mechanism, PointLoad, Tendon};
use crate::space::Spatial;
use crate::spatial::SpatialFlexure;
use nalgebra::{Isometry3, Matrix3, Point3, Rotation3, Translation3, UnitQuaternion, Vector3, Vector6};

/// A rigid body in space ([`Body`]).
pub type SpatialBody = Body<Spatial>;
/// A joint between two bodies in space ([`JointSpec`]).
pub type SpatialJointSpec = JointSpec<Spatial>;
/// A tendon in space ([`Tendon`]).
pub type SpatialTendon = Tendon<Spatial>;
/// A force and moment at a point of a body, in space ([`PointLoad`]).
pub type SpatialPointLoad = PointLoad<Spatial>;
/// The loads of a spatial mechanism ([`Loads`]).
pub type SpatialLoads = Loads<Spatial>;
/// A spatial mechanism ([`Mechanism`]).
pub type SpatialMechanism = Mechanism<Spatial>;

/// A loop closure in space ([`Closure`]).
pub type SpatialClosure = Closure<Spatial>;

impl Closure<Spatial> {
    /// A pin (hinge) whose axis is `a_axis` in `a`'s frame at `a_at` and
    /// `b_axis` in `b`'s at `b_at`: each frame's z is its axis, and `b`'s
    /// x and y are the two normals whose components of `a`'s axis the pin
    /// holds at zero ($x = \hat z_b\times h$ normalized, $h$ the first of
    /// $\hat x, \hat y$ not along the axis; $y = z\times x$).
    pub fn pin(
        a: usize,
        a_at: Point3<f64>,
        a_axis: Vector3<f64>,
        b: usize,
        b_at: Point3<f64>,
        b_axis: Vector3<f64>,
    ) -> Result<Self> {
        let frame = |at: Point3<f64>, axis: Vector3<f64>| -> Result<Isometry3<f64>> {
            let z = joints::unit_axis("axis", axis)?.into_inner();
            let helper = if z.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
            let x = z.cross(&helper).normalize();
            let y = z.cross(&x);
            let r = Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[x, y, z]));
            Ok(Isometry3::from_parts(Translation3::from(at.coords), UnitQuaternion::from_rotation_matrix(&r)))
        };
        Ok(Closure { holds: Holds::Pin, a, a_origin: frame(a_at, a_axis)?, b, b_origin: frame(b_at, b_axis)? })
    }

    /// The frames' axes $\hat x, \hat y, \hat z$ on `a` (in its frame), then on `b`:
    /// the columns of their rotation matrices (one conversion from the
    /// quaternion each, as the weld's residual always took them).
    pub fn axes(&self) -> [Vector3<f64>; 6] {
        let (ra, rb) = (self.a_origin.rotation.to_rotation_matrix(), self.b_origin.rotation.to_rotation_matrix());
        std::array::from_fn(|k| if k < 3 { ra.matrix().column(k) } else { rb.matrix().column(k - 3) }.into_owned())
    }
}

impl Loads<Spatial> {
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

impl Mechanism<Spatial> {
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
    /// let joint = SpatialJointSpec { name: "f".into(), kind: SpatialJointKind::Flexure(Box::new(f)), parent: 0, child: 1, origin: nalgebra::Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default() };
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
