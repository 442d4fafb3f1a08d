//! Derivatives of a spatial mechanism's kinematics, potential and closures
//! (`mechanism::spatial::{kinematics, lagrangian}`), each against central
//! finite differences of the quantity it differentiates (step 1e-6, or 1e-5
//! for second derivatives from first; tolerance 1e-6 of the scale).

use flexure::mechanism::Fixed;
use flexure::mechanism::spatial::kinematics::{attach, frames};
use flexure::mechanism::spatial::lagrangian::{SpatialAssembly, assemble_into, closures_into};
use flexure::mechanism::spatial::{
    Prismatic, Revolute, SpatialBody, SpatialClosure, SpatialJointKind, SpatialJointSpec, SpatialLoads,
    SpatialMechanism, SpatialPointLoad, SpatialTendon, Spherical,
};
use flexure::section::Profile;
use flexure::spatial::SpatialSpec;
use nalgebra::{DMatrix, DVector, Isometry3, Matrix3, Point3, Translation3, Unit, UnitQuaternion, Vector3, Vector6};

fn body(name: &str, mass: f64, com: [f64; 3]) -> SpatialBody {
    SpatialBody { name: name.into(), mass, com: Point3::from(com), inertia: Matrix3::from_diagonal_element(1e-3) }
}

fn joint(name: &str, kind: SpatialJointKind, parent: usize, child: usize, origin: Isometry3<f64>) -> SpatialJointSpec {
    SpatialJointSpec { name: name.into(), kind, parent, child, origin, offset: 0, damping: 0.0 }
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
            SpatialJointKind::Revolute(Revolute { axis, stiffness: 0.4, rest: 0.1 }),
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
            SpatialJointKind::Prismatic(Prismatic { axis: Vector3::y_axis(), stiffness: 5.0, rest: 0.0 }),
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
        SpatialClosure::Ball { a: 3, a_at: Point3::new(0.01, 0.0, 0.0), b: 0, b_at: Point3::new(0.1, 0.1, 0.0) },
        SpatialClosure::Weld {
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

fn assembled(m: &SpatialMechanism, q: &[f64], mu: &[f64], loads: &SpatialLoads) -> SpatialAssembly {
    let mut a = SpatialAssembly::new(m);
    assemble_into(m, &frames(m, q), mu, loads, true, &mut a);
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
                close(x.jacobian[(c, i)], fd[c], 1.0, 1e-7, "attached Jacobian");
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
    m.closures = vec![SpatialClosure::Weld { a: 5, a_origin: Isometry3::identity(), b: 0, b_origin: here }];
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
            let expected = if on_path { omega[(i, col)] } else { 0.0 };
            close(g[(3 + i, col)], expected, 1.0, 1e-14, "weld rotation rows");
        }
    }
    assert_eq!(g.clone().svd(false, false).rank(1e-9), 6);
}
