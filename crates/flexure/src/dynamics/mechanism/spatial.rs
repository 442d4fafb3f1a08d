//! Space's mass elements ([`StationMasses`]): bodies, and a spatial flexure's
//! stations as bodies, with their velocity products by Newton–Euler's
//! recursion over the tree and the stations (the parent module's docs give
//! the equations).

use super::dimension::MassElements;
use crate::error::Result;
use crate::kinematics::Level;
use crate::mechanism::JointState;
use crate::mechanism::kinematics::{Frames, attach, frame_distance, frames_given_into, frames_into, frames_level_into};
use crate::mechanism::lagrangian::{Assembly, assemble_into, closures_into, flexure_weight_potential};
use crate::mechanism::spatial::{SpatialLoads, SpatialMechanism};
use crate::space::Spatial;
use crate::spatial::{MassQuadrature, SpatialKinematics, StationKinematics, stations_dynamics_update, update_rate};
use nalgebra::{DMatrix, DVector, Matrix3, Matrix3xX, Vector3};
use std::cell::RefCell;

/// A spatial mechanism's mass elements and the buffers of their evaluation.
#[derive(Debug, Clone)]
pub struct StationMasses {
    frames: Frames<Spatial>,
    assembly: Assembly<Spatial>,
    pair: RefCell<[Frames<Spatial>; 2]>,
    /// An orthonormal basis $U^T$ ($r\times m$) of the closure equations'
    /// independent combinations, where they are dependent at rest (a
    /// planar linkage's pins in space: their out-of-plane rows vanish), so
    /// that the integrator's Newton matrix is not singular; `None` when
    /// all $m$ are independent.
    independent: Option<DMatrix<f64>>,
    /// The spatial flexures with mass: joint, stations and their buffers.
    flexures: Vec<(usize, MassQuadrature, RefCell<StationKinematics>)>,
    /// Each joint's entry in `flexures`, if it has one.
    station: Vec<Option<usize>>,
    /// Whether each joint has one: its motion subspace comes from the stations' pass ([`Self::frames_at`]).
    given: Vec<bool>,
    /// A massless spatial flexure's kinematics for its rate's bias, by joint (made on first use).
    tips: RefCell<Vec<Option<SpatialKinematics>>>,
    /// The recursion's buffers.
    motion: RefCell<Motion>,
    /// The buffers of [`Self::add_flexure_mass`].
    work: RefCell<FlexureMassWork>,
}

/// A flexure's stations' Jacobians stacked and weighted, $X$ with
/// $X^TX$ its own block of $M$, and the wrench of each of its coordinates
/// on the parent ([`StationMasses::add_flexure_mass`]).
#[derive(Debug, Clone, Default)]
struct FlexureMassWork {
    stack: DMatrix<f64>,
    forces: Vec<Vector3<f64>>,
    moments: Vec<Vector3<f64>>,
}

/// Each body's motion at $\ddot q = 0$ and the inertial wrench of what it
/// carries (the Data of the velocity products' recursion): angular
/// velocity and acceleration, its origin's acceleration, and the force
/// and moment about the world's origin of its subtree.
#[derive(Debug, Clone, Default)]
struct Motion {
    omega: Vec<Vector3<f64>>,
    alpha: Vec<Vector3<f64>>,
    accel: Vec<Vector3<f64>>,
    force: Vec<Vector3<f64>>,
    moment: Vec<Vector3<f64>>,
}

impl Motion {
    fn reset(&mut self, bodies: usize) {
        for v in [&mut self.omega, &mut self.alpha, &mut self.accel, &mut self.force, &mut self.moment] {
            v.clear();
            v.resize(bodies, Vector3::zeros());
        }
    }
}

fn origin_of(pose: &nalgebra::Isometry3<f64>) -> Vector3<f64> {
    pose.translation.vector
}

/// A body's mass terms at one configuration: its centre of mass's
/// Jacobian and its rotation Jacobian, and its inertia in the world.
struct BodyTerms {
    mass: f64,
    com: Matrix3xX<f64>,
    rotation: Matrix3xX<f64>,
    inertia: Matrix3<f64>,
}

impl MassElements<Spatial> for StationMasses {
    fn new(m: &SpatialMechanism) -> Result<Self> {
        let mut flexures = Vec::new();
        let mut station = vec![None; m.joints.len()];
        for (j, spec) in m.joints.iter().enumerate() {
            let Some(flexure) = spec.kind.flexure() else { continue };
            let Some(quadrature) = MassQuadrature::new(flexure) else { continue };
            let buffers = RefCell::new(StationKinematics::new(flexure, &quadrature));
            station[j] = Some(flexures.len());
            flexures.push((j, quadrature, buffers));
        }
        Ok(StationMasses {
            frames: Frames::new(m),
            assembly: Assembly::new(m),
            pair: RefCell::new([Frames::new(m), Frames::new(m)]),
            independent: independent_closures(m),
            flexures,
            given: station.iter().map(Option::is_some).collect(),
            station,
            tips: RefCell::new(vec![None; m.joints.len()]),
            motion: RefCell::new(Motion::default()),
            work: RefCell::new(FlexureMassWork::default()),
        })
    }

    fn has_inertia(&self, m: &SpatialMechanism) -> bool {
        m.bodies.iter().skip(1).any(|b| b.mass > 0.0 || b.inertia != Matrix3::zeros()) || !self.flexures.is_empty()
    }

    fn forces(
        &mut self,
        m: &SpatialMechanism,
        loads: &SpatialLoads,
        q: &[f64],
        v: &[f64],
        mass: &mut [f64],
        force: &mut [f64],
    ) -> Result<()> {
        // The gradient, M and h need the joints' first derivatives alone.
        self.frames_at(m, q, Some(v));
        let mu = vec![0.0; m.constraints()];
        assemble_into(m, &self.frames, &mu, loads, false, &mut self.assembly)?;
        let mm = self.mass_at(m, &self.frames);
        let h = self.velocity_product_at(m, &self.frames, v);
        for (i, f) in force.iter_mut().enumerate() {
            *f = -self.assembly.gradient[i] - h[i];
        }
        mass.copy_from_slice(mm.as_slice());
        Ok(())
    }

    fn stiffness(
        &mut self,
        m: &SpatialMechanism,
        loads: &SpatialLoads,
        q: &[f64],
        v: &[f64],
        out: &mut [f64],
    ) -> Result<()> {
        // The static Hessian and ∂h/∂q: central differences of the exact h
        // (exact, it would take the stations' third derivatives).
        let n = m.dof();
        frames_into(m, q, &mut self.frames);
        let mu = vec![0.0; m.constraints()];
        assemble_into(m, &self.frames, &mu, loads, true, &mut self.assembly)?;
        let mut k = self.assembly.hessian.clone();
        if v.iter().any(|x| *x != 0.0) {
            let mut shifted = q.to_vec();
            let mut f = Frames::new(m);
            for i in 0..n {
                let e = 1e-6 * (1.0 + q[i].abs());
                shifted[i] = q[i] + e;
                let up = self.velocity_product_from(m, &shifted, v, &mut f);
                shifted[i] = q[i] - e;
                let down = self.velocity_product_from(m, &shifted, v, &mut f);
                shifted[i] = q[i];
                k.set_column(i, &(k.column(i) + (up - down) / (2.0 * e)));
            }
        }
        out.copy_from_slice(k.as_slice());
        Ok(())
    }

    fn rate_step(v: &[f64], _: usize) -> f64 {
        1e-3 * v.iter().fold(0.0_f64, |a, x| a.max(x.abs())).max(1.0)
    }

    fn closures(&self, m: &SpatialMechanism) -> usize {
        self.independent.as_ref().map_or(m.constraints(), |u| u.nrows())
    }

    fn closure(&mut self, m: &SpatialMechanism, q: &[f64], c: &mut [f64], g: &mut [f64]) {
        let rows = m.constraints();
        frames_into(m, q, &mut self.frames);
        let (mut cv, mut gm) = (DVector::zeros(rows), DMatrix::zeros(rows, m.dof()));
        closures_into(m, &self.frames, &mut cv, &mut gm);
        match &self.independent {
            None => {
                c.copy_from_slice(cv.as_slice());
                g.copy_from_slice(gm.as_slice());
            }
            Some(u) => {
                c.copy_from_slice((u * cv).as_slice());
                g.copy_from_slice((u * gm).as_slice());
            }
        }
    }

    fn energy(&mut self, m: &SpatialMechanism, loads: &SpatialLoads, q: &[f64], v: &[f64]) -> Result<f64> {
        self.frames_at(m, q, None);
        let mm = self.mass_at(m, &self.frames);
        let qd = DVector::from_column_slice(v);
        Ok(0.5 * qd.dot(&(mm * &qd)) + Self::potential_at(m, loads, &self.frames))
    }

    fn distance(&self, m: &SpatialMechanism, a: &[f64], b: &[f64]) -> f64 {
        frame_distance(m, a, b, &mut self.pair.borrow_mut())
    }

    fn mass_matrix(&mut self, m: &SpatialMechanism, _: &SpatialLoads, q: &[f64]) -> DMatrix<f64> {
        self.frames_at(m, q, None);
        self.mass_at(m, &self.frames)
    }

    fn velocity_product(&mut self, m: &SpatialMechanism, _: &SpatialLoads, q: &[f64], v: &[f64]) -> DVector<f64> {
        // The tangent asks for h at one q and many rates: the frames are kept.
        if self.frames.level() == Level::Pose || self.frames.coordinates != q {
            self.frames_at(m, q, Some(v));
        } else {
            self.update_stations(m, q, Some(v));
        }
        self.velocity_product_at(m, &self.frames, v)
    }
}

impl StationMasses {
    /// $h(q, \dot q)$ with the frames of `q` into `f`.
    fn velocity_product_from(
        &self,
        m: &SpatialMechanism,
        q: &[f64],
        v: &[f64],
        f: &mut Frames<Spatial>,
    ) -> DVector<f64> {
        self.update_stations(m, q, Some(v));
        fill_frames(m, q, f, &self.given, &self.station, &self.flexures);
        self.velocity_product_at(m, f, v)
    }

    /// The frames at `q` into `self.frames` with the stations' buffers
    /// brought to them ([`Self::update_stations`]): a massive flexure's
    /// motion subspace is the tip's columns of its stations' pass
    /// (`fill_frames`), so that its own Jacobian pass is not run as well.
    fn frames_at(&mut self, m: &SpatialMechanism, q: &[f64], v: Option<&[f64]>) {
        self.update_stations(m, q, v);
        fill_frames(m, q, &mut self.frames, &self.given, &self.station, &self.flexures);
    }

    /// Brings the stations' buffers to the coordinates `q`: their Jacobians, and
    /// with a rate `v` their motion under it ([`stations_dynamics_update`]).
    fn update_stations(&self, m: &SpatialMechanism, q: &[f64], v: Option<&[f64]>) {
        for (j, quadrature, buffers) in &self.flexures {
            let spec = &m.joints[*j];
            let Some(flexure) = spec.kind.flexure() else { continue };
            let (o, n) = (spec.offset, flexure.coordinates());
            let (alpha, k) = (&q[o..o + n], &mut *buffers.borrow_mut());
            stations_dynamics_update(flexure, quadrature, alpha, v.map(|v| &v[o..o + n]), k);
        }
    }

    /// Adds the flexures' stations' $M_f$ (module docs) to `mass`, their
    /// buffers brought to the frames `f` ([`Self::update_stations`]). With
    /// $r_k = R_Ap_k$ from the root's origin $o_A$, a coordinate $c$ upstream moves
    /// every station as a point of the parent, by $u_c + \omega_c\times r_k$ ($u_c$
    /// the velocity of $o_A$), so the upstream block is the stations' rigid
    /// inertia, $m\thinspace u_c\cdot u_d + u_c\cdot(\omega_d\times s) + u_d\cdot(\omega_c\times s) + \omega_c\cdot\Theta\omega_d$
    /// with $m = \sum_km_k$, $s = \sum_km_kr_k$ and $\Theta = \sum_kI_k + m_k(\lvert r_k\rvert^21 - r_kr_k^T)$;
    /// across, $u_c\cdot F_a + \omega_c\cdot N_a$ with the wrench of the joint's own
    /// coordinate $a$, $F_a = \sum_km_kR_A\partial_ap_k$ and $N_a = \sum_kr_k\times m_kR_A\partial_ap_k + I_kR_A\omega_{k,a}$.
    /// The sums are taken in the root frame, where the stations' columns
    /// are, and turned by $R_A$ once: $F_a = R_A\sum_km_k\partial_ap_k$,
    /// $N_a = R_A\sum_k(p_k\times m_k\partial_ap_k + R_kI_kR_k^T\omega_{k,a})$, $s = R_A\sum_km_kp_k$
    /// and $\Theta = R_A\big(\sum_kR_kI_kR_k^T + m_k(\lvert p_k\rvert^21 - p_kp_k^T)\big)R_A^T$.
    fn add_flexure_mass(&self, m: &SpatialMechanism, f: &Frames<Spatial>, mass: &mut DMatrix<f64>) {
        for (j, quadrature, buffers) in &self.flexures {
            let spec = &m.joints[*j];
            let Some(flexure) = spec.kind.flexure() else { continue };
            let (o, n) = (spec.offset, flexure.coordinates());
            let k = buffers.borrow();
            let ra = *f.root_turn(*j);
            let oa = f.roots[*j].translation.vector;
            let (mut total, mut first, mut second) = (0.0, Vector3::zeros(), Matrix3::zeros());
            let work = &mut *self.work.borrow_mut();
            work.forces.clear();
            work.forces.resize(n, Vector3::zeros());
            work.moments.clear();
            work.moments.resize(n, Vector3::zeros());
            // Without rotary inertia (mass per length alone) a station has
            // no rotary rows: its terms would be zeros.
            let turning = quadrature.rotary();
            let width = if turning { 6 } else { 3 };
            let stack = &mut work.stack;
            if stack.shape() != (width * quadrature.stations().len(), n) {
                *stack = DMatrix::zeros(width * quadrature.stations().len(), n);
            }
            for (i, st) in quadrature.stations().iter().enumerate() {
                let (vel, omg) = (&k.velocity[i * n..(i + 1) * n], &k.omega[i * n..(i + 1) * n]);
                let (axes, p) = (&k.rotation[i], k.position[i]);
                let rotary = Vector3::from(st.rotary);
                let (root_mass, root_rotary) = (st.mass.sqrt(), rotary.map(f64::sqrt));
                for a in 0..n {
                    let v = vel[a] * st.mass;
                    // Station i's rows of X: √m_k ∂_ap_k and √I_k R_kᵀω_{k,a}, so that
                    // row pairs sum to m_k ∂_ap_k·∂_bp_k + ω_{k,a}·R_kI_kR_kᵀω_{k,b}.
                    let mut column = stack.column_mut(a);
                    let mut rows = column.rows_mut(width * i, width);
                    rows.fixed_rows_mut::<3>(0).copy_from(&(vel[a] * root_mass));
                    work.forces[a] += v;
                    if turning {
                        let w = axes.tr_mul(&omg[a]);
                        rows.fixed_rows_mut::<3>(3).copy_from(&w.component_mul(&root_rotary));
                        work.moments[a] += p.cross(&v) + axes * w.component_mul(&rotary);
                    } else {
                        work.moments[a] += p.cross(&v);
                    }
                }
                total += st.mass;
                first += p * st.mass;
                let arm = (Matrix3::from_diagonal_element(p.norm_squared()) - p * p.transpose()) * st.mass;
                second += if turning { axes * Matrix3::from_diagonal(&rotary) * axes.transpose() + arm } else { arm };
            }
            let (first, second) = (ra * first, ra * second * ra.transpose());
            for (fa, na) in work.forces.iter_mut().zip(work.moments.iter_mut()) {
                (*fa, *na) = (ra * *fa, ra * *na);
            }
            let (forces, moments) = (&work.forces, &work.moments);
            // The joint's own block, Σ_k m_k ∂p_k·∂p_k + ω_k·I_kω_k, as XᵀX:
            // dot products of contiguous columns, each pair once (symmetric).
            let rows = stack.nrows();
            let column = |a: usize| &stack.as_slice()[a * rows..(a + 1) * rows];
            for a in 0..n {
                for b in a..n {
                    let v = dot(column(a), column(b));
                    mass[(o + a, o + b)] += v;
                    if a != b {
                        mass[(o + b, o + a)] += v;
                    }
                }
            }
            let upstream: Vec<(usize, Vector3<f64>, Vector3<f64>)> = m
                .path(spec.parent)
                .into_iter()
                .flat_map(|i| {
                    let (oi, origin) = (m.joints[i].offset, f.bodies[m.joints[i].child].translation.vector);
                    (oi..oi + m.joints[i].kind.joint().dof())
                        .map(move |c| (c, f.omega[c], f.velocity[c] + f.omega[c].cross(&(oa - origin))))
                })
                .collect();
            for (e, &(c, wc, uc)) in upstream.iter().enumerate() {
                for a in 0..n {
                    let v = uc.dot(&forces[a]) + wc.dot(&moments[a]);
                    mass[(c, o + a)] += v;
                    mass[(o + a, c)] += v;
                }
                for &(d, wd, ud) in &upstream[e..] {
                    let v = total * uc.dot(&ud)
                        + uc.dot(&wd.cross(&first))
                        + ud.dot(&wc.cross(&first))
                        + wc.dot(&(second * wd));
                    mass[(c, d)] += v;
                    if c != d {
                        mass[(d, c)] += v;
                    }
                }
            }
        }
    }

    fn bodies(m: &SpatialMechanism, f: &Frames<Spatial>) -> Vec<(usize, BodyTerms)> {
        let mut out = Vec::new();
        for (b, body) in m.bodies.iter().enumerate().skip(1) {
            if body.mass == 0.0 && body.inertia == Matrix3::zeros() {
                continue;
            }
            // Rows ω (zero off the path), then the centre of mass's.
            let jacobian = attach(m, f, b, body.com.coords, true).jacobian;
            let (rotation, com) = (jacobian.fixed_rows::<3>(0).into_owned(), jacobian.fixed_rows::<3>(3).into_owned());
            let r = f.body_rotation(b);
            out.push((b, BodyTerms { mass: body.mass, com, rotation, inertia: r * body.inertia * r.transpose() }));
        }
        out
    }

    /// $M(q)$ at the frames `f`, the stations' buffers brought to them ([`Self::update_stations`]).
    fn mass_at(&self, m: &SpatialMechanism, f: &Frames<Spatial>) -> DMatrix<f64> {
        let n = m.dof();
        let mut mass = DMatrix::zeros(n, n);
        for (_, t) in Self::bodies(m, f) {
            mass += t.com.transpose() * &t.com * t.mass + t.rotation.transpose() * (t.inertia * &t.rotation);
        }
        self.add_flexure_mass(m, f, &mut mass);
        mass
    }

    /// $h(q, \dot q)$ at the frames `f` (of $q$, at [`Level::Jacobian`] or
    /// above), the stations' buffers brought to them with the rate `v`
    /// ([`Self::update_stations`]): Newton–Euler's recursion (module docs),
    /// each frame's accelerations at $\ddot q = 0$ down the tree, each mass
    /// element's inertial wrench, and their sums projected on the
    /// coordinates up the tree.
    fn velocity_product_at(&self, m: &SpatialMechanism, f: &Frames<Spatial>, v: &[f64]) -> DVector<f64> {
        let n = m.dof();
        let mut h = DVector::zeros(n);
        let motion = &mut *self.motion.borrow_mut();
        motion.reset(m.bodies.len());
        let Motion { omega, alpha, accel, force, moment } = motion;
        let origin = |b: usize| f.bodies[b].translation.vector;
        for (i, spec) in m.joints.iter().enumerate() {
            let (o, k, state) = (spec.offset, f.joints[i].gradient.len(), &f.joints[i]);
            let (p, c, u) = (spec.parent, spec.child, &v[o..o + k]);
            let ra = f.root_turn(i);
            // The joint's own rate in the world, and its bias Σ ∂_b S_a u_a u_b in the root frame.
            let (mut spin, mut slide) = (Vector3::zeros(), Vector3::zeros());
            for (a, &ua) in u.iter().enumerate() {
                spin += f.omega[o + a] * ua;
                slide += f.velocity[o + a] * ua;
            }
            let (turning, moving) = match (spec.kind.flexure(), self.station[i]) {
                (Some(_), Some(s)) => {
                    let tip = self.flexures[s].2.borrow().tip;
                    (tip[2], tip[3])
                }
                (Some(flexure), None) => {
                    let mut tips = self.tips.borrow_mut();
                    let data = tips[i].get_or_insert_with(|| SpatialKinematics::new(flexure));
                    let rate = update_rate(flexure, &f.coordinates[o..o + k], u, data);
                    let [_, _, turning, moving] = rate.in_root(&data.rotation);
                    (turning, moving)
                }
                (None, _) => {
                    let contract = |c: usize| {
                        (0..k).map(|a| u[a] * (0..k).map(|b| state.hessian[c][(a, b)] * u[b]).sum::<f64>()).sum()
                    };
                    (Vector3::from_fn(|c, _| contract(c)), Vector3::from_fn(|c, _| contract(c + 3)))
                }
            };
            let (wp, ap, acc) = (omega[p], alpha[p], accel[p]);
            let r = origin(c) - origin(p);
            omega[c] = wp + spin;
            alpha[c] = ap + wp.cross(&spin) + ra * turning;
            accel[c] = acc + ap.cross(&r) + wp.cross(&wp.cross(&r)) + 2.0 * wp.cross(&slide) + ra * moving;
            let Some(s) = self.station[i] else { continue };
            // The stations: x_k = o_A + R_A p_k, moving with the parent and
            // within the joint. Their wrenches are taken in the root frame,
            // where their motion is, and turned once: the parent's motion
            // and o_A's arm from the parent's origin turned by R_Aᵀ, and
            // x_k × f_k = o_A × R_Af + R_A(p_k × f).
            let (_, quadrature, buffers) = &self.flexures[s];
            let b = buffers.borrow();
            let root = origin_of(&f.roots[i]);
            let (wp, ap, acc, arm) = (ra.tr_mul(&wp), ra.tr_mul(&ap), ra.tr_mul(&acc), ra.tr_mul(&(root - origin(p))));
            let (mut fs, mut ms) = (Vector3::zeros(), Vector3::zeros());
            let turning = quadrature.rotary();
            for (kk, st) in quadrature.stations().iter().enumerate() {
                let [w, pd, wd, pdd] = b.rates[kk];
                let (x, axes) = (b.position[kk], &b.rotation[kk]);
                let arm = arm + x;
                let spin = wp + w;
                let turn = ap + wp.cross(&w) + wd;
                let a = acc + ap.cross(&arm) + wp.cross(&wp.cross(&arm)) + 2.0 * wp.cross(&pd) + pdd;
                let fl = a * st.mass;
                fs += fl;
                if !turning {
                    for c in 0..k {
                        h[o + c] += b.velocity[kk * k + c].dot(&fl);
                    }
                    ms += x.cross(&fl);
                    continue;
                }
                // I_k v = R_k I (R_kᵀ v), I diagonal in the section frame.
                let inertia = |v: &Vector3<f64>| axes * axes.tr_mul(v).component_mul(&Vector3::from(st.rotary));
                let tl = inertia(&turn) + spin.cross(&inertia(&spin));
                for c in 0..k {
                    h[o + c] += b.velocity[kk * k + c].dot(&fl) + b.omega[kk * k + c].dot(&tl);
                }
                ms += x.cross(&fl) + tl;
            }
            let fk = ra * fs;
            force[p] += fk;
            moment[p] += root.cross(&fk) + ra * ms;
        }
        for (b, body) in m.bodies.iter().enumerate().skip(1) {
            if body.mass == 0.0 && body.inertia == Matrix3::zeros() {
                continue;
            }
            let turn = f.body_rotation(b);
            let x = (f.bodies[b] * body.com).coords;
            let arm = x - origin(b);
            let a = accel[b] + alpha[b].cross(&arm) + omega[b].cross(&omega[b].cross(&arm));
            let inertia = turn * body.inertia * turn.transpose();
            let fb = a * body.mass;
            force[b] += fb;
            moment[b] += x.cross(&fb) + inertia * alpha[b] + omega[b].cross(&(inertia * omega[b]));
        }
        for (i, spec) in m.joints.iter().enumerate().rev() {
            let (o, c, p) = (spec.offset, spec.child, spec.parent);
            let (fc, mc) = (force[c], moment[c]);
            // The wrench about the joint's output origin, on each of its twists.
            let about = mc - origin(c).cross(&fc);
            for a in o..o + f.joints[i].gradient.len() {
                h[a] += f.velocity[a].dot(&fc) + f.omega[a].dot(&about);
            }
            force[p] += fc;
            moment[p] += mc;
        }
        h
    }

    /// The elastic and gravitational energy (J) at the frames `f`.
    fn potential_at(m: &SpatialMechanism, loads: &SpatialLoads, f: &Frames<Spatial>) -> f64 {
        let elastic: f64 = f.joints.iter().map(|s| s.energy).sum();
        let gravity: f64 = m
            .bodies
            .iter()
            .enumerate()
            .skip(1)
            .map(|(b, body)| -body.mass * loads.gravity.dot(&(f.bodies[b] * body.com).coords))
            .sum();
        elastic + gravity + flexure_weight_potential(m, f, loads.gravity)
    }
}

/// $a\cdot b$ in eight running sums, which the compiler keeps in vector
/// registers (a strided view's `dot` recomputes each entry's place).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut sums = [0.0; 8];
    let (left, right) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = left.remainder().iter().zip(right.remainder()).map(|(x, y)| x * y).sum();
    for (x, y) in left.zip(right) {
        for i in 0..8 {
            sums[i] += x[i] * y[i];
        }
    }
    (sums[0] + sums[4]) + (sums[1] + sums[5]) + (sums[2] + sums[6]) + (sums[3] + sums[7]) + tail
}

/// The frames at `q` into `f` at [`Level::Jacobian`], a joint with
/// `given` taking its motion subspace from its stations' pass (brought to
/// `q` first): column $a$ is $(\omega_a, \partial_ap)$ in the flexure's root frame.
fn fill_frames(
    m: &SpatialMechanism,
    q: &[f64],
    f: &mut Frames<Spatial>,
    given: &[bool],
    station: &[Option<usize>],
    flexures: &[(usize, MassQuadrature, RefCell<StationKinematics>)],
) {
    frames_given_into(m, q, f, given, |i, state: &mut JointState<Spatial>| {
        let Some(s) = station[i] else { return };
        let k = flexures[s].2.borrow();
        let (turning, moving) = k.tip_columns();
        for (a, (w, p)) in turning.iter().zip(moving).enumerate() {
            let mut column = state.jacobian.column_mut(a);
            column.fixed_rows_mut::<3>(0).copy_from(w);
            column.fixed_rows_mut::<3>(3).copy_from(p);
        }
    });
}

/// $U^T$ for the closures: the left singular vectors of
/// $G$ at the joints' rest whose singular values exceed $10^{-10}$ of the
/// largest, as rows; `None` when $G$ has full row rank there (or no rows).
fn independent_closures(m: &SpatialMechanism) -> Option<DMatrix<f64>> {
    let rows = m.constraints();
    if rows == 0 {
        return None;
    }
    let mut f = Frames::new(m);
    // G needs the joints' motion subspaces, not their Hessians.
    frames_level_into(m, &m.rest(), Level::Jacobian, &mut f);
    let (mut c, mut g) = (DVector::zeros(rows), DMatrix::zeros(rows, m.dof()));
    closures_into(m, &f, &mut c, &mut g);
    let svd = g.svd(true, false);
    let top = svd.singular_values.amax();
    let rank = svd.singular_values.iter().filter(|s| **s > 1e-10 * top).count();
    if rank == rows {
        return None;
    }
    let u = svd.u?;
    let kept: Vec<usize> = (0..svd.singular_values.len()).filter(|&k| svd.singular_values[k] > 1e-10 * top).collect();
    Some(DMatrix::from_fn(kept.len(), rows, |r, c| u[(c, kept[r])]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::stations_update;

    /// The second leg's own block of $M$ (nothing is beyond it), with rotary inertia (the example's)
    /// and without (mass per length alone, whose stations then have no
    /// rotary rows), meets the sum over its stations written out from the
    /// statics' Jacobian-level pass,
    /// $\sum_km_k\partial_ap_k\cdot\partial_bp_k + (R_k^T\omega_{k,a})\cdot I_k(R_k^T\omega_{k,b})$, to 1e-13 of its largest entry.
    #[test]
    fn the_last_legs_own_block_is_its_stations_sum() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/right_angle_cantilever.toml");
        let text = std::fs::read_to_string(path).unwrap();
        let plain: String = text.lines().filter(|l| !l.starts_with("rotary")).map(|l| format!("{l}\n")).collect();
        assert_ne!(plain, text, "the example gives a rotary inertia");
        for (file, rotary) in [(&text, true), (&plain, false)] {
            let m = crate::mechanism::file::spatial_from_toml(file).unwrap();
            let mut masses = StationMasses::new(&m).unwrap();
            assert_eq!(masses.flexures[1].1.rotary(), rotary);
            let q: Vec<f64> = (0..m.dof()).map(|i| 0.08 * (i as f64 * 1.3 + 0.2).sin()).collect();
            masses.frames_at(&m, &q, None);
            let mass = masses.mass_at(&m, &masses.frames);
            let (j, quadrature, _) = &masses.flexures[1];
            let flexure = m.joints[*j].kind.flexure().unwrap();
            let (o, n) = (m.joints[*j].offset, flexure.coordinates());
            let mut k = StationKinematics::new(flexure, quadrature);
            stations_update(flexure, quadrature, &q[o..o + n], Level::Jacobian, &mut k);
            let own = DMatrix::from_fn(n, n, |a, b| {
                quadrature.stations().iter().enumerate().fold(0.0, |sum, (i, st)| {
                    let turned = |c: usize| k.rotation[i].tr_mul(&k.omega[i * n + c]);
                    sum + st.mass * k.velocity[i * n + a].dot(&k.velocity[i * n + b])
                        + turned(a).component_mul(&Vector3::from(st.rotary)).dot(&turned(b))
                })
            });
            let block = mass.view((o, o), (n, n));
            let d = (block - &own).amax() / own.amax();
            assert!(d < 1e-13, "rotary {rotary}: apart by {d:e}");
        }
    }

    /// The frames the dynamics take, a massive flexure's motion subspace
    /// from its stations' pass, meet the joints' own Jacobian-level frames to
    /// rounding: every coordinate's world twist and every body's pose.
    #[test]
    fn stations_give_the_joints_motion_subspace() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/right_angle_cantilever.toml");
        let m = crate::mechanism::file::spatial_from_toml(&std::fs::read_to_string(path).unwrap()).unwrap();
        let mut masses = StationMasses::new(&m).unwrap();
        assert!(masses.given.iter().all(|g| *g), "both legs have mass");
        let q: Vec<f64> = (0..m.dof()).map(|i| 0.08 * (i as f64 * 1.3 + 0.2).sin()).collect();
        let mut own = Frames::new(&m);
        frames_level_into(&m, &q, Level::Jacobian, &mut own);
        masses.frames_at(&m, &q, None);
        let f = &masses.frames;
        for c in 0..m.dof() {
            let (dw, dv) = ((f.omega[c] - own.omega[c]).amax(), (f.velocity[c] - own.velocity[c]).amax());
            assert!(dw < 1e-14 && dv < 1e-13 * own.velocity[c].amax().max(1.0), "coordinate {c}: {dw:e} {dv:e}");
        }
        for (a, b) in f.bodies.iter().zip(&own.bodies) {
            assert!((a.translation.vector - b.translation.vector).amax() < 1e-13);
            assert!(
                (a.rotation.to_rotation_matrix().into_inner() - b.rotation.to_rotation_matrix().into_inner()).amax()
                    < 1e-15
            );
        }
    }
}
