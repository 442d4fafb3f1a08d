//! `mechanism/statics/contact.rs`: equilibria with frictionless contact
//! against the exact elastica with contact unknowns
//! ([`flexure::reference::elastica::contact`], its own tests check it
//! against closed forms and the plain elastica), a unit strip (L = EI = 1)
//! clamped along x:
//!
//! - a tip moment presses the tip onto a floor (propped cantilever): the
//!   curvature stays smooth, so order 6 meets the reference to rounding;
//! - a tip force and moment move the contact from the tip into the span
//!   (the tip lifts); a tip force presses the span onto a circular post:
//!   an inner contact puts a kink in the shear, which the model's
//!   polynomials resolve algebraically, so order 8 meets the reference's
//!   contact force to 0.2 % and its place to 1e-3 L, and the reported error
//!   estimate covers the tip's true error;
//! - the planar floor problem written as a spatial file gives the planar answer.

use flexure::mechanism::contact::{Contact, ContactMode};
use flexure::mechanism::file::from_toml;
use flexure::mechanism::statics::{Settings, solve};
use flexure::reference::elastica::{self, contact::Obstacle};
use flexure::{Flexure, TipLoad};

fn strip(order: usize, geom: &str, load: &str) -> String {
    format!(
        "[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\norder = {order}\n\
         [[force]]\nbody = \"tip\"\nat = [0.0, 0.0]\n{load}\n[[geom]]\nname = \"floor\"\nbody = \"ground\"\n{geom}"
    )
}

#[test]
fn a_tip_moment_presses_the_tip_onto_a_floor() {
    let floor = "shape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n";
    let m = from_toml(&strip(6, floor, "moment = -0.1")).unwrap();
    let s = solve(&m, &Settings::default()).unwrap();
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let exact = elastica::contact(
        &f,
        &[Obstacle::half_plane([0.0, -0.01], [0.0, 1.0])],
        0.0,
        &[TipLoad { moment: -0.1, fx: 0.0, fy: 0.0 }],
        &Default::default(),
    )
    .unwrap();
    println!("{:#?}", s.contacts);
    println!("{:#?}", exact.contacts);
    assert_eq!(s.contacts.len(), 1);
    assert_eq!(s.contacts[0].state, ContactMode::Slip);
    let rel = (s.contacts[0].normal_force - exact.contacts[0].normal_force).abs() / exact.contacts[0].normal_force;
    assert!(rel < 1e-3, "{rel}");
}

/// The model at `order` and the exact elastica, each with its contacts:
/// (s, normal force, tip (x, y)) of the model's and of the reference's.
type Found = (Vec<(f64, f64)>, [f64; 2], flexure::report::SolveReport);

fn both(order: usize, geom: &str, load: &str, obstacle: Obstacle, tip: TipLoad) -> (Found, Vec<(f64, f64)>, [f64; 2]) {
    let m = from_toml(&strip(order, geom, load)).unwrap();
    let s = solve(&m, &Settings::default()).unwrap();
    let report = flexure::report::solve_report(&m, &s, &Default::default()).map_err(|f| f.error).unwrap();
    let model: Vec<(f64, f64)> = s.contacts.iter().map(|c| (c.s.unwrap(), c.normal_force)).collect();
    let end = flexure::pose_root_tip(m.joints[0].kind.flexure().unwrap(), &s.q);
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let exact = elastica::contact(&f, &[obstacle], 0.0, &[tip], &Default::default()).unwrap();
    assert!(exact.reached());
    let reference: Vec<(f64, f64)> = exact.contacts.iter().map(|c| (c.s, c.normal_force)).collect();
    let last = exact.shape.last().unwrap();
    ((model, [end.x, end.y], report), reference, [last.x, last.y])
}

/// One inner contact each, at order 8: its place to 1e-3 L and its force
/// to 0.2 %; the estimate's position error at least a third of the tip's
/// true distance from the reference's (an estimate, not a bound) and
/// within 1e-3 L; every gap along the shape closed or open to 1e-10 L.
fn inner_contact_matches(geom: &str, load: &str, obstacle: Obstacle, tip: TipLoad) {
    let ((model, end, report), exact, exact_end) = both(8, geom, load, obstacle, tip);
    assert!(model.len() == 1 && exact.len() == 1 && exact[0].0 < 1.0, "{model:?} vs {exact:?}");
    let (place, force) = ((model[0].0 - exact[0].0).abs(), (model[0].1 / exact[0].1 - 1.0).abs());
    assert!(place < 1e-3 && force < 2e-3, "place off by {place:e}, force by {force:e}");
    let true_error = (end[0] - exact_end[0]).hypot(end[1] - exact_end[1]);
    let estimate = report.error_estimate.get("strip").unwrap();
    assert!(estimate.position >= true_error / 3.0 && estimate.position < 1e-3, "{estimate:?} vs {true_error:e}");
    assert_eq!(report.contacts.map(|c| c.len()), Some(1));
}

#[test]
fn a_tip_force_and_moment_move_the_contact_into_the_span() {
    let floor = "shape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n";
    let obstacle = Obstacle::half_plane([0.0, -0.01], [0.0, 1.0]);
    inner_contact_matches(
        floor,
        "moment = 0.4\nforce = [0.0, -1.0]",
        obstacle,
        TipLoad { moment: 0.4, fx: 0.0, fy: -1.0 },
    );
}

#[test]
fn a_tip_force_presses_the_span_onto_a_post() {
    let post = "shape = \"circle\"\norigin = [0.55, -0.3]\nradius = 0.25\n";
    let obstacle = Obstacle::circle([0.55, -0.3], 0.25);
    inner_contact_matches(post, "force = [0.0, -3.0]", obstacle, TipLoad { moment: 0.0, fx: 0.0, fy: -3.0 });
}

/// The floor problem written in space: the strip along x bending about z,
/// the floor's normal along y, gives the planar contact to 1e-7 (relative
/// in force, of L in place): the two integrate the same curvature series
/// differently (Gauss quadrature of the angle in the plane, Magnus steps
/// in space), each to about 1e-8 here.
#[test]
fn a_spatial_file_of_the_planar_problem_gives_the_planar_answer() {
    let floor = "shape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n";
    let planar =
        solve(&from_toml(&strip(6, floor, "moment = 0.4\nforce = [0.0, -1.0]")).unwrap(), &Settings::default())
            .unwrap();
    let text = "dimension = 3\n[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\n\
                gj = 1.0\nei_y = 1.0\nei_z = 1.0\norders = [1, 1, 6]\n\
                [[force]]\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nmoment = [0.0, 0.0, 0.4]\nforce = [0.0, -1.0, 0.0]\n\
                [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01, 0.0]\nnormal = [0.0, 1.0, 0.0]\n";
    let spatial = solve(&flexure::mechanism::file::spatial_from_toml(text).unwrap(), &Settings::default()).unwrap();
    same_contact(&planar.contacts, &spatial.contacts, [0, 1, 2]);
}

/// The post problem bent out of the plane: the strip along x bending about
/// y, pushed down (−z) onto a sphere whose section is the planar post, gives
/// the planar answer to 1e-7 (see the test above); so does the strip
/// bending about z pushed (−y) onto a cylinder along z, a smaller post
/// (radius L/20, at 0.6 L) that the tip force 0.1 EI/L² reaches.
/// The bare centreline touches the cylinder's side, where its curvature
/// once read zero and the path was refused as lying along it.
#[test]
fn a_strip_pressed_onto_a_sphere_or_a_cylinder_is_the_planar_post() {
    let post = "shape = \"circle\"\norigin = [0.55, -0.3]\nradius = 0.25\n";
    let planar = solve(&from_toml(&strip(6, post, "force = [0.0, -3.0]")).unwrap(), &Settings::default()).unwrap();
    let text = "dimension = 3\n[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\n\
                gj = 1.0\nei_y = 1.0\nei_z = 1.0\norders = [1, 6, 1]\n\
                [[force]]\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nforce = [0.0, 0.0, -3.0]\n\
                [[geom]]\nname = \"ball\"\nbody = \"ground\"\nshape = \"sphere\"\norigin = [0.55, 0.0, -0.3]\nradius = 0.25\n";
    let spatial = solve(&flexure::mechanism::file::spatial_from_toml(text).unwrap(), &Settings::default()).unwrap();
    same_contact(&planar.contacts, &spatial.contacts, [0, 2, 1]);
    let post = "shape = \"circle\"\norigin = [0.6, -0.055]\nradius = 0.05\n";
    let planar = solve(&from_toml(&strip(8, post, "force = [0.0, -0.1]")).unwrap(), &Settings::default()).unwrap();
    let text = "dimension = 3\n[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\n\
                gj = 1.0\nei_y = 1.0\nei_z = 1.0\norders = [1, 1, 8]\n\
                [[force]]\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nforce = [0.0, -0.1, 0.0]\n\
                [[geom]]\nname = \"post\"\nbody = \"ground\"\nshape = \"cylinder\"\norigin = [0.6, -0.055, 0.0]\nradius = 0.05\nhalf_length = 0.1\n";
    let spatial = solve(&flexure::mechanism::file::spatial_from_toml(text).unwrap(), &Settings::default()).unwrap();
    same_contact(&planar.contacts, &spatial.contacts, [0, 1, 2]);
}

/// A geom touching a geom: an arm on a hinge of stiffness k = 2 N·m/rad
/// carries a circle of radius r = 0.01 at x = 0.1 on its frame, a floor
/// 0.02 below it; a moment M = −1 N·m turns the arm down onto it. In
/// contact the circle's centre is r above the floor: sin θ = −(0.02 − r)/0.1,
/// and the floor takes the rest of the moment, N = (kθ − M)/(0.1 cos θ)
/// (1e-12 relative).
#[test]
fn a_pad_on_an_arm_rests_on_a_floor() {
    let text = "[[joint]]\nname = \"hinge\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n\
                [[force]]\nbody = \"arm\"\nmoment = -1.0\n\
                [[geom]]\nname = \"pad\"\nbody = \"arm\"\nshape = \"circle\"\norigin = [0.1, 0.0]\nradius = 0.01\n\
                [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.02]\nnormal = [0.0, 1.0]\n";
    let s = solve(&from_toml(text).unwrap(), &Settings::default()).unwrap();
    let theta = (-0.01f64 / 0.1).asin();
    assert!((s.q[0] - theta).abs() < 1e-12, "{:?}", s.q);
    assert_eq!(s.contacts.len(), 1);
    let c = &s.contacts[0];
    let exact = (2.0 * theta + 1.0) / (0.1 * theta.cos());
    assert!((c.normal_force / exact - 1.0).abs() < 1e-12, "{c:?} vs {exact}");
    assert!(c.s.is_none() && c.geom == "floor" && c.body.as_deref() == Some("arm") && c.flexure.is_none(), "{c:?}");
}

/// One contact each, the same to 1e-7 (the two integrations' difference):
/// the planar point's x and y are the spatial point's components
/// `axes[0]` and `axes[1]`, and its component `axes[2]` is zero.
fn same_contact(planar: &[Contact], spatial: &[Contact], axes: [usize; 3]) {
    assert_eq!((planar.len(), spatial.len()), (1, 1));
    let (a, b) = (&planar[0], &spatial[0]);
    assert!((a.s.unwrap() - b.s.unwrap()).abs() < 1e-7, "{a:?} vs {b:?}");
    assert!((a.normal_force / b.normal_force - 1.0).abs() < 1e-7, "{a:?} vs {b:?}");
    assert!(
        (a.point[0] - b.point[axes[0]]).abs() < 1e-7 && (a.point[1] - b.point[axes[1]]).abs() < 1e-7,
        "{a:?} vs {b:?}"
    );
    assert!(b.point[axes[2]].abs() < 1e-12, "{b:?}");
}

/// A sweep of the tip moment follows the tip from free to pressed onto the
/// floor (linear theory: it touches at M = −2EIg/L² = −0.02), each value
/// from the last; without friction the answer does not depend on the path,
/// so each row is the solve at its value (1e-9), each row's estimate is
/// made under its own load (the refined model within 1e-12 m: a tip contact
/// keeps the curvature smooth), and the last is the exact elastica's (1e-9
/// relative).
#[test]
fn a_sweep_follows_the_tip_onto_the_floor() {
    use flexure::mechanism::sweep::{Parameter, sweep};
    let floor = "shape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n";
    let text = strip(6, floor, "moment = -0.1").replace("[[force]]\n", "[[force]]\nname = \"push\"\n");
    let m = from_toml(&text).unwrap();
    let values = [0.0, -0.01, -0.05, -0.1];
    let out = sweep(&m, &Parameter::parse(&m, "force.push.moment").unwrap(), &values, &Settings::default()).unwrap();
    assert!(out.stopped.is_none() && out.rows.len() == 4);
    let touching: Vec<usize> =
        out.rows.iter().map(|(_, s)| s.contacts.iter().filter(|c| c.normal_force > 0.0).count()).collect();
    assert_eq!(touching, [0, 0, 1, 1]);
    for (v, s) in &out.rows {
        let alone = solve(
            &from_toml(&text.replace("moment = -0.1", &format!("moment = {v:?}"))).unwrap(),
            &Settings::default(),
        )
        .unwrap();
        let force = |s: &flexure::mechanism::statics::Solution| s.contacts.iter().map(|c| c.normal_force).sum::<f64>();
        assert!((force(s) - force(&alone)).abs() < 1e-9 && (s.q[0] - alone.q[0]).abs() < 1e-9, "at {v}");
        // The estimate is made under the row's loads, not the file's: a tip
        // contact leaves the curvature smooth, so the refined model agrees.
        let report = flexure::report::solve_report(&m, s, &Default::default()).map_err(|f| f.error).unwrap();
        let e = report.error_estimate.get("strip").unwrap();
        assert!(!report.flagged && e.position < 1e-12, "at {v}: {e:?}");
    }
    let exact = elastica::contact(
        &Flexure::new(1.0, 1.0, 3).unwrap(),
        &[Obstacle::half_plane([0.0, -0.01], [0.0, 1.0])],
        0.0,
        &[TipLoad { moment: -0.1, fx: 0.0, fy: 0.0 }],
        &Default::default(),
    )
    .unwrap();
    let last = &out.rows[3].1.contacts[0];
    assert!((last.normal_force / exact.contacts[0].normal_force - 1.0).abs() < 1e-9, "{last:?}");
}

/// A flexure without thickness meeting a box's corner: the gap has a kink
/// there and no point of the flexure is tangent to the box, so the path
/// stops with an error naming the pair and what to do, not a panic or a
/// penetration.
#[test]
fn a_box_corner_against_a_bare_centreline_is_refused_by_name() {
    let corner = "shape = \"box\"\norigin = [0.55, -0.3]\nhalf_extents = [0.3, 0.2]\n";
    let e = solve(&from_toml(&strip(6, corner, "force = [0.0, -3.0]")).unwrap(), &Settings::default()).unwrap_err();
    let text = e.to_string();
    assert!(text.contains("geom \"floor\" (box) and flexure \"strip\"") && text.contains("round the edge"), "{text}");
}

/// The floor's friction along its tangent $t = (-n_y, n_x)$, as the reference reports it.
fn along_floor(c: &Contact) -> f64 {
    -c.normal[1] * c.friction_force[0] + c.normal[0] * c.friction_force[1]
}

/// Friction, case (c) of the reference: a clockwise tip moment presses the
/// tip onto a floor with $\mu = 0.2$; the stuck tip would need more
/// friction than that from the touch on, so it slides back toward the
/// root with friction $\mu N$ forward. Against the exact elastica with
/// contact unknowns ([`elastica::contact`]): the tip's curvature stays
/// smooth, so order 8 meets its N, T and place to 1e-8 (measured 7e-12).
#[test]
fn a_tip_pressed_by_a_moment_slides_on_a_rough_floor() {
    let floor = "shape = \"plane\"\norigin = [0.0, -0.1]\nnormal = [0.0, 1.0]\nfriction = 0.2\n";
    let m = from_toml(&strip(8, floor, "moment = -2.0")).unwrap();
    let s = solve(&m, &Settings::default()).unwrap();
    let exact = elastica::contact(
        &Flexure::new(1.0, 1.0, 3).unwrap(),
        &[Obstacle::half_plane([0.0, -0.1], [0.0, 1.0]).with_friction(0.2)],
        0.0,
        &[TipLoad { moment: -2.0, fx: 0.0, fy: 0.0 }],
        &Default::default(),
    )
    .unwrap();
    let (c, e) = (&s.contacts[0], &exact.contacts[0]);
    assert!(s.contacts.len() == 1 && c.state == ContactMode::Slip, "{:?}", s.contacts);
    assert!((c.normal_force / e.normal_force - 1.0).abs() < 1e-8, "{c:?} vs {e:?}");
    assert!((along_floor(c) / e.friction_force - 1.0).abs() < 1e-8, "{c:?} vs {e:?}");
    // Sliding back toward the root, held forward by friction.
    assert!((c.friction_force[0] - 0.2 * c.normal_force).abs() < 1e-12 * c.normal_force, "{c:?}");
    assert!((c.point[0] - e.point[0]).abs() < 1e-8, "{c:?} vs {e:?}");
}

/// Friction on a path, case (c) of the reference: a tip force presses the
/// tip onto a floor with $\mu = 0.3$, then a growing pull along the floor
/// (a sweep of the force's x from 0 to −0.6, each value followed from the
/// last): the tip sticks, then slips where $0.6t = \mu(1 - \lambda_t)$. Each
/// row against the exact elastica along the same path (legs: the press,
/// then the pull to the row's value): state, N, T and place to 1e-8 at order 8
/// (measured 5e-10 stuck, 1e-13 sliding).
/// A sweep back to no pull sticks the tip and then slides it back part of
/// the way, not to where the press left it: the answer remembers the path.
#[test]
fn a_sweep_sticks_then_slips_the_tip_along_a_rough_floor() {
    use flexure::mechanism::sweep::{Parameter, sweep};
    let floor = "shape = \"plane\"\norigin = [0.0, -0.2]\nnormal = [0.0, 1.0]\nfriction = 0.3\n";
    let text = strip(8, floor, "force = [0.0, -1.0]").replace("[[force]]\n", "[[force]]\nname = \"push\"\n");
    let m = from_toml(&text).unwrap();
    let values = [0.0, -0.05, -0.1, -0.2, -0.4, -0.6, -0.3, 0.0];
    let p = Parameter::parse(&m, "force.push.fx").unwrap();
    let out = sweep(&m, &p, &values, &Settings::default()).unwrap();
    assert!(out.stopped.is_none() && out.rows.len() == values.len());
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let rough = [Obstacle::half_plane([0.0, -0.2], [0.0, 1.0]).with_friction(0.3)];
    let press = TipLoad { moment: 0.0, fx: 0.0, fy: -1.0 };
    let mut path = vec![press];
    let mut states = Vec::new();
    for (k, (v, s)) in out.rows.iter().enumerate() {
        if k > 0 {
            path.push(TipLoad { fx: *v, ..press });
        }
        let exact = elastica::contact(&f, &rough, 0.0, &path, &Default::default()).unwrap();
        assert!(exact.reached());
        let (c, e) = (&s.contacts[0], &exact.contacts[0]);
        let state = match e.state {
            elastica::contact::ContactState::Stick => ContactMode::Stick,
            elastica::contact::ContactState::Slip | elastica::contact::ContactState::Closed => ContactMode::Slip,
        };
        assert_eq!(c.state, state, "at {v}: {c:?} vs {e:?}");
        assert!((c.normal_force - e.normal_force).abs() < 1e-8, "at {v}: {c:?} vs {e:?}");
        assert!((along_floor(c) - e.friction_force).abs() < 1e-8, "at {v}: {c:?} vs {e:?}");
        assert!((c.point[0] - e.point[0]).abs() < 1e-8, "at {v}: {c:?} vs {e:?}");
        // The estimate follows the refined mechanism along the same path:
        // the tip's curvature stays smooth, so it agrees to 1e-9 L.
        let report = flexure::report::solve_report(&m, s, &Default::default()).map_err(|f| f.error).unwrap();
        let estimate = report.error_estimate.get("strip").unwrap();
        assert!(!report.flagged && estimate.position < 1e-9, "at {v}: {estimate:?}");
        states.push(c.state);
    }
    assert!(states.contains(&ContactMode::Stick) && states.contains(&ContactMode::Slip), "{states:?}");
    let (start, end) = (&out.rows[0].1.contacts[0], &out.rows[values.len() - 1].1.contacts[0]);
    assert!(end.point[0] < start.point[0] - 1e-5, "the same load, another place: {start:?} vs {end:?}");
}

/// The rough-floor sweep written in space (the strip bending about z, the
/// pull along x) gives the planar rows: each row's state, and its N, its
/// friction and its place to 1e-7 (the two integrations differ by about
/// 1e-8, as without friction).
#[test]
fn a_spatial_file_of_the_rough_floor_sweep_gives_the_planar_rows() {
    use flexure::mechanism::sweep::{Parameter, sweep};
    let floor = "shape = \"plane\"\norigin = [0.0, -0.2]\nnormal = [0.0, 1.0]\nfriction = 0.3\n";
    let planar =
        from_toml(&strip(6, floor, "force = [0.0, -1.0]").replace("[[force]]\n", "[[force]]\nname = \"push\"\n"))
            .unwrap();
    let text = "dimension = 3\n[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\n\
                gj = 1.0\nei_y = 1.0\nei_z = 1.0\norders = [1, 1, 6]\n\
                [[force]]\nname = \"push\"\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nforce = [0.0, -1.0, 0.0]\n\
                [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.2, 0.0]\nnormal = [0.0, 1.0, 0.0]\nfriction = 0.3\n";
    let spatial = flexure::mechanism::file::spatial_from_toml(text).unwrap();
    let values = [0.0, -0.1, -0.4, -0.6, -0.3, 0.0];
    let settings = Settings::default();
    let a = sweep(&planar, &Parameter::parse(&planar, "force.push.fx").unwrap(), &values, &settings).unwrap();
    let b = sweep(&spatial, &Parameter::parse(&spatial, "force.push.fx").unwrap(), &values, &settings).unwrap();
    for ((v, p), (_, s)) in a.rows.iter().zip(&b.rows) {
        let (p, s) = (&p.contacts[0], &s.contacts[0]);
        assert_eq!(p.state, s.state, "at {v}: {p:?} vs {s:?}");
        assert!((p.normal_force - s.normal_force).abs() < 1e-7, "at {v}: {p:?} vs {s:?}");
        assert!((p.friction_force[0] - s.friction_force[0]).abs() < 1e-7, "at {v}: {p:?} vs {s:?}");
        assert!((p.point[0] - s.point[0]).abs() < 1e-7 && s.friction_force[2].abs() < 1e-12, "at {v}: {p:?} vs {s:?}");
    }
}

/// The tip frame's compliance with its contact held, against central
/// differences (δ = 1e-5) of the exact elastica with contact unknowns:
/// frictionless, the tip pressed onto a floor by a moment slides along it
/// ($\partial\phi/\partial M$, $\partial\phi/\partial F_x$, $\partial x/\partial F_x$), and the floor holds its height
/// ($C_{yy} = 0$); stuck by friction after a press, it only turns. Order 8,
/// to 1e-6 relative to the largest entry (measured 8e-8). A spatial file of
/// the frictionless case gives the same entries to 1e-7.
#[test]
fn the_compliance_holds_the_contacts_as_they_are() {
    use flexure::mechanism::statics::compliance;
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let tip = |obstacle: Obstacle, path: &[TipLoad]| {
        let s = elastica::contact(&f, &[obstacle], 0.0, path, &Default::default()).unwrap();
        assert!(s.reached());
        *s.shape.last().unwrap()
    };
    let h = 1e-5;
    // The path on to the nudged load (friction remembers where it touched).
    let nudged = |path: &[TipLoad], k: usize, by: f64| {
        let mut p = path.to_vec();
        p.push(*path.last().unwrap());
        let last = p.last_mut().unwrap();
        match k {
            0 => last.moment += by,
            1 => last.fx += by,
            _ => last.fy += by,
        }
        p
    };
    let cases = [
        (
            "shape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n",
            "moment = -0.1",
            0.0,
            vec![TipLoad { moment: -0.1, fx: 0.0, fy: 0.0 }],
        ),
        (
            "shape = \"plane\"\norigin = [0.0, -0.2]\nnormal = [0.0, 1.0]\nfriction = 0.3\n",
            "force = [0.0, -1.0]",
            0.3,
            vec![TipLoad { moment: 0.0, fx: 0.0, fy: -1.0 }],
        ),
    ];
    for (geom, load, mu, path) in cases {
        let m = from_toml(&strip(8, geom, load)).unwrap();
        let s = solve(&m, &Settings::default()).unwrap();
        let c = compliance(&m, &s, m.body("tip").unwrap(), [0.0, 0.0].into()).unwrap();
        let floor = match geom.contains("-0.2") {
            true => Obstacle::half_plane([0.0, -0.2], [0.0, 1.0]).with_friction(mu),
            false => Obstacle::half_plane([0.0, -0.01], [0.0, 1.0]),
        };
        let largest = c.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for k in 0..3 {
            let (up, down) = (tip(floor, &nudged(&path, k, h)), tip(floor, &nudged(&path, k, -h)));
            let exact = [(up.phi - down.phi) / (2.0 * h), (up.x - down.x) / (2.0 * h), (up.y - down.y) / (2.0 * h)];
            for (r, e) in exact.iter().enumerate() {
                assert!((c[(r, k)] - e).abs() < 1e-6 * largest, "{load}: C[{r}][{k}] = {:e}, exact {e:e}", c[(r, k)]);
            }
        }
        assert!(c[(2, 2)].abs() < 1e-12 * largest && largest > 0.1, "{load}: the floor holds the tip's height: {c}");
        if mu == 0.0 {
            let text = "dimension = 3\n[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\n\
                        gj = 1.0\nei_y = 1.0\nei_z = 1.0\norders = [1, 1, 8]\n\
                        [[force]]\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nmoment = [0.0, 0.0, -0.1]\n\
                        [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01, 0.0]\nnormal = [0.0, 1.0, 0.0]\n";
            let m = flexure::mechanism::file::spatial_from_toml(text).unwrap();
            let s = solve(&m, &Settings::default()).unwrap();
            let d = compliance(&m, &s, m.body("tip").unwrap(), [0.0, 0.0, 0.0].into()).unwrap();
            // (M, Fx, Fy) of the plane are (m_z, f_x, f_y) of space: rows and columns 2, 3, 4.
            for (a, b) in [(0, 2), (1, 3), (2, 4)] {
                for (k, l) in [(0, 2), (1, 3), (2, 4)] {
                    assert!((c[(a, k)] - d[(b, l)]).abs() < 1e-7 * largest, "C[{a}][{k}] {c} vs {d}");
                }
            }
        }
    }
}

/// Modes about a touching equilibrium hold the contact closed: a strip
/// (EI = ρA = L = 1) whose tip a small moment rests on a frictionless floor
/// vibrates as the clamped–pinned beam, $\omega_k = (\beta_kL)^2$ with
/// $\tan\beta L = \tanh\beta L$ (3.9266023, 7.0685827): the floor holds the
/// tip's height, and the press is too light to stiffen it (its force is
/// across the strip). Order 8, the first two to 1e-5 (measured 3e-7).
#[test]
fn modes_about_a_touching_tip_are_the_clamped_pinned_beams() {
    let floor = "shape = \"plane\"\norigin = [0.0, -0.0001]\nnormal = [0.0, 1.0]\n";
    let text = strip(8, floor, "moment = -0.001").replace("order = 8\n", "order = 8\nmass_per_length = 1.0\n");
    let model = flexure::model::Model::from_toml(&text).unwrap();
    let eigen = model.modes(2, &Default::default()).unwrap();
    for (w, beta) in eigen.answer.omega.iter().zip([3.926602312f64, 7.068582745]) {
        assert!((w / (beta * beta) - 1.0).abs() < 1e-5, "{w} vs {}", beta * beta);
    }
}

/// A tip pressed onto a rough floor and pulled across it, along and off
/// the strip's plane at once, slides (no reference: properties of Coulomb
/// sliding): its friction is μN (1e-12 relative), in the floor's plane
/// (1e-12 of it), and against the way the tip went over the last hundredth
/// of the load (the same path, solved to 0.99 of the load), within 0.02
/// rad: each step's friction follows the way the tip moved in the step
/// before, and a step turns it by at most 0.01 rad.
#[test]
fn a_tip_pulled_across_a_rough_floor_slides_against_its_motion() {
    let text = "dimension = 3\n[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\n\
                gj = 1.0\nei_y = 1.0\nei_z = 1.0\norders = [4, 4, 4]\n\
                [[force]]\nbody = \"tip\"\nat = [0.0, 0.0, 0.0]\nforce = [-0.5, -1.0, 0.5]\n\
                [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.2, 0.0]\nnormal = [0.0, 1.0, 0.0]\nfriction = 0.3\n";
    let m = flexure::mechanism::file::spatial_from_toml(text).unwrap();
    let s = solve(&m, &Settings::default()).unwrap();
    let c = &s.contacts[0];
    assert_eq!(c.state, ContactMode::Slip, "{c:?}");
    let t = &c.friction_force;
    let size = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
    assert!((size - 0.3 * c.normal_force).abs() < 1e-12 * c.normal_force && t[1].abs() < 1e-12 * size, "{c:?}");
    let before =
        flexure::mechanism::file::spatial_from_toml(&text.replace("[-0.5, -1.0, 0.5]", "[-0.495, -0.99, 0.495]"))
            .unwrap();
    let b = solve(&before, &Settings::default()).unwrap();
    let (p, q) = (&b.contacts[0].point, &c.point);
    let moved = nalgebra::Vector3::new(q[0] - p[0], q[1] - p[1], q[2] - p[2]).normalize();
    let along = nalgebra::Vector3::new(t[0], t[1], t[2]) / size;
    assert!(along.dot(&moved) < -(0.02f64).cos(), "friction {along:?} vs moved {moved:?}");
}

/// A steel blade (0.3 m, 10 × 0.2 mm, order 8) sagging under its own
/// weight onto a floor 10 mm below its root: its tip lands, and as gravity
/// grows the tip's slope falls to zero and the blade begins to lie along
/// the floor. That is refused by name (distributed contact), at the load
/// where it begins, not reported as a buckling. Reference: the propped
/// cantilever under a uniform load $w$ in linear theory, whose tip slope
/// vanishes at $w = 72EI\delta/L^4$ (the tip force $wL/3$): g = 7.549 m/s²
/// here; the sag (3 % of the length) moves it, so 2 % (measured 0.9 %).
/// Before, the path "lost stability (a buckling or limit load)" there.
#[test]
fn a_blade_sagging_onto_a_floor_is_refused_where_it_begins_to_lie_along_it() {
    let text = "gravity = [0.0, -9.81]\n[[joint]]\nname = \"blade\"\nkind = \"flexure\"\nparent = \"ground\"\n\
                child = \"tip\"\nlength = 0.3\nmodulus = 200e9\nwidth = 0.01\nthickness = 0.0002\ndensity = 7850\n\
                order = 8\n[[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01]\n\
                normal = [0.0, 1.0]\n";
    let m = from_toml(text).unwrap();
    let e = solve(&m, &Settings::default()).unwrap_err().to_string();
    assert!(e.contains("geom \"floor\" (plane) and flexure \"blade\"") && e.contains("lies along the geom"), "{e}");
    let percent: f64 = e.split("(at ").nth(1).and_then(|r| r.split(" %").next()).unwrap().parse().unwrap();
    let ei = 200e9 * 0.01 * 0.0002f64.powi(3) / 12.0;
    let w_per_g = 7850.0 * 0.01 * 0.0002;
    let g_flat = 72.0 * ei * 0.01 / 0.3f64.powi(4) / w_per_g;
    let g = percent / 100.0 * 9.81;
    assert!((g / g_flat - 1.0).abs() < 0.02, "lies along at g = {g}, linear theory {g_flat}");
}

/// A free-clamped column (L = EI = 1, order 8) pushed along its axis, a
/// wall 0.5 beside it that it never reaches: a sweep of the push from 0 to
/// −3 N loses stability at Euler's load π²/4 (to 1e-5 relative; the order's
/// own error is 1e-6), the same as the sweep without the wall (to 1e-6, the
/// precision to which that sweep refines its limit; measured 1.1e-8), and
/// keeps the rows before it, leaving out the two past it. Before, a sweep
/// with contact stopped there with an error instead.
#[test]
fn a_sweep_with_contact_finds_eulers_load_as_one_without() {
    use flexure::mechanism::sweep::{Parameter, sweep};
    let column = "[[joint]]\nname = \"column\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\n\
                  length = 1.0\nei = 1.0\norder = 8\n[[force]]\nname = \"push\"\nbody = \"tip\"\nforce = [-1.0, 0.0]\n";
    let wall =
        "[[geom]]\nname = \"wall\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, 0.5]\nnormal = [0.0, -1.0]\n";
    let values: Vec<f64> = (0..7).map(|k| -0.5 * k as f64).collect();
    let limits: Vec<f64> = [column.to_string(), format!("{column}{wall}")]
        .iter()
        .map(|text| {
            let m = from_toml(text).unwrap();
            let p = Parameter::parse(&m, "force.push.fx").unwrap();
            let out = sweep(&m, &p, &values, &Settings::default()).unwrap();
            assert!(out.stopped.is_none(), "{:?}", out.stopped);
            assert_eq!(out.rows.len(), 5, "the rows to −2 N");
            out.stability_limit.expect("Euler's load").value
        })
        .collect();
    let euler = std::f64::consts::PI.powi(2) / 4.0;
    assert!((limits[1] + euler).abs() < 1e-5 * euler, "{limits:?}");
    assert!((limits[1] - limits[0]).abs() < 1e-6 * euler, "{limits:?}");
}

/// A box resting on a floor at no load, on sliders with no stiffness: the
/// contacts that meet at the start touch, so the floor carries its weight.
/// A 1 kg box (20 mm wide, on free x and y sliders) under gravity: its two
/// bottom corners carry mg = 9.81 N together (1e-9 relative), and on a
/// floor of μ = 0.5 a 2 N push along x, below μmg = 4.905 N, is held by
/// friction (its sum −2 N, 1e-9) with the box where it rests (1e-12 m).
/// In space, its four corners carry mg. Without friction nothing holds x:
/// refused, naming the joint, where it read as a buckling at 0 % of the load.
#[test]
fn a_box_resting_on_a_floor_on_free_sliders_carries_its_weight() {
    let planar = |friction: f64, push: f64| {
        format!(
            "gravity = [0.0, -9.81]\n[[joint]]\nname = \"sx\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"cart\"\n\
             [[joint]]\nname = \"sy\"\nkind = \"prismatic\"\nparent = \"cart\"\nchild = \"box\"\norigin = [0.0, 0.005, 1.5707963267948966]\n\
             [[body]]\nname = \"box\"\nmass = 1.0\ninertia = 1e-5\n\
             [[force]]\nname = \"push\"\nbody = \"box\"\nforce = [{push}, 0.0]\n\
             [[geom]]\nname = \"block\"\nbody = \"box\"\nshape = \"box\"\nangle = -1.5707963267948966\nhalf_extents = [0.01, 0.005]\n\
             [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\nnormal = [0.0, 1.0]\nfriction = {friction}\n"
        )
    };
    let sum = |contacts: &[Contact], axis: usize| -> (f64, f64) {
        let n = contacts.iter().map(|c| c.normal_force).sum();
        (n, contacts.iter().map(|c| c.friction_force[axis]).sum())
    };
    let s = solve(&from_toml(&planar(0.5, 2.0)).unwrap(), &Settings::default()).unwrap();
    assert!(s.q.iter().all(|q| q.abs() < 1e-12), "{:?}", s.q);
    assert_eq!(s.contacts.len(), 2);
    assert!(s.contacts.iter().all(|c| c.state == ContactMode::Stick && c.gap.abs() < 1e-12), "{:?}", s.contacts);
    let (n, f) = sum(&s.contacts, 0);
    assert!((n / 9.81 - 1.0).abs() < 1e-9 && (f + 2.0).abs() < 1e-9, "N = {n}, friction {f}");
    let e = solve(&from_toml(&planar(0.0, 0.0)).unwrap(), &Settings::default()).unwrap_err().to_string();
    assert!(e.contains("moves freely at no load (joint \"sx\")"), "{e}");
    let spatial = "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n\
                   [[joint]]\nname = \"sx\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"cart\"\n\
                   [[joint]]\nname = \"sz\"\nkind = \"prismatic\"\nparent = \"cart\"\nchild = \"box\"\norigin = [0.0, 0.0, 0.005]\naxis = [0.0, 0.0, 1.0]\n\
                   [[body]]\nname = \"box\"\nmass = 1.0\nixx = 1e-5\niyy = 1e-5\nizz = 1e-5\n\
                   [[geom]]\nname = \"block\"\nbody = \"box\"\nshape = \"box\"\nhalf_extents = [0.01, 0.01, 0.005]\n\
                   [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\nnormal = [0.0, 0.0, 1.0]\nfriction = 0.5\n";
    let s = solve(&flexure::mechanism::file::spatial_from_toml(spatial).unwrap(), &Settings::default()).unwrap();
    assert!(s.q.iter().all(|q| q.abs() < 1e-12) && s.contacts.len() == 4, "{:?} {:?}", s.q, s.contacts);
    let (n, _) = sum(&s.contacts, 0);
    assert!((n / 9.81 - 1.0).abs() < 1e-9, "N = {n}");
}

/// Pairs that only meet at no load touch there only where the mechanism
/// needs them to rest on: a stable mechanism keeps its path as without
/// them. Three such, each lifted off by its load, touch nothing: a bare
/// strip lying on a floor along its length (the floor through its
/// centreline), a strip whose root sits on a base block's face, and a
/// sprung box set on a floor. Each answer lists no contact, and the strip's
/// tip rises by FL³/3EI (to 1e-6 of it; a 1e-3 N tip force on L = 0.1 m,
/// EI = 0.01 N·m²: 0.0333 mm) as without the floor.
#[test]
fn pairs_that_only_meet_at_no_load_touch_only_where_something_rests_on_them() {
    let strip = |geom: &str| {
        format!(
            "[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.1\nei = 0.01\norder = 4\n\
             [[force]]\nbody = \"tip\"\nforce = [0.0, 1e-3]\n[[geom]]\nname = \"base\"\nbody = \"ground\"\n{geom}"
        )
    };
    let floor = "shape = \"plane\"\norigin = [0.0, 0.0]\nnormal = [0.0, 1.0]\n";
    let block = "shape = \"box\"\norigin = [-0.01, 0.0]\nhalf_extents = [0.01, 0.01]\n";
    let rise = 1e-3 * 0.1f64.powi(3) / (3.0 * 0.01);
    for geom in [floor, block] {
        let m = from_toml(&strip(geom)).unwrap();
        let s = solve(&m, &Settings::default()).unwrap();
        assert!(s.contacts.is_empty(), "{geom}: {:?}", s.contacts);
        let tip = flexure::mechanism::kinematics::frames(&m, &s.q).bodies[1];
        assert!((tip.y / rise - 1.0).abs() < 1e-6, "{geom}: tip at {}", tip.y);
    }
    let sprung = "gravity = [0.0, -9.81]\n\
                  [[joint]]\nname = \"sy\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"box\"\norigin = [0.0, 0.005, 1.5707963267948966]\nstiffness = 100.0\n\
                  [[body]]\nname = \"box\"\nmass = 1.0\ninertia = 1e-5\n\
                  [[force]]\nbody = \"box\"\nforce = [0.0, 20.0]\n\
                  [[geom]]\nname = \"block\"\nbody = \"box\"\nshape = \"box\"\nangle = -1.5707963267948966\nhalf_extents = [0.01, 0.005]\n\
                  [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\nnormal = [0.0, 1.0]\n";
    let s = solve(&from_toml(sprung).unwrap(), &Settings::default()).unwrap();
    assert!(s.contacts.is_empty(), "{:?}", s.contacts);
    assert!((s.q[0] - (20.0 - 9.81) / 100.0).abs() < 1e-12, "{:?}", s.q);
}

/// A ball 1 cm in radius on free x and y sliders, set on a rough incline
/// of θ = 0.3 rad (`spatial`: the same in a spatial file), of `mass` (kg),
/// its friction `mu`.
fn ball_on_incline(spatial: bool, mass: f64, mu: f64) -> String {
    let (s, c) = 0.3_f64.sin_cos();
    let (r, up) = (0.01, if spatial { "axis = [0.0, 1.0, 0.0]" } else { "origin = [0.0, 0.0, 1.5707963267948966]" });
    let (head, zero, ball) = match spatial {
        true => ("dimension = 3\ngravity = [0.0, -9.81, 0.0]", ", 0.0", "sphere"),
        false => ("gravity = [0.0, -9.81]", "", "circle"),
    };
    format!(
        "{head}\n[[joint]]\nname = \"sx\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"carriage\"\norigin = [{}, {}, 0.0]\n\
         [[joint]]\nname = \"sy\"\nkind = \"prismatic\"\nparent = \"carriage\"\nchild = \"ball\"\n{up}\n\
         [[body]]\nname = \"ball\"\nmass = {mass}\n\
         [[geom]]\nname = \"shot\"\nbody = \"ball\"\nshape = \"{ball}\"\nradius = {r}\n\
         [[geom]]\nname = \"incline\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, 0.0{zero}]\nnormal = [{}, {c}{zero}]\nfriction = {mu}\n",
        -r * s,
        r * c,
        -s
    )
}

/// Coulomb's incline: the ball of [`ball_on_incline`] holds where
/// $\mu \ge \tan\theta$ = 0.3093362, stuck with $N = mg\cos\theta$ and a friction
/// of $mg\sin\theta$ (each to $10^{-9}$ of $mg$), and at $\mu$ 1e-5 below it
/// there is no equilibrium: it slips at no load and slides away, friction's
/// limit. So for 1 g, 100 g and 10 kg, in the plane and in space. The
/// event tolerances took their force unit from the stiffest joint, and a
/// mechanism with none from a stand-in of 1 N·m: a 1 g ball at μ = 0.21
/// was answered stuck with a friction 47 % over μN (an audit's case).
#[test]
fn a_ball_on_a_rough_incline_holds_where_coulomb_says_whatever_its_mass() {
    let (s, c, tan) = (0.3_f64.sin(), 0.3_f64.cos(), 0.3_f64.tan());
    for spatial in [false, true] {
        for mass in [1e-3, 0.1, 10.0] {
            for (mu, holds) in [(tan + 1e-5, true), (tan - 1e-5, false)] {
                let text = ball_on_incline(spatial, mass, mu);
                let contacts = match spatial {
                    true => solve(&flexure::mechanism::file::spatial_from_toml(&text).unwrap(), &Settings::default())
                        .map(|s| s.contacts),
                    false => solve(&from_toml(&text).unwrap(), &Settings::default()).map(|s| s.contacts),
                };
                let case = format!("spatial {spatial}, {mass} kg, μ {mu}");
                match (holds, contacts) {
                    (true, Ok(contacts)) => {
                        let [touch] = &contacts[..] else { panic!("{case}: {contacts:?}") };
                        let friction = touch.friction_force.iter().map(|f| f * f).sum::<f64>().sqrt();
                        let weight = mass * 9.81;
                        assert_eq!(touch.state, ContactMode::Stick, "{case}");
                        assert!((touch.normal_force - weight * c).abs() < 1e-9 * weight, "{case}: {touch:?}");
                        assert!((friction - weight * s).abs() < 1e-9 * weight, "{case}: {touch:?}");
                    }
                    (false, Err(e)) => assert!(e.to_string().contains("friction's limit"), "{case}: {e}"),
                    (_, answer) => panic!("{case}: {answer:?}"),
                }
            }
        }
    }
}
