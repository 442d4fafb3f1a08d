//! Findings (issue 20, items 3 and 4): closures open at rest with the
//! preload that closes them, and parts that cross in a solved or simulated
//! shape. Each test names its reference.

use flexure::dynamics::simulation::{SimulationSettings, Start, simulate};
use flexure::mechanism::file::from_toml;
use flexure::mechanism::findings::{
    GAP_TOLERANCE, Part, Severity, crossings, crossings_along, open_closures, segments_meet,
};
use flexure::mechanism::statics::{Settings, solve};
use flexure::mechanism::sweep::{Parameter, sweep};
use std::f64::consts::PI;
use std::path::Path;

fn example(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(format!("{name}.toml"));
    std::fs::read_to_string(path).unwrap()
}

/// The names of every shipped planar example (`examples/*.toml`), so that a new one is checked too.
fn example_names() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().to_str()?.strip_suffix(".toml").map(String::from))
        // Planar findings: spatial mechanisms have none yet.
        .filter(|n| !example(n).contains("dimension = 3"))
        .collect();
    names.sort();
    assert!(names.len() >= 8, "the examples: {names:?}");
    names
}

/// The parallelogram example with its weld's lines replaced.
fn parallelogram(a_origin: &str, b_origin: &str, extra: &str) -> String {
    let text = example("parallelogram");
    let text = text.replace("a_origin = [0.0, -0.04, 0.0]", a_origin);
    let text = text.replace("b_origin = [0.0, 0.0, 0.0]", &format!("{b_origin}\n{extra}"));
    assert_ne!(text, example("parallelogram"), "the example's weld lines moved");
    text
}

// --- The segment test, against hand-computed cases. ---

/// The diagonals of the square [0, 2]²: they cross at its centre, halfway along each.
#[test]
fn crossing_diagonals_meet_at_the_centre() {
    let c = segments_meet([0.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.0, 0.0], 1e-12).unwrap();
    assert_eq!(c.at, [1.0, 1.0]);
    assert_eq!(c.t, [0.5, 0.5]);
    assert!(!c.collinear);
}

/// Two sides of the unit square meet at their shared corner (1, 0): the
/// end of the first, the start of the second.
#[test]
fn segments_sharing_an_endpoint_touch_there() {
    let c = segments_meet([0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 1.0], 1e-12).unwrap();
    assert_eq!(c.at, [1.0, 0.0]);
    assert_eq!(c.t, [1.0, 0.0]);
    assert!(!c.collinear);
    // A T: (1, 0)–(1, 1) stands on the middle of (0, 0)–(2, 0).
    let t = segments_meet([0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0], 1e-12).unwrap();
    assert_eq!((t.at, t.t), ([1.0, 0.0], [0.5, 0.0]));
}

/// [0, 2] and [1, 3] on the x axis overlap on [1, 2]: the contact starts at
/// x = 1, halfway along the first and at the start of the second.
#[test]
fn collinear_segments_overlap() {
    let c = segments_meet([0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [3.0, 0.0], 1e-12).unwrap();
    assert!(c.collinear);
    assert_eq!(c.at, [1.0, 0.0]);
    assert_eq!(c.t, [0.5, 0.0]);
    // Reversed, the second runs from 3 back to 1: x = 1 is its end.
    let r = segments_meet([0.0, 0.0], [2.0, 0.0], [3.0, 0.0], [1.0, 0.0], 1e-12).unwrap();
    assert_eq!((r.at, r.t), ([1.0, 0.0], [0.5, 1.0]));
    // [0, 1] and [2, 3] on one line do not meet.
    assert!(segments_meet([0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0], 1e-12).is_none());
}

/// Parallel segments one apart never meet; nor do crossing lines whose
/// segments stop short of the crossing, or a near miss wider than the tolerance.
#[test]
fn parallel_and_short_segments_do_not_meet() {
    assert!(segments_meet([0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], 1e-12).is_none());
    // The lines y = x and y = 2 − x cross at (1, 1), beyond both segments.
    assert!(segments_meet([0.0, 0.0], [0.9, 0.9], [0.0, 2.0], [0.9, 1.1], 1e-12).is_none());
    // (1, 1e-6)–(1, 1) stops 1e-6 above (0, 0)–(2, 0): touching within 1e-5, not within 1e-9.
    assert!(segments_meet([0.0, 0.0], [2.0, 0.0], [1.0, 1e-6], [1.0, 1.0], 1e-9).is_none());
    let near = segments_meet([0.0, 0.0], [2.0, 0.0], [1.0, 1e-6], [1.0, 1.0], 1e-5).unwrap();
    assert_eq!(near.at, [1.0, 0.0]);
}

// --- Closures open at rest. ---

/// The parallelogram's weld turned by half a turn (b_origin's angle π):
/// at rest the frames meet in position (0 m) and differ by π rad. Closing
/// it bends both legs: a warning naming the weld, with its preload.
#[test]
fn a_half_turn_weld_warns_with_its_gap_of_pi() {
    let m = from_toml(&parallelogram("a_origin = [0.0, -0.04, 0.0]", "b_origin = [0.0, 0.0, 3.141592653589793]", ""))
        .unwrap();
    let open = open_closures(&m, &Settings::default()).unwrap();
    assert_eq!(open.len(), 1, "{open:?}");
    let c = &open[0];
    assert_eq!(c.severity(), Severity::Warning);
    assert!(c.gap < 1e-15, "{}", c.gap);
    assert!((c.turn.unwrap().abs() - PI).abs() < 1e-12, "{:?}", c.turn);
    assert!(c.force.unwrap() > 0.1 && c.moment.unwrap() > 1e-3, "{c:?}");
    let text = c.message();
    assert!(text.contains("weld of \"stage\" and \"b_tip\"") && text.contains("3.141593 rad"), "{text}");
    assert!(text.contains("preload = true") && c.place == "line 26, column 5", "{text}");
    // The equilibrium it forces is still reported stable: only the finding says so.
    assert!(solve(&m, &Settings::default()).unwrap().stable);
}

/// The weld's point on the stage moved from 40 to 41 mm along it: at rest
/// the frames are 1 mm apart (the legs stand 40 mm apart) and not turned.
/// Closing it bends each leg 0.5 mm sideways as a guided beam (both tips
/// keep one angle, the weld's), stiffness 12 EI/L³ = 192 N/m each: a force
/// of 0.096 N and, at each tip, the guided beam's moment F L/2 = 2.4e-3 N·m
/// (small deflection; 0.5 mm is 1 % of L).
#[test]
fn a_weld_offset_by_a_millimetre_reports_that_gap_and_its_preload() {
    let m = from_toml(&parallelogram("a_origin = [0.0, -0.041, 0.0]", "b_origin = [0.0, 0.0, 0.0]", "")).unwrap();
    let open = open_closures(&m, &Settings::default()).unwrap();
    assert_eq!(open.len(), 1, "{open:?}");
    let c = &open[0];
    assert!((c.gap - 1e-3).abs() < 1e-15, "{}", c.gap);
    assert!(c.turn.unwrap().abs() < 1e-15, "{:?}", c.turn);
    let (ei, l) = (2.0e-3, 0.05_f64);
    let force = 0.5e-3 * 12.0 * ei / l.powi(3);
    assert!((c.force.unwrap() / force - 1.0).abs() < 2e-3, "{:?} against {force}", c.force);
    let moment = force * l / 2.0;
    assert!((c.moment.unwrap() / moment - 1.0).abs() < 2e-3, "{:?} against {moment}", c.moment);
    assert!(c.message().contains("1.000000e-3 m and 0.000000 rad"), "{}", c.message());
}

/// Closures that meet: the parallelogram as shipped, and its weld moved by
/// less than the tolerance (1e-12 m, against 1e-9 of its 0.14 m size);
/// moved by more (1e-9 m), it is open.
#[test]
fn a_closure_that_meets_does_not_warn() {
    let settings = Settings::default();
    let shipped = from_toml(&example("parallelogram")).unwrap();
    assert!((shipped.size() - 0.14).abs() < 1e-15);
    assert!(open_closures(&shipped, &settings).unwrap().is_empty());
    let within =
        from_toml(&parallelogram("a_origin = [0.0, -0.040000000001, 0.0]", "b_origin = [0.0, 0.0, 0.0]", "")).unwrap();
    assert!(open_closures(&within, &settings).unwrap().is_empty());
    assert!(1e-12 < GAP_TOLERANCE * shipped.size() && 1e-9 > GAP_TOLERANCE * shipped.size());
    let beyond =
        from_toml(&parallelogram("a_origin = [0.0, -0.040000001, 0.0]", "b_origin = [0.0, 0.0, 0.0]", "")).unwrap();
    let open = open_closures(&beyond, &settings).unwrap();
    assert_eq!(open.len(), 1);
    assert!((open[0].gap - 1e-9).abs() < 1e-15, "{}", open[0].gap);
    // Every shipped example's closures meet at rest, but the four-bar's pin, which says `preload = true`.
    for name in example_names().into_iter().filter(|n| n != "four_bar") {
        let m = from_toml(&example(&name)).unwrap();
        assert!(open_closures(&m, &settings).unwrap().is_empty(), "{name}");
    }
}

/// A pin 1 m away from the tip of a 50 mm flexure cannot be closed (the
/// tip reaches 50 mm at most): the gap is still reported, the preload is
/// not known, and no error is raised (a simulation from `[initial]` needs
/// no assembly); solving fails, placed at the pin.
#[test]
fn a_closure_that_cannot_be_assembled_still_reports_its_gap() {
    let text = "[[joint]]\nname = \"leg\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.05\nei = 1.0\n\
                [[pin]]\na = \"tip\"\nb = \"ground\"\nb_at = [1.05, 0.0]\n";
    let m = from_toml(text).unwrap();
    let open = open_closures(&m, &Settings::default()).unwrap();
    assert_eq!(open.len(), 1);
    assert!((open[0].gap - 1.0).abs() < 1e-12, "{}", open[0].gap);
    assert!(open[0].force.is_none() && open[0].moment.is_none() && open[0].turn.is_none());
    assert!(open[0].message().contains("cannot be assembled"), "{}", open[0].message());
    let e = solve(&m, &Settings::default()).unwrap_err().to_string();
    assert!(e.contains("pin of \"tip\" and \"ground\""), "{e}");
}

/// `preload = true` on the half-turn weld: the same gap, told as a note.
/// The four-bar example's pin says so too: 10 mm open at rest (its coupler
/// hinge's length: the coupler's end, 40 mm along it, sits 10 mm short of
/// the output's top).
#[test]
fn preload_true_notes_instead_of_warning() {
    let text =
        parallelogram("a_origin = [0.0, -0.04, 0.0]", "b_origin = [0.0, 0.0, 3.141592653589793]", "preload = true");
    let m = from_toml(&text).unwrap();
    assert!(m.closure_preload(0));
    let open = open_closures(&m, &Settings::default()).unwrap();
    assert_eq!(open.len(), 1);
    assert_eq!(open[0].severity(), Severity::Note);
    assert!((open[0].turn.unwrap().abs() - PI).abs() < 1e-12);
    assert!(open[0].message().ends_with("(preload = true)"), "{}", open[0].message());
    // `preload = false` is the default: a warning.
    let m = from_toml(&text.replace("preload = true", "preload = false")).unwrap();
    assert_eq!(open_closures(&m, &Settings::default()).unwrap()[0].severity(), Severity::Warning);
    let four_bar = from_toml(&example("four_bar")).unwrap();
    let open = open_closures(&four_bar, &Settings::default()).unwrap();
    assert_eq!(open.len(), 1);
    assert_eq!(open[0].severity(), Severity::Note);
    assert!((open[0].gap - 0.01).abs() < 1e-12, "{}", open[0].gap);
    assert!(open[0].turn.is_none() && open[0].moment.is_none());
}

// --- Crossings. ---

/// The parallelogram at order 10, swept past its buckling load (16 N,
/// `buckle`): the sweep snaps through to stable states at −20 N in which
/// the stage hangs below the legs' tops and leg "right" passes through it
/// (the case). Below buckling nothing crosses.
#[test]
fn the_parallelogram_past_buckling_crosses_its_stage() {
    let text = example("parallelogram").replace("ei = 2.0e-3\n", "ei = 2.0e-3\norder = 10\n");
    let m = from_toml(&text).unwrap();
    let p = Parameter::parse(&m, "force.push.fy").unwrap();
    let out = sweep(&m, &p, &[0.0, -10.0, -20.0], &Settings::default()).unwrap();
    assert_eq!(out.rows.len(), 3, "{:?}", out.stability_limit);
    let found = crossings_along(&m, out.rows.iter().map(|r| r.1.q.as_slice()));
    assert_eq!(found.iter().map(|f| f.0).collect::<Vec<_>>(), [2], "{found:?}");
    let (right, stage) = (m.joints.iter().position(|j| j.name == "right").unwrap(), m.body("stage").unwrap());
    let c = found[0].1.iter().find(|c| c.a == Part::Flexure(right) && c.b == Part::Link(stage)).expect("right × stage");
    assert!(out.rows[2].1.stable);
    assert!(c.message().starts_with("flexure \"right\" crosses link \"stage\" at ("), "{}", c.message());
    let s = c.s[0].unwrap();
    assert!(s > 0.0 && s < 0.05 && c.s[1].is_none(), "{c:?}");
}

/// A pendulum let go level swings down through a flexure post standing
/// beside its pivot: the bob's link (pivot to centre of mass, 0.2 m) meets
/// the post (x = 0.05 m, y from −0.3 to −0.02 m) while its angle lies
/// between −75.5° (cos θ = 0.05/0.2) and −21.8° (tan θ = −0.02/0.05).
const PENDULUM: &str = include_str!("data/pendulum_through_post.toml");

#[test]
fn a_simulation_that_crosses_reports_it_at_its_samples() {
    let m = from_toml(PENDULUM).unwrap();
    let mut settings = SimulationSettings::default();
    settings.motion.duration = 0.3;
    settings.motion.every = 0.01;
    let run = simulate(&m, &settings, Start::Equilibrium).unwrap();
    let found = crossings_along(&m, (0..run.time.len()).map(|k| run.q(k)));
    assert!(!found.is_empty(), "the bob never crossed the post");
    let (post, bob) = (m.joints.iter().position(|j| j.name == "post").unwrap(), m.body("bob").unwrap());
    let pivot = m.joints.iter().find(|j| j.name == "pivot").unwrap().offset;
    let mut counted = [0, 0];
    for k in 0..run.time.len() {
        let theta = run.q(k)[pivot];
        let here = found.iter().find(|f| f.0 == k);
        let crosses = here.is_some_and(|f| f.1.iter().any(|c| c.a == Part::Flexure(post) && c.b == Part::Link(bob)));
        // Away from the window's edges (1e-3 rad), the geometry decides.
        let inside = theta > -75.52f64.to_radians() + 1e-3 && theta < -21.80f64.to_radians() - 1e-3;
        let outside = theta < -75.52f64.to_radians() - 1e-3 || theta > -21.80f64.to_radians() + 1e-3;
        counted[usize::from(outside)] += usize::from(inside || outside);
        if inside {
            assert!(crosses, "t = {}: θ = {theta} inside the window, no crossing: {here:?}", run.time[k]);
        }
        if outside {
            assert!(!crosses, "t = {}: θ = {theta} outside the window: {here:?}", run.time[k]);
        }
    }
    assert!(found.iter().all(|f| f.0 > 0), "level at t = 0, it does not cross");
    // Samples on both sides of the window's edges were checked.
    assert!(counted[0] >= 3 && counted[1] >= 3, "{counted:?}");
}

/// A solved shape that crosses nothing, and the static answers of every
/// shipped example at its own loads: no crossing.
#[test]
fn the_examples_at_their_loads_cross_nothing() {
    for name in example_names() {
        let m = from_toml(&example(&name)).unwrap();
        let s = solve(&m, &Settings::default()).unwrap();
        let found = crossings(&m, &s.q);
        assert!(found.is_empty(), "{name}: {:?}", found.iter().map(|c| c.message()).collect::<Vec<_>>());
    }
}
