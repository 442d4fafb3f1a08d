//! The figures as a reader meets them, checked in the SVG text of
//! `reproduce` and of `draw` on every example (issue 13, "Figures fit to
//! publish"):
//! - every text at least 12 px;
//! - tick labels at round values: at most 6 significant digits (never
//!   `9.999999999999999e-6`), no negative zero, powers of ten on log axes,
//!   whole numbers on axes of counts;
//! - curves that may overlap differ in line width, dash or marker, not in colour alone;
//! - shapes at one scale on both axes (checked from the tick positions);
//! - `draw`'s legend names every shape, tendon and load and states the arrows' scale.
//!
//! Runs the CLI in-process through `flexure_cli::run`.

use serde_json::Value;
use std::collections::BTreeSet;
use std::path::Path;

fn run(args: &[&str]) -> Value {
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let mut all: Vec<&str> = args.to_vec();
    all.push("--json");
    let code = flexure_cli::run(std::iter::once("flexure").chain(all.iter().copied()), &mut out, &mut err);
    assert_eq!(code, 0, "{args:?}: {}", String::from_utf8_lossy(&err));
    serde_json::from_slice(&out).unwrap()
}

/// One `<text>` element.
#[derive(Debug)]
struct Text {
    class: String,
    size: f64,
    x: f64,
    y: f64,
    body: String,
}

fn attr(tag: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    Some(tag[start..start + tag[start..].find('"')?].to_string())
}

fn texts(svg: &str) -> Vec<Text> {
    svg.split("<text")
        .skip(1)
        .map(|chunk| {
            let (tag, rest) = chunk.split_once('>').unwrap();
            let body = rest.split("</text>").next().unwrap();
            let number = |n: &str| attr(tag, n).and_then(|v| v.parse().ok()).unwrap_or(f64::NAN);
            Text {
                class: attr(tag, "class").unwrap_or_default(),
                size: number("font-size"),
                x: number("x"),
                y: number("y"),
                body: body.replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", "\"").replace("&amp;", "&"),
            }
        })
        .collect()
}

/// A linear tick label's value (with a true minus sign read as `-`).
fn value(label: &str) -> Option<f64> {
    label.replace('−', "-").parse().ok()
}

/// The rules every figure keeps; returns its texts.
fn readable(name: &str, svg: &str) -> Vec<Text> {
    let t = texts(svg);
    assert!(t.len() >= 6, "{name}: too little text");
    for x in &t {
        // The smallest text in print: 12 px at the default size.
        assert!(x.size >= 12.0, "{name}: {:?} is {} px", x.body, x.size);
    }
    for axis in ["tick-x", "tick-y"] {
        let ticks: Vec<&Text> = t.iter().filter(|x| x.class == axis).collect();
        assert!(ticks.len() >= 2, "{name}: {axis} has {} labels", ticks.len());
        for tick in ticks {
            let digits =
                tick.body.trim_start_matches(['−', '-', '0', '.']).chars().filter(char::is_ascii_digit).count();
            assert!(digits <= 6, "{name}: tick {:?} has {digits} significant digits", tick.body);
            assert!(!tick.body.contains("e-") && !tick.body.contains("e+"), "{name}: tick {:?}", tick.body);
            if let Some(v) = value(&tick.body) {
                assert!(!(v == 0.0 && tick.body.starts_with(['−', '-'])), "{name}: negative zero tick {:?}", tick.body);
            }
        }
    }
    t
}

/// Pixels per unit along an axis, from its first and last tick labels.
fn px_per_unit(t: &[Text], class: &str, name: &str) -> f64 {
    let ticks: Vec<(f64, f64)> = t
        .iter()
        .filter(|x| x.class == class)
        .map(|x| {
            (
                value(&x.body).unwrap_or_else(|| panic!("{name}: tick {:?}", x.body)),
                if class == "tick-x" { x.x } else { x.y },
            )
        })
        .collect();
    let (a, b) = (ticks[0], ticks[ticks.len() - 1]);
    ((b.1 - a.1) / (b.0 - a.0)).abs()
}

/// Both axes at one scale: a tick position is rounded to 0.01 px, so two
/// ticks hundreds of px apart agree to well under 0.1 %.
fn same_scale(t: &[Text], name: &str) {
    let (sx, sy) = (px_per_unit(t, "tick-x", name), px_per_unit(t, "tick-y", name));
    assert!((sx / sy - 1.0).abs() < 1e-3, "{name}: {sx} px per unit across, {sy} up");
}

/// The line styles (width, dash) of the curves drawn; markers count as a style too.
fn styles(svg: &str) -> BTreeSet<String> {
    let mut out: BTreeSet<String> = svg
        .split("<polyline")
        .skip(1)
        .map(|c| {
            let tag = c.split('>').next().unwrap();
            format!("{:?} {:?}", attr(tag, "stroke-width"), attr(tag, "stroke-dasharray"))
        })
        .collect();
    for marker in ["<circle", "<rect", "<polygon"] {
        if svg.contains(marker) {
            out.insert(marker.into());
        }
    }
    out
}

#[test]
fn report_figures_are_fit_to_publish() {
    let dir = tempfile::tempdir().unwrap();
    run(&["reproduce", "--out", dir.path().to_str().unwrap()]);
    let read = |name: &str| std::fs::read_to_string(dir.path().join(name)).unwrap();
    let mut seen = 0;
    for entry in std::fs::read_dir(dir.path()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "svg") {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            readable(&name, &read(&name));
            seen += 1;
        }
    }
    assert!(seen >= 10, "{seen} figures");

    // Log axes: decades as powers of ten; the x axes count orders or segments.
    for name in ["convergence_eta.svg", "convergence_buckling.svg", "fig4_eta.svg"] {
        let t = readable(name, &read(name));
        for tick in t.iter().filter(|x| x.class == "tick-y") {
            let power = tick.body.split('×').next_back().unwrap();
            assert!(
                power.starts_with("10") && power[2..].chars().all(|c| "⁻⁰¹²³⁴⁵⁶⁷⁸⁹".contains(c)),
                "{name}: {:?}",
                tick.body
            );
        }
        for tick in t.iter().filter(|x| x.class == "tick-x") {
            assert!(tick.body.parse::<i64>().is_ok(), "{name}: count axis tick {:?}", tick.body);
        }
    }

    // Curves that lie on one another differ in more than colour, and have a legend.
    for (name, curves) in [
        ("fig4_shapes.svg", 3),
        ("fig5_curvature.svg", 3),
        ("fig8_position.svg", 3),
        ("fig8_angle.svg", 3),
        ("convergence_buckling.svg", 4),
    ] {
        let svg = read(name);
        let legend = texts(&svg).into_iter().filter(|x| x.class == "legend").count();
        assert_eq!(legend, curves, "{name}: legend entries");
        assert!(styles(&svg).len() >= curves, "{name}: styles {:?}", styles(&svg));
    }

    // Shapes: one scale on both axes.
    for name in ["fig4_shapes.svg", "fig12_ellipses.svg"] {
        same_scale(&readable(name, &read(name)), name);
    }
}

/// The names under each `[[table]]` of a mechanism file.
fn names(toml: &str, table: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in toml.lines().map(str::trim) {
        if line.starts_with("[[") {
            inside = line == format!("[[{table}]]");
        } else if inside && let Some(v) = line.strip_prefix("name = \"") {
            out.push(v.trim_end_matches('"').to_string());
        }
    }
    out
}

#[test]
fn drawings_name_every_shape_tendon_and_load() {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let dir = tempfile::tempdir().unwrap();
    let mut files: Vec<_> = std::fs::read_dir(&examples)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        // Planar drawings here; spatial ones in tests/spatial_mechanism.rs.
        .filter(|p| !std::fs::read_to_string(p).unwrap().contains("dimension = 3"))
        .collect();
    files.sort();
    assert!(files.len() >= 6);
    for file in &files {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let out = dir.path().join(format!("{name}.svg"));
        let v = run(&["draw", file.to_str().unwrap(), "--out", out.to_str().unwrap()]);
        let svg = std::fs::read_to_string(&out).unwrap();
        let t = readable(&name, &svg);
        same_scale(&t, &name);
        let legend: Vec<&str> = t.iter().filter(|x| x.class == "legend").map(|x| x.body.as_str()).collect();
        for shape in ["ground", "unloaded", "loaded"] {
            assert!(legend.contains(&shape), "{name}: no {shape:?} in {legend:?}");
        }
        let toml = std::fs::read_to_string(file).unwrap();
        for tendon in names(&toml, "tendon") {
            assert!(
                legend.iter().any(|l| l.starts_with(&format!("tendon {tendon}: "))),
                "{name}: {tendon} in {legend:?}"
            );
        }
        for force in names(&toml, "force") {
            let named = |kind: &str| legend.iter().any(|l| l.starts_with(&format!("{kind} {force} on ")));
            assert!(named("force") || named("moment"), "{name}: {force} in {legend:?}");
        }
        if toml.contains("[[body]]") && toml.contains("gravity") {
            assert!(legend.iter().any(|l| l.starts_with("weight of ")), "{name}: no weight in {legend:?}");
        }
        // A drawn force states its scale, the one the command reports.
        if let Some(k) = v["force_scale_m_per_n"].as_f64() {
            let stated = legend
                .iter()
                .find_map(|l| l.strip_prefix("force arrows: ").and_then(|r| r.strip_suffix(" m per N")))
                .unwrap_or_else(|| panic!("{name}: no arrow scale in {legend:?}"));
            assert_eq!(value(stated), Some(k), "{name}");
        }
    }
    // The moment in mixed_chain.toml is drawn and named with its sense.
    let svg = std::fs::read_to_string(dir.path().join("mixed_chain.toml.svg")).unwrap();
    assert!(
        texts(&svg).iter().any(|x| x.class == "legend" && x.body == "moment grip on hand: 0.01 N·m counter-clockwise")
    );

    // A sweep: one named shape per value, in its unit.
    let out = dir.path().join("sweep.svg");
    let file = examples.join("finger.toml");
    run(&["draw", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--sweep", "tendon.flexor.tension=0:12:3"]);
    let t = readable("sweep", &std::fs::read_to_string(&out).unwrap());
    for shape in ["tendon.flexor.tension = 0 N", "tendon.flexor.tension = 6 N", "tendon.flexor.tension = 12 N"] {
        assert!(t.iter().any(|x| x.class == "legend" && x.body == shape), "no {shape:?}");
    }
}
