//! Every shipped example with every mechanism subcommand that applies to it
//! (issue 13, item 9), typed as a newcomer would (`solve`, `solve --sweep`,
//! `solve --compliance`, `buckle`, `draw`, `draw --sweep`), run in-process
//! through `flexure_cli::run`. Each pair either exits 0 with a finite answer
//! and no warning, or exits 2 with the reason its example's header comment
//! gives; the commands its closing comment shows are the ones run here.
//! Then the answers with an independent reference are held to it.

use flexure::model::Model;
use serde_json::Value;
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::{Path, PathBuf};

fn examples_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn file(name: &str) -> String {
    examples_dir().join(format!("{name}.toml")).display().to_string()
}

use crate::cli::run;

/// The answer to `args --json`, which must exit 0 without a warning.
fn json(args: &[&str]) -> Value {
    let mut a = args.to_vec();
    a.push("--json");
    let (code, out, err) = run(&a);
    assert!(code == 0 && warned(&err).is_empty(), "{args:?}: exit {code}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: {e}: {out}"))
}

/// What stderr says beyond notes (`note: …`, such as the four-bar's pin,
/// open at rest with `preload = true`): warnings and errors.
fn warned(stderr: &str) -> Vec<&str> {
    stderr.lines().filter(|l| !l.starts_with("note: ")).collect()
}

/// The answer to `args --json` whose estimate misses the default 1 %
/// target: exit 0, `flagged`, and a warning saying so, nothing else.
fn flagged_json(args: &[&str]) -> Value {
    let mut a = args.to_vec();
    a.push("--json");
    let (code, out, err) = run(&a);
    assert!(code == 0 && err.contains("estimated error") && warned(&err).len() == 1, "{args:?}: exit {code}: {err}");
    let v: Value = serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: {e}: {out}"));
    assert_eq!(v["flagged"], Value::Bool(true), "{args:?}");
    v
}

/// An example's comments as one line of words: its header (the leading
/// `#` lines), or all of them (with the closing "Running it" block).
fn comments(name: &str, header_only: bool) -> String {
    let text = std::fs::read_to_string(file(name)).unwrap();
    let lines: Vec<&str> = if header_only {
        text.lines().take_while(|l| l.starts_with('#')).collect()
    } else {
        text.lines().filter(|l| l.starts_with('#')).collect()
    };
    lines.iter().flat_map(|l| l.trim_start_matches('#').split_whitespace()).collect::<Vec<_>>().join(" ")
}

/// What a subcommand must do with an example.
#[derive(Clone, Copy, Debug)]
enum Expect {
    Answers,
    /// Answers, flagged with a warning: its estimate misses the 1 % target
    /// (order 3's guided legs buckle 1.3 % above the beam's load).
    Flagged,
    /// Exit 2, nothing on stdout, this on stderr, and the header saying it.
    Refused(&'static str),
}

struct Example {
    name: &'static str,
    /// `PARAMETER=FROM:TO:COUNT` over one of its loads.
    sweep: &'static str,
    /// `--compliance BODY --at X,Y`: where its load acts, or its tip.
    compliance: (&'static str, &'static str),
    /// What `solve --compliance` does (it answers with contacts held).
    compliance_expect: Expect,
    buckle: Expect,
}

const EXAMPLES: [Example; 9] = [
    Example {
        name: "finger",
        sweep: "tendon.flexor.tension=0:6:4",
        compliance: ("distal", "0.025,0"),
        compliance_expect: Expect::Answers,
        buckle: Expect::Answers,
    },
    Example {
        name: "finger_dynamics",
        sweep: "tendon.flexor.tension=0:6:4",
        compliance: ("distal", "0.025,0"),
        compliance_expect: Expect::Answers,
        buckle: Expect::Answers,
    },
    Example {
        name: "four_bar",
        sweep: "tendon.pull.tension=0:1.5:4",
        compliance: ("output", "0.04,0"),
        compliance_expect: Expect::Answers,
        buckle: Expect::Answers,
    },
    Example {
        name: "four_leg_stage",
        sweep: "force.push.fx=0:2:3",
        compliance: ("stage", "0,-0.06"),
        compliance_expect: Expect::Answers,
        buckle: Expect::Flagged,
    },
    // A pure moment adds no geometric stiffness: see the file's header.
    // Its rod and pads may touch: buckling does not apply.
    Example {
        name: "grasp",
        sweep: "tendon.flexor.tension=0:4:9",
        compliance: ("distal", "0.025,0"),
        // Its distal pad slides on the rod at the file's tension.
        compliance_expect: Expect::Refused("no linear answer"),
        buckle: Expect::Refused("may touch"),
    },
    Example {
        name: "mixed_chain",
        sweep: "force.grip.moment=0:0.01:3",
        compliance: ("hand", "0.02,0"),
        compliance_expect: Expect::Answers,
        buckle: Expect::Refused("no buckling load"),
    },
    Example {
        name: "paper_tendon",
        sweep: "tendon.flexor.tension=0:28:5",
        compliance: ("link", "0,0.005"),
        compliance_expect: Expect::Answers,
        buckle: Expect::Answers,
    },
    Example {
        name: "parallelogram",
        sweep: "force.push.fy=0:-1:2",
        compliance: ("stage", "0,-0.02"),
        compliance_expect: Expect::Answers,
        buckle: Expect::Flagged,
    },
    Example {
        name: "tapered_finger",
        sweep: "tendon.flexor.tension=0:8:5",
        compliance: ("distal", "0.02,0"),
        compliance_expect: Expect::Answers,
        buckle: Expect::Answers,
    },
];

fn count(sweep: &str) -> usize {
    sweep.rsplit(':').next().unwrap().parse().unwrap()
}

/// The `null`s in `v` (serde_json's stand-in for NaN and ±∞), by path.
fn nulls(v: &Value, path: &str, found: &mut Vec<String>) {
    match v {
        Value::Null => found.push(path.to_string()),
        Value::Array(a) => a.iter().enumerate().for_each(|(i, x)| nulls(x, &format!("{path}[{i}]"), found)),
        Value::Object(o) => o.iter().for_each(|(k, x)| nulls(x, &format!("{path}.{k}"), found)),
        _ => {}
    }
}

fn matrix(v: &Value) -> Vec<Vec<f64>> {
    v.as_array().unwrap().iter().map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()).collect()
}

/// The sweep table's column `name` in row `row`.
fn cell(v: &Value, row: usize, name: &str) -> f64 {
    let columns = v["columns"].as_array().unwrap();
    let i = columns.iter().position(|c| c == name).unwrap_or_else(|| panic!("no column {name}"));
    v["rows"][row][i].as_f64().unwrap()
}

/// What each kind of answer must hold besides being finite.
fn check_answer(what: &str, ex: &Example, v: &Value, out: &Path) {
    match what {
        "solve" => assert_eq!(v["stable"], true, "{}: {v}", ex.name),
        "solve --sweep" => {
            let rows = v["rows"].as_array().unwrap();
            assert_eq!(rows.len(), count(ex.sweep), "{}: every value reached stably", ex.name);
            assert!(v.get("stability_limit").is_none() && v.get("flagged").is_none(), "{}: {v}", ex.name);
        }
        "solve --compliance" => {
            // C = J K⁻¹ Jᵀ with K positive definite: symmetric, no negative diagonal.
            let c = matrix(&v["compliance"]);
            let scale = c.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
            for i in 0..3 {
                assert!(c[i][i] >= -1e-12 * scale, "{}: {c:?}", ex.name);
                for j in 0..3 {
                    assert!((c[i][j] - c[j][i]).abs() <= 1e-9 * scale, "{}: {c:?}", ex.name);
                }
            }
        }
        "buckle" => {
            assert!(v["load_factor"].as_f64().unwrap() > 0.0, "{}: {v}", ex.name);
            let mode = v["mode"].as_array().unwrap();
            assert!(mode.iter().any(|x| x.as_f64().unwrap() != 0.0), "{}: {v}", ex.name);
        }
        "draw" | "draw --sweep" => {
            let shapes = if what == "draw" { 2 } else { count(ex.sweep) + 1 };
            assert_eq!(v["shapes"].as_u64(), Some(shapes as u64), "{}: {v}", ex.name);
            let svg = std::fs::read_to_string(out).unwrap_or_else(|e| panic!("{}: {}: {e}", ex.name, out.display()));
            assert!(svg.contains("<svg") && svg.trim_end().ends_with("</svg>"), "{}: not an SVG", ex.name);
        }
        _ => unreachable!(),
    }
}

/// Each example, each subcommand: an answer, or the refusal its header states.
#[test]
fn every_example_with_every_subcommand() {
    let dir = tempfile::tempdir().unwrap();
    let mut outcomes = Vec::new();
    for ex in &EXAMPLES {
        let path = file(ex.name);
        let (head, all) = (comments(ex.name, true), comments(ex.name, false));
        // The comments show the commands run here.
        for shown in
            [format!("--sweep {}", ex.sweep), format!("--compliance {} --at {}", ex.compliance.0, ex.compliance.1)]
        {
            assert!(all.contains(&shown), "{}: the comments do not show {shown:?}", ex.name);
        }
        let (body, at) = ex.compliance;
        let out = dir.path().join(format!("{}.svg", ex.name));
        let out_sweep = dir.path().join(format!("{}-sweep.svg", ex.name));
        let (out_str, out_sweep_str) = (out.display().to_string(), out_sweep.display().to_string());
        let pairs: [(&str, Vec<&str>, Expect, &Path); 6] = [
            ("solve", vec!["solve", &path], Expect::Answers, &out),
            ("solve --sweep", vec!["solve", &path, "--sweep", ex.sweep], Expect::Answers, &out),
            ("solve --compliance", vec!["solve", &path, "--compliance", body, "--at", at], ex.compliance_expect, &out),
            ("buckle", vec!["buckle", &path], ex.buckle, &out),
            ("draw", vec!["draw", &path, "--out", &out_str], Expect::Answers, &out),
            (
                "draw --sweep",
                vec!["draw", &path, "--out", &out_sweep_str, "--sweep", ex.sweep],
                Expect::Answers,
                &out_sweep,
            ),
        ];
        for (what, mut args, expect, written) in pairs {
            args.push("--json");
            let (code, stdout, stderr) = run(&args);
            match expect {
                Expect::Answers => {
                    assert!(code == 0 && warned(&stderr).is_empty(), "{} {what}: exit {code}: {stderr}", ex.name);
                    let v: Value = serde_json::from_str(&stdout).unwrap();
                    let mut found = Vec::new();
                    nulls(&v, "", &mut found);
                    assert!(found.is_empty(), "{} {what}: not finite: {found:?}", ex.name);
                    check_answer(what, ex, &v, written);
                }
                Expect::Flagged => {
                    assert!(
                        code == 0 && stderr.contains("estimated error"),
                        "{} {what}: exit {code}: {stderr}",
                        ex.name
                    );
                    let v: Value = serde_json::from_str(&stdout).unwrap();
                    assert_eq!(v["flagged"], Value::Bool(true), "{} {what}", ex.name);
                    check_answer(what, ex, &v, written);
                }
                Expect::Refused(reason) => {
                    assert_eq!(code, 2, "{} {what}: {stdout}", ex.name);
                    assert!(stdout.is_empty(), "{} {what}: {stdout}", ex.name);
                    assert!(stderr.contains(reason), "{} {what}: {stderr}", ex.name);
                    assert!(
                        head.contains(&format!("`{what}` does not apply")) && head.contains(reason),
                        "{} {what}: the header must say why: {reason:?}",
                        ex.name
                    );
                }
            }
            outcomes.push(format!("{} {what}: {expect:?}", ex.name));
        }
    }
    assert_eq!(outcomes.len(), 54, "{outcomes:#?}");
}

/// No example escapes the table above.
#[test]
fn the_table_names_every_example() {
    let mut shipped: Vec<String> = std::fs::read_dir(examples_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        // The spatial examples (`dimension = 3`) have their own tests (tests/spatial_mechanism.rs).
        .filter(|p| !std::fs::read_to_string(p).unwrap().contains("dimension = 3"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    shipped.sort();
    let tested: Vec<&str> = EXAMPLES.iter().map(|e| e.name).collect();
    assert_eq!(shipped, tested);
}

/// Lateral stiffness of a clamped–guided beam under compression `p`
/// (beam-column: two cantilevers of L/2 with a tip force, Timoshenko & Gere,
/// Theory of Elastic Stability, §1.11): δ/F = (2 tan(kL/2)/k − L)/p, k² = p/EI;
/// 12 EI/L³ as p → 0.
fn guided_stiffness(p: f64, ei: f64, l: f64) -> f64 {
    let k = (p / ei).sqrt();
    p / (2.0 * (k * l / 2.0).tan() / k - l)
}

/// Legs of the stages: L = 0.05 m, EI = 2e-3 N·m².
const LEG: (f64, f64) = (0.05, 2.0e-3);

/// Table I, guided: the three-term model buckles at 10 EI/L², 1.32 % above
/// Euler's π² EI/L². Its lateral stiffness falls from the same 12 EI/L³ to
/// zero at that load, so under a push p it is high by at most about
/// 1.32 % · p/P_cr: the tolerance of the loaded stiffness checks.
const GUIDED_EXCESS: f64 = 0.0132;

/// The parallelogram: lateral stiffness 24 EI/L³ unloaded (exact for the
/// model: linear curvature is in its basis), the beam-column's under the
/// file's 1 N push, and buckling at 2 × 10 EI/L² (Table I, model).
#[test]
fn parallelogram_stiffness_and_buckling() {
    let (l, ei) = LEG;
    let f = file("parallelogram");
    let v = json(&["solve", &f, "--sweep", "force.push.fy=0:-1:2", "--compliance", "stage", "--at", "0,-0.02"]);
    let unloaded = 1.0 / cell(&v, 0, "compliance.xx");
    assert!((unloaded / (24.0 * ei / l.powi(3)) - 1.0).abs() < 1e-9, "{unloaded}");
    // Each leg carries half of the 1 N; P_cr = 16 N.
    let loaded = 1.0 / cell(&v, 1, "compliance.xx");
    let beam = 2.0 * guided_stiffness(0.5, ei, l);
    assert!(loaded >= beam && loaded / beam - 1.0 < GUIDED_EXCESS / 16.0, "{loaded} vs {beam}");
    // The centred push below buckling moves nothing: the legs are inextensible.
    let s = json(&["solve", &f]);
    assert!(s["bodies"]["stage"]["x"].as_f64().unwrap().abs() < 1e-12 && s["energy"].as_f64().unwrap() < 1e-20);
    // 1.3 % above the beam's 2π² EI/L²: flagged.
    let b = flagged_json(&["buckle", &f])["load_factor"].as_f64().unwrap();
    assert!((b / (2.0 * 10.0 * ei / (l * l)) - 1.0).abs() < 1e-9, "{b}");
}

/// The four-leg stage: at fx = 0 of its sweep the legs are straight under
/// the 10 N push, and its lateral stiffness is four beam-columns' (48 EI/L³
/// softened by 2.5 N each); it slides level; it buckles at 4 × 10 EI/L².
#[test]
fn four_leg_stage_stiffness_and_buckling() {
    let (l, ei) = LEG;
    let f = file("four_leg_stage");
    let v = json(&["solve", &f, "--sweep", "force.push.fx=0:2:3", "--compliance", "stage", "--at", "0,-0.06"]);
    let k = 1.0 / cell(&v, 0, "compliance.xx");
    let beam = 4.0 * guided_stiffness(2.5, ei, l);
    assert!(48.0 * ei / l.powi(3) > beam);
    assert!(k >= beam && k / beam - 1.0 < GUIDED_EXCESS * 10.0 / 32.0, "{k} vs {beam}");
    // Welded parallel legs keep the stage level; the lateral load pushes it along +x.
    for row in 0..3 {
        assert!((cell(&v, row, "stage.phi") - FRAC_PI_2).abs() < 1e-9);
    }
    let x = [0, 1, 2].map(|row| cell(&v, row, "stage.x"));
    assert!(x[0].abs() < 1e-12 && x[1] > 1e-4 && x[2] > x[1], "{x:?}");
    // 1.3 % above the beam's 4π² EI/L²: flagged.
    let b = flagged_json(&["buckle", &f])["load_factor"].as_f64().unwrap();
    assert!((b * 10.0 / (4.0 * 10.0 * ei / (l * l)) - 1.0).abs() < 1e-9, "{b}");
}

/// The mixed chain under a pure end moment M: each joint turns by M times
/// its compliance (1/k for the spring, L/EI for a flexure bent into an arc),
/// so the hand turns M · 50.5 rad and its rotational compliance is 50.5
/// rad/(N·m) whatever M is. Exact for the model (constant curvature is in
/// its basis): to rounding.
#[test]
fn mixed_chain_turns_by_its_compliances() {
    let per_moment = 1.0 / 2.0 + 0.02 / 1.0e-3 + 0.015 / 5.0e-4;
    let f = file("mixed_chain");
    let v = json(&["solve", &f, "--sweep", "force.grip.moment=0:0.01:3"]);
    for row in 0..3 {
        let m = cell(&v, row, "force.grip.moment");
        assert!((cell(&v, row, "hand.phi") - per_moment * m).abs() < 1e-12, "row {row}");
        assert!(cell(&v, row, "slide[0]").abs() < 1e-12, "the slider's spring carries nothing");
    }
    let c = matrix(&json(&["solve", &f, "--compliance", "hand", "--at", "0.02,0"])["compliance"]);
    assert!((c[0][0] / per_moment - 1.0).abs() < 1e-9, "{c:?}");
}

/// Linearised about the straight flexure, a tendon of tension T anchored a
/// behind the flexure's root (and offset from it) pulls the tip toward the
/// anchor: to second order its potential T·(length) adds −(T/2)∫w'² + T w(L)²/(2(L + a)),
/// a dead compression T with a lateral spring T/(L + a) at the tip (the offset
/// gives only the first-order moment). Clamped at the root, the Euler problem
/// EI w'' + T w = T w(L) (x + a)/(L + a) then buckles at tan(kL) = −k a,
/// k² = T/EI: kL = π when a = 0. The model, a Ritz reduction, can only
/// buckle later; for one half wave its excess is within Table I's 1.32 %.
fn tendon_euler_load(a: f64, l: f64, ei: f64) -> f64 {
    // sin z + (a/L) z cos z falls from 1 to −1 across (π/2, 3π/2), through
    // its one root there (in (π/2, π] for a ≥ 0): bisection.
    let g = |z: f64| z.sin() + a / l * z * z.cos();
    let (mut lo, mut hi) = (FRAC_PI_2, 1.5 * PI);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if g(lo) * g(mid) <= 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let z = 0.5 * (lo + hi);
    z * z * ei / (l * l)
}

/// The tendon examples' `buckle` against [`tendon_euler_load`].
#[test]
fn tendon_buckling_against_the_beam() {
    // Eq. 25: the paper's steel flexure, 15 mm; its tendon anchored at the root (a = 0), 28 N.
    let ei = 200e9 / (1.0 - 0.29_f64.powi(2)) * 0.01 * 0.0002_f64.powi(3) / 12.0;
    let euler = tendon_euler_load(0.0, 0.015, ei);
    assert!((euler - PI * PI * ei / (0.015 * 0.015)).abs() < 1e-9 * euler);
    let f = file("paper_tendon");
    let t = 28.0 * json(&["buckle", &f])["load_factor"].as_f64().unwrap();
    assert!(t >= euler && t / euler - 1.0 < GUIDED_EXCESS, "{t} vs {euler}");
    // Fig. 10: about 28 N turns it to a right angle (read off a plot: 2°).
    let v = json(&["solve", &f, "--sweep", "tendon.flexor.tension=0:28:5"]);
    assert!((cell(&v, 4, "link.phi").to_degrees() - 90.0).abs() < 2.0);

    // The finger: its mcp flexure (15 mm, EI 1.4558e-3) buckles alone: its
    // tendon is anchored 10 mm behind the root, the pip's at its own root
    // (68 N, beyond), and the tip force adds no stiffness about straight links.
    let euler = tendon_euler_load(0.01, 0.015, 1.4558e-3);
    let t = 6.0 * json(&["buckle", &file("finger")])["load_factor"].as_f64().unwrap();
    assert!(t >= euler && t / euler - 1.0 < GUIDED_EXCESS, "{t} vs {euler}");
}

/// The four-bar's pin holds: the coupler's end and the output's top, each
/// placed from its body's reported pose, are one point, along the sweep too
/// (closures are solved to rounding; 1 nm is 1e-7 of the 10 mm hinges).
#[test]
fn four_bar_pin_holds() {
    let f = file("four_bar");
    let point = |x: f64, y: f64, phi: f64| [x + 0.04 * phi.cos(), y + 0.04 * phi.sin()];
    let s = json(&["solve", &f]);
    let pose = |b: &str| ["x", "y", "phi"].map(|k| s["bodies"][b][k].as_f64().unwrap());
    let ([cx, cy, cp], [ox, oy, op]) = (pose("coupler"), pose("output"));
    let (a, b) = (point(cx, cy, cp), point(ox, oy, op));
    assert!((a[0] - b[0]).hypot(a[1] - b[1]) < 1e-9, "{a:?} {b:?}");
    let v = json(&["solve", &f, "--sweep", "tendon.pull.tension=0:1.5:4"]);
    for row in 0..4 {
        let c = |b: &str| {
            point(
                cell(&v, row, &format!("{b}.x")),
                cell(&v, row, &format!("{b}.y")),
                cell(&v, row, &format!("{b}.phi")),
            )
        };
        let (a, b) = (c("coupler"), c("output"));
        assert!((a[0] - b[0]).hypot(a[1] - b[1]) < 1e-9, "row {row}: {a:?} {b:?}");
    }
}

/// A mechanism file without its `[[geom]]` tables (the grasp's come last,
/// before its closing comments).
fn without_geoms(text: &str) -> String {
    text.split("[[geom]]").next().unwrap().to_string()
}

/// Every number of the bodies' poses in a solve answer (a spatial one's rotation too).
fn poses(v: &Value) -> Vec<f64> {
    fn numbers(v: &Value, out: &mut Vec<f64>) {
        match v {
            Value::Number(n) => out.push(n.as_f64().unwrap()),
            Value::Array(a) => a.iter().for_each(|x| numbers(x, out)),
            Value::Object(o) => o.values().for_each(|x| numbers(x, out)),
            _ => {}
        }
    }
    let mut out = Vec::new();
    numbers(&v["bodies"], &mut out);
    out
}

/// Reference for a contact file's answer `v` (of file `text`): each
/// touching contact's force applied back as a plain `[[force]]`, the geoms
/// removed, solves to the same equilibrium. The ground's geom pushes the
/// pad's body with N·n (n out of the ground's geom) and its friction
/// force there: a force at that point in the body's
/// frame (from its reported pose: `x`, `y`, `phi` or `rotation`).
/// Checked to 1e-9 m and rad on every pose number: both are solved to
/// Newton's tolerance, far below; the grasp's force made 0.1 % larger
/// moves its distal link by 50 µm and 1.3 mrad (tried), so the check can fail.
fn balances_its_contact_forces(text: &str, v: &Value, dir: &Path) {
    let m = Model::from_toml(text).unwrap();
    let touching: Vec<&Value> = v["contacts"].as_array().unwrap().iter().filter(|c| c["state"] != "open").collect();
    assert!(!touching.is_empty(), "it must touch under its own load: {v}");
    let spatial = v["dimension"] == 3;
    let mut loads = String::new();
    for (i, c) in touching.iter().enumerate() {
        // The object on the ground is the geom touched; the pad's body touches it,
        // pushed along the object's outward normal.
        let grounded = match &m {
            Model::Planar(m) => m.geoms.iter().any(|g| g.name == c["geom"] && g.body == 0),
            Model::Spatial(m) => m.geoms.iter().any(|g| g.name == c["geom"] && g.body == 0),
        };
        assert!(grounded && c["body"] != "ground", "{c}: a pad touches the object on the ground");
        let body = c["body"].as_str().unwrap();
        let b = &v["bodies"][body];
        let n = c["normal_force"].as_f64().unwrap();
        let point: Vec<f64> = c["point"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        // N·n and the friction on the pad's body.
        let friction = c["friction_force"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap());
        let normal = c["normal"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap());
        let force: Vec<f64> = normal.zip(friction).map(|(x, f)| n * x + f).collect();
        let origin: Vec<f64> = ["x", "y", "z"].iter().take(point.len()).map(|k| b[k].as_f64().unwrap()).collect();
        let d: Vec<f64> = point.iter().zip(&origin).map(|(p, o)| p - o).collect();
        // Into the body's frame: Rᵀ d.
        let at: Vec<f64> = if spatial {
            let r = |i: usize, j: usize| b["rotation"][i][j].as_f64().unwrap();
            (0..3).map(|j| (0..3).map(|i| r(i, j) * d[i]).sum()).collect()
        } else {
            let phi = b["phi"].as_f64().unwrap();
            vec![phi.cos() * d[0] + phi.sin() * d[1], -phi.sin() * d[0] + phi.cos() * d[1]]
        };
        let list = |x: &[f64]| x.iter().map(|v| format!("{v:e}")).collect::<Vec<_>>().join(", ");
        loads += &format!(
            "\n[[force]]\nname = \"contact{i}\"\nbody = \"{body}\"\nat = [{}]\nforce = [{}]\n",
            list(&at),
            list(&force)
        );
    }
    let bare = dir.join("bare.toml");
    std::fs::write(&bare, without_geoms(text) + &loads).unwrap();
    let free = json(&["solve", bare.to_str().unwrap()]);
    let (a, b) = (poses(v), poses(&free));
    assert_eq!(a.len(), b.len());
    assert!(a.iter().zip(&b).all(|(p, q)| (p - q).abs() < 1e-9), "{a:?} with contact, {b:?} loaded");
}

/// The grasp held to what contact means, not to its own earlier output:
/// (a) each touching contact's force, normal and friction, applied back as
/// a plain load, makes the mechanism without its geoms rest where the grasp
/// does; (b) before the first contact the sweep is the sweep without geoms;
/// (c) a touching contact's gap is zero and an open one's positive; (d) its
/// friction is on Coulomb's cone where it slides, inside it where it sticks.
#[test]
fn the_grasp_balances_its_contact_forces() {
    let path = file("grasp");
    let text = std::fs::read_to_string(&path).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let bare = dir.path().join("bare.toml");
    let v = json(&["solve", &path]);
    let contacts = v["contacts"].as_array().unwrap();
    // (c) Touching: the gap solved to zero, 1e-10 of the 0.08 m finger
    // (the solver's contact tolerance is 1e-10 of the size, a bound on it).
    // Open: apart.
    let size = 0.08;
    for c in contacts {
        let gap = c["gap"].as_f64().unwrap();
        match c["state"].as_str().unwrap() {
            "open" => assert!(gap > 0.0 && c["normal_force"].as_f64().unwrap() == 0.0, "{c}"),
            _ => assert!(gap.abs() < 1e-10 * size && c["normal_force"].as_f64().unwrap() > 0.0, "{c}"),
        }
    }
    // (a) At 4 N the distal pad presses the rod.
    balances_its_contact_forces(&text, &v, dir.path());
    // (b) The rows before the first contact (every normal force 0) are the
    // sweep without geoms: the same equilibria, to 1e-9 m and rad.
    let sweep = "tendon.flexor.tension=0:4:9";
    let with = json(&["solve", &path, "--sweep", sweep]);
    std::fs::write(&bare, without_geoms(&text)).unwrap();
    let plain = json(&["solve", bare.to_str().unwrap(), "--sweep", sweep]);
    let forces: Vec<&str> = with["columns"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|c| c.as_str())
        .filter(|c| c.starts_with("contact."))
        .collect();
    let first = (0..9).find(|&r| forces.iter().any(|c| cell(&with, r, c) > 0.0)).unwrap();
    assert!(first >= 2, "the sweep must show rows before the first contact: {first}");
    // Then the first contact's force grows before the distal pad takes over.
    for r in 0..first {
        for body in ["proximal", "distal"] {
            for k in ["x", "y", "phi"] {
                let name = format!("{body}.{k}");
                let (a, b) = (cell(&with, r, &name), cell(&plain, r, &name));
                assert!((a - b).abs() < 1e-9, "row {r}, {name}: {a} with geoms, {b} without");
            }
        }
    }
    let proximal = "contact.cylinder.proximal.normal_force";
    assert!(cell(&with, first + 1, proximal) > cell(&with, first, proximal), "the squeeze grows");
    let distal = "contact.cylinder.distal.normal_force";
    let last = (0..9).map(|r| cell(&with, r, distal)).collect::<Vec<_>>();
    assert!(last[8] > last[7] && last[7] > last[6] && last[6] > 0.0, "the distal pad squeezes harder: {last:?}");
    // (d) Each row's contacts (μ = 0.5): a sliding pad's friction is μN, a
    // stuck one's within it (to 1e-9 of N); both happen along the sweep.
    let mut states = Vec::new();
    for (r, row) in with["contacts"].as_array().unwrap().iter().enumerate() {
        assert_eq!(row["value"], with["rows"][r][0], "each row's contacts by its value");
        for c in row["contacts"].as_array().unwrap().iter().filter(|c| c["state"] != "open") {
            let n = c["normal_force"].as_f64().unwrap();
            let f =
                c["friction_force"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap().powi(2)).sum::<f64>().sqrt();
            match c["state"].as_str().unwrap() {
                "slip" => assert!((f - 0.5 * n).abs() < 1e-9 * n, "{c}"),
                _ => assert!(f <= 0.5 * n * (1.0 + 1e-9), "{c}"),
            }
            states.push(c["state"].as_str().unwrap().to_string());
        }
    }
    assert!(states.iter().any(|s| s == "stick") && states.iter().any(|s| s == "slip"), "{states:?}");
}

/// The grasp's drawing shows its rod, its pads' contacts and their forces:
/// the geoms named in the legend, each touching contact's entry and its
/// value in N beside its arrow (the solve's own normal force, to its four
/// digits); `--simulate` is refused (it has no mass).
#[test]
fn the_grasp_is_drawn_with_its_contacts() {
    let path = file("grasp");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("grasp.svg");
    json(&["draw", &path, "--out", out.to_str().unwrap()]);
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("geom: cylinder (circle), proximal_pad (box), distal_pad (box)"), "the geoms' key");
    assert!(svg.contains(">cylinder<"), "the rod named beside it");
    let v = json(&["solve", &path]);
    for c in v["contacts"].as_array().unwrap().iter().filter(|c| c["state"] != "open") {
        let n = c["normal_force"].as_f64().unwrap();
        let value = format!("{:.4}", n).trim_end_matches('0').to_string();
        assert!(svg.contains(&format!(">{value} N<")), "{c}: its value {value} N beside its arrow");
        let (geom, body) = (c["geom"].as_str().unwrap(), c["body"].as_str().unwrap());
        assert!(svg.contains(&format!("contact {geom} on {body}: normal force")), "{c}: its legend");
    }
    // The sweep draws the first contact's range from 0.
    let out = dir.path().join("grasp-sweep.svg");
    json(&["draw", &path, "--out", out.to_str().unwrap(), "--sweep", "tendon.flexor.tension=0:4:9"]);
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("contact cylinder on proximal: normal force 0 to "), "the sweep's contacts");
    // The grasp has no mass: `draw --simulate` refuses it for that, writing nothing.
    let out = dir.path().join("grasp-motion.svg");
    let (code, stdout, err) = run(&["draw", &path, "--out", out.to_str().unwrap(), "--simulate", "0.01"]);
    assert!(code == 2 && stdout.is_empty() && err.contains("nothing moves") && !out.exists(), "{code}: {err}");
}

/// The commands an example's closing comment lists (`#   flexure …`),
/// its path and `--out` files made absolute (the outputs in `dir`).
fn listed(name: &str, dir: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(file(name)).unwrap();
    let commands = text.lines().filter_map(|l| l.strip_prefix("#   flexure "));
    let args = |line: &str| {
        let mut out: Vec<String> = Vec::new();
        for word in line.split_whitespace() {
            let word = match out.last().map(String::as_str) {
                Some("--out") => dir.join(word).display().to_string(),
                _ if word == format!("examples/{name}.toml") => file(name),
                _ => word.to_string(),
            };
            out.push(word);
        }
        out
    };
    commands.map(args).collect()
}

/// The spatial grasp: every command its closing comment lists answers
/// without a warning (draws write an SVG with the ball and the pad's
/// contact), `solve --compliance` answers with the contact held, `buckle` is
/// refused as its header says, and its contact force balances (as the
/// planar grasp's).
#[test]
fn the_spatial_grasp_runs_its_commands_and_balances() {
    let dir = tempfile::tempdir().unwrap();
    let commands = listed("grasp3d", dir.path());
    assert_eq!(commands.len(), 5, "{commands:?}");
    for args in &commands {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let v = json(&args);
        if args[0] == "draw" {
            let svg = std::fs::read_to_string(v["out"].as_str().unwrap()).unwrap();
            assert!(svg.contains("geom: ball (sphere), distal_pad (box)"), "{args:?}: the geoms' key");
            assert!(svg.contains("contact ball on distal: normal force"), "{args:?}: the contact");
        }
    }
    let path = file("grasp3d");
    let head = comments("grasp3d", true);
    let held = json(&["solve", &path, "--compliance", "distal", "--at", "0.025,0,0"]);
    assert!(held["compliance"].as_array().is_some_and(|rows| rows.len() == 6), "{held}");
    let what = "buckle";
    let (code, out, err) = run(&["buckle", &path]);
    assert!(code == 2 && out.is_empty() && err.contains("may touch"), "{what}: {code} {err}");
    // The pair names itself: no option `--geom` was given.
    assert!(err.contains("error: ") && err.contains(": geom \"ball\" (sphere) and "), "{what}: {err}");
    assert!(head.contains(&format!("`{what}` does not apply")) && head.contains("may touch"), "{what}");
    let text = std::fs::read_to_string(&path).unwrap();
    let v = json(&["solve", &path]);
    // The ball leans the normal out of the finger's plane (out of the ball,
    // toward −z): 0.42 at 3 N, as the header says (25°).
    let c = v["contacts"].as_array().unwrap().iter().find(|c| c["state"] != "open").unwrap();
    let nz = -c["normal"][2].as_f64().unwrap();
    assert!((nz.asin().to_degrees() - 25.0).abs() < 1.0, "{c}");
    balances_its_contact_forces(&text, &v, dir.path());
}
