//! Where two geoms meet edge across edge. In space two of box, capsule and
//! cylinder may touch where an edge of one crosses an edge of the other
//! and no corner touches. Each pair of their edges (a box's twelve, a
//! capsule's segment, a cylinder's side as its axis rounded by its radius) is a [`super::corner::Corner`] whose point
//! moves: the point $x_A$ of the one edge nearest the other's line,
//! against the plane through the other's nearest point $x_B$, across both
//! edges. With $a, b$ the edges' unit directions (world) and
//! $\hat n = \sigma\thinspace(a\times b)/\lvert a\times b\rvert$ ($\sigma = \pm 1$,
//! out of the geom touched),
//! $$g = \hat n\cdot(x_A - x_B) - r_A - r_B,$$
//! the lines' signed distance less the radii. It holds for any two points
//! of the lines, so its derivatives are those of two material points and
//! of $\hat n$, which turns as the two bodies turn apart ([`Turn`]).
//!
//! The pair applies where the lines' nearest points lie within both
//! edges (a cylinder's axis by more than the edge's depth in its side, else
//! its lid is nearer), $\hat n$ lies between the two faces that meet at a box's edge
//! (and $-\hat n$ at the other's), and the lines are apart or $x_A$ is inside
//! the geom touched (two edges at the far sides of two boxes are no
//! touch), or, where $\hat n$ is a face's normal of each (two faces flush,
//! neither point deep in the other), the two faces overlap next to the
//! crossing inside both. Elsewhere its gap is the two segments' distance less the radii,
//! plus how far the lines' nearest points lie beyond the edges' ends, and
//! not less than a cylinder's own gap at the other edge's point (its axis
//! rounded is a capsule, less than its lid past the ends): continuous
//! where it begins to apply, and above the gap of the corner that touches
//! there, which so takes the touch; in motion a pair that does not apply
//! is never held. A touching pair keeps
//! the lines' gap past where it stops applying (`held`), so its gap stays
//! smooth up to where it is let go ([`Crossing::margin`] below zero); where
//! the crossing ran off an edge's end ([`End`]), the corner there takes the
//! touch at that instant (`super::corner::ran_off`).

use super::{Geom, GeomShape, Touch, array, vector};
use crate::mechanism::Dimension;

/// An edge of a geom: a box's, between two faces, a capsule's segment, or
/// a cylinder's axis (its side between the rims), in the shape's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Ridge {
    /// One end (m).
    pub from: [f64; 3],
    /// The other end (m).
    pub to: [f64; 3],
    /// Its radius (m): 0 at a box's edge.
    pub radius: f64,
    /// The outward signs of the two faces that meet at it, by axis (0 on
    /// its own axis; all 0 for a capsule, round every way across it).
    faces: [f64; 3],
}

/// How many edges a shape has ([`ridge`]): a box's twelve, a capsule's
/// segment or a cylinder's axis, in space; none in the plane, where two
/// outlines are nearest at a corner of one of them.
pub(crate) fn ridges<D: Dimension>(s: &GeomShape<D>) -> usize {
    match s {
        _ if D::POINT_DIM != 3 => 0,
        GeomShape::Box { .. } => 12,
        GeomShape::Cylinder { .. } => 1,
        GeomShape::Capsule { half_length, .. } if *half_length > 0.0 => 1,
        _ => 0,
    }
}

/// Edge `k` of a shape (below [`ridges`]): a box's along axis `k / 4`,
/// its other two axes' signs from `k % 4`; a capsule's segment; a
/// cylinder's axis (its side, between the rims).
pub(crate) fn ridge<D: Dimension>(s: &GeomShape<D>, k: usize) -> Ridge {
    match s {
        GeomShape::Box { half_extents } => {
            let h = [half_extents[0], half_extents[1], half_extents[2]];
            let (axis, signs) = (k / 4, k % 4);
            let (j, l) = ((axis + 1) % 3, (axis + 2) % 3);
            let mut faces = [0.0; 3];
            faces[j] = if signs & 1 == 0 { 1.0 } else { -1.0 };
            faces[l] = if signs & 2 == 0 { 1.0 } else { -1.0 };
            let mut from = [0.0; 3];
            (from[j], from[l], from[axis]) = (faces[j] * h[j], faces[l] * h[l], -h[axis]);
            let mut to = from;
            to[axis] = h[axis];
            Ridge { from, to, radius: 0.0, faces }
        }
        GeomShape::Cylinder { half_length, radius } => {
            Ridge { from: [0.0, 0.0, -half_length], to: [0.0, 0.0, *half_length], radius: *radius, faces: [0.0; 3] }
        }
        GeomShape::Capsule { half_length, radius } => {
            Ridge { from: [-half_length, 0.0, 0.0], to: [*half_length, 0.0, 0.0], radius: *radius, faces: [0.0; 3] }
        }
        _ => unreachable!("a shape without edges has no edge {k}"),
    }
}

/// How the normal of two crossing edges turns: their unit directions $a$
/// (the corner's geom's) and $b$ (the geom touched's) in the world, $\sigma$,
/// and the lines' signed distance $\hat n\cdot(x_A - x_B)$ (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Turn {
    pub a: [f64; 3],
    pub b: [f64; 3],
    pub sign: f64,
    pub distance: f64,
}

/// An edge pair placed: the point of the one edge ($x_A$, in its geom's
/// body's frame), the plane it is held against (a geom of the other's
/// body), and how far it is within where it applies.
pub(crate) struct Crossing<D: Touch> {
    /// $x_A$ in the frame of the body of the corner's geom (m).
    pub centre: D::Vector,
    /// The plane through $x_B$ (shifted out by the other's radius) across both edges.
    pub surface: Geom<D>,
    /// How far the nearest points lie within the edges (m), or, where
    /// $\hat n$ lies beyond the faces' normals by more than rounding, how
    /// far (an angle times the shorter edge, below zero), past rounding:
    /// below zero the pair no longer applies, and a touching one is let go.
    /// ($\hat n$ on the faces' bound, an edge flush on a face, is within.)
    pub margin: f64,
    /// Where the pair applies, how its normal turns.
    pub turn: Option<Turn>,
    /// Of crossing lines, the edges' end nearest where they cross.
    pub end: Option<End>,
}

impl<D: Touch> Crossing<D> {
    /// Whether the pair applies where it was placed ([`Crossing::margin`]
    /// not below zero): a touching pair is let go, and an open one is not
    /// touched, where it does not (a corner touches there).
    pub fn applies(&self) -> bool {
        self.margin >= 0.0
    }
}

/// The end of two crossing edges nearest where their lines cross: where a
/// corner takes the touch when the crossing runs off it, and gives it
/// back when the crossing comes back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct End {
    /// Whether that edge is the corner's geom's (`round`'s).
    pub of_round: bool,
    /// Its surface point at that end, toward the other, in its shape's frame (m).
    pub point: [f64; 3],
    /// How far the lines' nearest point lies within the edge from that end
    /// (m; below zero beyond it).
    pub within: f64,
    /// The edge's length (m).
    pub length: f64,
}

/// Edge `edges.0` of `round` against edge `edges.1` of `flat`, bodies at
/// `bodies` (see the module docs). A pair that touches (`held`) keeps the
/// lines' gap wherever they cross, so that its gap is smooth past where it
/// stops applying, up to where it is let go.
pub(crate) fn crossing<D: Touch>(
    round: &Geom<D>,
    flat: &Geom<D>,
    edges: (usize, usize),
    bodies: &[D::Pose],
    held: bool,
) -> Crossing<D> {
    let (ra, rb) = (ridge(&round.shape, edges.0), ridge(&flat.shape, edges.1));
    let (fa, fb) = (D::compose(&bodies[round.body], &round.frame), D::compose(&bodies[flat.body], &flat.frame));
    let (a0, a1, b0, b1) = (at::<D>(&fa, &ra.from), at::<D>(&fa, &ra.to), at::<D>(&fb, &rb.from), at::<D>(&fb, &rb.to));
    let (u, v, w0) = (sub(a1, a0), sub(b1, b0), sub(a0, b0));
    let (aa, bb, cc, dd, ee) = (dot(u, u), dot(u, v), dot(v, v), dot(u, w0), dot(v, w0));
    let (la, lb) = (aa.sqrt(), cc.sqrt());
    let den = aa * cc - bb * bb;
    let across = den > 1e-12 * aa * cc;
    let (ta, tb) = if across { ((bb * ee - cc * dd) / den, (aa * ee - bb * dd) / den) } else { (0.0, ee / cc) };
    // The least of n's components along the faces' outward axes (+∞ round every way).
    let cone = |frame: &D::Pose, faces: [f64; 3], n: [f64; 3]| {
        let local = array::<D>(&D::rotate(&D::inverse(frame), &vector::<D>(&n)));
        (0..3).filter(|&k| faces[k] != 0.0).map(|k| local[k] * faces[k]).fold(f64::INFINITY, f64::min)
    };
    let within = [ta * la, (1.0 - ta) * la, tb * lb, (1.0 - tb) * lb].into_iter().fold(f64::INFINITY, f64::min);
    let (mut margin, mut end) = (-(la + lb), None);
    if across {
        let w = cross(u, v);
        let unit = scale(w, 1.0 / dot(w, w).sqrt());
        let (xa, xb) = (add(a0, scale(u, ta)), add(b0, scale(v, tb)));
        let faced = |s: f64| cone(&fb, rb.faces, scale(unit, s)).min(cone(&fa, ra.faces, scale(unit, -s)));
        let sign = match faced(1.0).is_finite() {
            true if faced(1.0) >= faced(-1.0) => 1.0,
            true => -1.0,
            false if dot(sub(xa, xb), unit) >= 0.0 => 1.0,
            false => -1.0,
        };
        let n = scale(unit, sign);
        let distance = dot(n, sub(xa, xb));
        // Within the edges and the faces' normals to rounding (an edge along a face, a crossing at an end).
        let (tolerance, tiny) = (1e-9 * (la + lb), 1e-12 * (la + lb));
        // An edge lying flush on a face (n̂ on its faces' bound to rounding)
        // lies within: there the bound stays at zero as long as it lies so
        // (a box's edge on a rail's end face, the lid turning about it), and
        // how far the edges leave is what measures the margin.
        let facing = faced(sign) * la.min(lb);
        // A cylinder's side is the surface an edge meets only while its
        // depth in the side is less than its way along the axis to the lid:
        // past that, the lid is nearer (a box's edge on a can's lid, over
        // its axis, read 28 mm deep in the side), and a rim's point takes it.
        let depth = (ra.radius + rb.radius - distance).max(0.0);
        let lid = |g: &Geom<D>, t: f64, l: f64| match g.shape {
            GeomShape::Cylinder { .. } => (0.5 - (t - 0.5).abs()) * l - depth,
            _ => f64::INFINITY,
        };
        let within = within.min(lid(round, ta, la)).min(lid(flat, tb, lb));
        margin = within.min(if facing >= -tolerance { f64::INFINITY } else { facing }) + tolerance;
        // Crossed by δ, an edge's nearest point lies δ·c inside the other geom,
        // c its face normals' least component along n̂ (1 round every way):
        // at least half of that on a side where c > 0. Not so for two boxes
        // that only rest on each other (a bottom edge across a side edge,
        // n̂ along a face of each), nor for far sides.
        let inside = distance >= -tiny || {
            let depth = |g: &Geom<D>, p: [f64; 3]| -g.gap(&bodies[g.body], &point::<D>(p), 0.0).0;
            let (c_flat, c_round) = (cone(&fb, rb.faces, n).min(1.0), cone(&fa, ra.faces, scale(n, -1.0)).min(1.0));
            let deep = |c: f64, d: f64| c > 1e-9 && d >= -0.5 * distance * c;
            // At the edges' own points (within them to rounding, not beyond).
            let (ya, yb) = (add(a0, scale(u, ta.clamp(0.0, 1.0))), add(b0, scale(v, tb.clamp(0.0, 1.0))));
            // Two faces flush (n̂ a face's normal of each): each edge lies
            // along the other's face, no depth at either point, yet where
            // the two faces overlap next to where the lines cross, they are
            // inside each other between the faces' planes: a box on a box
            // turned 45° (its corners all outside the other), or of the
            // same width (corners on the other's edges). Not so where a
            // bottom edge crosses a side edge's top, resting on it, nor
            // where the faces' planes cross by more than the solids' depth
            // behind them (a top face above another's bottom face): the
            // point halfway between the planes, as far into the faces'
            // overlap, is inside both.
            let flush = c_flat <= 1e-9 && c_round <= 1e-9 && {
                let bounds = [(&ra, &fa, ta, la, scale(n, -1.0)), (&rb, &fb, tb, lb, n)];
                faces_meet::<D>(&bounds, n, tolerance).is_some_and(|d| {
                    let p = add(scale(add(xa, xb), 0.5), scale(d, -distance));
                    depth(flat, p) > 0.0 && depth(round, p) > 0.0
                })
            };
            flush || deep(c_flat, depth(flat, ya)) || deep(c_round, depth(round, yb))
        };
        // The end nearest the crossing, its surface point toward the other.
        let near = |r: &Ridge, t: f64, l: f64, frame: &D::Pose, of_round: bool| {
            let toward = if of_round { -1.0 } else { 1.0 };
            let n_local = array::<D>(&D::rotate(&D::inverse(frame), &vector::<D>(&scale(n, toward))));
            let point = add(if t < 0.5 { r.from } else { r.to }, scale(n_local, r.radius));
            End { of_round, point, within: (0.5 - (t - 0.5).abs()) * l, length: l }
        };
        let ends = [near(&ra, ta, la, &fa, true), near(&rb, tb, lb, &fb, false)];
        end = ends.into_iter().min_by(|x, y| x.within.total_cmp(&y.within));
        if held || (margin >= 0.0 && inside) {
            let turn = Turn { a: scale(u, 1.0 / la), b: scale(v, 1.0 / lb), sign, distance };
            let surface = plane(flat, &bodies[flat.body], add(xb, scale(n, rb.radius)), n);
            let centre = local::<D>(&bodies[round.body], xa);
            return Crossing { centre, surface, margin, turn: Some(turn), end };
        }
    }
    // The segments' nearest points (Ericson, Real-Time Collision Detection, 5.1.9).
    let mut s = if across { ta.clamp(0.0, 1.0) } else { 0.0 };
    let mut t = (bb * s + ee) / cc;
    if t < 0.0 {
        (t, s) = (0.0, (-dd / aa).clamp(0.0, 1.0));
    } else if t > 1.0 {
        (t, s) = (1.0, ((bb - dd) / aa).clamp(0.0, 1.0));
    }
    let (xa, xb) = (add(a0, scale(u, s)), add(b0, scale(v, t)));
    let r = sub(xa, xb);
    let size = dot(r, r).sqrt();
    let n = if size > 0.0 { scale(r, 1.0 / size) } else { [0.0, 0.0, 1.0] };
    let mut beyond = if across { (ta - s).abs() * la + (tb - t).abs() * lb } else { 0.0 };
    // A cylinder's axis rounded by its radius is a capsule: past the axis's
    // ends it reads less than the flat faces do (a box over a can's lid
    // read it touching 47 mm up). Not less than the cylinder's own gap
    // at the other edge's point, which is as much where the pair applies.
    let own = |g: &Geom<D>, p: [f64; 3], r: f64| match g.shape {
        GeomShape::Cylinder { .. } => g.gap(&bodies[g.body], &point::<D>(p), 0.0).0 - r,
        _ => f64::NEG_INFINITY,
    };
    let least = own(flat, xa, ra.radius).max(own(round, xb, rb.radius));
    beyond = beyond.max(least - (size - ra.radius - rb.radius));
    let surface = plane(flat, &bodies[flat.body], add(xb, scale(n, rb.radius - beyond)), n);
    Crossing { centre: local::<D>(&bodies[round.body], xa), surface, margin, turn: None, end }
}

/// A box edge whose face lies flush on another's ([`faces_meet`]): the
/// edge, its geom's frame (world), the lines' nearest point's parameter
/// along it, its length (m), and the flush face's outward normal (world).
type FlushEdge<'a, P> = (&'a Ridge, &'a P, f64, f64, [f64; 3]);

/// Where the faces that lie flush across two crossing box edges overlap
/// next to where the lines cross: a unit direction across `n` (world)
/// that points strictly into both faces, or `None`. Each edge bounds its
/// face there by the edge's other face, and, where the crossing is at the
/// edge's end (to `tolerance`, m), by the next edge too.
fn faces_meet<D: Touch>(edges: &[FlushEdge<D::Pose>; 2], n: [f64; 3], tolerance: f64) -> Option<[f64; 3]> {
    let mut bounds: Vec<[f64; 3]> = Vec::new();
    for &(r, frame, t, length, outward) in edges {
        let world = |k: usize, sign: f64| {
            let mut e = [0.0; 3];
            e[k] = sign;
            array::<D>(&D::rotate(frame, &vector::<D>(&e)))
        };
        let local = array::<D>(&D::rotate(&D::inverse(frame), &vector::<D>(&outward)));
        let faces: Vec<usize> = (0..3).filter(|&k| r.faces[k] != 0.0).collect();
        let axis = (0..3).find(|&k| r.faces[k] == 0.0)?;
        let [a, b] = faces[..] else { return None };
        // The edge's other face: the one the flush face's normal does not point along.
        let other = if local[a] * r.faces[a] >= local[b] * r.faces[b] { b } else { a };
        bounds.push(world(other, r.faces[other]));
        if t * length < tolerance {
            bounds.push(world(axis, -1.0));
        } else if (1.0 - t) * length < tolerance {
            bounds.push(world(axis, 1.0));
        }
    }
    // The open cone of directions within every bound is empty or a wedge
    // between two bounds' edges (a half-plane: against one bound).
    let rays: Vec<[f64; 3]> = bounds.iter().flat_map(|c| [cross(n, *c), cross(*c, n), scale(*c, -1.0)]).collect();
    let within = |d: [f64; 3]| {
        let size = dot(d, d).sqrt();
        size > 1e-12 && bounds.iter().all(|c| dot(*c, d) < -1e-9 * size)
    };
    let pairs = rays.iter().flat_map(|&x| rays.iter().map(move |&y| add(x, y)));
    rays.iter().copied().chain(pairs).find(|&d| within(d)).map(|d| scale(d, 1.0 / dot(d, d).sqrt()))
}

/// The plane through `origin` with outward `normal` (both world), fixed in `flat`'s body at `body`.
fn plane<D: Touch>(flat: &Geom<D>, body: &D::Pose, origin: [f64; 3], normal: [f64; 3]) -> Geom<D> {
    let normal = D::rotate(&D::inverse(body), &vector::<D>(&normal));
    let at = D::at(&D::moved(&D::origin(&D::identity()), &local::<D>(body, origin), 1.0));
    flat.stand_in(at, GeomShape::Plane { normal })
}

/// The world point of `p` (the frame `frame`'s).
fn at<D: Touch>(frame: &D::Pose, p: &[f64; 3]) -> [f64; 3] {
    array::<D>(&D::position(&D::act(frame, &point::<D>(*p))))
}

/// The point at `p`.
fn point<D: Touch>(p: [f64; 3]) -> D::Point {
    D::moved(&D::origin(&D::identity()), &vector::<D>(&p), 1.0)
}

/// The world point `p` in the frame `frame`.
fn local<D: Touch>(frame: &D::Pose, p: [f64; 3]) -> D::Vector {
    D::position(&D::act(&D::inverse(frame), &point::<D>(p)))
}

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(crate) fn scale(a: [f64; 3], k: f64) -> [f64; 3] {
    [a[0] * k, a[1] * k, a[2] * k]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::space::Spatial;
    use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

    /// A box's edge flush on a rail's end face: the lid of
    /// `tests/contact_corner.rs` (a box of half extents 10, 20, 5 mm turned
    /// 45° about y, 80 mm along the lid) on its carriage at
    /// $x_c = 0.1 + 0.0075\sqrt2$, where its edge between its $-x'$ and $-z'$
    /// faces lies in the rail's end face $x = 0.1$, the lid turned
    /// $\theta = -0.36$ about x. The edges' normal is the end face's, on the
    /// rail edge's faces' bound, as long as the lid turns. The margin is how
    /// far the crossing lies within the rail's top edge of the end face
    /// ($z = -0.03$, $y \in [0.088, 0.092]$), from the closed form: the box's
    /// edge, $(y_l, 0.0025\sqrt2)$ in the lid's frame, meets $z = -0.03$ at
    /// $y_l = (-0.03 - 0.0025\sqrt2\cos\theta)/\sin\theta$, so at
    /// $y = y_l\cos\theta - 0.0025\sqrt2\sin\theta$. To 1e-12 m, past the
    /// rounding allowed (1e-9 of the two edges' lengths). Reading the bound
    /// instead, it was that rounding alone (4.4e-11 m): inside the motion's
    /// band all along, so the run let go and touched again at every step.
    #[test]
    fn an_edge_flush_on_a_face_is_within_by_how_far_it_crosses_the_faces_edge() {
        let rail = Geom::<Spatial>::new(
            "rail",
            0,
            Isometry3::translation(0.0, 0.09, -0.04),
            GeomShape::Box { half_extents: Vector3::new(0.1, 0.002, 0.01) },
        );
        let turned = Isometry3::from_parts(
            Translation3::new(0.0, 0.08, 0.0),
            UnitQuaternion::from_euler_angles(0.0, std::f64::consts::FRAC_PI_4, 0.0),
        );
        let block =
            Geom::<Spatial>::new("block", 1, turned, GeomShape::Box { half_extents: Vector3::new(0.01, 0.02, 0.005) });
        let theta = -0.36f64;
        let (half, x_c) = (0.5f64.sqrt(), 0.1 + 0.015 * 0.5f64.sqrt());
        let lid =
            Isometry3::from_parts(Translation3::new(x_c, 0.0, 0.0), UnitQuaternion::from_euler_angles(theta, 0.0, 0.0));
        // The rail's edge 4 (along y, its +z and +x faces) against the box's edge 7 (along y', its -x' and -z' faces).
        let k = crossing(&rail, &block, (4, 7), &[Isometry3::identity(), lid], true);
        let z_l = 0.005 * half;
        let y_l = (-0.03 - z_l * theta.cos()) / theta.sin();
        let y = y_l * theta.cos() - z_l * theta.sin();
        let within = (y - 0.088).min(0.092 - y);
        assert!(within > 1e-3, "{y}");
        let rounding = 1e-9 * (0.004 + 0.04);
        assert!((k.margin - (within + rounding)).abs() < 1e-12, "{} against {}", k.margin, within + rounding);
        assert!(k.turn.is_some_and(|t| t.distance.abs() < 1e-12), "the edge lies on the face");
    }
}
