//! The shapes a geom can have, and each one's signed distance and outward
//! normal at a point given in the shape's own frame: closed forms, written
//! once over the dimension (a vector's components are indexed up to
//! [`Space::POINT_DIM`](crate::space::Space::POINT_DIM)).
//!
//! | shape | the solid (in its frame) | signed distance $d(p)$ |
//! | --- | --- | --- |
//! | plane | $p\cdot n \le 0$ | $p\cdot n$ |
//! | circle, sphere | $\lvert p\rvert \le R$ | $\lvert p\rvert - R$ |
//! | capsule | within $R$ of the segment $\lvert x\rvert \le h$ on the $x$ axis | $\lvert p - c(p)\rvert - R$ |
//! | box | $\lvert p_i\rvert \le e_i$ | $\lvert\max(q, 0)\rvert + \min(\max_i q_i, 0)$, $q_i = \lvert p_i\rvert - e_i$ |
//! | cylinder (space) | $\rho \le R$, $\lvert z\rvert \le h$ about the $z$ axis | the box's, in $(\rho, z)$ |
//!
//! $d > 0$ outside, $d = 0$ on the surface, $d < 0$ inside (the depth,
//! the distance to the nearest surface point). The normal is the unit
//! gradient $\nabla d$ where it exists: outward, along the shortest way out.

use crate::mechanism::Dimension;

/// A geom's solid, in its own frame (see the module docs for each one's
/// signed distance).
///
/// # Example
/// ```
/// use flexure::mechanism::contact::GeomShape;
/// use flexure::space::Planar;
/// use nalgebra::Vector2;
/// let post: GeomShape<Planar> = GeomShape::Ball { radius: 0.5 };
/// let (d, n) = post.distance(&Vector2::new(0.0, 2.0));
/// assert_eq!((d, n), (1.5, Vector2::new(0.0, 1.0)));
/// assert_eq!(post.name(), "circle");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GeomShape<D: Dimension> {
    /// The half-space behind the plane (a line in the plane) through the
    /// frame's origin with the outward unit normal `normal`.
    Plane {
        /// Outward unit normal, in the geom's frame; the solid lies behind it.
        normal: D::Vector,
    },
    /// A circle in the plane, a sphere in space, about the frame's origin.
    Ball {
        /// Radius (m), greater than zero.
        radius: f64,
    },
    /// The points within `radius` of the segment from $-h$ to $h$ on the frame's $x$ axis.
    Capsule {
        /// $h$ (m), not negative.
        half_length: f64,
        /// Radius (m), greater than zero.
        radius: f64,
    },
    /// The box $\lvert p_i\rvert \le e_i$ (a rectangle in the plane).
    Box {
        /// $e_i$ (m), each greater than zero.
        half_extents: D::Vector,
    },
    /// The solid cylinder of `radius` about the frame's $z$ axis,
    /// $\lvert z\rvert \le h$; the file gives it in space only (in the plane
    /// $z = 0$ it is its circle, as [`GeomShape::distance`] takes it).
    Cylinder {
        /// $h$ (m), greater than zero.
        half_length: f64,
        /// Radius (m), greater than zero.
        radius: f64,
    },
}

/// $a\cdot b$ over the dimension's components.
fn dot<D: Dimension>(a: &D::Vector, b: &D::Vector) -> f64 {
    (0..D::POINT_DIM).map(|i| a[i] * b[i]).sum()
}

/// The unit vector along axis `i`.
fn axis<D: Dimension>(i: usize) -> D::Vector {
    let mut e = D::Vector::default();
    e[i] = 1.0;
    e
}

/// `v` scaled by `k`.
fn scaled<D: Dimension>(v: &D::Vector, k: f64) -> D::Vector {
    let mut out = *v;
    for i in 0..D::POINT_DIM {
        out[i] *= k;
    }
    out
}

/// $\lvert v\rvert - R$ and $v/\lvert v\rvert$ ($e_x$ when $v = 0$,
/// where every direction is as near).
fn away<D: Dimension>(v: &D::Vector, radius: f64) -> (f64, D::Vector) {
    let r = dot::<D>(v, v).sqrt();
    if r == 0.0 { (-radius, axis::<D>(0)) } else { (r - radius, scaled::<D>(v, 1.0 / r)) }
}

/// The signed distance and normal of a box of half extents `e` (its first
/// `n` components) at `p`: outside, to the nearest surface point; inside,
/// the face nearest (the first of equals).
fn boxed<D: Dimension>(p: &D::Vector, e: &D::Vector, n: usize) -> (f64, D::Vector) {
    let sign = |x: f64| if x < 0.0 { -1.0 } else { 1.0 };
    let mut out = D::Vector::default();
    let mut outside = 0.0;
    for i in 0..n {
        let q = p[i].abs() - e[i];
        if q > 0.0 {
            out[i] = sign(p[i]) * q;
            outside += q * q;
        }
    }
    if outside > 0.0 {
        let d = outside.sqrt();
        return (d, scaled::<D>(&out, 1.0 / d));
    }
    let (mut k, mut depth) = (0, f64::NEG_INFINITY);
    for i in 0..n {
        let q = p[i].abs() - e[i];
        if q > depth {
            (k, depth) = (i, q);
        }
    }
    (depth, scaled::<D>(&axis::<D>(k), sign(p[k])))
}

impl<D: Dimension> GeomShape<D> {
    /// Its name in the file: `plane`, `circle` (plane) or `sphere` (space),
    /// `capsule`, `box`, `cylinder`.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::contact::GeomShape;
    /// use flexure::space::Spatial;
    /// assert_eq!(GeomShape::<Spatial>::Ball { radius: 1.0 }.name(), "sphere");
    /// ```
    pub fn name(&self) -> &'static str {
        match self {
            GeomShape::Plane { .. } => "plane",
            GeomShape::Ball { .. } if D::POINT_DIM == 2 => "circle",
            GeomShape::Ball { .. } => "sphere",
            GeomShape::Capsule { .. } => "capsule",
            GeomShape::Box { .. } => "box",
            GeomShape::Cylinder { .. } => "cylinder",
        }
    }

    /// The signed distance $d(p)$ (m; negative inside) from the point `p`,
    /// given in the shape's frame, to the shape's surface, and the outward
    /// unit normal $\nabla d$ there (see the module docs). Where the
    /// gradient is not defined (a ball's or a capsule's axis, a box's
    /// medial planes) it is one of the equally short ways out.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::contact::GeomShape;
    /// use flexure::space::Spatial;
    /// use nalgebra::Vector3;
    /// let can: GeomShape<Spatial> = GeomShape::Cylinder { half_length: 1.0, radius: 0.5 };
    /// // Beyond the rim: the distance to the circle of the top face's edge.
    /// let (d, n) = can.distance(&Vector3::new(0.0, 3.5, 5.0));
    /// assert!((d - 5.0).abs() < 1e-15 && (n - Vector3::new(0.0, 0.6, 0.8)).norm() < 1e-15);
    /// ```
    pub fn distance(&self, p: &D::Vector) -> (f64, D::Vector) {
        match self {
            GeomShape::Plane { normal } => (dot::<D>(p, normal), *normal),
            GeomShape::Ball { radius } => away::<D>(p, *radius),
            GeomShape::Capsule { half_length, radius } => {
                let mut off = *p;
                off[0] -= p[0].clamp(-half_length, *half_length);
                away::<D>(&off, *radius)
            }
            GeomShape::Box { half_extents } => boxed::<D>(p, half_extents, D::POINT_DIM),
            // In the plane z = 0 the cylinder about z is its circle.
            GeomShape::Cylinder { radius, .. } if D::POINT_DIM == 2 => away::<D>(p, *radius),
            GeomShape::Cylinder { half_length, radius } => {
                // The box in (ρ, z) of half extents (R, h), turned back about z.
                let rho = p[0].hypot(p[1]);
                let (cos, sin) = if rho == 0.0 { (1.0, 0.0) } else { (p[0] / rho, p[1] / rho) };
                let mut flat = D::Vector::default();
                let mut extents = D::Vector::default();
                (flat[0], flat[1], extents[0], extents[1]) = (rho, p[2], *radius, *half_length);
                let (d, m) = boxed::<D>(&flat, &extents, 2);
                let mut n = D::Vector::default();
                (n[0], n[1], n[2]) = (m[0] * cos, m[0] * sin, m[1]);
                (d, n)
            }
        }
    }
}
