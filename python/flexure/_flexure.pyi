"""Type stubs for the compiled module. Units SI, angles in radians; order (phi, x, y)."""

from typing import Literal, Optional, Tuple, TypedDict, overload

import numpy as np
from numpy.typing import ArrayLike

class ConvergenceError(RuntimeError):
    """A solver stopped before meeting its tolerance."""
    residual: float

class StabilityWarning(UserWarning):
    """An equilibrium was found but is unstable."""

class AccuracyWarning(UserWarning):
    """A model answer's estimated error misses its accuracy target (by default 1 % of L and 1 degree)."""

class _ErrorEstimate(TypedDict):
    """An answer's error, estimated against a refined model of reference_order with reference_quadrature points."""
    position: float  # m
    angle: float  # rad
    flagged: bool  # whether it misses the accuracy target
    reference_order: int
    reference_quadrature: int

# Stub-only names. accuracy: (position as a fraction of L, angle in rad), each finite and > 0; None means (0.01, 1 degree).
_Accuracy = Optional[Tuple[float, float]]

class Flexure:
    """A planar flexure joint of the Smooth Curvature Model.

    length (m), ei (N*m^2) or modulus (Pa) with width and thickness (m) and optional poisson;
    order N (1 to 64) of the shifted-Legendre curvature basis; quadrature points
    (1 to 1024, default N + 2); rest curvature coefficients (N,).
    Invalid values raise ValueError naming the parameter, as do options that
    would be ignored (width, thickness or poisson without modulus; ei with modulus).
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
    # Every alpha below must have N entries (per row): another length raises ValueError.
    def pose(self, alpha: ArrayLike) -> np.ndarray:
        """[phi, x, y] for alpha (N,); (n, 3) for alpha (n, N), in parallel without the GIL
        (Ctrl-C stops a batch with KeyboardInterrupt)."""
    def jacobian(self, alpha: ArrayLike) -> np.ndarray:
        """(3, N), rows phi, x, y."""
    def hessians(self, alpha: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
        """(Hx, Hy), each (N, N)."""
    def transform(self, alpha: ArrayLike) -> np.ndarray:
        """(4, 4) homogeneous transform of the tip frame in the root frame."""
    def energy(self, alpha: ArrayLike) -> float:
        """Bending energy in joules."""
    @overload
    def deflect(self, moment: float = 0.0, fx: float = 0.0, fy: float = 0.0, *,
                accuracy: _Accuracy = None, order: None = None) -> np.ndarray:
        """Equilibrium alpha (N,) under a tip moment (N*m) and force (N) in the root frame.
        Raises ConvergenceError if no equilibrium is found; warns StabilityWarning if it is unstable,
        and AccuracyWarning if its estimated error (see error_estimate) misses `accuracy`.
        Runs without the GIL; Ctrl-C stops it with KeyboardInterrupt."""
    @overload
    def deflect(self, moment: float = 0.0, fx: float = 0.0, fy: float = 0.0, *,
                accuracy: _Accuracy = None, order: Literal["auto"]) -> Tuple["Flexure", np.ndarray]:
        """(flexure_used, alpha): the lowest order (from this one, doubling, with the reference's
        quadrature) whose equilibrium meets `accuracy`. ValueError if even order 64 misses it."""
    def error_estimate(self, alpha: ArrayLike, moment: float = 0.0, fx: float = 0.0, fy: float = 0.0,
                       accuracy: _Accuracy = None) -> _ErrorEstimate:
        """Estimated error of alpha (N,) as the equilibrium under the tip load, against a refined
        model corrected from it (estimate::deflect_error). Does not warn: flagged says it misses."""
    def stiffness(self, alpha: ArrayLike, moment: float = 0.0, fx: float = 0.0, fy: float = 0.0) -> np.ndarray:
        """(N, N) generalized stiffness K = ∇∇U − Fx∇∇x − Fy∇∇y at alpha under the tip load (Eq. 32)."""
    def compliance(self, alpha: ArrayLike, moment: float = 0.0, fx: float = 0.0, fy: float = 0.0) -> np.ndarray:
        """(3, 3) tip compliance J K^-1 J^T with the loaded stiffness K (Eqs. 32, 36). At an equilibrium
        alpha for that load (from deflect) it is d(pose)/d(moment, fx, fy). Raises ValueError where K
        is not positive definite (an unstable equilibrium has no compliance)."""
    def rest_compliance(self) -> np.ndarray:
        """(3, 3) tip compliance of the unloaded flexure at its rest shape (Eqs. 35–36)."""
    def buckling_load(self, tip: str = "free") -> float:
        """Critical compressive tip load (N): tip is free, guided, pinned or clamped."""

class Mechanism:
    @staticmethod
    def from_text(text: str) -> "Mechanism": ...
    @property
    def dof(self) -> int: ...
    def solve(self, accuracy: _Accuracy = None) -> dict: ...

def exact_deflect(moment: float, fx: float, fy: float, length: float, ei: float,
                  rest: Optional[ArrayLike]) -> np.ndarray: ...
def exact_compliance_tip(length: float, ei: float, rest: Optional[ArrayLike]) -> np.ndarray: ...
