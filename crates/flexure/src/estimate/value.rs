//! The estimate of an eigenvalue answer, a buckling load or natural
//! frequencies: [`ValueEstimate`], one relative change per value.

use super::accuracy::Accuracy;

/// The estimated error of eigenvalue answers, buckling loads and natural
/// frequencies, one entry per value (one for a buckling load, one per mode):
/// the relative change of each value in the reference model, the same
/// analysis repeated with every flexure refined ([`eigen_reference`](super::eigen_reference)).
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
    pub(super) fn new(
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
