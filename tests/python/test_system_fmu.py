"""A system of lines as an FMU (issue 49; docs/guide/systems.md, "In an FMU"): the OC3-Hywind
mooring (three chains, docs/cases/oc3_hywind_mooring.toml, 20 elements a line here) packaged as
its own FMU the way `riser-tools package-fmu --scene` does, driven by fmpy with the vessel's
motion as inputs, against `riser run SYSTEM` with the same motion (the command line's exact
harmonics; the FMU's inputs at its communication points, the path between them the input path's,
docs/theory.md §7); its lines' outputs named; coupled both ways to the six-degree-of-freedom
vessel in libcosim."""
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "docs" / "cases" / "oc3_hywind_mooring.toml"
LINES = ("line1", "line2", "line3")


@pytest.fixture(scope="module")
def system_scene(tmp_path_factory):
    """The OC3 mooring with 20 elements a line (the test's cost), as a file."""
    d = tmp_path_factory.mktemp("system")
    p = d / "oc3_coarse.toml"
    p.write_text(SCENE.read_text().replace("n_elements = 100", "n_elements = 20"))
    return p


@pytest.fixture(scope="module")
def system_fmu(fmu_path, riser_bin, system_scene, tmp_path_factory):
    """The system FMU: the generic FMU's binary, `riser model-description --scene`, the scene in
    its resources and resources/packaged_scene.txt (what `riser-tools package-fmu --scene` writes)."""
    from riser_tools.fmu import package_system
    return package_system(fmu_path, riser_bin, system_scene, tmp_path_factory.mktemp("system_fmu") / "oc3.fmu")


def ramped(amplitude, period, ramp, t):
    """The command line's harmonic (src/sim/mod.rs Heave): displacement and velocity."""
    w = 2 * np.pi / period
    a = np.pi / ramp
    inside = t < ramp
    r = np.where(inside, 0.5 * (1 - np.cos(a * t)), 1.0)
    dr = np.where(inside, 0.5 * a * np.sin(a * t), 0.0)
    return amplitude * r * np.sin(w * t), amplitude * (r * w * np.cos(w * t) + dr * np.sin(w * t))


def test_the_system_fmu_names_its_lines_outputs_and_starts_in_its_scene(system_fmu, system_scene):
    from fmpy import read_model_description
    md = read_model_description(str(system_fmu), validate=True)
    names = {v.name: v for v in md.modelVariables}
    for line in LINES:
        for q in ("tension_from", "tension_to", "min_tension", "touchdown_s"):
            v = names[f"{line}.{q}"]
            assert v.causality == "output" and v.valueReference >= 100000
    assert names["scene"].start == system_scene.name
    # every output in ModelStructure, without direct feedthrough
    outputs = {u.variable.name for u in md.outputs}
    assert {f"{line}.tension_to" for line in LINES} <= outputs
    assert all(u.dependencies == [] for u in md.outputs)


def test_the_system_fmu_moves_its_lines_as_the_command_line_does(system_fmu, system_scene, riser_bin, tmp_path):
    """Surge 10 m / 100 s with heave 2 m / 12 s, ramped over 100 s, 150 s. The command line's run
    (timeseries.csv) and the FMU's at communication steps of 0.05 s (the internal step), inputs
    the same harmonics with their velocities: the resultant force and each line's tensions agree
    within the input path's interpolation (measured: see the print), and the system's energy
    balance closes (the FMU's energies are the system's sums)."""
    from fmpy import simulate_fmu
    duration, h = 150.0, 0.05
    subprocess.run([riser_bin, "run", str(system_scene), "--surge", "10,100", "--heave", "2,12", "--duration",
                    str(duration), "--out", str(tmp_path)], check=True, capture_output=True)
    cli = np.genfromtxt(tmp_path / "timeseries.csv", delimiter=",", names=True)
    t = np.arange(int(round(duration / h)) + 1) * h
    names = ["heave", "surge", "sway", "heave_velocity", "surge_velocity", "sway_velocity", "roll", "pitch", "yaw",
             "angular_velocity_x", "angular_velocity_y", "angular_velocity_z"]
    sig = np.zeros(len(t), dtype=[("time", float)] + [(n, float) for n in names])
    sig["time"] = t
    sig["surge"], sig["surge_velocity"] = ramped(10.0, 100.0, 100.0, t)
    sig["heave"], sig["heave_velocity"] = ramped(2.0, 12.0, 100.0, t)
    outs = ["top_force_x", "top_force_z", "top_moment_y", "total_energy", "work_top", "work_hydro", "work_seabed",
            "dissipated_energy", "algorithmic_dissipation"] + [f"{line}.tension_{e}" for line in LINES
                                                              for e in ("from", "to")]
    res = simulate_fmu(str(system_fmu), stop_time=duration, output_interval=h, input=sig, output=outs)
    assert np.allclose(res["time"], cli["t"])
    worst = {}
    for fmu_name, cli_name in [("top_force_x", "top_force_x"), ("top_force_z", "top_force_z"),
                               ("top_moment_y", "top_moment_y")] + \
            [(f"{line}.tension_{e}", f"{line}tension_{e}") for line in LINES for e in ("from", "to")]:
        a, b = res[fmu_name], cli[cli_name]
        worst[fmu_name] = np.max(np.abs(a - b)) / np.ptp(b)
    print({k: f"{v:.2e}" for k, v in worst.items()})
    assert max(worst.values()) < 1e-3, worst
    # the surge moved the vessel by 10 m: the chains' restoring force is of the order of 41 kN/m x 10 m
    assert 2e5 < np.ptp(res["top_force_x"]) / 2 < 8e5
    from riser_tools.fmu import energy_balance
    balance, exchanged = energy_balance(res, seabed=True)
    print(f"energy balance {balance:.3e} J of {exchanged:.3e} J exchanged")
    assert balance < 1e-6 * exchanged


def test_the_command_lines_system_run_json(system_scene, riser_bin):
    """`riser run SYSTEM --json`: steady.top_force per axis and steady.lines as the contract names
    them; the same bits on one and on two threads."""
    runs = []
    for threads in (1, 2):
        done = subprocess.run([riser_bin, "run", str(system_scene), "--surge", "5,60", "--duration", "90",
                               "--threads", str(threads), "--json"], check=True, capture_output=True, text=True)
        runs.append(json.loads(done.stdout))
    a, b = runs
    assert a["steady"]["top_force"] == b["steady"]["top_force"] and a["steady"]["lines"] == b["steady"]["lines"]
    assert [l["name"] for l in a["steady"]["lines"]] == list(LINES)
    lo, mean, hi = a["steady"]["top_force"]["x"]
    assert lo < mean < hi
    for line in a["steady"]["lines"]:
        assert len(line["tension_from"]) == 3 and len(line["tension_to"]) == 3
        # the fairlead is the line's `to` end here: its tension is the larger (the chain's weight)
        assert line["tension_to"][1] > line["tension_from"][1]
    assert a["completed"] and a["energy_balance_relative"] < 1e-6


def test_bad_system_runs_are_named(system_scene, riser_bin):
    for args, needle in [(["--threads", "0"], "--threads must be at least 1"),
                         (["--set", "n_elements=10"], "--set n_elements: not for a system scene"),
                         (["--fatigue", "D-air"], "--fatigue")]:
        done = subprocess.run([riser_bin, "run", str(system_scene), "--duration", "1", *args], capture_output=True,
                              text=True)
        assert done.returncode != 0 and needle in done.stderr, (args, done.stderr)
    done = subprocess.run([riser_bin, "run", "catenary", "--duration", "1", "--threads", "2"], capture_output=True,
                          text=True)
    assert done.returncode != 0 and "only for a system" in done.stderr


def test_riser_scene_and_modes_take_a_system(system_scene, riser_bin, tmp_path):
    """`riser scene SYSTEM` prints each line as the single-line scene it is; saved as a file, that
    scene's modes (`riser modes LINE.toml`) are the system's modes of that line (`riser modes
    SYSTEM`: the vessel held, the lines vibrate independently); the three chains of the symmetric
    spread have the same periods."""
    text = subprocess.run([riser_bin, "scene", str(system_scene)], check=True, capture_output=True,
                          text=True).stdout
    assert text.count("# line '") == 3
    # the second line's scene, as printed (up to the next line's header)
    second = text.split("# line 'line2'")[1].split("\n", 1)[1].split("# line '")[0]
    line2 = tmp_path / "line2.toml"
    line2.write_text(second)
    sys_modes = json.loads(subprocess.run([riser_bin, "modes", str(system_scene), "--count", "4", "--json"],
                                          check=True, capture_output=True, text=True).stdout)
    alone = json.loads(subprocess.run([riser_bin, "modes", str(line2), "--count", "4", "--json"], check=True,
                                      capture_output=True, text=True).stdout)
    rows = {l["name"]: l["periods"] for l in sys_modes["lines"]}
    assert np.allclose(rows["line2"], alone["periods"], rtol=1e-12, atol=0)
    assert np.allclose(rows["line2"], rows["line3"], rtol=1e-9) and np.allclose(rows["line1"], rows["line2"], rtol=1e-6)
    assert [m["period"] for m in sys_modes["modes"]] == sorted((m["period"] for m in sys_modes["modes"]), reverse=True)
