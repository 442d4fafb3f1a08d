//! `[[geom]]` in the file (`mechanism/file/geoms.rs`): what each key
//! becomes, every refusal placed at its line and column and naming the
//! field and the value, the start-inside check against closed-form gaps,
//! and the refusal to solve a mechanism with a pair that may touch.

use flexure::estimate::Accuracy;
use flexure::mechanism::contact::{GeomShape, Toucher, pairs};
use flexure::mechanism::file::{from_toml, spatial_from_toml};
use flexure::mechanism::statics::{Settings, solve};
use flexure::model::Model;

/// A steel strip 100 mm long, 1 mm thick, along the ground's x from the origin.
const STRIP: &str = r#"
[[joint]]
name = "strip"
kind = "flexure"
parent = "ground"
child = "tip"
length = 0.1
modulus = 2e11
width = 0.01
thickness = 0.001
"#;

/// The same strip in space.
fn strip3() -> String {
    format!("dimension = 3{STRIP}")
}

/// "line L, column C" of the first `needle` in `text`, found by search.
fn at(text: &str, needle: &str) -> String {
    place(text, text.find(needle).unwrap_or_else(|| panic!("{needle:?} is not in the text")))
}

/// "line L, column C" of the byte `offset` of `text` (ASCII).
fn place(text: &str, offset: usize) -> String {
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = offset - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    format!("line {line}, column {column}")
}

/// The file's error (either dimension), which must start with the place of `needle` and contain `says`.
fn refused(text: &str, needle: &str, says: &str) {
    let e = Model::from_toml(text).err().unwrap_or_else(|| panic!("accepted:\n{text}")).to_string();
    assert!(e.starts_with(&format!("{}: ", at(text, needle))), "{e}\nexpected at {needle:?}: {}", at(text, needle));
    assert!(e.contains(says), "{e}\nexpected to say {says:?}");
}

#[test]
fn a_geom_becomes_its_shape_frame_and_friction() {
    let text = format!(
        "{STRIP}[[geom]]\nname = \"peg\"\nbody = \"ground\"\nshape = \"capsule\"\norigin = [0.05, 0.02]\nangle = 0.5\nradius = 0.004\nhalf_length = 0.01\nfriction = 0.3\n[[geom]]\nbody = \"tip\"\nshape = \"plane\"\norigin = [0.0, -0.03]\nnormal = [0.0, 2.0]\nexclude = [\"peg\"]\n[[geom]]\nname = \"pad\"\nbody = \"tip\"\nshape = \"circle\"\nradius = 0.003\nexclude = [\"strip\"]\n"
    );
    let m = from_toml(&text).unwrap();
    let (peg, pad) = (&m.geoms[0], &m.geoms[1]);
    assert_eq!((peg.name.as_str(), peg.body, peg.friction), ("peg", 0, 0.3));
    assert_eq!((peg.frame.x, peg.frame.y, peg.frame.phi), (0.05, 0.02, 0.5));
    assert_eq!(peg.shape, GeomShape::Capsule { half_length: 0.01, radius: 0.004 });
    // An unnamed geom is named by its place; a plane's normal is made unit.
    // (A plane on the tip, solid below y = -0.03, carried by it.)
    assert_eq!((pad.name.as_str(), pad.body), ("geom 2", 1));
    assert_eq!(pad.shape, GeomShape::Plane { normal: nalgebra::Vector2::new(0.0, 1.0) });
    // The strip may touch the peg and the tip's plane, 0.03 m below it at
    // rest; the pad around the strip's tip excludes it; geoms on different
    // bodies may touch, but the tip's plane excludes the peg (without the
    // exclude they touch at the capsule's two end balls).
    assert_eq!(m.geoms[2].exclude, [Toucher::Flexure(0)]);
    let found: Vec<_> = pairs(&m).iter().map(|p| (p.geom, p.part)).collect();
    assert_eq!(found, [(0, Toucher::Flexure(0)), (0, Toucher::Geom(2)), (1, Toucher::Flexure(0))]);
    let both = from_toml(&text.replace("exclude = [\"peg\"]\n", "")).unwrap();
    let found: Vec<_> = pairs(&both).iter().map(|p| (p.geom, p.part, p.corner)).collect();
    let ends = [(0, Toucher::Geom(1), 0), (0, Toucher::Geom(1), 1)];
    assert_eq!(found[1..3], ends);
}

/// Two geoms touch at corners (`corners`): a plane and a box at the box's
/// corners, a plane and a capsule at its end balls, and two boxes or
/// capsules at each one's corners against the other, and in space also at
/// each pair of their edges; a cylinder at 32 points of each rim, and its
/// side as an edge (its axis, rounded). Two planes, and in
/// are refused at the later geom's `shape`, naming both.
#[test]
fn two_geoms_touch_at_their_corners_or_are_refused_by_name() {
    let geoms = |d: usize, a: &str, b: &str| {
        let (head, origin) = if d == 3 { (strip3(), "[0.0, 0.0, -0.5]") } else { (STRIP.to_string(), "[0.0, -0.5]") };
        format!(
            "{head}[[geom]]\nname = \"a\"\nbody = \"ground\"\norigin = {origin}\n{a}\nexclude = [\"strip\"]\n[[geom]]\nname = \"b\"\nbody = \"tip\"\n{b}\nexclude = [\"strip\"]\n"
        )
    };
    let plane2 = "shape = \"plane\"\nnormal = [0.0, 1.0]";
    let plane3 = "shape = \"plane\"\nnormal = [0.0, 0.0, 1.0]";
    let box2 = "shape = \"box\"\nhalf_extents = [0.01, 0.02]";
    let box3 = "shape = \"box\"\nhalf_extents = [0.01, 0.02, 0.03]";
    let capsule = "shape = \"capsule\"\nradius = 0.01\nhalf_length = 0.02";
    let cylinder = "shape = \"cylinder\"\nradius = 0.01\nhalf_length = 0.02";
    let count = |text: &str| Model::from_toml(text).unwrap().contact_columns().len();
    let corners = |d: usize, text: &str| match d {
        2 => pairs(&from_toml(text).unwrap()).len(),
        _ => pairs(&spatial_from_toml(text).unwrap()).len(),
    };
    for (d, a, b, n) in [
        (2, plane2, box2, 4),
        (2, plane2, capsule, 2),
        (2, box2, box2, 8),
        (2, box2, capsule, 6),
        (2, capsule, capsule, 4),
        (3, plane3, box3, 8),
        (3, plane3, capsule, 2),
        // In space, with each pair of their edges after the corners: 12 × 12, 12 × 1, 1 × 1.
        (3, box3, box3, 16 + 144),
        (3, box3, capsule, 10 + 12),
        (3, capsule, capsule, 4 + 1),
        // A cylinder's 64 rim points; with a box or a capsule, the other's corners too, and its side's edge pairs.
        (3, plane3, cylinder, 64),
        (3, box3, cylinder, 64 + 8 + 12),
        (3, cylinder, capsule, 2 + 64 + 1),
        (3, cylinder, cylinder, 128 + 1),
    ] {
        let text = geoms(d, a, b);
        // One column for the two geoms, a pair for each corner.
        assert_eq!((count(&text), corners(d, &text)), (1, n), "{a} and {b} in {d}-D");
    }
    // Two bars crossed at rest, no corner of either inside the other and
    // each centre outside the other, are found by their edges: 5 mm deep.
    let crossed = format!(
        "{STRIP}[[geom]]\nname = \"bar\"\nbody = \"ground\"\nshape = \"box\"\norigin = [0.0, -0.5]\nhalf_extents = [0.05, 0.005]\nexclude = [\"strip\"]\n\
         [[geom]]\nname = \"post\"\nbody = \"tip\"\nshape = \"box\"\norigin = [-0.07, -0.47]\nhalf_extents = [0.005, 0.05]\nexclude = [\"strip\"]\n"
    );
    refused(
        &crossed,
        "\"box\"\norigin = [0.0, -0.5]",
        "geom \"post\" on body \"tip\" starts inside it, 5.000e-3 m deep",
    );
    let said = |d: usize| match d {
        2 => "two geoms touch only where one is a circle, or neither is a plane",
        _ => "two geoms touch only where one is a sphere, or neither is a plane",
    };
    for (d, a, b, names) in [
        (2, plane2, "shape = \"plane\"\nnormal = [0.0, -1.0]", "(plane) and geom \"b\" (plane)"),
        (3, plane3, "shape = \"plane\"\nnormal = [0.0, 0.0, -1.0]", "(plane) and geom \"b\" (plane)"),
    ] {
        let text = geoms(d, a, b);
        let at_shape = text.rfind("shape = ").expect("a shape") + "shape = ".len();
        let e = Model::from_toml(&text).err().unwrap_or_else(|| panic!("accepted:\n{text}")).to_string();
        assert!(e.starts_with(&format!("{}: ", place(&text, at_shape))), "{e}");
        assert!(e.contains(&format!("geom \"a\" {names} may touch")) && e.contains(said(d)), "{e}");
    }
}

#[test]
fn exclude_names_flexures_bodies_and_geoms() {
    let geoms = "[[geom]]\nname = \"post\"\nbody = \"ground\"\nshape = \"circle\"\norigin = [0.05, 0.02]\nradius = 0.005\nexclude = [\"strip\", \"tip\"]\n[[geom]]\nname = \"pad\"\nbody = \"tip\"\nshape = \"circle\"\norigin = [0.01, 0.0]\nradius = 0.002\nexclude = [\"strip\"]\n";
    let m = from_toml(&format!("{STRIP}{geoms}")).unwrap();
    assert_eq!(m.geoms[0].exclude, [Toucher::Flexure(0), Toucher::Geom(1)]);
    assert_eq!(m.geoms[1].exclude, [Toucher::Flexure(0)]);
    assert!(pairs(&m).is_empty());
    // Nothing may touch: solved as if there were no geoms, to the bit.
    let force = "[[force]]\nbody = \"tip\"\nforce = [0.0, 2.0]\n";
    let with = from_toml(&format!("{STRIP}{force}{geoms}")).unwrap();
    let without = from_toml(&format!("{STRIP}{force}")).unwrap();
    let (a, b) = (solve(&with, &Settings::default()).unwrap(), solve(&without, &Settings::default()).unwrap());
    assert_eq!(a.q, b.q);
    let bad = format!(
        "{STRIP}[[geom]]\nname = \"post\"\nbody = \"ground\"\nshape = \"circle\"\norigin = [0.05, 0.02]\nradius = 0.005\nexclude = [\"nothing\"]\n"
    );
    refused(&bad, "\"nothing\"", "geom \"post\": exclude: unknown part \"nothing\"");
    let own = format!(
        "{STRIP}[[geom]]\nname = \"post\"\nbody = \"ground\"\nshape = \"circle\"\norigin = [0.05, 0.02]\nradius = 0.005\nexclude = [\"post\"]\n"
    );
    refused(&own, "\"post\"]", "\"post\" is this geom itself");
}

/// The equilibrium solve handles a pair that may touch (the strip pushed
/// onto a floor touches it, its gap closed to 1e-12 of its length, with a
/// compressive force, in the library and through the door, whose answer
/// carries the contact); buckling and export refuse it by name. Friction
/// where the strip touches with its thickness is solved, and the spatial
/// file of it gives the plane's answer.
#[test]
fn the_solve_handles_a_pair_that_may_touch_and_buckling_refuses_it() {
    let text = format!(
        "{STRIP}[[force]]\nbody = \"tip\"\nforce = [0.0, -10.0]\n[[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n"
    );
    let m = from_toml(&text).unwrap();
    let s = solve(&m, &Settings::default()).unwrap();
    assert_eq!(s.contacts.len(), 1, "{:?}", s.contacts);
    let c = &s.contacts[0];
    assert!(c.gap.abs() < 1e-12 * 0.1 && c.normal_force > 0.0 && c.geom == "floor", "{c:?}");
    let model = Model::from_toml(&text).unwrap();
    let solved = model.solve(&Accuracy::default(), None).unwrap();
    let report = solved.report.map_err(|f| f.error).unwrap();
    assert_eq!(report.contacts, Some(s.contacts));
    let e = model.buckle(&Accuracy::default()).err().map(|e| e.to_string()).expect("refused");
    let named = "geom \"floor\" (plane) and flexure \"strip\": may touch, and only equilibrium solves, sweeps, compliances, modes and motion";
    assert!(e.contains(named), "{e}");
    // The library itself, not only the door: export refuses it too; motion
    // takes the geom (`dynamics_contact.rs`), and refuses this strip only
    // because nothing in it has mass.
    let export = flexure::export::export(&m, &Default::default()).err().map(|e| e.to_string()).expect("refused");
    assert!(export.contains("geom \"floor\" (plane) and flexure \"strip\": may touch"), "{export}");
    let motion = flexure::dynamics::simulate(&m, &Default::default(), flexure::dynamics::Start::Rest);
    let e = motion.err().map(|e| e.to_string()).expect("refused");
    assert!(e.contains("mass") && !e.contains("may touch"), "{e}");
    // With friction the strip's surface rolls on the floor: held within
    // Coulomb's cone (on it where it slides, to 1e-9 of N).
    let rough = text.replace("normal = [0.0, 1.0]\n", "normal = [0.0, 1.0]\nfriction = 0.3\n");
    let s = solve(&from_toml(&rough).unwrap(), &Settings::default()).unwrap();
    let c = &s.contacts[0];
    let f = c.friction_force.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!(c.normal_force > 0.0 && f <= 0.3 * c.normal_force * (1.0 + 1e-9), "{c:?}");
    let stuck = c.state == flexure::mechanism::contact::ContactMode::Stick;
    assert!(stuck || (f - 0.3 * c.normal_force).abs() < 1e-9 * c.normal_force, "{c:?}");
    // In space its surface's material point turns with its section (its
    // twist too): the plane's contact, to 1e-5 of N (measured 3.5e-6: a
    // stuck rolling contact's small friction, 2e-5 N here, follows its
    // path's steps, whose pins err by Δθ²/6 each).
    let spatial = rough
        .replace("[[joint]]", "dimension = 3\n[[joint]]")
        .replace("force = [0.0, -10.0]", "force = [0.0, -10.0, 0.0]")
        .replace("origin = [0.0, -0.01]\nnormal = [0.0, 1.0]", "origin = [0.0, -0.01, 0.0]\nnormal = [0.0, 1.0, 0.0]");
    let m3 = flexure::mechanism::file::spatial_from_toml(&spatial).unwrap();
    let d = &solve(&m3, &Settings::default()).unwrap().contacts[0];
    assert_eq!((d.state, d.s), (c.state, c.s), "{d:?} vs the plane's {c:?}");
    for (a, b) in [(d.normal_force, c.normal_force), (d.friction_force[0], c.friction_force[0])] {
        assert!((a - b).abs() < 1e-5 * c.normal_force, "{d:?} vs the plane's {c:?}");
    }
}

#[test]
fn bad_geoms_are_refused_at_their_place_naming_the_field_and_value() {
    let geom = |keys: &str| format!("{STRIP}[[geom]]\nname = \"g\"\nbody = \"ground\"\n{keys}");
    refused(
        &geom("shape = \"cone\"\n"),
        "\"cone\"",
        "geom \"g\": unknown shape \"cone\": must be one of \"plane\", \"circle\", \"capsule\", \"box\"",
    );
    refused(
        &geom("shape = \"circle\"\norigin = [0.0, 0.5]\nradius = -0.1\n"),
        "-0.1",
        "geom \"g\": radius = -0.1: must be greater than zero",
    );
    refused(
        &geom("shape = \"circle\"\norigin = [0.0, 0.5]\nradius = 0.0\n"),
        "0.0\n",
        "radius = 0: must be greater than zero",
    );
    refused(
        &geom("shape = \"plane\"\norigin = [0.0, -0.5]\nnormal = [0.0, 0.0]\n"),
        "[0.0, 0.0]",
        "geom \"g\": normal = [0, 0]: must not be zero",
    );
    refused(
        &geom("shape = \"circle\"\norigin = [0.0, 0.5]\nradius = 0.1\nfriction = -0.2\n"),
        "-0.2",
        "geom \"g\": friction = -0.2: must not be negative",
    );
    refused(&geom("shape = \"circle\"\n"), "\"circle\"", "geom \"g\": a circle needs `radius`");
    refused(
        &geom("shape = \"plane\"\nnormal = [0.0, 1.0]\norigin = [0.0, -0.5]\nradius = 1.0\n"),
        "1.0\n",
        "`radius` does not apply to a plane",
    );
    refused(
        &geom("shape = \"circle\"\norigin = [0.0, 0.5]\nradius = 0.1\nangle = 0.3\n"),
        "0.3",
        "`angle` does not apply to a circle",
    );
    refused(
        &geom("shape = \"box\"\norigin = [0.0, 0.5]\nhalf_extents = [0.1, -0.2]\n"),
        "[0.1, -0.2]",
        "half_extents[1] = -0.2: must be greater than zero",
    );
    refused(
        &geom("shape = \"sphere\"\nradius = 0.1\n"),
        "\"sphere\"",
        "shape = \"sphere\" is for spatial mechanisms (dimension = 3): in the plane a sphere is a circle",
    );
    refused(
        &geom("shape = \"cylinder\"\nradius = 0.1\n"),
        "\"cylinder\"",
        "in the plane a cylinder about z is its circle",
    );
    refused(
        &geom("shape = \"box\"\nhalf_extents = [0.1, 0.1]\nrpy = [0.0, 0.0, 0.1]\n"),
        "rpy",
        "`rpy` is for spatial mechanisms (dimension = 3): a planar geom turns by `angle`",
    );
    let unknown = format!("{STRIP}[[geom]]\nbody = \"palm\"\nshape = \"circle\"\nradius = 0.1\n");
    refused(&unknown, "\"palm\"", "geom \"geom 1\": body: unknown body \"palm\"");
    let twice = format!(
        "{STRIP}[[geom]]\nname = \"g\"\nbody = \"ground\"\nshape = \"circle\"\norigin = [0.0, 0.5]\nradius = 0.1\n[[geom]]\nname = \"g\"\nbody = \"ground\"\nshape = \"circle\"\norigin = [0.0, 0.9]\nradius = 0.1\n"
    );
    let second = twice.rfind("name = \"g\"").unwrap() + "name = ".len();
    let e = from_toml(&twice).unwrap_err().to_string();
    let want = format!("{}: geom \"g\": two geoms have this name", place(&twice, second));
    assert!(e.starts_with(&want), "{e}\nexpected {want}");
}

#[test]
fn bad_spatial_geoms_are_refused_at_their_place() {
    let geom = |keys: &str| format!("{}[[geom]]\nname = \"g\"\nbody = \"ground\"\n{keys}", strip3());
    refused(
        &geom("shape = \"circle\"\nradius = 0.1\n"),
        "\"circle\"",
        "shape = \"circle\" is for planar mechanisms: in space a round obstacle is a sphere",
    );
    refused(
        &geom("shape = \"sphere\"\norigin = [0.0, 0.0, 0.5]\nradius = 0.1\nangle = 0.2\n"),
        "angle",
        "`angle` is for planar mechanisms: a spatial geom turns by `rpy`",
    );
    refused(
        &geom("shape = \"cylinder\"\norigin = [0.0, 0.0, 0.5]\nradius = 0.1\nhalf_length = 0.0\n"),
        "0.0\n",
        "half_length = 0: must be greater than zero",
    );
    refused(
        &geom("shape = \"plane\"\norigin = [0.0, 0.0, -0.5]\nnormal = [0.0, 0.0, 0.0]\n"),
        "[0.0, 0.0, 0.0]",
        "normal = [0, 0, 0]: must not be zero",
    );
    refused(
        &geom("shape = \"cone\"\n"),
        "\"cone\"",
        "must be one of \"plane\", \"sphere\", \"capsule\", \"box\", \"cylinder\"",
    );
    let ok = geom(
        "shape = \"cylinder\"\norigin = [0.05, 0.0, 0.02]\nrpy_deg = [90.0, 0.0, 0.0]\nradius = 0.005\nhalf_length = 0.02\n",
    );
    let m = spatial_from_toml(&ok).unwrap();
    // Rolled a quarter about x: the cylinder's axis lies along the world's -y.
    let axis = m.geoms[0].frame.rotation * nalgebra::Vector3::z();
    assert!((axis - nalgebra::Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-15, "{axis}");
}

/// The strip at rest lies on y = 0 between x = 0 and 0.1 with its surface
/// 0.5 mm either side: a floor at y = -0.0004 reaches 0.1 mm into it; a
/// circle of radius 5 mm at (0.05, 0.0052), 0.3 mm; a floor at y = -0.0005
/// just touches it, which is allowed.
#[test]
fn a_part_that_starts_inside_a_geom_is_refused_with_its_depth() {
    let floor = |y: &str| {
        format!(
            "{STRIP}[[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, {y}]\nnormal = [0.0, 1.0]\n"
        )
    };
    // The strip lies along the floor: every point is as deep, and one is named.
    refused(&floor("-0.0004"), "\"plane\"", "geom \"floor\" (plane): flexure \"strip\" starts inside it at s = ");
    refused(&floor("-0.0004"), "\"plane\"", " m, 1.000e-4 m deep");
    assert!(from_toml(&floor("-0.0005")).is_ok());
    let post = format!(
        "{STRIP}[[geom]]\nname = \"post\"\nbody = \"ground\"\nshape = \"circle\"\norigin = [0.05, 0.0052]\nradius = 0.005\n"
    );
    let e = from_toml(&post).unwrap_err().to_string();
    assert!(
        e.starts_with(&at(&post, "\"circle\"")) && e.contains("flexure \"strip\" starts inside it at s = 0.050000 m"),
        "{e}"
    );
    let depth: f64 = e.split(", ").nth(2).unwrap().split(" m deep").next().unwrap().parse().unwrap();
    assert!((depth - 3e-4).abs() < 5e-8, "{e}");
    // A geom on the tip body starting inside a ground geom: the pad's
    // circle of 2 mm about the tip reaches 1 mm below a floor at y = -0.001.
    let pad = format!(
        "{STRIP}[[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.001]\nnormal = [0.0, 1.0]\nexclude = [\"strip\"]\n[[geom]]\nname = \"pad\"\nbody = \"tip\"\nshape = \"circle\"\nradius = 0.002\nexclude = [\"strip\"]\n"
    );
    let e = from_toml(&pad).unwrap_err().to_string();
    assert!(
        e.starts_with(&at(&pad, "\"plane\""))
            && e.contains("geom \"pad\" on body \"tip\" starts inside it, 1.000e-3 m deep"),
        "{e}"
    );
}

/// In space the strip touches with the tube of half its thickness.
#[test]
fn a_spatial_flexure_that_starts_inside_a_sphere_is_refused() {
    let ball = format!(
        "{}[[geom]]\nname = \"ball\"\nbody = \"ground\"\nshape = \"sphere\"\norigin = [0.1, 0.0, 0.0052]\nradius = 0.005\n",
        strip3()
    );
    let e = spatial_from_toml(&ball).unwrap_err().to_string();
    assert!(
        e.starts_with(&at(&ball, "\"sphere\"")) && e.contains("flexure \"strip\" starts inside it at s = 0.100000 m"),
        "{e}"
    );
    let clear = ball.replace("0.0052", "0.0056");
    assert!(spatial_from_toml(&clear).is_ok());
}

/// `contacts` is in every answer of a file with a pair that may touch, an
/// empty list where nothing touched (the strip bent toward a floor it does
/// not reach: 1 N on 0.1 m bends it 2.0 mm by FL³/3EI, 10 mm short), and
/// absent from a file with no geom: a script reads the key whenever the
/// file has a geom a part may reach.
#[test]
fn contacts_is_empty_where_nothing_touches_and_absent_without_a_geom() {
    let force = "[[force]]\nbody = \"tip\"\nforce = [0.0, -1.0]\n";
    let floor = "[[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n";
    let near = Model::from_toml(&format!("{STRIP}{force}{floor}")).unwrap();
    let bare = Model::from_toml(&format!("{STRIP}{force}")).unwrap();
    let report = |m: &Model| m.solve(&Accuracy::default(), None).unwrap().report.map_err(|f| f.error).unwrap();
    let sweep = |m: &Model| m.sweep("force.0.fy", &[-0.5, -1.0], &Accuracy::default(), None).unwrap().unwrap();
    assert_eq!(report(&near).contacts, Some(Vec::new()));
    assert_eq!(sweep(&near).contacts, Some(vec![Vec::new(), Vec::new()]));
    let json = serde_json::to_value(report(&near)).unwrap();
    assert_eq!(json["contacts"], serde_json::json!([]));
    assert_eq!(report(&bare).contacts, None);
    assert_eq!(sweep(&bare).contacts, None);
    assert!(serde_json::to_value(report(&bare)).unwrap().get("contacts").is_none());
}
