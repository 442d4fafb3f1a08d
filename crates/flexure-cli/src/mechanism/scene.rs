//! What `draw` draws of a mechanism, in the world (m): the one block of the
//! drawing that knows the dimension, [`Drawn`]. A planar mechanism is drawn
//! as the spatial one lying in the plane z = 0, its rotations about z; a
//! spatial one as it is. The drawing
//! ([`super::drawing`]) reads only a [`Scene`] and its [`Snapshot`]s, so the
//! planar picture is the spatial one seen from the top.

use super::drawing::{FLEXURE_SAMPLES, Marks, MotionFigures, Track, View, figure, motion_figures, short};
use flexure::dynamics::Simulation;
use flexure::mechanism::contact::{Contact, ContactMode, GeomShape};
use flexure::mechanism::kinematics::frames;
use flexure::mechanism::spatial::{SpatialLoads, SpatialMechanism};
use flexure::mechanism::statics::Solution;
use flexure::mechanism::{Holds, Loads, Mechanism};
use flexure::model::Analyses;
use flexure::space::{Planar, Spatial};
use flexure_chart::Figure;
use nalgebra::{Isometry3, Point2, Point3, Rotation3, Vector3};

type V = Vector3<f64>;

/// What every shape of one mechanism shares: its names and its words.
pub struct Scene {
    /// Every point attached to the ground (world).
    pub ground: Vec<V>,
    /// Each tendon's name.
    pub tendons: Vec<String>,
    /// Each load of [`Snapshot::loads`]: its name and the body it acts on
    /// (`None`: the weight of the body named).
    pub loads: Vec<(String, Option<String>)>,
    /// The components a load or a position is written with: 2 in the plane (x, y), 3 in space.
    pub components: usize,
    /// The components of a rotation vector a body turns in: z in the plane.
    pub rotations: &'static [usize],
    /// The stress the colour bar shows ("bending", "von Mises").
    pub stress: &'static str,
    /// How a flexure without a stress (no section geometry) is given.
    pub plain: &'static str,
    /// Each geom's name, its shape's name and whether it is on the ground
    /// (drawn once) rather than on a moving body (drawn with each shape).
    pub geoms: Vec<(String, &'static str, bool)>,
}

/// A geom where a shape puts it: its frame in the world and its solid, a
/// planar one lying at z = 0 (its normal and box in the plane, its circle
/// and cylinder about z).
pub struct Solid {
    pub frame: Isometry3<f64>,
    pub shape: GeomShape<Spatial>,
}

/// A contact of a shape, as its answer gives it (world): where the toucher
/// touches, the geom's outward normal there, and the forces the geom exerts.
pub struct ContactMark {
    /// What touches what: `cylinder on distal`.
    pub name: String,
    pub point: V,
    pub normal: V,
    /// Along the normal (N), not negative.
    pub normal_force: f64,
    /// Along the surface (N).
    pub friction_force: V,
}

/// The mark of a rigid joint or a closure.
#[derive(Clone, Copy, PartialEq, Debug)]
pub enum Symbol {
    /// One rotation: a hinge about [`JointMark::axis`].
    Hinge,
    /// Rotations about more than one axis: a ball joint.
    Ball,
    /// A translation along [`JointMark::axis`]: a slider.
    Slider,
}

/// A rigid joint or closure, where it is.
pub struct JointMark {
    pub symbol: Symbol,
    /// Its root (a joint's) or its frame on body `a` (a closure's).
    pub at: V,
    /// The axis of a hinge or a slider (unit, world).
    pub axis: V,
    /// The child's origin: a slider's travel ends there.
    pub child: V,
    /// A closure's, not a joint's.
    pub closure: bool,
}

/// A flexure's centreline through [`FLEXURE_SAMPLES`] sections.
pub struct Centreline {
    pub points: Vec<V>,
    /// The stress (Pa) at each section, if its section has a geometry.
    pub stress: Option<Vec<f64>>,
    /// The largest stress (Pa) along it (finer than the sections), if any.
    pub peak: Option<f64>,
    pub length: f64,
}

/// Shapes, each with its name.
pub type Shapes = Vec<(String, Snapshot)>;

/// A load: a force (N) and a moment (N·m) at a point (world).
pub struct Load {
    pub at: V,
    pub force: V,
    pub moment: V,
}

/// One shape of the mechanism, in the world.
pub struct Snapshot {
    /// Every point attached to each body but the ground.
    pub links: Vec<Vec<V>>,
    /// Every body's origin.
    pub origins: Vec<V>,
    /// Every joint's root.
    pub roots: Vec<V>,
    /// Each joint leaving the ground: its root and the direction it leaves in.
    pub leaving: Vec<(V, V)>,
    pub flexures: Vec<Centreline>,
    pub joints: Vec<JointMark>,
    /// Each tendon's via points.
    pub tendons: Vec<Vec<V>>,
    pub tensions: Vec<f64>,
    /// The loads of [`Scene::loads`], in its order.
    pub loads: Vec<Load>,
    /// The geoms of [`Scene::geoms`], in its order.
    pub geoms: Vec<Solid>,
    /// The contacts that touch (none unless given: [`Snapshot::with_contacts`]).
    pub contacts: Vec<ContactMark>,
}

/// A vector of 2 or 3 components (a contact's) in the world.
fn world(v: &[f64]) -> V {
    V::new(v.first().copied().unwrap_or(0.0), v.get(1).copied().unwrap_or(0.0), v.get(2).copied().unwrap_or(0.0))
}

impl Snapshot {
    /// The shape with the contacts of its answer that touch (an open one
    /// has no force to draw).
    pub fn with_contacts(mut self, contacts: &[Contact]) -> Self {
        self.contacts = contacts
            .iter()
            .filter(|c| c.state != ContactMode::Open)
            .map(|c| ContactMark {
                name: format!("{} on {}", c.geom, c.flexure.as_ref().or(c.body.as_ref()).map_or("?", |s| s.as_str())),
                point: world(&c.point),
                normal: world(&c.normal),
                normal_force: c.normal_force,
                friction_force: world(&c.friction_force),
            })
            .collect();
        self
    }
}

fn flat(p: Point2<f64>) -> V {
    V::new(p.x, p.y, 0.0)
}

/// What the drawing asks of a dimension, the rest of the picture being
/// written once: a point in the world, a shape's world points, a run's
/// body tracks, and the scene's words. The plane and space side by side.
pub trait Drawn: Analyses {
    /// The view when `--view` is not given: top in the plane (x right, y up), iso in space.
    const VIEW: View;
    /// [`Scene::components`].
    const COMPONENTS: usize;
    /// [`Scene::rotations`].
    const ROTATIONS: &'static [usize];
    /// [`Scene::stress`].
    const STRESS: &'static str;
    /// [`Scene::plain`].
    const PLAIN: &'static str;
    /// A point of the dimension in the world (m): at z = 0 in the plane.
    fn world(p: &Self::Point) -> V;
    /// The shape at coordinates `q` under `loads`, named `label` in its
    /// errors: a shape that does not fit `m`, or a flexure whose
    /// coordinates the library refuses.
    fn pose(m: &Mechanism<Self>, label: &str, q: &[f64], loads: &Loads<Self>) -> Result<Snapshot, String>;
    /// Each moving body's track of a run: its rotation vector and its origin.
    fn tracks(run: &Simulation<Self>) -> Vec<Track>;
}

/// A mechanism's scene.
pub fn scene<D: Drawn>(m: &Mechanism<D>) -> Scene {
    let forces = m.forces.iter().map(|p| (p.name.clone(), Some(m.bodies[p.body].name.clone())));
    let weights = m.bodies.iter().filter(|b| b.mass > 0.0).map(|b| (format!("weight of {}", b.name), None));
    Scene {
        ground: m.attachments(0).iter().map(D::world).collect(),
        tendons: m.tendons.iter().map(|t| t.name.clone()).collect(),
        loads: forces.chain(weights).collect(),
        components: D::COMPONENTS,
        rotations: D::ROTATIONS,
        stress: D::STRESS,
        plain: D::PLAIN,
        geoms: m.geoms.iter().map(|g| (g.name.clone(), g.shape.name(), g.body == 0)).collect(),
    }
}

/// A planar mechanism is drawn lying at z = 0: hinges about z, moments along z.
impl Drawn for Planar {
    const VIEW: View = View::Top;
    const COMPONENTS: usize = 2;
    const ROTATIONS: &'static [usize] = &[2];
    const STRESS: &'static str = "bending";
    const PLAIN: &'static str = "ei alone";

    fn world(p: &Point2<f64>) -> V {
        flat(*p)
    }

    fn pose(m: &Mechanism, _: &str, q: &[f64], loads: &Loads) -> Result<Snapshot, String> {
        Ok(planar(m, q, loads))
    }

    fn tracks(run: &Simulation) -> Vec<Track> {
        let track = |b: &flexure::dynamics::simulation::BodyMotion| Track {
            name: b.name.clone(),
            rotation: b.phi.iter().map(|&phi| V::new(0.0, 0.0, phi)).collect(),
            position: b.x.iter().zip(&b.y).map(|(x, y)| V::new(*x, *y, 0.0)).collect(),
        };
        run.bodies.iter().map(track).collect()
    }
}

/// A spatial mechanism is drawn as it is; a body's rotation is tracked as
/// its rotation vector $\theta = \varphi\thinspace\hat n$ (angle times unit axis, rad).
impl Drawn for Spatial {
    const VIEW: View = View::Iso;
    const COMPONENTS: usize = 3;
    const ROTATIONS: &'static [usize] = &[0, 1, 2];
    const STRESS: &'static str = "von Mises";
    const PLAIN: &'static str = "stiffnesses alone";

    fn world(p: &Point3<f64>) -> V {
        p.coords
    }

    fn pose(m: &SpatialMechanism, label: &str, q: &[f64], loads: &SpatialLoads) -> Result<Snapshot, String> {
        spatial(m, label, q, loads)
    }

    fn tracks(run: &Simulation<Spatial>) -> Vec<Track> {
        let rotation = |r: &[[f64; 3]; 3]| {
            Rotation3::from_matrix_unchecked(nalgebra::Matrix3::from_fn(|i, j| r[i][j])).scaled_axis()
        };
        let track = |b: &flexure::dynamics::simulation::BodyPoses| Track {
            name: b.name.clone(),
            rotation: b.rotation.iter().map(rotation).collect(),
            position: b.position.iter().map(|p| V::from(*p)).collect(),
        };
        run.bodies.iter().map(track).collect()
    }
}

/// A shape's rigid part: its links and tendons through `at` (a body's
/// point in the world), its bodies' `origins` and joints' `roots`; its
/// flexures, joints and loads are the dimension's to fill.
fn rigid<D: Drawn>(
    m: &Mechanism<D>,
    at: &impl Fn(usize, &D::Point) -> V,
    (origins, roots): (Vec<V>, Vec<V>),
    tensions: &[f64],
) -> Snapshot {
    Snapshot {
        links: (1..m.bodies.len()).map(|b| m.attachments(b).iter().map(|r| at(b, r)).collect()).collect(),
        origins,
        roots,
        leaving: Vec::new(),
        flexures: Vec::new(),
        joints: Vec::new(),
        tendons: m.tendons.iter().map(|t| t.path.iter().map(|(b, r)| at(*b, r)).collect()).collect(),
        tensions: tensions.to_vec(),
        loads: Vec::new(),
        geoms: Vec::new(),
        contacts: Vec::new(),
    }
}

/// A planar geom's solid lying at z = 0.
fn flat_shape(shape: &GeomShape<Planar>) -> GeomShape<Spatial> {
    match *shape {
        GeomShape::Plane { normal } => GeomShape::Plane { normal: V::new(normal.x, normal.y, 0.0) },
        GeomShape::Ball { radius } => GeomShape::Ball { radius },
        GeomShape::Capsule { half_length, radius } => GeomShape::Capsule { half_length, radius },
        GeomShape::Box { half_extents: e } => GeomShape::Box { half_extents: V::new(e.x, e.y, 0.0) },
        GeomShape::Cylinder { half_length, radius } => GeomShape::Cylinder { half_length, radius },
    }
}

/// A planar shape (coordinates `q` under `loads`) at z = 0.
fn planar(m: &Mechanism, q: &[f64], loads: &Loads) -> Snapshot {
    let f = frames(m, q);
    let at = |b: usize, r: &Point2<f64>| flat(f.bodies[b].act(r));
    let turn = |phi: f64, (x, y): (f64, f64)| V::new(phi.cos() * x - phi.sin() * y, phi.sin() * x + phi.cos() * y, 0.0);
    let origins = f.bodies.iter().map(|b| V::new(b.x, b.y, 0.0)).collect();
    let mut pose = rigid(m, &at, (origins, f.roots.iter().map(|r| V::new(r.x, r.y, 0.0)).collect()), &loads.tension);
    for (ji, j) in m.joints.iter().enumerate() {
        let (root, kind) = (f.roots[ji], j.kind.joint());
        let origin = pose.roots[ji];
        let child = pose.origins[j.child];
        if let Some(fl) = j.kind.flexure() {
            let q = &q[j.offset..j.offset + fl.order()];
            let points = flexure::kinematics::backbone(fl, q, FLEXURE_SAMPLES);
            let ds = fl.length() / (FLEXURE_SAMPLES - 1) as f64;
            let stress = fl.section().modulus().map(|_| {
                (0..FLEXURE_SAMPLES).map(|i| flexure::stress::stress(fl, q, i as f64 * ds).unwrap_or(0.0)).collect()
            });
            pose.flexures.push(Centreline {
                points: points.iter().map(|p| flat(root.act(&Point2::new(p.x, p.y)))).collect(),
                stress,
                peak: flexure::stress::peak_stress(fl, q).map(|p| p.value),
                length: fl.length(),
            });
        }
        if j.parent == 0 {
            let away = if j.kind.flexure().is_some() { turn(root.phi, (1.0, 0.0)) } else { child - origin };
            pose.leaving.push((origin, away));
        }
        if j.kind.flexure().is_none() && kind.dof() > 0 {
            let (symbol, axis) = if kind.is_translation() {
                let s = &f.joints[ji].jacobian;
                (Symbol::Slider, turn(root.phi, (s[(1, 0)], s[(2, 0)])).normalize())
            } else {
                (Symbol::Hinge, V::z())
            };
            pose.joints.push(JointMark { symbol, at: origin, axis, child, closure: false });
        }
    }
    for c in m.closures.iter().filter(|c| c.holds == Holds::Pin) {
        let p = at(c.a, &c.a_origin.origin());
        pose.joints.push(JointMark { symbol: Symbol::Hinge, at: p, axis: V::z(), child: p, closure: true });
    }
    let g = loads.gravity;
    let forces = m.forces.iter().zip(&loads.force).map(|(p, l)| Load {
        at: at(p.body, &p.at),
        force: V::new(l.fx, l.fy, 0.0),
        moment: V::new(0.0, 0.0, l.moment),
    });
    let weights = m.bodies.iter().enumerate().filter(|(_, b)| b.mass > 0.0).map(|(i, b)| Load {
        at: at(i, &b.com),
        force: V::new(b.mass * g[0], b.mass * g[1], 0.0),
        moment: V::zeros(),
    });
    pose.loads = forces.chain(weights).collect();
    pose.geoms = m
        .geoms
        .iter()
        .map(|g| {
            let p = f.bodies[g.body].compose(&g.frame);
            Solid { frame: Isometry3::new(V::new(p.x, p.y, 0.0), V::z() * p.phi), shape: flat_shape(&g.shape) }
        })
        .collect();
    pose
}

/// Checks that a shape has one finite coordinate per coordinate of `m`.
fn check_shape(m: &SpatialMechanism, label: &str, q: &[f64], loads: &SpatialLoads) -> Result<(), String> {
    if q.len() != m.dof() {
        return Err(format!("shape {label:?}: q has {} coordinates, the mechanism {}", q.len(), m.dof()));
    }
    if let Some((i, v)) = q.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(format!("shape {label:?}: q[{i}] = {v}, not finite"));
    }
    if loads.validate(m).is_err() {
        return Err(format!(
            "shape {label:?}: its loads do not fit the mechanism (one tension per tendon, one wrench per force)"
        ));
    }
    Ok(())
}

/// A spatial shape, named `label` in its errors: a shape that does not fit
/// `m`, or a flexure whose coordinates the library refuses.
fn spatial(m: &SpatialMechanism, label: &str, q: &[f64], loads: &SpatialLoads) -> Result<Snapshot, String> {
    check_shape(m, label, q, loads)?;
    let f = frames(m, q);
    let at = |b: usize, r: &Point3<f64>| (f.bodies[b] * r).coords;
    let origins = f.bodies.iter().map(|b| b.translation.vector).collect();
    let mut pose = rigid(m, &at, (origins, f.roots.iter().map(|r| r.translation.vector).collect()), &loads.tension);
    let named = |name: &str, e: flexure::Error| format!("shape {label:?}, flexure {name}: {}", crate::describe(e));
    for (ji, j) in m.joints.iter().enumerate() {
        let (root, kind) = (f.roots[ji], j.kind.joint());
        let child = pose.origins[j.child];
        if let Some(fl) = j.kind.flexure() {
            let q = &q[j.offset..j.offset + fl.coordinates()];
            let sections = flexure::spatial::shape(fl, q, FLEXURE_SAMPLES).map_err(|e| named(&j.name, e))?;
            let shaped = fl.section().stress(0.0, [0.0; 3]).is_ok();
            let peak = match shaped {
                true => Some(flexure::spatial::peak_stress(fl, q).map_err(|e| named(&j.name, e))?.stress.von_mises),
                false => None,
            };
            pose.flexures.push(Centreline {
                points: sections.iter().map(|p| (root * Point3::from(p.position)).coords).collect(),
                stress: sections.iter().map(|p| p.stress).collect(),
                peak,
                length: fl.length(),
            });
        }
        if j.parent == 0 {
            let away = if j.kind.flexure().is_some() { root.rotation * V::x() } else { child - pose.roots[ji] };
            pose.leaving.push((pose.roots[ji], away));
        }
        if j.kind.flexure().is_none() && kind.dof() > 0 {
            let (symbol, axis) = if kind.is_translation() {
                (Symbol::Slider, f.velocity[j.offset])
            } else if kind.dof() == 1 {
                (Symbol::Hinge, f.omega[j.offset])
            } else {
                (Symbol::Ball, V::z())
            };
            pose.joints.push(JointMark { symbol, at: pose.roots[ji], axis, child, closure: false });
        }
    }
    for c in &m.closures {
        let frame = f.bodies[c.a] * c.a_origin;
        let p = frame.translation.vector;
        let symbol = match c.holds {
            Holds::Pin => Symbol::Hinge,
            Holds::Ball => Symbol::Ball,
            Holds::Weld => continue,
        };
        pose.joints.push(JointMark { symbol, at: p, axis: frame.rotation * V::z(), child: p, closure: true });
    }
    let g = loads.gravity;
    let forces = m.forces.iter().zip(&loads.force).map(|(p, w)| Load {
        at: at(p.body, &p.at),
        force: w.fixed_rows::<3>(3).into_owned(),
        moment: w.fixed_rows::<3>(0).into_owned(),
    });
    let weights = m.bodies.iter().enumerate().filter(|(_, b)| b.mass > 0.0).map(|(i, b)| Load {
        at: at(i, &b.com),
        force: g * b.mass,
        moment: V::zeros(),
    });
    pose.loads = forces.chain(weights).collect();
    pose.geoms = m.geoms.iter().map(|g| Solid { frame: f.bodies[g.body] * g.frame, shape: g.shape }).collect();
    Ok(pose)
}

/// The figure of a mechanism's unloaded and loaded shapes seen from
/// `view` ([`figure`]), and the force arrows' scale (m per N) if any force
/// is drawn. Errors name the shape whose coordinates or loads do not fit
/// `m`, or the flexure whose coordinates the library refuses.
///
/// # Example
/// ```
/// use flexure_cli::drawing::{Marks, View};
/// use flexure_cli::scene::shapes_figure;
/// use flexure::mechanism::spatial::{RevoluteUnaligned, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism, SpatialPointLoad};
/// use flexure::mechanism::statics::{assemble_unloaded, solve};
/// use nalgebra::{Isometry3, Point3, Vector3, Vector6};
/// let hinge = SpatialJointSpec {
///     name: "hinge".into(), kind: SpatialJointKind::Revolute(RevoluteUnaligned { axis: Vector3::z_axis(), stiffness: 2.0, rest: 0.0 }),
///     parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default(),
/// };
/// let push = SpatialPointLoad { name: "push".into(), body: 1, at: Point3::new(0.1, 0.0, 0.0), wrench: Vector6::new(0.0, 0.0, 0.0, 0.0, 1.0, 0.0) };
/// let bodies = vec![SpatialBody::massless("ground"), SpatialBody::massless("arm")];
/// let m = SpatialMechanism::new(bodies, vec![hinge], vec![], vec![push], vec![], Vector3::zeros()).unwrap();
/// let s = solve(&m, &Default::default()).unwrap();
/// let unloaded = assemble_unloaded(&m, &Default::default()).unwrap();
/// let (fig, per_newton) = shapes_figure(&m, "arm", &unloaded, &[("loaded".into(), s)], &Marks::default(), View::Top, true).unwrap();
/// // The largest force drawn a quarter of the arm's 0.1 m, at a round scale: 0.02 m per N.
/// assert_eq!(per_newton, Some(0.02));
/// assert!(fig.legend.iter().any(|e| e.label == "force push on arm: (0, 1, 0) N"));
/// assert!(flexure_chart::render(&fig).unwrap().starts_with("<svg"));
/// ```
pub fn shapes_figure<D: Drawn>(
    m: &Mechanism<D>,
    title: &str,
    unloaded: &Solution<D>,
    loaded: &[(String, Solution<D>)],
    marks: &Marks,
    view: View,
    stress: bool,
) -> Result<(Figure, Option<f64>), String> {
    let rest = D::pose(m, "unloaded", &unloaded.q, &unloaded.loads)?;
    let shapes = loaded
        .iter()
        .map(|(l, s)| Ok((l.clone(), D::pose(m, l, &s.q, &s.loads)?.with_contacts(&s.contacts))))
        .collect::<Result<Shapes, String>>()?;
    Ok(figure(&scene(m), title, &rest, &shapes, marks, view, stress))
}

/// The snapshots of a run at its samples `picked` (their loads, schedules
/// applied, at their times), and each moving body's track ([`Drawn::tracks`]).
pub fn motion<D: Drawn>(
    m: &Mechanism<D>,
    run: &Simulation<D>,
    picked: &[usize],
) -> Result<(Shapes, Vec<Track>), String> {
    let snapshots = picked
        .iter()
        .map(|&k| {
            let loads = flexure::dynamics::schedule::loads_at(m, run.time[k]);
            let label = format!("t = {} s", short(run.time[k]));
            let contacts = run.contacts.get(k).map_or(&[][..], Vec::as_slice);
            Ok((label.clone(), D::pose(m, &label, run.q(k), &loads)?.with_contacts(contacts)))
        })
        .collect::<Result<Shapes, String>>()?;
    Ok((snapshots, D::tracks(run)))
}

/// `draw --simulate` of a run ([`motion_figures`]).
///
/// Errors name an empty run or a shape that does not fit `m`.
pub fn run_figures<D: Drawn>(
    m: &Mechanism<D>,
    title: &str,
    unloaded: &Solution<D>,
    run: &Simulation<D>,
    view: View,
    stress: bool,
) -> Result<MotionFigures, String> {
    let samples = run.time.len();
    if samples == 0 || run.coordinates.len() != samples * m.dof() {
        return Err(format!("the run has {samples} samples of {} coordinates: nothing to draw", run.dim));
    }
    let picked = super::drawing::snapshot_samples(samples);
    let (snapshots, tracks) = motion(m, run, &picked)?;
    let rest = D::pose(m, "unloaded", &unloaded.q, &unloaded.loads)?;
    motion_figures(&scene(m), title, (&rest, &snapshots), (&run.time, &tracks), &picked, view, stress)
}
