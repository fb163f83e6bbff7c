"""The wave terms' constants of the accuracy knob's error model (docs/theory.md §16.4), checked
against the study's runs (docs/accuracy_runs.csv, written by `riser-tools accuracy`):

    e_w = S [C_wt (ω_w Δt)^1.5 + min(C_wk2 (h k_w)², C_wk (h k_w)⁴)] + E_w + [regular wave] E_c F_c,

on top of the still-water terms C_κ (h κ)⁴ + C_t (A/A₀)(ω Δt)^1.5 with their constants (the run's
own heave; none: zero). For each wave case the scales (S, F_c, k_w, ω_w, the line's length and
largest curvature) are read from the binary's own choice (`--json`'s `accuracy` object); every
grid run with at least 75 steps per period is a point. Printed: each constant's envelope, the
smallest value that bounds every point with the others as given (C_wk with C_wk2 left out and
C_wk2 with C_wk left out: each of the two mesh bounds holds alone), and each point's error
against the model.

    riser-tools accuracy-fit [--bin target/fasttest/riser] [--runs docs/accuracy_runs.csv]
                             [C_wt C_wk C_wk2 E_w E_c]
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
# the wave constants of src/sim/accuracy.rs: C_WAVE_TIME, C_WAVE_MESH, C_WAVE_MESH2, WAVE_FLOOR,
# C_CURRENT_RINGING
CONSTANTS = (0.05, 0.05, 0.018, 3.5e-5, 7.5e-3)
NAMES = ("C_wt", "C_wk", "C_wk2", "E_w", "E_c")


def points(binary: str, runs: str):
    rows = list(csv.DictReader(open(runs)))
    out = []
    for case, (scene, amp, period, els, sea, dur, win) in A.WAVE_CASES.items():
        if case in A.STILL_CASES:
            # no sea: their floor is E_s F_c (docs/theory.md 16.6, C_STILL_CURRENT), not a wave term
            continue
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
        s, fc, regular = d["wave_load_ratio"], d["current_load_ratio"], d["wave_regular"]
        print(f"{case}: S {s:.4f}, F_c {fc:.4f}, k_w {d['wave_number']:.4f} rad/m, "
              f"omega_w {d['wave_omega']:.4f} rad/s, {'regular' if regular else 'spectrum'}")
        for r in m:
            if r["kind"] != "grid":
                continue
            n, dt = int(r["n_elements"]), float(r["time_step"])
            if dt * 75 > min(2 * math.pi / d["wave_omega"], period) * (1 + 1e-9):
                continue
            h = d["length"] / n
            still = C_K * (h * d["max_curvature"]) ** 4 + C_T * amp / 10 * (2 * math.pi / period * dt) ** 1.5
            hk = h * d["wave_number"]
            x = dict(t=s * (d["wave_omega"] * dt) ** 1.5, k4=s * hk ** 4, k2=s * hk ** 2, c=fc if regular else 0.0)
            out.append((case, n, dt, A.error(r, ref), still, x))
    return out


def model(c, still, x):
    ct, ck, ck2, ew, ec = c
    return still + ct * x["t"] + min(ck2 * x["k2"], ck * x["k4"]) + ew + ec * x["c"]


def envelope(pts, c, i):
    """The smallest value of constant i that bounds every point, the others as in c (for a mesh
    constant, with the other mesh bound left out)."""
    lo, hi = 0.0, 1.0
    other = {1: 2, 2: 1}.get(i)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        q = list(c)
        q[i] = mid
        if other is not None:
            q[other] = 1e9
        if all(model(q, s, x) >= e for (_, _, _, e, s, x) in pts):
            hi = mid
        else:
            lo = mid
    return hi


def main(argv=None):
    ap = argparse.ArgumentParser(prog="riser-tools accuracy-fit", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/fasttest/riser")
    ap.add_argument("--runs", default="docs/accuracy_runs.csv")
    ap.add_argument("constants", nargs="*", type=float, help="C_wt C_wk C_wk2 E_w E_c")
    args = ap.parse_args(argv)
    c = tuple(args.constants) if len(args.constants) == 5 else CONSTANTS
    pts = points(args.bin, args.runs)
    print("constants: " + ", ".join(f"{n} {v:g}" for n, v in zip(NAMES, c)))
    print("envelopes, each with the others as given: "
          + ", ".join(f"{n} {envelope(pts, c, i):.3g}" for i, n in enumerate(NAMES)))
    worst = min(model(c, s, x) / e for (_, _, _, e, s, x) in pts)
    print(f"smallest model / error over {len(pts)} points: {worst:.3f}")
    for (case, n, dt, e, s, x) in pts:
        m = model(c, s, x)
        print(f"{case:24s} {n:4d} {dt:6.3f} e {e:.1e} model {m:.1e} ratio {m / e:5.1f} "
              f"(still {s:.1e}, step {c[0] * x['t']:.1e}, mesh {min(c[2] * x['k2'], c[1] * x['k4']):.1e}, "
              f"floor {c[3] + c[4] * x['c']:.1e})")
    return 0


if __name__ == "__main__":
    main()
