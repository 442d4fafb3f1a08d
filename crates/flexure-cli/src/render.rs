//! Output: one JSON object with `--json`, otherwise the same content as a readable table.

use serde_json::Value;
use std::fmt::Write;

/// Renders `value` as indented `key: value` lines; numeric vectors on one
/// line, matrices as aligned rows.
pub fn readable(value: &Value) -> String {
    let mut out = String::new();
    write_value(&mut out, value, 0, "");
    out
}

/// The unit (or meaning) shown after a number of the table form, by its
/// key and the key of the object holding it; `None` for pure numbers
/// (factors, counts, flags) and for matrices of mixed units.
fn unit(parent: &str, key: &str) -> Option<&'static str> {
    Some(match (parent, key) {
        ("error_estimate", "omega" | "critical_load" | "load_factor") => "(relative)",
        ("curvature_max", "max") | (_, "curvature") => "1/m",
        ("stress", "max") | (_, "stress" | "bending_y" | "bending_z" | "shear" | "von_mises") => "Pa",
        ("curvature_max" | "stress", "at") => "m along the flexure",
        (_, "phi" | "angle" | "alpha" | "gap_rad" | "rpy" | "roll" | "pitch" | "yaw") => "rad",
        (_, "angle_degrees") => "°",
        (_, "x" | "y" | "z" | "position" | "tendon_length" | "s" | "gap_m" | "gap") | ("contacts", "point") => "m",
        (_, "normal_force" | "friction_force") => "N",
        (_, "moment" | "root_moment" | "residual") => "N·m",
        (_, "fx" | "fy" | "force" | "tension" | "critical_load" | "reference_critical_load") => "N",
        (_, "energy" | "model_energy") => "J",
        (_, "omega" | "reference_omega") => "rad/s",
        (_, "frequency") => "Hz",
        (_, "time") => "s",
        (_, "factor") => "times the load",
        (_, "force_scale_m_per_n") => "m per N",
        (_, "eta") => "(η = model energy / exact energy − 1: how much stiffer the model is, paper Sec. II-E)",
        _ => return None,
    })
}

/// A long vector `q` labelled by joint, when `map` lists the joints with
/// their `name` and `coordinates` (a spatial answer): one line a joint.
fn by_joint(map: &serde_json::Map<String, Value>, q: &Value) -> Option<Vec<(String, Value)>> {
    let joints = map.get("joints")?.as_array()?;
    let rows: Vec<(String, Value)> = joints
        .iter()
        .map(|j| Some((j.get("name")?.as_str()?.to_string(), j.get("coordinates")?.clone())))
        .collect::<Option<_>>()?;
    let rows: Vec<(String, Value)> =
        rows.into_iter().filter(|(_, c)| c.as_array().is_some_and(|c| !c.is_empty())).collect();
    let count: usize = rows.iter().map(|(_, c)| c.as_array().map_or(0, Vec::len)).sum();
    (q.as_array().map(Vec::len) == Some(count)).then_some(rows)
}

fn write_value(out: &mut String, value: &Value, indent: usize, parent: &str) {
    let pad = " ".repeat(indent);
    match value {
        Value::Object(map) => {
            for (key, v) in map {
                match v {
                    // An empty list is no row.
                    Value::Array(items) if items.is_empty() => {}
                    Value::Array(_) if key == "q" && by_joint(map, v).is_some() => {
                        let _ = writeln!(out, "{pad}{key}:");
                        for (name, c) in by_joint(map, v).unwrap_or_default() {
                            let _ = writeln!(out, "{pad}  {name}: {}", inline(&c));
                        }
                    }
                    Value::Object(_) => {
                        let _ = writeln!(out, "{pad}{key}:");
                        // Per-flexure maps of a quantity keep its name, for units.
                        let context = if matches!(parent, "curvature_max" | "stress") { parent } else { key };
                        write_value(out, v, indent + 2, context);
                    }
                    Value::Array(rows) if rows.iter().all(|r| r.is_array()) && !rows.is_empty() => {
                        let _ = writeln!(out, "{pad}{key}:");
                        for r in rows {
                            let _ = writeln!(out, "{pad}  {}", inline(r));
                        }
                    }
                    Value::Array(items) if items.iter().any(|r| r.is_object()) => {
                        let _ = writeln!(out, "{pad}{key}:");
                        for (i, item) in items.iter().enumerate() {
                            let _ = writeln!(out, "{pad}  [{i}]");
                            write_value(out, item, indent + 4, key);
                        }
                    }
                    _ => {
                        let numeric = v.is_number() || v.as_array().is_some_and(|a| a.iter().all(Value::is_number));
                        let shown = match unit(parent, key) {
                            Some(u) if numeric => format!("{} {u}", inline(v)),
                            _ => inline(v),
                        };
                        let _ = writeln!(out, "{pad}{key}: {shown}");
                    }
                }
            }
        }
        other => {
            let _ = writeln!(out, "{pad}{}", inline(other));
        }
    }
}

fn inline(v: &Value) -> String {
    match v {
        Value::Number(n) => match n.as_f64() {
            Some(x) if n.is_f64() => number(x),
            _ => n.to_string(),
        },
        Value::Array(items) => items.iter().map(inline).collect::<Vec<_>>().join(" "),
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Fixed notation for ordinary magnitudes, scientific for very small or large ones.
fn number(x: f64) -> String {
    if x == 0.0 || (1e-3..1e6).contains(&x.abs()) { format!("{x:>12.6}") } else { format!("{x:>12.4e}") }
}

/// The path of the first `null` in `value` (`""` for the whole value), if
/// any: serde_json writes NaN and ±∞ as `null`, and no answer holds a
/// `null` otherwise, so this finds every non-finite number.
pub fn non_finite(value: &Value) -> Option<String> {
    match value {
        Value::Null => Some(String::new()),
        Value::Array(items) => items.iter().enumerate().find_map(|(i, v)| non_finite(v).map(|p| format!("[{i}]{p}"))),
        Value::Object(map) => map.iter().find_map(|(k, v)| non_finite(v).map(|p| format!(".{k}{p}"))),
        _ => None,
    }
}

/// The error for a non-finite number at `path` (as found by [`non_finite`]).
pub fn non_finite_message(path: &str) -> String {
    let field = path.strip_prefix('.').unwrap_or(path);
    if field.is_empty() {
        "the result is not a finite number (NaN or infinite); nothing was printed".into()
    } else {
        format!("the result's field `{field}` is not a finite number (NaN or infinite); nothing was printed")
    }
}

/// `x` in the shortest form that reads back to the same number: plain
/// from 1e-4 up to 1e16 (`0.5`, `1`), with an exponent beyond (`1e-30`, not
/// 30 zeros; `3.2048809982368066e-6`), as Python's `repr` writes floats.
pub fn shortest(x: f64) -> String {
    let magnitude = x.abs().log10().floor();
    if x == 0.0 || (-4.0..16.0).contains(&magnitude) { x.to_string() } else { format!("{x:e}") }
}

/// The leaves of `value`, in order, as one CSV line (the `--input` table form).
pub fn csv_line(value: &Value) -> String {
    fn leaves(v: &Value, out: &mut Vec<String>) {
        match v {
            Value::Array(items) => items.iter().for_each(|i| leaves(i, out)),
            Value::Object(map) => map.values().for_each(|i| leaves(i, out)),
            Value::Number(n) if n.is_f64() => out.push(n.as_f64().map_or_else(|| n.to_string(), shortest)),
            Value::Number(n) => out.push(n.to_string()),
            Value::String(s) => out.push(s.clone()),
            other => out.push(other.to_string()),
        }
    }
    let mut out = Vec::new();
    leaves(value, &mut out);
    out.join(",")
}

#[cfg(test)]
mod tests {
    use super::{readable, shortest};

    /// A contact's numbers carry their units in the table form, as every
    /// other answer's do; its normal (a unit vector) and state carry none.
    #[test]
    fn a_contacts_numbers_carry_their_units() {
        let answer = serde_json::json!({ "contacts": [{
            "geom": "floor", "s": 0.1, "point": [0.08, -0.05], "normal": [0.0, 1.0],
            "normal_force": 0.66, "friction_force": [0.0, 0.0], "gap": 0.0, "state": "slip"
        }] });
        let text = readable(&answer);
        for (key, unit) in
            [("s", " m"), ("point", " m"), ("normal_force", " N"), ("friction_force", " N"), ("gap", " m")]
        {
            let line = text.lines().find(|l| l.trim_start().starts_with(&format!("{key}:"))).unwrap();
            assert!(line.ends_with(unit), "{line:?}");
        }
        let normal = text.lines().find(|l| l.trim_start().starts_with("normal:")).unwrap();
        assert!(normal.ends_with("1.000000"), "{normal:?}");
    }

    /// Short forms, and every form reads back to the very same number
    /// (seeded values across the whole range of magnitudes).
    #[test]
    fn shortest_reads_back_exactly() {
        assert_eq!([shortest(1e-30), shortest(0.5), shortest(1.0), shortest(0.0)], ["1e-30", "0.5", "1", "0"]);
        assert_eq!([shortest(-2.5e-5), shortest(1e16), shortest(123.25)], ["-2.5e-5", "1e16", "123.25"]);
        let mut bits = 0x9E37_79B9_7F4A_7C15_u64;
        for _ in 0..10_000 {
            bits ^= bits << 13;
            bits ^= bits >> 7;
            bits ^= bits << 17;
            let x = f64::from_bits(bits);
            if x.is_finite() {
                let s = shortest(x);
                assert_eq!(s.parse::<f64>().unwrap(), x, "{s}");
                assert!(s.len() <= 24, "{s}");
            }
        }
    }
}
