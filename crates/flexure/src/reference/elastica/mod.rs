//! The exact large-deflection elastica (paper Eq. 3), solved by shooting on
//! the shared solver core ([`crate::solver`]).

use crate::error::{Error, Result};
use crate::joint::Flexure;
use crate::kinematics::Pose;
use crate::ode::{Tolerance, integrate_through};
use crate::scalar::Scalar;
use crate::solver::{self, Problem};
use crate::statics::TipLoad;
use crate::stress::Peak;
use nalgebra::Const;
use num_dual::DualSVec64;

/// Settings of [`deflect`] and [`connect`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Integrator tolerance.
    pub ode: Tolerance,
    /// Newton and load-continuation settings. The residual is the tip-moment
    /// mismatch, relative to $EI/L + |M| + L(|F_x| + |F_y|)$ ([`deflect`]),
    /// or the tip-pose mismatch relative to $L$ ([`connect`]).
    pub solver: solver::Settings,
    /// The integrator's tolerance (relative and absolute) while [`deflect`]
    /// follows the loading path; the end state is then refined to `ode`.
    /// The path only has to keep to its branch and tell where it loses
    /// stability, and a looser integration takes far fewer steps, the more
    /// so the more the beam bends. Zero (or anything below `ode`'s
    /// tolerances) follows the path at `ode` itself.
    pub path_tolerance: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self { ode: Tolerance::default(), solver: solver::Settings::default(), path_tolerance: PATH_TOLERANCE }
    }
}

/// The default [`Settings::path_tolerance`]: where the loading path still
/// costs a few times less than the refinement of its end (a tip angle of
/// 45° to 270°), while its states and stability stay those of the exact
/// elastica to about that tolerance.
pub const PATH_TOLERANCE: f64 = 1e-6;

impl Settings {
    /// Checks the integrator and solver settings, naming the first bad one.
    ///
    /// # Example
    /// ```
    /// use flexure::reference::elastica::Settings;
    /// let mut s = Settings::default();
    /// s.ode.relative = f64::NAN;
    /// assert!(s.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<()> {
        self.ode.validate()?;
        self.solver.validate()?;
        let p = self.path_tolerance;
        if !(p.is_finite() && (0.0..=1e-4).contains(&p)) {
            return Err(Error::invalid("path_tolerance", p, "must be a finite number from 0 to 1e-4"));
        }
        Ok(())
    }

    /// The integrator's tolerance along the loading path.
    fn path_ode(&self) -> Tolerance {
        let p = self.path_tolerance;
        Tolerance { relative: self.ode.relative.max(p), absolute: self.ode.absolute.max(p), ..self.ode }
    }
}

/// An exact solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solution {
    /// Tip pose in the root frame.
    pub pose: Pose<f64>,
    /// Bending moment at the root, $M_0 = EI(\omega(0) - \omega_0(0))$ (N·m).
    pub root_moment: f64,
    /// Load-continuation steps taken.
    pub load_steps: usize,
    /// Whether the shape is a minimum of the potential energy under the
    /// (dead) tip load: see [`is_stable`].
    pub stable: bool,
    /// The load fraction where the loading path first lost stability (a
    /// limit load passed by snap-through, or a bifurcation), if it did.
    pub limit: Option<f64>,
}

/// Integrates Eq. 3 from the clamped root, $\phi(0) = x(0) = y(0) = 0$, with
/// $\phi^{\prime} = \omega_0(s) + (M_0 - F_y x + F_x y)/EI(s)$: the internal moment of a
/// beam carrying tip force $(F_x, F_y)$ and root moment $M_0$.
/// Returns $(\phi, x, y)$ at $s = L$; `observe` sees every accepted step
/// (the integration restarts at the section's breakpoints).
pub fn shoot<T: Scalar>(
    flexure: &Flexure,
    root_moment: T,
    fx: T,
    fy: T,
    tol: &Tolerance,
    observe: impl FnMut(f64, &[T; 3]),
) -> Result<[T; 3]> {
    let (l, stops) = (flexure.length(), crate::reference::stops(flexure));
    integrate_through(rhs(flexure, root_moment, fx, fy), 0.0, l, &stops, [T::zero(); 3], tol, &mut 0.0, observe)
}

/// The right-hand side of Eq. 3 for [`shoot`].
fn rhs<T: Scalar>(flexure: &Flexure, root_moment: T, fx: T, fy: T) -> impl FnMut(f64, &[T; 3]) -> [T; 3] {
    let kappa = flexure.rest();
    move |s: f64, y: &[T; 3]| {
        let (sn, cs) = y[0].sin_cos();
        let ei = T::c(flexure.ei_at(s));
        [T::c(flexure.curvature(kappa, s)) + (root_moment - fy * y[1] + fx * y[2]) / ei, cs, sn]
    }
}

/// The fewest segments [`Chain`] uses: their nodes are the cross-sections
/// whose rotation bounds the continuation's steps.
const MIN_SEGMENTS: usize = 4;

/// The largest $L\sqrt{|F|/EI}$ [`deflect`] accepts (a force of $10^4 EI/L^2$,
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

/// The Jacobi test of the state the last derivatives were taken at.
#[derive(Debug, Clone, Default)]
struct Jacobi {
    /// The unknowns and load factor of that state.
    x: Vec<f64>,
    lambda: f64,
    /// Whether $h = \partial\phi/\partial M_0$ stayed positive at every accepted step on $(0, L]$.
    positive: bool,
    /// Whether $EI h^{\prime}(L) = \partial m(L)/\partial M_0 > 0$.
    rising: bool,
}

impl Jacobi {
    fn at(&self, x: &[f64], lambda: f64) -> bool {
        self.lambda == lambda && self.x == x
    }
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
struct Chain<'a> {
    flexure: &'a Flexure,
    load: TipLoad,
    ode: Tolerance,
    scale: f64,
    /// $k = \overline{EI}/L$ (N·m per rad).
    stiffness: f64,
    segments: usize,
    /// The arc lengths of the nodes, $s_0 = 0 < \dots < s_N = L$.
    nodes: Vec<f64>,
    /// The section's breakpoints (m), where each segment's integration restarts.
    stops: Vec<f64>,
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
    fn new(flexure: &'a Flexure, load: TipLoad, ode: Tolerance) -> Result<Self> {
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
        let nodes = (0..=segments)
            .map(|j| match j {
                0 => 0.0,
                _ if j == segments => l,
                _ if uniform => l * j as f64 / segments as f64,
                _ => stretch.at_fraction(j as f64 / segments as f64),
            })
            .collect();
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
    fn states(&mut self, x: &[f64]) -> Result<Vec<(f64, [f64; 4])>> {
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
    fn shot(&mut self, root_moment: f64, lambda: f64) -> Result<Vec<f64>> {
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

    /// The Jacobi test (see [`is_stable`]) of the state, from the
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

/// The exact tip pose under `load`: the elastica clamped at the root whose
/// moment at the tip equals $M$, i.e. $M_0 - F_y x_L + F_x y_L = M$.
///
/// Solved by multiple shooting on the shared pseudo-arclength continuation
/// ([`solver::continuation`]) from the rest shape, so the solution lies on
/// the loading path: a small imperfection decides which way a column
/// buckles, a snap-through load reaches the stable shape the path leads to
/// ([`Solution::limit`] names the load fraction where stability was lost),
/// and no step turns a node's cross-section by more than
/// `settings.solver.max_rotation_per_step`. The path is integrated to
/// `settings.path_tolerance` and its end refined by Newton to `settings.ode`,
/// so that the cost grows little with the angle the tip turns. Newton's
/// derivatives come from dual numbers carried through the integrator;
/// [`Solution::stable`] is the Jacobi test ([`is_stable`]) of the refined state.
///
/// The beam is cut into $N = \lceil L\sqrt{|F|/EI}\rceil$ segments (at
/// least 4), so that shooting across one segment stays well conditioned and
/// the cost grows little with the load; a force with
/// $L\sqrt{|F|/EI} >$ [`MAX_FORCE_GROWTH`] is refused.
///
/// Errors: [`Error::InvalidParameter`] for a non-finite load, bad settings or
/// too large a force; [`Error::ContinuationStalled`] with the load fraction
/// reached; [`Error::Unstable`] when the path loses stability and does not
/// come back to the full load; integrator failures.
///
/// # Example
/// ```
/// use flexure::{reference::elastica, Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // Bisshopp–Drucker: PL²/EI = 1 across the tip.
/// let s = elastica::deflect(&f, &TipLoad { moment: 0.0, fx: 0.0, fy: 1.0 }, &Default::default()).unwrap();
/// assert!((s.pose.x - 0.94357).abs() < 1e-5 && (s.pose.y - 0.30172).abs() < 1e-5);
/// ```
pub fn deflect(flexure: &Flexure, load: &TipLoad, settings: &Settings) -> Result<Solution> {
    deflect_traced(flexure, load, settings).map(|(solution, _)| solution)
}

/// [`deflect`], with the [`Trace`] of the exact shape: its cross-sections,
/// bending moment and stress anywhere along the flexure.
///
/// # Example
/// ```
/// use flexure::{reference::elastica, Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // A pure tip moment bends an arc: m = M all along, curvature M/EI.
/// let load = TipLoad { moment: 0.5, fx: 0.0, fy: 0.0 };
/// let (s, trace) = elastica::deflect_traced(&f, &load, &Default::default()).unwrap();
/// assert!((s.pose.phi - 0.5).abs() < 1e-10);
/// let mid = trace.at(0.5).unwrap();
/// assert!((mid.moment - 0.5).abs() < 1e-9 && (mid.phi - 0.25).abs() < 1e-9);
/// ```
pub fn deflect_traced<'a>(flexure: &'a Flexure, load: &TipLoad, settings: &Settings) -> Result<(Solution, Trace<'a>)> {
    load.validate()?;
    settings.validate()?;
    let mut chain = Chain::new(flexure, *load, settings.path_ode())?;
    let mut ws = solver::Workspace::new(chain.dim());
    // The rest shape: no moment anywhere, the nodes at their rest angles.
    ws.x = chain.shot(0.0, 0.0)?;
    let path = solver::continuation(&mut chain, &mut ws, &settings.solver)?;
    // The end state refined to `ode`: Newton starts within about
    // path_tolerance of it and converges in one or two iterations; the
    // stability verdict is the refined state's.
    chain.ode = settings.ode;
    solver::newton(&mut chain, &mut ws, 1.0, &settings.solver)?;
    let stable = chain.stable(&ws.x, 1.0, &ws.jacobian);
    let nodes = chain.states(&ws.x)?;
    let tip = nodes[nodes.len() - 1].1;
    let solution = Solution {
        stable,
        pose: Pose { phi: tip[0], x: tip[2], y: tip[3] },
        root_moment: ws.x[0] * chain.stiffness,
        load_steps: path.steps,
        limit: path.limit,
    };
    let trace = Trace { flexure, fx: load.fx, fy: load.fy, stops: chain.stops, nodes, ode: settings.ode };
    Ok((solution, trace))
}

/// Whether the elastica shot from `root_moment` under the tip force
/// $(F_x, F_y)$ is stable, by the Jacobi (conjugate-point) test.
///
/// The second variation of the potential energy about the shape $\phi(s)$,
///
/// $$\delta^2 E = \int_0^L \big[EI\thinspace\delta\phi^{\prime 2} +
/// (F_x\cos\phi + F_y\sin\phi)\thinspace\delta\phi^2\big]\thinspace ds,
/// \qquad \delta\phi(0) = 0,$$
///
/// is positive definite exactly when the Jacobi field $h = \partial\phi/\partial M_0$
/// (which solves $(EI h^{\prime})^{\prime} = (F_x\cos\phi + F_y\sin\phi)h$, $h(0) = 0$,
/// $EI h^{\prime}(0) = 1$) stays positive on $(0, L]$ and $EI h^{\prime}(L) > 0$: the
/// Prüfer angle of $h$ then stays below $\pi/2$ at the free end. $h$ is the
/// dual part of $\phi$ when the shot carries a dual root moment, and
/// $EI h^{\prime}(L)$ is the derivative of the tip-moment balance the shooting solves.
///
/// # Example
/// ```
/// use flexure::{reference::elastica, Flexure};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // A straight column, clamped and free, buckles at P = π²EI/4L² ≈ 2.467.
/// assert!(elastica::is_stable(&f, 0.0, -2.4, 0.0, &Default::default()).unwrap());
/// assert!(!elastica::is_stable(&f, 0.0, -2.5, 0.0, &Default::default()).unwrap());
/// ```
pub fn is_stable(flexure: &Flexure, root_moment: f64, fx: f64, fy: f64, tol: &Tolerance) -> Result<bool> {
    TipLoad { moment: root_moment, fx, fy }.validate()?;
    tol.validate()?;
    // The chain through the shot from the root (the tip moment that shot
    // carries does not enter the test).
    let mut chain = Chain::new(flexure, TipLoad { moment: 0.0, fx, fy }, *tol)?;
    let x = chain.shot(root_moment, 1.0)?;
    Ok(chain.stable(&x, 1.0, &[]))
}

/// An exact minimum-energy shape between two poses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Connection {
    /// Bending energy $U^* = \int_0^L \frac{EI}{2}(\omega - \omega_0)^2 ds$ (J).
    pub energy: f64,
    /// Bending moment at the root, $M_0$ (N·m).
    pub root_moment: f64,
    /// The force carried along the beam, equal to the force on the tip (N).
    pub fx: f64,
    /// See `fx`.
    pub fy: f64,
}

/// Integrates Eq. 3 as [`shoot`] does, adding the energy $\int m^2/2EI\thinspace ds$ as a fourth state.
fn shoot_with_energy<T: Scalar>(
    flexure: &Flexure,
    stops: &[f64],
    m0: T,
    fx: T,
    fy: T,
    tol: &Tolerance,
) -> Result<[T; 4]> {
    let kappa = flexure.rest();
    let rhs = |s: f64, y: &[T; 4]| {
        let (sn, cs) = y[0].sin_cos();
        let m = m0 - fy * y[1] + fx * y[2];
        let ei = T::c(flexure.ei_at(s));
        [T::c(flexure.curvature(kappa, s)) + m / ei, cs, sn, m * m / (ei + ei)]
    };
    integrate_through(rhs, 0.0, flexure.length(), stops, [T::zero(); 4], tol, &mut 0.0, |_, _| {})
}

/// The connection as a [`Problem`] for [`solver::newton`]: unknowns
/// $(M_0, F_x, F_y)$, residual the tip-pose mismatch $((\phi_L - \phi_t)L, x_L - x_t, y_L - y_t)$.
struct Through<'a> {
    flexure: &'a Flexure,
    target: Pose,
    ode: Tolerance,
    /// The section's breakpoints (m).
    stops: Vec<f64>,
    /// $\int_0^L ds/EI$ and $\int_0^L EI^{-1/2} ds$ (`L/EI` and `L/√EI` when uniform).
    flexibility: f64,
    stretch: f64,
}

impl Problem<f64> for Through<'_> {
    fn dim(&self) -> usize {
        3
    }

    fn evaluate(
        &mut self,
        z: &[f64],
        _lambda: f64,
        residual: &mut [f64],
        jacobian: Option<&mut [f64]>,
        dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        let (l, t) = (self.flexure.length(), self.target);
        // Iterates no connection needs are refused before integrating: a
        // shot under such loads coils and costs steps in proportion to them.
        let growth = z[1].hypot(z[2]).sqrt() * self.stretch;
        if growth > MAX_FORCE_GROWTH || z[0].abs() * self.flexibility > MAX_FORCE_GROWTH.powi(2) {
            return Err(Error::Singular {
                what: "exact connection: a Newton iterate beyond any connection's load".into(),
            });
        }
        if let Some(jac) = jacobian {
            let v = |i: usize| DualSVec64::<3>::from_re(z[i]).derivative(i);
            let tip = shoot_with_energy(self.flexure, &self.stops, v(0), v(1), v(2), &self.ode)?;
            let r = [(tip[0] - t.phi) * l, tip[1] - t.x, tip[2] - t.y];
            for (row, ri) in r.iter().enumerate() {
                residual[row] = ri.re;
                let d = ri.eps.unwrap_generic(Const::<3>, Const::<1>);
                for col in 0..3 {
                    jac[col * 3 + row] = d[col];
                }
            }
        } else {
            let tip = shoot_with_energy(self.flexure, &self.stops, z[0], z[1], z[2], &self.ode)?;
            residual.copy_from_slice(&[(tip[0] - t.phi) * l, tip[1] - t.x, tip[2] - t.y]);
        }
        if let Some(d) = dlambda {
            d.fill(0.0);
        }
        if residual.iter().all(|r| r.is_finite()) {
            Ok(())
        } else {
            Err(Error::Singular { what: "exact connection: non-finite tip pose".into() })
        }
    }

    /// An upper bound, in linear theory, of the cross-sections' rotation
    /// between the loads $(M_0, F_x, F_y)$ `a` and `b`: $(|\Delta M_0| + L|\Delta F|_1)\int_0^L ds/EI$.
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        let l = self.flexure.length();
        ((a[0] - b[0]).abs() + l * ((a[1] - b[1]).abs() + (a[2] - b[2]).abs())) * self.flexibility
    }

    fn scale(&self) -> f64 {
        self.flexure.length()
    }

    fn unit(&self) -> &'static str {
        "m"
    }

    fn name(&self) -> &'static str {
        "exact connection"
    }
}

/// The exact elastica through `target`, by shooting on the root moment and
/// both force components (three unknowns) until the tip pose matches.
///
/// `guess` is $(M_0, F_x, F_y)$; the model's [`crate::connect::connect`]
/// multipliers, moved to the root, make a good one. Damped Newton
/// ([`solver::newton`]) with the Jacobian from dual numbers through the
/// integrator, to a tip-pose mismatch of `settings.solver.tolerance` × $L$.
/// The minimum energy $U^*$ of Eq. 16.
///
/// # Example
/// ```
/// use flexure::{reference::elastica, Flexure, Pose};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // An arc of angle 1 needs a pure moment 1: U* = 1/2.
/// let target = Pose { phi: 1.0, x: 1f64.sin(), y: 1.0 - 1f64.cos() };
/// let c = elastica::connect(&f, &target, [0.9, 0.0, 0.0], &Default::default()).unwrap();
/// assert!((c.energy - 0.5).abs() < 1e-10 && (c.root_moment - 1.0).abs() < 1e-9);
/// ```
pub fn connect(flexure: &Flexure, target: &Pose, guess: [f64; 3], settings: &Settings) -> Result<Connection> {
    crate::connect::check_pose(flexure, target)?;
    settings.validate()?;
    for (name, g) in ["guess[0]", "guess[1]", "guess[2]"].into_iter().zip(guess) {
        crate::error::finite(name, g)?;
    }
    let s = crate::reference::Stretch::of(flexure)?;
    let (flexibility, stretch) = (s.flexibility, s.total());
    let stops = crate::reference::stops(flexure);
    let mut problem = Through { flexure, target: *target, ode: settings.ode, stops, flexibility, stretch };
    let mut ws = solver::Workspace::new(3);
    ws.x.copy_from_slice(&guess);
    solver::newton(&mut problem, &mut ws, 1.0, &settings.solver)?;
    let tip = shoot_with_energy(flexure, &problem.stops, ws.x[0], ws.x[1], ws.x[2], &settings.ode)?;
    Ok(Connection { energy: tip[3], root_moment: ws.x[0], fx: ws.x[1], fy: ws.x[2] })
}

/// Nodes a [`Trace::shot`] keeps along the flexure: a cross-section is then
/// integrated from at most $L/16$ away.
const SHOT_NODES: usize = 16;

/// Evenly spaced samples of the scan that brackets a peak ([`Trace::peak_stress`]).
const PEAK_SAMPLES: usize = 256;

/// Golden-section steps refining a bracketed peak: $0.618^{60} \approx 3\cdot10^{-13}$ of the bracket.
const PEAK_REFINEMENTS: usize = 60;

/// A cross-section of the exact elastica.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Arc length from the root (m).
    pub s: f64,
    /// Angle (rad).
    pub phi: f64,
    /// Position in the root frame (m).
    pub x: f64,
    /// See `x`.
    pub y: f64,
    /// Bending moment $m(s)$ (N·m).
    pub moment: f64,
    /// Total curvature $\omega_0(s) + m/EI(s)$ (1/m).
    pub curvature: f64,
    /// Change of curvature from rest, $m/EI(s)$ (1/m).
    pub curvature_change: f64,
    /// Bending stress $E^{\prime}\frac{h(s)}{2}\frac{|m|}{EI(s)}$ (Pa); `None` for a section without thickness.
    pub stress: Option<f64>,
}

/// The exact elastica along a flexure: the state $(\phi, m, x, y)$ at nodes
/// from the root to the tip, from which any cross-section is integrated by
/// $$\phi^{\prime} = \omega_0(s) + \frac{m}{EI(s)}, \quad m^{\prime} = F_x\sin\phi - F_y\cos\phi, \quad x^{\prime} = \cos\phi, \quad y^{\prime} = \sin\phi,$$
/// the force $(F_x, F_y)$ carried along the beam being the tip force. Made
/// by [`deflect_traced`], [`Trace::shot`] or [`Connection::trace`].
#[derive(Debug, Clone, PartialEq)]
pub struct Trace<'a> {
    flexure: &'a Flexure,
    fx: f64,
    fy: f64,
    /// The section's breakpoints (m).
    stops: Vec<f64>,
    /// $(s_j, [\phi, m, x, y])$ with $s_0 = 0$ and the last at $L$.
    nodes: Vec<(f64, [f64; 4])>,
    ode: Tolerance,
}

impl<'a> Trace<'a> {
    /// The elastica shot from the clamped root with moment $M_0$ under the
    /// force $(F_x, F_y)$, kept at 16 evenly spaced nodes.
    ///
    /// # Example
    /// ```
    /// use flexure::{reference::elastica::Trace, Flexure};
    /// let f = Flexure::new(2.0, 4.0, 3).unwrap();
    /// // A root moment 2 and no force: an arc of curvature 1/2, angle 1.
    /// let t = Trace::shot(&f, 2.0, 0.0, 0.0, &Default::default()).unwrap();
    /// assert!((t.tip().phi - 1.0).abs() < 1e-11 && (t.at(1.0).unwrap().curvature - 0.5).abs() < 1e-12);
    /// ```
    pub fn shot(flexure: &'a Flexure, root_moment: f64, fx: f64, fy: f64, tol: &Tolerance) -> Result<Self> {
        TipLoad { moment: root_moment, fx, fy }.validate()?;
        tol.validate()?;
        let l = flexure.length();
        let mut trace = Self { flexure, fx, fy, stops: crate::reference::stops(flexure), nodes: Vec::new(), ode: *tol };
        let mut node = (0.0, [0.0, root_moment, 0.0, 0.0]);
        trace.nodes.push(node);
        for j in 1..=SHOT_NODES {
            let s = if j == SHOT_NODES { l } else { l * j as f64 / SHOT_NODES as f64 };
            node = (s, trace.advance(node, s, &mut 0.0)?);
            trace.nodes.push(node);
        }
        Ok(trace)
    }

    /// The flexure traced.
    pub fn flexure(&self) -> &'a Flexure {
        self.flexure
    }

    /// The tip pose.
    pub fn tip(&self) -> Pose {
        let y = self.nodes[self.nodes.len() - 1].1;
        Pose { phi: y[0], x: y[2], y: y[3] }
    }

    /// The state at `to`, integrated from `from` (forward).
    fn advance(&self, from: (f64, [f64; 4]), to: f64, step: &mut f64) -> Result<[f64; 4]> {
        let (f, kappa, fx, fy) = (self.flexure, self.flexure.rest(), self.fx, self.fy);
        let rhs = |s: f64, y: &[f64; 4]| {
            let (sn, cs) = y[0].sin_cos();
            [f.curvature(kappa, s) + y[1] / f.ei_at(s), fx * sn - fy * cs, cs, sn]
        };
        integrate_through(rhs, from.0, to, &self.stops, from.1, &self.ode, step, |_, _| {})
    }

    /// The states at `points` (increasing, within $[0, L]$): each
    /// integrated from the last point or the node before it, whichever is nearer.
    fn states(&self, points: &[f64]) -> Result<Vec<[f64; 4]>> {
        let l = self.flexure.length();
        let mut out = Vec::with_capacity(points.len());
        let mut last = self.nodes[0];
        let mut step = 0.0;
        for (i, &s) in points.iter().enumerate() {
            if !(s.is_finite() && (0.0..=l).contains(&s)) || (i > 0 && s < points[i - 1]) {
                return Err(Error::invalid("s", s, "must increase within the flexure, from 0 to its length"));
            }
            let j = self.nodes.partition_point(|n| n.0 <= s).max(1) - 1;
            if last.0 < self.nodes[j].0 || last.0 > s {
                last = self.nodes[j];
            }
            last = (s, self.advance(last, s, &mut step)?);
            out.push(last.1);
        }
        Ok(out)
    }

    /// The cross-section at `s` from its state.
    fn point(&self, s: f64, y: &[f64; 4]) -> Point {
        let (f, l) = (self.flexure, self.flexure.length());
        let change = y[1] / f.ei_at(s);
        let section = f.section();
        let stress = section.modulus().zip(section.thickness(s / l, l)).map(|(e, h)| e * 0.5 * h * change.abs());
        Point {
            s,
            phi: y[0],
            x: y[2],
            y: y[3],
            moment: y[1],
            curvature: f.curvature(f.rest(), s) + change,
            curvature_change: change,
            stress,
        }
    }

    /// The cross-section at arc length `s` (m).
    pub fn at(&self, s: f64) -> Result<Point> {
        Ok(self.point(s, &self.states(&[s])?[0]))
    }

    /// The cross-sections at `points` (m, increasing within $[0, L]$).
    pub fn sample(&self, points: &[f64]) -> Result<Vec<Point>> {
        let states = self.states(points)?;
        Ok(points.iter().zip(&states).map(|(&s, y)| self.point(s, y)).collect())
    }

    /// The deformed flexure at `count` points evenly spaced in arc length,
    /// ends included (2 to 100 000 points).
    ///
    /// # Example
    /// ```
    /// use flexure::{reference::elastica::Trace, Flexure};
    /// let f = Flexure::new(1.0, 1.0, 3).unwrap();
    /// let shape = Trace::shot(&f, 0.0, 0.0, 0.0, &Default::default()).unwrap().shape(5).unwrap();
    /// assert_eq!(shape.len(), 5);
    /// assert!((shape[2].x - 0.5).abs() < 1e-15 && shape[4].s == 1.0);
    /// ```
    pub fn shape(&self, count: usize) -> Result<Vec<Point>> {
        if !(2..=100_000).contains(&count) {
            return Err(Error::invalid("count", count, "must be from 2 to 100000 points"));
        }
        let l = self.flexure.length();
        let points: Vec<f64> =
            (0..count).map(|i| if i + 1 == count { l } else { l * i as f64 / (count - 1) as f64 }).collect();
        self.sample(&points)
    }

    /// The peak bending stress along the flexure, $\max_s E^{\prime}\frac{h}{2}\frac{|m|}{EI}$;
    /// `None` for a section without thickness.
    pub fn peak_stress(&self) -> Result<Option<Peak>> {
        if self.flexure.section().modulus().is_none() {
            return Ok(None);
        }
        self.peak(|p| p.stress.unwrap_or(0.0)).map(Some)
    }

    /// The largest change of curvature from rest, $\max_s |m|/EI$ (1/m).
    pub fn peak_curvature(&self) -> Result<Peak> {
        self.peak(|p| p.curvature_change.abs())
    }

    /// The maximum of `g` along the flexure: a scan of evenly spaced
    /// points, the breakpoints and the nodes, then golden-section
    /// refinement between the best point's neighbours (bounded steps).
    fn peak(&self, g: impl Fn(&Point) -> f64) -> Result<Peak> {
        let l = self.flexure.length();
        let mut points: Vec<f64> = (0..=PEAK_SAMPLES).map(|k| l * k as f64 / PEAK_SAMPLES as f64).collect();
        points.extend(&self.stops);
        points.extend(self.nodes.iter().map(|n| n.0));
        points.retain(|s| (0.0..=l).contains(s));
        points.sort_by(f64::total_cmp);
        points.dedup();
        let states = self.states(&points)?;
        let values: Vec<f64> = points.iter().zip(&states).map(|(&s, y)| g(&self.point(s, y))).collect();
        let best = (0..points.len()).max_by(|&a, &b| values[a].total_cmp(&values[b])).unwrap_or(0);
        let top = Peak { value: values[best], at: points[best] };
        let from = best.saturating_sub(1);
        let base = (points[from], states[from]);
        let bracket = (points[from], points[(best + 1).min(points.len() - 1)]);
        crate::stress::refine(bracket, top, l, PEAK_REFINEMENTS, |s| {
            Ok(g(&self.point(s, &self.advance(base, s, &mut 0.0)?)))
        })
    }
}

impl Connection {
    /// The exact shape of this connection on `flexure` (the one it was
    /// found for): the shot from the root with its moment and force.
    pub fn trace<'a>(&self, flexure: &'a Flexure, tol: &Tolerance) -> Result<Trace<'a>> {
        Trace::shot(flexure, self.root_moment, self.fx, self.fy, tol)
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
        let lambda = 0.6;
        let (mut r, mut jac, mut dl) = (vec![0.0; n], vec![0.0; n * n], vec![0.0; n]);
        chain.evaluate(&x, lambda, &mut r, Some(&mut jac), Some(&mut dl)).unwrap();
        let h = 1e-6;
        let mut residual_at = |x: &[f64], lambda: f64| {
            let mut r = vec![0.0; n];
            chain.evaluate(x, lambda, &mut r, None, None).unwrap();
            r
        };
        for col in 0..n {
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[col] += h;
            xm[col] -= h;
            let (rp, rm) = (residual_at(&xp, lambda), residual_at(&xm, lambda));
            for row in 0..n {
                let fd = (rp[row] - rm[row]) / (2.0 * h);
                assert!((jac[col * n + row] - fd).abs() < 1e-6, "J[{row},{col}] {} vs {fd}", jac[col * n + row]);
            }
        }
        let (rp, rm) = (residual_at(&x, lambda + h), residual_at(&x, lambda - h));
        for row in 0..n {
            let fd = (rp[row] - rm[row]) / (2.0 * h);
            assert!((dl[row] - fd).abs() < 1e-6, "∂r{row}/∂λ {} vs {fd}", dl[row]);
        }
    }
}
