//! docs/first-mechanism.md, run as a newcomer runs it: each file the page
//! says to save is saved from its ```toml block and solved with
//! `flexure solve`, and each number the page quotes is checked twice: against
//! the answer, to the digits the page shows, and against beam theory's closed
//! form for small loads, to the tolerance each test names.

use crate::cli::{answer, run};
use serde_json::{Value, json};
use std::path::PathBuf;

const PAGE: &str = include_str!("../../../docs/first-mechanism.md");

/// The ```toml block that follows "Save this as `NAME`" on the page.
fn block(name: &str) -> String {
    let said = format!("as `{name}`");
    let at = PAGE.find(&said).unwrap_or_else(|| panic!("the page never says to save {name}"));
    let rest = &PAGE[at..];
    let start = rest.find("```toml\n").expect("a toml block after it") + "```toml\n".len();
    let end = rest[start..].find("```").expect("the block's end");
    rest[start..start + end].to_string()
}

/// The page's file `name` (or `text` in its place), saved in a fresh directory as the page says.
fn saved(dir: &tempfile::TempDir, name: &str, text: &str) -> String {
    let path: PathBuf = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// The page's file `name`, saved and solved: its text and the answer.
fn page_file(dir: &tempfile::TempDir, name: &str) -> (String, Value) {
    let text = block(name);
    let v = solve(&saved(dir, name, &text));
    (text, v)
}

/// Body `name` of an answer: both dimensions map bodies by name.
fn body<'a>(v: &'a Value, name: &str) -> &'a Value {
    v["bodies"].get(name).unwrap_or_else(|| panic!("no body {name} in {v}"))
}

/// A spatial body's position and its roll, pitch and yaw.
fn placement(b: &Value) -> (Value, Value) {
    (json!([b["x"], b["y"], b["z"]]), json!([b["roll"], b["pitch"], b["yaw"]]))
}

/// Whether `value` is within the relative `tolerance` of `expected`.
fn near(value: f64, expected: f64, tolerance: f64) -> bool {
    (value / expected - 1.0).abs() < tolerance
}

/// `flexure solve FILE --json`, which must answer without a warning.
fn solve(file: &str) -> Value {
    let (v, err) = answer(&["solve", file]);
    assert!(err.trim().is_empty(), "{file}: {err}");
    v
}

/// The numbers the page quotes right after `context` (whitespace-insensitive, and
/// unique on the page), one for each of `values`, each of which must round to it:
/// within half a unit in the last digit shown. Words between them are skipped.
fn quoted(context: &str, values: &[f64]) {
    let page = PAGE.split_whitespace().collect::<Vec<_>>().join(" ");
    let context = context.split_whitespace().collect::<Vec<_>>().join(" ");
    assert_eq!(page.matches(&context).count(), 1, "the page must say {context:?} once");
    let after = &page[page.find(&context).unwrap() + context.len()..];
    let shown: Vec<&str> = after
        .split_whitespace()
        .map(|t| t.trim_matches(|c| "`,();:$".contains(c)).trim_end_matches('.'))
        .filter(|t| t.parse::<f64>().is_ok())
        .take(values.len())
        .collect();
    assert_eq!(shown.len(), values.len(), "after {context:?} the page quotes {shown:?}");
    for (shown, value) in shown.iter().zip(values) {
        let (mantissa, exponent) = shown.split_once('e').map_or((*shown, 0), |(m, e)| (m, e.parse::<i32>().unwrap()));
        let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len() as i32);
        let half = 0.5 * 10f64.powi(exponent - decimals);
        let number: f64 = shown.parse().unwrap();
        assert!(
            (value - number).abs() <= half * (1.0 + 1e-9),
            "after {context:?} the page quotes {shown}, the answer is {value}"
        );
    }
}

/// Whether the page says `text`, whitespace-insensitive.
fn says(text: &str) -> bool {
    let words = |t: &str| t.split_whitespace().collect::<Vec<_>>().join(" ");
    words(PAGE).contains(&words(text))
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The blade of every file: L = 50 mm, E = 200 GPa, 10 mm × 0.2 mm.
const L: f64 = 0.05;
const E: f64 = 200e9;
const W: f64 = 0.01;
const H: f64 = 2e-4;

/// EI about the blade's soft axis, E w h³/12 (the planar file has no `poisson`,
/// and the spatial rectangle takes E: the same in both).
fn ei() -> f64 {
    E * W * H.powi(3) / 12.0
}

#[test]
fn the_cantilever_bends_as_beam_theory_says() {
    let dir = tempfile::tempdir().unwrap();
    let (text, v) = page_file(&dir, "cantilever.toml");
    let (arm, p) = (body(&v, "arm"), 0.01);
    // Small-load cantilever: PL³/3EI and PL²/2EI. The load is 1.9 % of EI/L², so the
    // large-deflection answer is within 0.05 % of them (tolerance 1e-3 relative).
    let (y, phi) = (p * L.powi(3) / (3.0 * ei()), p * L * L / (2.0 * ei()));
    assert!(near(f(&arm["y"]), y, 1e-3) && near(f(&arm["phi"]), phi, 1e-3), "{arm}");
    quoted("where the arm's frame is:", &[f(&arm["x"]), f(&arm["y"]), f(&arm["phi"])]);
    assert!(says("1.3333\\times10^{-3}") && (ei() - 1.3333e-3).abs() < 5e-8);
    // The peak stress at the root, 6PL/(b h²) = 7.5 MPa, within 1e-3.
    let stress = f(&v["stress"]["blade"]["max"]);
    assert!(near(stress, 6.0 * p * L / (W * H * H), 1e-3) && f(&v["stress"]["blade"]["at"]) == 0.0);
    quoted("the peak bending stress,", &[stress]);

    // The force 20 mm along the arm, in the arm's (tip) frame: also a moment Pa at the
    // tip. PL³/3EI + PaL²/2EI and PL²/2EI + PaL/EI, within 1e-3 as above.
    let moved = text.replace("at = [0.0, 0.0] ", "at = [0.02, 0.0] ");
    assert_ne!(moved, text, "the page's `at` line changed");
    let v = solve(&saved(&dir, "moved.toml", &moved));
    let (arm, a) = (body(&v, "arm"), 0.02);
    let y = p * L.powi(3) / (3.0 * ei()) + p * a * L * L / (2.0 * ei());
    let phi = p * L * L / (2.0 * ei()) + p * a * L / ei();
    assert!(near(f(&arm["y"]), y, 1e-3) && near(f(&arm["phi"]), phi, 1e-3), "{arm}");
    quoted("puts the tip at", &[f(&arm["y"]), f(&arm["phi"])]);
    assert!(says("5.0\\times10^{-4}") && (y - 5.0e-4).abs() < 1e-12 && (phi - 0.016875).abs() < 1e-12);

    // 100 times the load at the tip: far from the small-load PL³/3EI (more than 20 %
    // below it), and within the default 1 % of L of the exact elastica, whose
    // command the page gives.
    let hard = text.replace("force = [0.0, 0.01] ", "force = [0.0, 1.0] ");
    assert_ne!(hard, text, "the page's force line changed");
    let v = solve(&saved(&dir, "hard.toml", &hard));
    let arm = body(&v, "arm");
    let small = 1.0 * L.powi(3) / (3.0 * ei());
    assert!(f(&arm["y"]) < 0.8 * small, "{arm}");
    quoted("the tip rises to", &[f(&arm["y"])]);
    quoted("for as it turns", &[f(&arm["phi"])]);
    let command = "flexure deflect --length 0.05 --modulus 200e9 --width 0.01 --thickness 2e-4 --fy 1 --exact";
    assert!(says(&format!("`{command}`")), "the page's command");
    let (exact, err) = answer(&command.split_whitespace().skip(1).collect::<Vec<_>>());
    assert!(err.trim().is_empty(), "{err}");
    let pose = &exact["pose"];
    assert!((f(&pose["y"]) - f(&arm["y"])).abs() < 0.01 * L && (f(&pose["x"]) - f(&arm["x"])).abs() < 0.01 * L);
    quoted("puts its tip at y =", &[f(&pose["y"])]);
}

#[test]
fn the_stage_slides_without_turning() {
    let dir = tempfile::tempdir().unwrap();
    let (text, v) = page_file(&dir, "stage.toml");
    let stage = body(&v, "stage");
    // Two guided blades side by side: F L³/24EI. The push is 0.1 N, 7.5 % of the
    // blades' EI/L²: within 1e-3 relative of the small-load answer.
    let x = 0.1 * L.powi(3) / (24.0 * ei());
    assert!(near(f(&stage["x"]), x, 1e-3), "{stage}");
    quoted("puts the stage at", &[f(&stage["x"]), f(&stage["phi"])]);
    assert!((f(&stage["phi"]) - std::f64::consts::FRAC_PI_2).abs() < 1e-9, "the stage turned: {stage}");

    // The weld's frame written in the ground's axes is 57 mm from the right tip at rest:
    // refused, naming the weld and the gap, as the page says.
    let wrong = text.replace("a_origin = [0.0, -0.04, 0.0]", "a_origin = [0.04, 0.0, 0.0]");
    assert_ne!(wrong, text, "the page's a_origin line changed");
    let file = saved(&dir, "wrong.toml", &wrong);
    let (code, out, err) = run(&["solve", &file]);
    assert_eq!(code, 2, "{out}");
    let gap = (2.0f64).sqrt() * 0.04;
    assert!(says("the closures cannot be assembled; at rest this one is open widest (5.657e-2 m"), "the error");
    assert!(err.contains("weld") && err.contains(&format!("open widest ({gap:.3e} m")), "{err}");
    assert!(err.contains("cannot be assembled") && format!("{gap:.3e}") == "5.657e-2", "{err}");
}

#[test]
fn the_spatial_cantilever_bends_as_the_planar_one_and_twists() {
    let dir = tempfile::tempdir().unwrap();
    let (_, v) = page_file(&dir, "cantilever3d.toml");
    let arm = body(&v, "arm");
    let (position, rpy) = placement(arm);
    let p = 0.01;
    // In the plane, as the planar file (within 1e-3, as there).
    assert!(near(f(&position[1]), p * L.powi(3) / (3.0 * ei()), 1e-3), "{position}");
    assert!(near(f(&rpy[2]), p * L * L / (2.0 * ei()), 1e-3), "{rpy}");
    // The twist of the offset force's moment eF: -eFL/GJ, with the thin strip's
    // GJ = G w h³/3 (1 - 0.630 h/w) (Timoshenko and Goodier; the series' next term is
    // 1e-9 of it at w/h = 50), G = E/2(1 + 0.3). The roll is the twist to within
    // the bending's coupling: tolerance 1e-3 relative.
    let g = E / (2.0 * 1.3);
    let gj = g * W * H.powi(3) / 3.0 * (1.0 - 0.630 * H / W);
    let twist = -0.005 * p * L / gj;
    assert!(near(f(&rpy[0]), twist, 1e-3), "roll {} against {twist}", rpy[0]);
    assert!(says("2.0254\\times10^{-3}") && (gj - 2.0254e-3).abs() < 5e-8, "GJ {gj}");
    let values: Vec<f64> = (0..3).map(|i| f(&position[i])).chain((0..3).map(|i| f(&rpy[i]))).collect();
    quoted("puts the arm at", &values[..3]);
    quoted("turns it by", &values[3..]);
}

#[test]
fn the_spatial_stage_is_stiff_out_of_its_plane() {
    let dir = tempfile::tempdir().unwrap();
    let (text, v) = page_file(&dir, "stage3d.toml");
    let stage = body(&v, "stage");
    // Out of the plane each blade is a cantilever the stiff way, EI_y = E h w³/12, carrying
    // half the load: F L³/6EI_y (the load is 1e-5 of EI_y/L²: tolerance 1e-6 relative).
    let ei_y = E * H * W.powi(3) / 12.0;
    let z = 0.1 * L.powi(3) / (6.0 * ei_y);
    let (position, _) = placement(stage);
    assert!(near(f(&position[2]), z, 1e-6), "{position}");
    quoted("lifts the stage by", &[f(&position[2])]);
    assert!(says("3.3333") && (ei_y - 3.3333).abs() < 5e-5);
    assert!(says("625 times") && ((0.1 * L.powi(3) / (24.0 * ei())) / z - 625.0).abs() < 1e-9);

    // The planar push gives the planar answer, 3.9060e-4 along x.
    let planar = text.replace("force = [0.0, 0.0, 0.1]", "force = [0.1, 0.0, 0.0]");
    assert_ne!(planar, text, "the page's force line changed");
    let v = solve(&saved(&dir, "planar.toml", &planar));
    let stage = body(&v, "stage");
    quoted("gives the planar answer,", &[f(&stage["x"])]);

    // The page says stage3d.toml is stage.toml with these changes: check that it is.
    let converted = block("stage.toml")
        .replace(
            "origin = [0.0, 0.0, 1.5707963267948966]    # x, y, phi: turned 90°, so x points up",
            "rpy_deg = [0.0, 0.0, 90.0]",
        )
        .replace(
            "origin = [0.04, 0.0, 1.5707963267948966]   # 40 mm to the right, also upright",
            "origin = [0.04, 0.0, 0.0]\nrpy_deg = [0.0, 0.0, 90.0]",
        );
    let words = |t: &str| -> Vec<String> {
        t.lines()
            .map(|l| l.split('#').next().unwrap().trim().to_string())
            .filter(|l| !l.is_empty() && !l.starts_with("at =") && !l.starts_with("force =") && l != "dimension = 3")
            .collect()
    };
    assert_eq!(words(&converted), words(&text));
}

/// mechanism-format.md: a spatial flexure's rest coefficients are angles. Each
/// component's curvature is its series over L (Eq. 8), and every Legendre term
/// but the first integrates to zero, so `[0.5, 0.0, 0.0]` alone turns the tip
/// by 0.5 rad about its axis, whatever the length (to rounding: 1e-12).
#[test]
fn spatial_rest_coefficients_are_angles() {
    let dir = tempfile::tempdir().unwrap();
    for (key, axis) in [("twist", 0), ("kappa_y", 1), ("kappa_z", 2), ("kappa", 2)] {
        for length in [0.05, 2.0] {
            let text = format!(
                "dimension = 3\n[[joint]]\nname = \"blade\"\nkind = \"flexure\"\nparent = \"ground\"\n\
                 child = \"tip\"\nlength = {length}\nei = 0.01\n{key} = [0.5, 0.0, 0.0]\n"
            );
            let v = solve(&saved(&dir, "rest.toml", &text));
            let (_, rpy) = placement(body(&v, "tip"));
            for i in 0..3 {
                let expected = if i == axis { 0.5 } else { 0.0 };
                assert!((f(&rpy[i]) - expected).abs() < 1e-12, "{key} over {length} m: rpy {rpy}");
            }
        }
    }
}
