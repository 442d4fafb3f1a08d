//! A spatial flexure's cross-sections: torsional stiffness $GJ(s)$ and the
//! bending stiffnesses $EI_y(s)$ and $EI_z(s)$ about the section's axes.
//!
//! Frames as for the planar flexure: $x$ along the rest tangent, $y$ the
//! in-plane normal, $z$ out of the plane. The body-frame curvature is
//! $u = (\tau, \kappa_y, \kappa_z)$, twist about $x$ then bending about $y$
//! and $z$, and the energy is
//! $$U = \tfrac12\int_0^L \big(GJ\thinspace\tau^2 + EI_y\thinspace\kappa_y^2 + EI_z\thinspace\kappa_z^2\big)\thinspace ds$$
//! about the rest shape, so [`SpatialSection::stiffness`] lists the three in
//! that order. $EI_z$ is the planar model's $EI$: in-plane bending.

use super::Profile;
use crate::error::Result;

/// The three stiffnesses of a spatial flexure's section along its length.
///
/// # Example
/// ```
/// use flexure::section::SpatialSection;
/// let s = SpatialSection::uniform(0.5, 4.0, 1.0).unwrap();
/// assert_eq!(s.stiffness(0.3), [0.5, 4.0, 1.0]);
/// assert!(s.is_uniform());
/// assert!(SpatialSection::uniform(0.0, 4.0, 1.0).is_err());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialSection {
    stiffness: Stiffness,
}

/// How the stiffnesses are given.
#[derive(Debug, Clone, PartialEq)]
enum Stiffness {
    /// $GJ$, $EI_y$, $EI_z$ as profiles (N·m²).
    Given { gj: Profile, ei_y: Profile, ei_z: Profile },
}

impl SpatialSection {
    /// A section of stiffnesses given directly as profiles over $t = s/L$
    /// (N·m²); errors name `gj`, `ei_y` or `ei_z`.
    pub fn given(gj: Profile, ei_y: Profile, ei_z: Profile) -> Result<Self> {
        gj.check("gj")?;
        ei_y.check("ei_y")?;
        ei_z.check("ei_z")?;
        Ok(Self { stiffness: Stiffness::Given { gj, ei_y, ei_z } })
    }

    /// A uniform section of torsional stiffness `gj` and bending
    /// stiffnesses `ei_y`, `ei_z` (N·m²).
    pub fn uniform(gj: f64, ei_y: f64, ei_z: f64) -> Result<Self> {
        Self::given(Profile::Constant(gj), Profile::Constant(ei_y), Profile::Constant(ei_z))
    }

    /// $(GJ, EI_y, EI_z)$ (N·m²) at $t = s/L$: the weights of the twist and
    /// the two bending curvatures in the energy.
    pub fn stiffness(&self, t: f64) -> [f64; 3] {
        match &self.stiffness {
            Stiffness::Given { gj, ei_y, ei_z } => [gj.at(t), ei_y.at(t), ei_z.at(t)],
        }
    }

    /// Whether all three are the same all along (the Gram matrices are then diagonal).
    pub fn is_uniform(&self) -> bool {
        match &self.stiffness {
            Stiffness::Given { gj, ei_y, ei_z } => [gj, ei_y, ei_z].iter().all(|p| matches!(p, Profile::Constant(_))),
        }
    }

    /// The $t$ in $(0, 1)$ where a stiffness stops being smooth (table
    /// points), increasing; integrals split there.
    pub fn breakpoints(&self) -> Vec<f64> {
        let mut out: Vec<f64> = Vec::new();
        match &self.stiffness {
            Stiffness::Given { gj, ei_y, ei_z } => {
                for p in [gj, ei_y, ei_z] {
                    out.extend(p.kinks().iter().map(|k| k[0]));
                }
            }
        }
        out.retain(|t| *t > 0.0 && *t < 1.0);
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
    }
}
