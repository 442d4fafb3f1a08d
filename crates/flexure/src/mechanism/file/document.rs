//! The TOML document: its top-level tables, read with their spans, the
//! keys only the other dimension takes, and the checks of numbers that
//! place every error at a line and column.

use super::closures::{BallToml, PinToml, WeldToml};
use super::dimension::FileDimension;
use super::geoms::GeomToml;
use super::{BTreeMap, Deserialize, Error, Range, Result, Spanned};
use super::{BodyToml, ForceToml, JointToml, MAX_MAGNITUDE, MIN_MAGNITUDE, ScheduleToml, TendonToml};
use toml::de::{DeTable, DeValue};

pub(super) type Span = Range<usize>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
#[serde(bound = "")]
pub(super) struct FileToml<D: FileDimension> {
    /// 2 or 3 (checked by `dimension` before the tables are read).
    #[allow(dead_code)]
    pub(super) dimension: Option<Spanned<toml::Value>>,
    #[serde(default)]
    pub(super) joint: Vec<JointToml>,
    #[serde(default)]
    pub(super) body: Vec<BodyToml<D>>,
    #[serde(default)]
    pub(super) tendon: Vec<TendonToml<D>>,
    #[serde(default)]
    pub(super) force: Vec<ForceToml<D>>,
    #[serde(default)]
    pub(super) weld: Vec<WeldToml>,
    #[serde(default)]
    pub(super) pin: Vec<PinToml<D>>,
    #[serde(default)]
    pub(super) ball: Vec<BallToml<D>>,
    #[serde(default)]
    pub(super) geom: Vec<GeomToml<D>>,
    pub(super) gravity: Option<Spanned<D::Coords>>,
    #[serde(default)]
    pub(super) schedule: Vec<ScheduleToml>,
    // `[initial]` and `[initial_velocity]`: joint name → coordinates (a
    // number or an array): read by `initial_state`.
    pub(super) initial: Option<BTreeMap<String, Spanned<toml::Value>>>,
    pub(super) initial_velocity: Option<BTreeMap<String, Spanned<toml::Value>>>,
}

/// A mechanism file parsed once: its text, its TOML document with every
/// span, and its `dimension` with the offset of its value (0 when absent).
/// [`Document::planar`] or [`Document::spatial`] then reads its tables.
pub struct Document<'i> {
    pub(super) text: &'i str,
    pub(super) doc: Spanned<DeTable<'i>>,
    pub(super) dimension: (u8, usize),
}

impl<'i> Document<'i> {
    /// Parses `text` as TOML once and reads its `dimension`: 2 (a planar
    /// mechanism, also when absent) or 3 (a spatial one); any other value
    /// is an error at its place, as is a TOML error.
    pub fn parse(text: &'i str) -> Result<Self> {
        if text.len() > super::MAX_TEXT_BYTES {
            return Err(Error::File {
                place: "the whole file".into(),
                message: format!(
                    "{} bytes, more than the {} MiB a mechanism file may hold",
                    text.len(),
                    super::MAX_TEXT_BYTES >> 20
                ),
            });
        }
        let doc = DeTable::parse(text).map_err(|e| Error::File {
            place: place(text, e.span().map_or(0, |s| s.start).min(text.len())),
            message: e.message().trim().to_string(),
        })?;
        let dimension = match doc.get_ref().get("dimension") {
            None => (2, 0),
            Some(d) => {
                let at = d.span().start;
                let value = toml::Value::deserialize(toml::de::ValueDeserializer::from(d.clone()));
                match value {
                    Ok(toml::Value::Integer(n @ (2 | 3))) => (n as u8, at),
                    v => {
                        let shown = v.map_or_else(|_| "a value".into(), |v| written(&v));
                        return Err(Error::File {
                            place: place(text, at),
                            message: format!(
                                "dimension = {shown}: must be 2 (a planar mechanism, the default) or 3 (a spatial one)"
                            ),
                        });
                    }
                }
            }
        };
        Ok(Document { text, doc, dimension })
    }

    /// 2 or 3.
    pub fn dimension(&self) -> u8 {
        self.dimension.0
    }

    /// The text it was parsed from.
    pub fn text(&self) -> &str {
        self.text
    }

    /// The document read as `T` (a view of some of its tables, for the
    /// hints), without parsing the text again; `None` if it does not fit.
    pub(crate) fn view<T: serde::de::DeserializeOwned>(&self) -> Option<T> {
        T::deserialize(toml::de::Deserializer::from(self.doc.clone())).ok()
    }
}

/// How many numbers each array of a file writes, by where it starts ([`Source::whole`]).
pub(super) type Counts = BTreeMap<usize, usize>;

/// The document's tables, in the dimension `D`, with its arrays' [`Counts`],
/// or the first error placed where it is: a serde error, or a key that only
/// the other dimension's file takes (with why).
pub(super) fn parse<D: FileDimension>(text: &str, doc: Spanned<DeTable<'_>>) -> Result<(FileToml<D>, Counts)> {
    refused::<D>(text, doc.get_ref())?;
    let mut counts = BTreeMap::new();
    for value in doc.get_ref().values() {
        count_numbers(value, &mut counts);
    }
    let file = FileToml::deserialize(toml::de::Deserializer::from(doc)).map_err(|e| toml_error::<D>(text, e))?;
    Ok((file, counts))
}

/// The numbers `value` writes (nested arrays' too: an inertia's rows), and
/// into `counts` each array's count by where it starts.
fn count_numbers(value: &Spanned<DeValue<'_>>, counts: &mut Counts) -> usize {
    match value.get_ref() {
        DeValue::Integer(_) | DeValue::Float(_) => 1,
        DeValue::Array(entries) => {
            let n = entries.iter().map(|v| count_numbers(v, counts)).sum();
            counts.insert(value.span().start, n);
            n
        }
        DeValue::Table(keys) => {
            keys.values().for_each(|v| _ = count_numbers(v, counts));
            0
        }
        _ => 0,
    }
}

/// The first key (in the file's order) of a table that only the other
/// dimension's file takes ([`FileDimension::REFUSED`]), refused with why.
fn refused<D: FileDimension>(text: &str, doc: &DeTable) -> Result<()> {
    let mut found: Option<(usize, String, &str)> = None;
    let mut check = |table: &str, keys: &DeTable| {
        for key in keys.keys() {
            let k: &str = key.get_ref();
            let hit = D::REFUSED.iter().find(|(t, ks, _)| *t == table && ks.contains(&k));
            if let Some((_, _, why)) = hit
                && found.as_ref().is_none_or(|f| key.span().start < f.0)
            {
                found = Some((key.span().start, k.to_string(), why));
            }
        }
    };
    check("", doc);
    for (name, value) in doc {
        if let DeValue::Array(tables) = value.get_ref() {
            for t in tables.iter() {
                if let DeValue::Table(keys) = t.get_ref() {
                    check(name.get_ref(), keys);
                }
            }
        }
    }
    match found {
        Some((at, key, why)) => {
            Err(Error::File { place: place(text, at), message: format!("`{key}` is for {}: {why}", D::OTHER) })
        }
        None => Ok(()),
    }
}

/// A TOML or serde error of `text`, placed. A message that names no key
/// (a wrong type, an array's length) is given the key its line starts
/// with (`at: invalid length 2, expected an array of length 3`); an
/// unknown key's list of the keys expected leaves out those only the
/// other dimension takes.
fn toml_error<D: FileDimension>(text: &str, e: toml::de::Error) -> Error {
    let at = e.span().map_or(0, |s| s.start).min(text.len());
    let message = e.message().trim().to_string();
    let line = &text[text[..at].rfind('\n').map_or(0, |n| n + 1)..at];
    let key = line.split_once('=').map(|(k, _)| k.trim()).filter(|k| {
        !k.is_empty()
            && k.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !["unknown field", "missing field", "duplicate"].iter().any(|p| message.starts_with(p))
    });
    let message = match (key, message.strip_prefix("unknown field `")) {
        (_, Some(rest)) => unknown_field::<D>(rest).unwrap_or(message),
        (Some(k), None) => format!("{k}: {message}"),
        (None, None) => message,
    };
    Error::File { place: place(text, at), message }
}

/// serde's "unknown field `k`, expected …" (given from after its first
/// backtick) with only the keys of `D`'s file, as serde words it.
fn unknown_field<D: FileDimension>(rest: &str) -> Option<String> {
    let (key, expected) = rest.split_once("`, expected ")?;
    let expected: Vec<&str> =
        expected.split('`').skip(1).step_by(2).filter(|k| !D::REFUSED.iter().any(|(_, r, _)| r.contains(k))).collect();
    let list = match expected.as_slice() {
        [] => return Some(format!("unknown field `{key}`, there are no fields")),
        [one] => format!("`{one}`"),
        [a, b] => format!("`{a}` or `{b}`"),
        many => format!("one of {}", many.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ")),
    };
    Some(format!("unknown field `{key}`, expected {list}"))
}

/// A value as the file writes it: `3`, `2.5`, `"six"`, or its type.
pub(super) fn written(v: &toml::Value) -> String {
    match v {
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(x) => format!("{x:?}"),
        toml::Value::String(s) => format!("{s:?}"),
        other => format!("a {}", other.type_str()),
    }
}

/// "line L, column C" of a byte offset.
pub(in crate::mechanism) fn place(text: &str, offset: usize) -> String {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.chars().count() - before.rfind('\n').map_or(0, |i| before[..=i].chars().count()) + 1;
    format!("line {line}, column {column}")
}

/// A number as the file would write it: plain, or in exponent form when extreme.
pub(super) fn number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e6).contains(&v.abs()) { format!("{v}") } else { format!("{v:e}") }
}

/// What a number may be, beyond finite and within the magnitudes.
#[derive(Clone, Copy, PartialEq)]
pub(super) enum Sign {
    Any,
    /// Greater than zero.
    Positive,
    /// Zero or greater.
    NotNegative,
}

/// The numbers of a value the file gives: one (a moment in the plane) or
/// several (a point, a vector).
pub(super) trait Numbers: Copy + Default {
    fn numbers(&self) -> &[f64];
}

impl Numbers for f64 {
    fn numbers(&self) -> &[f64] {
        std::slice::from_ref(self)
    }
}

impl<const N: usize> Numbers for [f64; N]
where
    [f64; N]: Default,
{
    fn numbers(&self) -> &[f64] {
        self
    }
}

/// Checks against the text they came from.
pub(super) struct Source<'t> {
    pub(super) text: &'t str,
    /// How many numbers each array writes, by where it starts.
    pub(super) counts: &'t Counts,
}

impl Source<'_> {
    pub(super) fn error(&self, span: &Span, message: String) -> Error {
        Error::File { place: place(self.text, span.start), message }
    }

    pub(super) fn fail<T>(&self, span: &Span, message: String) -> Result<T> {
        Err(self.error(span, message))
    }

    /// The array at `span` (shown as `key`, in `owner`'s entry) writes no
    /// more than the `len` numbers it takes: the file's parser reads a
    /// fixed-length array's first entries and drops the rest, so a planar
    /// `origin = [x, y, phi]` would lose its angle unsaid.
    pub(super) fn whole(&self, owner: &str, key: &str, span: &Span, len: usize) -> Result<()> {
        match self.counts.get(&span.start) {
            Some(&n) if n > len => self.fail(span, format!("{owner}{key}: {n} numbers given, where it takes {len}")),
            _ => Ok(()),
        }
    }

    /// The array at `span` is `values`, [`Source::whole`], each of them [`Source::numbers`].
    pub(super) fn array_numbers(&self, owner: &str, key: &str, span: &Span, values: &[f64], sign: Sign) -> Result<()> {
        self.whole(owner, key, span, values.len())?;
        self.numbers(owner, key, span, values, sign)
    }

    /// `values` (shown as `key`, in `owner`'s entry) are finite, within the magnitudes, of `sign`.
    pub(super) fn numbers(&self, owner: &str, key: &str, span: &Span, values: &[f64], sign: Sign) -> Result<()> {
        for (i, &v) in values.iter().enumerate() {
            let shown = if values.len() > 1 { format!("{key}[{i}]") } else { key.to_string() };
            let reason = if !v.is_finite() {
                Some("must be a finite number")
            } else if v != 0.0 && !(MIN_MAGNITUDE..=MAX_MAGNITUDE).contains(&v.abs()) {
                Some(
                    "must be zero or between 1e-30 and 1e30 in magnitude (SI units): beyond, the products the model forms leave the range of floating point",
                )
            } else if sign == Sign::Positive && v <= 0.0 {
                Some("must be greater than zero")
            } else if sign == Sign::NotNegative && v < 0.0 {
                Some("must not be negative")
            } else {
                None
            };
            if let Some(reason) = reason {
                return self.fail(span, format!("{owner}{shown} = {}: {reason}", number(v)));
            }
        }
        Ok(())
    }

    pub(super) fn number(&self, owner: &str, key: &str, value: &Spanned<f64>, sign: Sign) -> Result<f64> {
        self.numbers(owner, key, &value.span(), &[*value.get_ref()], sign)?;
        Ok(*value.get_ref())
    }

    /// The numbers of `key` (zero when absent), each checked.
    pub(super) fn array<T: Numbers>(&self, owner: &str, key: &str, value: &Option<Spanned<T>>) -> Result<T> {
        match value {
            Some(v) => {
                self.array_numbers(owner, key, &v.span(), v.get_ref().numbers(), Sign::Any)?;
                Ok(*v.get_ref())
            }
            None => Ok(T::default()),
        }
    }

    /// A library error about `owner`'s value at `span`, placed.
    pub(super) fn placed(&self, owner: &str, span: &Span, e: Error) -> Error {
        let message = match &e {
            Error::InvalidParameter { name, value, reason } => format!("{owner}{name} = {value}: {reason}"),
            other => format!("{owner}{other}"),
        };
        self.error(span, message)
    }
}
