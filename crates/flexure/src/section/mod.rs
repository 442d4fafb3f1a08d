//! Cross-sections along a flexure: bending stiffness $EI(s)$, thickness
//! $h(s)$ for stress, and mass per length $\mu(s)$.
//!
//! Every quantity is a [`Profile`] over $t = s/L \in [0, 1]$: a constant, a
//! linear taper from root to tip, or a table linear between its points. A
//! circular [`Notch`] cuts the thickness of a rectangular section.
//! [`SectionSpec`] is a section as a front end gives it, built in one place.

use crate::error::{Error, Result, positive};

mod plausible;
mod spatial;
mod spec;
pub mod torsion;
pub use plausible::{Hint, LEAST_MODULUS, MM_SECTION, QUESTIONED_LENGTH, thinner_than_long, unit_hints};
pub use spatial::{Outline, Shear, SpatialSection, SpatialStress, StressPoint};
pub use spec::SectionSpec;

/// Bending stiffnesses a flexure may have (N·m²): from a nanowire's to a bridge girder's and beyond.
pub const EI_RANGE: (f64, f64) = (1e-30, 1e15);

pub(crate) fn within(name: &'static str, v: f64, (lo, hi): (f64, f64)) -> Result<f64> {
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(Error::invalid(
            name,
            v,
            if name == "length" { "must lie in [1e-9, 1e6] m" } else { "must lie in [1e-30, 1e15] N·m²" },
        ))
    }
}

/// Bending stiffness $EI = \frac{E}{1-\nu^2}\thinspace\frac{b h^3}{12}$ of a
/// rectangular section (Eq. 25); without `poisson`, $EI = E b h^3 / 12$.
///
/// The $1/(1-\nu^2)$ factor is the plate (wide flexure) modulus.
///
/// # Example
/// ```
/// // The paper's steel flexure, Eq. 25 (errata: 1.4558e-3 N·m²).
/// let ei = flexure::bending_stiffness(200e9, 0.01, 0.0002, Some(0.29)).unwrap();
/// assert!((ei - 1.4558e-3).abs() < 1e-7);
/// ```
pub fn bending_stiffness(modulus: f64, width: f64, thickness: f64, poisson: Option<f64>) -> Result<f64> {
    let e = positive("modulus", modulus)?;
    let b = positive("width", width)?;
    let h = positive("thickness", thickness)?;
    let plate = match poisson {
        None => 1.0,
        Some(nu) => {
            if !(nu.is_finite() && nu > -1.0 && nu <= 0.5) {
                return Err(Error::invalid("poisson", nu, "must lie in (-1, 0.5]"));
            }
            1.0 / (1.0 - nu * nu)
        }
    };
    within("ei", e * plate * b * h.powi(3) / 12.0, EI_RANGE)
}

/// A positive quantity along the flexure, a function of $t = s/L$.
#[derive(Debug, Clone, PartialEq)]
pub enum Profile {
    /// The same value everywhere.
    Constant(f64),
    /// $v(t) = (1-t)\thinspace v_{root} + t\thinspace v_{tip}$.
    Linear {
        /// Value at the root, $t = 0$.
        root: f64,
        /// Value at the tip, $t = 1$.
        tip: f64,
    },
    /// Points $(t_k, v_k)$ with $t_0 = 0 < t_1 < \dots < t_m = 1$, linear between them.
    Table(Vec<[f64; 2]>),
}

impl Profile {
    /// Checks that every value is finite and positive and, for a table, that
    /// $t$ starts at 0, ends at 1 and increases strictly; errors name `name`.
    ///
    /// # Example
    /// ```
    /// use flexure::section::Profile;
    /// assert!(Profile::Table(vec![[0.0, 1.0], [1.0, 2.0]]).check("width").is_ok());
    /// assert!(Profile::Table(vec![[0.0, 1.0], [0.9, 2.0]]).check("width").is_err());
    /// assert!(Profile::Linear { root: 1.0, tip: 0.0 }.check("width").is_err());
    /// ```
    pub fn check(&self, name: &'static str) -> Result<()> {
        let value = |v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(Error::invalid(name, v, "must be a finite number greater than zero everywhere along the flexure"))
            }
        };
        match self {
            Profile::Constant(v) => value(*v),
            Profile::Linear { root, tip } => value(*root).and(value(*tip)),
            Profile::Table(points) => {
                let shown = || format!("{points:?}");
                if points.len() < 2 {
                    return Err(Error::invalid(name, shown(), "a table needs at least two points [t, value]"));
                }
                let ts: Vec<f64> = points.iter().map(|p| p[0]).collect();
                if ts[0] != 0.0 || ts[ts.len() - 1] != 1.0 || ts.windows(2).any(|w| w[1].is_nan() || w[1] <= w[0]) {
                    return Err(Error::invalid(
                        name,
                        shown(),
                        "a table's t = s/L must start at 0, end at 1 and increase strictly",
                    ));
                }
                points.iter().try_for_each(|p| value(p[1]))
            }
        }
    }

    /// The value at $t$.
    ///
    /// # Example
    /// ```
    /// use flexure::section::Profile;
    /// let p = Profile::Table(vec![[0.0, 1.0], [0.5, 3.0], [1.0, 2.0]]);
    /// assert_eq!(p.at(0.25), 2.0);
    /// assert_eq!(Profile::Linear { root: 2.0, tip: 1.0 }.at(0.5), 1.5);
    /// ```
    pub fn at(&self, t: f64) -> f64 {
        match self {
            Profile::Constant(v) => *v,
            // Weighted, not root + t·(tip − root): exact at both ends
            // however different the two values are.
            Profile::Linear { root, tip } => (1.0 - t) * root + t * tip,
            Profile::Table(points) => {
                let k = points.partition_point(|p| p[0] <= t).clamp(1, points.len() - 1);
                let ([t0, v0], [t1, v1]) = (points[k - 1], points[k]);
                let w = (t - t0) / (t1 - t0);
                (1.0 - w) * v0 + w * v1
            }
        }
    }

    /// Interior $t$ where the profile's slope jumps (a table's points).
    fn kinks(&self) -> &[[f64; 2]] {
        match self {
            Profile::Table(points) if points.len() > 2 => &points[1..points.len() - 1],
            _ => &[],
        }
    }
}

/// A circular notch hinge: two circular cut-outs of radius `radius`,
/// centred on the flexure, leaving `min_thickness` at its middle. Around
/// the middle, $h(s) = h_{min} + 2R - 2\sqrt{R^2 - (s - L/2)^2}$, capped
/// by the section's thickness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Notch {
    /// Radius $R$ of each cut-out (m).
    pub radius: f64,
    /// Thickness $h_{min}$ left at the middle (m).
    pub min_thickness: f64,
}

/// Where the bending stiffness comes from.
#[derive(Debug, Clone, PartialEq)]
enum Stiffness {
    /// $EI(t)$ given directly (N·m²).
    Given(Profile),
    /// A rectangle $b(t) \times h(t)$ of effective modulus $E^{\prime}$:
    /// $EI = E^{\prime} b h^3/12$.
    Rectangle { modulus: f64, width: Profile, thickness: Profile, notch: Option<Notch> },
}

/// Where a section's mass per length comes from, in both dimensions.
#[derive(Debug, Clone, PartialEq)]
enum Mass {
    /// None: the flexure is massless.
    None,
    /// A density $\rho$ (kg/m³), times the section's area.
    Density(f64),
    /// $\mu(t)$ given directly (kg/m).
    PerLength(Profile),
}

/// The cross-section along a flexure (immutable; validated when built).
///
/// # Example
/// ```
/// use flexure::section::{Profile, Section};
/// // Steel strip 10 mm wide, tapering from 0.4 mm to 0.2 mm thick.
/// let s = Section::rectangle(200e9, None, Profile::Constant(0.01), Profile::Linear { root: 4e-4, tip: 2e-4 })
///     .unwrap();
/// let ei_root = 200e9 * 0.01 * 4e-4f64.powi(3) / 12.0;
/// assert!((s.ei(0.0, 0.02) - ei_root).abs() < 1e-12 * ei_root);
/// assert!((s.ei(1.0, 0.02) - ei_root / 8.0).abs() < 1e-12 * ei_root);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    stiffness: Stiffness,
    mass: Mass,
}

impl Section {
    /// A uniform section of bending stiffness `ei` (N·m²).
    pub fn uniform(ei: f64) -> Result<Self> {
        Self::given(Profile::Constant(ei))
    }

    /// A section of bending stiffness $EI(t)$ given directly (N·m²), with no
    /// thickness, so no stress (answers report curvature instead).
    pub fn given(ei: Profile) -> Result<Self> {
        ei.check("ei")?;
        Ok(Self { stiffness: Stiffness::Given(ei), mass: Mass::None })
    }

    /// A rectangle of `width` $b(t)$ and `thickness` $h(t)$ (m), modulus `modulus`
    /// $E$ (Pa); with `poisson` $\nu$ the plate modulus $E^{\prime} = E/(1-\nu^2)$ is used
    /// (as in [`crate::bending_stiffness`]).
    pub fn rectangle(modulus: f64, poisson: Option<f64>, width: Profile, thickness: Profile) -> Result<Self> {
        let e = crate::error::positive("modulus", modulus)?;
        let plate = match poisson {
            None => 1.0,
            Some(nu) if nu.is_finite() && nu > -1.0 && nu <= 0.5 => 1.0 / (1.0 - nu * nu),
            Some(nu) => return Err(Error::invalid("poisson", nu, "must lie in (-1, 0.5]")),
        };
        width.check("width")?;
        thickness.check("thickness")?;
        Ok(Self {
            stiffness: Stiffness::Rectangle { modulus: e * plate, width, thickness, notch: None },
            mass: Mass::None,
        })
    }

    /// The same rectangle with a circular [`Notch`]. Fails for a section
    /// given by `ei`, a notch at least as deep as the thickness at the
    /// middle, or one whose radius is less than half its cut.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Notch, Profile, Section};
    /// let s = Section::rectangle(70e9, None, Profile::Constant(0.01), Profile::Constant(0.005)).unwrap();
    /// assert!(s.clone().with_notch(Notch { radius: 0.005, min_thickness: 0.0005 }).is_ok());
    /// assert!(s.with_notch(Notch { radius: 0.005, min_thickness: 0.006 }).is_err());
    /// ```
    pub fn with_notch(mut self, notch: Notch) -> Result<Self> {
        crate::error::positive("notch.radius", notch.radius)?;
        crate::error::positive("notch.min_thickness", notch.min_thickness)?;
        match &mut self.stiffness {
            Stiffness::Given(_) => Err(Error::invalid(
                "notch",
                format!("radius {}, min_thickness {}", notch.radius, notch.min_thickness),
                "needs a thickness (a rectangle of width and thickness), not ei alone",
            )),
            Stiffness::Rectangle { thickness, notch: slot, .. } => {
                let blank = thickness.at(0.5);
                if notch.min_thickness >= blank {
                    return Err(Error::invalid(
                        "notch.min_thickness",
                        notch.min_thickness,
                        "must be less than the thickness at the middle of the flexure (the notch would be deeper than the thickness)",
                    ));
                }
                if 2.0 * notch.radius < blank - notch.min_thickness {
                    return Err(Error::invalid(
                        "notch.radius",
                        notch.radius,
                        "must be at least half the cut, (thickness - min_thickness)/2, for a circular cut-out",
                    ));
                }
                *slot = Some(notch);
                Ok(self)
            }
        }
    }

    /// The same section with mass from `density` $\rho$ (kg/m³): $\mu = \rho\thinspace b h$.
    /// Fails for a section given by `ei` alone (it has no area).
    pub fn with_density(mut self, density: f64) -> Result<Self> {
        crate::error::positive("density", density)?;
        if matches!(self.stiffness, Stiffness::Given(_)) {
            return Err(Error::invalid(
                "density",
                density,
                "needs a width and thickness; give mass_per_length with ei",
            ));
        }
        self.mass = Mass::Density(density);
        Ok(self)
    }

    /// The same section with mass per length $\mu(t)$ (kg/m) given directly.
    pub fn with_mass_per_length(mut self, mass_per_length: Profile) -> Result<Self> {
        mass_per_length.check("mass_per_length")?;
        self.mass = Mass::PerLength(mass_per_length);
        Ok(self)
    }

    /// Whether $EI$ is the same all along.
    pub fn is_uniform(&self) -> bool {
        match &self.stiffness {
            Stiffness::Given(p) => matches!(p, Profile::Constant(_)),
            Stiffness::Rectangle { width, thickness, notch, .. } => {
                matches!((width, thickness, notch), (Profile::Constant(_), Profile::Constant(_), None))
            }
        }
    }

    /// Bending stiffness $EI$ (N·m²) at $t = s/L$ on a flexure of `length` (m).
    pub fn ei(&self, t: f64, length: f64) -> f64 {
        match &self.stiffness {
            Stiffness::Given(p) => p.at(t),
            Stiffness::Rectangle { modulus, width, .. } => {
                let h = self.thickness(t, length).unwrap_or(0.0);
                modulus * width.at(t) * h * h * h / 12.0
            }
        }
    }

    /// Thickness $h$ (m) at $t$, notch included; `None` for a section given by `ei`.
    pub fn thickness(&self, t: f64, length: f64) -> Option<f64> {
        match &self.stiffness {
            Stiffness::Given(_) => None,
            Stiffness::Rectangle { thickness, notch, .. } => {
                let blank = thickness.at(t);
                Some(match notch {
                    Some(n) => blank.min(notched(n, (t - 0.5) * length)),
                    None => blank,
                })
            }
        }
    }

    /// The circular notch cut into the rectangle, if any.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Notch, Profile, Section};
    /// let plate = Section::rectangle(70e9, None, Profile::Constant(0.01), Profile::Constant(0.0105)).unwrap();
    /// assert_eq!(plate.notch(), None);
    /// let hinge = plate.with_notch(Notch { radius: 0.005, min_thickness: 5e-4 }).unwrap();
    /// assert_eq!(hinge.notch().map(|n| n.min_thickness), Some(5e-4));
    /// ```
    pub fn notch(&self) -> Option<&Notch> {
        match &self.stiffness {
            Stiffness::Rectangle { notch, .. } => notch.as_ref(),
            Stiffness::Given(_) => None,
        }
    }

    /// Width $b$ (m) at $t$; `None` for a section given by `ei`.
    pub fn width(&self, t: f64) -> Option<f64> {
        match &self.stiffness {
            Stiffness::Given(_) => None,
            Stiffness::Rectangle { width, .. } => Some(width.at(t)),
        }
    }

    /// Effective modulus $E^{\prime}$ (Pa); `None` for a section given by `ei`.
    pub fn modulus(&self) -> Option<f64> {
        match &self.stiffness {
            Stiffness::Given(_) => None,
            Stiffness::Rectangle { modulus, .. } => Some(*modulus),
        }
    }

    /// Mass per length $\mu$ (kg/m) at $t$; `None` without a density or mass per length.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, Section};
    /// let s = Section::rectangle(200e9, None, Profile::Constant(0.01), Profile::Constant(2e-4))
    ///     .unwrap()
    ///     .with_density(7850.0)
    ///     .unwrap();
    /// assert!((s.mass_per_length(0.3, 0.02).unwrap() - 7850.0 * 0.01 * 2e-4).abs() < 1e-15);
    /// ```
    pub fn mass_per_length(&self, t: f64, length: f64) -> Option<f64> {
        match &self.mass {
            Mass::None => None,
            Mass::Density(rho) => Some(rho * self.width(t)? * self.thickness(t, length)?),
            Mass::PerLength(p) => Some(p.at(t)),
        }
    }

    /// Rotary inertia per length $\rho I = \mu h^2/12$ (kg·m) at $t$: the
    /// section's resistance to turning. Zero without a thickness; `None`
    /// without mass.
    pub fn rotary_inertia_per_length(&self, t: f64, length: f64) -> Option<f64> {
        let mu = self.mass_per_length(t, length)?;
        Some(self.thickness(t, length).map_or(0.0, |h| mu * h * h / 12.0))
    }

    /// The $t$ in $(0, 1)$ where a quantity of the section stops being
    /// smooth (table points, the edges of a notch), increasing; integrals
    /// split there so that each piece is smooth.
    pub fn breakpoints(&self, length: f64) -> Vec<f64> {
        let mut out: Vec<f64> = Vec::new();
        let mut add = |p: &Profile| out.extend(p.kinks().iter().map(|k| k[0]));
        match &self.stiffness {
            Stiffness::Given(p) => add(p),
            Stiffness::Rectangle { width, thickness, notch, .. } => {
                add(width);
                add(thickness);
                if let Some(n) = notch {
                    for side in [-1.0, 1.0] {
                        if let Some(x) = notch_edge(n, thickness, length, side) {
                            out.push(0.5 + x / length);
                        }
                    }
                }
            }
        }
        if let Mass::PerLength(p) = &self.mass {
            out.extend(p.kinks().iter().map(|k| k[0]));
        }
        out.retain(|t| *t > 0.0 && *t < 1.0);
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
    }

    /// Whether $EI(t)$ is a polynomial between breakpoints (no notch), so
    /// Gauss–Legendre integrates it exactly.
    pub(crate) fn polynomial(&self) -> bool {
        !matches!(self.stiffness, Stiffness::Rectangle { notch: Some(_), .. })
    }
}

/// Thickness of the notch alone at `x` from the middle (infinite outside the cut-outs).
fn notched(n: &Notch, x: f64) -> f64 {
    let r = n.radius;
    if x.abs() >= r { f64::INFINITY } else { n.min_thickness + 2.0 * (r - (r * r - x * x).sqrt()) }
}

/// Signed distance from the middle where the notch meets the blank's
/// thickness on `side`, if within the flexure; by bisection (60 halvings,
/// to rounding).
fn notch_edge(n: &Notch, thickness: &Profile, length: f64, side: f64) -> Option<f64> {
    let gap = |x: f64| notched(n, side * x) - thickness.at(0.5 + side * x / length);
    let (mut lo, mut hi) = (0.0, n.radius.min(0.5 * length));
    if gap(hi) < 0.0 {
        return None;
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if gap(mid) < 0.0 { lo = mid } else { hi = mid }
    }
    Some(side * hi)
}
