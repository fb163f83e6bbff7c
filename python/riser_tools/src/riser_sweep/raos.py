"""The vessel on its RAOs in a sweep (spec key ``[motion] raos = "FILE"``;
docs/guide/sweeps.md "The vessel on its RAOs").

Each case's motion is the one ``riser run`` drives in that case's sea: the
client runs ``riser waves SCENE --set NAME=VALUE ... --raos FILE --duration
D --step h --out DIR`` with the case's scene and parameters (the FMU's
parameters are riser's ``--set`` names; those riser does not take, such as
``coupling_inputs``, do not touch the sea and are left out) and reads
``DIR/vessel_motion.csv``: the reference point's displacement and velocity,
the angles and the angular velocity in the vessel frame at t_k = k h, the
waves' ramp included — the FMU's twelve inputs. One implementation of the
RAOs (riser's, in Rust), the sea realised by the same code as the FMU's.

The riser binary: ``$RISER_BIN``, else ``riser`` on the PATH, else
``target/release/riser`` under the working directory.
"""

from __future__ import annotations

import functools
import json
import os
import shutil
import subprocess
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

# the FMU's inputs vessel_motion.csv holds, in its column order
VESSEL_INPUTS = ("surge", "sway", "heave", "roll", "pitch", "yaw", "surge_velocity", "sway_velocity",
                 "heave_velocity", "angular_velocity_x", "angular_velocity_y", "angular_velocity_z")


class RaoError(RuntimeError):
    """riser could not give a case's motion (its message says why)."""


def riser_binary() -> str:
    for cand in (os.environ.get("RISER_BIN"), shutil.which("riser"), "target/release/riser"):
        if cand and Path(cand).is_file():
            return str(cand)
    raise RaoError("[motion] raos needs the riser binary: set RISER_BIN, put riser on the PATH, or build "
                   "target/release/riser (cargo build --release)")


@functools.lru_cache(maxsize=64)
def _set_names(binary: str, scene: str) -> frozenset[str]:
    """The names `riser --set` takes on `scene`."""
    p = subprocess.run([binary, "params", scene, "--json"], capture_output=True, text=True)
    if p.returncode != 0:
        raise RaoError(p.stderr.strip() or f"riser params {scene} failed")
    return frozenset(v["name"] for v in json.loads(p.stdout))


def _text(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return repr(v) if isinstance(v, float) else str(v)


def vessel_motion(scene: str, parameters: dict[str, Any], raos: str, duration: float, h: float,
                  binary: str | None = None) -> tuple[np.ndarray, dict[str, Any]]:
    """The vessel's motion on its RAOs at t_k = k h, k = 0 .. duration/h, in the sea of `scene` with
    `parameters` (FMU names): a structured array (time and VESSEL_INPUTS) and `riser waves --json`'s
    summary (ramp, tp, components, ...)."""
    binary = binary or riser_binary()
    names = _set_names(binary, scene)
    sets = [a for k, v in sorted(parameters.items()) if k in names for a in ("--set", f"{k}={_text(v)}")]
    n = int(round(duration / h))
    with tempfile.TemporaryDirectory(prefix="riser-raos-") as out:
        # one step more: the record runs from 0 to duration inclusive
        cmd = [binary, "waves", scene, *sets, "--raos", raos, "--duration", repr((n + 1) * h), "--step", repr(h),
               "--out", out, "--json"]
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            raise RaoError(p.stderr.strip().removeprefix("riser: error: ") or "riser waves failed")
        info = json.loads(p.stdout)
        lines = [ln for ln in (Path(out) / "vessel_motion.csv").read_text().splitlines() if not ln.startswith("#")]
    head = lines[0].split(",")
    rows = np.array([[float(x) for x in ln.split(",")] for ln in lines[1:]]).reshape(-1, len(head))[: n + 1]
    data = {name: rows[:, j] for j, name in enumerate(head)}
    sig = np.zeros(n + 1, dtype=[("time", np.float64)] + [(k, np.float64) for k in VESSEL_INPUTS])
    sig["time"] = np.arange(n + 1) * h
    if len(rows) != n + 1 or np.max(np.abs(data["t"] - sig["time"])) > 1e-9 * max(1.0, duration):
        raise RaoError(f"riser waves gave {len(rows)} samples of the vessel's motion, not {n + 1} at k h")
    for k in VESSEL_INPUTS:
        sig[k] = data[k]
    return sig, info
