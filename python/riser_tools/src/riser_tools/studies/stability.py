#!/usr/bin/env python3
"""Stability at the extremes (issue 5): runs `riser run` over a matrix of
settings, one axis at a time from the catenary scene (heave 2.5 m / 20 s,
current 0.8 m/s, 60 elements, dt 0.05 s), and writes docs/stability.md.

Each cell either completes with the energy balance closed and finite outputs,
or fails cleanly with a message; a crash, a hang (timeout) or a NaN is a
failure of the cell and is reported as such.

A plain loop, not a riser-sweep spec: the cells check the CLI itself (a crash, a hang under a
timeout, the "riser: error" of a clean stop, a NaN in the CSV), which an fmpy run in a worker
cannot see, and they go one axis at a time, not a product.

    riser-tools stability [--bin target/release/riser] [--duration 20] [--out docs/stability.md]
"""

import argparse
import json
import math
import subprocess
import time
from collections.abc import Sequence
from pathlib import Path

from .. import cli
from ..cases import Case, Motion, unique_labels

CATENARY_HEAVE = Motion(2.5, 20.0)
LAZY_WAVE_HEAVE = Motion(2.5, 30.0)


def cell(axis: str, label: str, scene: str, sets: Sequence[str], motion: Motion = CATENARY_HEAVE,
         factor: float = 1.0) -> Case:
    """One cell; `factor` scales the duration (dt = 1e-4 s runs 1/20 of it). The duration is set
    when the matrix runs (Case.duration holds the factor)."""
    return Case(f"{axis}: {label}", scene, tuple(sets), motion, factor, group=axis, note=label)


CELLS = [cell("time step", f"dt = {dt} s", "catenary", [f"time_step={dt}"], factor=0.05 if dt == "1e-4" else 1.0)
         for dt in ["1e-4", "1e-3", "0.01", "0.1", "0.5", "1"]]
CELLS += [cell("elements", f"{n} elements", "catenary", [f"n_elements={n}"]) for n in [4, 10, 100, 400]]
CELLS += [cell("EA", f"EA = {ea} N", "catenary", [f"axial_stiffness={ea}"]) for ea in ["1e6", "1e7", "1e9", "1e10", "1e11"]]
CELLS += [cell("EI", f"EI = {ei} N m²", "catenary", [f"bending_stiffness={ei}"]) for ei in ["0", "1", "1e3", "1e6", "1e7"]]
CELLS += [cell("heave", f"heave {a:g} m / {t:g} s", "catenary", [], Motion(a, t))
          for a, t in [(5.0, 3.0), (10.0, 3.0), (10.0, 10.0), (10.0, 20.0)]]
CELLS += [cell("current", f"current {c} m/s", "catenary", [f"current_top={c}", f"current_bottom={c}"])
          for c in ["-3", "-1", "1.5", "3"]]
CELLS += [
    cell("lazy wave", "buoyancy doubled (1340 N/m)", "lazy_wave", ["buoyancy_load=1340"], LAZY_WAVE_HEAVE),
    cell("lazy wave", "buoyancy tripled (2010 N/m)", "lazy_wave", ["buoyancy_load=2010"], LAZY_WAVE_HEAVE),
    cell("combined", "EI = 0, heave 10 m / 3 s, current 3 m/s", "catenary",
         ["bending_stiffness=0", "current_top=3", "current_bottom=3"], Motion(10.0, 3.0)),
    cell("combined", "EA = 1e11, dt = 1 s, heave 10 m / 3 s", "catenary", ["axial_stiffness=1e11", "time_step=1"],
         Motion(10.0, 3.0)),
]
# the cable model (model = "cable") over the same extremes
CELLS += [cell("cable", label, scene, ["model=cable"] + sets, motion, 0.05 if "1e-3" in label else 1.0)
          for label, scene, sets, motion in [
              ("dt = 1e-3 s", "catenary", ["time_step=1e-3"], CATENARY_HEAVE),
              ("dt = 1 s", "catenary", ["time_step=1"], CATENARY_HEAVE),
              ("4 elements", "catenary", ["n_elements=4"], CATENARY_HEAVE),
              ("400 elements", "catenary", ["n_elements=400"], CATENARY_HEAVE),
              ("EA = 1e6 N", "catenary", ["axial_stiffness=1e6"], CATENARY_HEAVE),
              ("EA = 1e11 N", "catenary", ["axial_stiffness=1e11"], CATENARY_HEAVE),
              ("heave 10 m / 3 s (slack, snap)", "catenary", [], Motion(10.0, 3.0)),
              ("current -3 m/s", "catenary", ["current_top=-3", "current_bottom=-3"], CATENARY_HEAVE),
              ("current 3 m/s", "catenary", ["current_top=3", "current_bottom=3"], CATENARY_HEAVE),
              ("lazy wave, buoyancy doubled", "lazy_wave", ["buoyancy_load=1340"], LAZY_WAVE_HEAVE),
              ("EA = 1e11, dt = 1 s, heave 10 m / 3 s", "catenary", ["axial_stiffness=1e11", "time_step=1"],
               Motion(10.0, 3.0)),
          ]]
# waves (issue 27): a storm sea on both scenes with their heave, and the
# jumper whose top (5 m under the mean level) is uncovered by every trough
STORM = ["wave_kind=jonswap", "wave_hs=15", "wave_tp=13", "wave_direction=20"]
JUMPER = "docs/cases/lowe_langley_jumper.toml"
THROUGH = ["wave_kind=airy", "wave_height=14", "wave_period=10", "wave_direction=45"]
CELLS += [cell("waves", f"{label}{', cable' if cable else ''}", scene, (["model=cable"] if cable else []) + sets, motion)
          for cable in [False, True]
          for label, scene, sets, motion in [
              ("catenary, JONSWAP Hs 15 m Tp 13 s", "catenary", STORM, CATENARY_HEAVE),
              ("catenary, JONSWAP Hs 15 m Tp 13 s, 400 components", "catenary", STORM + ["wave_components=400"],
               CATENARY_HEAVE),
              ("lazy wave, JONSWAP Hs 15 m Tp 13 s", "lazy_wave", STORM, LAZY_WAVE_HEAVE),
              ("jumper, top through the surface, 14 m / 10 s", JUMPER, THROUGH, Motion(0.0, 10.0)),
          ]]
CELLS = unique_labels(CELLS)


def run_cell(binary: str, c: Case, duration: float, timeout: float, out: str) -> tuple[str, ...]:
    """One cell's row: axis, label, outcome, reason, top tension min / max, energy balance, wall."""
    axis, label = c.group, c.note
    cmd = cli.run_command(binary, c.scene, c.sets, c.motion, duration, out)
    t0 = time.time()
    try:
        p = cli.execute(cmd, timeout=timeout)
        wall = time.time() - t0
    except subprocess.TimeoutExpired:
        return (axis, label, "HANG (timeout)", "", "", "", f"> {timeout:g}")
    if p.returncode not in (0, 1) or not p.stdout.strip():
        msg = (p.stderr.strip().splitlines() or ["no output"])[-1]
        outcome = "clean error" if p.returncode == 1 and msg.startswith("riser: error") else f"CRASH ({p.returncode})"
        return (axis, label, outcome, msg.replace("|", "/"), "", "", f"{wall:.1f}")
    v = json.loads(p.stdout)
    ts = cli.read_rows(f"{out}/timeseries.csv")
    finite = all(math.isfinite(float(x)) for r in ts for k, x in r.items())
    tt = v["top_tension"]
    if not finite:
        outcome = "NaN OUTPUT"
    elif v["completed"]:
        outcome = "completes" if v["energy_balance_relative"] <= 1e-6 else "completes, balance OPEN"
    else:
        outcome = "clean stop (error kept state)"
    reason = "" if v["completed"] else (v.get("error") or "").replace("|", "/")
    return (axis, label, outcome, reason, f"{tt['min'] / 1e3:.1f} / {tt['max'] / 1e3:.1f}",
            f"{v['energy_balance_relative']:.1e}",
            f"{v['solve_wall_time']:.1f} ({v['steps']} steps, {v['iterations_per_step']:.1f} it/step)")


def main(argv=None):
    ap = argparse.ArgumentParser(prog="riser-tools stability", description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", default="target/release/riser")
    ap.add_argument("--duration", type=float, default=20.0)
    ap.add_argument("--timeout", type=float, default=600.0)
    ap.add_argument("--out", default="docs/stability.md")
    args = ap.parse_args(argv)
    rows = []
    for c in CELLS:
        rows.append(run_cell(args.bin, c, args.duration * c.duration, args.timeout, f"out/stability/{len(rows)}"))
        print(c.note, "->", rows[-1][2], flush=True)
    # the hand-written sections after the table (from the first "## " heading) are kept
    previous = Path(args.out).read_text() if Path(args.out).exists() else ""
    kept = previous[previous.index("\n## ") + 1:] if "\n## " in previous else ""
    with open(args.out, "w") as f:
        f.write("# Stability at the extremes\n\n")
        f.write("Made by `riser-tools stability` (`make stability`). From the catenary scene (heave 2.5 m / "
                f"20 s, current 0.8 m/s, 60 elements, dt 0.05 s), one axis at a time, {args.duration:g} s each "
                "(dt = 1e-4 s: 1 s), the paper's abrupt start, no structural damping; the *cable* rows repeat the "
                "extremes with `model = cable`. Outcome: *completes* = every "
                "output finite and the energy balance closed to ≤ 1e-6 of the energy exchanged; *clean stop* = "
                "the run stopped with a typed error and the state kept (the message is the reason). A crash, a "
                "hang or a NaN would be a failure of the cell. The cheap cells run in `make test` "
                "(`tests/it/stability.rs`).\n\n")
        f.write("| axis | cell | outcome | reason | top tension min / max (kN) | energy balance | wall (s) |\n")
        f.write("|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write("| " + " | ".join(r) + " |\n")
        if kept:
            f.write("\n" + kept)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
