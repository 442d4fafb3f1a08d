//! The CLI contract of solve, buckle and draw on the example files.

use serde_json::Value;
use std::process::Command;

fn examples() -> String {
    format!("{}/../../examples", env!("CARGO_MANIFEST_DIR"))
}

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_flexure")).args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// The index of the sweep table's column `name`.
fn column(v: &Value, name: &str) -> usize {
    v["columns"].as_array().unwrap().iter().position(|c| c == name).unwrap_or_else(|| panic!("no column {name}"))
}

fn json(args: &[&str]) -> Value {
    let mut a = args.to_vec();
    a.push("--json");
    let (code, out, err) = run(&a);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn solve_keys_and_values() {
    let file = format!("{}/mixed_chain.toml", examples());
    let v = json(&["solve", &file]);
    for key in ["bodies", "coordinates", "energy", "stable"] {
        assert!(v.get(key).is_some(), "{key}");
    }
    // Closed form: the spring turns M/k = 0.01/2.
    assert!((v["coordinates"]["shoulder"][0].as_f64().unwrap() - 0.005).abs() < 1e-10);
    assert_eq!(v["coordinates"]["wrist"].as_array().unwrap().len(), 5);
    assert!(v["bodies"]["hand"]["phi"].is_number());
}

#[test]
fn compliance_and_buckling_of_the_stage() {
    let file = format!("{}/parallelogram.toml", examples());
    let v = json(&["solve", &file, "--compliance", "stage", "--at", "0,-0.02"]);
    // Under the file's 1 N push: 24 EI/L³ · (1 − 1/16) = 360 N/m.
    let c = v["compliance"][1][1].as_f64().unwrap();
    assert!((1.0 / c - 360.0).abs() < 1e-6, "{}", 1.0 / c);
    let b = json(&["buckle", &file]);
    assert!((b["load_factor"].as_f64().unwrap() - 16.0).abs() < 1e-8, "2 × 10 EI/L² for 1 N");
    assert_eq!(b["mode"].as_array().unwrap().len(), 6);
}

/// A compliance where a contact slides is refused naming the pair, with no
/// option in front (it read `--compliance = at geom …`).
#[test]
fn a_compliance_where_a_contact_slides_is_refused_naming_the_pair() {
    let file = format!("{}/grasp.toml", examples());
    let (code, out, err) = run(&["solve", &file, "--compliance", "distal", "--at", "0.025,0"]);
    let named = "grasp.toml: compliance at geom \"cylinder\" (circle) and geom \"distal_pad\" (box) on body \"distal\" (sliding, friction 0.5): has no linear answer";
    assert!(code == 2 && out.is_empty() && err.contains(named), "exit {code}: {err}");
}

#[test]
fn sweep_and_draw() {
    let file = format!("{}/paper_tendon.toml", examples());
    let v = json(&["solve", &file, "--sweep", "tendon.flexor.tension=0:30:31"]);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 31);
    assert!(v.get("stability_limit").is_none());
    // Fig. 10: past 90° by 30 N, near it at 28 N.
    let at28 = rows[28][column(&v, "hinge[0]")].as_f64().unwrap();
    assert_eq!(rows[28][column(&v, "tendon.flexor.tension")].as_f64(), Some(28.0));
    assert!((at28.to_degrees() - 90.0).abs() < 2.0, "{}", at28.to_degrees());
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shape.svg");
    let d = json(&[
        "draw",
        &format!("{}/finger.toml", examples()),
        "--out",
        out.to_str().unwrap(),
        "--sweep",
        "tendon.flexor.tension=0:12:3",
    ]);
    assert_eq!(d["shapes"].as_u64(), Some(4));
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("<svg") && svg.matches("<polyline").count() > 10);
}

/// `draw --sweep` of nine values: each value's shape has its own colour
/// in the legend (past five they came round again), in the sweep's order
/// from light to dark.
#[test]
fn a_drawn_sweep_of_many_values_gives_each_its_own_colour() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("grasp.svg");
    let file = format!("{}/grasp.toml", examples());
    let path = out.to_str().unwrap();
    json(&["draw", &file, "--out", path, "--sweep", "tendon.flexor.tension=0:4:9"]);
    let svg = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = svg.lines().collect();
    let strokes: Vec<&str> = lines
        .windows(2)
        .filter(|w| w[1].contains("class=\"legend\">tendon.flexor.tension = "))
        .map(|w| w[0].split(" stroke=\"").nth(1).and_then(|s| s.get(..7)).expect("a swatch's stroke"))
        .collect();
    assert_eq!(strokes.len(), 9, "{strokes:?}");
    let lightness =
        |hex: &str| (1..7).step_by(2).map(|i| u32::from_str_radix(&hex[i..i + 2], 16).unwrap()).sum::<u32>();
    assert!(strokes.windows(2).all(|w| lightness(w[0]) > lightness(w[1])), "{strokes:?}");
}

#[test]
fn bad_files_exit_2_naming_the_place() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"palm\"\nchild = \"b\"\nlength = 0.01\nei = 1.0\n",
            "line 4",
        ),
        (
            "[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b\"\nlength = 0\nei = 1.0\n",
            "line 6",
        ),
        (
            "[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b\"\nlength = 0.01\nei = 1.0\n[[pin]]\na = \"b\"\nb = \"c\"\n",
            "line 10",
        ),
        ("[[joint]\n", "line 1"),
        (
            "[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b\"\nlength = 0.01\nei = 1.0\n[[geom]]\nbody = \"ground\"\nshape = \"circle\"\nradius = -0.1\n",
            "line 11, column 10: geom \"geom 1\": radius = -0.1: must be greater than zero",
        ),
        (
            "[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b\"\nlength = 0.01\nei = 1.0\n[[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\nfriction = -0.3\n",
            "line 14, column 12: geom \"floor\": friction = -0.3: must not be negative",
        ),
    ];
    for (i, (text, place)) in cases.iter().enumerate() {
        let path = dir.path().join(format!("bad{i}.toml"));
        std::fs::write(&path, text).unwrap();
        let (code, out, err) = run(&["solve", path.to_str().unwrap(), "--json"]);
        assert_eq!(code, 2, "{text}");
        assert!(err.contains(place) && err.contains(path.to_str().unwrap()) && !err.contains("panicked"), "{err}");
        assert!(out.is_empty());
    }
    // Beyond the buckling load the stage buckles sideways to a stable state:
    // an answer (exit 0), with the fraction where stability was lost, and a
    // warning. The model's critical push, 2 × 10 EI/L² = 16 N (Table I,
    // guided), is 40 % of 40 N.
    let heavy = std::fs::read_to_string(format!("{}/parallelogram.toml", examples()))
        .unwrap()
        .replace("[0.0, -1.0]", "[0.0, -40.0]");
    let path = dir.path().join("heavy.toml");
    std::fs::write(&path, heavy).unwrap();
    let (code, out, err) = run(&["solve", path.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    assert!((v["limit_fraction"].as_f64().unwrap() - 0.4).abs() < 1e-5, "{out}");
    assert!(err.starts_with("warning: ") && err.contains("lost stability at 39.9999 %"), "{err}");
    // A perfectly aligned sprung arm (k = 1 N·m/rad, l = 0.1 m) pushed along
    // itself by 15 N stays straight, an equilibrium at every load, unstable
    // past k/l = 10 N: no stable state is reached, exit 2 at 2/3 of the load.
    let arm = "[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 1.0\n\
               [[force]]\nbody = \"arm\"\nat = [0.1, 0.0]\nforce = [-15.0, 0.0]\n";
    let path = dir.path().join("arm.toml");
    std::fs::write(&path, arm).unwrap();
    let (code, out, err) = run(&["solve", path.to_str().unwrap(), "--json"]);
    assert_eq!(code, 2, "{out}");
    let pct: f64 = err.split("loses stability at ").nth(1).and_then(|t| t.split(' ').next()).unwrap().parse().unwrap();
    assert!((pct - 100.0 / 1.5).abs() < 1e-3, "{err}");
    assert!(out.is_empty());
    let file = format!("{}/paper_tendon.toml", examples());
    for (args, what) in [
        (vec!["solve", file.as_str(), "--sweep", "tendon.nope.tension=0:1:3"], "--sweep"),
        (vec!["solve", file.as_str(), "--sweep", "tendon.flexor.tension=0:1:1"], "--sweep"),
        (vec!["solve", file.as_str(), "--compliance", "nobody", "--at", "0,0"], "--compliance"),
        (vec!["solve", "/nonexistent.toml"], "nonexistent"),
    ] {
        let (code, _, err) = run(&args);
        assert_eq!(code, 2, "{args:?}");
        assert!(err.contains(what), "{args:?}: {err}");
    }
}

/// Sweeping the parallelogram's push past its critical load: the stable rows
/// (beyond the limit, the stage buckled sideways), then the limit, found
/// between the two values around it. The model's
/// critical push is twice one leg's guided load (`buckling_load`, Table I:
/// 10 EI/L² at N = 3), from the file's L = 0.05 m and EI = 2e-3 N·m². The
/// limit is bisected to 1e-6 of the value and the stability test's margin
/// (√tolerance of the joints' stiffness) moves it by about as much: 1e-5.
#[test]
fn sweep_past_the_critical_load() {
    use flexure::{Flexure, TipConstraint, buckling_load};
    let leg = Flexure::new(0.05, 2.0e-3, 3).unwrap();
    let critical = 2.0 * buckling_load(&leg, TipConstraint::Guided).unwrap().critical_load;
    let file = format!("{}/parallelogram.toml", examples());
    // Past 16 N the stage buckles sideways to stable states: rows too.
    for (range, stable) in [("0:-20:5", vec![0.0, -5.0, -10.0, -15.0, -20.0]), ("0:-20:3", vec![0.0, -10.0, -20.0])] {
        let spec = format!("force.push.fy={range}");
        let (code, out, err) = run(&["solve", &file, "--sweep", &spec, "--json"]);
        assert_eq!(code, 0, "{err}");
        assert!(err.starts_with("warning: ") && err.contains("stability is lost"), "{err}");
        let v: Value = serde_json::from_str(&out).unwrap();
        let rows = v["rows"].as_array().unwrap();
        let at = column(&v, "force.push.fy");
        let values: Vec<f64> = rows.iter().map(|r| r[at].as_f64().unwrap()).collect();
        assert_eq!(values, stable, "{range}");
        let limit = &v["stability_limit"];
        let value = limit["value"].as_f64().unwrap();
        assert!((value / -critical - 1.0).abs() < 1e-5, "{range}: {value} vs {}", -critical);
        assert!((limit["fraction"].as_f64().unwrap() - critical / 20.0).abs() < 1e-5, "{range}");
        // The table: one line per stable value, then the limit; no null.
        let (code, table, _) = run(&["solve", &file, "--sweep", &spec]);
        assert_eq!(code, 0);
        let lines: Vec<&str> = table.lines().collect();
        let first = lines.iter().position(|l| *l == "rows:").unwrap() + 1;
        let last = lines.iter().position(|l| *l == "stability_limit:").unwrap();
        assert_eq!(last - first, stable.len(), "{table}");
        assert!(!table.contains("null") && !table.contains("NaN"), "{table}");
        assert!(lines[last + 1].trim_start().starts_with("value:"), "{table}");
    }
}

/// The fuzzer's findings at the command line: exit 2 with the key, line and
/// column, no panic, nothing on stdout.
#[test]
fn fuzzer_findings_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let spring = "[[joint]]\nname = \"a\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"b\"\nstiffness = 5e-324\n[[force]]\nbody = \"b\"\nat = [0.0, 0.0]\nmoment = 1.0\n";
    let long = std::fs::read_to_string(format!("{}/parallelogram.toml", examples())).unwrap().replacen(
        "length = 0.05",
        "length = 1e300",
        1,
    );
    for (name, text, command, what) in [
        ("empty.toml", String::new(), "buckle", "nothing can buckle".to_string()),
        ("spring.toml", spring.to_string(), "solve", "line 6, column 13: joint \"a\": stiffness = 5e-324".to_string()),
        ("long.toml", long, "buckle", "line 11, column 10: joint \"left\": length = 1e300".to_string()),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        for json in [true, false] {
            let mut args = vec![command, path.to_str().unwrap()];
            if json {
                args.push("--json");
            }
            let (code, out, err) = run(&args);
            assert_eq!(code, 2, "{name}: {out}{err}");
            assert!(err.contains(&what) && !err.contains("panicked"), "{name}: {err}");
            assert!(out.is_empty(), "{name}: {out}");
        }
    }
}

/// `solve --sweep` keeps the rows it reached when a later value cannot be
/// solved, prints them, then the failure, and exits 2. The finger's tendon
/// at 50 N curls it past what the continuation can follow (0 and 25 N solve).
#[test]
fn a_stopped_sweep_keeps_its_rows() {
    let finger = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/finger.toml");
    let (code, out, err) = crate::cli::run(&["solve", finger, "--sweep", "tendon.flexor.tension=0:100:5", "--json"]);
    assert_eq!(code, 2, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let tensions: Vec<f64> = v["rows"].as_array().unwrap().iter().map(|r| r[0].as_f64().unwrap()).collect();
    assert_eq!(tensions, [0.0, 25.0]);
    assert_eq!(v["stopped"]["value"], 50.0);
    assert!(err.contains("the sweep stopped at tendon.flexor.tension = 50 after 2 of 5 values"), "{err}");
    // Its error's fraction of the load is of the way from the last value reached.
    assert!(err.contains("on its way there from 25 (a fraction of the load below is of that way)"), "{err}");
}

/// `draw` gives the warnings `solve` gives on the same file: here a sweep
/// past the parallelogram's buckling load (16 N, `buckle`) and the row
/// whose estimate is flagged, and the drawing marks the limit in its legend.
#[test]
fn draw_warns_as_solve_does() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/parallelogram.toml");
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("p.svg");
    let sweep = "force.push.fy=0:-30:7";
    let (_, _, solved) = crate::cli::run(&["solve", file, "--sweep", sweep]);
    let (code, _, drawn) = crate::cli::run(&["draw", file, "--out", svg.to_str().unwrap(), "--sweep", sweep]);
    assert_eq!(code, 0, "{drawn}");
    let warnings = |e: &str| e.lines().filter(|l| l.starts_with("warning:")).map(String::from).collect::<Vec<_>>();
    assert!(warnings(&solved).len() >= 2 && warnings(&solved) == warnings(&drawn), "{solved}\n---\n{drawn}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.contains("stability lost at force.push.fy = −16")
            || text.contains("stability lost at force.push.fy = -16"),
        "no limit in the legend"
    );
    assert!(text.contains("(past the stability limit)"));
}

/// `solve --limit` on the grasp: the factor on the file's 4 N tension
/// where the finger's grasp loses stability, followed in order with its
/// contacts, is where a sweep of the tension, row by row, finds it (to
/// $10^{-6}$: two paths of other steps through the same sticking and
/// sliding). With `--sweep`, which finds its own, it is refused.
#[test]
fn solve_limit_of_the_grasp_is_where_its_sweep_loses_stability() {
    let file = format!("{}/grasp.toml", examples());
    let v = json(&["solve", &file, "--limit"]);
    let limit = &v["stability_limit"];
    assert_eq!(limit["status"], "lost", "{limit}");
    let swept = json(&["solve", &file, "--sweep", "tendon.flexor.tension=0:12:13"]);
    let value = swept["stability_limit"]["value"].as_f64().unwrap();
    let factor = limit["factor"].as_f64().unwrap();
    assert!((4.0 * factor / value - 1.0).abs() < 1e-6, "{factor} × 4 N, not {value} N");
    let (code, out, err) = run(&["solve", &file, "--limit", "--sweep", "tendon.flexor.tension=0:1:2"]);
    assert!(code == 2 && out.is_empty() && err.contains("--limit") && err.contains("--sweep"), "exit {code}: {err}");
}
