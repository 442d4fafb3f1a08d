//! URDF (ROS): the tree only.

use super::model::{Attachment, LinkMotion, RigidModel};
use super::xml::{Element, number, numbers};
use crate::space::Pose;

/// The name of URDF's root link, the ground: ROS and Gazebo fix a link of this name to the world.
pub const ROOT: &str = "world";

fn origin(p: &Pose) -> Element {
    Element::new("origin").attr("xyz", numbers(&[p.x, p.y, 0.0])).attr("rpy", numbers(&[0.0, 0.0, p.phi]))
}

/// The model as URDF, with `comment` at its top, and a warning for each
/// thing URDF cannot hold: springs (every joint with a stiffness), tendons,
/// forces, gravity, closures, armature.
///
/// URDF turns a joint about its child link's origin, so a hinge away from
/// it (a flexure's pivot) gets a massless link `NAME_pivot` there, which
/// the hinge turns, and a fixed joint `NAME_tip` to the body, whose frame
/// stays the file's. Hinges are `continuous`; a slide is `prismatic`, whose
/// required limits are written as $\pm$ `travel` (m) with zero effort and
/// velocity, with a warning. Coordinates are measured from rest.
pub fn write(model: &RigidModel, name: &str, comment: &[String], travel: f64) -> (String, Vec<String>) {
    let mut warnings = Vec::new();
    let mut robot = Element::new("robot").attr("name", name);
    for c in comment {
        robot.comment(c.clone());
    }
    robot.push(Element::new("link").attr("name", ROOT));
    let link_name = |i: usize| if i == 0 { ROOT.to_string() } else { model.links[i].name.clone() };
    for (i, l) in model.links.iter().enumerate().skip(1) {
        let m = &l.inertia;
        let inertia = Element::new("inertia")
            .attr("ixx", number(m.inertia))
            .attr("ixy", "0")
            .attr("ixz", "0")
            .attr("iyy", number(m.inertia))
            .attr("iyz", "0")
            .attr("izz", number(m.inertia));
        let inertial = Element::new("inertial")
            .child(origin(&Pose { phi: 0.0, x: m.com[0], y: m.com[1] }))
            .child(Element::new("mass").attr("value", number(m.mass)))
            .child(inertia);
        robot.push(Element::new("link").attr("name", l.name.as_str()).child(inertial));
        let parent = link_name(l.parent);
        let Some(h) = l.joints.first() else {
            robot.push(
                Element::new("joint")
                    .attr("name", l.connection.as_str())
                    .attr("type", "fixed")
                    .child(Element::new("parent").attr("link", parent))
                    .child(Element::new("child").attr("link", l.name.as_str()))
                    .child(origin(&l.pose)),
            );
            continue;
        };
        let (kind, axis) = match h.motion {
            LinkMotion::Hinge => ("continuous", [0.0, 0.0, 1.0]),
            LinkMotion::Slide => ("prismatic", [h.axis.x, h.axis.y, 0.0]),
        };
        let pivot = h.at.x != 0.0 || h.at.y != 0.0;
        let (child, place) = if pivot {
            (format!("{}_pivot", h.name), l.pose.compose(&Pose { phi: 0.0, x: h.at.x, y: h.at.y }))
        } else {
            (l.name.clone(), l.pose)
        };
        let mut j = Element::new("joint")
            .attr("name", h.name.as_str())
            .attr("type", kind)
            .child(Element::new("parent").attr("link", parent))
            .child(Element::new("child").attr("link", child.as_str()))
            .child(origin(&place))
            .child(Element::new("axis").attr("xyz", numbers(&axis)));
        if h.motion == LinkMotion::Slide {
            let (limit, said) = slide_limit(&h.name, travel);
            j.push(limit);
            warnings.push(said);
        }
        if h.damping > 0.0 {
            j.push(Element::new("dynamics").attr("damping", number(h.damping)));
        }
        if h.stiffness.iter().any(|k| *k != 0.0) {
            warnings.push(format!(
                "joint {:?}: URDF has no springs; its stiffness [{}] is not written",
                h.name,
                numbers(&h.stiffness).replace(' ', ", ")
            ));
        }
        if h.armature > 0.0 {
            warnings.push(format!("joint {:?}: URDF has no armature; dropped", h.name));
        }
        if pivot {
            // The massless pivot link, then the body fixed to it at its own frame.
            robot.push(Element::new("link").attr("name", child.as_str()));
            robot.push(j);
            robot.push(
                Element::new("joint")
                    .attr("name", format!("{}_tip", h.name))
                    .attr("type", "fixed")
                    .child(Element::new("parent").attr("link", child.as_str()))
                    .child(Element::new("child").attr("link", l.name.as_str()))
                    .child(origin(&Pose { phi: 0.0, x: -h.at.x, y: -h.at.y })),
            );
        } else {
            robot.push(j);
        }
        let _ = i;
    }
    if model.gravity != nalgebra::Vector2::zeros() {
        warnings.push(format!(
            "gravity [{}]: URDF has no gravity (the simulator's world sets it); not written",
            numbers(&[model.gravity.x, model.gravity.y]).replace(' ', ", ")
        ));
    }
    for a in &model.attachments {
        warnings.push(match a {
            Attachment::Tendon { name, .. } => format!("tendon {name:?}: URDF has no tendons; not written"),
            Attachment::Force { name, .. } => format!("force {name:?}: URDF has no applied loads; not written"),
            Attachment::Weld { label, .. } | Attachment::Pin { label, .. } => {
                format!("{label}: URDF has no loops (a tree only); this closure is not written")
            }
        });
    }
    (robot.document(), warnings)
}

/// A prismatic joint's `limit` of ±`travel` (m), which URDF requires, with
/// the warning naming joint `name` that says so (both dimensions' URDF).
pub(super) fn slide_limit(name: &str, travel: f64) -> (Element, String) {
    let limit = Element::new("limit")
        .attr("lower", number(-travel))
        .attr("upper", number(travel))
        .attr("effort", "0")
        .attr("velocity", "0");
    let said = format!(
        "joint {name:?}: URDF requires a prismatic joint's limits; written as ±{} m (the mechanism's size), effort and velocity 0",
        number(travel)
    );
    (limit, said)
}
