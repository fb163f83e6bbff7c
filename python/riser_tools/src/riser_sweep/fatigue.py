"""Fatigue over a scatter diagram: each sea state a `riser run --fatigue` on a Dask worker, the
annual damage combined point by point along the line (issue 50; docs/guide/sweeps.md "Fatigue
over a scatter diagram", docs/guide/design.md).

A spec with a ``[fatigue]`` table is a fatigue sweep (``riser-sweep SPEC --out DIR``)::

    description = "the 1,000 m SCR over its scatter diagram"
    scene = "scr_1000m.toml"         # a built-in of riser or a scene file, relative to this file

    [parameters]                     # riser's --set names (`riser params SCENE`), fixed for every state
    n_elements = 300
    wave_components = 200

    [motion]
    raos = "semi_raos.csv"           # the vessel's RAO table (default: the scene's [vessel] raos)

    [fatigue]
    curve = "D-seawater-cp"          # DNV-RP-C203 S-N curve (riser run --fatigue's names)
    scf = 1.0                        # >= 1 (default 1)
    dff = 10.0                       # >= 1 (default 1): life = 1 / (DFF max D_year)
    scatter = "scatter.csv"          # the sea states, relative to this file (below)
    duration = 10800.0               # s: each sea state's run (the damage counts over its steady window)
    touchdown_zone = 50.0            # m (default 50): the touchdown zone is S_td +- this
    timeout = 7200.0                 # s of wall time per sea state (default none)

The scatter file (CSV; ``#`` lines and blank lines skipped; columns in any order)::

    hs,tp,probability,gamma,direction
    1.5,7.0,0.40,3.3,180
    ...

``hs`` (m, > 0), ``tp`` (s, > 0), ``probability`` (the fraction of the year, >= 0),
optional ``gamma`` (JONSWAP's, 1 to 10; default the scene's) and ``direction`` (deg, the
waves' direction of travel, -360 to 360; default the scene's). A state steeper than
DNV-RP-C205's limiting average steepness S_p = 2 pi Hs / (g Tp^2) (1/15 at Tp <= 8 s, 1/25 at
Tp >= 15 s, linear between) is refused; probabilities that do not sum to 1 (within 1e-6) are
warned of (the annual damage is still the sum as given).

Each state runs ``riser run SCENE --set ... --set wave_kind=jonswap --set wave_hs=.. --set
wave_tp=.. [--set wave_gamma=..] [--set wave_direction=..] --raos RAOS --duration D --fatigue
CURVE --scf X --dff Y --json --out TMP`` on a worker; the client keeps its JSON and fatigue.csv
(DIR/cases/<state>/) and combines, at every point S and fibre of the line::

    D_year(S, fibre) = sum_i p_i * (D_i(S, fibre) * T_year / T_i)     T_year = 365.25 days
    life = 1 / (max D_year * DFF)

with T_i the state's steady window (``window_length``), the sum in the scatter file's order (the
same bits on any number of workers). One state of probability 1 gives `riser run`'s
``damage_per_year`` and ``life_years`` exactly.
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
import math
import os
import shutil
import stat
import subprocess
import sys
import tempfile
import time
import tomllib
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TextIO

import numpy as np
from distributed import WorkerPlugin

from .spec import SpecError, _suggest, _unknown, coerce, optional_timeout, read_toml, worker_failure

SECONDS_PER_YEAR = 365.25 * 86_400.0  # riser's (src/sim/fatigue.rs)
SCATTER_REQUIRED = ("hs", "tp", "probability")
SCATTER_OPTIONAL = ("gamma", "direction")
FATIGUE_TOP = ("description", "scene", "parameters", "motion", "fatigue")
FATIGUE_KEYS = ("curve", "scf", "dff", "scatter", "duration", "touchdown_zone", "timeout")
PROBABILITY_SUM_TOLERANCE = 1e-6
TOUCHDOWN_ZONE_DEFAULT = 50.0
# the sea state's own keys: the scatter file sets them, [parameters] may not
STATE_PARAMETERS = ("wave_kind", "wave_hs", "wave_tp")
RESULT_COLUMNS = ["row", "hs", "tp", "probability", "gamma", "direction", "window_s", "damage",
                  "damage_per_year", "damage_per_year_weighted", "worst_s", "worst_fibre", "share_at_worst",
                  "wall_s", "status", "error"]


class ScatterError(SpecError):
    """A scatter file the sweep refuses; the message names the row and column."""


def steepness_limit(tp: float) -> float:
    """DNV-RP-C205's limiting average steepness S_p = 2 pi Hs / (g Tp^2) of a sea state:
    1/15 for Tp <= 8 s, 1/25 for Tp >= 15 s, linear in Tp between."""
    if tp <= 8.0:
        return 1.0 / 15.0
    if tp >= 15.0:
        return 1.0 / 25.0
    return 1.0 / 15.0 + (1.0 / 25.0 - 1.0 / 15.0) * (tp - 8.0) / 7.0


@dataclass(frozen=True)
class SeaState:
    row: int              # 1-based among the data rows
    line: int             # the file's line number
    hs: float
    tp: float
    probability: float
    gamma: float | None
    direction: float | None

    def label(self) -> str:
        extra = (f" gamma={self.gamma!r}" if self.gamma is not None else "") + \
            (f" direction={self.direction!r}" if self.direction is not None else "")
        return f"row {self.row}: hs={self.hs!r} tp={self.tp!r} p={self.probability!r}{extra}"

    def name(self) -> str:
        return f"{self.row:03d}_hs={self.hs!r}_tp={self.tp!r}"

    def sets(self) -> list[str]:
        out = ["wave_kind=jonswap", f"wave_hs={self.hs!r}", f"wave_tp={self.tp!r}"]
        if self.gamma is not None:
            out.append(f"wave_gamma={self.gamma!r}")
        if self.direction is not None:
            out.append(f"wave_direction={self.direction!r}")
        return out


def read_scatter(path: str | Path) -> tuple[list[SeaState], list[str]]:
    """The sea states of a scatter file and its warnings (probabilities not summing to 1).
    Raises ScatterError naming the row (and its line) and the column."""
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as e:
        raise ScatterError(f"{path}: cannot read: {e.strerror}") from None
    lines = [(i + 1, ln) for i, ln in enumerate(text.splitlines()) if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        raise ScatterError(f"{path}: no header and no sea states")
    head_line, head_text = lines[0]
    header = [h.strip() for h in next(csv.reader([head_text]))]
    known = list(SCATTER_REQUIRED + SCATTER_OPTIONAL)
    for h in header:
        if h not in known:
            raise ScatterError(f"{path} line {head_line}: unknown column {h!r} (columns: hs, tp, probability and "
                               f"optionally gamma, direction){_suggest(h, known)}")
    if len(set(header)) != len(header):
        raise ScatterError(f"{path} line {head_line}: a column comes twice ({', '.join(header)})")
    missing = [c for c in SCATTER_REQUIRED if c not in header]
    if missing:
        raise ScatterError(f"{path} line {head_line}: missing column{'s' if len(missing) > 1 else ''} "
                           f"{', '.join(missing)} (the header has {', '.join(header)})")
    states: list[SeaState] = []
    for row, (ln, t) in enumerate(lines[1:], start=1):
        where = f"{path} row {row} (line {ln})"
        cells = [c.strip() for c in next(csv.reader([t]))]
        if len(cells) != len(header):
            raise ScatterError(f"{where}: {len(cells)} values for the {len(header)} columns {', '.join(header)}")
        v: dict[str, float] = {}
        for c, s in zip(header, cells):
            try:
                x = float(s)
            except ValueError:
                raise ScatterError(f"{where}, column {c}: {s!r} is not a number") from None
            if not math.isfinite(x):
                raise ScatterError(f"{where}, column {c}: {s!r} is not a finite number")
            v[c] = x
        hs, tp, p = v["hs"], v["tp"], v["probability"]
        if p < 0:
            raise ScatterError(f"{where}, column probability: {p!r} is negative")
        if p > 1:
            raise ScatterError(f"{where}, column probability: {p!r} is more than the whole year (1)")
        if hs <= 0:
            raise ScatterError(f"{where}, column hs: {hs!r} m; a sea state needs hs > 0 (calm water does no damage: "
                               "leave the row out)")
        if tp <= 0:
            raise ScatterError(f"{where}, column tp: {tp!r} s; needs tp > 0")
        sp = 2 * math.pi * hs / (9.81 * tp * tp)
        lim = steepness_limit(tp)
        if sp > lim:
            tp_min = tp
            while 2 * math.pi * hs / (9.81 * tp_min * tp_min) > steepness_limit(tp_min):
                tp_min += 0.01
            raise ScatterError(f"{where}, column tp: Tp = {tp!r} s is too short for Hs = {hs!r} m: the steepness "
                               f"2 pi Hs / (g Tp^2) = 1/{1 / sp:.1f} exceeds DNV-RP-C205's limit 1/{1 / lim:.1f} "
                               f"(a sea that breaks; Tp >= {tp_min:.2f} s for this Hs)")
        gamma = v.get("gamma")
        if gamma is not None and not (1.0 <= gamma <= 10.0):
            raise ScatterError(f"{where}, column gamma: {gamma!r}; JONSWAP's peak enhancement is 1 to 10")
        direction = v.get("direction")
        if direction is not None and not (-360.0 <= direction <= 360.0):
            raise ScatterError(f"{where}, column direction: {direction!r} deg; within -360 to 360")
        states.append(SeaState(row, ln, hs, tp, p, gamma, direction))
    if not states:
        raise ScatterError(f"{path}: a header and no sea states")
    warnings = []
    total = math.fsum(s.probability for s in states)
    if abs(total - 1.0) > PROBABILITY_SUM_TOLERANCE:
        warnings.append(f"{path}: the probabilities sum to {total!r}, not 1: the annual damage is the sum as "
                        "given (a scatter diagram of part of the year, or a mistake)")
    return states, warnings


# ---- the spec -------------------------------------------------------------------------------------

def is_fatigue_spec(path: str | Path) -> bool:
    """Whether the TOML at `path` has a [fatigue] table (unreadable: False, load_spec says why)."""
    try:
        return "fatigue" in tomllib.loads(Path(path).read_text())
    except (OSError, tomllib.TOMLDecodeError):
        return False


def riser_binary(given: str | None = None) -> str:
    """--riser-bin, else $RISER_BIN, else `riser` on the PATH, else target/release/riser."""
    if given is not None:
        if not Path(given).is_file():
            raise SpecError(f"--riser-bin {given}: not a file")
        return str(Path(given).resolve())
    for cand in (os.environ.get("RISER_BIN"), shutil.which("riser"), "target/release/riser"):
        if cand and Path(cand).is_file():
            return str(Path(cand).resolve())
    raise SpecError("a fatigue sweep runs the riser CLI: give --riser-bin, set RISER_BIN, put riser on the PATH, "
                    "or build target/release/riser (cargo build --release)")


def _text(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return repr(v) if isinstance(v, float) else str(v)


@dataclass
class FatigueSpec:
    path: Path
    binary: str
    scene: str                              # a built-in's name or the scene file's name
    scene_file: tuple[str, str] | None      # (file name, text), shipped to the workers
    extra_files: dict[str, str]             # the scene's own relative files (its [vessel] raos): path -> text
    parameters: dict[str, Any]
    raos: tuple[str, str] | None            # (file name, text) of the RAO table, --raos
    curve: str
    scf: float
    dff: float
    scatter: Path
    states: list[SeaState]
    duration: float
    touchdown_zone: float
    timeout: float | None
    description: str = ""
    warnings: list[str] = field(default_factory=list)
    static_touchdown_s: float | None = None  # the static state's, from the check run

    def args(self, state: SeaState) -> list[str]:
        """`riser run`'s arguments after the scene, but --out."""
        sets = [f"{k}={_text(v)}" for k, v in sorted(self.parameters.items())] + state.sets()
        out = [a for s in sets for a in ("--set", s)]
        if self.raos:
            out += ["--raos", self.raos[0]]
        return out + ["--duration", repr(self.duration), "--fatigue", self.curve, "--scf", repr(self.scf),
                      "--dff", repr(self.dff), "--json"]

    def job(self, state: SeaState) -> dict[str, Any]:
        """Plain data: everything a worker needs to run `state`."""
        files = dict(self.extra_files)
        if self.scene_file:
            files[self.scene_file[0]] = self.scene_file[1]
        if self.raos:
            files[self.raos[0]] = self.raos[1]
        return {"scene": self.scene, "files": files, "args": self.args(state), "timeout": self.timeout}

    def fingerprint(self) -> dict[str, Any]:
        """What a rerun into the same DIR must agree on to reuse its finished states."""
        h = hashlib.sha256
        return {
            "binary": h(Path(self.binary).read_bytes()).hexdigest(),
            "scene": self.scene,
            "files": {k: h(v.encode()).hexdigest() for k, v in sorted(self.job(self.states[0])["files"].items())},
            "parameters": {k: _text(v) for k, v in sorted(self.parameters.items())},
            "curve": self.curve, "scf": repr(self.scf), "dff": repr(self.dff), "duration": repr(self.duration),
        }


def _ship(path: Path, what: str) -> tuple[str, str]:
    try:
        return path.name, path.read_text()
    except OSError as e:
        raise SpecError(f"{what}: cannot read {path}: {e.strerror}") from None


def load_fatigue_spec(path: str | Path, riser_bin: str | None = None) -> FatigueSpec:
    """Read and check a fatigue spec whole before any state runs: its keys, the scatter file,
    the parameters' names (`riser params`), then one short `riser run` (the scene, the values,
    the curve, the wall: riser's own checks; the static touchdown) and `riser waves` per state
    (the RAO table covers each state's sea). Raises SpecError naming the field or row."""
    path = Path(path)
    raw = read_toml(path)
    base = path.resolve().parent
    for k in raw:
        if k not in FATIGUE_TOP:
            why = " (a fatigue sweep's cases are the scatter file's sea states)" if k in ("grid", "run", "outputs", "fmu") \
                else ""
            raise SpecError(f"{k}: not a key of a fatigue spec{why} (allowed: {', '.join(FATIGUE_TOP)})"
                            f"{_suggest(k, list(FATIGUE_TOP))}")
    binary = riser_binary(riser_bin)
    description = raw.get("description", "")
    if not isinstance(description, str):
        raise SpecError("description: expected a string")

    # the scene: a built-in or a file (its text and its own relative RAO table shipped)
    scene = coerce("scene", "String", raw.get("scene", "steel_catenary"))
    scene_file = None
    extra: dict[str, str] = {}
    scene_path = Path(scene) if Path(scene).is_absolute() else base / scene
    scene_where = scene
    if scene.endswith(".toml") or scene_path.is_file():
        if not scene_path.is_file():
            raise SpecError(f"scene = {scene!r}: {scene_path} is not a file")
        scene_file = _ship(scene_path, "scene")
        scene = scene_file[0]
        scene_where = str(scene_path)
        try:
            vessel = tomllib.loads(scene_file[1]).get("vessel", {})
        except tomllib.TOMLDecodeError as e:
            raise SpecError(f"scene = {raw['scene']!r}: not valid TOML: {e}") from None
        own = vessel.get("raos") if isinstance(vessel, dict) else None
        if isinstance(own, str) and not Path(own).is_absolute():
            p = scene_path.parent / own
            if p.is_file():
                extra[own] = p.read_text()

    # parameters: riser's --set names on this scene
    p = subprocess.run([binary, "params", scene_where, "--json"], capture_output=True, text=True)
    if p.returncode != 0:
        raise SpecError(f"scene = {raw.get('scene')!r}: {p.stderr.strip().removeprefix('riser: error: ')}")
    names = [v["name"] for v in json.loads(p.stdout)]
    parameters: dict[str, Any] = {}
    section = raw.get("parameters", {})
    if not isinstance(section, dict):
        raise SpecError("parameters: expected a table")
    for k, v in section.items():
        if k not in names:
            raise SpecError(f"parameters.{k}: not a parameter of riser on {scene}{_suggest(k, names)} "
                            f"(`riser params {scene}` lists them)")
        if k in STATE_PARAMETERS:
            raise SpecError(f"parameters.{k}: each sea state's, from the scatter file (wave_kind is jonswap)")
        if isinstance(v, (dict, list)):
            raise SpecError(f"parameters.{k} = {v!r}: expected a single value")
        parameters[k] = v

    # motion: the RAO table only
    motion = raw.get("motion", {})
    if not isinstance(motion, dict):
        raise SpecError("motion: expected a table")
    _unknown("motion", motion, ("raos",))
    raos = None
    if "raos" in motion:
        v = coerce("motion.raos", "String", motion["raos"])
        rp = Path(v) if Path(v).is_absolute() else base / v
        if not rp.is_file():
            raise SpecError(f"motion.raos = {v!r}: {rp} is not a file")
        name, text = _ship(rp, "motion.raos")
        raos = (f"raos-{hashlib.sha256(text.encode()).hexdigest()[:12]}-{name}", text)

    # [fatigue]
    fat = raw["fatigue"]
    if not isinstance(fat, dict):
        raise SpecError("fatigue: expected a table")
    _unknown("fatigue", fat, FATIGUE_KEYS)
    for k in ("curve", "scatter", "duration"):
        if k not in fat:
            raise SpecError(f"fatigue.{k}: required")
    curve = coerce("fatigue.curve", "String", fat["curve"])
    scf = coerce("fatigue.scf", "Real", fat.get("scf", 1.0))
    dff = coerce("fatigue.dff", "Real", fat.get("dff", 1.0))
    for k, x in (("scf", scf), ("dff", dff)):
        if x < 1.0:
            raise SpecError(f"fatigue.{k} = {x!r}: at least 1")
    duration = coerce("fatigue.duration", "Real", fat["duration"])
    if duration <= 0:
        raise SpecError(f"fatigue.duration = {duration!r}: must be > 0 (s)")
    zone = coerce("fatigue.touchdown_zone", "Real", fat.get("touchdown_zone", TOUCHDOWN_ZONE_DEFAULT))
    if zone < 0:
        raise SpecError(f"fatigue.touchdown_zone = {zone!r}: must be >= 0 (m)")
    timeout = optional_timeout(fat, "fatigue")
    sv = coerce("fatigue.scatter", "String", fat["scatter"])
    scatter = Path(sv) if Path(sv).is_absolute() else base / sv
    try:
        states, warnings = read_scatter(scatter)
    except ScatterError as e:
        raise ScatterError(f"fatigue.scatter: {e}") from None
    if "wave_gamma" in parameters and any(s.gamma is not None for s in states):
        raise SpecError("parameters.wave_gamma: the scatter file has a gamma column too")
    if "wave_direction" in parameters and any(s.direction is not None for s in states):
        raise SpecError("parameters.wave_direction: the scatter file has a direction column too")
    if raos is None and not extra:
        warnings.append("no RAO table ([motion] raos, or the scene's [vessel] raos): the vessel stays still, only "
                        "the waves on the line load it")

    spec = FatigueSpec(path=path, binary=binary, scene=scene, scene_file=scene_file, extra_files=extra,
                       parameters=parameters, raos=raos, curve=curve, scf=scf, dff=dff, scatter=scatter,
                       states=states, duration=duration, touchdown_zone=zone, timeout=timeout,
                       description=description, warnings=warnings)
    _check_with_riser(spec)
    return spec


def _check_with_riser(spec: FatigueSpec) -> None:
    """riser's own checks before any state runs: one short run of the first state (the scene, the
    values, the curve, the wall; the static touchdown), and each state's sea on the RAO table."""
    with tempfile.TemporaryDirectory(prefix="riser-fatigue-check-") as d:
        _write_files(d, spec.job(spec.states[0])["files"])
        for st in spec.states:
            sets = [f"{k}={_text(v)}" for k, v in sorted(spec.parameters.items()) if k.startswith("wave_")]
            sets += st.sets()
            cmd = [spec.binary, "waves", spec.scene, *[a for s in sets for a in ("--set", s)], "--duration", "1",
                   "--json"]
            if spec.raos:
                cmd += ["--raos", spec.raos[0]]
            p = subprocess.run(cmd, capture_output=True, text=True, cwd=d)
            if p.returncode != 0:
                raise ScatterError(f"fatigue.scatter: {spec.scatter} row {st.row} (line {st.line}): "
                                   f"{p.stderr.strip().removeprefix('riser: error: ')}")
        args = spec.args(spec.states[0])
        i = args.index("--duration")
        args[i + 1] = "0.5"
        p = subprocess.run([spec.binary, "run", spec.scene, *args], capture_output=True, text=True, cwd=d)
        if p.returncode != 0:
            raise SpecError(f"riser refuses the run: {p.stderr.strip().removeprefix('riser: error: ')}")
        spec.static_touchdown_s = json.loads(p.stdout)["statics"].get("touchdown_s")


# ---- one sea state on a worker --------------------------------------------------------------------

def _write_files(root: str, files: dict[str, str]) -> None:
    for name, text in files.items():
        p = Path(root) / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)


def run_state(binary: str, job: dict[str, Any], workdir: str | None = None) -> dict[str, Any]:
    """Run one sea state: {"status", "error", "json" (riser run's), "fatigue_csv" (text), "wall_s"}.
    Never raises for what riser does: its message is the error."""
    t0 = time.perf_counter()
    out: dict[str, Any] = {"status": "ok", "error": "", "json": None, "fatigue_csv": None}
    with tempfile.TemporaryDirectory(prefix="riser-state-", dir=workdir) as d:
        _write_files(d, job["files"])
        cmd = [binary, "run", job["scene"], *job["args"], "--out", "out"]
        try:
            p = subprocess.run(cmd, capture_output=True, text=True, cwd=d, timeout=job.get("timeout"))
        except subprocess.TimeoutExpired:
            out.update(status="error", error=f"timeout: {job['timeout']!r} s of wall time")
        else:
            if p.returncode != 0:
                msg = p.stderr.strip().splitlines()
                err = [m for m in msg if m.startswith("riser: error")] or msg[-1:] or [f"exit status {p.returncode}"]
                out.update(status="error", error=" ".join(err).removeprefix("riser: error: "))
            else:
                try:
                    out["json"] = json.loads(p.stdout)
                    out["fatigue_csv"] = (Path(d) / "out" / "fatigue.csv").read_text()
                except (OSError, ValueError) as e:
                    out.update(status="error", error=f"riser run's output: {e}")
    out["wall_s"] = time.perf_counter() - t0
    return out


class ShipRiser(WorkerPlugin):
    """The riser binary's bytes to every worker (written once, executable, in its local directory):
    nothing on a worker reads a path only the client has."""

    idempotent = True

    def __init__(self, data: bytes):
        self.data = data
        self.digest = hashlib.sha256(data).hexdigest()
        self.name = f"riser-bin-{self.digest[:16]}"
        self.path = ""

    def setup(self, worker: Any) -> None:
        target = Path(worker.local_directory) / self.name
        if not target.is_file():
            tmp = target.with_name(f".{self.name}.{os.getpid()}")
            tmp.write_bytes(self.data)
            tmp.chmod(tmp.stat().st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
            os.replace(tmp, target)
        self.path = str(target)


def state_task(job: dict[str, Any], plugin: str) -> dict[str, Any]:
    """The Dask task: one sea state on this worker's copy of riser."""
    from distributed import get_worker

    worker = get_worker()
    return run_state(worker.plugins[plugin].path, job, workdir=worker.local_directory)


# ---- the combination ------------------------------------------------------------------------------

@dataclass
class CaseFatigue:
    """One state's fatigue.csv read back: every point and fibre, in its order."""

    s: np.ndarray
    fibre: np.ndarray
    damage: np.ndarray
    window: float

    @staticmethod
    def read(text: str, window: float) -> CaseFatigue:
        rows = list(csv.DictReader(io.StringIO(text)))
        return CaseFatigue(np.array([float(r["S"]) for r in rows]), np.array([int(r["fibre"]) for r in rows]),
                           np.array([float(r["damage"]) for r in rows]), window)

    def per_year(self) -> np.ndarray:
        """riser's damage_per_year, in its order of operations: damage * T_year / window."""
        return self.damage * SECONDS_PER_YEAR / self.window


def combine(states: list[SeaState], cases: list[CaseFatigue]) -> np.ndarray:
    """D_year(S, fibre) = sum_i p_i (D_i T_year / T_i), summed in the states' order."""
    first = cases[0]
    total = np.zeros_like(first.damage)
    for st, c in zip(states, cases):
        if not (np.array_equal(c.s, first.s) and np.array_equal(c.fibre, first.fibre)):
            raise ValueError(f"row {st.row}: its fatigue.csv has other points than row {states[0].row}'s")
        total = total + st.probability * c.per_year()
    return total


def life(annual: float, dff: float) -> float:
    """riser's life_years: 1 / (D_year DFF), inf without damage."""
    return 1.0 / (annual * dff) if annual > 0 else math.inf


def _worst(s: np.ndarray, fibre: np.ndarray, annual: np.ndarray, mask: np.ndarray, dff: float) -> dict[str, Any] | None:
    if not mask.any():
        return None
    idx = np.flatnonzero(mask)
    j = int(idx[np.argmax(annual[idx])])
    return {"s": float(s[j]), "fibre": int(fibre[j]), "annual_damage": float(annual[j]),
            "life_years": life(float(annual[j]), dff)}


def zones(s: np.ndarray, n_elements: int, touchdown_s: float | None, zone: float) -> dict[str, np.ndarray]:
    """The touchdown zone (|S - S_td| <= zone, S_td the static touchdown) and the hang-off (the first
    element's points: the smallest of the line's points, len(points) / n_elements of them)."""
    points = np.unique(s)
    per = len(points) // n_elements if n_elements > 0 and len(points) % n_elements == 0 else 1
    first = points[: max(per, 1)]
    out = {"hang_off": np.isin(s, first)}
    if touchdown_s is not None:
        out["touchdown"] = np.abs(s - touchdown_s) <= zone
    return out


# ---- the sweep ------------------------------------------------------------------------------------

@dataclass
class FatigueSummary:
    total: int
    skipped: int = 0
    ran: int = 0
    errors: int = 0
    interrupted: bool = False
    workers: int = 0
    wall_s: float = 0.0
    complete: bool = False
    summary: dict[str, Any] = field(default_factory=dict)


def _cell(v: Any) -> str:
    if v is None:
        return ""
    if isinstance(v, float):
        return repr(v)
    return str(v)


def _write_csv(path: Path, header: list[str], rows: list[list[Any]]) -> None:
    tmp = path.with_name(f".{path.name}.tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for r in rows:
            w.writerow([_cell(x) for x in r])
    os.replace(tmp, path)


def _load_done(out: Path, spec: FatigueSpec) -> dict[str, dict[str, Any]]:
    """The finished states of an earlier run into `out` with the same settings (else none)."""
    meta = out / "scatter.json"
    fp = spec.fingerprint()
    done: dict[str, dict[str, Any]] = {}
    if meta.is_file() and json.loads(meta.read_text()).get("settings") == fp:
        for st in spec.states:
            d = out / "cases" / st.name()
            if (d / "result.json").is_file() and (d / "fatigue.csv").is_file():
                res = json.loads((d / "result.json").read_text())
                if res.get("status") == "ok" and res.get("state") == [st.hs, st.tp, st.gamma, st.direction]:
                    res["fatigue_csv"] = (d / "fatigue.csv").read_text()
                    done[st.name()] = res
    meta.write_text(json.dumps({"spec": str(spec.path), "settings": fp}, indent=1) + "\n")
    return done


def _save_case(out: Path, st: SeaState, res: dict[str, Any]) -> None:
    d = out / "cases" / st.name()
    d.mkdir(parents=True, exist_ok=True)
    if res.get("fatigue_csv") is not None:
        (d / "fatigue.csv").write_text(res["fatigue_csv"])
    keep = {k: v for k, v in res.items() if k != "fatigue_csv"}
    keep["state"] = [st.hs, st.tp, st.gamma, st.direction]
    tmp = d / ".result.json.tmp"
    tmp.write_text(json.dumps(keep, indent=1) + "\n")
    os.replace(tmp, d / "result.json")


def run_fatigue_sweep(spec: FatigueSpec, out_dir: str | Path, scheduler: str | None = None,
                      workers: int | None = None, log: TextIO | None = None, bar: bool | None = None,
                      plot: bool = True) -> FatigueSummary:
    """Run the sea states of `spec` on Dask (those not finished in `out_dir` already), then write
    scatter_results.csv, fatigue_life.csv, fatigue_summary.json and annual_damage.png."""
    from .sweep import _workers, collect, dask_client

    log = log or sys.stderr
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    for w in spec.warnings:
        print(f"riser-sweep: warning: {w}", file=log, flush=True)
    results: dict[str, dict[str, Any]] = _load_done(out, spec)
    todo = [st for st in spec.states if st.name() not in results]
    summary = FatigueSummary(total=len(spec.states), skipped=len(spec.states) - len(todo))
    print(f"riser-sweep: {summary.total} sea states: {summary.skipped} done, {len(todo)} to run", file=log, flush=True)
    t0 = time.perf_counter()
    if todo:
        with dask_client(scheduler, workers, len(todo), log) as client:
            summary.workers = len(client.nthreads())
            print(f"riser-sweep: {scheduler or 'a local cluster'}, {_workers(summary.workers)}", file=log, flush=True)
            plugin = ShipRiser(Path(spec.binary).read_bytes())
            client.register_plugin(plugin, name=plugin.name)
            run = uuid.uuid4().hex[:8]
            by_key: dict[str, SeaState] = {}
            futures = []
            # submitted in the file's order; they complete in any, and the combination is in the file's order
            for st in todo:
                key = f"riser-state-{st.row}-{run}"
                by_key[key] = st
                futures.append(client.submit(state_task, spec.job(st), plugin.name, key=key, retries=0))

            def save(st: SeaState, res: dict[str, Any]) -> None:
                _save_case(out, st, res)
                results[st.name()] = res

            collect(client, futures, by_key, summary, save, lambda e: worker_failure(e, json=None, fatigue_csv=None),
                    log, bar)
    summary.wall_s = time.perf_counter() - t0
    write_results(spec, out, results, summary, plot=plot)
    return summary


def write_results(spec: FatigueSpec, out: Path, results: dict[str, dict[str, Any]], summary: FatigueSummary,
                  plot: bool = True) -> None:
    """scatter_results.csv (a row per state, the file's order), and when every state finished:
    fatigue_life.csv, fatigue_summary.json and annual_damage.png."""
    ok = [st for st in spec.states if results.get(st.name(), {}).get("status") == "ok"]
    summary.complete = len(ok) == len(spec.states)
    cases = {st.name(): CaseFatigue.read(results[st.name()]["fatigue_csv"],
                                         results[st.name()]["json"]["steady"]["fatigue"]["window_length"])
             for st in ok}
    annual = combine(ok, [cases[st.name()] for st in ok]) if ok else None
    first = cases[ok[0].name()] if ok else None
    j_worst = int(np.argmax(annual)) if annual is not None else None
    rows = []
    for st in spec.states:
        res = results.get(st.name())
        row: list[Any] = [st.row, st.hs, st.tp, st.probability, st.gamma, st.direction]
        if res is None:
            rows.append(row + [None] * 8 + ["not run", ""])
            continue
        if res["status"] != "ok":
            rows.append(row + [None] * 7 + [res.get("wall_s"), res["status"], res.get("error", "")])
            continue
        f = res["json"]["steady"]["fatigue"]
        c = cases[st.name()]
        share = None
        if annual is not None and j_worst is not None and annual[j_worst] > 0:
            share = float(st.probability * c.per_year()[j_worst] / annual[j_worst])
        dpy = f["damage_per_year"]
        rows.append(row + [f["window_length"], f["damage"], dpy, None if dpy is None else st.probability * dpy,
                           f["worst_s"], f["worst_fibre"], share, res.get("wall_s"), "ok", ""])
    _write_csv(out / "scatter_results.csv", RESULT_COLUMNS, rows)
    for stale in ("fatigue_life.csv", "annual_damage.png"):
        (out / stale).unlink(missing_ok=True)
    info: dict[str, Any] = {
        "spec": str(spec.path), "description": spec.description, "scene": spec.scene,
        "curve": spec.curve, "scf": spec.scf, "dff": spec.dff, "duration": spec.duration,
        "scatter": str(spec.scatter), "states": len(spec.states), "ok": len(ok),
        "errors": sum(1 for st in spec.states if results.get(st.name(), {}).get("status") == "error"),
        "probability_sum": math.fsum(st.probability for st in spec.states),
        "seconds_per_year": SECONDS_PER_YEAR, "complete": summary.complete,
        "wall_s": summary.wall_s, "workers": summary.workers, "warnings": spec.warnings,
    }
    if summary.complete and annual is not None and first is not None:
        lives = [life(float(a), spec.dff) for a in annual]
        _write_csv(out / "fatigue_life.csv", ["s", "fibre", "annual_damage", "life"],
                   [[float(s), int(fb), float(a), lf] for s, fb, a, lf in zip(first.s, first.fibre, annual, lives)])
        n_el = int(results[ok[0].name()]["json"]["n_elements"])
        touchdown = spec.static_touchdown_s
        if touchdown is None:
            touchdown = results[ok[0].name()]["json"]["statics"].get("touchdown_s")
        z = zones(first.s, n_el, touchdown, spec.touchdown_zone)
        info["worst"] = _worst(first.s, first.fibre, annual, np.ones(len(annual), bool), spec.dff)
        info["hang_off"] = _worst(first.s, first.fibre, annual, z["hang_off"], spec.dff)
        info["hang_off"]["points"] = sorted(float(x) for x in np.unique(first.s[z["hang_off"]]))
        info["touchdown"] = None
        if "touchdown" in z:
            info["touchdown"] = _worst(first.s, first.fibre, annual, z["touchdown"], spec.dff)
            if info["touchdown"] is not None:
                info["touchdown"].update(static_touchdown_s=touchdown, zone=spec.touchdown_zone)
        if plot:
            plot_annual_damage(out / "fatigue_life.csv", out / "annual_damage.png", touchdown,
                               spec.touchdown_zone, title=f"{spec.scene}: {len(spec.states)} sea states, "
                               f"{spec.curve}, SCF {spec.scf:g}, DFF {spec.dff:g}")
    (out / "fatigue_summary.json").write_text(json.dumps(_finite(info), indent=1) + "\n")
    summary.summary = info


def _finite(v: Any) -> Any:
    """JSON has no infinity: an infinite life is null."""
    if isinstance(v, dict):
        return {k: _finite(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_finite(x) for x in v]
    return None if isinstance(v, float) and not math.isfinite(v) else v


def plot_annual_damage(life_csv: Path, png: Path, touchdown_s: float | None = None, zone: float = 0.0,
                       title: str = "") -> Path:
    """The annual damage along the line, the largest over the fibres at each point, log scale."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with open(life_csv, newline="") as f:
        rows = list(csv.DictReader(f))
    by_s: dict[float, float] = {}
    for r in rows:
        s, a = float(r["s"]), float(r["annual_damage"])
        by_s[s] = max(by_s.get(s, 0.0), a)
    s = np.array(sorted(by_s))
    a = np.array([by_s[x] for x in s])
    fig, ax = plt.subplots(figsize=(8, 4.5))
    pos = a > 0
    ax.semilogy(s[pos], a[pos], lw=1.2, color="C0", label="annual damage (largest over the 8 fibres)")
    if touchdown_s is not None:
        ax.axvline(touchdown_s, color="C3", lw=0.8, ls="--", label=f"static touchdown S = {touchdown_s:.1f} m")
        if zone > 0:
            ax.axvspan(touchdown_s - zone, touchdown_s + zone, color="C3", alpha=0.08,
                       label=f"touchdown zone +-{zone:g} m")
    ax.set_xlabel("S, arc length from the hang-off (m)")
    ax.set_ylabel("damage per year (unfactored)")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    plt.close(fig)
    return png
