//! Sweeps of one load of a spatial mechanism, as the planar
//! [`crate::mechanism::sweep`]: each value continued from the last, the
//! first loss of stability found by bisection.

use super::statics::{SpatialSolution, assemble_unloaded, solve_between};
use super::{SpatialLoads, SpatialMechanism};
use crate::error::{Error, Result};
use crate::mechanism::statics::{LIMIT_PRECISION, PROBE_STEPS};
use crate::mechanism::sweep::SweepLimit;
use crate::solver::Settings;

/// The one load a sweep varies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpatialParameter {
    /// Component 0..6 (`mx, my, mz, fx, fy, fz`) of point load `i`.
    Force(usize, usize),
    /// Tendon `i`'s tension.
    Tension(usize),
    /// Gravity's component 0..3 (`x, y, z`).
    Gravity(usize),
}

/// The components of a point load, by name.
pub const WRENCH_COMPONENTS: [&str; 6] = ["mx", "my", "mz", "fx", "fy", "fz"];

impl SpatialParameter {
    /// `force.NAME.mx|my|mz|fx|fy|fz`, `tendon.NAME.tension` or `gravity.x|y|z`.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::spatial::sweep::SpatialParameter;
    /// # use flexure::mechanism::spatial::{SpatialBody, SpatialMechanism};
    /// # let m = SpatialMechanism::new(vec![SpatialBody::massless("ground")], vec![], vec![], vec![], vec![], Default::default()).unwrap();
    /// assert_eq!(SpatialParameter::parse(&m, "gravity.z").unwrap(), SpatialParameter::Gravity(2));
    /// assert!(SpatialParameter::parse(&m, "force.none.fx").unwrap_err().to_string().contains("none"));
    /// ```
    pub fn parse(m: &SpatialMechanism, text: &str) -> Result<Self> {
        let bad = |why: &'static str| Error::invalid("sweep", text, why);
        let parts: Vec<&str> = text.split('.').collect();
        match parts.as_slice() {
            ["gravity", axis] => ["x", "y", "z"]
                .iter()
                .position(|a| a == axis)
                .map(SpatialParameter::Gravity)
                .ok_or_else(|| bad("gravity's component must be x, y or z")),
            ["force", name, component] => {
                let i = m
                    .forces
                    .iter()
                    .position(|f| f.name == *name)
                    .ok_or_else(|| bad("names no force of the mechanism"))?;
                let c = WRENCH_COMPONENTS
                    .iter()
                    .position(|c| c == component)
                    .ok_or_else(|| bad("a force's component must be mx, my, mz, fx, fy or fz"))?;
                Ok(SpatialParameter::Force(i, c))
            }
            ["tendon", name, "tension"] => {
                let i = m
                    .tendons
                    .iter()
                    .position(|t| t.name == *name)
                    .ok_or_else(|| bad("names no tendon of the mechanism"))?;
                Ok(SpatialParameter::Tension(i))
            }
            _ => Err(bad("must be force.NAME.mx|my|mz|fx|fy|fz, tendon.NAME.tension or gravity.x|y|z")),
        }
    }

    /// `loads` with this parameter set to `value`.
    pub fn apply(&self, loads: &SpatialLoads, value: f64) -> SpatialLoads {
        let mut out = loads.clone();
        match *self {
            SpatialParameter::Force(i, c) => out.force[i][c] = value,
            SpatialParameter::Tension(i) => out.tension[i] = value,
            SpatialParameter::Gravity(c) => out.gravity[c] = value,
        }
        out
    }
}

/// What [`sweep`] reached.
#[derive(Debug, Clone)]
pub struct SpatialSweep {
    /// The values solved, each with its stable equilibrium.
    pub rows: Vec<(f64, SpatialSolution)>,
    /// The first loss of stability along the sweep, if any.
    pub stability_limit: Option<SweepLimit>,
    /// Why the sweep ended before its last value, if a solve failed.
    pub stopped: Option<(f64, Error)>,
}

/// The fraction of the way from `start` to `to` where stability is first
/// lost, by bisection to `precise` (at most 64 halvings, each a
/// continuation of at most [`PROBE_STEPS`] steps from the last stable state).
fn first_loss(
    m: &SpatialMechanism,
    start: &SpatialSolution,
    to: &SpatialLoads,
    settings: &Settings,
    precise: impl Fn(f64, f64) -> bool,
) -> Result<f64> {
    let settings = Settings { max_steps: settings.max_steps.min(PROBE_STEPS), ..*settings };
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut at = start.clone();
    let mut loads = start.loads.clone();
    for _ in 0..64 {
        if precise(lo, hi) {
            break;
        }
        let mid = 0.5 * (lo + hi);
        start.loads.lerp_into(to, mid, &mut loads);
        match solve_between(m, &at, &loads, &settings) {
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

/// Equilibria along `values` of one load, each continued from the last,
/// with the first loss of stability between two values found by bisection
/// to a relative [`LIMIT_PRECISION`]; as the planar [`crate::mechanism::sweep::sweep`].
pub fn sweep(
    m: &SpatialMechanism,
    parameter: &SpatialParameter,
    values: &[f64],
    settings: &Settings,
) -> Result<SpatialSweep> {
    settings.validate()?;
    if values.is_empty() {
        return Err(Error::invalid("sweep", "no values", "a sweep needs at least one value"));
    }
    if let Some(v) = values.iter().find(|v| !v.is_finite()) {
        return Err(Error::invalid("sweep", v, "values must be finite"));
    }
    if let SpatialParameter::Tension(_) = parameter
        && let Some(v) = values.iter().find(|v| **v < 0.0)
    {
        return Err(Error::invalid("sweep", v, "a tendon's tension must be finite and not negative"));
    }
    let base = m.loads();
    let (first, last) = (values[0], values[values.len() - 1]);
    let fraction = |v: f64| if last != first { (v - first) / (last - first) } else { 0.0 };
    let mut out = SpatialSweep { rows: Vec::with_capacity(values.len()), stability_limit: None, stopped: None };
    let mut start = assemble_unloaded(m, &base.zero_like(), settings)?;
    for (i, &v) in values.iter().enumerate() {
        let target = parameter.apply(&base, v);
        let found = solve_between(m, &start, &target, settings);
        let lost = i > 0
            && match &found {
                Ok(s) => s.limit.is_some(),
                Err(Error::Unstable { .. }) => true,
                Err(_) => false,
            };
        let mut limit = None;
        if lost {
            let previous = values[i - 1];
            let value = |s: f64| previous + s * (v - previous);
            let precise = |lo: f64, hi: f64| {
                (value(hi) - value(lo)).abs() <= LIMIT_PRECISION * value(lo).abs().max(value(hi).abs())
            };
            let s = match first_loss(m, &start, &target, settings, precise) {
                Ok(s) => s,
                Err(e) => {
                    out.stopped = Some((v, e));
                    break;
                }
            };
            limit = Some(s);
            if out.stability_limit.is_none() {
                out.stability_limit = Some(SweepLimit { value: value(s), fraction: fraction(value(s)) });
            }
        }
        match found {
            Ok(s) => {
                let s = SpatialSolution { limit: limit.or(s.limit), ..s };
                start = s.clone();
                out.rows.push((v, s));
            }
            Err(Error::Unstable { .. }) if lost => break,
            Err(e @ Error::InvalidParameter { .. }) => return Err(e),
            Err(e) => {
                out.stopped = Some((v, e));
                break;
            }
        }
    }
    Ok(out)
}
