//! What the door to one flexure ([`super::OneFlexure`]) needs of a
//! dimension: its load, its equilibrium and the parts of an answer that
//! differ (coordinates, pose, shape, exact reference, kinematics,
//! compliance). The plane and space implement it here, side by side; the
//! analyses are written once over it.

use super::answer::{Alpha, Bending, Compared, ExactReference, Headroom, Refinement, RestCompliance, TipMotion, rows};
use crate::error::{Error, Result};
use crate::estimate::{Accuracy, ErrorEstimate};
use crate::flexure::Flexure;
use crate::kinematics::TipKinematics;
use crate::limit::StabilityLimit;
use crate::model::Analyses;
use crate::reference::rod::{self, Rod};
use crate::report::{BodyPose, PeakStress, Shape, ShapeSection};
use crate::space::{Planar, Spatial};
use crate::spatial::{SpatialFlexure, SpatialLoad, SpatialPoint, SpatialStatics, StabilityTest};
use crate::statics::Settings;
use crate::statics::{StaticsData, TipLoad};
use nalgebra::DMatrix;

/// An equilibrium of one flexure, as a dimension finds it.
pub struct Found {
    /// Its coordinates.
    pub alpha: Vec<f64>,
    /// The tip's pose.
    pub pose: BodyPose,
    /// The loaded stiffness.
    pub stiffness: DMatrix<f64>,
    /// The statics' answer: stable, residual, where stability was lost.
    pub equilibrium: crate::statics::Equilibrium,
}

/// A dimension whose single flexure the door analyses.
pub trait FlexureAnalyses: Analyses {
    /// 2 or 3.
    const DIMENSION: u8;
    /// The tip load of this dimension.
    type Load;
    /// The load from a wrench in space: the plane takes $M_z$, $F_x$, $F_y$.
    fn load(w: &SpatialLoad) -> Result<Self::Load>;
    /// The stability question the load's `stable` answers: the energy's,
    /// except under a dead moment in space, which has no potential.
    fn stability_test(load: &Self::Load) -> StabilityTest;
    /// The lowest orders that meet `target` under `load` (`--order auto`).
    fn auto(f: &Self::Flexure, load: &Self::Load, target: &Accuracy) -> Result<Self::Flexure>;
    /// Refuses a yield strength the flexure cannot give a stress for, before solving.
    fn check_yield(f: &Self::Flexure, yield_strength: Option<f64>) -> Result<()>;
    /// The equilibrium under `load`, followed from rest.
    fn deflect(f: &Self::Flexure, load: &Self::Load, settings: &Settings) -> Result<Found>;
    /// The coordinates by component.
    fn alpha(f: &Self::Flexure, alpha: &[f64]) -> Alpha;
    /// The orders and points (or subintervals) an answer was found at.
    fn reached(f: &Self::Flexure) -> Refinement;
    /// The estimated error of `alpha` under `load`.
    fn estimate(f: &Self::Flexure, load: &Self::Load, alpha: &[f64], target: &Accuracy) -> Result<ErrorEstimate>;
    /// Whether a higher order is left to try once `e` misses its target.
    fn headroom(f: &Self::Flexure, e: &ErrorEstimate) -> Headroom;
    /// The factor on `load` at which the path from rest loses stability.
    fn limit(f: &Self::Flexure, load: &Self::Load, max_factor: f64) -> Result<StabilityLimit>;
    /// The exact reference under `load`, against the model's `pose` (and
    /// its `shape`, whose arc lengths it is sampled at).
    fn exact(
        f: &Self::Flexure,
        load: &Self::Load,
        model: (&BodyPose, Option<&Shape>),
        stress: (Option<f64>, Option<usize>),
    ) -> Result<ExactReference>;
    /// Pose, Jacobian (and the plane's transform and Hessians) at `alpha`.
    fn tip(f: &Self::Flexure, alpha: &[f64]) -> Result<TipMotion>;
    /// The energy and its gradient at `alpha`.
    fn energy(f: &Self::Flexure, alpha: &[f64]) -> (f64, Vec<f64>);
    /// The tip's compliance at rest (the model's, or the exact reference's).
    fn compliance(f: &Self::Flexure, exact: bool) -> Result<RestCompliance>;
}

impl FlexureAnalyses for Planar {
    const DIMENSION: u8 = 2;
    type Load = TipLoad;

    fn load(w: &SpatialLoad) -> Result<TipLoad> {
        let [mx, my, moment] = w.moment;
        let [fx, fy, fz] = w.force;
        match [mx, my, fz].iter().find(|v| **v != 0.0) {
            Some(v) => {
                Err(Error::invalid("load", v, "a planar flexure takes a moment about z and a force along x and y"))
            }
            None => Ok(TipLoad { moment, fx, fy }),
        }
    }

    fn stability_test(_: &TipLoad) -> StabilityTest {
        // A moment in the plane has the potential −Mφ: every planar load does.
        StabilityTest::Energy
    }

    fn auto(f: &Flexure, load: &TipLoad, target: &Accuracy) -> Result<Flexure> {
        Ok(crate::estimate::deflect_auto(f, load, target)?.0)
    }

    fn check_yield(f: &Flexure, yield_strength: Option<f64>) -> Result<()> {
        super::check_yield(f, yield_strength)
    }

    fn deflect(f: &Flexure, load: &TipLoad, settings: &Settings) -> Result<Found> {
        let mut data = StaticsData::new(f);
        let equilibrium = crate::statics::deflect(f, load, &mut data, settings)?;
        let pose = BodyPose::planar(&data.pose_root_tip());
        Ok(Found { alpha: data.alpha().to_vec(), pose, stiffness: data.stiffness, equilibrium })
    }

    fn alpha(_: &Flexure, alpha: &[f64]) -> Alpha {
        Alpha::Planar(alpha.to_vec())
    }

    fn reached(f: &Flexure) -> Refinement {
        Refinement::Planar { order: f.order(), quadrature: f.quadrature_points() }
    }

    fn estimate(f: &Flexure, load: &TipLoad, alpha: &[f64], target: &Accuracy) -> Result<ErrorEstimate> {
        crate::estimate::deflect_error(f, load, alpha, target)
    }

    fn headroom(f: &Flexure, e: &ErrorEstimate) -> Headroom {
        // At the highest order the estimate is against the exact elastica.
        if e.exact { Headroom::Exhausted { order: f.order(), against_exact: true } } else { Headroom::Higher }
    }

    fn limit(f: &Flexure, load: &TipLoad, max_factor: f64) -> Result<StabilityLimit> {
        crate::statics::stability_limit(f, load, max_factor)
    }

    fn exact(
        f: &Flexure,
        load: &TipLoad,
        (model, _): (&BodyPose, Option<&Shape>),
        (yield_strength, shape): (Option<f64>, Option<usize>),
    ) -> Result<ExactReference> {
        let (exact, trace) = crate::reference::elastica::deflect_traced(f, load, &Default::default())?;
        let pose = BodyPose::planar(&exact.pose);
        let stress = trace.peak_stress()?.map(PeakStress::from);
        let curvature_max = if stress.is_none() { Some(trace.peak_curvature()?.into()) } else { None };
        let points = |k| -> Result<Shape> {
            let at = trace.shape(k)?.into_iter().map(|p| crate::report::ShapePoint {
                s: p.s,
                x: p.x,
                y: p.y,
                phi: p.phi,
                curvature: p.curvature,
                stress: p.stress,
            });
            Ok(Shape::Planar(at.collect()))
        };
        Ok(ExactReference {
            compared: Compared::of(model, &pose, f.length()),
            pose,
            root_moment: vec![exact.root_moment],
            stable: exact.stable,
            bending: Bending {
                safety_factor: super::safety_factor(stress.as_ref(), yield_strength),
                stress,
                curvature_max,
                shape: shape.map(points).transpose()?,
            },
        })
    }

    fn tip(f: &Flexure, alpha: &[f64]) -> Result<TipMotion> {
        Ok(TipMotion::Planar(TipKinematics::at(f, alpha)?))
    }

    fn energy(f: &Flexure, alpha: &[f64]) -> (f64, Vec<f64>) {
        let mut gradient = vec![0.0; f.order()];
        crate::energy::energy_gradient(f, alpha, &mut gradient);
        (crate::energy::energy(f, alpha), gradient)
    }

    fn compliance(f: &Flexure, exact: bool) -> Result<RestCompliance> {
        let c = if exact {
            crate::reference::compliance::compliance_tip(f, &Default::default())?
        } else {
            crate::compliance::compliance_tip_rest(f)
        };
        Ok(RestCompliance { compliance: rows(&c), order: None })
    }
}

/// The exact rod of the spatial flexure's length, section and rest shape.
fn rod_of(f: &SpatialFlexure) -> Result<Rod> {
    let (shape, rest) = (f.clone(), f.rest().to_vec());
    Rod::new(f.length(), f.section().clone())?.with_rest(move |s| shape.curvature(&rest, s))
}

impl FlexureAnalyses for Spatial {
    const DIMENSION: u8 = 3;
    type Load = SpatialLoad;

    fn load(w: &SpatialLoad) -> Result<SpatialLoad> {
        Ok(*w)
    }

    fn stability_test(load: &SpatialLoad) -> StabilityTest {
        load.stability_test()
    }

    fn auto(f: &SpatialFlexure, load: &SpatialLoad, target: &Accuracy) -> Result<SpatialFlexure> {
        Ok(crate::estimate::spatial::deflect_auto(f, load, target)?.0)
    }

    fn check_yield(f: &SpatialFlexure, yield_strength: Option<f64>) -> Result<()> {
        match yield_strength {
            Some(s) if !f.section().has_geometry() => Err(Error::invalid(
                "yield_strength",
                s,
                "needs a section with a shape to give a stress: give --modulus with --width and --thickness, or --diameter",
            )),
            _ => Ok(()),
        }
    }

    fn deflect(f: &SpatialFlexure, load: &SpatialLoad, settings: &Settings) -> Result<Found> {
        let mut data = SpatialStatics::new(f);
        let equilibrium = crate::spatial::deflect(f, load, &mut data, settings)?;
        let (r, p) = crate::spatial::pose_root_tip(f, data.alpha());
        let pose = BodyPose::spatial(p.into(), &r);
        Ok(Found { alpha: data.alpha().to_vec(), pose, stiffness: data.stiffness.clone(), equilibrium })
    }

    fn alpha(f: &SpatialFlexure, alpha: &[f64]) -> Alpha {
        let [a, b, _] = f.orders();
        let part = |r: std::ops::Range<usize>| alpha[r].to_vec();
        Alpha::Spatial { twist: part(0..a), kappa_y: part(a..a + b), kappa_z: part(a + b..alpha.len()) }
    }

    fn reached(f: &SpatialFlexure) -> Refinement {
        Refinement::Spatial { orders: f.orders(), subintervals: f.subintervals() }
    }

    fn estimate(f: &SpatialFlexure, load: &SpatialLoad, alpha: &[f64], target: &Accuracy) -> Result<ErrorEstimate> {
        crate::estimate::spatial::deflect_error(f, load, alpha, target)
    }

    fn headroom(f: &SpatialFlexure, _: &ErrorEstimate) -> Headroom {
        let top = crate::estimate::spatial::MAX_AUTO_ORDER;
        let orders = f.orders();
        if orders.iter().all(|&n| n >= top) {
            Headroom::Exhausted { order: orders.into_iter().max().unwrap_or(top), against_exact: false }
        } else {
            Headroom::Higher
        }
    }

    fn limit(f: &SpatialFlexure, load: &SpatialLoad, max_factor: f64) -> Result<StabilityLimit> {
        crate::spatial::stability_limit(f, load, max_factor)
    }

    fn exact(
        f: &SpatialFlexure,
        load: &SpatialLoad,
        (model, shape): (&BodyPose, Option<&Shape>),
        _: (Option<f64>, Option<usize>),
    ) -> Result<ExactReference> {
        let rod = rod_of(f)?;
        let exact = rod::deflect(&rod, load, &Default::default())?;
        let pose = BodyPose::spatial(exact.position.into(), &exact.rotation);
        let shape = match shape {
            Some(Shape::Spatial(points)) => Some(rod_shape(&rod, load, &exact, points)?),
            _ => None,
        };
        let m = exact.root_moment;
        Ok(ExactReference {
            compared: Compared::of(model, &pose, f.length()),
            pose,
            root_moment: vec![m.x, m.y, m.z],
            stable: exact.stable,
            bending: Bending { shape, ..Default::default() },
        })
    }

    fn tip(f: &SpatialFlexure, alpha: &[f64]) -> Result<TipMotion> {
        f.check_coordinates("alpha", alpha)?;
        let mut k = crate::spatial::SpatialKinematics::new(f);
        crate::spatial::update(f, alpha, crate::kinematics::Level::Jacobian, &mut k);
        let pose = BodyPose::spatial(k.position.into(), &k.rotation);
        Ok(TipMotion::Spatial { pose, jacobian: rows(&k.jacobian) })
    }

    fn energy(f: &SpatialFlexure, alpha: &[f64]) -> (f64, Vec<f64>) {
        let mut gradient = vec![0.0; f.coordinates()];
        crate::spatial::energy_gradient(f, alpha, &mut gradient);
        (crate::spatial::energy(f, alpha), gradient)
    }

    fn compliance(f: &SpatialFlexure, exact: bool) -> Result<RestCompliance> {
        let c = if exact {
            rod::compliance_rest(&rod_of(f)?, &Default::default())?
        } else {
            crate::spatial::compliance_rest(f)?
        };
        Ok(RestCompliance { compliance: rows(&c), order: Some(Self::COMPLIANCE_AXES) })
    }
}

/// A 3 × 3 matrix by rows.
fn rows3(m: &nalgebra::Matrix3<f64>) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// The spatial flexure's sections, curvature by component.
fn sections(points: &[SpatialPoint]) -> Shape {
    Shape::Spatial(points.iter().map(ShapeSection::from).collect())
}

/// The exact rod's sections at the arc lengths of the model's `shape`: each
/// carried from the rod's nearest frame ([`rod::sections`]), its curvature
/// $K^{-1}R^Tm + u^0$ from its moment, and its stress that of the change
/// $K^{-1}R^Tm$.
fn rod_shape(rod: &Rod, load: &SpatialLoad, exact: &rod::RodSolution, model: &[ShapeSection]) -> Result<Shape> {
    let at: Vec<f64> = model.iter().map(|p| p.s).collect();
    let (l, section) = (rod.length(), rod.section());
    let found = rod::sections(rod, load, exact, &at, &Default::default())?;
    let points: Vec<SpatialPoint> = found
        .iter()
        .map(|q| {
            let t = (q.s / l).clamp(0.0, 1.0);
            let k = section.stiffness(t);
            let body = q.rotation.tr_mul(&q.moment);
            let change: [f64; 3] = std::array::from_fn(|c| body[c] / k[c]);
            let rest = rod.rest_at(q.s);
            SpatialPoint {
                s: q.s,
                position: q.position.into(),
                rotation: rows3(&q.rotation),
                curvature: std::array::from_fn(|c| change[c] + rest[c]),
                stress: section.stress(t, change).ok().map(|x| x.von_mises),
            }
        })
        .collect();
    Ok(sections(&points))
}
