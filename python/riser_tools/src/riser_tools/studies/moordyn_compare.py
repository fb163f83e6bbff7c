#!/usr/bin/env python3
"""Side-by-side comparison of riser with the peer code MoorDyn v2 (Python
package `moordyn`, MoorDyn-C) on riser's built-in `catenary` scene.

The case: 100 m line, 226.7 kg/m, D 0.3172 m, EA 7.96e8 N, EI 5.882e4 N m^2,
Cd 0.6 normal / 0.05 tangential on D, no added mass, hang-off 10 m below the
surface, anchor 60 m across and 70 m below it, uniform current 0.8 m/s along
+x, hang-off heave 2.5 m / 20 s grown over 20 s with ½(1 − cos(πt/20)),
Kelvin–Voigt structural damping η = 2 ms (MoorDyn BA = η·EA), 100 s.

Both codes start from the static state *without* the current (MoorDyn-C
computes its initial condition before it sets up the water kinematics, and
riser's default `static_current = false` does the same), and the current
acts in full from t = 0 in both (riser's `current_ramp = 0`: by default it
grows over 10 s, docs/theory.md §5.11).

What it measures (top tension = magnitude of the force at the hang-off):
1. Agreement of the two converged runs over t in [40, 100] s.
2. Work-precision of each code against its OWN converged reference:
   error = max |T − T_ref| / max T_ref over t in [40, 100] s, against the wall
   time of the time stepping alone (riser: `solve_wall_time`; MoorDyn: the
   Python loop of `moordyn.Step` calls, Create/Init excluded, also reported
   with the measured cost of the Python call itself subtracted).
   MoorDyn is explicit: for each segment count and time scheme the script
   finds the largest stable dtM (of the form 0.01 s / k) and also runs
   smaller ones.
3. The wall-time ratio at matched accuracy (1e-2, 1e-3, 1e-4).

MoorDyn is driven one internal step per `Step` call (coupling step = dtM):
MoorDyn moves a coupled point linearly over a coupling step, so a coarser
coupling step adds a saw-tooth error of order BA·a·dt/(2 l) to the tension.
Three side checks are run and reported: that coupling-step error (one call
per 0.01 s against one per dtM), the insensitivity of the comparison window
to MoorDyn's initial-condition solver, and MoorDyn's stable dtM without the
structural damping.

The script pins itself (and the riser processes it starts) to one CPU and
sets the usual thread-count variables to 1. The full run takes about 6 min
on the 2-core project machine.

Outputs: OUT/runs.csv (every run, including the unstable dtM probes),
OUT/reference_timeseries.csv, DOCS/figures/moordyn_compare.png and
DOCS/moordyn.md.

Usage (`make moordyn`):
    riser-tools moordyn --bin target/release/riser --out out/moordyn --docs docs
    riser-tools moordyn --quick ...     (a few cells, a smoke run)
Needs numpy, matplotlib and moordyn (requirements.txt). MoorDyn is driven by
riser_tools.moordyn, riser by riser_tools.cli.
"""

import csv
import datetime
import math
import os
import platform
import statistics
import sys
import time
from importlib import metadata

from ..report import PeerStudy, peer_study_main, single_threaded

single_threaded()   # before any numerical library is loaded

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .. import cli, moordyn  # noqa: E402
from ..cases import CATENARY, Motion  # noqa: E402
from ..series import window_stats as _window_stats  # noqa: E402

# ----------------------------------------------------------------------------- the case
LINE = CATENARY          # 100 m, 226.7 kg/m, D 0.3172 m, EA 7.96e8 N, EI 5.882e4 N m^2, Cd 0.6 / 0.05
LENGTH, MASS, EA = LINE.length, LINE.mass, LINE.ea
CD_AX = moordyn.cd_axial(LINE)   # MoorDyn: CdAx is on the surface pi*D
ETA = 0.002              # s, Kelvin-Voigt structural damping
BA = ETA * EA            # N s, MoorDyn's internal damping
CURRENT = 0.8            # m/s along +x, uniform
WATER_DEPTH = 200.0      # deeper than the anchor: no seabed contact
AMPLITUDE, PERIOD, RAMP = 2.5, 20.0, 20.0
DURATION = 100.0
WINDOW = 40.0            # errors over the last three periods, t in [40, 100]
MOTION = Motion(AMPLITUDE, PERIOD, ramp=RAMP, duration=DURATION, window=WINDOW)
SAMPLE = 0.01            # s, output grid of the references and of MoorDyn
WAVE_SPEED = LINE.wave_speed
LEVELS = (1e-2, 1e-3, 1e-4)
CHEAP = 3.0              # s: runs cheaper than this are timed 3 times (median)
MAX_VALID_ERROR = 0.05   # a MoorDyn run further than this from its reference is "unstable"
K_CANDIDATES = [1, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 25, 30, 40, 50, 60, 75, 80, 100, 120, 150,
                200, 250, 300, 400, 500, 600, 800, 1000]   # dtM = 0.01 s / k
TITLE = "riser catenary scene: comparison with riser (riser_tools.studies.moordyn_compare)"


def support_tension(run, nseg):
    """MoorDyn's end force with its end node's inertia added back (riser_tools.moordyn.support_force)."""
    return moordyn.support_force(run["run"], LINE, nseg)


def relative_error(t, tension, t_ref, tension_ref):
    """max |T - T_ref| / max T_ref over t >= WINDOW, at the run's own output times."""
    m = t >= WINDOW - 1e-9
    mr = t_ref >= WINDOW - 1e-9
    ref = np.interp(t[m], t_ref, tension_ref)
    return float(np.max(np.abs(tension[m] - ref)) / np.max(tension_ref[mr]))


def window_stats(t, tension):
    return _window_stats(t, tension, WINDOW)


# ----------------------------------------------------------------------------- riser
def riser_run(bin_, out_dir, n, dt, tol=None, repeats=1, model="rod"):
    """`riser run catenary` with the line `model` (rod or cable): the time series and the
    median solve time."""
    sets = {"model": model, "n_elements": n, "time_step": dt, "structural_damping": ETA, "current_ramp": 0}
    if tol is not None:
        sets["newton_tolerance"] = tol
    r = cli.run(bin_, "catenary", sets, MOTION, DURATION, out_dir, repeats=repeats, cheap=CHEAP)
    return {"t": r.t, "T": r.top_tension, "walls": r.walls, "wall": r.wall, "summary": r.summary,
            "cmd": " ".join(r.cmd)}


# ----------------------------------------------------------------------------- MoorDyn
def segment_length(nseg):
    return LENGTH / nseg


def damping_dt(nseg):
    """m l^2 / (2 BA): the explicit-integration limit set by the axial damping."""
    return moordyn.damping_dt(LINE, nseg, BA)


def wave_dt(nseg):
    """l / c: the limit set by the axial waves."""
    return moordyn.wave_dt(LINE, nseg)


def k_at_most(dt):
    """Smallest k of K_CANDIDATES with 0.01/k <= dt."""
    for k in K_CANDIDATES:
        if SAMPLE / k <= dt:
            return k
    return K_CANDIDATES[-1]


def write_moordyn_input(path, nseg, dtm, options, ba=BA):
    """The catenary as a MoorDyn v2 input file, with the uniform current beside it."""
    moordyn.write_input(path, LINE, nseg, dtm, {**moordyn.NO_OUTPUT, **options}, ba=ba, depth=WATER_DEPTH,
                        current=CURRENT, title=TITLE)


def moordyn_ic(work, nseg):
    """Static state (no current) by MoorDyn's dynamic relaxation, once per segment count,
    at a conservative dtM; saved with SaveState and loaded by every run of that mesh."""
    k = k_at_most(min(0.8 * damping_dt(nseg), 0.5 * wave_dt(nseg)))
    while True:
        d = work / f"ic_{nseg}"
        inp = d / "ic.txt"
        write_moordyn_input(inp, nseg, SAMPLE / k, {
            "ICgenDynamic": 1, "CdScaleIC": 20, "threshIC": 1e-5, "dtIC": 1.0, "TmaxIC": 300})
        try:
            st = moordyn.static_state(inp, LINE, nseg, save=d / f"state_{nseg}.ic")
            if math.isfinite(st.tension) and 0.5e5 < st.tension < 3e5:
                return {"state": st.state, "T0": st.tension, "F0": st.force, "dtm_ic": SAMPLE / k,
                        "ic_time": st.seconds}
        except RuntimeError:
            pass
        if k >= K_CANDIDATES[-1]:
            raise RuntimeError(f"MoorDyn initial condition failed for {nseg} segments")
        k = K_CANDIDATES[K_CANDIDATES.index(k) + 1]


def moordyn_run(work, nseg, k, scheme, ic, repeats=1, coupling=1, tag="", ba=BA):
    """One MoorDyn run with dtM = 0.01/k and `coupling` internal steps per `Step` call
    (1: one call per step); the tension every 0.01 s (NaN after a failure) and the loop
    wall times. `ic`: a state from moordyn_ic (loaded with LoadState), or None for MoorDyn's
    own initial-condition solver with its default options."""
    dtm = SAMPLE / k
    inp = work / f"run_{nseg}_{scheme}_{k}{tag}" / "lines.txt"
    write_moordyn_input(inp, nseg, dtm, {"tScheme": scheme}, ba=ba)
    r = moordyn.run(inp, LINE, nseg, MOTION, DURATION, dtm, SAMPLE, coupling=coupling,
                    state=ic["state"] if ic else None, T0=ic["T0"] if ic else float("nan"),
                    repeats=repeats, cheap=CHEAP, probe_overhead=True)
    return {"t": r.t, "T": r.T, "F": r.F, "ok": r.ok, "walls": r.walls, "wall": r.wall, "per_call": r.per_call,
            "steps": r.steps, "overhead": r.overhead, "dtm": dtm, "T0": r.T0, "run": r}


# ----------------------------------------------------------------------------- the study
class Study(PeerStudy):
    def __init__(self, args):
        super().__init__(args)
        self.rows = []
        self.ics = {}
        self.series = {}
        self.side = {}

    # riser -------------------------------------------------------------------------
    def riser_reference(self):
        n, dt, tol = self.cfg["riser_ref"]
        self.log(f"riser reference: {n} elements, dt {dt} s, tolerance {tol:g}")
        r = riser_run(self.args.bin, self.work / f"riser_ref_{n}_{dt}", n, dt, tol, repeats=1)
        self.riser_ref = r
        self.add_row("riser", "reference", n, dt, "", "ok", 0.0, r, static=r["summary"]["static_top_tension"],
                     extra={"tolerance": tol})

    def riser_grid(self):
        for role, cells in (("grid", self.cfg["riser_grid"]), ("extra", self.cfg["riser_extra"])):
            for n, dt in cells:
                r = riser_run(self.args.bin, self.work / f"riser_{n}_{dt}", n, dt,
                              repeats=self.cfg["repeats"])
                err = relative_error(r["t"], r["T"], self.riser_ref["t"], self.riser_ref["T"])
                self.log(f"riser {n:3d} el dt {dt:<5g}: error {err:.2e}, wall {r['wall']:.3f} s "
                         f"({len(r['walls'])} runs)")
                self.add_row("riser", role, n, dt, "", "ok", err, r, static=r["summary"]["static_top_tension"])

    def riser_cable(self):
        """riser's cable model (no bending, no torsion: a model of MoorDyn's class), its error
        measured against the converged *rod*, a stricter test than against its own reference."""
        for n, dt in self.cfg["cable_grid"]:
            r = riser_run(self.args.bin, self.work / f"cable_{n}_{dt}", n, dt, repeats=self.cfg["repeats"],
                          model="cable")
            err = relative_error(r["t"], r["T"], self.riser_ref["t"], self.riser_ref["T"])
            self.log(f"riser cable {n:3d} seg dt {dt:<5g}: error vs the rod {err:.2e}, wall {r['wall']:.4f} s")
            self.add_row("riser_cable", "cable", n, dt, "", "ok", err, r, static=r["summary"]["static_top_tension"])

    # MoorDyn -----------------------------------------------------------------------
    def ic(self, nseg):
        if nseg not in self.ics:
            ic = moordyn_ic(self.work, nseg)
            self.log(f"MoorDyn static state, {nseg} segments: T0 {ic['T0']:.1f} N "
                     f"(dynamic relaxation at dtM {ic['dtm_ic']:.3g} s, {ic['ic_time']:.1f} s)")
            self.ics[nseg] = ic
        return self.ics[nseg]

    def moordyn_reference(self):
        nseg, k, scheme = self.cfg["md_ref"]
        ic = self.ic(nseg)
        while True:
            self.log(f"MoorDyn reference: {nseg} segments, {scheme}, dtM {SAMPLE / k:.3g} s")
            r = moordyn_run(self.work, nseg, k, scheme, ic)
            if r["ok"] and relative_error(r["t"], r["T"], self.riser_ref["t"], self.riser_ref["T"]) < MAX_VALID_ERROR:
                break
            self.log("  unstable; halving dtM")
            k = K_CANDIDATES[K_CANDIDATES.index(k) + 1]
        self.md_ref = r
        self.md_ref_cfg = (nseg, k, scheme)
        self.add_row("moordyn", "reference", nseg, r["dtm"], scheme, "ok", 0.0, r, static=ic["T0"])

    def moordyn_cell(self, nseg, k, scheme, role):
        ic = self.ic(nseg)
        r = moordyn_run(self.work, nseg, k, scheme, ic, repeats=self.cfg["repeats"])
        self.series[(nseg, scheme, k)] = r
        err = (relative_error(r["t"], r["T"], self.md_ref["t"], self.md_ref["T"])
               if r["ok"] else float("nan"))
        ok = r["ok"] and err < MAX_VALID_ERROR
        status = "ok" if ok else "unstable"
        self.log(f"MoorDyn {nseg:3d} seg {scheme:5s} dtM {r['dtm']:.3g}: {status}, "
                 f"error {err:.2e}, loop {r['wall']:.3f} s ({len(r['walls'])} runs)")
        self.add_row("moordyn", role, nseg, r["dtm"], scheme, status, err if r["ok"] else float("nan"), r,
                     static=ic["T0"])
        return ok

    def moordyn_grid(self):
        self.md_limits = {}
        for role, segs in (("grid", self.cfg["md_grid"]), ("extra", self.cfg["md_extra"])):
            for nseg in segs:
                for scheme in self.cfg["md_schemes"]:
                    # the largest stable dtM = 0.01/k, from above the damping / wave estimate down
                    k = k_at_most(min(2.0 * damping_dt(nseg), 1.5 * wave_dt(nseg)))
                    smallest_unstable = None
                    while not self.moordyn_cell(nseg, k, scheme, role):
                        smallest_unstable = k
                        k = K_CANDIDATES[K_CANDIDATES.index(k) + 1]
                    self.md_limits[(nseg, scheme)] = (k, smallest_unstable)
                    smaller = [2] + ([4] if nseg <= 20 else [])
                    for f in smaller[: self.cfg["md_smaller"]]:
                        self.moordyn_cell(nseg, k * f, scheme, role)

    def side_checks(self):
        """Three checks of the MoorDyn set-up (rows with role "check" in runs.csv)."""
        segs = [n for n in self.cfg["md_grid"] if n <= 40]
        # 1. Coupling step: one Step call per 0.01 s (MoorDyn sub-steps inside) against one per dtM.
        n = max(segs)
        k = self.md_limits[(n, "RK2")][0]
        base = self.series[(n, "RK2", k)]
        r = moordyn_run(self.work, n, k, "RK2", self.ic(n), coupling=k, tag="_coupled_0.01")
        self.check_row(n, k, "RK2 coupled every 0.01 s", r)
        dev = float(np.max(np.abs(r["T"][r["t"] >= WINDOW] - base["T"][base["t"] >= WINDOW])))
        self.side["coupling"] = {"n": n, "dtm": SAMPLE / k, "dev": dev, "rel": dev / np.max(base["T"])}
        self.log(f"check: {n} segments coupled every 0.01 s instead of every dtM: up to {dev:.0f} N")
        # 2. Initial state: MoorDyn's default stationary solver instead of the dynamic relaxation.
        n = min(segs[-1], 20)
        k = self.md_limits[(n, "RK2")][0]
        base = self.series[(n, "RK2", k)]
        r = moordyn_run(self.work, n, k, "RK2", None, tag="_stationary_ic")
        self.check_row(n, k, "RK2 from the stationary IC solver", r)
        m = r["t"] >= WINDOW
        dev = float(np.max(np.abs(r["T"][m] - base["T"][m])))
        self.side["ic"] = {"n": n, "dev": dev, "rel": dev / np.max(base["T"]), "T0_stationary": r["T0"],
                           "T0_relaxation": self.ic(n)["T0"]}
        self.log(f"check: {n} segments from the stationary IC solver: T0 {r['T0']:.1f} N against "
                 f"{self.ic(n)['T0']:.1f} N, window differs by {dev:.2g} N")
        # 3. The role of the structural damping: the largest stable RK2 dtM with BA = 0
        #    (binary search over K_CANDIDATES, at 20 segments).
        n = 20 if 20 in segs else max(segs)
        ref = self.series[(n, "RK2", self.md_limits[(n, "RK2")][0])]

        def stable(i):
            r = moordyn_run(self.work, n, K_CANDIDATES[i], "RK2", self.ic(n), tag="_undamped", ba=0.0)
            ok = r["ok"] and relative_error(r["t"], r["T"], ref["t"], ref["T"]) < MAX_VALID_ERROR
            self.check_row(n, K_CANDIDATES[i], "RK2 with BA = 0", r, ok)
            return ok

        lo = K_CANDIDATES.index(self.md_limits[(n, "RK2")][0])   # smallest index tried
        hi = len(K_CANDIDATES) - 1                               # assumed stable
        if stable(lo):
            hi = lo
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if stable(mid):
                hi = mid
            else:
                lo = mid
        k = K_CANDIDATES[hi]
        self.side["undamped"] = {"n": n, "dtm": SAMPLE / k, "dtm_damped": SAMPLE / self.md_limits[(n, "RK2")][0]}
        self.log(f"check: {n} segments without structural damping: largest stable RK2 dtM {SAMPLE / k:.3g} s")

    # bookkeeping ----------------------------------------------------------------------
    def check_row(self, nseg, k, what, r, ok=None):
        ok = r["ok"] if ok is None else ok
        err = relative_error(r["t"], r["T"], self.md_ref["t"], self.md_ref["T"]) if r["ok"] else float("nan")
        self.add_row("moordyn", "check", nseg, SAMPLE / k, what, "ok" if ok else "unstable", err, r,
                     static=r["T0"])

    def add_row(self, code, role, n, dt, scheme, status, err, r, static, extra=None):
        ok = status == "ok"
        mean, lo, hi = window_stats(r["t"], r["T"]) if ok else (float("nan"),) * 3
        row = {
            "code": code, "role": role, "n": n, "dt": dt, "scheme": scheme, "status": status,
            "error": err, "wall": r["wall"], "walls": ";".join(f"{w:.4f}" for w in r["walls"]),
            "python_overhead": r.get("overhead", 0.0),
            "wall_net": r["wall"] - r.get("overhead", 0.0),
            "steps": r.get("steps") or r["summary"]["steps"],
            "newton_per_step": r["summary"]["iterations_per_step"] if code == "riser" else "",
            "static_T0": static, "mean": mean, "min": lo, "max": hi,
        }
        if extra:
            row.update(extra)
        self.rows.append(row)

    def run(self):
        self.t0 = time.perf_counter()
        q = self.args.quick
        self.cfg = {
            "riser_ref": (60, 0.02, 1e-10) if q else (120, 0.01, 1e-10),
            "riser_grid": [(n, dt) for n in ((10, 20) if q else (10, 20, 40, 60))
                           for dt in ((0.1, 0.05) if q else (0.1, 0.05, 0.02))],
            "riser_extra": [] if q else [(4, 0.2), (5, 0.2), (5, 0.1), (10, 0.2)],
            "md_ref": (40, 50, "RK2") if q else (120, 250, "RK2"),
            "md_grid": (10, 20) if q else (10, 20, 40, 60),
            "md_extra": [] if q else [5, 8],
            "md_schemes": ("RK2",) if q else ("RK2", "Euler"),
            "md_smaller": 1 if q else 2,
            "repeats": 1 if q else 3,
            "cable_grid": [(10, 0.1)] if q else [(5, 0.2), (8, 0.2), (10, 0.2), (10, 0.1), (20, 0.1), (40, 0.05)],
        }
        self.load_before = os.getloadavg()
        self.riser_reference()
        self.moordyn_reference()
        self.riser_grid()
        self.riser_cable()
        self.moordyn_grid()
        self.side_checks()
        self.load_after = os.getloadavg()
        self.elapsed = time.perf_counter() - self.t0
        self.write_csv()
        self.write_timeseries()
        self.plot()
        self.write_markdown()
        self.log(f"done in {self.elapsed:.0f} s")

    # outputs -------------------------------------------------------------------------
    def write_csv(self):
        self.out.mkdir(parents=True, exist_ok=True)
        keys = ["code", "role", "n", "dt", "scheme", "status", "error", "wall", "walls", "python_overhead",
                "wall_net", "steps", "newton_per_step", "static_T0", "mean", "min", "max"]
        with open(self.out / "runs.csv", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
            w.writeheader()
            for r in self.rows:
                w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})

    def write_timeseries(self):
        t = self.md_ref["t"]
        riser = np.interp(t, self.riser_ref["t"], self.riser_ref["T"])
        with open(self.out / "reference_timeseries.csv", "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["t", "riser_top_tension", "moordyn_top_tension"])
            for a, b, c in zip(t, riser, self.md_ref["T"]):
                w.writerow([f"{a:.2f}", f"{b:.3f}", f"{c:.3f}"])

    def ok_rows(self, code):
        return [r for r in self.rows if r["code"] == code and r["role"] in ("grid", "extra") and r["status"] == "ok"]

    def cheapest(self, code, level, key, grid_only=False):
        cands = [r for r in self.ok_rows(code) if r["error"] <= level
                 and (r["role"] == "grid" or not grid_only)]
        return min(cands, key=lambda r: r[key]) if cands else None

    def plot(self):
        fig_dir = self.docs / "figures"
        fig_dir.mkdir(parents=True, exist_ok=True)
        fig, axes = plt.subplots(1, 3, figsize=(17, 5))
        t = self.md_ref["t"]
        riser = np.interp(t, self.riser_ref["t"], self.riser_ref["T"])
        rn, rdt, _ = self.cfg["riser_ref"]
        mn, mk, ms = self.md_ref_cfg
        ax = axes[0]
        ax.plot(self.riser_ref["t"], self.riser_ref["T"] / 1e3, lw=1.6, label=f"riser ({rn} el., dt {rdt} s)")
        ax.plot(t, self.md_ref["T"] / 1e3, "--", lw=1.2, label=f"MoorDyn ({mn} seg., {ms}, dtM {SAMPLE / mk:.2g} s)")
        ax.axvspan(WINDOW, DURATION, color="0.93", zorder=0)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("top tension (kN)")
        ax.set_title("Converged runs (shaded: comparison window)")
        ax.legend(loc="lower right", fontsize=8)
        ax = axes[1]
        ax.plot(t, (self.md_ref["T"] - riser), lw=1.0, label="MoorDyn's returned force")
        ax.plot(t, (support_tension(self.md_ref, mn) - riser), lw=1.0,
                label="with its end node's inertia added back")
        ax.axvspan(WINDOW, DURATION, color="0.93", zorder=0)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("MoorDyn − riser (N)")
        ax.set_title("Difference of the converged runs")
        ax.legend(loc="lower right", fontsize=8)
        m = t >= WINDOW
        span = np.max(np.abs(self.md_ref["T"][m] - riser[m]))
        ax.set_ylim(-4 * span, 4 * span)
        ax = axes[2]
        markers = {0.2: "v", 0.1: "o", 0.05: "s", 0.02: "D"}
        for n in sorted({r["n"] for r in self.ok_rows("riser")}):
            rs = sorted([r for r in self.ok_rows("riser") if r["n"] == n], key=lambda r: r["wall"])
            ax.plot([r["wall"] for r in rs], [max(r["error"], 1e-8) for r in rs], "-", color="C0", alpha=0.4)
            for r in rs:
                ax.plot(r["wall"], max(r["error"], 1e-8), markers.get(r["dt"], "o"), color="C0", ms=6)
                ax.annotate(f"{n}", (r["wall"], max(r["error"], 1e-8)), fontsize=6, xytext=(3, 3),
                            textcoords="offset points", color="C0")
        colours = {"RK2": "C1", "Euler": "C3"}
        for scheme in self.cfg["md_schemes"]:
            rs = [r for r in self.ok_rows("moordyn") if r["scheme"] == scheme]
            limit = [r for r in rs if self.md_limits.get((r["n"], scheme), (None,))[0] == round(SAMPLE / r["dt"])]
            limit.sort(key=lambda r: r["n"])
            ax.plot([r["wall_net"] for r in limit], [r["error"] for r in limit], "-", color=colours[scheme],
                    label=f"MoorDyn {scheme}, largest stable dtM")
            ax.plot([r["wall_net"] for r in rs], [r["error"] for r in rs], "x", color=colours[scheme], ms=6)
            for r in limit:
                ax.annotate(f"{r['n']}", (r["wall_net"], r["error"]), fontsize=6, xytext=(3, -9),
                            textcoords="offset points", color=colours[scheme])
        for dt, mk_ in markers.items():
            ax.plot([], [], mk_, color="C0", label=f"riser dt {dt} s")
        for lv in LEVELS:
            ax.axhline(lv, color="0.7", lw=0.8, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time of the time stepping (s), one core")
        ax.set_ylabel("max |T − T_ref| / max T_ref, t in [40, 100] s")
        ax.set_title("Work-precision, each code against its own reference\n(labels: elements / segments; "
                     "MoorDyn: Python-call cost removed)", fontsize=9)
        ax.legend(fontsize=7, loc="upper right")
        fig.tight_layout()
        self.figure = fig_dir / "moordyn_compare.png"
        fig.savefig(self.figure, dpi=130)
        plt.close(fig)

    def write_markdown(self):
        a = self.args
        rr, mr = self.riser_ref, self.md_ref
        rn, rdt, rtol = self.cfg["riser_ref"]
        mn, mk, ms = self.md_ref_cfg
        t = mr["t"]
        riser_on_grid = np.interp(t, rr["t"], rr["T"])
        m = t >= WINDOW - 1e-9
        diff = mr["T"][m] - riser_on_grid[m]
        r_mean, r_min, r_max = window_stats(rr["t"], rr["T"])
        m_mean, m_min, m_max = window_stats(t, mr["T"])
        r_static = rr["summary"]["static_top_tension"]
        m_static = self.ics[mn]["T0"]
        md_version = metadata.version("moordyn")
        cp, ic_chk, ud = self.side["coupling"], self.side["ic"], self.side["undamped"]
        riser_version = cli.version(a.bin)
        L = []
        w = L.append
        if a.quick:
            w("> **Quick smoke run (`--quick`): coarse references and a few cells only; not the study.**\n")
        w("# riser and MoorDyn on the catenary scene\n")
        w(f"Generated by `riser-tools moordyn` (riser_tools.studies.moordyn_compare) on {datetime.date.today()} "
          f"({riser_version}, MoorDyn {md_version} from PyPI `moordyn=={md_version}`, "
          f"Python {platform.python_version()}, numpy {np.__version__}).\n")
        w("## The case\n")
        w("riser's built-in `catenary` scene, written as a MoorDyn v2 input file "
          "(riser's frame has the hang-off at the origin and the surface at z = +10 m; "
          "MoorDyn's surface is z = 0):\n")
        w("| quantity | riser | MoorDyn v2 |")
        w("|---|---|---|")
        w("| line | 100 m, 226.7 kg/m, D 0.3172 m | `LINE TYPES`: Diam 0.3172, MassDen 226.7 |")
        w("| axial / bending stiffness | EA 7.96e8 N, EI 5.882e4 N m² | EA 7.96e8, EI 5.882e4 |")
        w(f"| structural damping | Kelvin–Voigt η = 2 ms (`structural_damping=0.002`) | BA = η·EA = {BA:.4g} N s |")
        w(f"| drag | C_Dn 0.6 and C_Dt 0.05, both on D | Cd 0.6 (on D), CdAx = 0.05/π = {CD_AX:.5f} (on πD) |")
        w("| added mass | C_a 0 | Ca 0, CaAx 0 |")
        w("| hang-off | prescribed heave (pinned) | `Coupled` point at (0, 0, −10) |")
        w("| anchor | (60, 0, −70) pinned | `Fixed` point at (60, 0, −80); WtrDpth 200 m (no seabed contact) |")
        w("| water | ρ 1025, g 9.81, uniform current 0.8 m/s along +x | rho 1025, g 9.81, `Currents 1` "
          "(uniform `current_profile.txt`) |")
        w("| motion | `--heave 2.5,20 --ramp 20 --duration 100` | same z(t) fed to `moordyn.Step` |\n")
        w("**Current and static state.** MoorDyn-C (2.7) computes its initial condition before it "
          "sets up the water kinematics: its log prints *Water kinematics for IC gen: No Waves or "
          "Currents* and only then reads `current_profile.txt` *for runtime*. Its static state "
          "therefore excludes the current, as riser's does by default (`static_current = false`, the "
          "paper). Both runs start from the still-water static state and the current acts in full "
          "from t = 0 (riser's `current_ramp = 0`); `static_current` is left at its default. (The "
          "start transient has died out long before "
          f"the comparison window: at {ic_chk['n']} segments, a MoorDyn run from its default "
          f"stationary IC solver (T0 {ic_chk['T0_stationary'] / 1e3:.3f} kN) and one from the "
          f"dynamic relaxation used here (T0 {ic_chk['T0_relaxation'] / 1e3:.3f} kN) differ by "
          f"{ic_chk['rel']:.1e} of the tension over t ≥ {WINDOW:g} s.)\n")
        w("**Driving MoorDyn.** The fairlead is a `Coupled` point. MoorDyn moves a coupled point "
          "linearly over each `Step` call (x + v·(t − t_start)), so the script calls `moordyn.Step` "
          "once per internal step (coupling step = dtM) with the exact position at the start of the "
          "step and the secant velocity (z(t + dtM) − z(t))/dtM, which lands the point exactly on "
          f"z(t + dtM). A coarser coupling step is not free: at {cp['n']} segments a 0.01 s coupling "
          f"step moved the tension by up to {cp['dev']:.0f} N ({cp['rel']:.1e}) against one call per "
          f"dtM = {cp['dtm']:.2g} s, a saw-tooth of order BA·a·Δt/(2l) from the piecewise-constant "
          "fairlead velocity. The tension is the magnitude of "
          "the force `Step` returns (the net force of the line's end node on the coupled point, "
          "weight and buoyancy as distributed loads, so an effective tension like riser's "
          "`top_tension`). The static state comes from MoorDyn's legacy dynamic relaxation "
          "(`ICgenDynamic 1`, CdScaleIC 20, threshIC 1e-5), computed once per mesh at a "
          "conservative dtM and loaded into every run of that mesh with `SaveState`/`LoadState`, "
          "so the dtM search below is not limited by the initial-condition solver (which can fail "
          "at a dtM where the dynamics still run).\n")
        w("## 1. Agreement of the converged runs\n")
        w(f"riser: {rn} elements, dt {rdt} s, Newton tolerance {rtol:g}. MoorDyn: {mn} segments, "
          f"{ms}, dtM {SAMPLE / mk:.3g} s. Over t in [{WINDOW:g}, {DURATION:g}] s, at 0.01 s:\n")
        w("| | riser | MoorDyn | MoorDyn − riser |")
        w("|---|---|---|---|")
        w(f"| static top tension, t = 0 (kN) | {r_static / 1e3:.3f} | {m_static / 1e3:.3f} | "
          f"{(m_static - r_static):+.0f} N ({(m_static - r_static) / r_static:+.1e}) |")
        w(f"| mean (kN) | {r_mean / 1e3:.3f} | {m_mean / 1e3:.3f} | {(m_mean - r_mean):+.1f} N |")
        w(f"| min (kN) | {r_min / 1e3:.3f} | {m_min / 1e3:.3f} | {(m_min - r_min):+.1f} N |")
        w(f"| max (kN) | {r_max / 1e3:.3f} | {m_max / 1e3:.3f} | {(m_max - r_max):+.1f} N |")
        w(f"| max \\|T_MoorDyn − T_riser\\| / max T_riser | | | **{np.max(np.abs(diff)) / r_max:.2e}** "
          f"({np.max(np.abs(diff)):.0f} N) |")
        w(f"| mean of T_MoorDyn − T_riser | | | {np.mean(diff):+.1f} N |\n")
        corr = support_tension(mr, mn)[m] - riser_on_grid[m]
        self.agreement = {"max_rel": float(np.max(np.abs(diff)) / r_max),
                          "max_rel_corrected": float(np.max(np.abs(corr)) / r_max)}
        w("Part of the remaining difference is a sinusoid at the heave period (figure, middle): "
          "MoorDyn's `Step` returns the force of the line on the coupled point, without the inertia "
          "of the driven end node (half a segment, "
          f"{0.5 * MASS * segment_length(mn):.0f} kg at {mn} segments), which riser's hang-off "
          "reaction contains. Adding it back, |F − M_end·a| with a the hang-off acceleration, the "
          f"largest difference drops from {np.max(np.abs(diff)):.0f} N to {np.max(np.abs(corr)):.0f} N "
          f"(**{np.max(np.abs(corr)) / r_max:.1e}**); mean {np.mean(corr):+.1f} N, min "
          f"{np.min(support_tension(mr, mn)[m]) - r_min:+.1f} N, max "
          f"{np.max(support_tension(mr, mn)[m]) - r_max:+.1f} N. That term shrinks like 1/N and is "
          "part of MoorDyn's discretisation, so the work-precision below uses the returned force "
          "as it is.\n")
        w(f"![riser and MoorDyn](figures/{self.figure.name})\n")
        # convergence of MoorDyn toward riser
        w("How MoorDyn's window statistics approach riser's converged values as its mesh is "
          "refined (largest stable RK2 dtM; returned force):\n")
        w("| MoorDyn segments | mean − riser (N) | min − riser (N) | max − riser (N) | static T0 − riser (N) |")
        w("|---|---|---|---|---|")
        lim_rows = [r for r in self.ok_rows("moordyn") if r["scheme"] == "RK2"
                    and self.md_limits.get((r["n"], "RK2"), (None,))[0] == round(SAMPLE / r["dt"])]
        for r in sorted(lim_rows, key=lambda r: r["n"]) + [
                {"n": mn, "mean": m_mean, "min": m_min, "max": m_max, "static_T0": m_static}]:
            w(f"| {r['n']} | {r['mean'] - r_mean:+.1f} | {r['min'] - r_min:+.1f} | {r['max'] - r_max:+.1f} | "
              f"{r['static_T0'] - r_static:+.0f} |")
        w("")
        w("### Modelling differences that remain\n")
        w("* **Lumped masses.** MoorDyn is a lumped-mass model: N straight segments, point masses "
          "and all loads at the N+1 nodes, the end nodes carrying half a segment. riser uses "
          "cubic Hermite rod elements with a consistent mass and consistent loads. Against its own "
          "reference MoorDyn's error falls "
          + (f"like N^{self.md_order():.1f}" if math.isfinite(self.md_order()) else "with N")
          + " (section 2); riser's "
          f"10-element run at dt 0.1 s is within {self.riser_err(10, 0.1):.0e} of its converged "
          "result.\n")
        w("* **End force.** MoorDyn returns the net force of the line on the coupled point: the "
          "end segment's tension plus the end node's half-segment weight, buoyancy and drag, but not "
          "that node's inertia (the point is driven). riser's `top_tension` is the reaction of the "
          "discrete equations at the hang-off, inertia of the end element included. The difference, "
          "half a segment's mass times the heave acceleration (≤ 0.25 m/s²), is about "
          f"{0.5 * MASS * LENGTH / mn * AMPLITUDE * (2 * math.pi / PERIOD) ** 2:.0f} N at {mn} segments "
          "and vanishes with refinement (section 1).\n")
        w("* **Drag.** Both use Morison drag on the relative velocity split into normal and "
          "tangential parts, per unit stretched length. MoorDyn's tangential coefficient CdAx "
          "refers to the wetted surface πD, riser's C_Dt to D, hence CdAx = 0.05/π. MoorDyn "
          "evaluates drag at the nodes with a node tangent averaged from the two adjacent "
          "segments; riser integrates it along the element (midpoint in time).\n")
        w("* **Bending.** MoorDyn has no rotational degrees of freedom: it computes a curvature at "
          "each internal node from the directions of the two adjacent segments and turns the bending "
          "moment EI·κ into transverse node forces; line ends attached to points are moment-free. "
          "riser is a Cosserat rod with directors (bending, twist and shear), pinned at both ends. "
          "With EI = 5.9e4 N m² and 40–140 kN of tension the bending length √(EI/T) is under 1.2 m, "
          "so bending matters only in short boundary layers at the ends, which coarse MoorDyn meshes "
          "do not resolve.\n")
        w("* **Damping.** riser's η acts on all material strains (axial, shear, bending, twist); "
          "MoorDyn's BA only on the axial strain rate. At the slow transverse motion this is "
          "negligible (damping ratio ηω/2 ≈ 3e-4).\n")
        w("* **Initial state.** MoorDyn's static state comes from dynamic relaxation (or its newer "
          "stationary solver) stopped at a threshold; riser's from Newton on the static equations "
          "to 1e-8. MoorDyn's t = 0 tension therefore carries the IC solver's residual (at "
          f"{ic_chk['n']} segments its two IC solvers differ by "
          f"{abs(ic_chk['T0_stationary'] - ic_chk['T0_relaxation']):.0f} N), which is why the static "
          "column above converges less cleanly. It does not reach the comparison window.\n")
        w("* **Time integration.** MoorDyn integrates explicitly (RK2 by default, Euler below); riser "
          "uses an implicit energy–momentum midpoint scheme with Newton. In MoorDyn-C the coupled "
          "point's force comes from the last force evaluation inside the step (RK2: its mid-step "
          "stage; Euler: the start of the step), a lag of at most one dtM (≤ 5 ms here).\n")
        # work-precision
        w("## 2. Work-precision, each code against its own reference\n")
        w("Error = max |T − T_ref| / max T_ref over t in [40, 100] s at the run's output times "
          "(riser: every dt; MoorDyn: every 0.01 s). Wall time: the time stepping only, one core, "
          f"median of 3 runs when a run takes under {CHEAP:g} s. riser: `solve_wall_time` from "
          "`--json`. MoorDyn: the Python loop of `moordyn.Step` calls (Create, Init and LoadState "
          "excluded); *net* subtracts the cost of the Python call itself, measured per run by the "
          "same calls with dt = 0 (about "
          f"{statistics.median([r['python_overhead'] / r['steps'] * 1e6 for r in self.ok_rows('moordyn')]):.1f} "
          "µs per call). The ratios below use the net time, which favours MoorDyn.\n")
        w(f"### riser (reference: {rn} elements, dt {rdt} s, tolerance {rtol:g})\n")
        rgrid = self.ok_rows("riser")
        dts = sorted({r["dt"] for r in rgrid}, reverse=True)
        w("| elements | " + " | ".join(f"dt {d:g} s: error / wall (s)" for d in dts) + " |")
        w("|---|" + "---|" * len(dts))
        for n in sorted({r["n"] for r in rgrid}):
            cells = []
            for d in dts:
                rs = [r for r in rgrid if r["n"] == n and r["dt"] == d]
                cells.append(f"{rs[0]['error']:.2e} / {rs[0]['wall']:.3f}" if rs else "")
            tag = "" if any(r["role"] == "grid" for r in rgrid if r["n"] == n) else " (extra)"
            w(f"| {n}{tag} | " + " | ".join(cells) + " |")
        w("")
        if self.cfg["riser_extra"]:
            w("Extra cells, outside the requested grid (10–60 elements × dt 0.02–0.1 s): "
              + ", ".join(f"{n} el. / dt {dt:g} s" for n, dt in self.cfg["riser_extra"])
              + ". They measure the coarse end of riser's curve instead of assuming it.\n")
        w(f"### MoorDyn (reference: {mn} segments, {ms}, dtM {SAMPLE / mk:.3g} s)\n")
        w("MoorDyn is explicit. Two estimates bound its dtM: the axial-wave time l/c (c = √(EA/m) = "
          f"{WAVE_SPEED:.0f} m/s) and the damping time m·l²/(2·BA), which falls with l² and is the "
          f"smaller one once l < 2ηc = {2 * ETA * WAVE_SPEED:.1f} m (more than "
          f"{LENGTH / (2 * ETA * WAVE_SPEED):.0f} segments): at 40 segments {damping_dt(40):.2g} s "
          f"against {wave_dt(40):.2g} s. For each mesh and scheme the script tries dtM = 0.01 s/k from above "
          "these estimates downward; a run counts as unstable when it aborts, blows up or ends more "
          f"than {MAX_VALID_ERROR:g} from the reference. Euler (one force evaluation per step, RK2 has two) is "
          "included as a cheaper alternative to the default RK2."
          + (" Meshes of " + " and ".join(str(n) for n in self.cfg["md_extra"])
             + " segments are extra, outside the requested 10–60, for the coarse end of its curve."
             if self.cfg["md_extra"] else "") + "\n")
        w("| segments | scheme | largest stable dtM (s) | smallest unstable dtM tried (s) | dtM (s) | error | "
          "loop wall (s) | net wall (s) |")
        w("|---|---|---|---|---|---|---|---|")
        for nseg in sorted({r["n"] for r in self.ok_rows("moordyn")}):
            for scheme in self.cfg["md_schemes"]:
                if (nseg, scheme) not in self.md_limits:
                    continue
                k_ok, k_bad = self.md_limits[(nseg, scheme)]
                rs = sorted([r for r in self.ok_rows("moordyn") if r["n"] == nseg and r["scheme"] == scheme],
                            key=lambda r: -r["dt"])
                for i, r in enumerate(rs):
                    head = (f"| {nseg} | {scheme} | {SAMPLE / k_ok:.3g} | "
                            f"{(f'{SAMPLE / k_bad:.3g}' if k_bad else '—')} |") if i == 0 else "| | | | |"
                    w(f"{head} {r['dt']:.3g} | {r['error']:.2e} | {r['wall']:.3f} | {r['wall_net']:.3f} |")
        w("")
        # matched accuracy
        w("## 3. Wall time at matched accuracy\n")
        w("The cheapest setting of each code whose error (against its own reference) is at most "
          "the level. Ratio = MoorDyn net wall / riser wall (raw MoorDyn loop time in brackets).\n")
        w("| error level | riser setting | riser wall (s) | MoorDyn setting | MoorDyn net wall (s) | ratio |")
        w("|---|---|---|---|---|---|")
        self.ratios = {}
        for lv in LEVELS:
            rb = self.cheapest("riser", lv, "wall")
            mb = self.cheapest("moordyn", lv, "wall_net")
            r_set = (f"{rb['n']} el., dt {rb['dt']:g} s (error {rb['error']:.1e})"
                     + (", extra cell" if rb["role"] == "extra" else "")) if rb else "not reached"
            r_wall = f"{rb['wall']:.3f}" if rb else "—"
            m_set = (f"{mb['n']} seg., {mb['scheme']}, dtM {mb['dt']:.3g} s (error {mb['error']:.1e})"
                     + (", extra cell" if mb["role"] == "extra" else "")) if mb else "not reached in the grid"
            m_wall = f"{mb['wall_net']:.3f}" if mb else "—"
            ratio = "—"
            if rb and mb:
                self.ratios[lv] = mb["wall_net"] / rb["wall"]
                ratio = f"**{self.ratios[lv]:.1f}×** ({mb['wall'] / rb['wall']:.1f}×)"
            w(f"| {lv:.0e} | {r_set} | {r_wall} | {m_set} | {m_wall} | {ratio} |")
        w("")
        self.extrapolation_note(w)
        if self.cfg["riser_extra"] or self.cfg["md_extra"]:
            w("The same with both codes restricted to the requested grids (riser 10–60 elements × "
              "dt 0.02–0.1 s, MoorDyn 10–60 segments):\n")
            w("| error level | riser setting | riser wall (s) | MoorDyn setting | MoorDyn net wall (s) | ratio |")
            w("|---|---|---|---|---|---|")
            for lv in LEVELS:
                rb = self.cheapest("riser", lv, "wall", grid_only=True)
                mb = self.cheapest("moordyn", lv, "wall_net", grid_only=True)
                r_set = f"{rb['n']} el., dt {rb['dt']:g} s" if rb else "not reached"
                m_set = f"{mb['n']} seg., {mb['scheme']}, dtM {mb['dt']:.3g} s" if mb else "not reached"
                ratio = f"{mb['wall_net'] / rb['wall']:.1f}×" if rb and mb else "—"
                r_wall = f"{rb['wall']:.3f}" if rb else "—"
                m_wall = f"{mb['wall_net']:.3f}" if mb else "—"
                w(f"| {lv:.0e} | {r_set} | {r_wall} | {m_set} | {m_wall} | {ratio} |")
            w("")
        # riser's cable model
        cables = [r for r in self.rows if r["code"] == "riser_cable"]
        if cables:
            w("## riser's cable model\n")
            w("`model = cable` (no bending, no torsion, position-only nodes: a model of MoorDyn's class, with "
              "riser's implicit energy–momentum step). Its error is measured against the converged *rod* "
              "above, which includes what the cable leaves out (1.3e-3 on this case when converged): a "
              "stricter measure than MoorDyn's against its own reference. A coarse cable can land below that "
              "converged 1.3e-3 where its discretisation error has the opposite sign (20 segments here): read "
              "such cells as luck, and the rod above as the reliable way to 1e-3.\n")
            w("| segments | dt (s) | error vs the converged rod | wall (s) |")
            w("|---|---|---|---|")
            for r in cables:
                w(f"| {r['n']} | {r['dt']:g} | {r['error']:.1e} | {r['wall']:.4f} |")
            w("")
            w("| error level | riser cable | wall (s) | MoorDyn (own reference) | MoorDyn net wall (s) | ratio |")
            w("|---|---|---|---|---|---|")
            for lv in LEVELS:
                ok = [r for r in cables if r["error"] <= lv]
                cb = min(ok, key=lambda r: r["wall"]) if ok else None
                mb = self.cheapest("moordyn", lv, "wall_net")
                c_set = f"{cb['n']} seg., dt {cb['dt']:g} s (error {cb['error']:.1e})" if cb else "not reached"
                m_set = f"{mb['n']} seg., {mb['scheme']}, dtM {mb['dt']:.3g} s (error {mb['error']:.1e})" \
                    if mb else "not reached"
                ratio = f"**{mb['wall_net'] / cb['wall']:.1f}×**" if cb and mb else "—"
                w(f"| {lv:.0e} | {c_set} | {cb['wall']:.4f} | {m_set} | "
                  f"{mb['wall_net']:.3f} | {ratio} |" if cb and mb else f"| {lv:.0e} | {c_set} | — | {m_set} | — | — |")
            w("")
        # caveats
        w("## Caveats\n")
        w("* Each code is measured against its own converged run, so the ratios compare the cost of "
          "converging each model, not of matching the other code. The two converged runs agree to "
          f"{self.agreement['max_rel']:.1e} ({self.agreement['max_rel_corrected']:.1e} with MoorDyn's "
          "end-node inertia added back; section 1).\n")
        w("* MoorDyn's time step is limited by stability, not accuracy: halving dtM from the largest "
          f"stable one changed the error by {self.halving_text()} (table above), so the way to a "
          "smaller error is more segments, and with the damping-bound dtM ∝ l² a run's cost "
          + (f"grows like N^{self.md_cost_order():.1f} (measured from 20 segments up). "
             if math.isfinite(self.md_cost_order()) else "grows steeply with N. ")
          + "The damping bounds "
          "dtM on fine meshes, but MoorDyn could not simply drop it: without it (BA = 0) "
          f"the largest stable RK2 dtM at {ud['n']} segments drops from {ud['dtm_damped']:.3g} s to "
          f"{ud['dtm']:.3g} s (the wave estimate l/c is {wave_dt(ud['n']):.2g} s). RK2 has no stable "
          "interval on the imaginary axis, so undamped axial waves grow unless something damps them; "
          "this is why MoorDyn asks for internal damping (BA, or −ζ as a fraction of critical).\n")
        w("* MoorDyn is driven from Python one internal step per call. The net times remove the "
          "measured cost of the call; what remains is the C++ step. A C/C++ driver calling "
          "`MoorDyn_Step` with a coarser coupling step would save the call but add the coupling "
          "error described above.\n")
        w("* riser's coarse runs are sampled every dt (0.1–0.2 s), MoorDyn's every 0.01 s, so a "
          "riser error may miss a sharper peak between its samples.\n")
        w("* At 1e-2 both codes have slack: their cheapest qualifying settings are well below the "
          "level, and neither grid goes coarser (riser below 4 elements or above dt 0.2 s; MoorDyn "
          "below 5 segments), so that ratio is the least certain.\n")
        w(f"* Timings on a shared 2-core machine ({platform.processor() or platform.machine()}), the "
          f"study pinned to CPU {max(os.sched_getaffinity(0)) if hasattr(os, 'sched_getaffinity') else '?'}; "
          f"load average {self.load_before[0]:.2f} before and {self.load_after[0]:.2f} after the study. "
          f"Across the repeated runs of one setting the wall time spread by up to {self.spread():.0f} % "
          "of the median.\n")
        w("## Reproduce\n")
        w("`make moordyn` (the pinned `moordyn` is in requirements.txt, installed into the project's venv by "
          "`make venv`), or by hand:\n")
        w("```")
        w("make venv && cargo build --release")
        w(".venv/bin/riser-tools moordyn --bin target/release/riser --out out/moordyn --docs docs")
        w("```\n")
        w(f"This run: `{' '.join(sys.argv)}`, {self.elapsed / 60:.1f} min. Every run (also the unstable "
          f"dtM probes) is in `{self.out / 'runs.csv'}`; the two converged series in "
          f"`{self.out / 'reference_timeseries.csv'}`; MoorDyn's input files and logs under "
          f"`{self.work}`. `--quick` runs a few cells against coarser references as a smoke test.\n")
        self.docs.mkdir(parents=True, exist_ok=True)
        (self.docs / "moordyn.md").write_text("\n".join(L))

    def limit_rows(self, best_scheme=True):
        """Runs at the largest stable dtM; with best_scheme, the cheapest scheme per mesh."""
        rows = [r for r in self.ok_rows("moordyn")
                if self.md_limits.get((r["n"], r["scheme"]), (None,))[0] == round(SAMPLE / r["dt"])]
        if not best_scheme:
            return rows
        best = {}
        for r in rows:
            if r["n"] not in best or r["wall_net"] < best[r["n"]]["wall_net"]:
                best[r["n"]] = r
        return [best[n] for n in sorted(best)]

    def md_order(self):
        """Slope of log(error) against log(N), MoorDyn at 20 segments and more."""
        pts = [r for r in self.limit_rows() if r["n"] >= 20]
        if len(pts) < 2:
            return float("nan")
        return float(np.polyfit(np.log([r["n"] for r in pts]), np.log([r["error"] for r in pts]), 1)[0])

    def md_cost_order(self):
        """Slope of log(net wall) against log(N), MoorDyn at 20 segments and more."""
        pts = [r for r in self.limit_rows() if r["n"] >= 20]
        if len(pts) < 2:
            return float("nan")
        return float(np.polyfit(np.log([r["n"] for r in pts]), np.log([r["wall_net"] for r in pts]), 1)[0])

    def riser_err(self, n, dt):
        rs = [r for r in self.ok_rows("riser") if r["n"] == n and r["dt"] == dt]
        return rs[0]["error"] if rs else float("nan")

    def spread(self):
        """Largest (max − min)/median of the repeated wall times, in %."""
        out = 0.0
        for r in self.rows:
            walls = [float(x) for x in r["walls"].split(";") if x]
            if len(walls) > 1:
                out = max(out, 100.0 * (max(walls) - min(walls)) / statistics.median(walls))
        return out

    def halving_text(self):
        """Range of err(dtM/2)/err(dtM) − 1 over the meshes and schemes, as text."""
        changes = []
        for (nseg, scheme), (k, _) in self.md_limits.items():
            a = [r for r in self.ok_rows("moordyn") if r["n"] == nseg and r["scheme"] == scheme]
            e1 = [r["error"] for r in a if round(SAMPLE / r["dt"]) == k]
            e2 = [r["error"] for r in a if round(SAMPLE / r["dt"]) == 2 * k]
            if e1 and e2:
                changes.append(e2[0] / e1[0] - 1.0)
        if not changes:
            return "an unmeasured amount"
        return f"{100 * min(changes):+.0f} % to {100 * max(changes):+.0f} %"

    def extrapolation_note(self, w):
        """Where MoorDyn does not reach a level, a power-law estimate from its largest-stable runs."""
        for lv in LEVELS:
            if self.cheapest("moordyn", lv, "wall_net") is not None:
                continue
            pts = [r for r in self.limit_rows() if r["n"] >= 20]
            if len(pts) < 2:
                continue
            n = np.log([r["n"] for r in pts])
            p_err = np.polyfit(n, np.log([r["error"] for r in pts]), 1)
            p_cost = np.polyfit(n, np.log([r["wall_net"] for r in pts]), 1)
            n_needed = math.exp((math.log(lv) - p_err[1]) / p_err[0])
            cost = math.exp(np.polyval(p_cost, math.log(n_needed)))
            rb = self.cheapest("riser", lv, "wall")
            ratio = f", about {cost / rb['wall']:.0f}× riser's {rb['wall']:.2f} s" if rb else ""
            w(f"*Estimate, not a measurement:* MoorDyn does not reach {lv:.0e} in the grid. A power-law "
              f"fit to its cheapest runs at 20–{pts[-1]['n']} segments ("
              + ", ".join(f"{r['n']}: {r['scheme']}" for r in pts)
              + f"; error ∝ N^{p_err[0]:.2f}, net wall ∝ N^{p_cost[0]:.2f}) puts {lv:.0e} at about "
              f"{n_needed:.0f} segments and {cost:.0f} s{ratio}. This is optimistic for MoorDyn: errors "
              f"this small are measured against a {self.md_ref_cfg[0]}-segment reference that is itself "
              f"{self.agreement['max_rel']:.1e} from riser's converged run "
              f"({self.agreement['max_rel_corrected']:.1e} with its end node's inertia added back).\n")


def main(argv=None):
    peer_study_main(argv, __doc__, Study, "out/moordyn", "moordyn.md and figures/moordyn_compare.png",
                    "a few cells against coarse references (smoke run)")


if __name__ == "__main__":
    main()
