//! The weighted root-mean-square norm of the error test and of Newton's
//! stopping test: each entry over `absolute` + `tolerance` × its size, so
//! both tests measure in fractions of the tolerance.

use super::work::Work;

/// Root mean square of the position parts `dq` and velocity parts `dv`
/// (times `vw`) of `k` blocks, each entry over its scale.
pub(super) fn scaled_norm(w: &Work, dq: &[f64], dv: &[f64], vw: f64) -> f64 {
    (scaled_dot(w, dq, dv, dq, dv, vw) / (2 * dq.len()).max(1) as f64).sqrt()
}

/// The scaled inner product of two increments (positions and velocities,
/// the latter times `vw`), each entry over its scale as in [`scaled_norm`].
pub(super) fn scaled_dot(w: &Work, aq: &[f64], av: &[f64], bq: &[f64], bv: &[f64], vw: f64) -> f64 {
    let n = w.n;
    let mut sum = 0.0;
    for k in 0..aq.len() {
        let r = k % n;
        // Products of scaled entries: a vector with itself gives the sum of
        // its scaled squares, scaled_norm's.
        sum += (aq[k] / w.sq[r]) * (bq[k] / w.sq[r]) + (vw * av[k] / w.sv[r]) * (vw * bv[k] / w.sv[r]);
    }
    sum
}
