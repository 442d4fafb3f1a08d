//! `flexure solve`: a mechanism's equilibrium, optionally with the
//! compliance of a frame or a sweep of one load.

use super::checks::{insert_sweep_checks, solved_answer};
use super::point_any;
use crate::analyses::{SweepSpec, sweep_values};
use clap::Args;
use flexure::mechanism::Mechanism;
use flexure::mechanism::statics::{Settings, Solution, body_frames, compliance};
use flexure::mechanism::sweep::{Parameter, sweep};
use flexure::model::Model;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

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
    let model = super::read_model(&args.file)?;
    let target = args.accuracy.target();
    let at = args.compliance.as_deref().zip(args.at.as_ref().map(|p| p.0.as_slice()));
    if let Some((name, point)) = at {
        super::check_frame(&model, name, point, &args.file)?;
    }
    if let Some(spec) = &args.sweep {
        return match &model {
            Model::Planar(m) => planar_sweep(m, spec, at, &target, &args.file),
            Model::Spatial(m) => super::spatial::sweep_cmd(m, &args.file, at, spec),
        };
    }
    let findings = super::told_closures(&model, &args.file)?;
    let solved = model.solve(&target, at).map_err(super::solver_error(&args.file))?;
    solved_answer(&model, findings, solved, &target, &args.file)
}

/// `solve --sweep` on a planar file.
fn planar_sweep(
    m: &Mechanism,
    spec: &SweepSpec,
    at: Option<(&str, &[f64])>,
    target: &flexure::estimate::Accuracy,
    file: &Path,
) -> Result<Value, String> {
    let settings = Settings::default();
    let err = |e: flexure::Error| super::file_error(file, e);
    let compliance_at = at.and_then(|(name, at)| Some((m.body(name)?, [*at.first()?, *at.get(1)?])));
    let p = Parameter::parse(m, &spec.parameter).map_err(crate::describe)?;
    let values = sweep_values(&spec.range);
    let out = sweep(m, &p, &values, &settings).map_err(err)?;
    let rows: Vec<Value> = out
        .rows
        .iter()
        .map(|(v, s)| {
            let c = compliance_at.map(|(b, at)| compliance(m, s, b, at.into())).transpose().map_err(err)?;
            Ok(json!(sweep_row(m, *v, s, c.as_ref())))
        })
        .collect::<Result<_, String>>()?;
    let mut v = json!({
        "columns": sweep_table(m, &spec.parameter, compliance_at.is_some()),
        "rows": rows,
    });
    insert_sweep_checks(&mut v, m, &out, (target, file), (&spec.parameter, &values))?;
    Ok(v)
}
