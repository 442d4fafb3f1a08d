//! Following the equilibrium path between two loads, and bisecting for where it first loses stability.

use super::dimension::Statics;
use super::kkt::Kkt;
use super::stiffness::stiffness;
use super::workspace::{Buffers, Workspace};
use super::{Settings, Solution};
use crate::error::{Error, Result};
use crate::linalg;
use crate::mechanism::equilibria::refine_limit;
use crate::mechanism::{Loads, Mechanism};
use crate::solver;

/// The solution at the unknowns `x`, under the problem's loads at the
/// end of its path (`end`) or at its start, computed in the problem's
/// buffers: the frames and $G$ of the last evaluation if it was at `x`.
pub(super) fn solution<D: Statics>(
    problem: &mut Kkt<D>,
    x: &[f64],
    end: bool,
    path: &solver::Path,
) -> Result<Solution<D>> {
    let n = problem.mechanism.dof();
    let (q, mu) = (&x[..n], problem.multipliers(x));
    let loads = if end { problem.to.clone() } else { problem.from.clone() };
    let multipliers = D::settled(problem, q, mu, &loads);
    // + 0.0: an empty sum is −0.
    let energy = problem.work.frames.joints.iter().map(|s| s.energy).sum::<f64>() + 0.0;
    if !(energy.is_finite() && q.iter().chain(&multipliers).all(|v| v.is_finite())) {
        return Err(Error::Singular { what: "mechanism equilibrium: the solution is not finite".into() });
    }
    Ok(Solution {
        q: q.to_vec(),
        multipliers,
        loads,
        energy,
        stable: path.stable,
        limit: path.limit,
        residual: path.residual,
        load_steps: path.steps,
        iterations: path.iterations,
        contacts: Vec::new(),
        path: Vec::new(),
    })
}

/// Equilibrium under `to`, continued from `start` (an equilibrium under
/// `start.loads`) by the shared continuation.
///
/// A snap-through that ends in a stable state is an answer, with
/// [`Solution::limit`] the fraction of the load change where stability was
/// first lost. A path that loses stability and does not reach a stable
/// state at the full load (it ends unstable, or stops after the loss) is
/// [`Error::Unstable`] at that fraction. The fraction is the continuation's
/// ([`solver::Path::limit`]) refined by bisection to a relative
/// [`super::LIMIT_PRECISION`] (as [`crate::mechanism::sweep::sweep`] does between two values).
pub fn solve_between<D: Statics>(
    m: &Mechanism<D>,
    start: &Solution<D>,
    to: &Loads<D>,
    settings: &Settings,
) -> Result<Solution<D>> {
    solve_between_in(m, start, to, settings, &mut Workspace::new(m))
}

pub(super) fn solve_between_in<D: Statics>(
    m: &Mechanism<D>,
    start: &Solution<D>,
    to: &Loads<D>,
    settings: &Settings,
    work: &mut Workspace<D>,
) -> Result<Solution<D>> {
    let found = follow_in(m, start, to, settings, work);
    refine_limit(m, start, to, settings, found)
}

/// Where a path starts: a solution, or the assembled state at $\lambda = 0$
/// of the problem itself (its unknowns in [`Workspace::start_x`], reached by `path`).
pub(super) enum Start<'s, D: Statics> {
    Given(&'s Solution<D>),
    Assembled(&'s solver::Path),
}

/// [`solve_between`] with the continuation's own limit, unrefined.
pub(in crate::mechanism) fn follow<D: Statics>(
    m: &Mechanism<D>,
    start: &Solution<D>,
    to: &Loads<D>,
    settings: &Settings,
) -> Result<Solution<D>> {
    follow_in(m, start, to, settings, &mut Workspace::new(m))
}

/// [`follow`] in the buffers `work` (made for `m`).
pub(super) fn follow_in<D: Statics>(
    m: &Mechanism<D>,
    start: &Solution<D>,
    to: &Loads<D>,
    settings: &Settings,
    work: &mut Workspace<D>,
) -> Result<Solution<D>> {
    D::check_start(m, &start.q, &start.multipliers, &start.loads)?;
    if !work.fits(m) {
        return Err(Error::invalid("workspace", work.dof, "was made for another mechanism"));
    }
    let mut problem = Kkt::fitted(m, &start.loads, to, settings, Buffers::Borrowed(work))?;
    let dim = solver::Problem::dim(&problem);
    let mut ws = problem.work.solver(dim);
    ws.x.iter_mut().zip(&start.q).for_each(|(x, q)| *x = *q);
    let n = m.dof();
    for ((x, mu), s) in ws.x[n..].iter_mut().zip(&start.multipliers).zip(&problem.multiplier_scale) {
        *x = mu / s;
    }
    let found = follow_path(m, Start::Given(start), &mut problem, &mut ws, settings);
    let mut work = problem.release();
    work.solver = Some(ws);
    found
}

pub(super) fn follow_path<D: Statics>(
    m: &Mechanism<D>,
    start: Start<D>,
    problem: &mut Kkt<D>,
    ws: &mut solver::SolverWorkspace<f64>,
    settings: &Settings,
) -> Result<Solution<D>> {
    let unstable =
        |limit: Option<f64>| Error::Unstable { what: "mechanism equilibrium", load_fraction: limit.unwrap_or(0.0) };
    let path = match solver::trace(problem, ws, settings) {
        Ok(path) => path,
        // No path starts: the start has a zero-stiffness motion along the load; name it.
        Err(Error::Singular { what }) if D::NAMES_FREE_MOTION => {
            let joints = match start {
                Start::Given(s) => free_motion(m, s),
                Start::Assembled(path) => {
                    let x0 = problem.work.start_x.clone();
                    solution(problem, &x0, false, path).ok().and_then(|s| free_motion(m, &s))
                }
            };
            return Err(Error::Singular {
                what: match joints {
                    Some(joints) => format!(
                        "mechanism equilibrium: the mechanism moves freely at the start ({joints}) and the load drives that motion: no equilibrium can be followed; give a joint on it a stiffness, or hold it with a closure"
                    ),
                    None => what,
                },
            });
        }
        Err(e) => return Err(e),
    };
    match path.error(&*problem) {
        None if path.stable => solution(problem, &ws.x, true, &path),
        None => Err(unstable(path.limit)),
        Some(e @ Error::Interrupted { .. }) => Err(e),
        // A path that stopped after losing stability: it is the loss that counts.
        Some(e) => Err(path.limit.map_or(e, |limit| unstable(Some(limit)))),
    }
}

/// The joints that move in a zero-stiffness motion of `s` (the constrained
/// stiffness's softest mode, if it is singular), as "joint \"a\" and joint \"b\"".
pub(in crate::mechanism) fn free_motion<D: Statics>(m: &Mechanism<D>, s: &Solution<D>) -> Option<String> {
    let (z, k) = stiffness(m, s).ok()?;
    if k.nrows() == 0 || linalg::is_positive_definite(&k) {
        return None;
    }
    let (_, soft) = linalg::softest_mode(&k)?;
    moving_joints(m, &(&z * soft))
}

/// The joints of `m` whose coordinates move by more than a tenth of the
/// largest in `motion`, as "joint \"a\" and joint \"b\"".
pub(in crate::mechanism) fn moving_joints<D: Statics>(
    m: &Mechanism<D>,
    motion: &nalgebra::DVector<f64>,
) -> Option<String> {
    let largest = motion.amax();
    let names: Vec<String> = m
        .joints
        .iter()
        .filter(|j| (0..j.kind.joint().dof()).any(|i| motion[j.offset + i].abs() > 0.1 * largest))
        .map(|j| format!("joint {:?}", j.name))
        .collect();
    (!names.is_empty()).then(|| names.join(" and "))
}
