//! Crossings: the parts of a solved shape that cross another part, or
//! themselves ([`crossings`]), written once over the dimension
//! ([`Findings`]); see the module docs of [`super`] for the parts and the rules.

use super::convex::{nearest_on_segments, within};
use super::dimension::Findings;
use super::geometry::{distance, meet};
use crate::mechanism::{Dimension, Mechanism};
use crate::space::{Planar, Spatial};
use nalgebra::{Point, Point2, Point3};

/// The most a flexure's backbone turns (rad) along one of the chords that
/// stand for it in [`crossings`].
pub const CHORD_TURN: f64 = 0.05;

/// The fewest chords per flexure in [`crossings`].
pub const MIN_CHORDS: usize = 64;

/// The most chords per flexure in [`crossings`] (a flexure winding more
/// than `MAX_CHORDS × CHORD_TURN` = 205 rad has longer chords).
pub const MAX_CHORDS: usize = 4096;

/// Two segments touch when they come this close, relative to the
/// mechanism's size; and a contact this close to an end of both parts is
/// where they are joined.
pub const TOUCH_TOLERANCE: f64 = 1e-7;

/// A part of a drawn mechanism.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// A flexure joint, by index in [`Mechanism::joints`].
    Flexure(usize),
    /// A body's link (the ground included), by index in [`Mechanism::bodies`].
    Link(usize),
    /// A geom, by index in [`Mechanism::geoms`]: a spatial strip's width
    /// that passes through it ([`crate::mechanism::contact::width_crossings`]).
    Geom(usize),
}

impl Part {
    /// `flexure "left"` or `link "stage"`.
    pub fn describe<D: Dimension>(&self, m: &Mechanism<D>) -> String {
        match *self {
            Part::Flexure(j) => format!("flexure {:?}", m.joints[j].name),
            Part::Link(b) => format!("link {:?}", m.bodies[b].name),
            Part::Geom(g) => format!("geom {:?}", m.geoms[g].name),
        }
    }
}

/// Two parts that cross, meeting at `at`: a point of the plane (`[f64; 2]`)
/// or of space (`[f64; 3]`), as [`crossings`] finds them.
#[derive(Debug, Clone, PartialEq)]
pub struct Crossing<P = [f64; 2]> {
    /// The first part (the earlier flexure, or a flexure before a link).
    pub a: Part,
    /// The second part (equal to `a` for a flexure that crosses itself).
    pub b: Part,
    /// `a` and `b` as [`Part::describe`] gives them.
    pub names: [String; 2],
    /// The first point where they meet (ground frame, m), first along `a`.
    pub at: P,
    /// The arc length (m from its root) where each part meets the other
    /// there, for a flexure; `None` for a link.
    pub s: [Option<f64>; 2],
    /// At how many distinct points their segments meet (one crossing, or several).
    pub points: usize,
}

impl<P: AsRef<[f64]>> Crossing<P> {
    /// The finding in words.
    pub fn message(&self) -> String {
        let along: Vec<String> =
            (0..2).filter_map(|k| self.s[k].map(|s| format!("{s:.6e} m along {}", self.names[k]))).collect();
        let at: Vec<String> = self.at.as_ref().iter().map(|x| format!("{x:.6e}")).collect();
        let mut where_ = format!("at ({}) m", at.join(", "));
        if self.a == self.b {
            if let (Some(s0), Some(s1)) = (self.s[0], self.s[1]) {
                where_ += &format!(" ({s0:.6e} and {s1:.6e} m along it)");
            }
            return format!(
                "{} crosses itself {where_}; parts touch only geoms, not each other, so this shape passes through itself",
                self.names[0]
            );
        }
        if !along.is_empty() {
            where_ += &format!(" ({})", along.join(", "));
        }
        if matches!(self.b, Part::Geom(_)) {
            let more = if self.points > 1 { format!(", {} sections in all", self.points) } else { String::new() };
            return format!(
                "{}'s width crosses {} {where_}{more}; a spatial flexure touches geoms with the tube of half its \
                 thickness about its centreline, so its width passes through this one (a narrower strip, or the \
                 geom moved, if they should touch)",
                self.names[0], self.names[1]
            );
        }
        let more = if self.points > 1 { format!(", {} points in all", self.points) } else { String::new() };
        format!(
            "{} crosses {} {where_}{more}; parts touch only geoms, not each other, so this shape passes through itself",
            self.names[0], self.names[1]
        )
    }
}

/// A crossing in the dimension `D`.
pub type CrossingAt<D> = Crossing<<D as Findings>::At>;

/// One piece of a part: its solid (in space), its centreline (a flexure's
/// chord, or a link's edge), its ends' indices along the part (a chord's
/// samples, an edge's points: pieces sharing one are neighbours), the arc
/// length at its ends (a flexure), and its bounding box (the plane's at
/// z = 0).
pub struct Piece<D: Findings> {
    pub(super) solid: D::Solid,
    pub(super) line: [D::Point; 2],
    pub(super) ends: [usize; 2],
    pub(super) arc: Option<[f64; 2]>,
    pub(super) lo: [f64; 3],
    pub(super) hi: [f64; 3],
}

impl<D: Findings> Piece<D> {
    /// A piece whose bounding box is its centreline's.
    pub(super) fn new(solid: D::Solid, line: [D::Point; 2], ends: [usize; 2], arc: Option<[f64; 2]>) -> Self {
        let (lo, hi) = bounds(line.iter().map(D::coordinates), 0.0);
        Piece { solid, line, ends, arc, lo, hi }
    }

    /// The arc length at `t` along it (0 at its start, 1 at its end), for a flexure.
    fn arc_at(&self, t: f64) -> Option<f64> {
        self.arc.map(|r| r[0] + t * (r[1] - r[0]))
    }
}

/// A part's geometry: its pieces, the points where it is joined to others,
/// its largest section half-diagonal (0 without a section), and its
/// bounding box.
pub struct PartGeometry<D: Findings> {
    pub(super) pieces: Vec<Piece<D>>,
    pub(super) ends: Vec<D::Point>,
    pub(super) reach: f64,
    pub(super) lo: [f64; 3],
    pub(super) hi: [f64; 3],
}

impl<D: Findings> PartGeometry<D> {
    /// A shape whose bounding box is its pieces'.
    pub(super) fn new(pieces: Vec<Piece<D>>, ends: Vec<D::Point>, reach: f64) -> Self {
        let (lo, hi) = bounds(pieces.iter().flat_map(|p| [p.lo, p.hi]), 0.0);
        PartGeometry { pieces, ends, reach, lo, hi }
    }
}

/// A part as drawn: which it is, the bodies it belongs to (a closure's or a
/// rigid joint's bodies count as one, see [`crossings`]), and its shape.
pub struct PlacedPart<D: Findings> {
    pub(super) part: Part,
    pub(super) groups: Vec<usize>,
    pub(super) shape: PartGeometry<D>,
}

/// The box of `corners`, each grown by `grow`.
pub(super) fn bounds(corners: impl IntoIterator<Item = [f64; 3]>, grow: f64) -> ([f64; 3], [f64; 3]) {
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for p in corners {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i] - grow);
            hi[i] = hi[i].max(p[i] + grow);
        }
    }
    (lo, hi)
}

/// Whether two boxes are more than `gap` apart along an axis.
fn apart(lo_a: &[f64; 3], hi_a: &[f64; 3], lo_b: &[f64; 3], hi_b: &[f64; 3], gap: f64) -> bool {
    (0..3).any(|i| hi_a[i] + gap < lo_b[i] || hi_b[i] + gap < lo_a[i])
}

/// The chords that stand for a flexure with coordinates `alpha` (see the module docs).
pub fn chords(alpha: &[f64]) -> usize {
    let turning: f64 = alpha.iter().map(|a| a.abs()).sum();
    let wanted = (turning / CHORD_TURN).ceil();
    if wanted.is_finite() { (wanted as usize).clamp(MIN_CHORDS, MAX_CHORDS) } else { MAX_CHORDS }
}

/// Every part of `m` at coordinates `q` that crosses another, or itself
/// (see the module docs): at most one [`Crossing`] per pair of parts, the
/// first along the first part, with the number of points where they meet.
///
/// # Panics
/// If `q` does not have [`Mechanism::dof`] entries.
///
/// # Example
/// ```
/// use flexure::mechanism::file::spatial_from_toml;
/// use flexure::mechanism::findings::crossings;
/// // Two round rods 2 mm thick side by side, their axes 1.9 mm apart: they overlap.
/// let rods = |gap: f64| format!(
///     "dimension = 3\n[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"ta\"\n\
///      length = 0.05\ndiameter = 2e-3\nmodulus = 2e11\npoisson = 0.3\n\
///      [[joint]]\nname = \"b\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tb\"\n\
///      origin = [0.0, {gap}, 0.0]\nlength = 0.05\ndiameter = 2e-3\nmodulus = 2e11\npoisson = 0.3\n");
/// let m = spatial_from_toml(&rods(1.9e-3)).unwrap();
/// let found = crossings(&m, &m.rest());
/// assert_eq!(found.len(), 1);
/// assert!(found[0].message().starts_with("flexure \"a\" crosses flexure \"b\""));
/// let m = spatial_from_toml(&rods(2.1e-3)).unwrap();
/// assert!(crossings(&m, &m.rest()).is_empty());
/// ```
pub fn crossings<D: Findings>(m: &Mechanism<D>, q: &[f64]) -> Vec<CrossingAt<D>> {
    assert_eq!(q.len(), m.dof(), "crossings: q must have one entry per coordinate");
    let (bodies, roots) = D::poses(m, q);
    let tolerance = D::touch_tolerance(m);
    let parts = drawn(m, q, &bodies, &roots, &groups(m), tolerance);
    let mut out = Vec::new();
    for (i, a) in parts.iter().enumerate() {
        if let Part::Flexure(_) = a.part
            && let Some(c) = D::cross(a, a, false, tolerance)
        {
            out.push(named(m, c));
        }
        for b in &parts[i + 1..] {
            if apart(&a.shape.lo, &a.shape.hi, &b.shape.lo, &b.shape.hi, tolerance) {
                continue;
            }
            let joined = a.groups.iter().any(|g| b.groups.contains(g));
            if let Some(c) = D::cross(a, b, joined, tolerance) {
                out.push(named(m, c));
            }
        }
    }
    out.extend(D::width_crossings(m, q, (&bodies, &roots), tolerance));
    out
}

fn named<D: Findings>(m: &Mechanism<D>, mut c: CrossingAt<D>) -> CrossingAt<D> {
    c.names = [c.a.describe(m), c.b.describe(m)];
    c
}

/// Each body's group: bodies joined by a closure, or by a joint other than a flexure, are one group.
fn groups<D: Dimension>(m: &Mechanism<D>) -> Vec<usize> {
    let mut g: Vec<usize> = (0..m.bodies.len()).collect();
    fn root(g: &mut [usize], mut i: usize) -> usize {
        while g[i] != i {
            g[i] = g[g[i]];
            i = g[i];
        }
        i
    }
    let closed = m.closures.iter().map(|c| (c.a, c.b));
    // Rigid joints (revolute, prismatic, fixed, ball) hold their bodies together at a point, as closures do.
    let rigid = m.joints.iter().filter(|j| j.kind.flexure().is_none()).map(|j| (j.parent, j.child));
    for (a, b) in closed.chain(rigid) {
        let (ra, rb) = (root(&mut g, a), root(&mut g, b));
        g[ra.max(rb)] = ra.min(rb);
    }
    (0..g.len()).map(|i| root(&mut g, i)).collect()
}

/// The parts of `m` at `q`, the bodies' and joints' root frames given:
/// flexures first, in joint order, then links.
fn drawn<D: Findings>(
    m: &Mechanism<D>,
    q: &[f64],
    bodies: &[D::Pose],
    roots: &[D::Pose],
    group: &[usize],
    tolerance: f64,
) -> Vec<PlacedPart<D>> {
    let mut parts = Vec::new();
    for (ji, j) in m.joints.iter().enumerate() {
        let Some(f) = j.kind.flexure() else { continue };
        let alpha = &q[j.offset..j.offset + j.kind.joint().dof()];
        let tip = D::origin(&bodies[j.child]);
        let Some(shape) = D::flexure_shape(f, alpha, chords(alpha) + 1, &roots[ji], tip) else { continue };
        parts.push(PlacedPart { part: Part::Flexure(ji), groups: vec![group[j.parent], group[j.child]], shape });
    }
    for b in 0..m.bodies.len() {
        let anchors = m.tendons.iter().flat_map(|t| &t.path).filter(|v| v.0 == b).map(|v| v.1);
        let points = hull_points(m.attachments(b), b, anchors).iter().map(|r| D::act(&bodies[b], r)).collect();
        let Some(mut shape) = D::link_shape(points, tolerance) else { continue };
        // Where a body it carries by a rigid joint (a slider's carriage, a hinge's child) is held.
        let carried = m.joints.iter().filter(|j| j.parent == b && j.kind.flexure().is_none());
        shape.ends.extend(carried.map(|j| D::origin(&bodies[j.child])));
        parts.push(PlacedPart { part: Part::Link(b), groups: vec![group[b]], shape });
    }
    parts
}

/// A flexure's centreline through `points` (as its own integration gives
/// them, ending within that integration's error of the model's tip),
/// moved in proportion to arc length so that it ends at `tip`, where the
/// child is drawn.
pub(super) fn ending_at<const N: usize>(mut points: Vec<Point<f64, N>>, tip: Point<f64, N>) -> Vec<Point<f64, N>> {
    let last = points.len() - 1;
    let miss = tip - points[last];
    for (i, p) in points.iter_mut().enumerate() {
        *p += miss * (i as f64 / last as f64);
    }
    points
}

/// The arc lengths at the ends of chord `i` of `chords` along a flexure of `length`.
pub(super) fn arc(length: f64, i: usize, chords: usize) -> Option<[f64; 2]> {
    Some([length * i as f64 / chords as f64, length * (i + 1) as f64 / chords as f64])
}

/// The points of body `b` whose hull is its solid: its attachment points,
/// but for the ground without the tendons' anchors in it (`anchors`, each
/// taken out once), which are separate points of the world, not corners of
/// one part: a tendon anchored beside the mechanism does not make the
/// ground a hull that its parts cross.
pub(crate) fn hull_points<P: PartialEq>(mut attachments: Vec<P>, b: usize, anchors: impl Iterator<Item = P>) -> Vec<P> {
    if b == 0 {
        for a in anchors {
            if let Some(i) = attachments.iter().position(|p| *p == a) {
                attachments.remove(i);
            }
        }
    }
    attachments
}

/// [`crossings`] at each of a series of shapes (a sweep's rows, a
/// simulation's samples): (index in the series, its crossings), for the
/// shapes that have any.
pub fn crossings_along<'a, D: Findings>(
    m: &Mechanism<D>,
    shapes: impl IntoIterator<Item = &'a [f64]>,
) -> Vec<(usize, Vec<CrossingAt<D>>)> {
    shapes.into_iter().map(|q| crossings(m, q)).enumerate().filter(|(_, c)| !c.is_empty()).collect()
}

// The plane: a flexure is its backbone's chords, and parts cross where
// their segments meet.

/// A planar flexure's chords through `points`, a flexure of `length`.
pub(super) fn chords_in_plane(points: &[Point2<f64>], length: f64) -> Vec<Piece<Planar>> {
    let n = points.len() - 1;
    (0..n).map(|k| Piece::new((), [points[k], points[k + 1]], [k, k + 1], arc(length, k, n))).collect()
}

/// Where two planar parts' segments first meet, with the number of distinct
/// points where they do; a contact at an end of both parts that `joined`
/// connects is their joint, unless it is a collinear overlap that runs on
/// from there. A flexure against itself: its chords other than consecutive
/// ones at their shared point.
pub(super) fn segments_cross(
    a: &PlacedPart<Planar>,
    b: &PlacedPart<Planar>,
    joined: bool,
    tolerance: f64,
) -> Option<CrossingAt<Planar>> {
    let itself = a.part == b.part;
    let at_end = |d: &PlacedPart<Planar>, p: &Point2<f64>| d.shape.ends.iter().any(|e| distance(e, p) <= tolerance);
    let mut first: Option<CrossingAt<Planar>> = None;
    let mut points: Vec<Point2<f64>> = Vec::new();
    for (k, pa) in a.shape.pieces.iter().enumerate() {
        for pb in &b.shape.pieces[if itself { (k + 2).min(b.shape.pieces.len()) } else { 0 }..] {
            let (sa, sb) = (&pa.line, &pb.line);
            let Some(c) = meet(&sa[0], &sa[1], &sb[0], &sb[1], tolerance) else { continue };
            let at = Point2::from(c.at);
            if joined && at_end(a, &at) && at_end(b, &at) {
                // A collinear overlap running on from the joint is a crossing.
                if !c.collinear || overlap_is_point(sa, sb, tolerance) {
                    continue;
                }
            }
            add_point(&mut points, at, tolerance);
            if first.is_none() {
                let s = [pa.arc_at(c.t[0]), pb.arc_at(c.t[1])];
                first = Some(Crossing { a: a.part, b: b.part, names: Default::default(), at: c.at, s, points: 0 });
            }
        }
    }
    first.map(|c| Crossing { points: points.len(), ..c })
}

/// Counts the contact at `p` unless one already counted is within `tolerance`
/// (a crossing through a chord's end is met by both chords there).
fn add_point(points: &mut Vec<Point2<f64>>, p: Point2<f64>, tolerance: f64) {
    if points.iter().all(|c| distance(c, &p) > tolerance) {
        points.push(p);
    }
}

/// Whether two collinear segments share no more than a point.
fn overlap_is_point(sa: &[Point2<f64>; 2], sb: &[Point2<f64>; 2], tolerance: f64) -> bool {
    let r = sa[1] - sa[0];
    let lr = r.x.hypot(r.y);
    let along = |p: &Point2<f64>| (p - sa[0]).dot(&r) / lr;
    let (t0, t1) = (along(&sb[0]), along(&sb[1]));
    t0.max(t1).min(lr) - t0.min(t1).max(0.0) <= tolerance
}

// Space: parts are solids, and cross where their pieces come within the
// tolerance (GJK), neighbouring touches counted as one contact.

/// The relative rounding of a solved position (m per m of distance from
/// the origin): a few hundred times double precision's, for the frames
/// composed along a chain and the flexure shapes integrated there.
const RESOLUTION: f64 = 1e-13;

/// Whether a part is near enough the origin that rounding there is below
/// `tolerance`: one farther out (an origin of 1e30 m) cannot be told
/// touching from apart, and is not tested.
fn resolved(d: &PlacedPart<Spatial>, tolerance: f64) -> bool {
    (0..3).all(|i| d.shape.lo[i].abs().max(d.shape.hi[i].abs()) * RESOLUTION <= tolerance)
}

/// Where two spatial parts' pieces first touch (the least pair of pieces),
/// with the number of separate points where they touch: touching pairs grouped by
/// neighbourhood ([`clusters`]), less those at a joint, if `joined`: a
/// contact holding a piece of each whose centreline passes through a point
/// that is an end of both, however far it runs on from there. A flexure
/// against itself: its pieces farther apart along it than twice its
/// section's half-diagonal (which only a bend tighter than the section
/// could make meet).
pub(super) fn solids_cross(
    a: &PlacedPart<Spatial>,
    b: &PlacedPart<Spatial>,
    joined: bool,
    tolerance: f64,
) -> Option<CrossingAt<Spatial>> {
    if !resolved(a, tolerance) || !resolved(b, tolerance) {
        return None;
    }
    let itself = a.part == b.part;
    let apart_along = |pk: &Piece<Spatial>, pl: &Piece<Spatial>| {
        let (ak, al) = (pk.arc.expect("a flexure's piece"), pl.arc.expect("a flexure's piece"));
        al[0] - ak[1] > 2.0 * a.shape.reach + tolerance
    };
    let mut touching = Vec::new();
    for (k, pa) in a.shape.pieces.iter().enumerate() {
        if apart(&pa.lo, &pa.hi, &b.shape.lo, &b.shape.hi, tolerance) {
            continue;
        }
        for (l, pb) in b.shape.pieces.iter().enumerate().skip(if itself { k + 2 } else { 0 }) {
            if (!itself || apart_along(pa, pb))
                && !apart(&pa.lo, &pa.hi, &pb.lo, &pb.hi, tolerance)
                && within(&pa.solid, &pb.solid, tolerance)
            {
                touching.push((k, l));
            }
        }
    }
    if touching.is_empty() {
        return None;
    }
    let shared: Vec<Point3<f64>> = if joined {
        let near = |p: &Point3<f64>| b.shape.ends.iter().any(|e| (e - p).norm() <= tolerance);
        a.shape.ends.iter().filter(|p| near(p)).copied().collect()
    } else {
        Vec::new()
    };
    // The contact at a joint, however far it runs on from there, is the joint.
    let (pa, pb) = (&a.shape.pieces, &b.shape.pieces);
    let at_joint =
        |k: usize, l: usize| shared.iter().any(|p| passes(&pa[k], p, tolerance) && passes(&pb[l], p, tolerance));
    let clusters = clusters(&touching, a, b);
    let kept: Vec<&Vec<(usize, usize)>> = clusters.iter().filter(|c| !c.iter().any(|&(k, l)| at_joint(k, l))).collect();
    let first = kept.iter().flat_map(|c| c.iter()).min()?;
    Some(crossing(a, b, *first, kept.len()))
}

/// The crossing of `a` and `b` at their pieces' pair `(k, l)`: the midpoint
/// of the nearest points of the two centrelines, and the arc lengths there.
fn crossing(
    a: &PlacedPart<Spatial>,
    b: &PlacedPart<Spatial>,
    (k, l): (usize, usize),
    points: usize,
) -> CrossingAt<Spatial> {
    let (pa, pb) = (&a.shape.pieces[k], &b.shape.pieces[l]);
    let (s, t) = nearest_on_segments(&pa.line, &pb.line);
    let (xa, xb) = (pa.line[0] + (pa.line[1] - pa.line[0]) * s, pb.line[0] + (pb.line[1] - pb.line[0]) * t);
    let at = nalgebra::center(&xa, &xb);
    Crossing { a: a.part, b: b.part, names: Default::default(), at: at.into(), s: [pa.arc_at(s), pb.arc_at(t)], points }
}

/// Whether a piece's centreline passes within `tolerance` of `p`.
fn passes(piece: &Piece<Spatial>, p: &Point3<f64>, tolerance: f64) -> bool {
    let [a, b] = piece.line;
    let ab = b - a;
    let len = ab.norm_squared();
    let t = if len > 0.0 { ((p - a).dot(&ab) / len).clamp(0.0, 1.0) } else { 0.0 };
    (a + ab * t - p).norm() <= tolerance
}

/// The touching pairs of pieces grouped into places: two pairs are one
/// place when each side's pieces are the same or neighbours.
fn clusters(pairs: &[(usize, usize)], a: &PlacedPart<Spatial>, b: &PlacedPart<Spatial>) -> Vec<Vec<(usize, usize)>> {
    let near = |d: &PlacedPart<Spatial>, i: usize, j: usize| {
        i == j || d.shape.pieces[i].ends.iter().any(|e| d.shape.pieces[j].ends.contains(e))
    };
    let mut root: Vec<usize> = (0..pairs.len()).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    for i in 0..pairs.len() {
        for j in i + 1..pairs.len() {
            if near(a, pairs[i].0, pairs[j].0) && near(b, pairs[i].1, pairs[j].1) {
                let (ri, rj) = (find(&mut root, i), find(&mut root, j));
                root[ri.max(rj)] = ri.min(rj);
            }
        }
    }
    let mut out: Vec<(usize, Vec<(usize, usize)>)> = Vec::new();
    for (i, pair) in pairs.iter().enumerate() {
        let r = find(&mut root, i);
        match out.iter_mut().find(|c| c.0 == r) {
            Some(c) => c.1.push(*pair),
            None => out.push((r, vec![*pair])),
        }
    }
    out.into_iter().map(|c| c.1).collect()
}
