#!/usr/bin/env python3
"""The command line against an earlier build, interleaved (issue 49, evidence 4: "a one-line
scene answers bit for bit today's, its cost unchanged").

For each mesh (default 5, 10 and 60 elements) the catenary heaved 2.5 m / 10 s for --duration
seconds by `riser run catenary --set n_elements=N --heave 2.5,10 --out DIR`, by the old and the
new binary in turn, --repeat rounds, the order alternating (old first, then new first), so a
machine's drift falls on both alike. Reported per mesh: the median wall time of each and their
ratio (new / old), whether timeseries.csv has the same text in every old column (a new build
may add columns), and with --instructions the
instructions each run retires under valgrind's callgrind (`Collected`, one run each: exact,
whatever the machine's load, where the wall time of a busy machine is not).

Usage: riser-tools bench-cli --old OLD_BIN --new NEW_BIN [--elements 5,10,60] [--duration 60]
       [--repeat 5] [--instructions] [--set time_step=0.2 ...]
Prints a Markdown table (the section of docs/performance.md).
"""

from __future__ import annotations

import argparse
import csv
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


SETS: list[str] = []  # --set NAME=VALUE of the command line (e.g. time_step=0.2), for every run


def run_args(n: int, duration: float, out: Path) -> list[str]:
    sets = [a for kv in SETS for a in ("--set", kv)]
    return ["run", "catenary", "--set", f"n_elements={n}", *sets, "--heave", "2.5,10", "--duration", str(duration),
            "--out", str(out)]


def same_columns(old: Path, new: Path) -> tuple[bool, list[str]]:
    """Whether every column of the old timeseries.csv is in the new one with the same text in
    every row (the new build may add columns); and the columns it adds."""
    with open(old, newline="") as f:
        a = list(csv.reader(f))
    with open(new, newline="") as f:
        b = list(csv.reader(f))
    if len(a) != len(b):
        return False, []
    where = {name: i for i, name in enumerate(b[0])}
    if any(name not in where for name in a[0]):
        return False, []
    same = all([row_b[where[name]] for name in a[0]] == row_a for row_a, row_b in zip(a, b))
    return same, [name for name in b[0] if name not in a[0]]


def wall(binary: str, n: int, duration: float, out: Path) -> float:
    start = time.perf_counter()
    subprocess.run([binary, *run_args(n, duration, out)], check=True, capture_output=True)
    return time.perf_counter() - start


def instructions(binary: str, n: int, duration: float, out: Path) -> int:
    """Instructions retired by one run under callgrind."""
    done = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", binary,
                           *run_args(n, duration, out)], check=True, capture_output=True, text=True)
    m = re.search(r"Collected\s*:\s*(\d+)", done.stderr)
    if not m:
        raise RuntimeError(f"callgrind printed no count:\n{done.stderr[-2000:]}")
    return int(m.group(1))


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="riser-tools bench-cli", description=__doc__.split("\n\n")[0])
    p.add_argument("--old", required=True, help="the earlier build's riser binary")
    p.add_argument("--new", required=True, help="this build's riser binary")
    p.add_argument("--elements", default="5,10,60", help="meshes, comma-separated (default 5,10,60)")
    p.add_argument("--duration", type=float, default=60.0, help="simulated seconds a run (default 60)")
    p.add_argument("--repeat", type=int, default=5, help="rounds of each (default 5)")
    p.add_argument("--instructions", action="store_true", help="also count instructions under callgrind")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter of every run (e.g. time_step=0.2), repeatable")
    a = p.parse_args(argv)
    SETS[:] = a.set
    meshes = [int(x) for x in a.elements.split(",")]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        for n in meshes:
            times: dict[str, list[float]] = {"old": [], "new": []}
            for r in range(a.repeat):
                order = ("old", "new") if r % 2 == 0 else ("new", "old")
                for which in order:
                    binary = a.old if which == "old" else a.new
                    times[which].append(wall(binary, n, a.duration, root / f"{which}{n}"))
            same, added = same_columns(root / f"old{n}" / "timeseries.csv", root / f"new{n}" / "timeseries.csv")
            row = {"n": n, "old": statistics.median(times["old"]), "new": statistics.median(times["new"]),
                   "same": same, "added": added}
            if a.instructions:
                row["old_ir"] = instructions(a.old, n, a.duration, root / f"ir_old{n}")
                row["new_ir"] = instructions(a.new, n, a.duration, root / f"ir_new{n}")
            rows.append(row)
            print(f"{n} elements done", file=sys.stderr, flush=True)
    head = "| elements | old, s (median) | new, s (median) | new / old |"
    rule = "|---|---|---|---|"
    if a.instructions:
        head += " old, instructions | new, instructions | new / old |"
        rule += "---|---|---|"
    print(head + " timeseries.csv |")
    print(rule + "---|")
    for r in rows:
        line = f"| {r['n']} | {r['old']:.3f} | {r['new']:.3f} | {r['new'] / r['old']:.3f} |"
        if a.instructions:
            line += f" {r['old_ir']:,} | {r['new_ir']:,} | {r['new_ir'] / r['old_ir']:.4f} |"
        print(line + (" the same text |" if r["same"] else " **differs** |"))
    added = sorted({c for r in rows for c in r["added"]})
    if added:
        print(f"\n(the new build's timeseries.csv adds the columns {', '.join(added)}; the old columns compared)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
