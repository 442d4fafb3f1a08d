"""The exact references on non-uniform sections from Python (flexure.exact with
`flexure=`): the exact stress against beam theory, the compliance ODE against
closed forms, the column against Euler, the model converging to them with the
order, the warnings, and bad input.

Each test names its reference and the reason for its tolerance. The exact
solvers integrate to 1e-12 relative (1e-13 absolute); that sets their floor.
"""

import math
import warnings

import numpy as np
import pytest

import flexure
from flexure import exact

# A steel strip 50 mm long and 10 mm wide.
E, B, L = 200e9, 0.01, 0.05


def quiet(call, *args, **kwargs):
    """Runs `call` with warnings turned into errors: the answer must come without any."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return call(*args, **kwargs)


def taper(order=3, **kwargs):
    """The thickness falls linearly from 0.6 mm to 0.25 mm: EI(s) is cubic in s."""
    return flexure.Flexure(length=L, modulus=E, width=B, thickness=(6e-4, 2.5e-4), order=order, **kwargs)


def test_exact_stress_of_a_tapered_cantilever_is_beam_theory():
    # Euler-Bernoulli beam theory, a cantilever with a small tip force F across it:
    # m(s) = F (L - s), sigma(s) = 6 F (L - s) / (b h(s)^2). With h falling from h0 to h1 = h0/3
    # the maximum of (L - s)/h^2 lies at s* = L (2 h1 - h0)/(h1 - h0) = L/2.
    h0, h1 = 6e-4, 2e-4
    f = flexure.Flexure(length=L, modulus=E, width=B, thickness=(h0, h1))
    force = 1e-5 * f.ei / L**2  # tip deflection ~1e-5 L: the nonlinearity is ~(1e-5)^2
    e = quiet(exact.elastica, fy=force, flexure=f)
    assert e.stable and e.load == (0.0, 0.0, force)

    def beam(s):
        return 6 * force * (L - s) / (B * (h0 + (h1 - h0) * s / L) ** 2)

    shape = e.shape(11)
    assert shape.dtype.names == ("s", "x", "y", "phi", "curvature", "stress")
    assert shape["s"][0] == 0.0 and shape["s"][-1] == L
    # Every point to 1e-7 relative: the shooting tolerance (1e-12) and the nonlinearity (1e-10)
    # lie far below; 1e-7 is the Rust test's bound (crates/flexure/tests/section_exact.rs).
    s = shape["s"][:-1]
    assert np.max(np.abs(shape["stress"][:-1] / beam(s) - 1)) < 1e-7
    # No moment at a free tip without a tip moment: zero up to the shooting tolerance.
    assert shape["stress"][-1] < 1e-9 * beam(0.0)
    peak = e.stress()
    assert abs(peak["max"] / beam(L / 2) - 1) < 1e-7
    # A smooth maximum is placed to about the square root of its value's accuracy.
    assert abs(peak["at"] - L / 2) < 1e-3 * L
    # The stress is E' h/2 times the curvature change; with a straight rest shape the
    # curvature column is that change: the two columns agree to rounding.
    h = h0 + (h1 - h0) * shape["s"] / L
    assert np.allclose(shape["stress"], E * h / 2 * np.abs(shape["curvature"]), rtol=1e-12, atol=0)
    # The shape's last point is the tip pose (one integration from the nearest node: 1e-12 L).
    tip = [shape["phi"][-1], shape["x"][-1], shape["y"][-1]]
    assert np.allclose(tip, e.pose, rtol=0, atol=1e-12 * L)


def test_notch_hinge_under_a_moment_is_stressed_most_at_its_waist():
    # A tip moment M loads every section with m = M: sigma(s) = 6 M / (b h(s)^2), largest
    # at the notch's waist (the middle) where h = h_min. To 1e-9: the moment stays M to the
    # shooting tolerance, and the waist lies on a section breakpoint the peak scan includes.
    r, h_min, length = 4e-3, 5e-4, 0.03
    f = flexure.Flexure(length=length, modulus=E, width=B, thickness=2e-3, notch=(r, h_min))
    moment = 0.02
    e = quiet(exact.elastica, moment=moment, flexure=f)
    peak = e.stress()
    assert abs(peak["max"] / (6 * moment / (B * h_min**2)) - 1) < 1e-9
    assert abs(peak["at"] - length / 2) < 1e-12
    # The curvature change M/EI(s) at every point of the shape (1e-9, as above).
    shape = e.shape(7)
    assert np.allclose(shape["curvature"] * f.ei_at(shape["s"]), moment, rtol=1e-9, atol=0)


def test_a_section_given_by_ei_has_curvature_but_no_stress():
    # EI falling linearly from 2 to 1 under a tip moment M: curvature M/EI(s), largest at the
    # tip, M/1 (1e-9: the moment is constant to the shooting tolerance). No thickness, no stress,
    # and the shape has no stress column, as the model's.
    f = flexure.Flexure(length=1.0, ei=(2.0, 1.0))
    e = quiet(exact.elastica, moment=0.1, flexure=f)
    assert e.stress() is None
    peak = e.peak_curvature()
    assert abs(peak["max"] - 0.1) < 1e-9 and abs(peak["at"] - 1.0) < 1e-9
    assert e.shape(3).dtype.names == ("s", "x", "y", "phi", "curvature") == f.shape(np.zeros(3), 3).dtype.names
    # The tip angle is the closed form M ∫ds/EI = M ln(2)/c with c = 1 per unit length (1e-10).
    assert abs(e.pose[0] - 0.1 * math.log(2.0)) < 1e-10


@pytest.mark.parametrize("a, b, length", [(2.0, 0.5, 0.3), (1.0, 3.0, 1.2)])
def test_linear_ei_taper_compliance_in_closed_form(a, b, length):
    # EI(s) = a + c s from a = EI(root) to b = EI(tip), c = (b - a)/L. With u = EI(s),
    # L - s = (b - u)/c, the integrals of the compliance ODE (Eq. 34) for a straight beam are
    # C_phiphi = ∫ds/EI = ln(b/a)/c, C_phiy = ∫(L - s)/EI ds = b ln(b/a)/c^2 - L/c,
    # C_yy = ∫(L - s)^2/EI ds = [b^2 ln(b/a) - 2b(b - a) + (b^2 - a^2)/2]/c^3
    # (as in crates/flexure/tests/section_exact.rs). 1e-10 relative to the largest entry: the
    # ODE is integrated to 1e-12, the closed forms cancel to ~1e-14 at b/a = 1/4.
    c = (b - a) / length
    log = math.log(b / a)
    pp = log / c
    py = b * log / c**2 - length / c
    yy = (b * b * log - 2 * b * (b - a) + (b * b - a * a) / 2) / c**3
    closed = np.array([[pp, 0.0, py], [0.0, 0.0, 0.0], [py, 0.0, yy]])
    f = flexure.Flexure(length=length, ei=(a, b))
    got = exact.compliance(flexure=f)
    assert np.max(np.abs(got - closed)) < 1e-10 * np.max(np.abs(closed))
    # The same beam given to exact.compliance directly: the same integration.
    assert np.array_equal(exact.compliance(length=length, ei=(a, b)), got)


def euler_factors():
    """Euler's loads P L^2/EI of a column clamped at its root: free pi^2/4, guided pi^2,
    pinned beta^2 with tan(beta) = beta (beta = 4.4934, ERRATA: 20.1907), clamped 4 pi^2."""
    beta = 4.49
    for _ in range(50):  # Newton on tan(b) - b, from inside its basin (converges in ~5 steps)
        beta -= (math.tan(beta) - beta) / (math.tan(beta) ** 2)
    assert abs(beta**2 - 20.1907) < 1e-4
    return {"free": math.pi**2 / 4, "guided": math.pi**2, "pinned": beta**2, "clamped": 4 * math.pi**2}


@pytest.mark.parametrize("tip", ["free", "guided", "pinned", "clamped"])
@pytest.mark.parametrize("length, ei", [(1.0, 1.0), (0.015, 1.46e-3), (3.0, 250.0)])
def test_uniform_column_is_euler(tip, length, ei):
    euler = euler_factors()[tip] * ei / length**2
    # A uniform flexure takes Euler's closed form: its own, 1e-12 for the rounding of beta.
    assert abs(exact.buckling_load(tip, flexure=flexure.Flexure(length=length, ei=ei)) / euler - 1) < 1e-12
    assert abs(exact.buckling_load(tip, length=length, ei=ei) / euler - 1) < 1e-12
    # The same column written as a "taper" with equal ends goes through the shooting
    # determinant instead: 1e-9 (bisection to rounding, integrator to 1e-12), the Rust bound.
    shot = exact.buckling_load(tip, flexure=flexure.Flexure(length=length, ei=(ei, ei)))
    assert abs(shot / euler - 1) < 1e-9


def test_tapered_column_lies_between_the_euler_loads_of_its_extremes():
    # Rayleigh's quotient: the least critical load of a column with EI_min <= EI(s) <= EI_max lies
    # between Euler's loads for EI_min and for EI_max (strictly, for a strict taper).
    f = taper()
    ei = f.ei_at(np.linspace(0, L, 101))
    for tip, factor in euler_factors().items():
        p = exact.buckling_load(tip, flexure=f)
        assert factor * ei.min() / L**2 < p < factor * ei.max() / L**2


def test_model_at_high_order_approaches_the_exact_answers_on_a_taper():
    # Reference: the exact references on the same section. The taper's EI is smooth, so the
    # model converges geometrically: each doubling of the order must at least halve the error,
    # down to the exact solvers' floor (measured at N = 16: tip 1.2e-13 L and 5e-14 rad, peak
    # stress 2e-9, compliance 6e-13, buckling loads 1.5e-13). Bounds at N = 16 leave a factor
    # ~10-100 above those, the exact side's own tolerance (1e-12) included.
    f = taper()
    compliance = exact.compliance(flexure=f)
    force = 0.8 / compliance[0, 2]  # about 0.8 rad of tip rotation in the linear theory: a large deflection
    e = quiet(exact.elastica, fy=force, flexure=f)
    assert e.stable and e.pose[0] > 0.5
    sigma = e.stress()["max"]
    buckling = {tip: exact.buckling_load(tip, flexure=f) for tip in euler_factors()}
    last = {"position": math.inf, "stress": math.inf, "compliance": math.inf}
    for order in [2, 4, 8, 16]:
        g = taper(order)
        with warnings.catch_warnings():
            # The low orders miss the default accuracy target: their error is measured here.
            warnings.simplefilter("ignore", flexure.AccuracyWarning)
            alpha = g.deflect(fy=force)
        pose = g.pose(alpha)
        error = {
            "position": math.hypot(*(pose[1:] - e.pose[1:])) / L,
            "stress": abs(g.stress(alpha)["max"] / sigma - 1),
            "compliance": abs(g.rest_compliance()[2, 2] / compliance[2, 2] - 1),
        }
        for what in last:
            assert error[what] < 0.5 * last[what] or error[what] < 1e-11, (order, what, error[what], last[what])
        last = error
        # The model is a Ritz approximation: stiffer than the exact beam. Its compliance is below
        # the exact one and its buckling loads above, by more than the 1e-12 floor of either.
        assert g.rest_compliance()[2, 2] < compliance[2, 2] * (1 + 1e-12)
        for tip, p in buckling.items():
            if order > 2:  # (order 2 leaves a clamped tip no freedom: the model refuses it)
                assert g.buckling_load(tip) > p * (1 - 1e-12), (order, tip)
    assert last["position"] < 1e-11 and abs(pose[0] - e.pose[0]) < 1e-11
    assert last["stress"] < 1e-7
    assert last["compliance"] < 1e-10
    for tip, p in buckling.items():
        assert taper(16).buckling_load(tip) / p - 1 < 1e-10, tip


def test_bisshopp_drucker_on_a_flexure():
    # Bisshopp & Drucker (1945): PL^2/EI = 1 across the tip puts it at (0.94357, 0.30172) L.
    # A rectangle of EI = E b h^3/12 = 1 N m^2 over L = 1 m, to their 5 digits.
    h = 1e-3
    b = 12 / (E * h**3)
    f = flexure.Flexure(length=1.0, modulus=E, width=b, thickness=h)
    pose = quiet(exact.deflect, fy=1.0, flexure=f)
    assert np.allclose(pose[1:], [0.94357, 0.30172], atol=5e-6)
    # exact.deflect is elastica's pose, and the old form (length and ei) the same beam.
    assert np.array_equal(pose, exact.elastica(fy=1.0, flexure=f).pose)
    assert np.allclose(exact.deflect(fy=1.0), pose, rtol=0, atol=1e-11)


def test_past_the_tapered_columns_buckling_load_the_exact_elastica_warns():
    # The straight shape under 1.1 x the exact buckling load (free tip) is an equilibrium, but
    # unstable: the Jacobi test says so. Below it (0.9 x) it is stable and quiet.
    f = taper()
    p = exact.buckling_load("free", flexure=f)
    with pytest.warns(flexure.StabilityWarning, match=r"exact\.elastica.*Jacobi"):
        e = exact.elastica(fx=-1.1 * p, flexure=f)
    assert not e.stable
    with pytest.warns(flexure.StabilityWarning, match=r"exact\.deflect"):
        exact.deflect(fx=-1.1 * p, flexure=f)
    assert quiet(exact.elastica, fx=-0.9 * p, flexure=f).stable


def test_yield_strength_gives_the_exact_safety_factor():
    # The safety factor is S/sigma_max of the exact peak (rounding only); 700 MPa against
    # the ~736 MPa peak of this load warns YieldWarning at the solve and at safety_factor.
    f = taper()
    force = 0.8 / exact.compliance(flexure=f)[0, 2]
    sigma = exact.elastica(fy=force, flexure=f).stress()["max"]
    strong = taper(yield_strength=2 * sigma)
    e = quiet(exact.elastica, fy=force, flexure=strong)
    assert abs(quiet(e.safety_factor) - 2.0) < 1e-12
    weak = taper(yield_strength=0.95 * sigma)
    with pytest.warns(flexure.YieldWarning, match=r"exact\.elastica: the peak bending stress"):
        e = exact.elastica(fy=force, flexure=weak)
    with pytest.warns(flexure.YieldWarning, match="safety factor 0.950"):
        assert abs(e.safety_factor() - 0.95) < 1e-12
    with pytest.warns(flexure.YieldWarning, match=r"exact\.deflect"):
        exact.deflect(fy=force, flexure=weak)
    # Unloaded: unstressed, an infinite safety factor and no warning.
    assert quiet(quiet(exact.elastica, flexure=weak).safety_factor) == math.inf


BAD = [
    ("exact.elastica(fy=1.0, flexure='steel')", r"flexure must be a flexure.Flexure, got str"),
    ("exact.deflect(fy=1.0, length=2.0, flexure=f)", r"length given with flexure would be ignored"),
    ("exact.compliance(ei=1.0, kappa=[0.0], flexure=f)", r"ei and kappa given with flexure would be ignored"),
    ("exact.buckling_load('free', ei=2.0, flexure=f)", r"ei given with flexure would be ignored"),
    ("exact.elastica(moment=float('nan'), flexure=f)", r"moment = NaN"),
    ("exact.elastica(fx=-1e9, flexure=f)", r"force"),
    ("exact.buckling_load('hinged', flexure=f)", r"tip"),
    ("exact.buckling_load(flexure=flexure.Flexure(kappa=[0.5, 0.0, 0.0]))", r"kappa = \[0.5, 0.0, 0.0\].*straight"),
    ("exact.elastica(fy=1.0, flexure=f).shape(1)", r"k = 1: must be from 2 to"),
    ("exact.elastica(fy=1.0, flexure=f).safety_factor()", r"yield_strength"),
    ("exact.compliance(ei=(1.0, -1.0))", r"ei"),
    ("exact.compliance(ei=(1.0, 2.0, 3.0))", r"ei must be"),
    ("exact.elastica(fy=1.0, length=-1.0, ei=(1.0, 2.0))", r"length = -1"),
    ("exact.deflect(fy=1.0, kappa=[])", r"kappa must have from 1 to 64 entries .*got 0"),
]


@pytest.mark.parametrize("code, message", BAD)
def test_bad_input_is_a_value_error_naming_the_parameter(code, message):
    f = taper()
    with pytest.raises(ValueError, match=message):
        eval(code, {"exact": exact, "flexure": flexure, "f": f})
