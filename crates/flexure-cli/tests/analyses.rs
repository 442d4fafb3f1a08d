//! The CLI contract of connect and tendon: keys, reference values, bad input.

use serde_json::Value;
use std::process::Command;

fn run(args: &str) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_flexure")).args(args.split_whitespace()).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn json(args: &str) -> Value {
    let (code, out, err) = run(&format!("{args} --json"));
    assert_eq!(code, 0, "{args}: {err}");
    serde_json::from_str(&out).unwrap()
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// An arc of angle 1.2 (L = EI = 1): every method reaches it with U = a²/2
/// and the pure moment a at the root (closed form).
#[test]
fn connect_an_arc() {
    let a = 1.2_f64;
    let pose = format!("{a},{},{}", a.sin() / a, (1.0 - a.cos()) / a);
    let model = json(&format!("connect --pose {pose}"));
    assert_eq!(model["alpha"].as_array().unwrap().len(), 3);
    assert!((f(&model["energy"]) - a * a / 2.0).abs() < 1e-10);
    let exact = json(&format!("connect --pose {pose} --exact"));
    assert!((f(&exact["energy"]) - a * a / 2.0).abs() < 1e-10);
    assert!((f(&exact["loads"]["moment"]) - a).abs() < 1e-8 && f(&exact["loads"]["fx"]).abs() < 1e-8);
    let chain = json(&format!("connect --pose {pose} --segments 4"));
    let k = chain["curvatures"].as_array().unwrap();
    assert_eq!(k.len(), 4);
    assert!(k.iter().all(|c| (f(c) - a).abs() < 1e-8), "constant curvature a/L");
    let order5 = json(&format!("connect --pose {pose} --order 5"));
    assert_eq!(order5["alpha"].as_array().unwrap().len(), 5);
}

/// η ≥ 0 (Eq. 16: the elastica has the least energy) and the chain's energy
/// lies above the exact one.
#[test]
fn connect_energy_ordering() {
    let exact = json("connect --pose 90deg,0.55,0.65 --exact");
    let model = json("connect --pose 90deg,0.55,0.65");
    let chain = json("connect --pose 90deg,0.55,0.65 --segments 22");
    assert!(f(&model["energy"]) > f(&exact["energy"]) && f(&chain["energy"]) > f(&exact["energy"]));
    assert!((f(&model["eta"]) - (f(&model["energy"]) / f(&exact["energy"]) - 1.0)).abs() < 1e-12);
}

/// Fig. 10: about 28 N turns the paper's steel flexure (Eq. 25, 5 mm offsets) to 90°.
#[test]
fn tendon_paper_joint() {
    let steel = "--length 0.015 --modulus 200e9 --width 0.01 --thickness 0.0002 --poisson 0.29";
    let v = json(&format!("tendon {steel} --tension 28 --root-offset 0.005 --tip-offset 0.005"));
    assert!((f(&v["pose"]["phi"]).to_degrees() - 90.0).abs() < 2.0, "{}", f(&v["pose"]["phi"]).to_degrees());
    assert!(f(&v["tendon_length"]) < 0.015, "tension shortens the tendon");
    let s = json(&format!("tendon {steel} --sweep 0:40:9 --root-offset 0.005 --tip-offset 0.005"));
    let rows = s["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 9);
    assert_eq!(f(&rows[0]["tension"]), 0.0);
    let angles: Vec<f64> = rows.iter().map(|r| f(&r["pose"]["phi"])).collect();
    assert!(angles.windows(2).all(|w| w[1] > w[0]), "rotation grows with tension");
    for key in ["alpha", "pose", "tendon_length"] {
        assert!(rows[3].get(key).is_some(), "{key}");
    }
}

#[test]
fn bad_input_exits_2() {
    for (args, option) in [
        ("connect --pose 0,0.9,0.5", "--pose"),
        ("connect --pose 0,1,0", "--pose"),
        ("connect --pose 1,0.5", "--pose"),
        ("connect --pose 1,0.5,0.5 --segments 0", "--segments"),
        ("connect --pose 1,0.5,0.5 --segments 5 --kappa 1,0,0", "--kappa"),
        ("tendon --tension -1 --root-offset 0 --tip-offset 0", "--tension"),
        ("tendon --sweep 0:1:1 --root-offset 0 --tip-offset 0", "--sweep"),
        ("tendon --sweep -1:1:3 --root-offset 0 --tip-offset 0", "--sweep"),
        ("tendon --tension 1 --root-offset nan --tip-offset 0", "--root-offset"),
    ] {
        let (code, out, err) = run(&format!("{args} --json"));
        assert_eq!(code, 2, "{args}");
        assert!(err.contains(option) && !err.contains("panicked"), "{args}: {err}");
        assert!(out.is_empty());
    }
}

/// The exact connection of a curved flexure does not depend on the model's
/// order: the exact elastica reaching the pose is one and the same shape,
/// seeded by the order-3 model with the same rest curvature (its first
/// three coefficients). Energies agree to the shooting tolerance (1e-9).
#[test]
fn exact_connection_of_a_curved_flexure_is_the_same_at_any_order() {
    // Order 5 with five rest coefficients, and order 7 with the same five and two zeros.
    let energy = |kappa: &str, order: usize| {
        f(&json(&format!("connect --pose 1.2,0.6,0.6 --kappa {kappa} --order {order} --exact"))["energy"])
    };
    let (five, seven) = (energy("0.5,0.2,0.1,0.05,0.02", 5), energy("0.5,0.2,0.1,0.05,0.02,0,0", 7));
    assert!((five - seven).abs() < 1e-9 * five, "{five} vs {seven}");
}

/// `--limit` answers with one `stability_limit` on loads where it used to
/// fail (issue 20: `deflect --moment 1 --fx 0.5 --fy 0.3 --limit` and
/// `--moment 2 --limit` exited 2 with a stalled probe), and never with the
/// path's own cruder `limit_fraction` beside it.
#[test]
fn limit_answers_once_on_ordinary_loads() {
    for load in ["--moment 1 --fx 0.5 --fy 0.3", "--moment 2", "--moment 0.2 --fx -1", "--fx -1 --fy 0.3"] {
        let v = json(&format!("deflect {load} --limit"));
        assert!(v.get("limit_fraction").is_none(), "{load}: {v}");
        let status = v["stability_limit"]["status"].as_str();
        assert!(status == Some("lost") || status == Some("stable_up_to"), "{load}: {v}");
        assert!(v["stability_limit"]["factor"].as_f64().is_some(), "{load}: {v}");
    }
    // A pure moment of 2 is followed, stable, to 734 times itself (the
    // continuation's 1000 steps), said on stderr as a bound, not an instability.
    let (code, out, err) = run("deflect --moment 2 --limit --json");
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    let bound = v["stability_limit"]["factor"].as_f64().unwrap();
    assert!(bound > 1.0 && bound < 1000.0, "{v}");
    assert_eq!(v["stability_limit"]["status"], "stable_up_to");
    assert!(v["stability_limit"]["stalled"].as_str().is_some_and(|why| !why.is_empty()), "{v}");
    assert!(err.contains("as far as it could be followed") && !err.contains("max_steps"), "{err}");
}

/// `tendon --limit` and `connect --limit` answer as `deflect --limit` does.
/// The crossing tendon stays stable up to 22.893 N, where its tip
/// attachment meets its root attachment and the path ends (its mirror
/// image, root offset −0.1 and tip offset 0.05, at the same tension; it was
/// reported lost there, from a corrector that had jumped, issue 39);
/// `connect`'s limit is `deflect --limit` under the load that holds the pose.
#[test]
fn tendon_and_connect_limits() {
    let a = json("tendon --tension 1 --root-offset 0.1 --tip-offset -0.05 --limit");
    let b = json("tendon --tension 1 --root-offset -0.1 --tip-offset 0.05 --limit");
    let stable_up_to = || "stable_up_to".into();
    assert_eq!((&a["stability_limit"]["status"], &b["stability_limit"]["status"]), (&stable_up_to(), &stable_up_to()));
    let (a, b) = (a["stability_limit"]["factor"].as_f64().unwrap(), b["stability_limit"]["factor"].as_f64().unwrap());
    assert!((a - 22.893).abs() < 1e-3 && (a / b - 1.0).abs() < 1e-9, "{a} {b}");
    let c = json("connect --pose 0.5,0.9,0.3 --limit");
    let load = &c["load"];
    let d = json(&format!("deflect --moment {} --fx {} --fy {} --limit", load["moment"], load["fx"], load["fy"]));
    assert_eq!(c["stability_limit"]["status"], d["stability_limit"]["status"], "{c} {d}");
    assert_eq!(c["stability_limit"]["factor"].as_f64(), d["stability_limit"]["factor"].as_f64(), "{c} {d}");
}

/// A sweep that stops prints every row it reached, then the failure in its
/// place, and exits 2 (issue 20: `tendon --sweep 0:20:5 --root-offset 0.1
/// --tip-offset 0.1` printed nothing). At 20 N this tendon pulls the tip
/// onto the root, where the continuation stalls; 0 to 15 N solve.
#[test]
fn a_stopped_tendon_sweep_keeps_its_rows() {
    let (code, out, err) = run("tendon --sweep 0:20:5 --root-offset 0.1 --tip-offset 0.1 --json");
    assert_eq!(code, 2, "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    let tensions: Vec<f64> = v["rows"].as_array().unwrap().iter().map(|r| r["tension"].as_f64().unwrap()).collect();
    assert_eq!(tensions, [0.0, 5.0, 10.0, 15.0]);
    assert_eq!(v["stopped"]["tension"], 20.0);
    assert!(err.contains("error: tendon --sweep: stopped at tension = 20 N after 4 of 5 values"), "{err}");
    // The table form prints the same rows first.
    let (code, out, _) = run("tendon --sweep 0:20:5 --root-offset 0.1 --tip-offset 0.1");
    assert_eq!(code, 2);
    assert!(out.contains("15.000000") && out.contains("stopped:"), "{out}");
}

/// Any unstable answer is said on stderr, as Python warns (issue 20:
/// `deflect --fx -3` printed `stable: false` with exit 0 and no word). The
/// free column buckles at π²/4 ≈ 2.47, so 3 N of compression is past it.
#[test]
fn unstable_answers_warn() {
    let (code, out, err) = run("deflect --fx -3 --json");
    assert_eq!(code, 0);
    assert!(out.contains(r#""stable":false"#), "{out}");
    assert!(err.contains("warning: deflect: the equilibrium is unstable"), "{err}");
    let (_, _, err) = run("deflect --fx -2 --json");
    assert!(!err.contains("unstable"), "{err}");
}

/// `tendon --force` is the old name of `--tension`: the same answer, and a
/// warning naming the new option.
#[test]
fn tendon_force_is_a_deprecated_alias_of_tension() {
    let args = "--root-offset 0.1 --tip-offset 0.05 --json";
    let (code, old, err) = run(&format!("tendon --force 5 {args}"));
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("warning: --force is deprecated for tendon; use --tension"), "{err}");
    let (code, new, err) = run(&format!("tendon --tension 5 {args}"));
    assert!(code == 0 && !err.contains("deprecated"), "{err}");
    assert_eq!(old, new);
    let (code, _, err) = run(&format!("tendon --tension 5 --force 5 {args}"));
    assert_eq!(code, 2, "{err}");
}
