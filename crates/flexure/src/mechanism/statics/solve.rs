//! Equilibrium under the mechanism's own loads: assembly, then the path from no load.

use super::assembly::assembled_kept;
use super::dimension::Statics;
use super::kkt::Kkt;
use super::path::{Start, follow_path, solution, solve_between};
use super::workspace::{Buffers, Workspace};
use super::{Settings, Solution};
use crate::error::Result;
use crate::mechanism::Mechanism;
use crate::mechanism::equilibria::{lost, refine_limit};
use crate::solver;

/// Equilibrium under the mechanism's loads, by continuation from the
/// unloaded, assembled shape (see [`solve_between`] for the policy).
///
/// # Example
/// ```
/// use flexure::mechanism::{file::from_toml, statics::{solve, Settings}};
/// let m = from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n\
///      [[force]]\nbody = \"arm\"\nat = [0.0, 0.0]\nmoment = 0.5\n",
/// )
/// .unwrap();
/// let s = solve(&m, &Settings::default()).unwrap();
/// assert!(s.stable && (s.q[0] - 0.25).abs() < 1e-12); // M/k
/// ```
pub fn solve<D: Statics>(m: &Mechanism<D>, settings: &Settings) -> Result<Solution<D>> {
    solve_with(m, settings, &mut Workspace::new(m))
}

/// [`solve`] in the buffers `work`, kept for the next solve on the same
/// mechanism (a workspace made for other joints is replaced). The
/// workspace also keeps the assembled, unloaded start and its stability,
/// reused while the closures and settings stay the same: a solve from a
/// kept workspace equals a fresh one to the bit.
///
/// # Example
/// ```
/// use flexure::mechanism::{file::from_toml, statics::{solve_with, Settings, Workspace}};
/// let m = from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n\
///      [[force]]\nbody = \"arm\"\nat = [0.0, 0.0]\nmoment = 0.5\n",
/// )
/// .unwrap();
/// let mut work = Workspace::new(&m);
/// for _ in 0..2 {
///     let s = solve_with(&m, &Settings::default(), &mut work).unwrap();
///     assert!(s.stable && (s.q[0] - 0.25).abs() < 1e-12); // M/k
/// }
/// ```
pub fn solve_with<D: Statics>(m: &Mechanism<D>, settings: &Settings, work: &mut Workspace<D>) -> Result<Solution<D>> {
    if !work.fits(m) {
        *work = Workspace::new(m);
    }
    if !crate::mechanism::contact::pairs(m).is_empty() {
        return super::contact::solve_touching(m, settings, work);
    }
    // One problem from no load to the full load: assembled at λ = 0, then
    // continued from there without a second solve or stability test.
    let [mut zero, mut to] = std::mem::take(&mut work.given);
    m.loads_into(&mut to);
    D::zero_into(&to, &mut zero);
    let mut problem = Kkt::fitted(m, &zero, &to, settings, Buffers::Borrowed(work))?;
    let dim = solver::Problem::dim(&problem);
    let mut ws = problem.work.solver(dim);
    // The start as a solution only if the path lost stability (for the
    // refinement), or if it is the start of a second path (`Restart`).
    let found = assembled_kept(&mut problem, &mut ws, settings).and_then(|path| {
        problem.work.start_x.copy_from_slice(&ws.x);
        if D::OWN_ASSEMBLY {
            if m.constraints() > 0 {
                // Redundant closures: the path continues from the settled
                // multipliers, at which this Jacobian was not evaluated.
                let x0 = problem.work.start_x.clone();
                let mu = problem.multipliers(&x0);
                let zero = problem.from.clone();
                if D::settled(&mut problem, &x0[..m.dof()], mu.clone(), &zero) != mu {
                    return Ok(Found::Restart(solution(&mut problem, &x0, false, &path)?));
                }
            }
            // The path's own count: the assembly's iterations are not the path's.
            let report =
                solver::NewtonReport { stop: solver::NewtonStop::Converged, iterations: 0, residual: path.residual };
            ws.restore_start(report, path.stable);
        } else {
            ws.start_stable = Some(path.stable);
        }
        let found = follow_path(m, Start::Assembled(&path), &mut problem, &mut ws, settings);
        if !lost(&found, path.stable) {
            return Ok(Found::Path(None, found));
        }
        let x0 = problem.work.start_x.clone();
        Ok(Found::Path(Some(solution(&mut problem, &x0, false, &path)?), found))
    });
    let mut buffers = problem.release();
    buffers.solver = Some(ws);
    buffers.given = [zero, to];
    drop(buffers);
    match found? {
        Found::Path(Some(start), found) => refine_limit(m, &start, &work.given[1], settings, found),
        Found::Path(None, found) => found,
        Found::Restart(start) => solve_between(m, &start, &work.given[1], settings),
    }
}

/// What the path from the assembled start found: its end, with the start
/// if the path lost stability; or the start, settled, to continue from.
enum Found<D: Statics> {
    Path(Option<Solution<D>>, Result<Solution<D>>),
    Restart(Solution<D>),
}
