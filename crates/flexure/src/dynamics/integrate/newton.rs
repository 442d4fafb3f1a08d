//! The stage equations' simplified Newton method: the Newton matrix built
//! from kept data and factored once per step length (or, once the run has
//! needed it, with each stage's own mass matrix, factored at every
//! iteration), its start from the last step's collocation polynomial, and
//! RADAU5's stopping test.
//!
//! A step aimed at an event ([`Work::carry`]) holds each closure at its
//! start's violation, $c(Q_i) = c(q_0)$ (a velocity row at its start's
//! rate, $G_k\dot Q_i = G_k\dot q_0$), rather than at zero: aimed steps can
//! be very short, and correcting a violation $\epsilon$ within a step $h$
//! moves the velocities by $\epsilon/h$, which on a step of $10^{-11}$ s from
//! a violation of $10^{-16}$ m is a velocity error of $10^{-5}$ m/s. The steps
//! after the event correct it.

use super::fatal;
use super::norm::{scaled_dot, scaled_norm};
use super::radau::Radau;
use super::step::Refusal;
use super::work::Work;
use crate::dynamics::System;
use crate::error::{Error, Result};
use crate::linalg;
use crate::solver::interrupted;

/// Simplified Newton iterations per step before the step is retried shorter.
const NEWTON_ITERATIONS: usize = 7;

/// Newton increments (scaled, as fractions of the tolerance) that stop
/// shrinking below this are rounding's level, not divergence: the stage
/// solve is taken as converged there.
const NEWTON_FLOOR: f64 = 1e-2;

/// The Newton matrix's data are kept for the next step when the last
/// Newton contraction was at most this (RADAU5's `THET`, at the value its
/// authors advise for costly Jacobians); its factors while the step stays.
pub(super) const REUSE: f64 = 0.1;

/// Solves the stage equations of a step of length `h` from $(q_0, \dot q_0)$
/// at $t_0$ by the simplified Newton method, leaving the stage accelerations
/// and multipliers in `w.x` and the last contraction in `w.theta`; `eta` is
/// RADAU5's estimate of the contraction, kept over steps. The error scales
/// `w.sq`, `w.sv` must be set, and `vw` weighs the velocities in the norm.
#[allow(clippy::too_many_arguments)]
pub(super) fn solve<S: System + ?Sized>(
    system: &mut S,
    rk: &Radau,
    w: &mut Work,
    (t0, h, duration, jump): (f64, f64, f64, Option<f64>),
    (q0, v0): (&[f64], &[f64]),
    rtol: f64,
    eta: &mut f64,
    vw: f64,
) -> Result<std::result::Result<(), Refusal>> {
    // A step that ends on a load's jump sees the load just before it.
    let stage_time = |i: usize| match jump {
        Some(j) => (t0 + rk.c[i] * h).min(j.next_down()),
        None => t0 + rk.c[i] * h,
    };
    let (n, m) = (w.n, w.m);
    let big = 3 * (n + m);
    // A staged matrix is factored at each iteration, with the stages' masses.
    if !w.staged && w.factored != h && !factor(rk, w, h) {
        return Ok(Err(Refusal::Failed(
            "the Newton matrix is singular (a direction with neither mass nor stiffness, or dependent closures)".into(),
        )));
    }
    guess(rk, w, h);
    // Newton's stopping test (RADAU5): the estimated distance to the
    // solution at most kappa of the tolerance, above rounding.
    let kappa = (10.0 * f64::EPSILON / rtol).max(0.03f64.min(rtol.sqrt()));
    let mut previous = 0.0;
    let mut converged = false;
    w.theta = 0.0;
    for iteration in 0..NEWTON_ITERATIONS {
        if interrupted() {
            return Err(Error::InterruptedAt { time: t0, duration });
        }
        stages(rk, w, h, q0, v0);
        for i in 0..3 {
            let (qi, vi) = (&w.qs[i * n..(i + 1) * n], &w.vs[i * n..(i + 1) * n]);
            let evaluated = system
                .dynamics(qi, vi, stage_time(i), &mut w.mass, &mut w.force)
                .and_then(|()| if m > 0 { system.closure(qi, &mut w.closure, &mut w.jac) } else { Ok(()) })
                .and_then(|()| if m > 0 { system.closure_forces(qi, vi, &w.jac, &mut w.forces) } else { Ok(()) });
            match evaluated {
                Ok(()) => {}
                Err(e) if fatal(&e) => return Err(e),
                Err(e) => return Ok(Err(Refusal::Failed(e.to_string()))),
            }
            for r in 0..n {
                let mut s = -w.force[r];
                for c in 0..n {
                    s += w.mass[c * n + r] * w.x[i * n + c];
                }
                for k in 0..m {
                    s += w.forces[r * m + k] * w.x[3 * n + i * m + k];
                }
                w.r[i * n + r] = -s;
            }
            // A position row's residual is c/h², a velocity row's G v/h: each
            // the stage accelerations' scale (their rows in `factor` agree).
            for k in 0..m {
                let carried = if w.carry { w.violation[k] } else { 0.0 };
                w.r[3 * n + i * m + k] = if w.velocity[k] {
                    -((0..n).map(|c| w.jac[c * m + k] * vi[c]).sum::<f64>() - carried) / h
                } else {
                    -(w.closure[k] - carried) / (h * h)
                };
            }
            if w.staged {
                w.stage_mass[i * n * n..(i + 1) * n * n].copy_from_slice(&w.mass);
            }
        }
        if w.r.iter().any(|x| !x.is_finite()) {
            return Ok(Err(Refusal::Failed("a non-finite force or closure at a stage".into())));
        }
        if w.staged && !factor(rk, w, h) {
            return Ok(Err(Refusal::Failed(
                "the Newton matrix with the stages' masses is singular (a direction with neither mass nor \
                 stiffness, or dependent closures)"
                    .into(),
            )));
        }
        linalg::lu_solve(&w.matrix, big, &w.pivots, &mut w.r);
        for i in 0..3 {
            for r in 0..n {
                let (mut a, mut b) = (0.0, 0.0);
                for j in 0..3 {
                    a += rk.a2[i][j] * w.r[j * n + r];
                    b += rk.a[i][j] * w.r[j * n + r];
                }
                w.dq[i * n + r] = h * h * a;
                w.dv[i * n + r] = h * b;
            }
        }
        for (x, d) in w.x.iter_mut().zip(&w.r) {
            *x += d;
        }
        let size = scaled_norm(w, &w.dq, &w.dv, vw);
        if !size.is_finite() {
            return Ok(Err(Refusal::Failed("a non-finite Newton step".into())));
        }
        if iteration > 0 {
            let theta = size / previous;
            if theta >= 0.99 {
                // Stalled at rounding's level, far below the tolerance? With
                // rho the last increment's component along the one before
                // (error e -> rho e), the distance to the solution is about
                // size * |rho| / |1 - rho|: near the last increment when they
                // alternate or are unrelated (noise), unbounded as they align.
                let rho = scaled_dot(w, &w.dq, &w.dv, &w.dq_prev, &w.dv_prev, vw)
                    / scaled_dot(w, &w.dq_prev, &w.dv_prev, &w.dq_prev, &w.dv_prev, vw);
                let distance = size * (rho.abs() / (1.0 - rho).abs()).max(1.0);
                if distance <= NEWTON_FLOOR {
                    w.theta = 1.0;
                    converged = true;
                    break;
                }
                return Ok(Err(Refusal::Newton(format!("Newton diverged (contraction {theta:.2})"))));
            }
            *eta = theta / (1.0 - theta);
            w.theta = theta;
        } else {
            *eta = eta.max(f64::EPSILON).powf(0.8);
        }
        if *eta * size <= kappa {
            converged = true;
            break;
        }
        previous = size;
        w.dq_prev.copy_from_slice(&w.dq);
        w.dv_prev.copy_from_slice(&w.dv);
    }
    // Out of iterations while creeping at rounding's level: the estimated
    // distance to the solution is still far below the tolerance.
    if !converged && *eta * previous <= NEWTON_FLOOR {
        w.theta = 1.0;
        converged = true;
    }
    if !converged {
        *eta = 1.0;
        return Ok(Err(Refusal::Newton(format!("Newton did not converge in {NEWTON_ITERATIONS} iterations"))));
    }
    Ok(Ok(()))
}

/// The stage positions and velocities from the stage accelerations in `w.x`.
pub(super) fn stages(rk: &Radau, w: &mut Work, h: f64, q0: &[f64], v0: &[f64]) {
    let n = w.n;
    for i in 0..3 {
        for r in 0..n {
            let (mut dv, mut dq) = (0.0, 0.0);
            for j in 0..3 {
                dv += rk.a[i][j] * w.x[j * n + r];
                dq += rk.a2[i][j] * w.x[j * n + r];
            }
            w.vs[i * n + r] = v0[r] + h * dv;
            w.qs[i * n + r] = q0[r] + rk.c[i] * h * v0[r] + h * h * dq;
        }
    }
}

/// Builds and factors the Newton matrix of the stages for a step `h` from
/// the kept data (`w.mj`, `w.k0`, `w.d0`, `w.g0`), or with
/// [`Work::staged`] each stage's own mass matrix (`w.stage_mass`) in place
/// of `w.mj` on its diagonal block; false if it is singular.
pub(super) fn factor(rk: &Radau, w: &mut Work, h: f64) -> bool {
    let (n, m) = (w.n, w.m);
    let big = 3 * (n + m);
    w.factored = f64::NAN;
    w.matrix.fill(0.0);
    for i in 0..3 {
        for j in 0..3 {
            let (ha, h2a) = (h * rk.a[i][j], h * h * rk.a2[i][j]);
            let diag = if i == j { 1.0 } else { 0.0 };
            for c in 0..n {
                for r in 0..n {
                    let k = c * n + r;
                    let mass = if w.staged { w.stage_mass[i * n * n + k] } else { w.mj[k] };
                    w.matrix[(j * n + c) * big + i * n + r] = diag * mass + ha * w.d0[k] + h2a * w.k0[k];
                }
                for k in 0..m {
                    let a = if w.velocity[k] { rk.a[i][j] } else { rk.a2[i][j] };
                    w.matrix[(j * n + c) * big + 3 * n + i * m + k] = a * w.g0[c * m + k];
                }
            }
        }
        for k in 0..m {
            for r in 0..n {
                w.matrix[(3 * n + i * m + k) * big + i * n + r] = w.w0[r * m + k];
            }
        }
    }
    if !linalg::lu(&mut w.matrix, big, &mut w.pivots) {
        return false;
    }
    // A staged matrix holds this iteration's masses: none is kept.
    w.factored = if w.staged { f64::NAN } else { h };
    true
}

/// Newton's start in `w.x`: the last accepted step's stage accelerations
/// and multipliers, the values at its nodes $c_j$ of a quadratic in time
/// (the derivative of the velocity's collocation polynomial), extrapolated
/// to this step's nodes $1 + c_ih/h_{prev}$; zero before the first step.
pub(super) fn guess(rk: &Radau, w: &mut Work, h: f64) {
    let (n, m) = (w.n, w.m);
    if w.prev_h == 0.0 {
        w.x.fill(0.0);
        return;
    }
    for i in 0..3 {
        let tau = 1.0 + rk.c[i] * h / w.prev_h;
        let mut l = [1.0; 3];
        for (j, lj) in l.iter_mut().enumerate() {
            for k in (0..3).filter(|&k| k != j) {
                *lj *= (tau - rk.c[k]) / (rk.c[j] - rk.c[k]);
            }
        }
        for r in 0..n {
            w.x[i * n + r] = (0..3).map(|j| l[j] * w.prev[j * n + r]).sum();
        }
        for k in 0..m {
            w.x[3 * n + i * m + k] = (0..3).map(|j| l[j] * w.prev[3 * n + j * m + k]).sum();
        }
    }
}
