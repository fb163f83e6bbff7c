"""riser's rainflow counting (src/sim/fatigue.rs, ASTM E1049-85) against the `rainflow` package
(pinned in requirements.txt) on random histories, cycle by cycle; `riser run --fatigue`'s worst
damage recomputed from the stress history it writes with the package's counts; and
`riser-tools plot-fatigue` (issue 50, docs/theory.md §12.5)."""

import json
import math
import subprocess

import numpy as np
import rainflow


def riser_cycles(riser_bin, tmp_path, history):
    path = tmp_path / "history.txt"
    path.write_text("".join(f"{float(v)!r}\n" for v in history))
    out = subprocess.run([riser_bin, "rainflow", str(path)], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def test_rainflow_matches_the_rainflow_package(riser_bin, tmp_path):
    """30 random histories (Gaussian noise, random walks, integers with repeated values and plateaus,
    a sine with noise; 0 to 3000 samples): the same cycles in the same order as
    rainflow.extract_cycles, ranges to 1e-12 of the history's spread, counts (1 and 0.5) equal."""
    rng = np.random.default_rng(50)
    histories = [[], [1.0], [1.0, 2.0], [1.0, 2.0, 0.5], [3.0, 3.0, 3.0], [-2, 1, -3, 5, -1, 3, -4, 4, -2]]
    for k in range(24):
        n = int(rng.integers(10, 3000))
        kind = k % 4
        if kind == 0:
            h = rng.normal(0.0, 50e6, n)
        elif kind == 1:
            h = np.cumsum(rng.normal(0.0, 1.0, n))
        elif kind == 2:
            h = rng.integers(-3, 4, n).astype(float)  # plateaus and repeated values
        else:
            t = np.arange(n) * 0.05
            h = 100e6 + 30e6 * np.sin(2 * np.pi * t / 7.0) + rng.normal(0.0, 5e6, n)
        histories.append(list(h))
    compared = 0
    for h in histories:
        ours = riser_cycles(riser_bin, tmp_path, h)
        theirs = [(r, c) for r, _, c, _, _ in rainflow.extract_cycles(h)]
        assert len(ours) == len(theirs), (len(h), len(ours), len(theirs))
        spread = (max(h) - min(h)) if h else 1.0
        for (r, c), (r2, c2) in zip(ours, theirs):
            assert abs(r - r2) <= 1e-12 * max(spread, 1e-300) and c == c2, (r, c, r2, c2)
        compared += len(ours)
    assert compared > 10000


def test_the_run_s_worst_damage_is_the_package_s_count_of_its_history(riser_bin, tmp_path):
    """`riser run steel_catenary --heave 2,12 --duration 60 --fatigue D-seawater-cp --scf 1.3` with
    the 20.6 mm X65 wall, run twice (the second writing the worst point's stress history): Miner's
    sum of rainflow.count_cycles of the worst fibre's history, n (SCF Δσ)^m / a on the JSON's
    curve, equals the JSON's damage to 1e-12; fatigue.csv's largest damage is it; the worst point
    lies at the touchdown; `riser-tools plot-fatigue` draws fatigue.csv."""
    out = tmp_path / "run"
    base = [riser_bin, "run", "steel_catenary", "--heave", "2,12", "--duration", "60",
            "--fatigue", "D-seawater-cp", "--scf", "1.3", "--set", "wall_thickness=0.0206",
            "--set", "yield_stress=448e6", "--json", "--out", str(out)]
    first = json.loads(subprocess.run(base, capture_output=True, text=True, check=True).stdout)
    f = first["steady"]["fatigue"]
    again = base + ["--fatigue-series", repr(f["worst_s"])]
    second = json.loads(subprocess.run(again, capture_output=True, text=True, check=True).stdout)
    assert second["steady"]["fatigue"] == f
    data = np.genfromtxt(out / "fatigue_series.csv", delimiter=",", names=True)
    history = data[f"fibre{f['worst_fibre']}"]
    c = f["curve"]
    s_switch = 10 ** ((c["log_a1"] - math.log10(c["n_switch"])) / c["m1"])
    damage = 0.0
    for rng_pa, count in rainflow.count_cycles(history):
        s = 1.3 * rng_pa / 1e6
        m, log_a = (c["m1"], c["log_a1"]) if s >= s_switch else (c["m2"], c["log_a2"])
        damage += count * s ** m / 10 ** log_a
    assert abs(damage / f["damage"] - 1) < 1e-12, (damage, f["damage"])
    table = np.genfromtxt(out / "fatigue.csv", delimiter=",", names=True)
    assert table["damage"].max() == f["damage"]
    lo, _, hi = first["steady"]["touchdown_s"]
    element = 400.0 / first["n_elements"]
    assert lo - 2 * element < f["worst_s"] < hi + 2 * element, (f["worst_s"], lo, hi)
    from riser_tools.fatigue_plot import main as plot_fatigue
    plot_fatigue([str(out / "fatigue.csv"), str(tmp_path / "fatigue.png")])
    assert (tmp_path / "fatigue.png").stat().st_size > 10000
