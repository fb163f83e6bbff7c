#!/usr/bin/env python3
"""The FMU against an earlier build's, interleaved: each FMU stepped by fmpy's FMU2Slave at a
communication step of 0.1 s for --duration seconds, the hang-off heaved 2.5 m / 10 s through the
`heave` and `heave_velocity` inputs, at each mesh (and time step) asked; --repeat rounds, the
order alternating. Reported per case: the median wall time of each (instantiation to
termination), their ratio, and whether `top_tension` is the same bits at every communication
point.

Usage: riser-tools bench-fmu --old OLD.fmu --new NEW.fmu [--cases 5:0.2,10:0.1,60:0.05]
       [--duration 60] [--repeat 5]
Prints a Markdown table (docs/performance.md).
"""

from __future__ import annotations

import argparse
import math
import shutil
import statistics
import sys
import tempfile
import time

import numpy as np


def run(fmu: str, unzipped: str, n: int, dt: float, duration: float) -> tuple[float, np.ndarray]:
    from fmpy import read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    h, w = 0.1, 2.0 * math.pi / 10.0
    start = time.perf_counter()
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="bench")
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.setInteger([vr["n_elements"]], [n])
    s.setReal([vr["time_step"]], [dt])
    s.exitInitializationMode()
    steps = int(round(duration / h))
    out = np.empty(steps)
    for k in range(steps):
        t = k * h
        s.setReal([vr["heave"], vr["heave_velocity"]], [2.5 * math.sin(w * t), 2.5 * w * math.cos(w * t)])
        s.doStep(t, h)
        out[k] = s.getReal([vr["top_tension"]])[0]
    s.terminate()
    s.freeInstance()
    return time.perf_counter() - start, out


def main(argv: list[str] | None = None) -> int:
    from fmpy import extract
    p = argparse.ArgumentParser(prog="riser-tools bench-fmu", description=__doc__.split("\n\n")[0])
    p.add_argument("--old", required=True, help="the earlier build's FMU")
    p.add_argument("--new", required=True, help="this build's FMU")
    p.add_argument("--cases", default="5:0.2,10:0.1,60:0.05", help="elements:time_step, comma-separated")
    p.add_argument("--duration", type=float, default=60.0)
    p.add_argument("--repeat", type=int, default=5)
    a = p.parse_args(argv)
    cases = [(int(c.split(":")[0]), float(c.split(":")[1])) for c in a.cases.split(",")]
    tmp = tempfile.mkdtemp()
    dirs = {"old": extract(a.old, tmp + "/old"), "new": extract(a.new, tmp + "/new")}
    fmus = {"old": a.old, "new": a.new}
    print("| elements | time step, s | old, s (median) | new, s (median) | new / old | top_tension |")
    print("|---|---|---|---|---|---|")
    for n, dt in cases:
        times: dict[str, list[float]] = {"old": [], "new": []}
        series: dict[str, np.ndarray] = {}
        for r in range(a.repeat):
            for which in (("old", "new") if r % 2 == 0 else ("new", "old")):
                wall, out = run(fmus[which], dirs[which], n, dt, a.duration)
                times[which].append(wall)
                series[which] = out
        same = np.array_equal(series["old"], series["new"])
        mo, mn = statistics.median(times["old"]), statistics.median(times["new"])
        print(f"| {n} | {dt} | {mo:.3f} | {mn:.3f} | {mn / mo:.3f} | "
              f"{'the same bits' if same else '**differs** by ' + format(np.abs(series['old'] - series['new']).max(), '.3g')} |",
              flush=True)
    shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
