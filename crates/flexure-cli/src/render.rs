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
