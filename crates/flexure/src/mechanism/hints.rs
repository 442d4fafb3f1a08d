//! What a mechanism file's text says besides its mechanism, read leniently
//! (any other key is the parser's to judge, so no struct here denies
//! unknown keys): numbers implausible as written, told with what was
//! probably meant ([`habits`]); and where its loads are written
//! ([`loads_placed`]), for messages about the load as a whole. Nothing here
//! refuses a file.

use super::file::place;
use crate::section::{QUESTIONED_LENGTH, unit_hints};
use serde::Deserialize;
use toml::Spanned;

/// The few keys of a joint the checks read; every other key is left to the parser.
#[derive(Deserialize)]
struct Joint {
    name: Option<toml::Value>,
    length: Option<Spanned<toml::Value>>,
    modulus: Option<Spanned<toml::Value>>,
    thickness: Option<toml::Value>,
    diameter: Option<toml::Value>,
    origin: Option<Spanned<Vec<toml::Value>>>,
    rpy: Option<toml::Value>,
    rpy_deg: Option<toml::Value>,
}

#[derive(Deserialize)]
struct JointsView {
    dimension: Option<toml::Value>,
    #[serde(default)]
    joint: Vec<Joint>,
}

fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// A profile's largest value: a number, or the largest of `[root, tip]`
/// (a table's `[[t, v], …]` is read by its values).
fn largest(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Array(items) => items
            .iter()
            .filter_map(|i| match i {
                toml::Value::Array(pair) => pair.get(1).and_then(number),
                other => number(other),
            })
            .reduce(f64::max),
        other => number(other),
    }
}

/// The largest length of the mechanism other than joint `j`'s: the other
/// flexures' lengths and every joint's origin offsets (its first two
/// numbers, a planar origin's third being an angle).
fn lengths(doc: &JointsView, j: &Joint) -> f64 {
    let origin = |o: &Joint| -> f64 {
        o.origin
            .as_ref()
            .map_or(0.0, |v| v.get_ref().iter().take(2).filter_map(number).map(f64::abs).fold(0.0, f64::max))
    };
    let length = |o: &Joint| o.length.as_ref().and_then(|l| number(l.get_ref())).unwrap_or(0.0);
    doc.joint.iter().map(|o| if std::ptr::eq(o, j) { origin(o) } else { origin(o).max(length(o)) }).fold(0.0, f64::max)
}

/// Whether `z` (rad) is a multiple of 15° from 15° to 360°, as written to
/// four places or more: the third number of a planar `origin = [x, y, φ]`.
fn angle_sized(z: f64) -> bool {
    let step = std::f64::consts::PI / 12.0;
    let k = (z.abs() / step).round();
    (1.0..=24.0).contains(&k) && (z.abs() - k * step).abs() < 1e-3
}

/// The implausible numbers of a mechanism file, each as "line L, column C:
/// joint "name": key = value is read as …; write … if … were meant":
/// a flexure's `modulus` below [`LEAST_MODULUS`](crate::section::LEAST_MODULUS)
/// (GPa given as Pa); a `length` in the tens of metres on a section
/// millimetres thick, or, without a section, a hundred times every other
/// length of the mechanism (millimetres given as metres); and, in a spatial file,
/// an `origin` whose third number is an angle (a multiple of 15°), far
/// beyond the flexures' length, with no `rpy`: the planar habit
/// `origin = [x, y, φ]`, which in space reads φ as z in metres. A file that
/// does not parse has none (the parser says what is wrong).
///
/// # Example
/// ```
/// use flexure::mechanism::file::{Document, habits};
/// let text = "dimension = 3\n[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b\"\n\
///             origin = [0.0, 0.0, 1.5708]\nlength = 0.03\nmodulus = 200\nwidth = 0.01\nthickness = 3e-4\n";
/// let found = habits(&Document::parse(text).unwrap());
/// assert_eq!(found.len(), 2);
/// assert!(found[0].starts_with("line 9, column 11: joint \"a\": modulus = 200 is read as Pa"));
/// assert!(found[1].starts_with("line 7, column 10: joint \"a\": origin's third number 1.5708 is read as z = 1.5708 m"));
/// ```
pub fn habits(document: &super::file::Document) -> Vec<String> {
    let text = document.text();
    let Some(doc) = document.view::<JointsView>() else { return Vec::new() };
    let spatial = doc.dimension.as_ref().and_then(number) == Some(3.0);
    let size = doc.joint.iter().filter_map(|j| j.length.as_ref().and_then(|l| number(l.get_ref()))).fold(0.0, f64::max);
    let mut out = Vec::new();
    for j in &doc.joint {
        let owner = match j.name.as_ref() {
            Some(toml::Value::String(n)) => format!("joint {n:?}: "),
            _ => String::new(),
        };
        let at = |span: std::ops::Range<usize>| place(text, span.start);
        if let Some(l) = &j.length
            && let Some(length) = number(l.get_ref())
        {
            let thickness = j.thickness.as_ref().or(j.diameter.as_ref()).and_then(largest);
            let modulus = j.modulus.as_ref().and_then(|m| number(m.get_ref()));
            for h in unit_hints(length, modulus, thickness) {
                let span = if h.name == "modulus" { j.modulus.as_ref().map(Spanned::span) } else { Some(l.span()) };
                out.push(format!("{}: {owner}{} = {}", at(span.unwrap_or(l.span())), h.name, h.message));
            }
            // Without a section, the rest of the mechanism tells the scale.
            let others = lengths(&doc, j);
            if thickness.is_none() && length >= QUESTIONED_LENGTH && others > 0.0 && others <= length / 100.0 {
                out.push(format!(
                    "{}: {owner}length = {length} is read as metres (a flexure {length} m long, where every other length of the mechanism is {others} m or less); write {} if millimetres were meant",
                    at(l.span()),
                    length / 1000.0
                ));
            }
        }
        if spatial
            && j.rpy.is_none()
            && j.rpy_deg.is_none()
            && let Some(o) = &j.origin
            && let [x, y, z] = o.get_ref().as_slice()
            && let (Some(x), Some(y), Some(z)) = (number(x), number(y), number(z))
            && angle_sized(z)
            && z.abs() > 10.0 * size.max(x.abs()).max(y.abs())
        {
            out.push(format!(
                "{}: {owner}origin's third number {z} is read as z = {z} m, far beyond the flexures ({size} m long at most); a planar file's origin = [x, y, angle] puts an angle there: in a spatial file write origin = [{x:?}, {y:?}, 0.0] and rpy = [0.0, 0.0, {z}] if the angle were meant",
                at(o.span())
            ));
        }
    }
    out
}

#[derive(Deserialize)]
struct Named {
    name: Option<Spanned<toml::Value>>,
}

#[derive(Deserialize)]
struct LoadsDocument {
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
    let Ok(doc) = toml::from_str::<LoadsDocument>(text) else { return Vec::new() };
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
