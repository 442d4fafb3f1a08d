//! Open closures: a weld or pin whose two sides do not meet with every
//! joint at rest ([`open_closures`]), and the preload that closing it puts
//! into the unloaded mechanism.

use super::Severity;
use super::geometry::distance;
use crate::error::{Error, Result};
use crate::mechanism::kinematics::frames;
use crate::mechanism::statics::{Settings, assemble_unloaded};
use crate::mechanism::{Closure, Dimension, Holds, Mechanism};

/// A closure meets at rest when its gap is at most this: relative to the
/// mechanism's size for positions, in rad for a weld's angle.
pub const GAP_TOLERANCE: f64 = 1e-9;

/// A weld or pin whose two sides do not meet in the unloaded mechanism.
#[derive(Debug, Clone, PartialEq)]
pub struct OpenClosure {
    /// Its index in [`Mechanism::closures`].
    pub closure: usize,
    /// What it is: `weld of "stage" and "b_tip"`.
    pub what: String,
    /// Where it is given in the file ("line L, column C").
    pub place: String,
    /// Distance between its two points at rest (m).
    pub gap: f64,
    /// A weld's angle between its two frames at rest (rad, in $(-\pi, \pi]$,
    /// frame `a`'s angle minus frame `b`'s); `None` for a pin.
    pub turn: Option<f64>,
    /// The magnitude of the force it carries when assembled with no load
    /// (N); `None` if the unloaded mechanism cannot be assembled (from rest,
    /// by Newton: then every solve of it fails, saying so).
    pub force: Option<f64>,
    /// A weld's moment when assembled with no load (N·m); `None` for a pin,
    /// or if the unloaded mechanism cannot be assembled.
    pub moment: Option<f64>,
    /// Whether the file says `preload = true`.
    pub preload: bool,
}

impl OpenClosure {
    /// A warning, or a note with `preload = true`.
    pub fn severity(&self) -> Severity {
        if self.preload { Severity::Note } else { Severity::Warning }
    }

    /// The finding in words, with its place in the file.
    pub fn message(&self) -> String {
        let gap = match self.turn {
            Some(t) => format!("{:.6e} m and {t:.6} rad", self.gap),
            None => format!("{:.6e} m", self.gap),
        };
        let preload = match (self.force, self.moment) {
            (Some(force), Some(moment)) => format!("with no load it carries {force:.6e} N and {moment:.6e} N·m"),
            (Some(force), None) => format!("with no load it carries {force:.6e} N"),
            (None, _) => "the unloaded mechanism cannot be assembled, so how much is not known".to_string(),
        };
        let what = format!(
            "{}: {} is open at rest by {gap}; closing it preloads the mechanism: {preload}",
            self.place, self.what
        );
        if self.preload {
            format!("{what} (preload = true)")
        } else {
            format!("{what}; if that is meant, say `preload = true` in it, else make its frames meet at rest")
        }
    }
}

/// `weld of "a" and "b"`, `pin of …` or `ball of …`, in either dimension.
pub fn closure_name<D: Dimension>(m: &Mechanism<D>, i: usize) -> String {
    m.closures[i].name(m)
}

/// Each closure's gap at rest: (distance in m, a weld's angle in rad).
pub fn rest_gaps(m: &Mechanism) -> Vec<(f64, Option<f64>)> {
    let f = frames(m, &m.rest());
    m.closures
        .iter()
        .map(|c| match c.holds {
            Holds::Weld => {
                let (fa, fb) = (f.bodies[c.a].compose(&c.a_origin), f.bodies[c.b].compose(&c.b_origin));
                let turn = crate::mechanism::lagrangian::wrap(fa.phi - fb.phi);
                (distance(&fa.origin(), &fb.origin()), Some(turn))
            }
            Holds::Pin | Holds::Ball => {
                let (pa, pb) = (c.a_origin.origin(), c.b_origin.origin());
                (distance(&f.bodies[c.a].act(&pa), &f.bodies[c.b].act(&pb)), None)
            }
        })
        .collect()
}

/// The closures whose gaps at rest (as [`rest_gaps`] gives them) exceed
/// [`GAP_TOLERANCE`] of `length` or of a radian, with their index: the
/// planar and the spatial mechanism's test.
pub(in crate::mechanism) fn open_gaps(gaps: Vec<(f64, Option<f64>)>, length: f64) -> Vec<(usize, (f64, Option<f64>))> {
    gaps.into_iter()
        .enumerate()
        .filter(|(_, (gap, turn))| *gap > GAP_TOLERANCE * length || turn.is_some_and(|t| t.abs() > GAP_TOLERANCE))
        .collect()
}

/// Each closure's first multiplier row, from the closures' equation counts.
pub(in crate::mechanism) fn first_rows(equations: impl Iterator<Item = usize>) -> Vec<usize> {
    equations
        .scan(0, |row, n| {
            let first = *row;
            *row += n;
            Some(first)
        })
        .collect()
}

/// The closures of `m` that do not meet at rest (see the module docs),
/// each with the preload that closes it: the unloaded mechanism is
/// assembled (with `settings`) only if one is open. If that assembly
/// fails, as every static solve of `m` then does, the preload is `None`
/// (a simulation from an `[initial]` state may still run); an error only
/// if it is interrupted.
pub fn open_closures(m: &Mechanism, settings: &Settings) -> Result<Vec<OpenClosure>> {
    let open = open_gaps(rest_gaps(m), m.size());
    if open.is_empty() {
        return Ok(Vec::new());
    }
    let unloaded = match assemble_unloaded(m, settings) {
        Ok(s) => Some(s),
        Err(Error::File { .. } | Error::NoConvergence { .. } | Error::Singular { .. }) => None,
        Err(e) => return Err(e),
    };
    let rows = first_rows(m.closures.iter().map(Closure::equations));
    Ok(open
        .into_iter()
        .map(|(i, (gap, turn))| {
            let mu = unloaded.as_ref().map(|s| &s.multipliers[rows[i]..rows[i] + m.closures[i].equations()]);
            OpenClosure {
                closure: i,
                what: closure_name(m, i),
                place: m.closure_place(i).to_string(),
                gap,
                turn,
                force: mu.map(|mu| mu[0].hypot(mu[1])),
                moment: mu.zip(turn).map(|(mu, _)| mu[2].abs()),
                preload: m.closure_preload(i),
            }
        })
        .collect())
}
