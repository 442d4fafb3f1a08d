//! The error estimates of eigenvalue answers (`buckling`, `buckle`,
//! `modes`): the `--accuracy` they are held to, and how they are written
//! and warned about. The library computes them
//! (`flexure::estimate::ValueEstimate`); this only prints them.

use crate::options::{number, warn};
use clap::Args;
use flexure::estimate::{Accuracy, ValueEstimate};
use flexure::model::Model;
use serde_json::{Map, Value, json};

/// Parses `--accuracy REL` of a buckling load or frequency: a fraction of the value.
pub fn relative(s: &str) -> Result<Accuracy, String> {
    let hint = "a buckling load or frequency has one target, a fraction of itself such as 0.005";
    if s.contains(',') {
        return Err(format!("{s:?}: {hint} (POS,ANGLE[,STRESS] is deflect's)"));
    }
    let target = Accuracy { eigenvalue: number(s)?, ..Default::default() };
    target.validate().map_err(|_| format!("{s:?} must be finite and greater than zero: {hint}"))?;
    Ok(target)
}

/// `--accuracy` of `buckling`, `buckle` and `modes`.
#[derive(Debug, Clone, Args)]
pub struct EigenAccuracyOptions {
    /// Accuracy target REL: the estimated relative error every buckling load
    /// or frequency must meet (as a fraction: 0.01 is 1 %). One above it is
    /// flagged, with a warning; --order auto (order = "auto" in a file)
    /// raises the order until all meet it [default: 0.01].
    #[arg(long, value_parser = relative, allow_hyphen_values = true)]
    pub accuracy: Option<Accuracy>,
}

impl EigenAccuracyOptions {
    /// The target, by default 1 % of the value.
    pub fn target(&self) -> Accuracy {
        self.accuracy.unwrap_or_default()
    }
}

/// How an estimate is written: `key` names the estimated values
/// (`critical_load`, `load_factor`, `omega`), `one` whether there is a
/// single value (a number) or one per mode (an array), `flexures` the
/// flexure joints' names for a mechanism (empty for one joint).
pub struct EigenKeys<'a> {
    pub key: &'static str,
    pub one: bool,
    pub flexures: &'a [String],
}

/// Writes `error_estimate` and `flagged` into `answer`:
/// `error_estimate` = {KEY: relative error (one number, or one per value
/// paired with the reference), reference_KEY, reference_order,
/// reference_quadrature (numbers for one joint, {joint: n} for a
/// mechanism), and where some value has no estimate, `unestimated` (their
/// numbers from 1) and `reference_stable`}.
pub fn insert_eigen_estimate(answer: &mut Value, e: &ValueEstimate, shape: &EigenKeys) {
    let paired: Vec<f64> = e.relative.iter().map_while(|r| *r).collect();
    let mut out = Map::new();
    let relative = if shape.one { paired.first().map_or(Value::Null, |r| json!(r)) } else { json!(paired) };
    if !relative.is_null() {
        out.insert(shape.key.into(), relative);
    }
    let reference = if shape.one { e.reference.first().map_or(Value::Null, |r| json!(r)) } else { json!(e.reference) };
    if !reference.is_null() {
        out.insert(format!("reference_{}", shape.key), reference);
    }
    if shape.flexures.is_empty() {
        if let Some(&(order, points)) = e.reference_orders.first() {
            out.insert("reference_order".into(), json!(order));
            out.insert("reference_quadrature".into(), json!(points));
        }
    } else {
        let by_joint = |pick: fn(&(usize, usize)) -> usize| {
            Value::Object(
                shape.flexures.iter().zip(&e.reference_orders).map(|(n, o)| (n.clone(), json!(pick(o)))).collect(),
            )
        };
        out.insert("reference_order".into(), by_joint(|o| o.0));
        out.insert("reference_quadrature".into(), by_joint(|o| o.1));
    }
    let unestimated: Vec<usize> = (0..e.relative.len()).filter(|&k| e.relative[k].is_none()).map(|k| k + 1).collect();
    if !unestimated.is_empty() {
        out.insert("unestimated".into(), json!(unestimated));
        out.insert("reference_stable".into(), json!(e.reference_stable));
    }
    answer["error_estimate"] = Value::Object(out);
    answer["flagged"] = json!(e.flagged);
}

/// Warns about each value of a flagged estimate that misses `target`:
/// `what` names the answer (`buckling`, `FILE: modes`), `name(k)` the
/// value (`the critical load 42 N`, `mode 3 (118.1 rad/s)`), `reference`
/// the reference model, and `hint` what to do (`try --order auto`, or that
/// the order cap is reached).
pub fn warn_missed(
    e: &ValueEstimate,
    target: &Accuracy,
    what: &str,
    name: impl Fn(usize) -> String,
    reference: &str,
    hint: &str,
) {
    if !e.flagged {
        return;
    }
    let goal = 100.0 * target.eigenvalue;
    let parts: Vec<String> = e
        .missed(target)
        .into_iter()
        .map(|k| match e.relative[k] {
            Some(r) => format!("{}: estimated error {:.3} % (target {goal} %)", name(k), 100.0 * r),
            None if !e.reference_stable => format!(
                "{}: no estimate: the reference model is unstable under these loads (it buckles below them, the model does not), so the model's frequencies are not to be trusted",
                name(k)
            ),
            None => format!("{}: no estimate: the reference model resolves no such mode", name(k)),
        })
        .collect();
    warn(format!("{what}: {} (against {reference}); {hint}", parts.join("; ")));
}

/// The reference model of a single joint, for warnings: "order N with Q points".
pub fn reference_of_joint(e: &ValueEstimate) -> String {
    e.reference_orders.first().map_or("the refined model".into(), |(n, q)| format!("order {n} with {q} points"))
}

/// `error_estimate` and `flagged` of a mechanism's eigenvalue answer, the
/// estimated values under `key` (with `order`, {joint: its order(s)}, when a
/// flexure has `order = "auto"`: the orders the answer was found at).
pub fn insert_mechanism_estimate(answer: &mut Value, used: &Model, e: &ValueEstimate, key: &'static str) {
    let flexures = used.flexure_names();
    insert_eigen_estimate(answer, e, &EigenKeys { key, one: key == "load_factor", flexures: &flexures });
    insert_orders(answer, used);
}

/// `order`, {joint: N (planar) or [n_twist, n_y, n_z] (spatial)}, when a
/// flexure of `used` has `order = "auto"`: the orders an answer was found
/// at (`buckle`, `modes`, `solve` and `solve --sweep` alike).
pub fn insert_orders(answer: &mut Value, used: &Model) {
    if used.auto_order() {
        let orders = used.orders().0.into_iter().map(|(name, o)| match o.as_slice() {
            [one] => (name, json!(one)),
            all => (name, json!(all)),
        });
        answer["order"] = Value::Object(orders.collect());
    }
}

/// What to do about a mechanism's eigenvalue answer that misses its target.
pub fn advice(used: &Model) -> &'static str {
    if used.auto_order() {
        "the flexures of order = \"auto\" are at the cap of 64, or there are none left to raise: give the others order = \"auto\""
    } else {
        "give the flexures order = \"auto\" (or a higher order)"
    }
}
