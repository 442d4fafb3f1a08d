//! Error estimates for model answers, and the order that meets a target.
//!
//! The model's two approximations are the truncated curvature basis (order
//! $N$) and the quadrature of the tip position (Eqs. 14–15, $Q$ points). An
//! answer's error is estimated against a **reference model** that refines
//! both: order $N_r = \min(2N, 64)$ (at least $N + 3$) and a rule of
//! $Q_r = N_r + 6 + \lceil V\rceil$ points, where $V = \sum_i|\alpha_i|$
//! bounds the total turning $\int_0^L|\phi^{\prime}|\thinspace ds$ of the answer's
//! shape ([`turning`]), so that $\cos\phi$ and $\sin\phi$ are integrated to
//! rounding however far the flexure winds.
//! The reference starts from the answer (its coordinates padded with zeros:
//! the shifted-Legendre basis is nested) and one Newton solve at the full
//! load corrects it, which costs a few evaluations at the higher order,
//! less than the continuation that produced the answer. The estimate is the
//! distance between the two answers: the error of the answer, to within the
//! reference's own error, which is far smaller wherever the basis converges.
//!
//! **At the order cap** ([`MAX_ORDER`] = 64) no model refines the answer's
//! order, and more points alone would leave a smooth answer unchanged: the
//! model against itself, an estimate of 0 whatever its true error (a steep
//! taper of $EI$ converges slowly in the basis). So an estimate at the cap
//! is never against order 64 itself. One rule: the reference is the most
//! independent one the library has for that answer. A tip load's answer
//! ([`deflect_error`], [`joint_error`], the last try of [`deflect_auto`])
//! is estimated against the exact elastica with the flexure's $EI(s)$
//! ([`crate::reference::elastica`], `ErrorEstimate::exact`), so the estimate
//! is its true error; answers the elastica module does not solve as such
//! (tendon joints, connections, buckling loads and frequencies,
//! [`eigen_reference`]) against order 32, whose change overstates the
//! order-64 answer's error where the basis converges, and flags it where it
//! does not.
//!
//! [`Estimator`] keeps the reference model and its buffers between
//! estimates of one flexure (Model and Data), so a repeated estimate costs
//! the reference's Newton solve and the peaks, not the reference's tables.

pub mod spatial;

use crate::buckling::{Buckling, TipConstraint, buckling_load};
use crate::dynamics::{self, Body, Modes};
use crate::error::{Error, Result, positive};
use crate::joint::{Basis, Flexure, MAX_ORDER};
use crate::kinematics::{self, Pose, backbone};
use crate::mechanism::{
    self, Mechanism, buckling::Buckling as MechanismBuckling, statics::Settings as MechanismSettings,
};
use crate::quadrature::MAX_POINTS;
use crate::statics::{Settings, Statics, TipLoad, deflect};
use crate::stress::{peak_curvature_legendre, peak_stress};
use crate::tendon::{Tendon, TendonData, pull};

/// The accuracy an answer must meet: tip position within `position` × L,
/// tip angle within `angle` rad, and peak bending stress (or, for a section
/// without thickness, peak curvature change) within `stress` of itself;
/// a buckling load or natural frequency within `eigenvalue` of itself.
/// The default is the paper's 1 % of L and 1°, 1 % of the peak and 1 % of
/// the value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Accuracy {
    /// Position tolerance as a fraction of the flexure's length.
    pub position: f64,
    /// Angle tolerance (rad).
    pub angle: f64,
    /// Peak stress tolerance as a fraction of the peak.
    pub stress: f64,
    /// Tolerance of an eigenvalue answer (a buckling load or factor, a
    /// natural frequency) as a fraction of itself.
    pub eigenvalue: f64,
}

impl Default for Accuracy {
    fn default() -> Self {
        Self { position: 0.01, angle: 1f64.to_radians(), stress: 0.01, eigenvalue: 0.01 }
    }
}

impl Accuracy {
    /// Checks every tolerance: finite and greater than zero.
    pub fn validate(&self) -> Result<()> {
        positive("accuracy", self.position)?;
        positive("accuracy", self.angle)?;
        positive("accuracy", self.stress)?;
        positive("accuracy", self.eigenvalue)?;
        Ok(())
    }
}

/// An answer's estimated error, and whether it misses the [`Accuracy`].
///
/// It serializes as the one shape every answer prints (the CLI's
/// `error_estimate`, batch rows included): `position`, `angle`, `stress`
/// (only with a thickness), `curvature`, `reference_order`,
/// `reference_quadrature` and `reference` (`"model"` or `"elastica"`, from
/// [`exact`](Self::exact)); `peak` and `flagged` are verdicts, printed
/// beside it.
///
/// # Example
///
/// ```
/// use flexure::estimate::{Accuracy, deflect_error};
/// use flexure::{Flexure, Statics, TipLoad, deflect};
///
/// let f = Flexure::new(1.0, 1.0, 3)?;
/// let load = TipLoad { moment: 0.5, fx: 0.0, fy: 0.2 };
/// let mut data = Statics::new(&f);
/// deflect(&f, &load, &mut data, &Default::default())?;
/// let e = deflect_error(&f, &load, data.alpha(), &Accuracy::default())?;
/// // Against the refined model, without a thickness: no stress is printed.
/// assert!(!e.exact && e.reference_order > 3 && e.stress.is_none());
/// fn printable(_: &impl serde::Serialize) {}
/// printable(&e);
/// # Ok::<(), flexure::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ErrorEstimate {
    /// Estimated position error (m).
    pub position: f64,
    /// Estimated angle error (rad).
    pub angle: f64,
    /// Estimated error of the peak bending stress (Pa); `None` for a
    /// section without thickness.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress: Option<f64>,
    /// Estimated error of the peak curvature change (1/m).
    pub curvature: f64,
    /// The reported peak's estimated error as a fraction of the peak:
    /// stress with a thickness, curvature change without (0 when unbent).
    #[serde(skip)]
    pub peak: f64,
    /// Whether the estimate exceeds the accuracy target.
    #[serde(skip)]
    pub flagged: bool,
    /// Order of the reference model (0 when the reference is the exact elastica).
    pub reference_order: usize,
    /// Quadrature points of the reference model (0 when the reference is the exact elastica).
    pub reference_quadrature: usize,
    /// Whether the reference is the exact elastica ([`crate::reference::elastica`]) rather than
    /// a refined model: so at order [`MAX_ORDER`], which no model refines (see the module docs).
    #[serde(rename = "reference", serialize_with = "reference_name")]
    pub exact: bool,
}

/// What an estimate was made against, as it is printed.
fn reference_name<S: serde::Serializer>(exact: &bool, s: S) -> std::result::Result<S::Ok, S::Error> {
    s.serialize_str(if *exact { "elastica" } else { "model" })
}

impl ErrorEstimate {
    /// The estimate of the answer `alpha` of `flexure` whose tip is off by
    /// `position` and `angle` from the reference's answer `exact`: the peaks
    /// are compared here, along the whole flexure.
    fn new(
        (flexure, alpha): (&Flexure, &[f64]),
        (reference, exact): (&Flexure, &[f64]),
        position: f64,
        angle: f64,
        target: &Accuracy,
    ) -> Self {
        let peaks = (peak_curvature_legendre(reference, exact), peak_stress(reference, exact).map(|p| p.value));
        let size = (reference.order(), reference.quadrature_points());
        Self::from_peaks((flexure, alpha), peaks, position, angle, size, target)
    }

    /// The estimate of the answer `alpha` of `flexure` against a reference
    /// whose peak curvature change and peak stress are `exact_peaks`, of
    /// (order, quadrature) `size` ((0, 0): the exact elastica).
    fn from_peaks(
        (flexure, alpha): (&Flexure, &[f64]),
        (exact_peak, exact_stress): (f64, Option<f64>),
        position: f64,
        angle: f64,
        size: (usize, usize),
        target: &Accuracy,
    ) -> Self {
        let model_peak = peak_curvature_legendre(flexure, alpha);
        let curvature = (model_peak - exact_peak).abs();
        let stress = match (peak_stress(flexure, alpha), exact_stress) {
            (Some(a), Some(b)) => Some(((a.value - b).abs(), b)),
            _ => None,
        };
        // The peak that is reported: stress with a thickness, else curvature.
        let (peak_error, peak) = stress.unwrap_or((curvature, exact_peak));
        Self {
            position,
            angle,
            stress: stress.map(|s| s.0),
            curvature,
            peak: if peak > 0.0 { peak_error / peak } else { 0.0 },
            flagged: position > target.position * flexure.length()
                || angle > target.angle
                || peak_error > target.stress * peak,
            reference_order: size.0,
            reference_quadrature: size.1,
            exact: size == (0, 0),
        }
    }
}

/// A bound on the total turning $\int_0^1|\partial_t\phi|\thinspace dt$
/// (rad) of the shape `alpha`: $\sum_i|\alpha_i|$, since
/// $\partial_t\psi_i = \tilde P_{i-1}$ and $|\tilde P_{i-1}| \le 1$ on
/// $[0, 1]$ (exact for an arc). It only sizes the reference's quadrature,
/// where an overestimate costs a few points and an underestimate accuracy.
pub fn turning(alpha: &[f64]) -> f64 {
    alpha.iter().map(|a| a.abs()).sum()
}

/// The reference model for an answer `alpha` of `flexure` (see the module docs).
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
/// // A circle turned by 20 rad needs many more points than the model's 5.
/// let r = flexure::estimate::reference(&f, &[20.0, 0.0, 0.0]).unwrap();
/// assert_eq!((r.order(), r.quadrature_points()), (6, 32));
/// ```
pub fn reference(flexure: &Flexure, alpha: &[f64]) -> Result<Flexure> {
    let (order, points) = reference_size(flexure, alpha)?;
    refined(flexure, order, points)
}

/// The (order, quadrature points) of [`reference()`] for `alpha`.
fn reference_size(flexure: &Flexure, alpha: &[f64]) -> Result<(usize, usize)> {
    legendre(flexure)?;
    let n = flexure.order();
    let order = (2 * n).max(n + 3).min(MAX_ORDER);
    let v = turning(alpha);
    let points = (order as f64 + 6.0 + v.ceil()).min(MAX_POINTS as f64) as usize;
    Ok((order, points))
}

fn legendre(flexure: &Flexure) -> Result<()> {
    if flexure.basis() != Basis::Legendre {
        return Err(Error::invalid("basis", "segments", "error estimates are made for the Legendre model"));
    }
    Ok(())
}

/// `flexure` at another order and quadrature, its rest shape padded with zeros.
fn refined(flexure: &Flexure, order: usize, points: usize) -> Result<Flexure> {
    let mut kappa = flexure.rest().to_vec();
    kappa.resize(order, 0.0);
    Flexure::with_points(flexure.length(), flexure.ei(), order, points)?
        .with_rest(&kappa)?
        .with_section(flexure.section().clone())
}

fn padded(alpha: &[f64], order: usize) -> Vec<f64> {
    let mut a = alpha.to_vec();
    a.resize(order, 0.0);
    a
}

fn pose_error(a: &Pose, b: &Pose) -> (f64, f64) {
    ((a.x - b.x).hypot(a.y - b.y), (a.phi - b.phi).abs())
}

/// The error of a [`deflect`] answer `alpha` under `load`: the tip pose
/// against the reference model's equilibrium, corrected from `alpha` by
/// Newton at the full load (continuation from rest if that fails).
///
/// # Example
/// ```
/// use flexure::{deflect, estimate, Flexure, Statics, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let mut data = Statics::new(&f);
/// // A moment of 20 N·m winds the flexure 3 times round: 5 points cannot integrate it.
/// let load = TipLoad { moment: 20.0, fx: 0.0, fy: 0.0 };
/// deflect(&f, &load, &mut data, &Default::default()).unwrap();
/// let e = estimate::deflect_error(&f, &load, data.alpha(), &Default::default()).unwrap();
/// // The exact answer is the circle of radius 1/20 through the root: tip at (sin 20, 1 − cos 20)/20.
/// let exact = (20f64.sin() / 20.0, (1.0 - 20f64.cos()) / 20.0);
/// let p = data.pose_root_tip();
/// let truth = (p.x - exact.0).hypot(p.y - exact.1);
/// assert!(e.flagged && (e.position / truth - 1.0).abs() < 1e-6);
/// ```
pub fn deflect_error(flexure: &Flexure, load: &TipLoad, alpha: &[f64], target: &Accuracy) -> Result<ErrorEstimate> {
    Estimator::new().deflect_error(flexure, load, alpha, target)
}

/// The reusable pieces of [`deflect_error`] (a Model and its Data): the
/// reference model of the last flexure estimated, immutable once built, and
/// the buffers of its equilibrium. Estimating many answers of one flexure
/// with one `Estimator` builds the reference once (again only when an
/// answer turns so much further that the reference needs more quadrature
/// points, [`reference()`]); the numbers are those of [`deflect_error`].
///
/// # Example
/// ```
/// use flexure::{deflect, estimate::Estimator, Flexure, Statics, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let (mut data, mut estimator) = (Statics::new(&f), Estimator::new());
/// for fy in [1.0, 2.0, 3.0] {
///     let load = TipLoad { moment: 0.0, fx: 0.0, fy };
///     deflect(&f, &load, &mut data, &Default::default()).unwrap();
///     let e = estimator.deflect_error(&f, &load, data.alpha(), &Default::default()).unwrap();
///     let once = flexure::estimate::deflect_error(&f, &load, data.alpha(), &Default::default()).unwrap();
///     assert_eq!(e, once);
/// }
/// ```
#[derive(Debug, Clone, Default)]
pub struct Estimator {
    /// The flexure estimated last, its reference model and that model's buffers.
    cached: Option<(Flexure, Flexure, Statics)>,
    /// The answer padded to the reference's order: the start of its Newton solve.
    warm: Vec<f64>,
}

impl Estimator {
    /// An estimator with nothing built yet: the first estimate builds the reference.
    pub fn new() -> Self {
        Self::default()
    }

    /// The reference model for the answer `alpha` of `flexure` ([`reference()`]),
    /// built only when the last one was for another flexure or size, with its buffers.
    fn reference(&mut self, flexure: &Flexure, alpha: &[f64]) -> Result<(&Flexure, &mut Statics)> {
        let size = reference_size(flexure, alpha)?;
        let fits = self.cached.as_ref().is_some_and(|(source, reference, _)| {
            (reference.order(), reference.quadrature_points()) == size && source == flexure
        });
        if !fits {
            let reference = refined(flexure, size.0, size.1)?;
            let data = Statics::new(&reference);
            self.cached = Some((flexure.clone(), reference, data));
        }
        let (_, reference, data) = self.cached.as_mut().expect("built above");
        Ok((reference, data))
    }

    /// [`deflect_error`], reusing the reference while `flexure` is the same.
    pub fn deflect_error(
        &mut self,
        flexure: &Flexure,
        load: &TipLoad,
        alpha: &[f64],
        target: &Accuracy,
    ) -> Result<ErrorEstimate> {
        target.validate()?;
        flexure.check_coordinates("alpha", alpha)?;
        legendre(flexure)?;
        let model = kinematics::pose_root_tip(flexure, alpha);
        if flexure.order() >= MAX_ORDER {
            return exact_deflect_error(flexure, load, alpha, &model, target);
        }
        let mut warm = std::mem::take(&mut self.warm);
        let (reference, data) = self.reference(flexure, alpha)?;
        warm.clear();
        warm.extend_from_slice(alpha);
        warm.resize(reference.order(), 0.0);
        let settings = Settings::default();
        if crate::statics::correct(reference, load, &warm, data, &settings).is_err() {
            deflect(reference, load, data, &settings)?;
        }
        let (position, angle) = pose_error(&model, &data.pose_root_tip());
        let e = ErrorEstimate::new((flexure, alpha), (reference, data.alpha()), position, angle, target);
        self.warm = warm;
        Ok(e)
    }
}

/// [`deflect_error`] at the order cap, where no model refines the answer's
/// (more points alone would leave a smooth answer unchanged and report a
/// false 0): against the exact elastica with the flexure's $EI(s)$ and rest
/// shape, its tip pose and peaks along the flexure.
fn exact_deflect_error(
    flexure: &Flexure,
    load: &TipLoad,
    alpha: &[f64],
    model: &Pose,
    target: &Accuracy,
) -> Result<ErrorEstimate> {
    let (exact, trace) = crate::reference::elastica::deflect_traced(flexure, load, &Default::default())?;
    let peaks = (trace.peak_curvature()?.value, trace.peak_stress()?.map(|p| p.value));
    let (position, angle) = pose_error(model, &exact.pose);
    Ok(ErrorEstimate::from_peaks((flexure, alpha), peaks, position, angle, (0, 0), target))
}

/// The error of a tendon joint's answer `alpha` under `tension` (see [`deflect_error`]).
pub fn tendon_error(
    flexure: &Flexure,
    tendon: &Tendon,
    tension: f64,
    alpha: &[f64],
    target: &Accuracy,
) -> Result<ErrorEstimate> {
    target.validate()?;
    let reference = eigen_reference(flexure, alpha)?;
    let model = kinematics::pose_root_tip(flexure, alpha);
    let mut data = TendonData::new(&reference);
    let warm = padded(alpha, reference.order());
    let corrected = crate::tendon::correct(&reference, tendon, tension, &warm, &mut data);
    if corrected.is_err() {
        data = TendonData::new(&reference);
        pull(&reference, tendon, tension, &mut data)?;
    }
    let pose = kinematics::pose_root_tip(&reference, data.alpha());
    let (position, angle) = pose_error(&model, &pose);
    Ok(ErrorEstimate::new((flexure, alpha), (&reference, data.alpha()), position, angle, target))
}

/// The error of a [`crate::connect::connect`] answer `alpha` reaching
/// `target_pose`: the tip is exact by construction, so the error is the
/// shape's, the largest distance between the answer's backbone and the
/// reference model's (33 points, each integrated accurately).
pub fn connect_error(flexure: &Flexure, target_pose: &Pose, alpha: &[f64], target: &Accuracy) -> Result<ErrorEstimate> {
    target.validate()?;
    let reference = eigen_reference(flexure, alpha)?;
    let exact = crate::connect::connect(&reference, target_pose)?;
    let (a, b) = (backbone(flexure, alpha, 33), backbone(&reference, &exact.alpha, 33));
    let (position, angle) =
        a.iter().zip(&b).map(|(p, q)| pose_error(p, q)).fold((0.0_f64, 0.0_f64), |m, e| (m.0.max(e.0), m.1.max(e.1)));
    Ok(ErrorEstimate::new((flexure, alpha), (&reference, &exact.alpha), position, angle, target))
}

/// The error of a flexure joint's coordinates `alpha` inside a mechanism:
/// the joint carries only a tip load (every load acts on bodies), found from
/// $\nabla U = \mathcal J^T(M, F_x, F_y)$ by least squares; the estimate is
/// [`deflect_error`] under that load, in the joint's root frame.
///
/// # Example
/// ```
/// use flexure::{deflect, estimate, Flexure, Statics, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let mut data = Statics::new(&f);
/// let load = TipLoad { moment: 0.0, fx: 0.0, fy: 10.0 };
/// deflect(&f, &load, &mut data, &Default::default()).unwrap();
/// let direct = estimate::deflect_error(&f, &load, data.alpha(), &Default::default()).unwrap();
/// let joint = estimate::joint_error(&f, data.alpha(), &Default::default()).unwrap();
/// assert!((joint.position - direct.position).abs() < 1e-9 * direct.position);
/// ```
pub fn joint_error(flexure: &Flexure, alpha: &[f64], target: &Accuracy) -> Result<ErrorEstimate> {
    flexure.check_coordinates("alpha", alpha)?;
    let mut k = crate::kinematics::Kinematics::new(flexure);
    crate::kinematics::update(flexure, alpha, &mut k, crate::kinematics::Level::Jacobian);
    let load = crate::connect::tip_load(flexure, alpha, &k)?;
    deflect_error(flexure, &load, alpha, target)
}

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
        let mut data = Statics::new(f);
        deflect(f, load, &mut data, &Settings::default())?;
        let alpha = data.alpha().to_vec();
        let e = deflect_error(f, load, &alpha, target)?;
        Ok((alpha, e))
    })
}

/// [`deflect_auto`] for the tendon joint.
pub fn tendon_auto(
    flexure: &Flexure,
    tendon: &Tendon,
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
fn raise<T>(
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

// ---------------------------------------------------------------------------
// Eigenvalue answers: buckling loads and natural frequencies.

/// The estimated error of eigenvalue answers, buckling loads and natural
/// frequencies, one entry per value (one for a buckling load, one per mode):
/// the relative change of each value in the reference model, the same
/// analysis repeated with every flexure refined ([`eigen_reference`]).
///
/// The model is a Rayleigh–Ritz discretization on a nested basis, so each
/// value converges from above (the $k$-th value of the reference is at most
/// the model's); the change is the model's error less the reference's own,
/// which is far smaller where the basis converges. Values are paired by
/// rank (lowest with lowest); a value the reference cannot pair (it
/// resolves fewer modes, or its equilibrium is unstable: the load exceeds
/// the reference's buckling load though not the model's) has no estimate,
/// and is flagged, never reported as accurate.
#[derive(Debug, Clone, PartialEq)]
pub struct ValueEstimate {
    /// Per value, $\lvert v - v_r\rvert / v_r$ against the reference model's
    /// value $v_r$; `None` where the reference has no counterpart.
    pub relative: Vec<Option<f64>>,
    /// The reference model's values, as many as it paired (N, a load
    /// factor, or rad/s).
    pub reference: Vec<f64>,
    /// Whether the reference's equilibrium is stable (always for buckling,
    /// which is about the unloaded state).
    pub reference_stable: bool,
    /// Whether any value misses [`Accuracy::eigenvalue`] or has no estimate.
    pub flagged: bool,
    /// Order and quadrature points of each flexure of the reference model:
    /// one for a single joint; one per flexure joint, in joint order, for a
    /// mechanism (none for a mechanism without flexures, whose model has no
    /// discretization error: its estimate is 0).
    pub reference_orders: Vec<(usize, usize)>,
}

impl ValueEstimate {
    fn new(
        values: &[f64],
        reference: Vec<f64>,
        reference_stable: bool,
        reference_orders: Vec<(usize, usize)>,
        target: &Accuracy,
    ) -> Self {
        let relative: Vec<Option<f64>> =
            values.iter().enumerate().map(|(k, v)| reference.get(k).map(|r| ((v - r) / r).abs())).collect();
        let flagged = relative.iter().any(|&e| misses(e, target));
        Self { relative, reference, reference_stable, flagged, reference_orders }
    }

    /// The largest estimate; infinite when a value has none.
    pub fn largest(&self) -> f64 {
        self.relative.iter().fold(0.0, |m, e| m.max(e.unwrap_or(f64::INFINITY)))
    }

    /// The values (by index, from 0) that miss `target` or have no estimate.
    pub fn missed(&self, target: &Accuracy) -> Vec<usize> {
        (0..self.relative.len()).filter(|&k| misses(self.relative[k], target)).collect()
    }
}

/// Whether a value's estimate `e` misses `target`: above it, not a number,
/// or missing.
fn misses(e: Option<f64>, target: &Accuracy) -> bool {
    e.is_none_or(|e| e.is_nan() || e > target.eigenvalue)
}

/// The reference model for an eigenvalue answer of `flexure` about the
/// shape `alpha`: [`reference()`] (order $\min(\max(2N, N + 3), 64)$), except
/// at the cap $N = 64$, where more points alone would change a straight
/// flexure's answer by nothing and report a false 0: there it is order 32
/// (with the same rule for its points), whose change overstates the
/// order-64 answer's error.
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 64).unwrap();
/// let r = flexure::estimate::eigen_reference(&f, &[0.0; 64]).unwrap();
/// assert_eq!(r.order(), 32);
/// ```
pub fn eigen_reference(flexure: &Flexure, alpha: &[f64]) -> Result<Flexure> {
    if flexure.order() < MAX_ORDER {
        return reference(flexure, alpha);
    }
    if flexure.basis() != Basis::Legendre {
        return Err(Error::invalid("basis", "segments", "error estimates are made for the Legendre model"));
    }
    let order = MAX_ORDER / 2;
    let points = (order as f64 + 6.0 + turning(alpha).ceil()).min(MAX_POINTS as f64) as usize;
    let mut kappa = flexure.rest().to_vec();
    kappa.truncate(order);
    Flexure::with_points(flexure.length(), flexure.ei(), order, points)?
        .with_rest(&kappa)?
        .with_section(flexure.section().clone())
}

/// The error of a [`crate::buckling_load`] answer `b` of `flexure` under
/// `tip`: the same load of the reference model about the rest shape.
///
/// # Example
/// ```
/// use flexure::{buckling_load, estimate, Flexure, TipConstraint};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let b = buckling_load(&f, TipConstraint::Clamped).unwrap();
/// let e = estimate::buckling_error(&f, TipConstraint::Clamped, &b, &Default::default()).unwrap();
/// // Order 3 says 42 EI/L², Euler 4π² = 39.48: 6.4 % high, and the estimate sees it.
/// let truth = b.critical_load / (4.0 * std::f64::consts::PI.powi(2)) - 1.0;
/// assert!(e.flagged && (e.relative[0].unwrap() / truth - 1.0).abs() < 0.01);
/// ```
pub fn buckling_error(flexure: &Flexure, tip: TipConstraint, b: &Buckling, target: &Accuracy) -> Result<ValueEstimate> {
    target.validate()?;
    let reference = eigen_reference(flexure, flexure.rest())?;
    let exact = buckling_load(&reference, tip)?.critical_load;
    let orders = vec![(reference.order(), reference.quadrature_points())];
    Ok(ValueEstimate::new(&[b.critical_load], vec![exact], true, orders, target))
}

/// The lowest order (from `flexure`'s, each step the reference's order and
/// quadrature) whose buckling load under `tip` meets `target`, with that
/// flexure, the load and its estimate. At order 64 the answer is returned
/// as it is, its estimate `flagged` if it still misses.
///
/// # Example
/// ```
/// use flexure::{estimate, Flexure, TipConstraint};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let (used, b, e) = estimate::buckling_auto(&f, TipConstraint::Clamped, &Default::default()).unwrap();
/// let euler = 4.0 * std::f64::consts::PI.powi(2);
/// assert!(!e.flagged && used.order() > 3 && (b.critical_load / euler - 1.0).abs() < 0.01);
/// ```
pub fn buckling_auto(
    flexure: &Flexure,
    tip: TipConstraint,
    target: &Accuracy,
) -> Result<(Flexure, Buckling, ValueEstimate)> {
    let (f, (b, e)) = raise(flexure, |f| {
        let b = buckling_load(f, tip)?;
        let e = buckling_error(f, tip, &b, target)?;
        let next = e.reference_orders[0];
        let flagged = e.flagged;
        Ok(((b, e), flagged, next))
    })?;
    Ok((f, b, e))
}

/// The error of the frequencies `modes` of `flexure` (with the tip `body`)
/// about its equilibrium under `load` ([`dynamics::modes()`]): the same
/// analysis (equilibrium, loaded stiffness, mass) in the reference model,
/// whose frequencies are paired with the model's by rank.
///
/// # Example
/// ```
/// use flexure::{dynamics, estimate, section::{Profile, Section}, Flexure, TipLoad};
/// let section = Section::uniform(1.0).unwrap().with_mass_per_length(Profile::Constant(1.0)).unwrap();
/// let f = Flexure::new(1.0, 1.0, 3).unwrap().with_section(section).unwrap();
/// let m = dynamics::modes(&f, &TipLoad::default(), None, 3).unwrap();
/// let e = estimate::modes_error(&f, &TipLoad::default(), None, &m, &Default::default()).unwrap();
/// // The third mode of order 3 is 91 % above the beam's (βL)² = 61.70: the estimate flags it.
/// assert!(e.flagged && e.relative[2].unwrap() > 0.5);
/// ```
pub fn modes_error(
    flexure: &Flexure,
    load: &TipLoad,
    body: Option<&Body>,
    modes: &Modes,
    target: &Accuracy,
) -> Result<ValueEstimate> {
    target.validate()?;
    let rest;
    let alpha = if modes.coordinates.len() == flexure.order() {
        &modes.coordinates
    } else {
        rest = flexure.rest().to_vec();
        &rest
    };
    let reference = eigen_reference(flexure, alpha)?;
    let orders = vec![(reference.order(), reference.quadrature_points())];
    let (omega, stable) = reference_values(dynamics::modes(&reference, load, body, modes.omega.len().max(1)))?;
    Ok(ValueEstimate::new(&modes.omega, omega, stable, orders, target))
}

/// The reference's frequencies, or none (unstable) when its equilibrium is
/// not stable: then no mode can be estimated.
fn reference_values(modes: Result<Modes>) -> Result<(Vec<f64>, bool)> {
    match modes {
        Ok(m) => Ok((m.omega, true)),
        Err(Error::Unstable { .. }) => Ok((Vec::new(), false)),
        Err(e) => Err(e),
    }
}

/// The lowest order (from `flexure`'s, raised to `count` if lower, each
/// step the reference's order and quadrature) whose lowest `count`
/// frequencies all meet `target` ([`modes_error`]), with that flexure, the
/// modes and their estimate; at order 64 returned as they are, `flagged` if
/// they still miss.
///
/// # Example
/// ```
/// use flexure::{dynamics, estimate, section::{Profile, Section}, Flexure, TipLoad};
/// let section = Section::uniform(1.0).unwrap().with_mass_per_length(Profile::Constant(1.0)).unwrap();
/// let f = Flexure::new(1.0, 1.0, 3).unwrap().with_section(section).unwrap();
/// let (used, m, e) = estimate::modes_auto(&f, &TipLoad::default(), None, 3, &Default::default()).unwrap();
/// // The cantilever's third mode: (βL)² with βL = 7.8548 (ω in rad/s for EI = m = L = 1).
/// assert!(!e.flagged && used.order() > 3 && (m.omega[2] / 7.8548f64.powi(2) - 1.0).abs() < 0.01);
/// ```
pub fn modes_auto(
    flexure: &Flexure,
    load: &TipLoad,
    body: Option<&Body>,
    count: usize,
    target: &Accuracy,
) -> Result<(Flexure, Modes, ValueEstimate)> {
    let start = if count > flexure.order() && count <= MAX_ORDER {
        refined(flexure, count, flexure.quadrature_points().max(count + 2))?
    } else {
        flexure.clone()
    };
    let (f, (m, e)) = raise(&start, |f| {
        let m = dynamics::modes(f, load, body, count)?;
        let e = modes_error(f, load, body, &m, target)?;
        let next = e.reference_orders[0];
        let flagged = e.flagged;
        Ok(((m, e), flagged, next))
    })?;
    Ok((f, m, e))
}

/// The reference mechanism: every flexure joint replaced by its
/// [`eigen_reference`] about its coordinates in `q` (the rest shape when
/// `q` is not the mechanism's), with their (order, quadrature).
fn mechanism_reference(m: &Mechanism, q: &[f64]) -> Result<(Mechanism, Vec<(usize, usize)>)> {
    let rest;
    let q = if q.len() == m.dof() {
        q
    } else {
        rest = m.rest();
        &rest
    };
    let mut orders = Vec::new();
    let reference = m.with_flexures(|j, f| {
        let o = m.joints[j].offset;
        let r = eigen_reference(f, &q[o..o + f.order()])?;
        orders.push((r.order(), r.quadrature_points()));
        Ok(Some(r))
    })?;
    Ok((reference, orders))
}

/// The next mechanism of an automatic order: each flexure joint of
/// `order = "auto"` below the cap at its reference's (order, quadrature)
/// from `orders`; `None` when no joint can be raised.
fn raised(m: &Mechanism, orders: &[(usize, usize)]) -> Result<Option<Mechanism>> {
    let (mut k, mut any) = (0, false);
    let next = m.with_flexures(|j, f| {
        let (order, points) = orders[k];
        k += 1;
        if !m.joints[j].auto_order || f.order() >= MAX_ORDER {
            return Ok(None);
        }
        any = true;
        refined(f, order.max(f.order() + 1).min(MAX_ORDER), points).map(Some)
    })?;
    Ok(any.then_some(next))
}

/// The error of a mechanism's [`mechanism::buckling::buckle`] answer `b`:
/// the load factor of the reference mechanism, every flexure refined.
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
pub fn buckle_error(
    m: &Mechanism,
    b: &MechanismBuckling,
    settings: &MechanismSettings,
    target: &Accuracy,
) -> Result<ValueEstimate> {
    target.validate()?;
    let (reference, orders) = mechanism_reference(m, &[])?;
    let exact = mechanism::buckling::buckle(&reference, settings)?.load_factor;
    Ok(ValueEstimate::new(&[b.load_factor], vec![exact], true, orders, target))
}

/// [`mechanism::buckling::buckle`] with its estimate, the flexure joints of
/// `order = "auto"` raised (each to its reference's order and quadrature)
/// until the estimate meets `target`, or none can be raised further (then
/// `flagged`). Returns the mechanism used, the answer and its estimate;
/// without such joints, the mechanism as given.
pub fn buckle_auto(
    m: &Mechanism,
    settings: &MechanismSettings,
    target: &Accuracy,
) -> Result<(Mechanism, MechanismBuckling, ValueEstimate)> {
    let mut m = m.clone();
    loop {
        let b = mechanism::buckling::buckle(&m, settings)?;
        let e = buckle_error(&m, &b, settings, target)?;
        if !e.flagged {
            return Ok((m, b, e));
        }
        match raised(&m, &e.reference_orders)? {
            Some(next) => m = next,
            None => return Ok((m, b, e)),
        }
    }
}

/// The error of a mechanism's [`dynamics::mechanism::modes`] answer: the
/// same analysis of the reference mechanism (every flexure refined about
/// its coordinates at the equilibrium), frequencies paired by rank.
pub fn mechanism_modes_error(
    m: &Mechanism,
    modes: &Modes,
    settings: &MechanismSettings,
    target: &Accuracy,
) -> Result<ValueEstimate> {
    target.validate()?;
    let (reference, orders) = mechanism_reference(m, &modes.coordinates)?;
    let count = modes.omega.len().max(1).min(reference.dof().max(1));
    let (omega, stable) = reference_values(dynamics::mechanism::modes(&reference, settings, count))?;
    Ok(ValueEstimate::new(&modes.omega, omega, stable, orders, target))
}

/// [`dynamics::mechanism::modes`] with its estimate, the flexure joints of
/// `order = "auto"` raised as in [`buckle_auto`].
pub fn mechanism_modes_auto(
    m: &Mechanism,
    settings: &MechanismSettings,
    count: usize,
    target: &Accuracy,
) -> Result<(Mechanism, Modes, ValueEstimate)> {
    let mut m = m.clone();
    loop {
        let modes = dynamics::mechanism::modes(&m, settings, count)?;
        let e = mechanism_modes_error(&m, &modes, settings, target)?;
        if !e.flagged {
            return Ok((m, modes, e));
        }
        match raised(&m, &e.reference_orders)? {
            Some(next) => m = next,
            None => return Ok((m, modes, e)),
        }
    }
}
