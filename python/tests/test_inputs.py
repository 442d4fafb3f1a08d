"""Bad input: a ValueError naming the Python parameter, never a panic, an
OverflowError, a crash of the interpreter, or an option silently ignored.

Each case is code run against `flexure`, `np` and a default flexure `f`
(order 3), with a pattern its message must match.
"""

import subprocess
import sys

import numpy as np
import pytest

import flexure

CASES = [
    # Counts: any Python or NumPy integer, however large or negative (the library's bounds: order <= 64, quadrature <= 1024).
    ("flexure.Flexure(order=2**40)", r"order = 1099511627776: must be from 1 to 64"),
    ("flexure.Flexure(order=2**64)", r"order = 18446744073709551616: must be from 1 to 64"),
    ("flexure.Flexure(order=2**200)", r"order = \d+: must be from 1 to 64"),
    ("flexure.Flexure(order=-1)", r"order = -1: must be from 1 to 64"),
    ("flexure.Flexure(order=np.int64(-5))", r"order = -5: must be from 1 to 64"),
    ("flexure.Flexure(order=0)", r"order = 0"),
    ("flexure.Flexure(order=65)", r"order = 65"),
    ("flexure.Flexure(quadrature=2**70)", r"quadrature = \d+: must be from 1 to 1024"),
    ("flexure.Flexure(quadrature=-3)", r"quadrature = -3: must be from 1 to 1024"),
    ("flexure.Flexure(quadrature=0)", r"quadrature = 0"),
    ("flexure.Flexure(quadrature=1025)", r"quadrature = 1025"),
    # Options that would be ignored, or that contradict each other.
    ("flexure.Flexure(poisson=0.3)", r"poisson given without modulus"),
    ("flexure.Flexure(width=0.01)", r"width given without modulus"),
    ("flexure.Flexure(thickness=0.0002)", r"thickness given without modulus"),
    ("flexure.Flexure(ei=2.0, width=0.01, thickness=0.0002, poisson=0.3)", r"width, thickness, poisson given without modulus"),
    ("flexure.Flexure(ei=1.0, modulus=2e11, width=0.01, thickness=0.0002)", r"ei and modulus were both given"),
    ("flexure.Flexure(modulus=2e11, width=0.01)", r"modulus needs width and thickness: thickness missing"),
    ("flexure.Flexure(modulus=2e11)", r"modulus needs width and thickness: width and thickness missing"),
    ("flexure.Flexure(modulus=2e11, width=0.01, thickness=0.0002, poisson=0.7)", r"poisson = 0.7"),
    # Coordinates of the wrong length or shape, or not finite: named as in Python, with expected and got.
    ("flexure.Flexure(kappa=[1.0, 2.0])", r"kappa must have 3 entries .*got 2"),
    ("flexure.Flexure(order=2, kappa=[1.0, 2.0, 3.0])", r"kappa must have 2 entries .*got 3"),
    ("flexure.Flexure(kappa=[[1.0, 2.0, 3.0]])", r"kappa must be one-dimensional"),
    ("flexure.Flexure(kappa=[1.0, float('nan'), 0.0])", r"kappa contains NaN"),
    ("f.energy([1.0, 2.0, 3.0, 99.0])", r"alpha must have 3 entries .*got 4"),
    ("f.energy([1.0, 2.0])", r"alpha must have 3 entries .*got 2"),
    ("f.pose([1.0, 2.0])", r"alpha must have 3 entries .*got 2"),
    ("f.pose(np.zeros((5, 4)))", r"alpha must have 3 entries .*got 4"),
    ("f.pose(np.zeros((2, 2, 3)))", r"alpha must have shape \(3,\) or \(n, 3\)"),
    ("f.pose(1.0)", r"alpha must have shape"),
    ("f.pose(np.array([1.0, np.nan, 0.0]))", r"alpha contains NaN"),
    ("f.pose(np.zeros(4))", r"alpha must have 3 entries .*got 4"),
    ("f.pose(np.array([[0.0, 0.0, 0.0], [0.0, np.inf, 0.0]]))", r"alpha contains inf"),
    ("f.jacobian([0.0] * 4)", r"alpha must have 3 entries .*got 4"),
    ("f.jacobian([[0.0, 0.0, 0.0]])", r"alpha must have shape \(3,\) here"),
    ("f.hessians([0.0] * 2)", r"alpha must have 3 entries .*got 2"),
    ("f.transform([0.0] * 5)", r"alpha must have 3 entries .*got 5"),
    ("f.stiffness([0.0] * 4)", r"alpha must have 3 entries .*got 4"),
    ("f.compliance([0.0] * 2, fx=1.0)", r"alpha must have 3 entries .*got 2"),
    ("f.compliance([0.0, float('inf'), 0.0])", r"alpha contains inf"),
    ("flexure.exact.deflect(fy=1.0, kappa=[])", r"kappa must have from 1 to 64 entries .*got 0"),
    ("flexure.exact.deflect(fy=1.0, kappa=np.zeros(65))", r"kappa must have from 1 to 64 entries .*got 65"),
    ("flexure.exact.compliance(kappa=[[1.0]])", r"kappa must be one-dimensional"),
    ("flexure.exact.compliance(kappa=[float('inf')])", r"kappa contains inf"),
    # Loads and other values.
    ("f.deflect(fx=float('inf'))", r"fx = inf"),
    ("f.compliance([0.0] * 3, moment=float('nan'))", r"moment = NaN"),
    ("f.stiffness([0.0] * 3, fy=float('-inf'))", r"fy = -inf"),
    ("flexure.exact.deflect(moment=float('nan'))", r"moment = NaN"),
    ("flexure.exact.deflect(fy=1.0, length=-1.0)", r"length = -1"),
    ("flexure.exact.compliance(ei=0.0)", r"ei = 0"),
    ("flexure.Flexure(length=float('inf'))", r"length = inf"),
    ("f.buckling_load('sideways')", r"tip"),
    # Accuracy targets and the order of an answer (test_accuracy.py has the full table).
    ("f.deflect(fy=1.0, accuracy=(0.0, 0.01))", r"accuracy = \(0, 0\.01\): its position fraction of L is 0"),
    ("f.deflect(fy=1.0, accuracy=(0.01, float('nan')), order='auto')", r"accuracy .*angle \(rad\) is NaN"),
    ("f.deflect(fy=1.0, accuracy=0.01)", r"accuracy must be a pair"),
    ("f.deflect(fy=1.0, order=5)", r'order must be None or "auto", got 5'),
    ("f.error_estimate([0.0] * 4)", r"alpha must have 3 entries .*got 4"),
    ("f.error_estimate([0.0] * 3, fx=float('nan'))", r"fx = NaN"),
    ("f.error_estimate([0.0] * 3, accuracy=(-1.0, 0.01))", r"accuracy .*position fraction of L is -1"),
    # An unstable state has no compliance: said, not a NaN matrix.
    ("f.compliance([0.0] * 3, fx=-3.0)", r"not positive definite"),
    # A mechanism file with a count out of range.
    ("flexure.Mechanism.from_toml(\"[[joint]]\\nname='a'\\nkind='flexure'\\nparent='ground'\\nchild='b'\\nlength=0.01\\nei=1.0\\norder=-1\\n\")", r"line 8"),
    ("flexure.Mechanism.from_toml(\"[[joint]]\\nname='a'\\nkind='flexure'\\nparent='ground'\\nchild='b'\\nlength=0.01\\nei=1.0\\norder=99999999999\\n\")", r"order = 99999999999"),
]


def run(code):
    return eval(code, {"flexure": flexure, "np": np, "f": flexure.Flexure()})


@pytest.mark.parametrize("code, message", CASES)
def test_bad_input_raises_value_error_naming_it(code, message):
    with pytest.raises(ValueError, match=message):
        run(code)


def test_no_bad_input_panics_or_kills_the_interpreter():
    # In a child interpreter, so that an abort fails this test rather than the run.
    # A Rust panic surfaces as pyo3's PanicException, a BaseException that
    # `except Exception` does not catch: the child then exits non-zero.
    child = (
        "import sys, flexure, numpy as np\n"
        f"cases = {[code for code, _ in CASES]!r}\n"
        "for code in cases:\n"
        "    try:\n"
        "        eval(code, {'flexure': flexure, 'np': np, 'f': flexure.Flexure()})\n"
        "        print('accepted', code)\n"
        "    except Exception as e:\n"
        "        print(type(e).__name__, code)\n"
    )
    done = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    kinds = [line.split(" ", 1)[0] for line in done.stdout.splitlines()]
    assert kinds == ["ValueError"] * len(CASES), done.stdout


def test_non_integer_counts_are_type_errors_naming_the_argument():
    # Not a number of points at all: a TypeError, as Python gives for range(3.0), naming the argument.
    with pytest.raises(TypeError, match="argument 'order'"):
        flexure.Flexure(order=3.0)
    with pytest.raises(TypeError, match="argument 'quadrature'"):
        flexure.Flexure(quadrature="5")


def test_bounds_are_reachable():
    # The largest order and rule the library allows work end to end.
    f = flexure.Flexure(order=np.int64(64), quadrature=1024)
    assert f.order == 64 and f.quadrature == 1024
    alpha = f.deflect(moment=1.0)
    # A pure moment: the arc of angle ML/EI = 1 (rounding over 1024 points: 1e-9).
    assert abs(f.pose(alpha)[1] - np.sin(1.0)) < 1e-9


def test_section_options_with_modulus_are_used():
    # Eq. 25 with and without the plate factor 1/(1 - nu^2): both options act.
    plain = flexure.Flexure(modulus=200e9, width=0.01, thickness=0.0002)
    plate = flexure.Flexure(modulus=200e9, width=0.01, thickness=0.0002, poisson=0.29)
    assert abs(plain.ei - 200e9 * 0.01 * 0.0002**3 / 12) < 1e-15
    assert abs(plate.ei / plain.ei - 1 / (1 - 0.29**2)) < 1e-12
