//! MuJoCo's MJCF.

use super::model::{Attachment, Link, LinkMotion, ModelJoint, RigidModel};
use super::xml::{Element, number, numbers};
use crate::space::Pose;

/// The name of the world site that force actuators measure against
/// (`refsite`), so that their gear is in the world's frame: dead loads.
pub const WORLD_SITE: &str = "world_frame";
/// The name of the keyframe whose controls apply the file's loads.
pub const KEYFRAME: &str = "loads";

/// A closure's impedance: MuJoCo's largest, 0.9999, at every violation.
/// At rest a soft constraint is open by $(1-d)/(d\thinspace k)$ times the
/// acceleration it holds back, $k = 1/(d\thinspace t_c)^2$; MuJoCo's default
/// $d = 0.9$–$0.95$ with $t_c = 0.02$ s leaves the four-bar's pin 0.54 mm
/// open, this with $t_c = 2\Delta t$ about $10^{-7}$ m.
pub const CLOSURE_SOLIMP: &str = "0.9999 0.9999 0.001 0.5 2";

/// A closure's `solref`: time constant twice the step (the least MuJoCo
/// keeps stable), critically damped; MuJoCo's default 0.02 s when the step
/// is zero (unsized).
pub fn closure_solref(step: f64) -> String {
    let tc = if step > 0.0 { 2.0 * step } else { 0.02 };
    numbers(&[tc, 1.0])
}

/// A tendon through the sites named, `<spatial>`, and its motor, gear −1
/// (MuJoCo's tendon force is positive when it lengthens the tendon), whose
/// control is the tension (N).
pub fn tendon<'a>(name: &str, sites: impl Iterator<Item = &'a str>) -> (Element, Element) {
    let mut t = Element::new("spatial").attr("name", name);
    for s in sites {
        t.push(Element::new("site").attr("site", s));
    }
    let motor = Element::new("motor").attr("name", format!("tendon_{name}")).attr("tendon", name).attr("gear", "-1");
    (t, motor)
}

/// A hinge's `range` (its coordinate, about `ref`): where its spring stops
/// holding ([`super::step::soft_limits`]), ±π on a side where it never
/// does; `None` when it holds everywhere or is not a hinge.
pub fn hinge_range(j: &ModelJoint) -> Option<(f64, f64)> {
    if j.motion != LinkMotion::Hinge {
        return None;
    }
    let (lo, hi) = super::step::soft_limits(j.stiffness);
    if lo.is_none() && hi.is_none() {
        return None;
    }
    let pi = std::f64::consts::PI;
    Some((j.reference + lo.unwrap_or(-pi), j.reference + hi.unwrap_or(pi)))
}

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
///   snaps sites apart at rest together (a preload). Each is as stiff as
///   the step allows ([`closure_solref`], [`CLOSURE_SOLIMP`]): MuJoCo's
///   default (`solref` 0.02 s, impedance 0.9–0.95) leaves a loaded pin
///   open by a share of a millimetre at rest;
/// - a hinge whose fitted spring softens to nothing at some angle is
///   limited there (`range`, [`hinge_range`], as stiff as a closure): not
///   met at rest, it stops a hinge thrown past its spring's reach (a load
///   applied at once, undamped) from running away;
/// - `step` (s), when not zero, is `<option timestep>`: the step the
///   joints' armatures are sized for ([`super::step`]).
pub fn write(model: &RigidModel, name: &str, comment: &[String], step: f64) -> String {
    let mut root = Element::new("mujoco").attr("model", name);
    for c in comment {
        root.comment(c.clone());
    }
    root.push(Element::new("compiler").attr("angle", "radian").attr("autolimits", "true"));
    let mut option = Element::new("option");
    if step > 0.0 {
        option = option.attr("timestep", number(step));
    }
    root.push(option.attr("gravity", numbers(&[model.gravity.x, model.gravity.y, 0.0])));
    let solref = closure_solref(step);
    let children = model.children();
    let mut world = Element::new("worldbody");
    world.push(Element::new("site").attr("name", WORLD_SITE).attr("pos", "0 0 0").attr("size", "0.001"));
    sites(model, 0, &mut world);
    for &c in &children[0] {
        world.push(body(model, c, &children, step));
    }
    root.push(world);
    let mut tendons = Element::new("tendon");
    let mut equality = Element::new("equality");
    let mut actuators = Element::new("actuator");
    let mut ctrl = Vec::new();
    for a in &model.attachments {
        match a {
            Attachment::Tendon { name, sites, tension } => {
                let (t, motor) = tendon(name, sites.iter().map(|s| model.sites[*s].name.as_str()));
                tendons.push(t);
                actuators.push(motor);
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
                    .attr("site2", model.sites[*b].name.as_str())
                    .attr("solref", solref.as_str())
                    .attr("solimp", CLOSURE_SOLIMP),
            ),
            Attachment::Pin { name, a, b, .. } => equality.push(
                Element::new("connect")
                    .attr("name", name.as_str())
                    .attr("site1", model.sites[*a].name.as_str())
                    .attr("site2", model.sites[*b].name.as_str())
                    .attr("solref", solref.as_str())
                    .attr("solimp", CLOSURE_SOLIMP),
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

fn body(model: &RigidModel, i: usize, children: &[Vec<usize>], step: f64) -> Element {
    let l: &Link = &model.links[i];
    let mut b = placed(Element::new("body").attr("name", l.name.as_str()), &l.pose);
    // Several joints on a body (a massless flexure's merged chain) act in
    // order, each about its own `pos`.
    for j in &l.joints {
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
        if let Some((lo, hi)) = hinge_range(j) {
            // As stiff as a closure: MuJoCo's default limit (0.02 s) lets a
            // hinge thrown at it by a load applied at once run through.
            e = e
                .attr("range", numbers(&[lo, hi]))
                .attr("solreflimit", closure_solref(step))
                .attr("solimplimit", CLOSURE_SOLIMP);
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
        b.push(body(model, c, children, step));
    }
    b
}
