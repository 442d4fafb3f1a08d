"""Spatial mechanisms exported to MJCF (issue 36, item 5) and stepped in MuJoCo itself: each
spatial example steps stably at MuJoCo's default 2 ms step from qpos0 and from its keyframe;
stepped to rest with damping under the keyframe's loads, each body is where `solve` puts it
within the fit errors carried through lever arms; closures stay closed; MuJoCo's own
linearization (mjd_transitionFD) rings at `modes`' lowest frequency within a stated band.

No Newton here: the rest is reached by mj_step alone (test_export_mujoco.settle).
"""

import mujoco
import numpy as np
import pytest

import flexure
from test_export import EXAMPLES
from test_export_mujoco import bounds, check_flags, exported, lowest, settle, steps_stably

SPATIAL = ["finger3d.toml", "stage3d.toml", "continuum_robot.toml"]
CASES = [pytest.param(f, prb, id=f"{f}-{prb}") for f in SPATIAL for prb in ("1R", "3R")]


def turn(a, b):
    """The angle (rad) of the rotation between two rotation matrices."""
    c = (np.trace(a.T @ b) - 1) / 2
    return float(np.arccos(np.clip(c, -1.0, 1.0)))


def gaps(m, d):
    """Each closure's opening at d: (distance between its sites (m), turn between them (rad), 0 for a connect)."""
    out = []
    for e in range(m.neq):
        a, b = m.eq_obj1id[e], m.eq_obj2id[e]
        dist = np.linalg.norm(d.site_xpos[a] - d.site_xpos[b])
        weld = m.eq_type[e] == mujoco.mjtEq.mjEQ_WELD
        t = turn(d.site_xmat[a].reshape(3, 3), d.site_xmat[b].reshape(3, 3)) if weld else 0.0
        out.append((dist, t))
    return out


def test_spatial_export_writes_three_hinges_per_pivot_and_the_closures():
    xml, report, _ = exported(EXAMPLES / "stage3d.toml", "3R")
    m = mujoco.MjModel.from_xml_string(xml)
    assert report["dimension"] == 3 and report["prb"] == "3R"
    # Two flexures, three pivots each, three hinges a pivot: 18 hinges, all sprung.
    assert m.njnt == 18 and np.all(m.jnt_type == mujoco.mjtJoint.mjJNT_HINGE) and np.all(m.jnt_stiffness > 0)
    assert m.neq == 1 and m.eq_type[0] == mujoco.mjtEq.mjEQ_WELD
    assert m.nu == 1 and m.nkey == 1
    for j in ("left", "right"):
        f = report["joints"][j]
        assert len(f["pivots"]) == 3 and len(f["pivots"][0]) == 3
        assert len(f["stiffness"]) == len(f["stiffness_y"]) == len(f["stiffness_x"]) == 3
    # The stage's blade is wide along z: bending about y (the stiff axis) is (w / t)^2 stiffer.
    f = report["joints"]["left"]
    kz, ky = np.array(f["stiffness"])[:, 0], np.array(f["stiffness_y"])
    assert np.allclose(ky / kz, (0.01 / 0.0003) ** 2, rtol=1e-6)


def test_one_report_shape_in_both_dimensions():
    # The planar report's keys, top and per joint, in the spatial one: only stiffness_y and
    # stiffness_x are added (issue 34).
    _, planar, _ = exported(EXAMPLES / "finger_dynamics.toml", "3R")
    _, spatial, _ = exported(EXAMPLES / "finger3d.toml", "3R")
    assert set(planar) == set(spatial) and planar["dimension"] == 2 and spatial["dimension"] == 3
    for p, s in zip(planar["joints"].values(), spatial["joints"].values()):
        assert set(s) - set(p) == {"stiffness_y", "stiffness_x"} and set(p) <= set(s)


def test_spatial_sdf_and_urdf_are_refused_by_name():
    m = flexure.Mechanism.from_file(EXAMPLES / "finger3d.toml")
    for to in ("sdf", "urdf"):
        with pytest.raises(ValueError, match="mjcf only"):
            m.export(to=to)


@pytest.mark.parametrize("name, prb", CASES)
def test_spatial_examples_step_stably_from_rest_and_from_their_keyframe(name, prb):
    steps_stably(*exported(EXAMPLES / name, prb)[:2])


@pytest.mark.parametrize("name, prb", CASES)
def test_spatial_examples_rest_in_mujoco_where_solve_says(name, prb):
    # As in the plane (test_export_mujoco): position within margin * sum_j (e_pos + e_angle * span),
    # angle within margin * sum_j e_angle, margin 1.1 for a tree and 2 with closures, plus each
    # closure's softness (its gap g, and g / L_min of turn). The fit error here is the chain's
    # small-motion response against the model's tip over the load range, so it holds the large
    # motion's part too.
    path = EXAMPLES / name
    xml, report, caught = exported(path, prb)
    fits = report["joints"]
    check_flags(fits, caught)
    m, d = settle(xml)
    solved = flexure.Mechanism.from_file(path).solve()["bodies"]
    points = np.array([[b["x"], b["y"], b["z"]] for b in solved.values()])
    span = max(np.linalg.norm(p - r) for p in points for r in points) + max(f["length"] for f in fits.values())
    margin, e_pos, e_ang, soft_pos, soft_ang = bounds(fits, gaps(m, d), span)
    for body, s in solved.items():
        if body == "ground":
            continue
        i = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, body)
        dp = np.linalg.norm(d.xpos[i] - [s["x"], s["y"], s["z"]])
        da = turn(d.xmat[i].reshape(3, 3), np.array(s["rotation"]))
        assert dp <= margin * e_pos + soft_pos + 1e-9 * span, f"{body}: {dp:.3e} m against {e_pos:.3e}"
        assert da <= margin * e_ang + soft_ang + 1e-9, f"{body}: {da:.3e} rad against {e_ang:.3e}"


# The stage's weld at rest: its gap against the fit errors (each tip's angle error carried over
# its flexure's length), or the closure's own softness (1e-4 of the shortest flexure, 1e-4 rad).
@pytest.mark.parametrize("prb", ["1R", "3R"])
def test_spatial_closures_hold_at_rest(prb):
    xml, report, _ = exported(EXAMPLES / "stage3d.toml", prb)
    m, d = settle(xml)
    fits = report["joints"].values()
    e_pos = sum(f["error"]["position"] + f["error"]["angle"] * f["length"] for f in fits)
    e_ang = sum(f["error"]["angle"] for f in fits)
    floor = 1e-4 * min(f["length"] for f in fits)
    g = gaps(m, d)
    assert g, "the stage is welded"
    for dist, t in g:
        assert dist <= max(e_pos, floor), f"gap {dist:.3e} m against {e_pos:.3e} (floor {floor:.1e})"
        assert t <= max(2 * e_ang, 1e-4), f"turn {t:.3e} rad against {e_ang:.3e}"


# The lowest frequency of MuJoCo's linearization about the stepped rest, against `modes`, each
# model exported for a step resolving that mode (omega h <= 0.05, at most 2 ms), the settling
# damping taken off. Measured (issue 36, item 1, links merged): finger3d 1R +35.6 %, 3R -0.3 %;
# stage3d 3R -0.3 %; continuum_robot 1R +32.4 %, 3R -0.6 %. Bands: 3R 5 %; 1R 40 % (one spring per axis
# fitted to the tip's position under a tip force, so its rotation is off; the plane's 1R, fitted
# along the loads, is within 25 %). The stage's 1R model is left out: a 1R leg's tip cannot move
# without turning, so the welded stage cannot slide as the blades let it, and its lowest mode is
# of another kind (measured +954 %); its rest is still checked above, and 3R is the default.
BAND = {"1R": 0.40, "3R": 0.05}
RINGS = [
    pytest.param(f, prb, id=f"{f}-{prb}")
    for f in SPATIAL
    for prb in ("1R", "3R")
    if not (f == "stage3d.toml" and prb == "1R")
]


@pytest.mark.parametrize("name, prb", RINGS)
def test_spatial_examples_ring_in_mujoco_as_modes(name, prb):
    path = EXAMPLES / name
    want = flexure.Mechanism.from_file(path).modes(count=1)["omega"][0]
    step = min(0.002, 0.05 / want)
    xml, report, _ = exported(path, prb, step=step)
    m0 = mujoco.MjModel.from_xml_string(xml)
    m, d = settle(xml)
    m.dof_damping[:] = m0.dof_damping
    got = lowest(m, d)
    assert abs(got / want - 1) < BAND[prb], f"{got:.4g} rad/s against {want:.4g}"
