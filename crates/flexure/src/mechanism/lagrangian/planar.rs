//! The plane's part of the Lagrangian ([`super`]): point loads $V = -F\cdot w - M\phi$
//! (a moment has a potential, since planar rotations add), the weight of a
//! flexure's distributed mass ([`Weight`]), tendons, and the closures, whose
//! angle is the difference of two bodies' angles.
//!
//! A tendon of length $\ell = \sum_i\lvert d_i\rvert$,
//! $d_i = w_{i+1} - w_i$, has $\nabla\ell = \sum_i \partial d_i^T u_i$ and
//! $\nabla^2\ell = \sum_i \partial d_i^T(I - u_iu_i^T)\partial d_i/\lvert d_i\rvert + u_i\cdot\partial^2 d_i$.

use crate::error::{Error, Result};
use crate::mass::{MassModel, Weight, weight};
use crate::mechanism::kinematics::{Attached, Frames, add_attached_hessian, attach_into};
use crate::mechanism::{Holds, Loads, Mechanism};
use crate::space::Wrench;
use nalgebra::{DMatrix, DVector, Matrix2, Point2, Vector2};

pub(crate) fn wrap(a: f64) -> f64 {
    a - std::f64::consts::TAU * (a / std::f64::consts::TAU).round()
}

/// The joints' own distributed mass, for their weight: per joint with an
/// inertia ([`crate::mechanism::Joint::inertia`]: a flexure with a density or mass per
/// length), the nested quadrature tables of [`MassModel`] and a buffer for
/// its [`Weight`], asked for the first time gravity acts (so a weightless
/// assembly costs nothing more).
#[derive(Debug, Clone, Default)]
pub struct Weights {
    /// (joint, what it answered once asked: `None` for a joint without
    /// inertia; the tables are an error where its mass integrals cannot be
    /// made accurate).
    joints: Vec<(usize, Option<Option<Tables>>)>,
}

/// A flexure's mass tables and weight buffer, or why they could not be built.
type Tables = std::result::Result<(MassModel, Weight), Error>;

impl Weights {
    /// Every joint of `m`, not yet asked for its inertia.
    pub fn new(m: &Mechanism) -> Self {
        Weights { joints: (0..m.joints.len()).map(|i| (i, None)).collect() }
    }
}

/// $c$ and $G$ at the frames `f`.
pub(crate) fn closures(m: &Mechanism, f: &Frames) -> (DVector<f64>, DMatrix<f64>) {
    let (mut c, mut g) = (DVector::zeros(m.constraints()), DMatrix::zeros(m.constraints(), m.dof()));
    add_closures(m, f, &[], &mut c, &mut g, None, &mut [Attached::new(m), Attached::new(m)]);
    (c, g)
}

/// Writes $c$ and $G$, and adds $\sum_i\mu_i\nabla^2 c_i$ to `hessian` if given.
pub(crate) fn add_closures(
    m: &Mechanism,
    f: &Frames,
    mu: &[f64],
    closure: &mut DVector<f64>,
    g: &mut DMatrix<f64>,
    mut hessian: Option<&mut DMatrix<f64>>,
    points: &mut [Attached; 2],
) {
    let mut row = 0;
    let [pa, pb] = points;
    for c in &m.closures {
        let (a, ar, aphi, b, br, bphi) =
            (c.a, c.a_origin.origin(), c.a_origin.phi, c.b, c.b_origin.origin(), c.b_origin.phi);
        let angle = c.holds == Holds::Weld;
        attach_into(m, f, a, ar.coords, true, pa);
        attach_into(m, f, b, br.coords, true, pb);
        for k in 0..2 {
            closure[row + k] = pa.value[k] - pb.value[k];
        }
        // Column-major: G's column `col` and the points' (θ, x, y) columns.
        let rows = g.nrows();
        let (ja, jb) = (pa.jacobian.as_slice(), pb.jacobian.as_slice());
        for (col, column) in g.as_mut_slice().chunks_exact_mut(rows).enumerate() {
            let (ja, jb) = (&ja[3 * col..3 * col + 3], &jb[3 * col..3 * col + 3]);
            column[row] = ja[1] - jb[1];
            column[row + 1] = ja[2] - jb[2];
            if angle {
                column[row + 2] = ja[0] - jb[0];
            }
        }
        // The angle is linear in q for every joint kind: no Hessian term.
        if let Some(h) = hessian.as_deref_mut() {
            add_attached_hessian(m, f, pa, &Vector2::new(mu[row], mu[row + 1]), h);
            add_attached_hessian(m, f, pb, &Vector2::new(-mu[row], -mu[row + 1]), h);
        }
        if angle {
            closure[row + 2] = wrap(f.bodies[a].phi + aphi - f.bodies[b].phi - bphi);
        }
        row += c.equations();
    }
}

/// $\sum_i\mu_i\nabla^2 c_i$ alone.
pub(crate) fn closure_hessian(m: &Mechanism, f: &Frames, mu: &[f64]) -> DMatrix<f64> {
    let (n, rows) = (m.dof(), m.constraints());
    let mut h = DMatrix::zeros(n, n);
    let mut points = [Attached::new(m), Attached::new(m)];
    add_closures(m, f, mu, &mut DVector::zeros(rows), &mut DMatrix::zeros(rows, n), Some(&mut h), &mut points);
    h
}

/// Adds the loads' gradient (and Hessian) to `gradient` (`hessian`);
/// returns their potential. `points` are scratch buffers.
pub(crate) fn add_loads(
    m: &Mechanism,
    f: &Frames,
    loads: &Loads,
    gradient: &mut DVector<f64>,
    mut hessian: Option<&mut DMatrix<f64>>,
    points: &mut [Attached; 2],
    weights: &mut Weights,
) -> Result<f64> {
    let n = m.dof();
    let mut potential = 0.0;
    for (p, l) in m.forces.iter().zip(&loads.force) {
        if l != &Wrench::default() {
            let point = (p.body, p.at);
            potential += add_point_load(m, f, point, l, gradient, hessian.as_deref_mut(), &mut points[0]);
        }
    }
    for (b, body) in m.bodies.iter().enumerate() {
        let weight = Wrench { moment: 0.0, fx: body.mass * loads.gravity[0], fy: body.mass * loads.gravity[1] };
        if body.mass > 0.0 && weight != Wrench::default() {
            potential += add_point_load(m, f, (b, body.com), &weight, gradient, hessian.as_deref_mut(), &mut points[0]);
        }
    }
    // A tendon: V = T Σ|w_{i+1} − w_i|, its via points taken two at a time.
    for (t, &tension) in m.tendons.iter().zip(&loads.tension) {
        if tension == 0.0 {
            continue;
        }
        let [first, second] = points;
        let (mut a, mut b) = (first, second);
        attach_into(m, f, t.path[0].0, t.path[0].1.coords, true, a);
        for i in 0..t.path.len() - 1 {
            let (body, r) = t.path[i + 1];
            attach_into(m, f, body, r.coords, true, b);
            let d = [b.value[0] - a.value[0], b.value[1] - a.value[1]];
            let len = d[0].hypot(d[1]);
            // Coincident to rounding: the direction u is undefined.
            let size = a.value.iter().chain(b.value.iter()).map(|v| v.abs()).sum::<f64>();
            if len.is_nan() || len <= 1e-14 * size {
                return Err(Error::Singular {
                    what: format!("tendon {:?}: via points {} and {} coincide", t.name, i + 1, i + 2),
                });
            }
            potential += tension * len;
            let u = [d[0] / len, d[1] / len];
            let jd = |k: usize, c: usize| b.jacobian[(1 + k, c)] - a.jacobian[(1 + k, c)];
            for c in 0..n {
                gradient[c] += (jd(0, c) * u[0] + jd(1, c) * u[1]) * tension;
            }
            if let Some(h) = hessian.as_deref_mut() {
                // ∂²|d| = ∂dᵀ(I − u uᵀ)∂d/|d| + u·∂²d.
                let proj = Matrix2::new(1.0 - u[0] * u[0], -u[0] * u[1], -u[0] * u[1], 1.0 - u[1] * u[1]) / len;
                for c in 0..n {
                    let (x, y) = (jd(0, c), jd(1, c));
                    if x == 0.0 && y == 0.0 {
                        continue;
                    }
                    let pc = [proj[(0, 0)] * x + proj[(0, 1)] * y, proj[(1, 0)] * x + proj[(1, 1)] * y];
                    for r in 0..n {
                        h[(r, c)] += (jd(0, r) * pc[0] + jd(1, r) * pc[1]) * tension;
                    }
                }
                add_attached_hessian(m, f, b, &Vector2::new(u[0] * tension, u[1] * tension), h);
                add_attached_hessian(m, f, a, &Vector2::new(-u[0] * tension, -u[1] * tension), h);
            }
            std::mem::swap(&mut a, &mut b);
        }
    }
    if loads.gravity != Vector2::zeros() {
        potential += add_flexure_weights(m, f, loads.gravity, gradient, hessian, &mut points[0], weights)?;
    }
    Ok(potential)
}

/// A wrench (moment and force) at the point `at` of a body, `(body, at)`:
/// $V = -F\cdot w - M\phi$, its gradient added to `gradient` and its
/// Hessian to `hessian` if given; `p` is left holding the point and its
/// derivatives. Returns $V$.
#[allow(clippy::too_many_arguments)]
fn add_point_load(
    m: &Mechanism,
    f: &Frames,
    (body, at): (usize, Point2<f64>),
    w: &Wrench,
    gradient: &mut DVector<f64>,
    hessian: Option<&mut DMatrix<f64>>,
    p: &mut Attached,
) -> f64 {
    attach_into(m, f, body, at.coords, true, p);
    // Column-major 3 × n: coordinate c's (φ, x, y).
    for (g, j) in gradient.as_mut_slice().iter_mut().zip(p.jacobian.as_slice().chunks_exact(3)) {
        *g -= w.fx * j[1] + w.fy * j[2] + w.moment * j[0];
    }
    if let Some(h) = hessian {
        add_attached_hessian(m, f, p, &Vector2::new(-w.fx, -w.fy), h);
    }
    -(w.fx * p.value[0] + w.fy * p.value[1] + w.moment * f.bodies[body].phi)
}

/// The flexures' weight: with the first moment $c(\alpha)$ of a flexure's
/// mass in its root frame ([`Weight`]), $V = -g\cdot(m\thinspace o + Rc)$
/// for a root at $o$ turned by $R$. Over the coordinates upstream it is the
/// whole weight $mg$ at the centre of mass, a point fixed in the root frame
/// (so its derivatives are a point load's); over the flexure's own,
/// $\partial_iV = -g\cdot R\thinspace\partial_ic$ and $\partial_{ij}V = -g\cdot R\thinspace\partial_{ij}c$;
/// across them, $\partial_u\partial_iV = -\theta_{,u}\thinspace g\cdot ER\thinspace\partial_ic$
/// ($\theta$ the root's angle, $E$ the quarter turn). Returns $V$.
fn add_flexure_weights(
    m: &Mechanism,
    f: &Frames,
    g: Vector2<f64>,
    gradient: &mut DVector<f64>,
    mut hessian: Option<&mut DMatrix<f64>>,
    p: &mut Attached,
    weights: &mut Weights,
) -> Result<f64> {
    let n = m.dof();
    let mut potential = 0.0;
    for (j, tables) in &mut weights.joints {
        let spec = &m.joints[*j];
        let built = tables.get_or_insert_with(|| {
            let model = spec.kind.joint().inertia()?;
            Some(
                model
                    .map(|model| {
                        let w = Weight::new(&model);
                        (model, w)
                    })
                    .map_err(|e| e.in_joint(&spec.name)),
            )
        });
        let (model, w) = match built {
            None => continue,
            Some(Ok((model, w))) => (&*model, w),
            Some(Err(e)) => return Err(e.clone()),
        };
        let (o, k) = (spec.offset, model.order());
        weight(model, &f.coordinates[o..o + k], w);
        if w.mass <= 0.0 {
            continue;
        }
        let centre = [w.first_moment[0] / w.mass, w.first_moment[1] / w.mass];
        let (s0, c0) = spec.origin.phi.sin_cos();
        let at = Point2::new(
            spec.origin.x + c0 * centre[0] - s0 * centre[1],
            spec.origin.y + s0 * centre[0] + c0 * centre[1],
        );
        let weight = Wrench { moment: 0.0, fx: w.mass * g[0], fy: w.mass * g[1] };
        potential += add_point_load(m, f, (spec.parent, at), &weight, gradient, hessian.as_deref_mut(), p);
        let root = f.roots[*j];
        // g·R v for v in the root frame, and g·E R v.
        let along = |v: [f64; 2]| {
            let world = root.rotate(&Vector2::new(v[0], v[1]));
            (g[0] * world[0] + g[1] * world[1], g[1] * world[0] - g[0] * world[1])
        };
        for (i, di) in w.jacobian.iter().enumerate() {
            gradient[o + i] -= along(*di).0;
        }
        if let Some(h) = hessian.as_deref_mut() {
            for i in 0..k {
                for jj in 0..k {
                    h[(o + i, o + jj)] -= along(w.hessian[i * k + jj]).0;
                }
                let turn = along(w.jacobian[i]).1;
                for u in 0..n {
                    let theta = p.jacobian[(0, u)];
                    if theta != 0.0 {
                        h[(u, o + i)] -= theta * turn;
                        h[(o + i, u)] -= theta * turn;
                    }
                }
            }
        }
    }
    Ok(potential)
}
