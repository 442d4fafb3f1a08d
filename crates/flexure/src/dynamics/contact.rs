//! Motion with contact: the equations of motion of a mechanism whose parts
//! touch its geoms ([`crate::mechanism::contact`]), as a [`System`] that
//! changes its mode where a contact touches or opens ([`ContactSystem`]).
//!
//! **A touching contact** holds its gap at zero: it is a closure row
//! $g_c(q) = 0$ after the mechanism's own, with the gradient
//! $\nabla_q g_c$ ([`gap_slope`]), and its multiplier is the push of the
//! geom, $N_c = -\lambda_c$. Inside a flexure's span it sits where the gap is
//! least, $\partial_s g_c = 0$, which Newton's method in $s$ keeps at each
//! evaluation from the last place; since $s$ minimizes $g$, the gradient at
//! fixed $s$ is the whole gradient. At an end it stays while the gap rises
//! into the span. Frictionless: no force along the surface.
//!
//! **Events** ([`System::guards`]): an open pair's least gap (each least of
//! its flexure but those within a hundredth of its length of a touching
//! contact of the same pair) falling below zero, and a touching contact's
//! $N_c$ falling below zero. The integrator lands on each within a band: the
//! gap to `tolerance` × the mechanism's size, the push to `tolerance` × the
//! largest push the contact has carried. A contact that touches while its
//! parts approach ($\dot g_c < 0$) takes a perfectly inelastic impact: the
//! first step of the new mode, whose stages keep the gap closed, takes the
//! normal speed away (for Radau IIA exactly, for closures linear over the
//! step), so the impact dissipates energy and never adds any. A pair that
//! reaches zero gap without approaching is not held: it touches when it
//! presses in. A contact that pulls at its first step is let go there.
//!
//! **Refused by name:** friction in motion (a geom with `friction` > 0 that
//! a part may touch), and a start where a part overlaps a geom.

use super::mechanism::Dynamics;
use super::schedule::ScheduledSystem;
use super::system::System;
use crate::error::{Error, Result};
use crate::kinematics::Level;
use crate::mechanism::Mechanism;
use crate::mechanism::contact::{
    Contact, ContactMode, Gap, GapSlope, Pair, Toucher, column, gap_slope, minima, named, pairs,
};
use crate::mechanism::kinematics::{Frames, frames_level_into};

/// Two leasts of one pair closer than this × the flexure's length are one contact.
const NEAR: f64 = 1e-2;
/// Newton iterations for a contact's place along its flexure.
const PLACE_ITERATIONS: usize = 30;

/// A touching contact: its pair, its place on a flexure, and the push it carries.
#[derive(Debug, Clone, Copy)]
struct Held {
    pair: Pair,
    s: Option<f64>,
    /// Its flexure's length (m; 1 between geoms).
    length: f64,
    /// The last push reported (N), and the largest it has carried.
    force: f64,
    largest: f64,
}

/// A change of a contact during a motion: when, which pair (its column
/// name, `contact.GEOM.PART`) and what it became.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ContactChange {
    /// The time (s).
    pub time: f64,
    /// The pair, as a sweep's column names it.
    pub contact: String,
    /// `"slip"` where it touched (frictionless), `"open"` where it opened.
    pub state: ContactMode,
}

/// A mechanism's motion with its contacts (module docs): the scheduled
/// equations of motion ([`ScheduledSystem`]) with a closure row for each
/// touching contact, and the contacts at each sample.
#[derive(Debug, Clone)]
pub struct ContactSystem<D: Dynamics> {
    inner: ScheduledSystem<D>,
    mechanism: Mechanism<D>,
    pairs: Vec<Pair>,
    held: Vec<Held>,
    frames: Frames<D>,
    /// The relative band of the events ([`crate::dynamics::integrate::MotionSettings::tolerance`]) and the gap's (m).
    tolerance: f64,
    gap_band: f64,
    /// The mechanism's own closure Jacobian ($m_0\times n$).
    own: Vec<f64>,
    /// The contacts at each sample, and the changes so far.
    samples: Vec<Vec<Contact>>,
    changes: Vec<ContactChange>,
}

impl<D: Dynamics> ContactSystem<D> {
    /// The motion of `m` with its contacts, from `q0` where the contacts of
    /// `touching` (an equilibrium's, say) touch with their pushes, events
    /// landed on within `tolerance` (relative).
    ///
    /// Errors: friction on a geom a part may touch, a part that overlaps a
    /// geom at `q0` by more than the band, those of [`ScheduledSystem::new`].
    pub fn new(m: &Mechanism<D>, q0: &[f64], touching: &[Contact], tolerance: f64) -> Result<Self> {
        let all = pairs(m);
        if let Some(p) = all.iter().find(|p| m.geoms[p.geom].friction > 0.0 || rough_ball(m, p)) {
            return Err(Error::invalid(
                "friction",
                named(m, p),
                "may touch in motion, which is frictionless yet: set the geom's friction to 0 for `simulate` (solve and sweep take it)",
            ));
        }
        let held = touching
            .iter()
            .filter(|c| c.state != ContactMode::Open)
            .map(|c| Held {
                pair: c.pair,
                s: c.s,
                length: length(m, &c.pair),
                force: c.normal_force,
                largest: c.normal_force,
            })
            .collect();
        let mut system = ContactSystem {
            inner: ScheduledSystem::new(m)?,
            mechanism: m.clone(),
            pairs: all,
            held,
            frames: Frames::new(m),
            tolerance,
            gap_band: tolerance * m.size(),
            own: vec![0.0; m.constraints() * m.dof()],
            samples: Vec::new(),
            changes: Vec::new(),
        };
        frames_level_into(m, q0, Level::Jacobian, &mut system.frames);
        for k in 0..system.pairs.len() {
            let pair = system.pairs[k];
            if let Some(low) = system.open_least(&pair, q0)?
                && low.gap < -system.gap_band
            {
                return Err(Error::invalid(
                    "geom",
                    format!("{} (overlapping by {:.3e} m)", named(m, &pair), -low.gap),
                    "overlap where the motion starts: start from an equilibrium, or move the geom or the [initial] coordinates apart",
                ));
            }
        }
        Ok(system)
    }

    /// The scheduled system within.
    pub fn inner(&mut self) -> &mut ScheduledSystem<D> {
        &mut self.inner
    }

    /// The contacts at each sample recorded so far: each touching contact,
    /// then each pair that does not touch, at its least gap.
    pub fn samples(&self) -> &[Vec<Contact>] {
        &self.samples
    }

    /// The contacts' changes so far, in time.
    pub fn changes(&self) -> &[ContactChange] {
        &self.changes
    }

    /// The least gap of `pair` at `q` (frames at `q` in `self.frames`) away
    /// from its touching contacts; `None` when every least is touching.
    fn open_least(&self, pair: &Pair, q: &[f64]) -> Result<Option<Gap<D>>> {
        let mine: Vec<&Held> = self.held.iter().filter(|h| h.pair == *pair).collect();
        let apart = |g: &Gap<D>| match g.s {
            Some(s) => mine.iter().all(|h| h.s.is_none_or(|t| (s - t).abs() > NEAR * h.length)),
            None => mine.is_empty(),
        };
        let found = minima(&self.mechanism, q, &self.frames.bodies, pair)?;
        Ok(found.into_iter().filter(apart).min_by(|a, b| a.gap.total_cmp(&b.gap)))
    }

    /// Touching contact `i` at `q` (frames in `self.frames`, Jacobian level):
    /// its place settled where the gap is least (module docs), and its gap there.
    fn settle(&mut self, i: usize, q: &[f64]) -> Result<GapSlope<D>> {
        let (m, f) = (&self.mechanism, &self.frames);
        let Held { pair, s, length, .. } = self.held[i];
        let Some(mut s) = s else { return gap_slope(m, f, q, &pair, None) };
        for _ in 0..PLACE_ITERATIONS {
            let slope = gap_slope(m, f, q, &pair, Some(s))?;
            // At an end the gap rises into the span: it stays there.
            let stays = (s <= 0.0 && slope.ds >= 0.0) || (s >= length && slope.ds <= 0.0);
            if stays || (slope.ds.abs() <= 1e-12 && slope.dss > 0.0) {
                self.held[i].s = Some(s);
                return Ok(slope);
            }
            let next = if slope.dss > 0.0 {
                (s - slope.ds / slope.dss).clamp(0.0, length)
            } else {
                // Not convex here: the sampled least nearest.
                let found = minima(m, q, &f.bodies, &pair)?;
                let near = found.iter().filter_map(|g| g.s).min_by(|a, b| (a - s).abs().total_cmp(&(b - s).abs()));
                near.unwrap_or(s)
            };
            if (next - s).abs() <= 1e-13 * length {
                self.held[i].s = Some(next);
                return gap_slope(m, f, q, &pair, Some(next));
            }
            s = next;
        }
        Err(Error::Singular {
            what: format!(
                "the place of the contact of {} did not settle in {PLACE_ITERATIONS} Newton steps",
                named(m, &pair)
            ),
        })
    }

    fn report(&mut self, q: &[f64], multipliers: Option<&[f64]>) -> Result<Vec<Contact>> {
        let m0 = self.inner.closures();
        frames_level_into(&self.mechanism, q, Level::Jacobian, &mut self.frames);
        let none = D::Vector::default();
        let mut out = Vec::new();
        for i in 0..self.held.len() {
            if let Some(l) = multipliers {
                self.held[i].force = -l[m0 + i];
            }
            let slope = self.settle(i, q)?;
            let h = self.held[i];
            let place = (h.s, &slope.point, &slope.normal, slope.gap);
            out.push(Contact::of(&self.mechanism, &h.pair, place, (h.force.max(0.0), &none), ContactMode::Slip));
        }
        for pair in self.pairs.clone() {
            if self.held.iter().any(|h| h.pair == pair) {
                continue;
            }
            if let Some(low) = self.open_least(&pair, q)? {
                let place = (low.s, &low.point, &low.normal, low.gap);
                out.push(Contact::of(&self.mechanism, &pair, place, (0.0, &none), ContactMode::Open));
            }
        }
        Ok(out)
    }
}

/// A pair of two geoms whose other geom is rough.
fn rough_ball<D: Dynamics>(m: &Mechanism<D>, p: &Pair) -> bool {
    matches!(p.part, Toucher::Geom(h) if m.geoms[h].friction > 0.0)
}

/// The length of the flexure of `pair` (1 between geoms).
fn length<D: Dynamics>(m: &Mechanism<D>, pair: &Pair) -> f64 {
    match pair.part {
        Toucher::Flexure(j) => m.joints[j].kind.flexure().map_or(1.0, D::flexure_length),
        Toucher::Geom(_) => 1.0,
    }
}

impl<D: Dynamics> System for ContactSystem<D> {
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    fn closures(&self) -> usize {
        self.inner.closures() + self.held.len()
    }

    fn dynamics(&mut self, q: &[f64], v: &[f64], t: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
        self.inner.dynamics(q, v, t, mass, force)
    }

    fn tangent(&mut self, q: &[f64], v: &[f64], t: f64, stiffness: &mut [f64], damping: &mut [f64]) -> Result<()> {
        self.inner.tangent(q, v, t, stiffness, damping)
    }

    fn closure(&mut self, q: &[f64], c: &mut [f64], g: &mut [f64]) -> Result<()> {
        let (n, m0) = (self.dim(), self.inner.closures());
        let rows = self.closures();
        if m0 > 0 {
            self.inner.closure(q, &mut c[..m0], &mut self.own)?;
            for col in 0..n {
                g[col * rows..col * rows + m0].copy_from_slice(&self.own[col * m0..(col + 1) * m0]);
            }
        }
        if self.held.is_empty() {
            return Ok(());
        }
        frames_level_into(&self.mechanism, q, Level::Jacobian, &mut self.frames);
        for i in 0..self.held.len() {
            let slope = self.settle(i, q)?;
            c[m0 + i] = slope.gap;
            for col in 0..n {
                g[col * rows + m0 + i] = slope.gradient[col];
            }
        }
        Ok(())
    }

    fn energy(&mut self, q: &[f64], v: &[f64], t: f64) -> Result<f64> {
        self.inner.energy(q, v, t)
    }

    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        self.inner.distance(a, b)
    }

    fn jumps(&self) -> Vec<f64> {
        self.inner.jumps()
    }

    fn guard_count(&self) -> usize {
        self.held.len() + self.pairs.len()
    }

    /// Each touching contact's push over its band, then each pair's least
    /// open gap over its band (module docs).
    fn guards(&mut self, q: &[f64], _v: &[f64], multipliers: Option<&[f64]>, out: &mut [f64]) -> Result<()> {
        let m0 = self.inner.closures();
        for (i, h) in self.held.iter_mut().enumerate() {
            out[i] = match multipliers {
                None => 1.0,
                Some(l) => {
                    let push = -l[m0 + i];
                    if h.largest <= 0.0 && push < 0.0 {
                        // Pulling from its first step: let go at once.
                        -0.5
                    } else {
                        h.largest = h.largest.max(push);
                        push / (self.tolerance * h.largest)
                    }
                }
            };
        }
        frames_level_into(&self.mechanism, q, Level::Pose, &mut self.frames);
        let a = self.held.len();
        for k in 0..self.pairs.len() {
            let pair = self.pairs[k];
            out[a + k] = self.open_least(&pair, q)?.map_or(f64::MAX, |g| g.gap / self.gap_band);
        }
        Ok(())
    }

    /// A pair that touches while approaching is held; a touching contact
    /// that pulls is let go.
    fn switch(&mut self, ks: &[usize], t: f64, q: &[f64], v: &[f64]) -> Result<()> {
        let a = self.held.len();
        frames_level_into(&self.mechanism, q, Level::Jacobian, &mut self.frames);
        let mut added = Vec::new();
        for &k in ks.iter().filter(|&&k| k >= a) {
            let pair = self.pairs[k - a];
            let Some(low) = self.open_least(&pair, q)? else { continue };
            let slope = gap_slope(&self.mechanism, &self.frames, q, &pair, low.s)?;
            let approach: f64 = slope.gradient.iter().zip(v).map(|(g, v)| g * v).sum();
            if approach < 0.0 {
                let length = length(&self.mechanism, &pair);
                added.push(Held { pair, s: low.s, length, force: 0.0, largest: 0.0 });
            }
        }
        let released: Vec<usize> = ks.iter().copied().filter(|&k| k < a).collect();
        for &i in released.iter().rev() {
            let h = self.held.remove(i);
            let contact = column(&self.mechanism, &h.pair);
            self.changes.push(ContactChange { time: t, contact, state: ContactMode::Open });
        }
        for h in added {
            let contact = column(&self.mechanism, &h.pair);
            self.changes.push(ContactChange { time: t, contact, state: ContactMode::Slip });
            self.held.push(h);
        }
        Ok(())
    }

    fn sampled(&mut self, _t: f64, q: &[f64], _v: &[f64], multipliers: Option<&[f64]>) -> Result<()> {
        let contacts = self.report(q, multipliers)?;
        self.samples.push(contacts);
        Ok(())
    }
}
