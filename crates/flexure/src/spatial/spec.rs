//! A spatial flexure as a front end gives it, built in one place (as
//! [`crate::flexure::FlexureSpec`] is for the planar flexure): the CLI's
//! `--spatial` options and Python's `SpatialFlexure` fill it.

use super::SpatialFlexure;
use crate::error::{Error, Result};
use crate::section::{Profile, Shear, SpatialSection};

/// Poisson's ratio taken when a rectangle's or circle's shear modulus is not given.
pub const DEFAULT_POISSON: f64 = 0.3;

/// A spatial flexure's length, section, orders and rest shape, as given.
///
/// The section is `gj`, `ei_y` and `ei_z` given directly (N·m²; `ei_z` is
/// the planar `ei`), or a material `modulus` with a rectangle's `width`
/// and `thickness` or a circle's `diameter`, and `poisson` (default
/// [`DEFAULT_POISSON`]) or `shear_modulus` for $G$.
///
/// # Example
/// ```
/// use flexure::section::Profile;
/// use flexure::spatial::SpatialSpec;
/// let spec = SpatialSpec { ei_z: Some(Profile::Constant(2.0)), kappa_z: Some(vec![0.5, 0.0, 0.0]), ..Default::default() };
/// let f = spec.build().unwrap();
/// assert_eq!((f.orders(), f.section().stiffness(0.0)), ([3, 3, 3], [2.0, 2.0, 2.0]));
/// assert_eq!(f.rest()[6], 0.5);
/// let bad = SpatialSpec { gj: Some(Profile::Constant(-1.0)), ..Default::default() };
/// assert!(bad.build().unwrap_err().to_string().contains("gj"));
/// // A diameter without a modulus is refused, not ignored.
/// let bad = SpatialSpec { diameter: Some(Profile::Constant(1e-3)), ..Default::default() };
/// assert!(bad.build().unwrap_err().to_string().starts_with("invalid diameter = given: goes with modulus"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialSpec {
    /// Length $L$ (m).
    pub length: f64,
    /// $GJ$ (N·m²) [default: `ei_z`].
    pub gj: Option<Profile>,
    /// $EI_y$ (N·m²) [default: `ei_z`].
    pub ei_y: Option<Profile>,
    /// $EI_z$ (N·m²) [default: 1].
    pub ei_z: Option<Profile>,
    /// Young's modulus $E$ (Pa), with a width and thickness or a diameter.
    pub modulus: Option<f64>,
    /// A rectangle's width along $z$ (m).
    pub width: Option<Profile>,
    /// A rectangle's thickness along $y$ (m).
    pub thickness: Option<Profile>,
    /// A circle's diameter (m).
    pub diameter: Option<Profile>,
    /// Poisson's ratio, for $G$.
    pub poisson: Option<f64>,
    /// The shear modulus $G$ (Pa), in place of `poisson`.
    pub shear_modulus: Option<f64>,
    /// Orders $[n_\tau, n_y, n_z]$.
    pub orders: [usize; 3],
    /// Rest coefficients of the twist [default: none].
    pub twist: Option<Vec<f64>>,
    /// Rest coefficients of the bending about $y$.
    pub kappa_y: Option<Vec<f64>>,
    /// Rest coefficients of the bending about $z$ (the planar `kappa`).
    pub kappa_z: Option<Vec<f64>>,
}

impl Default for SpatialSpec {
    fn default() -> Self {
        Self {
            length: 1.0,
            gj: None,
            ei_y: None,
            ei_z: None,
            modulus: None,
            width: None,
            thickness: None,
            diameter: None,
            poisson: None,
            shear_modulus: None,
            orders: [3; 3],
            twist: None,
            kappa_y: None,
            kappa_z: None,
        }
    }
}

impl SpatialSpec {
    /// The section the spec describes; errors name the field.
    pub fn section(&self) -> Result<SpatialSection> {
        if self.modulus.is_none() {
            // As the planar SectionSpec: a shape or material without a modulus
            // is refused, not ignored.
            let shape = [
                ("width", self.width.is_some()),
                ("thickness", self.thickness.is_some()),
                ("diameter", self.diameter.is_some()),
                ("poisson", self.poisson.is_some()),
                ("shear_modulus", self.shear_modulus.is_some()),
            ];
            if let Some((name, _)) = shape.into_iter().find(|(_, given)| *given) {
                return Err(Error::invalid(
                    name,
                    "given",
                    "goes with modulus (and width and thickness, or diameter), not with the stiffnesses gj, ei_y, ei_z",
                ));
            }
        }
        let Some(e) = self.modulus else {
            let ei_z = self.ei_z.clone().unwrap_or(Profile::Constant(1.0));
            let gj = self.gj.clone().unwrap_or_else(|| ei_z.clone());
            let ei_y = self.ei_y.clone().unwrap_or_else(|| ei_z.clone());
            return SpatialSection::given(gj, ei_y, ei_z);
        };
        for (name, given) in [("gj", self.gj.is_some()), ("ei_y", self.ei_y.is_some()), ("ei_z", self.ei_z.is_some())] {
            if given {
                return Err(Error::invalid(
                    name,
                    "given with modulus",
                    "give the stiffnesses or the material and shape, not both",
                ));
            }
        }
        let shear = match (self.shear_modulus, self.poisson) {
            (Some(_), Some(nu)) => {
                return Err(Error::invalid("poisson", nu, "give poisson or shear_modulus, not both"));
            }
            (Some(g), None) => Shear::Modulus(g),
            (None, nu) => Shear::Poisson(nu.unwrap_or(DEFAULT_POISSON)),
        };
        match (&self.width, &self.thickness, &self.diameter) {
            (Some(w), Some(t), None) => SpatialSection::rectangle(e, shear, w.clone(), t.clone()),
            (None, None, Some(d)) => {
                let nu = match shear {
                    Shear::Poisson(nu) => nu,
                    // ν = E/2G − 1: the circle is built from E and ν.
                    Shear::Modulus(g) => e / (2.0 * crate::error::positive("shear_modulus", g)?) - 1.0,
                };
                SpatialSection::circle(e, nu, d.clone())
            }
            _ => Err(Error::invalid(
                "modulus",
                e,
                "needs a rectangle's width and thickness, or a circle's diameter (one of the two)",
            )),
        }
    }

    /// Builds and validates the flexure.
    pub fn build(&self) -> Result<SpatialFlexure> {
        let f = SpatialFlexure::new(self.length, self.section()?, self.orders)?;
        let (n, mut rest) = (f.coordinates(), Vec::with_capacity(f.coordinates()));
        for ((name, given), order) in [("twist", &self.twist), ("kappa_y", &self.kappa_y), ("kappa_z", &self.kappa_z)]
            .into_iter()
            .zip(self.orders)
        {
            match given {
                Some(k) if k.len() != order => {
                    return Err(Error::invalid(
                        name,
                        format!("{} values", k.len()),
                        "must have one rest coefficient per order of its component",
                    ));
                }
                Some(k) => rest.extend_from_slice(k),
                None => rest.resize(rest.len() + order, 0.0),
            }
        }
        debug_assert_eq!(rest.len(), n);
        f.with_rest(&rest)
    }
}
