//! The shipped spatial examples (`examples/*3d.toml`,
//! `examples/continuum_robot.toml`): each solves to a stable equilibrium
//! whose flexures meet the default accuracy, against its named reference.

use flexure::estimate::Accuracy;
use flexure::mechanism::file::spatial_from_toml;
use flexure::mechanism::spatial::SpatialMechanism;
use flexure::mechanism::statics::solve;
use flexure::report::{Placement, SolveReport, placements, solve_report};

fn example(name: &str) -> (SpatialMechanism, Report) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name);
    let m = spatial_from_toml(&std::fs::read_to_string(path).unwrap()).unwrap();
    let s = solve(&m, &Default::default()).unwrap();
    assert!(s.stable, "{name}");
    let r = solve_report(&m, &s, &Accuracy::default()).unwrap();
    assert!(!r.flagged, "{name}: a flexure misses the default accuracy");
    let bodies = placements(&m, &s.q);
    (m, Report { report: r, bodies })
}

/// The solve report, and every moving body's placement.
struct Report {
    report: SolveReport,
    bodies: Vec<Placement>,
}

fn body<'a>(r: &'a Report, name: &str) -> &'a Placement {
    r.bodies.iter().find(|b| b.name == name).unwrap()
}

/// Reference: a parallelogram's guided legs, in plane $F/(24EI_z/L^3)$, and
/// out of plane (the legs lie in one plane, so the stage tilts about their
/// line and each is a cantilever) $F/(2\cdot 3EI_y/L^3)$: to 1e-3 in plane
/// (the large deflection of a 0.1 mm slide), and to 5e-3 out of it, where
/// the legs' S-bend from the in-plane push couples their bending with
/// twist (measured +0.31 %).
#[test]
fn the_stage_moves_as_its_legs_guide_it() {
    let (_, r) = example("stage3d.toml");
    let (e, w, t, l): (f64, f64, f64, f64) = (200e9, 0.01, 0.0003, 0.03);
    let (ei_z, ei_y) = (e * w * t.powi(3) / 12.0, e * t * w.powi(3) / 12.0);
    let stage = body(&r, "stage");
    let x = 0.5 / (24.0 * ei_z / l.powi(3));
    let z = 2.0 / (6.0 * ei_y / l.powi(3));
    assert!((stage.position[0] - x).abs() < 1e-3 * x, "{:?} against x = {x}", stage.position);
    assert!((stage.position[2] - z).abs() < 5e-3 * z, "{:?} against z = {z}", stage.position);
}

/// Reference: the symmetry of a round backbone: tendons at +y and +z with
/// tensions 0.6 and 0.3 N bend the tip toward y and z in the ratio of the
/// tensions (to 1e-4: at this 0.4 rad bend the two are not exactly
/// superposed, measured 7e-6), and each segment by about $Tr/EI$ (the tendon's
/// offset moment; to 10 %: the tendon runs as chords between the discs).
#[test]
fn the_continuum_robot_bends_toward_both_tendons() {
    let (m, r) = example("continuum_robot.toml");
    let tip = body(&r, "disc5");
    assert!((tip.position[1] / tip.position[2] - 2.0).abs() < 1e-4, "{:?}", tip.position);
    let ei = 60e9 * std::f64::consts::PI * 0.0006f64.powi(4) / 64.0;
    let kappa = (0.6f64.hypot(0.3)) * 0.004 / ei;
    // The tip's rotation: five segments of 12 mm each at κ.
    let r = tip.rotation;
    let turn = (0.5 * (r[0][0] + r[1][1] + r[2][2] - 1.0)).acos();
    let expected = 5.0 * 0.012 * kappa;
    assert!((turn - expected).abs() < 0.1 * expected, "{turn} against {expected}");
    assert_eq!(m.tendons.len(), 2);
}

/// Reference: the finger's mid-plane symmetry: a fingertip force in the
/// mid-plane would leave every twist zero; this one, 3 mm off it with a
/// sideways part, twists every blade, most the one nearest the root
/// (which carries the longest lever), while the finger flexes (the tip
/// turns about −z).
#[test]
fn the_off_centre_fingertip_load_twists_the_finger() {
    let (m, r) = example("finger3d.toml");
    let twist = |name: &str| r.report.coordinates.get(name).unwrap()[0];
    let (mcp, pip, dip) = (twist("mcp"), twist("pip"), twist("dip"));
    assert!(mcp.abs() > 1e-4 && pip.abs() > 1e-4 && dip.abs() > 1e-5, "{mcp} {pip} {dip}");
    let tip = body(&r, "fingertip");
    assert!(tip.rpy[2] < -0.1, "it flexes: {:?}", tip.rpy);
    // The same force in the mid-plane, without its sideways part: no twist at all.
    let mut centred = m.clone();
    centred.forces[0].at.z = 0.0;
    centred.forces[0].wrench[5] = 0.0;
    let s = solve(&centred, &Default::default()).unwrap();
    for j in &centred.joints {
        if j.kind.flexure().is_some() {
            assert!(s.q[j.offset].abs() < 1e-12, "{}: {}", j.name, s.q[j.offset]);
        }
    }
}
