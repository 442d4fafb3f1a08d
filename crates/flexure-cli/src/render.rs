//! Output: one JSON object with `--json`, otherwise the same content as a readable table.

use serde_json::Value;
use std::fmt::Write;

/// Renders `value` as indented `key: value` lines; numeric vectors on one
/// line, matrices as aligned rows.
pub fn readable(value: &Value) -> String {
    let mut out = String::new();
    write_value(&mut out, value, 0);
    out
}

fn write_value(out: &mut String, value: &Value, indent: usize) {
    let pad = " ".repeat(indent);
    match value {
        Value::Object(map) => {
            for (key, v) in map {
                match v {
                    Value::Object(_) => {
                        let _ = writeln!(out, "{pad}{key}:");
                        write_value(out, v, indent + 2);
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
                            write_value(out, item, indent + 4);
                        }
                    }
                    _ => {
                        let _ = writeln!(out, "{pad}{key}: {}", inline(v));
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

/// The leaves of `value`, in order, as one CSV line (the `--input` table form).
pub fn csv_line(value: &Value) -> String {
    fn leaves(v: &Value, out: &mut Vec<String>) {
        match v {
            Value::Array(items) => items.iter().for_each(|i| leaves(i, out)),
            Value::Object(map) => map.values().for_each(|i| leaves(i, out)),
            Value::Number(n) => out.push(n.as_f64().map_or_else(|| n.to_string(), |x| x.to_string())),
            Value::String(s) => out.push(s.clone()),
            other => out.push(other.to_string()),
        }
    }
    let mut out = Vec::new();
    leaves(value, &mut out);
    out.join(",")
}
