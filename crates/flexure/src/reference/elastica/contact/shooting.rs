//! The elastica with a fixed set of point contacts by multiple shooting:
//! the square system that [`contact`](super::contact) solves at each load.

use super::obstacle::Obstacle;
use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::ode::{Tolerance, integrate_through};
use crate::scalar::Scalar;
use crate::solver::Problem;
use crate::statics::TipLoad;
use nalgebra::Const;
use num_dual::DualSVec64;

/// Derivative directions carried by one evaluation: every unknown and the load factor.
pub(super) const DIRECTIONS: usize = 48;

/// The most contact points held at once.
pub(super) const MAX_CONTACTS: usize = 4;

/// The fewest shooting segments.
const MIN_SEGMENTS: usize = 4;

/// The most shooting segments: with [`MAX_CONTACTS`] contacts of three
/// unknowns each and the load factor, the unknowns fill [`DIRECTIONS`].
pub(super) const MAX_SEGMENTS: usize = (DIRECTIONS - 1 - 3 * MAX_CONTACTS) / 2;

/// The integrator's first step in each evaluation, as a fraction of a segment.
const FIRST_STEP: f64 = 0.3;

type Dual = DualSVec64<DIRECTIONS>;

/// How an active contact transmits force along the obstacle's surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Law {
    /// No tangential force.
    Frictionless,
    /// The tip holds its place along the surface, at `at` (m).
    Stick {
        /// The point where it stuck.
        at: [f64; 2],
    },
    /// The tangential force is $T = d\mu N$ along the surface tangent $(-n_y, n_x)$.
    Slip {
        /// $d = \pm 1$.
        direction: f64,
    },
}

/// One contact of the active set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Active {
    /// Index into the obstacles.
    pub obstacle: usize,
    /// At the tip ($s_c = L$), else at an unknown interior $s_c$.
    pub tip: bool,
    pub law: Law,
}

impl Active {
    /// Its unknowns: the scaled force, and $s_c/L$ when interior.
    pub fn unknowns(&self) -> usize {
        if self.tip { 2 } else { 3 }
    }
}

/// What a contact looks like in a solved state (f64).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Seen {
    pub s: f64,
    pub phi: f64,
    pub point: [f64; 2],
    pub normal: [f64; 2],
    /// Force on the flexure (N).
    pub force: [f64; 2],
    pub gap: f64,
}

/// A sample of a solved shape: $s$, $(\phi, m, x, y)$ and the internal force there (N).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Sample {
    pub s: f64,
    pub state: [f64; 4],
    pub force: [f64; 2],
}

/// The shooting problem for one active set along one leg of the load path.
///
/// Along the flexure, with the bending moment $m$ scaled to $\mu = m/k$
/// by $k = \overline{EI}/L$ and $N(s)$ the force the part beyond $s$ carries
/// (the tip load plus every contact force beyond $s$),
/// $$\phi^{\prime} = \omega_0 + \frac{k\mu}{EI(s)},\quad
/// \mu^{\prime} = \frac{N_x\sin\phi - N_y\cos\phi}{k},\quad
/// x^{\prime} = \cos\phi,\quad y^{\prime} = \sin\phi.$$
/// $N$ jumps by the contact force $f_c$ at each $s_c$; $\phi$, $m$, $p$ are continuous.
pub(super) struct Shooting<'a> {
    pub flexure: &'a Flexure,
    pub obstacles: &'a [Obstacle],
    pub half_thickness: f64,
    /// The loads the path visits, from zero: leg $i$ runs from `path[i-1]` (zero for $i = 0$) to `path[i]`.
    pub path: &'a [TipLoad],
    pub active: Vec<Active>,
    pub ode: Tolerance,
    /// $k = \overline{EI}/L$.
    pub k: f64,
    nodes: Vec<f64>,
    stops: Vec<f64>,
    scale: f64,
    step: f64,
}

impl<'a> Shooting<'a> {
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        flexure: &'a Flexure,
        obstacles: &'a [Obstacle],
        half_thickness: f64,
        path: &'a [TipLoad],
        segments: usize,
        ode: Tolerance,
    ) -> Result<Self> {
        let l = flexure.length();
        let stretch = crate::reference::Stretch::of(flexure)?;
        let uniform = flexure.section().is_uniform();
        let nodes = stretch.nodes(l, uniform, segments);
        let biggest = path.iter().fold(0.0, |m: f64, p| m.max(p.moment.abs() + l * (p.fx.abs() + p.fy.abs())));
        Ok(Self {
            flexure,
            obstacles,
            half_thickness,
            path,
            active: Vec::new(),
            ode,
            k: flexure.ei() / l,
            nodes,
            stops: crate::reference::stops(flexure),
            scale: flexure.ei() / l + biggest,
            step: 0.0,
        })
    }

    /// The number of shooting segments for `path` (an error naming the force beyond [`MAX_SEGMENTS`]).
    pub fn segments(flexure: &Flexure, path: &[TipLoad]) -> Result<usize> {
        let stretch = crate::reference::Stretch::of(flexure)?;
        let force = path.iter().fold(0.0, |m: f64, p| m.max(p.fx.hypot(p.fy)));
        // Contact forces can exceed the load: half again as many segments.
        let growth = 1.5 * force.sqrt() * stretch.total();
        if growth > MAX_SEGMENTS as f64 {
            return Err(Error::invalid(
                "force",
                format!("{force} N (1.5·∫√(|F|/EI) ds = {growth:.1})"),
                "is beyond what the contact reference follows: 1.5·∫√(|F|/EI) ds must be at most 17",
            ));
        }
        Ok((growth.ceil() as usize).max(MIN_SEGMENTS))
    }

    fn segment_count(&self) -> usize {
        self.nodes.len() - 1
    }

    /// Index of $\phi_j$ ($j \ge 1$).
    fn angle(j: usize) -> usize {
        2 * j - 1
    }

    /// Index of $\mu_j$ ($j < N$).
    fn moment(j: usize) -> usize {
        2 * j
    }

    /// The first unknown of active contact `c`.
    pub fn base(&self, c: usize) -> usize {
        2 * self.segment_count() + self.active[..c].iter().map(Active::unknowns).sum::<usize>()
    }

    /// The tip load at `lambda` along the path, and its derivative in `lambda`.
    pub fn load(&self, lambda: f64) -> (TipLoad, TipLoad) {
        let legs = self.path.len();
        let i = (lambda.floor().max(0.0) as usize).min(legs - 1);
        let from = if i == 0 { TipLoad::default() } else { self.path[i - 1] };
        let to = self.path[i];
        let t = lambda - i as f64;
        let rate = TipLoad { moment: to.moment - from.moment, fx: to.fx - from.fx, fy: to.fy - from.fy };
        let at =
            TipLoad { moment: from.moment + t * rate.moment, fx: from.fx + t * rate.fx, fy: from.fy + t * rate.fy };
        (at, rate)
    }

    /// The unknowns of the unloaded flexure with no contact: its rest shape.
    pub fn rest(&mut self) -> Result<Vec<f64>> {
        let n = 2 * self.segment_count();
        let mut x = vec![0.0; n];
        let f = self.flexure;
        let kappa = f.rest();
        let mut phi = 0.0;
        for j in 0..self.segment_count() {
            let rhs = |s: f64, _: &[f64; 1]| [f.curvature(kappa, s)];
            let (s0, s1) = (self.nodes[j], self.nodes[j + 1]);
            phi = integrate_through(rhs, s0, s1, &self.stops, [phi], &self.ode, &mut 0.0, |_, _| {})?[0];
            x[Self::angle(j + 1)] = phi;
        }
        Ok(x)
    }

    /// The residuals at `x` under the load at `lambda`, every quantity lifted
    /// by `lift(i, value)` (a dual number with derivative along unknown $i$,
    /// or the value itself); the load factor is direction `dim()`.
    /// `contacts` receives each active contact's state, `observe` every
    /// integrator step (with the internal force of its piece).
    fn sweep<T: Scalar>(
        &mut self,
        x: &[f64],
        lambda: f64,
        lift: impl Fn(usize, f64) -> T,
        residual: &mut [T],
        mut contacts: Option<&mut Vec<Seen>>,
        mut observe: impl FnMut(f64, &[T; 4], [f64; 2]),
    ) -> Result<()> {
        let (f, l, k) = (self.flexure, self.flexure.length(), self.k);
        let n = self.dim();
        let unit = k / l;
        let segments = self.segment_count();
        let kappa = f.rest();
        let (load, rate) = self.load(lambda);
        let dl = lift(n, lambda) - T::c(lambda);
        let tip_force =
            [(T::c(load.fx) + dl * T::c(rate.fx)) / T::c(unit), (T::c(load.fy) + dl * T::c(rate.fy)) / T::c(unit)];
        let tip_moment = (T::c(load.moment) + dl * T::c(rate.moment)) / T::c(k);
        // The contacts: scaled force, arc length (lifted), the infinitesimal of σ.
        let mut forces = Vec::with_capacity(self.active.len());
        let mut places = Vec::with_capacity(self.active.len());
        for (c, a) in self.active.iter().enumerate() {
            let b = self.base(c);
            forces.push([lift(b, x[b]), lift(b + 1, x[b + 1])]);
            if a.tip {
                places.push((l, T::zero()));
            } else {
                let sigma = x[b + 2];
                if !(sigma > 0.0 && sigma < 1.0) {
                    return Err(Error::Singular {
                        what: format!("contact reference: a contact point left the flexure (s/L = {sigma})"),
                    });
                }
                places.push((sigma * l, lift(b + 2, sigma) - T::c(sigma)));
            }
        }
        let mut order: Vec<usize> = (0..self.active.len()).collect();
        order.sort_by(|&a, &b| places[a].0.total_cmp(&places[b].0));
        let uniform = self.stops.is_empty() && f.section().is_uniform();
        let rhs = |s: f64, y: &[T; 4], force: &[T; 2]| {
            let (sn, cs) = y[0].sin_cos();
            let bend = if uniform { y[1] / T::c(l) } else { y[1] * T::c(k / f.ei_at(s)) };
            [T::c(f.curvature(kappa, s)) + bend, (force[0] * sn - force[1] * cs) / T::c(l), cs, sn]
        };
        let mut at_contact: Vec<Option<(T, [T; 2])>> = vec![None; forces.len()];
        let (mut px, mut py) = (T::zero(), T::zero());
        self.step = FIRST_STEP * (self.nodes[1] - self.nodes[0]);
        let mut tip_angle = T::zero();
        for j in 0..segments {
            let (s0, s1) = (self.nodes[j], self.nodes[j + 1]);
            let phi = if j == 0 { T::zero() } else { lift(Self::angle(j), x[Self::angle(j)]) };
            let mut state = [phi, lift(Self::moment(j), x[Self::moment(j)]), px, py];
            // Pieces between the contacts inside the segment, each under
            // the tip load and the contacts beyond its start.
            let inside = order.iter().copied().filter(|&c| places[c].0 > s0 && places[c].0 <= s1 && places[c].0 < l);
            let mut a = s0;
            for (b, contact) in inside.map(|c| (places[c].0, Some(c))).chain([(s1, None)]) {
                let mut force = tip_force;
                for c in 0..forces.len() {
                    if places[c].0 > a {
                        force[0] += forces[c][0];
                        force[1] += forces[c][1];
                    }
                }
                if b > a {
                    let fre = [force[0].re(), force[1].re()];
                    let rhs = |s, y: &[T; 4]| rhs(s, y, &force);
                    let observe = |s, y: &[T; 4]| observe(s, y, fre);
                    state = integrate_through(rhs, a, b, &self.stops, state, &self.ode, &mut self.step, observe)?;
                }
                a = b;
                let Some(c) = contact else { continue };
                // The state there, moved with σ: d/ds_c of (φ, x, y) is (φ', cos φ, sin φ).
                let d = rhs(b, &state, &force);
                let eps = places[c].1 * T::c(l);
                let phi_c = state[0] + eps * T::c(d[0].re());
                let p_c = [state[2] + eps * T::c(d[2].re()), state[3] + eps * T::c(d[3].re())];
                at_contact[c] = Some((phi_c, p_c));
                // Beyond s_c the force drops by f_c: the state beyond moves
                // with s_c by (rhs⁻ − rhs⁺) = (0, (f_x sin φ − f_y cos φ)/L, 0, 0).
                let (sn, cs) = state[0].re().sin_cos();
                let jump = (forces[c][0].re() * sn - forces[c][1].re() * cs) / l;
                state[1] += eps * T::c(jump);
            }
            let end = state;
            (px, py) = (end[2], end[3]);
            let (target_phi, target_mu) = if j + 1 == segments {
                (lift(Self::angle(j + 1), x[Self::angle(j + 1)]), tip_moment)
            } else {
                (lift(Self::angle(j + 1), x[Self::angle(j + 1)]), lift(Self::moment(j + 1), x[Self::moment(j + 1)]))
            };
            residual[2 * j] = T::c(k) * (end[0] - target_phi);
            residual[2 * j + 1] = T::c(k) * (end[1] - target_mu);
            if j + 1 == segments {
                tip_angle = end[0];
            }
        }
        if let Some(seen) = contacts.as_deref_mut() {
            seen.clear();
        }
        for (c, a) in self.active.iter().enumerate() {
            let (phi, p) =
                if a.tip { (tip_angle, [px, py]) } else { at_contact[c].expect("every interior contact is passed") };
            let obstacle = &self.obstacles[a.obstacle];
            let gap = obstacle.gap_of(p, self.half_thickness);
            let normal = obstacle.normal_of(p);
            let tangent = [-normal[1], normal[0]];
            let fc = forces[c];
            let push = fc[0] * normal[0] + fc[1] * normal[1];
            let along = fc[0] * tangent[0] + fc[1] * tangent[1];
            let b = self.base(c);
            residual[b] = T::c(k / l) * gap;
            residual[b + 1] = T::c(k)
                * match a.law {
                    Law::Frictionless => along,
                    Law::Stick { at } => {
                        ((p[0] - T::c(at[0])) * tangent[0] + (p[1] - T::c(at[1])) * tangent[1]) / T::c(l)
                    }
                    Law::Slip { direction } => along - T::c(direction * obstacle.friction) * push,
                };
            if !a.tip {
                let (sn, cs) = phi.sin_cos();
                residual[b + 2] = T::c(k) * (normal[0] * cs + normal[1] * sn);
            }
            if let Some(seen) = contacts.as_deref_mut() {
                seen.push(Seen {
                    s: places[c].0,
                    phi: phi.re(),
                    point: [p[0].re(), p[1].re()],
                    normal: [normal[0].re(), normal[1].re()],
                    force: [fc[0].re() * unit, fc[1].re() * unit],
                    gap: gap.re(),
                });
            }
        }
        if residual.iter().all(|r| r.re().is_finite()) {
            Ok(())
        } else {
            Err(Error::Singular { what: "contact reference: non-finite residual".into() })
        }
    }

    /// The contacts' states and the shape's samples at a solved `x`.
    pub fn inspect(&mut self, x: &[f64], lambda: f64) -> Result<(Vec<Seen>, Vec<Sample>)> {
        let n = self.dim();
        let mut r = vec![0.0; n];
        let (mut seen, mut samples) = (Vec::new(), Vec::new());
        let (k, unit) = (self.k, self.k / self.flexure.length());
        self.sweep(
            x,
            lambda,
            |_, v| v,
            &mut r,
            Some(&mut seen),
            |s, y, force| {
                let force = [force[0] * unit, force[1] * unit];
                samples.push(Sample { s, state: [y[0], y[1] * k, y[2], y[3]], force })
            },
        )?;
        Ok((seen, samples))
    }

    /// Integrates the shape from `sample` to arc length `s` inside the same
    /// piece (no contact between): $(\phi, m, x, y)$ there.
    pub fn advance(&self, sample: &Sample, s: f64) -> Result<[f64; 4]> {
        let f = self.flexure;
        let kappa = f.rest();
        let force = sample.force;
        let rhs = |s: f64, y: &[f64; 4]| {
            let (sn, cs) = y[0].sin_cos();
            [f.curvature(kappa, s) + y[1] / f.ei_at(s), force[0] * sn - force[1] * cs, cs, sn]
        };
        if s == sample.s {
            return Ok(sample.state);
        }
        integrate_through(rhs, sample.s, s, &self.stops, sample.state, &self.ode, &mut 0.0, |_, _| {})
    }
}

fn parts(x: &Dual) -> nalgebra::SVector<f64, DIRECTIONS> {
    x.eps.unwrap_generic(Const::<DIRECTIONS>, Const::<1>)
}

impl Problem<f64> for Shooting<'_> {
    fn dim(&self) -> usize {
        2 * self.segment_count() + self.active.iter().map(Active::unknowns).sum::<usize>()
    }

    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        residual: &mut [f64],
        jacobian: Option<&mut [f64]>,
        dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        let n = self.dim();
        if jacobian.is_none() && dlambda.is_none() {
            return self.sweep(x, lambda, |_, v| v, residual, None, |_, _, _| {});
        }
        let mut r = vec![Dual::from_re(0.0); n];
        self.sweep(x, lambda, |i, v| Dual::from_re(v).derivative(i), &mut r, None, |_, _, _| {})?;
        let d: Vec<_> = r.iter().map(parts).collect();
        for (row, ri) in r.iter().enumerate() {
            residual[row] = ri.re;
        }
        if let Some(jac) = jacobian {
            for col in 0..n {
                for row in 0..n {
                    jac[col * n + row] = d[row][col];
                }
            }
        }
        if let Some(dl) = dlambda {
            for row in 0..n {
                dl[row] = d[row][n];
            }
        }
        Ok(())
    }

    /// The largest change of a node's angle.
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        (1..=self.segment_count()).fold(0.0, |m: f64, j| m.max((a[Self::angle(j)] - b[Self::angle(j)]).abs()))
    }

    fn scale(&self) -> f64 {
        self.scale
    }

    fn unit(&self) -> &'static str {
        "N·m"
    }

    fn name(&self) -> &'static str {
        "exact elastica with contact"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Jacobian and load derivative against central differences
    /// ([`crate::solver::assert_derivatives`], 1e-6 absolute), off the
    /// solution, with every kind of contact: interior on a half-plane and
    /// on a circle (the $s_c$ derivative through the force's jump), the tip
    /// stuck, and slipping; rest curvature and a section table with a kink.
    #[test]
    fn derivatives_match_finite_differences() {
        let f = Flexure::new(1.1, 0.9, 3).unwrap().with_rest(&[0.3, -0.2, 0.1]).unwrap();
        let table = crate::section::Profile::Table(vec![[0.0, 1.2], [0.35, 0.5], [1.0, 0.9]]);
        let kinked = f.clone().with_section(crate::section::Section::given(table).unwrap()).unwrap();
        let obstacles =
            [Obstacle::half_plane([0.0, -0.2], [0.1, 1.0]), Obstacle::circle([0.9, 0.6], 0.3).with_friction(0.4)];
        let path = [TipLoad { moment: 0.3, fx: -2.0, fy: 1.5 }, TipLoad { moment: -0.2, fx: 1.0, fy: 3.0 }];
        for flexure in [&f, &kinked] {
            for law in [Law::Stick { at: [1.0, 0.3] }, Law::Slip { direction: -1.0 }] {
                let mut sh = Shooting::new(flexure, &obstacles, 0.01, &path, 5, Tolerance::default()).unwrap();
                sh.active = vec![
                    Active { obstacle: 0, tip: false, law: Law::Frictionless },
                    Active { obstacle: 1, tip: true, law },
                    Active { obstacle: 1, tip: false, law: Law::Frictionless },
                ];
                let n = sh.dim();
                assert_eq!(n, 10 + 8);
                let mut x: Vec<f64> = (0..n).map(|i| 0.2 + 0.1 * (i as f64).sin()).collect();
                (x[12], x[17]) = (0.37, 0.71);
                crate::solver::assert_derivatives(&mut sh, &x, 1.4);
            }
        }
    }
}
