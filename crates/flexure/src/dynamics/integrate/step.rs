//! The step loop and its control: each step tried, accepted or refused by
//! its error estimate, rotation and closures; the next length chosen; the
//! samples and jumps landed on; the budgets that end a run.

use super::event::{self, MAX_AIMS, PROJECTION_STEP, Pending, Verdict};
use super::local_error::estimate;
use super::newton::{self, REUSE, stages};
use super::progress;
use super::radau::Radau;
use super::start::consistent_start;
use super::trajectory::{Trajectory, record};
use super::work::Work;
use super::{MotionSettings, fatal, largest};
use crate::dynamics::System;
use crate::dynamics::system::ErrorWeights;
use crate::error::{Error, Result};

/// Every this many accepted steps, the run checks its pace: if the time
/// left would take more than [`PACE_MARGIN`] times the steps left in the
/// budget at the mean step of the last this many, it stops there, with the
/// samples reached, rather than spend the budget to fail at its end.
pub const PACE_WINDOW: usize = 1000;

/// See [`PACE_WINDOW`].
pub const PACE_MARGIN: f64 = 10.0;

/// The most switches at one instant (within $10^{-12}$ of its time
/// relative to the larger of it and the sample interval, as a jump's
/// bracket): [`MAX_SWITCHES_AT_ONCE`] plus two per guard (the guards at
/// the run's start). A set of
/// contacts that settles switches each guard once or twice there; one
/// that keeps switching (each new set's guards past their bands at once)
/// has no consistent set the integrator finds, and the run stops saying
/// so rather than spend its step budget on switches that take no time.
pub const MAX_SWITCHES_AT_ONCE: usize = 16;

/// Switches at one instant: its time, how many so far, and how many it
/// may take.
struct Burst {
    t: f64,
    count: usize,
    most: usize,
}

impl Burst {
    /// Counts a switch at `t`, a new instant if farther than `close` from
    /// the last; the switches already made there if this one would pass
    /// the bound.
    fn past_bound(&mut self, t: f64, close: f64) -> Option<usize> {
        if (t - self.t).abs() > close {
            (self.t, self.count) = (t, 0);
        }
        self.count += 1;
        (self.count > self.most).then_some(self.count - 1)
    }
}

/// Why a step was not taken.
pub(super) enum Refusal {
    /// Its error estimate (scaled, > 1) or rotation asks for a step of this ratio.
    Shorter(f64, String),
    /// The state could not be evaluated: halve the step.
    Failed(String),
    /// It passed over an event: the next step aims at it.
    Event,
    /// Newton diverged or did not converge: retry with fresh matrix data
    /// if they were kept, else with the stages' own masses if the matrix
    /// did not yet take them, else halve the step.
    Newton(String),
}

/// Largest $\lvert c_k(q)\rvert$.
fn violation<S: System + ?Sized>(system: &mut S, q: &[f64], w: &mut Work) -> Result<f64> {
    if w.m == 0 {
        return Ok(0.0);
    }
    system.closure(q, &mut w.closure, &mut w.jac)?;
    Ok(largest(&w.closure))
}

/// The steps of [`integrate_kept`](super::integrate_kept), from the consistent start, recording into `run`.
pub(super) fn advance<S: System + ?Sized>(
    system: &mut S,
    q0: &[f64],
    v0: &[f64],
    settings: &MotionSettings,
    run: &mut Trajectory,
) -> Result<()> {
    let (n, mut m) = (system.dim(), system.closures());
    let rk = Radau::new();
    let mut w = Work::new(n, m);
    w.velocity = system.velocity_closures();
    weigh(system, &mut w)?;
    let times = settings.times();
    let duration = settings.duration;
    let (mut q, mut v) = (q0.to_vec(), v0.to_vec());
    let massless = consistent_start(system, &mut q, &v, settings)?;
    let (mut q1, mut v1) = (q.clone(), v.clone());
    let mut t = 0.0;
    run.violation = violation(system, &q, &mut w)?;
    record(system, run, 0.0, &q, &v, None)?;
    // The guards at the last state accepted, at a step's end, and the event aimed at.
    let (mut g_now, mut g_end) = (Vec::new(), Vec::new());
    event::entered(system, 0.0, &q, &v, &mut g_now)?;
    let mut pending: Option<Pending> = None;
    // Accepted steps since the start or the last switch, and the multipliers
    // of the last step accepted (none at the start or after a switch).
    let mut since_switch = 0;
    let mut multipliers: Option<Vec<f64>> = None;
    // A first step well inside the sample interval; the controller grows it
    // by up to 5 per step.
    let mut h = 1e-2 * settings.every.min(settings.max_step).min(duration);
    let mut eta = 1.0;
    let mut fresh = false;
    let mut last_rejected = false;
    let mut rejections = 0;
    let mut cause = String::new();
    // The Newton matrix's data must be evaluated anew; it was at this step's start.
    let (mut stale, mut current) = (true, false);
    let jumps = system.jumps();
    let budget = settings.step_budget();
    // The time and accepted steps at the start of the pace window (PACE_WINDOW).
    let (mut window_start, mut window_steps) = (0.0, 0);
    // No instant yet: the first switch starts one.
    let mut burst = Burst { t: f64::NEG_INFINITY, count: 0, most: MAX_SWITCHES_AT_ONCE + 2 * system.guard_count() };
    for &target in &times[1..] {
        while t < target {
            // The next jump of the loads up to this sample, landed on like a
            // sample, and the event aimed at, before either.
            let jump = jumps.iter().copied().find(|&j| j > t && j <= target);
            let aim = pending.as_ref().map(|p| p.aim(t, &g_now));
            let stop = aim.into_iter().chain(jump).fold(target, f64::min);
            let jump = jump.filter(|&j| j == stop);
            let stalled = move |cause: &str, h: f64, run: &Trajectory| Error::IntegrationStalled {
                cause: cause.to_string(),
                time: t,
                duration,
                steps: run.steps,
                rejected: run.rejected,
                step: h,
            };
            let out_of_aims = move |step: f64, run: &Trajectory| {
                stalled(&format!("an event was not landed on in {MAX_AIMS} aimed steps"), step, run)
            };
            let close = 1e-12 * t.abs().max(settings.every);
            let unsettled = move |count: usize, run: &Trajectory| {
                stalled(
                    &format!(
                        "the contacts or modes switched {count} times at one instant without time advancing: no set \
                         of them was found whose guards all hold there (a release that is inconsistent, or guards \
                         that disagree at rounding's level)"
                    ),
                    0.0,
                    run,
                )
            };
            if run.steps + run.rejected >= budget {
                // Many short steps that each passed or nearly passed: the
                // tolerance asks to resolve motion that fast, and lightly
                // damped stiff modes are what usually moves that fast.
                return Err(stalled(
                    &format!(
                        "{cause}; its limit of {} steps was reached, the steps near {h:.1e} s resolving \
                         motion that fast to the tolerance (lightly damped stiff modes, usually: material \
                         damping on the flexures lets the integrator step over them)",
                        budget
                    ),
                    h,
                    run,
                ));
            }
            if run.steps >= window_steps + PACE_WINDOW && run.rejected + run.steps < budget {
                let pace = (t - window_start) / (run.steps - window_steps) as f64;
                let needed = (duration - t) / pace;
                let left = (budget - run.steps - run.rejected) as f64;
                if needed > PACE_MARGIN * left {
                    return Err(stalled(
                        &format!(
                            "at the pace of the last {PACE_WINDOW} steps ({pace:.3e} s each) the {:.6e} s left would take \
                             about {needed:.2e} steps, more than {PACE_MARGIN} times the {left:.0} left of its budget of \
                             {budget} steps; stopped early rather than at the budget's end (a larger budget, a looser \
                             tolerance, damping on the flexures or a shorter duration)",
                            duration - t
                        ),
                        h,
                        run,
                    ));
                }
                (window_start, window_steps) = (t, run.steps);
            }
            if rejections > settings.max_rejections {
                return Err(stalled(&format!("{cause}; {rejections} successive rejections"), h, run));
            }
            if aim.is_none_or(|a| a > stop) && stop - t <= 1e-13 * t.abs().max(settings.every) {
                // A sample or jump within rounding of where the run is (a
                // jump at 0.6 s, the sample at 12 × 0.05 s): it is here.
                t = stop;
                continue;
            }
            let mut step = h.min(settings.max_step);
            let landing = t + 1.01 * step >= stop && stop - t <= settings.max_step;
            if landing {
                step = stop - t;
            }
            if step < 1e-14 * t.max(settings.every) || t + step == t {
                // Aimed at an event closer than a step can be: it is here,
                // as a jump's (below).
                if let Some(p) = pending.as_ref().filter(|_| landing && aim == Some(stop)) {
                    let ks = event::past_bands(&p.g_hi);
                    if let Some(count) = burst.past_bound(t, close) {
                        return Err(unsettled(count, run));
                    }
                    enter(system, &ks, t, (&mut q, &mut v), &mut w, settings, &mut g_now)?;
                    (m, pending, multipliers, since_switch, stale, fresh) = (w.m, None, None, 0, true, false);
                    continue;
                }
                return Err(stalled(&format!("{cause}; the step fell to rounding's level"), step, run));
            }
            // Whether the last state passed to `dynamics` is this step's start.
            let mut at_start = false;
            if !fresh {
                // The step's start: M, f and G for the error estimate.
                system.dynamics(&q, &v, t, &mut w.m0, &mut w.f0)?;
                if m > 0 {
                    system.closure(&q, &mut w.closure, &mut w.g_start)?;
                    system.closure_forces(&q, &v, &w.g_start, &mut w.w_start)?;
                    // A velocity row's violation is its rate, G q̇.
                    for k in 0..m {
                        w.violation[k] = match w.velocity[k] {
                            true => (0..n).map(|c| w.g_start[c * m + k] * v[c]).sum(),
                            false => w.closure[k],
                        };
                    }
                }
                fresh = true;
                current = false;
                at_start = true;
            }
            if stale {
                // The tangents for the Newton matrix, at the state last
                // passed to `dynamics`: after a rejected attempt that was a stage.
                if !at_start {
                    system.dynamics(&q, &v, t, &mut w.mass, &mut w.force)?;
                }
                system.tangent(&q, &v, t, &mut w.k0, &mut w.d0)?;
                w.mj.copy_from_slice(&w.m0);
                if m > 0 {
                    system.closure(&q, &mut w.closure, &mut w.g0)?;
                    system.closure_forces(&q, &v, &w.g0, &mut w.w0)?;
                }
                w.factored = f64::NAN;
                stale = false;
                current = true;
            }
            // Aimed at an event, a step may be very short: it carries its
            // start's closure violation rather than correct it (module docs of `newton`).
            w.carry = pending.is_some();
            let attempt = attempt(
                system,
                &rk,
                &mut w,
                (t, step, duration, jump.filter(|_| landing)),
                (&q, &v),
                settings,
                &mut eta,
                (last_rejected || run.steps == 0, since_switch < 2, m > 0 || massless),
            );
            let refusal = match attempt {
                Err(e) => return Err(e),
                Ok(Ok(ratio)) => {
                    let (qn, vn) = (&w.qs[2 * n..], &w.vs[2 * n..]);
                    let turn = system.distance(&q, qn);
                    if turn > settings.max_rotation_per_step || turn.is_nan() {
                        let r = 0.9 * settings.max_rotation_per_step / turn;
                        Some(Refusal::Shorter(
                            if r.is_nan() { 0.5 } else { r.min(0.5) },
                            format!("a step turned {turn:.3e} rad"),
                        ))
                    } else {
                        q1.copy_from_slice(qn);
                        v1.copy_from_slice(vn);
                        // Aimed at an event, the step is short: its guards take
                        // the multipliers of the equations themselves.
                        let consistent = match pending.is_some() && m > 0 {
                            true => event::consistent_multipliers(system, t + step, &q1, &v1)?,
                            false => None,
                        };
                        let lambda = consistent.as_deref().unwrap_or(&w.x[3 * n + 2 * m..3 * n + 3 * m]);
                        let mut verdict = event::guards(system, &q1, &v1, Some(lambda), &mut g_end)
                            .map(|()| event::verdict(&g_now, &g_end, pending.as_ref()));
                        // Clear of every guard, yet through a geom (which no guard sees): refused, shortened.
                        if pending.is_none()
                            && matches!(verdict, Ok(Verdict::Clear))
                            && let Some(why) = system.passed(&q1)?
                        {
                            verdict = Err(Error::Singular { what: why });
                        }
                        // An event seen through the step's own multipliers is
                        // checked with the equations' own, which the steps
                        // aimed at it read: one that only the step's own see
                        // (they err by its start's closure violation over h²)
                        // is one those steps never find, and they shrank to
                        // rounding (a fast grasp with friction stalled so).
                        // One that both see is aimed at as before.
                        if matches!(verdict, Ok(Verdict::Overshot))
                            && consistent.is_none()
                            && m > 0
                            && let Some(lambda) = event::consistent_multipliers(system, t + step, &q1, &v1)?
                        {
                            let mut g_check = Vec::new();
                            event::guards(system, &q1, &v1, Some(&lambda), &mut g_check)?;
                            match event::verdict(&g_now, &g_check, pending.as_ref()) {
                                Verdict::Overshot => {
                                    let own = &w.x[3 * n + 2 * m..3 * n + 3 * m];
                                    event::guards(system, &q1, &v1, Some(own), &mut g_end)?;
                                }
                                seen => (g_end, verdict) = (g_check, Ok(seen)),
                            }
                        }
                        // Aimed at the event and short of it, a step is not
                        // taken: it is the bracket's near end (module docs of
                        // `event`); aimed at the far end itself and clear, it
                        // is (the event was not there).
                        let aimed = landing && aim == Some(stop);
                        let at_far_end = pending.as_ref().is_some_and(|p| p.far);
                        // A bracket narrower than the tolerance of the step
                        // (or rounding), its near end past the last state
                        // accepted: a step that overshoots to its far end
                        // lands there, on the guards it finds past their
                        // bands; one short of it aims at the far end next. A
                        // guard that jumps (a slide in space whose friction
                        // turns over) has no crossing to land on within its
                        // band; landing there, the step's own end is as
                        // accurate as any.
                        let mut narrow_short = false;
                        if let Some(p) = pending.as_ref()
                            && let (t_near, _) = p.near(t, &g_now)
                            && let Ok(found) = &verdict
                            && let narrow = close.max(settings.tolerance * step)
                            && t_near > t
                        {
                            match found {
                                Verdict::Overshot if t + step > t_near && t + step - t_near <= narrow => {
                                    let ks = event::past_bands(&g_end);
                                    if !ks.is_empty() {
                                        verdict = Ok(Verdict::Landed(ks));
                                    }
                                }
                                Verdict::Clear if aimed && !at_far_end && p.t_hi - (t + step) <= narrow => {
                                    narrow_short = true;
                                }
                                _ => {}
                            }
                        }
                        let checked = match verdict {
                            Ok(Verdict::Overshot) => Err(None),
                            Ok(verdict) => violation(system, &q1, &mut w).map(|c| (c, verdict)).map_err(Some),
                            Err(e) => Err(Some(e)),
                        };
                        match checked {
                            Err(None) => {
                                // An event within the step: aim at it, from this step's start.
                                match pending.as_mut() {
                                    Some(p) => p.overshot(t, t + step, &g_end),
                                    None => pending = Some(Pending::new(t, t + step, &g_end)),
                                }
                                let p = pending.as_ref().expect("just set");
                                if p.aims > MAX_AIMS {
                                    return Err(out_of_aims(step, run));
                                }
                                if p.t_hi - t <= 1e-12 * t.abs().max(settings.every) {
                                    // The guards jump at the step's start (a load's jump):
                                    // the events are there.
                                    let ks = event::past_bands(&p.g_hi);
                                    if let Some(count) = burst.past_bound(t, close) {
                                        return Err(unsettled(count, run));
                                    }
                                    enter(system, &ks, t, (&mut q, &mut v), &mut w, settings, &mut g_now)?;
                                    (m, pending, multipliers, since_switch, stale, fresh) =
                                        (w.m, None, None, 0, true, false);
                                }
                                Some(Refusal::Event)
                            }
                            Ok((c, Verdict::Clear)) if c.is_finite() && aimed && !at_far_end => {
                                let p = pending.as_mut().expect("aimed at an event");
                                p.fell_short(t, Some((t + step, &g_end)));
                                p.far = narrow_short;
                                if p.aims > MAX_AIMS {
                                    return Err(out_of_aims(step, run));
                                }
                                Some(Refusal::Event)
                            }
                            Ok((c, verdict)) if c.is_finite() => {
                                run.violation = run.violation.max(c);
                                // Accept; next step from the controller, within the rotation bound.
                                t = if landing { stop } else { t + step };
                                std::mem::swap(&mut q, &mut q1);
                                std::mem::swap(&mut v, &mut v1);
                                // Not within an event's bracket: its guards stay those it was bracketed with.
                                if pending.is_none() {
                                    system.accepted(&q, &v)?;
                                }
                                w.prev.copy_from_slice(&w.x);
                                w.prev_h = step;
                                run.steps += 1;
                                since_switch += 1;
                                progress::report(t / duration);
                                fresh = false;
                                multipliers = Some(w.x[3 * n + 2 * m..3 * n + 3 * m].to_vec());
                                std::mem::swap(&mut g_now, &mut g_end);
                                // Past a jump the loads, and so the tangents, are new.
                                stale = w.theta > REUSE || (landing && jump.is_some());
                                let mut next = step * ratio.min(if last_rejected { 1.0 } else { 5.0 });
                                if turn > 0.0 {
                                    next = next.min(0.9 * step * settings.max_rotation_per_step / turn);
                                }
                                h = if landing && next >= step { next.max(h) } else { next };
                                last_rejected = false;
                                rejections = 0;
                                match verdict {
                                    Verdict::Landed(ks) => {
                                        // The mode changes here; the next steps start afresh.
                                        if let Some(count) = burst.past_bound(t, close) {
                                            return Err(unsettled(count, run));
                                        }
                                        enter(system, &ks, t, (&mut q, &mut v), &mut w, settings, &mut g_now)?;
                                        (m, pending, multipliers, since_switch, stale) = (w.m, None, None, 0, true);
                                    }
                                    // Aimed at the far end and clear there: the event was not there.
                                    Verdict::Clear | Verdict::Overshot if at_far_end => pending = None,
                                    Verdict::Clear | Verdict::Overshot => {
                                        if let Some(p) = pending.as_mut() {
                                            p.fell_short(t, None);
                                        }
                                    }
                                }
                                None
                            }
                            Ok((c, _)) => Some(Refusal::Failed(format!("a closure violation of {c}"))),
                            Err(Some(e)) if fatal(&e) => return Err(e),
                            Err(Some(e)) => Some(Refusal::Failed(e.to_string())),
                        }
                    }
                }
                Ok(Err(r)) => Some(r),
            };
            if let Some(refusal) = refusal {
                let ratio = match refusal {
                    Refusal::Shorter(ratio, why) => {
                        cause = why;
                        ratio
                    }
                    Refusal::Failed(why) => {
                        cause = why;
                        0.5
                    }
                    // Aimed at the event next: the step that overshot was
                    // sound, its matrix too, and it is no failure in a row.
                    Refusal::Event => {
                        run.rejected += 1;
                        continue;
                    }
                    Refusal::Newton(why) => {
                        cause = why;
                        if !current {
                            // Kept data: retry with fresh.
                            1.0
                        } else if !w.staged {
                            // Fresh data at the step's start, yet no
                            // convergence: the mass matrix changes within
                            // the step by much of itself where inertia is
                            // small, which a shorter step does not cure.
                            // Retry (and go on) with the stages' own masses.
                            w.staged = true;
                            1.0
                        } else {
                            0.5
                        }
                    }
                };
                h = step * ratio;
                // RADAU5: a matrix kept from an earlier step is renewed.
                stale = !current;
                run.rejected += 1;
                rejections += 1;
                last_rejected = true;
            }
        }
        // Landed on a switch at the sample: the new set's multipliers, not none
        // (a contact just touched would read no push at rest).
        let fresh_multipliers = match (&multipliers, system.closures()) {
            (None, m) if m > 0 => event::consistent_multipliers(system, target, &q, &v)?,
            _ => None,
        };
        record(system, run, target, &q, &v, multipliers.as_deref().or(fresh_multipliers.as_deref()))?;
    }
    Ok(())
}

/// Enters the mode after the events of guards `ks` at time `t`: the
/// system switches, the buffers fit its closures, the state moves onto them
/// ([`event::project`]: an impact), and `g_now` takes the new guards, none
/// of which may be past its band.
fn enter<S: System + ?Sized>(
    system: &mut S,
    ks: &[usize],
    t: f64,
    (q, v): (&mut [f64], &mut [f64]),
    w: &mut Work,
    settings: &MotionSettings,
    g_now: &mut Vec<f64>,
) -> Result<()> {
    system.switch(ks, t, q, v)?;
    if system.closures() != w.m {
        let staged = w.staged;
        let (weights, groups) = (std::mem::take(&mut w.weights), std::mem::take(&mut w.groups));
        *w = Work::new(w.n, system.closures());
        (w.staged, w.weights, w.groups) = (staged, weights, groups);
    }
    w.velocity = system.velocity_closures();
    w.prev_h = 0.0;
    event::project(system, t, (q, v), PROJECTION_STEP * settings.every.min(settings.max_step))?;
    event::entered(system, t, q, v, g_now)?;
    match g_now.iter().find(|g| **g < -1.0 || g.is_nan()) {
        Some(g) => {
            Err(Error::Singular { what: format!("a guard {g:.3e} times past its band just after an event at {t} s") })
        }
        None => Ok(()),
    }
}

/// Tries one step of length `h` from $(q_0, \dot q_0)$ at $t_0$: on success
/// the new state is the last stage in `w.qs`, `w.vs`, and the value is the
/// ratio of the next step to this one proposed by the error estimate.
#[allow(clippy::too_many_arguments)]
fn attempt<S: System + ?Sized>(
    system: &mut S,
    rk: &Radau,
    w: &mut Work,
    (t0, h, duration, jump): (f64, f64, f64, Option<f64>),
    (q0, v0): (&[f64], &[f64]),
    settings: &MotionSettings,
    eta: &mut f64,
    (refine, start, index2): (bool, bool, bool),
) -> Result<std::result::Result<f64, Refusal>> {
    let n = w.n;
    let (rtol, atol) = (settings.tolerance, settings.absolute);
    // Velocities are index-2 variables of a constrained system, and so are
    // those of directions without inertia (derivatives of coordinates that
    // obey algebraic equations): their error is weighed by h (RADAU5's
    // scaling). Weighed as states, a massless direction's velocity, which
    // the stage equations leave accurate only to O(h^2), holds the step
    // down as its inertia grows from zero with the deflection (a spatial
    // flexure's: issue 39, finger3d stalled at 12 us). In the first two steps it
    // is not weighed at all: where a start off the quasi-static equilibrium
    // of a massless direction is projected onto it, that direction's
    // velocity jumps (by the jump over h), in the first step's estimate and
    // (through v0) the second's, and no step size would make it small. By
    // the third step the velocities derive from consistent positions.
    let vw = if start {
        0.0
    } else if index2 {
        h
    } else {
        1.0
    };
    for r in 0..n {
        w.sq[r] = atol + rtol * q0[r].abs();
        w.sv[r] = atol + rtol * v0[r].abs();
    }
    if let Err(refusal) = newton::solve(system, rk, w, (t0, h, duration, jump), (q0, v0), rtol, eta, vw)? {
        return Ok(Err(refusal));
    }
    stages(rk, w, h, q0, v0);
    // Error scales over the step's two ends, each coordinate's in its
    // group's weighted units (System::error_weights).
    w.group_q.fill(0.0);
    w.group_v.fill(0.0);
    for r in 0..n {
        let (g, weight) = (w.groups[r], w.weights[r]);
        w.group_q[g] = w.group_q[g].max(weight * q0[r].abs().max(w.qs[2 * n + r].abs()));
        w.group_v[g] = w.group_v[g].max(weight * v0[r].abs().max(w.vs[2 * n + r].abs()));
    }
    for r in 0..n {
        let (g, weight) = (w.groups[r], w.weights[r]);
        w.sq[r] = (atol + rtol * w.group_q[g]) / weight;
        w.sv[r] = (atol + rtol * w.group_v[g]) / weight;
    }
    let err = estimate(system, rk, w, t0, h, q0, v0, vw, false)?;
    let err = match err {
        Some(e) if e >= 1.0 && refine => estimate(system, rk, w, t0, h, q0, v0, vw, true)?,
        other => other,
    };
    let Some(err) = err else {
        return Ok(Err(Refusal::Failed(
            "the error estimate's matrix is singular or its state cannot be evaluated".into(),
        )));
    };
    let ratio = (0.9 / err.powf(0.25)).clamp(0.125, 5.0);
    if err > 1.0 {
        Ok(Err(Refusal::Shorter(ratio.min(0.9), format!("a local error of {err:.3e} times the tolerance"))))
    } else {
        Ok(Ok(ratio))
    }
}

/// The system's error weights into `w`, checked, with its groups numbered
/// from 0 in their order of first appearance.
fn weigh<S: System + ?Sized>(system: &S, w: &mut Work) -> Result<()> {
    let ErrorWeights { group, weight } = system.error_weights();
    let n = w.n;
    if group.len() != n || weight.len() != n {
        return Err(Error::invalid(
            "error_weights",
            format!("{} groups and {} weights", group.len(), weight.len()),
            "must give one group and one weight per coordinate",
        ));
    }
    if let Some(k) = (0..n).find(|&k| !(weight[k] > 0.0 && weight[k] <= 1.0)) {
        return Err(Error::invalid(
            "error_weights",
            format!("{} at coordinate {k}", weight[k]),
            "must each be greater than 0 and at most 1",
        ));
    }
    let mut labels: Vec<usize> = Vec::new();
    for (r, label) in group.iter().enumerate() {
        w.groups[r] = match labels.iter().position(|l| l == label) {
            Some(g) => g,
            None => {
                labels.push(*label);
                labels.len() - 1
            }
        };
    }
    w.weights = weight;
    Ok(())
}
