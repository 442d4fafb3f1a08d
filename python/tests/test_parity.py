"""Python parity with the CLI (issue 20, item 9): Mechanism.solve's error_estimate and
flagged, Mechanism.buckle, compliance and sweep, Flexure.tendon, connect and
stability_limit. Each test names its reference: a closed form, or the CLI's JSON for
the same call (`flexure ... --json`, whose numbers the library computes for both)."""

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import flexure

ROOT = Path(__file__).resolve().parents[2]
TENDON = ROOT / "examples" / "paper_tendon.toml"


def column(ei=2.0, length=1.0, push=-1.0, order=6):
    """One flexure clamped to the ground, a tip body, a tip force `push` along x."""
    return flexure.Mechanism.from_toml(
        f"""
[[joint]]
name = "leg"
kind = "flexure"
parent = "ground"
child = "tip"
length = {length}
ei = {ei}
order = {order}

[[force]]
name = "push"
body = "tip"
at = [0.0, 0.0]
force = [{push}, 0.0]
"""
    )


def close(a, b, rel):
    return abs(a - b) <= rel * abs(b)


# --- Mechanism.solve ---------------------------------------------------------------


def test_solve_has_the_clis_error_estimate_and_flagged():
    # The CLI's error_estimate {joint: estimate} and flagged: the library's serialization of the
    # estimate, its keys in its order, with Python's flagged after them.
    m = flexure.Mechanism.from_file(TENDON)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", flexure.AccuracyWarning)
        r = m.solve()
    e = r["error_estimate"]["hinge"]
    assert list(e) == ["position", "angle", "stress", "curvature", "reference_order", "reference_quadrature",
                       "reference", "flagged"]
    assert r["flagged"] == e["flagged"]


def test_solve_flags_a_joint_that_misses_its_target():
    m = flexure.Mechanism.from_file(TENDON)
    with pytest.warns(flexure.AccuracyWarning, match="flexure joint 'hinge'"):
        r = m.solve(accuracy=(1e-12, 1e-12))
    assert r["flagged"] is True


# --- Mechanism.buckle --------------------------------------------------------------


def test_buckle_is_eulers_free_column():
    # Euler: a clamped-free column buckles at pi^2 EI / (4 L^2) = pi^2/2 N for EI = 2, L = 1,
    # so the factor on a 1 N push is pi^2/2. Order 6 is within 1e-9 of it.
    r = column().buckle()
    assert close(r["load_factor"], math.pi**2 / 2, 1e-9)
    assert r["mode"].shape == (6,) and abs(np.linalg.norm(r["mode"]) - 1.0) < 1e-12
    e = r["error_estimate"]
    assert e["load_factor"] < 1e-6 and e["reference_order"] == {"leg": 12}
    assert r["flagged"] is False and "findings" not in r


def test_buckle_warns_when_its_estimate_misses():
    with pytest.warns(flexure.AccuracyWarning, match="Mechanism.buckle"):
        r = column(order=1).buckle(accuracy=1e-9)
    assert r["flagged"] is True


def test_buckle_refuses_a_bad_accuracy():
    with pytest.raises(ValueError, match="accuracy"):
        column().buckle(accuracy=-1.0)


# --- Mechanism.compliance ----------------------------------------------------------


@pytest.mark.parametrize("order", [3, 6])
def test_compliance_of_a_single_flexure_is_the_closed_form(order):
    # Unloaded cantilever, tip frame: phi/M = L/EI, y/Fy = L^3/3EI, phi/Fy = y/M = L^2/2EI,
    # and no axial compliance (the flexure is inextensible). Exact for order >= 2.
    ei, length = 2.0, 0.5
    c = column(ei=ei, length=length, push=0.0, order=order).compliance("tip", (0.0, 0.0))
    expected = np.array(
        [[length / ei, 0.0, length**2 / (2 * ei)], [0.0, 0.0, 0.0], [length**2 / (2 * ei), 0.0, length**3 / (3 * ei)]]
    )
    assert c.shape == (3, 3)
    assert np.allclose(c, expected, rtol=1e-12, atol=1e-15)


def test_compliance_away_from_the_tip_moves_with_the_lever():
    # A frame at (d, 0) past the tip: its y yields by L^3/3EI + L^2 d/EI + L d^2/EI (the tip's
    # deflection and rotation carried over the lever d).
    ei, length, d = 2.0, 0.5, 0.1
    c = column(ei=ei, length=length, push=0.0).compliance("tip", [d, 0.0])
    expected = length**3 / (3 * ei) + length**2 * d / ei + length * d**2 / ei
    assert close(c[2, 2], expected, 1e-12)


@pytest.mark.parametrize(
    "body, at, match",
    [
        ("nope", (0.0, 0.0), r'body = "nope": names no body .*"ground", "tip"'),
        ("tip", (0.0,), r"invalid at = \(0.0,\)"),
        ("tip", (0.0, float("nan")), r"invalid at = \(0.0, nan\)"),
        ("tip", (0.0, 1e7), r"at most 1e6 m"),
    ],
)
def test_compliance_refuses_bad_input_by_name(body, at, match):
    with pytest.raises(ValueError, match=match):
        column(push=0.0).compliance(body, at)


def test_compliance_past_a_buckling_load_is_refused():
    # Past Euler's load (pi^2/2 N) no stable equilibrium is reached by loading: the solve says
    # where stability is lost, (pi^2/2)/6 of a 6 N push, and no compliance is returned.
    with pytest.raises(flexure.ConvergenceError, match="loses stability") as caught:
        column(push=-6.0).compliance("tip", (0.0, 0.0))
    assert close(caught.value.load_fraction, math.pi**2 / 12, 1e-5)


# --- Mechanism.sweep ---------------------------------------------------------------


def test_sweep_finds_eulers_load_and_leaves_out_the_values_past_it():
    # As `flexure solve --sweep force.push.fx=0:-8:5 --json`: rows at 0, -2 and -4, then
    # stability_limit at -pi^2/2 (found to a relative 1e-6), fraction (pi^2/2)/8.
    with pytest.warns(flexure.StabilityWarning, match="stability is lost at force.push.fx"):
        r = column().sweep("force.push.fx", [0.0, -2.0, -4.0, -6.0, -8.0])
    assert list(r["values"]) == [0.0, -2.0, -4.0]
    assert r["coordinates"]["leg"].shape == (3, 6) and r["energy"].shape == (3,)
    assert list(r["bodies"]) == ["tip"] and np.allclose(r["bodies"]["tip"]["x"], 1.0)
    limit = r["stability_limit"]
    assert close(limit["value"], -math.pi**2 / 2, 1e-5)
    assert close(limit["fraction"], math.pi**2 / 16, 1e-5)
    assert len(r["flagged"]) == 0 and "stopped" not in r


def test_a_sweep_reports_each_rows_compliance_as_the_closed_form():
    # As `solve --sweep ... --compliance tip --at 0,0`: the unloaded row is the closed form
    # L/EI, L^3/3EI; a loaded row is Mechanism.compliance under that load.
    ei, length = 2.0, 0.5
    m = column(ei=ei, length=length, push=0.0)
    r = m.sweep("force.push.fx", [0.0, -1.0, -2.0], compliance="tip", at=(0.0, 0.0))
    c = r["compliance"]
    assert c.shape == (3, 3, 3)
    assert close(c[0, 0, 0], length / ei, 1e-12) and close(c[0, 2, 2], length**3 / (3 * ei), 1e-12)
    # Compression softens the column sideways: each row yields more than the last.
    assert c[0, 2, 2] < c[1, 2, 2] < c[2, 2, 2]
    assert np.allclose(c[2], column(ei=ei, length=length, push=-2.0).compliance("tip", (0.0, 0.0)), rtol=1e-9)
    # Without `at`, the body frame's origin, as Mechanism.compliance takes it.
    origin = m.sweep("force.push.fx", [0.0], compliance="tip")["compliance"]
    assert np.array_equal(origin[0], c[0])
    with pytest.raises(ValueError, match="at is given without compliance"):
        m.sweep("force.push.fx", [0.0], at=(0.0, 0.0))


def test_a_sweep_that_stops_raises_carrying_its_rows():
    # As `flexure solve examples/paper_tendon.toml --sweep tendon.flexor.tension=0:70:8 --json`:
    # rows at 0 to 50 N, flagged at 40 and 50 N, and the continuation stalls at 60 N, where the
    # tendon's ends are about to meet (the file's comments); the CLI prints the rows, exits 2.
    m = flexure.Mechanism.from_file(TENDON)
    with pytest.raises(flexure.ConvergenceError, match="stopped at tendon.flexor.tension = 60") as caught:
        with pytest.warns(flexure.AccuracyWarning, match="at 2 of the swept values"):
            m.sweep("tendon.flexor.tension", np.linspace(0.0, 70.0, 8))
    e = caught.value
    assert str(TENDON) in str(e) and e.residual > 0
    r = e.result
    assert list(r["values"]) == [0.0, 10.0, 20.0, 30.0, 40.0, 50.0]
    assert list(r["flagged"]) == [40.0, 50.0]
    assert r["stopped"]["value"] == 60.0 and "stalled" in r["stopped"]["error"]
    # The CLI's row at 10 N: link.phi and hinge.stress.
    assert close(r["bodies"]["link"]["phi"][1], 0.5690973499552956, 1e-9)
    assert close(r["stress"]["hinge"][1], 883513033.3406314, 1e-9)


@pytest.mark.parametrize(
    "parameter, values, match",
    [
        ("force.nope.fx", [1.0], r'invalid parameter = "force.nope.fx": names no force'),
        ("push", [1.0], r'invalid parameter = "push": must be tendon.NAME.tension'),
        ("force.push.fx", [], r"a sweep takes from 1 to 10000 values"),
        ("force.push.fx", [0.0, float("nan")], r"invalid values: one is NaN"),
        ("force.push.fx", "0:1:3", r"invalid values = '0:1:3'"),
    ],
)
def test_sweep_refuses_bad_input_by_name(parameter, values, match):
    with pytest.raises(ValueError, match=match):
        column().sweep(parameter, values)


# --- Flexure.tendon ----------------------------------------------------------------


def paper_joint(order=5):
    # The paper's tendon joint (Sec. III-D): steel, 15 mm x 10 mm x 0.2 mm.
    return flexure.Flexure(length=0.015, modulus=200e9, width=0.01, thickness=0.0002, poisson=0.29, order=order)


def test_tendon_is_the_clis_answer():
    # `flexure tendon --length 0.015 --modulus 200e9 --width 0.01 --thickness 0.0002
    #  --poisson 0.29 --order 5 --force 10 --root-offset 0.005 --tip-offset 0.005 --json`
    r = paper_joint().tendon(10.0, 0.005, 0.005)
    assert close(r["alpha"][0], 0.5690976382725186, 1e-9)
    assert close(r["alpha"][2], -0.07562637937750497, 1e-9)
    assert np.allclose(r["pose"], [0.5690976382725186, 0.014192868831576121, 0.004151212024033775], rtol=1e-9)
    assert close(r["tendon_length"], 0.011980253239227627, 1e-9)
    assert r["stable"] is True and r["flagged"] is False
    assert close(r["stress"]["max"], 884073397.6591686, 1e-9) and r["stress"]["at"] == 0.0075
    e = r["error_estimate"]
    assert e["reference_order"] == 10 and e["reference_quadrature"] == 17
    assert close(e["curvature"], 0.00023823372326603476, 1e-6)


def test_tendon_limit_and_its_warning_are_the_clis():
    # `flexure tendon --force 1 --root-offset 0.1 --tip-offset -0.05 --limit --json`: a tendon
    # that crosses the flexure stays stable up to 22.893 N, where its attachments meet and the
    # path ends; the order-3 peak curvature misses 1 %.
    with (
        pytest.warns(flexure.AccuracyWarning, match='tendon.*peak curvature.*order="auto"'),
        pytest.warns(flexure.StabilityWarning, match="as far as it could be followed"),
    ):
        r = flexure.Flexure().tendon(1.0, 0.1, -0.05, limit=True)
    assert r["stability_limit"]["status"] == "stable_up_to"
    assert close(r["stability_limit"]["factor"], 22.89305162214922, 1e-9)
    assert r["flagged"] is True and "curvature_max" in r
    assert close(r["tendon_length"], 1.008594647054488, 1e-9)


def test_tendon_auto_raises_the_order_until_the_target_is_met():
    with warnings.catch_warnings():
        warnings.simplefilter("error", flexure.AccuracyWarning)
        r = flexure.Flexure().tendon(1.0, 0.1, -0.05, order="auto")
    assert r["order"] > 3 and r["flagged"] is False


@pytest.mark.parametrize(
    "call, error, match",
    [
        ("f.tendon(-1.0, 0.005, 0.005)", ValueError, r"invalid tension = -1"),
        ("f.tendon(1.0, float('nan'), 0.005)", ValueError, r"root_offset = NaN"),
        ("f.tendon(1.0, 0.005, float('inf'))", ValueError, r"tip_offset = inf"),
        ("f.tendon(1.0, 0.005, 0.005, order=5)", ValueError, r'order must be None or "auto"'),
        ("f.tendon(1.0, 0.005, 0.005, limit=True, max_factor=0.0)", ValueError, r"invalid max_factor = 0"),
    ],
)
def test_tendon_refuses_bad_input_by_name(call, error, match):
    f = flexure.Flexure()
    with pytest.raises(error, match=match):
        eval(call)


# --- Flexure.connect ---------------------------------------------------------------


def test_connect_is_the_clis_answer():
    # `flexure connect --pose 1.0,0.8,0.4 --order 5 --json`
    r = flexure.Flexure(order=5).connect([1.0, 0.8, 0.4])
    assert np.allclose(
        r["alpha"], [1.0, 0.2117905528827514, -2.7981137001172427, -0.08391166028468036, 0.44135543574979447], rtol=1e-9
    )
    assert close(r["energy"], 1.3017447647779428, 1e-9)
    load = r["load"]
    assert close(load["moment"], -1.253335133593236, 1e-9)
    assert close(load["fx"], -17.156674970978703, 1e-9) and close(load["fy"], -8.920693418916855, 1e-9)
    assert r["flagged"] is False and r["error_estimate"]["reference_order"] == 10
    # The tip reaches the pose: Eq. 16's constraint.
    assert np.allclose(flexure.Flexure(order=5).pose(r["alpha"]), [1.0, 0.8, 0.4], atol=1e-10)


def test_connect_refuses_a_pose_out_of_reach():
    with pytest.raises(ValueError, match="pose"):
        flexure.Flexure().connect((0.0, 2.0, 0.0))
    with pytest.raises(ValueError, match=r"invalid pose = \(0.0, 1.0\)"):
        flexure.Flexure().connect((0.0, 1.0))


# --- Flexure.stability_limit -------------------------------------------------------


def test_stability_limit_of_a_free_column_is_eulers():
    # Euler: pi^2 EI / (4 L^2) for a clamped-free column; order 6 is within 1e-10 of it.
    r = flexure.Flexure(order=6).stability_limit(fx=-1.0)
    assert set(r) == {"factor", "status"} and r["status"] == "lost"
    assert close(r["factor"], math.pi**2 / 4, 1e-9)
    # Order 3, as `flexure deflect --fx -1 --limit --json`: 2.4677381624149675.
    assert close(flexure.Flexure().stability_limit(fx=-1.0)["factor"], 2.4677381624149675, 1e-9)


def test_a_moment_stays_stable_up_to_max_factor():
    # A pure tip moment bends the flexure into arcs, each stable: the bound is returned.
    # stalled is None: max_factor was reached (the CLI's shape).
    limit = flexure.Flexure().stability_limit(moment=1.0, max_factor=10.0)
    assert limit == {"factor": 10.0, "status": "stable_up_to", "stalled": None}


@pytest.mark.parametrize("bad", [0.0, -1.0, float("inf"), float("nan")])
def test_stability_limit_refuses_a_bad_max_factor(bad):
    with pytest.raises(ValueError, match="invalid max_factor"):
        flexure.Flexure().stability_limit(fx=-1.0, max_factor=bad)


# --- the package's API -------------------------------------------------------------


def test_the_package_exports_only_its_api():
    # Every public name of the package is in __all__, and `import *` gives exactly those.
    public = {name for name in vars(flexure) if not name.startswith("_")}
    assert public == set(flexure.__all__)
    star = {}
    exec("from flexure import *", star)
    assert set(star) - {"__builtins__"} == set(flexure.__all__)
    for name in flexure.__all__:
        assert getattr(flexure, name) is not None
