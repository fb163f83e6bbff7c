"""One case through the FMU with fmpy: what runs inside a Dask task (and in a
plain loop, for the benchmark's baseline).

`run_case` takes an extracted FMU directory and a job (plain data from
`Spec.job`) and returns a result dict; it never raises for what the FMU does:
a value the FMU refuses (fmi2Error in fmi2SetXXX), statics that fail
(fmi2Error at fmi2ExitInitializationMode), a step Newton cannot take
(fmi2Discard), a non-finite output or the timeout each give ``status = "error"``
and the FMU's own message in ``error``.

`ShipFMU` is the worker plugin that brings the FMU to the workers: the client
registers it with the FMU's bytes, the scheduler hands it to every worker that
joins (also one that replaces a dead one), and each worker extracts it once into
its local directory. Nothing on a worker reads a path only the client has.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import os
import shutil
import tempfile
import time
import zipfile
from pathlib import Path
from typing import Any

import numpy as np
from distributed import WorkerPlugin
from riser_tools.series import window_time_mean

INPUTS = ("heave", "surge", "sway", "heave_velocity", "surge_velocity", "sway_velocity")
LOG_CATEGORIES = ["logStatusWarning", "logStatusDiscard", "logStatusError"]


def motion_signal(motion: dict[str, float], duration: float, h: float,
                  vessel: np.ndarray | None = None) -> np.ndarray:
    """The FMU's six inputs at t_k = k h, k = 0 .. duration/h, as fmpy's input
    table (see the formula in riser_sweep.spec's docstring); with `vessel` (the
    vessel's motion on its RAOs at the same times, riser_sweep.raos) its twelve,
    the harmonic motion added to it."""
    n = int(round(duration / h))
    t = np.arange(n + 1) * h
    ramp = motion["ramp"]
    if ramp > 0:
        r = np.where(t < ramp, 0.5 * (1.0 - np.cos(np.pi * t / ramp)), 1.0)
        dr = np.where(t < ramp, 0.5 * (np.pi / ramp) * np.sin(np.pi * t / ramp), 0.0)
    else:
        r = np.ones_like(t)
        dr = np.zeros_like(t)
    sig = np.zeros(n + 1, dtype=[("time", np.float64)] + [(name, np.float64) for name in INPUTS])
    sig["time"] = t
    for d in ("heave", "surge", "sway"):
        a = motion[f"{d}_amplitude"]
        if a == 0.0:
            continue
        w = 2.0 * np.pi / motion[f"{d}_period"]
        p = np.deg2rad(motion[f"{d}_phase"])
        s = np.sin(w * t + p)
        c = np.cos(w * t + p)
        sig[d] = a * r * s
        sig[f"{d}_velocity"] = a * (dr * s + r * w * c)
    if vessel is None:
        return sig
    from riser_sweep.raos import VESSEL_INPUTS

    both = np.zeros(n + 1, dtype=[("time", np.float64)] + [(k, np.float64) for k in VESSEL_INPUTS])
    both["time"] = t
    for k in VESSEL_INPUTS:
        both[k] = vessel[k] + (sig[k] if k in INPUTS else 0.0)
    return both


# The relative resolution of the line's energy in the balance: a still line closed to round-off
# (E - E0 within a few eps of |U| + |V| + K) gives at most 1e-14 / 1e-8 = 1e-6, the project's threshold
# of a closed balance; see energy_balance_relative
ENERGY_RESOLUTION = 1e-8


def energy_balance_relative(res: np.ndarray) -> float:
    """The energy balance's residual relative to the energy at play (results.csv's column):

        r(t) = E(t) - E(0) - work_top - work_hydro - work_seabed + dissipated_energy + algorithmic_dissipation
        X(t) = |work_top| + |work_hydro| + |work_seabed|            (the energy exchanged)
        S(t) = kinetic_energy + |strain_energy| + |potential_energy|  (the magnitude of what E sums)

        energy_balance_relative = max_t |r| / max(max_t X, ENERGY_RESOLUTION * max_t S)

    over every sample of the run. While anything moves X dominates (1e-8 S is 0.06 J on the catenary,
    0.6 J on the steel catenary) and this is `riser run --json`'s ratio, residual / exchanged. A line
    held still exchanges nothing (X round-off small, or 0) while E - E(0) still carries the round-off
    of summing |U| + |V| + K, a few eps of S: the residual then counts against that resolution, so a
    still case closed to round-off stays below 1e-6 and a real leak of more than ~1e-14 S still shows.
    `work_seabed` and the energy terms count when the run recorded them (an FMU without them: 0, and
    S = |total_energy|). Nothing recorded at all: 0."""
    names = res.dtype.names or ()

    def col(name: str) -> np.ndarray:
        return res[name] if name in names else np.zeros(len(res))

    e = res["total_energy"]
    seabed = col("work_seabed")
    balance = e - e[0] - res["work_top"] - res["work_hydro"] - seabed + res["dissipated_energy"] \
        + res["algorithmic_dissipation"]
    if len(balance) == 0:
        return 0.0
    exchanged = float(np.max(np.abs(res["work_top"]) + np.abs(res["work_hydro"]) + np.abs(seabed)))
    if all(n in names for n in ("kinetic_energy", "strain_energy", "potential_energy")):
        held = np.abs(res["kinetic_energy"]) + np.abs(res["strain_energy"]) + np.abs(res["potential_energy"])
    else:
        held = np.abs(e)
    scale = max(exchanged, ENERGY_RESOLUTION * float(np.max(held)))
    residual = float(np.max(np.abs(balance)))
    if scale > 0:
        return residual / scale
    return 0.0 if residual == 0 else float("inf")


def _scene_path(workdir: str, name: str, text: str) -> str:
    """A scene file shipped as text, written once under `workdir`."""
    d = Path(workdir) / "riser-scenes" / hashlib.sha256(text.encode()).hexdigest()[:16]
    p = d / name
    if not p.is_file():
        d.mkdir(parents=True, exist_ok=True)
        tmp = d / f".{name}.{os.getpid()}"
        tmp.write_text(text)
        os.replace(tmp, p)
    return str(p)


def run_case(unzipdir: str, job: dict[str, Any], model_description: Any = None,
             workdir: str | None = None) -> dict[str, Any]:
    """Run one case; returns {"reductions": {column: float}, "wall_s", "status",
    "error", "timeseries" (a structured array, when the job asks for it)}."""
    from fmpy import read_model_description, simulate_fmu
    from riser_tools.fmpy_logging import instantiate_logged

    t0 = time.perf_counter()
    out: dict[str, Any] = {"reductions": {}, "status": "ok", "error": "", "timeseries": None}
    messages: list[str] = []

    def logger(_env: Any, _name: Any, status: int, _category: Any, message: bytes) -> None:
        if status >= 1:  # warning, discard, error, fatal
            messages.append(message.decode(errors="replace"))

    def fail(what: str) -> dict[str, Any]:
        why = " | ".join(m.replace("\n", " ") for m in messages)
        out["status"] = "error"
        out["error"] = f"{what}: {why}" if why else what
        out["wall_s"] = time.perf_counter() - t0
        return out

    fmu = None
    try:
        md = model_description or read_model_description(unzipdir)
        start_values = dict(job["start_values"])
        if job.get("scene_file"):
            name, text = job["scene_file"]
            start_values["scene"] = _scene_path(workdir or tempfile.gettempdir(), name, text)
        h = job["communication_step"]
        duration = job["duration"]
        if job.get("vessel_error"):
            return fail(job["vessel_error"])
        signal = motion_signal(job["motion"], duration, h, job.get("vessel"))
        fmu = instantiate_logged(unzipdir, md, logger, debug_logging=True)
        fmu.setDebugLogging(True, LOG_CATEGORIES)
        state: dict[str, Any] = {"time": 0.0, "stopped": ""}
        timeout = job.get("timeout")

        def step_finished(t: float, _recorder: Any) -> bool:
            # an FMU that answers fmi2Terminated false after a discard (riser's before
            # issue 52) has fmpy retry the step forever: a step that did not advance the
            # time is a discard, stop there
            if t <= state["time"]:
                state["stopped"] = f"fmi2DoStep returned fmi2Discard at t = {t!r} s"
                return False
            state["time"] = t
            if timeout is not None and time.perf_counter() - t0 > timeout:
                state["stopped"] = f"timeout: {timeout!r} s of wall time reached at t = {t!r} s"
                return False
            return True

        # fmpy prints a warning for each input the table leaves out: the rotations and
        # their rates, which the sweep leaves unset on purpose (a still rotation)
        printed = io.StringIO()
        try:
            with contextlib.redirect_stdout(printed):
                res = simulate_fmu(unzipdir, stop_time=duration, output_interval=h, input=signal,
                                   start_values=start_values, output=job["record"], fmu_instance=fmu,
                                   model_description=md, step_finished=step_finished)
        except Exception as e:  # fmpy raises FMICallException on fmi2Error
            return fail(str(e).rstrip("."))
        finally:
            for line in printed.getvalue().splitlines():
                if not line.startswith("Warning: missing input for variable"):
                    print(line)
        if state["stopped"]:
            return fail(state["stopped"])
        # riser answers fmi2Terminated after a discard: fmpy ends the run at the last good time
        last = float(res["time"][-1]) if len(res) else 0.0
        if last < duration - 1e-9 * max(1.0, duration):
            return fail(f"fmi2DoStep returned fmi2Discard: the run ended at t = {last!r} s "
                        f"(fmi2LastSuccessfulTime) of {duration!r} s")
        for name in job["record"]:
            bad = ~np.isfinite(res[name])
            if bad.any():
                return fail(f"non-finite {name} at t = {float(res['time'][bad.argmax()])!r} s")
        a, b = job["window"]
        tol = 1e-9 * max(1.0, duration)
        win = (res["time"] >= a - tol) & (res["time"] <= b + tol)
        red = out["reductions"]
        tt = res["top_tension"][win]
        red["top_tension_min"] = float(tt.min())
        # the time mean over exactly the window, as `riser run` reports it: the samples' own mean with
        # both ends carries an O(dt) bias, (T_end - mean) dt / W, and the samples inside alone start
        # the window up to a communication step late where it does not fall on one
        red["top_tension_mean"] = window_time_mean(res["time"], res["top_tension"], a, b)
        red["top_tension_max"] = float(tt.max())
        red["min_tension_min"] = float(res["min_tension"][win].min())
        red["energy_balance_relative"] = energy_balance_relative(res)
        for name, ops in job["reduce"].items():
            x = res[name][win]
            for op in ops:
                red[f"{name}_{op}"] = float(getattr(np, op)(x))
        if job.get("timeseries"):
            out["timeseries"] = res
        out["wall_s"] = time.perf_counter() - t0
        return out
    except Exception as e:  # anything else: the case's row says what, the sweep goes on
        return fail(f"{type(e).__name__}: {e}")
    finally:
        if fmu is not None:
            try:
                fmu.freeInstance()
            except Exception:
                pass


def extract_once(data: bytes, digest: str, root: str) -> str:
    """The FMU's bytes extracted under `root`/riser-fmu-<digest> (once; atomic,
    so several worker processes on one machine share it)."""
    target = Path(root) / f"riser-fmu-{digest[:16]}"
    if (target / "modelDescription.xml").is_file():
        return str(target)
    Path(root).mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=".riser-fmu-", dir=root))
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        z.extractall(tmp)
    try:
        os.rename(tmp, target)
    except OSError:  # another process got there first
        shutil.rmtree(tmp, ignore_errors=True)
    return str(target)


class ShipFMU(WorkerPlugin):
    """Carries the FMU's bytes to every worker and extracts them there once."""

    idempotent = True

    def __init__(self, data: bytes):
        self.data = data
        self.digest = hashlib.sha256(data).hexdigest()
        self.name = plugin_name(self.digest)
        self.unzipdir = ""
        self.model_description: Any = None

    def setup(self, worker: Any) -> None:
        from fmpy import read_model_description

        self.unzipdir = extract_once(self.data, self.digest, worker.local_directory)
        self.model_description = read_model_description(self.unzipdir)


def plugin_name(digest: str) -> str:
    return f"riser-fmu-{digest[:16]}"


def case_task(job: dict[str, Any], plugin: str) -> dict[str, Any]:
    """The Dask task: one case on this worker's copy of the FMU."""
    from distributed import get_worker

    worker = get_worker()
    p = worker.plugins[plugin]
    assert isinstance(p, ShipFMU)
    return run_case(p.unzipdir, job, p.model_description, workdir=worker.local_directory)

