//! `flexure solve`: a mechanism's equilibrium, optionally with the
//! compliance of a frame or a sweep of one load.

use super::checks::{insert_sweep_checks, solution_answer};
use super::{load_with_reports, point_any};
use crate::analyses::{SweepSpec, sweep_values};
use clap::Args;
use flexure::mechanism::Mechanism;
use flexure::mechanism::statics::{Settings, Solution, body_frames, compliance, solve};
use flexure::mechanism::sweep::{Parameter, sweep};
use serde_json::{Value, json};
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
    at: Option<super::Point>,
    /// Sweep one load, e.g. tendon.flexor.tension=0:30:31 (or force.NAME.fx|fy|moment, gravity.x|y):
    /// a table with one row per value reached stably, then `stability_limit` (value, fraction) if
    /// stability is lost between two values (found by bisection; a warning on stderr, exit 0).
    #[arg(long, value_parser = crate::analyses::sweep_spec, allow_hyphen_values = true)]
    sweep: Option<SweepSpec>,
    #[command(flatten)]
    accuracy: crate::options::AccuracyOptions,
}

/// A sweep as a table: the column names, then one row of numbers per
/// value: the value, each moving body's x, y, phi, each joint coordinate,
/// the energy, and the compliance entries if asked for.
fn sweep_table(m: &Mechanism, parameter: &str, with_compliance: bool) -> Vec<String> {
    let mut columns = vec![parameter.to_string()];
    for b in &m.bodies[1..] {
        columns.extend(["x", "y", "phi"].map(|c| format!("{}.{c}", b.name)));
    }
    for j in &m.joints {
        columns.extend((0..j.kind.joint().dof()).map(|i| format!("{}[{i}]", j.name)));
    }
    columns.push("energy".into());
    // The peak stress of each flexure joint that has a thickness (Pa).
    for j in &m.joints {
        if let Some(f) = j.kind.flexure()
            && f.section().modulus().is_some()
        {
            columns.push(format!("{}.stress", j.name));
        }
    }
    if with_compliance {
        let axes = ["phi", "x", "y"];
        columns.extend(axes.iter().flat_map(|r| axes.iter().map(move |c| format!("compliance.{r}{c}"))));
    }
    columns
}

fn sweep_row(m: &Mechanism, value: f64, s: &Solution, compliance: Option<&nalgebra::Matrix3<f64>>) -> Vec<f64> {
    let f = body_frames(m, s);
    let mut row = vec![value];
    row.extend(f.bodies[1..].iter().flat_map(|b| [b.x, b.y, b.phi]));
    row.extend(&s.q);
    row.push(s.energy);
    for j in &m.joints {
        if let Some(f) = j.kind.flexure()
            && let Some(p) = flexure::stress::peak_stress(f, &s.q[j.offset..j.offset + f.order()])
        {
            row.push(p.value);
        }
    }
    if let Some(c) = compliance {
        row.extend((0..3).flat_map(|i| (0..3).map(move |j| c[(i, j)])));
    }
    row
}

/// Equilibrium of a mechanism file, optionally with a compliance or a sweep.
pub fn solve_cmd(args: &SolveArgs) -> Result<Value, String> {
    if let Some(m) = super::spatial::read(&args.file)? {
        let at = args.compliance.as_deref().zip(args.at.as_ref().map(|p| p.0.as_slice()));
        return super::spatial::solve_cmd(&m, &args.file, at, args.sweep.as_ref(), &args.accuracy.target());
    }
    let (m, reports) = load_with_reports(&args.file)?;
    let settings = Settings::default();
    let target = args.accuracy.target();
    let err = |e: flexure::Error| super::file_error(&args.file, e);
    let body = match &args.compliance {
        Some(name) => Some(
            m.body(name).ok_or_else(|| format!("--compliance: no body named {name:?} in {}", args.file.display()))?,
        ),
        None => None,
    };
    let at = match args.at.as_ref().map(|p| p.0.as_slice()) {
        Some([x, y]) => Some([*x, *y]),
        Some(_) => return Err(format!("--at: {} is a planar mechanism: give the point as X,Y", args.file.display())),
        None => None,
    };
    let compliance_at = body.zip(at);
    match &args.sweep {
        Some(spec) => {
            let p = Parameter::parse(&m, &spec.parameter).map_err(crate::describe)?;
            let values = sweep_values(&spec.range);
            let out = sweep(&m, &p, &values, &settings).map_err(err)?;
            let rows: Vec<Value> = out
                .rows
                .iter()
                .map(|(v, s)| {
                    let c = compliance_at.map(|(b, at)| compliance(&m, s, b, at.into())).transpose().map_err(err)?;
                    Ok(json!(sweep_row(&m, *v, s, c.as_ref())))
                })
                .collect::<Result<_, String>>()?;
            let mut v = json!({
                "columns": sweep_table(&m, &spec.parameter, compliance_at.is_some()),
                "rows": rows,
            });
            insert_sweep_checks(&mut v, &m, &out, &reports, (&target, &args.file), (&spec.parameter, &values))?;
            Ok(v)
        }
        None => {
            let s = solve(&m, &settings).map_err(err)?;
            let c = compliance_at.map(|(b, at)| compliance(&m, &s, b, at.into())).transpose().map_err(err)?;
            let mut v = solution_answer(&m, &s, &reports, &target, &args.file)?;
            if let Some(c) = c {
                v["compliance"] = crate::joint::matrix(&c);
            }
            Ok(v)
        }
    }
}
