"""The one MoorDyn v2 driver (the Python package `moordyn`, MoorDyn-C) used by
every peer comparison: a `Line` written as a MoorDyn input file, MoorDyn's
static state, and a run with the fairlead driven along a `Motion`.

How MoorDyn is driven: the fairlead is a `Coupled` point; MoorDyn moves a
coupled point linearly over each `Step` call (x + v (t - t_start)), so the
driver calls `moordyn.Step` once per internal step (coupling step = dtM,
unless asked otherwise) with the exact position at the start of the step and
the secant velocity (x(t + dtc) - x(t)) / dtc, which lands the point exactly
on x(t + dtc). The force `Step` returns is the net force of the line's end node
on the coupled point (weight and buoyancy as distributed loads: an effective
tension like riser's `top_tension`); it leaves out the driven end node's
inertia (`support_force` adds it back).

MoorDyn's frame has z = 0 at the water surface; riser's has the hang-off at
the origin and the surface at `line.surface_z`: the fairlead is at
(0, 0, -surface_z) in MoorDyn's.

The C++ library prints to fds 1 and 2: every call here runs inside `quiet`,
which sends that to a log file beside the input.
"""

from __future__ import annotations

import contextlib
import ctypes
import math
import os
import statistics
import sys
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .cases import CaseError, Line, Motion

# options every driver run sets: no output files from MoorDyn itself
NO_OUTPUT = {"disableOutput": 1, "disableOutTime": 1}


def coupling_calls(dtm: float, coupling: int, sample: float, duration: float) -> tuple[float, int, int]:
    """The coupling step dtc = `coupling` MoorDyn steps of `dtm` s, the calls per output
    `sample` (refused unless a whole number) and the calls in `duration`."""
    dtc = dtm * coupling
    per_sample = int(round(sample / dtc))
    if per_sample < 1 or abs(per_sample * dtc - sample) > 1e-9 * sample:
        raise CaseError(f"moordyn.sample = {sample!r}: not a whole number of coupling steps {dtc!r}")
    return dtc, per_sample, int(round(duration / dtc))


def _moordyn():
    import moordyn  # imported on use: the rest of riser_tools runs without it
    return moordyn


@contextlib.contextmanager
def quiet(log_path: str | Path) -> Iterator[None]:
    """Send the C++ library's console output (fd 1 and 2) to a log file."""
    libc = ctypes.CDLL(None)
    sys.stdout.flush()
    sys.stderr.flush()
    saved = os.dup(1), os.dup(2)
    with open(log_path, "a") as log:
        os.dup2(log.fileno(), 1)
        os.dup2(log.fileno(), 2)
        try:
            yield
        finally:
            libc.fflush(None)
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])


def external_wave_run(input_path: str | Path, point: int, line: int,
                      kinematics: Callable[[float, list[float]], tuple[list[float], list[float]]],
                      duration: float, dt: float, log: str | Path) -> list[tuple[float, float]] | None:
    """A MoorDyn system with its point `point` held where the input file puts it and the water's
    kinematics given from outside (`kinematics(t, position) -> (velocity, acceleration)` at the
    middle of each step, MoorDyn's ExternalWaveKin): (t, the force at line `line`'s last node, kN)
    after every step of `dt` up to `duration`; None if `moordyn` does not import."""
    try:
        md = _moordyn()
    except ImportError:
        return None
    rows = []
    with quiet(log):
        system = md.Create(str(input_path))
        p, ln = md.GetPoint(system, point), md.GetLine(system, line)
        r, u = list(md.GetPointPos(p)), [0.0, 0.0, 0.0]
        md.Init(system, r, u)
        md.ExternalWaveKinInit(system)
        n = md.GetLineN(ln)
        t = 0.0
        for _ in range(int(round(duration / dt))):
            kin = [kinematics(t + 0.5 * dt, q) for q in md.ExternalWaveKinGetCoordinates(system)]
            md.ExternalWaveKinSet(system, [k[0] for k in kin], [k[1] for k in kin], t + 0.5 * dt)
            md.Step(system, r, u, t, dt)
            t += dt
            rows.append((t, 1e-3 * math.sqrt(sum(c * c for c in md.GetLineNodeForce(ln, n)))))
        md.Close(system)
    return rows


def fairlead(line: Line) -> tuple[float, float, float]:
    """The hang-off in MoorDyn's frame."""
    return (0.0, 0.0, -line.surface_z)


def anchor(line: Line) -> tuple[float, float, float]:
    """The anchor in MoorDyn's frame."""
    return (line.anchor[0], line.anchor[1], line.anchor[2] - line.surface_z)


def water_depth(line: Line, default: float = 200.0) -> float:
    """MoorDyn's WtrDpth: the seabed below the surface, or `default` for a line without one."""
    return line.surface_z - line.seabed_z if line.seabed_z is not None else default


def cd_axial(line: Line) -> float:
    """MoorDyn's CdAx is on the wetted surface pi D, riser's C_Dt on D."""
    return line.cd_tangential / math.pi


def input_text(line: Line, nseg: int, dtm: float, options: Mapping[str, Any] = NO_OUTPUT, ba: float = 0.0,
               ei: float | None = None, depth: float | None = None, currents: bool = False,
               title: str = "riser_tools.moordyn") -> str:
    """A MoorDyn v2 input file: one line of `nseg` segments from the anchor (point 1, Fixed)
    to the fairlead (point 2, Coupled); OPTIONS dtM, g, rho, WtrDpth, [Currents 1,] then
    `options` in their order. dtM is written with repr() so that MoorDyn reads back the very
    double the driver passes as the coupling step (a dtM rounded below it would add a tiny
    extra internal step per call). `ba`: internal damping BA (N s, or -zeta)."""
    if not isinstance(nseg, int) or nseg < 1:
        raise CaseError(f"moordyn.nseg = {nseg!r}: expected an integer >= 1")
    if not (isinstance(dtm, float) and math.isfinite(dtm) and dtm > 0):
        raise CaseError(f"moordyn.dtm = {dtm!r}: expected a number > 0")
    ei = line.ei if ei is None else ei
    opts: dict[str, Any] = {"dtM": repr(dtm), "g": line.gravity, "rho": line.rho_water,
                            "WtrDpth": water_depth(line) if depth is None else depth}
    if currents:
        opts["Currents"] = 1
    opts.update(options)
    extra = "\n".join(f"{v:<14} {k}" for k, v in opts.items())
    a, f = anchor(line), fairlead(line)
    return f"""--------------------- MoorDyn Input File ------------------------------------
{title}
---------------------- LINE TYPES ----------------------------------------------------------------------
TypeName   Diam      Mass/m     EA           BA/-zeta     EI           Cd     Ca     CdAx          CaAx
(name)     (m)       (kg/m)     (N)          (N-s/-)      (N-m^2)      (-)    (-)    (-)           (-)
riser      {line.diameter}    {line.mass}     {line.ea:.6e}   {ba:.6e}   {ei:.6e}   {line.cd_normal}    {line.ca_normal}    {cd_axial(line):.10f}  0.0
---------------------- POINTS ---------------------------------------
ID   Attachment  X       Y     Z      Mass   Volume  CdA    Ca
(#)   (word/ID)  (m)     (m)   (m)    (kg)   (m^3)   (m^2)  (-)
1     Fixed      {a[0]}    {a[1]}   {a[2]}    0      0       0      0
2     Coupled    {f[0]}     {f[1]}   {f[2]}    0      0       0      0
---------------------- LINES ----------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (ID)     (ID)      (m)       (-)      (-)
1     riser       1        2        {line.length}     {nseg}       -
---------------------- OPTIONS -----------------------------------------
{extra}
--------------------- need this line ------------------
"""


def write_input(path: str | Path, line: Line, nseg: int, dtm: float, options: Mapping[str, Any] = NO_OUTPUT,
                ba: float = 0.0, ei: float | None = None, depth: float | None = None,
                current: float | None = None, title: str = "riser_tools.moordyn") -> Path:
    """`input_text` to `path` (its folder made); with `current` (m/s along +x, uniform) also the
    steady profile current_profile.txt beside it that `Currents 1` reads."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    d = water_depth(line) if depth is None else depth
    path.write_text(input_text(line, nseg, dtm, options, ba, ei, d, current is not None, title))
    if current is not None:
        (path.parent / "current_profile.txt").write_text(
            "--------------------- MoorDyn steady currents File ----------------------------------\n"
            "Uniform current along +x\n"
            "z (m), ux (m/s), uy (m/s), uz (m/s)\n"
            f"-{d + 100:g} {current} 0 0\n"
            f"0.0 {current} 0 0\n")
    return path


def touchdown(line_handle: Any, nseg: int, length: float, seabed_z: float) -> float:
    """riser's definition (src/loads/seabed.rs `touchdown`) on MoorDyn's nodes: from the
    fairlead (node N), the first node below the seabed (`seabed_z` in MoorDyn's frame), the
    crossing interpolated linearly in the penetration from the node before it; arc length =
    unstretched distance from the fairlead; the length when no node touches."""
    md = _moordyn()
    ds = length / nseg
    before = -math.inf
    for j, i in enumerate(range(nseg, -1, -1)):
        d = seabed_z - md.GetLineNodePos(line_handle, i)[2]
        if d > 0.0:
            if j == 0:
                return 0.0
            w = -before / (d - before)
            return (j - 1) * ds + w * ds
        before = d
    return length


@dataclass
class Static:
    """MoorDyn's static state: the force of the line on the fairlead (N, MoorDyn's frame: x
    towards the anchor's side, z up), its node positions (MoorDyn's frame, anchor first)."""

    force: np.ndarray
    nodes: np.ndarray
    seconds: float
    state: Path | None = None

    @property
    def tension(self) -> float:
        return float(np.linalg.norm(self.force))

    @property
    def horizontal(self) -> float:
        """H: the horizontal force on the fairlead (N)."""
        return float(math.hypot(self.force[0], self.force[1]))

    @property
    def vertical(self) -> float:
        """V: the downward pull of the line on the fairlead (N)."""
        return float(-self.force[2])


def static_state(input_path: str | Path, line: Line, nseg: int, save: str | Path | None = None) -> Static:
    """Create and Init (MoorDyn's initial-condition solver, as its OPTIONS ask), the fairlead
    force by a Step of dt = 0, the nodes; with `save`, SaveState there."""
    md = _moordyn()
    input_path = Path(input_path)
    x0 = list(fairlead(line))
    t0 = time.perf_counter()
    with quiet(input_path.parent / "moordyn.log"):
        s = md.Create(str(input_path))
        try:
            md.Init(s, x0, [0.0, 0.0, 0.0])
            f = md.Step(s, x0, [0.0, 0.0, 0.0], 0.0, 0.0)
            handle = md.GetLine(s, 1)
            nodes = np.array([md.GetLineNodePos(handle, i) for i in range(nseg + 1)])
            if save is not None:
                md.SaveState(s, str(save))
        finally:
            md.Close(s)
    return Static(np.asarray(f, dtype=float), nodes, time.perf_counter() - t0, Path(save) if save else None)


@dataclass
class MoorDynRun:
    """A MoorDyn run on the output grid t = k * sample: the fairlead force F (N, rows x, y, z;
    NaN after a failure), its magnitude T, the touchdown (when asked), whether it completed,
    the loop wall times of the repeats (Create/Init excluded) and the cost of the Python call."""

    t: np.ndarray
    F: np.ndarray
    T: np.ndarray
    td: np.ndarray | None
    ok: bool
    t_fail: float
    walls: list[float]
    dtm: float
    steps: int
    T0: float
    ic_time: float
    per_call: float = 0.0
    overhead: float = 0.0
    motion: Motion | None = None
    input: Path | None = None
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def wall(self) -> float:
        return statistics.median(self.walls)


def run(input_path: str | Path, line: Line, nseg: int, motion: Motion, duration: float, dtm: float,
        sample: float, coupling: int = 1, state: str | Path | None = None, T0: float = float("nan"),
        repeats: int = 1, cheap: float = float("inf"), probe_overhead: bool = False,
        record_touchdown: bool = False, blow_up: float = 1e8) -> MoorDynRun:
    """One MoorDyn run of `duration` s with internal step `dtm` and `coupling` internal steps
    per `Step` call, the fairlead moved along `motion`; outputs every `sample` s (a whole number
    of calls). From `state` (a SaveState file, loaded after Init_NoIC; its tension `T0` given)
    or from MoorDyn's own initial-condition solver (Init). A run that raises, or whose force
    exceeds `blow_up` N or is NaN, stops there (ok False). `repeats`: run again for a median
    wall time unless it took more than `cheap` s or failed. `probe_overhead`: time the same
    calls with dt = 0 (MoorDyn then only returns the forces) as the cost of the call itself."""
    md = _moordyn()
    dtc, per_sample, ncalls = coupling_calls(dtm, coupling, sample, duration)
    t_calls = np.arange(ncalls) * dtc
    u0 = motion.displacement(t_calls)
    u1 = motion.displacement(t_calls + dtc)
    x = np.tile(np.array(fairlead(line)), (ncalls, 1))
    x[:, motion.index] += u0
    v = np.zeros((ncalls, 3))
    v[:, motion.index] = (u1 - u0) / dtc
    xs, vs, ts = x.tolist(), v.tolist(), t_calls.tolist()
    x0 = list(fairlead(line))
    nout = int(round(duration / sample))
    seabed = line.seabed_z - line.surface_z if (record_touchdown and line.seabed_z is not None) else None
    input_path = Path(input_path)
    walls: list[float] = []
    per_call = 0.0
    calls = 0
    for _ in range(max(1, repeats)):
        F = np.full((nout + 1, 3), np.nan)
        T = np.full(nout + 1, np.nan)
        td = np.full(nout + 1, np.nan) if seabed is not None else None
        ok, t_fail = True, float("nan")
        with quiet(input_path.parent / "moordyn.log"):
            t0 = time.perf_counter()
            s = md.Create(str(input_path))
            handle = md.GetLine(s, 1) if seabed is not None else None
            if state is not None:
                md.Init_NoIC(s, x0, [0.0, 0.0, 0.0])
                md.LoadState(s, str(state))
                T[0] = T0
            else:
                md.Init(s, x0, [0.0, 0.0, 0.0])
                F[0] = md.Step(s, x0, [0.0, 0.0, 0.0], 0.0, 0.0)
                T[0] = np.linalg.norm(F[0])
            if td is not None:
                td[0] = touchdown(handle, nseg, line.length, seabed)
            ic_time = time.perf_counter() - t0
            step = md.Step
            t0 = time.perf_counter()
            calls = 0
            try:
                j = 0
                for i in range(ncalls):
                    calls = i + 1
                    f = step(s, xs[i], vs[i], ts[i], dtc)
                    if (i + 1) % per_sample == 0:
                        j += 1
                        T[j] = math.sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2])
                        F[j] = f
                        if td is not None:
                            td[j] = touchdown(handle, nseg, line.length, seabed)
                        if not T[j] < blow_up:          # NaN or blown up
                            ok, t_fail = False, ts[i]
                            break
            except RuntimeError:
                ok, t_fail = False, ts[calls - 1]
            wall = time.perf_counter() - t0
            if probe_overhead:
                n_probe = min(ncalls, 20000)
                t1 = time.perf_counter()
                for i in range(n_probe):
                    step(s, xs[i], vs[i], ts[i], 0.0)
                per_call = (time.perf_counter() - t1) / n_probe
            md.Close(s)
        walls.append(wall)
        if not ok or wall > cheap:
            break
    return MoorDynRun(t=np.arange(nout + 1) * sample, F=F, T=T, td=td, ok=ok, t_fail=t_fail, walls=walls,
                      dtm=dtm, steps=calls * coupling, T0=float(T[0]), ic_time=ic_time, per_call=per_call,
                      overhead=per_call * calls, motion=motion, input=input_path)


def support_force(r: MoorDynRun, line: Line, nseg: int) -> np.ndarray:
    """MoorDyn's end force with its end node's inertia added back, |F - M a| with M = m l / 2
    and a the fairlead's acceleration: the force the support must give, as riser's hang-off
    reaction includes it."""
    assert r.motion is not None
    m_end = 0.5 * line.mass * line.length / nseg
    f = r.F.copy()
    f[:, r.motion.index] -= m_end * r.motion.acceleration(r.t)
    return np.linalg.norm(f, axis=1)


def damping_dt(line: Line, nseg: int, ba: float) -> float:
    """m l^2 / (2 BA): the explicit-integration limit set by the axial damping."""
    return line.mass * (line.length / nseg) ** 2 / (2.0 * ba) if ba > 0 else math.inf


def wave_dt(line: Line, nseg: int) -> float:
    """l / c: the limit set by the axial waves."""
    return (line.length / nseg) / line.wave_speed
