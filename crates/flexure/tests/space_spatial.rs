//! The spatial space's group operations (`space::Spatial`, SE(3)) against
//! independent references: 4×4 homogeneous matrices (products, inverse,
//! action), the matrix exponential of the twist's hat (a Taylor series
//! after scaling and squaring, written here), central differences of exp,
//! $\mathrm{Ad}_g\xi = (g\hat\xi g^{-1})^\vee$, frame-free power, and the
//! planar space embedded in it.

use flexure::space::{Planar, Pose, Space, Spatial, Twist};
use nalgebra::{Isometry3, Matrix4, Point3, Vector3, Vector6};
use proptest::prelude::*;

fn matrix(g: &Isometry3<f64>) -> Matrix4<f64> {
    g.to_homogeneous()
}

/// The hat $\begin{pmatrix}\hat\omega & v\cr 0 & 0\end{pmatrix}$ of a twist (angular, linear).
fn hat(t: &Vector6<f64>) -> Matrix4<f64> {
    let mut m = Matrix4::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&Vector3::new(t[0], t[1], t[2]).cross_matrix());
    m.fixed_view_mut::<3, 1>(0, 3).copy_from(&Vector3::new(t[3], t[4], t[5]));
    m
}

/// The twist of a hat.
fn vee(m: &Matrix4<f64>) -> Vector6<f64> {
    Vector6::new(m[(2, 1)], m[(0, 2)], m[(1, 0)], m[(0, 3)], m[(1, 3)], m[(2, 3)])
}

/// $e^{X}$ by 20 Taylor terms of $X/2^{10}$, squared 10 times.
fn matrix_exp(x: &Matrix4<f64>) -> Matrix4<f64> {
    let a = x / 1024.0;
    let (mut sum, mut term) = (Matrix4::identity(), Matrix4::identity());
    for k in 1..20 {
        term = term * a / k as f64;
        sum += term;
    }
    for _ in 0..10 {
        sum = sum * sum;
    }
    sum
}

fn poses() -> impl Strategy<Value = Isometry3<f64>> {
    (prop::array::uniform3(-2.0..2.0f64), prop::array::uniform3(-1.5..1.5f64))
        .prop_map(|(p, w)| Isometry3::new(Vector3::from(p), Vector3::from(w)))
}

fn twists() -> impl Strategy<Value = Vector6<f64>> {
    prop::array::uniform6(-1.7..1.7f64).prop_map(Vector6::from)
}

proptest! {
    /// Compose, inverse and act are the homogeneous matrices' product,
    /// inverse and product with $(r, 1)$; rotate drops the translation.
    /// Tolerance 1e-13: a few roundings of numbers of order 10.
    #[test]
    fn group_operations_are_matrix_products(a in poses(), b in poses(), r in prop::array::uniform3(-2.0..2.0f64)) {
        prop_assert!((matrix(&Spatial::compose(&a, &b)) - matrix(&a) * matrix(&b)).abs().max() < 1e-13);
        prop_assert!((matrix(&Spatial::inverse(&a)) - matrix(&a).try_inverse().unwrap()).abs().max() < 1e-13);
        let m = matrix(&a) * nalgebra::Vector4::new(r[0], r[1], r[2], 1.0);
        let w = Spatial::act(&a, &Point3::from(r));
        prop_assert!((w.coords - m.xyz()).abs().max() < 1e-13);
        let d = matrix(&a) * nalgebra::Vector4::new(r[0], r[1], r[2], 0.0);
        prop_assert!((Spatial::rotate(&a, &Vector3::from(r)) - d.xyz()).abs().max() < 1e-13);
    }

    /// exp is the matrix exponential of the hat (1e-12, the squaring's
    /// rounding); log inverts it for angles below π (1e-11).
    #[test]
    fn exp_is_the_matrix_exponential_and_log_inverts_it(t in twists()) {
        let g = Spatial::exp(&t);
        prop_assert!((matrix(&g) - matrix_exp(&hat(&t))).abs().max() < 1e-12);
        let back = Spatial::log(&g);
        prop_assert!((back - t).abs().max() < 1e-11, "{} against {}", back, t);
    }

    /// The derivative of exp along δ, as a body twist, is
    /// $\mathrm{dexp}_{-\xi}\delta = \int_0^1 \mathrm{Ad}_{\exp(-s\xi)}\delta\thinspace ds$;
    /// central differences of exp (step 1e-6, tolerance 1e-8) against that
    /// integral by 12-point Gauss–Legendre of the matrix exponentials (whose
    /// integrand is smooth; error below 1e-13).
    #[test]
    fn exp_differentiates_as_its_tangent(t in twists(), d in twists()) {
        let h = 1e-6;
        let g = matrix(&Spatial::exp(&t));
        let fd = (matrix(&Spatial::exp(&(t + d * h))) - matrix(&Spatial::exp(&(t - d * h)))) / (2.0 * h);
        let body = vee(&(g.try_inverse().unwrap() * fd));
        let rule = flexure::quadrature::GaussLegendre::new(12).unwrap();
        let mut integral = Vector6::zeros();
        for (&s, &w) in rule.nodes().iter().zip(rule.weights()) {
            let e = matrix_exp(&hat(&(-t * s)));
            integral += vee(&(e * hat(&d) * e.try_inverse().unwrap())) * w;
        }
        prop_assert!((body - integral).abs().max() < 1e-8, "{} against {}", body, integral);
    }

    /// $\mathrm{Ad}_g\xi = (g\hat\xi g^{-1})^\vee$ (1e-13); Ad of a product is
    /// the product of the Ads; power is frame-free,
    /// $w^{\prime}\cdot\mathrm{Ad}_g\xi = (\mathrm{Ad}_g^Tw^{\prime})\cdot\xi$.
    #[test]
    fn adjoint_conjugates_and_power_is_frame_free(a in poses(), b in poses(), t in twists(), w in twists()) {
        let conj = vee(&(matrix(&a) * hat(&t) * matrix(&a).try_inverse().unwrap()));
        prop_assert!((Spatial::adjoint(&a) * t - conj).abs().max() < 1e-13);
        let ab = Spatial::adjoint(&Spatial::compose(&a, &b));
        prop_assert!((ab - Spatial::adjoint(&a) * Spatial::adjoint(&b)).abs().max() < 1e-13);
        let moved = Spatial::adjoint(&a) * t;
        let pulled = Spatial::adjoint(&a).transpose() * w;
        prop_assert!((Spatial::power(&w, &moved) - Spatial::power(&pulled, &t)).abs() < 1e-12);
    }

    /// A point's velocity under a twist is the derivative of
    /// $\exp(\epsilon\xi)\cdot r$ at 0 (central differences, step 1e-6, tolerance 1e-8).
    #[test]
    fn velocity_at_is_the_derivative_of_acting(t in twists(), r in prop::array::uniform3(-2.0..2.0f64)) {
        let h = 1e-6;
        let at = |e: f64| Spatial::act(&Spatial::exp(&(t * e)), &Point3::from(r));
        let fd = (at(h) - at(-h)) / (2.0 * h);
        prop_assert!((Spatial::velocity_at(&t, &Vector3::from(r)) - fd).abs().max() < 1e-8);
    }

    /// The plane embeds: planar poses mapped into SE(3) compose, invert and
    /// exponentiate as they do in SE(2), to 1e-13.
    #[test]
    fn planar_poses_and_twists_embed(phi in -3.0..3.0f64, x in -2.0..2.0f64, y in -2.0..2.0f64, psi in -3.0..3.0f64, w in -3.0..3.0f64) {
        let a = Pose { phi, x, y };
        let b = Pose { phi: psi, x: y, y: -x };
        let embed = Spatial::from_planar_pose;
        let both = Spatial::compose(&embed(&a), &embed(&b));
        prop_assert!((matrix(&both) - matrix(&embed(&Planar::compose(&a, &b)))).abs().max() < 1e-13);
        prop_assert!((matrix(&Spatial::inverse(&embed(&a))) - matrix(&embed(&Planar::inverse(&a)))).abs().max() < 1e-13);
        let t = Twist { omega: w, vx: x, vy: y };
        let g = Spatial::exp(&Spatial::from_planar_twist(&t));
        prop_assert!((matrix(&g) - matrix(&embed(&Planar::exp(&t)))).abs().max() < 1e-13);
    }
}

/// $e^X$ by 40 Taylor terms without scaling: for $\lVert X\rVert \le 2.5$ the
/// first term left out is below 1e-30, and no squaring adds rounding.
fn taylor_exp(x: &Matrix4<f64>) -> Matrix4<f64> {
    let (mut sum, mut term) = (Matrix4::identity(), Matrix4::identity());
    for k in 1..40 {
        term = term * x / k as f64;
        sum += term;
    }
    sum
}

/// exp and log keep full precision through a zero angle, where the
/// quotients $f_m$ would cancel, and on both sides of the series' switch
/// ($\theta = 2$) and log's ($\theta = 0.1$), against the unscaled Taylor
/// series (tolerance 2e-15 on numbers of order 1); log is right at angle π
/// (1e-12: there the axis is ill-conditioned).
#[test]
fn exp_and_log_are_accurate_at_zero_and_pi() {
    for w in [0.0, 1e-12, -3e-9, 1e-4, 0.0999, 0.1001, 1.999, 2.001] {
        let t = Vector6::new(w * 0.6, -w * 0.8, 0.0, 1.0, -0.5, 0.25);
        let g = Spatial::exp(&t);
        let e = (matrix(&g) - taylor_exp(&hat(&t))).abs().max();
        assert!(e < 2e-15, "exp at {w}: {e:e}");
        let e = (Spatial::log(&g) - t).abs().max();
        assert!(e < 2e-15, "log at {w}: {e:e}");
    }
    let t = Vector6::new(0.0, 0.0, std::f64::consts::PI, 1.0, 2.0, 3.0);
    let back = Spatial::log(&Spatial::exp(&t));
    assert!((back[2].abs() - std::f64::consts::PI).abs() < 1e-12);
    assert!((matrix(&Spatial::exp(&back)) - matrix(&Spatial::exp(&t))).abs().max() < 1e-12);
}
