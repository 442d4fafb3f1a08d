//! Open closures: a weld, pin or ball whose two sides do not meet with every
//! joint at rest ([`open_closures`]), and the preload that closing it puts
//! into the unloaded mechanism.

use super::Severity;
use super::dimension::Findings;
use crate::error::{Error, Result};
use crate::mechanism::statics::Settings;
use crate::mechanism::{Closure, Dimension, Mechanism};

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
    /// The angle it holds that is open at rest (rad, as [`rest_gaps`] gives
    /// it): a weld's between its two frames, in space also a pin's between
    /// its two axes; `None` for a ball, and for a pin in the plane.
    pub turn: Option<f64>,
    /// The magnitude of the force it carries when assembled with no load
    /// (N); `None` if the unloaded mechanism cannot be assembled (from rest,
    /// by Newton: then every solve of it fails, saying so).
    pub force: Option<f64>,
    /// The moment it carries when assembled with no load (N·m): a weld's, in
    /// space also a pin's; `None` for a ball or a planar pin, or if the
    /// unloaded mechanism cannot be assembled.
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

/// Each closure's gap at rest: the distance between its two points (m),
/// and the angle it holds (rad): a weld's between its two frames (in the
/// plane frame `a`'s angle minus frame `b`'s, in $(-\pi, \pi]$), in space
/// also a pin's between its two axes (in $[0, \pi]$).
pub fn rest_gaps<D: Findings>(m: &Mechanism<D>) -> Vec<(f64, Option<f64>)> {
    let (bodies, _) = D::poses(m, &m.rest());
    m.closures.iter().map(|c| D::rest_gap(c, &bodies)).collect()
}

/// The closures whose gaps at rest (as [`rest_gaps`] gives them) exceed
/// [`GAP_TOLERANCE`] of `length` or of a radian, with their index.
fn open_gaps(gaps: Vec<(f64, Option<f64>)>, length: f64) -> Vec<(usize, (f64, Option<f64>))> {
    gaps.into_iter()
        .enumerate()
        .filter(|(_, (gap, turn))| *gap > GAP_TOLERANCE * length || turn.is_some_and(|t| t.abs() > GAP_TOLERANCE))
        .collect()
}

/// Each closure's first multiplier row, from the closures' equation counts.
fn first_rows(equations: impl Iterator<Item = usize>) -> Vec<usize> {
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
///
/// # Example
/// ```
/// use flexure::mechanism::file::spatial_from_toml;
/// use flexure::mechanism::findings::open_closures;
/// // Two sprung hinges about z whose arms' tips meet 1 mm apart at rest: a ball closes them.
/// let m = spatial_from_toml("dimension = 3\n\
///     [[joint]]\nname = \"l\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"a\"\nstiffness = 1.0\n\
///     [[joint]]\nname = \"r\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"b\"\norigin = [0.2, 0.0, 0.0]\nstiffness = 1.0\n\
///     [[ball]]\na = \"a\"\na_at = [0.1, 0.0, 0.0]\nb = \"b\"\nb_at = [-0.099, 0.0, 0.0]\n").unwrap();
/// let open = open_closures(&m, &Default::default()).unwrap();
/// assert_eq!(open.len(), 1);
/// assert!((open[0].gap - 1e-3).abs() < 1e-12 && open[0].turn.is_none());
/// assert!(open[0].message().contains("ball of \"a\" and \"b\" is open at rest by 1.0"));
/// ```
pub fn open_closures<D: Findings>(m: &Mechanism<D>, settings: &Settings) -> Result<Vec<OpenClosure>> {
    let open = open_gaps(rest_gaps(m), m.size());
    if open.is_empty() {
        return Ok(Vec::new());
    }
    let unloaded = match crate::mechanism::statics::assemble_unloaded(m, settings) {
        Ok(s) => Some(s),
        Err(Error::File { .. } | Error::NoConvergence { .. } | Error::Singular { .. }) => None,
        Err(e) => return Err(e),
    };
    let rows = first_rows(m.closures.iter().map(Closure::equations));
    Ok(open
        .into_iter()
        .map(|(i, (gap, turn))| {
            let mu = unloaded.as_ref().map(|s| &s.multipliers[rows[i]..rows[i] + m.closures[i].equations()]);
            let (force, moment) = mu.map(D::preload).unzip();
            OpenClosure {
                closure: i,
                what: closure_name(m, i),
                place: m.closure_place(i).to_string(),
                gap,
                turn,
                force,
                moment: moment.flatten(),
                preload: m.closure_preload(i),
            }
        })
        .collect())
}
