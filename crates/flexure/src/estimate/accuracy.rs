//! What an answer must meet and what it is estimated to miss by: the
//! [`Accuracy`] target and the [`ErrorEstimate`] of a statics answer.

use crate::error::{Result, positive};
use crate::flexure::Flexure;
use crate::stress::{peak_curvature_legendre, peak_stress};

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
/// use flexure::{Flexure, StaticsData, TipLoad, deflect};
///
/// let f = Flexure::new(1.0, 1.0, 3)?;
/// let load = TipLoad { moment: 0.5, fx: 0.0, fy: 0.2 };
/// let mut data = StaticsData::new(&f);
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
    /// a refined model: so at order [`MAX_ORDER`](crate::flexure::MAX_ORDER), which no model refines (see the module docs).
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
    pub(super) fn new(
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
    pub(super) fn from_peaks(
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
