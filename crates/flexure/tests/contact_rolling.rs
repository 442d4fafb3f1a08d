//! `mechanism/statics/contact.rs`: friction where a contact rolls, against
//! closed forms.
//!
//! A wheel (radius $r$) turns on a sprung axle ($k_\theta$) carried by a
//! hub on two sprung slides ($k_x$, $k_y$), over a rough floor ($\mu$). A
//! press $F_y$ sets it on the floor with $N = F_y - k_yg_0$; a push $F_x$
//! then rolls it: stuck, the wheel's point on the floor does not slide, so
//! $x - x_1 = -r(\theta - \theta_1)$, and with the axle's balance
//! $k_\theta\theta = -rf$ and the hub's $F_x - k_xx - f = 0$,
//! $$x = \frac{F_x + K(x_1 + r\theta_1)}{k_x + K},\qquad K = k_\theta/r^2,$$
//! $(x_1, \theta_1)$ where it last stuck. It slides once $\lvert f\rvert >
//! \mu N$, where $f = \pm\mu N$, $x = (F_x \mp \mu N)/k_x$ and
//! $\theta = \mp r\mu N/k_\theta$.

use flexure::mechanism::contact::ContactMode;
use flexure::mechanism::file::{from_toml, spatial_from_toml};
use flexure::mechanism::statics::Settings;
use flexure::mechanism::sweep::{Parameter, sweep};

/// The wheel's radius (m), the slides' and the axle's stiffness (N/m, N·m/rad),
/// its gap to the floor (m), the press (N) and the floor's μ.
const R: f64 = 0.1;
const KX: f64 = 100.0;
const KY: f64 = 1000.0;
const KT: f64 = 1.0;
const G0: f64 = 0.001;
const FY: f64 = 10.0;
const MU: f64 = 0.3;

/// The wheel, planar or spatial (the same problem in the x-y plane).
fn wheel(spatial: bool) -> String {
    let (lift, spin, at, floor, normal, dim) = if spatial {
        (
            "axis = [0.0, 1.0, 0.0]\n",
            "axis = [0.0, 0.0, 1.0]\n",
            "[0.0, 0.0, 0.0]",
            "[0.0, -0.101, 0.0]",
            "[0.0, 1.0, 0.0]",
            "dimension = 3\n",
        )
    } else {
        ("origin = [0.0, 0.0, 1.5707963267948966]\n", "", "[0.0, 0.0]", "[0.0, -0.101]", "[0.0, 1.0]", "")
    };
    let shape = if spatial { "sphere" } else { "circle" };
    format!(
        "{dim}[[joint]]\nname = \"x\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"carriage\"\nstiffness = {KX}\n\
         [[joint]]\nname = \"y\"\nkind = \"prismatic\"\nparent = \"carriage\"\nchild = \"hub\"\nstiffness = {KY}\n{lift}\
         [[joint]]\nname = \"axle\"\nkind = \"revolute\"\nparent = \"hub\"\nchild = \"wheel\"\nstiffness = {KT}\n{spin}\
         [[force]]\nname = \"push\"\nbody = \"hub\"\nat = {at}\nforce = {}\n\
         [[geom]]\nname = \"tyre\"\nbody = \"wheel\"\nshape = \"{shape}\"\nradius = {R}\n\
         [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = {floor}\nnormal = {normal}\nfriction = {MU}\n",
        if spatial { format!("[0.0, -{FY}, 0.0]") } else { format!("[0.0, -{FY}]") }
    )
}

/// A push along the floor from 0 to 8 N and back to -4 N, each value
/// followed from the last: the wheel rolls stuck, slides from 5.4 N, rolls
/// back stuck from where it slid, and slides back from -2.8 N. Each row's
/// hub, wheel angle, state and forces against the closed form: N to 1e-9
/// of itself, the hub and the angle to 5e-5 of their travel (0.05 m,
/// 0.5 rad), the friction to $k_x$ times the hub's. That last is the rolling pin's: set anew at
/// each step, which turns the wheel by at most 0.01 rad, it rolls the hub
/// by $r\sin\Delta\theta$ for $r\Delta\theta$, a relative
/// $\Delta\theta^2/6 \approx 1.7\times10^{-5}$ (measured 2.2e-5 at 2 N).
fn rolls_then_slides_as_the_closed_form_says(spatial: bool) {
    let values = [0.0, 2.0, 4.0, 5.0, 6.0, 8.0, 6.0, 0.0, -2.0, -4.0];
    let out = if spatial {
        let m = spatial_from_toml(&wheel(true)).unwrap();
        let out = sweep(&m, &Parameter::parse(&m, "force.push.fx").unwrap(), &values, &Settings::default()).unwrap();
        let rows = out.rows.into_iter().map(|(v, s)| (v, s.q, s.contacts)).collect::<Vec<_>>();
        (rows, out.stopped.map(|e| e.1.to_string()))
    } else {
        let m = from_toml(&wheel(false)).unwrap();
        let out = sweep(&m, &Parameter::parse(&m, "force.push.fx").unwrap(), &values, &Settings::default()).unwrap();
        let rows = out.rows.into_iter().map(|(v, s)| (v, s.q, s.contacts)).collect::<Vec<_>>();
        (rows, out.stopped.map(|e| e.1.to_string()))
    };
    let (rows, stopped) = out;
    assert!(stopped.is_none() && rows.len() == values.len(), "{stopped:?}");
    let (n, k) = (FY - KY * G0, KT / (R * R));
    // x + rθ, kept while it sticks (where it last slid).
    let mut held = 0.0;
    let mut states = Vec::new();
    for (fx, q, contacts) in &rows {
        let x = (fx + k * held) / (KX + k);
        let (x, theta, f, state) = if (fx - KX * x).abs() <= MU * n {
            (x, (held - x) / R, fx - KX * x, ContactMode::Stick)
        } else {
            let f = MU * n * (fx - KX * x).signum();
            ((fx - f) / KX, -R * f / KT, f, ContactMode::Slip)
        };
        held = x + R * theta;
        let c = &contacts[0];
        assert_eq!((c.geom.as_str(), c.body.as_deref(), c.state), ("floor", Some("wheel"), state), "at {fx}: {c:?}");
        assert!((q[0] - x).abs() < 5e-5 * 0.05, "at {fx}: x {} vs {x}", q[0]);
        assert!((q[1] + G0).abs() < 1e-9, "at {fx}: y {}", q[1]);
        assert!((q[2] - theta).abs() < 5e-5 * 0.5, "at {fx}: θ {} vs {theta}", q[2]);
        assert!((c.normal_force - n).abs() < 1e-9 * n, "at {fx}: N {} vs {n}", c.normal_force);
        assert!((c.friction_force[0] + f).abs() < KX * 5e-5 * 0.05, "at {fx}: f {:?} vs {f}", c.friction_force);
        states.push(state);
    }
    assert_eq!(states.iter().filter(|s| **s == ContactMode::Slip).count(), 3, "{states:?}");
}

#[test]
fn a_wheel_rolls_then_slides_as_the_closed_form_says() {
    rolls_then_slides_as_the_closed_form_says(false);
}

/// In space, where a rolling contact's slide is solved with each step:
/// the same rows as in the plane.
#[test]
fn a_spatial_wheel_rolls_then_slides_as_the_closed_form_says() {
    rolls_then_slides_as_the_closed_form_says(true);
}

/// The spatial wheel on a third sprung slide, along z ($k_z$), held by a
/// side push $F_z$ while $F_x$ is swept: the wheel rolls along x and
/// cannot along z, so its contact slides along a direction that turns as
/// it goes. Quasi-statics, Coulomb's law and the springs give, for the
/// slide $u = (x + r\theta,\ z)$ of the wheel's material point and the
/// floor's friction $\varphi$ on it, $u = AF + C\varphi$ with $A =
/// \mathrm{diag}(1/k_x, 1/k_z)$ and $C = \mathrm{diag}(1/k_x + r^2/k_\theta,\
/// 1/k_z)$; stuck, $u$ stays; sliding, $\lvert\varphi\rvert = \mu N$ and $\dot
/// u$ lies against $\varphi$. The reference integrates that path by
/// implicit Euler (a return map in $C$'s metric: $\varphi_i = c_i\varphi^{\rm
/// trial}_i/(c_i + \gamma)$ with $\lvert\varphi\rvert = \mu N$) at 4,000 and
/// 8,000 steps a row, extrapolated (Richardson); independent of the library.
fn skid_reference(values: &[f64], fz: f64, kz: f64) -> Vec<([f64; 2], bool)> {
    let n = FY - KY * G0;
    let c = [1.0 / KX + R * R / KT, 1.0 / kz];
    let run = |substeps: usize| {
        // After the press and side push, stuck from the touch at a tenth of them.
        let mut phi = [0.0, -(1.0 - KY * G0 / FY) * fz];
        let mut last = values[0];
        let mut out = Vec::new();
        for &fx in values {
            let (step, mut slid) = ((fx - last) / substeps as f64, false);
            for _ in 0..substeps {
                let trial = [phi[0] - step / KX / c[0], phi[1]];
                let size = (trial[0] * trial[0] + trial[1] * trial[1]).sqrt();
                slid = size > MU * n;
                if !slid {
                    phi = trial;
                    continue;
                }
                let at = |g: f64| [c[0] * trial[0] / (c[0] + g), c[1] * trial[1] / (c[1] + g)];
                let (mut lo, mut hi) = (0.0, 1.0);
                while at(hi).iter().map(|v| v * v).sum::<f64>().sqrt() > MU * n {
                    hi *= 2.0;
                }
                for _ in 0..100 {
                    let mid = 0.5 * (lo + hi);
                    if at(mid).iter().map(|v| v * v).sum::<f64>().sqrt() > MU * n { lo = mid } else { hi = mid }
                }
                phi = at(0.5 * (lo + hi));
            }
            last = fx;
            out.push((phi, slid));
        }
        out
    };
    let (coarse, fine) = (run(4000), run(8000));
    coarse.iter().zip(&fine).map(|(a, b)| ([2.0 * b.0[0] - a.0[0], 2.0 * b.0[1] - a.0[1]], b.1)).collect()
}

/// A push along x from 0 to 8 N and back to -6 N with 2 N along z held:
/// the contact sticks to 4 N, slides with its friction turning from 42°
/// off -x to 13°, sticks on the way back and slides back from about
/// -2.5 N. Each row's state, hub (x, z), wheel angle and friction against
/// [`skid_reference`], to 1e-3 of $\mu N$ in force and of the matching
/// travel (the spring's force) in place: measured 6.5e-4 at the last row.
/// The slide's direction is solved by implicit Euler in load steps that
/// turn the friction by at most 2e-3 rad, a first-order error (at 1e-2
/// rad a step, 2.8e-3; at 1e-3, 3.2e-4).
#[test]
fn a_spatial_wheel_held_aside_slides_along_a_turning_direction() {
    let (fz, kz) = (2.0, 100.0);
    let text = wheel(true)
        .replace("[0.0, -10, 0.0]", &format!("[0.0, -{FY}, {fz}]"))
        .replace(
            "[[joint]]\nname = \"y\"\nkind = \"prismatic\"\nparent = \"carriage\"",
            &format!(
                "[[joint]]\nname = \"z\"\nkind = \"prismatic\"\nparent = \"carriage\"\nchild = \"sled\"\nstiffness = {kz}\naxis = [0.0, 0.0, 1.0]\n\
                 [[joint]]\nname = \"y\"\nkind = \"prismatic\"\nparent = \"sled\""
            ),
        );
    let m = spatial_from_toml(&text).unwrap();
    let values = [0.0, 2.0, 4.0, 5.0, 6.0, 8.0, 6.0, 2.0, 0.0, -2.0, -4.0, -6.0];
    let out = sweep(&m, &Parameter::parse(&m, "force.push.fx").unwrap(), &values, &Settings::default()).unwrap();
    assert!(out.stopped.is_none() && out.rows.len() == values.len(), "{:?}", out.stopped);
    let expected = skid_reference(&values, fz, kz);
    let limit = MU * (FY - KY * G0);
    for ((fx, s), (phi, slid)) in out.rows.iter().zip(&expected) {
        let c = &s.contacts[0];
        let (x, z, theta) = ((fx + phi[0]) / KX, (fz + phi[1]) / kz, R * phi[0] / KT);
        let state = if *slid { ContactMode::Slip } else { ContactMode::Stick };
        assert_eq!(c.state, state, "at {fx}: {c:?} vs {phi:?}");
        let errors = [
            (s.q[0] - x).abs() * KX,
            (s.q[1] - z).abs() * kz,
            (s.q[3] - theta).abs() * KT / R,
            (c.friction_force[0] - phi[0]).abs(),
            (c.friction_force[2] - phi[1]).abs(),
        ];
        let error = errors.iter().fold(0.0f64, |a, b| a.max(*b)) / limit;
        assert!(error < 1e-3, "at {fx}: q {:?}, friction {:?} vs {phi:?}: {errors:?}", s.q, c.friction_force);
    }
}

/// Pressed and pushed together (4 N along the floor), the wheel sticks all
/// the way; its hub's compliance holds the contact as it is, rolling: along
/// the floor $1/(k_x + k_\theta/r^2)$, into it none, to 1e-9 of the first.
#[test]
fn a_stuck_wheel_rolls_under_a_small_push() {
    use flexure::mechanism::statics::{compliance, solve};
    let m =
        from_toml(&wheel(false).replace(&format!("force = [0.0, -{FY}]"), &format!("force = [4.0, -{FY}]"))).unwrap();
    let s = solve(&m, &Settings::default()).unwrap();
    assert_eq!(s.contacts[0].state, ContactMode::Stick, "{:?}", s.contacts);
    let c = compliance(&m, &s, m.body("hub").unwrap(), [0.0, 0.0].into()).unwrap();
    let along = 1.0 / (KX + KT / (R * R));
    // Ordered (φ, x, y).
    assert!((c[(1, 1)] - along).abs() < 1e-9 * along, "{c}");
    assert!(c[(2, 2)].abs() < 1e-9 * along, "{c}");
}

/// A unit strip (no thickness) curled onto a rough post ($\mu = 1$) by a
/// tip moment of 3 N·m slides outward on it; let go in steps to 2 N·m, it
/// sticks and rolls back, so the arc it rolls along itself is the arc it
/// rolls along the post, $\Delta s = -R\Delta\varphi$ (the closed form of
/// rolling without slipping), to 1e-5 of the arc (measured 1.5e-6).
/// Frictionless, the same moments slide it: the two arcs differ by 6 %.
#[test]
fn a_strip_rolls_on_a_rough_post_without_slipping() {
    let (radius, centre) = (0.25, [0.55, -0.3]);
    let text = |mu: f64| {
        format!(
            "[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\norder = 8\n\
             [[force]]\nname = \"push\"\nbody = \"tip\"\nat = [0.0, 0.0]\nmoment = -1.0\n\
             [[geom]]\nname = \"post\"\nbody = \"ground\"\nshape = \"circle\"\norigin = [{}, {}]\nradius = {radius}\nfriction = {mu}\n",
            centre[0], centre[1]
        )
    };
    let values = [-3.0, -2.75, -2.5, -2.25, -2.0];
    let arcs = |mu: f64| {
        let m = from_toml(&text(mu)).unwrap();
        let out =
            sweep(&m, &Parameter::parse(&m, "force.push.moment").unwrap(), &values, &Settings::default()).unwrap();
        assert!(out.stopped.is_none(), "{:?}", out.stopped);
        out.rows
            .iter()
            .map(|(_, s)| {
                let c = &s.contacts[0];
                let phi = (c.point[1] - centre[1]).atan2(c.point[0] - centre[0]);
                (c.s.unwrap(), phi, c.state)
            })
            .collect::<Vec<_>>()
    };
    let rough = arcs(1.0);
    // Pressed to -3 N·m it slides outward; let go, it sticks and rolls back.
    let (s0, phi0, first) = rough[0];
    assert_eq!(first, ContactMode::Slip);
    for &(s, phi, state) in &rough[1..] {
        assert_eq!(state, ContactMode::Stick);
        let (along, around) = (s - s0, -radius * (phi - phi0));
        assert!(
            along.abs() > 1e-3 && (along - around).abs() < 1e-5 * along.abs(),
            "{along} along the strip, {around} around the post"
        );
    }
    let smooth = arcs(0.0);
    let (s0, phi0, _) = smooth[0];
    let (s, phi, _) = smooth[4];
    assert!(((s - s0) + radius * (phi - phi0)).abs() > 1e-2 * (s - s0).abs(), "frictionless, it slides");
}

/// A unit strip 20 mm thick (EI = 1), its root on a sprung slide along x,
/// pressed onto a rough floor by its tip ($\mu = 1$), then turned by a tip
/// moment: its tip's rounded end (radius
/// $h$, half the thickness) rolls on the floor without slipping, so its
/// centre keeps $h$ above the floor and moves by $-h\Delta\theta$ as the
/// tip turns by $\Delta\theta$ (the closed form of a rolling circle), to
/// 1e-6 of $h\Delta\theta$ (measured 2.3e-7); a strip with no thickness
/// would keep its tip still.
#[test]
fn a_thick_tip_rolls_on_a_rough_floor() {
    use flexure::mechanism::kinematics::frames;
    let h = 0.01;
    let text = thick_tip(false, h);
    let m = from_toml(&text).unwrap();
    let values = [0.0, 0.05, 0.1, 0.15, 0.2];
    let out = sweep(&m, &Parameter::parse(&m, "force.push.moment").unwrap(), &values, &Settings::default()).unwrap();
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    let tip = m.body("tip").unwrap();
    let pose = |q: &[f64]| {
        let p = frames(&m, q).bodies[tip];
        (p.x, p.y, p.phi)
    };
    let (x0, _, t0) = pose(&out.rows[0].1.q);
    for (v, s) in &out.rows[1..] {
        let (x, y, t) = pose(&s.q);
        let c = &s.contacts[0];
        assert_eq!((c.state, c.s), (ContactMode::Stick, Some(1.0)), "at {v}: {c:?}");
        assert!((y - (-0.05 + h)).abs() < 1e-9, "at {v}: the tip's centre {y}");
        assert!(
            (t - t0).abs() > 1e-3 && ((x - x0) + h * (t - t0)).abs() < 1e-6 * h * (t - t0).abs(),
            "at {v}: {} for {}",
            x - x0,
            -h * (t - t0)
        );
    }
}

/// The spatial file of [`a_thick_tip_rolls_on_a_rough_floor`]: a strip
/// touching with its thickness in space, whose surface's material point
/// turns with its section. The same closed form, to 1e-6 of $h\Delta\theta$,
/// and the planar file's tip at each row to 1e-9 m.
#[test]
fn a_thick_tip_rolls_on_a_rough_floor_in_space() {
    use flexure::mechanism::kinematics::frames;
    let h = 0.01;
    let (planar, spatial) = (thick_tip(false, h), thick_tip(true, h));
    let values = [0.0, 0.05, 0.1, 0.15, 0.2];
    let m = from_toml(&planar).unwrap();
    let out = sweep(&m, &Parameter::parse(&m, "force.push.moment").unwrap(), &values, &Settings::default()).unwrap();
    let tip = m.body("tip").unwrap();
    let flat: Vec<[f64; 2]> = out.rows.iter().map(|(_, s)| frames(&m, &s.q).bodies[tip]).map(|p| [p.x, p.y]).collect();
    let m = spatial_from_toml(&spatial).unwrap();
    let out = sweep(&m, &Parameter::parse(&m, "force.push.mz").unwrap(), &values, &Settings::default()).unwrap();
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    let tip = m.body("tip").unwrap();
    let pose = |q: &[f64]| {
        let p = frames(&m, q).bodies[tip];
        let e = p.rotation * nalgebra::Vector3::x();
        (p.translation.vector, e.y.atan2(e.x))
    };
    let (c0, t0) = pose(&out.rows[0].1.q);
    for ((v, s), flat) in out.rows.iter().zip(&flat).skip(1) {
        let (c, t) = pose(&s.q);
        let contact = &s.contacts[0];
        assert_eq!((contact.state, contact.s), (ContactMode::Stick, Some(1.0)), "at {v}: {contact:?}");
        assert!((c.y - (-0.05 + h)).abs() < 1e-9 && c.z.abs() < 1e-12, "at {v}: the tip's centre {c}");
        assert!(
            (t - t0).abs() > 1e-3 && ((c.x - c0.x) + h * (t - t0)).abs() < 1e-6 * h * (t - t0).abs(),
            "at {v}: {} for {}",
            c.x - c0.x,
            -h * (t - t0)
        );
        assert!((c.x - flat[0]).abs() < 1e-9 && (c.y - flat[1]).abs() < 1e-9, "at {v}: {c} vs the plane's {flat:?}");
    }
}

/// The thick strip of [`a_thick_tip_rolls_on_a_rough_floor`], planar or
/// spatial (the same problem in the x-y plane).
fn thick_tip(spatial: bool, h: f64) -> String {
    let (dim, order, at, force, floor, normal) = if spatial {
        ("dimension = 3\n", "8", "[0.0, 0.0, 0.0]", "[0.0, -1.0, 0.0]", "[0.0, -0.05, 0.0]", "[0.0, 1.0, 0.0]")
    } else {
        ("", "8", "[0.0, 0.0]", "[0.0, -1.0]", "[0.0, -0.05]", "[0.0, 1.0]")
    };
    format!(
        "{dim}[[joint]]\nname = \"slide\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"base\"\nstiffness = 1.0\n\
         [[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"base\"\nchild = \"tip\"\nlength = 1.0\nmodulus = 1.5e8\nwidth = 0.01\nthickness = {}\norder = {order}\n\
         [[force]]\nname = \"push\"\nbody = \"tip\"\nat = {at}\nforce = {force}\n\
         [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = {floor}\nnormal = {normal}\nfriction = 1.0\n",
        2.0 * h
    )
}

/// Twisted, the same thick strip's tip rolls sideways on the floor: its
/// section turns about its own axis, so the material point under it turns
/// with the twist and the tip's centre, $h$ above the floor, moves by
/// $h\thinspace\Delta\vartheta\times\hat y$ for a turn $\Delta\vartheta$ (the
/// rotation vector of the tip's section from one row to the next, nearly
/// about one axis: a ball rolling on a plane). Rows of 0.002 N·m of twist
/// from a press of 1 N: each row's move (76 µm) to 1e-4 of itself
/// (measured 2.6e-5: the rolling pin's $\Delta\theta^2/6$ per step).
#[test]
fn a_twisted_thick_tip_rolls_sideways() {
    use flexure::mechanism::kinematics::frames;
    let h = 0.01;
    let m = spatial_from_toml(&thick_tip(true, h)).unwrap();
    let values: Vec<f64> = (0..=5).map(|i| 0.002 * i as f64).collect();
    let out = sweep(&m, &Parameter::parse(&m, "force.push.mx").unwrap(), &values, &Settings::default()).unwrap();
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    let tip = m.body("tip").unwrap();
    let poses: Vec<_> = out.rows.iter().map(|(_, s)| frames(&m, &s.q).bodies[tip]).collect();
    for (k, pair) in poses.windows(2).enumerate() {
        let (a, b) = (pair[0], pair[1]);
        let turn = (b.rotation * a.rotation.inverse()).scaled_axis();
        let moved = b.translation.vector - a.translation.vector;
        let rolled = turn.cross(&nalgebra::Vector3::y()) * h;
        let c = &out.rows[k + 1].1.contacts[0];
        assert_eq!(c.state, ContactMode::Stick, "{c:?}");
        assert!((moved - rolled).norm() < 1e-4 * rolled.norm(), "row {}: moved {moved}, rolled {rolled}", k + 1);
    }
}

/// Two strips (10 × 1 mm, E = 1.2 GPa, 50 mm, order 8) squeeze a disc
/// (radius 10 mm, μ = 0.5) with 0.3 N on each tip; the disc sits on a soft
/// slide (1 N/m) and a pull draws it out between them, planar, or spatial
/// with the disc a cylinder.
fn two_finger_grasp(spatial: bool) -> String {
    let (dim, at, orders, down, up, pull, shape) = if spatial {
        let cylinder = "shape = \"cylinder\"\nhalf_length = 0.02\n";
        (
            "dimension = 3\n",
            ", 0.0",
            "orders = [1, 1, 8]",
            "[0.0, -0.3, 0.0]",
            "[0.0, 0.3, 0.0]",
            "[0.0, 0.0, 0.0]",
            cylinder,
        )
    } else {
        ("", ", 0.0", "order = 8", "[0.0, -0.3]", "[0.0, 0.3]", "[0.0, 0.0]", "shape = \"circle\"\n")
    };
    let finger = |name: &str, tip: &str, y: f64| {
        format!(
            "[[joint]]\nname = \"{name}\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"{tip}\"\norigin = [0.0, {y}{at}]\n\
             length = 0.05\nmodulus = 1.2e9\nwidth = 0.01\nthickness = 0.001\n{orders}\n"
        )
    };
    format!(
        "{dim}{}{}[[joint]]\nname = \"slot\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"disc\"\norigin = [0.045, 0.0{at}]\nstiffness = 1.0\n\
         [[force]]\nname = \"squeeze_upper\"\nbody = \"upper_tip\"\nforce = {down}\n\
         [[force]]\nname = \"squeeze_lower\"\nbody = \"lower_tip\"\nforce = {up}\n\
         [[force]]\nname = \"pull\"\nbody = \"disc\"\nforce = {pull}\n\
         [[geom]]\nname = \"part\"\nbody = \"disc\"\n{shape}radius = 0.01\nfriction = 0.5\n",
        finger("upper", "upper_tip", 0.0115),
        finger("lower", "lower_tip", -0.0115),
    )
}

/// The disc pulled from the two-finger grasp: both contacts roll stuck,
/// inside the strips' spans, until their friction reaches μN together.
/// Sliding on, the disc would move toward the tips, where the strips press
/// less, so it would take less pull: the grasp lets go there, a limit point
/// of the path, which the sweep reports as its stability limit (it had
/// stuck again and slipped again in steps of 1e-4 of the load, for minutes).
/// Reference: the same grasp in motion (`simulate`; strips of 1200 kg/m³
/// with β = 1 ms, a 10 g disc), its pull ramped at 0.5 N/s from 0.1 s:
/// both contacts slip at the sweep's limit to 1e-4 of it (measured 4e-6),
/// and the disc then slides out (3 mm in the 70 ms to the run's end),
/// where before it had moved less than 0.1 mm. The spatial file gives the planar limit to 1e-4 (measured 2e-5,
/// its slide solved with each step).
#[test]
fn a_disc_pulled_from_a_two_finger_grasp_lets_go_where_its_friction_is_spent() {
    use flexure::dynamics::integrate::MotionSettings;
    use flexure::dynamics::simulation::{SimulationSettings, Start, simulate};
    let values = [0.0, 0.1, 0.2, 0.3, 0.4];
    let m = from_toml(&two_finger_grasp(false)).unwrap();
    let out = sweep(&m, &Parameter::parse(&m, "force.pull.fx").unwrap(), &values, &Settings::default()).unwrap();
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    let limit = out.stability_limit.expect("the grasp lets go").value;
    assert!(out.rows.len() == 4 && (0.3..0.4).contains(&limit), "{} rows, limit {limit}", out.rows.len());
    for (v, s) in &out.rows {
        for c in &s.contacts {
            let f = c.friction_force.iter().map(|f| f * f).sum::<f64>().sqrt();
            assert!(c.state == ContactMode::Stick && f < 0.5 * c.normal_force, "{v}: {c:?}");
        }
    }
    let s = spatial_from_toml(&two_finger_grasp(true)).unwrap();
    let out = sweep(&s, &Parameter::parse(&s, "force.pull.fx").unwrap(), &[0.0, 0.4], &Settings::default()).unwrap();
    let spatial = out.stability_limit.expect("the spatial grasp lets go").value;
    assert!((spatial - limit).abs() < 1e-4 * limit, "spatial {spatial} vs planar {limit}");

    let (start, rate) = (0.1, 0.5);
    let moving = two_finger_grasp(false).replace("order = 8\n", "order = 8\ndensity = 1200.0\ndamping = 0.001\n")
        + &format!(
            "[[body]]\nname = \"disc\"\nmass = 0.01\ninertia = 5e-7\n\
             [[schedule]]\nload = \"force.pull.fx\"\npoints = [[0.0, 0.0], [{start}, 0.0], [1.1, {}]]\n",
            rate * (1.1 - start)
        );
    let motion = MotionSettings { duration: 0.85, every: 0.05, tolerance: 1e-6, absolute: 1e-6, ..Default::default() };
    let settings = SimulationSettings { motion, ..Default::default() };
    let run = simulate(&from_toml(&moving).unwrap(), &settings, Start::Equilibrium).unwrap();
    assert!(run.stopped.is_none(), "{:?}", run.stopped);
    let slips: Vec<f64> = run.changes.iter().filter(|c| c.state == ContactMode::Slip).map(|c| c.time).collect();
    assert_eq!(slips.len(), 2, "{:?}", run.changes);
    for t in slips {
        let pull = rate * (t - start);
        assert!((pull - limit).abs() < 1e-4 * limit, "slips at {pull} N in motion, lets go at {limit} N in the sweep");
    }
    let x = &run.bodies.iter().find(|b| b.name == "disc").expect("the disc moves").x;
    let held = run.time.iter().zip(x).filter(|(t, _)| rate * (**t - start) < limit).map(|(_, d)| d - x[0]);
    assert!(held.clone().all(|d| d.abs() < 1e-4), "{:?}", held.collect::<Vec<_>>());
    assert!(x[x.len() - 1] - x[0] > 1e-3, "the disc is pulled free: {x:?}");
}

/// `examples/grasp.toml` with its rod on two sprung sliders (50 N/m each
/// way) instead of the ground: at 4 N the distal pad holds the rod, stuck
/// where it rolls, and the rod's balance closes (Newton's third law): its
/// springs' pull, $-k(x, y)$, against the reported contact forces on it,
/// $-\sum(Nn + f)$, to $10^{-9}$ N of a 0.2 N push. The forces were reported
/// in the rolling contact's tangents as turned at the last step, not
/// those they were solved in: 1e-4 N out, along the normal (an audit's
/// case; frictionless, it closed to 1e-12 N).
#[test]
fn a_sprung_rod_held_by_the_grasp_balances_its_reported_contact_forces() {
    let path = format!("{}/../../examples/grasp.toml", env!("CARGO_MANIFEST_DIR"));
    let k = 50.0;
    let text = std::fs::read_to_string(path).unwrap().replace(
        "name = \"cylinder\"\nbody = \"ground\"\nshape = \"circle\"\norigin = [0.046, 0.023]\n",
        "name = \"cylinder\"\nbody = \"rod\"\nshape = \"circle\"\n",
    ) + &format!(
        "[[joint]]\nname = \"rx\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"carriage\"\norigin = [0.046, 0.023, 0.0]\nstiffness = {k}\n\
         [[joint]]\nname = \"ry\"\nkind = \"prismatic\"\nparent = \"carriage\"\nchild = \"rod\"\norigin = [0.0, 0.0, 1.5707963267948966]\nstiffness = {k}\n"
    );
    let m = from_toml(&text).unwrap();
    let s = flexure::mechanism::statics::solve(&m, &Settings::default()).unwrap();
    let held: Vec<_> = s.contacts.iter().filter(|c| c.normal_force > 0.0).collect();
    assert!(held.len() == 1 && held[0].state == ContactMode::Stick && held[0].normal_force > 0.1, "{:?}", s.contacts);
    let on_parts =
        held.iter().fold([0.0; 2], |a, c| [0, 1].map(|i| a[i] + c.normal[i] * c.normal_force + c.friction_force[i]));
    let friction = held[0].friction_force.iter().map(|f| f * f).sum::<f64>().sqrt();
    assert!(friction > 0.01, "a friction to turn: {friction}");
    let n = m.dof();
    let (x, y) = (s.q[n - 2], s.q[n - 1]);
    let off = [-on_parts[0] - k * x, -on_parts[1] - k * y];
    assert!(off[0].hypot(off[1]) < 1e-9, "out of balance by {off:?} N");
}
