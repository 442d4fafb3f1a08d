//! What the findings need of a dimension: the frames at a shape, a
//! closure's gap and preload, and the parts' geometry (a flexure as chords
//! and a link as the edges of its hull in the plane; a flexure as convex
//! solids along its chords and a link as its hull's edges in space, met by
//! GJK). The plane and space implement it here, side by side; the findings
//! ([`super::open_closures`], [`super::crossings`]) are written once over it.

use super::convex::{Convex, distinct, hull_edges};
use super::crossing::{self, CrossingAt, PartGeometry, Piece, PlacedPart, TOUCH_TOLERANCE};
use super::geometry::{convex_hull, distance};

use crate::kinematics::{Level, backbone};
use crate::mechanism::lagrangian::wrap;

use crate::mechanism::{Closure, Holds, Mechanism};
use crate::section::Outline;
use crate::space::{Planar, Spatial};
use nalgebra::{Point2, Point3, UnitQuaternion, Vector3};

/// A dimension whose mechanisms the findings examine: [`Planar`] or [`Spatial`].
///
/// # Example
/// ```
/// use flexure::mechanism::findings::Findings;
/// use flexure::space::{Planar, Spatial};
/// use nalgebra::{Point2, Point3};
/// // Bounding boxes are in space: the plane's at z = 0.
/// assert_eq!(Planar::coordinates(&Point2::new(1.0, 2.0)), [1.0, 2.0, 0.0]);
/// assert_eq!(Spatial::coordinates(&Point3::new(1.0, 2.0, 3.0)), [1.0, 2.0, 3.0]);
/// // A weld's force, then its moment: (3, 4) N and 5 N·m in the plane.
/// assert_eq!(Planar::preload(&[3.0, 4.0, -5.0]), (5.0, Some(5.0)));
/// ```
pub trait Findings: crate::mechanism::statics::Statics {
    /// A point where two parts meet, as a [`super::Crossing`] gives it:
    /// `[f64; 2]` in the plane, `[f64; 3]` in space.
    type At: AsRef<[f64]> + Copy + std::fmt::Debug + PartialEq;
    /// The solid of a piece of a part: none in the plane (a piece is its
    /// segment), a [`Convex`] in space.
    type Solid;

    /// The bodies' frames and the joints' root frames at coordinates `q`.
    fn poses(m: &Mechanism<Self>, q: &[f64]) -> (Vec<Self::Pose>, Vec<Self::Pose>);
    /// The geoms a strip's width passes through at `q` (the bodies' and
    /// joints' root frames given), by more than `tolerance` (m): none in the
    /// plane, where a flexure is its section; in space
    /// [`crate::mechanism::contact::width_crossings`].
    fn width_crossings(
        _m: &Mechanism<Self>,
        _q: &[f64],
        _frames: (&[Self::Pose], &[Self::Pose]),
        _tolerance: f64,
    ) -> Vec<super::CrossingAt<Self>> {
        Vec::new()
    }
    /// A closure's gap at rest, given the bodies' frames: the distance
    /// between its points (m) and the angle it holds between its frames (rad).
    fn rest_gap(c: &Closure<Self>, bodies: &[Self::Pose]) -> (f64, Option<f64>);
    /// A closure's force (N) and, where it holds a turn, moment (N·m), from
    /// its multipliers.
    fn preload(mu: &[f64]) -> (f64, Option<f64>);
    /// How near two parts must come to touch.
    fn touch_tolerance(m: &Mechanism<Self>) -> f64;
    /// A point's coordinates in space (the plane's at z = 0), for bounding boxes.
    fn coordinates(p: &Self::Point) -> [f64; 3];
    /// A flexure with coordinates `alpha` as `samples − 1` pieces, its root
    /// frame at `root` and its tip at `tip`; `None` if it cannot be drawn.
    fn flexure_shape(
        f: &Self::Flexure,
        alpha: &[f64],
        samples: usize,
        root: &Self::Pose,
        tip: Self::Point,
    ) -> Option<PartGeometry<Self>>;
    /// A link through the points `points` (world frame); `None` for fewer than two.
    fn link_shape(points: Vec<Self::Point>, tolerance: f64) -> Option<PartGeometry<Self>>;
    /// Where two parts cross, if they do (a flexure, itself, when `a` is
    /// `b`); `joined` when a joint or a closure connects them.
    fn cross(a: &PlacedPart<Self>, b: &PlacedPart<Self>, joined: bool, tolerance: f64) -> Option<CrossingAt<Self>>;
}

impl Findings for Planar {
    type At = [f64; 2];
    type Solid = ();

    fn poses(m: &Mechanism, q: &[f64]) -> (Vec<crate::Pose>, Vec<crate::Pose>) {
        let f = crate::mechanism::kinematics::frames(m, q);
        (f.bodies, f.roots)
    }

    fn rest_gap(c: &Closure, bodies: &[crate::Pose]) -> (f64, Option<f64>) {
        let (ba, bb) = (&bodies[c.a], &bodies[c.b]);
        match c.holds {
            Holds::Weld => {
                let (fa, fb) = (ba.compose(&c.a_origin), bb.compose(&c.b_origin));
                (distance(&fa.origin(), &fb.origin()), Some(wrap(fa.phi - fb.phi)))
            }
            Holds::Pin | Holds::Ball => (distance(&ba.act(&c.a_origin.origin()), &bb.act(&c.b_origin.origin())), None),
        }
    }

    fn preload(mu: &[f64]) -> (f64, Option<f64>) {
        (mu[0].hypot(mu[1]), mu.get(2).map(|m| m.abs()))
    }

    fn touch_tolerance(m: &Mechanism) -> f64 {
        TOUCH_TOLERANCE * m.size()
    }

    fn coordinates(p: &Point2<f64>) -> [f64; 3] {
        [p.x, p.y, 0.0]
    }

    fn flexure_shape(
        f: &crate::Flexure,
        alpha: &[f64],
        samples: usize,
        root: &crate::Pose,
        tip: Point2<f64>,
    ) -> Option<PartGeometry<Planar>> {
        let centre: Vec<Point2<f64>> = backbone(f, alpha, samples).iter().map(|p| root.act(&p.origin())).collect();
        let points = crossing::ending_at(centre, tip);
        let ends = vec![points[0], points[samples - 1], tip];
        Some(PartGeometry::new(crossing::chords_in_plane(&points, f.length()), ends, 0.0))
    }

    fn link_shape(points: Vec<Point2<f64>>, _: f64) -> Option<PartGeometry<Planar>> {
        let mut outline = convex_hull(points.clone());
        if outline.len() < 2 {
            return None;
        }
        if outline.len() > 2 {
            outline.push(outline[0]);
        }
        let pieces = outline.windows(2).enumerate().map(|(k, e)| Piece::new((), [e[0], e[1]], [k, k + 1], None));
        Some(PartGeometry::new(pieces.collect(), points, 0.0))
    }

    fn cross(
        a: &PlacedPart<Planar>,
        b: &PlacedPart<Planar>,
        joined: bool,
        tolerance: f64,
    ) -> Option<CrossingAt<Planar>> {
        crossing::segments_cross(a, b, joined, tolerance)
    }
}

impl Findings for Spatial {
    type At = [f64; 3];
    type Solid = Convex;

    fn width_crossings(
        m: &Mechanism<Spatial>,
        q: &[f64],
        frames: (&[nalgebra::Isometry3<f64>], &[nalgebra::Isometry3<f64>]),
        tolerance: f64,
    ) -> Vec<super::CrossingAt<Spatial>> {
        crate::mechanism::contact::width_crossings(m, q, frames, tolerance)
    }

    fn poses(m: &Mechanism<Spatial>, q: &[f64]) -> (Vec<nalgebra::Isometry3<f64>>, Vec<nalgebra::Isometry3<f64>>) {
        // Poses alone: the bodies' frames are the same at every level.
        let mut f = crate::mechanism::kinematics::Frames::new(m);
        crate::mechanism::kinematics::frames_level_into(m, q, Level::Pose, &mut f);
        (f.bodies, f.roots)
    }

    fn rest_gap(c: &Closure<Spatial>, bodies: &[nalgebra::Isometry3<f64>]) -> (f64, Option<f64>) {
        let (fa, fb) = (bodies[c.a] * c.a_origin, bodies[c.b] * c.b_origin);
        let gap = (fa.translation.vector - fb.translation.vector).norm();
        match c.holds {
            Holds::Weld => {
                let turn: UnitQuaternion<f64> = fa.rotation.inverse() * fb.rotation;
                (gap, Some(turn.angle()))
            }
            Holds::Pin => {
                // atan2 of sine and cosine: exact near 0, where acos loses half the digits.
                let (za, zb) = (fa.rotation * Vector3::z(), fb.rotation * Vector3::z());
                (gap, Some(za.cross(&zb).norm().atan2(za.dot(&zb))))
            }
            Holds::Ball => (gap, None),
        }
    }

    fn preload(mu: &[f64]) -> (f64, Option<f64>) {
        // The force (3), then a weld's or pin's misalignment moment.
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        (norm(&mu[..3]), (mu.len() > 3).then(|| norm(&mu[3..])))
    }

    /// [`TOUCH_TOLERANCE`] × the mechanism's size, but no more than that ×
    /// 10⁴ shortest flexure lengths, so that one far offset (an origin of
    /// 1e30 m) does not make every part touch every other.
    fn touch_tolerance(m: &Mechanism<Spatial>) -> f64 {
        let shortest = m.joints.iter().filter_map(|j| Some(j.kind.flexure()?.length())).fold(f64::INFINITY, f64::min);
        TOUCH_TOLERANCE * m.size().min(1e4 * shortest)
    }

    fn coordinates(p: &Point3<f64>) -> [f64; 3] {
        p.coords.into()
    }

    fn flexure_shape(
        f: &crate::spatial::SpatialFlexure,
        alpha: &[f64],
        samples: usize,
        root: &nalgebra::Isometry3<f64>,
        tip: Point3<f64>,
    ) -> Option<PartGeometry<Spatial>> {
        // The convex pieces between the sections at the ends of each chord (see the module docs of `super`).
        let sections = crate::spatial::shape(f, alpha, samples).ok()?;
        let centres = crossing::ending_at(sections.iter().map(|s| root * Point3::from(s.position)).collect(), tip);
        let (l, mut reach) = (f.length(), 0.0f64);
        let mut solids = Vec::with_capacity(samples);
        for (c, sec) in centres.into_iter().zip(&sections) {
            let r = root.rotation.to_rotation_matrix() * nalgebra::Matrix3::from(sec.rotation).transpose();
            let axes = [r.column(0).into_owned(), r.column(1).into_owned(), r.column(2).into_owned()];
            let outline = f.section().outline(sec.s / l);
            reach = reach.max(match outline {
                Some(Outline::Rectangle { width, thickness }) => 0.5 * width.hypot(thickness),
                Some(Outline::Circle { diameter }) => 0.5 * diameter,
                None => 0.0,
            });
            solids.push((c, axes, outline));
        }
        let mut pieces = Vec::with_capacity(samples - 1);
        for i in 0..samples - 1 {
            let ((c0, x0, o0), (c1, x1, o1)) = (&solids[i], &solids[i + 1]);
            let solid = match (o0, o1) {
                (
                    Some(Outline::Rectangle { width: w0, thickness: h0 }),
                    Some(Outline::Rectangle { width: w1, thickness: h1 }),
                ) => {
                    let corners = |c: &Point3<f64>, x: &[Vector3<f64>; 3], w: f64, h: f64| {
                        [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)]
                            .map(|(a, b)| c + x[1] * (0.5 * h * a) + x[2] * (0.5 * w * b))
                    };
                    let mut v = corners(c0, x0, *w0, *h0).to_vec();
                    v.extend(corners(c1, x1, *w1, *h1));
                    Convex::Hull(v)
                }
                (Some(Outline::Circle { diameter: d0 }), Some(Outline::Circle { diameter: d1 })) => {
                    Convex::Discs { centres: [*c0, *c1], normals: [x0[0], x1[0]], radius: 0.5 * d0.max(*d1) }
                }
                _ => Convex::Hull(vec![*c0, *c1]),
            };
            let (lo, hi) = match &solid {
                Convex::Hull(v) => crossing::bounds(v.iter().map(|p| p.coords.into()), 0.0),
                Convex::Discs { centres, radius, .. } => {
                    crossing::bounds(centres.iter().map(|p| p.coords.into()), *radius)
                }
            };
            pieces.push(Piece {
                solid,
                line: [*c0, *c1],
                ends: [i, i + 1],
                arc: crossing::arc(l, i, samples - 1),
                lo,
                hi,
            });
        }
        Some(PartGeometry::new(pieces, vec![solids[0].0, tip], reach))
    }

    fn link_shape(points: Vec<Point3<f64>>, tolerance: f64) -> Option<PartGeometry<Spatial>> {
        let points = distinct(points, tolerance);
        let edges = hull_edges(&points, tolerance);
        if edges.is_empty() {
            return None;
        }
        let pieces = edges.iter().map(|&(i, k)| {
            let line = [points[i], points[k]];
            Piece::new(Convex::Hull(line.to_vec()), line, [i, k], None)
        });
        let (lo, hi) = crossing::bounds(points.iter().map(Self::coordinates), 0.0);
        Some(PartGeometry { pieces: pieces.collect(), ends: points, reach: 0.0, lo, hi })
    }

    fn cross(
        a: &PlacedPart<Spatial>,
        b: &PlacedPart<Spatial>,
        joined: bool,
        tolerance: f64,
    ) -> Option<CrossingAt<Spatial>> {
        crossing::solids_cross(a, b, joined, tolerance)
    }
}
