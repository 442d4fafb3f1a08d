//! The unloaded, assembled configuration: the start of every path.

use super::dimension::Statics;
use super::kkt::Kkt;
use super::path::solution;
use super::workspace::{Buffers, Workspace};
use super::{Settings, Solution};
use crate::error::{Error, Result};
use crate::mechanism::Mechanism;
use crate::mechanism::kinematics::frames;
use crate::mechanism::lagrangian::closures;
use crate::solver;

/// The unloaded, assembled configuration: the rest coordinates moved, if
/// the closures require it, to the nearest configuration that closes them.
/// Its geoms play no part: whether a part there overlaps one is the caller's to check.
pub fn assemble_unloaded<D: Statics>(m: &Mechanism<D>, settings: &Settings) -> Result<Solution<D>> {
    let mut work = Workspace::new(m);
    work.touching = true;
    assemble_in(m, settings, &mut work)
}

/// [`assemble_unloaded`] in the buffers `work` (made for `m`).
pub(super) fn assemble_in<D: Statics>(
    m: &Mechanism<D>,
    settings: &Settings,
    work: &mut Workspace<D>,
) -> Result<Solution<D>> {
    let zero = D::zero(&m.loads());
    if !work.fits(m) {
        return Err(Error::invalid("workspace", work.dof, "was made for another mechanism"));
    }
    let mut problem = Kkt::fitted(m, &zero, &zero, settings, Buffers::Borrowed(work))?;
    let dim = solver::Problem::dim(&problem);
    let mut ws = problem.work.solver(dim);
    let found = assemble(&mut problem, &mut ws, settings);
    let mut work = problem.release();
    work.solver = Some(ws);
    found
}

/// The unloaded, assembled configuration, by Newton from rest on the
/// problem at $\lambda = 0$ (whose loads there must be zero), left in `ws`.
pub(super) fn assemble<D: Statics>(
    problem: &mut Kkt<D>,
    ws: &mut solver::SolverWorkspace<f64>,
    settings: &Settings,
) -> Result<Solution<D>> {
    let path = assembled(problem, ws, settings)?;
    solution(problem, &ws.x, false, &path)
}

/// [`assemble`] without the solution: how the path to it went. Newton
/// converges to the tolerance of the whole path, or with
/// [`Statics::OWN_ASSEMBLY`] to that of the loads at $\lambda = 0$ alone.
pub(super) fn assembled<D: Statics>(
    problem: &mut Kkt<D>,
    ws: &mut solver::SolverWorkspace<f64>,
    settings: &Settings,
) -> Result<solver::Path> {
    let m = problem.mechanism;
    ws.x.fill(0.0);
    m.rest_into(&mut ws.x[..m.dof()]);
    let start = assembly_scale(problem);
    let full = std::mem::replace(&mut problem.scale, start);
    let report = solver::newton(problem, ws, 0.0, settings);
    problem.scale = full;
    match report {
        Ok(report) => {
            let stable = solver::Problem::stable(problem, &ws.x, 0.0, &ws.jacobian);
            Ok(solver::Path::at_start(report, stable))
        }
        Err(e @ (Error::NoConvergence { .. } | Error::Singular { .. })) => Err(D::unassembled(m, problem.length, e)),
        Err(e) => Err(e),
    }
}

/// The scale of the assembly's Newton tolerance ([`assembled`]).
fn assembly_scale<D: Statics>(problem: &Kkt<D>) -> f64 {
    if D::OWN_ASSEMBLY { problem.start_scale } else { problem.scale }
}

/// [`assembled`] for [`solve_with`](super::solve_with): the start the workspace keeps if it
/// is this problem's (`StartCache::holds`), with the load derivative of
/// this problem's loads; else solved, and kept.
pub(super) fn assembled_kept<D: Statics>(
    problem: &mut Kkt<D>,
    ws: &mut solver::SolverWorkspace<f64>,
    settings: &Settings,
) -> Result<solver::Path> {
    let m = problem.mechanism;
    // The tolerance of solver::newton.
    let tolerance = settings.tolerance * assembly_scale(problem);
    if let Some((report, stable)) = problem.work.start.holds(m, settings, tolerance) {
        let Workspace { start, assembled, .. } = &mut *problem.work;
        ws.x.copy_from_slice(&start.x);
        ws.jacobian.copy_from_slice(&start.jacobian);
        // The workspace's frames are not the start's: the next evaluation makes them.
        *assembled = false;
        problem.load_derivative(ws.dlambda_mut(), true)?;
        ws.restore_start(report, stable);
        return Ok(solver::Path::at_start(report, stable));
    }
    let found = assembled(problem, ws, settings)?;
    // `assembled` returns only what solver::newton converged.
    let report = solver::NewtonReport {
        stop: solver::NewtonStop::Converged,
        iterations: found.iterations,
        residual: found.residual,
    };
    let Workspace { start, frames, .. } = &mut *problem.work;
    start.keep(m, settings, tolerance, report, found.stable, &ws.x, &ws.jacobian, frames);
    Ok(solver::Path::at_start(report, found.stable))
}

/// The error for closures that Newton could not close from rest: placed at
/// the closure open widest at rest (position gap over the mechanism's
/// `length`, plus angle gap), or `e` itself if all are closed there.
pub(super) fn unassembled(m: &Mechanism, length: f64, e: Error) -> Error {
    let rest = frames(m, &m.rest());
    let (c, _) = closures(m, &rest);
    let mut row = 0;
    let mut widest: Option<(usize, f64, f64, f64)> = None;
    for (i, closure) in m.closures.iter().enumerate() {
        let gap = c[row].hypot(c[row + 1]);
        let turn = if closure.equations() == 3 { c[row + 2].abs() } else { 0.0 };
        let size = gap / length + turn;
        if size > widest.map_or(1e-9, |w| w.1) {
            widest = Some((i, size, gap, turn));
        }
        row += closure.equations();
    }
    let Some((i, _, gap, turn)) = widest else { return e };
    let what = m.closures[i].name(m);
    Error::File {
        place: m.closure_place(i).to_string(),
        message: format!(
            "{what}: the closures cannot be assembled; at rest this one is open widest ({gap:.3e} m, {turn:.3e} rad), and from there {e}"
        ),
    }
}
