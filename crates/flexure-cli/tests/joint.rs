//! The CLI contract of the core subcommands: JSON keys, numbers checked
//! against independent references, and bad input exiting with status 2.

use serde_json::Value;
use std::process::Command;

pub fn run(args: &str) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_flexure")).args(args.split_whitespace()).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

pub fn json(args: &str) -> Value {
    let (code, out, err) = run(&format!("{args} --json"));
    assert_eq!(code, 0, "{args}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args}: not one JSON object ({e}): {out}"))
}

pub fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

#[test]
fn kinematics_keys_and_arc() {
    let v = json("kinematics --alpha 1,0,0");
    // Circular arc of angle 1: x = sin 1, y = 1 − cos 1 (5-point rule: 1e-9).
    assert!((f(&v["pose"]["x"]) - 1f64.sin()).abs() < 1e-9);
    assert!((f(&v["pose"]["y"]) - (1.0 - 1f64.cos())).abs() < 1e-9);
    assert_eq!(f(&v["pose"]["phi"]), 1.0);
    assert_eq!(v["transform"].as_array().unwrap().len(), 4);
    assert!((f(&v["transform"][0][3]) - 1f64.sin()).abs() < 1e-9, "row-major: [0][3] is x");
    for k in ["phi", "x", "y"] {
        assert_eq!(v["jacobian"][k].as_array().unwrap().len(), 3);
    }
    assert_eq!(v["hessian"]["x"].as_array().unwrap().len(), 3);
    assert!((f(&v["energy"]) - 0.5).abs() < 1e-15, "Eq. 9");
    assert_eq!(v["gradient"].as_array().unwrap().len(), 3);
}

#[test]
fn deflect_model_and_exact() {
    // Bisshopp–Drucker: the exact tip at PL²/EI = 1 across the flexure (±5e-6).
    let v = json("deflect --force 1 --exact");
    assert!((f(&v["pose"]["x"]) - 0.94357).abs() < 5e-6 && (f(&v["pose"]["y"]) - 0.30172).abs() < 5e-6);
    assert!((f(&v["pose"]["phi"]) - 0.46135).abs() < 5e-6);
    // Root moment of a tip force across the flexure: P·x_tip.
    assert!((f(&v["root_moment"]) - f(&v["pose"]["x"])).abs() < 1e-9);
    assert_eq!(v["stable"], Value::Bool(true));
    // A straight column past Euler's π²/4 ≈ 2.47: both say unstable.
    let column = json("deflect --fx -3 --fy 0 --exact");
    assert_eq!(column["stable"], Value::Bool(false));
    assert_eq!(column["model"]["stable"], Value::Bool(false));
    let m = json("deflect --fx 0 --fy 1");
    assert_eq!(m["alpha"].as_array().unwrap().len(), 3);
    assert_eq!(m["stiffness"].as_array().unwrap().len(), 3);
    assert_eq!(m["stable"], Value::Bool(true));
    assert!((f(&m["pose"]["x"]) - 0.94357).abs() < 0.01, "model within 1 % of L");
}

#[test]
fn deflect_angle_in_degrees() {
    let a = json("deflect --force 2 --angle 30deg");
    let b = json(&format!("deflect --force 2 --angle {}", 30f64.to_radians()));
    assert_eq!(a["alpha"], b["alpha"]);
}

#[test]
fn deflect_material_options() {
    // Eq. 25 with the paper's steel flexure; a moment EI·(π/2)/L bends it to 90°.
    let ei = 2e11 / (1.0 - 0.29f64 * 0.29) * 0.01 * 0.0002f64.powi(3) / 12.0;
    let m = ei * std::f64::consts::FRAC_PI_2 / 0.015;
    let v = json(&format!(
        "deflect --length 0.015 --modulus 200e9 --width 0.01 --thickness 0.0002 --poisson 0.29 --moment {m}"
    ));
    assert!((f(&v["pose"]["phi"]) - std::f64::consts::FRAC_PI_2).abs() < 1e-10);
}

#[test]
fn compliance_eq_37() {
    let pi = std::f64::consts::PI;
    let exact = json(&format!("compliance --kappa {pi},0,0 --exact"));
    let model = json(&format!("compliance --kappa {pi},0,0"));
    // Eq. 37 as printed (±5e-5), and the model within Fig. 13's 7.33e-4.
    // 0.3183 is the printed digit string of Eq. 37.
    #[allow(clippy::approx_constant)]
    let printed_01 = -0.3183;
    assert!((f(&exact["compliance"][0][1]) - printed_01).abs() < 5e-5);
    assert!((f(&exact["compliance"][2][2]) - 0.0507).abs() < 5e-5);
    for i in 0..3 {
        for j in 0..3 {
            assert!((f(&exact["compliance"][i][j]) - f(&model["compliance"][i][j])).abs() < 7.34e-4);
        }
    }
}

#[test]
fn buckling_table_i() {
    // Table I (model) and Euler with the errata; loads scale as EI/L².
    let rows =
        [("free", 2.4677, 2.4674), ("guided", 10.0, 9.8696), ("pinned", 20.9187, 20.1907), ("clamped", 42.0, 39.4784)];
    for (tip, model, euler) in rows {
        let v = json(&format!("buckling --tip {tip}"));
        assert!((f(&v["critical_load"]) - model).abs() < 5e-5, "{tip}");
        assert_eq!(v["mode"].as_array().unwrap().len(), 3);
        let e = json(&format!("buckling --tip {tip} --exact --length 2 --ei 3"));
        assert!((f(&e["critical_load"]) - euler * 3.0 / 4.0).abs() < 5e-5, "{tip} Euler");
    }
}

#[test]
fn readable_output_without_json() {
    let (code, out, _) = run("buckling --tip guided");
    assert_eq!(code, 0);
    assert!(out.contains("critical_load") && out.contains("10.000000"), "{out}");
}

/// Every bad input: exit status 2, a message naming the option, no panic.
#[test]
fn bad_input_exits_2_and_names_the_option() {
    let cases = [
        ("deflect --length nan", "--length"),
        ("deflect --moment inf", "--moment"),
        ("deflect --fx nan", "--fx"),
        ("deflect --length -1", "--length"),
        ("deflect --length 0", "--length"),
        ("deflect --ei -2", "--ei"),
        ("deflect --ei 0", "--ei"),
        ("deflect --modulus 2e11 --width 0.01 --thickness -1", "--thickness"),
        ("kinematics --alpha 1,2", "--alpha"),
        ("kinematics --alpha 1,nan,2", "--alpha"),
        ("compliance --kappa 1,2,3,4", "--kappa"),
        ("kinematics --alpha 0 --order 0", "--order"),
        ("kinematics --alpha 0,0,0 --quadrature 0", "--quadrature"),
        ("buckling --tip sideways", "--tip"),
        ("buckling", "--tip"),
        ("deflect --force 1 --fx 2", "--fx"),
        ("deflect --tolerance 0", "--tolerance"),
        ("deflect --tolerance -1", "--tolerance"),
        ("deflect --tolerance 1e-20", "--tolerance"),
    ];
    for (args, option) in cases {
        for args in [args.to_string(), format!("{args} --json")] {
            let (code, out, err) = run(&args);
            assert_eq!(code, 2, "{args}: exit status");
            assert!(err.contains(option), "{args}: stderr must name {option}: {err}");
            assert!(!err.contains("panicked"), "{args}: {err}");
            assert!(out.is_empty(), "{args}: nothing on stdout");
        }
    }
}

/// A solver that cannot reach the answer is reported (status 2, how far it
/// got, the residual), not printed as garbage: a 10¹² N·m moment would turn
/// the tip 10¹² rad, far past what 1000 continuation steps of at most 0.5 rad follow.
#[test]
fn non_convergence_is_reported() {
    let (code, out, err) = run("deflect --moment 1e12 --json");
    assert_eq!(code, 2);
    assert!(err.contains("% of the load") && err.contains("residual"), "{err}");
    assert!(out.is_empty());
}
