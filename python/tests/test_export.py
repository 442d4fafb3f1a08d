"""Mechanism.export checked in real clients: the writer's exactness on a mechanism without
flexures, MuJoCo's springs against the fits, and SDFormat and URDF exports parsed with
published parsers (python-sdformat, yourdfpy). The examples are stepped in MuJoCo itself, to
rest and for their frequencies, in test_export_mujoco.py.

The writer's check solves the static balance on MuJoCo's own forces, to rounding (stepping
stops at the pin's softness, 1e-8 m): at zero velocity
and acceleration the generalized force qfrc_passive + qfrc_actuator - qfrc_bias (springs,
the keyframe's tendon and force actuators, gravity) plus J^T mu of the equality
constraints (welds, pins) must vanish with the constraints closed, J and their residual
being MuJoCo's efc_J and efc_pos. Newton on those equations, its Jacobian by central
differences of MuJoCo's forces, loads ramped in 10 steps, at most 60 iterations a step.
Small-motion frequencies: MuJoCo's mass matrix (mj_fullM) and the stiffness by central
differences of the same forces at the balance, restricted to the null space of J.
"""

import io
import warnings
from pathlib import Path

import mujoco
import numpy as np
import pysdf
import pytest
import yourdfpy

import flexure

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
# The planar examples (the spatial ones are exported in test_export_spatial.py), but those
# with shapes their parts may touch (`[[geom]]`, the grasp's), which export refuses.
PLANAR = sorted(p.name for p in EXAMPLES.glob("*.toml") if "dimension = 3" not in p.read_text() and "[[geom]]" not in p.read_text())

# A mechanism of rigid joints only: springs with rest values, a slider, a fixed joint,
# masses off their frames' origins, gravity off the axes, a tendon through three bodies,
# a force with a moment, and a pin open at rest (closed by a preload). Its export has no
# fitted part, so MuJoCo must agree with the library to rounding.
RIGID = """
gravity = [0.3, -9.81]
[[joint]]
name = "shoulder"
kind = "revolute"
parent = "ground"
child = "upper"
origin = [0.0, 0.0, 0.2]
stiffness = 2.0
rest = 0.1
[[joint]]
name = "slider"
kind = "prismatic"
parent = "upper"
child = "carriage"
origin = [0.1, 0.0, 0.3]
stiffness = 50.0
rest = 0.01
[[joint]]
name = "elbow"
kind = "revolute"
parent = "carriage"
child = "hand"
origin = [0.02, 0.0, -0.2]
stiffness = 1.0
rest = -0.1
[[joint]]
name = "mount"
kind = "fixed"
parent = "hand"
child = "finger"
origin = [0.08, 0.0, 0.5]
[[joint]]
name = "strut"
kind = "revolute"
parent = "ground"
child = "prop"
origin = [0.15, -0.05, 1.2]
stiffness = 0.5
[[body]]
name = "upper"
mass = 0.1
inertia = 1e-3
com = [0.05, 0.01]
[[body]]
name = "carriage"
mass = 0.05
inertia = 2e-4
[[body]]
name = "hand"
mass = 0.03
inertia = 1e-4
com = [0.04, 0.0]
[[body]]
name = "finger"
mass = 0.01
inertia = 1e-5
com = [0.01, 0.005]
[[body]]
name = "prop"
mass = 0.02
inertia = 5e-5
com = [0.05, 0.0]
[[tendon]]
name = "pull"
tension = 2.0
path = [["ground", 0.0, 0.05], ["upper", 0.05, 0.02], ["hand", 0.03, 0.01]]
[[force]]
name = "push"
body = "finger"
at = [0.02, 0.0]
force = [0.5, -1.0]
moment = 0.05
[[pin]]
a = "prop"
a_at = [0.12, 0.0]
b = "hand"
b_at = [0.06, 0.0]
preload = true
"""


def load(xml):
    m = mujoco.MjModel.from_xml_string(xml)
    m.opt.jacobian = mujoco.mjtJacobian.mjJAC_DENSE
    return m


def forces(m, d, q, ctrl):
    """MuJoCo's generalized force at rest at q, and its equality constraints' J and residual."""
    d.qpos[:] = q
    d.qvel[:] = 0
    d.ctrl[:] = ctrl
    mujoco.mj_forward(m, d)
    f = d.qfrc_passive + d.qfrc_actuator - d.qfrc_bias
    eq = d.efc_type == mujoco.mjtConstraint.mjCNSTR_EQUALITY
    J = d.efc_J.reshape(d.nefc, m.nv)[eq].copy() if d.nefc else np.zeros((0, m.nv))
    c = d.efc_pos[eq].copy() if d.nefc else np.zeros(0)
    return f.copy(), J, c


def balance(m, steps=10, iterations=60, tol=1e-11, h=1e-7):
    """Static balance under the keyframe's controls and the model's gravity, loads ramped in
    `steps`; raises naming the load fraction and residual if Newton does not converge."""
    d = mujoco.MjData(m)
    ctrl = m.key_ctrl[0].copy() if m.nkey else np.zeros(m.nu)
    gravity = m.opt.gravity.copy()
    q, mu = m.qpos0.copy(), None
    try:
        for k in range(steps + 1):
            lam = k / steps
            m.opt.gravity[:] = lam * gravity
            for _ in range(iterations):
                f, J, c = forces(m, d, q, lam * ctrl)
                mu = np.zeros(len(c)) if mu is None else mu
                r = np.concatenate([f + J.T @ mu, c])
                if np.linalg.norm(r) < tol:
                    break
                K = np.zeros((m.nv, m.nv))
                G = np.zeros((len(c), m.nv))
                for i in range(m.nv):
                    a, b = q.copy(), q.copy()
                    a[i] += h
                    b[i] -= h
                    fa, Ja, ca = forces(m, d, a, lam * ctrl)
                    fb, Jb, cb = forces(m, d, b, lam * ctrl)
                    K[:, i] = (fa + Ja.T @ mu - fb - Jb.T @ mu) / (2 * h)
                    G[:, i] = (ca - cb) / (2 * h)
                A = np.block([[K, J.T], [G, np.zeros((len(c), len(c)))]])
                step = np.linalg.lstsq(A, -r, rcond=1e-12)[0]
                q, mu = q + step[: m.nv], mu + step[m.nv :]
            else:
                raise AssertionError(f"MuJoCo balance: no convergence at load fraction {lam}, residual {np.linalg.norm(r):.3e}")
    finally:
        m.opt.gravity[:] = gravity
    forces(m, d, q, ctrl)
    return q, mu, d


def poses(m, d):
    out = {}
    for b in range(1, m.nbody):
        w, _, _, z = d.xquat[b]
        out[mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_BODY, b)] = (d.xpos[b][0], d.xpos[b][1], 2 * np.arctan2(z, w))
    return out


def frequencies(m, q, mu, h=1e-7):
    """Small-motion frequencies (rad/s) about the balance q, closures respected."""
    d = mujoco.MjData(m)
    ctrl = m.key_ctrl[0].copy() if m.nkey else np.zeros(m.nu)

    def force(q):
        f, J, c = forces(m, d, q, ctrl)
        return (f + J.T @ mu if len(c) else f), J

    K = np.zeros((m.nv, m.nv))
    for i in range(m.nv):
        a, b = q.copy(), q.copy()
        a[i] += h
        b[i] -= h
        K[:, i] = -(force(a)[0] - force(b)[0]) / (2 * h)
    K = 0.5 * (K + K.T)
    _, J = force(q)
    M = np.zeros((m.nv, m.nv))
    mujoco.mj_fullM(m, d, M)
    Z = np.eye(m.nv)
    if J.shape[0]:
        _, s, vt = np.linalg.svd(J)
        Z = vt[int((s > 1e-9 * max(s.max(), 1.0)).sum()) :].T
    L = np.linalg.inv(np.linalg.cholesky(Z.T @ M @ Z))
    return np.sqrt(np.clip(np.linalg.eigvalsh(L @ (Z.T @ K @ Z) @ L.T), 0, None))


def exported(path, to="mjcf", prb="3R"):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        xml, report = flexure.Mechanism.from_file(path).export(to=to, prb=prb)
    return xml, report, [str(w.message) for w in caught]


def test_rigid_mechanism_balances_and_rings_in_mujoco_as_in_the_library(tmp_path):
    # No fit: the writer alone. MuJoCo's balance against the library's solve, to 1e-12 m
    # and rad (measured 3e-17: rounding); frequencies to 1e-6 relative (measured 1e-10,
    # the central differences of the stiffness).
    path = tmp_path / "rigid.toml"
    path.write_text(RIGID)
    xml, report, caught = exported(path)
    assert caught == [] and report["joints"] == {}
    m = load(xml)
    q, mu, d = balance(m)
    mech = flexure.Mechanism.from_file(path)
    solved = mech.solve()["bodies"]
    for name, (x, y, phi) in poses(m, d).items():
        s = solved[name]
        assert np.hypot(x - s["x"], y - s["y"]) < 1e-12 and abs(phi - s["phi"]) < 1e-12, name
    omega = mech.modes(count=2)["omega"]
    np.testing.assert_allclose(frequencies(m, q, mu), omega, rtol=1e-6)


@pytest.mark.parametrize("prb", ["1R", "3R"])
def test_mujoco_springs_are_the_fits_torque(prb):
    # MuJoCo's spring force on each hinge, qfrc_spring = -(k1 x + k2 x^2 + k3 x^3) with the
    # fit's stiffness, at angles across the fit's range: to 1e-12 relative (rounding).
    xml, report, _ = exported(EXAMPLES / "finger.toml", prb=prb)
    m = load(xml)
    d = mujoco.MjData(m)
    k = np.array([s for j in report["joints"].values() for s in j["stiffness"]])
    for theta in (-0.6, -0.1, 0.25, 0.8):
        d.qpos[:] = theta * np.linspace(0.5, 1.0, m.nq)
        mujoco.mj_forward(m, d)
        x = d.qpos
        expected = -(k[:, 0] * x + k[:, 1] * x**2 + k[:, 2] * x**3)
        np.testing.assert_allclose(d.qfrc_spring, expected, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("prb", ["1R", "3R"])
@pytest.mark.parametrize("name", PLANAR)
def test_sdf_and_urdf_parse_and_name_every_loss(name, prb):
    path = EXAMPLES / name
    spec = flexure.Mechanism.from_file(path)
    bodies = set(spec.solve()["bodies"]) - {"ground"}
    sdf, report, caught = exported(path, to="sdf", prb=prb)
    model = pysdf.SDF.from_xml(sdf)
    assert model.version == "1.9"
    assert bodies <= {link.name for link in model.iter("link")}
    # A flexure's hinge is named for it (1R), or NAME_1 to NAME_3 (3R).
    hinges = {joint.name for joint in model.iter("joint")}
    for j in report["joints"]:
        assert (j if prb == "1R" else f"{j}_1") in hinges, (j, hinges)
    urdf, report, caught = exported(path, to="urdf", prb=prb)
    robot = yourdfpy.URDF.load(io.StringIO(urdf), build_scene_graph=True, load_meshes=False)
    assert bodies <= set(robot.link_map) and "world" in robot.link_map
    text = path.read_text()
    # Every spring (each fitted hinge), tendon, force and closure is named in a warning.
    for j, fit in report["joints"].items():
        assert any(f'"{j}' in w and "no springs" in w for w in caught), (j, caught)
    for kind in ("tendon", "force"):
        for line in text.splitlines():
            if line.startswith(f"[[{kind}]]"):
                assert any(w.startswith(f"{kind} ") and "not written" in w for w in caught), (kind, caught)
    closures = text.count("[[weld]]") + text.count("[[pin]]")
    assert sum("no loops" in w for w in caught) == closures
    assert report["warnings"] == caught


def test_bad_arguments_raise_value_error_naming_them():
    m = flexure.Mechanism.from_file(EXAMPLES / "finger.toml")
    for kwargs, word in [
        ({"to": "xml"}, "to"),
        ({"prb": "2R"}, "prb"),
        ({"range": "0:1"}, "range"),
        ({"range": (0, 1, 1)}, "range"),
        ({"range": (0, 1, True)}, "range"),
        ({"armature": -1.0}, "armature"),
        ({"step": -0.002}, "step"),
        ({"step": float("nan")}, "step"),
    ]:
        with pytest.raises(ValueError, match=word):
            m.export(**kwargs)


def test_mujocos_log_is_written_in_the_tests_directory_not_the_tree(tmp_path):
    # MuJoCo writes MUJOCO_LOG.TXT to the working directory at its first warning (here an
    # infinite applied force: "Nan, Inf or huge value in QACC"); conftest.py runs every test in
    # its own tmp_path, so the log lands there and never in the source tree.
    m = mujoco.MjModel.from_xml_string(
        '<mujoco><worldbody><body><joint type="slide"/><geom size="0.1"/></body></worldbody></mujoco>'
    )
    d = mujoco.MjData(m)
    d.qfrc_applied[0] = np.inf
    mujoco.mj_step(m, d)
    assert Path.cwd() == tmp_path
    assert "QACC" in (tmp_path / "MUJOCO_LOG.TXT").read_text()
