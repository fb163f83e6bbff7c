"""Speed against accuracy (issue 5; `make study`): `riser run` over model (rod, cable) x
elements x time step x Newton tolerance on the catenary and lazy-wave scenes. Wall time and the
error of the top tension (max and RMS over the last three periods), and of the shape (max
distance of the 21 shape points at the end), against a converged reference of the rod (whose
convergence is shown): the cable's error includes what it leaves out (bending, torsion). Writes
CSV, a work-precision plot, docs/study.md (every cell) and the summary section of
docs/performance.md (between its `study` markers).

All runs: 100 s, heave 2.5 m with the scene's period, grown over one period (a smooth start: an
abrupt one rings the undamped axial waves chaotically, and no mesh or step converges on the
ringing), structural damping 2 ms. A plain loop, one run at a time: the wall time is the result.

    riser-tools study [--bin target/release/riser] [--quick] [--no-timing-docs]
"""

import csv
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .. import cli, report  # noqa: E402
from ..cases import SCENE_PERIODS, Motion, product  # noqa: E402

SCENES = SCENE_PERIODS
ELEMENTS = [10, 20, 40, 60, 120, 240]
STEPS = [0.2, 0.1, 0.05, 0.02, 0.01]
DURATION = 100.0
MODELS = ["rod", "cable"]
MARK_BEGIN, MARK_END = report.markers("study", "riser-tools study")


def run(bin_, scene, model, n, dt, tol, out):
    """One cell: the wall time, the top tension and the 21 shape points at the end (None if riser failed)."""
    period = SCENES[scene]
    # the current in full from t = 0 (current_ramp 0), as this page was measured before the current grew over its
    # first 10 s by default (docs/theory.md §5.11): the committed figures reproduce
    r = cli.try_run(bin_, scene, {"model": model, "n_elements": n, "time_step": dt, "newton_tolerance": tol,
                                  "structural_damping": 0.002, "current_ramp": 0},
                    Motion(2.5, period, ramp=period), DURATION, out, extra=["--shape-times", str(DURATION)])
    if r is None:
        return None
    shape = cli.read_columns(Path(out) / "shapes.csv")
    # the 21 shape points of the FMU: interpolate the node rows at S = k L/20
    s = shape["S"]
    sk = np.linspace(0, s[-1], 21)
    pts = np.stack([np.interp(sk, s, shape[c]) for c in "xyz"], axis=1)
    return {"wall": r.summary["solve_wall_time"], "t": r.t, "tt": r.top_tension, "shape": pts,
            "iters": r.summary["iterations_per_step"]}


def errors(r, ref, period):
    grid = np.arange(DURATION - 3 * period, DURATION + 1e-9, 0.2)
    a = np.interp(grid, r["t"], r["tt"])
    b = np.interp(grid, ref["t"], ref["tt"])
    scale = np.max(np.abs(b))
    return (np.max(np.abs(a - b)) / scale, np.sqrt(np.mean((a - b) ** 2)) / scale,
            np.max(np.linalg.norm(r["shape"] - ref["shape"], axis=1)))


def cheapest(rows, scene, model, target):
    ok = [r for r in rows if r[0] == scene and (model is None or r[1] == model) and r[5] and r[6] <= target]
    return min(ok, key=lambda r: r[5]) if ok else None


def describe(b):
    if b is None:
        return "none of the settings tried"
    return (f"{b[1]}, {b[2]} el., dt {b[3]} s, tol {b[4]:g}: {b[5]:.2f} s ({DURATION / b[5]:.0f}× real time), "
            f"error {b[6]:.1e}")


def main(argv=None):
    ap = report.parser("study", __doc__, out="out/study")
    ap.add_argument("--quick", action="store_true", help="fewer cells (a smoke run)")
    ap.add_argument("--no-timing-docs", action="store_true",
                    help="write study.csv and study.md but leave the figure and performance.md (timed on a loaded machine)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    elements = [10, 60] if args.quick else ELEMENTS
    steps = [0.1, 0.05] if args.quick else STEPS
    rows = []
    notes = []
    for scene, period in SCENES.items():
        ref = run(args.bin, scene, "rod", 240, 0.005, 1e-10, out / scene / "ref")
        check = run(args.bin, scene, "rod", 120, 0.005, 1e-10, out / scene / "check")
        check2 = run(args.bin, scene, "rod", 240, 0.01, 1e-10, out / scene / "check2")
        cable_ref = run(args.bin, scene, "cable", 240, 0.005, 1e-10, out / scene / "cable_ref")
        e1, e2, ec = errors(check, ref, period), errors(check2, ref, period), errors(cable_ref, ref, period)
        notes.append(f"{scene}: reference the rod with 240 elements, dt 0.005 s, tolerance 1e-10; against it 120 "
                     f"elements give {e1[0]:.1e} (max) / {e1[1]:.1e} (RMS) top-tension error and {e1[2]:.1e} m "
                     f"shape error, dt 0.01 s gives {e2[0]:.1e} / {e2[1]:.1e} and {e2[2]:.1e} m: the reference is "
                     f"converged well below the errors tabulated. The cable at the same resolution differs from it "
                     f"by {ec[0]:.1e} / {ec[1]:.1e} and {ec[2]:.1e} m: the error of leaving out bending and "
                     "torsion, the floor of the cable's errors below.")
        for cell in product(model=MODELS, n=elements, dt=steps):
            model, n, dt = cell["model"], cell["n"], cell["dt"]
            for tol in ([1e-8, 1e-6] if n == 60 else [1e-8]):
                r = run(args.bin, scene, model, n, dt, tol, out / scene / f"{model}_{n}_{dt}_{tol}")
                if r is None:
                    rows.append((scene, model, n, dt, tol, None, None, None, None, None))
                    continue
                emax, erms, eshape = errors(r, ref, period)
                rows.append((scene, model, n, dt, tol, r["wall"], emax, erms, eshape, r["iters"]))
                print(scene, model, n, dt, tol, f"{r['wall']:.2f} s", f"{emax:.2e}", flush=True)
    out.mkdir(parents=True, exist_ok=True)
    # --no-timing-docs: the page, the CSV and the figure go to --out, docs/ keeps its timings
    docs = out if args.no_timing_docs else Path(args.docs)
    for path in [out / "study.csv", docs / "study.csv"]:
        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["scene", "model", "n_elements", "time_step", "newton_tolerance", "wall_s",
                        "top_tension_err_max", "top_tension_err_rms", "shape_err_m", "newton_per_step"])
            w.writerows(rows)
    figs = docs / "figures"
    figs.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.5))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, scene in zip(axes, SCENES):
        for model, style in [("rod", "o-"), ("cable", "s--")]:
            for i, n in enumerate(elements):
                pts = [(r[5], r[6]) for r in rows
                       if r[0] == scene and r[1] == model and r[2] == n and r[4] == 1e-8 and r[5]]
                if pts:
                    ax.loglog([p[0] for p in pts], [p[1] for p in pts], style, color=colors[i % len(colors)],
                              label=f"{model} {n} el.", markersize=4)
        ax.set_xlabel("wall time for 100 s (s)")
        ax.set_ylabel("top tension error, max over 3 periods (relative)")
        ax.set_title(f"{scene}: time steps 0.2 → 0.01 s along each line")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(figs / "work_precision.png", dpi=110)

    with open(docs / "study.md", "w") as f:
        f.write("# Speed against accuracy: every cell\n\n")
        f.write("Made by `riser-tools study` (`make study`, riser_tools.studies.speed_accuracy); the summary is in "
                "[performance.md](performance.md#speed-against-accuracy). Every run: 100 s, heave 2.5 m at the "
                "scene's period grown over one period, structural damping 2 ms. Errors of the top tension over "
                "the last three periods, relative to its maximum; shape error = largest distance of the 21 shape "
                "points at t = 100 s. Wall time of the time stepping on one core.\n\n")
        for n in notes:
            f.write(f"* {n}\n")
        f.write("\n![work-precision](figures/work_precision.png)\n\n")
        for scene in SCENES:
            f.write(f"## {scene}\n\n| model | elements | dt (s) | tolerance | wall (s) | real-time factor | "
                    "top T error max | RMS | shape error (m) | Newton/step |\n|---|---|---|---|---|---|---|---|---|---|\n")
            for r in rows:
                if r[0] != scene:
                    continue
                if r[5] is None:
                    f.write(f"| {r[1]} | {r[2]} | {r[3]} | {r[4]:g} | failed | | | | | |\n")
                    continue
                f.write(f"| {r[1]} | {r[2]} | {r[3]} | {r[4]:g} | {r[5]:.2f} | {DURATION / r[5]:.0f} | {r[6]:.1e} | "
                        f"{r[7]:.1e} | {r[8]:.1e} | {r[9]:.2f} |\n")
            f.write("\n")

    # the summary section of performance.md
    sec = ["## Speed against accuracy", "",
           "Made by `make study` (`riser-tools study`, about 20 minutes; run it on a quiet machine): the rod and the "
           "cable model on both scenes over elements {10, 20, 40, 60, 120, 240} × time step {0.2, 0.1, 0.05, "
           "0.02, 0.01} s × Newton tolerance {1e-8; 1e-6 at 60 elements}, 100 s of heave 2.5 m grown over one "
           "period, structural damping 2 ms. Error: the top tension's largest deviation over the last three "
           "periods from a converged rod reference, relative to its maximum. Every cell, the CSV "
           "([study.csv](study.csv)) and the shape errors: [study.md](study.md).", ""]
    sec += [f"* {n}" for n in notes] + ["", "![work-precision](figures/work_precision.png)", ""]
    sec += ["Cheapest settings for a top-tension error below 10 %, 1 % and 0.1 % (wall time of 100 s on one core):",
            "", "| scene | error below | any model | rod | cable |", "|---|---|---|---|---|"]
    for scene in SCENES:
        for target in [0.1, 0.01, 0.001]:
            sec.append(f"| {scene} | {target:g} | {describe(cheapest(rows, scene, None, target))} | "
                       f"{describe(cheapest(rows, scene, 'rod', target))} | "
                       f"{describe(cheapest(rows, scene, 'cable', target))} |")
    sec += ["", "A coarse cable can land below the converged cable's own difference from the rod (a discretisation "
            "error of the opposite sign cancels part of the model error: the catenary at 20 segments); the floor "
            "of the cable's error is the converged difference above.",
            "", "Rod against cable at equal settings (tolerance 1e-8): speed gained and accuracy lost.", "",
            "| scene | elements | dt (s) | rod wall (s) | cable wall (s) | speed-up | rod error | cable error |",
            "|---|---|---|---|---|---|---|---|"]
    for scene in SCENES:
        for n in [10, 20, 60, 240]:
            for dt in [0.1, 0.05]:
                a = [r for r in rows if r[0] == scene and r[1] == "rod" and r[2] == n and r[3] == dt and r[4] == 1e-8]
                b = [r for r in rows if r[0] == scene and r[1] == "cable" and r[2] == n and r[3] == dt and r[4] == 1e-8]
                if a and b and a[0][5] and b[0][5]:
                    a, b = a[0], b[0]
                    sec.append(f"| {scene} | {n} | {dt} | {a[5]:.2f} | {b[5]:.2f} | {a[5] / b[5]:.1f}× | "
                               f"{a[6]:.1e} | {b[6]:.1e} |")
    if args.no_timing_docs:
        print("wrote", docs / "study.md", "(docs/ left as it was)")
        return
    perf = docs / "performance.md"
    report.replace_section(perf, MARK_BEGIN, MARK_END, sec)
    print("wrote", docs / "study.md", "and the study section of", perf)
