"""Exact Euler-Bernoulli references, to measure the model's error.

Each function solves beam theory itself rather than the Smooth Curvature Model:
the elastica (Eq. 3) by multiple shooting with load continuation, the tip
compliance by its ODE (Eq. 34), and the buckling load of a straight column.
Give the beam either as `flexure=` a `flexure.Flexure`, whose length, section
(EI(s) from `ei`, or `modulus`, `width`, `thickness` and `notch`), rest curvature
and `yield_strength` are used (its order and quadrature are not: the references
are exact), or as `length`, `ei` (a number, a pair (root, tip) or a table of
[t, value] rows, as `Flexure`'s) and `kappa` (1 to 64 rest curvature coefficients
in the model's basis; `rest`, its deprecated name, warns DeprecationWarning), by
default a straight flexure of length 1 and EI 1. Not both: `length`, `ei` or
`kappa` beside `flexure` raises ValueError.

`elastica` returns an `Elastica`: the tip pose, root moment and stability, and
the exact `stress()`, `peak_curvature()`, `safety_factor()` and `shape(k)`, the
counterparts of the model's `Flexure.stress(alpha)` and the rest.
An unstable shape warns StabilityWarning (Jacobi test); a peak stress beyond
the flexure's yield strength warns YieldWarning.

>>> import flexure
>>> from flexure import exact
>>> f = flexure.Flexure(length=0.05, modulus=200e9, width=0.01, thickness=(6e-4, 2e-4))
>>> e = exact.elastica(fy=2.0, flexure=f)   # a tapered steel strip, 2 N across its tip
>>> round(float(e.pose[2]) * 1e3, 2)        # tip deflection, mm
4.84
>>> round(e.stress()["max"] / 1e6)          # peak bending stress, MPa (beam theory, 6F(L-s)/(b h(s)^2): 187.5)
185
>>> round(e.stress()["at"] * 1e3, 1)        # where, mm from the root (beam theory: 25)
24.6
"""

from typing import Optional, Tuple, Union

import numpy as np
from numpy.typing import ArrayLike

from ._flexure import (
    Elastica,
    Flexure,
    SpatialFlexure,
    exact_buckling_load,
    exact_compliance,
    exact_elastica,
    exact_flexure,
    exact_frequencies,
)

__all__ = ["elastica", "deflect", "compliance", "buckling_load", "frequencies", "rod", "Elastica"]

_Profile = Union[float, Tuple[float, float], ArrayLike]


def _beam(flexure: Optional[Flexure], length: Optional[float], ei: Optional[_Profile],
          kappa: Optional[ArrayLike], rest: Optional[ArrayLike] = None) -> Flexure:
    """The flexure to solve: `flexure`, or one built from `length`, `ei` and `kappa` (or
    `rest`, its deprecated name, warned about at the line that called `flexure.exact`)."""
    if flexure is None:
        return exact_flexure(1.0 if length is None else length, ei, kappa, rest, stacklevel=3)
    if not isinstance(flexure, Flexure):
        raise ValueError(f"flexure must be a flexure.Flexure, got {type(flexure).__name__}")
    given = [
        name
        for name, value in (("length", length), ("ei", ei), ("kappa", kappa), ("rest", rest))
        if value is not None
    ]
    if given:
        raise ValueError(
            f"{' and '.join(given)} given with flexure would be ignored: the exact references use the "
            f"flexure's own length, section and rest curvature; leave {' and '.join(given)} out"
        )
    return flexure


def elastica(moment: float = 0.0, fx: float = 0.0, fy: float = 0.0, length: Optional[float] = None,
             ei: Optional[_Profile] = None, kappa: Optional[ArrayLike] = None, *,
             flexure: Optional[Flexure] = None, rest: Optional[ArrayLike] = None) -> Elastica:
    """The exact elastica under a tip moment (N*m) and force (N) in the root frame, with EI(s):
    an `Elastica` (pose, root_moment, stable, limit_fraction; stress(), peak_curvature(), safety_factor(),
    shape(k)). Warns StabilityWarning if the shape is unstable (Jacobi test), and YieldWarning if
    the flexure has a yield_strength that its peak stress exceeds. Raises ConvergenceError if the
    load continuation stalls, ValueError for a force beyond what shooting can follow
    (integral of sqrt(|F|/EI(s)) ds above 100). Runs without the GIL; Ctrl-C stops it."""
    f = _beam(flexure, length, ei, kappa, rest)
    return exact_elastica(f, moment, fx, fy, what="exact.elastica")


def deflect(moment: float = 0.0, fx: float = 0.0, fy: float = 0.0, length: Optional[float] = None,
            ei: Optional[_Profile] = None, kappa: Optional[ArrayLike] = None, *,
            flexure: Optional[Flexure] = None, rest: Optional[ArrayLike] = None) -> np.ndarray:
    """Tip pose [phi, x, y] of the exact elastica (Eq. 3) under a tip moment and force:
    `elastica(...).pose`, with the same warnings. `kappa`: 1 to 64 rest curvature coefficients
    in the model's basis (straight by default; `rest` is its deprecated name)."""
    f = _beam(flexure, length, ei, kappa, rest)
    return exact_elastica(f, moment, fx, fy, what="exact.deflect").pose


def compliance(length: Optional[float] = None, ei: Optional[_Profile] = None, kappa: Optional[ArrayLike] = None, *,
               flexure: Optional[Flexure] = None, rest: Optional[ArrayLike] = None) -> np.ndarray:
    """Exact small-load tip compliance (3, 3), order (phi, x, y), from the compliance ODE
    (Eq. 34) with EI(s), integrated to 1e-12 relative."""
    return exact_compliance(_beam(flexure, length, ei, kappa, rest))


def buckling_load(tip: str = "free", length: Optional[float] = None, ei: Optional[_Profile] = None, *,
                  flexure: Optional[Flexure] = None) -> float:
    """Exact critical compressive tip load (N) of a straight column clamped at its root, its tip
    "free", "guided", "pinned" or "clamped": Euler's closed form for a uniform section, else
    the first root of the column's shooting determinant in the load, found by scan and bisection.
    ValueError for a flexure with rest curvature."""
    return exact_buckling_load(_beam(flexure, length, ei, None), tip)


def frequencies(count: Optional[int] = None, compression: float = 0.0, *, flexure: Flexure,
                tip_mass: Optional[float] = None, tip_inertia: Optional[float] = None,
                tip_com: Optional[Tuple[float, float]] = None) -> dict:
    """Exact natural frequencies of `flexure` as a straight Euler-Bernoulli beam with rotary
    inertia, clamped at its root: EI(s) and the mass per length mu(s) of its section (its
    `density` or `mass_per_length`; none for a massless flexure), carrying an optional rigid tip
    body (tip_mass kg, tip_inertia kg*m^2 about its centre of mass, tip_com (x, y) m in the tip
    frame), under an axial `compression` (N; negative for tension): the frequencies below a
    trial one counted by the Wittrick-Williams argument on the beam cut into short exact
    elements, so none is skipped, each refined to 1e-12 relative in beta_l. The counterpart
    of `Flexure.modes` about a straight equilibrium (fx = -compression). A dict of omega
    (rad/s, ascending), frequency (Hz), beta_l (the scaled frequency: beta L for a uniform
    beam) and mass_per_length (its reference, kg/m). count: 1 to 64 (default 3); a massless
    flexure has at most as many modes as its body has inertial degrees of freedom.
    ValueError naming mass without any mass, for a flexure with rest curvature, and naming
    compression (and the buckling load) for a compression at or past the column's buckling
    load. Runs without the GIL; Ctrl-C raises KeyboardInterrupt saying how many modes were
    found.

    >>> import flexure
    >>> from flexure import exact
    >>> f = flexure.Flexure(length=1.0, ei=1.0, mass_per_length=1.0)
    >>> [round(float(b), 4) for b in exact.frequencies(2, flexure=f)["beta_l"]]   # cos bL cosh bL = -1
    [1.8751, 4.6941]
    """
    if not isinstance(flexure, Flexure):
        raise ValueError(f"flexure must be a flexure.Flexure, got {type(flexure).__name__}")
    # Booleans are not numbers, here as everywhere in the package.
    given = {"count": count, "compression": compression, "tip_mass": tip_mass, "tip_inertia": tip_inertia}
    given.update({f"tip_com[{i}]": c for i, c in enumerate(tip_com or ())})
    for name, value in given.items():
        if isinstance(value, bool):
            raise ValueError(f"{name} = {value}: must be a number, not a boolean")
    return exact_frequencies(flexure, count, compression, tip_mass, tip_inertia, tip_com)


def rod(flexure: SpatialFlexure, force: Optional[ArrayLike] = None, moment: Optional[ArrayLike] = None) -> dict:
    """The exact Kirchhoff rod (inextensible, unshearable) of a `flexure.SpatialFlexure`'s length,
    section and rest shape, clamped at its root, under a dead tip force (fx, fy, fz) and moment
    (mx, my, mz) in the root frame, followed from rest by multiple shooting: a dict of pose (the
    tip's 4 x 4 transform), root_moment, stable (no conjugate point on the way), stability_test
    ("energy" without a moment, "static" with one, as `SpatialFlexure.deflect`'s) and limit_fraction
    where the path lost stability, if it did. The reference `SpatialFlexure.deflect` is measured
    against; the planar elastica is its special case.

    >>> import flexure
    >>> from flexure import exact
    >>> f = flexure.SpatialFlexure(length=0.8, gj=0.25)
    >>> round(float(exact.rod(f, moment=(0.1, 0.0, 0.0))["pose"][2, 1]), 6)   # sin(TL/GJ) = sin 0.32
    0.314567
    """
    if not isinstance(flexure, SpatialFlexure):
        raise ValueError(f"flexure must be a flexure.SpatialFlexure, got {type(flexure).__name__}")
    return flexure.exact_rod(force, moment)

