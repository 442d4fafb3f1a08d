//! The minimum-energy shape between two poses (paper Sec. II-E, Eq. 16).

use crate::energy::{energy, energy_gradient, stiffness};
use crate::error::{Error, Result, finite};
use crate::joint::{Basis, Flexure};
use crate::kinematics::{self, Kinematics, Level, Pose};
use crate::newton::find_root;
use crate::statics::TipLoad;
use nalgebra::{DMatrix, DVector, SMatrix, SVector};

/// A minimum-energy shape.
#[derive(Debug, Clone, PartialEq)]
pub struct Connection {
    /// Joint coordinates.
    pub alpha: Vec<f64>,
    /// Bending energy $U(\alpha)$ (J).
    pub energy: f64,
    /// The tip load that holds this shape: the Lagrange multipliers of the
    /// three tip constraints, $\nabla U = \mathcal J^T (M, F_x, F_y)$.
    pub load: TipLoad,
    /// Newton iterations.
    pub iterations: usize,
}

/// Checks that a tip pose is finite and within reach of an inextensible flexure.
pub fn check_pose(flexure: &Flexure, target: &Pose) -> Result<()> {
    finite("pose", target.phi)?;
    finite("pose", target.x)?;
    finite("pose", target.y)?;
    let r = target.x.hypot(target.y);
    if r >= flexure.length() {
        return Err(Error::invalid(
            "pose",
            format!("({}, {}, {}) at distance {r} from the root", target.phi, target.x, target.y),
            "the tip must lie closer to the root than the length L",
        ));
    }
    Ok(())
}

/// The coordinates of least energy $U(\alpha)$ whose tip reaches `target`.
///
/// For the paper's $N = 3$ Legendre model there is nothing to minimize: Eq. 11
/// fixes $\alpha_1 = \phi$, and Eqs. 14–15 give two equations in $\alpha_2,
/// \alpha_3$, solved by Newton. Otherwise (any order $N > 3$, or a segment
/// chain) Newton solves the KKT conditions of $\min U$ s.t. tip pose = target,
/// $$\begin{bmatrix} K & -\mathcal J^T\\ \mathcal J & 0\end{bmatrix}
/// \begin{bmatrix}\delta\alpha\\ \delta\lambda\end{bmatrix} = -\begin{bmatrix}\nabla U - \mathcal J^T\lambda\\ p(\alpha) - p^*\end{bmatrix},$$
/// with $K = \nabla\nabla U - F_x\nabla\nabla x - F_y\nabla\nabla y$ (Eq. 32).
/// Both start from the circular arc through the target angle.
///
/// # Example
/// ```
/// use flexure::{connect::connect, Flexure, Pose};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // The tip of a circular arc of angle 1 is reached by that arc.
/// let target = Pose { phi: 1.0, x: 1f64.sin(), y: 1.0 - 1f64.cos() };
/// let c = connect(&f, &target).unwrap();
/// assert!((c.alpha[0] - 1.0).abs() < 1e-12 && c.alpha[1].abs() < 1e-8);
/// ```
pub fn connect(flexure: &Flexure, target: &Pose) -> Result<Connection> {
    check_pose(flexure, target)?;
    let n = flexure.order();
    if n < 3 {
        return Err(Error::invalid("order", n, "must be at least 3 to reach a tip pose (three constraints)"));
    }
    let mut k = Kinematics::new(flexure);
    let tolerance = 1e-13 * flexure.length();
    let (alpha, iterations) = if flexure.basis() == Basis::Legendre && n == 3 {
        direct(flexure, target, &mut k, tolerance)?
    } else {
        kkt(flexure, target, &mut k, tolerance)?
    };
    kinematics::update(flexure, &alpha, &mut k, Level::Jacobian);
    let load = multipliers(flexure, &alpha, &k)?;
    Ok(Connection { energy: energy(flexure, &alpha), alpha, load, iterations })
}

/// Coordinates of the circular arc with tip angle `phi`.
fn arc(flexure: &Flexure, phi: f64) -> Vec<f64> {
    let n = flexure.order();
    match flexure.basis() {
        Basis::Legendre => (0..n).map(|i| if i == 0 { phi } else { 0.0 }).collect(),
        Basis::Segments => vec![phi / n as f64; n],
    }
}

/// Eqs. 11, 14, 15: $\alpha_1 = \phi$, then Newton on $(x, y)$ in $(\alpha_2, \alpha_3)$.
fn direct(flexure: &Flexure, target: &Pose, k: &mut Kinematics<f64>, tolerance: f64) -> Result<(Vec<f64>, usize)> {
    let phi = target.phi;
    let residual = |z: &SVector<f64, 2>| -> Result<(SVector<f64, 2>, SMatrix<f64, 2, 2>)> {
        kinematics::update(flexure, &[phi, z[0], z[1]], k, Level::Jacobian);
        let (p, j) = (k.pose_root_tip, &k.jacobian_root_tip);
        Ok((
            SVector::from([p.x - target.x, p.y - target.y]),
            SMatrix::<f64, 2, 2>::new(j[(1, 1)], j[(1, 2)], j[(2, 1)], j[(2, 2)]),
        ))
    };
    let root = find_root(residual, SVector::zeros(), tolerance, 100)?;
    Ok((vec![phi, root.x[0], root.x[1]], root.iterations))
}

/// Newton on the KKT system, with damping on the residual norm.
fn kkt(flexure: &Flexure, target: &Pose, k: &mut Kinematics<f64>, tolerance: f64) -> Result<(Vec<f64>, usize)> {
    let n = flexure.order();
    let mut z = DVector::zeros(n + 3);
    z.rows_mut(0, n).copy_from_slice(&arc(flexure, target.phi));
    let scale = flexure.ei() / flexure.length();
    let mut gradient = vec![0.0; n];
    let mut evaluate = |z: &DVector<f64>, jacobian: Option<&mut DMatrix<f64>>| -> DVector<f64> {
        let alpha = z.rows(0, n);
        kinematics::update(flexure, alpha.as_slice(), k, Level::Hessian);
        energy_gradient(flexure, alpha.as_slice(), &mut gradient);
        let (m, fx, fy) = (z[n], z[n + 1], z[n + 2]);
        let j = &k.jacobian_root_tip;
        let mut r = DVector::zeros(n + 3);
        for i in 0..n {
            r[i] = (gradient[i] - (j[(0, i)] * m + j[(1, i)] * fx + j[(2, i)] * fy)) / scale;
        }
        let p = k.pose_root_tip;
        r[n] = (p.phi - target.phi) * flexure.length();
        r[n + 1] = p.x - target.x;
        r[n + 2] = p.y - target.y;
        if let Some(jac) = jacobian {
            jac.fill(0.0);
            for c in 0..n {
                for row in 0..n {
                    jac[(row, c)] =
                        -(fx * k.hessian_root_tip_x[(row, c)] + fy * k.hessian_root_tip_y[(row, c)]) / scale;
                }
                jac[(c, c)] += stiffness(flexure, c) / scale;
                for a in 0..3 {
                    jac[(c, n + a)] = -j[(a, c)] / scale;
                    jac[(n + a, c)] = j[(a, c)] * if a == 0 { flexure.length() } else { 1.0 };
                }
            }
        }
        r
    };
    let mut jac = DMatrix::zeros(n + 3, n + 3);
    let mut r = evaluate(&z, Some(&mut jac));
    for iteration in 0..200 {
        let residual = r.amax();
        if residual <= tolerance {
            return Ok((z.rows(0, n).iter().copied().collect(), iteration));
        }
        let fail =
            Error::NoConvergence { unit: "relative", solver: "connect (KKT Newton)", iterations: iteration, residual };
        let step = jac.clone().lu().solve(&(-&r)).ok_or(fail.clone())?;
        let mut t = 1.0;
        loop {
            let trial = &z + &step * t;
            let rt = evaluate(&trial, None);
            if rt.amax() < residual || (t == 1.0 && residual < 1e3 * tolerance) {
                z = trial;
                r = evaluate(&z, Some(&mut jac));
                break;
            }
            t *= 0.5;
            if t < 1e-8 {
                return Err(fail);
            }
        }
    }
    Err(Error::NoConvergence { unit: "relative", solver: "connect (KKT Newton)", iterations: 200, residual: r.amax() })
}

/// Least-squares tip load with $\nabla U = \mathcal J^T\lambda$ (exact at a KKT point).
fn multipliers(flexure: &Flexure, alpha: &[f64], k: &Kinematics<f64>) -> Result<TipLoad> {
    let mut g = vec![0.0; alpha.len()];
    energy_gradient(flexure, alpha, &mut g);
    let jt = k.jacobian_root_tip.transpose();
    let l = (jt.transpose() * &jt)
        .lu()
        .solve(&(jt.transpose() * DVector::from_vec(g)))
        .ok_or_else(|| Error::Singular { what: "the tip Jacobian is rank-deficient at this shape".into() })?;
    Ok(TipLoad { moment: l[0], fx: l[1], fy: l[2] })
}
