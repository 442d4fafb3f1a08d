//! The mechanism subcommands on spatial files (`dimension = 3`): each
//! prints what the library's spatial mechanism returns
//! (`flexure::mechanism::spatial`), in the shape of its planar answer.

use flexure::dynamics::spatial::SpatialSimulation;
use flexure::mechanism::spatial::SpatialMechanism;
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
