//! Where a spatial strip's width passes through a geom. A spatial flexure
//! touches geoms with the tube of half its thickness about its centreline
//! (module docs of [`super`]); a strip's edges reach a further half of its
//! width off its bending plane, which contact leaves out. So that this is
//! never silent, [`width_crossings`] finds the geoms that a strip's width
//! passes through, as a finding.

use super::{Toucher, pairs};
use crate::mechanism::Mechanism;
use crate::mechanism::findings::{Crossing, Part};
use crate::section::Outline;
use crate::space::Spatial;
use crate::spatial::SpatialPoint;
use nalgebra::{Isometry3, Point3, Vector3};

/// Sections sampled along each strip.
const SECTIONS: usize = 65;

/// Points across the width sampled on each side of the centreline, on each
/// face and between them: at $\tfrac14, \tfrac12, \tfrac34$ and 1 of the
/// half width.
const ACROSS: [f64; 4] = [0.25, 0.5, 0.75, 1.0];

/// Each strip of `m` at `q` (a rectangle section wider than thick) whose
/// width passes through a geom it may touch, by more than `tolerance` (m),
/// where the tube of its thickness does not: the first such point along
/// it (world frame, m), its arc length, and how many sections do; `bodies`
/// and `roots` the bodies' and joints' root frames.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::width_crossings;
/// use flexure::mechanism::file::spatial_from_toml;
/// // A 10 mm wide blade beside a 1 mm ball 4 mm off its centreline, within its width.
/// let blade = "dimension = 3\n[[joint]]\nname = \"blade\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\n\
///              length = 0.05\nmodulus = 2e11\nwidth = 0.01\nthickness = 0.0005\npoisson = 0.3\n\
///              [[geom]]\nname = \"ball\"\nbody = \"ground\"\nshape = \"sphere\"\nradius = 0.001\n";
/// let m = spatial_from_toml(&format!("{blade}origin = [0.045, 0.0, 0.004]\n")).unwrap();
/// let (bodies, roots) = flexure::mechanism::findings::Findings::poses(&m, &m.rest());
/// let found = width_crossings(&m, &m.rest(), (&bodies, &roots), 1e-9);
/// assert_eq!(found.len(), 1);
/// assert!(found[0].message().starts_with("flexure \"blade\"'s width crosses geom \"ball\""));
/// // Moved off the blade's side: nothing.
/// let m = spatial_from_toml(&format!("{blade}origin = [0.045, 0.0, 0.0075]\n")).unwrap();
/// assert!(width_crossings(&m, &m.rest(), (&bodies, &roots), 1e-9).is_empty());
/// ```
pub fn width_crossings(
    m: &Mechanism<Spatial>,
    q: &[f64],
    (bodies, roots): (&[Isometry3<f64>], &[Isometry3<f64>]),
    tolerance: f64,
) -> Vec<Crossing<[f64; 3]>> {
    let mut out = Vec::new();
    // Each flexure's sections, drawn once for all the geoms it may touch.
    let mut drawn: Vec<Option<Vec<SpatialPoint>>> = vec![None; m.joints.len()];
    for pair in pairs(m) {
        let Toucher::Flexure(j) = pair.part else { continue };
        let (joint, geom) = (&m.joints[j], &m.geoms[pair.geom]);
        let Some(f) = joint.kind.flexure() else { continue };
        if drawn[j].is_none() {
            let alpha = &q[joint.offset..joint.offset + joint.kind.joint().dof()];
            // A shape that cannot be drawn is no finding: the solve said why.
            let Ok(sections) = crate::spatial::shape(f, alpha, SECTIONS) else { continue };
            drawn[j] = Some(sections);
        }
        let sections = drawn[j].as_deref().expect("just drawn");
        let at = &bodies[geom.body];
        let mut first: Option<(Point3<f64>, f64)> = None;
        let mut count = 0;
        for sec in sections {
            let Some(Outline::Rectangle { width, thickness }) = f.section().outline(sec.s / f.length()) else {
                continue;
            };
            if width <= thickness {
                continue;
            }
            let place = |y: f64, z: f64| {
                let r = &sec.rotation;
                let local = Vector3::from(sec.position)
                    + Vector3::new(r[0][1], r[1][1], r[2][1]) * y
                    + Vector3::new(r[0][2], r[1][2], r[2][2]) * z;
                roots[j] * Point3::from(local)
            };
            if geom.gap(at, &place(0.0, 0.0), 0.5 * thickness).0 < -tolerance {
                continue;
            }
            let faces = [-0.5 * thickness, 0.0, 0.5 * thickness];
            let inside = ACROSS.iter().flat_map(|k| [-k, *k]).flat_map(|k| faces.map(|y| place(y, k * 0.5 * width)));
            if let Some(p) = inside.into_iter().find(|p| geom.gap(at, p, 0.0).0 < -tolerance) {
                count += 1;
                first.get_or_insert((p, sec.s));
            }
        }
        if let Some((p, s)) = first {
            let (a, b) = (Part::Flexure(j), Part::Geom(pair.geom));
            let names = [a.describe(m), b.describe(m)];
            out.push(Crossing { a, b, names, at: [p.x, p.y, p.z], s: [Some(s), None], points: count });
        }
    }
    out
}
