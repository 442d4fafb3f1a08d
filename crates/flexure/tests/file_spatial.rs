//! The spatial file format (`dimension = 3`, `docs/mechanism-format.md`,
//! "Spatial mechanisms"): every kind and table parses into the numbers the
//! page gives it, planar examples rewritten by a text transform keep their
//! structure, and bad values are errors at their key's line and column.
//! (`tests/spatial_files.rs` solves rewritten examples against the planar
//! answers; `tests/format.rs` keeps the page's key tables and the parser in step.)

use flexure::mechanism::file::{from_toml, spatial_from_toml};
use flexure::mechanism::kinematics::frames;
use flexure::mechanism::spatial::{SpatialClosure, SpatialJointKind, SpatialMechanism};
use flexure::mechanism::{Holds, JointKind};
use flexure::model::Model;
use nalgebra::{Matrix3, Point3, UnitQuaternion, Vector3, Vector6};
use std::f64::consts::PI;

fn rx(a: f64) -> Matrix3<f64> {
    Matrix3::new(1.0, 0.0, 0.0, 0.0, a.cos(), -a.sin(), 0.0, a.sin(), a.cos())
}
fn ry(a: f64) -> Matrix3<f64> {
    Matrix3::new(a.cos(), 0.0, a.sin(), 0.0, 1.0, 0.0, -a.sin(), 0.0, a.cos())
}
fn rz(a: f64) -> Matrix3<f64> {
    Matrix3::new(a.cos(), -a.sin(), 0.0, a.sin(), a.cos(), 0.0, 0.0, 0.0, 1.0)
}

/// URDF's rpy, fixed axes x then y then z: $R = R_z(y)R_y(p)R_x(r)$, multiplied out by hand.
fn urdf(rpy: [f64; 3]) -> Matrix3<f64> {
    rz(rpy[2]) * ry(rpy[1]) * rx(rpy[0])
}

fn rotation(q: &UnitQuaternion<f64>) -> Matrix3<f64> {
    q.to_rotation_matrix().into_inner()
}

/// Reference: $R_z(y)R_y(p)R_x(r)$ from the elementary rotations, to 1e-15,
/// over a grid of angles through every quadrant and near the pitch's ±π/2.
#[test]
fn nalgebra_euler_angles_are_urdf_rpy() {
    let angles = [-3.0, -PI / 2.0 + 1e-3, -0.7, 0.0, 0.4, PI / 2.0 - 1e-3, 2.5];
    for r in angles {
        for p in angles {
            for y in angles {
                let q = UnitQuaternion::from_euler_angles(r, p, y);
                let e = (rotation(&q) - urdf([r, p, y])).amax();
                assert!(e < 1e-15, "rpy ({r}, {p}, {y}): {e:e}");
            }
        }
    }
}

/// One file with every joint kind, every table and every form of a flexure's section.
const ALL_KINDS: &str = r#"dimension = 3
gravity = [0.0, 0.0, -9.81]

[[joint]]
name = "blade"
kind = "flexure"
parent = "ground"
child = "a"
origin = [0.01, 0.02, 0.03]
rpy_deg = [90.0, 0.0, 0.0]
length = 0.05
ei = [2e-3, 1e-3]
ei_y = 4e-3
gj = 3e-3
orders = [2, 3, 4]
subintervals = 12
twist = [0.5, 0.0]
kappa = [1.0, 2.0, 0.0, 0.0]
damping = 0.01

[[joint]]
name = "rod"
kind = "flexure"
parent = "a"
child = "b"
length = 0.02
modulus = 2e11
diameter = 0.001
poisson = 0.25
order = 2

[[joint]]
name = "strip"
kind = "flexure"
parent = "b"
child = "c"
length = 0.02
modulus = 2e11
width = 0.01
thickness = 0.0005
shear_modulus = 8e10

[[joint]]
name = "hinge"
kind = "revolute"
parent = "c"
child = "d"
axis = [1.0, 1.0, 0.0]
stiffness = 0.5
rest = 0.1

[[joint]]
name = "slide"
kind = "prismatic"
parent = "d"
child = "e"
stiffness = 200.0
rest = 0.002
damping = 3.0

[[joint]]
name = "ball"
kind = "spherical"
parent = "e"
child = "f"
stiffness = 0.3
rest = [0.1, -0.2, 0.3]

[[joint]]
name = "weld"
kind = "fixed"
parent = "f"
child = "g"
origin = [0.0, 0.0, 0.01]
rpy = [0.1, 0.2, 0.3]

[[body]]
name = "g"
mass = 0.2
com = [0.001, 0.002, 0.003]
inertia = [[2e-6, 1e-7, 0.0], [1e-7, 3e-6, 0.0], [0.0, 0.0, 4e-6]]

[[tendon]]
name = "t"
tension = 2.0
path = [["ground", 0.0, 0.0, 0.002], ["a", 0.0, 0.003, -0.001], ["g", 0.0, 0.0, 0.0]]

[[force]]
name = "f"
body = "g"
at = [0.01, 0.0, 0.0]
force = [1.0, 2.0, 3.0]
moment = [0.1, 0.2, 0.3]

[[weld]]
a = "g"
a_origin = [0.01, 0.0, 0.0]
a_rpy_deg = [0.0, 0.0, 90.0]
b = "ground"
b_origin = [0.0, 0.1, 0.0]
b_rpy = [0.3, 0.0, 0.0]

[[pin]]
a = "ground"
a_at = [0.0, 0.0, 0.1]
axis = [0.0, 0.0, 2.0]
b = "d"
b_at = [0.0, 0.0, 0.0]
b_axis = [0.0, 3.0, 0.0]

[[ball]]
a = "c"
a_at = [0.001, 0.0, 0.0]
b = "f"
b_at = [0.0, -0.001, 0.0]

[initial]
ball = [0.01, 0.02, 0.03]
hinge = 0.2
blade = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.5]

[initial_velocity]
slide = 0.1
"#;

fn joint<'a>(m: &'a SpatialMechanism, name: &str) -> &'a flexure::mechanism::spatial::SpatialJointSpec {
    m.joints.iter().find(|j| j.name == name).unwrap_or_else(|| panic!("joint {name}"))
}

/// "line L, column C" of the value of the first `key = ` line after the
/// line `after` (the file's own text: where an entry is written).
fn place_of(text: &str, after: &str, key: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let start = lines.iter().position(|l| *l == after).unwrap_or_else(|| panic!("{after}"));
    let k = (start..lines.len()).find(|&k| lines[k].starts_with(&format!("{key} = "))).unwrap();
    format!("line {}, column {}", k + 1, key.len() + 4)
}

/// Reference: the page's key tables, each number as written; URDF's rpy
/// from the elementary rotations; a circle's $EI = E\pi d^4/64$ and
/// $GJ = G\pi d^4/32$ with $G = E/2(1+\nu)$, a rectangle's
/// $EI_z = Ewt^3/12$, $EI_y = Etw^3/12$ (thickness along y), all to 1e-12 relative;
/// a linear taper's middle the mean of its ends; axes normalized.
#[test]
fn every_kind_and_table_parses_with_its_numbers() {
    let m = spatial_from_toml(ALL_KINDS).unwrap();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-300);
    assert_eq!(m.gravity, Vector3::new(0.0, 0.0, -9.81));
    let names: Vec<&str> = m.bodies.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["ground", "a", "b", "c", "d", "e", "f", "g"]);

    // The blade: placement, orders, subintervals, stiffness profiles, rest.
    let blade = joint(&m, "blade");
    assert_eq!(blade.origin.translation.vector, Vector3::new(0.01, 0.02, 0.03));
    assert!((rotation(&blade.origin.rotation) - rx(PI / 2.0)).amax() < 1e-15);
    assert_eq!(blade.damping, 0.01);
    let f = blade.kind.flexure().unwrap();
    assert_eq!((f.length(), f.orders(), f.subintervals(), f.coordinates()), (0.05, [2, 3, 4], 12, 9));
    let [gj, ei_y, ei_z] = f.section().stiffness(0.0);
    assert!(close(gj, 3e-3) && close(ei_y, 4e-3) && close(ei_z, 2e-3), "{gj} {ei_y} {ei_z}");
    assert!(close(f.section().stiffness(0.5)[2], 1.5e-3) && close(f.section().stiffness(1.0)[2], 1e-3));
    // Twist's 2 coefficients, then κ_y's 3 (zero), then κ_z's 4 (`kappa`).
    assert_eq!(f.rest(), [0.5, 0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 0.0, 0.0]);

    // The rod: a circle, `order` for all three.
    let rod = joint(&m, "rod").kind.flexure().unwrap();
    assert_eq!(rod.orders(), [2, 2, 2]);
    let (e, d) = (2e11, 0.001f64);
    let g = e / (2.0 * 1.25);
    let [gj, ei_y, ei_z] = rod.section().stiffness(0.3);
    let (ei, j) = (e * PI * d.powi(4) / 64.0, g * PI * d.powi(4) / 32.0);
    assert!(close(ei_y, ei) && close(ei_z, ei) && close(gj, j), "{gj} {ei_y} {ei_z} against {j} {ei}");

    // The strip: a rectangle, default orders.
    let strip = joint(&m, "strip").kind.flexure().unwrap();
    assert_eq!(strip.orders(), [3, 3, 3]);
    let (w, t) = (0.01f64, 0.0005f64);
    let [_, ei_y, ei_z] = strip.section().stiffness(0.0);
    assert!(close(ei_z, e * w * t.powi(3) / 12.0) && close(ei_y, e * t * w.powi(3) / 12.0), "{ei_y} {ei_z}");

    let SpatialJointKind::Revolute(h) = &joint(&m, "hinge").kind else { panic!("a hinge") };
    let s = 0.5f64.sqrt();
    assert!((h.axis.into_inner() - Vector3::new(s, s, 0.0)).amax() < 1e-15);
    assert_eq!((h.stiffness, h.rest), (0.5, 0.1));
    let slide = joint(&m, "slide");
    let SpatialJointKind::Prismatic(p) = &slide.kind else { panic!("a slider") };
    assert_eq!((p.axis.into_inner(), p.stiffness, p.rest, slide.damping), (Vector3::x(), 200.0, 0.002, 3.0));
    let SpatialJointKind::Spherical(b) = &joint(&m, "ball").kind else { panic!("a ball") };
    assert_eq!((b.stiffness, b.rest), (0.3, [0.1, -0.2, 0.3]));
    let weld = joint(&m, "weld");
    assert!(matches!(weld.kind, SpatialJointKind::Fixed(_)));
    assert_eq!(weld.origin.translation.vector, Vector3::new(0.0, 0.0, 0.01));
    assert!((rotation(&weld.origin.rotation) - urdf([0.1, 0.2, 0.3])).amax() < 1e-15);
    // Coordinates: 9 + 6 + 9 in the flexures, 1 + 1 + 3 in the hinge, slider and ball.
    assert_eq!(m.dof(), 29);

    let gb = &m.bodies[m.body("g").unwrap()];
    assert_eq!((gb.mass, gb.com), (0.2, Point3::new(0.001, 0.002, 0.003)));
    assert_eq!(gb.inertia, Matrix3::new(2e-6, 1e-7, 0.0, 1e-7, 3e-6, 0.0, 0.0, 0.0, 4e-6));
    // Bodies not described are massless.
    assert_eq!((m.bodies[1].mass, m.bodies[1].inertia), (0.0, Matrix3::zeros()));

    let tendon = &m.tendons[0];
    assert_eq!((tendon.name.as_str(), tendon.tension), ("t", 2.0));
    let path: Vec<(usize, Point3<f64>)> =
        vec![(0, Point3::new(0.0, 0.0, 0.002)), (1, Point3::new(0.0, 0.003, -0.001)), (7, Point3::new(0.0, 0.0, 0.0))];
    assert_eq!(tendon.path, path);
    // A wrench is (moment, force), both in the ground frame.
    let force = &m.forces[0];
    assert_eq!((force.name.as_str(), force.body, force.at), ("f", 7, Point3::new(0.01, 0.0, 0.0)));
    assert_eq!(force.wrench, Vector6::new(0.1, 0.2, 0.3, 1.0, 2.0, 3.0));

    // Closures: welds, then pins, then balls, each placed where its `a` is written.
    assert_eq!(m.closures.len(), 3);
    let SpatialClosure { holds, a, a_origin, b, b_origin } = &m.closures[0];
    assert_eq!((*holds, *a, *b), (Holds::Weld, 7, 0));
    assert_eq!(a_origin.translation.vector, Vector3::new(0.01, 0.0, 0.0));
    assert!((rotation(&a_origin.rotation) - rz(PI / 2.0)).amax() < 1e-15);
    assert_eq!(b_origin.translation.vector, Vector3::new(0.0, 0.1, 0.0));
    assert!((rotation(&b_origin.rotation) - rx(0.3)).amax() < 1e-15);
    // A pin's frames: z along its axes (to rounding, as unit quaternions), b's x and y normal to it.
    let pin = &m.closures[1];
    let at = |p: &nalgebra::Isometry3<f64>| Point3::from(p.translation.vector);
    assert_eq!((pin.holds, pin.a, at(&pin.a_origin)), (Holds::Pin, 0, Point3::new(0.0, 0.0, 0.1)));
    assert_eq!((pin.b, at(&pin.b_origin)), (4, Point3::origin()));
    let axes = pin.axes();
    assert!((axes[2] - Vector3::z()).amax() < 1e-15 && (axes[5] - Vector3::y()).amax() < 1e-15, "{axes:?}");
    for n in &axes[3..5] {
        assert!(n.dot(&axes[5]).abs() < 1e-15 && (n.norm() - 1.0).abs() < 1e-15);
    }
    let ball = &m.closures[2];
    assert_eq!((ball.holds, ball.a, at(&ball.a_origin)), (Holds::Ball, 3, Point3::new(0.001, 0.0, 0.0)));
    assert_eq!((ball.b, at(&ball.b_origin)), (6, Point3::new(0.0, -0.001, 0.0)));
    let places: Vec<String> = ["[[weld]]", "[[pin]]", "[[ball]]"].iter().map(|t| place_of(ALL_KINDS, t, "a")).collect();
    assert_eq!((0..3).map(|i| m.closure_place(i)).collect::<Vec<_>>(), places);
    assert_eq!(m.closure_place(0), "line 96, column 5");

    // [initial] and [initial_velocity], by joint index.
    let index = |name: &str| m.joints.iter().position(|j| j.name == name).unwrap();
    let mut initial = m.initial.clone();
    initial.sort_by_key(|(j, _)| *j);
    let mut expected = vec![
        (index("ball"), vec![0.01, 0.02, 0.03]),
        (index("hinge"), vec![0.2]),
        (index("blade"), vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.5]),
    ];
    expected.sort_by_key(|(j, _)| *j);
    assert_eq!(initial, expected);
    assert_eq!(m.initial_velocity, [(index("slide"), vec![0.1])]);
    // The same file through `Model::from_toml`.
    assert!(matches!(Model::from_toml(ALL_KINDS).unwrap(), Model::Spatial(s) if s == m));
}

/// Reference: a pin's axis on `b`, when not given, is where `axis` (in `a`'s
/// frame) lies with every joint at rest: `b`'s frame is turned by the
/// joints' rpy, so the axis in it is $R_b^TR_a\,\hat a$, multiplied out by
/// hand here ($R_z(90°)^T\hat x = -\hat y$, $R_z(90°)\hat x = \hat y$, and
/// $R_z(90°)^TR_y(-90°)\hat y = \hat x$: a straight flexure's tip at rest
/// is its root frame moved along x), to 1e-15.
#[test]
fn a_pins_axis_on_b_is_where_it_lies_at_rest() {
    let text = r#"dimension = 3
[[joint]]
name = "turn"
kind = "fixed"
parent = "ground"
child = "p"
rpy_deg = [0.0, 0.0, 90.0]
[[joint]]
name = "blade"
kind = "flexure"
parent = "ground"
child = "q"
origin = [0.0, 0.0, 0.05]
rpy_deg = [0.0, -90.0, 0.0]
length = 0.02
ei = 1e-3
[[pin]]
a = "ground"
axis = [2.0, 0.0, 0.0]
b = "p"
[[pin]]
a = "p"
axis = [1.0, 0.0, 0.0]
b = "ground"
[[pin]]
a = "q"
axis = [0.0, 1.0, 0.0]
b = "p"
"#;
    let m = spatial_from_toml(text).unwrap();
    let axes: Vec<(Vector3<f64>, Vector3<f64>)> = m
        .closures
        .iter()
        .map(|c| {
            assert_eq!(c.holds, Holds::Pin);
            (c.axes()[2], c.axes()[5])
        })
        .collect();
    // q's frame: pitch −90° turns x to +z and z to −x, and keeps y. Its
    // axis y is the ground's y, which in p (turned 90° about z, x to y) is x.
    let expected = [(Vector3::x(), -Vector3::y()), (Vector3::x(), Vector3::y()), (Vector3::y(), Vector3::x())];
    for (k, ((a, b), (ea, eb))) in axes.iter().zip(expected).enumerate() {
        assert!((a - ea).amax() < 1e-15 && (b - eb).amax() < 1e-15, "pin {k}: {a:?} {b:?}");
    }
    // The same from the library's rest frames.
    let rest = frames(&m, &m.rest());
    let (ra, rb) = (rest.bodies[m.body("q").unwrap()].rotation, rest.bodies[m.body("p").unwrap()].rotation);
    assert!((rb.inverse() * (ra * Vector3::y()) - axes[2].1).amax() < 1e-15);
}

/// A planar file rewritten as the page says, by text alone: `dimension = 3`
/// first, a zero z on every point, force and gravity, an origin's angle as
/// rpy's yaw, a moment about z, `inertia` as `izz`, a pin's axis along z.
fn to_3d(text: &str) -> String {
    let mut out = String::from("dimension = 3\n");
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let Some((key, value)) = line.split_once(" = ") else {
            out.push_str(line);
            out.push('\n');
            if line == "[[pin]]" {
                out.push_str("axis = [0.0, 0.0, 1.0]\n");
            }
            continue;
        };
        let z = |v: &str| v.replace(']', ", 0.0]");
        let line = match key {
            "origin" | "a_origin" | "b_origin" => {
                let v: Vec<&str> = value.trim_matches(['[', ']']).split(", ").collect();
                let rpy = key.replace("origin", "rpy");
                format!("{key} = [{}, {}, 0.0]\n{rpy} = [0.0, 0.0, {}]", v[0], v[1], v[2])
            }
            "at" | "a_at" | "b_at" | "force" | "com" | "gravity" => format!("{key} = {}", z(value)),
            "path" => format!("path = [{}]", z(&value[1..value.len() - 1])),
            "moment" => format!("moment = [0.0, 0.0, {value}]"),
            "inertia" => format!("izz = {value}"),
            _ => line.to_string(),
        };
        out.push_str(&line);
        out.push('\n');
    }
    out
}

/// Reference: the planar mechanism (`from_toml`) of the same file: the
/// same bodies, joints (names, parents, children, kinds, placements: (x, y, 0)
/// turned by φ about z), numbers, tendons, forces and closures; a flexure
/// of order n has orders [n, n, n] and 3n coordinates, hinges keep the z
/// axis and sliders x; a pin's axis at rest on `b` is z. Exact (1e-15 for
/// rotations), as every number is copied.
#[test]
fn planar_examples_keep_their_structure_in_space() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    for name in ["finger.toml", "parallelogram.toml", "four_bar.toml", "mixed_chain.toml"] {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        let planar = from_toml(&text).unwrap();
        let converted = to_3d(&text);
        let Model::Spatial(m) = Model::from_toml(&converted).unwrap_or_else(|e| panic!("{name}: {e}\n{converted}"))
        else {
            panic!("{name}: not spatial")
        };
        let body_names = |names: Vec<&str>| names.into_iter().map(str::to_string).collect::<Vec<_>>();
        assert_eq!(
            body_names(m.bodies.iter().map(|b| b.name.as_str()).collect()),
            body_names(planar.bodies.iter().map(|b| b.name.as_str()).collect()),
            "{name}"
        );
        for (pb, sb) in planar.bodies.iter().zip(&m.bodies) {
            assert_eq!((sb.mass, sb.com), (pb.mass, Point3::new(pb.com.x, pb.com.y, 0.0)), "{name}");
            assert_eq!(sb.inertia, Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, pb.inertia), "{name}");
        }
        assert_eq!(m.joints.len(), planar.joints.len(), "{name}");
        let mut dof = 0;
        for pj in &planar.joints {
            let sj = joint(&m, &pj.name);
            let at = format!("{name}: joint {}", pj.name);
            assert_eq!((sj.parent, sj.child, sj.damping), (pj.parent, pj.child, pj.damping), "{at}");
            assert_eq!(sj.origin.translation.vector, Vector3::new(pj.origin.x, pj.origin.y, 0.0), "{at}");
            assert!((rotation(&sj.origin.rotation) - rz(pj.origin.phi)).amax() < 1e-15, "{at}");
            match (&pj.kind, &sj.kind) {
                (JointKind::Flexure(p), SpatialJointKind::Flexure(s)) => {
                    let n = p.order();
                    assert_eq!((s.orders(), s.coordinates(), s.length()), ([n; 3], 3 * n, p.length()), "{at}");
                    // `ei` is in the plane, about z; the twist and out-of-plane default to it.
                    assert_eq!(s.section().stiffness(0.5), [p.ei(); 3], "{at}");
                    assert_eq!(&s.rest()[2 * n..], p.rest(), "{at}");
                    dof += 3 * n;
                }
                (JointKind::Revolute(p), SpatialJointKind::Revolute(s)) => {
                    assert_eq!((s.axis.into_inner(), s.stiffness, s.rest), (Vector3::z(), p.stiffness, p.rest), "{at}");
                    dof += 1;
                }
                (JointKind::Prismatic(p), SpatialJointKind::Prismatic(s)) => {
                    assert_eq!((s.axis.into_inner(), s.stiffness, s.rest), (Vector3::x(), p.stiffness, p.rest), "{at}");
                    dof += 1;
                }
                (JointKind::Fixed(_), SpatialJointKind::Fixed(_)) => {}
                (p, s) => panic!("{at}: {p:?} became {s:?}"),
            }
        }
        assert_eq!(m.dof(), dof, "{name}");
        assert_eq!(m.gravity, Vector3::new(planar.gravity.x, planar.gravity.y, 0.0), "{name}");
        assert_eq!(m.tendons.len(), planar.tendons.len(), "{name}");
        for (pt, st) in planar.tendons.iter().zip(&m.tendons) {
            let path: Vec<(usize, Point3<f64>)> =
                pt.path.iter().map(|(b, p)| (*b, Point3::new(p.x, p.y, 0.0))).collect();
            assert_eq!((&st.name, st.tension, &st.path), (&pt.name, pt.tension, &path), "{name}");
        }
        assert_eq!(m.forces.len(), planar.forces.len(), "{name}");
        for (pf, sf) in planar.forces.iter().zip(&m.forces) {
            let w = &pf.wrench;
            assert_eq!((&sf.name, sf.body, sf.at), (&pf.name, pf.body, Point3::new(pf.at.x, pf.at.y, 0.0)), "{name}");
            assert_eq!(sf.wrench, Vector6::new(0.0, 0.0, w.moment, w.fx, w.fy, 0.0), "{name}");
        }
        assert_eq!(m.closures.len(), planar.closures.len(), "{name}");
        for (pc, sc) in planar.closures.iter().zip(&m.closures) {
            let (a, a_origin, b, b_origin) = (&pc.a, &pc.a_origin, &pc.b, &pc.b_origin);
            let (sa, sao, sb, sbo) = (&sc.a, &sc.a_origin, &sc.b, &sc.b_origin);
            assert_eq!(pc.holds, sc.holds, "{name}");
            match pc.holds {
                Holds::Weld => {
                    assert_eq!((sa, sb), (a, b), "{name}");
                    for (p, s) in [(a_origin, sao), (b_origin, sbo)] {
                        assert_eq!(s.translation.vector, Vector3::new(p.x, p.y, 0.0), "{name}");
                        assert!((rotation(&s.rotation) - rz(p.phi)).amax() < 1e-15, "{name}");
                    }
                }
                Holds::Pin => {
                    assert_eq!((sa, sb), (a, b), "{name}");
                    let (a_at, b_at) = (a_origin.origin(), b_origin.origin());
                    assert_eq!(sao.translation.vector, Vector3::new(a_at.x, a_at.y, 0.0), "{name}");
                    assert_eq!(sbo.translation.vector, Vector3::new(b_at.x, b_at.y, 0.0), "{name}");
                    // Every rest frame turns about z, so z stays z.
                    let axes = sc.axes();
                    assert!((axes[2] - Vector3::z()).amax() < 1e-15 && (axes[5] - Vector3::z()).amax() < 1e-15);
                }
                Holds::Ball => panic!("{name}: a planar file has no ball"),
            }
        }
        // The equations: a weld's 3 become 6, a pin's 2 become 5.
        let expected: usize = planar.closures.iter().map(|c| if c.equations() == 3 { 6 } else { 5 }).sum();
        assert_eq!(m.constraints(), expected, "{name}");
    }
}

const HEAD: &str = "dimension = 3\n[[joint]]\nname = \"j\"\nparent = \"ground\"\nchild = \"a\"\n";

/// Reference: the file's own text. Each bad value is an error at the line
/// and column of the value it names (the key's entry for a missing one),
/// and the message names the entry, the key and the value as written.
#[test]
fn bad_values_name_their_key_line_and_column() {
    let cases: Vec<(String, &str)> = vec![
        // Each kind's foreign keys.
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.1\naxis = [1.0, 0.0, 0.0]\n"),
            "line 8, column 8: joint \"j\": `axis` does not apply to a flexure joint",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.1\nstiffness = 1.0\n"),
            "line 8, column 13: joint \"j\": `stiffness` does not apply to a flexure joint",
        ),
        (
            format!("{HEAD}kind = \"revolute\"\nei = 1.0\n"),
            "line 7, column 6: joint \"j\": `ei` does not apply to a revolute joint",
        ),
        (
            format!("{HEAD}kind = \"prismatic\"\ntwist = [0.1]\n"),
            "line 7, column 9: joint \"j\": `twist` does not apply to a prismatic joint",
        ),
        (
            format!("{HEAD}kind = \"spherical\"\naxis = [1.0, 0.0, 0.0]\n"),
            "line 7, column 8: joint \"j\": `axis` does not apply to a spherical joint",
        ),
        (
            format!("{HEAD}kind = \"fixed\"\ndamping = 1.0\n"),
            "line 7, column 11: joint \"j\": `damping` does not apply to a fixed joint",
        ),
        // Axes.
        (
            format!("{HEAD}kind = \"prismatic\"\naxis = [0.0, 0.0, 0.0]\n"),
            "line 7, column 8: joint \"j\": axis = [0, 0, 0]: must be a finite, non-zero direction",
        ),
        (
            format!("{HEAD}kind = \"revolute\"\naxis = [nan, 0.0, 1.0]\n"),
            "line 7, column 8: joint \"j\": axis[0] = NaN: must be a finite number",
        ),
        (
            format!(
                "{HEAD}kind = \"fixed\"\n[[pin]]\na = \"a\"\nb = \"ground\"\naxis = [0.0, 0.0, 1.0]\nb_axis = [0.0, 0.0, 0.0]\n"
            ),
            "line 11, column 10: pin of \"a\" and \"ground\": b_axis = [0, 0, 0]: must be a finite, non-zero direction",
        ),
        // Placements.
        (
            format!("{HEAD}kind = \"fixed\"\nrpy = [0.0, 0.0, 0.0]\nrpy_deg = [0.0, 0.0, 90.0]\n"),
            "line 8, column 11: joint \"j\": give rpy (rad) or rpy_deg (degrees), not both",
        ),
        (
            format!(
                "{HEAD}kind = \"fixed\"\n[[weld]]\na = \"a\"\nb = \"ground\"\na_rpy = [0.0, 0.0, 0.0]\na_rpy_deg = [0.0, 0.0, 0.0]\n"
            ),
            "line 11, column 13: weld of \"a\" and \"ground\": give a_rpy (rad) or a_rpy_deg (degrees), not both",
        ),
        (
            format!("{HEAD}kind = \"revolute\"\norigin = [0.0, 1e31, 0.0]\n"),
            "line 7, column 10: joint \"j\": origin[1] = 1e31: must be zero or between 1e-30 and 1e30",
        ),
        (format!("{HEAD}kind = \"revolute\"\norigin = [0.0, 0.0]\n"), "line 7, column 10: origin: invalid length 2"),
        // A flexure's keys, named as written.
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.1\norders = [0, 2, 3]\n"),
            "line 8, column 10: joint \"j\": orders = [0, 2, 3]: each component's order must be from 1 to 64",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.1\norder = 100\n"),
            "line 8, column 9: joint \"j\": order = 100: each component's order must be from 1 to 64",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.1\nkappa = [1.0, 2.0]\n"),
            "line 8, column 9: joint \"j\": kappa = 2 values: must have one rest coefficient per order",
        ),
        (
            format!(
                "{HEAD}kind = \"flexure\"\nlength = 0.1\nei = 1.0\nmodulus = 2e11\nwidth = 0.01\nthickness = 0.001\n"
            ),
            "line 8, column 6: joint \"j\": ei = given with modulus",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.1\nei = 1.0\nei_z = 2.0\n"),
            "line 9, column 8: joint \"j\": give ei (the planar spelling) or ei_z, not both",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.1\nmodulus = 2e11\ndiameter = 0.001\npoisson = 0.7\n"),
            "line 10, column 11: joint \"j\": poisson = 0.7: must lie in (-1, 0.5]",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.1\nsubintervals = 0\n"),
            "line 8, column 16: joint \"j\": subintervals = 0",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.1\nei = [1.0, -1.0]\n"),
            "line 8, column 6: joint \"j\": ei[1] = -1: must be greater than zero",
        ),
        (
            format!("{HEAD}kind = \"spherical\"\nrest = [0.1, 0.2]\n"),
            "line 7, column 8: joint \"j\": rest must be a rotation vector",
        ),
        // Inertias.
        (
            format!("{HEAD}kind = \"fixed\"\n[[body]]\nname = \"a\"\nixx = 1.0\niyy = 1.0\nizz = 3.0\n"),
            "line 9, column 7: body \"a\": ixx … iyz: its principal moments 1.0000e0, 1.0000e0, 3.0000e0 break the triangle inequality",
        ),
        (
            format!(
                "{HEAD}kind = \"fixed\"\n[[body]]\nname = \"a\"\ninertia = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 3.0]]\n"
            ),
            "line 9, column 11: body \"a\": inertia: its principal moments 1.0000e0, 1.0000e0, 3.0000e0 break the triangle inequality",
        ),
        (
            format!("{HEAD}kind = \"fixed\"\n[[body]]\nname = \"a\"\nixx = 1.0\niyy = 1.0\nizz = 1.0\nixy = 2.0\n"),
            "line 9, column 7: body \"a\": ixx … iyz must be positive semi-definite",
        ),
        (
            format!(
                "{HEAD}kind = \"fixed\"\n[[body]]\nname = \"a\"\ninertia = [[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]\n"
            ),
            "line 9, column 11: body \"a\": inertia must be symmetric",
        ),
        (
            format!(
                "{HEAD}kind = \"fixed\"\n[[body]]\nname = \"a\"\ninertia = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]\nizz = 1.0\n"
            ),
            "line 10, column 7: body \"a\": give inertia (3 × 3) or izz and the other components, not both",
        ),
        // Names, loads and closures.
        (
            format!("{HEAD}kind = \"fixed\"\n[[force]]\nbody = \"b\"\n"),
            "line 8, column 8: unknown body \"b\": bodies are ground and the joints' children",
        ),
        (
            format!("{HEAD}kind = \"fixed\"\n[[force]]\nbody = \"a\"\nmoment = 1.0\n"),
            "line 9, column 10: moment: invalid type: floating point `1.0`, expected an array of length 3",
        ),
        (
            format!(
                "{HEAD}kind = \"fixed\"\n[[tendon]]\nname = \"t\"\ntension = 1.0\npath = [[\"a\", 0.0, 0.0], [\"ground\", 0.0, 0.0]]\n"
            ),
            "line 10, column 9: path: invalid length 3, expected a tuple of size 4",
        ),
        (
            format!("{HEAD}kind = \"fixed\"\n[[ball]]\na = \"a\"\nb = \"a\"\n"),
            "line 9, column 5: a ball joins body \"a\" to itself",
        ),
        (
            format!(
                "{HEAD}kind = \"fixed\"\n[[pin]]\na = \"a\"\nb = \"ground\"\naxis = [0.0, 0.0, 1.0]\npreload = 1\n"
            ),
            "line 11, column 11: preload: invalid type: integer `1`, expected a boolean",
        ),
        // Planar keys a spatial flexure does not take, with why.
        (
            format!(
                "{HEAD}kind = \"flexure\"\nlength = 0.01\nmodulus = 2e11\nwidth = 0.01\nthickness = 0.001\nnotch = {{ radius = 0.002, min_thickness = 0.0002 }}\n"
            ),
            "line 11, column 1: `notch` is for planar mechanisms: a circular notch hinge",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.01\nei = 1e-3\nquadrature = 8\n"),
            "line 9, column 1: `quadrature` is for planar mechanisms: the planar flexure's Gauss rule: a spatial flexure integrates by Magnus steps",
        ),
        // The report's keys, read as in the plane.
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.01\nei = 1e-3\nyield_strength = 5e8\n"),
            "line 9, column 18: joint \"j\": yield_strength needs a section to give a stress",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.01\nei = 1e-3\nshape = 1\n"),
            "line 9, column 9: joint \"j\": shape = 1: must be from 2 to 10000 points",
        ),
        (format!("{HEAD}kind = \"fixed\"\nshape = 5\n"), "line 7, column 9: joint \"j\": `shape` does not apply"),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.01\nei = 1e-3\norder = \"six\"\n"),
            "line 9, column 9: joint \"j\": order = \"six\": must be a whole number from 1 to 64 or \"auto\"",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.01\norder = -1\n"),
            "line 8, column 9: joint \"j\": order = -1: must be a whole number from 1 to 64 or \"auto\"",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.01\nei = 1e-3\norder = 2.5\n"),
            "line 9, column 9: joint \"j\": order = 2.5: must be a whole number",
        ),
        (
            format!("{HEAD}kind = \"flexure\"\nlength = 0.01\nei = 1e-3\norder = \"auto\"\norders = [3, 3, 3]\n"),
            "line 10, column 10: joint \"j\": give order (all three) or orders, not both",
        ),
        (
            format!("{HEAD}kind = \"spherical\"\n[initial]\nj = [0.1, 0.2]\n"),
            "line 8, column 5: initial: joint \"j\": the joint has 3 coordinates and 2 were given",
        ),
        // The top level.
        ("dimension = \"3\"\n".into(), "line 1, column 13: dimension = \"3\": must be 2"),
        ("dimension = 3.0\n".into(), "line 1, column 13: dimension = 3.0: must be 2"),
        ("gravity = [0.0, 0.0, -9.81]\ndimension = 1\n".into(), "line 2, column 13: dimension = 1: must be 2"),
        ("dimension = 3\ngravity = [0.0, -9.81]\n".into(), "line 2, column 11: gravity: invalid length 2"),
        (
            "dimension = 3\n[[schedule]]\nload = \"gravity.w\"\npoints = [[0.0, 1.0]]\n".into(),
            "line 3, column 8: schedule \"gravity.w\": load \"gravity.w\" gravity's component must be x, y or z",
        ),
    ];
    let mut seen = std::collections::BTreeSet::new();
    for (text, expected) in &cases {
        let e = spatial_from_toml(text).unwrap_err().to_string();
        assert!(e.starts_with(expected), "{e:?} should start with {expected:?} for\n{text}");
        // Through either reader the same error.
        assert_eq!(Model::from_toml(text).unwrap_err().to_string(), e);
        assert!(seen.insert(e), "two cases give one error");
    }
    assert!(cases.len() >= 10);
}

/// Reference: the format page: a planar file reads as before, with or
/// without `dimension = 2`; the planar reader refuses a spatial file at
/// its `dimension`, naming the reader that takes it, and the spatial
/// reader a planar one.
#[test]
fn each_reader_takes_its_dimension() {
    let planar = "[[joint]]\nname = \"hinge\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"link\"\nlength = 0.02\nei = 1e-3\n";
    let two = from_toml(&format!("dimension = 2\n{planar}")).unwrap();
    assert_eq!(two, from_toml(planar).unwrap());
    assert!(matches!(Model::from_toml(planar).unwrap(), Model::Planar(p) if p == two));
    let e = from_toml("gravity = [0.0, 0.0, -9.81]\ndimension = 3\n").unwrap_err().to_string();
    assert!(
        e.starts_with("line 2, column 13: dimension = 3: a spatial mechanism; read it with `Model::from_toml`"),
        "{e}"
    );
    let e = spatial_from_toml(planar).unwrap_err().to_string();
    assert!(e.contains("a planar mechanism") && e.contains("Model::from_toml"), "{e}");
}

/// Reference: the format page's two key tables. One reader reads both
/// dimensions, so a key only the other dimension takes is refused with
/// why, placed at the key; an unknown key's list names only the keys of
/// the file's own dimension.
#[test]
fn a_key_of_the_other_dimension_is_refused_with_why() {
    let planar = |extra: &str| {
        format!("[[joint]]\nname = \"j\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"a\"\n{extra}")
    };
    let cases = [
        (
            planar("rpy = [0.0, 0.0, 1.0]\n"),
            "line 6, column 1: `rpy` is for spatial mechanisms (dimension = 3): a planar origin's angle is its third number",
        ),
        (
            planar("axis = [0.0, 0.0, 1.0]\n"),
            "line 6, column 1: `axis` is for spatial mechanisms (dimension = 3): a planar hinge turns about z",
        ),
        (
            planar("[[body]]\nname = \"a\"\nizz = 1.0\n"),
            "line 8, column 1: `izz` is for spatial mechanisms (dimension = 3): a planar body's inertia is one number",
        ),
        (
            planar("[[ball]]\na = \"a\"\nb = \"ground\"\n"),
            "line 6, column 3: `ball` is for spatial mechanisms (dimension = 3): in the plane a [[pin]] holds",
        ),
        (
            planar("[[weld]]\na = \"a\"\nb = \"ground\"\nb_rpy_deg = [0.0, 0.0, 9.0]\n"),
            "line 9, column 1: `b_rpy_deg` is for spatial mechanisms",
        ),
    ];
    for (text, expected) in &cases {
        let e = from_toml(text).unwrap_err().to_string();
        assert!(e.starts_with(expected), "{e:?} should start with {expected:?} for\n{text}");
    }
    // Two refused keys: the first in the file is named.
    let e = from_toml(&planar("axis = [0.0, 0.0, 1.0]\nrpy = [0.0, 0.0, 1.0]\n")).unwrap_err().to_string();
    assert!(e.starts_with("line 6, column 1: `axis`"), "{e}");
    // An unknown key lists the keys of its own dimension only.
    let e = from_toml(&planar("colour = 1\n")).unwrap_err().to_string();
    assert!(e.starts_with("line 6, column 1: unknown field `colour`, expected one of `name`, `kind`"), "{e}");
    assert!(e.contains("`notch`") && !e.contains("`rpy`") && !e.contains("`axis`"), "{e}");
    let e = spatial_from_toml(&format!("{HEAD}kind = \"fixed\"\ncolour = 1\n")).unwrap_err().to_string();
    assert!(e.contains("`rpy`") && e.contains("`axis`") && !e.contains("`notch`"), "{e}");
    let e = spatial_from_toml(&format!("{HEAD}kind = \"fixed\"\n[[ball]]\na = \"a\"\nb = \"ground\"\nc = 1\n"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("unknown field `c`, expected one of `a`, `a_at`, `b`, `b_at`, `preload`"), "{e}");
}

/// Reference: the checks of the whole mechanism, read once for both
/// dimensions (formerly the planar reader's alone): a tendon whose
/// consecutive via points coincide at rest, on two bodies, has no
/// direction there; joints whose stiffnesses differ by more than 1e12
/// cannot be weighed together; an initial coordinate beyond 1e6 is refused.
#[test]
fn the_whole_mechanisms_checks_hold_in_space() {
    let e = spatial_from_toml(&format!(
        "{HEAD}kind = \"revolute\"\norigin = [0.1, 0.0, 0.0]\n[[tendon]]\nname = \"t\"\ntension = 1.0\n\
         path = [[\"ground\", 0.0, 0.0, 0.0], [\"ground\", 0.1, 0.0, 0.0], [\"a\", 0.0, 0.0, 0.0]]\n"
    ))
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("line 11, column 63: tendon \"t\": via points 2 and 3 coincide at rest"), "{e}");
    let e = spatial_from_toml(&format!(
        "{HEAD}kind = \"revolute\"\nstiffness = 1e6\n[[joint]]\nname = \"s\"\nkind = \"spherical\"\nparent = \"a\"\nchild = \"b\"\nstiffness = 1e-7\n"
    ))
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("line 13, column 13: joint \"s\": stiffness 1.000e-7 N·m is 1.0e13 times softer"), "{e}");
    let e = spatial_from_toml(&format!("{HEAD}kind = \"revolute\"\n[initial]\nj = 1e7\n")).unwrap_err().to_string();
    assert!(e.starts_with("line 8, column 5: initial: joint \"j\": coordinates[0] = 1e7: must be at most 1e6"), "{e}");
}
