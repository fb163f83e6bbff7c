"""The still-water error model of the accuracy knob searched over its forms and constants on the
committed runs (docs/theory.md §16.8, the rule of §16.2): the knob's own arithmetic (src/sim/accuracy.rs
space_error, time_error, cost and the choice) evaluated over docs/accuracy_runs.csv, no run made.

    riser-tools accuracy-search [--bin target/fasttest/riser] [--runs docs/accuracy_runs.csv]

For each heave case the scales are read from the binary's own choice (`--json`'s `accuracy`
object) and the statics' top tension on each mesh of the ladder (`riser statics --set
n_elements=N`, the departure check of §16.7). Points: every grid and ladder run of the eight heave
cases with at least 75 steps a period, Δt ≥ 0.0125 s and e ≥ 1e-4 (the jumper at 10 s in its later window),
the still cases' grid runs at or above 1e-4, and the still steel catenary's static departures at or
above 1e-4 (its run is its statics: no current). A model is admissible if it bounds every point; its
work is the geometric mean of the work model (cost) of its choices over the eight cases at the ten
targets. Printed: the bend's two mesh terms summed, in quadrature or the larger (each with its
least C_t), the touchdown's still part A_s (each with its least C_c2, C_c and C_t), the powers p, q
of the motion's mesh term C_d (A ω²/g)^p (h κ)^q, a step term falling with the mesh (A ω)(ω Δt)²
[C_t + C_th g(n)] at 75 and 100 steps a period (not the knob's: docs/theory.md §16.8, "The step term's
forms searched again"), the crate's constants' smallest model/error, and their choices at 1e-2,
1e-3, 1e-4 with the work over the cheapest grid cell reaching the target.
"""
from __future__ import annotations

import argparse
import csv
import math
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, replace

from . import accuracy as A

# src/sim/accuracy.rs ELEMENT_LADDER, STEP_LADDER, SAFETY, MIN_STEPS_PER_PERIOD, MAX_TARGET,
# MAX_TOUCHDOWN_ELEMENT
ELEMENT_LADDER = (10, 12, 16, 20, 24, 30, 40, 50, 60, 80, 100, 120, 160, 200, 240, 320, 400, 480, 640, 800)
STEP_LADDER = (0.2, 0.15, 0.1, 0.075, 0.05, 0.04, 0.03, 0.025, 0.02, 0.015, 0.0125)
SAFETY = 1.5
MAX_TARGET = 1e-2
MAX_TOUCHDOWN_ELEMENT = 1.2
TARGETS = (1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 3e-4, 2e-4, 1.5e-4, 1.2e-4, 1e-4)
# the meshes the statics is solved on for the departure check (those the choices reach)
STATIC_MESHES = (10, 12, 16, 20, 24, 30, 40, 50, 60, 80, 100, 120, 160)
HEAVE_CASES = tuple(A.EXTRA_TARGETS)
FLOOR = 1e-4


@dataclass(frozen=True)
class Model:
    """(16.9) and its variants: combine "sum" (16.8), "rss" (16.9) or "max" of the bend's two mesh
    terms; the touchdown's term times (A ω²/g + a_s) if `touchdown_motion`, else static."""
    c_k: float = 7.4e-4
    c_c2: float = 8.3e-3
    c_c: float = 1.92e-2
    a_s: float = 0.02
    c_d: float = 0.03
    c_t: float = 0.137
    combine: str = "rss"
    touchdown_motion: bool = True
    # the powers p, q of C_d (A ω²/g)^p (h κ)^q (1 and 3 in the knob)
    accel_power: float = 1.0
    bend_power: float = 3.0
    # a step term that falls with the mesh, (A ω)(ω Δt)² [C_t + C_th g(n)] (not the knob's: C_th 0), g
    # one of STEP_MESH_FACTORS; and the fewest steps a period taken (the knob's 75)
    c_th: float = 0.0
    step_mesh: str = "10/n"
    steps_per_period: float = A.STEPS_PER_PERIOD


# the candidate mesh factors g(n) of a step term (A ω)(ω Δt)² [C_t + C_th g(n)] (docs/theory.md §16.8,
# "The step term's forms searched again"): the coarse meshes' steps err most (the catenary at 10 s: 10
# elements 4 times its 20 at 0.075 s)
STEP_MESH_FACTORS = {
    "10/n": lambda s, n: 10.0 / n,
    "(10/n)^2": lambda s, n: (10.0 / n) ** 2,
    "h kappa": lambda s, n: s.length / n * s.curvature,
    "(h kappa)^2": lambda s, n: (s.length / n * s.curvature) ** 2,
}


@dataclass
class Case:
    name: str
    length: float
    curvature: float
    bending_length: float | None
    amplitude: float
    omega: float
    period: float
    acceleration: float
    departures: dict
    buoyancy_tens: bool


def space_error(m: Model, s: Case, n: int) -> float:
    h = s.length / n
    contact = 0.0
    if s.bending_length:
        x = h / s.bending_length
        contact = min(m.c_c2 * x * x, m.c_c * x ** 4)
        if m.touchdown_motion:
            contact *= s.acceleration + m.a_s
    bend = m.c_k * (h * s.curvature) ** 4
    dynamic = m.c_d * s.acceleration ** m.accel_power * (h * s.curvature) ** m.bend_power
    mesh = {"sum": bend + dynamic, "rss": math.hypot(bend, dynamic), "max": max(bend, dynamic)}[m.combine]
    return mesh + contact


def time_error(m: Model, s: Case, dt: float, n: int) -> float:
    if s.amplitude == 0.0:
        return 0.0
    c = m.c_t + (m.c_th * STEP_MESH_FACTORS[m.step_mesh](s, n) if m.c_th else 0.0)
    return c * s.amplitude * s.omega * (s.omega * dt) ** 2


def cost(n: int, dt: float) -> float:
    return n * min(2.0 + 40.0 * dt, 7.0) / dt


def choose(m: Model, s: Case, target: float) -> tuple[int, float] | None:
    """The knob's choice (src/sim/accuracy.rs choose, nothing pinned): the cheapest ladder point whose
    predicted error is within target/SAFETY, a mesh whose statics departs by more than SAFETY times
    its model skipped, a smaller departure counted as its mesh term; on the seabed no element longer
    than MAX_TOUCHDOWN_ELEMENT bending lengths (docs/theory.md §16.9). The knob's kink cap
    (MAX_STATIC_KINK, §16.10) is not repeated: on the study's cases the meshes it excludes (the lazy
    wave's 30 elements) depart in top tension too."""
    budget = min(target, MAX_TARGET) / SAFETY
    ns = [n for n in ELEMENT_LADDER if (not s.buoyancy_tens or n % 10 == 0)
          and (not s.bending_length or s.length / n <= MAX_TOUCHDOWN_ELEMENT * s.bending_length)]
    dts = [dt for dt in STEP_LADDER if dt * m.steps_per_period <= s.period * (1 + 1e-9)]
    cands = sorted((cost(n, dt), n, dt) for n in ns for dt in dts
                   if space_error(m, s, n) + time_error(m, s, dt, n) <= budget)
    for _, n, dt in cands:
        model, dep = space_error(m, s, n), s.departures.get(n, 0.0)
        if dep > SAFETY * model:
            continue
        if max(dep, model) + time_error(m, s, dt, n) <= budget:
            return n, dt
    return None



def top_row_tension(binary: str, scene: str, n: int) -> float:
    """The static line's tension at the hang-off on n elements, as src/sim/accuracy.rs
    static_mesh_error reads it: the shape's first row (the top force's magnitude differs from it by the
    top element's shear where the mesh kinks the line)."""
    return A.json_of([binary, "statics", scene, "--set", f"n_elements={n}", "--json"])["shape"][0][4]


def case_scales(binary: str, name: str) -> Case:
    d = A.choice(binary, name, ["accuracy=1e-2"])
    scene = A.CASES[name][0]
    # the statics on each mesh, one binary per core at a time (independent runs)
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        tops = dict(zip(STATIC_MESHES, pool.map(lambda n: top_row_tension(binary, scene, n), STATIC_MESHES)))
    # the departure's base: the scales' mesh, the scene's own of at least 60 elements (src/sim/accuracy.rs
    # scales, static_mesh_error)
    base_n = max(A.json_of([binary, "statics", scene, "--json"])["n_elements"], 60)
    base = tops.get(base_n) or top_row_tension(binary, scene, base_n)
    period = d["motion_period"] if d["motion_period"] is not None else math.inf
    return Case(name=name, length=d["length"], curvature=d["max_curvature"],
                bending_length=d["touchdown_bending_length"], amplitude=d["motion_amplitude"] or 0.0,
                omega=2 * math.pi / period, period=period, acceleration=d["acceleration_ratio"],
                departures={n: abs(t - base) / base for n, t in tops.items()},
                buoyancy_tens=scene.startswith("lazy_wave"))


def points(rows: list, cases: dict, binary: str) -> list:
    """(case, n, Δt, e) the model must bound (module docstring)."""
    out = []
    for name, s in cases.items():
        ref = next(r for r in rows if r["case"] == name and r["kind"] == "reference")
        still = name in A.STILL_CASES
        for r in rows:
            if r["case"] != name or r["completed"] != "True" or r["kind"] not in (("grid",) if still else ("grid", "ladder")):
                continue
            n, dt = int(r["n_elements"]), float(r["time_step"])
            if not still and (dt * A.STEPS_PER_PERIOD > s.period * (1 + 1e-9) or dt < A.REF_STEP - 1e-12):
                continue
            e = A.error(r, ref)
            if e >= FLOOR:
                out.append((name, n, dt, e))
    # the still steel catenary: its statics against the converged line (its reference's mesh)
    steel = cases["steel_catenary"]
    ref_top = A.json_of([binary, "statics", "steel_catenary", "--set", "n_elements=320", "--json"])["top_tension"]
    for n in STATIC_MESHES:
        top = A.json_of([binary, "statics", "steel_catenary", "--set", f"n_elements={n}", "--json"])["top_tension"]
        e = abs(top - ref_top) / ref_top
        if e >= FLOOR:
            cases.setdefault("steel_still", replace(steel, name="steel_still", amplitude=0.0, acceleration=0.0,
                                                    omega=0.0, period=math.inf))
            out.append(("steel_still", n, 0.1, e))
    return out


def smallest_ratio(m: Model, cases: dict, pts: list) -> float:
    """The smallest model/error over the points: ≥ 1 if the model bounds them all."""
    return min((space_error(m, cases[c], n) + time_error(m, cases[c], dt, n)) / e for c, n, dt, e in pts
               if dt * m.steps_per_period <= cases[c].period * (1 + 1e-9))


def least(m: Model, field: str, cases: dict, pts: list, hi: float = 10.0) -> Model | None:
    """m with the least value of `field` that bounds every point (None: not even `hi`)."""
    if smallest_ratio(replace(m, **{field: hi}), cases, pts) < 1.0:
        return None
    lo = 0.0
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        if smallest_ratio(replace(m, **{field: mid}), cases, pts) < 1.0:
            lo = mid
        else:
            hi = mid
    return replace(m, **{field: hi})


def jointly(m: Model, cases: dict, pts: list, rounds: int = 4) -> Model | None:
    """The least C_t, C_c2 and C_c together: C_t first, the least with the touchdown's term unbounded
    (what the lines off the seabed need), then C_c2 and C_c each the least with the others as they
    stand, then C_t again, in turn until they settle; None if no C_c2 or C_c bounds the points."""
    m = least(replace(m, c_c2=1e9, c_c=1e9), "c_t", cases, pts)
    if m is None:
        return None
    for _ in range(rounds):
        c2, c4 = least(replace(m, c_c=1e9), "c_c2", cases, pts), least(replace(m, c_c2=1e9), "c_c", cases, pts)
        if c2 is None or c4 is None:
            return None
        m = least(replace(m, c_c2=c2.c_c2, c_c=c4.c_c), "c_t", cases, pts)
    return m


def work(m: Model, cases: dict) -> float:
    """The geometric mean of the work model over the heave cases' choices at the ten targets (a target
    no choice reaches, which the knob refuses, counts as the ladder's dearest point)."""
    refused = cost(ELEMENT_LADDER[-1], STEP_LADDER[-1])
    logs = []
    for name in HEAVE_CASES:
        for t in TARGETS:
            c = choose(m, cases[name], t)
            logs.append(math.log(cost(*c) if c else refused))
    return math.exp(sum(logs) / len(logs))


def cheapest_cell(rows: list, name: str, target: float) -> tuple[int, float] | None:
    ref = next(r for r in rows if r["case"] == name and r["kind"] == "reference")
    ok = [(cost(int(r["n_elements"]), float(r["time_step"])), int(r["n_elements"]), float(r["time_step"]))
          for r in rows if r["case"] == name and r["kind"] == "grid" and r["completed"] == "True"
          and A.error(r, ref) <= target]
    return min(ok)[1:] if ok else None


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="riser-tools accuracy-search", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/fasttest/riser")
    ap.add_argument("--runs", default="docs/accuracy_runs.csv")
    args = ap.parse_args(argv)
    rows = list(csv.DictReader(open(args.runs)))
    cases = {name: case_scales(args.bin, name) for name in HEAVE_CASES + tuple(A.STILL_CASES)}
    pts = points(rows, cases, args.bin)
    print(f"{len(pts)} points")
    before = Model(c_c2=1.0e-3, c_c=2.4e-3, c_t=0.134, combine="sum", touchdown_motion=False)
    w0 = work(before, cases)
    print(f"(16.8), the model of §16.7: smallest model/error {smallest_ratio(before, cases, pts):.4f}, work {w0:.1f}")
    print("the bend's two mesh terms (the touchdown's static), each with its least C_t:")
    for combine in ("sum", "rss", "max"):
        m = least(replace(before, combine=combine), "c_t", cases, pts)
        print(f"  {combine}: C_t {m.c_t:.4f}, work {work(m, cases) / w0:.3f} of (16.8)'s")
    print("the touchdown's factor A w^2/g + A_s, in quadrature, each A_s with its least C_c2, C_c, C_t:")
    for a_s in (0.0, 0.005, 0.01, 0.015, 0.02, 0.025, 0.03, 0.04):
        m = jointly(Model(a_s=a_s), cases, pts)
        if m is None:
            print(f"  A_s {a_s}: no C_c2, C_c bounds the points")
            continue
        print(f"  A_s {a_s}: C_c2 {m.c_c2:.4g}, C_c {m.c_c:.4g}, C_t {m.c_t:.4f}, work {work(m, cases) / w0:.3f}")
    print("the motion's mesh term C_d (A w^2/g)^p (h kappa)^q, each with its least C_t, C_c2, C_c (the best three):")
    scan = []
    for p in (1.0, 1.5, 2.0):
        for q in (3.0, 3.5):
            for c_d in (0.03, 0.05, 0.1, 0.2, 0.3, 0.5, 0.8):
                m = jointly(Model(c_d=c_d, accel_power=p, bend_power=q), cases, pts)
                if m is not None:
                    scan.append((work(m, cases) / w0, m))
    for w, m in sorted(scan, key=lambda x: x[0])[:3]:
        print(f"  p {m.accel_power:g}, q {m.bend_power:g}, C_d {m.c_d:g}: C_t {m.c_t:.4f}, work {w:.3f}")
    print("the step term falling with the mesh, (A w)(w dt)^2 [C_t + C_th g(n)], each with its least C_t, C_c2, "
          "C_c; the worst work ratio of the four lines at their own motions over the cheapest grid cell, at "
          "1e-2, 1e-3, 1e-4:")
    own = ("catenary", "lazy_wave", "steel_catenary", "lowe_langley_jumper")
    for spp in (A.STEPS_PER_PERIOD, 100.0):
        for g in STEP_MESH_FACTORS:
            for c_th in (0.0, 0.05, 0.1, 0.13):
                if c_th == 0.0 and g != "10/n":
                    continue
                m = jointly(Model(c_th=c_th, step_mesh=g, steps_per_period=spp), cases, pts)
                if m is None:
                    print(f"  {spp:g} steps a period, g {g}, C_th {c_th:g}: no C_c2, C_c bounds the points")
                    continue
                worst = max(cost(*choose(m, cases[k], t)) / cost(*cheapest_cell(rows, k, t))
                            for k in own for t in (1e-2, 1e-3, 1e-4))
                steel = cost(*choose(m, cases["steel_catenary"], 1e-4)) / cost(*cheapest_cell(rows, "steel_catenary", 1e-4))
                print(f"  {spp:g} steps a period, " + ("no mesh factor" if c_th == 0.0 else f"g {g}, C_th {c_th:g}")
                      + f": C_t {m.c_t:.4f}, work {work(m, cases) / w0:.3f}, worst {worst:.2f}, "
                      f"the steel catenary at 1e-4 {steel:.2f}")
    m = Model()
    print(f"(16.9) with the crate's constants: smallest model/error {smallest_ratio(m, cases, pts):.4f}, "
          f"work {work(m, cases) / w0:.3f} of (16.8)'s")
    for name in HEAVE_CASES:
        cells = []
        for t in (1e-2, 1e-3, 1e-4):
            c, g = choose(m, cases[name], t), cheapest_cell(rows, name, t)
            cells.append(f"{t:g}: {c[0]}, {c[1]:g} s ({cost(*c) / cost(*g):.2f})" if c and g else f"{t:g}: -")
        print(f"  {name:24s} " + "   ".join(cells))
    return 0


if __name__ == "__main__":
    main()
