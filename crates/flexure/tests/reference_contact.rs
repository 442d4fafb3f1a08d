//! The exact elastica with contact (`reference::elastica::contact`) against
//! closed forms, the plain elastica, and its own balance laws.

use flexure::reference::elastica::{self, contact::*};
use flexure::section::{Profile, Section};
use flexure::{Error, Flexure, TipLoad};

fn unit() -> Flexure {
    Flexure::new(1.0, 1.0, 3).unwrap()
}

fn load(moment: f64, fx: f64, fy: f64) -> TipLoad {
    TipLoad { moment, fx, fy }
}

fn scaled(l: &TipLoad, t: f64) -> TipLoad {
    load(t * l.moment, t * l.fx, t * l.fy)
}

fn solve(obstacles: &[Obstacle], h: f64, path: &[TipLoad]) -> ContactSolution {
    let s = elastica::contact(&unit(), obstacles, h, path, &Default::default()).unwrap();
    assert!(s.reached(), "{:?}", s.stop);
    s
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The free body of every tail: the bending moment at each shape point
/// against the moment of the tip load and the contact forces beyond it,
/// $m(s) = M + (p_L - p)\times F + \sum_{s_c > s}(p_c - p)\times f_c$.
/// Returns the largest mismatch (N·m).
fn tail_balance(s: &ContactSolution, tip: &TipLoad) -> f64 {
    let end = s.shape.last().unwrap();
    let mut worst: f64 = 0.0;
    for p in &s.shape {
        let mut m = tip.moment + cross([end.x - p.x, end.y - p.y], [tip.fx, tip.fy]);
        for c in s.contacts.iter().filter(|c| c.s > p.s) {
            m += cross([c.point[0] - p.x, c.point[1] - p.y], c.force());
        }
        worst = worst.max((m - p.moment).abs());
    }
    worst
}

/// Small deflection, case (a): a tip moment $M$ presses the tip onto a
/// floor at gap $g$ (a half thickness included). Propped cantilever: contact
/// when $ML^2/2EI = g$, then $N = 3M/2L - 3EIg/L^3$ from $\delta_M - \delta_N = g$.
/// Deflections of $10^{-3}L$: geometric terms of relative order $10^{-6}$;
/// tolerance $10^{-3}$ relative.
#[test]
fn propped_cantilever_matches_the_closed_form() {
    let (g, h, m) = (1e-3, 5e-4, 0.01);
    let floor = [Obstacle::half_plane([0.3, -(g + h)], [0.0, 3.0])];
    let s = solve(&floor, h, &[load(-m, 0.0, 0.0)]);
    let touch = s.events[0];
    assert_eq!((s.events.len(), touch.kind, touch.s), (1, EventKind::Touch, 1.0));
    let expected = 2.0 * g / m;
    assert!((touch.load - expected).abs() < 1e-3 * expected, "touch at {} vs {expected}", touch.load);
    let c = s.contacts[0];
    let n = 1.5 * m - 3.0 * g;
    assert!((c.normal_force - n).abs() < 1e-3 * n, "N = {} vs {n}", c.normal_force);
    assert!(c.friction_force.abs() < 1e-15 && c.gap.abs() < 1e-14, "{c:?}");
    assert_eq!(c.state, ContactState::Closed);
}

/// With obstacles out of the way the answer is `elastica::deflect`'s, to
/// 1e-10 (both integrate to 1e-12): Bisshopp–Drucker's flexure under a
/// moment and both force components, a floor far below and a post far off;
/// then a flexure with rest curvature and a section table with a kink.
#[test]
fn no_obstacle_in_the_way_is_the_plain_elastica() {
    let tip = load(0.2, -0.3, 1.0);
    let far = [Obstacle::half_plane([0.0, -5.0], [0.0, 1.0]), Obstacle::circle([3.0, 3.0], 1.0)];
    let table = Profile::Table(vec![[0.0, 1.2], [0.35, 0.5], [1.0, 0.9]]);
    let curved = Flexure::new(1.0, 1.0, 3).unwrap().with_rest(&[0.4, -0.2, 0.1]).unwrap();
    let kinked = curved.clone().with_section(Section::given(table).unwrap()).unwrap();
    for f in [unit(), curved, kinked] {
        let s = elastica::contact(&f, &far, 0.0, &[tip], &Default::default()).unwrap();
        assert!(s.reached() && s.events.is_empty() && s.contacts.is_empty());
        let exact = elastica::deflect(&f, &tip, &Default::default()).unwrap();
        let end = s.shape.last().unwrap();
        let error =
            (end.x - exact.pose.x).abs().max((end.y - exact.pose.y).abs()).max((end.phi - exact.pose.phi).abs());
        assert!(error < 1e-10, "tip pose differs by {error:e}");
        assert!((s.root_moment - exact.root_moment).abs() < 1e-10);
    }
}

/// Case (a) backwards: from the interior contact, a second leg takes the
/// load to a push along the flexure alone. The contact runs back to the tip
/// (reaching it within $10^{-9}L$), then opens as the flexure straightens;
/// no gap below $-10^{-12}$ on the way, and at the end the plain elastica's
/// straight column under the push (1e-10).
#[test]
fn floor_contact_returns_to_the_tip_then_opens() {
    let floor = [Obstacle::half_plane([0.0, -0.01], [0.0, 1.0])];
    let path = [load(0.4, 0.0, -1.0), load(0.0, -1.0, 0.0)];
    let s = solve(&floor, 0.0, &path);
    let kinds: Vec<_> = s.events.iter().map(|e| e.kind).collect();
    assert_eq!(kinds, [EventKind::Touch, EventKind::Roll, EventKind::Unroll, EventKind::Open]);
    assert!((s.events[2].s - 1.0).abs() < 1e-9 && s.events[2].load > 1.0, "{:?}", s.events[2]);
    for t in [1.5, 0.5 * (s.events[2].load + s.events[3].load)] {
        let at = [path[0], scaled(&path[0], 2.0 - t)];
        let at = [at[0], load(at[1].moment, -(t - 1.0), at[1].fy)];
        let partway = solve(&floor, 0.0, &at);
        assert!(partway.min_gap(&floor[0], 0.0) >= -1e-12 && partway.contacts.len() == 1);
        assert!(partway.contacts[0].normal_force > 0.0);
    }
    assert!(s.contacts.is_empty());
    let exact = elastica::deflect(&unit(), &path[1], &Default::default()).unwrap();
    let end = s.shape.last().unwrap();
    assert!((end.x - exact.pose.x).abs().max(end.y.abs()).max(end.phi.abs()) < 1e-10, "{end:?}");
}

/// Large deflection with the tip alone on the floor: the plain elastica
/// under the tip load plus the contact force found puts its tip on the
/// contact point with the same angle (1e-9).
#[test]
fn tip_contact_is_the_elastica_under_the_contact_force() {
    let tip = load(-1.5, 0.0, 0.0);
    let floor = [Obstacle::half_plane([0.0, -0.3], [0.0, 1.0])];
    let s = solve(&floor, 0.0, &[tip]);
    assert_eq!(s.events.iter().map(|e| e.kind).collect::<Vec<_>>(), [EventKind::Touch]);
    let c = s.contacts[0];
    assert!(c.s == 1.0 && c.normal_force > 0.1, "{c:?}");
    let f = c.force();
    let total = load(tip.moment, tip.fx + f[0], tip.fy + f[1]);
    let exact = elastica::deflect(&unit(), &total, &Default::default()).unwrap();
    let error = (c.point[0] - exact.pose.x)
        .abs()
        .max((c.point[1] - exact.pose.y).abs())
        .max((s.shape.last().unwrap().phi - exact.pose.phi).abs());
    assert!(error < 1e-9, "tip differs from the elastica's by {error:e}");
    assert!(tail_balance(&s, &tip) < 1e-10);
}

/// The elastica of length `length` clamped at `root` (angle `phi`) under
/// `tip` (global frame): its tip pose (φ, x, y), global.
fn piece(length: f64, root: [f64; 2], phi: f64, tip: &TipLoad) -> [f64; 3] {
    let f = Flexure::new(length, 1.0, 3).unwrap();
    let (sn, cs) = phi.sin_cos();
    let local = load(tip.moment, cs * tip.fx + sn * tip.fy, -sn * tip.fx + cs * tip.fy);
    let e = elastica::deflect(&f, &local, &Default::default()).unwrap().pose;
    [phi + e.phi, root[0] + cs * e.x - sn * e.y, root[1] + sn * e.x + cs * e.y]
}

/// Case (a), the transition: a downward tip force with a smaller
/// counter-clockwise moment, $F = -\lambda$, $M = 0.4\lambda$ (EI = L = 1),
/// onto a floor 0.01 below. Linear theory: the tip touches at
/// $\lambda = 7.5g$ and its slope turns up (the tip lifts) at $\lambda = 15g$;
/// measured to $10^{-3}$ relative (geometric terms, deflections of 0.01).
/// At each tenth of the load: $N \ge 0$ (to $10^{-12}$), no gap below
/// $-10^{-12}$ along the shape, and each side of the interior contact is
/// the plain elastica (1e-9): beyond it under the tip load, before it under
/// the tip load, the contact force and the moment they carry there.
#[test]
fn floor_contact_moves_from_the_tip_into_the_span() {
    let g = 0.01;
    let floor = [Obstacle::half_plane([0.0, -g], [0.0, 1.0])];
    let full = load(0.4, 0.0, -1.0);
    let s = solve(&floor, 0.0, &[full]);
    let kinds: Vec<_> = s.events.iter().map(|e| e.kind).collect();
    assert_eq!(kinds, [EventKind::Touch, EventKind::Roll]);
    for (event, expected) in s.events.iter().zip([7.5 * g, 15.0 * g]) {
        assert!((event.load - expected).abs() < 1e-3 * expected, "{event:?} vs {expected}");
    }
    for tenth in 1..=10 {
        let tip = scaled(&full, tenth as f64 / 10.0);
        let s = solve(&floor, 0.0, &[tip]);
        let gap = s.min_gap(&floor[0], 0.0);
        assert!(gap >= -1e-12, "gap {gap:e} at {tenth}/10");
        for c in &s.contacts {
            assert!(c.normal_force >= -1e-12, "{c:?}");
        }
        assert!(tail_balance(&s, &tip) < 1e-10 * 2.4);
        let Some(c) = s.contacts.iter().find(|c| c.s < 1.0) else { continue };
        // The tangent is the floor's at an interior contact.
        let phi = s.shape.iter().find(|p| p.s == c.s).unwrap().phi;
        assert!(phi.sin().abs() < 1e-12, "tangent angle {phi:e} at the contact");
        let end = s.shape.last().unwrap();
        let beyond = piece(1.0 - c.s, c.point, phi, &tip);
        let f = c.force();
        let moment = tip.moment + cross([end.x - c.point[0], end.y - c.point[1]], [tip.fx, tip.fy]);
        let before = piece(c.s, [0.0, 0.0], 0.0, &load(moment, tip.fx + f[0], tip.fy + f[1]));
        for (a, b) in [(beyond, [end.phi, end.x, end.y]), (before, [phi, c.point[0], c.point[1]])] {
            let e = (0..3).fold(0.0f64, |m, i| m.max((a[i] - b[i]).abs()));
            assert!(e < 1e-9, "{e:e} at {tenth}/10: {a:?} vs {b:?}");
        }
    }
}

/// Case (b): a tip force presses the flexure onto a circular post under
/// its span. At the contact the centreline is tangent to the circle
/// (1e-9), the force is along the circle's normal, and every tail of the
/// rod is in balance (1e-10 of the load's moment).
#[test]
fn post_contact_is_tangent_and_in_balance() {
    let post = [Obstacle::circle([0.55, -0.3], 0.25)];
    let tip = load(0.0, 0.0, -3.0);
    let s = solve(&post, 0.0, &[tip]);
    assert!(!s.contacts.is_empty() && s.contacts.iter().all(|c| c.s < 1.0), "{:?}", s.contacts);
    for c in &s.contacts {
        let p = s.shape.iter().find(|p| p.s == c.s).unwrap();
        let radial = [c.point[0] - 0.55, c.point[1] + 0.3];
        let r = radial[0].hypot(radial[1]);
        let tangency = (radial[0] * p.phi.cos() + radial[1] * p.phi.sin()) / r;
        assert!(tangency.abs() < 1e-9, "tangency {tangency:e}");
        assert!((r - 0.25).abs() < 1e-12 && c.friction_force.abs() < 1e-12 && c.normal_force > 0.0);
    }
    let balance = tail_balance(&s, &tip);
    assert!(balance < 1e-10 * 3.0, "tail balance off by {balance:e} N·m");
    // The whole rod: the clamp's force against the loads.
    let sum: [f64; 2] = s.contacts.iter().fold([tip.fx, tip.fy], |a, c| [a[0] + c.force()[0], a[1] + c.force()[1]]);
    assert!((sum[0] + s.reaction[0]).abs() < 1e-14 && (sum[1] + s.reaction[1]).abs() < 1e-14);
    assert!(s.min_gap(&post[0], 0.0) >= -1e-12);
}

/// Case (c): a tip force presses the tip onto a floor with friction
/// $\mu = 0.3$ (leg 1: $F = (0, -1)$), then a growing pull along the floor
/// (leg 2: to $F = (-0.6, -1)$). While stuck the shape is the touch's, so the
/// floor takes every load added since: $f = F_t - F$ with $F_t = (0, -\lambda_t)$
/// the load at touch (checked by the plain elastica, 1e-9), and the tip
/// slips where $0.6t = \mu(1 - \lambda_t)$ along leg 2 (1e-9). While stuck
/// $\lvert T\rvert < \mu N$; slipping, $\lvert T\rvert = \mu N$ (1e-12 relative).
/// The path shows: the same end load reached with the pull first ends stuck
/// with no friction; taking the pull off again (leg 3) sticks the tip, then
/// slips it back only part of the way (friction reversed, $T = \mu N$), not
/// to where leg 1 left it: tip displacements of about $10^{-4}L$, checked
/// against $10^{-5}L$.
#[test]
fn friction_sticks_then_slips_and_remembers_the_path() {
    let mu = 0.3;
    let floor = [Obstacle::half_plane([0.0, -0.2], [0.0, 1.0]).with_friction(mu)];
    let (press, pull) = (load(0.0, 0.0, -1.0), load(0.0, -0.6, -1.0));
    let pressed = solve(&floor, 0.0, &[press]);
    let kinds: Vec<_> = pressed.events.iter().map(|e| e.kind).collect();
    assert_eq!(kinds, [EventKind::Touch]);
    let touch = pressed.events[0].load;
    let c = pressed.contacts[0];
    assert_eq!(c.state, ContactState::Stick);
    assert!((c.normal_force - (1.0 - touch)).abs() < 1e-9 && c.friction_force.abs() < 1e-9, "{c:?}");
    let at_touch = elastica::deflect(&unit(), &load(0.0, 0.0, -touch), &Default::default()).unwrap().pose;
    assert!((at_touch.y + 0.2).abs() < 1e-9 && (at_touch.x - c.point[0]).abs() < 1e-9, "{at_touch:?} vs {c:?}");
    let pulled = solve(&floor, 0.0, &[press, pull]);
    let slip = pulled.events.iter().find(|e| e.kind == EventKind::Slip).expect("it slips");
    let expected = 1.0 + mu * (1.0 - touch) / 0.6;
    assert!((slip.load - expected).abs() < 1e-9, "slips at {} vs {expected}", slip.load);
    let c = pulled.contacts[0];
    assert_eq!(c.state, ContactState::Slip);
    assert!((c.friction_force.abs() - mu * c.normal_force).abs() < 1e-12 * c.normal_force, "{c:?}");
    assert!(c.point[0] < at_touch.x - 1e-5, "the pull drags the tip back: {c:?}");
    // Stuck partway: the touch's shape, the floor taking the load added since.
    let t = 0.5 * (expected - 1.0);
    let partway = solve(&floor, 0.0, &[press, load(0.0, -0.6 * t, -1.0)]);
    let c = partway.contacts[0];
    assert_eq!(c.state, ContactState::Stick);
    assert!(c.friction_force.abs() < mu * c.normal_force, "{c:?}");
    assert!((c.friction_force + 0.6 * t).abs() < 1e-9 && (c.point[0] - at_touch.x).abs() < 1e-9, "{c:?}");
    // The pull first: the same end load, stuck with no friction.
    let first = solve(&floor, 0.0, &[load(0.0, -0.6, 0.0), pull]);
    let c = first.contacts[0];
    assert_eq!(c.state, ContactState::Stick);
    assert!(c.friction_force.abs() < 1e-9 && (c.point[0] - pulled.contacts[0].point[0]).abs() > 1e-5, "{c:?}");
    // The pull taken off: the tip sticks as the load turns back (at the
    // corner of the path), then slips back part of the way, friction now the other way.
    let back = solve(&floor, 0.0, &[press, pull, press]);
    let kinds: Vec<_> = back.events.iter().map(|e| e.kind).collect();
    assert_eq!(kinds, [EventKind::Touch, EventKind::Slip, EventKind::Stick, EventKind::Slip]);
    assert!((back.events[2].load - 2.0).abs() < 1e-8, "{:?}", back.events[2]);
    let c = back.contacts[0];
    assert_eq!(c.state, ContactState::Slip);
    assert!((c.friction_force - mu * c.normal_force).abs() < 1e-12 * c.normal_force, "{c:?}");
    assert!(c.point[0] < at_touch.x - 1e-5, "{c:?} vs leg 1's tip at x = {}", at_touch.x);
}

/// Case (c) with a tip moment: pressed by a clockwise moment onto a floor
/// with $\mu = 0.2$, the stuck tip would need more friction than that from
/// the first touch on (the bent flexure pulls its tip back), so it slips at
/// once: the events are the touch and the slip at the same load (1e-9), with
/// no stick–slip flicker, and $\lvert T\rvert = \mu N$ at the end (1e-12 relative).
#[test]
fn a_tip_pressed_by_a_moment_slips_from_the_touch() {
    let mu = 0.2;
    let floor = [Obstacle::half_plane([0.0, -0.1], [0.0, 1.0]).with_friction(mu)];
    let s = solve(&floor, 0.0, &[load(-2.0, 0.0, 0.0)]);
    let kinds: Vec<_> = s.events.iter().map(|e| e.kind).collect();
    assert_eq!(kinds, [EventKind::Touch, EventKind::Slip], "{:?}", s.events);
    assert!((s.events[1].load - s.events[0].load).abs() < 1e-9, "{:?}", s.events);
    let c = s.contacts[0];
    assert!(c.state == ContactState::Slip && c.friction_force < 0.0, "pulled back toward the root: {c:?}");
    assert!((c.friction_force.abs() - mu * c.normal_force).abs() < 1e-12 * c.normal_force, "{c:?}");
}

fn refused(obstacles: &[Obstacle], h: f64, path: &[TipLoad]) -> &'static str {
    match elastica::contact(&unit(), obstacles, h, path, &Default::default()) {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("{other:?}"),
    }
}

/// Bad input is an error naming the field.
#[test]
fn bad_input_names_the_field() {
    let tip = [load(0.1, 0.0, 0.0)];
    let floor = Obstacle::half_plane([0.0, -0.1], [0.0, 1.0]);
    assert_eq!(refused(&[Obstacle::circle([0.0, 1.0], 0.0)], 0.0, &tip), "radius");
    assert_eq!(refused(&[Obstacle::half_plane([0.0, -0.1], [0.0, 0.0])], 0.0, &tip), "normal");
    assert_eq!(refused(&[floor.with_friction(-0.1)], 0.0, &tip), "friction");
    assert_eq!(refused(&[Obstacle::circle([0.0, 0.0], 0.1)], 0.0, &tip), "obstacle");
    assert_eq!(refused(&[floor], 0.2, &tip), "obstacle", "the root within the half thickness");
    assert_eq!(refused(&[floor], -0.01, &tip), "half_thickness");
    assert_eq!(refused(&[floor], 0.0, &[]), "path");
    assert_eq!(refused(&[Obstacle::circle([0.5, 0.0], 0.1)], 0.0, &tip), "obstacle", "the rest shape enters it");
    assert_eq!(refused(&[floor], 0.0, &[load(0.0, 0.0, 1e4)]), "force");
}
