"""Fatigue over a scatter diagram through riser-sweep on Dask (issue 50; riser_sweep.fatigue,
docs/guide/sweeps.md "Fatigue over a scatter diagram").

The steel catenary with its 20.6 mm X65 wall, 20 elements, on a small RAO table, three JONSWAP
states of 60 s (the windows 46, 42 and 38 s):

(a) fatigue_life.csv is the combination computed here independently from each state's fatigue.csv
    and window (plain Python floats, sum_i p_i D_i T_year / T_i at every point and fibre), to 1e-12;
    the life is 1 / (DFF max D_year);
(b) one state of probability 1 gives `riser run --fatigue`'s damage_per_year and life_years, run
    here on its own, to the bit;
(c) doubling a probability adds that state's contribution once more (the same states reused);
(d) bad scatter files are refused naming the row and the column;
(e) 1 and 2 Dask workers give the same bits.
"""

import csv
import json
import math
import subprocess
from pathlib import Path

import pytest

T_YEAR = 365.25 * 86400.0
RAOS = "dof,frequency,direction,amplitude,phase\n" + "".join(
    f"{dof},{f},{d},{a},{p}\n"
    for d in (90.0, 180.0, 270.0)
    for f in (0.02, 0.1, 0.2, 0.4, 1.0)
    for dof, a, p in (("heave", 1.0 / (1.0 + 40 * f * f), -20.0 * f), ("surge", 0.8 * math.exp(-4 * f), -90.0),
                      ("pitch", 0.05 * f * math.exp(-2 * f), -90.0)))
SCATTER = "hs,tp,probability,direction\n1.5,7.0,0.5,180\n3.0,9.0,0.3,180\n5.0,11.0,0.2,180\n"


def write_spec(d: Path, scatter: str, dff: float = 10.0) -> Path:
    d.mkdir(parents=True, exist_ok=True)
    (d / "raos.csv").write_text(RAOS)
    (d / "scatter.csv").write_text(scatter)
    spec = d / "spec.toml"
    spec.write_text(f"""scene = "steel_catenary"
[parameters]
n_elements = 20
time_step = 0.1
wall_thickness = 0.0206
[motion]
raos = "raos.csv"
[fatigue]
curve = "D-seawater-cp"
scf = 1.1
dff = {dff!r}
scatter = "scatter.csv"
duration = 60.0
""")
    return spec


def sweep(riser_bin, d: Path, scatter: str, workers: int, out: Path | None = None):
    from riser_sweep.fatigue import load_fatigue_spec, run_fatigue_sweep

    spec = load_fatigue_spec(write_spec(d, scatter), riser_bin=riser_bin)
    summary = run_fatigue_sweep(spec, out or d / "out", workers=workers, bar=False)
    assert summary.complete, (d / "out" / "scatter_results.csv").read_text()
    return spec, summary


def rows(path: Path) -> list[dict[str, str]]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.fixture(scope="module")
def two_workers(riser_bin, tmp_path_factory):
    d = tmp_path_factory.mktemp("scatter2")
    spec, summary = sweep(riser_bin, d, SCATTER, workers=2)
    assert summary.workers == 2 and summary.ran == 3
    return d


def test_the_annual_damage_is_the_probability_weighted_sum_of_the_states(two_workers):
    """(a) at every point and fibre, from the per-state files alone."""
    out = two_workers / "out"
    states = rows(two_workers / "scatter.csv")
    expected: dict[tuple[float, int], float] = {}
    for i, st in enumerate(states, start=1):
        case = out / "cases" / f"{i:03d}_hs={float(st['hs'])!r}_tp={float(st['tp'])!r}"
        window = json.loads((case / "result.json").read_text())["json"]["steady"]["fatigue"]["window_length"]
        assert window < 60.0  # the steady window, not the run
        for r in rows(case / "fatigue.csv"):
            key = (float(r["S"]), int(r["fibre"]))
            expected[key] = expected.get(key, 0.0) + float(st["probability"]) * (float(r["damage"]) * T_YEAR / window)
    got = rows(out / "fatigue_life.csv")
    assert len(got) == len(expected) == 20 * 4 * 8
    worst = 0.0
    for r in got:
        e = expected[(float(r["s"]), int(r["fibre"]))]
        a = float(r["annual_damage"])
        assert abs(a - e) <= 1e-12 * e, (r, e)
        if e > 0:
            assert abs(float(r["life"]) - 1.0 / (e * 10.0)) <= 1e-12 / (e * 10.0)
        worst = max(worst, e)
    summary = json.loads((out / "fatigue_summary.json").read_text())
    assert abs(summary["worst"]["annual_damage"] - worst) <= 1e-12 * worst
    assert abs(summary["worst"]["life_years"] - 1.0 / (10.0 * worst)) <= 1e-12 / (10.0 * worst)
    # the touchdown zone holds the worst point; the hang-off is the first element's four points
    assert abs(summary["worst"]["s"] - summary["touchdown"]["static_touchdown_s"]) <= 50.0
    assert summary["touchdown"]["annual_damage"] == summary["worst"]["annual_damage"]
    assert len(summary["hang_off"]["points"]) == 4 and max(summary["hang_off"]["points"]) < 400.0 / 20
    assert summary["hang_off"]["annual_damage"] < summary["worst"]["annual_damage"]
    res = rows(out / "scatter_results.csv")
    assert [r["status"] for r in res] == ["ok"] * 3 and [r["row"] for r in res] == ["1", "2", "3"]
    shares = sum(float(r["share_at_worst"]) for r in res)
    assert abs(shares - 1.0) <= 1e-12
    assert (out / "annual_damage.png").stat().st_size > 10_000


def test_one_state_of_probability_one_is_riser_run_s_damage_per_year(riser_bin, tmp_path):
    """(b) the same bits as `riser run --fatigue` of that sea state."""
    spec, summary = sweep(riser_bin, tmp_path, "hs,tp,probability,direction\n3.0,9.0,1.0,180\n", workers=1)
    run = tmp_path / "alone"
    run.mkdir()
    for name, text in spec.job(spec.states[0])["files"].items():  # the RAO table as the workers get it
        (run / name).write_text(text)
    p = subprocess.run([riser_bin, "run", "steel_catenary", *spec.args(spec.states[0]), "--out", str(run)],
                       capture_output=True, text=True, cwd=run)
    assert p.returncode == 0, p.stderr
    ref = json.loads(p.stdout)["steady"]["fatigue"]
    s = summary.summary["worst"]
    print(f"riser run: damage/year {ref['damage_per_year']!r}, life {ref['life_years']!r}; sweep: "
          f"{s['annual_damage']!r}, {s['life_years']!r}")
    assert s["annual_damage"] == ref["damage_per_year"]
    assert s["life_years"] == ref["life_years"]
    assert s["s"] == ref["worst_s"] and s["fibre"] == ref["worst_fibre"]
    theirs = rows(run / "fatigue.csv")
    ours = rows(tmp_path / "out" / "fatigue_life.csv")
    assert len(theirs) == len(ours)
    for a, b in zip(theirs, ours):
        assert float(a["damage_per_year"]) == float(b["annual_damage"]) and float(a["life"]) == float(b["life"])


def test_doubling_a_probability_doubles_that_state_s_contribution(two_workers, riser_bin, tmp_path):
    """(c) the same finished states (reused, nothing runs again), row 2's probability doubled: the
    annual damage grows by exactly p_2 D_year,2 at every point; the sum 1.3 is warned of."""
    import shutil

    from riser_sweep.fatigue import CaseFatigue, load_fatigue_spec, run_fatigue_sweep

    d = tmp_path / "doubled"
    shutil.copytree(two_workers, d)
    spec = load_fatigue_spec(write_spec(d, SCATTER.replace("3.0,9.0,0.3", "3.0,9.0,0.6")), riser_bin=riser_bin)
    assert any("sum to 1.3" in w for w in spec.warnings)
    summary = run_fatigue_sweep(spec, d / "out", workers=1, bar=False)
    assert summary.ran == 0 and summary.skipped == 3 and summary.complete
    case = d / "out" / "cases" / "002_hs=3.0_tp=9.0"
    window = json.loads((case / "result.json").read_text())["json"]["steady"]["fatigue"]["window_length"]
    d2 = CaseFatigue.read((case / "fatigue.csv").read_text(), window).per_year()
    before = rows(two_workers / "out" / "fatigue_life.csv")
    after = rows(d / "out" / "fatigue_life.csv")
    for b, a, x in zip(before, after, d2):
        grew = float(a["annual_damage"]) - float(b["annual_damage"])
        assert abs(grew - 0.3 * x) <= 1e-12 * float(a["annual_damage"]), (b, a, x)
    old = rows(two_workers / "out" / "scatter_results.csv")[1]
    new = rows(d / "out" / "scatter_results.csv")[1]
    assert float(new["damage_per_year_weighted"]) == 2 * float(old["damage_per_year_weighted"])
    assert new["damage"] == old["damage"]


@pytest.mark.parametrize("text, says", [
    ("hs,tp,probability\n1.5,7.0,0.5\n3.0,9.0,-0.1\n", "row 2 (line 3), column probability: -0.1 is negative"),
    ("hs,probability\n1.5,0.5\n", "missing column tp"),
    ("hs,tp,probability\n1.5,7.0,0.5\n\n# a comment\n6.0,5.0,0.5\n",
     "row 2 (line 5), column tp: Tp = 5.0 s is too short for Hs = 6.0 m"),
    ("hs,tp,probability\n1.5,7.0,0.5\n2.0,abc,0.5\n", "row 2 (line 3), column tp: 'abc' is not a number"),
    ("hs,tp,probability,gama\n1.5,7.0,1.0,3.3\n", "unknown column 'gama' (columns: hs, tp, probability and "
     "optionally gamma, direction); did you mean gamma?"),
    ("hs,tp,probability\n1.5,7.0\n", "row 1 (line 2): 2 values for the 3 columns"),
    ("hs,tp,probability\n0.0,7.0,1.0\n", "row 1 (line 2), column hs: 0.0 m"),
])
def test_bad_scatter_files_are_refused_naming_the_row(tmp_path, text, says):
    """(d)"""
    from riser_sweep.fatigue import ScatterError, read_scatter

    p = tmp_path / "scatter.csv"
    p.write_text(text)
    with pytest.raises(ScatterError) as e:
        read_scatter(p)
    assert says in str(e.value), str(e.value)


def test_the_sweep_refuses_a_bad_scatter_before_any_state_runs(riser_bin, tmp_path, capsys):
    """(d) through the command: exit 2, the spec's field, the file, the row; and a state whose sea the
    RAO table does not cover (Tp 30 s reaches 0.017 Hz) is refused with its row too."""
    from riser_sweep.cli import main

    spec = write_spec(tmp_path, "hs,tp,probability\n1.5,7.0,0.5\n3.0,9.0,-0.5\n")
    assert main([str(spec), "--out", str(tmp_path / "out"), "--riser-bin", riser_bin]) == 2
    err = capsys.readouterr().err
    assert "fatigue.scatter:" in err and "row 2 (line 3), column probability: -0.5 is negative" in err, err
    assert not (tmp_path / "out").exists()
    spec = write_spec(tmp_path, "hs,tp,probability,direction\n1.5,7.0,0.5,180\n2.0,30.0,0.5,180\n")
    assert main([str(spec), "--out", str(tmp_path / "out"), "--riser-bin", riser_bin]) == 2
    err = capsys.readouterr().err
    assert "row 2 (line 3): vessel.raos:" in err and "outside the table's 0.02 to 1 Hz" in err, err


def test_one_and_two_workers_give_the_same_bits(two_workers, riser_bin, tmp_path):
    """(e) the results of a sweep on one worker are the two workers' (wall times aside)."""
    sweep(riser_bin, tmp_path, SCATTER, workers=1)
    a, b = two_workers / "out", tmp_path / "out"
    assert (a / "fatigue_life.csv").read_bytes() == (b / "fatigue_life.csv").read_bytes()
    ra, rb = rows(a / "scatter_results.csv"), rows(b / "scatter_results.csv")
    assert [{k: v for k, v in r.items() if k != "wall_s"} for r in ra] == \
        [{k: v for k, v in r.items() if k != "wall_s"} for r in rb]
    sa = json.loads((a / "fatigue_summary.json").read_text())
    sb = json.loads((b / "fatigue_summary.json").read_text())
    for k in ("worst", "touchdown", "hang_off"):
        assert sa[k] == sb[k]
