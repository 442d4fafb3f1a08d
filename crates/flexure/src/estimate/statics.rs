//! Error estimates of one flexure's static answers: a tip load
//! ([`deflect_error`], reusable as [`Estimator`]), a tendon
//! ([`tendon_error`]), a connection ([`connect_error`]) and a joint inside a
//! mechanism ([`joint_error`]).

use super::accuracy::{Accuracy, ErrorEstimate};
use super::refinement::{eigen_reference, legendre, reference_size, refined};
use crate::error::Result;
use crate::flexure::{Flexure, MAX_ORDER};
use crate::kinematics::{self, Pose, backbone};
use crate::statics::{Settings, StaticsData, TipLoad, deflect};
use crate::tendon::{TendonData, TendonOffsets, pull};

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
/// use flexure::{deflect, estimate, Flexure, StaticsData, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let mut data = StaticsData::new(&f);
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
/// points, [`reference()`](super::reference())); the numbers are those of [`deflect_error`].
///
/// # Example
/// ```
/// use flexure::{deflect, estimate::Estimator, Flexure, StaticsData, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let (mut data, mut estimator) = (StaticsData::new(&f), Estimator::new());
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
    cached: Option<(Flexure, Flexure, StaticsData)>,
    /// The answer padded to the reference's order: the start of its Newton solve.
    warm: Vec<f64>,
}

impl Estimator {
    /// An estimator with nothing built yet: the first estimate builds the reference.
    pub fn new() -> Self {
        Self::default()
    }

    /// The reference model for the answer `alpha` of `flexure` ([`reference()`](super::reference())),
    /// built only when the last one was for another flexure or size, with its buffers.
    fn reference(&mut self, flexure: &Flexure, alpha: &[f64]) -> Result<(&Flexure, &mut StaticsData)> {
        let size = reference_size(flexure, alpha)?;
        let fits = self.cached.as_ref().is_some_and(|(source, reference, _)| {
            (reference.order(), reference.quadrature_points()) == size && source == flexure
        });
        if !fits {
            let reference = refined(flexure, size.0, size.1)?;
            let data = StaticsData::new(&reference);
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
        self.estimate(flexure, load, alpha, target, true)
    }

    /// [`Estimator::deflect_error`]; `path`: check the reference against
    /// the loading path from rest ([`on_the_loading_path`]), which a joint
    /// inside a mechanism ([`joint_error`]) did not follow: its tip load
    /// is the mechanism's, reached along the mechanism's path.
    fn estimate(
        &mut self,
        flexure: &Flexure,
        load: &TipLoad,
        alpha: &[f64],
        target: &Accuracy,
        path: bool,
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
        } else if path {
            on_the_loading_path(reference, load, data, &settings);
        }
        let (position, angle) = pose_error(&model, &data.pose_root_tip());
        let e = ErrorEstimate::new((flexure, alpha), (reference, data.alpha()), position, angle, target);
        self.warm = warm;
        Ok(e)
    }
}

/// Replaces the reference equilibrium in `data` (corrected from the answer)
/// by the one the reference reaches along the loading path from rest
/// ([`deflect`]), when they differ: a [`deflect`] answer is the end of that
/// path, and Newton from an answer on another branch corrects it on that
/// branch, so an answer whose model followed a path the finer model does
/// not would be estimated against itself (issue 39: at order 6, under $M =
/// -6.26$, $F = (-15.5, 5.02)$, an answer at $\varphi = 0.744$, where a
/// continuation step once strayed, was estimated at $2\times10^{-5}$,
/// while the exact elastica and order 12 reach $\varphi = -4.97$, 0.99 L
/// away). Equilibria of one model on one branch agree to the solver's
/// tolerance; $10^{-6}$ of the length or radian tells them apart. Where the
/// path cannot be followed, the corrected reference stays.
fn on_the_loading_path(reference: &Flexure, load: &TipLoad, data: &mut StaticsData, settings: &Settings) {
    let mut path = StaticsData::new(reference);
    if deflect(reference, load, &mut path, settings).is_err() {
        return;
    }
    let (position, angle) = pose_error(&data.pose_root_tip(), &path.pose_root_tip());
    if position > 1e-6 * reference.length() || angle > 1e-6 {
        *data = path;
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
    tendon: &TendonOffsets,
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
/// use flexure::{deflect, estimate, Flexure, StaticsData, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let mut data = StaticsData::new(&f);
/// let load = TipLoad { moment: 0.0, fx: 0.0, fy: 10.0 };
/// deflect(&f, &load, &mut data, &Default::default()).unwrap();
/// let direct = estimate::deflect_error(&f, &load, data.alpha(), &Default::default()).unwrap();
/// let joint = estimate::joint_error(&f, data.alpha(), &Default::default()).unwrap();
/// assert!((joint.position - direct.position).abs() < 1e-9 * direct.position);
/// ```
pub fn joint_error(flexure: &Flexure, alpha: &[f64], target: &Accuracy) -> Result<ErrorEstimate> {
    joint_error_and_load(flexure, alpha, target).map(|(e, _)| e)
}

/// [`joint_error`] with the tip load the joint carries, which it finds on
/// the way ([`crate::connect::tip_load`]): what a mechanism's report gives of each flexure joint.
pub fn joint_error_and_load(flexure: &Flexure, alpha: &[f64], target: &Accuracy) -> Result<(ErrorEstimate, TipLoad)> {
    flexure.check_coordinates("alpha", alpha)?;
    let mut k = crate::kinematics::Kinematics::new(flexure);
    crate::kinematics::update(flexure, alpha, &mut k, crate::kinematics::Level::Jacobian);
    let load = crate::connect::tip_load(flexure, alpha, &k)?;
    Ok((Estimator::new().estimate(flexure, &load, alpha, target, false)?, load))
}
