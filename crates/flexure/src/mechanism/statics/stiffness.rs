//! Stiffness and compliance of a mechanism at an equilibrium.

use super::Solution;
use super::dimension::{Statics, parts};
use super::kkt::constrained;
use crate::error::{Error, Result};
use crate::kinematics::Level;
use crate::linalg;
use crate::mechanism::Mechanism;
use crate::mechanism::kinematics::{Frames, attach, frames, frames_level_into};
use crate::mechanism::lagrangian::{Assembly, assemble_into};
use nalgebra::DMatrix;

/// Frames of the solution.
pub fn body_frames<D: Statics>(m: &Mechanism<D>, s: &Solution<D>) -> Frames<D> {
    D::pose_frames(m, &s.q)
}

/// $Z$ and the generalized stiffness on the admissible motions,
/// $Z^T\nabla^2 L\thinspace Z$ (Eq. 27, projected), at a solution, from the
/// exact Hessian (the joints' own second derivatives): symmetrized, unless
/// a dead moment may make it unsymmetric ([`Statics::DEAD_MOMENTS`]). The
/// contacts that touch are held as they are: closed, and stuck where
/// stuck (their gap's curvature and force in $\nabla^2 L$, their gradients
/// among the constraints); a sliding one with friction is refused.
pub fn stiffness<D: Statics>(m: &Mechanism<D>, s: &Solution<D>) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    D::check_start(m, &s.q, &s.multipliers, &s.loads)?;
    let f = frames(m, &s.q);
    let mut a = Assembly::new(m);
    assemble_into(m, &f, &s.multipliers, &s.loads, true, &mut a)?;
    let a = parts(&a);
    // The contacts that touch, held as they are (super::contact::held).
    let (extra, rows) = super::contact::held(m, s)?;
    let hessian = a.hessian + extra;
    let g = a.closure_jacobian;
    let g = DMatrix::from_fn(g.nrows() + rows.len(), g.ncols(), |r, c| {
        if r < g.nrows() { g[(r, c)] } else { rows[r - g.nrows()][c] }
    });
    let z = linalg::null_space(&g);
    let k = if D::DEAD_MOMENTS { z.transpose() * &hessian * &z } else { constrained(&hessian, &z) };
    Ok((z, k))
}

/// Compliance of the frame at `at` on `body` to a small extra load there,
/// with the contacts that touch held as they are ([`stiffness`]):
/// $C = J Z (Z^T\nabla^2 L Z)^{-1} Z^T J^T$, $J$ the point's Jacobian, in the
/// order of the dimension's wrench, $(M, F_x, F_y)$ in the plane,
/// $(m, f)$ in space (the small rotation and displacement in the ground
/// frame). A symmetric stiffness must be positive definite (else
/// [`Error::Singular`]: unstable, or a joint is free); an unsymmetric one
/// ([`Statics::DEAD_MOMENTS`]) is solved by LU, and not symmetrized.
///
/// # Example
/// ```
/// use flexure::mechanism::{file::from_toml, statics::{assemble_unloaded, compliance, Settings}};
/// // A sprung arm (k = 2 N·m/rad): its tip, 0.1 m out, yields l²/k sideways.
/// let m = from_toml("[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n").unwrap();
/// let s = assemble_unloaded(&m, &Settings::default()).unwrap();
/// let c = compliance(&m, &s, m.body("arm").unwrap(), [0.1, 0.0].into()).unwrap();
/// assert!((c[(0, 0)] - 0.5).abs() < 1e-15 && (c[(2, 2)] - 0.005).abs() < 1e-15);
/// ```
pub fn compliance<D: Statics>(m: &Mechanism<D>, s: &Solution<D>, body: usize, at: D::Point) -> Result<D::Compliance> {
    if body >= m.bodies.len() {
        return Err(Error::invalid("body", body, "names no body of the mechanism"));
    }
    if !D::point_finite(&at) {
        return Err(Error::invalid("at", format!("{at:?}"), "must be finite"));
    }
    let (z, k) = stiffness(m, s)?;
    let jz = point_jacobian(m, &s.q, body, at) * &z;
    let c = if D::DEAD_MOMENTS {
        // Not symmetrized: under a dead moment the tangent stiffness is not symmetric, nor is the compliance.
        let solved = k.lu().solve(&jz.transpose()).filter(|x| x.iter().all(|v| v.is_finite())).ok_or_else(|| {
            Error::Singular {
                what: "mechanism compliance: the constrained stiffness is singular (a free motion)".into(),
            }
        })?;
        &jz * solved
    } else {
        let not_definite = || Error::Singular {
            what: "the constrained stiffness is not positive definite: the equilibrium is unstable or a joint is free"
                .into(),
        };
        if !linalg::is_positive_definite(&k) {
            return Err(not_definite());
        }
        let chol = k.cholesky().ok_or_else(not_definite)?;
        let c = &jz * chol.solve(&jz.transpose());
        if !c.iter().all(|v| v.is_finite()) {
            return Err(Error::Singular { what: "the compliance is not finite".into() });
        }
        c
    };
    Ok(D::compliance_matrix(&c))
}

/// The Jacobian of the frame at `at` on `body` at `q`, rows in the order of
/// the wrench: the body's rotation ($\phi$, or $\delta\theta$), then the point's displacement.
fn point_jacobian<D: Statics>(m: &Mechanism<D>, q: &[f64], body: usize, at: D::Point) -> DMatrix<f64> {
    let mut f = Frames::new(m);
    frames_level_into(m, q, Level::Jacobian, &mut f);
    attach(m, &f, body, D::translation(&D::at(&at)), true).jacobian
}
