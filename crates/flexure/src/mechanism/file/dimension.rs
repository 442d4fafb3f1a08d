//! What the file's reading needs of its dimension: the plane and space side
//! by side. Everything else (the tree, bodies, tendons, forces, closures,
//! schedules, the initial state and the checks) is read once, over
//! [`FileDimension`].
//!
//! | | plane (`dimension = 2`, the default) | space (`dimension = 3`) |
//! | --- | --- | --- |
//! | a point, a force, gravity | $[x, y]$ | $[x, y, z]$ |
//! | a moment | $M_z$ | $[M_x, M_y, M_z]$ |
//! | a frame (`origin`, `a_origin`) | $[x, y, \phi]$ | $[x, y, z]$ with `rpy` or `rpy_deg` |
//! | a body's `inertia` | $I_{zz}$ | 3 × 3, or `ixx` … `iyz` |
//! | the joint kinds | flexure, revolute, prismatic, fixed | and spherical; an `axis` for a hinge or slider |
//! | closures | weld, pin | weld, pin about an `axis`, ball |
//! | geoms | plane, circle, capsule, box; turned by `angle` | plane, sphere, capsule, box, cylinder; turned by `rpy` |

use super::bodies::{BodyToml, inertia_matrix};
use super::closures::PinToml;
use super::document::{Numbers, Sign, Source, Span};
use super::geoms::GeomToml;
use super::joints::{JointToml, planar_kind, spatial_kind};
use super::{PLANAR_ONLY, Result, SPATIAL_ONLY, Spanned};
use crate::kinematics::{Level, Pose};
use crate::mechanism::contact::Touch;
use crate::mechanism::joints::JointState;
use crate::mechanism::kinematics::frames_level_into;
use crate::mechanism::spatial::joints::unit_axis;
use crate::mechanism::{Closure, Holds, JointKind, Mechanism, ReportOptions, kinematics};
use crate::space::{Planar, Spatial, Wrench};
use nalgebra::{Isometry3, Point2, Point3, Translation3, UnitQuaternion, Vector2, Vector3, Vector6};
use serde::de::DeserializeOwned;

/// A joint's kind as its keys give it.
pub(super) struct Kind<D: crate::mechanism::Dimension> {
    pub(super) kind: JointKind<D>,
    /// Where its stiffness is given (the joint's name when it has none),
    /// for the check of the stiffness ratio.
    pub(super) stiffness_place: Span,
    /// A flexure of `order = "auto"`.
    pub(super) auto_order: bool,
    /// A flexure's report keys.
    pub(super) report: ReportOptions,
}

/// A via point of a tendon: `[body, x, y]` or `[body, x, y, z]`.
pub(super) type Via<C> = (Spanned<String>, C);

/// A dimension's file: what differs between the plane and space.
pub(super) trait FileDimension: Touch {
    /// Its `dimension`.
    const DIMENSION: u8;
    /// The keys of the other dimension's file it refuses: (table, keys, why).
    const REFUSED: &'static [(&'static str, &'static [&'static str], &'static str)];
    /// The other dimension's mechanisms, as its refusals name them.
    const OTHER: &'static str;
    /// A point's or a vector's numbers.
    type Coords: Numbers + DeserializeOwned;
    /// A moment's numbers.
    type Moment: Numbers + DeserializeOwned;
    /// A via point as the file writes it, `[body, x, y(, z)]`.
    type Via: DeserializeOwned;
    /// A body's `inertia` as the file writes it.
    type Inertia: DeserializeOwned;

    fn point(c: Self::Coords) -> Self::Point;
    fn vector(c: Self::Coords) -> Self::Vector;
    /// A point's numbers, back.
    fn coords(p: &Self::Point) -> Self::Coords;
    fn wrench(force: Self::Coords, moment: Self::Moment) -> Self::Wrench;
    /// A via point's body and numbers.
    fn via(v: &Self::Via) -> Via<Self::Coords>;
    /// A frame: `origin` and, in space, `rpy` or `rpy_deg` (the keys named by `keys`).
    fn pose(src: &Source, owner: &str, keys: [&str; 3], values: [&Option<Spanned<[f64; 3]>>; 3]) -> Result<Self::Pose>;
    /// A `[[body]]` table's rotary inertia.
    fn inertia(src: &Source, owner: &str, b: &BodyToml<Self>) -> Result<Self::AngularInertia>;
    /// A joint's kind: the one place a `kind` becomes a joint.
    fn kind(src: &Source, owner: &str, j: &JointToml) -> Result<Kind<Self>>;
    /// A pin of bodies `a` and `b` at its points; `rest`: the bodies' frames at rest.
    fn pin(
        src: &Source,
        owner: &str,
        p: &PinToml<Self>,
        a: (usize, Self::Point),
        b: (usize, Self::Point),
        rest: &[Self::Pose],
    ) -> Result<Closure<Self>>;
    /// The bodies' frames and the joints' states at rest.
    fn rest(m: &Mechanism<Self>) -> (Vec<Self::Pose>, Vec<JointState<Self>>);
    /// Whether a geom may be of this `shape` here.
    fn takes_shape(shape: &str) -> bool;
    /// Why a geom's `shape` is the other dimension's, if it is.
    fn refused_shape(shape: &str) -> Option<&'static str>;
    /// A geom's frame in its body's: `origin`, turned by `angle` in the
    /// plane, by `rpy` or `rpy_deg` in space.
    fn geom_frame(src: &Source, owner: &str, g: &GeomToml<Self>) -> Result<Self::Pose>;
}

impl FileDimension for Planar {
    const DIMENSION: u8 = 2;
    const REFUSED: &'static [(&'static str, &'static [&'static str], &'static str)] = SPATIAL_ONLY;
    const OTHER: &'static str = "spatial mechanisms (dimension = 3)";
    type Coords = [f64; 2];
    type Moment = f64;
    type Via = (Spanned<String>, f64, f64);
    type Inertia = f64;

    fn point(c: [f64; 2]) -> Point2<f64> {
        c.into()
    }

    fn vector(c: [f64; 2]) -> Vector2<f64> {
        c.into()
    }

    fn coords(p: &Point2<f64>) -> [f64; 2] {
        [p.x, p.y]
    }

    fn wrench([fx, fy]: [f64; 2], moment: f64) -> Wrench {
        Wrench { moment, fx, fy }
    }

    fn via((body, x, y): &Self::Via) -> Via<[f64; 2]> {
        (body.clone(), [*x, *y])
    }

    fn pose(
        src: &Source,
        owner: &str,
        keys: [&str; 3],
        [origin, _, _]: [&Option<Spanned<[f64; 3]>>; 3],
    ) -> Result<Pose> {
        let [x, y, phi] = src.array(owner, keys[0], origin)?;
        Ok(Pose { x, y, phi })
    }

    fn inertia(src: &Source, owner: &str, b: &BodyToml<Planar>) -> Result<f64> {
        b.inertia.as_ref().map_or(Ok(0.0), |i| src.number(owner, "inertia", i, Sign::NotNegative))
    }

    fn kind(src: &Source, owner: &str, j: &JointToml) -> Result<Kind<Planar>> {
        planar_kind(src, owner, j)
    }

    fn pin(
        _: &Source,
        _: &str,
        _: &PinToml<Planar>,
        (a, a_at): (usize, Point2<f64>),
        (b, b_at): (usize, Point2<f64>),
        _: &[Pose],
    ) -> Result<Closure> {
        Ok(Closure::at_points(Holds::Pin, a, a_at, b, b_at))
    }

    fn rest(m: &Mechanism) -> (Vec<Pose>, Vec<JointState>) {
        let f = kinematics::frames(m, &m.rest());
        (f.bodies, f.joints)
    }

    fn takes_shape(shape: &str) -> bool {
        !matches!(shape, "sphere" | "cylinder")
    }

    fn refused_shape(shape: &str) -> Option<&'static str> {
        match shape {
            "sphere" => Some("in the plane a sphere is a circle: shape = \"circle\""),
            "cylinder" => Some("in the plane a cylinder about z is its circle: shape = \"circle\""),
            _ => None,
        }
    }

    fn geom_frame(src: &Source, owner: &str, g: &GeomToml<Planar>) -> Result<Pose> {
        let [x, y] = src.array(owner, "origin", &g.origin)?;
        let phi = g.angle.as_ref().map_or(Ok(0.0), |a| src.number(owner, "angle", a, Sign::Any))?;
        Ok(Pose { phi, x, y })
    }
}

impl FileDimension for Spatial {
    const DIMENSION: u8 = 3;
    const REFUSED: &'static [(&'static str, &'static [&'static str], &'static str)] = PLANAR_ONLY;
    const OTHER: &'static str = "planar mechanisms";
    type Coords = [f64; 3];
    type Moment = [f64; 3];
    type Via = (Spanned<String>, f64, f64, f64);
    type Inertia = [[f64; 3]; 3];

    fn point(c: [f64; 3]) -> Point3<f64> {
        c.into()
    }

    fn vector(c: [f64; 3]) -> Vector3<f64> {
        c.into()
    }

    fn coords(p: &Point3<f64>) -> [f64; 3] {
        [p.x, p.y, p.z]
    }

    fn wrench(f: [f64; 3], m: [f64; 3]) -> Vector6<f64> {
        Vector6::new(m[0], m[1], m[2], f[0], f[1], f[2])
    }

    fn via((body, x, y, z): &Self::Via) -> Via<[f64; 3]> {
        (body.clone(), [*x, *y, *z])
    }

    /// URDF's placement: `origin = [x, y, z]` (m) and `rpy = [roll, pitch,
    /// yaw]` (rad) or `rpy_deg` (degrees), the fixed-axis convention
    /// $R = R_z(\text{yaw})R_y(\text{pitch})R_x(\text{roll})$.
    fn pose(
        src: &Source,
        owner: &str,
        keys: [&str; 3],
        [origin, rpy, rpy_deg]: [&Option<Spanned<[f64; 3]>>; 3],
    ) -> Result<Isometry3<f64>> {
        let p = src.array(owner, keys[0], origin)?;
        let angles = match (rpy, rpy_deg) {
            (Some(_), Some(d)) => {
                return src
                    .fail(&d.span(), format!("{owner}give {} (rad) or {} (degrees), not both", keys[1], keys[2]));
            }
            (Some(_), None) => src.array(owner, keys[1], rpy)?,
            (None, Some(_)) => src.array(owner, keys[2], rpy_deg)?.map(f64::to_radians),
            (None, None) => [0.0; 3],
        };
        Ok(Isometry3::from_parts(
            Translation3::new(p[0], p[1], p[2]),
            UnitQuaternion::from_euler_angles(angles[0], angles[1], angles[2]),
        ))
    }

    fn inertia(src: &Source, owner: &str, b: &BodyToml<Spatial>) -> Result<nalgebra::Matrix3<f64>> {
        inertia_matrix(src, owner, b)
    }

    fn kind(src: &Source, owner: &str, j: &JointToml) -> Result<Kind<Spatial>> {
        spatial_kind(src, owner, j)
    }

    /// A hinge: `axis` in `a`'s frame; on `b`, `b_axis`, or where `axis` lies at rest.
    fn pin(
        src: &Source,
        owner: &str,
        p: &PinToml<Spatial>,
        (a, a_at): (usize, Point3<f64>),
        (b, b_at): (usize, Point3<f64>),
        rest: &[Isometry3<f64>],
    ) -> Result<Closure<Spatial>> {
        let axis = p
            .axis
            .as_ref()
            .ok_or_else(|| src.error(&p.a.span(), format!("{owner}a pin needs its axis (in a's frame)")))?;
        let unit = |key: &'static str, v: &Spanned<[f64; 3]>| -> Result<Vector3<f64>> {
            src.array_numbers(owner, key, &v.span(), v.get_ref(), Sign::Any)?;
            Ok(unit_axis(key, Vector3::from(*v.get_ref())).map_err(|e| src.placed(owner, &v.span(), e))?.into_inner())
        };
        let a_axis = unit("axis", axis)?;
        let b_axis = match &p.b_axis {
            Some(v) => unit("b_axis", v)?,
            None => rest[b].rotation.inverse() * (rest[a].rotation * a_axis),
        };
        Closure::pin(a, a_at, a_axis, b, b_at, b_axis).map_err(|e| src.placed(owner, &axis.span(), e))
    }

    fn rest(m: &Mechanism<Spatial>) -> (Vec<Isometry3<f64>>, Vec<JointState<Spatial>>) {
        // At the pose level: the Hessians cost most at high orders, and the
        // checks read the stiffness, which every level gives.
        let mut f = kinematics::Frames::new(m);
        frames_level_into(m, &m.rest(), Level::Pose, &mut f);
        (f.bodies, f.joints)
    }

    fn takes_shape(shape: &str) -> bool {
        shape != "circle"
    }

    fn refused_shape(shape: &str) -> Option<&'static str> {
        (shape == "circle").then_some(
            "in space a round obstacle is a sphere (shape = \"sphere\") or a cylinder (shape = \"cylinder\", about its frame's z)",
        )
    }

    fn geom_frame(src: &Source, owner: &str, g: &GeomToml<Spatial>) -> Result<Isometry3<f64>> {
        Self::pose(src, owner, ["origin", "rpy", "rpy_deg"], [&g.origin, &g.rpy, &g.rpy_deg])
    }
}
