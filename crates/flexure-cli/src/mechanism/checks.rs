//! What `solve` checks of a solution or a sweep, and `draw` repeats:
//! closures and crossings (`findings`), each flexure joint's error estimate
//! and stress, snap-throughs, stability, and a sweep that stopped.

use super::flexures;
use flexure::estimate::{Accuracy, ErrorEstimate, joint_error};
use flexure::mechanism::file::Report;
use flexure::mechanism::statics::Solution;
use flexure::mechanism::sweep::{StabilityLimit, Sweep};
use flexure::mechanism::{JointKind, Mechanism};
use serde_json::{Value, json};
use std::path::Path;

/// Per flexure joint, by name: `stress` {max, at} (or `curvature_max` for
/// one given by ei alone), `safety_factor` with a `yield_strength`, and
/// `shape` with a `shape` key; each map left out when empty.
fn put_flexure_stress(v: &mut Value, m: &Mechanism, s: &Solution, reports: &[(String, Report)], file: &Path) {
    let mut maps: [(&str, serde_json::Map<String, Value>); 4] =
        ["stress", "curvature_max", "safety_factor", "shape"].map(|k| (k, serde_json::Map::new()));
    for (name, f, q, r) in flexures(m, s, reports) {
        let mut one = json!({});
        let what = format!("{}: flexure joint {name:?}", file.display());
        crate::stress::peak(&mut one, f, q, r.yield_strength, &what);
        if let Some(k) = r.shape {
            one["shape"] = crate::stress::shape(f, q, k);
        }
        for (key, map) in &mut maps {
            if let Some(x) = one.get(*key) {
                map.insert(name.to_string(), x.clone());
            }
        }
    }
    for (key, map) in maps {
        if !map.is_empty() {
            v[key] = Value::Object(map);
        }
    }
}

/// The error estimate of every flexure joint at `s`, in joint order: the
/// joint under the tip load it carries, against the refined model. A
/// failure names the joint and the file, and says it was the estimate's
/// own solve that failed (not the mechanism's).
fn joint_estimates(
    m: &Mechanism,
    s: &Solution,
    target: &Accuracy,
    file: &Path,
) -> Result<Vec<(&'static str, String, ErrorEstimate, f64)>, String> {
    let mut out = Vec::new();
    for j in &m.joints {
        if let JointKind::Flexure(fl) = &j.kind {
            let e = joint_error(fl, &s.q[j.offset..j.offset + fl.order()], target).map_err(|e| {
                format!(
                    "{}: flexure joint {:?}: its error estimate (the joint alone under the tip load it carries, against the refined model) failed: {e}",
                    file.display(),
                    j.name
                )
            })?;
            out.push(("flexure joint", j.name.clone(), e, fl.length()));
        }
    }
    Ok(out)
}

/// `error_estimate` {joint: estimate} and `flagged` for a solution, warning per flagged joint.
fn put_joint_estimates(
    v: &mut Value,
    m: &Mechanism,
    s: &Solution,
    target: &Accuracy,
    file: &Path,
) -> Result<(), String> {
    let estimates = joint_estimates(m, s, target, file)?;
    let mut map = serde_json::Map::new();
    for (what, name, e, length) in &estimates {
        if e.flagged {
            crate::options::warn(format!(
                "{}: {what} {name:?}: {}; raise its order",
                file.display(),
                crate::joint::misses(e, *length, target),
            ));
        }
        map.insert(name.clone(), crate::joint::estimate(e));
    }
    v["error_estimate"] = Value::Object(map);
    v["flagged"] = json!(estimates.iter().any(|e| e.2.flagged));
    Ok(())
}

fn limit_json(l: &StabilityLimit) -> Value {
    json!({ "value": l.value, "fraction": l.fraction })
}

/// The warning for a sweep that lost stability, or `None`.
fn sweep_warning(file: &Path, parameter: &str, out: &Sweep, values: &[f64]) -> Option<String> {
    let l = out.stability_limit?;
    let beyond = match values.len() - out.rows.len() {
        0 => "the path snapped through to stable states beyond it".to_string(),
        1 => "the last value has no stable equilibrium reachable by loading and is not printed".to_string(),
        k => format!("the last {k} values have no stable equilibrium reachable by loading and are not printed"),
    };
    // Seven significant digits: the limit is found to a relative 1e-6.
    let magnitude = if l.value != 0.0 { l.value.abs().log10().floor().clamp(-300.0, 300.0) as i64 } else { 0 };
    let digits = (6 - magnitude).clamp(0, 17) as usize;
    Some(format!(
        "{}: stability is lost at {parameter} = {:.*} ({:.4} % along the sweep); {beyond}",
        file.display(),
        digits,
        l.value,
        100.0 * l.fraction
    ))
}

/// The checks `solve` makes of one solution, shared by `draw`: closures
/// open at rest and parts that cross (`findings`), each flexure joint's
/// estimate (a warning per flagged joint), its stress (a warning past its
/// yield strength), a snap-through on the way, and an unstable answer.
pub(super) fn put_solution_checks(
    v: &mut Value,
    m: &Mechanism,
    s: &Solution,
    reports: &[(String, Report)],
    target: &Accuracy,
    file: &Path,
) -> Result<(), String> {
    let mut findings = crate::findings::closures(m, file)?;
    findings.extend(crate::findings::shape(m, &s.q, file));
    if !findings.is_empty() {
        v["findings"] = json!(findings);
    }
    put_joint_estimates(v, m, s, target, file)?;
    put_flexure_stress(v, m, s, reports, file);
    if let Some(limit) = s.limit {
        v["limit_fraction"] = json!(limit);
        crate::options::warn(format!(
            "{}: the loading path lost stability at {:.4} % of the load and snapped through to this stable equilibrium",
            file.display(),
            100.0 * limit
        ));
    }
    if !s.stable {
        crate::options::warn(format!(
            "{}: the equilibrium is unstable (`stable: false`): its constrained stiffness is not positive definite, so a small disturbance moves it away",
            file.display()
        ));
    }
    Ok(())
}

/// The checks `solve --sweep` makes of a sweep, shared by `draw --sweep`:
/// closures open at rest and rows whose parts cross (`findings`), where
/// stability is lost, the rows whose estimate is flagged, the first row past
/// each yield strength, and a sweep that stopped (`stopped`, which makes the
/// command exit 2 after printing its rows).
pub(super) fn put_sweep_checks(
    v: &mut Value,
    m: &Mechanism,
    out: &Sweep,
    reports: &[(String, Report)],
    (target, file): (&Accuracy, &Path),
    (parameter, values): (&str, &[f64]),
) -> Result<(), String> {
    let mut findings = crate::findings::closures(m, file)?;
    let shapes: Vec<(f64, &[f64])> = out.rows.iter().map(|(v, s)| (*v, s.q.as_slice())).collect();
    findings.extend(crate::findings::along(m, &shapes, (parameter, "swept values"), "value", file));
    if !findings.is_empty() {
        v["findings"] = json!(findings);
    }
    if let Some(l) = &out.stability_limit {
        v["stability_limit"] = limit_json(l);
    }
    if let Some(w) = sweep_warning(file, parameter, out, values) {
        crate::options::warn(w);
    }
    let mut flagged = Vec::new();
    for (value, s) in &out.rows {
        if joint_estimates(m, s, target, file)?.iter().any(|e| e.2.flagged) {
            flagged.push(*value);
        }
    }
    if !flagged.is_empty() {
        v["flagged"] = json!(flagged);
        crate::options::warn(format!(
            "{}: at {} of the swept values a flexure joint's estimated error exceeds the accuracy target (listed in `flagged`); raise its order",
            file.display(),
            flagged.len()
        ));
    }
    for (k, r) in reports.iter().enumerate() {
        let Some(strength) = r.1.yield_strength else { continue };
        let over = out.rows.iter().find_map(|(value, s)| {
            let (_, f, q, _) = flexures(m, s, reports).nth(k)?;
            let p = flexure::stress::peak_stress(f, q)?;
            (p.value > strength).then_some((*value, p.value))
        });
        if let Some((value, sigma)) = over {
            crate::options::warn(format!(
                "{}: flexure joint {:?}: from {parameter} = {value} on, the peak bending stress ({sigma:.4e} Pa there) exceeds the yield strength {strength:e} Pa (column {}.stress)",
                file.display(),
                r.0,
                r.0
            ));
        }
    }
    if let Some((value, e)) = &out.stopped {
        let error = format!(
            "{}: the sweep stopped at {parameter} = {value} after {} of {} values (each printed above): {e}",
            file.display(),
            out.rows.len(),
            values.len()
        );
        v["stopped"] = json!({ "value": value, "error": error });
    }
    Ok(())
}
