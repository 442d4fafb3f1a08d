"""Flexure joints with the Smooth Curvature Model, beside exact beam theory.

Conventions (the same as the Rust crate): SI units, angles in radians.
The root frame's x axis runs along the unbent flexure; poses, Jacobian
rows and compliance rows/columns are ordered (phi, x, y); tip loads are a
moment M (counter-clockwise) and a force (Fx, Fy) in the root frame.
Bad input raises ValueError naming the parameter. Every model answer
carries its error, estimated against a refined model (`Flexure.error_estimate`,
the `estimates` of `Mechanism.solve`); one that misses its accuracy target
(by default 1 % of L and 1 degree) warns AccuracyWarning, and
`Flexure.deflect(..., order="auto")` raises the order until it is met.
Solves and batches run without the GIL; Ctrl-C stops `Flexure.deflect`
and a batch `Flexure.pose` with KeyboardInterrupt (the exact and mechanism
solvers poll for it once they run on the library's interruptible solver core).

>>> import flexure
>>> f = flexure.Flexure(length=1.0, ei=1.0)
>>> alpha = f.deflect(fy=1.0)          # Bisshopp-Drucker load, PL^2/EI = 1
>>> round(float(f.pose(alpha)[1]), 2)  # tip x; the exact elastica gives 0.94357
0.94
"""

from os import PathLike, fspath
from pathlib import Path
from typing import Optional, Tuple, Union

from . import exact
from ._flexure import AccuracyWarning, ConvergenceError, Flexure, StabilityWarning
from ._flexure import Mechanism as _Mechanism

__all__ = ["Flexure", "Mechanism", "ConvergenceError", "StabilityWarning", "AccuracyWarning", "exact"]


class Mechanism:
    """A flexure-jointed mechanism described in TOML (see the README's Mechanisms section)."""

    def __init__(self, inner: _Mechanism):
        self._inner = inner

    @classmethod
    def from_toml(cls, text_or_path: Union[str, "PathLike[str]"]) -> "Mechanism":
        """Parses TOML text, or reads it from a path (a `Path`, or a string naming an existing file)."""
        if isinstance(text_or_path, PathLike) or (
            isinstance(text_or_path, str) and "\n" not in text_or_path and Path(text_or_path).is_file()
        ):
            text = Path(fspath(text_or_path)).read_text()
        elif isinstance(text_or_path, str):
            text = text_or_path
        else:
            raise ValueError(f"text_or_path must be TOML text or a path, got {type(text_or_path).__name__}")
        return cls(_Mechanism.from_text(text))

    @property
    def dof(self) -> int:
        """Number of generalized coordinates."""
        return self._inner.dof

    def solve(self, accuracy: Optional[Tuple[float, float]] = None) -> dict:
        """Static equilibrium: a dict shaped like `flexure solve --json`
        (bodies {name: {x, y, phi}}, coordinates {joint: array}, energy, stable), and
        estimates {flexure joint: dict as `Flexure.error_estimate` returns, or None}.
        A flexure joint whose estimated error misses `accuracy` (position as a fraction
        of its length, angle in rad; default (0.01, 1 degree)) warns AccuracyWarning
        naming it, as does one whose error could not be estimated."""
        return self._inner.solve(accuracy)
