//! `flexure draw` of a spatial mechanism: its shapes projected onto a
//! picture plane ([`View`], [`super::projection`]) and drawn as siblings of
//! the planar drawing (`mechanism/drawing.rs`): the same colours, legend,
//! stress colour bar, unloaded (grey) and loaded styles, load arrows and
//! names.
//!
//! # What is drawn
//!
//! - **Flexures**: the centreline through 41 sections (the planar drawing's count)
//!   ([`flexure::spatial::shape`], in the joint's root frame, turned into
//!   the world by the root frame $A$: $p_{world} = A\thinspace p(s)$), thick.
//! - **Rigid bodies**: the projected convex hull of every point attached to
//!   them ([`attachments`]), grown by 1.2 % of the mechanism's size, as the
//!   planar links.
//! - **Joints**, read through the joint interface alone (so a new kind is
//!   drawn without a case here): a rotation of one coordinate (a hinge) as a
//!   hollow circle with a short line along its projected axis $R_A S^{\omega}$,
//!   a rotation of more (a ball joint) as a filled circle, a translation (a
//!   slider) as a square and a short double line along its projected axis
//!   $R_A S^{p}$ with its travel dashed; a weld as nothing (its bodies' hulls
//!   meet). Pin closures as hinges, ball closures as ball joints.
//! - **Tendons**: thin polylines through their via points, told apart by
//!   dash and via marker.
//! - **Loads**: forces (and weights) as arrows $k\thinspace f$ long, $k$ the
//!   planar drawing's round scale (a quarter of the mechanism's size for the
//!   largest force); moments as double-headed arrows along the moment
//!   vector (right-hand rule) at a scale of their own.
//! - **Ground**: a hatched anchor at each point attached to it, its bar
//!   across the joint that leaves it.
//! - **An axis triad** left of the drawing, x, y and z as arrows; an axis
//!   along the line of sight is a circle, with a dot when it points at the
//!   viewer and a cross when it points away.
//!
//! # Depth
//!
//! Within each shape, the bodies, the flexures' segments and the tendons'
//! segments are painted in increasing depth $p\cdot t$ ([`View::project`]),
//! so near parts cover far ones: a segment at the mean depth of its ends, a
//! body at the depth of its back (its farthest point less its half
//! thickness), so that a link covers what
//! lies wholly behind it but not the flexures and tendons it carries
//! (which end inside its hull, as the planar drawing draws them over
//! their links). Joint symbols,
//! via points and loads go on top of their shape, as annotations. Shapes are
//! layered as the planar drawing layers them: the unloaded shape first, then
//! each loaded one in order.
//!
//! # Stress
//!
//! With `stress`, each segment of a loaded flexure whose section has a
//! shape (a rectangle or a circle) is coloured by the mean of its ends' peak
//! von Mises stress over the section ([`flexure::spatial::SpatialPoint::stress`],
//! of the curvature's change from rest), on the planar ramp from 0 to the
//! largest peak along any flexure in any loaded shape
//! ([`flexure::spatial::peak_stress`]), the colour bar's top (MPa). A
//! flexure given by its stiffnesses alone has no geometry, so no stress: it
//! keeps its shape's colour, and a note says so.

pub use super::drawing::Marks;
use super::drawing::{
    FLEXURE_SAMPLES, FLEXURE_WIDTH, GROUND, KEY, SHAPES, TENDON_DASH, VIA, round_down, short, slab, values,
};
pub use super::projection::View;
use flexure::dynamics::spatial::SpatialSimulation;
use flexure::mechanism::Holds;
use flexure::mechanism::spatial::SpatialMechanism;
use flexure::mechanism::spatial::kinematics::{SpatialFrames, frames};
use flexure::mechanism::spatial::statics::SpatialSolution;
use flexure::spatial::SpatialFlexure;
use flexure_chart::{
    Anchor, COLORS, ColorBar, Dash, Entry, Figure, Fill, GRAY, Mark, Marker, Place, Stroke, Swatch, ramp,
};
use flexure_chart::{Chart, Color, Series, chart_figure};
use nalgebra::{Point3, Rotation3, Vector3};

/// Every point attached to body `b`, in its frame
/// ([`SpatialMechanism::attachments`]).
pub fn attachments(m: &SpatialMechanism, b: usize) -> Vec<Point3<f64>> {
    m.attachments(b)
}

/// A part of one shape, painted at its depth (larger: nearer).
struct Part {
    depth: f64,
    marks: Vec<Mark>,
}

/// The sizes every shape of one figure shares.
#[derive(Clone, Copy)]
struct Sizes {
    /// The mechanism's size (m): the largest span of its unloaded points, or its longest flexure.
    extent: f64,
    /// The links' half thickness (m): 1.2 % of the size.
    thick: f64,
    /// Force arrows' length per newton (m/N), if any force acts.
    per_newton: Option<f64>,
    /// Moment arrows' length per newton metre (m/(N·m)), if any moment acts.
    per_newton_metre: Option<f64>,
}

/// How a shape's loads are drawn: not at all (the unloaded shape), or
/// with its arrows, its flexures coloured by stress up to `stress_top`
/// (Pa) when that is given.
#[derive(Clone, Copy)]
enum Loads {
    Hidden,
    Drawn { stress_top: Option<f64> },
}

/// The mark of a rigid joint with coordinates, read from the joint interface.
#[derive(Clone, Copy, PartialEq)]
enum Symbol {
    /// One rotation: a hinge about the world axis of its motion subspace.
    Hinge,
    /// Rotations about more than one axis: a ball joint.
    Ball,
    /// A translation: a slider.
    Slider,
}

fn symbol(j: &dyn flexure::mechanism::Joint<flexure::space::Spatial>) -> Option<Symbol> {
    if j.flexure().is_some() || j.dof() == 0 {
        None
    } else if j.is_translation() {
        Some(Symbol::Slider)
    } else if j.dof() == 1 {
        Some(Symbol::Hinge)
    } else {
        Some(Symbol::Ball)
    }
}

/// The symbol of spatial joint `j`: `None` for a flexure (drawn as its
/// centreline) and a weld.
fn joint_symbol(m: &SpatialMechanism, j: usize) -> Option<Symbol> {
    let kind = &m.joints[j].kind;
    if kind.flexure().is_some() { None } else { symbol(kind.joint()) }
}

/// A picture point from a world point.
fn pic(view: View, p: &Vector3<f64>) -> (f64, f64) {
    view.project(p).0
}

fn depth(view: View, p: &Vector3<f64>) -> f64 {
    view.project(p).1
}

/// The mean depth of world points.
fn mean_depth(view: View, pts: &[Vector3<f64>]) -> f64 {
    if pts.is_empty() { 0.0 } else { pts.iter().map(|p| depth(view, p)).sum::<f64>() / pts.len() as f64 }
}

/// A flexure's coordinates in the solution `s`.
fn alpha<'a>(m: &SpatialMechanism, s: &'a SpatialSolution, j: usize, fl: &SpatialFlexure) -> &'a [f64] {
    let o = m.joints[j].offset;
    &s.q[o..o + fl.coordinates()]
}

/// Whether a flexure's section has a shape, so a stress.
fn shaped(fl: &SpatialFlexure) -> bool {
    fl.section().stress(0.0, [0.0; 3]).is_ok()
}

/// The largest peak von Mises stress (Pa) along any flexure with a shaped
/// section in any of `shapes` ([`flexure::spatial::peak_stress`]), or `None`
/// if no flexure has a shaped section.
///
/// # Example
/// ```
/// use flexure_cli::spatial_drawing::stress_max;
/// use flexure::mechanism::spatial::{SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism};
/// use flexure::mechanism::spatial::statics::solve;
/// use flexure::section::{Profile, SpatialSection};
/// use flexure::spatial::SpatialFlexure;
/// use nalgebra::{Isometry3, Vector3};
/// let rod = SpatialFlexure::new(0.02, SpatialSection::circle(200e9, 0.3, Profile::Constant(1e-3)).unwrap(), [1, 1, 1]).unwrap();
/// let spec = SpatialJointSpec {
///     name: "rod".into(), kind: SpatialJointKind::Flexure(Box::new(rod)),
///     parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default(),
/// };
/// let bodies = vec![SpatialBody::massless("ground"), SpatialBody::massless("tip")];
/// let m = SpatialMechanism::new(bodies, vec![spec], vec![], vec![], vec![], Vector3::zeros()).unwrap();
/// let mut s = solve(&m, &Default::default()).unwrap();
/// // A uniform bend about y of 0.02 rad over 20 mm: 1 1/m, σ = E κ d/2 = 100 MPa.
/// s.q = vec![0.0, 0.02, 0.0];
/// let top = stress_max(&m, &[("bent".into(), s)]).unwrap().unwrap();
/// assert!((top - 100e6).abs() < 1e-3);
/// ```
pub fn stress_max(m: &SpatialMechanism, shapes: &[(String, SpatialSolution)]) -> Result<Option<f64>, String> {
    let mut top: Option<f64> = None;
    for (label, s) in shapes {
        check_shape(m, label, s)?;
        for (j, spec) in m.joints.iter().enumerate() {
            if let Some(fl) = spec.kind.flexure().filter(|fl| shaped(fl)) {
                let peak = flexure::spatial::peak_stress(fl, alpha(m, s, j, fl))
                    .map_err(|e| format!("shape {label:?}, flexure {}: {}", spec.name, crate::describe(e)))?;
                top = Some(top.unwrap_or(0.0).max(peak.stress.von_mises));
            }
        }
    }
    Ok(top)
}

/// Checks that a shape has one finite coordinate per coordinate of `m`.
fn check_shape(m: &SpatialMechanism, label: &str, s: &SpatialSolution) -> Result<(), String> {
    if s.q.len() != m.dof() {
        return Err(format!("shape {label:?}: q has {} coordinates, the mechanism {}", s.q.len(), m.dof()));
    }
    if let Some((i, v)) = s.q.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(format!("shape {label:?}: q[{i}] = {v}, not finite"));
    }
    if s.loads.validate(m).is_err() {
        return Err(format!(
            "shape {label:?}: its loads do not fit the mechanism (one tension per tendon, one wrench per force)"
        ));
    }
    Ok(())
}

/// The forces (N, world) a solution applies: each point load's, then each weight's.
fn force_vectors(m: &SpatialMechanism, s: &SpatialSolution) -> Vec<Vector3<f64>> {
    let g = s.loads.gravity;
    let weights = m.bodies.iter().filter(|b| b.mass > 0.0).map(move |b| g * b.mass);
    s.loads.force.iter().map(|w| w.fixed_rows::<3>(3).into_owned()).chain(weights).collect()
}

/// Where each load of [`force_vectors`] acts: (body, point in its frame).
fn load_places(m: &SpatialMechanism) -> Vec<(usize, Point3<f64>)> {
    let heavy = m.bodies.iter().enumerate().filter(|(_, b)| b.mass > 0.0).map(|(i, b)| (i, b.com));
    m.forces.iter().map(|p| (p.body, p.at)).chain(heavy).collect()
}

/// A straight line in the picture.
fn line(points: Vec<(f64, f64)>, stroke: Stroke) -> Mark {
    Mark::Path { points, stroke: Some(stroke), fill: None, closed: false }
}

/// A unit picture direction, or `None` if `v` is (nearly) along the line of sight.
fn picture_direction(view: View, v: &Vector3<f64>) -> Option<(f64, f64)> {
    let (a, b) = pic(view, v);
    let n = a.hypot(b);
    (n > 1e-6 * v.norm() && n > 0.0).then(|| (a / n, b / n))
}

/// A double-headed arrow from `from` to `to` (a moment vector): the second
/// head `gap` (m) behind the first.
fn double_arrow(from: (f64, f64), to: (f64, f64), gap: f64, color: Color) -> [Mark; 2] {
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let len = dx.hypot(dy);
    let back = if len > 0.0 { (gap / len).min(0.4) } else { 0.0 };
    let inner = (to.0 - back * dx, to.1 - back * dy);
    [Mark::Arrow { from, to, color, width: 2.0 }, Mark::Arrow { from, to: inner, color, width: 2.0 }]
}

/// One shape's marks, bodies, flexures and tendons in increasing depth, then its symbols and loads.
fn draw_shape(
    m: &SpatialMechanism,
    s: &SpatialSolution,
    view: View,
    color: Color,
    sizes: &Sizes,
    loads: Loads,
) -> Result<Vec<Mark>, String> {
    let f = frames(m, &s.q);
    let world = |b: usize, r: &Point3<f64>| (f.bodies[b] * r).coords;
    let mut parts: Vec<Part> = Vec::new();
    let link_fill = Fill { color: color.tint(0.55), opacity: 0.55 };
    for b in 1..m.bodies.len() {
        let pts: Vec<Vector3<f64>> = attachments(m, b).iter().map(|r| world(b, r)).collect();
        let flat: Vec<[f64; 2]> = pts.iter().map(|p| pic(view, p)).map(|(a, c)| [a, c]).collect();
        // At its back, its farthest point less its half thickness: a link is
        // drawn over what lies wholly behind it, and the flexures and tendons
        // it carries over it.
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
    for (ji, j) in m.joints.iter().enumerate() {
        let Some(fl) = j.kind.flexure() else { continue };
        let q = alpha(m, s, ji, fl);
        let sections = flexure::spatial::shape(fl, q, FLEXURE_SAMPLES)
            .map_err(|e| format!("flexure {}: {}", j.name, crate::describe(e)))?;
        let pts: Vec<Vector3<f64>> = sections.iter().map(|p| (f.roots[ji] * Point3::from(p.position)).coords).collect();
        let top = match loads {
            Loads::Drawn { stress_top: Some(top) } if sections.iter().all(|p| p.stress.is_some()) => top,
            _ => {
                let points = pts.iter().map(|p| pic(view, p)).collect();
                let marks = vec![line(points, Stroke::solid(color, FLEXURE_WIDTH))];
                parts.push(Part { depth: mean_depth(view, &pts), marks });
                continue;
            }
        };
        // Each segment in the colour of its ends' mean stress, at its own depth.
        let sigma = |i: usize| sections[i].stress.unwrap_or(0.0);
        for i in 0..pts.len() - 1 {
            let stroke = Stroke::solid(ramp(0.5 * (sigma(i) + sigma(i + 1)) / top), FLEXURE_WIDTH);
            let marks = vec![line(vec![pic(view, &pts[i]), pic(view, &pts[i + 1])], stroke)];
            parts.push(Part { depth: mean_depth(view, &pts[i..i + 2]), marks });
        }
    }
    for (k, t) in m.tendons.iter().enumerate() {
        let pts: Vec<Vector3<f64>> = t.path.iter().map(|(b, r)| world(*b, r)).collect();
        let stroke = Stroke { color, width: 1.5, dash: TENDON_DASH[k % TENDON_DASH.len()] };
        for pair in pts.windows(2) {
            let marks = vec![line(vec![pic(view, &pair[0]), pic(view, &pair[1])], stroke)];
            parts.push(Part { depth: mean_depth(view, pair), marks });
        }
    }
    parts.sort_by(|a, b| a.depth.total_cmp(&b.depth));
    let mut out: Vec<Mark> = parts.into_iter().flat_map(|p| p.marks).collect();
    out.extend(symbols(m, &f, view, color, sizes));
    for (k, t) in m.tendons.iter().enumerate() {
        for (b, r) in &t.path {
            let at = pic(view, &world(*b, r));
            out.push(Mark::Dot { at, shape: VIA[k % VIA.len()], radius: 4.0, color, filled: false });
        }
    }
    if let Loads::Drawn { .. } = loads {
        for ((b, r), v) in load_places(m).into_iter().zip(force_vectors(m, s)) {
            if let (Some(k), true) = (sizes.per_newton, v != Vector3::zeros()) {
                let from = world(b, &r);
                out.push(Mark::Arrow { from: pic(view, &from), to: pic(view, &(from + v * k)), color, width: 2.5 });
            }
        }
        for (p, w) in m.forces.iter().zip(&s.loads.force) {
            let moment = w.fixed_rows::<3>(0).into_owned();
            if let (Some(k), true) = (sizes.per_newton_metre, moment != Vector3::zeros()) {
                let from = world(p.body, &p.at);
                let to = from + moment * k;
                out.extend(double_arrow(pic(view, &from), pic(view, &to), 0.03 * sizes.extent, color));
            }
        }
    }
    Ok(out)
}

/// The joints' and closures' symbols at frames `f`.
fn symbols(m: &SpatialMechanism, f: &SpatialFrames, view: View, color: Color, sizes: &Sizes) -> Vec<Mark> {
    let mut out = Vec::new();
    let reach = 2.5 * sizes.thick;
    let hinge = |out: &mut Vec<Mark>, at: Vector3<f64>, axis: Vector3<f64>| {
        let points = vec![pic(view, &(at - axis * reach)), pic(view, &(at + axis * reach))];
        out.push(line(points, Stroke::solid(color, 2.0)));
        out.push(Mark::Dot { at: pic(view, &at), shape: Marker::Circle, radius: 6.0, color, filled: false });
    };
    for (ji, j) in m.joints.iter().enumerate() {
        let root = f.roots[ji].translation.vector;
        match joint_symbol(m, ji) {
            Some(Symbol::Hinge) => hinge(&mut out, root, f.omega.column(j.offset).into_owned()),
            Some(Symbol::Ball) => {
                out.push(Mark::Dot { at: pic(view, &root), shape: Marker::Circle, radius: 5.0, color, filled: true });
            }
            Some(Symbol::Slider) => {
                let axis = f.velocity.column(j.offset).into_owned();
                let child = f.bodies[j.child].translation.vector;
                let travel = Stroke { color, width: 2.0, dash: Dash::Dashed };
                out.push(line(vec![pic(view, &root), pic(view, &child)], travel));
                if let Some((a, b)) = picture_direction(view, &axis) {
                    let (c, r) = (pic(view, &root), reach);
                    let normal = (-b * 0.4 * sizes.thick, a * 0.4 * sizes.thick);
                    for side in [-1.0, 1.0] {
                        let (ox, oy) = (c.0 + side * normal.0, c.1 + side * normal.1);
                        out.push(line(
                            vec![(ox - r * a, oy - r * b), (ox + r * a, oy + r * b)],
                            Stroke::solid(color, 2.0),
                        ));
                    }
                }
                out.push(Mark::Dot { at: pic(view, &root), shape: Marker::Square, radius: 5.0, color, filled: false });
            }
            None => {}
        }
    }
    for c in &m.closures {
        let at = f.bodies[c.a] * c.a_origin;
        match c.holds {
            Holds::Pin => hinge(&mut out, at.translation.vector, at.rotation * Vector3::z()),
            Holds::Ball => {
                let at = pic(view, &at.translation.vector);
                out.push(Mark::Dot { at, shape: Marker::Circle, radius: 5.0, color, filled: true });
            }
            Holds::Weld => {}
        }
    }
    out
}

/// A hatched anchor at world point `at` of the ground: a bar across the
/// picture direction `away` (toward the mechanism), hatched on the far side.
fn anchor(view: View, at: &Vector3<f64>, away: (f64, f64), sizes: &Sizes) -> Vec<Mark> {
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

/// The ground's anchors, at the unloaded frames `f0`.
fn ground(m: &SpatialMechanism, f0: &SpatialFrames, view: View, sizes: &Sizes) -> Vec<Mark> {
    let mut out = Vec::new();
    let up = (0.0, 1.0);
    let mut placed: Vec<Vector3<f64>> = Vec::new();
    for (ji, j) in m.joints.iter().enumerate().filter(|(_, j)| j.parent == 0) {
        let root = f0.roots[ji].translation.vector;
        // The direction the joint leaves the ground in: a flexure's tangent, else toward its child.
        let leaving = if j.kind.flexure().is_some() {
            f0.roots[ji].rotation * Vector3::x()
        } else {
            f0.bodies[j.child].translation.vector - root
        };
        out.extend(anchor(view, &root, picture_direction(view, &leaving).unwrap_or(up), sizes));
        placed.push(root);
    }
    // Other points of the ground (tendon via points, closures, loads): an
    // anchor of their own unless one is drawn within a bar's length in the picture.
    for r in attachments(m, 0) {
        let p = pic(view, &r.coords);
        let apart = |q: &Vector3<f64>| {
            let q = pic(view, q);
            (q.0 - p.0).hypot(q.1 - p.1) > 6.0 * sizes.thick
        };
        if placed.iter().all(apart) {
            out.extend(anchor(view, &r.coords, up, sizes));
            placed.push(r.coords);
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

/// The axis triad, left of everything in `marks`, its arrows a sixth of the drawing's height or width.
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
    let axes = [("x", Vector3::x()), ("y", Vector3::y()), ("z", Vector3::z())];
    let tips: Vec<((f64, f64), f64)> = axes.iter().map(|(_, e)| view.project(e)).collect();
    let hi_u = tips.iter().fold(0.0_f64, |h, t| h.max(t.0.0));
    let lo_v = tips.iter().fold(0.0_f64, |l, t| l.min(t.0.1));
    // The triad's right edge half an arrow left of the drawing, its bottom level with the drawing's.
    let o = (u0 - 0.5 * a - a * hi_u, v0 - a * lo_v);
    let (mut out, mut sight) = (Vec::new(), Vec::new());
    let others = |skip: usize| {
        tips.iter().enumerate().filter(|(i, _)| *i != skip).fold((0.0, 0.0), |s, (_, t)| (s.0 + t.0.0, s.1 + t.0.1))
    };
    for (i, ((name, _), ((du, dv), toward))) in axes.iter().zip(&tips).enumerate() {
        let n = du.hypot(*dv);
        if n > 1e-9 {
            let to = (o.0 + a * du, o.1 + a * dv);
            out.push(Mark::Arrow { from: o, to, color: KEY, width: 1.5 });
            let (ux, uy) = (du / n, dv / n);
            let anchor = if ux > 0.3 {
                Anchor::Start
            } else if ux < -0.3 {
                Anchor::End
            } else {
                Anchor::Middle
            };
            let offset = (8.0 * ux, -12.0 * uy + 6.0);
            out.push(Mark::Label { at: to, offset, text: (*name).into(), color: KEY, anchor });
        } else {
            // Along the line of sight: ⊙ toward the viewer, ⊗ away, over the
            // other arrows' tails (a hollow marker is white inside).
            sight.push(Mark::Dot { at: o, shape: Marker::Circle, radius: 9.0, color: KEY, filled: false });
            if *toward > 0.0 {
                sight.push(Mark::Dot { at: o, shape: Marker::Circle, radius: 2.5, color: KEY, filled: true });
            } else {
                let cross =
                    Mark::Label { at: o, offset: (0.0, 5.5), text: "×".into(), color: KEY, anchor: Anchor::Middle };
                sight.push(cross);
            }
            // Its name opposite the other two arrows.
            let (su, sv) = others(i);
            let n = su.hypot(sv).max(1e-9);
            let (ux, uy) = (-su / n, -sv / n);
            let offset = (18.0 * ux, -18.0 * uy + 6.0);
            let anchor = if ux > 0.3 {
                Anchor::Start
            } else if ux < -0.3 {
                Anchor::End
            } else {
                Anchor::Middle
            };
            sight.push(Mark::Label { at: o, offset, text: (*name).into(), color: KEY, anchor });
        }
    }
    out.extend(sight);
    out
}

/// Names beside the last shape's loads: past a force's head, past a moment's heads.
fn load_names(m: &SpatialMechanism, s: &SpatialSolution, view: View, color: Color, sizes: &Sizes) -> Vec<Mark> {
    let f = frames(m, &s.q);
    let mut out = Vec::new();
    let mut label = |from: Vector3<f64>, v: Vector3<f64>, k: f64, text: String| {
        let to = from + v * k;
        let (at, dir) = (pic(view, &to), picture_direction(view, &v));
        let (ux, uy) = dir.unwrap_or((0.7, 0.7));
        let anchor = if ux > 0.3 {
            Anchor::Start
        } else if ux < -0.3 {
            Anchor::End
        } else {
            Anchor::Middle
        };
        let offset = if dir.is_some() { (10.0 * ux, -14.0 * uy + 6.0) } else { (12.0, -12.0) };
        out.push(Mark::Label { at, offset, text, color, anchor });
    };
    let names = m
        .forces
        .iter()
        .map(|p| p.name.clone())
        .chain(m.bodies.iter().filter(|b| b.mass > 0.0).map(|b| format!("weight of {}", b.name)));
    let forces = force_vectors(m, s);
    for (((b, r), name), v) in load_places(m).into_iter().zip(names).zip(&forces) {
        if *v != Vector3::zeros() {
            label((f.bodies[b] * r).coords, *v, sizes.per_newton.unwrap_or(0.0), name);
        }
    }
    // A pure moment's name at its head (one with a force is named at the force's).
    for ((p, w), v) in m.forces.iter().zip(&s.loads.force).zip(&forces) {
        let moment = w.fixed_rows::<3>(0).into_owned();
        if moment != Vector3::zeros() && *v == Vector3::zeros() {
            label((f.bodies[p.body] * p.at).coords, moment, sizes.per_newton_metre.unwrap_or(0.0), p.name.clone());
        }
    }
    out
}

/// A vector as text, `(1, −2, 0.5)`.
fn triple(v: &Vector3<f64>) -> String {
    format!("({}, {}, {})", short(v.x), short(v.y), short(v.z))
}

/// The figure of a spatial mechanism's unloaded and loaded shapes seen
/// from `view`, and the force arrows' scale (m per N) if any force is drawn.
/// With `stress`, loaded flexures with a shaped section are coloured by
/// their von Mises stress (the module docs). As the planar
/// `drawing::figure`: the same sizes, colours, legend and marks
/// (`marks`: yield strengths on the colour bar, a stability note).
///
/// Errors name the shape whose coordinates or loads do not fit `m`, or the
/// flexure whose coordinates the library refuses.
///
/// # Example
/// ```
/// use flexure_cli::spatial_drawing::{Marks, View, spatial_figure};
/// use flexure::mechanism::spatial::{Revolute, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism, SpatialPointLoad};
/// use flexure::mechanism::spatial::statics::{assemble_unloaded, solve};
/// use nalgebra::{Isometry3, Point3, Vector3, Vector6};
/// let hinge = SpatialJointSpec {
///     name: "hinge".into(), kind: SpatialJointKind::Revolute(Revolute { axis: Vector3::z_axis(), stiffness: 2.0, rest: 0.0 }),
///     parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default(),
/// };
/// let push = SpatialPointLoad { name: "push".into(), body: 1, at: Point3::new(0.1, 0.0, 0.0), wrench: Vector6::new(0.0, 0.0, 0.0, 0.0, 1.0, 0.0) };
/// let bodies = vec![SpatialBody::massless("ground"), SpatialBody::massless("arm")];
/// let m = SpatialMechanism::new(bodies, vec![hinge], vec![], vec![push], vec![], Vector3::zeros()).unwrap();
/// let s = solve(&m, &Default::default()).unwrap();
/// let unloaded = assemble_unloaded(&m, &m.loads().zero_like(), &Default::default()).unwrap();
/// let (fig, per_newton) = spatial_figure(&m, "arm", &unloaded, &[("loaded".into(), s)], &Marks::default(), View::Top, true).unwrap();
/// // The largest force drawn a quarter of the arm's 0.1 m, at a round scale: 0.02 m per N.
/// assert_eq!(per_newton, Some(0.02));
/// assert!(fig.legend.iter().any(|e| e.label == "force push on arm: (0, 1, 0) N"));
/// assert!(flexure_chart::render(&fig).unwrap().starts_with("<svg"));
/// ```
pub fn spatial_figure(
    m: &SpatialMechanism,
    title: &str,
    unloaded: &SpatialSolution,
    loaded: &[(String, SpatialSolution)],
    marks: &Marks,
    view: View,
    stress: bool,
) -> Result<(Figure, Option<f64>), String> {
    check_shape(m, "unloaded", unloaded)?;
    for (label, s) in loaded {
        check_shape(m, label, s)?;
    }
    let (x_label, y_label) = view.axis_labels();
    let mut fig = Figure::new(title, x_label, y_label);
    fig.equal_aspect = true;
    fig.width = 1200.0;
    fig.height = 760.0;
    fig.place = Place::Outside;
    fig.fit_height = true;

    // Sizes from the unloaded mechanism in space (the same in every view):
    // links 2.4 % of it thick, the longest arrow about a quarter of it.
    let f0 = frames(m, &unloaded.q);
    let mut pts: Vec<Vector3<f64>> = (0..m.bodies.len())
        .flat_map(|b| attachments(m, b).into_iter().map(move |r| (b, r)))
        .map(|(b, r)| (f0.bodies[b] * r).coords)
        .collect();
    pts.extend(f0.roots.iter().map(|r| r.translation.vector));
    pts.extend(f0.bodies.iter().map(|b| b.translation.vector));
    let span = |i: usize| {
        let (lo, hi) = pts.iter().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p[i]), b.max(p[i])));
        if hi > lo { hi - lo } else { 0.0 }
    };
    let lengths = m.joints.iter().map(|j| j.kind.flexure().map_or(0.0, |fl| fl.length()));
    let extent = span(0).max(span(1)).max(span(2)).max(lengths.fold(0.0, f64::max)).max(1e-9);
    let largest = loaded.iter().flat_map(|(_, s)| force_vectors(m, s)).map(|v| v.norm()).fold(0.0, f64::max);
    let largest_moment =
        loaded.iter().flat_map(|(_, s)| &s.loads.force).map(|w| w.fixed_rows::<3>(0).norm()).fold(0.0, f64::max);
    let sizes = Sizes {
        extent,
        thick: 0.012 * extent,
        per_newton: (largest > 0.0).then(|| round_down(0.25 * extent / largest)),
        per_newton_metre: (largest_moment > 0.0).then(|| round_down(0.25 * extent / largest_moment)),
    };
    // The colour bar from 0 to the largest stress (1 MPa if none is
    // loaded), on past the highest yield strength so that its mark shows.
    let highest_yield = marks.yields.iter().map(|y| y.1).fold(0.0, f64::max);
    let stress_top = if stress { stress_max(m, loaded)? } else { None }
        .map(|top| if top > 0.0 { top } else { 1e6 })
        .map(|top| top.max(1.05 * highest_yield));

    fig.marks.extend(ground(m, &f0, view, &sizes));
    let ground_swatch = Swatch::Area(Fill { color: GROUND.tint(0.4), opacity: 0.8 }, Stroke::solid(GROUND, 1.5));
    fig.legend.push(Entry { swatch: ground_swatch, label: "ground (hatched anchors)".into() });
    let link = |c: Color| Swatch::Area(Fill { color: c.tint(0.55), opacity: 0.55 }, Stroke::solid(c, 1.5));
    fig.marks.extend(draw_shape(m, unloaded, view, GRAY, &sizes, Loads::Hidden)?);
    fig.legend.push(Entry { swatch: link(GRAY), label: "unloaded".into() });
    for (i, (label, s)) in loaded.iter().enumerate() {
        let color = SHAPES[i % SHAPES.len()];
        fig.marks.extend(draw_shape(m, s, view, color, &sizes, Loads::Drawn { stress_top })?);
        fig.legend.push(Entry { swatch: link(color), label: label.clone() });
    }
    if let Some((_, s)) = loaded.last() {
        fig.marks.extend(load_names(m, s, view, SHAPES[(loaded.len() - 1) % SHAPES.len()], &sizes));
    }
    let axes = triad(view, &fig.marks);
    fig.marks.extend(axes);

    // Keys for what every shape shows.
    if m.joints.iter().any(|j| j.kind.flexure().is_some()) {
        let swatch = Swatch::Line(Some(Stroke::solid(KEY, FLEXURE_WIDTH)), None);
        fig.legend.push(Entry { swatch, label: "flexure".into() });
    }
    let drawn = |want: Symbol| (0..m.joints.len()).any(|j| joint_symbol(m, j) == Some(want));
    let (hinge, pin) = (drawn(Symbol::Hinge), m.closures.iter().any(|c| c.holds == Holds::Pin));
    if hinge || pin {
        let swatch = Swatch::Line(Some(Stroke::solid(KEY, 2.0)), Some((Marker::Circle, KEY, false)));
        let what = match (hinge, pin) {
            (true, true) => "revolute joint or pin",
            (true, false) => "revolute joint",
            _ => "pin",
        };
        fig.legend.push(Entry { swatch, label: format!("{what} (line along its axis)") });
    }
    let (ball, ball_closure) = (drawn(Symbol::Ball), m.closures.iter().any(|c| c.holds == Holds::Ball));
    if ball || ball_closure {
        let swatch = Swatch::Line(None, Some((Marker::Circle, KEY, true)));
        let label = if ball { "ball joint" } else { "ball closure" };
        fig.legend.push(Entry { swatch, label: label.into() });
    }
    if drawn(Symbol::Slider) {
        let swatch = Swatch::Line(
            Some(Stroke { color: KEY, width: 2.0, dash: Dash::Dashed }),
            Some((Marker::Square, KEY, false)),
        );
        fig.legend.push(Entry { swatch, label: "slider (double line along its axis, its travel dashed)".into() });
    }
    for (k, t) in m.tendons.iter().enumerate() {
        let tensions: Vec<f64> = loaded.iter().map(|(_, s)| s.loads.tension[k]).collect();
        let stroke = Stroke { color: KEY, width: 1.5, dash: TENDON_DASH[k % TENDON_DASH.len()] };
        fig.legend.push(Entry {
            swatch: Swatch::Line(Some(stroke), Some((VIA[k % VIA.len()], KEY, false))),
            label: format!("tendon {}: {}", t.name, values(&tensions, "N")),
        });
    }
    for (i, p) in m.forces.iter().enumerate() {
        let body = &m.bodies[p.body].name;
        let wrenches: Vec<_> = loaded.iter().map(|(_, s)| s.loads.force[i]).collect();
        let part =
            |w: &nalgebra::Vector6<f64>, linear: bool| w.fixed_rows::<3>(if linear { 3 } else { 0 }).into_owned();
        for (linear, what, unit) in [(true, "force", "N"), (false, "moment", "N·m")] {
            let vectors: Vec<Vector3<f64>> = wrenches.iter().map(|w| part(w, linear)).collect();
            let acts = vectors.iter().any(|v| *v != Vector3::zeros());
            // A load of neither is listed as a force, as the planar drawing does.
            let listed = acts || (linear && wrenches.iter().all(|w| *w == nalgebra::Vector6::zeros()));
            if !listed {
                continue;
            }
            let same = vectors.windows(2).all(|w| w[0] == w[1]);
            let value = match vectors.first() {
                Some(v) if same => format!("{} {unit}", triple(v)),
                _ => values(&vectors.iter().map(|v| v.norm()).collect::<Vec<_>>(), unit),
            };
            let swatch = Swatch::Arrow(KEY);
            let label = if linear {
                format!("{what} {} on {body}: {value}", p.name)
            } else {
                format!("{what} {} on {body}: {value} (double arrow, right-hand rule)", p.name)
            };
            fig.legend.push(Entry { swatch, label });
        }
    }
    if loaded.iter().any(|(_, s)| s.loads.gravity != Vector3::zeros()) {
        for b in m.bodies.iter().filter(|b| b.mass > 0.0) {
            let w: Vec<f64> = loaded.iter().map(|(_, s)| b.mass * s.loads.gravity.norm()).collect();
            fig.legend.push(Entry {
                swatch: Swatch::Arrow(KEY),
                label: format!("weight of {}: {}", b.name, values(&w, "N")),
            });
        }
    }
    if let Some(k) = sizes.per_newton {
        fig.legend.push(Entry { swatch: Swatch::Note, label: format!("force arrows: {} m per N", short(k)) });
    }
    if let Some(k) = sizes.per_newton_metre {
        fig.legend.push(Entry { swatch: Swatch::Note, label: format!("moment arrows: {} m per N·m", short(k)) });
    }
    if let Some(limit) = &marks.limit {
        fig.legend.push(Entry { swatch: Swatch::Note, label: limit.clone() });
    }
    fig.legend.push(Entry { swatch: Swatch::Note, label: view.description().into() });
    let plain = m.joints.iter().filter_map(|j| j.kind.flexure()).any(|fl| !shaped(fl));
    if let Some(top) = stress_top {
        let mut label = "flexures' von Mises stress (MPa)".to_string();
        if !marks.yields.is_empty() {
            let named: Vec<String> =
                marks.yields.iter().map(|(name, y)| format!("{name} {} MPa", short(y / 1e6))).collect();
            label += &format!("; black line: yield strength ({})", named.join(", "));
        }
        let bar_marks = marks.yields.iter().map(|y| y.1 / 1e6).collect();
        fig.color_bar = Some(ColorBar { label, lo: 0.0, hi: top / 1e6, marks: bar_marks });
        let label = if plain {
            "loaded flexures coloured by stress; those given by stiffnesses alone (no section shape) in their shape's colour"
        } else {
            "loaded flexures coloured by von Mises stress"
        };
        fig.legend.push(Entry { swatch: Swatch::Note, label: label.into() });
    } else if stress && plain {
        let label = "no flexure has a section shape (stiffnesses given alone): no stress to colour";
        fig.legend.push(Entry { swatch: Swatch::Note, label: label.into() });
    }
    Ok((fig, sizes.per_newton))
}

/// The samples `draw --simulate` draws of a run of `samples` samples: five
/// from the first to the last, evenly spaced (fewer if the run is shorter),
/// as the planar drawing picks them.
///
/// # Example
/// ```
/// use flexure_cli::spatial_drawing::snapshot_samples;
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

/// What [`spatial_motion_figures`] draws.
pub struct MotionFigures {
    /// The snapshots over the rest shape, then the bodies' rotations and
    /// origins against time: for [`flexure_chart::write_stack`].
    pub figures: Vec<Figure>,
    /// The times of the snapshots (s).
    pub snapshots: Vec<f64>,
    /// The force arrows' scale (m per N), if any force is drawn.
    pub per_newton: Option<f64>,
}

/// `draw --simulate` of a spatial mechanism, as the planar one: five
/// snapshots of the run `sim` ([`snapshot_samples`]), each in its colour and
/// labelled by its time, over the unloaded shape (one [`spatial_figure`]
/// seen from `view`, flexures coloured by stress with `stress`), then two
/// charts against time: each body's rotation vector $\theta = \varphi\thinspace\hat n$
/// (its rotation from the ground frame, angle times unit axis; rad) and its
/// origin (mm), x solid, y dashed, z dotted, each body in its colour. Each
/// snapshot's loads (for its stresses) are its time's, schedules applied.
///
/// Errors name an empty run or a shape that does not fit `m`.
pub fn spatial_motion_figures(
    m: &SpatialMechanism,
    title: &str,
    unloaded: &SpatialSolution,
    sim: &SpatialSimulation,
    view: View,
    stress: bool,
) -> Result<MotionFigures, String> {
    let samples = sim.time.len();
    if samples == 0 || sim.coordinates.len() != samples * m.dof() {
        return Err(format!("the run has {samples} samples of {} coordinates: nothing to draw", sim.dim));
    }
    let picked = snapshot_samples(samples);
    let snapshots: Vec<(String, SpatialSolution)> = picked
        .iter()
        .map(|&k| {
            let s = SpatialSolution {
                q: sim.q(k).to_vec(),
                multipliers: Vec::new(),
                // The loads then, as the planar snapshots take them.
                loads: flexure::dynamics::schedule::spatial_loads_at(m, sim.time[k]),
                energy: sim.energy[k],
                stable: true,
                limit: None,
                residual: 0.0,
                load_steps: 0,
                iterations: 0,
            };
            (format!("t = {} s", short(sim.time[k])), s)
        })
        .collect();
    let duration = sim.time[samples - 1];
    let (shapes, per_newton) = spatial_figure(
        m,
        &format!("{title}: motion over {} s", short(duration)),
        unloaded,
        &snapshots,
        &Marks::default(),
        view,
        stress,
    )?;
    // Each body by colour, each component by dash: the legend lists the
    // bodies once and the three dashes once, not every body's components.
    // Past the six colours, each round of them adds a marker shape, so that
    // no two bodies look alike.
    let color = |i: usize| COLORS[i % COLORS.len()];
    let rounds = [None, Some(Marker::Circle), Some(Marker::Square), Some(Marker::Triangle), Some(Marker::Diamond)];
    let marker = |i: usize| rounds[(i / COLORS.len()) % rounds.len()];
    let every = samples.div_ceil(8).max(1);
    let styled = |s: Series, i: usize| match marker(i) {
        Some(shape) => s.marked(shape, every, (i % COLORS.len()) * every / COLORS.len()),
        None => s,
    };
    let dashes = [Dash::Solid, Dash::Dashed, Dash::Dotted];
    let mut rotations = Vec::new();
    let mut positions = Vec::new();
    for (i, b) in sim.bodies.iter().enumerate() {
        let theta: Vec<Vector3<f64>> = b
            .rotation
            .iter()
            .map(|r| Rotation3::from_matrix_unchecked(nalgebra::Matrix3::from_fn(|i, j| r[i][j])).scaled_axis())
            .collect();
        for (c, dash) in dashes.into_iter().enumerate() {
            let along_theta = sim.time.iter().zip(&theta).map(|(t, v)| (*t, v[c])).collect();
            let along_p = sim.time.iter().zip(&b.position).map(|(t, p)| (*t, p[c] * 1e3)).collect();
            rotations.push(styled(Series::line("", along_theta, color(i)).dashed(dash), i));
            positions.push(styled(Series::line("", along_p, color(i)).dashed(dash), i));
        }
    }
    let legend = |components: [&str; 3]| -> Vec<Entry> {
        let bodies = sim.bodies.iter().enumerate().map(|(i, b)| Entry {
            swatch: Swatch::Line(Some(Stroke::solid(color(i), 2.0)), marker(i).map(|m| (m, color(i), true))),
            label: b.name.clone(),
        });
        let key = components.into_iter().zip(dashes).map(|(label, dash)| Entry {
            swatch: Swatch::Line(Some(Stroke { color: GRAY, width: 2.0, dash }), None),
            label: label.to_string(),
        });
        bodies.chain(key).collect()
    };
    let chart = |title: &'static str, y: &'static str| Chart {
        title,
        x_label: "time (s)",
        y_label: y,
        log_y: false,
        equal_aspect: false,
    };
    let mut figures = vec![shapes];
    for (c, series, key) in [
        (chart("Body rotations", "θ = angle × axis (rad), ground frame"), rotations, ["θx", "θy", "θz"]),
        (chart("Body origins", "x, y, z (mm), ground frame"), positions, ["x", "y", "z"]),
    ] {
        let mut fig = chart_figure(&c, &series)?;
        fig.legend = legend(key);
        fig.width = 1200.0;
        fig.height = 420.0;
        fig.place = Place::Outside;
        figures.push(fig);
    }
    Ok(MotionFigures { figures, snapshots: picked.iter().map(|&k| sim.time[k]).collect(), per_newton })
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexure::mechanism::Fixed;
    use flexure::mechanism::spatial::statics::{assemble_unloaded, solve};
    use flexure::mechanism::spatial::{
        Prismatic, Revolute, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialPointLoad, Spherical,
    };
    use flexure::section::SpatialSection;
    use nalgebra::{Isometry3, Vector6};

    fn spec(
        name: &str,
        kind: SpatialJointKind,
        parent: usize,
        child: usize,
        origin: Isometry3<f64>,
    ) -> SpatialJointSpec {
        SpatialJointSpec {
            name: name.into(),
            kind,
            parent,
            child,
            origin,
            offset: 0,
            damping: 0.0,
            auto_order: false,
            report: Default::default(),
        }
    }

    fn bodies(names: &[&str]) -> Vec<SpatialBody> {
        names.iter().map(|n| SpatialBody::massless(n)).collect()
    }

    fn unloaded(m: &SpatialMechanism) -> SpatialSolution {
        assemble_unloaded(m, &m.loads().zero_like(), &Default::default()).unwrap()
    }

    /// A flexure from the ground along x, 0.1 m, given by stiffnesses
    /// alone, and a tip force along +z.
    fn plain_rod() -> SpatialMechanism {
        let fl = SpatialFlexure::new(0.1, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [2, 2, 2]).unwrap();
        let joint = spec("rod", SpatialJointKind::Flexure(Box::new(fl)), 0, 1, Isometry3::identity());
        let push = SpatialPointLoad {
            name: "lift".into(),
            body: 1,
            at: Point3::origin(),
            wrench: Vector6::new(0.0, 0.0, 0.0, 0.0, 0.0, 2.0),
        };
        SpatialMechanism::new(bodies(&["ground", "tip"]), vec![joint], vec![], vec![push], vec![], Vector3::zeros())
            .unwrap()
    }

    /// Reference: the unloaded straight rod lies along x from 0 to 0.1 m in
    /// the front view's picture (x right, z up), exactly at z = 0: its
    /// centreline path runs from (0, 0) to (0.1, 0) to rounding (1e-15).
    #[test]
    fn the_unloaded_rod_lies_along_x_in_the_front_view() {
        let m = plain_rod();
        let s = unloaded(&m);
        let sizes = Sizes { extent: 0.1, thick: 0.0012, per_newton: None, per_newton_metre: None };
        let marks = draw_shape(&m, &s, View::Front, GRAY, &sizes, Loads::Hidden).unwrap();
        let rods: Vec<&Vec<(f64, f64)>> = marks
            .iter()
            .filter_map(|mk| match mk {
                Mark::Path { points, stroke: Some(st), closed: false, .. } if st.width == FLEXURE_WIDTH => Some(points),
                _ => None,
            })
            .collect();
        assert_eq!(rods.len(), 1);
        let (first, last) = (rods[0][0], rods[0][rods[0].len() - 1]);
        assert!(first.0.abs() < 1e-15 && first.1.abs() < 1e-15 && (last.0 - 0.1).abs() < 1e-15 && last.1.abs() < 1e-15);
        assert_eq!(rods[0].len(), FLEXURE_SAMPLES);
    }

    /// Reference: a tip force along +z bends the rod up by the cantilever's
    /// $FL^3/(3EI)$ (1e-3 relative): in the front view the loaded tip is that high, and in the top view (z
    /// toward the viewer) the two tips draw at the same picture y = 0 (the
    /// bend is in the x–z plane: y = 0 exactly, since the force has no y
    /// part). Then the arrow: 2 N at the round scale of a quarter of 0.1 m,
    /// 0.01 m per N, is 0.02 m long and points up in the front view.
    #[test]
    fn a_lifted_tip_is_up_in_front_and_in_place_seen_from_the_top() {
        let m = plain_rod();
        let s = solve(&m, &Default::default()).unwrap();
        let tip = frames(&m, &s.q).bodies[1].translation.vector;
        // The cantilever's small-deflection tip, F L³/(3 EI) = 2 · 0.001/3 m; the
        // large-deflection correction is of order (F L²/EI)² = 4e-4 relative.
        let beam = 2.0 * 0.1f64.powi(3) / 3.0;
        assert!((tip.z - beam).abs() < 1e-3 * beam && tip.y.abs() < 1e-12, "{tip}");
        let ((_, up), _) = View::Front.project(&tip);
        assert!((up - tip.z).abs() < 1e-15);
        let ((_, across), toward) = View::Top.project(&tip);
        assert!(across.abs() < 1e-12 && (toward - tip.z).abs() < 1e-15);
        let (fig, per_newton) =
            spatial_figure(&m, "rod", &unloaded(&m), &[("loaded".into(), s)], &Marks::default(), View::Front, true)
                .unwrap();
        assert_eq!(per_newton, Some(0.01));
        let arrows: Vec<_> = fig
            .marks
            .iter()
            .filter_map(|mk| match mk {
                Mark::Arrow { from, to, width, .. } if *width == 2.5 => Some((*from, *to)),
                _ => None,
            })
            .collect();
        assert_eq!(arrows.len(), 1);
        let (from, to) = arrows[0];
        assert!((to.1 - from.1 - 0.02).abs() < 1e-15 && (to.0 - from.0).abs() < 1e-15, "{from:?} {to:?}");
        // Given by stiffnesses alone: no stress, no colour bar, and a note says why.
        assert!(fig.color_bar.is_none());
        assert!(fig.legend.iter().any(|e| e.label.starts_with("no flexure has a section shape")));
    }

    /// The joint interface's symbols: a hinge, a ball joint, a slider, and
    /// nothing for a weld; each drawn at its root (the hinge's axis line
    /// along the world axis z, so a point seen from the top and a vertical
    /// line from the front, 2 × 2.5 × thick long).
    #[test]
    fn each_rigid_joint_has_its_symbol() {
        let hinge = Revolute { axis: Vector3::z_axis(), stiffness: 1.0, rest: 0.0 };
        let slide = Prismatic { axis: Vector3::x_axis(), stiffness: 1.0, rest: 0.0 };
        let joints = vec![
            spec("h", SpatialJointKind::Revolute(hinge), 0, 1, Isometry3::translation(0.1, 0.0, 0.0)),
            spec(
                "b",
                SpatialJointKind::Spherical(Spherical { stiffness: 1.0, rest: [0.0; 3] }),
                1,
                2,
                Isometry3::translation(0.1, 0.0, 0.0),
            ),
            spec("s", SpatialJointKind::Prismatic(slide), 2, 3, Isometry3::translation(0.1, 0.0, 0.0)),
            spec("w", SpatialJointKind::Fixed(Fixed), 3, 4, Isometry3::translation(0.1, 0.0, 0.0)),
        ];
        let m = SpatialMechanism::new(
            bodies(&["ground", "a", "b", "c", "d"]),
            joints,
            vec![],
            vec![],
            vec![],
            Vector3::zeros(),
        )
        .unwrap();
        let got: Vec<_> = (0..4).map(|j| joint_symbol(&m, j)).collect();
        assert!(got == [Some(Symbol::Hinge), Some(Symbol::Ball), Some(Symbol::Slider), None]);
        let f = frames(&m, &m.rest());
        let sizes = Sizes { extent: 0.4, thick: 0.0048, per_newton: None, per_newton_metre: None };
        let axis_line = |view: View| match &symbols(&m, &f, view, GRAY, &sizes)[0] {
            Mark::Path { points, .. } => (points[1].0 - points[0].0, points[1].1 - points[0].1),
            _ => panic!("a hinge's first mark is its axis"),
        };
        assert_eq!(axis_line(View::Top), (0.0, 0.0));
        let (dx, dz) = axis_line(View::Front);
        assert!(dx == 0.0 && (dz - 5.0 * 0.0048).abs() < 1e-15);
    }

    /// Errors name the shape: a q of the wrong length, and one not finite.
    #[test]
    fn a_shape_that_does_not_fit_is_refused_by_name() {
        let m = plain_rod();
        let mut bad = unloaded(&m);
        bad.q.pop();
        let e = spatial_figure(
            &m,
            "rod",
            &unloaded(&m),
            &[("short".into(), bad.clone())],
            &Marks::default(),
            View::Iso,
            true,
        )
        .err()
        .unwrap();
        assert!(e.contains("\"short\"") && e.contains("5 coordinates"), "{e}");
        bad.q.push(f64::NAN);
        let e = spatial_figure(&m, "rod", &unloaded(&m), &[("nan".into(), bad)], &Marks::default(), View::Iso, true)
            .err()
            .unwrap();
        assert!(e.contains("\"nan\"") && e.contains("q[5]"), "{e}");
    }

    /// Reference: the hatched anchor sits at the ground's end of the rod and
    /// its bar lies across the rod (normal to x in the front view: vertical),
    /// 6 thick long.
    #[test]
    fn the_ground_anchor_lies_across_the_joint_leaving_it() {
        let m = plain_rod();
        let f = frames(&m, &m.rest());
        let sizes = Sizes { extent: 0.1, thick: 0.0012, per_newton: None, per_newton_metre: None };
        let marks = ground(&m, &f, View::Front, &sizes);
        assert_eq!(marks.len(), 6, "a bar and five hatches");
        let Mark::Path { points, closed: true, .. } = &marks[0] else { panic!("the bar first") };
        let (a, b) = (points[0], points[1]);
        assert!(
            a.0.abs() < 1e-18 && b.0.abs() < 1e-18 && ((b.1 - a.1).abs() - 6.0 * 0.0012).abs() < 1e-15,
            "{points:?}"
        );
        // The bar is behind the root (x ≤ 0), away from the rod.
        assert!(points.iter().all(|p| p.0 <= 1e-18));
    }
}
