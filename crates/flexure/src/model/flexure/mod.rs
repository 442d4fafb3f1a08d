//! The door to one flexure: a planar [`Flexure`] or a [`SpatialFlexure`],
//! with the analyses the command line and Python call on one joint
//! (deflect with its estimate, `--order auto`, stress, shape and exact
//! reference; compliance; kinematics). [`OneFlexure`] is the only code
//! above the dimension that matches on it: each method sends its flexure
//! to one function written once over [`FlexureAnalyses`], and each answer
//! is one type in both dimensions.

mod answer;
mod dimension;

pub use answer::{
    Alpha, Bending, Compared, Deflected, Deflection, ExactDeflected, ExactReference, Headroom, Posed, Refinement,
    RestCompliance, TipMotion,
};
pub use dimension::{FlexureAnalyses, Found};

use crate::error::{Error, Result};
use crate::estimate::Accuracy;
use crate::flexure::{Flexure, FlexureSpec};
use crate::report::PeakStress;
use crate::section::Profile;
use crate::space::{Planar, Spatial};
use crate::spatial::{SpatialFlexure, SpatialLoad, SpatialSpec};
use crate::statics::Settings;

/// One flexure of either dimension.
#[derive(Debug, Clone, PartialEq)]
pub enum OneFlexure {
    /// In the plane.
    Planar(Flexure),
    /// In space: two bendings and a twist.
    Spatial(SpatialFlexure),
}

/// `$body` for the flexure, with `D` its dimension: the one match.
macro_rules! either {
    ($flexure:expr, $f:ident, $d:ident => $body:expr) => {
        match $flexure {
            OneFlexure::Planar($f) => {
                type $d = Planar;
                $body
            }
            OneFlexure::Spatial($f) => {
                type $d = Spatial;
                $body
            }
        }
    };
}

/// The keys only a spatial flexure has; with them, [`OneFlexure::build`]
/// builds one in space.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SpatialKeys {
    /// $EI_y$ (N·m²) [default: `ei`].
    pub ei_y: Option<Profile>,
    /// $GJ$ (N·m²) [default: `ei`].
    pub gj: Option<Profile>,
    /// A round rod's diameter (m), in place of width and thickness.
    pub diameter: Option<Profile>,
    /// $G$ (Pa), in place of Poisson's ratio.
    pub shear_modulus: Option<f64>,
    /// Rest coefficients of the bending about $y$.
    pub kappa_y: Option<Vec<f64>>,
    /// Rest coefficients of the twist.
    pub twist: Option<Vec<f64>>,
}

/// What [`OneFlexure::deflect`] is asked.
#[derive(Debug, Clone, Default)]
pub struct Deflect {
    /// The tip load in the root frame; a planar flexure takes $M_z$, $F_x$, $F_y$ of it.
    pub load: SpatialLoad,
    /// The solver's tolerance and iterations.
    pub settings: Settings,
    /// The error estimate's target.
    pub target: Accuracy,
    /// Raise the orders until the estimate meets `target` (`--order auto`).
    pub auto: bool,
    /// Find the factor on the load, up to this one, at which stability is lost.
    pub limit: Option<f64>,
    /// Also the exact reference (the elastica, the Kirchhoff rod).
    pub exact: bool,
    /// A yield strength (Pa), for the safety factor.
    pub yield_strength: Option<f64>,
    /// The deformed shape at this many points.
    pub shape: Option<usize>,
}

impl OneFlexure {
    /// Builds a planar flexure from `spec`, or with `spatial` a spatial one
    /// (`spec.section.ei` its $EI_z$, `spec.kappa` its $\kappa_z$, each
    /// component of order `spec.order`), refusing the planar-only keys.
    ///
    /// # Example
    /// ```
    /// use flexure::FlexureSpec;
    /// use flexure::model::{OneFlexure, SpatialKeys};
    /// let planar = OneFlexure::build(&FlexureSpec::default(), None).unwrap();
    /// let spatial = OneFlexure::build(&FlexureSpec::default(), Some(&SpatialKeys::default())).unwrap();
    /// assert_eq!((planar.dimension(), spatial.dimension()), (2, 3));
    /// let notched = FlexureSpec { quadrature: Some(5), ..Default::default() };
    /// assert!(OneFlexure::build(&notched, Some(&SpatialKeys::default())).is_err());
    /// ```
    pub fn build(spec: &FlexureSpec, spatial: Option<&SpatialKeys>) -> Result<Self> {
        match spatial {
            None => spec.build().map(OneFlexure::Planar),
            Some(keys) => Self::spatial(spec, keys).map(OneFlexure::Spatial),
        }
    }

    /// The spatial flexure of [`OneFlexure::build`], as the spatial type.
    pub fn spatial(spec: &FlexureSpec, keys: &SpatialKeys) -> Result<SpatialFlexure> {
        spatial_spec(spec, keys)?.build()
    }

    /// 2 or 3.
    pub fn dimension(&self) -> u8 {
        either!(self, _f, D => D::DIMENSION)
    }

    /// The equilibrium under a tip load, with its estimate, and what else `options` asks.
    ///
    /// # Example
    /// ```
    /// use flexure::FlexureSpec;
    /// use flexure::model::{Deflect, OneFlexure, SpatialKeys};
    /// use flexure::spatial::SpatialLoad;
    /// // A small tip force F on a cantilever (EI = 1, L = 1) moves the tip F L³/3EI.
    /// let load = SpatialLoad { force: [0.0, 1e-4, 0.0], ..Default::default() };
    /// for keys in [None, Some(&SpatialKeys::default())] {
    ///     let f = OneFlexure::build(&FlexureSpec::default(), keys).unwrap();
    ///     let d = f.deflect(&Deflect { load, ..Default::default() }).unwrap();
    ///     let y = d.model().pose.position()[1];
    ///     assert!((y / (1e-4 / 3.0) - 1.0).abs() < 1e-3 && d.model().stable, "{y}");
    /// }
    /// ```
    pub fn deflect(&self, options: &Deflect) -> Result<Deflection> {
        either!(self, f, D => deflect::<D>(f, options))
    }

    /// The tip's pose, Jacobian (the plane's with its transform and
    /// Hessians), energy and gradient at `alpha`.
    pub fn kinematics(&self, alpha: &[f64]) -> Result<Posed> {
        either!(self, f, D => {
            let tip = D::tip(f, alpha)?;
            let (energy, gradient) = D::energy(f, alpha);
            Ok(Posed { tip, energy, gradient })
        })
    }

    /// The tip's compliance at rest: the model's, or with `exact` the
    /// exact reference's (the compliance ODE, Eq. 34; the linearized rod).
    pub fn compliance(&self, exact: bool) -> Result<RestCompliance> {
        either!(self, f, D => D::compliance(f, exact))
    }
}

impl From<Flexure> for OneFlexure {
    fn from(f: Flexure) -> Self {
        OneFlexure::Planar(f)
    }
}

impl From<SpatialFlexure> for OneFlexure {
    fn from(f: SpatialFlexure) -> Self {
        OneFlexure::Spatial(f)
    }
}

/// The spatial flexure's spec: the planar keys it shares, its own, and a
/// refusal of those it has not (a notch, a Gauss rule, a mass, which the
/// spatial flexure takes after it is built).
fn spatial_spec(spec: &FlexureSpec, keys: &SpatialKeys) -> Result<SpatialSpec> {
    let s = &spec.section;
    let planar_only = [
        ("notch", s.notch.is_some()),
        ("quadrature", spec.quadrature.is_some()),
        ("density", s.density.is_some()),
        ("mass_per_length", s.mass_per_length.is_some()),
    ];
    if let Some((name, _)) = planar_only.iter().find(|(_, given)| *given) {
        return Err(Error::invalid(name, "given with --spatial", "is for planar flexures only"));
    }
    Ok(SpatialSpec {
        length: spec.length,
        gj: keys.gj.clone(),
        ei_y: keys.ei_y.clone(),
        ei_z: s.ei.clone(),
        modulus: s.modulus,
        width: s.width.clone(),
        thickness: s.thickness.clone(),
        diameter: keys.diameter.clone(),
        poisson: s.poisson,
        shear_modulus: keys.shear_modulus,
        orders: [spec.order; 3],
        twist: keys.twist.clone(),
        kappa_y: keys.kappa_y.clone(),
        kappa_z: spec.kappa.clone(),
    })
}

/// Refuses a yield strength on a planar flexure without thickness, whose
/// stress is therefore unknown.
pub fn check_yield(f: &Flexure, yield_strength: Option<f64>) -> Result<()> {
    match yield_strength {
        Some(s) if f.section().modulus().is_none() => Err(Error::invalid(
            "yield_strength",
            s,
            "needs a thickness to give a stress: give --modulus, --width and --thickness (a flexure given by --ei alone has no stress)",
        )),
        _ => Ok(()),
    }
}

/// The yield strength over the peak stress, left out while unstressed (it would be infinite).
fn safety_factor(stress: Option<&PeakStress>, yield_strength: Option<f64>) -> Option<f64> {
    match (stress, yield_strength) {
        (Some(p), Some(s)) if p.max > 0.0 => Some(s / p.max),
        _ => None,
    }
}

fn deflect<D: FlexureAnalyses>(given: &D::Flexure, o: &Deflect) -> Result<Deflection> {
    let load = D::load(&o.load)?;
    let raised = if o.auto { Some(D::auto(given, &load, &o.target)?) } else { None };
    let f = raised.as_ref().unwrap_or(given);
    D::check_yield(f, o.yield_strength)?;
    let found = D::deflect(f, &load, &o.settings)?;
    let alpha = &found.alpha;
    let (stress, curvature_max) = D::bending(f, alpha)?;
    let shape = o.shape.map(|k| D::shape(f, alpha, k)).transpose()?;
    let error_estimate = D::estimate(f, &load, alpha, &o.target)?;
    let stability_limit = o.limit.map(|max| D::limit(f, &load, max)).transpose()?;
    let model = Deflected {
        alpha: D::alpha(f, alpha),
        pose: found.pose,
        stiffness: answer::rows(&found.stiffness),
        stable: found.equilibrium.stable,
        stability_test: D::stability_test(&load),
        residual: found.equilibrium.residual,
        // With a stability limit, its refined factor is the one number given.
        limit_fraction: found.equilibrium.limit.filter(|_| o.limit.is_none()),
        bending: Bending {
            safety_factor: safety_factor(stress.as_ref(), o.yield_strength),
            stress,
            curvature_max,
            shape,
        },
        refinement: o.auto.then(|| D::reached(f)),
        flagged: error_estimate.flagged,
        headroom: D::headroom(f, &error_estimate),
        error_estimate,
        stability_limit,
        length: D::flexure_length(f),
    };
    if !o.exact {
        return Ok(Deflection::Model(Box::new(model)));
    }
    let e = D::exact(f, &load, (&model.pose, model.bending.shape.as_ref()), (o.yield_strength, o.shape))?;
    Ok(Deflection::Exact(Box::new(ExactDeflected {
        pose: e.pose,
        root_moment: e.root_moment,
        stable: e.stable,
        stability_test: model.stability_test,
        model,
        error: e.compared,
        bending: e.bending,
    })))
}
