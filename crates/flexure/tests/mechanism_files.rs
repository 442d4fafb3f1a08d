//! Bad mechanism files: every bad value is an error naming its key, line
//! and column; nothing panics; no result holds a number that is not finite.

use flexure::Error;
use flexure::mechanism::buckling::buckle;
use flexure::mechanism::file::from_toml;
use flexure::mechanism::statics::{Settings, solve};

fn joint(extra: &str) -> String {
    format!(
        "[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b\"\nlength = 0.01\nei = 1e-3\n{extra}"
    )
}

fn file_error(text: &str) -> String {
    match from_toml(text) {
        Err(e @ Error::File { .. }) => e.to_string(),
        other => panic!("expected a file error for\n{text}\ngot {other:?}"),
    }
}

/// The fuzzer's findings: an empty file, a subnormal spring, a huge length.
#[test]
fn fuzzer_findings() {
    // An empty file is a mechanism of the ground alone: it solves to nothing
    // and has nothing to buckle (an error, not a panic).
    let empty = from_toml("").unwrap();
    let s = solve(&empty, &Settings::default()).unwrap();
    assert!(s.q.is_empty() && s.energy == 0.0 && s.stable);
    assert!(matches!(buckle(&empty, &Settings::default()), Err(Error::Singular { .. })));
    let spring =
        "[[joint]]\nname = \"a\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"b\"\nstiffness = 5e-324\n";
    let e = file_error(spring);
    assert!(
        e.starts_with("line 6, column 13: joint \"a\": stiffness = 5e-324: must be zero or between 1e-30 and 1e30"),
        "{e}"
    );
    let e = file_error(&joint("").replace("length = 0.01", "length = 1e300"));
    assert!(e.starts_with("line 6, column 10: joint \"a\": length = 1e300"), "{e}");
}

/// Each bad value names its key and the place of its value.
#[test]
fn bad_values_name_key_line_and_column() {
    let cases = [
        (joint("order = 65\n"), "line 8, column 9", "order = 65"),
        (joint("order = -1\n"), "line 8, column 9", ""),
        (joint("quadrature = 0\n"), "line 8, column 14", "quadrature = 0"),
        (joint("kappa = [0.1]\n"), "line 8, column 9", "kappa"),
        (joint("kappa = [0.0, 1e31, 0.0]\n"), "line 8, column 9", "kappa[1] = 1e31"),
        (joint("origin = [0.0, nan, 0.0]\n"), "line 8, column 10", "origin[1] = NaN"),
        (joint("stiffness = 2.0\n"), "line 8, column 13", "`stiffness` does not apply to a flexure joint"),
        (joint("width = 0.01\n"), "line 8, column 9", "`width` goes with modulus"),
        (joint("").replace("ei = 1e-3", "modulus = 2e11\nwidth = 0.01"), "line 7, column 11", "thickness is missing"),
        (
            joint("").replace("ei = 1e-3", "modulus = 2e11\nwidth = 0.01\nthickness = 2e-4\npoisson = 0.7"),
            "line 10, column 11",
            "poisson = 0.7",
        ),
        (joint("").replace("ei = 1e-3", "ei = -1e-3"), "line 7, column 6", "ei = -0.001: must be greater than zero"),
        (
            joint("").replace("kind = \"flexure\"", "kind = \"revolute\""),
            "line 6, column 10",
            "`length` does not apply",
        ),
        (joint("[[body]]\nname = \"b\"\nmass = -1.0\n"), "line 10, column 8", "mass = -1"),
        (joint("[[body]]\nname = \"b\"\ncom = [inf, 0.0]\n"), "line 10, column 7", "com[0] = inf"),
        (joint("[[body]]\nname = \"b\"\n[[body]]\nname = \"b\"\n"), "line 11, column 8", "described twice"),
        (joint("[[body]]\nname = \"ground\"\nmass = 1.0\n"), "line 9, column 8", "the ground does not move"),
        (
            joint("[[force]]\nbody = \"b\"\nat = [0.0, 0.0]\nforce = [1e31, 0.0]\n"),
            "line 11, column 9",
            "force[0] = 1e31",
        ),
        (joint("[[force]]\nbody = \"b\"\nat = [0.0, 0.0]\nmoment = -inf\n"), "line 11, column 10", "moment = -inf"),
        (
            joint("[[tendon]]\nname = \"t\"\ntension = -2.0\npath = [[\"ground\", 0.0, 0.001], [\"b\", 0.0, 0.001]]\n"),
            "line 10, column 11",
            "tension = -2",
        ),
        (
            joint(
                "[[tendon]]\nname = \"t\"\ntension = 2.0\npath = [[\"ground\", 0.0, 0.001], [\"b\", 1e-40, 0.001]]\n",
            ),
            "line 11, column 33",
            "path[1][0] = 1e-40",
        ),
        (
            joint("[[tendon]]\nname = \"t\"\ntension = 2.0\npath = [[\"ground\", 0.01, 0.0], [\"b\", 0.0, 0.0]]\n"),
            "line 11, column 32",
            "via points 1 and 2 coincide",
        ),
        (joint("[[weld]]\na = \"b\"\nb = \"b\"\n"), "line 10, column 5", "joins body \"b\" to itself"),
        (joint("[[pin]]\na = \"b\"\nb = \"ground\"\nb_at = [0.0, 1e99]\n"), "line 11, column 8", "b_at[1] = 1e99"),
        (joint("gravity = [0.0, -9.81]\n"), "line 8, column 1", ""),
        (format!("gravity = [0.0, nan]\n{}", joint("")), "line 1, column 11", "gravity[1] = NaN"),
        (
            joint("[[joint]]\nname = \"s\"\nkind = \"revolute\"\nparent = \"b\"\nchild = \"c\"\nstiffness = 1e-14\n"),
            "line 13, column 13",
            "times softer than joint \"a\"",
        ),
    ];
    for (text, place, what) in cases {
        let e = file_error(&text);
        assert!(e.starts_with(&format!("{place}:")) && e.contains(what), "expected {what:?} at {place}:\n{text}\n{e}");
    }
}

/// Closures that no configuration near rest can close: a pin joining a
/// 1 m arm's end, which can only reach the unit circle, to a point 2 m from
/// its pivot. The error places the pin.
#[test]
fn closures_that_cannot_be_assembled_are_placed() {
    let text = "[[joint]]\nname = \"a\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"b\"\nstiffness = 1.0\n\
                [[pin]]\na = \"b\"\na_at = [1.0, 0.0]\nb = \"ground\"\nb_at = [0.0, 2.0]\n";
    let m = from_toml(text).unwrap();
    let e = solve(&m, &Settings::default()).unwrap_err().to_string();
    assert!(e.starts_with("line 8, column 5: pin of \"b\" and \"ground\": the closures cannot be assembled"), "{e}");
}

/// SplitMix64, seeded.
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) % n as u64) as usize
    }
}

/// Mutated example files (a number replaced by an extreme or wrong value,
/// a line dropped or doubled), seeded: parsing names the place of every
/// file error; a file that parses never fails later on a value (the
/// solvers' errors are numerical ones: no convergence, stalled, unstable,
/// singular; or closures that cannot be assembled, placed; or, where
/// parts may touch, contact's refusals naming the geom); nothing panics;
/// every answer is finite.
#[test]
fn mutated_examples() {
    let dir = format!("{}/../../examples", env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| std::fs::read_to_string(p).unwrap())
        // Planar files; the spatial ones are mutated in tests/spatial_files.rs.
        .filter(|t| !t.contains("dimension = 3"))
        .collect();
    files.sort();
    let values = [
        "0",
        "-1",
        "1e300",
        "-1e300",
        "5e-324",
        "nan",
        "inf",
        "-inf",
        "1e-300",
        "0.0",
        "3",
        "-0.5",
        "1e30",
        "1e-30",
        "99999999999",
        "\"x\"",
        "[]",
        "[1.0]",
        "true",
        "1e16",
        "1e-3",
        "65",
        "1.0e5",
    ];
    let mut rng = Rng(20261130);
    let (mut parsed, mut answered) = (0, 0);
    for _ in 0..600 {
        let mut lines: Vec<String> = files[rng.below(files.len())].lines().map(str::to_string).collect();
        for _ in 0..1 + rng.below(2) {
            let i = rng.below(lines.len());
            match rng.below(6) {
                0 => {
                    lines.remove(i);
                }
                1 => lines.insert(i, lines[i].clone()),
                _ => {
                    // Replace a value (the right of `key = `, or a number inside an array).
                    let v = values[rng.below(values.len())];
                    if let Some(eq) = lines[i].find(" = ") {
                        lines[i] = format!("{} = {v}", &lines[i][..eq]);
                    }
                }
            }
        }
        let text = lines.join("\n");
        let outcome = std::panic::catch_unwind(|| match from_toml(&text) {
            Err(Error::File { place, .. }) => {
                assert!(place.starts_with("line ") && place.contains(", column "), "{place}\n{text}");
                None
            }
            Err(e) => panic!("a file error that is not Error::File: {e}\n{text}"),
            Ok(m) => {
                // Numerical outcomes, or closures that cannot be assembled
                // (an inconsistent file, placed at the widest-open closure).
                // A file whose parts may touch (the grasp's): contact's refusals name
                // the geom (buckling does not handle contact; a part starting inside
                // a geom; a contact set Newton cannot solve where it changed). Two
                // geoms neither a circle (a dropped `exclude` line) are refused by the
                // file, placed.
                let touching = !flexure::mechanism::contact::pairs(&m).is_empty();
                let numerical = |e: &Error| match e {
                    Error::File { place, .. } => place.starts_with("line ") && place.contains(", column "),
                    Error::InvalidParameter { name: "geom", .. } => touching,
                    e => matches!(
                        e,
                        Error::NoConvergence { .. }
                            | Error::ContinuationStalled { .. }
                            | Error::Unstable { .. }
                            | Error::Singular { .. }
                    ),
                };
                let mut answers = 0;
                match solve(&m, &Settings::default()) {
                    Ok(s) => {
                        assert!(s.q.iter().chain(&s.multipliers).chain([&s.energy]).all(|v| v.is_finite()), "{text}");
                        answers += 1;
                    }
                    Err(e) => assert!(numerical(&e), "{e}\n{text}"),
                }
                match buckle(&m, &Settings::default()) {
                    Ok(b) => {
                        assert!(b.load_factor.is_finite() && b.mode.iter().all(|v| v.is_finite()), "{text}");
                        answers += 1;
                    }
                    Err(e) => assert!(numerical(&e), "{e}\n{text}"),
                }
                Some(answers)
            }
        });
        match outcome {
            Ok(Some(n)) => {
                parsed += 1;
                answered += n;
            }
            Ok(None) => {}
            Err(_) => panic!("panicked on\n{text}"),
        }
    }
    // The mutations leave work for both halves of the check.
    assert!(parsed > 100 && answered > 100, "{parsed} parsed, {answered} answered");
}

/// A flexure of modulus 7e10 Pa, `extra` from line 8 on.
fn rectangle(extra: &str) -> String {
    format!(
        "[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b\"\nlength = 0.01\nmodulus = 7e10\n{extra}"
    )
}

/// Bad sections (issue 11): each names its key and the place of its value.
#[test]
fn bad_sections_name_key_line_and_column() {
    let thick = "thickness = 0.004\n";
    let with_width = |w: &str| rectangle(&format!("width = {w}\n{thick}"));
    let with_notch = |n: &str| rectangle(&format!("width = 0.01\n{thick}notch = {n}\n"));
    let cases = [
        (with_width("0.0"), "line 8, column 9", "width = 0: must be greater than zero"),
        (with_width("-0.01"), "line 8, column 9", "width = -0.01: must be greater than zero"),
        (
            rectangle("width = 0.01\nthickness = [0.004, 0.0]\n"),
            "line 9, column 13",
            "thickness[1] = 0: must be greater",
        ),
        (rectangle("width = 0.01\nthickness = [-0.004, 0.001]\n"), "line 9, column 13", "thickness[0] = -0.004"),
        (with_width("[[0.0, 0.01], [0.5, 0.02]]"), "line 8, column 9", "t = s/L must start at 0, end at 1"),
        (with_width("[[0.1, 0.01], [1.0, 0.02]]"), "line 8, column 9", "t = s/L must start at 0, end at 1"),
        (with_width("[[0.0, 0.01], [0.5, 0.02], [0.5, 0.02], [1.0, 0.01]]"), "line 8, column 9", "increase strictly"),
        (with_width("[[0.0, 0.01], [-0.5, 0.01], [1.0, 0.01]]"), "line 8, column 9", "width[1][0] = -0.5"),
        (with_width("[[0.0, 0.01], [1.0, nan]]"), "line 8, column 9", "width[1][1] = NaN: must be a finite number"),
        (with_width("[[0.0, 0.01], [1.0, 0.0]]"), "line 8, column 9", "width[1][1] = 0: must be greater than zero"),
        (with_width("[[0.0, 0.01]]"), "line 8, column 9", "at least two points"),
        (with_width("\"wide\""), "line 8, column 9", "width must be a number, [root, tip] or a table"),
        (with_width("[0.01, 0.02, 0.03]"), "line 8, column 9", "width must be a number, [root, tip] or a table"),
        (with_width("[[0.0, 0.01], [1.0]]"), "line 8, column 9", "width must be a number, [root, tip] or a table"),
        (with_width("inf"), "line 8, column 9", "width = inf: must be a finite number"),
        (
            with_notch("{ radius = 0.005, min_thickness = 0.004 }"),
            "line 10, column 9",
            "notch.min_thickness = 0.004: must be less than the thickness",
        ),
        (with_notch("{ radius = 0.005, min_thickness = 0.006 }"), "line 10, column 9", "deeper than the thickness"),
        (with_notch("{ radius = 0.001, min_thickness = 0.0001 }"), "line 10, column 9", "notch.radius = 0.001"),
        (with_notch("{ radius = -0.005, min_thickness = 0.001 }"), "line 10, column 9", "notch.radius = -0.005"),
        (with_notch("{ radius = 0.005, min_thickness = nan }"), "line 10, column 9", "notch.min_thickness = NaN"),
        (with_notch("{ radius = 0.005 }"), "line 10, column 9", "notch.min_thickness is missing"),
        (
            with_notch("{ radius = 0.005, min_thickness = 0.001, depth = 1 }"),
            "line 10, column 9",
            "unknown key `depth`",
        ),
        (
            with_notch("{ radius = \"big\", min_thickness = 0.001 }"),
            "line 10, column 9",
            "notch.radius must be a number",
        ),
        (with_notch("0.005"), "line 10, column 9", "notch must be { radius = R, min_thickness = h }"),
        // Thicker than the flexure is long (the library names the thickness, so it is placed there).
        (rectangle("width = 0.01\nthickness = 0.02\n"), "line 9, column 13", "thickness = 0.02 m at t = 0"),
        (rectangle(&format!("width = 0.01\n{thick}density = 0.0\n")), "line 10, column 11", "density = 0"),
        (
            rectangle(&format!("width = 0.01\n{thick}mass_per_length = [0.1, -0.1]\n")),
            "line 10, column 19",
            "mass_per_length[1] = -0.1",
        ),
        (
            rectangle(&format!("width = 0.01\n{thick}density = 2700.0\nmass_per_length = 0.1\n")),
            "line 11, column 19",
            "give density or mass_per_length, not both",
        ),
        (
            rectangle(&format!("width = 0.01\n{thick}yield_strength = 0.0\n")),
            "line 10, column 18",
            "yield_strength = 0",
        ),
        (rectangle(&format!("width = 0.01\n{thick}shape = 1\n")), "line 10, column 9", "shape = 1: must be from 2 to"),
        (rectangle(&format!("width = 0.01\n{thick}shape = 10001\n")), "line 10, column 9", "shape = 10001"),
        (rectangle(&format!("width = 0.01\n{thick}shape = -3\n")), "line 10, column 9", ""),
        (rectangle("width = 0.01\n"), "line 7, column 11", "thickness is missing"),
        (joint("notch = { radius = 0.005, min_thickness = 0.001 }\n"), "line 8, column 9", "`notch` goes with modulus"),
        (joint("density = 7850.0\n"), "line 8, column 11", "give mass_per_length with ei"),
        (joint("yield_strength = 1e8\n"), "line 8, column 18", "yield_strength needs a section to give a stress"),
        (joint("").replace("ei = 1e-3", "ei = [1e-3, 0.0]"), "line 7, column 6", "ei[1] = 0: must be greater"),
        (joint("").replace("ei = 1e-3", "ei = [[0.0, 1e-3], [1.0, inf]]"), "line 7, column 6", "ei[1][1] = inf"),
        (joint("").replace("ei = 1e-3", "ei = [1e-3, 1e20]"), "line 7, column 6", "ei = "),
        (
            joint("").replace("kind = \"flexure\"", "kind = \"revolute\"").replace("length = 0.01\nei = 1e-3\n", "")
                + "shape = 5\n",
            "line 6, column 9",
            "`shape` does not apply to a revolute joint",
        ),
    ];
    for (text, place, what) in cases {
        let e = file_error(&text);
        assert!(e.starts_with(&format!("{place}:")) && e.contains(what), "expected {what:?} at {place}:\n{text}\n{e}");
    }
}

/// The section forms read as the library builds them: a table through the
/// ends equals the linear taper, `[root, tip]` is `Profile::Linear`, a
/// notch leaves its least thickness at the middle, `density` gives ρ b h,
/// and the joint keeps `yield_strength` and `shape` for the report.
#[test]
fn section_forms_read_as_the_library_builds_them() {
    use flexure::mechanism::JointKind;
    use flexure::section::{Profile, Section};
    let flexure = |text: &str| match from_toml(text).unwrap().joints.remove(0).kind {
        JointKind::Flexure(f) => *f,
        _ => panic!("a flexure"),
    };
    let table = flexure(&rectangle("width = [[0.0, 0.01], [1.0, 0.02]]\nthickness = 0.004\n"));
    let taper = flexure(&rectangle("width = [0.01, 0.02]\nthickness = 0.004\n"));
    let k = taper.stiffness_matrix();
    let scale = k.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    // Both exact for a linear EI (Gauss–Legendre on one piece): to rounding.
    assert!(table.stiffness_matrix().iter().zip(k).all(|(a, b)| (a - b).abs() < 1e-13 * scale));
    let given = flexure(&joint("").replace("ei = 1e-3", "ei = [2e-3, 1e-3]"));
    let library = flexure::Flexure::new(0.01, 1.0, 3)
        .unwrap()
        .with_section(Section::given(Profile::Linear { root: 2e-3, tip: 1e-3 }).unwrap())
        .unwrap();
    assert_eq!(given.stiffness_matrix(), library.stiffness_matrix());
    assert!(given.section().thickness(0.5, 0.01).is_none());
    let text = rectangle(
        "width = 0.008\nthickness = 0.0105\nnotch = { radius = 0.005, min_thickness = 5e-4 }\ndensity = 2700.0\nyield_strength = 2.5e8\nshape = 7\n",
    );
    let notched = flexure(&text);
    assert_eq!(notched.section().thickness(0.5, 0.01), Some(5e-4));
    assert!((notched.section().mass_per_length(0.5, 0.01).unwrap() - 2700.0 * 0.008 * 5e-4).abs() < 1e-15);
    let r = from_toml(&text).unwrap().joints[0].report;
    assert_eq!((r.yield_strength, r.shape), (Some(2.5e8), Some(7)));
    assert!(from_toml(&rectangle("width = 0.0\nthickness = 0.004\n")).is_err());
}

/// Reference: statics, $M = F\thinspace y$ about the pin. A planar force
/// may leave out `at`, as a spatial one may: it then acts at the body
/// frame's origin, the same as `at = [0.0, 0.0]`.
#[test]
fn a_force_without_at_acts_at_the_body_origin() {
    let arm = "[[joint]]\nname = \"a\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"b\"\nstiffness = 1.0\n\
               [[joint]]\nname = \"c\"\nkind = \"fixed\"\nparent = \"b\"\nchild = \"d\"\norigin = [0.1, 0.0, 0.0]\n\
               [[force]]\nbody = \"d\"\nforce = [0.0, 0.01]\n";
    let without = from_toml(arm).unwrap();
    let with = from_toml(&format!("{arm}at = [0.0, 0.0]\n")).unwrap();
    assert_eq!(without, with);
    let s = solve(&without, &Settings::default()).unwrap();
    // Small rotation: k θ = F L cos θ, so θ ≈ 1e-3 to 1e-6.
    assert!((s.q[0] - 1e-3).abs() < 1e-6, "{}", s.q[0]);
}

/// Reference: the sources themselves. A file is parsed once: the reader's
/// one `DeTable::parse` (`file::Document::parse`), which the door
/// (`Model::from_document`), the hints and both dimensions' readers share;
/// no other parse of the text sits in the reader or the door.
#[test]
fn a_file_is_parsed_in_one_place() {
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut parses = Vec::new();
    // The folders' files, and their subfolders' (the door to one flexure is `model/flexure/`).
    let mut dirs = vec![src.join("mechanism/file"), src.join("model")];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            for (n, line) in text.lines().enumerate() {
                let code = line.split("//").next().unwrap_or("");
                if ["DeTable::parse", "toml::from_str", "toml::de::from_str"].iter().any(|p| code.contains(p)) {
                    parses.push(format!("{}:{}", path.display(), n + 1));
                }
            }
        }
    }
    assert_eq!(parses.len(), 1, "{parses:?}");
    assert!(parses[0].contains("document.rs"), "{parses:?}");
}

/// Reference: each example's text. An array given one number too many is
/// refused at its line, naming its key: the file's parser reads a
/// fixed-length array's first entries and dropped the rest unsaid (a
/// planar geom's `origin = [x, y, phi]` lost its angle). Every line of
/// every example (planar and spatial) that writes numbers in brackets gets
/// one more, before its first `]` (a tendon's via, an inertia's row, a
/// schedule's point).
#[test]
fn an_array_given_a_number_too_many_is_refused_at_its_line() {
    let dir = format!("{}/../../examples", env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<(String, String)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| (p.display().to_string(), std::fs::read_to_string(&p).unwrap()))
        .collect();
    // The keys no example writes: a spatial gravity, axis, rpy, inertia,
    // moment and a plane's normal, and the planar plane's normal.
    let spatial = "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[[joint]]\nname = \"hinge\"\nkind = \"revolute\"\n\
                   parent = \"ground\"\nchild = \"arm\"\naxis = [0.0, 0.0, 1.0]\nrpy = [0.0, 0.0, 0.0]\nstiffness = 1.0\n\
                   [[body]]\nname = \"arm\"\nmass = 0.1\ninertia = [[1e-4, 0.0, 0.0], [0.0, 1e-4, 0.0], [0.0, 0.0, 1e-4]]\n\
                   [[force]]\nname = \"push\"\nbody = \"arm\"\nmoment = [0.0, 0.0, 0.1]\n\
                   [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, 0.0, -0.5]\nnormal = [0.0, 0.0, 1.0]\n";
    let planar =
        spatial.replace("dimension = 3\n", "").replace("gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, -9.81]");
    let planar = planar
        .replace("axis = [0.0, 0.0, 1.0]\nrpy = [0.0, 0.0, 0.0]\n", "")
        .replace("inertia = [[1e-4, 0.0, 0.0], [0.0, 1e-4, 0.0], [0.0, 0.0, 1e-4]]", "inertia = 1e-4");
    let planar = planar.replace("moment = [0.0, 0.0, 0.1]", "moment = 0.1").replace("[0.0, 0.0, -0.5]", "[0.0, -0.5]");
    files.push(("spatial".into(), spatial.into()));
    files.push(("planar".into(), planar.replace("normal = [0.0, 0.0, 1.0]", "normal = [0.0, 1.0]")));
    let mut checked = 0;
    for (path, text) in &files {
        flexure::model::Model::from_toml(text).unwrap_or_else(|e| panic!("{path}: {e}"));
        for (n, line) in text.lines().enumerate() {
            let code = line.split('#').next().unwrap_or("");
            let (Some(open), Some(close)) = (code.find('['), code.find(']')) else { continue };
            let inner = code[..close].rsplit('[').next().unwrap_or("");
            let key = code.split('=').next().unwrap_or("").trim();
            if key.is_empty() || open > close || !inner.split(',').any(|x| x.trim().parse::<f64>().is_ok()) {
                continue;
            }
            let longer = format!("{}, 0.0{}", &line[..close], &line[close..]);
            let mutated: Vec<&str> =
                text.lines().enumerate().map(|(k, l)| if k == n { longer.as_str() } else { l }).collect();
            let e = match flexure::model::Model::from_toml(&mutated.join("\n")) {
                Ok(_) => panic!("{path}: line {}: {longer}: accepted", n + 1),
                Err(e) => e.to_string(),
            };
            let at = format!("line {},", n + 1);
            // A section's profile ([root, tip]) is read as a value of its own, with its own words.
            let refused = e.contains("numbers given") || e.contains("must be a number, [root, tip]");
            assert!(e.contains(&at) && e.contains(key) && refused, "{path}: {longer}: {e}");
            checked += 1;
        }
    }
    assert!(checked >= 90, "only {checked} arrays");
}
