//! A cross-section as a front end gives it: plain data, each parameter as
//! given, built and validated in one place for the mechanism file, the CLI
//! and Python alike.

use super::bending_stiffness;
use super::{Notch, Profile, Section};
use crate::error::{Error, Result};

/// A flexure's cross-section as given: either `ei` (a [`Profile`] of
/// $EI$, N·m²) or a rectangle of `modulus` $E$ (Pa), `width` $b$ and
/// `thickness` $h$ (m), with an optional `poisson` $\nu$ (the plate modulus
/// $E/(1-\nu^2)$, Eq. 25) and circular `notch`; mass from `density` (kg/m³,
/// with a rectangle) or `mass_per_length` (kg/m). Neither `ei` nor
/// `modulus` means $EI = 1$ N·m². Built by [`SectionSpec::section`].
///
/// # Example
/// ```
/// use flexure::section::{Profile, SectionSpec};
/// let strip = SectionSpec {
///     modulus: Some(200e9),
///     width: Some(Profile::Constant(0.01)),
///     thickness: Some(Profile::Linear { root: 4e-4, tip: 2e-4 }),
///     ..Default::default()
/// };
/// let s = strip.section().unwrap().unwrap();
/// assert!((s.ei(1.0, 0.02) - 200e9 * 0.01 * 2e-4f64.powi(3) / 12.0).abs() < 1e-15);
/// // A uniform EI without mass needs no section.
/// assert_eq!(SectionSpec { ei: Some(Profile::Constant(2.0)), ..Default::default() }.section().unwrap(), None);
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SectionSpec {
    /// Bending stiffness $EI(t)$ (N·m²), in place of a rectangle.
    pub ei: Option<Profile>,
    /// Young's modulus $E$ (Pa) of a rectangle of `width` and `thickness`.
    pub modulus: Option<f64>,
    /// Width $b(t)$ (m), with `modulus`.
    pub width: Option<Profile>,
    /// Thickness $h(t)$ (m), with `modulus`.
    pub thickness: Option<Profile>,
    /// Poisson ratio $\nu$, with `modulus`: the plate modulus $E/(1-\nu^2)$.
    pub poisson: Option<f64>,
    /// A circular notch cut into the rectangle.
    pub notch: Option<Notch>,
    /// Density $\rho$ (kg/m³), with `modulus`: $\mu = \rho\thinspace b h$.
    pub density: Option<f64>,
    /// Mass per length $\mu(t)$ (kg/m).
    pub mass_per_length: Option<Profile>,
}

impl SectionSpec {
    /// Refuses parameters that do not go together, naming the second one.
    fn consistent(&self) -> Result<()> {
        if let (Some(_), Some(e)) = (&self.ei, self.modulus) {
            return Err(Error::invalid("modulus", e, "give ei, or modulus with width and thickness, not both"));
        }
        if self.modulus.is_none() {
            let rectangle = [
                ("width", self.width.is_some()),
                ("thickness", self.thickness.is_some()),
                ("poisson", self.poisson.is_some()),
                ("notch", self.notch.is_some()),
            ];
            if let Some((name, _)) = rectangle.into_iter().find(|(_, given)| *given) {
                return Err(Error::invalid(name, "given", "goes with modulus (and width and thickness), not with ei"));
            }
        }
        if let (Some(rho), Some(_)) = (self.density, &self.mass_per_length) {
            return Err(Error::invalid(
                "mass_per_length",
                format!("with density {rho}"),
                "give density or mass_per_length, not both",
            ));
        }
        Ok(())
    }

    /// The rectangle's width and thickness, each required with a modulus.
    fn rectangle(&self) -> Result<(&Profile, &Profile)> {
        let missing = |name| Error::invalid(name, "missing", "modulus needs width and thickness");
        Ok((
            self.width.as_ref().ok_or_else(|| missing("width"))?,
            self.thickness.as_ref().ok_or_else(|| missing("thickness"))?,
        ))
    }

    /// The uniform $EI$ (N·m²) a flexure is first built with: a constant
    /// `ei`; Eq. 25's product for a uniform rectangle, held to
    /// [`super::EI_RANGE`] and named `ei` when outside; otherwise 1,
    /// which the [`SectionSpec::section`] replaces.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, SectionSpec};
    /// let c = Profile::Constant;
    /// let steel = SectionSpec { modulus: Some(200e9), width: Some(c(0.01)), thickness: Some(c(2e-4)), poisson: Some(0.29), ..Default::default() };
    /// assert_eq!(steel.uniform_ei().unwrap(), flexure::bending_stiffness(200e9, 0.01, 2e-4, Some(0.29)).unwrap());
    /// assert_eq!(SectionSpec::default().uniform_ei().unwrap(), 1.0);
    /// ```
    pub fn uniform_ei(&self) -> Result<f64> {
        self.consistent()?;
        match (self.modulus, &self.ei) {
            (Some(e), _) => match self.rectangle()? {
                (Profile::Constant(b), Profile::Constant(h)) => bending_stiffness(e, *b, *h, self.poisson),
                _ => Ok(1.0),
            },
            (None, Some(Profile::Constant(ei))) => Ok(*ei),
            (None, _) => Ok(1.0),
        }
    }

    /// The [`Section`], or `None` for a uniform `ei` (or none) without
    /// mass, which needs none. Errors name the parameter and its value.
    pub fn section(&self) -> Result<Option<Section>> {
        self.consistent()?;
        let mut section = match (self.modulus, &self.ei) {
            (Some(e), _) => {
                let (w, h) = self.rectangle()?;
                let s = Section::rectangle(e, self.poisson, w.clone(), h.clone())?;
                match self.notch {
                    Some(n) => s.with_notch(n)?,
                    None => s,
                }
            }
            (None, Some(p)) if !matches!(p, Profile::Constant(_)) => Section::given(p.clone())?,
            (None, ei) if self.density.is_some() || self.mass_per_length.is_some() => {
                Section::given(ei.clone().unwrap_or(Profile::Constant(1.0)))?
            }
            _ => return Ok(None),
        };
        if let Some(rho) = self.density {
            section = section.with_density(rho)?;
        }
        if let Some(mu) = &self.mass_per_length {
            section = section.with_mass_per_length(mu.clone())?;
        }
        Ok(Some(section))
    }
}
