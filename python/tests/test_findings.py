"""Findings (issue 20, items 3 and 4): a closure open at rest warns
PreloadWarning with its gap and preload (a note, without a warning, with
`preload = true`); parts that cross warn IntersectionWarning. Both are
listed under `findings`."""

import math
import warnings
from pathlib import Path

import pytest

import flexure

ROOT = Path(__file__).resolve().parents[2]
PARALLELOGRAM = (ROOT / "examples" / "parallelogram.toml").read_text()
HALF_TURN = PARALLELOGRAM.replace("b_origin = [0.0, 0.0, 0.0]", "b_origin = [0.0, 0.0, 3.141592653589793]")


@pytest.mark.filterwarnings("ignore::flexure.AccuracyWarning")
def test_a_half_turn_weld_warns_with_its_gap_of_pi():
    # The weld's frames meet in position at rest and differ by half a turn.
    assert HALF_TURN != PARALLELOGRAM
    with pytest.warns(flexure.PreloadWarning, match='weld of "stage" and "b_tip" is open at rest') as caught:
        result = flexure.Mechanism.from_toml(HALF_TURN).solve()
    (preload,) = [w for w in caught if w.category is flexure.PreloadWarning]
    assert "3.141593 rad" in str(preload.message)
    (found,) = [f for f in result["findings"] if f["kind"] == "open_closure"]
    assert found["severity"] == "warning" and found["preload"] is False
    assert abs(abs(found["gap_rad"]) - math.pi) < 1e-12 and found["gap_m"] < 1e-15
    assert found["preload_force_n"] > 0.1 and found["preload_moment_n_m"] > 1e-3


def test_preload_true_is_listed_as_a_note_without_a_warning():
    text = HALF_TURN.replace("b_origin = [0.0, 0.0, 3.14159265358979", "preload = true\nb_origin = [0.0, 0.0, 3.14159265358979")
    assert "preload = true" in text
    with warnings.catch_warnings():
        warnings.simplefilter("error", flexure.PreloadWarning)
        warnings.simplefilter("ignore", flexure.AccuracyWarning)
        result = flexure.Mechanism.from_toml(text).solve()
    (found,) = [f for f in result["findings"] if f["kind"] == "open_closure"]
    assert found["severity"] == "note" and found["preload"] is True
    assert found["message"].endswith("(preload = true)")


def test_a_closure_that_meets_has_no_findings():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = flexure.Mechanism.from_toml(PARALLELOGRAM).solve()
    assert "findings" not in result and result["stable"] is True


# A pendulum let go level swings down through a flexure post beside its pivot
# (the post at x = 0.05 m, y from -0.3 to -0.02 m; the bob's link 0.2 m long),
# the file the library's and the CLI's crossing tests read too.
PENDULUM = (
    Path(__file__).resolve().parents[2] / "crates" / "flexure" / "tests" / "data" / "pendulum_through_post.toml"
).read_text(encoding="utf-8")


def test_a_simulation_that_crosses_warns_and_lists_the_samples():
    with pytest.warns(flexure.IntersectionWarning, match='flexure "post" crosses link "bob"'):
        run = flexure.Mechanism.from_toml(PENDULUM).simulate(0.3, every=0.01)
    times = [f["time"] for f in run["findings"] if f["parts"] == ("flexure \"post\"", "link \"bob\"")]
    assert times and min(times) > 0.0
    # At each listed sample the bob's angle lies where the geometry lets it meet the post.
    for t in times:
        k = int(round(t / 0.01))
        theta = float(run["coordinates"]["pivot"][k][0])
        assert math.radians(-75.6) < theta < math.radians(-21.7), (t, theta)


# The same pendulum and post in space, the post a blade 10 mm thick: the
# window where the bob's link meets the post's solid widens to -77.0 deg ..
# -19.98 deg (the file's comment derives it).
PENDULUM3D = (
    Path(__file__).resolve().parents[2] / "crates" / "flexure" / "tests" / "data" / "pendulum_through_post3d.toml"
).read_text(encoding="utf-8")


def test_a_spatial_simulation_that_crosses_warns_and_lists_the_samples():
    with pytest.warns(flexure.IntersectionWarning, match='flexure "post" crosses link "bob"'):
        run = flexure.Mechanism.from_toml(PENDULUM3D).simulate(0.3, every=0.01, start="rest")
    found = [f for f in run["findings"] if f["parts"] == ('flexure "post"', 'link "bob"')]
    assert found and min(f["time"] for f in found) > 0.0
    for f in found:
        assert len(f["at"]) == 3 and f["s_b"] is None and 0.0 < f["s_a"] <= 0.28 and f["points"] == 1
        k = int(round(f["time"] / 0.01))
        theta = float(run["coordinates"]["pivot"][k][0])
        assert math.radians(-77.01) < theta < math.radians(-19.97), (f["time"], theta)


def test_spatial_rods_pushed_together_cross_in_a_sweep():
    # Two round rods 2 mm thick, axes 4 mm apart: a tip push of F moves rod a by
    # F L^3/(3 E I), 2 mm (touching) at 7.54 N; crossings at 10 and 15 N only.
    rod = lambda name, z: (
        f'[[joint]]\nname = "{name}"\nkind = "flexure"\nparent = "ground"\nchild = "{name}_tip"\n'
        f"origin = [0.0, 0.0, {z}]\nlength = 0.05\nmodulus = 2e11\npoisson = 0.3\ndiameter = 2e-3\n"
    )
    text = "dimension = 3\n" + rod("a", 0.0) + rod("b", 4e-3)
    text += '[[force]]\nname = "push"\nbody = "a_tip"\nforce = [0.0, 0.0, 10.0]\n'
    m = flexure.Mechanism.from_toml(text)
    with pytest.warns(flexure.IntersectionWarning, match='flexure "a" crosses flexure "b"'):
        out = m.sweep("force.push.fz", [0.0, 5.0, 10.0, 15.0])
    assert [f["value"] for f in out["findings"]] == [10.0, 15.0]
    with pytest.warns(flexure.IntersectionWarning):
        solved = m.solve()
    assert solved["findings"][0]["parts"] == ('flexure "a"', 'flexure "b"')
