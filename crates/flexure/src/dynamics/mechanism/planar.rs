//! The plane's mass elements ([`ClosedFormMasses`]): bodies and flexure sections,
//! their mass matrix, velocity-product terms and gravity in one pass down
//! the tree, with a flexure's sections summed into its mass moments
//! (the parent module's docs give the equations).

use super::dimension::MassElements;
use super::distributed::{Distributed, path_columns};
use super::moments::{Moments, quarter};
use crate::error::Result;
use crate::mechanism::kinematics::{Attached, Frames, attach_into, frames_into};
use crate::mechanism::lagrangian::{Assembly, GradientWork, assemble_into, gradient_into, lagrangian};
use crate::mechanism::{Loads, Mechanism};
use crate::sincos::cos_sin;
use crate::space::Planar;
use nalgebra::{DMatrix, DVector, Point2, Vector2};

/// The angular velocity (rad/s), velocity and velocity-product
/// acceleration ($\ddot q = 0$) of a frame's origin, in the world.
#[derive(Debug, Clone, Copy, Default)]
struct Rate {
    omega: f64,
    velocity: Vector2<f64>,
    acceleration: Vector2<f64>,
}

/// A planar mechanism's mass elements and the buffers of one pass over them.
#[derive(Debug, Clone)]
pub struct ClosedFormMasses {
    /// The loads without gravity, which the pass applies to every mass element.
    loads_weightless: Loads,
    distributed: Vec<Distributed>,
    /// Bodies with mass or inertia, with the coordinates they move with.
    bodies: Vec<(usize, Vec<usize>)>,
    length: f64,
    frames: Frames,
    rates: Vec<Rate>,
    point: Attached,
    jx: Vec<f64>,
    jy: Vec<f64>,
    jt: Vec<f64>,
    zeros: Vec<f64>,
    /// $J_r$ of the flexure being integrated.
    jr: Vec<Vector2<f64>>,
    /// The angle, its rate and $(\cos, \sin)$ at every inner node of the
    /// flexure being integrated (the sines and cosines taken four at a time).
    angles: Vec<f64>,
    spins: Vec<f64>,
    trig: Vec<[f64; 2]>,
    /// The mass moments of the flexure being integrated.
    moments: Moments,
    /// The potential's assembly for the tangent (its flexure weight tables built once).
    assembly: Assembly,
    /// $M$, $h$ and $\nabla V$ of the forces.
    mass: DMatrix<f64>,
    product: DVector<f64>,
    gradient: GradientWork,
}

/// What one pass over the mass elements gives.
struct Pass {
    /// Gravity's generalized force $Q_g = -\nabla V_g$.
    gravity_force: DVector<f64>,
    /// $V_g$ (J).
    gravity_potential: f64,
}

impl MassElements<Planar> for ClosedFormMasses {
    fn new(m: &Mechanism) -> Result<Self> {
        let n = m.dof();
        let mut distributed = Vec::new();
        for (i, j) in m.joints.iter().enumerate() {
            let joint = j.kind.joint();
            // A joint's own mass moves with its shape: a flexure's, by its angle shapes.
            if let (Some(model), Some(f)) = (joint.inertia(), joint.flexure()) {
                let d = model.and_then(|model| Distributed::new(m, i, f, &model));
                distributed.push(d.map_err(|e| e.in_joint(&j.name))?);
            }
        }
        let bodies = (1..m.bodies.len())
            .filter(|&b| m.bodies[b].rigid_inertia().has_inertia())
            .map(|b| (b, path_columns(m, b)))
            .collect();
        let largest = m.joints.iter().map(|j| j.kind.joint().dof()).max().unwrap_or(0);
        let nodes = distributed.iter().map(|d: &Distributed| d.inner_weight.len()).max().unwrap_or(0);
        Ok(ClosedFormMasses {
            loads_weightless: Loads::default(),
            distributed,
            bodies,
            length: m.size(),
            frames: Frames::new(m),
            rates: vec![Rate::default(); m.bodies.len()],
            point: Attached::new(m),
            jx: vec![0.0; n],
            jy: vec![0.0; n],
            jt: vec![0.0; n],
            zeros: vec![0.0; m.constraints()],
            jr: vec![Vector2::zeros(); largest],
            angles: vec![0.0; nodes],
            spins: vec![0.0; nodes],
            trig: vec![[0.0; 2]; nodes],
            moments: Moments::new(largest),
            assembly: Assembly::new(m),
            mass: DMatrix::zeros(n, n),
            product: DVector::zeros(n),
            gradient: GradientWork::new(m),
        })
    }

    fn has_inertia(&self, _: &Mechanism) -> bool {
        !self.bodies.is_empty() || !self.distributed.is_empty()
    }

    fn set_loads(&mut self, loads: &Loads) {
        // The pass weighs every mass element itself, the potential the rest.
        self.loads_weightless = Loads { gravity: Vector2::zeros(), ..loads.clone() };
    }

    fn forces(
        &mut self,
        m: &Mechanism,
        loads: &Loads,
        q: &[f64],
        v: &[f64],
        mass: &mut [f64],
        force: &mut [f64],
    ) -> Result<()> {
        let (mut mm, mut h) = (std::mem::take(&mut self.mass), std::mem::take(&mut self.product));
        mm.fill(0.0);
        h.fill(0.0);
        let pass = self.pass(m, loads.gravity, q, v, Some(&mut mm), &mut h);
        // The pass left the frames at q: the potential's gradient reuses them.
        let (_, _, gradient) = gradient_into(m, &self.frames, &self.loads_weightless, &mut self.gradient)?;
        for (r, f) in force.iter_mut().enumerate() {
            *f = pass.gravity_force[r] - gradient[r] - h[r];
        }
        mass.copy_from_slice(mm.as_slice());
        (self.mass, self.product) = (mm, h);
        Ok(())
    }

    fn mass_matrix(&mut self, m: &Mechanism, loads: &Loads, q: &[f64]) -> DMatrix<f64> {
        let n = m.dof();
        let mut mass = DMatrix::zeros(n, n);
        let mut h = DVector::zeros(n);
        self.pass(m, loads.gravity, q, &vec![0.0; n], Some(&mut mass), &mut h);
        mass
    }

    fn velocity_product(&mut self, m: &Mechanism, loads: &Loads, q: &[f64], v: &[f64]) -> DVector<f64> {
        let mut h = DVector::zeros(m.dof());
        self.pass(m, loads.gravity, q, v, None, &mut h);
        h
    }

    fn stiffness(&mut self, m: &Mechanism, loads: &Loads, q: &[f64], _: &[f64], out: &mut [f64]) -> Result<()> {
        // The potential's Hessian (elastic, point loads, tendons, the weight of
        // bodies and flexure sections). Left out: the change of h with q,
        // second order in the rates and small beside a flexure's stiffness.
        frames_into(m, q, &mut self.frames);
        assemble_into(m, &self.frames, &self.zeros, loads, true, &mut self.assembly)?;
        out.copy_from_slice(self.assembly.hessian.as_slice());
        Ok(())
    }

    fn rate_step(v: &[f64], c: usize) -> f64 {
        1.0 + v[c].abs()
    }

    fn closure(&mut self, m: &Mechanism, q: &[f64], c: &mut [f64], g: &mut [f64]) {
        if m.constraints() == 0 {
            return;
        }
        frames_into(m, q, &mut self.frames);
        self.assembly.closures_at(m, &self.frames);
        c.copy_from_slice(self.assembly.closure.as_slice());
        g.copy_from_slice(self.assembly.closure_jacobian.as_slice());
    }

    fn energy(&mut self, m: &Mechanism, loads: &Loads, q: &[f64], v: &[f64]) -> Result<f64> {
        let n = m.dof();
        let mut mm = DMatrix::zeros(n, n);
        let mut h = DVector::zeros(n);
        let pass = self.pass(m, loads.gravity, q, v, Some(&mut mm), &mut h);
        let lag = lagrangian(m, q, &self.zeros, &self.loads_weightless)?;
        let rate = DVector::from_column_slice(v);
        Ok(0.5 * rate.dot(&(&mm * &rate)) + lag.elastic + pass.gravity_potential)
    }

    fn distance(&self, m: &Mechanism, a: &[f64], b: &[f64]) -> f64 {
        let mut buffers = [vec![0.0; m.bodies.len()], vec![0.0; m.bodies.len()]];
        crate::mechanism::kinematics::distance(m, a, b, self.length, &mut buffers)
    }
}

impl ClosedFormMasses {
    /// One pass over the mass elements at $(q, \dot q)$ under gravity `g`:
    /// adds $M$ (if asked) and $h$, and returns gravity's force and potential.
    fn pass(
        &mut self,
        m: &Mechanism,
        g: Vector2<f64>,
        q: &[f64],
        v: &[f64],
        mut mass: Option<&mut DMatrix<f64>>,
        h: &mut DVector<f64>,
    ) -> Pass {
        frames_into(m, q, &mut self.frames);
        let f = &self.frames;
        // Rates down the tree, parents first.
        self.rates[0] = Rate::default();
        for (ji, j) in m.joints.iter().enumerate() {
            let s = &f.joints[ji];
            let parent = self.rates[j.parent];
            let (root, o_p, o_c) = (f.roots[ji], f.bodies[j.parent].origin(), f.bodies[j.child].origin());
            let w = parent.omega;
            let arm = root.origin() - o_p;
            let turn = quarter(arm);
            let v_a = parent.velocity + turn * w;
            let a_a = parent.acceleration - arm * (w * w);
            let k = s.gradient.len();
            let rates = &v[j.offset..j.offset + k];
            let (mut dphi, mut dp, mut ddp) = (0.0, Vector2::zeros(), Vector2::zeros());
            for (a, &va) in rates.iter().enumerate() {
                dphi += s.jacobian[(0, a)] * va;
                dp.x += s.jacobian[(1, a)] * va;
                dp.y += s.jacobian[(2, a)] * va;
                for (b, &vb) in rates.iter().enumerate() {
                    ddp.x += s.hessian[1][(a, b)] * va * vb;
                    ddp.y += s.hessian[2][(a, b)] * va * vb;
                }
            }
            let p = o_c - root.origin();
            let (rdp, rddp) = (root.rotate(&dp), root.rotate(&ddp));
            let (tp, tdp) = (quarter(p), quarter(rdp));
            self.rates[j.child] = Rate {
                omega: w + dphi,
                velocity: v_a + tp * w + rdp,
                acceleration: a_a - p * (w * w) + tdp * (2.0 * w) + rddp,
            };
        }
        let n = m.dof();
        let mut gravity_force = DVector::zeros(n);
        let mut gravity_potential = 0.0;
        let (jx, jy, jt) = (&mut self.jx, &mut self.jy, &mut self.jt);
        // Adds mass × (J_xᵀJ_x + J_yᵀJ_y) and inertia × J_θᵀJ_θ on `cols`,
        // h += mass Jᵀa, Q_g += mass Jᵀg.
        let mut add = |cols: &[usize],
                       jx: &[f64],
                       jy: &[f64],
                       jt: &[f64],
                       mw: f64,
                       iw: f64,
                       a: Vector2<f64>,
                       mass: Option<&mut DMatrix<f64>>| {
            if let Some(mm) = mass {
                for &c in cols {
                    let (xc, yc, tc) = (mw * jx[c], mw * jy[c], iw * jt[c]);
                    for &r in cols {
                        mm[(r, c)] += jx[r] * xc + jy[r] * yc + jt[r] * tc;
                    }
                }
            }
            for &c in cols {
                h[c] += mw * (jx[c] * a.x + jy[c] * a.y);
                gravity_force[c] += mw * (jx[c] * g[0] + jy[c] * g[1]);
            }
        };
        for (b, cols) in &self.bodies {
            let body = &m.bodies[*b];
            attach_into(m, f, *b, body.com.coords, true, &mut self.point);
            let (w, o) = (Point2::from(self.point.value), f.bodies[*b].origin());
            let r = self.rates[*b];
            let d = w - o;
            let a = r.acceleration - d * (r.omega * r.omega);
            for &c in cols {
                jt[c] = self.point.jacobian[(0, c)];
                jx[c] = self.point.jacobian[(1, c)];
                jy[c] = self.point.jacobian[(2, c)];
            }
            add(cols, jx, jy, jt, body.mass, body.inertia, a, mass.as_deref_mut());
            gravity_potential -= body.mass * g.dot(&w.coords);
        }
        for d in &self.distributed {
            let spec = &m.joints[d.joint];
            let (off, k) = (spec.offset, d.order);
            attach_into(m, f, spec.parent, spec.origin.origin().coords, true, &mut self.point);
            let root = f.roots[d.joint];
            let rate = self.rates[spec.parent];
            let arm = root.origin() - f.bodies[spec.parent].origin();
            let w = rate.omega;
            let a_root = rate.acceleration - arm * (w * w);
            let (alpha, alpha_dot) = (&q[off..off + k], &v[off..off + k]);
            let jr = &mut self.jr[..k];
            jr.fill(Vector2::zeros());
            let (mut r, mut acc) = (Vector2::zeros(), Vector2::zeros());
            let nodes = d.inner_weight.len();
            for (node, psi) in d.inner_psi.chunks_exact(k).enumerate() {
                let (mut phi, mut dphi) = (0.0, 0.0);
                for i in 0..k {
                    phi += psi[i] * alpha[i];
                    dphi += psi[i] * alpha_dot[i];
                }
                self.angles[node] = phi;
                self.spins[node] = dphi;
            }
            let (angles, trig) = (&self.angles[..nodes], &mut self.trig[..nodes]);
            let mut chunks = trig.chunks_exact_mut(4);
            for (out, x) in (&mut chunks).zip(angles.chunks_exact(4)) {
                out.copy_from_slice(&cos_sin::<4>(x.try_into().expect("four angles")));
            }
            for (out, &x) in chunks.into_remainder().iter_mut().zip(&angles[nodes - nodes % 4..]) {
                *out = cos_sin::<1>(&[x])[0];
            }
            // The flexure's mass moments in its root frame (module docs):
            // everything the sections add to M, h and Q_g, so the columns
            // upstream are visited once per flexure, not once per section.
            let c = &mut self.moments;
            c.clear(k);
            let panels = d.inner_psi.chunks_exact(d.per_panel * k).zip(d.inner_weight.chunks_exact(d.per_panel));
            for (p, (psis, weights)) in panels.enumerate() {
                for (e, (psi, &wt)) in psis.chunks_exact(k).zip(weights).enumerate() {
                    let node = p * d.per_panel + e;
                    let (dphi, [cs, sn]) = (self.spins[node], self.trig[node]);
                    r.x += wt * cs;
                    r.y += wt * sn;
                    for (j, &ps) in jr.iter_mut().zip(psi) {
                        j.x -= wt * ps * sn;
                        j.y += wt * ps * cs;
                    }
                    acc.x -= wt * dphi * dphi * cs;
                    acc.y -= wt * dphi * dphi * sn;
                }
                let (mw, iw) = (d.mass[p], d.rotary[p]);
                if mw == 0.0 && iw == 0.0 {
                    continue;
                }
                let mut u = Vector2::zeros();
                for (j, &ad) in jr.iter().zip(alpha_dot) {
                    u += j * ad;
                }
                let er = quarter(r);
                let eu = quarter(u);
                c.mass += mw;
                c.first += r * mw;
                c.second += mw * r.dot(&r) + iw;
                c.velocity += u * mw;
                c.acceleration += acc * mw;
                c.turning += mw * r.dot(&u);
                c.swinging += mw * er.dot(&acc);
                let psi_end = &d.outer_psi[p * k..(p + 1) * k];
                for i in 0..k {
                    let ji = jr[i];
                    c.along[i] += ji * mw;
                    c.across[i] += mw * er.dot(&ji) + iw * psi_end[i];
                    c.product[i] += mw * (-w * w * ji.dot(&r) + 2.0 * w * ji.dot(&eu) + ji.x * acc.x + ji.y * acc.y);
                    for j in i..k {
                        c.inertia[i * k + j] += mw * ji.dot(&jr[j]) + iw * psi_end[i] * psi_end[j];
                    }
                }
            }
            if c.mass == 0.0 && c.second == 0.0 {
                continue;
            }
            // World forms: R S, its quarter turn, and Σ μ a over the sections.
            let rs = root.rotate(&c.first);
            let ers = quarter(rs);
            let (ru, racc) = (quarter(root.rotate(&c.velocity)), root.rotate(&c.acceleration));
            let sum_a = a_root * c.mass - rs * (w * w) + ru * (2.0 * w) + racc;
            let sum_turn_a = ers.dot(&a_root) + 2.0 * w * c.turning + c.swinging;
            let upstream = &d.columns[..d.columns.len() - k];
            for &col in upstream {
                jt[col] = self.point.jacobian[(0, col)];
                jx[col] = self.point.jacobian[(1, col)];
                jy[col] = self.point.jacobian[(2, col)];
            }
            for i in 0..k {
                let ra = root.rotate(&c.along[i]);
                jx[off + i] = ra.x;
                jy[off + i] = ra.y;
            }
            if let Some(mm) = mass.as_deref_mut() {
                for (b, &cv) in upstream.iter().enumerate() {
                    let (ov, tv) = (Vector2::new(jx[cv], jy[cv]), jt[cv]);
                    for &cu in &upstream[..=b] {
                        let (ou, tu) = (Vector2::new(jx[cu], jy[cu]), jt[cu]);
                        let value = c.mass * ou.dot(&ov) + tu * ers.dot(&ov) + tv * ers.dot(&ou) + tu * tv * c.second;
                        mm[(cu, cv)] += value;
                        if cu != cv {
                            mm[(cv, cu)] += value;
                        }
                    }
                    for i in 0..k {
                        let value = ov.x * jx[off + i] + ov.y * jy[off + i] + tv * c.across[i];
                        mm[(cv, off + i)] += value;
                        mm[(off + i, cv)] += value;
                    }
                }
                for i in 0..k {
                    for j in i..k {
                        let value = c.inertia[i * k + j];
                        mm[(off + i, off + j)] += value;
                        if i != j {
                            mm[(off + j, off + i)] += value;
                        }
                    }
                }
            }
            for &col in upstream {
                h[col] += jx[col] * sum_a.x + jy[col] * sum_a.y + jt[col] * sum_turn_a;
                gravity_force[col] += c.mass * (jx[col] * g.x + jy[col] * g.y) + jt[col] * ers.dot(&g);
            }
            for i in 0..k {
                let ra = Vector2::new(jx[off + i], jy[off + i]);
                h[off + i] += ra.dot(&a_root) + c.product[i];
                gravity_force[off + i] += ra.dot(&g);
            }
            gravity_potential -= c.mass * g.dot(&root.origin().coords) + g.x * rs.x + g.y * rs.y;
        }
        Pass { gravity_force, gravity_potential }
    }
}
