//! The plane geometry the crossings are found with: where two segments
//! meet ([`segments_meet`]) and the convex hull of a set of points
//! ([`hull`]).

use nalgebra::{Point2, Vector2};

/// How two segments meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Meeting {
    /// The point (the start of the overlap, along the first segment, for collinear ones).
    pub at: [f64; 2],
    /// Where it is along each segment, from 0 at its start to 1 at its end.
    pub t: [f64; 2],
    /// Whether they are collinear and overlap (more than at a point, or at one).
    pub collinear: bool,
}

/// The distance between two points, as `hypot` gives it.
pub(super) fn distance(a: &Point2<f64>, b: &Point2<f64>) -> f64 {
    length(&(a - b))
}

/// The length of a vector, as `hypot` gives it.
fn length(v: &Vector2<f64>) -> f64 {
    v.x.hypot(v.y)
}

/// Where segment `p0`–`p1` meets segment `q0`–`q1`, if they come within
/// `tolerance` (m) of each other at a crossing, a touch or a collinear
/// overlap; `None` if they do not, or if either has no length.
///
/// # Example
/// ```
/// use flexure::mechanism::findings::segments_meet;
/// let c = segments_meet([0.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.0, 0.0], 1e-12).unwrap();
/// assert_eq!(c.at, [1.0, 1.0]);
/// assert!(segments_meet([0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], 1e-12).is_none());
/// ```
pub fn segments_meet(p0: [f64; 2], p1: [f64; 2], q0: [f64; 2], q1: [f64; 2], tolerance: f64) -> Option<Meeting> {
    meet(&p0.into(), &p1.into(), &q0.into(), &q1.into(), tolerance)
}

/// [`segments_meet`] on points.
pub(super) fn meet(
    p0: &Point2<f64>,
    p1: &Point2<f64>,
    q0: &Point2<f64>,
    q1: &Point2<f64>,
    tolerance: f64,
) -> Option<Meeting> {
    let (r, s) = (p1 - p0, q1 - q0);
    let (lr, ls) = (length(&r), length(&s));
    if lr == 0.0 || ls == 0.0 {
        return None;
    }
    let qp = q0 - p0;
    let denom = r.perp(&s);
    // The sine of the angle between them, against the tolerance over the shorter one.
    if denom.abs() > (tolerance / lr.min(ls)).min(1e-9) * lr * ls {
        let t = qp.perp(&s) / denom;
        let u = qp.perp(&r) / denom;
        let (et, eu) = (tolerance / lr, tolerance / ls);
        if (-et..=1.0 + et).contains(&t) && (-eu..=1.0 + eu).contains(&u) {
            let t = t.clamp(0.0, 1.0);
            return Some(Meeting { at: (p0 + r * t).into(), t: [t, u.clamp(0.0, 1.0)], collinear: false });
        }
        return None;
    }
    // Parallel: they meet only if collinear, where their projections overlap.
    if qp.perp(&r).abs() / lr > tolerance {
        return None;
    }
    let along = |p: &Point2<f64>| (p - p0).dot(&r) / (lr * lr);
    let (t0, t1) = (along(q0), along(q1));
    let (lo, hi) = (t0.min(t1).max(0.0), t0.max(t1).min(1.0));
    if lo > hi + tolerance / lr {
        return None;
    }
    let t = lo.min(1.0);
    let at = p0 + r * t;
    let u = ((at - q0).dot(&s) / (ls * ls)).clamp(0.0, 1.0);
    Some(Meeting { at: at.into(), t: [t, u], collinear: true })
}

/// The convex hull of `p`, counter-clockwise (Andrew's monotone chain),
/// collinear points left out.
pub fn hull(p: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    convex_hull(p.into_iter().map(Point2::from).collect()).into_iter().map(Into::into).collect()
}

/// [`hull`] on points.
pub(super) fn convex_hull(mut p: Vec<Point2<f64>>) -> Vec<Point2<f64>> {
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let turn = |o: &Point2<f64>, a: &Point2<f64>, b: &Point2<f64>| (a - o).perp(&(b - o));
    let chain = |pts: &mut dyn Iterator<Item = &Point2<f64>>| {
        let mut h: Vec<Point2<f64>> = Vec::new();
        for &q in pts {
            while h.len() >= 2 && turn(&h[h.len() - 2], &h[h.len() - 1], &q) <= 0.0 {
                h.pop();
            }
            h.push(q);
        }
        h.pop();
        h
    };
    let mut lower = chain(&mut p.iter());
    lower.extend(chain(&mut p.iter().rev()));
    lower
}
