#!/usr/bin/env python3
"""riser.so under valgrind's memcheck (`make valgrind`; docs/fuzz.md, 'valgrind').

Three runs of the venv's python with PYTHONMALLOC=malloc (so that memcheck
sees every allocation), --leak-check=full, --track-origins=yes,
--trace-children=no, XML output in out/valgrind/ (about 7 minutes):

  baseline   python imports fmpy and numpy and reads the FMU's
             modelDescription.xml, riser.so never loaded: the leaks of the
             interpreter and its extensions alone;
  simulate   fmpy.simulate_fmu of the catenary (n_elements 10, 5 s, heave
             input), as a co-simulation user's tooling runs it;
  fuzz       a sample of the fuzzer's sequences (riser_tools.fmi_fuzz),
             in this process (no fork), each ending with the reset and normal
             run, every state and instance freed.

Every error valgrind reports is attributed to riser.so when a frame of one
of its stacks (the error's, the block's, the uninitialised value's origin)
is in riser.so, otherwise to the interpreter and its libraries. Prints a summary per run (errors by kind, riser.so / other,
bytes) and the stacks of what is attributed to riser.so plus the top of the
others' definitely-lost stacks; exits 1 if any error is attributed to
riser.so.

    riser-tools valgrind [--fmu fmu/riser.fmu] [--sequences 30] [--seed 1] [--only RUN] [--no-track-origins]
"""

import argparse
import collections
import os
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

ROOT = os.getcwd()
PY = os.path.join(ROOT, ".venv", "bin", "python")
OUT = os.path.join(ROOT, "out", "valgrind")
VALGRIND = "/usr/bin/valgrind"
LEAKS = ("Leak_DefinitelyLost", "Leak_IndirectlyLost", "Leak_PossiblyLost", "Leak_StillReachable")
TRACK = [True]      # --track-origins (the origin stacks count for the attribution)


# --------------------------------------------------------------------------- inside valgrind

def inner(args):
    if args.inner == "baseline":
        import numpy  # noqa: F401
        from fmpy import read_model_description
        md = read_model_description(args.fmu)
        print(f"baseline: {md.modelName}, {len(md.modelVariables)} variables, riser.so not loaded")
        return 0
    if args.inner == "simulate":
        import numpy as np
        from fmpy import simulate_fmu
        t = np.arange(0.0, 5.0 + 1e-9, 0.05)
        sig = np.array([(x, 0.5 * np.sin(2 * np.pi * x / 5.0)) for x in t],
                       dtype=[("time", np.float64), ("heave", np.float64)])
        res = simulate_fmu(args.fmu, stop_time=5.0, output_interval=0.05, input=sig,
                           start_values={"n_elements": 10},
                           output=["top_tension", "total_energy", "shape[10].z"])
        tt = res["top_tension"]
        print(f"simulate: {len(res)} rows, top tension {tt.min():.0f}..{tt.max():.0f} N, "
              f"finite: {bool(np.isfinite(tt).all())}")
        return 0
    # fuzz: in this process
    from riser_tools import fmi_fuzz as F
    from fmpy import extract
    lib = F.Library(extract(args.fmu, unzipdir=tempfile.mkdtemp(prefix="riser_vg_")))
    n_calls, bad = 0, 0
    for seed in range(args.seed, args.seed + args.sequences):
        res = F.run_sequence(lib, seed, tempfile.mkdtemp(prefix="riser_vg_seq_"))
        n_calls += len(res["trace"])
        bad += bool(res["failures"])
        print(f"seed {seed}: {len(res['trace'])} calls, {len(res['failures'])} failures, {res['seconds']:.1f} s",
              flush=True)
    print(f"fuzz: {args.sequences} sequences, {n_calls} calls, {bad} with oracle failures")
    return 0


# --------------------------------------------------------------------------- outside

def run_valgrind(name, inner_args, log, origins=False):
    os.makedirs(OUT, exist_ok=True)
    xml = os.path.join(OUT, f"{name}.xml")
    cmd = [VALGRIND, "--tool=memcheck", "--leak-check=full", "--show-leak-kinds=definite,indirect,possible",
           "--errors-for-leak-kinds=definite,indirect", "--trace-children=no", "--num-callers=40",
           f"--track-origins={'yes' if origins else 'no'}",
           "--xml=yes", f"--xml-file={xml}", PY, "-m", "riser_tools.valgrind", "--inner", name] + inner_args
    env = dict(os.environ, PYTHONMALLOC="malloc")
    t0 = time.monotonic()
    p = subprocess.run(cmd, env=env, capture_output=True, text=True)
    secs = time.monotonic() - t0
    with open(os.path.join(OUT, f"{name}.out"), "w") as f:
        f.write(p.stdout + p.stderr)
    last = [ln for ln in p.stdout.splitlines() if ln.strip()][-1:] or ["(no output)"]
    log(f"  {name}: exit {p.returncode}, {secs:.0f} s: {last[0]}")
    return xml, p.returncode, secs


def frames(err):
    out = []
    for stack in err.iter("stack"):
        for fr in stack.iter("frame"):
            out.append({k: (fr.findtext(k) or "") for k in ("obj", "fn", "file", "line")})
    return out


def parse(xml):
    """The errors of a valgrind XML file: kind, bytes, blocks, riser (bool), frames."""
    tree = ET.parse(xml)
    errs = []
    for e in tree.getroot().iter("error"):
        kind = e.findtext("kind")
        bytes_ = int(e.findtext("xwhat/leakedbytes") or 0)
        blocks = int(e.findtext("xwhat/leakedblocks") or 0)
        fr = frames(e)
        riser = any(f["obj"].endswith("riser.so") for f in fr)
        what = e.findtext("xwhat/text") or e.findtext("what") or ""
        errs.append({"kind": kind, "bytes": bytes_, "blocks": blocks, "riser": riser, "frames": fr, "what": what})
    return errs


def short_stack(fr, n=8):
    parts = []
    for f in fr[:n]:
        obj = os.path.basename(f["obj"]) if f["obj"] else "?"
        fn = (f["fn"] or "???").split("(")[0]
        parts.append(f"{fn} ({obj})")
    return " < ".join(parts)


ALLOCATORS = ("malloc", "calloc", "realloc", "memalign", "posix_memalign", "aligned_alloc", "operator new")


def origin(e):
    """The library that made the allocation (leaks) or the access (others):
    the first frame that is not valgrind's allocator."""
    for f in e["frames"]:
        if "vgpreload" in f["obj"] or (f["fn"] or "").startswith(ALLOCATORS):
            continue
        return os.path.basename(f["obj"]) or "?"
    return "?"


def key(e):
    return (e["kind"],) + tuple((f["fn"] or "?") for f in e["frames"][:12])


def summarize(name, errs, log, baseline_keys=None):
    by = collections.defaultdict(lambda: [0, 0, 0])    # (kind, riser) -> [records, bytes, blocks]
    for e in errs:
        c = by[(e["kind"], e["riser"])]
        c[0] += 1
        c[1] += e["bytes"]
        c[2] += e["blocks"]
    log(f"\n{name}:")
    if not errs:
        log("  no errors, no leaks reported")
    for (kind, riser), (n, b, k) in sorted(by.items()):
        where = "riser.so" if riser else "other"
        extra = f", {b} bytes in {k} blocks" if kind in LEAKS else ""
        log(f"  {kind:22s} {where:8s} {n} records{extra}")
    others = [e for e in errs if not e["riser"] and e["kind"] != "Leak_PossiblyLost"]
    if others:
        where = collections.Counter()
        for e in others:
            where[(e["kind"], origin(e))] += e["bytes"] if e["kind"] in LEAKS else 1
        log("  not riser.so, by the library at the top of the stack: " + "; ".join(
            f"{k} {o}: {v}{' bytes' if k in LEAKS else ''}" for (k, o), v in sorted(where.items())))
    if baseline_keys is not None:
        new = [e for e in others if key(e) not in baseline_keys]
        kinds = collections.Counter(e["kind"] for e in new)
        if not new:
            log("  every record above that is not riser.so's also appears in the baseline (riser.so not loaded)")
        else:
            log(f"  not in the baseline (same kinds, other stacks: where the interpreter's GC or an import ran): "
                + ", ".join(f"{k} {n}" for k, n in sorted(kinds.items())) + "; none has a riser.so frame"
                + (" in any of its stacks, including where an uninitialised value was made" if TRACK[0] else ""))
            for e in new[:2]:
                log(f"    e.g. {e['kind']}: {short_stack(e['frames'], 6)}")
    return by


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--fmu", default=os.path.join(ROOT, "fmu", "riser.fmu"))
    ap.add_argument("--sequences", type=int, default=30)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--inner", choices=["baseline", "simulate", "fuzz"], help=argparse.SUPPRESS)
    ap.add_argument("--no-track-origins", action="store_true",
                    help="faster, but where an uninitialised value was made is not known (nor attributed)")
    ap.add_argument("--only", choices=["baseline", "simulate", "fuzz"], action="append",
                    help="run only these (repeatable)")
    args = ap.parse_args(argv)
    if args.inner:
        return inner(args)
    TRACK[0] = not args.no_track_origins
    lines = []

    def log(s):
        print(s, flush=True)
        lines.append(s)

    fmu = os.path.abspath(args.fmu)
    runs = [("baseline", ["--fmu", fmu]), ("simulate", ["--fmu", fmu]),
            ("fuzz", ["--fmu", fmu, "--sequences", str(args.sequences), "--seed", str(args.seed)])]
    runs = [r for r in runs if not args.only or r[0] in args.only]
    log(f"valgrind {subprocess.run([VALGRIND, '--version'], capture_output=True, text=True).stdout.strip()} "
        f"memcheck on {os.path.relpath(fmu, ROOT)} (PYTHONMALLOC=malloc, --leak-check=full, "
        f"--track-origins={'yes' if TRACK[0] else 'no'}); XML in "
        f"{os.path.relpath(OUT, ROOT)}/")
    results = {}
    for name, inner_args in runs:
        xml, rc, secs = run_valgrind(name, inner_args, log, TRACK[0])
        if not os.path.exists(xml):
            log(f"  {name}: no XML written")
            results[name] = None
            continue
        results[name] = (parse(xml), rc, secs)
    riser_errors = 0
    base = results.get("baseline")
    baseline_keys = {key(e) for e in base[0]} if base else None
    for name, r in results.items():
        if r is None:
            riser_errors += 1
            continue
        errs, rc, secs = r
        summarize(name, errs, log, None if name == "baseline" else baseline_keys)
        mine = [e for e in errs if e["riser"] and e["kind"] != "Leak_PossiblyLost"]
        riser_errors += len(mine) + (rc != 0)
        for e in mine:
            log(f"  riser.so {e['kind']}: {e['what']}\n      {short_stack(e['frames'], 12)}")
        if name == "baseline":
            definite = sorted((e for e in errs if e["kind"] == "Leak_DefinitelyLost"), key=lambda e: -e["bytes"])
            for e in definite[:3]:
                log(f"  e.g. definitely lost, {e['bytes']} bytes in {e['blocks']} blocks: {short_stack(e['frames'])}")
            for e in [e for e in errs if e["kind"] not in LEAKS][:2]:
                log(f"  e.g. {e['kind']}: {e['what']}: {short_stack(e['frames'])}")
        if rc != 0:
            log(f"  {name}: python exited {rc} under valgrind (see {os.path.relpath(OUT, ROOT)}/{name}.out)")
    log("\nresult: " + ("no error and no leak attributed to riser.so" if riser_errors == 0
                        else f"{riser_errors} problems attributed to riser.so (or a run that did not finish)"))
    with open(os.path.join(OUT, "summary.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return 0 if riser_errors == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
