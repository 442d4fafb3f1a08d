//! The pseudo-rigid-body model's data: its kind, joints and fit.

use crate::error::{Error, Result};
use nalgebra::Point2;
use serde::ser::{Serialize, SerializeStruct, Serializer};

/// Which pseudo-rigid-body chain: Howell's one joint or Su's three.
/// Serialized, and parsed by [`str::parse`], as `"1R"` and `"3R"`
/// (parsing also accepts `"1r"` and `"3r"`).
///
/// # Example
/// ```
/// use flexure::prb::PrbKind;
/// assert_eq!("3r".parse::<PrbKind>()?, PrbKind::ThreeR);
/// assert_eq!(PrbKind::OneR.to_string(), "1R");
/// assert!("2R".parse::<PrbKind>().is_err());
/// # Ok::<(), flexure::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum PrbKind {
    /// One revolute joint at the characteristic pivot (Howell).
    #[serde(rename = "1R")]
    OneR,
    /// Three revolute joints (Su's 3R chain).
    #[serde(rename = "3R")]
    ThreeR,
}

impl PrbKind {
    /// The number of joints of the chain.
    pub fn joints(self) -> usize {
        match self {
            PrbKind::OneR => 1,
            PrbKind::ThreeR => 3,
        }
    }
}

impl std::fmt::Display for PrbKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            PrbKind::OneR => "1R",
            PrbKind::ThreeR => "3R",
        })
    }
}

impl std::str::FromStr for PrbKind {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self> {
        match s {
            "1R" | "1r" => Ok(PrbKind::OneR),
            "3R" | "3r" => Ok(PrbKind::ThreeR),
            _ => Err(Error::invalid("prb", s, "must be 1R or 3R")),
        }
    }
}

/// One revolute joint of the chain, in the flexure's root frame.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PrbJoint {
    /// The pivot's position at rest (m), root frame; serialized as `[x, y]`.
    #[serde(serialize_with = "point")]
    pub pivot: Point2<f64>,
    /// The spring torque $\tau(\theta) = k_1\theta + k_2\theta^2 + k_3\theta^3$:
    /// $[k_1, k_2, k_3]$ in N·m/rad, N·m/rad², N·m/rad³.
    pub stiffness: [f64; 3],
}

impl PrbJoint {
    /// The spring torque $\tau(\theta) = k_1\theta + k_2\theta^2 + k_3\theta^3$ (N·m).
    ///
    /// # Example
    /// ```
    /// use flexure::prb::PrbJoint;
    /// let j = PrbJoint { pivot: nalgebra::Point2::origin(), stiffness: [2.0, 0.5, -1.0] };
    /// assert_eq!(j.torque(2.0), 4.0 + 2.0 - 8.0);
    /// ```
    pub fn torque(&self, theta: f64) -> f64 {
        let [k1, k2, k3] = self.stiffness;
        theta * (k1 + theta * (k2 + theta * k3))
    }

    /// The spring's tangent stiffness $\tau^{\prime}(\theta) = k_1 + 2k_2\theta + 3k_3\theta^2$ (N·m/rad).
    ///
    /// # Example
    /// ```
    /// use flexure::prb::PrbJoint;
    /// let j = PrbJoint { pivot: nalgebra::Point2::origin(), stiffness: [2.0, 0.5, -1.0] };
    /// assert_eq!(j.tangent_stiffness(2.0), 2.0 + 2.0 - 12.0);
    /// ```
    pub fn tangent_stiffness(&self, theta: f64) -> f64 {
        let [k1, k2, k3] = self.stiffness;
        k1 + theta * (2.0 * k2 + theta * 3.0 * k3)
    }

    /// The spring's energy $\int_0^\theta\tau = \frac12k_1\theta^2 + \frac13k_2\theta^3 + \frac14k_3\theta^4$ (J).
    ///
    /// # Example
    /// ```
    /// use flexure::prb::PrbJoint;
    /// let j = PrbJoint { pivot: nalgebra::Point2::origin(), stiffness: [2.0, 3.0, 4.0] };
    /// assert_eq!(j.energy(1.0), 1.0 + 1.0 + 1.0);
    /// ```
    pub fn energy(&self, theta: f64) -> f64 {
        let [k1, k2, k3] = self.stiffness;
        theta * theta * (k1 / 2.0 + theta * (k2 / 3.0 + theta * k3 / 4.0))
    }
}

fn point<S: Serializer>(p: &Point2<f64>, s: S) -> std::result::Result<S::Ok, S::Error> {
    [p.x, p.y].serialize(s)
}

/// The largest error of a fit over its samples.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct FitError {
    /// Largest distance between the PRB tip and the model's tip (m).
    pub position: f64,
    /// Largest difference between the PRB tip frame's rotation and the model's tip angle (rad).
    pub angle: f64,
}

/// A pseudo-rigid-body chain fitted to a flexure ([`fit`](super::fit())).
///
/// Serialized as `{"prb", "gamma", "k_theta", "stiffness", "pivots",
/// "error": {"position", "angle"}, "flagged", "samples"}`, with `stiffness`
/// and `pivots` one row per joint, root to tip.
#[derive(Debug, Clone, PartialEq)]
pub struct PrbFit {
    /// The chain.
    pub kind: PrbKind,
    /// Its joints, root to tip: one for 1R, three for 3R.
    pub joints: Vec<PrbJoint>,
    /// The links' length fractions, root to tip: $[1-\gamma, \gamma]$ for 1R
    /// (Howell's $\gamma$ is the last), $[\gamma_0, \dots, \gamma_3]$ for 3R (Su's).
    pub gamma: Vec<f64>,
    /// The nondimensional spring constants: Howell's $K_\Theta$ for 1R
    /// ($k_1 = \gamma K_\Theta EI/L$), Su's $K_{\Theta i}$ for 3R ($k_{1,i} = K_{\Theta i}EI/L$).
    pub k_theta: Vec<f64>,
    /// The largest error over the samples, of the PRB equilibrium against the model's.
    pub error: FitError,
    /// Whether `error.position` exceeds 1 % of the flexure's length ([`super::FLAG_FRACTION`]).
    pub flagged: bool,
    /// The number of loads fitted.
    pub samples: usize,
}

impl Serialize for PrbFit {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let stiffness: Vec<[f64; 3]> = self.joints.iter().map(|j| j.stiffness).collect();
        let pivots: Vec<[f64; 2]> = self.joints.iter().map(|j| [j.pivot.x, j.pivot.y]).collect();
        let mut m = s.serialize_struct("PrbFit", 8)?;
        m.serialize_field("prb", &self.kind)?;
        m.serialize_field("gamma", &self.gamma)?;
        m.serialize_field("k_theta", &self.k_theta)?;
        m.serialize_field("stiffness", &stiffness)?;
        m.serialize_field("pivots", &pivots)?;
        m.serialize_field("error", &self.error)?;
        m.serialize_field("flagged", &self.flagged)?;
        m.serialize_field("samples", &self.samples)?;
        m.end()
    }
}
