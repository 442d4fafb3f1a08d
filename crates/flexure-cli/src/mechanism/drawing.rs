//! `flexure draw`: a mechanism's shapes as one figure. Each shape has its
//! colour: its rigid links are filled hulls of every point attached to
//! them, its flexures thick curves, its tendons thin lines through marked
//! via points, its loads arrows (forces, weights, drawn to a stated scale)
//! and turning arrows (moments).

use flexure::kinematics::backbone;
use flexure::mechanism::joints::Joint;
use flexure::mechanism::statics::{Solution, body_frames};
use flexure::mechanism::{Holds, Mechanism};
use flexure_chart::{
    Anchor, COLORS, Color, ColorBar, Dash, Entry, Figure, Fill, GRAY, Mark, Marker, Place, Stroke, Swatch, ramp,
};
use nalgebra::Point2;
use std::f64::consts::TAU;

/// The colour of legend keys that stand for every shape.
pub(super) const KEY: Color = Color(60, 60, 60);
pub(super) const GROUND: Color = Color(90, 90, 90);
/// The loaded shapes' colours, in order.
pub(super) const SHAPES: [Color; 5] = [COLORS[0], COLORS[2], COLORS[3], COLORS[1], COLORS[4]];
/// Tendons are told apart by dash and via-point marker, not colour.
pub(super) const TENDON_DASH: [Dash; 3] = [Dash::Solid, Dash::Dashed, Dash::Chain];
pub(super) const VIA: [Marker; 4] = [Marker::Circle, Marker::Square, Marker::Triangle, Marker::Diamond];
pub(super) const FLEXURE_WIDTH: f64 = 5.0;

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

/// A swept shape's name: `tendon.flexor.tension = 4 N`.
pub fn swept(parameter: &str, value: f64) -> String {
    format!("{parameter} = {} {}", short(value), unit(parameter))
}

/// Every point attached to body `b`, in its frame ([`Mechanism::attachments`]:
/// the library's crossing test takes the same points as the link).
pub(super) fn attachments(m: &Mechanism, b: usize) -> Vec<Point2<f64>> {
    m.attachments(b)
}

/// The convex hull, counter-clockwise: the library's, which the crossing test uses.
pub(super) fn hull(p: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    let points = p.into_iter().map(|(x, y)| [x, y]).collect();
    flexure::mechanism::findings::hull(points).into_iter().map(|[x, y]| (x, y)).collect()
}

/// A rigid link: the hull of its points grown by `r`, so that two
/// points make a bar and one a disc.
pub(super) fn slab(pts: &[[f64; 2]], r: f64) -> Vec<(f64, f64)> {
    let round = (0..16).map(|k| TAU * f64::from(k) / 16.0).map(|a| (r * a.cos(), r * a.sin()));
    hull(pts.iter().flat_map(|p| round.clone().map(move |d| (p[0] + d.0, p[1] + d.1))).collect())
}

/// The largest 1, 2 or 5 × 10ᵏ not above `x`.
pub(super) fn round_down(x: f64) -> f64 {
    let base = 10f64.powf(x.log10().floor());
    [5.0, 2.0, 1.0].into_iter().map(|m| m * base).find(|s| *s <= x * (1.0 + 1e-9)).unwrap_or(base)
}

/// The forces (N) a solution applies: each point load's, then each weight's.
fn force_vectors(m: &Mechanism, s: &Solution) -> Vec<[f64; 2]> {
    let g = s.loads.gravity;
    let weights = m.bodies.iter().filter(|b| b.mass > 0.0).map(|b| [b.mass * g[0], b.mass * g[1]]);
    s.loads.force.iter().map(|l| [l.fx, l.fy]).chain(weights).collect()
}

/// How a load reads in the legend: one value, or the range over the shapes.
pub(super) fn values(v: &[f64], unit: &str) -> String {
    let (lo, hi) = v.iter().fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    if v.is_empty() || lo == hi {
        format!("{} {unit}", short(v.first().copied().unwrap_or(0.0)))
    } else {
        format!("{} to {} {unit}", short(lo), short(hi))
    }
}

/// How a shape's loads are drawn: not at all (the unloaded shape), or
/// with force arrows `per_newton` m long per N (none if no force acts).
#[derive(Clone, Copy)]
enum Loads {
    Hidden,
    /// `stress_top`: the stress (Pa) at the top of the colour bar, when
    /// flexures with a thickness are coloured by their stress.
    Drawn {
        per_newton: Option<f64>,
        stress_top: Option<f64>,
    },
}

/// Points along each drawn flexure.
pub(super) const FLEXURE_SAMPLES: usize = 41;

/// The mark of a rigid joint at its root.
#[derive(Clone, Copy, PartialEq)]
enum Symbol {
    /// A circle: a rotation.
    Pin,
    /// A square and the travel dashed: a translation.
    Slider,
}

/// The symbol of a rigid joint with coordinates, read from the joint
/// interface (so a new kind is drawn without a case here); `None` for a
/// flexure (drawn as its backbone) and for a weld.
fn symbol(j: &dyn Joint) -> Option<Symbol> {
    if j.flexure().is_some() || j.dof() == 0 {
        None
    } else if j.is_translation() {
        Some(Symbol::Slider)
    } else {
        Some(Symbol::Pin)
    }
}

/// The largest bending stress (Pa) of any flexure with a thickness in
/// any of the shapes, or `None` if no flexure has a thickness.
pub fn stress_max(m: &Mechanism, shapes: &[(String, Solution)]) -> Option<f64> {
    let mut top = None;
    for (_, s) in shapes {
        for j in &m.joints {
            if let Some(fl) = j.kind.flexure()
                && let Some(p) = flexure::stress::peak_stress(fl, &s.q[j.offset..j.offset + fl.order()])
            {
                top = Some(p.value.max(top.unwrap_or(0.0)));
            }
        }
    }
    top
}

/// One shape's marks.
fn shape(fig: &mut Figure, m: &Mechanism, s: &Solution, color: Color, thick: f64, loads: Loads) {
    let f = body_frames(m, s);
    let at = |b: usize, r: Point2<f64>| {
        let p = f.bodies[b].act(&r);
        (p.x, p.y)
    };
    for b in 1..m.bodies.len() {
        let pts: Vec<[f64; 2]> = attachments(m, b).iter().map(|r| f.bodies[b].act(r)).map(|p| [p.x, p.y]).collect();
        fig.marks.push(Mark::Path {
            points: slab(&pts, thick),
            stroke: Some(Stroke::solid(color, 1.5)),
            fill: Some(Fill { color: color.tint(0.55), opacity: 0.55 }),
            closed: true,
        });
    }
    for (ji, j) in m.joints.iter().enumerate() {
        let root = f.roots[ji];
        let origin = (root.x, root.y);
        match (j.kind.flexure(), symbol(j.kind.joint())) {
            (Some(fl), _) => {
                let q = &s.q[j.offset..j.offset + fl.order()];
                let points: Vec<(f64, f64)> = backbone(fl, q, FLEXURE_SAMPLES)
                    .iter()
                    .map(|p| root.act(&Point2::new(p.x, p.y)))
                    .map(|p| (p.x, p.y))
                    .collect();
                let top = match loads {
                    Loads::Drawn { stress_top: Some(top), .. } if fl.section().modulus().is_some() => top,
                    _ => {
                        let stroke = Some(Stroke::solid(color, FLEXURE_WIDTH));
                        fig.marks.push(Mark::Path { points, stroke, fill: None, closed: false });
                        continue;
                    }
                };
                // Each piece in the colour of its mean stress.
                let ds = fl.length() / (FLEXURE_SAMPLES - 1) as f64;
                let sigma = |i: usize| flexure::stress::stress(fl, q, i as f64 * ds).unwrap_or(0.0);
                for (i, pair) in points.windows(2).enumerate() {
                    let stroke = Some(Stroke::solid(ramp(0.5 * (sigma(i) + sigma(i + 1)) / top), FLEXURE_WIDTH));
                    fig.marks.push(Mark::Path { points: pair.to_vec(), stroke, fill: None, closed: false });
                }
            }
            (None, Some(Symbol::Pin)) => {
                fig.marks.push(Mark::Dot { at: origin, shape: Marker::Circle, radius: 6.0, color, filled: false });
            }
            (None, Some(Symbol::Slider)) => {
                let points = vec![origin, at(j.child, Point2::origin())];
                let stroke = Some(Stroke { color, width: 2.0, dash: Dash::Dashed });
                fig.marks.push(Mark::Path { points, stroke, fill: None, closed: false });
                fig.marks.push(Mark::Dot { at: origin, shape: Marker::Square, radius: 6.0, color, filled: false });
            }
            (None, None) => {}
        }
    }
    for c in &m.closures {
        if c.holds == Holds::Pin {
            let a_at = c.a_origin.origin();
            fig.marks.push(Mark::Dot { at: at(c.a, a_at), shape: Marker::Circle, radius: 5.0, color, filled: false });
        }
    }
    for (k, t) in m.tendons.iter().enumerate() {
        let points: Vec<(f64, f64)> = t.path.iter().map(|&(b, r)| at(b, r)).collect();
        for &p in &points {
            fig.marks.push(Mark::Dot { at: p, shape: VIA[k % VIA.len()], radius: 4.0, color, filled: false });
        }
        let stroke = Some(Stroke { color, width: 1.5, dash: TENDON_DASH[k % TENDON_DASH.len()] });
        fig.marks.push(Mark::Path { points, stroke, fill: None, closed: false });
    }
    let Loads::Drawn { per_newton, .. } = loads else { return };
    for (from, to) in arrows(m, s, per_newton).into_iter().flatten() {
        fig.marks.push(Mark::Arrow { from, to, color, width: 2.5 });
    }
    for (p, l) in m.forces.iter().zip(&s.loads.force) {
        if l.moment != 0.0 {
            fig.marks.push(Mark::Turn { at: at(p.body, p.at), radius: 18.0, ccw: l.moment > 0.0, color, width: 2.0 });
        }
    }
}

/// A force's arrow: its tail and head (m).
type Arrow = ((f64, f64), (f64, f64));

/// The fewest of the longest arrow's length an arrow is drawn at: a force
/// far smaller than the others would be an arrow of no length, its head
/// and name on its tail (the legend still gives its value).
const LEAST_ARROW: f64 = 0.02;

/// Each load of [`force_vectors`] as the arrow drawn for it, tail and head
/// (m), at `per_newton` m per N; `None` where none is drawn (no scale, or
/// an arrow shorter than [`LEAST_ARROW`] of the longest). Arrows from one
/// point in one direction are drawn side by side, each moved across its
/// direction by a twentieth of the longest arrow from the one before.
fn arrows(m: &Mechanism, s: &Solution, per_newton: Option<f64>) -> Vec<Option<Arrow>> {
    let f = body_frames(m, s);
    let vectors = force_vectors(m, s);
    let Some(k) = per_newton else { return vec![None; vectors.len()] };
    let longest = vectors.iter().map(|v| k * v[0].hypot(v[1])).fold(0.0, f64::max);
    let mut drawn: Vec<Option<Arrow>> = Vec::new();
    for ((b, r), v) in load_places(m).into_iter().zip(vectors) {
        let p = f.bodies[b].act(&r);
        let length = k * v[0].hypot(v[1]);
        if length == 0.0 || length < LEAST_ARROW * longest {
            drawn.push(None);
            continue;
        }
        let (ux, uy) = (k * v[0] / length, k * v[1] / length);
        let along = |a: &Arrow| {
            let (d, e) = (a.1.0 - a.0.0, a.1.1 - a.0.1);
            let n = d.hypot(e);
            (a.0.0 - p.x).hypot(a.0.1 - p.y) <= 0.2 * longest && (d * ux + e * uy) > 0.99 * n
        };
        let beside = drawn.iter().flatten().filter(|a| along(a)).count() as f64;
        let from = (p.x - uy * 0.05 * longest * beside, p.y + ux * 0.05 * longest * beside);
        drawn.push(Some((from, (from.0 + k * v[0], from.1 + k * v[1]))));
    }
    drawn
}

/// Where each load of [`force_vectors`] acts: (body, point in its frame).
fn load_places(m: &Mechanism) -> Vec<(usize, Point2<f64>)> {
    let heavy = m.bodies.iter().enumerate().filter(|(_, b)| b.mass > 0.0).map(|(i, b)| (i, b.com));
    m.forces.iter().map(|p| (p.body, p.at)).chain(heavy).collect()
}

/// Names beside the last shape's loads: past a force's head, beside a moment's turn.
fn load_names(fig: &mut Figure, m: &Mechanism, s: &Solution, color: Color, per_newton: Option<f64>) {
    let f = body_frames(m, s);
    let names = m
        .forces
        .iter()
        .map(|p| p.name.clone())
        .chain(m.bodies.iter().filter(|b| b.mass > 0.0).map(|b| format!("weight of {}", b.name)));
    let moments = s.loads.force.iter().map(|l| l.moment).chain(std::iter::repeat(0.0));
    let drawn = arrows(m, s, per_newton);
    for ((((b, r), name), arrow), moment) in load_places(m).into_iter().zip(names).zip(drawn).zip(moments) {
        let p = f.bodies[b].act(&r);
        // A force with no arrow and no moment has no mark to name.
        if arrow.is_none() && moment == 0.0 {
            continue;
        }
        let (ux, uy) = match arrow {
            Some((from, to)) => {
                let n = (to.0 - from.0).hypot(to.1 - from.1);
                ((to.0 - from.0) / n, (to.1 - from.1) / n)
            }
            None => (0.7, 0.7),
        };
        let n = if arrow.is_some() { 1.0 } else { 0.0 };
        let at = arrow.map_or((p[0], p[1]), |a| a.1);
        let anchor = if ux > 0.3 {
            Anchor::Start
        } else if ux < -0.3 {
            Anchor::End
        } else {
            Anchor::Middle
        };
        // Beyond the head (px: y down), or beside the moment's turn.
        let offset = if n > 0.0 { (10.0 * ux, -14.0 * uy + 6.0) } else { (24.0, -18.0) };
        fig.marks.push(Mark::Label { at, offset, text: name, color, anchor });
    }
}

/// What a figure marks beyond the shapes: each flexure's yield strength
/// (Pa) on the stress colour bar, and where a sweep lost stability.
#[derive(Default)]
pub struct Marks {
    pub yields: Vec<(String, f64)>,
    pub limit: Option<String>,
}

/// The figure, and the arrows' scale (m per N) if any force is drawn.
pub fn figure(
    m: &Mechanism,
    title: &str,
    unloaded: &Solution,
    loaded: &[(String, Solution)],
    marks: &Marks,
) -> (Figure, Option<f64>) {
    let mut fig = Figure::new(title, "x (m)", "y (m)");
    fig.equal_aspect = true;
    fig.width = 1200.0;
    fig.height = 760.0;
    fig.place = Place::Outside;
    fig.fit_height = true;

    // Sizes from the unloaded mechanism: links 2.4 % of it thick, the
    // longest force arrow about a quarter of it, at a round scale.
    let f0 = body_frames(m, unloaded);
    let mut pts: Vec<[f64; 2]> = (0..m.bodies.len())
        .flat_map(|b| attachments(m, b).into_iter().map(move |r| (b, r)))
        .map(|(b, r)| f0.bodies[b].act(&r))
        .map(|p| [p.x, p.y])
        .collect();
    pts.extend(m.joints.iter().zip(&f0.roots).map(|(_, r)| [r.x, r.y]));
    pts.extend(f0.bodies.iter().map(|b| [b.x, b.y]));
    let span = |i: usize| {
        let (lo, hi) = pts.iter().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p[i]), b.max(p[i])));
        if hi > lo { hi - lo } else { 0.0 }
    };
    let lengths = m.joints.iter().map(|j| j.kind.flexure().map_or(0.0, |fl| fl.length()));
    let extent = span(0).max(span(1)).max(lengths.fold(0.0, f64::max)).max(1e-9);
    let thick = 0.012 * extent;
    let largest = loaded.iter().flat_map(|(_, s)| force_vectors(m, s)).map(|v| v[0].hypot(v[1])).fold(0.0, f64::max);
    let per_newton = (largest > 0.0).then(|| round_down(0.25 * extent / largest));
    // The colour bar runs from 0 to the largest stress (1 MPa if none is
    // loaded), and on past the highest yield strength, so that its mark shows.
    let highest_yield = marks.yields.iter().map(|y| y.1).fold(0.0, f64::max);
    let stress_top =
        stress_max(m, loaded).map(|top| if top > 0.0 { top } else { 1e6 }).map(|top| top.max(1.05 * highest_yield));

    // The ground, once: it does not move.
    let ground: Vec<[f64; 2]> = attachments(m, 0).iter().map(|p| [p.x, p.y]).collect();
    let (fill, stroke) = (Fill { color: GROUND.tint(0.4), opacity: 0.8 }, Stroke::solid(GROUND, 1.5));
    if !ground.is_empty() {
        let points = slab(&ground, thick);
        fig.marks.push(Mark::Path { points, stroke: Some(stroke), fill: Some(fill), closed: true });
    }
    fig.legend.push(Entry { swatch: Swatch::Area(fill, stroke), label: "ground".into() });
    let link = |c: Color| Swatch::Area(Fill { color: c.tint(0.55), opacity: 0.55 }, Stroke::solid(c, 1.5));
    shape(&mut fig, m, unloaded, GRAY, thick, Loads::Hidden);
    fig.legend.push(Entry { swatch: link(GRAY), label: "unloaded".into() });
    for (i, (label, s)) in loaded.iter().enumerate() {
        let color = SHAPES[i % SHAPES.len()];
        shape(&mut fig, m, s, color, thick, Loads::Drawn { per_newton, stress_top });
        fig.legend.push(Entry { swatch: link(color), label: label.clone() });
    }
    if let Some((_, s)) = loaded.last() {
        load_names(&mut fig, m, s, SHAPES[(loaded.len() - 1) % SHAPES.len()], per_newton);
    }

    // Keys for what every shape shows.
    if m.joints.iter().any(|j| j.kind.flexure().is_some()) {
        let swatch = Swatch::Line(Some(Stroke::solid(KEY, FLEXURE_WIDTH)), None);
        fig.legend.push(Entry { swatch, label: "flexure".into() });
    }
    let drawn = |want: Symbol| m.joints.iter().any(|j| symbol(j.kind.joint()) == Some(want));
    let revolute = drawn(Symbol::Pin);
    let pin = m.closures.iter().any(|c| c.holds == Holds::Pin);
    if revolute || pin {
        let swatch = Swatch::Line(None, Some((Marker::Circle, KEY, false)));
        let label = match (revolute, pin) {
            (true, true) => "revolute joint or pin",
            (true, false) => "revolute joint",
            _ => "pin",
        };
        fig.legend.push(Entry { swatch, label: label.into() });
    }
    if drawn(Symbol::Slider) {
        let swatch = Swatch::Line(
            Some(Stroke { color: KEY, width: 2.0, dash: Dash::Dashed }),
            Some((Marker::Square, KEY, false)),
        );
        fig.legend.push(Entry { swatch, label: "slider (its travel dashed)".into() });
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
        let loads: Vec<[f64; 3]> =
            loaded.iter().map(|(_, s)| s.loads.force[i]).map(|l| [l.fx, l.fy, l.moment]).collect();
        let moments: Vec<f64> = loads.iter().map(|l| l[2]).collect();
        let pushes = loads.iter().any(|l| l[0] != 0.0 || l[1] != 0.0);
        if pushes || moments.iter().all(|&x| x == 0.0) {
            let same = loads.windows(2).all(|w| w[0][..2] == w[1][..2]);
            let value = match loads.first() {
                Some(l) if same => format!("({}, {}) N", short(l[0]), short(l[1])),
                _ => values(&loads.iter().map(|l| l[0].hypot(l[1])).collect::<Vec<_>>(), "N"),
            };
            let label = format!("force {} on {body}: {value}", p.name);
            fig.legend.push(Entry { swatch: Swatch::Arrow(KEY), label });
        }
        if moments.iter().any(|&x| x != 0.0) {
            let positive = moments.iter().all(|&x| x > 0.0);
            let value = if positive || moments.iter().all(|&x| x < 0.0) {
                let sizes: Vec<f64> = moments.iter().map(|x| x.abs()).collect();
                format!("{} {}", values(&sizes, "N·m"), if positive { "counter-clockwise" } else { "clockwise" })
            } else {
                format!("{} (+: counter-clockwise)", values(&moments, "N·m"))
            };
            let label = format!("moment {} on {body}: {value}", p.name);
            fig.legend.push(Entry { swatch: Swatch::Turn(KEY), label });
        }
    }
    if loaded.iter().any(|(_, s)| s.loads.gravity != nalgebra::Vector2::zeros()) {
        for b in m.bodies.iter().filter(|b| b.mass > 0.0) {
            let w: Vec<f64> =
                loaded.iter().map(|(_, s)| b.mass * s.loads.gravity[0].hypot(s.loads.gravity[1])).collect();
            fig.legend.push(Entry {
                swatch: Swatch::Arrow(KEY),
                label: format!("weight of {}: {}", b.name, values(&w, "N")),
            });
        }
    }
    if let Some(k) = per_newton {
        fig.legend.push(Entry { swatch: Swatch::Note, label: format!("force arrows: {} m per N", short(k)) });
    }
    if let Some(limit) = &marks.limit {
        fig.legend.push(Entry { swatch: Swatch::Note, label: limit.clone() });
    }
    if let Some(top) = stress_top {
        let mut label = "flexures' bending stress (MPa)".to_string();
        if !marks.yields.is_empty() {
            let named: Vec<String> =
                marks.yields.iter().map(|(name, y)| format!("{name} {} MPa", short(y / 1e6))).collect();
            label += &format!("; black line: yield strength ({})", named.join(", "));
        }
        let bar_marks = marks.yields.iter().map(|y| y.1 / 1e6).collect();
        fig.color_bar = Some(ColorBar { label, lo: 0.0, hi: top / 1e6, marks: bar_marks });
        let plain = m.joints.iter().filter_map(|j| j.kind.flexure()).any(|fl| fl.section().modulus().is_none());
        let label = if plain {
            "loaded flexures coloured by stress; those given by ei alone (no thickness) in their shape's colour"
        } else {
            "loaded flexures coloured by bending stress"
        };
        fig.legend.push(Entry { swatch: Swatch::Note, label: label.into() });
    }
    (fig, per_newton)
}

#[cfg(test)]
mod tests {
    use super::{attachments, hull, slab};
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
        let pts: Vec<[f64; 2]> =
            attachments(&m, stage).iter().map(|r| f.bodies[stage].act(r)).map(|p| [p.x, p.y]).collect();
        let r = 1e-3;
        let xs: Vec<f64> = slab(&pts, r).iter().map(|p| p.0).collect();
        let (lo, hi) = xs.iter().fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
        // Closure solved to ~1e-12 m; the slab reaches r beyond each tip.
        assert!((lo + r).abs() < 1e-9 && (hi - 0.04 - r).abs() < 1e-9, "{lo} {hi}");
    }
}
