"""Type stubs for the compiled module. Units SI, angles in radians; order (phi, x, y)."""

from typing import Any, Dict, Literal, Optional, Sequence, Tuple, TypedDict, Union, overload

import numpy as np
from numpy.typing import ArrayLike

class ConvergenceError(RuntimeError):
    """A solver stopped before meeting its tolerance."""
    residual: float
    # Mechanism.sweep: the answer with the rows reached and `stopped`.
    result: dict

class StabilityWarning(UserWarning):
    """An equilibrium was found but is unstable."""

class AccuracyWarning(UserWarning):
    """A model answer's estimated error misses its accuracy target (by default 1 % of L and 1 degree)."""

class YieldWarning(UserWarning):
    """A flexure's peak bending stress exceeds its yield strength: the safety factor is below 1."""

class PreloadWarning(UserWarning):
    """A weld or pin of a mechanism is open at rest: closing it preloads the mechanism."""

class IntersectionWarning(UserWarning):
    """Two parts of a solved mechanism cross: parts touch only geoms, not each other."""

class _Peak(TypedDict):
    """The largest value of a quantity along the flexure (Pa for stress, 1/m for curvature) and where."""
    max: float
    at: float  # m from the root

# Stub-only names. A quantity along the flexure, over t = s/L in [0, 1]: a number, a pair
# (root, tip) for a linear taper, or a table of [t, value] rows (an (m, 2) array or a list of
# pairs; t starts at 0, ends at 1 and increases strictly), linear between its rows.
_Profile = Union[float, Tuple[float, float], Sequence[Sequence[float]], ArrayLike]

class _ErrorEstimate(TypedDict):
    """An answer's error, estimated against a refined model of reference_order with reference_quadrature points,
    or, at order 64 (reference "elastica", both then 0), against the exact elastica."""
    position: float  # m
    angle: float  # rad
    stress: float  # Pa, the peak bending stress's error; present only for flexures with a thickness
    curvature: float  # 1/m, the peak curvature change's error
    reference_order: int
    reference_quadrature: int
    reference: str  # "model" (refined) or "elastica" (exact, at order 64)
    flagged: bool  # whether it misses the accuracy target (Python's; the CLI's answer says it once)

# Stub-only names. accuracy: (position as a fraction of L, angle in rad[, peak stress or curvature as a
# fraction of the peak]), each finite and > 0; None means (0.01, 1 degree, 0.01).
_Accuracy = Optional[Union[Tuple[float, float], Tuple[float, float, float]]]

class _Modes(TypedDict):
    # Angular frequencies (rad/s), ascending.
    omega: np.ndarray
    # omega / 2 pi (Hz).
    frequency: np.ndarray
    # (modes, order): each row a mode's coordinates alpha, normalized to v^T M v = 1.
    shapes: np.ndarray
    # Directions without inertia (a massless flexure's), condensed out as quasi-static.
    quasi_static: int
    # Each mode's estimated relative error against the refined model: omega (NaN where the
    # reference pairs none), reference_omega, reference_order, reference_quadrature,
    # reference_stable, flagged.
    error_estimate: dict

class _Vibration(TypedDict):
    omega: np.ndarray
    frequency: np.ndarray
    # Scaled frequencies (mean mu omega^2 L^4 / mean EI)^(1/4): beta L for a uniform beam.
    beta_l: np.ndarray
    # The reference mass per length of beta_l (kg/m).
    mass_per_length: float

class _StabilityLimit(TypedDict, total=False):
    """The factor on the load where stability is lost (status "lost"), or the bound it holds to (status
    "stable_up_to", with stalled: None when that is max_factor, else why the path could not be followed
    further), as the CLI prints it."""
    factor: float
    status: Literal["lost", "stable_up_to"]
    stalled: Optional[str]

class _Tendon(TypedDict, total=False):
    alpha: np.ndarray
    pose: np.ndarray  # [phi, x, y]
    tendon_length: float  # m
    stable: bool
    error_estimate: Optional[_ErrorEstimate]
    flagged: bool
    stress: _Peak  # with a thickness
    curvature_max: _Peak  # without one
    safety_factor: float  # with a yield_strength, while stressed
    order: int  # with order="auto"
    quadrature: int  # with order="auto"
    stability_limit: _StabilityLimit  # with limit=True

class _TipLoad(TypedDict):
    moment: float
    fx: float
    fy: float

class _Connection(TypedDict, total=False):
    alpha: np.ndarray
    energy: float  # J
    load: _TipLoad  # the tip load that holds the shape
    error_estimate: Optional[_ErrorEstimate]
    flagged: bool
    stress: _Peak
    curvature_max: _Peak
    safety_factor: float
    order: int
    quadrature: int
    stability_limit: _StabilityLimit  # with limit=True

class Flexure:
    """A planar flexure joint of the Smooth Curvature Model.

    length (m), ei (N*m^2) or modulus (Pa) with width and thickness (m) and optional poisson;
    order N (1 to 64) of the shifted-Legendre curvature basis; quadrature points
    (1 to 1024, default N + 2); kappa, the rest curvature coefficients (N,) (`rest`, its deprecated
    name, warns DeprecationWarning; both at once raise ValueError).
    ei, width and thickness may each vary along the flexure (see _Profile): a number, a pair
    (root, tip), or a table of [t, value] rows over t = s/L. notch=(R, h) cuts two circular
    cut-outs of radius R centred on the flexure, leaving thickness h at its middle.
    density (kg/m^3, with width and thickness) or mass_per_length (kg/m, a _Profile) gives
    the mass per length, for dynamics. yield_strength S (Pa, with a thickness) gives the
    safety factor S/σmax, and a YieldWarning from deflect when it is below 1.
    Invalid values raise ValueError naming the parameter, as do options that
    would be ignored (width, thickness, poisson or notch without modulus; ei with modulus).
    """
    def __init__(self, length: float = 1.0, ei: Optional[_Profile] = None, order: int = 3,
                 quadrature: Optional[int] = None, kappa: Optional[ArrayLike] = None, *,
                 modulus: Optional[float] = None, width: Optional[_Profile] = None,
                 thickness: Optional[_Profile] = None, poisson: Optional[float] = None,
                 notch: Optional[Tuple[float, float]] = None, density: Optional[float] = None,
                 mass_per_length: Optional[_Profile] = None,
                 yield_strength: Optional[float] = None,
                 rest: Optional[ArrayLike] = None) -> None: ...
    @property
    def length(self) -> float: ...
    @property
    def ei(self) -> float:
        """EI (N*m^2); for a non-uniform section, its mean (1/L)∫EI ds."""
    @property
    def order(self) -> int: ...
    @property
    def quadrature(self) -> int: ...
    @property
    def kappa(self) -> np.ndarray:
        """Rest curvature coefficients κ, shape (N,)."""
    @property
    def rest(self) -> np.ndarray:
        """Deprecated name of kappa (warns DeprecationWarning)."""
    @property
    def modulus(self) -> Optional[float]:
        """Effective modulus E' (Pa; E/(1-ν²) with poisson), or None for a flexure given by ei (no stress)."""
    @property
    def yield_strength(self) -> Optional[float]: ...
    @property
    def uniform(self) -> bool:
        """Whether EI is the same all along the flexure."""
    # Section along the flexure, at arc length s (m) in [0, L]: a float for a number, an array like s.
    def ei_at(self, s: ArrayLike) -> Union[float, np.ndarray]:
        """EI(s) (N*m^2)."""
    def thickness_at(self, s: ArrayLike) -> Optional[Union[float, np.ndarray]]:
        """h(s) (m), notch included; None for a flexure given by ei."""
    def width_at(self, s: ArrayLike) -> Optional[Union[float, np.ndarray]]:
        """b(s) (m); None for a flexure given by ei."""
    def mass_per_length_at(self, s: ArrayLike) -> Optional[Union[float, np.ndarray]]:
        """μ(s) (kg/m); None without density or mass_per_length."""
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
    def buckling_load(self, tip: str = "free", *, accuracy: Optional[float] = None) -> float:
        """Critical compressive tip load (N): tip is free, guided, pinned or clamped. Its error
        is estimated against the same load at a higher order: a miss of accuracy (a fraction of
        the load, default 0.01) warns AccuracyWarning."""
    def modes(self, count: Optional[int] = None, *, tip_mass: Optional[float] = None,
              tip_inertia: Optional[float] = None, tip_com: Optional[Tuple[float, float]] = None,
              moment: float = 0.0, fx: float = 0.0, fy: float = 0.0,
              accuracy: Optional[float] = None) -> _Modes:
        """Vibration modes about the equilibrium under a tip load (loaded stiffness: a frequency
        falls to zero at a buckling load), with the flexure's density or mass_per_length and an
        optional tip body (tip_mass kg, tip_inertia kg*m^2 about its centre of mass, tip_com (x, y)
        m in the tip frame). count: 1 to order (default 3, or the order); fewer are returned if
        fewer are finite. ValueError naming mass without any mass; ConvergenceError past a
        buckling load."""
    def tendon(self, tension: float, root_offset: float, tip_offset: float, *, accuracy: _Accuracy = None,
               order: Optional[Literal["auto"]] = None, limit: bool = False, max_factor: float = 1000.0,
               force: Optional[float] = None) -> _Tendon:
        """The tendon-driven joint under a tendon of `tension` (N; `force`, its deprecated name, warns
        DeprecationWarning) attached root_offset and
        tip_offset (m) from the neutral axis, as `flexure tendon --json` (pose an array [phi, x, y]).
        Warns StabilityWarning when unstable, AccuracyWarning when flagged; order="auto" raises the
        order until the target is met; limit=True adds stability_limit {factor, status[, stalled]} (stalled with stable_up_to)."""
    def connect(self, pose: ArrayLike, *, accuracy: _Accuracy = None, order: Optional[Literal["auto"]] = None,
                limit: bool = False, max_factor: float = 1000.0) -> _Connection:
        """The minimum-energy shape whose tip reaches pose (phi, x, y), as `flexure connect --json`
        (without eta): alpha, energy, load {moment, fx, fy}, error_estimate, flagged, stress."""
    def stability_limit(self, moment: float = 0.0, fx: float = 0.0, fy: float = 0.0, *,
                        max_factor: float = 1000.0) -> _StabilityLimit:
        """The factor on the tip load at which the path from rest loses stability
        ({"factor": f, "status": "lost"}), or the bound it stays stable to ({"factor": f,
        "status": "stable_up_to", "stalled": None when that is max_factor, else why the path could not
        be followed further), as `deflect --limit`'s stability_limit."""
    # Bending at alpha (N,), such as deflect's answer.
    def stress(self, alpha: ArrayLike) -> Optional[_Peak]:
        """Peak bending stress σ(s) = E' h(s)/2 |ω(s) - ω0(s)|: {max (Pa), at (m from the root)};
        None for a flexure given by ei (no thickness)."""
    def peak_curvature(self, alpha: ArrayLike) -> _Peak:
        """Largest change of curvature from rest: {max (1/m), at (m)}."""
    def safety_factor(self, alpha: ArrayLike) -> float:
        """S/σmax against the flexure's yield_strength (inf while unstressed); warns YieldWarning
        below 1. ValueError without a yield_strength."""
    def shape(self, alpha: ArrayLike, k: int) -> np.ndarray:
        """The deformed flexure at k (2 to 10000) points evenly spaced in arc length, ends included,
        in its root frame: a structured array of fields s, x, y (m), phi (rad), curvature (1/m, total)
        and, with a thickness, stress (Pa). shape["x"], shape["y"] plot it."""

class SpatialFlexure:
    """A spatial flexure: two bendings and a twist (curvature components twist, κ_y, κ_z), pose in SE(3)."""

    def __init__(
        self,
        length: float = 1.0,
        ei: Optional[_Profile] = None,
        order: Optional[int] = None,
        *,
        ei_y: Optional[_Profile] = None,
        gj: Optional[_Profile] = None,
        modulus: Optional[float] = None,
        width: Optional[_Profile] = None,
        thickness: Optional[_Profile] = None,
        diameter: Optional[_Profile] = None,
        poisson: Optional[float] = None,
        shear_modulus: Optional[float] = None,
        kappa: Optional[ArrayLike] = None,
        kappa_y: Optional[ArrayLike] = None,
        twist: Optional[ArrayLike] = None,
        density: Optional[float] = None,
        mass_per_length: Optional[_Profile] = None,
        rotary_inertia_per_length: Optional[Tuple[float, float, float]] = None,
    ) -> None: ...
    @property
    def length(self) -> float: ...
    @property
    def orders(self) -> Tuple[int, int, int]: ...
    @property
    def density(self) -> Optional[float]: ...
    @property
    def mass_per_length(self) -> Union[None, float, Tuple[float, float], np.ndarray]: ...
    @property
    def rotary_inertia_per_length(self) -> Optional[Tuple[float, float, float]]: ...
    def mass_per_length_at(self, s: ArrayLike) -> Union[None, float, np.ndarray]: ...
    def mass(self) -> Optional[float]: ...
    @property
    def coordinates(self) -> int: ...
    def pose(self, alpha: ArrayLike) -> np.ndarray: ...
    def jacobian(self, alpha: ArrayLike) -> np.ndarray: ...
    def deflect(
        self, force: Optional[ArrayLike] = None, moment: Optional[ArrayLike] = None, *, accuracy: Optional[Any] = None
    ) -> Dict[str, Any]: ...
    def compliance(self) -> np.ndarray: ...
    def stress(self, alpha: ArrayLike) -> Optional[Dict[str, Any]]: ...
    def shape(self, alpha: ArrayLike, k: int) -> np.ndarray: ...
    def exact_rod(self, force: Optional[ArrayLike] = None, moment: Optional[ArrayLike] = None) -> Dict[str, Any]: ...

class Mechanism:
    """A mechanism file's model, planar or spatial (dimension = 3); the spatial forms of each
    answer are flexure.Mechanism's."""
    @staticmethod
    def from_text(text: str) -> "Mechanism": ...
    @property
    def dof(self) -> int: ...
    @property
    def dimension(self) -> int:
        """2 (planar) or 3 (spatial)."""
    def simulate(
        self,
        duration: float,
        every: Optional[float] = None,
        tolerance: float = 1e-8,
        start: str = "equilibrium",
        max_steps: Optional[int] = None,
        accuracy: _Accuracy = None,
    ) -> dict:
        """As flexure.Mechanism.simulate: time, bodies {name: {x, y, phi}}, coordinates and
        velocities {joint: (N, k) array}, energy, steps, rejected, violation, dimension,
        error_estimate, flagged; spatial:
        bodies {name: {x, y, z, roll, pitch, yaw (N,), rotation (N, 3, 3)}}."""
    def solve(self, accuracy: _Accuracy = None, limit: bool = False) -> dict:
        """As flexure.Mechanism.solve, one shape in both dimensions: dimension, bodies (planar
        {x, y, phi}; spatial {x, y, z, roll, pitch, yaw, rotation (3, 3)}), coordinates, energy,
        stable, error_estimate {flexure joint: _ErrorEstimate}, flagged, findings, and per flexure
        joint stress (or curvature_max), safety_factor and shape where they apply, load,
        multipliers, residual, load_steps, iterations[, order]."""
    def buckle(self, accuracy: Optional[float] = None) -> dict:
        """As flexure.Mechanism.buckle, in both dimensions: load_factor, mode, dimension,
        error_estimate, flagged[, order, findings]."""
    def compliance(self, body: str, at: Optional[ArrayLike] = None) -> np.ndarray:
        """As flexure.Mechanism.compliance: (3, 3), order (phi, x, y), of the frame at `at` on `body`;
        spatial: (6, 6), order (rx, ry, rz, x, y, z), at `at` (x, y, z)."""
    def sweep(self, parameter: str, values: ArrayLike, accuracy: _Accuracy = None,
              compliance: Optional[str] = None, at: Optional[ArrayLike] = None) -> dict:
        """As flexure.Mechanism.sweep: values, bodies, coordinates, energy, stress, flagged,
        stability_limit, findings[, order]; a sweep that stops raises with the rows in `result`; bodies
        keyed as simulate's (spatial: x, y, z, roll, pitch, yaw, rotation) and compliance (n, 6, 6)."""
    def export(self, to: str = "mjcf", prb: str = "3R", range: Union[None, str, Sequence[float]] = None,
               armature: float = 0.0, step: float = 0.002, name: str = "mechanism") -> Tuple[str, dict]:
        """As flexure.Mechanism.export: (xml, report {format, prb, range, joints, step, armature, warnings, notes})."""
    def modes(self, count: Optional[int] = None, accuracy: Optional[float] = None) -> dict:
        """As flexure.Mechanism.modes: omega, frequency, shapes {joint: (modes, coordinates)},
        quasi_static, and limit_fraction after a snap-through; spatial: the same keys, with
        error_estimate and dimension."""

class Elastica:
    """The exact elastica of a flexure under a tip load (flexure.exact.elastica): Eq. 3 with EI(s),
    solved by multiple shooting. The stress, curvature and shape come from the exact shape, solved
    again (to the same answer) when first asked for; each runs without the GIL."""
    @property
    def pose(self) -> np.ndarray:
        """Tip pose [phi, x, y] in the root frame."""
    @property
    def root_moment(self) -> float:
        """Bending moment at the root (N*m)."""
    @property
    def stable(self) -> bool:
        """Whether the shape is a minimum of the potential energy (Jacobi test)."""
    @property
    def limit_fraction(self) -> Optional[float]:
        """The load fraction where the loading path first lost stability (snap-through), or None."""
    @property
    def limit(self) -> Optional[float]:
        """Deprecated name of limit_fraction (warns DeprecationWarning)."""
    @property
    def load(self) -> Tuple[float, float, float]:
        """(moment, fx, fy) in the root frame."""
    @property
    def flexure(self) -> Flexure: ...
    def stress(self) -> Optional[_Peak]:
        """Peak bending stress E' h(s)/2 |m(s)|/EI(s): {max (Pa), at (m from the root)};
        None for a flexure given by ei (no thickness)."""
    def peak_curvature(self) -> _Peak:
        """Largest change of curvature from rest |m(s)|/EI(s): {max (1/m), at (m)}."""
    def safety_factor(self) -> float:
        """S/σmax against the flexure's yield_strength (inf while unstressed); warns YieldWarning
        below 1. ValueError without a yield_strength."""
    def shape(self, k: int) -> np.ndarray:
        """The exact shape at k (2 to 10000) points evenly spaced in arc length, ends included: a
        structured array of fields s, x, y (m), phi (rad), curvature (1/m, total) and, with a
        thickness, stress (Pa), as Flexure.shape."""

# The exact references behind flexure.exact, which is their documented interface.
def exact_elastica(flexure: Flexure, moment: float = 0.0, fx: float = 0.0, fy: float = 0.0, *,
                   what: str = "exact.elastica") -> Elastica: ...
def exact_compliance(flexure: Flexure) -> np.ndarray: ...
def exact_buckling_load(flexure: Flexure, tip: str = "free") -> float: ...
def exact_frequencies(flexure: Flexure, count: Optional[int] = None, compression: float = 0.0,
                      tip_mass: Optional[float] = None, tip_inertia: Optional[float] = None,
                      tip_com: Optional[Tuple[float, float]] = None) -> _Vibration: ...
def exact_flexure(length: float = 1.0, ei: Optional[_Profile] = None, kappa: Optional[ArrayLike] = None,
                  rest: Optional[ArrayLike] = None, stacklevel: int = 1) -> Flexure: ...
