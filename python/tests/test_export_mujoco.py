"""Exported MJCF models stepped in MuJoCo itself (issue 36): every planar example, 1R and 3R,
steps stably at the step it is written for (MuJoCo's default 2 ms, default solver), from
qpos0 and from its keyframe; stepped to rest with damping under the keyframe's loads, each
body is where `solve` puts it within the fit errors carried through lever arms, and each
closure is closed within the fit error; MuJoCo's own linearization (mjd_transitionFD) rings
at `modes`' lowest frequency.

No Newton here: the rest is reached by mj_step alone. Damping is added for the settling only
(2 sqrt(k M_ii) on each coordinate, M_ii from mj_fullM): it moves no balance.
"""

import contextlib
import io
import warnings

import mujoco
import numpy as np
import pytest

import flexure
from test_export import EXAMPLES, PLANAR, poses

CASES = [pytest.param(f, prb, id=f"{f}-{prb}") for f in PLANAR for prb in ("1R", "3R")]


def exported(source, prb, **kwargs):
    """The MJCF, report and warnings of a mechanism file (a path) or its text (a str)."""
    mechanism = flexure.Mechanism.from_toml(source) if isinstance(source, str) else flexure.Mechanism.from_file(source)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        xml, report = mechanism.export(to="mjcf", prb=prb, **kwargs)
    return xml, report, [str(w.message) for w in caught]


def unstable(d):
    return d.warning[mujoco.mjtWarning.mjWARN_BADQACC].number > 0 or not np.all(np.isfinite(d.qpos))


def steps_stably(xml, report):
    """Two seconds at the model's own step, MuJoCo's default 2 ms, with no damping but the
    file's: from qpos0 unloaded, then from the keyframe with every load applied at once."""
    m = mujoco.MjModel.from_xml_string(xml)
    assert m.opt.timestep == 0.002 and report["step"] == 0.002
    for key in (False, True):
        d = mujoco.MjData(m)
        mujoco.mj_resetDataKeyframe(m, d, 0) if key and m.nkey else mujoco.mj_resetData(m, d)
        for _ in range(1000):
            mujoco.mj_step(m, d)
            assert not unstable(d), f"{'keyframe' if key else 'qpos0'}: unstable at t = {d.time:.4f} s"


def settle(m, tol=1e-10, seconds=20.0):
    """Steps from the keyframe (loads on) with settling damping until every velocity is under
    tol; fails on an unstable step or no rest in `seconds`. Returns the data at rest."""
    m = mujoco.MjModel.from_xml_string(m) if isinstance(m, str) else m
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0) if m.nkey else mujoco.mj_resetData(m, d)
    mujoco.mj_forward(m, d)
    M = np.zeros((m.nv, m.nv))
    mujoco.mj_fullM(m, d, M)
    k = m.jnt_stiffness[m.dof_jntid]
    m.dof_damping[:] += 2 * np.sqrt(np.maximum(k, 0) * np.diag(M))
    for i in range(int(seconds / m.opt.timestep)):
        mujoco.mj_step(m, d)
        assert not unstable(d), f"unstable at t = {d.time:.4f} s"
        if i % 50 == 49 and np.abs(d.qvel).max() < tol:
            mujoco.mj_forward(m, d)
            return m, d
    raise AssertionError(f"not at rest after {seconds} s: |qvel| {np.abs(d.qvel).max():.3e}")


def gaps(m, d):
    """Each closure's opening at d: (distance between its sites (m), turn between them (rad), 0 for a pin)."""
    out = []
    for e in range(m.neq):
        a, b = m.eq_obj1id[e], m.eq_obj2id[e]
        dist = np.linalg.norm(d.site_xpos[a] - d.site_xpos[b])
        R = d.site_xmat[a].reshape(3, 3).T @ d.site_xmat[b].reshape(3, 3)
        turn = abs(np.arctan2(R[1, 0], R[0, 0])) if m.eq_type[e] == mujoco.mjtEq.mjEQ_WELD else 0.0
        out.append((dist, turn))
    return out


def check_flags(fits, caught):
    """Each fit is flagged exactly when past 1 % of L or 1°, and each flagged one warned of by name."""
    for j, f in fits.items():
        over = f["error"]["position"] > 0.01 * f["length"] or f["error"]["angle"] > np.pi / 180
        assert f["flagged"] == over, j
        if over:
            assert any(f'"{j}"' in w and "1 % of L or 1°" in w for w in caught), caught


def bounds(fits, g, span):
    """(margin, e_pos, e_ang, soft_pos, soft_ang) of the rest check: the fit errors carried through
    lever arms (position: sum of e_pos + e_angle * span; angle: sum of e_angle), the margin (1.1
    for a tree, 2 with closures), and the closures' softness from their gaps g."""
    e_pos = sum(f["error"]["position"] + f["error"]["angle"] * span for f in fits.values())
    e_ang = sum(f["error"]["angle"] for f in fits.values())
    margin = 2.0 if g else 1.1
    shortest = min(f["length"] for f in fits.values())
    soft_pos = margin * sum(p + t * span for p, t in g)
    soft_ang = margin * sum(t + p / shortest for p, t in g)
    return margin, e_pos, e_ang, soft_pos, soft_ang


@pytest.mark.parametrize("name, prb", CASES)
def test_examples_step_stably_from_rest_and_from_their_keyframe(name, prb):
    # Two seconds, no damping but the file's, at the model's own step (MuJoCo's default 2 ms),
    # from qpos0 unloaded and from the keyframe with every load applied at once. Before issue 36,
    # 15 of these 16 models blew up ("Nan, Inf or huge value in QACC") within 8 ms.
    steps_stably(*exported(EXAMPLES / name, prb)[:2])


@pytest.mark.parametrize("name, prb", CASES)
def test_examples_rest_in_mujoco_where_solve_says(name, prb):
    # Stepped to rest, each body against `solve`. The tolerance is the fit errors carried
    # through lever arms: position sum over flexures of (e_pos + e_angle * span), angle sum of
    # e_angle (span: the largest distance between two bodies plus the longest flexure), times 1.1
    # for a tree and 2 with closures (a closure turns one flexure's angle error into another's
    # position), to which each closure's softness at rest adds its gap g (measured below), and
    # g / L_min of turn: a closure open by g turns the bodies it holds by about g over their
    # lever (the parallelogram's stage, pivoting on one leg's tip 40 mm from the other's, turns
    # 3.9e-5 rad at a 1.6e-6 m gap, where the fits are exact: nothing bends). Flagged fits
    # (past 1 % of L or 1°: every 1R but the parallelogram's and the tapered finger's) are
    # checked to be flagged and warned of by name, and held to the same bound from their own
    # (larger) errors.
    path = EXAMPLES / name
    xml, report, caught = exported(path, prb)
    fits = report["joints"]
    check_flags(fits, caught)
    if prb == "3R":
        assert not any(f["flagged"] for f in fits.values()), "the default chain is unflagged on every example"
    m, d = settle(xml)
    # The hinges' limits (where a fitted spring stops holding) are not met at rest.
    assert not (d.efc_type[: d.nefc] == mujoco.mjtConstraint.mjCNSTR_LIMIT_JOINT).any()
    solved = flexure.Mechanism.from_file(path).solve()["bodies"]
    points = np.array([[b["x"], b["y"]] for b in solved.values()])
    span = max(np.hypot(*(p - r)) for p in points for r in points) + max(f["length"] for f in fits.values())
    margin, e_pos, e_ang, soft_pos, soft_ang = bounds(fits, gaps(m, d), span)
    for body, (x, y, phi) in poses(m, d).items():
        if body not in solved:
            continue  # a pseudo-rigid link
        s = solved[body]
        dp, da = np.hypot(x - s["x"], y - s["y"]), abs(phi - s["phi"])
        assert dp <= margin * e_pos + soft_pos + 1e-9 * span, f"{body}: {dp:.3e} m against {e_pos:.3e}"
        assert da <= margin * e_ang + soft_ang + 1e-9, f"{body}: {da:.3e} rad against {e_ang:.3e}"


# Closures at rest, stepped: their gap against the fit errors of the flexures, each tip's angle
# error carried over a flexure's length (a 1R leg's tip turns by Howell's Theta, not c_theta Theta,
# and four welded legs strain to agree), or against the closure's own softness where the fits are
# exact. A soft constraint at rest is open
# by (1 - d)/(d k) times the acceleration it holds back, k = 1/(d tc)^2: the export's solimp d =
# 0.9999 and solref tc = 2 steps leave about 1.6e-9 s^2 times that acceleration (MuJoCo's default
# d = 0.9-0.95, tc = 0.02 s: 2e-5 s^2, the four-bar's 0.54 mm). Bound on the softness: 1e-4 of the
# shortest flexure, 1e-4 rad. Measured: four_bar 8e-8 m (1R), 7e-8 m (3R); four_leg_stage 5e-6 m
# (1R), 5e-6 m and 1e-4 rad (3R); parallelogram 1.4e-7 m (1R), 1.6e-6 m (3R).
@pytest.mark.parametrize("name, prb", [c for c in CASES if any(k in c.id for k in ("four_bar", "four_leg", "parallelogram"))])
def test_closures_hold_at_rest(name, prb):
    xml, report, _ = exported(EXAMPLES / name, prb)
    m, d = settle(xml)
    fits = report["joints"].values()
    e_pos = sum(f["error"]["position"] + f["error"]["angle"] * f["length"] for f in fits)
    e_ang = sum(f["error"]["angle"] for f in fits)
    floor = 1e-4 * min(f["length"] for f in fits)
    g = gaps(m, d)
    assert g, "a closed mechanism has closures"
    for dist, turn in g:
        assert dist <= max(e_pos, floor), f"gap {dist:.3e} m against {e_pos:.3e} (floor {floor:.1e})"
        assert turn <= max(2 * e_ang, 1e-4), f"turn {turn:.3e} rad against {e_ang:.3e}"


def lowest(m, d):
    """The lowest frequency (rad/s) of MuJoCo's own one-step linearization at d: each complex
    pair of eigenvalues lambda = r e^{i theta} of the transition matrix is an oscillator whose
    Euler step turns by theta, omega = 2 sin(theta / 2) / h (exact for the undamped semi-implicit
    Euler step, cos theta = 1 - (omega h)^2 / 2)."""
    A = np.zeros((2 * m.nv, 2 * m.nv))
    mujoco.mjd_transitionFD(m, d, 1e-8, 1, A, None, None, None)
    lam = np.linalg.eigvals(A)
    theta = np.abs(np.angle(lam[np.abs(lam.imag) > 1e-12]))
    return (2 * np.sin(theta / 2) / m.opt.timestep).min()


# The lowest frequency of MuJoCo's linearization about the stepped rest, against `modes`. Each
# model is exported for a step that resolves that mode (omega h <= 0.05, at most MuJoCo's 2 ms:
# tapered_finger's 5704 rad/s cannot be followed at 2 ms, where its armature brings it to 309
# rad/s), and the settling damping is taken off again for the linearization. Measured (issue 36,
# massless flexures' links merged): finger_dynamics 1R +23.4 %, 3R -0.6 %; four_bar 1R +16.3 %,
# 3R -4.8 %; tapered_finger 1R -8.2 %, 3R -3.4 %. Bands: 1R 25 % (a secant spring fitted over the range, and the tip's angle
# mismatch), 3R 5 % (the flexures' mass lumped on rigid links).
@pytest.mark.parametrize("name", ["finger_dynamics.toml", "four_bar.toml", "tapered_finger.toml"])
@pytest.mark.parametrize("prb, band", [("1R", 0.25), ("3R", 0.05)])
def test_examples_ring_in_mujoco_as_modes(name, prb, band):
    path = EXAMPLES / name
    want = flexure.Mechanism.from_file(path).modes(count=1)["omega"][0]
    step = min(0.002, 0.05 / want)
    xml, report, _ = exported(path, prb, step=step)
    m0 = mujoco.MjModel.from_xml_string(xml)
    m, d = settle(xml)
    m.dof_damping[:] = m0.dof_damping
    got = lowest(m, d)
    assert abs(got / want - 1) < band, f"{got:.4g} rad/s against {want:.4g}"


# Every example export takes (not those with `[[geom]]` shapes: export refuses parts that may touch).
EXPORTED = sorted(p.name for p in EXAMPLES.glob("*.toml") if "[[geom]]" not in p.read_text())
ALL = [pytest.param(f, prb, id=f"{f}-{prb}") for f in EXPORTED for prb in ("1R", "3R")]


@pytest.mark.parametrize("name, prb", ALL)
def test_no_body_sits_at_a_mass_floor(name, prb):
    # Issue 36: no link at a mass floor. Reference: the mechanism's lightest real body, the least
    # MuJoCo body_mass over the file's bodies (those `solve` names; a body the file leaves
    # massless is written at the least mass simulators accept, 1e-9 kg, and is its own
    # reference). Every body of the MJCF weighs at least 1e-6 of it: a massless flexure's links
    # are merged away (its hinges on the child body), a flexure with mass gives its links its own.
    # The one exception, stated: a spatial 3R chain's nine hinges cannot all go on one body
    # (MuJoCo holds at most 6 dofs a body), so its first link stays, at the least mass, and is
    # warned of by name.
    xml, report, caught = exported(EXAMPLES / name, prb)
    m = mujoco.MjModel.from_xml_string(xml)
    real = set(flexure.Mechanism.from_file(EXAMPLES / name).solve()["bodies"]) - {"ground"}
    names = {i: mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_BODY, i) for i in range(1, m.nbody)}
    lightest = min(m.body_mass[i] for i, n in names.items() if n in real)
    for i, n in names.items():
        if m.body_mass[i] >= 1e-6 * lightest:
            continue
        spatial_3r = report["dimension"] == 3 and prb == "3R" and n.endswith("_prb1")
        assert spatial_3r, f"{n}: {m.body_mass[i]:.3e} kg against the lightest real body's {lightest:.3e} kg"
        assert any(f'"{n}"' in w and "at most 6" in w for w in caught), caught
    if report["dimension"] == 2:
        # Where a file body is massless the reference is the floor itself, so also: a planar
        # pseudo-rigid body is left only with its flexure's own mass, above the 1e-9 kg floor.
        light = [n for i, n in names.items() if n not in real and m.body_mass[i] <= 1e-9]
        assert not light, light


def test_the_readmes_mujoco_snippet_rests_where_solve_says(tmp_path, monkeypatch):
    # The README's snippet, run as written on the finger exported as its `flexure export` line
    # does (3R, the default): what it prints is each body where `solve` puts it, to the six
    # digits it prints, and the README's own printed lines are that output.
    readme = (EXAMPLES.parent / "README.md").read_text()
    block = readme[readme.index('flexure export examples/finger.toml') :]
    code = block[block.index('python -c "') + len('python -c "') :]
    code, shown = code[: code.index('"\n')], block[: block.index("```\n")]
    xml, _, _ = exported(EXAMPLES / "finger.toml", "3R")
    (tmp_path / "finger.xml").write_text(xml)
    monkeypatch.chdir(tmp_path)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(code, {})
    lines = out.getvalue().strip().splitlines()
    assert [f"# {line}" for line in lines] == [l for l in shown.splitlines() if l.startswith("# ")]
    solved = flexure.Mechanism.from_file(EXAMPLES / "finger.toml").solve()["bodies"]
    for line in lines:
        name, rest = line.split(" ", 1)
        numbers = [float(x) for x in rest.replace("[", " ").replace("]", " ").split()]
        s = solved[name]
        assert np.allclose(numbers, [s["x"], s["y"], s["phi"]], atol=1e-6), (line, s)
