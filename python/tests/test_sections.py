"""Sections along a flexure from Python: tapers, tables and notches against
closed forms, the stress outputs, the yield warning, and bad input.

Each test names its reference and the reason for its tolerance.
"""

import math
import warnings

import numpy as np
import pytest

import flexure

# A steel strip 50 mm long and 10 mm wide.
E, B, L = 200e9, 0.01, 0.05


def quiet(call, *args, **kwargs):
    """Runs `call` with warnings turned into errors: the answer must come without any."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return call(*args, **kwargs)


def test_tapered_cantilever_stress_is_beam_theory():
    # Euler-Bernoulli beam theory for a cantilever with a small tip force F across it:
    # M(s) = F (L - s), so sigma(s) = E h/2 * M/(E b h^3/12) = 6 F (L - s) / (b h(s)^2).
    # A thickness tapering from h0 to h1 = 0.3 h0 puts the peak inside the flexure, where
    # d/ds[(L - s)/h^2] = 0: t* = (2r - 1)/(r - 1) = 4/7 for r = h1/h0 = 0.3.
    h0, h1 = 4e-4, 1.2e-4
    f = flexure.Flexure(length=L, modulus=E, width=B, thickness=(h0, h1), order=20)
    force = 3e-4 * f.ei / L**2  # tip deflection about 1e-4 L: linear beam theory holds to (1e-4)^2
    alpha = quiet(f.deflect, fy=force)
    shape = f.shape(alpha, 201)
    s = shape["s"]
    beam = 6 * force * (L - s) / (B * (h0 + (h1 - h0) * s / L) ** 2)
    t_peak = (2 * 0.3 - 1) / (0.3 - 1)
    h_peak = h0 + (h1 - h0) * t_peak
    peak = 6 * force * L * (1 - t_peak) / (B * h_peak**2)
    # Tolerance 1e-6 of the peak: the curvature F (L - s)/EI(s) with EI ~ h^3 is rational, so
    # its Legendre series converges geometrically (measured 3e-4 at order 12, 5e-6 at 16,
    # 6e-8 at 20), and the geometric nonlinearity at this load is (1e-4)^2 = 1e-8.
    assert np.max(np.abs(shape["stress"] - beam)) < 1e-6 * peak
    p = f.stress(alpha)
    assert abs(p["max"] / peak - 1) < 1e-6
    # A smooth maximum is located to the square root of its value's error: sqrt(1e-6) L.
    assert abs(p["at"] - t_peak * L) < 1e-3 * L
    # The shape's columns, and its ends: the root, and the tip exactly at L.
    assert shape.dtype.names == ("s", "x", "y", "phi", "curvature", "stress")
    assert s[0] == 0.0 and s[-1] == L and len(s) == 201
    assert np.allclose(np.diff(s), L / 200, rtol=0, atol=1e-15)
    # The tip of the shape is the tip pose (two quadratures of one integral: 1e-12 L).
    assert np.allclose([shape["phi"][-1], shape["x"][-1], shape["y"][-1]], f.pose(alpha), rtol=0, atol=1e-12 * L)


def test_notch_hinge_compliance_is_paros_weisbord():
    # Paros & Weisbord (1965), the circular hinge of radius R and least thickness h cut
    # through a blank 2R + h thick, L = 2R, under a moment: the exact integral of ds/EI,
    # d(phi)/dM = 3/(2 E b R^2) / (2 beta + beta^2) * [(3 + 4 beta + 2 beta^2) / ((1 + beta)(2 beta + beta^2))
    #             + 6 (1 + beta)/(2 beta + beta^2)^(3/2) * atan(sqrt((2 + beta)/beta))], beta = h/(2R)
    # (the formula of crates/flexure/tests/section.rs).
    e, b, r, h = 70e9, 0.01, 0.005, 5e-4
    beta = h / (2 * r)
    q = 2 * beta + beta**2
    closed = (
        3 / (2 * e * b * r * r) / q
        * ((3 + 4 * beta + 2 * beta**2) / ((1 + beta) * q) + 6 * (1 + beta) / q**1.5 * math.atan(math.sqrt((2 + beta) / beta)))
    )
    errors = []
    for order in [16, 32, 48, 64]:
        f = flexure.Flexure(length=2 * r, modulus=e, width=b, thickness=2 * r + h, notch=(r, h), order=order)
        errors.append((closed - f.rest_compliance()[0, 0]) / closed)
    # The model is a Ritz approximation: stiffer than the exact beam, so its compliance is below
    # the closed form (to the 1e-13 of K's adaptive integration), and it converges as the order grows.
    assert all(e > -1e-12 for e in errors), errors
    assert all(a > b for a, b in zip(errors, errors[1:])), errors
    # At order 64 within 1e-9 (measured 5e-11; 2e-9 at order 48, 1e-5 at order 32).
    assert errors[-1] < 1e-9, errors
    # The thickness is the notch's: h at the middle, the blank's at the ends.
    assert abs(f.thickness_at(r) - h) < 1e-15
    assert np.allclose(f.thickness_at([0.0, 2 * r]), 2 * r + h, rtol=1e-12)


def test_tables_as_arrays_lists_and_pairs_agree():
    # The same table given as an array, a list of lists and a tuple of tuples is the same
    # section, so every answer is identical to the bit.
    table = [[0.0, 4e-4], [0.3, 3e-4], [1.0, 2.5e-4]]
    forms = [np.array(table), table, tuple(tuple(row) for row in table), np.asfortranarray(np.array(table))]
    answers = []
    alpha = [0.1, -0.03, 0.01, 0.004, -0.002, 0.001, 0.0005, -0.0002]
    for thickness in forms:
        f = flexure.Flexure(length=L, modulus=E, width=B, thickness=thickness, order=8)
        answers.append((f.stiffness(alpha, fy=0.05), f.stress(alpha), f.shape(alpha, 11)))
    for other in answers[1:]:
        assert np.array_equal(other[0], answers[0][0])
        assert other[1] == answers[0][1]
        assert np.array_equal(other[2], answers[0][2])
    # A two-row table is the linear taper (root, tip): the same EI(s) to rounding (1e-15).
    s = np.linspace(0, L, 7)
    pair = flexure.Flexure(length=L, modulus=E, width=(0.012, 0.008), thickness=2e-4)
    rows = flexure.Flexure(length=L, modulus=E, width=[[0, 0.012], [1, 0.008]], thickness=2e-4)
    assert np.allclose(pair.ei_at(s), rows.ei_at(s), rtol=1e-15, atol=0)
    assert np.allclose(pair.stiffness([0.0] * 3), rows.stiffness([0.0] * 3), rtol=1e-14, atol=0)
    # And EI(s) is E b(s) h^3/12 along it, linear in s (exact arithmetic up to rounding).
    assert np.allclose(pair.ei_at(s), E * (0.012 - 0.004 * s / L) * 2e-4**3 / 12, rtol=1e-14, atol=0)
    # ei tables likewise: EI given directly, so a curvature peak and no stress.
    g = flexure.Flexure(ei=np.array([[0.0, 2.0], [0.5, 1.0], [1.0, 1.5]]))
    assert g.ei_at(0.25) == pytest.approx(1.5, rel=1e-15) and not g.uniform and g.modulus is None
    assert g.stress([1.0, 0.0, 0.0]) is None and g.thickness_at(0.5) is None
    assert g.shape([1.0, 0.0, 0.0], 3).dtype.names == ("s", "x", "y", "phi", "curvature")


def test_uniform_rectangle_under_a_moment_is_an_arc():
    # A pure moment M bends a uniform beam into an arc of curvature M/EI (exact in the model,
    # whose first basis function is a constant curvature): sigma = 6 M/(b h^2) all along,
    # x = sin(k s)/k, y = (1 - cos(k s))/k. Tolerance 1e-12 relative: rounding over 5 points.
    h, m = 2e-4, 0.02
    f = flexure.Flexure(length=L, modulus=E, width=B, thickness=h, poisson=0.3)
    assert f.uniform and f.modulus == pytest.approx(E / (1 - 0.09), rel=1e-15)
    alpha = quiet(f.deflect, moment=m)
    k = m / f.ei
    shape = f.shape(alpha, 5)
    sigma = 6 * m / (B * h**2)
    assert np.allclose(shape["stress"], sigma, rtol=1e-12, atol=0)
    assert np.allclose(shape["curvature"], k, rtol=1e-12, atol=0)
    assert np.allclose(shape["x"], np.sin(k * shape["s"]) / k, rtol=0, atol=1e-12 * L)
    assert np.allclose(shape["y"], (1 - np.cos(k * shape["s"])) / k, rtol=0, atol=1e-12 * L)
    assert f.stress(alpha)["max"] == pytest.approx(sigma, rel=1e-12)
    assert f.peak_curvature(alpha)["max"] == pytest.approx(k, rel=1e-12)


def test_yield_warning_and_safety_factor():
    assert issubclass(flexure.YieldWarning, UserWarning) and "YieldWarning" in flexure.__all__
    h, m = 2e-4, 0.02
    sigma = 6 * m / (B * h**2)  # the arc of the test above: 300 MPa
    weak = flexure.Flexure(length=L, modulus=E, width=B, thickness=h, yield_strength=0.8 * sigma)
    with pytest.warns(flexure.YieldWarning, match=r"deflect: .*exceeds the yield strength 2\.4e8 Pa: safety factor 0\.800") as caught:
        alpha = weak.deflect(moment=m)
    assert caught[0].filename == __file__
    with pytest.warns(flexure.YieldWarning, match=r"yield strength 2\.4e8 Pa"):
        assert weak.safety_factor(alpha) == pytest.approx(0.8, rel=1e-12)
    # The flexure deflect(order="auto") returns keeps the yield strength, and warns too.
    with pytest.warns(flexure.YieldWarning):
        used, _ = weak.deflect(moment=m, order="auto")
    assert used.yield_strength == weak.yield_strength
    # Strong enough: the factor, no warning; unstressed: infinite.
    strong = flexure.Flexure(length=L, modulus=E, width=B, thickness=h, yield_strength=2 * sigma)
    alpha = quiet(strong.deflect, moment=m)
    assert quiet(strong.safety_factor, alpha) == pytest.approx(2.0, rel=1e-12)
    assert quiet(strong.safety_factor, [0.0, 0.0, 0.0]) == math.inf


MECHANISM = """
[[joint]]
name = "hinge"
kind = "flexure"
parent = "ground"
child = "link"
length = 0.05
modulus = 2.0e11
width = 0.01
thickness = 2.0e-4
{extra}

[[joint]]
name = "spring"
kind = "flexure"
parent = "link"
child = "tip"
length = 0.05
ei = 0.01

[[force]]
body = "tip"
at = [0.0, 0.0]
moment = 0.02
"""


def test_mechanism_reports_stress_per_flexure_joint():
    # A moment on the last body passes unchanged through both flexures: each is an arc, the
    # hinge stressed 6 M/(b h^2) = 300 MPa, the spring (ei alone) bent by M/EI = 2 1/m.
    text = MECHANISM.format(extra="yield_strength = 2.4e8\nshape = 3")
    with pytest.warns(flexure.YieldWarning, match=r"flexure joint 'hinge'.*yield strength 2\.4e8 Pa") as caught:
        result = flexure.Mechanism.from_toml(text).solve()
    assert caught[0].filename == __file__
    assert set(result["stress"]) == {"hinge"} and set(result["curvature_max"]) == {"spring"}
    # Tolerance 1e-9 relative: the equilibrium is met to the solver's tolerance.
    assert result["stress"]["hinge"]["max"] == pytest.approx(300e6, rel=1e-9)
    assert result["curvature_max"]["spring"]["max"] == pytest.approx(2.0, rel=1e-9)
    assert result["safety_factor"]["hinge"] == pytest.approx(0.8, rel=1e-9)
    shape = result["shape"]["hinge"]
    assert len(shape) == 3 and shape["s"][-1] == 0.05
    assert np.allclose(shape["stress"], 300e6, rtol=1e-9)
    # Without yield_strength or shape, those maps are left out.
    plain = quiet(flexure.Mechanism.from_toml(MECHANISM.format(extra="")).solve)
    assert "safety_factor" not in plain and "shape" not in plain


def test_section_properties_and_mass():
    f = flexure.Flexure(length=L, modulus=E, width=[[0, 0.012], [0.5, 0.008], [1, 0.008]], thickness=2e-4, density=7850)
    s = np.array([0.0, L / 4, L])
    assert np.allclose(f.width_at(s), [0.012, 0.010, 0.008], rtol=1e-15)
    assert np.allclose(f.mass_per_length_at(s), 7850 * np.array([0.012, 0.010, 0.008]) * 2e-4, rtol=1e-15)
    assert isinstance(f.ei_at(0.0), float) and f.ei_at(s).shape == (3,)
    # EI's mean: (1/L) int E b(s) h^3/12 ds, b averaging (0.012 + 0.008)/2 and 0.008 on the halves.
    assert f.ei == pytest.approx(E * 0.009 * 2e-4**3 / 12, rel=1e-14)
    g = flexure.Flexure(ei=1.0, mass_per_length=(0.2, 0.1))
    assert g.mass_per_length_at(0.5) == pytest.approx(0.15, rel=1e-15)
    assert flexure.Flexure().mass_per_length_at(0.5) is None and flexure.Flexure().width_at(0.5) is None


BAD = [
    # Zero or negative width or thickness, anywhere along the flexure.
    ("flexure.Flexure(modulus=2e11, width=0.0, thickness=2e-4)", r"width = 0: must be a finite number greater than zero"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=-2e-4)", r"thickness = -0.0002"),
    ("flexure.Flexure(modulus=2e11, width=(0.01, 0.0), thickness=2e-4)", r"width = 0"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=(-1e-4, 2e-4))", r"thickness = -0.0001"),
    ("flexure.Flexure(modulus=2e11, width=[[0, 0.01], [0.5, -0.01], [1, 0.01]], thickness=2e-4)", r"width = -0.01"),
    ("flexure.Flexure(ei=(1.0, 0.0))", r"ei = 0"),
    ("flexure.Flexure(ei=1.0, mass_per_length=[[0, 1.0], [1, -1.0]])", r"mass_per_length = -1"),
    # Tables that do not start at 0, end at 1 and increase strictly.
    ("flexure.Flexure(modulus=2e11, width=[[0.1, 0.01], [1, 0.01]], thickness=2e-4)", r"width = .*t = s/L must start at 0, end at 1 and increase strictly"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=[[0, 2e-4], [0.9, 2e-4]])", r"thickness = .*must start at 0, end at 1"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=[[0, 2e-4], [0.5, 2e-4], [0.5, 1e-4], [1, 1e-4]])", r"thickness = .*increase strictly"),
    ("flexure.Flexure(ei=[[0, 1.0], [0.6, 1.0], [0.4, 1.0], [1, 1.0]])", r"ei = .*increase strictly"),
    ("flexure.Flexure(ei=[[0, 1.0]])", r"ei = .*at least two points"),
    # A notch deeper than the thickness, or too small for its cut, or malformed.
    ("flexure.Flexure(length=0.01, modulus=7e10, width=0.01, thickness=0.005, notch=(0.005, 0.006))", r"notch.min_thickness = 0.006: must be less than the thickness"),
    ("flexure.Flexure(length=0.01, modulus=7e10, width=0.01, thickness=0.005, notch=(0.005, 0.005))", r"notch.min_thickness = 0.005"),
    ("flexure.Flexure(length=0.01, modulus=7e10, width=0.01, thickness=0.005, notch=(0.001, 0.0005))", r"notch.radius = 0.001: must be at least half the cut"),
    ("flexure.Flexure(length=0.01, modulus=7e10, width=0.01, thickness=0.005, notch=(-0.005, 0.0005))", r"notch.radius = -0.005"),
    ("flexure.Flexure(length=0.01, modulus=7e10, width=0.01, thickness=0.005, notch=(0.005,))", r"notch must be a pair \(radius, min_thickness\)"),
    ("flexure.Flexure(length=0.01, modulus=7e10, width=0.01, thickness=0.005, notch='0.005,0.001')", r"notch must be a pair"),
    # Non-finite values.
    ("flexure.Flexure(modulus=2e11, width=float('nan'), thickness=2e-4)", r"width = NaN"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=(2e-4, float('inf')))", r"thickness contains inf"),
    ("flexure.Flexure(modulus=2e11, width=np.array([[0, 0.01], [np.nan, 0.01], [1, 0.01]]), thickness=2e-4)", r"width contains NaN"),
    ("flexure.Flexure(ei=float('-inf'))", r"ei = -inf"),
    ("flexure.Flexure(length=0.01, modulus=7e10, width=0.01, thickness=0.005, notch=(float('nan'), 0.001))", r"notch radius = NaN"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=2e-4, density=float('nan'))", r"density = NaN"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=2e-4, yield_strength=float('inf'))", r"yield_strength = inf"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=2e-4, yield_strength=-1.0)", r"yield_strength = -1"),
    # Wrong shapes.
    ("flexure.Flexure(modulus=2e11, width=[0.01, 0.008, 0.006], thickness=2e-4)", r"width must be a number, a pair .*3 values"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=np.zeros((3, 3)) + 1e-4)", r"thickness .*rows must be \[t, value\] pairs, got shape \(3, 3\)"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=np.ones((2, 2, 2)))", r"thickness .*too many dimensions"),
    ("flexure.Flexure(modulus=2e11, width=[[0, 0.01], [1]], thickness=2e-4)", r"width must be a number, a pair"),
    ("flexure.Flexure(modulus=2e11, width=[], thickness=2e-4)", r"width must be .*0 values"),
    ("flexure.Flexure(modulus=2e11, width=['a', 'b'], thickness=2e-4)", r"width must be .*not all numbers"),
    ("flexure.Flexure(ei=1.0, mass_per_length=np.ones(5))", r"mass_per_length must be .*5 values"),
    # Options that contradict or would be ignored.
    ("flexure.Flexure(notch=(0.005, 0.001))", r"notch given without modulus would be ignored"),
    ("flexure.Flexure(ei=(1.0, 2.0), thickness=2e-4)", r"thickness given without modulus"),
    ("flexure.Flexure(ei=(1.0, 2.0), density=7850)", r"density = 7850: needs a width and thickness"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=2e-4, density=7850, mass_per_length=0.1)", r"density = 7850 and mass_per_length were both given"),
    ("flexure.Flexure(ei=(1.0, 2.0), yield_strength=1e8)", r"yield_strength = 100000000: needs a thickness"),
    # Shapes of fewer than two points, or too many; s off the flexure; a safety factor without S.
    ("f.shape([0.0] * 3, 1)", r"k = 1: must be from 2 to 10000"),
    ("f.shape([0.0] * 3, 0)", r"k = 0"),
    ("f.shape([0.0] * 3, -4)", r"k = -4"),
    ("f.shape([0.0] * 3, 10001)", r"k = 10001"),
    ("f.shape([0.0] * 2, 5)", r"alpha must have 3 entries"),
    ("f.stress([0.0, float('nan'), 0.0])", r"alpha contains NaN"),
    ("f.peak_curvature([[0.0] * 3] * 2)", r"alpha must have shape \(3,\) here"),
    ("f.ei_at(1.5)", r"s = 1.5: must lie along the flexure, in \[0, L\] = \[0, 1\] m"),
    ("f.ei_at([0.0, -0.1])", r"s = -0.1"),
    ("f.ei_at(float('nan'))", r"s = NaN"),
    ("f.safety_factor([0.0] * 3)", r"safety_factor needs the flexure's yield_strength"),
]


@pytest.mark.parametrize("code, message", BAD)
def test_bad_section_input_raises_value_error_naming_it(code, message):
    with pytest.raises(ValueError, match=message):
        eval(code, {"flexure": flexure, "np": np, "f": flexure.Flexure()})


def test_text_is_a_type_error():
    # As for any float argument: NumPy would read "0.01" as a number, the bindings do not.
    with pytest.raises(TypeError, match="argument 'width'"):
        flexure.Flexure(modulus=2e11, width="0.01", thickness=2e-4)
    with pytest.raises(TypeError, match="argument 'k'"):
        flexure.Flexure().shape([0.0] * 3, 2.5)


def test_constructor_forms_of_before_still_work():
    # A number for ei (positional too), and a uniform rectangle by Eq. 25: the same EI as before.
    assert flexure.Flexure(1.0, 2.0).ei == 2.0
    plain = flexure.Flexure(modulus=200e9, width=0.01, thickness=0.0002)
    assert plain.ei == pytest.approx(200e9 * 0.01 * 0.0002**3 / 12, rel=1e-15) and plain.uniform
    assert np.array_equal(flexure.Flexure(ei=np.float64(2.0)).stiffness([0.0] * 3), flexure.Flexure(ei=2.0).stiffness([0.0] * 3))
