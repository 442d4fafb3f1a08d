//! `mechanism/contact/jet.rs`: a pair's gap with its derivatives in the
//! coordinates and the arc length, against central differences of its own
//! value (step 1e-6, compared to 1e-6 of the largest first or second
//! derivative at the point: truncation about 1e-12, rounding about 1e-10
//! of values of order 1). The states are random, so some points lie
//! inside a shape, where the shapes' curvature must hold too. Every kind of
//! pair and motion: a flexure downstream of a hinge touching a post on the
//! ground and a capsule on a body that turns, and a ball on a moving body
//! touching a floor; in the plane and in space (with a sphere, a cylinder
//! and a box).

use flexure::mechanism::contact::{GapJet, Geom, GeomShape, Touch, Toucher, gap_jet, pairs};
use flexure::mechanism::file::{from_toml, spatial_from_toml};
use flexure::mechanism::kinematics::{FrameChain, frames};
use flexure::mechanism::{Dimension, Mechanism};

const PLANAR: &str = r#"
[[joint]]
name = "pin"
kind = "revolute"
parent = "ground"
child = "arm"
stiffness = 1.0
[[joint]]
name = "strip"
kind = "flexure"
parent = "arm"
child = "tip"
origin = [0.02, 0.01, 0.0]
length = 0.1
modulus = 2e11
width = 0.01
thickness = 0.001
order = 4
[[joint]]
name = "wrist"
kind = "revolute"
parent = "ground"
child = "hand"
origin = [0.05, 0.08, 0.0]
stiffness = 1.0
[[geom]]
name = "post"
body = "ground"
shape = "circle"
origin = [0.07, -0.05]
radius = 0.02
[[geom]]
name = "pad"
body = "hand"
shape = "capsule"
origin = [0.03, -0.01]
angle = 0.3
half_length = 0.02
radius = 0.005
[[geom]]
name = "floor"
body = "ground"
shape = "plane"
origin = [0.0, -0.2]
normal = [0.1, 1.0]
exclude = ["strip", "pad"]
[[geom]]
name = "knob"
body = "tip"
shape = "circle"
radius = 0.004
exclude = ["strip"]
"#;

const SPATIAL: &str = r#"
dimension = 3
[[joint]]
name = "pin"
kind = "revolute"
parent = "ground"
child = "arm"
axis = [0.0, 1.0, 0.2]
stiffness = 1.0
[[joint]]
name = "strip"
kind = "flexure"
parent = "arm"
child = "tip"
origin = [0.02, 0.01, 0.0]
length = 0.1
modulus = 2e11
width = 0.01
thickness = 0.001
order = 3
[[joint]]
name = "wrist"
kind = "revolute"
parent = "ground"
child = "hand"
origin = [0.05, 0.0, 0.08]
axis = [0.3, 1.0, 0.0]
stiffness = 1.0
[[geom]]
name = "ball"
body = "ground"
shape = "sphere"
origin = [0.07, 0.01, -0.05]
radius = 0.02
[[geom]]
name = "can"
body = "hand"
shape = "cylinder"
origin = [0.03, 0.0, -0.01]
rpy = [0.3, 1.2, 0.1]
half_length = 0.01
radius = 0.005
[[geom]]
name = "block"
body = "hand"
shape = "box"
origin = [0.0, 0.03, -0.03]
rpy = [0.1, 0.2, 0.3]
half_extents = [0.01, 0.002, 0.003]
[[geom]]
name = "knob"
body = "tip"
shape = "sphere"
radius = 0.004
exclude = ["strip"]
"#;

/// Seeded uniform numbers in [−1, 1) (xorshift64*).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

fn jet<D: Touch + FrameChain>(m: &Mechanism<D>, q: &[f64], pair: usize, s: Option<f64>) -> GapJet<D> {
    gap_jet(m, &frames(m, q), q, &pairs(m)[pair], s).unwrap()
}

/// Every derivative of every pair of `m` at seeded configurations, against differences.
fn check<D: Touch + FrameChain + Dimension>(m: &Mechanism<D>, seed: u64) -> usize {
    let mut rng = Rng(seed);
    let n = m.dof();
    let h = 1e-6;
    // Each derivative against 1e-6 of the largest of its kind at the point.
    let close = |a: f64, b: f64, size: f64, what: &str| {
        assert!((a - b).abs() <= 1e-6 * size, "{what}: exact {a:e}, differences {b:e} (size {size:e})")
    };
    let largest = |v: &mut dyn Iterator<Item = f64>| v.fold(f64::MIN_POSITIVE, |a, b| a.max(b.abs()));
    let mut checked = 0;
    for _ in 0..4 {
        let q: Vec<f64> = m.rest().iter().map(|q| q + 0.4 * rng.next()).collect();
        for (p, pair) in pairs(m).iter().enumerate() {
            let s = matches!(pair.part, Toucher::Flexure(_)).then(|| 0.05 + 0.045 * rng.next());
            let at = jet(m, &q, p, s);
            let first = largest(&mut at.gradient.iter().copied().chain([at.ds]));
            let second = largest(&mut at.hessian.iter().copied().chain(at.dqs.iter().copied()).chain([at.dss]));
            for c in 0..n {
                let (mut up, mut down) = (q.clone(), q.clone());
                up[c] += h;
                down[c] -= h;
                let (a, b) = (jet(m, &up, p, s), jet(m, &down, p, s));
                close(at.gradient[c], (a.gap - b.gap) / (2.0 * h), first, &format!("pair {p}: dg/dq{c}"));
                for r in 0..n {
                    let fd = (a.gradient[r] - b.gradient[r]) / (2.0 * h);
                    close(at.hessian[(r, c)], fd, second, &format!("pair {p}: d2g/dq{r}dq{c}"));
                }
                close(at.dqs[c], (a.ds - b.ds) / (2.0 * h), second, &format!("pair {p}: d2g/dq{c}ds"));
                for i in 0..D::POINT_DIM {
                    let fd = (a.normal[i] - b.normal[i]) / (2.0 * h);
                    close(at.normal_jacobian[c][i], fd, second, &format!("pair {p}: dn{i}/dq{c}"));
                }
                checked += 1;
            }
            if let Some(s) = s {
                let (a, b) = (jet(m, &q, p, Some(s + h)), jet(m, &q, p, Some(s - h)));
                close(at.ds, (a.gap - b.gap) / (2.0 * h), first, &format!("pair {p}: dg/ds"));
                close(at.dss, (a.ds - b.ds) / (2.0 * h), second, &format!("pair {p}: d2g/ds2"));
                for c in 0..n {
                    close(at.dqs[c], (a.gradient[c] - b.gradient[c]) / (2.0 * h), second, "d2g/dsdq");
                }
            }
        }
    }
    checked
}

/// Adds `shapes` on the ground at `frame`, around the strip (a file
/// refuses shapes a part starts inside), touching the strip alone.
fn around<D: Dimension>(m: &mut Mechanism<D>, frame: D::Pose, shapes: &[GeomShape<D>]) {
    let others: Vec<Toucher> = (0..m.geoms.len()).map(Toucher::Geom).collect();
    for (i, shape) in shapes.iter().enumerate() {
        let mut g = Geom::new(&format!("blob {i}"), 0, frame, *shape);
        g.exclude = others.clone();
        for earlier in 0..i {
            g.exclude.push(Toucher::Geom(m.geoms.len() - 1 - earlier));
        }
        m.geoms.push(g);
    }
}

#[test]
fn planar_gap_derivatives_match_differences() {
    let mut m = from_toml(PLANAR).unwrap();
    assert_eq!(pairs(&m).len(), 6);
    assert!(check(&m, 0x9E37_79B9_7F4A_7C15) >= 4 * 6 * m.dof());
    let frame = flexure::Pose { phi: 0.3, x: 0.08, y: 0.02 };
    around(&mut m, frame, &[GeomShape::Ball { radius: 0.2 }, GeomShape::Capsule { half_length: 0.03, radius: 0.15 }]);
    assert_eq!(pairs(&m).len(), 8);
    assert!(check(&m, 0x9E37_79B9_7F4A_7C15) >= 4 * 8 * m.dof());
}

#[test]
fn spatial_gap_derivatives_match_differences() {
    let mut m = spatial_from_toml(SPATIAL).unwrap();
    assert_eq!(pairs(&m).len(), 8);
    assert!(check(&m, 0x2545_F491_4F6C_DD1D) >= 4 * 8 * m.dof());
    let frame =
        nalgebra::Isometry3::new(nalgebra::Vector3::new(0.08, 0.02, 0.01), nalgebra::Vector3::new(0.1, 1.4, 0.2));
    let inside = [
        GeomShape::Ball { radius: 0.2 },
        GeomShape::Capsule { half_length: 0.03, radius: 0.15 },
        GeomShape::Cylinder { half_length: 0.3, radius: 0.15 },
    ];
    around(&mut m, frame, &inside);
    assert_eq!(pairs(&m).len(), 11);
    assert!(check(&m, 0x2545_F491_4F6C_DD1D) >= 4 * 11 * m.dof());
}

/// A section's axes and a material point off its centreline
/// (`offset_jet`), which turn with the section (in space with its twist):
/// the axes against the rotation of `spatial::shape_at` (an independent
/// integration) to 1e-12, the point's Jacobian and Hessian against central
/// differences of its value and Jacobian (step 1e-6, to 1e-6 of the
/// largest), at seeded coordinates of the spatial strip and the planar one.
#[test]
fn a_sections_surface_point_turns_with_it() {
    use flexure::mechanism::contact::offset_jet;
    fn points<D: Touch>(f: &D::Flexure, alpha: &[f64], s: f64, offset: [f64; 3]) {
        let h = 1e-6;
        let at = |a: &[f64]| offset_jet(&D::section_jet(f, a, s).unwrap(), offset);
        let x = at(alpha);
        let k = alpha.len();
        let first = x.jacobian.iter().flat_map(|v| (0..D::POINT_DIM).map(move |i| v[i].abs())).fold(0.0, f64::max);
        let second = x.hessian.iter().flat_map(|m| m.iter().map(|v| v.abs())).fold(0.0, f64::max);
        for a in 0..k {
            let (mut up, mut down) = (alpha.to_vec(), alpha.to_vec());
            up[a] += h;
            down[a] -= h;
            let (u, d) = (at(&up), at(&down));
            for i in 0..D::POINT_DIM {
                let fd = (u.point[i] - d.point[i]) / (2.0 * h);
                assert!((x.jacobian[a][i] - fd).abs() < 1e-6 * first, "dx{i}/da{a}: {} vs {fd}", x.jacobian[a][i]);
                for b in 0..k {
                    let fd = (u.jacobian[b][i] - d.jacobian[b][i]) / (2.0 * h);
                    assert!((x.hessian[i][(b, a)] - fd).abs() < 1e-6 * second, "d2x{i}/da{b}da{a}");
                }
            }
        }
        // Off the centreline by the offset in the section's axes, which are the tangent first.
        let jet = D::section_jet(f, alpha, s).unwrap();
        let t = (0..D::POINT_DIM).map(|i| (jet.frame[0][i] - jet.tangent[i]).abs()).fold(0.0, f64::max);
        assert!(t < 1e-15 && x.frame.len() == D::POINT_DIM);
    }
    let mut rng = Rng(0x5DEE_CE66_D1CE_4E5B);
    let m = spatial_from_toml(SPATIAL).unwrap();
    let f = m.joints[1].kind.flexure().unwrap();
    for _ in 0..3 {
        let alpha: Vec<f64> = (0..m.joints[1].kind.joint().dof()).map(|_| 20.0 * rng.next()).collect();
        let s = 0.05 + 0.045 * rng.next();
        points::<flexure::space::Spatial>(f, &alpha, s, [0.0004 * rng.next(), 0.0005, -0.0003]);
        let jet = flexure::space::Spatial::section_jet(f, &alpha, s).unwrap();
        let r = flexure::spatial::shape_at(f, &alpha, &[s]).unwrap()[0].rotation;
        for (j, e) in jet.frame.iter().enumerate() {
            for i in 0..3 {
                assert!((e[i] - r[i][j]).abs() < 1e-12, "axis {j}: {e} vs column {j} of {r:?}");
            }
        }
    }
    let m = from_toml(PLANAR).unwrap();
    let f = m.joints[1].kind.flexure().unwrap();
    let alpha: Vec<f64> = (0..m.joints[1].kind.joint().dof()).map(|_| 5.0 * rng.next()).collect();
    points::<flexure::space::Planar>(f, &alpha, 0.07, [0.0003, -0.0005, 0.0]);
}

/// Two bars crossing and a rod (a capsule) across the lower one, each on
/// a hinge of its own (the upper bar's hinged on the lower's body, so a
/// coordinate turns both and another the upper alone): where the pair of
/// two geoms nearest each other is two edges crossing
/// (`mechanism/contact/crossing.rs`), its gap is the lines' signed
/// distance, whose normal turns with both bodies. The rod is the geom
/// touched by the lower bar's edge (a rounded edge on that side), and the
/// lower bar the geom touched by the upper's. Its derivatives against
/// central differences as above, at seeded states near the crossing (each
/// fails without the normal's turn in the Hessian: 1e-6 of the largest).
#[test]
fn two_edges_crossing_gap_derivatives_match_differences() {
    let m = spatial_from_toml(
        r#"
dimension = 3
[[joint]]
name = "lower"
kind = "revolute"
parent = "ground"
child = "base"
axis = [0.2, 1.0, 0.3]
stiffness = 1.0
[[joint]]
name = "upper"
kind = "revolute"
parent = "base"
child = "top"
origin = [0.0, 0.0, 0.05]
axis = [1.0, 0.1, -0.2]
stiffness = 1.0
[[joint]]
name = "cradle"
kind = "revolute"
parent = "ground"
child = "holder"
origin = [0.01, 0.0, 0.0]
axis = [0.3, -0.2, 1.0]
stiffness = 1.0
[[geom]]
name = "rod"
body = "holder"
shape = "capsule"
origin = [-0.01, 0.0, 0.009]
rpy = [0.0, 0.0, 1.4]
half_length = 0.04
radius = 0.0031
[[geom]]
name = "bar"
body = "base"
shape = "box"
origin = [0.0, 0.0, 0.02]
rpy = [0.7, 0.0, 0.0]
half_extents = [0.05, 0.004, 0.004]
[[geom]]
name = "beam"
body = "top"
shape = "box"
origin = [0.0, 0.0, -0.0194]
rpy = [0.6, 0.0, 1.5]
half_extents = [0.05, 0.004, 0.003]
"#,
    )
    .unwrap();
    let (mut rng, n, h) = (Rng(0x5851_F42D_4C95_7F2D), m.dof(), 1e-6);
    let all = pairs(&m);
    let mut checked = 0;
    for _ in 0..12 {
        let q: Vec<f64> = (0..n).map(|_| 0.02 * rng.next()).collect();
        let f = frames(&m, &q);
        for parts in [(0, 1), (1, 2)] {
            // The pair of these two geoms nearest: two edges where it is past the corners.
            let of: Vec<usize> =
                (0..all.len()).filter(|&p| (all[p].geom, all[p].part) == (parts.0, Toucher::Geom(parts.1))).collect();
            let corners =
                flexure::mechanism::contact::corners(&m.geoms[parts.0].shape, &m.geoms[parts.1].shape).unwrap().len();
            let gap = |p: usize| flexure::mechanism::contact::gap(&m, &q, &f.bodies, &all[p]).unwrap().gap;
            let p = *of.iter().min_by(|a, b| gap(**a).total_cmp(&gap(**b))).unwrap();
            if all[p].corner < corners {
                continue;
            }
            let at = jet(&m, &q, p, None);
            let first = at.gradient.iter().fold(f64::MIN_POSITIVE, |a, b| a.max(b.abs()));
            let second = at.hessian.iter().fold(f64::MIN_POSITIVE, |a, b| a.max(b.abs()));
            for c in 0..n {
                let (mut up, mut down) = (q.clone(), q.clone());
                up[c] += h;
                down[c] -= h;
                let (a, b) = (jet(&m, &up, p, None), jet(&m, &down, p, None));
                let fd = (a.gap - b.gap) / (2.0 * h);
                assert!(
                    (at.gradient[c] - fd).abs() <= 1e-6 * first,
                    "pair {p}: dg/dq{c} {} against {fd}",
                    at.gradient[c]
                );
                for r in 0..n {
                    let fd = (a.gradient[r] - b.gradient[r]) / (2.0 * h);
                    let e = at.hessian[(r, c)];
                    assert!((e - fd).abs() <= 1e-6 * second, "pair {p}: d2g/dq{r}dq{c} {e} against {fd}");
                }
                for i in 0..3 {
                    let fd = (a.normal[i] - b.normal[i]) / (2.0 * h);
                    let e = at.normal_jacobian[c][i];
                    assert!((e - fd).abs() <= 1e-6 * second.max(1.0), "pair {p}: dn{i}/dq{c} {e} against {fd}");
                }
            }
            checked += 1;
        }
    }
    assert!(checked >= 12, "{checked} edge pairs checked");
}

/// A box's corner in the plane of a face of the box it touches, both
/// faces facing the same way (two boxes of one width, half extents 50 mm,
/// the upper on a slider along z and a hinge about y at its centre, 0.2 m
/// above the lower): at $q = (-0.1, 0.1)$ its corner $(0.05, 0.05, -0.05)$
/// lies in the lower box's face $y = 0.05$ and sinks below its top, at
/// $z = 0.1 - 0.05(\sin 0.1 + \cos 0.1)$. Its gap is the top face's,
/// $z - 0.05$, along $+z$, to 1e-15 m (as the face $y = 0.05$ it read 0),
/// and its derivatives match central differences (step 1e-6, to 1e-6 of
/// the largest).
#[test]
fn a_corner_in_a_face_plane_facing_as_its_own_reads_the_other_faces_gap() {
    let m = spatial_from_toml(
        "dimension = 3\n[[joint]]\nname = \"slide\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"c\"\naxis = [0.0, 0.0, 1.0]\nstiffness = 100.0\n\
         [[joint]]\nname = \"tilt\"\nkind = \"revolute\"\nparent = \"c\"\nchild = \"b\"\norigin = [0.0, 0.0, 0.2]\naxis = [0.0, 1.0, 0.0]\nstiffness = 1.0\n\
         [[geom]]\nname = \"B\"\nbody = \"ground\"\nshape = \"box\"\nhalf_extents = [0.05, 0.05, 0.05]\n\
         [[geom]]\nname = \"A\"\nbody = \"b\"\nshape = \"box\"\nhalf_extents = [0.05, 0.05, 0.05]\n",
    )
    .unwrap();
    let q = [-0.1, 0.1];
    let z = 0.1 - 0.05 * (0.1f64.sin() + 0.1f64.cos());
    let all = pairs(&m);
    // The upper box's corners come first (16 corners, then pairs of edges).
    let p = (0..16).min_by(|&a, &b| jet(&m, &q, a, None).gap.total_cmp(&jet(&m, &q, b, None).gap)).unwrap();
    assert!(all[p].corner < 8, "{:?}: a corner of the upper box", all[p]);
    let at = jet(&m, &q, p, None);
    assert!((at.gap - (z - 0.05)).abs() < 1e-15, "{} against {}", at.gap, z - 0.05);
    assert!((at.normal - nalgebra::Vector3::z()).norm() < 1e-15, "{}", at.normal);
    let h = 1e-6;
    let largest = at.gradient.iter().fold(f64::MIN_POSITIVE, |a, b| a.max(b.abs()));
    for c in 0..2 {
        let (mut up, mut down) = (q.to_vec(), q.to_vec());
        up[c] += h;
        down[c] -= h;
        let fd = (jet(&m, &up, p, None).gap - jet(&m, &down, p, None).gap) / (2.0 * h);
        assert!((at.gradient[c] - fd).abs() <= 1e-6 * largest, "dg/dq{c}: {} against {fd}", at.gradient[c]);
    }
}
