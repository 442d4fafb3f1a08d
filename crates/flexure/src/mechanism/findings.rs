//! What is not an error but must not pass without a word: closures open at
//! rest, whose closing preloads the mechanism, and parts that cross each
//! other in a solved shape (self-intersection; the model has no contact).
//!
//! The library prints nothing: each finding has a [`Severity`] and a
//! message, and the callers (the command line, Python) report them.
//!
//! **Open closures** ([`open_closures`]). A weld or pin *meets at rest*
//! when, with every joint at its rest coordinates, its two points are at
//! most [`GAP_TOLERANCE`] × [`Mechanism::size`] apart and (a weld) its two
//! frames' angles differ by at most [`GAP_TOLERANCE`] rad, the angle taken
//! to $(-\pi, \pi]$ as the closure equation takes it. One that does not
//! meet is closed by force before any load acts: the finding gives the gap
//! and the preload, the closure's multiplier (force in N, and moment in
//! N·m for a weld) in the unloaded, assembled configuration, that is, the
//! force the weld or pin carries with no external load. It is a warning,
//! or a note when the closure says `preload = true`.
//!
//! **Crossings** ([`crossings`]). Each flexure is its backbone
//! ([`crate::kinematics::backbone`]) as a polyline of chords; each body,
//! the ground included, the edges of the hull of its attachment points
//! ([`Mechanism::attachments`]: what `flexure draw` fills as the link).
//! The backbone's curvature is at most $V/L$ everywhere, with
//! $V = \sum_i\lvert\alpha_i\rvert$ (each angle shape's slope is a shifted
//! Legendre polynomial, at most 1 in magnitude), so with
//! $\lceil V/\theta\rceil$ chords or more each chord turns by at most
//! $\theta$ = [`CHORD_TURN`] and stays within $h\theta/2$ of its arc, $h$ its
//! length (at least [`MIN_CHORDS`] chords, at most [`MAX_CHORDS`]): only a
//! crossing shallower than that is missed. Two segments cross when they
//! share a point (within [`TOUCH_TOLERANCE`] × the mechanism's size), a
//! collinear overlap included. Parts that a joint or a closure connects
//! meet at their ends (a flexure's root on its parent link, its tip on its
//! child, two legs on a stage welded to one of them, links on either side
//! of a revolute joint, a slider's carriage on its rail): a contact there,
//! at a point that is an end of both parts (a link's attachment points or
//! the origin of a body it carries by a revolute, prismatic or fixed joint;
//! a flexure's root and tip), is not a crossing, unless it is a collinear
//! overlap that runs on from there. A flexure's
//! non-consecutive chords are tested against each other too (a loop).

use super::kinematics::{Frames, frames};
use super::statics::{Settings, assemble_unloaded};
use super::{Closure, Mechanism};
use crate::error::{Error, Result};
use crate::kinematics::backbone;

/// A closure meets at rest when its gap is at most this: relative to the
/// mechanism's size for positions, in rad for a weld's angle.
pub const GAP_TOLERANCE: f64 = 1e-9;

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

/// How much a finding matters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// Something is likely wrong with the answer or the file.
    Warning,
    /// Something the file says is meant (a closure with `preload = true`).
    Note,
}

/// A weld or pin whose two sides do not meet in the unloaded mechanism.
#[derive(Debug, Clone, PartialEq)]
pub struct OpenClosure {
    /// Its index in [`Mechanism::closures`].
    pub closure: usize,
    /// What it is: `weld of "stage" and "b_tip"`.
    pub what: String,
    /// Where it is given in the file ("line L, column C").
    pub place: String,
    /// Distance between its two points at rest (m).
    pub gap: f64,
    /// A weld's angle between its two frames at rest (rad, in $(-\pi, \pi]$,
    /// frame `a`'s angle minus frame `b`'s); `None` for a pin.
    pub turn: Option<f64>,
    /// The magnitude of the force it carries when assembled with no load
    /// (N); `None` if the unloaded mechanism cannot be assembled (from rest,
    /// by Newton: then every solve of it fails, saying so).
    pub force: Option<f64>,
    /// A weld's moment when assembled with no load (N·m); `None` for a pin,
    /// or if the unloaded mechanism cannot be assembled.
    pub moment: Option<f64>,
    /// Whether the file says `preload = true`.
    pub preload: bool,
}

impl OpenClosure {
    /// A warning, or a note with `preload = true`.
    pub fn severity(&self) -> Severity {
        if self.preload { Severity::Note } else { Severity::Warning }
    }

    /// The finding in words, with its place in the file.
    pub fn message(&self) -> String {
        let gap = match self.turn {
            Some(t) => format!("{:.6e} m and {t:.6} rad", self.gap),
            None => format!("{:.6e} m", self.gap),
        };
        let preload = match (self.force, self.moment) {
            (Some(force), Some(moment)) => format!("with no load it carries {force:.6e} N and {moment:.6e} N·m"),
            (Some(force), None) => format!("with no load it carries {force:.6e} N"),
            (None, _) => "the unloaded mechanism cannot be assembled, so how much is not known".to_string(),
        };
        let what = format!(
            "{}: {} is open at rest by {gap}; closing it preloads the mechanism: {preload}",
            self.place, self.what
        );
        if self.preload {
            format!("{what} (preload = true)")
        } else {
            format!("{what}; if that is meant, say `preload = true` in it, else make its frames meet at rest")
        }
    }
}

/// `weld of "a" and "b"` or `pin of "a" and "b"`.
pub fn closure_name(m: &Mechanism, i: usize) -> String {
    let name = |b: usize| &m.bodies[b].name;
    match m.closures[i] {
        Closure::Weld { a, b, .. } => format!("weld of {:?} and {:?}", name(a), name(b)),
        Closure::Pin { a, b, .. } => format!("pin of {:?} and {:?}", name(a), name(b)),
    }
}

/// Each closure's gap at rest: (distance in m, a weld's angle in rad).
pub fn rest_gaps(m: &Mechanism) -> Vec<(f64, Option<f64>)> {
    let f = frames(m, &m.rest());
    m.closures
        .iter()
        .map(|c| match *c {
            Closure::Weld { a, a_origin, b, b_origin } => {
                let (fa, fb) = (f.bodies[a].compose(&a_origin), f.bodies[b].compose(&b_origin));
                let turn = super::lagrangian::wrap(fa.phi - fb.phi);
                (distance([fa.x, fa.y], [fb.x, fb.y]), Some(turn))
            }
            Closure::Pin { a, a_at, b, b_at } => (
                distance(f.bodies[a].act_components([a_at.x, a_at.y]), f.bodies[b].act_components([b_at.x, b_at.y])),
                None,
            ),
        })
        .collect()
}

/// The closures of `m` that do not meet at rest (see the module docs),
/// each with the preload that closes it: the unloaded mechanism is
/// assembled (with `settings`) only if one is open. If that assembly
/// fails, as every static solve of `m` then does, the preload is `None`
/// (a simulation from an `[initial]` state may still run); an error only
/// if it is interrupted.
pub fn open_closures(m: &Mechanism, settings: &Settings) -> Result<Vec<OpenClosure>> {
    let length = m.size();
    let open: Vec<(usize, (f64, Option<f64>))> = rest_gaps(m)
        .into_iter()
        .enumerate()
        .filter(|(_, (gap, turn))| *gap > GAP_TOLERANCE * length || turn.is_some_and(|t| t.abs() > GAP_TOLERANCE))
        .collect();
    if open.is_empty() {
        return Ok(Vec::new());
    }
    let unloaded = match assemble_unloaded(m, settings) {
        Ok(s) => Some(s),
        Err(Error::File { .. } | Error::NoConvergence { .. } | Error::Singular { .. }) => None,
        Err(e) => return Err(e),
    };
    let mut rows = Vec::with_capacity(m.closures.len());
    let mut row = 0;
    for c in &m.closures {
        rows.push(row);
        row += c.equations();
    }
    Ok(open
        .into_iter()
        .map(|(i, (gap, turn))| {
            let mu = unloaded.as_ref().map(|s| &s.multipliers[rows[i]..rows[i] + m.closures[i].equations()]);
            OpenClosure {
                closure: i,
                what: closure_name(m, i),
                place: m.closure_place(i).to_string(),
                gap,
                turn,
                force: mu.map(|mu| mu[0].hypot(mu[1])),
                moment: mu.zip(turn).map(|(mu, _)| mu[2].abs()),
                preload: m.closure_preload(i),
            }
        })
        .collect())
}

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

/// Two parts that cross.
#[derive(Debug, Clone, PartialEq)]
pub struct Crossing {
    /// The first part (the earlier flexure, or a flexure before a link).
    pub a: Part,
    /// The second part (equal to `a` for a flexure that crosses itself).
    pub b: Part,
    /// `a` and `b` as [`Part::describe`] gives them.
    pub names: [String; 2],
    /// The first point where they meet (ground frame, m), first along `a`.
    pub at: [f64; 2],
    /// The arc length (m from its root) where each part meets the other
    /// there, for a flexure; `None` for a link.
    pub s: [Option<f64>; 2],
    /// At how many distinct points their segments meet (one crossing, or several).
    pub contacts: usize,
}

impl Crossing {
    /// The finding in words.
    pub fn message(&self) -> String {
        let along: Vec<String> =
            (0..2).filter_map(|k| self.s[k].map(|s| format!("{s:.6e} m along {}", self.names[k]))).collect();
        let mut where_ = format!("at ({:.6e}, {:.6e}) m", self.at[0], self.at[1]);
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

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
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

/// A part as segments: its polyline, the arc length at each point (a
/// flexure), the points where it is joined to others, and the bodies it
/// belongs to (a closure's two bodies count as one, see [`crossings`]).
struct Drawn {
    part: Part,
    points: Vec<[f64; 2]>,
    arc: Option<Vec<f64>>,
    ends: Vec<[f64; 2]>,
    groups: Vec<usize>,
    lo: [f64; 2],
    hi: [f64; 2],
}

/// The chords that stand for a flexure with coordinates `alpha` (see the module docs).
pub fn chords(alpha: &[f64]) -> usize {
    let turning: f64 = alpha.iter().map(|a| a.abs()).sum();
    let wanted = (turning / CHORD_TURN).ceil();
    if wanted.is_finite() { (wanted as usize).clamp(MIN_CHORDS, MAX_CHORDS) } else { MAX_CHORDS }
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
            if a.hi[0] + tolerance < b.lo[0]
                || b.hi[0] + tolerance < a.lo[0]
                || a.hi[1] + tolerance < b.lo[1]
                || b.hi[1] + tolerance < a.lo[1]
            {
                continue;
            }
            let joined = a.groups.iter().any(|g| b.groups.contains(g));
            let at_end = |d: &Drawn, p: [f64; 2]| d.ends.iter().any(|e| distance(*e, p) <= tolerance);
            let mut first: Option<Crossing> = None;
            let mut contacts: Vec<[f64; 2]> = Vec::new();
            for (k, sa) in a.points.windows(2).enumerate() {
                for (l, sb) in b.points.windows(2).enumerate() {
                    let Some(c) = segments_meet(sa[0], sa[1], sb[0], sb[1], tolerance) else { continue };
                    if joined && at_end(a, c.at) && at_end(b, c.at) {
                        // A collinear overlap running on from the joint is a crossing.
                        if !c.collinear || overlap_is_point(sa, sb, tolerance) {
                            continue;
                        }
                    }
                    add_contact(&mut contacts, c.at, tolerance);
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
fn add_contact(contacts: &mut Vec<[f64; 2]>, p: [f64; 2], tolerance: f64) {
    if contacts.iter().all(|c| distance(*c, p) > tolerance) {
        contacts.push(p);
    }
}

/// Whether two collinear segments share no more than a point.
fn overlap_is_point(sa: &[[f64; 2]], sb: &[[f64; 2]], tolerance: f64) -> bool {
    let r = sub(sa[1], sa[0]);
    let lr = r[0].hypot(r[1]);
    let along = |p: [f64; 2]| dot(sub(p, sa[0]), r) / lr;
    let (t0, t1) = (along(sb[0]), along(sb[1]));
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
    let mut contacts: Vec<[f64; 2]> = Vec::new();
    let n = d.points.len() - 1;
    for k in 0..n {
        for l in k + 2..n {
            let (sa, sb) = (&d.points[k..k + 2], &d.points[l..l + 2]);
            if let Some(c) = segments_meet(sa[0], sa[1], sb[0], sb[1], tolerance) {
                add_contact(&mut contacts, c.at, tolerance);
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
    let closed = m.closures.iter().map(|c| match *c {
        Closure::Weld { a, b, .. } | Closure::Pin { a, b, .. } => (a, b),
    });
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
    let bounds = |points: &[[f64; 2]]| {
        points.iter().fold(([f64::MAX; 2], [f64::MIN; 2]), |(lo, hi), p| {
            ([lo[0].min(p[0]), lo[1].min(p[1])], [hi[0].max(p[0]), hi[1].max(p[1])])
        })
    };
    for (ji, j) in m.joints.iter().enumerate() {
        let Some(fl) = j.kind.flexure() else { continue };
        let alpha = &q[j.offset..j.offset + fl.order()];
        let samples = chords(alpha) + 1;
        let root = f.roots[ji];
        let mut points: Vec<[f64; 2]> =
            backbone(fl, alpha, samples).iter().map(|p| root.act_components([p.x, p.y])).collect();
        // The backbone integrates its own way: it ends within its quadrature
        // error of the model's tip, the child's origin, where the child is
        // drawn. Its points are moved by that error in proportion to arc
        // length, so that it ends there exactly.
        let tip = [f.bodies[j.child].x, f.bodies[j.child].y];
        let miss = sub(tip, points[samples - 1]);
        for (i, p) in points.iter_mut().enumerate() {
            let t = i as f64 / (samples - 1) as f64;
            *p = [p[0] + t * miss[0], p[1] + t * miss[1]];
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
        let mut ends: Vec<[f64; 2]> = m.attachments(b).iter().map(|r| f.bodies[b].act_components([r.x, r.y])).collect();
        let mut points = hull(ends.clone());
        // Where a slider's carriage (or a pin's child) sits on this link.
        let carried = m.joints.iter().filter(|j| j.parent == b && j.kind.flexure().is_none());
        ends.extend(carried.map(|j| [f.bodies[j.child].x, f.bodies[j.child].y]));
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

/// [`crossings`] at each of a series of shapes (a sweep's rows, a
/// simulation's samples): (index in the series, its crossings), for the
/// shapes that have any.
pub fn crossings_along<'a>(m: &Mechanism, shapes: impl IntoIterator<Item = &'a [f64]>) -> Vec<(usize, Vec<Crossing>)> {
    shapes.into_iter().map(|q| crossings(m, q)).enumerate().filter(|(_, c)| !c.is_empty()).collect()
}
