"""DIR/results.csv: one row per case, appended and flushed as each case finishes,
read back on a rerun to skip the finished cases.

A row is identified by its swept parameters, compared in canonical form (floats
by repr, so a float read back is the float written). DIR/sweep.json holds the
rest of the spec's settings (`Spec.fingerprint`): a rerun with other fixed
settings into the same DIR is refused rather than mixed.
"""

from __future__ import annotations

import csv
import fcntl
import json
import os
from pathlib import Path
from typing import Any, TextIO

from .spec import Case, Spec, SpecError, _canonical

CONTRACT = ["top_tension_min", "top_tension_mean", "top_tension_max", "min_tension_min", "energy_balance_relative",
            "wall_s", "status", "error"]


def header(spec: Spec) -> list[str]:
    return spec.columns + CONTRACT + spec.extra_columns


def case_key(case: Case) -> tuple[str, ...]:
    return tuple(_canonical(v) for _, v in case.params)


def _parse(ftype: str, s: str) -> str:
    """A CSV cell as the canonical string of the value of type `ftype`."""
    if ftype == "Real":
        return repr(float(s))
    if ftype == "Integer":
        return str(int(s))
    if ftype == "Boolean":
        return "true" if s.strip().lower() in ("true", "1") else "false"
    return s


def _cell(v: Any) -> Any:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return repr(v)
    return "" if v is None else v


class ResultsFile:
    """results.csv opened for appending, locked against a second riser-sweep on the
    same DIR (the lock goes with the process, also when it is killed)."""

    def __init__(self, out_dir: Path, spec: Spec):
        self.dir = out_dir
        self.path = out_dir / "results.csv"
        self.spec = spec
        self.header = header(spec)
        self.done: dict[tuple[str, ...], str] = {}  # key -> status
        self.foreign = 0  # rows of cases not in this spec's grid
        self._f: TextIO | None = None
        self._w: Any = None

    def open(self, retry_errors: bool = False) -> None:
        self.dir.mkdir(parents=True, exist_ok=True)
        self._f = open(self.path, "a+", newline="")
        try:
            fcntl.flock(self._f.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            self._f.close()
            self._f = None
            raise SpecError(f"{self.path}: another riser-sweep is writing it") from None
        self._f.seek(0)
        text = self._f.read()
        try:
            rows = self._read(text) if text else []
            self._check_settings(bool(rows))
        except SpecError:
            self.close()
            raise
        keep = [r for r in rows if not (retry_errors and r["status"] != "ok")]
        if not text or len(keep) != len(rows) or not text.endswith("\n"):
            self._rewrite(keep)  # a new file; error rows dropped to retry; a last line cut by a kill
        keys = {case_key(c) for c in self.spec.cases}
        for r in keep:
            k = self._key(r)
            if k in keys and k not in self.done:
                self.done[k] = r["status"]
            else:
                self.foreign += 1
        self._w = csv.writer(self._f)

    def _check_settings(self, has_rows: bool) -> None:
        meta = self.dir / "sweep.json"
        fp = self.spec.fingerprint()
        if meta.exists() and has_rows:
            old = json.loads(meta.read_text())
            if old.get("settings") != fp:
                diff = sorted(k for k in set(fp) | set(old.get("settings", {}))
                              if fp.get(k) != old.get("settings", {}).get(k))
                raise SpecError(f"{self.dir}: holds a sweep with other settings ({', '.join(diff)} differ); "
                                "use another --out, or remove its results.csv to start over")
        meta.write_text(json.dumps({"spec": str(self.spec.path), "settings": fp}, indent=1) + "\n")

    def _read(self, text: str) -> list[dict[str, str]]:
        lines = text.splitlines(keepends=True)
        if lines and not lines[-1].endswith("\n"):
            lines = lines[:-1]  # cut short by a kill mid-write: that case runs again
        rows = list(csv.reader(lines))
        if not rows:
            return []
        if rows[0] != self.header:
            raise SpecError(f"{self.path}: its columns ({', '.join(rows[0])}) are not this spec's "
                            f"({', '.join(self.header)}); use another --out")
        return [dict(zip(self.header, r)) for r in rows[1:] if len(r) == len(self.header)]

    def _key(self, row: dict[str, str]) -> tuple[str, ...]:
        try:
            return tuple(_parse(self.spec.param_type(c), row[c]) for c in self.spec.columns)
        except ValueError:
            return ("?",)

    def _rewrite(self, rows: list[dict[str, str]]) -> None:
        assert self._f is not None
        tmp = self.path.with_suffix(".csv.tmp")
        with open(tmp, "w", newline="") as g:
            w = csv.writer(g)
            w.writerow(self.header)
            for r in rows:
                w.writerow([r[c] for c in self.header])
            g.flush()
            os.fsync(g.fileno())
        # keep our locked handle: copy the content into it rather than replacing the inode
        self._f.seek(0)
        self._f.truncate()
        self._f.write(tmp.read_text())
        self._f.flush()
        os.fsync(self._f.fileno())
        tmp.unlink()

    def append(self, case: Case, result: dict[str, Any]) -> None:
        """One finished case: written, flushed and synced before the next."""
        assert self._f is not None and self._w is not None
        red = result.get("reductions", {})
        row = [_cell(v) for _, v in case.params]
        row += [_cell(red.get(c)) for c in CONTRACT[:5]]
        row += [_cell(result.get("wall_s")), result["status"], result.get("error", "")]
        row += [_cell(red.get(c)) for c in self.spec.extra_columns]
        self._w.writerow(row)
        self._f.flush()
        os.fsync(self._f.fileno())
        self.done[case_key(case)] = result["status"]

    def close(self) -> None:
        if self._f is not None:
            self._f.close()
            self._f = None


def read_results(out_dir: Path) -> tuple[list[str], list[dict[str, str]]]:
    """results.csv as (parameter columns, rows)."""
    path = Path(out_dir) / "results.csv"
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
        f.seek(0)
        cols = next(csv.reader(f))
    params = cols[: cols.index(CONTRACT[0])]
    return params, rows
