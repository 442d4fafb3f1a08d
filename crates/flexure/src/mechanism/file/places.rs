//! Where a file's loads are written, for messages about the load as a
//! whole ("the loading path loses stability at 40 % of the load").

use super::document::place;
use serde::Deserialize;
use toml::Spanned;

#[derive(Deserialize)]
struct Named {
    name: Option<Spanned<toml::Value>>,
}

#[derive(Deserialize)]
struct Document {
    #[serde(default)]
    force: Vec<Named>,
    #[serde(default)]
    tendon: Vec<Named>,
    gravity: Option<Spanned<toml::Value>>,
}

/// The loads of a mechanism file, each named with its place: `force
/// "tip" (line 30, column 8)`, `tendon "flexor" (…)`, `gravity (…)`; the
/// load a continuation follows from rest is all of them at once. Empty for
/// a file that does not parse.
///
/// # Example
/// ```
/// let text = "gravity = [0.0, -9.81]\n[[force]]\nname = \"tip\"\nbody = \"b\"\nat = [0.0, 0.0]\nforce = [0.0, -1.0]\n";
/// let placed = flexure::mechanism::file::loads_placed(text);
/// assert_eq!(placed, ["force \"tip\" (line 3, column 8)", "gravity (line 1, column 11)"]);
/// ```
pub fn loads_placed(text: &str) -> Vec<String> {
    let Ok(doc) = toml::from_str::<Document>(text) else { return Vec::new() };
    let named = |kind: &str, n: &Named| {
        let name = n.name.as_ref()?;
        let shown = match name.get_ref() {
            toml::Value::String(s) => format!("{s:?}"),
            other => format!("{other:?}"),
        };
        Some(format!("{kind} {shown} ({})", place(text, name.span().start)))
    };
    let mut out: Vec<String> = doc.force.iter().filter_map(|n| named("force", n)).collect();
    out.extend(doc.tendon.iter().filter_map(|n| named("tendon", n)));
    if let Some(g) = &doc.gravity {
        out.push(format!("gravity ({})", place(text, g.span().start)));
    }
    out
}
