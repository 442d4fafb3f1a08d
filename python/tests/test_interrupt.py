"""Ctrl-C stops a long call: KeyboardInterrupt, saying how far the call got.

The interrupt is Ctrl-C simulated (`_thread.interrupt_main`: SIGINT arriving
at the main thread, its Python handler run) from inside the call, at a
given solver poll (`flexure._flexure._ctrl_c_at_poll`, a hook for these
tests): the solvers poll at every Newton iteration, continuation step,
integrator step, batch chunk and element, and the bindings run Python's
signal handlers there. The trigger is counted in the call's own iterations,
never in seconds, so no machine, fast or loaded, finishes the call before
it fires. The messages checked below come only from the bindings' interrupt
path, so a KeyboardInterrupt raised anywhere else (before or after the call)
fails the tests. What is asserted is the work the call had not yet done when
it stopped (the load fraction, the rows, the modes, the time).
"""

import re
import signal

import numpy as np
import pytest

import flexure
from flexure import _flexure


@pytest.fixture(autouse=True)
def python_handles_sigint():
    # A process started with SIGINT ignored (as a shell does for background jobs, and as
    # some CI runners do) has no Python handler, and interrupt_main then does nothing:
    # give these tests Python's default handler, as an interactive session has.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def interrupted_at(call, poll):
    """Runs `call` with Ctrl-C simulated at its `poll`-th solver poll; the exception it raised."""
    _flexure._ctrl_c_at_poll(poll)
    try:
        call()
    except BaseException as e:  # KeyboardInterrupt is what is tested
        return e
    finally:
        # A trigger the call never reached does not fire in the next test.
        _flexure._ctrl_c_at_poll(0)
    pytest.fail(f"the call ran to its end before its solver poll {poll}")


def load_fraction(error):
    """The percentage of the load an interrupted solve had reached, from its message."""
    found = re.search(r"interrupted at ([0-9.]+) % of the load", str(error))
    assert found, str(error)
    return float(found.group(1))


def long_deflect():
    # A moment that would coil the order-64 flexure 1600 turns: continuation runs its
    # 1000 steps (each a poll, and its Newton iterations more) before reporting that it stalled.
    f = flexure.Flexure(order=64, quadrature=1024)
    return lambda: f.deflect(moment=1e4)


def test_ctrl_c_stops_deflect():
    call = long_deflect()
    error = interrupted_at(call, 50)
    assert isinstance(error, KeyboardInterrupt)
    # Stopped on the way: uninterrupted, the call stalls at 14 % of this load after its 1000 steps.
    assert load_fraction(error) < 14.0, str(error)
    # The flexure is usable afterwards, and a call without Ctrl-C is not stopped.
    assert np.allclose(flexure.Flexure().deflect(moment=1.0), [1.0, 0.0, 0.0])


def test_another_handlers_exception_propagates():
    # A SIGINT handler of the program's own: its exception, not KeyboardInterrupt, leaves the call.
    class Stop(Exception):
        pass

    def handler(signum, frame):
        raise Stop("from the handler")

    call = long_deflect()
    previous = signal.signal(signal.SIGINT, handler)
    try:
        error = interrupted_at(call, 50)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert isinstance(error, Stop)


def test_ctrl_c_stops_a_batch():
    # 60 000 poses at order 64 with 1024 points, polled before each chunk of rows: stopped at
    # the second poll, after the first chunk.
    f = flexure.Flexure(order=64, quadrature=1024)
    alphas = np.random.default_rng(5).uniform(-1.0, 1.0, (60_000, 64))
    error = interrupted_at(lambda: f.pose(alphas), 2)
    assert isinstance(error, KeyboardInterrupt)
    found = re.search(r"pose: interrupted after ([0-9]+) of 60000 rows", str(error))
    assert found and 0 < int(found.group(1)) < 60000, str(error)


def test_ctrl_c_stops_exact_frequencies():
    # 64 modes of a flexure whose EI is a table of 2000 rows: every row is an element boundary,
    # so each trial frequency integrates at least 2000 elements, polling at each. Stopped a
    # few trial frequencies in, it says how many of the 64 modes it had found.
    t = np.linspace(0.0, 1.0, 2000)
    f = flexure.Flexure(ei=np.column_stack([t, 1.0 + 0.5 * np.sin(7.0 * t)]), mass_per_length=1.0)
    error = interrupted_at(lambda: flexure.exact.frequencies(64, flexure=f), 10_000)
    assert isinstance(error, KeyboardInterrupt)
    found = re.search(r"exact\.frequencies: interrupted after ([0-9]+) of 64 modes", str(error))
    assert found and int(found.group(1)) < 64, str(error)
    # A call without Ctrl-C is not stopped.
    assert len(flexure.exact.frequencies(2, flexure=flexure.Flexure(mass_per_length=1.0))["omega"]) == 2


def test_ctrl_c_stops_a_simulation():
    # The tendon finger in motion for 20 s at the default tolerance: about 20 000 steps, each
    # polled (its 1 s run takes about 1 000 steps). Stopped, it says the time it had reached,
    # not a fraction of a load.
    from pathlib import Path

    m = flexure.Mechanism.from_file(Path(__file__).resolve().parents[2] / "examples" / "finger_dynamics.toml")
    error = interrupted_at(lambda: m.simulate(20.0, every=0.01), 200)
    assert isinstance(error, KeyboardInterrupt)
    found = re.search(r"interrupted at t = ([0-9.e+-]+) s of 2\.000000e1 s", str(error))
    assert found and float(found.group(1)) < 20.0, str(error)


def test_ctrl_c_stops_an_exact_rod():
    # A twist of 100 N·m on the default rod (260 rad): its exact rod runs some ten
    # seconds to its bound of integration pieces; Ctrl-C at its 50th solver poll stops it on the way.
    f = flexure.SpatialFlexure()
    error = interrupted_at(lambda: f.exact_rod(moment=(100.0, 0.0, 0.0)), 50)
    assert isinstance(error, KeyboardInterrupt)
    assert load_fraction(error) < 100.0, str(error)


def test_an_exact_rod_past_its_bound_stops_naming_it():
    # A moment of 1e6 N·m about z would need 16 million pieces a sweep: refused at once, naming the bound.
    f = flexure.SpatialFlexure()
    with pytest.raises(flexure.ConvergenceError, match="its limit of 1000000 integration pieces was reached"):
        f.exact_rod(moment=(0.0, 0.0, 1e6))
