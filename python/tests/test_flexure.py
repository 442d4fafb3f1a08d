"""The Python package against the same references as the Rust tests.

Each test names its source and its tolerance's reason.
"""

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import flexure

ROOT = Path(__file__).resolve().parents[2]


def test_table_i_buckling_loads():
    # Table I, model column, N = 3 (4 decimals printed: 5e-5).
    f = flexure.Flexure()
    for tip, load in [("free", 2.4677), ("guided", 10.0), ("pinned", 20.9187), ("clamped", 42.0)]:
        assert abs(f.buckling_load(tip) - load) < 5e-5, tip
    # Loads scale as EI/L^2.
    g = flexure.Flexure(length=2.0, ei=3.0)
    assert abs(g.buckling_load("free") - 2.4677 * 3.0 / 4.0) < 5e-5


def test_eq_37_compliance():
    # Eq. 37: the ODE's compliance for constant rest curvature pi (printed to 4 decimals).
    printed = np.array([[1.0000, -0.3183, -0.2026], [-0.3183, 0.1520, 0.0645], [-0.2026, 0.0645, 0.0507]])
    exact = flexure.exact.compliance(kappa=[math.pi, 0.0, 0.0])
    assert np.max(np.abs(exact - printed)) < 5e-5
    # Fig. 13: the model within 7.33e-4 (printed to 3 digits: 5e-7).
    model = flexure.Flexure(kappa=[math.pi, 0, 0]).rest_compliance()
    assert abs(np.max(np.abs(model - exact)) - 7.33e-4) < 5e-7
    assert model.shape == (3, 3) and model.dtype == np.float64


def test_bisshopp_drucker():
    # PL^2/EI = 1 across the tip: x = 0.94357, y = 0.30172, phi = 0.46135 (5 digits: 5e-6).
    exact = flexure.exact.deflect(fy=1.0)
    assert np.allclose(exact, [0.46135, 0.94357, 0.30172], atol=5e-6)
    f = flexure.Flexure()
    model = f.pose(f.deflect(fy=1.0))
    # The model: within 1 % of L and 1 degree (Sec. III-C).
    assert math.hypot(*(model[1:] - exact[1:])) < 0.01
    assert abs(math.degrees(model[0] - exact[0])) < 1.0


def test_unstable_equilibrium_warns():
    # A straight column past Euler's pi^2 EI/(4 L^2) = 2.467 (model, N = 3: 2.4677):
    # the straight shape is an equilibrium, but unstable, and both solvers say so.
    f = flexure.Flexure()
    with pytest.warns(flexure.StabilityWarning, match="unstable"):
        alpha = f.deflect(fx=-3.0)
    assert np.allclose(alpha, 0.0)
    with pytest.warns(flexure.StabilityWarning, match="Jacobi"):
        flexure.exact.deflect(fx=-3.0)
    # Below it, and with the side force that makes it bend stably, no warning.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        f.deflect(fx=-2.4)
        flexure.exact.deflect(fx=-2.4)
        # (Its peak curvature is 5 % off at order 3, flagged by the default 1 % target: loosened here.)
        f.deflect(fx=-4.0, fy=0.05, accuracy=(0.01, 0.0175, 0.1))
        flexure.exact.deflect(fx=-4.0, fy=0.05)


def test_circular_arc():
    # A pure moment bends an arc of angle ML/EI: closed form (5-point rule: 1e-9).
    f = flexure.Flexure(length=2.0, ei=4.0)
    alpha = f.deflect(moment=2.0)
    a = 2.0 * 2.0 / 4.0
    assert np.allclose(f.pose(alpha), [a, 2.0 * math.sin(a) / a, 2.0 * (1 - math.cos(a)) / a], atol=1e-9)
    assert abs(f.energy(alpha) - 4.0 * a * a / (2 * 2.0)) < 1e-12
    g = f.transform(alpha)
    assert g.shape == (4, 4) and abs(g[0, 3] - f.pose(alpha)[1]) < 1e-15


def test_derivatives_against_central_differences():
    # Central differences, h = 1e-6: truncation 1e-12, rounding 1e-10.
    rng = np.random.default_rng(7)
    f = flexure.Flexure(order=4)
    for _ in range(10):
        alpha = rng.uniform(-1.5, 1.5, 4)
        jac = f.jacobian(alpha)
        hx, hy = f.hessians(alpha)
        h = 1e-6
        for i in range(4):
            step = np.zeros(4)
            step[i] = h
            fd = (f.pose(alpha + step) - f.pose(alpha - step)) / (2 * h)
            assert np.allclose(jac[:, i], fd, atol=1e-8)
            jd = (f.jacobian(alpha + step) - f.jacobian(alpha - step)) / (2 * h)
            assert np.allclose(hx[:, i], jd[1], atol=1e-8) and np.allclose(hy[:, i], jd[2], atol=1e-8)
        assert np.array_equal(hx, hx.T) and np.array_equal(hy, hy.T)


def test_batch_equals_rows():
    rng = np.random.default_rng(3)
    f = flexure.Flexure()
    alphas = rng.uniform(-2, 2, (10_000, 3))
    batch = f.pose(alphas)
    assert batch.shape == (10_000, 3) and batch.dtype == np.float64
    for i in range(0, 10_000, 997):
        assert np.array_equal(batch[i], f.pose(alphas[i]))


def test_array_like_inputs():
    f = flexure.Flexure()
    assert np.array_equal(f.pose([1, 0, 0]), f.pose(np.array([1.0, 0.0, 0.0])))
    assert np.array_equal(f.pose((1, 0, 0)), f.pose(np.array([1, 0, 0], dtype=np.int64)))
    assert f.pose([[0, 0, 0], [1, 0, 0]]).shape == (2, 3)


def arc(length, angle):
    """Tip pose of a circular arc of `length` turning by `angle`: alpha = (angle, 0, 0) is one."""
    return np.array([angle, length * math.sin(angle) / angle, length * (1 - math.cos(angle)) / angle])


def test_every_form_of_one_configuration_is_read_alike():
    # Closed form: alpha = (a, 0, 0) bends the flexure into a circular arc of tip angle a, whose
    # energy is EI a^2 / (2 L). Tolerance 1e-9: the Gauss rule's error on the arc (as in
    # test_circular_arc). Every form of the input (the fast paths for a float64 vector and a
    # list or tuple of numbers, and NumPy's conversion for the rest) must give the same bits.
    f = flexure.Flexure(length=2.0, ei=3.0)
    wide = np.zeros(6)
    wide[::2] = [1.0, 0.0, 0.0]
    frozen = np.array([1.0, 0.0, 0.0])
    frozen.flags.writeable = False
    forms = [
        np.array([1.0, 0.0, 0.0]),
        wide[::2],  # strided view
        frozen,
        np.array([1.0, 0.0, 0.0], dtype=np.float32),
        np.array([1, 0, 0], dtype=np.int64),
        [1.0, 0.0, 0.0],
        [1, 0, 0],
        (1.0, 0, 0.0),
        [np.float64(1.0), np.int32(0), 0.0],
        np.array([[1.0, 0.0, 0.0]])[0],
    ]
    reference = f.pose(forms[0])
    assert type(reference) is np.ndarray and reference.shape == (3,) and reference.dtype == np.float64
    assert np.allclose(reference, arc(2.0, 1.0), rtol=0, atol=1e-9)
    assert abs(f.energy(forms[0]) - 3.0 / 4.0) < 1e-12
    for alpha in forms:
        assert np.array_equal(f.pose(alpha), reference), repr(alpha)
        assert f.energy(alpha) == f.energy(forms[0]), repr(alpha)
        assert np.array_equal(f.jacobian(alpha), f.jacobian(forms[0])), repr(alpha)
    # Past order 8 a configuration is held on the heap, not inline: the same reading.
    g = flexure.Flexure(length=2.0, ei=3.0, order=12)
    high = [1.0] + [0.0] * 11
    assert np.allclose(g.pose(high), arc(2.0, 1.0), rtol=0, atol=1e-9)
    for alpha in [np.array(high), tuple(high), np.repeat(high, 2)[::2]]:
        assert np.array_equal(g.pose(alpha), g.pose(high))
    # Each call returns a fresh array: changing one answer changes no other.
    again = f.pose(forms[0])
    again[0] = 99.0
    assert f.pose(forms[0])[0] == 1.0 and reference[0] == 1.0


def test_batch_reads_any_layout():
    # Rows of circular arcs (closed form above, tolerance 1e-9) in every memory layout: read in
    # place when C-contiguous float64, copied once otherwise; all give the same bits.
    f = flexure.Flexure()
    angles = np.arange(1, 51) / 32.0  # exact in float32 too
    rows = np.zeros((50, 3))
    rows[:, 0] = angles
    expected = np.array([arc(1.0, a) for a in angles])
    wide = np.zeros((100, 6))
    wide[::2, ::2] = rows
    forms = [rows, np.asfortranarray(rows), rows.T.copy().T, wide[::2, ::2], rows.astype(np.float32), rows.tolist()]
    reference = f.pose(rows)
    assert reference.shape == (50, 3) and reference.dtype == np.float64 and reference.flags.c_contiguous
    assert np.allclose(reference, expected, rtol=0, atol=1e-9)
    for alpha in forms:
        assert np.array_equal(f.pose(alpha), reference)
    # The input is only read, and the answer is a new array.
    before = rows.copy()
    out = f.pose(rows)
    out[:] = 0.0
    assert np.array_equal(rows, before) and np.array_equal(f.pose(rows), reference)
    # No rows: an empty (0, 3) answer.
    assert f.pose(np.zeros((0, 3))).shape == (0, 3)


def test_material_options():
    # Eq. 25: the paper's steel flexure, EI = 1.4558e-3 N*m^2.
    f = flexure.Flexure(length=0.015, modulus=200e9, width=0.01, thickness=0.0002, poisson=0.29)
    assert abs(f.ei - 1.4558e-3) < 1e-7


@pytest.mark.parametrize(
    "make, name",
    [
        (lambda: flexure.Flexure(length=-1.0), "length"),
        (lambda: flexure.Flexure(ei=0.0), "ei"),
        (lambda: flexure.Flexure(length=float("nan")), "length"),
        (lambda: flexure.Flexure(order=0), "order"),
        (lambda: flexure.Flexure(quadrature=0), "quadrature"),
        (lambda: flexure.Flexure(kappa=[1.0, 2.0]), "kappa"),
        (lambda: flexure.Flexure().pose([1.0, 2.0]), "alpha"),
        (lambda: flexure.Flexure().pose([1.0, float("nan"), 0.0]), "alpha"),
        (lambda: flexure.Flexure().jacobian([[0, 0, 0]]), "alpha"),
        (lambda: flexure.Flexure().deflect(fx=float("inf")), "fx"),
        (lambda: flexure.Flexure().buckling_load("sideways"), "tip"),
        (lambda: flexure.Flexure(modulus=2e11, width=0.01, thickness=-1.0), "thickness"),
        (lambda: flexure.Mechanism.from_toml("[[joint]]\nname = 'a'\nkind = 'flexure'\nparent = 'palm'\nchild = 'b'\nlength = 0.01\nei = 1.0\n"), "line 4"),
    ],
)
def test_bad_input_raises_value_error(make, name):
    with pytest.raises(ValueError, match=name):
        make()


def test_non_convergence_raises_with_residual():
    # A moment that coils the elastica through a million radians: continuation stalls.
    with pytest.raises(flexure.ConvergenceError) as info:
        flexure.exact.deflect(moment=1e6)
    assert math.isfinite(info.value.residual) and info.value.residual > 0


def test_mechanism_from_path_and_text():
    path = ROOT / "examples" / "mixed_chain.toml"
    for source in (path, str(path), path.read_text()):
        result = flexure.Mechanism.from_toml(source).solve()
        # Its flexures are given by ei (no thickness): curvature_max, as `flexure solve --json`.
        assert set(result) == {"dimension", "bodies", "coordinates", "energy", "stable", "error_estimate", "flagged",
                               "curvature_max", "load", "multipliers", "residual", "load_steps", "iterations"}
        # Closed form: the shoulder spring turns M/k = 0.01/2.
        assert abs(result["coordinates"]["shoulder"][0] - 0.005) < 1e-10
        assert result["stable"] is True
    tendon = flexure.Mechanism.from_toml(ROOT / "examples" / "paper_tendon.toml").solve()
    # Fig. 10: about 28 N turns the paper's steel flexure to 90 degrees.
    assert abs(math.degrees(tendon["bodies"]["link"]["phi"]) - 90) < 2


def test_docstring_example():
    # The package docstring's example runs and prints what it says.
    import doctest

    result = doctest.testmod(flexure)
    assert result.attempted > 0 and result.failed == 0


def test_old_names_warn_and_mean_the_same():
    # One vocabulary (CHANGELOG.md): kappa, tension and limit_fraction; the old names still work, warning.
    with pytest.warns(DeprecationWarning, match="rest is deprecated: use kappa") as caught:
        f = flexure.Flexure(rest=[0.5, 0.0, 0.0])
    assert caught[0].filename == __file__
    assert list(f.kappa) == [0.5, 0.0, 0.0]
    with pytest.warns(DeprecationWarning, match="Flexure.rest is deprecated: use Flexure.kappa"):
        assert list(f.rest) == [0.5, 0.0, 0.0]
    with pytest.raises(ValueError, match="kappa and rest given together"):
        flexure.Flexure(kappa=[0.5, 0.0, 0.0], rest=[0.5, 0.0, 0.0])
    with pytest.warns(DeprecationWarning, match="rest is deprecated: use kappa") as caught:
        old = flexure.exact.compliance(rest=[0.5, 0.0, 0.0])
    assert caught[0].filename == __file__
    assert np.array_equal(old, flexure.exact.compliance(kappa=[0.5, 0.0, 0.0]))
    with pytest.raises(ValueError, match="kappa and rest given together"):
        flexure.exact.compliance(kappa=[0.5], rest=[0.5])
    g = flexure.Flexure()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", flexure.AccuracyWarning)
        with pytest.warns(DeprecationWarning, match="force is deprecated: use tension"):
            old = g.tendon(force=1.0, root_offset=0.005, tip_offset=0.005)
        assert np.array_equal(old["alpha"], g.tendon(tension=1.0, root_offset=0.005, tip_offset=0.005)["alpha"])
    with pytest.raises(ValueError, match="tension and force given together"):
        g.tendon(1.0, 0.005, 0.005, force=1.0)
    with pytest.raises(TypeError, match="missing required argument 'tension'"):
        g.tendon(root_offset=0.005, tip_offset=0.005)
    with pytest.raises(ValueError, match="invalid tension = -1"):
        g.tendon(-1.0, 0.005, 0.005)
    e = flexure.exact.elastica(fy=1.0)
    with pytest.warns(DeprecationWarning, match="Elastica.limit is deprecated: use Elastica.limit_fraction"):
        assert e.limit == e.limit_fraction
