//! Where two geoms touch: at their corners. Two shapes' gap is watched at
//! points of one of them, each a ball (its centre a material point of its
//! geom, radius $r \ge 0$) against the other's exact signed distance
//! $d$: the gap there is $d(c) - r$.
//!
//! | pair | its corners |
//! | --- | --- |
//! | a circle or sphere and any geom | the ball itself (the later geom's, when both are) |
//! | a plane and a box | the box's $2^n$ corners ($r = 0$) |
//! | a plane and a capsule | the capsule's two end balls ($r$ its radius) |
//! | a plane and a cylinder (space) | [`RIM_POINTS`] points of each of its two rims ($r = 0$) |
//! | two of box, capsule and cylinder | each one's corners against the other |
//!
//! These are exact where the two touch at a corner of one of them: a
//! plane first touches a convex solid at a corner, and in the plane two
//! convex outlines (a capsule is its segment's, rounded) are nearest at a
//! corner of one of them. In space two of box, capsule and cylinder may
//! also meet edge across edge, where no corner touches: their pairs of
//! edges (a cylinder's is its axis, rounded by its radius: its side) are
//! watched too ([`edges_cross`]), after the corners, each as a corner that
//! moves along its edge ([`super::crossing`]). A cylinder's rim is no
//! finite set of points: it is watched at [`RIM_POINTS`] points, a regular
//! polygon inscribed in it, so a rim may sink into the other geom by
//! at most $R(1 - \cos(\pi/32)) = 0.0048R$ between two of them (exact at
//! the points, and where the rim touches at one of them). Two planes are
//! refused by name (they never part).

use super::crossing::{Crossing, crossing, ridge, ridges};
use super::{Geom, GeomShape, Pair, Touch, Toucher, named, vector};
use crate::error::{Error, Result};
use crate::mechanism::{Dimension, Mechanism};

/// A corner of a pair of two geoms ([`corners`]): a ball of `radius` about
/// `centre` in the frame of one of the two shapes, against the other.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerOf<D: Dimension> {
    /// Whether the corner is the pair's part's (the later geom's), not its geom's.
    pub of_part: bool,
    /// Its centre in its shape's frame (m).
    pub centre: D::Vector,
    /// Its radius (m): 0 at a box's corner.
    pub radius: f64,
}

/// The corners of two shapes, the pair's geom `a` and part `b` (see the
/// module docs), or `None` where their gap is not found.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{corners, GeomShape};
/// use flexure::space::{Planar, Spatial};
/// use nalgebra::{Vector2, Vector3};
/// let floor = GeomShape::<Spatial>::Plane { normal: Vector3::z() };
/// let brick = GeomShape::<Spatial>::Box { half_extents: Vector3::new(0.1, 0.2, 0.3) };
/// assert_eq!(corners(&floor, &brick).unwrap().len(), 8);
/// // Two boxes: each one's corners against the other.
/// assert_eq!(corners(&brick, &brick).unwrap().len(), 16);
/// // A cylinder's rims are watched at RIM_POINTS points each.
/// let can = GeomShape::<Spatial>::Cylinder { half_length: 0.1, radius: 0.05 };
/// assert_eq!(corners(&floor, &can).unwrap().len(), 2 * flexure::mechanism::contact::RIM_POINTS);
/// // Two planes never part: refused.
/// assert!(corners(&floor, &floor).is_none());
/// // In the plane they are nearest at a vertex of one of them.
/// let tile = GeomShape::<Planar>::Box { half_extents: Vector2::new(0.1, 0.2) };
/// assert_eq!(corners(&tile, &tile).unwrap().len(), 8);
/// ```
pub fn corners<D: Dimension>(a: &GeomShape<D>, b: &GeomShape<D>) -> Option<Vec<CornerOf<D>>> {
    let n = corner_count(a, b)?;
    Some((0..n).map(|k| corner_of(a, b, k)).collect())
}

/// How many corners shapes `a` and `b` have ([`corners`]), or `None`.
fn corner_count<D: Dimension>(a: &GeomShape<D>, b: &GeomShape<D>) -> Option<usize> {
    let plane = |s: &GeomShape<D>| matches!(s, GeomShape::Plane { .. });
    let (na, nb) = (point_count(a), point_count(b));
    match (plane(a), plane(b)) {
        _ if matches!(b, GeomShape::Ball { .. }) || matches!(a, GeomShape::Ball { .. }) => Some(1),
        (true, false) if nb > 0 => Some(nb),
        (false, true) if na > 0 => Some(na),
        (false, false) if na > 0 && nb > 0 => Some(na + nb),
        _ => None,
    }
}

/// Corner `k` of shapes `a` and `b` (below [`corner_count`]): the part's
/// (`b`'s) first, then the geom's.
fn corner_of<D: Dimension>(a: &GeomShape<D>, b: &GeomShape<D>, k: usize) -> CornerOf<D> {
    let of = |of_part: bool, s: &GeomShape<D>, k: usize| {
        let (centre, radius) = point(s, k);
        CornerOf { of_part, centre, radius }
    };
    match (a, b) {
        (_, GeomShape::Ball { radius }) => CornerOf { of_part: true, centre: D::Vector::default(), radius: *radius },
        (GeomShape::Ball { radius }, _) => CornerOf { of_part: false, centre: D::Vector::default(), radius: *radius },
        (GeomShape::Plane { .. }, _) => of(true, b, k),
        (_, GeomShape::Plane { .. }) => of(false, a, k),
        _ if k < point_count(b) => of(true, b, k),
        _ => of(false, a, k - point_count(b)),
    }
}

/// The points of a cylinder's rim watched, on each of its two rims, evenly
/// from its $x$ axis: a regular polygon inscribed in the rim, within
/// $R(1 - \cos(\pi/32)) = 0.0048R$ of it ([`corners`]).
pub const RIM_POINTS: usize = 32;

/// How many corners a shape has ([`point`]): a box's $2^n$, a capsule's two
/// end balls (one ball where it has no length), a cylinder's rim points
/// (in space); none for other shapes.
fn point_count<D: Dimension>(s: &GeomShape<D>) -> usize {
    match s {
        GeomShape::Box { .. } => 1 << D::POINT_DIM,
        GeomShape::Cylinder { .. } if D::POINT_DIM == 3 => 2 * RIM_POINTS,
        GeomShape::Capsule { half_length, .. } if *half_length == 0.0 => 1,
        GeomShape::Capsule { .. } => 2,
        _ => 0,
    }
}

/// Corner `k` of a box, a capsule or a cylinder (below [`point_count`]) in
/// its frame: centre and radius.
fn point<D: Dimension>(s: &GeomShape<D>, k: usize) -> (D::Vector, f64) {
    match s {
        GeomShape::Box { half_extents } => {
            let mut c = *half_extents;
            for i in 0..D::POINT_DIM {
                if k >> i & 1 == 1 {
                    c[i] = -c[i];
                }
            }
            (c, 0.0)
        }
        GeomShape::Cylinder { half_length, radius } => {
            let turn = std::f64::consts::TAU * (k % RIM_POINTS) as f64 / RIM_POINTS as f64;
            let side = if k < RIM_POINTS { 1.0 } else { -1.0 };
            (vector::<D>(&[radius * turn.cos(), radius * turn.sin(), side * half_length]), 0.0)
        }
        GeomShape::Capsule { half_length, radius } if *half_length == 0.0 => (D::Vector::default(), *radius),
        GeomShape::Capsule { half_length, radius } => {
            let side = if k == 0 { 1.0 } else { -1.0 };
            (vector::<D>(&[side * half_length, 0.0, 0.0]), *radius)
        }
        _ => unreachable!("a shape without corners has no corner {k}"),
    }
}

/// Whether two shapes that touch at corners may also meet edge across
/// edge, where no corner touches: two of box, capsule and cylinder, in space. Their
/// pairs of edges are then watched after their corners (`mechanism/contact/crossing.rs`).
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{edges_cross, GeomShape};
/// use flexure::space::{Planar, Spatial};
/// use nalgebra::{Vector2, Vector3};
/// let brick = GeomShape::<Spatial>::Box { half_extents: Vector3::new(0.1, 0.2, 0.3) };
/// assert!(edges_cross(&brick, &brick));
/// let tile = GeomShape::<Planar>::Box { half_extents: Vector2::new(0.1, 0.2) };
/// assert!(!edges_cross(&tile, &tile));
/// ```
pub fn edges_cross<D: Dimension>(a: &GeomShape<D>, b: &GeomShape<D>) -> bool {
    D::POINT_DIM == 3 && point_count(a) > 0 && point_count(b) > 0
}

/// Which two geoms touch ([`corners`]), as refusals say it.
pub(crate) fn touching<D: Dimension>() -> &'static str {
    match D::POINT_DIM {
        2 => "two geoms touch only where one is a circle, or neither is a plane (two planes never part)",
        _ => "two geoms touch only where one is a sphere, or neither is a plane (two planes never part)",
    }
}

/// The number of corners of geoms `g` and `h` of `m` (1 where their gap
/// is not found, so that the pair is kept and refused by name where it is used).
/// Their pairs of edges ([`super::crossing`]) follow their corners.
pub(crate) fn count<D: Dimension>(m: &Mechanism<D>, g: usize, h: usize) -> usize {
    let (a, b) = (&m.geoms[g].shape, &m.geoms[h].shape);
    corner_count(a, b).unwrap_or(1) + crossings(a, b)
}

/// The number of pairs of edges of shapes `a` and `b` that may cross ([`edges_cross`]).
fn crossings<D: Dimension>(a: &GeomShape<D>, b: &GeomShape<D>) -> usize {
    match edges_cross(a, b) {
        true => ridges(a) * ridges(b),
        false => 0,
    }
}

/// A corner of a pair of two geoms, placed: the geom it is of, the geom
/// it touches, its centre in its geom's body's frame, and its radius.
pub(crate) struct Corner<'m, D: Touch> {
    /// The geom whose corner it is.
    pub round: &'m Geom<D>,
    /// The geom it touches.
    pub flat: &'m Geom<D>,
    /// Its centre in `round`'s body's frame (m).
    pub centre: D::Vector,
    /// Its radius (m).
    pub radius: f64,
    /// Of a pair of edges, `round`'s and `flat`'s ([`super::crossing`]):
    /// its centre moves along its edge, placed by [`Corner::crossing`].
    pub edge: Option<(usize, usize)>,
}

impl<'m, D: Touch> Corner<'m, D> {
    /// The material point of its geom at `point` (world), its body at
    /// `bodies[round.body]`, as [`super::material_jet`] takes it.
    pub fn material(&self, bodies: &[D::Pose], point: &D::Point) -> super::Material {
        let local = D::act(&D::inverse(&bodies[self.round.body]), point);
        super::on_ball(super::array::<D>(&D::position(&local)))
    }

    /// Whether it is one material point that slides and does not roll: a
    /// box's sharp corner, or a point of an edge crossing another.
    pub fn sharp(&self) -> bool {
        self.radius == 0.0 || self.edge.is_some()
    }

    /// The corner's point in the world, bodies at `bodies`.
    fn world(&self, bodies: &[D::Pose]) -> D::Point {
        D::act(&bodies[self.round.body], &D::moved(&D::origin(&D::identity()), &self.centre, 1.0))
    }

    /// Of a fixed corner, how far its centre lies within the face of the
    /// geom it touches whose outward normal is `normal` (world), past
    /// rounding ($10^{-9}$ of the mechanism's size `size`), bodies at
    /// `bodies` (m; [`GeomShape::face_margin`]): below zero it has slid past
    /// that face's edge. `None` for a pair of edges.
    ///
    /// [`GeomShape::face_margin`]: super::GeomShape::face_margin
    pub fn on_face(&self, bodies: &[D::Pose], size: f64, normal: &D::Vector) -> Option<f64> {
        if self.edge.is_some() {
            return None;
        }
        let frame = D::compose(&bodies[self.flat.body], &self.flat.frame);
        let world = self.world(bodies);
        let local = D::position(&D::act(&D::inverse(&frame), &world));
        let n = D::rotate(&D::inverse(&frame), normal);
        Some(self.flat.shape.face_margin(&local, &n) + 1e-9 * size)
    }

    /// The geom a fixed corner touches, bodies at `bodies`: `flat`, or,
    /// where a box's sharp corner lies in the plane of a face of the box
    /// `flat` that faces the same way as one of its own box's faces at the
    /// corner (two faces flush in one plane: boxes of one width stacked,
    /// or side by side), `flat` with each such face moved out by its width.
    /// On that plane the corner is on `flat`'s surface, and sunk below its
    /// other face it read no depth (the box went through); the face moved
    /// out, it reads the other face's. Off the plane, and above that face,
    /// the two agree.
    pub fn against(&self, bodies: &[D::Pose]) -> std::borrow::Cow<'m, Geom<D>> {
        use std::borrow::Cow;
        let (GeomShape::Box { half_extents: e }, GeomShape::Box { half_extents: own }) =
            (&self.flat.shape, &self.round.shape)
        else {
            return Cow::Borrowed(self.flat);
        };
        if self.edge.is_some() || self.radius != 0.0 {
            return Cow::Borrowed(self.flat);
        }
        let world = self.world(bodies);
        let (mine, theirs) = (
            D::compose(&bodies[self.round.body], &self.round.frame),
            D::compose(&bodies[self.flat.body], &self.flat.frame),
        );
        let (at_mine, at_theirs) =
            (D::position(&D::act(&D::inverse(&mine), &world)), D::position(&D::act(&D::inverse(&theirs), &world)));
        let size: f64 = (0..D::POINT_DIM).map(|i| e[i] + own[i]).sum();
        let sign = |x: f64| if x < 0.0 { -1.0 } else { 1.0 };
        let normal = |frame: &D::Pose, i: usize, s: f64| {
            let mut a = D::Vector::default();
            a[i] = s;
            D::rotate(frame, &a)
        };
        let (mut half, mut shift) = (*e, D::Vector::default());
        for i in 0..D::POINT_DIM {
            let s = sign(at_theirs[i]);
            let n = normal(&theirs, i, s);
            let faces =
                (0..D::POINT_DIM).any(|j| super::dot::<D>(&n, &normal(&mine, j, sign(at_mine[j]))) > 1.0 - 1e-9);
            if (at_theirs[i].abs() - e[i]).abs() <= 1e-9 * size && faces {
                (half[i], shift[i]) = (2.0 * e[i], s * e[i]);
            }
        }
        if half == *e {
            return Cow::Borrowed(self.flat);
        }
        let frame = D::compose(&self.flat.frame, &D::at(&D::moved(&D::origin(&D::identity()), &shift, 1.0)));
        Cow::Owned(self.flat.stand_in(frame, GeomShape::Box { half_extents: half }))
    }

    /// Of a pair of edges, where they are nearest, bodies at `bodies`
    /// ([`super::crossing::crossing`]); `None` for a fixed corner.
    pub fn crossing(&self, bodies: &[D::Pose]) -> Option<Crossing<D>> {
        self.edge.map(|e| crossing(self.round, self.flat, e, bodies, false))
    }

    /// [`Corner::crossing`] of a pair that touches: the lines' gap
    /// wherever they cross, smooth up to where it is let go.
    pub fn held(&self, bodies: &[D::Pose]) -> Option<Crossing<D>> {
        self.edge.map(|e| crossing(self.round, self.flat, e, bodies, true))
    }
}

/// The corner of `pair` of `m` (its [`Pair::corner`]th, [`corners`]); an
/// error naming the pair where two geoms' gap is not found, or where the
/// pair is no pair of two geoms.
pub(crate) fn corner<'m, D: Touch>(m: &'m Mechanism<D>, pair: &Pair) -> Result<Corner<'m, D>> {
    let Toucher::Geom(h) = pair.part else {
        return Err(Error::invalid("pair", named(m, pair), "is not a pair of two geoms"));
    };
    let (geom, other) = (&m.geoms[pair.geom], &m.geoms[h]);
    let refused = || Error::invalid("pair", named(m, pair), touching::<D>());
    let found = corner_count(&geom.shape, &other.shape).ok_or_else(refused)?;
    if let Some(k) = pair.corner.checked_sub(found).filter(|&k| k < crossings(&geom.shape, &other.shape)) {
        let n = ridges(&geom.shape);
        let radius = ridge(&other.shape, k / n).radius;
        return Ok(Corner {
            round: other,
            flat: geom,
            centre: D::Vector::default(),
            radius,
            edge: Some((k / n, k % n)),
        });
    }
    if pair.corner >= found {
        return Err(refused());
    }
    let c = corner_of(&geom.shape, &other.shape, pair.corner);
    let (round, flat) = if c.of_part { (other, geom) } else { (geom, other) };
    let centre = D::position(&D::act(&round.frame, &D::moved(&D::origin(&D::identity()), &c.centre, 1.0)));
    Ok(Corner { round, flat, centre, radius: c.radius, edge: None })
}

/// Of a pair of two edges ([`Corner::crossing`]), where they are nearest,
/// bodies at `bodies`; `None` for any other pair.
pub(crate) fn crossing_of<D: Touch>(m: &Mechanism<D>, pair: &Pair, bodies: &[D::Pose]) -> Option<Crossing<D>> {
    corner(m, pair).ok()?.crossing(bodies)
}

/// Of a pair of two edges (placed as `k`), the pair of the corner at the
/// end nearest where they cross ([`super::crossing::End`]): that edge's
/// geom's corner nearest its surface point there. It takes the touch where
/// the crossing runs off that end, and gives it back where it comes back.
pub(crate) fn end_corner<D: Touch>(m: &Mechanism<D>, pair: &Pair, k: &Crossing<D>) -> Option<Pair> {
    let end = k.end?;
    let Toucher::Geom(h) = pair.part else { return None };
    let (a, b) = (&m.geoms[pair.geom].shape, &m.geoms[h].shape);
    let far = |c: &CornerOf<D>| {
        let d = super::array::<D>(&c.centre);
        (0..3).map(|i| (d[i] - end.point[i]).powi(2)).sum::<f64>()
    };
    (0..corner_count(a, b)?)
        .map(|i| (i, corner_of(a, b, i)))
        .filter(|(_, c)| c.of_part == end.of_round)
        .min_by(|x, y| far(&x.1).total_cmp(&far(&y.1)))
        .map(|(corner, _)| Pair { corner, ..*pair })
}

/// Of a touching pair of two edges (placed as `k`) let go, the pair of the
/// corner that takes its touch: where the crossing ran off an edge's end,
/// or lies within `near` of the edge's length of it (where a step landed on
/// it to a tolerance; [`end_corner`]); `None` where it left the faces'
/// normals instead.
pub(crate) fn ran_off<D: Touch>(m: &Mechanism<D>, pair: &Pair, k: &Crossing<D>, near: f64) -> Option<Pair> {
    k.end.filter(|e| e.within < near * e.length).and_then(|_| end_corner(m, pair, k))
}

/// Of a pair of two edges that begins to touch, bodies at `bodies`, the
/// corner pair it takes the touch from, where its crossing came back onto
/// an edge from that corner ([`end_corner`]; within [`COMING_BACK`] of the
/// edge's length of its end): the same touch, not a second one beside it,
/// whose rows the motion's closures would hold twice.
pub(crate) fn came_back<D: Touch>(m: &Mechanism<D>, pair: &Pair, bodies: &[D::Pose]) -> Option<Pair> {
    let k = crossing_of(m, pair, bodies)?;
    k.end.filter(|e| e.within <= COMING_BACK * e.length).and_then(|_| end_corner(m, pair, &k))
}

/// How near an edge's end (a share of its length) a crossing that begins to
/// touch takes the touch of the corner there ([`came_back`]): where it
/// comes back onto a rounded edge, its gap falls below the tolerance $\epsilon$ some
/// $\sqrt{2r\epsilon}$ in, a few micrometres.
pub(crate) const COMING_BACK: f64 = 1e-3;

/// A box's edges (pairs of corners one axis apart) or a capsule's segment,
/// each with its radius, in the shape's frame; a ball is its centre.
fn edges<D: Dimension>(s: &GeomShape<D>) -> Vec<(D::Vector, D::Vector, f64)> {
    match s {
        GeomShape::Box { .. } => {
            let mut out = Vec::new();
            for k in 0..point_count(s) {
                for i in 0..D::POINT_DIM {
                    if k >> i & 1 == 0 {
                        out.push((point(s, k).0, point(s, k | 1 << i).0, 0.0));
                    }
                }
            }
            out
        }
        GeomShape::Capsule { half_length, radius } => {
            let end = vector::<D>(&[*half_length, 0.0, 0.0]);
            vec![(end, super::scaled::<D>(&end, -1.0), *radius)]
        }
        GeomShape::Ball { radius } => vec![(D::Vector::default(), D::Vector::default(), *radius)],
        _ => Vec::new(),
    }
}

/// Why two geoms are stopped at that went through each other edge across
/// edge between two states, neither their corners nor their edges seen to
/// touch ([`crossed_edges`]).
pub(crate) const PASSED_THROUGH: &str = "passed through each other edge across edge between two states, where neither their corners nor their edges were seen to touch: make the steps smaller";

/// Whether `pair` is two geoms that may meet edge across edge
/// ([`edges_cross`]), at its first corner (one for the two).
pub(crate) fn may_cross<D: Dimension>(m: &Mechanism<D>, pair: &Pair) -> bool {
    match pair.part {
        Toucher::Geom(h) => pair.corner == 0 && edges_cross(&m.geoms[pair.geom].shape, &m.geoms[h].shape),
        Toucher::Flexure(_) => false,
    }
}

/// The first pair of `pairs` whose two geoms may meet edge across edge
/// ([`may_cross`]) and are through each other, an edge dipping into the
/// other deeper than `depth` (m) below its own corners ([`deepest_edge`]),
/// bodies at `bodies`: a guard against a step that went through a thin geom,
/// where their gaps, corners' and edges', may all be positive again.
pub(crate) fn crossed_edges<D: Touch>(
    m: &Mechanism<D>,
    bodies: &[D::Pose],
    pairs: &[Pair],
    depth: f64,
) -> Option<Pair> {
    let dips = |p: &Pair| match p.part {
        Toucher::Geom(h) => deepest_edge(m, bodies, p.geom, h) < -depth,
        Toucher::Flexure(_) => false,
    };
    pairs.iter().copied().find(|p| may_cross(m, p) && dips(p))
}

/// How far any edge of geom `a` (a box's, a capsule's segment) dips into
/// geom `b` below its own ends and below the surface, and the other way
/// (m; negative: that deep), bodies at `bodies`: what finds two bars
/// crossed with no corner inside the other. An edge along a face dips no
/// deeper than its ends (its corners, which their own gaps watch). A
/// convex solid's signed distance is convex along a line, so
/// golden-section search finds each edge's least.
pub(crate) fn deepest_edge<D: Touch>(m: &Mechanism<D>, bodies: &[D::Pose], a: usize, b: usize) -> f64 {
    let one_way = |a: &Geom<D>, b: &Geom<D>| {
        let frame = D::compose(&bodies[a.body], &a.frame);
        let at = |from: &D::Vector, to: &D::Vector, r: f64, t: f64| {
            let p = *from + super::scaled::<D>(&(*to - *from), t);
            b.gap(&bodies[b.body], &D::act(&frame, &D::moved(&D::origin(&D::identity()), &p, 1.0)), r).0
        };
        edges(&a.shape)
            .iter()
            .map(|(from, to, r)| {
                let ratio = 0.5 * (5f64.sqrt() - 1.0);
                let (mut lo, mut hi) = (0.0, 1.0);
                for _ in 0..80 {
                    let (c, d) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
                    if at(from, to, *r, c) < at(from, to, *r, d) { hi = d } else { lo = c }
                }
                let ends = at(from, to, *r, 0.0).min(at(from, to, *r, 1.0));
                at(from, to, *r, 0.5 * (lo + hi)).min(ends) - ends.min(0.0)
            })
            .fold(f64::INFINITY, f64::min)
    };
    one_way(&m.geoms[a], &m.geoms[b]).min(one_way(&m.geoms[b], &m.geoms[a]))
}
