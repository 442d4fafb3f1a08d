"""Python as strict as the CLI (issue 21, item 5): no infinity or NaN is returned (the
CLI refuses any non-finite number in an answer, naming the field), booleans are not
numbers, coordinates keep the library's bound of 1e6 rad, and a thickness above the
length is refused by the library, so every front end refuses it."""

import warnings

import numpy as np
import pytest

import flexure


def named(error, name):
    """Whether `error` names `name`: in its message, or in the note PyO3 adds to a failed
    argument conversion ("while processing 'name'")."""
    text = str(error) + " ".join(getattr(error, "__notes__", []))
    return f"'{name}'" in text


# --- no infinity or NaN comes back -------------------------------------------------


def test_modes_of_a_vanishing_mass_are_refused_not_infinite():
    # Measured on main: omega = [inf, inf]. The CLI refuses the same answer, naming omega.
    f = flexure.Flexure(ei=1.0, mass_per_length=1e-308)
    with pytest.raises(ValueError, match=r"Flexure.modes: the result's field `omega\[0\]` is not a finite number"):
        f.modes(2)


def test_energy_beyond_the_coordinate_bound_is_refused():
    # Measured on main: energy([1e155, 0, 0]) = inf. The library bounds coordinates at 1e6 rad.
    with pytest.raises(ValueError, match=r"alpha contains 1e155: .*at most 1e6 rad"):
        flexure.Flexure().energy([1e155, 0.0, 0.0])


@pytest.mark.parametrize(
    "call",
    [
        "f.pose([1e7, 0.0, 0.0])",
        "f.pose(np.array([[0.0, 0.0, 0.0], [0.0, -2e6, 0.0]]))",
        "f.jacobian([0.0, 0.0, 1e6 * (1 + 1e-15)])",
        "f.compliance([2e6, 0.0, 0.0])",
        "f.stress([0.0, 1e7, 0.0])",
        "flexure.Flexure(kappa=[0.0, 0.0, 1e7])",
    ],
)
def test_coordinates_above_the_librarys_bound_are_refused(call):
    # The CLI refuses |alpha| > 1e6 (`kinematics --alpha`); Python accepted them.
    f = flexure.Flexure(modulus=2e11, width=0.01, thickness=2e-4)
    with pytest.raises(ValueError, match=r"(alpha|kappa) contains .*at most 1e6 rad"):
        eval(call)


def test_coordinates_at_the_bound_are_accepted():
    f = flexure.Flexure()
    assert np.isfinite(f.pose([1e6, 0.0, 0.0])).all()
    assert np.isfinite(f.energy([-1e6, 0.0, 0.0]))


# --- booleans are not numbers ------------------------------------------------------


@pytest.mark.parametrize(
    "call, name",
    [
        ("flexure.Flexure(length=True)", "length"),
        ("flexure.Flexure(modulus=2e11, width=0.01, thickness=True)", "thickness"),
        ("flexure.Flexure(modulus=2e11, width=(0.01, True), thickness=2e-4)", "width"),
        ("flexure.Flexure(modulus=True, width=0.01, thickness=2e-4)", "modulus"),
        ("flexure.Flexure(modulus=2e11, width=0.01, thickness=2e-4, poisson=False)", "poisson"),
        ("flexure.Flexure(modulus=2e11, width=0.01, thickness=2e-4, density=np.True_)", "density"),
        ("flexure.Flexure(ei=True)", "ei"),
        ("flexure.Flexure(mass_per_length=True)", "mass_per_length"),
        ("flexure.Flexure(modulus=2e11, width=0.01, thickness=2e-4, yield_strength=True)", "yield_strength"),
        ("flexure.Flexure(length=0.01, modulus=7e10, width=0.01, thickness=0.005, notch=(True, 0.001))", "notch"),
        ("f.deflect(fx=True)", "fx"),
        ("f.deflect(moment=False)", "moment"),
        ("f.deflect(fy=1.0, accuracy=(True, 0.01))", "accuracy"),
        ("f.stiffness([0.0] * 3, fy=True)", "fy"),
        ("f.modes(tip_mass=True)", "tip_mass"),
        ("f.pose([True, 0.0, 0.0])", "alpha"),
        ("f.pose(np.array([True, False, True]))", "alpha"),
        ("f.tendon(True, 0.005, 0.005)", "tension"),
        ("f.connect((0.0, True, 0.0))", "pose"),
        ("f.stability_limit(fx=-1.0, max_factor=True)", "max_factor"),
        ("flexure.exact.elastica(fy=True)", "fy"),
        ("flexure.Flexure(kappa=[True, 0.0, 0.0])", "kappa"),
        ("flexure.Flexure(kappa=np.array([False, True, False]))", "kappa"),
        ("flexure.exact.compliance(kappa=(0.0, True))", "kappa"),
    ],
)
def test_booleans_are_refused_naming_the_argument(call, name):
    f = flexure.Flexure(mass_per_length=1.0)
    with pytest.raises(TypeError) as caught:
        eval(call)
    assert "boolean" in str(caught.value)
    assert named(caught.value, name), (str(caught.value), getattr(caught.value, "__notes__", None))


def test_mechanism_arguments_refuse_booleans():
    m = flexure.Mechanism.from_toml(
        '[[joint]]\nname = "pin"\nkind = "revolute"\nparent = "ground"\nchild = "arm"\nstiffness = 2.0\n'
        '[[force]]\nname = "push"\nbody = "arm"\nat = [0.1, 0.0]\n'
    )
    with pytest.raises(TypeError, match="boolean"):
        m.compliance("arm", (True, 0.0))
    with pytest.raises(TypeError, match="boolean"):
        m.sweep("force.push.fx", [0.0, True])
    with pytest.raises(TypeError, match="boolean"):
        m.simulate(True)


# --- a thickness above the length --------------------------------------------------


def test_a_thickness_above_the_length_is_refused_naming_both():
    with pytest.raises(ValueError, match=r"invalid thickness = 0.02 m at t = 0, on a flexure of length 0.01 m"):
        flexure.Flexure(length=0.01, modulus=1e9, width=0.01, thickness=0.02)
    # A taper is thickest at an end: its tip here.
    with pytest.raises(ValueError, match=r"thickness = 0.015 m at t = 1"):
        flexure.Flexure(length=0.01, modulus=1e9, width=0.01, thickness=(0.001, 0.015))
    # Equal to the length is a (stubby) flexure still.
    assert flexure.Flexure(length=0.01, modulus=1e9, width=0.01, thickness=0.01).length == 0.01


def test_a_mechanism_file_refuses_a_thickness_above_the_length():
    text = (
        '[[joint]]\nname = "leg"\nkind = "flexure"\nparent = "ground"\nchild = "tip"\n'
        "length = 0.01\nmodulus = 1e9\nwidth = 0.01\nthickness = 0.02\n"
    )
    with pytest.raises(ValueError, match=r'line \d+, column \d+: joint "leg": thickness = 0.02 m .*length 0.01 m'):
        flexure.Mechanism.from_toml(text)


# --- errors name the parameter and its value ---------------------------------------


@pytest.mark.parametrize(
    "call, match",
    [
        ("flexure.Flexure(length=-1.0)", r"length = -1"),
        ("f.tendon(1.0, 0.005, float('nan'))", r"tip_offset = NaN"),
        ("f.stability_limit(fx=float('inf'))", r"fx = inf"),
        ("f.connect((float('nan'), 1.0, 0.0))", r"invalid pose = \(nan, 1.0, 0.0\)"),
    ],
)
def test_errors_are_value_errors_naming_the_parameter_and_value(call, match):
    f = flexure.Flexure()
    with pytest.raises(ValueError, match=match), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        eval(call)


def test_exact_frequencies_refuses_booleans():
    # As every other call: True is not 1 here either.
    f = flexure.Flexure(mass_per_length=1.0)
    for kwargs in [{"count": True}, {"compression": True}, {"tip_mass": True}, {"tip_com": (True, 0.0)}]:
        name = next(iter(kwargs))
        with pytest.raises(ValueError, match=rf"^{name}(\[0\])? = True: must be a number, not a boolean"):
            flexure.exact.frequencies(**{"count": 2, **kwargs}, flexure=f)


# --- in space as in the plane (issue "robust", item 6) -----------------------------


FINGER3D = (
    "dimension = 3\n[[joint]]\nname = \"mcp\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\n"
    "length = 0.01\nmodulus = 2e11\nwidth = 0.006\nthickness = 3e-4\n"
    "[[body]]\nname = \"tip\"\nmass = 0.002\ncom = [0.01, 0.0, 0.0]\nixx = 1e-8\niyy = 1e-8\nizz = 1e-8\n"
)


@pytest.mark.parametrize(
    "call, name",
    [
        ("flexure.SpatialFlexure(order=True)", "order"),
        ("flexure.Flexure(order=True)", "order"),
        ("m.modes(count=True)", "count"),
        ("m.simulate(0.01, max_steps=True)", "max_steps"),
    ],
)
def test_counts_refuse_booleans_in_space_as_in_the_plane(call, name):
    # True would be read as 1: orders [1, 1, 1], one mode, a budget of one step.
    m = flexure.Mechanism.from_toml(FINGER3D)
    with pytest.raises(TypeError) as caught:
        eval(call)
    assert "boolean" in str(caught.value), str(caught.value)
    assert named(caught.value, name), str(caught.value)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"diameter": 1e-3}, "diameter"),
        ({"width": 0.01}, "width"),
        ({"thickness": 2e-4}, "thickness"),
        ({"poisson": 0.3}, "poisson"),
        ({"shear_modulus": 8e10}, "shear_modulus"),
    ],
)
def test_a_spatial_section_without_a_modulus_is_refused_naming_it(kwargs, name):
    # Ignored before: SpatialFlexure(diameter=1e-3) was the default EI = 1 N·m² rod.
    with pytest.raises(ValueError, match=rf"invalid {name} = given: goes with modulus"):
        flexure.SpatialFlexure(**kwargs)


def test_a_spatial_section_thicker_than_long_is_refused_as_the_planar_one():
    with pytest.raises(ValueError, match=r"invalid thickness = 0.02 m at t = 0, on a flexure of length 0.01 m"):
        flexure.SpatialFlexure(length=0.01, modulus=1e9, width=0.01, thickness=0.02)
    with pytest.raises(ValueError, match=r"invalid diameter = 0.02 m at t = 0"):
        flexure.SpatialFlexure(length=0.01, modulus=1e9, diameter=0.02)


@pytest.mark.parametrize(
    "value, what",
    [
        (np.array([0.0, 0.0, 1.0 + 2.0j]), "complex"),
        (np.array([0.0, 0.0, 1.0], dtype=object), "object"),
        (memoryview(np.array([0.0, 0.0, 1.0])), "memoryview"),
    ],
)
def test_complex_object_and_memoryview_arrays_are_refused_not_cast(value, what):
    # NumPy would drop the imaginary part, convert each object, or reinterpret the buffer.
    for call in [lambda: flexure.SpatialFlexure().deflect(force=value), lambda: flexure.Flexure().pose(value)]:
        with pytest.raises(TypeError, match=what):
            call()
