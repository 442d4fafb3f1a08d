//! Convex solids in space given by their support mappings, and whether two
//! of them come within a distance of each other, by the
//! Gilbert–Johnson–Keerthi (GJK) iteration: the point of the Minkowski
//! difference $A - B$ nearest the origin is approached through simplices of
//! its support points
//! $$w = s_A(-v) - s_B(v),\qquad s_A(d) = \arg\max_{a\in A} d\cdot a,$$
//! and $\lvert v\rvert$ is the distance once $\lvert v\rvert^2 - v\cdot w$ is
//! negligible. At every step $v\cdot w/\lvert v\rvert$ is a lower bound of
//! the distance and $\lvert v\rvert$ an upper one, so [`within`] stops as
//! soon as either settles the question. Besides: the nearest points of two
//! segments ([`nearest_on_segments`]) and the edges of the hull of a few points
//! ([`hull_edges`]), which make a link in space.

use nalgebra::{Point3, Vector3};

/// The most GJK iterations [`within`] takes (each adds a support point; on
/// polytopes of a few vertices it ends in a handful).
pub const MAX_ITERATIONS: usize = 64;

/// A convex solid: the hull of a few points, or of two discs (a round
/// section at each end of a piece of rod).
#[derive(Debug, Clone, PartialEq)]
pub enum Convex {
    /// The convex hull of these points (a point, a segment, a box, …).
    Hull(Vec<Point3<f64>>),
    /// The convex hull of two discs of one radius, each a centre and the unit normal of its plane.
    Discs { centres: [Point3<f64>; 2], normals: [Vector3<f64>; 2], radius: f64 },
}

impl Convex {
    /// The point of the solid farthest along `d`, $s(d)$.
    ///
    /// For a disc of centre $c$, normal $n$ and radius $r$:
    /// $s(d) = c + r\thinspace d_{\perp}/\lvert d_{\perp}\rvert$ with
    /// $d_{\perp} = d - (d\cdot n)n$ ($c$ itself when $d \parallel n$).
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::findings::Convex;
    /// use nalgebra::{Point3, Vector3};
    /// let rod = Convex::Discs {
    ///     centres: [Point3::origin(), Point3::new(1.0, 0.0, 0.0)],
    ///     normals: [Vector3::x(), Vector3::x()],
    ///     radius: 0.1,
    /// };
    /// assert_eq!(rod.support(&Vector3::new(1.0, 1.0, 0.0)), Point3::new(1.0, 0.1, 0.0));
    /// ```
    pub fn support(&self, d: &Vector3<f64>) -> Point3<f64> {
        match self {
            Convex::Hull(points) => {
                let mut best = points[0];
                let mut reach = d.dot(&best.coords);
                for p in &points[1..] {
                    let r = d.dot(&p.coords);
                    if r > reach {
                        (best, reach) = (*p, r);
                    }
                }
                best
            }
            Convex::Discs { centres, normals, radius } => {
                let rim = |k: usize| {
                    let across = d - normals[k] * d.dot(&normals[k]);
                    let norm = across.norm();
                    if norm > 0.0 { centres[k] + across * (*radius / norm) } else { centres[k] }
                };
                let (a, b) = (rim(0), rim(1));
                if d.dot(&b.coords) > d.dot(&a.coords) { b } else { a }
            }
        }
    }

    /// A point inside the solid (where the iteration starts).
    fn inner(&self) -> Point3<f64> {
        match self {
            Convex::Hull(points) => points[0],
            Convex::Discs { centres, .. } => centres[0],
        }
    }
}

/// Whether the solids `a` and `b` come within `gap` (m) of each other
/// (touch or overlap when `gap` is 0), by the GJK iteration of the module
/// docs, at most [`MAX_ITERATIONS`] steps. It stops when the lower bound
/// $v\cdot w/\lvert v\rvert$ exceeds `gap` (apart), when $\lvert v\rvert$
/// falls to `gap` or the simplex holds the origin (within), or when a step
/// no longer brings $v$ closer than a relative $10^{-12}$ (the distance is
/// then $\lvert v\rvert$). After the cap, $\lvert v\rvert$, an upper bound,
/// decides, so that a near touch is not missed.
///
/// # Example
/// ```
/// use flexure::mechanism::findings::{Convex, within};
/// use nalgebra::Point3;
/// let seg = |a: [f64; 3], b: [f64; 3]| Convex::Hull(vec![Point3::from(a), Point3::from(b)]);
/// // Two skew lines 1 apart: the common perpendicular along z.
/// let (p, q) = (seg([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]), seg([0.0, -1.0, 1.0], [0.0, 1.0, 1.0]));
/// assert!(within(&p, &q, 1.0 + 1e-9) && !within(&p, &q, 1.0 - 1e-9));
/// ```
pub fn within(a: &Convex, b: &Convex, gap: f64) -> bool {
    let support = |d: &Vector3<f64>| a.support(&-d) - b.support(d);
    let mut v = a.inner() - b.inner();
    let mut simplex: Vec<Vector3<f64>> = Vec::with_capacity(4);
    for _ in 0..MAX_ITERATIONS {
        let vv = v.norm_squared();
        if vv <= gap * gap {
            return true;
        }
        let w = support(&v);
        let vw = v.dot(&w);
        if vw > 0.0 && vw * vw > gap * gap * vv {
            return false;
        }
        if vv - vw <= 1e-12 * vv {
            return vv.sqrt() <= gap;
        }
        simplex.push(w);
        match nearest(&simplex) {
            None => return true,
            Some((point, kept)) => {
                simplex = kept;
                v = point;
            }
        }
    }
    v.norm() <= gap
}

/// The point of the simplex's hull (1 to 4 points) nearest the origin, and
/// the fewest of its points whose hull holds it; `None` when the origin is
/// inside a tetrahedron.
fn nearest(s: &[Vector3<f64>]) -> Option<(Vector3<f64>, Vec<Vector3<f64>>)> {
    match s.len() {
        1 => Some((s[0], s.to_vec())),
        2 => Some(segment(s[0], s[1])),
        3 => Some(triangle(s[0], s[1], s[2])),
        _ => tetrahedron(s[0], s[1], s[2], s[3]),
    }
}

/// The nearest point of segment $ab$ to the origin.
fn segment(a: Vector3<f64>, b: Vector3<f64>) -> (Vector3<f64>, Vec<Vector3<f64>>) {
    let ab = b - a;
    let t = -a.dot(&ab);
    if t <= 0.0 {
        return (a, vec![a]);
    }
    let len = ab.norm_squared();
    if t >= len {
        return (b, vec![b]);
    }
    (a + ab * (t / len), vec![a, b])
}

/// The nearest point of triangle $abc$ to the origin, by its Voronoi
/// regions (Ericson, *Real-Time Collision Detection*, §5.1.5).
fn triangle(a: Vector3<f64>, b: Vector3<f64>, c: Vector3<f64>) -> (Vector3<f64>, Vec<Vector3<f64>>) {
    let (ab, ac, ap) = (b - a, c - a, -a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, vec![a]);
    }
    let bp = -b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (b, vec![b]);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (a + ab * (d1 / (d1 - d3)), vec![a, b]);
    }
    let cp = -c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (c, vec![c]);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (a + ac * (d2 / (d2 - d6)), vec![a, c]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))), vec![b, c]);
    }
    let denominator = va + vb + vc;
    if denominator.abs() <= f64::MIN_POSITIVE {
        // A degenerate (flat) triangle: the nearest of its edges.
        return [segment(a, b), segment(a, c), segment(b, c)]
            .into_iter()
            .min_by(|x, y| x.0.norm_squared().total_cmp(&y.0.norm_squared()))
            .expect("three edges");
    }
    let (v, w) = (vb / denominator, vc / denominator);
    (a + ab * v + ac * w, vec![a, b, c])
}

/// The nearest point of tetrahedron $abcd$ to the origin: of the faces the
/// origin lies outside of, the nearest point; `None` inside. A flat
/// tetrahedron (volume below $10^{-12}$ of its edges' cube) is the union of
/// its faces.
fn tetrahedron(
    a: Vector3<f64>,
    b: Vector3<f64>,
    c: Vector3<f64>,
    d: Vector3<f64>,
) -> Option<(Vector3<f64>, Vec<Vector3<f64>>)> {
    let volume = (b - a).cross(&(c - a)).dot(&(d - a));
    let scale = [b - a, c - a, d - a].iter().map(|e| e.norm()).fold(0.0, f64::max);
    let flat = volume.abs() <= 1e-12 * scale * scale * scale;
    // Face (p, q, r) with the opposite vertex o: the origin is outside when on the other side from o.
    let outside = |p: Vector3<f64>, q: Vector3<f64>, r: Vector3<f64>, o: Vector3<f64>| {
        let n = (q - p).cross(&(r - p));
        flat || n.dot(&-p) * n.dot(&(o - p)) < 0.0
    };
    let faces = [(a, b, c, d), (a, c, d, b), (a, d, b, c), (b, d, c, a)];
    faces
        .iter()
        .filter(|f| outside(f.0, f.1, f.2, f.3))
        .map(|f| triangle(f.0, f.1, f.2))
        .min_by(|x, y| x.0.norm_squared().total_cmp(&y.0.norm_squared()))
}

/// The parameters $(s, t) \in [0, 1]^2$ of the nearest points of two
/// segments (Ericson, *Real-Time Collision Detection*, §5.1.9).
pub(super) fn nearest_on_segments(p: &[Point3<f64>; 2], q: &[Point3<f64>; 2]) -> (f64, f64) {
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

/// The points, each once (within `tolerance`).
pub(super) fn distinct(points: Vec<Point3<f64>>, tolerance: f64) -> Vec<Point3<f64>> {
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
pub(super) fn hull_edges(points: &[Point3<f64>], tolerance: f64) -> Vec<(usize, usize)> {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(at: [f64; 3], half: f64) -> Convex {
        let mut v = Vec::new();
        for i in 0..8 {
            let s = |k: usize| if i >> k & 1 == 1 { half } else { -half };
            v.push(Point3::new(at[0] + s(0), at[1] + s(1), at[2] + s(2)));
        }
        Convex::Hull(v)
    }

    // Reference: two axis-aligned cubes' distance is the Euclidean norm of the per-axis gaps.
    #[test]
    fn cubes_apart_by_their_axis_gaps() {
        let a = cube([0.0, 0.0, 0.0], 0.5);
        let b = cube([2.0, 1.5, -0.5], 0.5);
        let exact = (1.0f64 * 1.0 + 0.5 * 0.5).sqrt();
        assert!(within(&a, &b, exact * (1.0 + 1e-9)));
        assert!(!within(&a, &b, exact * (1.0 - 1e-9)));
        assert!(within(&a, &cube([0.9, 0.3, 0.2], 0.5), 0.0));
    }

    // Reference: two parallel rods of radius r with axes D apart are D − 2r apart.
    #[test]
    fn parallel_round_rods() {
        let rod = |y: f64| Convex::Discs {
            centres: [Point3::new(0.0, y, 0.0), Point3::new(1.0, y, 0.0)],
            normals: [Vector3::x(), Vector3::x()],
            radius: 0.1,
        };
        assert!(within(&rod(0.0), &rod(0.3), 0.1 + 1e-9));
        assert!(!within(&rod(0.0), &rod(0.3), 0.1 - 1e-6));
        assert!(within(&rod(0.0), &rod(0.15), 0.0));
    }

    // Reference: a segment through a cube's interior meets it; one passing
    // a corner at distance d along the diagonal's normal is d away.
    #[test]
    fn segment_and_cube() {
        let c = cube([0.0, 0.0, 0.0], 0.5);
        let through = Convex::Hull(vec![Point3::new(-2.0, 0.1, 0.2), Point3::new(2.0, -0.1, 0.0)]);
        assert!(within(&c, &through, 0.0));
        let d = 0.3;
        let past = Convex::Hull(vec![Point3::new(0.5 + d, 0.5, -3.0), Point3::new(0.5 + d, 0.5, 3.0)]);
        assert!(within(&c, &past, d + 1e-9) && !within(&c, &past, d - 1e-9));
    }

    // Reference: the closed form of the nearest points of two segments in
    // random positions (the minimum over a fine grid of both parameters,
    // refined), against GJK's decision just above and below it.
    #[test]
    fn random_segments_against_a_dense_search() {
        let mut seed = 7u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..50 {
            let p: Vec<Point3<f64>> = (0..4).map(|_| Point3::new(next(), next(), next())).collect();
            let at = |s: f64, t: f64| ((p[0] + (p[1] - p[0]) * s) - (p[2] + (p[3] - p[2]) * t)).norm();
            let mut best = f64::MAX;
            let n = 400;
            for i in 0..=n {
                for j in 0..=n {
                    best = best.min(at(i as f64 / n as f64, j as f64 / n as f64));
                }
            }
            let (a, b) = (Convex::Hull(vec![p[0], p[1]]), Convex::Hull(vec![p[2], p[3]]));
            // The grid's minimum is at most 2 × (1/400) × 2√3 above the true one.
            assert!(within(&a, &b, best + 1e-12), "{p:?}: {best}");
            assert!(!within(&a, &b, best - 0.02), "{p:?}: {best}");
        }
    }

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
