"""`riser-tools plot-fatigue fatigue.csv fatigue.png [--title T]`: the damage along the line of
`riser run --fatigue CURVE --out DIR` (docs/theory.md §12.5): per arc length the largest damage
over the 8 fibres, log scale, with the worst point marked."""

from __future__ import annotations

import sys
from collections.abc import Sequence

import numpy as np


def damage_along(columns: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(S, the largest damage over the fibres, its fibre) per point of fatigue.csv's columns."""
    s, fibre, damage = columns["S"], columns["fibre"].astype(int), columns["damage"]
    points = np.unique(s)
    worst = np.array([damage[s == p].max() for p in points])
    which = np.array([fibre[s == p][np.argmax(damage[s == p])] for p in points])
    return points, worst, which


def plot(columns: dict[str, np.ndarray], png: str, title: str | None = None) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    s, worst, which = damage_along(columns)
    fig, ax = plt.subplots(figsize=(8, 4))
    positive = worst > 0
    ax.semilogy(s[positive], worst[positive], "k-", lw=1.2, label="largest over the 8 fibres")
    i = int(np.argmax(worst))
    ax.semilogy([s[i]], [worst[i]], "ro",
                label=f"worst: S = {s[i]:.1f} m, fibre {which[i]} ({45 * which[i]} deg), D = {worst[i]:.3e}")
    ax.set_xlabel("arc length S from the hang-off (m)")
    ax.set_ylabel("Miner's damage over the steady window")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    ax.set_title(title or "fatigue damage along the line")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def main(argv: Sequence[str] | None = None) -> None:
    """`riser-tools plot-fatigue fatigue.csv fatigue.png [--title T]`: the damage along the line
    of `riser run --fatigue CURVE --out DIR` (the largest over the fibres per point, log scale)."""
    import argparse

    from .cli import read_columns
    ap = argparse.ArgumentParser(prog="riser-tools plot-fatigue", description=main.__doc__)
    ap.add_argument("fatigue_csv")
    ap.add_argument("png")
    ap.add_argument("--title", default=None, help="the figure's title (e.g. the scene and the curve)")
    args = ap.parse_args(sys.argv[1:] if argv is None else argv)
    plot(read_columns(args.fatigue_csv), args.png, title=args.title)
    print(f"wrote {args.png}")
