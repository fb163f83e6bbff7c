#!/usr/bin/env python3
"""The seed paper's runs (the list of the project's contract), reproduced with `riser run`.

Usage: python scripts/paper_runs.py [--bin target/release/riser] [--out out/paper]
       [--docs docs] [--only NAME ...] [--damping ETA]

Every run: 100 s from the static state, heave U0 sin(2πt/T) at the hang-off
(the paper's abrupt start). Writes per run out/paper/<name>/{timeseries,shapes}.csv,
figures docs/figures/paper_<name>.png (deformed shapes over the last period, as
the paper's figures 4–13, and the top tension against time), and the table
docs/paper_runs.md with the figures of every run.
"""

import argparse
import csv
import json
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# name, scene, --set overrides, (U0, T), heave_until, what the paper shows
RUNS = [
    ("catenary_T20", "catenary", [], (2.5, 20.0), None, "Fig. 4: catenary, T = 20 s, current 0.8 m/s"),
    ("catenary_T15", "catenary", [], (2.5, 15.0), None, "Fig. 5: catenary, T = 15 s, current 0.8 m/s"),
    ("current_m0.1", "catenary", ["current_top=-0.1", "current_bottom=-0.1"], (2.5, 20.0), None,
     "Fig. 6: current -0.1 m/s"),
    ("current_0", "catenary", ["current_top=0", "current_bottom=0"], (2.5, 20.0), None, "Fig. 6: no current"),
    ("current_0.25", "catenary", ["current_top=0.25", "current_bottom=0.25"], (2.5, 20.0), None,
     "Fig. 7: current 0.25 m/s"),
    ("current_0.5", "catenary", ["current_top=0.5", "current_bottom=0.5"], (2.5, 20.0), None,
     "Fig. 7: current 0.5 m/s"),
    ("mesh_10", "catenary", ["n_elements=10", "current_top=0.5", "current_bottom=0.5"], (2.5, 20.0), None,
     "Fig. 8: 10 elements, 0.5 m/s"),
    ("mesh_40", "catenary", ["n_elements=40", "current_top=0.5", "current_bottom=0.5"], (2.5, 20.0), None,
     "Fig. 8: 40 elements, 0.5 m/s"),
    ("mesh_54", "catenary", ["n_elements=54", "current_top=0.5", "current_bottom=0.5"], (2.5, 20.0), None,
     "Fig. 9: 54 elements, 0.5 m/s"),
    ("mesh_60", "catenary", ["n_elements=60", "current_top=0.5", "current_bottom=0.5"], (2.5, 20.0), None,
     "Fig. 9: 60 elements, 0.5 m/s"),
    ("free_motion", "catenary", ["cd_normal=0", "cd_tangential=0", "current_top=0", "current_bottom=0"],
     (2.5, 20.0), 15.0, "Figs. 10-11: 15 s of excitation, then free motion, no drag"),
    ("lazy_wave", "lazy_wave", [], (2.5, 30.0), None, "Fig. 12: lazy wave, T = 30 s, current 0.8 -> 0.3 m/s"),
    ("lazy_wave_reverse", "lazy_wave", ["current_top=0.3", "current_bottom=0.8"], (2.5, 30.0), None,
     "Fig. 13: lazy wave, current 0.3 -> 0.8 m/s"),
]


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def plot(name, title, run_dir, fig_path):
    ts = read_csv(run_dir / "timeseries.csv")
    shapes = read_csv(run_dir / "shapes.csv")
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.8))
    times = sorted({float(r["t"]) for r in shapes})
    for t in times:
        rows = [r for r in shapes if float(r["t"]) == t]
        ax1.plot([float(r["x"]) for r in rows], [float(r["z"]) for r in rows], lw=1.0, label=f"t = {t:.1f} s")
    ax1.set_xlabel("x (m)")
    ax1.set_ylabel("z (m)")
    ax1.set_aspect("equal", adjustable="datalim")
    ax1.grid(True, alpha=0.3)
    ax1.legend(fontsize=7)
    ax1.set_title("deformed shapes over the last period")
    t = [float(r["t"]) for r in ts]
    ax2.plot(t, [float(r["top_tension"]) / 1e3 for r in ts], lw=0.6)
    ax2.set_xlabel("t (s)")
    ax2.set_ylabel("top tension (kN)")
    ax2.grid(True, alpha=0.3)
    ax2.set_title("top tension")
    fig.suptitle(f"{name}: {title}")
    fig.tight_layout()
    fig.savefig(fig_path, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default="target/release/riser")
    ap.add_argument("--out", default="out/paper")
    ap.add_argument("--docs", default="docs")
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--damping", type=float, default=0.0, help="structural_damping (s); 0 = the paper's scheme")
    args = ap.parse_args()
    suffix = "" if args.damping == 0.0 else "_damped"
    out = Path(args.out + suffix)
    figs = Path(args.docs) / "figures"
    figs.mkdir(parents=True, exist_ok=True)
    rows = []
    for name, scene, sets, (u0, period), until, title in RUNS:
        if args.only and name not in args.only:
            continue
        run_dir = out / name
        cmd = [args.bin, "run", scene, "--heave", f"{u0},{period}", "--duration", "100", "--json",
               "--out", str(run_dir), "--set", f"structural_damping={args.damping}"]
        for s in sets:
            cmd += ["--set", s]
        if until is not None:
            cmd += ["--heave-until", str(until)]
        print("running", name, flush=True)
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0 and not p.stdout.strip():
            print(p.stderr, file=sys.stderr)
            rows.append((name, title, None, p.stderr.strip().splitlines()[-1]))
            continue
        v = json.loads(p.stdout)
        extra = ""
        if until is not None:
            ts = read_csv(run_dir / "timeseries.csv")
            e_after = [float(r["total_energy"]) for r in ts if float(r["t"]) > until + 1e-9]
            drift = max(abs(e - e_after[0]) for e in e_after)
            extra = f"energy after {until:g} s constant to {drift:.2e} J ({drift / abs(e_after[0]):.1e} of |E|)"
            v["free_motion_drift"] = drift
        plot(name, title, run_dir, figs / f"paper_{name}{suffix}.png")
        rows.append((name, title, v, extra))
    with open(Path(args.docs) / f"paper_runs{suffix}.md", "w") as f:
        f.write("# The paper's runs\n\n")
        f.write("Made by `python scripts/paper_runs.py` (`make paper`), 100 s each from the static state, heave "
                "U0 sin(2πt/T) with the paper's abrupt start, time step 0.05 s, Newton tolerance 1e-8, "
                f"structural damping {args.damping} s. ")
        if args.damping == 0.0:
            f.write("Tension in kN. The start's velocity jump rings the undamped axial waves "
                    "(docs/VALIDATION.md, known limitations): the min/max include that ringing, for the whole run; "
                    "the deformed shapes are those of the last period. The same runs with structural damping: "
                    "[paper_runs_damped.md](paper_runs_damped.md).\n\n")
        else:
            f.write("Tension in kN. With structural damping (theory §5.9) the axial ringing of the abrupt start "
                    "decays within seconds; the max still contains the start's axial wave. The undamped runs: "
                    "[paper_runs.md](paper_runs.md).\n\n")
        f.write("| run | case | static top T | top T min / mean / max | energy balance (rel. to exchanged) "
                "| steps | Newton/step | wall (s) | real-time factor | figure |\n")
        f.write("|---|---|---|---|---|---|---|---|---|---|\n")
        for name, title, v, extra in rows:
            if v is None:
                f.write(f"| {name} | {title} | — | failed: {extra} | | | | | | |\n")
                continue
            tt = v["top_tension"]
            note = f" {extra}" if extra else ""
            f.write(
                f"| {name} | {title} | {v['static_top_tension'] / 1e3:.2f} | {tt['min'] / 1e3:.1f} / "
                f"{tt['mean'] / 1e3:.2f} / {tt['max'] / 1e3:.1f} | {v['energy_balance_relative']:.1e}{note} | "
                f"{v['steps']} | {v['iterations_per_step']:.2f} | {v['solve_wall_time']:.2f} | "
                f"{v['real_time_factor']:.1f} | ![](figures/paper_{name}{suffix}.png) |\n"
            )
    print("wrote", Path(args.docs) / f"paper_runs{suffix}.md")


if __name__ == "__main__":
    main()
