//! What `draw` draws of contact: each geom's solid where its body puts it,
//! and each contact that touches with the force the geom exerts.
//!
//! - **Geoms**: the outline of each solid as the view sees it (its
//!   orthographic projection, the convex hull of its projected silhouette
//!   points): a circle or sphere as a circle, a capsule as two circles and
//!   the band between them, a box and a cylinder as the hull of their
//!   corners or end circles. A plane, unbounded, is drawn as a band behind
//!   its surface under the mechanism, across the box of what is drawn (the
//!   unloaded mechanism and every shape) and a little past it (about its
//!   centre's foot on the plane), so that it never widens the view much
//!   beyond them. A geom on the ground is drawn once, grey,
//!   named beside it; one on a moving body with each shape, in its colour.
//! - **Contacts** (of the loaded shapes): a dot where each touches and an
//!   arrow for the normal force the geom exerts on the part, its head at
//!   the point (so the arrow comes out of the geom), at the force arrows'
//!   scale; the friction force likewise, thinner, where it is not zero; ⊙
//!   or ⊗ for a force along the line of sight. The last shape's are
//!   labelled with their value (N); the legend gives each contact's range.

use super::drawing::{Drawn, KEY, LEAST_ARROW, Part, Sizes, View, anchor_along, hull, pic, short, sight};
use super::scene::{ContactMark, Scene, Snapshot, Solid};
use flexure::mechanism::contact::GeomShape;
use flexure_chart::{Anchor, Color, Entry, Fill, GRAY, Mark, Marker, Stroke, Swatch};
use nalgebra::Vector3;
use std::f64::consts::TAU;

type V = Vector3<f64>;

/// Points sampled around each circle of an outline.
const AROUND: usize = 48;
/// A plane's band: how far it reaches past the mechanism's box, and its
/// depth behind the surface, as fractions of the mechanism's size.
const PLANE_MARGIN: f64 = 0.15;
const PLANE_DEPTH: f64 = 0.04;
/// The geoms' fill: light, so that the parts on them show.
const OPACITY: f64 = 0.35;

/// `n` points on the circle of radius `r` about `c` in the plane of the unit vectors `a` and `b`.
fn circle(c: V, (a, b): (V, V), r: f64, n: usize) -> impl Iterator<Item = V> {
    (0..n).map(move |k| TAU * k as f64 / n as f64).map(move |t| c + (a * t.cos() + b * t.sin()) * r)
}

/// A unit vector across `n`: in the x–y plane where it can be (a planar
/// plane's line), so that the plane's band lies along it.
fn across(n: &V) -> V {
    let t = V::z().cross(n);
    if t.norm() > 0.1 { t.normalize() } else { V::x().cross(n).normalize() }
}

/// The world points whose picture's hull is the solid's outline in `view`;
/// a plane's band about the foot of the drawn box's centre, across the box.
fn silhouette(view: View, solid: &Solid, sizes: &Sizes) -> Vec<V> {
    let f = &solid.frame;
    let at = |x: f64, y: f64, z: f64| (f * nalgebra::Point3::new(x, y, z)).coords;
    let [right, up, _] = view.basis();
    let seen = (right, up);
    match solid.shape {
        GeomShape::Ball { radius } => circle(f.translation.vector, seen, radius, AROUND).collect(),
        GeomShape::Capsule { half_length, radius } => [-half_length, half_length]
            .into_iter()
            .flat_map(|x| circle(at(x, 0.0, 0.0), seen, radius, AROUND))
            .collect(),
        GeomShape::Box { half_extents: e } => (0..8)
            .map(|k| {
                let sign = |bit: usize| if k & bit == 0 { -1.0 } else { 1.0 };
                at(sign(1) * e.x, sign(2) * e.y, sign(4) * e.z)
            })
            .collect(),
        GeomShape::Cylinder { half_length, radius } => {
            let ends = (f.rotation * V::x(), f.rotation * V::y());
            [-half_length, half_length]
                .into_iter()
                .flat_map(|z| circle(at(0.0, 0.0, z), ends, radius, AROUND))
                .collect()
        }
        GeomShape::Plane { normal } => {
            let n = (f.rotation * normal).normalize();
            let c = sizes.centre;
            let foot = c - n * (c - f.translation.vector).dot(&n);
            let t1 = across(&n);
            let t2 = n.cross(&t1);
            // How far the box reaches along t: its support, Σ|tᵢ| hᵢ.
            let reach = |t: &V| t.abs().dot(&sizes.half) + PLANE_MARGIN * sizes.extent;
            let (r1, r2, depth) = (reach(&t1), reach(&t2), PLANE_DEPTH * sizes.extent);
            let mut out = Vec::new();
            for (u, v) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                for back in [0.0, depth] {
                    out.push(foot + t1 * (u * r1) + t2 * (v * r2) - n * back);
                }
            }
            out
        }
    }
}

/// The solid's outline in the picture, and its depth (its farthest point's).
fn outline(view: View, solid: &Solid, sizes: &Sizes) -> (Vec<(f64, f64)>, f64) {
    let pts = silhouette(view, solid, sizes);
    let far = pts.iter().map(|p| view.project(p).1).fold(f64::INFINITY, f64::min);
    (hull(pts.iter().map(|p| pic(view, p)).collect()), if far.is_finite() { far } else { 0.0 })
}

/// The solid's outline filled in `color`.
fn filled(points: Vec<(f64, f64)>, color: Color) -> Mark {
    Mark::Path {
        points,
        stroke: Some(Stroke::solid(color, 1.5)),
        fill: Some(Fill { color: color.tint(0.6), opacity: OPACITY }),
        closed: true,
    }
}

/// A geom's name under its outline.
fn named(points: &[(f64, f64)], name: &str, color: Color) -> Mark {
    let (lo, hi) = points.iter().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let bottom = points.iter().map(|p| p.1).fold(f64::MAX, f64::min);
    Mark::Label { at: (0.5 * (lo + hi), bottom), offset: (0.0, 16.0), text: name.into(), color, anchor: Anchor::Middle }
}

/// A bounded solid's bounding ball (world): its centre and radius; none for a plane.
pub(super) fn bounding_ball(solid: &Solid) -> Option<(V, f64)> {
    let radius = match solid.shape {
        GeomShape::Plane { .. } => return None,
        GeomShape::Ball { radius } => radius,
        GeomShape::Capsule { half_length, radius } => half_length + radius,
        GeomShape::Box { half_extents } => half_extents.norm(),
        GeomShape::Cylinder { half_length, radius } => half_length.hypot(radius),
    };
    Some((solid.frame.translation.vector, radius))
}

/// The geoms on the ground, grey, each named: drawn once, under every shape.
pub(super) fn ground_geoms(scene: &Scene, rest: &Snapshot, view: View, sizes: &Sizes) -> Vec<Mark> {
    let (mut solids, mut names) = (Vec::new(), Vec::new());
    for ((name, _, grounded), solid) in scene.geoms.iter().zip(&rest.geoms) {
        if *grounded {
            let (points, _) = outline(view, solid, sizes);
            names.push(named(&points, name, GRAY));
            solids.push(filled(points, GRAY));
        }
    }
    // The names over every solid.
    solids.extend(names);
    solids
}

/// A shape's geoms on moving bodies, in its colour, each at its depth (its back).
pub(super) fn moving_geoms(scene: &Scene, pose: &Snapshot, view: View, color: Color, sizes: &Sizes) -> Vec<Part> {
    let mut out = Vec::new();
    for ((_, _, grounded), solid) in scene.geoms.iter().zip(&pose.geoms) {
        if !grounded {
            let (points, depth) = outline(view, solid, sizes);
            out.push(Part { depth, marks: vec![filled(points, color)] });
        }
    }
    out
}

/// A force `f` (N) at `point`: an arrow with its head there (picture), ⊙
/// or ⊗ along the line of sight, or nothing under [`LEAST_ARROW`] of the
/// longest arrow.
fn pushed(view: View, point: &V, f: &V, sizes: &Sizes) -> Option<Drawn> {
    let k = sizes.per_newton?;
    let longest = k * sizes.largest;
    let (head, ((a, b), toward)) = (pic(view, point), view.project(&(f * k)));
    if k * f.norm() < LEAST_ARROW * longest || f.norm() == 0.0 {
        return None;
    }
    if a.hypot(b) < LEAST_ARROW * longest {
        return Some(Drawn::Sight(head, toward > 0.0));
    }
    Some(Drawn::Arrow((head.0 - a, head.1 - b), head, 0))
}

/// A shape's contacts: a dot at each point, the normal force's arrow and
/// the friction force's (thinner), in its colour.
pub(super) fn contact_marks(pose: &Snapshot, view: View, color: Color, sizes: &Sizes) -> Vec<Mark> {
    let mut out = Vec::new();
    for c in &pose.contacts {
        let at = pic(view, &c.point);
        for (f, width) in [(c.normal * c.normal_force, 2.5), (c.friction_force, 1.5)] {
            match pushed(view, &c.point, &f, sizes) {
                Some(Drawn::Arrow(from, to, _)) => out.push(Mark::Arrow { from, to, color, width }),
                Some(Drawn::Sight(at, toward)) => out.extend(sight(at, toward, 7.0, color)),
                None => {}
            }
        }
        out.push(Mark::Dot { at, shape: Marker::Circle, radius: 4.0, color, filled: true });
    }
    out
}

/// The values of the last shape's normal forces, past each arrow's tail (or beside its point).
pub(super) fn contact_values(pose: &Snapshot, view: View, color: Color, sizes: &Sizes) -> Vec<Mark> {
    let mut out = Vec::new();
    for c in &pose.contacts {
        let text = format!("{} N", short(c.normal_force));
        let (at, offset, anchor) = match pushed(view, &c.point, &(c.normal * c.normal_force), sizes) {
            Some(Drawn::Arrow(from, to, _)) => {
                let n = (from.0 - to.0).hypot(from.1 - to.1);
                let (ux, uy) = ((from.0 - to.0) / n, (from.1 - to.1) / n);
                (from, (8.0 * ux, -12.0 * uy + 5.0), anchor_along(ux))
            }
            _ => (pic(view, &c.point), (10.0, -10.0), Anchor::Start),
        };
        out.push(Mark::Label { at, offset, text, color, anchor });
    }
    out
}

/// The largest contact force (N) of the shapes, normal or friction.
pub(super) fn largest_contact(loaded: &[(String, Snapshot)]) -> f64 {
    let each = loaded.iter().flat_map(|(_, p)| &p.contacts);
    each.map(|c| c.normal_force.max(c.friction_force.norm())).fold(0.0, f64::max)
}

/// The legend's entries for the geoms and each contact that touches in a
/// shape: its normal force over the shapes (0 where it is open).
pub(super) fn contact_entries(scene: &Scene, loaded: &[(String, Snapshot)]) -> Vec<Entry> {
    let mut out = Vec::new();
    if !scene.geoms.is_empty() {
        let swatch = Swatch::Area(Fill { color: GRAY.tint(0.6), opacity: OPACITY }, Stroke::solid(GRAY, 1.5));
        let named: Vec<String> = scene.geoms.iter().map(|(name, shape, _)| format!("{name} ({shape})")).collect();
        out.push(Entry { swatch, label: format!("geom: {}", named.join(", ")) });
    }
    let mut names: Vec<&str> = Vec::new();
    for c in loaded.iter().flat_map(|(_, p)| &p.contacts) {
        if !names.contains(&c.name.as_str()) {
            names.push(&c.name);
        }
    }
    // Over the shapes: its least and largest (one value where they agree),
    // rounding's residue (a stuck friction of 1e-38 N) as the 0 it is.
    let residue = 1e-12 * largest_contact(loaded);
    let range = |v: Vec<f64>| {
        let v = v.into_iter().map(|x| if x.abs() <= residue { 0.0 } else { x });
        let (lo, hi) = v.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
        if lo == hi { format!("{} N", short(lo)) } else { format!("{} to {} N", short(lo), short(hi)) }
    };
    for name in names {
        let sum = |p: &Snapshot, f: &dyn Fn(&ContactMark) -> f64| {
            p.contacts.iter().filter(|c| c.name == name).map(f).sum::<f64>()
        };
        let normal = range(loaded.iter().map(|(_, p)| sum(p, &|c| c.normal_force)).collect());
        let friction: Vec<f64> = loaded.iter().map(|(_, p)| sum(p, &|c| c.friction_force.norm())).collect();
        // The thinner arrow, where friction holds it.
        let label = match friction.iter().any(|f| *f > residue) {
            true => format!("contact {name}: normal force {normal}, friction {} (thin arrow)", range(friction)),
            false => format!("contact {name}: normal force {normal}"),
        };
        out.push(Entry { swatch: Swatch::Arrow(KEY), label });
    }
    if loaded.iter().any(|(_, p)| !p.contacts.is_empty()) {
        let label = "contact: a dot where a part touches a geom, an arrow for the force the geom exerts (its head at the point)";
        out.push(Entry { swatch: Swatch::Note, label: label.into() });
    }
    out
}
