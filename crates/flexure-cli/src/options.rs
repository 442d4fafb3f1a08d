//! Options shared by every subcommand, and the parsers that reject bad numbers.

use clap::Args;
use flexure::{Flexure, bending_stiffness};

/// Parses a finite number.
pub fn number(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().parse().map_err(|_| format!("{s:?} is not a number"))?;
    if v.is_finite() { Ok(v) } else { Err(format!("{s:?} is not a finite number")) }
}

/// Parses an angle in radians, or in degrees with a `deg` suffix (`45deg`).
pub fn angle(s: &str) -> Result<f64, String> {
    match s.trim().strip_suffix("deg") {
        Some(d) => number(d).map(f64::to_radians),
        None => number(s),
    }
}

/// A comma-separated list of finite numbers (a newtype: clap reads a bare
/// `Vec` as a repeated option).
#[derive(Debug, Clone, PartialEq)]
pub struct List(pub Vec<f64>);

/// Parses a comma-separated list of finite numbers.
pub fn numbers(s: &str) -> Result<List, String> {
    s.split(',').map(number).collect::<Result<_, _>>().map(List)
}

/// The flexure: `--length`, `--ei` (or `--modulus --width --thickness [--poisson]`),
/// `--kappa`, `--order`, `--quadrature`.
#[derive(Debug, Clone, Args)]
pub struct FlexureOptions {
    /// Length L in metres.
    #[arg(long, default_value = "1", value_parser = number, allow_hyphen_values = true)]
    pub length: f64,
    /// Bending stiffness EI in N·m² [default: 1, or from --modulus --width --thickness].
    #[arg(long, value_parser = number, allow_hyphen_values = true, conflicts_with = "modulus")]
    pub ei: Option<f64>,
    /// Young's modulus E in Pa (with --width and --thickness, in place of --ei).
    #[arg(long, value_parser = number, allow_hyphen_values = true, requires_all = ["width", "thickness"])]
    pub modulus: Option<f64>,
    /// Width b in metres.
    #[arg(long, value_parser = number, allow_hyphen_values = true, requires = "modulus")]
    pub width: Option<f64>,
    /// Thickness h in metres.
    #[arg(long, value_parser = number, allow_hyphen_values = true, requires = "modulus")]
    pub thickness: Option<f64>,
    /// Poisson ratio ν: a wide flexure, EI = E/(1−ν²)·b·h³/12 (Eq. 25).
    #[arg(long, value_parser = number, allow_hyphen_values = true, requires = "modulus")]
    pub poisson: Option<f64>,
    /// Rest curvature coefficients κ1,κ2,… (one per order) [default: straight].
    #[arg(long, value_parser = numbers, allow_hyphen_values = true)]
    pub kappa: Option<List>,
    /// Order N: the number of curvature coefficients.
    #[arg(long, default_value_t = 3)]
    pub order: usize,
    /// Gauss–Legendre points [default: order + 2].
    #[arg(long)]
    pub quadrature: Option<usize>,
}

impl FlexureOptions {
    /// Builds and validates the flexure.
    pub fn build(&self) -> flexure::Result<Flexure> {
        let ei = match self.modulus {
            Some(e) => {
                bending_stiffness(e, self.width.unwrap_or(f64::NAN), self.thickness.unwrap_or(f64::NAN), self.poisson)?
            }
            None => self.ei.unwrap_or(1.0),
        };
        let mut f = Flexure::new(self.length, ei, self.order)?;
        if let Some(q) = self.quadrature {
            f = f.with_quadrature(q)?;
        }
        if let Some(k) = &self.kappa {
            f = f.with_rest(&k.0)?;
        }
        Ok(f)
    }
}
