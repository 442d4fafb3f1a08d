//! Every model answer carries its error estimate; a flagged one warns, and
//! `--order auto` meets the target. References: the pure moment's circle
//! (closed form) and the paper's 1 % / 1° target. Runs in-process.

use serde_json::Value;

use crate::cli::run;

fn json(args: &[&str]) -> (Value, String) {
    let mut a = args.to_vec();
    a.push("--json");
    let (code, out, err) = run(&a);
    assert_eq!(code, 0, "{args:?}: {err}");
    (serde_json::from_str(&out).unwrap(), err)
}

/// A moment of 20 N·m on L = EI = 1 winds the flexure into a circle of
/// radius 1/20: tip (sin 20, 1 − cos 20)/20. Five points cannot integrate
/// it; the answer is flagged, with a warning, and its estimate is its true
/// error (to the reference's Newton tolerance, 1e-6 relative).
#[test]
fn a_wound_flexure_is_flagged_with_its_true_error() {
    let (v, err) = json(&["deflect", "--moment", "20"]);
    let (x, y) = (v["pose"]["x"].as_f64().unwrap(), v["pose"]["y"].as_f64().unwrap());
    let truth = (x - 20f64.sin() / 20.0).hypot(y - (1.0 - 20f64.cos()) / 20.0);
    let estimate = v["error_estimate"]["position"].as_f64().unwrap();
    assert!((estimate / truth - 1.0).abs() < 1e-6, "estimate {estimate}, truth {truth}");
    assert_eq!(v["flagged"], Value::Bool(true));
    assert!(err.contains("warning: deflect: the estimated error") && err.contains("--order auto"), "{err}");
}

/// `--order auto` raises order and quadrature until the estimate meets the
/// target, reports what it used, and its tip is truly on the circle.
#[test]
fn order_auto_meets_the_target() {
    let (v, err) = json(&["deflect", "--moment", "20", "--order", "auto"]);
    assert!(err.is_empty(), "{err}");
    assert_eq!(v["flagged"], Value::Bool(false));
    assert!(v["order"].as_u64().unwrap() > 3 && v["quadrature"].as_u64().unwrap() > 5);
    let (x, y) = (v["pose"]["x"].as_f64().unwrap(), v["pose"]["y"].as_f64().unwrap());
    assert!((x - 20f64.sin() / 20.0).hypot(y - (1.0 - 20f64.cos()) / 20.0) < 0.01);
}

/// A small load is within target: no flag, no warning; a tighter
/// `--accuracy` flags the same answer.
#[test]
fn accuracy_sets_the_target() {
    let (v, err) = json(&["deflect", "--fy", "3"]);
    assert!(err.is_empty() && v["flagged"] == Value::Bool(false), "{err}");
    let (v, err) = json(&["deflect", "--fy", "3", "--accuracy", "1e-6,0.0001deg"]);
    assert!(v["flagged"] == Value::Bool(true) && err.contains("accuracy target"), "{err}");
    for bad in ["0,1", "-1,1", "0.01", "nan,1deg", "0.01,x"] {
        let (code, _, err) = run(&["deflect", "--fy", "3", "--accuracy", bad]);
        assert!(code == 2 && err.contains("--accuracy"), "{bad}: {err}");
    }
}

/// Tendon, connect and batch rows carry estimates too.
#[test]
fn every_answer_carries_an_estimate() {
    let tendon = ["tendon", "--force", "28", "--root-offset", "0.005", "--tip-offset", "0.005"];
    let (v, _) = json(&[&tendon[..], &["--length", "0.015", "--ei", "1.4558e-3"]].concat());
    assert!(v["error_estimate"]["position"].as_f64().unwrap() >= 0.0 && v["flagged"].is_boolean());
    let (v, _) = json(&["connect", "--pose", "90deg,0.55,0.65"]);
    assert!(v["error_estimate"]["angle"].as_f64().unwrap() > 0.0 && v["flagged"].is_boolean());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("loads.csv");
    std::fs::write(&path, "moment,fx,fy\n0,0,1\n20,0,0\n").unwrap();
    let (code, out, err) = run(&["deflect", "--input", path.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0, "{err}");
    let rows: Vec<Value> = out.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!((rows[0]["flagged"].as_bool(), rows[1]["flagged"].as_bool()), (Some(false), Some(true)));
    assert!(err.contains("1 rows have an estimated error above the accuracy target"), "{err}");
}

/// `--order auto` where no estimate is made is refused, naming the option.
#[test]
fn order_auto_is_refused_where_it_does_not_apply() {
    for args in [&["kinematics", "--alpha", "0,0,0", "--order", "auto"][..], &["compliance", "--order", "auto"]] {
        let (code, _, err) = run(args);
        assert!(code == 2 && err.contains("order"), "{args:?}: {err}");
    }
}

/// `solve` holds every flexure joint to the target: a moment of 20 N·m on a
/// unit flexure joint winds it into the circle of radius 1/20 (closed form),
/// which five points cannot integrate; the joint is flagged by name, and its
/// estimate is the true error of its tip (1e-6 relative, the reference's
/// Newton tolerance).
#[test]
fn mechanism_joints_are_flagged_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("wound.toml");
    std::fs::write(
        &path,
        "[[joint]]\nname = \"hinge\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"link\"\n\
         origin = [0.0, 0.0, 0.0]\nlength = 1.0\nei = 1.0\n\n\
         [[force]]\nname = \"twist\"\nbody = \"link\"\nat = [0.0, 0.0]\nforce = [0.0, 0.0]\nmoment = 20.0\n",
    )
    .unwrap();
    let (v, err) = json(&["solve", path.to_str().unwrap()]);
    assert_eq!(v["flagged"], Value::Bool(true));
    assert!(err.contains("flexure joint \"hinge\"") && err.contains("accuracy target"), "{err}");
    let (x, y) = (v["bodies"]["link"]["x"].as_f64().unwrap(), v["bodies"]["link"]["y"].as_f64().unwrap());
    let truth = (x - 20f64.sin() / 20.0).hypot(y - (1.0 - 20f64.cos()) / 20.0);
    let estimate = v["error_estimate"]["hinge"]["position"].as_f64().unwrap();
    assert!((estimate / truth - 1.0).abs() < 1e-6, "estimate {estimate}, truth {truth}");
    // The shipped examples are all within the default target.
    for example in ["finger", "four_bar", "four_leg_stage", "mixed_chain", "paper_tendon", "parallelogram"] {
        let file = format!("{}/../../examples/{example}.toml", env!("CARGO_MANIFEST_DIR"));
        let (v, _) = json(&["solve", &file]);
        assert_eq!(v["flagged"], Value::Bool(false), "{example}");
    }
}
