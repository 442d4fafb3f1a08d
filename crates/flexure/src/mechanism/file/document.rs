//! The TOML document: its top-level tables, read with their spans, and the
//! checks of numbers that place every error at a line and column.

use super::{BTreeMap, Deserialize};
use super::{BodyToml, ForceToml, PinToml, ScheduleToml, TendonToml, WeldToml};
use super::{Error, JointToml, MAX_MAGNITUDE, MIN_MAGNITUDE, Range, Result, Spanned};

pub(super) type Span = Range<usize>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileToml {
    /// 2 (checked by `spatial::dimension` before the tables are read).
    #[allow(dead_code)]
    pub(super) dimension: Option<Spanned<toml::Value>>,
    #[serde(default)]
    pub(super) joint: Vec<JointToml>,
    #[serde(default)]
    pub(super) body: Vec<BodyToml>,
    #[serde(default)]
    pub(super) tendon: Vec<TendonToml>,
    #[serde(default)]
    pub(super) force: Vec<ForceToml>,
    #[serde(default)]
    pub(super) weld: Vec<WeldToml>,
    #[serde(default)]
    pub(super) pin: Vec<PinToml>,
    pub(super) gravity: Option<Spanned<[f64; 2]>>,
    #[serde(default)]
    pub(super) schedule: Vec<ScheduleToml>,
    // `[initial]` and `[initial_velocity]`: joint name → coordinates (a
    // number or an array): read by `initial_state`.
    pub(super) initial: Option<BTreeMap<String, Spanned<toml::Value>>>,
    pub(super) initial_velocity: Option<BTreeMap<String, Spanned<toml::Value>>>,
}

/// The document's tables, or the TOML error placed where it is.
pub(super) fn parse(text: &str) -> Result<FileToml> {
    toml::from_str(text).map_err(|e| {
        // Errors without a span (rare) concern the file as a whole.
        let at = place(text, e.span().map_or(0, |s| s.start));
        Error::File { place: at, message: e.message().trim().to_string() }
    })
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

/// Checks against the text they came from.
pub(super) struct Source<'t> {
    pub(super) text: &'t str,
}

impl Source<'_> {
    pub(super) fn error(&self, span: &Span, message: String) -> Error {
        Error::File { place: place(self.text, span.start), message }
    }

    pub(super) fn fail<T>(&self, span: &Span, message: String) -> Result<T> {
        Err(self.error(span, message))
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

    pub(super) fn array<const N: usize>(
        &self,
        owner: &str,
        key: &str,
        value: &Option<Spanned<[f64; N]>>,
    ) -> Result<[f64; N]> {
        match value {
            Some(v) => {
                self.numbers(owner, key, &v.span(), v.get_ref(), Sign::Any)?;
                Ok(*v.get_ref())
            }
            None => Ok([0.0; N]),
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
