//! Crossings of spatial mechanisms (issue 24, "each as it works on planar
//! files"): parts with the thickness of their sections that pass through
//! each other or themselves. Each test names its closed-form reference.

use flexure::mechanism::file::spatial_from_toml;
use flexure::mechanism::findings::Part;
use flexure::mechanism::findings::{crossings, crossings_along};
use flexure::mechanism::statics::solve;
use std::f64::consts::PI;
use std::path::Path;

fn example(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(format!("{name}.toml"));
    std::fs::read_to_string(path).unwrap()
}

fn rod(name: &str, origin: [f64; 3], rpy_deg: [f64; 3], section: &str) -> String {
    format!(
        "[[joint]]\nname = \"{name}\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"{name}_tip\"\n\
         origin = {origin:?}\nrpy_deg = {rpy_deg:?}\nlength = 0.05\nmodulus = 2e11\npoisson = 0.3\n{section}\n"
    )
}

/// Two round rods side by side, axes `gap` apart: two cylinders of
/// diameter d meet exactly when their axes are at most d apart.
#[test]
fn round_rods_meet_when_their_axes_are_a_diameter_apart() {
    let d = 2e-3;
    for (gap, meet) in [(0.99 * d, true), (1.01 * d, false), (0.5 * d, true), (3.0 * d, false)] {
        let text = format!(
            "dimension = 3\n{}{}",
            rod("a", [0.0; 3], [0.0; 3], "diameter = 2e-3"),
            rod("b", [0.0, 0.0, gap], [0.0; 3], "diameter = 2e-3")
        );
        let m = spatial_from_toml(&text).unwrap();
        let found = crossings(&m, &m.rest());
        assert_eq!(!found.is_empty(), meet, "gap {gap}: {found:?}");
        if meet {
            let c = &found[0];
            assert_eq!((c.a, c.b, c.points), (Part::Flexure(0), Part::Flexure(1), 1), "{c:?}");
            // All along: the first contact is at the roots, halfway between the axes.
            assert!(c.at[0].abs() < 1e-3 && (c.at[2] - gap / 2.0).abs() < 1e-12, "{c:?}");
        }
    }
}

/// A cross-spring pivot built in space: two blades 10 mm wide (along z)
/// crossing at right angles in the xy plane, the second raised by Δ. Their
/// solids overlap where their projections cross exactly when Δ is less than
/// the sum of their half-widths, w; the crossing is at the blades'
/// midpoints, (L/√2, 0) in the plane, halfway up.
#[test]
fn crossed_blades_meet_unless_raised_by_their_width() {
    let (l, w) = (0.05, 0.01);
    // Roots at y = ∓L/(2√2): the blades cross halfway, at x = L/(2√2).
    let mid = l / (2.0 * 2f64.sqrt());
    let blade = "width = 0.01\nthickness = 3e-4";
    for (raise, meet) in [(0.98 * w, true), (1.02 * w, false), (0.0, true)] {
        let text = format!(
            "dimension = 3\n{}{}",
            rod("a", [0.0, -mid, 0.0], [0.0, 0.0, 45.0], blade),
            rod("b", [0.0, mid, raise], [0.0, 0.0, -45.0], blade),
        );
        let m = spatial_from_toml(&text).unwrap();
        let found = crossings(&m, &m.rest());
        let pair: Vec<_> = found.iter().filter(|c| c.a == Part::Flexure(0) && c.b == Part::Flexure(1)).collect();
        assert_eq!(pair.len(), usize::from(meet), "raised {raise}: {found:?}");
        // The ground's edge between the roots leaves each blade's root at
        // 45°: that contact runs on from the root, so it is the joint.
        assert_eq!(found.len(), pair.len(), "only the blades cross: {found:?}");
        if let Some(c) = pair.first() {
            assert!((c.at[0] - mid).abs() < 1e-4 && c.at[1].abs() < 1e-4, "{c:?}");
            assert!((c.at[2] - raise / 2.0).abs() < 1e-9, "{c:?}");
            let [sa, sb] = [c.s[0].unwrap(), c.s[1].unwrap()];
            assert!((sa - l / 2.0).abs() < 1e-3 && (sb - l / 2.0).abs() < 1e-3, "{c:?}");
            assert!(c.message().starts_with("flexure \"a\" crosses flexure \"b\" at ("), "{}", c.message());
        }
    }
}

/// A round rod bent into a helix by constant twist τ and bending κ (its
/// body-frame curvature (τ, 0, κ)): radius r = κ/(κ² + τ²) and rise per turn
/// p = 2πτ/(κ² + τ²). Its tube of diameter d touches its next turn exactly
/// when d reaches the least distance between a point and the next turn,
/// min over φ of √(4r²sin²(φ/2) + c²(2π + φ)²), c = p/2π.
#[test]
fn a_helix_touches_its_next_turn_when_thicker_than_their_distance() {
    let (r, p) = (0.01, 0.003);
    let c = p / (2.0 * PI);
    let kappa = r / (r * r + c * c);
    let tau = c / (r * r + c * c);
    let length = 2.5 * 2.0 * PI * (r * r + c * c).sqrt();
    let least = (0..=200_000)
        .map(|i| -0.5 + i as f64 * 1e-6 * 5.0)
        .filter(|phi| *phi <= 0.5)
        .map(|phi: f64| (4.0 * r * r * (phi / 2.0).sin().powi(2) + c * c * (2.0 * PI + phi).powi(2)).sqrt())
        .fold(f64::MAX, f64::min);
    assert!(least < p && least > 0.9 * p, "{least}");
    for (d, meet) in [(1.03 * least, true), (0.97 * least, false)] {
        let text = format!(
            "dimension = 3\n[[joint]]\nname = \"coil\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"end\"\n\
             length = {length}\nmodulus = 2e11\npoisson = 0.3\ndiameter = {d}\norders = [1, 1, 1]\n"
        );
        let m = spatial_from_toml(&text).unwrap();
        let q = [tau * length, 0.0, kappa * length];
        let found = crossings(&m, &q);
        assert_eq!(!found.is_empty(), meet, "d = {d}: {found:?}");
        if let Some(x) = found.first() {
            assert_eq!((x.a, x.b), (Part::Flexure(0), Part::Flexure(0)));
            // One contact, running along the 1.5 turns that have a turn before them.
            assert_eq!(x.points, 1, "{x:?}");
            let [s0, s1] = [x.s[0].unwrap(), x.s[1].unwrap()];
            let turn = 2.0 * PI * (r * r + c * c).sqrt();
            assert!(((s1 - s0) / turn - 1.0).abs() < 0.02, "a turn apart: {x:?}");
            assert!(x.message().starts_with("flexure \"coil\" crosses itself at ("), "{}", x.message());
        }
    }
}

/// The planar pendulum and post in space (`tests/data/pendulum_through_post3d.toml`),
/// the post a blade h = 10 mm thick along x: the bob's link, pivot to centre
/// of mass (0.2 m, no thickness), meets the post's solid (x from 0.05 − h/2
/// to 0.05 + h/2, y up to −0.02 m) when the pivot's angle θ < 0 has
/// 0.2 cos θ ≥ 0.05 − h/2 and (0.05 + h/2) tan|θ| ≥ 0.02, that is
/// −77.0° ≤ θ ≤ −19.98° (the planar window, −75.5° to −21.8°, widened by
/// the thickness). Nothing else crosses: the ground's edge (pivot to the
/// post's root) and the post meet only at its root.
const PENDULUM: &str = include_str!("data/pendulum_through_post3d.toml");

fn window() -> (f64, f64) {
    let h = 0.01;
    (-((0.05 - h / 2.0) / 0.2f64).acos(), -(0.02 / (0.05 + h / 2.0f64)).atan())
}

#[test]
fn a_pendulum_meets_a_thick_post_in_the_window_its_thickness_widens() {
    let m = spatial_from_toml(PENDULUM).unwrap();
    let (low, high) = window();
    let pivot = m.joints.iter().find(|j| j.name == "pivot").unwrap().offset;
    let (post, bob) = (m.joints.iter().position(|j| j.name == "post").unwrap(), m.body("bob").unwrap());
    let angles: Vec<f64> = [low - 0.2, low - 1e-3, low + 1e-3, -0.7, high - 1e-3, high + 1e-3, 0.0, 0.5].to_vec();
    let shapes: Vec<Vec<f64>> = angles
        .iter()
        .map(|theta| {
            let mut q = m.rest();
            q[pivot] = *theta;
            q
        })
        .collect();
    let found = crossings_along(&m, shapes.iter().map(Vec::as_slice));
    for (k, theta) in angles.iter().enumerate() {
        let inside = *theta > low && *theta < high;
        let here: Vec<_> = found.iter().filter(|f| f.0 == k).flat_map(|f| f.1.iter()).collect();
        assert_eq!(here.len(), usize::from(inside), "θ = {theta}: {here:?}");
        if let Some(c) = here.first() {
            assert_eq!((c.a, c.b), (Part::Flexure(post), Part::Link(bob)), "{c:?}");
            assert!(c.message().starts_with("flexure \"post\" crosses link \"bob\" at ("), "{}", c.message());
            // Midway between the post's centreline x = 0.05 and the bob's
            // link, which are at most h apart where they touch.
            let [x, y, z] = c.at;
            assert!(z.abs() < 1e-12 && (x - 0.05).abs() <= 0.005 + 1e-9, "{c:?}");
            assert!((x * theta.sin() - y * theta.cos()).abs() <= 0.005 + 1e-9, "{c:?}");
        }
    }
}

/// The same pendulum let go level, simulated: a crossing at exactly the
/// samples whose angle lies in the window (away from its edges by 1e-3 rad).
#[test]
fn a_swing_through_the_post_crosses_it_at_its_samples() {
    use flexure::dynamics::integrate::MotionSettings as Motion;
    use flexure::dynamics::simulation::{SimulationSettings, Start, simulate};
    let m = spatial_from_toml(PENDULUM).unwrap();
    let motion = Motion { duration: 0.3, every: 0.01, ..Default::default() };
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none(), "{:?}", run.stopped);
    let found = crossings_along(&m, (0..run.time.len()).map(|k| run.q(k)));
    let (low, high) = window();
    let mut counted = [0, 0];
    for k in 0..run.time.len() {
        let theta = run.q(k)[0];
        let crosses = found.iter().any(|f| f.0 == k);
        if theta > low + 1e-3 && theta < high - 1e-3 {
            counted[0] += 1;
            assert!(crosses, "t = {}: θ = {theta} in the window", run.time[k]);
        } else if theta < low - 1e-3 || theta > high + 1e-3 {
            counted[1] += 1;
            assert!(!crosses, "t = {}: θ = {theta} outside the window", run.time[k]);
        }
    }
    assert!(counted[0] >= 3 && counted[1] >= 3, "{counted:?}");
}

/// The shipped spatial examples, unloaded and at their own loads, are
/// designs whose parts do not touch: no crossing.
#[test]
fn the_spatial_examples_cross_nothing() {
    for name in ["finger3d", "continuum_robot", "stage3d"] {
        let m = spatial_from_toml(&example(name)).unwrap();
        let rest = crossings(&m, &m.rest());
        assert!(rest.is_empty(), "{name} at rest: {:?}", rest.iter().map(|c| c.message()).collect::<Vec<_>>());
        let s = solve(&m, &Default::default()).unwrap();
        let loaded = crossings(&m, &s.q);
        assert!(loaded.is_empty(), "{name}: {:?}", loaded.iter().map(|c| c.message()).collect::<Vec<_>>());
    }
}

/// A blade 10 mm wide (along z) and 0.5 mm thick at rest along x, beside a
/// ball of radius 1 mm centred in its plane (y = 0) at x = 45 mm and
/// `z` off its centreline. Contact holds the tube of its thickness, so a
/// ball within the width but clear of the tube passes through the blade:
/// that is found (closed form: a ball at z meets the blade's mid-plane where
/// |z| − r < 5 mm), with its point inside the ball and its arc length
/// within the ball's span along x; a ball past the edge is not.
#[test]
fn a_blades_width_passing_through_a_ball_is_found() {
    let (r, c) = (1e-3, 0.045);
    for (z, found) in [(0.004, true), (0.0059, true), (0.0061, false), (0.0075, false), (-0.003, true)] {
        let text = format!(
            "dimension = 3\n{}[[geom]]\nname = \"ball\"\nbody = \"ground\"\nshape = \"sphere\"\n\
             origin = [{c}, 0.0, {z}]\nradius = {r}\n",
            rod("blade", [0.0; 3], [0.0; 3], "width = 0.01\nthickness = 0.0005")
        );
        let m = spatial_from_toml(&text).unwrap();
        let all = crossings(&m, &m.rest());
        assert_eq!(all.len(), usize::from(found), "z = {z}: {all:?}");
        let Some(x) = all.first() else { continue };
        assert_eq!((x.a, x.b), (Part::Flexure(0), Part::Geom(0)), "{x:?}");
        assert!(x.message().starts_with("flexure \"blade\"'s width crosses geom \"ball\""), "{}", x.message());
        let inside = ((x.at[0] - c).powi(2) + x.at[1].powi(2) + (x.at[2] - z).powi(2)).sqrt();
        let s = x.s[0].unwrap();
        assert!(inside < r && (s - c).abs() < r, "z = {z}: {x:?}");
    }
}
