"""Cases done / total with an ETA: a redrawn bar on a terminal, a line per case
otherwise (logs, CI). No dependency: a bar is twenty lines."""

from __future__ import annotations

import sys
import time
from typing import TextIO


def _hms(s: float) -> str:
    s = int(round(s))
    return f"{s // 3600}h{s % 3600 // 60:02d}m" if s >= 3600 else (f"{s // 60}m{s % 60:02d}s" if s >= 60 else f"{s}s")


class Progress:
    def __init__(self, total: int, done_before: int = 0, stream: TextIO | None = None, bar: bool | None = None):
        self.total = total
        self.done = done_before
        self.ran = 0
        self.errors = 0
        self.stream = stream or sys.stderr
        self.bar = self.stream.isatty() if bar is None else bar
        self.t0 = time.perf_counter()
        if self.bar:
            self._draw()

    def update(self, label: str, status: str, wall_s: float | None, error: str = "") -> None:
        self.done += 1
        self.ran += 1
        self.errors += status != "ok"
        if self.bar:
            self._draw()
        else:
            wall = f"{wall_s:.2f} s" if isinstance(wall_s, float) else "-"
            what = status if status == "ok" else f"{status}: {error[:200]}"
            print(f"riser-sweep: [{self.done}/{self.total}] {label}: {what} ({wall}){self._eta()}", file=self.stream,
                  flush=True)

    def _eta(self) -> str:
        if self.ran == 0 or self.done >= self.total:
            return ""
        elapsed = time.perf_counter() - self.t0
        return f", ETA {_hms(elapsed / self.ran * (self.total - self.done))}"

    def _draw(self) -> None:
        width = 30
        filled = int(width * self.done / max(self.total, 1))
        errs = f", {self.errors} errors" if self.errors else ""
        elapsed = _hms(time.perf_counter() - self.t0)
        self.stream.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} cases{errs}, "
                          f"{elapsed}{self._eta()}   ")
        self.stream.flush()

    def close(self) -> None:
        if self.bar:
            self.stream.write("\n")
            self.stream.flush()
