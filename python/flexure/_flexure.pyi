"""Type stubs for the compiled module. Units SI, angles in radians; order (phi, x, y)."""

from typing import Optional, Tuple

import numpy as np
from numpy.typing import ArrayLike

class ConvergenceError(RuntimeError):
    """A solver stopped before meeting its tolerance."""
    residual: float

class StabilityWarning(UserWarning):
    """An equilibrium was found but is unstable."""

class Flexure:
    """A planar flexure joint of the Smooth Curvature Model.

    length (m), ei (N*m^2) or modulus (Pa), width, thickness (m) and poisson;
    order N of the shifted-Legendre curvature basis; quadrature points (default N + 2);
    rest curvature coefficients (N,). Invalid values raise ValueError naming the parameter.
    """
    def __init__(self, length: float = 1.0, ei: Optional[float] = None, order: int = 3,
                 quadrature: Optional[int] = None, rest: Optional[ArrayLike] = None, *,
                 modulus: Optional[float] = None, width: Optional[float] = None,
                 thickness: Optional[float] = None, poisson: Optional[float] = None) -> None: ...
    @property
    def length(self) -> float: ...
    @property
    def ei(self) -> float: ...
    @property
    def order(self) -> int: ...
    @property
    def quadrature(self) -> int: ...
    @property
    def rest(self) -> np.ndarray: ...
    def pose(self, alpha: ArrayLike) -> np.ndarray:
        """[phi, x, y] for alpha (N,); (n, 3) for alpha (n, N), in parallel without the GIL."""
    def jacobian(self, alpha: ArrayLike) -> np.ndarray:
        """(3, N), rows phi, x, y."""
    def hessians(self, alpha: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
        """(Hx, Hy), each (N, N)."""
    def transform(self, alpha: ArrayLike) -> np.ndarray:
        """(4, 4) homogeneous transform of the tip frame in the root frame."""
    def energy(self, alpha: ArrayLike) -> float:
        """Bending energy in joules."""
    def deflect(self, moment: float = 0.0, fx: float = 0.0, fy: float = 0.0) -> np.ndarray:
        """Equilibrium alpha (N,) under a tip moment (N*m) and force (N) in the root frame.
        Raises ConvergenceError if no equilibrium is found; warns StabilityWarning if it is unstable."""
    def compliance(self, alpha: Optional[ArrayLike] = None) -> np.ndarray:
        """(3, 3) tip compliance J K^-1 J^T (Eq. 36), at the rest shape by default."""
    def buckling_load(self, tip: str = "free") -> float:
        """Critical compressive tip load (N): tip is free, guided, pinned or clamped."""

class Mechanism:
    @staticmethod
    def from_text(text: str) -> "Mechanism": ...
    @property
    def dof(self) -> int: ...
    def solve(self) -> dict: ...

def exact_deflect(moment: float, fx: float, fy: float, length: float, ei: float,
                  rest: Optional[ArrayLike]) -> np.ndarray: ...
def exact_compliance_tip(length: float, ei: float, rest: Optional[ArrayLike]) -> np.ndarray: ...
