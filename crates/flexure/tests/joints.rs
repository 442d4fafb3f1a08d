//! The joint interface's contract, kind by kind: the motion subspace is the
//! placement's derivative and its derivative the Hessians (central
//! differences, step 1e-6: truncation ~1e-12, rounding ~1e-10, so 1e-7);
//! the energy's gradient and stiffness are its derivatives; a linear
//! rotation's row is the motion subspace's φ row; damping and distance are
//! what the kind's docs state.

use flexure::Flexure;
use flexure::mechanism::{Fixed, Joint, Prismatic, Revolute};
use nalgebra::DMatrix;

fn kinds() -> Vec<(&'static str, Box<dyn Joint>, Vec<f64>)> {
    let mut bent = Flexure::new(0.3, 2.0, 4).unwrap();
    bent = bent.with_rest(&[0.2, -0.1, 0.05, 0.0]).unwrap();
    vec![
        ("flexure", Box::new(bent), vec![0.7, -0.3, 0.2, 0.1]),
        ("revolute", Box::new(Revolute { stiffness: 3.0, rest: 0.2 }), vec![0.9]),
        ("prismatic", Box::new(Prismatic { stiffness: 50.0, rest: 0.01 }), vec![0.04]),
        ("fixed", Box::new(Fixed), vec![]),
    ]
}

fn pose_row(j: &dyn Joint, q: &[f64]) -> [f64; 3] {
    j.evaluate(q).pose.into()
}

#[test]
fn motion_subspace_and_its_derivative_are_the_placements_derivatives() {
    let h = 1e-6;
    for (name, j, q) in kinds() {
        let s = j.evaluate(&q);
        let k = j.dof();
        assert_eq!((s.jacobian.shape(), s.gradient.len()), ((3, k), k), "{name}: shapes");
        for a in 0..k {
            let (mut qp, mut qm) = (q.clone(), q.clone());
            qp[a] += h;
            qm[a] -= h;
            let (p, m) = (pose_row(j.as_ref(), &qp), pose_row(j.as_ref(), &qm));
            let (sp, sm) = (j.evaluate(&qp), j.evaluate(&qm));
            for r in 0..3 {
                let fd = (p[r] - m[r]) / (2.0 * h);
                assert!(
                    (s.jacobian[(r, a)] - fd).abs() < 1e-7,
                    "{name}: S[{r},{a}] {} against {fd}",
                    s.jacobian[(r, a)]
                );
                for b in 0..k {
                    let fd = (sp.jacobian[(r, b)] - sm.jacobian[(r, b)]) / (2.0 * h);
                    assert!((s.hessian[r][(a, b)] - fd).abs() < 1e-7, "{name}: H{r}[{a},{b}]");
                }
            }
            let fd = (sp.energy - sm.energy) / (2.0 * h);
            assert!((s.gradient[a] - fd).abs() < 1e-7 * (1.0 + fd.abs()), "{name}: ∇U[{a}]");
            for b in 0..k {
                let fd = (sp.gradient[b] - sm.gradient[b]) / (2.0 * h);
                assert!((s.stiffness[(a, b)] - fd).abs() < 1e-6 * (1.0 + fd.abs()), "{name}: K[{a},{b}]");
            }
        }
        if let Some(row) = j.angle_row() {
            assert_eq!(row.len(), k, "{name}: one entry per coordinate");
            for a in 0..k {
                assert_eq!(row[a], s.jacobian[(0, a)], "{name}: φ = dᵀq");
            }
            assert!(s.hessian[0].iter().all(|v| *v == 0.0), "{name}: a linear rotation has no curvature");
        }
        let rest = j.rest();
        assert_eq!(j.evaluate(&rest).gradient.norm(), 0.0, "{name}: no force at rest");
    }
}

/// Damping: βK on a flexure, the coefficient itself on a revolute or
/// prismatic joint, nothing on a weld (each kind's documentation).
#[test]
fn damping_is_each_kinds_documented_matrix() {
    for (name, j, q) in kinds() {
        let k = j.dof();
        let mut d = DMatrix::zeros(k, k);
        j.add_damping(0.5, &mut d.view_mut((0, 0), (k, k)));
        let expected = match j.flexure() {
            Some(_) => j.evaluate(&q).stiffness * 0.5,
            None if k == 1 => DMatrix::from_element(1, 1, 0.5),
            None => DMatrix::zeros(k, k),
        };
        assert!((d - expected).abs().max() < 1e-15, "{name}");
    }
}

/// A joint's own distance: a slider's travel over the length, a flexure's
/// largest section rotation, which for a change of α₁ alone (a uniform
/// curvature change) is that change at the tip, to the rule's last node.
#[test]
fn distance_is_the_largest_rotation_inside_the_joint() {
    let slider = Prismatic { stiffness: 1.0, rest: 0.0 };
    assert!((slider.distance(&[0.3], &[0.1], 2.0) - 0.1).abs() < 1e-16);
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let last = *f.nodes().last().unwrap();
    let d = f.distance(&[0.5, 0.0, 0.0], &[0.1, 0.0, 0.0], 1.0);
    assert!((d - 0.4 * last).abs() < 1e-15, "{d} against {}", 0.4 * last);
    assert_eq!(Revolute { stiffness: 0.0, rest: 0.0 }.distance(&[1.0], &[0.0], 1.0), 0.0);
}

/// Reference: a straight uniform beam of mass per length μ in
/// constant-curvature motion, y = α s²/2L, has the generalized mass
/// ∫μ (s²/2L)² ds = μL³/20 (closed form; 1e-13 relative). Pins, sliders and
/// welds carry no mass of their own, nor does a flexure without a density.
#[test]
fn inertia_is_the_joints_own_distributed_mass() {
    use flexure::mass::{MassData, update};
    use flexure::section::{Profile, Section};
    let (mu, l) = (2.5, 0.4);
    let s = Section::given(Profile::Constant(1.0)).unwrap().with_mass_per_length(Profile::Constant(mu)).unwrap();
    let f = Flexure::new(l, 1.0, 1).unwrap().with_section(s).unwrap();
    let model = f.inertia().expect("a flexure with mass has inertia").unwrap();
    let mut data = MassData::new(&model);
    update(&model, &[0.0], None, &mut data);
    let exact = mu * l.powi(3) / 20.0;
    assert!((data.mass_matrix[(0, 0)] - exact).abs() < 1e-13 * exact, "{} vs {exact}", data.mass_matrix[(0, 0)]);
    assert!(Flexure::new(l, 1.0, 3).unwrap().inertia().is_none());
    for (name, joint, _) in kinds() {
        if joint.flexure().is_none() {
            assert!(joint.inertia().is_none(), "{name} has no mass of its own");
        }
    }
}

/// The second dimension behind the same interface. Reference: central
/// differences (step 1e-6) of the spatial flexure's placement: column a of
/// the motion subspace is (vee(∂_aR Rᵀ), ∂_a p), the root frame's angular
/// velocity and origin velocity; the derivative matrices are the columns'
/// differences; the gradient and stiffness those of the energy. 1e-7
/// absolute on quantities of order one.
#[test]
fn a_spatial_flexure_keeps_the_joint_contract() {
    use flexure::mechanism::JointState;
    use flexure::section::SpatialSection;
    use flexure::space::Spatial;
    use flexure::spatial::SpatialFlexure;
    let f = SpatialFlexure::new(0.7, SpatialSection::uniform(0.5, 1.5, 1.0).unwrap(), [3, 2, 3])
        .unwrap()
        .with_rest(&[0.1, 0.0, 0.0, 0.2, 0.0, 0.3, -0.1, 0.05])
        .unwrap();
    let q = [0.4, -0.2, 0.1, 0.6, -0.3, 0.9, 0.2, -0.1];
    let n = q.len();
    let at = |x: &[f64]| -> JointState<Spatial> { Joint::<Spatial>::evaluate(&f, x) };
    let s = at(&q);
    assert_eq!((s.jacobian.shape(), s.hessian.len()), ((6, n), 6));
    let h = 1e-6;
    for a in 0..n {
        let (mut up, mut down) = (q.to_vec(), q.to_vec());
        up[a] += h;
        down[a] -= h;
        let (su, sd) = (at(&up), at(&down));
        let (ru, rd) = (su.pose.rotation.to_rotation_matrix(), sd.pose.rotation.to_rotation_matrix());
        let spin = (ru.matrix() - rd.matrix()) / (2.0 * h) * s.pose.rotation.to_rotation_matrix().matrix().transpose();
        let dp = (su.pose.translation.vector - sd.pose.translation.vector) / (2.0 * h);
        let column = [spin[(2, 1)], spin[(0, 2)], spin[(1, 0)], dp.x, dp.y, dp.z];
        for (i, c) in column.iter().enumerate() {
            assert!((s.jacobian[(i, a)] - c).abs() < 1e-7, "S[{i},{a}] {} vs {c}", s.jacobian[(i, a)]);
        }
        // Column b's derivative along a is matrix i's entry (b, a).
        for b in 0..n {
            for i in 0..6 {
                let fd = (su.jacobian[(i, b)] - sd.jacobian[(i, b)]) / (2.0 * h);
                assert!((s.hessian[i][(b, a)] - fd).abs() < 1e-7, "dS[{i}][{b},{a}] {} vs {fd}", s.hessian[i][(b, a)]);
            }
            let k = (su.gradient[b] - sd.gradient[b]) / (2.0 * h);
            assert!((s.stiffness[(b, a)] - k).abs() < 1e-7);
        }
        let g = (su.energy - sd.energy) / (2.0 * h);
        assert!((s.gradient[a] - g).abs() < 1e-7, "∇U[{a}] {} vs {g}", s.gradient[a]);
    }
    // Rotations do not add in space: no planar fast path, no planar flexure.
    assert!(Joint::<Spatial>::angle_row(&f).is_none() && Joint::<Spatial>::flexure(&f).is_none());
}
