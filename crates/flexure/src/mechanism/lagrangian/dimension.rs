//! What the Lagrangian needs of a dimension beyond [`FrameChain`]: its loads and
//! its closures. In the plane a moment has a potential (angles add), a
//! flexure's weight comes from its [`crate::mass::Weight`] and a closure's
//! angle is a difference of angles; in space a moment is dead (its
//! derivative unsymmetric), a flexure's weight is its stations' and a
//! closure compares frames' axes, with the Hessians' same-joint parts
//! gathered per joint ([`JointWrenches`]). The plane and space implement it
//! here, side by side.

use super::{Attached, planar, spatial};
use crate::error::Result;
use crate::mechanism::kinematics::{FrameChain, Frames, JointWrenches};
use crate::mechanism::{Loads, Mechanism};
use crate::space::{Planar, Spatial};
use nalgebra::{DMatrix, DVector};
use std::fmt::Debug;

/// A dimension whose Lagrangian [`super::assemble_into`] assembles.
pub trait Potential: FrameChain {
    /// What only this dimension's loads and closures keep between assemblies.
    type Kept: Clone + Debug;

    /// Those buffers for `m`.
    fn kept(m: &Mechanism<Self>) -> Self::Kept;
    /// Checks that `loads` fit `m`, are finite, and pull no tendon negative.
    fn check_loads(m: &Mechanism<Self>, loads: &Loads<Self>) -> Result<()>;
    /// Adds the loads' gradient (and its derivative, when given a Hessian,
    /// whose same-joint parts may stay in `kept` until
    /// [`Potential::closure_terms`] adds them) and returns their potential.
    /// `points` are scratch buffers.
    fn load_terms(
        m: &Mechanism<Self>,
        f: &Frames<Self>,
        loads: &Loads<Self>,
        gradient: &mut DVector<f64>,
        hessian: Option<&mut DMatrix<f64>>,
        points: &mut [Attached<Self>; 2],
        kept: &mut Self::Kept,
    ) -> Result<f64>;
    /// Writes $c$ and $G$, and adds $\sum_i\mu_i\nabla^2 c_i$ (and whatever
    /// `kept` gathered) to `hessian` if given.
    #[allow(clippy::too_many_arguments)]
    fn closure_terms(
        m: &Mechanism<Self>,
        f: &Frames<Self>,
        mu: &[f64],
        closure: &mut DVector<f64>,
        g: &mut DMatrix<f64>,
        hessian: Option<&mut DMatrix<f64>>,
        points: &mut [Attached<Self>; 2],
        kept: &mut Self::Kept,
    );
}

impl Potential for Planar {
    type Kept = planar::Weights;

    fn kept(m: &Mechanism) -> planar::Weights {
        planar::Weights::new(m)
    }
    fn check_loads(m: &Mechanism, loads: &Loads) -> Result<()> {
        loads.validate(m)
    }
    fn load_terms(
        m: &Mechanism,
        f: &Frames,
        loads: &Loads,
        gradient: &mut DVector<f64>,
        hessian: Option<&mut DMatrix<f64>>,
        points: &mut [Attached; 2],
        weights: &mut planar::Weights,
    ) -> Result<f64> {
        planar::add_loads(m, f, loads, gradient, hessian, points, weights)
    }
    fn closure_terms(
        m: &Mechanism,
        f: &Frames,
        mu: &[f64],
        closure: &mut DVector<f64>,
        g: &mut DMatrix<f64>,
        hessian: Option<&mut DMatrix<f64>>,
        points: &mut [Attached; 2],
        _: &mut planar::Weights,
    ) {
        planar::add_closures(m, f, mu, closure, g, hessian, points);
    }
}

impl Potential for Spatial {
    type Kept = JointWrenches;

    fn kept(m: &Mechanism<Spatial>) -> JointWrenches {
        JointWrenches::new(m)
    }
    fn check_loads(m: &Mechanism<Spatial>, loads: &Loads<Spatial>) -> Result<()> {
        loads.validate(m)
    }
    fn load_terms(
        m: &Mechanism<Spatial>,
        f: &Frames<Spatial>,
        loads: &Loads<Spatial>,
        gradient: &mut DVector<f64>,
        hessian: Option<&mut DMatrix<f64>>,
        _: &mut [Attached<Spatial>; 2],
        sums: &mut JointWrenches,
    ) -> Result<f64> {
        Ok(spatial::gather_loads(m, f, loads, gradient, hessian.map(|h| (h, sums))))
    }
    fn closure_terms(
        m: &Mechanism<Spatial>,
        f: &Frames<Spatial>,
        mu: &[f64],
        closure: &mut DVector<f64>,
        g: &mut DMatrix<f64>,
        hessian: Option<&mut DMatrix<f64>>,
        _: &mut [Attached<Spatial>; 2],
        sums: &mut JointWrenches,
    ) {
        spatial::closures_into(m, f, closure, g);
        if let Some(h) = hessian {
            spatial::gather_closure_hessian(m, f, mu, h, sums);
            sums.flush(m, f, h);
        }
    }
}
