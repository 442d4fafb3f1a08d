//! The spatial flexure's SE(3) kinematics (`flexure::spatial`) against
//! independent references: central differences and num-dual numbers for
//! the body Jacobian and the Hessians, the Hessians' symmetry, the Magnus
//! method's order, closed forms for constant curvature (a circle, a helix)
//! and the planar flexure for in-plane shapes.

use flexure::section::SpatialSection;
use flexure::spatial::{SpatialFlexure, SpatialKinematics, pose_root_tip, update};
use flexure::{Flexure, Kinematics, Level, update_kinematics};
use nalgebra::{Matrix3, Vector3, Vector6};
use num_dual::{Dual64, HyperDual64};

fn flexure(orders: [usize; 3]) -> SpatialFlexure {
    SpatialFlexure::new(0.8, SpatialSection::uniform(0.6, 1.2, 1.0).unwrap(), orders).unwrap()
}

/// A bent and twisted shape of moderate curvature: about a radian per
/// component, every coefficient nonzero.
const ALPHA: [f64; 9] = [0.7, -0.3, 0.2, -0.9, 0.4, 0.25, 1.1, -0.5, 0.3];

fn vee(m: &Matrix3<f64>) -> Vector3<f64> {
    Vector3::new(m[(2, 1)], m[(0, 2)], m[(1, 0)])
}

/// The body twist $(\mathrm{vee}(R^T\dot R), R^T\dot p)$ of a derivative $(\dot R, \dot p)$.
fn body(r: &Matrix3<f64>, dr: &Matrix3<f64>, dp: &Vector3<f64>) -> Vector6<f64> {
    let w = vee(&(r.transpose() * dr));
    let v = r.transpose() * dp;
    Vector6::new(w[0], w[1], w[2], v[0], v[1], v[2])
}

fn column(k: &SpatialKinematics, a: usize) -> Vector6<f64> {
    Vector6::from_iterator(k.jacobian.column(a).iter().copied())
}

fn kinematics(f: &SpatialFlexure, alpha: &[f64], level: Level) -> SpatialKinematics {
    let mut k = SpatialKinematics::new(f);
    update(f, alpha, level, &mut k);
    k
}

fn shifted(alpha: &[f64], a: usize, h: f64) -> Vec<f64> {
    let mut x = alpha.to_vec();
    x[a] += h;
    x
}

/// The body Jacobian against central differences of the pose (step 1e-5:
/// truncation ~1e-10, rounding ~1e-11; tolerance 1e-8) and against
/// num-dual's dual numbers through the same pose code (tolerance 1e-13).
///
/// Also with 2 subintervals at 4 × `ALPHA`, where each step turns by more
/// than 2 rad and the exponential's coefficients take their closed forms
/// instead of their series.
#[test]
fn jacobian_matches_central_differences_and_dual_numbers() {
    jacobian_check(&flexure([3, 3, 3]), &ALPHA);
    let strong: Vec<f64> = ALPHA.iter().map(|a| 4.0 * a).collect();
    jacobian_check(&flexure([3, 3, 3]).with_subintervals(2).unwrap(), &strong);
    // Past 18 coordinates the step's tangents are combined from those
    // along its nodal directions (issue 39's order cap, made faster).
    let many: Vec<f64> = (0..39).map(|i| ALPHA[i % 9] / (1 + i / 9) as f64).collect();
    jacobian_check(&flexure([13, 13, 13]), &many);
}

fn jacobian_check(f: &SpatialFlexure, alpha: &[f64]) {
    let scale = alpha.iter().fold(1.0f64, |m, a| m.max(a.abs()));
    let k = kinematics(f, alpha, Level::Jacobian);
    let h = 1e-5;
    let n = alpha.len();
    for a in 0..n {
        let (rp, pp) = pose_root_tip(f, &shifted(alpha, a, h));
        let (rm, pm) = pose_root_tip(f, &shifted(alpha, a, -h));
        let fd = body(&k.rotation, &((rp - rm) / (2.0 * h)), &((pp - pm) / (2.0 * h)));
        let col = column(&k, a);
        assert!((col - fd).abs().max() < 1e-8 * scale * scale, "column {a}: {col} against {fd}");

        let x: Vec<Dual64> = (0..n).map(|i| Dual64::new(alpha[i], if i == a { 1.0 } else { 0.0 })).collect();
        let (r, p) = pose_root_tip(f, &x);
        let dual = body(&k.rotation, &r.map(|v| v.eps), &p.map(|v| v.eps));
        assert!((col - dual).abs().max() < 1e-13 * scale, "column {a}: {col} against num-dual {dual}");
    }
}

/// $H_{ab} = \partial_bJ_a$ against central differences of the Jacobian
/// (step 1e-5, tolerance 1e-8) and against hyper-dual numbers through the
/// pose code, $\partial_b(R^T\partial_aR) = \partial_bR^T\partial_aR + R^T\partial_{ab}R$
/// (tolerance 1e-12); the position's Hessian against the hyper-duals'
/// $\partial_{ab}p$ (tolerance 1e-12).
/// Also at 2 subintervals and 4 × `ALPHA`, the coefficients' closed forms
/// (tolerances times the largest coefficient's square and cube).
#[test]
fn hessians_match_central_differences_and_hyper_duals() {
    hessian_check(&flexure([3, 3, 3]), &ALPHA);
    let strong: Vec<f64> = ALPHA.iter().map(|a| 4.0 * a).collect();
    hessian_check(&flexure([3, 3, 3]).with_subintervals(2).unwrap(), &strong);
    // Past 36 coordinates the step's second derivatives are combined from
    // those along its nodal directions (issue 39's order cap, made faster).
    let many: Vec<f64> = (0..39).map(|i| ALPHA[i % 9] / (1 + i / 9) as f64).collect();
    hessian_check(&flexure([13, 13, 13]), &many);
}

fn hessian_check(f: &SpatialFlexure, alpha: &[f64]) {
    let scale = alpha.iter().fold(1.0f64, |m, a| m.max(a.abs()));
    let k = kinematics(f, alpha, Level::Hessian);
    let h = 1e-5;
    let n = alpha.len();
    for b in 0..n {
        let kp = kinematics(f, &shifted(alpha, b, h), Level::Jacobian);
        let km = kinematics(f, &shifted(alpha, b, -h), Level::Jacobian);
        for a in 0..n {
            let fd = (column(&kp, a) - column(&km, a)) / (2.0 * h);
            let hab = k.hessian(a, b);
            assert!((hab - fd).abs().max() < 1e-8 * scale.powi(3), "H[{a}][{b}] = {hab} against {fd}");

            let x: Vec<HyperDual64> =
                (0..n).map(|i| HyperDual64::new(alpha[i], (i == a) as u8 as f64, (i == b) as u8 as f64, 0.0)).collect();
            let (r, p) = pose_root_tip(f, &x);
            let (r0, ra, rb, rab) = (r.map(|v| v.re), r.map(|v| v.eps1), r.map(|v| v.eps2), r.map(|v| v.eps1eps2));
            let (pa, pab) = (p.map(|v| v.eps1), p.map(|v| v.eps1eps2));
            let w = vee(&(rb.transpose() * ra + r0.transpose() * rab));
            let v = rb.transpose() * pa + r0.transpose() * pab;
            let dual = Vector6::new(w[0], w[1], w[2], v[0], v[1], v[2]);
            assert!((hab - dual).abs().max() < 1e-12 * scale.powi(2), "H[{a}][{b}] = {hab} against hyper-dual {dual}");
            let hp = k.hessian_position(a, b);
            assert!((hp - pab).abs().max() < 1e-12 * scale.powi(2), "∂²p[{a}][{b}] = {hp} against hyper-dual {pab}");
        }
    }
}

/// Each pair is propagated on its own, so the two structural identities
/// check the pass: the position's Hessian is symmetric, and
/// $H_{ab} - H_{ba} = [J_a, J_b]$ (Maurer–Cartan), both to 1e-13.
#[test]
fn hessians_are_symmetric_and_meet_maurer_cartan() {
    let f = flexure([3, 2, 4]);
    let k = kinematics(&f, &ALPHA, Level::Hessian);
    let j = |a: usize| column(&k, a);
    for a in 0..9 {
        for b in 0..9 {
            let asym = (k.hessian_position(a, b) - k.hessian_position(b, a)).abs().max();
            assert!(asym < 1e-13, "∂²p[{a}][{b}] − ∂²p[{b}][{a}] = {asym:e}");
            let mc = k.hessian(a, b) - k.hessian(b, a) - flexure::space::Spatial::bracket(&j(a), &j(b));
            assert!(mc.abs().max() < 1e-13, "Maurer–Cartan at ({a}, {b}): {mc}");
        }
    }
}

/// The tip pose's error against 2048 subintervals (converged to rounding)
/// at `alpha` with `m` subintervals: the position's, and the rotation's
/// Frobenius error times L.
fn magnus_error(alpha: &[f64], m: usize) -> f64 {
    let reference = flexure([3, 3, 3]).with_subintervals(2048).unwrap();
    let (r0, p0) = pose_root_tip(&reference, alpha);
    let f = flexure([3, 3, 3]).with_subintervals(m).unwrap();
    let (r, p) = pose_root_tip(&f, alpha);
    (p - p0).norm().max((r - r0).norm() * f.length())
}

/// The error falls as $M^{-6}$ (6th-order Magnus): the slopes between
/// successive doublings of $M$ from 2 to 32 lie in [5.7, 6.3] on a log
/// scale (measured 5.95–6.0).
#[test]
fn magnus_converges_at_sixth_order() {
    let errors: Vec<f64> = [2, 4, 8, 16, 32].iter().map(|&m| magnus_error(&ALPHA, m)).collect();
    for w in errors.windows(2) {
        let slope = (w[0] / w[1]).log2();
        assert!((5.7..=6.3).contains(&slope), "slope {slope} from errors {errors:?}");
    }
}

/// The default 8 subintervals' pose error, measured against 2048 (the
/// numbers in `DEFAULT_SUBINTERVALS`' docs): within 1e-10·L for
/// coefficients a quarter of `ALPHA`'s (tip rotations up to 0.3 rad per
/// component; measured 7.2e-11·L), within 1e-9·L at half of them
/// (measured 6.1e-10·L), and 9.4e-9·L at `ALPHA` itself (bound 2e-8·L).
#[test]
fn default_subintervals_error() {
    let l = flexure([3, 3, 3]).length();
    let m = flexure::spatial::DEFAULT_SUBINTERVALS;
    for (scale, bound) in [(0.25, 1e-10), (0.5, 1e-9), (1.0, 2e-8)] {
        let a: Vec<f64> = ALPHA.iter().map(|x| x * scale).collect();
        let e = magnus_error(&a, m);
        assert!(e < bound * l, "scale {scale}: {e:e} m");
    }
}

/// A circle (κ_z constant, 2.5 rad over L) is exact to rounding:
/// $x = \frac L\theta\sin\theta$, $y = \frac L\theta(1 - \cos\theta)$, to 1e-15.
#[test]
fn a_circle_is_exact_to_rounding() {
    let f = flexure([3, 3, 3]);
    let theta: f64 = 2.5;
    let mut alpha = [0.0; 9];
    alpha[6] = theta;
    let (r, p) = pose_root_tip(&f, &alpha);
    let l = f.length();
    assert!((p.x - l / theta * theta.sin()).abs() < 1e-15 && (p.y - l / theta * (1.0 - theta.cos())).abs() < 1e-15);
    assert!(p.z == 0.0);
    assert!((r[(0, 0)] - theta.cos()).abs() < 1e-15 && (r[(1, 0)] - theta.sin()).abs() < 1e-15);
}

/// The 4×4 exponential of a hat by a Taylor series after scaling by
/// $2^{-10}$ and squaring back: independent of the library's Rodrigues form.
fn matrix_exp(xi: &Vector6<f64>) -> nalgebra::Matrix4<f64> {
    let mut m = nalgebra::Matrix4::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&Vector3::new(xi[0], xi[1], xi[2]).cross_matrix());
    m.fixed_view_mut::<3, 1>(0, 3).copy_from(&Vector3::new(xi[3], xi[4], xi[5]));
    let a = m / 1024.0;
    let (mut sum, mut term) = (nalgebra::Matrix4::identity(), nalgebra::Matrix4::identity());
    for k in 1..20 {
        term = term * a / k as f64;
        sum += term;
    }
    for _ in 0..10 {
        sum = sum * sum;
    }
    sum
}

/// A helix: constant twist and bending, $u = (0.9, -0.6, 1.3)/L$, is the
/// exponential of the constant twist $L(u, e_1)$: against Rodrigues written
/// out here with sin and cos (1e-14) and the 4×4 matrix exponential (1e-12,
/// the squaring's rounding).
#[test]
fn a_helix_is_the_exponential_of_its_constant_twist() {
    let f = flexure([3, 3, 3]);
    let mut alpha = [0.0; 9];
    (alpha[0], alpha[3], alpha[6]) = (0.9, -0.6, 1.3);
    let (r, p) = pose_root_tip(&f, &alpha);
    let w = Vector3::new(0.9f64, -0.6, 1.3);
    let v = Vector3::new(f.length(), 0.0, 0.0);
    let theta = w.norm();
    let k = w.cross_matrix();
    let rot = Matrix3::identity() + k * (theta.sin() / theta) + k * k * ((1.0 - theta.cos()) / (theta * theta));
    let vm = Matrix3::identity()
        + k * ((1.0 - theta.cos()) / (theta * theta))
        + k * k * ((theta - theta.sin()) / theta.powi(3));
    assert!((r - rot).abs().max() < 1e-14 && (p - vm * v).abs().max() < 1e-14, "{p} against {}", vm * v);
    let e = matrix_exp(&Vector6::new(w[0], w[1], w[2], v[0], v[1], v[2]));
    assert!((r - e.fixed_view::<3, 3>(0, 0)).abs().max() < 1e-12);
    assert!((p - e.fixed_view::<3, 1>(0, 3)).abs().max() < 1e-12);
}

/// Only κ_z nonzero: the shape stays in the plane (z, r_x, r_y exactly
/// zero in pose, Jacobian and position Hessian) and meets the planar
/// flexure of the same order and EI. With 64 subintervals (Magnus error
/// ~1e-15) against the planar model with a 40-point rule (its quadrature
/// error below 1e-15), the pose, the in-plane Jacobian rows (the body twist
/// rotated into the root frame) and the Hessians of x and y agree to 1e-13.
/// At the defaults on both sides, the difference is the planar 5-point
/// rule's own error (measured 7.0e-8 m) plus the Magnus error of 8
/// subintervals (measured 1.3e-9 m); tolerance 1e-7.
#[test]
fn in_plane_shapes_meet_the_planar_flexure() {
    let f = flexure([3, 3, 3]).with_subintervals(64).unwrap();
    let kz = [1.1, -0.5, 0.3];
    let mut alpha = [0.0; 9];
    alpha[6..].copy_from_slice(&kz);
    let k = kinematics(&f, &alpha, Level::Hessian);
    assert!(k.position.z == 0.0 && k.rotation[(2, 0)] == 0.0 && k.rotation[(2, 1)] == 0.0);
    let planar = Flexure::with_points(f.length(), 1.0, 3, 40).unwrap();
    let mut pk = Kinematics::new(&planar);
    update_kinematics(&planar, &kz, &mut pk, Level::Hessian);
    let pose = pk.pose_root_tip;
    let tol = 1e-13;
    assert!((k.position.x - pose.x).abs() < tol && (k.position.y - pose.y).abs() < tol);
    assert!((k.rotation[(1, 0)].atan2(k.rotation[(0, 0)]) - pose.phi).abs() < 1e-14);
    for i in 0..3 {
        let col = column(&k, 6 + i);
        assert!(col[0] == 0.0 && col[1] == 0.0 && col[5] == 0.0, "column {i} leaves the plane: {col}");
        let lin = k.rotation * Vector3::new(col[3], col[4], col[5]);
        assert!((col[2] - pk.jacobian_root_tip[(0, i)]).abs() < 1e-14);
        assert!(
            (lin.x - pk.jacobian_root_tip[(1, i)]).abs() < tol && (lin.y - pk.jacobian_root_tip[(2, i)]).abs() < tol
        );
        for j in 0..3 {
            let hp = k.hessian_position(6 + i, 6 + j);
            assert!(
                (hp.x - pk.hessian_root_tip_x[(i, j)]).abs() < tol
                    && (hp.y - pk.hessian_root_tip_y[(i, j)]).abs() < tol
            );
            assert!(hp.z == 0.0);
        }
    }
    let (_, p) = pose_root_tip(&flexure([3, 3, 3]), &alpha);
    let coarse = flexure::pose_root_tip(&Flexure::new(f.length(), 1.0, 3).unwrap(), &kz);
    assert!((p.x - coarse.x).abs() < 1e-7 && (p.y - coarse.y).abs() < 1e-7);
}

/// Bad input is an error naming the parameter, never a panic.
#[test]
fn bad_input_names_the_parameter() {
    let s = SpatialSection::uniform(1.0, 1.0, 1.0).unwrap();
    let name = |e: flexure::Error| match e {
        flexure::Error::InvalidParameter { name, .. } => name,
        other => panic!("{other}"),
    };
    assert_eq!(name(SpatialFlexure::new(-1.0, s.clone(), [3, 3, 3]).unwrap_err()), "length");
    assert_eq!(name(SpatialFlexure::new(1.0, s.clone(), [3, 65, 3]).unwrap_err()), "order");
    assert_eq!(name(flexure([3, 3, 3]).with_subintervals(0).unwrap_err()), "subintervals");
    assert_eq!(name(flexure([3, 3, 3]).with_rest(&[f64::NAN; 9]).unwrap_err()), "rest");
    assert_eq!(name(flexure([3, 3, 3]).check_coordinates("alpha", &[0.0; 8]).unwrap_err()), "alpha");
}
