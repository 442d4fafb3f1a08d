//! Checks of the assembled mechanism that no single table shows.

use super::dimension::FileDimension;
use super::document::{Numbers, Source, Span};
use super::{JointState, MAX_STIFFNESS_RATIO, Mechanism, Result};
use crate::mechanism::contact::{GeomShape, Toucher, corners, deepest_edge, gap, pairs, touching};

/// The joints' diagonal stiffnesses at rest (`joints`) span at most [`MAX_STIFFNESS_RATIO`].
pub(super) fn check_stiffness_ratio<D: FileDimension>(
    src: &Source,
    m: &Mechanism<D>,
    joints: &[JointState<D>],
    places: &[Span],
) -> Result<()> {
    let length = m.size();
    // (joint, stiffness in N·m)
    let mut all: Vec<(usize, f64)> = Vec::new();
    for (i, (j, s)) in m.joints.iter().zip(joints).enumerate() {
        let unit = if j.kind.joint().is_translation() { length * length } else { 1.0 };
        all.extend((0..s.gradient.len()).map(|k| (i, s.stiffness[(k, k)] * unit)).filter(|&(_, k)| k > 0.0));
    }
    let (Some(stiff), Some(soft)) = (
        all.iter().copied().max_by(|a, b| a.1.total_cmp(&b.1)),
        all.iter().copied().min_by(|a, b| a.1.total_cmp(&b.1)),
    ) else {
        return Ok(());
    };
    if stiff.1 > MAX_STIFFNESS_RATIO * soft.1 {
        return src.fail(
            &places[soft.0],
            format!(
                "joint {:?}: stiffness {:.3e} N·m is {:.1e} times softer than joint {:?} ({:.3e} N·m); double precision cannot weigh their forces together beyond a ratio of 1e12",
                m.joints[soft.0].name,
                soft.1,
                stiff.1 / soft.1,
                m.joints[stiff.0].name,
                stiff.1
            ),
        );
    }
    Ok(())
}

/// No two consecutive via points of a tendon coincide at rest (`bodies`:
/// the bodies' frames there): the tendon would have no direction there.
pub(super) fn check_tendon_directions<D: FileDimension>(
    src: &Source,
    m: &Mechanism<D>,
    bodies: &[D::Pose],
    places: &[Vec<Span>],
) -> Result<()> {
    for (t, spans) in m.tendons.iter().zip(places) {
        let w: Vec<D::Coords> = t.path.iter().map(|(b, r)| D::coords(&D::act(&bodies[*b], r))).collect();
        for (k, pair) in w.windows(2).enumerate() {
            let (p, q) = (pair[0].numbers(), pair[1].numbers());
            let size = p.iter().chain(q).map(|v| v.abs()).sum::<f64>();
            let gap = p.iter().zip(q).map(|(a, b)| (b - a) * (b - a)).sum::<f64>().sqrt();
            if gap <= 1e-12 * size {
                return src.fail(
                    &spans[k + 1],
                    format!(
                        "tendon {:?}: via points {} and {} coincide at rest, so the tendon has no direction there",
                        t.name,
                        k + 1,
                        k + 2
                    ),
                );
            }
        }
    }
    Ok(())
}

/// No part starts inside a geom it may touch (`bodies`: the bodies' frames
/// at rest; `places`: each geom's `shape`). A flexure, and a circle or
/// sphere, by the pair's [`gap`] at rest; two other geoms by the largest
/// ball about each one's centre that it holds (its radius for a capsule
/// or cylinder, the smallest half extent for a box; a plane's own point is
/// on its surface), which finds their deep overlaps.
pub(super) fn check_geoms_clear<D: FileDimension>(
    src: &Source,
    m: &Mechanism<D>,
    bodies: &[D::Pose],
    places: &[Span],
) -> Result<()> {
    let tolerance = 1e-9 * m.size();
    let q = m.rest();
    for pair in pairs(m) {
        let geom = &m.geoms[pair.geom];
        let at = &bodies[geom.body];
        let (deepest, what) = match pair.part {
            Toucher::Flexure(j) => {
                let g = gap(m, &q, bodies, &pair).map_err(|e| src.placed("", &places[pair.geom], e))?;
                let s = g.s.unwrap_or(0.0);
                (g.gap, format!("flexure {:?} starts inside it at s = {s:.6} m", m.joints[j].name))
            }
            Toucher::Geom(h) => {
                let other = &m.geoms[h];
                if corners(&geom.shape, &other.shape).is_none() {
                    return src.fail(
                        &places[h.max(pair.geom)],
                        format!(
                            "geom {:?} ({}) and geom {:?} ({}) may touch, and {}: name one in the other's `exclude`",
                            geom.name,
                            geom.shape.name(),
                            other.name,
                            other.shape.name(),
                            touching::<D>()
                        ),
                    );
                }
                let corner = gap(m, &q, bodies, &pair).map_err(|e| src.placed("", &places[pair.geom], e))?.gap;
                // Corners outside each other's solid, and neither's centre deep in the other (two bars crossed).
                let centre = |g: &crate::mechanism::contact::Geom<D>| {
                    D::act(&D::compose(&bodies[g.body], &g.frame), &D::origin(&D::identity()))
                };
                let inner = |g: &crate::mechanism::contact::Geom<D>| match g.shape {
                    GeomShape::Plane { .. } => 0.0,
                    GeomShape::Ball { radius } | GeomShape::Capsule { radius, .. } => radius,
                    GeomShape::Box { half_extents } => {
                        (0..D::POINT_DIM).map(|i| half_extents[i]).fold(f64::INFINITY, f64::min)
                    }
                    GeomShape::Cylinder { radius, half_length } => radius.min(half_length),
                };
                let one = geom.gap(at, &centre(other), inner(other)).0;
                let two = other.gap(&bodies[other.body], &centre(geom), inner(geom)).0;
                let crossed = deepest_edge(m, bodies, pair.geom, h);
                (
                    one.min(two).min(corner).min(crossed),
                    format!("geom {:?} on body {:?} starts inside it", other.name, m.bodies[other.body].name),
                )
            }
        };
        if deepest < -tolerance {
            return src.fail(
                &places[pair.geom],
                format!(
                    "geom {:?} ({}): {what}, {:.3e} m deep; move one of them, or name the part in the geom's `exclude`",
                    geom.name,
                    geom.shape.name(),
                    -deepest
                ),
            );
        }
    }
    Ok(())
}
