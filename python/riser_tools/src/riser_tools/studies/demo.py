"""`make demo`: the paper's catenary case through the FMU with fmpy.

Heave 2.5 m, T = 20 s at the hang-off, grown over one period (as `riser run` does by default;
`--ramp 0` is the paper's abrupt start), current 0.8 m/s, 100 s, from the static state. Prints the
static top tension, the top tension's min/mean/max over the steady window (one period after the
ramp to the end) and over the whole run, labelled, the energy balance residual, the wall time and
the real-time factor (of fmpy's loop with the FMU in it); writes out/demo/fmu_timeseries.csv, out/demo/shapes.png (deformed shapes over
the last period, as the paper's Fig. 4) and out/demo/tension_energy.png.

Structural damping 2 ms (docs/theory.md §5.9) damps the axial waves that an abrupt start rings; `--damping 0` runs the paper's conserving scheme. The inputs are the displacement and its
velocity: the FMU interpolates the motion smoothly (cubic Hermite) across a communication step;
with the displacement alone it is piecewise linear, and its velocity kinks ring the axial waves.

Then, shorter (issue 30): the same catenary hanging 30 m forward of the reference point of the
six-degree-of-freedom vessel osp/vessel/Vessel6.py (built with pythonfmu), coupled both ways in
libcosim's fixed-step algorithm at 0.05 s for 60 s in the vessel's default wave (10 s, grown over
20 s): the vessel's pose and velocities to riser, riser's top force and its moment about the
reference point (global) to the vessel (riser_tools.coupling_loop.fixed_step6; docs/coupling.md).
Prints the vessel's heave, roll and pitch amplitudes and the top tension's min/mean/max over the
steady window (one wave period after the ramp to the end), the moment's amplitude, the check
M = (R ρ) × F at the vessel's pose and the wall time; writes out/demo/vessel_coupling.csv and
out/demo/vessel_coupling.png. `--vessel-duration 0` leaves it out.

Last (issue 49): a moored vessel, docs/cases/moored_vessel.toml: the same vessel held by four
catenary chains and carrying a steel catenary riser, the five lines one system FMU (packaged from
fmu/riser.fmu with `riser model-description --scene`), both ways in libcosim at 0.05 s for 100 s in
the vessel's wave, its own station-keeping springs off (the chains hold it). Prints the vessel's
motion, the resultant force on it and each line's tension at its vessel end over the steady
window; writes out/demo/moored_vessel.csv and out/demo/moored_vessel.png. `--moored-duration 0`
leaves it out.
"""

from __future__ import annotations

import csv
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from .. import fmu, plots, report
from ..cases import Motion
from ..series import time_mean

OUTPUTS = ["top_tension", "top_force_x", "top_force_z", "bottom_tension", "min_tension", "total_energy",
           "kinetic_energy", "strain_energy", "potential_energy", "work_top", "work_hydro", "dissipated_energy",
           "algorithmic_dissipation"]
SHAPE = [f"shape[{k}].{c}" for k in range(21) for c in "xz"]
# the vessel coupling's CSV: the vessel's pose (m, rad), riser's top tension, force and moment (N, N m)
VESSEL_COLUMNS = ["t", "surge", "sway", "heave", "roll", "pitch", "yaw", "top_tension", "top_force_x",
                  "top_force_y", "top_force_z", "top_moment_x", "top_moment_y", "top_moment_z"]
HANG_OFF = np.array([30.0, 0.0, 0.0])  # the hang-off in the vessel frame, ρ (m)


def main(argv: Sequence[str] | None = None) -> None:
    ap = report.parser("demo", __doc__, bin=False, fmu=True, out="out/demo", docs=False)
    ap.add_argument("--damping", type=float, default=0.002)
    ap.add_argument("--duration", type=float, default=100.0)
    ap.add_argument("--ramp", type=float, default=20.0, help="s; 0 is the paper's abrupt start (default one period)")
    ap.add_argument("--vessel-duration", type=float, default=60.0,
                    help="s of the coupling with the six-degree-of-freedom vessel (0 leaves it out)")
    ap.add_argument("--moored-duration", type=float, default=100.0,
                    help="s of the moored vessel, a system FMU of four chains and a riser (0 leaves it out)")
    ap.add_argument("--bin", default="target/release/riser", help="the riser binary (model-description --scene)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    motion, dt = Motion(2.5, 20.0, ramp=args.ramp), 0.1
    # the paper's abrupt start (--ramp 0) puts the current in full at t = 0 too (docs/theory.md §5.11)
    params = {"structural_damping": args.damping, **({"current_ramp": 0.0} if args.ramp == 0 else {})}
    r = fmu.simulate(args.fmu, motion, args.duration, dt, OUTPUTS + SHAPE, params,
                     t=np.arange(0.0, args.duration + 1e-9, dt))
    s, wall = r.series, r.wall
    tt = s["top_tension"]
    residual, exchanged = fmu.energy_balance(s)
    print(f"riser FMU demo: catenary scene, heave {motion.amplitude} m / {motion.period} s, current 0.8 m/s, "
          f"{args.duration:g} s, structural damping {args.damping} s")
    t0 = min(args.ramp + motion.period, 0.5 * args.duration)
    win = s["t"] >= t0 - 1e-9
    steady = tt[win]
    start = f"grown over {args.ramp:g} s" if args.ramp > 0 else "abrupt start (the paper's)"
    print(f"  static top tension       {tt[0] / 1e3:10.3f} kN")
    print(f"  steady window {t0:g} to {args.duration:g} s ({start}):")
    print(f"    top tension            min {steady.min() / 1e3:.3f} / mean {time_mean(s['t'][win], steady) / 1e3:.3f} / "
          f"max {steady.max() / 1e3:.3f} kN")
    print(f"  whole run, with the start: top tension min {tt.min() / 1e3:.3f} / mean {time_mean(s['t'], tt) / 1e3:.3f} / "
          f"max {tt.max() / 1e3:.3f} kN")
    print(f"  energy balance residual  {residual:.3e} J ({residual / exchanged:.1e} of the {exchanged:.3e} J exchanged)")
    print(f"  wall time                {wall:.2f} s (real-time factor {args.duration / wall:.1f}, fmpy's loop "
          f"included)")
    with open(out / "fmu_timeseries.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t"] + OUTPUTS)
        for row in r.result:
            w.writerow([row["time"]] + [row[n] for n in OUTPUTS])
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 6))
    last = s["t"] >= args.duration - motion.period - 1e-9
    rows = r.result[last][:: int(round(motion.period / 8 / dt))]
    plots.shapes_axis(ax, [(row["time"], np.array([row[f"shape[{k}].x"] for k in range(21)]),
                            np.array([row[f"shape[{k}].z"] for k in range(21)])) for row in rows],
                      "catenary riser: deformed shapes over the last period")
    fig.tight_layout()
    fig.savefig(out / "shapes.png", dpi=110)
    plt.close(fig)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    a1.plot(s["t"], tt / 1e3, lw=0.8)
    # the steady window the summary reads, and the end of the motion's ramp
    a1.axvspan(t0, args.duration, color="tab:green", alpha=0.08, label=f"steady window {t0:g} to {args.duration:g} s")
    if args.ramp > 0:
        a1.axvline(args.ramp, color="0.5", lw=0.8, ls="--", label=f"end of the ramp ({args.ramp:g} s)")
    a1.set_ylabel("top tension (kN)")
    a1.set_title(f"catenary riser (FMU), heave {motion.amplitude:g} m / {motion.period:g} s: top tension and "
                 "energy", fontsize=10)
    a1.legend(loc="lower left", fontsize=8)
    a1.grid(True, alpha=0.3)
    for n in ["total_energy", "work_top", "work_hydro"]:
        a2.plot(s["t"], (s[n] - (s[n][0] if n == "total_energy" else 0)) / 1e3, label=n)
    a2.set_ylabel("energy (kJ)")
    a2.set_xlabel("t (s)")
    a2.grid(True, alpha=0.3)
    a2.legend()
    fig.tight_layout()
    fig.savefig(out / "tension_energy.png", dpi=110)
    plt.close(fig)
    print(f"  wrote {out}/fmu_timeseries.csv, shapes.png, tension_energy.png")
    if args.vessel_duration > 0:
        vessel_coupling(args.fmu, out, args.vessel_duration, damping=args.damping)
    if args.moored_duration > 0:
        moored_vessel(args.fmu, args.bin, out, args.moored_duration)


def _csv_and_pose_plot(path: Path, res: dict, columns: Sequence[str]):
    """Writes `columns` of a coupled run `res` to the CSV `path`; returns a figure of four rows
    and its axes, the vessel's translations and rotations plotted in the first two."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for row in zip(*(res[n] for n in columns)):
            w.writerow([repr(float(x)) for x in row])
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(4, 1, figsize=(9, 10), sharex=True)
    for n in ["surge", "sway", "heave"]:
        axes[0].plot(res["t"], res[n], lw=0.8, label=n)
    axes[0].set_ylabel("translation (m)")
    for n in ["roll", "pitch", "yaw"]:
        axes[1].plot(res["t"], np.degrees(res[n]), lw=0.8, label=n)
    axes[1].set_ylabel("rotation (°)")
    return fig, axes


def moment_error(res) -> float:
    """max |M − (R ρ) × F| over the run at the vessel's recorded pose, relative to |ρ| max |F|
    (tests/python/test_coupling6.py's moment_error; R = I if riser did not take the rotation)."""
    from ..coupling_loop import rotation

    f = np.stack([res[f"top_force_{c}"] for c in "xyz"], axis=1)
    m = np.stack([res[f"top_moment_{c}"] for c in "xyz"], axis=1)
    if res.get("rotations", True):
        arm = np.array([rotation(a, b, c) @ HANG_OFF for a, b, c in zip(res["roll"], res["pitch"], res["yaw"])])
    else:
        arm = np.tile(HANG_OFF, (len(res["t"]), 1))
    scale = np.linalg.norm(HANG_OFF) * np.max(np.linalg.norm(f, axis=1))
    return float(np.max(np.abs(m - np.cross(arm, f))) / scale)


def vessel_coupling(fmu_path: str, out: str | Path, duration: float = 60.0, h: float = 0.05,
                    damping: float = 0.002) -> dict:
    """The catenary hanging HANG_OFF from the reference point of osp/vessel/Vessel6.py, both ways in
    libcosim's fixed-step algorithm at step `h` for `duration` s in the vessel's default wave, with
    the structural damping `damping` s of the first part (the scene's current grows over its first
    10 s, current_ramp, docs/theory.md §5.11).
    Prints the summary, writes `out`/vessel_coupling.csv (VESSEL_COLUMNS) and vessel_coupling.png;
    returns fixed_step6's columns with "wall" (s, the coupled run) and "moment_error"."""
    import subprocess
    import tempfile
    import time

    from ..coupling_loop import build_vessel_fmu, fixed_step6

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="riser_demo_vessel6_") as tmp:
        try:
            vessel_fmu = build_vessel_fmu(tmp, "Vessel6")
        except subprocess.CalledProcessError as e:  # say why (pythonfmu missing, a bad Vessel6.py)
            raise RuntimeError(f"pythonfmu could not build osp/vessel/Vessel6.py:\n{e.stderr.decode(errors='replace')}"
                               f"{e.stdout.decode(errors='replace')}") from e
        w0 = time.perf_counter()
        riser = {"hang_off_x": float(HANG_OFF[0]), "structural_damping": damping}
        res = fixed_step6(fmu_path, vessel_fmu, h, duration, riser=riser)
        wall = time.perf_counter() - w0
    res["wall"], res["moment_error"] = wall, moment_error(res)
    t = res["t"]
    if not np.all(np.isfinite(np.stack([res[n] for n in VESSEL_COLUMNS]))):
        raise RuntimeError("the coupled run with the vessel gave non-finite values")
    t0 = min(30.0, 0.5 * duration)  # one wave period (10 s) after the wave's 20 s ramp
    win = t >= t0 - 1e-9
    amp = {n: np.ptp(res[n][win]) / 2 for n in VESSEL_COLUMNS[1:]}
    tt = res["top_tension"][win]
    print(f"riser on the six-degree-of-freedom vessel (osp/vessel/Vessel6.py): hang-off {HANG_OFF[0]:g} m forward "
          f"of its reference point, libcosim fixed step {h:g} s, {duration:g} s in its default wave (10 s, grown "
          f"over 20 s); rotations to riser: {res['rotations']}")
    print(f"  steady window {t0:g} to {duration:g} s:")
    print(f"    vessel amplitudes      heave {amp['heave']:.3f} m, roll {np.degrees(amp['roll']):.2f}° "
          f"({amp['roll']:.4f} rad), pitch {np.degrees(amp['pitch']):.2f}° ({amp['pitch']:.4f} rad)")
    print(f"    top tension            min {tt.min() / 1e3:.3f} / mean {time_mean(t[win], tt) / 1e3:.3f} / "
          f"max {tt.max() / 1e3:.3f} kN")
    print(f"    moment about the reference point (global), amplitude x {amp['top_moment_x'] / 1e3:.1f} / "
          f"y {amp['top_moment_y'] / 1e3:.1f} / z {amp['top_moment_z'] / 1e3:.1f} kN m "
          f"(mean y {time_mean(t[win], res['top_moment_y'][win]) / 1e3:.0f} kN m)")
    print(f"  |M − (Rρ)×F| / (|ρ| max|F|) at the vessel's pose: {res['moment_error']:.1e} (whole run)")
    print(f"  wall time                {wall:.2f} s (real-time factor {duration / wall:.1f}, libcosim with both "
          f"FMUs)")
    fig, (a1, a2, a3, a4) = _csv_and_pose_plot(out / "vessel_coupling.csv", res, VESSEL_COLUMNS)
    import matplotlib.pyplot as plt
    a3.plot(t, res["top_tension"] / 1e3, lw=0.8)
    a3.set_ylabel("top tension (kN)")
    for c in "xyz":
        m = res[f"top_moment_{c}"]
        a4.plot(t, (m - m[0]) / 1e3, lw=0.8, label=f"top_moment_{c} − {m[0] / 1e3:.0f} kN m")
    a4.set_ylabel("moment about the\nreference point − M(0) (kN m)")
    a4.set_xlabel("t (s)")
    for a in (a1, a2, a3, a4):
        a.grid(True, alpha=0.3)
        a.axvline(t0, color="k", lw=0.5, ls=":")
    for a in (a1, a2, a4):
        a.legend(fontsize=8)
    a1.set_title(f"riser {HANG_OFF[0]:g} m forward of the vessel's reference point, both ways in libcosim "
                 f"(fixed step {h:g} s)")
    fig.tight_layout()
    fig.savefig(out / "vessel_coupling.png", dpi=110)
    plt.close(fig)
    print(f"  wrote {out}/vessel_coupling.csv, vessel_coupling.png")
    return res


MOORED_SCENE = Path("docs") / "cases" / "moored_vessel.toml"  # make demo runs from the repository
# the vessel without its own station-keeping springs (the chains hold it), trimmed for the lines' load at t = 0
MOORED_VESSEL = {"stiffness_11": 0.0, "stiffness_22": 0.0, "stiffness_66": 0.0, "balance_initial_load": True}


def moored_vessel(fmu_path: str, riser_bin: str, out: str | Path, duration: float = 100.0, h: float = 0.05,
                  scene: str | Path = MOORED_SCENE) -> dict:
    """The moored vessel: the system FMU of `scene` (packaged from `fmu_path` with `riser_bin`) both
    ways with osp/vessel/Vessel6.py in libcosim at `h` for `duration` s. Prints the summary, writes
    `out`/moored_vessel.csv and moored_vessel.png; returns fixed_step6's columns with the lines'."""
    import subprocess
    import tempfile
    import time
    import tomllib

    from ..coupling_loop import build_vessel_fmu, fixed_step6, vessel6_inertia

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    lines = [(l["name"], l["from"], l["to"]) for l in tomllib.loads(Path(scene).read_text())["line"]]
    kinds = {p["name"]: p["kind"] for p in tomllib.loads(Path(scene).read_text())["point"]}
    # each line's tension at its vessel end
    at_vessel = {n: f"{n}.tension_{'from' if kinds[a] == 'vessel' else 'to'}" for n, a, _ in lines}
    with tempfile.TemporaryDirectory(prefix="riser_demo_moored_") as tmp:
        system = fmu.package_system(fmu_path, riser_bin, scene, Path(tmp) / "moored_vessel.fmu")
        try:
            vessel_fmu = build_vessel_fmu(tmp, "Vessel6")
        except subprocess.CalledProcessError as e:
            raise RuntimeError(f"pythonfmu could not build osp/vessel/Vessel6.py:\n{e.stderr.decode(errors='replace')}"
                               ) from e
        w0 = time.perf_counter()
        # riser given the vessel's mass and inertia: its answer to riser's own load within each step
        # (docs/theory.md §7.8; without it the loop rings the chains at 0.1 and 0.5 s, issue 53)
        res = fixed_step6(str(system), vessel_fmu, h, duration, vessel=MOORED_VESSEL,
                          riser=vessel6_inertia(vessel_fmu, MOORED_VESSEL), extra=list(at_vessel.values()))
        wall = time.perf_counter() - w0
    t = res["t"]
    t0 = min(60.0, 0.5 * duration)  # the roll near its resonance grows for about 50 s
    win = t >= t0 - 1e-9
    amp = {n: np.ptp(res[n][win]) / 2 for n in ["surge", "sway", "heave", "roll", "pitch", "yaw"]}
    print(f"a moored vessel (docs/cases/moored_vessel.toml: four chains and a steel catenary riser, one system FMU) "
          f"on the six-degree-of-freedom vessel, both ways in libcosim at {h:g} s, {duration:g} s in its wave")
    print(f"  steady window {t0:g} to {duration:g} s:")
    print(f"    vessel mean surge {time_mean(t[win], res['surge'][win]):.3f} m; amplitudes surge {amp['surge']:.3f} m, "
          f"heave {amp['heave']:.3f} m, roll {np.degrees(amp['roll']):.2f}°, pitch {np.degrees(amp['pitch']):.2f}°")
    for c in "xyz":
        f = res[f"top_force_{c}"][win]
        print(f"    force on the vessel {c}  min {f.min() / 1e3:10.1f} / mean {time_mean(t[win], f) / 1e3:10.1f} / "
              f"max {f.max() / 1e3:10.1f} kN")
    for n, col in at_vessel.items():
        x = res[col][win]
        print(f"    {n:<22} tension at the vessel min {x.min() / 1e3:8.1f} / mean {time_mean(t[win], x) / 1e3:8.1f} / "
              f"max {x.max() / 1e3:8.1f} kN")
    print(f"  wall time                {wall:.2f} s (real-time factor {duration / wall:.1f}, libcosim with both "
          f"FMUs)")
    columns = ["t", "surge", "sway", "heave", "roll", "pitch", "yaw", "top_force_x", "top_force_y", "top_force_z",
               "top_moment_x", "top_moment_y", "top_moment_z"] + list(at_vessel.values())
    fig, (a1, a2, a3, a4) = _csv_and_pose_plot(out / "moored_vessel.csv", res, columns)
    import matplotlib.pyplot as plt
    for c in "xyz":
        f = res[f"top_force_{c}"]
        a3.plot(t, (f - f[0]) / 1e3, lw=0.8, label=f"top_force_{c} − {f[0] / 1e3:.0f} kN")
    a3.set_ylabel("force on the vessel\n− F(0) (kN)")
    for n, col in at_vessel.items():
        a4.plot(t, res[col] / 1e3, lw=0.8, label=n)
    a4.set_ylabel("tension at the\nvessel (kN)")
    a4.set_xlabel("t (s)")
    for a in (a1, a2, a3, a4):
        a.grid(True, alpha=0.3)
        a.axvline(t0, color="k", lw=0.5, ls=":")
        a.legend(fontsize=7, loc="upper left")
    a1.set_title(f"moored vessel: four chains and a riser (one system FMU) both ways in libcosim (fixed step {h:g} s)")
    fig.tight_layout()
    fig.savefig(out / "moored_vessel.png", dpi=110)
    plt.close(fig)
    print(f"  wrote {out}/moored_vessel.csv, moored_vessel.png")
    res["wall"] = wall
    return res
