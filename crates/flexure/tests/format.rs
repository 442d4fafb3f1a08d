//! `docs/mechanism-format.md` against the parser it documents.
//!
//! The keys the parser accepts are read from its source,
//! `src/mechanism/file/`: the fields of its `serde` structs, all of which
//! deny unknown fields, less the keys only the other dimension takes
//! (`SPATIAL_ONLY`, `PLANAR_ONLY`). The page's key tables must name exactly
//! those keys, table by table and dimension by dimension; its examples must
//! parse and solve; and what it says of frames, signs and defaults is
//! checked here against closed forms.

use flexure::mechanism::file::{PLANAR_ONLY, SPATIAL_ONLY, from_toml};
use flexure::mechanism::kinematics::frames;
use flexure::mechanism::statics::{Settings, solve};
use flexure::mechanism::sweep::Parameter;
use flexure::mechanism::{JointKind, Mechanism};
use std::collections::BTreeSet;
use std::f64::consts::FRAC_PI_2;

/// The parser's files, one per part of the document (checked to be all of them).
const PARSER_FILES: [(&str, &str); 11] = [
    ("bodies.rs", include_str!("../src/mechanism/file/bodies.rs")),
    ("closures.rs", include_str!("../src/mechanism/file/closures.rs")),
    ("dimension.rs", include_str!("../src/mechanism/file/dimension.rs")),
    ("document.rs", include_str!("../src/mechanism/file/document.rs")),
    ("flexures.rs", include_str!("../src/mechanism/file/flexures.rs")),
    ("geoms.rs", include_str!("../src/mechanism/file/geoms.rs")),
    ("joints.rs", include_str!("../src/mechanism/file/joints.rs")),
    ("loads.rs", include_str!("../src/mechanism/file/loads.rs")),
    ("mod.rs", include_str!("../src/mechanism/file/mod.rs")),
    ("schedules.rs", include_str!("../src/mechanism/file/schedules.rs")),
    ("validation.rs", include_str!("../src/mechanism/file/validation.rs")),
];
const PAGE: &str = include_str!("../../../docs/mechanism-format.md");

/// A `serde` struct of the parser: its name and its fields (key, type).
struct Table {
    name: String,
    fields: Vec<(String, String)>,
}

/// Every `#[derive(Deserialize)]` struct of the parser, refusing any `serde`
/// attribute that could change which keys are accepted (rename, alias,
/// flatten, …) or let unknown keys through: this reading would miss them.
fn parser_tables() -> Vec<Table> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/mechanism/file");
    let mut files: Vec<String> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    files.sort();
    let listed: Vec<&str> = PARSER_FILES.iter().map(|(name, _)| *name).collect();
    assert_eq!(files, listed, "tests/format.rs must read every file of the parser");
    tables_in(&parser())
}

/// The `Deserialize` structs of a parser's source (see [`parser_tables`]).
fn tables_in(parser: &str) -> Vec<Table> {
    for line in parser.lines().map(str::trim).filter(|l| l.starts_with("#[serde(")) {
        assert!(
            line == "#[serde(deny_unknown_fields)]" || line == "#[serde(default)]" || line == "#[serde(bound = \"\")]",
            "the parser uses `{line}`: teach tests/format.rs what it does to the accepted keys"
        );
    }
    let lines: Vec<&str> = parser.lines().map(str::trim).collect();
    let mut tables = Vec::new();
    for (i, _) in lines.iter().enumerate().filter(|(_, l)| l.contains("Deserialize)]")) {
        assert_eq!(
            lines[i + 1],
            "#[serde(deny_unknown_fields)]",
            "line {}: a Deserialize struct must deny unknown keys",
            i + 2
        );
        // The struct, after its attributes: `struct Name {` or `struct Name<D: …> {`.
        let at = (i + 2..lines.len()).find(|&k| !lines[k].starts_with("#[")).unwrap();
        let name = lines[at]
            .strip_prefix("struct ")
            .and_then(|s| s.strip_suffix(" {"))
            .map(|s| s.split('<').next().unwrap())
            .unwrap_or_else(|| panic!("line {}: expected `struct Name {{`, got {:?}", at + 1, lines[at]));
        let mut fields = Vec::new();
        for field in lines[at + 1..].iter().take_while(|l| **l != "}") {
            if field.is_empty() || field.starts_with("//") || field.starts_with("#[") {
                continue;
            }
            let (key, ty) = field.split_once(':').unwrap_or_else(|| panic!("{name}: cannot read field {field:?}"));
            fields.push((key.trim().to_string(), ty.trim().trim_end_matches(',').to_string()));
        }
        assert!(!fields.is_empty(), "{name} has no fields");
        tables.push(Table { name: name.to_string(), fields });
    }
    tables
}

/// The parser's source, its files one after the other, without the
/// `pub(super)` that lets the parts share their structs.
fn parser() -> String {
    PARSER_FILES.iter().map(|(_, text)| *text).collect::<String>().replace("pub(super) ", "")
}

/// The file's tables, by the name they have in TOML (`""` for the top
/// level), each with the keys the parser accepts in it in a file of one
/// dimension: all its structs' keys but those `refused` (table, key, why).
fn parser_keys(refused: &[(&str, &[&str], &str)]) -> Vec<(String, BTreeSet<String>)> {
    let mut tables = keys_of(parser_tables());
    for (table, keys) in &mut tables {
        keys.retain(|k| !refused.iter().any(|(t, r, _)| t == table && r.contains(&k.as_str())));
    }
    tables.retain(|(table, _)| !refused.iter().any(|(t, r, _)| t.is_empty() && r.contains(&table.as_str())));
    tables
}

/// [`parser_keys`] of a parser's structs.
fn keys_of(tables: Vec<Table>) -> Vec<(String, BTreeSet<String>)> {
    let find = |name: &str| tables.iter().find(|t| t.name == name).unwrap_or_else(|| panic!("no struct {name}"));
    let top = find("FileToml");
    let mut out = vec![(String::new(), BTreeSet::new())];
    let mut reached = BTreeSet::from([top.name.clone()]);
    for (key, ty) in &top.fields {
        match ty.strip_prefix("Vec<").and_then(|t| t.strip_suffix('>')).map(|t| t.split('<').next().unwrap()) {
            // An array of tables, `[[key]]`, read by its own struct.
            Some(inner) => {
                let table = find(inner);
                reached.insert(table.name.clone());
                out.push((key.clone(), table.fields.iter().map(|(k, _)| k.clone()).collect()));
            }
            None => {
                out[0].1.insert(key.clone());
            }
        }
    }
    // Inline tables (a schedule's `harmonic`) are read by structs that a table's field names.
    for t in &tables {
        if reached.contains(&t.name) {
            for (_, ty) in &t.fields {
                reached.extend(tables.iter().filter(|u| ty.contains(&u.name)).map(|u| u.name.clone()));
            }
        }
    }
    let all: BTreeSet<String> = tables.iter().map(|t| t.name.clone()).collect();
    assert_eq!(reached, all, "a Deserialize struct of the parser that no table of the file reaches");
    out
}

/// The page's sections: (heading, body).
fn sections() -> Vec<(&'static str, String)> {
    let mut out: Vec<(&'static str, String)> = Vec::new();
    for line in PAGE.lines() {
        if let Some(heading) = line.strip_prefix("## ") {
            out.push((heading, String::new()));
        } else if let Some((_, body)) = out.last_mut() {
            body.push_str(line);
            body.push('\n');
        }
    }
    out
}

/// The keys named in the first column of a section's tables: rows "| `key` |".
fn documented_keys(body: &str) -> BTreeSet<String> {
    body.lines()
        .filter_map(|l| l.strip_prefix("| `"))
        .map(|l| l.split('`').next().unwrap_or_default().to_string())
        .collect()
}

/// The section documenting table `table` (`""`: the top level).
fn section_of(table: &str) -> String {
    let all = sections();
    let matching: Vec<&(&str, String)> = if table.is_empty() {
        all.iter().filter(|(h, _)| h.contains("top level")).collect()
    } else {
        all.iter().filter(|(h, _)| h.contains(&format!("`[[{table}]]`"))).collect()
    };
    assert_eq!(
        matching.len(),
        1,
        "docs/mechanism-format.md needs one `## ` section for [[{table}]] (or the top level)"
    );
    matching[0].1.clone()
}

/// Every key the parser accepts is named in its table's section, and every
/// key a section names is accepted: the page and the parser agree.
#[test]
fn every_parser_key_is_documented() {
    let tables = parser_keys(SPATIAL_ONLY);
    assert!(tables.len() >= 7, "expected the top level and six tables, read {}", tables.len());
    for (table, accepted) in &tables {
        let documented = documented_keys(&section_of(table));
        let shown = if table.is_empty() { "the top level".to_string() } else { format!("[[{table}]]") };
        let missing: Vec<_> = accepted.difference(&documented).collect();
        let extra: Vec<_> = documented.difference(accepted).collect();
        assert!(
            missing.is_empty(),
            "{shown}: the parser accepts {missing:?}, which docs/mechanism-format.md does not document"
        );
        assert!(extra.is_empty(), "{shown}: docs/mechanism-format.md documents {extra:?}, which the parser refuses");
        if !table.is_empty() {
            // The top level names each array of tables.
            assert!(section_of("").contains(&format!("`[[{table}]]`")), "the top level does not name [[{table}]]");
        }
    }
    // The joint kinds: the string literals the parser matches `kind` on.
    let parser = parser();
    let line = parser
        .lines()
        .find(|l| l.contains("checked_kind(") && !l.contains("spherical") && l.contains("&["))
        .expect("the planar parser's list of kinds");
    let kinds: Vec<&str> = line.split('"').skip(1).step_by(2).collect();
    assert_eq!(kinds, ["flexure", "revolute", "prismatic", "fixed"]);
    let joint = section_of("joint");
    for kind in kinds {
        assert!(joint.contains(&format!("`\"{kind}\"`")), "kind {kind:?} is not documented");
    }
}

/// The page's TOML examples parse, solve to a stable equilibrium, and the
/// numbers the page quotes from `flexure solve` are what they give.
#[test]
fn examples_parse_and_solve() {
    let blocks: Vec<String> = PAGE
        .split("```toml\n")
        .skip(1)
        .map(|b| b.split("```").next().unwrap().to_string())
        .filter(|b| !b.contains("dimension = 3"))
        .collect();
    assert!(blocks.len() >= 2, "the page's examples");
    for (i, text) in blocks.iter().enumerate() {
        let m = from_toml(text).unwrap_or_else(|e| panic!("example {}: {e}", i + 1));
        let s = solve(&m, &Settings::default()).unwrap_or_else(|e| panic!("example {}: {e}", i + 1));
        assert!(s.stable, "example {}", i + 1);
    }
    // Quoted to 6 decimals from `flexure solve`; the solver converges far tighter.
    let angle = |text: &str, body: &str| {
        let m = from_toml(text).unwrap();
        let s = solve(&m, &Settings::default()).unwrap();
        frames(&m, &s.q).bodies[m.body(body).unwrap()].phi
    };
    assert!((angle(&blocks[0], "arm") - -0.078267).abs() < 5e-7);
    assert!(PAGE.contains("`phi: -0.078267`"));
    assert!((angle(&blocks[1], "post") - 1.552022).abs() < 5e-7);
    assert!(PAGE.contains("`phi: 1.552022`"));
}

/// A sprung arm: a revolute joint of stiffness 1 N·m/rad from the ground to
/// body `arm`, with `top` above it (top-level keys) and `extra` below.
fn arm(top: &str, extra: &str) -> Mechanism {
    from_toml(&format!(
        "{top}[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 1.0\n{extra}"
    ))
    .unwrap()
}

/// The root of a strictly increasing `f` on [lo, hi], by bisection to rounding.
fn root(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    assert!(f(lo) < 0.0 && f(hi) > 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

/// "`force` is in the ground frame, `at` in the body's": a sprung arm
/// (k = 1 N·m/rad) standing up at rest (rest = π/2), pushed by F = 2 N along
/// the ground's x at a = 0.5 m along the arm, balances at
/// k(θ − π/2) + F a sin θ = 0. Were `force` in the body frame it would pull
/// along the arm and leave θ = π/2; were `at` in the ground frame the push
/// would act at (0.5, 0) on the ground's axis. Tolerance 1e-9 rad: the
/// solver converges to a relative residual of 1e-12.
#[test]
fn force_in_ground_frame_at_in_body_frame() {
    let m = arm("", "rest = 1.5707963267948966\n[[force]]\nbody = \"arm\"\nat = [0.5, 0.0]\nforce = [2.0, 0.0]\n");
    let theta = solve(&m, &Settings::default()).unwrap().q[0];
    let exact = root(|t| (t - FRAC_PI_2) + 2.0 * 0.5 * t.sin(), 0.0, FRAC_PI_2);
    assert!((theta - exact).abs() < 1e-9, "{theta} vs {exact}");
    assert!(FRAC_PI_2 - theta > 0.5, "the push turned the arm clockwise");
}

/// Gravity in the ground frame, acting at `com` in the body's frame: a
/// sprung horizontal arm with m = 0.1 kg at 0.5 m under g = 9.81 balances
/// at kθ + m g l cos θ = 0 (a follower load would give θ = −m g l/k exactly).
#[test]
fn gravity_in_ground_frame_at_com() {
    let m = arm("gravity = [0.0, -9.81]\n", "[[body]]\nname = \"arm\"\nmass = 0.1\ncom = [0.5, 0.0]\n");
    let theta = solve(&m, &Settings::default()).unwrap().q[0];
    let exact = root(|t| t + 0.1 * 9.81 * 0.5 * t.cos(), -FRAC_PI_2, 0.0);
    assert!((theta - exact).abs() < 1e-9, "{theta} vs {exact}");
    assert!((theta + 0.4905).abs() > 0.01, "not a follower load");
}

/// A moment is counter-clockwise positive: θ = M/k exactly (a linear spring).
#[test]
fn moment_counter_clockwise() {
    let m = arm("", "[[force]]\nbody = \"arm\"\nat = [0.0, 0.0]\nmoment = 0.25\n");
    assert!((solve(&m, &Settings::default()).unwrap().q[0] - 0.25).abs() < 1e-12);
}

/// Child frames as the page describes them: a joint's root frame at
/// `origin` in the parent's frame; a revolute child turned by θ = `rest`,
/// a prismatic child moved by d = `rest` along the root's x, a straight
/// flexure's child at (L, 0) in the root frame. Exact up to rounding.
#[test]
fn child_frames() {
    let m = from_toml(
        "[[joint]]\nname = \"r\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"a\"\norigin = [1.0, 2.0, 0.5]\nrest = 0.25\n\
         [[joint]]\nname = \"p\"\nkind = \"prismatic\"\nparent = \"a\"\nchild = \"b\"\nrest = 0.1\n\
         [[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"b\"\nchild = \"c\"\norigin = [0.0, 0.0, 1.0]\nlength = 0.3\nei = 1.0\norder = 5\n",
    )
    .unwrap();
    let f = frames(&m, &m.rest());
    let body = |name: &str| f.bodies[m.body(name).unwrap()];
    let (a, b, c) = (body("a"), body("b"), body("c"));
    assert!((a.phi - 0.75).abs() < 1e-15 && (a.x - 1.0).abs() < 1e-15 && (a.y - 2.0).abs() < 1e-15);
    let (s, co) = 0.75f64.sin_cos();
    assert!((b.x - (1.0 + 0.1 * co)).abs() < 1e-15 && (b.y - (2.0 + 0.1 * s)).abs() < 1e-15);
    let (s, co) = 1.75f64.sin_cos();
    assert!((c.phi - 1.75).abs() < 1e-15);
    assert!((c.x - (b.x + 0.3 * co)).abs() < 1e-14 && (c.y - (b.y + 0.3 * s)).abs() < 1e-14);
    // The default quadrature is order + 2.
    let JointKind::Flexure(flex) = &m.joints[2].kind else { panic!("joint f is a flexure") };
    assert_eq!(flex.quadrature_points(), 7);
}

/// A force without a name is named by its index, from "0", and a sweep finds it so.
#[test]
fn unnamed_forces_are_numbered() {
    let m = arm("", "[[force]]\nbody = \"arm\"\nat = [0.0, 0.0]\n[[force]]\nbody = \"arm\"\nat = [0.1, 0.0]\n");
    let names: Vec<&str> = m.forces.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["0", "1"]);
    assert_eq!(Parameter::parse(&m, "force.1.fy").unwrap(), Parameter::Force(1, 2));
}

/// The keys named in the first cell of a section's table rows, every one
/// of them (a row may name several: "| `a`, `b` |").
fn all_documented_keys(body: &str) -> BTreeSet<String> {
    body.lines()
        .filter_map(|l| l.strip_prefix("| "))
        .filter_map(|l| l.split(" |").next())
        .flat_map(|cell| cell.split(", ").filter_map(|k| k.strip_prefix('`')?.strip_suffix('`')).map(str::to_string))
        .collect()
}

/// The page's `### ` subsections of its spatial section: (heading, body).
fn spatial_sections() -> Vec<(String, String)> {
    let (_, spatial) = sections().into_iter().find(|(h, _)| h.contains("dimension = 3")).expect("a spatial section");
    let mut out: Vec<(String, String)> = Vec::new();
    for line in spatial.lines() {
        if let Some(heading) = line.strip_prefix("### ") {
            out.push((heading.to_string(), String::new()));
        } else if let Some((_, body)) = out.last_mut() {
            body.push_str(line);
            body.push('\n');
        }
    }
    out
}

/// The spatial file (`dimension = 3`): every key its parser accepts is in
/// the spatial section's table for it, and every key a table names is
/// accepted by one of the parser's tables that section documents.
#[test]
fn every_spatial_parser_key_is_documented() {
    let tables = parser_keys(PLANAR_ONLY);
    assert_eq!(tables.len(), 10, "the top level and nine tables");
    let subsections = spatial_sections();
    let section = |table: &str| -> &(String, String) {
        let found: Vec<&(String, String)> = subsections
            .iter()
            .filter(
                |(h, _)| if table.is_empty() { h.contains("top level") } else { h.contains(&format!("`[[{table}]]`")) },
            )
            .collect();
        assert_eq!(found.len(), 1, "one spatial subsection for [[{table}]] (or the top level)");
        found[0]
    };
    for (table, accepted) in &tables {
        let (heading, body) = section(table);
        let documented = all_documented_keys(body);
        let missing: Vec<_> = accepted.difference(&documented).collect();
        assert!(
            missing.is_empty(),
            "[[{table}]] in space: the parser accepts {missing:?}, which the page does not document"
        );
        // The keys of every table this subsection covers.
        let covered: BTreeSet<String> =
            tables
                .iter()
                .filter(|(t, _)| {
                    if t.is_empty() { heading.contains("top level") } else { heading.contains(&format!("`[[{t}]]`")) }
                })
                .flat_map(|(_, k)| k.iter().cloned())
                .collect();
        let extra: Vec<_> = documented.difference(&covered).collect();
        assert!(extra.is_empty(), "{heading}: the page documents {extra:?}, which the parser refuses");
        if !table.is_empty() {
            assert!(
                section("").1.contains(&format!("`[[{table}]]`")),
                "the spatial top level does not name [[{table}]]"
            );
        }
    }
    let parser = parser();
    let line = parser
        .lines()
        .find(|l| l.contains("checked_kind(") && l.contains("spherical"))
        .expect("the spatial parser's list of kinds");
    let kinds: Vec<&str> = line.split('"').skip(1).step_by(2).collect();
    assert_eq!(kinds, ["flexure", "revolute", "prismatic", "spherical", "fixed"]);
    for kind in kinds {
        assert!(section("joint").1.contains(&format!("`\"{kind}\"`")), "spatial kind {kind:?} is not documented");
    }
}

/// The page's spatial example parses and solves to the numbers it quotes:
/// the tip's y against the closed form $FL^3/3EI_z$ (1e-3: the large
/// deflection and the twist move it that little), and the numbers quoted
/// from `flexure solve` to their printed digits.
#[test]
fn the_spatial_example_solves_as_the_page_says() {
    use flexure::report::placements;
    let text = PAGE
        .split("```toml\n")
        .skip(1)
        .map(|b| b.split("```").next().unwrap())
        .find(|b| b.contains("dimension = 3"))
        .unwrap();
    let m = flexure::mechanism::file::spatial_from_toml(text).unwrap();
    let s = flexure::mechanism::statics::solve(&m, &Settings::default()).unwrap();
    assert!(s.stable);
    let tip = &placements(&m, &s.q)[0];
    let ei_z = 200e9 * 0.01 * 0.0005f64.powi(3) / 12.0;
    let linear = 0.5 * 0.05f64.powi(3) / (3.0 * ei_z);
    assert!((tip.position[1] - linear).abs() < 1e-3 * linear, "{:?} against {linear}", tip.position);
    assert!((tip.position[1] - 0.001001).abs() < 5e-7 && (tip.position[0] - 0.049988).abs() < 5e-7);
    assert!((tip.rpy[0] - -0.004242).abs() < 5e-7);
    assert!(PAGE.contains("position: 0.049988 0.001001") && PAGE.contains("rpy: -0.004242"));
}
