//! `flexure`: the command-line face of the flexure library.
//!
//! Every subcommand prints one JSON object with `--json`, a readable table
//! otherwise. Bad input exits with status 2 and a message on stderr naming
//! the option; so does a solver that cannot find an answer.

mod analyses;
mod batch;
mod figures;
mod joint;
mod mechanism;
mod options;
mod render;
mod reproduce;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

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
    Kinematics(joint::KinematicsArgs),
    /// Equilibrium under a tip load, with its stiffness and stability.
    Deflect(joint::DeflectArgs),
    /// Small-load tip compliance at the rest shape, order (φ, x, y).
    Compliance(joint::ComplianceArgs),
    /// Critical compressive load under a tip constraint.
    Buckling(joint::BucklingArgs),
    /// Minimum-energy shape reaching a tip pose (model, exact, or segment chain).
    Connect(analyses::ConnectArgs),
    /// Tendon-driven joint: equilibrium under tendon tension, or a sweep.
    Tendon(analyses::TendonArgs),
    /// Regenerate the paper's tables and figures beside its printed values.
    Reproduce(reproduce::ReproduceArgs),
    /// Equilibrium of a mechanism file: body poses, joint coordinates, energy, stability.
    Solve(mechanism::SolveArgs),
    /// Linear buckling of a mechanism file: the factor on its loads, and the mode.
    Buckle(mechanism::BuckleArgs),
    /// Draw a mechanism's unloaded and loaded shapes as SVG.
    Draw(mechanism::DrawArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // --input: one result per CSV row, printed line by line.
    let rows = match &cli.command {
        Command::Kinematics(a) => {
            a.input.as_ref().map(|p| a.flexure().map_err(describe).and_then(|f| batch::kinematics(&f, p, cli.json)))
        }
        Command::Deflect(a) => {
            a.input.as_ref().map(|p| a.flexure().map_err(describe).and_then(|f| batch::deflect_rows(&f, p, cli.json)))
        }
        _ => None,
    };
    if let Some(rows) = rows {
        return match rows {
            Ok(text) => {
                print!("{text}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(2)
            }
        };
    }
    let result = match &cli.command {
        Command::Kinematics(a) => joint::kinematics(a).map_err(describe),
        Command::Deflect(a) => joint::deflect_cmd(a).map_err(describe),
        Command::Compliance(a) => joint::compliance(a).map_err(describe),
        Command::Buckling(a) => joint::buckling(a).map_err(describe),
        Command::Connect(a) => analyses::connect_cmd(a).map_err(describe),
        Command::Tendon(a) => analyses::tendon_cmd(a).map_err(describe),
        Command::Reproduce(a) => reproduce::run(a),
        Command::Solve(a) => mechanism::solve_cmd(a),
        Command::Buckle(a) => mechanism::buckle_cmd(a),
        Command::Draw(a) => mechanism::draw_cmd(a),
    };
    match result {
        Ok(value) => {
            if cli.json {
                println!("{value}");
            } else {
                print!("{}", render::readable(&value));
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// The library's error with the parameter spelled as the option that set it.
pub fn describe(e: flexure::Error) -> String {
    match &e {
        flexure::Error::InvalidParameter { name, value, reason } => format!("--{name} = {value}: {reason}"),
        other => other.to_string(),
    }
}
