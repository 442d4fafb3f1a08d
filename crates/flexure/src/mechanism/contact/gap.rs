//! The gap of a pair that may touch, at a configuration: how far apart its
//! two parts are (negative: how deep one is in the other), where, and along
//! which normal. What a contact watches while it is open, and reports.
//!
//! For a geom and a flexure the gap is the least over the flexure's arc
//! length $s$ of
//! $$g(s) = d(p(s)) - h(s),$$
//! $d$ the geom's signed distance ([`super::GeomShape::distance`]), $p(s)$ the
//! centreline and $h(s)$ half the thickness. It is found on 65 evenly
//! spaced points, then refined on the two intervals about the least of
//! them by golden-section search (48 steps: the interval, a thirty-second
//! of the length, shrinks by $0.618^{48} \approx 10^{-10}$, which puts the
//! least's value at rounding, the gap being flat there to second order),
//! so an interior least meets the tangency condition $\hat n\cdot p^{\prime}(s) = 0$
//! to about $10^{-12}$ of the length and an end's is that end.

use super::{Pair, Touch, Toucher, corner, named};
use crate::error::{Error, Result};
use crate::mechanism::Mechanism;

/// A pair's gap at a configuration ([`gap`]).
///
/// # Example
/// ```
/// use flexure::mechanism::contact::Gap;
/// use flexure::space::Planar;
/// use nalgebra::{Point2, Vector2};
/// let g: Gap<Planar> = Gap { s: Some(0.05), point: Point2::new(0.05, 0.0), normal: Vector2::y(), gap: -1e-4 };
/// assert!(g.gap < 0.0); // overlapping by 0.1 mm
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gap<D: Touch> {
    /// The arc length (m) of the flexure's nearest point; `None` for two geoms.
    pub s: Option<f64>,
    /// The toucher's surface point nearest the geom (world frame): a
    /// flexure's centreline point at `s` moved by its half thickness
    /// against `normal`; for two geoms, the corner's surface point
    /// along `normal`.
    pub point: D::Point,
    /// The geom's outward unit normal there (world frame); of two geoms,
    /// the one's that the corner touches.
    pub normal: D::Vector,
    /// The gap (m): positive apart, negative overlapping by that depth.
    pub gap: f64,
}

/// The gap of the pair `pair` of `m` with coordinates `q`, its bodies'
/// frames (world) `bodies` (as [`crate::mechanism::kinematics`] gives
/// them at `q`). A geom and a flexure, or two geoms at a corner (its
/// centre's distance less its radius, exact: [`super::corners`]); two geoms
/// without corners are refused by name.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{gap, pairs};
/// use flexure::mechanism::kinematics::frames;
/// // A 1 mm strip 0.1 m long along x, and a post of radius 5 mm whose
/// // centre is 10.2 mm above its middle: 4.7 mm apart at s = 0.05 m.
/// let m = flexure::mechanism::file::from_toml(r#"
/// [[joint]]
/// name = "strip"
/// kind = "flexure"
/// parent = "ground"
/// child = "tip"
/// length = 0.1
/// modulus = 2e11
/// width = 0.01
/// thickness = 0.001
/// [[geom]]
/// name = "post"
/// body = "ground"
/// shape = "circle"
/// origin = [0.05, 0.0102]
/// radius = 0.005
/// "#).unwrap();
/// let q = m.rest();
/// let g = gap(&m, &q, &frames(&m, &q).bodies, &pairs(&m)[0]).unwrap();
/// assert!((g.gap - 0.0047).abs() < 1e-12 && (g.s.unwrap() - 0.05).abs() < 1e-9);
/// assert!((g.point.y - 0.0005).abs() < 1e-12 && (g.normal.y + 1.0).abs() < 1e-12);
/// ```
pub fn gap<D: Touch>(m: &Mechanism<D>, q: &[f64], bodies: &[D::Pose], pair: &Pair) -> Result<Gap<D>> {
    let found = minima(m, q, bodies, pair)?;
    Ok(found.into_iter().min_by(|a, b| a.gap.total_cmp(&b.gap)).expect("at least one least"))
}

/// Every local least of the gap of `pair` along its flexure (the sampled
/// points lower than their neighbours, each refined as [`gap`] refines
/// its least), root to tip: where a flexure may touch a geom at several
/// places at once. For two geoms, the gap at their corner.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{minima, pairs};
/// use flexure::mechanism::kinematics::frames;
/// // A straight strip above a floor tilted down toward the tip, so the tip is nearest.
/// let m = flexure::mechanism::file::from_toml(r#"
/// [[joint]]
/// name = "strip"
/// kind = "flexure"
/// parent = "ground"
/// child = "tip"
/// length = 0.1
/// ei = 1e-3
/// [[geom]]
/// body = "ground"
/// shape = "plane"
/// origin = [0.0, -0.02]
/// normal = [-0.1, 1.0]
/// "#).unwrap();
/// let q = m.rest();
/// let found = minima(&m, &q, &frames(&m, &q).bodies, &pairs(&m)[0]).unwrap();
/// assert_eq!(found.len(), 1);
/// assert_eq!(found[0].s, Some(0.1));
/// ```
pub fn minima<D: Touch>(m: &Mechanism<D>, q: &[f64], bodies: &[D::Pose], pair: &Pair) -> Result<Vec<Gap<D>>> {
    let geom = &m.geoms[pair.geom];
    let at = &bodies[geom.body];
    match pair.part {
        Toucher::Flexure(j) => {
            let joint = &m.joints[j];
            let Some(f) = joint.kind.flexure() else {
                return Err(Error::invalid("pair", named(m, pair), "names a joint that is not a flexure"));
            };
            let root = D::compose(&bodies[joint.parent], &joint.origin);
            let alpha = &q[joint.offset..joint.offset + joint.kind.joint().dof()];
            let length = D::flexure_length(f);
            let samples = D::surface(f, alpha, SAMPLES)?;
            let step = length / (samples.len() - 1) as f64;
            // From the sample at or before s: a piece, not a run from the root.
            let at_s = |s: f64| -> Result<Nearest<D>> {
                let from = &samples[((s / step).floor() as usize).min(samples.len() - 1)];
                let (_, p, h) =
                    if from.0 <= s { D::surface_from(f, alpha, from, s)? } else { D::surface_at(f, alpha, s)? };
                let world = D::act(&root, &p);
                let (g, n) = geom.gap(at, &world, h);
                Ok((g, D::moved(&world, &n, -h), n))
            };
            let gaps: Vec<f64> = samples.iter().map(|(_, p, h)| geom.gap(at, &D::act(&root, p), *h).0).collect();
            let last = gaps.len() - 1;
            let lows =
                (0..gaps.len()).filter(|&k| (k == 0 || gaps[k] < gaps[k - 1]) && (k == last || gaps[k] <= gaps[k + 1]));
            let mut out = Vec::new();
            for k in lows {
                let (a, b) = ((k as f64 - 1.0).max(0.0) * step, ((k + 1) as f64 * step).min(length));
                let (s, (g, point, normal)) = least::<D>(&at_s, a, b)?;
                out.push(Gap { s: Some(s), point, normal, gap: g });
            }
            Ok(out)
        }
        Toucher::Geom(_) => {
            let c = corner(m, pair)?;
            let placed = c.crossing(bodies);
            let against = c.against(bodies);
            let (centre, flat) = placed.as_ref().map_or((c.centre, &*against), |k| (k.centre, &k.surface));
            let centre = D::act(&bodies[c.round.body], &D::moved(&D::origin(&D::identity()), &centre, 1.0));
            let (g, normal) = flat.gap(&bodies[flat.body], &centre, c.radius);
            Ok(vec![Gap { s: None, point: D::moved(&centre, &normal, -c.radius), normal, gap: g }])
        }
    }
}

/// A gap at an arc length, with the surface point and normal there.
type Nearest<D> = (f64, <D as crate::space::Space>::Point, <D as crate::space::Space>::Vector);

/// Points sampled along a flexure before refining.
const SAMPLES: usize = 65;

/// Golden-section steps refining a least (see the module docs).
const GOLDEN_STEPS: usize = 48;

/// The least of `at_s` on $[a, b]$ by golden-section search ([`GOLDEN_STEPS`]) and
/// the interval's ends: its arc length and value.
fn least<D: Touch>(at_s: &impl Fn(f64) -> Result<Nearest<D>>, a: f64, b: f64) -> Result<(f64, Nearest<D>)> {
    let (mut a, mut b) = (a, b);
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - ratio * (b - a), a + ratio * (b - a));
    let (mut gc, mut gd) = (at_s(c)?.0, at_s(d)?.0);
    for _ in 0..GOLDEN_STEPS {
        if gc < gd {
            (b, d, gd) = (d, c, gc);
            c = b - ratio * (b - a);
            gc = at_s(c)?.0;
        } else {
            (a, c, gc) = (c, d, gd);
            d = a + ratio * (b - a);
            gd = at_s(d)?.0;
        }
    }
    // The least of the refined point and the interval's ends.
    Ok([a, 0.5 * (a + b), b]
        .into_iter()
        .map(|s| at_s(s).map(|v| (s, v)))
        .collect::<Result<Vec<_>>>()?
        .into_iter()
        .min_by(|x, y| x.1.0.total_cmp(&y.1.0))
        .expect("three points"))
}
