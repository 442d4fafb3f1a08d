//! The step loop and its control: each step tried, accepted or refused by
//! its error estimate, rotation and closures; the next length chosen; the
//! samples and jumps landed on; the budgets that end a run.

use super::local_error::estimate;
use super::newton::{self, REUSE, stages};
use super::progress;
use super::radau::Radau;
use super::start::consistent_start;
use super::trajectory::{Trajectory, record};
use super::work::Work;
use super::{MotionSettings, fatal, largest};
use crate::dynamics::System;
use crate::error::{Error, Result};

/// Every this many accepted steps, the run checks its pace: if the time
/// left would take more than [`PACE_MARGIN`] times the steps left in the
/// budget at the mean step of the last this many, it stops there, with the
/// samples reached, rather than spend the budget to fail at its end.
pub const PACE_WINDOW: usize = 1000;

/// See [`PACE_WINDOW`].
pub const PACE_MARGIN: f64 = 10.0;

/// Why a step was not taken.
pub(super) enum Refusal {
    /// Its error estimate (scaled, > 1) or rotation asks for a step of this ratio.
    Shorter(f64, String),
    /// The state could not be evaluated: halve the step.
    Failed(String),
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
    let (n, m) = (system.dim(), system.closures());
    let rk = Radau::new();
    let mut w = Work::new(n, m);
    let times = settings.times();
    let duration = settings.duration;
    let (mut q, mut v) = (q0.to_vec(), v0.to_vec());
    let massless = consistent_start(system, &mut q, &v, settings)?;
    let (mut q1, mut v1) = (q.clone(), v.clone());
    let mut t = 0.0;
    run.violation = violation(system, &q, &mut w)?;
    record(system, run, 0.0, &q, &v)?;
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
    for &target in &times[1..] {
        while t < target {
            // The next jump of the loads up to this sample, landed on like a sample.
            let jump = jumps.iter().copied().find(|&j| j > t && j <= target);
            let stop = jump.unwrap_or(target);
            let stalled = |cause: &str, h: f64, run: &Trajectory| Error::IntegrationStalled {
                cause: cause.to_string(),
                time: t,
                duration,
                steps: run.steps,
                rejected: run.rejected,
                step: h,
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
            let mut step = h.min(settings.max_step);
            let landing = t + 1.01 * step >= stop && stop - t <= settings.max_step;
            if landing {
                step = stop - t;
            }
            if step < 1e-14 * t.max(settings.every) || t + step == t {
                return Err(stalled(&format!("{cause}; the step fell to rounding's level"), step, run));
            }
            // Whether the last state passed to `dynamics` is this step's start.
            let mut at_start = false;
            if !fresh {
                // The step's start: M, f and G for the error estimate.
                system.dynamics(&q, &v, t, &mut w.m0, &mut w.f0)?;
                if m > 0 {
                    system.closure(&q, &mut w.closure, &mut w.g_start)?;
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
                }
                w.factored = f64::NAN;
                stale = false;
                current = true;
            }
            let attempt = attempt(
                system,
                &rk,
                &mut w,
                (t, step, duration, jump.filter(|_| landing)),
                (&q, &v),
                settings,
                &mut eta,
                (last_rejected || run.steps == 0, run.steps < 2, m > 0 || massless),
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
                        match violation(system, &q1, &mut w) {
                            Ok(c) if c.is_finite() => {
                                run.violation = run.violation.max(c);
                                // Accept; next step from the controller, within the rotation bound.
                                t = if landing { stop } else { t + step };
                                std::mem::swap(&mut q, &mut q1);
                                std::mem::swap(&mut v, &mut v1);
                                w.prev.copy_from_slice(&w.x);
                                w.prev_h = step;
                                run.steps += 1;
                                progress::report(t / duration);
                                fresh = false;
                                // Past a jump the loads, and so the tangents, are new.
                                stale = w.theta > REUSE || (landing && jump.is_some());
                                let mut next = step * ratio.min(if last_rejected { 1.0 } else { 5.0 });
                                if turn > 0.0 {
                                    next = next.min(0.9 * step * settings.max_rotation_per_step / turn);
                                }
                                h = if landing && next >= step { next.max(h) } else { next };
                                last_rejected = false;
                                rejections = 0;
                                None
                            }
                            Ok(c) => Some(Refusal::Failed(format!("a closure violation of {c}"))),
                            Err(e) if fatal(&e) => return Err(e),
                            Err(e) => Some(Refusal::Failed(e.to_string())),
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
        record(system, run, target, &q, &v)?;
    }
    Ok(())
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
    // Error scales over the step's two ends.
    for r in 0..n {
        w.sq[r] = atol + rtol * q0[r].abs().max(w.qs[2 * n + r].abs());
        w.sv[r] = atol + rtol * v0[r].abs().max(w.vs[2 * n + r].abs());
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
