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

use crate::error::{Error, Result, positive};
use crate::joint::{Basis, Flexure, MAX_ORDER};
use crate::kinematics::{self, Pose, backbone};
use crate::quadrature::MAX_POINTS;
use crate::statics::{Settings, Statics, TipLoad, deflect};
use crate::stress::{peak_curvature, peak_stress};
use crate::tendon::{Tendon, TendonData, pull};

/// The accuracy an answer must meet: tip position within `position` × L,
/// tip angle within `angle` rad, and peak bending stress (or, for a section
/// without thickness, peak curvature change) within `stress` of itself.
/// The default is the paper's 1 % of L and 1°, and 1 % of the peak.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Accuracy {
    /// Position tolerance as a fraction of the flexure's length.
    pub position: f64,
    /// Angle tolerance (rad).
    pub angle: f64,
    /// Peak stress tolerance as a fraction of the peak.
    pub stress: f64,
}

impl Default for Accuracy {
    fn default() -> Self {
        Self { position: 0.01, angle: 1f64.to_radians(), stress: 0.01 }
    }
}

impl Accuracy {
    /// Checks every tolerance: finite and greater than zero.
    pub fn validate(&self) -> Result<()> {
        positive("accuracy", self.position)?;
        positive("accuracy", self.angle)?;
        positive("accuracy", self.stress)?;
        Ok(())
    }
}

/// An answer's estimated error, and whether it misses the [`Accuracy`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorEstimate {
    /// Estimated position error (m).
    pub position: f64,
    /// Estimated angle error (rad).
    pub angle: f64,
    /// Estimated error of the peak bending stress (Pa); `None` for a
    /// section without thickness.
    pub stress: Option<f64>,
    /// Estimated error of the peak curvature change (1/m).
    pub curvature: f64,
    /// The reported peak's estimated error as a fraction of the peak:
    /// stress with a thickness, curvature change without (0 when unbent).
    pub peak: f64,
    /// Whether the estimate exceeds the accuracy target.
    pub flagged: bool,
    /// Order of the reference model.
    pub reference_order: usize,
    /// Quadrature points of the reference model.
    pub reference_quadrature: usize,
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
        let (model_peak, exact_peak) = (peak_curvature(flexure, alpha).value, peak_curvature(reference, exact).value);
        let curvature = (model_peak - exact_peak).abs();
        let stress = match (peak_stress(flexure, alpha), peak_stress(reference, exact)) {
            (Some(a), Some(b)) => Some(((a.value - b.value).abs(), b.value)),
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
            reference_order: reference.order(),
            reference_quadrature: reference.quadrature_points(),
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
    if flexure.basis() != Basis::Legendre {
        return Err(Error::invalid("basis", "segments", "error estimates are made for the Legendre model"));
    }
    let n = flexure.order();
    let order = (2 * n).max(n + 3).min(MAX_ORDER);
    let v = turning(alpha);
    let points = (order as f64 + 6.0 + v.ceil()).min(MAX_POINTS as f64) as usize;
    refined(flexure, order, points)
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
    target.validate()?;
    let reference = reference(flexure, alpha)?;
    let model = kinematics::pose_root_tip(flexure, alpha);
    let mut data = Statics::new(&reference);
    let settings = Settings::default();
    let warm = padded(alpha, reference.order());
    if crate::statics::correct(&reference, load, &warm, &mut data, &settings).is_err() {
        deflect(&reference, load, &mut data, &settings)?;
    }
    let (position, angle) = pose_error(&model, &data.pose_root_tip());
    Ok(ErrorEstimate::new((flexure, alpha), (&reference, data.alpha()), position, angle, target))
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
    let reference = reference(flexure, alpha)?;
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
    let reference = reference(flexure, alpha)?;
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
    let mut f = flexure.clone();
    loop {
        let (alpha, e) = solve(&f)?;
        if !e.flagged {
            return Ok((f, alpha, e));
        }
        if f.order() >= MAX_ORDER {
            return Err(Error::invalid(
                "order",
                "auto",
                "even order 64 misses the accuracy target: loosen --accuracy or reduce the load",
            ));
        }
        f = refined(&f, e.reference_order, e.reference_quadrature)?;
    }
}
