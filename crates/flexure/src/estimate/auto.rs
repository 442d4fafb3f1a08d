//! The automatic order of static answers: raise the order (and the
//! quadrature, to the reference's) until the estimate meets the target
//! ([`deflect_auto`], [`tendon_auto`], [`connect_auto`]), in the one loop
//! every `*_auto` shares.

use super::accuracy::{Accuracy, ErrorEstimate};
use super::refinement::refined;
use super::statics::{connect_error, deflect_error, tendon_error};
use crate::error::{Error, Result};
use crate::flexure::{Flexure, MAX_ORDER};
use crate::kinematics::Pose;
use crate::statics::{Settings, StaticsData, TipLoad, deflect};
use crate::tendon::{TendonData, TendonOffsets, pull};

/// The lowest order (from 3, doubling, with the reference's quadrature)
/// whose [`deflect`] answer under `load` meets `target`, with that answer's
/// flexure, coordinates and estimate. Errors if even order 64 misses it.
///
/// # Example
/// ```
/// use flexure::{estimate, Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let (used, alpha, e) = estimate::deflect_auto(&f, &TipLoad { moment: 20.0, fx: 0.0, fy: 0.0 }, &Default::default()).unwrap();
/// assert!(!e.flagged && used.quadrature_points() > 5 && (alpha[0] - 20.0).abs() < 1e-9);
/// ```
pub fn deflect_auto(
    flexure: &Flexure,
    load: &TipLoad,
    target: &Accuracy,
) -> Result<(Flexure, Vec<f64>, ErrorEstimate)> {
    auto(flexure, |f| {
        let mut data = StaticsData::new(f);
        deflect(f, load, &mut data, &Settings::default())?;
        let alpha = data.alpha().to_vec();
        let e = deflect_error(f, load, &alpha, target)?;
        Ok((alpha, e))
    })
}

/// [`deflect_auto`] for the tendon joint.
pub fn tendon_auto(
    flexure: &Flexure,
    tendon: &TendonOffsets,
    tension: f64,
    target: &Accuracy,
) -> Result<(Flexure, Vec<f64>, ErrorEstimate)> {
    auto(flexure, |f| {
        let mut data = TendonData::new(f);
        pull(f, tendon, tension, &mut data)?;
        let alpha = data.alpha().to_vec();
        let e = tendon_error(f, tendon, tension, &alpha, target)?;
        Ok((alpha, e))
    })
}

/// [`deflect_auto`] for [`crate::connect::connect`].
pub fn connect_auto(flexure: &Flexure, pose: &Pose, target: &Accuracy) -> Result<(Flexure, Vec<f64>, ErrorEstimate)> {
    auto(flexure, |f| {
        let c = crate::connect::connect(f, pose)?;
        let e = connect_error(f, pose, &c.alpha, target)?;
        Ok((c.alpha, e))
    })
}

/// Raises the order (and the quadrature, to the reference's) until `solve` meets its target.
fn auto(
    flexure: &Flexure,
    mut solve: impl FnMut(&Flexure) -> Result<(Vec<f64>, ErrorEstimate)>,
) -> Result<(Flexure, Vec<f64>, ErrorEstimate)> {
    let (f, (alpha, e)) = raise(flexure, |f| {
        let (alpha, e) = solve(f)?;
        let next = (e.reference_order, e.reference_quadrature);
        Ok(((alpha, e), e.flagged, next))
    })?;
    if e.flagged {
        // The value says by how much, and against what, so the refusal is not blind either.
        let reference = if e.exact {
            "the exact elastica".to_string()
        } else {
            format!("order {} with {} points", e.reference_order, e.reference_quadrature)
        };
        let value = format!(
            "auto (order {} is estimated {:.3} % of L off in tip position, {:.3}° in tip angle and {:.3} % in \
             the peak, against {reference})",
            f.order(),
            100.0 * e.position / f.length(),
            e.angle.to_degrees(),
            100.0 * e.peak,
        );
        return Err(Error::invalid(
            "order",
            value,
            "even order 64 misses the accuracy target: loosen --accuracy or reduce the load",
        ));
    }
    Ok((f, alpha, e))
}

/// The one loop of every `*_auto`: solves at `flexure`'s order, and while
/// the answer is flagged and the order below [`MAX_ORDER`], again at the
/// (order, quadrature) `solve` names (its reference's). Returns the last
/// flexure and answer, flagged or not: the caller says what a miss at the
/// cap means.
pub(super) fn raise<T>(
    flexure: &Flexure,
    mut solve: impl FnMut(&Flexure) -> Result<(T, bool, (usize, usize))>,
) -> Result<(Flexure, T)> {
    let mut f = flexure.clone();
    loop {
        let (answer, flagged, (order, points)) = solve(&f)?;
        if !flagged || f.order() >= MAX_ORDER {
            return Ok((f, answer));
        }
        f = refined(&f, order.max(f.order() + 1).min(MAX_ORDER), points)?;
    }
}
