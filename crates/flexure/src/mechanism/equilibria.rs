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
use super::{Dimension, Loads, Mechanism};
use crate::error::{Error, Result};
use crate::solver::Settings;
use crate::space::{Planar, Spatial};

/// A mechanism's statics as load paths see them: its loads, its unloaded
/// state, and a continuation between two loads.
pub trait Equilibria {
    /// The dimension: the loads, solutions and parameters are its.
    type Dim: Dimension;

    /// The loads as given (the file's, at full value).
    fn loads(&self) -> Loads<Self::Dim>;
    /// The assembled state with no load.
    fn unloaded(&self, settings: &Settings) -> Result<Solution<Self::Dim>>;
    /// The continuation from `start` to `to`, with its own (unrefined)
    /// limit: a stable end is `Ok` (its limit set if stability was lost on
    /// the way), an unstable one [`Error::Unstable`].
    fn follow(
        &self,
        start: &Solution<Self::Dim>,
        to: &Loads<Self::Dim>,
        settings: &Settings,
    ) -> Result<Solution<Self::Dim>>;
    /// `loads` with `parameter` set to `value`.
    fn apply(&self, parameter: &ParameterOf<Self>, loads: &Loads<Self::Dim>, value: f64) -> Loads<Self::Dim>;
    /// Whether `parameter` is a tendon's tension (which cannot be negative).
    fn is_tension(parameter: &ParameterOf<Self>) -> bool;
    /// $L(\lambda)$ between `from` and `to`.
    fn lerp(from: &Loads<Self::Dim>, to: &Loads<Self::Dim>, lambda: f64) -> Loads<Self::Dim>;
}

/// The load parameter of `M`'s dimension.
pub type ParameterOf<M> = <<M as Equilibria>::Dim as Dimension>::Parameter;

/// Whether the path that `found` ends lost stability on the way (from a
/// start that was `stable`), so that its limit is refined.
pub(in crate::mechanism) fn lost<D: Dimension>(found: &Result<Solution<D>>, stable: bool) -> bool {
    match found {
        Ok(s) => s.limit.is_some(),
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
    start: &Solution<M::Dim>,
    to: &Loads<M::Dim>,
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
        match m.follow(&at, &M::lerp(&start.loads, to, mid), &settings) {
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
pub fn refine_limit<M: Equilibria>(
    m: &M,
    start: &Solution<M::Dim>,
    to: &Loads<M::Dim>,
    settings: &Settings,
    found: Result<Solution<M::Dim>>,
) -> Result<Solution<M::Dim>> {
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

impl Equilibria for Mechanism {
    type Dim = Planar;

    fn loads(&self) -> Loads {
        Mechanism::loads(self)
    }
    fn unloaded(&self, settings: &Settings) -> Result<Solution> {
        assemble_unloaded(self, settings)
    }
    fn follow(&self, start: &Solution, to: &Loads, settings: &Settings) -> Result<Solution> {
        follow(self, start, to, settings)
    }
    fn apply(&self, parameter: &ParameterOf<Self>, loads: &Loads, value: f64) -> Loads {
        parameter.apply(loads, value)
    }
    fn is_tension(parameter: &ParameterOf<Self>) -> bool {
        matches!(parameter, super::sweep::Parameter::Tension(_))
    }
    fn lerp(from: &Loads, to: &Loads, lambda: f64) -> Loads {
        from.lerp(to, lambda)
    }
}

impl Equilibria for SpatialMechanism {
    type Dim = Spatial;

    fn loads(&self) -> SpatialLoads {
        SpatialMechanism::loads(self)
    }
    fn unloaded(&self, settings: &Settings) -> Result<SpatialSolution> {
        spatial_unloaded(self, &self.loads().zero_like(), settings)
    }
    fn follow(&self, start: &SpatialSolution, to: &SpatialLoads, settings: &Settings) -> Result<SpatialSolution> {
        super::spatial::statics::follow(self, start, to, settings)
    }
    fn apply(&self, parameter: &ParameterOf<Self>, loads: &SpatialLoads, value: f64) -> SpatialLoads {
        parameter.apply(loads, value)
    }
    fn is_tension(parameter: &ParameterOf<Self>) -> bool {
        matches!(parameter, super::spatial::sweep::SpatialParameter::Tension(_))
    }
    fn lerp(from: &SpatialLoads, to: &SpatialLoads, lambda: f64) -> SpatialLoads {
        let mut out = from.clone();
        from.lerp_into(to, lambda, &mut out);
        out
    }
}
