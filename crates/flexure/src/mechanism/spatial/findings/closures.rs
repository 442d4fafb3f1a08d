//! Open closures of a spatial mechanism: a weld, pin or ball whose two
//! sides do not meet with every joint at rest, and the preload that closing
//! it puts into the unloaded mechanism, as the planar
//! [`crate::mechanism::findings::open_closures`] finds them (the same
//! [`OpenClosure`], and the same [`GAP_TOLERANCE`](crate::mechanism::findings::GAP_TOLERANCE)).

use crate::Level;
use crate::error::{Error, Result};
use crate::mechanism::findings::OpenClosure;
use crate::mechanism::findings::closures::{closure_name, first_rows, open_gaps};
use crate::mechanism::spatial::SpatialMechanism;
use crate::mechanism::spatial::kinematics::{SpatialFrames, frames_level_into};
use crate::mechanism::statics::assemble_unloaded;
use crate::mechanism::{Closure, Holds};
use crate::solver::Settings;
use nalgebra::{UnitQuaternion, Vector3};

/// Each closure's gap at rest: the distance between its two points (m),
/// and for a weld the angle between its two frames, for a pin that between
/// its two axes (rad, in $[0, \pi]$).
pub fn rest_gaps(m: &SpatialMechanism) -> Vec<(f64, Option<f64>)> {
    // Poses alone: the bodies' frames are the same at every level.
    let mut f = SpatialFrames::new(m);
    frames_level_into(m, &m.rest(), Level::Pose, &mut f);
    m.closures
        .iter()
        .map(|c| {
            let (fa, fb) = (f.bodies[c.a] * c.a_origin, f.bodies[c.b] * c.b_origin);
            let gap = (fa.translation.vector - fb.translation.vector).norm();
            match c.holds {
                Holds::Weld => {
                    let turn: UnitQuaternion<f64> = fa.rotation.inverse() * fb.rotation;
                    (gap, Some(turn.angle()))
                }
                Holds::Pin => {
                    // atan2 of sine and cosine: exact near 0, where acos loses half the digits.
                    let (za, zb) = (fa.rotation * Vector3::z(), fb.rotation * Vector3::z());
                    (gap, Some(za.cross(&zb).norm().atan2(za.dot(&zb))))
                }
                Holds::Ball => (gap, None),
            }
        })
        .collect()
}

/// The closures of `m` that do not meet at rest (by more than
/// [`GAP_TOLERANCE`](crate::mechanism::findings::GAP_TOLERANCE) of [`SpatialMechanism::size`], or of a radian), each
/// with the force and moment it carries in the unloaded, assembled
/// mechanism (`None` if that cannot be assembled from rest, as every solve
/// of it then says): a warning, or a note where the file says
/// `preload = true`. An error only if the assembly is interrupted.
///
/// # Example
/// ```
/// use flexure::mechanism::file::spatial_from_toml;
/// use flexure::mechanism::spatial::findings::open_closures;
/// // Two sprung hinges about z whose arms' tips meet 1 mm apart at rest: a ball closes them.
/// let m = spatial_from_toml("dimension = 3\n\
///     [[joint]]\nname = \"l\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"a\"\nstiffness = 1.0\n\
///     [[joint]]\nname = \"r\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"b\"\norigin = [0.2, 0.0, 0.0]\nstiffness = 1.0\n\
///     [[ball]]\na = \"a\"\na_at = [0.1, 0.0, 0.0]\nb = \"b\"\nb_at = [-0.099, 0.0, 0.0]\n").unwrap();
/// let open = open_closures(&m, &Default::default()).unwrap();
/// assert_eq!(open.len(), 1);
/// assert!((open[0].gap - 1e-3).abs() < 1e-12 && open[0].turn.is_none());
/// assert!(open[0].message().contains("ball of \"a\" and \"b\" is open at rest by 1.0"));
/// ```
pub fn open_closures(m: &SpatialMechanism, settings: &Settings) -> Result<Vec<OpenClosure>> {
    let open = open_gaps(rest_gaps(m), m.size());
    if open.is_empty() {
        return Ok(Vec::new());
    }
    let unloaded = match assemble_unloaded(m, settings) {
        Ok(s) => Some(s),
        Err(Error::File { .. } | Error::NoConvergence { .. } | Error::Singular { .. }) => None,
        Err(e) => return Err(e),
    };
    let rows = first_rows(m.closures.iter().map(Closure::equations));
    Ok(open
        .into_iter()
        .map(|(i, (gap, turn))| {
            // Multipliers: the force (3), then a weld's or pin's misalignment moment.
            let mu = unloaded.as_ref().map(|s| &s.multipliers[rows[i]..rows[i] + m.closures[i].equations()]);
            let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
            OpenClosure {
                closure: i,
                what: closure_name(m, i),
                place: m.closure_place(i).to_string(),
                gap,
                turn,
                force: mu.map(|mu| norm(&mu[..3])),
                moment: mu.filter(|mu| mu.len() > 3).map(|mu| norm(&mu[3..])),
                preload: m.closure_preload(i),
            }
        })
        .collect())
}
