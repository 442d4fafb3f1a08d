//! Crossings: the parts of a solved shape (each flexure's backbone as
//! chords, each link as the hull of its attachment points) that cross
//! another part, or themselves ([`crossings`]).

use super::geometry::{convex_hull, distance, meet};
use crate::kinematics::backbone;
use crate::mechanism::Mechanism;
use crate::mechanism::kinematics::{Frames, frames};
use nalgebra::Point2;

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
}

impl Part {
    /// `flexure "left"` or `link "stage"`.
    pub fn describe(&self, m: &Mechanism) -> String {
        match *self {
            Part::Flexure(j) => format!("flexure {:?}", m.joints[j].name),
            Part::Link(b) => format!("link {:?}", m.bodies[b].name),
        }
    }
}

/// Two parts that cross, meeting at `at`: a point of the plane (`[f64; 2]`,
/// the planar [`crossings`]) or of space (`[f64; 3]`,
/// [`crate::mechanism::spatial::findings::crossings`]).
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
    pub contacts: usize,
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
                "{} crosses itself {where_}; the model has no contact, so this shape passes through itself",
                self.names[0]
            );
        }
        if !along.is_empty() {
            where_ += &format!(" ({})", along.join(", "));
        }
        let more = if self.contacts > 1 { format!(", {} contacts in all", self.contacts) } else { String::new() };
        format!(
            "{} crosses {} {where_}{more}; the model has no contact, so this shape passes through itself",
            self.names[0], self.names[1]
        )
    }
}

/// A part as segments: its polyline, the arc length at each point (a
/// flexure), the points where it is joined to others, and the bodies it
/// belongs to (a closure's two bodies count as one, see [`crossings`]).
struct Drawn {
    part: Part,
    points: Vec<Point2<f64>>,
    arc: Option<Vec<f64>>,
    ends: Vec<Point2<f64>>,
    groups: Vec<usize>,
    lo: Point2<f64>,
    hi: Point2<f64>,
}

/// The chords that stand for a flexure with coordinates `alpha` (see the module docs).
pub fn chords(alpha: &[f64]) -> usize {
    let turning: f64 = alpha.iter().map(|a| a.abs()).sum();
    let wanted = (turning / CHORD_TURN).ceil();
    if wanted.is_finite() { (wanted as usize).clamp(MIN_CHORDS, MAX_CHORDS) } else { MAX_CHORDS }
}

/// Every part of `m` at coordinates `q` that crosses another, or itself
/// (see the module docs): at most one [`Crossing`] per pair of parts, the
/// first along the first part, with the number of contacts between them.
///
/// # Panics
/// If `q` does not have [`Mechanism::dof`] entries.
pub fn crossings(m: &Mechanism, q: &[f64]) -> Vec<Crossing> {
    assert_eq!(q.len(), m.dof(), "crossings: q must have one entry per coordinate");
    let f = frames(m, q);
    let tolerance = TOUCH_TOLERANCE * m.size();
    let group = groups(m);
    let parts = drawn(m, q, &f, &group);
    let mut out = Vec::new();
    for (i, a) in parts.iter().enumerate() {
        if let Some(c) = self_crossing(a, tolerance) {
            out.push(named(m, c));
        }
        for b in &parts[i + 1..] {
            if a.hi.x + tolerance < b.lo.x
                || b.hi.x + tolerance < a.lo.x
                || a.hi.y + tolerance < b.lo.y
                || b.hi.y + tolerance < a.lo.y
            {
                continue;
            }
            let joined = a.groups.iter().any(|g| b.groups.contains(g));
            let at_end = |d: &Drawn, p: &Point2<f64>| d.ends.iter().any(|e| distance(e, p) <= tolerance);
            let mut first: Option<Crossing> = None;
            let mut contacts: Vec<Point2<f64>> = Vec::new();
            for (k, sa) in a.points.windows(2).enumerate() {
                for (l, sb) in b.points.windows(2).enumerate() {
                    let Some(c) = meet(&sa[0], &sa[1], &sb[0], &sb[1], tolerance) else { continue };
                    let at = Point2::from(c.at);
                    if joined && at_end(a, &at) && at_end(b, &at) {
                        // A collinear overlap running on from the joint is a crossing.
                        if !c.collinear || overlap_is_point(sa, sb, tolerance) {
                            continue;
                        }
                    }
                    add_contact(&mut contacts, at, tolerance);
                    if first.is_none() {
                        first = Some(Crossing {
                            a: a.part,
                            b: b.part,
                            names: [String::new(), String::new()],
                            at: c.at,
                            s: [arc(a, k, c.t[0]), arc(b, l, c.t[1])],
                            contacts: 0,
                        });
                    }
                }
            }
            if let Some(mut c) = first {
                c.contacts = contacts.len();
                out.push(named(m, c));
            }
        }
    }
    out
}

/// Counts the contact at `p` unless one already counted is within `tolerance`
/// (a crossing through a chord's end is met by both chords there).
fn add_contact(contacts: &mut Vec<Point2<f64>>, p: Point2<f64>, tolerance: f64) {
    if contacts.iter().all(|c| distance(c, &p) > tolerance) {
        contacts.push(p);
    }
}

/// Whether two collinear segments share no more than a point.
fn overlap_is_point(sa: &[Point2<f64>], sb: &[Point2<f64>], tolerance: f64) -> bool {
    let r = sa[1] - sa[0];
    let lr = r.x.hypot(r.y);
    let along = |p: &Point2<f64>| (p - sa[0]).dot(&r) / lr;
    let (t0, t1) = (along(&sb[0]), along(&sb[1]));
    t0.max(t1).min(lr) - t0.min(t1).max(0.0) <= tolerance
}

fn named(m: &Mechanism, mut c: Crossing) -> Crossing {
    c.names = [c.a.describe(m), c.b.describe(m)];
    c
}

/// The arc length at `t` along segment `k` of a flexure.
fn arc(d: &Drawn, k: usize, t: f64) -> Option<f64> {
    d.arc.as_ref().map(|s| s[k] + t * (s[k + 1] - s[k]))
}

/// A flexure's chords that meet, other than consecutive ones at their shared point.
fn self_crossing(d: &Drawn, tolerance: f64) -> Option<Crossing> {
    let Part::Flexure(_) = d.part else { return None };
    let mut first: Option<Crossing> = None;
    let mut contacts: Vec<Point2<f64>> = Vec::new();
    let n = d.points.len() - 1;
    for k in 0..n {
        for l in k + 2..n {
            let (sa, sb) = (&d.points[k..k + 2], &d.points[l..l + 2]);
            if let Some(c) = meet(&sa[0], &sa[1], &sb[0], &sb[1], tolerance) {
                add_contact(&mut contacts, Point2::from(c.at), tolerance);
                if first.is_none() {
                    let s = [arc(d, k, c.t[0]), arc(d, l, c.t[1])];
                    first =
                        Some(Crossing { a: d.part, b: d.part, names: Default::default(), at: c.at, s, contacts: 0 });
                }
            }
        }
    }
    first.map(|mut c| {
        c.contacts = contacts.len();
        c
    })
}

/// Each body's group: bodies joined by a closure, or by a joint other than a flexure, are one group.
fn groups(m: &Mechanism) -> Vec<usize> {
    let mut g: Vec<usize> = (0..m.bodies.len()).collect();
    fn root(g: &mut [usize], mut i: usize) -> usize {
        while g[i] != i {
            g[i] = g[g[i]];
            i = g[i];
        }
        i
    }
    let closed = m.closures.iter().map(|c| (c.a, c.b));
    // Rigid joints (revolute, prismatic, fixed) hold their bodies together at a point, as closures do.
    let rigid = m.joints.iter().filter(|j| j.kind.flexure().is_none()).map(|j| (j.parent, j.child));
    for (a, b) in closed.chain(rigid) {
        let (ra, rb) = (root(&mut g, a), root(&mut g, b));
        g[ra.max(rb)] = ra.min(rb);
    }
    (0..g.len()).map(|i| root(&mut g, i)).collect()
}

/// The parts of `m` at `q` as segments: flexures first, in joint order, then links.
fn drawn(m: &Mechanism, q: &[f64], f: &Frames, group: &[usize]) -> Vec<Drawn> {
    let mut parts = Vec::new();
    let bounds = |points: &[Point2<f64>]| {
        let (lo, hi) = (Point2::new(f64::MAX, f64::MAX), Point2::new(f64::MIN, f64::MIN));
        points.iter().fold((lo, hi), |(lo, hi), p| {
            (Point2::new(lo.x.min(p.x), lo.y.min(p.y)), Point2::new(hi.x.max(p.x), hi.y.max(p.y)))
        })
    };
    for (ji, j) in m.joints.iter().enumerate() {
        let Some(fl) = j.kind.flexure() else { continue };
        let alpha = &q[j.offset..j.offset + fl.order()];
        let samples = chords(alpha) + 1;
        let root = f.roots[ji];
        let mut points: Vec<Point2<f64>> = backbone(fl, alpha, samples).iter().map(|p| root.act(&p.origin())).collect();
        // The backbone integrates its own way: it ends within its quadrature
        // error of the model's tip, the child's origin, where the child is
        // drawn. Its points are moved by that error in proportion to arc
        // length, so that it ends there exactly.
        let tip = f.bodies[j.child].origin();
        let miss = tip - points[samples - 1];
        for (i, p) in points.iter_mut().enumerate() {
            let t = i as f64 / (samples - 1) as f64;
            *p += miss * t;
        }
        let arc = (0..samples).map(|i| fl.length() * i as f64 / (samples - 1) as f64).collect();
        let ends = vec![points[0], points[samples - 1], tip];
        let (lo, hi) = bounds(&points);
        parts.push(Drawn {
            part: Part::Flexure(ji),
            points,
            arc: Some(arc),
            ends,
            groups: vec![group[j.parent], group[j.child]],
            lo,
            hi,
        });
    }
    for b in 0..m.bodies.len() {
        let anchors = m.tendons.iter().flat_map(|t| &t.path).filter(|v| v.0 == b).map(|v| v.1);
        let mut ends: Vec<Point2<f64>> =
            hull_points(m.attachments(b), b, anchors).iter().map(|r| f.bodies[b].act(r)).collect();
        let mut points = convex_hull(ends.clone());
        // Where a slider's carriage (or a pin's child) sits on this link.
        let carried = m.joints.iter().filter(|j| j.parent == b && j.kind.flexure().is_none());
        ends.extend(carried.map(|j| f.bodies[j.child].origin()));
        if points.len() < 2 {
            continue;
        }
        if points.len() > 2 {
            points.push(points[0]);
        }
        let (lo, hi) = bounds(&points);
        parts.push(Drawn { part: Part::Link(b), points, arc: None, ends, groups: vec![group[b]], lo, hi });
    }
    parts
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
pub fn crossings_along<'a>(m: &Mechanism, shapes: impl IntoIterator<Item = &'a [f64]>) -> Vec<(usize, Vec<Crossing>)> {
    shapes.into_iter().map(|q| crossings(m, q)).enumerate().filter(|(_, c)| !c.is_empty()).collect()
}
