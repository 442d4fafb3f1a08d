//! Error estimates of a spatial mechanism: every flexure's at a solution
//! ([`flexure_errors`]), and its eigenvalue answers, the buckling load
//! factor ([`buckle_error`]) and the natural frequencies ([`modes_error`]),
//! as the planar mechanism's: the same analysis of the reference mechanism,
//! every spatial flexure joint refined ([`reference_mechanism`]).

use super::eigen::reference_values;
use super::spatial::{padded, reference};
use super::value::ValueEstimate;
use super::{Accuracy, ErrorEstimate, spatial::deflect_error};
use crate::dynamics::{Modes, spatial as spatial_dynamics};
use crate::error::Result;
use crate::flexure::MAX_ORDER;
use crate::mechanism::buckling::Buckling;
use crate::mechanism::buckling::buckle;
use crate::mechanism::spatial::SpatialMechanism;
use crate::mechanism::spatial::statics::flexure_loads;
use crate::mechanism::statics::Solution;
use crate::solver::Settings;
use crate::spatial::SpatialFlexure;

/// Each spatial flexure joint's error estimate at a solution: the flexure
/// under the tip wrench it carries ([`flexure_loads`]) against its own
/// refined reference ([`deflect_error`]), flagged against `target`, as the
/// planar mechanism's per-flexure estimates are. One entry per joint,
/// `None` for the other kinds.
///
/// # Example
/// ```
/// use flexure::estimate::spatial_mechanism::flexure_errors;
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
pub fn flexure_errors(
    m: &SpatialMechanism,
    s: &Solution<crate::space::Spatial>,
    target: &Accuracy,
) -> Result<Vec<Option<ErrorEstimate>>> {
    let loads = flexure_loads(m, s);
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

/// The reference for an eigenvalue answer of `flexure` about the shape
/// `alpha`: [`reference()`] (each order $n_c \to \min(\max(2n_c, n_c + 3), 64)$,
/// at least twice the subintervals), except that a component at the cap
/// $n_c = 64$ goes to order 32, as the planar
/// [`eigen_reference`](super::eigen_reference) does: more subintervals alone
/// would leave a straight flexure's answer unchanged and report a false 0.
fn eigen_reference(flexure: &SpatialFlexure, alpha: &[f64]) -> Result<SpatialFlexure> {
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

/// `q` if it is `m`'s coordinates, else the rest shape.
fn coordinates_or_rest<'a>(m: &SpatialMechanism, q: &'a [f64]) -> std::borrow::Cow<'a, [f64]> {
    if q.len() == m.dof() { q.into() } else { m.rest().into() }
}

/// The reference spatial mechanism: every spatial flexure joint replaced by
/// its refined reference ([`reference()`], at the cap as the planar
/// [`eigen_reference`](super::eigen_reference)) about its coordinates in `q`
/// (the rest shape when `q` is not the mechanism's), with, per flexure joint
/// in joint order, the reference's (largest order, subintervals).
///
/// # Example
/// ```
/// use flexure::estimate::spatial_mechanism::reference_mechanism;
/// use flexure::mechanism::spatial::{SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism};
/// use flexure::{section::SpatialSection, spatial::SpatialFlexure};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 2, 3]).unwrap();
/// let joint = SpatialJointSpec { name: "f".into(), kind: SpatialJointKind::Flexure(Box::new(f)), parent: 0, child: 1, origin: nalgebra::Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default() };
/// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), SpatialBody::massless("tip")], vec![joint], vec![], vec![], vec![], nalgebra::Vector3::zeros()).unwrap();
/// let (r, orders) = reference_mechanism(&m, &[]).unwrap();
/// // Orders [6, 5, 6] with 4·(6 − 1) = 20 subintervals: 17 coordinates.
/// assert_eq!((r.dof(), orders), (17, vec![(6, 20)]));
/// ```
pub fn reference_mechanism(m: &SpatialMechanism, q: &[f64]) -> Result<(SpatialMechanism, Vec<(usize, usize)>)> {
    let q = coordinates_or_rest(m, q);
    let q = &q[..];
    let mut orders = Vec::new();
    let reference = m.with_flexures(|j, f| {
        let o = m.joints[j].offset;
        let r = eigen_reference(f, &q[o..o + f.coordinates()])?;
        orders.push((r.orders().into_iter().max().unwrap_or(0), r.subintervals()));
        Ok(Some(r))
    })?;
    Ok((reference, orders))
}

/// The error of a spatial mechanism's [`buckle`] answer `b`: the load
/// factor $\lambda_r$ of the reference mechanism ([`reference_mechanism`]
/// about the rest shape, where buckling is taken), as the relative change
/// $\lvert\lambda - \lambda_r\rvert/\lambda_r$, flagged against
/// [`Accuracy::eigenvalue`], as the planar [`buckle_error`](super::buckle_error).
///
/// # Example
/// ```
/// use flexure::estimate::spatial_mechanism::buckle_error;
/// use flexure::mechanism::buckling::buckle;
/// use flexure::mechanism::spatial::{SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism, SpatialPointLoad};
/// use flexure::{section::SpatialSection, spatial::SpatialFlexure};
/// use nalgebra::{Isometry3, Point3, Vector3, Vector6};
/// // A column (L = 1, EI = 1 about both axes) pushed along itself by 1 N:
/// // the free tip's Euler load π²EI/(4L²) = 2.4674.
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(0.8, 1.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
/// let joint = SpatialJointSpec { name: "f".into(), kind: SpatialJointKind::Flexure(Box::new(f)), parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default() };
/// let push = SpatialPointLoad { name: "p".into(), body: 1, at: Point3::origin(), wrench: Vector6::new(0.0, 0.0, 0.0, -1.0, 0.0, 0.0) };
/// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), SpatialBody::massless("tip")], vec![joint], vec![], vec![push], vec![], Vector3::zeros()).unwrap();
/// let b = buckle(&m, &Default::default()).unwrap();
/// let e = buckle_error(&m, &b, &Default::default(), &Default::default()).unwrap();
/// let euler = std::f64::consts::PI.powi(2) / 4.0;
/// // Orders 3 are 1.4e-4 high; the estimate is that error to within the reference's own (0.03 % of it).
/// let truth = b.load_factor / euler - 1.0;
/// assert!((e.reference[0] / euler - 1.0).abs() < 1e-4 && (e.relative[0].unwrap() / truth - 1.0).abs() < 1e-3 && !e.flagged);
/// ```
pub fn buckle_error(
    m: &SpatialMechanism,
    b: &Buckling,
    settings: &Settings,
    target: &Accuracy,
) -> Result<ValueEstimate> {
    target.validate()?;
    let (reference, orders) = reference_mechanism(m, &[])?;
    let exact = buckle(&reference, settings)?.load_factor;
    Ok(ValueEstimate::new(&[b.load_factor], vec![exact], true, orders, target))
}

/// The error of a spatial mechanism's [`modes`](spatial_dynamics::modes)
/// answer: the same analysis (equilibrium under the loads, loaded
/// stiffness, mass) of the reference mechanism, every spatial flexure
/// refined about its coordinates at the equilibrium
/// ([`reference_mechanism`]), frequencies paired by rank, each as
/// $\lvert\omega_k - \omega_{r,k}\rvert/\omega_{r,k}$; as the planar
/// [`mechanism_modes_error`](super::mechanism_modes_error). A reference
/// that is unstable under the loads pairs no mode (then `flagged`).
///
/// # Example
/// ```
/// use flexure::dynamics::spatial::modes;
/// use flexure::estimate::spatial_mechanism::modes_error;
/// use flexure::mechanism::spatial::{SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism};
/// use flexure::{section::SpatialSection, spatial::SpatialFlexure};
/// use nalgebra::{Isometry3, Matrix3, Point3, Vector3};
/// // A massless rod (L = 0.2 m, GJ = 0.8 N·m²) carrying a disc of 2e-4 kg·m² about
/// // its axis twists at ω = √(GJ/(L·I)) = 141.42 rad/s; the model is exact.
/// let rod = SpatialFlexure::new(0.2, SpatialSection::uniform(0.8, 1.5, 2.5).unwrap(), [3, 3, 3]).unwrap();
/// let joint = SpatialJointSpec { name: "rod".into(), kind: SpatialJointKind::Flexure(Box::new(rod)), parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default() };
/// let disc = SpatialBody { name: "disc".into(), mass: 0.3, com: Point3::origin(), inertia: Matrix3::from_diagonal(&Vector3::new(2e-4, 1e-4, 1e-4)) };
/// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), disc], vec![joint], vec![], vec![], vec![], Vector3::zeros()).unwrap();
/// let found = modes(&m, &Default::default(), 5).unwrap();
/// let e = modes_error(&m, &found, &Default::default(), &Default::default()).unwrap();
/// assert!(!e.flagged && e.reference.iter().any(|w| (w / (0.8f64 / (0.2 * 2e-4)).sqrt() - 1.0).abs() < 1e-8));
/// ```
pub fn modes_error(
    m: &SpatialMechanism,
    modes: &Modes,
    settings: &Settings,
    target: &Accuracy,
) -> Result<ValueEstimate> {
    target.validate()?;
    let (reference, orders) = reference_mechanism(m, &modes.coordinates)?;
    let count = modes.omega.len().max(1).min(reference.dof().max(1));
    let (omega, stable) = reference_values(spatial_dynamics::modes(&reference, settings, count))?;
    Ok(ValueEstimate::new(&modes.omega, omega, stable, orders, target))
}

/// The next mechanism of an automatic order: each spatial flexure joint of
/// `order = "auto"` ([`JointSpec::auto_order`](crate::mechanism::JointSpec::auto_order)) with a component
/// below the cap replaced by its reference about its coordinates in `q`
/// (the rest shape when `q` is not the mechanism's), as the planar
/// mechanism raises its own; `None` when no joint can be raised.
fn raised(m: &SpatialMechanism, q: &[f64]) -> Result<Option<SpatialMechanism>> {
    let q = coordinates_or_rest(m, q);
    let q = &q[..];
    let mut any = false;
    let next = m.with_flexures(|j, f| {
        if !m.joints[j].auto_order || f.orders().iter().all(|n| *n >= MAX_ORDER) {
            return Ok(None);
        }
        any = true;
        let o = m.joints[j].offset;
        reference(f, &q[o..o + f.coordinates()]).map(Some)
    })?;
    Ok(any.then_some(next))
}

/// [`buckle`] with its estimate ([`buckle_error`]), the spatial flexure
/// joints of `order = "auto"` raised (each to its reference's orders and
/// subintervals) until the estimate meets `target`, or none can be raised
/// further (then `flagged`), as the planar
/// [`buckle_auto`](super::buckle_auto). Returns the mechanism used, the
/// answer and its estimate; without such joints, the mechanism as given.
/// Bounded: each pass raises every automatic component by at least 3, up to 64.
///
/// # Example
/// ```
/// use flexure::estimate::{Accuracy, spatial_mechanism::buckle_auto};
/// use flexure::mechanism::file::spatial_from_toml;
/// // A column (L = 1, EI = 1) pushed along itself by 1 N: Euler's π²/4.
/// let m = spatial_from_toml("dimension = 3\n[[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"ground\"\n\
///     child = \"tip\"\nlength = 1.0\nei = 1.0\norder = \"auto\"\n\
///     [[force]]\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nforce = [-1.0, 0.0, 0.0]\n").unwrap();
/// let tight = Accuracy { eigenvalue: 1e-6, ..Default::default() };
/// let (used, b, e) = buckle_auto(&m, &Default::default(), &tight).unwrap();
/// let euler = std::f64::consts::PI.powi(2) / 4.0;
/// assert!(!e.flagged && (b.load_factor / euler - 1.0).abs() < 1e-6);
/// assert!(used.joints[0].kind.flexure().unwrap().orders()[0] > 3);
/// ```
pub fn buckle_auto(
    m: &SpatialMechanism,
    settings: &Settings,
    target: &Accuracy,
) -> Result<(SpatialMechanism, Buckling, ValueEstimate)> {
    let mut m = m.clone();
    loop {
        let b = buckle(&m, settings)?;
        let e = buckle_error(&m, &b, settings, target)?;
        if !e.flagged {
            return Ok((m, b, e));
        }
        match raised(&m, &[])? {
            Some(next) => m = next,
            None => return Ok((m, b, e)),
        }
    }
}

/// [`modes`](spatial_dynamics::modes) with its estimate ([`modes_error`]),
/// the spatial flexure joints of `order = "auto"` raised as in
/// [`buckle_auto`], each about its coordinates at the equilibrium.
pub fn modes_auto(
    m: &SpatialMechanism,
    settings: &Settings,
    count: usize,
    target: &Accuracy,
) -> Result<(SpatialMechanism, Modes, ValueEstimate)> {
    let mut m = m.clone();
    loop {
        let modes = spatial_dynamics::modes(&m, settings, count)?;
        let e = modes_error(&m, &modes, settings, target)?;
        if !e.flagged {
            return Ok((m, modes, e));
        }
        match raised(&m, &modes.coordinates)? {
            Some(next) => m = next,
            None => return Ok((m, modes, e)),
        }
    }
}
