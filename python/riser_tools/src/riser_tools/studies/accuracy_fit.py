"""The wave terms' constants of the accuracy knob's error model (docs/theory.md §16.4), fitted to
the study's runs (docs/accuracy_runs.csv, written by `riser-tools accuracy`):

    e_w = C_wt (a/A₀)(ω_w Δt)^1.5 + C_wk (a/A₀)(h k_w)² + E_w,

on top of the still-water terms C_κ (h κ)⁴ + C_t (A/A₀)(ω Δt)^1.5 with their constants. For each
wave case the scales (a, ω_w, k_w, the line's length and largest curvature) are read from the
binary's own choice (`--json`'s `accuracy` object); every grid run with at least 75 steps per
period is a point. For a grid of (E_w, C_wk), C_wt is the smallest that bounds every point; the
triple whose model is the tightest over all points (least Σ log(model / error)) is printed, and
each point's error against the model.

    riser-tools accuracy-fit [--bin target/fasttest/riser] [--runs docs/accuracy_runs.csv] [E_w C_wk C_wt]
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import subprocess

from . import accuracy as A

# the still-water constants of src/sim/accuracy.rs (C_CURVATURE, C_TIME)
C_K, C_T = 7e-4, 0.3


def points(binary: str, runs: str):
    rows = list(csv.DictReader(open(runs)))
    out = []
    for case, (scene, amp, period, els, sea, dur, win) in A.WAVE_CASES.items():
        cmd = A.command(binary, case)
        cmd[cmd.index("--duration") + 1] = "0.2"
        i = cmd.index("--window")
        del cmd[i:i + 2]
        p = subprocess.run(cmd + ["--set", "accuracy=1e-2"], capture_output=True, text=True, check=True)
        d = json.loads([line for line in p.stdout.splitlines() if line.startswith("{")][0])["accuracy"]
        m = [r for r in rows if r["case"] == case and r["completed"] == "True"]
        ref = next((r for r in m if r["kind"] == "reference"), None)
        if ref is None:
            continue
        print(f"{case}: k_w {d['wave_number']:.4f} rad/m, omega_w {d['wave_omega']:.4f} rad/s, "
              f"a {d['wave_amplitude']:.2f} m")
        for r in m:
            if r["kind"] != "grid":
                continue
            n, dt = int(r["n_elements"]), float(r["time_step"])
            if dt * 75 > min(2 * math.pi / d["wave_omega"], period) * (1 + 1e-9):
                continue
            h = d["length"] / n
            still = C_K * (h * d["max_curvature"]) ** 4 + C_T * amp / 10 * (2 * math.pi / period * dt) ** 1.5
            xt = d["wave_amplitude"] / 10 * (d["wave_omega"] * dt) ** 1.5
            xk = d["wave_amplitude"] / 10 * (h * d["wave_number"]) ** 2
            out.append((case, n, dt, A.error(r, ref), still, xt, xk))
    return out


def fit(pts):
    best = None
    for ew in [0, 1e-4, 1.5e-4, 2e-4, 2.5e-4, 3e-4, 3.5e-4, 4e-4]:
        for ck in [0, 1e-3, 2e-3, 5e-3, 1e-2, 1.2e-2, 1.4e-2, 1.6e-2, 1.8e-2, 2e-2, 2.5e-2, 3e-2, 4e-2]:
            ct = max(max(0.0, e - s - ew - ck * xk) / xt for (_, _, _, e, s, xt, xk) in pts)
            score = sum(math.log((s + ct * xt + ck * xk + ew) / e) for (_, _, _, e, s, xt, xk) in pts)
            if best is None or score < best[0]:
                best = (score, ew, ck, ct)
    return best


def main(argv=None):
    ap = argparse.ArgumentParser(prog="riser-tools accuracy-fit", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/fasttest/riser")
    ap.add_argument("--runs", default="docs/accuracy_runs.csv")
    ap.add_argument("constants", nargs="*", type=float, help="E_w C_wk C_wt to print the points against")
    args = ap.parse_args(argv)
    pts = points(args.bin, args.runs)
    score, ew, ck, ct = fit(pts)
    print(f"tightest bound: E_w {ew:g}, C_wk {ck:g}, C_wt {ct:.3f} (sum of log(model/error) {score:.1f})")
    if len(args.constants) == 3:
        ew, ck, ct = args.constants
    for (case, n, dt, e, s, xt, xk) in pts:
        model = s + ct * xt + ck * xk + ew
        print(f"{case:24s} {n:4d} {dt:6.3f} e {e:.1e} model {model:.1e} ratio {model / e:5.1f} "
              f"(still {s:.1e}, step {ct * xt:.1e}, mesh {ck * xk:.1e})")
    return 0


if __name__ == "__main__":
    main()
