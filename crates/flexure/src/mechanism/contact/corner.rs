//! Where two geoms touch: at their corners. Two shapes' gap is watched at
//! points of one of them, each a ball (its centre a material point of its
//! geom, radius $r \ge 0$) against the other's exact signed distance
//! $d$: the gap there is $d(c) - r$.
//!
//! | pair | its corners |
//! | --- | --- |
//! | a circle or sphere and any geom | the ball itself (the later geom's, when both are) |
//! | a plane and a box | the box's $2^n$ corners ($r = 0$) |
//! | a plane and a capsule | the capsule's two end balls ($r$ its radius) |
//! | in the plane, two of box and capsule | each one's corners against the other |
//!
//! These are exact: a convex solid is first touched by a plane at a
//! corner, and in the plane two convex polygons (a capsule is its
//! segment's, rounded) are nearest at a vertex of one of them, so holding
//! each corner's gap $\ge 0$ holds the two apart. In space two boxes, or
//! a box and a capsule, also meet edge across edge, and a cylinder's rim
//! is no finite set of points: those pairs are refused by name, as are two
//! planes.

use super::{Geom, GeomShape, Pair, Touch, Toucher, named, vector};
use crate::error::{Error, Result};
use crate::mechanism::{Dimension, Mechanism};

/// A corner of a pair of two geoms ([`corners`]): a ball of `radius` about
/// `centre` in the frame of one of the two shapes, against the other.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerOf<D: Dimension> {
    /// Whether the corner is the pair's part's (the later geom's), not its geom's.
    pub of_part: bool,
    /// Its centre in its shape's frame (m).
    pub centre: D::Vector,
    /// Its radius (m): 0 at a box's corner.
    pub radius: f64,
}

/// The corners of two shapes, the pair's geom `a` and part `b` (see the
/// module docs), or `None` where their gap is not found.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{corners, GeomShape};
/// use flexure::space::{Planar, Spatial};
/// use nalgebra::{Vector2, Vector3};
/// let floor = GeomShape::<Spatial>::Plane { normal: Vector3::z() };
/// let brick = GeomShape::<Spatial>::Box { half_extents: Vector3::new(0.1, 0.2, 0.3) };
/// assert_eq!(corners(&floor, &brick).unwrap().len(), 8);
/// // In space two boxes also meet edge across edge: refused.
/// assert!(corners(&brick, &brick).is_none());
/// // In the plane they are nearest at a vertex of one of them.
/// let tile = GeomShape::<Planar>::Box { half_extents: Vector2::new(0.1, 0.2) };
/// assert_eq!(corners(&tile, &tile).unwrap().len(), 8);
/// ```
pub fn corners<D: Dimension>(a: &GeomShape<D>, b: &GeomShape<D>) -> Option<Vec<CornerOf<D>>> {
    let ball = |s: &GeomShape<D>| match s {
        GeomShape::Ball { radius } => Some(*radius),
        _ => None,
    };
    let plane = |s: &GeomShape<D>| matches!(s, GeomShape::Plane { .. });
    let of = |of_part: bool, s: &GeomShape<D>| {
        points(s).into_iter().map(move |(centre, radius)| CornerOf { of_part, centre, radius })
    };
    if let Some(radius) = ball(b) {
        return Some(vec![CornerOf { of_part: true, centre: D::Vector::default(), radius }]);
    }
    if let Some(radius) = ball(a) {
        return Some(vec![CornerOf { of_part: false, centre: D::Vector::default(), radius }]);
    }
    let cornered = |s: &GeomShape<D>| !points(s).is_empty();
    let found: Vec<CornerOf<D>> = match (plane(a), plane(b)) {
        (true, false) if cornered(b) => of(true, b).collect(),
        (false, true) if cornered(a) => of(false, a).collect(),
        (false, false) if D::POINT_DIM == 2 && cornered(a) && cornered(b) => of(true, b).chain(of(false, a)).collect(),
        _ => return None,
    };
    Some(found)
}

/// A box's or a capsule's corners in its frame: centre and radius (none for other shapes).
fn points<D: Dimension>(s: &GeomShape<D>) -> Vec<(D::Vector, f64)> {
    match s {
        GeomShape::Box { half_extents } => (0..1usize << D::POINT_DIM)
            .map(|k| {
                let mut c = *half_extents;
                for i in 0..D::POINT_DIM {
                    if k >> i & 1 == 1 {
                        c[i] = -c[i];
                    }
                }
                (c, 0.0)
            })
            .collect(),
        GeomShape::Capsule { half_length, radius } if *half_length == 0.0 => vec![(D::Vector::default(), *radius)],
        GeomShape::Capsule { half_length, radius } => {
            [1.0, -1.0].map(|side| (vector::<D>(&[side * half_length, 0.0, 0.0]), *radius)).to_vec()
        }
        _ => Vec::new(),
    }
}

/// The number of corners of geoms `g` and `h` of `m` (1 where their gap
/// is not found, so that the pair is kept and refused by name where it is used).
pub(crate) fn count<D: Dimension>(m: &Mechanism<D>, g: usize, h: usize) -> usize {
    corners(&m.geoms[g].shape, &m.geoms[h].shape).map_or(1, |c| c.len())
}

/// A corner of a pair of two geoms, placed: the geom it is of, the geom
/// it touches, its centre in its geom's body's frame, and its radius.
pub(crate) struct Corner<'m, D: Touch> {
    /// The geom whose corner it is.
    pub round: &'m Geom<D>,
    /// The geom it touches.
    pub flat: &'m Geom<D>,
    /// Its centre in `round`'s body's frame (m).
    pub centre: D::Vector,
    /// Its radius (m).
    pub radius: f64,
}

/// The corner of `pair` of `m` (its [`Pair::corner`]th, [`corners`]); an
/// error naming the pair where two geoms' gap is not found, or where the
/// pair is no pair of two geoms.
pub(crate) fn corner<'m, D: Touch>(m: &'m Mechanism<D>, pair: &Pair) -> Result<Corner<'m, D>> {
    let Toucher::Geom(h) = pair.part else {
        return Err(Error::invalid("pair", named(m, pair), "is not a pair of two geoms"));
    };
    let (geom, other) = (&m.geoms[pair.geom], &m.geoms[h]);
    let refused = || {
        Error::invalid(
            "pair",
            named(m, pair),
            if D::POINT_DIM == 2 {
                "the gap of two geoms is found where one is a circle, or neither is a plane (two planes never part)"
            } else {
                "the gap of two geoms is found where one is a sphere, or a plane and a box or capsule (two boxes, a box and a capsule, and a cylinder meet edge across edge or along a rim)"
            },
        )
    };
    let found = corners(&geom.shape, &other.shape).ok_or_else(refused)?;
    let c = found.get(pair.corner).ok_or_else(refused)?;
    let (round, flat) = if c.of_part { (other, geom) } else { (geom, other) };
    let centre = D::position(&D::act(&round.frame, &D::moved(&D::origin(&D::identity()), &c.centre, 1.0)));
    Ok(Corner { round, flat, centre, radius: c.radius })
}
