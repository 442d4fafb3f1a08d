//! The plane geometry the crossings are found with: where two segments
//! meet ([`segments_meet`]) and the convex hull of a set of points
//! ([`hull`]).

/// How two segments meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// The point (the start of the overlap, along the first segment, for collinear ones).
    pub at: [f64; 2],
    /// Where it is along each segment, from 0 at its start to 1 at its end.
    pub t: [f64; 2],
    /// Whether they are collinear and overlap (more than at a point, or at one).
    pub collinear: bool,
}

/// The vector from `b` to `a`.
pub(super) fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// The planar cross product $a_xb_y - a_yb_x$.
pub(super) fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The dot product.
pub(super) fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The distance between two points.
pub(super) fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
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
pub fn segments_meet(p0: [f64; 2], p1: [f64; 2], q0: [f64; 2], q1: [f64; 2], tolerance: f64) -> Option<Contact> {
    let (r, s) = (sub(p1, p0), sub(q1, q0));
    let (lr, ls) = (r[0].hypot(r[1]), s[0].hypot(s[1]));
    if lr == 0.0 || ls == 0.0 {
        return None;
    }
    let qp = sub(q0, p0);
    let denom = cross(r, s);
    // The sine of the angle between them, against the tolerance over the shorter one.
    if denom.abs() > (tolerance / lr.min(ls)).min(1e-9) * lr * ls {
        let t = cross(qp, s) / denom;
        let u = cross(qp, r) / denom;
        let (et, eu) = (tolerance / lr, tolerance / ls);
        if (-et..=1.0 + et).contains(&t) && (-eu..=1.0 + eu).contains(&u) {
            let t = t.clamp(0.0, 1.0);
            return Some(Contact {
                at: [p0[0] + t * r[0], p0[1] + t * r[1]],
                t: [t, u.clamp(0.0, 1.0)],
                collinear: false,
            });
        }
        return None;
    }
    // Parallel: they meet only if collinear, where their projections overlap.
    if cross(qp, r).abs() / lr > tolerance {
        return None;
    }
    let along = |p: [f64; 2]| dot(sub(p, p0), r) / (lr * lr);
    let (t0, t1) = (along(q0), along(q1));
    let (lo, hi) = (t0.min(t1).max(0.0), t0.max(t1).min(1.0));
    if lo > hi + tolerance / lr {
        return None;
    }
    let t = lo.min(1.0);
    let at = [p0[0] + t * r[0], p0[1] + t * r[1]];
    let u = (dot(sub(at, q0), s) / (ls * ls)).clamp(0.0, 1.0);
    Some(Contact { at, t: [t, u], collinear: true })
}

/// The convex hull of `p`, counter-clockwise (Andrew's monotone chain),
/// collinear points left out.
pub fn hull(mut p: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let turn = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| cross(sub(a, o), sub(b, o));
    let chain = |pts: &mut dyn Iterator<Item = &[f64; 2]>| {
        let mut h: Vec<[f64; 2]> = Vec::new();
        for &q in pts {
            while h.len() >= 2 && turn(h[h.len() - 2], h[h.len() - 1], q) <= 0.0 {
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
