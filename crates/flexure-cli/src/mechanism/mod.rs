//! Subcommands on mechanism files: `solve` (with its compliance and
//! sweeps), `buckle` and `draw`, and the checks `solve` and `draw` share.

mod buckle;
mod checks;
mod draw;
pub mod drawing;
pub mod projection;
pub mod scene;
mod solve;
pub mod spatial;

pub use buckle::{BuckleArgs, buckle_cmd};
pub use draw::{DrawArgs, draw_cmd};
pub use solve::{SolveArgs, solve_cmd};

use crate::options::number;
use flexure::mechanism::Mechanism;
use flexure::mechanism::file::{ReportOptions, from_toml, reports};
use flexure::mechanism::statics::Solution;
use serde_json::{Value, json};
use std::path::Path;

/// A solver's error on mechanism file `file`, after the file's name, with
/// the loads named where it is about the load as a whole ([`loads_named`]).
pub fn file_error(file: &Path, e: flexure::Error) -> String {
    let loads = loads_named(file, &e);
    format!("{}: {e}{loads}", file.display())
}

/// Where `e` is about the load as a whole (a path that loses stability or
/// stalls at a fraction of it), "; the load is the file's, all at once: "
/// and the loads that make it up, each where the file writes it; else "".
pub fn loads_named(file: &Path, e: &flexure::Error) -> String {
    if !matches!(e, flexure::Error::Unstable { .. } | flexure::Error::ContinuationStalled { .. }) {
        return String::new();
    }
    let loads =
        crate::input::read_text(file, "").map(|t| flexure::mechanism::file::loads_placed(&t)).unwrap_or_default();
    if loads.is_empty() {
        String::new()
    } else {
        format!("; the load is the file's, all at once: {}", loads.join(", "))
    }
}

fn load(path: &Path) -> Result<Mechanism, String> {
    let text = crate::input::read_mechanism(path)?;
    from_toml(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// The mechanism, and each flexure joint's `yield_strength` and `shape`.
fn load_with_reports(path: &Path) -> Result<(Mechanism, Vec<(String, ReportOptions)>), String> {
    let text = crate::input::read_mechanism(path)?;
    let m = from_toml(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let reports = reports(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok((m, reports))
}

/// Each flexure joint of `m` with its coordinates in `s` and its report keys.
fn flexures<'a>(
    m: &'a Mechanism,
    s: &'a Solution,
    reports: &'a [(String, ReportOptions)],
) -> impl Iterator<Item = (&'a str, &'a flexure::Flexure, &'a [f64], ReportOptions)> {
    m.joints.iter().filter_map(move |j| {
        let f = j.kind.flexure()?;
        let r = reports.iter().find(|r| r.0 == j.name).map_or_else(ReportOptions::default, |r| r.1);
        Some((j.name.as_str(), f, &s.q[j.offset..j.offset + f.order()], r))
    })
}

/// A point `X,Y` (a planar file) or `X,Y,Z` (a spatial one).
pub fn point_any(s: &str) -> Result<Point, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if !(2..=3).contains(&parts.len()) {
        return Err(format!("{s:?} must be X,Y (a planar mechanism) or X,Y,Z (a spatial one)"));
    }
    parts.into_iter().map(number).collect::<Result<_, _>>().map(Point)
}

/// A point of two or three coordinates (one value to clap, not a list).
#[derive(Debug, Clone, PartialEq)]
pub struct Point(pub Vec<f64>);

/// A point `X,Y`.
pub fn point_arg(s: &str) -> Result<[f64; 2], String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 2 {
        return Err(format!("{s:?} must be two values X,Y"));
    }
    Ok([number(parts[0])?, number(parts[1])?])
}

/// The flexure joints' names, in joint order (the order of the library's
/// per-flexure lists, such as an estimate's reference orders).
pub fn flexure_names(m: &Mechanism) -> Vec<String> {
    m.joints.iter().filter(|j| j.kind.flexure().is_some()).map(|j| j.name.clone()).collect()
}

/// {joint: order} of the flexure joints.
pub fn flexure_orders(m: &Mechanism) -> Value {
    Value::Object(m.joints.iter().filter_map(|j| Some((j.name.clone(), json!(j.kind.flexure()?.order())))).collect())
}
