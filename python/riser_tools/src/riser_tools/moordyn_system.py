"""MoorDyn-C (the Python package `moordyn`, v2) driving a *system* of lines on one vessel, from
the numbers of a riser system scene (docs/guide/systems.md): issue 49's dynamic comparison of
a spread mooring under a prescribed vessel motion (docs/system_moordyn.md).

What the scene becomes in MoorDyn's input file:

* each `[[line_type]]` a LINE TYPE: Diam = `outer_diameter`, Mass/m = `mass_per_length`,
  EA = `axial_stiffness`, EI = 0 (the cable model only: a rod type is refused), Cd =
  `cd_normal`, Ca = `ca_normal`, CdAx = `cd_tangential` / pi (MoorDyn's axial drag is on the
  wetted surface pi D, riser's on D), CaAx = 0 (riser has no tangential added mass); BA is
  the axial damping the caller asks for (`ba`: N s, or -zeta, a fraction of the critical
  damping of one segment's axial mode, MoorDyn's convention), by default riser's
  `[analysis] structural_damping` eta as BA = eta EA (0 unless the scene sets it);
* one BODY "Coupled" at the vessel's reference point (the system's origin), with no mass,
  volume, drag or added mass of its own: MoorDyn moves it as it is told (6 DOF);
* each `[[point]]` a POINT: `fixed` -> Fixed at its global position, `vessel` -> attached to
  the body ("Body1") at its vessel-frame position; `free` -> Free at its initial position with
  its Mass = `mass`, Volume = `volume`, CdA = `cd_area`, Ca = `ca`. The conventions are
  riser's (docs/theory.md 17.7): MoorDyn-C's point has weight and buoyancy rho g V (always the
  whole volume: riser's only below the surface, so the points must stay submerged), drag
  1/2 rho CdA |u - v| (u - v) and added mass Ca rho V; it has no seabed contact (riser's point
  has: keep the points clear of the seabed to compare);
* each `[[line]]` a LINE from its `from` point (MoorDyn's end A, node 0) to its `to` point
  (end B, node N), `length`, `nseg` segments (the caller's, not the scene's n_elements);
* OPTIONS: dtM, g, rho = `water_density`, WtrDpth = `water_surface_z` - `[seabed] z` (a flat
  seabed only), kBot = `[seabed] stiffness`, cBot = `[seabed] damping` (riser's defaults, 3e6
  Pa/m and 3e5 Pa s/m, are MoorDyn's), FrictionCoefficient = `[seabed] friction`, tScheme.

MoorDyn's frame is riser's system frame when the water surface is at z = 0 (the default of a
system); another `water_surface_z` is refused rather than shifted.

The forces recorded (`run`): for each line, the force of its end nodes on the points they
are attached to, F_end - M_end a (MoorDyn's node net force with the node's inertia taken
off, a the point's acceleration: exact for the vessel's points, 0 for the anchors), as riser's
end reactions are: the `tension_from` / `tension_to` magnitudes; the resultant on the vessel,
the sum of the vessel ends' forces (and, as a check, MoorDyn's own coupled-body force, whose
inertia term uses MoorDyn's finite-difference acceleration).
"""

from __future__ import annotations

import math
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, Sequence

import numpy as np

from .cases import CaseError, Motion
from .moordyn import NO_OUTPUT, _moordyn, coupling_calls, quiet

AXIS_INDEX = {"surge": 0, "sway": 1, "heave": 2}


@dataclass
class LineType:
    name: str
    diameter: float
    mass: float
    ea: float
    cd_normal: float = 0.0
    cd_tangential: float = 0.0
    ca_normal: float = 0.0

    @property
    def cd_axial(self) -> float:
        """MoorDyn's CdAx (on pi D) of riser's `cd_tangential` (on D)."""
        return self.cd_tangential / math.pi

    @property
    def wave_speed(self) -> float:
        return math.sqrt(self.ea / self.mass)


@dataclass
class Point:
    name: str
    kind: str
    position: tuple[float, float, float]
    mass: float = 0.0
    volume: float = 0.0
    cd_area: float = 0.0
    ca: float = 0.0


@dataclass
class SystemLine:
    name: str
    type: str
    start: str      # the scene's `from`
    end: str        # the scene's `to`
    length: float
    n_elements: int


@dataclass
class System:
    """The numbers of a riser system scene that MoorDyn needs."""

    name: str
    line_types: dict[str, LineType]
    points: dict[str, Point]
    lines: list[SystemLine]
    rho: float = 1025.0
    g: float = 9.81
    surface_z: float = 0.0
    seabed_z: float | None = None
    seabed_stiffness: float = 3.0e6
    seabed_damping: float = 3.0e5
    friction: float = 0.0
    structural_damping: float = 0.0
    time_step: float = 0.05
    source: Path | None = None

    @property
    def depth(self) -> float:
        return self.surface_z - self.seabed_z if self.seabed_z is not None else 1000.0

    def line_type(self, line: SystemLine) -> LineType:
        return self.line_types[line.type]

    def vessel_end(self, line: SystemLine) -> str | None:
        """'from' or 'to': which end of `line` is on the vessel (None: neither)."""
        if self.points[line.end].kind == "vessel":
            return "to"
        return "from" if self.points[line.start].kind == "vessel" else None

    def free_points(self) -> list[str]:
        return [p.name for p in self.points.values() if p.kind == "free"]

    def segment_dt(self, nseg: int) -> float:
        """The shortest axial-wave crossing of a segment, l / c, s: the explicit scheme's scale."""
        return min((ln.length / nseg) / self.line_type(ln).wave_speed for ln in self.lines)


def _num(where: str, v: Any) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise CaseError(f"{where} = {v!r}: expected a finite number")
    return float(v)


def load(path: str | Path, overrides: Mapping[str, Mapping[str, float]] | None = None) -> System:
    """A system scene's numbers (tomllib). `overrides`: {line type name: {key: value}} changes
    a line type's keys (e.g. to give the chain drag) as riser would read the same scene edited."""
    path = Path(path)
    d = tomllib.loads(path.read_text())
    if "line" in d and not isinstance(d["line"], list):
        raise CaseError(f"{path}: a single-line scene ([line]); this driver takes a system ([[line]])")
    types = {}
    for t in d.get("line_type", []):
        t = {**t, **(overrides or {}).get(t["name"], {})}
        name = t["name"]
        if t.get("model", "rod") != "cable":
            raise CaseError(f"line_type.{name}.model = {t.get('model', 'rod')!r}: this driver writes cables only")
        types[name] = LineType(name, _num(f"line_type.{name}.outer_diameter", t["outer_diameter"]),
                               _num(f"line_type.{name}.mass_per_length", t["mass_per_length"]),
                               _num(f"line_type.{name}.axial_stiffness", t["axial_stiffness"]),
                               float(t.get("cd_normal", 0.0)), float(t.get("cd_tangential", 0.0)),
                               float(t.get("ca_normal", 0.0)))
    points = {}
    for p in d.get("point", []):
        if p["kind"] not in ("fixed", "vessel", "free"):
            raise CaseError(f"point.{p['name']}.kind = {p['kind']!r}: expected fixed, vessel or free")
        points[p["name"]] = Point(p["name"], p["kind"], tuple(float(x) for x in p["position"]),
                                  *(float(p.get(k, 0.0)) for k in ("mass", "volume", "cd_area", "ca")))
    lines = []
    for ln in d.get("line", []):
        if ln["type"] not in types:
            raise CaseError(f"line.{ln['name']}.type = {ln['type']!r}: no such line type")
        for k in ("from", "to"):
            if ln[k] not in points:
                raise CaseError(f"line.{ln['name']}.{k} = {ln[k]!r}: no such point")
        lines.append(SystemLine(ln["name"], ln["type"], ln["from"], ln["to"], float(ln["length"]),
                                int(ln.get("n_elements", 60))))
    env = d.get("environment", {})
    bed = d.get("seabed")
    an = d.get("analysis", {})
    s = System(d.get("name", path.stem), types, points, lines,
               rho=float(env.get("water_density", 1025.0)), g=float(env.get("gravity", 9.81)),
               surface_z=float(env.get("water_surface_z", 0.0)),
               structural_damping=float(an.get("structural_damping", 0.0)),
               time_step=float(an.get("time_step", 0.05)), source=path)
    if s.surface_z != 0.0:
        raise CaseError(f"environment.water_surface_z = {s.surface_z!r}: this driver needs the surface at z = 0")
    if bed is not None:
        if float(bed.get("slope", 0.0)) != 0.0:
            raise CaseError("seabed.slope: this driver writes a flat seabed only")
        s.seabed_z = float(bed["z"])
        s.seabed_stiffness = float(bed.get("stiffness", 3.0e6))
        s.seabed_damping = float(bed.get("damping", 3.0e5))
        s.friction = float(bed.get("friction", 0.0))
    return s


def input_text(system: System, nseg: int, dtm: float, ba: float | None = None, scheme: str = "RK2",
               options: Mapping[str, Any] = NO_OUTPUT, title: str = "riser_tools.moordyn_system") -> str:
    """A MoorDyn v2 input file of `system`, every line in `nseg` segments, internal step
    `dtm` (written with repr: MoorDyn reads back the very double), time scheme `scheme`;
    `ba`: the lines' axial damping BA (N s, or -zeta), default eta EA of the scene."""
    if not isinstance(nseg, int) or nseg < 1:
        raise CaseError(f"moordyn.nseg = {nseg!r}: expected an integer >= 1")
    if not (isinstance(dtm, float) and math.isfinite(dtm) and dtm > 0):
        raise CaseError(f"moordyn.dtm = {dtm!r}: expected a number > 0")
    types = []
    for t in system.line_types.values():
        b = system.structural_damping * t.ea if ba is None else ba
        types.append(f"{t.name:<10} {t.diameter!r}  {t.mass!r}  {t.ea:.9e}  {b:.9e}  0.0  {t.cd_normal!r}  "
                     f"{t.ca_normal!r}  {t.cd_axial:.12f}  0.0")
    ids = {name: i + 1 for i, name in enumerate(system.points)}
    pts = []
    for p in system.points.values():
        att = {"fixed": "Fixed", "vessel": "Body1", "free": "Free"}[p.kind]
        x, y, z = p.position
        pts.append(f"{ids[p.name]:<4} {att:<8} {x!r}  {y!r}  {z!r}  {p.mass!r}  {p.volume!r}  {p.cd_area!r}  "
                   f"{p.ca!r}")
    lns = [f"{i + 1:<4} {ln.type:<10} {ids[ln.start]:<4} {ids[ln.end]:<4} {ln.length!r}  {nseg}  -"
           for i, ln in enumerate(system.lines)]
    opts: dict[str, Any] = {"dtM": repr(dtm), "g": system.g, "rho": system.rho, "WtrDpth": system.depth,
                            "kBot": system.seabed_stiffness, "cBot": system.seabed_damping,
                            "FrictionCoefficient": system.friction, "tScheme": scheme}
    opts.update(options)
    nl = "\n"
    return f"""--------------------- MoorDyn Input File ------------------------------------
{title}: {system.name}
---------------------- LINE TYPES ----------------------------------------------------------------------
TypeName   Diam      Mass/m     EA           BA/-zeta     EI           Cd     Ca     CdAx          CaAx
(name)     (m)       (kg/m)     (N)          (N-s/-)      (N-m^2)      (-)    (-)    (-)           (-)
{nl.join(types)}
---------------------- BODIES ---------------------------------------
ID   Attachment  X0  Y0  Z0  r0  p0  y0  Mass  CG*  I*  Volume  CdA*  Ca*
(#)  (word)      (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)
1    Coupled     0   0   0   0   0   0   0     0    0   0       0     0
---------------------- POINTS ---------------------------------------
ID   Attachment  X       Y     Z      Mass   Volume  CdA    Ca
(#)   (word/ID)  (m)     (m)   (m)    (kg)   (m^3)   (m^2)  (-)
{nl.join(pts)}
---------------------- LINES ----------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (ID)     (ID)      (m)       (-)      (-)
{nl.join(lns)}
---------------------- OPTIONS -----------------------------------------
{nl.join(f"{v:<14} {k}" for k, v in opts.items())}
--------------------- need this line ------------------
"""


def write_input(path: str | Path, system: System, nseg: int, dtm: float, **kw: Any) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(input_text(system, nseg, dtm, **kw))
    return path


@dataclass
class VesselMotion:
    """The vessel's reference point on riser's harmonics: each a `Motion` (surge, sway or
    heave, ramped as `riser run --ramp` ramps it); no rotations."""

    motions: Sequence[Motion]

    def displacement(self, t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        out = np.zeros(t.shape + (3,))
        for m in self.motions:
            out[..., m.index] += m.displacement(t)
        return out

    def acceleration(self, t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        out = np.zeros(t.shape + (3,))
        for m in self.motions:
            out[..., m.index] += m.acceleration(t)
        return out


@dataclass
class SystemRunResult:
    """A MoorDyn run on the output grid t = k sample: per line the end forces' magnitudes
    (`tension_from`, `tension_to`, N), the resultant force on the vessel (N, rows x, y, z: the
    vessel ends' forces summed) and MoorDyn's own coupled-body force (6 per row)."""

    t: np.ndarray
    tension: dict[str, dict[str, np.ndarray]]
    force: np.ndarray
    body: np.ndarray
    ok: bool
    t_fail: float
    wall: float
    ic_time: float
    dtm: float
    nseg: int
    steps: int
    input: Path
    extra: dict[str, Any] = field(default_factory=dict)

    def series(self, name: str) -> np.ndarray:
        """A column by riser's timeseries.csv name: `top_force_x|y|z`, `LINE.tension_from|to`."""
        if name.startswith("top_force_"):
            return self.force[:, "xyz".index(name[-1])]
        if name.split(".")[0] in self.extra.get("points", {}):
            point, axis = name.split(".")
            return self.extra["points"][point][:, "xyz".index(axis)]
        line, what = name.split(".")
        return self.tension[line][what.removeprefix("tension_")]


def wave_number(omega: np.ndarray, depth: float, g: float) -> np.ndarray:
    """k of omega^2 = g k tanh(k d) (riser's (13.2)), Newton from Eckart's start."""
    y = omega * omega * depth / g
    x = y / np.sqrt(np.tanh(y))
    for _ in range(50):
        th = np.tanh(x)
        f = x * th - y
        x = x - f / (th + x * (1.0 - th * th))
    return x / depth


@dataclass
class Sea:
    """Linear (Airy) components as riser's `[waves] kind = "table"` reads them (docs/theory.md
    13.1-13.5, 13.7): frequency (Hz), amplitude (m), phase and direction (deg), the phase origin
    at (0, 0), the mean water level at z = 0, no stretching (`stretching = "none"`: every node
    of these lines is far below the surface), the sea grown over `ramp` s by r(t) = (1 - cos(pi
    t / ramp)) / 2, the velocity r u and the acceleration r du/dt + r' u."""

    frequency: np.ndarray
    amplitude: np.ndarray
    phase: np.ndarray
    direction: np.ndarray
    depth: float
    g: float
    ramp: float

    def __post_init__(self) -> None:
        self.omega = 2.0 * np.pi * np.asarray(self.frequency, dtype=float)
        self.k = wave_number(self.omega, self.depth, self.g)
        b = np.radians(self.direction)
        self.kx, self.ky = self.k * np.cos(b), self.k * np.sin(b)
        self.cb, self.sb = np.cos(b), np.sin(b)
        self.phi = np.radians(self.phase)
        self.amplitude = np.asarray(self.amplitude, dtype=float)

    @classmethod
    def read(cls, csv: str | Path, depth: float, g: float, ramp: float) -> Sea:
        """A components table (riser waves --out's components.csv: frequency,amplitude,phase,direction;
        `#` lines are comments)."""
        rows = [ln for ln in Path(csv).read_text().splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
        head = [h.strip() for h in rows[0].split(",")]
        data = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
        col = {h: data[:, i] for i, h in enumerate(head)}
        return cls(col["frequency"], col["amplitude"], col["phase"], col["direction"], depth, g, ramp)

    def elevation(self, t: np.ndarray) -> np.ndarray:
        """r(t) eta at the phase origin."""
        t = np.asarray(t, dtype=float)
        eta = (self.amplitude * np.cos(self.phi - np.multiply.outer(t, self.omega))).sum(axis=-1)
        return self._ramp(t)[0] * eta

    def _ramp(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        t = np.asarray(t, dtype=float)
        if self.ramp <= 0.0:
            return np.ones_like(t), np.zeros_like(t)
        inside = t < self.ramp
        tt = np.minimum(t, self.ramp)
        r = np.where(inside, 0.5 * (1.0 - np.cos(np.pi * tt / self.ramp)), 1.0)
        dr = np.where(inside, 0.5 * np.pi / self.ramp * np.sin(np.pi * tt / self.ramp), 0.0)
        return r, dr

    def kinematics(self, t: float, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The water's velocity and acceleration (n x 3) at `points` (n x 3, global) at `t`."""
        p = np.asarray(points, dtype=float).reshape(-1, 3)
        zeta = np.clip(p[:, 2:3], -self.depth, 0.0)           # (n, 1): below the seabed its value
        th = p[:, 0:1] * self.kx + p[:, 1:2] * self.ky - self.omega * t + self.phi
        kd = self.k * self.depth
        e1 = np.exp(self.k * zeta)
        e2 = np.exp(-self.k * (zeta + 2.0 * self.depth))
        den = 1.0 - np.exp(-2.0 * kd)
        c, s = (e1 + e2) / den, (e1 - e2) / den                # cosh k(z+d)/sinh kd, sinh .../sinh kd
        aw = self.amplitude * self.omega
        cos_t, sin_t = np.cos(th), np.sin(th)
        uh = (aw * c * cos_t)
        w = (aw * s * sin_t)
        duh = (aw * self.omega * c * sin_t)
        dw = (-aw * self.omega * s * cos_t)
        u = np.stack([(uh * self.cb).sum(1), (uh * self.sb).sum(1), w.sum(1)], axis=1)
        du = np.stack([(duh * self.cb).sum(1), (duh * self.sb).sum(1), dw.sum(1)], axis=1)
        r, dr = self._ramp(t)
        return r * u, r * du + dr * u


def point_water_velocity(u: np.ndarray, du: np.ndarray, v: np.ndarray, point: Point, rho: float) -> np.ndarray:
    """The water velocity to hand MoorDyn-C's Free point so that its drag, 1/2 rho CdA |U* - v|
    (U* - v), is riser's whole wave load on a point (docs/theory.md (17.18)): the drag on the
    relative velocity u - v plus the waves' inertia (1 + Ca) rho V du, which MoorDyn-C 2.7's point
    leaves out (its Point.cpp: "TODO add Ud to inertia force"). U* = v + F / |F| sqrt(|F| / c),
    c = 1/2 rho CdA, F the sum; the point needs a drag area."""
    c = 0.5 * rho * point.cd_area
    w = u - v
    f = c * np.linalg.norm(w) * w + (1.0 + point.ca) * rho * point.volume * du
    size = np.linalg.norm(f)
    return v if size == 0.0 else v + f / size * np.sqrt(size / c)


def run(input_path: str | Path, system: System, nseg: int, motion: VesselMotion, duration: float,
        dtm: float, sample: float, coupling: int = 1, blow_up: float = 1e9, sea: Sea | None = None,
        point_wave_inertia: bool = False) -> SystemRunResult:
    """One MoorDyn run of `duration` s: MoorDyn's initial-condition solver (Init, its dynamic
    relaxation to the static state at the neutral pose), then a `Step` call every `coupling`
    internal steps of `dtm`, the body at the exact position of the call's start and the secant
    velocity to the next (MoorDyn moves it linearly within the call, landing exactly on the
    motion at each call's end); outputs every `sample` s (a whole number of calls). With
    `point_wave_inertia`, each Free point's water velocity is [`point_water_velocity`]'s (the
    waves' inertia on the point through its drag, held over the call)."""
    md = _moordyn()
    dtc, per_sample, ncalls = coupling_calls(dtm, coupling, sample, duration)
    tc = np.arange(ncalls + 1) * dtc
    u = motion.displacement(tc)
    x6 = np.zeros((ncalls + 1, 6))
    x6[:, :3] = u
    v6 = np.zeros((ncalls, 6))
    v6[:, :3] = (u[1:] - u[:-1]) / dtc
    xs, vs, ts = x6.tolist(), v6.tolist(), tc.tolist()
    nout = int(round(duration / sample))
    tout = np.arange(nout + 1) * sample
    acc = motion.acceleration(tout)
    input_path = Path(input_path)
    names = [ln.name for ln in system.lines]
    ten = {n: {"from": np.full(nout + 1, np.nan), "to": np.full(nout + 1, np.nan)} for n in names}
    # a free point's position, and each line's end forces at a free point (their node's inertia
    # taken off after the run, with the point's acceleration from its recorded positions)
    ids = {name: i + 1 for i, name in enumerate(system.points)}
    free = system.free_points()
    pos = {p: np.full((nout + 1, 3), np.nan) for p in free}
    at_free: list[tuple[str, str, int, str]] = []       # (line, 'from'|'to', node, point)
    for ln in system.lines:
        for end, p in (("from", ln.start), ("to", ln.end)):
            if p in free:
                at_free.append((ln.name, end, 0 if end == "from" else nseg, p))
    end_force = {(ln, end): np.full((nout + 1, 3), np.nan) for ln, end, _, _ in at_free}
    force = np.full((nout + 1, 3), np.nan)
    body = np.full((nout + 1, 6), np.nan)
    ok, t_fail = True, float("nan")
    steps = 0
    with quiet(input_path.parent / "moordyn.log"):
        t0 = time.perf_counter()
        s = md.Create(str(input_path))
        handles = [md.GetLine(s, i + 1) for i in range(len(names))]
        masses = [(np.array(md.GetLineNodeM(h, 0)), np.array(md.GetLineNodeM(h, nseg))) for h in handles]
        vessel_end = [system.vessel_end(ln) for ln in system.lines]
        point_handles = {p: md.GetPoint(s, ids[p]) for p in free}
        md.Init(s, xs[0], [0.0] * 6)
        free_index: dict[str, int] = {}
        if sea is not None:
            md.ExternalWaveKinInit(s)
            # each Free point's entry among the coordinates (after the lines' nodes)
            coords = np.array(md.ExternalWaveKinGetCoordinates(s)).reshape(-1, 3)
            n_nodes = sum(md.GetLineNumberNodes(h) for h in handles)
            for p, h in point_handles.items():
                at = np.flatnonzero(np.all(coords[n_nodes:] == np.array(md.GetPointPos(h)), axis=1))
                if len(at) != 1:
                    raise CaseError(f"MoorDyn's wave kinematics coordinates: point {p} not found once")
                free_index[p] = n_nodes + int(at[0])
        ic_time = time.perf_counter() - t0

        def record(j: int, f6: Sequence[float]) -> bool:
            total = np.zeros(3)
            for ln, h, (m0, mn), ve in zip(names, handles, masses, vessel_end):
                f0 = np.array(md.GetLineNodeForce(h, 0))
                fn = np.array(md.GetLineNodeForce(h, nseg))
                if ve == "to":
                    fn = fn - mn @ acc[j]
                    total += fn
                elif ve == "from":
                    f0 = f0 - m0 @ acc[j]
                    total += f0
                ten[ln]["from"][j] = np.linalg.norm(f0)
                ten[ln]["to"][j] = np.linalg.norm(fn)
                for end, f in (("from", f0), ("to", fn)):
                    if (ln, end) in end_force:
                        end_force[(ln, end)][j] = f
            for p, h in point_handles.items():
                pos[p][j] = md.GetPointPos(h)
            force[j] = total
            body[j] = f6
            return bool(np.all(np.abs(total) < blow_up))

        record(0, md.Step(s, xs[0], [0.0] * 6, 0.0, 0.0))
        t0 = time.perf_counter()
        step = md.Step
        try:
            j = 0
            for i in range(ncalls):
                if sea is not None:
                    # the water at the call's midpoint, at the nodes where the call starts (held over it)
                    coords = np.array(md.ExternalWaveKinGetCoordinates(s)).reshape(-1, 3)
                    u, du = sea.kinematics(ts[i] + 0.5 * dtc, coords)
                    if point_wave_inertia:
                        for p, h in point_handles.items():
                            k = free_index[p]
                            u[k] = point_water_velocity(u[k], du[k], np.array(md.GetPointVel(h)),
                                                        system.points[p], system.rho)
                    md.ExternalWaveKinSet(s, u.tolist(), du.tolist(), ts[i] + 0.5 * dtc)
                f6 = step(s, xs[i], vs[i], ts[i], dtc)
                steps += coupling
                if (i + 1) % per_sample == 0:
                    j += 1
                    if not record(j, f6):
                        ok, t_fail = False, ts[i + 1]
                        break
        except RuntimeError:
            ok, t_fail = False, ts[min(i + 1, ncalls)]
        wall = time.perf_counter() - t0
        node_mass = {(ln, end): np.array(md.GetLineNodeM(handles[names.index(ln)], node))
                     for ln, end, node, _ in at_free}
        md.Close(s)
    # the force of a line's end node on its free point: the node's net force less its inertia
    # M a, a the point's acceleration (central differences of the recorded positions)
    for ln, end, _, p in at_free:
        a = np.gradient(np.gradient(pos[p], sample, axis=0), sample, axis=0)
        ten[ln][end] = np.linalg.norm(end_force[(ln, end)] - a @ node_mass[(ln, end)].T, axis=1)
    return SystemRunResult(tout, ten, force, body, ok, t_fail, wall, ic_time, dtm, nseg, steps, input_path,
                           extra={"points": pos})


def window(t: np.ndarray, y: np.ndarray, w0: float, w1: float) -> tuple[float, float, float]:
    """min, time mean (trapezoidal), max of y over w0 <= t <= w1, as `riser run` reports its window."""
    m = (t >= w0 - 1e-9) & (t <= w1 + 1e-9)
    tt, yy = t[m], y[m]
    return float(yy.min()), float(np.trapezoid(yy, tt) / (tt[-1] - tt[0])), float(yy.max())


def riser_series(csv: str | Path) -> dict[str, np.ndarray]:
    """riser's timeseries.csv as columns."""
    import csv as _csv
    with open(csv) as f:
        r = _csv.reader(f)
        head = next(r)
        data = np.array([[float(x) for x in row] for row in r])
    return {h: data[:, i] for i, h in enumerate(head)}


def quantities(system: System) -> list[str]:
    """The compared columns: each line's vessel-end tension (both ends' of a line without one),
    the resultant's x and z, and each free point's x, y, z."""
    q = []
    for ln in system.lines:
        ve = system.vessel_end(ln)
        q += [f"{ln.name}.tension_{e}" for e in ((ve,) if ve else ("from", "to"))]
    return q + ["top_force_x", "top_force_z"] + [f"{p}.{a}" for p in system.free_points() for a in "xyz"]


def edit_scene(text: str, n_elements: int | None = None, time_step: float | None = None,
               line_type: Mapping[str, float] | None = None) -> str:
    """A system scene's text with every `[[line]]`'s `n_elements` set, `[analysis] time_step`
    set, and keys added to every `[[line_type]]` (e.g. drag: `cd_normal`): the variant both
    codes then read. Keys it adds must not be in the text already (TOML refuses a repeated key)."""
    import re
    if n_elements is not None:
        text, n = re.subn(r"(?m)^(\s*n_elements\s*=\s*)\d+", rf"\g<1>{int(n_elements)}", text)
        if n == 0:
            raise CaseError("edit_scene: no `n_elements` in the scene's lines")
    if line_type:
        keys = "".join(f"{k} = {v!r}\n" for k, v in line_type.items())
        text = re.sub(r"(?m)^\[\[line_type\]\]\s*\n", lambda m: m.group(0) + keys, text)
    if time_step is not None:
        if re.search(r"(?m)^\s*time_step\s*=", text):
            text = re.sub(r"(?m)^(\s*time_step\s*=\s*)[^#\n]+", rf"\g<1>{time_step!r} ", text)
        elif re.search(r"(?m)^\[analysis\]\s*$", text):
            text = re.sub(r"(?m)^\[analysis\]\s*\n", lambda m: m.group(0) + f"time_step = {time_step!r}\n", text)
        else:
            text += f"\n[analysis]\ntime_step = {time_step!r}\n"
    return text


def run_riser(riser_bin: str, scene: str | Path, out: str | Path, motions: Sequence[Motion],
              duration: float, threads: int | None = None,
              window: tuple[float, float] | None = None) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
    """`riser run SCENE --surge ... --heave ... --duration D --out OUT --json`: its
    timeseries.csv as columns and its JSON."""
    import json
    import subprocess
    args = [riser_bin, "run", str(scene)]
    for i, m in enumerate(motions):
        args += m.cli_args(ramp=(i == 0))
    args += ["--duration", f"{duration:g}", "--out", str(out), "--json"]
    if threads is not None:
        args += ["--threads", str(threads)]
    if window is not None:
        args += ["--window", f"{window[0]:g},{window[1]:g}"]
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(args)}: {p.stderr.strip()}")
    return riser_series(Path(out) / "timeseries.csv"), json.loads(p.stdout)
