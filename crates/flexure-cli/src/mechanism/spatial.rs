//! The mechanism subcommands on spatial files (`dimension = 3`): each
//! prints what the library's spatial mechanism returns
//! (`flexure::mechanism::spatial`), in the shape of its planar answer.

use crate::analyses::{SweepSpec, sweep_values};
use crate::options::warn;
use flexure::dynamics::spatial::SpatialSimulation;
use flexure::estimate::spatial_mechanism::{buckle_auto, modes_auto};
use flexure::estimate::{Accuracy, ValueEstimate};
use flexure::mechanism::spatial::SpatialMechanism;
use flexure::mechanism::spatial::statics::{compliance, solve};
use flexure::mechanism::spatial::sweep::{SpatialParameter, sweep};
use flexure::report::spatial::{placements, report};
use flexure::solver::Settings;
use serde_json::{Value, json};
use std::path::Path;

/// The file's mechanism if it says `dimension = 3`, else `None` (planar).
pub fn read(path: &Path) -> Result<Option<SpatialMechanism>, String> {
    let text = crate::input::read_mechanism(path)?;
    match flexure::mechanism::file::model_from_toml(&text) {
        Ok(flexure::mechanism::file::Model::Spatial(m)) => Ok(Some(m)),
        Ok(flexure::mechanism::file::Model::Planar(_)) => Ok(None),
        Err(e) => Err(format!("{}: {e}", path.display())),
    }
}

fn file_error(file: &Path) -> impl Fn(flexure::Error) -> String + '_ {
    move |e| match e {
        e @ flexure::Error::InvalidParameter { .. } => format!("{}: {}", file.display(), crate::describe(e)),
        e => crate::mechanism::file_error(file, e),
    }
}

/// A point `X,Y,Z` for `--at` on a spatial file.
fn point3(at: &[f64], file: &Path) -> Result<nalgebra::Point3<f64>, String> {
    match at {
        [x, y, z] => Ok(nalgebra::Point3::new(*x, *y, *z)),
        _ => Err(format!("--at: {} is a spatial mechanism (dimension = 3): give the point as X,Y,Z", file.display())),
    }
}

/// Warns of each flexure whose error estimate misses `target`.
fn warn_flagged(
    answer: &flexure::report::spatial::SpatialReport,
    m: &SpatialMechanism,
    target: &Accuracy,
    file: &Path,
) {
    for f in answer.flexures.iter().filter(|f| f.error_estimate.flagged) {
        let length =
            m.joints.iter().find(|j| j.name == f.name).and_then(|j| j.kind.flexure()).map_or(0.0, |f| f.length());
        let misses = crate::joint::misses(&f.error_estimate, length, target);
        warn(format!("{}: flexure joint {:?}: {misses}; raise its orders", file.display(), f.name));
    }
}

/// `solve` on a spatial file: the equilibrium's report, with the 6 × 6
/// compliance of a point of a body, or a sweep of one load.
pub fn solve_cmd(
    m: &SpatialMechanism,
    file: &Path,
    compliance_at: Option<(&str, &[f64])>,
    sweep_spec: Option<&SweepSpec>,
    target: &Accuracy,
) -> Result<Value, String> {
    let settings = Settings::default();
    let err = file_error(file);
    let mut findings = crate::findings::spatial_closures(m, file)?;
    let at = match compliance_at {
        Some((name, at)) => {
            let b =
                m.body(name).ok_or_else(|| format!("--compliance: no body named {name:?} in {}", file.display()))?;
            Some((b, point3(at, file)?))
        }
        None => None,
    };
    if let Some(spec) = sweep_spec {
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
            for p in placements(m, &s.q) {
                row.extend(p.position);
                row.extend(p.rpy);
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
        return Ok(v);
    }
    let s = solve(m, &settings).map_err(&err)?;
    if let Some(limit) = s.limit {
        warn(format!(
            "{}: the loading path lost stability at {:.4} % of the load and snapped through to the stable equilibrium reported",
            file.display(),
            100.0 * limit
        ));
    }
    findings.extend(crate::findings::spatial_shape(m, &s.q, file));
    let answer = report(m, &s, target).map_err(&err)?;
    warn_flagged(&answer, m, target, file);
    let mut v = json!(answer);
    if let Some((b, point)) = at {
        v["compliance"] = crate::joint::matrix(&compliance(m, &s, b, point).map_err(&err)?);
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

/// The spatial flexure joints' names, in joint order (the order of an
/// eigenvalue estimate's reference orders).
fn flexure_names(m: &SpatialMechanism) -> Vec<String> {
    m.joints.iter().filter(|j| j.kind.flexure().is_some()).map(|j| j.name.clone()).collect()
}

/// The reference mechanism of an eigenvalue estimate, for warnings: each
/// spatial flexure at its largest order and its Magnus subintervals.
fn reference_of(e: &ValueEstimate, flexures: &[String]) -> String {
    if e.reference_orders.is_empty() {
        return "the same mechanism: it has no flexure to refine".into();
    }
    let parts: Vec<String> = flexures
        .iter()
        .zip(&e.reference_orders)
        .map(|(n, (o, q))| format!("{n:?} at orders up to {o} with {q} subintervals"))
        .collect();
    format!("the mechanism with {}", parts.join(", "))
}

/// What to do about a spatial eigenvalue answer that misses its target.
fn advice_for_orders(m: &SpatialMechanism) -> &'static str {
    if m.joints.iter().any(|j| j.auto_order) {
        "the flexures of order = \"auto\" are at the cap of 64, or there are none left to raise: give the others order = \"auto\" (or higher orders)"
    } else {
        "give the spatial flexures order = \"auto\", or raise their orders (`order` or `orders`) in the file"
    }
}

/// `order` {joint: [n_twist, n_y, n_z], as the file's `orders`} when a
/// spatial flexure has `order = "auto"`: the orders the answer was found at.
fn insert_orders(v: &mut Value, m: &SpatialMechanism) {
    if m.joints.iter().any(|j| j.auto_order) {
        v["order"] = Value::Object(
            m.joints.iter().filter_map(|j| Some((j.name.clone(), json!(j.kind.flexure()?.orders())))).collect(),
        );
    }
}

/// `buckle` on a spatial file: the linear buckling factor on all loads and
/// its mode, with its error estimate against the mechanism with every
/// spatial flexure refined (`error_estimate`, `flagged`, as the planar
/// answer's), warning when it misses `target`.
pub fn buckle_cmd(m: &SpatialMechanism, file: &Path, target: &Accuracy) -> Result<Value, String> {
    let settings = Settings::default();
    let findings = crate::findings::spatial_closures(m, file)?;
    let (m, b, e) = buckle_auto(m, &settings, target).map_err(file_error(file))?;
    let mut v = json!(b);
    v["dimension"] = json!(3);
    let flexures = flexure_names(&m);
    crate::eigen::insert_eigen_estimate(
        &mut v,
        &e,
        &crate::eigen::Shape { key: "load_factor", one: true, flexures: &flexures },
    );
    insert_orders(&mut v, &m);
    crate::eigen::warn_missed(
        &e,
        target,
        &format!("{}: buckle", file.display()),
        |_| format!("the load factor {:.6}", b.load_factor),
        &reference_of(&e, &flexures),
        advice_for_orders(&m),
    );
    insert_findings(&mut v, findings);
    Ok(v)
}

/// Each joint's part of a vector of coordinates, by name.
fn by_joint(m: &SpatialMechanism, v: &[f64]) -> Value {
    Value::Object(
        m.joints
            .iter()
            .filter(|j| j.kind.joint().dof() > 0)
            .map(|j| (j.name.clone(), json!(v[j.offset..j.offset + j.kind.joint().dof()])))
            .collect(),
    )
}

/// `modes` on a spatial file: frequencies and shapes about the loaded equilibrium.
/// Each mode's error estimate is against the mechanism with every spatial
/// flexure refined about the equilibrium (`error_estimate`, `flagged`, as
/// the planar answer's), warning per mode that misses `target`.
pub fn modes_cmd(m: &SpatialMechanism, file: &Path, count: Option<usize>, target: &Accuracy) -> Result<Value, String> {
    if m.dof() == 0 {
        return Err(format!("{}: {}", file.display(), crate::modes::nothing_moves("the mechanism")));
    }
    let asked = count.unwrap_or(m.dof());
    let settings = Settings::default();
    let findings = crate::findings::spatial_closures(m, file)?;
    let unstable = |e| match e {
        flexure::Error::Unstable { .. } => format!(
            "{}: unstable: {e}{}; an unstable equilibrium has no vibration modes (a frequency would be imaginary)",
            file.display(),
            crate::mechanism::loads_named(file, &e)
        ),
        e => file_error(file)(e),
    };
    let (m, modes, e) = modes_auto(m, &settings, asked, target).map_err(unstable)?;
    let shapes: Vec<Value> = (0..modes.omega.len()).map(|k| by_joint(&m, modes.shapes.column(k).as_slice())).collect();
    let mut v = json!({ "dimension": 3, "omega": modes.omega, "frequency": modes.frequency, "shapes": shapes });
    let flexures = flexure_names(&m);
    crate::eigen::insert_eigen_estimate(
        &mut v,
        &e,
        &crate::eigen::Shape { key: "omega", one: false, flexures: &flexures },
    );
    insert_orders(&mut v, &m);
    crate::eigen::warn_missed(
        &e,
        target,
        &format!("{}: modes", file.display()),
        |k| format!("mode {} ({:.6} rad/s)", k + 1, modes.omega[k]),
        &reference_of(&e, &flexures),
        &format!("{}, or ask fewer --count", advice_for_orders(&m)),
    );
    if modes.quasi_static > 0 {
        v["quasi_static"] = json!(modes.quasi_static);
    }
    if let Some(limit) = modes.limit {
        v["limit_fraction"] = json!(limit);
    }
    insert_findings(&mut v, findings);
    Ok(v)
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
