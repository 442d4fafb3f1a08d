//! `--input FILE`: every row is answered, by the single call's result or by
//! its own error in its place, and the exit status says whether all succeeded.

use serde_json::Value;
use std::path::Path;
use std::process::Command;

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_flexure")).args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

fn single(args: &[&str]) -> Value {
    let (code, out, err) = run(&[args, &["--json"]].concat());
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn kinematics_rows_match_single_calls() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "alpha.csv", "# configurations\na1,a2,a3\n0,0,0\n1,0,0\n0.5,-0.2,0.1\n");
    let (code, out, err) = run(&["kinematics", "--json", "--input", &path]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<Value> = out.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), 3);
    for (line, alpha) in lines.iter().zip(["0,0,0", "1,0,0", "0.5,-0.2,0.1"]) {
        let single = single(&["kinematics", "--alpha", alpha]);
        assert_eq!(line["pose"], single["pose"]);
        assert_eq!(line["energy"], single["energy"]);
    }
    let (_, csv, _) = run(&["kinematics", "--input", &path]);
    assert!(csv.starts_with("a1,a2,a3,phi,x,y,energy\n") && csv.lines().count() == 4);
    // Arc of angle 1 (closed form x = sin 1, U = 1/2): the CSV columns are in header order.
    let arc: Vec<f64> = csv.lines().nth(2).unwrap().split(',').map(|c| c.parse().unwrap()).collect();
    assert_eq!(arc[..3], [1.0, 0.0, 0.0]);
    assert!((arc[4] - 1f64.sin()).abs() < 1e-9 && (arc[6] - 0.5).abs() < 1e-15, "{arc:?}");
}

#[test]
fn deflect_rows_match_single_calls() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "loads.csv", "moment,fx,fy\n0,0,1\n1,0,0\n0.3,-0.5,2\n");
    let (code, out, err) = run(&["deflect", "--json", "--input", &path]);
    assert_eq!(code, 0, "{err}");
    for (line, (m, fx, fy)) in out.lines().zip([("0", "0", "1"), ("1", "0", "0"), ("0.3", "-0.5", "2")]) {
        let row: Value = serde_json::from_str(line).unwrap();
        let single = single(&["deflect", "--moment", m, "--fx", fx, "--fy", fy]);
        assert_eq!(row["alpha"], single["alpha"]);
        assert_eq!(row["stable"], single["stable"]);
    }
}

/// One bad row among good ones: the good rows are still answered, the bad
/// one prints `{"row": n, "error": …}` in its place, and the exit status is 2.
#[test]
fn failing_rows_are_answered_in_place() {
    let dir = tempfile::tempdir().unwrap();
    // Rows: good, nan cell, good, ragged, garbage, energy overflows to ∞ (α1² / 2 with α1 = 1e300), good.
    let text = "a1,a2,a3\n0,0,0\n0,nan,0\n1,0,0\n# a comment between rows\n0,0\n0,0,zero\n1e300,0,0\n0.5,-0.2,0.1\n";
    let path = write(dir.path(), "mixed.csv", text);
    let (code, out, err) = run(&["kinematics", "--json", "--input", &path]);
    assert_eq!(code, 2, "{err}");
    let lines: Vec<Value> = out.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), 7, "{out}");
    for (row, expect) in [(2, "column a2"), (4, "2 values for 3 columns"), (5, "column a3"), (6, "energy")] {
        let line = &lines[row - 1];
        assert_eq!(line["row"], row, "{line}");
        assert!(line["error"].as_str().unwrap().contains(expect), "row {row}: {line}");
        assert_eq!(line.as_object().unwrap().len(), 2, "only row and error: {line}");
    }
    for (row, alpha) in [(1, "0,0,0"), (3, "1,0,0"), (7, "0.5,-0.2,0.1")] {
        assert_eq!(lines[row - 1]["pose"], single(&["kinematics", "--alpha", alpha])["pose"], "row {row}");
    }
    assert!(err.contains("4 of 7 rows failed (rows 2, 4, 5, 6)") && err.contains(&path), "{err}");
    assert!(!out.contains("null"), "a non-finite number is never printed: {out}");

    // The table form: a readable line in each failing row's place.
    let (code, csv, _) = run(&["kinematics", "--input", &path]);
    assert_eq!(code, 2);
    let csv: Vec<&str> = csv.lines().collect();
    assert_eq!(csv.len(), 8, "header and seven rows: {csv:?}");
    assert!(csv[2].starts_with("# row 2: error: line 3, column a2"), "{}", csv[2]);
    assert!(csv[6].starts_with("# row 6: error:") && csv[6].contains("energy"), "{}", csv[6]);
    assert!(csv[3].starts_with("1,0,0,"), "{}", csv[3]);
}

/// Many rows, every third bad: all are answered, in order (the Trust issue's
/// sweep lost 2,082 of 2,450 rows to one failure).
#[test]
fn a_long_file_keeps_every_row() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("moment,fx,fy\n");
    for i in 0..300 {
        text += &if i % 3 == 1 { format!("{i},x,0\n") } else { format!("{},0,0\n", i as f64 / 300.0) };
    }
    let path = write(dir.path(), "many.csv", &text);
    let (code, out, err) = run(&["deflect", "--json", "--input", &path]);
    assert_eq!(code, 2);
    assert!(err.contains("100 of 300 rows failed"), "{err}");
    let lines: Vec<Value> = out.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), 300);
    for (i, line) in lines.iter().enumerate() {
        if i % 3 == 1 {
            assert_eq!(line["row"], i + 1);
        } else {
            // A pure moment M bends a unit flexure into an arc: α1 = M (closed form).
            let m = i as f64 / 300.0;
            assert!((line["alpha"][0].as_f64().unwrap() - m).abs() < 1e-12, "row {}: {line}", i + 1);
        }
    }
}

/// `angle` cells take a `deg` suffix as `--angle` does; a bare angle beyond
/// 2π draws a warning that it is read as radians.
#[test]
fn angle_cells_take_degrees() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "polar.csv", "moment,force,angle\n0,1,45deg\n0, 1 , 30 deg\n0,1,0.5\n");
    let (code, out, err) = run(&["deflect", "--json", "--input", &path]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("warning"), "{err}");
    let lines: Vec<Value> = out.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    for (line, angle) in lines.iter().zip(["45deg", "30deg", "0.5"]) {
        assert_eq!(line["alpha"], single(&["deflect", "--force", "1", "--angle", angle])["alpha"], "{angle}");
    }
    // Fx = −P sin θ (paper Sec. III-C): θ = 45° gives −√2/2.
    assert!((lines[0]["load"]["fx"].as_f64().unwrap() + 0.5f64.sqrt()).abs() < 1e-15);

    let path = write(dir.path(), "bare.csv", "moment,force,angle\n0,1,0.5\n0,1,45\n0,1,90\n");
    let (code, _, err) = run(&["deflect", "--input", &path]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("warning") && err.contains("line 3: angle 45") && err.contains("45deg"), "{err}");
    assert!(err.contains("and 1 more"), "{err}");
}

/// A file whose header cannot be answered is an error of the whole file: nothing on stdout.
#[test]
fn bad_files_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    for (name, text, expect) in [
        ("short.csv", "a1,a2\n0,0\n", "missing column \"a3\""),
        ("unknown.csv", "a1,a2,a3,z\n0,0,0,1\n", "unknown column \"z\""),
        ("twice.csv", "a1,a2,a3,a1\n0,0,0,1\n", "\"a1\" appears twice"),
        ("empty.csv", "# nothing\n\n", "no header"),
    ] {
        let path = write(dir.path(), name, text);
        let (code, out, err) = run(&["kinematics", "--input", &path]);
        assert_eq!(code, 2, "{name}");
        assert!(err.contains("--input") && err.contains(expect), "{name}: {err}");
        assert!(out.is_empty(), "{name}: {out}");
    }
    let path = write(dir.path(), "both.csv", "fx,force\n0,1\n");
    let (code, _, err) = run(&["deflect", "--input", &path]);
    assert_eq!(code, 2);
    assert!(err.contains("not both"), "{err}");
    let (code, _, err) = run(&["deflect", "--input", "/nonexistent/loads.csv"]);
    assert_eq!(code, 2);
    assert!(err.contains("--input /nonexistent/loads.csv"), "{err}");
}

/// A header with no rows has nothing to answer: exit 2 saying so, not an
/// empty success (found by the fuzzer).
#[test]
fn a_file_without_rows_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (command, header) in [("deflect", "moment,fx,fy\n"), ("kinematics", "a1,a2,a3\n")] {
        let path = write(dir.path(), "empty.csv", header);
        let (code, out, err) = run(&[command, "--json", "--input", &path]);
        assert_eq!(code, 2, "{command}: {out}");
        assert!(out.is_empty() && err.contains("no rows"), "{command}: {err}");
    }
}

/// A batch row carries the whole error estimate, the single call's very
/// object (curvature, and stress with a thickness, included), and its
/// table form one column per leaf, under a header naming each.
#[test]
fn rows_carry_the_single_calls_estimate() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "loads.csv", "moment,fx,fy\n0.5,0,0.2\n");
    let steel = ["--length", "0.05", "--modulus", "200e9", "--width", "0.01", "--thickness", "4e-4"];
    for section in [&steel[..], &[]] {
        let (code, out, err) = run(&[&["deflect", "--json", "--input", &path], section].concat());
        assert_eq!(code, 0, "{err}");
        let row: Value = serde_json::from_str(out.lines().next().unwrap()).unwrap();
        let one = single(&[&["deflect", "--moment", "0.5", "--fy", "0.2"], section].concat());
        assert_eq!(row["error_estimate"], one["error_estimate"], "{section:?}");
        assert!(row["error_estimate"]["curvature"].is_f64());
        assert_eq!(row["error_estimate"].get("stress").is_some(), !section.is_empty());
        let (_, table, _) = run(&[&["deflect", "--input", &path], section].concat());
        let lines: Vec<&str> = table.lines().collect();
        assert_eq!(lines[0].split(',').count(), lines[1].split(',').count(), "{table}");
        assert_eq!(lines[0].contains("error_stress"), !section.is_empty());
    }
}
