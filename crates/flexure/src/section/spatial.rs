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

use super::torsion;
use super::{Mass, Profile};
use crate::error::{Error, Result};

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
    mass: Mass,
    /// Rotary inertia per length given directly (kg·m), with a mass per length.
    rotary: Option<[f64; 3]>,
}

/// How the stiffnesses are given.
#[derive(Debug, Clone, PartialEq)]
enum Stiffness {
    /// $GJ$, $EI_y$, $EI_z$ as profiles (N·m²).
    Given { gj: Profile, ei_y: Profile, ei_z: Profile },
    /// A solid rectangle of modulus $E$ and shear modulus $G$ (Pa), `width`
    /// along $z$ and `thickness` along $y$ (m).
    Rectangle { modulus: f64, shear: f64, width: Profile, thickness: Profile },
    /// A solid circle of modulus $E$ and shear modulus $G$ (Pa), `diameter` (m).
    Circle { modulus: f64, shear: f64, diameter: Profile },
}

/// The outline of a section with a shape ([`SpatialSection::outline`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Outline {
    /// A rectangle, `width` along the section's $z$ and `thickness` along its $y$ (m).
    Rectangle {
        /// Along $z$ (m).
        width: f64,
        /// Along $y$ (m).
        thickness: f64,
    },
    /// A circle of this diameter (m).
    Circle {
        /// The diameter (m).
        diameter: f64,
    },
}

/// How the shear modulus $G$ of a section is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shear {
    /// Poisson's ratio $\nu \in (-1, 0.5]$ of an isotropic material: $G = E/(2(1 + \nu))$.
    Poisson(f64),
    /// The shear modulus $G$ itself (Pa).
    Modulus(f64),
}

impl Shear {
    /// $G$ (Pa) for the Young's modulus `modulus`; errors name `poisson` or `shear_modulus`.
    ///
    /// # Example
    /// ```
    /// use flexure::section::Shear;
    /// assert_eq!(Shear::Poisson(0.25).modulus(200e9).unwrap(), 80e9);
    /// assert!(Shear::Poisson(0.6).modulus(200e9).is_err());
    /// assert!(Shear::Modulus(-1.0).modulus(200e9).is_err());
    /// ```
    pub fn modulus(self, modulus: f64) -> Result<f64> {
        match self {
            Shear::Poisson(nu) if nu.is_finite() && nu > -1.0 && nu <= 0.5 => Ok(modulus / (2.0 * (1.0 + nu))),
            Shear::Poisson(nu) => Err(Error::invalid("poisson", nu, "must lie in (-1, 0.5]")),
            Shear::Modulus(g) => crate::error::positive("shear_modulus", g),
        }
    }
}

/// Where over a section its peak von Mises stress sits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StressPoint {
    /// A corner of a rectangle: both bending stresses, no torsional shear.
    Corner,
    /// The middle of a side of length `width` ($y = \pm t/2$, $z = 0$): the
    /// bending stress about $z$ and that side's torsional shear.
    WidthSide,
    /// The middle of a side of length `thickness` ($z = \pm w/2$, $y = 0$):
    /// the bending stress about $y$ and that side's torsional shear.
    ThicknessSide,
    /// The rim of a circle where the resultant bending stress peaks (the
    /// torsional shear is the same all round).
    Rim,
}

/// The peak stresses over one cross-section (Pa, never negative).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SpatialStress {
    /// The largest normal stress of bending about $y$, $E\lvert\Delta\kappa_y\rvert w/2$
    /// (rectangle) or $E\lvert\Delta\kappa_y\rvert d/2$ (circle).
    pub bending_y: f64,
    /// The largest normal stress of bending about $z$, $E\lvert\Delta\kappa_z\rvert t/2$ or $E\lvert\Delta\kappa_z\rvert d/2$.
    pub bending_z: f64,
    /// The largest torsional shear: $k(r)\thinspace G\lvert\Delta\tau\rvert c$ at the middle of a
    /// rectangle's long sides ([`torsion::long_side_shear`]), $G\lvert\Delta\tau\rvert d/2$ on a circle's rim.
    pub shear: f64,
    /// The peak von Mises stress $\sqrt{\sigma^2 + 3\tau^2}$ over the candidate points ([`StressPoint`]).
    pub von_mises: f64,
    /// Where `von_mises` peaks.
    pub at: StressPoint,
}

impl SpatialStress {
    /// `yield_strength` (Pa) over the peak von Mises stress (infinite at no stress).
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, Shear, SpatialSection};
    /// let s = SpatialSection::circle(200e9, 0.3, Profile::Constant(1e-3)).unwrap();
    /// // Bending alone: σ = E κ d/2 = 200e9 · 1 · 5e-4 = 100 MPa.
    /// let stress = s.stress(0.5, [0.0, 1.0, 0.0]).unwrap();
    /// assert!((stress.safety_factor(250e6).unwrap() - 2.5).abs() < 1e-12);
    /// assert!(stress.safety_factor(0.0).is_err());
    /// # let _ = Shear::Poisson(0.3);
    /// ```
    pub fn safety_factor(&self, yield_strength: f64) -> Result<f64> {
        let y = crate::error::positive("yield_strength", yield_strength)?;
        Ok(if self.von_mises > 0.0 { y / self.von_mises } else { f64::INFINITY })
    }
}

impl SpatialSection {
    /// A section of stiffnesses given directly as profiles over $t = s/L$
    /// (N·m²); errors name `gj`, `ei_y` or `ei_z`.
    pub fn given(gj: Profile, ei_y: Profile, ei_z: Profile) -> Result<Self> {
        gj.check("gj")?;
        ei_y.check("ei_y")?;
        ei_z.check("ei_z")?;
        Ok(Self { stiffness: Stiffness::Given { gj, ei_y, ei_z }, mass: Mass::None, rotary: None })
    }

    /// A uniform section of torsional stiffness `gj` and bending
    /// stiffnesses `ei_y`, `ei_z` (N·m²).
    pub fn uniform(gj: f64, ei_y: f64, ei_z: f64) -> Result<Self> {
        Self::given(Profile::Constant(gj), Profile::Constant(ei_y), Profile::Constant(ei_z))
    }

    /// A solid rectangle of Young's modulus `modulus` $E$ (Pa), shear
    /// modulus from `shear`, `width` $w(t)$ along $z$ and `thickness` $h(t)$
    /// along $y$ (m):
    /// $$EI_z = \frac{E w h^3}{12}, \qquad EI_y = \frac{E h w^3}{12}, \qquad
    /// GJ = G\thinspace\beta(r)\thinspace b c^3,$$
    /// with $b = \max(w, h)$, $c = \min(w, h)$, $r = b/c$ and $\beta$ of
    /// Timoshenko and Goodier's series ([`torsion::beta`]). $E$ is the beam's,
    /// not the plate modulus $E/(1 - \nu^2)$ of the planar [`super::Section`]:
    /// a strip that twists and bends both ways is a beam. Errors name
    /// `modulus`, `poisson` or `shear_modulus`, `width` and `thickness`.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, Shear, SpatialSection};
    /// // A steel strip 10 mm × 0.2 mm (r = 50): GJ ≈ G w h³/3 (1 − 0.630/r).
    /// let s = SpatialSection::rectangle(200e9, Shear::Poisson(0.25), Profile::Constant(0.01), Profile::Constant(2e-4))
    ///     .unwrap();
    /// let [gj, ei_y, ei_z] = s.stiffness(0.0);
    /// let thin = 80e9 * 0.01 * 2e-4f64.powi(3) / 3.0 * (1.0 - 0.630_25 / 50.0);
    /// assert!((gj - thin).abs() < 1e-6 * thin);
    /// assert!((ei_z - 200e9 * 0.01 * 2e-4f64.powi(3) / 12.0).abs() < 1e-20);
    /// assert!((ei_y / ei_z - 2500.0).abs() < 1e-9);
    /// ```
    pub fn rectangle(modulus: f64, shear: Shear, width: Profile, thickness: Profile) -> Result<Self> {
        let e = crate::error::positive("modulus", modulus)?;
        let g = shear.modulus(e)?;
        width.check("width")?;
        thickness.check("thickness")?;
        Ok(Self {
            stiffness: Stiffness::Rectangle { modulus: e, shear: g, width, thickness },
            mass: Mass::None,
            rotary: None,
        })
    }

    /// A solid circle of Young's modulus `modulus` $E$ (Pa), Poisson's ratio
    /// `poisson` $\nu$ ($G = E/(2(1 + \nu))$) and `diameter` $d(t)$ (m):
    /// $EI_y = EI_z = E\pi d^4/64$ and $GJ = G\pi d^4/32$. Errors name
    /// `modulus`, `poisson` and `diameter`.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, SpatialSection};
    /// let s = SpatialSection::circle(200e9, 0.25, Profile::Constant(1e-3)).unwrap();
    /// let [gj, ei_y, ei_z] = s.stiffness(0.5);
    /// let i = std::f64::consts::PI * 1e-12 / 64.0;
    /// assert!((ei_y - 200e9 * i).abs() < 1e-15 && ei_y == ei_z);
    /// assert!((gj - 80e9 * 2.0 * i).abs() < 1e-15);
    /// ```
    pub fn circle(modulus: f64, poisson: f64, diameter: Profile) -> Result<Self> {
        let e = crate::error::positive("modulus", modulus)?;
        let g = Shear::Poisson(poisson).modulus(e)?;
        diameter.check("diameter")?;
        Ok(Self { stiffness: Stiffness::Circle { modulus: e, shear: g, diameter }, mass: Mass::None, rotary: None })
    }

    /// $(GJ, EI_y, EI_z)$ (N·m²) at $t = s/L$: the weights of the twist and
    /// the two bending curvatures in the energy.
    pub fn stiffness(&self, t: f64) -> [f64; 3] {
        match &self.stiffness {
            Stiffness::Given { gj, ei_y, ei_z } => [gj.at(t), ei_y.at(t), ei_z.at(t)],
            Stiffness::Rectangle { modulus, shear, width, thickness } => {
                let (w, h) = (width.at(t), thickness.at(t));
                let (b, c) = (w.max(h), w.min(h));
                [
                    shear * torsion::beta(b / c) * b * c * c * c,
                    modulus * h * w * w * w / 12.0,
                    modulus * w * h * h * h / 12.0,
                ]
            }
            Stiffness::Circle { modulus, shear, diameter } => {
                let i = std::f64::consts::PI * diameter.at(t).powi(4) / 64.0;
                [2.0 * shear * i, modulus * i, modulus * i]
            }
        }
    }

    /// The peak stresses over the cross-section at $t = s/L$ under the
    /// curvature change `u` $= u - u^0 = (\Delta\tau, \Delta\kappa_y, \Delta\kappa_z)$ (1/m):
    /// the bending stresses $\sigma_y = E\lvert\Delta\kappa_y\rvert\thinspace w/2$ (largest at
    /// $z = \pm w/2$) and $\sigma_z = E\lvert\Delta\kappa_z\rvert\thinspace h/2$ (at $y = \pm h/2$), the
    /// torsional shears at the middles of the sides ([`torsion`]), and the
    /// von Mises stress $\sqrt{\sigma^2 + 3\tau^2}$ at the candidates where it
    /// can peak:
    ///
    /// - the corners: $\sigma_y + \sigma_z$, no shear;
    /// - the middle of the sides of length $w$: $\sqrt{\sigma_z^2 + 3\tau_w^2}$;
    /// - the middle of the sides of length $h$: $\sqrt{\sigma_y^2 + 3\tau_h^2}$.
    ///
    /// Points between them are not searched: along a side the shear falls
    /// from its middle to zero at the corner as the other bending stress
    /// grows, and the engineering rule (Roark, §10.3) takes the larger of
    /// the two ends; [`SpatialStress::at`] says which governs. A circle's
    /// peak is on the rim where the resultant bending stress
    /// $E\sqrt{\Delta\kappa_y^2 + \Delta\kappa_z^2}\thinspace d/2$ peaks, with the
    /// shear $G\lvert\Delta\tau\rvert d/2$ that is the same all round.
    ///
    /// Errors: a section given by its stiffnesses alone has no geometry
    /// (`section`), and a non-finite `u` or `t` outside $[0, 1]$ names it.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, Shear, SpatialSection, StressPoint};
    /// let s = SpatialSection::rectangle(200e9, Shear::Poisson(0.25), Profile::Constant(0.01), Profile::Constant(1e-3))
    ///     .unwrap();
    /// // Bending both ways: the corner carries σ_y + σ_z.
    /// let b = s.stress(0.0, [0.0, 0.01, 0.1]).unwrap();
    /// assert!((b.von_mises - (200e9 * 0.01 * 5e-3 + 200e9 * 0.1 * 5e-4)).abs() < 1e-3);
    /// assert_eq!(b.at, StressPoint::Corner);
    /// // Twist alone: the thin strip's shear Gθc at the middle of its wide faces.
    /// let t = s.stress(0.0, [0.1, 0.0, 0.0]).unwrap();
    /// assert_eq!(t.at, StressPoint::WidthSide);
    /// assert!((t.shear - 80e9 * 0.1 * 1e-3).abs() < 1e-6 * t.shear);
    /// ```
    pub fn stress(&self, t: f64, u: [f64; 3]) -> Result<SpatialStress> {
        if !(0.0..=1.0).contains(&t) {
            return Err(Error::invalid("t", t, "must lie in [0, 1] (s/L)"));
        }
        for (name, v) in ["twist", "kappa_y", "kappa_z"].into_iter().zip(u) {
            crate::error::finite(name, v)?;
        }
        let [twist, ky, kz] = u.map(f64::abs);
        match &self.stiffness {
            Stiffness::Given { .. } => Err(Error::invalid(
                "section",
                "stiffnesses given directly",
                "has no geometry for stress: give a rectangle or a circle",
            )),
            Stiffness::Rectangle { modulus, shear, width, thickness } => {
                let (w, h) = (width.at(t), thickness.at(t));
                let (sy, sz) = (modulus * ky * w / 2.0, modulus * kz * h / 2.0);
                let (c, r) = (w.min(h), w.max(h) / w.min(h));
                let (long, short) =
                    (shear * twist * c * torsion::long_side_shear(r), shear * twist * c * torsion::short_side_shear(r));
                // The sides of length w are the long ones when w ≥ h.
                let (tau_w, tau_h) = if w >= h { (long, short) } else { (short, long) };
                let candidates = [
                    (sy + sz, StressPoint::Corner),
                    ((sz * sz + 3.0 * tau_w * tau_w).sqrt(), StressPoint::WidthSide),
                    ((sy * sy + 3.0 * tau_h * tau_h).sqrt(), StressPoint::ThicknessSide),
                ];
                let (von_mises, at) = candidates
                    .into_iter()
                    .fold((0.0, StressPoint::Corner), |best, c| if c.0 > best.0 { c } else { best });
                Ok(SpatialStress { bending_y: sy, bending_z: sz, shear: long, von_mises, at })
            }
            Stiffness::Circle { modulus, shear, diameter } => {
                let d = diameter.at(t);
                let (sy, sz, tau) = (modulus * ky * d / 2.0, modulus * kz * d / 2.0, shear * twist * d / 2.0);
                let sigma = sy.hypot(sz);
                let von_mises = (sigma * sigma + 3.0 * tau * tau).sqrt();
                Ok(SpatialStress { bending_y: sy, bending_z: sz, shear: tau, von_mises, at: StressPoint::Rim })
            }
        }
    }

    /// The same section with mass from `density` $\rho$ (kg/m³):
    /// $\mu = \rho A$ and rotary inertia $\rho\thinspace\mathrm{diag}(I_y + I_z, I_y, I_z)$
    /// per length ([`SpatialSection::rotary_inertia_per_length`]). Fails,
    /// naming `density`, for a section given by its stiffnesses alone (it
    /// has no area) or a density that is not positive and finite.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, SpatialSection};
    /// let s = SpatialSection::circle(200e9, 0.3, Profile::Constant(2e-3)).unwrap().with_density(7850.0).unwrap();
    /// let area = std::f64::consts::PI * 1e-6;
    /// assert!((s.mass_per_length(0.5).unwrap() - 7850.0 * area).abs() < 1e-15);
    /// assert!(SpatialSection::uniform(1.0, 1.0, 1.0).unwrap().with_density(7850.0).is_err());
    /// ```
    pub fn with_density(mut self, density: f64) -> Result<Self> {
        crate::error::positive("density", density)?;
        if !self.has_geometry() {
            return Err(Error::invalid(
                "density",
                density,
                "needs a rectangle's width and thickness or a circle's diameter; give mass_per_length with gj, ei_y, ei_z",
            ));
        }
        self.mass = Mass::Density(density);
        self.rotary = None;
        Ok(self)
    }

    /// The same section with mass per length $\mu(t)$ (kg/m) given
    /// directly; errors name `mass_per_length`. Its rotary inertia is
    /// $\mu/A$ times the geometry's second moments when the section has a
    /// geometry, and zero when it is given by its stiffnesses alone.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, SpatialSection};
    /// let s = SpatialSection::uniform(1.0, 1.0, 1.0).unwrap().with_mass_per_length(Profile::Constant(0.2)).unwrap();
    /// assert_eq!((s.mass_per_length(0.3), s.rotary_inertia_per_length(0.3)), (Some(0.2), Some([0.0; 3])));
    /// assert!(SpatialSection::uniform(1.0, 1.0, 1.0).unwrap().with_mass_per_length(Profile::Constant(-1.0)).is_err());
    /// ```
    pub fn with_mass_per_length(mut self, mass_per_length: Profile) -> Result<Self> {
        mass_per_length.check("mass_per_length")?;
        self.mass = Mass::PerLength(mass_per_length);
        Ok(self)
    }

    /// The same section with its rotary inertia per length given directly,
    /// $(\rho J_x, \rho J_y, \rho J_z)$ (kg·m) about the section's axes
    /// $(x, y, z)$, the polar moment about the axis first, in place of
    /// $\mu/A$ times the geometry's second moments (or zero without a
    /// geometry). It needs a mass per length
    /// ([`SpatialSection::with_mass_per_length`], given first): a density
    /// takes its rotary inertia from the section. Each must be finite and not
    /// negative, and, as the moments of a section's mass, they must meet the
    /// triangle inequality $\rho J_x \le \rho J_y + \rho J_z$ (and its turns)
    /// within $10^{-12}$ of their sum; errors name `rotary_inertia_per_length`.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, SpatialSection};
    /// let s = SpatialSection::uniform(1e3, 1e3, 1e3).unwrap().with_mass_per_length(Profile::Constant(1.0)).unwrap();
    /// let s = s.with_rotary_inertia_per_length([20.0, 10.0, 10.0]).unwrap();
    /// assert_eq!(s.rotary_inertia_per_length(0.4), Some([20.0, 10.0, 10.0]));
    /// assert!(s.clone().with_rotary_inertia_per_length([30.0, 10.0, 10.0]).is_err());
    /// assert!(SpatialSection::uniform(1.0, 1.0, 1.0).unwrap().with_rotary_inertia_per_length([2.0, 1.0, 1.0]).is_err());
    /// ```
    pub fn with_rotary_inertia_per_length(mut self, rotary: [f64; 3]) -> Result<Self> {
        let name = "rotary_inertia_per_length";
        let shown = |r: [f64; 3]| format!("[{}]", r.iter().map(|v| format!("{v}")).collect::<Vec<_>>().join(", "));
        if !matches!(self.mass, Mass::PerLength(_)) {
            return Err(Error::invalid(
                name,
                shown(rotary),
                "needs mass_per_length (a density takes it from the section)",
            ));
        }
        if rotary.iter().any(|v| !v.is_finite() || *v < 0.0) {
            return Err(Error::invalid(name, shown(rotary), "each must be finite and not negative"));
        }
        let sum: f64 = rotary.iter().sum();
        if (0..3).any(|i| rotary[i] > sum - rotary[i] + 1e-12 * sum) {
            return Err(Error::invalid(
                name,
                shown(rotary),
                "must meet the triangle inequality, as a section's moments do (the polar one is the sum of the other two)",
            ));
        }
        self.rotary = Some(rotary);
        Ok(self)
    }

    /// Whether it has mass (a density or a mass per length).
    pub fn has_mass(&self) -> bool {
        !matches!(self.mass, Mass::None)
    }

    /// The area $A$ (m²) at $t = s/L$: $wh$ for a rectangle, $\pi d^2/4$ for
    /// a circle; `None` for stiffnesses given directly.
    pub fn area(&self, t: f64) -> Option<f64> {
        match &self.stiffness {
            Stiffness::Given { .. } => None,
            Stiffness::Rectangle { width, thickness, .. } => Some(width.at(t) * thickness.at(t)),
            Stiffness::Circle { diameter, .. } => Some(std::f64::consts::PI * diameter.at(t).powi(2) / 4.0),
        }
    }

    /// The area's second moments $(I_y, I_z)$ (m⁴) at $t$ about the
    /// section's axes: $(hw^3/12,\ wh^3/12)$ for a rectangle of width $w$
    /// along $z$ and thickness $h$ along $y$, $\pi d^4/64$ both for a
    /// circle; `None` for stiffnesses given directly.
    pub fn second_moments(&self, t: f64) -> Option<[f64; 2]> {
        match &self.stiffness {
            Stiffness::Given { .. } => None,
            Stiffness::Rectangle { width, thickness, .. } => {
                let (w, h) = (width.at(t), thickness.at(t));
                Some([h * w * w * w / 12.0, w * h * h * h / 12.0])
            }
            Stiffness::Circle { diameter, .. } => {
                let i = std::f64::consts::PI * diameter.at(t).powi(4) / 64.0;
                Some([i, i])
            }
        }
    }

    /// The mass per length $\mu$ (kg/m) at $t = s/L$: $\rho A$ or the one
    /// given; `None` without mass.
    pub fn mass_per_length(&self, t: f64) -> Option<f64> {
        match &self.mass {
            Mass::None => None,
            Mass::Density(rho) => self.area(t).map(|a| rho * a),
            Mass::PerLength(p) => Some(p.at(t)),
        }
    }

    /// The rotary inertia per length (kg·m) at $t$, in the section frame
    /// $(x, y, z)$: $\rho\thinspace(I_y + I_z, I_y, I_z)$, the polar moment
    /// about the axis first, with $\rho = \mu/A$ when the mass per length is
    /// given. Zero for a mass per length on stiffnesses given directly (no
    /// geometry: a string of point masses), unless given directly
    /// ([`SpatialSection::with_rotary_inertia_per_length`]); `None` without mass.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, Shear, SpatialSection};
    /// let s = SpatialSection::rectangle(1e9, Shear::Poisson(0.3), Profile::Constant(0.02), Profile::Constant(0.01))
    ///     .unwrap()
    ///     .with_density(1000.0)
    ///     .unwrap();
    /// let [p, iy, iz] = s.rotary_inertia_per_length(0.0).unwrap();
    /// // ρ h w³/12 about y (w = 0.02 along z), ρ w h³/12 about z.
    /// assert!((iy - 1000.0 * 0.01 * 8e-6 / 12.0).abs() < 1e-15 && (iz - 1000.0 * 0.02 * 1e-6 / 12.0).abs() < 1e-15);
    /// assert!((p - iy - iz).abs() < 1e-18);
    /// ```
    pub fn rotary_inertia_per_length(&self, t: f64) -> Option<[f64; 3]> {
        let mu = self.mass_per_length(t)?;
        if let Some(rotary) = self.rotary {
            return Some(rotary);
        }
        Some(match (self.area(t), self.second_moments(t)) {
            (Some(a), Some([iy, iz])) => {
                let rho = mu / a;
                [rho * (iy + iz), rho * iy, rho * iz]
            }
            _ => [0.0; 3],
        })
    }

    /// The section's outline at $t = s/L$ (m): its width along $z$ and
    /// thickness along $y$, or its diameter; `None` for stiffnesses given
    /// directly, which have no geometry.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Outline, Profile, Shear, SpatialSection};
    /// let s = SpatialSection::rectangle(1e9, Shear::Poisson(0.3), Profile::Constant(0.02), Profile::Constant(0.01)).unwrap();
    /// assert_eq!(s.outline(0.5), Some(Outline::Rectangle { width: 0.02, thickness: 0.01 }));
    /// assert_eq!(SpatialSection::uniform(1.0, 1.0, 1.0).unwrap().outline(0.5), None);
    /// ```
    pub fn outline(&self, t: f64) -> Option<Outline> {
        match &self.stiffness {
            Stiffness::Given { .. } => None,
            Stiffness::Rectangle { width, thickness, .. } => {
                Some(Outline::Rectangle { width: width.at(t), thickness: thickness.at(t) })
            }
            Stiffness::Circle { diameter, .. } => Some(Outline::Circle { diameter: diameter.at(t) }),
        }
    }

    /// Whether it has a shape and material (a rectangle or a circle), and
    /// so stresses; stiffnesses given directly have none.
    pub fn has_geometry(&self) -> bool {
        !matches!(self.stiffness, Stiffness::Given { .. })
    }

    /// Whether all three are the same all along (the Gram matrices are then diagonal).
    pub fn is_uniform(&self) -> bool {
        let constant = |p: &Profile| matches!(p, Profile::Constant(_));
        match &self.stiffness {
            Stiffness::Given { gj, ei_y, ei_z } => [gj, ei_y, ei_z].into_iter().all(constant),
            Stiffness::Rectangle { width, thickness, .. } => constant(width) && constant(thickness),
            Stiffness::Circle { diameter, .. } => constant(diameter),
        }
    }

    /// The $t$ in $(0, 1)$ where a stiffness stops being smooth (table
    /// points), increasing; integrals split there.
    pub fn breakpoints(&self) -> Vec<f64> {
        let mut out: Vec<f64> = Vec::new();
        let profiles: Vec<&Profile> = match &self.stiffness {
            Stiffness::Given { gj, ei_y, ei_z } => vec![gj, ei_y, ei_z],
            Stiffness::Rectangle { width, thickness, .. } => vec![width, thickness],
            Stiffness::Circle { diameter, .. } => vec![diameter],
        };
        for p in profiles {
            out.extend(p.kinks().iter().map(|k| k[0]));
        }
        out.retain(|t| *t > 0.0 && *t < 1.0);
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
    }
}
