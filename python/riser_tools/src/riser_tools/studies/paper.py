"""The seed paper's runs (the list of the project's contract), reproduced with `riser run`
(`make paper`): docs/paper_runs.md (or paper_runs_damped.md with --damping) and
docs/figures/paper_<name>.png.

    riser-tools paper [--bin target/release/riser] [--out out/paper] [--docs docs] [--only NAME ...]
                      [--damping ETA]

Every run: 100 s from the static state, heave U0 sin(2 pi t/T) at the hang-off (the paper's
abrupt start). Per run out/paper/<name>/{timeseries,shapes}.csv, the figure (deformed shapes over
the last period, as the paper's figures 4-13, and the top tension against time), and the table
with the figures of every run.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path

from .. import cli, plots, report
from ..cases import Case, Motion, unique_labels

CURRENT_05 = ("current_top=0.5", "current_bottom=0.5")


def _case(name: str, scene: str, sets: Sequence[str], u0: float, period: float, note: str,
          until: float | None = None) -> Case:
    return Case(name, scene, tuple(sets), Motion(u0, period, until=until), 100.0, note=note)


# the paper's runs: name, scene, --set overrides, motion, what the paper shows
RUNS = unique_labels([
    _case("catenary_T20", "catenary", [], 2.5, 20.0, "Fig. 4: catenary, T = 20 s, current 0.8 m/s"),
    _case("catenary_T15", "catenary", [], 2.5, 15.0, "Fig. 5: catenary, T = 15 s, current 0.8 m/s"),
    _case("current_m0.1", "catenary", ["current_top=-0.1", "current_bottom=-0.1"], 2.5, 20.0,
          "Fig. 6: current -0.1 m/s"),
    _case("current_0", "catenary", ["current_top=0", "current_bottom=0"], 2.5, 20.0, "Fig. 6: no current"),
    _case("current_0.25", "catenary", ["current_top=0.25", "current_bottom=0.25"], 2.5, 20.0,
          "Fig. 7: current 0.25 m/s"),
    _case("current_0.5", "catenary", CURRENT_05, 2.5, 20.0, "Fig. 7: current 0.5 m/s"),
    _case("mesh_10", "catenary", ["n_elements=10", *CURRENT_05], 2.5, 20.0, "Fig. 8: 10 elements, 0.5 m/s"),
    _case("mesh_40", "catenary", ["n_elements=40", *CURRENT_05], 2.5, 20.0, "Fig. 8: 40 elements, 0.5 m/s"),
    _case("mesh_54", "catenary", ["n_elements=54", *CURRENT_05], 2.5, 20.0, "Fig. 9: 54 elements, 0.5 m/s"),
    _case("mesh_60", "catenary", ["n_elements=60", *CURRENT_05], 2.5, 20.0, "Fig. 9: 60 elements, 0.5 m/s"),
    _case("free_motion", "catenary", ["cd_normal=0", "cd_tangential=0", "current_top=0", "current_bottom=0"],
          2.5, 20.0, "Figs. 10-11: 15 s of excitation, then free motion, no drag", until=15.0),
    _case("lazy_wave", "lazy_wave", [], 2.5, 30.0, "Fig. 12: lazy wave, T = 30 s, current 0.8 -> 0.3 m/s"),
    _case("lazy_wave_reverse", "lazy_wave", ["current_top=0.3", "current_bottom=0.8"], 2.5, 30.0,
          "Fig. 13: lazy wave, current 0.3 -> 0.8 m/s"),
])


def main(argv: Sequence[str] | None = None) -> None:
    ap = report.parser("paper", __doc__, out="out/paper")
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--damping", type=float, default=0.0, help="structural_damping (s); 0 = the paper's scheme")
    args = ap.parse_args(argv)
    suffix = "" if args.damping == 0.0 else "_damped"
    out = Path(args.out + suffix)
    figs = Path(args.docs) / "figures"
    figs.mkdir(parents=True, exist_ok=True)
    rows = []
    for case in RUNS:
        if args.only and case.label not in args.only:
            continue
        name, until = case.label, case.motion.until
        print("running", name, flush=True)
        try:
            r = cli.run(args.bin, case.scene, [f"structural_damping={args.damping}", *case.sets], case.motion,
                        case.duration, out / name)
        except cli.CliError as e:
            print(e, file=sys.stderr)
            rows.append((name, case.note, None, str(e).strip().splitlines()[-1]))
            continue
        v, extra = r.summary, ""
        if until is not None:
            e_after = r.series["total_energy"][r.t > until + 1e-9]
            drift = float(max(abs(e - e_after[0]) for e in e_after))
            extra = f"energy after {until:g} s constant to {drift:.2e} J ({drift / abs(e_after[0]):.1e} of |E|)"
            v["free_motion_drift"] = drift
        plots.shapes_and_tension(plots.shapes_csv_curves(cli.read_rows(out / name / "shapes.csv")), r.t,
                                 r.top_tension, f"{name}: {case.note}", figs / f"paper_{name}{suffix}.png")
        rows.append((name, case.note, v, extra))
    with open(Path(args.docs) / f"paper_runs{suffix}.md", "w") as f:
        f.write("# The paper's runs\n\n")
        f.write("Made by `riser-tools paper` (`make paper`, riser_tools.studies.paper), 100 s each from the static "
                "state, heave U0 sin(2πt/T) with the paper's abrupt start, time step 0.05 s, Newton tolerance 1e-8, "
                f"structural damping {args.damping} s. ")
        if args.damping == 0.0:
            f.write("Tension in kN, with the default `rho_infinity` = 0.8 (theory §5.10). The start's velocity "
                    "jump launches axial waves that the scheme's high-frequency dissipation takes out within about "
                    "15 s (docs/figures/abrupt_vs_smooth.png): the whole-run min/max are those waves' (`riser run`'s "
                    "steady window leaves them out); the deformed shapes are those of the last period. With "
                    "`--set rho_infinity=1`, the paper's conserving scheme, they ring for the whole run. The same "
                    "runs with structural damping: [paper_runs_damped.md](paper_runs_damped.md).\n\n")
        else:
            f.write("Tension in kN. With structural damping (theory §5.9) the axial ringing of the abrupt start "
                    "decays within seconds; the max still contains the start's axial wave. The undamped runs: "
                    "[paper_runs.md](paper_runs.md).\n\n")
        f.write("| run | case | static top T | top T min / mean / max | energy balance (rel. to exchanged) "
                "| steps | Newton/step | wall (s) | real-time factor | figure |\n")
        f.write("|---|---|---|---|---|---|---|---|---|---|\n")
        for name, title, v, extra in rows:
            if v is None:
                f.write(f"| {name} | {title} | — | failed: {extra} | | | | | | |\n")
                continue
            tt = v["top_tension"]
            note = f" {extra}" if extra else ""
            f.write(
                f"| {name} | {title} | {v['static_top_tension'] / 1e3:.2f} | {tt['min'] / 1e3:.1f} / "
                f"{tt['mean'] / 1e3:.2f} / {tt['max'] / 1e3:.1f} | {v['energy_balance_relative']:.1e}{note} | "
                f"{v['steps']} | {v['iterations_per_step']:.2f} | {v['solve_wall_time']:.2f} | "
                f"{v['real_time_factor']:.1f} | ![](figures/paper_{name}{suffix}.png) |\n"
            )
    print("wrote", Path(args.docs) / f"paper_runs{suffix}.md")
