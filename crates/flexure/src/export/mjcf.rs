//! MuJoCo's MJCF.

use super::model::{Attachment, Link, LinkMotion, RigidModel};
use super::xml::{Element, number, numbers};
use crate::space::Pose;

/// The name of the world site that force actuators measure against
/// (`refsite`), so that their gear is in the world's frame: dead loads.
pub const WORLD_SITE: &str = "world_frame";
/// The name of the keyframe whose controls apply the file's loads.
pub const KEYFRAME: &str = "loads";

fn pos(p: &Pose) -> String {
    numbers(&[p.x, p.y, 0.0])
}

/// A planar rotation $\phi$ about z as MuJoCo's quaternion $(w, x, y, z)$.
fn quat(phi: f64) -> String {
    numbers(&[(phi / 2.0).cos(), 0.0, 0.0, (phi / 2.0).sin()])
}

fn placed(mut e: Element, p: &Pose) -> Element {
    e = e.attr("pos", pos(p));
    if p.phi != 0.0 { e.attr("quat", quat(p.phi)) } else { e }
}

/// The model as MJCF (MuJoCo 3.8 or later, for polynomial joint stiffness; checked with 4.0), site
/// constraints), with the fit summary `comment` at its top.
///
/// What is written where, for a MuJoCo user:
/// - links are nested `<body>`s (the ground is `<worldbody>`), each with
///   its `<inertial>` (planar: the rotary inertia $I$ on all three axes,
///   which keeps MuJoCo's triangle inequality; only $I_{zz}$ acts in the plane);
/// - a hinge is `type="hinge"` about z at its point, a slide along its
///   axis; `ref` and `springref` are the rest coordinate, and a spring
///   $\tau = -(k_1 x + k_2 x^2 + k_3 x^3)$, $x = q - q_{ref}$, is MuJoCo's
///   `stiffness="k1 k2 k3"` exactly (engine_passive.c: `-x * polyForce`);
/// - gravity is `<option gravity>`;
/// - a tendon is a `<spatial>` tendon through sites, pulled by a `<motor>`
///   of gear −1 whose control is its tension (N): MuJoCo's tendon force is
///   positive when it lengthens the tendon;
/// - a force is a `<motor>` on a site measured against the world
///   ([`WORLD_SITE`] as `refsite`), gear $(F_x, F_y, 0, 0, 0, M)$ (MuJoCo
///   puts the translation first) and control 1, so it keeps its direction
///   as the body turns;
/// - MJCF has no loads in the XML itself: the controls are in the keyframe
///   [`KEYFRAME`] (`mj_resetDataKeyframe(model, data, 0)` applies them;
///   each control is also the fraction of its load);
/// - a weld is `<weld site1 site2>`, a pin `<connect site1 site2>`; MuJoCo
///   snaps sites apart at rest together (a preload).
pub fn write(model: &RigidModel, name: &str, comment: &[String]) -> String {
    let mut root = Element::new("mujoco").attr("model", name);
    for c in comment {
        root.comment(c.clone());
    }
    root.push(Element::new("compiler").attr("angle", "radian").attr("autolimits", "true"));
    root.push(Element::new("option").attr("gravity", numbers(&[model.gravity.x, model.gravity.y, 0.0])));
    let children = model.children();
    let mut world = Element::new("worldbody");
    world.push(Element::new("site").attr("name", WORLD_SITE).attr("pos", "0 0 0").attr("size", "0.001"));
    sites(model, 0, &mut world);
    for &c in &children[0] {
        world.push(body(model, c, &children));
    }
    root.push(world);
    let mut tendons = Element::new("tendon");
    let mut equality = Element::new("equality");
    let mut actuators = Element::new("actuator");
    let mut ctrl = Vec::new();
    for a in &model.attachments {
        match a {
            Attachment::Tendon { name, sites, tension } => {
                let mut t = Element::new("spatial").attr("name", name.as_str());
                for s in sites {
                    t.push(Element::new("site").attr("site", model.sites[*s].name.as_str()));
                }
                tendons.push(t);
                actuators.push(
                    Element::new("motor")
                        .attr("name", format!("tendon_{name}"))
                        .attr("tendon", name.as_str())
                        .attr("gear", "-1"),
                );
                ctrl.push(*tension);
            }
            Attachment::Force { name, site, wrench } => {
                actuators.push(
                    Element::new("motor")
                        .attr("name", format!("force_{name}"))
                        .attr("site", model.sites[*site].name.as_str())
                        .attr("refsite", WORLD_SITE)
                        .attr("gear", numbers(&[wrench.fx, wrench.fy, 0.0, 0.0, 0.0, wrench.moment])),
                );
                ctrl.push(1.0);
            }
            Attachment::Weld { name, a, b, .. } => equality.push(
                Element::new("weld")
                    .attr("name", name.as_str())
                    .attr("site1", model.sites[*a].name.as_str())
                    .attr("site2", model.sites[*b].name.as_str()),
            ),
            Attachment::Pin { name, a, b, .. } => equality.push(
                Element::new("connect")
                    .attr("name", name.as_str())
                    .attr("site1", model.sites[*a].name.as_str())
                    .attr("site2", model.sites[*b].name.as_str()),
            ),
        }
    }
    for e in [tendons, equality, actuators] {
        if !e.children.is_empty() {
            root.push(e);
        }
    }
    if !ctrl.is_empty() {
        root.push(
            Element::new("keyframe").child(Element::new("key").attr("name", KEYFRAME).attr("ctrl", numbers(&ctrl))),
        );
    }
    root.document()
}

fn sites(model: &RigidModel, link: usize, e: &mut Element) {
    for s in model.sites.iter().filter(|s| s.link == link) {
        e.push(placed(Element::new("site").attr("name", s.name.as_str()), &s.pose).attr("size", "0.001"));
    }
}

fn body(model: &RigidModel, i: usize, children: &[Vec<usize>]) -> Element {
    let l: &Link = &model.links[i];
    let mut b = placed(Element::new("body").attr("name", l.name.as_str()), &l.pose);
    if let Some(j) = &l.joint {
        let mut e = Element::new("joint").attr("name", j.name.as_str());
        e = match j.motion {
            LinkMotion::Hinge => {
                e.attr("type", "hinge").attr("pos", numbers(&[j.at.x, j.at.y, 0.0])).attr("axis", "0 0 1")
            }
            LinkMotion::Slide => e.attr("type", "slide").attr("axis", numbers(&[j.axis.x, j.axis.y, 0.0])),
        };
        if j.reference != 0.0 {
            e = e.attr("ref", number(j.reference));
        }
        e = e.attr("springref", number(j.reference));
        let k = j.stiffness;
        e = if k[1] == 0.0 && k[2] == 0.0 {
            e.attr("stiffness", number(k[0]))
        } else {
            e.attr("stiffness", numbers(&k))
        };
        if j.damping > 0.0 {
            e = e.attr("damping", number(j.damping));
        }
        if j.armature > 0.0 {
            e = e.attr("armature", number(j.armature));
        }
        b.push(e);
    }
    let m = &l.inertia;
    if i != 0 {
        b.push(
            Element::new("inertial")
                .attr("pos", numbers(&[m.com[0], m.com[1], 0.0]))
                .attr("mass", number(m.mass))
                .attr("diaginertia", numbers(&[m.inertia, m.inertia, m.inertia])),
        );
    }
    sites(model, i, &mut b);
    for &c in &children[i] {
        b.push(body(model, c, children));
    }
    b
}
