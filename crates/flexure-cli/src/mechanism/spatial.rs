//! The mechanism subcommands on spatial files (`dimension = 3`): each
//! prints what the library's spatial mechanism returns
//! (`flexure::mechanism::spatial`), in the shape of its planar answer.

use crate::analyses::{SweepSpec, sweep_values};
use crate::options::warn;
use flexure::dynamics::spatial::SpatialSimulation;
use flexure::mechanism::spatial::SpatialMechanism;
use flexure::mechanism::spatial::statics::compliance;
use flexure::mechanism::spatial::sweep::{SpatialParameter, sweep};
use flexure::report::Reported;
use flexure::solver::Settings;
use flexure::space::Spatial;
use serde_json::{Value, json};
use std::path::Path;

/// The file's mechanism if it says `dimension = 3`, else `None` (planar).
pub fn read(path: &Path) -> Result<Option<SpatialMechanism>, String> {
    let text = crate::input::read_mechanism(path)?;
    match flexure::model::Model::from_toml(&text) {
        Ok(flexure::model::Model::Spatial(m)) => Ok(Some(m)),
        Ok(flexure::model::Model::Planar(_)) => Ok(None),
        Err(e) => Err(format!("{}: {e}", path.display())),
    }
}

/// `solve --sweep` on a spatial file: a table of one load's values, with
/// the 6 × 6 compliance of a point of a body in each row if asked for.
pub fn sweep_cmd(
    m: &SpatialMechanism,
    file: &Path,
    compliance_at: Option<(&str, &[f64])>,
    spec: &SweepSpec,
) -> Result<Value, String> {
    let settings = Settings::default();
    let err = crate::mechanism::solver_error(file);
    let mut findings = crate::findings::spatial_closures(m, file)?;
    let at = compliance_at
        .and_then(|(name, at)| Some((m.body(name)?, nalgebra::Point3::new(*at.first()?, *at.get(1)?, *at.get(2)?))));
    let p = SpatialParameter::parse(m, &spec.parameter).map_err(crate::describe)?;
    let values = sweep_values(&spec.range);
    let out = sweep(m, &p, &values, &settings).map_err(&err)?;
    let shapes: Vec<(f64, &[f64])> = out.rows.iter().map(|(v, s)| (*v, s.q.as_slice())).collect();
    findings.extend(crate::findings::spatial_along(m, &shapes, (&spec.parameter, "swept values"), "value", file));
    let mut columns = vec![spec.parameter.clone()];
    for b in &m.bodies[1..] {
        columns.extend(["x", "y", "z", "roll", "pitch", "yaw"].map(|c| format!("{}.{c}", b.name)));
    }
    for j in &m.joints {
        columns.extend((0..j.kind.joint().dof()).map(|i| format!("{}[{i}]", j.name)));
    }
    columns.push("energy".into());
    let mut rows = Vec::new();
    for (v, s) in &out.rows {
        let mut row = vec![*v];
        for p in &Spatial::poses(m, &s.q)[1..] {
            row.extend(p.coordinates());
        }
        row.extend(&s.q);
        row.push(s.energy);
        if let Some((b, point)) = at {
            let c = compliance(m, s, b, point).map_err(&err)?;
            row.extend((0..6).flat_map(|r| (0..6).map(move |k| (r, k))).map(|(r, k)| c[(r, k)]));
        }
        rows.push(json!(row));
    }
    if at.is_some() {
        let axes = ["rx", "ry", "rz", "x", "y", "z"];
        columns.extend(axes.iter().flat_map(|r| axes.iter().map(move |c| format!("compliance.{r}{c}"))));
    }
    let mut v = json!({ "dimension": 3, "columns": columns, "rows": rows });
    if let Some(limit) = &out.stability_limit {
        v["stability_limit"] = json!(limit);
        warn(format!(
            "{}: the sweep of {} lost stability at {} = {:.6e} ({:.4} % of the way)",
            file.display(),
            spec.parameter,
            spec.parameter,
            limit.value,
            100.0 * limit.fraction
        ));
    }
    if let Some((value, e)) = &out.stopped {
        v["stopped"] = json!({ "value": value, "error": format!("{}: {e}", file.display()) });
    }
    insert_findings(&mut v, findings);
    Ok(v)
}

/// `findings`, when there are any (each already told on stderr).
pub fn insert_findings(v: &mut Value, findings: Vec<Value>) {
    if !findings.is_empty() {
        v["findings"] = Value::Array(findings);
    }
}

/// The JSON of a spatial simulation: time, each body's positions and
/// rotation matrices, each joint's coordinates, energy and counts.
pub fn motion_json(m: &SpatialMechanism, run: &SpatialSimulation) -> Value {
    let bodies: serde_json::Map<String, Value> = run
        .bodies
        .iter()
        .map(|b| (b.name.clone(), json!({ "position": b.position, "rotation": b.rotation })))
        .collect();
    let coordinates: serde_json::Map<String, Value> = m
        .joints
        .iter()
        .map(|j| {
            let k = j.kind.joint().dof();
            let rows: Vec<&[f64]> = (0..run.time.len()).map(|s| &run.q(s)[j.offset..j.offset + k]).collect();
            (j.name.clone(), json!(rows))
        })
        .collect();
    json!({
        "dimension": 3,
        "time": run.time,
        "bodies": bodies,
        "coordinates": coordinates,
        "energy": run.energy,
        "steps": run.steps,
        "rejected": run.rejected,
        "violation": run.violation,
    })
}

/// `simulate` on a spatial file.
pub fn simulate(
    m: &SpatialMechanism,
    file: &Path,
    duration: f64,
    options: &crate::simulate::MotionOptions,
) -> Result<SpatialSimulation, String> {
    let settings = options.settings(duration);
    let equilibrium = options.start() == flexure::dynamics::simulation::Start::Equilibrium;
    flexure::dynamics::spatial::simulate(m, &settings.motion, &settings.equilibrium, equilibrium)
        .map_err(|e| format!("{}: {}", file.display(), crate::simulate::simulation_error(e, duration)))
}
