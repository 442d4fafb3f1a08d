//! Contact: the shapes ("geoms") on the ground and on bodies that a
//! mechanism's flexures and other bodies' geoms may touch.
//!
//! A [`Geom`] is a [`GeomShape`] placed in a body's frame (`frame`), with a
//! Coulomb coefficient. Its gap to a point is the shape's signed distance
//! ([`shape`](self::GeomShape::distance)) less the toucher's half thickness:
//! a flexure touches with its surface, its centreline offset by half its
//! thickness ([`Touch::surface`]). The pairs that may touch
//! ([`pairs`]) are every geom with every flexure and every geom with every
//! other body's geom (at each of their [`corners`]), less those a geom's `exclude` names: a flexure's
//! own parent and child bodies' geoms too (a finger's pad around its
//! flexure's tip must exclude the flexure, or the file refuses it as
//! starting inside the pad).
//!
//! The equilibrium solve and sweep handle contact, with friction where a
//! flexure's bare end touches ([`crate::mechanism::statics::solve`], [`crate::mechanism::sweep::sweep`]): each pair's gap ([`gap()`],
//! [`minima`]) and its derivatives ([`gap_jet`]) enter its equations as
//! unilateral constraints, and [`Contact`]s are in its answer. Every other
//! analysis refuses a mechanism with a pair that may touch, naming the
//! pair ([`refuse_unsolved`]), so nothing passes through a shape silently.

mod corner;
mod crossing;
mod dimension;
mod gap;
mod jet;
mod rolling;
mod shape;
mod width;

use super::{Dimension, Mechanism};
use crate::error::{Error, Result};
use crate::space::Planar;
pub(crate) use corner::{
    COMING_BACK, PASSED_THROUGH, came_back, corner, crossed_edges, crossing_of, deepest_edge, may_cross, ran_off,
    touching,
};
pub use corner::{CornerOf, RIM_POINTS, corners, edges_cross};
pub(crate) use crossing::Turn;
pub use dimension::{SectionJet, Touch, offset_jet};
pub use gap::{Gap, gap, minima};
pub use jet::{GapJet, GapSlope, gap_jet, gap_slope};
pub(crate) use jet::{Material, PointJet, gap_slope_on, material_jet, on_ball, point_jet};
pub(crate) use rolling::{on_flexure, tangents, touched, turned};
pub use shape::{DistanceHessian, GeomShape};
pub(crate) use shape::{array, dot, scaled, vector};
pub use width::width_crossings;

/// A shape on a body (body 0 is the ground): it moves with the body.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{Geom, GeomShape};
/// use flexure::space::Planar;
/// use flexure::Pose;
/// use nalgebra::{Point2, Vector2};
/// // A floor at y = -0.2 on the ground.
/// let floor = Geom::<Planar>::new("floor", 0, Pose { phi: 0.0, x: 0.0, y: -0.2 }, GeomShape::Plane { normal: Vector2::y() });
/// let (gap, normal) = floor.gap(&Pose::default(), &Point2::new(3.0, 0.5), 0.1);
/// assert!((gap - 0.6).abs() < 1e-15 && normal == Vector2::y());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Geom<D: Dimension = Planar> {
    /// Its name (`geom N`, its place among the file's geoms, when the file gives none).
    pub name: String,
    /// The body it is on.
    pub body: usize,
    /// Its frame in the body's frame: where the shape's own frame lies.
    pub frame: D::Pose,
    /// Its solid.
    pub shape: GeomShape<D>,
    /// Coulomb's $\mu \ge 0$ against whatever touches it (0: frictionless).
    pub friction: f64,
    /// The parts it never touches, besides its own body's.
    pub exclude: Vec<Toucher>,
}

/// A part a geom may touch: a flexure joint or another geom (by index).
///
/// # Example
/// ```
/// use flexure::mechanism::contact::Toucher;
/// // Flexures sort before geoms, each by index (`exclude` is kept sorted).
/// assert!(Toucher::Flexure(3) < Toucher::Geom(0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Toucher {
    /// The flexure of this joint.
    Flexure(usize),
    /// This geom.
    Geom(usize),
}

/// A geom and a part that may touch it; of two geoms, at one of their
/// corners ([`corners`]), each corner a pair of its own.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{Pair, Toucher};
/// let p = Pair { geom: 0, part: Toucher::Flexure(1), corner: 0 };
/// assert_eq!(p.part, Toucher::Flexure(1));
/// // Another corner of the same two parts.
/// assert!(p.parts(&Pair { corner: 3, ..p }));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pair {
    /// The geom.
    pub geom: usize,
    /// What may touch it.
    pub part: Toucher,
    /// Of two geoms, which of their [`corners`] (0 for a flexure).
    pub corner: usize,
}

impl Pair {
    /// Whether `other` is of the same two parts (at any corner): what a
    /// sweep's column sums.
    pub fn parts(&self, other: &Pair) -> bool {
        (self.geom, self.part) == (other.geom, other.part)
    }
}

impl<D: Dimension> Geom<D> {
    /// A frictionless geom excluding nothing.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::contact::{Geom, GeomShape};
    /// let g: Geom = Geom::new("post", 0, Default::default(), GeomShape::Ball { radius: 0.1 });
    /// assert_eq!((g.friction, g.exclude.len()), (0.0, 0));
    /// ```
    pub fn new(name: &str, body: usize, frame: D::Pose, shape: GeomShape<D>) -> Self {
        Geom { name: name.into(), body, frame, shape, friction: 0.0, exclude: Vec::new() }
    }

    /// A geom of the same body and friction with another frame and shape,
    /// read in its place: a crossing's plane, a corner's face plane, a box
    /// with a face moved out.
    pub(crate) fn stand_in(&self, frame: D::Pose, shape: GeomShape<D>) -> Self {
        let mut g = Geom::new("", self.body, frame, shape);
        g.friction = self.friction;
        g
    }

    /// Whether it never touches `part` by its own `exclude`.
    fn excludes(&self, part: Toucher) -> bool {
        self.exclude.contains(&part)
    }
}

impl<D: Touch> Geom<D> {
    /// The gap $g = d(p) - h$ (m) between the geom, its body at `body`
    /// (world frame), and a point `p` (world frame) of a toucher of half
    /// thickness $h$ (`half_thickness`), and the geom's outward unit
    /// normal there (world frame); $d$ is [`GeomShape::distance`] in the
    /// geom's frame.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::contact::{Geom, GeomShape};
    /// use flexure::space::Spatial;
    /// use nalgebra::{Isometry3, Point3, Vector3};
    /// let ball = Geom::<Spatial>::new("ball", 1, Isometry3::translation(0.0, 0.0, 1.0), GeomShape::Ball { radius: 0.5 });
    /// let body = Isometry3::translation(1.0, 0.0, 0.0);
    /// let (gap, n) = ball.gap(&body, &Point3::new(1.0, 0.0, 3.0), 0.25);
    /// assert!((gap - 1.25).abs() < 1e-15 && (n - Vector3::z()).norm() < 1e-15);
    /// ```
    pub fn gap(&self, body: &D::Pose, p: &D::Point, half_thickness: f64) -> (f64, D::Vector) {
        let frame = D::compose(body, &self.frame);
        let local = D::position(&D::act(&D::inverse(&frame), p));
        let (d, n) = self.shape.distance(&local);
        (d - half_thickness, D::rotate(&frame, &n))
    }
}

/// The pairs of `m` that may touch, geom by geom: each geom with each
/// flexure, then with each later geom on another body (a pair for each of
/// their [`corners`]); a pair the geom's (or either geom's) `exclude` names is left out.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{pairs, Toucher};
/// let m = flexure::mechanism::file::from_toml(r#"
/// [[joint]]
/// name = "hinge"
/// kind = "flexure"
/// parent = "ground"
/// child = "link"
/// length = 0.02
/// ei = 1e-3
/// [[geom]]
/// body = "ground"
/// shape = "plane"
/// origin = [0.0, -0.01]
/// normal = [0.0, 1.0]
/// [[geom]]
/// body = "link"
/// shape = "circle"
/// origin = [0.001, 0.0]
/// radius = 0.002
/// exclude = ["hinge"]
/// "#).unwrap();
/// let found: Vec<_> = pairs(&m).iter().map(|p| (p.geom, p.part)).collect();
/// // The link's circle holds the flexure's tip, so it excludes the flexure.
/// assert_eq!(found, [(0, Toucher::Flexure(0)), (0, Toucher::Geom(1))]);
/// ```
pub fn pairs<D: Dimension>(m: &Mechanism<D>) -> Vec<Pair> {
    let mut out = Vec::new();
    for (g, geom) in m.geoms.iter().enumerate() {
        for (j, joint) in m.joints.iter().enumerate() {
            if joint.kind.flexure().is_some() && !geom.excludes(Toucher::Flexure(j)) {
                out.push(Pair { geom: g, part: Toucher::Flexure(j), corner: 0 });
            }
        }
        for (h, other) in m.geoms.iter().enumerate().skip(g + 1) {
            if other.body != geom.body && !geom.excludes(Toucher::Geom(h)) && !other.excludes(Toucher::Geom(g)) {
                let part = Toucher::Geom(h);
                out.extend((0..corner::count(m, g, h)).map(|corner| Pair { geom: g, part, corner }));
            }
        }
    }
    out
}

/// The pairs that name a sweep's columns ([`column()`]): of [`pairs`], one
/// per two parts, its first corner; a column sums the pairs of the same
/// two parts ([`Pair::parts`]).
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{column_pairs, pairs};
/// let m = flexure::mechanism::file::from_toml("[[joint]]\nname = \"hinge\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"link\"\nlength = 0.02\nei = 1e-3\n\
///     [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n\
///     [[geom]]\nname = \"foot\"\nbody = \"link\"\nshape = \"box\"\norigin = [0.005, 0.0]\nhalf_extents = [0.002, 0.001]\nexclude = [\"hinge\"]\n").unwrap();
/// // The floor with the flexure, and with the foot at its four corners.
/// assert_eq!(pairs(&m).len(), 5);
/// assert_eq!(column_pairs(&m).len(), 2);
/// ```
pub fn column_pairs<D: Dimension>(m: &Mechanism<D>) -> Vec<Pair> {
    pairs(m).into_iter().filter(|p| p.corner == 0).collect()
}

/// A contact's mode at an equilibrium (its `state` in answers): `"open"` (apart), `"stick"`
/// (held in place along the surface by friction) or `"slip"` (sliding, or
/// free to: a frictionless contact that touches slips, nothing holds it
/// along the surface).
///
/// # Example
/// ```
/// use flexure::mechanism::contact::ContactMode;
/// assert_eq!(serde_json::to_string(&ContactMode::Slip).unwrap(), "\"slip\"");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactMode {
    /// Apart: no force.
    Open,
    /// Touching, held in place along the surface by friction.
    Stick,
    /// Touching, free to slide (or sliding) along the surface.
    Slip,
}

/// A contact of an equilibrium: a pair that touches, or touched on the way
/// and has opened. Forces are what the geom exerts on the toucher (world
/// frame, N); vectors have the dimension's 2 or 3 components.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{Contact, ContactMode};
/// let c = Contact { geom: "floor".into(), flexure: Some("strip".into()), body: None, s: Some(0.1),
///     point: vec![0.1, -0.01], normal: vec![0.0, 1.0], normal_force: 0.12,
///     friction_force: vec![0.0, 0.0], gap: 0.0, state: ContactMode::Slip,
///     pair: flexure::mechanism::contact::Pair { geom: 0, part: flexure::mechanism::contact::Toucher::Flexure(0), corner: 0 } };
/// let json = serde_json::to_value(&c).unwrap();
/// assert_eq!(json["state"], "slip");
/// assert!(json.get("body").is_none());
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Contact {
    /// The geom touched: of two geoms, the one on the ground when one is
    /// (the object a pad closes on), else the pair's first.
    pub geom: String,
    /// The flexure touching it (its joint's name), if a flexure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flexure: Option<String>,
    /// The body that touches it with its own geom, for two geoms.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// Where on the flexure (m from its root).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub s: Option<f64>,
    /// The toucher's surface point (world frame, m).
    pub point: Vec<f64>,
    /// The geom's outward unit normal there (world frame).
    pub normal: Vec<f64>,
    /// The compressive force along the normal (N), not negative.
    pub normal_force: f64,
    /// The tangential (friction) force on the toucher, the flexure or `body` (N, world frame).
    pub friction_force: Vec<f64>,
    /// The gap (m): 0 to the solver's tolerance where touching.
    pub gap: f64,
    /// What it does.
    pub state: ContactMode,
    /// The pair it is of (not serialized: `geom` and `flexure` or `body` name it).
    #[serde(skip)]
    pub pair: Pair,
}

impl Contact {
    /// The contact of `pair` of `m` at `place` (its arc length on a flexure,
    /// the toucher's point, the normal of the gap, the gap) with `forces`
    /// (the normal force, the friction force) and `state`, named as answers
    /// and the sweep's columns name it: the geom touched, and the flexure or
    /// the body that touches it, the normal out of the geom touched.
    pub(crate) fn of<D: Touch>(
        m: &Mechanism<D>,
        pair: &Pair,
        (s, point, normal, gap): (Option<f64>, &D::Point, &D::Vector, f64),
        (normal_force, friction_force): (f64, &D::Vector),
        state: ContactMode,
    ) -> Contact {
        let vector = |v: &D::Vector| (0..D::POINT_DIM).map(|i| v[i]).collect::<Vec<f64>>();
        // The gap's normal is out of the geom the corner touches, and its
        // friction acts on the corner: both turned when the corner's geom is the one named.
        let (geom, flexure, body, side) = match (pair.part, sides(m, pair)) {
            (_, Some((geom, body))) => {
                let own = corner(m, pair).is_ok_and(|c| std::ptr::eq(c.round, &m.geoms[geom]));
                (m.geoms[geom].name.clone(), None, Some(m.bodies[body].name.clone()), if own { -1.0 } else { 1.0 })
            }
            (Toucher::Flexure(j), None) => (m.geoms[pair.geom].name.clone(), Some(m.joints[j].name.clone()), None, 1.0),
            (Toucher::Geom(_), None) => unreachable!("two geoms have sides"),
        };
        Contact {
            geom,
            flexure,
            body,
            s,
            point: vector(&D::position(point)),
            normal: vector(&scaled::<D>(normal, side)),
            normal_force,
            // + 0.0: a turned zero is −0.
            friction_force: vector(&scaled::<D>(friction_force, side)).into_iter().map(|f| f + 0.0).collect(),
            gap,
            state,
            pair: *pair,
        }
    }
}

/// Of a pair of two geoms, the geom touched and the body that touches it
/// with its own geom: the geom on the ground when one is (the object a
/// finger's pad closes on), else the pair's first.
pub(crate) fn sides<D: Dimension>(m: &Mechanism<D>, pair: &Pair) -> Option<(usize, usize)> {
    let Toucher::Geom(h) = pair.part else { return None };
    let (a, b) = (pair.geom, h);
    let grounded = |g: usize| m.geoms[g].body == 0;
    Some(if grounded(b) && !grounded(a) { (b, m.geoms[a].body) } else { (a, m.geoms[b].body) })
}

/// Coulomb's $\mu$ of `pair`: its geom's against a flexure, the larger of
/// the two geoms' between geoms (MuJoCo's rule).
pub(crate) fn friction<D: Dimension>(m: &Mechanism<D>, pair: &Pair) -> f64 {
    match pair.part {
        Toucher::Flexure(_) => m.geoms[pair.geom].friction,
        Toucher::Geom(h) => m.geoms[pair.geom].friction.max(m.geoms[h].friction),
    }
}

/// The length (m) of the flexure of `pair`, the scale of its place `s`; 1 between two geoms.
pub(crate) fn length<D: Dimension>(m: &Mechanism<D>, pair: &Pair) -> f64 {
    match pair.part {
        Toucher::Flexure(j) => m.joints[j].kind.flexure().map_or(1.0, D::flexure_length),
        Toucher::Geom(_) => 1.0,
    }
}

/// A pair's column name in a sweep's table: `contact.GEOM.PART`, PART the
/// flexure's joint or, for two geoms, the body that touches GEOM with its
/// own geom ([`Contact`]'s `geom` and `flexure` or `body`).
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{column, pairs};
/// let m = flexure::mechanism::file::from_toml("[[joint]]\nname = \"hinge\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"link\"\nlength = 0.02\nei = 1e-3\n\
///     [[geom]]\nname = \"post\"\nbody = \"ground\"\nshape = \"circle\"\norigin = [0.01, 0.01]\nradius = 0.002\n").unwrap();
/// assert_eq!(column(&m, &pairs(&m)[0]), "contact.post.hinge");
/// ```
pub fn column<D: Dimension>(m: &Mechanism<D>, p: &Pair) -> String {
    let (geom, part) = match (p.part, sides(m, p)) {
        (Toucher::Flexure(j), _) => (p.geom, &m.joints[j].name),
        (_, Some((geom, body))) => (geom, &m.bodies[body].name),
        (Toucher::Geom(_), None) => unreachable!("two geoms have sides"),
    };
    format!("contact.{}.{part}", m.geoms[geom].name)
}

/// A pair as a message names it: `geom "floor" (plane) and flexure "hinge"`.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{Geom, GeomShape, Pair, Toucher, named};
/// let mut m = flexure::mechanism::file::from_toml("[[joint]]\nname = \"hinge\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"link\"\nlength = 0.02\nei = 1e-3\n").unwrap();
/// m.geoms.push(Geom::new("post", 0, Default::default(), GeomShape::Ball { radius: 0.01 }));
/// let p = Pair { geom: 0, part: Toucher::Flexure(0), corner: 0 };
/// assert_eq!(named(&m, &p), "geom \"post\" (circle) and flexure \"hinge\"");
/// ```
pub fn named<D: Dimension>(m: &Mechanism<D>, p: &Pair) -> String {
    let g = &m.geoms[p.geom];
    let other = match p.part {
        Toucher::Flexure(j) => format!("flexure {:?}", m.joints[j].name),
        Toucher::Geom(h) => format!(
            "geom {:?} ({}) on body {:?}",
            m.geoms[h].name,
            m.geoms[h].shape.name(),
            m.bodies[m.geoms[h].body].name
        ),
    };
    format!("geom {:?} ({}) and {other}", g.name, g.shape.name())
}

/// An error naming the first pair of `m` that may touch, for the analyses
/// that do not solve contact yet (all but the equilibrium solve, sweep, motion,
/// compliance and modes): none may
/// let a part pass through a shape silently. `Ok` when no pair may touch (no geoms, or every pair
/// excluded), so a mechanism's other analyses are unchanged.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::refuse_unsolved;
/// let text = "[[joint]]\nname = \"hinge\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"link\"\nlength = 0.02\nei = 1e-3\n";
/// let free = flexure::mechanism::file::from_toml(text).unwrap();
/// assert!(refuse_unsolved(&free).is_ok());
/// let floor = "[[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n";
/// let m = flexure::mechanism::file::from_toml(&format!("{text}{floor}")).unwrap();
/// let e = refuse_unsolved(&m).unwrap_err().to_string();
/// assert!(e.contains("geom \"floor\" (plane) and flexure \"hinge\""), "{e}");
/// ```
pub fn refuse_unsolved<D: Dimension>(m: &Mechanism<D>) -> Result<()> {
    match pairs(m).first() {
        None => Ok(()),
        Some(p) => Err(Error::invalid(
            "geom",
            named(m, p),
            "may touch, and only equilibrium solves, sweeps, compliances, modes and motion handle contact yet: solve it, remove the geom, or name the other part in its `exclude` to let them pass through each other",
        )),
    }
}
