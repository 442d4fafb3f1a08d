//! What `solve` checks of a solution or a sweep, and `draw` repeats:
//! closures and crossings (`findings`), each flexure joint's error estimate
//! and stress, snap-throughs, stability, and a sweep that stopped.

use crate::options::warn;
use flexure::estimate::Accuracy;
use flexure::model::{Model, Solved, Swept};
use flexure::report::{EstimateFailed, SolveReport};
use serde_json::{Value, json};
use std::path::Path;

/// Why a solve report has no answer: the flexure joint whose error
/// estimate failed, and that it was the estimate's own solve that failed
/// (not the mechanism's).
fn estimate_failed(file: &Path, f: EstimateFailed) -> String {
    format!(
        "{}: flexure joint {:?}: its error estimate (the joint alone under the tip load it carries, against the refined model) failed: {}",
        file.display(),
        f.joint,
        f.error
    )
}

/// What to do about a flexure joint whose estimate misses the target:
/// raise its order, unless it has `order = "auto"` and stopped at the cap.
fn order_hint(joint: &str, capped: &[String]) -> &'static str {
    if capped.iter().any(|c| c == joint) { CAPPED } else { "raise its order" }
}

/// What a flexure of `order = "auto"` that still misses at the cap says.
const CAPPED: &str =
    "order = \"auto\" raised it to the cap of 64 and it still misses: loosen --accuracy or reduce the load";

/// Warns of each flexure joint whose estimate misses `target` (`capped`:
/// those of `order = "auto"` at the cap), then of each stressed past its
/// yield strength.
fn warn_joints(r: &SolveReport, (model, capped): (&Model, &[String]), target: &Accuracy, file: &Path) {
    for (name, e) in r.error_estimate.0.iter().filter(|(_, e)| e.flagged) {
        let misses = crate::answer::misses(e, model.flexure_length(name).unwrap_or(0.0), target);
        warn(format!("{}: flexure joint {name:?}: {misses}; {}", file.display(), order_hint(name, capped)));
    }
    for (name, factor) in r.safety_factor.0.iter().filter(|(_, factor)| *factor < 1.0) {
        if let (Some(p), Some(strength)) = (r.stress.get(name), model.yield_strength(name)) {
            warn(format!(
                "{}: flexure joint {name:?}: the peak stress {:.4e} Pa (at s = {:.4e} m) exceeds the yield strength {strength:e} Pa: safety factor {factor:.3}",
                file.display(),
                p.max,
                p.at
            ));
        }
    }
}

/// The warning for a sweep that lost stability, or `None`.
fn sweep_warning(file: &Path, parameter: &str, out: &Swept, values: &[f64]) -> Option<String> {
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

/// `solve`'s answer, shared by `draw`: the library's report
/// ([`flexure::report::solve_report`]) with the compliance asked for,
/// `order` (the orders used) when a flexure has `order = "auto"`, and
/// after the `findings` told before the solve (the closures open at rest)
/// the parts that cross; each told
/// on stderr, as are each flagged estimate, a stress past its yield
/// strength, a snap-through on the way, and an unstable answer.
pub(super) fn solve_answer(
    model: &Model,
    mut findings: Vec<Value>,
    solved: Solved,
    target: &Accuracy,
    file: &Path,
) -> Result<Value, String> {
    findings.extend(crate::findings::crossing_answers(solved.crossings, file));
    let r = solved.report.map_err(|f| estimate_failed(file, f))?;
    warn_joints(&r, (model, &solved.capped), target, file);
    let mut v = serde_json::to_value(&r).map_err(|e| format!("{}: {e}", file.display()))?;
    crate::eigen::insert_orders(&mut v, &solved.model);
    if let Some(c) = &solved.compliance {
        v["compliance"] = crate::answer::matrix(c);
    }
    if !findings.is_empty() {
        v["findings"] = json!(findings);
    }
    if let Some(limit) = r.limit_fraction {
        warn(format!(
            "{}: the loading path lost stability at {:.4} % of the load and snapped through to this stable equilibrium",
            file.display(),
            100.0 * limit
        ));
    }
    if !r.stable {
        warn(format!(
            "{}: the equilibrium is unstable (`stable: false`): its constrained stiffness is not positive definite, so a small disturbance moves it away",
            file.display()
        ));
    }
    Ok(v)
}

/// `solve --sweep`'s answer, shared by `draw --sweep`: the table, with
/// after the `findings` told before the sweep (the closures open at rest)
/// the rows whose parts cross; where stability is lost, the rows whose
/// estimate is flagged, the first row past each yield strength, each told
/// on stderr; and a sweep that stopped (`stopped`, which makes the command
/// exit 2 after printing its rows).
pub(super) fn swept_answer(
    model: &Model,
    mut findings: Vec<Value>,
    out: &Swept,
    file: &Path,
    (parameter, values): (&str, &[f64]),
) -> Value {
    let mut v = json!({ "dimension": model.dimension(), "columns": out.columns, "rows": out.rows });
    // Each row's contacts as `solve` reports them (state and friction too),
    // by its value, where a pair may touch: the table has only their normal forces.
    if let Some(contacts) = &out.contacts {
        let rows = out.rows.iter().zip(contacts);
        v["contacts"] = json!(rows.map(|(r, c)| json!({ "value": r[0], "contacts": c })).collect::<Vec<_>>());
    }
    crate::eigen::insert_orders(&mut v, &out.model);
    let shapes: Vec<(f64, &[f64])> = out.rows.iter().zip(&out.q).map(|(r, q)| (r[0], q.as_slice())).collect();
    let found = out.crossings.clone();
    findings.extend(crate::findings::crossing_answers_along(
        found,
        &shapes,
        (parameter, "swept values"),
        "value",
        file,
    ));
    if !findings.is_empty() {
        v["findings"] = json!(findings);
    }
    if let Some(l) = &out.stability_limit {
        v["stability_limit"] = json!(l);
    }
    if let Some(w) = sweep_warning(file, parameter, out, values) {
        warn(w);
    }
    if !out.flagged.is_empty() {
        v["flagged"] = json!(out.flagged);
        let hint = match out.capped.as_slice() {
            [] => "raise its order".to_string(),
            capped => format!("flexure joints {capped:?}: {CAPPED}"),
        };
        warn(format!(
            "{}: at {} of the swept values a flexure joint's estimated error exceeds the accuracy target (listed in `flagged`); {hint}",
            file.display(),
            out.flagged.len()
        ));
    }
    for (joint, value, sigma) in &out.yielded {
        let strength = model.yield_strength(joint).unwrap_or(f64::NAN);
        warn(format!(
            "{}: flexure joint {joint:?}: from {parameter} = {value} on, the peak stress ({sigma:.4e} Pa there) exceeds the yield strength {strength:e} Pa (column {joint}.stress)",
            file.display(),
        ));
    }
    if let Some((value, e)) = &out.stopped {
        let error = format!(
            "{}: the sweep stopped at {parameter} = {value} after {} of {} values (each printed above), {}: {e}",
            file.display(),
            out.rows.len(),
            values.len(),
            flexure::mechanism::sweep::way_to(out.rows.last().map(|r| r[0]))
        );
        v["stopped"] = json!({ "value": value, "error": error });
    }
    v
}

/// The sweep of `parameter` over `values` on `model`, with the compliance
/// of a frame in each row if asked for: the table and its checks ([`swept_answer`]).
pub(super) fn sweep_table(
    model: &Model,
    (parameter, values): (&str, &[f64]),
    compliance: Option<(&str, &[f64])>,
    target: &Accuracy,
    file: &Path,
) -> Result<(Value, Swept), String> {
    let findings = crate::findings::open_at_rest(model, file)?;
    let out = model
        .sweep(parameter, values, target, compliance)
        .map_err(|e| match e {
            e @ flexure::Error::InvalidParameter { name: "sweep", .. } => crate::describe(e),
            e => super::solver_error(file)(e),
        })?
        .map_err(|f| estimate_failed(file, f))?;
    Ok((swept_answer(model, findings, &out, file, (parameter, values)), out))
}
