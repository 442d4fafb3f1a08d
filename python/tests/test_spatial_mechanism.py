"""Spatial mechanism files (dimension = 3) from Python: Mechanism.solve, compliance, sweep,
modes, simulate and buckle. Each test names its reference and tolerance: a closed form, the
single SpatialFlexure's answer, the planar Mechanism on the same mechanism, or MuJoCo on the
same rigid chain (test_mujoco_*)."""

import math
from pathlib import Path

import numpy as np
import pytest

import flexure

ROOT = Path(__file__).resolve().parents[2]

# Two sprung hinges: "yaw" about the ground's z, then "roll" about x at 0.1 m along x.
HINGES = """
dimension = 3
[[joint]]
name = "yaw"
kind = "revolute"
parent = "ground"
child = "arm"
axis = [0.0, 0.0, 1.0]
stiffness = {k1}

[[joint]]
name = "roll"
kind = "revolute"
parent = "arm"
child = "hand"
axis = [1.0, 0.0, 0.0]
origin = [0.1, 0.0, 0.0]
stiffness = {k2}
"""


def hinges(k1=1.0, k2=2.0, extra=""):
    return flexure.Mechanism.from_toml(HINGES.format(k1=k1, k2=k2) + extra)


def cantilever(force=(0.0, 0.0, 0.0), moment=(0.0, 0.0, 0.0), order=5):
    """A round spatial flexure (EI_z = 1, EI_y = 2, GJ = 0.7, L = 1) clamped to the ground, its
    tip body loaded at its origin (the tip) by a dead force and moment."""
    return flexure.Mechanism.from_toml(
        f"""
dimension = 3
[[joint]]
name = "rod"
kind = "flexure"
parent = "ground"
child = "tip"
length = 1.0
ei = 1.0
ei_y = 2.0
gj = 0.7
order = {order}

[[force]]
name = "load"
body = "tip"
at = [0.0, 0.0, 0.0]
force = [{force[0]}, {force[1]}, {force[2]}]
moment = [{moment[0]}, {moment[1]}, {moment[2]}]
"""
    )


def orthonormal(r, tol=1e-12):
    r = np.asarray(r)
    eye = np.eye(3)
    return np.abs(r @ np.swapaxes(r, -1, -2) - eye).max() < tol and np.all(np.abs(np.linalg.det(r) - 1.0) < tol)


def rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


# --- solve ----------------------------------------------------------------------------------


def test_dimension_and_dof():
    m = hinges()
    assert (m.dimension, m.dof) == (3, 2)
    planar = flexure.Mechanism.from_file(ROOT / "examples" / "finger.toml")
    assert planar.dimension == 2


def position(body):
    """A spatial body's origin (x, y, z) as an array (3,), or (3, N) over a motion's samples."""
    return np.array([body["x"], body["y"], body["z"]])


def test_hinge_chain_solve_is_the_closed_form():
    # Closed form: a dead moment M = (Mx, 0, Mz) on the hand. The yaw hinge (axis z) carries Mz,
    # q1 = Mz/k1; the roll hinge's axis is Rz(q1) x, so it carries Mx cos q1: q2 = Mx cos(q1)/k2.
    # The hand sits at Rz(q1) (0.1, 0, 0), turned Rz(q1) Rx(q2). Tolerance 1e-12 (Newton's).
    k1, k2, mx, mz = 1.0, 2.0, 0.3, 0.2
    m = hinges(k1, k2, f'[[force]]\nname = "twist"\nbody = "hand"\nmoment = [{mx}, 0.0, {mz}]\n')
    s = m.solve()
    q1, q2 = mz / k1, mx * math.cos(mz / k1) / k2
    assert abs(s["coordinates"]["yaw"][0] - q1) < 1e-12 and abs(s["coordinates"]["roll"][0] - q2) < 1e-12
    hand = s["bodies"]["hand"]
    assert hand["rotation"].shape == (3, 3)
    assert np.abs(position(hand) - rz(q1) @ [0.1, 0.0, 0.0]).max() < 1e-12
    assert np.abs(hand["rotation"] - rz(q1) @ rx(q2)).max() < 1e-12
    # URDF's roll, pitch, yaw of Rz(q1) Rx(q2): (q2, 0, q1).
    assert np.abs(np.array([hand["roll"], hand["pitch"], hand["yaw"]]) - [q2, 0.0, q1]).max() < 1e-12
    assert orthonormal(s["bodies"]["arm"]["rotation"]) and orthonormal(hand["rotation"])
    assert abs(s["energy"] - 0.5 * (k1 * q1**2 + k2 * q2**2)) < 1e-12
    assert s["dimension"] == 3 and s["stable"] is True and s["flagged"] is False
    # The planar answer's shape: the ground among the bodies, no flexure to estimate or load.
    assert "ground" in s["bodies"] and s["load"] == {} and s["error_estimate"] == {}
    assert "q" not in s and set(s["coordinates"]) == {"yaw", "roll"}


def test_cantilever_solve_is_the_single_spatial_flexures_deflection():
    # Reference: SpatialFlexure.deflect of the same flexure under the same tip load (its root
    # frame is the ground's): the tip's frame to 1e-10 (two Newton solves of one model, each
    # stopped at its own residual tolerance); alpha to 1e-9, its highest coefficients being the
    # least determined by that residual (they differ by 3e-10).
    force, moment = (0.1, 0.4, -0.3), (0.05, -0.1, 0.2)
    s = cantilever(force, moment).solve()
    f = flexure.SpatialFlexure(length=1.0, ei=1.0, ei_y=2.0, gj=0.7, order=5)
    d = f.deflect(force=force, moment=moment)
    tip = s["bodies"]["tip"]
    assert np.abs(position(tip) - d["pose"][:3, 3]).max() < 1e-10
    assert np.abs(tip["rotation"] - d["pose"][:3, :3]).max() < 1e-10
    assert np.abs(s["coordinates"]["rod"] - d["alpha"]).max() < 1e-9
    assert orthonormal(tip["rotation"])
    # The wrench it carries, in its root frame: the tip load itself, moved to the root would
    # add r x F; at the tip it is the load (the library's report; here checked at the force).
    load = s["load"]["rod"]
    assert np.abs(load["force"] - np.array(force)).max() < 1e-10
    e = s["error_estimate"]["rod"]
    assert e["flagged"] is False and e["position"] < 1e-3 and e["reference_order"] > 5
    assert s["flagged"] is False


def test_a_flagged_flexure_warns_accuracy_naming_it():
    # Order 1 bends at constant curvature: under a tip force its error is far beyond 1e-9 of L.
    with pytest.warns(flexure.AccuracyWarning, match="flexure joint 'rod'"):
        s = cantilever(force=(0.0, 0.5, 0.0), order=1).solve(accuracy=(1e-9, 1e-9))
    assert s["flagged"] is True and s["error_estimate"]["rod"]["flagged"] is True


def test_a_planar_example_with_dimension_3_gives_the_planar_solve():
    # Reference: the planar Mechanism.solve of examples/finger.toml. Converted as
    # docs/mechanism-format.md says (dimension = 3, a third coordinate 0 to each point and
    # force), its blades given out-of-plane stiffnesses 100 times ei as a blade has: every
    # body's (x, y) and its rotation about z equal the planar answer to 1e-8 (m and rad; the two
    # integrate the same curvature by different rules, which differ by about 1e-11 here), and
    # nothing leaves the plane.
    planar = flexure.Mechanism.from_file(ROOT / "examples" / "finger.toml").solve()
    spatial = flexure.Mechanism.from_toml(
        """
dimension = 3

[[joint]]
name = "mcp"
kind = "flexure"
parent = "ground"
child = "proximal"
origin = [0.0, 0.0, 0.0]
length = 0.015
ei = 1.4558e-3
ei_y = 0.14558
gj = 0.14558

[[joint]]
name = "pip"
kind = "flexure"
parent = "proximal"
child = "distal"
origin = [0.03, 0.0, 0.0]
length = 0.012
ei = 1.0e-3
ei_y = 0.1
gj = 0.1

[[tendon]]
name = "flexor"
tension = 6.0
path = [["ground", -0.01, 0.005, 0.0], ["proximal", 0.0, 0.005, 0.0], ["proximal", 0.03, 0.005, 0.0], ["distal", 0.0, 0.005, 0.0]]

[[force]]
name = "tip"
body = "distal"
at = [0.025, 0.0, 0.0]
force = [0.0, -0.5, 0.0]
"""
    ).solve()
    assert set(spatial["bodies"]) == {"ground", "proximal", "distal"}
    for name, b in spatial["bodies"].items():
        p = planar["bodies"][name]
        r = b["rotation"]
        assert abs(b["x"] - p["x"]) < 1e-8 and abs(b["y"] - p["y"]) < 1e-8, name
        assert abs(math.atan2(r[1, 0], r[0, 0]) - p["phi"]) < 1e-8 and abs(b["yaw"] - p["phi"]) < 1e-8, name
        assert abs(b["z"]) < 1e-14 and abs(r[2, 2] - 1.0) < 1e-14, name
        assert orthonormal(r)
    assert spatial["stable"] == planar["stable"]
    # The rotation about z is each flexure's bending alone (kappa_z's series, last), the planar alpha.
    for joint in ("mcp", "pip"):
        assert np.abs(spatial["coordinates"][joint][-3:] - planar["coordinates"][joint]).max() < 1e-8


# --- compliance and sweep -------------------------------------------------------------------


def test_hinge_chain_compliance_is_the_closed_form():
    # Closed form, unloaded: C = J K^-1 J^T, J's columns (axis; axis x (p - pivot)) in the order
    # (rx, ry, rz, x, y, z). Yaw: (z; z x p); roll: (x; x x (p - (0.1, 0, 0))). Tolerance 1e-12.
    k1, k2 = 1.0, 2.0
    m = hinges(k1, k2)
    for at in (None, (0.0, 0.0, 0.05)):
        c = m.compliance("hand") if at is None else m.compliance("hand", at)
        p = np.array([0.1, 0.0, 0.0]) + (np.zeros(3) if at is None else np.array(at))
        z, x = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])
        j = np.column_stack([np.r_[z, np.cross(z, p)], np.r_[x, np.cross(x, p - [0.1, 0.0, 0.0])]])
        assert c.shape == (6, 6)
        assert np.abs(c - j @ np.diag([1 / k1, 1 / k2]) @ j.T).max() < 1e-12


def test_cantilever_compliance_is_the_single_flexures():
    # Reference: SpatialFlexure.compliance (the tip's 6 x 6 at rest, (rx, ry, rz, x, y, z)):
    # L/GJ, L/EI_y, L/EI_z, L^3/3EI_z, L^3/3EI_y, to 1e-10.
    c = cantilever().compliance("tip", [0.0, 0.0, 0.0])
    ref = flexure.SpatialFlexure(length=1.0, ei=1.0, ei_y=2.0, gj=0.7, order=5).compliance()
    assert np.abs(c - ref).max() < 1e-10
    assert abs(c[0, 0] - 1 / 0.7) < 1e-10 and abs(c[4, 4] - 1 / 3) < 1e-10 and abs(c[5, 5] - 1 / 6) < 1e-10


def test_sweep_rows_are_the_single_flexures_deflections():
    # Reference: SpatialFlexure.deflect at each swept tip force (1e-9: continued Newton solves);
    # each row's compliance that of compliance() on the mechanism with that load (1e-8).
    m = cantilever(force=(0.0, 0.0, 0.0))
    values = [0.2, 0.5, 1.0]
    w = m.sweep("force.load.fz", values, compliance="tip")
    f = flexure.SpatialFlexure(length=1.0, ei=1.0, ei_y=2.0, gj=0.7, order=5)
    tip = w["bodies"]["tip"]
    position = np.column_stack([tip["x"], tip["y"], tip["z"]])
    assert np.array_equal(w["values"], values) and position.shape == (3, 3) and tip["yaw"].shape == (3,)
    assert w["bodies"]["tip"]["rotation"].shape == (3, 3, 3) and w["coordinates"]["rod"].shape == (3, 15)
    for k, v in enumerate(values):
        d = f.deflect(force=(0.0, 0.0, v))
        assert np.abs(position[k] - d["pose"][:3, 3]).max() < 1e-9
        assert orthonormal(w["bodies"]["tip"]["rotation"][k])
    last = cantilever(force=(0.0, 0.0, 1.0)).compliance("tip")
    assert w["compliance"].shape == (3, 6, 6) and np.abs(w["compliance"][-1] - last).max() < 1e-8
    assert len(w["flagged"]) == 0 and "stability_limit" not in w


# --- modes, buckle, simulate ----------------------------------------------------------------


def test_hinge_chain_modes_are_the_closed_form():
    # Closed form: K = diag(k1, k2), M = sum of m J^T J of two point masses, the arm's at
    # (0.05, 0, 0) and the hand's at (0.1, 0, 0.05): omega^2 the eigenvalues of M^-1 K (1e-9
    # relative); each shape v with v^T M v = 1 (1e-9).
    k1, k2, m1, m2 = 1.0, 2.0, 0.3, 0.2
    bodies = (
        f'[[body]]\nname = "arm"\nmass = {m1}\ncom = [0.05, 0.0, 0.0]\n'
        f'[[body]]\nname = "hand"\nmass = {m2}\ncom = [0.0, 0.0, 0.05]\n'
    )
    r = hinges(k1, k2, bodies).modes()
    ja = np.array([[0.0, 0.0], [0.05, 0.0], [0.0, 0.0]])
    jh = np.array([[0.0, 0.0], [0.1, -0.05], [0.0, 0.0]])
    mass = m1 * ja.T @ ja + m2 * jh.T @ jh
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(mass, np.diag([k1, k2]))).real)
    assert r["dimension"] == 3 and r["omega"].shape == (2,)
    assert np.all(np.abs(r["omega"] ** 2 - w2) < 1e-9 * w2)
    assert np.all(np.abs(r["frequency"] - r["omega"] / (2 * math.pi)) < 1e-12 * r["frequency"])
    for k in range(2):
        v = np.array([r["shapes"]["yaw"][k, 0], r["shapes"]["roll"][k, 0]])
        assert abs(v @ mass @ v - 1.0) < 1e-9
    assert r["quasi_static"] == 0


def test_cantilever_buckles_at_eulers_load():
    # Euler: a clamped-free column of EI = 1 (both bendings: EI_z = 1 < EI_y = 2, so about z),
    # L = 1, buckles at pi^2 EI / 4L^2; the factor on a 1 N push. Order 8 within 1e-8 of it.
    r = cantilever(force=(-1.0, 0.0, 0.0), order=8).buckle()
    assert abs(r["load_factor"] - math.pi**2 / 4) < 1e-8 * math.pi**2 / 4
    assert r["mode"].shape == (24,) and abs(np.linalg.norm(r["mode"]) - 1.0) < 1e-12
    assert r["dimension"] == 3


def test_cantilever_buckle_carries_its_estimate_in_the_planar_keys():
    # Euler: pi^2 EI / 4L^2 with EI = 1 (about z). Orders 3 are 1.4e-4 high; the estimate,
    # against orders 6, is that error to within the reference's own (1e-3 of it, measured
    # 3e-7). Within the default 1 % it is not flagged; against 1e-5 it is, with AccuracyWarning.
    euler = math.pi**2 / 4
    m = cantilever(force=(-1.0, 0.0, 0.0), order=3)
    r = m.buckle()
    e = r["error_estimate"]
    truth = r["load_factor"] / euler - 1.0
    assert set(e) == {"load_factor", "reference_load_factor", "reference_order", "reference_quadrature"}
    assert abs(e["load_factor"] / truth - 1.0) < 1e-3
    assert abs(e["reference_load_factor"] / euler - 1.0) < 1e-6
    assert e["reference_order"] == {"rod": 6} and e["reference_quadrature"] == {"rod": 20}
    assert r["flagged"] is False
    with pytest.warns(flexure.AccuracyWarning, match=r"Mechanism\.buckle: the load factor"):
        tight = m.buckle(accuracy=1e-5)
    assert tight["flagged"] is True


def test_order_auto_raises_a_spatial_flexure_until_buckle_meets_its_accuracy():
    # Euler: pi^2 EI / 4L^2 with EI = 1. order = "auto" starts at 3 (1.4e-4 high) and is raised
    # until the estimate meets 1e-7; the answer is then Euler's to 1e-7, with the orders used.
    euler = math.pi**2 / 4
    r = cantilever(force=(-1.0, 0.0, 0.0), order='"auto"').buckle(accuracy=1e-7)
    assert r["flagged"] is False and abs(r["load_factor"] / euler - 1.0) < 1e-7
    orders = r["order"]["rod"]
    assert len(orders) == 3 and all(n > 3 for n in orders)
    assert "order" not in cantilever(force=(-1.0, 0.0, 0.0), order=3).buckle()


# A massless round rod (EI_z = 1, EI_y = 2, GJ = 0.7, L = 1) carrying a 0.3 kg point mass at its tip.
ROD = """
dimension = 3
[[joint]]
name = "rod"
kind = "flexure"
parent = "ground"
child = "tip"
length = 1.0
ei = 1.0
ei_y = 2.0
gj = 0.7
order = {order}

[[body]]
name = "tip"
mass = 0.3
"""


def test_rod_modes_carry_their_estimate_and_a_coarse_rod_is_flagged():
    # Closed form: the tip mass bends at omega = sqrt(3 EI / (m L^3)) about each axis (EI = 1
    # and 2), exact from order 2 (the tip compliance is), so each estimate is rounding (1e-8).
    # At order 1 (constant curvature: k = 4 EI / L^3, 15 % high) the estimate is that error to
    # 1e-9 (the reference is exact), flagged with AccuracyWarning.
    exact = np.sqrt(3.0 * np.array([1.0, 2.0]) / 0.3)
    r = flexure.Mechanism.from_toml(ROD.format(order=3)).modes()
    e = r["error_estimate"]
    keys = {"omega", "reference_omega", "reference_order", "reference_quadrature", "reference_stable", "flagged"}
    assert set(e) == keys
    assert np.all(np.abs(r["omega"] / exact - 1.0) < 1e-8)
    assert np.all(e["omega"] < 1e-8) and e["flagged"] is False
    assert e["reference_order"] == {"rod": 6} and e["reference_quadrature"] == {"rod": 20}
    with pytest.warns(flexure.AccuracyWarning, match=r"Mechanism\.modes: mode 1"):
        coarse = flexure.Mechanism.from_toml(ROD.format(order=1)).modes()
    e = coarse["error_estimate"]
    truth = np.abs(coarse["omega"] / exact - 1.0)
    assert np.all(truth > 0.1) and np.all(np.abs(e["omega"] - truth) < 1e-9)
    assert e["flagged"] is True


BALL = """
dimension = 3
gravity = [0.0, 0.0, -9.81]
[[joint]]
name = "ball"
kind = "spherical"
parent = "ground"
child = "bob"
[[body]]
name = "bob"
mass = 0.1
com = [0.0, 0.0, -0.5]
[initial]
ball = [{theta}, 0.0, 0.0]
"""

PLANAR_PENDULUM = """
gravity = [0.0, -9.81]
[[joint]]
name = "pin"
kind = "revolute"
parent = "ground"
child = "bob"
[[body]]
name = "bob"
mass = 0.1
com = [0.0, -0.5]
[initial]
pin = {theta}
"""


def test_ball_pendulum_swings_as_the_planar_pendulum():
    # Reference: the planar Mechanism's pendulum (a revolute joint, the same mass and length):
    # released from 0.8 rad about x, the ball swings in the y-z plane with the planar angle,
    # theta'' = -(g/l) sin theta, to 1e-7 rad at every sample (both at tolerance 1e-10 over ~300
    # steps); energy constant to 1e-10 J; every rotation matrix orthonormal to 1e-12.
    theta = 0.8
    run = flexure.Mechanism.from_toml(BALL.format(theta=theta)).simulate(1.0, every=0.1, tolerance=1e-10)
    ref = flexure.Mechanism.from_toml(PLANAR_PENDULUM.format(theta=theta)).simulate(1.0, every=0.1, tolerance=1e-10)
    assert run["dimension"] == 3 and run["time"].shape == (11,) and np.allclose(run["time"], ref["time"])
    q = run["coordinates"]["ball"]
    assert q.shape == (11, 3) and run["velocities"]["ball"].shape == (11, 3)
    assert np.abs(q[:, 0] - ref["coordinates"]["pin"][:, 0]).max() < 1e-7
    assert np.abs(q[:, 1:]).max() < 1e-12
    bob = run["bodies"]["bob"]
    assert position(bob).shape == (3, 11) and bob["rotation"].shape == (11, 3, 3)
    assert orthonormal(bob["rotation"])
    # The bob's centre, R (0, 0, -l), on the circle of radius l in the y-z plane.
    centre = bob["rotation"] @ np.array([0.0, 0.0, -0.5])
    assert np.abs(centre[:, 1] - 0.5 * np.sin(q[:, 0])).max() < 1e-12
    assert np.ptp(run["energy"]) < 1e-10
    assert run["steps"] > 0 and run["rejected"] >= 0 and run["violation"] == 0.0


def test_free_ball_has_no_equilibrium_to_solve_or_vibrate_about():
    # A ball pendulum turns freely about the vertical: no equilibrium is isolated.
    m = flexure.Mechanism.from_toml(BALL.format(theta=0.0))
    for call in (m.solve, m.modes):
        with pytest.raises(ValueError, match="zero-stiffness"):
            call()


# --- MuJoCo ---------------------------------------------------------------------------------

# A rigid chain of three hinges, axes z, then y, then x, each body with a mass, an offset centre
# of mass and a full inertia about it (MuJoCo's fullinertia order ixx iyy izz ixy ixz iyz, in
# the body frame), the second joint's frame turned by rpy; no springs, no damping, gravity
# askew. Written once for both: flexure's `ixx ... iyz` keys are MuJoCo's components.
GRAVITY = [0.8, -0.5, -9.81]
CHAIN = [  # joint, axis, origin and rpy in the parent's frame; body, mass, com, inertia
    ("j1", [0, 0, 1], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], "b1", 1.2, [0.1, 0.02, -0.03],
     [0.020, 0.030, 0.025, 0.002, -0.001, 0.0015]),
    ("j2", [0, 1, 0], [0.2, 0.0, 0.05], [0.2, -0.1, 0.3], "b2", 0.7, [0.15, -0.01, 0.02],
     [0.008, 0.012, 0.010, -0.001, 0.0005, 0.0008]),
    ("j3", [1, 0, 0], [0.25, 0.05, 0.0], [0.0, 0.0, 0.0], "b3", 0.4, [0.05, 0.1, -0.02],
     [0.004, 0.003, 0.005, 0.0003, -0.0004, 0.0002]),
]  # fmt: skip
Q0, V0 = [0.3, -0.5, 0.8], [1.0, -2.0, 1.5]


def _numbers(v, sep):
    return sep.join(repr(float(x)) for x in v)


def chain_toml():
    out = [f"dimension = 3\ngravity = [{_numbers(GRAVITY, ', ')}]\n"]
    parent = "ground"
    for joint, axis, origin, rpy, body, *_ in CHAIN:
        out.append(
            f'[[joint]]\nname = "{joint}"\nkind = "revolute"\nparent = "{parent}"\nchild = "{body}"\n'
            f"axis = [{_numbers(axis, ', ')}]\norigin = [{_numbers(origin, ', ')}]\nrpy = [{_numbers(rpy, ', ')}]\n"
        )
        parent = body
    for *_, body, mass, com, inertia in CHAIN:
        keys = "".join(f"{k} = {x!r}\n" for k, x in zip(("ixx", "iyy", "izz", "ixy", "ixz", "iyz"), inertia))
        out.append(f'[[body]]\nname = "{body}"\nmass = {mass!r}\ncom = [{_numbers(com, ", ")}]\n{keys}')
    out.append("[initial]\n" + "".join(f"{c[0]} = {q!r}\n" for c, q in zip(CHAIN, Q0)))
    out.append("[initial_velocity]\n" + "".join(f"{c[0]} = {v!r}\n" for c, v in zip(CHAIN, V0)))
    return "\n".join(out)


def quaternion(rpy):
    """URDF's R = Rz(yaw) Ry(pitch) Rx(roll) as MuJoCo's quat (w, x, y, z): qz qy qx."""

    def about(axis, a):
        q = np.zeros(4)
        q[0], q[1 + axis] = math.cos(a / 2), math.sin(a / 2)
        return q

    def times(a, b):
        w1, x1, y1, z1 = a
        w2, x2, y2, z2 = b
        return np.array(
            [
                w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
                w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
            ]
        )

    roll, pitch, yaw = rpy
    return times(times(about(2, yaw), about(1, pitch)), about(0, roll))


def chain_mjcf():
    # MuJoCo XML reference (mujoco.readthedocs.io, XMLreference: body, joint, inertial, option):
    # a body's pos and quat place its frame in its parent's; a hinge's axis is in the frame of
    # the body holding it, through its pos (default the body's origin); inertial pos is the
    # centre of mass in the body frame, fullinertia the inertia about it in the inertial frame
    # (no quat: the body's axes), ordered M11 M22 M33 M12 M13 M23. No geoms: no contacts.
    out = [
        f'<mujoco model="chain"><option timestep="1e-4" integrator="RK4" gravity="{_numbers(GRAVITY, " ")}">'
        '<flag contact="disable" energy="enable"/></option><worldbody>'
    ]
    for joint, axis, origin, rpy, body, mass, com, inertia in CHAIN:
        out.append(
            f'<body name="{body}" pos="{_numbers(origin, " ")}" quat="{_numbers(quaternion(rpy), " ")}">'
            f'<joint name="{joint}" type="hinge" axis="{_numbers(axis, " ")}" damping="0" armature="0"/>'
            f'<inertial pos="{_numbers(com, " ")}" mass="{mass!r}" fullinertia="{_numbers(inertia, " ")}"/>'
        )
    out.append("</body>" * len(CHAIN) + "</worldbody></mujoco>")
    return "".join(out)


def test_mujoco_agrees_on_a_rigid_3d_chain():
    # Reference: MuJoCo (RK4 at 1e-4 s) on the same chain from the same state. Over 1 s the
    # joint angles agree to 1e-7 rad at 10 sample times: flexure's error is bounded by its local
    # tolerance 1e-10 times its ~800 steps (8e-8), RK4's global error at h = 1e-4 is ~h^4 times
    # the motion's fourth derivative, far below that (they agree to ~1e-11 in fact). Each
    # body's world frame (MuJoCo's xpos, xmat) agrees to 1e-7 at the end. Total energy (both:
    # kinetic plus -m g.x of every centre, so the same datum) agrees at the start to 1e-12 J
    # and is conserved by each to 1e-9 J over the run.
    mujoco = pytest.importorskip("mujoco")
    model = mujoco.MjModel.from_xml_string(chain_mjcf())
    # The compiled inertia (principal moments in a rotated frame) is the given full matrix.
    for k, (*_, mass, com, (ixx, iyy, izz, ixy, ixz, iyz)) in enumerate(CHAIN, start=1):
        rot = np.zeros(9)
        mujoco.mju_quat2Mat(rot, model.body_iquat[k])
        rot = rot.reshape(3, 3)
        full = rot @ np.diag(model.body_inertia[k]) @ rot.T
        given = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
        assert np.abs(full - given).max() < 1e-12 and model.body_mass[k] == mass
        assert np.abs(model.body_ipos[k] - com).max() < 1e-15
    assert model.nv == 3 and model.ngeom == 0
    data = mujoco.MjData(model)
    data.qpos[:], data.qvel[:] = Q0, V0
    mujoco.mj_forward(model, data)
    angles, energy = [data.qpos.copy()], [data.energy.sum()]
    for _ in range(10):
        for _ in range(1000):
            mujoco.mj_step(model, data)
        angles.append(data.qpos.copy())
        energy.append(data.energy.sum())
    angles, energy = np.array(angles), np.array(energy)
    assert abs(data.time - 1.0) < 1e-9

    run = flexure.Mechanism.from_toml(chain_toml()).simulate(1.0, every=0.1, tolerance=1e-10)
    ours = np.column_stack([run["coordinates"][c[0]][:, 0] for c in CHAIN])
    assert np.allclose(run["time"], np.linspace(0.0, 1.0, 11), atol=1e-12)
    assert np.abs(ours[0] - Q0).max() == 0.0
    # The motion is far from trivial: every joint travels more than a radian.
    assert np.all(np.ptp(angles, axis=0) > 1.0)
    assert np.abs(ours - angles).max() < 1e-7
    for k, (*_, body, _mass, _com, _inertia) in enumerate(CHAIN, start=1):
        b = run["bodies"][body]
        assert np.abs(position(b)[:, -1] - data.xpos[k]).max() < 1e-7
        assert np.abs(b["rotation"][-1] - data.xmat[k].reshape(3, 3)).max() < 1e-7
        assert orthonormal(b["rotation"])
    assert abs(run["energy"][0] - energy[0]) < 1e-12
    assert np.abs(run["energy"] - run["energy"][0]).max() < 1e-9
    assert np.abs(energy - energy[0]).max() < 1e-9


# --- refusals -------------------------------------------------------------------------------


def test_what_spatial_files_do_not_have_yet_is_refused_by_name():
    m = hinges()
    # Export writes a spatial file's rigid joints as MuJoCo's own (test_export_spatial.py); a ball
    # in URDF, which has none, is refused naming it.
    xml, _ = m.export()
    assert '<joint name="yaw" type="hinge"' in xml and '<joint name="roll" type="hinge"' in xml
    ball = flexure.Mechanism.from_toml(HINGES.format(k1=1.0, k2=2.0).replace('"revolute"\nparent = "arm"', '"spherical"\nparent = "arm"').replace("axis = [1.0, 0.0, 0.0]\n", ""))
    with pytest.raises(ValueError, match=r"joint = roll: is a ball, which URDF cannot hold"):
        ball.export(to="urdf")


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda m: m.compliance("nobody"), 'body = "nobody"'),
        (lambda m: m.compliance("hand", (0.0, 0.0)), r"at = \(0\.0, 0\.0\): must be three numbers"),
        (lambda m: m.compliance("hand", (0.0, float("nan"), 0.0)), "at"),
        (lambda m: m.solve(accuracy=(-1.0, 0.1)), "accuracy"),
        (lambda m: m.modes(count=5), "count"),
        (lambda m: m.modes(accuracy=-1.0), "accuracy"),
        (lambda m: m.buckle(accuracy=0.0), "accuracy"),
        (lambda m: m.simulate(1.0, start="moving"), "start"),
        (lambda m: m.simulate(-1.0), "duration"),
        (lambda m: m.simulate(1.0, every=0.0), "every"),
        (lambda m: m.simulate(1.0, tolerance=float("nan")), "tolerance"),
        (lambda m: m.sweep("force.nothing.fx", [1.0]), "parameter"),
        (lambda m: m.sweep("gravity.w", [1.0]), "parameter"),
        (lambda m: m.sweep("gravity.z", []), "values"),
        (lambda m: m.sweep("gravity.z", "abc"), "values"),
        (lambda m: m.sweep("gravity.z", [1.0], at=(0.0, 0.0, 0.0)), "compliance"),
        (lambda m: m.sweep("gravity.z", [1.0], compliance="nobody"), "nobody"),
    ],
)
def test_bad_arguments_raise_value_error_naming_them(call, match):
    m = hinges(extra='[[body]]\nname = "hand"\nmass = 0.1\ncom = [0.0, 0.0, 0.05]\n')
    with pytest.raises(ValueError, match=match):
        call(m)


def test_a_boolean_point_is_refused_as_everywhere_in_the_package():
    # The package's rule (test_strict.py): a boolean where a number goes is a TypeError naming it.
    with pytest.raises(TypeError, match="'at'.*boolean"):
        hinges().compliance("hand", (True, 0.0, 0.0))


def test_errors_in_a_spatial_file_name_it_line_and_column(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(HINGES.format(k1=1.0, k2=2.0).replace("axis = [1.0, 0.0, 0.0]", "axis = [0.0, 0.0, 0.0]"))
    with pytest.raises(ValueError, match=rf"^{bad}: line \d+, column \d+: joint \"roll\": axis"):
        flexure.Mechanism.from_file(bad)
