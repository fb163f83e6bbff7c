"""The `riser-sweep` command.

    riser-sweep SPEC.toml --out DIR [--scheduler ADDRESS] [--workers N] [--fmu PATH]
                [--retry-errors] [--dry-run] [--plot] [--no-bar] [--riser-bin PATH]
    riser-sweep plot DIR [--png FILE]

A spec with a [fatigue] table is a fatigue sweep over a scatter diagram
(riser_sweep.fatigue): each sea state a `riser run --fatigue` on a worker, the
riser binary from --riser-bin, else $RISER_BIN, else `riser` on the PATH, else
target/release/riser; DIR gets scatter_results.csv, fatigue_life.csv,
fatigue_summary.json and annual_damage.png. Its exit status is 1 when a sea
state failed (no life is combined without every state).

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
    ap.add_argument("--riser-bin", help="a fatigue sweep ([fatigue]): the riser CLI each sea state runs (default "
                                        "$RISER_BIN, else riser on the PATH, else target/release/riser)")
    args = ap.parse_args(argv)
    if args.workers is not None and args.workers < 1:
        ap.error("--workers must be >= 1")

    from .fatigue import is_fatigue_spec

    if is_fatigue_spec(args.spec):
        return _fatigue_main(args)

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


def _fatigue_main(args: argparse.Namespace) -> int:
    from .fatigue import load_fatigue_spec, run_fatigue_sweep
    from .sweep import _workers

    for flag, given in (("--fmu", args.fmu), ("--retry-errors", args.retry_errors), ("--plot", args.plot)):
        if given:
            print(f"riser-sweep: error: {args.spec}: {flag} is not for a fatigue sweep (it runs the riser CLI; "
                  "failed sea states always run again; annual_damage.png is always written)", file=sys.stderr)
            return 2
    try:
        spec = load_fatigue_spec(args.spec, riser_bin=args.riser_bin)
    except SpecError as e:
        print(f"riser-sweep: error: {args.spec}: {e}", file=sys.stderr)
        return 2
    if args.dry_run:
        print(f"riser-sweep: {len(spec.states)} sea states, probabilities summing to "
              f"{sum(s.probability for s in spec.states)!r}; riser {spec.binary}", file=sys.stderr)
        for w in spec.warnings:
            print(f"riser-sweep: warning: {w}", file=sys.stderr)
        return 0
    try:
        summary = run_fatigue_sweep(spec, args.out, scheduler=args.scheduler, workers=args.workers,
                                    bar=False if args.no_bar else None)
    except KeyboardInterrupt:
        print("riser-sweep: interrupted; the finished sea states are in DIR/cases, run again to go on",
              file=sys.stderr)
        return 130
    except OSError as e:
        print(f"riser-sweep: error: {e}", file=sys.stderr)
        return 1
    s = summary.summary
    print(f"riser-sweep: {summary.ran} sea states in {summary.wall_s:.1f} s on {_workers(summary.workers)}: "
          f"{summary.ran - summary.errors} ok, {summary.errors} errors -> {args.out}/scatter_results.csv",
          file=sys.stderr)
    if summary.interrupted:
        return 130
    if not summary.complete:
        print(f"riser-sweep: {s['states'] - s['ok']} of {s['states']} sea states failed: no annual damage or life "
              "(a life without them would be unconservative); see scatter_results.csv", file=sys.stderr)
        return 1

    def where(w: dict | None) -> str:
        if not w:
            return "n/a"
        lf = w["life_years"]
        return (f"life {lf:.4g} years (annual damage {w['annual_damage']:.4g}) at S = {w['s']:.2f} m, "
                f"fibre {w['fibre']}")

    print(f"riser-sweep: fatigue ({spec.curve}, SCF {spec.scf:g}, DFF {spec.dff:g}) worst: {where(s['worst'])}",
          file=sys.stderr)
    td = s.get("touchdown")
    if td:
        print(f"riser-sweep: touchdown zone (static touchdown S = {td['static_touchdown_s']:.2f} m "
              f"+- {td['zone']:g} m): {where(td)}", file=sys.stderr)
    print(f"riser-sweep: hang-off (the first element): {where(s['hang_off'])}", file=sys.stderr)
    print(f"riser-sweep: wrote {args.out}/fatigue_life.csv, fatigue_summary.json, annual_damage.png",
          file=sys.stderr)
    return 0
