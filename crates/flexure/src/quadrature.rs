//! Gauss–Legendre quadrature on $[0, 1]$ (paper Eqs. 14–15, Appendix).

use crate::error::{Error, Result};
use std::num::NonZeroUsize;

/// The most points a rule may have. 1024 points integrate $\cos\phi$
/// exactly to rounding for cross-sections turning by up to about 1500 rad,
/// far beyond any flexure; the kernel's tables grow as $N^2Q$, and at
/// $N = 64$, $Q = 1024$ they take 17 MB.
pub const MAX_POINTS: usize = 1024;

/// Nodes $t_k \in (0, 1)$ and weights $\Delta_k$ with $\sum_k \Delta_k = 1$.
#[derive(Debug, Clone, PartialEq)]
pub struct GaussLegendre {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl GaussLegendre {
    /// The `points`-point rule, exact for polynomials of degree $2Q - 1$.
    ///
    /// # Example
    /// ```
    /// let q = flexure::quadrature::GaussLegendre::new(5).unwrap();
    /// // The Appendix's first weight and node.
    /// assert!((q.weights()[0] - 0.118463442528095).abs() < 1e-14);
    /// assert!((q.nodes()[0] - 0.046910077030668).abs() < 1e-14);
    /// ```
    pub fn new(points: usize) -> Result<Self> {
        crate::error::count("quadrature", points, MAX_POINTS, "must be from 1 to 1024 points")?;
        let count = NonZeroUsize::new(points)
            .ok_or_else(|| Error::invalid("quadrature", points, "must be at least 1 point"))?;
        let rule = gauss_quad::GaussLegendre::new(count);
        let mut pairs: Vec<(f64, f64)> =
            rule.nodes().zip(rule.weights()).map(|(x, w)| (0.5 * (x + 1.0), 0.5 * w)).collect();
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        Ok(Self { nodes: pairs.iter().map(|p| p.0).collect(), weights: pairs.iter().map(|p| p.1).collect() })
    }

    /// The default number of points for a model of order `order`: $N + 2$.
    ///
    /// The geometric (load) stiffness of a straight flexure is
    /// $-L\int_0^1 \psi_i\psi_j\thinspace dt$, a polynomial of degree $2N$; the rule
    /// must integrate it exactly or the buckling eigenproblem loses rank (at
    /// $N = 6$, 5 points give a rank-5 matrix). $Q = N + 1$ is the least that
    /// does; one more point absorbs the non-polynomial $\cos\phi$ of bent
    /// shapes, and $N = 3$ gives the paper's five points.
    pub fn default_points(order: usize) -> usize {
        order.saturating_add(2)
    }

    /// Nodes on $[0, 1]$, increasing.
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// Weights, summing to one.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Always false: a rule has at least one point.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }
}

/// The deepest an adaptive piece is halved: $2^{-40}$ of the flexure,
/// below rounding of $t$.
const MAX_DEPTH: u32 = 40;

/// The most pieces an adaptive integral visits before it reports failure.
const MAX_PIECES: usize = 200_000;

/// Pieces narrower than this share of $[0, 1]$ are held to the error
/// budget of one this wide, so that a square-root endpoint (a notch cut
/// to the flexure's end) converges; with at most [`MAX_PIECES`] pieces, the
/// total stays below $0.2\thinspace\varepsilon$.
const FLOOR: f64 = 1.0 / 1_048_576.0;

/// $\int_0^1 f(t)\thinspace dt$ of a vector-valued `f` (which writes
/// `dim` values), split at `breaks` (increasing, inside $(0, 1)$).
///
/// With `exact`, each piece takes one `points`-point Gauss–Legendre rule
/// (exact when $f$ is a polynomial of degree below $2Q$ there). Otherwise a
/// piece is halved until its halves agree with it to `relative` of the
/// largest entry of the whole integral times its width (at least $2^{-20}$),
/// at most 40 halvings deep and 200 000 pieces in all; beyond that it
/// fails, saying what was reached.
///
/// # Example
/// ```
/// use flexure::quadrature::integrate;
/// // ∫ 1/(1 + 100 t²) dt = atan(10)/10.
/// let v = integrate(&[], 8, false, 1e-13, 1, |t, out| out[0] = 1.0 / (1.0 + 100.0 * t * t)).unwrap();
/// assert!((v[0] - 10f64.atan() / 10.0).abs() < 1e-13);
/// ```
pub fn integrate(
    breaks: &[f64],
    points: usize,
    exact: bool,
    relative: f64,
    dim: usize,
    mut f: impl FnMut(f64, &mut [f64]),
) -> Result<Vec<f64>> {
    let rule = GaussLegendre::new(points)?;
    let mut value = vec![0.0; dim];
    let mut piece = |a: f64, b: f64, out: &mut [f64]| {
        out.fill(0.0);
        for (&t, &w) in rule.nodes().iter().zip(rule.weights()) {
            f(a + t * (b - a), &mut value);
            for (o, v) in out.iter_mut().zip(&value) {
                *o += w * (b - a) * v;
            }
        }
    };
    let ends: Vec<f64> = std::iter::once(0.0).chain(breaks.iter().copied()).chain(std::iter::once(1.0)).collect();
    let mut stack: Vec<(f64, f64, u32, Vec<f64>)> = Vec::new();
    let mut total = vec![0.0; dim];
    for w in ends.windows(2) {
        let mut whole = vec![0.0; dim];
        piece(w[0], w[1], &mut whole);
        total.iter_mut().zip(&whole).for_each(|(t, v)| *t += v);
        stack.push((w[0], w[1], 0, whole));
    }
    if exact {
        return Ok(total);
    }
    let scale = total.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut result = vec![0.0; dim];
    let (mut left, mut right) = (vec![0.0; dim], vec![0.0; dim]);
    let mut visited = 0;
    while let Some((a, b, depth, whole)) = stack.pop() {
        visited += 1;
        let mid = 0.5 * (a + b);
        piece(a, mid, &mut left);
        piece(mid, b, &mut right);
        let error = whole.iter().zip(left.iter().zip(&right)).fold(0.0_f64, |m, (w, (l, r))| m.max((w - l - r).abs()));
        if !error.is_finite() {
            return Err(Error::Singular { what: format!("the integrand is not finite near t = {mid:.6}") });
        }
        let budget = relative * scale * (b - a).max(FLOOR);
        if error <= budget || depth >= MAX_DEPTH {
            if error > budget {
                return Err(Error::Singular {
                    what: format!(
                        "an integral along the flexure did not converge near t = {mid:.6} after {MAX_DEPTH} halvings (error {error:.3e} of {scale:.3e})"
                    ),
                });
            }
            result.iter_mut().zip(left.iter().zip(&right)).for_each(|(o, (l, r))| *o += l + r);
        } else if visited + stack.len() >= MAX_PIECES {
            return Err(Error::Singular {
                what: format!(
                    "an integral along the flexure needed more than {MAX_PIECES} pieces (reached t = {a:.6})"
                ),
            });
        } else {
            stack.push((a, mid, depth + 1, left.clone()));
            stack.push((mid, b, depth + 1, right.clone()));
        }
    }
    Ok(result)
}
