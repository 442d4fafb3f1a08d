//! Non-uniform sections on the command line (issue 11): tapers and notches
//! from `--width`, `--thickness`, `--ei` and `--notch`; the peak bending
//! stress, the safety factor and its warning, `--shape`; mechanism files'
//! section keys through `solve`; and bad input exiting with status 2.
//! Run in-process through `flexure_cli::run`.

use serde_json::Value;

use crate::cli::run;

/// The answer to `args --json` (exit 0), and its stderr.
fn answer(args: &[&str]) -> (Value, String) {
    let mut a = args.to_vec();
    a.push("--json");
    let (code, out, err) = run(&a);
    assert_eq!(code, 0, "{args:?}: {err}");
    (serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: {e}: {out}")), err)
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// A steel strip 50 mm long and 10 mm wide, its thickness tapering linearly
/// from 0.4 mm at the root to 0.1 mm at the tip, under a tip force F across it.
const TAPER: [&str; 8] = ["--length", "0.05", "--modulus", "200e9", "--width", "0.01", "--thickness", "4e-4,1e-4"];

/// Beam theory (Euler–Bernoulli, small deflection; e.g. Timoshenko & Gere,
/// Mechanics of Materials, §5): M(s) = F(L − s), so σ(s) = 6F(L − s)/(b h(s)²).
/// With h = h₀(1 − ¾ t) it peaks inside the flexure, at t = 2/3, at 4/3 of
/// the root's 6FL/(b h₀²). F = 5e-5 N turns the tip by 2.3e-5 rad, so the
/// large-deflection terms are (2.3e-5)² ≈ 5e-10 of the stress; order 32
/// resolves the curvature of an EI falling 64-fold to 6e-12 (measured:
/// 2e-5 at order 12, 1e-6 at 20, 2e-8 at 24). Tolerance 1e-8 of the root
/// stress; the peak's place, at a flat maximum, to 1e-5 L.
#[test]
fn tapered_cantilever_stress_is_beam_theory() {
    let (force, l, b, h0) = (5e-5, 0.05, 0.01, 4e-4);
    let mut args = vec!["deflect"];
    args.extend(TAPER);
    args.extend(["--force", "5e-5", "--order", "32", "--shape", "21"]);
    let (v, err) = answer(&args);
    assert!(err.is_empty(), "{err}");
    let h = |s: f64| h0 * (1.0 - 0.75 * s / l);
    let sigma = |s: f64| 6.0 * force * (l - s) / (b * h(s) * h(s));
    let root = sigma(0.0);
    assert!((f(&v["stress"]["max"]) / (4.0 / 3.0 * root) - 1.0).abs() < 1e-8, "{}", v["stress"]);
    assert!((f(&v["stress"]["at"]) - 2.0 / 3.0 * l).abs() < 1e-5 * l, "{}", v["stress"]);
    let shape = v["shape"].as_array().unwrap();
    assert_eq!(shape.len(), 21);
    for p in shape {
        let s = f(&p["s"]);
        assert!((f(&p["stress"]) - sigma(s)).abs() < 1e-8 * root, "s = {s}: {p}");
    }
    assert!(v.get("curvature_max").is_none() && v.get("safety_factor").is_none());
}

/// Paros & Weisbord (1965, "How to design flexure hinges", Machine Design
/// 37): a circular notch of radius R leaving h, cut through a blank h + 2R
/// thick over L = 2R, turns by Δφ/M = 3/(2EbR²) · 1/(2β+β²) ·
/// [(3+4β+2β²)/((1+β)(2β+β²)) + 6(1+β)/(2β+β²)^{3/2} · atan √((2+β)/β)],
/// β = h/(2R): the exact ∫ds/EI. `--notch` raises the blank's L/(EI) by
/// that much; the model, a Ritz reduction, stays below the closed form and
/// reaches it as the order rises (measured through this command: 2.7e-2 at
/// order 16, 7e-4 at 24, 1.2e-5 at 32). Symmetry about the middle gives
/// C_φy = ∫(L − s)/EI ds = (L/2)·C_φφ, to the same order error.
#[test]
fn notch_compliance_is_paros_weisbord() {
    let (e, b, r, h) = (70e9_f64, 0.01, 0.005, 5e-4);
    let beta = h / (2.0 * r);
    let q = 2.0 * beta + beta * beta;
    let closed = 3.0 / (2.0 * e * b * r * r) / q
        * ((3.0 + 4.0 * beta + 2.0 * beta * beta) / ((1.0 + beta) * q)
            + 6.0 * (1.0 + beta) / q.powf(1.5) * ((2.0 + beta) / beta).sqrt().atan());
    let blank = ["compliance", "--length", "0.01", "--modulus", "70e9", "--width", "0.01", "--thickness", "0.0105"];
    // The blank alone, 10.5 mm thick over 10 mm, is no flexure: refused, naming the thickness
    // and the length. Cut into a hinge it is held to its 0.5 mm neck.
    let (code, _, err) = run(&blank);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--thickness = 0.0105 m") && err.contains("length 0.01 m"), "{err}");
    let mut last = 1.0;
    for (order, tolerance) in [("16", 3e-2), ("24", 1e-3), ("32", 2e-5)] {
        let mut args = blank.to_vec();
        args.extend(["--notch", "0.005,5e-4", "--order", order]);
        let c = answer(&args).0["compliance"].clone();
        let (phi, phi_y) = (f(&c[0][0]), f(&c[0][2]));
        let error = (closed - phi) / closed;
        assert!(error > -1e-12 && error < tolerance && error < last, "order {order}: {error:e}");
        assert!((phi_y / (r * phi) - 1.0).abs() < 1e-9, "order {order}: {phi_y} vs {}", r * phi);
        last = error;
    }
}

/// A uniform strip bent by a tip moment M into an arc (exact for the model):
/// σ = 6M/(b h²) all along. With `--yield-strength S` the safety factor is
/// S/σ; below 1 a warning on stderr names the yield strength, and the
/// answer is still given (exit 0).
#[test]
fn safety_factor_and_its_warning() {
    let (m, b, h) = (0.02, 0.01, 2e-4);
    let sigma = 6.0 * m / (b * h * h);
    let strip = ["deflect", "--length", "0.02", "--modulus", "200e9", "--width", "0.01", "--thickness", "2e-4"];
    for (strength, warned) in [("1e9", false), ("2e8", true)] {
        let mut args = strip.to_vec();
        args.extend(["--moment", "0.02", "--yield-strength", strength]);
        let (v, err) = answer(&args);
        assert!((f(&v["stress"]["max"]) / sigma - 1.0).abs() < 1e-12, "{}", v["stress"]);
        let s: f64 = strength.parse().unwrap();
        assert!((f(&v["safety_factor"]) - s / sigma).abs() < 1e-12 * s / sigma);
        assert_eq!(err.contains("warning:") && err.contains("yield strength 2e8 Pa"), warned, "{err}");
        assert_eq!(err.lines().count(), usize::from(warned), "{err}");
    }
    // Unstressed: no safety factor (it would be infinite), no warning.
    let mut args = strip.to_vec();
    args.extend(["--yield-strength", "2e8"]);
    let (v, err) = answer(&args);
    assert!(v.get("safety_factor").is_none() && f(&v["stress"]["max"]) == 0.0 && err.is_empty(), "{v} {err}");
    // tendon and connect report the same keys.
    let mut args = strip.to_vec();
    args[0] = "tendon";
    args.extend(["--force", "5", "--root-offset", "0.002", "--tip-offset", "0.002", "--yield-strength", "1e8"]);
    let (v, err) = answer(&args);
    assert!(f(&v["safety_factor"]) < 1.0 && err.contains("tendon at 5 N") && err.contains("1e8 Pa"), "{v} {err}");
    let mut args = strip.to_vec();
    args[0] = "connect";
    args.extend(["--pose", "0.5,0.019,0.005", "--yield-strength", "1e9", "--shape", "3"]);
    let (v, _) = answer(&args);
    assert!(f(&v["safety_factor"]) > 0.0 && v["shape"].as_array().unwrap().len() == 3, "{v}");
}

/// `--shape K`: K points, the first at the root (s = 0, the origin, φ = 0
/// when straight at rest), the last at the tip (s = L, the reported pose),
/// evenly spaced, every number finite; `curvature` is the total curvature,
/// so a rest shape shows in it; `stress` only with a thickness.
#[test]
fn shape_points() {
    for (extra, stressed) in [(&["--ei", "0.002,0.001"][..], false), (&TAPER[2..], true)] {
        for k in ["2", "7"] {
            let mut args = vec!["deflect", "--length", "0.05", "--force", "0.01", "--angle", "20deg", "--shape", k];
            args.extend(extra);
            let (v, _) = answer(&args);
            let shape = v["shape"].as_array().unwrap();
            let k: usize = k.parse().unwrap();
            assert_eq!(shape.len(), k);
            let (first, last) = (&shape[0], &shape[k - 1]);
            assert!(f(&first["s"]) == 0.0 && f(&first["x"]) == 0.0 && f(&first["y"]) == 0.0 && f(&first["phi"]) == 0.0);
            assert_eq!(f(&last["s"]), 0.05);
            for key in ["x", "y", "phi"] {
                assert!((f(&last[key]) - f(&v["pose"][key])).abs() < 1e-12, "{key}: {last} vs {}", v["pose"]);
            }
            for (i, p) in shape.iter().enumerate() {
                assert!((f(&p["s"]) - 0.05 * i as f64 / (k - 1) as f64).abs() < 1e-15);
                assert!(["x", "y", "phi", "curvature"].iter().all(|key| f(&p[key]).is_finite()));
                assert_eq!(p.get("stress").is_some(), stressed, "{p}");
            }
            assert_eq!(v.get("stress").is_some(), stressed);
            assert_eq!(v.get("curvature_max").is_some(), !stressed);
        }
    }
    // κ = 2 (1/m) at rest over 0.05 m: curvature 2 + its change, which is 0 unloaded.
    let (v, _) = answer(&["deflect", "--length", "0.05", "--kappa", "0.1,0,0", "--shape", "3"]);
    assert!(v["shape"].as_array().unwrap().iter().all(|p| (f(&p["curvature"]) - 2.0).abs() < 1e-12), "{v}");
    assert_eq!(f(&v["curvature_max"]["max"]), 0.0);
}

/// With `--exact` the exact elastica's stress, safety factor and shape sit
/// at the top level and the model's under `model`. On the tapered strip
/// under a small force the exact stress is beam theory's (as in
/// `tapered_cantilever_stress_is_beam_theory`: 4/3 of the root's 6FL/(bh₀²)
/// at t = 2/3, large-deflection terms 5e-10; the shooting tolerance 1e-10),
/// at any order of the model: tolerance 1e-8, the peak's place 1e-3 L (a
/// flat maximum, found by golden section on the exact stress).
#[test]
fn exact_stress_sits_at_the_top_level() {
    let (force, l, b, h0) = (5e-5, 0.05, 0.01, 4e-4);
    let mut args = vec!["deflect"];
    args.extend(TAPER);
    // The model's own peak (order 3) is 6.5 % off and would be flagged; not what is tested here.
    args.extend([
        "--force",
        "5e-5",
        "--exact",
        "--shape",
        "6",
        "--yield-strength",
        "1e9",
        "--accuracy",
        "0.01,1deg,0.1",
    ]);
    let (v, err) = answer(&args);
    assert!(err.is_empty(), "{err}");
    let h = |s: f64| h0 * (1.0 - 0.75 * s / l);
    let sigma = |s: f64| 6.0 * force * (l - s) / (b * h(s) * h(s));
    let root = sigma(0.0);
    assert!((f(&v["stress"]["max"]) / (4.0 / 3.0 * root) - 1.0).abs() < 1e-8, "{}", v["stress"]);
    assert!((f(&v["stress"]["at"]) - 2.0 / 3.0 * l).abs() < 1e-3 * l, "{}", v["stress"]);
    assert!((f(&v["safety_factor"]) - 1e9 / f(&v["stress"]["max"])).abs() < 1e-6);
    let shape = v["shape"].as_array().unwrap();
    assert_eq!(shape.len(), 6);
    for p in shape {
        let s = f(&p["s"]);
        assert!((f(&p["stress"]) - sigma(s)).abs() < 1e-8 * root, "s = {s}: {p}");
    }
    assert_eq!(f(&shape[5]["s"]), l);
    assert!((f(&shape[5]["x"]) - f(&v["pose"]["x"])).abs() < 1e-12);
    assert!(v["model"]["stress"]["max"].is_number() && v["model"]["shape"].as_array().unwrap().len() == 6);
    assert!(v["model"]["safety_factor"].is_number());
}

/// `--exact` takes EI(s): the compliance ODE against the closed forms of a
/// linear EI taper, EI = a + cs: C_φφ = ln(b/a)/c, C_φy = b ln(b/a)/c² − L/c,
/// C_yy = [b² ln(b/a) − 2b(b − a) + (b² − a²)/2]/c³ (1e-10 relative); the
/// exact buckling load of the tapered strip is the limit the model's
/// Rayleigh–Ritz loads fall onto (order 32 within 1e-10); and connect's
/// exact answer has its stress at the top level, η ≥ 0 (Eq. 16).
#[test]
fn exact_references_take_the_section() {
    let (l, a, b): (f64, f64, f64) = (0.5, 2.0, 0.5);
    let (v, _) = answer(&["compliance", "--length", "0.5", "--ei", "2,0.5", "--exact"]);
    let c = (b - a) / l;
    let log = (b / a).ln();
    let closed = [
        (0, 0, log / c),
        (0, 2, b * log / (c * c) - l / c),
        (2, 2, (b * b * log - 2.0 * b * (b - a) + 0.5 * (b * b - a * a)) / c.powi(3)),
    ];
    for (i, j, want) in closed {
        let got = f(&v["compliance"][i][j]);
        assert!((got / want - 1.0).abs() < 1e-10, "C[{i}][{j}] {got} vs {want}");
    }
    for tip in ["free", "guided", "pinned", "clamped"] {
        let mut args = vec!["buckling", "--tip", tip];
        args.extend(TAPER);
        let exact = f(&answer(&[&args[..], &["--exact"]].concat()).0["critical_load"]);
        let model = f(&answer(&[&args[..], &["--order", "32"]].concat()).0["critical_load"]);
        assert!(model >= exact * (1.0 - 1e-12) && model / exact - 1.0 < 1e-10, "{tip}: {model} vs {exact}");
    }
    let mut args = vec!["connect", "--pose", "1,0.035,0.025", "--exact", "--shape", "3"];
    args.extend(TAPER);
    let (v, _) = answer(&args);
    assert!(f(&v["eta"]) >= 0.0 && f(&v["stress"]["max"]) > 0.0 && v["model"]["stress"]["max"].is_number());
    assert_eq!(v["shape"].as_array().unwrap().len(), 3);
    let mut args = vec!["connect", "--pose", "1,0.035,0.025", "--order", "12"];
    args.extend(TAPER);
    let (v, _) = answer(&args);
    assert!(f(&v["eta"]) >= 0.0, "η against the exact connection with EI(s): {}", v["eta"]);
}

/// A tapered `--ei` is a section without a thickness: `curvature_max`, the
/// largest change of curvature from rest. For EI falling linearly from 2E to
/// E under a tip moment M, κ = M/EI(s) peaks at the tip, M/E.
#[test]
fn tapered_ei_reports_curvature() {
    let (v, _) = answer(&["deflect", "--length", "0.05", "--ei", "0.002,0.001", "--moment", "1e-4", "--order", "24"]);
    // M/EI(s) = 0.1/(2 − t): order 24 resolves it to ~1e-12; the small
    // moment (tip angle 3.5e-3 rad) does not change a pure moment's κ.
    assert!((f(&v["curvature_max"]["max"]) - 0.1).abs() < 1e-9, "{}", v["curvature_max"]);
    assert!((f(&v["curvature_max"]["at"]) - 0.05).abs() < 1e-9);
}

/// Bad sections exit 2, print nothing on stdout, and name the option.
#[test]
fn bad_sections_name_the_option() {
    let rect = |w: &'static str, h: &'static str| {
        vec!["deflect", "--force", "1", "--modulus", "70e9", "--width", w, "--thickness", h]
    };
    let with = |mut base: Vec<&'static str>, extra: &[&'static str]| {
        base.extend(extra);
        base
    };
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (rect("0", "0.004"), "--width"),
        (rect("-0.01", "0.004"), "--width"),
        (rect("0.01,0", "0.004"), "--width"),
        (rect("0.01", "0.004,-0.001"), "--thickness"),
        (rect("0.01", "0.004,nan"), "--thickness"),
        (rect("0.01", "inf"), "--thickness"),
        (rect("0.01,0.01,0.01", "0.004"), "--width"),
        (rect("0.01", "0.004,"), "--thickness"),
        (vec!["deflect", "--force", "1", "--ei", "0,1"], "--ei"),
        (vec!["deflect", "--force", "1", "--ei", "1,-1"], "--ei"),
        (vec!["deflect", "--force", "1", "--ei", "1,nan"], "--ei"),
        (with(rect("0.01", "0.004"), &["--notch", "0.005,0.004"]), "--notch H"),
        (with(rect("0.01", "0.004"), &["--notch", "0.005,0.006"]), "--notch H"),
        (with(rect("0.01", "0.004"), &["--notch", "0,0.001"]), "--notch R"),
        (with(rect("0.01", "0.004"), &["--notch", "0.005,-0.001"]), "--notch H"),
        (with(rect("0.01", "0.004"), &["--notch", "0.001,0.0001"]), "--notch R"),
        (with(rect("0.01", "0.004"), &["--notch", "0.005"]), "--notch"),
        (with(rect("0.01", "0.004"), &["--notch", "nan,0.001"]), "--notch"),
        (vec!["deflect", "--force", "1", "--notch", "0.005,0.001"], "--modulus"),
        (with(rect("0.01", "0.004"), &["--density", "-7850"]), "--density"),
        (with(rect("0.01", "0.004"), &["--density", "nan"]), "--density"),
        (vec!["deflect", "--force", "1", "--ei", "1", "--density", "7850"], "--density"),
        (with(rect("0.01", "0.004"), &["--mass-per-length", "0"]), "--mass-per-length"),
        (with(rect("0.01", "0.004"), &["--mass-per-length", "0.1,-0.1"]), "--mass-per-length"),
        (with(rect("0.01", "0.004"), &["--density", "7850", "--mass-per-length", "0.1"]), "--density"),
        (with(rect("0.01", "0.004"), &["--yield-strength", "0"]), "--yield-strength"),
        (with(rect("0.01", "0.004"), &["--yield-strength", "-1e8"]), "--yield-strength"),
        (with(rect("0.01", "0.004"), &["--yield-strength", "inf"]), "--yield-strength"),
        (vec!["deflect", "--force", "1", "--yield-strength", "1e8"], "--yield-strength"),
        (
            vec!["tendon", "--tension", "1", "--root-offset", "0", "--tip-offset", "0.01", "--yield-strength", "1e8"],
            "--yield-strength",
        ),
        (vec!["connect", "--pose", "0.5,0.9,0.2", "--yield-strength", "1e8"], "--yield-strength"),
        (vec!["deflect", "--force", "1", "--shape", "1"], "--shape"),
        (vec!["deflect", "--force", "1", "--shape", "10001"], "--shape"),
        (vec!["deflect", "--force", "1", "--shape", "18446744073709551616"], "--shape"),
        (vec!["deflect", "--force", "1", "--shape", "2.5"], "--shape"),
    ];
    for (args, option) in &cases {
        for json in [false, true] {
            let mut a = args.clone();
            if json {
                a.push("--json");
            }
            let (code, out, err) = run(&a);
            assert_eq!(code, 2, "{a:?}: {out}{err}");
            assert!(out.is_empty(), "{a:?}: {out}");
            assert!(err.contains(option), "{a:?}: stderr must name {option}: {err}");
        }
    }
    // Valid forms of the same options answer.
    for extra in [&["--notch", "0.005,0.001"][..], &["--density", "2700"], &["--mass-per-length", "0.1,0.05"]] {
        let (code, _, err) = run(&with(rect("0.01,0.008", "0.004"), extra));
        assert_eq!(code, 0, "{extra:?}: {err}");
    }
}

fn tapered_finger() -> String {
    concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/tapered_finger.toml").to_string()
}

/// `solve` reports each flexure joint's peak stress, its safety factor and
/// the shape the file asks for. The notch's stress peaks at its waist, the
/// middle, 5 mm along (order 24 places it there to 0.1 mm), below 6M/(b h²)
/// at the waist for M the most the loads can put on it: the tendon's 4 N at
/// 4 mm plus the 0.3 N tip force at most 30 mm away.
#[test]
fn solve_reports_stress_per_flexure_joint() {
    let file = tapered_finger();
    let (v, err) = answer(&["solve", &file]);
    assert!(err.is_empty(), "{err}");
    for joint in ["knuckle", "notch"] {
        let s = &v["stress"][joint];
        assert!(f(&s["max"]) > 0.0 && f(&v["safety_factor"][joint]) > 1.0, "{joint}: {v}");
    }
    assert!((f(&v["stress"]["notch"]["at"]) - 0.005).abs() < 1e-4, "{}", v["stress"]["notch"]);
    let shape = v["shape"]["notch"].as_array().unwrap();
    assert_eq!(shape.len(), 5);
    assert!(v["shape"].get("knuckle").is_none() && v.get("curvature_max").is_none());
    let bound = 6.0 * (4.0 * 0.004 + 0.3 * 0.03) / (0.008 * 6e-4 * 6e-4);
    assert!(f(&v["stress"]["notch"]["max"]) < bound, "{} vs {bound}", v["stress"]["notch"]);

    // Stressed past a low yield strength: a warning naming it, per joint; the answer is still given.
    let text = std::fs::read_to_string(&file).unwrap().replace("yield_strength = 2.5e8", "yield_strength = 1e6");
    let dir = tempfile::tempdir().unwrap();
    let weak = dir.path().join("weak.toml");
    std::fs::write(&weak, text).unwrap();
    let weak = weak.display().to_string();
    let (v, err) = answer(&["solve", &weak]);
    assert!(f(&v["safety_factor"]["notch"]) < 1.0, "{v}");
    assert!(err.contains("flexure joint \"notch\"") && err.contains("yield strength 1e6 Pa"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    // A sweep: a stress column per flexure joint with a thickness, and the warning once.
    let (v, err) = answer(&["solve", &weak, "--sweep", "tendon.flexor.tension=0:8:3"]);
    let columns: Vec<&str> = v["columns"].as_array().unwrap().iter().map(|c| c.as_str().unwrap()).collect();
    assert!(columns.ends_with(&["energy", "knuckle.stress", "notch.stress"]), "{columns:?}");
    assert!(err.contains("notch.stress") && err.lines().count() == 1, "{err}");

    // A joint given by ei reports curvature_max.
    let finger = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/finger.toml");
    let (v, _) = answer(&["solve", finger]);
    assert!(v.get("stress").is_none() && f(&v["curvature_max"]["mcp"]["max"]) > 0.0, "{v}");
}

/// `draw` colours flexures with a thickness by stress under a colour bar
/// in MPa, topped at the largest stress `solve` reports or, past it, at 1.05
/// times the highest yield strength (the file's 1.2e9 Pa and 2.5e8 Pa),
/// which the bar marks with a line per yield strength and names in its label;
/// a mechanism without thickness draws as before, without a bar.
#[test]
fn draw_has_a_stress_colour_bar() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("finger.svg");
    let out_s = out.display().to_string();
    let (v, _) = answer(&["draw", &tapered_finger(), "--out", &out_s]);
    assert_eq!(v["shapes"], 2);
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("bending stress (MPa)") && svg.contains("linearGradient"), "no colour bar");
    let solved = answer(&["solve", &tapered_finger()]).0;
    let top =
        (f(&solved["stress"]["knuckle"]["max"]).max(f(&solved["stress"]["notch"]["max"])) / 1e6).max(1.05 * 1200.0);
    assert!(
        svg.contains("black line: yield strength (knuckle 1200 MPa, notch 250 MPa)"),
        "no yield in the bar's label"
    );
    // The bar's two yield marks: black lines 2.5 px wide, beside the ticks' 1.2.
    assert_eq!(svg.matches(r##"stroke="#000000" stroke-width="2.5""##).count(), 2, "yield marks");
    // The bar's last tick is a round value not above the largest stress.
    let ticks: Vec<f64> = svg
        .lines()
        .filter(|l| l.contains(r#"class="bar-tick""#))
        .map(|l| l.split('>').nth(1).unwrap().split('<').next().unwrap().parse().unwrap())
        .collect();
    assert!(ticks.len() >= 3 && ticks[0] == 0.0, "{ticks:?}");
    assert!(*ticks.last().unwrap() <= top && *ticks.last().unwrap() > 0.5 * top, "{ticks:?} vs {top}");
    let plain = dir.path().join("plain.svg");
    let plain_s = plain.display().to_string();
    answer(&["draw", concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/finger.toml"), "--out", &plain_s]);
    assert!(!std::fs::read_to_string(&plain).unwrap().contains("linearGradient"));
}
