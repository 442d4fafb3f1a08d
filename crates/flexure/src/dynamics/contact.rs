//! Motion with contact: the equations of motion of a mechanism whose parts
//! touch its geoms ([`crate::mechanism::contact`]), as a [`System`] that
//! changes its mode where a contact touches, opens, sticks or slips
//! ([`ContactSystem`]).
//!
//! **A touching contact** holds its gap at zero: it is a closure row
//! $g_c(q) = 0$ after the mechanism's own, with the gradient
//! $\nabla_q g_c$ ([`gap_slope`]), and its multiplier is the push of the
//! geom, $N_c = -\lambda_c$. Inside a flexure's span it sits where the gap is
//! least, $\partial_s g_c = 0$, which Newton's method in $s$ keeps at each
//! evaluation from the last place; since $s$ minimizes $g$, the gradient at
//! fixed $s$ is the whole gradient. At an end it stays while the gap rises
//! into the span. A sharp corner on a face of a box or a cylinder is held
//! against that face's plane, fixed in its geom's body, so that its gap is
//! smooth up to where it slides past the face's edge and is let go.
//!
//! **Friction** (Coulomb's $\mu$: a flexure's geom's, or the larger of two
//! geoms', as MuJoCo combines them). Where the touching point is material
//! (a flexure's bare end, or a ball whose body only translates against the
//! geom's: sliders between them), **stuck**, the point $x$ is held at a
//! material point $a$ of the geom's body: its rows are $x - a = 0$ and the
//! force on it is $-\lambda$ (its normal part $N$, its tangential part
//! $f_t$). Where it is not (inside a flexure's span, at a thick strip's
//! end, a ball that turns against the geom), the touching point moves over
//! both surfaces as they roll, and **stuck** means rolling without
//! slipping: the velocity of the toucher's material point at the contact
//! relative to the geom's material point there, $\Delta_m\dot q$, is zero
//! along the surface. It keeps its gap row and adds one row per tangent
//! $t_k$, $t_k^T\Delta_m\dot q = 0$, held on the velocities
//! ([`System::velocity_closures`]: in space rolling is not integrable,
//! no function of $q$ says it), the force along them $-\sum_k\lambda_kt_k$.
//! **Sliding** along $\hat s$, the direction of its (material point's)
//! velocity $v_t$ relative to the geom in the tangent plane, it keeps its
//! gap row and takes the force $N(n - \mu\hat s)$: its multiplier acts along
//! $\nabla g - \mu\hat s^T\Delta$ ([`System::closure_forces`]; $\Delta$ the
//! material point's Jacobian relative to the geom), so friction does work
//! only against the sliding. ($\hat s$ is $v_t$ normalized with the direction
//! it slid in, $\hat s_0$, added at $10^{-12}$ of the mechanism's size per
//! second, so a slide that starts from rest has a direction; each in the
//! tangent plane.)
//!
//! **Events** ([`System::guards`], three per touching contact, then one per
//! pair): a touching contact's $N$ falling below zero opens it, and so
//! does its leaving where it applies (two edges' crossing running off
//! either edge, a corner sliding past the edge of the face it touches,
//! where the normal jumps to the next face's); a stuck
//! one's $\mu N - \lvert f_t\rvert$ falling below zero slips it, toward
//! $-f_t$; a sliding one's $v_t\cdot\hat s_0$ ($\hat s_0$ the direction it
//! slid in at the last step accepted, [`System::accepted`]: in space a
//! slide turns as it goes) falling below zero sticks it where it is; an open pair's
//! least gap (each least of its flexure but those within a hundredth of its
//! length of a touching contact of the same pair) falling below zero
//! touches. The integrator lands on each within a band: a gap to
//! `tolerance` × the mechanism's size, a force or speed to `tolerance` ×
//! the largest the contact has had at the steps accepted (a speed, at least
//! what the integrator resolves of it: each rate to the
//! tolerance of itself, each moving the point by its $\Delta_c$). A slip
//! begins where a stuck contact needs more than $\mu N$ past its guard's
//! band, and turns back at its first step only past the speed it still had
//! the other way where it began. A contact that touches while its parts
//! approach ($\dot g_c < 0$) takes a perfectly inelastic impact (the
//! integrator's projection onto the new closures: the energy never grows);
//! with friction it slides on the way it moves after the impact (which can
//! turn a slide back: a turning body takes the normal impulse too), or
//! sticks where it touched without sliding. A stuck contact's rows that
//! depend on the rows before them are left out (a Gram–Schmidt of $G$):
//! what they would hold is held, and their force is indeterminate. A pair that reaches zero gap without approaching
//! is not held: it touches when it presses in. A contact that pulls at its
//! first step is let go there.
//!
//! **Refused by name**, met in the run (it stops there, with the samples
//! reached): friction where a
//! bare end with friction would roll onto its span; and a start where a part
//! overlaps a geom.

use super::integrate::consistent_multipliers;
use super::mechanism::Dynamics;
use super::schedule::ScheduledSystem;
use super::system::System;
use crate::error::{Error, Result};
use crate::kinematics::Level;
use crate::linalg;
use crate::mechanism::Mechanism;
use crate::mechanism::contact::{
    COMING_BACK, Contact, ContactMode, Gap, GapSlope, Geom, GeomShape, Material, PASSED_THROUGH, Pair, PointJet,
    Toucher, array, came_back, column, corner, crossed_edges, crossing_of, dot, friction, gap_slope, gap_slope_on,
    length, material_jet, may_cross, minima, named, on_flexure, pairs, point_jet, ran_off, scaled, tangents, vector,
};
use crate::mechanism::kinematics::{Frames, frames_level_into};

/// Two leasts of one pair closer than this × the flexure's length are one contact.
const NEAR: f64 = 1e-2;
/// The move (× the mechanism's size) over which a pair's gap is read ahead
/// of the state ([`ContactSystem::parts_ahead`]), and the share of its
/// fastest rate above which it parts.
const AHEAD: f64 = 1e-7;
const PARTS: f64 = 1e-3;
/// The guards of each touching contact ([`System::guards`]): its push, its
/// friction's, and how far it lies within where it applies.
const HELD_GUARDS: usize = 3;
/// Newton iterations for a contact's place along its flexure.
const PLACE_ITERATIONS: usize = 30;
/// The speed (× the mechanism's size, per second) at which a slide's last
/// direction is added to its velocity, so a slide from rest has a direction.
const CREEP: f64 = 1e-12;

/// How a touching contact holds along the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Law {
    /// Frictionless.
    Free,
    /// Stuck at `anchor`, a material point of the geom's body (its frame).
    Stick { anchor: [f64; 3] },
    /// Sliding in the direction `from` (a unit tangent, world: where it
    /// began, then at each step accepted), its fastest speed so far
    /// `fastest`; `lag`, the speed it still had the other way where it
    /// began from stuck (a stop landed a little past its turn), which it
    /// sheds before it can turn back.
    Slip { from: [f64; 3], fastest: f64, lag: f64 },
    /// Rolling without slipping: the velocity of the toucher's material
    /// point where it touches, relative to the geom's there, held at zero
    /// along the surface's tangents, those nearest `tangents` (world, kept
    /// from sample to sample so that in space they turn smoothly).
    Roll { tangents: [[f64; 3]; 2] },
}

/// A touching contact: its pair, its place on a flexure, its law, and the forces it carries.
#[derive(Debug, Clone, Copy)]
struct Held {
    pair: Pair,
    s: Option<f64>,
    /// Its flexure's length (m; 1 between geoms).
    length: f64,
    law: Law,
    /// Whether it rolls: the point that touches is not one material point
    /// (inside a span, a thick flexure, a ball that turns against the geom).
    rolls: bool,
    /// Coulomb's $\mu$ of the pair.
    mu: f64,
    /// Its stuck rows left out, each dependent on the rows before it (a
    /// pendulum's bob on a floor: the gap stops its one coordinate, and
    /// nothing is left to slide): [`ContactSystem::prune`].
    dropped: [bool; 3],
    /// A stuck one's tangents where [`ContactSystem::prune`] turned them
    /// (world; else those of [`tangents`]).
    axes: Option<[[f64; 3]; 2]>,
    /// A sharp corner's on a face of a box or a cylinder: that face's plane where
    /// it touched, its point and outward normal in the frame of the body of
    /// the geom touched ([`ContactSystem::face_of`]), held in place of the
    /// geom up to where the corner slides past the face's edge and is let go.
    face: Option<[[f64; 3]; 2]>,
    /// The last push (N) and friction force (world) reported, and the largest push it has carried.
    force: f64,
    friction: [f64; 3],
    largest: f64,
}

impl Held {
    /// Its closure rows: the point's components when stuck (a rolling one:
    /// its gap, then its tangents), else the gap; each with whether it is
    /// held (not [`Held::dropped`]).
    fn all_rows<D: Dynamics>(&self) -> impl Iterator<Item = bool> + '_ {
        let all = if matches!(self.law, Law::Stick { .. } | Law::Roll { .. }) { D::POINT_DIM } else { 1 };
        (0..all).map(|k| !self.dropped[k])
    }

    /// The number of its rows held.
    fn rows<D: Dynamics>(&self) -> usize {
        self.all_rows::<D>().filter(|&held| held).count()
    }

    /// Where each of its rows sits among the closures, its first held row
    /// at `first` (`None`: left out, or beyond its rows).
    fn slots<D: Dynamics>(&self, first: usize) -> [Option<usize>; 3] {
        let mut slots = [None; 3];
        let mut next = first;
        for (k, held) in self.all_rows::<D>().enumerate() {
            if held {
                slots[k] = Some(next);
                next += 1;
            }
        }
        slots
    }
}

/// A change of a contact during a motion: when, which pair (its column
/// name, `contact.GEOM.PART`) and what it became.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ContactChange {
    /// The time (s).
    pub time: f64,
    /// The pair, as a sweep's column names it.
    pub contact: String,
    /// What it became: `"slip"` where it touched without friction or began
    /// to slide, `"stick"` where friction holds it, `"open"` where it opened.
    pub state: ContactMode,
    /// The pair it is of, at its corner between two geoms (not serialized:
    /// `contact` names the two parts, and each corner of two geoms is a
    /// pair of its own).
    #[serde(skip)]
    pub pair: Pair,
}

/// What a touching contact is doing at a state ([`ContactSystem::read`]).
struct Reading<D: Dynamics> {
    slope: GapSlope<D>,
    /// Its normal push (N), its friction force (world), and its speed along the surface (world).
    push: f64,
    friction: D::Vector,
    slide: D::Vector,
    /// Its point's Jacobian relative to the geom, $\Delta_c$ per coordinate (world).
    delta: Vec<D::Vector>,
}

/// A mechanism's motion with its contacts (module docs): the scheduled
/// equations of motion ([`ScheduledSystem`]) with closure rows for each
/// touching contact, and the contacts at each sample.
#[derive(Debug, Clone)]
pub struct ContactSystem<D: Dynamics> {
    inner: ScheduledSystem<D>,
    mechanism: Mechanism<D>,
    pairs: Vec<Pair>,
    held: Vec<Held>,
    frames: Frames<D>,
    /// The relative band of the events ([`crate::dynamics::integrate::MotionSettings::tolerance`]),
    /// the gap's (m), and the creep speed (m/s).
    tolerance: f64,
    gap_band: f64,
    creep: f64,
    /// The mechanism's own closure Jacobian ($m_0\times n$).
    own: Vec<f64>,
    /// The multipliers of the last guards' evaluation: where an event landed.
    last: Vec<f64>,
    /// The contacts at each sample, and the changes so far.
    samples: Vec<Vec<Contact>>,
    changes: Vec<ContactChange>,
}

impl<D: Dynamics> ContactSystem<D> {
    /// The motion of `m` with its contacts, from `q0` where the contacts of
    /// `touching` (an equilibrium's, say) touch with their pushes, events
    /// landed on within `tolerance` (relative).
    ///
    /// Errors: a part that overlaps a geom at `q0` by more than the band,
    /// friction where a contact of `touching` rolls, those of [`ScheduledSystem::new`].
    pub fn new(m: &Mechanism<D>, (q0, v0): (&[f64], &[f64]), touching: &[Contact], tolerance: f64) -> Result<Self> {
        let mut system = ContactSystem {
            inner: ScheduledSystem::new(m)?,
            mechanism: m.clone(),
            pairs: pairs(m),
            held: Vec::new(),
            frames: Frames::new(m),
            tolerance,
            gap_band: tolerance * m.size(),
            creep: CREEP * m.size(),
            own: vec![0.0; m.constraints() * m.dof()],
            last: Vec::new(),
            samples: Vec::new(),
            changes: Vec::new(),
        };
        system.frames_at(q0);
        for c in touching.iter().filter(|c| c.state != ContactMode::Open) {
            let mut h = system.touch(&c.pair, c.s, q0)?;
            h.force = c.normal_force;
            h.largest = c.normal_force;
            // An equilibrium's contact with friction is at rest, stuck (or
            // rolling), unless `[initial_velocity]` launches it along the
            // geom, or off it.
            let slope = gap_slope(m, &system.frames, q0, &h.pair, h.s)?;
            if gap_rate(&slope, v0) > system.creep {
                continue;
            }
            if h.mu > 0.0 {
                h.law = system.starting_law(&h, &slope.normal, (q0, v0))?;
            }
            system.hold(h, q0)?;
        }
        for k in 0..system.pairs.len() {
            let pair = system.pairs[k];
            let Some(low) = system.open_least(&pair, q0)? else { continue };
            if low.gap < -system.gap_band {
                return Err(overlap(m, &pair, -low.gap));
            }
            if low.gap <= system.gap_band {
                // Set on the geom: held from the start (let go at the first
                // step if it pulls), stuck unless it slides; open if it leaves.
                if gap_rate(&gap_slope(m, &system.frames, q0, &pair, low.s)?, v0) > system.creep {
                    continue;
                }
                let mut h = system.touch(&pair, low.s, q0)?;
                h.law = system.starting_law(&h, &low.normal, (q0, v0))?;
                system.hold(h, q0)?;
            }
        }
        system.prune(q0)?;
        Ok(system)
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

    /// A new touching contact of `pair` at `s` (frames at `q`), frictionless
    /// or, with friction, sliding as it moves (stuck if it does not): an
    /// error by name where friction would hold a contact that rolls.
    fn touch(&self, pair: &Pair, s: Option<f64>, q: &[f64]) -> Result<Held> {
        let m = &self.mechanism;
        let mu = friction(m, pair);
        let mut h = Held {
            pair: *pair,
            s,
            length: length(m, pair),
            law: Law::Free,
            rolls: false,
            mu,
            dropped: [false; 3],
            axes: None,
            face: self.face_of(pair, q)?,
            force: 0.0,
            friction: [0.0; 3],
            largest: 0.0,
        };
        if mu > 0.0 {
            let p = point_jet(m, &self.frames, q, pair, s, None)?;
            h.rolls = match pair.part {
                Toucher::Flexure(_) => p.half[0] != 0.0 || s.is_some_and(|s| s > 0.0 && s < h.length),
                // A box's sharp corner, or a point of an edge crossing another, is one material point: it does not roll.
                Toucher::Geom(h) => {
                    !corner(m, pair)?.sharp() && !self.translates_only(m.geoms[h].body, m.geoms[pair.geom].body)
                }
            };
            h.law = Law::Slip { from: [0.0; 3], fastest: 0.0, lag: 0.0 };
        }
        Ok(h)
    }

    /// The law of `h` as it touches where the geom's normal is `normal`
    /// (frames at `q`): frictionless, or with friction sliding on the way
    /// it moves along the surface, or stuck where it touches if it does not
    /// move along it.
    fn starting_law(&self, h: &Held, normal: &D::Vector, (q, v): (&[f64], &[f64])) -> Result<Law> {
        if h.law == Law::Free {
            return Ok(Law::Free);
        }
        let p = point_jet(&self.mechanism, &self.frames, q, &h.pair, h.s, None)?;
        // Rolling: its place and normal, for its material point and its tangents.
        let slope = match h.rolls {
            true => Some(gap_slope(&self.mechanism, &self.frames, q, &h.pair, h.s)?),
            false => None,
        };
        let delta = match &slope {
            Some(slope) => self.material_delta(h, &p, slope, q)?,
            None => p.delta.clone(),
        };
        let slide = sliding::<D>(&delta, v, normal);
        let speed = dot::<D>(&slide, &slide).sqrt();
        Ok(match (speed > self.creep, &slope) {
            (true, _) => Law::Slip { from: array::<D>(&scaled::<D>(&slide, 1.0 / speed)), fastest: speed, lag: 0.0 },
            (false, Some(slope)) => rolling::<D>(&slope.normal),
            (false, None) => Law::Stick { anchor: self.anchor(h, q)? },
        })
    }

    /// The toucher's material point where `h` touches (`p` its point,
    /// `slope` its gap there, frames at its state), as [`material_jet`]'s
    /// `on`, and the geom body's there (its frame).
    fn material(&self, h: &Held, p: &PointJet<'_, D>, slope: &GapSlope<D>) -> Result<(Material, [f64; 3])> {
        let (m, f) = (&self.mechanism, &self.frames);
        let local = |body: usize| array::<D>(&D::position(&D::act(&D::inverse(&f.bodies[body]), &slope.point)));
        let on = match h.s {
            Some(s) => on_flexure::<D>(s, &p.frame(), &slope.normal, p.half[0]),
            None => corner(m, &h.pair)?.material(&f.bodies, &slope.point),
        };
        Ok((on, local(p.shape.body)))
    }

    /// The Jacobian of the motion of the toucher's material point where `h`
    /// touches at `q` (`p` its point, `slope` its gap there), relative to the
    /// geom body's there: a rolling contact's slide is theirs.
    fn material_delta(&self, h: &Held, p: &PointJet<'_, D>, slope: &GapSlope<D>, q: &[f64]) -> Result<Vec<D::Vector>> {
        let (on, anchor) = self.material(h, p, slope)?;
        Ok(material_jet(&self.mechanism, &self.frames, q, &h.pair, &on, vector::<D>(&anchor))?.delta)
    }

    /// Whether body `a` only translates against body `b` (frames at Jacobian
    /// level): no coordinate between them turns either.
    fn translates_only(&self, a: usize, b: usize) -> bool {
        let m = &self.mechanism;
        let path = |mut body: usize| {
            let mut joints = Vec::new();
            while let Some(j) = m.parent_joint(body) {
                joints.push(j);
                body = m.joints[j].parent;
            }
            joints
        };
        let (pa, pb) = (path(a), path(b));
        let axes = [vector::<D>(&[1.0, 0.0, 0.0]), vector::<D>(&[0.0, 1.0, 0.0])];
        pa.iter().filter(|j| !pb.contains(j)).chain(pb.iter().filter(|j| !pa.contains(j))).all(|&j| {
            let (o, k) = (m.joints[j].offset, m.joints[j].kind.joint().dof());
            (o..o + k).all(|c| axes.iter().all(|e| D::spin(&self.frames.omega[c], e) == D::Vector::default()))
        })
    }

    /// Where contact `h`'s point is, in the frame of the body of the geom it
    /// touches (frames at `q`).
    fn anchor(&self, h: &Held, q: &[f64]) -> Result<[f64; 3]> {
        let p = point_jet(&self.mechanism, &self.frames, q, &h.pair, h.s, None)?;
        // The geom touched: of a ball and another geom, the other.
        let body = &self.frames.bodies[p.shape.body];
        Ok(array::<D>(&D::position(&D::act(&D::inverse(body), &p.x))))
    }

    /// The frames at `q`, Jacobian level: the integrator asks the closures,
    /// then their forces, the guards and the switch at one state each.
    fn frames_at(&mut self, q: &[f64]) {
        if self.frames.level() < Level::Jacobian || self.frames.coordinates != q {
            frames_level_into(&self.mechanism, q, Level::Jacobian, &mut self.frames);
        }
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

    /// Where `pair`'s fixed sharp corner touches a face of a box or a cylinder
    /// at `q` (frames there), within it past rounding: that face's plane, its
    /// point and outward normal in the frame of the body of the geom touched.
    /// Held against the geom itself, a corner that slides past the face's
    /// edge must turn onto the next face in one step: Newton's method
    /// diverged on every step across, and the steps shrank to rounding,
    /// whose last one threw the box (a box's corner off a rail's end face).
    fn face_of(&self, pair: &Pair, q: &[f64]) -> Result<Option<[[f64; 3]; 2]>> {
        let m = &self.mechanism;
        if !matches!(pair.part, Toucher::Geom(_)) {
            return Ok(None);
        }
        let c = corner(m, pair)?;
        // A ball's centre lies off the surface, where the distance to a
        // convex geom turns smoothly round its edges: it rolls over them.
        if c.radius > 0.0 {
            return Ok(None);
        }
        let bodies = &self.frames.bodies;
        let slope = gap_slope(m, &self.frames, q, pair, None)?;
        if !c.on_face(bodies, m.size(), &slope.normal).is_some_and(|g| g.is_finite() && g > 2e-9 * m.size()) {
            return Ok(None);
        }
        let on = D::moved(&slope.point, &slope.normal, -slope.gap);
        let inverse = D::inverse(&bodies[c.flat.body]);
        Ok(Some([array::<D>(&D::position(&D::act(&inverse, &on))), array::<D>(&D::rotate(&inverse, &slope.normal))]))
    }

    /// The plane [`Held::face`] of a touching corner, fixed in the body of the geom it touches.
    fn face_plane(&self, h: &Held) -> Result<Option<Geom<D>>> {
        let Some([origin, normal]) = h.face else { return Ok(None) };
        let flat = corner(&self.mechanism, &h.pair)?.flat;
        let at = D::at(&D::moved(&D::origin(&D::identity()), &vector::<D>(&origin), 1.0));
        Ok(Some(flat.stand_in(at, GeomShape::Plane { normal: vector::<D>(&normal) })))
    }

    /// Whether `pair`, open at `low` (frames at `q`), parts as the state
    /// moves on along $\dot q$: its gap grows faster than $10^{-3}$ of
    /// $\lVert\nabla g\rVert \lVert\dot q\rVert$, read one-sided over a move of
    /// $10^{-7}$ of the mechanism's size. A corner that sits on the other
    /// geom's edge, where the gap's gradient jumps from one face's to the
    /// other's, reads the face it moves over: handed the touch of two edges
    /// that ran off the end of one (a box's edge off a rail's end), it
    /// parts from the face beyond the edge, and held there the impact would
    /// pull the box onto that face, or push it off the other.
    fn parts_ahead(&mut self, pair: &Pair, low: &Gap<D>, (q, v): (&[f64], &[f64])) -> Result<bool> {
        let slope = gap_slope(&self.mechanism, &self.frames, q, pair, low.s)?;
        let bound = linalg::norm(&slope.gradient) * linalg::norm(v);
        if bound == 0.0 {
            return Ok(false);
        }
        let tau = AHEAD * self.mechanism.size() / bound;
        let ahead: Vec<f64> = q.iter().zip(v).map(|(q, v)| q + tau * v).collect();
        self.frames_at(&ahead);
        let later = self.open_least(pair, &ahead);
        self.frames_at(q);
        Ok(later?.is_some_and(|g| g.gap - low.gap > PARTS * tau * bound))
    }

    /// Touching contact `i` at `q` (frames in `self.frames`, Jacobian level):
    /// its place settled where the gap is least (module docs), and its gap
    /// there. A contact with friction stays where it is: one that would roll
    /// into a span is refused by name.
    fn settle(&mut self, i: usize, q: &[f64]) -> Result<GapSlope<D>> {
        let (m, f) = (&self.mechanism, &self.frames);
        let Held { pair, s, length, law, .. } = self.held[i];
        let Some(mut s) = s else {
            return match self.face_plane(&self.held[i])? {
                Some(plane) => gap_slope_on(m, f, q, &pair, plane),
                None => gap_slope(m, f, q, &pair, None),
            };
        };
        for _ in 0..PLACE_ITERATIONS {
            let slope = gap_slope(m, f, q, &pair, Some(s))?;
            // At an end the gap rises into the span: it stays there.
            let stays = (s <= 0.0 && slope.ds >= 0.0) || (s >= length && slope.ds <= 0.0);
            if stays || (slope.ds.abs() <= 1e-12 && slope.dss > 0.0) {
                self.held[i].s = Some(s);
                return Ok(slope);
            }
            if law != Law::Free && !self.held[i].rolls {
                return Err(Error::invalid(
                    "friction",
                    format!("{} ({})", self.held[i].mu, named(m, &pair)),
                    "holds in motion only where the touching point is material: this end would roll onto its flexure's span, where friction is not solved yet: set the friction to 0",
                ));
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

    /// Leaves out each stuck contact's rows that depend on the rows before
    /// them at `q` ([`ContactSystem::independent_rows`]: the pushes before
    /// any friction, a stuck contact's rows along its normal and tangents,
    /// [`stuck_axes`]). Its force is
    /// indeterminate (a pendulum's bob stopped on a rough floor: the gap row
    /// stops its one coordinate, and no friction is needed to hold it), and
    /// held, it would make the closures singular. A rolling contact's gap row
    /// is never left out; its friction along a row left out is reported 0.
    /// Where a tangential row is left out, the contact's tangents turn to
    /// the principal directions of what the rows before leave of its rows
    /// ([`ContactSystem::turn_tangents`]), as the solve's do: the least
    /// friction, whatever the world's axes.
    fn prune(&mut self, q: &[f64]) -> Result<()> {
        for h in &mut self.held {
            h.dropped = [false; 3];
            h.axes = None;
        }
        let independent = self.independent_rows(q)?;
        let firsts = self.first_rows();
        let mut turn = false;
        for (h, first) in self.held.iter_mut().zip(firsts) {
            let stuck = matches!(h.law, Law::Stick { .. } | Law::Roll { .. });
            for (k, slot) in h.slots::<D>(first).into_iter().enumerate() {
                let Some(r) = slot else { continue };
                let rolls_gap = k == 0 && matches!(h.law, Law::Roll { .. });
                if !independent[r] && stuck && !rolls_gap {
                    h.dropped[k] = true;
                    turn |= k > 0;
                }
            }
        }
        if turn && D::POINT_DIM == 3 { self.turn_tangents(q) } else { Ok(()) }
    }

    /// Turns each stuck or rolling contact's tangents, one of whose rows
    /// `prune` left out, to the principal directions of what the
    /// closures', the pushes' and the earlier contacts' rows leave of its
    /// tangential rows at `q` (the eigenvectors of $r_ir_j$), and leaves out
    /// a direction whose part is under $10^{-9}$ of the largest row.
    fn turn_tangents(&mut self, q: &[f64]) -> Result<()> {
        let pushes: Vec<bool> = self.held.iter().map(|h| h.dropped[0]).collect();
        let before: Vec<[bool; 3]> = self.held.iter().map(|h| h.dropped).collect();
        for h in &mut self.held {
            h.dropped = [false; 3];
        }
        let (n, m) = (self.dim(), self.closures());
        let (mut c, mut g) = (vec![0.0; m], vec![0.0; m * n]);
        self.closure(q, &mut c, &mut g)?;
        let row = |r: usize| (0..n).map(|col| g[col * m + r]).collect::<Vec<f64>>();
        let scale = (0..m).map(|r| linalg::norm(&row(r))).fold(0.0, f64::max);
        let mut basis = linalg::Basis::default();
        (0..self.inner.closures()).for_each(|r| basis.add(&row(r)));
        let firsts = self.first_rows();
        for (&first, &left_out) in firsts.iter().zip(&pushes) {
            if !left_out {
                basis.add(&row(first));
            }
        }
        // Each one's rows among all (none left out while G is read).
        let slots: Vec<[Option<usize>; 3]> = self.held.iter().zip(&firsts).map(|(h, &f)| h.slots::<D>(f)).collect();
        for (i, slots) in slots.into_iter().enumerate() {
            self.held[i].dropped = before[i];
            if !before[i][1..].contains(&true) {
                slots[1..].iter().flatten().for_each(|&r| basis.add(&row(r)));
                continue;
            }
            let rows: Vec<Vec<f64>> = slots[1..D::POINT_DIM].iter().flatten().map(|&r| row(r)).collect();
            let size = rows.iter().map(|r| linalg::norm(r)).fold(scale, f64::max);
            // Its tangents as the rows took them, turned.
            let normal = self.settle(i, q)?.normal;
            let h = &mut self.held[i];
            let units = match h.law {
                Law::Roll { tangents: kept } => tangents::<D>(&array::<D>(&normal), Some(&kept)),
                _ => tangents::<D>(&array::<D>(&normal), None),
            };
            let (turned, kept) = linalg::turn_rows(&mut basis, &rows, &units[..rows.len()], size);
            let turned = [turned[0], turned[1]];
            match &mut h.law {
                Law::Roll { tangents: u } => *u = turned,
                _ => h.axes = Some(turned),
            }
            h.dropped = [before[i][0], !kept[0], !kept[1]];
        }
        Ok(())
    }

    /// Holds `h` at `q` if one of its rows adds a direction to the rows
    /// held (a rolling one, its gap row, which `prune` never leaves out),
    /// and says whether it did. One that adds none (a box's face landing
    /// flat on a body that one corner already holds) would make the
    /// closures singular: it stays open, its gap held at zero by the others.
    fn hold(&mut self, h: Held, q: &[f64]) -> Result<bool> {
        self.held.push(h);
        let first = self.first_rows()[self.held.len() - 1];
        let independent = self.independent_rows(q)?;
        let slots = h.slots::<D>(first);
        let adds = match h.law {
            Law::Roll { .. } => slots[0].is_some_and(|r| independent[r]),
            _ => slots.iter().flatten().any(|&r| independent[r]),
        };
        if !adds {
            self.held.pop();
        }
        Ok(adds)
    }

    /// Whether each row of the closures' $G$ at `q` is independent of the
    /// rows before it, taken in the order the mechanism's, each contact's
    /// first (its push), then the contacts' others (their friction):
    /// Gram–Schmidt, a row whose remainder is under $10^{-9}$ of the
    /// largest row being dependent.
    fn independent_rows(&mut self, q: &[f64]) -> Result<Vec<bool>> {
        let (n, m) = (self.dim(), self.closures());
        let (mut c, mut g) = (vec![0.0; m], vec![0.0; m * n]);
        self.closure(q, &mut c, &mut g)?;
        // The mechanism's rows, then each contact's normal (its first),
        // then their tangential rows: a push goes before any friction.
        let firsts = self.first_rows();
        let mut order: Vec<usize> = (0..self.inner.closures()).collect();
        order.extend(firsts.iter().copied());
        for (h, &first) in self.held.iter().zip(&firsts) {
            order.extend(h.slots::<D>(first).into_iter().skip(1).flatten());
        }
        let mut basis: Vec<Vec<f64>> = Vec::new();
        // The largest row: a row all of rounding's size (a slider's motion
        // across itself, cos(π/2)) is no row.
        let row_size = |r: usize| (0..n).map(|col| g[col * m + r].powi(2)).sum::<f64>().sqrt();
        let scale = (0..m).map(row_size).fold(0.0, f64::max);
        let mut independent = vec![false; m];
        for r in order {
            let mut rest: Vec<f64> = (0..n).map(|col| g[col * m + r]).collect();
            let size = row_size(r).max(scale);
            for b in &basis {
                let along: f64 = rest.iter().zip(b).map(|(x, y)| x * y).sum();
                rest.iter_mut().zip(b).for_each(|(x, y)| *x -= along * y);
            }
            let left = rest.iter().map(|x| x * x).sum::<f64>().sqrt();
            independent[r] = left > 1e-9 * size;
            if independent[r] {
                basis.push(rest.iter().map(|x| x / left).collect());
            }
        }
        Ok(independent)
    }

    /// Each contact of `stopped` (its pair and place) that
    /// a slide stopped and that, stuck at $(q, \dot q, t)$, needs more than
    /// its friction by the equations of motion themselves
    /// ([`consistent_multipliers`]): it slides on, the other way, toward
    /// where the stuck force pulls it (its slide turned back rather than
    /// stopped), and the change said is a slide.
    fn slide_on(&mut self, stopped: &[(Pair, Option<f64>)], t: f64, (q, v): (&[f64], &[f64])) -> Result<()> {
        if stopped.is_empty() {
            return Ok(());
        }
        let Some(lambda) = consistent_multipliers(self, t, q, v)? else { return Ok(()) };
        let rows = self.first_rows();
        let mut changed = false;
        for (pair, s) in stopped {
            let Some(i) = self.held.iter().position(|h| h.pair == *pair && h.s == *s) else { continue };
            let r = self.read(i, rows[i], (q, v), Some(&lambda))?;
            let h = &mut self.held[i];
            let size = dot::<D>(&r.friction, &r.friction).sqrt();
            // Past the band its stick guard lands in (a friction within it
            // of μN, stuck again, slid again and stopped at once, 24 times
            // at one instant).
            if size > h.mu * r.push + self.tolerance * h.largest.max(r.push) && size > 0.0 {
                h.law = slipping::<D>(&scaled::<D>(&r.friction, -1.0 / size), &r.slide);
                if let Some(c) = self.changes.iter_mut().rev().find(|c| c.pair == h.pair) {
                    c.state = ContactMode::Slip;
                }
                changed = true;
            }
        }
        if changed { self.prune(q) } else { Ok(()) }
    }

    /// The first row of each touching contact among the closures.
    fn first_rows(&self) -> Vec<usize> {
        let mut row = self.inner.closures();
        self.held
            .iter()
            .map(|h| {
                let r = row;
                row += h.rows::<D>();
                r
            })
            .collect()
    }

    /// Contact `i` at $(q, \dot q)$ (frames at `q`, Jacobian level) with the
    /// closures' multipliers `lambda` (or its last forces without them).
    fn read(&mut self, i: usize, row: usize, (q, v): (&[f64], &[f64]), lambda: Option<&[f64]>) -> Result<Reading<D>> {
        let slope = self.settle(i, q)?;
        let h = self.held[i];
        let p = point_jet(&self.mechanism, &self.frames, q, &h.pair, h.s, None)?;
        let delta = match h.rolls && h.law != Law::Free {
            true => self.material_delta(&h, &p, &slope, q)?,
            false => p.delta,
        };
        let n = slope.normal;
        let slide = sliding::<D>(&delta, v, &n);
        let (push, friction) = match (h.law, lambda) {
            (_, None) => (h.force, vector::<D>(&h.friction)),
            (Law::Roll { tangents: kept }, Some(l)) => {
                let units = tangents::<D>(&array::<D>(&n), Some(&kept));
                let slots = h.slots::<D>(row);
                let along = (0..D::POINT_DIM - 1)
                    .filter_map(|k| slots[1 + k].map(|r| scaled::<D>(&vector::<D>(&units[k]), -l[r])));
                (-l[row], along.fold(D::Vector::default(), |a, b| a + b))
            }
            (Law::Stick { .. }, Some(l)) => {
                let held = h.slots::<D>(row).map(|r| r.map_or(0.0, |r| l[r]));
                let axes = stuck_axes::<D>(&n, h.axes.as_ref());
                let force = (0..D::POINT_DIM).fold(D::Vector::default(), |f, k| f - scaled::<D>(&axes[k], held[k]));
                let push = dot::<D>(&n, &force);
                (push, force - scaled::<D>(&n, push))
            }
            (Law::Slip { from, .. }, Some(l)) => {
                let push = -l[row];
                (push, scaled::<D>(&self.direction(&slide, &vector::<D>(&from), &n), -h.mu * push))
            }
            (Law::Free, Some(l)) => (-l[row], D::Vector::default()),
        };
        Ok(Reading { slope, push, friction, slide, delta })
    }

    /// $\hat s$: the slide `slide` with the direction it slid from, `from`,
    /// added at the creep speed; `from` itself once the slide has turned
    /// back from it; each in the tangent plane of the normal `n`. A slide
    /// turns back only through an event (it sticks, or slides on the other
    /// way), which the steps land on: within a step the friction keeps
    /// pushing against `from`, so the slide crosses zero where the motion
    /// does, rather than being held near zero by a friction that turns over
    /// with it (the steps aimed at the stop then found it anywhere after the
    /// crossing). In the tangent plane, $\hat s$ is continuous where the slide
    /// stops, and the friction has no part along the normal: `from` as it
    /// was, where the surface has turned since, leaned the friction into the
    /// normal as the slide stopped, and the push jumped there.
    fn direction(&self, slide: &D::Vector, from: &D::Vector, n: &D::Vector) -> D::Vector {
        let from = *from - scaled::<D>(n, dot::<D>(n, from));
        let s = match dot::<D>(slide, &from) <= 0.0 {
            true => from,
            false => *slide + scaled::<D>(&from, self.creep),
        };
        let size = dot::<D>(&s, &s).sqrt();
        if size > 0.0 { scaled::<D>(&s, 1.0 / size) } else { s }
    }

    fn report(&mut self, q: &[f64], v: &[f64], multipliers: Option<&[f64]>) -> Result<Vec<Contact>> {
        self.frames_at(q);
        let mut out = Vec::new();
        for (i, row) in self.first_rows().into_iter().enumerate() {
            let r = self.read(i, row, (q, v), multipliers)?;
            let h = &mut self.held[i];
            (h.force, h.friction) = (r.push, array::<D>(&r.friction));
            let stuck = matches!(h.law, Law::Stick { .. } | Law::Roll { .. });
            let state = if stuck { ContactMode::Stick } else { ContactMode::Slip };
            let place = (h.s, &r.slope.point, &r.slope.normal, r.slope.gap);
            out.push(Contact::of(&self.mechanism, &h.pair, place, (r.push.max(0.0), &r.friction), state));
        }
        let none = D::Vector::default();
        for pair in self.pairs.clone() {
            if self.held.iter().any(|h| h.pair == pair) {
                continue;
            }
            // Two edges are a contact where they cross within both, facing each other.
            if crossing_of(&self.mechanism, &pair, &self.frames.bodies).is_some_and(|k| k.turn.is_none()) {
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

/// The refusal of `pair` overlapping by `depth` (m) where the motion
/// starts: at the `[initial]` entry that moves one of its two parts
/// against the other, where one does (the last such in the file that
/// moves its joint from rest, else the last such), else at the geom.
fn overlap<D: Dynamics>(m: &Mechanism<D>, pair: &Pair, depth: f64) -> Error {
    let geom = m.path(m.geoms[pair.geom].body);
    let part = match pair.part {
        Toucher::Flexure(j) => m.path(m.joints[j].parent).into_iter().chain([j]).collect(),
        Toucher::Geom(h) => m.path(m.geoms[h].body),
    };
    // A joint on both paths moves the two together.
    let moving: Vec<usize> =
        geom.iter().chain(&part).filter(|j| geom.contains(j) != part.contains(j)).copied().collect();
    let what = format!("{} overlap by {depth:.3e} m where the motion starts", named(m, pair));
    // An entry that leaves its joint at rest moves nothing (a slider given
    // 0.0 after the one that pushed the ball into its floor was blamed).
    let rest = m.rest();
    let from_rest = |(j, values): &(usize, Vec<f64>)| {
        let o = m.joints[*j].offset;
        values.iter().zip(&rest[o..]).any(|(a, b)| a != b)
    };
    let entries = &m.initial;
    let culprit = entries.iter().rposition(|e| moving.contains(&e.0) && from_rest(e));
    match culprit.or_else(|| entries.iter().rposition(|(j, _)| moving.contains(j))) {
        Some(k) => Error::File {
            place: m.initial_place(k).to_string(),
            message: format!(
                "[initial] joint {:?}: {what}; give it coordinates where the two are apart, or leave it out to start from the equilibrium",
                m.joints[m.initial[k].0].name
            ),
        },
        None => Error::invalid("geom", what, "start from an equilibrium, or move the geom apart"),
    }
}

/// A pair's gap rate $\dot g = \partial g/\partial q\thinspace\dot q$ (m/s) at the
/// velocities `v`: below zero it approaches its geom, above it leaves it.
fn gap_rate<D: Dynamics>(slope: &GapSlope<D>, v: &[f64]) -> f64 {
    slope.gradient.iter().zip(v).map(|(g, v)| g * v).sum()
}

/// A point's velocity relative to the geom, $\sum_c\Delta_c\dot q_c$, in the
/// tangent plane of the normal `n`.
fn sliding<D: Dynamics>(delta: &[D::Vector], v: &[f64], n: &D::Vector) -> D::Vector {
    let mut velocity = D::Vector::default();
    for (d, v) in delta.iter().zip(v) {
        velocity = velocity + scaled::<D>(d, *v);
    }
    velocity - scaled::<D>(n, dot::<D>(n, &velocity))
}

/// A stuck contact's row axes: the normal `n` first, then its tangents
/// ([`tangents`], nearest `turned` where `prune` turned them). Its pinned
/// point's offset is held along each.
fn stuck_axes<D: Dynamics>(n: &D::Vector, turned: Option<&[[f64; 3]; 2]>) -> Vec<D::Vector> {
    let t = tangents::<D>(&array::<D>(n), turned);
    std::iter::once(*n).chain(t[..D::POINT_DIM - 1].iter().map(vector::<D>)).collect()
}

/// The slide's speed the integrator resolves, per unit of its tolerance:
/// each rate $\dot q_c$ to about the tolerance of $1 + \lvert\dot q_c\rvert$
/// (its error's weight), each moving the point by its $\Delta_c$,
/// $$\sqrt{\textstyle\sum_c \lvert\Delta_c\rvert^2(1 + \lvert\dot q_c\rvert)^2}.$$
/// A stuck slide is held to this, not to zero: where the flexures ring
/// fast (rates of thousands per second), a stuck pad's slide is 1e-7 m/s,
/// which read as a slip turning back at once had stuck it again 24 times
/// at one instant.
fn resolved<D: Dynamics>(delta: &[D::Vector], v: &[f64]) -> f64 {
    delta.iter().zip(v).map(|(d, v)| dot::<D>(d, d) * (1.0 + v.abs()).powi(2)).sum::<f64>().sqrt()
}

/// A stuck contact that begins to slide along `from` (world), its slide
/// now `slide`: from rest, first shedding the speed it still has the other
/// way ([`Law::Slip`]'s `lag`).
fn slipping<D: Dynamics>(from: &D::Vector, slide: &D::Vector) -> Law {
    Law::Slip { from: array::<D>(from), fastest: 0.0, lag: (-dot::<D>(slide, from)).max(0.0) }
}

/// A contact rolling stuck where the geom's normal is `normal`: its tangents from it.
fn rolling<D: Dynamics>(normal: &D::Vector) -> Law {
    Law::Roll { tangents: tangents::<D>(&array::<D>(normal), None) }
}

/// `x`'s entries (two or three), padded with zeros to three.
fn array_of(x: &[f64]) -> [f64; 3] {
    let mut a = [0.0; 3];
    a[..x.len()].copy_from_slice(x);
    a
}

impl<D: Dynamics> System for ContactSystem<D> {
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    fn closures(&self) -> usize {
        self.inner.closures() + self.held.iter().map(Held::rows::<D>).sum::<usize>()
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
        self.frames_at(q);
        for (i, row) in self.first_rows().into_iter().enumerate() {
            let slope = self.settle(i, q)?;
            let h = self.held[i];
            let slots = h.slots::<D>(row);
            if let Law::Stick { anchor } = h.law {
                let p = point_jet(&self.mechanism, &self.frames, q, &h.pair, h.s, Some(vector::<D>(&anchor)))?;
                let body = &self.frames.bodies[p.shape.body];
                let a = D::act(body, &D::moved(&D::origin(&D::identity()), &vector::<D>(&anchor), 1.0));
                let offset = D::position(&p.x) - D::position(&a);
                let axes = stuck_axes::<D>(&slope.normal, h.axes.as_ref());
                for (k, r) in slots.iter().enumerate().take(D::POINT_DIM).filter_map(|(k, r)| r.map(|r| (k, r))) {
                    c[r] = dot::<D>(&axes[k], &offset);
                    for col in 0..n {
                        g[col * rows + r] = dot::<D>(&axes[k], &p.delta[col]);
                    }
                }
            } else {
                c[row] = slope.gap;
                for col in 0..n {
                    g[col * rows + row] = slope.gradient[col];
                }
            }
            if let Law::Roll { tangents: kept } = h.law {
                // Velocity rows: its material points' relative velocity
                // along the surface (`velocity_closures`); c is not read.
                let p = point_jet(&self.mechanism, &self.frames, q, &h.pair, h.s, None)?;
                let delta = self.material_delta(&h, &p, &slope, q)?;
                let units = tangents::<D>(&array::<D>(&slope.normal), Some(&kept));
                for (k, u) in units[..D::POINT_DIM - 1].iter().map(vector::<D>).enumerate() {
                    let Some(r) = slots[1 + k] else { continue };
                    c[r] = 0.0;
                    for col in 0..n {
                        g[col * rows + r] = dot::<D>(&u, &delta[col]);
                    }
                }
            }
        }
        Ok(())
    }

    /// $G$, but a sliding contact's row pushes along $\nabla g - \mu\hat s^T\Delta$ (module docs).
    fn closure_forces(&mut self, q: &[f64], v: &[f64], g: &[f64], w: &mut [f64]) -> Result<()> {
        w.copy_from_slice(g);
        if !self.held.iter().any(|h| matches!(h.law, Law::Slip { .. })) {
            return Ok(());
        }
        let rows = self.closures();
        self.frames_at(q);
        for (i, row) in self.first_rows().into_iter().enumerate() {
            let h = self.held[i];
            let Law::Slip { from, .. } = h.law else { continue };
            let r = self.read(i, row, (q, v), None)?;
            let s = self.direction(&r.slide, &vector::<D>(&from), &r.slope.normal);
            for (col, d) in r.delta.iter().enumerate() {
                w[col * rows + row] -= h.mu * dot::<D>(&s, d);
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

    /// The default, not the mechanism's: the contact events are landed on
    /// to `tolerance` of each push and speed, which every coefficient's
    /// motion moves, so each is resolved to its own scale (with the
    /// mechanism's weights, a strip lifted off a post at 1e-8 could not land
    /// on its opening: the push, read through the high coefficients' looser
    /// rates, missed its band at every aimed step).
    fn error_weights(&self) -> crate::dynamics::system::ErrorWeights {
        crate::dynamics::system::ErrorWeights::unit(self.inner.dim())
    }

    fn jumps(&self) -> Vec<f64> {
        self.inner.jumps()
    }

    fn guard_count(&self) -> usize {
        HELD_GUARDS * self.held.len() + self.pairs.len()
    }

    /// Each touching contact's push, its friction's (module docs) and how
    /// far it lies within where it applies (two edges' crossing within both
    /// edges, a corner within the face it touches), then each pair's least
    /// open gap, over their bands.
    fn guards(&mut self, q: &[f64], v: &[f64], multipliers: Option<&[f64]>, out: &mut [f64]) -> Result<()> {
        self.frames_at(q);
        self.last = multipliers.map(<[f64]>::to_vec).unwrap_or_default();
        for (i, row) in self.first_rows().into_iter().enumerate() {
            let r = self.read(i, row, (q, v), multipliers)?;
            let tolerance = self.tolerance;
            let h = &mut self.held[i];
            (out[HELD_GUARDS * i], out[HELD_GUARDS * i + 1]) = match multipliers {
                None => {
                    // Just after a touch, the velocities moved onto the
                    // closures (an impact can turn a slide back): a slide
                    // that moved into the touch is measured from where it
                    // now goes. (One that starts from stuck, `fastest` 0,
                    // keeps the way its stuck force pulled it: its speed is
                    // still the closures' rounding.)
                    let speed = dot::<D>(&r.slide, &r.slide).sqrt();
                    if let Law::Slip { from, fastest, .. } = &mut h.law
                        && *fastest > 0.0
                        && speed > self.creep
                    {
                        (*from, *fastest) = (array::<D>(&scaled::<D>(&r.slide, 1.0 / speed)), speed);
                    }
                    (1.0, 1.0)
                }
                // Pulling from its first step: let go where it began to hold,
                // as if the push had crossed zero there.
                Some(_) if h.largest <= 0.0 && r.push < 0.0 => (-1e12, 1.0),
                Some(_) => {
                    h.largest = h.largest.max(r.push);
                    let band = tolerance * h.largest;
                    let friction = match &mut h.law {
                        Law::Free => f64::MAX,
                        Law::Stick { .. } | Law::Roll { .. } => {
                            (h.mu * r.push - dot::<D>(&r.friction, &r.friction).sqrt()) / band
                        }
                        Law::Slip { from, fastest, lag } => {
                            let speed = dot::<D>(&r.slide, &vector::<D>(from));
                            // Its fastest at the steps accepted, or now: a
                            // trial step's is not kept (one refused had set
                            // it, and a slip that began at the stop after
                            // read as turning back, 24 times at one instant).
                            let top = fastest.max(speed);
                            // Not finer than the integrator resolves a slide.
                            let reach = resolved::<D>(&r.delta, v);
                            match top > 0.0 {
                                true => speed / (tolerance * top.max(reach)),
                                // Turning back from its first step, past the
                                // speed it had the other way where it began:
                                // it sticks where it began.
                                false if speed < -(*lag + tolerance * reach) => -1e12,
                                false => 1.0,
                            }
                        }
                    };
                    (r.push / band, friction)
                }
            };
        }
        // Two edges whose crossing leaves either edge are let go (the corner
        // there takes the touch), and so is a corner that slides past the
        // edge of the face it touches, where the face's normal gives way to
        // the next face's: held on, the step across would turn it there in
        // one jump (a box's corner off a rail's end face).
        let (m, bodies) = (&self.mechanism, &self.frames.bodies);
        for (i, h) in self.held.iter().enumerate() {
            let margin = match h.pair.part {
                Toucher::Geom(_) => {
                    let c = corner(m, &h.pair)?;
                    let face = |[_, n]: [[f64; 3]; 2]| D::rotate(&bodies[c.flat.body], &vector::<D>(&n));
                    let on_face = h.face.map(face).and_then(|n| c.on_face(bodies, m.size(), &n));
                    c.crossing(bodies).map(|k| k.margin).or(on_face)
                }
                Toucher::Flexure(_) => None,
            };
            // Read a band later: a margin that stays at its bound (a crossing
            // at an edge's end, two boxes' corners aligned on each other's
            // edges) lies inside the band a guard lands in, and each step
            // aimed at another event landed on it (1,452 switches in 1 s).
            out[HELD_GUARDS * i + 2] = margin.map_or(f64::MAX, |g| g / self.gap_band + 1.0);
        }
        let a = HELD_GUARDS * self.held.len();
        for k in 0..self.pairs.len() {
            let pair = self.pairs[k];
            out[a + k] = self.open_least(&pair, q)?.map_or(f64::MAX, |g| g.gap / self.gap_band);
        }
        Ok(())
    }

    /// A pair that touches while approaching is held; a touching contact
    /// that pulls is let go; a stuck one that needs more than its friction
    /// slides, and a sliding one that turns back sticks (module docs). Two
    /// edges whose crossing ran off an edge's end hand the touch to the
    /// corner there, unless it parts as the state moves on
    /// (`ContactSystem::parts_ahead`), and take it back where the
    /// crossing comes back.
    fn switch(&mut self, ks: &[usize], t: f64, q: &[f64], v: &[f64]) -> Result<()> {
        let a = self.held.len();
        self.frames_at(q);
        let change = |changes: &mut Vec<ContactChange>, m: &Mechanism<D>, pair: &Pair, state| {
            changes.push(ContactChange { time: t, contact: column(m, pair), state, pair: *pair });
        };
        // The laws first, at the contacts' own rows (the last multipliers).
        let last = std::mem::take(&mut self.last);
        let rows = self.first_rows();
        // The sliding contacts that stopped: stuck, unless that needs more than their friction.
        let mut stopped = Vec::new();
        for &k in ks.iter().filter(|&&k| k < HELD_GUARDS * a && k % HELD_GUARDS == 1) {
            let i = k / HELD_GUARDS;
            let r = self.read(i, rows[i], (q, v), Some(&last).filter(|l| !l.is_empty()).map(Vec::as_slice))?;
            let h = self.held[i];
            let size = dot::<D>(&r.friction, &r.friction).sqrt();
            let law = match h.law {
                Law::Stick { .. } | Law::Roll { .. } => {
                    let from = if size > 0.0 { scaled::<D>(&r.friction, -1.0 / size) } else { r.slide };
                    slipping::<D>(&from, &r.slide)
                }
                _ if h.rolls => rolling::<D>(&r.slope.normal),
                _ => Law::Stick { anchor: self.anchor(&h, q)? },
            };
            self.held[i].law = law;
            let state = if matches!(law, Law::Stick { .. } | Law::Roll { .. }) {
                stopped.push((h.pair, h.s));
                ContactMode::Stick
            } else {
                ContactMode::Slip
            };
            change(&mut self.changes, &self.mechanism, &h.pair, state);
        }
        let mut released: Vec<usize> =
            ks.iter().filter(|&&k| k < HELD_GUARDS * a && k % HELD_GUARDS != 1).map(|k| k / HELD_GUARDS).collect();
        released.dedup();
        let mut added = Vec::new();
        for &k in ks.iter().filter(|&&k| k >= HELD_GUARDS * a) {
            let pair = self.pairs[k - HELD_GUARDS * a];
            let Some(low) = self.open_least(&pair, q)? else { continue };
            // Two edges that do not cross within both: a corner touches there.
            if crossing_of(&self.mechanism, &pair, &self.frames.bodies).is_some_and(|k| !k.applies()) {
                continue;
            }
            let slope = gap_slope(&self.mechanism, &self.frames, q, &pair, low.s)?;
            if gap_rate(&slope, v) < 0.0 {
                let mut h = self.touch(&pair, low.s, q)?;
                h.law = self.starting_law(&h, &low.normal, (q, v))?;
                added.push(h);
            }
        }
        let mut handed = Vec::new();
        for &i in released.iter().rev() {
            let h = self.held.remove(i);
            change(&mut self.changes, &self.mechanism, &h.pair, ContactMode::Open);
            // Only one let go where it left where it applies (its third
            // guard) hands its touch on; one that pulls, to none: at an edge's
            // end (a box landing flat on a box offset 1 mm) it was handed
            // to the crossing at the support's other end, which pulled too,
            // and back (336 switches at one instant).
            if !ks.contains(&(HELD_GUARDS * i + 2)) {
                continue;
            }
            // Two edges whose crossing ran off an edge's end (the step lands
            // on it to the tolerance, either side): the corner there takes the touch.
            let (m, bodies) = (&self.mechanism, &self.frames.bodies);
            let Some(corner) = crossing_of(m, &h.pair, bodies).and_then(|k| ran_off(m, &h.pair, &k, COMING_BACK))
            else {
                continue;
            };
            // Where another crossing of the two geoms' edges applies and
            // touches, the nearest to where it was holds instead: an edge
            // lying flush on a face touches it along a segment whose ends
            // are two crossings (a box's edge on a rail's end face, across
            // its top and its upright edges), and the corner that ends one
            // sits on the edge, where its normal is undefined. A corner
            // left open that is needed is touched by its own guard.
            let Some(from) = self.open_least(&h.pair, q)?.map(|g| D::position(&g.point)) else {
                handed.push(corner);
                continue;
            };
            let mut next: Option<(f64, Pair)> = None;
            for p in self.pairs.iter().filter(|p| p.geom == h.pair.geom && p.part == h.pair.part && **p != h.pair) {
                let applies = crossing_of(m, p, bodies).is_some_and(|k| k.applies());
                let held = self.held.iter().any(|k| k.pair == *p);
                if let (true, false, Some(g)) = (applies, held, self.open_least(p, q)?)
                    && g.gap <= self.gap_band
                {
                    let d = D::position(&g.point) - from;
                    let far = dot::<D>(&d, &d).sqrt();
                    if next.is_none_or(|(f, _)| far < f) {
                        next = Some((far, *p));
                    }
                }
            }
            handed.push(next.map_or(corner, |(_, p)| p));
        }
        // Two edges whose crossing came back onto an edge from the corner
        // that held the touch (or is handed it now) take it: not both.
        let backs: Vec<Option<Pair>> =
            added.iter().map(|h| came_back(&self.mechanism, &h.pair, &self.frames.bodies)).collect();
        handed.retain(|p| !backs.contains(&Some(*p)));
        for pair in handed {
            let Some(low) = self.open_least(&pair, q)? else { continue };
            if added.iter().any(|h: &Held| h.pair == pair) || self.parts_ahead(&pair, &low, (q, v))? {
                continue;
            }
            let mut h = self.touch(&pair, None, q)?;
            h.law = self.starting_law(&h, &low.normal, (q, v))?;
            added.push(h);
        }
        for (k, h) in added.into_iter().enumerate() {
            // The corner it came back from lets go only where it is held in its place.
            let back = backs.get(k).copied().flatten().and_then(|c| self.held.iter().position(|k| k.pair == c));
            let corner = back.map(|i| (i, self.held.remove(i)));
            if !self.hold(h, q)? {
                if let Some((i, c)) = corner {
                    self.held.insert(i, c);
                }
                continue;
            }
            if let Some((_, c)) = corner {
                change(&mut self.changes, &self.mechanism, &c.pair, ContactMode::Open);
            }
            let stuck = matches!(h.law, Law::Stick { .. } | Law::Roll { .. });
            let state = if stuck { ContactMode::Stick } else { ContactMode::Slip };
            change(&mut self.changes, &self.mechanism, &h.pair, state);
        }
        self.prune(q)?;
        self.slide_on(&stopped, t, (q, v))
    }

    /// The contact rows after the mechanism's own: a rolling contact's
    /// tangential rows hold velocities (module docs).
    fn velocity_closures(&self) -> Vec<bool> {
        let mut rows = vec![false; self.inner.closures()];
        for h in &self.held {
            let rolls = matches!(h.law, Law::Roll { .. });
            rows.extend(h.all_rows::<D>().enumerate().filter(|(_, held)| *held).map(|(k, _)| rolls && k > 0));
        }
        rows
    }

    /// Each sliding contact's direction $\hat s_0$ becomes the way it slides
    /// at the step accepted, unless it slides slower than its stop's band
    /// (the speed the integrator resolves) or has turned back from it (the
    /// event the steps land on): in space a slide
    /// turns as it goes (a pad rising onto a ball), and measured from where
    /// it began, its speed along it fell to zero where it had only turned
    /// a right angle, and its friction turned over there (a guard that
    /// jumped a thousand bands).
    /// The first pair of two geoms one of whose edges went through the
    /// other past the gap's band at `q`, with none of their gaps negative
    /// (`crossed_edges`), named.
    fn passed(&mut self, q: &[f64]) -> Result<Option<String>> {
        if !self.pairs.iter().any(|p| may_cross(&self.mechanism, p)) {
            return Ok(None);
        }
        self.frames_at(q);
        let pair = crossed_edges(&self.mechanism, &self.frames.bodies, &self.pairs, self.gap_band);
        Ok(pair.map(|pair| Error::invalid("geom", named(&self.mechanism, &pair), PASSED_THROUGH).to_string()))
    }

    fn accepted(&mut self, q: &[f64], v: &[f64]) -> Result<()> {
        if !self.held.iter().any(|h| matches!(h.law, Law::Slip { .. })) {
            return Ok(());
        }
        self.frames_at(q);
        for (i, row) in self.first_rows().into_iter().enumerate() {
            if !matches!(self.held[i].law, Law::Slip { .. }) {
                continue;
            }
            let r = self.read(i, row, (q, v), None)?;
            let (slide, tolerance) = (r.slide, self.tolerance);
            let speed = dot::<D>(&slide, &slide).sqrt();
            // Above the speed the integrator resolves (its stop guard's
            // band): below it, the slide's way is mostly the rates' error.
            let reach = resolved::<D>(&r.delta, v);
            if let Law::Slip { from, fastest, .. } = &mut self.held[i].law {
                let along = dot::<D>(&slide, &vector::<D>(from));
                *fastest = fastest.max(along);
                if speed > self.creep.max(tolerance * fastest.max(reach)) && along > 0.0 {
                    *from = array::<D>(&scaled::<D>(&slide, 1.0 / speed));
                }
            }
        }
        Ok(())
    }

    fn sampled(&mut self, _t: f64, q: &[f64], v: &[f64], multipliers: Option<&[f64]>) -> Result<()> {
        let contacts = self.report(q, v, multipliers)?;
        // A rolling contact's tangents follow its normal, kept near the last.
        for (h, c) in self.held.iter_mut().zip(&contacts) {
            if let Law::Roll { tangents: kept } = &mut h.law {
                *kept = tangents::<D>(&array_of(&c.normal), Some(kept));
            }
        }
        self.samples.push(contacts);
        Ok(())
    }

    /// Each pair's push at the last sample (N; 0 while open; two geoms' summed
    /// over their corners), in the order of [`crate::mechanism::contact::column_pairs`]: a sweep's
    /// `contact.GEOM.PART.normal_force` columns.
    fn sample_columns(&self) -> Vec<f64> {
        let last = self.samples.last().map_or(&[][..], Vec::as_slice);
        // + 0.0: an empty sum is −0.
        let push = |p: &Pair| last.iter().filter(|c| c.pair.parts(p)).map(|c| c.normal_force).sum::<f64>() + 0.0;
        self.pairs.iter().filter(|p| p.corner == 0).map(push).collect()
    }
}
