//! Lumped inertia: a flexure's distributed mass on the rigid links of its
//! pseudo-rigid-body model, and rigid inertias added together.

use crate::error::Result;
use crate::flexure::Flexure;
use crate::inertia::RigidInertia;
use crate::quadrature::GaussLegendre;
use crate::space::Pose;

/// Gauss points on each smooth piece of a segment.
const POINTS: usize = 16;

/// The rigid inertia, in the flexure's root frame, of its piece from arc
/// length `from` to `to` (m) held in its rest shape: mass
/// $m = \int\mu\thinspace ds$, centre of mass $c = \frac1m\int\mu\thinspace r(s)\thinspace ds$
/// and rotary inertia about it
/// $I_c = \int\left(\mu\lvert r(s) - c\rvert^2 + \rho I(s)\right)ds$,
/// with $\mu$ the mass per length, $\rho I = \mu h^2/12$ its sections' own
/// rotary inertia and $r(s)$ the rest backbone. By Gauss–Legendre on each
/// smooth piece (split at the section's breakpoints); the backbone's
/// position by a second rule from the root. `None` when the flexure has no mass.
///
/// # Example
/// ```
/// use flexure::export::lump::segment;
/// use flexure::section::{Profile, Section};
/// let s = Section::given(Profile::Constant(1.0)).unwrap().with_mass_per_length(Profile::Constant(2.0)).unwrap();
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap().with_section(s).unwrap();
/// let b = segment(&f, 0.25, 0.75).unwrap().unwrap();
/// // A uniform rod of mass 1 kg and length 0.5 m: I = m l²/12 about its middle.
/// assert!((b.mass - 1.0).abs() < 1e-14 && (b.com[0] - 0.5).abs() < 1e-14);
/// assert!((b.inertia - 0.25 / 12.0).abs() < 1e-14);
/// ```
pub fn segment(f: &Flexure, from: f64, to: f64) -> Result<Option<RigidInertia>> {
    let length = f.length();
    let section = f.section();
    if section.mass_per_length(0.5, length).is_none() || to <= from {
        return Ok(None);
    }
    let rule = GaussLegendre::new(POINTS)?;
    let mut psi = vec![0.0; f.order()];
    let mut angle = |t: f64| {
        f.angle_shapes(t, &mut psi);
        psi.iter().zip(f.rest()).map(|(p, k)| p * k).sum::<f64>()
    };
    // The rest backbone at arc length s: ∫₀ˢ (cos θ, sin θ), piecewise from the root.
    let mut position = |s: f64| {
        let (mut x, mut y) = (0.0, 0.0);
        for (&t, &w) in rule.nodes().iter().zip(rule.weights()) {
            let th = angle(t * s / length);
            x += w * s * th.cos();
            y += w * s * th.sin();
        }
        [x, y]
    };
    let mut cuts: Vec<f64> = vec![from];
    cuts.extend(section.breakpoints(length).into_iter().map(|t| t * length).filter(|s| *s > from && *s < to));
    cuts.push(to);
    // Sums of μ, μ r, μ |r|² and ρI.
    let (mut m0, mut m1, mut m2, mut rot) = (0.0, [0.0, 0.0], 0.0, 0.0);
    for piece in cuts.windows(2) {
        let (a, b) = (piece[0], piece[1]);
        for (&t, &w) in rule.nodes().iter().zip(rule.weights()) {
            let s = a + (b - a) * t;
            let ds = w * (b - a);
            let mu = section.mass_per_length(s / length, length).unwrap_or(0.0);
            let r = position(s);
            m0 += mu * ds;
            m1[0] += mu * r[0] * ds;
            m1[1] += mu * r[1] * ds;
            m2 += mu * (r[0] * r[0] + r[1] * r[1]) * ds;
            rot += section.rotary_inertia_per_length(s / length, length).unwrap_or(0.0) * ds;
        }
    }
    if m0 <= 0.0 {
        return Ok(None);
    }
    let com = [m1[0] / m0, m1[1] / m0];
    // Parallel axes: ∫μ|r − c|² = ∫μ|r|² − m|c|² (never below zero for rounding).
    let spread = (m2 - m0 * (com[0] * com[0] + com[1] * com[1])).max(0.0);
    Ok(Some(RigidInertia { mass: m0, inertia: spread + rot, com }))
}

/// Two rigid inertias in one frame as one: masses added, the centre of mass
/// their weighted mean, and each rotary inertia moved to it by the parallel
/// axis theorem, $I = \sum_k I_k + m_k\lvert c_k - c\rvert^2$.
///
/// # Example
/// ```
/// use flexure::{export::lump::add, inertia::RigidInertia};
/// let a = RigidInertia { mass: 1.0, inertia: 0.0, com: [0.0, 0.0] };
/// let b = RigidInertia { mass: 1.0, inertia: 0.0, com: [2.0, 0.0] };
/// let s = add(&a, &b);
/// assert_eq!((s.mass, s.com, s.inertia), (2.0, [1.0, 0.0], 2.0));
/// ```
pub fn add(a: &RigidInertia, b: &RigidInertia) -> RigidInertia {
    let mass = a.mass + b.mass;
    if mass <= 0.0 {
        return RigidInertia { mass: 0.0, inertia: a.inertia + b.inertia, com: a.com };
    }
    let com = std::array::from_fn(|i| (a.mass * a.com[i] + b.mass * b.com[i]) / mass);
    let d2 = |c: [f64; 2]| (c[0] - com[0]).powi(2) + (c[1] - com[1]).powi(2);
    RigidInertia { mass, inertia: a.inertia + a.mass * d2(a.com) + b.inertia + b.mass * d2(b.com), com }
}

/// `b`, given in a frame whose pose is `frame`, expressed in that frame's
/// parent: the centre of mass moved, the rotary inertia unchanged (a planar
/// rotation keeps it).
pub fn moved(frame: &Pose, b: &RigidInertia) -> RigidInertia {
    let c = frame.act(&nalgebra::Point2::new(b.com[0], b.com[1]));
    RigidInertia { com: [c.x, c.y], ..*b }
}

/// A rigid body's inertia in space: mass (kg), centre of mass (m) and the
/// rotary inertia about it (kg·m²), in one frame's axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialLump {
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass (m).
    pub com: nalgebra::Point3<f64>,
    /// Rotary inertia about the centre of mass (kg·m²).
    pub inertia: nalgebra::Matrix3<f64>,
}

impl SpatialLump {
    /// Nothing: no mass, no inertia.
    pub fn zero() -> Self {
        SpatialLump { mass: 0.0, com: nalgebra::Point3::origin(), inertia: nalgebra::Matrix3::zeros() }
    }

    /// Two lumps in one frame as one: masses added, the centre of mass their
    /// weighted mean, each inertia moved to it by the parallel axis theorem,
    /// $I = \sum_k I_k + m_k\left(\lvert d_k\rvert^2 1 - d_k d_k^T\right)$, $d_k = c_k - c$.
    ///
    /// # Example
    /// ```
    /// use flexure::export::lump::SpatialLump;
    /// use nalgebra::{Matrix3, Point3};
    /// let a = SpatialLump { mass: 1.0, com: Point3::new(0.0, 0.0, 0.0), inertia: Matrix3::zeros() };
    /// let b = SpatialLump { mass: 1.0, com: Point3::new(2.0, 0.0, 0.0), inertia: Matrix3::zeros() };
    /// let s = a.add(&b);
    /// // Two point masses 2 m apart along x: 2 kg·m² about y and z through the middle, none about x.
    /// assert_eq!((s.mass, s.com.x), (2.0, 1.0));
    /// assert_eq!(s.inertia, Matrix3::from_diagonal(&nalgebra::Vector3::new(0.0, 2.0, 2.0)));
    /// ```
    pub fn add(&self, other: &SpatialLump) -> SpatialLump {
        let mass = self.mass + other.mass;
        if mass <= 0.0 {
            return SpatialLump { mass: 0.0, com: self.com, inertia: self.inertia + other.inertia };
        }
        let com = nalgebra::Point3::from((self.com.coords * self.mass + other.com.coords * other.mass) / mass);
        let shift = |l: &SpatialLump| {
            let d = l.com - com;
            l.inertia + (nalgebra::Matrix3::identity() * d.norm_squared() - d * d.transpose()) * l.mass
        };
        SpatialLump { mass, com, inertia: shift(self) + shift(other) }
    }

    /// The lump, given in a frame whose pose is `frame`, in that frame's
    /// parent: $c \mapsto g c$, $I \mapsto R I R^T$.
    pub fn moved(&self, frame: &nalgebra::Isometry3<f64>) -> SpatialLump {
        let r = frame.rotation.to_rotation_matrix();
        SpatialLump {
            mass: self.mass,
            com: frame * self.com,
            inertia: r.matrix() * self.inertia * r.matrix().transpose(),
        }
    }
}

/// The rigid inertia, in its root frame, of the piece of a spatial flexure
/// `f` from arc length `from` to `to` (m), held in its rest shape (sections
/// at $p(s)$ turned by $R(s)$, [`crate::spatial::shape_at`]): mass
/// $m = \int\mu\thinspace ds$, centre of mass $c = \frac1m\int\mu p\thinspace ds$, and
/// about it $I = \int\left(\mu(\lvert d\rvert^2 1 - d d^T) + R\rho I R^T\right)ds$,
/// $d = p(s) - c$, with $\rho I = \rho\thinspace\mathrm{diag}(I_y + I_z, I_y, I_z)$ the
/// sections' own ([`crate::section::SpatialSection::rotary_inertia_per_length`]).
/// By Gauss–Legendre on each smooth piece (split at the section's
/// breakpoints). `None` when the flexure has no mass.
///
/// # Example
/// ```
/// use flexure::export::lump::spatial_segment;
/// use flexure::section::{Profile, SpatialSection};
/// use flexure::spatial::SpatialFlexure;
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 3, 3])?
///     .with_mass_per_length(Profile::Constant(2.0))?;
/// let b = spatial_segment(&f, 0.25, 0.75)?.unwrap();
/// // A uniform rod of 1 kg, 0.5 m long (no section geometry: a string of point masses):
/// // m l²/12 about y and z through its middle, nothing about its axis.
/// assert!((b.mass - 1.0).abs() < 1e-14 && (b.com.x - 0.5).abs() < 1e-14);
/// assert!((b.inertia[(1, 1)] - 0.25 / 12.0).abs() < 1e-14 && (b.inertia[(2, 2)] - 0.25 / 12.0).abs() < 1e-14);
/// assert!(b.inertia[(0, 0)].abs() < 1e-14);
/// // Bent at rest into a half circle about z (κ = π, radius 1/π): p(s) = (sin πs, 1 − cos πs)/π,
/// // whose mean over the length is (2/π², 1/π, 0).
/// let pi = std::f64::consts::PI;
/// let bent = f.with_rest(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, pi, 0.0, 0.0])?;
/// let all = spatial_segment(&bent, 0.0, 1.0)?.unwrap();
/// assert!((all.mass - 2.0).abs() < 1e-12 && (all.com.x - 2.0 / (pi * pi)).abs() < 1e-9);
/// assert!((all.com.y - 1.0 / pi).abs() < 1e-9 && all.com.z.abs() < 1e-12);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn spatial_segment(f: &crate::spatial::SpatialFlexure, from: f64, to: f64) -> Result<Option<SpatialLump>> {
    let length = f.length();
    let section = f.section();
    if !section.has_mass() || to <= from {
        return Ok(None);
    }
    let rule = GaussLegendre::new(POINTS)?;
    let mut cuts: Vec<f64> = vec![from];
    cuts.extend(section.breakpoints().into_iter().map(|t| t * length).filter(|s| *s > from && *s < to));
    cuts.push(to);
    // The nodes and weights, in order along the length.
    let mut nodes: Vec<(f64, f64)> = Vec::new();
    for piece in cuts.windows(2) {
        let (a, b) = (piece[0], piece[1]);
        for (&t, &w) in rule.nodes().iter().zip(rule.weights()) {
            nodes.push((a + (b - a) * t, w * (b - a)));
        }
    }
    nodes.sort_by(|a, b| a.0.total_cmp(&b.0));
    let at: Vec<f64> = nodes.iter().map(|n| n.0).collect();
    let sections = crate::spatial::shape_at(f, f.rest(), &at)?;
    // Sums of μ, μ p, μ p pᵀ and R ρI Rᵀ.
    let (mut m0, mut m1, mut m2, mut rot) =
        (0.0, nalgebra::Vector3::zeros(), nalgebra::Matrix3::zeros(), nalgebra::Matrix3::zeros());
    for ((s, ds), p) in nodes.iter().zip(&sections) {
        let mu = section.mass_per_length(s / length).unwrap_or(0.0);
        let r = nalgebra::Matrix3::from_fn(|i, j| p.rotation[i][j]);
        let x = nalgebra::Vector3::from(p.position);
        m0 += mu * ds;
        m1 += x * (mu * ds);
        m2 += x * x.transpose() * (mu * ds);
        let own = section.rotary_inertia_per_length(s / length).unwrap_or([0.0; 3]);
        rot += r * nalgebra::Matrix3::from_diagonal(&nalgebra::Vector3::from(own)) * r.transpose() * *ds;
    }
    if m0 <= 0.0 {
        return Ok(None);
    }
    let c = m1 / m0;
    // ∫μ d dᵀ = ∫μ p pᵀ − m c cᵀ; the inertia is its trace times 1 less it.
    let spread = m2 - c * c.transpose() * m0;
    let inertia = nalgebra::Matrix3::identity() * spread.trace() - spread + rot;
    Ok(Some(SpatialLump { mass: m0, com: nalgebra::Point3::from(c), inertia }))
}
