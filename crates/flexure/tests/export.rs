//! The exporter: load ranges, tip wrenches, the rigid-body model against the
//! PRB chain's own kinematics, lumped masses against closed forms, and what
//! each format writes and warns of. The checks in a real simulator (MuJoCo)
//! are `python/tests/test_export.py`.

use flexure::export::model::{Chain, LinkMotion, RigidModel, build};
use flexure::export::{Format, LoadRange, Options, chain, export, fits, lump, wrench};
use flexure::mechanism::file::from_toml;
use flexure::mechanism::statics::Settings;
use flexure::prb::{self, PrbKind};
use flexure::space::Pose;
use nalgebra::Point2;

const FINGER: &str = include_str!("../../../examples/finger.toml");
const FOUR_BAR: &str = include_str!("../../../examples/four_bar.toml");

/// The rotation by `theta` about `p`: $(\theta, p - R(\theta)p)$.
fn about(p: Point2<f64>, theta: f64) -> Pose {
    let (s, c) = theta.sin_cos();
    Pose { phi: theta, x: p.x - (c * p.x - s * p.y), y: p.y - (s * p.x + c * p.y) }
}

/// Each link's world pose with its hinge at `theta[k]` (the k-th moving joint), by composing
/// the model's link poses: the forward kinematics any simulator does with the file's tree.
fn world(model: &RigidModel, theta: &[f64]) -> Vec<Pose> {
    let mut out: Vec<Pose> = Vec::with_capacity(model.links.len());
    let mut k = 0;
    for (i, l) in model.links.iter().enumerate() {
        if i == 0 {
            out.push(Pose::default());
            continue;
        }
        let mut p = out[l.parent].compose(&l.pose);
        for j in &l.joints {
            assert_eq!(j.motion, LinkMotion::Hinge);
            p = p.compose(&about(j.at, theta[k]));
            k += 1;
        }
        out.push(p);
    }
    out
}

#[test]
fn load_ranges_parse_and_refuse_by_name() {
    let r: LoadRange = "0.5:1:3".parse().unwrap();
    assert_eq!(r.fractions(), vec![0.5, 0.75, 1.0]);
    assert_eq!(LoadRange::default().fractions().len(), 12);
    for bad in ["0:1", "0:1:1", "0:1:65", "1:1:4", "a:1:4", "0:nan:4", "0:1e4:4"] {
        let e = bad.parse::<LoadRange>().unwrap_err().to_string();
        assert!(e.contains("range"), "{bad}: {e}");
    }
    let e = "xml".parse::<Format>().unwrap_err().to_string();
    assert!(e.contains("to") && e.contains("xml"), "{e}");
}

/// A single flexure turned by its origin, holding an arm with a force 30 mm
/// out: the tip wrench in the root frame is the force turned into it and
/// its moment about the tip, $M = r \times F$ (statics by hand), to 1e-9
/// relative (the least squares of a converged equilibrium).
#[test]
fn tip_wrenches_are_the_loads_the_bodies_pass_on() {
    let m = from_toml(
        "[[joint]]\nname = \"h\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"arm\"\norigin = [0.0, 0.0, 0.5]\nlength = 0.02\nei = 1e-3\n\
         [[force]]\nname = \"f\"\nbody = \"arm\"\nat = [0.03, 0.0]\nforce = [0.1, -0.2]\n",
    )
    .unwrap();
    let range = LoadRange { from: 0.0, to: 1.0, count: 3 };
    let sols = wrench::equilibria(&m, &range, &Settings::default()).unwrap();
    for (lambda, s) in range.fractions().iter().zip(&sols) {
        let w = wrench::tip_wrench(&m, 0, s).unwrap().unwrap();
        // The arm's frame in the ground: the root (turned 0.5) then the tip.
        let tip = flexure::pose_root_tip(m.joints[0].kind.flexure().unwrap(), &s.q);
        let arm_phi = 0.5 + tip.phi;
        let (fx, fy) = (0.1 * lambda, -0.2 * lambda);
        // Force in the root frame, and its moment about the tip point.
        let (sr, cr) = 0.5f64.sin_cos();
        let (rx, ry) = (cr * fx + sr * fy, -sr * fx + cr * fy);
        let (dx, dy) = (0.03 * arm_phi.cos(), 0.03 * arm_phi.sin());
        let moment = dx * fy - dy * fx;
        let scale = 1e-9 * 0.2;
        assert!((w.fx - rx).abs() < scale && (w.fy - ry).abs() < scale, "λ = {lambda}: {w:?}");
        assert!((w.moment - moment).abs() < scale * 0.03, "λ = {lambda}: {} against {moment}", w.moment);
    }
    assert!(!wrench::weighs_itself(&m, 0));
}

/// A flexure curved at rest, placed off the origin and turned, under a tip force.
const CURVED: &str = "[[joint]]\nname = \"h\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"arm\"\n\
    origin = [0.01, 0.02, 0.7]\nlength = 0.02\nei = 1e-3\norder = 4\nkappa = [0.3, -0.1, 0.05, 0.0]\n\
    [[force]]\nbody = \"arm\"\nat = [0.0, 0.0]\nforce = [0.0, -0.3]\n";

/// The model's links, with their hinges turned, put each flexure's child
/// where the PRB chain's own kinematics ([`prb::tip_pose`]) puts its tip,
/// for 1R and 3R and a rest-curved flexure, its links kept (SDFormat,
/// URDF) or merged on the child (MJCF, each hinge turning the body about
/// its own point as the ones before moved it, as MuJoCo does): to 1e-15 m
/// (rounding of composed poses).
#[test]
fn the_links_move_as_the_chain() {
    let f = flexure::Flexure::new(0.02, 1e-3, 4).unwrap().with_rest(&[0.3, -0.1, 0.05, 0.0]).unwrap();
    let m = from_toml(CURVED).unwrap();
    for kind in [PrbKind::OneR, PrbKind::ThreeR] {
        let fit = fits(&m, kind, &LoadRange::default(), &Settings::default()).unwrap().remove(0).unwrap();
        for merge in [false, true] {
            let model = build(&m, &[Some(chain(&fit, f.length()))], 0.0, merge).unwrap();
            let n = fit.joints.len();
            assert_eq!(model.joints().count(), n);
            assert_eq!(model.links.len(), if merge { 2 } else { n + 1 }, "{kind} merge {merge}");
            for theta in [vec![0.0; n], vec![0.4; n], (0..n).map(|i| -0.3 + 0.2 * i as f64).collect()] {
                let tip = prb::tip_pose(&fit, &f, &theta);
                let expected = m.joints[0].origin.compose(&tip);
                let got = world(&model, &theta)[model.body_link[1]];
                let d = (got.x - expected.x).hypot(got.y - expected.y);
                assert!(
                    d < 1e-15 && (got.phi - expected.phi).abs() < 1e-15,
                    "{kind} merge {merge} at {theta:?}: {got:?} against {expected:?}"
                );
            }
        }
    }
}

/// Reference: the fit's pivots ([`prb::PrbFit`]'s, in the flexure's root
/// frame). A massless flexure exported to MJCF is one body, the child,
/// carrying its hinges in order; each hinge sits at its pivot, carried into
/// the child's frame at rest: to 1e-15 m in the world. A flexure with mass
/// keeps its links (their own mass lumped), none at the floor.
#[test]
fn a_merged_bodys_joints_sit_at_the_pivots() {
    let m = from_toml(CURVED).unwrap();
    for kind in [PrbKind::OneR, PrbKind::ThreeR] {
        let fit = fits(&m, kind, &LoadRange::default(), &Settings::default()).unwrap().remove(0).unwrap();
        let e = export(&m, &Options { prb: kind, ..Default::default() }).unwrap();
        let model = e.model.as_ref().unwrap();
        assert_eq!(model.links.len(), 2, "{kind}: the ground and the arm");
        let arm = &model.links[model.body_link[1]];
        assert_eq!(arm.joints.len(), fit.joints.len());
        for (j, p) in arm.joints.iter().zip(&fit.joints) {
            let (got, want) = (arm.world.act(&j.at), m.joints[0].origin.act(&p.pivot));
            assert!((got - want).norm() < 1e-15, "{kind} {}: {got} against {want}", j.name);
        }
        // Written so, root first, each hinge at its point in the arm's frame.
        let first = &arm.joints[0];
        let at = flexure::export::xml::numbers(&[first.at.x, first.at.y, 0.0]);
        assert!(e.xml.contains(&format!(r#"<joint name="{}" type="hinge" pos="{at}""#, first.name)), "{}", e.xml);
        assert!(!e.xml.contains("_prb"), "{kind}: no pseudo-rigid body");
        // SDFormat keeps one joint a link: the links, at the least mass, said so.
        let sdf = export(&m, &Options { prb: kind, format: Format::Sdf, ..Default::default() }).unwrap();
        assert_eq!(sdf.model.as_ref().unwrap().links.len(), fit.joints.len() + 1);
    }
    let steel = from_toml(include_str!("../../../examples/finger_dynamics.toml")).unwrap();
    let e = export(&steel, &Options::default()).unwrap();
    let model = e.model.as_ref().unwrap();
    assert!(model.links.iter().any(|l| l.name.contains("_prb")) && model.links.iter().all(|l| !l.floored));
}

/// A uniform strip's pieces against the closed forms of a rod: mass
/// $\mu\ell$, centre at its middle, $I = \mu\ell^3/12 + \rho I\ell$ (with
/// $\rho I = \mu h^2/12$), to 1e-13 relative; and a taper's mass against
/// $\int\rho b h\thinspace ds$ of a linear thickness, exact for Gauss.
#[test]
fn lumped_pieces_are_the_rods_closed_forms() {
    use flexure::section::{Profile, Section};
    let (l, b, h, rho) = (0.02, 0.01, 2e-4, 7850.0);
    let s =
        Section::rectangle(2e11, None, Profile::Constant(b), Profile::Constant(h)).unwrap().with_density(rho).unwrap();
    let f = flexure::Flexure::new(l, 1.0, 3).unwrap().with_section(s).unwrap();
    let mu = rho * b * h;
    let (a, e) = (0.003, 0.017);
    let p = lump::segment(&f, a, e).unwrap().unwrap();
    let len = e - a;
    assert!((p.mass - mu * len).abs() < 1e-13 * p.mass);
    assert!((p.com[0] - 0.01).abs() < 1e-15 && p.com[1].abs() < 1e-18);
    let inertia = mu * len.powi(3) / 12.0 + mu * h * h / 12.0 * len;
    assert!((p.inertia - inertia).abs() < 1e-12 * inertia, "{} against {inertia}", p.inertia);
    let taper = Section::rectangle(2e11, None, Profile::Constant(b), Profile::Linear { root: 4e-4, tip: 2e-4 })
        .unwrap()
        .with_density(rho)
        .unwrap();
    let f = flexure::Flexure::new(l, 1.0, 3).unwrap().with_section(taper).unwrap();
    let whole = lump::segment(&f, 0.0, l).unwrap().unwrap();
    let exact = rho * b * l * (4e-4 + 2e-4) / 2.0;
    assert!((whole.mass - exact).abs() < 1e-13 * exact);
    // Cut anywhere, the pieces add back to the whole (mass, centre, inertia).
    let (p1, p2) = (lump::segment(&f, 0.0, 0.007).unwrap().unwrap(), lump::segment(&f, 0.007, l).unwrap().unwrap());
    let sum = lump::add(&p1, &p2);
    assert!((sum.mass - whole.mass).abs() < 1e-13 * whole.mass && (sum.com[0] - whole.com[0]).abs() < 1e-15);
    assert!((sum.inertia - whole.inertia).abs() < 1e-12 * whole.inertia);
}

/// The finger with steel flexures: the model's total mass and its centre
/// of mass at rest equal the file's bodies plus each whole flexure
/// ([`lump::segment`] over its length) but the piece of one on the ground
/// before its first pivot (the ground does not move), to 1e-12 relative;
/// links get the least mass only where they have none of their own.
#[test]
fn the_model_keeps_every_mass() {
    let m = from_toml(include_str!("../../../examples/finger_dynamics.toml")).unwrap();
    let e = export(&m, &Options { format: Format::Mjcf, prb: PrbKind::ThreeR, ..Default::default() }).unwrap();
    let (mut mass, mut moment) = (0.0, [0.0, 0.0]);
    for l in e.model.as_ref().unwrap().links.iter().skip(1) {
        let c = l.world.act(&Point2::new(l.inertia.com[0], l.inertia.com[1]));
        mass += l.inertia.mass;
        moment[0] += l.inertia.mass * c.x;
        moment[1] += l.inertia.mass * c.y;
    }
    let frames = flexure::mechanism::kinematics::frames(&m, &m.rest());
    let (mut m0, mut m1) = (0.0, [0.0, 0.0]);
    for (b, body) in m.bodies.iter().enumerate().skip(1) {
        let c = frames.bodies[b].act(&body.com);
        m0 += body.mass;
        m1[0] += body.mass * c.x;
        m1[1] += body.mass * c.y;
    }
    for (j, (_, fit)) in m.joints.iter().zip(&e.report.joints) {
        let f = j.kind.flexure().unwrap();
        let from = if j.parent == 0 { fit.gamma[0] * f.length() } else { 0.0 };
        let p = lump::segment(f, from, f.length()).unwrap().unwrap();
        let c = frames.bodies[j.parent].compose(&j.origin).act(&Point2::new(p.com[0], p.com[1]));
        m0 += p.mass;
        m1[0] += p.mass * c.x;
        m1[1] += p.mass * c.y;
    }
    assert!(e.model.as_ref().unwrap().links.iter().skip(1).all(|l| !l.floored), "every link of this finger has mass");
    assert!((mass - m0).abs() < 1e-12 * m0, "{mass} against {m0}");
    for i in 0..2 {
        assert!((moment[i] / mass - m1[i] / m0).abs() < 1e-12 * 0.05, "centre of mass {i}");
    }
}

#[test]
fn mjcf_writes_every_load_and_closure() {
    let m = from_toml(FOUR_BAR).unwrap();
    let e = export(&m, &Options { format: Format::Mjcf, name: "four_bar".into(), ..Default::default() }).unwrap();
    assert!(e.warnings.is_empty(), "MJCF holds all of the four-bar: {:?}", e.warnings);
    for part in [
        r#"<spatial name="pull">"#,
        r#"<motor name="tendon_pull" tendon="pull" gear="-1"/>"#,
        r#"refsite="world_frame" gear="0.3 0 0 0 0 0""#,
        r#"<option timestep="0.002" gravity="0 -9.81 0"/>"#,
        r#"<connect name="pin_0" site1="pin_0_a" site2="pin_0_b" solref="0.004 1" solimp="0.9999 0.9999 0.001 0.5 2"/>"#,
        r#"<key name="loads" ctrl="1.5 1"/>"#,
        r#"<body name="coupler""#,
    ] {
        assert!(e.xml.contains(part), "{part} missing from\n{}", e.xml);
    }
    // Three hinges per flexure; each stiffness is the fit's polynomial, as written.
    for (name, fit) in &e.report.joints {
        let k = fit.stiffness[0];
        let written = format!(r#"<joint name="{name}_1" type="hinge""#);
        assert!(e.xml.contains(&written), "{name}");
        let poly = flexure::export::xml::numbers(&k);
        assert!(e.xml.contains(&format!(r#"stiffness="{poly}""#)), "{name}: {poly}");
    }
}

/// URDF holds the tree only: every spring, the tendon, the force, gravity
/// and the pin are named in a warning, none dropped silently.
#[test]
fn urdf_and_sdf_name_what_they_cannot_hold() {
    let m = from_toml(FOUR_BAR).unwrap();
    let e = export(&m, &Options { format: Format::Urdf, prb: PrbKind::OneR, ..Default::default() }).unwrap();
    let has = |w: &[String], s: &str| w.iter().any(|x| x.contains(s));
    for s in [
        "\"input_hinge\"",
        "\"coupler_hinge\"",
        "\"output_hinge\"",
        "tendon \"pull\"",
        "force \"push\"",
        "gravity",
        "pin \"coupler\"–\"output\"",
    ] {
        assert!(has(&e.warnings, s), "URDF: no warning names {s}: {:?}", e.warnings);
    }
    assert!(e.xml.contains(r#"<link name="world"/>"#) && e.xml.contains(r#"type="continuous""#));
    assert_eq!(e.report.warnings, e.warnings);
    let e = export(&m, &Options { format: Format::Sdf, ..Default::default() }).unwrap();
    for s in ["tendon \"pull\"", "force \"push\"", "open at rest"] {
        assert!(has(&e.warnings, s), "SDF: no warning names {s}: {:?}", e.warnings);
    }
    assert!(e.xml.contains("<gravity>0 -9.81 0</gravity>") && e.xml.contains(r#"<sdf version="1.9">"#));
}

/// Revolute and prismatic joints keep their springs and rest values
/// (`ref`, `springref`), and a fixed joint's child is a body without a joint.
#[test]
fn rigid_joints_are_written_as_they_are() {
    let m = from_toml(
        "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"a\"\nstiffness = 2.0\nrest = 0.1\n\
         [[joint]]\nname = \"slide\"\nkind = \"prismatic\"\nparent = \"a\"\nchild = \"b\"\nstiffness = 50.0\nrest = 0.01\n\
         [[joint]]\nname = \"weld\"\nkind = \"fixed\"\nparent = \"b\"\nchild = \"c\"\norigin = [0.1, 0.0, 0.5]\n",
    )
    .unwrap();
    let e = export(&m, &Options { step: 0.0, ..Default::default() }).unwrap();
    assert!(
        e.xml.contains(
            r#"<joint name="pin" type="hinge" pos="0 0 0" axis="0 0 1" ref="0.1" springref="0.1" stiffness="2"/>"#
        ),
        "{}",
        e.xml
    );
    assert!(
        e.xml.contains(r#"<joint name="slide" type="slide" axis="1 0 0" ref="0.01" springref="0.01" stiffness="50"/>"#)
    );
    assert_eq!(e.model.as_ref().unwrap().links[3].joints, vec![]);
    assert!(e.report.joints.is_empty());
    // Massless bodies get the least mass simulators accept, and say so; with
    // no step, no armature.
    assert_eq!(e.report.notes.len(), 3, "{:?}", e.report.notes);
    assert!(e.report.armature.is_empty() && !e.xml.contains("timestep"));
    // Sized for MuJoCo's step, both sprung joints of these massless bodies
    // get an armature (one the hinge's inertia, one the slide's mass).
    let e = export(&m, &Options::default()).unwrap();
    let names: Vec<&str> = e.report.armature.iter().map(|(j, _)| j.as_str()).collect();
    assert_eq!(names, ["pin", "slide"]);
}

#[test]
fn generated_names_do_not_take_a_files() {
    let toml =
        format!("{FINGER}\n[[joint]]\nname = \"x\"\nkind = \"fixed\"\nparent = \"distal\"\nchild = \"mcp_prb1\"\n");
    let m = from_toml(&toml).unwrap();
    let e = export(&m, &Options { prb: PrbKind::ThreeR, ..Default::default() }).unwrap_err().to_string();
    assert!(e.contains("mcp_prb1"), "{e}");
    let bad = Chain { pivots: vec![Point2::origin()], stiffness: vec![], arcs: vec![0.0] };
    let m = from_toml(FINGER).unwrap();
    assert!(build(&m, &[Some(bad), None], 0.0, true).is_err());
    assert!(build(&m, &[None, None], 0.0, true).unwrap_err().to_string().contains("mcp"));
    let e = export(&m, &Options { armature: -1.0, ..Default::default() }).unwrap_err().to_string();
    assert!(e.contains("armature"), "{e}");
}

/// Reference: a hinge of stiffness k on a link of inertia I rings at
/// √(k/I), so a massless body (floored at 1e-14 kg·m²) rings far faster
/// than MuJoCo's 2 ms step. Sized for the step, every hinge of the massless
/// finger carries an armature, written in the MJCF and in the report: one
/// hinge on a body (1R), k₁(10Δt/2π)² less its body's own inertia about it
/// (a period of 10 steps, by hand), to 1e-12; several on one body (3R, the
/// chain merged), enough that the body's mass matrix over its hinges plus
/// the armature is at least D = diag(k₁)(10Δt/2π)², so no combination of
/// them rings faster than 10 steps: the least eigenvalue of
/// D^(-1/2)(M + A)D^(-1/2), M by hand from the body's mass, centre and
/// inertia, is 1 to 1e-12. For a step ten times shorter, a hundredth.
#[test]
fn light_links_get_the_armature_of_the_step() {
    let m = from_toml(FINGER).unwrap();
    for kind in [PrbKind::OneR, PrbKind::ThreeR] {
        for step in [0.002, 0.0002] {
            let e = export(&m, &Options { prb: kind, step, ..Default::default() }).unwrap();
            let model = e.model.as_ref().unwrap();
            let hinges: Vec<_> = model.joints().collect();
            assert_eq!(e.report.armature.len(), hinges.len(), "{kind} {step}");
            let period = 10.0 * step / std::f64::consts::TAU;
            for ((_, j), (name, a)) in hinges.iter().zip(&e.report.armature) {
                assert_eq!(name, &j.name);
                assert!(e.xml.contains(&format!("armature=\"{}\"", flexure::export::xml::number(*a))), "{name}");
            }
            for l in model.links.iter().filter(|l| !l.joints.is_empty()) {
                let i = &l.inertia;
                let arm = |j: &flexure::export::model::ModelJoint| [-(i.com[1] - j.at.y), i.com[0] - j.at.x];
                let n = l.joints.len();
                let d: Vec<f64> = l.joints.iter().map(|j| j.stiffness[0] * period * period).collect();
                let scaled = nalgebra::DMatrix::from_fn(n, n, |a, b| {
                    let (ja, jb) = (&l.joints[a], &l.joints[b]);
                    let (va, vb) = (arm(ja), arm(jb));
                    let own = i.inertia + i.mass * (va[0] * vb[0] + va[1] * vb[1]);
                    (own + if a == b { ja.armature } else { 0.0 }) / (d[a] * d[b]).sqrt()
                });
                let least = scaled.symmetric_eigenvalues().min();
                assert_eq!(n, if kind == PrbKind::OneR { 1 } else { 3 }, "{}", l.name);
                assert!((least - 1.0).abs() < 1e-12, "{kind} {step} {}: {least}", l.name);
            }
            assert!(e.xml.contains(&format!("timestep=\"{step}\"")), "{}", e.xml);
            assert!(e.report.notes.iter().any(|n| n.contains("armature")), "{:?}", e.report.notes);
        }
    }
    let e = export(&m, &Options { step: -1.0, ..Default::default() }).unwrap_err().to_string();
    assert!(e.contains("step"), "{e}");
    let e = export(&m, &Options { step: f64::NAN, ..Default::default() }).unwrap_err().to_string();
    assert!(e.contains("step"), "{e}");
}

/// Reference: the model's own shapes along the range (`solve` at each load
/// fraction). The paper's tendon joint turns to 90° under a pull that turns
/// with the link; the same wrench held dead from rest buckles the flexure
/// the other way. Fitted to the shapes the tendon holds, the 1R chain is
/// within 1 % of L of them (measured 0.38 %) but flagged, its angle off by
/// Howell's c_θ mismatch (0.50 rad at 90°, past 1°), and the 3R chain within
/// 1e-4 of L (measured 1.4e-5) and 1° (measured 6.6e-4 rad), where fitting
/// to the dead wrenches from rest gave 59 % of L and no 3R chain at all.
#[test]
fn a_tendon_joint_is_fitted_to_the_shapes_its_tendon_holds() {
    let m = from_toml(include_str!("../../../examples/paper_tendon.toml")).unwrap();
    let settings = Settings::default();
    for (kind, bound, flagged) in [(PrbKind::OneR, 1e-2, true), (PrbKind::ThreeR, 1e-4, false)] {
        let fit = fits(&m, kind, &LoadRange::default(), &settings).unwrap().remove(0).unwrap();
        assert!(fit.error.position < bound * 0.015, "{kind:?}: {:?}", fit.error);
        assert_eq!(fit.flagged, fit.error.angle > flexure::export::ANGLE_FLAG, "{kind:?}: {:?}", fit.error);
        assert_eq!(fit.flagged, flagged, "{kind:?}: {:?}", fit.error);
    }
}
