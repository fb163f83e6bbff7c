"""The references' floor of the accuracy study, examined (docs/accuracy.md, last section).

    riser-tools accuracy-ref [--bin target/fasttest/riser] [--phase run|bias|report|all] [--case C ...]
                             [--steps 0.00625,0.003125] [--max-wall 60]

Run phase: the heave cases' references (`riser-tools accuracy`, riser_tools.studies.accuracy: the same
`command()`, scene, heave, duration and steady window; the reference mesh, 2x the grid's finest, tolerance
1e-10) at shorter steps than the study's 0.0125 s, rows appended to out/accuracy_ref/fine.csv (a rerun reuses
them) and copied to docs/accuracy_references_fine.csv. A step is skipped when 2.5 times the solve wall time of the
case's run at the step before exceeds --max-wall s (the next takes about twice as long; the committed runs:
--max-wall 100, two cases at a time on a 2-core machine).

Bias phase: each case's reference rerun at 0.0125 s with --out; from its top tension series, the window's time
mean (trapezoid) and, for every step of the grid, ladder and references, the mean `riser run` reports (the
arithmetic mean of the samples at k dt in the window, both ends included) less it: the sampling bias, O(dt),
written to docs/accuracy_mean_bias.csv.

Report phase (markdown on stdout): per case the steady window's top tension min / mean / max at 0.025 s (the
study's check_step), 0.0125 s (its reference) and the fine steps, the successive differences over max_ref and
the observed order p = log2(d_coarse / d_fine); then every grid and ladder cell of docs/accuracy_runs.csv
against the study's reference and against the finest new one (the error of the study, eq. 16.1, and its mean
alone; and the finest reference's extremes with the time mean, each run's mean less its bias), the smallest /
median / largest error of the cells at 0.025 s and shorter, and the targets' "cheapest grid cell reaching it"
and cost ratios under the three measures. The write-up: docs/accuracy.md, "The references' floor, examined".

The bias and report phases take runs whose window mean is the samples' average with both ends, as `riser run`
reported it until it reported the time mean (`--runs`: `git show b7668a3:docs/accuracy_runs.csv`, the runs of the
write-up); on runs made since, the bias they subtract is no longer in the runs' means. The run phase's references
are of the binary given (the committed ones: time means).
"""
from __future__ import annotations

import argparse
import csv
import math
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from ..series import in_window, time_mean as trapezoid_mean
from . import accuracy as A

HEAVE_CASES = ["catenary", "catenary_T10", "lazy_wave", "steel_catenary", "lowe_langley_jumper",
               "lazy_wave_T10", "steel_catenary_T10", "lowe_langley_jumper_T10"]
FINE_STEPS = [0.00625, 0.003125]
TOL = 1e-10


def n_ref(case):
    return 2 * A.CASES[case][3][-1]


def run_phase(binary, path, cases, steps, max_wall):
    rows = A.load(path)
    for case in cases:
        prev_wall = None
        for dt in steps:
            if prev_wall is not None and prev_wall * 2.5 > max_wall and not A.have(rows, case, "reference_fine",
                                                                                   n_ref(case), dt, TOL):
                print(case, dt, "skipped: the step before took", prev_wall, "s", flush=True)
                continue
            r = A.one(binary, path, rows, case, "reference_fine", n_ref(case), dt, TOL)
            prev_wall = float(r["wall_s"]) if r["completed"] == "True" else math.inf


def series_of(binary, case, dt=0.0125):
    """The reference mesh's run at dt with --out: t and top tension, and the steady window (2T, 4T; later in
    the study's LATE_WINDOW)."""
    with tempfile.TemporaryDirectory() as d:
        cmd = A.command(binary, case) + ["--set", f"n_elements={n_ref(case)}", "--set", f"time_step={dt}", "--set",
                                         f"newton_tolerance={TOL}", "--out", d]
        subprocess.run(cmd, capture_output=True, text=True, check=True)
        with open(Path(d) / "timeseries.csv", newline="") as f:
            rows = list(csv.DictReader(f))
    t = [float(r["t"]) for r in rows]
    return t, [float(r["top_tension"]) for r in rows], A.heave_window(case)


def time_mean(t, f, w0, w1):
    """The window's time mean (trapezoid rule) of a series, as `riser run` reports it."""
    t, f = np.asarray(t), np.asarray(f)
    m = in_window(t, w0, w1)
    return trapezoid_mean(t[m], f[m])


def sampled_mean(t, f, w0, w1, dt):
    """What `riser run` reports as the window's mean for a run at dt: the arithmetic mean of the samples at
    k dt in [w0, w1] (both ends included), here of the fine series interpolated linearly."""
    k0, k1 = math.ceil(w0 / dt - 1e-6), math.floor(w1 / dt + 1e-6)
    vals = []
    j = 0
    for k in range(k0, k1 + 1):
        x = k * dt
        while j + 1 < len(t) - 1 and t[j + 1] < x - 1e-12:
            j += 1
        a = (x - t[j]) / (t[j + 1] - t[j])
        vals.append(f[j] + a * (f[j + 1] - f[j]))
    return sum(vals) / len(vals), len(vals)


def bias_phase(binary, runs, cases, out):
    """Per case and every step of the grid, ladder and references: the sampled mean's bias against the
    window's time mean, on the reference's own series (0.0125 s)."""
    rows = []
    for case in cases:
        t, f, (w0, w1) = series_of(binary, case)
        m = time_mean(t, f, w0, w1)
        tmax = max(x for x, y in zip(f, t) if w0 - 1e-9 <= y <= w1 + 1e-9)
        dts = {float(r["time_step"]) for r in runs if r["case"] == case and r["time_step"] not in ("", "refused")}
        dts = sorted(dts | set(FINE_STEPS) | {0.025, 0.0125}, reverse=True)
        for dt in dts:
            sm, n = sampled_mean(t, f, w0, w1, dt)
            rows.append({"case": case, "time_step": dt, "samples": n, "time_mean": m, "window_start": f[t.index(min(
                t, key=lambda x: abs(x - w0)))], "window_end": f[t.index(min(t, key=lambda x: abs(x - w1)))],
                "bias": sm - m, "bias_rel": (sm - m) / tmax})
        print(case, "time mean", m, flush=True)
    with open(out, "w", newline="") as fh:
        w = csv.DictWriter(fh, list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def window(r):
    return [float(r[k]) for k in ("tt_min", "tt_mean", "tt_max")]


def err(row, ref, mean_only=False):
    """The study's error (16.1), `accuracy.error`; with `mean_only`, of the window's mean alone."""
    if not mean_only:
        return A.error(row, ref)
    a, b = window(row), window(ref)
    return abs(a[1] - b[1]) / b[2]


def series(runs, fine, case):
    """The case's reference-mesh runs by step: check_step 0.025, reference 0.0125, the fine ones."""
    out = {}
    for r in runs + fine:
        if r["case"] == case and r["completed"] == "True" and r["kind"] in ("check_step", "reference",
                                                                              "reference_fine"):
            if int(r["n_elements"]) == n_ref(case) and float(r["newton_tolerance"]) == TOL:
                out[float(r["time_step"])] = r
    return dict(sorted(out.items(), reverse=True))


def fmt(x):
    return f"{x:.1e}"


def report(runs, fine, cases):
    print("## Convergence of the references in the step (reference mesh, tolerance 1e-10)\n")
    print("Each step's window top tension min / mean / max (kN), then the change to the next shorter step over "
          "max_ref, per quantity (min, mean, max), and the observed order p = log2(d(dt) / d(dt/2)).\n")
    best = {}
    for case in cases:
        s = series(runs, fine, case)
        if not s:
            continue
        dts = list(s)
        best[case] = s[dts[-1]]
        tmax = window(s[0.0125])[2]
        print(f"### {case} ({n_ref(case)} elements)\n")
        print("| dt s | min kN | mean kN | max kN | wall s | d min | d mean | d max | p min | p mean | p max |")
        print("|---|---|---|---|---|---|---|---|---|---|---|")
        prev_d = None
        for i, dt in enumerate(dts):
            w = window(s[dt])
            cells = [f"{dt:g}", *(f"{x / 1e3:.4f}" for x in w), f"{float(s[dt]['wall_s']):.1f}"]
            if i + 1 < len(dts):
                d = [abs(x - y) / tmax for x, y in zip(w, window(s[dts[i + 1]]))]
                cells += [fmt(x) for x in d]
                if prev_d:
                    cells += [f"{math.log2(a / b):.1f}" if a > 0 and b > 0 else "" for a, b in zip(prev_d, d)]
                else:
                    cells += ["", "", ""]
                prev_d = d
            else:
                cells += [""] * 6
            print("| " + " | ".join(cells) + " |")
        print()
    return best


# the cases whose references do not converge below 0.0125 s (a high-frequency oscillation of the sag bend
# grows over the run at 0.00625 s and shorter): their new reference is the study's own
NOT_CONVERGED = ("lazy_wave", "lazy_wave_T10")


def measures(runs, fine, bias, case, best):
    """The three error measures of a case: (name, function of a run row) for the study's reference (16.1), the
    finest converged reference (16.1), and the finest reference's extremes with the window's time mean, every
    run's reported mean less its sampling bias at its step."""
    old = next(r for r in runs if r["case"] == case and r["kind"] == "reference")
    new = old if case in NOT_CONVERGED else best[case]
    b = {float(r["time_step"]): float(r["bias"]) for r in bias if r["case"] == case}
    tm = next(float(r["time_mean"]) for r in bias if r["case"] == case)
    ref_b = window(new)
    ref_b[1] = tm

    def e_b(r):
        w = window(r)
        w[1] -= b[float(r["time_step"])]
        return max(abs(x - y) for x, y in zip(w, ref_b)) / ref_b[2]

    return old, new, [("old", lambda r: err(r, old)), ("new", lambda r: err(r, new)), ("time mean", e_b)]


def floor(runs, fine, bias, best, cases):
    """Per case, the grid and ladder cells at 0.025 s and shorter: the smallest, median and largest error under
    each measure (the references' floor is where these stop falling)."""
    print("## The floor: cells at dt <= 0.025 s (grid and ladder), smallest / median / largest e\n")
    print("| case | cells | against the study's reference | against the finest | finest, window time mean | "
          "mean alone, less its bias, against the time mean |")
    print("|---|---|---|---|---|---|")
    for case in cases:
        if case not in best:
            continue
        old, _, ms = measures(runs, fine, bias, case, best)
        b = {float(r["time_step"]): float(r["bias"]) for r in bias if r["case"] == case}
        tm = next(float(r["time_mean"]) for r in bias if r["case"] == case)
        ms = ms + [("mean alone", lambda r: abs(float(r["tt_mean"]) - b[float(r["time_step"])] - tm)
                    / float(old["tt_max"]))]
        cells = [r for r in runs if r["case"] == case and r["kind"] in ("grid", "ladder") and r["completed"] == "True"
                 and float(r["time_step"]) <= 0.025 + 1e-12]
        out = []
        for _, f in ms:
            e = sorted(f(r) for r in cells)
            out.append(f"{fmt(e[0])} / {fmt(e[len(e) // 2])} / {fmt(e[-1])}")
        print(f"| {case} | {len(cells)} | " + " | ".join(out) + " |")
    print()


def recompute(runs, fine, bias, best, cases):
    print("## The grid and ladder against the finest reference\n")
    print("Each cell: e against the study's reference / against the finest converged one (same measure, 16.1) / "
          "against the finest one's extremes and the window's time mean, each run's mean less its sampling bias.\n")
    for case in cases:
        if case not in best:
            continue
        old, new, ms = measures(runs, fine, bias, case, best)
        print(f"### {case}: finest converged reference dt {new['time_step']} s; the study's reference against it: "
              f"e = {fmt(err(old, new))} (mean alone {fmt(err(old, new, True))})\n")
        grid = [r for r in runs if r["case"] == case and r["kind"] == "grid" and r["completed"] == "True"]
        lad = [r for r in runs if r["case"] == case and r["kind"] == "ladder" and r["completed"] == "True"]
        for name, rows in (("grid", grid), ("ladder", lad)):
            if not rows:
                continue
            steps = sorted({float(r["time_step"]) for r in rows}, reverse=True)
            meshes = sorted({int(r["n_elements"]) for r in rows})
            print(f"{name}:\n")
            print("| elements | " + " | ".join(f"{dt:g} s" for dt in steps) + " |")
            print("|---|" + "---|" * len(steps))
            for n in meshes:
                cells = []
                for dt in steps:
                    r = next((r for r in rows if int(r["n_elements"]) == n and float(r["time_step"]) == dt), None)
                    cells.append(" / ".join(fmt(f(r)) for _, f in ms) if r else "")
                print(f"| {n} | " + " | ".join(cells) + " |")
            print()
        covered = [g for g in grid if float(g["time_step"]) * A.STEPS_PER_PERIOD <= A.shortest_period(case) + 1e-9]
        print("| target | knob's choice | its e (old / new / time mean) | cheapest cell, ratio, ratio covered: old | "
              "new | time mean |")
        print("|---|---|---|---|---|---|")
        acc = sorted((r for r in runs if r["case"] == case and r["kind"] == "accuracy" and r["completed"] == "True"),
                     key=lambda r: -float(r["accuracy"]))
        for r in acc:
            t = float(r["accuracy"])
            cells = [f"{t:g}", f"{r['n_elements']}, {r['time_step']} s", " / ".join(fmt(f(r)) for _, f in ms)]
            for _, f in ms:
                ok = [g for g in grid if f(g) <= t]
                okc = [g for g in covered if f(g) <= t]
                b = min(ok, key=A.work) if ok else None
                bc = min(okc, key=A.work) if okc else None
                cells.append((f"{b['n_elements']}, {b['time_step']} ({fmt(f(b))}), {A.work(r) / A.work(b):.2f}"
                              if b else "none") + (f", {A.work(r) / A.work(bc):.2f}" if bc else ", –"))
            print("| " + " | ".join(cells) + " |")
        print()


def main(argv=None):
    ap = argparse.ArgumentParser(prog="riser-tools accuracy-ref", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/fasttest/riser")
    ap.add_argument("--out", default="out/accuracy_ref")
    ap.add_argument("--docs", default="docs")
    ap.add_argument("--phase", choices=["run", "bias", "report", "all"], default="all")
    ap.add_argument("--case", action="append", help="only these cases (default: the heave cases)")
    ap.add_argument("--steps", default=",".join(f"{s:g}" for s in FINE_STEPS))
    ap.add_argument("--max-wall", type=float, default=60.0)
    ap.add_argument("--runs", help="the study's runs for the bias and report phases (default DOCS/accuracy_runs.csv); "
                    "they assume runs whose window mean is the samples' average, as `riser run` reported it before "
                    "the time mean: `git show b7668a3:docs/accuracy_runs.csv`")
    args = ap.parse_args(argv)
    cases = args.case or HEAVE_CASES
    out, docs = Path(args.out), Path(args.docs)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "fine.csv"
    if args.phase in ("run", "all"):
        run_phase(args.bin, path, cases, [float(s) for s in args.steps.split(",")], args.max_wall)
        shutil.copy(path, docs / "accuracy_references_fine.csv")
    runs = A.load(Path(args.runs) if args.runs else docs / "accuracy_runs.csv")
    if args.phase in ("bias", "all"):
        bias_phase(args.bin, runs, cases, docs / "accuracy_mean_bias.csv")
    if args.phase in ("report", "all"):
        fine = A.load(docs / "accuracy_references_fine.csv")
        bias = A.load(docs / "accuracy_mean_bias.csv")
        best = report(runs, fine, cases)
        floor(runs, fine, bias, best, cases)
        recompute(runs, fine, bias, best, cases)


if __name__ == "__main__":
    main()
