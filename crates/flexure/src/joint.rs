//! The flexure joint model: geometry, stiffness, rest shape and precomputed tables.

use crate::basis;
use crate::error::{Error, Result, finite, positive};
use crate::quadrature::GaussLegendre;

/// Bending stiffness $EI = \frac{E}{1-\nu^2}\,\frac{b h^3}{12}$ of a
/// rectangular section (Eq. 25); without `poisson`, $EI = E b h^3 / 12$.
///
/// The $1/(1-\nu^2)$ factor is the plate (wide flexure) modulus.
///
/// # Example
/// ```
/// // The paper's steel flexure, Eq. 25 (errata: 1.4558e-3 N·m²).
/// let ei = flexure::bending_stiffness(200e9, 0.01, 0.0002, Some(0.29)).unwrap();
/// assert!((ei - 1.4558e-3).abs() < 1e-7);
/// ```
pub fn bending_stiffness(modulus: f64, width: f64, thickness: f64, poisson: Option<f64>) -> Result<f64> {
    let e = positive("modulus", modulus)?;
    let b = positive("width", width)?;
    let h = positive("thickness", thickness)?;
    let plate = match poisson {
        None => 1.0,
        Some(nu) => {
            if !(nu.is_finite() && nu > -1.0 && nu <= 0.5) {
                return Err(Error::invalid("poisson", nu, "must lie in (-1, 0.5]"));
            }
            1.0 / (1.0 - nu * nu)
        }
    };
    positive("ei", e * plate * b * h.powi(3) / 12.0)
}

/// An immutable planar flexure joint of order $N$ (the Model).
///
/// Holds length $L$, stiffness $EI$, rest coefficients $\kappa$ (Eq. 5) and
/// the quadrature tables shared by every evaluation. Build it with
/// [`Flexure::new`] and the `with_*` methods; all input is validated there.
#[derive(Debug, Clone, PartialEq)]
pub struct Flexure {
    length: f64,
    ei: f64,
    kappa: Vec<f64>,
    rule: GaussLegendre,
    /// `psi[k * n + i]` = $\psi_i(t_k)$: angle shapes at the nodes.
    psi: Vec<f64>,
    /// `weights[k]` = $L\Delta_k$.
    weights: Vec<f64>,
}

impl Flexure {
    /// A straight flexure of `length` and stiffness `ei`, order `order`, with
    /// the default quadrature ([`GaussLegendre::default_points`]).
    ///
    /// # Example
    /// ```
    /// let f = flexure::Flexure::new(0.015, 1.4558e-3, 3).unwrap();
    /// assert_eq!(f.quadrature_points(), 5);
    /// assert!(flexure::Flexure::new(-1.0, 1.0, 3).is_err());
    /// ```
    pub fn new(length: f64, ei: f64, order: usize) -> Result<Self> {
        let length = positive("length", length)?;
        let ei = positive("ei", ei)?;
        if order == 0 {
            return Err(Error::invalid("order", order, "must be at least 1"));
        }
        let mut f =
            Self { length, ei, kappa: vec![0.0; order], rule: GaussLegendre::new(1)?, psi: vec![], weights: vec![] };
        f.set_rule(GaussLegendre::new(GaussLegendre::default_points(order))?);
        Ok(f)
    }

    /// The same flexure with rest curvature coefficients $\kappa$ (Eq. 5).
    pub fn with_rest(mut self, kappa: &[f64]) -> Result<Self> {
        if kappa.len() != self.order() {
            return Err(Error::invalid("kappa", format!("{} values", kappa.len()), "must have one value per order"));
        }
        for &k in kappa {
            finite("kappa", k)?;
        }
        self.kappa = kappa.to_vec();
        Ok(self)
    }

    /// The same flexure with a `points`-point Gauss–Legendre rule.
    pub fn with_quadrature(mut self, points: usize) -> Result<Self> {
        self.set_rule(GaussLegendre::new(points)?);
        Ok(self)
    }

    fn set_rule(&mut self, rule: GaussLegendre) {
        let n = self.order();
        self.psi = vec![0.0; rule.len() * n];
        for (row, &t) in self.psi.chunks_exact_mut(n).zip(rule.nodes()) {
            basis::angle_shapes(t, row);
        }
        self.weights = rule.weights().iter().map(|w| w * self.length).collect();
        self.rule = rule;
    }

    /// Length $L$ in metres.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Bending stiffness $EI$ in N·m².
    pub fn ei(&self) -> f64 {
        self.ei
    }

    /// Order $N$: the number of curvature coefficients.
    pub fn order(&self) -> usize {
        self.kappa.len()
    }

    /// Rest coefficients $\kappa$.
    pub fn rest(&self) -> &[f64] {
        &self.kappa
    }

    /// Number of quadrature points $Q$.
    pub fn quadrature_points(&self) -> usize {
        self.rule.len()
    }

    /// The quadrature rule on $[0, 1]$.
    pub fn quadrature(&self) -> &GaussLegendre {
        &self.rule
    }

    /// Rows $\psi_i(t_k)$, one per node.
    pub(crate) fn psi_rows(&self) -> std::slice::ChunksExact<'_, f64> {
        self.psi.chunks_exact(self.order())
    }

    /// Scaled weights $L\Delta_k$.
    pub(crate) fn scaled_weights(&self) -> &[f64] {
        &self.weights
    }

    /// Checks that `alpha` has one finite value per order.
    pub fn check_coordinates(&self, name: &'static str, alpha: &[f64]) -> Result<()> {
        if alpha.len() != self.order() {
            return Err(Error::invalid(name, format!("{} values", alpha.len()), "must have one value per order"));
        }
        for &a in alpha {
            finite(name, a)?;
        }
        Ok(())
    }
}
