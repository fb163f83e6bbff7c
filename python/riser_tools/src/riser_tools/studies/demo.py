"""`make demo`: the paper's catenary case through the FMU with fmpy.

Heave 2.5 m, T = 20 s at the hang-off, grown over one period (as `riser run` does by default;
`--ramp 0` is the paper's abrupt start), current 0.8 m/s, 100 s, from the static state. Prints the
static top tension, the top tension's min/mean/max over the steady window (one period after the
ramp to the end) and over the whole run, labelled, the energy balance residual, the wall time and
the real-time factor (of fmpy's loop with the FMU in it); writes out/demo/fmu_timeseries.csv, out/demo/shapes.png (deformed shapes over
the last period, as the paper's Fig. 4) and out/demo/tension_energy.png.

Structural damping 2 ms (docs/theory.md §5.9) damps the axial waves that an abrupt start rings; `--damping 0` runs the paper's conserving scheme. The inputs are the displacement and its
velocity: the FMU interpolates the motion smoothly (cubic Hermite) across a communication step;
with the displacement alone it is piecewise linear, and its velocity kinks ring the axial waves.
"""

from __future__ import annotations

import csv
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from .. import fmu, plots, report
from ..cases import Motion

OUTPUTS = ["top_tension", "top_force_x", "top_force_z", "bottom_tension", "min_tension", "total_energy",
           "kinetic_energy", "strain_energy", "potential_energy", "work_top", "work_hydro", "dissipated_energy",
           "algorithmic_dissipation"]
SHAPE = [f"shape[{k}].{c}" for k in range(21) for c in "xz"]


def main(argv: Sequence[str] | None = None) -> None:
    ap = report.parser("demo", __doc__, bin=False, fmu=True, out="out/demo", docs=False)
    ap.add_argument("--damping", type=float, default=0.002)
    ap.add_argument("--duration", type=float, default=100.0)
    ap.add_argument("--ramp", type=float, default=20.0, help="s; 0 is the paper's abrupt start (default one period)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    motion, dt = Motion(2.5, 20.0, ramp=args.ramp), 0.1
    r = fmu.simulate(args.fmu, motion, args.duration, dt, OUTPUTS + SHAPE, {"structural_damping": args.damping},
                     t=np.arange(0.0, args.duration + 1e-9, dt))
    s, wall = r.series, r.wall
    tt = s["top_tension"]
    residual, exchanged = fmu.energy_balance(s)
    print(f"riser FMU demo: catenary scene, heave {motion.amplitude} m / {motion.period} s, current 0.8 m/s, "
          f"{args.duration:g} s, structural damping {args.damping} s")
    t0 = min(args.ramp + motion.period, 0.5 * args.duration)
    steady = tt[s["t"] >= t0 - 1e-9]
    start = f"grown over {args.ramp:g} s" if args.ramp > 0 else "abrupt start (the paper's)"
    print(f"  static top tension       {tt[0] / 1e3:10.3f} kN")
    print(f"  steady window {t0:g} to {args.duration:g} s ({start}):")
    print(f"    top tension            min {steady.min() / 1e3:.3f} / mean {steady.mean() / 1e3:.3f} / "
          f"max {steady.max() / 1e3:.3f} kN")
    print(f"  whole run, with the start: top tension min {tt.min() / 1e3:.3f} / mean {tt.mean() / 1e3:.3f} / "
          f"max {tt.max() / 1e3:.3f} kN")
    print(f"  energy balance residual  {residual:.3e} J ({residual / exchanged:.1e} of the {exchanged:.3e} J exchanged)")
    print(f"  wall time                {wall:.2f} s (real-time factor {args.duration / wall:.1f}, fmpy's loop "
          f"included)")
    with open(out / "fmu_timeseries.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t"] + OUTPUTS)
        for row in r.result:
            w.writerow([row["time"]] + [row[n] for n in OUTPUTS])
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 6))
    last = s["t"] >= args.duration - motion.period - 1e-9
    rows = r.result[last][:: int(round(motion.period / 8 / dt))]
    plots.shapes_axis(ax, [(row["time"], np.array([row[f"shape[{k}].x"] for k in range(21)]),
                            np.array([row[f"shape[{k}].z"] for k in range(21)])) for row in rows],
                      "catenary riser: deformed shapes over the last period")
    fig.tight_layout()
    fig.savefig(out / "shapes.png", dpi=110)
    plt.close(fig)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    a1.plot(s["t"], tt / 1e3, lw=0.8)
    a1.set_ylabel("top tension (kN)")
    a1.grid(True, alpha=0.3)
    for n in ["total_energy", "work_top", "work_hydro"]:
        a2.plot(s["t"], (s[n] - (s[n][0] if n == "total_energy" else 0)) / 1e3, label=n)
    a2.set_ylabel("energy (kJ)")
    a2.set_xlabel("t (s)")
    a2.grid(True, alpha=0.3)
    a2.legend()
    fig.tight_layout()
    fig.savefig(out / "tension_energy.png", dpi=110)
    plt.close(fig)
    print(f"  wrote {out}/fmu_timeseries.csv, shapes.png, tension_energy.png")
