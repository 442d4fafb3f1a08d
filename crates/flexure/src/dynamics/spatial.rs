//! Dynamics of a spatial mechanism ([`crate::mechanism::spatial`]): its
//! equations of motion as a [`System`], its vibration modes, and its
//! motion in time.
//!
//! Each body of mass $m$, centre of mass $c(q)$ and inertia $I_c$ (in the
//! world, $I_w = RI_cR^T$) turning at $\omega = J_\omega\dot q$ has
//! $T = \frac12 m\lvert J_c\dot q\rvert^2 + \frac12\omega\cdot I_w\omega$, so
//! $$M = \sum_b m J_c^TJ_c + J_\omega^TI_wJ_\omega,\qquad
//! h = \sum_b m J_c^T(\dot J_c\dot q) + J_\omega^T\big(I_w\dot J_\omega\dot q + \omega\times I_w\omega\big),$$
//! Newton–Euler's equations projected on the coordinates (which are
//! Lagrange's, $h = \dot M\dot q - \frac12\nabla(\dot q^TM\dot q)$). The
//! accelerations at $\ddot q = 0$, $\dot J_c\dot q = \dot q^T\nabla^2c\thinspace\dot q$
//! and $\dot J_\omega\dot q = \sum_{ab}\partial_b\omega_a\dot q_a\dot q_b$, come from
//! the tree's second derivatives ([`crate::mechanism::spatial::kinematics`]).
//!
//! A spatial flexure with a density or mass per length adds its stations
//! ([`crate::spatial::MassQuadrature`]) as bodies: station $k$ of joint $j$,
//! at $x_k = o_A + R_Ap_k$ with axes $R_AR_k$ ($A$ the joint's root frame),
//! has $J_{v,k}$ of a point fixed in the parent body for the coordinates
//! upstream and $R_A\partial_ap_k$ for the joint's own, $J_{\omega,k}$ the
//! upstream $\omega_c$ and $R_A\omega_{k,a}$, so
//! $$M_f = \sum_k \mu_kw_k J_{v,k}^TJ_{v,k} + J_{\omega,k}^T\big(R\rho I_kR^T\big)J_{\omega,k}.$$
//! Its velocity products are Lagrange's from $M_f$ itself,
//! $h_f = \dot M_f\dot q - \frac12\nabla(\dot q^TM_f\dot q)$, from central
//! differences of $M_f$ along each coordinate that moves a station (steps
//! $10^{-5}(1 + \lvert q_i\rvert)$, truncation about $10^{-10}$ relative), kept
//! for the configuration they were taken at. Being Lagrange's equations of
//! the same $T$, they keep $T + V$ to the differences' error, which a free
//! swing checks (`tests/spatial_flexure_mass.rs`).
//!
//! The generalized force is $f = -(\nabla V - Q_m) - h - D\dot q$, with the
//! potential and dead moments of [`crate::mechanism::spatial::lagrangian`]
//! and $D = \operatorname{diag}(\beta_jK_j, c_k)$.

use super::integrate::{self, Trajectory, integrate_kept};
use super::modes::{Modes, finite_modes};
use super::schedule::{Scheduled, spatial_loads_at};
use super::system::System;
use crate::error::{Error, Result};
use crate::kinematics::Level;
use crate::mechanism::spatial::kinematics::frames_level_into;
use crate::mechanism::spatial::kinematics::{
    SpatialFrames, add_attached_hessian, add_rotation_derivative, attach, distance, frames_into,
};
use crate::mechanism::spatial::lagrangian::{SpatialAssembly, assemble_into, closures_into, flexure_weight_potential};
use crate::mechanism::spatial::{SpatialLoads, SpatialMechanism};
use crate::mechanism::statics::{self, assemble_unloaded, solve_between};
use crate::solver::Settings;
use crate::spatial::{MassQuadrature, StationKinematics, stations_update};
use nalgebra::{DMatrix, DVector, Matrix3, Matrix3xX, Vector3};
use std::cell::RefCell;

/// The equations of motion of a spatial mechanism, as a [`System`].
#[derive(Debug)]
pub struct SpatialSystem<'a> {
    mechanism: &'a SpatialMechanism,
    loads: SpatialLoads,
    damping: DMatrix<f64>,
    frames: SpatialFrames,
    assembly: SpatialAssembly,
    pair: RefCell<[SpatialFrames; 2]>,
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
    shifted: RefCell<SpatialFrames>,
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

impl<'a> SpatialSystem<'a> {
    /// The system of `m` under its own loads.
    pub fn new(m: &'a SpatialMechanism) -> Result<Self> {
        let n = m.dof();
        let mut damping = DMatrix::zeros(n, n);
        for j in &m.joints {
            let joint = j.kind.joint();
            let k = joint.dof();
            if j.damping != 0.0 {
                joint.add_damping(j.damping, &mut damping.view_mut((j.offset, j.offset), (k, k)));
            }
        }
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
        Ok(SpatialSystem {
            mechanism: m,
            loads: m.loads(),
            damping,
            frames: SpatialFrames::new(m),
            assembly: SpatialAssembly::new(m),
            pair: RefCell::new([SpatialFrames::new(m), SpatialFrames::new(m)]),
            independent: independent_closures(m),
            flexures,
            moving: (0..n).filter(|&i| moving[i]).collect(),
            shifted: RefCell::new(SpatialFrames::new(m)),
            derivatives: RefCell::new((Vec::new(), Vec::new())),
        })
    }

    /// Takes `loads` from now on (a schedule's, at the time evaluated).
    pub fn set_loads(&mut self, loads: SpatialLoads) -> Result<()> {
        loads.validate(self.mechanism)?;
        self.loads = loads;
        Ok(())
    }

    /// Whether any body has mass or inertia, or any spatial flexure a
    /// density or mass per length.
    pub fn has_inertia(&self) -> bool {
        self.mechanism.bodies.iter().skip(1).any(|b| b.mass > 0.0 || b.inertia != Matrix3::zeros())
            || !self.flexures.is_empty()
    }

    /// Adds the flexures' stations' $M_f$ (module docs) at the frames `f` to `mass`.
    fn add_flexure_mass(&self, f: &SpatialFrames, mass: &mut DMatrix<f64>) {
        let m = self.mechanism;
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
                    let w = f.omega.column(c).into_owned();
                    jv.set_column(col, &(f.velocity.column(c) + w.cross(&(x.coords - origin))));
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
    fn flexure_mass(&self, q: &[f64], f: &mut SpatialFrames) -> DMatrix<f64> {
        let n = self.mechanism.dof();
        frames_level_into(self.mechanism, q, Level::Jacobian, f);
        let mut mass = DMatrix::zeros(n, n);
        self.add_flexure_mass(f, &mut mass);
        mass
    }

    /// The flexures' velocity products $h_f$ (module docs) at `q`, `v`:
    /// with $D_i = \partial_iM_f$ (central differences, step $10^{-5}(1 + \lvert q_i\rvert)$),
    /// $h_f = \sum_i\dot q_iD_i\dot q - \frac12\big(\dot q^TD_i\dot q\big)_i$.
    fn flexure_velocity_product(&self, q: &[f64], v: &[f64]) -> DVector<f64> {
        let n = self.mechanism.dof();
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
                let up = self.flexure_mass(&shifted, f);
                shifted[i] = q[i] - e;
                let down = self.flexure_mass(&shifted, f);
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

    fn bodies(&self, f: &SpatialFrames) -> Vec<(usize, BodyTerms)> {
        let m = self.mechanism;
        let mut out = Vec::new();
        for (b, body) in m.bodies.iter().enumerate().skip(1) {
            if body.mass == 0.0 && body.inertia == Matrix3::zeros() {
                continue;
            }
            let com = attach(m, f, b, body.com.coords, true).jacobian;
            let mut rotation = Matrix3xX::zeros(m.dof());
            for j in m.path(b) {
                let o = m.joints[j].offset;
                let k = m.joints[j].kind.joint().dof();
                rotation.columns_mut(o, k).copy_from(&f.omega.columns(o, k));
            }
            let r = f.body_rotation(b);
            out.push((b, BodyTerms { mass: body.mass, com, rotation, inertia: r * body.inertia * r.transpose() }));
        }
        out
    }

    /// $M(q)$ at the frames `f`.
    fn mass_at(&self, f: &SpatialFrames) -> DMatrix<f64> {
        let n = self.mechanism.dof();
        let mut mass = DMatrix::zeros(n, n);
        for (_, t) in self.bodies(f) {
            mass += t.com.transpose() * &t.com * t.mass + t.rotation.transpose() * (t.inertia * &t.rotation);
        }
        self.add_flexure_mass(f, &mut mass);
        mass
    }

    /// The mass matrix $M(q)$.
    pub fn mass_matrix(&mut self, q: &[f64]) -> DMatrix<f64> {
        frames_into(self.mechanism, q, &mut self.frames);
        self.mass_at(&self.frames)
    }

    /// $h(q, \dot q)$ at the frames `f` (of $q$).
    fn velocity_product_at(&self, f: &SpatialFrames, v: &[f64]) -> DVector<f64> {
        let m = self.mechanism;
        let n = m.dof();
        let qd = DVector::from_column_slice(v);
        let mut h = DVector::zeros(n);
        let mut scratch = DMatrix::zeros(n, n);
        let quadratic = |s: &DMatrix<f64>| qd.dot(&(s * &qd));
        for (b, t) in self.bodies(f) {
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
                add_rotation_derivative(m, f, b, &e, &mut scratch);
                turn[i] = quadratic(&scratch);
            }
            let omega = &t.rotation * &qd;
            let omega = Vector3::new(omega[0], omega[1], omega[2]);
            let moment = t.inertia * turn + omega.cross(&(t.inertia * omega));
            h += t.com.transpose() * (bias * t.mass) + t.rotation.transpose() * moment;
        }
        h + self.flexure_velocity_product(&f.coordinates, v)
    }

    /// The velocity-product terms $h(q, \dot q)$.
    pub fn velocity_product(&mut self, q: &[f64], v: &[f64]) -> DVector<f64> {
        frames_into(self.mechanism, q, &mut self.frames);
        self.velocity_product_at(&self.frames, v)
    }

    /// The elastic and gravitational energy (J) at the frames `f`.
    fn potential_at(&self, f: &SpatialFrames) -> f64 {
        let m = self.mechanism;
        let elastic: f64 = f.joints.iter().map(|s| s.energy).sum();
        let gravity: f64 = m
            .bodies
            .iter()
            .enumerate()
            .skip(1)
            .map(|(b, body)| -body.mass * self.loads.gravity.dot(&(f.bodies[b] * body.com).coords))
            .sum();
        elastic + gravity + flexure_weight_potential(m, f, self.loads.gravity)
    }
}

impl System for SpatialSystem<'_> {
    fn dim(&self) -> usize {
        self.mechanism.dof()
    }

    fn closures(&self) -> usize {
        self.independent.as_ref().map_or(self.mechanism.constraints(), |u| u.nrows())
    }

    fn dynamics(&mut self, q: &[f64], v: &[f64], _t: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
        let m = self.mechanism;
        let n = m.dof();
        frames_into(m, q, &mut self.frames);
        let mu = vec![0.0; m.constraints()];
        assemble_into(m, &self.frames, &mu, &self.loads, false, &mut self.assembly);
        let mm = self.mass_at(&self.frames);
        let h = self.velocity_product_at(&self.frames, v);
        let d = &self.damping * DVector::from_column_slice(v);
        for i in 0..n {
            force[i] = -self.assembly.gradient[i] - h[i] - d[i];
        }
        mass.copy_from_slice(mm.as_slice());
        if !force.iter().chain(mass.iter()).all(|x| x.is_finite()) {
            return Err(Error::Singular { what: "spatial mechanism dynamics: a non-finite force or mass".into() });
        }
        Ok(())
    }

    /// The static Hessian and $\partial h/\partial q$ (central differences),
    /// and $D + \partial h/\partial\dot q$ (exact: $h$ is quadratic in $\dot q$).
    fn tangent(&mut self, q: &[f64], v: &[f64], _t: f64, stiffness: &mut [f64], damping: &mut [f64]) -> Result<()> {
        let m = self.mechanism;
        let n = m.dof();
        frames_into(m, q, &mut self.frames);
        let mu = vec![0.0; m.constraints()];
        assemble_into(m, &self.frames, &mu, &self.loads, true, &mut self.assembly);
        let mut k = self.assembly.hessian.clone();
        let mut d = self.damping.clone();
        let speed = v.iter().fold(0.0_f64, |a, x| a.max(x.abs())).max(1.0);
        let mut p = v.to_vec();
        for i in 0..n {
            let e = 1e-3 * speed;
            p[i] = v[i] + e;
            let up = self.velocity_product_at(&self.frames, &p);
            p[i] = v[i] - e;
            let down = self.velocity_product_at(&self.frames, &p);
            p[i] = v[i];
            d.set_column(i, &(d.column(i) + (up - down) / (2.0 * e)));
        }
        if v.iter().any(|x| *x != 0.0) {
            let mut shifted = q.to_vec();
            let mut f = SpatialFrames::new(m);
            for i in 0..n {
                let e = 1e-6 * (1.0 + q[i].abs());
                shifted[i] = q[i] + e;
                frames_into(m, &shifted, &mut f);
                let up = self.velocity_product_at(&f, v);
                shifted[i] = q[i] - e;
                frames_into(m, &shifted, &mut f);
                let down = self.velocity_product_at(&f, v);
                shifted[i] = q[i];
                k.set_column(i, &(k.column(i) + (up - down) / (2.0 * e)));
            }
        }
        stiffness.copy_from_slice(k.as_slice());
        damping.copy_from_slice(d.as_slice());
        Ok(())
    }

    fn closure(&mut self, q: &[f64], c: &mut [f64], g: &mut [f64]) -> Result<()> {
        let m = self.mechanism;
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
        Ok(())
    }

    fn energy(&mut self, q: &[f64], v: &[f64], _t: f64) -> Result<f64> {
        frames_into(self.mechanism, q, &mut self.frames);
        let mm = self.mass_at(&self.frames);
        let qd = DVector::from_column_slice(v);
        Ok(0.5 * qd.dot(&(mm * &qd)) + self.potential_at(&self.frames))
    }

    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        distance(self.mechanism, a, b, &mut self.pair.borrow_mut())
    }
}

/// The vibration modes of `m` about its equilibrium under its loads
/// ([`statics::solve`]): the finite solutions of
/// $Z^THZ\thinspace a = \omega^2Z^TMZ\thinspace a$, $v = Za$, as the planar
/// [`crate::dynamics::mechanism::modes`]; at most `count`, lowest first.
///
/// # Example
/// ```
/// use flexure::dynamics::spatial::modes;
/// use flexure::mechanism::spatial::{Revolute, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism};
/// use nalgebra::{Isometry3, Matrix3, Point3, Vector3};
/// // A sprung hinge about z (k = 2 N·m/rad) carrying 0.5 kg at 0.1 m: ω = √(k / m l²) = 20 rad/s.
/// let hinge = SpatialJointSpec {
///     name: "pin".into(), kind: SpatialJointKind::Revolute(Revolute { axis: Vector3::z_axis(), stiffness: 2.0, rest: 0.0 }),
///     parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default(),
/// };
/// let arm = SpatialBody { name: "arm".into(), mass: 0.5, com: Point3::new(0.1, 0.0, 0.0), inertia: Matrix3::zeros() };
/// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), arm], vec![hinge], vec![], vec![], vec![], Vector3::zeros()).unwrap();
/// let w = modes(&m, &Default::default(), 4).unwrap().omega;
/// assert!(w.len() == 1 && (w[0] - 20.0).abs() < 1e-12);
/// ```
pub fn modes(m: &SpatialMechanism, settings: &Settings, count: usize) -> Result<Modes> {
    if count == 0 {
        return Err(Error::invalid("count", count, "must be at least 1"));
    }
    let mut sys = SpatialSystem::new(m)?;
    if !sys.has_inertia() {
        return Err(Error::invalid(
            "mass",
            "none",
            "no body has mass or inertia and no flexure has a density or mass per length",
        ));
    }
    if m.dof() == 0 {
        return Err(Error::Singular { what: "the mechanism has no coordinates: nothing can vibrate".into() });
    }
    let s = statics::solve(m, settings)?;
    if !s.stable {
        return Err(Error::Unstable { what: "modes", load_fraction: s.limit.unwrap_or(1.0) });
    }
    let (z, k) = statics::stiffness(m, &s)?;
    if z.ncols() == 0 {
        return Err(Error::Singular { what: "the closures leave the mechanism no motion: nothing can vibrate".into() });
    }
    let mass = sys.mass_matrix(&s.q);
    let mz = z.transpose() * mass * &z;
    let found = finite_modes(&k, &mz, count)?;
    Ok(Modes { shapes: &z * &found.shapes, limit: s.limit, coordinates: s.q.clone(), ..found })
}

/// $U^T$ for [`SpatialSystem`]'s closures: the left singular vectors of
/// $G$ at the joints' rest whose singular values exceed $10^{-10}$ of the
/// largest, as rows; `None` when $G$ has full row rank there (or no rows).
fn independent_closures(m: &SpatialMechanism) -> Option<DMatrix<f64>> {
    let rows = m.constraints();
    if rows == 0 {
        return None;
    }
    let mut f = SpatialFrames::new(m);
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

/// One body's motion: its frame in the ground frame at each sample.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SpatialBodyMotion {
    /// The body's name.
    pub name: String,
    /// Its origin (m), ground frame, at each sample.
    pub position: Vec<[f64; 3]>,
    /// Its rotation matrix (rows), ground frame, at each sample.
    pub rotation: Vec<[[f64; 3]; 3]>,
}

/// A simulated motion of a spatial mechanism (as [`super::Simulation`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SpatialSimulation {
    /// Every moving body (not the ground), in the mechanism's order.
    pub bodies: Vec<SpatialBodyMotion>,
    /// The integrator's samples and counts; energy is kinetic, elastic and gravitational (J).
    #[serde(flatten)]
    pub trajectory: Trajectory,
    /// Why the run ended before its duration, if it did.
    #[serde(serialize_with = "message", skip_serializing_if = "Option::is_none")]
    pub stopped: Option<Error>,
}

impl std::ops::Deref for SpatialSimulation {
    type Target = Trajectory;

    fn deref(&self) -> &Trajectory {
        &self.trajectory
    }
}

fn message<S: serde::Serializer>(error: &Option<Error>, s: S) -> std::result::Result<S::Ok, S::Error> {
    match error {
        Some(e) => s.collect_str(e),
        None => s.serialize_none(),
    }
}

/// The state $(q, \dot q)$ a simulation starts from: the equilibrium under
/// the loads at $t = 0$ (`equilibrium`) or the assembled rest, then the file's
/// `[initial]` and `[initial_velocity]`.
pub fn initial_state(m: &SpatialMechanism, settings: &Settings, equilibrium: bool) -> Result<(Vec<f64>, Vec<f64>)> {
    let given = |j: usize| m.initial.iter().any(|(k, _)| *k == j);
    let mut q = if (0..m.joints.len()).all(given) {
        m.rest()
    } else {
        let loads = spatial_loads_at(m, 0.0);
        let unloaded = assemble_unloaded(m, settings)?;
        if equilibrium { solve_between(m, &unloaded, &loads, settings)?.q } else { unloaded.q }
    };
    let mut v = vec![0.0; m.dof()];
    for (state, given) in [(&mut q, &m.initial), (&mut v, &m.initial_velocity)] {
        for (j, values) in given {
            let o = m.joints[*j].offset;
            state[o..o + values.len()].copy_from_slice(values);
        }
    }
    Ok((q, v))
}

/// Simulates `m` from its equilibrium (or rest, `equilibrium = false`), with
/// `[initial]` and `[initial_velocity]`, under its loads and their `[[schedule]]`s.
///
/// Errors: `mass` when nothing has mass or inertia; a bad setting by name;
/// those of the start's static solve. A run that stops early keeps its
/// samples, with the error in [`SpatialSimulation::stopped`].
pub fn simulate(
    m: &SpatialMechanism,
    motion: &integrate::Settings,
    settings: &Settings,
    equilibrium: bool,
) -> Result<SpatialSimulation> {
    motion.validate()?;
    settings.validate()?;
    let system = SpatialSystem::new(m)?;
    if !system.has_inertia() {
        return Err(Error::invalid(
            "mass",
            "none",
            "no body has mass or inertia and no flexure has a density or mass per length: nothing moves",
        ));
    }
    let mut system = Scheduled::with(system, m.schedules.clone(), m.loads())?;
    let (q0, v0) = initial_state(m, settings, equilibrium)?;
    let (run, stopped) = integrate_kept(&mut system, &q0, &v0, motion)?;
    let mut bodies: Vec<SpatialBodyMotion> = m.bodies[1..]
        .iter()
        .map(|b| SpatialBodyMotion { name: b.name.clone(), position: Vec::new(), rotation: Vec::new() })
        .collect();
    let mut f = SpatialFrames::new(m);
    for k in 0..run.time.len() {
        // The bodies' poses alone (the flexures' Hessians cost most at high orders).
        frames_level_into(m, run.q(k), Level::Pose, &mut f);
        for (i, motion) in bodies.iter_mut().enumerate() {
            let b = i + 1;
            let p = f.bodies[b].translation.vector;
            let r = f.body_rotation(b);
            motion.position.push([p.x, p.y, p.z]);
            motion.rotation.push(std::array::from_fn(|row| std::array::from_fn(|col| r[(row, col)])));
        }
    }
    Ok(SpatialSimulation { bodies, trajectory: run, stopped })
}
