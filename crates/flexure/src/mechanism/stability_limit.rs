//! The stability limit of a mechanism: the factor $f$ on all its loads
//! (tendons, forces, gravity) at which the equilibrium followed from no
//! load, $L(\lambda) = \lambda f L$, first stops being stable.
//!
//! Without contact it is [`crate::limit`]'s search, as for one flexure:
//! one path to the largest factor, then bisection on "the path to $f$
//! stays stable". With contact the answer depends on the path (a stuck
//! contact holds where a sliding one gives), so the load is followed once,
//! in order, with its contacts touching, sticking, sliding and opening
//! as they do along it ([`follow_touching`]), in stages of doubling factor
//! $1, 2, 4, \dots$, each continued from the last: where a stage loses
//! stability its path found where, to $10^{-10}$ of the stage.

use super::Mechanism;
use super::contact::pairs;
use super::equilibria::lerp;
use super::statics::{
    Settings, Solution, Statics, Touched, Workspace, assemble_unloaded, follow_touching, solve_between,
};
use crate::error::{Error, Result};
use crate::limit::{PathEnd, StabilityLimit, search};

impl<D: super::Dimension> PathEnd for Solution<D> {
    fn ended_stable(&self) -> bool {
        self.stable
    }
    fn lost_at(&self) -> Option<f64> {
        self.limit
    }
}

/// Bisections on the factor a contact path reaches, where a stage stops
/// for another reason than a loss of stability.
const REACH_PROBES: usize = 40;

/// The factor on `m`'s loads, up to `max_factor`, at which the
/// equilibrium followed from no load stops being stable, or up to which it
/// stays stable (`max_factor`, or as far as the path could be followed,
/// with why it could not go further).
///
/// Errors: `max_factor` not finite and above zero, an interrupt, and a
/// path that gets nowhere from no load (the refusal [`follow_touching`]
/// gives there, as a solve does).
///
/// # Example
/// ```
/// use flexure::mechanism::{file::from_toml, stability_limit::stability_limit, statics::Settings};
/// use flexure::StabilityLimit;
/// // A sprung arm (k = 1 N·m/rad, l = 0.1 m) pushed along itself by 4 N loses
/// // stability at P = k/l = 10 N: 2.5 times the load.
/// let m = from_toml(
///     "[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 1.0\n\
///      [[force]]\nname = \"push\"\nbody = \"arm\"\nat = [0.1, 0.0]\nforce = [-4.0, 0.0]\n",
/// )
/// .unwrap();
/// let l = stability_limit(&m, &Settings::default(), 1000.0).unwrap();
/// assert!(matches!(l, StabilityLimit::Lost { factor } if (factor - 2.5).abs() < 1e-5));
/// ```
pub fn stability_limit<D: Statics>(m: &Mechanism<D>, settings: &Settings, max_factor: f64) -> Result<StabilityLimit> {
    settings.validate()?;
    if !(max_factor.is_finite() && max_factor > 0.0) {
        return Err(Error::invalid("max_factor", max_factor, "must be a finite number greater than zero"));
    }
    let loads = m.loads();
    let scaled = |factor: f64| lerp(&D::zero(&loads), &loads, factor);
    if pairs(m).is_empty() {
        let start = assemble_unloaded(m, settings)?;
        return search(max_factor, |factor| solve_between(m, &start, &scaled(factor), settings));
    }
    let work = &mut Workspace::new(m);
    let mut from: Option<Touched<D>> = None;
    let mut reached = 0.0;
    while reached < max_factor {
        let next = (2.0 * reached).max(1.0).min(max_factor);
        match follow_touching(m, from.as_ref(), &scaled(next), settings, work) {
            Ok((_, touched)) => (reached, from) = (next, Some(touched)),
            Err(Error::Unstable { load_fraction, .. }) => {
                return Ok(StabilityLimit::Lost { factor: reached + load_fraction * (next - reached) });
            }
            Err(e @ Error::Interrupted { .. }) => return Err(e),
            Err(e) => {
                let limit = farthest(m, (from, reached), next, settings, work, &scaled)?;
                // Nowhere from no load: the mechanism's refusal, as `solve` gives it.
                if limit.factor() == 0.0 {
                    return Err(e);
                }
                return Ok(stalled(limit, format!("on the way from {reached} to {next} times the load, {e}")));
            }
        }
    }
    Ok(StabilityLimit::StableUpTo { factor: max_factor, stalled: None })
}

/// `limit`, where it holds to its factor, as stalled there, for `why`.
fn stalled(limit: StabilityLimit, why: String) -> StabilityLimit {
    match limit {
        StabilityLimit::StableUpTo { factor, .. } => StabilityLimit::StableUpTo { factor, stalled: Some(why) },
        lost => lost,
    }
}

/// The largest factor below `next` that a contact path from `from` (at
/// `reached`) gets to, stably, by bisection ([`REACH_PROBES`] at most), as
/// stable up to it; or where a probe lost stability on the way.
fn farthest<D: Statics>(
    m: &Mechanism<D>,
    (mut from, mut reached): (Option<Touched<D>>, f64),
    next: f64,
    settings: &Settings,
    work: &mut Workspace<D>,
    scaled: &impl Fn(f64) -> super::Loads<D>,
) -> Result<StabilityLimit> {
    let mut beyond = next;
    for _ in 0..REACH_PROBES {
        if beyond - reached <= 1e-10 * beyond {
            break;
        }
        let mid = 0.5 * (reached + beyond);
        match follow_touching(m, from.as_ref(), &scaled(mid), settings, work) {
            Ok((_, touched)) => (reached, from) = (mid, Some(touched)),
            Err(Error::Unstable { load_fraction, .. }) => {
                return Ok(StabilityLimit::Lost { factor: reached + load_fraction * (mid - reached) });
            }
            Err(e @ Error::Interrupted { .. }) => return Err(e),
            Err(_) => beyond = mid,
        }
    }
    Ok(StabilityLimit::StableUpTo { factor: reached, stalled: None })
}
