//! Static equilibrium, stiffness and compliance of a spatial mechanism.
//!
//! As in the plane ([`crate::mechanism::statics`]): equilibrium is
//! $$\nabla V - Q_m + G^T\mu = 0,\qquad c(q) = 0,$$
//! ([`super::lagrangian`]) with the KKT matrix $\begin{bmatrix}H & G^T\cr G & 0\end{bmatrix}$
//! as Jacobian, followed by the shared continuation ([`crate::solver`])
//! from the unloaded, assembled configuration in the load factor
//! $\lambda$, through folds, reporting where stability was lost.
//! Stability is the constrained stiffness $Z^THZ$ (symmetrized: a dead
//! moment's part is not symmetric) positive definite with the planar
//! margin, $Z$ spanning the null space of $G$, in coordinates scaled to
//! each joint's own stiffness. Scaling of rows and multipliers is the
//! planar [`crate::mechanism::statics::Kkt`]'s.
//!
//! The Newton matrix is assembled from frames at [`Level::Jacobian`]: each
//! joint's part of $H$ is its motion subspace's derivative contracted with
//! the wrench it carries ([`crate::mechanism::Joint::add_wrench_hessian`];
//! for a spatial flexure by quadrature of the virtual work, within the
//! Magnus rule's $h^6$ of the exact Hessian: about $10^{-8}$ of the load
//! stiffness at a bend of a radian per flexure). The residual is exact, so
//! only Newton's rate and the stability tests' matrix see the difference;
//! [`stiffness`] and [`compliance`] take the exact Hessian.

use super::kinematics::{SpatialFrames, attach, distance_of, frames_level_into};
use super::lagrangian::{SpatialAssembly, add_closure_hessian, add_loads, assemble_into};
use super::{SpatialLoads, SpatialMechanism};
use crate::error::{Error, Result};
use crate::kinematics::Level;
use crate::linalg;
use crate::mechanism::equilibria::{lost, refine_limit};
use crate::mechanism::statics::Solution;
use crate::solver::{self, Settings};
use crate::space::Spatial;
use nalgebra::{DMatrix, DVector, Isometry3, Matrix6, Point3, Vector3};
use std::cell::RefCell;

/// An equilibrium of a spatial mechanism ([`Solution`]).
pub type SpatialSolution = Solution<Spatial>;

/// The KKT conditions of a spatial mechanism under the loads
/// $\text{from} + \lambda(\text{to} - \text{from})$, as a [`solver::Problem`]
/// (unknowns $(q, \nu)$, $\mu_i = s_i\nu_i$, rows scaled as the planar `Kkt`'s).
#[derive(Debug)]
pub struct SpatialKkt<'a> {
    mechanism: &'a SpatialMechanism,
    from: SpatialLoads,
    to: SpatialLoads,
    change: SpatialLoads,
    row_scale: Vec<f64>,
    closure_scale: Vec<f64>,
    multiplier_scale: Vec<f64>,
    weight: Vec<f64>,
    /// $\sqrt{s_i}$ of the row scales: the stability tests' coordinates.
    root_scale: Vec<f64>,
    scale: f64,
    /// The scale of the assembly alone (the loads at $\lambda = 0$ both
    /// ends), whose tolerance [`assemble`] converges to.
    start_scale: f64,
    margin: f64,
    frames: SpatialFrames,
    assembly: SpatialAssembly,
    loads: SpatialLoads,
    mu: Vec<f64>,
    /// Pose-level frames for [`solver::Problem::distance`], each with
    /// whether it holds its coordinates' frames yet: a continuation asks
    /// for the distance from the same state several times.
    pair: RefCell<([SpatialFrames; 2], [bool; 2])>,
    /// The stability tests' matrix and Cholesky scratch ($n^2$ each).
    definite: Vec<f64>,
    scratch: Vec<f64>,
}

impl<'a> SpatialKkt<'a> {
    /// The problem of moving `m` from `from` to `to`, for a solver run with
    /// `settings` (whose tolerance sets the stability margin).
    pub fn new(m: &'a SpatialMechanism, from: &SpatialLoads, to: &SpatialLoads, settings: &Settings) -> Result<Self> {
        settings.validate()?;
        from.validate(m)?;
        to.validate(m)?;
        let n = m.dof();
        let length = m.size();
        // The joints' stiffness is there at every level.
        let f = frames_at(m, &m.rest(), Level::Pose);
        let mut stiffness = vec![0.0; n];
        let mut unit = vec![1.0; n];
        for (j, s) in m.joints.iter().zip(&f.joints) {
            let joint = j.kind.joint();
            for i in 0..joint.dof() {
                stiffness[j.offset + i] = s.stiffness[(i, i)];
                if joint.is_translation() {
                    unit[j.offset + i] = length * length;
                }
            }
        }
        let moments = || stiffness.iter().zip(&unit).map(|(k, u)| k * u);
        let k_max = moments().fold(0.0, f64::max);
        let k_max = if k_max > 0.0 { k_max } else { 1.0 };
        let k_min = moments().filter(|&k| k > 0.0).fold(k_max, f64::min);
        let row_scale: Vec<f64> =
            stiffness.iter().zip(&unit).map(|(k, u)| if *k > 0.0 { 1.0 / k } else { u / k_max }).collect();
        let weight = unit.iter().map(|u| 1.0 / u.sqrt()).collect();
        let (mut closure_scale, mut multiplier_scale) = (Vec::new(), Vec::new());
        for c in &m.closures {
            for row in 0..c.equations() {
                let position = row < 3;
                closure_scale.push(if position { 1.0 / length } else { 1.0 });
                multiplier_scale.push(if position { k_max / length } else { k_max });
            }
        }
        let magnitude = |l: &SpatialLoads| {
            let forces: f64 =
                l.force.iter().map(|w| w.fixed_rows::<3>(3).norm() * length + w.fixed_rows::<3>(0).norm()).sum();
            let tendons: f64 = l.tension.iter().map(|t| t * length).sum();
            let mass: f64 = m.bodies.iter().map(|b| b.mass).sum();
            forces + tendons + mass * l.gravity.norm() * length
        };
        let scale = 1.0 + (magnitude(from) + magnitude(to)) / k_min;
        let start_scale = 1.0 + (magnitude(from) + magnitude(from)) / k_min;
        if !scale.is_finite() {
            return Err(Error::invalid(
                "loads",
                format!("{:.3e}", scale - 1.0),
                "are too large for the joints' stiffness to be represented",
            ));
        }
        Ok(SpatialKkt {
            mechanism: m,
            from: from.clone(),
            to: to.clone(),
            change: from.difference(to),
            closure_scale,
            multiplier_scale,
            weight,
            root_scale: row_scale.iter().map(|r| r.sqrt()).collect(),
            scale,
            start_scale,
            margin: settings.tolerance.sqrt(),
            frames: f,
            assembly: SpatialAssembly::new(m),
            loads: from.clone(),
            mu: vec![0.0; m.constraints()],
            pair: RefCell::new(([SpatialFrames::new(m), SpatialFrames::new(m)], [false; 2])),
            definite: vec![0.0; n * n],
            scratch: vec![0.0; n * n],
            row_scale,
        })
    }

    /// The unknowns $(q, \nu)$ of coordinates `q` and multipliers `mu`.
    pub fn state(&self, q: &[f64], mu: &[f64]) -> Vec<f64> {
        q.iter().copied().chain(mu.iter().zip(&self.multiplier_scale).map(|(m, s)| m / s)).collect()
    }

    /// The multipliers $\mu$ of the unknowns `x`.
    pub fn multipliers(&self, x: &[f64]) -> Vec<f64> {
        x[self.mechanism.dof()..].iter().zip(&self.multiplier_scale).map(|(v, s)| v * s).collect()
    }

    /// The solution at unknowns `x`, at the end of `path` (`end`) or its start.
    fn solution(&mut self, x: &[f64], end: bool, path: &solver::Path) -> Result<SpatialSolution> {
        let m = self.mechanism;
        let n = m.dof();
        let mu = self.multipliers(x);
        let loads = if end { &self.to } else { &self.from };
        let multipliers = if mu.is_empty() {
            // The energy alone: the joints' at their coordinates, at any
            // level, so from the last evaluation if that was at `x`.
            let at_x = self.frames.coordinates.iter().zip(&x[..n]).all(|(a, b)| a.to_bits() == b.to_bits());
            if !at_x {
                frames_level_into(m, &x[..n], Level::Pose, &mut self.frames);
            }
            mu
        } else {
            frames_level_into(m, &x[..n], Level::Jacobian, &mut self.frames);
            assemble_into(m, &self.frames, &mu, loads, false, &mut self.assembly);
            settled(m, &self.frames, &self.assembly, &mu, loads)
        };
        let energy = self.frames.joints.iter().map(|s| s.energy).sum::<f64>() + 0.0;
        if !(energy.is_finite() && x.iter().chain(&multipliers).all(|v| v.is_finite())) {
            return Err(Error::Singular { what: "mechanism equilibrium: the solution is not finite".into() });
        }
        Ok(SpatialSolution {
            q: x[..n].to_vec(),
            multipliers,
            loads: if end { self.to.clone() } else { self.from.clone() },
            energy,
            stable: path.stable,
            limit: path.limit,
            residual: path.residual,
            load_steps: path.steps,
            iterations: path.iterations,
        })
    }
}

impl solver::Problem<f64> for SpatialKkt<'_> {
    fn dim(&self) -> usize {
        self.mechanism.dof() + self.mechanism.constraints()
    }

    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        residual: &mut [f64],
        jacobian: Option<&mut [f64]>,
        dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        for ((mu, v), s) in self.mu.iter_mut().zip(&x[n..]).zip(&self.multiplier_scale) {
            *mu = v * s;
        }
        // Jacobian-level frames even for the Newton matrix: each joint's
        // second derivatives enter contracted with the wrench it carries
        // (`Joint::add_wrench_hessian`; module docs).
        frames_level_into(m, &x[..n], Level::Jacobian, &mut self.frames);
        self.from.lerp_into(&self.to, lambda, &mut self.loads);
        let a = &mut self.assembly;
        assemble_into(m, &self.frames, &self.mu, &self.loads, jacobian.is_some(), a);
        let g = &a.closure_jacobian;
        for i in 0..n {
            let mut force = a.gradient[i];
            for (k, mu) in self.mu.iter().enumerate() {
                force += g[(k, i)] * mu;
            }
            residual[i] = force * self.row_scale[i];
        }
        for i in 0..rows {
            residual[n + i] = a.closure[i] * self.closure_scale[i];
        }
        if !residual.iter().all(|r| r.is_finite()) {
            return Err(Error::Singular { what: "mechanism equilibrium: a non-finite generalized force".into() });
        }
        if let Some(jac) = jacobian {
            for c in 0..n {
                for r in 0..n {
                    jac[c * size + r] = a.hessian[(r, c)] * self.row_scale[r];
                }
                for i in 0..rows {
                    jac[c * size + n + i] = g[(i, c)] * self.closure_scale[i];
                }
            }
            for i in 0..rows {
                let column = &mut jac[(n + i) * size..(n + i + 1) * size];
                for r in 0..n {
                    column[r] = g[(i, r)] * self.multiplier_scale[i] * self.row_scale[r];
                }
                column[n..].fill(0.0);
                column[n + i] = -1e-10;
            }
        }
        if let Some(d) = dlambda {
            let mut gradient = DVector::zeros(n);
            add_loads(m, &self.frames, &self.change, &mut gradient, None);
            for i in 0..n {
                d[i] = gradient[i] * self.row_scale[i];
            }
            d[n..].fill(0.0);
        }
        Ok(())
    }

    /// $\tilde Z^T\tilde H\tilde Z - \sqrt{\text{tolerance}}\thinspace I$ positive
    /// definite, in coordinates scaled to each joint's stiffness, $H$ symmetrized.
    fn stable(&mut self, _x: &[f64], _lambda: f64, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        if n == 0 {
            return true;
        }
        let size = n + rows;
        let s = &self.root_scale;
        let entry = |r: usize, c: usize| jacobian[c * size + r] / self.row_scale[r];
        if rows == 0 {
            // In the buffers: no allocation on the continuation's every step.
            let k = &mut self.definite;
            for c in 0..n {
                for r in 0..n {
                    k[c * n + r] = 0.5 * (entry(r, c) + entry(c, r)) * s[r] * s[c];
                }
                k[c * n + c] -= self.margin;
            }
            return linalg::positive_definite(k, n, &mut self.scratch);
        }
        let mut h = DMatrix::from_fn(n, n, |r, c| 0.5 * (entry(r, c) + entry(c, r)) * s[r] * s[c]);
        // Redundant closures: their indeterminate part of μ taken least (see `settled`).
        let mu = &self.mu;
        let best = settled(m, &self.frames, &self.assembly, mu, &self.loads);
        if best != *mu {
            let change: Vec<f64> = best.iter().zip(mu).map(|(a, b)| a - b).collect();
            let mut extra = DMatrix::zeros(n, n);
            add_closure_hessian(m, &self.frames, &change, &mut extra);
            h += DMatrix::from_fn(n, n, |r, c| extra[(r, c)] * s[r] * s[c]);
        }
        let g = DMatrix::from_fn(rows, n, |i, c| jacobian[c * size + n + i] / self.closure_scale[i] * s[c]);
        let z = linalg::null_space(&g);
        let k = z.transpose() * h * &z;
        let mut k = (&k + k.transpose()) * 0.5;
        for i in 0..k.nrows() {
            k[(i, i)] -= self.margin;
        }
        linalg::is_positive_definite(&k)
    }

    /// Without closures: the symmetrized $H - \tfrac12 K$ positive definite,
    /// $K$ the joints' elastic stiffness, as the planar mechanism tests it.
    fn far_from_instability(&mut self, _x: &[f64], _lambda: f64, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let n = m.dof();
        if m.constraints() > 0 || n == 0 {
            return false;
        }
        let k = &mut self.definite;
        for c in 0..n {
            for r in 0..n {
                k[c * n + r] =
                    0.5 * (jacobian[c * n + r] / self.row_scale[r] + jacobian[r * n + c] / self.row_scale[c]);
            }
        }
        for (j, s) in m.joints.iter().zip(&self.frames.joints) {
            let (o, d) = (j.offset, s.gradient.len());
            for c in 0..d {
                for r in 0..d {
                    k[(o + c) * n + o + r] -= s.stiffness[(r, c)] * crate::mechanism::statics::FAR_MARGIN;
                }
            }
        }
        linalg::positive_definite(k, n, &mut self.scratch)
    }

    /// [`super::kinematics::distance`], with the frames at a configuration
    /// of the last call kept (the same coordinates, bit for bit, give the
    /// same frames).
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        let m = self.mechanism;
        let n = m.dof();
        let (a, b) = (&a[..n], &b[..n]);
        let (frames, held) = &mut *self.pair.borrow_mut();
        let holds = |f: &SpatialFrames, held: bool, q: &[f64]| {
            held && f.coordinates.iter().zip(q).all(|(x, y)| x.to_bits() == y.to_bits())
        };
        // Frames for `b` (slot 1 unless slot 0 already holds them), then for `a` in the other.
        let ib = usize::from(!holds(&frames[0], held[0], b));
        if !holds(&frames[ib], held[ib], b) {
            frames_level_into(m, b, Level::Pose, &mut frames[ib]);
            held[ib] = true;
        }
        let ia = 1 - ib;
        if !holds(&frames[ia], held[ia], a) {
            frames_level_into(m, a, Level::Pose, &mut frames[ia]);
            held[ia] = true;
        }
        distance_of(m, &frames[ia], &frames[ib])
    }

    fn scale(&self) -> f64 {
        self.scale
    }

    fn unit(&self) -> &'static str {
        "relative"
    }

    fn name(&self) -> &'static str {
        "mechanism equilibrium"
    }

    fn weight(&self, i: usize) -> f64 {
        self.weight.get(i).copied().unwrap_or(0.0)
    }
}

/// The multipliers `mu` with the part that redundant closures leave
/// statically indeterminate (the left null space of $G$, as with several
/// legs welded to one stage) chosen as the planar mechanism chooses it
/// (`mechanism::indeterminate`): the least transmitted force
/// $\sum_j L_j\lvert F_j\rvert^2$ over the flexures, $F_j$ the force the bodies
/// beyond flexure $j$ pass through it (the point loads, weights and tendon
/// pulls on them, and the closures' $-\mu$ on `a` and $+\mu$ on `b`).
/// Otherwise the free part is whatever the continuation left, and the
/// self-stress it carries through the closures' curvature makes a stable
/// mechanism look unstable. `mu` itself where $G$ has full row rank.
fn settled(m: &SpatialMechanism, f: &SpatialFrames, a: &SpatialAssembly, mu: &[f64], loads: &SpatialLoads) -> Vec<f64> {
    let g = &a.closure_jacobian;
    let rows = g.nrows();
    if rows == 0 {
        return mu.to_vec();
    }
    // Full row rank by a wide margin (a Cholesky of $GG^T$) is full rank to
    // the singular values too; only a doubtful case pays for them.
    let mut gram = vec![0.0; rows * rows];
    if linalg::columns_independent(g.transpose().as_slice(), g.ncols(), rows, &mut gram)
        || g.clone().svd(false, false).rank(1e-10 * g.amax().max(f64::MIN_POSITIVE)) == rows
    {
        return mu.to_vec();
    }
    let free = linalg::null_space(&g.transpose());
    let flexures: Vec<(usize, f64)> =
        m.joints.iter().enumerate().filter_map(|(j, spec)| spec.kind.flexure().map(|fl| (j, fl.length()))).collect();
    if free.ncols() == 0 || flexures.is_empty() {
        return mu.to_vec();
    }
    let mut body_forces: Vec<(usize, Vector3<f64>)> = Vec::new();
    for (p, w) in m.forces.iter().zip(&loads.force) {
        body_forces.push((p.body, Vector3::new(w[3], w[4], w[5])));
    }
    for (i, body) in m.bodies.iter().enumerate() {
        body_forces.push((i, loads.gravity * body.mass));
    }
    for (t, &tension) in m.tendons.iter().zip(&loads.tension) {
        let w: Vec<Vector3<f64>> = t.path.iter().map(|(b, r)| (f.bodies[*b] * r).coords).collect();
        for (i, pair) in w.windows(2).enumerate() {
            let d = pair[1] - pair[0];
            if d.norm() > 0.0 {
                let pull = d * (tension / d.norm());
                body_forces.push((t.path[i].0, pull));
                body_forces.push((t.path[i + 1].0, -pull));
            }
        }
    }
    let (mut e, mut b) = (DVector::zeros(3 * flexures.len()), DMatrix::zeros(3 * flexures.len(), rows));
    for (k, &(j, length)) in flexures.iter().enumerate() {
        let inside: Vec<bool> = (0..m.bodies.len()).map(|body| m.path(body).contains(&j)).collect();
        let w = length.sqrt();
        for (body, force) in &body_forces {
            if inside[*body] {
                for i in 0..3 {
                    e[3 * k + i] += w * force[i];
                }
            }
        }
        let mut row = 0;
        for c in &m.closures {
            let [ca, cb] = c.bodies();
            let sign = match (inside[ca], inside[cb]) {
                (true, false) => -1.0,
                (false, true) => 1.0,
                _ => 0.0,
            };
            for i in 0..3 {
                b[(3 * k + i, row + i)] = sign * w;
            }
            row += c.equations();
        }
    }
    let mu0 = DVector::from_column_slice(mu);
    let y = linalg::least_squares(&(&b * &free), &-(e + &b * &mu0));
    if y.iter().all(|v| v.is_finite()) { (mu0 + &free * y).iter().copied().collect() } else { mu.to_vec() }
}

/// Equilibrium under the mechanism's own loads, by continuation from the
/// unloaded, assembled configuration.
///
/// A path that loses stability and ends in a stable state is an answer
/// with its [`SpatialSolution::limit`]; one that does not reach a stable
/// state at the full load is [`Error::Unstable`] at the fraction where it
/// lost stability.
///
/// # Example
/// ```
/// use flexure::mechanism::spatial::{Revolute, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism, SpatialPointLoad};
/// use flexure::mechanism::spatial::statics::solve;
/// use nalgebra::{Isometry3, Point3, Vector3, Vector6};
/// let hinge = SpatialJointSpec {
///     name: "hinge".into(), kind: SpatialJointKind::Revolute(Revolute { axis: Vector3::x_axis(), stiffness: 2.0, rest: 0.0 }),
///     parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default(),
/// };
/// let push = SpatialPointLoad { name: "m".into(), body: 1, at: Point3::origin(), wrench: Vector6::new(0.5, 0.0, 0.0, 0.0, 0.0, 0.0) };
/// let bodies = vec![SpatialBody::massless("ground"), SpatialBody::massless("arm")];
/// let m = SpatialMechanism::new(bodies, vec![hinge], vec![], vec![push], vec![], Vector3::zeros()).unwrap();
/// let s = solve(&m, &Default::default()).unwrap();
/// assert!(s.stable && (s.q[0] - 0.25).abs() < 1e-12); // M/k
/// ```
pub fn solve(m: &SpatialMechanism, settings: &Settings) -> Result<SpatialSolution> {
    let to = m.loads();
    let zero = to.zero_like();
    // One problem from no load to the full load, as the planar solve:
    // assembled at λ = 0, then continued from there without a second
    // solve or stability test.
    let mut problem = SpatialKkt::new(m, &zero, &to, settings)?;
    let mut ws = solver::Workspace::new(solver::Problem::dim(&problem));
    let path = assemble(&mut problem, &mut ws, settings)?;
    let x0 = ws.x.clone();
    if m.constraints() > 0 {
        // Redundant closures: `solve_between` continues from the settled
        // multipliers, at which this Jacobian was not evaluated.
        let p = &problem;
        if settled(m, &p.frames, &p.assembly, &p.mu, &p.loads) != p.mu {
            let start = problem.solution(&x0, false, &path)?;
            return solve_between(m, &start, &to, settings);
        }
    }
    // The continuation's own count, as from a start solved elsewhere: the
    // assembly's iterations are not the path's.
    let report = solver::NewtonReport { stop: solver::NewtonStop::Converged, iterations: 0, residual: path.residual };
    ws.restore_start(report, path.stable);
    let found = continued(&mut problem, &mut ws, settings);
    if !lost(&found, path.stable) {
        return found;
    }
    let start = problem.solution(&x0, false, &path)?;
    refine_limit(m, &start, &to, settings, found)
}

/// The unloaded, assembled configuration under `loads` (no load: the
/// closures closed from rest by Newton).
pub fn assemble_unloaded(m: &SpatialMechanism, loads: &SpatialLoads, settings: &Settings) -> Result<SpatialSolution> {
    let mut problem = SpatialKkt::new(m, loads, loads, settings)?;
    let mut ws = solver::Workspace::new(solver::Problem::dim(&problem));
    let path = assemble(&mut problem, &mut ws, settings)?;
    let x = ws.x.clone();
    problem.solution(&x, false, &path)
}

/// Newton from the joints' rest at $\lambda = 0$ into `ws`, to the
/// tolerance of the assembly alone (the problem's loads at $\lambda = 0$
/// at both ends, whatever they are at $\lambda = 1$), and the stability
/// there: the path of no steps. `ws` is left as [`solver::newton`] leaves
/// it, a start for [`solver::Workspace::start_stable`].
fn assemble(problem: &mut SpatialKkt, ws: &mut solver::Workspace<f64>, settings: &Settings) -> Result<solver::Path> {
    let m = problem.mechanism;
    ws.x.fill(0.0);
    ws.x[..m.dof()].copy_from_slice(&m.rest());
    let full = std::mem::replace(&mut problem.scale, problem.start_scale);
    let report = solver::newton(problem, ws, 0.0, settings);
    problem.scale = full;
    let report = report.map_err(|e| match e {
        Error::NoConvergence { .. } | Error::Singular { .. } => Error::Singular {
            what: format!("mechanism assembly: the closures could not be closed from the joints' rest ({e})"),
        },
        e => e,
    })?;
    let stable = solver::Problem::stable(problem, &ws.x, 0.0, &ws.jacobian);
    Ok(solver::Path::at_start(report, stable))
}

/// Equilibrium under `to`, continued from `start` (an equilibrium under
/// `start.loads`), as the planar [`crate::mechanism::statics::solve_between`]:
/// a snap-through that ends in a stable state is an answer whose
/// [`SpatialSolution::limit`] is the load fraction where stability was
/// first lost, refined by bisection to a relative
/// [`crate::mechanism::statics::LIMIT_PRECISION`]; a path that ends
/// unstable is [`Error::Unstable`] at that fraction.
pub fn solve_between(
    m: &SpatialMechanism,
    start: &SpatialSolution,
    to: &SpatialLoads,
    settings: &Settings,
) -> Result<SpatialSolution> {
    let found = follow(m, start, to, settings);
    refine_limit(m, start, to, settings, found)
}

/// [`solve_between`] with the continuation's own limit, unrefined.
pub(in crate::mechanism) fn follow(
    m: &SpatialMechanism,
    start: &SpatialSolution,
    to: &SpatialLoads,
    settings: &Settings,
) -> Result<SpatialSolution> {
    if start.q.len() != m.dof() || start.multipliers.len() != m.constraints() {
        return Err(Error::invalid("start", start.q.len(), "was solved for another mechanism"));
    }
    let mut problem = SpatialKkt::new(m, &start.loads, to, settings)?;
    let dim = solver::Problem::dim(&problem);
    let mut ws = solver::Workspace::new(dim);
    let x0 = problem.state(&start.q, &start.multipliers);
    ws.x.copy_from_slice(&x0);
    continued(&mut problem, &mut ws, settings)
}

/// The continuation of `problem` from the start in `ws` to $\lambda = 1$,
/// as [`follow`] reports it.
fn continued(
    problem: &mut SpatialKkt,
    ws: &mut solver::Workspace<f64>,
    settings: &Settings,
) -> Result<SpatialSolution> {
    let path = solver::trace(problem, ws, settings)?;
    let unstable =
        |limit: Option<f64>| Error::Unstable { what: "mechanism equilibrium", load_fraction: limit.unwrap_or(0.0) };
    match path.error(&*problem) {
        None if path.stable => {
            let x = ws.x.clone();
            problem.solution(&x, true, &path)
        }
        None => Err(unstable(path.limit)),
        Some(e @ Error::Interrupted { .. }) => Err(e),
        Some(e) => Err(path.limit.map_or(e, |limit| unstable(Some(limit)))),
    }
}

/// The body frames of a solution (`pose_world_body`).
pub fn body_frames(m: &SpatialMechanism, s: &SpatialSolution) -> Vec<Isometry3<f64>> {
    frames_at(m, &s.q, Level::Pose).bodies
}

/// The frames of `m` at `q`, with the joints evaluated to `level`.
fn frames_at(m: &SpatialMechanism, q: &[f64], level: Level) -> SpatialFrames {
    let mut f = SpatialFrames::new(m);
    frames_level_into(m, q, level, &mut f);
    f
}

/// The constrained stiffness at a solution: $Z$ (a basis of the admissible
/// motions, $GZ = 0$) and $Z^THZ$, $H$ the Lagrangian Hessian with the
/// solution's multipliers.
pub fn stiffness(m: &SpatialMechanism, s: &SpatialSolution) -> (DMatrix<f64>, DMatrix<f64>) {
    // The exact Hessian (the joints' own second derivatives, not their
    // quadrature): compliance and the stability of a solution read it.
    let f = frames_at(m, &s.q, Level::Hessian);
    let mut a = SpatialAssembly::new(m);
    assemble_into(m, &f, &s.multipliers, &s.loads, true, &mut a);
    let z = if m.constraints() == 0 {
        DMatrix::identity(m.dof(), m.dof())
    } else {
        linalg::null_space(&a.closure_jacobian)
    };
    let k = z.transpose() * &a.hessian * &z;
    (z, k)
}

/// The $6\times6$ compliance at point `at` of `body` (in its frame): the
/// small rotation and displacement $(\delta\theta, \delta x)$ of that point,
/// in the ground frame, per unit moment and force $(m, f)$ applied there,
/// $C = J Z (Z^THZ)^{-1} Z^TJ^T$, $J$ the point's $6\times n$ Jacobian (rotation rows first).
///
/// Errors: [`Error::Singular`] where the constrained stiffness is singular
/// (a free motion).
pub fn compliance(m: &SpatialMechanism, s: &SpatialSolution, body: usize, at: Point3<f64>) -> Result<Matrix6<f64>> {
    let (z, k) = stiffness(m, s);
    let f = frames_at(m, &s.q, Level::Jacobian);
    let point = attach(m, &f, body, at.coords, true);
    let mut j = DMatrix::zeros(6, m.dof());
    for jt in m.path(body) {
        let o = m.joints[jt].offset;
        for c in o..o + m.joints[jt].kind.joint().dof() {
            for i in 0..3 {
                j[(i, c)] = f.omega[(i, c)];
            }
        }
    }
    for c in 0..m.dof() {
        for i in 0..3 {
            j[(3 + i, c)] = point.jacobian[(i, c)];
        }
    }
    let jz = j * z;
    // Not symmetrized: under a dead moment the tangent stiffness is not symmetric, nor is the compliance.
    let solved = k.lu().solve(&jz.transpose()).filter(|x| x.iter().all(|v| v.is_finite())).ok_or_else(|| {
        Error::Singular { what: "mechanism compliance: the constrained stiffness is singular (a free motion)".into() }
    })?;
    let c = &jz * solved;
    Ok(Matrix6::from_fn(|r, col| c[(r, col)]))
}

/// The wrench each flexure joint carries at a solution: for joint `j`, the
/// tip load $w$ (moment and force in its root frame, at its tip) with which
/// the flexure alone is in equilibrium at its coordinates,
/// $S_j^Tw = \nabla U_j$, $S_j$ its motion subspace (least squares: every
/// load beyond the joint reaches it through its tip, so the equations are
/// consistent at an equilibrium). `None` for the other kinds.
pub fn flexure_loads(m: &SpatialMechanism, s: &SpatialSolution) -> Vec<Option<crate::spatial::SpatialLoad>> {
    let f = frames_at(m, &s.q, Level::Jacobian);
    m.joints
        .iter()
        .zip(&f.joints)
        .map(|(j, state)| {
            j.kind.flexure()?;
            let w = linalg::least_squares(&state.jacobian.transpose(), &state.gradient);
            Some(crate::spatial::SpatialLoad { moment: [w[0], w[1], w[2]], force: [w[3], w[4], w[5]] })
        })
        .collect()
}
