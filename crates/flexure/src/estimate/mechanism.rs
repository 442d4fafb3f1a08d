//! Error estimates of a mechanism's eigenvalue answers, in either dimension:
//! its buckling load factor ([`buckle_error`], [`buckle_auto`]) and natural
//! frequencies ([`mechanism_modes_error`], [`mechanism_modes_auto`]), each
//! against the same analysis of the reference mechanism
//! ([`reference_mechanism`]), every flexure joint refined about its
//! coordinates, as the relative change $\lvert\lambda - \lambda_r\rvert/\lambda_r$
//! flagged against [`Accuracy::eigenvalue`].
//!
//! What differs between the plane and space is the flexure's refinement
//! ([`Refined`], implemented for [`Planar`] and [`Spatial`] side by side
//! below): the planar reference raises the order and the Gauss points
//! ([`super::eigen_reference`]), the spatial one each
//! component's order and the Magnus subintervals
//! ([`reference`](super::spatial::reference)); both go to order 32 at the
//! cap, where more points alone would report a false 0.

use super::accuracy::{Accuracy, ErrorEstimate};
use super::eigen::reference_values;
use super::refinement::{eigen_reference, refined};
use super::value::ValueEstimate;
use crate::dynamics::Modes;
use crate::error::Result;
use crate::flexure::MAX_ORDER;
use crate::mechanism::buckling::Buckling;
use crate::mechanism::{Dimension, Mechanism};
use crate::solver::Settings;
use crate::space::{Planar, Spatial};

/// What a mechanism's eigenvalue estimate needs of its dimension: the
/// flexure's reference and its next automatic order; the analyses it
/// estimates are the generic ones.
pub trait Refined: crate::dynamics::Dynamics {
    /// The reference of `f` for an eigenvalue answer about the shape `alpha`.
    fn eigen_reference(f: &Self::Flexure, alpha: &[f64]) -> Result<Self::Flexure>;
    /// A reference's (order, count) as the estimate reports it: (order,
    /// Gauss points) in the plane, (largest order, subintervals) in space.
    fn refinement(r: &Self::Flexure) -> (usize, usize);
    /// `f` of `order = "auto"` raised, given its coordinates `alpha` and its
    /// reference's [`refinement`](Refined::refinement); `None` at the cap.
    fn raised(f: &Self::Flexure, alpha: &[f64], reference: (usize, usize)) -> Option<Result<Self::Flexure>>;
    /// The estimate of `f` at `alpha` against the reference `r` at `exact`
    /// of the same joint: their tip poses in the joint's root frame
    /// compared, and their peaks along it.
    fn against(f: &Self::Flexure, alpha: &[f64], r: &Self::Flexure, exact: &[f64], target: &Accuracy) -> ErrorEstimate;
    /// `m` with flexure joints replaced ([`Mechanism::with_flexures`]).
    fn with_flexures(
        m: &Mechanism<Self>,
        refine: impl FnMut(usize, &Self::Flexure) -> Result<Option<Self::Flexure>>,
    ) -> Result<Mechanism<Self>>;
}

impl Refined for Planar {
    fn eigen_reference(f: &crate::Flexure, alpha: &[f64]) -> Result<crate::Flexure> {
        eigen_reference(f, alpha)
    }

    fn refinement(r: &crate::Flexure) -> (usize, usize) {
        (r.order(), r.quadrature_points())
    }

    fn raised(f: &crate::Flexure, _: &[f64], (order, points): (usize, usize)) -> Option<Result<crate::Flexure>> {
        (f.order() < MAX_ORDER).then(|| refined(f, order.max(f.order() + 1).min(MAX_ORDER), points))
    }

    fn against(
        f: &crate::Flexure,
        alpha: &[f64],
        r: &crate::Flexure,
        exact: &[f64],
        target: &Accuracy,
    ) -> ErrorEstimate {
        let (a, b) = (crate::pose_root_tip(f, alpha), crate::pose_root_tip(r, exact));
        let position = (a.x - b.x).hypot(a.y - b.y);
        ErrorEstimate::new((f, alpha), (r, exact), position, (a.phi - b.phi).abs(), target)
    }

    fn with_flexures(
        m: &Mechanism,
        refine: impl FnMut(usize, &crate::Flexure) -> Result<Option<crate::Flexure>>,
    ) -> Result<Mechanism> {
        m.with_flexures(refine)
    }
}

impl Refined for Spatial {
    fn eigen_reference(f: &crate::spatial::SpatialFlexure, alpha: &[f64]) -> Result<crate::spatial::SpatialFlexure> {
        super::spatial::eigen_reference(f, alpha)
    }

    fn refinement(r: &crate::spatial::SpatialFlexure) -> (usize, usize) {
        (r.orders().into_iter().max().unwrap_or(0), r.subintervals())
    }

    fn raised(
        f: &crate::spatial::SpatialFlexure,
        alpha: &[f64],
        _: (usize, usize),
    ) -> Option<Result<crate::spatial::SpatialFlexure>> {
        f.orders().iter().any(|n| *n < MAX_ORDER).then(|| super::spatial::reference(f, alpha))
    }

    fn against(
        f: &crate::spatial::SpatialFlexure,
        alpha: &[f64],
        r: &crate::spatial::SpatialFlexure,
        exact: &[f64],
        target: &Accuracy,
    ) -> ErrorEstimate {
        super::spatial::against((f, alpha), (r, exact), target)
    }

    fn with_flexures(
        m: &Mechanism<Spatial>,
        refine: impl FnMut(usize, &crate::spatial::SpatialFlexure) -> Result<Option<crate::spatial::SpatialFlexure>>,
    ) -> Result<Mechanism<Spatial>> {
        m.with_flexures(refine)
    }
}

/// Per flexure joint in joint order, its reference's [`Refined::refinement`].
pub type Refinements = Vec<(usize, usize)>;

/// `q` if it is `m`'s coordinates, else the rest shape.
fn coordinates_or_rest<'a, D: Dimension>(m: &Mechanism<D>, q: &'a [f64]) -> std::borrow::Cow<'a, [f64]> {
    if q.len() == m.dof() { q.into() } else { m.rest().into() }
}

/// Joint `j`'s coordinates in `q`.
fn joint_coordinates<'a, D: Dimension>(m: &Mechanism<D>, j: usize, q: &'a [f64]) -> &'a [f64] {
    let (offset, dof) = (m.joints[j].offset, m.joints[j].kind.joint().dof());
    &q[offset..offset + dof]
}

/// The reference mechanism: every flexure joint replaced by its
/// [`Refined::eigen_reference`] about its coordinates in `q` (the rest
/// shape when `q` is not the mechanism's), with its [`Refinements`].
///
/// # Example
/// ```
/// use flexure::estimate::reference_mechanism;
/// use flexure::mechanism::file::{from_toml, spatial_from_toml};
/// let joint = "[[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\n";
/// // Planar order 3 goes to order 6 with 6 + 6 = 12 Gauss points.
/// let (r, orders) = reference_mechanism(&from_toml(joint).unwrap(), &[]).unwrap();
/// assert_eq!((r.dof(), orders), (6, vec![(6, 12)]));
/// // Spatial orders [3, 3, 3] go to [6, 6, 6] with 4·(6 − 1) = 20 subintervals.
/// let (r, orders) = reference_mechanism(&spatial_from_toml(&format!("dimension = 3\n{joint}")).unwrap(), &[]).unwrap();
/// assert_eq!((r.dof(), orders), (18, vec![(6, 20)]));
/// ```
pub fn reference_mechanism<D: Refined>(m: &Mechanism<D>, q: &[f64]) -> Result<(Mechanism<D>, Refinements)> {
    let q = coordinates_or_rest(m, q);
    let mut orders = Vec::new();
    let reference = D::with_flexures(m, |j, f| {
        let r = D::eigen_reference(f, joint_coordinates(m, j, &q))?;
        orders.push(D::refinement(&r));
        Ok(Some(r))
    })?;
    Ok((reference, orders))
}

/// Each flexure joint's estimate, in joint order, for an equilibrium `s`
/// of `m` that touches its geoms: a joint alone under the load at its tip
/// would miss the contact forces along its span, so the whole mechanism is
/// solved again with every flexure joint refined ([`reference_mechanism`]),
/// under the answer's loads, contacts and all, and each joint compared with its reference
/// ([`Refined::against`]). Contact concentrates curvature where it
/// touches; the refined model resolves it better, and the estimate shows
/// how far the answer is from it.
///
/// # Example
/// ```
/// use flexure::estimate::{Accuracy, contact_estimates};
/// use flexure::mechanism::{file::from_toml, statics::{Settings, solve}};
/// // A tip moment presses a strip's tip onto a floor.
/// let m = from_toml("[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\norder = 6\n\
///     [[force]]\nbody = \"tip\"\nmoment = -0.1\n\
///     [[geom]]\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n").unwrap();
/// let s = solve(&m, &Settings::default()).unwrap();
/// assert_eq!(s.contacts.len(), 1);
/// let e = &contact_estimates(&m, &s, &Accuracy::default()).unwrap()[0];
/// assert!(!e.flagged && e.position < 1e-9 && e.reference_order == 12);
/// ```
pub fn contact_estimates<D: Refined>(
    m: &Mechanism<D>,
    s: &crate::mechanism::statics::Solution<D>,
    target: &Accuracy,
) -> Result<Vec<ErrorEstimate>> {
    target.validate()?;
    let (reference, _) = reference_mechanism(m, &s.q)?;
    // Under the answer's own loads (a sweep's value), not the file's; with
    // friction, along the answer's own path, which it remembers.
    let rough = crate::mechanism::contact::pairs(m).iter().any(|p| m.geoms[p.geom].friction > 0.0);
    let path = if rough { &s.path[..] } else { &[] };
    let mut work = crate::mechanism::statics::Workspace::new(&reference);
    let (mut exact, mut from) = (None, None);
    for loads in path.iter().chain([&s.loads]) {
        let (solution, next) = crate::mechanism::statics::follow_touching(
            &reference,
            from.as_ref(),
            loads,
            &Settings::default(),
            &mut work,
        )?;
        (exact, from) = (Some(solution), Some(next));
    }
    let exact = exact.expect("the answer's own loads at least");
    let flexures = m.joints.iter().zip(&reference.joints).filter_map(|(a, b)| Some((a, a.kind.flexure()?, b)));
    flexures
        .map(|(joint, f, refined)| {
            let r = refined.kind.flexure().expect("a flexure's reference is a flexure");
            let alpha = &s.q[joint.offset..joint.offset + joint.kind.joint().dof()];
            let exact = &exact.q[refined.offset..refined.offset + refined.kind.joint().dof()];
            Ok(D::against(f, alpha, r, exact, target))
        })
        .collect()
}

/// The next mechanism of an automatic order: each flexure joint of
/// `order = "auto"` below the cap raised ([`Refined::raised`]) about its
/// coordinates in `q` (the rest shape when `q` is not the mechanism's),
/// given its reference's `orders`; `None` when no joint can be raised.
fn raised<D: Refined>(m: &Mechanism<D>, q: &[f64], orders: &[(usize, usize)]) -> Result<Option<Mechanism<D>>> {
    let every: Vec<_> = orders.iter().map(|o| Some((q, *o))).collect();
    raise_auto(m, &every)
}

/// What [`raise_auto`] is asked of one flexure joint: nothing, or the
/// coordinates of the mechanism to raise it about and its reference's
/// [`Refined::refinement`].
pub type Asked<'a> = Option<(&'a [f64], (usize, usize))>;

/// The next mechanism of an automatic order, raising only the joints that
/// ask: per flexure joint in joint order, `None` to leave it, or the
/// coordinates of `m` it is raised about (the rest shape when they are not
/// the mechanism's) and its reference's [`Refined::refinement`]; each such
/// joint of `order = "auto"` below the cap is raised ([`Refined::raised`]),
/// a joint of a fixed order never. `None` when no joint was raised. Each
/// raise is a strict one (the order grows by at least one, up to 64), so a
/// loop that raises until this answers `None` ends.
///
/// # Example
/// ```
/// use flexure::estimate::raise_auto;
/// use flexure::mechanism::file::from_toml;
/// let two = "[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b\"\nlength = 1.0\nei = 1.0\norder = \"auto\"\n\
///     [[joint]]\nname = \"c\"\nkind = \"flexure\"\nparent = \"b\"\nchild = \"d\"\nlength = 1.0\nei = 1.0\norigin = [1.0, 0.0, 0.0]\norder = \"auto\"\n";
/// let m = from_toml(two).unwrap();
/// // Only the second asks: it goes to its reference's order 6; the first stays at 3.
/// let next = raise_auto(&m, &[None, Some((&[][..], (6, 12)))]).unwrap().unwrap();
/// assert_eq!(next.joints[1].kind.flexure().unwrap().order(), 6);
/// assert_eq!(next.joints[0].kind.flexure().unwrap().order(), 3);
/// // Neither asks: nothing to raise.
/// assert!(raise_auto(&m, &[None, None]).unwrap().is_none());
/// ```
pub fn raise_auto<D: Refined>(m: &Mechanism<D>, wanted: &[Asked<'_>]) -> Result<Option<Mechanism<D>>> {
    let (mut k, mut any) = (0, false);
    let next = D::with_flexures(m, |j, f| {
        let asked = wanted.get(k).copied().flatten();
        k += 1;
        let Some((q, reference)) = asked.filter(|_| m.joints[j].auto_order) else { return Ok(None) };
        let q = coordinates_or_rest(m, q);
        let Some(next) = D::raised(f, joint_coordinates(m, j, &q), reference) else { return Ok(None) };
        any = true;
        next.map(Some)
    })?;
    Ok(any.then_some(next))
}

/// The error of a mechanism's buckling answer `b`
/// ([`crate::mechanism::buckling::buckle`] in the plane): the load factor
/// of the reference mechanism ([`reference_mechanism`] about the rest
/// shape, where buckling is taken).
///
/// # Example
/// ```
/// use flexure::{estimate, mechanism::{buckling::buckle, file::from_toml, statics::Settings}};
/// // A flexure column pushed along itself by 1 N: free-tip Euler load π²EI/(4L²) = 2.4674.
/// let m = from_toml(
///     "[[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\n\
///      [[force]]\nbody = \"tip\"\nat = [0.0, 0.0]\nforce = [-1.0, 0.0]\n",
/// )
/// .unwrap();
/// let b = buckle(&m, &Settings::default()).unwrap();
/// let e = estimate::buckle_error(&m, &b, &Settings::default(), &Default::default()).unwrap();
/// assert!((e.reference[0] / 2.4674 - 1.0).abs() < 1e-4 && e.reference_orders == vec![(6, 12)]);
/// ```
pub fn buckle_error<D: Refined>(
    m: &Mechanism<D>,
    b: &Buckling,
    settings: &Settings,
    target: &Accuracy,
) -> Result<ValueEstimate> {
    target.validate()?;
    let (reference, orders) = reference_mechanism(m, &[])?;
    let exact = crate::mechanism::buckling::buckle(&reference, settings)?.load_factor;
    Ok(ValueEstimate::new(&[b.load_factor], vec![exact], true, orders, target))
}

/// Buckling with its estimate ([`buckle_error`]), the flexure joints of
/// `order = "auto"` raised (each to its reference's order and points, or
/// orders and subintervals) until the estimate meets `target`, or none can
/// be raised further (then `flagged`). Returns the mechanism used, the
/// answer and its estimate; without such joints, the mechanism as given.
/// Bounded: each pass raises every automatic flexure, up to order 64.
///
/// # Example
/// ```
/// use flexure::estimate::{Accuracy, buckle_auto};
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
pub fn buckle_auto<D: Refined>(
    m: &Mechanism<D>,
    settings: &Settings,
    target: &Accuracy,
) -> Result<(Mechanism<D>, Buckling, ValueEstimate)> {
    let mut m = m.clone();
    loop {
        let b = crate::mechanism::buckling::buckle(&m, settings)?;
        let e = buckle_error(&m, &b, settings, target)?;
        if !e.flagged {
            return Ok((m, b, e));
        }
        match raised(&m, &[], &e.reference_orders)? {
            Some(next) => m = next,
            None => return Ok((m, b, e)),
        }
    }
}

/// The error of a mechanism's vibration modes answer
/// ([`crate::dynamics::mechanism::modes`] in the plane): the same analysis
/// (equilibrium under the loads, loaded stiffness, mass) of the reference
/// mechanism, every flexure refined about its coordinates at the
/// equilibrium ([`reference_mechanism`]), frequencies paired by rank, each
/// as $\lvert\omega_k - \omega_{r,k}\rvert/\omega_{r,k}$. A reference that
/// is unstable under the loads pairs no mode (then `flagged`).
///
/// # Example
/// ```
/// use flexure::dynamics::mechanism::modes;
/// use flexure::estimate::mechanism_modes_error;
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
/// let e = mechanism_modes_error(&m, &found, &Default::default(), &Default::default()).unwrap();
/// assert!(!e.flagged && e.reference.iter().any(|w| (w / (0.8f64 / (0.2 * 2e-4)).sqrt() - 1.0).abs() < 1e-8));
/// ```
pub fn mechanism_modes_error<D: Refined>(
    m: &Mechanism<D>,
    modes: &Modes,
    settings: &Settings,
    target: &Accuracy,
) -> Result<ValueEstimate> {
    target.validate()?;
    let (reference, orders) = reference_mechanism(m, &modes.coordinates)?;
    let count = modes.omega.len().max(1).min(reference.dof().max(1));
    let (omega, stable) = reference_values(crate::dynamics::mechanism::modes(&reference, settings, count))?;
    Ok(ValueEstimate::new(&modes.omega, omega, stable, orders, target))
}

/// Vibration modes with their estimate ([`mechanism_modes_error`]), the
/// flexure joints of `order = "auto"` raised as in [`buckle_auto`], each
/// about its coordinates at the equilibrium.
pub fn mechanism_modes_auto<D: Refined>(
    m: &Mechanism<D>,
    settings: &Settings,
    count: usize,
    target: &Accuracy,
) -> Result<(Mechanism<D>, Modes, ValueEstimate)> {
    let mut m = m.clone();
    loop {
        let modes = crate::dynamics::mechanism::modes(&m, settings, count)?;
        let e = mechanism_modes_error(&m, &modes, settings, target)?;
        if !e.flagged {
            return Ok((m, modes, e));
        }
        match raised(&m, &modes.coordinates, &e.reference_orders)? {
            Some(next) => m = next,
            None => return Ok((m, modes, e)),
        }
    }
}
