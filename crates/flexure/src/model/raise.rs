//! `order = "auto"` in the static answers ([`super::Model::solve`],
//! [`super::Model::sweep`]): the analysis is run, and while a flexure joint
//! of `order = "auto"` misses the accuracy target, that joint alone is
//! raised ([`raise_auto`], the eigen analyses' ladder) and the analysis run
//! again on the raised mechanism, written once over the dimension. With
//! contact the estimate is the whole refined mechanism's
//! ([`crate::estimate::contact_estimates`]), which the report makes by itself.

use super::Analyses;
use crate::error::Result;
use crate::estimate::{Asked, raise_auto};
use crate::mechanism::Mechanism;
use crate::mechanism::statics::Solution;
use crate::mechanism::sweep::Sweep;
use crate::report::{EstimateFailed, SolveReport};
use std::borrow::Cow;

/// An answer of one or more equilibria, each with its report.
pub(super) trait Reports {
    /// Each equilibrium's coordinates and report; none when an estimate failed.
    fn reports(&self) -> Vec<(&[f64], &SolveReport)>;
}

/// Runs `analyse` on `m`, and while a flexure joint of `order = "auto"`
/// misses the target at one of the answer's equilibria, again on `m` with
/// each such joint raised about the equilibrium that asks for most
/// ([`worst`]); joints of a fixed order, and those that meet the target,
/// keep theirs. Returns the mechanism the answer was found with and the
/// answer. Bounded: each pass raises at least one joint's order strictly,
/// and none past 64.
pub(super) fn raising<'m, D: Analyses, T: Reports>(
    m: &'m Mechanism<D>,
    mut analyse: impl FnMut(&Mechanism<D>) -> Result<T>,
) -> Result<(Cow<'m, Mechanism<D>>, T)> {
    let mut used = Cow::Borrowed(m);
    loop {
        let answer = analyse(&used)?;
        let next = raise_auto(&used, &worst(&used, &answer.reports()))?;
        match next {
            Some(next) => used = Cow::Owned(next),
            None => return Ok((used, answer)),
        }
    }
}

/// Per flexure joint of `m` in joint order, the equilibrium among `reports`
/// at which its estimate misses the target with the largest reference
/// (order, then points or subintervals: the most turning), and that
/// reference's refinement; `None` where none misses.
fn worst<'a, D: Analyses>(m: &Mechanism<D>, reports: &[(&'a [f64], &SolveReport)]) -> Vec<Asked<'a>> {
    let count = m.joints.iter().filter(|j| j.kind.flexure().is_some()).count();
    (0..count)
        .map(|k| {
            let missed = reports.iter().filter_map(|(q, r)| {
                let e = &r.error_estimate.0.get(k)?.1;
                e.flagged.then_some((*q, (e.reference_order, e.reference_quadrature)))
            });
            missed.max_by_key(|(_, refinement)| *refinement)
        })
        .collect()
}

/// The flexure joints of `order = "auto"` of `m` (the mechanism an answer
/// was found with) whose estimate misses the target at one of `reports`:
/// after [`raising`], each is at the cap, with nothing left to raise.
pub(super) fn capped<D: Analyses>(m: &Mechanism<D>, reports: &[(&[f64], &SolveReport)]) -> Vec<String> {
    let auto = m.joints.iter().filter(|j| j.auto_order && j.kind.flexure().is_some()).map(|j| &j.name);
    auto.filter(|name| reports.iter().any(|(_, r)| r.error_estimate.get(name).is_some_and(|e| e.flagged)))
        .cloned()
        .collect()
}

/// A solve: its equilibrium and report.
impl<D: Analyses> Reports for (Solution<D>, std::result::Result<SolveReport, EstimateFailed>) {
    fn reports(&self) -> Vec<(&[f64], &SolveReport)> {
        self.1.iter().map(|r| (self.0.q.as_slice(), r)).collect()
    }
}

/// A sweep: each row's equilibrium and report.
impl<D: Analyses> Reports for (Sweep<Solution<D>>, std::result::Result<Vec<SolveReport>, EstimateFailed>) {
    fn reports(&self) -> Vec<(&[f64], &SolveReport)> {
        let rows = self.1.iter().flat_map(|reports| self.0.rows.iter().zip(reports));
        rows.map(|((_, s), r)| (s.q.as_slice(), r)).collect()
    }
}
