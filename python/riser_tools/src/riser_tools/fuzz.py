#!/usr/bin/env python3
"""The long fuzz run of fmu/riser.fmu's FMI 2.0 C ABI (`make fuzz`;
docs/fuzz.md): thousands of seeded random call sequences, each in a forked
child (the generator and the oracle: riser_tools.fmi_fuzz; the few
hundred of `make test`: tests/python/test_fuzz.py).

    riser-tools fuzz                      # 5000 sequences from seed 1, 2 at a time
    riser-tools fuzz --count 500 --seed 7
    riser-tools fuzz --replay SEED        # one sequence in this process, every call and status
    riser-tools fuzz --minimize SEED      # shrink a failing sequence to the calls that matter

Prints a summary table (sequences, FMI calls, crashes, hangs,
OK-with-non-finite, reset failures, outputs unreadable after an OK state
change, fmi2Fatal, seconds; the oracle: riser_tools.fmi_fuzz), the
distinct failures with their seeds, and what the sequences reached (calls by
function and status). Exits 1 if any sequence failed.
"""

import argparse
import collections
import json
import math
import os
import signal
import sys
import tempfile
import time

from . import fmi_fuzz as F

ROOT = os.getcwd()


def load(fmu):
    from fmpy import extract
    unzipdir = extract(fmu, unzipdir=tempfile.mkdtemp(prefix="riser_fmu_"))
    return F.Library(unzipdir)


def progress_printer(total, every):
    """Prints the first failure of each signature as it comes, and a count every `every` sequences."""
    t0 = time.monotonic()
    bad = [0]
    seen = set()

    def progress(o, done):
        if o.kind != "ok":
            bad[0] += 1
            sigs = {f["signature"] for f in o.failures} if o.kind == "fail" else {o.kind}
            if sigs - seen:
                seen.update(sigs)
                print(f"  FAIL {o.summary()[:300]}", flush=True)
        if done % every == 0 or done == total:
            print(f"  {done}/{total} sequences, {bad[0]} failing, {time.monotonic() - t0:.0f} s", flush=True)
    return progress


def table(counts, calls, seconds):
    head = ["sequences", "FMI calls", "crashes", "hangs", "OK-with-non-finite", "reset failures",
            "unreadable after OK", "fmi2Fatal", "other", "harness errors", "seconds"]
    row = [counts["sequences"], calls, counts["crashes"], counts["hangs"], counts["ok_nonfinite"],
           counts["recovery"], counts["unreadable"], counts["fatal"], counts["other"], counts["harness"],
           f"{seconds:.0f}"]
    return "\n".join(["| " + " | ".join(head) + " |", "|" + "---|" * len(head),
                      "| " + " | ".join(str(x) for x in row) + " |"])


def signatures(outcomes):
    """Distinct failures: signature -> seeds."""
    groups = collections.OrderedDict()
    for o in sorted(outcomes, key=lambda o: o.seed):
        if o.kind == "ok":
            continue
        keys = {f["signature"] for f in o.failures} if o.kind == "fail" else {o.kind}
        for k in sorted(keys):
            groups.setdefault(k, []).append(o)
    return groups


def coverage(outcomes):
    st = collections.Counter()
    for o in outcomes:
        st.update(o.stats)
    by_op = collections.OrderedDict()
    for key in sorted(st):
        op, status = key.rsplit(":", 1)
        by_op.setdefault(op, {})[status] = st[key]
    statuses = ["OK", "Warning", "Discard", "Error", "Fatal", "skipped"]
    lines = ["| call | " + " | ".join(statuses) + " |", "|---|" + "---:|" * len(statuses)]
    for op, d in by_op.items():
        lines.append(f"| {op} | " + " | ".join(str(d.get(s, 0)) for s in statuses) + " |")
    return "\n".join(lines), sum(v for k, v in st.items() if not k.endswith(":skipped"))


def run(args):
    lib = load(args.fmu)
    print(f"fuzzing {args.fmu}: {args.count} sequences from seed {args.seed}, {args.jobs} at a time, "
          f"{args.timeout:.0f} s limit each", flush=True)
    t0 = time.monotonic()
    outcomes = F.run_many(lib, F.seeds(args.seed, args.count), jobs=args.jobs, timeout=args.timeout,
                          progress=progress_printer(args.count, max(args.count // 20, 1)))
    seconds = time.monotonic() - t0
    counts = F.tally(outcomes)
    cov, calls = coverage(outcomes)
    print()
    print(table(counts, calls, seconds))
    groups = signatures(outcomes)
    if groups:
        print("\nDistinct failures (signature: sequences, first seeds):\n")
        for sig, os_ in groups.items():
            first = os_[0]
            example = next((f for f in first.failures if f.get("signature") == sig), None) if first.failures else None
            print(f"- {sig}: {len(os_)} sequences, seeds {', '.join(str(o.seed) for o in os_[:6])}"
                  + ("..." if len(os_) > 6 else ""))
            if example:
                print(f"    e.g. seed {first.seed}: {example['call'][:200]} -> {example['status']}: "
                      f"{example['detail'][:200]}")
            else:
                print(f"    e.g. seed {first.seed}: {first.detail[:300]}")
        print(f"\nreplay one: {sys.argv[0]} --replay SEED; shrink it: {sys.argv[0]} --minimize SEED")
    longest = max(outcomes, key=lambda o: o.longest_step)
    busiest = max(outcomes, key=lambda o: o.work_ratio)
    print(f"\nThe bounded step: the longest fmi2DoStep took {longest.longest_step:.2f} s (seed {longest.seed}); "
          f"the largest Newton iterations / bound of a step was {busiest.work_ratio:.3f} (seed {busiest.seed}); "
          f"steps beyond their bound: {sum(any(f['kind'] == 'unbounded' for f in o.failures) for o in outcomes)}")
    print("\nWhat the sequences reached (calls by function and status):\n")
    print(cov)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"counts": counts, "calls": calls, "seconds": seconds, "base_seed": args.seed,
                       "bad": [o.__dict__ for o in outcomes if o.kind != "ok"]}, f, indent=1)
    return 1 if any(o.kind != "ok" for o in outcomes) else 0


def replay(args, calls=None, recover=True):
    lib = load(args.fmu)
    workdir = tempfile.mkdtemp(prefix="riser_replay_")
    what = f"seed {args.replay}" if calls is None else f"{len(calls)} calls"
    print(f"replaying {what} (files in {workdir}); '-- recovery' marks the reset and normal run after it",
          flush=True)
    res = F.run_sequence(lib, args.replay if calls is None else 0, workdir, verbose=True, calls=calls,
                         recover=recover)
    print(f"\n{len(res['trace'])} calls, {res['seconds']:.2f} s, {len(res['failures'])} failures")
    for f in res["failures"]:
        print(f"  {f['signature']}: {f['call']} -> {f['status']}: {f['detail']}")
    return 1 if res["failures"] else 0


def ddmin(items, test):
    """Zeller's delta debugging on a list: a 1-minimal sublist for which test() holds."""
    n = 2
    while len(items) >= 2:
        chunk = math.ceil(len(items) / n)
        parts = [items[i:i + chunk] for i in range(0, len(items), chunk)]
        for i in range(len(parts)):
            rest = [c for j, p in enumerate(parts) if j != i for c in p]
            if test(rest):
                items, n = rest, max(n - 1, 2)
                break
        else:
            if n >= len(items):
                break
            n = min(len(items), 2 * n)
    return items


def minimize(args):
    lib = load(args.fmu)
    seed = args.minimize
    first = F.run_many(lib, [(seed, None)], jobs=1, timeout=args.timeout, keep_calls=True)[0]
    if first.kind == "ok":
        print(f"seed {seed} does not fail")
        return 0
    print(first.summary()[:300], flush=True)
    if first.kind == "fail":
        target = first.failures[0]["signature"]
        calls = first.calls
    else:
        target = first.kind
        # a crash or a hang leaves no result: record the calls without running them
        calls = record_calls(lib, seed)
    recover = target.startswith("recovery") or first.kind in ("crash", "hang")
    tries = [0]

    def test(sub):
        tries[0] += 1
        o = F.run_many(lib, [(seed, sub, recover)], jobs=1, timeout=args.timeout)[0]
        if first.kind == "fail":
            return o.kind == "fail" and any(f["signature"] == target for f in o.failures)
        return o.kind == first.kind

    print(f"shrinking {len(calls)} calls (target: {target}) ...", flush=True)
    small = ddmin(calls, test)
    print(f"{len(small)} calls after {tries[0]} runs:\n", flush=True)
    args.replay = seed
    replay(args, calls=[F.Call.from_json(c) for c in small], recover=recover)
    return 1


def record_calls(lib, seed):
    """The calls of sequence `seed`, generated in a child that runs them up to
    the crash or hang: rerun with the trace kept in a file of calls."""
    # the generator follows the statuses, so the calls must be run to be made;
    # run them in a child that writes each call before making it
    path = tempfile.mktemp(prefix="riser_calls_")
    pid = os.fork()
    if pid == 0:
        try:
            fd = os.open(os.devnull, os.O_WRONLY)
            os.dup2(fd, 1)
            os.dup2(fd, 2)
            import random
            ex = F.Executor(lib, tempfile.mkdtemp(), verbose=False)
            gen = F.Generator(lib, random.Random(seed), ex)
            with open(path, "w") as f:
                for _ in range(F.sequence_length(seed)):
                    c = gen.next()
                    f.write(json.dumps(c.to_json()) + "\n")
                    f.flush()
                    ex.run(c)
        finally:
            os._exit(0)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        done, _ = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        time.sleep(0.2)
    else:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
    with open(path) as f:
        calls = [json.loads(line) for line in f if line.strip()]
    os.unlink(path)
    return calls


def main(argv=None):
    # SIGTERM: the children are killed on the way out (run_many's finally)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fmu", default=os.path.join(ROOT, "fmu", "riser.fmu"))
    ap.add_argument("--seed", type=int, default=1, help="first seed (default 1)")
    ap.add_argument("--count", type=int, default=5000, help="sequences (default 5000)")
    ap.add_argument("--jobs", type=int, default=2, help="children at a time (default 2)")
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds per sequence before it is a hang")
    ap.add_argument("--json", help="write the counts and every failing outcome here")
    ap.add_argument("--replay", type=int, metavar="SEED", help="run one sequence here, printing every call")
    ap.add_argument("--minimize", type=int, metavar="SEED", help="shrink a failing sequence and print it")
    args = ap.parse_args(argv)
    if args.replay is not None:
        return replay(args)
    if args.minimize is not None:
        return minimize(args)
    return run(args)


if __name__ == "__main__":
    sys.exit(main())
