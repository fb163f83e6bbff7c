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
    """The Python port of tests/it/common/reference.rs against riser's cable statics: the catenary
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


# --------------------------------------------------------------------------- the accuracy study

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


def test_the_accuracy_figure_s_frontier_is_the_cheapest_cell_reaching_each_target(tmp_path):
    """docs/figures/accuracy_cost.png (riser-tools accuracy, doc phase): its solid line at a target is
    the work of the cheapest grid cell reaching the target (each cell's work at or above it for every
    cell whose error is within the target); a target below every cell's error has none; the figure
    is written."""
    import csv

    from riser_tools.studies import accuracy as A

    rows = list(csv.DictReader(open(A.Path(__file__).resolve().parents[2] / "docs" / "accuracy_runs.csv")))
    for case in A.FIGURE_CASES:
        front = A.cost_frontier(rows, case, [1e-2, 1e-3, 1e-4, 1e-9])
        assert front[3] is None and front[0] <= front[1] <= front[2]
    A.plot_cost(rows, tmp_path / "cost.png")
    assert (tmp_path / "cost.png").stat().st_size > 10_000


def test_the_accuracy_study_s_accounting_of_a_measured_choice(monkeypatch):
    """riser-tools accuracy, verify phase (measured_row): on a `--json` of the shape `riser run --set
    accuracy=T` prints and a grid whose every figure is set by hand, the error e (the largest of the
    window's min, mean and max off the reference, over its max), met (e <= target), the estimate over e,
    the work ratio over the cheapest grid cell reaching the target against the same reference, and the
    pilots' share of a 3-hour run (by wall time: their summed wall over the run's wall x 10800 s / its
    duration; by element-steps) are the hand-computed ones; a target no cell reaches has no ratio."""
    from riser_tools.studies import accuracy as A

    def row(kind, n, dt, nps, dmin, dmax):
        return {"case": "catenary", "kind": kind, "n_elements": str(n), "time_step": str(dt), "newton_tolerance":
                "1e-08", "accuracy": "", "tt_min": str(100e3 + dmin), "tt_mean": "110000", "tt_max": str(120e3 + dmax),
                "wall_s": "0.1", "newton_per_step": str(nps), "completed": "True"}

    ref = row("reference", 160, 0.0125, 3, 0, 0)
    # the catenary case runs 80 s: work = n x 80 / dt x iterations a step
    rows = [ref, row("grid", 10, 0.2, 2, -240, 0),  # e 2e-3, work 8000
            row("grid", 20, 0.1, 2, 0, 14.4),  # e 1.2e-4, work 32000
            row("grid", 40, 0.05, 2, 6, 0),  # e 5e-5, work 128000
            row("grid", 80, 0.2, 2, 0, 2.4)]  # e 2e-5, work 64000: cheaper than the 40 at 0.05 s
    pilots = [{"round": 1, "n_elements": 30, "time_step": 0.1, "values": {}, "wall_s": 1.0},
              {"round": 2, "n_elements": 60, "time_step": 0.05, "values": {}, "wall_s": 2.0}]
    d = {"n_elements": 30, "time_step": 0.1, "newton_tolerance": 1e-6, "iterations_per_step": 2.5, "duration": 80.0,
         "solve_wall_time": 0.5, "steady": {"top_tension": [100e3 - 36, 110e3 + 6, 120e3 + 12]},
         "accuracy": {"estimate": 4.5e-4, "notes": ["min: not converged"], "pilots": pilots, "pilot_window": [40, 80],
                      "wall_s": 2.2, "met": True, "orders": {"top_tension_max": {"mesh": 2.0, "step": None}}}}
    r = A.measured_row("catenary", 1e-3, d, ref, rows)
    assert r["error"] == pytest.approx(36 / 120e3, rel=1e-12) and r["met"]
    assert r["estimate_over_error"] == pytest.approx(4.5e-4 / 3e-4, rel=1e-12)
    assert r["work"] == pytest.approx(30 * 800 * 2.5) and r["grid_cell"] == "20 el., 0.1 s"
    assert r["work_ratio"] == pytest.approx(60000 / 32000, rel=1e-12)
    assert r["pilots"] == 2 and r["rounds"] == 2 and r["finest_pilot"] == "60 el., 0.05 s"
    assert r["pilots_share_3h"] == pytest.approx(3.0 / (0.5 * 10800 / 80), rel=1e-12)
    assert r["pilots_share_3h_element_steps"] == pytest.approx((30 * 800 + 60 * 1600) / (30 * 10800 / 0.1), rel=1e-12)
    assert r["orders"] == "max h2.0 t-" and r["notes"] == "min: not converged" and r["reference_finer"]
    # 1e-4: the 80 elements at 0.2 s (work 64000) reach it, cheaper than the 40 at 0.05 s (128000)
    r4 = A.measured_row("catenary", 1e-4, d, ref, rows)
    assert not r4["met"] and r4["grid_cell"] == "80 el., 0.2 s" and r4["work_ratio"] == pytest.approx(60000 / 64000)
    r5 = A.measured_row("catenary", 1e-5, d, ref, rows)
    assert r5["grid_cell"] == "none" and r5["work_ratio"] == ""
    # the reference of the pilots: the grid's when finer than twice the finest pilot's elements and half its
    # step, else the run it asks for (recorded, not run: `one` stubbed)
    asked = []
    monkeypatch.setattr(A, "one", lambda *a: asked.append(a[3:]) or ref)
    assert A.pilots_reference("bin", None, rows, "catenary", [d]) is ref and asked == []
    big = dict(d, accuracy=dict(d["accuracy"], pilots=pilots + [dict(pilots[1], n_elements=120, time_step=0.0125)]))
    A.pilots_reference("bin", None, rows, "catenary", [big])
    assert asked == [("catenary", "reference_pilots", 240, 0.00625, 1e-10)]
    assert not A.measured_row("catenary", 1e-3, big, ref, rows)["reference_finer"]
    # a pilot an earlier round ran, reused by a later one (`reused`, wall 0): counted once, in the pilots and
    # in their element-steps
    again = dict(d, accuracy=dict(d["accuracy"], pilots=pilots + [dict(pilots[0], round=2, wall_s=0.0, reused=True)]))
    ra = A.measured_row("catenary", 1e-3, again, ref, rows)
    assert ra["pilots"] == 2 and ra["pilots_share_3h_element_steps"] == r["pilots_share_3h_element_steps"]


def test_the_accuracy_study_s_later_phases_start_from_the_committed_runs(riser_bin, tmp_path, monkeypatch):
    """riser-tools accuracy --phase doc (or verify, scenes) on a fresh checkout, without
    out/accuracy/grid.csv: it starts from docs/accuracy_runs.csv, which it writes back unchanged, and
    hands every committed run to the document (write_doc, stubbed here: its figure takes tens of
    seconds); it once started from nothing and would have written the phase's runs alone over the
    committed ones."""
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
