#!/usr/bin/env python3
"""The flexible jumper of Lowe & Langley (OMAE 2006) as MoorDyn's test suite
encodes it, run with riser and compared with the paper's top tension.

Sources (FloatingArrayDesign/MoorDyn, commit in REF_COMMIT):
* tests/Mooring/lowe_and_langley_2006/line.txt: the MoorDyn input (line
  properties, anchor and fairlead, water depth, density, gravity);
* tests/lowe_and_langley_2006.cpp: the test (static forces within 0.2 kN per
  component; cases 1-3: fairlead surge / sway / heave 10 m, 27 s, ramped in
  over one period, then every point of the paper's digitised top tension
  over 80 s within 1 kN; cases 4-6: a regular wave H 10 m, T 10 s at 0, 45,
  90 deg, phase 230, 165, 0 deg, no fairlead motion, at full height from
  t = 0 (no ramp), every point over 30 s after t = 20 s within 1 kN);
* tests/Mooring/lowe_and_langley_2006/Case {1,...,6}.csv: the paper's top
  tension (t - t_ramp in s, kN), copied unchanged to
  docs/cases/lowe_langley_2006_case{1,...,6}.csv.

The scene is docs/cases/lowe_langley_jumper.toml (hang-off at the origin,
surface 5 m above it). Runs (each from the static state):
* statics;
* case 3: --heave 10,27 --ramp 27 --duration 107 (MoorDyn ramps over one
  period with a quintic smoothstep, riser with 1/2(1 - cos(pi t/27)); both
  are at full amplitude from t = 27 s, where the paper's time starts);
* case 3 with --set water_surface_z=1000 (the line always submerged: what
  the model gave before the free surface);
* case 3 at 68 elements (MoorDyn's segment count) and dt 0.025 s: the
  discretisation check;
* case 3 with --set seabed_z=-95 (MoorDyn's seabed): no contact expected;
* cases 1 and 2 (surge, sway) only if `riser run --help` offers --surge /
  --sway; the CLI moves the hang-off in heave only, so they are listed as
  not run otherwise;
* cases 4-6: no motion, `--duration 50` with --set wave_kind=airy,
  wave_height=10, wave_period=10, wave_direction=0/45/90,
  wave_phase=230/165/0, wave_ramp=0, wave_stretching=none, water_depth=100
  and structural_damping=7.18e-4 (MoorDyn's axial damping BA = 359035 N s
  over EA) (MoorDyn's sea on riser's axes: the hang-off at the origin with
  MoorDyn's x and y, riser's time = MoorDyn's, the paper's t = t - 20 s; the
  reasoning is in tests/it/free_surface.rs), and for case 5 the variants
  without the axial damping, Wheeler stretching, a 10 s ramp, dt 0.025 and
  0.0125 s, 68 elements, deep water. A binary that refuses waves (before the water's
  force with waves) lists them as not run;
* cases 4-6 through MoorDyn itself (the pinned Python package `moordyn`,
  when it imports): the test's `case456` ported line for line (LINE_TXT,
  its kinematics handed over at every node every 0.005 s at t + dt/2),
  against the paper with the test's check and against riser.

Usage (from the repository root; `make lowe-langley`):
    riser-tools lowe-langley [--bin target/release/riser] [--out out/lowe_langley] [--doc docs/lowe_langley.md]
"""

import argparse
import bisect
import datetime
import json
import math
import os
import sys
import time

from .. import cli
from ..cases import Motion

ROOT = os.getcwd()
SCENE = "docs/cases/lowe_langley_jumper.toml"
REF_REPO = "FloatingArrayDesign/MoorDyn"
REF_COMMIT = "319ff99771cffb835fea4423306a0849692afd53"
A, T = 10.0, 27.0  # m, s: amplitude and period of cases 1-3
T_RAMP = T  # s: MoorDyn ramps over one period; the paper's t = 0 is its end
T_WINDOW = 80.0  # s of paper data after the ramp
TOL_STATIC = 0.2  # kN per force component (test "Stationary")
TOL_MOTION = 1.0  # kN at every digitised point (cases 1-6)
# cases 4-6 (tests/lowe_and_langley_2006.cpp, case456): amplitude 5 m, 10 s,
# no ramp; the paper's t = 0 is MoorDyn's t = 2 T_W; compared over 30 s
H_W, T_W = 10.0, 10.0
T_START_W = 2 * T_W
T_WINDOW_W = 30.0
# (case, direction of travel deg from +x towards +y, phase deg): the test's
WAVE_CASES = ((4, 0.0, 230.0), (5, 45.0, 165.0), (6, 90.0, 0.0))
# case 5's worst point, and the rise of the digitised curve just before it (kN)
T13 = 1.3
REF5_JUMP = 45.30994 - 43.76488
# MoorDyn's axial damping: BA/-zeta = -0.5 is BA = zeta dl sqrt(EA m) = 359035 N s
# (MoorDyn 2.7.2 logs it), a Kelvin-Voigt stress BA eps_dot: riser's eta = BA/EA
BA_MD = 359035.0
ETA_MD = BA_MD / 5.0e8
# tests/Mooring/lowe_and_langley_2006/line.txt at REF_COMMIT, verbatim
LINE_TXT = """MoorDyn input file for a flexible jumper (Lowe and Langley, 2006)
True   Echo   echo the input file data (flag)
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam     Mass/m     EA         BA/-zeta    EI         Cd     Ca     CdAx    CaAx
(name)     (m)      (kg/m)     (N)        (N-s/-)     (N-m^2)    (-)    (-)    (-)     (-)
main       0.396    165.0      500.0e6    -0.5        120.8e3    1.0    1.0    0.0     0.0
---------------------- CONNECTION PROPERTIES --------------------------------
ID    Type      X       Y       Z       Mass    Volume      CdA    Ca
(#)   (-)       (m)     (m)     (m)     (kg)    (mˆ3)       (m^2)  (-)
1     Fixed     -100    0       -55     0       0           0      0
2     Coupled   0       0       -5      0       0           0      0
---------------------- LINES ----------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (#)      (#)       (m)       (-)     (-)
1      main      1        2         170       68      -
---------------------- OPTIONS -----------------------------------------
0             writeLog      Write a log file
0.001         dtM           Model time step (s)
3.0e6         kBot          bottom stiffness (Pa/m)
3.0e5         cBot          bottom damping (Pa-s/m)
100           WtrDpth       water depth (m)
1000.0        WtrDnsty      water density (kg/m^3)
9.807         g             gravity (m/s^2)
midpoint5     tScheme       Time integration scheme
5.0           CdScaleIC     Initial Condition generation drag factor
30            TmaxIC        Initial Condition generation maximum time (s)
1.0           dtIC          Initial Condition generation convergence tests (s)
5e-3          threshIC      Initial Condition generation convergence threshold
0             ICgenDynamic  IC generator (0 = stationary, 1 = legacy upscale dynamics)
1             WaveKin       The wave kinematics are provided through the API (-)
1       disableOutTime
------------------------- need this line --------------------------------------
"""
# test "Stationary": the force on the fairlead and on the anchor's node, kN
# (the test checks ref + 1e-3 F = 0, so F = -ref)
MD_TOP = (-11.40, 0.0, -45.71)
MD_BOTTOM = (11.40, 0.0, -24.04)
BUOY = 1000 * 9.807 * 3.141592653589793 / 4 * 0.396**2 / 1e3  # kN/m, the line's buoyancy


def run(cmd, log):
    t0 = time.monotonic()
    p = cli.execute(cmd, cwd=ROOT)
    wall = time.monotonic() - t0
    log.append((" ".join(cmd), wall, p.returncode))
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} exited {p.returncode}: {p.stderr.strip()}")
    return p.stdout


def read_ref(case):
    path = os.path.join(ROOT, f"docs/cases/lowe_langley_2006_case{case}.csv")
    with open(path) as f:
        return [tuple(float(v) for v in line.split(",")) for line in f if line.strip()]


def read_series(path):
    return {k: v.tolist() for k, v in cli.read_columns(path).items()}


def interp(ts, ys, x):
    j = bisect.bisect_left(ts, x)
    if j < len(ts) and ts[j] == x:
        return ys[j]
    a = (x - ts[j - 1]) / (ts[j] - ts[j - 1])
    return ys[j - 1] + a * (ys[j] - ys[j - 1])


def against_paper(rwin, win, diffs, ref, w0):
    """riser's top tension against the paper's: max/min/mean over the window
    (`rwin` the paper's (t, kN), `win` riser's) and MoorDyn's pointwise test
    on `diffs` (riser - paper at each of `ref`'s times), the last from `w0`."""
    worst = max(range(len(diffs)), key=lambda i: abs(diffs[i]))
    return {
        "max": (max(rwin, key=lambda p: p[1]), max(win, key=lambda p: p[1])),
        "min": (min(rwin, key=lambda p: p[1]), min(win, key=lambda p: p[1])),
        "mean": (sum(v for _, v in rwin) / len(rwin), sum(v for _, v in win) / len(win)),
        "maxdiff": (abs(diffs[worst]), ref[worst][0], diffs[worst]),
        "rms": (sum(d * d for d in diffs) / len(diffs)) ** 0.5,
        "maxdiff_last": max(abs(d) for d, (t, _) in zip(diffs, ref) if t >= w0),
        "n_fail": sum(abs(d) > TOL_MOTION for d in diffs),
        "n": len(diffs),
    }


def reduce_case(series, ref):
    """Top tension (kN) against the paper's: at the crest of the last
    period, max/min over the last period, and MoorDyn's pointwise test."""
    ts = series["t"]
    tt = [v / 1e3 for v in series["top_tension"]]
    ref_t = [r[0] for r in ref]
    ref_v = [r[1] for r in ref]
    # the last heave crest within the paper's data: t_ref = T/4 + kT = 60.75 s
    crest = T_RAMP + T / 4 + T * int((T_WINDOW - T / 4) // T)
    w0, w1 = T_WINDOW - T, T_WINDOW  # the last period of paper data, t_ref
    win = [(t - T_RAMP, v) for t, v in zip(ts, tt) if w0 <= t - T_RAMP <= ref_t[-1]]
    rwin = [(t, v) for t, v in zip(ref_t, ref_v) if w0 <= t <= w1]
    diffs = [interp(ts, tt, t + T_RAMP) - v for t, v in ref]
    return {
        "crest": (interp(ref_t, ref_v, crest - T_RAMP), interp(ts, tt, crest)),
        **against_paper(rwin, win, diffs, ref, w0),
        "touchdown_min": min(series["touchdown_s"]),
        "crest_t": crest - T_RAMP,
    }


def motion_run(bin_, out, name, motion, extra, log):
    """A case of 107 s from the static state: `motion` (a Motion) ramped over one period."""
    d = os.path.join(out, name)
    cmd = cli.run_command(bin_, SCENE, extra, motion, T_RAMP + T_WINDOW, d)
    summary = json.loads(run(cmd, log))
    if not summary.get("completed", True) or summary.get("error"):
        raise RuntimeError(f"{name}: {summary.get('error')}")
    return summary, read_series(os.path.join(d, "timeseries.csv"))


def wave_sets(direction, phase, extra=()):
    """MoorDyn's sea of cases 4-6 as riser's --set (docstring; tests/it/free_surface.rs)."""
    return ["wave_kind=airy", f"wave_height={H_W:g}", f"wave_period={T_W:g}", f"wave_direction={direction:g}",
            f"wave_phase={phase:g}", "wave_ramp=0", "wave_stretching=none", "water_depth=100",
            f"structural_damping={ETA_MD:.6g}", *extra]


def md_wave(phi, d, t, r):
    """The test's `wave()`: u and du/dt at r (MoorDyn's frame), A 5 m, T 10 s, Z 100 m."""
    A, Z = H_W / 2, 100.0
    om = 2 * math.pi / T_W
    k = om * om / 9.81
    x = r[0] * math.cos(d) + r[1] * math.sin(d)
    cs, ss = math.cos(k * x - om * t + phi), math.sin(k * x - om * t + phi)
    ch, sh = math.cosh(k * (r[2] + Z)) / math.cosh(k * Z), math.sinh(k * (r[2] + Z)) / math.cosh(k * Z)
    ua, aa = om * A, om * om * A
    return ([ua * cs * ch * math.cos(d), ua * cs * ch * math.sin(d), ua * ss * sh],
            [aa * ss * ch * math.cos(d), aa * ss * ch * math.sin(d), -aa * cs * sh])


def moordyn_case456(case, phase, out):
    """MoorDyn's `case456` (tests/lowe_and_langley_2006.cpp) through the project's MoorDyn driver
    (riser_tools.moordyn): (t, top tension kN) at every 0.005 s step up to t = 50 s; None if
    `moordyn` does not import."""
    from ..moordyn import external_wave_run
    d = os.path.join(out, "moordyn")
    os.makedirs(d, exist_ok=True)
    path = os.path.join(d, "line.txt")
    with open(path, "w") as f:
        f.write(LINE_TXT)
    dt, phi, direction = 0.005, math.radians(phase), (case - 4) * 0.25 * math.pi
    return external_wave_run(path, point=2, line=1, kinematics=lambda t, p: md_wave(phi, direction, t, p),
                             duration=T_START_W + T_WINDOW_W, dt=dt, log=os.path.join(d, f"case{case}.log"))


def reduce_moordyn(md_rows, ref, series):
    """MoorDyn against the paper with the test's check (its first step with t - 20 >= t_ref),
    and riser (interpolated) against MoorDyn at its steps over the paper's window."""
    ts = [r[0] - T_START_W for r in md_rows]
    diffs = []
    for t, v in ref:
        j = bisect.bisect_left(ts, t - 1e-9)
        diffs.append((md_rows[j][1] - v, t))
    worst = max(diffs, key=lambda p: abs(p[0]))
    rt = series["t"]
    rv = [v / 1e3 for v in series["top_tension"]]
    dd = [(interp(rt, rv, t + T_START_W) - v, t) for t, v in zip(ts, (r[1] for r in md_rows)) if 0.0 <= t <= T_WINDOW_W]
    rw = max(dd, key=lambda p: abs(p[0]))
    return {
        "paper": (abs(worst[0]), worst[1], worst[0]),
        "paper_n_fail": sum(abs(x) > TOL_MOTION for x, _ in diffs),
        "riser": (abs(rw[0]), rw[1], rw[0]),
        "riser_rms": (sum(x * x for x, _ in dd) / len(dd)) ** 0.5,
        "at": {t: x for x, t in diffs},
    }


def reduce_waves(series, ref, phase):
    """Top tension (kN) against the paper's over cases 4-6: MoorDyn's pointwise
    test, and max/min/mean over the last wave period of the paper's data; the
    elevation at the origin against MoorDyn's A cos(phi - omega t)."""
    ts = series["t"]
    tt = [v / 1e3 for v in series["top_tension"]]
    diffs = [interp(ts, tt, t + T_START_W) - v for t, v in ref]
    w0 = T_WINDOW_W - T_W
    rwin = [(t, v) for t, v in ref if t >= w0]
    win = [(t - T_START_W, v) for t, v in zip(ts, tt) if w0 <= t - T_START_W <= T_WINDOW_W]
    om, ph = 2 * math.pi / T_W, math.radians(phase)
    eta = series.get("wave_elevation")
    eta_err = None if eta is None else max(abs(e - H_W / 2 * math.cos(ph - om * t)) for t, e in zip(ts, eta))
    return {
        **against_paper(rwin, win, diffs, ref, w0),
        "eta_err": eta_err,
        "at": {t: d for d, (t, _) in zip(diffs, ref)},
    }


def wave_run(bin_, out, name, sets, log):
    """A wave case of 50 s from the static state, the hang-off still; None if
    the binary refuses waves (built before the water's force with waves)."""
    d = os.path.join(out, name)
    cmd = cli.run_command(bin_, SCENE, sets, None, T_START_W + T_WINDOW_W, d)
    t0 = time.monotonic()
    p = cli.execute(cmd, cwd=ROOT)
    if p.returncode != 0 and "not yet applied" in p.stderr:
        return None
    log.append((" ".join(cmd), time.monotonic() - t0, p.returncode))
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} exited {p.returncode}: {p.stderr.strip()}")
    summary = json.loads(p.stdout)
    if not summary.get("completed", True) or summary.get("error"):
        raise RuntimeError(f"{name}: {summary.get('error')}")
    return summary, read_series(os.path.join(d, "timeseries.csv"))


def fmt(x, nd=2):
    return f"{x:.{nd}f}"


def window_rows(tag, r, at=""):
    """The report's rows of a case against the paper (`r` of `against_paper`):
    max, min and mean top tension over the window (`at` names it) and
    MoorDyn's pointwise check."""
    rows = []
    for what in ("max", "min"):
        (pt, pv), (rt, rv) = r[what]
        rows.append(f"| {tag}: {what} top tension{at} | {fmt(pv)} (t_ref {pt:.1f} s) | {fmt(rv)} ({rt:.1f} s) | {rv - pv:+.2f} | ±{TOL_MOTION} |")
    pm, rm = r["mean"]
    rows.append(f"| {tag}: mean top tension{at} | {fmt(pm)} | {fmt(rm)} | {rm - pm:+.2f} | — |")
    md, mt_, ms = r["maxdiff"]
    rows.append(f"| {tag}: largest \\|difference\\| over the {r['n']} digitised points (MoorDyn's check) | — | {fmt(md)} at t_ref {mt_:.1f} s (RMS {fmt(r['rms'])}) | {ms:+.2f}; {r['n_fail']} points over 1 kN | ±{TOL_MOTION} each |")
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(prog="riser-tools lowe-langley", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/release/riser")
    ap.add_argument("--out", default="out/lowe_langley")
    ap.add_argument("--doc", default="docs/lowe_langley.md")
    args = ap.parse_args(argv)
    bin_ = args.bin
    os.makedirs(os.path.join(ROOT, args.out), exist_ok=True)
    log = []
    t_start = time.monotonic()

    # statics
    st = json.loads(run([bin_, "statics", SCENE, "--json"], log))
    low_z = min(r[3] for r in st["shape"])

    # case 3 (heave) and its variants
    heave = Motion(A, T, "heave", T_RAMP)
    ref3 = read_ref(3)
    variants = [
        ("case3", "surface at z = +5 m (the case)", []),
        ("case3_submerged", "`water_surface_z=1000`: always submerged", ["water_surface_z=1000"]),
        ("case3_fine", "68 elements, dt 0.025 s", ["n_elements=68", "time_step=0.025"]),
        ("case3_seabed", "`seabed_z=-95` (MoorDyn's seabed)", ["seabed_z=-95"]),
    ]
    res = {}
    for name, label, extra in variants:
        summary, series = motion_run(bin_, args.out, name, heave, extra, log)
        res[name] = (label, extra, summary, reduce_case(series, ref3))

    # cases 1 and 2 need a horizontal motion of the hang-off
    helptext = run([bin_, "run", "--help"], log)
    horiz = {}
    for case, flag in ((1, "--surge"), (2, "--sway")):
        if flag in helptext:
            try:
                summary, series = motion_run(bin_, args.out, f"case{case}", Motion(A, T, flag[2:], T_RAMP), [], log)
                horiz[case] = ("ok", reduce_case(series, read_ref(case)))
            except (RuntimeError, KeyError, ValueError) as e:
                horiz[case] = ("error", str(e))
        else:
            horiz[case] = ("absent", f"`riser run` has no `{flag}` (the CLI moves the hang-off in heave only)")

    # cases 4-6: the jumper in regular waves; case 4's variants
    waves, wseries, mdres, mdrows = {}, {}, {}, {}
    for case, direction, phase in WAVE_CASES:
        r = wave_run(bin_, args.out, f"case{case}", wave_sets(direction, phase), log)
        waves[case] = None if r is None else reduce_waves(r[1], read_ref(case), phase)
        if r is not None:
            wseries[case] = r[1]
            t0 = time.monotonic()
            md_rows = moordyn_case456(case, phase, args.out)
            if md_rows is not None:
                mdrows[case] = md_rows
                mdres[case] = reduce_moordyn(md_rows, read_ref(case), r[1])
                log.append((f"MoorDyn case456({case}) (moordyn Python package, ported test)", time.monotonic() - t0, 0))
    wave_variants = [
        ("case5_undamped", "without MoorDyn's axial damping (`structural_damping=0`)", ["structural_damping=0"]),
        ("case5_undamped_dt", "without the axial damping, dt 0.0125 s", ["structural_damping=0", "time_step=0.0125"]),
        ("case5_wheeler", "Wheeler stretching (`wave_stretching=wheeler`)", ["wave_stretching=wheeler"]),
        ("case5_ramp", "the waves ramped in over 10 s (`wave_ramp=10`) instead of MoorDyn's abrupt start",
         ["wave_ramp=10"]),
        ("case5_dt025", "dt 0.025 s", ["time_step=0.025"]),
        ("case5_dt0125", "dt 0.0125 s", ["time_step=0.0125"]),
        ("case5_68", "68 elements (MoorDyn's segments)", ["n_elements=68"]),
        ("case5_deep", "deep-water kinematics (`water_depth=0`: k = ω²/g, profiles e^kζ), not MoorDyn's", ["water_depth=0"]),
    ]
    wvar = {}
    if waves[5] is not None:
        for name, label, extra in wave_variants:
            r = wave_run(bin_, args.out, name, wave_sets(45.0, 165.0, extra), log)
            vs_md = reduce_moordyn(mdrows[5], read_ref(5), r[1]) if 5 in mdrows else None
            wvar[name] = (label, reduce_waves(r[1], read_ref(5), 165.0), vs_md)
    total = time.monotonic() - t_start

    # --- the report ---
    L = []
    L.append("# Lowe & Langley (2006) flexible jumper: riser against the paper\n")
    L.append(f"Generated by `riser-tools lowe-langley` (riser_tools.studies.lowe_langley) on {datetime.date.today().isoformat()} "
             f"({len([c for c in log if ' run ' in c[0] and '--help' not in c[0]])} dynamic runs and the statics, {total:.1f} s wall in all).\n")
    L.append("## The case and its sources\n")
    L.append("Lowe & Langley (2006), the flexible jumper of their OMAE 2006 paper (25th International Conference on "
             "Offshore Mechanics and Arctic Engineering; MoorDyn's test cites it as \"the Lowe and Langley OMAE 2006 paper\", "
             "without title or number, and the paper itself was not consulted here: its values are the digitised ones below), "
             f"as MoorDyn's test suite encodes it ([{REF_REPO}](https://github.com/{REF_REPO}) at `{REF_COMMIT[:12]}`):\n")
    L.append("* `tests/Mooring/lowe_and_langley_2006/line.txt`: the MoorDyn input;")
    L.append("* `tests/lowe_and_langley_2006.cpp`: the checks and their tolerances;")
    L.append("* `tests/Mooring/lowe_and_langley_2006/Case {1..6}.csv`: the paper's top tension "
             "(digitised with WebPlotDigitizer; time after the ramp in s, kN); all six are copied unchanged to "
             "`docs/cases/lowe_langley_2006_case{1,...,6}.csv`.\n")
    L.append("| quantity | MoorDyn test | riser scene (`docs/cases/lowe_langley_jumper.toml`) |")
    L.append("|---|---|---|")
    L.append("| line | 170 m, 165 kg/m, D 0.396 m, 68 segments | same, 60 elements (rod) |")
    L.append("| stiffness | EA 5.0e8 N, EI 1.208e5 N m² | same; GJ 1e5 N m² (nominal: MoorDyn has no torsion) |")
    L.append("| hydrodynamics | Cd 1.0, Ca 1.0, CdAx 0, CaAx 0 | `cd_normal` 1, `ca_normal` 1, `cd_tangential` 0 |")
    L.append("| internal damping | BA/-zeta = -0.5 (50 % of critical for each segment's axial mode; BA = 359035 N s) | cases 1-3: none; cases 4-6: `structural_damping` = BA/EA = 7.18e-4 s; `rho_infinity` 0.8 (default) |")
    L.append("| anchor | `Fixed` (-100, 0, -55) m | (-100, 0, -50) m |")
    L.append("| fairlead | `Coupled` (0, 0, -5) m | the hang-off, origin |")
    L.append("| water | depth 100 m, ρ 1000 kg/m³, g 9.807 m/s², surface z = 0 | `water_surface_z` = +5 m, ρ 1000, g 9.807; no seabed (see the check below) |")
    L.append(f"| motion, cases 1/2/3 | fairlead x / y / z += f(t)·{A:g} sin(2πt/{T:g}), f a quintic smoothstep over {T_RAMP:g} s; compared for {T_WINDOW:g} s after it | `--heave {A:g},{T:g} --ramp {T_RAMP:g} --duration {T_RAMP + T_WINDOW:g}` (ramp ½(1 − cos(πt/{T_RAMP:g})); full amplitude from t = {T_RAMP:g} s in both) |")
    L.append(f"| cases 4/5/6 | no fairlead motion; the test's own linear wave (`WaveKin 1`, kinematics handed over at every node and step): "
             f"A {H_W / 2:g} m, T {T_W:g} s, k = ω²/9.81, profiles cosh k(z+100)/cosh 100k at the node's own z, "
             f"η = A cos(k(x cos d + y sin d) − ωt + φ), d 0°/45°/90°, φ 230°/165°/0°, full height from t = 0; "
             f"compared for {T_WINDOW_W:g} s after t = {T_START_W:g} s | "
             f"`--set wave_kind=airy,wave_height={H_W:g},wave_period={T_W:g},wave_direction=0/45/90,wave_phase=230/165/0,"
             f"wave_ramp=0,wave_stretching=none,water_depth=100,structural_damping={ETA_MD:.3g} --duration {T_START_W + T_WINDOW_W:g}` (phase origin the hang-off, "
             "MoorDyn's (0, 0); riser's time = MoorDyn's; k = 0.04028 rad/m from ω² = gk tanh kd, g 9.807) |")
    L.append("| tolerances | statics: 0.2 kN per component of the top and bottom force; cases 1-6: 1 kN at every digitised point | |\n")
    L.append("The top tension is the magnitude of the force at the fairlead (MoorDyn: `MoorDyn_GetLineNodeForce` of the last node; riser: `top_tension`). "
             f"The heave crest is at t = {T_RAMP:g} + 6.75 + 27k s (the paper's t = 6.75 + 27k s), where the hang-off is 5 m above the surface: "
             "its top ~5 m are in air, without buoyancy.\n")

    L.append("## Results\n")
    L.append("Forces in kN (signs: the force of the line on the fairlead / on the anchor, x towards the fairlead's side, z up). "
             "Dynamic values over the last period of the paper's data (t_ref in [53, 80] s); \"difference\" is riser − paper.\n")
    L.append("| case | paper / MoorDyn expected | riser | difference | MoorDyn's tolerance |")
    L.append("|---|---|---|---|---|")
    tf, bf = st["top_force"], st["bottom_force"]
    for lab, ref, val in (("statics: top force x", MD_TOP[0], tf[0] / 1e3), ("statics: top force z", MD_TOP[2], tf[2] / 1e3),
                          ("statics: bottom force x", MD_BOTTOM[0], bf[0] / 1e3), ("statics: bottom force z", MD_BOTTOM[2], bf[2] / 1e3)):
        L.append(f"| {lab} | {fmt(ref)} | {fmt(val, 3)} | {val - ref:+.3f} | ±{TOL_STATIC} |")
    mt = (sum(v * v for v in MD_TOP)) ** 0.5
    mb = (sum(v * v for v in MD_BOTTOM)) ** 0.5
    L.append(f"| statics: top tension | {fmt(mt)} (from the components) | {fmt(st['top_tension'] / 1e3, 3)} | {st['top_tension'] / 1e3 - mt:+.3f} | (components) |")
    L.append(f"| statics: bottom tension | {fmt(mb)} (from the components) | {fmt(st['bottom_tension'] / 1e3, 3)} | {st['bottom_tension'] / 1e3 - mb:+.3f} | (components) |")
    for name in ("case3", "case3_submerged", "case3_fine"):
        label, _, summ, r = res[name]
        tag = "case 3 heave" + ("" if name == "case3" else f", {label}")
        pc, rc = r["crest"]
        L.append(f"| {tag}: top tension at the heave crest (t_ref {r['crest_t']:.2f} s) | {fmt(pc)} | {fmt(rc)} | {rc - pc:+.2f} | ±{TOL_MOTION} |")
        L.extend(window_rows(tag, r))
    for case, what in ((1, "surge"), (2, "sway")):
        status, r = horiz[case]
        ref = read_ref(case)
        rwin = [v for t, v in ref if T_WINDOW - T <= t]
        if status == "ok":
            (pt, pv), (rt, rv) = r["max"]
            L.append(f"| case {case} {what}: max top tension | {fmt(pv)} | {fmt(rv)} | {rv - pv:+.2f} | ±{TOL_MOTION} |")
            (pt, pv), (rt, rv) = r["min"]
            L.append(f"| case {case} {what}: min top tension | {fmt(pv)} | {fmt(rv)} | {rv - pv:+.2f} | ±{TOL_MOTION} |")
            md, mt_, ms = r["maxdiff"]
            L.append(f"| case {case} {what}: largest \\|difference\\| | — | {fmt(md)} | {r['n_fail']} points over 1 kN | ±{TOL_MOTION} each |")
        else:
            L.append(f"| case {case} {what} 10 m, 27 s: max / min top tension | {fmt(max(rwin))} / {fmt(min(rwin))} | not run | — | ±{TOL_MOTION} each |")
    w_last = f"t_ref in [{T_WINDOW_W - T_W:g}, {T_WINDOW_W:g}] s"
    for case, direction, phase in WAVE_CASES:
        r = waves[case]
        tag = f"case {case} waves at {direction:g}° (φ {phase:g}°)"
        if r is None:
            ref = [v for t, v in read_ref(case) if t >= T_WINDOW_W - T_W]
            L.append(f"| {tag}: max / min top tension ({w_last}) | {fmt(max(ref))} / {fmt(min(ref))} | not run: this binary refuses waves | — | ±{TOL_MOTION} each |")
            continue
        L.extend(window_rows(tag, r, f" ({w_last})"))
        if case in mdres:
            m = mdres[case]
            L.append(f"| {tag}: MoorDyn 2.7.2 (its test, run here) against the paper | — | largest \\|difference\\| {fmt(m['paper'][0])} at t_ref {m['paper'][1]:.1f} s | {m['paper'][2]:+.2f}; {m['paper_n_fail']} points over 1 kN | ±{TOL_MOTION} each |")
            L.append(f"| {tag}: riser against MoorDyn 2.7.2, every 0.005 s over t_ref [0, {T_WINDOW_W:g}] s | — | largest \\|difference\\| {fmt(m['riser'][0], 3)} at t_ref {m['riser'][1]:.2f} s (RMS {fmt(m['riser_rms'], 3)}) | {m['riser'][2]:+.3f} | — |")
    L.append("")
    if wvar:
        L.append(f"Case 5 (its largest difference is at t_ref {T13:g} s) under other settings, riser − paper and riser − MoorDyn (kN):\n")
        L.append(f"| case 5 with | largest \\|riser − paper\\| | riser − paper at t_ref {T13:g} s | points over 1 kN | largest \\|riser − MoorDyn\\| (RMS) |")
        L.append("|---|---|---|---|---|")
        b = waves[5]
        rows = [("the case's settings", b, mdres.get(5))] + [(lab, r, m) for lab, r, m in wvar.values()]
        for lab, r, m in rows:
            vm = "—" if m is None else f"{fmt(m['riser'][0], 3)} ({fmt(m['riser_rms'], 3)})"
            L.append(f"| {lab} | {fmt(r['maxdiff'][0], 3)} at {r['maxdiff'][1]:.1f} s | {r['at'][T13]:+.3f} | {r['n_fail']} | {vm} |")
        L.append("")
    L.append("Notes:\n")
    sub = res["case3_submerged"][3]
    base = res["case3"][3]
    L.append(f"* **The free surface.** With the surface far above (`--set water_surface_z=1000`) the top tension at the crest is "
             f"{fmt(sub['crest'][1])} kN instead of {fmt(base['crest'][1])} kN (paper {fmt(base['crest'][0])}): "
             f"{fmt(base['crest'][1] - sub['crest'][1])} kN less: the buoyancy lost by the top of the line, which is above the water at the crest "
             f"(ρgπD²/4 = {BUOY:.3f} kN/m, so {(base['crest'][1] - sub['crest'][1]) / BUOY:.1f} m of line's worth; the hang-off is 5 m above the surface). "
             "The hang-off is out of the water only while the heave exceeds 5 m (a third of each period, around the crest); "
             f"near the trough the two runs agree (max {fmt(sub['max'][1][1])} vs {fmt(base['max'][1][1])} kN), "
             f"and without the surface {sub['n_fail']} of the {sub['n']} digitised points fail MoorDyn's 1 kN check (none with it).")
    if horiz[1][0] != "ok" or horiz[2][0] != "ok":
        L.append(f"* **Cases 1 and 2** (surge, sway) are not run: {horiz[1][1] if horiz[1][0] != 'ok' else horiz[2][1]}. "
                 "The FMU has `surge`/`sway` inputs; the paper's values over the last period are listed for when a horizontal motion is available from the CLI.")
    fine = res["case3_fine"][3]
    L.append(f"* **Discretisation.** 68 elements with dt 0.025 s move the crest tension by {fine['crest'][1] - base['crest'][1]:+.3f} kN "
             f"and the largest pointwise difference from {fmt(base['maxdiff'][0])} to {fmt(fine['maxdiff'][0])} kN: "
             "the remaining differences are the paper's (digitisation, its model) rather than riser's mesh.")
    sb = res["case3_seabed"][3]
    L.append(f"* **Seabed.** The static low point is at z = {low_z:.2f} m (MoorDyn's seabed at z = −95 m here). With `--set seabed_z=-95` "
             f"(MoorDyn's kBot 3e6 Pa/m, cBot 3e5 Pa s/m) the smallest `touchdown_s` over the heave run is {sb['touchdown_min']:g} m "
             f"({'no contact at any step' if sb['touchdown_min'] >= 170.0 else 'CONTACT'}), and the crest tension {fmt(sb['crest'][1])} kN; the scene therefore has no `[seabed]`.")
    L.append("* MoorDyn's axial damping (BA/-zeta = −0.5) and the two codes' different ramps (quintic smoothstep, ½(1 − cos)) act mostly on the start: "
             f"the largest pointwise difference, {fmt(base['maxdiff'][0])} kN, is at t_ref {base['maxdiff'][1]:.1f} s, just after the ramp; "
             f"over the last period (t_ref ≥ {T_WINDOW - T:g} s) it is {fmt(base['maxdiff_last'])} kN.")
    if waves[4] is None:
        L.append("* **Cases 4-6** (waves) are not run: this binary refuses a dynamic run with waves (the water's force with waves "
                 "is not built into it). The paper's values over the last wave period are listed for when it is.\n")
    else:
        errs = [waves[c]["eta_err"] for c, _, _ in WAVE_CASES if waves[c]["eta_err"] is not None]
        L.append("* **The same sea as MoorDyn's.** The elevation riser reports at the phase origin (the hang-off, MoorDyn's (0, 0)) "
                 f"equals A cos(φ − ωt) at every step in the three cases (largest difference {max(errs):.1e} m): MoorDyn's sea at MoorDyn's time "
                 f"(the test's `wave()`, no ramp); the paper's t = riser's t − {T_START_W:g} s. MoorDyn's k = ω²/9.81 = 0.040243 rad/m against "
                 "riser's 0.040281 (ω² = gk tanh kd, g 9.807, d 100 m): 0.2° of phase at the anchor.")
        L.append(f"* **MoorDyn's axial damping.** line.txt's BA/-zeta = −0.5 is BA = {BA_MD:.0f} N s (MoorDyn logs it), a Kelvin–Voigt "
                 f"stress BA ε̇ on the axial strain: riser's `structural_damping` η = BA/EA = {ETA_MD:.3g} s (which also damps bending and torsion, "
                 "by ηω/2 = 2e-4 at the wave's frequency). The abrupt start rings the line's axial modes (10.6 Hz the strongest): MoorDyn's BA damps "
                 "that one by ηω/2 = 2.4 % (a decay time of 0.6 s); "
                 "without it riser leaves them to ρ∞ = 0.8, which damps them at dt 0.05 s and hardly at 0.0125 s, and its answer depends on the step "
                 "(the table above).")
        if 5 in mdres:
            b, m = waves[5], mdres[5]
            L.append(f"* **Case 5 at t_ref {T13:g} s.** The digitised curve rises {REF5_JUMP:.2f} kN between t_ref 1.2 and 1.3 s, its neighbours "
                     f"0.15 and 0.48 kN apart: MoorDyn is {m['at'][T13]:+.3f} kN from it there, riser {b['at'][T13]:+.3f} kN "
                     f"({wvar['case5_dt025'][1]['at'][T13]:+.3f} and {wvar['case5_dt0125'][1]['at'][T13]:+.3f} kN at dt 0.025 and 0.0125 s). "
                     f"riser is {b['at'][T13] - m['at'][T13]:+.3f} kN from MoorDyn there: MoorDyn passes its own check at this point by "
                     f"{TOL_MOTION - abs(m['at'][T13]):.3f} kN, riser {'passes' if abs(b['at'][T13]) <= TOL_MOTION else 'fails'} it by "
                     f"{abs(TOL_MOTION - abs(b['at'][T13])):.3f} kN at the scene's dt. The acceptance (MoorDyn's 1 kN) is kept.")
        L.append("")
    L.append("## Commands\n")
    L.append("```sh")
    L.append("riser-tools lowe-langley     # this page; the runs in out/lowe_langley/")
    for c, wall, rc in log:
        if "--help" in c:
            continue
        L.append(f"{'# ' if c.startswith('MoorDyn') else ''}{c}    # {wall:.2f} s")
    L.append("```")
    doc = os.path.join(ROOT, args.doc)
    with open(doc, "w") as f:
        f.write("\n".join(L) + "\n")
    print("\n".join(L))
    print(f"\nwrote {doc} ({total:.1f} s)", file=sys.stderr)


if __name__ == "__main__":
    main()
