"""riser_tools, the package that drives riser from outside: its MoorDyn driver against a
case with a known answer, its references against riser, and its case, grid and spec code
against bad input (each refused naming the field)."""

import math
import subprocess

import numpy as np
import pytest

from riser_tools import moordyn, reference
from riser_tools.cases import CATENARY, STEEL_CATENARY, Case, CaseError, Line, Motion, product, unique_labels
from riser_tools.cli import CliError, read_columns, run_command, statics


# --------------------------------------------------------------------------- the MoorDyn driver

def moordyn_static(tmp_path, line, nseg):
    path = moordyn.write_input(tmp_path / f"static_{nseg}" / "line.txt", line, nseg, 1e-3,
                               {"threshIC": 1e-6, **moordyn.NO_OUTPUT}, depth=200.0)
    return moordyn.static_state(path, line, nseg)


def test_moordyn_static_catenary_converges_to_the_elastic_catenary(tmp_path):
    """MoorDyn's static solve (its stationary initial-condition solver) of the catenary scene's
    line without bending, made soft (EA = 1e7 N: 1.4 % stretch, so the elastic term matters:
    the inextensible catenary is 5 % off in H) against Irvine's elastic catenary. A lumped-mass
    chain converges to the catenary at second order: at 40 segments H within 1e-3 and V within
    5e-4 (measured 4.4e-4 and 1.6e-4), the error falling 3 to 5 times from 20 to 40 segments
    (measured 4.0); the nodes within 2 cm of the closed-form shape."""
    line = CATENARY.replace(ei=0.0, ea=1e7)
    ref = reference.elastic_catenary(line.length, line.submerged_weight, line.ea, line.span, line.anchor[2])
    rigid = reference.elastic_catenary(line.length, line.submerged_weight, 1e13, line.span, line.anchor[2])
    assert abs(rigid.h / ref.h - 1) > 0.04            # the case tells an elastic line from a rigid one
    err = {}
    for nseg in (20, 40):
        st = moordyn_static(tmp_path, line, nseg)
        err[nseg] = (st.horizontal / ref.h - 1, st.vertical / ref.v_top - 1)
    assert abs(err[40][0]) < 1e-3 and abs(err[40][1]) < 5e-4, err
    assert 3.0 < err[20][0] / err[40][0] < 5.0, err
    # the nodes (MoorDyn's frame, anchor first) on the closed-form shape at the same arc length
    st = moordyn_static(tmp_path, line, 40)
    dist = []
    for i, node in enumerate(st.nodes):
        s = line.length * (1.0 - i / 40)
        x, z = reference.elastic_catenary_shape(line.submerged_weight, line.ea, ref, s)
        dist.append(math.hypot(node[0] - x, node[2] - (z - line.surface_z)))
    assert max(dist) < 0.02, max(dist)


def test_moordyn_run_holds_a_still_line_at_its_static_force(tmp_path):
    """A run with the fairlead held still (amplitude 0) from MoorDyn's own static state keeps
    the static fairlead force to 1e-3 over 2 s; the outputs land on the sample grid."""
    line = CATENARY.replace(ei=0.0, ea=1e7)
    path = moordyn.write_input(tmp_path / "still" / "line.txt", line, 20, 1e-3,
                               {"threshIC": 1e-6, **moordyn.NO_OUTPUT}, ba=1e5, depth=200.0)
    r = moordyn.run(path, line, 20, Motion(0.0, 10.0), 2.0, 1e-3, 0.01)
    assert r.ok and len(r.t) == 201 and np.all(np.isfinite(r.T))
    assert np.max(np.abs(r.T / r.T[0] - 1.0)) < 1e-3


# --------------------------------------------------------------------------- the references

def test_the_references_agree_with_riser_statics(riser_bin):
    """The Python port of tests/common/reference.rs against riser's cable statics: the catenary
    (no seabed) within 3e-4 of H and V at the scene's 60 elements, the steel catenary on a
    frictionless seabed within 5e-4 (the Rust tests' tolerances are 2e-4 on the rod)."""
    for scene, sets, ref in (
        ("catenary", ["model=cable"],
         reference.elastic_catenary(CATENARY.length, CATENARY.submerged_weight, CATENARY.ea, 60.0, -70.0)),
        ("steel_catenary", ["model=cable", "seabed_friction=0"],
         reference.catenary_on_seabed(STEEL_CATENARY.length, STEEL_CATENARY.submerged_weight, STEEL_CATENARY.ea,
                                      292.0, 200.0)),
    ):
        j = statics(riser_bin, scene, sets)
        h, v = j["top_force"][0], -j["top_force"][2]
        assert abs(h / ref.h - 1) < 5e-4 and abs(v / ref.v_top - 1) < 5e-4, (scene, h, ref.h, v, ref.v_top)


def test_the_seabed_catenary_lies_on_the_seabed():
    """The lying length closes the horizontal span: what is not lying spans the rest."""
    s = STEEL_CATENARY
    r = reference.catenary_on_seabed(s.length, s.submerged_weight, s.ea, 292.0, 200.0)
    assert 0 < r.lying < s.length
    assert abs(r.v_top - s.submerged_weight * (s.length - r.lying)) < 1e-6 * r.v_top


# --------------------------------------------------------------------------- bad input

@pytest.mark.parametrize("make, field", [
    (lambda: Motion(2.5, -20.0), "motion.period = -20.0"),
    (lambda: Motion(2.5, 20.0, axis="roll"), "motion.axis = 'roll'"),
    (lambda: Motion(float("nan"), 20.0), "motion.amplitude = nan"),
    (lambda: Motion(2.5, 20.0, ramp=-1.0), "motion.ramp = -1.0"),
    (lambda: Motion(2.5, 20.0, "surge", until=10.0), "motion.until"),
    (lambda: Motion(2.5, 20.0, duration=60.0, window=60.0), "motion.window = 60.0"),
    (lambda: Line(**{**CATENARY.__dict__, "mass": -1.0}), "line.mass = -1.0"),
    (lambda: Line(**{**CATENARY.__dict__, "anchor": (60.0, 0.0)}), "line.anchor"),
    (lambda: Line(**{**CATENARY.__dict__, "seabed_z": 5.0}), "line.seabed_z = 5.0"),
    (lambda: Case("a", "catenary", ("n_elements",)), "case a: sets: 'n_elements': expected name=value"),
    (lambda: Case("a", "catenary", "n_elements=10"), "case a: sets = 'n_elements=10'"),
    (lambda: Case("a", "catenary", duration=0.0), "case a: duration = 0.0"),
    (lambda: Case("", "catenary"), "case.label"),
    (lambda: unique_labels([Case("a", "catenary"), Case("a", "lazy_wave")]), "case a: label used twice"),
    (lambda: product(n_elements=[]), "grid.n_elements: an empty list"),
    (lambda: product(n_elements="10,20"), "grid.n_elements = '10,20'"),
    (lambda: product(time_step=[0.1, 0.1]), "grid.time_step: 0.1 appears twice"),
    (lambda: product(), "grid: no axes"),
    (lambda: run_command("riser", "catenary", ["=1"]), "sets: '=1'"),
    (lambda: moordyn.input_text(CATENARY, 0, 1e-3), "moordyn.nseg = 0"),
    (lambda: moordyn.input_text(CATENARY, 10, -1e-3), "moordyn.dtm = -0.001"),
    (lambda: moordyn.run("x", CATENARY, 10, Motion(1.0, 10.0), 1.0, 3e-3, 0.01), "moordyn.sample = 0.01"),
])
def test_cases_grids_and_the_moordyn_driver_refuse_bad_input_naming_the_field(make, field):
    with pytest.raises(CaseError) as e:
        make()
    assert str(e.value).startswith(field), str(e.value)


@pytest.mark.parametrize("call, field", [
    (lambda: reference.elastic_catenary(100.0, -1.0, 1e9, 60.0, -70.0), "w = -1.0"),
    (lambda: reference.elastic_catenary(100.0, 1e3, 1e9, 60.0, math.inf), "dz = inf"),
    (lambda: reference.catenary_on_seabed(400.0, 1e3, 3e9, 292.0, 0.0), "depth = 0.0"),
    (lambda: reference.catenary_on_seabed(400.0, 1e3, 3e9, 500.0, 200.0), "catenary_on_seabed: no touchdown"),
])
def test_the_references_refuse_bad_input_naming_the_argument(call, field):
    with pytest.raises(reference.ReferenceError) as e:
        call()
    assert str(e.value).startswith(field), str(e.value)


@pytest.mark.parametrize("text, field", [
    ("[run]\nduration = -10.0\n", "run.duration"),
    ("[run]\nduration = 10.0\ncommunication_step = 0.3\n", "run.duration"),
    ("[run]\nduration = 10.0\n[motion]\nheave_amplitude = \"big\"\n", "motion.heave_amplitude"),
    ("[run]\nduration = 10.0\n[motion]\nheave_periode = 10.0\n", "motion.heave_periode"),
    ("[run]\nduration = 10.0\n[outputs]\nwindow = [20.0, 5.0]\n", "outputs.window"),
    ("[run]\nduration = 10.0\n[grid]\nn_elements = { start = 10, stop = 40 }\n", "grid.n_elements"),
    ("[run]\nduration = 10.0\n[grid]\nmode = \"diagonal\"\nn_elements = [10]\n", "grid.mode"),
    ("[runn]\nduration = 10.0\n", "runn"),
    ("[parameters]\nn_elements = 10\n", "run"),
])
def test_a_spec_refuses_bad_input_naming_the_field(tmp_path, fmu_path, text, field):
    """riser-sweep's spec (riser_sweep.spec.load_spec) with the FMU under test (its variables name
    the parameters): each error's message starts with the field (the grid's FMU checks are
    test_sweep.py's)."""
    from riser_sweep import SpecError, load_spec
    p = tmp_path / "spec.toml"
    p.write_text(text)
    with pytest.raises(SpecError) as e:
        load_spec(p, fmu=fmu_path)
    assert field in str(e.value).split(":")[0], str(e.value)


def test_the_cli_driver_reports_a_failing_run(riser_bin, tmp_path):
    """A run riser refuses is a CliError carrying riser's message (the field and its range)."""
    from riser_tools import cli
    with pytest.raises(CliError) as e:
        cli.run(riser_bin, "catenary", {"n_elements": 0}, Motion(1.0, 10.0), 1.0, tmp_path / "x")
    assert "n_elements" in str(e.value)
    r = cli.run(riser_bin, "catenary", {"n_elements": 4, "model": "cable"}, Motion(1.0, 10.0, ramp=5.0), 2.0,
                tmp_path / "ok")
    assert r.summary["completed"] and set(read_columns(tmp_path / "ok" / "timeseries.csv")) >= {"t", "top_tension"}
    assert subprocess.run([riser_bin, "--version"], capture_output=True).returncode == 0


def test_a_spec_without_window_takes_each_cases_steady_window(tmp_path, fmu_path):
    """Issue 31: without `outputs.window` a case's statistics are over its steady window,
    as `riser run`'s (the ramp plus the longest period of what moves, to the end); an
    explicit window wins; a run too short for one is reduced whole."""
    from riser_sweep import load_spec
    p = tmp_path / "spec.toml"
    p.write_text(f'fmu = "{fmu_path}"\n[motion]\nheave_amplitude = 2.0\nsurge_amplitude = 1.0\nsurge_period = 12.0\n'
                 'ramp = 5.0\n[run]\nduration = 60.0\n[grid]\nheave_period = [8.0, 20.0, 60.0]\n')
    spec = load_spec(p)
    windows = [spec.job(c)["window"] for c in spec.cases]
    assert windows == [(17.0, 60.0), (25.0, 60.0), (0.0, 60.0)], windows
    p.write_text(p.read_text() + "[outputs]\nwindow = [30.0, 60.0]\n")
    spec = load_spec(p)
    assert all(spec.job(c)["window"] == (30.0, 60.0) for c in spec.cases)


def test_the_demo_couples_riser_to_the_six_degree_of_freedom_vessel(tmp_path, fmu_path):
    """Issue 30: `make demo`'s second part, shortened to 5 s: riser 30 m forward of the reference
    point of osp/vessel/Vessel6.py, both ways in libcosim at 0.05 s. Its CSV has the pose, the top
    tension, force and moment at every step to the end, all finite; the vessel moved; the moment
    about the reference point is (R ρ) × F at the recorded pose within 1e-3 of |ρ| max |F|
    (as test_coupling6.py's moment_error), computed here from the CSV."""
    from riser_tools.coupling_loop import rotation
    from riser_tools.studies.demo import VESSEL_COLUMNS, vessel_coupling

    res = vessel_coupling(fmu_path, tmp_path, duration=5.0)
    assert res["rotations"] and (tmp_path / "vessel_coupling.png").stat().st_size > 0
    cols = read_columns(tmp_path / "vessel_coupling.csv")
    assert list(cols) == VESSEL_COLUMNS
    c = {k: np.asarray(v, dtype=float) for k, v in cols.items()}
    assert len(c["t"]) == 100 and np.allclose(c["t"], 0.05 * np.arange(1, 101)), c["t"][[0, -1]]
    assert all(np.all(np.isfinite(x)) for x in c.values())
    assert np.ptp(c["heave"]) > 1e-3 and np.ptp(c["roll"]) > 1e-4 and c["top_tension"].min() > 1e5
    rho = np.array([30.0, 0.0, 0.0])
    f = np.stack([c[f"top_force_{k}"] for k in "xyz"], axis=1)
    m = np.stack([c[f"top_moment_{k}"] for k in "xyz"], axis=1)
    arm = np.array([rotation(a, b, y) @ rho for a, b, y in zip(c["roll"], c["pitch"], c["yaw"])])
    err = np.max(np.abs(m - np.cross(arm, f))) / (np.linalg.norm(rho) * np.max(np.linalg.norm(f, axis=1)))
    assert err <= 1e-3 and abs(err - res["moment_error"]) <= 1e-6, (err, res["moment_error"])


# --------------------------------------------------------------------------- the accuracy knob's step term

def test_a_step_form_that_generates_the_points_has_spread_one():
    """step_envelopes/spread (riser-tools accuracy-fit --still): points made by C M (ω Δt)^c with one C
    for two cases of different scales give each case the constant C, spread 1; another exponent
    does not."""
    from riser_tools.studies.accuracy_fit import spread, step_envelopes

    def scale(q):
        return q["A"] / 10

    cases = {}
    for name, amp, period in (("a", 2.5, 20.0), ("b", 10.0, 27.0)):
        q = dict(A=amp, w=2 * math.pi / period)
        pts = [(20, dt, None, 0.07 * scale(q) * (q["w"] * dt) ** 1.5) for dt in (0.2, 0.1, 0.05)]
        cases[name] = (q, pts)
    env = step_envelopes(cases, scale, 1.5)
    assert env == pytest.approx({"a": 0.07, "b": 0.07}, rel=1e-12)
    assert spread(env) == pytest.approx(1.0, rel=1e-12)
    assert spread(step_envelopes(cases, scale, 1.0)) > 1.1


def test_without_the_current_s_jolt_the_hang_off_s_acceleration_varies_least_across_the_lines(riser_bin):
    """docs/theory.md 16.3, "The step term's form", and §16.7: over the committed grid runs (the current
    grown over current_ramp), the hang-off's acceleration A ω²/g brings the five calibration cases'
    step constants within 1.82 of each other at c = 1 (2.43 at c = 2), its velocity A ω (the knob's
    scale, the least costly by the rule of §16.2) within 3.08 at c = 1.25 (4.36 at 2), every other
    scale within no less than 4; A/A0, the knob's before, spreads 9.55-fold at c = 3/2. With the
    current's jolt (before §16.7) A/A0 spread least, 5.45-fold, the acceleration 7.4-fold: the jolt's
    ringing, which the step resolved worst, was on the two lines with a current."""
    from riser_tools.studies import accuracy_fit as F

    rows = list(F.csv.DictReader(open(F.A.Path(__file__).resolve().parents[2] / "docs" / "accuracy_runs.csv")))
    cases = {}
    for case in F.STEP_CASES:
        q = F.step_scales(riser_bin, case)
        cases[case] = (q, F.step_points(rows, case, q))
    spreads = {(name, c): F.spread(F.step_envelopes(cases, f, c))
               for name, (_, f) in F.STEP_FORMS.items() for c in (1.0, 1.25, 1.5, 2.0)}
    assert spreads[("amplitude", 1.5)] == pytest.approx(9.55, abs=0.01)
    assert min(spreads, key=spreads.get) == ("acceleration", 1.0)
    assert spreads[("acceleration", 1.0)] == pytest.approx(1.82, abs=0.01)
    assert spreads[("acceleration", 2.0)] == pytest.approx(2.43, abs=0.01)
    assert spreads[("velocity", 2.0)] == pytest.approx(4.36, abs=0.01)
    assert min(v for (name, _), v in spreads.items() if name == "velocity") == pytest.approx(3.08, abs=0.01)
    assert all(v > 4.0 for (name, _), v in spreads.items() if name not in ("acceleration", "velocity")), spreads


def test_the_ladder_runs_every_knob_step_with_75_steps_a_period(monkeypatch):
    """riser-tools accuracy --phase ladder: each heave case's meshes at every step of the knob's
    STEP_LADDER (src/sim/accuracy.rs), from 0.2 s down to its shortest, 0.0125 s (the references'),
    and at 0.01 s, the step below it that the knob no longer takes, that leaves at least 75 steps a
    period of its motion: the catenary at 10 s from 0.1 s (10/75 = 0.133 s), at 20 s from 0.2 s."""
    from riser_tools.studies import accuracy as A

    text = open(A.Path(__file__).resolve().parents[2] / "src" / "sim" / "accuracy.rs").read()
    ladder = text[text.index("pub const STEP_LADDER"):].split("[", 2)[2].split("]")[0]
    knob = [float(x) for x in ladder.split(",")]
    assert knob[-1] == A.REF_STEP == 0.0125
    assert A.LADDER_STEPS == knob + [0.01]
    calls = []
    monkeypatch.setattr(A, "one", lambda binary, path, rows, case, kind, n, dt, tol: calls.append((case, n, dt)))
    A.ladder("riser", None, [])
    steps = {(c, n): [dt for (c2, n2, dt) in calls if (c2, n2) == (c, n)] for (c, n, _) in calls}
    assert steps[("catenary_T10", 10)] == [0.1, 0.075, 0.05, 0.04, 0.03, 0.025, 0.02, 0.015, 0.0125, 0.01]
    assert steps[("catenary", 10)] == A.LADDER_STEPS
    assert set(steps) == {(c, n) for c, ns in A.LADDER.items() for n in ns}


def test_the_fit_tool_keeps_the_knob_s_constants():
    """riser-tools accuracy-fit evaluates the error model with its own copy of the constants of
    src/sim/accuracy.rs (the still-water ones under the wave terms, and the wave ones): they must be
    the crate's, or its envelopes check another model."""
    import re

    from riser_tools.studies import accuracy_fit as F

    text = open(F.A.Path(__file__).resolve().parents[2] / "src" / "sim" / "accuracy.rs").read()

    def const(name):
        return float(re.search(rf"pub const {name}: f64 = ([0-9.e+-]+);", text).group(1))

    assert (F.C_K, F.C_T, F.C_D) == (const("C_CURVATURE"), const("C_TIME"), const("C_DYNAMIC_MESH"))
    assert (F.C_K2, F.C_C, F.A_S) == (const("C_CONTACT2"), const("C_CONTACT"), const("A_TOUCHDOWN_STILL"))
    assert F.CONSTANTS[:4] == tuple(const(n) for n in ("C_WAVE_TIME", "C_WAVE_MESH", "C_WAVE_MESH2", "WAVE_FLOOR"))
    # the step term's order (16.2): (ω Δt)² in time_error, and no current's ringing E_c (§16.7)
    assert F.STEP_ORDER == 2.0 and "(s.omega * dt).powi(2)" in text
    assert F.CONSTANTS[4] == 0.0 and "C_CURRENT_RINGING" not in text


def test_the_2x_cost_aim_needs_a_model_within_1_5_times_of_every_run_s_error():
    """docs/theory.md §16.3, "What a perfect model would cost", on the committed runs
    (docs/accuracy_runs.csv): a model that knew every grid and ladder run's error and kept the knob's
    safety factor (1.5) would choose, at 1e-2, 1e-3 and 1e-4 in all eight heave cases, within 2.03
    times the work of the cheapest grid cell reaching the target (the aim: 2), and never above its
    target over 1.5; one that over-predicts by up to 1.5 times more costs 2.02 at 1e-3 on the built-in
    scenes and 2.62 on the design motion: the aim needs a model within about 1.5 times of every run's
    error, where the a-priori step terms tried spread at least 1.8 times across the lines (the
    acceleration; the knob's velocity 3.1). (With the current's jolt, before §16.7: 2.06, 3.5, and one
    line with no run within 1e-4 over 2.25.)"""
    import csv

    from riser_tools.studies import accuracy_fit as F

    rows = list(csv.DictReader(open(F.A.Path(__file__).resolve().parents[2] / "docs" / "accuracy_runs.csv")))
    exact = [F.oracle(rows, c, t) for c in F.ORACLE_CASES for t in (1e-2, 1e-3, 1e-4)]
    assert all(o is not None for o in exact)
    assert max(o["oracle_ratio"] for o in exact) <= 2.1
    assert all(o["oracle"][2] <= t / F.SAFETY for o, t in zip(exact, [1e-2, 1e-3, 1e-4] * 8))
    # the knob itself (docs/theory.md §16.8, by the grid's measure, the grid at 1e-8 and the knob at the
    # target's square, 1e-6 at 1e-2 and 1e-3): above 2 at 1e-4 on the steel catenary (2.98; 3.52 before
    # §16.8), at 1e-3 on the lazy wave at 10 s (2.08) and at 1e-4 at 10 s on the lazy wave (2.44) and the
    # jumper (2.06); within 2 at every target on the built-in scenes and the jumper at their own motions
    # but that one (the steel catenary at 1e-3 1.18, 2.53 before; the lazy wave at 1e-2 0.62, 1.77
    # before), and at 1e-4 at 10 s on the catenary (1.79) and the steel catenary (1.95)
    knob = {(c, t): F.oracle(rows, c, t)["knob_ratio"] for c in F.ORACLE_CASES for t in (1e-2, 1e-3, 1e-4)}
    own = ("catenary", "lazy_wave", "steel_catenary", "lowe_langley_jumper")
    assert knob[("steel_catenary", 1e-4)] > 2
    assert max(v for (c, t), v in knob.items() if c in own and (c, t) != ("steel_catenary", 1e-4)) < 2
    assert max(knob[(c, 1e-4)] for c in ("catenary_T10", "steel_catenary_T10")) < 2
    loose = [F.oracle(rows, c, 1e-3, safety=1.5 * F.SAFETY) for c in F.ORACLE_CASES]
    assert max(o["oracle_ratio"] for o in loose[:4]) > 2.0 and max(o["oracle_ratio"] for o in loose[4:]) > 2.5


def test_the_like_for_like_cost_ratio_runs_the_grid_at_the_knob_s_tolerance():
    """docs/accuracy.md's last column (docs/theory.md §16.3, "The Newton tolerance"): the grid's cells
    run again at the knob's Newton tolerance where it is not the grid's 1e-8 (kind grid_tol, committed
    in docs/accuracy_runs.csv). The steel catenary at 1e-3: the knob at 1e-6 against its cheapest cell,
    20 elements at 0.2 s, 1.94 (1.18 against the same cell at 1e-8; 2.16 at 1e-7 before the tolerance
    was the target's square, 3.15 before the touchdown's term followed the motion, docs/theory.md
    §16.8); the catenary at 10 s at 1e-3: 10 elements at 0.2 s, 1.61 (1.86 at 1e-7; with the current's
    jolt, before docs/theory.md §16.7, they reached it at 1e-8 but not at 1e-7, and the next cell
    counted)."""
    import csv

    from riser_tools.studies import accuracy as A

    rows = list(csv.DictReader(open(A.Path(__file__).resolve().parents[2] / "docs" / "accuracy_runs.csv")))

    def ratio(case, target):
        ref = next(r for r in rows if r["case"] == case and r["kind"] == "reference")
        knob = next(r for r in rows if r["case"] == case and r["kind"] == "accuracy" and r["accuracy"]
                    and abs(float(r["accuracy"]) / target - 1) < 1e-9)
        tol = float(knob["newton_tolerance"])
        assert not A.same_tolerance(tol, A.GRID_TOL)
        cell = A.cheapest_at_tolerance(rows, case, ref, target, tol)
        assert cell is not None and A.error(cell, ref) <= target
        return cell, A.work(knob) / A.work(cell)

    cell, r = ratio("steel_catenary", 1e-3)
    assert (cell["n_elements"], float(cell["time_step"])) == ("20", 0.2) and abs(r - 1.94) < 0.01, (cell, r)
    cell, r = ratio("catenary_T10", 1e-3)
    assert (cell["n_elements"], float(cell["time_step"])) == ("10", 0.2) and abs(r - 1.61) < 0.01, (cell, r)


def test_the_window_time_mean_is_over_exactly_the_window():
    """riser_tools.series.window_time_mean (riser-sweep's top_tension_mean), as `riser run`'s
    window_min_mean_max: on a + b sin(ω t + 0.7) at a step that falls on neither end of a two-period
    window the interpolant's mean is a within the trapezoid rule's b (ω Δt)²/12, where the samples
    inside alone are off by more than 20 times that; where the samples fall on both ends it is
    time_mean of the samples inside."""
    import numpy as np

    from riser_tools.series import in_window, time_mean, window_time_mean

    a, b, period, dt = 140e3, 4e3, 20.0, 0.03
    w = 2 * np.pi / period
    t = np.arange(3001) * dt
    y = a + b * np.sin(w * t + 0.7)
    bound = b * (w * dt) ** 2 / 12
    assert abs(window_time_mean(t, y, 20.0, 60.0) - a) <= bound
    m = in_window(t, 20.0, 60.0)
    assert abs(time_mean(t[m], y[m]) - a) > 20 * bound
    t2 = np.arange(401) * 0.1
    y2 = a + b * np.cos(w * t2)
    m2 = in_window(t2, 10.0, 40.0)
    assert window_time_mean(t2, y2, 10.0, 40.0) == pytest.approx(time_mean(t2[m2], y2[m2]), rel=1e-12)


def test_the_search_tool_is_the_knob_s_arithmetic(riser_bin):
    """riser-tools accuracy-search (docs/theory.md §16.8) evaluates the error model with its own copy
    of src/sim/accuracy.rs: its default model must be the crate's constants, its choices the binary's
    for the eight heave cases at the ten targets and its mesh term the binary's with the mesh pinned
    (scales and statics' departures read from the binary), and the crate's constants must bound every point of the fit's rule (the smallest model
    over error at least 1) at 0.962 of the work of (16.8), the model of §16.7 (0.959 before the
    seabed's element cap of §16.9)."""
    import csv
    import re
    from dataclasses import replace

    from riser_tools.studies import accuracy_search as S

    root = S.A.Path(__file__).resolve().parents[2]
    text = open(root / "src" / "sim" / "accuracy.rs").read()

    def const(name):
        return float(re.search(rf"pub const {name}: f64 = ([0-9.e+-]+);", text).group(1))

    m = S.Model()
    assert (m.c_k, m.c_c2, m.c_c, m.a_s, m.c_d, m.c_t) == tuple(const(n) for n in (
        "C_CURVATURE", "C_CONTACT2", "C_CONTACT", "A_TOUCHDOWN_STILL", "C_DYNAMIC_MESH", "C_TIME"))
    assert (m.combine, m.touchdown_motion) == ("rss", True) and "bend.hypot(dynamic)" in text
    rows = list(csv.DictReader(open(root / "docs" / "accuracy_runs.csv")))
    cases = {name: S.case_scales(riser_bin, name) for name in S.HEAVE_CASES + tuple(S.A.STILL_CASES)}
    def knob(name, sets):
        return S.A.choice(riser_bin, name, sets)

    # the binary's choices, one binary per core at a time
    import os
    from concurrent.futures import ThreadPoolExecutor

    pairs = [(name, t) for name in S.HEAVE_CASES for t in S.TARGETS]
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        chosen = list(pool.map(lambda p: knob(p[0], [f"accuracy={p[1]}"]), pairs))
    for (name, t), d in zip(pairs, chosen):
        assert S.choose(m, cases[name], t) == (d["n_elements"], d["time_step"]), (name, t)
    # the mesh term with n pinned: the model or the statics' departure, the larger (the scales and the
    # departure's base on max(n, 60) elements, the pinned mesh being the scene's then)
    for name, meshes in (("steel_catenary", (20, 30, 100, 160)), ("lazy_wave", (10, 20, 30))):
        for n in meshes:
            d = knob(name, ["accuracy=1e-2", f"n_elements={n}"])
            s = replace(cases[name], curvature=d["max_curvature"], bending_length=d["touchdown_bending_length"])
            base = S.top_row_tension(riser_bin, name, max(n, 60))
            mine = max(abs(S.top_row_tension(riser_bin, name, n) - base) / base, S.space_error(m, s, n))
            assert d["predicted_space_error"] == pytest.approx(mine, rel=1e-9), (name, n)
    pts = S.points(rows, cases, riser_bin)
    assert len(pts) > 100 and any(c == "steel_still" for c, *_ in pts)
    assert S.smallest_ratio(m, cases, pts) >= 1.0
    # without its still part the touchdown's term bounds no point set (the still line's departures), and
    # (16.8), the model of §16.7, bounds the points too but costs more (0.962 of its work, both with
    # no element on the seabed longer than 1.2 bending lengths, docs/theory.md §16.9; 0.959 before)
    assert S.least(replace(m, a_s=0.0, c_c=1e9), "c_c2", cases, pts) is None
    before = replace(m, c_c2=1.0e-3, c_c=2.4e-3, c_t=0.134, combine="sum", touchdown_motion=False)
    assert S.smallest_ratio(before, cases, pts) >= 1.0
    assert S.work(m, cases) / S.work(before, cases) == pytest.approx(0.962, abs=0.001)


def test_the_accuracy_figure_s_frontier_is_the_cheapest_cell_reaching_each_target(tmp_path):
    """docs/figures/accuracy_cost.png (riser-tools accuracy, doc phase): its solid line at a target is
    the work of the cheapest grid cell reaching the target, the cell `accuracy-fit --oracle` compares
    the knob with; a target below every cell's error has none; the figure is written."""
    import csv

    from riser_tools.studies import accuracy as A
    from riser_tools.studies import accuracy_fit as F

    rows = list(csv.DictReader(open(A.Path(__file__).resolve().parents[2] / "docs" / "accuracy_runs.csv")))
    for case in A.FIGURE_CASES:
        front = A.cost_frontier(rows, case, [1e-2, 1e-3, 1e-4, 1e-9])
        assert front[:3] == [F.oracle(rows, case, t)["cell"][3] for t in (1e-2, 1e-3, 1e-4)], case
        assert front[3] is None and front[0] <= front[1] <= front[2]
    A.plot_cost(rows, tmp_path / "cost.png")
    assert (tmp_path / "cost.png").stat().st_size > 10_000


def test_the_accuracy_study_s_later_phases_start_from_the_committed_runs(riser_bin, tmp_path, monkeypatch):
    """riser-tools accuracy --phase doc (or ladder, verify) on a fresh checkout, without
    out/accuracy/grid.csv: it starts from docs/accuracy_runs.csv, which it writes back unchanged, and
    hands every committed run to the document (write_doc, stubbed here: it asks the binary for
    hundreds of predictions); it once started from nothing and would have written the phase's runs
    alone over the committed ones."""
    import csv
    import shutil

    from riser_tools.studies import accuracy as A

    root = A.Path(__file__).resolve().parents[2]
    docs = tmp_path / "docs"
    docs.mkdir()
    shutil.copy(root / "docs" / "accuracy_runs.csv", docs / "accuracy_runs.csv")
    seen = []
    monkeypatch.setattr(A, "write_doc", lambda rows, d, b: seen.append(len(rows)))
    A.main(["--bin", riser_bin, "--phase", "doc", "--out", str(tmp_path / "out"), "--docs", str(docs)])
    assert (docs / "accuracy_runs.csv").read_text() == (root / "docs" / "accuracy_runs.csv").read_text()
    assert seen == [len(list(csv.DictReader(open(root / "docs" / "accuracy_runs.csv"))))] and seen[0] > 700
