//! The weld.

use super::{Joint, JointState};

/// A rigid connection: no coordinates, the output frame is the root frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fixed;

impl Joint for Fixed {
    fn dof(&self) -> usize {
        0
    }

    fn rest_into(&self, _: &mut [f64]) {}

    fn evaluate_into(&self, _: &[f64], _: &mut JointState) {}

    fn add_damping(&self, _: f64, _: &mut nalgebra::DMatrixViewMut<'_, f64>) {}

    fn angle_row(&self) -> Option<&[f64]> {
        Some(&[])
    }

    fn distance(&self, _: &[f64], _: &[f64], _: f64) -> f64 {
        0.0
    }
}

/// In space too: no coordinates, the output frame is the root frame.
impl Joint<crate::space::Spatial> for Fixed {
    fn dof(&self) -> usize {
        0
    }

    fn rest_into(&self, _: &mut [f64]) {}

    fn evaluate_into(&self, _: &[f64], _: &mut JointState<crate::space::Spatial>) {}

    fn add_damping(&self, _: f64, _: &mut nalgebra::DMatrixViewMut<'_, f64>) {}

    fn angle_row(&self) -> Option<&[f64]> {
        None
    }

    fn distance(&self, _: &[f64], _: &[f64], _: f64) -> f64 {
        0.0
    }
}
