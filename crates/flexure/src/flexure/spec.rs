//! A flexure as a front end gives it: its length, [`SectionSpec`], order,
//! quadrature and rest curvature, built and validated in one place for the
//! mechanism file, the CLI and Python alike.

use super::Flexure;
use crate::error::Result;
use crate::section::SectionSpec;

/// A flexure as given: `length` (m), its [`SectionSpec`], `order` $N$,
/// Gauss–Legendre `quadrature` points ($N + 2$ when `None`) and rest
/// curvature coefficients `kappa` $\kappa$ (Eq. 5; straight when `None`).
/// [`FlexureSpec::build`] is the one place a front end's flexure is made.
///
/// # Example
/// ```
/// use flexure::FlexureSpec;
/// use flexure::section::{Profile, SectionSpec};
/// let spec = FlexureSpec {
///     length: 0.015,
///     section: SectionSpec { ei: Some(Profile::Constant(1.4558e-3)), ..Default::default() },
///     kappa: Some(vec![0.5, 0.0, 0.0]),
///     ..Default::default()
/// };
/// let f = spec.build().unwrap();
/// assert_eq!((f.order(), f.quadrature_points(), f.ei()), (3, 5, 1.4558e-3));
/// // An error names the parameter and the value it got.
/// let e = FlexureSpec { order: 65, ..spec }.build().unwrap_err();
/// assert!(matches!(e, flexure::Error::InvalidParameter { name: "order", .. }), "{e}");
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct FlexureSpec {
    /// Length $L$ (m).
    pub length: f64,
    /// The cross-section.
    pub section: SectionSpec,
    /// Order $N$: the number of curvature coefficients.
    pub order: usize,
    /// Gauss–Legendre points; $N + 2$ when `None`.
    pub quadrature: Option<usize>,
    /// Rest curvature coefficients $\kappa$, one per order; straight when `None`.
    pub kappa: Option<Vec<f64>>,
}

impl Default for FlexureSpec {
    /// A straight flexure 1 m long, $EI = 1$ N·m², order 3: the CLI's defaults.
    fn default() -> Self {
        Self { length: 1.0, section: SectionSpec::default(), order: 3, quadrature: None, kappa: None }
    }
}

impl FlexureSpec {
    /// Builds and validates the flexure: the section, then
    /// [`Flexure::new`] with [`SectionSpec::uniform_ei`] (so a uniform
    /// rectangle keeps Eq. 25's path), [`Flexure::with_section`],
    /// [`Flexure::with_quadrature`] and [`Flexure::with_rest`], in that order.
    pub fn build(&self) -> Result<Flexure> {
        let ei = self.section.uniform_ei()?;
        let section = self.section.section()?;
        let mut f = Flexure::new(self.length, ei, self.order)?;
        if let Some(s) = section {
            f = f.with_section(s)?;
        }
        if let Some(q) = self.quadrature {
            f = f.with_quadrature(q)?;
        }
        if let Some(k) = &self.kappa {
            f = f.with_rest(k)?;
        }
        Ok(f)
    }
}
