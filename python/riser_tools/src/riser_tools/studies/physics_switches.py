#!/usr/bin/env python3
"""Cost of each physics switch (docs/performance.md): the catenary scene,
60 elements, dt 0.05 s, 100 s of heave 2.5 m / 20 s grown over one period,
one thing switched at a time. Prints the Markdown rows: `riser run --json`'s
solve_wall_time (the time stepping with its per-step outputs, statics
excluded), median of 3 runs, the real-time factor, Newton iterations per step
and the top tension's range.

A plain loop: the wall time is the result.

    riser-tools physics-switches [--bin target/release/riser] [--runs 3]
"""

import argparse

from .. import cli
from ..cases import Motion

CASES = [
    ("scene as built (drag, current 0.8 m/s)", []),
    ("drag off (C_Dn = C_Dt = 0: the fluid pass is skipped)", ["cd_normal=0", "cd_tangential=0"]),
    ("current off (drag still on)", ["current_top=0", "current_bottom=0"]),
    ("added mass on (C_a = 1)", ["ca_normal=1"]),
    ("structural damping 2 ms (a second element pass)", ["structural_damping=0.002"]),
    ("EI × 100", ["bending_stiffness=5.882e6"]),
]


def main(argv=None):
    ap = argparse.ArgumentParser(prog="riser-tools physics-switches", description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default="target/release/riser")
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args(argv)
    print("| case | wall (s) | real-time factor | Newton / step | top tension min / max (kN) |")
    print("|---|---|---|---|---|")
    for name, sets in CASES:
        # the current in full from t = 0 (current_ramp 0), as this page was measured before the current grew over its
        # first 10 s by default (docs/theory.md §5.11): the committed figures reproduce
        r = cli.run(args.bin, "catenary", [*sets, "current_ramp=0"], Motion(2.5, 20.0, ramp=20.0), 100.0,
                    repeats=args.runs)
        d, w = r.summary, r.wall
        t = d["top_tension"]
        print(
            f"| {name} | {w:.2f} | {100 / w:.0f}× | {d['iterations_per_step']:.2f} "
            f"| {t['min'] / 1e3:.2f} / {t['max'] / 1e3:.2f} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
