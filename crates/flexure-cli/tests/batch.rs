//! `--input FILE`: every row's output equals the single call's.

use serde_json::Value;
use std::process::Command;

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_flexure")).args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

#[test]
fn kinematics_rows_match_single_calls() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("alpha.csv");
    std::fs::write(&path, "# configurations\na1,a2,a3\n0,0,0\n1,0,0\n0.5,-0.2,0.1\n").unwrap();
    let (code, out, err) = run(&["kinematics", "--json", "--input", path.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<Value> = out.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), 3);
    for (line, alpha) in lines.iter().zip(["0,0,0", "1,0,0", "0.5,-0.2,0.1"]) {
        let (_, single, _) = run(&["kinematics", "--json", "--alpha", alpha]);
        let single: Value = serde_json::from_str(&single).unwrap();
        assert_eq!(line["pose"], single["pose"]);
        assert_eq!(line["energy"], single["energy"]);
    }
    let (_, csv, _) = run(&["kinematics", "--input", path.to_str().unwrap()]);
    assert!(csv.starts_with("a1,a2,a3,phi,x,y,energy\n") && csv.lines().count() == 4);
}

#[test]
fn deflect_rows_match_single_calls() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("loads.csv");
    std::fs::write(&path, "moment,fx,fy\n0,0,1\n1,0,0\n0.3,-0.5,2\n").unwrap();
    let (code, out, err) = run(&["deflect", "--json", "--input", path.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    for (line, (m, fx, fy)) in out.lines().zip([("0", "0", "1"), ("1", "0", "0"), ("0.3", "-0.5", "2")]) {
        let row: Value = serde_json::from_str(line).unwrap();
        let (_, single, _) = run(&["deflect", "--json", "--moment", m, "--fx", fx, "--fy", fy]);
        let single: Value = serde_json::from_str(&single).unwrap();
        assert_eq!(row["alpha"], single["alpha"]);
        assert_eq!(row["stable"], single["stable"]);
    }
}

#[test]
fn bad_files_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    for (name, text, expect) in [
        ("short.csv", "a1,a2\n0,0\n", "a3"),
        ("nan.csv", "a1,a2,a3\n0,nan,0\n", "column a2"),
        ("unknown.csv", "a1,a2,a3,z\n0,0,0,1\n", "\"z\""),
        ("ragged.csv", "a1,a2,a3\n0,0\n", "line 2"),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let (code, out, err) = run(&["kinematics", "--input", path.to_str().unwrap()]);
        assert_eq!(code, 2, "{name}");
        assert!(err.contains("--input") && err.contains(expect), "{name}: {err}");
        assert!(out.is_empty());
    }
    let (code, _, err) = run(&["deflect", "--input", "/nonexistent/loads.csv"]);
    assert_eq!(code, 2);
    assert!(err.contains("--input"));
}
