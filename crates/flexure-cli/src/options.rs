//! Options shared by every subcommand, and the parsers that reject bad numbers.

use clap::Args;
use flexure::Flexure;
use flexure::FlexureSpec;
use flexure::section::{Notch, Profile, SectionSpec};

/// Parses a finite number.
pub fn number(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().parse().map_err(|_| format!("{s:?} is not a number"))?;
    if v.is_finite() { Ok(v) } else { Err(format!("{s:?} is not a finite number")) }
}

/// Parses an angle: radians, or degrees with a `deg` suffix (`45deg`).
/// Also tells whether it is a bare number larger than 2π in magnitude,
/// which was probably meant in degrees.
pub fn parse_angle(s: &str) -> Result<(f64, bool), String> {
    match s.trim().strip_suffix("deg") {
        Some(d) => number(d).map(|v| (v.to_radians(), false)),
        None => number(s).map(|v| (v, v.abs() > std::f64::consts::TAU)),
    }
}

/// Parses the angle given to `option`, warning when a bare number exceeds 2π.
pub fn angle_of(option: &str, s: &str) -> Result<f64, String> {
    let (v, bare_and_large) = parse_angle(s)?;
    if bare_and_large {
        let t = s.trim();
        warn(format!("{option} {t} is read as radians ({:.0}°); write {t}deg for degrees", v.to_degrees()));
    }
    Ok(v)
}

/// Parses `--angle`: radians, or degrees with a `deg` suffix.
pub fn angle(s: &str) -> Result<f64, String> {
    angle_of("--angle", s)
}

/// Parses a whole number from `min` to `max`. Comparing the text's value
/// before anything is sized by it keeps a huge count from allocating.
pub fn count(s: &str, min: usize, max: usize) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(v) if (min..=max).contains(&v) => Ok(v),
        _ => Err(format!("{s:?} is not a whole number from {min} to {max}")),
    }
}

/// `--order`: from 1 to [`flexure::flexure::MAX_ORDER`], or `auto`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Order {
    /// A given order.
    Fixed(usize),
    /// Raise order and quadrature until the error estimate meets `--accuracy`.
    Auto,
}

/// Parses `--order`: a whole number from 1 to 64, or `auto`.
pub fn order(s: &str) -> Result<Order, String> {
    if s.trim() == "auto" {
        return Ok(Order::Auto);
    }
    count(s, 1, flexure::flexure::MAX_ORDER).map(Order::Fixed).map_err(|e| format!("{e}, or auto"))
}

/// Parses `--accuracy POS,ANGLE[,STRESS]`: the position tolerance as a
/// fraction of the length, the angle tolerance in radians or with `deg`,
/// and the peak stress (or curvature) tolerance as a fraction of the peak.
pub fn accuracy(s: &str) -> Result<flexure::estimate::Accuracy, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if !(2..=3).contains(&parts.len()) {
        return Err(format!("{s:?} must be POS,ANGLE or POS,ANGLE,STRESS (for example 0.005,0.5deg,0.02)"));
    }
    let mut target = flexure::estimate::Accuracy {
        position: number(parts[0])?,
        angle: parse_angle(parts[1])?.0,
        ..Default::default()
    };
    if let Some(stress) = parts.get(2) {
        target.stress = number(stress)?;
    }
    target.validate().map_err(|_| format!("{s:?}: every tolerance must be finite and greater than zero"))?;
    Ok(target)
}

/// `--accuracy`: the target every model answer's error estimate is held to.
#[derive(Debug, Clone, Args)]
pub struct AccuracyOptions {
    /// Accuracy target POS,ANGLE[,STRESS]: position as a fraction of L,
    /// angle in radians or with deg, and peak stress (curvature without a
    /// thickness) as a fraction of the peak. An answer whose error estimate
    /// exceeds it is flagged, with a warning [default: 0.01,1deg,0.01].
    #[arg(long, value_parser = accuracy, allow_hyphen_values = true)]
    pub accuracy: Option<flexure::estimate::Accuracy>,
}

impl AccuracyOptions {
    /// The target, or the default 1 % of L and 1°.
    pub fn target(&self) -> flexure::estimate::Accuracy {
        self.accuracy.unwrap_or_default()
    }
}

/// `--quadrature`: from 1 to [`flexure::quadrature::MAX_POINTS`].
pub fn quadrature(s: &str) -> Result<usize, String> {
    count(s, 1, flexure::quadrature::MAX_POINTS)
}

/// `--segments`: from 1 to [`flexure::flexure::MAX_SEGMENTS`].
pub fn segments(s: &str) -> Result<usize, String> {
    count(s, 1, flexure::flexure::MAX_SEGMENTS)
}

/// Most Newton iterations one load step may take: enough for any problem
/// that converges (the default is 50), few enough to stop soon on one that does not.
pub const MAX_ITERATIONS: usize = 10_000;

/// `--max-iterations`: from 1 to [`MAX_ITERATIONS`].
pub fn iterations(s: &str) -> Result<usize, String> {
    count(s, 1, MAX_ITERATIONS)
}

/// A step budget: a whole number from 1 to 1e9 (`1e6` is accepted).
pub fn steps(s: &str) -> Result<usize, String> {
    let v = number(s)?;
    if v.fract() == 0.0 && (1.0..=1e9).contains(&v) {
        Ok(v as usize)
    } else {
        Err(format!("{s:?} must be a whole number from 1 to 1e9"))
    }
}

/// A relative tolerance: a finite number in (0, 1).
pub fn tolerance(s: &str) -> Result<f64, String> {
    let v = number(s)?;
    if v > 0.0 && v < 1.0 { Ok(v) } else { Err(format!("{s:?} must be greater than 0 and less than 1")) }
}

thread_local! {
    /// Warnings raised while parsing, for [`crate::run`] to write on stderr.
    static WARNINGS: std::cell::RefCell<Vec<String>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Queues a warning; value parsers have no stream of their own to write it
/// to. A warning already queued is not queued twice (a file read twice, a
/// flexure built again at a higher order, says it once).
pub fn warn(message: String) {
    WARNINGS.with(|w| {
        let mut w = w.borrow_mut();
        if !w.contains(&message) {
            w.push(message);
        }
    });
}

thread_local! {
    /// Notes (information, not warnings) for [`crate::run`] to write on stderr.
    static NOTES: std::cell::RefCell<Vec<String>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Queues a note: something the input says is meant, told on stderr as `note: …`.
pub fn note(message: String) {
    NOTES.with(|w| w.borrow_mut().push(message));
}

/// The queued notes, oldest first; the queue is left empty.
pub fn take_notes() -> Vec<String> {
    NOTES.with(|w| std::mem::take(&mut *w.borrow_mut()))
}

/// The queued warnings, oldest first; the queue is left empty.
pub fn take_warnings() -> Vec<String> {
    WARNINGS.with(|w| std::mem::take(&mut *w.borrow_mut()))
}

/// A comma-separated list of finite numbers (a newtype: clap reads a bare
/// `Vec` as a repeated option).
#[derive(Debug, Clone, PartialEq)]
pub struct List(pub Vec<f64>);

/// Parses a comma-separated list of finite numbers.
pub fn numbers(s: &str) -> Result<List, String> {
    s.split(',').map(number).collect::<Result<_, _>>().map(List)
}

/// A quantity along the flexure from the command line: `V` (constant) or
/// `ROOT,TIP` (a linear taper). Tables are for files and the library.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileArg(pub Profile);

/// Parses `V` or `ROOT,TIP` (finite numbers; their sign is checked with the section).
pub fn profile(s: &str) -> Result<ProfileArg, String> {
    let parts: Vec<&str> = s.split(',').collect();
    match parts[..] {
        [v] => Ok(ProfileArg(Profile::Constant(number(v)?))),
        [root, tip] => Ok(ProfileArg(Profile::Linear { root: number(root)?, tip: number(tip)? })),
        _ => Err(format!("{s:?} must be V, or ROOT,TIP for a linear taper")),
    }
}

/// Parses `--notch R,H`: the cut-outs' radius and the thickness left at the middle (m).
pub fn notch(s: &str) -> Result<Notch, String> {
    match s.split(',').collect::<Vec<_>>()[..] {
        [r, h] => Ok(Notch { radius: number(r)?, min_thickness: number(h)? }),
        _ => Err(format!("{s:?} must be R,H: the notch's radius and its least thickness, in metres")),
    }
}

/// Parses a finite number greater than zero (a strength, a density).
pub fn positive(s: &str) -> Result<f64, String> {
    let v = number(s)?;
    if v > 0.0 { Ok(v) } else { Err(format!("{s:?} must be greater than zero")) }
}

/// Most points of a `--shape` (or a file's `shape`): enough to plot any
/// deflection line smoothly, few enough to print.
pub const MAX_SHAPE: usize = flexure::mechanism::file::MAX_SHAPE;

/// Parses `--shape K`: from 2 to [`MAX_SHAPE`] points.
pub fn shape(s: &str) -> Result<usize, String> {
    count(s, 2, MAX_SHAPE)
}

/// The flexure: `--length`, `--ei` (or `--modulus --width --thickness [--poisson]`
/// with an optional `--notch`), mass (`--density` or `--mass-per-length`),
/// `--kappa`, `--order`, `--quadrature`.
#[derive(Debug, Clone, Args)]
pub struct FlexureOptions {
    /// Length L in metres.
    #[arg(long, default_value = "1", value_parser = number, allow_hyphen_values = true)]
    pub length: f64,
    /// Bending stiffness EI in N·m²: V, or ROOT,TIP for a linear taper
    /// [default: 1, or from --modulus --width --thickness]. No thickness, so
    /// answers report curvature_max instead of stress.
    #[arg(long, value_parser = profile, allow_hyphen_values = true, conflicts_with = "modulus")]
    pub ei: Option<ProfileArg>,
    /// Young's modulus E in Pa (with --width and --thickness, or a spatial
    /// rod's --diameter, in place of --ei; the library names what is missing).
    #[arg(long, value_parser = number, allow_hyphen_values = true)]
    pub modulus: Option<f64>,
    /// Width b in metres: V, or ROOT,TIP for a linear taper.
    #[arg(long, value_parser = profile, allow_hyphen_values = true, requires = "modulus")]
    pub width: Option<ProfileArg>,
    /// Thickness h in metres: V, or ROOT,TIP for a linear taper.
    #[arg(long, value_parser = profile, allow_hyphen_values = true, requires = "modulus")]
    pub thickness: Option<ProfileArg>,
    /// Poisson ratio ν: a wide flexure, EI = E/(1−ν²)·b·h³/12 (Eq. 25).
    #[arg(long, value_parser = number, allow_hyphen_values = true, requires = "modulus")]
    pub poisson: Option<f64>,
    /// A circular notch hinge R,H: two circular cut-outs of radius R centred
    /// on the flexure, leaving thickness H at its middle (m).
    #[arg(long, value_parser = notch, allow_hyphen_values = true, requires = "modulus")]
    pub notch: Option<Notch>,
    /// Density in kg/m³ (with --width and --thickness): mass per length
    /// density·b·h, for `modes` (a single joint has no gravity to weigh it).
    #[arg(long, value_parser = number, allow_hyphen_values = true, conflicts_with = "mass_per_length")]
    pub density: Option<f64>,
    /// Mass per length in kg/m: V, or ROOT,TIP, for `modes` (a single joint
    /// has no gravity to weigh it).
    #[arg(long, value_parser = profile, allow_hyphen_values = true)]
    pub mass_per_length: Option<ProfileArg>,
    /// Rest curvature coefficients κ1,κ2,… (one per order) [default: straight].
    #[arg(long, value_parser = numbers, allow_hyphen_values = true)]
    pub kappa: Option<List>,
    /// Order N: the number of curvature coefficients, 1 to 64; or `auto`
    /// (deflect, tendon, connect, buckling, modes): from 3, raise order and
    /// quadrature until the error estimate meets --accuracy.
    #[arg(long, default_value = "3", value_parser = order, allow_hyphen_values = true)]
    pub order: Order,
    /// Gauss–Legendre points, 1 to 1024 [default: order + 2].
    #[arg(long, value_parser = quadrature, allow_hyphen_values = true)]
    pub quadrature: Option<usize>,
}

impl FlexureOptions {
    /// Builds the flexure, refusing `--order auto` where `command` has no error estimate.
    pub fn build_fixed(&self, command: &'static str) -> flexure::Result<Flexure> {
        self.fixed(command)?;
        self.build()
    }

    /// Refuses `--order auto` where `command` has no error estimate.
    pub fn fixed(&self, command: &'static str) -> flexure::Result<()> {
        if self.order == Order::Auto {
            return Err(flexure::Error::invalid(
                "order",
                "auto",
                match command {
                    "kinematics" => "kinematics takes coordinates of a given order: give a number",
                    "deflect --input" => "the rows of --input share one order: give a number",
                    "buckling --exact" => "--exact uses no model order: give a number, or drop --exact",
                    _ => "auto applies to deflect, tendon, connect, buckling and modes: give a number here",
                },
            ));
        }
        Ok(())
    }

    /// Whether `--order auto` was given.
    pub fn auto(&self) -> bool {
        self.order == Order::Auto
    }

    /// The flexure the options describe, for the library to build.
    pub fn spec(&self) -> FlexureSpec {
        let profile = |p: &Option<ProfileArg>| p.as_ref().map(|p| p.0.clone());
        FlexureSpec {
            length: self.length,
            section: SectionSpec {
                ei: profile(&self.ei),
                modulus: self.modulus,
                width: profile(&self.width),
                thickness: profile(&self.thickness),
                poisson: self.poisson,
                notch: self.notch,
                density: self.density,
                mass_per_length: profile(&self.mass_per_length),
            },
            // `--order auto` starts from 3.
            order: match self.order {
                Order::Fixed(n) => n,
                Order::Auto => 3,
            },
            quadrature: self.quadrature,
            kappa: self.kappa.as_ref().map(|k| k.0.clone()),
        }
    }

    /// Builds and validates the flexure (order 3 to start from, for `--order auto`).
    pub fn build(&self) -> flexure::Result<Flexure> {
        self.hint_units(None);
        self.spec().build()
    }

    /// Warns of a `--modulus` or `--length` implausible as given, with what
    /// was probably meant ([`flexure::section::unit_hints`]); `diameter` is a
    /// spatial rod's, in place of `--thickness`.
    pub fn hint_units(&self, diameter: Option<&ProfileArg>) {
        let largest = |p: &ProfileArg| p.0.at(0.0).max(p.0.at(1.0));
        let thickness = self.thickness.as_ref().or(diameter).map(largest);
        for h in flexure::section::unit_hints(self.length, self.modulus, thickness) {
            warn(format!("--{} {}", h.name, h.message));
        }
    }
}

/// What an answer reports of the flexure's stress: `--yield-strength` and `--shape`.
#[derive(Debug, Clone, Args)]
pub struct StressOptions {
    /// Yield strength S in Pa (needs a thickness): adds safety_factor =
    /// S/σmax, and a warning when it is below 1.
    #[arg(long, value_parser = positive, allow_hyphen_values = true)]
    pub yield_strength: Option<f64>,
    /// Print the deformed flexure at K points evenly spaced in arc length,
    /// ends included (2 to 10000): shape: [{s, x, y, phi, curvature, stress}];
    /// deflect --spatial gives [{s, x, y, z, roll, pitch, yaw, rotation, curvature: {twist, kappa_y, kappa_z}, stress}].
    #[arg(long, value_parser = shape, allow_hyphen_values = true)]
    pub shape: Option<usize>,
}
