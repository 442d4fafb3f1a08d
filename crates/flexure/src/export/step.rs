//! Sizing the model for a simulator's time step: the armature that keeps
//! every sprung joint's own oscillation resolved by the step.
//!
//! A joint of stiffness $k_1$ moving a link of inertia $I$ about it (its
//! rotary inertia plus $m\lvert c - a\rvert^2$, $c$ its centre of mass and
//! $a$ the hinge; for a slide, its mass) rings at $\omega = \sqrt{k_1/I}$.
//! MuJoCo's Euler step is stable for $\omega\Delta t < 2$ and follows the
//! motion for $\omega\Delta t$ well below it; a pseudo-rigid link of a light
//! flexure, or a massless body, rings far faster (the finger's links at the
//! mass floor: $\omega\Delta t \sim 10^4$). Such a joint is given the armature
//! (rotor inertia on its coordinate) that brings it to a period of
//! $n$ = [`STEPS_PER_PERIOD`] steps:
//! $$I_a = k_1\left(\frac{n\Delta t}{2\pi}\right)^2 - I.$$
//! An armature adds inertia and nothing else: the balance is unchanged,
//! the motion of the light parts is slowed (their own modes, far above the
//! step's reach, come down to $2\pi/(n\Delta t)$).

use super::model::{LinkMotion, RigidModel};
use crate::error::{Error, Result};

/// Steps per period of the fastest joint's own oscillation after its
/// armature is added: $\omega\Delta t = 2\pi/10 \approx 0.63$, a third of
/// the explicit step's limit of 2.
pub const STEPS_PER_PERIOD: f64 = 10.0;

/// MuJoCo's default time step (s).
pub const DEFAULT_STEP: f64 = 0.002;

/// Checks a step: finite and zero (no sizing) or greater; errors name `step`.
pub fn validate(step: f64) -> Result<()> {
    if step.is_finite() && step >= 0.0 {
        Ok(())
    } else {
        Err(Error::invalid("step", step, "must be a finite time step (s), zero (no sizing) or greater"))
    }
}

/// Adds to each sprung joint of `model` the armature that slows its own
/// link's oscillation to [`STEPS_PER_PERIOD`] steps of `step` (none when
/// `step` is zero), and returns each joint given one, with the armature
/// added (kg·m², or kg for a slide), in link order.
///
/// # Example
/// ```
/// use flexure::export::{model, step};
/// let m = flexure::mechanism::file::from_toml(
///     "[[joint]]\nname = \"h\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"a\"\nstiffness = 4.0\n\
///      [[body]]\nname = \"a\"\nmass = 1e-3\ninertia = 1e-8\n",
/// )?;
/// let mut rigid = model::build(&m, &[None], 0.0, true)?;
/// let added = step::size(&mut rigid, 0.002)?;
/// // k (10 Δt / 2π)² = 4 × 1.013e-5 kg·m², less the link's own 1e-8.
/// let want = 4.0 * (10.0 * 0.002 / std::f64::consts::TAU).powi(2) - 1e-8;
/// assert_eq!(added.len(), 1);
/// assert!((added[0].1 - want).abs() < 1e-15);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn size(model: &mut RigidModel, step: f64) -> Result<Vec<(String, f64)>> {
    validate(step)?;
    let mut added = Vec::new();
    if step == 0.0 {
        return Ok(added);
    }
    let period = STEPS_PER_PERIOD * step / std::f64::consts::TAU;
    for l in model.links.iter_mut().skip(1) {
        let inertia = &l.inertia;
        // Each joint's motion of the link at rest: its turn, and its centre
        // of mass's velocity, per unit rate.
        let motions: Vec<(f64, [f64; 2])> = l
            .joints
            .iter()
            .map(|j| match j.motion {
                LinkMotion::Hinge => (1.0, [-(inertia.com[1] - j.at.y), inertia.com[0] - j.at.x]),
                LinkMotion::Slide => (0.0, [j.axis.x, j.axis.y]),
            })
            .collect();
        let m = |a: usize, b: usize| {
            let ((wa, va), (wb, vb)) = (motions[a], motions[b]);
            inertia.inertia * wa * wb + inertia.mass * (va[0] * vb[0] + va[1] * vb[1])
        };
        for (name, a) in armature_for(&mut l.joints, m, period) {
            added.push((name, a));
        }
    }
    Ok(added)
}

/// The armature each sprung joint of one link needs, added to it: the
/// link's mass matrix over its joints at rest is `m(a, b)` (its own, not
/// its children's). Each joint alone would ring at $\sqrt{k_1/(M_{jj}+I_a)}$;
/// several on one link (a massless flexure's merged chain) also move it in
/// combinations, one of which may turn it about its centre of mass alone,
/// its least inertia. So with $D = \mathrm{diag}(k_{1,j})\tau^2$,
/// $\tau = n\Delta t/2\pi$, each gets $I_a = sD_{jj}$, $s = 1 - \mu$ (none
/// if $\mu \ge 1$), $\mu$ the least eigenvalue of $D^{-1/2}(M + A_0)D^{-1/2}$:
/// then $M + A \succeq D$, and no mode of the link's springs rings faster
/// than $n$ steps. One joint: $I_a = D - M - A_0$, as before.
fn armature_for(
    joints: &mut [super::model::ModelJoint],
    m: impl Fn(usize, usize) -> f64,
    period: f64,
) -> Vec<(String, f64)> {
    let sprung: Vec<usize> =
        (0..joints.len()).filter(|&j| joints[j].stiffness[0].is_finite() && joints[j].stiffness[0] > 0.0).collect();
    let mut added = Vec::new();
    if sprung.is_empty() {
        return added;
    }
    let need: Vec<f64> = sprung.iter().map(|&j| joints[j].stiffness[0] * period * period).collect();
    let own = |a: usize, b: usize| m(sprung[a], sprung[b]) + if a == b { joints[sprung[a]].armature } else { 0.0 };
    for (&j, a) in sprung.iter().zip(added_inertia(&need, own)) {
        if a > 0.0 {
            joints[j].armature += a;
            added.push((joints[j].name.clone(), a));
        }
    }
    added
}

/// The armature to add to each of a link's sprung joints ([`armature_for`]'s
/// rule, in either dimension): `need` is each joint's $k_1\tau^2$, `own(a, b)`
/// the link's mass matrix over them with the armature already on them.
pub(crate) fn added_inertia(need: &[f64], own: impl Fn(usize, usize) -> f64) -> Vec<f64> {
    let n = need.len();
    if n == 1 {
        return vec![(need[0] - own(0, 0)).max(0.0)];
    }
    let scaled = nalgebra::DMatrix::from_fn(n, n, |a, b| own(a, b) / (need[a] * need[b]).sqrt());
    let s = (1.0 - scaled.symmetric_eigenvalues().min()).max(0.0);
    need.iter().map(|d| s * d).collect()
}

/// Where a spring $\tau = k_1 x + k_2 x^2 + k_3 x^3$ stops holding: the
/// nearest coordinates either side of rest at which its tangent stiffness
/// $k_1 + 2k_2x + 3k_3x^2$ vanishes (each `None` where it never does).
/// A fitted cubic is checked stiff over the range it was fitted on and a
/// quarter beyond; past these it pushes away from rest, and a hinge that
/// overshoots there (a load applied at once, undamped) runs away. MJCF
/// writes them as the hinge's `range`, a limit that is not met at rest.
///
/// # Example
/// ```
/// use flexure::export::step::soft_limits;
/// // τ = x - x³: tangent 1 - 3x², zero at x = ±1/√3.
/// let (lo, hi) = soft_limits([1.0, 0.0, -1.0]);
/// let r = 1.0 / 3f64.sqrt();
/// assert!((lo.unwrap() + r).abs() < 1e-15 && (hi.unwrap() - r).abs() < 1e-15);
/// // τ = x - x²: tangent 1 - 2x, zero at x = 1/2 only.
/// assert_eq!(soft_limits([1.0, -1.0, 0.0]), (None, Some(0.5)));
/// assert_eq!(soft_limits([1.0, 0.0, 1.0]), (None, None));
/// ```
pub fn soft_limits(k: [f64; 3]) -> (Option<f64>, Option<f64>) {
    let (a, b, c) = (3.0 * k[2], 2.0 * k[1], k[0]);
    if c.is_nan() || c <= 0.0 {
        return (None, None);
    }
    let mut roots = Vec::new();
    if a == 0.0 {
        if b != 0.0 {
            roots.push(-c / b);
        }
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            // The stable pair: q = -(b + sign(b)√disc)/2, roots q/a and c/q.
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            if q != 0.0 {
                roots.push(c / q);
            }
            roots.push(q / a);
        }
    }
    let lo = roots.iter().copied().filter(|r| *r < 0.0).fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))));
    let hi = roots.iter().copied().filter(|r| *r > 0.0).fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.min(r))));
    (lo, hi)
}
