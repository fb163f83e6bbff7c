"""The sweep specification: a TOML file, checked whole before any case runs.

Format (every section but ``[run]`` optional; unknown keys are errors)::

    description = "heave period x amplitude on the catenary"   # free text
    fmu = "../../fmu/riser.fmu"   # the FMU, relative to this file (default: fmu/riser.fmu
                                  # under the working directory; `--fmu` overrides both)
    scene = "catenary"            # the FMU's `scene`: a built-in (catenary, lazy_wave) or a
                                  # scene file, relative to this file; the client reads the
                                  # file and ships its text to the workers

    [parameters]                  # fixed FMU parameters, by their FMU names (see
    model = "cable"               # modelDescription/variables.csv): Real, Integer,
    n_elements = 20               # Boolean and String values
    time_step = 0.1

    [motion]                      # the hang-off motion, fed to the FMU's inputs
    heave_amplitude = 2.5         # m    (heave, surge, sway: each amplitude, period, phase;
    heave_period = 20.0           # s     amplitude 0, the default, leaves that input at 0)
    heave_phase = 0.0             # deg
    ramp = 20.0                   # s: the amplitude grows over this time (0: abrupt start)
    raos = "vessel_raos.csv"      # the vessel's RAO table, relative to this file: each case's
                                  # vessel moves on it in the case's own sea (riser_sweep.raos),
                                  # plus the harmonic motion above

    [run]
    duration = 100.0              # s (required)
    communication_step = 0.1      # s (default 0.1; the duration must be a whole number of them)
    timeout = 600.0               # s per case, checked between communication steps (default none)

    [grid]                        # the swept parameters: FMU parameters or motion keys
    mode = "product"              # full factorial (default) or "zip" (all lists of one length)
    heave_period = [10.0, 20.0]                       # a list ...
    heave_amplitude = { start = 1.0, stop = 3.0, num = 3 }   # ... or a range, stop included
    n_elements = { start = 10, stop = 40, step = 10 }        # (num: evenly spaced; step)

    [[grid.linked]]               # parameters that move together: zipped with each other,
    current_top = [0.5, 1.0]      # one axis of the product
    current_bottom = [0.5, 1.0]

    [outputs]
    window = [40.0, 100.0]        # s: the reductions' time window (default: the steady window,
                                  # from one period after the ramp to the end; see below)
    reduce = { bottom_tension = ["max"], top_force_z = ["min", "max"] }   # extra columns
    timeseries = false            # true: DIR/cases/<case>.csv with the recorded outputs

The input motion of each direction d in heave, surge, sway, sampled at the
communication points t_k = k h (k = 0 .. duration/h)::

    r(t)  = 0.5 (1 - cos(pi t / ramp))  for t < ramp, else 1
    r'(t) = 0.5 (pi / ramp) sin(pi t / ramp)  for t < ramp, else 0
    w = 2 pi / period,  p = phase in radians
    d(t)          = amplitude * r * sin(w t + p)
    d_velocity(t) = amplitude * (r' * sin(w t + p) + r * w * cos(w t + p))

(`motion_signal` in riser_sweep.case computes exactly this; the FMU reads the
velocity inputs too, so the motion between communication points is the exact
one to O(h^5)). The columns of results.csv are the swept parameters (in the
order they appear in [grid]), then ``top_tension_min``, ``top_tension_mean``,
``top_tension_max``, ``min_tension_min`` (over the window),
``energy_balance_relative`` (over the whole run, below), ``wall_s``, ``status``,
``error``, then the extra reductions ``<output>_<min|mean|max>``.

``energy_balance_relative`` is the energy balance's largest residual relative
to the energy at play, over every communication point t of the run (J; the
FMU's outputs)::

    r(t) = total_energy(t) - total_energy(0) - work_top - work_hydro - work_seabed
           + dissipated_energy + algorithmic_dissipation
    X(t) = |work_top| + |work_hydro| + |work_seabed|         (the energy exchanged)
    S(t) = kinetic_energy + |strain_energy| + |potential_energy|
    energy_balance_relative = max |r| / max(max X, 1e-8 max S)

While the line moves, X dominates (1e-8 S is 0.06 J on the catenary) and it is
``riser run --json``'s residual / exchanged. A line held still exchanges nothing,
and E(t) - E(0) still carries the round-off of the sum E = K + U + V, a few
1e-16 of S: against 1e-8 S that is below 1e-6 (the threshold of a closed
balance), where residual / exchanged was 1e7 to 1e18, relative to nothing
(issue 52). An FMU without ``work_seabed`` or the energy's terms: they count 0
and S is |total_energy|.

Without ``outputs.window`` each case's statistics are over its steady window,
as ``riser run``'s: from ``ramp`` plus the longest period of the directions
that move to the end of the run (the whole run if that leaves nothing, or
nothing moves); with ``raos``, no earlier than the waves' ramp plus their
peak period.

With ``motion.raos`` the FMU's twelve inputs (the reference point's
displacement and velocity, the angles and the angular velocity) carry the
vessel's motion on its RAOs in the case's sea, computed on the client by
``riser waves`` (riser_sweep.raos; the riser binary from $RISER_BIN, the
PATH or target/release/riser); the harmonic heave, surge and sway add to it.

A spec with a ``[fatigue]`` table is another kind: fatigue over a scatter
diagram, each sea state a ``riser run --fatigue`` (riser_sweep.fatigue).
"""

from __future__ import annotations

import difflib
import hashlib
import itertools
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

DIRECTIONS = ("heave", "surge", "sway")
MOTION_KEYS = tuple(f"{d}_{q}" for d in DIRECTIONS for q in ("amplitude", "period", "phase")) + ("ramp",)
MOTION_DEFAULTS: dict[str, float] = {k: 0.0 for k in MOTION_KEYS}
REDUCTIONS = ("min", "mean", "max")
# recorded for every case: the contract's statistics and the energy balance
BASE_OUTPUTS = ("top_tension", "min_tension", "total_energy", "work_top", "work_hydro", "dissipated_energy",
                "algorithmic_dissipation")
# and, where the FMU has them, the rest of the energy balance: the seabed's work and the energy's
# terms, the scale of a still case (riser_sweep.case.energy_balance_relative)
BALANCE_OUTPUTS = ("work_seabed", "kinetic_energy", "strain_energy", "potential_energy")
TOP_LEVEL = ("description", "fmu", "scene", "parameters", "motion", "run", "grid", "outputs")
RUN_KEYS = ("duration", "communication_step", "timeout")
OUTPUT_KEYS = ("window", "reduce", "timeseries")


class SpecError(ValueError):
    """A spec the sweep refuses; the message names the field."""


@dataclass(frozen=True)
class FmuVariables:
    """What the spec is checked against: the FMU's parameters (name -> FMI type)
    and outputs, from its modelDescription.xml."""

    parameters: dict[str, str]
    outputs: tuple[str, ...]
    inputs: tuple[str, ...]
    builtin_scenes: tuple[str, ...]

    @staticmethod
    def read(fmu: Path) -> FmuVariables:
        import zipfile

        from fmpy import read_model_description

        md = read_model_description(str(fmu))
        params = {v.name: v.type for v in md.modelVariables if v.causality == "parameter"}
        outputs = tuple(v.name for v in md.modelVariables if v.causality == "output")
        inputs = tuple(v.name for v in md.modelVariables if v.causality == "input")
        scenes: list[str] = []
        if zipfile.is_zipfile(fmu):
            with zipfile.ZipFile(fmu) as z:
                scenes = [Path(n).stem for n in z.namelist() if n.startswith("resources/") and n.endswith(".toml")]
        return FmuVariables(params, outputs, inputs, tuple(sorted(scenes)))


@dataclass(frozen=True)
class Axis:
    """One axis of the product: the names that move together and their rows of values."""

    names: tuple[str, ...]
    rows: tuple[tuple[Any, ...], ...]


@dataclass(frozen=True)
class Case:
    """One case: the swept parameters' values, in column order."""

    params: tuple[tuple[str, Any], ...]

    def as_dict(self) -> dict[str, Any]:
        return dict(self.params)

    def label(self) -> str:
        return " ".join(f"{k}={v}" for k, v in self.params) or "(the single case)"


@dataclass
class Spec:
    path: Path
    fmu: Path
    variables: FmuVariables
    fixed: dict[str, Any]                 # FMU parameters (scene included when not swept)
    motion: dict[str, float]              # every motion key, fixed values and defaults
    duration: float
    communication_step: float
    timeout: float | None
    mode: str
    axes: list[Axis]
    window: tuple[float, float] | None    # None: each case's steady window (steady_window)
    reduce: dict[str, list[str]]
    timeseries: bool
    description: str = ""
    raos: str | None = None               # the RAO table's absolute path ([motion] raos)
    scene_files: dict[str, tuple[str, str]] = field(default_factory=dict)  # value -> (file name, text)
    cases: list[Case] = field(default_factory=list)

    # ---- what the results look like -------------------------------------------------------
    @property
    def columns(self) -> list[str]:
        """The swept parameters, in column order."""
        return [n for a in self.axes for n in a.names]

    def param_type(self, name: str) -> str:
        return "Real" if name in MOTION_KEYS else self.variables.parameters[name]

    @property
    def extra_columns(self) -> list[str]:
        return [f"{name}_{op}" for name, ops in self.reduce.items() for op in ops]

    @property
    def recorded(self) -> list[str]:
        base = list(BASE_OUTPUTS) + [n for n in BALANCE_OUTPUTS if n in self.variables.outputs]
        return base + [n for n in self.reduce if n not in base]

    def fingerprint(self) -> dict[str, Any]:
        """Everything but the grid's values: a rerun into the same DIR must agree on it
        (the finished rows are identified by their swept parameters alone)."""
        return {
            "fixed": {k: _canonical(v) for k, v in sorted(self.fixed.items())},
            "scene_files": {k: hashlib.sha256(t.encode()).hexdigest() for k, (_, t) in self.scene_files.items()},
            "motion": {k: repr(v) for k, v in sorted(self.motion.items()) if k not in self.columns},
            **({"raos": hashlib.sha256(Path(self.raos).read_bytes()).hexdigest()} if self.raos else {}),
            "duration": repr(self.duration),
            "communication_step": repr(self.communication_step),
            "window": [repr(self.window[0]), repr(self.window[1])] if self.window else "steady",
            "columns": self.columns,
            "reduce": self.reduce,
        }

    # ---- the work of one case ----------------------------------------------------------------
    def job(self, case: Case) -> dict[str, Any]:
        """Everything a worker needs to run `case` (plain data: it travels to the worker)."""
        start_values = dict(self.fixed)
        motion = dict(self.motion)
        for k, v in case.params:
            (motion if k in MOTION_KEYS else start_values)[k] = v
        scene = start_values.get("scene")
        window = self.window or steady_window(motion, self.duration)
        vessel, vessel_error = None, ""
        if self.raos:
            from riser_sweep.raos import RaoError, vessel_motion

            where = str(scene)
            if scene in self.scene_files and not Path(where).is_absolute():
                where = str(self.path.resolve().parent / where)
            params = {k: v for k, v in start_values.items() if k != "scene"}
            try:
                vessel, info = vessel_motion(where, params, self.raos, self.duration, self.communication_step)
                if not self.window:
                    window = steady_window(motion, self.duration, info["ramp"] + info["tp"])
            except RaoError as e:
                vessel_error = f"motion.raos: {e}"
        return {
            "start_values": start_values,
            "scene_file": self.scene_files.get(scene) if isinstance(scene, str) else None,
            "motion": motion,
            "vessel": vessel,
            "vessel_error": vessel_error,
            "duration": self.duration,
            "communication_step": self.communication_step,
            "timeout": self.timeout,
            "window": window,
            "record": self.recorded,
            "reduce": self.reduce,
            "timeseries": self.timeseries,
        }


def steady_window(motion: dict[str, float], duration: float, sea_settled: float = 0.0) -> tuple[float, float]:
    """The steady window of a case (s), as `riser run`'s: from the ramp plus the longest
    period of the directions that move to the end, and no earlier than `sea_settled` (the
    waves' ramp plus their peak period, with RAOs); the whole run if that leaves nothing."""
    periods = [motion[f"{d}_period"] for d in DIRECTIONS if motion.get(f"{d}_amplitude", 0.0) != 0.0]
    t0 = max(motion.get("ramp", 0.0) + max(periods, default=0.0), sea_settled)
    return (t0, duration) if t0 < duration else (0.0, duration)


def _canonical(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return repr(v)
    return str(v)


def _suggest(name: str, known: list[str]) -> str:
    close = difflib.get_close_matches(name, known, n=1)
    return f"; did you mean {close[0]}?" if close else ""


def optional_timeout(table: dict[str, Any], section: str) -> float | None:
    """`table`'s `timeout`, s of wall time (> 0), or None where it is not given."""
    if "timeout" not in table:
        return None
    timeout = coerce(f"{section}.timeout", "Real", table["timeout"])
    if timeout <= 0:
        raise SpecError(f"{section}.timeout = {timeout!r}: must be > 0 (s)")
    return timeout


def coerce(where: str, ftype: str, value: Any) -> Any:
    """`value` as the FMI type `ftype` wants it, or a SpecError naming `where`."""
    if ftype == "Real":
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise SpecError(f"{where} = {value!r}: expected a number")
        x = float(value)
        if not math.isfinite(x):
            raise SpecError(f"{where} = {value!r}: expected a finite number")
        return x
    if ftype == "Integer":
        if isinstance(value, bool) or not isinstance(value, int):
            raise SpecError(f"{where} = {value!r}: expected an integer")
        return value
    if ftype == "Boolean":
        if not isinstance(value, bool):
            raise SpecError(f"{where} = {value!r}: expected true or false")
        return value
    if ftype == "String":
        if not isinstance(value, str):
            raise SpecError(f"{where} = {value!r}: expected a string")
        return value
    raise SpecError(f"{where}: the FMU's type {ftype} is not supported")


def _unknown(section: str, table: dict[str, Any], allowed: tuple[str, ...]) -> None:
    for k in table:
        if k not in allowed:
            prefix = f"{section}." if section else ""
            raise SpecError(f"{prefix}{k}: unknown key (allowed: {', '.join(allowed)}){_suggest(k, list(allowed))}")


def _values(where: str, ftype: str, raw: Any) -> list[Any]:
    """A grid entry: a non-empty list, or a range table {start, stop, step|num} (stop included)."""
    if isinstance(raw, list):
        if not raw:
            raise SpecError(f"{where}: an empty list")
        return [coerce(f"{where}[{i}]", ftype, v) for i, v in enumerate(raw)]
    if isinstance(raw, dict):
        _unknown(where, raw, ("start", "stop", "step", "num"))
        for k in ("start", "stop"):
            if k not in raw:
                raise SpecError(f"{where}.{k}: a range needs start, stop and one of step, num")
        if ("step" in raw) == ("num" in raw):
            raise SpecError(f"{where}: a range needs exactly one of step, num")
        if ftype not in ("Real", "Integer"):
            raise SpecError(f"{where}: a range needs a numeric parameter ({ftype})")
        start = coerce(f"{where}.start", ftype, raw["start"])
        stop = coerce(f"{where}.stop", ftype, raw["stop"])
        if "num" in raw:
            num = raw["num"]
            if isinstance(num, bool) or not isinstance(num, int) or num < 1:
                raise SpecError(f"{where}.num = {num!r}: expected an integer >= 1")
            if ftype == "Integer":
                raise SpecError(f"{where}: an Integer parameter takes a range with step, not num")
            if num == 1:
                return [start]
            return [start + (stop - start) * i / (num - 1) for i in range(num)]
        step = coerce(f"{where}.step", ftype, raw["step"])
        if step == 0 or (stop - start) * step < 0:
            raise SpecError(f"{where}.step = {step!r}: does not lead from {start!r} to {stop!r}")
        n = int(math.floor((stop - start) / step + 1e-9)) + 1
        if n > 1_000_000:
            raise SpecError(f"{where}: {n} values")
        return [start + i * step for i in range(n)]
    raise SpecError(f"{where} = {raw!r}: expected a list or a range table {{start, stop, step|num}}")


def read_toml(path: Path) -> dict[str, Any]:
    """A spec file's TOML, or SpecError naming the file (missing, not TOML)."""
    try:
        return tomllib.loads(path.read_text())
    except FileNotFoundError:
        raise SpecError(f"{path}: no such file") from None
    except tomllib.TOMLDecodeError as e:
        raise SpecError(f"{path}: not valid TOML: {e}") from None


def worker_failure(e: Exception, **empty: Any) -> dict[str, Any]:
    """A case's result where the worker or the cluster failed (not riser): status error, the
    exception in one line, `empty` the result's other keys."""
    return {"status": "error", "error": f"{type(e).__name__}: {e}".replace("\n", " "), "wall_s": None, **empty}


def load_spec(path: str | Path, fmu: str | Path | None = None) -> Spec:
    """Read and check a spec: names and types against the FMU's modelDescription,
    the grid's shape, the motion, the window. Raises SpecError naming the field."""
    path = Path(path)
    raw = read_toml(path)
    base = path.resolve().parent
    if "fatigue" in raw:
        raise SpecError("[fatigue]: a fatigue sweep over a scatter diagram; riser-sweep runs it, from Python "
                        "riser_sweep.fatigue.load_fatigue_spec and run_fatigue_sweep")
    _unknown("", raw, TOP_LEVEL)

    if fmu is not None:
        fmu_path = Path(fmu)
    elif "fmu" in raw:
        if not isinstance(raw["fmu"], str):
            raise SpecError(f"fmu = {raw['fmu']!r}: expected a path")
        fmu_path = base / raw["fmu"]
    else:
        fmu_path = Path("fmu/riser.fmu")
    if not fmu_path.is_file():
        raise SpecError(f"fmu: {fmu_path} is not a file (give `fmu` in the spec or --fmu; `make fmu` builds it)")
    variables = FmuVariables.read(fmu_path)
    params = variables.parameters
    known = sorted(params) + list(MOTION_KEYS)

    def check_name(where: str, name: str, motion_ok: bool = True) -> str:
        if name in params or (motion_ok and name in MOTION_KEYS):
            return "Real" if name in MOTION_KEYS else params[name]
        if name in variables.outputs or name in variables.inputs:
            kind = "an output" if name in variables.outputs else "an input (set it through [motion])"
            raise SpecError(f"{where}: {name} is {kind} of the FMU, not a parameter")
        raise SpecError(f"{where}: unknown parameter{_suggest(name, known)} "
                        f"(the FMU's parameters and the motion keys: {', '.join(known)})")

    # fixed FMU parameters
    fixed: dict[str, Any] = {}
    section = raw.get("parameters", {})
    if not isinstance(section, dict):
        raise SpecError("parameters: expected a table")
    for k, v in section.items():
        if k in MOTION_KEYS:
            raise SpecError(f"parameters.{k}: a motion key; put it in [motion]")
        if k == "scene":
            raise SpecError("parameters.scene: give the scene as the top-level `scene` (or sweep it in [grid])")
        fixed[k] = coerce(f"parameters.{k}", check_name(f"parameters.{k}", k, motion_ok=False), v)

    # motion
    motion = dict(MOTION_DEFAULTS)
    section = raw.get("motion", {})
    if not isinstance(section, dict):
        raise SpecError("motion: expected a table")
    _unknown("motion", section, MOTION_KEYS + ("raos",))
    raos = None
    for k, v in section.items():
        if k == "raos":
            if not isinstance(v, str):
                raise SpecError(f"motion.raos = {v!r}: expected the path of an RAO table (CSV)")
            p = Path(v) if Path(v).is_absolute() else base / v
            if not p.is_file():
                raise SpecError(f"motion.raos = {v!r}: {p} is not a file")
            raos = str(p.resolve())
            continue
        motion[k] = coerce(f"motion.{k}", "Real", v)

    # run
    run = raw.get("run")
    if not isinstance(run, dict):
        raise SpecError("run: the [run] table with `duration` is required")
    _unknown("run", run, RUN_KEYS)
    if "duration" not in run:
        raise SpecError("run.duration: required (s)")
    duration = coerce("run.duration", "Real", run["duration"])
    h = coerce("run.communication_step", "Real", run.get("communication_step", 0.1))
    if duration <= 0:
        raise SpecError(f"run.duration = {duration!r}: must be > 0")
    if h <= 0:
        raise SpecError(f"run.communication_step = {h!r}: must be > 0")
    n = round(duration / h)
    if n < 1 or abs(n * h - duration) > 1e-9 * duration:
        raise SpecError(f"run.duration = {duration!r}: not a whole number of communication steps ({h!r} s)")
    timeout = optional_timeout(run, "run")

    # grid
    grid = raw.get("grid", {})
    if not isinstance(grid, dict):
        raise SpecError("grid: expected a table")
    mode = grid.get("mode", "product")
    if mode not in ("product", "zip"):
        raise SpecError(f"grid.mode = {mode!r}: expected \"product\" or \"zip\"")
    axes: list[Axis] = []
    seen: dict[str, str] = {}

    def entry(where: str, name: str, rawv: Any) -> list[Any]:
        ftype = check_name(where, name)
        if name in seen:
            raise SpecError(f"{where}: {name} is swept twice (also {seen[name]})")
        if name in fixed:
            raise SpecError(f"{where}: {name} is also fixed in [parameters]")
        if name in section_motion or name == "raos":
            raise SpecError(f"{where}: {name} is also fixed in [motion]")
        if name == "scene" and "scene" in raw:
            raise SpecError(f"{where}: scene is also the top-level `scene`")
        seen[name] = where
        return _values(where, ftype, rawv)

    section_motion = raw.get("motion", {})
    for k, v in grid.items():
        if k in ("mode", "linked"):
            continue
        vals = entry(f"grid.{k}", k, v)
        axes.append(Axis((k,), tuple((x,) for x in vals)))
    linked = grid.get("linked", [])
    if not isinstance(linked, list) or not all(isinstance(g, dict) for g in linked):
        raise SpecError("grid.linked: expected [[grid.linked]] tables")
    for i, g in enumerate(linked):
        if not g:
            raise SpecError(f"grid.linked[{i}]: empty")
        cols = {k: entry(f"grid.linked[{i}].{k}", k, v) for k, v in g.items()}
        lengths = {k: len(v) for k, v in cols.items()}
        if len(set(lengths.values())) > 1:
            raise SpecError(f"grid.linked[{i}]: linked lists differ in length: "
                            + ", ".join(f"{k} has {n}" for k, n in lengths.items()))
        axes.append(Axis(tuple(cols), tuple(zip(*cols.values()))))
    if mode == "zip" and axes:
        lengths = {"/".join(a.names): len(a.rows) for a in axes}
        if len(set(lengths.values())) > 1:
            raise SpecError("grid: mode = \"zip\" needs lists of one length: "
                            + ", ".join(f"{k} has {n}" for k, n in lengths.items()))
        names = tuple(n for a in axes for n in a.names)
        rows = tuple(tuple(x for r in rs for x in r) for rs in zip(*(a.rows for a in axes)))
        axes = [Axis(names, rows)]

    # outputs
    outputs = raw.get("outputs", {})
    if not isinstance(outputs, dict):
        raise SpecError("outputs: expected a table")
    _unknown("outputs", outputs, OUTPUT_KEYS)
    window = None
    if "window" in outputs:
        w = outputs["window"]
        if not isinstance(w, list) or len(w) != 2:
            raise SpecError(f"outputs.window = {w!r}: expected [start, end] in s")
        window = (coerce("outputs.window[0]", "Real", w[0]), coerce("outputs.window[1]", "Real", w[1]))
        if not (0.0 <= window[0] < window[1] <= duration * (1 + 1e-12)):
            raise SpecError(f"outputs.window = {w!r}: needs 0 <= start < end <= run.duration ({duration!r})")
    reduce: dict[str, list[str]] = {}
    red = outputs.get("reduce", {})
    if not isinstance(red, dict):
        raise SpecError("outputs.reduce: expected a table {output = [\"min\", \"mean\", \"max\"]}")
    for name, ops in red.items():
        if name not in variables.outputs:
            raise SpecError(f"outputs.reduce.{name}: not an output of the FMU{_suggest(name, list(variables.outputs))}")
        if isinstance(ops, str):
            ops = [ops]
        if not isinstance(ops, list) or not ops or any(o not in REDUCTIONS for o in ops):
            raise SpecError(f"outputs.reduce.{name} = {ops!r}: expected a list of min, mean, max")
        contract = {"top_tension": REDUCTIONS, "min_tension": ("min",)}.get(name, ())
        ops = [o for o in dict.fromkeys(ops) if o not in contract]
        if ops:
            reduce[name] = ops
    timeseries = outputs.get("timeseries", False)
    if not isinstance(timeseries, bool):
        raise SpecError(f"outputs.timeseries = {timeseries!r}: expected true or false")

    description = raw.get("description", "")
    if not isinstance(description, str):
        raise SpecError("description: expected a string")

    if "scene" in raw:
        fixed["scene"] = coerce("scene", "String", raw["scene"])
    elif "scene" not in seen:
        fixed["scene"] = "catenary"

    spec = Spec(path=path, fmu=fmu_path, variables=variables, fixed=fixed, motion=motion, duration=duration,
                communication_step=h, timeout=timeout, mode=mode, axes=axes, window=window, reduce=reduce,
                timeseries=timeseries, description=description, raos=raos)
    _resolve_scenes(spec, base, "scene" in raw)
    spec.cases = _expand(spec)
    return spec


def _resolve_scenes(spec: Spec, base: Path, top_level: bool) -> None:
    """Each scene value: a built-in of the FMU, or a file (relative to the spec) whose
    text travels to the workers."""
    values = [(("scene" if top_level else "parameters.scene"), spec.fixed["scene"])] if "scene" in spec.fixed else []
    for a in spec.axes:
        if "scene" in a.names:
            j = a.names.index("scene")
            values += [(f"grid.scene[{i}]", r[j]) for i, r in enumerate(a.rows)]
    for where, v in values:
        if v in spec.variables.builtin_scenes or v in spec.scene_files:
            continue
        p = Path(v) if Path(v).is_absolute() else base / v
        if not p.is_file():
            raise SpecError(f"{where} = {v!r}: neither a built-in scene ({', '.join(spec.variables.builtin_scenes)}) "
                            f"nor a file ({p})")
        spec.scene_files[v] = (p.name, p.read_text())


def _expand(spec: Spec) -> list[Case]:
    cases = []
    seen: set[tuple[str, ...]] = set()
    for combo in itertools.product(*(a.rows for a in spec.axes)):
        params = tuple((n, v) for a, row in zip(spec.axes, combo) for n, v in zip(a.names, row))
        key = tuple(_canonical(v) for _, v in params)
        if key in seen:
            raise SpecError(f"grid: the case {' '.join(f'{n}={v}' for n, v in params)} comes twice")
        seen.add(key)
        _check_motion(spec, dict(params))
        cases.append(Case(params))
    return cases


def _check_motion(spec: Spec, swept: dict[str, Any]) -> None:
    m = dict(spec.motion)
    m.update({k: v for k, v in swept.items() if k in MOTION_KEYS})

    def where(k: str) -> str:
        return f"grid.{k} = {m[k]!r}" if k in swept else f"motion.{k} = {m[k]!r}"

    if m["ramp"] < 0:
        raise SpecError(f"{where('ramp')}: must be >= 0")
    for d in DIRECTIONS:
        if m[f"{d}_amplitude"] != 0 and m[f"{d}_period"] <= 0:
            raise SpecError(f"{where(d + '_period')}: must be > 0 when {d}_amplitude is not 0")


def check_values_with_fmu(spec: Spec, unzipdir: str) -> None:
    """Let the FMU refuse bad values before any case runs: each distinct value of
    every parameter is set once in an instance in initialization mode (the FMU checks
    ranges in fmi2SetReal/Integer/Boolean/String and names the allowed range). What
    only the whole case can tell (statics that fail, a scene a line cannot reach) is
    a case's error row instead."""
    from fmpy import read_model_description
    from riser_tools.fmpy_logging import instantiate_logged

    md = read_model_description(unzipdir)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    todo: list[tuple[str, str, Any]] = [(f"parameters.{k}", k, v) for k, v in spec.fixed.items() if k != "scene"]
    for a in spec.axes:
        for j, name in enumerate(a.names):
            if name in MOTION_KEYS or name == "scene":
                continue
            firsts: dict[str, int] = {}
            for i, row in enumerate(a.rows):
                firsts.setdefault(_canonical(row[j]), i)
            todo += [(f"grid.{name}[{i}]", name, a.rows[i][j]) for i in firsts.values()]
    messages: list[str] = []

    def logger(_env: Any, _name: Any, status: int, _category: Any, message: bytes) -> None:
        if status >= 3:
            messages.append(message.decode(errors="replace"))

    fmu = None
    try:
        for where, name, value in todo:
            if fmu is None:
                fmu = instantiate_logged(unzipdir, md, logger)
                fmu.setupExperiment(startTime=0.0)
                fmu.enterInitializationMode()
            ftype = spec.variables.parameters[name]
            setter = {"Real": fmu.setReal, "Integer": fmu.setInteger, "Boolean": fmu.setBoolean,
                      "String": fmu.setString}[ftype]
            messages.clear()
            try:
                setter([vr[name]], [value])
            except Exception as e:  # the FMU said fmi2Error: its message says why
                fmu.freeInstance()
                fmu = None
                why = " ".join(messages).replace("\n", " ") or str(e)
                raise SpecError(f"{where} = {value!r}: refused by the FMU: {why}") from None
    finally:
        if fmu is not None:
            fmu.freeInstance()
