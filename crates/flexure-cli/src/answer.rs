//! The JSON an answer is written in, for every command: a library result
//! serialized, an estimate, a stability limit, a matrix, and the warnings
//! that go with them on stderr.

use crate::options::warn;
use flexure::estimate::{Accuracy, ErrorEstimate};
use nalgebra::{Dim, Matrix, RawStorage};
use serde_json::{Value, json};

/// A library result as JSON: its `serde::Serialize` output, so the keys
/// the command prints are the library's field names.
pub fn serialized(result: &impl serde::Serialize) -> Value {
    // The results' keys are names and their numbers map to JSON (a NaN to
    // null, which `emit` refuses), so serializing them cannot fail.
    serde_json::to_value(result).unwrap_or(Value::Null)
}

/// The one JSON shape of an error estimate, batch rows and mechanism joints
/// included: the library's serialization of it.
pub fn estimate(e: &ErrorEstimate) -> Value {
    serialized(e)
}

pub use flexure::limit::MAX_FACTOR;

/// Writes `--limit`'s answer into `answer`: `stability_limit`, the
/// library's serialization `{factor, status}`, `status` "lost" (stability is
/// lost at `factor` times the load) or "stable_up_to" (the path holds to
/// `factor`, and `stalled` says why it could not be followed further, if it
/// could not); such a stall is also said on stderr (`what` names the answer).
pub fn insert_limit(answer: &mut Value, limit: &flexure::StabilityLimit, what: &str) {
    if let flexure::StabilityLimit::StableUpTo { factor, stalled: Some(why) } = limit {
        warn(format!(
            "{what}: the loading path stays stable up to {factor:.6} times the load, as far as it could be followed (of the {MAX_FACTOR} tried); beyond it stability is unknown: {why}"
        ));
    }
    let mut v = json!(limit);
    // The library writes `stalled: null` when `max_factor` was reached; a
    // null in an answer reads as a non-finite number, so the key is left out.
    if let Some(o) = v.as_object_mut().filter(|o| o.get("stalled").is_some_and(Value::is_null)) {
        o.remove("stalled");
    }
    answer["stability_limit"] = v;
}

/// Warns that an answer is not a stable equilibrium (`what` names it).
pub fn warn_unstable(stable: bool, what: &str) {
    if !stable {
        warn(format!(
            "{what}: the equilibrium is unstable (`stable: false`): the stiffness is not positive definite, so a small disturbance moves it away; it is not a state the joint can rest in"
        ));
    }
}

/// Which parts of a flagged estimate miss `target`, and by how much, with
/// the parts that meet it: for warnings.
pub fn misses(e: &ErrorEstimate, length: f64, target: &Accuracy) -> String {
    let peak = if e.stress.is_some() { "peak stress" } else { "peak curvature" };
    let parts = [
        ("tip position", 100.0 * e.position / length, 100.0 * target.position, "% of L"),
        ("tip angle", e.angle.to_degrees(), target.angle.to_degrees(), "°"),
        (peak, 100.0 * e.peak, 100.0 * target.stress, "%"),
    ];
    let show =
        |(name, value, goal, unit): &(&str, f64, f64, &str)| format!("{name} {value:.3}{unit} (target {goal}{unit})");
    let (miss, meet): (Vec<_>, Vec<_>) = parts.iter().partition(|p| p.1 > p.2);
    let mut text = format!(
        "the estimated error exceeds the accuracy target: {}",
        miss.into_iter().map(show).collect::<Vec<_>>().join(", ")
    );
    if !meet.is_empty() {
        text += &format!("; within it: {}", meet.into_iter().map(show).collect::<Vec<_>>().join(", "));
    }
    text
}

/// Any matrix as JSON rows.
pub fn matrix<R: Dim, C: Dim, S: RawStorage<f64, R, C>>(m: &Matrix<f64, R, C, S>) -> Value {
    json!(m.row_iter().map(|r| r.iter().copied().collect::<Vec<_>>()).collect::<Vec<_>>())
}
