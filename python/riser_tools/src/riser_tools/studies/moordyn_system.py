"""OC3-Hywind's spread mooring under a prescribed vessel motion: riser's `riser run SYSTEM`
against MoorDyn-C v2 (issue 49, evidence 3; docs/system_moordyn.md).

The scene is docs/cases/oc3_hywind_mooring.toml (three chains as cables, seabed kBot 3e6 Pa/m,
cBot 3e5 Pa s/m (riser's default, MoorDyn's), friction 0). MoorDyn's input is written from the
same file by riser_tools.moordyn_system: the fairleads are points on a Coupled body at the
reference point, which both codes move along surge 10 m / 100 s plus heave 2 m / 12 s, both
grown over 100 s with riser's ramp 1/2 (1 - cos(pi t / 100)), for 600 s. Each code starts from
its own static state (riser's Newton statics; MoorDyn's stationary initial-condition solver,
threshIC 1e-4); the windows are taken over 200-600 s (after the ramp and one surge period).

Three cases, each at 50 and 100 elements (segments) a line:

* `bare`: the scene as it is: no drag, no added mass (riser's defaults, Cd = Ca = 0);
* `hydro`: the chain given MoorDyn's OC3 hydrodynamics (MoorDyn's own OC3 test: Cd 1.6,
  Ca 1.0, CdAx 0.1 on pi D = riser's cd_tangential 0.1 pi on D, CaAx 0) in both codes;
* `sea`: `hydro` in a JONSWAP sea (Hs 6 m, Tp 12 s, 100 components, riser's realisation from
  `riser waves`, travelling along +x) read by riser as `[waves] kind = "table"` (stretching
  none, grown over 100 s) and handed to MoorDyn node by node through its external wave
  kinematics (WaveKin 1) from the same table and the same formulas (riser_tools.moordyn_system.Sea).

Numerics: riser at the scene's time step 0.05 s (rho_infinity 0.8, no structural damping: the
scene has none); MoorDyn RK2 with dtM = 0.1 s / n (0.002 s at 50, 0.001 s at 100 segments: a
quarter of a segment's axial wave time l/c), a `Step` call every 0.01 s, axial damping
BA = -0.05 (5 % of a segment's critical damping: the scene has no structural damping, and
MoorDyn with BA = 0 blows up within 15 s; -0.01 runs but rings, docs/system_moordyn.md).

Usage: riser-tools moordyn-system --bin target/release/riser --out out/moordyn_system --docs docs
(about 5 minutes on the 2-core project machine).
"""

from __future__ import annotations

import argparse
import csv
import math
import platform
import subprocess
import time
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Any

import numpy as np

from .. import moordyn_system as ms
from ..cases import Motion

ROOT = Path(__file__).resolve().parents[5]
SCENE = ROOT / "docs" / "cases" / "oc3_hywind_mooring.toml"
HYDRO = {"cd_normal": 1.6, "ca_normal": 1.0, "cd_tangential": 0.1 * math.pi}
SEA_HS, SEA_TP, SEA_RAMP = 6.0, 12.0, 100.0
MOTIONS = (Motion(10.0, 100.0, "surge", 100.0), Motion(2.0, 12.0, "heave", 100.0))
DURATION = 600.0
WINDOW = (200.0, 600.0)
MESHES = (50, 100)
BA = -0.05
SAMPLE = 0.05                 # s: riser's step, the output grid of both
CALL = 0.01                   # s: MoorDyn's coupling step (a Step call)
MD_OPTIONS = {**ms.NO_OUTPUT, "threshIC": 1e-4, "TmaxIC": 200}
CASES = {
    "bare": "the scene as it is (no drag, no added mass)",
    "hydro": "Cd 1.6, Ca 1.0, CdAx 0.1 (MoorDyn's OC3 chain)",
    "sea": "as hydro, in a JONSWAP sea Hs 6 m, Tp 12 s",
}
STATS = ("min", "mean", "max")
REL_TOL = 0.02               # the issue's "below ~2 %" (of the quantity's largest magnitude)


def dtm_for(nseg: int) -> float:
    """MoorDyn's internal step: 0.1 s / n, a quarter of a segment's l / c (c = sqrt(EA / m))."""
    return 0.1 / nseg


def sea_table(bin_: str, out: Path) -> Path:
    """riser's realisation of the JONSWAP sea (`riser waves` of a single-line scene: the
    components do not depend on the scene's line), components.csv as `kind = "table"` reads it."""
    d = out / "sea"
    cmd = [bin_, "waves", "catenary", "--set", "wave_kind=jonswap", "--set", f"wave_hs={SEA_HS:g}",
           "--set", f"wave_tp={SEA_TP:g}", "--duration", f"{DURATION:g}", "--out", str(d)]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    return d / "components.csv"


def scene_text(case: str, n: int, table: Path | None = None) -> str:
    """The scene both codes read for `case` at `n` elements a line."""
    text = ms.edit_scene(SCENE.read_text(), n_elements=n, line_type=None if case == "bare" else HYDRO)
    if case == "sea":
        assert table is not None
        text += (f'\n[waves]\nkind = "table"\nfile = "{table.resolve()}"\nstretching = "none"\n'
                 f"ramp = {SEA_RAMP!r}\n")
    return text


@dataclass
class Pair:
    """riser and MoorDyn on one case and mesh: their series on the common grid and costs."""

    case: str
    n: int
    riser: dict[str, np.ndarray]
    riser_json: dict[str, Any]
    riser_wall: float
    md: ms.SystemRunResult
    system: ms.System
    extra: dict[str, Any] = field(default_factory=dict)

    def windows(self, window: tuple[float, float] = WINDOW) -> dict[str, tuple[tuple[float, ...], tuple[float, ...]]]:
        """Per compared quantity: (riser's (min, mean, max), MoorDyn's), N."""
        out = {}
        for q in ms.quantities(self.system):
            out[q] = (ms.window(self.riser["t"], self.riser[q], *window),
                      ms.window(self.md.t, self.md.series(q), *window))
        return out


def run_pair(bin_: str, out: Path, case: str, n: int, motions: tuple[Motion, ...] = MOTIONS,
             duration: float = DURATION, window: tuple[float, float] = WINDOW, table: Path | None = None,
             dtm: float | None = None, ba: float = BA, threads: int | None = None) -> Pair:
    """Both codes on `case` at `n` elements (segments) a line."""
    d = out / f"{case}_{n}"
    d.mkdir(parents=True, exist_ok=True)
    scene = d / "scene.toml"
    scene.write_text(scene_text(case, n, table))
    t0 = time.perf_counter()
    series, summary = ms.run_riser(bin_, scene, d / "riser", motions, duration, threads=threads, window=window)
    riser_wall = time.perf_counter() - t0
    system = ms.load(scene)
    dtm = dtm_for(n) if dtm is None else dtm
    inp = ms.write_input(d / "moordyn" / "lines.txt", system, n, dtm, ba=ba,
                         options={**MD_OPTIONS, **({"WaveKin": 1} if case == "sea" else {})})
    sea = None
    if case == "sea":
        assert table is not None and system.seabed_z is not None
        sea = ms.Sea.read(table, system.depth, system.g, SEA_RAMP)
    md = ms.run(inp, system, n, ms.VesselMotion(motions), duration, dtm, SAMPLE,
                coupling=max(1, int(round(CALL / dtm))), sea=sea)
    if not md.ok:
        raise RuntimeError(f"MoorDyn {case} at {n} segments stopped at t = {md.t_fail} s")
    return Pair(case, n, series, summary, riser_wall, md, system)


def compare(coarse: Pair, fine: Pair, window: tuple[float, float] = WINDOW) -> list[dict[str, Any]]:
    """Rows of the acceptance: per quantity and statistic, both codes at both meshes, the code
    difference at the fine mesh against each code's mesh change and against REL_TOL of the
    quantity's largest magnitude in the window (a free point's coordinate: of the point's motion,
    the largest range of its x, y, z in MoorDyn's fine window)."""
    wc, wf = coarse.windows(window), fine.windows(window)

    def point(q: str) -> str | None:
        name, _, axis = q.rpartition(".")
        return name if name and axis in ("x", "y", "z") else None

    moved: dict[str, float] = {}
    for q, (_, mf) in wf.items():
        if (p := point(q)) is not None:
            moved[p] = max(moved.get(p, 0.0), mf[2] - mf[0])
    rows = []
    for q in wf:
        (rc, mc), (rf, mf) = wc[q], wf[q]
        p = point(q)
        scale = moved[p] if p is not None else max(abs(mf[0]), abs(mf[2]))
        for i, st in enumerate(STATS):
            diff = rf[i] - mf[i]
            mesh = max(abs(rf[i] - rc[i]), abs(mf[i] - mc[i]))
            ok_mesh, ok_rel = abs(diff) <= mesh, abs(diff) <= REL_TOL * scale
            rows.append({"case": fine.case, "quantity": q, "stat": st, "riser_coarse": rc[i], "md_coarse": mc[i],
                         "riser": rf[i], "md": mf[i], "diff": diff, "rel": diff / scale if scale > 0 else 0.0,
                         "diff_coarse": rc[i] - mc[i], "mesh": mesh, "scale": scale,
                         "ok": ok_mesh or ok_rel,
                         "why": "mesh" if ok_mesh else ("2 %" if ok_rel else "no")})
    return rows


# ----------------------------------------------------------------------------- a free point
CLUMP = ROOT / "docs" / "cases" / "clump_weight_mooring.toml"
CLUMP_DURATION = 300.0
CLUMP_WINDOW = (150.0, 300.0)
CLUMP_MESHES = (26, 52)


def dtm_clump(nseg: int, shortest: float = 260.0) -> float:
    """MoorDyn's internal step for chains whose shortest line is `shortest` m (the clump
    weight's: 260 m) in `nseg` segments: below a quarter of a segment's l / c (l / c = 0.029 s / n
    at 260 m), a whole fraction of the 0.01 s call."""
    return CALL / math.ceil(CALL / (0.025 * shortest / 260.0 / nseg))


@dataclass
class Airy:
    """A regular wave both codes take: riser's `[waves] kind = "airy"` (no stretching), MoorDyn's
    external kinematics of the same component (`ms.Sea`), the depth the seabed's."""

    height: float               # m
    period: float               # s
    direction: float = 0.0      # deg
    phase: float = 0.0          # deg
    ramp: float = 0.0           # s

    def toml(self) -> str:
        return (f'\n[waves]\nkind = "airy"\nheight = {self.height!r}\nperiod = {self.period!r}\n'
                f'direction = {self.direction!r}\nphase = {self.phase!r}\nramp = {self.ramp!r}\n'
                f'stretching = "none"\n')

    def sea(self, system: ms.System) -> ms.Sea:
        one = np.ones(1)
        return ms.Sea(one / self.period, one * self.height / 2, one * self.phase, one * self.direction,
                      system.depth, system.g, self.ramp)


def clump_pair(bin_: str, out: Path, n: int, motions: tuple[Motion, ...] = MOTIONS,
               duration: float = CLUMP_DURATION, window: tuple[float, float] = CLUMP_WINDOW,
               ba: float = BA, threads: int | None = None, case: Path = CLUMP, points: str = "",
               waves: Airy | None = None) -> Pair:
    """Both codes on a case with free points (default docs/cases/clump_weight_mooring.toml;
    issue 49, point 2) at `n` elements (segments) a line, the lines with MoorDyn's OC3
    hydrodynamics (`HYDRO`) and each free point with its own drag area and added mass (the
    case's `cd_area`, `ca`, or `points`' keys added to every free point; MoorDyn's Free point).
    In `waves`, MoorDyn's points take the waves' inertia through their water velocity
    (`ms.point_water_velocity`: MoorDyn-C's point has none)."""
    name = case.stem.replace("_mooring", "") + ("_waves" if waves else "")
    d = out / f"{name}_{n}"
    d.mkdir(parents=True, exist_ok=True)
    scene = d / "scene.toml"
    text = ms.edit_scene(case.read_text(), n_elements=n, line_type=HYDRO)
    if points:
        text = text.replace('kind = "free"\n', 'kind = "free"\n' + points)
    scene.write_text(text + (waves.toml() if waves else ""))
    t0 = time.perf_counter()
    series, summary = ms.run_riser(bin_, scene, d / "riser", motions, duration, threads=threads, window=window)
    riser_wall = time.perf_counter() - t0
    system = ms.load(scene)
    # MoorDyn's Free points start where riser's statics put them (at the scene's start position
    # MoorDyn's buoy swings 12 m in its first minute: its own start, not the physics)
    for pt in summary.get("points", []):
        system.points[pt["name"]].position = tuple(pt["static_position"])
    dtm = dtm_clump(n, min(line.length for line in system.lines))
    inp = ms.write_input(d / "moordyn" / "lines.txt", system, n, dtm, ba=ba,
                         options={**MD_OPTIONS, **({"WaveKin": 1} if waves else {})})
    md = ms.run(inp, system, n, ms.VesselMotion(motions), duration, dtm, SAMPLE,
                coupling=int(round(CALL / dtm)), sea=waves.sea(system) if waves else None,
                point_wave_inertia=waves is not None)
    if not md.ok:
        raise RuntimeError(f"MoorDyn on {case.name} at {n} segments stopped at t = {md.t_fail} s")
    return Pair(name, n, series, summary, riser_wall, md, system)


def clump_rows(pair: Pair, window: tuple[float, float] = CLUMP_WINDOW) -> list[dict[str, Any]]:
    """Per compared quantity and statistic: both codes, their difference, relative to the
    quantity's scale (a tension's: the largest tension in the window; the clump's position's:
    its motion's range, the largest of x, y, z, with the difference in m too)."""
    w = pair.windows(window)
    tension = max(max(abs(v) for v in m) for q, (_, m) in w.items() if ".tension" in q)
    moved = max(m[2] - m[0] for q, (_, m) in w.items() if q.split(".")[-1] in "xyz" and "." in q
                and not q.startswith("top_force"))
    rows = []
    for q, (r, m) in w.items():
        is_pos = "." in q and q.split(".")[-1] in ("x", "y", "z")
        scale = moved if is_pos else (tension if ".tension" in q else max(abs(m[0]), abs(m[2])))
        for st, a, b in zip(STATS, r, m):
            rows.append({"quantity": q, "stat": st, "riser": a, "md": b, "diff": a - b, "scale": scale,
                         "rel": (a - b) / scale if scale > 0 else 0.0})
    return rows


# ----------------------------------------------------------------------------- the page
def _kn(v: float) -> str:
    return f"{v / 1e3:.1f}"


def plot(pairs: dict[tuple[str, int], Pair], path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = max(MESHES)
    cases = [c for c in CASES if (c, n) in pairs]
    fig, axes = plt.subplots(len(cases) + 1, 1, figsize=(10, 3.0 * (len(cases) + 1)))
    for ax, c in zip(axes, cases):
        p = pairs[(c, n)]
        for ln, col in (("line1", "C0"), ("line2", "C1")):
            q = f"{ln}.tension_to"
            ax.plot(p.riser["t"], p.riser[q] / 1e3, col, lw=1.0, label=f"{ln} riser")
            ax.plot(p.md.t, p.md.series(q) / 1e3, "k--", lw=0.6, label=f"{ln} MoorDyn" if ln == "line1" else None)
        ax.axvspan(*WINDOW, color="0.93", zorder=-1)
        ax.set_ylabel("fairlead tension (kN)")
        ax.set_title(f"{c}: {CASES[c]}, {n} elements / segments a line", fontsize=9)
        ax.legend(fontsize=7, ncol=3, loc="lower left")
    # the zoom: the bare case around riser's largest line-1 tension
    c = "bare" if ("bare", n) in pairs else cases[0]
    p = pairs[(c, n)]
    t, y = p.riser["t"], p.riser["line1.tension_to"]
    k = int(np.argmax(np.where(t >= WINDOW[0], y, -np.inf)))
    lo, hi = t[k] - 15.0, t[k] + 15.0
    ax = axes[-1]
    m = (t >= lo) & (t <= hi)
    ax.plot(t[m], y[m] / 1e3, "C0", lw=1.0, label="line1 riser")
    m = (p.md.t >= lo) & (p.md.t <= hi)
    ax.plot(p.md.t[m], p.md.series("line1.tension_to")[m] / 1e3, "k--", lw=0.8, label="line1 MoorDyn")
    ax.set_title(f"{c}, {n}: around riser's largest line-1 tension", fontsize=9)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("fairlead tension (kN)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=90)
    plt.close(fig)


def write_csv(rows: list[dict[str, Any]], path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    keys = list(rows[0])
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def markdown(pairs: dict[tuple[str, int], Pair], rows: list[dict[str, Any]], extra: list[str]) -> str:
    L = ["# OC3-Hywind's mooring under a prescribed vessel motion: riser against MoorDyn-C", "",
         "Issue 49, evidence 3. Written by `riser-tools moordyn-system` "
         "(python/riser_tools/src/riser_tools/studies/moordyn_system.py); the driver of MoorDyn is "
         "riser_tools.moordyn_system; the test is tests/python/test_system_moordyn.py.", ""]
    L += ["## The runs", "",
          "* **Scene**: [docs/cases/oc3_hywind_mooring.toml](cases/oc3_hywind_mooring.toml), three chains "
          "of 902.2 m as cables; water 1025 kg/m³, g 9.80665 m/s², depth 320 m; seabed kBot 3e6 Pa/m, "
          "cBot 3e5 Pa s/m (riser's default damping, MoorDyn's), friction 0, in both codes.",
          "* **MoorDyn's input** is written from the same file (riser_tools.moordyn_system): one line "
          "type (Diam 0.09 m, 77.7066 kg/m, EA 384.243 MN, EI 0), the anchors Fixed points, the fairleads "
          "points on one Coupled body at the reference point (no mass, volume or drag of its own), the "
          "lines anchor (A) to fairlead (B) with as many segments as riser's elements.",
          "* **Motion**: surge 10 m / 100 s plus heave 2 m / 12 s of the reference point, both grown over "
          "100 s by ½(1 − cos(πt/100)), 600 s. riser's `riser run SCENE --surge 10,100 --heave 2,12 "
          "--ramp 100 --duration 600 --window 200,600`; MoorDyn's body moved along the same function "
          "(exact position at each 0.01 s call, linear within it).",
          "* **Start**: each code from its own static state at the neutral pose (riser's statics; "
          "MoorDyn's stationary initial-condition solver, threshIC 1e-4): static fairlead tensions in "
          "the table below. **Window**: 200–600 s for both (after the ramp and one surge period), "
          "min / time-mean / max on the same 0.05 s grid.",
          f"* **riser**: time step 0.05 s (the scene's), ρ∞ 0.8, no structural damping (the scene has "
          f"none). **MoorDyn** 2.7 (`moordyn` {_version('moordyn')}): RK2, dtM 0.002 s (50 segments) "
          "and 0.001 s (100), a quarter of a segment's axial wave time l/c; axial damping "
          "BA = −0.05 (5 % of a segment's critical damping): without it MoorDyn blows up "
          "(BA = 0: at t = 14 s, 50 segments, dtM 0.002 s); BA = −0.01 runs but the drag-free "
          "lines ring to 2.5 MN; −0.05 and −0.2 give the same line-2 maximum within 0.1 kN over "
          "200 s. BA is the smallest of these that holds MoorDyn still.",
          "* **Cases**: " + "; ".join(f"`{c}` {t}" for c, t in CASES.items()) + ". In `sea` the "
          "components are riser's realisation (`riser waves`, 100 components, Hs 6 m, Tp 12 s, "
          "travelling along +x, phase origin the reference point; the record repeats after 343 s), "
          "riser reads them as `[waves] kind = \"table\"` (stretching none: every node is 70 m or "
          "more below the surface; grown over 100 s) and MoorDyn takes the same sea node by node "
          "through its external wave kinematics (WaveKin 1), evaluated by the same linear formulas "
          "(docs/theory.md §13.1–13.2, (13.7)) at each call's midpoint.",
          "* **Compared**: each fairlead's tension (the magnitude of the line's end force on the vessel, "
          "MoorDyn's end-node force less its inertia M a, riser's end reaction) and the resultant "
          "force on the vessel, x (surge) and z (heave).", ""]
    L += ["## Cost of each run (wall seconds, this machine)", "",
          "| case | n | riser solve (s) | riser process (s) | MoorDyn IC (s) | MoorDyn steps (s) | MoorDyn dtM (s) |",
          "|---|---|---|---|---|---|---|"]
    for (c, n), p in sorted(pairs.items(), key=lambda x: (list(CASES).index(x[0][0]), x[0][1])):
        L.append(f"| {c} | {n} | {p.riser_json['solve_wall_time']:.1f} | {p.riser_wall:.1f} | "
                 f"{p.md.ic_time:.1f} | {p.md.wall:.1f} | {p.md.dtm:g} |")
    L += ["", "riser's solve on 2 threads (the lines on threads, `--threads 2`); MoorDyn single-threaded "
          "through its Python binding (one `Step` call per 0.01 s; the sea's kinematics in numpy).", ""]
    L += ["## Static state (neutral pose)", "", "| case | n | riser line1 / line2 (kN) | MoorDyn line1 / line2 (kN) |",
          "|---|---|---|---|"]
    for (c, n), p in sorted(pairs.items(), key=lambda x: (list(CASES).index(x[0][0]), x[0][1])):
        rs = {r["name"]: r["static_tension_to"] for r in p.riser_json["steady"]["lines"]}
        L.append(f"| {c} | {n} | {rs['line1'] / 1e3:.3f} / {rs['line2'] / 1e3:.3f} | "
                 f"{p.md.series('line1.tension_to')[0] / 1e3:.3f} / {p.md.series('line2.tension_to')[0] / 1e3:.3f} |")
    L += ["", "## The windows, 200–600 s", "",
          "kN; riser − MoorDyn at 100 elements against the larger of the two codes' changes from 50 to 100 "
          "(“mesh”), and relative to the quantity's largest magnitude in the window (“rel.”). "
          "Acceptance: within the mesh change, or below 2 %. line3 is line2's mirror image in "
          "every case without waves (equal to the last digit) and is left out of the table there.", ""]
    L += ["| case | quantity | stat | riser 50 | MoorDyn 50 | riser 100 | MoorDyn 100 | diff 100 | diff 50 | mesh | rel. | status |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["quantity"].startswith("line3") and r["case"] != "sea":
            continue
        q = r["quantity"].replace(".tension_to", " tension")
        L.append(f"| {r['case']} | {q} | {r['stat']} | {_kn(r['riser_coarse'])} | {_kn(r['md_coarse'])} | "
                 f"{_kn(r['riser'])} | {_kn(r['md'])} | {r['diff'] / 1e3:+.1f} | {r['diff_coarse'] / 1e3:+.1f} | "
                 f"{r['mesh'] / 1e3:.1f} | {100 * r['rel']:+.2f} % | "
                 f"{'pass (' + r['why'] + ')' if r['ok'] else '**fail**'} |")
    L += [""]
    L += extra
    L += ["![fairlead tensions, riser against MoorDyn](figures/system_moordyn.png)", "",
          f"Machine: {platform.machine()}, {platform.python_version()}, numpy {np.__version__}.", ""]
    return "\n".join(L)


def _version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "?"


def summary_lines(rows: list[dict[str, Any]]) -> list[str]:
    L = ["## What it shows", ""]
    for c in CASES:
        rs = [r for r in rows if r["case"] == c]
        if not rs:
            continue
        worst = max(rs, key=lambda r: abs(r["rel"]))
        n_ok = sum(r["ok"] for r in rs)
        n_mesh = sum(r["why"] == "mesh" for r in rs)
        L.append(f"* `{c}`: {n_ok} of {len(rs)} entries pass ({n_mesh} within the mesh change); the largest "
                 f"difference {worst['diff'] / 1e3:+.1f} kN ({100 * worst['rel']:+.2f} %) in "
                 f"{worst['quantity']} {worst['stat']}.")
    L.append("")
    return L


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="riser-tools moordyn-system", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/release/riser")
    ap.add_argument("--out", default="out/moordyn_system", type=Path)
    ap.add_argument("--docs", default=None, type=Path, help="write system_moordyn.md and figures/ here")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args(argv)
    bin_ = str(Path(a.bin).resolve())
    cases = a.cases.split(",")
    table = sea_table(bin_, a.out) if "sea" in cases else None
    pairs: dict[tuple[str, int], Pair] = {}
    rows: list[dict[str, Any]] = []
    for c in cases:
        for n in MESHES:
            print(f"{c} at {n}", flush=True)
            pairs[(c, n)] = run_pair(bin_, a.out, c, n, table=table, threads=a.threads)
        rows += compare(pairs[(c, MESHES[0])], pairs[(c, MESHES[-1])])
    write_csv(rows, a.out / "system_moordyn.csv")
    for r in rows:
        print(f"{r['case']:6s} {r['quantity']:18s} {r['stat']:4s} riser {_kn(r['riser']):>8s} MD {_kn(r['md']):>8s} "
              f"diff {r['diff'] / 1e3:+7.2f} mesh {r['mesh'] / 1e3:6.2f} rel {100 * r['rel']:+.2f} % {r['why']}")
    if a.docs is not None:
        plot(pairs, a.docs / "figures" / "system_moordyn.png")
        extra_path = a.docs / "system_moordyn_notes.md"
        extra = extra_path.read_text().splitlines() + [""] if extra_path.exists() else []
        (a.docs / "system_moordyn.md").write_text(markdown(pairs, rows, summary_lines(rows) + extra))
        write_csv(rows, a.docs / "system_moordyn.csv")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
