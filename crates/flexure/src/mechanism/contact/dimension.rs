//! What contact needs of a dimension: a point's coordinates as a vector
//! (for the shapes' closed forms) and a flexure's surface, its centreline
//! with the half thickness it touches with. The plane and space side by side.

use crate::error::Result;
use crate::kinematics::{backbone, pose_at};
use crate::mechanism::Dimension;
use crate::section::Outline;
use crate::space::{Planar, Spatial};
use nalgebra::{DMatrix, Point2, Point3, Vector2, Vector3};

/// A point of a flexure's surface: its arc length $s$ (m), its centreline
/// point in the flexure's root frame, and the half thickness $h$ (m) it
/// touches with there.
pub type SurfacePoint<D> = (f64, <D as crate::space::Space>::Point, f64);

/// A dimension whose shapes and flexures may touch: [`Planar`] or [`Spatial`].
///
/// # Example
/// ```
/// use flexure::mechanism::contact::Touch;
/// use flexure::space::Planar;
/// use nalgebra::{Point2, Vector2};
/// assert_eq!(Planar::position(&Point2::new(1.0, 2.0)), Vector2::new(1.0, 2.0));
/// ```
pub trait Touch: Dimension {
    /// A point's coordinates, as a vector from the origin.
    fn position(p: &Self::Point) -> Self::Vector;
    /// $p + k v$.
    fn moved(p: &Self::Point, v: &Self::Vector, k: f64) -> Self::Point;
    /// `samples` (at least 2) points of the flexure with coordinates
    /// `alpha`, evenly spaced in arc length from root to tip, each with the
    /// half thickness of its section: half the `thickness` of a strip (in
    /// space too, where a strip's edges reach a further half of its width
    /// off the bending plane), half the diameter of a rod, 0 for a flexure
    /// given by its stiffness alone (the centreline touches).
    fn surface(f: &Self::Flexure, alpha: &[f64], samples: usize) -> Result<Vec<SurfacePoint<Self>>>;
    /// The surface point at arc length `s` (m, in $[0, L]$), as [`Touch::surface`] gives them.
    fn surface_at(f: &Self::Flexure, alpha: &[f64], s: f64) -> Result<SurfacePoint<Self>>;
    /// [`Touch::surface_at`] from a surface point `from` of the same
    /// flexure (at an arc length at most `s`), where the integration may
    /// start rather than at the root; by default from the root.
    fn surface_from(f: &Self::Flexure, alpha: &[f64], from: &SurfacePoint<Self>, s: f64) -> Result<SurfacePoint<Self>> {
        let _ = from;
        Self::surface_at(f, alpha, s)
    }
    /// The centreline point at arc length `s` with its first and second
    /// derivatives in the coordinates `alpha` and in `s` ([`SectionJet`]),
    /// exact for the integration [`Touch::surface_at`] uses.
    fn section_jet(f: &Self::Flexure, alpha: &[f64], s: f64) -> Result<SectionJet<Self>>;
}

/// The jet of the section's material point `offset` (m) from the
/// centreline, in the section's axes $e_i$ (tangent first; in the plane
/// the first two entries): $x = p + \sum_i o_ie_i$, so $\partial_a x =
/// \partial_a p + \sum_i o_i\partial_ae_i$ and likewise its second
/// derivatives ([`SectionJet::frame`]). A strip's surface point turns with
/// its section: in space with its twist too.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{offset_jet, Touch};
/// use flexure::space::Planar;
/// // A straight strip of unit length: its section at s = 0.5 turns by
/// // alpha_0 s per unit of its first coordinate, so a point 0.01 above
/// // the centreline moves back by 0.01 along it.
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
/// let jet = Planar::section_jet(&f, &[0.0; 3], 0.5).unwrap();
/// let x = offset_jet(&jet, [0.0, 0.01, 0.0]);
/// assert!((x.point.y - 0.01).abs() < 1e-15);
/// assert!((x.jacobian[0].x - (jet.jacobian[0].x - 0.01 * 0.5)).abs() < 1e-15);
/// ```
pub fn offset_jet<D: Touch>(jet: &SectionJet<D>, offset: [f64; 3]) -> SectionJet<D> {
    let mut out = jet.clone();
    let k = jet.jacobian.len();
    for (i, o) in offset.iter().enumerate().take(D::POINT_DIM).filter(|(_, o)| **o != 0.0) {
        out.point = out.point + super::scaled::<D>(&jet.frame[i], *o);
        for a in 0..k {
            out.jacobian[a] = out.jacobian[a] + super::scaled::<D>(&jet.frame_jacobian[i][a], *o);
            for b in 0..k {
                let v = super::scaled::<D>(&jet.frame_hessian[i][a * k + b], *o);
                for (c, h) in out.hessian.iter_mut().enumerate() {
                    h[(a, b)] += v[c];
                }
            }
        }
    }
    out
}

/// A flexure's centreline point $p(\alpha, s)$ at one arc length, in its
/// root frame, with what a contact there needs of its derivatives (the
/// Data of [`Touch::section_jet`]); $k$ the flexure's coordinates.
#[derive(Debug, Clone)]
pub struct SectionJet<D: Dimension> {
    /// $p$ (m).
    pub point: D::Vector,
    /// $\partial p/\partial\alpha_a$, one per coordinate.
    pub jacobian: Vec<D::Vector>,
    /// $\partial^2 p_i/\partial\alpha_a\partial\alpha_b$: one $k\times k$ matrix per component $i$.
    pub hessian: Vec<DMatrix<f64>>,
    /// The unit tangent $t = \partial p/\partial s$.
    pub tangent: D::Vector,
    /// $\partial t/\partial\alpha_a$, one per coordinate.
    pub tangent_jacobian: Vec<D::Vector>,
    /// $\partial t/\partial s$: the curvature's bend of the tangent (1/m).
    pub bend: D::Vector,
    /// The half thickness $h(s)$ it touches with (m), $h^{\prime}$ and $h^{\prime\prime}$ (1/m).
    pub half: [f64; 3],
    /// The section's material axes $e_i$ (unit, tangent first; two in the
    /// plane, three in space).
    pub frame: Vec<D::Vector>,
    /// $\partial e_i/\partial\alpha_a$: per axis, one per coordinate.
    pub frame_jacobian: Vec<Vec<D::Vector>>,
    /// $\partial^2 e_i/\partial\alpha_a\partial\alpha_b$: per axis, at $ak + b$.
    pub frame_hessian: Vec<Vec<D::Vector>>,
}

impl Touch for Planar {
    fn position(p: &Point2<f64>) -> Vector2<f64> {
        p.coords
    }

    fn moved(p: &Point2<f64>, v: &Vector2<f64>, k: f64) -> Point2<f64> {
        p + v * k
    }

    fn surface(f: &crate::Flexure, alpha: &[f64], samples: usize) -> Result<Vec<SurfacePoint<Planar>>> {
        let count = samples.max(2);
        let l = f.length();
        let points = backbone(f, alpha, count);
        Ok(points
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let t = i as f64 / (count - 1) as f64;
                (t * l, p.origin(), 0.5 * f.section().thickness(t, l).unwrap_or(0.0))
            })
            .collect())
    }

    /// The centreline point by [`crate::kinematics::pose_at`], on 64 pieces of $[0, s]$.
    fn surface_at(f: &crate::Flexure, alpha: &[f64], s: f64) -> Result<SurfacePoint<Planar>> {
        f.check_coordinates("alpha", alpha)?;
        let l = f.length();
        if !(0.0..=l).contains(&s) {
            return Err(crate::Error::invalid("s", s, "must be an arc length on the flexure, from 0 to its length"));
        }
        let p = pose_at(f, alpha, s, 64);
        Ok((s, p.origin(), 0.5 * f.section().thickness(s / l, l).unwrap_or(0.0)))
    }

    /// The centreline run from `from` on pieces of at most a 64th of the
    /// length, as [`Touch::surface_at`] runs from the root.
    fn surface_from(
        f: &crate::Flexure,
        alpha: &[f64],
        from: &SurfacePoint<Planar>,
        s: f64,
    ) -> Result<SurfacePoint<Planar>> {
        f.check_coordinates("alpha", alpha)?;
        let l = f.length();
        if !(from.0..=l).contains(&s) {
            return Err(crate::Error::invalid(
                "s",
                s,
                "must be an arc length on the flexure, from the start point to its length",
            ));
        }
        let pieces = ((s - from.0) / l * 64.0).ceil() as usize;
        let p = crate::kinematics::pose_from(f, alpha, (from.0, from.1.x, from.1.y), s, pieces);
        Ok((s, p.origin(), 0.5 * f.section().thickness(s / l, l).unwrap_or(0.0)))
    }

    /// $p = L\int_0^{s/L} e(\theta)\thinspace dt$ with $e = (\cos\theta, \sin\theta)$,
    /// $e_\perp = (-\sin\theta, \cos\theta)$, so
    /// $\partial_a p = L\int\psi_a e_\perp\thinspace dt$ and
    /// $\partial_a\partial_b p = -L\int\psi_a\psi_b\thinspace e\thinspace dt$, by the Gauss rule
    /// and pieces of [`pose_at`]; $t = e(\theta(s))$, $\partial_a t = \psi_a e_\perp$,
    /// $\partial_s t = \theta^{\prime}(s)\thinspace e_\perp$. The section's axes
    /// $(t, e_\perp)$ turn by $\theta$, linear in $\alpha$: $\partial_ae =
    /// \psi_ae^\perp$ and $\partial_a\partial_be = -\psi_a\psi_be$.
    fn section_jet(f: &crate::Flexure, alpha: &[f64], s: f64) -> Result<SectionJet<Planar>> {
        f.check_coordinates("alpha", alpha)?;
        let (l, k) = (f.length(), f.order());
        if !(0.0..=l).contains(&s) {
            return Err(crate::Error::invalid("s", s, "must be an arc length on the flexure, from 0 to its length"));
        }
        let rule = crate::quadrature::GaussLegendre::new(5).expect("five points");
        let mut psi = vec![0.0; k];
        let angle = |psi: &[f64]| psi.iter().zip(alpha).map(|(p, a)| p * a).sum::<f64>();
        let mut jet = SectionJet::<Planar> {
            point: Vector2::zeros(),
            jacobian: vec![Vector2::zeros(); k],
            hessian: vec![DMatrix::zeros(k, k); 2],
            tangent: Vector2::zeros(),
            tangent_jacobian: vec![Vector2::zeros(); k],
            bend: Vector2::zeros(),
            half: half_planar(f, s),
            frame: Vec::new(),
            frame_jacobian: Vec::new(),
            frame_hessian: Vec::new(),
        };
        let pieces = 64;
        let h = s / l / pieces as f64;
        for piece in 0..pieces {
            for (t, w) in rule.nodes().iter().zip(rule.weights()) {
                f.angle_shapes((piece as f64 + t) * h, &mut psi);
                let (sin, cos) = angle(&psi).sin_cos();
                let w = w * h * l;
                jet.point += Vector2::new(cos, sin) * w;
                for a in 0..k {
                    jet.jacobian[a] += Vector2::new(-sin, cos) * (w * psi[a]);
                    for b in 0..k {
                        let v = w * psi[a] * psi[b];
                        jet.hessian[0][(a, b)] -= v * cos;
                        jet.hessian[1][(a, b)] -= v * sin;
                    }
                }
            }
        }
        f.angle_shapes(s / l, &mut psi);
        let (sin, cos) = angle(&psi).sin_cos();
        let normal = Vector2::new(-sin, cos);
        jet.tangent = Vector2::new(cos, sin);
        for a in 0..k {
            jet.tangent_jacobian[a] = normal * psi[a];
        }
        jet.bend = normal * f.curvature(alpha, s);
        jet.frame = vec![jet.tangent, normal];
        jet.frame_jacobian =
            jet.frame.iter().map(|e| psi.iter().map(|p| Vector2::new(-e.y, e.x) * *p).collect()).collect();
        jet.frame_hessian =
            jet.frame.iter().map(|e| (0..k * k).map(|ab| -e * (psi[ab / k] * psi[ab % k])).collect()).collect();
        Ok(jet)
    }
}

impl Touch for Spatial {
    fn position(p: &Point3<f64>) -> Vector3<f64> {
        p.coords
    }

    fn moved(p: &Point3<f64>, v: &Vector3<f64>, k: f64) -> Point3<f64> {
        p + v * k
    }

    fn surface(
        f: &crate::spatial::SpatialFlexure,
        alpha: &[f64],
        samples: usize,
    ) -> Result<Vec<SurfacePoint<Spatial>>> {
        let l = f.length();
        Ok(crate::spatial::shape(f, alpha, samples.max(2))?
            .into_iter()
            .map(|sec| (sec.s, Point3::from(sec.position), half_thickness(f, sec.s / l)))
            .collect())
    }

    fn surface_at(f: &crate::spatial::SpatialFlexure, alpha: &[f64], s: f64) -> Result<SurfacePoint<Spatial>> {
        let sec = crate::spatial::shape_at(f, alpha, &[s])?.remove(0);
        Ok((s, Point3::from(sec.position), half_thickness(f, s / f.length())))
    }

    /// From [`crate::spatial::section_at`]: $\partial_a p = RJ_a^{v}$,
    /// $\partial_a\partial_b p = R(J_b^{\omega}\times J_a^{v} + H_{ab}^{v})$,
    /// $t = Re_1$, $\partial_a t = R(J_a^{\omega}\times e_1)$ and
    /// $\partial_s t = R(u\times e_1)$, $u$ the body curvature; the
    /// section's axes $Re_i$, $\partial_a(Re_i) = R(J_a^{\omega}\times e_i)$ and
    /// $\partial_a\partial_b(Re_i) = R\big(J_b^{\omega}\times(J_a^{\omega}\times e_i) + H_{ab}^{\omega}\times e_i\big)$.
    fn section_jet(f: &crate::spatial::SpatialFlexure, alpha: &[f64], s: f64) -> Result<SectionJet<Spatial>> {
        f.check_coordinates("alpha", alpha)?;
        let (l, k) = (f.length(), f.coordinates());
        if !(0.0..=l).contains(&s) {
            return Err(crate::Error::invalid("s", s, "must be an arc length on the flexure, from 0 to its length"));
        }
        let mut data = crate::spatial::SpatialKinematics::new(f);
        let (r, p) = crate::spatial::section_at(f, alpha, s, &mut data);
        let parts = |x: &nalgebra::Vector6<f64>| (Vector3::new(x[0], x[1], x[2]), Vector3::new(x[3], x[4], x[5]));
        let columns: Vec<_> = data.jacobian_columns().iter().map(parts).collect();
        let mut hessian = vec![DMatrix::zeros(k, k); 3];
        for a in 0..k {
            for b in 0..k {
                let v = r * (columns[b].0.cross(&columns[a].1) + parts(data.column_derivative(a, b)).1);
                for (i, m) in hessian.iter_mut().enumerate() {
                    m[(a, b)] = v[i];
                }
            }
        }
        let u = Vector3::from(f.curvature(alpha, s));
        let axes = [Vector3::x(), Vector3::y(), Vector3::z()];
        let frame_jacobian = axes.iter().map(|e| columns.iter().map(|(w, _)| r * w.cross(e)).collect()).collect();
        let frame_hessian = axes
            .iter()
            .map(|e| {
                (0..k * k)
                    .map(|ab| {
                        let (a, b) = (ab / k, ab % k);
                        let turn = parts(data.column_derivative(a, b)).0;
                        r * (columns[b].0.cross(&columns[a].0.cross(e)) + turn.cross(e))
                    })
                    .collect()
            })
            .collect();
        Ok(SectionJet {
            point: p,
            jacobian: columns.iter().map(|(_, v)| r * v).collect(),
            hessian,
            tangent: r * Vector3::x(),
            tangent_jacobian: columns.iter().map(|(w, _)| r * w.cross(&Vector3::x())).collect(),
            bend: r * u.cross(&Vector3::x()),
            half: slopes(|s| half_thickness(f, s / l), s, l),
            frame: axes.iter().map(|e| r * e).collect(),
            frame_jacobian,
            frame_hessian,
        })
    }
}

/// $h$, $h^{\prime}$ and $h^{\prime\prime}$ of a planar flexure at `s`:
/// the section's thickness is a closed form of $s$ without derivatives, so
/// they are central differences over $10^{-4}L$ (one-sided at the ends),
/// exactly zero for a uniform strip; a notch's corner is a kink either way.
fn half_planar(f: &crate::Flexure, s: f64) -> [f64; 3] {
    let l = f.length();
    slopes(|s| 0.5 * f.section().thickness(s / l, l).unwrap_or(0.0), s, l)
}

/// $h$, $h^{\prime}$ and $h^{\prime\prime}$ of `half` at `s` on $[0, L]$ (see [`half_planar`]).
fn slopes(half: impl Fn(f64) -> f64, s: f64, l: f64) -> [f64; 3] {
    let d = 1e-4 * l;
    let c = s.clamp(d, l - d);
    let (a, m, b) = (half(c - d), half(c), half(c + d));
    [half(s), (b - a) / (2.0 * d), (b - 2.0 * m + a) / (d * d)]
}

/// Half a spatial flexure's thickness (a strip's) or diameter (a rod's) at
/// $t = s/L$; 0 for one given by its stiffnesses alone.
fn half_thickness(f: &crate::spatial::SpatialFlexure, t: f64) -> f64 {
    match f.section().outline(t) {
        Some(Outline::Rectangle { thickness, .. }) => 0.5 * thickness,
        Some(Outline::Circle { diameter }) => 0.5 * diameter,
        None => 0.0,
    }
}
