"""What the generated pages of docs/ share: a section of a page replaced between
markers, Markdown tables, and the conditions of a timed run (one CPU, one thread)."""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence
from pathlib import Path

THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "RAYON_NUM_THREADS")


def single_threaded() -> None:
    """One thread in every numerical library (set before numpy is loaded to take effect)."""
    for var in THREAD_VARIABLES:
        os.environ[var] = "1"


def one_cpu() -> None:
    """Run this process and its children on a single CPU (the highest one allowed)."""
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {max(os.sched_getaffinity(0))})


def markers(name: str, writer: str) -> tuple[str, str]:
    """The begin and end markers of a generated section: `<!-- NAME:begin (WRITER writes this section) -->`."""
    return f"<!-- {name}:begin ({writer} writes this section) -->", f"<!-- {name}:end -->"


def replace_section(path: str | Path, begin: str, end: str, lines: Iterable[str]) -> None:
    """Write `lines` between the markers `begin` and `end` of the page at `path` (the markers
    kept), or append them with the markers when the page has none yet."""
    path = Path(path)
    text = path.read_text()
    block = begin + "\n" + "\n".join(lines) + "\n" + end
    if begin in text:
        a = text.index(begin)
        b = text.index(end) + len(end)
        text = text[:a] + block + text[b:]
    else:
        text = text.rstrip() + "\n\n" + block + "\n"
    path.write_text(text)


def table(head: Sequence[str], rows: Iterable[Sequence[object]]) -> list[str]:
    """A Markdown table: the header, the rule, one line per row (cells as str)."""
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return out
