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
