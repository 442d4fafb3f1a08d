//! The spatial flexure's error estimate ([`crate::spatial`]): its answer
//! against a refined model's, as the rest of [`crate::estimate`] does for
//! the planar flexure.
//!
//! The reference raises each component's order to $\max(2n_c, n_c + 3)$
//! (at most [`MAX_ORDER`]) and takes at least twice the answer's Magnus
//! subintervals, at least the default for its own orders
//! ([`SpatialFlexure::default_subintervals`]) and at least two per radian of
//! total turning, so that its own truncation and discretization errors are
//! both far below the answer's, and the estimate includes the answer's
//! discretization error; the answer, padded with zeros, starts the
//! reference's Newton solve at the full load (continuation from rest if
//! that fails).

use super::{Accuracy, ErrorEstimate};
use crate::error::Result;
use crate::flexure::MAX_ORDER;
use crate::space::rotation_angle;
use crate::spatial::{self as spatial_flexure, SpatialFlexure, SpatialLoad, SpatialStatics, correct, deflect};

/// The reference model for the answer `alpha` of `flexure`: orders raised
/// to $\bar n_c = \max(2n_c, n_c + 3)$, and subintervals
/// $$\bar M = \max\big(2M,\thinspace M_0(\bar n),\thinspace \lceil 2\textstyle\sum_a\lvert\alpha_a\rvert\rceil\big)$$
/// (at most [`MAX_SUBINTERVALS`](spatial_flexure::MAX_SUBINTERVALS)), with
/// $M_0(\bar n)$ the default for the raised orders
/// ([`SpatialFlexure::default_subintervals`]): twice the answer's, so that
/// its discretization error shows, and resolved for its own orders.
///
/// # Example
/// ```
/// use flexure::estimate::spatial::reference;
/// use flexure::{section::SpatialSection, spatial::SpatialFlexure};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 2, 3]).unwrap();
/// let r = reference(&f, &[0.0; 8]).unwrap();
/// // Orders 6 take 4·(6 − 1) = 20 subintervals, more than twice the answer's 8.
/// assert_eq!((r.orders(), r.subintervals()), ([6, 5, 6], 20));
/// let fine = reference(&f.clone().with_subintervals(32).unwrap(), &[0.0; 8]).unwrap();
/// assert_eq!(fine.subintervals(), 64);
/// ```
pub fn reference(flexure: &SpatialFlexure, alpha: &[f64]) -> Result<SpatialFlexure> {
    flexure.check_coordinates("alpha", alpha)?;
    let orders = flexure.orders().map(|n| (2 * n).max(n + 3).min(MAX_ORDER));
    let turning: f64 = alpha.iter().map(|a| a.abs()).sum();
    let subintervals = (2 * flexure.subintervals())
        .max(SpatialFlexure::default_subintervals(orders))
        .max((2.0 * turning).ceil() as usize)
        .min(spatial_flexure::MAX_SUBINTERVALS);
    SpatialFlexure::new(flexure.length(), flexure.section().clone(), orders)?
        .with_rest(&padded(flexure, flexure.rest(), orders))?
        .with_subintervals(subintervals)
}

/// The reference for an eigenvalue answer of `flexure` about the shape
/// `alpha`: [`reference()`] (each order $n_c \to \min(\max(2n_c, n_c + 3), 64)$,
/// at least twice the subintervals), except that a component at the cap
/// $n_c = 64$ goes to order 32, as the planar
/// [`eigen_reference`](super::eigen_reference) does: more subintervals alone
/// would leave a straight flexure's answer unchanged and report a false 0.
pub(super) fn eigen_reference(flexure: &SpatialFlexure, alpha: &[f64]) -> Result<SpatialFlexure> {
    let r = reference(flexure, alpha)?;
    let capped = flexure.orders().map(|n| n >= MAX_ORDER);
    if !capped.contains(&true) {
        return Ok(r);
    }
    let mut orders = r.orders();
    for (o, c) in orders.iter_mut().zip(capped) {
        if c {
            *o = MAX_ORDER / 2;
        }
    }
    SpatialFlexure::new(flexure.length(), flexure.section().clone(), orders)?
        .with_rest(&padded(flexure, flexure.rest(), orders))?
        .with_subintervals(r.subintervals())
}

/// Each spatial flexure joint's error estimate at a solution: the flexure
/// under the tip wrench it carries ([`flexure_loads`]) against its own
/// refined reference ([`deflect_error`]), flagged against `target`, as the
/// planar mechanism's per-flexure estimates are. One entry per joint,
/// `None` for the other kinds.
///
/// # Example
/// ```
/// use flexure::estimate::spatial::flexure_errors;
/// use flexure::mechanism::statics::solve;
/// use flexure::mechanism::spatial::{SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism, SpatialPointLoad};
/// use flexure::section::SpatialSection;
/// use flexure::spatial::SpatialFlexure;
/// use nalgebra::{Isometry3, Point3, Vector3, Vector6};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(0.8, 1.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
/// let joint = SpatialJointSpec { name: "f".into(), kind: SpatialJointKind::Flexure(Box::new(f)), parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default() };
/// let push = SpatialPointLoad { name: "p".into(), body: 1, at: Point3::origin(), wrench: Vector6::new(0.0, 0.0, 0.0, 0.0, 0.5, 0.5) };
/// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), SpatialBody::massless("tip")], vec![joint], vec![], vec![push], vec![], Vector3::zeros()).unwrap();
/// let s = solve(&m, &Default::default()).unwrap();
/// let e = flexure_errors(&m, &s, &Default::default()).unwrap();
/// assert!(e[0].as_ref().unwrap().position < 1e-3);
/// ```
///
/// [`flexure_loads`]: crate::mechanism::spatial::statics::flexure_loads
pub fn flexure_errors(
    m: &crate::mechanism::spatial::SpatialMechanism,
    s: &crate::mechanism::statics::Solution<crate::space::Spatial>,
    target: &Accuracy,
) -> Result<Vec<Option<ErrorEstimate>>> {
    let loads = crate::mechanism::spatial::statics::flexure_loads(m, s);
    m.joints
        .iter()
        .zip(loads)
        .map(|(j, load)| match (j.kind.flexure(), load) {
            (Some(f), Some(load)) => {
                let alpha = &s.q[j.offset..j.offset + f.coordinates()];
                deflect_error(f, &load, alpha, target).map(Some)
            }
            _ => Ok(None),
        })
        .collect()
}

/// Coordinates of `flexure` padded with zeros, per component, to `orders`.
pub fn padded(flexure: &SpatialFlexure, alpha: &[f64], orders: [usize; 3]) -> Vec<f64> {
    let mut out = Vec::with_capacity(orders.iter().sum());
    let mut start = 0;
    for (n, m) in flexure.orders().into_iter().zip(orders) {
        out.extend_from_slice(&alpha[start..start + n.min(m)]);
        out.resize(out.len() + m.saturating_sub(n), 0.0);
        start += n;
    }
    out
}

/// The largest change of the body curvature from rest, $\max_s\lvert u(s) - u_0(s)\rvert$ (1/m), sampled.
fn peak_curvature(flexure: &SpatialFlexure, alpha: &[f64]) -> f64 {
    const SAMPLES: usize = 65;
    let change: Vec<f64> = alpha.iter().zip(flexure.rest()).map(|(a, k)| a - k).collect();
    (0..SAMPLES)
        .map(|k| {
            let u = flexure.curvature(&change, flexure.length() * k as f64 / (SAMPLES - 1) as f64);
            (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt()
        })
        .fold(0.0, f64::max)
}

/// The error of a [`deflect`] answer `alpha` under `load`: the tip's
/// position and rotation against the reference model's equilibrium
/// ([`reference()`]), in the one shape every estimate has
/// ([`ErrorEstimate`]; its `curvature` is that of the curvature vector's
/// peak change, and no stress is estimated yet).
///
/// # Example
/// ```
/// use flexure::section::SpatialSection;
/// use flexure::estimate::spatial::deflect_error;
/// use flexure::spatial::{SpatialFlexure, SpatialLoad, SpatialStatics, deflect};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(0.8, 1.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
/// let load = SpatialLoad { moment: [0.0; 3], force: [0.0, 0.5, 0.5] };
/// let mut data = SpatialStatics::new(&f);
/// deflect(&f, &load, &mut data, &Default::default()).unwrap();
/// let e = deflect_error(&f, &load, data.alpha(), &Default::default()).unwrap();
/// assert!(e.position < 1e-3 && !e.flagged && e.reference_order == 6);
/// ```
pub fn deflect_error(
    flexure: &SpatialFlexure,
    load: &SpatialLoad,
    alpha: &[f64],
    target: &Accuracy,
) -> Result<ErrorEstimate> {
    target.validate()?;
    let reference = reference(flexure, alpha)?;
    let mut data = SpatialStatics::new(&reference);
    let start = padded(flexure, alpha, reference.orders());
    let settings = Default::default();
    if correct(&reference, load, &start, &mut data, &settings).is_err() {
        deflect(&reference, load, &mut data, &settings)?;
    }
    let exact = data.alpha().to_vec();
    Ok(against((flexure, alpha), (&reference, &exact), target))
}

/// The estimate of the answer `alpha` of `flexure` against the reference
/// `reference` at `exact`: their tips (root frame) and peak curvature changes compared.
pub(super) fn against(
    (flexure, alpha): (&SpatialFlexure, &[f64]),
    (reference, exact): (&SpatialFlexure, &[f64]),
    target: &Accuracy,
) -> ErrorEstimate {
    let (ra, pa) = spatial_flexure::pose_root_tip(flexure, alpha);
    let (rb, pb) = spatial_flexure::pose_root_tip(reference, exact);
    let position = (pa - pb).norm();
    let angle = rotation_angle(&ra, &rb);
    let (model_peak, exact_peak) = (peak_curvature(flexure, alpha), peak_curvature(reference, exact));
    let curvature = (model_peak - exact_peak).abs();
    ErrorEstimate {
        position,
        angle,
        stress: None,
        curvature,
        peak: if exact_peak > 0.0 { curvature / exact_peak } else { 0.0 },
        flagged: position > target.position * flexure.length()
            || angle > target.angle
            || curvature > target.stress * exact_peak,
        reference_order: reference.orders().into_iter().max().unwrap_or(0),
        reference_quadrature: reference.subintervals(),
        exact: false,
    }
}

/// The highest order `--order auto` raises a spatial component to: 32
/// each, 96 coordinates, whose Hessian pass is already some thousand times
/// the default's.
pub const MAX_AUTO_ORDER: usize = 32;

/// How far `e` is from `target`, as the largest of its ratios: position
/// over `target.position`·`length`, angle over `target.angle`, the peak
/// curvature's relative change over `target.stress`; above 1 is flagged.
fn miss(e: &ErrorEstimate, target: &Accuracy, length: f64) -> f64 {
    (e.position / (target.position * length)).max(e.angle / target.angle).max(e.peak / target.stress)
}

/// The flexure of `flexure`'s length, section and rest shape (padded with
/// zeros) at `orders` and `subintervals`.
fn configured(flexure: &SpatialFlexure, orders: [usize; 3], subintervals: usize) -> Result<SpatialFlexure> {
    SpatialFlexure::new(flexure.length(), flexure.section().clone(), orders)?
        .with_rest(&padded(flexure, flexure.rest(), orders))?
        .with_subintervals(subintervals)
}

/// The lowest orders, and at them the fewest Magnus subintervals, whose
/// [`deflect`] answer under `load` meets `target`, discretization included
/// (the cheapest configuration along the orders tried), with that answer's
/// flexure (its [`SpatialFlexure::orders`] and
/// [`SpatialFlexure::subintervals`] are the configuration picked), its
/// coordinates and its estimate; as [`crate::estimate::deflect_auto`] for
/// the planar flexure.
///
/// From `flexure`'s orders $n$, raised as its [`reference()`]'s,
/// $n \to \min(\max(2n, n + 3), 32)$, each order tries the subintervals
/// $M = 1, 2, 4, 8, \dots$ up to the power of two at or above its default
/// $M_0(n)$ ([`SpatialFlexure::default_subintervals`]), and answers the
/// first whose estimate ([`deflect_error`], against a model of raised
/// orders and at least $2M$ subintervals, so the answer's discretization
/// error shows in it) is within `target`. An order stops doubling $M$ once
/// a doubling gains less than a factor 2 in the estimate (the order's
/// truncation then dominates), and the next order starts at the last $M$
/// that gained (at fixed $M$ the discretization error grows with the order).
/// A solve that fails below the last $M$ counts as a miss; at the last its
/// error is returned. At most 5 orders and 9 subinterval counts each (1 to
/// 256 at orders 32); `flexure`'s own subintervals are not used.
/// Errors, saying how far off it still was, if orders [`MAX_AUTO_ORDER`]
/// miss it.
///
/// # Example
/// ```
/// use flexure::section::SpatialSection;
/// use flexure::estimate::{Accuracy, spatial::deflect_auto};
/// use flexure::spatial::{SpatialFlexure, SpatialLoad};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(0.8, 1.0, 1.0).unwrap(), [2, 2, 2]).unwrap();
/// let load = SpatialLoad { moment: [0.0; 3], force: [0.0, 2.0, 2.0] };
/// let (used, _, e) = deflect_auto(&f, &load, &Default::default()).unwrap();
/// assert!(!e.flagged && used.orders()[2] > 2);
/// // A tighter target takes more subintervals as well as a higher order.
/// let tight = Accuracy { position: 1e-7, angle: 1e-7, stress: 1e-4, ..Default::default() };
/// let (finer, _, e) = deflect_auto(&f, &load, &tight).unwrap();
/// assert!(!e.flagged && e.position < 1e-7 && finer.subintervals() > used.subintervals());
/// ```
pub fn deflect_auto(
    flexure: &SpatialFlexure,
    load: &SpatialLoad,
    target: &Accuracy,
) -> Result<(SpatialFlexure, Vec<f64>, ErrorEstimate)> {
    target.validate()?;
    let mut orders = flexure.orders();
    let mut start = 1;
    // Bounded: every pass raises each order by at least 3 until the cap, and
    // each pass doubles M at most up to its default's power of two.
    loop {
        let last = SpatialFlexure::default_subintervals(orders).next_power_of_two();
        let mut m = start.min(last);
        // The last answer tried at these orders and how far it missed.
        let mut tried: Option<(SpatialFlexure, ErrorEstimate, f64)> = None;
        let (f, e) = loop {
            let f = configured(flexure, orders, m)?;
            let mut data = SpatialStatics::new(&f);
            match deflect(&f, load, &mut data, &Default::default()) {
                Ok(_) => {
                    let alpha = data.alpha().to_vec();
                    let e = deflect_error(&f, load, &alpha, target)?;
                    if !e.flagged {
                        return Ok((f, alpha, e));
                    }
                    let now = miss(&e, target, f.length());
                    let stalled = tried.as_ref().is_some_and(|(_, _, before)| now > before / 2.0);
                    if stalled || m >= last {
                        // The next orders start where these last gained.
                        start = if stalled { m / 2 } else { m };
                        break (f, e);
                    }
                    tried = Some((f, e, now));
                }
                Err(error) if m >= last => return Err(error),
                Err(_) => {}
            }
            m *= 2;
        };
        if orders.iter().all(|&n| n >= MAX_AUTO_ORDER) {
            let value = format!(
                "auto (orders {:?} at {} subintervals are estimated {:.3} % of L off in tip position and {:.3}° in tip rotation)",
                f.orders(),
                f.subintervals(),
                100.0 * e.position / f.length(),
                e.angle.to_degrees()
            );
            return Err(crate::Error::invalid(
                "order",
                value,
                "even orders 32 miss the accuracy target: loosen --accuracy or reduce the load",
            ));
        }
        orders = orders.map(|n| (2 * n).max(n + 3).min(MAX_ORDER).min(MAX_AUTO_ORDER.max(n)));
    }
}
