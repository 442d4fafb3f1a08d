//! The load path: continuation in the load with the active set found on
//! the way, each change bisected onto the load where it happens.

use super::super::trace::cross_section;
use super::obstacle::Obstacle;
use super::shooting::{Active, Law, MAX_CONTACTS, Sample, Seen, Shooting};
use super::solution::{ContactEvent, ContactPoint, ContactSolution, ContactState, ContactStop, EventKind};
use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::reference::elastica::ShootingSettings;
use crate::solver::{self, Problem, SolverWorkspace};
use crate::statics::TipLoad;

/// The first load step, and the largest, in path units (a leg is 1).
const FIRST_STEP: f64 = 0.05;
const LARGEST_STEP: f64 = 0.1;

/// Events are bisected until their bracket in the path parameter is this narrow.
const EVENT_RESOLUTION: f64 = 1e-12;

/// Active-set changes allowed at one load before the path is declared stalled.
const MAX_CHANGES_AT_ONCE: usize = 8;

/// A penetration deeper than this fraction of $L$ is a new contact.
const GAP_TOLERANCE: f64 = 1e-13;

/// A gap below this fraction of $L$ over more than [`FLAT_LENGTH`] × $L$ is
/// distributed contact.
const FLAT_GAP: f64 = 1e-9;
const FLAT_LENGTH: f64 = 1e-3;

/// A local minimum of the gap this close to an active contact (× $L$) is that contact.
const SAME_POINT: f64 = 1e-6;

/// An interior contact this close to the tip (× $L$), where no load step
/// beyond converges (bisected to [`EVENT_RESOLUTION`]), has reached the tip;
/// the bisection starts from a failed step while one lies within half the length.
const NEAR_TIP: f64 = 1e-4;

/// A tip's tangent turned away from the surface by more than this (rad) has lifted.
const ROLL_TOLERANCE: f64 = 1e-10;

/// A force violation (N) smaller than this × the residual scale / $L$ is rounding.
const FORCE_TOLERANCE: f64 = 1e-11;

/// What is wrong with a trial state.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Violation {
    /// Active contact `c` pulls.
    Open(usize),
    /// Tip contact `c`'s tangent turned away from the surface.
    Roll(usize),
    /// Stuck contact `c` needs more friction than $\mu N$; it slips along `direction`.
    Slip(usize, f64),
    /// Slipping contact `c` moved with its friction force, not against it.
    Stick(usize),
    /// The shape enters `obstacle` at arc length `s`.
    Touch { obstacle: usize, s: f64 },
    /// The shape lies along `obstacle` (distributed contact).
    Flat(usize),
    /// Interior contact `c` reached the tip (no state beyond).
    Unroll(usize),
}

/// The exact elastica clamped at the root (at the origin, along $+x$) under
/// a dead tip load that follows `path` from zero, kept out of `obstacles`:
/// its centreline, offset by `half_thickness` $h$, keeps a gap $g \ge 0$
/// to each ([`Obstacle`]).
///
/// **Contact.** The flexure touches at a finite set of points $s_c$, each
/// at the tip ($s_c = L$) or inside the span. An obstacle pushes with a force
/// $f_c = N_c\hat n + T_c\hat t$ at its outward normal $\hat n$ and tangent
/// $\hat t = (-n_y, n_x)$, under the complementarity
/// $$g_c \ge 0,\quad N_c \ge 0,\quad g_c N_c = 0.$$
/// A contact inside the span is where the gap is least, so the centreline
/// is tangent to the surface there: $\hat n\cdot(\cos\phi, \sin\phi) = 0$ at
/// $s_c$. Friction (the obstacle's $\mu$) acts at the tip only: it sticks
/// (its place along $\hat t$ fixed) while $\lvert T\rvert \le \mu N$, and slips with
/// $T = \pm\mu N$ against the motion; the answer depends on the path.
///
/// **Equations.** Between contacts the internal force $F(s)$ (the tip load
/// plus every contact force beyond $s$) is constant and the bending moment
/// $m = EI(\phi^{\prime} - \omega_0)$ obeys
/// $$m^{\prime} = F_x\sin\phi - F_y\cos\phi,\qquad m(L) = M,$$
/// with $\phi(0) = x(0) = y(0) = 0$. Multiple shooting: the unknowns are the
/// angle and moment at the nodes of the elastica's segments, each
/// contact's force $(f_x, f_y)$ and, inside the span, its $s_c$; the
/// residuals are the mismatches at the nodes, the gap at each contact, its
/// tangential law ($T = 0$; stuck in place; $T = \pm\mu N$) and, inside the
/// span, the tangency. The Jacobian is exact: dual numbers through the
/// integrator, and for $s_c$ the jump $-f_c$ of $F$ carried by the
/// variational equation from $s_c$.
///
/// **Path.** Leg $i$ runs the load linearly from `path[i-1]` (zero before
/// the first) to `path[i]`; the path parameter goes from 0 to the number of
/// legs, in steps of at most 0.1 that turn no node by more than
/// `settings.solver.max_rotation_per_step`, each solved by Newton
/// ([`crate::solver::newton`]) from the secant predictor. After each step the
/// shape is checked: a normal force below zero (the contact opens), a tip
/// tangent turned away from the surface (the tip lifts: its contact moves
/// into the span), a contact in the span reaching the tip (no step past
/// it converges: bisected, it becomes the tip's), a stuck tip needing
/// more than $\mu N$ (it slips), a
/// slipping tip moving with its friction (it sticks), and the gap scanned
/// along the whole shape, its local minima found to $10^{-12}L$ (a new
/// contact where it is below $-10^{-13}L$). A violated step is bisected
/// until the event is bracketed to $10^{-12}$ of the path, the active
/// set changed at the near side and settled there (at most 8 changes).
///
/// **Refused by name** (the path stops with [`ContactStop::Refused`] at the last
/// state handled): the flexure lying along an obstacle over an interval
/// (distributed contact: a gap within $10^{-9}L$ over $10^{-3}L$), more
/// than 4 contacts at once, friction at a contact inside the span. Bad input
/// is an error: an empty path, a bad load or obstacle, a negative or
/// non-finite half thickness, a root inside an obstacle (or touching it),
/// an unloaded shape that enters one, a force beyond 17 shooting segments
/// ($1.5\int_0^L\sqrt{\lvert F\rvert/EI}\thinspace ds > 17$).
///
/// # Example
/// ```
/// use flexure::reference::elastica::{self, contact::Obstacle};
/// use flexure::{Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // A floor 0.01 below the flexure; a clockwise tip moment presses the tip
/// // onto it. Propped cantilever: N = 3M/2L − 3EIg/L³ = 0.15 − 0.03.
/// let floor = [Obstacle::half_plane([0.0, -0.01], [0.0, 1.0])];
/// let load = [TipLoad { moment: -0.1, fx: 0.0, fy: 0.0 }];
/// let s = elastica::contact(&f, &floor, 0.0, &load, &Default::default()).unwrap();
/// assert!(s.reached() && s.contacts.len() == 1 && s.contacts[0].s == 1.0);
/// assert!((s.contacts[0].normal_force - 0.12).abs() < 2e-3);
/// ```
pub fn contact(
    flexure: &Flexure,
    obstacles: &[Obstacle],
    half_thickness: f64,
    path: &[TipLoad],
    settings: &ShootingSettings,
) -> Result<ContactSolution> {
    settings.validate()?;
    if path.is_empty() {
        return Err(Error::invalid("path", 0, "must hold at least one load"));
    }
    for load in path {
        load.validate()?;
    }
    if !(half_thickness.is_finite() && half_thickness >= 0.0) {
        return Err(Error::invalid("half_thickness", half_thickness, "must be a finite number, zero or greater"));
    }
    for (i, o) in obstacles.iter().enumerate() {
        o.validate()?;
        if o.gap([0.0, 0.0], half_thickness) <= 0.0 {
            return Err(Error::invalid("obstacle", i, "holds the root: the root must lie outside every obstacle"));
        }
    }
    let segments = Shooting::segments(flexure, path)?;
    let mut sh = Shooting::new(flexure, obstacles, half_thickness, path, segments, settings.ode)?;
    let total = path.len() as f64;
    let mut x = sh.rest()?;
    let mut lambda = 0.0;
    let (mut seen, mut samples) = sh.inspect(&x, lambda)?;
    if let Some(Violation::Touch { obstacle, .. } | Violation::Flat(obstacle)) = check(&sh, &seen, &samples, None) {
        return Err(Error::invalid(
            "obstacle",
            obstacle,
            "is entered or touched along an interval by the unloaded flexure",
        ));
    }
    let solver_settings = settings.solver;
    let mut step = FIRST_STEP;
    let mut upper: Option<(f64, Violation)> = None;
    let mut previous: Option<(Vec<f64>, f64)> = None;
    let (mut steps, mut trials) = (0, 0);
    let mut events = Vec::new();
    let mut stop = ContactStop::Reached;
    let mut last_error: Option<Error> = None;
    while lambda < total {
        trials += 1;
        if trials > solver_settings.max_steps {
            stop = ContactStop::Stalled(stalled(&sh, lambda / total, steps, "the step limit was reached", last_error));
            break;
        }
        let target = match upper {
            Some((u, _)) => 0.5 * (lambda + u),
            None => (lambda + step).min(lambda.floor() + 1.0).min(total),
        };
        // Predictor: the secant through the last two states of this active set.
        let mut guess = x.clone();
        if let Some((xp, lp)) = &previous
            && xp.len() == x.len()
            && lambda > *lp
        {
            let t = (target - lambda) / (lambda - lp);
            for i in 0..x.len() {
                guess[i] += t * (x[i] - xp[i]);
            }
        }
        let mut ws = SolverWorkspace::new(sh.dim());
        ws.x.copy_from_slice(&guess);
        let solved = solver::newton(&mut sh, &mut ws, target, &solver_settings)
            .and_then(|_| {
                if sh.distance(&ws.x, &x) > solver_settings.max_rotation_per_step {
                    Err(Error::Singular { what: "a load step turned a cross-section too far".into() })
                } else {
                    Ok(())
                }
            })
            .and_then(|_| sh.inspect(&ws.x, target));
        match solved {
            Err(e) => {
                last_error = Some(e);
                match &mut upper {
                    Some((u, _)) => *u = target,
                    // No state past an interior contact near the tip: it
                    // reaches the tip there; bisect onto that load.
                    None => match nearest_tip(&sh, &x, 0.5) {
                        Some(c) => upper = Some((target, Violation::Unroll(c))),
                        None => step *= 0.5,
                    },
                }
                if upper.is_none() && step < solver_settings.min_step {
                    stop =
                        ContactStop::Stalled(stalled(&sh, lambda / total, steps, "no load step converged", last_error));
                    break;
                }
            }
            Ok((seen_t, samples_t)) => match check(&sh, &seen_t, &samples_t, Some(&seen)) {
                None => {
                    previous = Some((std::mem::replace(&mut x, ws.x.clone()), lambda));
                    (lambda, seen, samples) = (target, seen_t, samples_t);
                    steps += 1;
                    if upper.is_none() {
                        step = (2.0 * step).min(LARGEST_STEP);
                    }
                }
                Some(Violation::Flat(o)) => {
                    stop = ContactStop::Refused(Error::invalid(
                        "obstacle",
                        o,
                        "is met along an interval (the flexure lies along it): distributed contact is not handled",
                    ));
                    break;
                }
                Some(v) => upper = Some((target, v)),
            },
        }
        let Some((u, v)) = upper else { continue };
        if u - lambda > EVENT_RESOLUTION * lambda.max(1.0) {
            continue;
        }
        // The event lies within the resolution past `lambda`: change the
        // active set there and settle it.
        upper = None;
        previous = None;
        if let Violation::Unroll(c) = v
            && nearest_tip(&sh, &x, NEAR_TIP) != Some(c)
        {
            stop = ContactStop::Stalled(stalled(&sh, lambda / total, steps, "no load step converged", last_error));
            break;
        }
        let mut pending = Some(v);
        let mut changes = 0;
        while let Some(v) = pending.take() {
            changes += 1;
            if changes > MAX_CHANGES_AT_ONCE {
                stop = ContactStop::Stalled(stalled(
                    &sh,
                    lambda / total,
                    steps,
                    "the active set does not settle",
                    last_error.clone(),
                ));
                break;
            }
            match apply(&mut sh, &mut x, (&seen, &samples), v, lambda, &mut events) {
                Ok(()) => {}
                Err(e) => {
                    stop = ContactStop::Refused(e);
                    break;
                }
            }
            let mut ws = SolverWorkspace::new(sh.dim());
            ws.x.copy_from_slice(&x);
            let settled =
                solver::newton(&mut sh, &mut ws, lambda, &solver_settings).and_then(|_| sh.inspect(&ws.x, lambda));
            match settled {
                Ok((seen_n, samples_n)) => {
                    pending = check(&sh, &seen_n, &samples_n, None);
                    x = ws.x;
                    (seen, samples) = (seen_n, samples_n);
                }
                Err(e) => {
                    stop = ContactStop::Stalled(stalled(
                        &sh,
                        lambda / total,
                        steps,
                        "no state after an active-set change",
                        Some(e),
                    ));
                    break;
                }
            }
        }
        if stop != ContactStop::Reached {
            break;
        }
    }
    Ok(solution(&sh, &x, lambda, &seen, &samples, steps, events, stop))
}

/// The interior contact nearest the tip in the state `x`, if within `within` × $L$ of it.
fn nearest_tip(sh: &Shooting, x: &[f64], within: f64) -> Option<usize> {
    let sigma = |c: usize| x[sh.base(c) + 2];
    (0..sh.active.len())
        .filter(|&c| !sh.active[c].tip && sigma(c) > 1.0 - within)
        .max_by(|&a, &b| sigma(a).total_cmp(&sigma(b)))
}

fn stalled(sh: &Shooting, fraction: f64, steps: usize, cause: &str, last: Option<Error>) -> Error {
    let (residual, why) = match &last {
        Some(Error::NoConvergence { residual, .. }) => {
            (*residual, format!("{cause}; {}", last.as_ref().expect("some")))
        }
        Some(e) => (0.0, format!("{cause}; {e}")),
        None => (0.0, cause.to_string()),
    };
    Error::ContinuationStalled {
        cause: why,
        rounding: false,
        solver: sh.name(),
        load_fraction: fraction,
        steps,
        residual,
        unit: sh.unit(),
    }
}

/// Changes the active set (and the unknowns `x`) by `v`, at the state (`seen`, `samples`) at `lambda`.
fn apply(
    sh: &mut Shooting,
    x: &mut Vec<f64>,
    (seen, samples): (&[Seen], &[Sample]),
    v: Violation,
    lambda: f64,
    events: &mut Vec<ContactEvent>,
) -> Result<()> {
    let l = sh.flexure.length();
    let mut event = |kind, obstacle, s| events.push(ContactEvent { load: lambda, kind, obstacle, s });
    match v {
        Violation::Open(c) => {
            let (b, a) = (sh.base(c), sh.active[c]);
            x.drain(b..b + a.unknowns());
            sh.active.remove(c);
            event(EventKind::Open, a.obstacle, seen[c].s);
        }
        Violation::Roll(c) => {
            let a = sh.active[c];
            if sh.obstacles[a.obstacle].friction > 0.0 {
                return Err(Error::invalid(
                    "friction",
                    sh.obstacles[a.obstacle].friction,
                    "the tip's contact moves into the span, and an interior contact with friction is not handled",
                ));
            }
            let b = sh.base(c);
            x.insert(b + 2, 1.0 - SAME_POINT * 0.1);
            sh.active[c].tip = false;
            event(EventKind::Roll, a.obstacle, l);
        }
        Violation::Slip(c, direction) => {
            sh.active[c].law = Law::Slip { direction };
            event(EventKind::Slip, sh.active[c].obstacle, seen[c].s);
        }
        Violation::Stick(c) => {
            sh.active[c].law = Law::Stick { at: seen[c].point };
            event(EventKind::Stick, sh.active[c].obstacle, seen[c].s);
        }
        Violation::Touch { obstacle, s } => {
            if sh.active.len() == MAX_CONTACTS {
                return Err(Error::invalid(
                    "contacts",
                    MAX_CONTACTS + 1,
                    "more than 4 contact points at once (the flexure wraps or lies along an obstacle) are not handled",
                ));
            }
            let tip = s >= l * (1.0 - 1e-12);
            let mu = sh.obstacles[obstacle].friction;
            let law = match (mu > 0.0, tip) {
                (false, _) => Law::Frictionless,
                // Stuck where the tip is now, not where the step past the
                // event put it: no tangential force yet.
                (true, true) => {
                    let tip = samples.last().expect("a shape has points").state;
                    Law::Stick { at: [tip[2], tip[3]] }
                }
                (true, false) => {
                    return Err(Error::invalid(
                        "friction",
                        mu,
                        "an interior contact with friction is not handled (only the tip's contact may have friction)",
                    ));
                }
            };
            x.extend_from_slice(&[0.0, 0.0]);
            if !tip {
                x.push(s / l);
            }
            sh.active.push(Active { obstacle, tip, law });
            event(EventKind::Touch, obstacle, s);
        }
        Violation::Unroll(c) => {
            let b = sh.base(c);
            x.remove(b + 2);
            sh.active[c].tip = true;
            event(EventKind::Unroll, sh.active[c].obstacle, seen[c].s);
        }
        Violation::Flat(_) => unreachable!("refused before"),
    }
    Ok(())
}

/// The first violation of the state (`seen`, `samples`), if any;
/// `before` is the last accepted state, for the direction of slip.
fn check(sh: &Shooting, seen: &[Seen], samples: &[Sample], before: Option<&[Seen]>) -> Option<Violation> {
    let l = sh.flexure.length();
    let force_tolerance = FORCE_TOLERANCE * sh.scale() / l;
    let mut found: Vec<Violation> = Vec::new();
    for (c, (a, q)) in sh.active.iter().zip(seen).enumerate() {
        let t = [-q.normal[1], q.normal[0]];
        let push = q.force[0] * q.normal[0] + q.force[1] * q.normal[1];
        let along = q.force[0] * t[0] + q.force[1] * t[1];
        if push < -force_tolerance {
            found.push(Violation::Open(c));
        }
        if a.tip && q.normal[0] * q.phi.cos() + q.normal[1] * q.phi.sin() > ROLL_TOLERANCE {
            found.push(Violation::Roll(c));
        }
        let mu = sh.obstacles[a.obstacle].friction;
        match a.law {
            Law::Stick { .. } if along.abs() > mu * push + force_tolerance => {
                found.push(Violation::Slip(c, along.signum()));
            }
            Law::Slip { direction } => {
                // The same contact in the last state (same obstacle, same place kind).
                let last = before.and_then(|b| b.get(c));
                if let Some(p) = last {
                    let moved = (q.point[0] - p.point[0]) * t[0] + (q.point[1] - p.point[1]) * t[1];
                    if moved * direction > GAP_TOLERANCE * l {
                        found.push(Violation::Stick(c));
                    }
                }
            }
            _ => {}
        }
    }
    // The gap along the shape, obstacle by obstacle.
    for (o, obstacle) in sh.obstacles.iter().enumerate() {
        let h = sh.half_thickness;
        let gap = |q: &[f64; 4]| obstacle.gap([q[2], q[3]], h);
        let slope = |q: &[f64; 4]| {
            let n = obstacle.normal_of([q[2], q[3]]);
            n[0] * q[0].cos() + n[1] * q[0].sin()
        };
        let near_active =
            |s: f64| sh.active.iter().zip(seen).any(|(a, q)| a.obstacle == o && (q.s - s).abs() <= SAME_POINT * l);
        let mut flat = 0.0;
        let mut worst: Option<(f64, f64)> = None;
        let mut consider = |s: f64, q: &[f64; 4]| {
            let g = gap(q);
            if g < -GAP_TOLERANCE * l && !near_active(s) && worst.is_none_or(|w| g < w.0) {
                worst = Some((g, s));
            }
        };
        for w in samples.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            if b.s <= a.s {
                continue;
            }
            if gap(&a.state).abs() <= FLAT_GAP * l && gap(&b.state).abs() <= FLAT_GAP * l {
                flat += b.s - a.s;
            }
            let (da, db) = (slope(&a.state), slope(&b.state));
            if da < 0.0 && db >= 0.0 {
                // A local minimum inside: the root of the slope, by Illinois' regula falsi from `a`.
                let (mut lo, mut hi, mut flo, mut fhi) = (a.s, b.s, da, db);
                let mut at = a.state;
                let mut side = 0;
                for _ in 0..60 {
                    let mid = (lo * fhi - hi * flo) / (fhi - flo);
                    let mid = if mid > lo && mid < hi { mid } else { 0.5 * (lo + hi) };
                    let Ok(q) = sh.advance(a, mid) else { break };
                    at = q;
                    let fm = slope(&q);
                    if fm < 0.0 {
                        (lo, flo) = (mid, fm);
                        if side == -1 {
                            fhi *= 0.5;
                        }
                        side = -1;
                    } else {
                        (hi, fhi) = (mid, fm);
                        if side == 1 {
                            flo *= 0.5;
                        }
                        side = 1;
                    }
                    if hi - lo <= 1e-12 * l || fm == 0.0 {
                        break;
                    }
                }
                let s = 0.5 * (lo + hi);
                let q = sh.advance(a, s).unwrap_or(at);
                consider(s, &q);
            }
            consider(a.s, &a.state);
        }
        if let Some(last) = samples.last() {
            consider(last.s, &last.state);
        }
        if flat > FLAT_LENGTH * l {
            return Some(Violation::Flat(o));
        }
        if let Some((_, s)) = worst {
            found.push(Violation::Touch { obstacle: o, s });
        }
    }
    found.into_iter().min_by_key(|v| match v {
        Violation::Open(_) => 0,
        Violation::Roll(_) => 1,
        Violation::Slip(..) => 2,
        Violation::Stick(_) => 3,
        Violation::Touch { .. } => 4,
        Violation::Flat(_) | Violation::Unroll(_) => 5,
    })
}

#[allow(clippy::too_many_arguments)]
fn solution(
    sh: &Shooting,
    x: &[f64],
    lambda: f64,
    seen: &[Seen],
    samples: &[Sample],
    steps: usize,
    events: Vec<ContactEvent>,
    stop: ContactStop,
) -> ContactSolution {
    let mut contacts: Vec<ContactPoint> = sh
        .active
        .iter()
        .zip(seen)
        .map(|(a, q)| {
            let t = [-q.normal[1], q.normal[0]];
            ContactPoint {
                obstacle: a.obstacle,
                s: q.s,
                point: q.point,
                normal: q.normal,
                normal_force: q.force[0] * q.normal[0] + q.force[1] * q.normal[1],
                friction_force: q.force[0] * t[0] + q.force[1] * t[1],
                gap: q.gap,
                state: match a.law {
                    Law::Frictionless => ContactState::Closed,
                    Law::Stick { .. } => ContactState::Stick,
                    Law::Slip { .. } => ContactState::Slip,
                },
            }
        })
        .collect();
    contacts.sort_by(|a, b| a.s.total_cmp(&b.s));
    let (load, _) = sh.load(lambda);
    let mut reaction = [-load.fx, -load.fy];
    for q in seen {
        reaction[0] -= q.force[0];
        reaction[1] -= q.force[1];
    }
    let shape = samples.iter().map(|p| cross_section(sh.flexure, p.s, &p.state)).collect();
    ContactSolution { shape, contacts, root_moment: x[0] * sh.k, reaction, load: lambda, steps, events, stop }
}
