//! `flexure draw`: a mechanism's shapes as one figure, seen from a [`View`]
//! ([`super::projection`]), in both dimensions alike: it reads only the
//! [`Scene`] and its [`Snapshot`]s ([`super::scene`], where a planar mechanism
//! lies at z = 0 and is seen from the top).
//!
//! # What is drawn
//!
//! Each shape in its colour (the unloaded one grey):
//! - **Rigid links**: the convex hull of every point attached to them,
//!   grown by 1.2 % of the mechanism's size, so that two points make a bar.
//! - **Flexures**: the centreline through 41 sections, thick; a loaded
//!   flexure whose section has a geometry coloured by its stress, each
//!   segment by the mean of its ends', on a ramp from 0 to the largest peak
//!   stress of any loaded shape (the colour bar's top, MPa), which goes on
//!   past the highest yield strength so that its mark shows.
//! - **Joints**: a hinge as a hollow circle with a short line along its
//!   projected axis (a point when seen along it), a ball joint as a filled
//!   circle, a slider as a square and a short double line along its axis
//!   with its travel dashed; pin closures as hinges, ball closures as balls.
//! - **Tendons**: thin lines through their via points, told apart by dash
//!   and via marker.
//! - **Loads** (not on the unloaded shape): forces and weights as arrows
//!   $k\thinspace f$ long, $k$ a round scale putting the largest a quarter
//!   of the mechanism's size; a force along the line of sight as ⊙ (toward
//!   the viewer) or ⊗; none for a force under 2 % of the largest (the legend
//!   still gives it). Forces from one point in one direction are drawn side
//!   by side, each named at its own head. A moment along the line of sight
//!   is a turning arrow (counter-clockwise as the viewer sees it if
//!   positive), else a double arrow along the moment vector at a scale of its own.
//! - **Ground**: a hatched anchor at each point attached to it, its bar
//!   across the joint that leaves it; an axis triad left of the drawing.
//!
//! # Depth
//!
//! Within each shape, links, flexure segments and tendon segments are
//! painted in increasing depth $p\cdot t$ ([`View::project`]): a segment at
//! the mean depth of its ends, a link at the depth of its back (its farthest
//! point less its half thickness), so that a link covers what lies wholly
//! behind it but not the flexures and tendons it carries. Symbols, via
//! points and loads go on top. Shapes are layered in order, unloaded first.

pub use super::projection::View;
use super::scene::{Scene, Snapshot, Solid, Symbol};
use super::solids;
use flexure_chart::{
    Anchor, COLORS, Chart, Color, ColorBar, Dash, Entry, Figure, Fill, GRAY, Mark, Marker, Place, Series, Stroke,
    Swatch, chart_figure, ramp,
};
use nalgebra::Vector3;
use std::f64::consts::TAU;

type V = Vector3<f64>;

/// The colour of legend keys that stand for every shape.
pub(super) const KEY: Color = Color(60, 60, 60);
const GROUND: Color = Color(90, 90, 90);
/// The loaded shapes' colours, in order.
const SHAPES: [Color; 5] = [COLORS[0], COLORS[2], COLORS[3], COLORS[1], COLORS[4]];

/// The colour of loaded shape `i` of `count`: one of [`SHAPES`] while they
/// last, else the first of them from light to full in order (a sweep's
/// values), so that no two shapes share a colour, and none is read on the
/// stress map.
fn shape_color(i: usize, count: usize) -> Color {
    match count <= SHAPES.len() {
        true => SHAPES[i],
        false => SHAPES[0].tint(0.6 * (1.0 - i as f64 / (count - 1) as f64)),
    }
}
/// Tendons are told apart by dash and via-point marker, not colour.
const TENDON_DASH: [Dash; 3] = [Dash::Solid, Dash::Dashed, Dash::Chain];
const VIA: [Marker; 4] = [Marker::Circle, Marker::Square, Marker::Triangle, Marker::Diamond];
const FLEXURE_WIDTH: f64 = 5.0;
/// Points along each drawn flexure.
pub const FLEXURE_SAMPLES: usize = 41;
/// The fewest of the longest arrow's length an arrow is drawn at: a force
/// far smaller than the others would be an arrow of no length, its head
/// and name on its tail (the legend still gives its value).
pub(super) const LEAST_ARROW: f64 = 0.02;
/// How far apart arrows from one point in one direction are drawn, as a
/// fraction of the longest arrow: their heads (about 12 px across) apart
/// once the longest is 80 px or more.
const BESIDE: f64 = 0.15;
/// How far apart (px) the names of arrows drawn side by side are stacked.
const NAME_STEP: f64 = 18.0;

/// `x` to four significant digits, without trailing zeros, with a true minus sign.
pub fn short(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let magnitude = x.abs().log10().floor();
    let text = if (-3.0..5.0).contains(&magnitude) {
        let t = format!("{x:.*}", (3.0 - magnitude).max(0.0) as usize);
        if t.contains('.') { t.trim_end_matches('0').trim_end_matches('.').to_string() } else { t }
    } else {
        format!("{x:.3e}")
    };
    text.replace('-', "−")
}

/// The unit of a swept parameter (`tendon.NAME.tension`, `force.NAME.fx|fy|moment`, `gravity.x|y`).
fn unit(parameter: &str) -> &'static str {
    if parameter.ends_with(".moment") {
        "N·m"
    } else if parameter.starts_with("gravity.") {
        "m/s²"
    } else {
        "N"
    }
}

/// The ends of each bounded geom's bounding ball along the axes: what
/// sizes a view by a geom (a block on a slider has no link).
fn ball_ends(geoms: &[Solid]) -> impl Iterator<Item = V> + '_ {
    let balls = geoms.iter().filter_map(solids::bounding_ball);
    balls.flat_map(|(c, r)| (0..3).flat_map(move |i| [c - V::ith(i, r), c + V::ith(i, r)]))
}

/// The least and largest component `i` of `points` (`(MAX, MIN)` for none).
fn bounds<'a>(points: impl Iterator<Item = &'a V>, i: usize) -> (f64, f64) {
    points.fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p[i]), b.max(p[i])))
}

/// A swept shape's name: `tendon.flexor.tension = 4 N`.
pub fn swept(parameter: &str, value: f64) -> String {
    format!("{parameter} = {} {}", short(value), unit(parameter))
}

/// The convex hull, counter-clockwise: the library's, which the crossing test uses.
pub(super) fn hull(p: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    let points = p.into_iter().map(|(x, y)| [x, y]).collect();
    flexure::mechanism::findings::hull(points).into_iter().map(|[x, y]| (x, y)).collect()
}

/// A rigid link: the hull of its points grown by `r`, so that two
/// points make a bar and one a disc.
fn slab(pts: &[(f64, f64)], r: f64) -> Vec<(f64, f64)> {
    let round = (0..16).map(|k| TAU * f64::from(k) / 16.0).map(|a| (r * a.cos(), r * a.sin()));
    hull(pts.iter().flat_map(|p| round.clone().map(move |d| (p.0 + d.0, p.1 + d.1))).collect())
}

/// The largest 1, 2 or 5 × 10ᵏ not above `x`.
fn round_down(x: f64) -> f64 {
    let base = 10f64.powf(x.log10().floor());
    [5.0, 2.0, 1.0].into_iter().map(|m| m * base).find(|s| *s <= x * (1.0 + 1e-9)).unwrap_or(base)
}

/// How a load reads in the legend: one value, or the range over the shapes.
fn values(v: &[f64], unit: &str) -> String {
    let (lo, hi) = v.iter().fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    if v.is_empty() || lo == hi {
        format!("{} {unit}", short(v.first().copied().unwrap_or(0.0)))
    } else {
        format!("{} to {} {unit}", short(lo), short(hi))
    }
}

/// A vector as text with `n` components, `(1, −2)` or `(1, −2, 0.5)`.
fn vector(v: &V, n: usize) -> String {
    let parts: Vec<String> = v.iter().take(n).map(|x| short(*x)).collect();
    format!("({})", parts.join(", "))
}

/// What a figure marks beyond the shapes: each flexure's yield strength
/// (Pa) on the stress colour bar, and where a sweep lost stability.
#[derive(Default)]
pub struct Marks {
    pub yields: Vec<(String, f64)>,
    pub limit: Option<String>,
}

/// The sizes every shape of one figure shares.
#[derive(Clone, Copy)]
pub(super) struct Sizes {
    /// The mechanism's size (m): the largest span of its unloaded points, or its longest flexure.
    pub(super) extent: f64,
    /// The middle of the box of what is drawn (the unloaded points and
    /// every shape's) and half its sides (world, m): a plane is drawn
    /// about the middle's foot, across the box.
    pub(super) centre: V,
    pub(super) half: V,
    /// The links' half thickness (m): 1.2 % of the size.
    pub(super) thick: f64,
    /// The largest force drawn (N): a load's or a contact's.
    pub(super) largest: f64,
    /// Force arrows' length per newton (m/N), if any force acts.
    pub(super) per_newton: Option<f64>,
    /// Moment arrows' length per newton metre (m/(N·m)), if any moment acts.
    pub(super) per_newton_metre: Option<f64>,
}

/// How a shape's loads are drawn: not at all (the unloaded shape), or with
/// its arrows and its flexures coloured by stress up to `stress_top` (Pa).
#[derive(Clone, Copy)]
enum Loads {
    Hidden,
    Drawn { stress_top: Option<f64> },
}

/// A picture point from a world point.
pub(super) fn pic(view: View, p: &V) -> (f64, f64) {
    view.project(p).0
}

fn depth(view: View, p: &V) -> f64 {
    view.project(p).1
}

/// The mean depth of world points.
fn mean_depth(view: View, pts: &[V]) -> f64 {
    if pts.is_empty() { 0.0 } else { pts.iter().map(|p| depth(view, p)).sum::<f64>() / pts.len() as f64 }
}

/// A unit picture direction, or `None` if `v` is (nearly) along the line of sight.
fn picture_direction(view: View, v: &V) -> Option<(f64, f64)> {
    let (a, b) = pic(view, v);
    let n = a.hypot(b);
    (n > 1e-6 * v.norm() && n > 0.0).then(|| (a / n, b / n))
}

/// A text anchor for a label placed past a head pointing along `ux` (picture).
pub(super) fn anchor_along(ux: f64) -> Anchor {
    if ux > 0.3 {
        Anchor::Start
    } else if ux < -0.3 {
        Anchor::End
    } else {
        Anchor::Middle
    }
}

/// A straight line in the picture.
fn line(points: Vec<(f64, f64)>, stroke: Stroke) -> Mark {
    Mark::Path { points, stroke: Some(stroke), fill: None, closed: false }
}

/// A part of one shape, painted at its depth (larger: nearer).
pub(super) struct Part {
    pub(super) depth: f64,
    pub(super) marks: Vec<Mark>,
}

/// How a force is drawn.
#[derive(Clone, Copy, Debug)]
pub(super) enum Drawn {
    /// An arrow, tail and head (picture), and how many arrows from its
    /// point in its direction were drawn before it (side by side).
    Arrow((f64, f64), (f64, f64), usize),
    /// Along the line of sight: ⊙ toward the viewer, ⊗ away.
    Sight((f64, f64), bool),
}

/// How each load's force of `pose` is drawn at `per_newton` m per N: `None`
/// where none is (no scale, a zero force, or one under [`LEAST_ARROW`] of the
/// longest). Arrows from one point in one direction (within 25°) go side
/// by side, each moved across its direction by [`BESIDE`] of the longest
/// arrow from the one before.
fn forces(pose: &Snapshot, view: View, per_newton: Option<f64>) -> Vec<Option<Drawn>> {
    let Some(k) = per_newton else { return vec![None; pose.loads.len()] };
    let longest = pose.loads.iter().map(|l| k * l.force.norm()).fold(0.0, f64::max);
    let mut drawn: Vec<Option<Drawn>> = Vec::new();
    for l in &pose.loads {
        let (length, p) = (k * l.force.norm(), pic(view, &l.at));
        let ((a, b), toward) = view.project(&(l.force * k));
        let across = a.hypot(b);
        if length == 0.0 || length < LEAST_ARROW * longest {
            drawn.push(None);
            continue;
        }
        if across < LEAST_ARROW * longest {
            drawn.push(Some(Drawn::Sight(p, toward > 0.0)));
            continue;
        }
        let (ux, uy) = (a / across, b / across);
        let along = |d: &Drawn| match d {
            Drawn::Arrow(from, to, _) => {
                let (d, e) = (to.0 - from.0, to.1 - from.1);
                (from.0 - p.0).hypot(from.1 - p.1) <= 0.2 * longest && d * ux + e * uy > 0.9 * d.hypot(e)
            }
            Drawn::Sight(..) => false,
        };
        let beside = drawn.iter().flatten().filter(|d| along(d)).count();
        let shift = BESIDE * longest * beside as f64;
        let from = (p.0 - uy * shift, p.1 + ux * shift);
        drawn.push(Some(Drawn::Arrow(from, (from.0 + a, from.1 + b), beside)));
    }
    drawn
}

/// How a moment is drawn: a turn about a point when along the line of
/// sight (`ccw` as the viewer sees it), else a double arrow (picture).
enum Turning {
    Turn((f64, f64), bool),
    Double((f64, f64), (f64, f64)),
}

fn moment(view: View, at: &V, m: &V, per_newton_metre: Option<f64>) -> Option<Turning> {
    if *m == V::zeros() {
        return None;
    }
    match picture_direction(view, m) {
        None => Some(Turning::Turn(pic(view, at), depth(view, m) > 0.0)),
        Some(_) => per_newton_metre.map(|k| Turning::Double(pic(view, at), pic(view, &(at + m * k)))),
    }
}

/// ⊙ (toward the viewer) or ⊗ at `at`, `r` px across.
pub(super) fn sight(at: (f64, f64), toward: bool, r: f64, color: Color) -> Vec<Mark> {
    let mut out = vec![Mark::Dot { at, shape: Marker::Circle, radius: r, color, filled: false }];
    out.push(match toward {
        true => Mark::Dot { at, shape: Marker::Circle, radius: 0.28 * r, color, filled: true },
        false => Mark::Label { at, offset: (0.0, 0.6 * r), text: "×".into(), color, anchor: Anchor::Middle },
    });
    out
}

/// One shape's marks: links, flexures and tendons in increasing depth, then its symbols and loads.
fn draw_shape(scene: &Scene, pose: &Snapshot, view: View, color: Color, sizes: &Sizes, loads: Loads) -> Vec<Mark> {
    let mut parts: Vec<Part> = solids::moving_geoms(scene, pose, view, color, sizes);
    let link_fill = Fill { color: color.tint(0.55), opacity: 0.55 };
    for pts in &pose.links {
        let flat: Vec<(f64, f64)> = pts.iter().map(|p| pic(view, p)).collect();
        let far = pts.iter().map(|p| depth(view, p)).fold(f64::INFINITY, f64::min);
        parts.push(Part {
            depth: if far.is_finite() { far - sizes.thick } else { 0.0 },
            marks: vec![Mark::Path {
                points: slab(&flat, sizes.thick),
                stroke: Some(Stroke::solid(color, 1.5)),
                fill: Some(link_fill),
                closed: true,
            }],
        });
    }
    for c in &pose.flexures {
        let (pts, top) = match (loads, &c.stress) {
            (Loads::Drawn { stress_top: Some(top) }, Some(stress)) => (&c.points, (top, stress)),
            _ => {
                let marks =
                    vec![line(c.points.iter().map(|p| pic(view, p)).collect(), Stroke::solid(color, FLEXURE_WIDTH))];
                parts.push(Part { depth: mean_depth(view, &c.points), marks });
                continue;
            }
        };
        // Each segment in the colour of its ends' mean stress, at its own depth.
        let (top, sigma) = top;
        for i in 0..pts.len() - 1 {
            let stroke = Stroke::solid(ramp(0.5 * (sigma[i] + sigma[i + 1]) / top), FLEXURE_WIDTH);
            let marks = vec![line(vec![pic(view, &pts[i]), pic(view, &pts[i + 1])], stroke)];
            parts.push(Part { depth: mean_depth(view, &pts[i..i + 2]), marks });
        }
    }
    for (k, pts) in pose.tendons.iter().enumerate() {
        let stroke = Stroke { color, width: 1.5, dash: TENDON_DASH[k % TENDON_DASH.len()] };
        for pair in pts.windows(2) {
            let marks = vec![line(vec![pic(view, &pair[0]), pic(view, &pair[1])], stroke)];
            parts.push(Part { depth: mean_depth(view, pair), marks });
        }
    }
    parts.sort_by(|a, b| a.depth.total_cmp(&b.depth));
    let mut out: Vec<Mark> = parts.into_iter().flat_map(|p| p.marks).collect();
    out.extend(symbols(pose, view, color, sizes));
    for (k, pts) in pose.tendons.iter().enumerate() {
        for p in pts {
            out.push(Mark::Dot { at: pic(view, p), shape: VIA[k % VIA.len()], radius: 4.0, color, filled: false });
        }
    }
    if let Loads::Drawn { .. } = loads {
        out.extend(solids::contact_marks(pose, view, color, sizes));
        for d in forces(pose, view, sizes.per_newton).into_iter().flatten() {
            match d {
                Drawn::Arrow(from, to, _) => out.push(Mark::Arrow { from, to, color, width: 2.5 }),
                Drawn::Sight(at, toward) => out.extend(sight(at, toward, 7.0, color)),
            }
        }
        for l in &pose.loads {
            match moment(view, &l.at, &l.moment, sizes.per_newton_metre) {
                Some(Turning::Turn(at, ccw)) => out.push(Mark::Turn { at, radius: 18.0, ccw, color, width: 2.0 }),
                Some(Turning::Double(from, to)) => {
                    // The second head a little behind the first.
                    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
                    let back = (0.03 * sizes.extent / dx.hypot(dy)).min(0.4);
                    let inner = (to.0 - back * dx, to.1 - back * dy);
                    out.push(Mark::Arrow { from, to, color, width: 2.0 });
                    out.push(Mark::Arrow { from, to: inner, color, width: 2.0 });
                }
                None => {}
            }
        }
    }
    out
}

/// The joints' and closures' symbols of a shape.
fn symbols(pose: &Snapshot, view: View, color: Color, sizes: &Sizes) -> Vec<Mark> {
    let mut out = Vec::new();
    let reach = 2.5 * sizes.thick;
    for j in &pose.joints {
        let root = pic(view, &j.at);
        match j.symbol {
            Symbol::Hinge => {
                // Its axis a line, unless seen end-on.
                if picture_direction(view, &j.axis).is_some() {
                    let points = vec![pic(view, &(j.at - j.axis * reach)), pic(view, &(j.at + j.axis * reach))];
                    out.push(line(points, Stroke::solid(color, 2.0)));
                }
                out.push(Mark::Dot { at: root, shape: Marker::Circle, radius: 6.0, color, filled: false });
            }
            Symbol::Ball => out.push(Mark::Dot { at: root, shape: Marker::Circle, radius: 5.0, color, filled: true }),
            Symbol::Slider => {
                let travel = Stroke { color, width: 2.0, dash: Dash::Dashed };
                out.push(line(vec![root, pic(view, &j.child)], travel));
                if let Some((a, b)) = picture_direction(view, &j.axis) {
                    let normal = (-b * 0.4 * sizes.thick, a * 0.4 * sizes.thick);
                    for side in [-1.0, 1.0] {
                        let (ox, oy) = (root.0 + side * normal.0, root.1 + side * normal.1);
                        let points = vec![(ox - reach * a, oy - reach * b), (ox + reach * a, oy + reach * b)];
                        out.push(line(points, Stroke::solid(color, 2.0)));
                    }
                }
                out.push(Mark::Dot { at: root, shape: Marker::Square, radius: 5.0, color, filled: false });
            }
        }
    }
    out
}

/// A hatched anchor at world point `at` of the ground: a bar across the
/// picture direction `away` (toward the mechanism), hatched on the far side.
fn anchor(view: View, at: &V, away: (f64, f64), sizes: &Sizes) -> Vec<Mark> {
    let (c, d) = (pic(view, at), away);
    let n = (-d.1, d.0);
    let (half, depth) = (3.0 * sizes.thick, 0.9 * sizes.thick);
    let p = |u: f64, v: f64| (c.0 + u * n.0 - v * d.0, c.1 + u * n.1 - v * d.1);
    let mut out = vec![Mark::Path {
        points: vec![p(-half, 0.0), p(half, 0.0), p(half, depth), p(-half, depth)],
        stroke: Some(Stroke::solid(GROUND, 1.5)),
        fill: Some(Fill { color: GROUND.tint(0.4), opacity: 0.8 }),
        closed: true,
    }];
    let hatch = 1.6 * sizes.thick;
    for i in 0..5 {
        let u = -half + 2.0 * half * (f64::from(i) + 0.5) / 5.0;
        out.push(line(vec![p(u, depth), p(u - hatch, depth + hatch)], Stroke::solid(GROUND, 1.2)));
    }
    out
}

/// The ground's anchors: one at each joint leaving it (unloaded), one at
/// each other point attached to it unless one is drawn within a bar's length.
fn ground(scene: &Scene, rest: &Snapshot, view: View, sizes: &Sizes) -> Vec<Mark> {
    let mut out = Vec::new();
    let up = (0.0, 1.0);
    let mut placed: Vec<V> = Vec::new();
    for (root, away) in &rest.leaving {
        out.extend(anchor(view, root, picture_direction(view, away).unwrap_or(up), sizes));
        placed.push(*root);
    }
    for r in &scene.ground {
        let p = pic(view, r);
        let apart = |q: &V| {
            let q = pic(view, q);
            (q.0 - p.0).hypot(q.1 - p.1) > 6.0 * sizes.thick
        };
        if placed.iter().all(apart) {
            out.extend(anchor(view, r, up, sizes));
            placed.push(*r);
        }
    }
    out
}

/// The points a mark occupies (picture units).
fn mark_points(mark: &Mark) -> Vec<(f64, f64)> {
    match mark {
        Mark::Path { points, .. } => points.clone(),
        Mark::Dot { at, .. } | Mark::Turn { at, .. } | Mark::Label { at, .. } => vec![*at],
        Mark::Arrow { from, to, .. } => vec![*from, *to],
    }
}

/// The axis triad, left of everything in `marks`, its arrows a sixth of the
/// drawing's height or width; an axis along the line of sight would be ⊙ or ⊗.
fn triad(view: View, marks: &[Mark]) -> Vec<Mark> {
    let pts: Vec<(f64, f64)> = marks.iter().flat_map(mark_points).collect();
    let (mut u0, mut u1, mut v0, mut v1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (u, v) in &pts {
        (u0, u1, v0, v1) = (u0.min(*u), u1.max(*u), v0.min(*v), v1.max(*v));
    }
    if u0 > u1 {
        (u0, u1, v0, v1) = (0.0, 1.0, 0.0, 1.0);
    }
    let a = 0.16 * (u1 - u0).max(v1 - v0).max(1e-9);
    let axes = [("x", V::x()), ("y", V::y()), ("z", V::z())];
    let tips: Vec<((f64, f64), f64)> = axes.iter().map(|(_, e)| view.project(e)).collect();
    let hi_u = tips.iter().fold(0.0_f64, |h, t| h.max(t.0.0));
    let lo_v = tips.iter().fold(0.0_f64, |l, t| l.min(t.0.1));
    // The triad's right edge half an arrow left of the drawing, its bottom level with the drawing's.
    let o = (u0 - 0.5 * a - a * hi_u, v0 - a * lo_v);
    let (mut out, mut along_sight) = (Vec::new(), Vec::new());
    for (i, ((name, _), ((du, dv), toward))) in axes.iter().zip(&tips).enumerate() {
        let n = du.hypot(*dv);
        if n > 1e-9 {
            let to = (o.0 + a * du, o.1 + a * dv);
            out.push(Mark::Arrow { from: o, to, color: KEY, width: 1.5 });
            let (ux, uy) = (du / n, dv / n);
            let offset = (8.0 * ux, -12.0 * uy + 6.0);
            out.push(Mark::Label { at: to, offset, text: (*name).into(), color: KEY, anchor: anchor_along(ux) });
        } else {
            // Over the other arrows' tails, named opposite them.
            along_sight.extend(sight(o, *toward > 0.0, 9.0, KEY));
            let (su, sv) = tips
                .iter()
                .enumerate()
                .filter(|(k, _)| *k != i)
                .fold((0.0, 0.0), |s, (_, t)| (s.0 + t.0.0, s.1 + t.0.1));
            let n = su.hypot(sv).max(1e-9);
            let (ux, uy) = (-su / n, -sv / n);
            let offset = (18.0 * ux, -18.0 * uy + 6.0);
            along_sight.push(Mark::Label { at: o, offset, text: (*name).into(), color: KEY, anchor: anchor_along(ux) });
        }
    }
    out.extend(along_sight);
    out
}

/// Names beside the last shape's loads: past a force's head (stacked when
/// side by side), beside a force along the line of sight, else at its moment.
fn load_names(scene: &Scene, pose: &Snapshot, view: View, color: Color, sizes: &Sizes) -> Vec<Mark> {
    let mut out = Vec::new();
    let drawn = forces(pose, view, sizes.per_newton);
    for (((name, _), l), d) in scene.loads.iter().zip(&pose.loads).zip(drawn) {
        let text = name.clone();
        let (at, offset, anchor) = match (d, moment(view, &l.at, &l.moment, sizes.per_newton_metre)) {
            (Some(Drawn::Arrow(from, to, beside)), _) => {
                let n = (to.0 - from.0).hypot(to.1 - from.1);
                let (ux, uy) = ((to.0 - from.0) / n, (to.1 - from.1) / n);
                // Away from the arrow: up past an upward head, else down (px: y down).
                let stack = NAME_STEP * beside as f64 * if uy > 0.3 { -1.0 } else { 1.0 };
                (to, (10.0 * ux, -14.0 * uy + 6.0 + stack), anchor_along(ux))
            }
            (Some(Drawn::Sight(at, _)), _) => (at, (12.0, -12.0), Anchor::Start),
            (None, Some(Turning::Turn(at, _))) => (at, (24.0, -18.0), Anchor::Start),
            (None, Some(Turning::Double(from, to))) => {
                let n = (to.0 - from.0).hypot(to.1 - from.1).max(f64::MIN_POSITIVE);
                let (ux, uy) = ((to.0 - from.0) / n, (to.1 - from.1) / n);
                (to, (10.0 * ux, -14.0 * uy + 6.0), anchor_along(ux))
            }
            (None, None) => continue,
        };
        out.push(Mark::Label { at, offset, text, color, anchor });
    }
    out
}

/// The legend's entries for the loads: each force (and moment) with its
/// value or range over the shapes, each weight, and the arrows' scales.
fn load_entries(scene: &Scene, loaded: &[(String, Snapshot)], view: View, sizes: &Sizes) -> Vec<Entry> {
    let mut out = Vec::new();
    let n = scene.components;
    for (i, (name, body)) in scene.loads.iter().enumerate() {
        let forces: Vec<V> = loaded.iter().map(|(_, p)| p.loads[i].force).collect();
        let moments: Vec<V> = loaded.iter().map(|(_, p)| p.loads[i].moment).collect();
        let norms = |v: &[V]| v.iter().map(|x| x.norm()).collect::<Vec<f64>>();
        let pushes = forces.iter().any(|f| *f != V::zeros());
        let Some(body) = body else {
            if pushes {
                out.push(Entry {
                    swatch: Swatch::Arrow(KEY),
                    label: format!("{name}: {}", values(&norms(&forces), "N")),
                });
            }
            continue;
        };
        let turns = moments.iter().any(|m| *m != V::zeros());
        let same = |v: &[V], unit: &str| match v.windows(2).all(|w| w[0] == w[1]) {
            true => format!("{} {unit}", vector(&v[0], n)),
            false => values(&norms(v), unit),
        };
        if pushes || !turns {
            let label = format!("force {name} on {body}: {}", same(&forces, "N"));
            out.push(Entry { swatch: Swatch::Arrow(KEY), label });
        }
        if !turns {
            continue;
        }
        // Seen along its axis, a moment turns one way or the other; else it is a vector.
        let label = if moments.iter().all(|m| picture_direction(view, m).is_none()) {
            let signed: Vec<f64> = moments.iter().map(|m| depth(view, m)).collect();
            let positive = signed.iter().all(|&x| x > 0.0);
            let value = if positive || signed.iter().all(|&x| x < 0.0) {
                let sense = if positive { "counter-clockwise" } else { "clockwise" };
                format!("{} {sense}", values(&norms(&moments), "N·m"))
            } else {
                format!("{} (+: counter-clockwise)", values(&signed, "N·m"))
            };
            (Swatch::Turn(KEY), value)
        } else {
            (Swatch::Arrow(KEY), format!("{} (double arrow, right-hand rule)", same(&moments, "N·m")))
        };
        out.push(Entry { swatch: label.0, label: format!("moment {name} on {body}: {}", label.1) });
    }
    if let Some(k) = sizes.per_newton {
        out.push(Entry { swatch: Swatch::Note, label: format!("force arrows: {} m per N", short(k)) });
    }
    let doubles = loaded.iter().flat_map(|(_, p)| &p.loads).any(|l| picture_direction(view, &l.moment).is_some());
    if let (Some(k), true) = (sizes.per_newton_metre, doubles) {
        out.push(Entry { swatch: Swatch::Note, label: format!("moment arrows: {} m per N·m", short(k)) });
    }
    out
}

/// The legend's keys for the joints, flexures and tendons every shape shows.
fn keys(scene: &Scene, rest: &Snapshot, loaded: &[(String, Snapshot)], view: View) -> Vec<Entry> {
    let mut out = Vec::new();
    if !rest.flexures.is_empty() {
        let swatch = Swatch::Line(Some(Stroke::solid(KEY, FLEXURE_WIDTH)), None);
        out.push(Entry { swatch, label: "flexure".into() });
    }
    let drawn = |want: Symbol, closure: bool| rest.joints.iter().any(|j| j.symbol == want && j.closure == closure);
    let (hinge, pin) = (drawn(Symbol::Hinge, false), drawn(Symbol::Hinge, true));
    if hinge || pin {
        let what = match (hinge, pin) {
            (true, true) => "revolute joint or pin",
            (true, false) => "revolute joint",
            _ => "pin",
        };
        let seen = rest.joints.iter().any(|j| j.symbol == Symbol::Hinge && picture_direction(view, &j.axis).is_some());
        let (line, label) = match seen {
            true => (Some(Stroke::solid(KEY, 2.0)), format!("{what} (line along its axis)")),
            false => (None, what.to_string()),
        };
        out.push(Entry { swatch: Swatch::Line(line, Some((Marker::Circle, KEY, false))), label });
    }
    if drawn(Symbol::Ball, false) || drawn(Symbol::Ball, true) {
        let swatch = Swatch::Line(None, Some((Marker::Circle, KEY, true)));
        let label = if drawn(Symbol::Ball, false) { "ball joint" } else { "ball closure" };
        out.push(Entry { swatch, label: label.into() });
    }
    if drawn(Symbol::Slider, false) {
        let stroke = Stroke { color: KEY, width: 2.0, dash: Dash::Dashed };
        let swatch = Swatch::Line(Some(stroke), Some((Marker::Square, KEY, false)));
        out.push(Entry { swatch, label: "slider (double line along its axis, its travel dashed)".into() });
    }
    for (k, name) in scene.tendons.iter().enumerate() {
        let tensions: Vec<f64> = loaded.iter().map(|(_, p)| p.tensions[k]).collect();
        let stroke = Stroke { color: KEY, width: 1.5, dash: TENDON_DASH[k % TENDON_DASH.len()] };
        out.push(Entry {
            swatch: Swatch::Line(Some(stroke), Some((VIA[k % VIA.len()], KEY, false))),
            label: format!("tendon {name}: {}", values(&tensions, "N")),
        });
    }
    out
}

/// The figure of a mechanism's unloaded and loaded shapes seen from
/// `view` (the module docs), and the force arrows' scale (m per N) if any
/// force is drawn. With `stress`, loaded flexures with a section geometry
/// are coloured by their stress; `marks` adds yield strengths to the colour
/// bar and a sweep's stability note.
pub fn figure(
    scene: &Scene,
    title: &str,
    rest: &Snapshot,
    loaded: &[(String, Snapshot)],
    marks: &Marks,
    view: View,
    stress: bool,
) -> (Figure, Option<f64>) {
    let (x_label, y_label) = view.axis_labels();
    let mut fig = Figure::new(title, x_label, y_label);
    fig.equal_aspect = true;
    fig.width = 1200.0;
    fig.height = 760.0;
    fig.place = Place::Outside;
    fig.fit_height = true;

    // Sizes from the unloaded mechanism in the world (the same in every
    // view): links 2.4 % of it thick, the longest arrow about a quarter of it.
    // Bounded geoms by their bounding balls: a block on a slider has no link to size the view by.
    let solids: Vec<V> = ball_ends(&rest.geoms).collect();
    let pts: Vec<&V> = rest
        .links
        .iter()
        .flatten()
        .chain(&scene.ground)
        .chain(&rest.roots)
        .chain(&rest.origins)
        .chain(&solids)
        .collect();
    let span = |i: usize| {
        let (lo, hi) = bounds(pts.iter().copied(), i);
        if hi > lo { hi - lo } else { 0.0 }
    };
    let longest_flexure = rest.flexures.iter().map(|c| c.length).fold(0.0, f64::max);
    let extent = span(0).max(span(1)).max(span(2)).max(longest_flexure).max(1e-9);
    // A plane's band spans what is drawn: the shapes too, not the rest
    // shape alone (a ball thrown 0.2 m along its floor rested past a band
    // of 25 mm, floating).
    let drawn: Vec<V> = pts
        .iter()
        .map(|p| **p)
        .chain(loaded.iter().flat_map(|(_, s)| {
            let centrelines = s.flexures.iter().flat_map(|c| &c.points);
            let points = s.links.iter().flatten().chain(&s.origins).chain(&s.roots).chain(centrelines);
            points.copied().chain(ball_ends(&s.geoms))
        }))
        .collect();
    let middle = |i: usize| {
        let (lo, hi) = bounds(drawn.iter(), i);
        if hi >= lo { 0.5 * (lo + hi) } else { 0.0 }
    };
    let half = V::from_fn(|i, _| {
        let (lo, hi) = bounds(drawn.iter(), i);
        if hi > lo { 0.5 * (hi - lo) } else { 0.0 }
    });
    let all_loads = || loaded.iter().flat_map(|(_, p)| &p.loads);
    let largest = all_loads().map(|l| l.force.norm()).fold(solids::largest_contact(loaded), f64::max);
    let largest_moment = all_loads().map(|l| l.moment.norm()).fold(0.0, f64::max);
    let sizes = Sizes {
        extent,
        centre: V::new(middle(0), middle(1), middle(2)),
        half,
        thick: 0.012 * extent,
        largest,
        per_newton: (largest > 0.0).then(|| round_down(0.25 * extent / largest)),
        per_newton_metre: (largest_moment > 0.0).then(|| round_down(0.25 * extent / largest_moment)),
    };
    // The colour bar from 0 to the largest stress (1 MPa if none is
    // loaded), on past the highest yield strength so that its mark shows.
    let highest_yield = marks.yields.iter().map(|y| y.1).fold(0.0, f64::max);
    let peaks = loaded.iter().flat_map(|(_, p)| &p.flexures).filter_map(|c| c.peak);
    let stress_top = peaks
        .fold(None, |top: Option<f64>, p| Some(top.unwrap_or(0.0).max(p)))
        .filter(|_| stress)
        .map(|top| if top > 0.0 { top } else { 1e6 })
        .map(|top| top.max(1.05 * highest_yield));

    fig.marks.extend(ground(scene, rest, view, &sizes));
    fig.marks.extend(solids::ground_geoms(scene, rest, view, &sizes));
    let ground_swatch = Swatch::Area(Fill { color: GROUND.tint(0.4), opacity: 0.8 }, Stroke::solid(GROUND, 1.5));
    fig.legend.push(Entry { swatch: ground_swatch, label: "ground".into() });
    let link = |c: Color| Swatch::Area(Fill { color: c.tint(0.55), opacity: 0.55 }, Stroke::solid(c, 1.5));
    fig.marks.extend(draw_shape(scene, rest, view, GRAY, &sizes, Loads::Hidden));
    fig.legend.push(Entry { swatch: link(GRAY), label: "unloaded".into() });
    for (i, (label, pose)) in loaded.iter().enumerate() {
        let color = shape_color(i, loaded.len());
        fig.marks.extend(draw_shape(scene, pose, view, color, &sizes, Loads::Drawn { stress_top }));
        fig.legend.push(Entry { swatch: link(color), label: label.clone() });
    }
    if let Some((_, pose)) = loaded.last() {
        let color = shape_color(loaded.len() - 1, loaded.len());
        fig.marks.extend(load_names(scene, pose, view, color, &sizes));
        fig.marks.extend(solids::contact_values(pose, view, color, &sizes));
    }
    // The axes of the other views are the picture's own, named on its axes.
    if view == View::Iso {
        let axes = triad(view, &fig.marks);
        fig.marks.extend(axes);
    }

    fig.legend.extend(keys(scene, rest, loaded, view));
    fig.legend.extend(load_entries(scene, loaded, view, &sizes));
    fig.legend.extend(solids::contact_entries(scene, loaded));
    if let Some(limit) = &marks.limit {
        fig.legend.push(Entry { swatch: Swatch::Note, label: limit.clone() });
    }
    fig.legend.push(Entry { swatch: Swatch::Note, label: view.description().into() });
    let plain = rest.flexures.iter().any(|c| c.stress.is_none());
    if let Some(top) = stress_top {
        let mut label = format!("flexures' {} stress (MPa)", scene.stress);
        if !marks.yields.is_empty() {
            let named: Vec<String> =
                marks.yields.iter().map(|(name, y)| format!("{name} {} MPa", short(y / 1e6))).collect();
            label += &format!("; black line: yield strength ({})", named.join(", "));
        }
        let bar_marks = marks.yields.iter().map(|y| y.1 / 1e6).collect();
        fig.color_bar = Some(ColorBar { label, lo: 0.0, hi: top / 1e6, marks: bar_marks });
        let label = match plain {
            true => format!(
                "loaded flexures coloured by stress; those given by {} (no section geometry) in their shape's colour",
                scene.plain
            ),
            false => format!("loaded flexures coloured by {} stress", scene.stress),
        };
        fig.legend.push(Entry { swatch: Swatch::Note, label });
    } else if stress && plain {
        let label = format!("no flexure has a section geometry (given by {}): no stress to colour", scene.plain);
        fig.legend.push(Entry { swatch: Swatch::Note, label });
    }
    (fig, sizes.per_newton)
}

/// The samples `draw --simulate` draws of a run of `samples` samples: five
/// from the first to the last, evenly spaced (fewer if the run is shorter).
///
/// # Example
/// ```
/// use flexure_cli::drawing::snapshot_samples;
/// assert_eq!(snapshot_samples(101), [0, 25, 50, 75, 100]);
/// assert_eq!(snapshot_samples(2), [0, 1]);
/// assert!(snapshot_samples(0).is_empty());
/// ```
pub fn snapshot_samples(samples: usize) -> Vec<usize> {
    if samples == 0 {
        return Vec::new();
    }
    let last = samples - 1;
    let mut picked: Vec<usize> = (0..5).map(|k| (k * last + 2) / 4).collect();
    picked.dedup();
    picked
}

/// A moving body over a run: its rotation from the ground frame as a
/// rotation vector (angle × unit axis, rad) and its origin (m), each sample.
pub struct Track {
    pub name: String,
    pub rotation: Vec<V>,
    pub position: Vec<V>,
}

/// What [`motion_figures`] draws.
pub struct MotionFigures {
    /// The snapshots over the rest shape, then the bodies' rotations and
    /// origins against time: for [`flexure_chart::write_stack`].
    pub figures: Vec<Figure>,
    /// The times of the snapshots (s).
    pub snapshots: Vec<f64>,
    /// The force arrows' scale (m per N), if any force is drawn.
    pub per_newton: Option<f64>,
}

/// `draw --simulate`: the snapshots (each in its colour, labelled by its
/// time) over the rest shape as one [`figure`], then two charts against
/// time: each body's rotation vector $\theta$ (rad) and its origin (mm),
/// x solid, y dashed, z dotted, each body in its colour: the components
/// the scene moves in (a planar body's θz, x and y).
pub fn motion_figures(
    scene: &Scene,
    title: &str,
    (rest, snapshots): (&Snapshot, &[(String, Snapshot)]),
    (time, tracks): (&[f64], &[Track]),
    picked: &[usize],
    view: View,
    stress: bool,
) -> Result<MotionFigures, String> {
    let duration = time.last().copied().unwrap_or(0.0);
    let title = format!("{title}: motion over {} s", short(duration));
    let (shapes, per_newton) = figure(scene, &title, rest, snapshots, &Marks::default(), view, stress);
    // Each body by colour, each component by dash: the legend lists the
    // bodies once and the dashes once. Past the six colours, each round of
    // them adds a marker shape, so that no two bodies look alike.
    let color = |i: usize| COLORS[i % COLORS.len()];
    let rounds = [None, Some(Marker::Circle), Some(Marker::Square), Some(Marker::Triangle), Some(Marker::Diamond)];
    let marker = |i: usize| rounds[(i / COLORS.len()) % rounds.len()];
    let every = time.len().div_ceil(8).max(1);
    let styled = |s: Series, i: usize| match marker(i) {
        Some(shape) => s.marked(shape, every, (i % COLORS.len()) * every / COLORS.len()),
        None => s,
    };
    let dashes = [Dash::Solid, Dash::Dashed, Dash::Dotted];
    let chart =
        |title: &'static str| Chart { title, x_label: "time (s)", y_label: "", log_y: false, equal_aspect: false };
    let mut figures = vec![shapes];
    for rotation in [true, false] {
        let (title, unit, names, scale) = match rotation {
            true => ("Body rotations", "(rad), ground frame", ["θx", "θy", "θz"], 1.0),
            false => ("Body origins", "(mm), ground frame", ["x", "y", "z"], 1e3),
        };
        let kept: Vec<usize> = if rotation { scene.rotations.to_vec() } else { (0..scene.components).collect() };
        let dash = |c: usize| kept.iter().position(|&k| k == c).unwrap_or(0);
        let mut series = Vec::new();
        for (i, t) in tracks.iter().enumerate() {
            for &c in &kept {
                let along = time
                    .iter()
                    .zip(if rotation { &t.rotation } else { &t.position })
                    .map(|(s, v)| (*s, v[c] * scale))
                    .collect();
                series.push(styled(Series::line("", along, color(i)).dashed(dashes[dash(c)]), i));
            }
        }
        let mut fig = chart_figure(&chart(title), &series)?;
        let named = kept.iter().map(|&c| names[c]).collect::<Vec<_>>().join(", ");
        fig.y_label = match (scale == 1.0, kept.len()) {
            (true, 3) => "θ = angle × axis (rad), ground frame".into(),
            _ => format!("{named} {unit}"),
        };
        let bodies = tracks.iter().enumerate().map(|(i, t)| Entry {
            swatch: Swatch::Line(Some(Stroke::solid(color(i), 2.0)), marker(i).map(|m| (m, color(i), true))),
            label: t.name.clone(),
        });
        let key = kept.iter().map(|&c| Entry {
            swatch: Swatch::Line(Some(Stroke { color: GRAY, width: 2.0, dash: dashes[dash(c)] }), None),
            label: names[c].to_string(),
        });
        fig.legend = bodies.chain(key).collect();
        (fig.width, fig.height, fig.place) = (1200.0, 420.0, Place::Outside);
        figures.push(fig);
    }
    Ok(MotionFigures { figures, snapshots: picked.iter().map(|&k| time[k]).collect(), per_newton })
}

#[cfg(test)]
mod tests {
    use super::{hull, slab};
    use flexure::mechanism::file::from_toml;
    use flexure::mechanism::statics::{Settings, assemble_unloaded, body_frames};

    #[test]
    fn a_hull_keeps_the_corners_only() {
        let h = hull(vec![(0.0, 0.0), (1.0, 0.0), (0.5, 0.5), (1.0, 1.0), (0.0, 1.0), (0.5, 0.0)]);
        assert_eq!(h, [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]);
    }

    /// The parallelogram's stage is drawn across both flexure tips: the
    /// file puts them 0.04 m apart, at x = 0 and x = 0.04 when unloaded.
    #[test]
    fn a_stage_spans_every_leg() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/parallelogram.toml");
        let m = from_toml(&std::fs::read_to_string(path).unwrap()).unwrap();
        let s = assemble_unloaded(&m, &Settings::default()).unwrap();
        let f = body_frames(&m, &s);
        let stage = m.body("stage").unwrap();
        let pts: Vec<(f64, f64)> =
            m.attachments(stage).iter().map(|r| f.bodies[stage].act(r)).map(|p| (p.x, p.y)).collect();
        let r = 1e-3;
        let xs: Vec<f64> = slab(&pts, r).iter().map(|p| p.0).collect();
        let (lo, hi) = xs.iter().fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
        // Closure solved to ~1e-12 m; the slab reaches r beyond each tip.
        assert!((lo + r).abs() < 1e-9 && (hi - 0.04 - r).abs() < 1e-9, "{lo} {hi}");
    }
}
