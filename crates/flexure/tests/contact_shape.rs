//! `mechanism/contact/shape.rs` and `Geom::gap`: each shape's signed
//! distance and normal against closed forms worked by hand (to 1e-15, a
//! few roundings), and the normal against central differences of the
//! distance (to 1e-6: the difference's truncation at a 1e-6 step) with the
//! geom turned and moved by its frame and its body, in both dimensions.

use flexure::Pose;
use flexure::mechanism::contact::{Geom, GeomShape};
use flexure::space::{Planar, Spatial};
use nalgebra::{Isometry3, Point2, Point3, Translation3, UnitQuaternion, Vector2, Vector3};

fn planar(shape: GeomShape<Planar>, p: [f64; 2]) -> (f64, [f64; 2]) {
    let (d, n) = shape.distance(&Vector2::from(p));
    (d, [n.x, n.y])
}

fn spatial(shape: GeomShape<Spatial>, p: [f64; 3]) -> (f64, [f64; 3]) {
    let (d, n) = shape.distance(&Vector3::from(p));
    (d, [n.x, n.y, n.z])
}

fn close<const N: usize>((d, n): (f64, [f64; N]), (want_d, want_n): (f64, [f64; N])) {
    assert!((d - want_d).abs() < 1e-15, "distance {d}, closed form {want_d}");
    for (a, b) in n.iter().zip(want_n) {
        assert!((a - b).abs() < 1e-15, "normal {n:?}, closed form {want_n:?}");
    }
}

#[test]
fn planar_shapes_meet_their_closed_forms() {
    let plane = GeomShape::Plane { normal: Vector2::new(0.6, 0.8) };
    close(planar(plane, [1.0, 2.0]), (0.6 + 1.6, [0.6, 0.8]));
    close(planar(plane, [-1.0, -2.0]), (-2.2, [0.6, 0.8]));
    let circle = GeomShape::Ball { radius: 1.0 };
    close(planar(circle, [3.0, 4.0]), (4.0, [0.6, 0.8]));
    close(planar(circle, [0.3, 0.4]), (-0.5, [0.6, 0.8]));
    // A capsule: beyond its side, beyond its end, off its end's corner, inside.
    let capsule = GeomShape::Capsule { half_length: 1.0, radius: 0.5 };
    close(planar(capsule, [0.2, 2.0]), (1.5, [0.0, 1.0]));
    close(planar(capsule, [3.0, 0.0]), (1.5, [1.0, 0.0]));
    close(planar(capsule, [-4.0, -4.0]), (4.5, [-0.6, -0.8]));
    close(planar(capsule, [0.5, -0.1]), (-0.4, [0.0, -1.0]));
    // A 4 × 2 rectangle: off a side, off a corner (3-4-5), inside by the nearest side.
    let rectangle = GeomShape::Box { half_extents: Vector2::new(2.0, 1.0) };
    close(planar(rectangle, [5.0, 0.0]), (3.0, [1.0, 0.0]));
    close(planar(rectangle, [-5.0, -5.0]), (5.0, [-0.6, -0.8]));
    close(planar(rectangle, [1.5, 0.2]), (-0.5, [1.0, 0.0]));
    close(planar(rectangle, [0.1, -0.9]), (-0.1, [0.0, -1.0]));
    // In the plane a cylinder about z is its circle.
    close(planar(GeomShape::Cylinder { half_length: 5.0, radius: 1.0 }, [3.0, 4.0]), (4.0, [0.6, 0.8]));
}

#[test]
fn spatial_shapes_meet_their_closed_forms() {
    close(spatial(GeomShape::Plane { normal: Vector3::z() }, [5.0, 6.0, -0.25]), (-0.25, [0.0, 0.0, 1.0]));
    close(spatial(GeomShape::Ball { radius: 2.0 }, [1.0, 2.0, 2.0]), (1.0, [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0]));
    let capsule = GeomShape::Capsule { half_length: 1.0, radius: 0.5 };
    let (d, n) = spatial(capsule, [2.0, 0.0, 1.0]);
    let r = std::f64::consts::FRAC_1_SQRT_2;
    close((d, n), (2f64.sqrt() - 0.5, [r, 0.0, r]));
    let cuboid = GeomShape::Box { half_extents: Vector3::new(1.0, 2.0, 3.0) };
    let s = 1.0 / 3f64.sqrt();
    close(spatial(cuboid, [2.0, 3.0, 4.0]), (3f64.sqrt(), [s, s, s]));
    close(spatial(cuboid, [0.1, -1.5, 0.2]), (-0.5, [0.0, -1.0, 0.0]));
    let can = GeomShape::Cylinder { half_length: 2.0, radius: 1.0 };
    close(spatial(can, [3.0, 4.0, 0.0]), (4.0, [0.6, 0.8, 0.0]));
    close(spatial(can, [0.0, 0.0, -2.5]), (0.5, [0.0, 0.0, -1.0]));
    close(spatial(can, [0.3, 0.4, 1.8]), (-0.2, [0.0, 0.0, 1.0]));
    close(spatial(can, [0.3, 0.4, 0.0]), (-0.5, [0.6, 0.8, 0.0]));
}

/// A small deterministic generator of points in [-3, 3).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 6.0 - 3.0
    }
}

/// Central differences of the gap of `g` at points `p` (world frame) against its normal.
fn normal_is_gradient<const N: usize>(
    gap: impl Fn([f64; N]) -> (f64, [f64; N]),
    points: impl Iterator<Item = [f64; N]>,
    what: &str,
) -> usize {
    let h = 1e-6;
    let mut checked = 0;
    for p in points {
        let (_, n) = gap(p);
        let mut fd = [0.0; N];
        for i in 0..N {
            let (mut a, mut b) = (p, p);
            a[i] += h;
            b[i] -= h;
            fd[i] = (gap(a).0 - gap(b).0) / (2.0 * h);
        }
        // Points within a step of a crease (a box's medial planes, a capsule's
        // end circles) have no gradient there: the one-sided limits differ.
        if fd.iter().map(|x| x * x).sum::<f64>().sqrt() < 1.0 - 1e-6 {
            continue;
        }
        let unit = n.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!((unit - 1.0).abs() < 1e-14, "{what}: |n| = {unit}");
        for i in 0..N {
            assert!((n[i] - fd[i]).abs() < 1e-6, "{what} at {p:?}: normal {n:?}, differences {fd:?}");
        }
        checked += 1;
    }
    checked
}

#[test]
fn the_planar_normal_is_the_gradient_of_the_gap_through_frames() {
    let body = Pose { phi: 0.4, x: 0.3, y: -0.7 };
    let frame = Pose { phi: -1.1, x: 0.5, y: 0.2 };
    let shapes = [
        GeomShape::Plane { normal: Vector2::new(0.6, -0.8) },
        GeomShape::Ball { radius: 0.7 },
        GeomShape::Capsule { half_length: 0.8, radius: 0.3 },
        GeomShape::Box { half_extents: Vector2::new(0.9, 0.4) },
    ];
    for shape in shapes {
        let g = Geom::<Planar>::new("g", 1, frame, shape);
        let gap = |p: [f64; 2]| {
            let (d, n) = g.gap(&body, &Point2::from(p), 0.05);
            (d, [n.x, n.y])
        };
        let mut rng = Lcg(7);
        let points = (0..200).map(|_| [rng.next(), rng.next()]);
        let checked = normal_is_gradient(gap, points, shape.name());
        assert!(checked > 150, "{}: only {checked} points away from creases", shape.name());
    }
}

#[test]
fn the_spatial_normal_is_the_gradient_of_the_gap_through_frames() {
    let turn = |r: f64, p: f64, y: f64, t: [f64; 3]| {
        Isometry3::from_parts(Translation3::new(t[0], t[1], t[2]), UnitQuaternion::from_euler_angles(r, p, y))
    };
    let (body, frame) = (turn(0.3, -0.2, 0.9, [0.1, 0.2, -0.3]), turn(-0.7, 0.5, 0.2, [0.4, -0.1, 0.3]));
    let shapes = [
        GeomShape::Plane { normal: Vector3::new(0.48, 0.6, 0.64) },
        GeomShape::Ball { radius: 0.7 },
        GeomShape::Capsule { half_length: 0.8, radius: 0.3 },
        GeomShape::Box { half_extents: Vector3::new(0.9, 0.4, 0.6) },
        GeomShape::Cylinder { half_length: 0.5, radius: 0.6 },
    ];
    for shape in shapes {
        let g = Geom::<Spatial>::new("g", 1, frame, shape);
        let gap = |p: [f64; 3]| {
            let (d, n) = g.gap(&body, &Point3::from(p), 0.0);
            (d, [n.x, n.y, n.z])
        };
        let mut rng = Lcg(11);
        let points = (0..200).map(|_| [rng.next(), rng.next(), rng.next()]);
        let checked = normal_is_gradient(gap, points, shape.name());
        assert!(checked > 150, "{}: only {checked} points away from creases", shape.name());
    }
}

/// The half thickness comes off the distance; the normal is the geom's,
/// turned into the world by the body and the geom's frame.
#[test]
fn the_gap_takes_the_half_thickness_and_turns_the_normal() {
    let body = Pose { phi: std::f64::consts::FRAC_PI_2, x: 1.0, y: 0.0 };
    let floor = Geom::<Planar>::new("floor", 1, Pose::default(), GeomShape::Plane { normal: Vector2::x() });
    // The body turned a quarter: its x is the world's y, its origin at (1, 0).
    let (gap, n) = floor.gap(&body, &Point2::new(4.0, 2.5), 0.5);
    assert!((gap - 2.0).abs() < 1e-15 && (n - Vector2::y()).norm() < 1e-15, "{gap} {n}");
}

/// Central differences of the normal of `shape` (its own frame) at points
/// `p` against its curvature $\nabla^2 d$, to 1e-6 of its size (the
/// difference's truncation at a 1e-7 step); points within a step of a crease
/// (the two one-sided differences disagree) are left out. Returns how many
/// were checked.
fn curvature_is_the_normals_derivative<const N: usize>(
    field: impl Fn([f64; N]) -> ([f64; N], [[f64; 3]; 3]),
    points: impl Iterator<Item = [f64; N]>,
    what: &str,
) -> usize {
    let h = 1e-7;
    let mut checked = 0;
    'points: for p in points {
        let (n, c) = field(p);
        let mut columns = Vec::new();
        for j in 0..N {
            let (mut a, mut b) = (p, p);
            a[j] += h;
            b[j] -= h;
            let (na, nb) = (field(a).0, field(b).0);
            let (ahead, behind): (Vec<f64>, Vec<f64>) =
                (0..N).map(|i| ((na[i] - n[i]) / h, (n[i] - nb[i]) / h)).unzip();
            let scale = 1.0 + ahead.iter().chain(&behind).fold(0.0f64, |m, x| m.max(x.abs()));
            if ahead.iter().zip(&behind).any(|(x, y)| (x - y).abs() > 1e-3 * scale) {
                continue 'points;
            }
            columns.push((0..N).map(|i| (na[i] - nb[i]) / (2.0 * h)).collect::<Vec<_>>());
        }
        for (j, column) in columns.iter().enumerate() {
            for i in 0..N {
                let scale = 1.0 + c[i][j].abs();
                assert!(
                    (c[i][j] - column[i]).abs() < 1e-6 * scale,
                    "{what} at {p:?}: ∇²d[{i}][{j}] = {}, differences {}",
                    c[i][j],
                    column[i]
                );
            }
        }
        checked += 1;
    }
    checked
}

/// Each shape's curvature (`GeomShape::curvature`, the Hessian of its
/// signed distance that the contact's stiffness and its stability read) is
/// the derivative of its normal, by central differences: at random points,
/// and on each curved surface itself, where a touching centreline (a
/// flexure with no thickness) reads it. A cylinder's side read zero there,
/// and a blade given by `ei` pressed onto a cylinder was refused as lying
/// along it.
#[test]
fn each_shapes_curvature_is_the_derivative_of_its_normal() {
    let spatial_shapes: [GeomShape<Spatial>; 4] = [
        GeomShape::Ball { radius: 0.7 },
        GeomShape::Capsule { half_length: 0.8, radius: 0.3 },
        GeomShape::Box { half_extents: Vector3::new(0.9, 0.4, 0.6) },
        GeomShape::Cylinder { half_length: 0.5, radius: 0.6 },
    ];
    let (a, b) = (0.7f64, 0.4f64);
    let surfaces = [
        vec![[0.7 * b.cos() * a.cos(), 0.7 * b.cos() * a.sin(), 0.7 * b.sin()]],
        vec![
            [0.2, 0.3 * a.cos(), 0.3 * a.sin()],
            [0.8 + 0.3 * b.cos(), 0.3 * b.sin() * a.cos(), 0.3 * b.sin() * a.sin()],
        ],
        vec![[0.9, 0.1, 0.2]],
        vec![[0.6 * a.cos(), 0.6 * a.sin(), 0.1]],
    ];
    for (shape, surface) in spatial_shapes.into_iter().zip(surfaces) {
        let field = |p: [f64; 3]| {
            let (_, n) = shape.distance(&Vector3::from(p));
            ([n.x, n.y, n.z], shape.curvature(&Vector3::from(p)))
        };
        let mut rng = Lcg(5);
        let points = (0..200).map(|_| [rng.next(), rng.next(), rng.next()]);
        let checked = curvature_is_the_normals_derivative(field, points, shape.name());
        assert!(checked > 150, "{}: only {checked} points away from creases", shape.name());
        let on_surface = curvature_is_the_normals_derivative(field, surface.iter().copied(), shape.name());
        assert_eq!(on_surface, surface.len(), "{}: a surface point on a crease", shape.name());
        for p in &surface {
            assert!(
                shape.distance(&Vector3::from(*p)).0.abs() < 1e-15,
                "{} at {p:?}: not on the surface",
                shape.name()
            );
        }
    }
    let planar_shapes: [GeomShape<Planar>; 3] = [
        GeomShape::Ball { radius: 0.7 },
        GeomShape::Capsule { half_length: 0.8, radius: 0.3 },
        GeomShape::Box { half_extents: Vector2::new(0.9, 0.4) },
    ];
    for shape in planar_shapes {
        let field = |p: [f64; 2]| {
            let (_, n) = shape.distance(&Vector2::from(p));
            ([n.x, n.y], shape.curvature(&Vector2::from(p)))
        };
        let mut rng = Lcg(3);
        let points = (0..200).map(|_| [rng.next(), rng.next()]);
        let checked = curvature_is_the_normals_derivative(field, points, shape.name());
        assert!(checked > 150, "{}: only {checked} points away from creases", shape.name());
    }
}
