//! `flexure`: the command-line face of the flexure library.
//!
//! Every subcommand prints one JSON object with `--json`, a readable table
//! otherwise. Bad input exits with status 2 and a message on stderr naming
//! the option; so does a solver that cannot find an answer, and so does a
//! result holding a number that is not finite. [`run`] is the whole program
//! with its streams passed in, so it can also run in-process.

mod analyses;
mod answer;
mod batch;
mod eigen;
mod export;
mod findings;
mod input;
mod joint;
mod joint_options;
mod mechanism;
mod modes;
mod options;
mod render;
mod reproduce;
mod samples;
mod simulate;
mod stress;

/// The drawing (`draw`): its views, the scene each dimension makes of a
/// mechanism, and the figures; public for the tests of `tests/draw3d.rs`.
pub use mechanism::{drawing, projection, scene};

use clap::{Parser, Subcommand};
use serde_json::Value;
use std::ffi::OsString;
use std::io::Write;

/// Exit status of a run that answered everything.
pub const SUCCESS: u8 = 0;
/// Exit status for bad input, a solver failure, or a non-finite result.
pub const FAILURE: u8 = 2;

#[derive(Debug, Parser)]
#[command(
    name = "flexure",
    version,
    about = "Flexure joints with the Smooth Curvature Model, beside exact beam theory"
)]
struct Cli {
    /// Print one JSON object on stdout instead of a table.
    #[arg(long, global = true)]
    json: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Tip pose, transform, Jacobian, Hessians and energy at joint coordinates α.
    Kinematics(joint_options::KinematicsArgs),
    /// Equilibrium under a tip load, with its stiffness and stability.
    Deflect(joint_options::DeflectArgs),
    /// Small-load tip compliance at the rest shape, order (φ, x, y).
    Compliance(joint_options::ComplianceArgs),
    /// Critical compressive load under a tip constraint, with its error estimate.
    Buckling(joint_options::BucklingArgs),
    /// Minimum-energy shape reaching a tip pose (model, exact, or segment chain).
    Connect(analyses::ConnectArgs),
    /// Tendon-driven joint: equilibrium under tendon tension, or a sweep.
    Tendon(analyses::TendonArgs),
    /// Regenerate the paper's tables and figures beside its printed values.
    Reproduce(reproduce::ReproduceArgs),
    /// Equilibrium of a mechanism file: body poses, joint coordinates, energy, stability.
    Solve(mechanism::SolveArgs),
    /// Linear buckling of a mechanism file: the factor on its loads, the mode, and its error estimate.
    Buckle(mechanism::BuckleArgs),
    /// Draw a mechanism's unloaded and loaded shapes as SVG.
    Draw(mechanism::DrawArgs),
    /// Motion of a mechanism file over time: body poses, coordinates and energy at each sample.
    Simulate(simulate::SimulateArgs),
    /// Natural frequencies and mode shapes about the loaded equilibrium: of a
    /// mechanism file, or of one flexure joint with a tip body (--exact: beside exact beam theory).
    Modes(modes::ModesArgs),
    /// A mechanism file as a rigid-body model for MuJoCo (MJCF), Gazebo (SDFormat) or ROS (URDF), each
    /// flexure a pseudo-rigid-body chain fitted to the model over the file's loads.
    Export(export::ExportArgs),
}

/// What a subcommand answers: one object, or one answer per `--input` row.
enum Answer {
    One(Value),
    Rows(batch::Rows),
    /// A model's text for stdout (`export` without `--out`).
    Text(String),
}

/// Runs the command line `args` (program name first), writing the answer to
/// `stdout` and errors and warnings to `stderr`; returns the exit status,
/// [`SUCCESS`] or [`FAILURE`] (clap's `--help` and `--version` also exit 0).
pub fn run<I, T>(args: I, stdout: &mut dyn Write, stderr: &mut dyn Write) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    options::take_warnings();
    options::take_notes();
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            // --help and --version are answers; everything else is bad input.
            if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                let _ = write!(stderr, "error: a subcommand is required\n\n{}", e.render());
                return FAILURE;
            }
            if e.use_stderr() {
                let _ = write!(stderr, "{}", e.render());
                return FAILURE;
            }
            let _ = write!(stdout, "{}", e.render());
            return SUCCESS;
        }
    };
    for w in options::take_warnings() {
        let _ = writeln!(stderr, "warning: {w}");
    }
    let answer = answer(&cli.command, cli.json);
    // Warnings raised while answering (e.g. by an --input file's cells).
    for w in options::take_warnings() {
        let _ = writeln!(stderr, "warning: {w}");
    }
    for n in options::take_notes() {
        let _ = writeln!(stderr, "note: {n}");
    }
    match answer {
        Ok(answer) => emit(answer, cli.json, stdout, stderr),
        Err(e) => {
            let _ = writeln!(stderr, "error: {e}");
            FAILURE
        }
    }
}

fn answer(command: &Command, json: bool) -> Result<Answer, String> {
    let one = |v: Result<Value, String>| v.map(Answer::One);
    match command {
        // --input: one answer per CSV row.
        Command::Kinematics(a) => match &a.input {
            Some(path) => batch::kinematics(&a.flexure().map_err(describe)?, path).map(Answer::Rows),
            None => one(joint::kinematics(a).map_err(describe)),
        },
        Command::Deflect(a) => match &a.input {
            Some(path) => {
                batch::deflect_rows(&a.flexure().map_err(describe)?, path, &a.accuracy.target()).map(Answer::Rows)
            }
            None => one(joint::deflect_cmd(a).map_err(describe)),
        },
        Command::Compliance(a) => one(joint::compliance(a).map_err(describe)),
        Command::Buckling(a) => one(joint::buckling(a).map_err(describe)),
        Command::Connect(a) => one(analyses::connect_cmd(a).map_err(describe)),
        Command::Tendon(a) => one(analyses::tendon_cmd(a).map_err(describe)),
        Command::Reproduce(a) => one(reproduce::run(a)),
        Command::Solve(a) => one(mechanism::solve_cmd(a)),
        Command::Buckle(a) => one(mechanism::buckle_cmd(a)),
        Command::Draw(a) => one(mechanism::draw_cmd(a)),
        Command::Simulate(a) => one(simulate::simulate_cmd(a)),
        Command::Modes(a) => one(modes::modes_cmd(a)),
        Command::Export(a) => export::export_cmd(a, json).map(|e| e.model.map_or(Answer::One(e.report), Answer::Text)),
    }
}

/// The one place output is written. Every answer is checked first: JSON
/// cannot hold NaN or ±∞ (serde_json turns them into `null`), so a `null`
/// anywhere is a non-finite result, reported by its field and never printed.
fn emit(answer: Answer, as_json: bool, stdout: &mut dyn Write, stderr: &mut dyn Write) -> u8 {
    let checked = |value: Value| match render::non_finite(&value) {
        Some(field) => Err(render::non_finite_message(&field)),
        None => Ok(value),
    };
    match answer {
        Answer::Text(text) => match stdout.write_all(text.as_bytes()).and_then(|()| stdout.flush()) {
            Ok(()) => SUCCESS,
            Err(e) => write_failed(e, stderr),
        },
        Answer::One(value) => {
            let value = match checked(value) {
                Ok(value) => value,
                Err(e) => {
                    let _ = writeln!(stderr, "error: {e}");
                    return FAILURE;
                }
            };
            let text = if as_json { format!("{value}\n") } else { render::readable(&value) };
            if let Err(e) = stdout.write_all(text.as_bytes()).and_then(|()| stdout.flush()) {
                return write_failed(e, stderr);
            }
            // A sweep that stopped early: its rows are printed above, then its failure.
            match value.get("stopped").and_then(|s| s.get("error")).and_then(Value::as_str) {
                Some(error) => {
                    let _ = writeln!(stderr, "error: {error}");
                    FAILURE
                }
                None => SUCCESS,
            }
        }
        Answer::Rows(rows) => {
            let total = rows.answers.len();
            let mut failed = Vec::new();
            let mut first_error = None;
            let mut text = String::new();
            if !as_json {
                text += &rows.header;
                text.push('\n');
            }
            for (i, answer) in rows.answers.into_iter().enumerate() {
                let row = i + 1;
                let line = match (answer.and_then(checked), as_json) {
                    (Ok(value), true) => value.to_string(),
                    (Ok(value), false) => render::csv_line(&value),
                    (Err(e), json) => {
                        failed.push(row);
                        first_error.get_or_insert_with(|| e.clone());
                        if json {
                            serde_json::json!({ "row": row, "error": e }).to_string()
                        } else {
                            format!("# row {row}: error: {e}")
                        }
                    }
                };
                text += &line;
                text.push('\n');
            }
            if let Err(e) = stdout.write_all(text.as_bytes()).and_then(|()| stdout.flush()) {
                return write_failed(e, stderr);
            }
            if failed.is_empty() {
                return SUCCESS;
            }
            let shown: Vec<String> = failed.iter().take(10).map(usize::to_string).collect();
            let more = if failed.len() > shown.len() { ", …" } else { "" };
            let _ = writeln!(
                stderr,
                "error: {}: {} of {total} rows failed (rows {}{more}), each answered by its error in its place; row {}: {}",
                rows.source,
                failed.len(),
                shown.join(", "),
                failed[0],
                first_error.unwrap_or_default()
            );
            FAILURE
        }
    }
}

fn write_failed(e: std::io::Error, stderr: &mut dyn Write) -> u8 {
    let _ = writeln!(stderr, "error: writing the output to stdout: {e}");
    FAILURE
}

/// The library's error with the parameter spelled as the option that set it.
pub fn describe(e: flexure::Error) -> String {
    match &e {
        // A value that names itself (a pair of parts) is no option's.
        flexure::Error::InvalidParameter { name, value, reason } if flexure::error::names_itself(name, value) => {
            format!("{value}: {reason}")
        }
        flexure::Error::InvalidParameter { name, value, reason } => format!("{} = {value}: {reason}", option(name)),
        other => other.to_string(),
    }
}

/// The option that sets the library's parameter `name`: `--max-iterations`
/// for `max_iterations`, `--notch R` for `notch.radius`.
fn option(name: &str) -> String {
    match name {
        "notch.radius" => "--notch R".into(),
        "notch.min_thickness" => "--notch H".into(),
        // A spatial flexure's in-plane parts are the planar options.
        "ei_z" => "--ei".into(),
        "kappa_z" => "--kappa".into(),
        // The mechanism's or flexure's masses, set by several options or keys.
        "mass" => "mass".into(),
        // A geom's key, or a pair of parts: no option sets them.
        "friction" | "pair" => name.into(),
        _ => format!("--{}", name.replace('_', "-")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A NaN anywhere in an answer is refused by name, exit 2, nothing on stdout.
    #[test]
    fn emit_refuses_a_non_finite_answer() {
        for as_json in [true, false] {
            let (mut out, mut err) = (Vec::new(), Vec::new());
            let answer = Answer::One(serde_json::json!({ "pose": { "x": f64::NAN, "y": 1.0 } }));
            assert_eq!(emit(answer, as_json, &mut out, &mut err), FAILURE);
            let err = String::from_utf8_lossy(&err);
            assert!(out.is_empty() && err.contains("x"), "{err}");
        }
    }
}
