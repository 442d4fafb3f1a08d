//! Derivatives of a spatial mechanism's kinematics, potential and closures
//! (`mechanism::spatial::{kinematics, lagrangian}`), each against central
//! finite differences of the quantity it differentiates (step 1e-6, or 1e-5
//! for second derivatives from first; tolerance 1e-6 of the scale). The
//! last three compare the Hessian from Jacobian-level frames (the joints'
//! contracted Hessians, the spatial flexure's by quadrature) with the
//! full-Hessian path, each to its stated tolerance.

use flexure::Level;
use flexure::mechanism::Holds;
use flexure::mechanism::kinematics::{Frames, attach, frames, frames_level_into};
use flexure::mechanism::lagrangian::{Assembly, assemble_into, closures_into};
use flexure::mechanism::spatial::{
    PrismaticUnaligned, RevoluteUnaligned, SpatialBody, SpatialClosure, SpatialJointKind, SpatialJointSpec,
    SpatialLoads, SpatialMechanism, SpatialPointLoad, SpatialTendon, Spherical,
};
use flexure::mechanism::statics::{Solution, compliance, solve};
use flexure::mechanism::{Fixed, Joint, JointState};
use flexure::section::{Profile, SpatialSection};
use flexure::space::Spatial;
use flexure::spatial::{SpatialFlexure, SpatialSpec};
use nalgebra::{DMatrix, DVector, Isometry3, Matrix3, Point3, Translation3, Unit, UnitQuaternion, Vector3, Vector6};

fn body(name: &str, mass: f64, com: [f64; 3]) -> SpatialBody {
    SpatialBody { name: name.into(), mass, com: Point3::from(com), inertia: Matrix3::from_diagonal_element(1e-3) }
}

fn joint(name: &str, kind: SpatialJointKind, parent: usize, child: usize, origin: Isometry3<f64>) -> SpatialJointSpec {
    SpatialJointSpec::new(name, kind, parent, child, origin)
}

fn placed(p: [f64; 3], rpy: [f64; 3]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(p[0], p[1], p[2]),
        UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    )
}

/// A tree of every kind (flexure, hinge, ball, slider, weld), loaded by
/// gravity, a force with a moment and a tendon, closed by a ball, a weld and a pin.
fn mechanism() -> SpatialMechanism {
    let flexure = SpatialSpec {
        length: 0.1,
        ei_z: Some(Profile::Constant(0.02)),
        ei_y: Some(Profile::Constant(0.05)),
        gj: Some(Profile::Constant(0.03)),
        orders: [2, 2, 3],
        kappa_y: Some(vec![0.5, 0.0]),
        ..Default::default()
    }
    .build()
    .unwrap();
    let axis = Unit::new_normalize(Vector3::new(0.3, 0.5, 0.8));
    let bodies = vec![
        body("ground", 0.0, [0.0; 3]),
        body("a", 0.2, [0.01, 0.02, -0.01]),
        body("b", 0.1, [0.03, 0.0, 0.01]),
        body("c", 0.3, [0.0, -0.02, 0.02]),
        body("d", 0.05, [0.01, 0.01, 0.01]),
        body("e", 0.05, [0.0, 0.01, 0.0]),
    ];
    let joints = vec![
        joint("flex", SpatialJointKind::Flexure(Box::new(flexure)), 0, 1, placed([0.0, 0.01, 0.0], [0.1, -0.2, 0.3])),
        joint(
            "hinge",
            SpatialJointKind::Revolute(RevoluteUnaligned { axis, stiffness: 0.4, rest: 0.1 }),
            1,
            2,
            placed([0.02, 0.0, 0.01], [0.0, 0.4, 0.0]),
        ),
        joint(
            "ball",
            SpatialJointKind::Spherical(Spherical { stiffness: 0.3, rest: [0.0; 3] }),
            2,
            3,
            placed([0.05, 0.0, 0.0], [0.2, 0.0, -0.1]),
        ),
        joint(
            "slide",
            SpatialJointKind::Prismatic(PrismaticUnaligned { axis: Vector3::y_axis(), stiffness: 5.0, rest: 0.0 }),
            3,
            4,
            placed([0.0, 0.03, 0.0], [0.0, 0.0, 0.7]),
        ),
        joint("weld", SpatialJointKind::Fixed(Fixed), 4, 5, placed([0.01, 0.0, 0.02], [0.3, 0.2, 0.1])),
    ];
    let tendons = vec![SpatialTendon {
        name: "t".into(),
        tension: 2.0,
        path: vec![
            (0, Point3::new(0.0, 0.02, 0.0)),
            (1, Point3::new(0.01, 0.01, 0.0)),
            (3, Point3::new(0.0, 0.01, 0.02)),
            (5, Point3::new(0.0, 0.0, 0.01)),
        ],
    }];
    let forces = vec![SpatialPointLoad {
        name: "push".into(),
        body: 5,
        at: Point3::new(0.01, -0.01, 0.02),
        wrench: Vector6::new(0.03, -0.02, 0.05, 1.0, -2.0, 0.5),
    }];
    let closures = vec![
        SpatialClosure::at_points(Holds::Ball, 3, Point3::new(0.01, 0.0, 0.0), 0, Point3::new(0.1, 0.1, 0.0)),
        SpatialClosure {
            holds: Holds::Weld,
            a: 5,
            a_origin: placed([0.0, 0.01, 0.0], [0.2, 0.1, 0.0]),
            b: 0,
            b_origin: placed([0.1, 0.0, 0.05], [0.0, 0.3, 0.2]),
        },
        SpatialClosure::pin(
            4,
            Point3::new(0.0, 0.0, 0.01),
            Vector3::new(0.0, 1.0, 0.2),
            2,
            Point3::new(0.01, 0.0, 0.0),
            Vector3::new(0.3, 0.0, 1.0),
        )
        .unwrap(),
    ];
    SpatialMechanism::new(bodies, joints, tendons, forces, closures, Vector3::new(0.3, -9.81, 1.0)).unwrap()
}

/// A configuration away from rest, so no derivative vanishes by symmetry.
fn configuration(m: &SpatialMechanism) -> Vec<f64> {
    let mut q = m.rest();
    for (i, v) in q.iter_mut().enumerate() {
        *v += 0.3 * ((i as f64 * 1.7 + 0.4).sin());
    }
    q
}

fn assembled(m: &SpatialMechanism, q: &[f64], mu: &[f64], loads: &SpatialLoads) -> Assembly<Spatial> {
    let mut a = Assembly::new(m);
    assemble_into(m, &frames(m, q), mu, loads, true, &mut a).unwrap();
    a
}

fn step(q: &[f64], i: usize, h: f64) -> Vec<f64> {
    let mut p = q.to_vec();
    p[i] += h;
    p
}

fn close(a: f64, b: f64, scale: f64, tol: f64, what: &str) {
    assert!((a - b).abs() <= tol * scale, "{what}: {a} against {b} (scale {scale})");
}

#[test]
fn points_and_directions_have_the_jacobian_of_their_finite_differences() {
    let m = mechanism();
    let q = configuration(&m);
    let h = 1e-6;
    for point in [true, false] {
        let local = Vector3::new(0.01, -0.02, 0.03);
        let x = attach(&m, &frames(&m, &q), 5, local, point);
        for i in 0..m.dof() {
            let up = attach(&m, &frames(&m, &step(&q, i, h)), 5, local, point).value;
            let down = attach(&m, &frames(&m, &step(&q, i, -h)), 5, local, point).value;
            let fd = (up - down) / (2.0 * h);
            for c in 0..3 {
                close(x.jacobian[(3 + c, i)], fd[c], 1.0, 1e-7, "attached Jacobian");
            }
        }
    }
}

#[test]
fn the_gradient_is_the_potentials_without_moments_and_the_moments_virtual_work_with_them() {
    let m = mechanism();
    let q = configuration(&m);
    let mu = vec![0.0; m.constraints()];
    let mut loads = m.loads();
    let moment = Vector3::new(loads.force[0][0], loads.force[0][1], loads.force[0][2]);
    for c in 0..3 {
        loads.force[0][c] = 0.0;
    }
    let a = assembled(&m, &q, &mu, &loads);
    let h = 1e-6;
    let scale = a.gradient.amax();
    for i in 0..m.dof() {
        let fd = (assembled(&m, &step(&q, i, h), &mu, &loads).potential
            - assembled(&m, &step(&q, i, -h), &mu, &loads).potential)
            / (2.0 * h);
        close(a.gradient[i], fd, scale, 1e-7, "gradient of the potential");
    }
    // The moment alone: Q_i = m·ω_i, ω_i from the rotation's central difference.
    let mut only = loads.zero_like();
    only.force[0] = Vector6::new(moment.x, moment.y, moment.z, 0.0, 0.0, 0.0);
    let elastic = assembled(&m, &q, &mu, &loads.zero_like()).gradient;
    let with = assembled(&m, &q, &mu, &only).gradient;
    for i in 0..m.dof() {
        let up = *frames(&m, &step(&q, i, h)).body_rotation(5);
        let down = *frames(&m, &step(&q, i, -h)).body_rotation(5);
        // The small turn from down to up by its skew part (sin θ ≈ θ to 1e-12 here; acos would lose it).
        let u = up * down.transpose();
        let turn = Vector3::new(u[(2, 1)] - u[(1, 2)], u[(0, 2)] - u[(2, 0)], u[(1, 0)] - u[(0, 1)]) / (4.0 * h);
        close(elastic[i] - with[i], moment.dot(&turn), moment.norm(), 1e-7, "a moment's generalized force");
    }
}

#[test]
fn the_hessian_is_the_derivative_of_the_gradient_with_the_closures() {
    let m = mechanism();
    let q = configuration(&m);
    let mu: Vec<f64> = (0..m.constraints()).map(|i| 0.5 * (i as f64 + 1.0).cos()).collect();
    let loads = m.loads();
    let a = assembled(&m, &q, &mu, &loads);
    let force = |q: &[f64]| -> DVector<f64> {
        let b = assembled(&m, q, &mu, &loads);
        &b.gradient + b.closure_jacobian.transpose() * DVector::from_column_slice(&mu)
    };
    let h = 1e-5;
    let scale = a.hessian.amax();
    let mut fd = DMatrix::zeros(m.dof(), m.dof());
    for i in 0..m.dof() {
        fd.set_column(i, &((force(&step(&q, i, h)) - force(&step(&q, i, -h))) / (2.0 * h)));
    }
    for r in 0..m.dof() {
        for c in 0..m.dof() {
            close(a.hessian[(r, c)], fd[(r, c)], scale, 1e-6, &format!("Hessian ({r}, {c})"));
        }
    }
    // Not symmetric (the moment); symmetric without it.
    let mut loads = loads;
    for c in 0..3 {
        loads.force[0][c] = 0.0;
    }
    let s = assembled(&m, &q, &mu, &loads).hessian;
    assert!((&s - s.transpose()).amax() <= 1e-12 * s.amax());
}

#[test]
fn closures_have_the_jacobian_of_their_finite_differences() {
    let m = mechanism();
    let q = configuration(&m);
    let rows = m.constraints();
    assert_eq!(rows, 3 + 6 + 5);
    let c = |q: &[f64]| {
        let (mut c, mut g) = (DVector::zeros(rows), DMatrix::zeros(rows, m.dof()));
        closures_into(&m, &frames(&m, q), &mut c, &mut g);
        (c, g)
    };
    let (_, g) = c(&q);
    let h = 1e-6;
    for i in 0..m.dof() {
        let fd = (c(&step(&q, i, h)).0 - c(&step(&q, i, -h)).0) / (2.0 * h);
        for r in 0..rows {
            close(g[(r, i)], fd[r], 1.0, 1e-7, &format!("closure Jacobian ({r}, {i})"));
        }
    }
}

#[test]
fn a_weld_closure_is_zero_and_has_full_rank_where_its_frames_coincide() {
    // Weld body 5's frame to where it is: the six rows vanish, and at
    // coincidence the rotation rows are ω_a − ω_b, so G has rank 6.
    let mut m = mechanism();
    let q = configuration(&m);
    let f = frames(&m, &q);
    let here = f.bodies[5];
    m.closures =
        vec![SpatialClosure { holds: Holds::Weld, a: 5, a_origin: Isometry3::identity(), b: 0, b_origin: here }];
    let (mut c, mut g) = (DVector::zeros(6), DMatrix::zeros(6, m.dof()));
    closures_into(&m, &f, &mut c, &mut g);
    assert!(c.amax() < 1e-15, "{c}");
    let omega = f.omega.clone();
    for col in 0..m.dof() {
        for i in 0..3 {
            let on_path = m
                .path(5)
                .iter()
                .any(|&j| (m.joints[j].offset..m.joints[j].offset + m.joints[j].kind.joint().dof()).contains(&col));
            let expected = if on_path { omega[col][i] } else { 0.0 };
            close(g[(3 + i, col)], expected, 1.0, 1e-14, "weld rotation rows");
        }
    }
    assert_eq!(g.clone().svd(false, false).rank(1e-9), 6);
}

/// $\sum_c w_c\partial_bS^c_a$ from the joint's exact Hessian (the Magnus product's second derivatives).
fn exact_contraction(s: &JointState<Spatial>, w: &[f64]) -> DMatrix<f64> {
    let k = s.gradient.len();
    let mut d = DMatrix::zeros(k, k);
    for (h, wc) in s.hessian.iter().zip(w) {
        d += h * *wc;
    }
    d
}

/// The contraction from Jacobian-level data ([`Joint::add_wrench_hessian`]).
fn cheap_contraction(f: &SpatialFlexure, a: &[f64], w: &[f64]) -> DMatrix<f64> {
    let mut state = f.state();
    f.evaluate_level_into(a, Level::Jacobian, &mut state);
    let k = a.len();
    let mut d = DMatrix::zeros(k, k);
    f.add_wrench_hessian(a, &state, w, &mut d.view_mut((0, 0), (k, k)));
    d
}

const WRENCHES: [[f64; 6]; 4] = [
    [0.0, 0.0, 0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 0.0, 0.3, -1.0, 0.5],
    [0.1, -0.2, 0.3, 0.0, 0.0, 0.0],
    [0.03, -0.02, 0.05, 1.0, -2.0, 0.5],
];

/// A flexure of orders 3 at a bend of `bend` rad per coefficient, on `subintervals`.
fn bent(bend: f64, subintervals: usize) -> (SpatialFlexure, Vec<f64>) {
    let f = SpatialFlexure::new(0.1, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 3, 3])
        .unwrap()
        .with_subintervals(subintervals)
        .unwrap();
    (f, (0..9).map(|i| bend * (i as f64 * 2.3 + 0.7).sin()).collect())
}

/// The largest difference of the contractions over `WRENCHES`, relative
/// to each wrench's size $|M| + L|F|$, and the largest difference of their skew parts relative to the exact one's size.
fn contraction_errors(f: &SpatialFlexure, a: &[f64]) -> (f64, f64) {
    let exact = f.evaluate(a);
    let (mut error, mut skew) = (0.0f64, 0.0f64);
    for w in WRENCHES {
        let e = exact_contraction(&exact, &w);
        let c = cheap_contraction(f, a, &w);
        let size = Vector3::new(w[0], w[1], w[2]).norm() + f.length() * Vector3::new(w[3], w[4], w[5]).norm();
        error = error.max((&c - &e).amax() / size);
        let skew_part = |d: &DMatrix<f64>| (d - d.transpose()) * 0.5;
        skew = skew.max((skew_part(&c) - skew_part(&e)).amax() / e.amax());
    }
    (error, skew)
}

/// The spatial flexure's contraction by quadrature of the virtual work
/// against the exact one from the Magnus product's Hessian: the skew part
/// is exact (taken from the motion subspace, to rounding, 1e-13), and the
/// rest is the quadrature's, whose error falls as $h^6$ (measured: 63 times
/// from 8 to 16 subintervals; asserted at least 32) and is at most 3.1e-7
/// of the wrench at 8 subintervals and a bend of 1.5 rad per coefficient
/// (asserted 5e-7), 1.5e-8 on the test mechanism's flexure (asserted
/// 5e-8); the skew parts agree to 2e-16.
#[test]
fn a_flexures_contracted_hessian_meets_the_exact_one_to_the_quadratures_h6() {
    let m = mechanism();
    let q = configuration(&m);
    let SpatialJointKind::Flexure(f) = &m.joints[0].kind else { panic!("joint 0 is the flexure") };
    let (error, skew) = contraction_errors(f, &q[..f.coordinates()]);
    assert!(error <= 5e-8 && skew <= 1e-13, "the mechanism's flexure: {error:.3e}, skew {skew:.3e}");
    let mut errors = Vec::new();
    for subintervals in [8, 16] {
        let (f, a) = bent(1.5, subintervals);
        let (error, skew) = contraction_errors(&f, &a);
        assert!(skew <= 1e-13, "skew part on {subintervals}: {skew:.3e}");
        errors.push(error);
    }
    assert!(errors[0] <= 5e-7, "8 subintervals: {:.3e}", errors[0]);
    assert!(errors[0] >= 32.0 * errors[1], "h⁶: {:.3e} then {:.3e}", errors[0], errors[1]);
}

/// Past 18 coordinates the contraction's quadrature is a matrix product
/// (`spatial::work`, for the order cap's speed, issue 39): at orders
/// [8, 8, 8] (24 coordinates) and a bend of 0.5 rad per coefficient it
/// meets the exact contraction from the Magnus product's Hessian as the
/// point-by-point sum does at orders 3: the skew part to rounding (1e-13),
/// the rest to the quadrature's error, which falls as $h^6$ (measured:
/// 1.3e-8 of the wrench at the default 28 subintervals, 63 times less at 56;
/// asserted 5e-8 and at least 32 times).
#[test]
fn the_contraction_as_a_matrix_product_meets_the_exact_one() {
    let f = SpatialFlexure::new(0.1, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [8, 8, 8]).unwrap();
    let a: Vec<f64> = (0..24).map(|i| 0.5 * (i as f64 * 2.3 + 0.7).sin() / (1 + i % 8) as f64).collect();
    let (error, skew) = contraction_errors(&f, &a);
    let (finer, finer_skew) = contraction_errors(&f.clone().with_subintervals(56).unwrap(), &a);
    assert!(error <= 5e-8 && skew <= 1e-13 && finer_skew <= 1e-13, "{error:.3e}, skew {skew:.3e}");
    assert!(error >= 32.0 * finer, "h⁶: {error:.3e} then {finer:.3e}");
}

/// The assembled Hessian from Jacobian-level frames (each joint's
/// contraction: the flexure's by quadrature) against the full-Hessian path
/// (Hessian-level frames, the joints' own second derivatives; checked
/// against finite differences above): the same outside the flexure's own
/// block (measured identical; asserted to 1e-14 of the largest entry),
/// within 1e-8 of it inside (measured 2.3e-9), and symmetric without the
/// moment (1e-12, as above; measured 3e-17).
#[test]
fn jacobian_level_frames_give_the_full_hessian_but_for_the_flexures_quadrature() {
    let m = mechanism();
    let q = configuration(&m);
    let mu: Vec<f64> = (0..m.constraints()).map(|i| 0.5 * (i as f64 + 1.0).cos()).collect();
    let mut loads = m.loads();
    let cheap = |loads: &SpatialLoads| {
        let mut f = Frames::new(&m);
        frames_level_into(&m, &q, Level::Jacobian, &mut f);
        assert_eq!(f.level(), Level::Jacobian);
        let mut a = Assembly::new(&m);
        assemble_into(&m, &f, &mu, loads, true, &mut a).unwrap();
        a.hessian
    };
    let exact = assembled(&m, &q, &mu, &loads).hessian;
    let h = cheap(&loads);
    let scale = exact.amax();
    let k = m.joints[0].kind.joint().dof();
    for r in 0..m.dof() {
        for c in 0..m.dof() {
            let tol = if r < k && c < k { 1e-8 } else { 1e-14 };
            close(h[(r, c)], exact[(r, c)], scale, tol, &format!("Hessian ({r}, {c})"));
        }
    }
    for c in 0..3 {
        loads.force[0][c] = 0.0;
    }
    let s = cheap(&loads);
    assert!((&s - s.transpose()).amax() <= 1e-12 * s.amax());
}

/// One spatial flexure of length 1 under a tip force that bends it by
/// about a radian, solved, with its tip compliance.
fn bent_cantilever(subintervals: Option<usize>, force: [f64; 3]) -> (SpatialMechanism, Solution<Spatial>) {
    let mut f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
    if let Some(s) = subintervals {
        f = f.with_subintervals(s).unwrap();
    }
    let bodies = vec![SpatialBody::massless("ground"), SpatialBody::massless("tip")];
    let joints = vec![joint("flex", SpatialJointKind::Flexure(Box::new(f)), 0, 1, Isometry3::identity())];
    let tip = SpatialPointLoad {
        name: "tip".into(),
        body: 1,
        at: Point3::origin(),
        wrench: Vector6::new(0.0, 0.0, 0.0, force[0], force[1], force[2]),
    };
    let m = SpatialMechanism::new(bodies, joints, vec![], vec![tip], vec![], Vector3::zeros()).unwrap();
    let s = solve(&m, &Default::default()).unwrap();
    (m, s)
}

/// $JH^{-1}J^T$ at the tip from frames evaluated to `level` (no closures).
fn tip_compliance(m: &SpatialMechanism, s: &Solution<Spatial>, level: Level) -> DMatrix<f64> {
    let mut f = Frames::new(m);
    frames_level_into(m, &s.q, level, &mut f);
    let mut a = Assembly::new(m);
    assemble_into(m, &f, &[], &s.loads, true, &mut a).unwrap();
    let x = attach(m, &f, 1, Vector3::zeros(), true);
    let j = DMatrix::from_fn(6, m.dof(), |r, c| if r < 3 { f.omega[c][r] } else { x.jacobian[(r, c)] });
    &j * a.hessian.lu().solve(&j.transpose()).unwrap()
}

/// Why compliance, modes and buckling keep the exact Hessian: on a
/// cantilever bent by about a radian (tip force 3 N and 2 N, EI = GJ = 1,
/// L = 1), the compliance from the quadrature's Hessian differs from the
/// exact one by 1.3e-8 of its size, above the 1e-8 the Newton matrix may
/// miss by but no more than the Magnus model's own discretization (8
/// against 64 subintervals: 1.5e-8; asserted within twice it, and within
/// 3e-8); [`compliance`] itself is the full-Hessian one (measured
/// identical, asserted 1e-12).
#[test]
fn compliance_keeps_the_exact_hessian_which_the_quadrature_meets_to_the_models_own_accuracy() {
    let force = [0.0, 3.0, 2.0];
    let (m, s) = bent_cantilever(None, force);
    let exact = compliance(&m, &s, 1, Point3::origin()).unwrap();
    let size = exact.amax();
    let full = tip_compliance(&m, &s, Level::Hessian);
    let cheap = tip_compliance(&m, &s, Level::Jacobian);
    let difference = |c: &DMatrix<f64>| {
        (0..36).map(|i| (c[(i % 6, i / 6)] - exact[(i % 6, i / 6)]).abs()).fold(0.0, f64::max) / size
    };
    assert!(difference(&full) <= 1e-12, "compliance is the full-Hessian one: {:.3e}", difference(&full));
    let (fine, sf) = bent_cantilever(Some(64), force);
    let model = (compliance(&fine, &sf, 1, Point3::origin()).unwrap() - exact).amax() / size;
    let quadrature = difference(&cheap);
    assert!(quadrature <= 3e-8 && quadrature <= 2.0 * model, "quadrature {quadrature:.3e}, model {model:.3e}");
}
