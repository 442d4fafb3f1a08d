//! Static equilibrium, stiffness, compliance and linear buckling of a mechanism.
//!
//! Equilibrium minimizes the potential
//! $V(q) = \sum_j U_j(q_j) - \sum_k (F_k\cdot w_k + M_k\theta_k) - \sum_b m_b\,g\cdot w_b + \sum_t T_t\,\ell_t(q)$
//! subject to the closures $c(q) = 0$. Newton solves the KKT conditions
//! $\nabla V + G^T\mu = 0$, $c = 0$ with exact Hessians (the joints' own,
//! chained through the tree), inside load continuation from the unloaded,
//! assembled configuration. Each Newton step costs one dense
//! $(n+m)\times(n+m)$ solve, $O((n+m)^3)$, after assembling point Hessians in
//! $O(n^2)$ per loaded point, for $n$ coordinates and $m$ closure equations.

use super::kinematics::{Frames, frames, point};
use super::{Closure, Loads, Mechanism};
use crate::buckling::{generalized_symmetric, normalized};
use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector, Matrix3, SymmetricEigen};

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Relative tolerance on the KKT residual.
    pub tolerance: f64,
    /// Newton iterations per load step.
    pub max_iterations: usize,
    /// Largest body rotation (rad) one load step may cause.
    pub max_rotation_per_step: f64,
    /// Smallest load step before giving up.
    pub min_load_step: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self { tolerance: 1e-10, max_iterations: 50, max_rotation_per_step: 0.5, min_load_step: 1e-4 }
    }
}

/// An equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Generalized coordinates.
    pub q: Vec<f64>,
    /// Closure multipliers (constraint forces and moments).
    pub multipliers: Vec<f64>,
    /// The loads it carries.
    pub loads: Loads,
    /// Elastic energy stored in the joints (J).
    pub energy: f64,
    /// Whether the constrained stiffness is positive definite.
    pub stable: bool,
    /// Final scaled KKT residual.
    pub residual: f64,
    /// Load-continuation steps.
    pub load_steps: usize,
}

/// Potential, its derivatives and the closures at one configuration.
struct Assembly {
    elastic: f64,
    gradient: DVector<f64>,
    /// Hessian of the Lagrangian $V + \mu^T c$.
    hessian: DMatrix<f64>,
    closure: DVector<f64>,
    /// Closure Jacobian $G$.
    g: DMatrix<f64>,
}

fn wrap(a: f64) -> f64 {
    a - std::f64::consts::TAU * (a / std::f64::consts::TAU).round()
}

fn assemble(m: &Mechanism, q: &[f64], mu: &[f64], loads: &Loads) -> Result<Assembly> {
    let n = m.dof();
    let f = frames(m, q);
    let (mut gradient, mut hessian) = (DVector::zeros(n), DMatrix::zeros(n, n));
    let mut elastic = 0.0;
    for (j, s) in m.joints.iter().zip(&f.joints) {
        let k = s.gradient.len();
        elastic += s.energy;
        let mut g = gradient.rows_mut(j.offset, k);
        g += &s.gradient;
        let mut h = hessian.view_mut((j.offset, j.offset), (k, k));
        h += &s.stiffness;
    }
    let mut push = |body: usize, at: [f64; 2], force: [f64; 2], moment: f64, f: &Frames| {
        if force == [0.0; 2] && moment == 0.0 {
            return;
        }
        let p = point(m, f, body, at, true);
        for c in 0..n {
            gradient[c] -= force[0] * p.jacobian[(1, c)] + force[1] * p.jacobian[(2, c)] + moment * p.jacobian[(0, c)];
        }
        if let Some([hx, hy]) = &p.hessian {
            hessian -= hx * force[0] + hy * force[1];
        }
    };
    for (p, l) in m.forces.iter().zip(&loads.force) {
        push(p.body, p.at, [l[0], l[1]], l[2], &f);
    }
    for (b, body) in m.bodies.iter().enumerate() {
        if body.mass > 0.0 {
            push(b, body.com, [body.mass * loads.gravity[0], body.mass * loads.gravity[1]], 0.0, &f);
        }
    }
    for (t, &tension) in m.tendons.iter().zip(&loads.tension) {
        if tension == 0.0 {
            continue;
        }
        let pts: Vec<_> = t.path.iter().map(|&(b, r)| point(m, &f, b, r, true)).collect();
        for (i, pair) in pts.windows(2).enumerate() {
            let (a, b) = (&pair[0], &pair[1]);
            let d = [b.position[0] - a.position[0], b.position[1] - a.position[1]];
            let len = d[0].hypot(d[1]);
            if len < 1e-15 {
                return Err(Error::Singular {
                    what: format!("tendon {:?}: via points {i} and {} coincide", t.name, i + 1),
                });
            }
            let u = [d[0] / len, d[1] / len];
            let jd = b.jacobian.rows(1, 2) - a.jacobian.rows(1, 2);
            gradient += jd.transpose() * DVector::from_column_slice(&u) * tension;
            let proj = nalgebra::Matrix2::new(1.0 - u[0] * u[0], -u[0] * u[1], -u[0] * u[1], 1.0 - u[1] * u[1]) / len;
            hessian += jd.transpose() * proj * &jd * tension;
            if let (Some([ax, ay]), Some([bx, by])) = (&a.hessian, &b.hessian) {
                hessian += ((bx - ax) * u[0] + (by - ay) * u[1]) * tension;
            }
        }
    }
    let rows = m.constraints();
    let (mut closure, mut g) = (DVector::zeros(rows), DMatrix::zeros(rows, n));
    let mut row = 0;
    for c in &m.closures {
        let (a, ar, aphi, b, br, bphi, angle) = match *c {
            Closure::Weld { a, a_origin, b, b_origin } => {
                (a, [a_origin.x, a_origin.y], a_origin.phi, b, [b_origin.x, b_origin.y], b_origin.phi, true)
            }
            Closure::Pin { a, a_at, b, b_at } => (a, a_at, 0.0, b, b_at, 0.0, false),
        };
        let (pa, pb) = (point(m, &f, a, ar, true), point(m, &f, b, br, true));
        for k in 0..2 {
            closure[row + k] = pa.position[k] - pb.position[k];
            g.row_mut(row + k).copy_from(&(pa.jacobian.row(1 + k) - pb.jacobian.row(1 + k)));
        }
        if let (Some([ax, ay]), Some([bx, by])) = (&pa.hessian, &pb.hessian) {
            hessian += (ax - bx) * mu[row] + (ay - by) * mu[row + 1];
        }
        if angle {
            closure[row + 2] = wrap(pa.angle + aphi - pb.angle - bphi);
            g.row_mut(row + 2).copy_from(&(pa.jacobian.row(0) - pb.jacobian.row(0)));
        }
        row += c.equations();
    }
    Ok(Assembly { elastic, gradient, hessian, closure, g })
}

/// Scales that make the KKT residual dimensionless: a stiffness and a length.
fn scales(m: &Mechanism) -> (f64, f64) {
    let f = frames(m, &m.rest());
    let stiffness =
        f.joints.iter().flat_map(|s| s.stiffness.diagonal().iter().copied().collect::<Vec<_>>()).fold(0.0, f64::max);
    let length = m
        .joints
        .iter()
        .map(|j| {
            j.origin.x.hypot(j.origin.y) + if let super::JointKind::Flexure(fl) = &j.kind { fl.length() } else { 0.0 }
        })
        .sum::<f64>();
    (if stiffness > 0.0 { stiffness } else { 1.0 }, if length > 0.0 { length } else { 1.0 })
}

fn residual(a: &Assembly, mu: &[f64], force: f64, length: f64) -> f64 {
    let top = &a.gradient + a.g.transpose() * DVector::from_column_slice(mu);
    (top.amax() / force).max(a.closure.amax() / length)
}

/// Damped Newton on the KKT system at fixed loads; `q`, `mu` updated in place.
fn newton(m: &Mechanism, q: &mut [f64], mu: &mut [f64], loads: &Loads, settings: &Settings) -> Result<(usize, f64)> {
    let (n, rows) = (m.dof(), m.constraints());
    let (fs, ls) = scales(m);
    let mut a = assemble(m, q, mu, loads)?;
    for iteration in 0..=settings.max_iterations {
        let r = residual(&a, mu, fs, ls);
        if r <= settings.tolerance {
            return Ok((iteration, r));
        }
        let fail = Error::NoConvergence {
            unit: "relative",
            solver: "mechanism equilibrium (KKT Newton)",
            iterations: iteration,
            residual: r,
        };
        if iteration == settings.max_iterations || !r.is_finite() {
            return Err(fail);
        }
        let mut rhs = DVector::zeros(n + rows);
        rhs.rows_mut(0, n).copy_from(&-(&a.gradient + a.g.transpose() * DVector::from_column_slice(mu)));
        rhs.rows_mut(n, rows).copy_from(&-&a.closure);
        let mut kkt = DMatrix::zeros(n + rows, n + rows);
        kkt.view_mut((0, 0), (n, n)).copy_from(&a.hessian);
        kkt.view_mut((0, n), (n, rows)).copy_from(&a.g.transpose());
        kkt.view_mut((n, 0), (rows, n)).copy_from(&a.g);
        // A singular KKT matrix: free joints at zero load (shift the stiffness
        // block up) or redundant closure equations (shift the multiplier block
        // down, which picks the least-norm multipliers).
        let mut step = kkt.clone().lu().solve(&rhs);
        let mut tau = 1e-10;
        while step.is_none() && tau < 1e3 {
            let mut shifted = kkt.clone();
            for i in 0..n {
                shifted[(i, i)] += tau * fs;
            }
            for i in n..n + rows {
                shifted[(i, i)] -= tau * ls * ls / fs;
            }
            step = shifted.lu().solve(&rhs);
            tau *= 100.0;
        }
        let step = step.ok_or(fail.clone())?;
        let mut t = 1.0;
        loop {
            let tq: Vec<f64> = q.iter().enumerate().map(|(i, v)| v + t * step[i]).collect();
            let tm: Vec<f64> = mu.iter().enumerate().map(|(i, v)| v + t * step[n + i]).collect();
            if let Ok(trial) = assemble(m, &tq, &tm, loads) {
                let rt = residual(&trial, &tm, fs, ls);
                if rt < r || (t == 1.0 && r < 1e3 * settings.tolerance && rt < 10.0 * r) {
                    q.copy_from_slice(&tq);
                    mu.copy_from_slice(&tm);
                    a = trial;
                    break;
                }
            }
            t *= 0.5;
            if t < 1e-6 {
                return Err(fail);
            }
        }
    }
    unreachable!("the loop returns at max_iterations")
}

/// Orthonormal basis of the null space of `g` ($n\times 0$ if there are no rows: the identity).
fn null_space(g: &DMatrix<f64>, n: usize) -> DMatrix<f64> {
    if g.nrows() == 0 {
        return DMatrix::identity(n, n);
    }
    let eig = SymmetricEigen::new(g.transpose() * g);
    let top = eig.eigenvalues.amax().max(f64::MIN_POSITIVE);
    let keep: Vec<usize> = (0..n).filter(|&i| eig.eigenvalues[i] <= 1e-10 * top).collect();
    DMatrix::from_fn(n, keep.len(), |r, c| eig.eigenvectors[(r, keep[c])])
}

/// Generalized stiffness on the admissible motions: $Z$ and $Z^T\nabla^2 L\,Z$ (Eq. 27, projected).
fn reduced(m: &Mechanism, s: &Solution) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    let a = assemble(m, &s.q, &s.multipliers, &s.loads)?;
    let z = null_space(&a.g, m.dof());
    let k = z.transpose() * &a.hessian * &z;
    Ok((z, (&k + k.transpose()) * 0.5))
}

fn positive_definite(k: &DMatrix<f64>) -> bool {
    if k.nrows() == 0 {
        return true;
    }
    let e = SymmetricEigen::new(k.clone()).eigenvalues;
    let top = e.amax();
    e.min() > 1e-10 * top
}

/// Equilibrium under `to`, continued from `start` (an equilibrium under `from`).
pub fn solve_between(m: &Mechanism, start: &Solution, to: &Loads, settings: &Settings) -> Result<Solution> {
    let from = &start.loads;
    // A path that starts stable must stay stable: past a buckling or limit
    // load the mechanism has no equilibrium it can reach by loading.
    let watch = start.stable;
    let (mut q, mut mu) = (start.q.clone(), start.multipliers.clone());
    let mut angles: Vec<f64> = frames(m, &q).bodies.iter().map(|b| b.angle).collect();
    let mut history: Option<(f64, Vec<f64>, Vec<f64>)> = None;
    let (mut s, mut allowed, mut steps, mut last) = (0.0_f64, 1.0_f64, 0, (0, 0.0));
    while s < 1.0 {
        let target = (s + allowed).min(1.0);
        let (mut tq, mut tm) = (q.clone(), mu.clone());
        if let Some((sp, qp, mp)) = &history {
            let ratio = (target - s) / (s - sp);
            tq.iter_mut().zip(&qp[..]).for_each(|(v, p)| *v += (*v - p) * ratio);
            tm.iter_mut().zip(&mp[..]).for_each(|(v, p)| *v += (*v - p) * ratio);
        }
        let loads = from.lerp(to, target);
        let found = newton(m, &mut tq, &mut tm, &loads, settings);
        let turned = frames(m, &tq).bodies.iter().zip(&angles).map(|(b, a)| (b.angle - a).abs()).fold(0.0, f64::max);
        match found {
            Ok(r) if turned <= settings.max_rotation_per_step => {
                if watch {
                    let trial = Solution {
                        q: tq.clone(),
                        multipliers: tm.clone(),
                        loads: loads.clone(),
                        energy: 0.0,
                        stable: false,
                        residual: r.1,
                        load_steps: steps,
                    };
                    if !positive_definite(&reduced(m, &trial)?.1) {
                        // Bisect between the last stable step and this one for where it is lost.
                        let (mut lo, mut hi) = (s, target);
                        while hi - lo > 1e-6 {
                            let mid = 0.5 * (lo + hi);
                            let (mut bq, mut bm) = (q.clone(), mu.clone());
                            let mid_loads = from.lerp(to, mid);
                            let stable = newton(m, &mut bq, &mut bm, &mid_loads, settings).ok().is_some_and(|_| {
                                let probe = Solution { q: bq, multipliers: bm, loads: mid_loads, ..trial.clone() };
                                reduced(m, &probe).is_ok_and(|(_, k)| positive_definite(&k))
                            });
                            if stable { lo = mid } else { hi = mid }
                        }
                        return Err(Error::Unstable { what: "mechanism equilibrium", load_fraction: hi });
                    }
                }
                history = Some((s, q.clone(), mu.clone()));
                (q, mu, s, last) = (tq, tm, target, r);
                angles = frames(m, &q).bodies.iter().map(|b| b.angle).collect();
                steps += 1;
                allowed *= 2.0;
            }
            other => {
                allowed = 0.5 * (target - s);
                if allowed < settings.min_load_step {
                    let residual = match other {
                        Err(Error::NoConvergence { residual, .. }) => residual,
                        _ => last.1,
                    };
                    return Err(Error::NoConvergence {
                        unit: "relative",
                        solver: "mechanism equilibrium (no equilibrium reachable by load continuation; beyond a limit or buckling load?)",
                        iterations: steps,
                        residual,
                    });
                }
            }
        }
    }
    let a = assemble(m, &q, &mu, to)?;
    let mut sol = Solution {
        q,
        multipliers: mu,
        loads: to.clone(),
        energy: a.elastic,
        stable: false,
        residual: last.1,
        load_steps: steps,
    };
    sol.stable = positive_definite(&reduced(m, &sol)?.1);
    Ok(sol)
}

/// The unloaded, assembled configuration: the rest coordinates moved, if
/// the closures require it, to the nearest configuration that closes them.
pub fn assemble_unloaded(m: &Mechanism, settings: &Settings) -> Result<Solution> {
    let zero = m.loads().zero_like();
    let (mut q, mut mu) = (m.rest(), vec![0.0; m.constraints()]);
    let (_, r) = newton(m, &mut q, &mut mu, &zero, settings)?;
    let a = assemble(m, &q, &mu, &zero)?;
    let mut sol =
        Solution { q, multipliers: mu, loads: zero, energy: a.elastic, stable: false, residual: r, load_steps: 0 };
    sol.stable = positive_definite(&reduced(m, &sol)?.1);
    Ok(sol)
}

/// Equilibrium under the mechanism's loads, by continuation from the unloaded, assembled shape.
pub fn solve(m: &Mechanism, settings: &Settings) -> Result<Solution> {
    let start = assemble_unloaded(m, settings)?;
    solve_between(m, &start, &m.loads(), settings)
}

/// Frames of the solution.
pub fn body_frames(m: &Mechanism, s: &Solution) -> Frames {
    frames(m, &s.q)
}

/// Generalized stiffness on the admissible motions, $Z^T\nabla^2 L Z$ (Eq. 27), and $Z$.
pub fn stiffness(m: &Mechanism, s: &Solution) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    reduced(m, s)
}

/// Compliance of the frame at `at` on `body` to a small extra load
/// $(M, F_x, F_y)$ there: $C = J Z (Z^T\nabla^2 L Z)^{-1} Z^T J^T$, order $(\phi, x, y)$.
pub fn compliance(m: &Mechanism, s: &Solution, body: usize, at: [f64; 2]) -> Result<Matrix3<f64>> {
    let (z, k) = reduced(m, s)?;
    let chol = k.cholesky().ok_or_else(|| Error::Singular {
        what: "the constrained stiffness is not positive definite: the equilibrium is unstable or a joint is free"
            .into(),
    })?;
    let f = frames(m, &s.q);
    let jz = point(m, &f, body, at, false).jacobian * &z;
    let c = &jz * chol.solve(&jz.transpose());
    Ok(Matrix3::from_fn(|i, j| c[(i, j)]))
}

/// Result of [`buckle`].
#[derive(Debug, Clone, PartialEq)]
pub struct Buckling {
    /// Factor on all forces, tensions and gravity at which the constrained stiffness becomes singular.
    pub load_factor: f64,
    /// Buckling mode in generalized coordinates, unit length, largest entry positive.
    pub mode: Vec<f64>,
}

/// Linear buckling: the smallest $\lambda > 0$ with
/// $\det Z^T(K_0 + \lambda K_g)Z = 0$ at the unloaded configuration, where
/// $K_0$ is the elastic stiffness and $K_g$ the loads' geometric stiffness
/// (with closure forces from the linear pre-buckling solve).
pub fn buckle(m: &Mechanism, settings: &Settings) -> Result<Buckling> {
    let s0 = assemble_unloaded(m, settings)?;
    let (n, rows) = (m.dof(), m.constraints());
    let base = m.loads();
    let a0 = assemble(m, &s0.q, &s0.multipliers, &s0.loads)?;
    let a1 = assemble(m, &s0.q, &s0.multipliers, &base)?;
    let load_gradient = &a1.gradient - &a0.gradient;
    // Linear pre-buckling state: the closure forces that carry the loads.
    let mut kkt = DMatrix::zeros(n + rows, n + rows);
    kkt.view_mut((0, 0), (n, n)).copy_from(&a0.hessian);
    kkt.view_mut((0, n), (n, rows)).copy_from(&a0.g.transpose());
    kkt.view_mut((n, 0), (rows, n)).copy_from(&a0.g);
    let mut rhs = DVector::zeros(n + rows);
    rhs.rows_mut(0, n).copy_from(&-&load_gradient);
    let pre = kkt.lu().solve(&rhs).ok_or_else(|| Error::Singular {
        what: "the unloaded mechanism has a zero-stiffness mode (a free joint): linear buckling is undefined".into(),
    })?;
    let mu1: Vec<f64> = s0.multipliers.iter().zip(pre.rows(n, rows).iter()).map(|(a, b)| a + b).collect();
    let closure_part = assemble(m, &s0.q, &mu1, &s0.loads)?.hessian - &a0.hessian;
    let geometric = &a1.hessian - &a0.hessian + closure_part;
    let z = null_space(&a0.g, n);
    let a = z.transpose() * &a0.hessian * &z;
    let b = z.transpose() * geometric * &z;
    let (mus, modes) = generalized_symmetric(&a, &b).ok_or_else(|| Error::Singular {
        what: "the unloaded mechanism has a zero-stiffness mode (a free joint): linear buckling is undefined".into(),
    })?;
    // det(A + λB) = 0 ⇔ λ = −1/μ for eigenvalues μ of B v = μ A v; the smallest positive λ comes from the most negative μ.
    let (best, &mu) = mus
        .iter()
        .enumerate()
        .min_by(|x, y| x.1.total_cmp(y.1))
        .ok_or_else(|| Error::Singular { what: "no admissible motion to buckle".into() })?;
    if mu >= -1e-14 * mus.amax() {
        return Err(Error::Singular { what: "these loads only stiffen the mechanism: no buckling load".into() });
    }
    let mode = normalized(&z * modes.column(best));
    Ok(Buckling { load_factor: -1.0 / mu, mode: mode.iter().copied().collect() })
}

/// A load that a sweep varies.
#[derive(Debug, Clone, PartialEq)]
pub enum Parameter {
    /// `tendon.NAME.tension`
    Tension(usize),
    /// `force.NAME.fx`, `.fy` or `.moment` (component 0, 1, 2).
    Force(usize, usize),
    /// `gravity.x` or `gravity.y`.
    Gravity(usize),
}

impl Parameter {
    /// Parses `tendon.NAME.tension`, `force.NAME.fx|fy|moment` or `gravity.x|y`.
    pub fn parse(m: &Mechanism, spec: &str) -> Result<Parameter> {
        let bad = |why: &'static str| Error::invalid("sweep", format!("{spec:?}"), why);
        let parts: Vec<&str> = spec.split('.').collect();
        match parts.as_slice() {
            ["tendon", name, "tension"] => m
                .tendons
                .iter()
                .position(|t| t.name == *name)
                .map(Parameter::Tension)
                .ok_or_else(|| bad("names no tendon of the mechanism")),
            ["force", name, comp] => {
                let k = m
                    .forces
                    .iter()
                    .position(|f| f.name == *name)
                    .ok_or_else(|| bad("names no force of the mechanism"))?;
                let c = match *comp {
                    "fx" => 0,
                    "fy" => 1,
                    "moment" => 2,
                    _ => return Err(bad("a force's component is fx, fy or moment")),
                };
                Ok(Parameter::Force(k, c))
            }
            ["gravity", "x"] => Ok(Parameter::Gravity(0)),
            ["gravity", "y"] => Ok(Parameter::Gravity(1)),
            _ => Err(bad("must be tendon.NAME.tension, force.NAME.fx|fy|moment or gravity.x|y")),
        }
    }

    /// `loads` with this parameter set to `value`.
    pub fn apply(&self, loads: &Loads, value: f64) -> Loads {
        let mut l = loads.clone();
        match *self {
            Parameter::Tension(t) => l.tension[t] = value,
            Parameter::Force(k, c) => l.force[k][c] = value,
            Parameter::Gravity(c) => l.gravity[c] = value,
        }
        l
    }
}

/// Equilibria along `values` of one load, each continued from the last.
pub fn sweep(m: &Mechanism, parameter: &Parameter, values: &[f64], settings: &Settings) -> Result<Vec<Solution>> {
    if let Parameter::Tension(_) = parameter
        && let Some(v) = values.iter().find(|v| !(v.is_finite() && **v >= 0.0))
    {
        return Err(Error::invalid("sweep", v, "a tendon's tension must be finite and not negative"));
    }
    let base = m.loads();
    let mut out: Vec<Solution> = Vec::with_capacity(values.len());
    let mut start = assemble_unloaded(m, settings)?;
    for &v in values {
        let s = solve_between(m, &start, &parameter.apply(&base, v), settings)?;
        start = s.clone();
        out.push(s);
    }
    Ok(out)
}
