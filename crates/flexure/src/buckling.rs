//! CriticalLoad of a flexure in compression under tip constraints (paper Sec. IV-D, Eqs. 39–44).

use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::kinematics::{self, Kinematics, Level};
use nalgebra::{DMatrix, DVector};
use std::str::FromStr;

/// How the tip is held while the compressive load acts along the root's $-x$.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TipConstraint {
    /// Tip free to translate and rotate.
    Free,
    /// Tip may not rotate: $\delta\phi = 0$ (Eq. 42).
    Guided,
    /// Tip may not move sideways: $\delta y = 0$ (Eq. 44).
    Pinned,
    /// Both: $\delta\phi = \delta y = 0$ (Eq. 43).
    Clamped,
}

impl TipConstraint {
    /// All four, in the order of Table I.
    pub const ALL: [TipConstraint; 4] = [Self::Free, Self::Guided, Self::Pinned, Self::Clamped];

    /// The lower-case name used by the CLI.
    pub fn name(self) -> &'static str {
        match self {
            Self::Free => "free",
            Self::Guided => "guided",
            Self::Pinned => "pinned",
            Self::Clamped => "clamped",
        }
    }

    /// Rows of the tip Jacobian that the constraint holds fixed: 0 = φ, 2 = y.
    fn held_rows(self) -> &'static [usize] {
        match self {
            Self::Free => &[],
            Self::Guided => &[0],
            Self::Pinned => &[2],
            Self::Clamped => &[0, 2],
        }
    }
}

impl FromStr for TipConstraint {
    type Err = crate::Error;
    fn from_str(s: &str) -> Result<Self> {
        Self::ALL
            .into_iter()
            .find(|t| t.name() == s)
            .ok_or_else(|| Error::invalid("tip", format!("{s:?}"), "must be one of free, guided, pinned, clamped"))
    }
}

/// The critical load and its mode (the mode serialized as a list).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CriticalLoad {
    /// Smallest compressive tip load $P$ (N) at which the constrained stiffness is singular.
    pub critical_load: f64,
    /// CriticalLoad mode in joint coordinates, unit length, largest entry positive.
    #[serde(serialize_with = "as_list")]
    pub mode: DVector<f64>,
}

/// A vector as a plain list of numbers.
fn as_list<S: serde::Serializer>(v: &DVector<f64>, s: S) -> std::result::Result<S::Ok, S::Error> {
    s.collect_seq(v.iter())
}

/// Smallest positive $P$ with $\det\big(Z^T(\nabla\nabla U + P\thinspace\nabla\nabla x)Z\big) = 0$,
/// where the columns of $Z$ span the perturbations $\delta\alpha$ the tip
/// constraint admits (Eqs. 39–44, with $L P$ for $L P_{crit}$ per the errata).
///
/// The constraint rows are the tip Jacobian's $\phi$ and/or $y$ rows at the
/// rest shape, so they hold for any order (for the shifted-Legendre basis,
/// $\partial y/\partial\alpha = L(1/2, -1/6, 0, \dots)$: pinned is
/// $\alpha_2 = 3\alpha_1$ for every $N \ge 2$). It is solved as the
/// generalized symmetric eigenproblem $B v = \mu A v$, $A = Z^T\nabla\nabla U Z$,
/// $B = -Z^T\nabla\nabla x Z$, $P = 1/\mu_{\max}$; $A$ is always positive
/// definite, so this holds even where $B$ is singular. For a pre-curved rest shape
/// this is the linearized (eigenvalue) buckling load about that shape.
///
/// # Example
/// ```
/// use flexure::{buckling_load, Flexure, TipConstraint};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // Table I: guided, 10 EI/L² for N = 3.
/// let b = buckling_load(&f, TipConstraint::Guided).unwrap();
/// assert!((b.critical_load - 10.0).abs() < 1e-9);
/// ```
pub fn buckling_load(flexure: &Flexure, tip: TipConstraint) -> Result<CriticalLoad> {
    let n = flexure.order();
    let mut k = Kinematics::new(flexure);
    kinematics::update(flexure, flexure.rest(), &mut k, Level::Hessian);
    let z = admissible_basis(&k.jacobian_root_tip, tip.held_rows(), n);
    if z.ncols() == 0 {
        return Err(Error::Singular {
            what: format!("a {} tip leaves an order-{n} flexure no freedom to buckle; use a higher order", tip.name()),
        });
    }
    let d = DMatrix::from_row_slice(n, n, flexure.stiffness_matrix());
    let a = z.transpose() * d * &z;
    let b = -(z.transpose() * &k.hessian_root_tip_x * &z);
    let (mus, modes) = crate::linalg::generalized_symmetric(&a, &b)
        .ok_or_else(|| Error::Singular { what: "energy Hessian not positive definite".into() })?;
    // nalgebra returns eigenvalues unsorted: the largest 1/P is the smallest P.
    let (best, &mu) = mus
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .ok_or_else(|| Error::Singular { what: "empty eigenproblem".into() })?;
    if mu.is_nan() || mu <= 0.0 {
        return Err(Error::Singular {
            what: format!("no compressive load buckles this flexure with a {} tip", tip.name()),
        });
    }
    let mode = normalized(z * modes.column(best));
    Ok(CriticalLoad { critical_load: 1.0 / mu, mode })
}

/// Orthonormal basis of $\lbrace\delta\alpha : J_r\thinspace\delta\alpha = 0\ \forall r \in \text{rows}\rbrace$.
fn admissible_basis(jacobian: &DMatrix<f64>, rows: &[usize], n: usize) -> DMatrix<f64> {
    let g = DMatrix::from_fn(rows.len(), n, |r, c| jacobian[(rows[r], c)]);
    crate::linalg::null_space(&g)
}

/// A mode scaled to unit length with its largest entry positive.
pub(crate) fn normalized(mut mode: DVector<f64>) -> DVector<f64> {
    mode /= mode.norm();
    if mode.iter().copied().fold(0.0_f64, |m, x| if x.abs() > m.abs() { x } else { m }) < 0.0 {
        mode = -mode;
    }
    mode
}
