//! Findings on the command line (issue 20, items 3 and 4): a closure open
//! at rest and parts that cross are told on stderr as `warning: …` (a
//! closure with `preload = true` as `note: …`) and listed under `findings`.

use crate::cli::answer;
use serde_json::Value;
use std::path::Path;

fn example(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(format!("{name}.toml")).display().to_string()
}

/// The names of every shipped example (`examples/*.toml`), so that a new one is checked too.
fn example_names() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().to_str()?.strip_suffix(".toml").map(String::from))
        .collect();
    names.sort();
    assert!(names.len() >= 8, "the examples: {names:?}");
    names
}

/// `text` written to `name` in `dir`, as a path.
fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

fn parallelogram() -> String {
    std::fs::read_to_string(example("parallelogram")).unwrap()
}

/// The half-turn weld (b_origin's angle π): a warning naming the weld and
/// its place, with the gap π rad, and the finding in the JSON answer.
#[test]
fn a_half_turn_weld_warns_on_stderr_and_in_json() {
    let dir = tempfile::tempdir().unwrap();
    let text = parallelogram().replace("b_origin = [0.0, 0.0, 0.0]", "b_origin = [0.0, 0.0, 3.141592653589793]");
    let path = write(dir.path(), "half.toml", &text);
    let (v, err) = answer(&["solve", &path]);
    let line = err.lines().find(|l| l.contains("is open at rest")).unwrap_or_else(|| panic!("{err}"));
    assert!(
        line.starts_with(&format!("warning: {path}: line 26, column 5: weld of \"stage\" and \"b_tip\"")),
        "{line}"
    );
    assert!(line.contains("3.141593 rad") && line.contains("N·m"), "{line}");
    let f = &v["findings"][0];
    assert_eq!((f["kind"].as_str(), f["severity"].as_str()), (Some("open_closure"), Some("warning")), "{v}");
    assert!((f["gap_rad"].as_f64().unwrap().abs() - std::f64::consts::PI).abs() < 1e-12, "{f}");
    // With preload = true: a note, and no warning of it.
    let meant = text.replace("b_origin = [0.0, 0.0, 3.1", "preload = true\nb_origin = [0.0, 0.0, 3.1");
    let path = write(dir.path(), "meant.toml", &meant);
    let (v, err) = answer(&["solve", &path]);
    assert!(err.lines().any(|l| l.starts_with("note: ") && l.ends_with("(preload = true)")), "{err}");
    assert!(!err.lines().any(|l| l.starts_with("warning: ") && l.contains("open at rest")), "{err}");
    assert_eq!(v["findings"][0]["severity"], "note");
}

/// The parallelogram at order 10 swept past its buckling load (16 N) to
/// −100 N: from −20 N on, leg "right" passes through the stage; one warning
/// per pair of parts, each crossing listed with its row's value.
#[test]
fn the_parallelogram_sweep_past_buckling_warns_of_a_crossing() {
    let dir = tempfile::tempdir().unwrap();
    let text = parallelogram().replace("ei = 2.0e-3\n", "ei = 2.0e-3\norder = 10\n");
    let path = write(dir.path(), "p10.toml", &text);
    let (v, err) = answer(&["solve", &path, "--sweep", "force.push.fy=0:-100:11"]);
    let line = err.lines().find(|l| l.contains("crosses link \"stage\"")).unwrap_or_else(|| panic!("{err}"));
    assert!(line.starts_with(&format!("warning: {path}: at force.push.fy = -20 ")), "{line}");
    assert!(line.contains("flexure \"right\" crosses link \"stage\" at ("), "{line}");
    let listed: Vec<f64> = v["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["parts"] == serde_json::json!(["flexure \"right\"", "link \"stage\""]))
        .map(|f| f["value"].as_f64().unwrap())
        .collect();
    assert_eq!(listed.first(), Some(&-20.0), "{v}");
    assert!(listed.iter().all(|x| *x <= -20.0), "{listed:?}");
}

/// The examples at their own loads (`solve`) warn of nothing; the four-bar
/// notes its pin, open 10 mm at rest with `preload = true`.
#[test]
fn the_examples_warn_of_nothing() {
    for name in example_names() {
        let path = example(&name);
        let (v, err) = answer(&["solve", &path]);
        assert!(!err.contains("warning:"), "{name}: {err}");
        let findings = v.get("findings").and_then(Value::as_array).cloned().unwrap_or_default();
        if name == "four_bar" {
            assert_eq!(findings.len(), 1, "{v}");
            assert_eq!(findings[0]["severity"], "note");
            assert!((findings[0]["gap_m"].as_f64().unwrap() - 0.01).abs() < 1e-12, "{v}");
            assert!(err.starts_with("note: ") && err.contains("pin of \"coupler\" and \"output\""), "{err}");
        } else {
            assert!(findings.is_empty() && err.is_empty(), "{name}: {v}: {err}");
        }
    }
}

/// A pendulum let go level swings through a flexure post beside its pivot:
/// `simulate` warns of it at the first sample where the bob's link meets the
/// post, and lists every such sample with its time; t = 0 is not one.
#[test]
fn a_simulation_that_crosses_warns_at_a_sample() {
    let dir = tempfile::tempdir().unwrap();
    // The library's crossing tests read the same file.
    let text = include_str!("../../flexure/tests/data/pendulum_through_post.toml");
    let path = write(dir.path(), "pendulum.toml", text);
    let (v, err) = answer(&["simulate", &path, "--duration", "0.3", "--every", "0.01"]);
    let line =
        err.lines().find(|l| l.contains("flexure \"post\" crosses link \"bob\"")).unwrap_or_else(|| panic!("{err}"));
    assert!(line.starts_with(&format!("warning: {path}: at t (s) = ")), "{line}");
    let times: Vec<f64> = v["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["parts"][0] == "flexure \"post\"" && f["parts"][1] == "link \"bob\"")
        .map(|f| f["time"].as_f64().unwrap())
        .collect();
    assert!(!times.is_empty() && times[0] > 0.0, "{times:?}");
    assert!(line.contains(&format!("t (s) = {} ", times[0])), "{line}");
    // draw --simulate gives simulate's warnings on the same run.
    let svg = dir.path().join("swing.svg").display().to_string();
    let (code, out, drawn) =
        crate::cli::run(&["draw", &path, "--simulate", "0.3", "--every", "0.01", "--out", &svg, "--json"]);
    assert_eq!(code, 0, "{drawn}");
    assert!(drawn.lines().any(|l| l == line), "{drawn}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v["findings"].as_array().is_some_and(|f| !f.is_empty()), "{v}");
}

/// The planar pendulum and post in space, the post a 10 mm blade
/// (`pendulum_through_post3d.toml`): `simulate` warns at the first sample
/// where the bob's link meets the post's solid and lists every such sample
/// with its time, each where the bob's angle lies in the window the file's
/// comment derives (−77.0° to −19.98°); `draw --simulate` warns alike.
#[test]
fn a_spatial_simulation_that_crosses_warns_at_a_sample() {
    let dir = tempfile::tempdir().unwrap();
    let text = include_str!("../../flexure/tests/data/pendulum_through_post3d.toml");
    let path = write(dir.path(), "pendulum3d.toml", text);
    let (v, err) = answer(&["simulate", &path, "--duration", "0.3", "--every", "0.01"]);
    let line =
        err.lines().find(|l| l.contains("flexure \"post\" crosses link \"bob\"")).unwrap_or_else(|| panic!("{err}"));
    assert!(line.starts_with(&format!("warning: {path}: at t (s) = ")), "{line}");
    let found: Vec<&Value> = v["findings"].as_array().unwrap().iter().collect();
    assert!(!found.is_empty() && found.iter().all(|f| f["parts"][0] == "flexure \"post\""), "{v}");
    let times: Vec<f64> = found.iter().map(|f| f["time"].as_f64().unwrap()).collect();
    assert!(times[0] > 0.0 && line.contains(&format!("t (s) = {} ", times[0])), "{line}");
    let time: Vec<f64> = v["time"].as_array().unwrap().iter().map(|t| t.as_f64().unwrap()).collect();
    let pivot: Vec<f64> =
        v["coordinates"]["pivot"].as_array().unwrap().iter().map(|r| r[0].as_f64().unwrap()).collect();
    for t in &times {
        let k = time.iter().position(|s| s == t).unwrap();
        assert!(pivot[k] > (-77.01f64).to_radians() && pivot[k] < (-19.97f64).to_radians(), "t = {t}: {}", pivot[k]);
        assert_eq!(found[0]["at"].as_array().unwrap().len(), 3);
    }
    let svg = dir.path().join("swing.svg").display().to_string();
    let (code, out, drawn) =
        crate::cli::run(&["draw", &path, "--simulate", "0.3", "--every", "0.01", "--out", &svg, "--json"]);
    assert_eq!(code, 0, "{drawn}");
    assert!(drawn.lines().any(|l| l == line), "{drawn}");
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["findings"].as_array().map(Vec::len), Some(found.len()), "{v}");
}

/// Two round rods 2 mm thick, their axes 4 mm apart along z, one pushed
/// toward the other at its tip: they touch when its tip has moved 2 mm, at
/// F = 3EIδ/L³ = 7.54 N by the cantilever's closed form (E = 200 GPa,
/// I = πd⁴/64, L = 50 mm; the tip turns 0.06 rad there, so the linear
/// theory holds to a fraction of a percent). `solve --sweep` lists the
/// crossing at 10 and 15 N, not at 0 or 5 N; `solve` at 10 N lists it too.
#[test]
fn a_spatial_sweep_lists_the_values_where_parts_cross() {
    let dir = tempfile::tempdir().unwrap();
    let rod = |name: &str, z: f64| {
        format!(
            "[[joint]]\nname = \"{name}\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"{name}_tip\"\n\
             origin = [0.0, 0.0, {z}]\nlength = 0.05\nmodulus = 2e11\npoisson = 0.3\ndiameter = 2e-3\n"
        )
    };
    let text = format!(
        "dimension = 3\n{}{}[[force]]\nname = \"push\"\nbody = \"a_tip\"\nforce = [0.0, 0.0, 10.0]\n",
        rod("a", 0.0),
        rod("b", 4e-3)
    );
    let path = write(dir.path(), "rods.toml", &text);
    let (v, err) = answer(&["solve", &path, "--sweep", "force.push.fz=0:15:4"]);
    let values: Vec<f64> = v["findings"].as_array().unwrap().iter().map(|f| f["value"].as_f64().unwrap()).collect();
    assert_eq!(values, [10.0, 15.0], "{v}");
    let line = err.lines().find(|l| l.contains("crosses")).unwrap_or_else(|| panic!("{err}"));
    assert!(line.contains("at force.push.fz = 10 and at 1 more of the swept values"), "{line}");
    assert!(line.contains("flexure \"a\" crosses flexure \"b\""), "{line}");
    let (v, err) = answer(&["solve", &path]);
    assert_eq!(v["findings"][0]["parts"], serde_json::json!(["flexure \"a\"", "flexure \"b\""]), "{v}");
    assert!(err.contains("warning: ") && err.contains("crosses flexure \"b\""), "{err}");
}
