//! `mechanism/contact/corner.rs`: two geoms touching at corners, against
//! closed forms. A lid on a sprung hinge (k = 0.5 N·m/rad), pushed down by
//! F at 0.1 m from the hinge, carries a box; the box's corner that meets a
//! floor (or a post's corner that meets the box) stops the lid at the
//! angle $\theta_c$ where it touches, and the moment balance about the
//! hinge, $k\theta_c + M_F(\theta_c) + M_N = 0$, gives the push $N$.
//! Tolerances: the angle to 1e-12 rad (the gap row solved to rounding),
//! the push to 1e-9 relative.

use flexure::mechanism::contact::ContactMode;
use flexure::mechanism::file::{from_toml, spatial_from_toml};
use flexure::mechanism::statics::{Settings, solve};

/// The angle in $[-1, 0]$ where `f` (increasing there) crosses zero, by bisection to rounding.
fn root(f: impl Fn(f64) -> f64) -> f64 {
    root_in(-1.0, 0.0, f)
}

/// The angle in $[lo, hi]$ where `f` changes sign, by bisection to rounding.
fn root_in(mut lo: f64, mut hi: f64, f: impl Fn(f64) -> f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) * f(lo) <= 0.0 { hi = mid } else { lo = mid }
    }
    0.5 * (lo + hi)
}

/// The planar lid: a hinge at the origin, the lid along x, a box on it,
/// `geom` below, and the push `force` N down at x = 0.1 m.
fn lid(block: &str, geom: &str, force: f64) -> String {
    format!(
        "[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"lid\"\nstiffness = 0.5\n\
         [[geom]]\nname = \"block\"\nbody = \"lid\"\nshape = \"box\"\n{block}\n\
         [[geom]]\nname = \"below\"\nbody = \"ground\"\n{geom}\n\
         [[force]]\nname = \"push\"\nbody = \"lid\"\nat = [0.1, 0.0]\nforce = [0.0, {}]\n",
        -force
    )
}

/// A box 40 × 10 mm centred 80 mm along the lid meets a floor 30 mm below
/// the hinge at its outer lower corner, $c = (0.1, -0.005)$: there
/// $c_x\sin\theta + c_y\cos\theta = -0.03$, and
/// $N = (k\theta + F\,0.1\cos\theta)/p_x$, $p_x$ the corner's arm. Below
/// the push that first brings it down, nothing touches.
#[test]
fn a_lid_pushed_onto_a_floor_rests_on_its_boxs_corner() {
    let block = "origin = [0.08, 0.0]\nhalf_extents = [0.02, 0.005]";
    let floor = "shape = \"plane\"\norigin = [0.0, -0.03]\nnormal = [0.0, 1.0]";
    let theta = root(|t| 0.1 * t.sin() - 0.005 * t.cos() + 0.03);
    let touches = -0.5 * theta / (0.1 * theta.cos());
    for force in [0.5 * touches, 20.0] {
        let m = from_toml(&lid(block, floor, force)).unwrap();
        let s = solve(&m, &Settings::default()).unwrap();
        if force < touches {
            assert!(s.contacts.is_empty(), "{:?}", s.contacts);
            assert!((s.q[0] + force * 0.1 * s.q[0].cos() / 0.5).abs() < 1e-12);
            continue;
        }
        assert_eq!(s.contacts.len(), 1, "{:?}", s.contacts);
        let c = &s.contacts[0];
        let arm = 0.1 * theta.cos() + 0.005 * theta.sin();
        let push = (0.5 * theta + force * 0.1 * theta.cos()) / arm;
        assert!((s.q[0] - theta).abs() < 1e-12, "{} against {theta}", s.q[0]);
        assert!((c.normal_force - push).abs() < 1e-9 * push, "{} against {push}", c.normal_force);
        assert!((c.point[0] - arm).abs() < 1e-12 && (c.point[1] + 0.03).abs() < 1e-12, "{:?}", c.point);
        assert_eq!((c.geom.as_str(), c.body.as_deref(), c.state), ("below", Some("lid"), ContactMode::Slip));
        assert_eq!(c.normal, [0.0, 1.0]);
    }
}

/// A post (a box on the ground, its top right corner at P = (0.09, −0.02))
/// meets the lid's box, which reaches past it, from below: the corner is the post's, against the
/// lid's face $y = -0.005$ in the lid's frame, so
/// $-\sin\theta\,P_x + \cos\theta\,P_y = -0.005$, and the face's outward
/// normal $n = (\sin\theta, -\cos\theta)$ takes the push $-Nn$ on the lid:
/// $N = (k\theta + F\,0.1\cos\theta)/(P_yn_x - P_xn_y)$. The contact names
/// the post as the geom touched, the normal out of it ($-n$), and P.
#[test]
fn a_posts_corner_meets_the_lids_box_along_its_face() {
    let block = "origin = [0.08, 0.0]\nhalf_extents = [0.04, 0.005]";
    let post = "shape = \"box\"\norigin = [0.07, -0.03]\nhalf_extents = [0.02, 0.01]";
    let (px, py) = (0.09, -0.02);
    let theta = root(|t| -t.sin() * px + t.cos() * py + 0.005);
    let force = 10.0;
    let m = from_toml(&lid(block, post, force)).unwrap();
    let s = solve(&m, &Settings::default()).unwrap();
    assert_eq!(s.contacts.len(), 1, "{:?}", s.contacts);
    let c = &s.contacts[0];
    let n = [theta.sin(), -theta.cos()];
    let push = (0.5 * theta + force * 0.1 * theta.cos()) / (py * n[0] - px * n[1]);
    assert!((s.q[0] - theta).abs() < 1e-12, "{} against {theta}", s.q[0]);
    assert!((c.normal_force - push).abs() < 1e-9 * push, "{} against {push}", c.normal_force);
    assert!((c.point[0] - px).abs() < 1e-12 && (c.point[1] - py).abs() < 1e-12, "{:?}", c.point);
    assert!((c.normal[0] + n[0]).abs() < 1e-12 && (c.normal[1] + n[1]).abs() < 1e-12, "{:?} against -{n:?}", c.normal);
    assert_eq!((c.geom.as_str(), c.body.as_deref()), ("below", Some("lid")));
}

/// The lid's capsule (radius 5 mm, its segment from x = 0.06 to 0.10)
/// meets the floor with its outer end ball: the ball's centre
/// $(0.1\cos\theta, 0.1\sin\theta)$ sits 5 mm above the floor, and $N = (k\theta + F\,0.1\cos\theta)/(0.1\cos\theta)$.
#[test]
fn a_capsule_meets_a_floor_with_its_end_ball() {
    let text = lid(
        "origin = [0.08, 0.0]\nhalf_extents = [0.001, 0.001]",
        "shape = \"plane\"\norigin = [0.0, -0.03]\nnormal = [0.0, 1.0]",
        20.0,
    )
    .replace(
        "shape = \"box\"\norigin = [0.08, 0.0]\nhalf_extents = [0.001, 0.001]",
        "shape = \"capsule\"\norigin = [0.08, 0.0]\nradius = 0.005\nhalf_length = 0.02",
    );
    let m = from_toml(&text).unwrap();
    let s = solve(&m, &Settings::default()).unwrap();
    let theta = (-0.025f64 / 0.1).asin();
    let push = (0.5 * theta + 20.0 * 0.1 * theta.cos()) / (0.1 * theta.cos());
    assert_eq!(s.contacts.len(), 1, "{:?}", s.contacts);
    assert!((s.q[0] - theta).abs() < 1e-12, "{} against {theta}", s.q[0]);
    assert!((s.contacts[0].normal_force - push).abs() < 1e-9 * push);
    assert!((s.contacts[0].point[0] - 0.1 * theta.cos()).abs() < 1e-12);
}

/// The spatial lid: a hinge about x, the lid along y, a box on it (`block`),
/// `below` on the ground, the push `force` N down at y = 0.1 m.
fn lid3(block: &str, below: &str, force: f64) -> String {
    format!(
        "dimension = 3\n[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"lid\"\naxis = [1.0, 0.0, 0.0]\nstiffness = 0.5\n\
         [[geom]]\nname = \"block\"\nbody = \"lid\"\nshape = \"box\"\n{block}\n\
         [[geom]]\nname = \"below\"\nbody = \"ground\"\n{below}\n\
         [[force]]\nname = \"push\"\nbody = \"lid\"\nat = [0.0, 0.1, 0.0]\nforce = [0.0, 0.0, {}]\n",
        -force
    )
}

/// In space: the lid's box turned 0.3 rad about its own z so that one
/// lower corner leads, onto a floor 30 mm below the hinge, or onto a
/// table (a box whose top face is there). Each corner $c$ (in the lid's
/// frame) goes to $z = c_y\sin\theta + c_z\cos\theta$; the first to
/// reach −0.03 stops the lid, and about the hinge
/// $N = (k\theta + F\,0.1\cos\theta)/p_y$, $p_y = c_y\cos\theta - c_z\sin\theta$.
#[test]
fn a_spatial_lid_rests_on_its_leading_corner_on_a_floor_or_a_table() {
    let block = "origin = [0.0, 0.08, 0.0]\nrpy = [0.0, 0.0, 0.3]\nhalf_extents = [0.01, 0.02, 0.005]";
    let floor = "shape = \"plane\"\norigin = [0.0, 0.0, -0.03]\nnormal = [0.0, 0.0, 1.0]";
    let table = "shape = \"box\"\norigin = [0.0, 0.08, -0.04]\nhalf_extents = [0.1, 0.1, 0.01]";
    // The corners in the lid's frame: the box's (±0.01, ±0.02, −0.005) turned by 0.3 about z.
    let (cos, sin) = (0.3f64.cos(), 0.3f64.sin());
    let lower = [(0.01, 0.02), (-0.01, 0.02), (0.01, -0.02), (-0.01, -0.02)]
        .map(|(x, y): (f64, f64)| (cos * x - sin * y, 0.08 + sin * x + cos * y, -0.005));
    let (theta, c) = lower
        .iter()
        .map(|&(x, y, z)| (root(|t| y * t.sin() + z * t.cos() + 0.03), (x, y, z)))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap();
    let p_y = c.1 * theta.cos() - c.2 * theta.sin();
    let push = (0.5 * theta + 20.0 * 0.1 * theta.cos()) / p_y;
    for below in [floor, table] {
        let s = solve(&spatial_from_toml(&lid3(block, below, 20.0)).unwrap(), &Settings::default()).unwrap();
        assert_eq!(s.contacts.len(), 1, "{:?}", s.contacts);
        let k = &s.contacts[0];
        assert!((s.q[0] - theta).abs() < 1e-12, "{below}: {} against {theta}", s.q[0]);
        assert!((k.normal_force - push).abs() < 1e-9 * push, "{below}: {} against {push}", k.normal_force);
        assert!(
            (k.point[0] - c.0).abs() < 1e-12 && (k.point[1] - p_y).abs() < 1e-12 && (k.point[2] + 0.03).abs() < 1e-12
        );
        assert!((k.normal[2] - 1.0).abs() < 1e-12, "{below}: {:?}", k.normal);
    }
}

/// In space two boxes may meet edge across edge, where no corner touches
/// (`mechanism/contact/crossing.rs`). The lid's box comes down onto a
/// rail, a box 4 mm wide across it whose outer top edge is
/// $(x, y_0, z_0) = (x, 0.092, -0.03)$. In the lid's frame that line is at height
/// $z = -y_0\sin\theta + z_0\cos\theta$ and $y_l = y_0\cos\theta + z_0\sin\theta$
/// along the lid, and it pushes along the lid's normal, so about the hinge
/// $N = (k\theta + F\,0.1\cos\theta)/y_l$. The box turned 45° about the lid's
/// $y$ meets it with its lowest edge, $z = -(0.01 + 0.005)/\sqrt2$, one edge
/// across the other; not turned, with its lower face $z = -0.005$ (two of
/// its edges across the rail's, one push shared between them). A rod
/// across the lid (a capsule of radius $r_1$ = 3 mm along its $y$) meets
/// the rail's edge at $z = -r_1$, and a rod along $x$ (radius $r_2$ = 8 mm, its
/// axis at $z_0 = -0.03 - r_2$) at $z = -r_1 - r_2$. The angle to 1e-12 rad and
/// the total push to 1e-9 relative; the point on the rail's edge, or on
/// the lower rod's surface, to 1e-12 m.
#[test]
fn a_box_or_a_rod_meets_a_rail_or_a_rod_edge_across_edge_in_space() {
    let rail = "shape = \"box\"\norigin = [0.0, 0.09, -0.04]\nhalf_extents = [0.1, 0.002, 0.01]";
    let rod = "shape = \"capsule\"\norigin = [0.0, 0.092, -0.038]\nhalf_length = 0.1\nradius = 0.008";
    let turned = "shape = \"box\"\norigin = [0.0, 0.08, 0.0]\nrpy = [0.0, 0.7853981633974483, 0.0]\nhalf_extents = [0.01, 0.02, 0.005]";
    let flat = "shape = \"box\"\norigin = [0.0, 0.08, 0.0]\nhalf_extents = [0.01, 0.02, 0.005]";
    let across = "shape = \"capsule\"\norigin = [0.0, 0.08, 0.0]\nrpy = [0.0, 0.0, 1.5707963267948966]\nhalf_length = 0.02\nradius = 0.003";
    let cases = [
        (turned, rail, -0.03, -0.015 * 0.5f64.sqrt(), 1),
        (flat, rail, -0.03, -0.005, 2),
        (across, rail, -0.03, -0.003, 1),
        (across, rod, -0.038, -0.011, 1),
    ];
    for (block, below, z0, low, count) in cases {
        let theta = root(|t| -0.092 * t.sin() + z0 * t.cos() - low);
        let arm = 0.092 * theta.cos() + z0 * theta.sin();
        let push = (0.5 * theta + 20.0 * 0.1 * theta.cos()) / arm;
        let text = lid3(block, below, 20.0).replacen("shape = \"box\"\n", "", 1);
        let s = solve(&spatial_from_toml(&text).unwrap(), &Settings::default()).unwrap();
        assert!((s.q[0] - theta).abs() < 1e-12, "{block}: {} against {theta}", s.q[0]);
        assert!((1..=count).contains(&s.contacts.len()), "{block}: {:?}", s.contacts);
        let total: f64 = s.contacts.iter().map(|k| k.normal_force).sum();
        assert!((total - push).abs() < 1e-9 * push, "{block}: {total} against {push}");
        // Along the lid's normal, out of the rail or the rod, on its surface.
        let (sin, cos, r2) = (theta.sin(), theta.cos(), -0.03 - z0);
        for k in &s.contacts {
            let point = [0.092 - r2 * sin, z0 + r2 * cos];
            assert!((k.point[1] - point[0]).abs() < 1e-12 && (k.point[2] - point[1]).abs() < 1e-12, "{block}: {k:?}");
            assert!((k.normal[1] + sin).abs() < 1e-12 && (k.normal[2] - cos).abs() < 1e-12, "{block}: {k:?}");
        }
        if block == turned {
            assert!((s.contacts[0].point[0].abs() - 0.005 * 0.5f64.sqrt()).abs() < 1e-12, "{:?}", s.contacts[0]);
        }
    }
}

/// The lid of [`a_box_or_a_rod_meets_a_rail_or_a_rod_edge_across_edge_in_space`]
/// on a carriage sprung along x (`k_x` N/m), dragged by `f_x` N at its push.
fn carried(block: &str, k_x: f64, f_x: f64) -> String {
    format!(
        "dimension = 3\n[[joint]]\nname = \"carriage\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"cart\"\naxis = [1.0, 0.0, 0.0]\nstiffness = {k_x:?}\n\
         [[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"cart\"\nchild = \"lid\"\naxis = [1.0, 0.0, 0.0]\nstiffness = 0.5\n\
         [[geom]]\nname = \"block\"\nbody = \"lid\"\n{block}\n\
         [[geom]]\nname = \"rail\"\nbody = \"ground\"\nshape = \"box\"\norigin = [0.0, 0.09, -0.04]\nhalf_extents = [0.1, 0.002, 0.01]\n\
         [[force]]\nname = \"push\"\nbody = \"lid\"\nat = [0.0, 0.1, 0.0]\nforce = [{f_x:?}, 0.0, -2.0]\n"
    )
}

const TURNED: &str = "shape = \"box\"\norigin = [0.0, 0.08, 0.0]\nrpy = [0.0, 0.7853981633974483, 0.0]\nhalf_extents = [0.01, 0.02, 0.005]";
const ACROSS: &str = "shape = \"capsule\"\norigin = [0.0, 0.08, 0.0]\nrpy = [0.0, 0.0, 1.5707963267948966]\nhalf_length = 0.02\nradius = 0.003";

/// Where the [`carried`] lid rests with the rail's corner
/// $c = (0.1, 0.092, -0.03)$ on the turned box's lower face (outward normal
/// $n = -(1, 0, 1)/\sqrt2$ in the lid's frame, 5 mm from its centre) or on
/// the rod's side (radius 3 mm): the slide $x$, the angle $\theta$ and the push $N$.
/// With the carriage at $x$ and the lid at $\theta$, $c$ lies at
/// $c_l = (0.1 - x,\ y^\prime,\ z^\prime)$ in the lid's frame,
/// $(y^\prime, z^\prime) = (0.092\cos\theta - 0.03\sin\theta,\ -0.092\sin\theta - 0.03\cos\theta)$:
/// on the face $x = 0.1 + z^\prime + 0.005\sqrt2$, on the rod
/// $x = 0.1 + \sqrt{0.003^2 - z^{\prime 2}}$. The push $N$ along $n$ balances
/// the carriage, $k_x x = F_x - N n_x$, and the hinge,
/// $k\theta = -0.2\cos\theta + (c - x e_x)\times(-N n)\cdot e_x$: a bisection in $\theta$.
fn on_the_rails_corner(rod: bool, k_x: f64, f_x: f64) -> (f64, f64, f64) {
    let half = 0.5f64.sqrt();
    let z_of = |t: f64| -0.092 * t.sin() - 0.03 * t.cos();
    // The slide, and the normal in the lid's frame, at an angle.
    let place = |t: f64| match rod {
        false => (0.1 + z_of(t) + 0.005 / half, [-half, 0.0, -half]),
        true => {
            let x = 0.1 + (0.003f64.powi(2) - z_of(t).powi(2)).max(0.0).sqrt();
            (x, [(0.1 - x) / 0.003, 0.0, z_of(t) / 0.003])
        }
    };
    // The push and the hinge's unbalanced moment at an angle.
    let balance = |t: f64| {
        let (x, n) = place(t);
        let push = (f_x - k_x * x) / n[0];
        let (ny, nz) = (n[1] * t.cos() - n[2] * t.sin(), n[1] * t.sin() + n[2] * t.cos());
        let moment = -0.2 * t.cos() + 0.092 * (-push * nz) + 0.03 * (-push * ny);
        (push, 0.5 * t - moment)
    };
    // The rod rests on c where -3 mm < z' < 0 (c below its axis), z' = -R sin(θ + φ),
    // at two angles: the path meets the one nearer the rail's end, between
    // the arc's middle and where the push vanishes (the other is the rod
    // hung 3 mm past the corner).
    let (big, phi) = (0.092f64.hypot(0.03), 0.03f64.atan2(0.092));
    let reach = (0.003 / big).asin() * (1.0 - 1e-12);
    let (lo, hi) = match rod {
        false => (-1.0, 0.0),
        true => (-phi + 0.5 * reach, root_in(-phi, -phi + reach, |t| place(t).0 - f_x / k_x)),
    };
    let theta = root_in(lo, hi, |t| balance(t).1);
    (place(theta).0, theta, balance(theta).0)
}

/// Where a crossing runs off an edge's end, the corner there takes the
/// touch (`Crossing::ran_off`): the [`carried`] lid's crossing runs along
/// the rail's top edge to its end, and the rail's corner then bears on the
/// box's face or the rod's side ([`on_the_rails_corner`]). The slide and
/// angle to 1e-12, the push to 1e-9 relative, the point to 1e-12 m.
#[test]
fn a_crossing_run_off_the_rails_end_hands_its_touch_to_the_rails_corner() {
    for (block, k_x, f_x) in [(TURNED, 100.0, 10.2), (TURNED, 100.0, 10.5), (ACROSS, 2000.0, 200.5)] {
        let (x, theta, push) = on_the_rails_corner(block == ACROSS, k_x, f_x);
        let s = solve(&spatial_from_toml(&carried(block, k_x, f_x)).unwrap(), &Settings::default()).unwrap();
        assert!(
            (s.q[0] - x).abs() < 1e-12 && (s.q[1] - theta).abs() < 1e-12,
            "{block}: {:?} against {x}, {theta}",
            s.q
        );
        let k: Vec<_> = s.contacts.iter().filter(|k| k.state != ContactMode::Open).collect();
        assert_eq!(k.len(), 1, "{block}: {k:?}");
        assert!((k[0].normal_force - push).abs() < 1e-9 * push, "{block}: {} against {push}", k[0].normal_force);
        assert!(k[0].point.iter().zip([0.1, 0.092, -0.03]).all(|(a, b)| (a - b).abs() < 1e-12), "{:?}", k[0]);
    }
}

/// And back: swept from 200.5 N down to 199 N, the rod's crossing comes
/// back onto the rail's edge from its corner: the two edges touch again,
/// and the corner lets go (one touch left, not two side by side). At 199 N
/// the rod rests across the edge, as in
/// [`a_box_or_a_rod_meets_a_rail_or_a_rod_edge_across_edge_in_space`]
/// ($z^\prime = -r_1$, $N = (k\theta + 0.2\cos\theta)/y_l$), its carriage
/// where its spring alone holds the drag, $x = F_x/k_x$ (the push is
/// across it). The angle and slide to 1e-12, the push to 1e-9 relative.
#[test]
fn a_crossing_swept_back_from_the_rails_corner_takes_its_touch_back() {
    use flexure::mechanism::sweep::{Parameter, sweep};
    let m = spatial_from_toml(&carried(ACROSS, 2000.0, 200.5)).unwrap();
    let drag = Parameter::parse(&m, "force.push.fx").unwrap();
    let out = sweep(&m, &drag, &[200.5, 199.0], &Settings::default()).unwrap();
    assert!(out.stopped.is_none() && out.rows.len() == 2, "{:?}", out.stopped);
    let s = &out.rows[1].1;
    let theta = root(|t| -0.092 * t.sin() - 0.03 * t.cos() + 0.003);
    let push = (0.5 * theta + 0.2 * theta.cos()) / (0.092 * theta.cos() - 0.03 * theta.sin());
    assert!((s.q[0] - 0.0995).abs() < 1e-12 && (s.q[1] - theta).abs() < 1e-12, "{:?} against {theta}", s.q);
    let k: Vec<_> = s.contacts.iter().filter(|k| k.state != ContactMode::Open).collect();
    assert_eq!(k.len(), 1, "{k:?}");
    assert!((k[0].normal_force - push).abs() < 1e-9 * push, "{} against {push}", k[0].normal_force);
}

/// And back for the turned box: the rail's corner slides back along the
/// box's lower face, whose push along the rail (its normal $n$, 45° to
/// it) holds the carriage out, $k_xx = F_x + N/\sqrt2$, until it reaches
/// the box's lowest edge: at the angle $\theta_c$ where the edge meets the
/// rail's (as in [`a_box_or_a_rod_meets_a_rail_or_a_rod_edge_across_edge_in_space`]),
/// $x = 0.1 - 0.005/\sqrt2$ and $N = \sqrt2N_c$, $N_c$ the push there
/// across the edges, so $F_x = 100x - N_c$ = 8.678 N. Below it the edges
/// cross again only with the carriage at $F_x/k_x$, 1 cm in: the path
/// snaps (forward, the corner took the touch at 9.646 N), and the sweep
/// from 10.5 N to 8.5 N stops there, said as a snap of the two geoms, at
/// that fraction of the last step to 1e-6.
#[test]
fn a_box_swept_back_from_the_rails_corner_snaps_onto_its_edge_and_the_sweep_says_where() {
    use flexure::mechanism::sweep::{Parameter, sweep};
    let m = spatial_from_toml(&carried(TURNED, 100.0, 10.5)).unwrap();
    let drag = Parameter::parse(&m, "force.push.fx").unwrap();
    let out = sweep(&m, &drag, &[10.5, 8.5], &Settings::default()).unwrap();
    let theta = root(|t| -0.092 * t.sin() - 0.03 * t.cos() + 0.015 * 0.5f64.sqrt());
    let across = (0.5 * theta + 0.2 * theta.cos()) / (0.092 * theta.cos() - 0.03 * theta.sin());
    let snap = 100.0 * (0.1 - 0.005 * 0.5f64.sqrt()) - across;
    let Some((8.5, e)) = out.stopped else { panic!("no stop at 8.5 N: {:?}", out.stopped) };
    let flexure::Error::ContinuationStalled { load_fraction, ref cause, .. } = e else { panic!("{e}") };
    assert!((load_fraction - (10.5 - snap) / 2.0).abs() < 1e-6, "{load_fraction} against {}: {e}", (10.5 - snap) / 2.0);
    assert!(cause.contains("snaps") && cause.contains("\"block\""), "{e}");
}

/// A can lying across a knife edge (a box turned 45° about y, its top
/// edge along y) and dragged along its own axis: the crossing runs along
/// the can's axis to its end at $x = h = 0.02$ m, where the carriage
/// alone holds the drag ($x = \lambda F_x/k_x$, the push across it), so at
/// $\lambda = k_x h/F_x$. Past it the rim's point slides off the knife's edge
/// with nothing to hold it: the path snaps, and the solve stops there,
/// said as a snap of two geoms (no flexure named), at that fraction to 1e-6.
#[test]
fn a_can_dragged_off_a_knife_edge_snaps_and_the_solve_says_where() {
    let e = solve(&spatial_from_toml(&on_a_knife()).unwrap(), &Settings::default()).unwrap_err();
    let flexure::Error::ContinuationStalled { load_fraction, ref cause, .. } = e else { panic!("{e}") };
    assert!((load_fraction - 0.02 * 100.0 / 2.05).abs() < 1e-6, "{e}");
    assert!(cause.contains("snaps") && !cause.contains("flexure"), "{e}");
}

/// The [`carried`] lid's can (radius 5 mm, 40 mm long, its axis along x)
/// across a knife edge (a box of half extents 5, 30, 5 mm turned 45° about
/// y, its top edge along y at $z = -0.0125 + 0.005\sqrt2$), dragged by 2.05 N
/// on 100 N/m.
fn on_a_knife() -> String {
    carried("shape = \"cylinder\"\norigin = [0.0, 0.08, 0.0]\nrpy = [0.0, 1.5707963267948966, 0.0]\nhalf_length = 0.02\nradius = 0.005", 100.0, 2.05)
        .replace(
            "origin = [0.0, 0.09, -0.04]\nhalf_extents = [0.1, 0.002, 0.01]",
            "origin = [0.0, 0.08, -0.0125]\nrpy = [0.0, 0.7853981633974483, 0.0]\nhalf_extents = [0.005, 0.03, 0.005]",
        )
}

/// In motion, undamped, given mass (0.1 kg on the carriage and on the lid
/// at the can's centre) and dragged from rest, the can of
/// [`a_can_dragged_off_a_knife_edge_snaps_and_the_solve_says_where`] lands
/// across the knife, runs off its end at 0.069 s, and falls free of it:
/// the rim's point there parts from the knife as the can runs on, so it is
/// not handed the touch (handed it, the run stopped there, a guard 7.2
/// bands past just after the event). Checked: the run reaches 3 s, its
/// energy never grows ([`never_gains`]), and at every sample no point of
/// the can's side and rims (41 along, 64 round) lies inside the knife.
#[test]
fn a_can_run_off_a_knife_edge_in_motion_falls_free_of_it() {
    use flexure::dynamics::integrate::MotionSettings;
    let text = format!(
        "{}[[body]]\nname = \"cart\"\nmass = 0.1\n[[body]]\nname = \"lid\"\nmass = 0.1\ncom = [0.0, 0.08, 0.0]\n",
        on_a_knife()
    );
    let run = from_rest(&text, MotionSettings { duration: 3.0, every: 0.05, ..Default::default() });
    never_gains(&run, 2.05);
    let (half, r) = (0.5f64.sqrt(), 0.005);
    for i in 0..run.time.len() {
        let (x, theta) = (run.q(i)[0], run.q(i)[1]);
        for (k, j) in (0..=40).flat_map(|k| (0..64).map(move |j| (k, j))) {
            let (a, phi) = (-0.02 + 0.001 * f64::from(k), std::f64::consts::TAU * f64::from(j) / 64.0);
            let (y, z) = (0.08 + r * phi.cos(), r * phi.sin());
            // The can's point in the world, then in the knife's frame.
            let w = [x + a, y * theta.cos() - z * theta.sin(), y * theta.sin() + z * theta.cos()];
            let d = [w[0], w[1] - 0.08, w[2] + 0.0125];
            let local = [half * (d[0] - d[2]), d[1], half * (d[0] + d[2])];
            let depth = (0.005 - local[0].abs()).min(0.03 - local[1].abs()).min(0.005 - local[2].abs());
            assert!(depth < 1e-9, "t = {}: the can's point ({a}, {phi}) {depth} m inside the knife", run.time[i]);
        }
    }
}

/// In motion, given mass and damping and dragged from rest, the [`carried`]
/// lid lands edge across edge, runs off the rail's end, and the rail's
/// corner takes the touch at that instant: it comes to rest where
/// [`on_the_rails_corner`] puts it (slide and angle to 1e-7 after 3 s, the
/// slowest mode damped by about e^-20), the touch handed over once.
#[test]
fn a_crossing_run_off_the_rails_end_in_motion_comes_to_rest_on_the_rails_corner() {
    use flexure::dynamics::integrate::MotionSettings;
    for (block, k_x, f_x) in [(TURNED, 100.0, 10.5), (ACROSS, 2000.0, 200.5)] {
        let (x, theta, _) = on_the_rails_corner(block == ACROSS, k_x, f_x);
        let damped = carried(block, k_x, f_x)
            .replace("stiffness = 0.5\n", "stiffness = 0.5\ndamping = 0.01\n")
            .replacen("child = \"cart\"\n", "child = \"cart\"\ndamping = 5.0\n", 1);
        let text = format!(
            "{damped}[[body]]\nname = \"cart\"\nmass = 0.1\n[[body]]\nname = \"lid\"\nmass = 0.1\ncom = [0.0, 0.08, 0.0]\n"
        );
        let run = from_rest(&text, MotionSettings { duration: 3.0, every: 0.05, ..Default::default() });
        let last = run.time.len() - 1;
        let q = run.q(last);
        assert!((q[0] - x).abs() < 1e-7 && (q[1] - theta).abs() < 1e-7, "{block}: {q:?} against {x}, {theta}");
        let k: Vec<_> = run.contacts[last].iter().filter(|k| k.state != ContactMode::Open).collect();
        assert!(k.len() == 1 && k[0].point.iter().zip([0.1, 0.092, -0.03]).all(|(a, b)| (a - b).abs() < 1e-9), "{k:?}");
    }
}

/// The [`carried`] lid with `block`, undamped, given mass (0.1 kg on the
/// carriage and on the lid at its box's centre) and pushed from rest for
/// `duration` s, sampled `every` s: its run, which must reach the end.
fn undamped(
    block: &str,
    k_x: f64,
    f_x: f64,
    duration: f64,
    every: f64,
) -> flexure::dynamics::simulation::Simulation<flexure::space::Spatial> {
    let text = format!(
        "{}[[body]]\nname = \"cart\"\nmass = 0.1\n[[body]]\nname = \"lid\"\nmass = 0.1\ncom = [0.0, 0.08, 0.0]\n",
        carried(block, k_x, f_x)
    );
    from_rest(&text, flexure::dynamics::integrate::MotionSettings { duration, every, ..Default::default() })
}

/// That an undamped run never gains energy: with `potential`, the constant
/// loads' potential at the coordinates, $E + V(q)$ never grows from sample
/// to sample (to 1e-6 J, the steps' tolerance); `what` names the run.
fn never_grows(
    run: &flexure::dynamics::simulation::Simulation<flexure::space::Spatial>,
    what: &str,
    potential: impl Fn(&[f64]) -> f64,
) {
    let total: Vec<f64> = (0..run.time.len()).map(|i| run.energy[i] + potential(run.q(i))).collect();
    for (i, w) in total.windows(2).enumerate() {
        assert!(w[1] <= w[0] + 1e-6, "{what}, t = {}: {} after {}", run.time[i + 1], w[1], w[0]);
    }
}

/// [`never_grows`] for an undamped [`carried`] lid dragged by `f_x`: with
/// the drag's and the push's potential, $E - F_xx + 0.2\sin\theta$.
fn never_gains(run: &flexure::dynamics::simulation::Simulation<flexure::space::Spatial>, f_x: f64) {
    never_grows(run, "the lid", |q| -f_x * q[0] + 0.2 * q[1].sin());
}

/// The spatial mechanism `text` run from rest with `motion`: its run, which must reach the end.
fn from_rest(
    text: &str,
    motion: flexure::dynamics::integrate::MotionSettings,
) -> flexure::dynamics::simulation::Simulation<flexure::space::Spatial> {
    use flexure::dynamics::simulation;
    let settings = simulation::SimulationSettings { motion, ..Default::default() };
    let run = simulation::simulate(&spatial_from_toml(text).unwrap(), &settings, simulation::Start::Rest).unwrap();
    assert!(run.stopped.is_none(), "{:?}", run.stopped);
    run
}

/// Undamped, the rod's carriage of [`a_crossing_run_off_the_rails_end_in_motion_comes_to_rest_on_the_rails_corner`]
/// swings about the rail's end at up to 14 m/s (2000 N/m on 0.1 kg): the
/// rod lands, runs off the end, drops beside it and is struck back:
/// more than 30 changes in its first second (43, each a landing, a leaving
/// or a hand-off; 53 when the rail's corner was handed a touch it let go at
/// once, as the rod parted from it: [`an_undamped_box_run_off_the_rails_end_falls_free_of_its_corner_without_gaining_energy`]).
/// A step that would carry it edge across edge
/// through the rail, where no gap is negative at its end, is refused and
/// shortened (it stopped the run at 0.9 s, sampled every 50 ms). Checked
/// against energy: with the drag's and the push's potential,
/// $E - F_xx + 0.2\sin\theta$ never grows (to 1e-6 J, the steps'
/// tolerance on a swing of 10 J), at every sample the rod lies outside the
/// rail by its radius (its axis sampled at 401 points against the box, to
/// 1e-6 m), and the run reaches its end.
#[test]
fn an_undamped_rod_struck_back_and_forth_at_the_rails_end_never_gains_energy() {
    let run = undamped(ACROSS, 2000.0, 200.5, 1.0, 0.05);
    assert!(run.changes.len() > 30, "{}", run.changes.len());
    never_gains(&run, 200.5);
    // The rail: x in ±0.1, y in 0.09 ± 0.002, z in -0.04 ± 0.01; the rod's axis along the lid's y.
    let outside = |p: [f64; 3]| {
        let d = [p[0].abs() - 0.1, (p[1] - 0.09).abs() - 0.002, (p[2] + 0.04).abs() - 0.01];
        let out = d.iter().map(|v| v.max(0.0).powi(2)).sum::<f64>().sqrt();
        if out > 0.0 { out } else { d.iter().fold(f64::MIN, |a, &b| a.max(b)) }
    };
    for i in 0..run.time.len() {
        let (x, theta) = (run.q(i)[0], run.q(i)[1]);
        let least = (0..=400)
            .map(|k| 0.06 + 0.04 * f64::from(k) / 400.0)
            .map(|y| outside([x, y * theta.cos(), y * theta.sin()]))
            .fold(f64::MAX, f64::min);
        assert!(least > 0.003 - 1e-6, "t = {}: the rod's axis {least} m from the rail", run.time[i]);
    }
}

/// Undamped, the turned box's carriage (100 N/m on 0.1 kg, 10.5 N) swings
/// about the rail's end, and the box's edge comes to lie flush on the
/// rail's end face, across its top and its upright edges: where the top
/// crossing runs off the rail's corner, the upright crossing, touching at
/// that instant, holds (handed to the corner, which sits on the box's
/// edge where its normal is undefined, the released edges read 30 bands
/// deep and the run stopped at 2.2 to 2.5 s). While the box's edge lies
/// flush on the end face, the crossing with its top edge holds until it
/// runs off that edge's end (the edges' normal is the face's, on the bound
/// of that edge's faces, which counts as within: read as its margin, 0 to
/// rounding, it let go and touched again at every step, 3,991 changes in
/// 3 s). Regression guard and geometry: the run reaches 3 s with fewer
/// than 100 changes (23, each a landing, a leaving or a hand-off), its
/// energy never grows ([`never_gains`]), and at every sample no point of
/// the box's edges (40 per edge) lies inside the rail.
#[test]
fn an_undamped_box_struck_back_and_forth_at_the_rails_end_runs_on_outside_it() {
    let run = undamped(TURNED, 100.0, 10.5, 3.0, 0.05);
    assert!(run.changes.len() < 100, "{} changes", run.changes.len());
    never_gains(&run, 10.5);
    // The box's edges in its own frame, turned 45° about y, 80 mm along the lid.
    let half = [0.01, 0.02, 0.005];
    let (c, s) = (0.5f64.sqrt(), 0.5f64.sqrt());
    let mut points = Vec::new();
    for axis in 0..3 {
        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
        for (sa, sb, k) in edge_points(40) {
            let mut p = [0.0; 3];
            (p[axis], p[a], p[b]) = (half[axis] * (2.0 * f64::from(k) / 40.0 - 1.0), sa * half[a], sb * half[b]);
            points.push([c * p[0] + s * p[2], 0.08 + p[1], -s * p[0] + c * p[2]]);
        }
    }
    for i in 0..run.time.len() {
        let (x, theta) = (run.q(i)[0], run.q(i)[1]);
        for p in &points {
            let w = [x + p[0], p[1] * theta.cos() - p[2] * theta.sin(), p[1] * theta.sin() + p[2] * theta.cos()];
            let depth = (0.1 - w[0].abs()).min(0.002 - (w[1] - 0.09).abs()).min(0.01 - (w[2] + 0.04).abs());
            assert!(depth < 1e-9, "t = {}: a point of the box's edge {depth} m inside the rail", run.time[i]);
        }
    }
}

/// Sampled every 5 ms, the box of
/// [`an_undamped_box_struck_back_and_forth_at_the_rails_end_runs_on_outside_it`]
/// runs off the rail's top edge at 1.19 s, where the rail's corner lies on
/// the box's edge between its lower face and its side: there the gap's
/// normal is either face's. Handed the touch and held on the side, the
/// corner's impact threw the lid up at 5.9 rad/s, and the next step, on
/// the lower face, pulled it down at 18.7: 0.253 J gained. Read ahead of
/// the state, the corner parts from the lower face as the box runs on, and
/// is not handed the touch: the lid falls free. Checked against energy
/// ([`never_gains`]) over 1.3 s.
#[test]
fn an_undamped_box_run_off_the_rails_end_falls_free_of_its_corner_without_gaining_energy() {
    let run = undamped(TURNED, 100.0, 10.5, 1.3, 0.005);
    never_gains(&run, 10.5);
}

/// The box of [`an_undamped_box_struck_back_and_forth_at_the_rails_end_runs_on_outside_it`]
/// on a rough rail (μ 0.3 and 1), sampled every 5 ms: its edge lies flush
/// on the rail's end face, and the box's corner at its end slides across
/// that face to the face's edge. Held against the rail itself, the corner
/// had to turn onto the next face in one step: Newton's method diverged on
/// every step across, the steps shrank to rounding, and either the run
/// stopped there (μ 0.3, at 0.318 s) or its last step threw the lid from
/// 4.4 to 21.9 rad/s (μ 1, 0.142 J gained at 0.215 s). Held against the
/// face's plane, it is let go where it slides past the edge. Checked: the
/// run reaches 1 s, its energy never grows ([`never_gains`]), and at every
/// sample each touching point lies on the rail's surface, to 1e-12 m (on
/// the face's plane past its edge, it would hold the box up on nothing).
#[test]
fn an_undamped_box_sliding_off_the_rails_end_face_with_friction_never_gains_energy() {
    for mu in [0.3, 1.0] {
        let rough =
            carried(TURNED, 100.0, 10.5).replace("name = \"rail\"\n", &format!("name = \"rail\"\nfriction = {mu:?}\n"));
        let text = format!(
            "{rough}[[body]]\nname = \"cart\"\nmass = 0.1\n[[body]]\nname = \"lid\"\nmass = 0.1\ncom = [0.0, 0.08, 0.0]\n"
        );
        let run = from_rest(
            &text,
            flexure::dynamics::integrate::MotionSettings { duration: 1.0, every: 0.005, ..Default::default() },
        );
        never_gains(&run, 10.5);
        for (i, contacts) in run.contacts.iter().enumerate() {
            for k in contacts.iter().filter(|k| k.state != ContactMode::Open) {
                let p = &k.point;
                let d = [p[0].abs() - 0.1, (p[1] - 0.09).abs() - 0.002, (p[2] + 0.04).abs() - 0.01];
                let off = d.iter().map(|v| v.max(0.0).powi(2)).sum::<f64>().sqrt();
                assert!(off < 1e-12, "μ {mu}, t = {}: a touching point {off} m off the rail: {k:?}", run.time[i]);
            }
        }
    }
}

/// A ball (radius 10 mm, 0.1 kg on a vertical slider, on a carriage of
/// 0.1 kg sprung at 1 N/m along x) dropped 1 mm onto a box's top face and
/// pushed across it (0.2 N along x, 2 N down) to its edge. A ball's centre
/// lies off the surface, where the distance to the box turns smoothly
/// round its edge: held, it rolls over the edge and leaves only where its
/// push falls to zero, its centre past the edge (by 5.2 mm, measured).
/// Held against the face's plane like a sharp corner, it was let go at
/// the edge and touched again round it (on 778b24c). Checked: the contact opens once, with the centre more than
/// 1 mm past the edge, no sample finds the ball in the box (its centre
/// at least its radius from it, to 1e-9 m), and the energy
/// $E - F\cdot x$ never grows ([`never_grows`], to 1e-6 J).
#[test]
fn a_ball_pushed_over_a_boxs_edge_rolls_round_it_before_it_leaves() {
    use flexure::dynamics::integrate::MotionSettings;
    let text = "dimension = 3\n[[joint]]\nname = \"x\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"c\"\naxis = [1.0, 0.0, 0.0]\nstiffness = 1.0\n\
        [[joint]]\nname = \"z\"\nkind = \"prismatic\"\nparent = \"c\"\nchild = \"b\"\naxis = [0.0, 0.0, 1.0]\nstiffness = 0.0\n\
        [[geom]]\nname = \"table\"\nbody = \"ground\"\nshape = \"box\"\norigin = [0.0, 0.0, -0.05]\nhalf_extents = [0.05, 0.05, 0.05]\n\
        [[geom]]\nname = \"ball\"\nbody = \"b\"\nshape = \"sphere\"\norigin = [0.0, 0.0, 0.011]\nradius = 0.01\n\
        [[force]]\nname = \"push\"\nbody = \"b\"\nat = [0.0, 0.0, 0.011]\nforce = [0.2, 0.0, -2.0]\n\
        [[body]]\nname = \"c\"\nmass = 0.1\n[[body]]\nname = \"b\"\nmass = 0.1\ncom = [0.0, 0.0, 0.011]\n";
    let run = from_rest(text, MotionSettings { duration: 0.5, every: 0.01, ..Default::default() });
    let opened: Vec<_> = run.changes.iter().filter(|c| c.state == ContactMode::Open).collect();
    assert_eq!(opened.len(), 1, "{:?}", run.changes);
    // The centre at the last sample before it opened.
    let after = run.time.iter().position(|&t| t > opened[0].time).expect("a sample after it opened");
    assert!(run.q(after - 1)[0] > 0.051, "opened with the centre at x = {}", run.q(after - 1)[0]);
    for i in 0..run.time.len() {
        let (x, z) = (run.q(i)[0], 0.011 + run.q(i)[1]);
        // The box spans x in ±0.05 and z in [-0.1, 0].
        let (dx, dz) = ((x.abs() - 0.05).max(0.0), ((z + 0.05).abs() - 0.05).max(0.0));
        let out = dx.hypot(dz);
        assert!(out > 0.01 - 1e-9, "t = {}: the ball's centre {out} m from the box", run.time[i]);
    }
    never_grows(&run, "the ball", |q| -0.2 * q[0] + 2.0 * q[1]);
}

/// A box (half extents 20 mm, turned 0.3 rad about z) dropped onto a can's
/// lid (radius and half length 50 mm), a can (radius 15 mm, half length
/// 20 mm) dropped onto a box's top face (half extents 50 mm), a box
/// (half extents 40 mm, turned 45° about z) dropped onto that box, and a
/// box like it (aligned over it, and 30 mm off along x): each
/// on a vertical slider (0.1 kg, 1 N/m) on a carriage (0.1 kg, 10 N/m along
/// x), pushed 3 N down and 1 N along x, lands and slides off the edge (or
/// sticks, the turned box at μ 0.3), with μ 0 and 0.3.
///
/// A cylinder's side is its axis rounded by its radius, and
/// past the axis's ends that reads less than the lid does: the box read
/// touching the can 47 mm above its lid (the run stopped at 0.015 s, a
/// guard 1.4e7 bands past just after), and the can read touching 2.6 mm
/// above the box (184 switches at one instant at 0.056 s). Read as the
/// can's own gap there, the box's edge over the lid's centre still read
/// 28 mm deep in the side at the landing: the side applies only while an
/// edge's depth in it is less than its way to the lid.
///
/// The turned box lands face on face with all its corners outside the box
/// below and the box's outside it: only the crossings of the two faces'
/// outlines carry it, two edges flush on each other's faces. Past the
/// touch they read no depth, and the solve went through there
/// (`a_box_pushed_flat_onto_a_box_rests_on_its_face`); the motion lands
/// on a gap as it enters its band, and passes here with or without that.
/// The box like it lands on crossings at the ends of edges, whose margin
/// stays at its bound as it slides: read in the band a guard lands in,
/// each step aimed at another event let it go, 1,452 changes in 1 s
/// aligned and 3,342 off along x.
///
/// Checked: each run reaches 1 s with fewer than 50 changes (the can hands
/// its touch on from rim point to rim point as it slides off: 24), its energy never grows
/// ([`never_grows`], $E - F\cdot x$, to 1e-6 J), and at every sample no point of the
/// falling geom's surface (a grid on each face) lies inside the other.
#[test]
fn boxes_and_a_can_dropped_on_a_lid_land_and_slide_off() {
    use flexure::dynamics::integrate::MotionSettings;
    let can = |r: f64, h: f64| format!("shape = \"cylinder\"\nhalf_length = {h:?}\nradius = {r:?}");
    let cube = |e: f64| format!("shape = \"box\"\nhalf_extents = [{e:?}, {e:?}, {e:?}]");
    // A grid on the small can's side and lids.
    let can_grid: Vec<[f64; 3]> = (0..=20)
        .flat_map(|k| {
            (0..32).flat_map(move |j| {
                let (phi, z) = (std::f64::consts::TAU * f64::from(j) / 32.0, -0.02 + 0.002 * f64::from(k));
                [0.015, 0.0075, 0.0]
                    .into_iter()
                    .filter(move |&r| r == 0.015 || k % 20 == 0)
                    .map(move |r| [r * phi.cos(), r * phi.sin(), z])
            })
        })
        .collect();
    // The depth of a world point in the geom below.
    let in_can = |w: [f64; 3]| (0.05 - w[0].hypot(w[1])).min(0.05 - w[2].abs());
    let in_box = |w: [f64; 3]| w.iter().fold(f64::MAX, |d, c| d.min(0.05 - c.abs()));
    type Scene<'a> = (String, String, f64, [f64; 2], Vec<[f64; 3]>, &'a dyn Fn([f64; 3]) -> f64);
    let scenes: [Scene; 5] = [
        (can(0.05, 0.05), cube(0.02), 0.3, [0.03, 0.02], cube_faces(0.02), &in_can),
        (cube(0.05), can(0.015, 0.02), 0.0, [0.03, 0.02], can_grid, &in_box),
        (cube(0.05), cube(0.04), std::f64::consts::FRAC_PI_4, [0.03, 0.02], cube_faces(0.04), &in_box),
        (cube(0.05), cube(0.05), 0.0, [0.0, 0.0], cube_faces(0.05), &in_box),
        (cube(0.05), cube(0.05), 0.0, [0.03, 0.0], cube_faces(0.05), &in_box),
    ];
    for (below, above, yaw, [x, y], points, depth) in &scenes {
        for mu in [0.0, 0.3] {
            let text = format!(
                "dimension = 3\n[[joint]]\nname = \"side\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"c\"\naxis = [1.0, 0.0, 0.0]\nstiffness = 10.0\n\
                 [[joint]]\nname = \"drop\"\nkind = \"prismatic\"\nparent = \"c\"\nchild = \"b\"\naxis = [0.0, 0.0, 1.0]\nstiffness = 1.0\n\
                 [[geom]]\nname = \"B\"\nbody = \"ground\"\n{below}\nfriction = {mu:?}\n\
                 [[geom]]\nname = \"A\"\nbody = \"b\"\n{above}\norigin = [{x:?}, {y:?}, 0.12]\nrpy = [0.0, 0.0, {yaw:?}]\n\
                 [[force]]\nname = \"push\"\nbody = \"b\"\nat = [{x:?}, {y:?}, 0.12]\nforce = [1.0, 0.0, -3.0]\n\
                 [[body]]\nname = \"c\"\nmass = 0.1\n[[body]]\nname = \"b\"\nmass = 0.1\ncom = [{x:?}, {y:?}, 0.12]\n"
            );
            let run = from_rest(&text, MotionSettings { duration: 1.0, every: 0.005, ..Default::default() });
            assert!(!run.changes.is_empty(), "{above} never landed");
            let n = run.changes.len();
            assert!(n < 50, "{above} at ({x}, {y}), μ {mu}: {n} changes");
            never_grows(&run, &format!("{above} at ({x}, {y}), μ {mu}"), |q| -q[0] + 3.0 * q[1]);
            let (cos, sin) = (yaw.cos(), yaw.sin());
            for i in 0..run.time.len() {
                let centre = [x + run.q(i)[0], *y, 0.12 + run.q(i)[1]];
                for p in points {
                    let w =
                        [centre[0] + cos * p[0] - sin * p[1], centre[1] + sin * p[0] + cos * p[1], centre[2] + p[2]];
                    let d = depth(w);
                    assert!(d < 1e-9, "{above}, μ {mu}, t = {}: a point {d} m inside", run.time[i]);
                }
            }
        }
    }
}

/// An 11 × 11 grid on each face of a cube of half extent `e` (its own frame).
fn cube_faces(e: f64) -> Vec<[f64; 3]> {
    (0..3)
        .flat_map(|ax| {
            [-1.0, 1.0].into_iter().flat_map(move |s| {
                (0..=10).flat_map(move |a| {
                    (0..=10).map(move |b| {
                        let mut v = [0.0; 3];
                        (v[ax], v[(ax + 1) % 3], v[(ax + 2) % 3]) =
                            (s, -1.0 + 0.2 * f64::from(a), -1.0 + 0.2 * f64::from(b));
                        v.map(|c| e * c)
                    })
                })
            })
        })
        .collect()
}

/// Each corner sign pair of an edge and each of its `n` + 1 points along it.
fn edge_points(n: u32) -> impl Iterator<Item = (f64, f64, u32)> {
    [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)]
        .into_iter()
        .flat_map(move |(a, b)| (0..=n).map(move |k| (a, b, k)))
}

/// The spatial lid `text` given mass (0.1 kg at its box's centre) and
/// pushed from rest for `duration` s, sampled every 5 ms (tolerance 1e-8):
/// its run, which must reach the end.
fn swung(text: &str, duration: f64) -> flexure::dynamics::simulation::Simulation<flexure::space::Spatial> {
    use flexure::dynamics::integrate::MotionSettings;
    let moving = format!("{text}[[body]]\nname = \"lid\"\nmass = 0.1\ncom = [0.0, 0.08, 0.0]\n");
    from_rest(&moving, MotionSettings { duration, every: 0.005, tolerance: 1e-8, absolute: 1e-8, ..Default::default() })
}

/// Given mass and pushed from rest, the lid of
/// [`a_box_or_a_rod_meets_a_rail_or_a_rod_edge_across_edge_in_space`] swings down and lands
/// edge across edge on the rail, and rests where the statics put it (its
/// closed form): the angle to 1e-7 rad, the push to 1e-6 relative, at
/// every sample after the touch (sampled every 5 ms, one of them just after it).
#[test]
fn a_box_swung_onto_a_rail_rests_on_it_edge_across_edge() {
    let rail = "shape = \"box\"\norigin = [0.0, 0.09, -0.04]\nhalf_extents = [0.1, 0.002, 0.01]";
    let turned = "origin = [0.0, 0.08, 0.0]\nrpy = [0.0, 0.7853981633974483, 0.0]\nhalf_extents = [0.01, 0.02, 0.005]";
    let theta = root(|t| -0.092 * t.sin() - 0.03 * t.cos() + 0.015 * 0.5f64.sqrt());
    let push = (0.5 * theta + 20.0 * 0.1 * theta.cos()) / (0.092 * theta.cos() - 0.03 * theta.sin());
    let run = swung(&lid3(turned, rail, 20.0), 0.2);
    // The impact stops the lid (one coordinate): every sample after it rests there, pushed by N.
    let landed = run.changes.last().expect("a touch").time;
    for (i, &t) in run.time.iter().enumerate().filter(|(_, t)| **t > landed) {
        assert!((run.q(i)[0] - theta).abs() < 1e-7, "t = {t}: {:?} against {theta}", run.q(i));
        let k: Vec<_> = run.contacts[i].iter().filter(|k| k.state != ContactMode::Open).collect();
        assert_eq!(k.len(), 1, "t = {t}: {k:?}");
        assert!((k[0].normal_force - push).abs() < 1e-6 * push, "t = {t}: {} against {push}", k[0].normal_force);
        assert!((k[0].point[1] - 0.092).abs() < 1e-9 && (k[0].point[2] + 0.03).abs() < 1e-9, "{:?}", k[0]);
    }
}

/// Friction across two edges: the [`carried`] lid's turned box comes down
/// across the rail's outer top edge, now rough (μ = 0.2), while the drag
/// $F_x$ grows with the push. Free, the lid turns as
/// $k\theta = -0.2\lambda\cos\theta$ and the carriage slides $\lambda F_x/k_x$;
/// it touches at $\lambda_t = -k\theta_c/(0.2\cos\theta_c)$, $\theta_c$ the
/// angle of [`a_box_or_a_rod_meets_a_rail_or_a_rod_edge_across_edge_in_space`],
/// and stuck, the carriage stays where it was, the friction
/// $-(\lambda - \lambda_t)F_x$ along the edge. The push balances the hinge
/// as without friction (friction along x has no moment about it), and the
/// rail's tangent across the edge moves nothing the push does not hold:
/// its friction is indeterminate and taken 0 (the least friction,
/// `ContactKkt::prune`). Where $(1 - \lambda_t)F_x > \mu N$ it slips, and at
/// the full load $k_xx = F_x - \mu N$. The angle to 1e-12 rad, the forces to
/// 1e-9 relative, the slide to 1e-12 m, or stuck to 2e-11 m: a touch is
/// found once the gap passes $-10^{-10}\ell$ ($\ell$ = 1 m here), which the
/// lid, closing at 0.036 m per unit load, reaches $2.8\times10^{-9}$ of the
/// load late, and the stuck carriage stays where it was then, 8e-12 m
/// on. (Without the rows left out, the stuck force was taken as Newton
/// found it, pulling, and the path stalled at 52 % of the load.)
#[test]
fn a_box_dragged_along_a_rough_rails_edge_sticks_then_slips() {
    let z0 = -0.03;
    let theta = root(|t| -0.092 * t.sin() + z0 * t.cos() + 0.015 * 0.5f64.sqrt());
    let arm = 0.092 * theta.cos() + z0 * theta.sin();
    let push = (0.5 * theta + 0.2 * theta.cos()) / arm;
    let touch = -0.5 * theta / (0.2 * theta.cos());
    for (f_x, state) in [(0.3, ContactMode::Stick), (5.0, ContactMode::Slip)] {
        let text = carried(TURNED, 100.0, f_x).replacen(
            "half_extents = [0.1, 0.002, 0.01]\n",
            "half_extents = [0.1, 0.002, 0.01]\nfriction = 0.2\n",
            1,
        );
        let s = solve(&spatial_from_toml(&text).unwrap(), &Settings::default()).unwrap();
        let (x, friction) = match state {
            ContactMode::Stick => (touch * f_x / 100.0, -(1.0 - touch) * f_x),
            _ => ((f_x - 0.2 * push) / 100.0, -0.2 * push),
        };
        let within = if state == ContactMode::Stick { 2e-11 } else { 1e-12 };
        assert!((s.q[0] - x).abs() < within && (s.q[1] - theta).abs() < 1e-12, "{f_x}: {:?} against {x}, {theta}", s.q);
        let k: Vec<_> = s.contacts.iter().filter(|k| k.state != ContactMode::Open).collect();
        assert_eq!(k.len(), 1, "{f_x}: {k:?}");
        assert_eq!(k[0].state, state, "{f_x}: {k:?}");
        assert!((k[0].normal_force - push).abs() < 1e-9 * push, "{f_x}: {} against {push}", k[0].normal_force);
        let f = &k[0].friction_force;
        assert!(
            (f[0] - friction).abs() < 1e-9 * push && f[1].abs() < 1e-9 * push && f[2].abs() < 1e-9 * push,
            "{f_x}: {f:?}"
        );
    }
}

/// The same drag in motion, the whole scene turned 30° about z (the rail,
/// the carriage's axis, the hinge, the box and the loads), so that no
/// tangent of the rail's edge is a world axis: given mass and damping and
/// pushed from rest, the lid comes down across the rough edge and rests
/// stuck. Its push is the frictionless one of
/// [`a_box_dragged_along_a_rough_rails_edge_sticks_then_slips`] (the
/// friction across the edge is indeterminate and taken 0: the least
/// friction, whatever the world's axes), to 1e-6 relative after 3 s; its
/// friction lies along the rail, to 1e-9 N across it, and balances the
/// carriage's spring and drag along it, $f = k_xx - F_x$, to 1e-6 N.
/// (With the tangents of the world's axes it read 0.9603 N against
/// 0.9680 N, the friction leaning 10° off the rail.)
#[test]
fn a_turned_box_stuck_on_a_rough_rail_in_motion_reads_the_frictionless_push() {
    use flexure::dynamics::integrate::MotionSettings;
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let turn = |v: [f64; 3]| format!("[{:?}, {:?}, {:?}]", c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]);
    let (axis, yaw) = (turn([1.0, 0.0, 0.0]), 30f64.to_radians());
    let text = format!(
        "dimension = 3\n[[joint]]\nname = \"carriage\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"cart\"\naxis = {axis}\nstiffness = 100.0\ndamping = 5.0\n\
         [[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"cart\"\nchild = \"lid\"\naxis = {axis}\nstiffness = 0.5\ndamping = 0.01\n\
         [[geom]]\nname = \"block\"\nbody = \"lid\"\nshape = \"box\"\norigin = {}\nrpy = [0.0, 0.7853981633974483, {yaw:?}]\nhalf_extents = [0.01, 0.02, 0.005]\n\
         [[geom]]\nname = \"rail\"\nbody = \"ground\"\nshape = \"box\"\norigin = {}\nrpy = [0.0, 0.0, {yaw:?}]\nhalf_extents = [0.1, 0.002, 0.01]\nfriction = 0.2\n\
         [[force]]\nname = \"push\"\nbody = \"lid\"\nat = {}\nforce = {}\n\
         [[body]]\nname = \"cart\"\nmass = 0.1\n[[body]]\nname = \"lid\"\nmass = 0.1\ncom = {}\n",
        turn([0.0, 0.08, 0.0]),
        turn([0.0, 0.09, -0.04]),
        turn([0.0, 0.1, 0.0]),
        turn([0.3, 0.0, -2.0]),
        turn([0.0, 0.08, 0.0]),
    );
    let theta = root(|t| -0.092 * t.sin() - 0.03 * t.cos() + 0.015 * 0.5f64.sqrt());
    let push = (0.5 * theta + 0.2 * theta.cos()) / (0.092 * theta.cos() - 0.03 * theta.sin());
    let run = from_rest(&text, MotionSettings { duration: 3.0, every: 0.5, ..Default::default() });
    let last = run.time.len() - 1;
    let k: Vec<_> = run.contacts[last].iter().filter(|k| k.state != ContactMode::Open).collect();
    assert!(k.len() == 1 && k[0].state == ContactMode::Stick, "{k:?}");
    assert!((k[0].normal_force - push).abs() < 1e-6 * push, "{} against {push}", k[0].normal_force);
    let f = &k[0].friction_force;
    let (along, across) = (c * f[0] + s * f[1], -s * f[0] + c * f[1]);
    assert!(across.abs() < 1e-9 && f[2].abs() < 1e-9, "{f:?}");
    assert!((along - (100.0 * run.q(last)[0] - 0.3)).abs() < 1e-6, "{along} against {}", 100.0 * run.q(last)[0] - 0.3);
}

/// A corner stuck on a rough floor that stops the lid's one coordinate:
/// the push alone holds it, and the friction, indeterminate, is taken 0
/// (the least friction): the push of the frictionless lid of
/// [`a_lid_pushed_onto_a_floor_rests_on_its_boxs_corner`], to 1e-9
/// relative, stuck. (Before the rows were left out, the stuck corner read
/// a push of 20.90 N against 18.93 N, and slipping, as measured on the
/// solve before this work.)
#[test]
fn a_lid_stuck_on_a_rough_floor_reads_the_frictionless_push() {
    let block = "origin = [0.08, 0.0]\nhalf_extents = [0.02, 0.005]";
    let floor = "shape = \"plane\"\norigin = [0.0, -0.03]\nnormal = [0.0, 1.0]\nfriction = 0.3";
    let theta = root(|t| 0.1 * t.sin() - 0.005 * t.cos() + 0.03);
    let arm = 0.1 * theta.cos() + 0.005 * theta.sin();
    let push = (0.5 * theta + 2.0 * theta.cos()) / arm;
    let s = solve(&from_toml(&lid(block, floor, 20.0)).unwrap(), &Settings::default()).unwrap();
    assert!((s.q[0] - theta).abs() < 1e-12, "{} against {theta}", s.q[0]);
    let c = &s.contacts[0];
    assert_eq!((s.contacts.len(), c.state), (1, ContactMode::Stick), "{:?}", s.contacts);
    assert!((c.normal_force - push).abs() < 1e-9 * push, "{} against {push}", c.normal_force);
    assert!(c.friction_force.iter().all(|f| f.abs() < 1e-9 * push), "{:?}", c.friction_force);
}

/// A box's sharp corner is one material point: stuck, it is pinned where
/// it touches, and slipping, it slides (it does not roll). A foot on a
/// sprung slider (100 N/m along z) and a soft hinge about x, its box
/// tilted 0.05 rad, pushed down 5 N onto a rough floor (μ = 0.3): it lands
/// on its lower edge, tips flat onto its face, and rests there. Closed
/// forms: the face flat (the hinge at −0.05 rad) with the box's centre
/// its half height above the floor, the slide $0.01 - 0.012\cos 0.05$;
/// the pushes summing to the push less the spring's pull along z (the
/// friction is horizontal), each friction within its cone. (Taken as a
/// rolling ball, the corner's slide stalled the path at 5.1 % of the load.)
#[test]
fn a_tilted_foot_lands_flat_on_a_rough_floor_on_its_sharp_corners() {
    let text = "dimension = 3\n[[joint]]\nname = \"slide\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"carriage\"\naxis = [0.0, 0.0, 1.0]\nstiffness = 100.0\n\
        [[joint]]\nname = \"tilt\"\nkind = \"revolute\"\nparent = \"carriage\"\nchild = \"foot\"\naxis = [1.0, 0.0, 0.0]\nstiffness = 0.01\n\
        [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\nnormal = [0.0, 0.0, 1.0]\nfriction = 0.3\n\
        [[geom]]\nname = \"sole\"\nbody = \"foot\"\nshape = \"box\"\norigin = [0.0, 0.0, 0.012]\nrpy = [0.05, 0.0, 0.0]\nhalf_extents = [0.005, 0.01, 0.01]\n\
        [[force]]\nname = \"push\"\nbody = \"foot\"\nat = [0.0, 0.0, 0.0]\nforce = [0.0, 0.0, -5.0]\n";
    let s = solve(&spatial_from_toml(text).unwrap(), &Settings::default()).unwrap();
    let slide = 0.01 - 0.012 * 0.05f64.cos();
    assert!((s.q[0] - slide).abs() < 1e-12 && (s.q[1] + 0.05).abs() < 1e-12, "{:?} against {slide}, -0.05", s.q);
    let touching: Vec<_> = s.contacts.iter().filter(|c| c.state != ContactMode::Open).collect();
    let pushes: f64 = touching.iter().map(|c| c.normal_force).sum();
    assert!((pushes - (5.0 + 100.0 * slide)).abs() < 1e-9, "{pushes}");
    for c in &touching {
        let f = c.friction_force.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!(f <= 0.3 * c.normal_force * (1.0 + 1e-9) && c.friction_force[2] == 0.0, "{c:?}");
        assert!(c.point[2].abs() < 1e-12, "{c:?}");
    }
    assert!(touching.iter().any(|c| c.state == ContactMode::Stick), "{touching:?}");
}

/// A cylinder's side is its axis rounded by its radius: across the rail's
/// edge it is an edge pair, exact. The lid carries a can lying along its
/// $y$ (radius $R$ = 4 mm, so its axis is the lid's $y$ axis at $z = 0$):
/// it meets the rail's outer top edge where that edge is at $z = -R$ in
/// the lid's frame, and $N = (k\theta + F\,0.1\cos\theta)/y_l$ as for the box.
/// The angle to 1e-12 rad and the push to 1e-9 relative.
#[test]
fn a_cans_side_meets_a_rail_edge_across_edge() {
    let rail = "shape = \"box\"\norigin = [0.0, 0.09, -0.04]\nhalf_extents = [0.1, 0.002, 0.01]";
    let can = "shape = \"cylinder\"\norigin = [0.0, 0.08, 0.0]\nrpy = [-1.5707963267948966, 0.0, 0.0]\nhalf_length = 0.02\nradius = 0.004";
    let theta = root(|t| -0.092 * t.sin() - 0.03 * t.cos() + 0.004);
    let push = (0.5 * theta + 20.0 * 0.1 * theta.cos()) / (0.092 * theta.cos() - 0.03 * theta.sin());
    let text = lid3(can, rail, 20.0).replacen("shape = \"box\"\n", "", 1);
    let s = solve(&spatial_from_toml(&text).unwrap(), &Settings::default()).unwrap();
    assert!((s.q[0] - theta).abs() < 1e-12, "{} against {theta}", s.q[0]);
    assert_eq!(s.contacts.len(), 1, "{:?}", s.contacts);
    let k = &s.contacts[0];
    assert!((k.normal_force - push).abs() < 1e-9 * push, "{} against {push}", k.normal_force);
    assert!((k.point[1] - 0.092).abs() < 1e-12 && (k.point[2] + 0.03).abs() < 1e-12, "{k:?}");
}

/// A cylinder's rim is watched at 32 points, a regular polygon inscribed
/// in it (`RIM_POINTS`). The lid carries a can standing on it (radius
/// $R$ = 10 mm, half length $h$ = 5 mm), turned 0.1 rad about its axis so
/// that no rim point is the lowest as the lid turns down onto a floor 30 mm
/// below the hinge. The rim's lowest point is at $y_l = 0.08 + R$; the
/// polygon's, at $0.08 + R\cos\delta$, $\delta$ = 0.0964 rad from the nearest
/// point. The solve stops the lid where the polygon's point touches,
/// $(0.08 + R\cos\delta)\sin\theta - h\cos\theta = -0.03$, to 1e-12 rad, and
/// there the rim sinks into the floor by less than the documented
/// $R(1 - \cos(\pi/32))$.
#[test]
fn a_cans_rim_meets_a_floor_at_its_polygons_point_within_the_bound() {
    let floor = "shape = \"plane\"\norigin = [0.0, 0.0, -0.03]\nnormal = [0.0, 0.0, 1.0]";
    let can =
        "shape = \"cylinder\"\norigin = [0.0, 0.08, 0.0]\nrpy = [0.0, 0.0, 0.1]\nhalf_length = 0.005\nradius = 0.01";
    let (r, h) = (0.01, 0.005);
    let step = std::f64::consts::TAU / 32.0;
    let delta =
        (0..32).map(|k| (0.1 + k as f64 * step - std::f64::consts::FRAC_PI_2).abs()).fold(f64::INFINITY, f64::min);
    assert!((delta - 0.0963495).abs() < 1e-6, "{delta}");
    let theta = root(|t| (0.08 + r * delta.cos()) * t.sin() - h * t.cos() + 0.03);
    let text = lid3(can, floor, 20.0).replacen("shape = \"box\"\n", "", 1);
    let s = solve(&spatial_from_toml(&text).unwrap(), &Settings::default()).unwrap();
    assert!((s.q[0] - theta).abs() < 1e-12, "{} against {theta}", s.q[0]);
    let sunk = -((0.08 + r) * theta.sin() - h * theta.cos() + 0.03);
    let bound = r * (1.0 - (std::f64::consts::PI / 32.0).cos());
    assert!(sunk > 0.0 && sunk < bound, "{sunk} against {bound}");
}

/// A cube of half extent `e` at `at`, turned `yaw` about z, on a vertical
/// slider (100 N/m) pushed down by 20 N onto the geom `below` (its shape's
/// keys) at the origin.
fn pushed_flat(below: &str, at: [f64; 3], yaw: f64, e: f64) -> String {
    let [x, y, z] = at;
    format!(
        "dimension = 3\n[[joint]]\nname = \"slide\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"b\"\naxis = [0.0, 0.0, 1.0]\nstiffness = 100.0\n\
         [[geom]]\nname = \"B\"\nbody = \"ground\"\n{below}\n\
         [[geom]]\nname = \"A\"\nbody = \"b\"\nshape = \"box\"\norigin = [{x:?}, {y:?}, {z:?}]\nrpy = [0.0, 0.0, {yaw:?}]\nhalf_extents = [{e:?}, {e:?}, {e:?}]\n\
         [[force]]\nname = \"push\"\nbody = \"b\"\nat = [{x:?}, {y:?}, {z:?}]\nforce = [0.0, 0.0, -20.0]\n"
    )
}

/// Two boxes that rest face on face are apart, not crossed: a box on a
/// vertical slider (100 N/m) pushed down by 20 N lands flat on a box 0.1 m
/// below, offset and turned about the vertical, where a bottom edge of one
/// lies across a side edge of the other (their lines cross 0.08 m apart
/// along a normal that is a face's normal of each, which is no depth). It
/// rests at $q = -0.1$ with the push $20 - 100\cdot0.1 = 10$ N, to 1e-12 m and
/// 1e-9 N; and a file of the two at rest face on face loads. Turned 45°
/// (centred, and 20 mm off along x), no corner of either lies inside the
/// other's face: the crossings of the two outlines carry it, two edges
/// flush on each other's faces, and it went through (stopped at half the
/// load as passed through) where their crossing read no depth. Aligned
/// over it, every corner sits on the other's edges, where no gap reads
/// depth: it went through silently, to $q = -0.2$. 30 mm off along x, it
/// stopped as passed through.
#[test]
fn a_box_pushed_flat_onto_a_box_rests_on_its_face() {
    let below = "shape = \"box\"\nhalf_extents = [0.05, 0.05, 0.05]";
    let text = |dx: f64, dy: f64, yaw: f64, z: f64| pushed_flat(below, [dx, dy, z], yaw, 0.05);
    let turned = std::f64::consts::FRAC_PI_4;
    let cases = [
        (0.03, 0.02, 0.3),
        (0.05, 0.05, 0.0),
        (0.03, 0.02, 0.0),
        (0.0, 0.0, turned),
        (0.02, 0.0, turned),
        (0.0, 0.0, 0.0),
        (0.03, 0.0, 0.0),
    ];
    for (dx, dy, yaw) in cases {
        let s = solve(&spatial_from_toml(&text(dx, dy, yaw, 0.2)).unwrap(), &Settings::default()).unwrap();
        assert!((s.q[0] + 0.1).abs() < 1e-12, "({dx}, {dy}, {yaw}): {}", s.q[0]);
        let total: f64 = s.contacts.iter().map(|k| k.normal_force).sum();
        assert!((total - 10.0).abs() < 1e-9, "({dx}, {dy}, {yaw}): {total}");
        assert!(spatial_from_toml(&text(dx, dy, yaw, 0.1)).is_ok(), "({dx}, {dy}, {yaw}) at rest face on face");
    }
}

/// The tipping box of [`a_box_tipped_onto_a_box_of_its_width_rests_on_its_corner_or_face`],
/// given mass (0.1 kg each for the carriage and the box, $10^{-4}$ kg·m² about
/// each axis) and let go from rest, aligned over the box below and 1 mm off
/// along y, with μ 0 and 0.3, steps to $10^{-10}$: it lands on its corner,
/// bounces on its edges and lands flat. At μ 0.3 the landing stopped the
/// run at 0.0495 s, 336 changes at one instant: the crossing at one end of
/// the box's far edge pulled, was let go and handed its touch to the
/// crossing at the edge's other end, which pulled too. A contact that pulls
/// now hands its touch to none. Checked: each run reaches 0.3 s, its energy
/// with the push's potential never grows ([`never_grows`], to 1e-6 J), and
/// no point of the box's faces (an 11 × 11 grid on each) lies inside the box below;
/// at μ 0.3 it rests flat and stuck, $q = (-0.1, 0)$ to 1e-9, on its edge
/// over the box's, pushed by $20 - 100\cdot0.1 = 10$ N and held by
/// the friction that balances the turn, $(0.6 - 0.05\cdot10)/0.05 = 2$ N
/// (within its $\mu N = 3$ N), to 1e-6 N.
#[test]
fn a_box_tipping_onto_a_box_of_its_width_lands_and_rests() {
    use flexure::dynamics::integrate::MotionSettings;
    let grid = cube_faces(0.05);
    for y in [0.0, 0.001] {
        for mu in [0.0, 0.3] {
            let text = format!(
                "dimension = 3\n[[joint]]\nname = \"slide\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"c\"\naxis = [0.0, 0.0, 1.0]\nstiffness = 100.0\n\
                 [[joint]]\nname = \"tilt\"\nkind = \"revolute\"\nparent = \"c\"\nchild = \"b\"\norigin = [0.0, {y:?}, 0.2]\naxis = [0.0, 1.0, 0.0]\nstiffness = 1.0\n\
                 [[geom]]\nname = \"B\"\nbody = \"ground\"\nshape = \"box\"\nhalf_extents = [0.05, 0.05, 0.05]\nfriction = {mu:?}\n\
                 [[geom]]\nname = \"A\"\nbody = \"b\"\nshape = \"box\"\nhalf_extents = [0.05, 0.05, 0.05]\n\
                 [[force]]\nname = \"push\"\nbody = \"b\"\nat = [0.03, 0.0, 0.0]\nforce = [0.0, 0.0, -20.0]\n\
                 [[body]]\nname = \"c\"\nmass = 0.1\n\
                 [[body]]\nname = \"b\"\nmass = 0.1\ninertia = [[1e-4, 0.0, 0.0], [0.0, 1e-4, 0.0], [0.0, 0.0, 1e-4]]\n"
            );
            let motion =
                MotionSettings { duration: 0.3, every: 0.005, tolerance: 1e-10, absolute: 1e-10, ..Default::default() };
            let run = from_rest(&text, motion);
            let what = format!("({y}, μ {mu})");
            never_grows(&run, &what, |q| 20.0 * (q[0] - 0.03 * q[1].sin()));
            for i in 0..run.time.len() {
                let (z, (sin, cos)) = (0.2 + run.q(i)[0], run.q(i)[1].sin_cos());
                for p in &grid {
                    let w = [p[0] * cos + p[2] * sin, y + p[1], z - p[0] * sin + p[2] * cos];
                    let depth = w.iter().fold(f64::MAX, |d, c| d.min(0.05 - c.abs()));
                    assert!(depth < 1e-9, "{what}, t = {}: a point {depth} m inside", run.time[i]);
                }
            }
            if mu > 0.0 {
                let last = run.time.len() - 1;
                let q = run.q(last);
                assert!((q[0] + 0.1).abs() < 1e-9 && q[1].abs() < 1e-9, "{what}: rests at {q:?}");
                let touching = &run.contacts[last];
                let push: f64 = touching.iter().map(|k| k.normal_force).sum();
                let friction = (0..3).map(|c| touching.iter().map(|k| k.friction_force[c]).sum::<f64>());
                let friction = friction.map(|f| f * f).sum::<f64>().sqrt();
                assert!((push - 10.0).abs() < 1e-6 && (friction - 2.0).abs() < 1e-6, "{what}: {push} N, {friction} N");
                assert!(touching.iter().all(|k| k.state != ContactMode::Slip), "{what}: slipping at rest");
            }
        }
    }
}

/// In the plane, a box (half extents 50 mm) on a vertical slider
/// (100 N/m) pushed down by 20 N lands flat on a box like it 0.2 m below,
/// aligned over it and 30 mm off: it rests at $q = -0.1$ with the push
/// $20 - 100\cdot0.1 = 10$ N, to 1e-12 m and 1e-9 N. Aligned, its
/// corners lie on the lines of the other's sides, facing the same way, and
/// read no depth below its top: it went through silently, to $q = -0.2$.
/// In space the same scene is [`a_box_pushed_flat_onto_a_box_rests_on_its_face`].
#[test]
fn a_rectangle_pushed_flat_onto_one_of_its_width_rests_on_it_in_the_plane() {
    for dx in [0.0, 0.03] {
        let text = format!(
            "[[joint]]\nname = \"slide\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"b\"\nstiffness = 100.0\norigin = [0.0, 0.0, 1.5707963267948966]\n\
             [[geom]]\nname = \"B\"\nbody = \"ground\"\nshape = \"box\"\nhalf_extents = [0.05, 0.05]\n\
             [[geom]]\nname = \"A\"\nbody = \"b\"\nshape = \"box\"\norigin = [0.2, {dx:?}]\nhalf_extents = [0.05, 0.05]\n\
             [[force]]\nname = \"push\"\nbody = \"b\"\nat = [0.2, {dx:?}]\nforce = [0.0, -20.0]\n"
        );
        let s = solve(&from_toml(&text).unwrap(), &Settings::default()).unwrap();
        assert!((s.q[0] + 0.1).abs() < 1e-12, "{dx}: {}", s.q[0]);
        let total: f64 = s.contacts.iter().map(|k| k.normal_force).sum();
        assert!((total - 10.0).abs() < 1e-9, "{dx}: {total}");
    }
}

/// A box on a vertical slider (100 N/m) pushed down by 20 N lands flat on
/// a can's lid (radius and half length 50 mm) 0.2 m below its centre: a
/// box of half extent $e$ rests at $q = e - 0.15$ with the push
/// $20 + 100q$, to 1e-12 m and 1e-9 N. Small ($e$ = 20 mm; offset and
/// turned, and centred) its corners carry it; as wide as the lid
/// ($e$ = 50 mm; aligned, and turned 45°) only the lid's rim does, whose
/// polygon's points lie on the box's face. Where the box overhangs the lid, the
/// can's side (its axis rounded, a capsule) must not read its corners
/// touching above the lid, nor the box's edges deep in it: read so (before
/// `01f4ebf`), the first stalled at 42 % of the load after 10,000 steps.
#[test]
fn a_box_pushed_flat_onto_a_cans_lid_rests_on_it() {
    let below = "shape = \"cylinder\"\nhalf_length = 0.05\nradius = 0.05";
    let text = |dx: f64, dy: f64, yaw: f64, e: f64| pushed_flat(below, [dx, dy, 0.2], yaw, e);
    let turned = std::f64::consts::FRAC_PI_4;
    for (dx, dy, yaw, e) in
        [(0.03, 0.02, 0.3, 0.02), (0.0, 0.0, 0.0, 0.02), (0.0, 0.0, 0.0, 0.05), (0.0, 0.0, turned, 0.05)]
    {
        let s = solve(&spatial_from_toml(&text(dx, dy, yaw, e)).unwrap(), &Settings::default()).unwrap();
        let q = e - 0.15;
        assert!((s.q[0] - q).abs() < 1e-12, "({dx}, {dy}, {yaw}, {e}): {} against {q}", s.q[0]);
        let total: f64 = s.contacts.iter().map(|k| k.normal_force).sum();
        assert!((total - (20.0 + 100.0 * q)).abs() < 1e-9, "({dx}, {dy}, {yaw}, {e}): {total}");
    }
}

/// A box (half extents 50 mm) on a vertical slider (100 N/m) and a hinge
/// about y at its centre (1 N·m/rad), 0.2 m above a box like it, pushed
/// down by 20 N 30 mm along its x axis, tips. Over the box below (centred,
/// and 1 mm off along y) it rests on its corner $(0.05, \mp0.05)$: with
/// $s = 0.05(\sin\theta + \cos\theta) - 0.15$ and $N = 20 + 100s$,
/// $0.6\cos\theta - 0.05N(\cos\theta - \sin\theta) = \theta$. Its hinge
/// 30 mm off along x, its face rests on the edge $x = 0.05$ below: with
/// $s = (0.05 + 0.02\sin\theta)/\cos\theta - 0.15$ and $N\cos\theta = 20 + 100s$,
/// $0.6\cos\theta - N((0.15 + s)\sin\theta + 0.02\cos\theta) = \theta$.
/// To 1e-9 rad and 1e-9 m, the push to 1e-7 N. Centred, the two boxes'
/// $\pm y$ faces lie in one plane facing the same way, and a corner on it
/// read no depth in the other box: the solve stopped at 44 % of the load
/// as passed through (46 % with the hinge off).
#[test]
fn a_box_tipped_onto_a_box_of_its_width_rests_on_its_corner_or_face() {
    let text = |x: f64, y: f64| {
        format!(
            "dimension = 3\n[[joint]]\nname = \"slide\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"c\"\naxis = [0.0, 0.0, 1.0]\nstiffness = 100.0\n\
             [[joint]]\nname = \"tilt\"\nkind = \"revolute\"\nparent = \"c\"\nchild = \"b\"\norigin = [{x:?}, {y:?}, 0.2]\naxis = [0.0, 1.0, 0.0]\nstiffness = 1.0\n\
             [[geom]]\nname = \"B\"\nbody = \"ground\"\nshape = \"box\"\nhalf_extents = [0.05, 0.05, 0.05]\n\
             [[geom]]\nname = \"A\"\nbody = \"b\"\nshape = \"box\"\nhalf_extents = [0.05, 0.05, 0.05]\n\
             [[force]]\nname = \"push\"\nbody = \"b\"\nat = [0.03, 0.0, 0.0]\nforce = [0.0, 0.0, -20.0]\n"
        )
    };
    // On its corner: the slide and the push at an angle, then the angle.
    let corner_slide = |t: f64| 0.05 * (t.sin() + t.cos()) - 0.15;
    let corner_push = |t: f64| 20.0 + 100.0 * corner_slide(t);
    let on_corner = root_in(0.0, 0.5, |t| 0.6 * t.cos() - 0.05 * corner_push(t) * (t.cos() - t.sin()) - t);
    // On the edge below.
    let edge_slide = |t: f64| (0.05 + 0.02 * t.sin()) / t.cos() - 0.15;
    let edge_push = |t: f64| (20.0 + 100.0 * edge_slide(t)) / t.cos();
    let on_edge =
        root_in(0.0, 0.5, |t| 0.6 * t.cos() - edge_push(t) * ((0.15 + edge_slide(t)) * t.sin() + 0.02 * t.cos()) - t);
    let cases = [
        (0.0, 0.0, on_corner, corner_slide(on_corner), corner_push(on_corner)),
        (0.0, 0.001, on_corner, corner_slide(on_corner), corner_push(on_corner)),
        (0.03, 0.0, on_edge, edge_slide(on_edge), edge_push(on_edge)),
    ];
    for (x, y, theta, slide, push) in cases {
        let s = solve(&spatial_from_toml(&text(x, y)).unwrap(), &Settings::default()).unwrap();
        assert!((s.q[1] - theta).abs() < 1e-9, "({x}, {y}): {} against {theta}", s.q[1]);
        assert!((s.q[0] - slide).abs() < 1e-9, "({x}, {y}): {} against {slide}", s.q[0]);
        let total: f64 = s.contacts.iter().map(|k| k.normal_force).sum();
        assert!((total - push).abs() < 1e-7, "({x}, {y}): {total} against {push}");
    }
}

/// Given mass and pushed from rest, the spatial lid swings its box onto a
/// floor 30 mm below the hinge, lands on its two leading corners
/// $(\pm0.01, 0.1, -0.005)$ (lid frame) at once, where
/// $0.1\sin\theta - 0.005\cos\theta = -0.03$, and rests there: every sample
/// after the touch, the first of them 2 ms after it (sampled every 5 ms),
/// reads the angle to 1e-7 rad and the corners' total push
/// $N = (k\theta + F\,0.1\cos\theta)/(0.1\cos\theta + 0.005\sin\theta)$ to 1e-6
/// relative (it read no push at the sample just after the touch, where the
/// step that landed had no multipliers yet).
#[test]
fn a_lid_swung_onto_a_floor_reads_its_push_from_the_first_sample_after() {
    let block = "origin = [0.0, 0.08, 0.0]\nhalf_extents = [0.01, 0.02, 0.005]";
    let floor = "shape = \"plane\"\norigin = [0.0, 0.0, -0.03]\nnormal = [0.0, 0.0, 1.0]";
    let theta = root(|t| 0.1 * t.sin() - 0.005 * t.cos() + 0.03);
    let push = (0.5 * theta + 2.0 * theta.cos()) / (0.1 * theta.cos() + 0.005 * theta.sin());
    let run = swung(&lid3(block, floor, 20.0), 0.04);
    let landed = run.changes.first().expect("a touch").time;
    let after: Vec<usize> = (0..run.time.len()).filter(|&i| run.time[i] > landed).collect();
    assert!(run.time[after[0]] - landed < 0.005 && after.len() >= 5, "{landed} {:?}", run.time);
    for i in after {
        let t = run.time[i];
        assert!((run.q(i)[0] - theta).abs() < 1e-7, "t = {t}: {:?} against {theta}", run.q(i));
        let total: f64 = run.contacts[i].iter().map(|k| k.normal_force).sum();
        assert!((total - push).abs() < 1e-6 * push, "t = {t}: {total} against {push}");
    }
}
