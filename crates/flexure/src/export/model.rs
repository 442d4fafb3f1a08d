//! The rigid-body model of a mechanism: its bodies, with each flexure
//! replaced by the hinges of its pseudo-rigid-body model, in a form every
//! writer reads.

use super::lump;
use crate::error::{Error, Result};
use crate::inertia::RigidInertia;
use crate::mechanism::{Holds, Mechanism};
use crate::space::{Pose, Wrench};
use nalgebra::{Point2, Vector2};

/// The least mass (kg) a moving link is given: MuJoCo refuses a moving body
/// of less than $10^{-15}$ kg, Gazebo's solvers misbehave with none. The
/// file's massless bodies get it, and the pseudo-rigid links of a massless
/// flexure where they are kept (SDFormat and URDF, one joint a link; MJCF
/// merges them away, [`build`]); it weighs $10^{-8}$ N under Earth's gravity.
pub const MIN_MASS: f64 = 1e-9;
/// The least rotary inertia (kg·m²) a moving link is given, for the same reason.
pub const MIN_INERTIA: f64 = 1e-14;

/// A flexure's pseudo-rigid-body chain as the model needs it: the pivot of
/// each hinge at rest, in the flexure's root frame (root first), and its
/// spring $\tau = -(k_1\theta + k_2\theta^2 + k_3\theta^3)$ about rest.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// The pivots (m), in the root frame, root first.
    pub pivots: Vec<Point2<f64>>,
    /// Each hinge's $[k_1, k_2, k_3]$ (N·m/rad, N·m/rad², N·m/rad³).
    pub stiffness: Vec<[f64; 3]>,
    /// Each pivot's arc length along the rest shape (m): where the
    /// flexure's mass is cut between the links on either side of it.
    pub arcs: Vec<f64>,
}

/// How a link moves in its parent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LinkMotion {
    /// About the z axis through [`ModelJoint::at`].
    Hinge,
    /// Along [`ModelJoint::axis`].
    Slide,
}

/// A moving joint of the model: it moves its link, at coordinate
/// `reference` the link is at its rest pose. A link's joints act in order,
/// each about its own point in the link's frame as the joints before it
/// have moved it (MuJoCo's rule for a body's joints), so several hinges on
/// one link move it as a chain of massless links would.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelJoint {
    /// Its name: the file joint's, or `NAME_1`… for a 3R chain's hinges.
    pub name: String,
    /// Hinge or slide.
    pub motion: LinkMotion,
    /// The hinge's point, in the link's frame (m).
    pub at: Point2<f64>,
    /// The slide's direction, in the link's frame (unit).
    pub axis: Vector2<f64>,
    /// The coordinate at the rest pose: a revolute or prismatic joint's
    /// `rest` (so the coordinate is the file's), zero for a pseudo-rigid hinge.
    pub reference: f64,
    /// The spring's $[k_1, k_2, k_3]$ about `reference`.
    pub stiffness: [f64; 3],
    /// Viscous damping (N·m·s/rad or N·s/m): a revolute or prismatic joint's,
    /// or a flexure's $\beta$ times $k_1$.
    pub damping: f64,
    /// Rotor inertia added to the coordinate (kg·m²), MuJoCo's `armature`.
    pub armature: f64,
    /// The file's joint it comes from (index into [`Mechanism::joints`]).
    pub source: usize,
}

/// A link: a file's body, or a pseudo-rigid link between two hinges.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// Its name: the body's, or `NAME_prbK` for the K-th link inside flexure NAME.
    pub name: String,
    /// Parent link (index; the ground's is itself, 0).
    pub parent: usize,
    /// Rest pose in the parent link's frame.
    pub pose: Pose,
    /// Rest pose in the world.
    pub world: Pose,
    /// Mass, rotary inertia and centre of mass in the link's frame: the
    /// body's with the flexure pieces lumped on it, floored at
    /// [`MIN_MASS`] and [`MIN_INERTIA`] where it moves.
    pub inertia: RigidInertia,
    /// Whether the inertia was raised to the floor.
    pub floored: bool,
    /// Its joints to the parent, applied in order ([`ModelJoint`]): none for
    /// the ground and a fixed joint's child, one for a hinge or slide, a
    /// massless flexure's whole chain on its child when merged.
    pub joints: Vec<ModelJoint>,
    /// The name of the connection to the parent (the file joint's, or a
    /// hinge's), for formats that name fixed joints too.
    pub connection: String,
}

/// A point or frame on a link: a tendon's via point, a force's point, a closure's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Site {
    /// Its name.
    pub name: String,
    /// The link.
    pub link: usize,
    /// Its pose in the link's frame.
    pub pose: Pose,
}

/// A load or closure of the file, on the model's sites.
#[derive(Debug, Clone, PartialEq)]
pub enum Attachment {
    /// A tendon through these sites, with its tension (N).
    Tendon { name: String, sites: Vec<usize>, tension: f64 },
    /// A force and moment at a site, in the world's frame (dead load).
    Force { name: String, site: usize, wrench: Wrench },
    /// Two site frames held together (a weld); `open` when apart at rest;
    /// `label` names it for a person (its bodies and place in the file).
    Weld { name: String, label: String, a: usize, b: usize, open: bool },
    /// Two site points held together (a pin), as a weld.
    Pin { name: String, label: String, a: usize, b: usize, open: bool },
}

/// The rigid-body model: links in parent-first order (link 0 is the ground,
/// the world), sites, loads and closures, and gravity (m/s², in the plane).
#[derive(Debug, Clone, PartialEq)]
pub struct RigidModel {
    /// Links; 0 is the ground.
    pub links: Vec<Link>,
    /// Sites.
    pub sites: Vec<Site>,
    /// Tendons, forces, welds and pins.
    pub attachments: Vec<Attachment>,
    /// Gravity (m/s²), in the plane.
    pub gravity: Vector2<f64>,
    /// The link of each of the file's bodies.
    pub body_link: Vec<usize>,
}

/// Builds the model of `m` with each flexure joint `j` replaced by
/// `chains[j]` (ignored for other kinds; required for flexures), its
/// hinges given `armature`.
///
/// Revolute joints become hinges at their child's origin, prismatic joints
/// slides along their root's x axis, fixed joints rigid attachments; every
/// body keeps its frame (the file's), so its name, mass, inertia and centre
/// of mass carry over unchanged. A flexure of $k$ hinges at pivots
/// $p_1, \dots, p_k$ (its root frame, at rest) puts links `NAME_prb1` …
/// `NAME_prb{k-1}` at $p_1, \dots, p_{k-1}$ (turned as the root), each
/// with its hinge at its origin, and the last hinge on the child body at
/// $p_k$; at rest every hinge is at zero and the child at the flexure's
/// rest tip. A flexure with mass has it cut at its pivots' arc lengths and
/// each piece lumped ([`lump::segment`]) on the link it moves with: the piece
/// before the first pivot on the parent body.
///
/// With `merge` (MJCF, whose body may carry several joints), a massless
/// flexure's links are merged away: its hinges all go on the child body,
/// in order, each at its pivot in the child's frame at rest, which moves
/// the child exactly as the chain of massless links would (MuJoCo applies a
/// body's joints in order, each about its own anchor in the body's frame as
/// moved by the ones before: `mj_kinematics`). Without it (SDFormat and
/// URDF, one joint a link) they are kept, at the least mass.
pub fn build(m: &Mechanism, chains: &[Option<Chain>], armature: f64, merge: bool) -> Result<RigidModel> {
    if !(armature.is_finite() && armature >= 0.0) {
        return Err(Error::invalid("armature", armature, "must be a finite number, zero or greater (kg·m²)"));
    }
    let ground = Link {
        name: m.bodies[0].name.clone(),
        parent: 0,
        pose: Pose::default(),
        world: Pose::default(),
        inertia: RigidInertia::default(),
        floored: false,
        joints: Vec::new(),
        connection: String::new(),
    };
    let mut links = vec![ground];
    let mut body_link = vec![0; m.bodies.len()];
    // Pieces of flexure mass lumped on a body, in its frame.
    let mut lumped: Vec<Vec<RigidInertia>> = vec![Vec::new(); m.bodies.len()];
    for (ji, spec) in m.joints.iter().enumerate() {
        let parent = body_link[spec.parent];
        let body = &m.bodies[spec.child];
        let mut link = |name: String, parent: usize, pose: Pose, joint: Option<ModelJoint>, connection: String| {
            let world = links[parent].world.compose(&pose);
            links.push(Link {
                name,
                parent,
                pose,
                world,
                inertia: RigidInertia::default(),
                floored: false,
                joints: joint.into_iter().collect(),
                connection,
            });
            links.len() - 1
        };
        let one = |motion, at, axis, reference, stiffness: f64, damping| ModelJoint {
            name: spec.name.clone(),
            motion,
            at,
            axis,
            reference,
            stiffness: [stiffness, 0.0, 0.0],
            damping,
            armature: 0.0,
            source: ji,
        };
        // Read from the joint interface, as the drawing does, so a new kind
        // is exported without a case here: a flexure by its pseudo-rigid
        // chain, a weld (no coordinates) as an attachment, and a rigid joint
        // of one coordinate as a hinge, or a slide if that coordinate is a
        // length, with its spring and rest read from its data at rest.
        let joint = spec.kind.joint();
        let child = match joint.flexure() {
            None if joint.dof() == 0 => link(body.name.clone(), parent, spec.origin, None, spec.name.clone()),
            None if joint.dof() == 1 => {
                let rest = joint.rest();
                let at_rest = joint.evaluate(&rest);
                let (motion, axis) = if joint.is_translation() {
                    let column = Vector2::new(at_rest.jacobian[(1, 0)], at_rest.jacobian[(2, 0)]);
                    (LinkMotion::Slide, column)
                } else {
                    (LinkMotion::Hinge, Vector2::x())
                };
                let pose = spec.origin.compose(&at_rest.pose);
                let j = one(motion, Point2::origin(), axis, rest[0], at_rest.stiffness[(0, 0)], spec.damping);
                link(body.name.clone(), parent, pose, Some(j), spec.name.clone())
            }
            None => {
                return Err(Error::invalid(
                    "joint",
                    &spec.name,
                    "is rigid with more than one coordinate: the export models rigid joints of one",
                ));
            }
            Some(f) => {
                let chain = chains.get(ji).and_then(Option::as_ref).ok_or(Error::Singular {
                    what: format!("flexure joint {:?} has no pseudo-rigid-body chain", spec.name),
                })?;
                let k = chain.pivots.len();
                if k == 0 || chain.stiffness.len() != k || chain.arcs.len() != k {
                    return Err(Error::Singular {
                        what: format!("flexure joint {:?}: a chain needs one stiffness per pivot", spec.name),
                    });
                }
                let tip = crate::kinematics::pose_root_tip(f, f.rest());
                let hinge = |i: usize, at: Point2<f64>| ModelJoint {
                    name: if k == 1 { spec.name.clone() } else { format!("{}_{}", spec.name, i + 1) },
                    motion: LinkMotion::Hinge,
                    at,
                    axis: Vector2::x(),
                    reference: 0.0,
                    stiffness: chain.stiffness[i],
                    damping: spec.damping * chain.stiffness[i][0],
                    armature,
                    source: ji,
                };
                // Frames in the root frame: each intermediate link at its pivot, then the tip.
                let mut frames: Vec<Pose> = chain.pivots[..k - 1].iter().map(|p| Pose::new(0.0, *p)).collect();
                frames.push(tip);
                let mut up = parent;
                let mut before = spec.origin; // the previous frame, in `up`'s frame: the root, first.
                let mut prev_root = Pose::default();
                let mut made = Vec::with_capacity(k);
                for (i, frame) in frames.iter().enumerate() {
                    let pose = before.compose(&prev_root.inverse().compose(frame));
                    let at = if i + 1 < k { Point2::origin() } else { tip.inverse().act(&chain.pivots[i]) };
                    let j = hinge(i, at);
                    let connection = j.name.clone();
                    let name = if i + 1 < k { format!("{}_prb{}", spec.name, i + 1) } else { body.name.clone() };
                    up = link(name, up, pose, Some(j), connection);
                    made.push(up);
                    before = Pose::default();
                    prev_root = *frame;
                }
                // The flexure's mass, cut at the pivots' arc lengths.
                let mut cuts = vec![0.0];
                cuts.extend(chain.arcs.iter().map(|s| s.clamp(0.0, f.length())));
                cuts.push(f.length());
                for (i, w) in cuts.windows(2).enumerate() {
                    let Some(piece) = lump::segment(f, w[0], w[1].max(w[0]))? else { continue };
                    if i == 0 {
                        if spec.parent != 0 {
                            let on = lump::moved(&spec.origin, &piece);
                            lumped[spec.parent].push(on);
                        }
                    } else {
                        let l = made[i - 1];
                        let frame = frames[i - 1];
                        let on = lump::moved(&frame.inverse(), &piece);
                        links[l].inertia = lump::add(&links[l].inertia, &on);
                    }
                }
                up
            }
        };
        body_link[spec.child] = child;
    }
    for (b, body) in m.bodies.iter().enumerate().skip(1) {
        let l = body_link[b];
        let mut total = body.rigid_inertia();
        for p in &lumped[b] {
            total = lump::add(&total, p);
        }
        // The last flexure piece (on the child) was added to the link already.
        links[l].inertia = lump::add(&links[l].inertia, &total);
    }
    // Names are checked before merging: a name a generated link takes is
    // refused in every format.
    check_names(&links, &[])?;
    if merge {
        merge_massless(&mut links, &mut body_link);
    }
    for l in links.iter_mut().skip(1) {
        if l.inertia.mass < MIN_MASS || l.inertia.inertia < MIN_INERTIA {
            l.floored = true;
            l.inertia.mass = l.inertia.mass.max(MIN_MASS);
            l.inertia.inertia = l.inertia.inertia.max(MIN_INERTIA);
        }
    }
    let mut model = RigidModel { links, sites: Vec::new(), attachments: Vec::new(), gravity: m.gravity, body_link };
    attach(m, &mut model);
    check_names(&model.links, &model.sites)?;
    Ok(model)
}

/// Merges each pseudo-rigid link without mass (of a massless flexure) into
/// its one child: the child takes the link's place (its pose composed) and
/// its joints first, each point carried into the child's frame; taken tip
/// first, a chain's hinges all end on the body, root first.
fn merge_massless(links: &mut Vec<Link>, body_link: &mut [usize]) {
    let n = links.len();
    let mut gone = vec![false; n];
    // Tip first: each link's joints go on the body, carried through the
    // links merged into it before.
    for i in (1..n).rev() {
        let is_body = body_link.contains(&i);
        let massless = links[i].inertia.mass == 0.0 && links[i].inertia.inertia == 0.0;
        let children: Vec<usize> = (i + 1..n).filter(|&c| !gone[c] && links[c].parent == i).collect();
        if is_body || !massless || children.len() != 1 {
            continue;
        }
        let c = children[0];
        let inward = links[c].pose.inverse();
        let mut joints: Vec<ModelJoint> = std::mem::take(&mut links[i].joints);
        for j in &mut joints {
            j.at = inward.act(&j.at);
            j.axis = inward.rotate(&j.axis);
        }
        joints.append(&mut links[c].joints);
        links[c].joints = joints;
        links[c].pose = links[i].pose.compose(&links[c].pose);
        links[c].parent = links[i].parent;
        gone[i] = true;
    }
    remove_merged(links, &gone, body_link, |l| &mut l.parent);
}

/// Removes the links marked `gone` (merged into their children), renumbering
/// each remaining link's parent and each body's link: the merges of either
/// dimension.
pub(crate) fn remove_merged<T>(
    links: &mut Vec<T>,
    gone: &[bool],
    body_link: &mut [usize],
    parent: fn(&mut T) -> &mut usize,
) {
    let mut index = Vec::with_capacity(gone.len());
    let mut k = 0;
    for g in gone {
        index.push(k);
        if !g {
            k += 1;
        }
    }
    let mut i = 0;
    links.retain(|_| {
        i += 1;
        !gone[i - 1]
    });
    for l in links.iter_mut() {
        let p = parent(l);
        *p = index[*p];
    }
    for b in body_link.iter_mut() {
        *b = index[*b];
    }
}

/// The file's tendons, forces and closures on sites of the model.
fn attach(m: &Mechanism, model: &mut RigidModel) {
    let site = |model: &mut RigidModel, name: String, body: usize, pose: Pose| {
        let link = model.body_link[body];
        model.sites.push(Site { name, link, pose });
        model.sites.len() - 1
    };
    for t in &m.tendons {
        let sites = t
            .path
            .iter()
            .enumerate()
            .map(|(i, (b, p))| site(model, format!("{}_{i}", t.name), *b, Pose::new(0.0, *p)))
            .collect();
        model.attachments.push(Attachment::Tendon { name: t.name.clone(), sites, tension: t.tension });
    }
    for f in &m.forces {
        let s = site(model, format!("force_{}", f.name), f.body, Pose::new(0.0, f.at));
        model.attachments.push(Attachment::Force { name: f.name.clone(), site: s, wrench: f.wrench });
    }
    let gap = 1e-9 * m.size();
    for (i, c) in m.closures.iter().enumerate() {
        let (a, b) = (c.a, c.b);
        let label =
            format!("{} {:?}–{:?} ({})", c.holds.name(), m.bodies[a].name, m.bodies[b].name, m.closure_place(i));
        match c.holds {
            Holds::Weld => {
                let name = format!("weld_{i}");
                let sa = site(model, format!("{name}_a"), a, c.a_origin);
                let sb = site(model, format!("{name}_b"), b, c.b_origin);
                let (wa, wb) = (model.world(sa), model.world(sb));
                let turn = (wa.phi - wb.phi).sin().atan2((wa.phi - wb.phi).cos());
                let open = (wa.x - wb.x).hypot(wa.y - wb.y) > gap || turn.abs() > 1e-9;
                model.attachments.push(Attachment::Weld { name, label, a: sa, b: sb, open });
            }
            Holds::Pin | Holds::Ball => {
                let name = format!("pin_{i}");
                let sa = site(model, format!("{name}_a"), a, Pose::new(0.0, c.a_origin.origin()));
                let sb = site(model, format!("{name}_b"), b, Pose::new(0.0, c.b_origin.origin()));
                let (wa, wb) = (model.world(sa), model.world(sb));
                let open = (wa.x - wb.x).hypot(wa.y - wb.y) > gap;
                model.attachments.push(Attachment::Pin { name, label, a: sa, b: sb, open });
            }
        }
    }
}

/// Generated names (pseudo-rigid links, sites) must not take a body's or a joint's.
fn check_names(links: &[Link], sites: &[Site]) -> Result<()> {
    let mut seen = std::collections::HashSet::new();
    for l in links {
        if !seen.insert(l.name.as_str()) {
            return Err(Error::invalid(
                "body",
                format!("{:?}", l.name),
                "is also the name of a generated pseudo-rigid link",
            ));
        }
    }
    let mut joints = std::collections::HashSet::new();
    for l in links {
        let mut names: Vec<&str> = l.joints.iter().map(|j| j.name.as_str()).collect();
        if names.is_empty() && !l.connection.is_empty() {
            names.push(l.connection.as_str());
        }
        for name in names {
            if !joints.insert(name) {
                return Err(Error::invalid(
                    "joint",
                    format!("{name:?}"),
                    "is also the name of a generated pseudo-rigid hinge",
                ));
            }
        }
    }
    let mut names = std::collections::HashSet::new();
    for s in sites {
        if !names.insert(s.name.as_str()) {
            return Err(Error::invalid(
                "site",
                format!("{:?}", s.name),
                "two generated sites share this name (rename a tendon or force)",
            ));
        }
    }
    Ok(())
}

impl RigidModel {
    /// Site `s`'s rest pose in the world.
    pub fn world(&self, s: usize) -> Pose {
        let site = &self.sites[s];
        self.links[site.link].world.compose(&site.pose)
    }

    /// The links' children, each list in order.
    pub fn children(&self) -> Vec<Vec<usize>> {
        let mut c = vec![Vec::new(); self.links.len()];
        for (i, l) in self.links.iter().enumerate().skip(1) {
            c[l.parent].push(i);
        }
        c
    }

    /// The moving joints, with their link, in link order (a link's in its order).
    pub fn joints(&self) -> impl Iterator<Item = (usize, &ModelJoint)> {
        self.links.iter().enumerate().flat_map(|(i, l)| l.joints.iter().map(move |j| (i, j)))
    }
}
