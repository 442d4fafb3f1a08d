//! Subcommands on mechanism files: `solve` (with its compliance and
//! sweeps), `buckle` and `draw`, and the checks `solve` and `draw` share.

mod buckle;
mod checks;
mod draw;
pub mod drawing;
pub mod projection;
pub mod scene;
mod solids;
mod solve;

pub use buckle::{BuckleArgs, buckle_cmd};
pub use draw::{DrawArgs, draw_cmd};
pub use solve::{SolveArgs, solve_cmd};

use crate::options::number;
use flexure::model::Model;
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

/// A solver's error on mechanism file `file`, a bad parameter described
/// as the command line writes it ([`crate::describe`]).
pub fn solver_error(file: &Path) -> impl Fn(flexure::Error) -> String + '_ {
    move |e| match e {
        e @ flexure::Error::InvalidParameter { .. } => format!("{}: {}", file.display(), crate::describe(e)),
        e => file_error(file, e),
    }
}

/// Checks `--compliance NAME --at POINT` against the model: a body of that
/// name, and a point of the model's dimension.
fn check_frame(model: &Model, name: &str, point: &[f64], file: &Path) -> Result<(), String> {
    if model.body(name).is_none() {
        return Err(format!("--compliance: no body named {name:?} in {}", file.display()));
    }
    match (model.dimension(), point.len()) {
        (2, 2) | (3, 3) => Ok(()),
        (2, _) => Err(format!("--at: {} is a planar mechanism: give the point as X,Y", file.display())),
        _ => Err(format!("--at: {} is a spatial mechanism (dimension = 3): give the point as X,Y,Z", file.display())),
    }
}

/// A point `X,Y` (a planar file) or `X,Y,Z` (a spatial one).
pub fn point_any(s: &str) -> Result<PointArg, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if !(2..=3).contains(&parts.len()) {
        return Err(format!("{s:?} must be X,Y (a planar mechanism) or X,Y,Z (a spatial one)"));
    }
    parts.into_iter().map(number).collect::<Result<_, _>>().map(PointArg)
}

/// A point of two or three coordinates (one value to clap, not a list).
#[derive(Debug, Clone, PartialEq)]
pub struct PointArg(pub Vec<f64>);

/// A point `X,Y`.
pub fn point_arg(s: &str) -> Result<[f64; 2], String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 2 {
        return Err(format!("{s:?} must be two values X,Y"));
    }
    Ok([number(parts[0])?, number(parts[1])?])
}
