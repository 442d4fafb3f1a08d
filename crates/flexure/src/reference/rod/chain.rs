//! The clamped rod under a dead tip wrench by multiple shooting: the
//! problem that [`deflect`](super::deflect) continues.

use super::shot::{MU, P, STATE, rhs, rotation};
use super::{Frame, Rod, TipWrench};
use crate::error::{Error, Result};
use crate::ode::{Tolerance, integrate_through};
use crate::scalar::Scalar;
use crate::solver::Problem;
use nalgebra::{Const, Matrix3, Vector3};
use num_dual::DualSVec64;

/// The fewest segments: their nodes are the cross-sections whose rotation
/// bounds the continuation's steps.
const MIN_SEGMENTS: usize = 4;

/// The most segments.
pub const MAX_SEGMENTS: usize = 64;

/// The largest $\int_0^L\sqrt{|F|/EI_{min}(s)}\thinspace ds$ accepted, one
/// segment per unit of it (as the elastica's
/// [`MAX_FORCE_GROWTH`](crate::reference::elastica::MAX_FORCE_GROWTH)).
pub const MAX_FORCE_GROWTH: f64 = MAX_SEGMENTS as f64;

/// Arc length per segment, at most, in quarter turns of the largest
/// rotation the rod can reach ([`Chain::new`]).
const TURN_PER_SEGMENT: f64 = std::f64::consts::FRAC_PI_2;

/// The most integration pieces (the stretches between the integrator's
/// restarts, each integrated on its own) one exact rod may take before its
/// integrations are refused: the bound on the work of a continuation, which
/// the steps' own cap bounds only loosely when each step integrates many
/// segments, each in many pieces (a large moment's fast-turning Jacobi
/// fields take a piece every $\epsilon^{1/5}/\omega$). A million pieces
/// take some ten seconds. The rod's deflection stops there, naming it,
/// with the load fraction reached.
pub const MAX_INTEGRATION_PIECES: usize = 1_000_000;

/// Points of the midpoint rules that size the segments (a few digits suffice).
const SIZING_POINTS: usize = 256;

/// The integrator's first step in each evaluation, as a fraction of a segment.
const FIRST_STEP: f64 = 0.3;

/// Eight derivative directions: a node's quaternion (4) and moment (3), and the load factor.
type Dual8 = DualSVec64<8>;

fn dual(re: f64, direction: usize) -> Dual8 {
    Dual8::from_re(re).derivative(direction)
}

fn parts(x: Dual8) -> [f64; 8] {
    let d = x.eps.unwrap_generic(Const::<8>, Const::<1>);
    std::array::from_fn(|i| d[i])
}

/// The conjugate-point test of the state the last derivatives were taken at.
#[derive(Debug, Clone, Default)]
struct Conjugate {
    x: Vec<f64>,
    lambda: f64,
    /// Whether every real eigenvalue of $\partial m(L)/\partial m(0)$ is positive.
    positive: bool,
}

/// The rod by multiple shooting, as a [`Problem`].
///
/// The rod is cut into $N$ segments of equal length. The unknowns are the
/// root moment $\mu_0 = m(0)/k$ and, at each inner node $j$, the state
/// $(q_j, p_j/L, \mu_j)$ (10 numbers: a quaternion that need not be of unit
/// norm, since each segment starts from $q_j/|q_j|$); the residuals (N·m)
/// are $k$ times the mismatch of each segment's end with the next node's
/// state, and at the tip $k\mu(L) - \lambda M$. The Jacobian comes from
/// dual numbers carried through the integrator: each segment's
/// sensitivities are the variational equations' solution.
///
/// A last unknown $z$ with residual $k(z - \lambda\Phi)$ carries the load
/// factor into the steps' distance ([`Chain::phase`]).
///
/// The quaternion needs no chart: the node's four components are unknowns
/// and the mismatch of four components is its residual, so no rotation
/// vector meets the singularity of a full turn, and the continuation,
/// following the path from rest, keeps each node's quaternion on the sheet
/// it started on (the path of $q_j$ is continuous).
pub(super) struct Chain<'a> {
    rod: &'a Rod,
    load: TipWrench,
    pub(super) ode: Tolerance,
    scale: f64,
    /// $k$ (N·m per rad): the least of the three stiffnesses at mid-length over $L$.
    k: f64,
    segments: usize,
    nodes: Vec<f64>,
    /// The section's breakpoints (m), where the integration restarts.
    stops: Vec<f64>,
    /// Per segment, $k\int ds/\min(GJ, EI_y, EI_z)$: the most a unit change
    /// of $\mu$ turns its sections.
    flexibility: Vec<f64>,
    /// $(|M| + L|F|)/k$: the largest $|\mu|$ of any equilibrium under the full load.
    reach: f64,
    /// $\omega$ (1/m): the fastest rate at which the Jacobi fields can turn or
    /// grow, $\max\big(\sqrt{|F|/EI_{min}}, (|M| + L|F|)/EI_{min}\big)$ over the rod.
    rate: f64,
    /// The least stiffness anywhere along the rod (N·m², at the sizing points).
    softest: f64,
    step: f64,
    last: Conjugate,
    /// Integration pieces so far, held to [`MAX_INTEGRATION_PIECES`].
    pub(super) integrations: usize,
}

/// The least of the three stiffnesses at `t`.
fn softest(rod: &Rod, t: f64) -> f64 {
    rod.section.stiffness(t).into_iter().fold(f64::INFINITY, f64::min)
}

impl<'a> Chain<'a> {
    /// The chain for `load`; an error names the force when it exceeds [`MAX_FORCE_GROWTH`].
    pub(super) fn new(rod: &'a Rod, load: TipWrench, ode: Tolerance) -> Result<Self> {
        let l = rod.length;
        let (force, moment) = (load.force.norm(), load.moment.norm());
        // Midpoint sums of ∫√(|F|/EI_min), ∫ds/EI_min and ∫|u⁰|: they only size the segments.
        let h = l / SIZING_POINTS as f64;
        let (mut growth, mut flexibility, mut rest_turn, mut stiff) = (0.0, 0.0, 0.0, f64::INFINITY);
        for i in 0..SIZING_POINTS {
            let s = (i as f64 + 0.5) * h;
            let ei = softest(rod, s / l);
            stiff = stiff.min(ei);
            growth += (force / ei).sqrt() * h;
            flexibility += h / ei;
            rest_turn += Vector3::from(rod.rest_at(s)).norm() * h;
        }
        if growth > MAX_FORCE_GROWTH {
            return Err(Error::invalid(
                "force",
                format!("{force} N (∫√(|F|/EI) ds = {growth:.1})"),
                "is beyond what the exact rod can follow: ∫√(|F|/EI_min) ds must be at most 64",
            ));
        }
        // The largest turn of a section from rest: its rest turn and what
        // the largest moment of the load, |M| + L|F|, can bend.
        let turn = rest_turn + (moment + l * force) * flexibility;
        let segments =
            (growth.ceil() as usize).max((turn / TURN_PER_SEGMENT).ceil() as usize).clamp(MIN_SEGMENTS, MAX_SEGMENTS);
        let nodes: Vec<f64> =
            (0..=segments).map(|j| if j == segments { l } else { l * j as f64 / segments as f64 }).collect();
        let k = softest(rod, 0.5) / l;
        let flexibility = nodes
            .windows(2)
            .map(|w| {
                let h = (w[1] - w[0]) / 16.0;
                k * (0..16).map(|i| h / softest(rod, (w[0] + (i as f64 + 0.5) * h) / l)).sum::<f64>()
            })
            .collect();
        let stops = rod.section.breakpoints().iter().map(|t| t * l).collect();
        Ok(Self {
            rod,
            load,
            ode,
            scale: k + moment + l * force,
            k,
            segments,
            nodes,
            stops,
            flexibility,
            reach: (moment + l * force) / k,
            rate: (force / stiff).sqrt().max((moment + l * force) / stiff),
            softest: stiff,
            step: 0.0,
            last: Conjugate::default(),
            integrations: 0,
        })
    }

    /// The same chain (the same segments) under `load`.
    pub(super) fn set_load(&mut self, load: TipWrench) {
        let l = self.rod.length;
        let (force, moment) = (load.force.norm(), load.moment.norm());
        self.scale = self.k + moment + l * force;
        self.reach = (moment + l * force) / self.k;
        self.rate = (force / self.softest).sqrt().max((moment + l * force) / self.softest);
        (self.load, self.last) = (load, Conjugate::default());
    }

    /// $\Phi = \omega L$: the most the Jacobi fields' phase can change from
    /// rest to the full load; the unknown $z = \lambda\Phi$ carries it, so that
    /// no continuation step changes it by more than a section may turn, and
    /// no step passes two conjugate points at once where the shape itself
    /// hardly changes (a straight column).
    fn phase(&self) -> f64 {
        self.rate * self.rod.length
    }

    /// The number of segments.
    pub(super) fn segments(&self) -> usize {
        self.segments
    }

    /// Where node $j \ge 1$'s state starts among the unknowns.
    fn base(j: usize) -> usize {
        3 + STATE * (j - 1)
    }

    /// Where node $j$'s moment $\mu_j$ sits among the unknowns.
    fn moment(j: usize) -> usize {
        if j == 0 { 0 } else { Self::base(j) + MU }
    }

    /// Segment $j$'s start in `x` (the root's is clamped: $q = 1$, $p = 0$).
    fn start(x: &[f64], j: usize) -> [f64; STATE] {
        let mut y = [0.0; STATE];
        if j == 0 {
            y[0] = 1.0;
            y[MU..].copy_from_slice(&x[..3]);
        } else {
            y.copy_from_slice(&x[Self::base(j)..Self::base(j) + STATE]);
        }
        y
    }

    /// Integrates segment `j` from `start` under the force `f` $= \lambda F/k$.
    fn segment<T: Scalar>(
        &mut self,
        j: usize,
        start: [T; STATE],
        f: [T; 3],
        observe: impl FnMut(f64, &[T; STATE]),
    ) -> Result<[T; STATE]> {
        // Each segment starts from a unit quaternion.
        let mut y = start;
        let norm = (y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3]).sqrt();
        for v in &mut y[..4] {
            *v /= norm;
        }
        let field = rhs(self.rod, self.k, f);
        let (s0, s1) = (self.nodes[j], self.nodes[j + 1]);
        let stops = self.stops_in(s0, s1);
        self.integrations += stops.len() + 1;
        if self.integrations > MAX_INTEGRATION_PIECES {
            return Err(Error::Singular {
                what: format!(
                    "exact rod: its limit of {MAX_INTEGRATION_PIECES} integration pieces was reached ({} segments of {} pieces each)",
                    self.segments,
                    stops.len() + 1
                ),
            });
        }
        integrate_through(field, s0, s1, &stops, y, &self.ode, &mut self.step, observe)
    }

    /// Where the integration of $[s_0, s_1]$ restarts: the section's
    /// breakpoints, and a grid of spacing at most $h = \epsilon^{1/5}/\omega$
    /// ($\epsilon$ the relative tolerance, [`Chain::rate`]'s $\omega$).
    ///
    /// Why: the integrator chooses its steps from the values alone, and on
    /// a rod that stays nearly straight under an axial or Michell load the
    /// values hardly change while the Jacobi fields (the dual parts) turn
    /// at the rate $\omega$. A fifth-order step of $\omega h = \epsilon^{1/5}$
    /// keeps their error near $\epsilon$, so the conjugate point is placed to
    /// about the tolerance (an Euler column's load to $10^{-9}$ at $\epsilon = 10^{-9}$).
    fn stops_in(&self, s0: f64, s1: f64) -> Vec<f64> {
        let mut stops: Vec<f64> = self.stops.iter().copied().filter(|s| *s > s0 && *s < s1).collect();
        if self.rate > 0.0 {
            let h = self.ode.relative.max(1e-15).powf(0.2) / self.rate;
            let pieces = ((s1 - s0) / h).ceil().min(1e6) as usize;
            stops.extend((1..pieces).map(|i| s0 + (s1 - s0) * i as f64 / pieces as f64));
            stops.sort_by(f64::total_cmp);
        }
        stops
    }

    fn force<T: Scalar>(&self, lambda: T) -> [T; 3] {
        let f = self.load.force / self.k;
        [lambda * T::c(f[0]), lambda * T::c(f[1]), lambda * T::c(f[2])]
    }

    /// The state shot from the root with moment $\mu_0$ under `lambda` × the load.
    pub(super) fn shot(&mut self, mu0: [f64; 3], lambda: f64) -> Result<Vec<f64>> {
        let mut x = vec![0.0; self.dim()];
        x[..3].copy_from_slice(&mu0);
        x[self.dim() - 1] = lambda * self.phase();
        self.step = FIRST_STEP * (self.nodes[1] - self.nodes[0]);
        let f = self.force(lambda);
        for j in 0..self.segments - 1 {
            let end = self.segment(j, Self::start(&x, j), f, |_, _| {})?;
            x[Self::base(j + 1)..Self::base(j + 1) + STATE].copy_from_slice(&end);
        }
        Ok(x)
    }

    /// The frames at every accepted integrator step of the state `x` under
    /// the full load, root to tip.
    pub(super) fn shape(&mut self, x: &[f64]) -> Result<Vec<Frame>> {
        let (l, k) = (self.rod.length, self.k);
        let mut out: Vec<Frame> = Vec::new();
        self.step = FIRST_STEP * (self.nodes[1] - self.nodes[0]);
        let f = self.force(1.0);
        for j in 0..self.segments {
            let first = j == 0;
            self.segment(j, Self::start(x, j), f, |s, y| {
                if first || s != out.last().map_or(-1.0, |p| p.s) {
                    out.push(frame(s, y, l, k));
                }
            })?;
        }
        Ok(out)
    }

    /// The residuals and, when asked, their derivatives and the conjugate-point test.
    fn sweep(
        &mut self,
        x: &[f64],
        lambda: f64,
        residual: &mut [f64],
        mut jacobian: Option<&mut [f64]>,
        mut dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        let (k, n, last) = (self.k, self.dim(), self.segments - 1);
        self.step = FIRST_STEP * (self.nodes[1] - self.nodes[0]);
        let tip = self.load.moment * lambda;
        if jacobian.is_none() && dlambda.is_none() {
            let f = self.force(lambda);
            for j in 0..self.segments {
                let end = self.segment(j, Self::start(x, j), f, |_, _| {})?;
                if j == last {
                    for i in 0..3 {
                        residual[STATE * j + i] = k * end[MU + i] - tip[i];
                    }
                } else {
                    let next = &x[Self::base(j + 1)..Self::base(j + 1) + STATE];
                    for i in 0..STATE {
                        residual[STATE * j + i] = k * (end[i] - next[i]);
                    }
                }
            }
        } else {
            if let Some(jac) = jacobian.as_deref_mut() {
                jac.fill(0.0);
            }
            let f = self.force(dual(lambda, 7));
            // ∂(q_j, μ_j)/∂μ₀ (7×3) carried node to node, rescaled there (only
            // the sign of the tip's determinant is kept).
            let mut sens = [[0.0; 3]; 7];
            for (i, row) in sens[4..].iter_mut().enumerate() {
                row[i] = 1.0;
            }
            for j in 0..self.segments {
                let start = Self::start(x, j);
                let mut y = start.map(Dual8::from_re);
                if j > 0 {
                    for i in 0..4 {
                        y[i] = dual(start[i], i);
                    }
                }
                for i in 0..3 {
                    y[MU + i] = dual(start[MU + i], 4 + i);
                }
                let end = self.segment(j, y, f, |_, _| {})?;
                let d: Vec<[f64; 8]> = end.iter().map(|v| parts(*v)).collect();
                let rows = if j == last { 3 } else { STATE };
                let row_of = |i: usize| if j == last { MU + i } else { i };
                for r in 0..rows {
                    let e = row_of(r);
                    let row = STATE * j + r;
                    residual[row] =
                        if j == last { k * end[e].re - tip[r] } else { k * (end[e].re - x[Self::base(j + 1) + e]) };
                    if let Some(jac) = jacobian.as_deref_mut() {
                        // Column-major n×n: entry (row, col) at col·n + row.
                        if j > 0 {
                            for c in 0..4 {
                                jac[(Self::base(j) + c) * n + row] = k * d[e][c];
                            }
                            if (P..P + 3).contains(&e) {
                                // p does not enter the right-hand side: ∂p_end/∂p_j = I.
                                jac[(Self::base(j) + e) * n + row] = k;
                            }
                        }
                        for c in 0..3 {
                            jac[(Self::moment(j) + c) * n + row] = k * d[e][4 + c];
                        }
                        if j < last {
                            jac[(Self::base(j + 1) + e) * n + row] = -k;
                        }
                    }
                    if let Some(dl) = dlambda.as_deref_mut() {
                        dl[row] = k * d[e][7] - if j == last { self.load.moment[r] } else { 0.0 };
                    }
                }
                // The chain rule through this segment: (q, μ) at its end.
                let mut next = [[0.0; 3]; 7];
                for (a, e) in [0, 1, 2, 3, MU, MU + 1, MU + 2].into_iter().enumerate() {
                    for c in 0..3 {
                        next[a][c] = (0..4).map(|b| d[e][b] * sens[b][c]).sum::<f64>()
                            + (0..3).map(|b| d[e][4 + b] * sens[4 + b][c]).sum::<f64>();
                    }
                }
                let size = next.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
                sens = if size > 0.0 && size.is_finite() { next.map(|r| r.map(|v| v / size)) } else { next };
            }
            let c = Matrix3::from_fn(|r, col| sens[4 + r][col]);
            let size = c.amax();
            let positive = c.complex_eigenvalues().iter().all(|e| e.im.abs() > 1e-9 * size || e.re > 0.0);
            self.last.x.clear();
            self.last.x.extend_from_slice(x);
            (self.last.lambda, self.last.positive) = (lambda, positive);
        }
        // The load's phase: z = λΦ.
        let z = self.dim() - 1;
        residual[z] = k * (x[z] - lambda * self.phase());
        if let Some(jac) = jacobian {
            jac[z * n + z] = k;
        }
        if let Some(dl) = dlambda {
            dl[z] = -k * self.phase();
        }
        if residual.iter().all(|r| r.is_finite()) {
            Ok(())
        } else {
            Err(Error::Singular { what: "exact rod: non-finite moment or pose at a node".into() })
        }
    }

    /// Whether `x` at `lambda` lies where an equilibrium on the way to the
    /// full load can: $-1 \le \lambda \le 2$, no node's $|\mu|$ beyond twice
    /// $\max(1, |\lambda|)$ × the reach plus 1, and each node's quaternion
    /// of norm within a factor 2 of 1.
    fn within_reach(&self, x: &[f64], lambda: f64) -> bool {
        let bound = 2.0 * lambda.abs().max(1.0) * self.reach + 1.0;
        (-1.0..=2.0).contains(&lambda)
            && (0..self.segments).all(|j| {
                let mu = Vector3::from_column_slice(&x[Self::moment(j)..Self::moment(j) + 3]);
                let q_ok = j == 0 || {
                    let b = Self::base(j);
                    let q = (0..4).map(|i| x[b + i] * x[b + i]).sum::<f64>().sqrt();
                    (0.5..=2.0).contains(&q)
                };
                mu.norm() <= bound && q_ok
            })
    }
}

/// The frame of the state `y` at `s`.
pub(super) fn frame(s: f64, y: &[f64; STATE], l: f64, k: f64) -> Frame {
    let r = rotation(&y[..4]);
    Frame {
        s,
        position: Vector3::new(y[P], y[P + 1], y[P + 2]) * l,
        rotation: Matrix3::from_fn(|i, j| r[i][j]),
        moment: Vector3::new(y[MU], y[MU + 1], y[MU + 2]) * k,
    }
}

impl Problem<f64> for Chain<'_> {
    fn dim(&self) -> usize {
        3 + STATE * (self.segments - 1) + 1
    }

    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        residual: &mut [f64],
        jacobian: Option<&mut [f64]>,
        dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        if !self.within_reach(x, lambda) {
            return Err(Error::Singular {
                what: "exact rod: a Newton iterate beyond the moment of any equilibrium".into(),
            });
        }
        self.sweep(x, lambda, residual, jacobian, dlambda)
    }

    /// The conjugate-point test: no real eigenvalue of $\partial m(L)/\partial m(0)$
    /// is zero or negative (its determinant then keeps the sign it has at
    /// rest, and a double conjugate point, as a round column's, is seen).
    fn stable(&mut self, x: &[f64], lambda: f64, _jacobian: &[f64]) -> bool {
        if !(self.last.lambda == lambda && self.last.x == x) {
            let (mut r, mut d) = (vec![0.0; x.len()], vec![0.0; x.len()]);
            // Not from the allowance: a sweep refused for it would read as unstable.
            let used = std::mem::take(&mut self.integrations);
            let swept = self.sweep(x, lambda, &mut r, None, Some(&mut d));
            self.integrations = used;
            if swept.is_err() {
                return false;
            }
        }
        self.last.positive
    }

    /// The largest rotation between the two states of a node's section,
    /// or of the sections a segment's moment change can turn.
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        let mut most: f64 = 0.0;
        for j in 0..self.segments {
            let m = Self::moment(j);
            let dmu = (0..3).map(|i| (a[m + i] - b[m + i]).powi(2)).sum::<f64>().sqrt();
            most = most.max(dmu * self.flexibility[j]);
            if j > 0 {
                let base = Self::base(j);
                let (qa, qb) = (&a[base..base + 4], &b[base..base + 4]);
                let dot: f64 = (0..4).map(|i| qa[i] * qb[i]).sum();
                let na = qa.iter().map(|v| v * v).sum::<f64>().sqrt();
                let nb = qb.iter().map(|v| v * v).sum::<f64>().sqrt();
                most = most.max(2.0 * (dot.abs() / (na * nb)).min(1.0).acos());
            }
        }
        let z = self.dim() - 1;
        most.max((a[z] - b[z]).abs())
    }

    fn scale(&self) -> f64 {
        self.scale
    }

    fn unit(&self) -> &'static str {
        "N·m"
    }

    fn name(&self) -> &'static str {
        "exact Kirchhoff rod"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::section::SpatialSection;

    /// The chain's Jacobian and load derivative against central differences
    /// of its residual (step 1e-6: truncation ~1e-12, rounding ~1e-10 of
    /// residuals of order 1; agreement to 1e-6 absolute), at a state off the
    /// solution, with rest curvature, a table section, a skew moment and force.
    #[test]
    fn derivatives_match_finite_differences() {
        let table = crate::section::Profile::Table(vec![[0.0, 1.2], [0.35, 0.7], [1.0, 0.9]]);
        let section = SpatialSection::given(
            crate::section::Profile::Constant(0.8),
            table,
            crate::section::Profile::Constant(1.1),
        )
        .unwrap();
        let rod = Rod::new(1.3, section).unwrap().with_rest(|s| [0.2, -0.3 * s, 0.5]).unwrap();
        let load = TipWrench { moment: Vector3::new(0.3, -0.2, 0.5), force: Vector3::new(-2.0, 1.0, 1.5) };
        let mut chain = Chain::new(&rod, load, Tolerance::default()).unwrap();
        let n = chain.dim();
        let lambda = 0.6;
        // A shot, then every unknown moved off it (the nodes' quaternions off unit norm too).
        let shot = chain.shot([0.3, -0.2, 0.4], lambda).unwrap();
        let x: Vec<f64> = shot.iter().enumerate().map(|(i, v)| v + 0.05 * (i as f64).sin()).collect();
        let (mut r, mut jac, mut dl) = (vec![0.0; n], vec![0.0; n * n], vec![0.0; n]);
        chain.evaluate(&x, lambda, &mut r, Some(&mut jac), Some(&mut dl)).unwrap();
        let mut plain = vec![0.0; n];
        chain.evaluate(&x, lambda, &mut plain, None, None).unwrap();
        assert!(r.iter().zip(&plain).all(|(a, b)| (a - b).abs() < 1e-12), "residual with and without derivatives");
        crate::solver::assert_derivatives(&mut chain, &x, lambda);
    }

    /// The pieces one sweep of the chain for `load` integrates.
    fn chain_pieces(rod: &Rod, load: TipWrench) -> usize {
        let chain = Chain::new(rod, load, Tolerance::default()).unwrap();
        (0..chain.segments).map(|j| chain.stops_in(chain.nodes[j], chain.nodes[j + 1]).len() + 1).sum()
    }

    /// The work bound: a continuation that runs out of integration pieces
    /// ([`MAX_INTEGRATION_PIECES`]) stops with the load fraction it
    /// reached and names the bound, rather than running on. Reference: the
    /// same twist, TL/GJ = 2.6 rad, is followed to the full load when the
    /// allowance is whole (its exact twist, checked to 1e-9).
    #[test]
    fn a_continuation_past_its_integrations_stops_naming_the_bound() {
        let rod = Rod::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap()).unwrap();
        let load = TipWrench { moment: Vector3::new(2.6, 0.0, 0.0), force: Vector3::zeros() };
        let follow = |used: usize| {
            let mut chain = Chain::new(&rod, load, Tolerance::default()).unwrap();
            let mut ws = crate::solver::SolverWorkspace::new(chain.dim());
            ws.x = chain.shot([0.0; 3], 0.0).unwrap();
            chain.integrations = used;
            crate::solver::continuation(&mut chain, &mut ws, &Default::default()).map(|_| ws.x[..3].to_vec())
        };
        let mu = follow(0).unwrap();
        assert!((mu[0] - 2.6).abs() < 1e-9, "the root moment's twist part is the load's: {mu:?}");
        // A few sweeps' worth left: the start and a step or two, then no more.
        let e = follow(MAX_INTEGRATION_PIECES - 3 * chain_pieces(&rod, load)).unwrap_err();
        match &e {
            Error::ContinuationStalled { load_fraction, .. } => assert!(*load_fraction < 1.0, "{e}"),
            other => panic!("expected a stall, got {other}"),
        }
        let text = e.to_string();
        assert!(text.contains("its limit of 1000000 integration pieces was reached"), "{text}");
        assert!(text.contains("% of the load"), "{text}");
    }
}
