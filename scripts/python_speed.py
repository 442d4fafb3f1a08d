#!/usr/bin/env python3
"""Times the Python bindings against their targets and prints the ratios.

Run it with the package installed (README, section Python):

    python scripts/python_speed.py

It reports and does not judge: the exit status is 0 whether or not a target is
met, since a shared machine makes one run's figure noisy (run it a few times).
Each figure is the best of several `timeit` repeats, the least disturbed one,
of a call made through a Python function (a lambda), as user code makes it;
that is how the issue's figures (pose 10-12 x a property read) were taken.
The last line gives the pose ratio also for bare statements, where the
property read costs less and the ratio is larger.

Targets (issue "Speed where users feel it"):
- `f.pose(alpha)` with a float64 vector at most 6 x a property read (`f.length`);
- per pose, a batch of 10^6 rows at most 1.5 x a batch of 10^4 rows;
- `f.deflect` at the paper's 90° load (with its error estimate) at most 4 x the library's
  deflect plus its estimate, criterion's `statics/deflect_90_estimated` (printed here in µs
  for that comparison; this script cannot run criterion);
- `SpatialFlexure.deflect` at orders 4 (with its error estimate) at most 3 x the library's
  call of it, criterion's `spatial/deflect_with_estimate_order_4`, on the same load.
"""

import math
import os
import timeit

import numpy as np

import flexure

REPEATS = 15
POSE_TARGET = 6.0
BATCH_TARGET = 1.5
FORCE_45 = 3.8477 * math.sin(math.radians(45.0))


def cos_loop(f, alpha):
    """The tip pose of order 3 by the same 5-point Gauss rule, in pure Python: a scale for the binding's cost."""
    nodes = (-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640)
    weights = (0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665, 0.2369268850561891)
    a0, a1, a2 = alpha
    x = y = 0.0
    for t, w in zip(nodes, weights):
        s = 0.5 * (t + 1.0)
        # Any fixed polynomial angle serves as a scale; its cost, not its value, is what counts here.
        phi = a0 * s + a1 * s * s + a2 * s * s * s
        x += w * math.cos(phi)
        y += w * math.sin(phi)
    return (a0 + a1 + a2, 0.5 * f.length * x, 0.5 * f.length * y)


def best_of(cases):
    """Seconds per call of each case (name: (statement, calls, names)), the best of REPEATS.

    The repeats are interleaved, every case once per round, so that the load
    of a shared machine falls alike on the figures a ratio divides."""
    times = {name: [] for name in cases}
    for _ in range(REPEATS):
        for name, (statement, calls, names) in cases.items():
            times[name].append(timeit.timeit(statement, number=calls, globals=names) / calls)
    return {name: min(t) for name, t in times.items()}


def main():
    f = flexure.Flexure()
    rng = np.random.default_rng(1)
    vector = np.array([0.3, -0.2, 0.1])
    as_list = [0.3, -0.2, 0.1]
    small = rng.uniform(-1.0, 1.0, (10_000, 3))
    large = rng.uniform(-1.0, 1.0, (1_000_000, 3))
    names = {"f": f, "vector": vector}
    # As criterion's spatial/deflect_with_estimate_order_4: L = 1, EI_z = EI_y = GJ = 1.
    spatial = flexure.SpatialFlexure(1.0, ei=1.0, order=4, ei_y=1.0, gj=1.0)
    force, moment = [0.1, 0.2, 0.3], [0.2, 0.1, 0.3]

    t = best_of(
        {
            "read": (lambda: f.length, 50_000, None),
            "pose": (lambda: f.pose(vector), 20_000, None),
            "pose_list": (lambda: f.pose(as_list), 20_000, None),
            "loop": (lambda: cos_loop(f, as_list), 5_000, None),
            "bare_read": ("f.length", 50_000, names),
            "bare_pose": ("f.pose(vector)", 20_000, names),
            "small": (lambda: f.pose(small), 20, None),
            "large": (lambda: f.pose(large), 1, None),
            # The paper's 90° load, TipLoad::polar(0, 3.8477, 45°) as in statics/deflect_90.
            "deflect": (lambda: f.deflect(fx=-FORCE_45, fy=FORCE_45), 5_000, None),
            "spatial": (lambda: spatial.deflect(force=force, moment=moment), 40, None),
        }
    )
    per_small, per_large = t["small"] / small.shape[0], t["large"] / large.shape[0]

    print(f"flexure on {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}; best of {REPEATS} interleaved repeats")
    print(f"  property read f.length          {t['read'] * 1e9:8.1f} ns")
    print(f"  f.pose(alpha), float64 vector   {t['pose'] * 1e9:8.1f} ns")
    print(f"  f.pose(alpha), list             {t['pose_list'] * 1e9:8.1f} ns")
    print(f"  pure-Python math.cos pose loop  {t['loop'] * 1e9:8.1f} ns")
    print(f"  batch of 10^4 rows, per pose    {per_small * 1e9:8.2f} ns")
    print(f"  batch of 10^6 rows, per pose    {per_large * 1e9:8.2f} ns")
    print(f"  f.deflect at the 90° load       {t['deflect'] * 1e6:8.2f} µs (with its estimate)")
    print(f"  SpatialFlexure.deflect, order 4 {t['spatial'] * 1e6:8.2f} µs (with its estimate)")
    for name, ratio, target in [
        ("f.pose(vector) / property read", t["pose"] / t["read"], POSE_TARGET),
        ("per pose, 10^6 rows / 10^4 rows", per_large / per_small, BATCH_TARGET),
    ]:
        verdict = "meets" if ratio <= target else "misses"
        print(f"  {name:34s} {ratio:6.2f} x (target <= {target} x: {verdict})")
    print(f"  (f.pose(list) / property read {t['pose_list'] / t['read']:.2f} x; math.cos loop / f.pose(vector) {t['loop'] / t['pose']:.2f} x;")
    print(f"   as bare statements, without the lambda: f.pose(vector) / property read {t['bare_pose'] / t['bare_read']:.2f} x)")


if __name__ == "__main__":
    main()
