"""Flexure joints with the Smooth Curvature Model, beside exact beam theory.

Conventions (the same as the Rust crate): SI units, angles in radians.
The root frame's x axis runs along the unbent flexure; poses, Jacobian
rows and compliance rows/columns are ordered (phi, x, y); tip loads are a
moment M (counter-clockwise) and a force (Fx, Fy) in the root frame.
Bad input raises ValueError naming the parameter. Every model answer
carries its error, estimated against a refined model (`Flexure.error_estimate`,
the `error_estimate` of `Mechanism.solve`); one that misses its accuracy target
(by default 1 % of L and 1 degree) warns AccuracyWarning, and
`Flexure.deflect(..., order="auto")` raises the order until it is met.
A flexure's section may vary along it (`width=(0.01, 0.005)`, tables of
[t, value] rows, `notch=(R, h)`); `Flexure.stress`, `safety_factor` and
`shape` report its bending, and a peak stress beyond `yield_strength` warns
YieldWarning. `flexure.exact` solves beam theory itself on the same flexure,
section included: `exact.elastica(fy=..., flexure=f)` has the exact pose and
the same `stress()`, `peak_curvature()`, `safety_factor()` and `shape(k)`;
`exact.compliance` and `exact.buckling_load` take `flexure=` too. Solves and batches run without the GIL; Ctrl-C stops `Flexure.deflect`
and a batch `Flexure.pose` with KeyboardInterrupt (the exact and mechanism
solvers poll for it once they run on the library's interruptible solver core).

>>> import flexure
>>> f = flexure.Flexure(length=1.0, ei=1.0)
>>> alpha = f.deflect(fy=1.0)          # Bisshopp-Drucker load, PL^2/EI = 1
>>> round(float(f.pose(alpha)[1]), 2)  # tip x; the exact elastica gives 0.94357
0.94
"""

# Imported under private names: the package's namespace is its API (`__all__`) alone.
import errno as _errno
import os as _os
from os import PathLike as _PathLike
from os import fspath as _fspath
from pathlib import Path as _Path
from typing import TYPE_CHECKING as _TYPE_CHECKING
from typing import Optional as _Optional
from typing import Sequence as _Sequence
from typing import Tuple as _Tuple
from typing import Union as _Union

if _TYPE_CHECKING:
    import numpy as np

from . import exact
from ._flexure import (
    AccuracyWarning,
    ConvergenceError,
    Flexure,
    IntersectionWarning,
    PreloadWarning,
    SpatialFlexure,
    StabilityWarning,
    YieldWarning,
)
from ._flexure import Mechanism as _Mechanism

__all__ = [
    "Flexure",
    "SpatialFlexure",
    "Mechanism",
    "ConvergenceError",
    "StabilityWarning",
    "AccuracyWarning",
    "YieldWarning",
    "PreloadWarning",
    "IntersectionWarning",
    "exact",
]


# The most a mechanism file may hold (64 MiB), as in the library and the CLI.
_MAX_FILE_BYTES = 64 << 20


class Mechanism:
    """A flexure-jointed mechanism described in TOML (docs/mechanism-format.md in the repository):
    planar, or spatial for a file with `dimension = 3` (`dimension` says which). A spatial
    mechanism answers solve, compliance, sweep, modes, simulate, buckle and export (MJCF
    only), each documented with its spatial form."""

    def __init__(self, inner: _Mechanism, source: _Optional[str] = None):
        self._inner = inner
        # The file it was read from, named in its errors.
        self._source = source

    @classmethod
    def from_file(cls, path: _Union[str, "_PathLike[str]"]) -> "Mechanism":
        """Reads a mechanism file. A missing file raises FileNotFoundError naming `path`;
        an error in the file raises ValueError naming the file, line and column."""
        if not isinstance(path, (str, _PathLike)):
            raise ValueError(f"path must be a str or os.PathLike naming a mechanism file, got {type(path).__name__}")
        name = _fspath(path)
        if not isinstance(name, str):
            raise ValueError(f"path must name the file as text, got {type(name).__name__}")
        try:
            # Bounded, as the CLI reads files: /dev/zero or a runaway file is refused, not read forever.
            with open(name, "rb") as f:
                data = f.read(_MAX_FILE_BYTES + 1)
            if len(data) > _MAX_FILE_BYTES:
                raise ValueError(f"{name}: larger than {_MAX_FILE_BYTES >> 20} MiB, the most a mechanism file may hold")
            text = data.decode("utf-8")
        except FileNotFoundError:
            where = f"no such mechanism file (relative paths start at {_os.getcwd()})"
            raise FileNotFoundError(_errno.ENOENT, where, name) from None
        except UnicodeDecodeError as e:
            raise ValueError(f"{name}: not UTF-8 text ({e.reason} at byte {e.start})") from None
        try:
            inner = _Mechanism.from_text(text)
        except ValueError as e:
            raise ValueError(f"{name}: {e}") from None
        return cls(inner, name)

    @classmethod
    def from_toml(cls, text_or_path: _Union[str, "_PathLike[str]"]) -> "Mechanism":
        """Parses TOML text, or reads a file as `from_file` does: a `Path`, a string naming an
        existing file, or a one-line string ending in ".toml" (a missing file then raises
        FileNotFoundError rather than being parsed as TOML)."""
        if isinstance(text_or_path, _PathLike) or (
            isinstance(text_or_path, str)
            and "\n" not in text_or_path
            and (
                _Path(text_or_path).is_file()
                or (text_or_path.strip().endswith(".toml") and not any(c in text_or_path for c in "=#["))
            )
        ):
            return cls.from_file(text_or_path)
        if isinstance(text_or_path, str):
            return cls(_Mechanism.from_text(text_or_path))
        raise ValueError(f"text_or_path must be TOML text or a path, got {type(text_or_path).__name__}")

    @property
    def dof(self) -> int:
        """Number of generalized coordinates."""
        return self._inner.dof

    @property
    def dimension(self) -> int:
        """2 for a planar mechanism, 3 for a spatial one (its file says `dimension = 3`)."""
        return self._inner.dimension

    def simulate(
        self,
        duration: float,
        every: _Optional[float] = None,
        tolerance: float = 1e-8,
        start: str = "equilibrium",
        max_steps: _Optional[int] = None,
        accuracy: _Optional[_Tuple[float, float]] = None,
    ) -> dict:
        """Motion over [0, duration] (s), as `flexure simulate --json` gives it, in NumPy arrays:
        time (N,) at 0, every, 2 every, ... and duration (every defaults to duration/100);
        bodies {name: {x, y, phi}} (each (N,), the body frame in the ground frame, the
        ground left out); coordinates and velocities {joint: (N, k)}; energy (N,)
        (kinetic, elastic and gravitational, J); steps, rejected; violation, the largest
        closure violation. The file's [[schedule]] tables give the loads in time. It starts
        from the static equilibrium under the loads at t = 0, at rest (start="rest": the
        unloaded shape), with the file's [initial] and [initial_velocity] overriding it;
        directions with neither mass nor damping (massless flexures) then start on
        their equilibrium under the loads at t = 0, which time[0] records.
        `tolerance` is the relative and absolute tolerance of each step's error.
        findings (left out when empty) lists what `solve` lists: closures open at
        rest (PreloadWarning), and parts that cross at a sample (IntersectionWarning,
        once per pair of parts; each sample's crossing listed with its time).
        With geoms a part may touch, contacts lists each sample's contacts as `solve`
        reports them (each touching contact, "stick" or "slip", then each other pair at
        its least gap, "open"), and changes lists where one touched or began to slide
        ("slip"), stuck ("stick") or opened ("open"): {time, contact, state}. A contact
        that touches while approaching takes a perfectly inelastic impact. Friction
        holds stuck where the touching point is material (a flexure's bare end, a ball
        whose body only translates) and rolling without slipping where it is not
        (inside a span, a ball that turns, a strip touching with its thickness).
        `max_steps` is the step budget (default 1e6 plus 10 per sample, as the CLI's).
        error_estimate {position (m), angle (rad), at (s), reference_tolerance, samples,
        complete, position_tolerance (m)} is the largest difference of a body's pose from a
        run at a tenth of `tolerance`, held to `accuracy` (position as a fraction of the
        mechanism's size, angle in rad; default 1 % and 1 deg): flagged, with AccuracyWarning,
        when it misses it (error_estimate is left out when no finer run is left).
        A duration, every or tolerance not above zero raises ValueError naming it; an
        integration that stalls (its budget included) raises ConvergenceError saying
        where; Ctrl-C stops it with KeyboardInterrupt saying the time reached. Runs
        without the GIL.

        Spatial (dimension = 3): bodies {name: {x, y, z, roll, pitch, yaw (each (N,)), rotation
        (N, 3, 3)}}, each body's origin, URDF angles and rotation matrix in the ground frame at
        each sample, as `flexure simulate --json`; dimension is 2 or 3; the rest as
        above: the file's [[schedule]] tables (force.NAME.mx ... fz, tendon.NAME.tension,
        gravity.x ... z) give the loads in time, and findings lists closures open at rest
        and parts that cross, with the thickness of their sections (each with a 3-vector `at`)."""
        try:
            return self._inner.simulate(duration, every, tolerance, start, max_steps, accuracy)
        except (ValueError, ConvergenceError) as e:
            # Name the file, unless the error is about an argument.
            arguments = ("duration", "every", "tolerance", "start", "max_steps", "accuracy")
            about_argument = str(e.args[0]).removeprefix("invalid ").startswith(arguments) if e.args else False
            if self._source is not None and not about_argument:
                e.args = (f"{self._source}: {e.args[0]}",) + e.args[1:]
            raise

    def solve(self, accuracy: _Optional[_Tuple[float, float]] = None, limit: bool = False) -> dict:
        """Static equilibrium: a dict shaped like `flexure solve --json`
        (bodies {name: {x, y, phi}}, coordinates {joint: array}, energy, stable),
        error_estimate {flexure joint: dict as `Flexure.error_estimate` returns (position (m),
        angle (rad), stress (Pa, with a thickness), curvature (1/m), reference_order,
        reference_quadrature, reference, flagged)} and flagged (True when any joint misses
        `accuracy`), with dimension (2), load {flexure joint: {moment, fx, fy}} (the tip load it
        carries, in its root frame), multipliers (array), residual, load_steps and iterations.
        An unstable answer warns StabilityWarning.
        A flexure joint whose estimated error misses `accuracy` (position as a fraction
        of its length, angle in rad; default (0.01, 1 degree)) warns AccuracyWarning
        naming it; one whose error could not be estimated warns so and raises the
        library's error, as `flexure solve` fails. Errors name the
        mechanism's file, if it was read from one. A flexure joint of
        order = "auto" that misses `accuracy` is raised (up to order 64) and the
        mechanism solved again until it meets it; then `order` {joint: int, or
        [n_twist, n_y, n_z] in space} says the orders used, and its coordinates
        are that many. One still missing at 64 warns AccuracyWarning saying so.

        Per flexure joint, in maps by joint name (each left out when empty):
        stress {max (Pa), at (m from its root)} for one with a thickness, else
        curvature_max {max (1/m), at}; safety_factor for one with `yield_strength`
        (left out while it is unstressed; below 1 it warns YieldWarning naming the
        joint and the yield strength); shape, a structured array as `Flexure.shape`
        returns, for one with `shape = K`.

        findings (left out when empty, as in `flexure solve --json`): a list of
        dicts (kind, severity, message, ...). A weld or pin open
        at rest (kind "open_closure": gap_m, gap_rad for a weld, and the preload,
        preload_force_n and preload_moment_n_m, that it carries with no load) warns
        PreloadWarning, unless the file says `preload = true` in it (severity
        "note", no warning). Two parts that cross in the answer (kind "crossing":
        parts, at, s_a and s_b along flexures, points) warn IntersectionWarning.

        contacts (an empty list where nothing touched, left out where no part may touch a
        geom, as in `flexure solve --json`): a list
        of dicts, each pair touching then each that touched on the way and opened: geom,
        flexure (or body, for a geom's touch), s (m along the flexure), point and normal
        (ground frame), normal_force (N, not negative), friction_force, gap (m) and state
        ("stick" held by friction, "slip" sliding or touching without friction, "open").
        Friction holds where a flexure's bare end touches, and rolls without slipping
        where a contact rolls (inside a span, where a strip touches with its thickness,
        between two geoms); in space, where a rolling contact slides, its direction is
        solved with each load step.

        Spatial (dimension = 3): the same dict, as `flexure solve --json` prints it: bodies
        {name: {x, y, z, roll, pitch, yaw, rotation (3, 3)}} (origin, URDF roll, pitch, yaw and
        rotation matrix in the ground frame); coordinates {joint: array} (a flexure's twist
        series, then its bendings about y and z; a hinge's angle, a slider's travel, a ball's
        rotation vector); load {flexure joint: {moment (3,), force (3,)}}, the tip wrench it
        carries in its root frame; stress {flexure joint: {max (the peak von Mises stress, Pa),
        at, point, bending_y, bending_z, shear}}; safety_factor and shape (a list of sections
        {s, position, rotation, curvature, stress}) as in the plane.

        limit=True adds stability_limit, as `flexure solve --limit`: {factor, status "lost"},
        the factor on all the loads (tensions, forces, gravity), up to 1000, at which the
        equilibrium followed from rest stops being stable, or {factor, status "stable_up_to",
        stalled}, the factor it holds to (stalled None at 1000, else why the path could not
        be followed further, with a StabilityWarning). With contact the load is followed in
        order, as the contacts touch, stick and slip."""
        try:
            return self._inner.solve(accuracy, limit)
        except (ValueError, ConvergenceError) as e:
            # Name the file, unless the error is about the `accuracy` argument.
            if self._source is not None and e.args and not str(e.args[0]).startswith("accuracy"):
                e.args = (f"{self._source}: {e.args[0]}",) + e.args[1:]
            raise

    def _named(self, e: BaseException, arguments: _Tuple[str, ...]) -> None:
        """Prefixes the error `e` with the mechanism's file, unless it is about one of `arguments`."""
        if self._source is None or not e.args:
            return
        text = str(e.args[0])
        if not text.removeprefix("invalid ").startswith(arguments):
            e.args = (f"{self._source}: {text}",) + e.args[1:]

    def buckle(self, accuracy: _Optional[float] = None) -> dict:
        """Linear buckling about the unloaded configuration, as `flexure buckle FILE --json`:
        load_factor, the factor on all loads (forces, tensions, gravity) at which the
        constrained stiffness becomes singular; mode (dof,), the buckling mode in generalized
        coordinates (unit length, largest entry positive); error_estimate, against the
        mechanism with every flexure refined: load_factor (its relative error; left out,
        with unestimated = [1] and reference_stable, when the reference has none),
        reference_load_factor, reference_order and reference_quadrature {flexure joint: int};
        flagged, whether it misses accuracy (a fraction, default 0.01; then AccuracyWarning).
        Flexures of order = "auto" in the file are raised until it is met (order then lists
        {joint: order}). findings lists closures open at rest (PreloadWarning). A mechanism
        without coordinates, or without loads, raises ValueError; errors name the file.

        Spatial (dimension = 3): load_factor, mode (dof,), error_estimate and flagged as above
        (the reference refines every spatial flexure; reference_order is its largest order and
        reference_quadrature its Magnus subintervals, by flexure joint), as `flexure buckle
        --json` prints them (dimension 3); flexures of order = "auto" are raised as above
        (order then lists {joint: [n_twist, n_y, n_z]}); findings lists closures open at rest."""
        try:
            return self._inner.buckle(accuracy)
        except (ValueError, ConvergenceError) as e:
            self._named(e, ("accuracy",))
            raise

    def compliance(self, body: str, at: _Optional[_Sequence[float]] = None) -> "np.ndarray":
        """Compliance (3, 3), order (phi, x, y), of the frame at point `at` (x, y, m, in the
        body's frame) on `body` at the loaded equilibrium: its response d(pose)/d(M, Fx, Fy)
        to a small extra load there, as `flexure solve FILE --compliance BODY --at X,Y`.
        For one flexure of length L and stiffness EI clamped to the ground, at its tip and
        unloaded: diag(L/EI, 0, L^3/3EI) with L^2/2EI coupling phi and y. An unknown body, or
        an `at` that is not two finite numbers within 1e6 m, raises ValueError naming it; an
        unstable equilibrium (or a free joint) raises ValueError; errors name the file.
        `at` defaults to the body's origin. Contacts that touch are held as they are
        (closed, and stuck where stuck); a sliding contact with friction raises ValueError.

        Spatial (dimension = 3): (6, 6), rows and columns (rx, ry, rz, x, y, z), small
        rotations then displacements per unit moment then force, in the ground frame, of the
        point `at` (x, y, z) on `body`, as `flexure solve FILE --compliance BODY --at X,Y,Z`.
        For one flexure clamped to the ground, unloaded, at its tip: diag(L/GJ, L/EI_y, L/EI_z,
        0, L^3/3EI_z, L^3/3EI_y) with the bending couplings L^2/2EI."""
        try:
            return self._inner.compliance(body, at)
        except (ValueError, ConvergenceError) as e:
            self._named(e, ("body", "at"))
            raise

    def sweep(
        self,
        parameter: str,
        values: _Sequence[float],
        accuracy: _Optional[_Tuple[float, float]] = None,
        compliance: _Optional[str] = None,
        at: _Optional[_Tuple[float, float]] = None,
    ) -> dict:
        """Equilibria along `values` of one load, each continued from the last, as
        `flexure solve FILE --sweep PARAMETER=...`. parameter: "tendon.NAME.tension",
        "force.NAME.fx", ".fy" or ".moment", "gravity.x" or "gravity.y"; values: 1 to 10000
        numbers (a tension not negative). The answer holds one entry per value reached stably:
        dimension; values (n,); bodies {name: {key: (n,)}} (the ground left out), keyed as
        `simulate`'s: x, y, phi in the plane; x, y, z, roll, pitch, yaw and rotation (n, 3, 3)
        in space; coordinates {joint: (n, k)}; energy (n,); stress {flexure joint with a
        section: (n,) peak stress, Pa; in space the von Mises peak}; where a part may touch
        a geom, normal_force {contact.GEOM.PART: (n,) its push, 0 while open, as the CLI's
        `contact.GEOM.PART.normal_force` column} and contacts, a list per row of its
        contacts as `solve` reports them (state and friction too: the path's stick and
        slip); flagged, the values at
        which a flexure joint's estimated error misses `accuracy` (AccuracyWarning); order
        as `solve`'s, when a flexure has order = "auto" (raised once for all rows, to the
        order the row that asks most needs);
        stability_limit {value, fraction} where stability is first lost (found by bisection
        between the two values that bracket it, to a relative 1e-6; StabilityWarning): values
        past it with no stable equilibrium reachable by loading are left out, and rows past a
        snap-through are kept; findings as `solve`'s (each crossing with the `value` it is
        found at). With compliance=BODY (and at, a point on it; default its origin),
        compliance (n, 3, 3) in the plane or (n, 6, 6) in space: each row's compliance of
        that frame, as `--sweep ... --compliance BODY --at X,Y` adds to each row.

        A sweep that stops (a solve that fails before the last value) raises
        ConvergenceError, or KeyboardInterrupt for Ctrl-C, whose `result` attribute holds the
        answer with the rows reached and `stopped` {value, error}: the CLI prints the same
        rows and exits 2. Bad input raises ValueError naming it; errors name the file.

        Parameters in the plane: "tendon.NAME.tension", "force.NAME.fx", ".fy" or ".moment",
        "gravity.x" or "gravity.y"; in space (dimension = 3): "tendon.NAME.tension",
        "force.NAME.fx" (".fy", ".fz", ".mx", ".my", ".mz") or "gravity.x" (".y", ".z")."""
        try:
            return self._inner.sweep(parameter, values, accuracy, compliance, at)
        except (ValueError, ConvergenceError, KeyboardInterrupt) as e:
            self._named(e, ("parameter", "values", "accuracy", "compliance", "body", "at"))
            raise

    def export(
        self,
        to: str = "mjcf",
        prb: str = "3R",
        range: _Union[None, str, _Sequence[float]] = None,
        armature: float = 0.0,
        step: float = 0.002,
        name: _Optional[str] = None,
    ) -> _Tuple[str, dict]:
        """The mechanism as a rigid-body model for a simulator, as `flexure export`: returns
        (xml, report). to: "mjcf" (MuJoCo), "sdf" (SDFormat 1.9, Gazebo) or "urdf" (ROS).
        Each flexure becomes a pseudo-rigid-body chain, prb "3R" (Su's, the default) or "1R"
        (Howell's characteristic pivot), fitted to the Smooth Curvature Model over the file's
        loads times each fraction of range ("F0:F1:N" or (F0, F1, N); default 0 to 1 at 12).
        step (s, default MuJoCo's 2 ms; 0: none) is the simulator step the model is sized for:
        each sprung joint whose own link would ring faster than 10 steps gets the armature
        that slows it to that, and MJCF's timestep and closures' solref follow it. armature
        (kg m^2) is added to every pseudo-rigid hinge on top; name is the model's (default
        the file's stem). report: format, prb, range, joints {flexure joint: {prb, gamma,
        k_theta, stiffness, pivots, error {position, angle}, flagged (past 1 % of L or 1°),
        samples, length}}, step, armature {joint: armature written}, warnings (also raised as UserWarning: flagged fits, what the format cannot hold) and
        notes. A spatial mechanism is written to MJCF, SDF or URDF (each hinge a link of its own
        in the last two; URDF refuses a ball joint), each flexure a chain of pivots of
        three hinges (bending about z and y, twist about x) along its rest shape, with springs
        fitted to its tip compliance at rest (1R there: one pivot and the tip's own hinges);
        rigid hinges, slides and balls are MuJoCo's own, and a flexure's mass is lumped on its
        links; its report adds dimension 3, 3-D pivots, and stiffness_y and stiffness_x per
        pivot. Bad arguments raise ValueError naming them (docs/export.md in
        the repository)."""
        if name is None:
            name = _Path(self._source).stem if self._source else "mechanism"
        try:
            return self._inner.export(to, prb, range, armature, step, name)
        except (ValueError, ConvergenceError) as e:
            if self._source is not None and e.args and not str(e.args[0]).startswith("invalid"):
                e.args = (f"{self._source}: {e.args[0]}",) + e.args[1:]
            raise

    def modes(self, count: _Optional[int] = None, accuracy: _Optional[float] = None) -> dict:
        """Vibration modes about the loaded equilibrium (the loads' stiffness included, so a
        frequency falls to zero at a buckling load; closures respected): a dict of omega
        (rad/s, ascending), frequency (Hz), shapes {joint: array (modes, joint coordinates),
        normalized to v^T M v = 1} and quasi_static (directions without inertia, such as a
        massless flexure's, condensed out: they follow quasi-statically and have no
        frequency). Only finite modes; count: 1 to dof (default 3, or dof), fewer returned if
        fewer are finite. Mass comes from the file's [[body]] mass and inertia and the
        flexures' density or mass_per_length: without any, ValueError naming mass. Past a
        buckling load, ConvergenceError; a loading path that snapped through warns
        StabilityWarning and adds limit_fraction. error_estimate holds each mode's estimated
        relative error against the mechanism with every flexure refined (omega, NaN where the
        reference pairs none; reference_omega; reference_order and reference_quadrature by
        flexure joint; reference_stable; flagged); a mode that misses accuracy (a fraction,
        default 0.01) warns AccuracyWarning. Flexures of order = "auto" in the file are raised
        until every mode meets it. Errors name the mechanism's file.

        Spatial (dimension = 3): omega, frequency, shapes {joint: (modes, k)}, quasi_static,
        limit_fraction and error_estimate as above (the reference refines every spatial flexure
        about the equilibrium; reference_order is its largest order and reference_quadrature
        its Magnus subintervals, by flexure joint); flexures of order = "auto" are raised as
        above (order lists {joint: [n_twist, n_y, n_z]}); findings lists closures open at rest.
        The mass is the bodies' and the spatial flexures' own (their density or
        mass_per_length), as in the plane."""
        try:
            return self._inner.modes(count, accuracy)
        except (ValueError, ConvergenceError) as e:
            if self._source is not None and e.args and not str(e.args[0]).startswith("invalid count"):
                e.args = (f"{self._source}: {e.args[0]}",) + e.args[1:]
            raise
