//! Equilibrium under the mechanism's own loads: assembly, then the path from no load.

use super::assembly::assembled_kept;
use super::kkt::Kkt;
use super::path::{Start, follow_path, solution};
#[cfg(doc)]
use super::solve_between;
use super::workspace::{Buffers, Workspace, copy_loads};
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
pub fn solve(m: &Mechanism, settings: &Settings) -> Result<Solution> {
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
pub fn solve_with(m: &Mechanism, settings: &Settings, work: &mut Workspace) -> Result<Solution> {
    if !work.fits(m) {
        *work = Workspace::new(m);
    }
    // One problem from no load to the full load: assembled at λ = 0, then
    // continued from there without a second solve or stability test.
    let [mut zero, mut to] = std::mem::take(&mut work.given);
    m.loads_into(&mut to);
    copy_loads(&to, &mut zero);
    zero.scale(0.0);
    let mut problem = Kkt::fitted(m, &zero, &to, settings, Buffers::Borrowed(work))?;
    let dim = solver::Problem::dim(&problem);
    let mut ws = problem.work.solver(dim);
    // The start as a solution only if the path lost stability: for the refinement.
    let found = assembled_kept(&mut problem, &mut ws, settings).and_then(|path| {
        problem.work.start_x.copy_from_slice(&ws.x);
        ws.start_stable = Some(path.stable);
        let found = follow_path(m, Start::Assembled(&path), &mut problem, &mut ws, settings);
        if !lost(&found, path.stable) {
            return Ok((None, found));
        }
        let x0 = problem.work.start_x.clone();
        Ok((Some(solution(&mut problem, &x0, false, &path)?), found))
    });
    let mut buffers = problem.release();
    buffers.solver = Some(ws);
    buffers.given = [zero, to];
    drop(buffers);
    match found? {
        (Some(start), found) => refine_limit(m, &start, &work.given[1], settings, found),
        (None, found) => found,
    }
}
