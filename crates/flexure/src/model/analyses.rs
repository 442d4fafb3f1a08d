//! What the door needs of a dimension beyond its report ([`Reported`]):
//! the analyses, each written once over the dimension's traits (its
//! statics, dynamics, findings and estimates), and the two things only
//! the door asks of a dimension: a compliance as a square matrix and a
//! flexure's orders. The plane and
//! space implement those here, side by side; [`super::Model`] is written
//! once over it.

use crate::dynamics::modes::Modes;
use crate::dynamics::simulation::{SimulationSettings, Start};
use crate::error::{Error, Result};
use crate::estimate::{Accuracy, Refined, ValueEstimate};
use crate::mechanism::buckling::Buckling;
use crate::mechanism::findings::{Crossing, Findings, OpenClosure};
use crate::mechanism::statics::{Settings, Solution};
use crate::mechanism::sweep::{Parameter, Sweep};
use crate::mechanism::{Mechanism, findings, statics};
use crate::report::Reported;
use crate::space::{Planar, Spatial};
use nalgebra::DMatrix;

/// A dimension whose mechanisms the door ([`super::Model`]) analyses.
pub trait Analyses: Reported + Refined + Findings {
    /// How a refined reference's (order, count) reads: "order 6 with 13
    /// points" (Gauss points) in the plane, "orders up to 6 with 20
    /// subintervals" (Magnus steps) in space.
    const REFINED: [&'static str; 2];
    /// The rows and columns of a compliance: the twist's parts, rotations first.
    const COMPLIANCE_AXES: &'static [&'static str];
    /// The compliance of the frame at point `at` (its body's frame; `POINT_DIM` numbers) of `body`.
    fn compliance(m: &Mechanism<Self>, s: &Solution<Self>, body: usize, at: &[f64]) -> Result<DMatrix<f64>>;
    /// A flexure's orders: one number in the plane, the three of twist and bendings in space.
    fn orders(f: &Self::Flexure) -> Vec<usize>;

    /// The equilibrium under the mechanism's loads.
    fn solve(m: &Mechanism<Self>, settings: &Settings) -> Result<Solution<Self>> {
        statics::solve(m, settings)
    }
    /// The closures open at rest.
    fn open_closures(m: &Mechanism<Self>, settings: &Settings) -> Result<Vec<OpenClosure>> {
        findings::open_closures(m, settings)
    }
    /// The parts that cross at coordinates `q`.
    fn crossings(m: &Mechanism<Self>, q: &[f64]) -> Vec<Crossing<Vec<f64>>> {
        findings::crossings(m, q).into_iter().map(crossing_at).collect()
    }
    /// Equilibria along `values` of the load named `parameter` ([`crate::mechanism::sweep::sweep`]).
    fn sweep(
        m: &Mechanism<Self>,
        parameter: &str,
        values: &[f64],
        settings: &Settings,
    ) -> Result<Sweep<Solution<Self>>> {
        crate::mechanism::sweep::sweep(m, &Parameter::parse(m, parameter)?, values, settings)
    }
    /// The parts that cross at each of `shapes`, by index, where any do.
    fn crossings_along(m: &Mechanism<Self>, shapes: &[&[f64]]) -> Vec<(usize, Vec<Crossing<Vec<f64>>>)> {
        let found = findings::crossings_along(m, shapes.iter().copied());
        found.into_iter().map(|(k, c)| (k, c.into_iter().map(crossing_at).collect())).collect()
    }
    /// The motion from `start` under the loads and their schedules: the
    /// samples reached, and why the run stopped early if it did.
    fn simulate(
        m: &Mechanism<Self>,
        settings: &SimulationSettings,
        start: Start,
    ) -> Result<crate::dynamics::Simulation<Self>> {
        crate::dynamics::simulation::simulate(m, settings, start)
    }
    /// Linear buckling with its estimate, flexures of `order = "auto"` raised.
    fn buckle(
        m: &Mechanism<Self>,
        settings: &Settings,
        target: &Accuracy,
    ) -> Result<(Mechanism<Self>, Buckling, ValueEstimate)> {
        crate::estimate::buckle_auto(m, settings, target)
    }
    /// Vibration modes with their estimate, flexures of `order = "auto"` raised.
    fn modes(
        m: &Mechanism<Self>,
        settings: &Settings,
        count: usize,
        target: &Accuracy,
    ) -> Result<(Mechanism<Self>, Modes, ValueEstimate)> {
        crate::estimate::mechanism_modes_auto(m, settings, count, target)
    }
}

/// `at` as a point of `N` coordinates (the dimension's), or an error naming it.
fn point<const N: usize>(at: &[f64]) -> Result<[f64; N]> {
    let reason = if N == 2 {
        "must be two numbers X,Y: a planar mechanism's point"
    } else {
        "must be three numbers X,Y,Z: a spatial mechanism's point"
    };
    let shown: Vec<String> = at.iter().map(f64::to_string).collect();
    at.try_into().map_err(|_| Error::invalid("at", shown.join(","), reason))
}

fn crossing_at<P: AsRef<[f64]>>(c: Crossing<P>) -> Crossing<Vec<f64>> {
    Crossing { a: c.a, b: c.b, names: c.names, at: c.at.as_ref().to_vec(), s: c.s, points: c.points }
}

impl Analyses for Planar {
    const REFINED: [&'static str; 2] = ["order", "points"];
    const COMPLIANCE_AXES: &'static [&'static str] = &["phi", "x", "y"];

    fn compliance(m: &Mechanism, s: &Solution, body: usize, at: &[f64]) -> Result<DMatrix<f64>> {
        let [x, y] = point(at)?;
        let c = statics::compliance(m, s, body, nalgebra::Point2::new(x, y))?;
        Ok(DMatrix::from_fn(3, 3, |i, j| c[(i, j)]))
    }

    fn orders(f: &crate::Flexure) -> Vec<usize> {
        vec![f.order()]
    }
}

impl Analyses for Spatial {
    const REFINED: [&'static str; 2] = ["orders up to", "subintervals"];
    const COMPLIANCE_AXES: &'static [&'static str] = &["rx", "ry", "rz", "x", "y", "z"];

    fn compliance(m: &Mechanism<Spatial>, s: &Solution<Spatial>, body: usize, at: &[f64]) -> Result<DMatrix<f64>> {
        let [x, y, z] = point(at)?;
        let c = statics::compliance(m, s, body, nalgebra::Point3::new(x, y, z))?;
        Ok(DMatrix::from_fn(6, 6, |i, j| c[(i, j)]))
    }

    fn orders(f: &crate::spatial::SpatialFlexure) -> Vec<usize> {
        f.orders().to_vec()
    }
}
