"""What the generated pages of docs/ share: a section of a page replaced between
markers, Markdown tables, and the conditions of a timed run (one CPU, one thread)."""

from __future__ import annotations

import os
import time
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


def peer_study_main(argv, doc: str, study, out: str, writes: str, quick: str) -> None:
    """The command line of a peer comparison (`--bin`, `--out`, `--docs`, `--quick`): parse it,
    pin this process to one CPU, run `study(args)`."""
    import argparse
    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/release/riser", help="riser binary")
    ap.add_argument("--out", default=out, help="CSV and work files")
    ap.add_argument("--docs", default="docs", help=f"where {writes} go")
    ap.add_argument("--quick", action="store_true", help=quick)
    args = ap.parse_args(argv)
    one_cpu()
    study(args).run()


def parser(name: str, doc: str, bin: bool = True, fmu: bool = False, out: str | None = None,
           docs: bool = True):
    """The argument parser of `riser-tools NAME`, with the options the studies share:
    --bin (target/release/riser), --fmu (fmu/riser.fmu), --out (default `out`), --docs (docs)."""
    import argparse
    ap = argparse.ArgumentParser(prog=f"riser-tools {name}", description=doc.split("\n\n")[0])
    if fmu:
        ap.add_argument("--fmu", default="fmu/riser.fmu")
    if bin:
        ap.add_argument("--bin", default="target/release/riser")
    if out is not None:
        ap.add_argument("--out", default=out)
    if docs:
        ap.add_argument("--docs", default="docs")
    return ap


class PeerStudy:
    """What a peer comparison keeps: its arguments, its folders (`out`, `out/work`, `docs`) and
    a log line with the seconds since `self.t0` (set when the study starts)."""

    def __init__(self, args) -> None:
        self.args = args
        self.out = Path(args.out)
        self.docs = Path(args.docs)
        self.work = self.out / "work"
        self.t0 = time.perf_counter()

    def log(self, msg: str) -> None:
        print(f"[{time.perf_counter() - self.t0:7.1f} s] {msg}", flush=True)
