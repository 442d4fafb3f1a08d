//! `flexure solve`: a mechanism's equilibrium, optionally with the
//! compliance of a frame or a sweep of one load.

use super::checks::{solve_answer, sweep_table};
use super::point_any;
use crate::analyses::{SweepSpec, sweep_values};
use crate::answer::{MAX_FACTOR, insert_limit};
use clap::Args;
use serde_json::Value;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct SolveArgs {
    /// Mechanism file (TOML).
    file: PathBuf,
    /// Report the compliance of a frame on this body…
    #[arg(long, requires = "at")]
    compliance: Option<String>,
    /// …at this point X,Y of the body's frame (m); X,Y,Z on a spatial file (its 6 × 6 compliance).
    #[arg(long, value_parser = point_any, allow_hyphen_values = true, requires = "compliance")]
    at: Option<super::PointArg>,
    /// Sweep one load, e.g. tendon.flexor.tension=0:30:31 (or force.NAME.fx|fy|moment, gravity.x|y):
    /// a table with one row per value reached stably, then `stability_limit` (value, fraction) if
    /// stability is lost between two values (found by bisection; a warning on stderr, exit 0).
    #[arg(long, value_parser = crate::analyses::sweep_spec, allow_hyphen_values = true)]
    sweep: Option<SweepSpec>,
    /// Also find the factor on all the file's loads (tendons, forces, gravity), up to 1000, at
    /// which the equilibrium followed from rest stops being stable, or up to which it stays stable
    /// (1000, or as far as the path could be followed, with a warning); with contact, the load is
    /// followed in order as the contacts touch, stick and slip: `stability_limit` {factor, status:
    /// lost | stable_up_to}.
    #[arg(long, conflicts_with = "sweep")]
    limit: bool,
    #[command(flatten)]
    accuracy: crate::options::AccuracyOptions,
}

/// Equilibrium of a mechanism file, optionally with a compliance or a sweep.
pub fn solve_cmd(args: &SolveArgs) -> Result<Value, String> {
    let model = crate::input::read_model(&args.file)?;
    let target = args.accuracy.target();
    let at = args.compliance.as_deref().zip(args.at.as_ref().map(|p| p.0.as_slice()));
    if let Some((name, point)) = at {
        super::check_frame(&model, name, point, &args.file)?;
    }
    if let Some(spec) = &args.sweep {
        let values = sweep_values(&spec.range);
        return Ok(sweep_table(&model, (&spec.parameter, &values), at, &target, &args.file)?.0);
    }
    let findings = crate::findings::open_at_rest(&model, &args.file)?;
    let solved = model.solve(&target, at).map_err(super::solver_error(&args.file))?;
    // At the orders the answer was found with.
    let limit = args.limit.then(|| solved.model.stability_limit(MAX_FACTOR)).transpose();
    let limit = limit.map_err(super::solver_error(&args.file))?;
    let mut answer = solve_answer(&model, findings, solved, &target, &args.file)?;
    if let Some(limit) = &limit {
        insert_limit(&mut answer, limit, &format!("{}: solve --limit", args.file.display()));
    }
    Ok(answer)
}
