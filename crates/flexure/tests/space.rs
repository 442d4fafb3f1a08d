//! The planar space's group operations against independent references: the
//! 3×3 homogeneous matrices of SE(2) (products, inverse, the matrix
//! exponential of the twist's hat), and central differences for the adjoint
//! and the velocity of a point.

use flexure::space::{Planar, Pose, Space, Twist, Wrench};
use nalgebra::{Matrix3, Point2, Vector2};
use proptest::prelude::*;

/// The homogeneous matrix of a planar pose.
fn matrix(g: &Pose) -> Matrix3<f64> {
    let (s, c) = g.phi.sin_cos();
    Matrix3::new(c, -s, g.x, s, c, g.y, 0.0, 0.0, 1.0)
}

/// The pose of a homogeneous matrix (its angle by atan2).
fn pose(m: &Matrix3<f64>) -> Pose {
    Pose { phi: m[(1, 0)].atan2(m[(0, 0)]), x: m[(0, 2)], y: m[(1, 2)] }
}

/// The twist's hat, $\begin{pmatrix}\hat\omega & v\cr 0 & 0\end{pmatrix}$.
fn hat(t: &Twist) -> Matrix3<f64> {
    Matrix3::new(0.0, -t.omega, t.vx, t.omega, 0.0, t.vy, 0.0, 0.0, 0.0)
}

/// Rotations agree modulo 2π.
fn same_angle(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

fn close(a: &Pose, b: &Pose, tol: f64) -> bool {
    same_angle(a.phi, b.phi) < tol && (a.x - b.x).abs() < tol && (a.y - b.y).abs() < tol
}

fn poses() -> impl Strategy<Value = Pose> {
    (-3.0..3.0f64, -2.0..2.0f64, -2.0..2.0f64).prop_map(|(phi, x, y)| Pose { phi, x, y })
}

fn twists() -> impl Strategy<Value = Twist> {
    (-3.0..3.0f64, -2.0..2.0f64, -2.0..2.0f64).prop_map(|(omega, vx, vy)| Twist { omega, vx, vy })
}

proptest! {
    /// Compose and inverse are the matrix product and inverse; tolerance
    /// 1e-13: a few roundings of numbers of order 10.
    #[test]
    fn compose_and_inverse_are_matrix_products(a in poses(), b in poses()) {
        prop_assert!(close(&Planar::compose(&a, &b), &pose(&(matrix(&a) * matrix(&b))), 1e-13));
        prop_assert!(close(&Planar::inverse(&a), &pose(&matrix(&a).try_inverse().unwrap()), 1e-13));
        prop_assert!(close(&Planar::compose(&a, &Planar::inverse(&a)), &Planar::identity(), 1e-14));
    }

    /// A point acted on is the matrix times its homogeneous coordinates; a
    /// direction turns without the translation.
    #[test]
    fn act_and_rotate_are_matrix_products(a in poses(), x in -2.0..2.0f64, y in -2.0..2.0f64) {
        let m = matrix(&a) * nalgebra::Vector3::new(x, y, 1.0);
        let w = Planar::act(&a, &Point2::new(x, y));
        prop_assert!((w.x - m[0]).abs() < 1e-14 && (w.y - m[1]).abs() < 1e-14);
        let d = matrix(&a) * nalgebra::Vector3::new(x, y, 0.0);
        let v = Planar::rotate(&a, &Vector2::new(x, y));
        prop_assert!((v.x - d[0]).abs() < 1e-14 && (v.y - d[1]).abs() < 1e-14);
    }

    /// exp is the matrix exponential of the hat (nalgebra's Padé
    /// approximant, an independent computation), to 1e-12; log inverts it
    /// for angles in (−π, π).
    #[test]
    fn exp_is_the_matrix_exponential_and_log_inverts_it(t in twists()) {
        let g = Planar::exp(&t);
        prop_assert!(close(&g, &pose(&hat(&t).exp()), 1e-12));
        let back = Planar::log(&g);
        prop_assert!((back.omega - t.omega).abs() < 1e-12);
        prop_assert!((back.vx - t.vx).abs() < 1e-11 && (back.vy - t.vy).abs() < 1e-11);
    }

    /// The adjoint is $\frac{d}{d\epsilon} g\exp(\epsilon\xi)g^{-1}$ at 0,
    /// by central differences (step 1e-6: error ~1e-12 plus rounding 1e-10).
    #[test]
    fn adjoint_is_the_derivative_of_conjugation(g in poses(), t in twists()) {
        let h = 1e-6;
        let conj = |e: f64| {
            let s = Twist { omega: e * t.omega, vx: e * t.vx, vy: e * t.vy };
            Planar::log(&Planar::compose(&Planar::compose(&g, &Planar::exp(&s)), &Planar::inverse(&g)))
        };
        let (p, m) = (conj(h), conj(-h));
        let fd = [(p.omega - m.omega) / (2.0 * h), (p.vx - m.vx) / (2.0 * h), (p.vy - m.vy) / (2.0 * h)];
        let ad = Planar::adjoint(&g) * nalgebra::Vector3::from(t.to_array());
        for i in 0..3 {
            prop_assert!((ad[i] - fd[i]).abs() < 1e-8, "component {}: {} against {}", i, ad[i], fd[i]);
        }
    }

    /// Power is frame-free: $w^{\prime}\cdot\mathrm{Ad}_g\xi = (\mathrm{Ad}_g^Tw^{\prime})\cdot\xi$, and
    /// `Ad` of a product is the product of the `Ad`s.
    #[test]
    fn adjoint_is_a_homomorphism_and_power_is_frame_free(a in poses(), b in poses(), t in twists()) {
        let ab = Planar::adjoint(&Planar::compose(&a, &b));
        prop_assert!((ab - Planar::adjoint(&a) * Planar::adjoint(&b)).abs().max() < 1e-13);
        let w = Wrench { moment: 0.7, fx: -1.3, fy: 2.1 };
        let moved = Planar::adjoint(&a) * nalgebra::Vector3::from(t.to_array());
        let pulled = Planar::adjoint(&a).transpose() * nalgebra::Vector3::from(w.to_array());
        let lhs = Planar::power(&w, &Twist::from_slice(moved.as_slice()));
        let rhs = Planar::power(&Wrench::from_array([pulled[0], pulled[1], pulled[2]]), &t);
        prop_assert!((lhs - rhs).abs() < 1e-12);
    }

    /// A point's velocity under a twist is the derivative of
    /// $\exp(\epsilon\xi)\cdot r$ at 0 (central differences, step 1e-6).
    #[test]
    fn velocity_at_is_the_derivative_of_acting(t in twists(), x in -2.0..2.0f64, y in -2.0..2.0f64) {
        let h = 1e-6;
        let r = Point2::new(x, y);
        let at = |e: f64| Planar::act(&Planar::exp(&Twist { omega: e * t.omega, vx: e * t.vx, vy: e * t.vy }), &r);
        let fd = (at(h) - at(-h)) / (2.0 * h);
        let v = Planar::velocity_at(&t, &Vector2::new(x, y));
        prop_assert!((v - fd).abs().max() < 1e-8);
    }
}

/// exp and log stay accurate through a zero angle, where the quotients
/// of V(ω) would cancel (tolerance 1e-15 on numbers of order 1).
#[test]
fn exp_and_log_are_smooth_through_zero_angle() {
    for w in [0.0, 1e-12, -3e-9, 9.99e-5, 1.01e-4] {
        let t = Twist { omega: w, vx: 1.0, vy: -0.5 };
        let g = Planar::exp(&t);
        let m = pose(&hat(&t).exp());
        assert!((g.x - m.x).abs() < 1e-15 && (g.y - m.y).abs() < 1e-15, "exp at {w}");
        let back = Planar::log(&g);
        assert!((back.vx - 1.0).abs() < 1e-15 && (back.vy + 0.5).abs() < 1e-15, "log at {w}");
    }
}
