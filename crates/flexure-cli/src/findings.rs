//! The library's findings (`flexure::mechanism::findings`) as the command
//! line tells them: each a `warning:` (or, for a closure with
//! `preload = true`, a `note:`) on stderr, and an entry of the answer's
//! `findings` list.

use crate::options::{note, warn};
use flexure::mechanism::Mechanism;
use flexure::mechanism::findings::{Crossing, Findings, OpenClosure, Severity, crossings_along, open_closures};
use flexure::mechanism::statics::Settings;
use serde_json::{Value, json};
use std::path::Path;

fn severity(s: Severity) -> &'static str {
    match s {
        Severity::Warning => "warning",
        Severity::Note => "note",
    }
}

fn closure_json(c: &OpenClosure) -> Value {
    let mut v = json!({
        "kind": "open_closure",
        "severity": severity(c.severity()),
        "closure": c.what,
        "place": c.place,
        "gap_m": c.gap,
        "preload": c.preload,
        "message": c.message(),
    });
    if let Some(turn) = c.turn {
        v["gap_rad"] = json!(turn);
    }
    if let Some(force) = c.force {
        v["preload_force_n"] = json!(force);
    }
    if let Some(moment) = c.moment {
        v["preload_moment_n_m"] = json!(moment);
    }
    v
}

fn crossing_json<P: AsRef<[f64]>>(c: &Crossing<P>) -> Value {
    let mut v = json!({
        "kind": "crossing",
        "severity": "warning",
        "parts": c.names,
        "at": c.at.as_ref(),
        "points": c.points,
        "message": c.message(),
    });
    for (k, key) in ["s_a", "s_b"].iter().enumerate() {
        if let Some(s) = c.s[k] {
            v[*key] = json!(s);
        }
    }
    v
}

/// The closures of `m` open at rest, told (warnings, or notes with `preload = true`) and listed.
pub fn closures<D: Findings>(m: &Mechanism<D>, file: &Path) -> Result<Vec<Value>, String> {
    let open = open_closures(m, &Settings::default()).map_err(|e| format!("{}: {e}", file.display()))?;
    Ok(open_answers(&open, file))
}

/// Closures open at rest, told (warnings, or notes with `preload = true`) and listed.
pub fn open_answers(open: &[OpenClosure], file: &Path) -> Vec<Value> {
    for c in open {
        let text = format!("{}: {}", file.display(), c.message());
        match c.severity() {
            Severity::Warning => warn(text),
            Severity::Note => note(text),
        }
    }
    open.iter().map(closure_json).collect()
}

/// Parts that cross, each told and listed.
pub fn crossing_answers<P: AsRef<[f64]>>(found: Vec<Crossing<P>>, file: &Path) -> Vec<Value> {
    for c in &found {
        warn(format!("{}: {}", file.display(), c.message()));
    }
    found.iter().map(crossing_json).collect()
}

/// The crossings at each of a series of shapes, `(value, q)` with the
/// value named `what` (a swept load, or `t (s)`) and the shapes called
/// `shapes_are` ("swept values", "samples"): one warning per pair of parts,
/// at the first value where they cross, saying at how many more; each
/// shape's crossings listed with its value under `key`.
pub fn along<D: Findings>(
    m: &Mechanism<D>,
    shapes: &[(f64, &[f64])],
    (what, shapes_are): (&str, &str),
    key: &str,
    file: &Path,
) -> Vec<Value> {
    crossing_answers_along(crossings_along(m, shapes.iter().map(|s| s.1)), shapes, (what, shapes_are), key, file)
}

/// Crossings found along a series of shapes (see [`along`]), told and listed.
pub fn crossing_answers_along<P: AsRef<[f64]>>(
    found: Vec<(usize, Vec<Crossing<P>>)>,
    shapes: &[(f64, &[f64])],
    (what, shapes_are): (&str, &str),
    key: &str,
    file: &Path,
) -> Vec<Value> {
    let mut told: Vec<(&[String; 2], usize)> = Vec::new();
    for (_, cs) in &found {
        for c in cs {
            match told.iter_mut().find(|t| t.0 == &c.names) {
                Some(t) => t.1 += 1,
                None => told.push((&c.names, 1)),
            }
        }
    }
    for (names, count) in &told {
        let (k, c) = found
            .iter()
            .find_map(|(k, cs)| cs.iter().find(|c| &&c.names == names).map(|c| (*k, c)))
            .expect("counted above");
        let others = match count - 1 {
            0 => String::new(),
            n => format!(" and at {n} more of the {shapes_are}"),
        };
        warn(format!(
            "{}: at {what} = {}{others} (listed in `findings`): {}",
            file.display(),
            shapes[k].0,
            c.message()
        ));
    }
    found
        .iter()
        .flat_map(|(k, cs)| {
            cs.iter().map(move |c| {
                let mut v = crossing_json(c);
                v[key] = json!(shapes[*k].0);
                v
            })
        })
        .collect()
}

/// The closures of `model` open at rest, told (before any analysis, which
/// may fail because of them) and listed.
pub fn open_at_rest(model: &flexure::model::Model, file: &Path) -> Result<Vec<serde_json::Value>, String> {
    let open = model.open_closures().map_err(|e| format!("{}: {e}", file.display()))?;
    Ok(open_answers(&open, file))
}
