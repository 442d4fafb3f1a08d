//! The tip-load elastica by multiple shooting: the problem that
//! [`deflect`](super::deflect) continues and [`is_stable`](super::is_stable) tests.

use super::jacobi::Jacobi;
use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::ode::{Tolerance, integrate_through};
use crate::scalar::Scalar;
use crate::solver::Problem;
use crate::statics::TipLoad;
use nalgebra::Const;
use num_dual::DualSVec64;

/// The fewest segments [`Chain`] uses: their nodes are the cross-sections
/// whose rotation bounds the continuation's steps.
const MIN_SEGMENTS: usize = 4;

/// The largest $L\sqrt{|F|/EI}$ [`deflect`](super::deflect) accepts (a force of $10^4 EI/L^2$,
/// four thousand times Euler's load), one segment per unit of it; with
/// $EI(s)$, the largest $\int_0^L\sqrt{|F|/EI(s)}\thinspace ds$. Beyond,
/// shooting a beam in tension is too sensitive (in a sweep of forces from
/// $10^4$ to $10^5 EI/L^2$, 2 % failed and one took 14 s).
pub const MAX_FORCE_GROWTH: f64 = 100.0;

/// The integrator's first step in each evaluation of the residual, as a
/// fraction of a segment (it is then carried from segment to segment).
const FIRST_STEP: f64 = 0.3;

/// Three derivative directions: a segment's start angle and moment, and the load factor.
type Dual3 = DualSVec64<3>;

fn dual(re: f64, direction: usize) -> Dual3 {
    Dual3::from_re(re).derivative(direction)
}

fn parts(x: Dual3) -> [f64; 3] {
    let d = x.eps.unwrap_generic(Const::<3>, Const::<1>);
    [d[0], d[1], d[2]]
}

/// The tip-load elastica by multiple shooting, as a [`Problem`].
///
/// Along the beam Eq. 3 reads, with the bending moment $m(s)$ scaled to a
/// rotation $\mu = m/k$ by $k = \overline{EI}/L$ (the mean stiffness), under the
/// load $\lambda(M, F_x, F_y)$,
/// $$\phi^{\prime} = \omega_0(s) + \frac{k\mu}{EI(s)}, \qquad \mu^{\prime} = \tfrac{1}{k}\lambda(F_x\sin\phi - F_y\cos\phi),$$
/// with $\phi(0) = 0$ (clamped) and $m(L) = \lambda M$ (the tip moment).
/// The beam is cut into $N$ segments, equal in $\tau = \int EI^{-1/2} ds$
/// (equal in $s$ for a uniform beam), and each segment's integration
/// restarts at the section's breakpoints; the unknowns are the root's
/// $\mu_0$, the angle and moment $(\phi_j, \mu_j)$ at the inner nodes and the
/// tip angle $\phi_N$; the residuals (N·m) are the mismatches at each node
/// of the segment arriving there, $k(\phi^-_{j} - \phi_j)$ and
/// $k(\mu^-_j - \mu_j)$, the last one being $m^-(L) - \lambda M$.
///
/// Why segments: a beam pulled along its length (the end of a cantilever
/// under a large transverse force, a buckled column) makes shooting from the
/// root sensitive like $e^{L\sqrt{|F|/EI}}$, so that Newton's basin shrinks
/// with the load and its wild iterates (coiled shapes) cost thousands of
/// integrator steps each. With $N \ge \int_0^L\sqrt{|F|/EI}\thinspace ds$ segments, equal
/// in $\tau$, each one's sensitivity stays below $e$, and Newton converges from the continuation's
/// predictor in a few iterations at any load.
pub(super) struct Chain<'a> {
    flexure: &'a Flexure,
    load: TipLoad,
    pub(super) ode: Tolerance,
    scale: f64,
    /// $k = \overline{EI}/L$ (N·m per rad).
    pub(super) stiffness: f64,
    segments: usize,
    /// The arc lengths of the nodes, $s_0 = 0 < \dots < s_N = L$.
    nodes: Vec<f64>,
    /// The section's breakpoints (m), where each segment's integration restarts.
    pub(super) stops: Vec<f64>,
    /// The largest $|\mu|$ of any equilibrium under the full load:
    /// $(|M| + L|F|)/k$, the load's moment about a point within $L$ of the tip.
    reach: f64,
    /// The largest turn of a cross-section from rest under the full load:
    /// $(|M| + L|F|)\int_0^L ds/EI$ (equal to `reach` for a uniform beam).
    turn: f64,
    /// The nodes' rest angles $\phi_j$, $j = 1..N$.
    rest: Vec<f64>,
    /// The integrator's next step, carried from segment to segment within
    /// one evaluation (and restarted at [`FIRST_STEP`] in each): each
    /// residual is then a function of $(x, \lambda)$ alone, and Newton can
    /// meet its tolerance even when the integrator's is far looser.
    step: f64,
    /// The Jacobi test of the last evaluation with derivatives.
    last: Jacobi,
}

impl<'a> Chain<'a> {
    /// The chain for `load`, or an error naming the force when it exceeds [`MAX_FORCE_GROWTH`].
    pub(super) fn new(flexure: &'a Flexure, load: TipLoad, ode: Tolerance) -> Result<Self> {
        let l = flexure.length();
        let scale = flexure.ei() / l + load.moment.abs() + l * (load.fx.abs() + load.fy.abs());
        let stretch = crate::reference::Stretch::of(flexure)?;
        let uniform = flexure.section().is_uniform();
        let growth = if uniform {
            l * (load.fx.hypot(load.fy) / flexure.ei()).sqrt()
        } else {
            load.fx.hypot(load.fy).sqrt() * stretch.total()
        };
        if growth > MAX_FORCE_GROWTH {
            return Err(Error::invalid(
                "force",
                format!("{} N (L·√(|F|/EI) = {growth:.1})", load.fx.hypot(load.fy)),
                "is beyond what the exact elastica can follow: L·√(|F|/EI) (∫√(|F|/EI) ds) must be at most 100",
            ));
        }
        let segments = (growth.ceil() as usize).max(MIN_SEGMENTS);
        let nodes = stretch.nodes(l, uniform, segments);
        let (stiffness, last) = (flexure.ei() / l, Jacobi::default());
        let load_moment = load.moment.abs() + l * load.fx.hypot(load.fy);
        let reach = load_moment / stiffness;
        let turn = if uniform { reach } else { load_moment * stretch.flexibility };
        let stops = crate::reference::stops(flexure);
        let mut chain = Self {
            flexure,
            load,
            ode,
            scale,
            stiffness,
            segments,
            nodes,
            stops,
            reach,
            turn,
            rest: vec![],
            step: 0.0,
            last,
        };
        let rest = chain.shot(0.0, 0.0)?;
        chain.rest = (1..=segments).map(|j| rest[Self::angle(j)]).collect();
        Ok(chain)
    }

    /// Whether `x` at `lambda` lies where an equilibrium on the way to the
    /// full load can: $-1 \le \lambda \le 2$, and no node's moment or
    /// turn from rest beyond twice $\max(1, |\lambda|)$ × [`Chain::reach`]
    /// (or [`Chain::turn`]) plus 1 rad. Newton iterates outside are refused unevaluated: coiled
    /// shapes cost integrator steps in proportion to their moment.
    fn within_reach(&self, x: &[f64], lambda: f64) -> bool {
        let factor = 2.0 * lambda.abs().max(1.0);
        let (moment, turn) = (factor * self.reach + 1.0, factor * self.turn + 1.0);
        (-1.0..=2.0).contains(&lambda)
            && (0..self.segments).all(|j| x[Self::moment(j)].abs() <= moment)
            && (1..=self.segments).all(|j| (x[Self::angle(j)] - self.rest[j - 1]).abs() <= turn)
    }

    /// Node $j$'s arc length.
    fn node(&self, j: usize) -> f64 {
        self.nodes[j]
    }

    /// Integrates segment `j` from `start` = $(\phi_j, \mu_j)$ (and, when
    /// $D = 4$, the position $(x, y)$) under $\lambda$ = `lambda`.
    fn segment<T: Scalar, const D: usize>(
        &mut self,
        j: usize,
        start: [T; D],
        lambda: T,
        observe: impl FnMut(f64, &[T; D]),
    ) -> Result<[T; D]> {
        let (f, l, k) = (self.flexure, self.flexure.length(), self.stiffness);
        let kappa = f.rest();
        let uniform = self.stops.is_empty() && f.section().is_uniform();
        // k/EI(s): exactly 1/L on a uniform beam, as before sections.
        let (fx, fy) = if uniform {
            (T::c(self.load.fx * l / f.ei()), T::c(self.load.fy * l / f.ei()))
        } else {
            (T::c(self.load.fx / k), T::c(self.load.fy / k))
        };
        let rhs = |s: f64, y: &[T; D]| {
            let (sn, cs) = y[0].sin_cos();
            let mut d = [T::zero(); D];
            d[0] = if uniform {
                T::c(f.curvature(kappa, s)) + y[1] / T::c(l)
            } else {
                T::c(f.curvature(kappa, s)) + y[1] * T::c(k / f.ei_at(s))
            };
            d[1] = lambda * (fx * sn - fy * cs);
            if D == 4 {
                (d[2], d[3]) = (cs, sn);
            }
            d
        };
        let (s0, s1) = (self.node(j), self.node(j + 1));
        integrate_through(rhs, s0, s1, &self.stops, start, &self.ode, &mut self.step, observe)
    }

    /// Index of $\phi_j$ ($j \ge 1$) among the unknowns.
    fn angle(j: usize) -> usize {
        2 * j - 1
    }

    /// Index of $\mu_j$ ($j < N$) among the unknowns.
    fn moment(j: usize) -> usize {
        2 * j
    }

    /// The states $(s_j, [\phi, m, x, y])$ at the nodes of the state `x`
    /// under the full load, tip included (positions summed over the segments).
    pub(super) fn states(&mut self, x: &[f64]) -> Result<Vec<(f64, [f64; 4])>> {
        let (k, mut out) = (self.stiffness, Vec::with_capacity(self.segments + 1));
        let (mut px, mut py) = (0.0, 0.0);
        for j in 0..self.segments {
            let phi = if j == 0 { 0.0 } else { x[Self::angle(j)] };
            out.push((self.node(j), [phi, x[Self::moment(j)] * k, px, py]));
            let end = self.segment(j, [phi, x[Self::moment(j)], px, py], 1.0, |_, _| {})?;
            (px, py) = (end[2], end[3]);
            if j + 1 == self.segments {
                out.push((self.node(j + 1), [end[0], end[1] * k, px, py]));
            }
        }
        Ok(out)
    }

    /// The state reached by shooting from the root with moment $M_0$ under
    /// `lambda` × the load, each segment starting where the last one ended.
    pub(super) fn shot(&mut self, root_moment: f64, lambda: f64) -> Result<Vec<f64>> {
        let mut x = vec![0.0; 2 * self.segments];
        let mut start = [0.0, root_moment / self.stiffness];
        for j in 0..self.segments {
            x[Self::moment(j)] = start[1];
            start = self.segment(j, start, lambda, |_, _| {})?;
            x[Self::angle(j + 1)] = start[0];
        }
        Ok(x)
    }

    /// The residuals at `x` under `lambda` × the load and, when asked, their
    /// derivatives and the Jacobi test (see [`Problem::evaluate`]).
    fn sweep(
        &mut self,
        x: &[f64],
        lambda: f64,
        residual: &mut [f64],
        mut jacobian: Option<&mut [f64]>,
        mut dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        let (k, n, last) = (self.stiffness, 2 * self.segments, self.segments - 1);
        self.step = FIRST_STEP * (self.node(1) - self.node(0));
        let tip_moment = lambda * self.load.moment / k;
        let target = |j: usize| {
            let phi = x[Self::angle(j + 1)];
            if j == last { [phi, tip_moment] } else { [phi, x[Self::moment(j + 1)]] }
        };
        if jacobian.is_none() && dlambda.is_none() {
            for j in 0..self.segments {
                let phi = if j == 0 { 0.0 } else { x[Self::angle(j)] };
                let end = self.segment(j, [phi, x[Self::moment(j)]], lambda, |_, _| {})?;
                let t = target(j);
                residual[2 * j] = k * (end[0] - t[0]);
                residual[2 * j + 1] = k * (end[1] - t[1]);
            }
        } else {
            if let Some(jac) = jacobian.as_deref_mut() {
                jac.fill(0.0);
            }
            // The Jacobi field (h, EI h') from (0, 1) at the root, carried
            // across the nodes by each segment's sensitivities and rescaled
            // there (only its signs matter).
            let (mut h, mut positive) = ([0.0, 1.0], true);
            for j in 0..self.segments {
                let phi = if j == 0 { 0.0 } else { x[Self::angle(j)] };
                let start = [dual(phi, 0), dual(x[Self::moment(j)], 1)];
                let end = self.segment(j, start, dual(lambda, 2), |s, y| {
                    let d = parts(y[0]);
                    positive &= s == 0.0 || d[0] * h[0] + d[1] * h[1] > 0.0;
                })?;
                let t = target(j);
                let (dphi, dmu) = (parts(end[0]), parts(end[1]));
                residual[2 * j] = k * (end[0].re - t[0]);
                residual[2 * j + 1] = k * (end[1].re - t[1]);
                if let Some(jac) = jacobian.as_deref_mut() {
                    // Column-major n×n: entry (row, col) at col·n + row.
                    for (row, d) in [(2 * j, dphi), (2 * j + 1, dmu)] {
                        if j > 0 {
                            jac[Self::angle(j) * n + row] = k * d[0];
                        }
                        jac[Self::moment(j) * n + row] = k * d[1];
                    }
                    jac[Self::angle(j + 1) * n + 2 * j] = -k;
                    if j < last {
                        jac[Self::moment(j + 1) * n + 2 * j + 1] = -k;
                    }
                }
                if let Some(d) = dlambda.as_deref_mut() {
                    d[2 * j] = k * dphi[2];
                    d[2 * j + 1] = k * dmu[2] - if j == last { self.load.moment } else { 0.0 };
                }
                let next = [dphi[0] * h[0] + dphi[1] * h[1], dmu[0] * h[0] + dmu[1] * h[1]];
                let size = next[0].abs().max(next[1].abs());
                h = if size > 0.0 && size.is_finite() { [next[0] / size, next[1] / size] } else { next };
            }
            self.last.x.clear();
            self.last.x.extend_from_slice(x);
            (self.last.lambda, self.last.positive, self.last.rising) = (lambda, positive, h[1] > 0.0);
        }
        if residual.iter().all(|r| r.is_finite()) {
            Ok(())
        } else {
            Err(Error::Singular { what: "exact elastica: non-finite moment or angle at a node".into() })
        }
    }
}

impl Problem<f64> for Chain<'_> {
    fn dim(&self) -> usize {
        2 * self.segments
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
                what: "exact elastica: a Newton iterate beyond the bending moment of any equilibrium".into(),
            });
        }
        self.sweep(x, lambda, residual, jacobian, dlambda)
    }

    /// The Jacobi test (see [`is_stable`](super::is_stable)) of the state, from the
    /// derivatives of its last evaluation.
    fn stable(&mut self, x: &[f64], lambda: f64, _jacobian: &[f64]) -> bool {
        if !self.last.at(x, lambda) {
            let mut r = vec![0.0; x.len()];
            let mut d = vec![0.0; x.len()];
            if self.sweep(x, lambda, &mut r, None, Some(&mut d)).is_err() {
                return false;
            }
        }
        self.last.positive && self.last.rising
    }

    /// The largest change of a node's angle: the cross-sections' rotation.
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        (1..=self.segments).fold(0.0, |m: f64, j| m.max((a[Self::angle(j)] - b[Self::angle(j)]).abs()))
    }

    fn scale(&self) -> f64 {
        self.scale
    }

    fn unit(&self) -> &'static str {
        "N·m"
    }

    fn name(&self) -> &'static str {
        "exact elastica"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The chain's Jacobian and load derivative against central differences
    /// of its residual (step 1e-6: truncation ~1e-12, rounding ~1e-10 of
    /// residuals of order 1; agreement to 1e-6 absolute), at a state off the
    /// solution, with rest curvature, moment and both force components.
    #[test]
    fn derivatives_match_finite_differences() {
        let f = Flexure::new(1.3, 0.8, 3).unwrap().with_rest(&[0.4, -0.2, 0.1]).unwrap();
        check_derivatives(&f, 5);
        // EI(s) from a table with a kink (a breakpoint inside a segment):
        // ∫√(|F|/EI) ds = 4.79: five segments, unequal in s.
        let table = crate::section::Profile::Table(vec![[0.0, 1.2], [0.35, 0.5], [1.0, 0.9]]);
        let f = f.with_section(crate::section::Section::given(table).unwrap()).unwrap();
        check_derivatives(&f, 5);
    }

    fn check_derivatives(f: &Flexure, segments: usize) {
        let load = TipLoad { moment: 0.7, fx: -9.0, fy: 4.0 };
        let mut chain = Chain::new(f, load, Tolerance::default()).unwrap();
        let n = chain.dim();
        assert_eq!(n, 2 * segments, "L√(|F|/EI) = 4.56 when uniform");
        let x: Vec<f64> = (0..n).map(|i| 0.3 + 0.1 * (i as f64).sin()).collect();
        crate::solver::assert_derivatives(&mut chain, &x, 0.6);
    }
}
