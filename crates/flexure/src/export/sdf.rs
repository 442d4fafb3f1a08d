//! SDFormat (Gazebo), version 1.9.

use super::model::{Attachment, LinkMotion, RigidModel};
use super::xml::{Element, number, numbers};
use crate::space::Pose;

fn pose(p: &Pose) -> Element {
    Element::new("pose").text(numbers(&[p.x, p.y, 0.0, 0.0, 0.0, p.phi]))
}

fn leaf(name: &str, v: f64) -> Element {
    Element::new(name).text(number(v))
}

/// The model as an SDFormat 1.9 world holding one model (so that gravity,
/// a world property in SDFormat, is kept), with `comment` at its top, and a
/// warning for each thing SDFormat cannot hold.
///
/// Links are posed in the model's frame at rest; each joint's frame is at
/// its hinge, relative to its child link, its axis in that frame; joint
/// coordinates are measured from rest (`spring_reference` 0). A joint's
/// spring is `spring_stiffness` $k_1$: SDFormat has no polynomial spring,
/// so $k_2$ and $k_3$ are dropped with a warning. Joints on the ground have
/// `world` as parent. A pin closed at rest becomes a revolute joint between
/// its bodies, a weld a fixed joint (kinematic loops: whether they hold
/// depends on the physics engine); one open at rest cannot be written (an
/// SDFormat joint has one frame), nor can tendons or forces (no static
/// loads without a plugin): each is warned of by name.
pub fn write(model: &RigidModel, name: &str, comment: &[String]) -> (String, Vec<String>) {
    let mut warnings = Vec::new();
    let mut m = Element::new("model").attr("name", name);
    for l in model.links.iter().skip(1) {
        let i = &l.inertia;
        let inertia = Element::new("inertia")
            .child(leaf("ixx", i.inertia))
            .child(leaf("ixy", 0.0))
            .child(leaf("ixz", 0.0))
            .child(leaf("iyy", i.inertia))
            .child(leaf("iyz", 0.0))
            .child(leaf("izz", i.inertia));
        let inertial = Element::new("inertial")
            .child(pose(&Pose { phi: 0.0, x: i.com[0], y: i.com[1] }))
            .child(leaf("mass", i.mass))
            .child(inertia);
        m.push(Element::new("link").attr("name", l.name.as_str()).child(pose(&l.world)).child(inertial));
    }
    let parent_name = |i: usize| if i == 0 { "world".to_string() } else { model.links[i].name.clone() };
    for l in model.links.iter().skip(1) {
        let mut j = Element::new("joint").attr("name", l.connection.as_str());
        match l.joints.first() {
            None => {
                j = j.attr("type", "fixed");
                j.push(Element::new("parent").text(parent_name(l.parent)));
                j.push(Element::new("child").text(l.name.as_str()));
            }
            Some(h) => {
                let (kind, axis) = match h.motion {
                    LinkMotion::Hinge => ("revolute", [0.0, 0.0, 1.0]),
                    LinkMotion::Slide => ("prismatic", [h.axis.x, h.axis.y, 0.0]),
                };
                j = j.attr("type", kind);
                j.push(Element::new("parent").text(parent_name(l.parent)));
                j.push(Element::new("child").text(l.name.as_str()));
                j.push(pose(&Pose { phi: 0.0, x: h.at.x, y: h.at.y }));
                let mut dynamics = Element::new("dynamics");
                dynamics.push(leaf("damping", h.damping));
                dynamics.push(leaf("spring_reference", 0.0));
                dynamics.push(leaf("spring_stiffness", h.stiffness[0]));
                let mut ax = Element::new("axis").child(Element::new("xyz").text(numbers(&axis)));
                ax.push(dynamics);
                j.push(ax);
                if h.stiffness[1] != 0.0 || h.stiffness[2] != 0.0 {
                    warnings.push(format!(
                        "joint {:?}: SDFormat has no polynomial spring; spring_stiffness is k1 = {}, and k2 = {}, k3 = {} are dropped",
                        h.name,
                        number(h.stiffness[0]),
                        number(h.stiffness[1]),
                        number(h.stiffness[2])
                    ));
                }
                if h.armature > 0.0 {
                    warnings.push(format!("joint {:?}: SDFormat has no armature; dropped", h.name));
                }
            }
        }
        m.push(j);
    }
    for a in &model.attachments {
        match a {
            Attachment::Tendon { name, .. } => {
                warnings.push(format!("tendon {name:?}: SDFormat has no tendons (a Gazebo plugin would pull it); not written"))
            }
            Attachment::Force { name, .. } => warnings
                .push(format!("force {name:?}: SDFormat has no static applied loads (a Gazebo plugin would apply it); not written")),
            Attachment::Weld { label, open: true, .. } | Attachment::Pin { label, open: true, .. } => warnings.push(format!(
                "{label}: open at rest (a preload); an SDFormat joint has one frame and cannot close it; not written"
            )),
            closure @ (Attachment::Weld { name, a, b, open: false, .. } | Attachment::Pin { name, a, b, open: false, .. }) => {
                let weld = matches!(closure, Attachment::Weld { .. });
                let (sa, sb) = (&model.sites[*a], &model.sites[*b]);
                let mut j = Element::new("joint").attr("name", name.as_str()).attr("type", if weld { "fixed" } else { "revolute" });
                j.push(Element::new("parent").text(parent_name(sa.link)));
                if sb.link == 0 {
                    // SDFormat's child cannot be the world: swap the ends.
                    j.children.clear();
                    j.push(Element::new("parent").text(parent_name(sb.link)));
                    j.push(Element::new("child").text(parent_name(sa.link)));
                    j.push(pose(&sa.pose));
                } else {
                    j.push(Element::new("child").text(parent_name(sb.link)));
                    j.push(pose(&sb.pose));
                }
                if !weld {
                    j.push(Element::new("axis").child(Element::new("xyz").text("0 0 1")));
                }
                m.push(j);
            }
        }
    }
    let mut world = Element::new("world").attr("name", name);
    world.push(Element::new("gravity").text(numbers(&[model.gravity.x, model.gravity.y, 0.0])));
    world.push(m);
    let mut root = Element::new("sdf").attr("version", "1.9");
    for c in comment {
        root.comment(c.clone());
    }
    root.push(world);
    (root.document(), warnings)
}
