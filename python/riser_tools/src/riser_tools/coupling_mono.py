"""Two-way runs against the monolithic reference (issue 53; docs/theory.md §7.9, docs/coupling.md
"Against the monolithic reference"): a body in heave and pitch with the hang-off at its lever,
coupled to riser's FMU in libcosim's fixed-step algorithm (osp/vessel/Vessel6.py with its surge,
sway, roll and yaw held by added masses and inertias of 1e11, riser given the body's mass and inertias,
`vessel_mass_*`, `vessel_inertia_*`, no filter), against the same body integrated inside riser's own
step (`examples/monolithic_body.rs`, riser::sim::monolithic) at a fine step.

Compared over the last `window` seconds: the top tension's minimum and maximum, the body's heave and
pitch amplitudes (half the peak to peak), relative to the reference's; and the energy through the
ports: the vessel's work on the line (riser's `work_top`) against minus the line's work on the
vessel (the vessel's `work`, the held force on its displacement), their sum the coupling's energy
error, relative to the energy exchanged (the vessel's `work_magnitude`, the sum of each step's |work|).

    riser-tools coupling-mono --fmu out/check/riser.fmu --steps 0.05,0.1,0.2,0.5
"""
from __future__ import annotations

import subprocess
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[4]
HELD = 1e11  # the mass or inertia (kg, kg m²) that holds a degree of freedom of Vessel6 still (riser takes up to 1e11 kg)


@dataclass(frozen=True)
class Case:
    """A heave–pitch body: mass and pitch inertia with their added mass, hydrostatic stiffness, linear
    damping, the excitation's amplitudes (heave force N, pitch moment N m) at `period` s with a ramp
    of `ramp` s; riser's scene overrides (`hang_off_x`: the lever, m)."""
    name: str
    mass: float
    inertia: float
    stiffness: tuple
    damping: tuple
    excitation: tuple
    period: float = 10.0
    ramp: float = 20.0
    riser: dict = field(default_factory=dict)

    def monolithic_args(self, h: float, duration: float) -> list[str]:
        nums = [h, duration, self.mass, self.inertia, *self.stiffness, *self.damping, *self.excitation, self.period,
                self.ramp]
        return ["catenary", *[repr(float(x)) for x in nums], *[f"{k}={v}" for k, v in self.riser.items()]]

    def vessel6(self) -> dict:
        """Vessel6's parameters: the body's heave and pitch, every other degree of freedom held."""
        pitch = self.inertia > 0
        p = {"mass": self.mass, "added_mass_11": HELD, "added_mass_22": HELD, "added_mass_33": 0.0,
             "inertia_xx": HELD, "inertia_yy": self.inertia if pitch else HELD, "inertia_zz": HELD,
             "added_mass_44": 0.0, "added_mass_55": 0.0, "added_mass_66": 0.0,
             "stiffness_33": self.stiffness[0], "stiffness_55": self.stiffness[1] if pitch else 0.0,
             "damping_33": self.damping[0], "damping_55": self.damping[1] if pitch else 0.0,
             "wave_period": self.period, "ramp": self.ramp,
             "wave_force_x": 0.0, "wave_force_y": 0.0, "wave_force_z": self.excitation[0],
             "wave_moment_x": 0.0, "wave_moment_y": self.excitation[1] if pitch else 0.0, "wave_moment_z": 0.0,
             "wave_phase_z": 0.0, "wave_phase_pitch": 0.0, "balance_initial_load": True}
        # surge and sway held by their added mass (Vessel6 has one mass for the three translations)
        p.update({"stiffness_11": 0.0, "stiffness_22": 0.0, "damping_11": 0.0, "damping_22": 0.0,
                  "stiffness_44": 0.0, "stiffness_66": 0.0, "damping_44": 0.0, "damping_66": 0.0})
        return p

    def riser_inertias(self) -> dict:
        """riser's `vessel_mass_*`, `vessel_inertia_*` (docs/theory.md §7.8) for this body."""
        return {"vessel_mass_heave": self.mass, "vessel_mass_surge": HELD, "vessel_mass_sway": HELD,
                "vessel_inertia_roll": HELD, "vessel_inertia_pitch": self.inertia if self.inertia > 0 else HELD,
                "vessel_inertia_yaw": HELD}


def _critical(zeta, m, c):
    return 2.0 * zeta * np.sqrt(m * c)


# the 2,000 t vessel of issue 53: M + A 3,000 t, K 5.03 MN/m (Vessel.py's), pitch inertia with added
# inertia 7e8 kg m², C55 = ρ g ∇ GM_L with ∇ 1951 m³ and GM_L 60 m, 5 % damping, hang-off 30 m forward
VESSEL_2000T = Case("2,000 t vessel, 30 m lever", 3.0e6, 7.0e8, (5.0276e6, 1.18e9),
                    (3.883e5, float(_critical(0.05, 7.0e8, 1.18e9))), (1.1e6, 1.4e7), riser={"hang_off_x": 30.0})
# the 50 t buoy of issue 29 (M + A 75 t, 10 m² waterplane, 5 %, a 10 s wave of 20 kN), no lever
BUOY_50T = Case("50 t buoy", 7.5e4, 0.0, (1.0055e5, 0.0), (float(_critical(0.05, 7.5e4, 1.0055e5)), 0.0),
                (2.0e4, 0.0))
# for the stability map: the same vessel with ten times the pitch inertia, and with its hang-off over
# its reference point (no lever: the hang-off's vertical inertia is then M + A alone)
VESSEL_2000T_I10 = Case("2,000 t vessel, 30 m lever, pitch inertia 7e9", 3.0e6, 7.0e9, (5.0276e6, 1.18e9),
                        (3.883e5, float(_critical(0.05, 7.0e9, 1.18e9))), (1.1e6, 2.5e7), riser={"hang_off_x": 30.0})
VESSEL_2000T_NO_LEVER = Case("2,000 t vessel, no lever", 3.0e6, 0.0, (5.0276e6, 0.0), (3.883e5, 0.0), (1.1e6, 0.0))
CASES = {"vessel": VESSEL_2000T, "buoy": BUOY_50T, "vessel_i10": VESSEL_2000T_I10, "vessel_no_lever": VESSEL_2000T_NO_LEVER}


def hang_off_inertia(case: Case) -> float:
    """The body's inertia felt at the hang-off along z, kg: 1/(1/M + ρ²/I) (heave and pitch at the lever ρ)."""
    rho = case.riser.get("hang_off_x", 0.0)
    return 1.0 / (1.0 / case.mass + (rho**2 / case.inertia if case.inertia > 0 else 0.0))


def monolithic(case: Case, h: float, duration: float, exe: str | None = None) -> dict:
    """The monolithic reference's columns (examples/monolithic_body.rs; built if `exe` is None)."""
    if exe is None:
        subprocess.run(["cargo", "build", "--profile", "fasttest", "--example", "monolithic_body"], cwd=ROOT,
                       check=True, capture_output=True)
        exe = str(ROOT / "target" / "fasttest" / "examples" / "monolithic_body")
    out = subprocess.run([exe, *case.monolithic_args(h, duration)], check=True, capture_output=True, text=True)
    lines = out.stdout.strip().splitlines()
    names = lines[0].split(",")
    a = np.array([[float(x) for x in ln.split(",")] for ln in lines[1:]])
    return {n: a[:, i] for i, n in enumerate(names)}


def two_way(case: Case, h: float, duration: float, riser_fmu: str, vessel_fmu: str, own: bool = True) -> dict:
    """libcosim's fixed step (riser_tools.coupling_loop.fixed_step6) on riser and Vessel6 as `case`;
    riser given the body's mass and inertias if `own`."""
    from .coupling_loop import fixed_step6

    riser = {**case.riser, **(case.riser_inertias() if own else {})}
    return fixed_step6(riser_fmu, vessel_fmu, h, duration, riser=riser, vessel=case.vessel6())


def compare(two: dict, ref: dict, start: float) -> dict:
    """The two-way run's window against the reference's (relative errors): tension min and max, heave and
    pitch amplitudes; and the ports' energy: riser's work_top against minus the vessel's work."""
    def win(res, name):
        m = res["t"] >= start - 1e-9
        return res[name][m]

    out = {}
    for name, key in [("tension min", "min"), ("tension max", "max")]:
        a, b = getattr(np, key)(win(two, "top_tension")), getattr(np, key)(win(ref, "top_tension"))
        out[name] = (a - b) / b
    for dof in ("heave", "pitch"):
        b = np.ptp(win(ref, dof)) / 2
        out[dof] = (np.ptp(win(two, dof)) / 2 - b) / b if b > 1e-12 else float("nan")
    out["tension swing (kN)"] = np.ptp(win(two, "top_tension")) / 1e3
    out["heave (m)"] = np.ptp(win(two, "heave")) / 2
    out["pitch (rad)"] = np.ptp(win(two, "pitch")) / 2
    # the ports' energy: the line's work_top (the vessel's work on it) and the vessel's (the line's on it),
    # their sum's largest magnitude over the energy exchanged (the vessel's sum of each step's |work|)
    out["energy"] = float(np.max(np.abs(two["work_top"] + two["work"])) / max(two["work_magnitude"][-1], 1e-300))
    return out


def main(argv=None):
    import argparse

    ap = argparse.ArgumentParser(prog="riser-tools coupling-mono", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fmu", default="out/check/riser.fmu")
    ap.add_argument("--vessel-fmu", default=None, help="Vessel6.fmu (built into out/check if not given)")
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--window", type=float, default=100.0)
    ap.add_argument("--h-ref", type=float, default=0.01)
    ap.add_argument("--steps", default="0.05,0.1,0.2,0.5")
    ap.add_argument("--cases", default="vessel,buoy")
    ap.add_argument("--without", action="store_true", help="also without riser's vessel_mass_* (today's default)")
    args = ap.parse_args(argv)
    from .coupling_loop import build_vessel_fmu

    vessel_fmu = args.vessel_fmu or build_vessel_fmu(ROOT / "out" / "check", "Vessel6")
    start = args.duration - args.window
    print("| body | h (s) | riser given the body's inertia | tension min | tension max | heave amplitude "
          "| pitch amplitude | tension swing (kN) | ports' energy |")
    print("|---|---|---|---|---|---|---|---|---|")
    for key in args.cases.split(","):
        case = CASES[key]
        ref = monolithic(case, args.h_ref, args.duration)
        m = ref["t"] >= start - 1e-9
        print(f"| {case.name} | monolithic {args.h_ref} | | {ref['top_tension'][m].min() / 1e3:.3f} kN "
              f"| {ref['top_tension'][m].max() / 1e3:.3f} kN | {np.ptp(ref['heave'][m]) / 2:.4f} m "
              f"| {np.ptp(ref['pitch'][m]) / 2:.5f} rad | {np.ptp(ref['top_tension'][m]) / 1e3:.3f} | |", flush=True)
        for h in [float(x) for x in args.steps.split(",")]:
            for own in ([True, False] if args.without else [True]):
                try:
                    c = compare(two_way(case, h, args.duration, args.fmu, vessel_fmu, own), ref, start)
                except RuntimeError as e:
                    print(f"| {case.name} | {h} | {'yes' if own else 'no'} | stopped: {e} | | | | | |", flush=True)
                    continue
                print(f"| {case.name} | {h} | {'yes' if own else 'no'} | {100 * c['tension min']:+.3f} % "
                      f"| {100 * c['tension max']:+.3f} % | {100 * c['heave']:+.3f} % | {100 * c['pitch']:+.3f} % "
                      f"| {c['tension swing (kN)']:.3f} | {c['energy']:.1e} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
