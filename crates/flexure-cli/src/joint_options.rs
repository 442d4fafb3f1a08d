//! The options of the commands on one flexure joint (kinematics, deflect,
//! compliance, buckling), planar and with `--spatial`.

use crate::options::{
    AccuracyOptions, FlexureOptions, List, ProfileArg, StressOptions, angle, iterations, number, numbers, profile,
    tolerance,
};
use clap::{Args, ValueEnum};
use flexure::model::SpatialKeys;
use flexure::{Error, TipConstraint, TipLoad};

#[derive(Debug, Args)]
pub struct KinematicsArgs {
    #[command(flatten)]
    pub(crate) flexure: FlexureOptions,
    #[command(flatten)]
    pub(crate) spatial: SpatialOptions,
    /// Joint coordinates α1,α2,… (one per order; with --spatial the twist's, then κ_y's, then κ_z's).
    #[arg(long, value_parser = numbers, allow_hyphen_values = true, required_unless_present = "input")]
    pub(crate) alpha: Option<List>,
    /// A CSV of α rows with header a1,a2,…: one output line per row.
    #[arg(long, conflicts_with = "alpha")]
    pub input: Option<std::path::PathBuf>,
}

impl KinematicsArgs {
    pub fn flexure(&self) -> flexure::Result<flexure::Flexure> {
        if self.spatial.spatial {
            return Err(Error::invalid("input", "given with --spatial", "batches are for planar flexures only"));
        }
        self.flexure.build_fixed("kinematics")
    }
}

/// A tip load: `--moment`, and `--force P --angle θ` or `--fx --fy`.
#[derive(Debug, Clone, Args)]
pub struct LoadOptions {
    /// Tip moment M in N·m (counter-clockwise positive).
    #[arg(long, default_value = "0", value_parser = number, allow_hyphen_values = true)]
    pub moment: f64,
    /// Tip force magnitude P in N, at --angle θ: Fx = −P sin θ, Fy = P cos θ (paper Sec. III-C).
    #[arg(long, value_parser = number, allow_hyphen_values = true, conflicts_with_all = ["fx", "fy"])]
    pub force: Option<f64>,
    /// Angle θ of --force, radians or e.g. 45deg [default: 0, across the flexure].
    #[arg(long, value_parser = angle, allow_hyphen_values = true, requires = "force")]
    pub angle: Option<f64>,
    /// Tip force along the root's x axis, N.
    #[arg(long, value_parser = number, allow_hyphen_values = true)]
    pub fx: Option<f64>,
    /// Tip force along the root's y axis, N.
    #[arg(long, value_parser = number, allow_hyphen_values = true)]
    pub fy: Option<f64>,
}

impl LoadOptions {
    pub fn load(&self) -> TipLoad {
        match self.force {
            Some(p) => TipLoad::polar(self.moment, p, self.angle.unwrap_or(0.0)),
            None => TipLoad { moment: self.moment, fx: self.fx.unwrap_or(0.0), fy: self.fy.unwrap_or(0.0) },
        }
    }
}

#[derive(Debug, Args)]
pub struct DeflectArgs {
    #[command(flatten)]
    pub(crate) flexure: FlexureOptions,
    #[command(flatten)]
    pub(crate) spatial: SpatialOptions,
    #[command(flatten)]
    pub(crate) load: LoadOptions,
    #[command(flatten)]
    pub(crate) spatial_load: SpatialLoadOptions,
    #[command(flatten)]
    pub accuracy: AccuracyOptions,
    #[command(flatten)]
    pub(crate) stress: StressOptions,
    /// Also solve the exact elastica (shooting); `pose` is then the exact one,
    /// and the model's stress and shape sit under `model`.
    #[arg(long)]
    pub(crate) exact: bool,
    /// Also find the factor on the load, up to 1000, at which the equilibrium
    /// followed from rest stops being stable, or up to which it stays stable
    /// (1000, or as far as the path could be followed, with a warning):
    /// `stability_limit` {factor, status: lost | stable_up_to}.
    #[arg(long)]
    pub(crate) limit: bool,
    /// Relative tolerance on the generalized-force residual, in (0, 1).
    #[arg(long, default_value = "1e-12", value_parser = tolerance, allow_hyphen_values = true)]
    pub(crate) tolerance: f64,
    /// Newton iterations allowed per load step, 1 to 10000.
    #[arg(long, default_value = "50", value_parser = iterations, allow_hyphen_values = true)]
    pub(crate) max_iterations: usize,
    /// A CSV of loads with header among moment,fx,fy (or moment,force,angle): one line per row.
    #[arg(
        long,
        conflicts_with_all = ["moment", "force", "angle", "fx", "fy", "exact", "limit", "yield_strength", "shape"]
    )]
    pub input: Option<std::path::PathBuf>,
}

impl DeflectArgs {
    /// The flexure for `--input` rows, which share one order.
    pub fn flexure(&self) -> flexure::Result<flexure::Flexure> {
        if self.spatial.spatial {
            return Err(Error::invalid("input", "given with --spatial", "batches are for planar flexures only"));
        }
        self.flexure.build_fixed("deflect --input")
    }
}

#[derive(Debug, Args)]
pub struct ComplianceArgs {
    #[command(flatten)]
    pub(crate) flexure: FlexureOptions,
    #[command(flatten)]
    pub(crate) spatial: SpatialOptions,
    /// Integrate the compliance ODE (Eq. 34, with EI(s)) instead of the model's J K⁻¹ Jᵀ.
    #[arg(long)]
    pub(crate) exact: bool,
}

#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum Tip {
    Free,
    Guided,
    Pinned,
    Clamped,
}

impl From<Tip> for TipConstraint {
    fn from(t: Tip) -> Self {
        match t {
            Tip::Free => TipConstraint::Free,
            Tip::Guided => TipConstraint::Guided,
            Tip::Pinned => TipConstraint::Pinned,
            Tip::Clamped => TipConstraint::Clamped,
        }
    }
}

#[derive(Debug, Args)]
pub struct BucklingArgs {
    #[command(flatten)]
    pub(crate) flexure: FlexureOptions,
    /// How the tip is held.
    #[arg(long, value_enum)]
    pub(crate) tip: Tip,
    /// The exact load of a straight column instead of the model: Euler's
    /// closed form for a uniform one, shooting on the load for EI(s).
    #[arg(long)]
    pub(crate) exact: bool,
    #[command(flatten)]
    pub(crate) accuracy: crate::eigen::EigenAccuracyOptions,
}

/// The spatial flexure's own options (each needs `--spatial`).
#[derive(Debug, Clone, Args)]
pub struct SpatialOptions {
    /// Make the joint spatial: two bendings and a twist (curvature
    /// components twist, κ_y, κ_z, each of order --order), pose in SE(3).
    #[arg(long)]
    pub spatial: bool,
    /// Bending stiffness about y, EI_y in N·m²: V, or ROOT,TIP [default: --ei].
    #[arg(long, value_parser = profile, allow_hyphen_values = true, requires = "spatial", conflicts_with = "modulus")]
    pub ei_y: Option<ProfileArg>,
    /// Torsional stiffness GJ in N·m²: V, or ROOT,TIP [default: --ei].
    #[arg(long, value_parser = profile, allow_hyphen_values = true, requires = "spatial", conflicts_with = "modulus")]
    pub gj: Option<ProfileArg>,
    /// A round rod's diameter d in metres (with --modulus), in place of --width and --thickness.
    #[arg(long, value_parser = profile, allow_hyphen_values = true, requires_all = ["spatial", "modulus"])]
    pub diameter: Option<ProfileArg>,
    /// Shear modulus G in Pa (with --modulus), in place of --poisson.
    #[arg(long, value_parser = number, allow_hyphen_values = true, requires = "spatial", conflicts_with = "poisson")]
    pub shear_modulus: Option<f64>,
    /// Rest curvature coefficients of the bending about y (one per order) [default: straight].
    #[arg(long, value_parser = numbers, allow_hyphen_values = true, requires = "spatial")]
    pub kappa_y: Option<List>,
    /// Rest twist coefficients (one per order) [default: untwisted].
    #[arg(long, value_parser = numbers, allow_hyphen_values = true, requires = "spatial")]
    pub twist: Option<List>,
}

impl SpatialOptions {
    /// The spatial flexure's own keys with `--spatial`, for the library's door.
    pub fn keys(&self) -> Option<SpatialKeys> {
        let profile = |p: &Option<ProfileArg>| p.as_ref().map(|p| p.0.clone());
        let list = |l: &Option<List>| l.as_ref().map(|l| l.0.clone());
        self.spatial.then(|| SpatialKeys {
            ei_y: profile(&self.ei_y),
            gj: profile(&self.gj),
            diameter: profile(&self.diameter),
            shear_modulus: self.shear_modulus,
            kappa_y: list(&self.kappa_y),
            twist: list(&self.twist),
        })
    }
}

/// The out-of-plane load components (each needs `--spatial`).
#[derive(Debug, Clone, Args)]
pub struct SpatialLoadOptions {
    /// Tip moment about the root's x axis (a twist), N·m.
    #[arg(long, value_parser = number, allow_hyphen_values = true, requires = "spatial")]
    pub mx: Option<f64>,
    /// Tip moment about the root's y axis, N·m.
    #[arg(long, value_parser = number, allow_hyphen_values = true, requires = "spatial")]
    pub my: Option<f64>,
    /// Tip force along the root's z axis, N.
    #[arg(long, value_parser = number, allow_hyphen_values = true, requires = "spatial")]
    pub fz: Option<f64>,
}
