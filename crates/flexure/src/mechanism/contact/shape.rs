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
pub(crate) fn dot<D: Dimension>(a: &D::Vector, b: &D::Vector) -> f64 {
    (0..D::POINT_DIM).map(|i| a[i] * b[i]).sum()
}

/// A vector of the dimension from the first components of `a`.
pub(crate) fn vector<D: Dimension>(a: &[f64; 3]) -> D::Vector {
    let mut v = D::Vector::default();
    for i in 0..D::POINT_DIM {
        v[i] = a[i];
    }
    v
}

/// `v`'s components, padded with zeros to three.
pub(crate) fn array<D: Dimension>(v: &D::Vector) -> [f64; 3] {
    let mut a = [0.0; 3];
    for (i, x) in a.iter_mut().enumerate().take(D::POINT_DIM) {
        *x = v[i];
    }
    a
}

/// The unit vector along axis `i`.
fn axis<D: Dimension>(i: usize) -> D::Vector {
    let mut e = D::Vector::default();
    e[i] = 1.0;
    e
}

/// `v` scaled by `k`.
pub(crate) fn scaled<D: Dimension>(v: &D::Vector, k: f64) -> D::Vector {
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

/// $\nabla^2 d$ of a distance $d = \lvert v\rvert$ to a point, or to a line
/// along `free` (a capsule's or cylinder's axis): $(I - \hat n\hat n^T - ff^T)/\lvert v\rvert$.
fn round<D: Dimension>(v: &D::Vector, free: Option<&D::Vector>) -> DistanceHessian {
    let r = dot::<D>(v, v).sqrt();
    let mut c = [[0.0; 3]; 3];
    if r == 0.0 {
        return c;
    }
    for i in 0..D::POINT_DIM {
        for j in 0..D::POINT_DIM {
            let along = free.map_or(0.0, |f| f[i] * f[j]);
            c[i][j] = (f64::from(u8::from(i == j)) - v[i] * v[j] / (r * r) - along) / r;
        }
    }
    c
}

/// A shape's $\nabla^2 d$ at a point, row by row ($3\times3$; in the plane its $2\times2$ corner).
pub type DistanceHessian = [[f64; 3]; 3];

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
        self.distance_curvature(p, false).0
    }

    /// The Hessian $\nabla^2 d$ of the signed distance at `p` (1/m, in the
    /// shape's frame): how the normal turns as the point moves, which a
    /// contact's stiffness needs, inside as outside. Zero on flat parts and inside a box; about a
    /// ball's centre, a capsule's axis, a box's edge or corner and a
    /// cylinder's side or rim, that of the distance to that point or line
    /// (`round`), less what the nearest point's own motion along a
    /// cylinder's circles takes away ($R/\rho$ of the motion along them).
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::contact::GeomShape;
    /// use flexure::space::Planar;
    /// use nalgebra::Vector2;
    /// let post: GeomShape<Planar> = GeomShape::Ball { radius: 0.5 };
    /// // 2 from the centre on y: the normal turns along x at 1/2 per metre.
    /// let c = post.curvature(&Vector2::new(0.0, 2.0));
    /// assert!((c[0][0] - 0.5).abs() < 1e-15 && c[1][1] == 0.0 && c[0][1] == 0.0);
    /// ```
    pub fn curvature(&self, p: &D::Vector) -> DistanceHessian {
        self.distance_curvature(p, true).1
    }

    /// [`GeomShape::distance`] and, when `curved`, [`GeomShape::curvature`].
    fn distance_curvature(&self, p: &D::Vector, curved: bool) -> ((f64, D::Vector), DistanceHessian) {
        let flat = [[0.0; 3]; 3];
        let found = self.distance_only(p);
        if !curved {
            return (found, flat);
        }
        let inside = found.0 < 0.0;
        let c = match self {
            GeomShape::Plane { .. } => flat,
            GeomShape::Ball { .. } => round::<D>(p, None),
            GeomShape::Cylinder { .. } if D::POINT_DIM == 2 => round::<D>(p, None),
            GeomShape::Capsule { half_length, .. } => {
                let mut off = *p;
                off[0] -= p[0].clamp(-half_length, *half_length);
                round::<D>(&off, (p[0].abs() < *half_length).then(|| axis::<D>(0)).as_ref())
            }
            GeomShape::Box { .. } if inside => flat,
            GeomShape::Box { half_extents } => {
                // Outside, the distance to the nearest face, edge or corner:
                // free along the axes within the box's extent.
                let mut off = D::Vector::default();
                let mut free = [None; 3];
                for i in 0..D::POINT_DIM {
                    let q = p[i].abs() - half_extents[i];
                    if q > 0.0 {
                        off[i] = p[i].signum() * q;
                    } else {
                        free[i] = Some(axis::<D>(i));
                    }
                }
                let r = dot::<D>(&off, &off).sqrt();
                let mut c = round::<D>(&off, None);
                for f in free.iter().flatten().filter(|_| r > 0.0) {
                    for i in 0..D::POINT_DIM {
                        for j in 0..D::POINT_DIM {
                            c[i][j] -= f[i] * f[j] / r;
                        }
                    }
                }
                c
            }
            GeomShape::Cylinder { half_length, radius } => {
                let rho = p[0].hypot(p[1]);
                let side = match inside {
                    true => rho - radius >= p[2].abs() - half_length && rho > 0.0,
                    false => p[2].abs() < *half_length,
                };
                if side {
                    // ρ − R turns about z at 1/ρ, on the surface too.
                    let t = [-p[1] / rho, p[0] / rho];
                    let mut c = [[0.0; 3]; 3];
                    for i in 0..2 {
                        for j in 0..2 {
                            c[i][j] = t[i] * t[j] / rho;
                        }
                    }
                    c
                } else if inside || rho <= *radius {
                    // A flat face, from within or above it.
                    flat
                } else {
                    // The rim (free along its tangent).
                    let mut off = *p;
                    let scale = (rho - radius) / rho;
                    (off[0], off[1]) = (p[0] * scale, p[1] * scale);
                    off[2] = p[2] - p[2].clamp(-half_length, *half_length);
                    let mut tangent = D::Vector::default();
                    (tangent[0], tangent[1]) = (-p[1] / rho, p[0] / rho);
                    let mut c = round::<D>(&off, None);
                    // Along the rim's tangent the nearest point moves by R/ρ of the point.
                    let r = dot::<D>(&off, &off).sqrt();
                    for i in 0..3 {
                        for j in 0..3 {
                            c[i][j] -= if r > 0.0 { radius / rho * tangent[i] * tangent[j] / r } else { 0.0 };
                        }
                    }
                    c
                }
            }
        };
        (found, c)
    }

    /// How far the point `p` on or near the face whose outward normal is
    /// `normal` (both in the shape's frame) lies within that face, from the
    /// edges where it meets the next faces (m): on a box's face across axis
    /// $k$ (the normal's largest component), $-\max_{i \ne k}(\lvert p_i\rvert - e_i)$;
    /// on a cylinder's flat face (in space), $R - \rho$, on its side
    /// $h - \lvert z\rvert$; below zero past an edge or a rim, where the
    /// normal turns from one face to the next. A plane, a ball and a capsule
    /// are smooth: $+\infty$.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::contact::GeomShape;
    /// use flexure::space::Spatial;
    /// use nalgebra::Vector3;
    /// let brick: GeomShape<Spatial> = GeomShape::Box { half_extents: Vector3::new(1.0, 2.0, 3.0) };
    /// // On the face x = 1, 0.5 from its edge y = 2; in its plane, 0.25 past its edge z = 3.
    /// assert_eq!(brick.face_margin(&Vector3::new(1.0, 1.5, 0.0), &Vector3::x()), 0.5);
    /// assert_eq!(brick.face_margin(&Vector3::new(1.0, 0.0, 3.25), &Vector3::x()), -0.25);
    /// ```
    pub fn face_margin(&self, p: &D::Vector, normal: &D::Vector) -> f64 {
        match self {
            GeomShape::Box { half_extents } => {
                let k = (0..D::POINT_DIM).fold(0, |k, i| if normal[i].abs() > normal[k].abs() { i } else { k });
                -(0..D::POINT_DIM)
                    .filter(|&i| i != k)
                    .map(|i| p[i].abs() - half_extents[i])
                    .fold(f64::NEG_INFINITY, f64::max)
            }
            GeomShape::Cylinder { half_length, radius } if D::POINT_DIM == 3 => {
                match normal[2].abs() > normal[0].hypot(normal[1]) {
                    true => radius - p[0].hypot(p[1]),
                    false => half_length - p[2].abs(),
                }
            }
            _ => f64::INFINITY,
        }
    }

    /// [`GeomShape::distance`] itself.
    fn distance_only(&self, p: &D::Vector) -> (f64, D::Vector) {
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
