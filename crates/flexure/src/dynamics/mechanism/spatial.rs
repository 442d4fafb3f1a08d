//! Space's mass elements ([`StationMasses`]): bodies, and a spatial flexure's
//! stations as bodies, with Lagrange's velocity products of the stations'
//! mass matrix from its differences (the parent module's docs give the
//! equations).

use super::dimension::MassElements;
use crate::error::Result;
use crate::kinematics::Level;
use crate::mechanism::kinematics::{
    Frames, add_attached_hessian, add_rotation_derivative, attach, frame_distance, frames_into, frames_level_into,
};
use crate::mechanism::lagrangian::{Assembly, assemble_into, closures_into, flexure_weight_potential};
use crate::mechanism::spatial::{SpatialLoads, SpatialMechanism};
use crate::space::Spatial;
use crate::spatial::{MassQuadrature, StationKinematics, stations_update};
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
    /// The coordinates that move a station (the flexures' own and upstream), ascending.
    moving: Vec<usize>,
    /// Frames for the velocity products' differences.
    shifted: RefCell<Frames<Spatial>>,
    /// $\partial_iM_f$ for each coordinate in `moving`, at the coordinates
    /// they were taken at: $h_f$ is quadratic in $\dot q$ through them, so
    /// every $\dot q$ at one $q$ (the tangent's differences in $\dot q$) reuses them.
    derivatives: RefCell<(Vec<f64>, Vec<DMatrix<f64>>)>,
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
        let n = m.dof();
        let mut flexures = Vec::new();
        let mut moving = vec![false; n];
        for (j, spec) in m.joints.iter().enumerate() {
            let Some(flexure) = spec.kind.flexure() else { continue };
            let Some(quadrature) = MassQuadrature::new(flexure) else { continue };
            let buffers = RefCell::new(StationKinematics::new(flexure, &quadrature));
            for i in m.path(spec.child) {
                let o = m.joints[i].offset;
                moving[o..o + m.joints[i].kind.joint().dof()].fill(true);
            }
            flexures.push((j, quadrature, buffers));
        }
        Ok(StationMasses {
            frames: Frames::new(m),
            assembly: Assembly::new(m),
            pair: RefCell::new([Frames::new(m), Frames::new(m)]),
            independent: independent_closures(m),
            flexures,
            moving: (0..n).filter(|&i| moving[i]).collect(),
            shifted: RefCell::new(Frames::new(m)),
            derivatives: RefCell::new((Vec::new(), Vec::new())),
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
        frames_into(m, q, &mut self.frames);
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
        // The static Hessian and ∂h/∂q (central differences).
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
                frames_into(m, &shifted, &mut f);
                let up = self.velocity_product_at(m, &f, v);
                shifted[i] = q[i] - e;
                frames_into(m, &shifted, &mut f);
                let down = self.velocity_product_at(m, &f, v);
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
        frames_into(m, q, &mut self.frames);
        let mm = self.mass_at(m, &self.frames);
        let qd = DVector::from_column_slice(v);
        Ok(0.5 * qd.dot(&(mm * &qd)) + Self::potential_at(m, loads, &self.frames))
    }

    fn distance(&self, m: &SpatialMechanism, a: &[f64], b: &[f64]) -> f64 {
        frame_distance(m, a, b, &mut self.pair.borrow_mut())
    }

    fn mass_matrix(&mut self, m: &SpatialMechanism, _: &SpatialLoads, q: &[f64]) -> DMatrix<f64> {
        frames_into(m, q, &mut self.frames);
        self.mass_at(m, &self.frames)
    }

    fn velocity_product(&mut self, m: &SpatialMechanism, _: &SpatialLoads, q: &[f64], v: &[f64]) -> DVector<f64> {
        // The tangent asks for h at one q and many rates: the frames are kept.
        if self.frames.level() != Level::Hessian || self.frames.coordinates != q {
            frames_into(m, q, &mut self.frames);
        }
        self.velocity_product_at(m, &self.frames, v)
    }
}

impl StationMasses {
    /// Adds the flexures' stations' $M_f$ (module docs) at the frames `f` to `mass`.
    fn add_flexure_mass(&self, m: &SpatialMechanism, f: &Frames<Spatial>, mass: &mut DMatrix<f64>) {
        for (j, quadrature, buffers) in &self.flexures {
            let spec = &m.joints[*j];
            let Some(flexure) = spec.kind.flexure() else { continue };
            let (o, n) = (spec.offset, flexure.coordinates());
            let mut k = buffers.borrow_mut();
            stations_update(flexure, quadrature, &f.coordinates[o..o + n], Level::Jacobian, &mut k);
            let root = &f.roots[*j];
            let ra = root.rotation.to_rotation_matrix().into_inner();
            // The columns a station moves with: upstream, then the joint's own.
            let upstream: Vec<(usize, usize)> = m
                .path(spec.parent)
                .into_iter()
                .flat_map(|i| {
                    let oi = m.joints[i].offset;
                    (oi..oi + m.joints[i].kind.joint().dof()).map(move |c| (c, i))
                })
                .collect();
            let columns: Vec<usize> = upstream.iter().map(|&(c, _)| c).chain(o..o + n).collect();
            let width = columns.len();
            let (mut jv, mut jw) = (Matrix3xX::zeros(width), Matrix3xX::zeros(width));
            for (i, st) in quadrature.stations().iter().enumerate() {
                let x = root * nalgebra::Point3::from(k.position[i]);
                for (col, &(c, joint)) in upstream.iter().enumerate() {
                    let origin = f.bodies[m.joints[joint].child].translation.vector;
                    let w = f.omega[c];
                    jv.set_column(col, &(f.velocity[c] + w.cross(&(x.coords - origin))));
                    jw.set_column(col, &w);
                }
                for a in 0..n {
                    jv.set_column(upstream.len() + a, &(ra * k.velocity[i * n + a]));
                    jw.set_column(upstream.len() + a, &(ra * k.omega[i * n + a]));
                }
                let r = ra * k.rotation[i];
                let inertia = r * Matrix3::from_diagonal(&Vector3::from(st.rotary)) * r.transpose();
                let block = jv.transpose() * &jv * st.mass + jw.transpose() * (inertia * &jw);
                for (a, &ca) in columns.iter().enumerate() {
                    for (b, &cb) in columns.iter().enumerate() {
                        mass[(ca, cb)] += block[(a, b)];
                    }
                }
            }
        }
    }

    /// $M_f$ at `q`, frames in `f`.
    fn flexure_mass(&self, m: &SpatialMechanism, q: &[f64], f: &mut Frames<Spatial>) -> DMatrix<f64> {
        let n = m.dof();
        frames_level_into(m, q, Level::Jacobian, f);
        let mut mass = DMatrix::zeros(n, n);
        self.add_flexure_mass(m, f, &mut mass);
        mass
    }

    /// The flexures' velocity products $h_f$ (module docs) at `q`, `v`:
    /// with $D_i = \partial_iM_f$ (central differences, step $10^{-5}(1 + \lvert q_i\rvert)$),
    /// $h_f = \sum_i\dot q_iD_i\dot q - \frac12\big(\dot q^TD_i\dot q\big)_i$.
    fn flexure_velocity_product(&self, m: &SpatialMechanism, q: &[f64], v: &[f64]) -> DVector<f64> {
        let n = m.dof();
        if self.flexures.is_empty() || v.iter().all(|x| *x == 0.0) {
            return DVector::zeros(n);
        }
        let mut cache = self.derivatives.borrow_mut();
        if cache.0 != q {
            let f = &mut *self.shifted.borrow_mut();
            let mut shifted = q.to_vec();
            cache.1.clear();
            for &i in &self.moving {
                let e = 1e-5 * (1.0 + q[i].abs());
                shifted[i] = q[i] + e;
                let up = self.flexure_mass(m, &shifted, f);
                shifted[i] = q[i] - e;
                let down = self.flexure_mass(m, &shifted, f);
                shifted[i] = q[i];
                cache.1.push((up - down) / (2.0 * e));
            }
            cache.0 = q.to_vec();
        }
        let qd = DVector::from_column_slice(v);
        let mut h = DVector::zeros(n);
        for (&i, d) in self.moving.iter().zip(&cache.1) {
            let dv = d * &qd;
            h.axpy(v[i], &dv, 1.0);
            h[i] -= 0.5 * qd.dot(&dv);
        }
        h
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

    /// $M(q)$ at the frames `f`.
    fn mass_at(&self, m: &SpatialMechanism, f: &Frames<Spatial>) -> DMatrix<f64> {
        let n = m.dof();
        let mut mass = DMatrix::zeros(n, n);
        for (_, t) in Self::bodies(m, f) {
            mass += t.com.transpose() * &t.com * t.mass + t.rotation.transpose() * (t.inertia * &t.rotation);
        }
        self.add_flexure_mass(m, f, &mut mass);
        mass
    }

    /// $h(q, \dot q)$ at the frames `f` (of $q$).
    fn velocity_product_at(&self, m: &SpatialMechanism, f: &Frames<Spatial>, v: &[f64]) -> DVector<f64> {
        let n = m.dof();
        let qd = DVector::from_column_slice(v);
        let mut h = DVector::zeros(n);
        let mut scratch = DMatrix::zeros(n, n);
        let quadratic = |s: &DMatrix<f64>| qd.dot(&(s * &qd));
        for (b, t) in Self::bodies(m, f) {
            let body = &m.bodies[b];
            let c = attach(m, f, b, body.com.coords, true);
            let mut bias = Vector3::zeros();
            let mut turn = Vector3::zeros();
            for i in 0..3 {
                let e = Vector3::ith(i, 1.0);
                scratch.fill(0.0);
                add_attached_hessian(m, f, &c, &e, &mut scratch);
                bias[i] = quadratic(&scratch);
                scratch.fill(0.0);
                add_rotation_derivative(m, f, b, &e, &mut scratch, None);
                turn[i] = quadratic(&scratch);
            }
            let omega = &t.rotation * &qd;
            let omega = Vector3::new(omega[0], omega[1], omega[2]);
            let moment = t.inertia * turn + omega.cross(&(t.inertia * omega));
            h += t.com.transpose() * (bias * t.mass) + t.rotation.transpose() * moment;
        }
        h + self.flexure_velocity_product(m, &f.coordinates, v)
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
