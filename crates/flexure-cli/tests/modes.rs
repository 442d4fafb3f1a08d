//! `flexure modes`, end to end through `flexure_cli::run`, against closed
//! forms of beam vibration: the uniform cantilever's roots of
//! cos βL cosh βL = −1 (βL = 1.87510, 4.69409; f = (βL)²/(2πL²)·√(EI/μ)),
//! a massless cantilever carrying a point mass (ω = √(3EI/(mL³))), and the
//! parallelogram stage's sway (ω = √(2·12EI/(L³m)), softened by 1 − P/P_cr
//! under an axial push); then the refusals of bad input.

use serde_json::Value;
use std::f64::consts::{PI, TAU};

use crate::cli::run;

/// The answer to `modes args --json`, which must exit 0 without a warning.
fn modes(args: &[&str]) -> Value {
    let mut a = vec!["modes"];
    a.extend_from_slice(args);
    a.push("--json");
    let (code, out, err) = run(&a);
    assert!(code == 0 && err.is_empty(), "{a:?}: exit {code}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{a:?}: {e}: {out}"))
}

/// `modes args` must exit 2 with nothing on stdout and every one of `words` on stderr.
fn refused(args: &[&str], words: &[&str]) {
    let mut a = vec!["modes"];
    a.extend_from_slice(args);
    let (code, out, err) = run(&a);
    assert_eq!(code, 2, "{a:?}: {out}");
    assert!(out.is_empty(), "{a:?}: {out}");
    for w in words {
        assert!(err.contains(w), "{a:?}: {w:?} not in {err}");
    }
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

/// The uniform cantilever's first two roots of cos βL cosh βL = −1
/// (Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1).
const BETA_L: [f64; 2] = [1.875_104_068_711_961, 4.694_091_132_974_175];

/// L = 0.5 m, EI = 2 N·m², μ = 0.3 kg/m at order 10: the model's first two
/// frequencies within 1e-6 of f = (βL)²/(2πL²)·√(EI/μ) (the library's
/// convergence test measures the first within 1e-10 from order 8 and the
/// second within 1e-6 at order 10); `--exact` within 1e-9 of the closed form
/// (each root refined to 1e-12 in βL, ODE to its default tolerance), and its
/// `error` is the model's relative error against it.
#[test]
fn distributed_mass_against_the_cantilever_roots() {
    let (l, ei, mu) = (0.5_f64, 2.0_f64, 0.3_f64);
    let v = modes(&[
        "--length",
        "0.5",
        "--ei",
        "2",
        "--mass-per-length",
        "0.3",
        "--order",
        "10",
        "--count",
        "2",
        "--exact",
    ]);
    let (f, w) = (numbers(&v["frequency"]), numbers(&v["omega"]));
    let (exact, relative) = (numbers(&v["exact"]["frequency"]), numbers(&v["error"]["relative"]));
    assert_eq!((f.len(), exact.len(), relative.len()), (2, 2, 2));
    assert_eq!(v["quasi_static"], 0);
    assert!(v.get("note").is_none(), "{v}");
    for k in 0..2 {
        let closed = BETA_L[k].powi(2) / (TAU * l * l) * (ei / mu).sqrt();
        assert!((f[k] / closed - 1.0).abs() < 1e-6, "mode {k}: model {} Hz vs {closed}", f[k]);
        assert!((w[k] - TAU * f[k]).abs() < 1e-12 * w[k], "ω = 2πf");
        assert!((exact[k] / closed - 1.0).abs() < 1e-9, "mode {k}: exact {} Hz vs {closed}", exact[k]);
        assert!((relative[k] - (f[k] / exact[k] - 1.0)).abs() < 1e-12, "error of mode {k}");
    }
    assert!(w[0] < w[1], "ascending");
    // One shape per mode, one amplitude per coordinate.
    let shapes = v["shapes"].as_array().unwrap();
    assert!(shapes.len() == 2 && shapes.iter().all(|s| s.as_array().unwrap().len() == 10));
}

/// A massless cantilever (L = 0.5, EI = 2) carrying m = 0.1 kg at its tip:
/// ω = √(3EI/(mL³)), exact in the model (its tip compliance L³/3EI is exact
/// from order 2), so within 1e-9; the exact beam (`--exact`) agrees to 1e-9.
/// The other coordinates carry no inertia: one finite mode, the rest
/// quasi-static and explained in the note.
#[test]
fn massless_flexure_with_a_tip_mass() {
    let (l, ei, m) = (0.5_f64, 2.0_f64, 0.1_f64);
    let closed = (3.0 * ei / (m * l.powi(3))).sqrt();
    let v = modes(&["--length", "0.5", "--ei", "2", "--tip-mass", "0.1", "--order", "4", "--count", "4", "--exact"]);
    let w = numbers(&v["omega"]);
    assert_eq!(w.len(), 1, "{v}");
    assert!((w[0] / closed - 1.0).abs() < 1e-9, "{} vs {closed}", w[0]);
    assert!((numbers(&v["exact"]["omega"])[0] / closed - 1.0).abs() < 1e-9, "{v}");
    assert_eq!(v["quasi_static"], 3);
    let note = v["note"].as_str().unwrap();
    assert!(note.contains("quasi-statically") && note.contains("1 finite mode"), "{note}");
    // The readable form says the same.
    let (code, out, _) = run(&["modes", "--ei", "2", "--length", "0.5", "--tip-mass", "0.1"]);
    assert!(code == 0 && out.contains("omega") && out.contains("quasi_static"), "{out}");
}

/// `--exact` to mode 30 (L = EI = μ = 1, order 30): the exact ω = (βL)²
/// within 1e-9 of the first four published roots (Blevins, Table 8-1, to
/// 1e-5 in βL, so these are checked against the closed form's bisection in
/// the library's tests; here the two of [`BETA_L`]) and within 1e-6 of
/// ((2n − 1)π/2)² from mode 5 on (the asymptote's own error there is 2e-7);
/// `error.relative` is the model's ω over it less one, never below −1e-9
/// (Rayleigh–Ritz: the model's frequencies lie above the exact ones), and
/// `largest` is the largest of them. The old single shot put modes 13–30
/// below 1420 rad/s, where these are 1542 to 8589.
#[test]
fn exact_frequencies_to_mode_30() {
    let (code, out, _) =
        run(&["modes", "--mass-per-length", "1", "--order", "30", "--count", "30", "--exact", "--json"]);
    assert_eq!(code, 0, "{out}");
    let v: Value = serde_json::from_str(&out).unwrap();
    let (model, exact) = (numbers(&v["omega"]), numbers(&v["exact"]["omega"]));
    let (relative, beta) = (numbers(&v["error"]["relative"]), numbers(&v["exact"]["beta_l"]));
    assert_eq!((model.len(), exact.len(), relative.len(), beta.len()), (30, 30, 30, 30));
    for k in 0..2 {
        assert!((exact[k] / BETA_L[k].powi(2) - 1.0).abs() < 1e-9, "mode {}: {}", k + 1, exact[k]);
    }
    for n in 5..=30 {
        let closed = ((2 * n - 1) as f64 * PI / 2.0).powi(2);
        assert!((exact[n - 1] / closed - 1.0).abs() < 1e-6, "mode {n}: exact ω = {} vs {closed}", exact[n - 1]);
        assert!((beta[n - 1].powi(2) - exact[n - 1]).abs() < 1e-9 * exact[n - 1]);
    }
    for k in 0..30 {
        assert!((relative[k] - (model[k] / exact[k] - 1.0)).abs() < 1e-12, "error of mode {}", k + 1);
        assert!(relative[k] > -1e-9, "mode {}: the model below the exact beam by {:e}", k + 1, relative[k]);
    }
    let largest = relative.iter().fold(0.0_f64, |m, e| m.max(e.abs()));
    assert_eq!(v["error"]["largest"].as_f64().unwrap(), largest);
}

/// A tip body with rotary inertia and an offset centre of mass, and an
/// axial compression of half the exact buckling load π²EI/(4L²): the model
/// (order 8) beside the exact beam, within 1e-5 (the library's check of
/// the same column measures its error below that); tension stiffens it.
#[test]
fn tip_body_under_compression_and_tension() {
    let (l, ei) = (0.5_f64, 2.0_f64);
    let half = 0.5 * PI * PI * ei / (4.0 * l * l);
    let fx = format!("{}", -half);
    let base = ["--length", "0.5", "--ei", "2", "--mass-per-length", "0.3", "--order", "8", "--tip-mass", "0.05"];
    let mut args = base.to_vec();
    args.extend(["--tip-inertia", "1e-4", "--tip-com", "0.01,0", "--fx", &fx, "--exact", "--count", "2"]);
    let v = modes(&args);
    assert!(v["error"]["largest"].as_f64().unwrap() < 1e-5, "{v}");
    let mut args = base.to_vec();
    args.extend(["--count", "1"]);
    let free = numbers(&modes(&args)["omega"])[0];
    let squeezed = numbers(&v["omega"])[0];
    args.extend(["--fx", "5"]);
    let pulled = numbers(&modes(&args)["omega"])[0];
    assert!(squeezed < free && free < pulled, "{squeezed} < {free} < {pulled}");
}

/// `examples/parallelogram.toml` with a 0.1 kg stage (written to a test
/// file): its two flexures are massless, so one finite mode, the sway,
/// ω = √(2·12EI/(L³m)) unloaded (a guided beam's curvature is linear: exact
/// in the model), softened by 1 − 1/16 under the file's 1 N push (its
/// buckling load is 16 N, `buckle`); within 1e-8. Its shape moves both
/// flexures alike.
#[test]
fn parallelogram_stage_sway() {
    let dir = tempfile::tempdir().unwrap();
    let example = format!("{}/../../examples/parallelogram.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(example).unwrap();
    let stage = "\n[[body]]\nname = \"stage\"\nmass = 0.1\ninertia = 2e-5\ncom = [0.0, -0.02]\n";
    let (l, ei, m) = (0.05_f64, 2.0e-3_f64, 0.1_f64);
    let k = 2.0 * 12.0 * ei / l.powi(3);
    for (name, text, factor) in [
        ("loaded.toml", format!("{text}{stage}"), 1.0 - 1.0 / 16.0),
        ("unloaded.toml", format!("{}{stage}", text.replace("force = [0.0, -1.0]", "force = [0.0, 0.0]")), 1.0),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let v = modes(&[path.to_str().unwrap(), "--count", "3"]);
        let w = numbers(&v["omega"]);
        let closed = (k * factor / m).sqrt();
        assert_eq!(w.len(), 1, "{name}: {v}");
        assert!((w[0] / closed - 1.0).abs() < 1e-8, "{name}: {} vs {closed}", w[0]);
        let shape = &v["shapes"][0];
        let (a, b) = (numbers(&shape["left"]), numbers(&shape["right"]));
        assert_eq!(a.len(), 3);
        let big = a.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-8 * big), "{a:?} vs {b:?}");
        assert!(v["note"].as_str().unwrap().contains("quasi-statically"), "{v}");
    }
}

/// Bad input: exit 2, nothing on stdout, the option (or `mass`, or the
/// instability) named on stderr.
#[test]
fn refusals() {
    let dir = tempfile::tempdir().unwrap();
    let example = format!("{}/../../examples/parallelogram.toml", env!("CARGO_MANIFEST_DIR"));
    refused(&["--ei", "2", "--tip-mass", "-1"], &["--tip-mass", "-1"]);
    refused(&["--ei", "2", "--tip-inertia", "-1e-3"], &["--tip-inertia"]);
    refused(&["--ei", "2", "--tip-mass", "1", "--tip-com", "0.1"], &["--tip-com", "X,Y"]);
    refused(&["--ei", "2", "--tip-mass", "1", "--tip-com", "0.1,nan"], &["--tip-com"]);
    refused(&["--ei", "2", "--tip-mass", "1", "--count", "0"], &["--count"]);
    refused(&["--ei", "2", "--tip-mass", "1", "--count", "4"], &["--count = 4", "3 coordinates"]);
    refused(&["--ei", "2", "--tip-mass", "1", "--count", "99999999999999999999"], &["--count"]);
    refused(&["--ei", "2", "--tip-mass", "1", "--order", "auto", "--count", "65"], &["--count = 65", "64"]);
    refused(&["--ei", "2", "--mass-per-length", "-0.3"], &["--mass-per-length"]);
    refused(&["--ei", "2"], &["mass", "--tip-mass"]);
    refused(&["--ei", "2", "--tip-mass", "0", "--tip-inertia", "0"], &["mass"]);
    // Past the buckling load π²EI/(4L²) ≈ 4.93 N the straight flexure is unstable.
    refused(&["--ei", "2", "--tip-mass", "1", "--fx", "-6"], &["unstable"]);
    // --exact covers a straight equilibrium only.
    refused(&["--ei", "2", "--tip-mass", "1", "--fy", "0.1", "--exact"], &["--fy", "--exact"]);
    refused(&["--ei", "2", "--tip-mass", "1", "--moment", "0.1", "--exact"], &["--moment", "--exact"]);
    refused(&["--ei", "2", "--tip-mass", "1", "--force", "1", "--exact"], &["--force", "--exact"]);
    refused(&["--ei", "2", "--tip-mass", "1", "--kappa", "0.1,0,0", "--exact"], &["--kappa", "--exact"]);
    // A file: no single-joint options; the file's own mass is needed.
    refused(&[&example, "--tip-mass", "1"], &["--tip-mass", "mechanism file"]);
    refused(&[&example], &["parallelogram.toml", "mass"]);
    refused(&[&example, "--count", "7"], &["--count = 7", "6 coordinates"]);
    let missing = dir.path().join("missing.toml");
    refused(&[missing.to_str().unwrap()], &["missing.toml"]);
    // A file whose load is past the stage's buckling load of 16 N: its
    // loading path snaps through to a stable state, whose modes come with
    // a warning saying so (stderr, exit 0).
    let text = std::fs::read_to_string(&example).unwrap().replace("force = [0.0, -1.0]", "force = [0.0, -20.0]");
    let path = dir.path().join("buckled.toml");
    std::fs::write(&path, format!("{text}\n[[body]]\nname = \"stage\"\nmass = 0.1\n")).unwrap();
    let (code, out, err) = run(&["modes", path.to_str().unwrap(), "--json"]);
    assert!(code == 0 && err.contains("snapped through") && err.contains("buckled.toml"), "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    assert!((v["limit_fraction"].as_f64().unwrap() - 0.8).abs() < 1e-3, "16 N of 20 N: {v}");
}
