"""The sweep on a Dask distributed cluster: a LocalCluster of worker processes by
default, an existing scheduler when given its address.

Every case to run is one task (`case.case_task`, one FMU instance per case) on
the workers' copy of the FMU (`case.ShipFMU`); the client takes the results as
they complete (`as_completed`) and appends each to DIR/results.csv, flushed and
synced before the next, so an interrupted client loses no finished case and a
rerun runs only the cases missing. A worker that dies takes no case with it: the
scheduler runs its tasks again elsewhere, and the row is still written once,
when its future completes.
"""

from __future__ import annotations

import csv
import hashlib
import logging
import os
import re
import signal
import sys
import time
import uuid
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TextIO

from distributed import Client, LocalCluster, as_completed

from .case import ShipFMU, case_task
from .progress import Progress
from .results import ResultsFile, case_key
from .spec import Case, Spec, _canonical, check_values_with_fmu, worker_failure


@dataclass
class Summary:
    total: int
    skipped: int
    ran: int = 0
    errors: int = 0
    interrupted: bool = False
    workers: int = 0
    wall_s: float = 0.0


def check_spec_with_fmu(spec: Spec) -> None:
    """The FMU's own range checks on every distinct parameter value (in this process)."""
    import tempfile

    from fmpy import extract

    with tempfile.TemporaryDirectory(prefix="riser-sweep-check-") as d:
        check_values_with_fmu(spec, extract(str(spec.fmu), unzipdir=d))


def case_file_name(case: Case) -> str:
    """DIR/cases/<this>.csv: the swept parameters, readable (hashed when long)."""
    name = "_".join(f"{k}={_canonical(v)}" for k, v in case.params) or "case"
    name = re.sub(r"[^A-Za-z0-9=.+_-]", "-", name)
    if len(name) > 120:
        name = name[:100] + "-" + hashlib.sha1(name.encode()).hexdigest()[:12]
    return name + ".csv"


def _write_timeseries(path: Path, res: Any) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    names = list(res.dtype.names)
    tmp = path.with_suffix(".tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t" if n == "time" else n for n in names])
        for row in res:
            w.writerow([repr(float(row[n])) for n in names])
    os.replace(tmp, path)


def _workers(n: int) -> str:
    return f"{n} worker" + ("" if n == 1 else "s")


@contextmanager
def dask_client(scheduler: str | None, workers: int | None, n_cases: int, log: TextIO) -> Iterator[Client]:
    """A client on `scheduler` (waiting for `workers` to join when given), or on a
    LocalCluster of `workers` single-threaded worker processes (default: one per
    core, no more than the cases)."""
    if scheduler:
        client = Client(scheduler, timeout="30s")
        try:
            if workers:
                if len(client.nthreads()) < workers:
                    print(f"riser-sweep: waiting for {workers} workers to join {scheduler}", file=log, flush=True)
                client.wait_for_workers(workers)
            elif not client.nthreads():
                print(f"riser-sweep: no worker at {scheduler} yet; the cases wait for one", file=log, flush=True)
            yield client
        finally:
            client.close()
    else:
        n = workers or max(1, min(os.cpu_count() or 1, n_cases))
        # the worker processes start with SIGINT ignored (they inherit it): a Ctrl-C on the
        # terminal goes to the whole process group, and only the client is to act on it
        # (write what it has, close the cluster) rather than every worker dying noisily
        handler = signal.signal(signal.SIGINT, signal.SIG_IGN)
        try:
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, silence_logs=logging.ERROR)
        finally:
            signal.signal(signal.SIGINT, handler)
        try:
            client = Client(cluster)
            try:
                yield client
            finally:
                client.close()
        finally:
            cluster.close()


def collect(client: Client, futures: list, items: dict[str, Any], summary: Any, save: Callable[[Any, dict], None],
            failure: Callable[[BaseException], dict], log: TextIO, bar: bool | None) -> None:
    """Each of `futures` as it completes: its item (`items` by the future's key) and result to
    `save`, a worker's or the cluster's exception (not the item's own failure) made a result by
    `failure`; counted in `summary` (ran, errors) and shown on `log`. Ctrl-C cancels the rest
    (`summary.interrupted`)."""
    progress = Progress(summary.total, summary.skipped, stream=log, bar=bar)
    try:
        for fut in as_completed(futures):
            item = items[fut.key]
            try:
                res = fut.result()
            except Exception as e:  # not the item's own failure: the worker or the cluster's
                res = failure(e)
            save(item, res)
            summary.ran += 1
            summary.errors += res["status"] != "ok"
            progress.update(item.label(), res["status"], res.get("wall_s"), res.get("error", ""))
            fut.release()
    except KeyboardInterrupt:
        summary.interrupted = True
        client.cancel([f for f in futures if not f.done()])
    finally:
        progress.close()


def run_sweep(spec: Spec, out_dir: str | Path, scheduler: str | None = None, workers: int | None = None,
              retry_errors: bool = False, dry_run: bool = False, log: TextIO | None = None,
              bar: bool | None = None) -> Summary:
    """Run the cases of `spec` not yet in `out_dir`/results.csv (progress and messages
    on `log`, default stderr). The spec must have been checked (`load_spec`, then
    `check_spec_with_fmu`)."""
    log = log or sys.stderr
    out = Path(out_dir)
    results = ResultsFile(out, spec)
    results.open(retry_errors=retry_errors)
    try:
        todo = [c for c in spec.cases if case_key(c) not in results.done]
        summary = Summary(total=len(spec.cases), skipped=len(spec.cases) - len(todo))
        print(f"riser-sweep: {summary.total} cases: {summary.skipped} done, {len(todo)} to run", file=log, flush=True)
        if results.foreign:
            print(f"riser-sweep: {results.foreign} rows of {results.path} are not cases of this spec (kept)",
                  file=log, flush=True)
        if dry_run or not todo:
            return summary
        t0 = time.perf_counter()
        with dask_client(scheduler, workers, len(todo), log) as client:
            summary.workers = len(client.nthreads())
            where = scheduler or "a local cluster"
            print(f"riser-sweep: {where}, {_workers(summary.workers)}", file=log, flush=True)
            if "dashboard" in client.scheduler_info().get("services", {}):
                print(f"riser-sweep: dashboard {client.dashboard_link}", file=log, flush=True)
            plugin = ShipFMU(spec.fmu.read_bytes())
            client.register_plugin(plugin, name=plugin.name)
            run = uuid.uuid4().hex[:8]
            cases: dict[str, Case] = {}
            futures = []
            for i, case in enumerate(todo):
                key = f"riser-case-{i}-{run}"
                cases[key] = case
                futures.append(client.submit(case_task, spec.job(case), plugin.name, key=key, retries=0))

            def save(case: Case, res: dict[str, Any]) -> None:
                results.append(case, res)
                if res.get("timeseries") is not None:
                    _write_timeseries(out / "cases" / case_file_name(case), res["timeseries"])

            collect(client, futures, cases, summary, save, lambda e: worker_failure(e, reductions={}), log, bar)
        summary.wall_s = time.perf_counter() - t0
        return summary
    finally:
        results.close()
