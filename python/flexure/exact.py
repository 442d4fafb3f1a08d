"""Exact Euler-Bernoulli references, to measure the model's error."""

from typing import Optional

import numpy as np
from numpy.typing import ArrayLike

from ._flexure import exact_compliance_tip, exact_deflect

__all__ = ["deflect", "compliance"]


def deflect(moment: float = 0.0, fx: float = 0.0, fy: float = 0.0, length: float = 1.0, ei: float = 1.0,
            rest: Optional[ArrayLike] = None) -> np.ndarray:
    """Tip pose [phi, x, y] of the exact elastica (Eq. 3) under a tip moment and force,
    solved by shooting with load continuation. `rest`: 1 to 64 rest curvature coefficients
    in the model's basis (straight by default).
    Warns StabilityWarning if the shape found is unstable (Jacobi test)."""
    return exact_deflect(moment, fx, fy, length, ei, rest)


def compliance(length: float = 1.0, ei: float = 1.0, rest: Optional[ArrayLike] = None) -> np.ndarray:
    """Exact small-load tip compliance (3, 3), order (phi, x, y), from the compliance ODE (Eq. 34)."""
    return exact_compliance_tip(length, ei, rest)
