"""`Mechanism.simulate`: a mechanism file's motion as NumPy arrays, against
closed forms (a linear oscillator; a pendulum's period by the complete
elliptic integral, as a series), with bad arguments refused by name."""

import math
from pathlib import Path

import numpy as np
import pytest

import flexure

ROOT = Path(__file__).resolve().parents[2]

# A sprung arm: k = 2 N*m/rad, I = 0.5 kg*m^2 about the pin (omega = 2 rad/s),
# a moment of 0.2 N*m (equilibrium 0.1 rad).
ARM = """
[[joint]]
name = "pin"
kind = "revolute"
parent = "ground"
child = "arm"
stiffness = 2.0

[[body]]
name = "arm"
inertia = 0.5

[[force]]
name = "turn"
body = "arm"
at = [0.0, 0.0]
moment = 0.2
"""


def test_a_sprung_arm_moves_in_closed_form():
    """Let go from 0.3 rad: phi = 0.1 + 0.2 cos 2t; tolerance 1e-7 rad, the integration's at 1e-10."""
    m = flexure.Mechanism.from_toml(ARM + "[initial]\npin = 0.3\n")
    run = m.simulate(2.2, every=0.4, tolerance=1e-10)
    t = run["time"]
    assert isinstance(t, np.ndarray) and t.shape == (7,)
    np.testing.assert_allclose(t, [0.0, 0.4, 0.8, 1.2, 1.6, 2.0, 2.2], atol=1e-12)
    phi = run["bodies"]["arm"]["phi"]
    np.testing.assert_allclose(phi, 0.1 + 0.2 * np.cos(2 * t), atol=1e-7)
    q = run["coordinates"]["pin"]
    assert q.shape == (7, 1)
    np.testing.assert_array_equal(q[:, 0], phi)
    np.testing.assert_allclose(run["velocities"]["pin"][:, 0], -0.4 * np.sin(2 * t), atol=1e-6)
    assert run["energy"].shape == (7,)
    assert run["steps"] > 0 and run["rejected"] >= 0 and run["violation"] == 0.0


def test_start_defaults_to_equilibrium_and_every_to_a_hundredth():
    m = flexure.Mechanism.from_toml(ARM)
    run = m.simulate(1.0)
    assert run["time"].shape == (101,)
    np.testing.assert_allclose(run["bodies"]["arm"]["phi"], 0.1, atol=1e-8)
    rest = m.simulate(1.0, every=0.5, tolerance=1e-10, start="rest")
    np.testing.assert_allclose(rest["bodies"]["arm"]["phi"], 0.1 - 0.1 * np.cos(2 * rest["time"]), atol=1e-8)


def test_pendulum_period_matches_the_elliptic_integral():
    """T = 4 sqrt(l/g) K(k), k = sin(theta0/2); K by its series (pi/2) sum ((2n)!/(2^2n n!^2))^2 k^2n."""
    l, g, theta0 = 0.25, 9.81, 1.0
    k2 = math.sin(theta0 / 2) ** 2
    terms = [(math.comb(2 * n, n) / 4**n) ** 2 * k2**n for n in range(60)]
    period = 4 * math.sqrt(l / g) * math.pi / 2 * sum(terms)
    text = (
        'gravity = [0.0, -9.81]\n[[joint]]\nname = "pivot"\nkind = "revolute"\nparent = "ground"\n'
        f'child = "bob"\n[[body]]\nname = "bob"\nmass = 0.1\ncom = [{l}, 0.0]\n[initial]\npivot = {-math.pi / 2 + theta0}\n'
    )
    run = flexure.Mechanism.from_toml(text).simulate(period, every=period / 2, tolerance=1e-10)
    phi = run["bodies"]["bob"]["phi"] + math.pi / 2
    np.testing.assert_allclose(phi, [theta0, -theta0, theta0], atol=1e-7)


def test_the_finger_example_runs():
    m = flexure.Mechanism.from_file(ROOT / "examples" / "finger_dynamics.toml")
    run = m.simulate(0.1, every=0.05, tolerance=1e-6)
    assert run["coordinates"]["mcp"].shape == (3, 3)
    assert np.all(np.isfinite(run["energy"]))


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"duration": 0.0}, "duration"),
        ({"duration": -1.0}, "duration"),
        ({"duration": float("nan")}, "duration"),
        ({"duration": 1.0, "every": 0.0}, "every"),
        ({"duration": 1.0, "tolerance": -1e-6}, "tolerance"),
        ({"duration": 1.0, "start": "loaded"}, "start"),
    ],
)
def test_bad_arguments_raise_value_error_naming_them(kwargs, name, tmp_path):
    with pytest.raises(ValueError, match=f"^(invalid )?{name}"):
        flexure.Mechanism.from_toml(ARM).simulate(**kwargs)
    # Read from a file, the error is still about the argument, not the file.
    path = tmp_path / "arm.toml"
    path.write_text(ARM)
    with pytest.raises(ValueError, match=f"^(invalid )?{name}"):
        flexure.Mechanism.from_file(path).simulate(**kwargs)


def test_file_errors_name_the_file(tmp_path):
    path = tmp_path / "massless.toml"
    path.write_text('[[joint]]\nname = "pin"\nkind = "revolute"\nparent = "ground"\nchild = "arm"\nstiffness = 1.0\n')
    with pytest.raises(ValueError, match=r"massless\.toml: invalid mass everywhere zero: .*nothing moves"):
        flexure.Mechanism.from_file(path).simulate(1.0)
    bad = tmp_path / "bad.toml"
    bad.write_text(ARM + '[[schedule]]\nload = "force.turn.moment"\npoints = [[0.5, 0.0], [0.1, 1.0]]\n')
    with pytest.raises(ValueError, match=r"bad\.toml: line 20, column 23: .*points\[1\]"):
        flexure.Mechanism.from_file(bad)


def test_the_error_estimate_is_near_the_true_error_and_warns_when_it_misses():
    """Reference: the closed form phi = 0.1 + 0.2 cos 2t. At tolerance 1e-3 over 20 s the
    estimate (a run at a tenth of the tolerance) is within a factor 2 of the true largest
    angle error; 1 deg is met; a target of 1e-6 rad is missed with AccuracyWarning."""
    m = flexure.Mechanism.from_toml(ARM + "[initial]\npin = 0.3\n")
    run = m.simulate(20.0, every=2.0, tolerance=1e-3)
    t, phi = run["time"], run["bodies"]["arm"]["phi"]
    truth = np.max(np.abs(phi - 0.1 - 0.2 * np.cos(2 * t)))
    e = run["error_estimate"]
    assert truth > 1e-5 and 0.5 * truth < e["angle"] < 2.0 * truth, (e, truth)
    assert (e["complete"], e["samples"], e["reference_tolerance"]) == (True, 11, pytest.approx(1e-4))
    assert run["flagged"] is False
    with pytest.warns(flexure.AccuracyWarning, match="misses accuracy"):
        tight = m.simulate(20.0, every=2.0, tolerance=1e-3, accuracy=(0.01, 1e-6))
    assert tight["flagged"] is True
    with pytest.raises(ValueError, match="accuracy"):
        m.simulate(1.0, accuracy=(0.01,))
