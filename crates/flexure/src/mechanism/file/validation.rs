//! Checks of the assembled mechanism that no single table shows.

use super::dimension::FileDimension;
use super::document::{Numbers, Source, Span};
use super::{JointState, MAX_STIFFNESS_RATIO, Mechanism, Result};

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
