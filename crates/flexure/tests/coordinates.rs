//! Coordinates of the wrong length: user-facing entries get an error naming
//! the parameter ([`Flexure::check_coordinates`]); the kernels panic with a
//! message naming `alpha`, the expected and the received length, and never
//! truncate to the overlapping entries.

use flexure::{
    Flexure, Kinematics, Level, StaticsData, compliance_tip, energy, energy_gradient, kinematics::backbone,
    pose_root_tip, update_kinematics,
};
use nalgebra::DMatrix;

fn order_3() -> Flexure {
    Flexure::new(1.0, 1.0, 3).unwrap()
}

#[test]
fn checker_rejects_short_and_long_coordinates_by_name() {
    let f = order_3();
    assert!(f.check_coordinates("alpha", &[0.1, 0.2, 0.3]).is_ok());
    for bad in [&[0.1, 0.2][..], &[0.1, 0.2, 0.3, 0.4], &[]] {
        match f.check_coordinates("rest", bad) {
            Err(flexure::Error::InvalidParameter { name, value, .. }) => {
                assert_eq!(name, "rest");
                assert!(value.contains(&bad.len().to_string()), "{value}");
            }
            other => panic!("{} values accepted: {other:?}", bad.len()),
        }
    }
    // The same check covers segment chains, whose order is their segment count.
    let chain = Flexure::segments(1.0, 1.0, 4).unwrap();
    assert!(chain.check_coordinates("alpha", &[0.1; 3]).is_err());
    assert!(chain.check_coordinates("alpha", &[0.1; 4]).is_ok());
}

// Before the checks, `energy` of [1, 2, 3, 99] on an order-3 flexure was the
// energy of [1, 2, 3]: the extra entry was dropped. Each kernel below must
// panic instead, naming alpha with both lengths.

#[test]
#[should_panic(expected = "alpha must have 3 entries (one per coordinate, the flexure's order), got 4")]
fn energy_panics_on_a_long_alpha() {
    energy(&order_3(), &[1.0, 2.0, 3.0, 99.0]);
}

#[test]
#[should_panic(expected = "alpha must have 3 entries (one per coordinate, the flexure's order), got 2")]
fn energy_panics_on_a_short_alpha() {
    energy(&order_3(), &[1.0, 2.0]);
}

#[test]
#[should_panic(expected = "alpha must have 3 entries (one per coordinate, the flexure's order), got 4")]
fn energy_gradient_panics_on_a_long_alpha() {
    energy_gradient(&order_3(), &[1.0, 2.0, 3.0, 4.0], &mut [0.0; 3]);
}

#[test]
#[should_panic(expected = "out must have 3 entries (one per coordinate, the flexure's order), got 2")]
fn energy_gradient_panics_on_a_short_output() {
    energy_gradient(&order_3(), &[1.0, 2.0, 3.0], &mut [0.0; 2]);
}

#[test]
#[should_panic(expected = "alpha must have 3 entries (one per coordinate, the flexure's order), got 2")]
fn pose_panics_on_a_short_alpha() {
    pose_root_tip(&order_3(), &[1.0, 2.0]);
}

#[test]
#[should_panic(expected = "alpha must have 7 entries (one per coordinate, the flexure's order), got 8")]
fn pose_panics_on_a_long_alpha_at_any_order() {
    // Order 7 takes the any-order path rather than a fixed-size kernel.
    pose_root_tip(&Flexure::new(1.0, 1.0, 7).unwrap(), &[0.1; 8]);
}

#[test]
#[should_panic(expected = "alpha must have 3 entries (one per coordinate, the flexure's order), got 4")]
fn kinematics_update_panics_on_a_long_alpha() {
    let f = order_3();
    let mut k = Kinematics::new(&f);
    update_kinematics(&f, &[0.1, 0.2, 0.3, 0.4], &mut k, Level::Hessian);
}

#[test]
#[should_panic(expected = "alpha must have 3 entries (one per coordinate, the flexure's order), got 2")]
fn backbone_panics_on_a_short_alpha() {
    backbone(&order_3(), &[1.0, 0.0], 11);
}

#[test]
#[should_panic(expected = "stiffness must be 3 x 3 (one row and column per coordinate), got 2 x 2")]
fn compliance_panics_on_a_stiffness_of_another_order() {
    let f = order_3();
    let data = StaticsData::new(&f);
    let _ = compliance_tip(&data.kinematics, &DMatrix::identity(2, 2));
}
