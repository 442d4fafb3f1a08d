//! The flexure joint model of the Smooth Curvature Model: geometry,
//! stiffness, rest shape and precomputed tables ([`Flexure`]), and the
//! flexure as a front end gives it ([`FlexureSpec`]).

mod spec;

use crate::section::within;
pub use crate::section::{EI_RANGE, bending_stiffness};
pub use spec::FlexureSpec;

use crate::basis;
use crate::error::{Error, Result};
use crate::quadrature::GaussLegendre;
use crate::section::Section;

/// Lengths a flexure may have (m): a nanometre to a thousand kilometres.
/// With [`EI_RANGE`] every derived scale ($EI/L$, $L^3/EI$, energies at
/// [`MAX_COORDINATE`]) stays far inside the range of `f64`, so no answer
/// overflows to infinity or underflows to zero.
pub const LENGTH_RANGE: (f64, f64) = (1e-9, 1e6);

/// The largest magnitude of a coordinate (rad): a flexure wound 160 000
/// times round. Beyond it, angles lose their precision in `f64`.
pub const MAX_COORDINATE: f64 = 1e6;

fn within_magnitude(name: &'static str, v: f64, max: f64) -> Result<f64> {
    if v.is_finite() && v.abs() <= max {
        Ok(v)
    } else {
        Err(Error::invalid(name, v, "must be a finite number of magnitude at most 1e6 rad"))
    }
}

/// The highest order of the Legendre basis. Order 64 resolves curvature
/// to a polynomial of degree 63, far past where the model converges to
/// rounding for any load a flexure survives; beyond it the Hessian tables
/// ($N^2Q/2$ entries) and the $O(N^3)$ solves stop paying for themselves.
///
/// In space the cap is costly, and bounded rather than made cheap: orders
/// [64, 64, 64] are $n = 192$ coordinates on $M = 1008$ Magnus
/// subintervals ([`crate::spatial::SpatialFlexure::default_subintervals`]),
/// and each Newton evaluation's load stiffness costs $O(Mn^2)$. A blade at
/// the cap under a load its orders resolve solves in 0.19 s (criterion's
/// `spatial_mechanism/blade_order_64`, 0.50 of its time before the
/// quadrature became a matrix product and the step tangents were combined
/// from the nodal directions); what needs the exact Hessians ($O(Mn^2)$
/// second derivatives of every Magnus step, 0.49 s each, 0.33 of their
/// time before they too were combined from the nodal directions:
/// `spatial/pose_jacobian_hessian_order_64`), such as `buckle`, `modes`
/// and `simulate`, takes seconds to minutes. A load no order resolves (1e12
/// N on a 30 mm blade: a boundary layer of $\sqrt{EI/F} \approx 10^{-7}$ m)
/// takes every path it needs, each a few hundred evaluations, and each
/// path is stopped past [`crate::solver::Settings::max_evaluations`] with
/// an error that names that bound; lower orders answer such a load sooner
/// and as well.
pub const MAX_ORDER: usize = 64;

/// The most constant-curvature segments in a chain (the paper's finite
/// elements). 64 segments with 5 points each keep the Hessian tables under
/// 6 MB; the paper's comparison needs 22 to 24.
pub const MAX_SEGMENTS: usize = 64;

/// The curvature basis of a joint's coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Basis {
    /// The Smooth Curvature Model: shifted Legendre polynomials (Eq. 8, any
    /// order). $\alpha_1$ is the tip angle.
    Legendre,
    /// The paper's finite-element comparison: $K$ equal segments of constant
    /// curvature; $\alpha_j$ is the rotation across segment $j$, so the
    /// curvature there is $\alpha_j K/L$ and the tip angle is $\sum_j\alpha_j$.
    Segments,
}

/// An immutable planar flexure joint of order $N$ (the Model).
///
/// Holds length $L$, the [`Section`] (stiffness $EI(s)$, thickness, mass),
/// rest coefficients $\kappa$ (Eq. 5) and the tables every evaluation
/// shares. In either [`Basis`] the tangent angle is linear in the
/// coordinates, $\phi(\alpha, s) = \sum_i \alpha_i\psi_i(s/L)$, and so is the
/// curvature, $\hat\omega = \frac1L\sum_i\alpha_i\psi_i^{\prime}(s/L)$; the energy
/// $U = \frac12\int_0^L EI(s)(\hat\omega - \hat\omega_0)^2 ds$ is the quadratic form
/// $U = \frac12(\alpha-\kappa)^T K(\alpha-\kappa)$ with the stiffness matrix
/// $K_{ij} = \frac1L\int_0^1 EI(t)\thinspace\psi_i^{\prime}(t)\psi_j^{\prime}(t)\thinspace dt$, so one
/// kinematics kernel serves both. For a uniform section $K$ is diagonal,
/// $\frac{EI}{L}\mathrm{diag}(1, \frac13, \frac15, \dots)$ (Eq. 28 as corrected). Build it with [`Flexure::new`] (or
/// [`Flexure::segments`]) and the `with_*` methods; all input is validated there.
/// Two flexures are equal when their definitions are (see [`PartialEq`]).
#[derive(Debug, Clone)]
pub struct Flexure {
    length: f64,
    /// Mean bending stiffness $\frac1L\int_0^L EI\thinspace ds$: the scale of loads.
    ei: f64,
    section: Section,
    kappa: Vec<f64>,
    basis: Basis,
    rule: GaussLegendre,
    /// Quadrature nodes $t_k$ on $[0, 1]$ (composite, one rule per segment, for [`Basis::Segments`]).
    nodes: Vec<f64>,
    /// `psi[k * n + i]` = $\psi_i(t_k)$: angle shapes at the nodes.
    psi: Vec<f64>,
    /// `weights[k]` = $L\Delta_k$.
    weights: Vec<f64>,
    /// `jacobian_weights[i * q + k]` = $L\Delta_k\psi_i(t_k)$ (Eqs. 20–21):
    /// node index last, so each Jacobian entry is one dot product over nodes.
    jacobian_weights: Vec<f64>,
    /// $L\Delta_k\psi_i(t_k)\psi_j(t_k)$ (Eqs. 30–31) for the pairs $j \ge i$
    /// in row-major order, a row of $q$ nodes per pair.
    hessian_weights: Vec<f64>,
    /// $K_{ij}$ at `[i * n + j]`: the energy's Hessian.
    stiffness: Vec<f64>,
    /// $\psi_i(1)$: the tip angle is $\sum_i \psi_i(1)\alpha_i$.
    tip_angle: Vec<f64>,
}

/// Equal definitions: length, section (and so $EI$), rest coefficients,
/// basis and quadrature rule. Every table is a function of these, so a
/// derived equality, which would compare the tables too, gives the same
/// answer for more work (workspaces check their flexures on every solve).
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
/// assert_eq!(f, flexure::Flexure::with_points(1.0, 1.0, 3, 5).unwrap());
/// assert_ne!(f, f.clone().with_quadrature(6).unwrap());
/// assert_ne!(f, f.clone().with_rest(&[0.1, 0.0, 0.0]).unwrap());
/// ```
impl PartialEq for Flexure {
    fn eq(&self, other: &Self) -> bool {
        self.length == other.length
            && self.ei == other.ei
            && self.basis == other.basis
            && self.kappa == other.kappa
            && self.rule == other.rule
            && self.section == other.section
    }
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
        Self::with_basis(length, ei, order, Basis::Legendre, GaussLegendre::default_points(order))
    }

    /// A straight flexure of order `order` with a `points`-point rule: the
    /// same as [`Flexure::new`] then [`Flexure::with_quadrature`], building
    /// the tables once.
    ///
    /// # Example
    /// ```
    /// let f = flexure::Flexure::with_points(1.0, 1.0, 6, 20).unwrap();
    /// assert_eq!((f.order(), f.quadrature_points()), (6, 20));
    /// ```
    pub fn with_points(length: f64, ei: f64, order: usize, points: usize) -> Result<Self> {
        Self::with_basis(length, ei, order, Basis::Legendre, points)
    }

    /// A straight chain of `count` constant-curvature segments (the paper's
    /// finite elements, Sec. II-E), integrated with 5 Gauss points per segment.
    ///
    /// # Example
    /// ```
    /// // Three equal bends of 0.5 rad: the tip turns 1.5 rad.
    /// let f = flexure::Flexure::segments(1.0, 1.0, 3).unwrap();
    /// let p = flexure::pose_root_tip(&f, &[0.5, 0.5, 0.5]);
    /// assert!((p.phi - 1.5).abs() < 1e-15 && (p.x - 1.5f64.sin() / 1.5).abs() < 1e-12);
    /// ```
    pub fn segments(length: f64, ei: f64, count: usize) -> Result<Self> {
        Self::with_basis(length, ei, count, Basis::Segments, 5)
    }

    fn with_basis(length: f64, ei: f64, order: usize, basis: Basis, points: usize) -> Result<Self> {
        let length = within("length", length, LENGTH_RANGE)?;
        let ei = within("ei", ei, EI_RANGE)?;
        match basis {
            Basis::Legendre => crate::error::count("order", order, MAX_ORDER, "must be from 1 to 64")?,
            Basis::Segments => crate::error::count("segments", order, MAX_SEGMENTS, "must be from 1 to 64")?,
        };
        let tip_angle = match basis {
            Basis::Legendre => {
                let mut tip = vec![0.0; order];
                tip[0] = 1.0;
                tip
            }
            Basis::Segments => vec![1.0; order],
        };
        let rule = GaussLegendre::new(points)?;
        let mut f = Self {
            length,
            ei,
            section: Section::uniform(ei)?,
            kappa: vec![0.0; order],
            basis,
            rule: rule.clone(),
            nodes: vec![],
            psi: vec![],
            weights: vec![],
            jacobian_weights: vec![],
            hessian_weights: vec![],
            stiffness: vec![],
            tip_angle,
        };
        f.set_rule(rule);
        f.stiffness = f.stiffness_matrix_of(&f.section)?.0;
        Ok(f)
    }

    /// The same flexure with a non-uniform [`Section`]: its $EI(s)$ replaces
    /// the uniform `ei` the flexure was built with, and [`Flexure::ei`]
    /// becomes the mean. The stiffness matrix $K$ is integrated once here:
    /// exactly (Gauss–Legendre on each smooth piece) when $EI$ is a polynomial
    /// there, as for tapers and tables; adaptively to $10^{-13}$ of its
    /// largest entry for a notch.
    ///
    /// Fails when $EI(s)$ leaves [`EI_RANGE`] anywhere, naming where, and
    /// when a rectangle's thickness exceeds the length anywhere: a beam that
    /// is thicker than it is long is no flexure (every front end, the CLI,
    /// mechanism files and Python, builds its flexure here, so all refuse it).
    /// A notch hinge is held to its thinnest section, `min_thickness`: its
    /// ends are as thick as the blank it is cut into, which for a full
    /// circular notch (length $2R$) is always more than the length.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, Section};
    /// // EI falling linearly from 2 to 1: K₁₁ = (1/L)∫EI dt = 1.5/L, K₁₂ = (1/L)∫EI(2t−1)dt = −1/(6L).
    /// let s = Section::given(Profile::Linear { root: 2.0, tip: 1.0 }).unwrap();
    /// let f = flexure::Flexure::new(0.5, 1.0, 3).unwrap().with_section(s).unwrap();
    /// let k = f.stiffness_matrix();
    /// assert!((k[0] - 3.0).abs() < 1e-14 && (k[1] + 1.0 / 3.0).abs() < 1e-14 && (f.ei() - 1.5).abs() < 1e-14);
    /// // A rectangle 2 cm thick on a 1 cm flexure is refused, naming the thickness.
    /// let thick = Section::rectangle(200e9, None, Profile::Constant(0.01), Profile::Constant(0.02)).unwrap();
    /// let e = flexure::Flexure::new(0.01, 1.0, 3).unwrap().with_section(thick).unwrap_err();
    /// assert!(e.to_string().contains("thickness") && e.to_string().contains("0.02"));
    /// ```
    pub fn with_section(mut self, section: Section) -> Result<Self> {
        // A thickness is piecewise linear in t (a notch only thins it): its largest value is at
        // an end or a breakpoint.
        let l = self.length;
        if let Some(n) = section.notch() {
            if n.min_thickness > l {
                return Err(Error::invalid(
                    "notch.min_thickness",
                    format!("{} m, on a flexure of length {l} m", n.min_thickness),
                    "must not exceed the flexure's length: a hinge thicker than it is long is no flexure",
                ));
            }
        } else {
            let at = [0.0, 1.0].into_iter().chain(section.breakpoints(l));
            crate::section::thinner_than_long("thickness", l, at.filter_map(|t| Some((t, section.thickness(t, l)?))))?;
        }
        let (stiffness, mean) = self.stiffness_matrix_of(&section)?;
        within("ei", mean, EI_RANGE)?;
        let n = self.order();
        if !crate::linalg::positive_definite(&stiffness, n, &mut vec![0.0; n * n]) {
            return Err(Error::invalid(
                "ei",
                format!("from {:e} to {:e} N·m²", section.ei(0.0, self.length), section.ei(1.0, self.length)),
                "varies too much along the flexure: its stiffness matrix is not positive definite to rounding",
            ));
        }
        self.stiffness = stiffness;
        self.ei = mean;
        self.section = section;
        Ok(self)
    }

    /// $K$ (row-major) and the mean $EI$ of `section` on this flexure's length and basis.
    fn stiffness_matrix_of(&self, section: &Section) -> Result<(Vec<f64>, f64)> {
        let (n, l) = (self.order(), self.length);
        if section.is_uniform() {
            let ei = section.ei(0.0, l);
            let diagonal = |i: usize| match self.basis {
                Basis::Legendre => basis::energy_weight(i),
                Basis::Segments => n as f64,
            };
            let k = (0..n * n).map(|ij| if ij / n == ij % n { ei / l * diagonal(ij / n) } else { 0.0 }).collect();
            return Ok((k, ei));
        }
        let mut breaks = section.breakpoints(l);
        if self.basis == Basis::Segments {
            breaks.extend((1..n).map(|j| j as f64 / n as f64));
            breaks.sort_by(f64::total_cmp);
        }
        let mut shapes = vec![0.0; n];
        let mut outside: Option<(f64, f64)> = None;
        // EI of a taper or table piece is smallest at a piece's end (a product
        // of positive linear factors is log-concave); a notch's at its middle.
        let ends = [0.0, 0.5, 1.0];
        for &t in breaks.iter().chain(&ends) {
            let ei = section.ei(t, l);
            if !(ei.is_finite() && (EI_RANGE.0..=EI_RANGE.1).contains(&ei)) && outside.is_none() {
                outside = Some((t, ei));
            }
        }
        let integrand = |t: f64, out: &mut [f64]| {
            let ei = section.ei(t, l);
            if !(ei.is_finite() && (EI_RANGE.0..=EI_RANGE.1).contains(&ei)) && outside.is_none() {
                outside = Some((t, ei));
            }
            match self.basis {
                Basis::Legendre => basis::shifted_legendre(t, &mut shapes),
                Basis::Segments => {
                    let j = ((t * n as f64) as usize).min(n - 1);
                    shapes.fill(0.0);
                    shapes[j] = n as f64;
                }
            }
            let mut k = 0;
            for i in 0..n {
                for j in i..n {
                    out[k] = ei * shapes[i] * shapes[j];
                    k += 1;
                }
            }
            out[k] = ei;
        };
        let pairs = n * (n + 1) / 2;
        let v = crate::quadrature::integrate(&breaks, n + 4, section.polynomial(), 1e-13, pairs + 1, integrand)?;
        if let Some((t, ei)) = outside {
            return Err(Error::InvalidParameter {
                name: "ei",
                value: format!("{ei:e} at s = {:e} m", t * l),
                reason: "must lie in [1e-30, 1e15] N·m² all along the flexure",
            });
        }
        let mut k = vec![0.0; n * n];
        let mut idx = 0;
        for i in 0..n {
            for j in i..n {
                k[i * n + j] = v[idx] / l;
                k[j * n + i] = v[idx] / l;
                idx += 1;
            }
        }
        Ok((k, v[pairs]))
    }

    /// The same flexure with rest curvature coefficients $\kappa$ (Eq. 5).
    pub fn with_rest(mut self, kappa: &[f64]) -> Result<Self> {
        if kappa.len() != self.order() {
            return Err(Error::invalid("kappa", format!("{} values", kappa.len()), "must have one value per order"));
        }
        for &k in kappa {
            within_magnitude("kappa", k, MAX_COORDINATE)?;
        }
        self.kappa = kappa.to_vec();
        Ok(self)
    }

    /// The same flexure with a `points`-point Gauss–Legendre rule (per
    /// segment, for [`Basis::Segments`]).
    pub fn with_quadrature(mut self, points: usize) -> Result<Self> {
        self.set_rule(GaussLegendre::new(points)?);
        Ok(self)
    }

    fn set_rule(&mut self, rule: GaussLegendre) {
        let n = self.order();
        let pieces = if self.basis == Basis::Segments { n } else { 1 };
        self.nodes.clear();
        self.weights.clear();
        for j in 0..pieces {
            for (&t, &w) in rule.nodes().iter().zip(rule.weights()) {
                self.nodes.push((j as f64 + t) / pieces as f64);
                self.weights.push(w * self.length / pieces as f64);
            }
        }
        self.psi = vec![0.0; self.nodes.len() * n];
        let mut psi = std::mem::take(&mut self.psi);
        for (row, &t) in psi.chunks_exact_mut(n).zip(&self.nodes) {
            self.angle_shapes(t, row);
        }
        self.psi = psi;
        // Products of the weights with the shapes: the kernel's only per-node constants.
        let q = self.nodes.len();
        let product = |k: usize, i: usize| self.weights[k] * self.psi[k * n + i];
        self.jacobian_weights = (0..n).flat_map(|i| (0..q).map(move |k| product(k, i))).collect();
        self.hessian_weights = (0..n)
            .flat_map(|i| (i..n).flat_map(move |j| (0..q).map(move |k| (i, j, k))))
            .map(|(i, j, k)| product(k, i) * self.psi[k * n + j])
            .collect();
        self.rule = rule;
    }

    /// The basis of the coordinates.
    #[inline]
    pub fn basis(&self) -> Basis {
        self.basis
    }

    /// Curvature $\hat\omega(c, s)$ (1/m) of coordinates `c` at arc length `s`.
    ///
    /// # Example
    /// ```
    /// let f = flexure::Flexure::segments(2.0, 1.0, 4).unwrap();
    /// // Segment 1 spans s in [0.5, 1): rotation 0.3 over 0.5 m.
    /// assert!((f.curvature(&[0.0, 0.3, 0.0, 0.0], 0.7) - 0.6).abs() < 1e-15);
    /// ```
    ///
    /// # Panics
    /// If `c` does not have one entry per coordinate ([`Flexure::order`]).
    pub fn curvature(&self, c: &[f64], s: f64) -> f64 {
        assert_coordinates(self, "c", c.len());
        match self.basis {
            Basis::Legendre => basis::curvature(c, self.length, s),
            Basis::Segments => {
                let n = c.len();
                let j = ((s / self.length * n as f64).floor().max(0.0) as usize).min(n - 1);
                c[j] * n as f64 / self.length
            }
        }
    }

    /// Angle shapes $\psi_i(t)$ at any $t \in [0, 1]$, written into `out` (one per coordinate).
    ///
    /// # Panics
    /// If `out` does not have one entry per coordinate ([`Flexure::order`]).
    pub fn angle_shapes(&self, t: f64, out: &mut [f64]) {
        assert_coordinates(self, "out", out.len());
        match self.basis {
            Basis::Legendre => basis::angle_shapes(t, out),
            Basis::Segments => {
                let n = out.len() as f64;
                for (j, v) in out.iter_mut().enumerate() {
                    *v = (n * t - j as f64).clamp(0.0, 1.0);
                }
            }
        }
    }

    /// The stiffness matrix $K$ (N·m/rad², row-major $N\times N$, symmetric):
    /// $U = \frac12(\alpha-\kappa)^TK(\alpha-\kappa)$.
    #[inline]
    pub fn stiffness_matrix(&self) -> &[f64] {
        &self.stiffness
    }

    /// The cross-section along the flexure.
    pub fn section(&self) -> &Section {
        &self.section
    }

    /// Bending stiffness $EI(s)$ (N·m²) at arc length `s` (m).
    ///
    /// # Example
    /// ```
    /// let f = flexure::Flexure::new(2.0, 3.0, 3).unwrap();
    /// assert_eq!(f.ei_at(0.7), 3.0);
    /// ```
    pub fn ei_at(&self, s: f64) -> f64 {
        self.section.ei(s / self.length, self.length)
    }

    /// $\partial\phi_{tip}/\partial\alpha$: $(1, 0, \dots)$ for Legendre (Eq. 19), all ones for segments.
    #[inline]
    pub fn tip_angle_row(&self) -> &[f64] {
        &self.tip_angle
    }

    /// Length $L$ in metres.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Bending stiffness $EI$ in N·m²; for a non-uniform [`Section`], its
    /// mean $\frac1L\int_0^L EI\thinspace ds$ (the scale of loads and energies).
    pub fn ei(&self) -> f64 {
        self.ei
    }

    /// Order $N$: the number of curvature coefficients.
    #[inline]
    pub fn order(&self) -> usize {
        self.kappa.len()
    }

    /// Rest coefficients $\kappa$.
    pub fn rest(&self) -> &[f64] {
        &self.kappa
    }

    /// Number of quadrature points $Q$ (per segment, for [`Basis::Segments`]).
    pub fn quadrature_points(&self) -> usize {
        self.rule.len()
    }

    /// Nodes $t_k$ on $[0, 1]$ of the whole (composite) rule.
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// Rows $\psi_i(t_k)$, one per node.
    #[inline]
    pub(crate) fn psi_rows(&self) -> std::slice::ChunksExact<'_, f64> {
        self.psi.chunks_exact(self.order())
    }

    /// $\psi_i(t_k)$ at `[k * n + i]`.
    #[inline]
    pub(crate) fn psi_table(&self) -> &[f64] {
        &self.psi
    }

    /// Scaled weights $L\Delta_k$.
    #[inline]
    pub(crate) fn scaled_weights(&self) -> &[f64] {
        &self.weights
    }

    /// $L\Delta_k\psi_i(t_k)$ by coordinate: row $i$ holds all nodes.
    #[inline]
    pub(crate) fn jacobian_weights(&self) -> &[f64] {
        &self.jacobian_weights
    }

    /// $L\Delta_k\psi_i\psi_j$ for $j \ge i$ in row-major pair order, each row holding all nodes.
    #[inline]
    pub(crate) fn hessian_weights(&self) -> &[f64] {
        &self.hessian_weights
    }

    /// Checks that `alpha` has one finite value per order (per segment).
    ///
    /// # Example
    /// ```
    /// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
    /// assert!(f.check_coordinates("alpha", &[0.0; 3]).is_ok());
    /// assert!(f.check_coordinates("alpha", &[0.0; 4]).is_err());
    /// ```
    pub fn check_coordinates<T: crate::Scalar>(&self, name: &'static str, alpha: &[T]) -> Result<()> {
        if alpha.len() != self.order() {
            return Err(Error::InvalidParameter {
                name,
                value: format!("{} values", alpha.len()),
                reason: if self.basis == Basis::Legendre {
                    "must have one value per order (the flexure's order N)"
                } else {
                    "must have one value per segment"
                },
            });
        }
        for a in alpha {
            within_magnitude(name, a.re(), MAX_COORDINATE)?;
        }
        Ok(())
    }
}

/// Panics unless a coordinate slice called `name` has `len` =
/// [`Flexure::order`] entries: the kernels' precondition, checked once per
/// call so that no kernel ever zips a short or long slice into a silently
/// truncated result. User-facing entries validate first with
/// [`Flexure::check_coordinates`], which returns an error instead.
#[inline]
#[track_caller]
pub(crate) fn assert_coordinates(flexure: &Flexure, name: &str, len: usize) {
    let order = flexure.order();
    assert!(len == order, "{name} must have {order} entries (one per coordinate, the flexure's order), got {len}");
}
