#!/usr/bin/env python3
"""Plot the static shape and tension written by `riser statics --out DIR`.

usage: plot_statics.py shape.csv shape.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src: str, dst: str) -> None:
    with open(src, newline="") as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    s = [r["S"] for r in rows]
    x = [r["x"] for r in rows]
    z = [r["z"] for r in rows]
    t = [r["tension"] / 1e3 for r in rows]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    ax1.plot(x, z, "-", color="C0", lw=2)
    ax1.plot([x[0], x[-1]], [z[0], z[-1]], "ks", ms=6)
    ax1.set_xlabel("x [m]")
    ax1.set_ylabel("z [m]")
    ax1.set_title("static shape")
    ax1.set_aspect("equal")
    ax1.grid(True, alpha=0.4)
    ax2.plot(s, t, "-", color="C1")
    ax2.set_xlabel("S from hang-off [m]")
    ax2.set_ylabel("effective tension [kN]")
    ax2.set_title("tension along the line")
    ax2.grid(True, alpha=0.4)
    fig.tight_layout()
    fig.savefig(dst, dpi=120)
    print(f"wrote {dst}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
