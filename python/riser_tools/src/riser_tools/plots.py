"""The figures the studies share: a static shape and its tension, deformed shapes over a
period beside the top tension, a work-precision diagram. Each takes arrays and writes a PNG."""

from __future__ import annotations

import sys
from collections.abc import Mapping, Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def statics(shape: Mapping[str, np.ndarray], dst: str | Path, title: str | None = None,
            surface_z: float | None = None) -> None:
    """shape.csv of `riser statics --out` (columns S, x, z, tension): the shape and the tension along it,
    with the mean water level at `surface_z` (m; None: not drawn) and `title` over both."""
    s, x, z, t = shape["S"], shape["x"], shape["z"], shape["tension"] / 1e3
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    if surface_z is not None:
        ax1.axhline(surface_z, color="tab:blue", lw=0.8, alpha=0.5, ls="--", label="mean water level")
    ax1.plot(x, z, "-", color="C0", lw=2)
    ax1.plot([x[0], x[-1]], [z[0], z[-1]], "ks", ms=6)
    if surface_z is not None:
        ax1.legend(loc="upper right", fontsize=8)
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
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(dst, dpi=120)
    plt.close(fig)


def shapes_axis(ax, curves: Sequence[tuple[float, np.ndarray, np.ndarray]], title: str) -> None:
    """Deformed shapes (t, x, z) in the x-z plane, equal axes, one line each."""
    for t, x, z in curves:
        ax.plot(x, z, lw=1.0, label=f"t = {t:.1f} s")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title(title)


def shapes_and_tension(curves: Sequence[tuple[float, np.ndarray, np.ndarray]], t: np.ndarray,
                       top_tension: np.ndarray, title: str, dst: str | Path) -> None:
    """The paper's figures: deformed shapes over the last period beside the top tension (kN)."""
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.8))
    shapes_axis(ax1, curves, "deformed shapes over the last period")
    ax2.plot(t, top_tension / 1e3, lw=0.6)
    ax2.set_xlabel("t (s)")
    ax2.set_ylabel("top tension (kN)")
    ax2.grid(True, alpha=0.3)
    ax2.set_title("top tension")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(dst, dpi=110)
    plt.close(fig)


def shapes_csv_curves(rows: Sequence[Mapping[str, str]]) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """shapes.csv of `riser run --out` as (t, x, z) per output time."""
    times = sorted({float(r["t"]) for r in rows})
    out = []
    for t in times:
        sel = [r for r in rows if float(r["t"]) == t]
        out.append((t, np.array([float(r["x"]) for r in sel]), np.array([float(r["z"]) for r in sel])))
    return out


def main(argv: Sequence[str] | None = None) -> None:
    """`riser-tools plot-statics shape.csv shape.png [--title T] [--surface-z Z]`: the figure of
    `riser statics --out DIR` (with the mean water level at Z m if given)."""
    import argparse

    from .cli import read_columns
    ap = argparse.ArgumentParser(prog="riser-tools plot-statics", description=main.__doc__)
    ap.add_argument("shape_csv")
    ap.add_argument("png")
    ap.add_argument("--title", default=None, help="the figure's title (e.g. the scene's name)")
    ap.add_argument("--surface-z", type=float, default=None,
                    help="the mean water level, m (the scene's water_surface_z; not drawn if not given)")
    args = ap.parse_args(sys.argv[1:] if argv is None else argv)
    statics(read_columns(args.shape_csv), args.png, title=args.title, surface_z=args.surface_z)
    print(f"wrote {args.png}")
