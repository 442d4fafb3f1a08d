//! Kinematics against closed forms, and every hand-written derivative
//! (Eqs. 20–21, 30–31) three ways: central differences, num-dual, symmetry.

use flexure::{Flexure, Kinematics, Level, Pose, pose_root_tip, update_kinematics};
use num_dual::{Dual64, HyperDual64};
use proptest::prelude::*;

fn flexure(order: usize) -> Flexure {
    Flexure::new(0.7, 2.0, order).unwrap()
}

/// Circular arc (all α but α₁ zero): x = L sin a / a, y = L (1 − cos a)/a.
/// Tolerance 1e-9 L: the 5-point rule's error on cos(a t) for |a| ≤ 2.
#[test]
fn constant_curvature_is_a_circular_arc() {
    let f = flexure(3);
    for a in [-2.0, -0.5, 0.3, 1.0, 2.0_f64] {
        let p = pose_root_tip(&f, &[a, 0.0, 0.0]);
        assert!((p.x - 0.7 * a.sin() / a).abs() < 1e-9 * 0.7, "x at a={a}");
        assert!((p.y - 0.7 * (1.0 - a.cos()) / a).abs() < 1e-9 * 0.7, "y at a={a}");
        assert_eq!(p.phi, a, "Eq. 11: the tip angle is α₁");
    }
}

/// The straight flexure's tip Jacobian and Hessians are polynomial integrals
/// (Eq. 39 and ∂y/∂α = L∫ψ): exact fractions, to rounding.
#[test]
fn straight_flexure_matches_exact_fractions() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let mut k = Kinematics::new(&f);
    update_kinematics(&f, &[0.0; 3], &mut k, Level::Hessian);
    let eq39 = [[-1.0 / 3.0, 1.0 / 12.0, 1.0 / 60.0], [1.0 / 12.0, -1.0 / 30.0, 0.0], [1.0 / 60.0, 0.0, -1.0 / 210.0]];
    for i in 0..3 {
        for j in 0..3 {
            assert!((k.hessian_root_tip_x[(i, j)] - eq39[i][j]).abs() < 1e-15, "Eq. 39 ({i},{j})");
            assert!(k.hessian_root_tip_y[(i, j)].abs() < 1e-15);
        }
    }
    let jy = [0.5, -1.0 / 6.0, 0.0];
    for i in 0..3 {
        assert!((k.jacobian_root_tip[(2, i)] - jy[i]).abs() < 1e-15);
        assert!(k.jacobian_root_tip[(1, i)].abs() < 1e-15);
    }
}

/// `update` at Level::Pose gives the same pose as the workspace-free function.
#[test]
fn pose_levels_agree() {
    let f = flexure(5);
    let a = [0.4, -0.3, 0.2, 0.1, -0.05];
    let mut k = Kinematics::new(&f);
    update_kinematics(&f, &a, &mut k, Level::Pose);
    assert_eq!(k.pose_root_tip, pose_root_tip(&f, &a));
}

/// The batch API fills exactly the poses the single-pose function gives, for
/// fixed-size and any-order kernels, serially and in parallel over chunks
/// (9000 poses span three); a length mismatch is an error naming `alpha`.
#[test]
fn batch_matches_single_poses() {
    use flexure::kinematics::{par_poses_root_tip, poses_root_tip};
    for order in 1..=8 {
        let f = flexure(order);
        for count in [0, 1, 2, 5, 9000] {
            let alphas: Vec<f64> = (0..count * order).map(|i| ((i * 7919) % 1000) as f64 / 400.0 - 1.25).collect();
            let single: Vec<Pose> = alphas.chunks_exact(order).map(|a| pose_root_tip(&f, a)).collect();
            let mut serial = vec![Pose::default(); count];
            let mut parallel = vec![Pose::default(); count];
            poses_root_tip(&f, &alphas, &mut serial).unwrap();
            par_poses_root_tip(&f, &alphas, &mut parallel).unwrap();
            assert!(serial == single && parallel == single, "order {order}, {count} poses");
        }
        let err = poses_root_tip(&f, &[0.0; 9], &mut [Pose::default(); 2]).unwrap_err().to_string();
        assert!(err.contains("alpha") && err.contains("9 values for 2 poses"), "{err}");
    }
}

/// Buffers made for another quadrature rule are refused, not misread.
#[test]
#[should_panic(expected = "another order or quadrature rule")]
fn buffers_of_another_rule_are_refused() {
    let f = flexure(3);
    let mut k = Kinematics::new(&f.clone().with_quadrature(9).unwrap());
    update_kinematics(&f, &[0.1, 0.2, 0.3], &mut k, Level::Hessian);
}

/// Eq. 7: the transform composes like the pose it came from.
#[test]
fn transform_is_rigid() {
    let g = Pose { phi: 0.8, x: 0.3, y: -0.2 }.transform();
    let r = g.fixed_view::<2, 2>(0, 0);
    assert!((r.transpose() * r - nalgebra::Matrix2::identity()).amax() < 1e-15);
    assert!((r.determinant() - 1.0).abs() < 1e-15);
}

fn check_derivatives(order: usize, alpha: &[f64]) {
    let f = flexure(order);
    let mut k = Kinematics::new(&f);
    update_kinematics(&f, alpha, &mut k, Level::Hessian);
    let n = order;
    // Central differences: error O(h²) + rounding O(ε/h); h = 1e-5 gives ~1e-9.
    let h = 1e-5;
    for i in 0..n {
        let (mut up, mut dn) = (alpha.to_vec(), alpha.to_vec());
        up[i] += h;
        dn[i] -= h;
        let (pu, pd) = (pose_root_tip(&f, &up), pose_root_tip(&f, &dn));
        let fd = [(pu.phi - pd.phi) / (2.0 * h), (pu.x - pd.x) / (2.0 * h), (pu.y - pd.y) / (2.0 * h)];
        for r in 0..3 {
            assert!((k.jacobian_root_tip[(r, i)] - fd[r]).abs() < 1e-8, "J[{r},{i}] vs central difference");
        }
        let (mut ku, mut kd) = (Kinematics::new(&f), Kinematics::new(&f));
        update_kinematics(&f, &up, &mut ku, Level::Jacobian);
        update_kinematics(&f, &dn, &mut kd, Level::Jacobian);
        for j in 0..n {
            let fdx = (ku.jacobian_root_tip[(1, j)] - kd.jacobian_root_tip[(1, j)]) / (2.0 * h);
            let fdy = (ku.jacobian_root_tip[(2, j)] - kd.jacobian_root_tip[(2, j)]) / (2.0 * h);
            assert!((k.hessian_root_tip_x[(i, j)] - fdx).abs() < 1e-8, "Hx[{i},{j}] vs central difference");
            assert!((k.hessian_root_tip_y[(i, j)] - fdy).abs() < 1e-8, "Hy[{i},{j}] vs central difference");
        }
    }
    // num-dual: first derivatives with Dual64, second with HyperDual64; exact to rounding.
    for i in 0..n {
        let a: Vec<Dual64> = (0..n).map(|m| Dual64::new(alpha[m], if m == i { 1.0 } else { 0.0 })).collect();
        let p = pose_root_tip(&f, &a);
        for (r, d) in [p.phi.eps, p.x.eps, p.y.eps].into_iter().enumerate() {
            assert!((k.jacobian_root_tip[(r, i)] - d).abs() < 1e-13, "J[{r},{i}] vs num-dual");
        }
        for j in 0..n {
            let a: Vec<HyperDual64> =
                (0..n).map(|m| HyperDual64::new(alpha[m], (m == i) as u8 as f64, (m == j) as u8 as f64, 0.0)).collect();
            let p = pose_root_tip(&f, &a);
            assert!((k.hessian_root_tip_x[(i, j)] - p.x.eps1eps2).abs() < 1e-13, "Hx[{i},{j}] vs num-dual");
            assert!((k.hessian_root_tip_y[(i, j)] - p.y.eps1eps2).abs() < 1e-13, "Hy[{i},{j}] vs num-dual");
            // Symmetry, exactly: both triangles come from one sum.
            assert_eq!(k.hessian_root_tip_x[(i, j)], k.hessian_root_tip_x[(j, i)]);
            assert_eq!(k.hessian_root_tip_y[(i, j)], k.hessian_root_tip_y[(j, i)]);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, rng_seed: proptest::test_runner::RngSeed::Fixed(7), ..ProptestConfig::default() })]
    #[test]
    fn derivatives_order_3(a in prop::array::uniform3(-2.0..2.0f64)) {
        check_derivatives(3, &a);
    }
    #[test]
    fn derivatives_order_6(a in prop::array::uniform6(-1.5..1.5f64)) {
        check_derivatives(6, &a);
    }
    // Order 8 runs the general (slice) kernel rather than a fixed-size one.
    #[test]
    fn derivatives_order_8(a in prop::array::uniform8(-1.0..1.0f64)) {
        check_derivatives(8, &a);
    }
}
