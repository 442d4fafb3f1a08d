//! The mechanism subcommands on spatial files (`dimension = 3`): each
//! prints the library's answer (checked against the library itself and a
//! closed form), and bad input exits 2 naming the key, line and column.

use crate::cli::{answer, run};
use serde_json::Value;

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// Every number in `v`, in order.
fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Number(n) => vec![n.as_f64().unwrap()],
        Value::Array(a) => a.iter().flat_map(numbers).collect(),
        Value::Object(o) => o.values().flat_map(numbers).collect(),
        _ => vec![],
    }
}

/// A file written for the test.
fn written(dir: &tempfile::TempDir, text: &str) -> String {
    let path = dir.path().join("m.toml");
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

const PENDULUM: &str = "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n\
    [[joint]]\nname = \"hinge\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\naxis = [0.0, 1.0, 0.0]\nstiffness = 2.0\n\
    [[body]]\nname = \"arm\"\nmass = 0.5\ncom = [0.1, 0.0, 0.0]\n";

/// Reference: the spatial examples through every subcommand that applies
/// to them (`solve`, `solve --sweep`, `solve --compliance X,Y,Z`,
/// `buckle`), each exiting 0 with a finite answer and no warning, the
/// solve's bodies being the library's report.
#[test]
fn the_spatial_examples_answer_every_mechanism_subcommand() {
    // The last: why `buckle` refuses, as its header says (None: it answers).
    let cases = [
        ("finger3d.toml", "force.contact.fz=0:0.1:3", ("fingertip", "0,0,0.003"), None),
        ("continuum_robot.toml", "tendon.side.tension=0:0.6:4", ("disc5", "0,0,0"), None),
        ("stage3d.toml", "force.load.fz=0:2:3", ("stage", "0,-0.02,0"), None),
        ("right_angle_cantilever.toml", "force.pulse.fz=0:50:3", ("tip", "0,0,0"), Some("no buckling load")),
    ];
    for (name, sweep, (body, at), refused) in cases {
        let file = example(name);
        let text = std::fs::read_to_string(&file).unwrap();
        // The comments show the commands run here.
        assert!(
            text.contains(&format!("--compliance {body} --at {at}")),
            "{name}: the comments do not show the compliance call"
        );
        let (v, err) = answer(&["solve", &file]);
        assert!(err.is_empty(), "{name}: {err}");
        assert_eq!(v["dimension"], 3);
        let m = flexure::mechanism::file::spatial_from_toml(&text).unwrap();
        let s = flexure::mechanism::statics::solve(&m, &Default::default()).unwrap();
        let library =
            serde_json::to_value(flexure::report::solve_report(&m, &s, &Default::default()).unwrap()).unwrap();
        // The same numbers (to the last bits that JSON's text round trip may move).
        let (a, b) = (numbers(&v["bodies"]), numbers(&library["bodies"]));
        assert_eq!(a.len(), b.len(), "{name}");
        assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= 1e-15 * x.abs().max(1e-3)), "{name}");
        let (v, err) = answer(&["solve", &file, "--sweep", sweep]);
        assert!(err.is_empty(), "{name} --sweep: {err}");
        assert!(v["rows"].as_array().unwrap().len() >= 3, "{name}: {v}");
        let (v, err) = answer(&["solve", &file, "--compliance", body, "--at", at]);
        assert!(err.is_empty(), "{name} --compliance: {err}");
        let c = v["compliance"].as_array().unwrap();
        assert_eq!((c.len(), c[0].as_array().unwrap().len()), (6, 6), "{name}");
        match refused {
            None => {
                let (v, _) = answer(&["buckle", &file]);
                assert!(v["load_factor"].as_f64().unwrap() > 1.0, "{name}: {v}");
            }
            Some(reason) => {
                let (code, stdout, stderr) = run(&["buckle", &file]);
                assert!(code == 2 && stdout.is_empty() && stderr.contains(reason), "{name} buckle: {code} {stderr}");
                assert!(
                    text.contains("`buckle` does not apply") && text.contains(reason),
                    "{name}: the header must say why"
                );
            }
        }
    }
}

/// Reference: a sprung hinge about y carrying 0.5 kg at 0.1 m: gravity turns
/// it by $k\theta = mgl\cos\theta$ (a turn about +y takes +x down), its one
/// mode is $\omega^2 = (k + mgl\sin\theta)/(ml^2)$ about that state ($V^{\prime\prime}$
/// of $V = \frac12k\theta^2 - mgl\sin\theta$), and a
/// simulation from the equilibrium stays there.
#[test]
fn a_sprung_arm_solves_rings_and_rests() {
    let dir = tempfile::tempdir().unwrap();
    let file = written(&dir, PENDULUM);
    let (k, m, g, l) = (2.0f64, 0.5, 9.81, 0.1);
    let (mut lo, mut hi) = (0.0, 1.5);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if k * mid < m * g * l * f64::cos(mid) { lo = mid } else { hi = mid }
    }
    let (v, _) = answer(&["solve", &file]);
    let theta = v["coordinates"]["hinge"][0].as_f64().unwrap();
    assert!((theta - lo).abs() < 1e-10, "{theta} against {lo}");
    let (v, _) = answer(&["modes", &file]);
    let omega = v["omega"][0].as_f64().unwrap();
    let expected = ((k + m * g * l * lo.sin()) / (m * l * l)).sqrt();
    assert!((omega - expected).abs() < 1e-8 * expected, "{omega} against {expected}");
    let (v, _) = answer(&["simulate", &file, "--duration", "0.2", "--every", "0.1"]);
    let rows = v["coordinates"]["hinge"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    for r in rows {
        assert!((r[0].as_f64().unwrap() - lo).abs() < 1e-7, "{v}");
    }
    let rotation = &v["bodies"]["arm"]["rotation"][2];
    assert_eq!(rotation.as_array().unwrap().len(), 3);
}

/// Reference: the file's text: every bad value is refused with exit 2,
/// nothing on stdout, and its key, line and column on stderr.
#[test]
fn bad_spatial_input_names_its_key_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &str, &[&str]); 4] = [
        (
            &PENDULUM.replace("axis = [0.0, 1.0, 0.0]", "axis = [0.0, 0.0, 0.0]"),
            "line 8, column 8: joint \"hinge\": axis",
            &["solve"],
        ),
        (&PENDULUM.replace("dimension = 3", "dimension = 5"), "line 1, column 13: dimension = 5", &["buckle"]),
        (&PENDULUM.replace("com = [0.1, 0.0, 0.0]", "com = [0.1, 0.0]"), "line 13, column 7", &["modes"]),
        (PENDULUM, "--at: ", &["solve", "--compliance", "arm", "--at", "0.1,0"]),
    ];
    for (text, expected, args) in cases {
        let file = written(&dir, text);
        let mut all = vec![args[0], file.as_str()];
        all.extend(&args[1..]);
        let (code, out, err) = run(&all);
        assert_eq!(code, 2, "{all:?}: {out}");
        assert!(out.is_empty() && err.contains(expected), "{all:?}: {err:?} should contain {expected:?}");
    }
    // SDFormat of a spatial file: each hinge a link of its own (checked with a published
    // parser in python/tests/test_export_spatial.py).
    let file = example("stage3d.toml");
    let (code, out, _) = run(&["export", &file, "--to", "sdf"]);
    assert!(code == 0 && out.contains(r#"<joint name="left_1z" type="revolute">"#), "{out}");
    // MJCF it writes (checked in MuJoCo in python/tests/test_export_spatial.py).
    let (code, out, _) = run(&["export", &file, "--to", "mjcf"]);
    assert!(code == 0 && out.contains(r#"<weld name="weld_0""#) && out.contains(r#"<joint name="left_3x""#), "{out}");
    // Draw renders it, from each view.
    for view in ["iso", "front", "top", "side"] {
        let out = dir.path().join(format!("{view}.svg"));
        let file = example("finger3d.toml");
        let (v, _) = answer(&["draw", &file, "--out", out.to_str().unwrap(), "--view", view]);
        assert_eq!(v["shapes"], 2);
        assert!(std::fs::read_to_string(&out).unwrap().starts_with("<svg"), "{view}");
    }
    // And a planar command's key on a spatial file says what to give.
    let file = written(&dir, PENDULUM);
    let (code, _, err) = run(&["solve", &file, "--sweep", "force.none.fx=0:1:2"]);
    assert!(code == 2 && err.contains("sweep"), "{err}");
    let _ = Value::Null;
}

/// Whether `v` holds a JSON null anywhere.
fn has_null(v: &Value) -> bool {
    match v {
        Value::Null => true,
        Value::Array(a) => a.iter().any(has_null),
        Value::Object(o) => o.values().any(has_null),
        _ => false,
    }
}

/// Reference: the library's `estimate::spatial_mechanism` estimates of the
/// same mechanism (to the last bits JSON's text round trip may move, 1e-15
/// relative): `buckle` and `modes` of the continuum robot carry
/// `error_estimate` {load_factor or omega, reference_load_factor or
/// reference_omega, reference_order and reference_quadrature by spatial
/// flexure joint} and `flagged`, in the planar answers' keys, with no null;
/// at the default 1 % neither is flagged nor warns.
#[test]
fn spatial_buckle_and_modes_carry_their_error_estimate() {
    let joints = ["s1", "s2", "s3", "s4", "s5"];
    let file = example("continuum_robot.toml");
    let (v, err) = answer(&["buckle", &file]);
    assert!(err.is_empty() && !has_null(&v), "{err}\n{v}");
    let m = flexure::mechanism::file::spatial_from_toml(&std::fs::read_to_string(&file).unwrap()).unwrap();
    let settings = Default::default();
    let b = flexure::mechanism::buckling::buckle(&m, &settings).unwrap();
    let e = flexure::estimate::buckle_error(&m, &b, &settings, &Default::default()).unwrap();
    let estimate = &v["error_estimate"];
    let close = |a: &Value, b: f64| (a.as_f64().unwrap() - b).abs() <= 1e-15 * b.abs();
    assert!(close(&estimate["load_factor"], e.relative[0].unwrap()), "{estimate}");
    assert!(close(&estimate["reference_load_factor"], e.reference[0]), "{estimate}");
    for (k, j) in joints.iter().enumerate() {
        assert_eq!(estimate["reference_order"][j], e.reference_orders[k].0, "{estimate}");
        assert_eq!(estimate["reference_quadrature"][j], e.reference_orders[k].1, "{estimate}");
    }
    assert_eq!(v["flagged"], false);
    // The example's discs carry mass, so it vibrates.
    let (v, err) = answer(&["modes", &file, "--count", "4"]);
    assert!(err.is_empty() && !has_null(&v), "{err}\n{v}");
    let found = flexure::dynamics::mechanism::modes(&m, &settings, 4).unwrap();
    let e = flexure::estimate::mechanism_modes_error(&m, &found, &settings, &Default::default()).unwrap();
    let estimate = &v["error_estimate"];
    let (omega, reference) = (estimate["omega"].as_array().unwrap(), estimate["reference_omega"].as_array().unwrap());
    assert_eq!((omega.len(), reference.len()), (4, 4), "{estimate}");
    for k in 0..4 {
        assert!(close(&omega[k], e.relative[k].unwrap()) && close(&reference[k], e.reference[k]), "{estimate}");
    }
    assert_eq!(estimate["reference_order"].as_object().unwrap().len(), 5, "{estimate}");
    assert_eq!(v["flagged"], false);
}

/// A column of orders [1, 1, 1] (constant curvature) along x, EI = 1 and 2,
/// pushed by 1 N along itself, with a disc at its tip.
const COARSE_COLUMN: &str = "dimension = 3\n\
    [[joint]]\nname = \"column\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\n\
    gj = 0.8\nei_y = 1.0\nei_z = 2.0\norders = [1, 1, 1]\n\
    [[body]]\nname = \"tip\"\nmass = 0.3\nixx = 2e-4\niyy = 1e-4\nizz = 1e-4\n\
    [[force]]\nname = \"push\"\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nforce = [-1.0, 0.0, 0.0]\n";

/// Reference: Euler's free-tip load $\pi^2EI/(4L^2)$ = 2.4674: constant
/// curvature says 3, 21.6 % high, so `buckle` is flagged and warns on
/// stderr with its estimate and what to do; the same at a loose `--accuracy
/// 0.5` is not; its bending modes (constant curvature ties the disc's slope
/// to its deflection: each is 15 % or more high against the cantilever's)
/// are flagged and warned per mode.
#[test]
fn a_coarse_spatial_column_is_flagged_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let file = written(&dir, COARSE_COLUMN);
    let (v, err) = answer(&["buckle", &file]);
    assert_eq!(v["flagged"], true, "{v}");
    let truth = v["load_factor"].as_f64().unwrap() / (std::f64::consts::PI.powi(2) / 4.0) - 1.0;
    let estimate = v["error_estimate"]["load_factor"].as_f64().unwrap();
    assert!(truth > 0.2 && (estimate / truth - 1.0).abs() < 1e-3, "estimate {estimate}, truth {truth}");
    assert!(
        err.contains("buckle: the load factor")
            && err.contains("target 1 %")
            && err.contains("\"column\" at orders up to 4"),
        "{err}"
    );
    let (v, err) = answer(&["buckle", &file, "--accuracy", "0.5"]);
    assert!(v["flagged"] == false && err.is_empty(), "{err}");
    let (v, err) = answer(&["modes", &file]);
    assert_eq!(v["flagged"], true, "{v}");
    assert!(!has_null(&v), "{v}");
    assert!(err.contains("modes: mode 1 (") && err.contains("estimated error"), "{err}");
    assert_eq!(err.lines().count(), 1, "one warning, naming each mode that misses: {err}");
}

/// Reference: the JSON answer of the same run and the rotation matrix of a
/// unit quaternion, $R = I + 2q_w[v]_\times + 2[v]_\times^2$ with
/// $v = (q_x, q_y, q_z)$: `simulate --out` on a spatial file writes one CSV
/// row per sample (time, each body's x, y, z, qw, qx, qy, qz, each joint's
/// coordinates and rates, energy) whose numbers are the answer's (to 1e-15
/// relative, JSON's parse) and whose quaternions rebuild its rotations to 1e-14.
#[test]
fn simulate_writes_a_spatial_runs_csv() {
    let dir = tempfile::tempdir().unwrap();
    // A ball joint started tilted about a skew axis, so every quaternion component moves.
    let text = "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n\
        [[joint]]\nname = \"ball\"\nkind = \"spherical\"\nparent = \"ground\"\nchild = \"bob\"\n\
        [[body]]\nname = \"bob\"\nmass = 1.0\ncom = [0.0, 0.0, -1.0]\nixx = 0.01\niyy = 0.02\nizz = 0.03\n\
        [initial]\nball = [0.3, -0.2, 0.4]\n";
    let file = written(&dir, text);
    let out = dir.path().join("run.csv");
    let (v, err) = answer(&["simulate", &file, "--duration", "0.5", "--every", "0.05", "--out", out.to_str().unwrap()]);
    assert!(err.is_empty(), "{err}");
    assert_eq!(v["out"], out.display().to_string());
    let csv = std::fs::read_to_string(&out).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header,
        [
            "time",
            "bob.x",
            "bob.y",
            "bob.z",
            "bob.qw",
            "bob.qx",
            "bob.qy",
            "bob.qz",
            "ball[0]",
            "ball[1]",
            "ball[2]",
            "ball[0].rate",
            "ball[1].rate",
            "ball[2].rate",
            "energy"
        ]
    );
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
    let time = v["time"].as_array().unwrap();
    assert_eq!(rows.len(), time.len());
    assert!(rows.len() >= 11);
    // serde_json's parse of the answer may be an ulp off (no float_roundtrip).
    let same =
        |a: &[f64], b: &[f64]| a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-15 * x.abs());
    for (k, row) in rows.iter().enumerate() {
        assert!(same(&row[..1], &[time[k].as_f64().unwrap()]), "{row:?}");
        let bob = &v["bodies"]["bob"];
        let position: Vec<f64> = ["x", "y", "z"].iter().map(|c| bob[*c][k].as_f64().unwrap()).collect();
        assert!(same(&row[1..4], &position), "{row:?}");
        let (w, x, y, z) = (row[4], row[5], row[6], row[7]);
        assert!(w >= 0.0 && (w * w + x * x + y * y + z * z - 1.0).abs() < 1e-14, "{row:?}");
        let r = [
            [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
            [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
            [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
        ];
        let rotation = numbers(&v["bodies"]["bob"]["rotation"][k]);
        for (a, b) in r.iter().flatten().zip(&rotation) {
            assert!((a - b).abs() < 1e-14, "sample {k}: {r:?} against {rotation:?}");
        }
        assert!(same(&row[8..11], &numbers(&v["coordinates"]["ball"][k])), "{row:?}");
        assert!(same(&row[14..], &[v["energy"][k].as_f64().unwrap()]), "{row:?}");
    }
}

/// Reference: Euler's free-tip load π²EI/(4L²) = 2.4674 (EI = 1 about the
/// weak axis): the coarse column with `order = "auto"` in place of its
/// orders [1, 1, 1] is raised by `buckle --accuracy 1e-6` until its
/// estimate meets that, answers within 1e-6 of Euler, says the orders it
/// used under `order`, and warns of nothing; `modes` names them too.
#[test]
fn order_auto_raises_a_spatial_flexure_until_the_estimate_meets_accuracy() {
    let dir = tempfile::tempdir().unwrap();
    let file = written(&dir, &COARSE_COLUMN.replace("orders = [1, 1, 1]", "order = \"auto\""));
    let (v, err) = answer(&["buckle", &file, "--accuracy", "1e-6"]);
    assert!(err.is_empty(), "{err}");
    let euler = std::f64::consts::PI.powi(2) / 4.0;
    assert!((v["load_factor"].as_f64().unwrap() / euler - 1.0).abs() < 1e-6, "{v}");
    assert_eq!(v["flagged"], false);
    let orders = numbers(&v["order"]["column"]);
    assert!(orders.len() == 3 && orders.iter().all(|n| *n > 1.0), "{v}");
    let (v, err) = answer(&["modes", &file, "--count", "2"]);
    assert!(err.is_empty() && v["order"]["column"].is_array(), "{err}\n{v}");
}

/// Reference: the library's `mechanism::findings::open_closures`
/// (whose numbers `tests/spatial_mechanism.rs` checks against small
/// rotations): a ball open 1 mm at rest is told on stderr with its place in
/// the file and listed under `findings` by `solve` and `simulate` (and
/// told by `buckle` and `modes`, which this locked mechanism then refuses),
/// as a warning; with `preload = true`, as a note.
#[test]
fn spatial_open_closures_are_told_and_listed() {
    let dir = tempfile::tempdir().unwrap();
    let text = "dimension = 3\n\
        [[joint]]\nname = \"l\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"a\"\nstiffness = 1.0\n\
        [[joint]]\nname = \"r\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"b\"\norigin = [0.1, -0.1, 0.0]\nstiffness = 1.0\n\
        [[body]]\nname = \"a\"\nmass = 0.1\nizz = 1e-4\nixx = 1e-4\niyy = 1e-4\n\
        [[ball]]\na = \"a\"\na_at = [0.1, 0.0, 0.0]\nb = \"b\"\nb_at = [0.001, 0.1, 0.0]\n";
    let file = written(&dir, text);
    for args in [vec!["solve"], vec!["buckle"], vec!["modes"], vec!["simulate", "--duration", "0.01"]] {
        // buckle and modes: the ball leaves no motion, an error after the finding was told.
        let mut all = vec![args[0], file.as_str()];
        all.extend(&args[1..]);
        let err = if matches!(args[0], "buckle" | "modes") {
            let (code, _, err) = run(&all);
            assert!(code == 2 && err.contains("no motion"), "{all:?}: {err}");
            err
        } else {
            let (v, err) = answer(&all);
            let f = &v["findings"][0];
            assert_eq!((f["kind"].as_str(), f["severity"].as_str()), (Some("open_closure"), Some("warning")), "{v}");
            assert!((f["gap_m"].as_f64().unwrap() - 1e-3).abs() < 1e-12, "{f}");
            err
        };
        assert!(
            err.contains("line 22, column 5: ball of \"a\" and \"b\" is open at rest by 1.000000e-3 m"),
            "{all:?}: {err}"
        );
    }
    let file = written(&dir, &format!("{text}preload = true\n"));
    let (v, err) = answer(&["solve", &file]);
    assert!(err.contains("note:") && !err.contains("warning:"), "{err}");
    assert_eq!(v["findings"][0]["severity"], "note", "{v}");
}

/// Reference: the library's spatial sweep of the same load: `draw --sweep`
/// on a spatial file draws the unloaded shape and one shape per value the
/// sweep reached, each named in the legend by its value, and answers the
/// number of shapes; a bad parameter is refused naming it.
#[test]
fn draw_sweeps_a_spatial_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sweep.svg");
    let file = example("continuum_robot.toml");
    let (v, err) = answer(&[
        "draw",
        &file,
        "--sweep",
        "tendon.side.tension=0:0.6:4",
        "--view",
        "front",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(err.is_empty(), "{err}");
    let m = flexure::mechanism::file::spatial_from_toml(&std::fs::read_to_string(&file).unwrap()).unwrap();
    let p = flexure::mechanism::sweep::Parameter::parse(&m, "tendon.side.tension").unwrap();
    let rows = flexure::mechanism::sweep::sweep(&m, &p, &[0.0, 0.2, 0.4, 0.6], &Default::default()).unwrap().rows.len();
    assert_eq!((rows, v["shapes"].as_u64()), (4, Some(5)), "{v}");
    let svg = std::fs::read_to_string(&out).unwrap();
    for value in ["0 N", "0.2 N", "0.4 N", "0.6 N"] {
        assert!(svg.contains(&format!("tendon.side.tension = {value}")), "no shape labelled {value}");
    }
    let (code, _, err) = run(&["draw", &file, "--sweep", "tendon.none.tension=0:1:2", "--out", out.to_str().unwrap()]);
    assert!(code == 2 && err.contains("tendon.none.tension"), "{err}");
}

/// One shape in both dimensions: `solve --json` on a planar file and on its
/// spatial twin (the same blade and tip force, `dimension = 3`) has the
/// same keys, maps by name, and the same numbers where the plane is a
/// special case of space. Reference: the planar answer itself, to 1e-7
/// relative, as docs/mechanism-format.md promises (the spatial blade's
/// extra directions carry no load; its tip kinematics integrates by Magnus
/// steps, the planar one's by Gauss quadrature), and a
/// joint's carried load equal to the tip force (statics: nothing else acts).
#[test]
fn both_dimensions_answer_solve_in_one_shape() {
    let dir = tempfile::tempdir().unwrap();
    let blade = "[[joint]]\nname = \"blade\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\n\
                 length = 0.05\nmodulus = 2e11\nwidth = 0.01\nthickness = 2e-4\n";
    let planar = format!("{blade}[[force]]\nname = \"push\"\nbody = \"tip\"\nat = [0.0, 0.0]\nforce = [0.0, 0.5]\n");
    let spatial = format!(
        "dimension = 3\n{blade}[[force]]\nname = \"push\"\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nforce = [0.0, 0.5, 0.0]\n"
    );
    let (two, err) = answer(&["solve", &written(&dir, &planar)]);
    assert!(err.is_empty(), "{err}");
    let (three, err) = answer(&["solve", &written(&dir, &spatial)]);
    assert!(err.is_empty(), "{err}");
    let keys = |v: &Value| v.as_object().unwrap().keys().cloned().collect::<Vec<_>>();
    assert_eq!(keys(&two), keys(&three));
    assert_eq!((two["dimension"].as_u64(), three["dimension"].as_u64()), (Some(2), Some(3)));
    let near = |a: &Value, b: &Value, tolerance: f64| {
        let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
        (a - b).abs() <= tolerance * a.abs().max(b.abs()).max(1e-12)
    };
    let (p, s) = (&two["bodies"]["tip"], &three["bodies"]["tip"]);
    let pose = [("x", "x"), ("y", "y"), ("phi", "yaw")];
    assert!(pose.iter().all(|(a, b)| near(&p[*a], &s[*b], 1e-7)), "{p} {s}");
    // The root stress is a curvature, the series' derivative: its last
    // coefficient, 2 % of the first, differs by 1e-5 between the two
    // integrations (measured), so 1e-6 relative.
    assert!(near(&two["stress"]["blade"]["max"], &three["stress"]["blade"]["max"], 1e-6), "{two} {three}");
    // The blade carries the tip force, in its root frame: 0.5 N along y.
    assert!((two["load"]["blade"]["fy"].as_f64().unwrap() - 0.5).abs() < 1e-9, "{two}");
    assert!((three["load"]["blade"]["force"][1].as_f64().unwrap() - 0.5).abs() < 1e-9, "{three}");
    // Given by its stiffnesses alone, each answers the peak change of
    // curvature instead, in one shape: the plane's |κ − κ₀| and space's
    // bending |(κ_y, κ_z) − (κ_y0, κ_z0)| agree in the plane, to 1e-6 as
    // the stress above (the same series by two integrations), at the root.
    let stiff = |text: &str| {
        text.replace("modulus = 2e11\nwidth = 0.01\nthickness = 2e-4\n", "ei = 2e-3\ngj = 1e-3\nei_y = 0.1\n")
    };
    let (two, err) = answer(&["solve", &written(&dir, &stiff(&planar).replace("gj = 1e-3\nei_y = 0.1\n", ""))]);
    assert!(err.is_empty(), "{err}");
    let (three, err) = answer(&["solve", &written(&dir, &stiff(&spatial))]);
    assert!(err.is_empty(), "{err}");
    assert_eq!(keys(&two), keys(&three));
    let (a, b) = (&two["curvature_max"]["blade"], &three["curvature_max"]["blade"]);
    assert!(near(&a["max"], &b["max"], 1e-6) && a["at"] == 0.0 && b["at"] == 0.0, "{a} {b}");
}

/// A spatial flexure's `yield_strength` and `shape`, as in the plane: the
/// safety factor is the yield strength over the peak von Mises stress, and
/// the shape's last section is the tip body's placement (the flexure's own
/// Magnus sections against the mechanism's kinematics: to 1e-12 m).
#[test]
fn a_spatial_flexure_reports_its_safety_factor_and_shape() {
    let dir = tempfile::tempdir().unwrap();
    let text = "dimension = 3\n[[joint]]\nname = \"blade\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\n\
                length = 0.05\nmodulus = 2e11\nwidth = 0.01\nthickness = 2e-4\nyield_strength = 5e8\nshape = 5\n\
                [[force]]\nname = \"push\"\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nforce = [0.0, 0.5, 0.1]\n";
    let (v, err) = answer(&["solve", &written(&dir, text)]);
    assert!(err.is_empty(), "{err}");
    let max = v["stress"]["blade"]["max"].as_f64().unwrap();
    let factor = v["safety_factor"]["blade"].as_f64().unwrap();
    assert!((factor - 5e8 / max).abs() < 1e-12 * factor, "{factor} against {}", 5e8 / max);
    let shape = v["shape"]["blade"].as_array().unwrap();
    assert_eq!(shape.len(), 5);
    let last = &shape[4];
    let tip = &v["bodies"]["tip"];
    for axis in ["x", "y", "z"] {
        let (a, b) = (last[axis].as_f64().unwrap(), tip[axis].as_f64().unwrap());
        assert!((a - b).abs() < 1e-12, "{axis}: {a} against {b}");
    }
    // Past its yield strength it warns, as the plane does.
    let weak = text.replace("yield_strength = 5e8", "yield_strength = 1e6");
    let (code, _, err) = run(&["solve", &written(&dir, &weak)]);
    assert_eq!(code, 0);
    assert!(
        err.contains("flexure joint \"blade\": the peak stress") && err.contains("exceeds the yield strength"),
        "{err}"
    );
}
