//! What a load path asks of a mechanism's statics, whatever its dimension:
//! [`Equilibria`], implemented by the planar [`Mechanism`] and the
//! [`SpatialMechanism`], and the path algorithms written once over it:
//! where a path first loses stability ([`first_loss`]), and the refinement
//! of a continuation's limit ([`refine_limit`]). The sweeps
//! ([`crate::mechanism::sweep::sweep`]) are written over it too.
//!
//! The load factor $\lambda \in [0, 1]$ runs from a solution's loads
//! $L_0$ to the target $L_1$ as $L(\lambda) = (1-\lambda)L_0 + \lambda L_1$.

use super::spatial::statics::{SpatialSolution, assemble_unloaded as spatial_unloaded};
use super::spatial::{SpatialLoads, SpatialMechanism};
use super::statics::{PROBE_STEPS, Solution, assemble_unloaded, follow};
use super::{Loads, Mechanism};
use crate::error::{Error, Result};
use crate::solver::Settings;

/// A mechanism's statics as load paths see them: its loads, its unloaded
/// state, and a continuation between two loads.
pub trait Equilibria {
    /// The loads it carries.
    type Loads: Clone;
    /// An equilibrium, with the loads it carries.
    type Solution: Clone;
    /// The one load a sweep varies.
    type Parameter;

    /// The loads as given (the file's, at full value).
    fn loads(&self) -> Self::Loads;
    /// The assembled state with no load.
    fn unloaded(&self, settings: &Settings) -> Result<Self::Solution>;
    /// The continuation from `start` to `to`, with its own (unrefined)
    /// limit: a stable end is `Ok` (its limit set if stability was lost on
    /// the way), an unstable one [`Error::Unstable`].
    fn follow(&self, start: &Self::Solution, to: &Self::Loads, settings: &Settings) -> Result<Self::Solution>;
    /// `loads` with `parameter` set to `value`.
    fn apply(&self, parameter: &Self::Parameter, loads: &Self::Loads, value: f64) -> Self::Loads;
    /// Whether `parameter` is a tendon's tension (which cannot be negative).
    fn is_tension(parameter: &Self::Parameter) -> bool;
    /// $L(\lambda)$ between `from` and `to`.
    fn lerp(from: &Self::Loads, to: &Self::Loads, lambda: f64) -> Self::Loads;
    /// The loads a solution carries.
    fn loads_of(s: &Self::Solution) -> &Self::Loads;
    /// Where a solution's path first lost stability, as a load fraction.
    fn limit_of(s: &Self::Solution) -> Option<f64>;
    /// `s` with its limit set to `limit`.
    fn with_limit(s: Self::Solution, limit: Option<f64>) -> Self::Solution;
    /// Whether a solution is stable.
    fn stable_of(s: &Self::Solution) -> bool;
}

/// Whether the path that `found` ends lost stability on the way (from a
/// start that was `stable`), so that its limit is refined.
pub(in crate::mechanism) fn lost<M: Equilibria>(found: &Result<M::Solution>, stable: bool) -> bool {
    match found {
        Ok(s) => M::limit_of(s).is_some(),
        Err(Error::Unstable { load_fraction, .. }) => *load_fraction > 0.0 || stable,
        Err(_) => false,
    }
}

/// The fraction $\lambda$ of the load change from `start`'s loads to `to`
/// where the path from `start` first loses stability, by bisection until
/// `precise(lo, hi)`: each probe continues from the last stable state, for
/// at most [`PROBE_STEPS`] steps, and at most 64 probes are made.
pub fn first_loss<M: Equilibria>(
    m: &M,
    start: &M::Solution,
    to: &M::Loads,
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
        match m.follow(&at, &M::lerp(M::loads_of(start), to, mid), &settings) {
            Ok(s) if M::limit_of(&s).is_none() => {
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
pub fn refine_limit<M: Equilibria>(
    m: &M,
    start: &M::Solution,
    to: &M::Loads,
    settings: &Settings,
    found: Result<M::Solution>,
) -> Result<M::Solution> {
    if !lost::<M>(&found, M::stable_of(start)) {
        return found;
    }
    let precision = super::statics::LIMIT_PRECISION;
    let limit = first_loss(m, start, to, settings, |lo, hi| hi - lo <= precision * hi)?;
    match found {
        Ok(s) => Ok(M::with_limit(s, Some(limit))),
        Err(_) => Err(Error::Unstable { what: "mechanism equilibrium", load_fraction: limit }),
    }
}

impl Equilibria for Mechanism {
    type Loads = Loads;
    type Solution = Solution;
    type Parameter = super::sweep::Parameter;

    fn loads(&self) -> Loads {
        Mechanism::loads(self)
    }
    fn unloaded(&self, settings: &Settings) -> Result<Solution> {
        assemble_unloaded(self, settings)
    }
    fn follow(&self, start: &Solution, to: &Loads, settings: &Settings) -> Result<Solution> {
        follow(self, start, to, settings)
    }
    fn apply(&self, parameter: &Self::Parameter, loads: &Loads, value: f64) -> Loads {
        parameter.apply(loads, value)
    }
    fn is_tension(parameter: &Self::Parameter) -> bool {
        matches!(parameter, super::sweep::Parameter::Tension(_))
    }
    fn lerp(from: &Loads, to: &Loads, lambda: f64) -> Loads {
        from.lerp(to, lambda)
    }
    fn loads_of(s: &Solution) -> &Loads {
        &s.loads
    }
    fn limit_of(s: &Solution) -> Option<f64> {
        s.limit
    }
    fn with_limit(s: Solution, limit: Option<f64>) -> Solution {
        Solution { limit, ..s }
    }
    fn stable_of(s: &Solution) -> bool {
        s.stable
    }
}

impl Equilibria for SpatialMechanism {
    type Loads = SpatialLoads;
    type Solution = SpatialSolution;
    type Parameter = super::spatial::sweep::SpatialParameter;

    fn loads(&self) -> SpatialLoads {
        SpatialMechanism::loads(self)
    }
    fn unloaded(&self, settings: &Settings) -> Result<SpatialSolution> {
        spatial_unloaded(self, &self.loads().zero_like(), settings)
    }
    fn follow(&self, start: &SpatialSolution, to: &SpatialLoads, settings: &Settings) -> Result<SpatialSolution> {
        super::spatial::statics::follow(self, start, to, settings)
    }
    fn apply(&self, parameter: &Self::Parameter, loads: &SpatialLoads, value: f64) -> SpatialLoads {
        parameter.apply(loads, value)
    }
    fn is_tension(parameter: &Self::Parameter) -> bool {
        matches!(parameter, super::spatial::sweep::SpatialParameter::Tension(_))
    }
    fn lerp(from: &SpatialLoads, to: &SpatialLoads, lambda: f64) -> SpatialLoads {
        let mut out = from.clone();
        from.lerp_into(to, lambda, &mut out);
        out
    }
    fn loads_of(s: &SpatialSolution) -> &SpatialLoads {
        &s.loads
    }
    fn limit_of(s: &SpatialSolution) -> Option<f64> {
        s.limit
    }
    fn with_limit(s: SpatialSolution, limit: Option<f64>) -> SpatialSolution {
        SpatialSolution { limit, ..s }
    }
    fn stable_of(s: &SpatialSolution) -> bool {
        s.stable
    }
}
