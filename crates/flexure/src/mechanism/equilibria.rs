//! The path algorithms of a mechanism's statics, whatever its dimension
//! ([`Statics`]): where a path first loses stability ([`first_loss`]), and
//! the refinement of a continuation's limit ([`refine_limit`]). The sweeps
//! ([`crate::mechanism::sweep::sweep`]) are written over them too.
//!
//! The load factor $\lambda \in [0, 1]$ runs from a solution's loads
//! $L_0$ to the target $L_1$ as $L(\lambda) = (1-\lambda)L_0 + \lambda L_1$.

use super::statics::{PROBE_STEPS, Solution, Statics, follow};
use super::{Dimension, Loads, Mechanism};
use crate::error::{Error, Result};
use crate::solver::Settings;

/// Whether the path that `found` ends lost stability on the way (from a
/// start that was `stable`), so that its limit is refined.
pub(in crate::mechanism) fn lost<D: Dimension>(found: &Result<Solution<D>>, stable: bool) -> bool {
    match found {
        Ok(s) => s.limit.is_some(),
        Err(Error::Unstable { load_fraction, .. }) => *load_fraction > 0.0 || stable,
        Err(_) => false,
    }
}

/// $L(\lambda)$ between `from` and `to`.
pub(in crate::mechanism) fn lerp<D: Statics>(from: &Loads<D>, to: &Loads<D>, lambda: f64) -> Loads<D> {
    let mut out = from.clone();
    D::lerp_into(from, to, lambda, &mut out);
    out
}

/// The fraction $\lambda$ of the load change from `start`'s loads to `to`
/// where the path from `start` first loses stability, by bisection until
/// `precise(lo, hi)`: each probe continues from the last stable state, for
/// at most [`PROBE_STEPS`] steps, and at most 64 probes are made.
pub fn first_loss<D: Statics>(
    m: &Mechanism<D>,
    start: &Solution<D>,
    to: &Loads<D>,
    settings: &Settings,
    precise: impl Fn(f64, f64) -> bool,
) -> Result<f64> {
    let settings = Settings { max_steps: settings.max_steps.min(PROBE_STEPS), ..*settings };
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut at = start.clone();
    for _ in 0..64 {
        if precise(lo, hi) {
            break;
        }
        let mid = 0.5 * (lo + hi);
        match follow(m, &at, &lerp(&start.loads, to, mid), &settings) {
            Ok(s) if s.limit.is_none() => {
                lo = mid;
                at = s;
            }
            Ok(_) | Err(Error::Unstable { .. }) => hi = mid,
            Err(e) => return Err(e),
        }
    }
    Ok(0.5 * (lo + hi))
}

/// The path from `start` to `to` as a solve reports it, from what the
/// continuation `found`: a lost stability's load fraction refined by
/// bisection to a relative [`super::statics::LIMIT_PRECISION`]; a path that
/// ends unstable is [`Error::Unstable`] at that fraction.
pub fn refine_limit<D: Statics>(
    m: &Mechanism<D>,
    start: &Solution<D>,
    to: &Loads<D>,
    settings: &Settings,
    found: Result<Solution<D>>,
) -> Result<Solution<D>> {
    if !lost(&found, start.stable) {
        return found;
    }
    let precision = super::statics::LIMIT_PRECISION;
    let limit = first_loss(m, start, to, settings, |lo, hi| hi - lo <= precision * hi)?;
    match found {
        Ok(s) => Ok(Solution { limit: Some(limit), ..s }),
        Err(_) => Err(Error::Unstable { what: "mechanism equilibrium", load_fraction: limit }),
    }
}
