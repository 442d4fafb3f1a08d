//! The stability limit of a loading path: the factor on a load at which
//! the equilibrium followed from rest stops being stable.
//!
//! One search serves every problem that follows a load from rest (a tip
//! load, a tendon's tension): it asks only for the path to a given factor
//! (the private `search`'s `path_to`), so a tip load and a tendon get the same answer
//! for the same reason.

use crate::error::{Error, Result};
use serde::ser::{Serialize, SerializeMap, Serializer};

/// The largest factor on a load that a stability limit tries unless told
/// otherwise: the CLI's `--limit` and Python's `max_factor` default.
pub const MAX_FACTOR: f64 = 1000.0;

/// How far a load can be scaled from rest before stability is lost.
#[derive(Debug, Clone, PartialEq)]
pub enum StabilityLimit {
    /// The path loses stability at `factor` times the load (a buckling or
    /// limit load): stable up to `factor`, confirmed, and unstable within a
    /// relative $10^{-10}$ above it (less precisely if a probe near it
    /// failed; then `factor` is still a confirmed-stable lower bound). If
    /// every probe below the first path's estimate fails, that estimate is
    /// kept: the first path was stable to within one of its steps of it.
    Lost {
        /// The largest factor confirmed stable.
        factor: f64,
    },
    /// The path stays stable up to at least `factor` times the load.
    StableUpTo {
        /// `max_factor`, or as far as the path could be followed.
        factor: f64,
        /// `None` when `max_factor` was reached; otherwise why the path
        /// could not be followed beyond `factor` (the solver's error), so
        /// stability further on is unknown.
        stalled: Option<String>,
    },
}

/// One shape wherever a stability limit is printed:
/// `{"factor": f, "status": "lost" | "stable_up_to"}`, with `"stalled"`
/// (the reason, or null when `max_factor` was reached) only for
/// `stable_up_to`.
impl Serialize for StabilityLimit {
    fn serialize<S: Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        let stalled = match self {
            StabilityLimit::Lost { .. } => None,
            StabilityLimit::StableUpTo { stalled, .. } => Some(stalled),
        };
        let mut map = serializer.serialize_map(Some(if stalled.is_some() { 3 } else { 2 }))?;
        map.serialize_entry("factor", &self.factor())?;
        map.serialize_entry("status", if stalled.is_some() { "stable_up_to" } else { "lost" })?;
        if let Some(stalled) = stalled {
            map.serialize_entry("stalled", stalled)?;
        }
        map.end()
    }
}

impl StabilityLimit {
    /// The factor: where stability is lost, or the bound it holds to.
    pub fn factor(&self) -> f64 {
        match self {
            StabilityLimit::Lost { factor } | StabilityLimit::StableUpTo { factor, .. } => *factor,
        }
    }
}

/// The end of a loading path followed from rest, as [`search`] reads it
/// (a flexure's [`crate::statics::Equilibrium`]).
pub(crate) trait PathEnd {
    /// Whether the end is stable.
    fn ended_stable(&self) -> bool;
    /// The load fraction where the path first lost stability, if it did.
    fn lost_at(&self) -> Option<f64>;
}

/// The stability limit of the paths `path_to(factor)` (each followed from
/// rest to `factor` times the load, stopping where stability is lost), for
/// factors up to `max_factor`.
///
/// One path to `max_factor` finds where stability is first lost, to within
/// a step; bisection on "the path to $\lambda$ stays stable" then refines
/// it to a relative $10^{-10}$, in at most [`MAX_PROBES`] paths. A path
/// that cannot be followed to the end (a stalled continuation) is not read
/// as instability: the first path answers [`StabilityLimit::StableUpTo`]
/// the factor it reached, and a bisection probe that fails leaves its
/// factor unconfirmed (the answer stays a confirmed-stable lower bound).
/// Only an interrupt or invalid input is returned as an error.
pub(crate) fn search<E: PathEnd>(max_factor: f64, mut path_to: impl FnMut(f64) -> Result<E>) -> Result<StabilityLimit> {
    if !(max_factor.is_finite() && max_factor > 0.0) {
        return Err(Error::invalid("max_factor", max_factor, "must be a finite number greater than zero"));
    }
    let first = match path_to(max_factor) {
        Ok(e) if e.ended_stable() && e.lost_at().is_none() => {
            return Ok(StabilityLimit::StableUpTo { factor: max_factor, stalled: None });
        }
        Ok(e) => e.lost_at().unwrap_or(1.0),
        Err(Error::Unstable { load_fraction, .. }) => load_fraction,
        Err(e @ Error::ContinuationStalled { load_fraction, .. }) => {
            return Ok(StabilityLimit::StableUpTo { factor: load_fraction * max_factor, stalled: Some(e.to_string()) });
        }
        Err(e) => return Err(e),
    };
    let probes = std::cell::Cell::new(1);
    // Some(true): stable up to `factor`; Some(false): lost before it;
    // None: unknown (the probe failed), which the bracket treats as lost.
    let mut probe = |factor: f64| -> Result<Option<bool>> {
        probes.set(probes.get() + 1);
        match path_to(factor) {
            Ok(e) => Ok(Some(e.ended_stable() && e.lost_at().is_none())),
            Err(Error::Unstable { .. }) => Ok(Some(false)),
            Err(e @ (Error::Interrupted { .. } | Error::InvalidParameter { .. })) => Err(e),
            Err(_) => Ok(None),
        }
    };
    // Bracket around the first path's estimate: `lo` confirmed stable (the
    // rest state, 0, is where every path starts), `hi` not; then bisect.
    let estimate = first * max_factor;
    let (mut lo, mut hi) = (0.0, (1.5 * estimate).min(max_factor));
    let mut below = 0.5 * estimate;
    while below > 0.0 && probes.get() < MAX_PROBES {
        if probe(below)? == Some(true) {
            lo = below;
            break;
        }
        (hi, below) = (below, 0.5 * below);
    }
    while lo > 0.0 && hi < max_factor && probes.get() < MAX_PROBES {
        if probe(hi)? != Some(true) {
            break;
        }
        (lo, hi) = (hi, (2.0 * hi).min(max_factor));
    }
    if lo == 0.0 {
        // No probe confirmed stability below the first path's estimate (each
        // failed): keep the answer that path gave, stable to within a step of it.
        return Ok(StabilityLimit::Lost { factor: estimate });
    }
    while hi - lo > 1e-10 * hi && probes.get() < MAX_PROBES {
        let mid = 0.5 * (lo + hi);
        if probe(mid)? == Some(true) { lo = mid } else { hi = mid }
    }
    Ok(StabilityLimit::Lost { factor: lo })
}

/// The most paths the search follows: the first, a few to bracket, and the
/// bisection's (about 35 from a bracket of the estimate's width).
pub const MAX_PROBES: usize = 100;
