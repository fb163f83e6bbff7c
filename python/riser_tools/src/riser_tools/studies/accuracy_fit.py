"""The wave terms' constants of the accuracy knob's error model (docs/theory.md §16.4), checked
against the study's runs (docs/accuracy_runs.csv, written by `riser-tools accuracy`):

    e_w = S [C_wt (ω_w Δt)^1.5 + min(C_wk2 (h k_w)², C_wk (h k_w)⁴)] + E_w + [regular wave] E_c F_c,

(E_c 0 since the current grows over current_ramp, §16.7) on top of the still-water terms
√([C_κ (h κ)⁴]² + [C_d (A ω²/g)(h κ)³]²) + C_t (A ω)(ω Δt)² (16.9; the seas' lines rest on no seabed)
with their constants (the run's own heave; none: zero). For each wave case the scales (S, F_c, k_w, ω_w, the line's length and
largest curvature) are read from the binary's own choice (`--json`'s `accuracy` object); every
grid run with at least 75 steps per period is a point. Printed: each constant's envelope, the
smallest value that bounds every point with the others as given (C_wk with C_wk2 left out and
C_wk2 with C_wk left out: each of the two mesh bounds holds alone), and each point's error
against the model.

    riser-tools accuracy-fit [--bin target/fasttest/riser] [--runs docs/accuracy_runs.csv]
                             [C_wt C_wk C_wk2 E_w E_c]

With --still, the still-water step term of (16.2) instead (docs/theory.md §16.3, "The step term's
form", and §16.7): for each candidate form M (ω Δt)^c, M one of the a-priori scales of STEP_FORMS (A/A₀,
the form before §16.7; the hang-off's velocity amplitude A ω, the knob's since; its acceleration A ω²/g; the rigid-body inertia of the line over its static top
tension; the drag of the line moving with the hang-off over it; the quasi-static swing of the top
tension from the statics with the hang-off moved by ±A), the envelope constant of each of the five
calibration cases (STEP_CASES, the grid points with at least 75 steps a period and e ≥ 4e-5, less
the model's mesh terms) and their spread, the largest over the smallest: the form whose constant
varies least across the lines and periods is the better founded.

    riser-tools accuracy-fit --still [--ladder] [--bin target/fasttest/riser] [--runs docs/accuracy_runs.csv]

--ladder takes the ladder's points between the grid's steps too (`riser-tools accuracy`, kind ladder).

With --oracle, what a perfect a-priori model would cost (docs/theory.md §16.3, "What a perfect model
would cost"): for each heave case (ORACLE_CASES) and target, the cheapest of the committed grid and
ladder runs with at least 75 steps a period whose error is at or below the target over the safety
factor (1.5) — the choice of a model that knew every run's error and kept the knob's margin — and its
cost ratio against the cheapest grid cell reaching the target, beside the knob's own.

    riser-tools accuracy-fit --oracle [--runs docs/accuracy_runs.csv]
"""
from __future__ import annotations

import argparse
import csv
import math
import subprocess
import tomllib

from . import accuracy as A

# the still-water constants of src/sim/accuracy.rs (C_CURVATURE, C_TIME, C_DYNAMIC_MESH), the step
# term C_T (A ω)(ω Δt)^STEP_ORDER, C_T in s/m (docs/theory.md §16.7: the hang-off's velocity and the
# order 2 since the current grows over current_ramp; C_T (A/A0)(ω Δt)^{3/2}, C_T 0.21, before)
C_K, C_T, C_D = 7.4e-4, 0.137, 0.03
STEP_ORDER = 2.0
# the wave constants of src/sim/accuracy.rs: C_WAVE_TIME, C_WAVE_MESH, C_WAVE_MESH2, WAVE_FLOOR, and the
# current's ringing in a regular wave E_c, 0 since the current grows over current_ramp (§16.7; it was
# C_CURRENT_RINGING, 7.5e-3, against the jolt of a current in full from t = 0)
CONSTANTS = (0.05, 0.05, 0.018, 3.5e-5, 0.0)
NAMES = ("C_wt", "C_wk", "C_wk2", "E_w", "E_c")


def points(binary: str, runs: str):
    rows = list(csv.DictReader(open(runs)))
    out = []
    for case, (scene, amp, period, els, sea, dur, win) in A.WAVE_CASES.items():
        if case in A.STILL_CASES:
            # no sea: the still-water terms alone (their floor E_s F_c went with the current's jolt, §16.7)
            continue
        d = A.choice(binary, case, ["accuracy=1e-2"])
        m = [r for r in rows if r["case"] == case and r["completed"] == "True"]
        ref = next((r for r in m if r["kind"] == "reference"), None)
        if ref is None:
            continue
        s, fc, regular = d["wave_load_ratio"], d["current_load_ratio"], d["wave_regular"]
        print(f"{case}: S {s:.4f}, F_c {fc:.4f}, k_w {d['wave_number']:.4f} rad/m, "
              f"omega_w {d['wave_omega']:.4f} rad/s, {'regular' if regular else 'spectrum'}")
        for r in m:
            if r["kind"] != "grid":
                continue
            n, dt = int(r["n_elements"]), float(r["time_step"])
            if dt * 75 > min(2 * math.pi / d["wave_omega"], period) * (1 + 1e-9):
                continue
            h = d["length"] / n
            # (16.9) with the mesh term of the motion, C_d (A ω²/g)(h κ)³ (the run's heave; none: zero), in
            # quadrature with C_κ (h κ)⁴ (docs/theory.md §16.8; the seas' lines rest on no seabed)
            still = (math.hypot(C_K * (h * d["max_curvature"]) ** 4,
                                C_D * d["acceleration_ratio"] * (h * d["max_curvature"]) ** 3)
                     + C_T * amp * 2 * math.pi / period * (2 * math.pi / period * dt) ** STEP_ORDER)
            hk = h * d["wave_number"]
            x = dict(t=s * (d["wave_omega"] * dt) ** 1.5, k4=s * hk ** 4, k2=s * hk ** 2, c=fc if regular else 0.0)
            out.append((case, n, dt, A.error(r, ref), still, x))
    return out


def model(c, still, x):
    ct, ck, ck2, ew, ec = c
    return still + ct * x["t"] + min(ck2 * x["k2"], ck * x["k4"]) + ew + ec * x["c"]


def envelope(pts, c, i):
    """The smallest value of constant i that bounds every point, the others as in c (for a mesh
    constant, with the other mesh bound left out)."""
    lo, hi = 0.0, 1.0
    other = {1: 2, 2: 1}.get(i)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        q = list(c)
        q[i] = mid
        if other is not None:
            q[other] = 1e9
        if all(model(q, s, x) >= e for (_, _, _, e, s, x) in pts):
            hi = mid
        else:
            lo = mid
    return hi


# the still-water calibration cases of the step term (docs/theory.md §16.2): a heave, no sea
STEP_CASES = ("catenary", "lazy_wave", "steel_catenary", "lowe_langley_jumper", "catenary_T10")
# below it a grid point is at the references' floor (docs/theory.md §16.1, §16.2)
FLOOR = 4e-5
# the seabed constants of the step form's analysis (docs/theory.md §16.3, "The step term's form,
# re-examined"): src/sim/accuracy.rs C_CONTACT2 and C_CONTACT, those of the contact's rule split at the
# crossings (docs/theory.md (9.7)) on whose runs the steel catenary's points now are. (The analysis was
# made before the mesh term of the motion C_d, with 7.6e-3 and 0.17 on the steel catenary's runs of the
# four fixed points; on the present runs these give every figure of it again: 5.45 at c = 1.5.)
C_K2, C_C = 8.3e-3, 1.92e-2
# the still part A_s of the touchdown term's factor A ω²/g + A_s (src/sim/accuracy.rs A_TOUCHDOWN_STILL,
# docs/theory.md §16.8: the touchdown's mesh error grows with the motion's acceleration; static, C_c2 1.0e-3
# and C_c 2.4e-3, before)
A_S = 0.02
A0 = 10.0
# the candidate scales M of the step term M (ω Δt)^c: name -> (description, M of a case's scales)
STEP_FORMS = {
    "amplitude": ("A/A0 (the form before docs/theory.md §16.7)", lambda q: q["A"] / A0),
    "velocity": ("A w, the hang-off's velocity amplitude, m/s (the knob's form since §16.7)",
                 lambda q: q["A"] * q["w"]),
    "acceleration": ("A w^2/g, the hang-off's acceleration", lambda q: q["A"] * q["w"] ** 2 / q["g"]),
    "inertia": ("(m + m_a) L A w^2 / T0, the line's rigid-body inertia over its top tension",
                lambda q: q["mass"] * q["L"] * q["A"] * q["w"] ** 2 / q["T0"]),
    "drag": ("1/2 rho Cd D L (A w)^2 / T0, the drag of the line moving with the hang-off",
             lambda q: 0.5 * q["rho"] * q["cdd"] * q["L"] * (q["A"] * q["w"]) ** 2 / q["T0"]),
    "quasi-static": ("|T0(+A) - T0(-A)| / (2 T0), the statics with the hang-off moved by +-A",
                     lambda q: q["Rqs"]),
}
STEP_EXPONENTS = (1.0, 1.25, 1.5, 2.0)



def step_scales(binary: str, case: str) -> dict:
    """A heave case's scales: the line's (its scene as riser prints it), the static top tension and
    its quasi-static swing (`riser statics` with the anchor, and the seabed, moved by -+A: the
    hang-off moved by +-A), the mesh terms' scales as the binary reports them."""
    scene, amp, period, _ = A.CASES[case]
    d = A.json_of([binary, "run", scene, "--heave", f"{amp},{period}", "--duration", "0.2", "--json",
               "--set", "accuracy=1e-2"])["accuracy"]
    sc = tomllib.loads(subprocess.run([binary, "scene", scene], capture_output=True, text=True, check=True).stdout)
    line, env = sc["line"], sc["environment"]
    rho = env["water_density"]

    def top(dz):
        sets = ["--set", f"anchor_z={sc['anchor']['z'] + dz}"]
        if "seabed" in sc:
            sets += ["--set", f"seabed_z={sc['seabed']['z'] + dz}"]
        return A.json_of([binary, "statics", scene, "--json"] + (sets if dz else []))["top_tension"]

    t0, up, down = top(0.0), top(-amp), top(amp)
    return dict(A=amp, w=2 * math.pi / period, T=period, g=env["gravity"], rho=rho, L=line["length"],
                mass=line["mass_per_length"] + rho * line["ca_normal"] * math.pi * line["outer_diameter"] ** 2 / 4,
                cdd=line["cd_normal"] * line["outer_diameter"], T0=t0, Rqs=abs(up - down) / (2 * t0),
                kappa=d["max_curvature"], lam=d["touchdown_bending_length"])


def mesh_error(q: dict, n: int) -> float:
    """The still-water mesh terms at n elements the step form's analysis takes off each point (docs/theory.md
    §16.3): C_κ (h κ)⁴ and the touchdown's term of (16.9), not C_d's (16.2), which is fitted with the step
    term."""
    h = q["L"] / n
    e = C_K * (h * q["kappa"]) ** 4
    if q["lam"]:
        # (16.9): the touchdown's term grows with the motion's acceleration
        e += (q["A"] * q["w"] ** 2 / q["g"] + A_S) * min(C_K2 * (h / q["lam"]) ** 2, C_C * (h / q["lam"]) ** 4)
    return e


def step_points(rows: list, case: str, q: dict, kinds=("grid",)) -> list:
    """(n, Δt, e, e less the mesh terms) of a heave case's points of the given kinds (the grid's; with
    "ladder", the steps between them too) the step term must bound: at least 75 steps a period, above
    the references' floor."""
    m = [r for r in rows if r["case"] == case and r["completed"] == "True"]
    ref = next(r for r in m if r["kind"] == "reference")
    out = []
    for r in m:
        if r["kind"] not in kinds:
            continue
        n, dt = int(r["n_elements"]), float(r["time_step"])
        if dt * A.STEPS_PER_PERIOD > q["T"] * (1 + 1e-9):
            continue
        e = A.error(r, ref)
        if e >= FLOOR:
            out.append((n, dt, e, e - mesh_error(q, n)))
    return out


def step_envelopes(cases: dict, scale, c: float) -> dict:
    """Each case's envelope constant of the step term scale(q) (ω Δt)^c: the smallest that bounds all
    its points (those the mesh terms bound alone need none). cases: name -> (q, points)."""
    return {k: max([y / (scale(q) * (q["w"] * dt) ** c) for (_, dt, _, y) in p if y > 0], default=0.0)
            for k, (q, p) in cases.items()}


def spread(envelopes: dict) -> float:
    """The largest case constant over the smallest: 1 if one constant fits every case alike."""
    v = [x for x in envelopes.values() if x > 0]
    return max(v) / min(v)


def still_main(binary: str, runs: str, ladder: bool = False) -> int:
    rows = list(csv.DictReader(open(runs)))
    cases = {}
    for case in STEP_CASES:
        q = step_scales(binary, case)
        cases[case] = (q, step_points(rows, case, q, ("grid", "ladder") if ladder else ("grid",)))
        print(f"{case}: A {q['A']} m, T {q['T']:g} s, T0 {q['T0'] / 1e3:.2f} kN, quasi-static swing {q['Rqs']:.4f}, "
              f"{len(cases[case][1])} points")
        for name, (_, f) in STEP_FORMS.items():
            print(f"  {name}: M = {f(q):.4g}")
    print("form, exponent c: spread (largest case constant over the smallest); each case's constant")
    for name, (what, f) in STEP_FORMS.items():
        for c in STEP_EXPONENTS:
            env = step_envelopes(cases, f, c)
            print(f"{name:13s} c {c:4.2f}: spread {spread(env):6.2f}; "
                  + ", ".join(f"{k} {v:.3g}" for k, v in env.items()) + f"  [{what}]")
    return 0


# the heave cases of the calibration (docs/accuracy.md): the built-in scenes and the jumper at their own
# motion, then the design motion (2.5 m at 10 s) on each line
ORACLE_CASES = ("catenary", "lazy_wave", "steel_catenary", "lowe_langley_jumper", "catenary_T10", "lazy_wave_T10",
                "steel_catenary_T10", "lowe_langley_jumper_T10")
SAFETY = 1.5


def oracle(rows: list, case: str, target: float, safety: float = SAFETY) -> dict | None:
    """The knob's choice for `case` at `target` from the committed runs (kind accuracy), the cheapest grid
    cell reaching the target, and the cheapest grid or ladder run with at least 75 steps a period whose
    error is within target/safety (a model knowing every run's error, with the knob's margin); each with
    its work and error, and the ratios of the choice's and the oracle's work to the cell's. None where no
    grid cell reaches the target, the knob has no run at it, or no run is within target/safety."""
    m = [r for r in rows if r["case"] == case and r["completed"] == "True"]
    ref = next(r for r in m if r["kind"] == "reference")
    runs = [r for r in m if r["kind"] in ("grid", "ladder")]
    cells = [r for r in runs if r["kind"] == "grid" and A.error(r, ref) <= target]
    knob = [r for r in m if r["kind"] == "accuracy" and r["accuracy"] and abs(float(r["accuracy"]) / target - 1) < 1e-9]
    covered = [r for r in runs if float(r["time_step"]) * A.STEPS_PER_PERIOD <= A.shortest_period(case) * (1 + 1e-9)
               and A.error(r, ref) <= target / safety]
    if not cells or not knob or not covered:
        return None
    cell, best, choice = min(cells, key=A.work), min(covered, key=A.work), knob[0]
    out = {}
    for name, r in (("cell", cell), ("oracle", best), ("knob", choice)):
        out[name] = (int(r["n_elements"]), float(r["time_step"]), A.error(r, ref), A.work(r))
    out["knob_ratio"] = out["knob"][3] / out["cell"][3]
    out["oracle_ratio"] = out["oracle"][3] / out["cell"][3]
    return out


def oracle_main(runs: str) -> int:
    rows = list(csv.DictReader(open(runs)))
    print("| case | ε | cheapest grid cell reaching ε | the knob's choice: e, cost ratio | "
          f"the cheapest run within ε/{SAFETY:g}: e, cost ratio |")
    print("|---|---|---|---|---|")
    for case in ORACLE_CASES:
        for target in (1e-2, 1e-3, 1e-4):
            o = oracle(rows, case, target)
            if o is None:
                print(f"| {case} | {target:g} | (no grid cell, knob run or run within ε/{SAFETY:g}) | | |")
                continue
            c, k, b = o["cell"], o["knob"], o["oracle"]
            print(f"| {case} | {target:g} | {c[0]}, {c[1]:g} s ({c[2]:.1e}) | {k[0]}, {k[1]:g} s: {k[2]:.1e}, "
                  f"{o['knob_ratio']:.2f} | {b[0]}, {b[1]:g} s: {b[2]:.1e}, {o['oracle_ratio']:.2f} |")
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(prog="riser-tools accuracy-fit", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/fasttest/riser")
    ap.add_argument("--runs", default="docs/accuracy_runs.csv")
    ap.add_argument("--still", action="store_true",
                    help="the still-water step term's candidate forms instead (docs/theory.md 16.3)")
    ap.add_argument("--ladder", action="store_true",
                    help="with --still: the ladder's steps between the grid's too (riser-tools accuracy --phase ladder)")
    ap.add_argument("--oracle", action="store_true",
                    help="what a model knowing every run's error would choose (docs/theory.md 16.3)")
    ap.add_argument("constants", nargs="*", type=float, help="C_wt C_wk C_wk2 E_w E_c")
    args = ap.parse_args(argv)
    if args.oracle:
        return oracle_main(args.runs)
    if args.still:
        return still_main(args.bin, args.runs, args.ladder)
    c = tuple(args.constants) if len(args.constants) == 5 else CONSTANTS
    pts = points(args.bin, args.runs)
    print("constants: " + ", ".join(f"{n} {v:g}" for n, v in zip(NAMES, c)))
    print("envelopes, each with the others as given: "
          + ", ".join(f"{n} {envelope(pts, c, i):.3g}" for i, n in enumerate(NAMES)))
    worst = min(model(c, s, x) / e for (_, _, _, e, s, x) in pts)
    print(f"smallest model / error over {len(pts)} points: {worst:.3f}")
    for (case, n, dt, e, s, x) in pts:
        m = model(c, s, x)
        print(f"{case:24s} {n:4d} {dt:6.3f} e {e:.1e} model {m:.1e} ratio {m / e:5.1f} "
              f"(still {s:.1e}, step {c[0] * x['t']:.1e}, mesh {min(c[2] * x['k2'], c[1] * x['k4']):.1e}, "
              f"floor {c[3] + c[4] * x['c']:.1e})")
    return 0


if __name__ == "__main__":
    main()
