"""Time series as the studies reduce them: statistics over a window, errors
against a reference, moving averages."""

from __future__ import annotations

import numpy as np


def in_window(t: np.ndarray, start: float, stop: float = np.inf) -> np.ndarray:
    """The mask start <= t <= stop (to 1e-9 s)."""
    return (t >= start - 1e-9) & (t <= stop + 1e-9)


def window_stats(t: np.ndarray, y: np.ndarray, start: float) -> tuple[float, float, float]:
    """(mean, min, max) of y over t >= start."""
    m = t >= start - 1e-9
    return float(np.mean(y[m])), float(np.min(y[m])), float(np.max(y[m]))


def time_mean(t: np.ndarray, y: np.ndarray) -> float:
    """The time mean of y over the span of t (trapezoid rule), as `riser run` reports its
    window's mean; a single sample: itself."""
    span = float(t[-1] - t[0])
    return float(np.trapezoid(y, t) / span) if span > 0 else float(np.mean(y))


def window_time_mean(t: np.ndarray, y: np.ndarray, start: float, stop: float) -> float:
    """The time mean of y's piecewise-linear interpolant over exactly [start, stop] (clipped to the
    span of t), as `riser run` reports its steady window's mean: where the samples do not fall on the
    window's ends, the ends are interpolated (the samples inside alone would start the window up to a
    step late). No interval inside: the samples' mean there."""
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    a, b = max(start, float(t[0])), min(stop, float(t[-1]))
    if not b > a:
        return float(np.mean(y[in_window(t, start, stop)]))
    inner = (t > a) & (t < b)
    tt = np.concatenate(([a], t[inner], [b]))
    yy = np.concatenate(([np.interp(a, t, y)], y[inner], [np.interp(b, t, y)]))
    return float(np.trapezoid(yy, tt) / (b - a))


def centred_average(x: np.ndarray, n: int) -> np.ndarray:
    """Centred moving average over n + 1 samples (n even); NaN within n/2 of the ends."""
    ker = np.ones(n + 1) / (n + 1)
    y = np.convolve(x, ker, mode="same")
    y[: n // 2] = np.nan
    y[len(y) - n // 2:] = np.nan
    return y


def relative_rms(y: np.ndarray, ref: np.ndarray) -> float:
    """RMS of y - ref relative to the mean of ref."""
    return float(np.sqrt(np.mean((y - ref) ** 2)) / np.mean(ref))
