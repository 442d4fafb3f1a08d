//! The local error estimate of RADAU5 (module docs of the integrator):
//! the embedded third-order solution's distance from the step, filtered
//! through one stage's Newton matrix.

use super::fatal;
use super::norm::scaled_norm;
use super::radau::Radau;
use super::work::Work;
use crate::dynamics::System;
use crate::error::Result;
use crate::linalg;

/// The scaled norm of the embedded error estimate (module docs), leaving
/// $e_q$, $e_v$ in `w.eq`, `w.ev`. With `refine`, the force term is taken
/// at $y_0 + e$ (the last estimate) rather than $y_0$: RADAU5's second
/// estimate, for a step that failed the first at the start or after a
/// rejection, where stiff components are overestimated. `None` when the
/// matrix is singular or that state cannot be evaluated.
#[allow(clippy::too_many_arguments)]
pub(super) fn estimate<S: System + ?Sized>(
    system: &mut S,
    rk: &Radau,
    w: &mut Work,
    t0: f64,
    h: f64,
    q0: &[f64],
    v0: &[f64],
    vw: f64,
    refine: bool,
) -> Result<Option<f64>> {
    let (n, m) = (w.n, w.m);
    let hg = h * rk.gamma;
    let size = n + m;
    if refine {
        for r in 0..n {
            w.qt[r] = q0[r] + w.eq[r];
            w.vt[r] = v0[r] + w.ev[r];
        }
        match system.dynamics(&w.qt, &w.vt, t0, &mut w.mass, &mut w.force) {
            Ok(()) => {}
            Err(e) if fatal(&e) => return Err(e),
            Err(_) => return Ok(None),
        }
    } else {
        w.force.copy_from_slice(&w.f0);
        w.vt.copy_from_slice(v0);
    }
    // R_q = hγ v + γ Σ d_i (Q_i − q0), and Σ d_i (V_i − v0).
    for r in 0..n {
        let (mut a, mut b) = (0.0, 0.0);
        for i in 0..3 {
            a += rk.d[i] * (w.qs[i * n + r] - q0[r]);
            b += rk.d[i] * (w.vs[i * n + r] - v0[r]);
        }
        w.rq[r] = hg * w.vt[r] + rk.gamma * a;
        w.rs[r] = b;
    }
    // Right side hγ R_v + (M + hγD) R_q, with R_v = hγ f + γ M Σ d_i (V_i − v0).
    for r in 0..n {
        let mut s = hg * hg * w.force[r];
        for c in 0..n {
            let k = c * n + r;
            s += hg * rk.gamma * w.m0[k] * w.rs[c] + (w.m0[k] + hg * w.d0[k]) * w.rq[c];
        }
        w.erhs[r] = s;
    }
    w.erhs[n..].fill(0.0);
    // The estimate's matrix takes this step's M and G, as its right side
    // does (a kept M would misjudge the error, a kept G would leak the
    // closure forces into the directions without inertia), and the kept tangents.
    w.e.fill(0.0);
    for c in 0..n {
        for r in 0..n {
            let k = c * n + r;
            w.e[c * size + r] = w.m0[k] + hg * w.d0[k] + hg * hg * w.k0[k];
        }
        for k in 0..m {
            w.e[c * size + n + k] = w.g_start[c * m + k];
            w.e[(n + k) * size + c] = w.w_start[c * m + k];
        }
    }
    if !linalg::lu(&mut w.e, size, &mut w.epiv) {
        return Ok(None);
    }
    linalg::lu_solve(&w.e, size, &w.epiv, &mut w.erhs);
    for r in 0..n {
        w.eq[r] = w.erhs[r];
        w.ev[r] = (w.erhs[r] - w.rq[r]) / hg;
    }
    let err = scaled_norm(w, &w.eq, &w.ev, vw);
    Ok(if err.is_finite() { Some(err) } else { None })
}
