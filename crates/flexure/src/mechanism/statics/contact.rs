//! Equilibrium with contact: the KKT conditions of [`Kkt`] with a
//! unilateral constraint for each contact that touches, followed along the
//! load with the set of touching contacts changed where one opens, one
//! touches, or one moves onto or off a flexure's end.
//!
//! **A touching contact** $c$ keeps its gap $g_c(q, s_c) = 0$
//! ([`gap_jet`]) with a compressive force $N_c \ge 0$ along the geom's
//! normal, which enters the stationarity rows as $-N_c\nabla_q g_c$ (the
//! Lagrangian $V + \mu^Tc - \sum_c N_cg_c$). A contact inside a flexure's
//! span sits where the gap is least: $s_c$ is an unknown with the row
//! $\partial_s g_c = 0$ (the surface and the flexure tangent); at an end
//! it stays there. Unknowns: $(q, \nu)$ of [`Kkt`], then each contact's
//! $N_c/\sigma$ ($\sigma = k/\ell$ as a position multiplier's scale), then each
//! inner contact's $s_c/L$. Rows: [`Kkt`]'s, then each gap over $\ell$, then
//! each tangency. The Jacobian is exact ([`gap_jet`]'s derivatives).
//!
//! **Complementarity along the path** ($g \ge 0$, $N \ge 0$, $gN = 0$):
//! the load factor $\lambda$ goes from 0 to 1 in steps of at most 0.1 that
//! turn nothing by more than `max_rotation_per_step`, each solved by Newton
//! from the secant predictor. After each step it is checked for an event:
//! a touching contact pulling ($N < 0$: it opens), a gap's local least
//! below $-10^{-10}\ell$ (a new contact), an end contact whose flexure turns
//! into the geom beside it ($\partial_s g$ pointing inward: it rolls onto
//! the span), an inner contact reaching an end, or a loss of stability. A
//! step with an event is bisected to $10^{-10}$ of the load, the set changed
//! at the near side and solved there again (at most 8 changes at one load).
//!
//! **Refused by name:** friction (not yet solved in statics), a mechanism
//! whose assembly overlaps a geom, a flexure lying along a geom (two
//! contacts of one pair closer than a hundredth of its length: distributed
//! contact), and a path that loses stability (snap-through is not followed
//! with contact).

use super::Settings;
use super::Solution;
use super::assembly::assemble_in;
use super::dimension::Statics;
use super::kkt::Kkt;
use super::workspace::{Buffers, Workspace};
use crate::error::{Error, Result};
use crate::kinematics::Level;
use crate::linalg;
use crate::mechanism::contact::{
    Contact, ContactMode, GapJet, Pair, Toucher, ball_and_other, gap_jet, minima, named, pairs,
};
use crate::mechanism::kinematics::{Frames, frames_level_into};
use crate::mechanism::{Loads, Mechanism};
use crate::solver::{self, Problem};
use nalgebra::DMatrix;

/// The first load step, and the largest.
const FIRST_STEP: f64 = 0.05;
const LARGEST_STEP: f64 = 0.1;
/// The smallest load step before the path is declared stalled.
const SMALLEST_STEP: f64 = 1e-9;
/// Events are bisected until their bracket in the load factor is this narrow.
const EVENT_RESOLUTION: f64 = 1e-10;
/// A gap below this fraction of $\ell$ is a new contact.
const GAP_TOLERANCE: f64 = 1e-10;
/// A force below $-$ this × $\sigma$ × the residual's scale pulls.
const FORCE_TOLERANCE: f64 = 1e-9;
/// $\partial_s g$ beyond this at an end contact turns it onto the span.
const ROLL_TOLERANCE: f64 = 1e-9;
/// Two contacts of one pair this close (× the flexure's length) lie along the geom.
const FLAT_LENGTH: f64 = 1e-2;
/// Changes of the set at one load before the path is declared stalled.
const MAX_CHANGES_AT_ONCE: usize = 8;
/// Accepted steps before the path is declared stalled.
const MAX_STEPS: usize = 10_000;

/// Where a contact sits.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Place {
    /// At a flexure's root or tip (this arc length), staying there.
    End(f64),
    /// Inside a flexure's span, where the gap is least (its arc length an unknown).
    Inner,
    /// Between two geoms.
    Geoms,
}

/// A contact that touches: its pair, place, force unknown and, inside a span, $s/L$.
#[derive(Debug, Clone, Copy)]
struct Touching {
    pair: Pair,
    place: Place,
    force: f64,
    at: f64,
    /// The flexure's length (1 between geoms).
    length: f64,
}

impl Touching {
    fn s(&self) -> Option<f64> {
        match self.place {
            Place::End(s) => Some(s),
            Place::Inner => Some(self.at * self.length),
            Place::Geoms => None,
        }
    }
}

/// [`Kkt`] with the rows and unknowns of the contacts that touch.
struct ContactKkt<'a, D: Statics> {
    kkt: Kkt<'a, D>,
    touching: Vec<Touching>,
    frames: Frames<D>,
    /// [`Kkt`]'s own Jacobian.
    inner: Vec<f64>,
    /// $\sigma$: a contact's force unknown in N.
    sigma: f64,
    jets: Vec<GapJet<D>>,
}

impl<D: Statics> ContactKkt<'_, D> {
    fn inner_dim(&self) -> usize {
        self.kkt.mechanism.dof() + self.kkt.mechanism.constraints()
    }

    /// The inner contacts' places among the unknowns after the forces.
    fn inner_index(&self) -> Vec<Option<usize>> {
        let mut k = 0;
        self.touching
            .iter()
            .map(|t| {
                (t.place == Place::Inner).then(|| {
                    k += 1;
                    k - 1
                })
            })
            .collect()
    }

    /// The unknowns of the Kkt state `x` and the touching contacts.
    fn state(&self, x: &[f64]) -> Vec<f64> {
        let mut out = x[..self.inner_dim()].to_vec();
        out.extend(self.touching.iter().map(|t| t.force / self.sigma));
        out.extend(self.touching.iter().filter(|t| t.place == Place::Inner).map(|t| t.at));
        out
    }

    /// The touching contacts' forces and places read from the unknowns `x`.
    fn read(&mut self, x: &[f64]) {
        let (kd, count) = (self.inner_dim(), self.touching.len());
        let index = self.inner_index();
        for (c, t) in self.touching.iter_mut().enumerate() {
            t.force = x[kd + c] * self.sigma;
            if let Some(i) = index[c] {
                t.at = x[kd + count + i];
            }
        }
    }
}

impl<D: Statics> Problem<f64> for ContactKkt<'_, D> {
    fn dim(&self) -> usize {
        self.inner_dim() + self.touching.len() + self.touching.iter().filter(|t| t.place == Place::Inner).count()
    }

    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        residual: &mut [f64],
        jacobian: Option<&mut [f64]>,
        dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        let (kd, size) = (self.inner_dim(), self.dim());
        let m = self.kkt.mechanism;
        let n = m.dof();
        let count = self.touching.len();
        let want = jacobian.is_some();
        let mut inner = std::mem::take(&mut self.inner);
        inner.resize(kd * kd, 0.0);
        let (head, _) = residual.split_at_mut(kd);
        match dlambda {
            Some(d) => {
                self.kkt.evaluate(&x[..kd], lambda, head, want.then_some(&mut inner[..]), Some(&mut d[..kd]))?;
                d[kd..].fill(0.0);
            }
            None => self.kkt.evaluate(&x[..kd], lambda, head, want.then_some(&mut inner[..]), None)?,
        }
        self.read(x);
        let q = &x[..n];
        frames_level_into(m, q, Level::Hessian, &mut self.frames);
        self.jets.clear();
        for t in &self.touching {
            let s = t.s().map(|s| s.clamp(0.0, t.length));
            self.jets.push(gap_jet(m, &self.frames, q, &t.pair, s)?);
        }
        let index = self.inner_index();
        let (rows, length) = (&self.kkt.row_scale, self.kkt.length);
        for (c, (t, jet)) in self.touching.iter().zip(&self.jets).enumerate() {
            for i in 0..n {
                residual[i] -= t.force * jet.gradient[i] * rows[i];
            }
            residual[kd + c] = jet.gap / length;
            if let Some(f) = index[c] {
                residual[kd + count + f] = jet.ds;
            }
        }
        if !residual.iter().all(|r| r.is_finite()) {
            return Err(Error::Singular { what: "mechanism equilibrium with contact: a non-finite residual".into() });
        }
        if let Some(jac) = jacobian {
            jac.fill(0.0);
            for c in 0..kd {
                jac[c * size..c * size + kd].copy_from_slice(&inner[c * kd..(c + 1) * kd]);
            }
            for (c, (t, jet)) in self.touching.iter().zip(&self.jets).enumerate() {
                let (force, row) = (t.force, kd + c);
                for j in 0..n {
                    for i in 0..n {
                        jac[j * size + i] -= force * jet.hessian[(i, j)] * rows[i];
                    }
                    jac[(kd + c) * size + j] = -self.sigma * jet.gradient[j] * rows[j];
                    jac[j * size + row] = jet.gradient[j] / length;
                }
                if let Some(f) = index[c] {
                    let (column, tangency) = (kd + count + f, kd + count + f);
                    for i in 0..n {
                        jac[column * size + i] = -force * jet.dqs[i] * rows[i] * t.length;
                        jac[i * size + tangency] = jet.dqs[i];
                    }
                    jac[column * size + row] = jet.ds * t.length / length;
                    jac[column * size + tangency] = jet.dss * t.length;
                }
            }
        }
        self.inner = inner;
        Ok(())
    }

    /// The constrained stiffness positive definite with [`Kkt`]'s margin, the
    /// touching contacts' gradients among the constraints and each inner
    /// contact's place eliminated: $\nabla^2 g_{\min} = g_{qq} - g_{qs}g_{sq}/g_{ss}$.
    fn stable(&mut self, _x: &[f64], _lambda: f64, jacobian: &[f64]) -> bool {
        let m = self.kkt.mechanism;
        let (n, rows, size) = (m.dof(), m.constraints(), self.dim());
        let scale = &self.kkt.row_scale;
        let mut h = DMatrix::from_fn(n, n, |r, c| jacobian[c * size + r] / scale[r]);
        let mut g: Vec<Vec<f64>> = (0..rows)
            .map(|i| (0..n).map(|c| jacobian[c * size + n + i] / self.kkt.closure_scale[i]).collect())
            .collect();
        for (t, jet) in self.touching.iter().zip(&self.jets) {
            if t.place == Place::Inner {
                if jet.dss <= 0.0 {
                    return false;
                }
                for r in 0..n {
                    for c in 0..n {
                        h[(r, c)] += t.force * jet.dqs[r] * jet.dqs[c] / jet.dss;
                    }
                }
            }
            if t.force > 0.0 {
                g.push(jet.gradient.clone());
            }
        }
        let s: Vec<f64> = scale.iter().map(|r| r.sqrt()).collect();
        let h = DMatrix::from_fn(n, n, |r, c| 0.5 * (h[(r, c)] + h[(c, r)]) * s[r] * s[c]);
        let g = DMatrix::from_fn(g.len(), n, |i, c| g[i][c] * s[c]);
        let z = linalg::null_space(&g);
        let mut k = super::constrained(&h, &z);
        for i in 0..k.nrows() {
            k[(i, i)] -= self.kkt.margin;
        }
        linalg::is_positive_definite(&k)
    }

    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        let kd = self.inner_dim();
        self.kkt.distance(&a[..kd], &b[..kd])
    }

    fn scale(&self) -> f64 {
        self.kkt.scale()
    }

    fn unit(&self) -> &'static str {
        "relative"
    }

    fn name(&self) -> &'static str {
        "mechanism equilibrium with contact"
    }

    fn weight(&self, i: usize) -> f64 {
        if i < self.inner_dim() { self.kkt.weight(i) } else { 0.0 }
    }
}

/// What ends a load step.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Event {
    /// Touching contact `c` pulls.
    Open(usize),
    /// Inner contact `c` reached the end at this arc length.
    AtEnd(usize, f64),
    /// End contact `c`'s flexure turns into the geom beside the end.
    Roll(usize),
    /// The pair's gap has a least below the tolerance at this arc length.
    Touch(Pair, Option<f64>),
    /// The equilibrium is no longer stable.
    Unstable,
}

/// A Newton solve of `problem` at `lambda` from `x`: the solution and its iterations.
fn newton<D: Statics>(
    problem: &mut ContactKkt<D>,
    x: &[f64],
    lambda: f64,
    settings: &Settings,
) -> Result<(Vec<f64>, solver::NewtonReport)> {
    let mut ws = solver::SolverWorkspace::new(problem.dim());
    ws.x.copy_from_slice(x);
    let report = solver::newton(problem, &mut ws, lambda, settings)?;
    Ok((ws.x, report))
}

/// The first event at the equilibrium `x` (solved at `lambda`), if any.
fn event<D: Statics>(problem: &mut ContactKkt<D>, x: &[f64], lambda: f64, all: &[Pair]) -> Result<Option<Event>> {
    let size = problem.dim();
    let (mut r, mut jac) = (vec![0.0; size], vec![0.0; size * size]);
    problem.evaluate(x, lambda, &mut r, Some(&mut jac), None)?;
    let m = problem.kkt.mechanism;
    let pull = -FORCE_TOLERANCE * problem.sigma * problem.kkt.scale();
    for (c, (t, jet)) in problem.touching.iter().zip(&problem.jets).enumerate() {
        if t.force < pull {
            return Ok(Some(Event::Open(c)));
        }
        match t.place {
            Place::Inner if !(0.0..=1.0).contains(&t.at) => {
                return Ok(Some(Event::AtEnd(c, t.at.clamp(0.0, 1.0) * t.length)));
            }
            Place::End(s) if (s > 0.0 && jet.ds > ROLL_TOLERANCE) || (s == 0.0 && jet.ds < -ROLL_TOLERANCE) => {
                return Ok(Some(Event::Roll(c)));
            }
            _ => {}
        }
    }
    let length = problem.kkt.length;
    let q = &x[..m.dof()];
    for pair in all {
        let near: Vec<&Touching> = problem.touching.iter().filter(|t| t.pair == *pair).collect();
        for low in minima(m, q, &problem.frames.bodies, pair)? {
            let known = near.iter().any(|t| match (t.s(), low.s) {
                (Some(a), Some(b)) => (a - b).abs() <= FLAT_LENGTH * t.length,
                _ => true,
            });
            if low.gap < -GAP_TOLERANCE * length && !known {
                return Ok(Some(Event::Touch(*pair, low.s)));
            }
        }
    }
    if !problem.stable(x, lambda, &jac) {
        return Ok(Some(Event::Unstable));
    }
    Ok(None)
}

/// The set after `event`, with each touching contact's unknowns; an error
/// for distributed contact or an unstable path.
fn changed<D: Statics>(m: &Mechanism<D>, touching: &[Touching], event: Event, lambda: f64) -> Result<Vec<Touching>> {
    let mut out = touching.to_vec();
    match event {
        Event::Open(c) => {
            out.remove(c);
        }
        Event::AtEnd(c, s) => out[c].place = Place::End(s),
        Event::Roll(c) => {
            // Just inside the end, where Newton finds the least.
            let s = out[c].s().unwrap_or(0.0);
            out[c].at = if s > 0.0 { 1.0 - 1e-6 } else { 1e-6 };
            out[c].place = Place::Inner;
        }
        Event::Touch(pair, s) => {
            let length = match pair.part {
                Toucher::Flexure(j) => m.joints[j].kind.flexure().map_or(1.0, D::flexure_length),
                Toucher::Geom(_) => 1.0,
            };
            let place = match s {
                None => Place::Geoms,
                Some(s) if s <= 1e-9 * length => Place::End(0.0),
                Some(s) if s >= (1.0 - 1e-9) * length => Place::End(length),
                Some(_) => Place::Inner,
            };
            let at = s.map_or(0.0, |s| s / length);
            let close = |t: &Touching| match (t.s(), s) {
                (Some(a), Some(b)) => (a - b).abs() <= FLAT_LENGTH * length,
                _ => false,
            };
            if out.iter().any(|t| t.pair == pair && close(t)) {
                return Err(lies_along(m, &pair));
            }
            out.push(Touching { pair, place, force: 0.0, at, length });
        }
        Event::Unstable => {
            return Err(Error::Unstable { what: "mechanism equilibrium with contact", load_fraction: lambda });
        }
    }
    Ok(out)
}

fn lies_along<D: Statics>(m: &Mechanism<D>, pair: &Pair) -> Error {
    Error::invalid(
        "geom",
        named(m, pair),
        "touch along an interval (distributed contact), which is not solved: the flexure lies along the geom",
    )
}

/// An equilibrium with contact and what the path to it left: its
/// touching contacts and the pairs that touched, where a path under other
/// loads goes on from (a sweep's next value).
#[derive(Debug, Clone)]
pub struct Touched<D: Statics> {
    q: Vec<f64>,
    multipliers: Vec<f64>,
    loads: Loads<D>,
    touching: Vec<Touching>,
    touched: Vec<Pair>,
}

/// Equilibrium of `m` under its loads, with its contacts (see the module
/// docs), in the buffers `work` (made for `m`).
pub(super) fn solve_touching<D: Statics>(
    m: &Mechanism<D>,
    settings: &Settings,
    work: &mut Workspace<D>,
) -> Result<Solution<D>> {
    follow_touching(m, None, &m.loads(), settings, work).map(|(s, _)| s)
}

/// Equilibrium of `m` under `to`, with its contacts, followed from `from`
/// (an equilibrium and its contacts), or from the unloaded, assembled
/// mechanism; with where a next path goes on from.
pub fn follow_touching<D: Statics>(
    m: &Mechanism<D>,
    from: Option<&Touched<D>>,
    to: &Loads<D>,
    settings: &Settings,
    work: &mut Workspace<D>,
) -> Result<(Solution<D>, Touched<D>)> {
    let all = pairs(m);
    if let Some(p) = all.iter().find(|p| m.geoms[p.geom].friction > 0.0) {
        return Err(Error::invalid(
            "friction",
            format!("{} ({})", m.geoms[p.geom].friction, named(m, p)),
            "is not solved in statics yet: set the geom's friction to 0 for frictionless contact",
        ));
    }
    if !work.fits(m) {
        *work = Workspace::new(m);
    }
    work.touching = true;
    let found = follow(m, from, to, settings, work, &all);
    work.touching = false;
    found
}

fn follow<D: Statics>(
    m: &Mechanism<D>,
    from: Option<&Touched<D>>,
    to: &Loads<D>,
    settings: &Settings,
    work: &mut Workspace<D>,
    all: &[Pair],
) -> Result<(Solution<D>, Touched<D>)> {
    D::check_loads(m, to)?;
    let start = match from {
        Some(t) => t.clone(),
        None => {
            let start = assemble_in(m, settings, work)?;
            let length = m.size();
            let bodies = crate::mechanism::kinematics::frames(m, &start.q).bodies;
            for pair in all {
                for low in minima(m, &start.q, &bodies, pair)? {
                    if low.gap < -GAP_TOLERANCE * length {
                        return Err(Error::invalid(
                            "geom",
                            format!("{} (overlapping by {:.3e} m)", named(m, pair), -low.gap),
                            "must not overlap once the mechanism is assembled, before any load",
                        ));
                    }
                }
            }
            Touched {
                q: start.q,
                multipliers: start.multipliers,
                loads: D::zero(to),
                touching: Vec::new(),
                touched: Vec::new(),
            }
        }
    };
    let kkt = Kkt::fitted(m, &start.loads, to, settings, Buffers::Borrowed(work))?;
    let length = kkt.length;
    // As a position closure row's multiplier: the stiffest joint's k over ℓ.
    let sigma = kkt.row_scale.iter().map(|r| 1.0 / r).fold(f64::MIN_POSITIVE, f64::max) / length;
    let x0 = kkt.state(&start.q, &start.multipliers);
    let mut problem = ContactKkt {
        kkt,
        touching: start.touching,
        frames: Frames::new(m),
        inner: Vec::new(),
        sigma,
        jets: Vec::new(),
    };
    let mut x = problem.state(&x0);
    let mut lambda = 0.0;
    let mut step = FIRST_STEP;
    let mut previous: Option<(f64, Vec<f64>)> = None;
    let (mut steps, mut iterations, mut residual) = (0, 0, 0.0);
    let mut touched = start.touched;
    let stalled = |lambda: f64, steps: usize, residual: f64, cause: String| Error::ContinuationStalled {
        cause,
        rounding: false,
        solver: "mechanism equilibrium with contact",
        load_fraction: lambda,
        steps,
        residual,
        unit: "relative",
    };
    // The touching set at the start (a pair touching with no load).
    settle_events(&mut problem, &mut x, 0.0, settings, all, &mut touched, &mut iterations)?;
    while lambda < 1.0 {
        if steps >= MAX_STEPS {
            return Err(stalled(lambda, steps, residual, format!("{MAX_STEPS} steps")));
        }
        let next = (lambda + step).min(1.0);
        let guess: Vec<f64> = match &previous {
            Some((l0, x0)) if x0.len() == x.len() && lambda > *l0 => {
                x.iter().zip(x0).map(|(a, b)| a + (a - b) * (next - lambda) / (lambda - l0)).collect()
            }
            _ => x.clone(),
        };
        let trial = newton(&mut problem, &guess, next, settings)
            .and_then(|(y, r)| {
                if problem.distance(&x, &y) > settings.max_rotation_per_step {
                    Err(stalled(next, steps, r.residual, "a step turned too far".into()))
                } else {
                    Ok((y, r))
                }
            })
            .and_then(|(y, r)| Ok((event(&mut problem, &y, next, all)?, y, r)));
        let (found, y, report) = match trial {
            Ok(t) => t,
            Err(e) => {
                step *= 0.5;
                if step < SMALLEST_STEP {
                    return Err(match e {
                        Error::ContinuationStalled { .. } => e,
                        other => stalled(lambda, steps, residual, other.to_string()),
                    });
                }
                continue;
            }
        };
        iterations += report.iterations;
        let Some(found) = found else {
            previous = Some((lambda, std::mem::replace(&mut x, y)));
            lambda = next;
            residual = report.residual;
            steps += 1;
            step = (step * 1.5).min(LARGEST_STEP);
            continue;
        };
        // Bisect for where the first event happens; change the set there.
        let (mut lo, mut hi, mut first) = (lambda, next, found);
        while hi - lo > EVENT_RESOLUTION {
            let mid = 0.5 * (lo + hi);
            match newton(&mut problem, &x, mid, settings) {
                Ok((y, r)) => {
                    iterations += r.iterations;
                    match event(&mut problem, &y, mid, all)? {
                        Some(e) => (hi, first) = (mid, e),
                        None => (lo, x) = (mid, y),
                    }
                }
                Err(_) => hi = mid,
            }
        }
        problem.read(&x);
        problem.touching = changed(m, &problem.touching, first, hi)?;
        remember(&mut touched, first);
        x = problem.state(&x);
        settle_events(&mut problem, &mut x, lo, settings, all, &mut touched, &mut iterations)?;
        lambda = lo;
        previous = None;
        steps += 1;
        step = FIRST_STEP.min(step);
    }
    let n = m.dof();
    let q = x[..n].to_vec();
    let multipliers = problem.kkt.multipliers(&x[..problem.inner_dim()]);
    let size = problem.dim();
    let mut r = vec![0.0; size];
    problem.evaluate(&x, 1.0, &mut r, None, None)?;
    let energy = problem.kkt.work.frames.joints.iter().map(|s| s.energy).sum::<f64>() + 0.0;
    let contacts = report(&problem, &q, &touched)?;
    let loads = problem.kkt.to.clone();
    problem.read(&x);
    let next = Touched {
        q: q.clone(),
        multipliers: multipliers.clone(),
        loads: loads.clone(),
        touching: problem.touching.clone(),
        touched: touched.clone(),
    };
    let _ = problem.kkt.release();
    let solution = Solution {
        q,
        multipliers,
        loads,
        energy,
        stable: true,
        limit: None,
        residual,
        load_steps: steps,
        iterations,
        contacts,
    };
    Ok((solution, next))
}

/// Solves at `lambda` with the set as it stands, then changes it while an
/// event holds there (at most [`MAX_CHANGES_AT_ONCE`] times).
fn settle_events<D: Statics>(
    problem: &mut ContactKkt<D>,
    x: &mut Vec<f64>,
    lambda: f64,
    settings: &Settings,
    all: &[Pair],
    touched: &mut Vec<Pair>,
    iterations: &mut usize,
) -> Result<()> {
    let m = problem.kkt.mechanism;
    for _ in 0..=MAX_CHANGES_AT_ONCE {
        let (y, r) = newton(problem, x, lambda, settings).map_err(|e| unsettled(m, &problem.touching, lambda, &e))?;
        *iterations += r.iterations;
        *x = y;
        match event(problem, x, lambda, all)? {
            None => return Ok(()),
            Some(e) => {
                problem.read(x);
                problem.touching = changed(m, &problem.touching, e, lambda)?;
                remember(touched, e);
                *x = problem.state(x);
            }
        }
    }
    Err(Error::ContinuationStalled {
        cause: format!("the contacts changed more than {MAX_CHANGES_AT_ONCE} times at one load"),
        rounding: false,
        solver: "mechanism equilibrium with contact",
        load_fraction: lambda,
        steps: 0,
        residual: 0.0,
        unit: "relative",
    })
}

/// The error of a set of contacts that Newton could not solve at the load
/// where it changed, naming them: most often a flexure touching a sharp
/// edge or corner (a box's), where the gap has a kink and no point of the
/// flexure is tangent to the geom.
fn unsettled<D: Statics>(m: &Mechanism<D>, touching: &[Touching], lambda: f64, e: &Error) -> Error {
    let names: Vec<String> = touching.iter().map(|t| named(m, &t.pair)).collect();
    Error::ContinuationStalled {
        cause: format!(
            "the contacts of {} could not be solved where they changed ({e}); a flexure touching a sharp edge or corner of a box, where no point of it is tangent to the geom, is not solved: round the edge (a capsule) or give the flexure a thickness",
            names.join(" and ")
        ),
        rounding: false,
        solver: "mechanism equilibrium with contact",
        load_fraction: lambda,
        steps: 0,
        residual: match e {
            Error::NoConvergence { residual, .. } => *residual,
            _ => f64::NAN,
        },
        unit: "relative",
    }
}

/// Adds a new contact's pair to `touched` (the pairs an answer reports).
fn remember(touched: &mut Vec<Pair>, event: Event) {
    if let Event::Touch(pair, _) = event
        && !touched.contains(&pair)
    {
        touched.push(pair);
    }
}

/// The contacts of the solution `q` (last evaluated by `problem`): each
/// touching one, then each pair in `touched` that no longer touches.
fn report<D: Statics>(problem: &ContactKkt<D>, q: &[f64], touched: &[Pair]) -> Result<Vec<Contact>> {
    let m = problem.kkt.mechanism;
    let vector = |v: &D::Vector| (0..D::POINT_DIM).map(|i| v[i]).collect::<Vec<f64>>();
    let point = |p: &D::Point| vector(&D::position(p));
    // (the geom touched, the flexure or the body whose circle or sphere touches it).
    let named_part = |pair: &Pair| match pair.part {
        Toucher::Flexure(j) => (m.geoms[pair.geom].name.clone(), Some(m.joints[j].name.clone()), None),
        Toucher::Geom(_) => match ball_and_other(m, pair) {
            Ok((round, flat, _)) => (flat.name.clone(), None, Some(m.bodies[round.body].name.clone())),
            Err(_) => (m.geoms[pair.geom].name.clone(), None, None),
        },
    };
    let mut out = Vec::new();
    for (t, jet) in problem.touching.iter().zip(&problem.jets) {
        let (geom, flexure, body) = named_part(&t.pair);
        out.push(Contact {
            geom,
            flexure,
            body,
            s: t.s(),
            point: point(&jet.point),
            normal: vector(&jet.normal),
            normal_force: t.force.max(0.0),
            friction_force: vec![0.0; D::POINT_DIM],
            gap: jet.gap,
            state: ContactMode::Slip,
            pair: t.pair,
        });
    }
    for pair in touched.iter().filter(|p| !problem.touching.iter().any(|t| t.pair == **p)) {
        let low = minima(m, q, &problem.frames.bodies, pair)?
            .into_iter()
            .min_by(|a, b| a.gap.total_cmp(&b.gap))
            .expect("at least one least");
        let (geom, flexure, body) = named_part(pair);
        out.push(Contact {
            geom,
            flexure,
            body,
            s: low.s,
            point: point(&low.point),
            normal: vector(&low.normal),
            normal_force: 0.0,
            friction_force: vec![0.0; D::POINT_DIM],
            gap: low.gap,
            state: ContactMode::Open,
            pair: *pair,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The problem's Jacobian and load derivative against central
    /// differences of its residual, with an inner contact on a post and a
    /// tip contact on a floor, at a bent state with forces.
    #[test]
    fn the_jacobian_matches_differences() {
        let text = "[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\norder = 4\n\
                    [[force]]\nbody = \"tip\"\nat = [0.0, 0.0]\nforce = [0.0, -3.0]\n\
                    [[geom]]\nname = \"post\"\nbody = \"ground\"\nshape = \"circle\"\norigin = [0.55, -0.3]\nradius = 0.25\n\
                    [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.5]\nnormal = [0.0, 1.0]\n";
        let m = crate::mechanism::file::from_toml(text).unwrap();
        let settings = Settings::default();
        let mut work = Workspace::new(&m);
        work.touching = true;
        let to = m.loads();
        let zero = crate::mechanism::Planar::zero(&to);
        let kkt = Kkt::fitted(&m, &zero, &to, &settings, Buffers::Borrowed(&mut work)).unwrap();
        let mut problem = ContactKkt {
            kkt,
            touching: Vec::new(),
            frames: Frames::new(&m),
            inner: Vec::new(),
            sigma: 1.0,
            jets: Vec::new(),
        };
        let all = pairs(&m);
        problem.touching = vec![
            Touching { pair: all[0], place: Place::Inner, force: 0.7, at: 0.6, length: 1.0 },
            Touching { pair: all[1], place: Place::End(1.0), force: 0.3, at: 1.0, length: 1.0 },
        ];
        let q = [-0.4, 0.1, -0.05, 0.02];
        let x = problem.state(&q);
        crate::solver::assert_derivatives(&mut problem, &x, 0.7);
    }
}
