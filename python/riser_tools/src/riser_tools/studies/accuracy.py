"""The `accuracy` knob (issue 28): the calibration grid of its error model and the check of what
it chooses. `riser-tools accuracy [--bin target/fasttest/riser] [--phase grid|verify|all]`.

The error (docs/theory.md, "The accuracy knob"): `riser run SCENE --heave A,T --duration 4T
--json` (the default ramp of one period and the default steady window, from 2T to 4T; the cases of
LATE_WINDOW run 2T longer per period of delay, with `--window` two periods long after it); its
`steady.top_tension` [min, mean, max] against the same of a converged reference run:

    e = max(|min - min_ref|, |mean - mean_ref|, |max - max_ref|) / max_ref.

In waves (WAVE_CASES, docs/theory.md section 16.4): `riser run SCENE [--heave A,T] --set wave_... --duration D
--window T0,T1 --json`, the same error over the case's own window (a regular wave: 20 to 40 s; an irregular
sea: 20 to 220 s, 20 Tp, so that the window's extremes are those of the sea's largest wave groups).

Ladder phase (LADDER): the heave cases' chosen and coarsest meshes at every step of the knob's own
ladder from 0.2 to 0.01 s, against the model's prediction for the same numerics: the points between the
grid's four steps that the choice may land on (docs/theory.md §16.3).

Grid phase: per calibration case, the reference (the finest mesh and step below, tolerance
1e-10), two checks of it (half the elements, twice the step) and the grid elements x time step
at tolerance 1e-8; rows appended to out/accuracy/grid.csv as they come (a rerun reuses them; the verify phase's
runs are always made afresh, replacing the stored ones),
copied to docs/accuracy_runs.csv. Verify phase: the same runs with only `--set accuracy=...`
(1e-2, 1e-3, 1e-4; the heave cases without a sea also INTERMEDIATE_TARGETS, 5e-3 to 1.2e-4, between
them) against the same reference: what riser chose, its error and its wall time
against the cheapest grid cell that reaches the target; the same csv and
docs/accuracy.md. The ladder, verify and doc phases alone on a fresh checkout (no
out/accuracy/grid.csv) start from the committed runs, docs/accuracy_runs.csv.
"""

from __future__ import annotations

import argparse
import csv
import json
import shutil
import subprocess
from pathlib import Path

# name -> (scene argument, heave amplitude m, heave period s, elements of the grid)
CASES = {
    "catenary": ("catenary", 2.5, 20.0, [10, 20, 40, 80]),
    "lazy_wave": ("lazy_wave", 2.5, 30.0, [10, 20, 40, 80]),
    "steel_catenary": ("steel_catenary", 2.5, 15.0, [20, 40, 80, 160]),
    "lowe_langley_jumper": ("docs/cases/lowe_langley_jumper.toml", 10.0, 27.0, [20, 40, 80, 160]),
    # the model's shortest period (MIN_PERIOD)
    "catenary_T10": ("catenary", 2.5, 10.0, [10, 20, 40, 80]),
    # the design motion (2.5 m at 10 s, what `riser statics` and the FMU choose for) on the other lines: the
    # mesh's error of the motion (docs/theory.md 16.2, C_d) where the line's slack sag bend (the lazy wave) or
    # low tension (the jumper) shortens the response's wavelength
    "lazy_wave_T10": ("lazy_wave", 2.5, 10.0, [10, 20, 40, 80]),
    "steel_catenary_T10": ("steel_catenary", 2.5, 10.0, [20, 40, 80, 160]),
    "lowe_langley_jumper_T10": ("docs/cases/lowe_langley_jumper.toml", 2.5, 10.0, [20, 40, 80, 160]),
    # the model's largest amplitude (MAX_AMPLITUDE) on the catenary: the step term's amplitude, separated
    # from the line (the jumper is the only other case with 10 m)
    "catenary_A10": ("catenary", 10.0, 20.0, [10, 20, 40, 80]),
}
# the scenes in waves (issue 28): name -> (scene, heave amplitude m (0: none), period s of the window's
# start and of the heave, elements, the sea's --set, the run's duration s, its steady window (t0, t1) s)
AIRY_CAT = ["wave_kind=airy", "wave_height=6", "wave_period=10"]
AIRY_JUMPER = ["wave_kind=airy", "wave_height=10", "wave_period=10"]
JONSWAP = ["wave_kind=jonswap", "wave_hs=6", "wave_tp=10", "wave_components=50", "wave_seed=1"]
JUMPER = "docs/cases/lowe_langley_jumper.toml"
# a regular wave: the sea's ramp (one period, 10 s) and one period more, then 2 periods (as the heave's 2T
# to 4T); an irregular sea: the ramp (Tp) and one Tp more, then 200 s = 20 Tp, about 25 zero up-crossings:
# the window's extremes are those of the sea's largest wave groups, not of one wave (WINDOW_IRREGULAR)
WINDOW_IRREGULAR = (20.0, 220.0)
WAVE_CASES = {
    "catenary_airy": ("catenary", 0.0, 10.0, [10, 20, 40, 80], AIRY_CAT, 40.0, (20.0, 40.0)),
    "catenary_airy_heave": ("catenary", 2.5, 10.0, [10, 20, 40, 80], AIRY_CAT, 40.0, (20.0, 40.0)),
    "catenary_jonswap": ("catenary", 0.0, 10.0, [10, 20, 40, 80], JONSWAP, 220.0, WINDOW_IRREGULAR),
    "catenary_jonswap_heave": ("catenary", 2.5, 10.0, [10, 20, 40, 80], JONSWAP, 220.0, WINDOW_IRREGULAR),
    "jumper_airy": (JUMPER, 0.0, 10.0, [10, 20, 40, 80, 160], AIRY_JUMPER, 40.0, (20.0, 40.0)),
    "jumper_airy_heave": (JUMPER, 2.5, 10.0, [10, 20, 40, 80, 160], AIRY_JUMPER, 40.0, (20.0, 40.0)),
    "jumper_jonswap": (JUMPER, 0.0, 10.0, [10, 20, 40, 80, 160], JONSWAP, 220.0, WINDOW_IRREGULAR),
    # still water, no motion (docs/theory.md §16.7; with the current in full from t = 0, the floor E_s F_c of
    # §16.2): what the window from 20 to 40 s holds of
    # the current's start, which `riser run` without a motion chooses for
    "catenary_still": ("catenary", 0.0, 10.0, [10, 20, 40, 80], [], 40.0, (20.0, 40.0)),
    "lazy_wave_still": ("lazy_wave", 0.0, 10.0, [10, 20, 40, 80], [], 40.0, (20.0, 40.0)),
}
# the cases without a motion or a sea: no period to take steps of
STILL_CASES = ("catenary_still", "lazy_wave_still")
CASES.update({k: v[:4] for k, v in WAVE_CASES.items()})
STEPS = [0.2, 0.1, 0.05, 0.025]
# The ladder (docs/theory.md §16.3, "Between the grid's steps"): the knob chooses its step from
# src/sim/accuracy.rs STEP_LADDER, not only from the grid's four; the heave cases' meshes it chooses
# (and the grid's coarsest) at every ladder step from 0.2 to 0.0125 s (the ladder's shortest, the
# references' step) and at 0.01 s, the step below it that the knob no longer takes, with at least 75
# steps a period, against the model's own prediction for those numerics (tolerance 1e-9, the knob's at 1e-4
# until 2026-11-27, 1e-8 since)
LADDER_STEPS = [0.2, 0.15, 0.1, 0.075, 0.05, 0.04, 0.03, 0.025, 0.02, 0.015, 0.0125, 0.01]
LADDER = {"catenary": [10, 20], "catenary_T10": [10, 20], "lazy_wave": [20, 40], "steel_catenary": [30, 50, 100, 160],
          "lowe_langley_jumper": [10, 16, 20], "lazy_wave_T10": [20, 40], "lowe_langley_jumper_T10": [10, 20],
          "steel_catenary_T10": [30, 50, 80, 160]}
LADDER_TOL = 1e-9
REF_STEP = 0.0125
TARGETS = [1e-2, 1e-3, 1e-4]
# targets between the three (docs/theory.md §16.3, "Between the targets"): the knob must meet every target it
# accepts, not only the three; each heave case (without a sea) is run at each of these as well
INTERMEDIATE_TARGETS = [5e-3, 2e-3, 5e-4, 3e-4, 2e-4, 1.5e-4, 1.2e-4]
EXTRA_TARGETS = {c: INTERMEDIATE_TARGETS for c in
                 ("catenary", "lazy_wave", "steel_catenary", "lowe_langley_jumper", "catenary_T10", "lazy_wave_T10",
                  "steel_catenary_T10", "lowe_langley_jumper_T10")}
FLOOR_HEADING = "## The references' floor, examined"
FIELDS = ["case", "kind", "n_elements", "time_step", "newton_tolerance", "accuracy", "tt_min", "tt_mean",
          "tt_max", "wall_s", "newton_per_step", "completed"]


# the heave cases whose steady window starts later than the default 2T (two periods long, as every heave
# case's): name -> the periods before it. The jumper at 10 s rings at its 3.2 Hz axial mode after the ramp, and
# still by 1.6e-4 of its top tension in the default window (20 to 40 s) at any numerics: 160 elements at
# 0.00625 s give min / max 27531.6 / 66305.0 N there, 27542.0 / 66298.1 N from 80 to 100 s, and 27541.9 /
# 66298.3 N from 40 to 60 s (3e-6 of the steady ones). What the knob targets is the steady response (docs/
# theory.md §16.10, "The jumper at 10 s"); the run warns when its window is not steady at the target.
LATE_WINDOW = {"lowe_langley_jumper_T10": 4}


def heave_window(case):
    """A heave case's steady window (t0, t1), s: two periods after LATE_WINDOW's periods (2 by default)."""
    period = CASES[case][2]
    start = LATE_WINDOW.get(case, 2) * period
    return start, start + 2 * period


def command(binary, case):
    """`riser run` of a case without its numerics: the heave (if any), the sea (if any), the duration
    and, in waves or in LATE_WINDOW, the steady window."""
    scene, amp, period, _ = CASES[case]
    if case not in WAVE_CASES:
        t0, t1 = heave_window(case)
        cmd = [binary, "run", scene, "--heave", f"{amp},{period}", "--duration", f"{t1:g}", "--json"]
        return cmd + (["--window", f"{t0:g},{t1:g}"] if case in LATE_WINDOW else [])
    *_, sea, duration, (t0, t1) = WAVE_CASES[case]
    cmd = [binary, "run", scene, "--duration", f"{duration:g}", "--window", f"{t0:g},{t1:g}", "--json"]
    if amp > 0:
        cmd += ["--heave", f"{amp},{period}"]
    for s in sea:
        cmd += ["--set", s]
    return cmd


# the fewest steps a period the knob takes (src/sim/accuracy.rs MIN_STEPS_PER_PERIOD): the grid cells it
# covers, for the second cost ratio
STEPS_PER_PERIOD = 75.0
# the grid's Newton tolerance
GRID_TOL = 1e-8


def shortest_period(case):
    """The shortest period of a case's motions: its heave's and, in waves, its sea's (10 s here)."""
    if case in STILL_CASES:
        return float("inf")
    return min(CASES[case][2], 10.0) if case in WAVE_CASES else CASES[case][2]


def duration_of(case):
    return WAVE_CASES[case][5] if case in WAVE_CASES else heave_window(case)[1]


def run(binary, case, sets):
    cmd = command(binary, case)
    for k, v in sets.items():
        cmd += ["--set", f"{k}={v}"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    line = next((ln for ln in p.stdout.splitlines() if ln.startswith("{")), None)
    if line is None:
        return {"completed": False, "stderr": p.stderr.strip()}
    d = json.loads(line)
    tt = d["steady"]["top_tension"]
    return {"completed": d["completed"] and p.returncode == 0, "tt": tt, "wall": d["solve_wall_time"],
            "iters": d["iterations_per_step"], "n": d["n_elements"], "dt": d["time_step"],
            "tol": d.get("newton_tolerance"), "stderr": p.stderr.strip()}


def error(row, ref):
    a = [float(row[k]) for k in ("tt_min", "tt_mean", "tt_max")]
    b = [float(ref[k]) for k in ("tt_min", "tt_mean", "tt_max")]
    return max(abs(x - y) for x, y in zip(a, b)) / b[2]


def work(row):
    """The cost of a run as the work of its Newton iterations: elements x steps x iterations per step
    (deterministic, unlike the wall time on a shared machine)."""
    return int(row["n_elements"]) * round(duration_of(row["case"]) / float(row["time_step"])) * float(
        row["newton_per_step"])


def load(path):
    if not path.exists():
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def append(path, row):
    new = not path.exists()
    with open(path, "a", newline="") as f:
        w = csv.DictWriter(f, FIELDS)
        if new:
            w.writeheader()
        w.writerow(row)


def have(rows, case, kind, n, dt, tol, acc=""):
    for r in rows:
        if (r["case"], r["kind"], r["n_elements"], r["time_step"], r["newton_tolerance"], r["accuracy"]) == (
                case, kind, str(n), str(dt), str(tol), str(acc)):
            return r
    return None


def one(binary, path, rows, case, kind, n, dt, tol, acc=""):
    r = have(rows, case, kind, n, dt, tol, acc) if acc == "" else None
    if r is not None:
        return r
    sets = {"accuracy": acc} if acc != "" else {"n_elements": n, "time_step": dt, "newton_tolerance": tol}
    out = run(binary, case, sets)
    if acc != "" and out["completed"]:
        n, dt, tol = out["n"], out["dt"], out["tol"]
    row = {"case": case, "kind": kind, "n_elements": n, "time_step": dt, "newton_tolerance": tol, "accuracy": acc,
           "completed": out["completed"]}
    if out["completed"]:
        row.update(tt_min=out["tt"][0], tt_mean=out["tt"][1], tt_max=out["tt"][2], wall_s=out["wall"],
                   newton_per_step=out["iters"])
    else:
        row.update(tt_min="", tt_mean="", tt_max="", wall_s="", newton_per_step="")
        print(case, kind, n, dt, tol, acc, "failed:", out["stderr"][-300:], flush=True)
    if acc != "":
        row["n_elements"], row["time_step"], row["newton_tolerance"] = (
            (n, dt, tol) if out["completed"] else ("refused", "", ""))
        row["kind"] = kind
    append(path, row)
    rows.append({k: str(v) for k, v in row.items()})
    print(case, kind, n, dt, tol, acc, row.get("tt_max"), row.get("wall_s"), flush=True)
    return rows[-1]


def reference(binary, path, rows, case):
    n_ref = 2 * CASES[case][3][-1]
    return one(binary, path, rows, case, "reference", n_ref, REF_STEP, 1e-10)


def grid(binary, path, rows):
    for case, (_, _, _, elements) in CASES.items():
        ref = reference(binary, path, rows, case)
        n_ref = int(ref["n_elements"])
        one(binary, path, rows, case, "check_mesh", n_ref // 2, REF_STEP, 1e-10)
        one(binary, path, rows, case, "check_step", n_ref, 2 * REF_STEP, 1e-10)
        for n in elements:
            for dt in STEPS:
                one(binary, path, rows, case, "grid", n, dt, GRID_TOL)


def ladder(binary, path, rows):
    for case, meshes in LADDER.items():
        if case not in CASES:
            continue
        for n in meshes:
            for dt in LADDER_STEPS:
                if dt * STEPS_PER_PERIOD <= shortest_period(case) * (1 + 1e-9):
                    one(binary, path, rows, case, "ladder", n, dt, LADDER_TOL)


def verify(binary, path, rows):
    """The knob's runs, always afresh (they check the present model; the grid's are reused): the
    stored ones of these cases are dropped first. Where the knob's Newton tolerance is not the grid's,
    the grid's cells reaching the target are run again at the knob's tolerance, cheapest first, until
    one reaches it there (kind grid_tol): the like-for-like cost ratio of docs/accuracy.md."""
    rows[:] = [r for r in rows if r["kind"] != "accuracy" or r["case"] not in CASES]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, FIELDS)
        w.writeheader()
        w.writerows({k: r.get(k, "") for k in FIELDS} for r in rows)
    for case in CASES:
        for acc in TARGETS + EXTRA_TARGETS.get(case, []):
            r = one(binary, path, rows, case, "accuracy", "", "", "", acc)
            if r["completed"] == "True" and not same_tolerance(float(r["newton_tolerance"]), GRID_TOL):
                grid_at_tolerance(binary, path, rows, case, float(acc), float(r["newton_tolerance"]))


def grid_at_tolerance(binary, path, rows, case, target, tol):
    """The cheapest grid cell reaching `target` when run at the Newton tolerance `tol`: the cells
    reaching it at the grid's tolerance, cheapest first, each run at `tol` (kind grid_tol, reused where
    stored) until one reaches it; that row, or None."""
    ref = next((r for r in rows if r["case"] == case and r["kind"] == "reference" and r["completed"] == "True"), None)
    if ref is None:
        return None
    cells = sorted((g for g in rows if g["case"] == case and g["kind"] == "grid" and g["completed"] == "True"
                    and error(g, ref) <= target), key=work)
    for g in cells:
        r = one(binary, path, rows, case, "grid_tol", int(g["n_elements"]), float(g["time_step"]), tol)
        if r["completed"] == "True" and error(r, ref) <= target:
            return r
    return None


def same_tolerance(a, b):
    return abs(a / b - 1) < 1e-9


def cheapest_at_tolerance(rows, case, ref, target, tol):
    """The cheapest stored grid_tol run of `case` at tolerance `tol` within `target` (None: none)."""
    ok = [g for g in rows if g["case"] == case and g["kind"] == "grid_tol" and g["completed"] == "True"
          and same_tolerance(float(g["newton_tolerance"]), tol) and error(g, ref) <= target]
    return min(ok, key=work) if ok else None


def json_of(cmd):
    """The `--json` object a riser command prints (its line starting with "{"); the command must succeed."""
    p = subprocess.run(cmd, capture_output=True, text=True, check=True)
    return json.loads(next(line for line in p.stdout.splitlines() if line.startswith("{")))


def choice(binary, case, sets):
    """The knob's choice for a case, the `accuracy` object of its `--json` (a 0.2 s run reports it),
    with `sets` (NAME=VALUE, accuracy among them) given; None where riser refuses."""
    cmd = command(binary, case)
    cmd[cmd.index("--duration") + 1] = "0.2"
    if "--window" in cmd:
        i = cmd.index("--window")
        del cmd[i:i + 2]
    for s in sets:
        cmd += ["--set", s]
    try:
        return json_of(cmd)["accuracy"]
    except (subprocess.CalledProcessError, StopIteration):
        return None


def predicted(binary, case, target, pinned=None):
    """The error model's prediction for a case and target; with pinned = (n, dt), its prediction for
    those numerics."""
    sets = [f"{k}={v}" for k, v in zip(("n_elements", "time_step"), pinned or ())] + [f"accuracy={target}"]
    c = choice(binary, case, sets)
    return c["predicted_error"] if c else None


# the lazy waves grow a high-frequency oscillation below the references' step (docs/accuracy.md, "The
# references' floor"): their fine references are not references
NO_FINE_REFERENCE = ("lazy_wave", "lazy_wave_T10")


def finest_reference(docs, case):
    """The case's reference at the shortest step of `riser-tools accuracy-ref`
    (docs/accuracy_references_fine.csv), or None (none run, or the case in NO_FINE_REFERENCE)."""
    path = Path(docs) / "accuracy_references_fine.csv"
    if case in NO_FINE_REFERENCE or not path.exists():
        return None
    fine = [r for r in load(path) if r["case"] == case and r["completed"] == "True"]
    return min(fine, key=lambda r: float(r["time_step"])) if fine else None


# the heave cases of the figure: the aim's (the built-in scenes and the jumper at their own motions), then
# the design motion on each line
FIGURE_CASES = ("catenary", "lazy_wave", "steel_catenary", "lowe_langley_jumper", "catenary_T10", "lazy_wave_T10",
                "steel_catenary_T10", "lowe_langley_jumper_T10")


def cost_frontier(rows, case, targets):
    """For each target, the work of the cheapest grid cell (at the grid's tolerance) whose error is at
    or below it (None where no cell reaches it)."""
    ref = next(r for r in rows if r["case"] == case and r["kind"] == "reference")
    cells = [(error(g, ref), work(g)) for g in rows
             if g["case"] == case and g["kind"] == "grid" and g["completed"] == "True"]
    return [min((w for e, w in cells if e <= t), default=None) for t in targets]


def plot_cost(rows, dst):
    """docs/figures/accuracy_cost.png: for each heave case, the knob's work at each target it was
    checked at against the cheapest grid cell reaching that target (the aim: within 2 times), and the
    knob's measured error against the target."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    fig, axes = plt.subplots(2, 4, figsize=(16, 7.5), sharex=True)
    grid_t = np.logspace(-4, -2, 200)
    for ax, case in zip(axes.flat, FIGURE_CASES):
        mine = [r for r in rows if r["case"] == case]
        ref = next(r for r in mine if r["kind"] == "reference")
        front = cost_frontier(rows, case, grid_t)
        ok = [(t, w) for t, w in zip(grid_t, front) if w is not None]
        ax.step([t for t, _ in ok], [w for _, w in ok], where="post", color="0.3",
                label="cheapest grid cell reaching the target")
        ax.step([t for t, _ in ok], [2 * w for _, w in ok], where="post", color="0.3", ls="--", lw=0.8,
                label="2 x that (the aim)")
        knob = sorted(((float(r["accuracy"]), work(r), error(r, ref)) for r in mine
                       if r["kind"] == "accuracy" and r["completed"] == "True"), key=lambda x: x[0])
        within = [(t, w) for t, w, e in knob if e <= t]
        above = [(t, w) for t, w, e in knob if e > t]
        ax.plot(*zip(*within), "o", color="tab:blue", label="the knob's choice (error within the target)")
        if above:
            ax.plot(*zip(*above), "x", color="tab:red", ms=8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(case, fontsize=10)
        ax.grid(True, which="both", lw=0.3)
    for ax in axes[1]:
        ax.set_xlabel("target: relative error of the top tension")
    fig.supylabel("work (elements x steps x Newton iterations)", fontsize=10)
    axes.flat[0].plot([], [], "x", color="tab:red", ms=8,
                      label="the knob's choice, above the target against the 0.0125 s reference")
    fig.legend(*axes.flat[0].get_legend_handles_labels(), loc="lower center", ncol=4, fontsize=8)
    fig.suptitle("The accuracy knob's cost against the study's grid (riser-tools accuracy; the grid at its "
                 "tolerance 1e-8, the knob at its own)", fontsize=11)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    Path(dst).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(dst, dpi=110)
    plt.close(fig)


def write_doc(rows, docs, binary):
    lines = ["# The accuracy knob: calibration grid and check", "",
             "Made by `riser-tools accuracy` (riser_tools.studies.accuracy; the model is in "
             "[theory.md](theory.md) §16). Each run: `riser run SCENE --heave A,T --duration 4T` "
             "(ramp one period, steady window 2T to 4T; lowe_langley_jumper_T10 runs 6T with the window 4T to 6T: its "
             "start's ringing, docs/theory.md §16.10); error e = the largest of the steady window's min, time "
             "mean and max top tension's differences from the reference's, over the reference's max (a miss is "
             "also measured against the finest reference of `riser-tools accuracy-ref` where the case has one). "
             "Cost: the work, "
             "elements x steps x Newton iterations per step (the wall time, in brackets, is of a shared 2-core "
             "machine and only indicative); the cost ratio is the choice's work over the cheapest grid cell's "
             "whose error is at or below the target (the second ratio: over the cheapest of the cells with at "
             "least 75 steps a period of the case's shortest motion, those the model covers; in waves and at 10 s, "
             "dt 0.1 s and below; the third: over the cheapest grid cell that reaches the target when run at the "
             "knob's own Newton tolerance where it is not the grid's 1e-8, the cells reaching it at 1e-8 run again "
             "cheapest first, kind grid_tol, docs/theory.md §16.3 \"The Newton tolerance\"). The cases in waves "
             "(from catenary_airy on; docs/theory.md "
             "§16.4) run the sea given with `--set` over their own duration and steady window (a regular wave: 20 to "
             "40 s; an irregular sea: 20 to 220 s, 20 Tp), with the heave if given; their runs at accuracy 1e-4 are "
             "refused (the model covers 1e-3 and above in waves), and the runs without heave are chosen for no "
             "hang-off motion, as `riser run` without a motion chooses (`riser statics` and the FMU choose for the "
             "design motion, 2.5 m at 10 s unless accuracy_motion_amplitude and accuracy_motion_period give "
             "another). catenary_still and lazy_wave_still: still water, no motion, the window 20 to 40 s: with "
             "the current grown over its first 10 s (current_ramp) the mesh's static error alone (docs/theory.md "
             "§16.7; with the current in full from t = 0 the window held what was left of its jolt, the floor "
             "E_s F_c of §16.2); the model covers every step there. catenary_A10 (10 m at "
             "20 s) is refused by the knob (docs/theory.md eq. 16.5: the motion takes the line taut); its grid shows "
             "why: the top tension snatches between 3 and 537 kN and its reference is converged to 5e-3 only. "
             "lazy_wave_T10, steel_catenary_T10 and lowe_langley_jumper_T10: the design motion (2.5 m at 10 s, what "
             "`riser statics` and the FMU choose for) on the other lines, in the calibration since the mesh term of the "
             "motion (docs/theory.md §16.2, C_d). The ladder "
             "tables (the heave cases without a sea): the meshes the knob chooses and the grid's coarsest at every step of "
             "the knob's own ladder from 0.2 to 0.01 s (at least 75 steps a period), each against the model's prediction "
             "for the same numerics (`--set accuracy=1e-2` with n_elements and time_step pinned): the points between the "
             "grid's four steps a choice may land on (docs/theory.md §16.3); 0.01 s, below the knob's shortest step "
             "(0.0125 s, the references'), shows why it is not taken. The heave cases without a sea are also checked "
             "between the targets, at " + ", ".join(f"{t:g}" for t in INTERMEDIATE_TARGETS) + " (each case's last table, "
             "by target).", "",
             "![The knob's work at each target against the cheapest grid cell reaching it]"
             "(figures/accuracy_cost.png)", "",
             "The figure: each heave case's knob runs (dots; a cross where a run is above its target against the "
             "0.0125 s reference) against the cheapest grid cell reaching each target (solid; dashed: twice it, "
             "the aim), both by the work at their own Newton tolerance (the table's first cost ratio; its last "
             "column compares like for like, the grid run again at the knob's tolerance).", ""]
    if all(any(r["case"] == c and r["kind"] == "reference" for r in rows) for c in FIGURE_CASES):
        plot_cost(rows, docs / "figures" / "accuracy_cost.png")
    for case, (scene, amp, period, _) in CASES.items():
        mine = [r for r in rows if r["case"] == case]
        ref = next((r for r in mine if r["kind"] == "reference"), None)
        if ref is None or ref["completed"] != "True":
            continue
        if case in WAVE_CASES:
            *_, sea, duration, (t0, t1) = WAVE_CASES[case]
            what = (f"`{scene}`, " + (f"heave {amp} m / {period:g} s, " if amp > 0 else "no heave, ")
                    + (f"`--set {','.join(sea)}`, " if sea else "still water, ")
                    + f"{duration:g} s, steady window {t0:g} to {t1:g} s")
        else:
            t0, t1 = heave_window(case)
            what = f"`{scene}`, heave {amp} m / {period:g} s, {t1:g} s" + (
                f", steady window {t0:g} to {t1:g} s (its start's ringing, docs/theory.md §16.10)"
                if case in LATE_WINDOW else "")
        lines += [f"## {case}", "", f"{what}; reference "
                  f"{ref['n_elements']} elements, dt {ref['time_step']} s, tolerance 1e-10 (steady top tension "
                  f"{float(ref['tt_min']) / 1e3:.3f} / {float(ref['tt_mean']) / 1e3:.3f} / "
                  f"{float(ref['tt_max']) / 1e3:.3f} kN).", ""]
        for kind in ("check_mesh", "check_step"):
            c = next((r for r in mine if r["kind"] == kind and r["completed"] == "True"), None)
            if c:
                lines.append(f"* {kind}: {c['n_elements']} elements, dt {c['time_step']} s: e = {error(c, ref):.1e}")
        lines += ["", "| elements | " + " | ".join(f"dt {dt:g} s" for dt in STEPS) + " |",
                  "|---|" + "---|" * len(STEPS)]
        for n in CASES[case][3]:
            cells = []
            for dt in STEPS:
                r = have(mine, case, "grid", n, dt, 1e-08)
                cells.append(f"{error(r, ref):.1e} ({float(r['wall_s']):.2f} s)" if r and r["completed"] == "True"
                             else "failed" if r else "")
            lines.append(f"| {n} | " + " | ".join(cells) + " |")
        lad = [r for r in mine if r["kind"] == "ladder"]
        if lad:
            meshes = sorted({int(r["n_elements"]) for r in lad})
            lines += ["", f"The ladder (tolerance {LADDER_TOL:g}): e against the model's prediction for the same numerics "
                      "(**above** where the error exceeds it).", "",
                      "| dt s | " + " | ".join(f"{n} el.: e | predicted" for n in meshes) + " |",
                      "|---|" + "---|---|" * len(meshes)]
            for dt in LADDER_STEPS:
                cells = []
                for n in meshes:
                    r = have(mine, case, "ladder", n, dt, LADDER_TOL)
                    if r is None or r["completed"] != "True":
                        cells += ["failed" if r else "", ""]
                        continue
                    e, pe = error(r, ref), predicted(binary, case, 1e-2, (n, dt))
                    cells += [f"{e:.1e}" + (" **above**" if pe is not None and e > pe else ""),
                              f"{pe:.1e}" if pe is not None else "?"]
                if any(cells):
                    lines.append(f"| {dt:g} | " + " | ".join(cells) + " |")
        acc_rows = sorted((r for r in mine if r["kind"] == "accuracy"), key=lambda r: -float(r["accuracy"]))
        if acc_rows:
            lines += ["", "| accuracy | chosen n, dt, tol | predicted | error | work (wall) | cheapest grid cell "
                      "reaching it | its work | cost ratio | cost ratio, covered cells | cost ratio, the grid at "
                      "the knob's tolerance |",
                      "|---|---|---|---|---|---|---|---|---|---|"]
            grid_ok = [r for r in mine if r["kind"] == "grid" and r["completed"] == "True"]
            covered = [g for g in grid_ok if float(g["time_step"]) * STEPS_PER_PERIOD <= shortest_period(case) + 1e-9]
            for r in acc_rows:
                target = float(r["accuracy"])
                ok = [g for g in grid_ok if error(g, ref) <= target]
                best = min(ok, key=work) if ok else None
                ok_cov = [g for g in covered if error(g, ref) <= target]
                best_cov = min(ok_cov, key=work) if ok_cov else None
                if r["completed"] != "True":
                    lines.append(f"| {target:g} | refused | | | | | | | | |")
                    continue
                tol = float(r["newton_tolerance"])
                same = best if same_tolerance(tol, GRID_TOL) else cheapest_at_tolerance(mine, case, ref, target, tol)
                if same is None:
                    like = "none"
                elif same_tolerance(tol, GRID_TOL):
                    like = f"{work(r) / work(same):.2f}"
                else:
                    like = f"{work(r) / work(same):.2f} ({same['n_elements']} el., dt {same['time_step']} s)"
                e = error(r, ref)
                pe = predicted(binary, case, target)
                pe = f"{pe:.1e}" if pe is not None else "?"
                b = (f"{best['n_elements']} el., dt {best['time_step']} s (e {error(best, ref):.1e})",
                     f"{work(best):.3g}", f"{work(r) / work(best):.2f}") if best else ("none", "", "")
                verdict = "ok" if e <= target else "ABOVE TARGET"
                fine = finest_reference(docs, case) if e > target else None
                if fine is not None:
                    # the reference itself is not converged at the target's level: what the finest says
                    ef = error(r, fine)
                    verdict += (f" (against the {float(fine['time_step']):g} s reference, {ef:.1e}: "
                                f"{'ok' if ef <= target else 'above too'})")
                lines.append(f"| {target:g} | {r['n_elements']}, {r['time_step']} s, {float(r['newton_tolerance']):g} "
                             f"| {pe} | {e:.1e} {verdict} | {work(r):.3g} "
                             f"({float(r['wall_s']):.2f} s) | {b[0]} | {b[1]} | {b[2]} | "
                             + (f"{work(r) / work(best_cov):.2f} |" if best_cov else "none |") + f" {like} |")
        lines.append("")
    # the hand-written section of `riser-tools accuracy-ref` (the references' floor) is kept at the end
    old = (docs / "accuracy.md").read_text() if (docs / "accuracy.md").exists() else ""
    kept = old[old.index(FLOOR_HEADING):] if FLOOR_HEADING in old else ""
    (docs / "accuracy.md").write_text("\n".join(lines) + "\n" + kept)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="riser-tools accuracy", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/fasttest/riser")
    ap.add_argument("--out", default="out/accuracy")
    ap.add_argument("--docs", default="docs")
    ap.add_argument("--phase", choices=["grid", "ladder", "verify", "all", "doc"], default="all")
    ap.add_argument("--case", action="append", help="only these cases (default: all)")
    args = ap.parse_args(argv)
    out, docs = Path(args.out), Path(args.docs)
    out.mkdir(parents=True, exist_ok=True)
    every = dict(CASES)
    if args.case:
        for c in list(CASES):
            if c not in args.case:
                del CASES[c]
    path = out / "grid.csv"
    committed = docs / "accuracy_runs.csv"
    if args.phase in ("ladder", "verify", "doc") and not path.exists() and committed.exists():
        # a phase after the grid on a fresh checkout: from the committed runs, not from nothing (which
        # would write docs/accuracy_runs.csv with this phase's runs alone)
        shutil.copy(committed, path)
        print(f"{path}: from {committed} (the committed runs)", flush=True)
    rows = load(path)
    if args.phase in ("grid", "all"):
        grid(args.bin, path, rows)
    if args.phase in ("ladder", "all"):
        ladder(args.bin, path, rows)
    if args.phase in ("verify", "all"):
        verify(args.bin, path, rows)
    shutil.copy(path, docs / "accuracy_runs.csv")
    # the write-up of every case, the ones not run now from their stored runs
    CASES.update(every)
    write_doc(rows, docs, args.bin)


if __name__ == "__main__":
    main()
