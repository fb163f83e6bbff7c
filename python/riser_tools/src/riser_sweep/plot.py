"""`riser-sweep plot DIR`: the top tension's range (min to max over the window,
the mean marked) against each swept parameter, one panel each, as a PNG."""

from __future__ import annotations

import math
from collections import defaultdict
from pathlib import Path

from .results import read_results


def _number(s: str) -> float | None:
    try:
        x = float(s)
    except ValueError:
        return None
    return x if math.isfinite(x) else None


def plot(out_dir: str | Path, png: str | Path | None = None) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out_dir = Path(out_dir)
    params, rows = read_results(out_dir)
    ok = [r for r in rows if r["status"] == "ok"]
    failed = len(rows) - len(ok)
    cols = params or ["case"]
    n = len(cols)
    ncols = min(n, 3)
    nrows = math.ceil(n / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols, 4.0 * nrows), squeeze=False)
    for ax, col in zip(axes.flat, cols):
        raw = [r.get(col, str(i)) for i, r in enumerate(ok)]
        nums = [_number(v) for v in raw]
        numeric = all(v is not None for v in nums) and bool(nums)
        if numeric:
            xs = [float(v) for v in nums]  # type: ignore[arg-type]
            distinct = sorted(set(xs))
            gap = min((b - a for a, b in zip(distinct, distinct[1:])), default=1.0)
        else:
            labels = list(dict.fromkeys(raw))
            xs = [float(labels.index(v)) for v in raw]
            gap = 1.0
            ax.set_xticks(range(len(labels)), labels, rotation=20)
        # one series per combination of the other parameters, side by side: the range as a bar,
        # the mean as a dot, the means joined
        others = [c for c in params if c != col]
        groups: dict[tuple[str, ...], list[int]] = defaultdict(list)
        for i, r in enumerate(ok):
            groups[tuple(r[c] for c in others)].append(i)
        k = len(groups)
        for g, (key, idx) in enumerate(sorted(groups.items())):
            dx = (g - (k - 1) / 2) * 0.15 * gap / k if k > 1 else 0.0
            idx.sort(key=lambda i: xs[i])
            x = [xs[i] + dx for i in idx]
            lo, mid, hi = ([float(ok[i][c]) / 1e3 for i in idx]
                           for c in ("top_tension_min", "top_tension_mean", "top_tension_max"))
            label = ", ".join(f"{c}={v}" for c, v in zip(others, key)) if 1 < k <= 10 else None
            color = f"C{g % 10}"
            ax.vlines(x, lo, hi, color=color, lw=2, alpha=0.6)
            ax.plot(x, mid, "o-", color=color, ms=3, lw=0.8, label=label)
        if 1 < k <= 10:
            ax.legend(fontsize=7)
        ax.set_xlabel(col)
        ax.set_ylabel("top tension (kN): min to max, mean")
        ax.grid(True, alpha=0.3)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    note = f" ({failed} failed cases left out)" if failed else ""
    fig.suptitle(f"{out_dir}: top tension range, {len(ok)} cases{note}", fontsize=10)
    fig.tight_layout()
    png = Path(png) if png else out_dir / "tension_range.png"
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return png
