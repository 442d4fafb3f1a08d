//! Sections that are no flexure, and numbers that are implausible as given:
//! the checks every front end shares, planar and spatial alike.

use crate::error::{Error, Result};

/// Refuses a section thicker than the flexure is long: a beam (or rod) that
/// is thicker than it is long is no flexure. `thickness` yields the
/// section's thickness $h$ (or a round rod's diameter) at points $t = s/L$
/// where its largest value lies (the ends and breakpoints of a piecewise
/// linear profile); the error names `name` and the first $t$ where $h > L$.
///
/// # Example
/// ```
/// use flexure::section::thinner_than_long;
/// assert!(thinner_than_long("thickness", 0.01, [(0.0, 2e-4), (1.0, 3e-4)]).is_ok());
/// let e = thinner_than_long("diameter", 0.01, [(0.0, 2e-4), (1.0, 0.02)]).unwrap_err();
/// assert!(e.to_string().starts_with("invalid diameter = 0.02 m at t = 1, on a flexure of length 0.01 m"));
/// ```
pub fn thinner_than_long(
    name: &'static str,
    length: f64,
    thickness: impl IntoIterator<Item = (f64, f64)>,
) -> Result<()> {
    match thickness.into_iter().find(|&(_, h)| h > length) {
        Some((t, h)) => Err(Error::invalid(
            name,
            format!("{h} m at t = {t}, on a flexure of length {length} m"),
            "must not exceed the flexure's length: a beam thicker than it is long is no flexure",
        )),
        None => Ok(()),
    }
}

/// The least Young's modulus taken as meant (Pa): soft rubber's. A smaller
/// one is probably in GPa or MPa, given as if in Pa.
pub const LEAST_MODULUS: f64 = 1e6;

/// The least length (m) that is questioned, with a section at most
/// [`MM_SECTION`] thick: a flexure tens of metres long and millimetres thick
/// was probably given in millimetres.
pub const QUESTIONED_LENGTH: f64 = 10.0;

/// The thickest section (m) for which a length of [`QUESTIONED_LENGTH`] or
/// more is questioned.
pub const MM_SECTION: f64 = 0.01;

/// A number a front end was given that is implausible as given: the
/// parameter, as files and Python spell it, and what it was read as and
/// probably meant ("200 is read as Pa …; write 200e9 if GPa were meant").
#[derive(Debug, Clone, PartialEq)]
pub struct Hint {
    /// `modulus` or `length`.
    pub name: &'static str,
    /// The value as read, and what was probably meant.
    pub message: String,
}

/// The hints for a flexure of `length` (m), Young's `modulus` (Pa) and
/// largest section `thickness` (or diameter, m), where one is implausible:
/// a modulus below [`LEAST_MODULUS`] (GPa given as Pa), and a length of
/// [`QUESTIONED_LENGTH`] or more on a section at most [`MM_SECTION`] thick
/// (millimetres given as metres). Nothing is refused: these are warnings.
///
/// # Example
/// ```
/// use flexure::section::unit_hints;
/// let h = unit_hints(0.04, Some(200.0), Some(2e-4));
/// assert_eq!(h.len(), 1);
/// assert_eq!(h[0].name, "modulus");
/// assert!(h[0].message.contains("write 200e9"));
/// let h = unit_hints(15.0, Some(200e9), Some(3e-4));
/// assert!(h[0].name == "length" && h[0].message.contains("write 0.015"));
/// assert!(unit_hints(0.04, Some(200e9), Some(2e-4)).is_empty());
/// ```
pub fn unit_hints(length: f64, modulus: Option<f64>, thickness: Option<f64>) -> Vec<Hint> {
    let mut out = Vec::new();
    if let Some(e) = modulus.filter(|e| *e > 0.0 && *e < LEAST_MODULUS) {
        out.push(Hint {
            name: "modulus",
            message: format!("{e} is read as Pa ({e} Pa, softer than rubber's 1e6 Pa); write {e}e9 if GPa were meant"),
        });
    }
    if let Some(h) = thickness.filter(|h| *h > 0.0 && *h <= MM_SECTION && length >= QUESTIONED_LENGTH) {
        out.push(Hint {
            name: "length",
            message: format!(
                "{length} is read as metres (a flexure {length} m long and {h} m thick); write {} if millimetres were meant",
                length / 1000.0
            ),
        });
    }
    out
}
