"""The accuracy measured on the user's scene (issue 51): the study's grid of the scheme's orders and its
references, and the check of what `--set accuracy=T` chooses. `riser-tools accuracy [--bin target/fasttest/riser]
[--phase grid|verify|scenes|doc|all] [--case C ...] [--jobs 2]`.

The error (docs/theory.md, eq. 16.1): `riser run SCENE --heave A,T --duration 4T --json` (the default ramp of
one period and the default steady window, from 2T to 4T; the cases of LATE_WINDOW run 2T longer per period of
delay, with `--window` two periods long after it); its `steady.top_tension` [min, mean, max] against the same of
a converged reference run:

    e = max(|min - min_ref|, |mean - mean_ref|, |max - max_ref|) / max_ref.

In waves (WAVE_CASES, docs/theory.md section 16.4): `riser run SCENE [--heave A,T] --set wave_... --duration D
--window T0,T1 --json`, the same error over the case's own window (a regular wave: 20 to 40 s; an irregular
sea: 20 to 220 s, 20 Tp, so that the window's extremes are those of the sea's largest wave groups).

Grid phase: per case, the reference (2x the grid's finest mesh, 0.0125 s, tolerance 1e-10), two checks of it
(half the elements, twice the step) and the grid elements x time step at tolerance 1e-8; rows appended to
out/accuracy/grid.csv as they come (a rerun reuses them), copied to docs/accuracy_runs.csv. The grid calibrated
the retired model of issue 28; it stays as the evidence of the scheme's orders and as the cases' references.

Verify phase: every case at TARGETS (in waves and still water WAVE_TARGETS) with only `--set accuracy=T`, riser's
pilots choosing (docs/theory.md §16.12); each `--json` kept in out/accuracy/measured/CASE@T.json (a rerun reuses
it; delete them to measure a new binary). Each case's reference is the grid's where it has at least twice the
finest pilot's elements and half its shortest step, else a run at those (kind reference_pilots). Per run
(measured_row): the chosen numerics, e against that reference, riser's estimate and estimate / e, met (e <= T),
the pilots and their wall time, the work against the cheapest grid cell reaching T (cost_frontier), and the
pilots' share of a 3-hour run at the chosen numerics. Scenes phase: the same for SCENE_CASES (the scenes the
calibrated model refused), each against a reference of its own. Both write docs/accuracy_measured.csv; every
phase writes docs/accuracy.md (the doc phase only that). The verify, scenes and doc phases on a fresh checkout
(no out/accuracy/grid.csv) start from the committed runs, docs/accuracy_runs.csv.
"""

from __future__ import annotations

import argparse
import csv
import json
import re
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
# The scenes the calibrated model refused (issue 51, evidence 2; the scenes phase): name -> (scene, the
# run's arguments besides its numerics, duration s, steady window (t0, t1) s). No grid: each against a
# reference of its own at twice the finest pilot's elements and half its shortest step (SCENE_TARGETS).
SCENE_CASES = {
    # the lazy wave whose 15 buoyancy modules are bodies on a [[section]] (mass, drag, added mass)
    "lazy_wave_sections": ("docs/cases/lazy_wave_modules.toml", ["--heave", "2.5,10"], 40.0, (20.0, 40.0)),
    # the hang-off 30 m forward of the vessel's reference point, the vessel pitching 0.05 rad at 10 s
    "catenary_pitch_offset": ("catenary", ["--pitch", "0.05,10", "--set", "hang_off_x=30"], 40.0, (20.0, 40.0)),
    # structural damping (Kelvin-Voigt) of 2 ms, the peers' comparison physics
    "catenary_damped": ("catenary", ["--heave", "2.5,10", "--set", "structural_damping=0.002"], 40.0,
                        (20.0, 40.0)),
    # the cable model (tension-only segments) on the steel catenary's seabed, its 120 m touchdown zone
    "steel_catenary_cable": ("steel_catenary", ["--heave", "2.5,15", "--set", "model=cable"], 60.0, (30.0, 60.0)),
    # issue 51's first refused scene: a 460 m lazy wave of a 6-inch flexible whose buoyancy modules are a
    # [[section]] (public-data-like properties, the file's header); its window from 60 s, where the start's
    # transients are below 1e-3 (riser's steadiness check)
    "lazy_wave_460m": ("docs/cases/lazy_wave_460m.toml", ["--heave", "2.5,10"], 90.0, (60.0, 90.0)),
    # the irregular sea of the wave cases from 45 degrees
    "catenary_jonswap_45": ("catenary", [a for s in JONSWAP + ["wave_direction=45"] for a in ("--set", s)], 220.0,
                            WINDOW_IRREGULAR),
}
SCENE_TARGETS = [1e-2, 1e-3]
# the cases without a motion or a sea: no period to take steps of
STILL_CASES = ("catenary_still", "lazy_wave_still")
CASES.update({k: v[:4] for k, v in WAVE_CASES.items()})
STEPS = [0.2, 0.1, 0.05, 0.025]
REF_STEP = 0.0125
TARGETS = [1e-2, 1e-3, 1e-4]
FLOOR_HEADING = "## The references' floor, examined"
# the hand-written sections kept at the end of docs/accuracy.md when the study rewrites it, from the first
# of these present: the reading of the measured runs, then the references' floor (riser-tools accuracy-ref)
FINDINGS_HEADING = "## What the measured runs show"
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
    if case in SCENE_CASES:
        scene, args, duration, (t0, t1) = SCENE_CASES[case]
        return [binary, "run", scene, *args, "--duration", f"{duration:g}", "--window", f"{t0:g},{t1:g}", "--json"]
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


# the fewest steps a period the retired model of issue 28 took: the grid cells it covered, for the
# covered-cells ratio of riser-tools accuracy-ref's report (the references' floor)
STEPS_PER_PERIOD = 75.0
# the grid's Newton tolerance
GRID_TOL = 1e-8


def shortest_period(case):
    """The shortest period of a case's motions: its heave's and, in waves, its sea's (10 s here)."""
    if case in STILL_CASES:
        return float("inf")
    return min(CASES[case][2], 10.0) if case in WAVE_CASES else CASES[case][2]


def duration_of(case):
    if case in SCENE_CASES:
        return SCENE_CASES[case][2]
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


def have(rows, case, kind, n, dt, tol):
    for r in rows:
        if (r["case"], r["kind"], r["n_elements"], r["time_step"], r["newton_tolerance"]) == (
                case, kind, str(n), str(dt), str(tol)):
            return r
    return None


def one(binary, path, rows, case, kind, n, dt, tol):
    """The run of `case` at n elements, step dt and Newton tolerance tol (kind: reference, grid, ...),
    reused where stored, else run and appended to `path`."""
    r = have(rows, case, kind, n, dt, tol)
    if r is not None:
        return r
    out = run(binary, case, {"n_elements": n, "time_step": dt, "newton_tolerance": tol})
    row = {"case": case, "kind": kind, "n_elements": n, "time_step": dt, "newton_tolerance": tol, "accuracy": "",
           "completed": out["completed"]}
    if out["completed"]:
        row.update(tt_min=out["tt"][0], tt_mean=out["tt"][1], tt_max=out["tt"][2], wall_s=out["wall"],
                   newton_per_step=out["iters"])
    else:
        row.update(tt_min="", tt_mean="", tt_max="", wall_s="", newton_per_step="")
        print(case, kind, n, dt, tol, "failed:", out["stderr"][-300:], flush=True)
    append(path, row)
    rows.append({k: str(v) for k, v in row.items()})
    print(case, kind, n, dt, tol, row.get("tt_max"), row.get("wall_s"), flush=True)
    return rows[-1]


def reference(binary, path, rows, case):
    n_ref = 2 * CASES[case][3][-1]
    return one(binary, path, rows, case, "reference", n_ref, REF_STEP, 1e-10)


def grid(binary, path, rows, cases=None):
    for case in cases or CASES:
        elements = CASES[case][3]
        ref = reference(binary, path, rows, case)
        n_ref = int(ref["n_elements"])
        one(binary, path, rows, case, "check_mesh", n_ref // 2, REF_STEP, 1e-10)
        one(binary, path, rows, case, "check_step", n_ref, 2 * REF_STEP, 1e-10)
        for n in elements:
            for dt in STEPS:
                one(binary, path, rows, case, "grid", n, dt, GRID_TOL)


# the heave cases of the figure: the aim's (the built-in scenes and the jumper at their own motions), then
# the design motion on each line
FIGURE_CASES = ("catenary", "lazy_wave", "steel_catenary", "lowe_langley_jumper", "catenary_T10", "lazy_wave_T10",
                "steel_catenary_T10", "lowe_langley_jumper_T10")


def cost_frontier(rows, case, targets, ref=None):
    """For each target, the work of the cheapest grid cell (at the grid's tolerance) whose error against
    `ref` (default: the case's reference) is at or below it (None where no cell reaches it)."""
    ref = ref or next(r for r in rows if r["case"] == case and r["kind"] == "reference")
    cells = [(error(g, ref), work(g)) for g in rows
             if g["case"] == case and g["kind"] == "grid" and g["completed"] == "True"]
    return [min((w for e, w in cells if e <= t), default=None) for t in targets]


# ------------------------------------------------------------------ the measured choice (issue 51)
# The verify phase: every case at each of its targets with only `--set accuracy=T` (riser's pilots choose;
# src/sim/accuracy.rs, docs/theory.md §16.12), the raw `--json` of each kept in out/accuracy/measured/, the
# table in docs/accuracy_measured.csv. Each case's reference is the grid's (2x its finest mesh, 0.0125 s,
# tolerance 1e-10) where it is finer than every pilot of every target, else one run here at twice the finest
# pilot's elements and half its shortest step (kind reference_pilots in out/accuracy/grid.csv).
WAVE_TARGETS = [1e-2, 1e-3]
# the most elements a scene takes (src/sim/accuracy.rs MAX_ELEMENTS): a reference's cap
MAX_ELEMENTS = 2000
# a 3-hour run (the pilots' cost is stated against it, issue 51)
THREE_HOURS = 10800.0
MEASURED_FIELDS = ["case", "target", "n_elements", "time_step", "newton_tolerance", "error", "estimate",
                   "estimate_over_error", "met", "riser_met", "orders", "notes", "pilots", "rounds", "finest_pilot", "reference", "reference_finer",
                   "pilots_wall_s", "pilots_elapsed_s", "run_wall_s", "work", "grid_cell", "grid_work", "work_ratio",
                   "pilots_share_3h", "pilots_share_3h_element_steps"]


def targets_of(case):
    if case in SCENE_CASES:
        return SCENE_TARGETS
    return WAVE_TARGETS if case in WAVE_CASES else TARGETS


def choose(binary, out, case, target):
    """`riser run` of `case` with only `--set accuracy=target`, its `--json` object (stored in
    out/measured/CASE@TARGET.json and reused); None where it failed (its stderr stored beside)."""
    path = Path(out) / "measured" / f"{case}@{target:g}.json"
    if path.exists():
        return json.loads(path.read_text())
    path.parent.mkdir(parents=True, exist_ok=True)
    p = subprocess.run(command(binary, case) + ["--set", f"accuracy={target:g}"], capture_output=True, text=True)
    path.with_suffix(".err").write_text(p.stderr)
    line = next((ln for ln in p.stdout.splitlines() if ln.startswith("{")), None)
    if p.returncode != 0 or line is None:
        print(case, target, "failed:", p.stderr.strip()[-300:], flush=True)
        return None
    path.write_text(line)
    d = json.loads(line)
    print(case, target, "chose", d["n_elements"], d["time_step"], flush=True)
    return d


def finest_pilot(choices):
    """The most elements and the shortest step of the pilots of all `choices` (the `--json` objects)."""
    pilots = [p for d in choices if d for p in d["accuracy"]["pilots"]]
    return max(p["n_elements"] for p in pilots), min(p["time_step"] for p in pilots)


def finer_than(ref, n, dt):
    """True where the reference row has at least n elements and at most step dt."""
    return int(ref["n_elements"]) >= n and float(ref["time_step"]) <= dt * (1 + 1e-9)


def pilots_reference(binary, path, rows, case, choices, run_new=True):
    """The case's reference for the measured choices: the grid's where it has at least twice the
    finest pilot's elements and half its shortest step, else one run at those (tolerance 1e-10; stored,
    kind reference_pilots). With run_new False a reference not stored is not run: the grid's is taken
    (the table's reference column says which)."""
    ref = next((r for r in rows if r["case"] == case and r["kind"] == "reference"), None)
    n, dt = finest_pilot(choices)
    if ref is not None and finer_than(ref, min(2 * n, MAX_ELEMENTS), dt / 2):
        return ref
    # a reference stored before that is fine enough (an earlier choice's pilots went finer): the finest
    stored = [r for r in rows if r["case"] == case and r["kind"] in ("reference", "reference_pilots")
              and r["completed"] == "True" and finer_than(r, min(2 * n, MAX_ELEMENTS), dt / 2)]
    if stored:
        return max(stored, key=lambda r: int(r["n_elements"]) / float(r["time_step"]))
    n_ref, dt_ref = min(2 * n, MAX_ELEMENTS), dt / 2
    if ref is not None:
        n_ref, dt_ref = max(n_ref, int(ref["n_elements"])), min(float(ref["time_step"]), dt_ref)
    dt_ref = float(f"{dt_ref:.4g}")
    if not run_new and ref is not None and have(rows, case, "reference_pilots", n_ref, dt_ref, 1e-10) is None:
        return ref
    return one(binary, path, rows, case, "reference_pilots", n_ref, dt_ref, 1e-10)


def pilot_element_steps(acc):
    """The pilots' work in element-steps (the chooser's cost unit, n/Δt over their simulated time); a pilot an
    earlier round's reused (`reused`) is not counted again."""
    t = acc["pilot_window"][1]
    return sum(p["n_elements"] * round(t / p["time_step"]) for p in acc["pilots"] if not p.get("reused"))


def measured_row(case, target, d, ref, rows):
    """One row of docs/accuracy_measured.csv: the choice `d` (a `--json` object) against `ref` (its
    error e, the study's), the estimate over e, the work of the choice against the cheapest grid cell
    reaching the target against the same reference (cost_frontier), and the pilots' wall time against
    a 3-hour run at the chosen numerics (pilot wall / (run wall x 10800 / run duration); also in
    element-steps, which a shared machine does not perturb)."""
    acc = d["accuracy"]
    tt = d["steady"]["top_tension"]
    run = {"case": case, "n_elements": d["n_elements"], "time_step": d["time_step"],
           "newton_per_step": d["iterations_per_step"], "tt_min": tt[0], "tt_mean": tt[1], "tt_max": tt[2]}
    e = error(run, ref)
    w = work(run)
    front = cost_frontier(rows, case, [target], ref)[0]
    cell = cheapest_cell(rows, case, target, ref)
    duration = float(d["duration"])
    pilots_wall = sum(p["wall_s"] for p in acc["pilots"])
    run_3h = float(d["solve_wall_time"]) * THREE_HOURS / duration
    steps_3h = d["n_elements"] * THREE_HOURS / d["time_step"]
    n_f, dt_f = finest_pilot([d])
    return {"case": case, "target": target, "n_elements": d["n_elements"], "time_step": d["time_step"],
            "newton_tolerance": d["newton_tolerance"], "error": e, "estimate": acc["estimate"],
            "estimate_over_error": acc["estimate"] / e if e > 0 else float("inf"), "met": e <= target,
            "riser_met": acc["met"],
            "orders": orders(acc), "notes": " / ".join(acc["notes"]),
            "pilots": sum(not p.get("reused") for p in acc["pilots"]),
            "rounds": max(p["round"] for p in acc["pilots"]), "finest_pilot": f"{n_f} el., {dt_f:g} s",
            "reference": f"{ref['n_elements']} el., {float(ref['time_step']):g} s",
            "reference_finer": finer_than(ref, min(2 * n_f, MAX_ELEMENTS), dt_f / 2),
            "pilots_wall_s": pilots_wall, "pilots_elapsed_s": acc["wall_s"], "run_wall_s": d["solve_wall_time"],
            "work": w, "grid_cell": f"{cell['n_elements']} el., {cell['time_step']} s" if cell else "none",
            "grid_work": front if front is not None else "", "work_ratio": w / front if front else "",
            "pilots_share_3h": pilots_wall / run_3h, "pilots_share_3h_element_steps": pilot_element_steps(acc) / steps_3h}


def orders(acc):
    """The observed orders of mesh (h) and step (t) of each quantity of the target, "-" where none (the
    triplet at the pilots' floor, or not monotone): "max h2.0 t-; min ..."."""
    def o(x):
        return "-" if x is None else f"{x:.1f}"
    return "; ".join(f"{q.removeprefix('top_tension_')} h{o(v['mesh'])} t{o(v['step'])}"
                     for q, v in sorted(acc["orders"].items()))


def cheapest_cell(rows, case, target, ref):
    """The cheapest grid cell (by work) whose error against `ref` is within `target`, or None."""
    ok = [g for g in rows if g["case"] == case and g["kind"] == "grid" and g["completed"] == "True"
          and error(g, ref) <= target]
    return min(ok, key=work) if ok else None


def measure(binary, out, path, rows, cases, jobs=2, run_new=True):
    """The measured choice of every case of `cases` at its targets (`jobs` runs at a time), each case
    against a reference finer than its pilots (pilots_reference); the rows of
    docs/accuracy_measured.csv."""
    from concurrent.futures import ThreadPoolExecutor

    todo = [(c, t) for c in cases for t in targets_of(c)]
    with ThreadPoolExecutor(jobs) as pool:
        got = dict(zip(todo, pool.map(lambda ct: choose(binary, out, *ct), todo)))
    refs = {}
    with ThreadPoolExecutor(jobs) as pool:
        for case in cases:
            choices = [got[(case, t)] for t in targets_of(case)]
            if any(choices):
                refs[case] = pool.submit(pilots_reference, binary, path, rows, case, choices, run_new)
    table = []
    for case in cases:
        if case not in refs:
            continue
        ref = refs[case].result()
        for t in targets_of(case):
            d = got[(case, t)]
            table.append(measured_row(case, t, d, ref, rows) if d and ref["completed"] == "True"
                         else {"case": case, "target": t, "notes": "failed" if not d else "its reference failed"})
    return table


def merge_measured(table, dst):
    """docs/accuracy_measured.csv with the rows of `table`'s cases replaced by its rows."""
    cases = {r["case"] for r in table}
    kept = [r for r in load(dst) if r["case"] not in cases]
    write_measured(kept + table, dst)


def write_measured(table, dst):
    with open(dst, "w", newline="") as f:
        w = csv.DictWriter(f, MEASURED_FIELDS)
        w.writeheader()
        for r in table:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})


def plot_cost(rows, dst, measured=()):
    """docs/figures/accuracy_cost.png: for each heave case of FIGURE_CASES, the cheapest grid cell reaching
    each target (the frontier; dashed: twice it, issue 51's bound) and the measured choice's work at each
    target (`measured`: rows of docs/accuracy_measured.csv; a cross where its error is above the target)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    fig, axes = plt.subplots(2, 4, figsize=(16, 7.5), sharex=True)
    grid_t = np.logspace(-4, -2, 200)
    for ax, case in zip(axes.flat, FIGURE_CASES):
        # the measured choices' reference (finer than their pilots) where run, else the grid's
        finer = [r for r in rows if r["case"] == case and r["kind"] == "reference_pilots" and r["completed"] == "True"]
        front = cost_frontier(rows, case, grid_t, max(finer, key=lambda r: int(r["n_elements"])) if finer else None)
        ok = [(t, w) for t, w in zip(grid_t, front) if w is not None]
        ax.step([t for t, _ in ok], [w for _, w in ok], where="post", color="0.3",
                label="cheapest grid cell reaching the target (against the choices' reference)")
        ax.step([t for t, _ in ok], [2 * w for _, w in ok], where="post", color="0.3", ls="--", lw=0.8,
                label="2 x that (issue 51's bound)")
        mine = [r for r in measured if r["case"] == case and r.get("work")]
        for met, mark, color in ((True, "o", "tab:blue"), (False, "x", "tab:red")):
            pts = [(float(r["target"]), float(r["work"])) for r in mine if (str(r["met"]) == "True") == met]
            if pts:
                ax.plot(*zip(*pts), mark, color=color, ms=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(case, fontsize=10)
        ax.grid(True, which="both", lw=0.3)
    for ax in axes[1]:
        ax.set_xlabel("target: relative error of the top tension")
    fig.supylabel("work (elements x steps x Newton iterations)", fontsize=10)
    axes.flat[0].plot([], [], "o", color="tab:blue", label="the measured choice, within its target")
    axes.flat[0].plot([], [], "x", color="tab:red", label="the measured choice, above its target")
    fig.legend(*axes.flat[0].get_legend_handles_labels(), loc="lower center", ncol=4, fontsize=8)
    fig.suptitle("The measured choice's cost against the study's grid (riser-tools accuracy; the grid at its "
                 "tolerance 1e-8, the choice at its own)", fontsize=11)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    Path(dst).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(dst, dpi=110)
    plt.close(fig)


def describe(case):
    """A case's run in words: scene, motion, sea, duration and window."""
    if case in SCENE_CASES:
        scene, args, duration, (t0, t1) = SCENE_CASES[case]
        return f"`{scene} {' '.join(args)}`, {duration:g} s, window {t0:g} to {t1:g} s"
    scene, amp, period, _ = CASES[case]
    if case in WAVE_CASES:
        *_, sea, duration, (t0, t1) = WAVE_CASES[case]
        return (f"`{scene}`, " + (f"heave {amp} m / {period:g} s, " if amp > 0 else "no heave, ")
                + (f"`--set {','.join(sea)}`, " if sea else "still water, ")
                + f"{duration:g} s, steady window {t0:g} to {t1:g} s")
    t0, t1 = heave_window(case)
    return f"`{scene}`, heave {amp} m / {period:g} s, {t1:g} s, window {t0:g} to {t1:g} s"


def fmt(v, spec=".2g"):
    """A csv cell as a number in `spec`, or as it is (blank, "none")."""
    try:
        return format(float(v), spec)
    except (TypeError, ValueError):
        return v or ""


def short_note(note):
    """A note of riser's choice in a few words: "min mesh: oscillatory, R -0.34" for a triplet that does not
    converge monotonically; another note's first 120 characters."""
    m = re.match(r"top_tension_(\w+): (mesh|step)[^:]*: refinement does not converge monotonically \((\w+), "
                 r"R = ([-+\d.e]+)\)", note.strip())
    if m:
        return f"{m[1]} {m[2]}: {m[3]}, R {float(m[4]):.2g}"
    return note.strip()[:120]


def in_order(table):
    """Rows by the cases' order (CASES, then SCENE_CASES), each case's targets from the loosest."""
    order = {c: i for i, c in enumerate(list(CASES) + list(SCENE_CASES))}
    return sorted(table, key=lambda r: (order.get(r["case"], len(order)), -float(r["target"])))


def measured_table(table):
    """The markdown table of rows of docs/accuracy_measured.csv."""
    lines = ["| case | target | chosen n, Δt s, tol | error e | estimate | estimate / e | met | pilots (rounds) | "
             "finest pilot | reference | pilots' wall s (elapsed) | run's wall s | work | cheapest grid cell | "
             "work ratio | pilots / 3 h run: wall (element-steps) | orders h / t per quantity; notes |",
             "|---|" + "---|" * 16]
    for r in in_order(table):
        if not r.get("n_elements"):
            lines.append(f"| {r['case']} | {fmt(r['target'], 'g')} | {r.get('notes', '')} |" + " |" * 14)
            continue
        lines.append(
            f"| {r['case']} | {fmt(r['target'], 'g')} | {r['n_elements']}, {fmt(r['time_step'], 'g')}, "
            f"{fmt(r['newton_tolerance'], 'g')} | {fmt(r['error'], '.1e')} | {fmt(r['estimate'], '.1e')} | "
            f"{fmt(r['estimate_over_error'])} | {'yes' if str(r['met']) == 'True' else '**no**'}"
            f"{'' if str(r['riser_met']) == 'True' else ' (riser: not met)'} | "
            f"{r['pilots']} ({r['rounds']}) | {r['finest_pilot']} | {r['reference']}"
            f"{'' if str(r['reference_finer']) == 'True' else ' (the grid’s: not finer)'} | "
            f"{fmt(r['pilots_wall_s'], '.3g')} ({fmt(r['pilots_elapsed_s'], '.3g')}) | "
            f"{fmt(r['run_wall_s'], '.2g')} | {fmt(r['work'], '.3g')} | {r['grid_cell']} | "
            f"{fmt(r['work_ratio'])} | {fmt(r['pilots_share_3h'], '.1%')} "
            f"({fmt(r['pilots_share_3h_element_steps'], '.1%')}) | {r['orders']}"
            + "".join(f"; {short_note(n)}" for n in r["notes"].split(" / ") if n.strip()) + " |")
    return lines


def summary(table):
    """One sentence of figures over the rows: targets met, estimate / e, work ratio, pilots' share."""
    done = [r for r in table if r.get("n_elements")]
    if not done:
        return "No runs."
    met = sum(str(r["met"]) == "True" for r in done)
    ratio = [float(r["estimate_over_error"]) for r in done]
    work_r = [float(r["work_ratio"]) for r in done if r["work_ratio"] not in ("", None)]
    share = [float(r["pilots_share_3h"]) for r in done]
    share_s = [float(r["pilots_share_3h_element_steps"]) for r in done]
    failed = len(table) - len(done)
    return (f"Targets met: {met} of {len(done)}" + (f" ({failed} runs failed)" if failed else "")
            + f"; estimate / measured error {min(ratio):.2f} to {max(ratio):.2f}"
            + (f"; work over the cheapest grid cell reaching the target {min(work_r):.2f} to {max(work_r):.2f}"
               f" ({sum(w <= 2 for w in work_r)} of {len(work_r)} within 2)" if work_r else "")
            + f"; the pilots' share of a 3-hour run {min(share):.1%} to {max(share):.1%} by wall time, "
            f"{min(share_s):.1%} to {max(share_s):.1%} by element-steps.")


def write_doc(rows, docs, binary):
    """docs/accuracy.md: the measured choice on the study's cases and on the refused scenes (from
    docs/accuracy_measured.csv), the figure, and the grid of each case (evidence of the orders and the
    references); the hand-written section from FLOOR_HEADING on is kept."""
    measured = load(docs / "accuracy_measured.csv")
    study = [r for r in measured if r["case"] in CASES]
    scenes = [r for r in measured if r["case"] in SCENE_CASES]
    lines = [
        "# Accuracy, measured: the choice on the study's cases and on new scenes, and the grid", "",
        "Made by `riser-tools accuracy` (riser_tools.studies.accuracy). With `--set accuracy=ε` riser measures its "
        "error on the scene as given: pilot runs of the scene's own motion and sea, in rounds, each axis' observed "
        "order, and the cheapest numerics whose estimate meets the target (docs/theory.md §16.12, (16.17)–(16.18); "
        "src/sim/accuracy.rs). The calibrated model of issue 28 (forty constants fitted to the grid below, coverage "
        "ranges and refusals) is retired (issue 51); its grid stays as the evidence of the scheme's orders and as "
        "the cases' references.", "",
        "Each row: `riser run` of the case with only `--set accuracy=T` (the verify phase; the scenes phase for the "
        "scenes), its `--json` kept in out/accuracy/measured/. Error e: the largest of the steady window's min, "
        "time mean and max top tension's differences from the reference's, over the reference's max (the quantity "
        "the target is on by default, `accuracy_quantity=top_tension`). The reference: the grid's (2x its finest "
        "mesh, 0.0125 s, Newton 1e-10) where it has at least twice the finest pilot's elements and half its "
        "shortest step, else a run made at those (kind reference_pilots in [accuracy_runs.csv](accuracy_runs.csv); "
        "the same window, Newton 1e-10). Estimate: riser's, the `accuracy.estimate` of its `--json`. Work: "
        "elements x steps x Newton iterations per step; the work ratio is the choice's over the cheapest grid cell "
        "(at the grid's tolerance 1e-8) whose error against the same reference is within the target "
        "(cost_frontier). The pilots' share of a 3-hour run: their wall time, summed over the pilots (they run "
        "on two threads; the elapsed time in brackets), over the run's solve wall time scaled to 10800 s of "
        "simulated time, and the same in element-steps (the pilots' n x steps against the chosen n x 10800 s / "
        "Δt: not perturbed by the shared 2-core machine the walls were measured on). A 3-hour run's pilots are "
        "these: they span the window's first three periods of the slowest forcing (twenty peak periods of an "
        "irregular sea) whatever the run's length. "
        "Orders: per quantity of the target (top tension max, min, mean) the observed order of the mesh (h) and "
        "the step (t) of the round the choice came from, – where the triplet's spread is at the pilots' floor or "
        "it did not converge monotonically (the notes say which). Rows: "
        "[accuracy_measured.csv](accuracy_measured.csv).", "",
        "## The study's cases", "",
        "Every case of the study at 1e-2, 1e-3 and 1e-4 (in waves and still water: 1e-2 and 1e-3), as in the "
        "grid sections below. " + summary(study), "",
        *measured_table(study), "",
        "![The measured choice's work at each target against the cheapest grid cell reaching it]"
        "(figures/accuracy_cost.png)", "",
        "## Scenes the calibrated model refused", "",
        "Each at 1e-2 and 1e-3, against a reference run here at twice the finest pilot's elements and half its "
        "shortest step (Newton 1e-10, the same window); no grid. " + summary(scenes), "",
    ]
    lines += [f"* {c}: {describe(c)}." for c in SCENE_CASES] + [""] + measured_table(scenes) + [""]
    lines += ["## The grid: the scheme's orders and the references", "",
              "Each case: its reference, the reference's two checks (half its mesh; twice its step), and the grid "
              "(tolerance 1e-8): e against the reference (the solve wall time in brackets, of a shared machine).",
              ""]
    plot_cost(rows, docs / "figures" / "accuracy_cost.png", measured)
    for case in CASES:
        mine = [r for r in rows if r["case"] == case]
        ref = next((r for r in mine if r["kind"] == "reference"), None)
        if ref is None or ref["completed"] != "True":
            continue
        lines += [f"### {case}", "", f"{describe(case)}; reference {ref['n_elements']} elements, dt "
                  f"{ref['time_step']} s, tolerance 1e-10 (steady top tension {float(ref['tt_min']) / 1e3:.3f} / "
                  f"{float(ref['tt_mean']) / 1e3:.3f} / {float(ref['tt_max']) / 1e3:.3f} kN).", ""]
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
        lines.append("")
    # the hand-written sections (the reading of the runs; `riser-tools accuracy-ref`'s references' floor)
    # are kept at the end
    old = (docs / "accuracy.md").read_text() if (docs / "accuracy.md").exists() else ""
    at = [old.index(h) for h in (FINDINGS_HEADING, FLOOR_HEADING) if h in old]
    kept = old[min(at):] if at else ""
    (docs / "accuracy.md").write_text("\n".join(lines) + "\n" + kept)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="riser-tools accuracy", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/fasttest/riser")
    ap.add_argument("--out", default="out/accuracy")
    ap.add_argument("--docs", default="docs")
    ap.add_argument("--phase", choices=["grid", "verify", "scenes", "all", "doc"], default="all")
    ap.add_argument("--case", action="append", help="only these cases (default: all)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--grid-references", action="store_true",
                    help="verify, scenes: where a reference finer than the pilots is not stored, take the grid's "
                         "rather than run one")
    args = ap.parse_args(argv)
    out, docs = Path(args.out), Path(args.docs)
    out.mkdir(parents=True, exist_ok=True)
    cases = [c for c in CASES if not args.case or c in args.case]
    scenes = [c for c in SCENE_CASES if not args.case or c in args.case]
    path = out / "grid.csv"
    committed = docs / "accuracy_runs.csv"
    if args.phase in ("verify", "scenes", "doc") and not path.exists() and committed.exists():
        # a phase after the grid on a fresh checkout: from the committed runs, not from nothing (which
        # would write docs/accuracy_runs.csv with this phase's runs alone)
        shutil.copy(committed, path)
        print(f"{path}: from {committed} (the committed runs)", flush=True)
    rows = load(path)
    if args.phase in ("grid", "all"):
        grid(args.bin, path, rows, cases)
    if args.phase in ("verify", "all"):
        merge_measured(measure(args.bin, out, path, rows, cases, args.jobs, not args.grid_references),
                       docs / "accuracy_measured.csv")
    if args.phase in ("scenes", "all"):
        merge_measured(measure(args.bin, out, path, rows, scenes, args.jobs, not args.grid_references),
                       docs / "accuracy_measured.csv")
    shutil.copy(path, docs / "accuracy_runs.csv")
    write_doc(rows, docs, args.bin)


if __name__ == "__main__":
    main()
