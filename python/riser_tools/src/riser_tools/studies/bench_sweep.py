#!/usr/bin/env python3
"""Benchmark of riser-sweep (issue 15, evidence 6): 48 cases as a plain loop in
one process (the same `run_case` per case, no Dask), then as a sweep on a
LocalCluster of 1 and of 2 workers, each timed whole (cluster start, shipping
the FMU, the cases, writing results.csv, closing). Two case sizes: *tiny*
(cable, 10 elements, 20 s: milliseconds a case, so the Dask overhead shows) and
*small* (rod, 20 elements, 60 s: about half a second a case, the kind a study
runs). Medians of --repeat runs. Prints a Markdown table (the "Sweeps on Dask"
section of docs/performance.md) and writes out/bench_sweep/bench.json.

Usage (`make bench-sweep`): riser-tools bench-sweep [--fmu fmu/riser.fmu] [--repeat 3] [--sizes tiny,small]
(5 to 8 minutes on 2 cores; run it on a quiet machine, it measures wall time).
"""

from __future__ import annotations

import argparse
import io
import json
import os
import shutil
import statistics
import tempfile
import time
from pathlib import Path

GRID = """
[grid]
heave_period = [8.0, 10.0, 12.0, 14.0, 16.0, 20.0]
heave_amplitude = [1.0, 2.0, 3.0, 4.0]
[[grid.linked]]
current_top = [0.4, 0.8]
current_bottom = [0.4, 0.8]
"""

SIZES = {
    "tiny": """
[parameters]
model = "cable"
n_elements = 10
time_step = 0.1
[motion]
ramp = 5.0
[run]
duration = 20.0
communication_step = 0.1
""",
    "small": """
[parameters]
n_elements = 20
time_step = 0.1
[motion]
ramp = 10.0
[run]
duration = 60.0
communication_step = 0.1
""",
}


def cpu() -> float:
    """CPU seconds of this process and of its finished children (the local cluster's
    worker processes, once closed): less sensitive than wall time to a busy machine."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def load(fmu: Path, size: str, tmp: Path):
    from riser_sweep import load_spec
    from riser_sweep.sweep import check_spec_with_fmu

    p = tmp / f"{size}.toml"
    p.write_text(f'fmu = "{fmu.resolve()}"\n' + SIZES[size] + GRID)
    spec = load_spec(p)
    check_spec_with_fmu(spec)
    assert len(spec.cases) == 48
    return spec


def plain_loop(spec) -> tuple[float, float, float]:
    """The same cases one after the other in this process: (total wall, sum of case walls, CPU)."""
    from fmpy import extract, read_model_description
    from riser_sweep import run_case

    c0 = cpu()
    t0 = time.perf_counter()
    d = extract(str(spec.fmu))
    md = read_model_description(d)
    walls = []
    for case in spec.cases:
        r = run_case(d, spec.job(case), md, workdir=d)
        assert r["status"] == "ok", r["error"]
        walls.append(r["wall_s"])
    total = time.perf_counter() - t0
    shutil.rmtree(d, ignore_errors=True)
    return total, sum(walls), cpu() - c0


def swept(spec, workers: int, tmp: Path) -> tuple[float, float, float]:
    """The sweep on a fresh LocalCluster: (total wall, sum of the rows' wall_s, CPU)."""
    import csv

    from riser_sweep import run_sweep

    out = tmp / f"out-{workers}-{time.monotonic_ns()}"
    c0 = cpu()
    t0 = time.perf_counter()
    s = run_sweep(spec, out, workers=workers, log=io.StringIO(), bar=False)
    total = time.perf_counter() - t0
    assert s.ran == 48 and s.errors == 0, s
    with open(out / "results.csv") as f:
        walls = [float(r["wall_s"]) for r in csv.DictReader(f)]
    shutil.rmtree(out, ignore_errors=True)
    return total, sum(walls), cpu() - c0


def empty_cluster(workers: int, fmu: Path) -> tuple[float, float]:
    """The fixed cost: start a LocalCluster, ship the FMU, close it, no case: (wall, CPU)."""
    from riser_sweep.case import ShipFMU
    from riser_sweep.sweep import dask_client

    c0 = cpu()
    t0 = time.perf_counter()
    with dask_client(None, workers, workers, io.StringIO()) as client:
        p = ShipFMU(fmu.read_bytes())
        client.register_plugin(p, name=p.name)
    return time.perf_counter() - t0, cpu() - c0


def main(argv=None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--fmu", default="fmu/riser.fmu")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--sizes", default="tiny,small")
    ap.add_argument("--out", default="out/bench_sweep")
    args = ap.parse_args(argv)
    fmu = Path(args.fmu)
    results: dict[str, dict[str, float]] = {}
    load0 = os.getloadavg()
    t_start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="bench-sweep-") as t:
        tmp = Path(t)
        empties = {w: [empty_cluster(w, fmu) for _ in range(args.repeat)] for w in (1, 2)}
        fixed = {w: statistics.median(e[0] for e in v) for w, v in empties.items()}
        fixed_cpu = {w: statistics.median(e[1] for e in v) for w, v in empties.items()}
        print(f"fixed cost (start a LocalCluster, ship the FMU, close): 1 worker {fixed[1]:.2f} s "
              f"({fixed_cpu[1]:.2f} s CPU), 2 workers {fixed[2]:.2f} s ({fixed_cpu[2]:.2f} s CPU)", flush=True)
        for size in args.sizes.split(","):
            spec = load(fmu, size, tmp)
            runs: dict[str, list[tuple[float, float, float]]] = {"loop": [], "1": [], "2": []}
            for i in range(args.repeat):  # interleaved, so a change of the machine's load hits all three
                runs["loop"].append(plain_loop(spec))
                runs["1"].append(swept(spec, 1, tmp))
                runs["2"].append(swept(spec, 2, tmp))
                print(f"{size} repeat {i + 1}: loop {runs['loop'][-1][0]:.2f} s, 1 worker {runs['1'][-1][0]:.2f} s, "
                      f"2 workers {runs['2'][-1][0]:.2f} s", flush=True)
            med = {k: statistics.median(r[0] for r in v) for k, v in runs.items()}
            case = {k: statistics.median(r[1] for r in v) / 48 for k, v in runs.items()}
            cpus = {k: statistics.median(r[2] for r in v) for k, v in runs.items()}
            results[size] = {
                "loop_s": med["loop"], "workers1_s": med["1"], "workers2_s": med["2"],
                "case_s_loop": case["loop"], "case_s_1": case["1"], "case_s_2": case["2"],
                "overhead_per_case_1_s": (med["1"] - med["loop"]) / 48,
                "overhead_per_case_1_without_fixed_s": (med["1"] - fixed[1] - med["loop"]) / 48,
                "cpu_loop_s": cpus["loop"], "cpu_1_s": cpus["1"], "cpu_2_s": cpus["2"],
                "cpu_overhead_per_case_1_s": (cpus["1"] - fixed_cpu[1] - cpus["loop"]) / 48,
                "cpu_overhead_per_case_2_s": (cpus["2"] - fixed_cpu[2] - cpus["loop"]) / 48,
                "in_flight_1": statistics.median(r[1] / r[0] for r in runs["1"]),
                "in_flight_2": statistics.median(r[1] / r[0] for r in runs["2"]),
                "speedup_2_vs_loop": med["loop"] / med["2"],
                "speedup_2_vs_1": med["1"] / med["2"],
                "all_runs": {k: [list(r) for r in v] for k, v in runs.items()},
            }
    elapsed = time.perf_counter() - t_start
    meta = {"cores": os.cpu_count(), "load_before": load0, "load_after": os.getloadavg(), "repeat": args.repeat,
            "fixed_s": fixed, "fixed_cpu_s": fixed_cpu, "elapsed_s": elapsed}
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "bench.json").write_text(json.dumps({"meta": meta, "results": results}, indent=1) + "\n")
    print()
    print(f"48 cases, medians of {args.repeat} (wall s, each run whole: cluster start to close); {os.cpu_count()} "
          f"cores, load average {load0[0]:.1f} before, {meta['load_after'][0]:.1f} after; {elapsed:.0f} s in all")
    print()
    print("| cases | plain loop | sweep, 1 worker | sweep, 2 workers | case wall (loop / 1 w / 2 w) | "
          "overhead per case, 1 worker (without the fixed cost) | 2 workers vs loop | 2 vs 1 worker | "
          "cases in flight (1 w / 2 w) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for size, r in results.items():
        print(f"| {size} | {r['loop_s']:.2f} | {r['workers1_s']:.2f} | {r['workers2_s']:.2f} | "
              f"{r['case_s_loop'] * 1e3:.0f} / {r['case_s_1'] * 1e3:.0f} / {r['case_s_2'] * 1e3:.0f} ms | "
              f"{r['overhead_per_case_1_s'] * 1e3:.0f} ms ({r['overhead_per_case_1_without_fixed_s'] * 1e3:.0f} ms) | "
              f"{r['speedup_2_vs_loop']:.2f}× | {r['speedup_2_vs_1']:.2f}× | "
              f"{r['in_flight_1']:.2f} / {r['in_flight_2']:.2f} |")
    print()
    print("| cases | CPU: plain loop | sweep, 1 worker | sweep, 2 workers | CPU overhead per case without the fixed "
          "cost (1 w / 2 w) |")
    print("|---|---|---|---|---|")
    for size, r in results.items():
        print(f"| {size} | {r['cpu_loop_s']:.2f} | {r['cpu_1_s']:.2f} | {r['cpu_2_s']:.2f} | "
              f"{r['cpu_overhead_per_case_1_s'] * 1e3:.0f} / {r['cpu_overhead_per_case_2_s'] * 1e3:.0f} ms |")
    print(f"\nfixed cost: {fixed[1]:.2f} s wall, {fixed_cpu[1]:.2f} s CPU (1 worker); {fixed[2]:.2f} s wall, "
          f"{fixed_cpu[2]:.2f} s CPU (2 workers); wrote {out / 'bench.json'}")


if __name__ == "__main__":
    main()
