"""Ctrl-C stops a long call: KeyboardInterrupt, saying how far the call got.

The interrupt comes from `_thread.interrupt_main`, which simulates SIGINT
arriving at the main thread, fired by a timer 0.2 s into a call that runs
for seconds otherwise (measured uninterrupted on the development machine:
deflect 1.3 to 1.8 s, the batch about 2 s). The call releases the GIL, so
the timer thread runs, and the solver polls Python's signal handlers at
least every 10 ms of work. The messages checked below come only from the
bindings' interrupt path, so a KeyboardInterrupt raised anywhere else
(before or after the call) fails the tests.
"""

import _thread
import signal
import threading
import time

import numpy as np
import pytest

import flexure

DELAY = 0.2
# Much longer than the delay plus one poll, much shorter than the uninterrupted calls:
# generous, since the 2-core machine may be busy with other work.
BOUND = 1.5


@pytest.fixture(autouse=True)
def python_handles_sigint():
    # A process started with SIGINT ignored (as a shell does for background jobs, and as
    # some CI runners do) has no Python handler, and interrupt_main then does nothing:
    # give these tests Python's default handler, as an interactive session has.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def interrupted_after(call, delay=DELAY):
    """Runs `call` with SIGINT simulated `delay` s in; the exception it raised and the seconds it took."""
    timer = threading.Timer(delay, _thread.interrupt_main)
    outcome, seconds = None, None
    start = time.monotonic()
    timer.start()
    try:
        try:
            call()
        except BaseException as e:  # KeyboardInterrupt is what is tested
            outcome, seconds = e, time.monotonic() - start
        # An interrupt the call did not honour lands here, not in the next test.
        timer.join()
        time.sleep(0.05)
    except BaseException:
        pass
    if outcome is None:
        pytest.fail(f"the call was not interrupted: it ended after {time.monotonic() - start:.2f} s")
    return outcome, seconds


def long_deflect():
    # A moment that would coil the order-64 flexure 1600 turns: continuation runs its
    # 1000 steps at 1 to 2 ms each before reporting that it stalled.
    f = flexure.Flexure(order=64, quadrature=1024)
    return lambda: f.deflect(moment=1e4)


def test_ctrl_c_stops_deflect():
    call = long_deflect()
    error, seconds = interrupted_after(call)
    assert isinstance(error, KeyboardInterrupt)
    assert "interrupted at" in str(error) and "% of the load" in str(error), str(error)
    assert seconds < BOUND
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
        error, seconds = interrupted_after(call)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert isinstance(error, Stop) and seconds < BOUND


def test_ctrl_c_stops_a_batch():
    # 60 000 poses at order 64 with 1024 points: about 2 s of kernel work, polled between chunks.
    f = flexure.Flexure(order=64, quadrature=1024)
    alphas = np.random.default_rng(5).uniform(-1.0, 1.0, (60_000, 64))
    error, seconds = interrupted_after(lambda: f.pose(alphas))
    assert isinstance(error, KeyboardInterrupt)
    assert "pose: interrupted after" in str(error) and "of 60000 rows" in str(error), str(error)
    assert seconds < BOUND
