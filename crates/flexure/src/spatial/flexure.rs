//! The spatial flexure's model: length, section, orders, rest shape and
//! the tables every evaluation shares.

use crate::basis;
use crate::error::{Error, Result};
use crate::flexure::{EI_RANGE, LENGTH_RANGE, MAX_COORDINATE, MAX_ORDER};
use crate::section::{Outline, SpatialSection};

/// The fewest Magnus subintervals $M$ a flexure gets by default
/// ([`SpatialFlexure::default_subintervals`] raises it with the order). With
/// 6th-order Magnus the tip pose's error falls as $M^{-6}$. At 8 subintervals
/// and order 3 per component (`tests/spatial_kinematics.rs` measures it) it
/// is $7\times10^{-11}L$ for coefficients up to 0.3 rad, $6\times10^{-10}L$
/// up to 0.55 rad and $9\times10^{-9}L$ at about a radian each (tip
/// rotations of 0.7–1.1 rad per component, curvature varying along the
/// length); the planar model's default 5-point rule is $10^{-7}L$ from its
/// converged answer at such a shape. 16 subintervals take the last to
/// $1.5\times10^{-10}L$ at twice the cost ([`SpatialFlexure::with_subintervals`]).
/// The cost is linear in $M$: at 8, order 3, a pose took 340 ns, 8.7 times
/// the planar `joint/pose` (the least of 200 interleaved runs of 1000 poses
/// each, on a loaded machine; criterion's `spatial/pose` there).
pub const DEFAULT_SUBINTERVALS: usize = 8;

/// The most subintervals: 4096 take the pose's error to rounding for
/// rotations of hundreds of radians.
pub const MAX_SUBINTERVALS: usize = 4096;

/// An immutable spatial flexure (the Model): length $L$, a
/// [`SpatialSection`] of stiffnesses $(GJ, EI_y, EI_z)$, orders
/// $[n_\tau, n_y, n_z]$, rest coefficients $\kappa$ and the number of
/// Magnus subintervals.
///
/// Its energy about the rest shape is
/// $$U = \tfrac12\int_0^L \big(GJ\thinspace(\tau-\tau_0)^2 + EI_y(\kappa_y-\kappa_{y0})^2 + EI_z(\kappa_z-\kappa_{z0})^2\big)\thinspace ds = \tfrac12(\alpha-\kappa)^TK(\alpha-\kappa),$$
/// with $K$ block diagonal, one Gram matrix per component,
/// $$K^{(c)}_{ij} = \frac1L\int_0^1 k_c(t)\thinspace\tilde P_i(t)\tilde P_j(t)\thinspace dt,$$
/// where $k_c$ is $GJ$, $EI_y$ or $EI_z$. The stiffnesses are piecewise
/// linear in $t$, so Gauss–Legendre with $\max n_c + 1$ points on each piece
/// between the section's breakpoints integrates $K$ exactly; for a uniform
/// section it is diagonal, $\frac{k_c}{L}\frac1{2i+1}$ (Eq. 28 as corrected,
/// per component).
///
/// # Example
/// ```
/// use flexure::section::SpatialSection;
/// use flexure::spatial::SpatialFlexure;
/// let s = SpatialSection::uniform(0.5, 2.0, 1.0).unwrap();
/// let f = SpatialFlexure::new(2.0, s, [3, 3, 3]).unwrap();
/// assert_eq!(f.coordinates(), 9);
/// let k = f.stiffness_matrix();
/// // GJ/L for the first twist coefficient, EI_z/(3L) for the second κ_z one.
/// assert!((k[0] - 0.25).abs() < 1e-15 && (k[7 * 9 + 7] - 1.0 / 6.0).abs() < 1e-15);
/// assert!(SpatialFlexure::new(2.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 0, 3]).is_err());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialFlexure {
    length: f64,
    section: SpatialSection,
    orders: [usize; 3],
    rest: Vec<f64>,
    stiffness: Vec<f64>,
    subintervals: usize,
    /// `shapes[(k * 2 + j) * width + i]` = $\tilde P_i(t_{kj})/L$ at the Gauss
    /// node $j$ of subinterval $k$, for $i$ below the largest order `width`.
    shapes: Vec<f64>,
}

impl SpatialFlexure {
    /// A straight flexure of `length` (m), `section` and `orders`
    /// $[n_\tau, n_y, n_z]$ (each from 1 to 64), with
    /// [`SpatialFlexure::default_subintervals`] of its orders. Errors name
    /// `length`, `order`, `thickness` or `diameter` (a section thicker than
    /// the flexure is long, refused as the planar flexure refuses it:
    /// [`thinner_than_long`](crate::section::thinner_than_long)), `gj`,
    /// `ei_y` or `ei_z`.
    pub fn new(length: f64, section: SpatialSection, orders: [usize; 3]) -> Result<Self> {
        if !(length.is_finite() && (LENGTH_RANGE.0..=LENGTH_RANGE.1).contains(&length)) {
            return Err(Error::invalid("length", length, "must lie in [1e-9, 1e6] m"));
        }
        for n in orders {
            if !(1..=MAX_ORDER).contains(&n) {
                return Err(Error::invalid(
                    "order",
                    format!("{orders:?}"),
                    "each component's order must be from 1 to 64",
                ));
            }
        }
        let names = ["gj", "ei_y", "ei_z"];
        let mut at: Vec<f64> = vec![0.0, 1.0];
        at.extend(section.breakpoints());
        // As the planar flexure: no section thicker than the flexure is long
        // (a rectangle's thickness along y or a rod's diameter; the width is
        // a wide blade's, as in the plane).
        let thickness = at.iter().filter_map(|&t| match section.outline(t)? {
            Outline::Rectangle { thickness, .. } => Some((t, thickness)),
            Outline::Circle { diameter } => Some((t, diameter)),
        });
        let name = match section.outline(0.0) {
            Some(Outline::Circle { .. }) => "diameter",
            _ => "thickness",
        };
        crate::section::thinner_than_long(name, length, thickness)?;
        for &t in &at {
            for (k, name) in section.stiffness(t).into_iter().zip(names) {
                if !(k.is_finite() && (EI_RANGE.0..=EI_RANGE.1).contains(&k)) {
                    return Err(Error::invalid(
                        name,
                        format!("{k:e} N·m² at t = {t}"),
                        "must lie in [1e-30, 1e15] N·m²",
                    ));
                }
            }
        }
        let n: usize = orders.iter().sum();
        let stiffness = gram(length, &section, orders)?;
        let mut f = Self { length, section, orders, rest: vec![0.0; n], stiffness, subintervals: 0, shapes: vec![] };
        f.set_subintervals(Self::default_subintervals(orders));
        Ok(f)
    }

    /// The same flexure with rest coefficients $\kappa$, one per coordinate
    /// (twist's, then $\kappa_y$'s, then $\kappa_z$'s); errors name `rest`.
    ///
    /// # Example
    /// ```
    /// use flexure::{section::SpatialSection, spatial::SpatialFlexure};
    /// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [1, 1, 2]).unwrap();
    /// assert!(f.clone().with_rest(&[0.0, 0.0, 0.5, 0.0]).is_ok());
    /// assert!(f.with_rest(&[0.0; 3]).is_err());
    /// ```
    pub fn with_rest(mut self, rest: &[f64]) -> Result<Self> {
        if rest.len() != self.coordinates() {
            return Err(Error::invalid(
                "rest",
                format!("{} values", rest.len()),
                "must have one value per coordinate (n_tau + n_y + n_z)",
            ));
        }
        for &k in rest {
            if !(k.is_finite() && k.abs() <= MAX_COORDINATE) {
                return Err(Error::invalid("rest", k, "must be a finite number of magnitude at most 1e6 rad"));
            }
        }
        self.rest = rest.to_vec();
        Ok(self)
    }

    /// The same flexure with its own mass from a `density` (kg/m³) and its
    /// section's geometry ([`SpatialSection::with_density`]); errors name `density`.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, SpatialSection};
    /// use flexure::spatial::SpatialFlexure;
    /// let s = SpatialSection::circle(200e9, 0.3, Profile::Constant(1e-3)).unwrap();
    /// let f = SpatialFlexure::new(0.1, s, [3, 3, 3]).unwrap().with_density(7850.0).unwrap();
    /// assert!(f.section().has_mass());
    /// ```
    pub fn with_density(mut self, density: f64) -> Result<Self> {
        self.section = self.section.with_density(density)?;
        Ok(self)
    }

    /// The same flexure with its own mass per length $\mu(t)$ (kg/m)
    /// ([`SpatialSection::with_mass_per_length`]); errors name `mass_per_length`.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, SpatialSection};
    /// use flexure::spatial::SpatialFlexure;
    /// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [2, 2, 2]).unwrap();
    /// let f = f.with_mass_per_length(Profile::Constant(0.5)).unwrap();
    /// assert_eq!(f.section().mass_per_length(0.2), Some(0.5));
    /// ```
    pub fn with_mass_per_length(mut self, mass_per_length: crate::section::Profile) -> Result<Self> {
        self.section = self.section.with_mass_per_length(mass_per_length)?;
        Ok(self)
    }

    /// The same flexure with its rotary inertia per length given directly
    /// (kg·m, twist then bending about $y$ and $z$;
    /// [`SpatialSection::with_rotary_inertia_per_length`]), after its mass
    /// per length; errors name `rotary_inertia_per_length`.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, SpatialSection};
    /// use flexure::spatial::SpatialFlexure;
    /// let f = SpatialFlexure::new(10.0, SpatialSection::uniform(1e3, 1e3, 1e3).unwrap(), [4, 4, 4]).unwrap();
    /// let f = f.with_mass_per_length(Profile::Constant(1.0)).unwrap().with_rotary_inertia_per_length([20.0, 10.0, 10.0]).unwrap();
    /// assert_eq!(f.section().rotary_inertia_per_length(0.5), Some([20.0, 10.0, 10.0]));
    /// ```
    pub fn with_rotary_inertia_per_length(mut self, rotary: [f64; 3]) -> Result<Self> {
        self.section = self.section.with_rotary_inertia_per_length(rotary)?;
        Ok(self)
    }

    /// The default number of Magnus subintervals for `orders`,
    /// $$M = \max\big(8,\thinspace 4(n - 1),\thinspace \lfloor n(n - 1)/4\rfloor\big),\qquad n = \max(n_\tau, n_y, n_z)$$
    /// (at most [`MAX_SUBINTERVALS`]): 8 ([`DEFAULT_SUBINTERVALS`]) up to
    /// orders 3, then four more per order, and from orders 16 on a quarter
    /// of $n(n-1)$, so that the discretization error stays well below the
    /// truncation error of the order. The highest shifted Legendre
    /// polynomial $\tilde P_{n-1}$ oscillates $n - 1$ times along the
    /// length, and both the Magnus steps and the statics' Gauss quadrature
    /// of the generalized force resolve it only with a few subintervals per
    /// oscillation: at 8 subintervals orders 10 and 12 put the
    /// Bathe–Bolourchi tip $2.6\times10^{-7}L$ and $1.1\times10^{-5}L$ from
    /// the exact rod, worse than order 8's $2.7\times10^{-8}L$. Measured
    /// against the same order at 256 subintervals, on the Bathe–Bolourchi
    /// bend and four random 3-D tip wrenches turning the tip by about a
    /// radian (VALIDATION.md, *Spatial: the model against the rod*), this
    /// $M$ keeps the discretization error below a tenth of the truncation
    /// error wherever that exceeds $10^{-9}L$ (at most 7 %), and below
    /// $5\times10^{-11}L$ where the truncation error is smaller (orders 9 and
    /// up there, where the total error is then at most $1.5\times10^{-11}L$
    /// at about a radian); the same holds with the loads tripled (about 3 rad
    /// of turning; measured up to orders 16). With $4n$ instead the
    /// discretization error is 2–3 times smaller, at 1.5 times the cost for
    /// orders 3. Beyond orders 16, $4(n-1)$ left the Bathe–Bolourchi tip
    /// $2\times10^{-12}$–$1.5\times10^{-9}L$ off at orders 20–40, all of it
    /// discretization; $n(n-1)/4$ takes it to $2\times10^{-13}L$ or less. [`crate::estimate::spatial::deflect_auto`]
    /// picks the fewest subintervals that meet an accuracy target instead.
    ///
    /// # Example
    /// ```
    /// use flexure::{section::SpatialSection, spatial::SpatialFlexure};
    /// assert_eq!(SpatialFlexure::default_subintervals([3, 3, 3]), 8);
    /// assert_eq!(SpatialFlexure::default_subintervals([2, 12, 4]), 44);
    /// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [10, 10, 10]).unwrap();
    /// assert_eq!(f.subintervals(), 36);
    /// assert_eq!(f.with_subintervals(8).unwrap().subintervals(), 8);
    /// assert_eq!(SpatialFlexure::default_subintervals([32, 1, 1]), 248);
    /// ```
    pub fn default_subintervals(orders: [usize; 3]) -> usize {
        let n = orders.iter().copied().max().unwrap_or(1);
        let n1 = n.saturating_sub(1);
        (4 * n1).max(n * n1 / 4).clamp(DEFAULT_SUBINTERVALS, MAX_SUBINTERVALS)
    }

    /// The same flexure integrated over `subintervals` Magnus steps (1 to
    /// [`MAX_SUBINTERVALS`]); errors name `subintervals`.
    pub fn with_subintervals(mut self, subintervals: usize) -> Result<Self> {
        if !(1..=MAX_SUBINTERVALS).contains(&subintervals) {
            return Err(Error::invalid("subintervals", subintervals, "must be from 1 to 4096"));
        }
        self.set_subintervals(subintervals);
        Ok(self)
    }

    fn set_subintervals(&mut self, m: usize) {
        let width = self.width();
        let mut p = vec![0.0; width];
        self.shapes = Vec::with_capacity(3 * m * width);
        for k in 0..m {
            for t in super::magnus::NODES {
                basis::shifted_legendre((k as f64 + t) / m as f64, &mut p);
                self.shapes.extend(p.iter().map(|v| v / self.length));
            }
        }
        self.subintervals = m;
    }

    /// The largest of the three orders: the width of a row of the shape table.
    #[inline]
    pub(crate) fn width(&self) -> usize {
        self.orders.iter().copied().max().unwrap_or(0)
    }

    /// $\tilde P_i(t)/L$ at the three Gauss nodes of subinterval `k`: three rows of [`SpatialFlexure::width`].
    #[inline]
    pub(crate) fn shapes(&self, k: usize) -> &[f64] {
        let w = self.width();
        &self.shapes[3 * k * w..3 * (k + 1) * w]
    }

    /// Length $L$ (m).
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The section.
    pub fn section(&self) -> &SpatialSection {
        &self.section
    }

    /// Orders $[n_\tau, n_y, n_z]$.
    pub fn orders(&self) -> [usize; 3] {
        self.orders
    }

    /// Number of coordinates $n = n_\tau + n_y + n_z$.
    pub fn coordinates(&self) -> usize {
        self.rest.len()
    }

    /// The curvature component (0 twist, 1 $\kappa_y$, 2 $\kappa_z$) and the
    /// Legendre index of coordinate `a`.
    #[inline]
    pub fn component(&self, a: usize) -> (usize, usize) {
        let [n0, n1, _] = self.orders;
        if a < n0 {
            (0, a)
        } else if a < n0 + n1 {
            (1, a - n0)
        } else {
            (2, a - n0 - n1)
        }
    }

    /// Rest coefficients $\kappa$.
    pub fn rest(&self) -> &[f64] {
        &self.rest
    }

    /// Number of Magnus subintervals $M$.
    pub fn subintervals(&self) -> usize {
        self.subintervals
    }

    /// The stiffness matrix $K$ (row-major $n\times n$, symmetric, block
    /// diagonal): $U = \frac12(\alpha-\kappa)^TK(\alpha-\kappa)$, N·m/rad².
    #[inline]
    pub fn stiffness_matrix(&self) -> &[f64] {
        &self.stiffness
    }

    /// The body-frame curvature $u(s) = (\tau, \kappa_y, \kappa_z)$ (1/m)
    /// of coordinates `alpha` at arc length `s`.
    ///
    /// # Example
    /// ```
    /// use flexure::{section::SpatialSection, spatial::SpatialFlexure};
    /// let f = SpatialFlexure::new(2.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [1, 1, 2]).unwrap();
    /// // κ_z = (1/L)(0.4 + 0.2·P̃₁(s/L)); at s = L it is (0.4 + 0.2)/2.
    /// let u = f.curvature(&[0.1, 0.0, 0.4, 0.2], 2.0);
    /// assert!((u[0] - 0.05).abs() < 1e-15 && u[1] == 0.0 && (u[2] - 0.3).abs() < 1e-15);
    /// ```
    ///
    /// # Panics
    /// If `alpha` does not have [`SpatialFlexure::coordinates`] entries.
    pub fn curvature(&self, alpha: &[f64], s: f64) -> [f64; 3] {
        assert_eq!(alpha.len(), self.coordinates(), "alpha must have one entry per coordinate");
        let mut start = 0;
        std::array::from_fn(|c| {
            let n = self.orders[c];
            let u = basis::curvature(&alpha[start..start + n], self.length, s);
            start += n;
            u
        })
    }

    /// Checks that `alpha` has one finite value per coordinate, of magnitude at most $10^6$.
    ///
    /// # Example
    /// ```
    /// use flexure::{section::SpatialSection, spatial::SpatialFlexure};
    /// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
    /// assert!(f.check_coordinates("alpha", &[0.0; 9]).is_ok());
    /// assert!(f.check_coordinates("alpha", &[0.0; 3]).is_err());
    /// ```
    pub fn check_coordinates<T: crate::Scalar>(&self, name: &'static str, alpha: &[T]) -> Result<()> {
        if alpha.len() != self.coordinates() {
            return Err(Error::invalid(
                name,
                format!("{} values", alpha.len()),
                "must have one value per coordinate (n_tau + n_y + n_z)",
            ));
        }
        for a in alpha {
            if !(a.re().is_finite() && a.re().abs() <= MAX_COORDINATE) {
                return Err(Error::invalid(name, a.re(), "must be a finite number of magnitude at most 1e6 rad"));
            }
        }
        Ok(())
    }
}

/// The block-diagonal Gram matrix $K$ (row-major): diagonal for a uniform
/// section, else Gauss–Legendre with $\max n_c + 1$ points per piece between
/// breakpoints, exact for the piecewise-linear stiffnesses.
fn gram(length: f64, section: &SpatialSection, orders: [usize; 3]) -> Result<Vec<f64>> {
    let n: usize = orders.iter().sum();
    let width = orders.iter().copied().max().unwrap_or(0);
    let mut k = vec![0.0; n * n];
    let offsets = [0, orders[0], orders[0] + orders[1]];
    if section.is_uniform() {
        let s = section.stiffness(0.0);
        for c in 0..3 {
            for i in 0..orders[c] {
                let a = offsets[c] + i;
                k[a * n + a] = s[c] / length * basis::energy_weight(i);
            }
        }
        return Ok(k);
    }
    // Each component's pairs i ≤ j, one after another.
    let pairs: usize = orders.iter().map(|m| m * (m + 1) / 2).sum();
    let mut p = vec![0.0; width];
    let integrand = |t: f64, out: &mut [f64]| {
        basis::shifted_legendre(t, &mut p);
        let s = section.stiffness(t);
        let mut idx = 0;
        for c in 0..3 {
            for i in 0..orders[c] {
                for j in i..orders[c] {
                    out[idx] = s[c] * p[i] * p[j];
                    idx += 1;
                }
            }
        }
    };
    let v = crate::quadrature::integrate(&section.breakpoints(), width + 1, true, 0.0, pairs, integrand)?;
    let mut idx = 0;
    for c in 0..3 {
        for i in 0..orders[c] {
            for j in i..orders[c] {
                let (a, b) = (offsets[c] + i, offsets[c] + j);
                k[a * n + b] = v[idx] / length;
                k[b * n + a] = v[idx] / length;
                idx += 1;
            }
        }
    }
    Ok(k)
}
