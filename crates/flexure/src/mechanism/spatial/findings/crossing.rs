//! Crossings of a spatial mechanism: parts of a solved shape that pass
//! through each other or themselves ([`crossings`]; see the module docs of
//! [`super`] for the parts' solids and the rules).

use crate::kinematics::Level;
use crate::mechanism::findings::{Convex, Crossing, Part, TOUCH_TOLERANCE, chords, within};
use crate::mechanism::spatial::SpatialMechanism;
use crate::mechanism::spatial::kinematics::{SpatialFrames, frames_level_into};
use crate::section::Outline;
use crate::spatial::shape;
use nalgebra::{Point3, Vector3};

/// Two parts of a spatial mechanism that cross, meeting at a point of space.
pub type SpatialCrossing = Crossing<[f64; 3]>;

/// `flexure "left"` or `link "stage"`.
pub fn describe(part: Part, m: &SpatialMechanism) -> String {
    match part {
        Part::Flexure(j) => format!("flexure {:?}", m.joints[j].name),
        Part::Link(b) => format!("link {:?}", m.bodies[b].name),
    }
}

/// One convex piece of a part: its solid, its centreline (a flexure's
/// chord, or a link's edge), the ends' indices along the part (a chord's
/// sections, an edge's hull vertices: pieces sharing one are neighbours),
/// the arc length at its ends (a flexure), and its bounding box.
struct Piece {
    solid: Convex,
    line: [Point3<f64>; 2],
    ends: [usize; 2],
    arc: Option<[f64; 2]>,
    lo: Point3<f64>,
    hi: Point3<f64>,
}

/// A part as pieces, the points where it is joined to others, the bodies
/// it belongs to (a closure's or a rigid joint's bodies count as one), its
/// largest section half-diagonal (0 for a link), and its bounding box.
struct Drawn {
    part: Part,
    pieces: Vec<Piece>,
    ends: Vec<Point3<f64>>,
    groups: Vec<usize>,
    reach: f64,
    lo: Point3<f64>,
    hi: Point3<f64>,
}

fn apart(lo_a: &Point3<f64>, hi_a: &Point3<f64>, lo_b: &Point3<f64>, hi_b: &Point3<f64>, gap: f64) -> bool {
    (0..3).any(|i| hi_a[i] + gap < lo_b[i] || hi_b[i] + gap < lo_a[i])
}

fn bounds<'a>(points: impl IntoIterator<Item = &'a Point3<f64>>, grow: f64) -> (Point3<f64>, Point3<f64>) {
    let (mut lo, mut hi) = (Point3::from([f64::MAX; 3]), Point3::from([f64::MIN; 3]));
    for p in points {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i] - grow);
            hi[i] = hi[i].max(p[i] + grow);
        }
    }
    (lo, hi)
}

/// Every part of `m` at coordinates `q` that crosses another, or itself:
/// at most one [`SpatialCrossing`] per pair of parts, at the first contact
/// along the first part, with the number of separate contacts between them
/// (see [`super`]).
///
/// # Panics
/// If `q` does not have [`SpatialMechanism::dof`] entries.
///
/// # Example
/// ```
/// use flexure::mechanism::file::spatial_from_toml;
/// use flexure::mechanism::spatial::findings::crossings;
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
pub fn crossings(m: &SpatialMechanism, q: &[f64]) -> Vec<SpatialCrossing> {
    assert_eq!(q.len(), m.dof(), "crossings: q must have one entry per coordinate");
    let mut f = SpatialFrames::new(m);
    frames_level_into(m, q, Level::Pose, &mut f);
    let tolerance = touch_tolerance(m);
    let parts = drawn(m, q, &f, &groups(m), tolerance);
    // A part so far out that rounding there exceeds the tolerance cannot be
    // told touching from apart (an origin of 1e30 m): it is not tested.
    let resolved = |d: &Drawn| (0..3).all(|i| d.lo[i].abs().max(d.hi[i].abs()) * RESOLUTION <= tolerance);
    let mut out = Vec::new();
    for (i, a) in parts.iter().enumerate() {
        if !resolved(a) {
            continue;
        }
        if let Some(c) = self_crossing(a, tolerance) {
            out.push(named(m, c));
        }
        for b in &parts[i + 1..] {
            if !resolved(b) || apart(&a.lo, &a.hi, &b.lo, &b.hi, tolerance) {
                continue;
            }
            let mut touching = Vec::new();
            for (k, pa) in a.pieces.iter().enumerate() {
                if apart(&pa.lo, &pa.hi, &b.lo, &b.hi, tolerance) {
                    continue;
                }
                for (l, pb) in b.pieces.iter().enumerate() {
                    if !apart(&pa.lo, &pa.hi, &pb.lo, &pb.hi, tolerance) && within(&pa.solid, &pb.solid, tolerance) {
                        touching.push((k, l));
                    }
                }
            }
            if touching.is_empty() {
                continue;
            }
            let joined = a.groups.iter().any(|g| b.groups.contains(g));
            let shared: Vec<Point3<f64>> = if joined {
                a.ends.iter().filter(|p| b.ends.iter().any(|e| (e - *p).norm() <= tolerance)).copied().collect()
            } else {
                Vec::new()
            };
            // The contact at a joint, however far it runs on from there, is the joint.
            let at_joint = |k: usize, l: usize| {
                shared.iter().any(|p| passes(&a.pieces[k], p, tolerance) && passes(&b.pieces[l], p, tolerance))
            };
            let clusters = clusters(&touching, a, b);
            let kept: Vec<&Vec<(usize, usize)>> =
                clusters.iter().filter(|c| !c.iter().any(|&(k, l)| at_joint(k, l))).collect();
            let Some(first) = kept.iter().flat_map(|c| c.iter()).min() else { continue };
            out.push(named(m, crossing(a, b, *first, kept.len())));
        }
    }
    out
}

/// The relative rounding of a solved position (m per m of distance from
/// the origin): a few hundred times double precision's, for the frames
/// composed along a chain and the flexure shapes integrated there.
const RESOLUTION: f64 = 1e-13;

/// How near two parts must come to touch: [`TOUCH_TOLERANCE`] × the
/// mechanism's size, but no more than that × 10⁴ shortest flexure lengths,
/// so that one far offset (an origin of 1e30 m) does not make every part
/// touch every other.
fn touch_tolerance(m: &SpatialMechanism) -> f64 {
    let shortest = m.joints.iter().filter_map(|j| Some(j.kind.flexure()?.length())).fold(f64::INFINITY, f64::min);
    TOUCH_TOLERANCE * m.size().min(1e4 * shortest)
}

/// The crossing of `a` and `b` at their pieces' pair `(k, l)`: the midpoint
/// of the nearest points of the two centrelines, and the arc lengths there.
fn crossing(a: &Drawn, b: &Drawn, (k, l): (usize, usize), contacts: usize) -> SpatialCrossing {
    let (pa, pb) = (&a.pieces[k], &b.pieces[l]);
    let (s, t) = nearest_on_segments(&pa.line, &pb.line);
    let (xa, xb) = (pa.line[0] + (pa.line[1] - pa.line[0]) * s, pb.line[0] + (pb.line[1] - pb.line[0]) * t);
    let at = nalgebra::center(&xa, &xb);
    let arc = |p: &Piece, t: f64| p.arc.map(|r| r[0] + t * (r[1] - r[0]));
    Crossing { a: a.part, b: b.part, names: Default::default(), at: at.into(), s: [arc(pa, s), arc(pb, t)], contacts }
}

fn named(m: &SpatialMechanism, mut c: SpatialCrossing) -> SpatialCrossing {
    c.names = [describe(c.a, m), describe(c.b, m)];
    c
}

/// Whether a piece's centreline passes within `tolerance` of `p`.
fn passes(piece: &Piece, p: &Point3<f64>, tolerance: f64) -> bool {
    let [a, b] = piece.line;
    let ab = b - a;
    let len = ab.norm_squared();
    let t = if len > 0.0 { ((p - a).dot(&ab) / len).clamp(0.0, 1.0) } else { 0.0 };
    (a + ab * t - p).norm() <= tolerance
}

/// The parameters $(s, t) \in [0, 1]^2$ of the nearest points of two
/// segments (Ericson, *Real-Time Collision Detection*, §5.1.9).
fn nearest_on_segments(p: &[Point3<f64>; 2], q: &[Point3<f64>; 2]) -> (f64, f64) {
    let (d1, d2, r) = (p[1] - p[0], q[1] - q[0], p[0] - q[0]);
    let (a, e, f) = (d1.norm_squared(), d2.norm_squared(), d2.dot(&r));
    if a <= f64::MIN_POSITIVE && e <= f64::MIN_POSITIVE {
        return (0.0, 0.0);
    }
    if a <= f64::MIN_POSITIVE {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(&r);
    if e <= f64::MIN_POSITIVE {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(&d2);
    let denominator = a * e - b * b;
    let mut s = if denominator > 0.0 { ((b * f - c * e) / denominator).clamp(0.0, 1.0) } else { 0.0 };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// The touching pairs of pieces grouped into contacts: two pairs are one
/// contact when each side's pieces are the same or neighbours.
fn clusters(pairs: &[(usize, usize)], a: &Drawn, b: &Drawn) -> Vec<Vec<(usize, usize)>> {
    let near = |d: &Drawn, i: usize, j: usize| i == j || d.pieces[i].ends.iter().any(|e| d.pieces[j].ends.contains(e));
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

/// A flexure's pieces that meet, other than those within twice its section's
/// half-diagonal of each other along it (which only a bend tighter than the
/// section could make meet).
fn self_crossing(d: &Drawn, tolerance: f64) -> Option<SpatialCrossing> {
    let Part::Flexure(_) = d.part else { return None };
    let mut touching = Vec::new();
    for (k, pk) in d.pieces.iter().enumerate() {
        for (l, pl) in d.pieces.iter().enumerate().skip(k + 2) {
            let (ak, al) = (pk.arc.expect("a flexure's piece"), pl.arc.expect("a flexure's piece"));
            if al[0] - ak[1] > 2.0 * d.reach + tolerance
                && !apart(&pk.lo, &pk.hi, &pl.lo, &pl.hi, tolerance)
                && within(&pk.solid, &pl.solid, tolerance)
            {
                touching.push((k, l));
            }
        }
    }
    let clusters = clusters(&touching, d, d);
    let first = *touching.first()?;
    Some(crossing(d, d, first, clusters.len()))
}

/// Each body's group: bodies joined by a closure, or by a joint other than a flexure, are one group.
fn groups(m: &SpatialMechanism) -> Vec<usize> {
    let mut g: Vec<usize> = (0..m.bodies.len()).collect();
    fn root(g: &mut [usize], mut i: usize) -> usize {
        while g[i] != i {
            g[i] = g[g[i]];
            i = g[i];
        }
        i
    }
    let closed = m.closures.iter().map(|c| {
        let [a, b] = c.bodies();
        (a, b)
    });
    let rigid = m.joints.iter().filter(|j| j.kind.flexure().is_none()).map(|j| (j.parent, j.child));
    for (a, b) in closed.chain(rigid) {
        let (ra, rb) = (root(&mut g, a), root(&mut g, b));
        g[ra.max(rb)] = ra.min(rb);
    }
    (0..g.len()).map(|i| root(&mut g, i)).collect()
}

/// The parts of `m` at `q`: flexures first, in joint order, then links.
fn drawn(m: &SpatialMechanism, q: &[f64], f: &SpatialFrames, group: &[usize], tolerance: f64) -> Vec<Drawn> {
    let mut parts = Vec::new();
    for (ji, j) in m.joints.iter().enumerate() {
        let Some(fl) = j.kind.flexure() else { continue };
        let alpha = &q[j.offset..j.offset + fl.coordinates()];
        let samples = chords(alpha) + 1;
        let Ok(sections) = shape(fl, alpha, samples) else { continue };
        let root = f.roots[ji];
        let tip = Point3::from(f.bodies[j.child].translation.vector);
        let centre = |i: usize| root * Point3::from(sections[i].position);
        // The sections' own integration ends within its error of the
        // model's tip, where the child is: moved in proportion to arc length
        // so that it ends there exactly.
        let miss = tip - centre(samples - 1);
        let (l, mut reach) = (fl.length(), 0.0f64);
        let mut solids = Vec::with_capacity(samples);
        for (i, sec) in sections.iter().enumerate() {
            let c = centre(i) + miss * (i as f64 / (samples - 1) as f64);
            let r = root.rotation.to_rotation_matrix() * nalgebra::Matrix3::from(sec.rotation).transpose();
            let axes = [r.column(0).into_owned(), r.column(1).into_owned(), r.column(2).into_owned()];
            let outline = fl.section().outline(sec.s / l);
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
            let grow = match &solid {
                Convex::Discs { radius, .. } => *radius,
                Convex::Hull(_) => 0.0,
            };
            let (lo, hi) = match &solid {
                Convex::Hull(v) => bounds(v, 0.0),
                Convex::Discs { centres, .. } => bounds(centres, grow),
            };
            let arc = Some([l * i as f64 / (samples - 1) as f64, l * (i + 1) as f64 / (samples - 1) as f64]);
            pieces.push(Piece { solid, line: [*c0, *c1], ends: [i, i + 1], arc, lo, hi });
        }
        let ends = vec![solids[0].0, tip];
        let (lo, hi) = bounds(pieces.iter().flat_map(|p| [&p.lo, &p.hi]), 0.0);
        parts.push(Drawn {
            part: Part::Flexure(ji),
            pieces,
            ends,
            groups: vec![group[j.parent], group[j.child]],
            reach,
            lo,
            hi,
        });
    }
    for b in 0..m.bodies.len() {
        let anchors = m.tendons.iter().flat_map(|t| &t.path).filter(|v| v.0 == b).map(|v| v.1);
        let points = crate::mechanism::findings::hull_points(m.attachments(b), b, anchors);
        let points: Vec<Point3<f64>> = points.iter().map(|r| f.bodies[b] * r).collect();
        let points = distinct(points, tolerance);
        let edges = hull_edges(&points, tolerance);
        if edges.is_empty() {
            continue;
        }
        let pieces: Vec<Piece> = edges
            .iter()
            .map(|&(i, k)| {
                let line = [points[i], points[k]];
                let (lo, hi) = bounds(&line, 0.0);
                Piece { solid: Convex::Hull(line.to_vec()), line, ends: [i, k], arc: None, lo, hi }
            })
            .collect();
        let mut ends = points.clone();
        // Where a body it carries by a rigid joint (a slider's carriage, a hinge's child) is held.
        let carried = m.joints.iter().filter(|j| j.parent == b && j.kind.flexure().is_none());
        ends.extend(carried.map(|j| Point3::from(f.bodies[j.child].translation.vector)));
        let (lo, hi) = bounds(&points, 0.0);
        parts.push(Drawn { part: Part::Link(b), pieces, ends, groups: vec![group[b]], reach: 0.0, lo, hi });
    }
    parts
}

/// The points, each once (within `tolerance`).
fn distinct(points: Vec<Point3<f64>>, tolerance: f64) -> Vec<Point3<f64>> {
    let mut out: Vec<Point3<f64>> = Vec::with_capacity(points.len());
    for p in points {
        if out.iter().all(|o| (o - p).norm() > tolerance) {
            out.push(p);
        }
    }
    out
}

/// The edges of the convex hull of distinct `points`, as index pairs: the
/// segment of the two farthest points if all are collinear; otherwise each
/// pair $(i, k)$ such that, seen along $p_k - p_i$, the two make a corner
/// of the hull of the others' projections (every other point within a
/// half-plane of it, strictly): for flat points, the sides of their
/// polygon; for others, the edges of their polytope, not its faces'
/// diagonals.
fn hull_edges(points: &[Point3<f64>], tolerance: f64) -> Vec<(usize, usize)> {
    let n = points.len();
    if n < 2 {
        return Vec::new();
    }
    let mut edges = Vec::new();
    let mut collinear = true;
    let (mut far, mut longest) = ((0, 1), 0.0);
    for i in 0..n {
        for k in i + 1..n {
            let e = points[k] - points[i];
            let len = e.norm();
            if len > longest {
                (far, longest) = ((i, k), len);
            }
            let axis = e / len;
            let (u, v) = plane(&axis);
            let mut angles = Vec::with_capacity(n);
            let mut beyond = false;
            for (j, p) in points.iter().enumerate() {
                if j == i || j == k {
                    continue;
                }
                let r = p - points[i];
                let along = r.dot(&axis);
                let across = r - axis * along;
                if across.norm() <= tolerance {
                    // On the line: outside the segment, the segment is not a whole edge.
                    beyond |= along < 0.0 || along > len;
                } else {
                    angles.push(across.dot(&v).atan2(across.dot(&u)));
                }
            }
            if !angles.is_empty() {
                collinear = false;
            }
            if beyond {
                continue;
            }
            angles.sort_by(f64::total_cmp);
            let gap = angles
                .windows(2)
                .map(|w| w[1] - w[0])
                .chain(angles.first().zip(angles.last()).map(|(a, b)| a + std::f64::consts::TAU - b))
                .fold(0.0, f64::max);
            if !angles.is_empty() && gap > std::f64::consts::PI + 1e-9 {
                edges.push((i, k));
            }
        }
    }
    if collinear { vec![far] } else { edges }
}

/// Two unit vectors completing `axis` to an orthonormal basis.
fn plane(axis: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let helper = if axis.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
    let u = axis.cross(&helper).normalize();
    (u, axis.cross(&u))
}

/// [`crossings`] at each of a series of shapes (a sweep's rows, a
/// simulation's samples): (index in the series, its crossings), for the
/// shapes that have any.
pub fn crossings_along<'a>(
    m: &SpatialMechanism,
    shapes: impl IntoIterator<Item = &'a [f64]>,
) -> Vec<(usize, Vec<SpatialCrossing>)> {
    shapes.into_iter().map(|q| crossings(m, q)).enumerate().filter(|(_, c)| !c.is_empty()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: a unit cube has 12 edges (its faces' 6 diagonals are not edges).
    #[test]
    fn a_cube_has_twelve_edges() {
        let v: Vec<Point3<f64>> =
            (0..8).map(|i| Point3::new((i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2 & 1) as f64)).collect();
        let e = hull_edges(&v, 1e-9);
        assert_eq!(e.len(), 12);
        assert!(e.iter().all(|&(i, k)| ((v[i] - v[k]).norm() - 1.0).abs() < 1e-15));
    }

    // Reference: a flat square with its centre has its 4 sides as edges;
    // three collinear points, the one segment of the outer two.
    #[test]
    fn flat_and_collinear_points() {
        let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]].map(|[x, y]| Point3::new(x, y, 0.3 * x));
        let e = hull_edges(&sq, 1e-9);
        assert_eq!(e, [(0, 1), (0, 3), (1, 2), (2, 3)]);
        let line = [0.0, 2.0, 1.0].map(|x| Point3::new(x, 2.0 * x, -x));
        assert_eq!(hull_edges(&line, 1e-9), [(0, 1)]);
    }

    // Reference: the nearest points of the lines x-axis and (t, 1, 1)… (the closed form s = t = ½).
    #[test]
    fn nearest_points_of_crossed_segments() {
        let p = [Point3::new(0.0, 0.0, 0.0), Point3::new(2.0, 0.0, 0.0)];
        let q = [Point3::new(1.0, -1.0, 1.0), Point3::new(1.0, 1.0, 1.0)];
        assert_eq!(nearest_on_segments(&p, &q), (0.5, 0.5));
    }
}
