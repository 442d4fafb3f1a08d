//! Pictures of mechanisms (`flexure_cli::drawing`, one drawing for both
//! dimensions), most of them spatial: the
//! views' projections, the SVG as XML with one centreline per flexure, the
//! stress colour bar against the library's own peak stress, painting in
//! depth, and the snapshots of a simulated motion. The mechanisms are
//! built in code: a finger of three phalanges on spatial flexures bent out
//! of its plane by a tip load, a parallelogram stage loaded out of its
//! plane, and a chain of two flexures in perpendicular planes.
//!
//! With `FLEXURE_PICTURES=DIR` set, `pictures_of_the_finger_and_the_stage`
//! and `a_motion_draws_five_snapshots_over_the_rest_shape` also write their
//! SVGs into DIR, to be looked at.

use flexure::dynamics::integrate::MotionSettings as Motion;
use flexure::dynamics::simulation::{SimulationSettings, Start, simulate};
use flexure::mechanism::Fixed;
use flexure::mechanism::Holds;
use flexure::mechanism::kinematics::frames;
use flexure::mechanism::spatial::{
    SpatialBody, SpatialClosure, SpatialJointKind, SpatialJointSpec, SpatialMechanism, SpatialPointLoad, SpatialTendon,
};
use flexure::mechanism::statics::{Solution, assemble_unloaded, solve};
use flexure::section::{Profile, Shear, SpatialSection};
use flexure::space::Spatial;
use flexure::spatial::SpatialFlexure;
use flexure_chart::{Figure, Mark};
use flexure_cli::drawing::Marks;
use flexure_cli::projection::View;
use flexure_cli::scene::{run_figures, shapes_figure};
use nalgebra::{Isometry3, Matrix3, Point3, Rotation3, Translation3, UnitQuaternion, Vector3, Vector6};

fn spec(name: &str, kind: SpatialJointKind, parent: usize, child: usize, origin: Isometry3<f64>) -> SpatialJointSpec {
    SpatialJointSpec::new(name, kind, parent, child, origin)
}

fn bodies(names: &[&str]) -> Vec<SpatialBody> {
    names.iter().map(|n| SpatialBody::massless(n)).collect()
}

fn flexure_joint(f: SpatialFlexure) -> SpatialJointKind {
    SpatialJointKind::Flexure(Box::new(f))
}

fn load(name: &str, body: usize, at: [f64; 3], moment: [f64; 3], force: [f64; 3]) -> SpatialPointLoad {
    SpatialPointLoad {
        name: name.into(),
        body,
        at: Point3::from(at),
        wrench: Vector6::new(moment[0], moment[1], moment[2], force[0], force[1], force[2]),
    }
}

/// A steel wire flexure, 0.8 mm across.
fn wire(length: f64) -> SpatialFlexure {
    let section = SpatialSection::circle(200e9, 0.3, Profile::Constant(0.8e-3)).unwrap();
    SpatialFlexure::new(length, section, [3, 3, 3]).unwrap()
}

/// A finger of three phalanges (45, 30 and 25 mm) on 15 mm steel wire
/// flexures, each joint curled 0.3 rad in the x–y plane, a flexor tendon
/// along its palm side at 1 N, and a tip load of 0.2 N along −z (out of the
/// finger's plane) with 0.05 N along −y.
fn finger() -> SpatialMechanism {
    let curl = |p: [f64; 3]| {
        Isometry3::from_parts(Translation3::new(p[0], p[1], p[2]), UnitQuaternion::from_euler_angles(0.0, 0.0, -0.3))
    };
    let joints = vec![
        spec("mcp", flexure_joint(wire(0.015)), 0, 1, Isometry3::identity()),
        spec("pip", flexure_joint(wire(0.015)), 1, 2, curl([0.045, 0.0, 0.0])),
        spec("dip", flexure_joint(wire(0.015)), 2, 3, curl([0.03, 0.0, 0.0])),
    ];
    let flexor = SpatialTendon {
        name: "flexor".into(),
        tension: 1.0,
        path: vec![
            (0, Point3::new(0.0, -0.006, 0.0)),
            (1, Point3::new(0.005, -0.006, 0.0)),
            (1, Point3::new(0.04, -0.006, 0.0)),
            (2, Point3::new(0.005, -0.006, 0.0)),
            (2, Point3::new(0.025, -0.006, 0.0)),
            (3, Point3::new(0.005, -0.006, 0.0)),
        ],
    };
    let tip = load("tip", 3, [0.025, 0.0, 0.0], [0.0; 3], [0.0, -0.05, -0.2]);
    let names = ["ground", "proximal", "middle", "distal"];
    SpatialMechanism::new(bodies(&names), joints, vec![flexor], vec![tip], vec![], Vector3::zeros()).unwrap()
}

/// A parallelogram stage: two 60 mm steel strips (0.4 mm thick along x,
/// 0.6 mm wide along y) standing up along z from the ground 40 mm apart, the
/// stage welded across their tips, pushed at its middle by 0.2 N along x
/// (in the parallelogram's x–z plane) and 0.25 N along y (out of it).
fn stage() -> SpatialMechanism {
    let strip = || {
        let s =
            SpatialSection::rectangle(200e9, Shear::Poisson(0.3), Profile::Constant(0.6e-3), Profile::Constant(0.4e-3))
                .unwrap();
        flexure_joint(SpatialFlexure::new(0.06, s, [3, 3, 3]).unwrap())
    };
    // Root frames with x (the strip) along z, y (its thickness) along x, z (its width) along y.
    let up = |x: f64| {
        let r = Rotation3::from_matrix_unchecked(Matrix3::new(0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0));
        Isometry3::from_parts(Translation3::new(x, 0.0, 0.0), UnitQuaternion::from_rotation_matrix(&r))
    };
    let joints = vec![spec("left", strip(), 0, 1, up(0.0)), spec("right", strip(), 0, 2, up(0.04))];
    // In the stage's frame (the left tip's, rest axes as the root's) the right tip is 0.04 along y.
    let weld = SpatialClosure {
        holds: Holds::Weld,
        a: 1,
        a_origin: Isometry3::translation(0.0, 0.04, 0.0),
        b: 2,
        b_origin: Isometry3::identity(),
    };
    let push = load("push", 1, [0.0, 0.02, 0.0], [0.0; 3], [0.2, 0.25, 0.0]);
    SpatialMechanism::new(
        bodies(&["ground", "stage", "right tip"]),
        joints,
        vec![],
        vec![push],
        vec![weld],
        Vector3::zeros(),
    )
    .unwrap()
}

/// Two flexures in perpendicular planes (the second's root turned a
/// quarter about x), given by their stiffnesses alone, with a tip load.
fn chain() -> SpatialMechanism {
    let f = |l: f64| SpatialFlexure::new(l, SpatialSection::uniform(0.8, 2.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
    let turned = Isometry3::from_parts(
        Translation3::new(0.01, 0.0, 0.0),
        UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_2, 0.0, 0.0),
    );
    let joints = vec![
        spec("one", flexure_joint(f(0.05)), 0, 1, Isometry3::identity()),
        spec("two", flexure_joint(f(0.03)), 1, 2, turned),
    ];
    let tip = load("tip", 2, [0.0; 3], [0.0, 0.0, 0.01], [0.0, 2.0, 3.0]);
    SpatialMechanism::new(bodies(&["ground", "mid", "tip"]), joints, vec![], vec![tip], vec![], Vector3::zeros())
        .unwrap()
}

fn unloaded(m: &SpatialMechanism) -> Solution<Spatial> {
    assemble_unloaded(m, &Default::default()).unwrap()
}

fn picture(m: &SpatialMechanism, view: View, stress: bool) -> (Figure, Solution<Spatial>) {
    let s = solve(m, &Default::default()).unwrap();
    let (fig, _) =
        shapes_figure(m, "test", &unloaded(m), &[("loaded".into(), s.clone())], &Marks::default(), view, stress)
            .unwrap();
    (fig, s)
}

/// Reference: the conventions of `docs/cli.md` (`draw --view`), exactly
/// (1e-15 for the isometric's square roots): a point on +z is up in the
/// front, side and isometric views and all depth in the top view; x is
/// right in front and top, y right in the side view; isometric x lower
/// left, y lower right.
#[test]
fn each_view_maps_known_points_where_the_conventions_say() {
    let z = Vector3::new(0.0, 0.0, 2.0);
    for view in [View::Front, View::Side] {
        assert_eq!(view.project(&z), ((0.0, 2.0), 0.0), "{view:?}");
    }
    let ((a, b), d) = View::Iso.project(&z);
    assert!(a.abs() < 1e-15 && (b - 4.0 / 6f64.sqrt()).abs() < 1e-15 && (d - 2.0 / 3f64.sqrt()).abs() < 1e-15);
    assert_eq!(View::Top.project(&z), ((0.0, 0.0), 2.0));
    let p = Vector3::new(1.0, 2.0, 3.0);
    assert_eq!(View::Front.project(&p), ((1.0, 3.0), -2.0));
    assert_eq!(View::Side.project(&p), ((2.0, 3.0), 1.0));
    assert_eq!(View::Top.project(&p), ((1.0, 2.0), 3.0));
    let ((xa, xb), _) = View::Iso.project(&Vector3::x());
    let ((ya, yb), _) = View::Iso.project(&Vector3::y());
    assert!(xa < 0.0 && xb < 0.0 && ya > 0.0 && yb < 0.0 && (xb - yb).abs() < 1e-15 && (xa + ya).abs() < 1e-15);
}

/// The `<polyline>`s of an SVG drawn `width` px wide.
fn polylines(svg: &roxmltree::Document, width: &str) -> usize {
    svg.descendants().filter(|n| n.has_tag_name("polyline") && n.attribute("stroke-width") == Some(width)).count()
}

/// The SVG of the two-flexure chain, from every view, is XML (parsed by
/// roxmltree) and holds one centreline per flexure per shape: the only
/// polylines drawn at the flexure width of 5 px, 2 flexures × 2 shapes
/// (unloaded and loaded); without stress colouring each is one path.
#[test]
fn the_chain_is_xml_with_one_path_per_flexure() {
    let m = chain();
    for view in View::ALL {
        let (fig, _) = picture(&m, view, false);
        let svg = flexure_chart::render(&fig).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("{view:?}: {e}"));
        assert_eq!(doc.root_element().tag_name().name(), "svg");
        assert_eq!(polylines(&doc, "5.00"), 4, "{view:?}");
        // Each centreline has its 41 sections, ends at the joints' roots and tips.
        let lines: Vec<&Mark> = fig
            .marks
            .iter()
            .filter(|mk| matches!(mk, Mark::Path { stroke: Some(s), closed: false, .. } if s.width == 5.0))
            .collect();
        assert!(lines.iter().all(|mk| matches!(mk, Mark::Path { points, .. } if points.len() == 41)));
    }
}

/// Reference: `flexure::spatial::peak_stress` of every flexure of the
/// loaded finger, computed here: the colour bar's top is the largest of
/// them (MPa, to 1e-12 relative), and every segment's colour is from the
/// ramp (no flexure drawn in its shape's plain colour: all are shaped).
#[test]
fn the_stress_bar_tops_at_the_largest_peak_stress() {
    let m = finger();
    let (fig, s) = picture(&m, View::Iso, true);
    let mut largest: f64 = 0.0;
    for j in &m.joints {
        let fl = j.kind.flexure().unwrap();
        let peak = flexure::spatial::peak_stress(fl, &s.q[j.offset..j.offset + fl.coordinates()]).unwrap();
        largest = largest.max(peak.stress.von_mises);
    }
    assert!(largest > 10e6, "a loaded finger is stressed: {largest}");
    let bar = fig.color_bar.as_ref().expect("a colour bar");
    assert!((bar.hi - largest / 1e6).abs() < 1e-12 * bar.hi && bar.lo == 0.0, "{} against {}", bar.hi, largest / 1e6);
    assert!(bar.label.contains("von Mises"));
    // Loaded: 3 flexures × 40 segments; unloaded: 3 centrelines.
    let svg = flexure_chart::render(&fig).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    assert_eq!(polylines(&doc, "5.00"), 3 * 40 + 3);
    // Without stress: no bar.
    assert!(picture(&m, View::Iso, false).0.color_bar.is_none());
}

/// The centres of the links' hulls (fill opacity 0.55), in the order drawn.
fn hull_order(fig: &Figure) -> Vec<(f64, f64)> {
    fig.marks
        .iter()
        .filter_map(|mk| match mk {
            Mark::Path { points, closed: true, fill: Some(f), .. } if f.opacity == 0.55 => {
                let n = points.len() as f64;
                Some((points.iter().map(|p| p.0).sum::<f64>() / n, points.iter().map(|p| p.1).sum::<f64>() / n))
            }
            _ => None,
        })
        .collect()
}

/// Painting in depth: two links welded to the ground, `a` at y = −0.1,
/// z = 0 and `b` at y = +0.1, z = 0.02. The front view looks along +y, so
/// `a` is near and `b` far: `b` is drawn first, against the joints'
/// order. The top view looks down −z, so `b` (higher) is near: drawn last.
#[test]
fn near_parts_are_painted_over_far_ones() {
    let joints = vec![
        spec("a", SpatialJointKind::Fixed(Fixed), 0, 1, Isometry3::translation(0.05, -0.1, 0.0)),
        spec("b", SpatialJointKind::Fixed(Fixed), 0, 2, Isometry3::translation(0.05, 0.1, 0.02)),
    ];
    let mut b = bodies(&["ground", "a", "b"]);
    for body in &mut b[1..] {
        body.mass = 1.0;
        body.com = Point3::new(0.05, 0.0, 0.0);
    }
    let m = SpatialMechanism::new(b, joints, vec![], vec![], vec![], Vector3::zeros()).unwrap();
    let s = unloaded(&m);
    // The loaded shape's two hulls are the last two (the unloaded grey ones come first).
    let order = |view: View| {
        let (fig, _) =
            shapes_figure(&m, "links", &s, &[("same".into(), s.clone())], &Marks::default(), view, false).unwrap();
        let h = hull_order(&fig);
        assert_eq!(h.len(), 4);
        h[2..].to_vec()
    };
    // Front: picture y is z; b (z = 0.02) first, then a (z = 0).
    let front = order(View::Front);
    assert!((front[0].1 - 0.02).abs() < 1e-12 && front[1].1.abs() < 1e-12, "{front:?}");
    // Top: picture y is y; a (y = −0.1) first, then b (y = 0.1).
    let top = order(View::Top);
    assert!((top[0].1 + 0.1).abs() < 1e-12 && (top[1].1 - 0.1).abs() < 1e-12, "{top:?}");
    let f = frames(&m, &s.q);
    assert!(f.bodies[2].translation.z > f.bodies[1].translation.z);
}

/// The snapshots of a simulated motion: a steel wire cantilever with a
/// 5 g tip mass (rotary inertia 1e-6 kg·m²: with 1e-8, the wire's twist,
/// GJ/L over so little inertia about 11 000 rad/s, set the step, and the
/// run took 3 588 steps, not 695, to draw the same pictures), starting at
/// rest unloaded under gravity, drawn at five
/// evenly spaced samples as the planar `draw --simulate` picks them, each
/// labelled by its time; then the bodies' rotations and origins against
/// time, stacked into one SVG that parses as XML.
#[test]
fn a_motion_draws_five_snapshots_over_the_rest_shape() {
    let mut b = bodies(&["ground", "bob"]);
    b[1].mass = 0.005;
    b[1].com = Point3::new(0.005, 0.0, 0.0);
    b[1].inertia = Matrix3::identity() * 1e-6;
    let m = SpatialMechanism::new(
        b,
        vec![spec("wire", flexure_joint(wire(0.04)), 0, 1, Isometry3::identity())],
        vec![],
        vec![],
        vec![],
        Vector3::new(0.0, 0.0, -9.81),
    )
    .unwrap();
    let motion = Motion { duration: 0.05, every: 0.005, ..Default::default() };
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none());
    let drawn = run_figures(&m, "bob", &unloaded(&m), &run, View::Front, true).unwrap();
    // Eleven samples, 0 to 10: the planar picks (k · 10 + 2)/4 for k = 0…4.
    assert_eq!(run.time.len(), 11);
    assert_eq!(drawn.snapshots, [0, 3, 5, 8, 10].map(|k| run.time[k]));
    assert_eq!(drawn.figures.len(), 3);
    let labels: Vec<&str> = drawn.figures[0].legend.iter().map(|e| e.label.as_str()).collect();
    for t in ["t = 0 s", "t = 0.025 s", "t = 0.05 s", "weight of bob: 0.04905 N"] {
        assert!(labels.contains(&t), "{t} not in {labels:?}");
    }
    let svg = flexure_chart::stack(&drawn.figures).unwrap();
    roxmltree::Document::parse(&svg).unwrap();
    if let Some(dir) = std::env::var_os("FLEXURE_PICTURES") {
        std::fs::write(std::path::Path::new(&dir).join("bob-motion-front.svg"), svg).unwrap();
    }
}

/// Pictures of the finger and the stage from iso, front, top and side:
/// each renders, and each legend names the view, the loads and the arrow
/// scale. With `FLEXURE_PICTURES` set, the SVGs are written there.
#[test]
fn pictures_of_the_finger_and_the_stage() {
    let out = std::env::var_os("FLEXURE_PICTURES").map(std::path::PathBuf::from);
    for (name, m) in [("finger", finger()), ("stage", stage())] {
        let s = solve(&m, &Default::default()).unwrap();
        assert!(s.stable, "{name}");
        for view in View::ALL {
            let marks = Marks { yields: vec![], limit: None };
            let (fig, per_newton) = shapes_figure(
                &m,
                &format!("{name} ({} view)", view.name()),
                &unloaded(&m),
                &[("loaded".into(), s.clone())],
                &marks,
                view,
                true,
            )
            .unwrap();
            assert!(per_newton.is_some());
            let labels: Vec<&str> = fig.legend.iter().map(|e| e.label.as_str()).collect();
            assert!(labels.contains(&view.description()), "{labels:?}");
            assert!(labels.iter().any(|l| l.starts_with("force arrows:")), "{labels:?}");
            let svg = flexure_chart::render(&fig).unwrap();
            roxmltree::Document::parse(&svg).unwrap();
            if let Some(dir) = &out {
                std::fs::write(dir.join(format!("{name}-{}.svg", view.name())), svg).unwrap();
            }
        }
    }
}

/// A motion of many bodies: a chain of 20 links on hinges about y and z in
/// turn, swinging under gravity. Each motion chart lists every body once
/// (and its three components' dashes once), and every legend entry lies
/// inside its figure: the text's baseline at least its descent (0.3 of
/// its size) above the foot and below its size from the top, and its start
/// plus a generous 0.72 em a character within the width. Before the legend
/// was laid out in columns the entries past the 14th fell off the foot.
#[test]
fn a_motion_of_many_bodies_keeps_every_legend_entry_inside_its_figure() {
    use flexure::mechanism::spatial::RevoluteUnaligned;
    let count = 20;
    let names: Vec<String> =
        std::iter::once("ground".to_string()).chain((1..=count).map(|i| format!("link_{i}"))).collect();
    let mut b = bodies(&names.iter().map(String::as_str).collect::<Vec<_>>());
    for body in &mut b[1..] {
        body.mass = 0.002;
        body.com = Point3::new(0.005, 0.0, 0.0);
        body.inertia = Matrix3::identity() * 1e-8;
    }
    let joints = (1..=count)
        .map(|i| {
            let axis = if i % 2 == 0 { Vector3::y_axis() } else { Vector3::z_axis() };
            let origin = if i == 1 { Isometry3::identity() } else { Isometry3::translation(0.01, 0.0, 0.0) };
            let hinge = SpatialJointKind::Revolute(RevoluteUnaligned { axis, stiffness: 0.02, rest: 0.0 });
            spec(&format!("hinge_{i}"), hinge, i - 1, i, origin)
        })
        .collect();
    let m = SpatialMechanism::new(b, joints, vec![], vec![], vec![], Vector3::new(0.0, -9.81, -9.81)).unwrap();
    let motion = Motion { duration: 0.01, every: 0.002, ..Default::default() };
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    let drawn = run_figures(&m, "chain", &unloaded(&m), &run, View::Iso, true).unwrap();
    let svg = flexure_chart::stack(&drawn.figures).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let number = |n: roxmltree::Node, a: &str| n.attribute(a).and_then(|v| v.parse::<f64>().ok()).unwrap();
    // The nested figures: the drawing, then the two charts.
    let figures: Vec<roxmltree::Node> = doc.root_element().children().filter(|n| n.has_tag_name("svg")).collect();
    assert_eq!(figures.len(), 3);
    for (k, fig) in figures.iter().enumerate().skip(1) {
        let (width, height) = (number(*fig, "width"), number(*fig, "height"));
        let legend: Vec<(String, f64, f64, f64)> = fig
            .descendants()
            .filter(|n| n.has_tag_name("text") && n.attribute("class") == Some("legend"))
            .map(|n| (n.text().unwrap_or_default().to_string(), number(n, "x"), number(n, "y"), number(n, "font-size")))
            .collect();
        for (label, x, y, size) in &legend {
            let right = x + 0.72 * size * label.chars().count() as f64;
            assert!(*y + 0.3 * size <= height && *y >= *size, "chart {k}: {label} at y = {y}, figure {height} px high");
            assert!(*x >= 0.0 && right <= width, "chart {k}: {label} from x = {x} to {right}, figure {width} px wide");
        }
        let labels: Vec<&str> = legend.iter().map(|e| e.0.as_str()).collect();
        for name in &names[1..] {
            assert!(labels.contains(&name.as_str()), "chart {k}: {name} not in the legend {labels:?}");
        }
        assert_eq!(legend.len(), count + 3, "chart {k}: one entry a body and one a component: {labels:?}");
    }
    if let Some(dir) = std::env::var_os("FLEXURE_PICTURES") {
        std::fs::write(std::path::Path::new(&dir).join("chain-motion-iso.svg"), svg).unwrap();
    }
}

/// The `<text>` elements of an SVG: (class, text, x, y, font size), in px.
fn texts(svg: &str) -> Vec<(String, String, f64, f64, f64)> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let number = |n: roxmltree::Node, a: &str| n.attribute(a).and_then(|v| v.parse::<f64>().ok()).unwrap_or(f64::NAN);
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| {
            let class = n.attribute("class").unwrap_or_default().to_string();
            (class, n.text().unwrap_or_default().to_string(), number(n, "x"), number(n, "y"), number(n, "font-size"))
        })
        .collect()
}

/// A label's box (px), at the chart's own measure of text: 0.6 em a
/// character wide (the widest it sets a lowercase letter), one em high,
/// placed by its anchor.
fn label_box(svg: &str, text: &str) -> Option<[f64; 4]> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let n = doc.descendants().find(|n| n.has_tag_name("text") && n.text() == Some(text))?;
    let number = |a: &str| n.attribute(a).and_then(|v| v.parse::<f64>().ok()).unwrap();
    let (x, y, size) = (number("x"), number("y"), number("font-size"));
    let width = 0.6 * size * text.chars().count() as f64;
    let left = match n.attribute("text-anchor") {
        Some("end") => x - width,
        Some("middle") => x - 0.5 * width,
        _ => x,
    };
    Some([left, y - size, left + width, y])
}

fn overlap(a: [f64; 4], b: [f64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// The force arrows (2.5 px wide) of a figure, tail and head in picture units.
fn force_arrows(fig: &Figure) -> Vec<((f64, f64), (f64, f64))> {
    fig.marks
        .iter()
        .filter_map(|mk| match mk {
            Mark::Arrow { from, to, width, .. } if *width == 2.5 => Some((*from, *to)),
            _ => None,
        })
        .collect()
}

/// A steel wire along x from the ground to a tip, with `loads` at the tip.
fn rod(loads: Vec<SpatialPointLoad>) -> SpatialMechanism {
    let joint = spec("rod", flexure_joint(wire(0.05)), 0, 1, Isometry3::identity());
    SpatialMechanism::new(bodies(&["ground", "tip"]), vec![joint], vec![], loads, vec![], Vector3::zeros()).unwrap()
}

/// Issue 35 item 6, in space: two equal forces at the rod's tip ("a" and
/// "b", 0.2 N along −y) are two arrows side by side, tails apart by 0.15
/// of the longest arrow (the drawing's rule, to 1e-12), each named
/// at its own head with the names' boxes apart in the SVG; a zero force
/// ("idle") and one along the line of sight ("lift", +z seen from the top)
/// draw no arrow of no length: "idle" nothing on the picture (the legend
/// keeps it), "lift" a ⊙ named beside it.
#[test]
fn coincident_forces_in_space_are_side_by_side_and_no_arrow_is_of_no_length() {
    let tip = [0.0; 3];
    let m = rod(vec![
        load("a", 1, tip, [0.0; 3], [0.0, -0.2, 0.0]),
        load("b", 1, tip, [0.0; 3], [0.0, -0.2, 0.0]),
        load("idle", 1, tip, [0.0; 3], [0.0; 3]),
        load("lift", 1, tip, [0.0; 3], [0.0, 0.0, 0.1]),
    ]);
    let (fig, s) = picture(&m, View::Top, false);
    assert!(s.stable);
    let arrows = force_arrows(&fig);
    assert_eq!(arrows.len(), 2, "a and b, not idle nor lift: {arrows:?}");
    let length = |a: &((f64, f64), (f64, f64))| (a.1.0 - a.0.0).hypot(a.1.1 - a.0.1);
    let apart = (arrows[0].0.0 - arrows[1].0.0).hypot(arrows[0].0.1 - arrows[1].0.1);
    assert!((apart - 0.15 * length(&arrows[0])).abs() < 1e-12 * length(&arrows[0]), "tails {apart} apart");
    // No arrow anywhere (forces, moments, triad) is of no length.
    for view in View::ALL {
        let (fig, _) = picture(&m, view, false);
        for mk in &fig.marks {
            if let Mark::Arrow { from, to, .. } = mk {
                assert!((to.0 - from.0).hypot(to.1 - from.1) > 0.0, "{view:?}: an arrow of no length at {from:?}");
            }
        }
    }
    // ⊙ at the tip: a hollow circle and a filled dot, 7 px and a quarter of it.
    let sight = fig.marks.iter().filter(|mk| matches!(mk, Mark::Dot { radius, .. } if *radius == 7.0)).count();
    assert_eq!(sight, 1);
    let svg = flexure_chart::render(&fig).unwrap();
    let (a, b) = (label_box(&svg, "a").unwrap(), label_box(&svg, "b").unwrap());
    assert!(!overlap(a, b), "the names cover one another: {a:?} {b:?}");
    assert!(label_box(&svg, "lift").is_some());
    assert!(label_box(&svg, "idle").is_none(), "a zero force is not named on the picture");
    let legend: Vec<&str> = fig.legend.iter().map(|e| e.label.as_str()).collect();
    assert!(legend.contains(&"force idle on tip: (0, 0, 0) N"), "{legend:?}");
}

/// Issue 35 item 6, in the plane: the finger example with a second force
/// "push" equal to its "tip" (0, −0.5) N at the same point, and a zero one
/// ("idle"): two arrows, tails apart, the two names' boxes apart in the
/// SVG (before, the equal arrows' names were drawn on one another), and
/// no arrow of no length.
#[test]
fn coincident_planar_forces_are_named_apart() {
    let dir = tempfile::tempdir().unwrap();
    let examples = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/");
    let extra = "\n[[force]]\nname = \"push\"\nbody = \"distal\"\nat = [0.025, 0.0]\nforce = [0.0, -0.5]\n\
                 \n[[force]]\nname = \"idle\"\nbody = \"distal\"\nat = [0.025, 0.0]\nforce = [0.0, 0.0]\n";
    let file = dir.path().join("two.toml");
    std::fs::write(&file, std::fs::read_to_string(format!("{examples}finger.toml")).unwrap() + extra).unwrap();
    let out = dir.path().join("two.svg");
    let svg = draw(&[file.to_str().unwrap(), "--out", out.to_str().unwrap()], &out);
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let lines: Vec<[f64; 4]> = doc
        .descendants()
        .filter(|n| n.has_tag_name("line") && n.attribute("stroke-width") == Some("2.50"))
        .map(|n| ["x1", "y1", "x2", "y2"].map(|a| n.attribute(a).unwrap().parse().unwrap()))
        .collect();
    assert_eq!(lines.len(), 2, "{lines:?}");
    assert!((lines[0][0] - lines[1][0]).hypot(lines[0][1] - lines[1][1]) > 3.0, "tails apart: {lines:?}");
    assert!(lines.iter().all(|l| (l[2] - l[0]).hypot(l[3] - l[1]) > 0.0));
    let (tip, push) = (label_box(&svg, "tip").unwrap(), label_box(&svg, "push").unwrap());
    assert!(!overlap(tip, push), "the names cover one another: {tip:?} {push:?}");
    assert!(label_box(&svg, "idle").is_none());
}

/// Runs `draw` in-process and returns the SVG it wrote to `out`.
fn draw(args: &[&str], out: &std::path::Path) -> String {
    let (mut o, mut e) = (Vec::new(), Vec::new());
    let code = flexure_cli::run(["flexure", "draw"].into_iter().chain(args.iter().copied()), &mut o, &mut e);
    assert_eq!(code, 0, "{}", String::from_utf8_lossy(&e));
    std::fs::read_to_string(out).unwrap()
}

/// Issue 35 item 6: the colour bar's title stays inside the figure in both
/// dimensions: its right end (0.6 em a character, the chart's measure)
/// within the SVG's width, and its font at least the chart's smallest text
/// (14 px), for the planar tapered finger (its title naming two yield
/// strengths) and the spatial finger, each from every view.
#[test]
fn colour_bar_titles_stay_inside_the_figure_in_both_dimensions() {
    let dir = tempfile::tempdir().unwrap();
    let examples = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/");
    for name in ["tapered_finger", "finger3d"] {
        for view in View::ALL {
            let out = dir.path().join(format!("{name}-{}.svg", view.name()));
            let file = format!("{examples}{name}.toml");
            let svg = draw(&[&file, "--out", out.to_str().unwrap(), "--view", view.name()], &out);
            let doc = roxmltree::Document::parse(&svg).unwrap();
            let width: f64 = doc.root_element().attribute("width").unwrap().parse().unwrap();
            let (_, title, x, _, size) =
                texts(&svg).into_iter().find(|t| t.0 == "bar-label").unwrap_or_else(|| panic!("{name}: no bar"));
            let right = x + 0.6 * size * title.chars().count() as f64;
            assert!(x >= 0.0 && right <= width, "{name} {view:?}: {title:?} runs to {right} px of {width}");
            assert!(size >= flexure_chart::MIN_TEXT, "{name} {view:?}: {size} px");
        }
    }
}

/// One drawing: a planar file is the spatial picture of its mechanism
/// lying at z = 0. Reference: the projection table (docs/cli.md): seen from
/// the front (x right, z up) every point of the planar finger's flexures
/// is at height 0 exactly, and seen from the top (x right, y up) the same
/// points are at the planar backbone's (x, y): the front and top pictures
/// share their x to the last bit, and the top picture spans the finger's
/// curl in y.
#[test]
fn a_planar_file_is_the_spatial_picture_seen_from_the_top() {
    use flexure::space::Planar;
    use flexure_cli::drawing::figure;
    use flexure_cli::scene::{Drawn, scene};
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/finger.toml")).unwrap();
    let m = flexure::mechanism::file::from_toml(&text).unwrap();
    let settings = flexure::mechanism::statics::Settings::default();
    let rest = flexure::mechanism::statics::assemble_unloaded(&m, &settings).unwrap();
    let s = flexure::mechanism::statics::solve(&m, &settings).unwrap();
    let scene = scene(&m);
    let shapes = [("loaded".to_string(), Planar::pose(&m, "loaded", &s.q, &s.loads).unwrap())];
    let centrelines = |view: View| -> Vec<(f64, f64)> {
        let (fig, _) = figure(
            &scene,
            "finger",
            &Planar::pose(&m, "rest", &rest.q, &rest.loads).unwrap(),
            &shapes,
            &Marks::default(),
            view,
            false,
        );
        fig.marks
            .iter()
            .filter_map(|mk| match mk {
                Mark::Path { points, stroke: Some(st), closed: false, .. } if st.width == 5.0 => Some(points.clone()),
                _ => None,
            })
            .flatten()
            .collect()
    };
    let (front, top) = (centrelines(View::Front), centrelines(View::Top));
    assert_eq!(front.len(), top.len());
    assert!(!front.is_empty() && front.iter().all(|p| p.1 == 0.0), "a planar shape lies at z = 0");
    assert!(front.iter().zip(&top).all(|(f, t)| f.0 == t.0));
    let (lo, hi) = top.iter().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
    assert!(hi - lo > 1e-3, "the loaded finger curls in y: {lo} to {hi}");
}

/// Errors name the shape: a q of the wrong length, and one not finite.
#[test]
fn a_shape_that_does_not_fit_is_refused_by_name() {
    let m = rod(vec![]);
    let mut bad = unloaded(&m);
    bad.q.pop();
    let draw = |s: &Solution<Spatial>, label: &str| {
        shapes_figure(&m, "rod", &unloaded(&m), &[(label.into(), s.clone())], &Marks::default(), View::Iso, true)
            .err()
            .unwrap()
    };
    let e = draw(&bad, "short");
    assert!(e.contains("\"short\"") && e.contains(&format!("{} coordinates", m.dof() - 1)), "{e}");
    bad.q.push(f64::NAN);
    let e = draw(&bad, "nan");
    assert!(e.contains("\"nan\"") && e.contains(&format!("q[{}]", m.dof() - 1)), "{e}");
}

/// A flexure from the ground along x, 0.1 m, given by stiffnesses alone
/// (EI = 1 N·m² about both axes), and a tip force of 2 N along +z.
fn plain_rod() -> SpatialMechanism {
    let fl = SpatialFlexure::new(0.1, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [2, 2, 2]).unwrap();
    let joint = spec("rod", flexure_joint(fl), 0, 1, Isometry3::identity());
    let lift = load("lift", 1, [0.0; 3], [0.0; 3], [0.0, 0.0, 2.0]);
    SpatialMechanism::new(bodies(&["ground", "tip"]), vec![joint], vec![], vec![lift], vec![], Vector3::zeros())
        .unwrap()
}

/// Reference: a tip force along +z bends the rod up by the cantilever's
/// $FL^3/(3EI)$ (1e-3 relative; the large-deflection correction is of
/// order $(FL^2/EI)^2$ = 4e-4): the loaded tip is that high in the front
/// view. The arrow: 2 N at the round scale of a quarter of 0.1 m, 0.01 m
/// per N, is 0.02 m long and points straight up in the front view (1e-15).
/// Given by stiffnesses alone: no colour bar, and a note says why.
#[test]
fn a_lifted_tip_is_up_in_the_front_view() {
    let m = plain_rod();
    let s = solve(&m, &Default::default()).unwrap();
    let tip = frames(&m, &s.q).bodies[1].translation.vector;
    let beam = 2.0 * 0.1f64.powi(3) / 3.0;
    assert!((tip.z - beam).abs() < 1e-3 * beam && tip.y.abs() < 1e-12, "{tip}");
    let (fig, per_newton) =
        shapes_figure(&m, "rod", &unloaded(&m), &[("loaded".into(), s)], &Marks::default(), View::Front, true).unwrap();
    assert_eq!(per_newton, Some(0.01));
    let arrows = force_arrows(&fig);
    assert_eq!(arrows.len(), 1);
    let (from, to) = arrows[0];
    assert!((to.1 - from.1 - 0.02).abs() < 1e-15 && (to.0 - from.0).abs() < 1e-15, "{from:?} {to:?}");
    assert!(fig.color_bar.is_none());
    assert!(fig.legend.iter().any(|e| e.label.starts_with("no flexure has a section geometry")));
}

/// The joint interface's symbols, read into the scene: a hinge (its axis
/// the world z), a ball joint, a slider (its axis the world x), and
/// nothing for a weld; drawn from the front, the hinge's axis line is
/// vertical, 2 × 2.5 link half thicknesses long (1e-15), and from the top
/// (seen end-on) there is no line, only its circle.
#[test]
fn each_rigid_joint_has_its_symbol() {
    use flexure::mechanism::spatial::{PrismaticUnaligned, RevoluteUnaligned, Spherical};
    use flexure::space::Spatial;
    use flexure_cli::scene::{Drawn, Symbol};
    let hinge = RevoluteUnaligned { axis: Vector3::z_axis(), stiffness: 1.0, rest: 0.0 };
    let slide = PrismaticUnaligned { axis: Vector3::x_axis(), stiffness: 1.0, rest: 0.0 };
    let step = Isometry3::translation(0.1, 0.0, 0.0);
    let ball = SpatialJointKind::Spherical(Spherical { stiffness: 1.0, rest: [0.0; 3] });
    let joints = vec![
        spec("h", SpatialJointKind::Revolute(hinge), 0, 1, step),
        spec("b", ball, 1, 2, step),
        spec("s", SpatialJointKind::Prismatic(slide), 2, 3, step),
        spec("w", SpatialJointKind::Fixed(Fixed), 3, 4, step),
    ];
    let names = ["ground", "a", "b", "c", "d"];
    let m = SpatialMechanism::new(bodies(&names), joints, vec![], vec![], vec![], Vector3::zeros()).unwrap();
    let rest = unloaded(&m);
    let pose = Spatial::pose(&m, "rest", &rest.q, &rest.loads).unwrap();
    let got: Vec<Symbol> = pose.joints.iter().map(|j| j.symbol).collect();
    assert_eq!(got, [Symbol::Hinge, Symbol::Ball, Symbol::Slider]);
    assert!((pose.joints[0].axis - Vector3::z()).norm() < 1e-15 && (pose.joints[2].axis - Vector3::x()).norm() < 1e-15);
    // Hinge axis lines: 2 px wide, solid, two points, the first symbol drawn of the loaded shape.
    let axis_lines = |view: View| -> Vec<(f64, f64)> {
        let (fig, _) =
            shapes_figure(&m, "j", &rest, &[("same".into(), rest.clone())], &Marks::default(), view, false).unwrap();
        fig.marks
            .iter()
            .filter_map(|mk| match mk {
                Mark::Path { points, stroke: Some(s), closed: false, .. }
                    if s.width == 2.0 && s.dash == flexure_chart::Dash::Solid && points.len() == 2 =>
                {
                    Some((points[1].0 - points[0].0, points[1].1 - points[0].1))
                }
                _ => None,
            })
            .collect()
    };
    // The extent is 0.4 m (four steps of 0.1), so the links' half thickness 0.0048 m.
    let front = axis_lines(View::Front);
    assert!(front.iter().any(|(dx, dz)| *dx == 0.0 && (dz - 5.0 * 0.0048).abs() < 1e-15), "{front:?}");
    // From the top the slider's double line (along x) remains, the hinge's none.
    let top = axis_lines(View::Top);
    assert!(!top.is_empty() && top.iter().all(|(dx, dy)| *dy == 0.0 && *dx != 0.0), "{top:?}");
}

/// Issue 34 item 4 (one drawing for both dimensions): a spatial `draw`
/// shows what only the planar one did. A steel blade stressed past its
/// `yield_strength` (1 MPa): the colour bar marks it and names it, and
/// `draw` gives the warnings `solve` gives on the same file (reference:
/// `solve`'s yield warning, `a_spatial_flexure_reports_its_safety_factor_and_shape`).
/// And a sweep past a stability limit says in its legend which shapes are
/// past it: a sprung arm (k = 1 N·m/rad about z) pushed along its
/// l = 0.1 m loses stability at P = k/l = 10 N (Euler's rigid bar), drawn
/// to its three digits; the sweep stops there, so no shape is past it.
#[test]
fn a_spatial_draw_marks_yield_strengths_and_the_shapes_past_a_limit() {
    let dir = tempfile::tempdir().unwrap();
    let blade = dir.path().join("blade.toml");
    std::fs::write(
        &blade,
        "dimension = 3\n[[joint]]\nname = \"blade\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\n\
         length = 0.05\nmodulus = 2e11\nwidth = 0.01\nthickness = 2e-4\nyield_strength = 1e6\n\
         [[force]]\nname = \"push\"\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nforce = [0.0, 0.5, 0.1]\n",
    )
    .unwrap();
    let (blade, out) = (blade.to_str().unwrap(), dir.path().join("blade.svg"));
    let warnings = |e: &str| e.lines().filter(|l| l.starts_with("warning:")).map(String::from).collect::<Vec<_>>();
    let (_, _, solved) = crate::cli::run(&["solve", blade]);
    let (code, _, drawn) = crate::cli::run(&["draw", blade, "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{drawn}");
    assert!(solved.contains("exceeds the yield strength"), "{solved}");
    assert_eq!(warnings(&drawn), warnings(&solved));
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("black line: yield strength (blade 1 MPa)"), "no yield in the bar's label");
    assert_eq!(svg.matches(r##"stroke="#000000" stroke-width="2.5""##).count(), 1, "one yield mark");

    let arm = dir.path().join("arm.toml");
    std::fs::write(
        &arm,
        "dimension = 3\n[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\naxis = [0.0, 0.0, 1.0]\nparent = \"ground\"\n\
         child = \"arm\"\nstiffness = 1.0\n[[force]]\nname = \"push\"\nbody = \"arm\"\nat = [0.1, 0.0, 0.0]\n",
    )
    .unwrap();
    let out = dir.path().join("arm.svg");
    let args = ["draw", arm.to_str().unwrap(), "--out", out.to_str().unwrap(), "--sweep", "force.push.fx=0:-12:4"];
    let (code, _, err) = crate::cli::run(&args);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(
        ["−10", "-10"]
            .iter()
            .any(|v| svg.contains(&format!("stability lost at force.push.fx = {v}: no shape is drawn past it"))),
        "no limit with its shapes in the legend"
    );
}

/// A steel strip (50 mm) pushed onto a capsule post above a floor: the
/// contact is drawn where the solve puts it, and the unbounded floor is a
/// band that does not widen the picture. References: the solve's own
/// contact (point, normal, force) for the arrow, to rounding: its head at
/// the point, its tail k·N back along the normal (k the figure's scale);
/// the drawing's rule for the band, to rounding: across the mechanism's box
/// (x from 0 to 0.05 m) and 15 % of its 0.05 m size past it, 4 % of it
/// deep behind the floor's line y = −0.01.
#[test]
fn a_contact_is_drawn_at_its_point_and_a_floor_does_not_widen_the_view() {
    use flexure::mechanism::statics::{Settings, Statics, Workspace, follow_touching};
    let text = "[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.05\n\
                modulus = 200e9\nwidth = 0.01\nthickness = 0.0003\norder = 6\n\
                [[force]]\nname = \"push\"\nbody = \"tip\"\nforce = [0.0, -3.0]\n\
                [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n\
                [[geom]]\nname = \"post\"\nbody = \"ground\"\nshape = \"capsule\"\norigin = [0.03, -0.006]\nangle = 0.3\n\
                half_length = 0.004\nradius = 0.002\n";
    let m = flexure::mechanism::file::from_toml(text).unwrap();
    let s = solve(&m, &Settings::default()).unwrap();
    let zero = flexure::space::Planar::zero(&m.loads());
    let (rest, _) = follow_touching(&m, None, &zero, &Settings::default(), &mut Workspace::new(&m)).unwrap();
    let (fig, k) =
        shapes_figure(&m, "strip", &rest, &[("loaded".into(), s.clone())], &Marks::default(), View::Top, true).unwrap();
    let k = k.unwrap();
    let touching: Vec<_> = s.contacts.iter().filter(|c| c.normal_force > 0.0).collect();
    assert!(!touching.is_empty(), "{:?}", s.contacts);
    let arrows = force_arrows(&fig);
    for c in touching {
        let head = (c.point[0], c.point[1]);
        let tail = (head.0 - k * c.normal_force * c.normal[0], head.1 - k * c.normal_force * c.normal[1]);
        let near = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1) < 1e-12;
        assert!(arrows.iter().any(|(from, to)| near(*to, head) && near(*from, tail)), "{c:?} in {arrows:?}");
    }
    // The floor's band: the closed path reaching below the post.
    let band = closed_path(&fig, |points| points.iter().any(|p| p.1 < -0.0105));
    let bounds = |i: usize| {
        band.iter().map(|p| if i == 0 { p.0 } else { p.1 }).fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)))
    };
    let ((x0, x1), (y0, y1)) = (bounds(0), bounds(1));
    let eps = 1e-12;
    assert!((x0 + 0.0075).abs() < eps && (x1 - 0.0575).abs() < eps, "{x0} {x1}");
    assert!((y0 + 0.012).abs() < eps && (y1 + 0.01).abs() < eps, "{y0} {y1}");
}

/// A floor's band spans the shapes as well as the unloaded mechanism: a
/// puck 2 cm across on a sprung slider (10 N/m) pushed 2 N along x rests
/// 0.2 m out over its floor, and the band reaches under it. Reference:
/// the drawing's rule for the band, to rounding: across the box of what
/// is drawn (x from −0.01 to 0.21 m) and 15 % of the mechanism's size
/// (0.02 m, the unloaded puck's) past it. Before, the band spanned the
/// unloaded box alone, to x = 0.013 m, and a ball thrown along its floor
/// rested past its end, floating.
#[test]
fn a_floor_reaches_under_every_shape() {
    use flexure::mechanism::statics::{Settings, Statics, Workspace, follow_touching};
    let text = "[[joint]]\nname = \"sx\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"puck\"\nstiffness = 10.0\n\
                [[body]]\nname = \"puck\"\nmass = 0.1\n\
                [[force]]\nname = \"push\"\nbody = \"puck\"\nforce = [2.0, 0.0]\n\
                [[geom]]\nname = \"disc\"\nbody = \"puck\"\nshape = \"circle\"\nradius = 0.01\n\
                [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.011]\nnormal = [0.0, 1.0]\n";
    let m = flexure::mechanism::file::from_toml(text).unwrap();
    let s = solve(&m, &Settings::default()).unwrap();
    assert!((s.q[0] - 0.2).abs() < 1e-12, "{:?}", s.q);
    let zero = flexure::space::Planar::zero(&m.loads());
    let (rest, _) = follow_touching(&m, None, &zero, &Settings::default(), &mut Workspace::new(&m)).unwrap();
    let (fig, _) =
        shapes_figure(&m, "puck", &rest, &[("pushed".into(), s)], &Marks::default(), View::Top, true).unwrap();
    // The floor's band: the closed path below the puck.
    let band = closed_path(&fig, |points| points.iter().all(|p| p.1 < -0.0105));
    let (x0, x1) = band.iter().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
    assert!((x0 + 0.013).abs() < 1e-12 && (x1 - 0.213).abs() < 1e-12, "{x0} {x1}");
}

/// The first closed path of `fig` whose points `pick` takes: a geom's outline.
fn closed_path(fig: &flexure_chart::Figure, pick: impl Fn(&[(f64, f64)]) -> bool) -> Vec<(f64, f64)> {
    let found = fig.marks.iter().find_map(|mk| match mk {
        Mark::Path { points, closed: true, .. } if pick(points) => Some(points.clone()),
        _ => None,
    });
    found.expect("a closed path")
}
