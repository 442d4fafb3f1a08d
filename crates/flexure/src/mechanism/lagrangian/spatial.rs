//! Space's part of the Lagrangian ([`super`]): point forces and dead
//! moments, the bodies' and the spatial flexures' weights, tendons, and the
//! closures, which compare the two frames' axes. The stations $x_k$ of a
//! spatial flexure's own mass ([`crate::spatial::MassQuadrature`]) carry
//! dead loads $\mu_kw_kg$; a moment $m_i$ fixed in space adds the
//! generalized force $Q_a = m_i\cdot\omega_a$.

use crate::kinematics::Level;
use crate::mechanism::Holds;
use crate::mechanism::kinematics::{
    Attached, Frames, JointWrenches, add_rotation_derivative, attach, gather_attached_hessian,
};
use crate::mechanism::spatial::{SpatialClosure, SpatialLoads, SpatialMechanism};
use crate::space::Spatial;
use crate::spatial::{MassQuadrature, StationKinematics, stations_update};
use nalgebra::{DMatrix, DVector, Matrix3, Matrix3xX, Point3, Vector3};

/// The Hessian and the sums its same-joint parts are gathered in.
type Gathered<'a> = Option<(&'a mut DMatrix<f64>, &'a mut JointWrenches)>;

/// Adds the loads' part of the gradient (and of its derivative, when asked
/// for, its same-joint parts gathered into the given [`JointWrenches`], not
/// yet added) and returns their potential. Linear in `loads`: with a change
/// of loads it gives the load derivative of the equilibrium equations.
pub(super) fn gather_loads(
    m: &SpatialMechanism,
    f: &Frames<Spatial>,
    loads: &SpatialLoads,
    gradient: &mut DVector<f64>,
    mut hessian: Gathered<'_>,
) -> f64 {
    let mut potential = 0.0;
    // A force u at a point: V = −u·x, ∇V = −Jᵀu, ∇²V = −Σ u_c ∇²x_c.
    let push = |x: &Attached<Spatial>, u: Vector3<f64>, gradient: &mut DVector<f64>, hessian: &mut Gathered<'_>| {
        gradient.gemv_tr(-1.0, &x.jacobian.fixed_rows::<3>(3), &u, 1.0);
        if let Some((h, w)) = hessian {
            gather_attached_hessian(m, f, x, &(-u), h, Some(w));
        }
        -u.dot(&x.value)
    };
    if loads.gravity != Vector3::zeros() {
        for (b, body) in m.bodies.iter().enumerate().skip(1) {
            if body.mass > 0.0 {
                let x = attach(m, f, b, body.com.coords, true);
                potential += push(&x, loads.gravity * body.mass, gradient, &mut hessian);
            }
        }
    }
    if loads.gravity != Vector3::zeros() {
        for (j, spec) in m.joints.iter().enumerate() {
            let Some(flexure) = spec.kind.flexure() else { continue };
            if let Some(quadrature) = MassQuadrature::new(flexure) {
                potential += flexure_weight(m, f, j, &quadrature, loads.gravity, gradient, &mut hessian);
            }
        }
    }
    for (load, w) in m.forces.iter().zip(&loads.force) {
        let force = Vector3::new(w[3], w[4], w[5]);
        let moment = Vector3::new(w[0], w[1], w[2]);
        if force != Vector3::zeros() {
            let x = attach(m, f, load.body, load.at.coords, true);
            potential += push(&x, force, gradient, &mut hessian);
        }
        if moment != Vector3::zeros() {
            let mut b = load.body;
            while let Some(j) = m.parent_joint(b) {
                let o = m.joints[j].offset;
                for c in o..o + f.joints[j].gradient.len() {
                    gradient[c] -= moment.dot(&f.omega[c]);
                }
                b = m.joints[j].parent;
            }
            if let Some((h, w)) = &mut hessian {
                add_rotation_derivative(m, f, load.body, &(-moment), h, Some(w));
            }
        }
    }
    for (t, &tension) in m.tendons.iter().zip(&loads.tension) {
        if tension == 0.0 {
            continue;
        }
        let points: Vec<Attached<Spatial>> = t.path.iter().map(|(b, r)| attach(m, f, *b, r.coords, true)).collect();
        for pair in points.windows(2) {
            let (x0, x1) = (&pair[0], &pair[1]);
            let d = x1.value - x0.value;
            let l = d.norm();
            if l == 0.0 {
                continue;
            }
            let u = d / l;
            potential += tension * l;
            let dj: Matrix3xX<f64> = x1.jacobian.fixed_rows::<3>(3) - x0.jacobian.fixed_rows::<3>(3);
            gradient.gemv_tr(tension, &dj, &u, 1.0);
            if let Some((h, w)) = &mut hessian {
                let projector = (Matrix3::identity() - u * u.transpose()) * (tension / l);
                **h += dj.transpose() * (projector * &dj);
                gather_attached_hessian(m, f, x1, &(u * tension), h, Some(w));
                gather_attached_hessian(m, f, x0, &(-u * tension), h, Some(w));
            }
        }
    }
    potential
}

/// The weight of spatial flexure joint `j`'s own mass under `gravity`:
/// adds its gradient (and derivative, when asked for) and returns its
/// potential $-g\cdot\sum_k\mu_kw_kx_k$.
///
/// With $A$ the joint's root frame $(R_A, o_A)$ and $S(q_j) = \sum_k\mu_kw_kp_k$
/// the first moment in it ([`stations_update`]), $\sum_k\mu_kw_kx_k = m\thinspace o_A + R_AS$:
/// upstream of the joint the stations move with the parent body, so their
/// weight is the whole mass $m$ at their centroid $\bar x$ fixed in it (a
/// body's weight, gradient and Hessian as [`attach`] and
/// [`gather_attached_hessian`] give them); within the joint the gradient is
/// $-g\cdot R_A\partial_aS$ and the Hessian $-g\cdot R_A\partial_a\partial_bS$;
/// across, $\partial_c(R_A\partial_aS) = \omega_c\times R_A\partial_aS$ for a
/// coordinate $c$ upstream gives $-g\cdot(\omega_c\times R_A\partial_aS)$.
fn flexure_weight(
    m: &SpatialMechanism,
    f: &Frames<Spatial>,
    j: usize,
    quadrature: &MassQuadrature,
    gravity: Vector3<f64>,
    gradient: &mut DVector<f64>,
    hessian: &mut Gathered<'_>,
) -> f64 {
    let spec = &m.joints[j];
    let Some(flexure) = spec.kind.flexure() else { return 0.0 };
    let (o, n) = (spec.offset, flexure.coordinates());
    let level = if hessian.is_some() { Level::Hessian } else { Level::Jacobian };
    let mut k = StationKinematics::new(flexure, quadrature);
    stations_update(flexure, quadrature, &f.coordinates[o..o + n], level, &mut k);
    let total = quadrature.mass();
    let root = &f.roots[j];
    let ra = root.rotation.to_rotation_matrix().into_inner();
    let first = root.translation.vector * total + ra * k.moment;
    // R_A ∂_a S, world directions.
    let turned: Vec<Vector3<f64>> = (0..n)
        .map(|a| {
            let d: Vector3<f64> =
                quadrature.stations().iter().enumerate().map(|(i, st)| k.velocity[i * n + a] * st.mass).sum();
            ra * d
        })
        .collect();
    for (a, d) in turned.iter().enumerate() {
        gradient[o + a] -= gravity.dot(d);
    }
    if total <= 0.0 {
        return -gravity.dot(&first);
    }
    let centroid = f.bodies[spec.parent].inverse() * Point3::from(first / total);
    let x = attach(m, f, spec.parent, centroid.coords, true);
    let weight = gravity * total;
    gradient.gemv_tr(-1.0, &x.jacobian.fixed_rows::<3>(3), &weight, 1.0);
    if let Some((h, w)) = hessian {
        gather_attached_hessian(m, f, &x, &(-weight), h, Some(w));
        for &up in x.path() {
            let ou = m.joints[up].offset;
            for c in ou..ou + f.joints[up].gradient.len() {
                let omega = f.omega[c];
                for (a, d) in turned.iter().enumerate() {
                    let v = -gravity.dot(&omega.cross(d));
                    h[(o + a, c)] += v;
                    h[(c, o + a)] += v;
                }
            }
        }
        let local = ra.tr_mul(&gravity);
        for a in 0..n {
            for b in 0..n {
                h[(o + a, o + b)] -= local.dot(&k.moment_hessian[a * n + b]);
            }
        }
    }
    -gravity.dot(&first)
}

/// The potential $-g\cdot\sum_k\mu_kw_kx_k$ of every spatial flexure's own
/// mass under `gravity` at the frames `f` (their poses alone).
pub(crate) fn flexure_weight_potential(m: &SpatialMechanism, f: &Frames<Spatial>, gravity: Vector3<f64>) -> f64 {
    if gravity == Vector3::zeros() {
        return 0.0;
    }
    let mut potential = 0.0;
    for (j, spec) in m.joints.iter().enumerate() {
        let Some(flexure) = spec.kind.flexure() else { continue };
        let Some(quadrature) = MassQuadrature::new(flexure) else { continue };
        let mut k = StationKinematics::new(flexure, &quadrature);
        let o = spec.offset;
        stations_update(flexure, &quadrature, &f.coordinates[o..o + flexure.coordinates()], Level::Pose, &mut k);
        let root = &f.roots[j];
        let first = root.translation.vector * quadrature.mass() + root.rotation * k.moment;
        potential -= gravity.dot(&first);
    }
    potential
}

/// The vectors a closure is made of: its two points, and the directions
/// its rotation equations compare.
struct ClosureVectors {
    points: [Attached<Spatial>; 2],
    /// Weld: the three axes of each frame; pin: the axis on `a` and the two normals on `b`.
    a_directions: Vec<Attached<Spatial>>,
    b_directions: Vec<Attached<Spatial>>,
}

fn closure_vectors(m: &SpatialMechanism, f: &Frames<Spatial>, c: &SpatialClosure) -> ClosureVectors {
    let point = |b: usize, r: Vector3<f64>| attach(m, f, b, r, true);
    let direction = |b: usize, r: Vector3<f64>| attach(m, f, b, r, false);
    let points = [point(c.a, c.a_origin.translation.vector), point(c.b, c.b_origin.translation.vector)];
    match c.holds {
        // Each frame's three axes.
        Holds::Weld => {
            let axes = c.axes();
            ClosureVectors {
                points,
                a_directions: axes[..3].iter().map(|x| direction(c.a, *x)).collect(),
                b_directions: axes[3..].iter().map(|x| direction(c.b, *x)).collect(),
            }
        }
        // a's axis, and b's two normals to its own.
        Holds::Pin => {
            let axes = c.axes();
            ClosureVectors {
                points,
                a_directions: vec![direction(c.a, axes[2])],
                b_directions: axes[3..5].iter().map(|x| direction(c.b, *x)).collect(),
            }
        }
        Holds::Ball => ClosureVectors { points, a_directions: vec![], b_directions: vec![] },
    }
}

/// $c(q)$ and $G$ into `c` ($m$) and `g` ($m\times n$).
pub fn closures_into(m: &SpatialMechanism, f: &Frames<Spatial>, c: &mut DVector<f64>, g: &mut DMatrix<f64>) {
    let mut row = 0;
    for closure in &m.closures {
        let v = closure_vectors(m, f, closure);
        let [pa, pb] = &v.points;
        for i in 0..3 {
            c[row + i] = pa.value[i] - pb.value[i];
            for k in 0..g.ncols() {
                g[(row + i, k)] = pa.jacobian[(3 + i, k)] - pb.jacobian[(3 + i, k)];
            }
        }
        row += 3;
        match closure.holds {
            Holds::Weld => {
                // e = ½ Σ b_i × a_i.
                let mut e = Vector3::zeros();
                for (a, b) in v.a_directions.iter().zip(&v.b_directions) {
                    e += b.value.cross(&a.value) * 0.5;
                }
                for k in 0..g.ncols() {
                    let mut d = Vector3::zeros();
                    for (a, b) in v.a_directions.iter().zip(&v.b_directions) {
                        d += (b.linear(k).cross(&a.value) + b.value.cross(&a.linear(k))) * 0.5;
                    }
                    for i in 0..3 {
                        g[(row + i, k)] = d[i];
                    }
                }
                for i in 0..3 {
                    c[row + i] = e[i];
                }
                row += 3;
            }
            Holds::Pin => {
                // c_k = n_k · z.
                let z = &v.a_directions[0];
                for (i, n) in v.b_directions.iter().enumerate() {
                    c[row + i] = n.value.dot(&z.value);
                    for k in 0..g.ncols() {
                        g[(row + i, k)] = n.linear(k).dot(&z.value) + n.value.dot(&z.linear(k));
                    }
                }
                row += 2;
            }
            Holds::Ball => {}
        }
    }
}

/// Adds $\mu\cdot(x\times y)$'s Hessian's cross terms, $C + C^T$ with
/// $C_{cd} = \mu\cdot(\partial_cx\times\partial_dy)$, to `h`.
fn add_cross_terms(x: &Attached<Spatial>, y: &Attached<Spatial>, mu: &Vector3<f64>, h: &mut DMatrix<f64>) {
    // μ·(X_c × Y_d) = X_c · (Y_d × μ).
    let ymu = DMatrix::from_fn(3, y.jacobian.ncols(), |i, d| y.linear(d).cross(mu)[i]);
    let c = x.jacobian.fixed_rows::<3>(3).transpose() * ymu;
    *h += &c + c.transpose();
}

/// Adds $\sum_i\mu_i\nabla^2c_i$ to `h` (within each joint as
/// [`crate::mechanism::kinematics::add_attached_hessian`]).
pub fn add_closure_hessian(m: &SpatialMechanism, f: &Frames<Spatial>, mu: &[f64], h: &mut DMatrix<f64>) {
    let mut w = JointWrenches::new(m);
    gather_closure_hessian(m, f, mu, h, &mut w);
    w.flush(m, f, h);
}

/// [`add_closure_hessian`] with the same-joint parts gathered into `w`, not yet added.
pub(super) fn gather_closure_hessian(
    m: &SpatialMechanism,
    f: &Frames<Spatial>,
    mu: &[f64],
    h: &mut DMatrix<f64>,
    sums: &mut JointWrenches,
) {
    let mut add = |x: &Attached<Spatial>, u: &Vector3<f64>, h: &mut DMatrix<f64>| {
        gather_attached_hessian(m, f, x, u, h, Some(sums))
    };
    let mut row = 0;
    for closure in &m.closures {
        let v = closure_vectors(m, f, closure);
        let w = Vector3::new(mu[row], mu[row + 1], mu[row + 2]);
        add(&v.points[0], &w, h);
        add(&v.points[1], &(-w), h);
        row += 3;
        match closure.holds {
            Holds::Weld => {
                let w = Vector3::new(mu[row], mu[row + 1], mu[row + 2]) * 0.5;
                for (a, b) in v.a_directions.iter().zip(&v.b_directions) {
                    // μ·(b × a): b's Hessian weighted a × μ, a's weighted μ × b.
                    add(b, &a.value.cross(&w), h);
                    add(a, &w.cross(&b.value), h);
                    add_cross_terms(b, a, &w, h);
                }
                row += 3;
            }
            Holds::Pin => {
                let z = &v.a_directions[0];
                for (i, n) in v.b_directions.iter().enumerate() {
                    let weight = mu[row + i];
                    add(z, &(n.value * weight), h);
                    add(n, &(z.value * weight), h);
                    let c = n.jacobian.fixed_rows::<3>(3).transpose() * z.jacobian.fixed_rows::<3>(3) * weight;
                    *h += &c + c.transpose();
                }
                row += 2;
            }
            Holds::Ball => {}
        }
    }
}
