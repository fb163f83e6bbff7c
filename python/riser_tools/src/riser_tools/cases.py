"""The cases the studies run: hang-off motions, the lines of the built-in
scenes as the peer codes need them, runs of `riser run` as data, and grids
of them.

Everything here is checked when it is made: a bad value raises `CaseError`
whose message starts with the field it names (``motion.period = -1.0: ...``,
``grid.n_elements: an empty list``), before any run starts.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

AXES = {"surge": 0, "sway": 1, "heave": 2}


class CaseError(ValueError):
    """A case or a grid refused: the message names the field."""


def _finite(where: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise CaseError(f"{where} = {value!r}: expected a number")
    if not math.isfinite(value):
        raise CaseError(f"{where} = {value!r}: expected a finite number")
    return float(value)


def _positive(where: str, value: Any) -> float:
    v = _finite(where, value)
    if v <= 0.0:
        raise CaseError(f"{where} = {value!r}: expected a number > 0")
    return v


def _non_negative(where: str, value: Any) -> float:
    v = _finite(where, value)
    if v < 0.0:
        raise CaseError(f"{where} = {value!r}: expected a number >= 0")
    return v


def ramp_weight(t: np.ndarray | float, ramp: float) -> np.ndarray:
    """riser's `--ramp` weight: 1/2 (1 - cos(pi t / ramp)) for t < ramp, then 1 (1 throughout for ramp 0)."""
    t = np.asarray(t, dtype=float)
    if ramp <= 0.0:
        return np.ones_like(t)
    return np.where(t < ramp, 0.5 * (1.0 - np.cos(np.pi * np.minimum(t, ramp) / ramp)), 1.0)


@dataclass(frozen=True)
class Motion:
    """A hang-off motion A w(t) sin(2 pi t / T) along one axis (heave, surge or
    sway), w the ramp weight; `until`: held after this time (`--heave-until`,
    heave only). `window`: where a study takes its statistics (t >= window)."""

    amplitude: float
    period: float
    axis: str = "heave"
    ramp: float = 0.0
    until: float | None = None
    duration: float | None = None
    window: float = 0.0

    def __post_init__(self) -> None:
        if self.axis not in AXES:
            raise CaseError(f"motion.axis = {self.axis!r}: expected one of {', '.join(AXES)}")
        _non_negative("motion.amplitude", self.amplitude)
        _positive("motion.period", self.period)
        _non_negative("motion.ramp", self.ramp)
        if self.until is not None:
            _non_negative("motion.until", self.until)
            if self.axis != "heave":
                raise CaseError(f"motion.until: `--heave-until` holds the heave only, not {self.axis}")
        if self.duration is not None:
            _positive("motion.duration", self.duration)
        _non_negative("motion.window", self.window)
        if self.duration is not None and self.window >= self.duration:
            raise CaseError(f"motion.window = {self.window!r}: must start before the duration {self.duration!r}")

    @property
    def index(self) -> int:
        """The axis as a component index (x 0, y 1, z 2)."""
        return AXES[self.axis]

    def displacement(self, t: np.ndarray | float) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        return self.amplitude * ramp_weight(t, self.ramp) * np.sin(2.0 * np.pi * t / self.period)

    def velocity(self, t: np.ndarray | float, h: float | None = None) -> np.ndarray:
        """d/dt of the displacement: exact (h None; riser_sweep's formula), or by central
        differences of step h."""
        t = np.asarray(t, dtype=float)
        if h is not None:
            return (self.displacement(t + h) - self.displacement(t - h)) / (2.0 * h)
        w = 2.0 * np.pi / self.period
        r = ramp_weight(t, self.ramp)
        dr = (np.where(t < self.ramp, 0.5 * (np.pi / self.ramp) * np.sin(np.pi * np.minimum(t, self.ramp) / self.ramp),
                       0.0) if self.ramp > 0 else np.zeros_like(t))
        return self.amplitude * (dr * np.sin(w * t) + r * w * np.cos(w * t))

    def acceleration(self, t: np.ndarray | float, h: float = 1e-4) -> np.ndarray:
        """d^2/dt^2 of the displacement by central differences."""
        t = np.asarray(t, dtype=float)
        return (self.displacement(t + h) - 2.0 * self.displacement(t) + self.displacement(t - h)) / (h * h)

    def cli_args(self, ramp: bool = True) -> list[str]:
        """The motion as `riser run` options (`--heave A,T --ramp R [--heave-until T]`). The
        ramp is always given: `riser run`'s default is one period, and `--ramp 0` is the
        paper's abrupt start. `ramp=False` leaves it out (for the second motion of a run)."""
        args = [f"--{self.axis}", f"{self.amplitude:g},{self.period:g}"]
        if ramp:
            args += ["--ramp", f"{self.ramp:g}"]
        if self.until is not None:
            args += ["--heave-until", f"{self.until:g}"]
        return args


@dataclass(frozen=True)
class Line:
    """A uniform line as a peer code (MoorDyn) needs it: SI units, riser's frame
    (hang-off at the origin), `surface_z` the water surface above the hang-off,
    `anchor` (x, y, z). Drag on D (riser's convention; MoorDyn's CdAx is on pi D)."""

    length: float
    mass: float
    diameter: float
    ea: float
    ei: float
    cd_normal: float
    cd_tangential: float
    ca_normal: float
    anchor: tuple[float, float, float]
    surface_z: float
    rho_water: float = 1025.0
    gravity: float = 9.81
    seabed_z: float | None = None

    def __post_init__(self) -> None:
        for name in ("length", "mass", "diameter", "ea", "rho_water", "gravity"):
            _positive(f"line.{name}", getattr(self, name))
        for name in ("ei", "cd_normal", "cd_tangential", "ca_normal"):
            _non_negative(f"line.{name}", getattr(self, name))
        if len(self.anchor) != 3:
            raise CaseError(f"line.anchor = {self.anchor!r}: expected (x, y, z)")
        for i, c in enumerate(self.anchor):
            _finite(f"line.anchor[{i}]", c)
        _finite("line.surface_z", self.surface_z)
        if self.seabed_z is not None and _finite("line.seabed_z", self.seabed_z) > min(0.0, self.anchor[2]):
            raise CaseError(f"line.seabed_z = {self.seabed_z!r}: above the hang-off or the anchor")

    @property
    def submerged_weight(self) -> float:
        """N/m: weight less buoyancy on pi D^2/4."""
        return (self.mass - self.rho_water * math.pi * self.diameter ** 2 / 4.0) * self.gravity

    @property
    def wave_speed(self) -> float:
        """m/s: sqrt(EA / m), the axial waves."""
        return math.sqrt(self.ea / self.mass)

    @property
    def span(self) -> float:
        """m: the horizontal distance from the hang-off to the anchor."""
        return math.hypot(self.anchor[0], self.anchor[1])

    def replace(self, **changes: Any) -> Line:
        from dataclasses import replace
        return replace(self, **changes)


# riser's built-in scenes (scenes/*.toml), as the peer comparisons state them
CATENARY = Line(length=100.0, mass=226.7, diameter=0.3172, ea=7.96e8, ei=5.882e4, cd_normal=0.6,
                cd_tangential=0.05, ca_normal=0.0, anchor=(60.0, 0.0, -70.0), surface_z=10.0)
STEEL_CATENARY = Line(length=400.0, mass=162.1, diameter=0.2731, ea=3.38e9, ei=2.71e7, cd_normal=1.0,
                      cd_tangential=0.008, ca_normal=1.0, anchor=(292.0, 0.0, -200.0), surface_z=10.0,
                      seabed_z=-200.0)
# the paper's heave of the catenary (20 s) and the lazy wave (30 s)
SCENE_PERIODS = {"catenary": 20.0, "lazy_wave": 30.0}


def set_args(sets: Mapping[str, Any] | Iterable[str]) -> list[str]:
    """`--set name=value` options from a mapping (in its order) or from "name=value" strings."""
    items = [f"{k}={v}" for k, v in sets.items()] if isinstance(sets, Mapping) else list(sets)
    out: list[str] = []
    for s in items:
        name, eq, value = s.partition("=")
        if not eq or not name.strip() or not value.strip():
            raise CaseError(f"sets: {s!r}: expected name=value")
        out += ["--set", s]
    return out


@dataclass(frozen=True)
class Case:
    """One run of `riser run`: the scene, its `--set` overrides, the motion, the duration."""

    label: str
    scene: str
    sets: tuple[str, ...] = ()
    motion: Motion | None = None
    duration: float = 100.0
    group: str = ""
    note: str = ""

    def __post_init__(self) -> None:
        if not self.label:
            raise CaseError("case.label: empty")
        if not self.scene:
            raise CaseError(f"case {self.label}: scene: empty")
        if isinstance(self.sets, (str, Mapping)):
            raise CaseError(f"case {self.label}: sets = {self.sets!r}: expected a sequence of name=value")
        try:
            set_args(self.sets)
        except CaseError as e:
            raise CaseError(f"case {self.label}: {e}") from None
        _positive(f"case {self.label}: duration", self.duration)

    def cli_args(self) -> list[str]:
        """`riser run` arguments after the binary: run SCENE --set... MOTION --duration D."""
        return ["run", self.scene, *set_args(self.sets), *(self.motion.cli_args() if self.motion else []),
                "--duration", f"{self.duration:g}"]


def product(**axes: Sequence[Any]) -> list[dict[str, Any]]:
    """The full factorial of named axes, the first varying slowest:
    ``product(n_elements=[10, 20], time_step=[0.1])`` -> two dicts. An axis that is
    not a non-empty list or tuple, or that repeats a value, is refused naming it."""
    if not axes:
        raise CaseError("grid: no axes")
    for name, values in axes.items():
        if isinstance(values, (str, bytes)) or not isinstance(values, Sequence):
            raise CaseError(f"grid.{name} = {values!r}: expected a list of values")
        if len(values) == 0:
            raise CaseError(f"grid.{name}: an empty list")
        seen = [v for i, v in enumerate(values) if v in values[:i]]
        if seen:
            raise CaseError(f"grid.{name}: {seen[0]!r} appears twice")
    names = list(axes)
    return [dict(zip(names, combo)) for combo in itertools.product(*(axes[n] for n in names))]


def unique_labels(cases: Sequence[Case]) -> list[Case]:
    """The cases, refused if two share a label (their outputs would overwrite each other)."""
    seen: set[str] = set()
    for c in cases:
        if c.label in seen:
            raise CaseError(f"case {c.label}: label used twice")
        seen.add(c.label)
    return list(cases)

