"""The CLI driver: `riser run` and `riser statics` as subprocesses, their
`--json` summary and the CSV files they write read back as numpy arrays.

    from riser_tools import cli
    from riser_tools.cases import Motion
    r = cli.run("target/release/riser", "catenary", {"n_elements": 20}, Motion(2.5, 20.0, ramp=20.0),
                duration=100.0, out="out/x")
    r.summary["solve_wall_time"], r.series["top_tension"]
"""

from __future__ import annotations

import csv
import json
import os
import statistics
import subprocess
import time
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .cases import Motion, set_args

DEFAULT_BIN = "target/release/riser"


class CliError(RuntimeError):
    """`riser` exited non-zero or printed nothing: the command and its stderr."""


def read_columns(path: str | Path) -> dict[str, np.ndarray]:
    """A CSV with a header row (timeseries.csv, shape.csv, ...) as float columns by name."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise CliError(f"{path}: no rows")
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def read_rows(path: str | Path) -> list[dict[str, str]]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def execute(cmd: Sequence[str], timeout: float | None = None, cwd: str | Path | None = None,
            wait_for_binary: float = 0.0) -> subprocess.CompletedProcess:
    """Run a command, capturing its text output. With `wait_for_binary` > 0, a binary that is
    missing or busy (being rebuilt) is waited for up to that many seconds, every 15 s."""
    deadline = time.monotonic() + wait_for_binary
    while True:
        try:
            return subprocess.run(list(cmd), capture_output=True, text=True, timeout=timeout, cwd=cwd)
        except OSError as e:          # missing, or "text file busy"
            if time.monotonic() >= deadline:
                raise CliError(f"{cmd[0]}: {e}") from None
            time.sleep(15)


def run_command(binary: str, scene: str, sets: Mapping[str, Any] | Iterable[str] = (),
                motion: Motion | Sequence[Motion] | None = None, duration: float = 100.0,
                out: str | Path | None = None, extra: Sequence[str] = ()) -> list[str]:
    """`riser run SCENE --set... MOTION... --duration D --json [--out DIR] EXTRA...`"""
    motions = [] if motion is None else [motion] if isinstance(motion, Motion) else list(motion)
    cmd = [str(binary), "run", scene, *set_args(sets)]
    if len({m.ramp for m in motions}) > 1:
        raise CliError(f"motions with different ramps {[m.ramp for m in motions]}: riser run has one --ramp")
    for i, m in enumerate(motions):
        cmd += m.cli_args(ramp=i == 0)
    cmd += ["--duration", f"{duration:g}", "--json"]
    if out is not None:
        cmd += ["--out", str(out)]
    return cmd + list(extra)


@dataclass
class Run:
    """A finished `riser run`: its JSON summary, its timeseries.csv columns (when it
    wrote one), the command, and the solve wall times of every repeat."""

    summary: dict[str, Any]
    series: dict[str, np.ndarray]
    cmd: list[str]
    out: Path | None
    walls: list[float] = field(default_factory=list)

    @property
    def wall(self) -> float:
        """Median `solve_wall_time` over the repeats (s)."""
        return statistics.median(self.walls)

    @property
    def t(self) -> np.ndarray:
        return self.series["t"]

    @property
    def top_tension(self) -> np.ndarray:
        return self.series["top_tension"]


def run(binary: str, scene: str, sets: Mapping[str, Any] | Iterable[str] = (),
        motion: Motion | Sequence[Motion] | None = None, duration: float = 100.0,
        out: str | Path | None = None, extra: Sequence[str] = (), repeats: int = 1, cheap: float = float("inf"),
        timeout: float | None = None, wait_for_binary: float = 0.0) -> Run:
    """`riser run` once (or `repeats` times for a median wall time, stopping after the first
    when it took more than `cheap` seconds); raises CliError when it fails."""
    if out is not None:
        Path(out).mkdir(parents=True, exist_ok=True)
    cmd = run_command(binary, scene, sets, motion, duration, out, extra)
    walls: list[float] = []
    summary: dict[str, Any] = {}
    for i in range(max(1, repeats)):
        p = execute(cmd, timeout=timeout, wait_for_binary=wait_for_binary)
        if p.returncode != 0 or not p.stdout.strip():
            raise CliError(f"riser failed: {' '.join(cmd)}\n{p.stderr}")
        summary = json.loads(p.stdout)
        walls.append(summary["solve_wall_time"])
        if i == 0 and walls[0] > cheap:
            break
    series = read_columns(Path(out) / "timeseries.csv") if out is not None else {}
    return Run(summary, series, cmd, Path(out) if out is not None else None, walls)


def try_run(*args: Any, **kwargs: Any) -> Run | None:
    """`run`, or None when riser fails (a cell a study reports as failed)."""
    try:
        return run(*args, **kwargs)
    except CliError:
        return None


def statics(binary: str, scene: str, sets: Mapping[str, Any] | Iterable[str] = (),
            cwd: str | Path | None = None) -> dict[str, Any]:
    """`riser statics SCENE --set... --json` as a dict (top_tension, top_force, shape, ...)."""
    cmd = [str(binary), "statics", scene, *set_args(sets), "--json"]
    p = execute(cmd, cwd=cwd)
    if p.returncode != 0:
        raise CliError(f"riser failed: {' '.join(cmd)}\n{p.stderr}")
    return json.loads(p.stdout)


def version(binary: str) -> str:
    """`riser --version`."""
    return subprocess.run([str(binary), "--version"], capture_output=True, text=True).stdout.strip()


def file_stamp(path: str | Path) -> str:
    """Modification time and the start of the SHA-256 of a file, for a provenance line."""
    import datetime
    import hashlib
    try:
        data = Path(path).read_bytes()
    except OSError:
        return "missing"
    mtime = datetime.datetime.fromtimestamp(os.path.getmtime(path), datetime.timezone.utc)
    return f"modified {mtime:%Y-%m-%d %H:%M} UTC, sha256 {hashlib.sha256(data).hexdigest()[:12]}"
