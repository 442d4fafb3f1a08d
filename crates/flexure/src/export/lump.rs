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
