//! Landing on a system's events ([`System::guards`]): a step whose end
//! leaves a guard below its band ($g < -1$) is refused, and the steps that
//! follow aim at the crossing, found by the Illinois variant of regula falsi
//! on the guards at the bracket's ends, until one ends on it ($\lvert g\rvert \le 1$).
//! Each aimed step is a whole Radau step from the last state accepted, so
//! the state landed on is as accurate as any other. A step aimed at the
//! event that ends short of it is not accepted: it moves the bracket's near
//! end, and the next aim starts from the same state. Were it accepted, the
//! run would creep up on the event and aim from ever closer, and a step of
//! $h$ carries rounding's error in its positions, about
//! $\epsilon_{\text{mach}}\lvert q\rvert$, into its velocities over $h$: a slide that
//! stops at a tolerance of $10^{-8}$ was read from steps of $10^{-13}$ s whose
//! velocities were off by 25 (the run let go a contact that pushed).
//! An aimed step holds the closures at its start's violation (see
//! `newton`), and its guards read the multipliers of the equations of
//! motion at its end ([`consistent_multipliers`]), not the step's own: a
//! short step's own err by the start's violation over $h^2$, and a push
//! falling to zero is a guard.

use crate::dynamics::System;

/// The most steps aimed at one event before the run is declared stalled:
/// regula falsi with Illinois' halving shrinks the bracket superlinearly,
/// so this is far more than a smooth guard needs.
pub(super) const MAX_AIMS: usize = 60;

/// An event bracketed: a refused step ended at `t_hi` with the guards `g_hi`,
/// at least one below its band.
pub(super) struct Pending {
    pub(super) t_hi: f64,
    pub(super) g_hi: Vec<f64>,
    /// The near end, where a step aimed at the event ended short of it
    /// (not accepted); the last state accepted until one does.
    near: Option<(f64, Vec<f64>)>,
    /// The bracket's width when it last halved (at first, its whole), the
    /// steps aimed since, and whether it is bisected from now on (two aims
    /// once did not halve it).
    halved: f64,
    since: usize,
    bisect: bool,
    /// Whether the next step aims at the far end itself: the bracket is
    /// narrower than the events need, its near end short of them, and that
    /// step lands there on the guards its own end finds past their bands
    /// (or, finding none, is taken as any step: the event was not there).
    pub(super) far: bool,
    /// Steps aimed so far, and whether the last one ended short of the event.
    pub(super) aims: usize,
    short: bool,
}

impl Pending {
    /// A bracket from `t`, the last state accepted, to `t_hi`.
    pub(super) fn new(t: f64, t_hi: f64, g_hi: &[f64]) -> Self {
        let halved = t_hi - t;
        Pending {
            t_hi,
            g_hi: g_hi.to_vec(),
            near: None,
            halved,
            since: 0,
            bisect: false,
            far: false,
            aims: 0,
            short: false,
        }
    }

    /// The bracket's near end: where a step aimed at the event fell short,
    /// if after `t` (the last state accepted, its guards `g_now`), else `t`.
    pub(super) fn near<'a>(&'a self, t: f64, g_now: &'a [f64]) -> (f64, &'a [f64]) {
        match &self.near {
            Some((t_near, g)) if *t_near > t => (*t_near, g),
            _ => (t, g_now),
        }
    }

    /// The time to aim the next step at from `t`, where the guards are
    /// `g_now` (each at least $-1$): the earliest of the guards' crossings,
    /// each of the line through its values at the bracket's ends at a level
    /// inside its band (halfway from where it is, or from 0, to $-1$), kept
    /// inside the bracket; its middle once two steps aimed so did not halve
    /// it (a guard that jumps: a line through a jump aims beside it, and
    /// Illinois' halving takes many steps to undo a far value a thousand
    /// bands deep; bisected from then on, the bracket narrows to the
    /// tolerance of the step in about $\log_2(1/\text{tolerance})$ steps); the far
    /// end itself once it is that narrow ([`Pending::far`]).
    pub(super) fn aim(&self, t: f64, g_now: &[f64]) -> f64 {
        if self.far {
            return self.t_hi;
        }
        let (t, g_now) = self.near(t, g_now);
        let span = self.t_hi - t;
        if self.bisect {
            return t + 0.5 * span;
        }
        let theta = g_now
            .iter()
            .zip(&self.g_hi)
            .filter(|(_, hi)| **hi < -1.0)
            .map(|(&a, &b)| {
                let level = 0.5 * (a.min(0.0) - 1.0);
                (a - level) / (a - b)
            })
            .fold(1.0, f64::min);
        t + span * theta.clamp(1e-3, 1.0 - 1e-3)
    }

    /// A step ended short of the event: aimed at it, at `end` (its time
    /// and guards: the bracket's new near end, the step not taken), or
    /// taken at the controller's length. The bracket keeps its far end; a
    /// second short step in a row halves the far guards (Illinois), so the
    /// aim moves toward it.
    pub(super) fn fell_short(&mut self, t: f64, end: Option<(f64, &[f64])>) {
        if let Some((t_end, g)) = end {
            self.near = Some((t_end, g.to_vec()));
        }
        self.narrowed(t);
        if self.short {
            for g in self.g_hi.iter_mut().filter(|g| **g < -1.0) {
                *g *= 0.5;
                // Still below the band: the guard's own band is what it aims within.
                *g = g.min(-1.0 - f64::EPSILON);
            }
        }
        self.short = true;
        self.aims += 1;
    }

    /// A step from `t` aimed at the event overshot it, ending at `t_end`
    /// with guards `g`: the new far end.
    pub(super) fn overshot(&mut self, t: f64, t_end: f64, g: &[f64]) {
        self.t_hi = t_end;
        self.g_hi.copy_from_slice(g);
        // A near end at or past the new far end (a shorter step, after a
        // refusal, overshot before it) is no end of this bracket.
        if self.near.as_ref().is_some_and(|(t_near, _)| *t_near >= t_end) {
            self.near = None;
        }
        self.narrowed(t);
        (self.short, self.far) = (false, false);
        self.aims += 1;
    }

    /// Counts a step aimed, the last state accepted at `t`: whether the bracket has halved since it last did.
    fn narrowed(&mut self, t: f64) {
        let width = self.t_hi - self.near(t, &[]).0;
        if width <= 0.5 * self.halved {
            (self.halved, self.since) = (width, 0);
        } else {
            self.since += 1;
            self.bisect |= self.since >= 2;
        }
    }
}

/// The guards of `g` past their bands ($g < -1$): the events a switch takes.
pub(super) fn past_bands(g: &[f64]) -> Vec<usize> {
    (0..g.len()).filter(|&k| g[k] < -1.0).collect()
}

/// What a step's end says of the events, from the guards at its start `g0`
/// and its end `g1`, and the event aimed at if any.
pub(super) enum Verdict {
    /// No event at or before its end.
    Clear,
    /// A guard fell below its band within the step: refuse it, aim at the crossing.
    Overshot,
    /// The step ends on the events of these guards: accept it and switch.
    Landed(Vec<usize>),
}

/// The [`Verdict`] of a step: overshot if any guard ends below $-1$; else it
/// lands on each guard that crossed 0 within it, and on each the aim was at
/// that ends within its band.
pub(super) fn verdict(g0: &[f64], g1: &[f64], pending: Option<&Pending>) -> Verdict {
    if g1.iter().any(|g| *g < -1.0 || g.is_nan()) {
        return Verdict::Overshot;
    }
    let landed: Vec<usize> = (0..g1.len())
        .filter(|&k| {
            let crossed = g0[k] >= 0.0 && g1[k] < 0.0;
            let aimed = pending.is_some_and(|p| p.g_hi[k] < -1.0 && g1[k] <= 1.0);
            crossed || aimed
        })
        .collect();
    if landed.is_empty() { Verdict::Clear } else { Verdict::Landed(landed) }
}

/// The guards of `system` at $(q, \dot q)$ with the closures' multipliers, into `out` (resized).
pub(super) fn guards<S: System + ?Sized>(
    system: &mut S,
    q: &[f64],
    v: &[f64],
    multipliers: Option<&[f64]>,
    out: &mut Vec<f64>,
) -> crate::error::Result<()> {
    out.resize(system.guard_count(), 0.0);
    system.guards(q, v, multipliers, out)
}

/// The guards at a state where a mode begins (the run's start, or just
/// after a switch), into `out`: read first without multipliers, which
/// sets what a mode's start sets (a slide's way after an impact) and puts
/// each push and friction at its band's edge, then with the equations' own
/// ([`consistent_multipliers`]) where they exist, whose values replace
/// those within or above their bands. The steps aimed at the next event
/// interpolate from these: with the band's edge, a push $3\times10^6$ bands from
/// zero read as at it, each aim fell to rounding, and over steps that short
/// rounding moved the velocities enough to read a slide turning back (a
/// fast grasp switched stick and slip 24 times at one instant). A value
/// past its band keeps the edge: the steps find that event.
pub(super) fn entered<S: System + ?Sized>(
    system: &mut S,
    t: f64,
    q: &[f64],
    v: &[f64],
    out: &mut Vec<f64>,
) -> crate::error::Result<()> {
    guards(system, q, v, None, out)?;
    if system.closures() > 0
        && let Some(lambda) = consistent_multipliers(system, t, q, v)?
    {
        let mut read = Vec::new();
        guards(system, q, v, Some(&lambda), &mut read)?;
        out.iter_mut().zip(&read).filter(|(_, r)| **r >= -1.0).for_each(|(g, r)| *g = *r);
    }
    Ok(())
}

/// The first step's scale after an event (× the sample interval), for [`project`]'s metric.
pub(super) const PROJECTION_STEP: f64 = 1e-6;

/// Newton steps of [`project`]'s position projection.
const PROJECTION_ITERATIONS: usize = 8;

/// Moves the state $(q, \dot q)$ at time `t` onto the closures of the mode
/// just entered: $q$ by Newton's method onto $c(q) = 0$, then $\dot q$ onto
/// $G\dot q = 0$, each the least change in the metric
/// $\tilde M = M + hD_t + h^2K_t$ ($h$ = `step`, short: where there is mass,
/// $\tilde M \approx M$; massless directions keep their stiffness):
/// $$\begin{bmatrix}\tilde M & G^T\cr G & 0\end{bmatrix}\begin{bmatrix}\Delta\cr\mu\end{bmatrix} = \begin{bmatrix}0\cr -r\end{bmatrix},$$
/// $r = c(q)$, then $r = G\dot q$. The velocity's is a perfectly inelastic
/// impact: the $\tilde M$-orthogonal projection, which takes the kinetic
/// energy of the motion the closures stop and adds none. So the first step
/// of the new mode starts consistent, and its multipliers are forces, not
/// an impulse spread over it.
pub(super) fn project<S: System + ?Sized>(
    system: &mut S,
    t: f64,
    (q, v): (&mut [f64], &mut [f64]),
    step: f64,
) -> crate::error::Result<()> {
    let (n, m) = (system.dim(), system.closures());
    if m == 0 {
        return Ok(());
    }
    let big = n + m;
    let (mut mass, mut force, mut k, mut d) = (vec![0.0; n * n], vec![0.0; n], vec![0.0; n * n], vec![0.0; n * n]);
    system.dynamics(q, v, t, &mut mass, &mut force)?;
    system.tangent(q, v, t, &mut k, &mut d)?;
    let (mut c, mut g) = (vec![0.0; m], vec![0.0; m * n]);
    let mut kkt = vec![0.0; big * big];
    let mut pivots = vec![0; big];
    // The KKT matrix at the state's G (column-major), factored; false if singular.
    let factor = |g: &[f64], kkt: &mut Vec<f64>, pivots: &mut Vec<usize>| {
        kkt.fill(0.0);
        for col in 0..n {
            for row in 0..n {
                let e = col * n + row;
                kkt[col * big + row] = mass[e] + step * d[e] + step * step * k[e];
            }
            for r in 0..m {
                kkt[col * big + n + r] = g[col * m + r];
                kkt[(n + r) * big + col] = g[col * m + r];
            }
        }
        crate::linalg::lu(kkt, big, pivots)
    };
    let singular = || crate::error::Error::Singular {
        what: "the closures after an event: their Jacobian is singular in the metric of the mass and stiffness".into(),
    };
    let mut rhs = vec![0.0; big];
    for _ in 0..PROJECTION_ITERATIONS {
        system.closure(q, &mut c, &mut g)?;
        if super::largest(&c) <= 1e-15 * (1.0 + super::largest(q)) {
            break;
        }
        if !factor(&g, &mut kkt, &mut pivots) {
            return Err(singular());
        }
        rhs.fill(0.0);
        for r in 0..m {
            rhs[n + r] = -c[r];
        }
        crate::linalg::lu_solve(&kkt, big, &pivots, &mut rhs);
        q.iter_mut().zip(&rhs).for_each(|(q, dq)| *q += dq);
    }
    system.closure(q, &mut c, &mut g)?;
    if !factor(&g, &mut kkt, &mut pivots) {
        return Err(singular());
    }
    rhs.fill(0.0);
    for r in 0..m {
        rhs[n + r] = -(0..n).map(|col| g[col * m + r] * v[col]).sum::<f64>();
    }
    crate::linalg::lu_solve(&kkt, big, &pivots, &mut rhs);
    v.iter_mut().zip(&rhs).for_each(|(v, dv)| *v += dv);
    Ok(())
}

/// The closures' multipliers at $(q, \dot q, t)$ from the equations of
/// motion themselves, independent of any step:
/// $$\begin{bmatrix}M & W^T\cr G & 0\end{bmatrix}\begin{bmatrix}\ddot q\cr\lambda\end{bmatrix} = \begin{bmatrix}f\cr -\dot G\dot q\end{bmatrix},$$
/// $\dot G\dot q$ by a central difference of $G$ along $\dot q$ (the
/// closures' acceleration held at zero; a velocity row's too). A step's own
/// multipliers correct its start's closure violation $\epsilon$ with forces
/// of order $\epsilon/h^2$, which swamp a push that falls to zero on the short
/// steps aimed at its event; these do not. `None` where $M$ is singular
/// (directions without inertia, or with less than $10^{-10}$ of the
/// largest) or the matrix is: the step's own then serve.
pub(crate) fn consistent_multipliers<S: System + ?Sized>(
    system: &mut S,
    t: f64,
    q: &[f64],
    v: &[f64],
) -> crate::error::Result<Option<Vec<f64>>> {
    let (n, m) = (system.dim(), system.closures());
    let big = n + m;
    let (mut mass, mut force) = (vec![0.0; n * n], vec![0.0; n]);
    let (mut c, mut g, mut w) = (vec![0.0; m], vec![0.0; m * n], vec![0.0; m * n]);
    system.dynamics(q, v, t, &mut mass, &mut force)?;
    // Only where every direction has inertia: elsewhere these equations
    // leave the multipliers to the stiffness, which the step's own hold.
    let largest_mass = (0..n).map(|i| mass[i * n + i]).fold(0.0, f64::max);
    let regular = nalgebra::DMatrix::from_column_slice(n, n, &mass)
        .cholesky()
        .is_some_and(|l| l.l_dirty().diagonal().iter().all(|d| d * d > 1e-10 * largest_mass));
    if !regular {
        return Ok(None);
    }
    // Ġ q̇ first, so that the closures are last evaluated at q itself.
    let speed = super::largest(v);
    let mut rate = vec![0.0; m];
    if speed > 0.0 {
        let delta = 1e-6 * (1.0 + super::largest(q)) / speed;
        let mut moved = q.to_vec();
        for (sign, scale) in [(1.0, 0.5 / delta), (-1.0, -0.5 / delta)] {
            moved.iter_mut().zip(q.iter().zip(v)).for_each(|(x, (q, v))| *x = q + sign * delta * v);
            system.closure(&moved, &mut c, &mut g)?;
            for (k, r) in rate.iter_mut().enumerate() {
                *r += scale * (0..n).map(|col| g[col * m + k] * v[col]).sum::<f64>();
            }
        }
    }
    system.closure(q, &mut c, &mut g)?;
    system.closure_forces(q, v, &g, &mut w)?;
    let mut kkt = vec![0.0; big * big];
    for col in 0..n {
        for row in 0..n {
            kkt[col * big + row] = mass[col * n + row];
        }
        for k in 0..m {
            kkt[col * big + n + k] = g[col * m + k];
            kkt[(n + k) * big + col] = w[col * m + k];
        }
    }
    let mut pivots = vec![0; big];
    if !crate::linalg::lu(&mut kkt, big, &mut pivots) {
        return Ok(None);
    }
    let mut rhs: Vec<f64> = force.iter().copied().chain(rate.iter().map(|r| -r)).collect();
    crate::linalg::lu_solve(&kkt, big, &pivots, &mut rhs);
    let lambda = rhs.split_off(n);
    Ok(lambda.iter().all(|x| x.is_finite()).then_some(lambda))
}
