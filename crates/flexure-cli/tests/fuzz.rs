//! Seeded fuzzing of the command line and the library.
//!
//! Five families of random cases, each generated from its own seed so that
//! any failure is reproduced by its printed command line or call:
//! - `argv`: random subcommands, options and values (0, negatives, 1e300,
//!   nan, inf, huge integers, garbage, missing values), run in-process
//!   through `flexure_cli::run`;
//! - `files`: the mechanism examples mutated (lines deleted, duplicated,
//!   swapped; numbers replaced by 0, −1, 1e300, nan; keys renamed; text
//!   truncated) and run through `solve`, `buckle`, `draw` and `modes`;
//! - `modes`: random single-joint `modes` command lines (their own family,
//!   run with `argv`'s test);
//! - `library`: library functions called directly with random values;
//! - `motion`: the examples mutated, with random `[[schedule]]` tables
//!   (ramps, steps, harmonics, edge values) and `[initial]` states
//!   appended, through `simulate` and `draw --simulate` with a bounded
//!   step budget;
//! - `process`: a smaller sample of `argv` cases run as real processes, to
//!   check the exit status end to end, killed if they outlive the bound.
//!
//! Every case must: not panic; finish within [`WORK_BUDGET`] solver
//! iterations (counted through the solver's interrupt hook, which stops it
//! there, so no verdict depends on the machine's speed or load), and never
//! hang (a case that makes no progress for [`HANG_WATCHDOG`] is reported);
//! exit
//! with 0 or 2, a failure carrying a message on stderr; print only finite
//! numbers (no `null`, `NaN` or `inf`), and a library `Ok` holds only
//! finite numbers. Each test prints a summary line (`cargo test -p
//! flexure-cli --test all fuzz:: -- --include-ignored --nocapture`: the two
//! long ones are `#[ignore]`d, run by `.ci/run`): the cases per family and
//! the failures, grouped by kind with a reproducing case each.

use flexure::kinematics::{Level, backbone, par_poses_root_tip};
use flexure::reference::{compliance as exact_compliance, elastica};
use flexure::tendon::{TendonData, TendonOffsets, pull};
use flexure::{
    Flexure, Kinematics, Pose, StaticsData, TipConstraint, TipLoad, bending_stiffness, buckling_load,
    compliance_tip_rest, connect::connect, deflect, energy, energy_gradient, update_kinematics,
};
use serde_json::Value;
use std::cell::{Cell, RefCell};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::sync::{Arc, Once};
use std::time::Duration;

/// The seed of every family (change it to explore; keep it fixed in CI).
const SEED: u64 = 0x5EED_F1E7_0002;
/// A case whose solvers poll the interrupt hook more often than this (Newton
/// iterations, continuation steps, integrator iterations, together) is
/// stopped there, and fails: no answer should cost a user this much. The
/// costliest case of these seeds takes about 55 000 (a `connect` of the
/// `library` family); the costliest command line about 23 000.
const WORK_BUDGET: u64 = 200_000;
/// Not a time limit on any case: only a case that ignores the interrupt
/// hook and returns nothing for this long (a hang) is reported, so the test
/// ends instead of blocking the run. No legitimate case comes near it.
const HANG_WATCHDOG: Duration = Duration::from_secs(300);

const ARGV_CASES: usize = 8000;
const FILE_CASES: usize = 3000;
const LIBRARY_CASES: usize = 5000;
const PROCESS_CASES: usize = 300;
const MODES_CASES: usize = 1000;
const MOTION_CASES: usize = 300;

// ---------------------------------------------------------------- random

/// SplitMix64: small, seeded, and the same on every platform.
struct Rng(u64);

impl Rng {
    fn for_case(family: u64, case: usize) -> Self {
        let mut r =
            Rng(SEED ^ family.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ (case as u64).wrapping_mul(0xD1B5_4A32_D192_ED03));
        r.next();
        r
    }
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn uniform(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }
    /// An index drawn with the given weights.
    fn weighted(&mut self, weights: &[usize]) -> usize {
        let mut x = self.below(weights.iter().sum());
        for (i, &w) in weights.iter().enumerate() {
            if x < w {
                return i;
            }
            x -= w;
        }
        weights.len() - 1
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Values no option should take quietly.
const WILD: [&str; 24] = [
    "0",
    "-0",
    "-1",
    "1e300",
    "-1e300",
    "1e-300",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "1099511627776",
    "18446744073709551616",
    "-1099511627776",
    "abc",
    "",
    " ",
    "1,2,3",
    "45deg",
    "--json",
    "0x10",
    "1e",
    "-",
    "∞",
    "3:1:2",
];

/// Numbers for library calls: ordinary ones most of the time, then the edges.
fn wild_f64(r: &mut Rng) -> f64 {
    *r.pick(&[
        0.0,
        -0.0,
        -1.0,
        1e300,
        -1e300,
        1e-300,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::MAX,
        f64::MIN_POSITIVE,
    ])
}

fn num(r: &mut Rng, lo: f64, hi: f64) -> f64 {
    if r.chance(0.85) { r.uniform(lo, hi) } else { wild_f64(r) }
}

fn count(r: &mut Rng, lo: usize, hi: usize) -> usize {
    if r.chance(0.9) { lo + r.below(hi - lo + 1) } else { *r.pick(&[0, 1, 64, 65, 1024, 1025, 1 << 20, usize::MAX]) }
}

// ------------------------------------------------------- command lines

#[derive(Clone, Copy)]
enum Kind {
    Number,
    Positive,
    Small,
    Angle,
    List,
    Order,
    Quadrature,
    Segments,
    Iterations,
    Tolerance,
    Pose,
    TendonSweep,
    MechanismSweep,
    Tip,
    Flag,
    Point,
    Body,
    Out,
    Csv,
    /// `V` or `ROOT,TIP`, near `scale`'s size: a quantity along the flexure.
    Profile(f64),
    /// `R,H`: a notch.
    Notch,
    /// `--shape K`.
    Shape,
}

const FLEXURE: [(&str, Kind); 12] = [
    ("--length", Kind::Positive),
    ("--ei", Kind::Profile(1.0)),
    ("--modulus", Kind::Positive),
    ("--width", Kind::Profile(0.1)),
    ("--thickness", Kind::Profile(0.1)),
    ("--poisson", Kind::Small),
    ("--notch", Kind::Notch),
    ("--density", Kind::Positive),
    ("--mass-per-length", Kind::Profile(1.0)),
    ("--kappa", Kind::List),
    ("--order", Kind::Order),
    ("--quadrature", Kind::Quadrature),
];

/// A subcommand, whether it takes a mechanism file, and its options.
type Subcommand = (&'static str, bool, Vec<(&'static str, Kind)>);

/// Each subcommand, whether it takes a mechanism file, and its own options.
fn commands() -> Vec<Subcommand> {
    let with_flexure = |own: &[(&'static str, Kind)]| FLEXURE.iter().chain(own).copied().collect::<Vec<_>>();
    vec![
        ("kinematics", false, with_flexure(&[("--alpha", Kind::List), ("--input", Kind::Csv)])),
        (
            "deflect",
            false,
            with_flexure(&[
                ("--moment", Kind::Number),
                ("--force", Kind::Number),
                ("--angle", Kind::Angle),
                ("--fx", Kind::Number),
                ("--fy", Kind::Number),
                ("--exact", Kind::Flag),
                ("--limit", Kind::Flag),
                ("--tolerance", Kind::Tolerance),
                ("--max-iterations", Kind::Iterations),
                ("--input", Kind::Csv),
                ("--yield-strength", Kind::Positive),
                ("--shape", Kind::Shape),
            ]),
        ),
        ("compliance", false, with_flexure(&[("--exact", Kind::Flag)])),
        ("buckling", false, with_flexure(&[("--tip", Kind::Tip), ("--exact", Kind::Flag)])),
        (
            "connect",
            false,
            with_flexure(&[
                ("--pose", Kind::Pose),
                ("--exact", Kind::Flag),
                ("--segments", Kind::Segments),
                ("--yield-strength", Kind::Positive),
                ("--shape", Kind::Shape),
                ("--limit", Kind::Flag),
            ]),
        ),
        (
            "tendon",
            false,
            with_flexure(&[
                ("--tension", Kind::Number),
                ("--root-offset", Kind::Small),
                ("--tip-offset", Kind::Small),
                ("--sweep", Kind::TendonSweep),
                ("--yield-strength", Kind::Positive),
                ("--shape", Kind::Shape),
                ("--limit", Kind::Flag),
            ]),
        ),
        ("solve", true, vec![("--compliance", Kind::Body), ("--at", Kind::Point), ("--sweep", Kind::MechanismSweep)]),
        ("buckle", true, vec![]),
        ("draw", true, vec![("--out", Kind::Out), ("--sweep", Kind::MechanismSweep)]),
    ]
}

const PARAMETERS: [&str; 9] = [
    "tendon.flexor.tension",
    "force.tip.fx",
    "force.tip.fy",
    "force.tip.moment",
    "force.load.fy",
    "gravity.y",
    "gravity.x",
    "tendon.nope.tension",
    "nonsense",
];

const BODIES: [&str; 6] = ["ground", "proximal", "distal", "stage", "link", "nobody"];

/// Where a case may write, and the example files.
struct Scratch {
    dir: PathBuf,
    examples: Vec<(String, String)>,
}

impl Scratch {
    /// A directory of this test's own: tests run at once, and each removes its directory.
    fn new(test: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("flexure-fuzz-{}-{test}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
        let mut examples: Vec<(String, String)> = std::fs::read_dir(&root)
            .unwrap()
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .map(|p| (p.display().to_string(), std::fs::read_to_string(&p).unwrap()))
            .collect();
        examples.sort();
        assert!(examples.len() >= 4, "examples/*.toml");
        Self { dir, examples }
    }
}

fn value(r: &mut Rng, kind: Kind, scratch: &Scratch, tag: &str) -> String {
    if r.chance(0.12) {
        let wild = r.pick(&WILD).to_string();
        // Whatever it is called, an output file lands in the scratch directory.
        return if matches!(kind, Kind::Out) { scratch.dir.join(wild).display().to_string() } else { wild };
    }
    let n = |r: &mut Rng, lo: f64, hi: f64| format!("{}", r.uniform(lo, hi));
    match kind {
        Kind::Number => n(r, -5.0, 5.0),
        Kind::Positive => format!("{}", 10f64.powf(r.uniform(-2.0, 1.0))),
        Kind::Small => n(r, -0.2, 0.5),
        Kind::Profile(scale) => {
            let v = |r: &mut Rng| {
                format!("{}", scale * 10f64.powf(r.uniform(-2.0, 0.5)) * if r.chance(0.05) { -1.0 } else { 1.0 })
            };
            if r.chance(0.5) { v(r) } else { format!("{},{}", v(r), v(r)) }
        }
        Kind::Notch => format!("{},{}", n(r, -0.01, 0.2), n(r, -0.01, 0.1)),
        Kind::Shape => (r.below(40) + 1).to_string(),
        Kind::Angle => {
            if r.chance(0.5) {
                format!("{}deg", r.uniform(-400.0, 400.0))
            } else {
                n(r, -8.0, 8.0)
            }
        }
        Kind::List => {
            let k = if r.chance(0.7) { 3 } else { r.below(6) + 1 };
            (0..k).map(|_| n(r, -2.0, 2.0)).collect::<Vec<_>>().join(",")
        }
        Kind::Order => (r.below(7) + 1).to_string(),
        Kind::Quadrature => (r.below(12) + 1).to_string(),
        Kind::Segments => (r.below(12) + 1).to_string(),
        Kind::Iterations => (r.below(60) + 1).to_string(),
        Kind::Tolerance => format!("{}", 10f64.powf(r.uniform(-16.0, -1.0))),
        Kind::Pose => format!("{},{},{}", r.uniform(-3.0, 3.0), r.uniform(-0.5, 1.0), r.uniform(-0.8, 0.8)),
        Kind::TendonSweep => format!("{}:{}:{}", r.uniform(0.0, 5.0), r.uniform(0.0, 20.0), r.below(5) + 1),
        Kind::MechanismSweep => {
            format!("{}={}:{}:{}", r.pick(&PARAMETERS), n(r, -10.0, 10.0), n(r, -10.0, 30.0), r.below(5) + 1)
        }
        Kind::Tip => r.pick(&["free", "guided", "pinned", "clamped", "sideways"]).to_string(),
        Kind::Flag => String::new(),
        Kind::Point => format!("{},{}", n(r, -0.05, 0.05), n(r, -0.05, 0.05)),
        Kind::Body => r.pick(&BODIES).to_string(),
        Kind::Out => {
            if r.chance(0.9) {
                scratch.dir.join(format!("{tag}.svg")).display().to_string()
            } else {
                "/no/such/dir/out.svg".into()
            }
        }
        Kind::Csv => {
            if r.chance(0.1) {
                return "/no/such/file.csv".into();
            }
            let columns = ["a1", "a2", "a3", "a4", "moment", "fx", "fy", "force", "angle", "zz"];
            let k = r.below(4) + 1;
            let header: Vec<&str> = (0..k).map(|_| *r.pick(&columns)).collect();
            let mut text = header.join(",") + "\n";
            for _ in 0..r.below(8) {
                let cells = if r.chance(0.9) { k } else { r.below(5) };
                let row: Vec<String> = (0..cells)
                    .map(|_| if r.chance(0.85) { n(r, -3.0, 3.0) } else { r.pick(&WILD).replace(',', ";") })
                    .collect();
                text += &(row.join(",") + "\n");
            }
            let path = scratch.dir.join(format!("{tag}.csv"));
            std::fs::write(&path, text).unwrap();
            path.display().to_string()
        }
    }
}

/// A random command line (without the program name).
fn argv(r: &mut Rng, scratch: &Scratch, tag: &str) -> Vec<String> {
    let commands = commands();
    let (name, takes_file, options) = r.pick(&commands);
    let mut args = vec![name.to_string()];
    if *takes_file && r.chance(0.97) {
        args.push(if r.chance(0.95) { r.pick(&scratch.examples).0.clone() } else { "/no/such/file.toml".into() });
    }
    // The options a call needs most of the time, then random others.
    let needed: &[&str] = match *name {
        "kinematics" => &["--alpha"],
        "buckling" => &["--tip"],
        "connect" => &["--pose"],
        "tendon" => &["--tension", "--root-offset", "--tip-offset"],
        "draw" => &["--out"],
        _ => &[],
    };
    let mut chosen: Vec<(&str, Kind)> =
        options.iter().filter(|(o, _)| needed.contains(o) && r.chance(0.9)).copied().collect();
    for _ in 0..r.below(4) {
        if !options.is_empty() {
            chosen.push(*r.pick(options));
        }
    }
    if r.chance(0.05) {
        // An option of another subcommand.
        let other = &commands[r.below(commands.len())].2;
        if !other.is_empty() {
            chosen.push(*r.pick(other));
        }
    }
    for (option, kind) in chosen {
        args.push(option.to_string());
        if !matches!(kind, Kind::Flag) {
            args.push(value(r, kind, scratch, tag));
        }
    }
    if r.chance(0.05) {
        args.pop(); // a missing value, or a missing flag
    }
    if r.chance(0.03) {
        args.insert(r.below(args.len() + 1), r.pick(&WILD).to_string());
    }
    if r.chance(0.5) {
        args.push("--json".into());
    }
    args
}

/// A random `modes` command line for one joint (a file's modes are in
/// [`file_case`]): a family of its own, so the other families' cases stay
/// as they were.
fn modes_argv(r: &mut Rng, scratch: &Scratch, tag: &str) -> Vec<String> {
    let own = [
        ("--moment", Kind::Number),
        ("--fx", Kind::Number),
        ("--fy", Kind::Number),
        ("--tip-mass", Kind::Positive),
        ("--tip-inertia", Kind::Positive),
        ("--tip-com", Kind::Point),
        ("--count", Kind::Segments),
        ("--exact", Kind::Flag),
    ];
    let options: Vec<(&str, Kind)> = FLEXURE.iter().chain(&own).copied().collect();
    let mut args = vec!["modes".to_string()];
    let mut chosen: Vec<(&str, Kind)> = Vec::new();
    if r.chance(0.7) {
        chosen.push(*r.pick(&[("--tip-mass", Kind::Positive), ("--mass-per-length", Kind::Profile(1.0))]));
    }
    for _ in 0..r.below(5) {
        chosen.push(*r.pick(&options));
    }
    for (option, kind) in chosen {
        args.push(option.to_string());
        if !matches!(kind, Kind::Flag) {
            args.push(value(r, kind, scratch, tag));
        }
    }
    if r.chance(0.5) {
        args.push("--json".into());
    }
    args
}

// ------------------------------------------------------- mechanism files

/// The text of an example after one to three random edits.
fn mutate(r: &mut Rng, text: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    for _ in 0..r.below(3) + 1 {
        if lines.is_empty() {
            break;
        }
        let i = r.below(lines.len());
        match r.below(7) {
            0 => {
                lines.remove(i);
            }
            1 => {
                let l = lines[i].clone();
                lines.insert(i, l);
            }
            2 => {
                let j = r.below(lines.len());
                lines.swap(i, j);
            }
            3 | 4 => {
                // A number becomes an edge value.
                let numbers: Vec<(usize, usize)> = number_spans(&lines[i]);
                if let Some(&(a, b)) = numbers.get(r.below(numbers.len().max(1))) {
                    let edge =
                        r.pick(&["0", "-1", "1e300", "-1e300", "nan", "inf", "-0.0", "1e-300", "99999999999999999999"]);
                    lines[i].replace_range(a..b, edge);
                }
            }
            5 => {
                // A key is renamed.
                if let Some(eq) = lines[i].find('=') {
                    let key = r.pick(&["name", "kind", "parent", "child", "length", "ei", "order", "tension", "bogus"]);
                    lines[i] = format!("{key} {}", &lines[i][eq..]);
                }
            }
            _ => {
                let j = r.below(lines.len());
                let l = lines[j].clone();
                lines.insert(i, l);
            }
        }
    }
    let mut out = lines.join("\n");
    if r.chance(0.15) {
        let mut cut = r.below(out.len() + 1);
        while !out.is_char_boundary(cut) {
            cut -= 1;
        }
        out.truncate(cut);
    }
    out
}

/// Byte ranges of the numbers in a line.
fn number_spans(line: &str) -> Vec<(usize, usize)> {
    let bytes = line.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts =
            bytes[i].is_ascii_digit() || (bytes[i] == b'-' && bytes.get(i + 1).is_some_and(u8::is_ascii_digit));
        if starts && (i == 0 || !bytes[i - 1].is_ascii_alphanumeric()) {
            let a = i;
            i += 1;
            while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'.' || bytes[i] == b'-') {
                i += 1;
            }
            spans.push((a, i));
        } else {
            i += 1;
        }
    }
    spans
}

/// A random `[[schedule]]` for one of the examples' loads: points (a ramp,
/// a step, out of order, a third point at one time) or a harmonic, with
/// edge values now and then.
fn schedule_table(r: &mut Rng) -> String {
    let load = r.pick(&PARAMETERS);
    let v =
        |r: &mut Rng| if r.chance(0.9) { format!("{}", r.uniform(-5.0, 10.0)) } else { r.pick(&WILD_TOML).to_string() };
    let body = match r.below(3) {
        0 => {
            let (t0, t1) = (r.uniform(0.0, 0.02), r.uniform(0.0, 0.03));
            format!("points = [[{t0}, {}], [{t1}, {}]]", v(r), v(r))
        }
        1 => {
            let t = r.uniform(0.0, 0.02);
            let third = if r.chance(0.2) { format!(", [{t}, {}]", v(r)) } else { String::new() };
            format!("points = [[{t}, {}], [{t}, {}]{third}]", v(r), v(r))
        }
        _ => format!("harmonic = {{ amplitude = {}, frequency = {}, offset = {} }}", v(r), v(r), v(r)),
    };
    format!("\n[[schedule]]\nload = \"{load}\"\n{body}\n")
}

/// TOML values no key should take quietly.
const WILD_TOML: [&str; 8] = ["0", "-1", "1e300", "-1e300", "nan", "inf", "1e-300", "1e7"];

/// Family `motion`: a mutated example with a schedule, run for a short time.
fn motion_case(r: &mut Rng, scratch: &Scratch, tag: &str) -> Vec<String> {
    let (_, text) = r.pick(&scratch.examples);
    let mut text = mutate(r, text);
    if r.chance(0.7) {
        text += &schedule_table(r);
    }
    let path = scratch.dir.join(format!("{tag}.toml"));
    std::fs::write(&path, text).unwrap();
    let file = path.display().to_string();
    let duration = if r.chance(0.9) { format!("{}", r.uniform(0.001, 0.03)) } else { r.pick(&WILD).to_string() };
    let mut args = if r.chance(0.8) {
        vec!["simulate".into(), file, "--duration".into(), duration]
    } else {
        let svg = scratch.dir.join(format!("{tag}.svg")).display().to_string();
        vec!["draw".into(), file, "--simulate".into(), duration, "--out".into(), svg]
    };
    args.extend(["--max-steps".into(), if r.chance(0.9) { "400".into() } else { r.pick(&WILD).to_string() }]);
    if r.chance(0.3) {
        args.extend(["--start".into(), "rest".into()]);
    }
    if r.chance(0.3) {
        args.extend(["--tolerance".into(), r.pick(&["1e-4", "1e-6", "1e-12", "0", "2"]).to_string()]);
    }
    if r.chance(0.5) {
        args.push("--json".into());
    }
    args
}

fn file_case(r: &mut Rng, scratch: &Scratch, tag: &str) -> Vec<String> {
    let (_, text) = r.pick(&scratch.examples);
    let path = scratch.dir.join(format!("{tag}.toml"));
    std::fs::write(&path, mutate(r, text)).unwrap();
    let file = path.display().to_string();
    let mut args = match r.below(4) {
        0 => vec!["solve".into(), file],
        1 => vec!["buckle".into(), file],
        2 => vec!["modes".into(), file],
        _ => vec!["draw".into(), file, "--out".into(), scratch.dir.join(format!("{tag}.svg")).display().to_string()],
    };
    if !matches!(args[0].as_str(), "buckle" | "modes") && r.chance(0.3) {
        args.push("--sweep".into());
        args.push(format!(
            "{}={}:{}:{}",
            r.pick(&PARAMETERS),
            r.uniform(-5.0, 5.0),
            r.uniform(-5.0, 30.0),
            r.below(4) + 2
        ));
    }
    if r.chance(0.5) {
        args.push("--json".into());
    }
    args
}

// ---------------------------------------------------------- checks

thread_local! {
    /// The solver polls of the running case (`None`: no case is running).
    static POLLS: Cell<Option<u64>> = const { Cell::new(None) };
    static CAPTURING: Cell<bool> = const { Cell::new(false) };
    static PANIC_AT: RefCell<String> = const { RefCell::new(String::new()) };
}

/// The interrupt hook: counts the solver's polls (one per Newton iteration,
/// continuation step and integrator iteration) and stops the case past
/// [`WORK_BUDGET`] of them.
fn past_budget() -> bool {
    POLLS.with(|p| match p.get() {
        Some(n) => {
            p.set(Some(n + 1));
            n >= WORK_BUDGET
        }
        None => false,
    })
}

/// Quiet panics inside cases (they are reported as failures, with where they happened).
fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if CAPTURING.with(Cell::get) {
                let at = info.location().map(|l| format!(" at {}:{}", l.file(), l.line())).unwrap_or_default();
                PANIC_AT.with(|p| *p.borrow_mut() = at);
            } else {
                default(info);
            }
        }));
    });
}

/// Runs `work` under the soft deadline, catching panics: the error names
/// a panic or an overrun.
fn guarded<R>(work: impl FnOnce() -> R) -> Result<(R, u64), String> {
    POLLS.with(|p| p.set(Some(0)));
    CAPTURING.with(|c| c.set(true));
    let out = flexure::solver::with_interrupt(past_budget, || catch_unwind(AssertUnwindSafe(work)));
    CAPTURING.with(|c| c.set(false));
    let polls = POLLS.with(|p| p.replace(None)).unwrap_or(0);
    let out = out.map_err(|payload| {
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        format!("panic: {message}{}", PANIC_AT.with(|p| p.borrow().clone()))
    })?;
    if polls > WORK_BUDGET {
        return Err(format!("work: stopped past the budget of {WORK_BUDGET} solver iterations"));
    }
    Ok((out, polls))
}

/// The first `null` in a JSON value (how serde_json prints NaN and ±∞).
fn null_at(v: &Value, path: &str) -> Option<String> {
    match v {
        Value::Null => Some(path.to_string()),
        Value::Array(a) => a.iter().enumerate().find_map(|(i, v)| null_at(v, &format!("{path}[{i}]"))),
        Value::Object(m) => m.iter().find_map(|(k, v)| null_at(v, &format!("{path}.{k}"))),
        _ => None,
    }
}

/// Status, stdout and stderr of one run against the CLI's contract.
fn check_output(args: &[String], status: i32, out: &str, err: &str) -> Result<(), String> {
    if err.contains("panicked") {
        return Err(format!("panic: {err}"));
    }
    match status {
        0 => {
            if out.trim().is_empty() {
                return Err("exit: status 0 with nothing on stdout".into());
            }
        }
        2 => {
            if !err.contains("error") {
                return Err(format!("message: status 2 without an error on stderr: {err:?}"));
            }
        }
        s => return Err(format!("exit: status {s}: {err}")),
    }
    let help = args.iter().any(|a| a == "--help" || a == "-h" || a == "--version" || a == "-V");
    if args.iter().any(|a| a == "--json") && !help && !out.is_empty() {
        for line in out.lines() {
            let v: Value = serde_json::from_str(line).map_err(|e| format!("json: {e}: {line}"))?;
            if let Some(p) = null_at(&v, "") {
                return Err(format!("non-finite: null at {p}: {line}"));
            }
        }
    } else {
        // Table and CSV forms: no non-finite number spelled out.
        let bad = out.split(|c: char| c.is_whitespace() || c == ',').find(|t| {
            let t = t.trim_start_matches(['-', '+']);
            t.eq_ignore_ascii_case("nan") || t == "inf" || t == "null"
        });
        if let Some(t) = bad {
            return Err(format!("non-finite: {t:?} printed"));
        }
    }
    if let Some(svg) = args.iter().position(|a| a == "--out").and_then(|i| args.get(i + 1)) {
        if status == 0
            && args.first().is_some_and(|c| c == "draw")
            && let Ok(text) = std::fs::read_to_string(svg)
            && (text.contains("NaN") || text.contains("inf\""))
        {
            return Err("non-finite: NaN in the SVG".into());
        }
        let _ = std::fs::remove_file(svg);
    }
    Ok(())
}

/// One command line, in-process.
fn run_in_process(args: &[String]) -> Result<u64, String> {
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let (status, polls) = guarded(|| {
        flexure_cli::run(std::iter::once("flexure").chain(args.iter().map(String::as_str)), &mut out, &mut err)
    })?;
    check_output(args, i32::from(status), &String::from_utf8_lossy(&out), &String::from_utf8_lossy(&err))?;
    Ok(polls)
}

/// One command line, as a real process, killed if it hangs past
/// [`HANG_WATCHDOG`]. Its work is not counted (the in-process families
/// bound it); the verdict is the exit contract.
fn run_process(args: &[String], scratch: &Scratch, tag: &str) -> Result<u64, String> {
    let (out_path, err_path) = (scratch.dir.join(format!("{tag}.out")), scratch.dir.join(format!("{tag}.err")));
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_flexure"))
        .args(args)
        .stdin(std::process::Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap())
        .spawn()
        .map_err(|e| format!("spawn: {e}"))?;
    let pid = child.id();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(child.wait());
    });
    let status = match rx.recv_timeout(HANG_WATCHDOG) {
        Ok(s) => s.map_err(|e| format!("wait: {e}"))?,
        Err(_) => {
            // The waiting thread still owns the child: kill it by its id.
            let _ = std::process::Command::new("kill").args(["-9", &pid.to_string()]).status();
            return Err(format!("hang: killed after {HANG_WATCHDOG:?} without an answer"));
        }
    };
    let out = std::fs::read_to_string(&out_path).unwrap_or_default();
    let err = std::fs::read_to_string(&err_path).unwrap_or_default();
    let _ = (std::fs::remove_file(&out_path), std::fs::remove_file(&err_path));
    // A signal (abort, segfault) has no code.
    check_output(args, status.code().unwrap_or(-1), &out, &err).map(|()| 0)
}

// ---------------------------------------------------------- library

/// Checks that every value is finite; the error names the call.
fn finite(call: &str, values: impl IntoIterator<Item = f64>) -> Result<(), String> {
    match values.into_iter().find(|v| !v.is_finite()) {
        Some(v) => Err(format!("non-finite: {v} from {call}")),
        None => Ok(()),
    }
}

/// A flexure from random (sometimes absurd) parameters; `call` spells the
/// construction. `None` when the library refuses it, as it may.
fn random_flexure(r: &mut Rng, call: &mut String) -> Option<Flexure> {
    let (l, ei, order) = (num(r, 0.1, 3.0), num(r, 0.1, 3.0), count(r, 1, 6));
    let segments = r.chance(0.1);
    *call = if segments {
        format!("Flexure::segments({l:?}, {ei:?}, {order})")
    } else {
        format!("Flexure::new({l:?}, {ei:?}, {order})")
    };
    let mut f = if segments { Flexure::segments(l, ei, order).ok() } else { Flexure::new(l, ei, order).ok() };
    if r.chance(0.2) {
        let q = count(r, 1, 12);
        *call += &format!(".unwrap().with_quadrature({q})");
        f = f.and_then(|f| f.with_quadrature(q).ok());
    }
    if r.chance(0.3) {
        let k: Vec<f64> = (0..order.min(8)).map(|_| num(r, -2.0, 2.0)).collect();
        *call += &format!(".unwrap().with_rest(&{k:?})");
        f = f.and_then(|f| f.with_rest(&k).ok());
    }
    *call += ".unwrap()";
    f
}

fn load(r: &mut Rng) -> TipLoad {
    TipLoad { moment: num(r, -5.0, 5.0), fx: num(r, -5.0, 5.0), fy: num(r, -5.0, 5.0) }
}

/// How often each library call of [`library_case`] is drawn, per 1000, in
/// its order: kernels, deflect, stability_limit, buckling_load,
/// compliance_tip_rest, the exact compliance, connect, the exact elastica's
/// deflect and connect, pull, bending_stiffness, backbone. The exact solvers
/// and the bisection take up to a second each in the dev profile: drawn
/// rarely, so the whole test stays near 30 s.
const CALL_WEIGHTS: [usize; 12] = [150, 150, 5, 100, 100, 5, 60, 4, 4, 150, 100, 172];

/// One random library call. `call` is written before the call is made, so
/// a panic or an overrun can name it; an `Ok` answer must be finite.
fn library_case(r: &mut Rng, call: &mut String) -> Result<(), String> {
    let Some(f) = random_flexure(r, call) else { return Ok(()) };
    let built = format!("let f = {call};");
    let n = f.order();
    let alpha: Vec<f64> = (0..n).map(|_| r.uniform(-3.0, 3.0)).collect();
    let mut set = |what: String| {
        *call = format!("{built} {what}");
        call.clone()
    };
    match r.weighted(&CALL_WEIGHTS) {
        0 => {
            // Kernels take finite coordinates; their answers must be finite.
            let c = set(format!("update_kinematics(&f, &{alpha:?}, &mut k, Level::Hessian); energy; energy_gradient"));
            let mut k = Kinematics::new(&f);
            update_kinematics(&f, &alpha, &mut k, Level::Hessian);
            let mut g = vec![0.0; n];
            energy_gradient(&f, &alpha, &mut g);
            let p = k.pose_root_tip;
            finite(&c, [p.phi, p.x, p.y, energy(&f, &alpha)])?;
            finite(&c, k.jacobian_root_tip.iter().chain(&k.hessian_root_tip_x).chain(&k.hessian_root_tip_y).copied())?;
            finite(&c, g)
        }
        1 => {
            let settings = flexure::Settings {
                tolerance: if r.chance(0.8) { 1e-12 } else { wild_f64(r) },
                max_iterations: if r.chance(0.8) { 50 } else { count(r, 1, 100) },
                max_steps: if r.chance(0.8) { 1000 } else { count(r, 1, 2000) },
                min_step: if r.chance(0.8) { 1e-6 } else { wild_f64(r) },
                max_rotation_per_step: if r.chance(0.8) { 0.5 } else { num(r, 0.01, 2.0) },
                // The default: no draw, so the seeds' sequences stay as they were.
                max_evaluations: flexure::Settings::default().max_evaluations,
            };
            let l = load(r);
            let c = set(format!("deflect(&f, &{l:?}, &mut StaticsData::new(&f), &{settings:?})"));
            let mut data = StaticsData::new(&f);
            match deflect(&f, &l, &mut data, &settings) {
                Ok(eq) => finite(&c, data.alpha().iter().chain(&data.stiffness).copied().chain([eq.residual])),
                Err(_) => Ok(()),
            }
        }
        2 => {
            let (l, factor) = (load(r), num(r, 0.5, 50.0));
            let c = set(format!("statics::stability_limit(&f, &{l:?}, {factor:?})"));
            match flexure::statics::stability_limit(&f, &l, factor) {
                Ok(x) => finite(&c, [x.factor()]),
                _ => Ok(()),
            }
        }
        3 => {
            let tip = *r.pick(&TipConstraint::ALL);
            let c = set(format!("buckling_load(&f, TipConstraint::{tip:?})"));
            match buckling_load(&f, tip) {
                Ok(b) => finite(&c, b.mode.iter().copied().chain([b.critical_load])),
                Err(_) => Ok(()),
            }
        }
        4 => {
            let c = set("compliance_tip_rest(&f)".into());
            finite(&c, compliance_tip_rest(&f).iter().copied())
        }
        5 => {
            let tol = flexure::ode::Tolerance {
                relative: num(r, 1e-12, 1e-6),
                absolute: num(r, 1e-13, 1e-6),
                max_steps: count(r, 10, 100_000),
            };
            let c = set(format!("reference::compliance::compliance_tip(&f, &{tol:?})"));
            match exact_compliance::compliance_tip(&f, &tol) {
                Ok(m) => finite(&c, m.iter().copied()),
                Err(_) => Ok(()),
            }
        }
        6 => {
            let target = Pose { phi: num(r, -3.0, 3.0), x: num(r, -0.5, 1.0), y: num(r, -0.8, 0.8) };
            let c = set(format!("connect(&f, &{target:?})"));
            match connect(&f, &target) {
                Ok(k) => finite(&c, k.alpha.iter().copied().chain([k.energy, k.load.moment, k.load.fx, k.load.fy])),
                Err(_) => Ok(()),
            }
        }
        7 => {
            let l = load(r);
            let c = set(format!("reference::elastica::deflect(&f, &{l:?}, &Default::default())"));
            match elastica::deflect(&f, &l, &Default::default()) {
                Ok(s) => finite(&c, [s.pose.phi, s.pose.x, s.pose.y, s.root_moment]),
                Err(_) => Ok(()),
            }
        }
        8 => {
            let target = Pose { phi: num(r, -2.0, 2.0), x: num(r, 0.0, 1.0), y: num(r, -0.5, 0.5) };
            let guess = [num(r, -3.0, 3.0), num(r, -3.0, 3.0), num(r, -3.0, 3.0)];
            let c = set(format!("reference::elastica::connect(&f, &{target:?}, {guess:?}, &Default::default())"));
            match elastica::connect(&f, &target, guess, &Default::default()) {
                Ok(k) => finite(&c, [k.energy, k.root_moment, k.fx, k.fy]),
                Err(_) => Ok(()),
            }
        }
        9 => {
            let t = TendonOffsets { root_offset: num(r, -0.2, 0.2), tip_offset: num(r, -0.2, 0.2) };
            let tension = num(r, 0.0, 10.0);
            let c = set(format!("tendon::pull(&f, &{t:?}, {tension:?}, &mut TendonData::new(&f))"));
            let mut data = TendonData::new(&f);
            match pull(&f, &t, tension, &mut data) {
                Ok(eq) => finite(&c, data.alpha().iter().copied().chain([eq.residual])),
                Err(_) => Ok(()),
            }
        }
        10 => {
            let (e, b, h) = (num(r, 1e9, 3e11), num(r, 1e-3, 0.1), num(r, 1e-4, 1e-2));
            let nu = if r.chance(0.5) { Some(num(r, 0.0, 0.5)) } else { None };
            let c = set(format!("bending_stiffness({e:?}, {b:?}, {h:?}, {nu:?})"));
            match bending_stiffness(e, b, h, nu) {
                Ok(ei) => finite(&c, [ei]),
                Err(_) => Ok(()),
            }
        }
        _ => {
            let samples = count(r, 0, 200).min(10_000);
            let c = set(format!("kinematics::backbone(&f, &{alpha:?}, {samples})"));
            let b = backbone(&f, &alpha, samples);
            finite(&c, b.iter().flat_map(|p| [p.phi, p.x, p.y]))?;
            let rows = r.below(4);
            let alphas: Vec<f64> = (0..rows * n).map(|_| r.uniform(-3.0, 3.0)).collect();
            let c = set(format!("kinematics::par_poses_root_tip(&f, &{alphas:?}, &mut [Pose::default(); {rows}])"));
            let mut poses = vec![Pose::default(); rows];
            par_poses_root_tip(&f, &alphas, &mut poses).map_err(|e| format!("error: {e} from {c}"))?;
            finite(&c, poses.iter().flat_map(|p| [p.phi, p.x, p.y]))
        }
    }
}

// ---------------------------------------------------------- driver

/// One family's results.
#[derive(Default)]
struct Tally {
    cases: usize,
    failures: Vec<String>,
    /// The costliest case: its solver polls, and its description.
    costliest: (u64, String),
}

/// Case `i` of a family: its description, and its verdict (on success, the
/// solver polls it took).
type CaseFn = dyn Fn(usize) -> (String, Result<u64, String>) + Send + Sync;

/// Runs `cases` cases of one family on a worker thread, so a case that
/// hangs past [`HANG_WATCHDOG`] is reported and left behind while the rest
/// go on. `case(i)` returns the case's description and its verdict.
fn drive(cases: usize, case: Arc<CaseFn>) -> Tally {
    let mut tally = Tally::default();
    let mut next = 0;
    while next < cases {
        let (tx, rx) = mpsc::channel();
        let job = case.clone();
        let start = next;
        std::thread::spawn(move || {
            install_panic_hook();
            for i in start..cases {
                if tx.send((i, None)).is_err() {
                    return;
                }
                let (what, verdict) = job(i);
                if tx.send((i, Some((what, verdict)))).is_err() {
                    return;
                }
            }
        });
        let mut current = start;
        loop {
            match rx.recv_timeout(HANG_WATCHDOG) {
                Ok((i, None)) => current = i,
                Ok((i, Some((what, verdict)))) => {
                    tally.cases += 1;
                    match verdict {
                        Ok(polls) if polls > tally.costliest.0 => tally.costliest = (polls, what),
                        Ok(_) => {}
                        Err(e) => tally.failures.push(format!("{e}\n    case {i}: {what}")),
                    }
                    next = i + 1;
                }
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    if next <= current && current < cases {
                        // The worker itself died (a panic outside the guarded call).
                        tally.cases += 1;
                        tally.failures.push(format!("panic: in the fuzz driver\n    case {current}"));
                        next = current + 1;
                    }
                    break;
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {
                    // The worker is stuck in a loop that ignores the interrupt hook.
                    tally.cases += 1;
                    tally.failures.push(format!(
                        "hang: no answer in {HANG_WATCHDOG:?}\n    case {current}: (see the case generator)"
                    ));
                    next = current + 1;
                    break;
                }
            }
        }
    }
    tally
}

fn shown(args: &[String]) -> String {
    let quoted: Vec<String> = args
        .iter()
        .map(|a| if a.is_empty() || a.contains([' ', ',', '=']) { format!("'{a}'") } else { a.clone() })
        .collect();
    format!("flexure {}", quoted.join(" "))
}

/// Prints the one-line summary of a test's families (with `--nocapture`),
/// then one line per kind of failure with its first case, and fails if any case did.
fn report(test: &str, families: &[(&str, Tally)]) {
    let total: usize = families.iter().map(|f| f.1.cases).sum();
    let failed: usize = families.iter().map(|f| f.1.failures.len()).sum();
    let counts: Vec<String> =
        families.iter().map(|(n, t)| format!("{n} {} cases ({} failed)", t.cases, t.failures.len())).collect();
    eprintln!("fuzz {test}: {total} cases, {failed} failures: {}", counts.join(", "));
    for (name, t) in families.iter().filter(|f| f.1.costliest.0 > 0) {
        let what: String = t.costliest.1.chars().take(300).collect();
        eprintln!("fuzz {test}: costliest {name} case, {} solver polls: {what}", t.costliest.0);
    }
    // One line per kind of failure (the call, or the first 60 characters), with its first case.
    let mut kinds: Vec<(String, usize, &String)> = Vec::new();
    for f in families.iter().flat_map(|f| f.1.failures.iter()) {
        let first = f.lines().next().unwrap_or_default();
        let key: String = match first.rsplit_once("; ") {
            Some((_, call)) if first.starts_with("non-finite") => {
                format!("non-finite from {}", call.split('(').next().unwrap_or(call))
            }
            _ => first.chars().take(60).collect(),
        };
        match kinds.iter_mut().find(|k| k.0 == key) {
            Some(k) => k.1 += 1,
            None => kinds.push((key, 1, f)),
        }
    }
    for (_, n, first) in &kinds {
        let first: String = first.chars().take(1200).collect();
        eprintln!("FAIL ×{n}: {first}");
    }
    assert!(failed == 0, "{failed} of {total} fuzz cases failed (listed above)");
}

/// Families `argv` (in-process) and `process` (real processes): the CLI's contract.
#[test]
#[ignore = "long: 9 300 fuzzed command lines, minutes; run by .ci/run (cargo test -- --ignored)"]
fn fuzz_command_lines() {
    let scratch = Arc::new(Scratch::new("argv"));
    let s = scratch.clone();
    let argv_tally = drive(
        ARGV_CASES,
        Arc::new(move |i| {
            let args = argv(&mut Rng::for_case(1, i), &s, &format!("argv{i}"));
            let verdict = run_in_process(&args);
            (shown(&args), verdict)
        }),
    );
    let s = scratch.clone();
    let process_tally = drive(
        PROCESS_CASES,
        Arc::new(move |i| {
            let tag = format!("process{i}");
            let args = argv(&mut Rng::for_case(4, i), &s, &tag);
            let verdict = run_process(&args, &s, &tag);
            (shown(&args), verdict)
        }),
    );
    let s = scratch.clone();
    let modes_tally = drive(
        MODES_CASES,
        Arc::new(move |i| {
            let args = modes_argv(&mut Rng::for_case(5, i), &s, &format!("modes{i}"));
            let verdict = run_in_process(&args);
            (shown(&args), verdict)
        }),
    );
    let _ = std::fs::remove_dir_all(&scratch.dir);
    report("command lines", &[("argv", argv_tally), ("process", process_tally), ("modes", modes_tally)]);
}

/// Family `files`: mutated mechanism files through solve, buckle, draw and modes.
#[test]
#[ignore = "long: 3 300 fuzzed mechanism files and motions, minutes; run by .ci/run (cargo test -- --ignored)"]
fn fuzz_mechanism_files() {
    let scratch = Arc::new(Scratch::new("files"));
    let s = scratch.clone();
    let tally = drive(
        FILE_CASES,
        Arc::new(move |i| {
            let tag = format!("file{i}");
            let args = file_case(&mut Rng::for_case(2, i), &s, &tag);
            let verdict = run_in_process(&args);
            let toml = s.dir.join(format!("{tag}.toml"));
            let text = std::fs::read_to_string(&toml).unwrap_or_default().replace('\n', "⏎");
            let _ = std::fs::remove_file(toml);
            (format!("{} (file: {text})", shown(&args)), verdict)
        }),
    );
    let s = scratch.clone();
    let motion = drive(
        MOTION_CASES,
        Arc::new(move |i| {
            let tag = format!("motion{i}");
            let args = motion_case(&mut Rng::for_case(6, i), &s, &tag);
            let verdict = run_in_process(&args);
            let toml = s.dir.join(format!("{tag}.toml"));
            let text = std::fs::read_to_string(&toml).unwrap_or_default().replace('\n', "⏎");
            let _ = std::fs::remove_file(toml);
            (format!("{} (file: {text})", shown(&args)), verdict)
        }),
    );
    let _ = std::fs::remove_dir_all(&scratch.dir);
    report("mechanism files", &[("files", tally), ("motion", motion)]);
}

/// Family `library`: library functions called directly.
#[test]
fn fuzz_library() {
    let tally = drive(
        LIBRARY_CASES,
        Arc::new(|i| {
            let (mut r, mut call) = (Rng::for_case(3, i), String::new());
            let verdict = guarded(|| library_case(&mut r, &mut call)).and_then(|(v, polls)| v.map(|()| polls));
            (call, verdict)
        }),
    );
    report("library", &[("library", tally)]);
}

/// Calls the fuzzer found running for seconds (from earlier seeds
/// and weights, so `fuzz_library` may not draw them), kept as explicit
/// cases: the exact elastica's `connect` from a far guess (13.8 s before its
/// Newton iterates were bounded and it polled the interrupt hook), and the
/// stability limit of order-64 and absurd flexures (each bisection step a
/// full deflection, before it started from the path's own limit). Reachable
/// from the command line: `flexure deflect --order 64 --fx 1.78 --fy -3.95
/// --moment 3.94 --limit` took 23.5 s.
#[test]
fn known_slow_library_calls() {
    type Case = (&'static str, fn());
    let cases: Vec<Case> = vec![
        (
            "elastica::connect(&Flexure::new(0.8447764841867875, 2.644199256439918, 3), Pose(-0.5952278734315599, 0, -0.25074782453854516), [-0.22606486448272278, -2.946442112662058, -0.5996101610779463]) took 13.8 s",
            || {
                let f = Flexure::new(0.8447764841867875, 2.644199256439918, 3).unwrap();
                let target = Pose { phi: -0.5952278734315599, x: 0.0, y: -0.25074782453854516 };
                let _ = elastica::connect(
                    &f,
                    &target,
                    [-0.22606486448272278, -2.946442112662058, -0.5996101610779463],
                    &Default::default(),
                );
            },
        ),
        (
            "stability_limit(&Flexure::segments(1.1819376154115153, 0.2906985224044335, 64), (3.942208198421355, 1.7847488478640336, -3.9504177523460937), 36.7505872015251) ran past 5 s",
            || {
                let f = Flexure::segments(1.1819376154115153, 0.2906985224044335, 64).unwrap();
                let load = TipLoad { moment: 3.942208198421355, fx: 1.7847488478640336, fy: -3.9504177523460937 };
                let _ = flexure::statics::stability_limit(&f, &load, 36.7505872015251);
            },
        ),
        (
            "stability_limit(&Flexure::new(0.5412453776886431, 2.3497325777340743, 64), (f64::MAX, -2.9872141926548244, 3.5550814570199947), 47.22350789090814) ran past 5 s",
            || {
                let f = Flexure::new(0.5412453776886431, 2.3497325777340743, 64).unwrap();
                let load = TipLoad { moment: f64::MAX, fx: -2.9872141926548244, fy: 3.5550814570199947 };
                let _ = flexure::statics::stability_limit(&f, &load, 47.22350789090814);
            },
        ),
        (
            "stability_limit(&Flexure::new(f64::MAX, 1.0647845717276523, 5), (3.3065161145907638, -1.8826186881914353, 2.4697282723383873), 0.574047943467237) ran past 5 s",
            || {
                // A length of f64::MAX is now refused (Flexure's LENGTH_RANGE): that is the answer.
                assert!(Flexure::new(f64::MAX, 1.0647845717276523, 5).is_err());
            },
        ),
        (
            "stability_limit(&Flexure::new(1, 1, 64), (3.94, 1.78, -3.95), 1000), as `flexure deflect --order 64 --fx 1.78 --fy -3.95 --moment 3.94 --limit`",
            || {
                let f = Flexure::new(1.0, 1.0, 64).unwrap();
                let load = TipLoad { moment: 3.94, fx: 1.78, fy: -3.95 };
                let _ = flexure::statics::stability_limit(&f, &load, 1000.0);
            },
        ),
    ];
    let cases = Arc::new(cases);
    let list = cases.clone();
    let tally = drive(cases.len(), Arc::new(move |i| (list[i].0.to_string(), guarded(list[i].1).map(|((), n)| n))));
    eprintln!(
        "fuzz: known slow library calls: {} cases, {} failed; the costliest took {} solver polls: {}",
        tally.cases,
        tally.failures.len(),
        tally.costliest.0,
        tally.costliest.1
    );
    for f in &tally.failures {
        eprintln!("FAIL {f}");
    }
    assert!(
        tally.failures.is_empty(),
        "{} of {} known slow calls still run past the bound",
        tally.failures.len(),
        tally.cases
    );
}
