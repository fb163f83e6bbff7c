"""The `riser-sweep` command.

    riser-sweep SPEC.toml --out DIR [--scheduler ADDRESS] [--workers N] [--fmu PATH]
                [--retry-errors] [--dry-run] [--plot] [--no-bar]
    riser-sweep plot DIR [--png FILE]

Exit status: 0 when the sweep ran to the end (cases that failed are rows with
their error), 2 for a spec refused before any case ran, 130 when interrupted
(the finished rows are kept: run the same command again to go on), 1 otherwise
(e.g. no scheduler at ADDRESS).
"""

from __future__ import annotations

import argparse
import sys

from .spec import SpecError, load_spec


def _plot_main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(prog="riser-sweep plot",
                                 description="The top tension's range against each swept parameter, as a PNG.")
    ap.add_argument("dir", help="a sweep's output directory (with results.csv)")
    ap.add_argument("--png", help="where to write the PNG (default DIR/tension_range.png)")
    args = ap.parse_args(argv)
    from .plot import plot

    try:
        png = plot(args.dir, args.png)
    except FileNotFoundError as e:
        print(f"riser-sweep plot: error: {e}", file=sys.stderr)
        return 2
    print(f"riser-sweep: wrote {png}", file=sys.stderr)
    return 0


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == ["plot"]:
        return _plot_main(argv[1:])
    ap = argparse.ArgumentParser(
        prog="riser-sweep",
        description="Run the cases of a sweep spec through fmu/riser.fmu (fmpy) on a Dask cluster; "
                    "DIR/results.csv gets one row per case. `riser-sweep plot DIR` plots it. "
                    "The spec format: python -c 'import riser_sweep.spec as s; print(s.__doc__)'.")
    ap.add_argument("spec", help="the sweep spec (TOML)")
    ap.add_argument("--out", required=True, help="output directory: results.csv, sweep.json, cases/")
    ap.add_argument("--scheduler", help="address of a running Dask scheduler (default: a local cluster)")
    ap.add_argument("--workers", type=int,
                    help="local cluster: its worker processes (default one per core); with --scheduler: "
                         "wait until this many workers have joined")
    ap.add_argument("--fmu", help="the FMU (default: the spec's `fmu`, else fmu/riser.fmu)")
    ap.add_argument("--retry-errors", action="store_true", help="run the cases whose rows are errors again")
    ap.add_argument("--dry-run", action="store_true", help="check the spec, say how many cases are done and to run")
    ap.add_argument("--plot", action="store_true", help="write DIR/tension_range.png at the end")
    ap.add_argument("--no-bar", action="store_true", help="a line per case instead of the progress bar")
    args = ap.parse_args(argv)
    if args.workers is not None and args.workers < 1:
        ap.error("--workers must be >= 1")

    from .sweep import _workers, check_spec_with_fmu, run_sweep

    try:
        spec = load_spec(args.spec, fmu=args.fmu)
        check_spec_with_fmu(spec)
    except SpecError as e:
        print(f"riser-sweep: error: {args.spec}: {e}", file=sys.stderr)
        return 2
    try:
        summary = run_sweep(spec, args.out, scheduler=args.scheduler, workers=args.workers,
                            retry_errors=args.retry_errors, dry_run=args.dry_run,
                            bar=False if args.no_bar else None)
    except SpecError as e:
        print(f"riser-sweep: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("riser-sweep: interrupted; the finished cases are in results.csv, run again to go on",
              file=sys.stderr)
        return 130
    except OSError as e:  # e.g. no scheduler at the address
        print(f"riser-sweep: error: {e}", file=sys.stderr)
        return 1
    if summary.interrupted:
        print(f"riser-sweep: interrupted after {summary.ran} cases; the finished cases are in "
              f"{args.out}/results.csv, run again to go on", file=sys.stderr)
        return 130
    if summary.ran:
        print(f"riser-sweep: {summary.ran} cases in {summary.wall_s:.1f} s on {_workers(summary.workers)}: "
              f"{summary.ran - summary.errors} ok, {summary.errors} errors -> {args.out}/results.csv",
              file=sys.stderr)
    if args.plot and not args.dry_run:
        from .plot import plot

        print(f"riser-sweep: wrote {plot(args.out)}", file=sys.stderr)
    return 0
