//! `mechanism/contact/gap.rs`: a pair's gap, nearest point, arc length and
//! normal at a configuration, against closed forms: a planar flexure bent
//! into a circular arc (its first coordinate alone: $\theta(s) = s$ for
//! $L = 1$) near a floor (its root nearest), a wall (its tip nearest) and a
//! post (an interior point nearest, on the arc's radius through the post's
//! centre); a spatial strip near spheres; a ball on a body near a floor.
//! Gaps to 1e-12 m (the quadrature of the arc is exact to rounding); arc
//! lengths to 1e-7 m (a smooth least locates to the square root of the
//! gap's rounding).

use flexure::mechanism::contact::{GeomShape, gap, pairs};
use flexure::mechanism::file::{from_toml, spatial_from_toml};
use flexure::mechanism::findings::Findings;
use flexure::mechanism::kinematics::frames;
use flexure::space::Spatial;

const ARC: &str = "[[joint]]\nname = \"arc\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\nkappa = [1.0, 0.0, 0.0]\n";

/// The pair of the arc's file with one geom: its gap at rest.
fn arc_gap(geom: &str) -> (f64, f64, [f64; 2], [f64; 2]) {
    let m = from_toml(&format!("{ARC}[[geom]]\nbody = \"ground\"\n{geom}")).unwrap();
    let q = m.rest();
    let g = gap(&m, &q, &frames(&m, &q).bodies, &pairs(&m)[0]).unwrap();
    (g.gap, g.s.unwrap(), [g.point.x, g.point.y], [g.normal.x, g.normal.y])
}

#[test]
fn a_circular_arc_meets_its_closed_forms() {
    // The arc: centre (0, 1), radius 1, from the origin to (sin 1, 1 − cos 1).
    let (g, s, p, n) = arc_gap("shape = \"plane\"\norigin = [0.0, -0.1]\nnormal = [0.0, 1.0]\n");
    assert!((g - 0.1).abs() < 1e-12 && s.abs() < 1e-7 && p[0].abs() < 1e-7 && n == [0.0, 1.0], "{g} {s} {p:?}");
    let (g, s, _, n) = arc_gap("shape = \"plane\"\norigin = [2.0, 0.0]\nnormal = [-1.0, 0.0]\n");
    assert!((g - (2.0 - 1f64.sin())).abs() < 1e-12 && (s - 1.0).abs() < 1e-7 && n == [-1.0, 0.0], "{g} {s}");
    // A post of radius 0.5 three from the arc's centre, along its radius through s = 0.5.
    let (sin, cos) = 0.5f64.sin_cos();
    let post = format!("shape = \"circle\"\norigin = [{}, {}]\nradius = 0.5\n", 3.0 * sin, 1.0 - 3.0 * cos);
    let (g, s, p, n) = arc_gap(&post);
    assert!((g - 1.5).abs() < 1e-12 && (s - 0.5).abs() < 1e-7, "{g} {s}");
    assert!((p[0] - sin).abs() < 1e-7 && (p[1] - (1.0 - cos)).abs() < 1e-7, "{p:?}");
    assert!((n[0] + sin).abs() < 1e-7 && (n[1] - cos).abs() < 1e-7, "{n:?}");
}

#[test]
fn a_spatial_strip_meets_its_closed_forms() {
    let strip = "dimension = 3\n[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.1\nmodulus = 2e11\nwidth = 0.01\nthickness = 0.001\n";
    let one = |origin: &str| {
        let m = spatial_from_toml(&format!(
            "{strip}[[geom]]\nbody = \"ground\"\nshape = \"sphere\"\norigin = {origin}\nradius = 0.005\n"
        ))
        .unwrap();
        let q = m.rest();
        gap(&m, &q, &Spatial::poses(&m, &q).0, &pairs(&m)[0]).unwrap()
    };
    // Above the middle: 10.2 mm less the radius and half the thickness.
    let g = one("[0.05, 0.0, 0.0102]");
    assert!((g.gap - 0.0047).abs() < 1e-12 && (g.s.unwrap() - 0.05).abs() < 1e-7, "{g:?}");
    assert!((g.point.z - 0.0005).abs() < 1e-12 && (g.normal.z + 1.0).abs() < 1e-12, "{g:?}");
    // Beyond the tip, a 3-4-5 triangle: the tip is nearest, 50 mm from the centre.
    let g = one("[0.13, 0.0, 0.04]");
    assert!((g.gap - 0.0445).abs() < 1e-12 && (g.s.unwrap() - 0.1).abs() < 1e-12, "{g:?}");
    assert!((g.normal - nalgebra::Vector3::new(-0.6, 0.0, -0.8)).norm() < 1e-12, "{g:?}");
}

#[test]
fn a_ball_on_a_body_meets_a_floor_two_boxes_meet_at_corners_and_two_planes_are_refused() {
    let strip = "[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.1\nei = 1.0\n";
    let text = format!(
        "{strip}[[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\nexclude = [\"strip\"]\n[[geom]]\nname = \"pad\"\nbody = \"tip\"\nshape = \"circle\"\nradius = 0.002\nexclude = [\"strip\"]\n"
    );
    let m = from_toml(&text).unwrap();
    let q = m.rest();
    let g = gap(&m, &q, &frames(&m, &q).bodies, &pairs(&m)[0]).unwrap();
    assert!((g.gap - 0.008).abs() < 1e-15 && g.s.is_none(), "{g:?}");
    assert!((g.point.x - 0.1).abs() < 1e-15 && (g.point.y + 0.002).abs() < 1e-15 && g.normal.y == 1.0, "{g:?}");
    // Two boxes in the plane touch at their corners: the pad's lower ones,
    // 1 mm below its centre, are 8 mm above the floor box's top.
    let mut boxes = m.clone();
    boxes.geoms[1].shape = GeomShape::Box { half_extents: nalgebra::Vector2::new(0.001, 0.001) };
    boxes.geoms[0].shape = GeomShape::Box { half_extents: nalgebra::Vector2::new(1.0, 0.001) };
    let all = pairs(&boxes);
    let gaps: Vec<_> = all.iter().map(|p| gap(&boxes, &q, &frames(&boxes, &q).bodies, p).unwrap()).collect();
    assert_eq!(gaps.len(), 8);
    let least = gaps.iter().min_by(|a, b| a.gap.total_cmp(&b.gap)).unwrap();
    assert!(
        (least.gap - 0.008).abs() < 1e-15 && least.normal.y == 1.0 && (least.point.y + 0.001).abs() < 1e-15,
        "{least:?}"
    );
    // Two planes never part: their gap is refused by name.
    boxes.geoms[1].shape = GeomShape::Plane { normal: nalgebra::Vector2::new(0.0, -1.0) };
    boxes.geoms[0].shape = GeomShape::Plane { normal: nalgebra::Vector2::new(0.0, 1.0) };
    let e = gap(&boxes, &q, &frames(&boxes, &q).bodies, &all[0]).unwrap_err().to_string();
    assert!(
        e.contains("geom \"floor\" (plane) and geom \"pad\" (plane) on body \"tip\"") && e.contains("circle"),
        "{e}"
    );
}

/// The planar–spatial cross-check: the arc in a spatial file (its rest
/// curvature about z, in the xy plane) near a sphere centred in that plane
/// has the planar arc's gap to the circle of the same centre and radius,
/// at the same arc length. The two flexures are integrated differently
/// (Gauss quadrature of the angle; Magnus steps of the frame), each exact
/// for a constant curvature to rounding: gaps to 1e-12 m, arc lengths to 1e-7 m.
#[test]
fn a_spatial_file_of_a_planar_gap_gives_the_planar_gap() {
    let (sin, cos) = 0.3f64.sin_cos();
    let (x, y) = (2.0 * sin + 0.1, 1.0 - 2.0 * cos);
    let planar = from_toml(&format!(
        "{ARC}[[geom]]\nbody = \"ground\"\nshape = \"circle\"\norigin = [{x}, {y}]\nradius = 0.4\n"
    ))
    .unwrap();
    let spatial = spatial_from_toml(&format!(
        "dimension = 3\n[[joint]]\nname = \"arc\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\nkappa_z = [1.0, 0.0, 0.0]\n[[geom]]\nbody = \"ground\"\nshape = \"sphere\"\norigin = [{x}, {y}, 0.0]\nradius = 0.4\n"
    ))
    .unwrap();
    let (qp, qs) = (planar.rest(), spatial.rest());
    let a = gap(&planar, &qp, &frames(&planar, &qp).bodies, &pairs(&planar)[0]).unwrap();
    let b = gap(&spatial, &qs, &Spatial::poses(&spatial, &qs).0, &pairs(&spatial)[0]).unwrap();
    assert!((a.gap - b.gap).abs() < 1e-12, "planar {a:?}, spatial {b:?}");
    assert!((a.s.unwrap() - b.s.unwrap()).abs() < 1e-7, "planar {a:?}, spatial {b:?}");
    assert!((a.point.x - b.point.x).abs() < 1e-7 && (a.point.y - b.point.y).abs() < 1e-7 && b.point.z.abs() < 1e-12);
    assert!(
        (a.normal.x - b.normal.x).abs() < 1e-7 && (a.normal.y - b.normal.y).abs() < 1e-7 && b.normal.z.abs() < 1e-12
    );
    assert!(a.gap > 0.3 && a.s.unwrap() > 0.05 && a.s.unwrap() < 0.95, "an interior nearest point: {a:?}");
}
