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
//! the span), an inner contact reaching an end, two edges whose crossing
//! runs off an edge's end (the corner there takes the touch and its push
//! at that instant), or a loss of stability. A
//! step with an event is bisected to $10^{-10}$ of the load, the set changed
//! at the near side and solved there again (at most 8 changes at one load).
//!
//! **Friction** (Coulomb's $\mu$ of the geom) holds where a flexure's bare
//! end touches. A stuck end keeps its point at a material point $a$ of the
//! geom's body: its rows are $x - a = 0$ and its unknown the whole force
//! $f$, entering as $-f\cdot\partial_c(x - a)$; it slips where
//! $\lvert f_t\rvert > \mu N$. A sliding end keeps its gap row with $N$
//! and takes the force $N(n - \mu\hat s)$, $\hat s$ its direction of
//! sliding relative to the geom kept in the tangent plane; it sticks
//! again where it would move back. Both are events of the path. In space
//! $\hat s$ turns, at each accepted step, to the way the end moved, in
//! steps short enough that it turns by at most 0.01 rad.
//!
//! **Friction where a contact rolls** (inside a flexure's span, at a thick
//! end, or a ball on a geom): the point that touches moves over both
//! surfaces, so a stuck contact is no pinned point. A thick flexure's
//! material point is on its surface, off the centreline in its section's
//! axes ([`crate::mechanism::contact::offset_jet`]). Over each step the
//! toucher's material point and the geom body's that met at the last
//! accepted state are held together along the surface there, $t_k\cdot(x -
//! a) = 0$ for its unit tangents $t_k$ (fixed for the step), beside the gap
//! row; the unknowns are $N$ and the tangential $f_k$, entering as
//! $-f_k t_k\cdot\partial_c(x - a)$. A sliding one's friction acts at the
//! same two points. At each accepted step the points and tangents are set
//! anew where it touches, in steps that turn either surface under the
//! contact by at most 0.01 rad: a wheel so pinned rolls $r\sin\Delta\theta$
//! for $r\Delta\theta$, a relative error of $\Delta\theta^2/6 \approx
//! 2\times10^{-5}$.
//!
//! **Indeterminate friction.** Where a stuck or rolling contact's
//! tangential rows depend on the closures' rows and the pushes (a lid's
//! corner stuck on a floor, the lid on one hinge), its friction along them
//! is indeterminate in a rigid model and Newton would leave it where it
//! started. After each change of the set they are left out
//! ([`ContactKkt::prune`]): the least friction that holds the same
//! equilibrium, the push then the frictionless one. Two edges' crossing
//! moves over both edges, so with friction it rolls.
//!
//! **Sliding where it rolls, in space,** the slide's direction turns with
//! the rolling, so it is solved with each step rather than lagged: the
//! friction's two tangential components stay unknowns, with Alart and
//! Curnier's sliding rows ([`Skid`]) in place of the stuck ones, and steps
//! short enough that the friction turns by at most 0.01 rad.
//!
//! **Friction's limit.** Where a slip sticks again at its own load, and
//! again when tried from where it stuck (its rolling pins then set there,
//! so what it rolled before is no slide), no contact slides on as the load
//! grows: sliding on would take less load. The path has reached a limit
//! point and ends there as it does where stability is lost.
//!
//! **Refused by name:** a mechanism
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
    Contact, ContactMode, GapJet, Material, PASSED_THROUGH, Pair, PointJet, Toucher, array, corner, crossed_edges,
    crossing_of, dot, gap_jet, length, material_jet, minima, named, on_flexure, pairs, point_jet, ran_off, scaled,
    tangents, touched, turned, vector,
};
use crate::mechanism::kinematics::{Frames, frames_level_into};
use crate::mechanism::{Loads, Mechanism};
use crate::solver::{self, Problem};
use nalgebra::{DMatrix, DVector};

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
/// A contact on a flexure whose gap curves along it by less than this over
/// the flexure's length ($g_{ss}L$: the strip's curvature against the geom's,
/// its radius past a hundred lengths) where the path loses stability lies
/// along the geom: its least gap is spreading into an interval.
const FLAT_CURVATURE: f64 = 1e-2;
/// Changes of the set at one load before the path is declared stalled.
const MAX_CHANGES_AT_ONCE: usize = 8;
/// The most a sliding contact's direction may turn in one step (rad).
const MAX_SLIDE_TURN: f64 = 1e-2;
/// The most a skidding contact's friction may turn in one step (rad):
/// implicit Euler's error is first order in it (on the wheel held aside
/// of `tests/contact_rolling.rs`, about a quarter of it, relative to $\mu N$).
const MAX_SKID_TURN: f64 = 2e-3;
/// The most a rolling contact with friction may turn either surface under it in one step (rad).
const MAX_ROLL_TURN: f64 = 1e-2;
/// Accepted steps before the path is declared stalled.
const MAX_STEPS: usize = 10_000;

/// Where a contact sits.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Place {
    /// At a flexure's root or tip (this arc length), staying there.
    End(f64),
    /// Inside a flexure's span, where the gap is least (its arc length an unknown).
    Inner,
    /// Between two geoms, at a ball's surface or a capsule's end (it rolls).
    Geoms,
    /// Between two geoms, at a box's sharp corner: one material point.
    Corner,
}

/// How a touching contact holds along the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Law {
    /// Frictionless: no tangential force.
    Free,
    /// Stuck at `anchor`, a material point of the geom's body (its frame):
    /// the force is any vector in the friction cone.
    Stick { anchor: [f64; 3] },
    /// Sliding along `direction` (a unit tangent in the geom body's frame),
    /// the friction $-\mu N$ along it.
    Slip { direction: [f64; 3] },
    /// Rolling without slipping: over a step, the toucher's material point
    /// and the geom body's that met at the last accepted state do not move
    /// apart along `tangents` (world, unit, orthogonal: the surface's there).
    Roll { tangents: [[f64; 3]; 2] },
    /// A contact that rolls in space, sliding: its friction's components
    /// along `tangents` (as [`Law::Roll`]'s) are unknowns, solved with the
    /// step so that the friction is $\mu N$ against the slide of the
    /// material points that met at the last accepted state; `accepted`,
    /// those components there (N).
    Skid { tangents: [[f64; 3]; 2], accepted: [f64; 2] },
}

/// A contact that touches: its pair, place, law, force unknowns and, inside a span, $s/L$.
#[derive(Debug, Clone, Copy)]
struct Touching {
    pair: Pair,
    place: Place,
    law: Law,
    /// $N$ (N), or a stuck contact's force (world frame, N).
    force: [f64; 3],
    at: f64,
    /// The flexure's length (1 between geoms).
    length: f64,
    /// Its point in the geom body's frame at the last accepted state.
    from: [f64; 3],
    /// The toucher's material point there: a flexure's arc length and the
    /// point's offset from its centreline in the section's axes, or the
    /// point in a ball's body frame.
    on: Material,
    /// Whether a flexure touches with a thickness (off its centreline).
    thick: bool,
    /// Its force rows left out ([`ContactKkt::prune`]).
    pruned: Pruned,
}

/// A touching contact's force rows left out where they depend on the rows
/// before them ([`ContactKkt::prune`]): a stuck one's rows and force
/// components are along `axes` (world: its normal, then its tangents;
/// the world's axes when `None`), a rolling one's along its law's
/// tangents; each row `dropped` holds its force component at 0.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Pruned {
    axes: Option<[[f64; 3]; 3]>,
    dropped: [bool; 3],
}

impl Pruned {
    /// Its `k`th axis (world).
    fn axis(&self, k: usize) -> [f64; 3] {
        self.axes.map_or_else(|| std::array::from_fn(|i| f64::from(u8::from(i == k))), |a| a[k])
    }
}

impl Touching {
    fn s(&self) -> Option<f64> {
        match self.place {
            Place::End(s) => Some(s),
            Place::Inner => Some(self.at * self.length),
            Place::Geoms | Place::Corner => None,
        }
    }

    /// Its force unknowns: the force's components when stuck ($N$ and the
    /// tangential components when it rolls), else $N$.
    fn width<D: Statics>(&self) -> usize {
        if matches!(self.law, Law::Stick { .. } | Law::Roll { .. } | Law::Skid { .. }) { D::POINT_DIM } else { 1 }
    }

    /// Whether it rolls: the point that touches is not one material point
    /// (inside a span, at a thick end, or a ball).
    fn rolls(&self) -> bool {
        matches!(self.place, Place::Inner | Place::Geoms) || self.thick
    }
}

/// What friction adds to a touching contact's equations.
enum Friction<D: Statics> {
    /// Frictionless.
    None,
    /// Stuck: $x - a$ (world), $\Delta_c = \partial_c(x - a)$ and $\partial_b\partial_c\thinspace f\cdot(x - a)$.
    Pin { offset: D::Vector, delta: Vec<D::Vector>, hessian: DMatrix<f64> },
    /// Sliding: the unit direction $\hat s$, $\hat s\cdot\Delta_c$ and
    /// $\partial_b(\hat s\cdot\Delta_c)$ at $(b, c)$; where it rolls,
    /// $\partial_s(\hat s\cdot\Delta_c)$ inside a span, the toucher's
    /// material point (world) and how far the surfaces turned under it.
    Slide { direction: D::Vector, along: Vec<f64>, jacobian: DMatrix<f64>, ds: Vec<f64>, rolled: Option<Rolled<D>> },
    /// Rolling: $r_k = t_k\cdot(x - a)$ for each tangent, $t_k\cdot\Delta_c$,
    /// $\sum_k f_k t_k\cdot\partial_b\partial_c(x - a)$, and the material
    /// point; where it slides in space ([`Law::Skid`]), its sliding rows.
    Roll {
        offsets: Vec<f64>,
        along: Vec<Vec<f64>>,
        hessian: DMatrix<f64>,
        tangents: Vec<D::Vector>,
        rolled: Rolled<D>,
        skid: Option<Skid>,
    },
}

/// A rolling contact's toucher material point (world) and the most either
/// surface turned under the contact since the last accepted state (rad).
#[derive(Clone, Copy)]
struct Rolled<D: Statics> {
    point: D::Point,
    turn: f64,
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
    friction: Vec<Friction<D>>,
    /// Settling a path's start from no load (not a sweep's next value): a
    /// pair that only meets may touch there, to hold what rests on it.
    unloaded: bool,
    /// At that start the mechanism was unstable without the pairs that only
    /// meet: each of them touches (a box set on a floor, all its corners).
    resting: bool,
}

impl<D: Statics> ContactKkt<'_, D> {
    fn inner_dim(&self) -> usize {
        self.kkt.mechanism.dof() + self.kkt.mechanism.constraints()
    }

    /// Each touching contact's first force unknown (and row) among all.
    fn force_index(&self) -> Vec<usize> {
        let mut k = self.inner_dim();
        self.touching
            .iter()
            .map(|t| {
                k += t.width::<D>();
                k - t.width::<D>()
            })
            .collect()
    }

    /// [`solver::Problem::stable`]'s constrained stiffness less the margin,
    /// and the basis of the motions it is taken on (each coordinate $c$
    /// scaled by $\sqrt{r_c}$, its row's scale); `None` where an inner
    /// contact's gap curves the wrong way along the flexure.
    fn reduced(&self, jacobian: &[f64]) -> Option<(DMatrix<f64>, DMatrix<f64>)> {
        let m = self.kkt.mechanism;
        let (n, rows, size) = (m.dof(), m.constraints(), self.dim());
        let scale = &self.kkt.row_scale;
        let mut h = DMatrix::from_fn(n, n, |r, c| jacobian[c * size + r] / scale[r]);
        let mut g: Vec<Vec<f64>> = (0..rows)
            .map(|i| (0..n).map(|c| jacobian[c * size + n + i] / self.kkt.closure_scale[i]).collect())
            .collect();
        for ((t, jet), friction) in self.touching.iter().zip(&self.jets).zip(&self.friction) {
            match friction {
                Friction::Pin { delta, .. } => {
                    g.extend(pin_rows::<D>(delta));
                    continue;
                }
                Friction::Roll { along, skid: None, .. } => g.extend(along.iter().cloned()),
                _ => {}
            }
            if t.place == Place::Inner {
                if jet.dss <= 0.0 {
                    return None;
                }
                add_place(&mut h, t.force[0], jet);
            }
            // At no load a contact that touches holds as it will once pressed.
            if t.force[0] > 0.0 || self.unloaded {
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
        Some((DMatrix::from_fn(n, z.ncols(), |r, c| z[(r, c)] * s[r]), k))
    }

    /// The joints of the motions that nothing stiffens (those of
    /// [`ContactKkt::reduced`] whose stiffness is zero to the margin, where
    /// the softest is not below it: that is an unstable state, not a free
    /// one), as "joint \"a\" and joint \"b\"".
    fn free_motion(&self, jacobian: &[f64]) -> Option<String> {
        let (z, k) = self.reduced(jacobian)?;
        let eigen = nalgebra::SymmetricEigen::new((&k + k.transpose()) * 0.5);
        let band = 2.0 * self.kkt.margin;
        let least = eigen.eigenvalues.iter().fold(f64::INFINITY, |a, &b| a.min(b));
        if least >= 0.0 || least < -band {
            return None;
        }
        // Every free motion, so that the answer names each joint to hold.
        let free =
            eigen.eigenvalues.iter().zip(eigen.eigenvectors.column_iter()).filter(|(v, _)| (-band..0.0).contains(*v));
        let motion = free.fold(DVector::zeros(z.nrows()), |sum, (_, u)| sum + (&z * u).abs());
        super::path::moving_joints(self.kkt.mechanism, &motion)
    }

    /// The inner contacts' tangency unknowns (and rows) among all.
    fn inner_index(&self) -> Vec<Option<usize>> {
        let mut k = self.inner_dim() + self.touching.iter().map(|t| t.width::<D>()).sum::<usize>();
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
        for t in &self.touching {
            let stuck = matches!(t.law, Law::Stick { .. });
            out.extend((0..t.width::<D>()).map(|k| match (t.pruned.dropped[k], stuck) {
                (true, _) => 0.0,
                (false, true) => (0..3).map(|i| t.pruned.axis(k)[i] * t.force[i]).sum::<f64>() / self.sigma,
                (false, false) => t.force[k] / self.sigma,
            }));
        }
        out.extend(self.touching.iter().filter(|t| t.place == Place::Inner).map(|t| t.at));
        out
    }

    /// The touching contacts' forces and places read from the unknowns `x`.
    fn read(&mut self, x: &[f64]) {
        let (forces, inner) = (self.force_index(), self.inner_index());
        let sigma = self.sigma;
        for (c, t) in self.touching.iter_mut().enumerate() {
            let w = t.width::<D>();
            t.force = [0.0; 3];
            // A row left out holds no force.
            for k in (0..w).filter(|&k| !t.pruned.dropped[k]) {
                let f = x[forces[c] + k] * sigma;
                match t.law {
                    // A stuck one's components are along its axes.
                    Law::Stick { .. } => t.pruned.axis(k).iter().zip(&mut t.force).for_each(|(e, out)| *out += f * e),
                    _ => t.force[k] = f,
                }
            }
            if let Some(i) = inner[c] {
                t.at = x[i];
            }
        }
    }

    /// Contact `c`'s whole force on the toucher (world, after [`Problem::evaluate`]) when it is held:
    /// a stuck end's unknowns, or a rolling one's $Nn + \sum_k f_kt_k$.
    fn held_force(&self, c: usize) -> Option<D::Vector> {
        let t = &self.touching[c];
        match (&t.law, &self.friction[c]) {
            (Law::Stick { .. }, _) => Some(vector::<D>(&t.force)),
            (Law::Roll { .. } | Law::Skid { .. }, Friction::Roll { tangents, .. }) => {
                Some(tangents.iter().enumerate().fold(scaled::<D>(&self.jets[c].normal, t.force[0]), |f, (k, u)| {
                    f + scaled::<D>(u, t.force[1 + k])
                }))
            }
            _ => None,
        }
    }

    /// Contact `c`'s normal force $N$ (after [`Problem::evaluate`]).
    fn normal_force(&self, c: usize) -> f64 {
        match self.held_force(c) {
            Some(f) => dot::<D>(&f, &self.jets[c].normal),
            None => self.touching[c].force[0],
        }
    }

    /// Contact `c`'s friction force (world, after [`Problem::evaluate`]).
    fn friction_force(&self, c: usize) -> D::Vector {
        let (t, n) = (&self.touching[c], self.jets[c].normal);
        match (self.held_force(c), &self.friction[c]) {
            (Some(f), _) => f - scaled::<D>(&n, self.normal_force(c)),
            (None, Friction::Slide { direction, .. }) => scaled::<D>(direction, -self.mu(c) * t.force[0]),
            _ => D::Vector::default(),
        }
    }

    fn mu(&self, c: usize) -> f64 {
        crate::mechanism::contact::friction(self.kkt.mechanism, &self.touching[c].pair)
    }

    /// The geom body's pose of contact `c` (after [`Problem::evaluate`]).
    fn geom_body(&self, c: usize) -> &D::Pose {
        &self.frames.bodies[geom_body(self.kkt.mechanism, &self.touching[c].pair)]
    }

    /// Where contact `c`'s toucher touches, as [`Touching::on`] holds it:
    /// a flexure's arc length, or the point in a ball's body frame (after [`Problem::evaluate`]).
    fn material(&self, c: usize) -> Material {
        let (m, t) = (self.kkt.mechanism, &self.touching[c]);
        let jet = &self.jets[c];
        match (t.s(), corner(m, &t.pair)) {
            (Some(s), _) => on_flexure::<D>(s, &jet.frame, &jet.normal, jet.half),
            (None, Ok(c)) => c.material(&self.frames.bodies, &jet.point),
            (None, Err(_)) => [0.0; 4],
        }
    }

    /// How far contact `c` rolled since the last accepted state: the toucher's
    /// material point `p` that touched there (after [`Problem::evaluate`]),
    /// and the most either surface turned under the contact (rad).
    fn rolled(&self, c: usize, p: &PointJet<'_, D>) -> Result<Rolled<D>> {
        let (m, t, jet) = (self.kkt.mechanism, &self.touching[c], &self.jets[c]);
        let place = (&jet.point, &jet.normal);
        let turn = turned(m, &self.frames, (&t.pair, &t.from), p, place, self.kkt.length)?;
        Ok(Rolled { point: p.x, turn })
    }

    /// Contact `c`'s point in its geom body's frame (after [`Problem::evaluate`]).
    fn local_point(&self, c: usize) -> [f64; 3] {
        array::<D>(&D::position(&D::act(&D::inverse(self.geom_body(c)), &self.jets[c].point)))
    }

    /// What friction adds to contact `c`'s equations at `q` (frames and jets evaluated).
    fn friction_of(&self, c: usize, q: &[f64]) -> Result<Friction<D>> {
        let (m, f, t, jet) = (self.kkt.mechanism, &self.frames, &self.touching[c], &self.jets[c]);
        Ok(match t.law {
            Law::Free => Friction::None,
            Law::Stick { anchor } => {
                let p = point_jet(m, f, q, &t.pair, t.s(), Some(vector::<D>(&anchor)))?;
                let a = D::act(self.geom_body(c), &D::moved(&D::origin(&D::identity()), &vector::<D>(&anchor), 1.0));
                let hessian = p.hessian_along(m, f, &vector::<D>(&t.force));
                Friction::Pin { offset: D::position(&p.x) - D::position(&a), delta: p.delta, hessian }
            }
            Law::Roll { tangents } | Law::Skid { tangents, .. } => {
                let p = material_jet(m, f, q, &t.pair, &t.on, vector::<D>(&t.from))?;
                let a = D::act(self.geom_body(c), &D::moved(&D::origin(&D::identity()), &vector::<D>(&t.from), 1.0));
                let offset = D::position(&p.x) - D::position(&a);
                let tangents: Vec<D::Vector> = tangents[..D::POINT_DIM - 1].iter().map(vector::<D>).collect();
                let offsets: Vec<f64> = tangents.iter().map(|u| dot::<D>(u, &offset)).collect();
                let along = tangents.iter().map(|u| p.delta.iter().map(|d| dot::<D>(u, d)).collect()).collect();
                let w = tangents
                    .iter()
                    .enumerate()
                    .fold(D::Vector::default(), |w, (k, u)| w + scaled::<D>(u, t.force[1 + k]));
                let hessian = p.hessian_along(m, f, &w);
                let rolled = self.rolled(c, &p)?;
                let skid = matches!(t.law, Law::Skid { .. })
                    .then(|| Skid::new(self.mu(c), t, self.sigma, &offsets, self.kkt.length));
                Friction::Roll { offsets, along, hessian, tangents, rolled, skid }
            }
            Law::Slip { direction } => {
                // Where it rolls, friction acts at the material points that
                // met at the last accepted state (as a rolling stuck one's
                // pin), so the slide does work only along the surface.
                let p = if t.rolls() {
                    material_jet(m, f, q, &t.pair, &t.on, vector::<D>(&t.from))?
                } else {
                    point_jet(m, f, q, &t.pair, t.s(), None)?
                };
                let (s, turn) = slide::<D>(&D::rotate(self.geom_body(c), &vector::<D>(&direction)), &jet.normal);
                let along: Vec<f64> = p.delta.iter().map(|d| dot::<D>(&s, d)).collect();
                let n = m.dof();
                let mut jacobian = p.hessian_along(m, f, &s);
                if t.rolls() {
                    // The direction turns with the geom's body: ∂_g ŝ from ω_g × e.
                    let (e, normal) = (D::rotate(self.geom_body(c), &vector::<D>(&direction)), jet.normal);
                    let pe = e - scaled::<D>(&normal, dot::<D>(&normal, &e));
                    let size = dot::<D>(&pe, &pe).sqrt();
                    for &g in &p.geom_columns {
                        let de = D::spin(&f.omega[g], &e);
                        let u = de - scaled::<D>(&normal, dot::<D>(&normal, &de));
                        let ds = scaled::<D>(&(u - scaled::<D>(&s, dot::<D>(&s, &u))), 1.0 / size);
                        for (k, d) in p.delta.iter().enumerate() {
                            jacobian[(g, k)] += dot::<D>(&ds, d);
                        }
                    }
                } else {
                    // The geom's material point under the end moves with it.
                    for &g in &p.geom_columns {
                        for b in 0..n {
                            jacobian[(b, g)] -= D::triple(&s, &f.omega[g], &p.delta[b]);
                        }
                    }
                }
                for b in 0..n {
                    let ds = turn(&jet.normal_jacobian[b]);
                    for (c, d) in p.delta.iter().enumerate() {
                        jacobian[(b, c)] += dot::<D>(&ds, d);
                    }
                }
                // Inside a span the normal turns with the place: ∂ŝ/∂s·Δ_c.
                let ds = if t.place == Place::Inner {
                    let along_s = turn(&jet.normal_ds);
                    p.delta.iter().map(|d| dot::<D>(&along_s, d)).collect()
                } else {
                    vec![0.0; n]
                };
                let rolled = if t.rolls() { Some(self.rolled(c, &p)?) } else { None };
                Friction::Slide { direction: s, along, jacobian, ds, rolled }
            }
        })
    }
}

impl<D: Statics> ContactKkt<'_, D> {
    /// Anchors a contact that `event` made stick where it meets the geom:
    /// a new touch between its point in the state `x` at `lambda` (just
    /// apart) and where the event found it (just inside), where the gap
    /// is zero along that chord; a sliding contact that turns back where
    /// it is in `x`. A stuck end is stiff along the surface, so an anchor
    /// off by the bisection's width would be a force of its own.
    fn anchor(&mut self, x: &[f64], lambda: f64, event: Event) -> Result<()> {
        let c = match event {
            Event::Stick(c, ..) | Event::AtEnd(c, _) => c,
            Event::Touch { .. } => self.touching.len() - 1,
            _ => return Ok(()),
        };
        if !matches!(self.touching[c].law, Law::Stick { .. }) {
            return Ok(());
        }
        let mut r = vec![0.0; self.dim()];
        self.evaluate(x, lambda, &mut r, None, None)?;
        let here = self.local_point(c);
        let anchor = match event {
            Event::Touch { point: there, gap: inside, .. } => {
                // Where the gap is zero on the line through here and there (here, where it does not change).
                let change = self.jets[c].gap - inside;
                let t = if change != 0.0 { self.jets[c].gap / change } else { 0.0 };
                std::array::from_fn(|i| here[i] + t * (there[i] - here[i]))
            }
            _ => here,
        };
        self.touching[c].law = Law::Stick { anchor };
        Ok(())
    }

    /// Leaves out each stuck or rolling contact's friction rows that depend
    /// on the rows before them at the state `x` (at `lambda`), and sets `x`
    /// in the forces' new components. The rows go in order: the
    /// closures', each contact's push (never left out), then each
    /// contact's tangential rows. Its force is otherwise indeterminate (a
    /// lid's box stopped on a rough rail: the push already stops the one
    /// coordinate that the rail's tangent across it moves), and Newton
    /// would leave it where it started. Of a contact's tangential rows,
    /// what the rows before leave of them, $r_k$, is split along the
    /// eigenvectors of $r_ir_j$, and a direction whose part is under
    /// $10^{-9}$ of the contact's largest row is left out, its friction
    /// held at 0: of the forces that hold the same equilibrium, the least
    /// friction. A contact none of whose rows depends keeps its own
    /// components (nothing changes where the force is determinate).
    fn prune(&mut self, x: &mut Vec<f64>, lambda: f64) -> Result<()> {
        self.read(x);
        for t in &mut self.touching {
            t.pruned = Pruned::default();
        }
        *x = self.state(x);
        let size = self.dim();
        let (mut r, mut jac) = (vec![0.0; size], vec![0.0; size * size]);
        self.evaluate(x, lambda, &mut r, Some(&mut jac), None)?;
        let (n, kd) = (self.kkt.mechanism.dof(), self.inner_dim());
        let mut basis = linalg::Basis::default();
        for i in n..kd {
            basis.add(&(0..n).map(|c| self.inner[c * kd + i]).collect::<Vec<_>>());
        }
        // Each contact's push row; then its tangential rows.
        let mut tangential: Vec<Option<Along>> = Vec::new();
        for (c, t) in self.touching.iter().enumerate() {
            let normal = &self.jets[c].normal;
            let (push, rest) = match (&self.friction[c], t.law) {
                (Friction::Pin { delta, .. }, _) => {
                    let row = |e: &D::Vector| delta.iter().map(|d| dot::<D>(e, d)).collect::<Vec<f64>>();
                    let units = tangents::<D>(&array::<D>(normal), None)[..D::POINT_DIM - 1].to_vec();
                    let rows = units.iter().map(|e| row(&vector::<D>(e))).collect();
                    (row(normal), Some((units, rows)))
                }
                (Friction::Roll { along, skid: None, .. }, Law::Roll { tangents: u }) => {
                    (self.jets[c].gradient.clone(), Some((u[..D::POINT_DIM - 1].to_vec(), along.clone())))
                }
                _ => (self.jets[c].gradient.clone(), None),
            };
            basis.add(&push);
            tangential.push(rest.map(|(units, rows): (_, Vec<Vec<f64>>)| {
                let largest = rows.iter().chain([&push]).map(|r| linalg::norm(r)).fold(0.0, f64::max);
                Along { units, rows, largest }
            }));
        }
        for (c, rest) in tangential.into_iter().enumerate() {
            let Some(Along { units, rows, largest }) = rest else { continue };
            let (turned, kept) = linalg::turn_rows(&mut basis, &rows, &units, largest);
            if kept.iter().all(|&k| k) {
                continue;
            }
            let normal = array::<D>(&self.jets[c].normal);
            let t = &mut self.touching[c];
            let mut axes = [[0.0; 3]; 3];
            axes[0] = normal;
            axes[1..1 + turned.len()].copy_from_slice(&turned);
            for (k, &keep) in kept.iter().enumerate() {
                t.pruned.dropped[1 + k] = !keep;
            }
            match &mut t.law {
                Law::Stick { .. } => t.pruned.axes = Some(axes),
                Law::Roll { tangents: u } => {
                    // Its friction, in the new tangents.
                    let f: [f64; 3] =
                        std::array::from_fn(|i| (0..turned.len()).map(|k| t.force[1 + k] * u[k][i]).sum());
                    for (k, e) in turned.iter().enumerate() {
                        u[k] = *e;
                        t.force[1 + k] = (0..3).map(|i| e[i] * f[i]).sum();
                    }
                }
                _ => {}
            }
        }
        *x = self.state(x);
        Ok(())
    }

    /// The most a sliding contact turned its way in the state last
    /// evaluated, from its direction to the way it moved since the last
    /// accepted state (rad; 0 in the plane, where it only keeps its sense).
    fn slide_turn(&self) -> f64 {
        let length = self.kkt.length;
        (0..self.touching.len())
            .filter_map(|c| {
                let (_, size, ahead) = self.slid(c)?;
                (size > 1e-9 * length).then(|| (ahead / size).clamp(-1.0, 1.0).acos())
            })
            .fold(0.0, f64::max)
    }

    /// The most a skidding contact's friction turned since the last
    /// accepted state, in the state last evaluated (rad).
    fn skid_turn(&self) -> f64 {
        self.touching
            .iter()
            .filter_map(|t| match t.law {
                Law::Skid { accepted: a, .. } => {
                    let f = [t.force[1], t.force[2]];
                    let cross = a[0] * f[1] - a[1] * f[0];
                    Some(cross.atan2(a[0] * f[0] + a[1] * f[1]).abs())
                }
                _ => None,
            })
            .fold(0.0, f64::max)
    }

    /// The most a rolling contact with friction turned either surface under
    /// it since the last accepted state, in the state last evaluated (rad).
    fn roll_turn(&self) -> f64 {
        self.friction
            .iter()
            .filter_map(|f| match f {
                Friction::Roll { rolled, .. } | Friction::Slide { rolled: Some(rolled), .. } => Some(rolled.turn),
                _ => None,
            })
            .fold(0.0, f64::max)
    }

    /// Sliding contact `c`'s motion since the last accepted state, in its
    /// geom body's frame (after [`Problem::evaluate`]): the move, its
    /// length and its part along the sliding direction; `None` unless it
    /// slides. Where it rolls, the motion of the toucher's material point
    /// that touched there.
    fn slid(&self, c: usize) -> Option<([f64; 3], f64, f64)> {
        let t = &self.touching[c];
        let Law::Slip { direction } = t.law else { return None };
        let mut moved: [f64; 3] = match &self.friction[c] {
            Friction::Slide { rolled: Some(r), .. } => {
                // Where it rolls, the material point also leaves the surface: only its slide counts.
                let inverse = D::inverse(self.geom_body(c));
                let here = D::position(&D::act(&inverse, &r.point)) - vector::<D>(&t.from);
                let n = D::rotate(&inverse, &self.jets[c].normal);
                array::<D>(&(here - scaled::<D>(&n, dot::<D>(&n, &here))))
            }
            _ => {
                let here = self.local_point(c);
                std::array::from_fn(|i| if i < D::POINT_DIM { here[i] - t.from[i] } else { 0.0 })
            }
        };
        moved[D::POINT_DIM..].fill(0.0);
        let size = moved.iter().map(|v| v * v).sum::<f64>().sqrt();
        let ahead = (0..D::POINT_DIM).map(|i| moved[i] * direction[i]).sum();
        Some((moved, size, ahead))
    }

    /// Takes the state last evaluated as accepted: each contact's point is
    /// where the next step's motion is measured from, a sliding contact's
    /// direction turns to the way it moved (in the plane it only keeps its
    /// sense), and a rolling stuck one is pinned anew where it touches.
    fn accept(&mut self) {
        let length = self.kkt.length;
        for c in 0..self.touching.len() {
            let (here, slid, on) = (self.local_point(c), self.slid(c), self.material(c));
            let normal = array::<D>(&self.jets[c].normal);
            let t = &mut self.touching[c];
            if let Law::Roll { tangents: u } = &mut t.law {
                *u = tangents::<D>(&normal, Some(u));
            }
            if let Law::Skid { tangents: u, accepted } = &mut t.law {
                // Its friction, kept in the new tangents.
                let old = *u;
                *u = tangents::<D>(&normal, Some(u));
                let f: [f64; 3] = std::array::from_fn(|i| t.force[1] * old[0][i] + t.force[2] * old[1][i]);
                *accepted = u.map(|e| (0..3).map(|i| e[i] * f[i]).sum());
            }
            t.on = on;
            if let (Law::Slip { direction }, Some((moved, size, ahead))) = (&mut t.law, slid)
                && size > 1e-9 * length
                && ahead > 0.0
            {
                for i in 0..D::POINT_DIM {
                    direction[i] = moved[i] / size;
                }
            }
            t.from = here;
        }
    }
}

/// A skidding contact's tangential rows ([`Law::Skid`]), in the unknowns'
/// units ($F_k = f_k/\sigma$, $\nu = N/\sigma$): with $w = F - r/\ell$ ($r_k =
/// t_k\cdot(x - a)$, the material points' slide since the last accepted
/// state),
/// $$F_k - \mu\nu\frac{w_k}{\lvert w\rvert} = 0,$$
/// Alart and Curnier's sliding rows: $\lvert F\rvert = \mu\nu$ and $F$ along
/// $w$, so $r = \ell F(1 - \lvert w\rvert/\mu\nu)$ lies against $F$ while
/// $\lvert w\rvert > \mu\nu$ (the slide turned back is a stick event). The
/// direction is solved with the step (implicit Euler), and the rows stay
/// regular where the slide starts ($r = 0$, $w = F \ne 0$). With their
/// derivatives in $\nu$, in each $F_i$ and in each $r_i$ (per metre).
struct Skid {
    rows: [f64; 2],
    normal: [f64; 2],
    friction: [[f64; 2]; 2],
    offset: [[f64; 2]; 2],
}

impl Skid {
    fn new(mu: f64, t: &Touching, sigma: f64, offsets: &[f64], length: f64) -> Skid {
        let m = offsets.len();
        let (nu, f) = (t.force[0] / sigma, [t.force[1] / sigma, t.force[2] / sigma]);
        let w: [f64; 2] = std::array::from_fn(|k| if k < m { f[k] - offsets[k] / length } else { 0.0 });
        let size = w.iter().map(|v| v * v).sum::<f64>().sqrt().max(f64::MIN_POSITIVE);
        let unit = w.map(|v| v / size);
        let projector = |k: usize, i: usize| f64::from(u8::from(k == i)) - unit[k] * unit[i];
        Skid {
            rows: std::array::from_fn(|k| f[k] - mu * nu * unit[k]),
            normal: unit.map(|u| -mu * u),
            friction: std::array::from_fn(|k| {
                std::array::from_fn(|i| f64::from(u8::from(k == i)) - mu * nu * projector(k, i) / size)
            }),
            offset: std::array::from_fn(|k| std::array::from_fn(|i| mu * nu * projector(k, i) / (size * length))),
        }
    }
}

/// $\hat s = Pe/\lvert Pe\rvert$, $P = I - nn^T$: the slide direction `e`
/// kept in the tangent plane of the normal `n`, with its derivative along
/// a change of $n$.
fn slide<D: Statics>(e: &D::Vector, n: &D::Vector) -> (D::Vector, impl Fn(&D::Vector) -> D::Vector + use<D>) {
    let (e, n) = (*e, *n);
    let ne = dot::<D>(&n, &e);
    let u = e - scaled::<D>(&n, ne);
    let size = dot::<D>(&u, &u).sqrt();
    let s = scaled::<D>(&u, 1.0 / size);
    (s, move |dn: &D::Vector| {
        let du = scaled::<D>(dn, -ne) - scaled::<D>(&n, dot::<D>(dn, &e));
        scaled::<D>(&(du - scaled::<D>(&s, dot::<D>(&s, &du))), 1.0 / size)
    })
}

/// The body of the geom `pair` touches ([`touched`]).
fn geom_body<D: Statics>(m: &Mechanism<D>, pair: &Pair) -> usize {
    touched(m, pair).body
}

/// A stuck contact's constraint rows, $\partial_c(x - a)$ per component.
fn pin_rows<D: Statics>(delta: &[D::Vector]) -> impl Iterator<Item = Vec<f64>> + '_ {
    (0..D::POINT_DIM).map(move |k| delta.iter().map(|d| d[k]).collect())
}

/// Adds an inner contact's place eliminated from the stiffness `h`:
/// $N g_{qs}g_{sq}/g_{ss}$ (the Hessian of $-Ng$ at the least in $s$).
fn add_place<D: Statics>(h: &mut DMatrix<f64>, force: f64, jet: &GapJet<D>) {
    let n = h.nrows();
    for r in 0..n {
        for c in 0..n {
            h[(r, c)] += force * jet.dqs[r] * jet.dqs[c] / jet.dss;
        }
    }
}

impl<D: Statics> Problem<f64> for ContactKkt<'_, D> {
    fn dim(&self) -> usize {
        let forces: usize = self.touching.iter().map(|t| t.width::<D>()).sum();
        self.inner_dim() + forces + self.touching.iter().filter(|t| t.place == Place::Inner).count()
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
        self.friction.clear();
        for c in 0..count {
            let f = self.friction_of(c, q)?;
            self.friction.push(f);
        }
        let (forces, index) = (self.force_index(), self.inner_index());
        let (rows, length, sigma) = (&self.kkt.row_scale, self.kkt.length, self.sigma);
        for (c, (t, jet)) in self.touching.iter().zip(&self.jets).enumerate() {
            let at = forces[c];
            match &self.friction[c] {
                Friction::Pin { offset, delta, .. } => {
                    let force = vector::<D>(&t.force);
                    for i in 0..n {
                        residual[i] -= dot::<D>(&force, &delta[i]) * rows[i];
                    }
                    for k in 0..D::POINT_DIM {
                        let e = vector::<D>(&t.pruned.axis(k));
                        residual[at + k] = if t.pruned.dropped[k] { x[at + k] } else { dot::<D>(&e, offset) / length };
                    }
                }
                Friction::Roll { offsets, along, skid, .. } => {
                    for i in 0..n {
                        let tangential: f64 = along.iter().enumerate().map(|(k, a)| t.force[1 + k] * a[i]).sum();
                        residual[i] -= (t.force[0] * jet.gradient[i] + tangential) * rows[i];
                    }
                    residual[at] = jet.gap / length;
                    for (k, r) in offsets.iter().enumerate() {
                        residual[at + 1 + k] = match t.pruned.dropped[1 + k] {
                            true => x[at + 1 + k],
                            false => skid.as_ref().map_or(r / length, |s| s.rows[k]),
                        };
                    }
                }
                other => {
                    let mu = crate::mechanism::contact::friction(m, &t.pair);
                    for i in 0..n {
                        let along = if let Friction::Slide { along, .. } = other { mu * along[i] } else { 0.0 };
                        residual[i] -= t.force[0] * (jet.gradient[i] - along) * rows[i];
                    }
                    residual[at] = jet.gap / length;
                }
            }
            if let Some(f) = index[c] {
                residual[f] = jet.ds;
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
                let row = forces[c];
                let force = t.force[0];
                match &self.friction[c] {
                    Friction::Pin { delta, hessian, .. } => {
                        for j in 0..n {
                            for i in 0..n {
                                jac[j * size + i] -= hessian[(i, j)] * rows[i];
                            }
                            for k in (0..D::POINT_DIM).filter(|&k| !t.pruned.dropped[k]) {
                                let along = dot::<D>(&vector::<D>(&t.pruned.axis(k)), &delta[j]);
                                jac[(row + k) * size + j] = -sigma * along * rows[j];
                                jac[j * size + row + k] = along / length;
                            }
                        }
                        for k in (0..D::POINT_DIM).filter(|&k| t.pruned.dropped[k]) {
                            jac[(row + k) * size + row + k] = 1.0;
                        }
                    }
                    Friction::None => {
                        for j in 0..n {
                            for i in 0..n {
                                jac[j * size + i] -= force * jet.hessian[(i, j)] * rows[i];
                            }
                            jac[row * size + j] = -sigma * jet.gradient[j] * rows[j];
                            jac[j * size + row] = jet.gradient[j] / length;
                        }
                    }
                    Friction::Roll { along, hessian, skid, .. } => {
                        for j in 0..n {
                            for i in 0..n {
                                jac[j * size + i] -= (force * jet.hessian[(i, j)] + hessian[(i, j)]) * rows[i];
                            }
                            jac[row * size + j] = -sigma * jet.gradient[j] * rows[j];
                            jac[j * size + row] = jet.gradient[j] / length;
                            for (k, a) in along.iter().enumerate().filter(|(k, _)| !t.pruned.dropped[1 + k]) {
                                jac[(row + 1 + k) * size + j] = -sigma * a[j] * rows[j];
                                jac[j * size + row + 1 + k] = a[j] / length;
                            }
                        }
                        for k in (0..along.len()).filter(|&k| t.pruned.dropped[1 + k]) {
                            jac[(row + 1 + k) * size + row + 1 + k] = 1.0;
                        }
                        if let Some(s) = skid {
                            for k in 0..along.len() {
                                for j in 0..n {
                                    jac[j * size + row + 1 + k] =
                                        along.iter().enumerate().map(|(i, a)| s.offset[k][i] * a[j]).sum();
                                }
                                jac[row * size + row + 1 + k] = s.normal[k];
                                for i in 0..along.len() {
                                    jac[(row + 1 + i) * size + row + 1 + k] = s.friction[k][i];
                                }
                            }
                        }
                    }
                    Friction::Slide { along, jacobian, .. } => {
                        let mu = crate::mechanism::contact::friction(m, &t.pair);
                        for j in 0..n {
                            for i in 0..n {
                                jac[j * size + i] -= force * (jet.hessian[(i, j)] - mu * jacobian[(j, i)]) * rows[i];
                            }
                            jac[row * size + j] = -sigma * (jet.gradient[j] - mu * along[j]) * rows[j];
                            jac[j * size + row] = jet.gradient[j] / length;
                        }
                    }
                }
                if let Some(f) = index[c] {
                    let (column, tangency) = (f, f);
                    let mu = crate::mechanism::contact::friction(m, &t.pair);
                    for i in 0..n {
                        let turning = match &self.friction[c] {
                            Friction::Slide { ds, .. } => mu * ds[i],
                            _ => 0.0,
                        };
                        jac[column * size + i] = -force * (jet.dqs[i] - turning) * rows[i] * t.length;
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
        self.reduced(jacobian).is_some_and(|(_, k)| linalg::is_positive_definite(&k))
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
    /// Touching contact `c` pulls, or, of two edges crossing, no longer
    /// crosses them ([`crate::mechanism::contact::edges_cross`]).
    Open(usize),
    /// Touching contact `c`, of two edges crossing, ran off an edge's end:
    /// the corner there (`pair`) takes its touch and force (world) at
    /// `point` (the new geom body's frame), where its toucher's material
    /// point is `on` and the normal `normal` (world).
    HandOff { c: usize, pair: Pair, point: [f64; 3], on: Material, normal: [f64; 3], force: [f64; 3] },
    /// Inner contact `c` reached the end at this arc length.
    AtEnd(usize, f64),
    /// End contact `c`'s flexure turns into the geom beside the end, whose normal is this (world).
    Roll(usize, [f64; 3]),
    /// The pair's gap has a least below the tolerance.
    Touch {
        pair: Pair,
        /// Its arc length on a flexure.
        s: Option<f64>,
        /// Where, in the geom body's frame.
        point: [f64; 3],
        /// Where on the toucher, as [`Touching::on`].
        on: Material,
        /// The geom's normal there (world).
        normal: [f64; 3],
        /// Whether a flexure's centreline touches there at an end, or a box's
        /// sharp corner (a material point).
        bare_end: bool,
        /// Whether a flexure touches there with a thickness.
        thick: bool,
        gap: f64,
    },
    /// Stuck contact `c` needs more than $\mu N$: it slides along this
    /// direction (geom body's frame), with this $N$.
    /// Where it rolls, its point in the geom body's frame and the toucher's
    /// material point there, from where its slide is measured.
    Slip(usize, [f64; 3], f64, [f64; 3], Material),
    /// Sliding contact `c` turned back: it sticks here (geom body's frame)
    /// with this force (world), where the normal is this (world), the
    /// toucher's material point there as [`Touching::on`] last.
    Stick(usize, [f64; 3], [f64; 3], [f64; 3], Material),
    /// The equilibrium is no longer stable.
    Unstable,
    /// The equilibrium is no longer stable where contact `c` lies flat
    /// along its geom ([`FLAT_CURVATURE`]): distributed contact.
    LiesAlong(usize),
    /// Two geoms went through each other edge across edge, and none of
    /// their gaps is negative ([`crate::mechanism::contact::crossed_edges`]):
    /// the bisection lands where they touch, which is never this.
    PassedThrough(Pair),
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
    let scale = problem.sigma * problem.kkt.scale();
    let pull = -FORCE_TOLERANCE * scale;
    for c in 0..problem.touching.len() {
        let (t, jet) = (&problem.touching[c], &problem.jets[c]);
        let normal = problem.normal_force(c);
        if normal < pull {
            return Ok(Some(Event::Open(c)));
        }
        // Two edges whose crossing left either edge: the corner there takes the touch.
        if let Some(k) = crossing_of(m, &t.pair, &problem.frames.bodies).filter(|k| !k.applies()) {
            let Some(pair) = ran_off(m, &t.pair, &k, 0.0) else { return Ok(Some(Event::Open(c))) };
            let bodies = &problem.frames.bodies;
            let body = &bodies[geom_body(m, &pair)];
            let point = array::<D>(&D::position(&D::act(&D::inverse(body), &jet.point)));
            let taker = corner(m, &pair)?;
            let on = taker.material(bodies, &jet.point);
            // Where the corner is the other geom's, toucher and touched swap: the normal and force turn over.
            let sign = if std::ptr::eq(taker.round, corner(m, &t.pair)?.round) { 1.0 } else { -1.0 };
            let force = scaled::<D>(&(scaled::<D>(&jet.normal, normal) + problem.friction_force(c)), sign);
            let (normal, force) = (array::<D>(&scaled::<D>(&jet.normal, sign)), array::<D>(&force));
            return Ok(Some(Event::HandOff { c, pair, point, on, normal, force }));
        }
        match t.place {
            Place::Inner if !(0.0..=1.0).contains(&t.at) => {
                return Ok(Some(Event::AtEnd(c, t.at.clamp(0.0, 1.0) * t.length)));
            }
            Place::End(s) if (s > 0.0 && jet.ds > ROLL_TOLERANCE) || (s == 0.0 && jet.ds < -ROLL_TOLERANCE) => {
                return Ok(Some(Event::Roll(c, array::<D>(&jet.normal))));
            }
            _ => {}
        }
        let body = problem.geom_body(c);
        match t.law {
            Law::Stick { .. } | Law::Roll { .. } => {
                let tangential = problem.friction_force(c);
                let size = dot::<D>(&tangential, &tangential).sqrt();
                if size > problem.mu(c) * normal + FORCE_TOLERANCE * scale {
                    let direction = D::rotate(&D::inverse(body), &scaled::<D>(&tangential, -1.0 / size));
                    let (here, on) = (problem.local_point(c), problem.material(c));
                    return Ok(Some(Event::Slip(c, array::<D>(&direction), normal, here, on)));
                }
            }
            Law::Skid { .. } => {
                // Its slide since the last accepted state, along its friction.
                let Friction::Roll { offsets, .. } = &problem.friction[c] else { continue };
                let f = &t.force[1..D::POINT_DIM];
                let size = f.iter().map(|v| v * v).sum::<f64>().sqrt().max(f64::MIN_POSITIVE);
                let ahead = -offsets.iter().zip(f).map(|(r, f)| r * f).sum::<f64>() / size;
                if ahead < -GAP_TOLERANCE * problem.kkt.length {
                    let force = problem.held_force(c).expect("a skidding contact is held");
                    let normal = array::<D>(&jet.normal);
                    let (here, on) = (problem.local_point(c), problem.material(c));
                    return Ok(Some(Event::Stick(c, here, array::<D>(&force), normal, on)));
                }
            }
            Law::Slip { .. } => {
                let (_, _, ahead) = problem.slid(c).expect("a sliding contact");
                if ahead < -GAP_TOLERANCE * problem.kkt.length {
                    let force = scaled::<D>(&jet.normal, normal) + problem.friction_force(c);
                    let normal = array::<D>(&jet.normal);
                    let (here, on) = (problem.local_point(c), problem.material(c));
                    return Ok(Some(Event::Stick(c, here, array::<D>(&force), normal, on)));
                }
            }
            Law::Free => {}
        }
    }
    let length = problem.kkt.length;
    let below = if problem.resting { GAP_TOLERANCE } else { -GAP_TOLERANCE } * length;
    if let Some(touch) = new_touch(problem, &x[..m.dof()], all, below)? {
        return Ok(Some(touch));
    }
    // Through each other between two states, and no gap negative: the bisection finds where they touch.
    if let Some(pair) = crossed_edges(m, &problem.frames.bodies, all, 2.0 * GAP_TOLERANCE * length) {
        return Ok(Some(Event::PassedThrough(pair)));
    }
    if !problem.stable(x, lambda, &jac) {
        // Flat against the geom, with no slope along it at an end: the
        // strip begins to lie along it, not to buckle.
        let flat = (0..problem.touching.len()).find(|&c| {
            let (t, jet) = (&problem.touching[c], &problem.jets[c]);
            let level = matches!(t.place, Place::Inner) || jet.ds.abs() <= FLAT_CURVATURE;
            t.s().is_some() && level && jet.dss * t.length <= FLAT_CURVATURE
        });
        if flat.is_none() && problem.unloaded && !problem.resting {
            // Unstable from no load: the pairs that meet hold what rests on them (a box set on a floor).
            problem.resting = true;
            if let Some(touch) = new_touch(problem, &x[..m.dof()], all, GAP_TOLERANCE * length)? {
                return Ok(Some(touch));
            }
        }
        // At no load, a motion nothing stiffens: the equilibrium is not one point.
        if flat.is_none()
            && problem.unloaded
            && let Some(joints) = problem.free_motion(&jac)
        {
            return Err(Error::Singular {
                what: format!(
                    "mechanism equilibrium with contact: the mechanism moves freely at no load ({joints}), held neither by a stiffness nor by a geom it rests on (a geom without friction holds only across its surface): its equilibrium is not one point; give a joint on it a stiffness or the geom friction, or hold it with a closure"
                ),
            });
        }
        return Ok(Some(flat.map_or(Event::Unstable, Event::LiesAlong)));
    }
    Ok(None)
}

/// The first pair (of `all`, at `q`, last evaluated by `problem`) whose
/// least gap lies below `below` where no touching contact of it is: a new
/// contact.
fn new_touch<D: Statics>(problem: &ContactKkt<D>, q: &[f64], all: &[Pair], below: f64) -> Result<Option<Event>> {
    let m = problem.kkt.mechanism;
    for pair in all {
        let near: Vec<&Touching> = problem.touching.iter().filter(|t| t.pair == *pair).collect();
        for low in minima(m, q, &problem.frames.bodies, pair)? {
            let known = near.iter().any(|t| match (t.s(), low.s) {
                (Some(a), Some(b)) => (a - b).abs() <= FLAT_LENGTH * t.length,
                _ => true,
            });
            if low.gap < below && !known {
                let body = &problem.frames.bodies[geom_body(m, pair)];
                let at = array::<D>(&D::position(&D::act(&D::inverse(body), &low.point)));
                let (bare_end, thick, on) = match (pair.part, low.s) {
                    (Toucher::Flexure(j), Some(s)) => {
                        let (f, offset) = (m.joints[j].kind.flexure().expect("a flexure pair"), m.joints[j].offset);
                        let length = D::flexure_length(f);
                        let alpha = &q[offset..offset + m.joints[j].kind.joint().dof()];
                        let half = D::surface_at(f, alpha, s)?.2;
                        let on = match half != 0.0 {
                            true => {
                                let jet = gap_jet(m, &problem.frames, q, pair, Some(s))?;
                                on_flexure::<D>(s, &jet.frame, &jet.normal, jet.half)
                            }
                            false => [s, 0.0, 0.0, 0.0],
                        };
                        ((s <= 1e-9 * length || s >= (1.0 - 1e-9) * length) && half == 0.0, half != 0.0, on)
                    }
                    _ => {
                        // A box's sharp corner is one material point, as a
                        // flexure's bare end; two edges' crossing moves along
                        // both, and rolls.
                        let round = corner(m, pair)?;
                        let one = round.sharp() && round.edge.is_none();
                        (one, false, round.material(&problem.frames.bodies, &low.point))
                    }
                };
                let normal = array::<D>(&low.normal);
                return Ok(Some(Event::Touch {
                    pair: *pair,
                    s: low.s,
                    point: at,
                    on,
                    normal,
                    bare_end,
                    thick,
                    gap: low.gap,
                }));
            }
        }
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
        Event::HandOff { c, pair, point, on, normal, force } => {
            // The same touch, force and law, now of one material point (or a capsule's end ball, which rolls).
            let sharp = corner(m, &pair)?.sharp();
            let t = &mut out[c];
            (t.pair, t.from, t.on) = (pair, point, on);
            t.place = if sharp { Place::Corner } else { Place::Geoms };
            let along = |v: &[f64; 3]| (0..3).map(|i| force[i] * v[i]).sum::<f64>();
            (t.law, t.force) = match t.law {
                Law::Free => (Law::Free, [along(&normal), 0.0, 0.0]),
                _ if sharp => (Law::Stick { anchor: point }, force),
                _ => {
                    let u = tangents::<D>(&normal, None);
                    (Law::Roll { tangents: u }, [along(&normal), along(&u[0]), along(&u[1])])
                }
            };
        }
        Event::AtEnd(c, s) => {
            out[c].place = Place::End(s);
            // A bare end is one material point: pinned where it is ([`ContactKkt::anchor`]).
            if let (Law::Roll { .. }, false) = (out[c].law, out[c].thick) {
                out[c].law = Law::Stick { anchor: out[c].from };
                out[c].force = [0.0; 3];
            }
        }
        Event::Roll(c, normal) => {
            // Just inside the end, where Newton finds the least.
            let s = out[c].s().unwrap_or(0.0);
            if let Law::Stick { anchor } = out[c].law {
                (out[c].from, out[c].on) = (anchor, [s, 0.0, 0.0, 0.0]);
                out[c].law = Law::Roll { tangents: tangents::<D>(&normal, None) };
                out[c].force = [0.0; 3];
            }
            out[c].at = if s > 0.0 { 1.0 - 1e-6 } else { 1e-6 };
            out[c].place = Place::Inner;
        }
        Event::Slip(c, _, _, here, on) if D::POINT_DIM == 3 && matches!(out[c].law, Law::Roll { .. }) => {
            // In space its slide's direction turns with the rolling: it is
            // solved with each step, from the force it had stuck.
            if let Law::Roll { tangents } = out[c].law {
                out[c].law = Law::Skid { tangents, accepted: [out[c].force[1], out[c].force[2]] };
            }
            (out[c].from, out[c].on) = (here, on);
        }
        Event::Slip(c, direction, normal, here, on) => {
            // A rolling contact slides from where it begins to: what it
            // rolled since the last accepted state is no slide.
            if out[c].rolls() {
                (out[c].from, out[c].on) = (here, on);
            }
            out[c].law = Law::Slip { direction };
            out[c].force = [normal, 0.0, 0.0];
        }
        Event::Stick(c, anchor, force, normal, on) if out[c].rolls() => {
            out[c].on = on;
            let u = tangents::<D>(&normal, None);
            let along = |v: &[f64; 3]| (0..3).map(|i| force[i] * v[i]).sum::<f64>();
            out[c].law = Law::Roll { tangents: u };
            out[c].force = [along(&normal), along(&u[0]), along(&u[1])];
            out[c].from = anchor;
        }
        Event::Stick(c, anchor, force, ..) => {
            out[c].law = Law::Stick { anchor };
            out[c].force = force;
        }
        Event::Touch { pair, s, point, on, normal, bare_end, thick, .. } => {
            let length = length(m, &pair);
            let place = match s {
                None if bare_end => Place::Corner,
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
            let law = match (crate::mechanism::contact::friction(m, &pair) > 0.0, bare_end, thick) {
                (false, ..) => Law::Free,
                (true, true, _) => Law::Stick { anchor: point },
                (true, false, _) => Law::Roll { tangents: tangents::<D>(&normal, None) },
            };
            let pruned = Pruned::default();
            out.push(Touching { pair, place, law, force: [0.0; 3], at, length, from: point, on, thick, pruned });
        }
        Event::Unstable => {
            return Err(Error::Unstable { what: "mechanism equilibrium with contact", load_fraction: lambda });
        }

        Event::LiesAlong(c) => {
            let at = format!("{} (at {:.4} % of the load)", named(m, &touching[c].pair), 100.0 * lambda);
            return Err(Error::invalid("geom", at, LIES_ALONG));
        }
        Event::PassedThrough(pair) => {
            let at = format!("{} (at {:.4} % of the load)", named(m, &pair), 100.0 * lambda);
            return Err(Error::invalid("geom", at, PASSED_THROUGH));
        }
    }
    // Each stuck force in the world's axes, all rows held, until [`ContactKkt::prune`].
    for t in &mut out {
        t.pruned = Pruned::default();
    }
    Ok(out)
}

const FRICTION_LIMIT: &str = "mechanism equilibrium with contact (friction's limit: where a contact's friction reaches μN, no contact can slide on under more load)";

/// Each touching contact's pair and whether it slides.
fn sliding(touching: &[Touching]) -> Vec<(Pair, bool)> {
    touching.iter().map(|t| (t.pair, matches!(t.law, Law::Slip { .. } | Law::Skid { .. }))).collect()
}

const LIES_ALONG: &str =
    "touch along an interval (distributed contact), which is not solved: the flexure lies along the geom";

fn lies_along<D: Statics>(m: &Mechanism<D>, pair: &Pair) -> Error {
    Error::invalid("geom", named(m, pair), LIES_ALONG)
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
    // As a position closure row's multiplier: the stiffest joint's moment
    // over ℓ, in N (a slider's k alone, not its k ℓ², made a ball on free
    // sliders 1 cm across judge its forces 1e4 times too coarsely).
    let sigma = kkt.stiffest / length;
    let x0 = kkt.state(&start.q, &start.multipliers);
    let mut problem = ContactKkt {
        kkt,
        touching: start.touching,
        frames: Frames::new(m),
        inner: Vec::new(),
        sigma,
        jets: Vec::new(),
        friction: Vec::new(),
        unloaded: from.is_none(),
        resting: false,
    };
    let mut x = problem.state(&x0);
    let mut lambda = 0.0;
    let mut step = FIRST_STEP;
    let mut previous: Option<(f64, Vec<f64>)> = None;
    let (mut steps, mut iterations, mut residual) = (0, 0, 0.0);
    let mut touched = start.touched;
    // The load where a slip last stuck again at once, with no step since.
    let mut restuck: Option<f64> = None;
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
    settle_events(&mut problem, &mut x, 0.0, settings, all, &mut touched, &mut iterations, false)?;
    (problem.unloaded, problem.resting) = (false, false);
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
            Err(e @ Error::Interrupted { .. }) => return Err(e),
            Err(e) => {
                step *= 0.5;
                if step < SMALLEST_STEP {
                    return Err(match e {
                        Error::ContinuationStalled { .. } => e,
                        other => stalled(lambda, steps, residual, snapping(m, &problem.touching, other)),
                    });
                }
                continue;
            }
        };
        iterations += report.iterations;
        let Some(found) = found else {
            // A slide that turns is followed in steps that turn it little,
            // each along the way it moved (its direction lags by one step,
            // or, rolling in space, is solved with it);
            // a contact that rolls with friction, in steps that roll it
            // little (its material points are pinned anew at each).
            let turned = problem.slide_turn() > MAX_SLIDE_TURN
                || problem.skid_turn() > MAX_SKID_TURN
                || problem.roll_turn() > MAX_ROLL_TURN;
            if turned && step > 1e3 * SMALLEST_STEP {
                step *= 0.5;
                continue;
            }
            problem.accept();
            restuck = None;
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
        let before = sliding(&problem.touching);
        problem.touching = changed(m, &problem.touching, first, hi)?;
        remember(&mut touched, first);
        x = problem.state(&x);
        problem.anchor(&x, lo, first)?;
        problem.prune(&mut x, lo)?;
        let slipped = matches!(first, Event::Slip(..));
        settle_events(&mut problem, &mut x, lo, settings, all, &mut touched, &mut iterations, slipped)?;
        // A slip that sticks again at its own load, tried again from there
        // (each rolling pin then set where it sticks, so what it rolled
        // before is no slide) and sticking again: no contact slides on as
        // the load grows, since sliding on would take less load (a part
        // pulled from a grasp whose squeeze drops as it slides). This is
        // friction's limit, a limit point of the path: nothing past it holds.
        if matches!(first, Event::Slip(..)) && sliding(&problem.touching) == before {
            if let Some(limit) = restuck {
                return Err(Error::Unstable { what: FRICTION_LIMIT, load_fraction: limit });
            }
            restuck = Some(lo);
        }
        lambda = lo;
        previous = None;
        steps += 1;
        step = FIRST_STEP.min(step);
    }
    // The last step's accept turned each rolling contact's tangents to its
    // normal there, but its forces were solved in the tangents before: a
    // grasp's 0.03 N of friction, turned 0.0036 rad, put the answer's
    // forces 1e-4 N out of balance with the springs that hold the rod.
    // Solved again in the tangents kept, the forces are the answer's.
    if problem.touching.iter().any(|t| matches!(t.law, Law::Roll { .. }))
        && let Ok((y, r)) = newton(&mut problem, &x, 1.0, settings)
    {
        (x, residual) = (y, r.residual);
        iterations += r.iterations;
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
        path: Vec::new(),
    };
    Ok((solution, next))
}

/// Solves at `lambda` with the set as it stands, then changes it while an
/// event holds there (at most [`MAX_CHANGES_AT_ONCE`] times). Where a
/// contact has just `slipped`, a sliding set that Newton cannot solve or
/// that is unstable at once is friction's limit: the slip holds nothing
/// at its own load (a ball on an incline steeper than its friction holds
/// slips at no load and slides away), not a stall or a buckling.
#[allow(clippy::too_many_arguments)]
fn settle_events<D: Statics>(
    problem: &mut ContactKkt<D>,
    x: &mut Vec<f64>,
    lambda: f64,
    settings: &Settings,
    all: &[Pair],
    touched: &mut Vec<Pair>,
    iterations: &mut usize,
    slipped: bool,
) -> Result<()> {
    let m = problem.kkt.mechanism;
    let limit = Error::Unstable { what: FRICTION_LIMIT, load_fraction: lambda };
    for k in 0..=MAX_CHANGES_AT_ONCE {
        let (y, r) = match newton(problem, x, lambda, settings) {
            Ok(solved) => solved,
            Err(_) if slipped && k == 0 => return Err(limit),
            Err(e) => return Err(unsettled(m, &problem.touching, lambda, &e)),
        };
        *iterations += r.iterations;
        *x = y;
        match event(problem, x, lambda, all)? {
            None => {
                problem.accept();
                return Ok(());
            }
            Some(Event::Unstable) if slipped => return Err(limit),
            Some(e) => {
                problem.read(x);
                problem.touching = changed(m, &problem.touching, e, lambda)?;
                remember(touched, e);
                *x = problem.state(x);
                problem.anchor(x, lambda, e)?;
                problem.prune(x, lambda)?;
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
    if let Error::Interrupted { .. } = e {
        return Error::Interrupted { load_fraction: lambda };
    }
    let names: Vec<String> = touching.iter().map(|t| named(m, &t.pair)).collect();
    Error::ContinuationStalled {
        cause: format!(
            "the contacts of {} could not be solved where they changed ({e}); {}",
            names.join(" and "),
            match touching.iter().any(|t| matches!(t.pair.part, Toucher::Flexure(_))) {
                true =>
                    "a flexure touching a sharp edge or corner of a box, where no point of it is tangent to the geom, is not solved: round the edge (a capsule) or give the flexure a thickness",
                false =>
                    "where a geom's corner or edge slides off the other's face or edge with nothing to hold it there, the path snaps, and the solve stops there",
            }
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

/// The cause of a path that stalled with `touching` on the error `e`,
/// naming the geoms that touch each other where any do: a corner or edge
/// of one that slides off the other's face or edge with nothing to hold
/// it there snaps (a box swept back from a rail's corner onto its edge,
/// whose push had held it out along the rail).
fn snapping<D: Statics>(m: &Mechanism<D>, touching: &[Touching], e: Error) -> String {
    let names: Vec<String> =
        touching.iter().filter(|t| matches!(t.pair.part, Toucher::Geom(_))).map(|t| named(m, &t.pair)).collect();
    match names.is_empty() {
        true => e.to_string(),
        false => format!(
            "{e}; {} touched there: where a geom's corner or edge slides off the other's face or edge, the path snaps, and the solve stops there",
            names.join(" and ")
        ),
    }
}

/// What the contacts touching at the equilibrium `s` add to its stiffness
/// when they are held as they are (closed, and stuck where stuck): the
/// Hessian of $-\sum_c N_c g_c$ (an inner contact's place eliminated, as
/// in the stability test) or of a stuck contact's $-f\cdot(x - a)$, and
/// their constraint gradients, $\nabla g_c$ or $\partial(x - a)$; a stuck
/// contact that rolls holds its gap and its material points along the surface. A small
/// extra load that would open a contact, or slide a stuck one, is outside
/// it; a sliding contact with friction has none (its friction turns with
/// the motion) and is refused by name.
pub(super) fn held<D: Statics>(m: &Mechanism<D>, s: &Solution<D>) -> Result<(DMatrix<f64>, Vec<Vec<f64>>)> {
    let n = m.dof();
    let (mut h, mut rows) = (DMatrix::zeros(n, n), Vec::new());
    let touching: Vec<&Contact> = s.contacts.iter().filter(|c| c.state != ContactMode::Open).collect();
    if touching.is_empty() {
        return Ok((h, rows));
    }
    let mut f = Frames::new(m);
    frames_level_into(m, &s.q, Level::Hessian, &mut f);
    for c in touching {
        let jet = gap_jet(m, &f, &s.q, &c.pair, c.s)?;
        let rough = crate::mechanism::contact::friction(m, &c.pair) > 0.0;
        let inner = c.s.is_some_and(|s| s > 0.0 && s < length(m, &c.pair));
        let friction = vector::<D>(&std::array::from_fn(|i| c.friction_force.get(i).copied().unwrap_or(0.0)));
        match c.state {
            ContactMode::Stick if inner || c.s.is_none() || jet.half > 0.0 => {
                // Rolling: the gap as a frictionless contact's, and the
                // material points that touch held together along the surface.
                h -= &jet.hessian * c.normal_force;
                if inner && jet.dss > 0.0 {
                    add_place(&mut h, c.normal_force, &jet);
                }
                let body = &f.bodies[geom_body(m, &c.pair)];
                let anchor = D::position(&D::act(&D::inverse(body), &jet.point));
                let on = match (c.s, corner(m, &c.pair)) {
                    (Some(s), _) => on_flexure::<D>(s, &jet.frame, &jet.normal, jet.half),
                    (None, Ok(k)) => k.material(&f.bodies, &jet.point),
                    (None, Err(e)) => return Err(e),
                };
                let p = material_jet(m, &f, &s.q, &c.pair, &on, anchor)?;
                h -= p.hessian_along(m, &f, &friction);
                rows.push(jet.gradient.clone());
                for u in &tangents::<D>(&array::<D>(&jet.normal), None)[..D::POINT_DIM - 1] {
                    let u = vector::<D>(u);
                    rows.push(p.delta.iter().map(|d| dot::<D>(&u, d)).collect());
                }
            }
            ContactMode::Stick => {
                let body = &f.bodies[geom_body(m, &c.pair)];
                let anchor = D::position(&D::act(&D::inverse(body), &jet.point));
                let p = point_jet(m, &f, &s.q, &c.pair, c.s, Some(anchor))?;
                let force = vector::<D>(&std::array::from_fn(|i| {
                    if i < D::POINT_DIM { c.normal_force * jet.normal[i] + c.friction_force[i] } else { 0.0 }
                }));
                h -= p.hessian_along(m, &f, &force);
                rows.extend(pin_rows::<D>(&p.delta));
            }
            _ if rough => {
                return Err(Error::invalid(
                    "compliance",
                    format!(
                        "compliance at {} (sliding, friction {})",
                        named(m, &c.pair),
                        m.geoms[c.pair.geom].friction
                    ),
                    "has no linear answer: a sliding contact's friction turns with the motion; a compliance holds contacts that touch without friction or stick",
                ));
            }
            _ => {
                h -= &jet.hessian * c.normal_force;
                let length = length(m, &c.pair);
                if c.s.is_some_and(|s| s > 0.0 && s < length) && jet.dss > 0.0 {
                    add_place(&mut h, c.normal_force, &jet);
                }
                rows.push(jet.gradient);
            }
        }
    }
    Ok((h, rows))
}

/// Adds a new contact's pair to `touched` (the pairs an answer reports).
fn remember(touched: &mut Vec<Pair>, event: Event) {
    if let Event::Touch { pair, .. } | Event::HandOff { pair, .. } = event
        && !touched.contains(&pair)
    {
        touched.push(pair);
    }
}

/// The contacts of the solution `q` (last evaluated by `problem`): each
/// touching one, then each pair in `touched` that no longer touches.
fn report<D: Statics>(problem: &ContactKkt<D>, q: &[f64], touched: &[Pair]) -> Result<Vec<Contact>> {
    let m = problem.kkt.mechanism;
    let mut out = Vec::new();
    for (c, (t, jet)) in problem.touching.iter().zip(&problem.jets).enumerate() {
        let state =
            if matches!(t.law, Law::Stick { .. } | Law::Roll { .. }) { ContactMode::Stick } else { ContactMode::Slip };
        out.push(Contact::of(
            m,
            &t.pair,
            (t.s(), &jet.point, &jet.normal, jet.gap),
            (problem.normal_force(c).max(0.0), &problem.friction_force(c)),
            state,
        ));
    }
    for pair in touched.iter().filter(|p| !problem.touching.iter().any(|t| t.pair == **p)) {
        let low = minima(m, q, &problem.frames.bodies, pair)?
            .into_iter()
            .min_by(|a, b| a.gap.total_cmp(&b.gap))
            .expect("at least one least");
        let none = D::Vector::default();
        out.push(Contact::of(m, pair, (low.s, &low.point, &low.normal, low.gap), (0.0, &none), ContactMode::Open));
    }
    Ok(out)
}

/// A contact's tangential rows as [`ContactKkt::prune`] takes them: its
/// tangents (world), their rows, and the largest of its rows (its push's too).
struct Along {
    units: Vec<[f64; 3]>,
    rows: Vec<Vec<f64>>,
    largest: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanism::contact::on_ball;
    use crate::space::Planar;

    /// The problem of `m` with no contact touching, fitted from no load to its own.
    fn bare<'a, D: Statics>(m: &'a Mechanism<D>, settings: &Settings, work: &'a mut Workspace<D>) -> ContactKkt<'a, D> {
        work.touching = true;
        let to = m.loads();
        let zero = D::zero(&to);
        let kkt = Kkt::fitted(m, &zero, &to, settings, Buffers::Borrowed(work)).unwrap();
        let (frames, inner, jets, friction) = (Frames::new(m), Vec::new(), Vec::new(), Vec::new());
        ContactKkt {
            kkt,
            touching: Vec::new(),
            frames,
            inner,
            sigma: 1.0,
            jets,
            friction,
            unloaded: false,
            resting: false,
        }
    }

    /// The problem's Jacobian and load derivative against central
    /// differences of its residual, with an inner contact on a post and a
    /// tip contact on a floor, at a bent state with forces.
    #[test]
    fn the_jacobian_matches_differences() {
        let text = "[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\norder = 4\n\
                    [[force]]\nbody = \"tip\"\nat = [0.0, 0.0]\nforce = [0.0, -3.0]\n\
                    [[geom]]\nname = \"post\"\nbody = \"ground\"\nshape = \"circle\"\norigin = [0.55, -0.3]\nradius = 0.25\nfriction = 0.3\n\
                    [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.5]\nnormal = [0.0, 1.0]\nfriction = 0.4\n";
        let m = crate::mechanism::file::from_toml(text).unwrap();
        let settings = Settings::default();
        let mut work = Workspace::new(&m);
        let mut problem = bare(&m, &settings, &mut work);
        let all = pairs(&m);
        let touching = |pair, place, law, force, at| Touching {
            pair,
            place,
            law,
            force,
            at,
            length: 1.0,
            from: [0.0; 3],
            on: [0.6, 0.0, 0.0, 0.0],
            thick: false,
            pruned: Pruned::default(),
        };
        let q = [-0.4, 0.1, -0.05, 0.02];
        let (stuck, sliding) = (Law::Stick { anchor: [0.9, 0.0, 0.0] }, Law::Slip { direction: [-0.8, 0.6, 0.0] });
        // Free, then the tip stuck to the floor at a point off it, then
        // sliding along it, then sliding on the post (its normal turns).
        for (first, second) in [
            (touching(all[0], Place::Inner, Law::Free, [0.7, 0.0, 0.0], 0.6), Law::Free),
            (touching(all[0], Place::Inner, Law::Free, [0.7, 0.0, 0.0], 0.6), stuck),
            (touching(all[0], Place::Inner, Law::Free, [0.7, 0.0, 0.0], 0.6), sliding),
            (
                touching(all[0], Place::End(1.0), Law::Slip { direction: [0.6, 0.8, 0.0] }, [0.5, 0.0, 0.0], 1.0),
                sliding,
            ),
        ] {
            let force = if second == stuck { [0.2, 0.5, 0.0] } else { [0.3, 0.0, 0.0] };
            problem.touching = vec![first, touching(all[1], Place::End(1.0), second, force, 1.0)];
            let x = problem.state(&q);
            crate::solver::assert_derivatives(&mut problem, &x, 0.7);
        }

        // On a round cap on a sprung arm: the geom moves and turns.
        let text = "[[joint]]\nname = \"hinge\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n\
                    [[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\norder = 4\n\
                    [[force]]\nbody = \"tip\"\nat = [0.0, 0.0]\nforce = [0.0, -3.0]\n\
                    [[geom]]\nname = \"cap\"\nbody = \"arm\"\nshape = \"circle\"\norigin = [0.6, -0.4]\nradius = 0.2\nfriction = 0.3\n";
        let m = crate::mechanism::file::from_toml(text).unwrap();
        let mut work = Workspace::new(&m);
        let all = pairs(&m);
        let mut problem = bare(&m, &settings, &mut work);
        let q = [0.3, -0.4, 0.1, -0.05, 0.02];
        for law in [Law::Stick { anchor: [0.7, -0.1, 0.0] }, Law::Slip { direction: [0.6, 0.8, 0.0] }] {
            problem.touching = vec![touching(all[0], Place::End(1.0), law, [0.5, -0.2, 0.0], 1.0)];
            let x = problem.state(&q);
            crate::solver::assert_derivatives(&mut problem, &x, 0.7);
        }
        // Rolling inside the span over the turning cap: stuck (material
        // points pinned apart, as within a step) and sliding.
        let rolling = [
            Law::Roll { tangents: tangents::<Planar>(&[0.6, 0.8, 0.0], None) },
            Law::Slip { direction: [0.8, -0.6, 0.0] },
        ];
        // Pinned at the centreline, then at a point of a strip's surface
        // (off it along the tangent and the normal: the section turns it),
        // inside the span and at the tip.
        for (law, on, place) in rolling
            .iter()
            .flat_map(|l| [[0.4, 0.0, 0.0, 0.0], [0.4, 0.003, -0.02, 0.0]].map(|on| (*l, on, Place::Inner)))
            .chain([(rolling[0], [1.0, 0.004, -0.02, 0.0], Place::End(1.0))])
        {
            let mut t = touching(all[0], place, law, [0.5, -0.2, 0.0], 0.45);
            (t.from, t.on, t.thick) = ([0.65, -0.15, 0.0], on, on[2] != 0.0);
            problem.touching = vec![t];
            let x = problem.state(&q);
            crate::solver::assert_derivatives(&mut problem, &x, 0.7);
        }
    }

    /// A spatial strip with a thickness rolling on a ball carried by a
    /// sprung arm that turns about a tilted axis: its surface's material
    /// point turns with its section (twist too), stuck (two tangents),
    /// sliding with a lagged direction and skidding; inside the span and
    /// at the tip.
    #[test]
    fn the_jacobian_of_a_thick_spatial_strip_rolling_matches_differences() {
        let text = "dimension = 3\n[[joint]]\nname = \"hinge\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\naxis = [0.2, 0.1, 1.0]\nstiffness = 2.0\n\
                    [[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nmodulus = 1e8\nwidth = 0.05\nthickness = 0.04\norder = 2\n\
                    [[force]]\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nforce = [0.0, -3.0, 0.5]\n\
                    [[geom]]\nname = \"cap\"\nbody = \"arm\"\nshape = \"sphere\"\norigin = [0.6, -0.4, 0.1]\nradius = 0.2\nfriction = 0.3\n";
        let m = crate::mechanism::file::spatial_from_toml(text).unwrap();
        let mut work = Workspace::new(&m);
        let all = pairs(&m);
        let mut problem = bare(&m, &Settings::default(), &mut work);
        let q: Vec<f64> = (0..m.dof()).map(|i| 0.3 * (1.7 * i as f64 + 0.4).sin()).collect();
        let u = tangents::<crate::space::Spatial>(&[0.36, 0.48, 0.8], None);
        let laws = [
            Law::Roll { tangents: u },
            Law::Slip { direction: [0.6, 0.0, -0.8] },
            Law::Skid { tangents: u, accepted: [0.0; 2] },
        ];
        let places = [(Place::Inner, [0.4, 0.004, -0.012, 0.015]), (Place::End(1.0), [1.0, 0.01, -0.014, 0.012])];
        for law in laws {
            for (place, on) in places {
                let t = Touching {
                    pair: all[0],
                    place,
                    law,
                    force: [0.5, -0.2, 0.3],
                    at: 0.45,
                    length: 1.0,
                    from: [0.65, -0.15, 0.05],
                    on,
                    thick: true,
                    pruned: Pruned::default(),
                };
                problem.touching = vec![t];
                let x = problem.state(&q);
                crate::solver::assert_derivatives(&mut problem, &x, 0.7);
            }
        }
    }

    /// The rows of a contact between two geoms of `m` (its first pair) in
    /// each of `laws`, stuck rolling and sliding, against differences at a
    /// state with the contact force `force`, the toucher's point `from` and
    /// the material point `on`: the planar and spatial tests' one check.
    fn rolling_rows_match_differences<D: Statics>(
        m: &Mechanism<D>,
        laws: &[Law],
        force: [f64; 3],
        from: [f64; 3],
        on: [f64; 3],
    ) {
        let on = on_ball(on);
        let mut work = Workspace::new(m);
        let all = pairs(m);
        let mut problem = bare(m, &Settings::default(), &mut work);
        let q = [0.2, 0.7, -0.3];
        for &law in laws {
            let t = Touching {
                pair: all[0],
                place: Place::Geoms,
                law,
                force,
                at: 0.0,
                length: 1.0,
                from,
                on,
                thick: false,
                pruned: Pruned::default(),
            };
            problem.touching = vec![t];
            let x = problem.state(&q);
            crate::solver::assert_derivatives(&mut problem, &x, 0.7);
        }
    }

    /// A wheel on a sprung, sliding hub and a pad on a sprung arm, in space, all axes skew.
    const WHEEL_ON_A_PAD: &str = "dimension = 3\n[[joint]]\nname = \"slide\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"hub\"\naxis = [1.0, 0.0, 0.2]\nstiffness = 3.0\n\
                    [[joint]]\nname = \"spin\"\nkind = \"revolute\"\nparent = \"hub\"\nchild = \"wheel\"\naxis = [0.3, 0.1, 1.0]\nstiffness = 2.0\n\
                    [[joint]]\nname = \"hinge\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\norigin = [0.0, -1.0, 0.0]\naxis = [1.0, 0.2, 0.1]\nstiffness = 5.0\n\
                    [[force]]\nbody = \"hub\"\nat = [0.0, 0.0, 0.0]\nforce = [1.0, -3.0, 0.5]\n\
                    [[geom]]\nname = \"tyre\"\nbody = \"wheel\"\nshape = \"sphere\"\nradius = 0.4\nfriction = 0.3\n\
                    [[geom]]\nname = \"pad\"\nbody = \"arm\"\nshape = \"plane\"\norigin = [0.0, 0.5, 0.0]\nnormal = [0.1, 1.0, 0.2]\n";

    /// As above, between two geoms that both move: a wheel on a sprung,
    /// sliding hub and a pad on a sprung arm, rolling stuck and sliding.
    #[test]
    fn the_jacobian_of_rolling_between_geoms_matches_differences() {
        let text = "[[joint]]\nname = \"slide\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"hub\"\nstiffness = 3.0\n\
                    [[joint]]\nname = \"spin\"\nkind = \"revolute\"\nparent = \"hub\"\nchild = \"wheel\"\nstiffness = 2.0\n\
                    [[joint]]\nname = \"hinge\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\norigin = [0.0, -1.0, 0.0]\nstiffness = 5.0\n\
                    [[force]]\nbody = \"hub\"\nat = [0.0, 0.0]\nforce = [1.0, -3.0]\n\
                    [[geom]]\nname = \"tyre\"\nbody = \"wheel\"\nshape = \"circle\"\nradius = 0.4\nfriction = 0.3\n\
                    [[geom]]\nname = \"pad\"\nbody = \"arm\"\nshape = \"plane\"\norigin = [0.0, 0.5]\nnormal = [0.0, 1.0]\n";
        let m = crate::mechanism::file::from_toml(text).unwrap();
        let rolling = [
            Law::Roll { tangents: tangents::<Planar>(&[0.1, 0.995, 0.0], None) },
            Law::Slip { direction: [1.0, 0.0, 0.0] },
        ];
        rolling_rows_match_differences(&m, &rolling, [0.5, -0.2, 0.0], [0.1, 0.45, 0.0], [0.05, -0.38, 0.0]);
    }

    /// The spatial rolling rows against differences: a ball on a hub that
    /// slides and turns about a tilted axis, on a pad on a turning arm,
    /// stuck (two tangents), sliding with a lagged direction, and skidding
    /// (the direction solved with the step).
    #[test]
    fn the_jacobian_of_rolling_in_space_matches_differences() {
        let m = crate::mechanism::file::spatial_from_toml(WHEEL_ON_A_PAD).unwrap();
        let n = [0.1f64, 0.98, 0.17];
        let size = n.iter().map(|v| v * v).sum::<f64>().sqrt();
        let n = n.map(|v| v / size);
        let u = tangents::<crate::space::Spatial>(&n, None);
        let rolling = [
            Law::Roll { tangents: u },
            Law::Slip { direction: [1.0, 0.0, 0.3] },
            Law::Skid { tangents: u, accepted: [0.0; 2] },
        ];
        rolling_rows_match_differences(&m, &rolling, [0.5, -0.2, 0.3], [0.1, 0.45, -0.05], [0.05, -0.38, 0.1]);
    }

    /// A contact with rows left out ([`ContactKkt::prune`]): stuck along
    /// turned axes with one tangent left out, and rolling with one, against
    /// differences on the wheel and pad of
    /// [`the_jacobian_of_rolling_in_space_matches_differences`].
    #[test]
    fn the_jacobian_with_rows_left_out_matches_differences() {
        let m = crate::mechanism::file::spatial_from_toml(WHEEL_ON_A_PAD).unwrap();
        let n = [0.6f64, 0.0, 0.8];
        let u = tangents::<crate::space::Spatial>(&n, None);
        let mut work = Workspace::new(&m);
        let all = pairs(&m);
        let mut problem = bare(&m, &Settings::default(), &mut work);
        let cases = [
            (
                Law::Stick { anchor: [0.1, 0.45, -0.05] },
                Pruned { axes: Some([n, u[0], u[1]]), dropped: [false, false, true] },
            ),
            (Law::Roll { tangents: u }, Pruned { axes: None, dropped: [false, true, false] }),
        ];
        for (law, pruned) in cases {
            let t = Touching {
                pair: all[0],
                place: Place::Geoms,
                law,
                force: [0.5, -0.2, 0.0],
                at: 0.0,
                length: 1.0,
                from: [0.1, 0.45, -0.05],
                on: on_ball([0.05, -0.38, 0.1]),
                thick: false,
                pruned,
            };
            problem.touching = vec![t];
            let x = problem.state(&[0.2, 0.7, -0.3]);
            crate::solver::assert_derivatives(&mut problem, &x, 0.7);
        }
    }
}
