"""Free points in a system FMU (issue 49; docs/guide/systems.md, "In an FMU"): the clump-weight
mooring (docs/cases/clump_weight_mooring.toml: anchor, 300 m of chain, a 10 t clump, 260 m of
chain, fairlead; 20 and 18 elements here, the test's cost) packaged as its own FMU the way
`riser-tools package-fmu --scene` does and driven by fmpy, against `riser run SYSTEM`. Both step
the clump with its chains by one stepper (src/sim/system_dynamics.rs FreePoints, docs/theory.md
§17.7): with the vessel held the two runs are the same arithmetic; with the vessel moving, the
FMU's vessel path between communication points is the input path's (docs/theory.md §7), the
command line's the exact harmonics."""
import subprocess
from pathlib import Path

import numpy as np
import pytest

from test_system_fmu import ramped

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "docs" / "cases" / "clump_weight_mooring.toml"
INPUTS = ["heave", "surge", "sway", "heave_velocity", "surge_velocity", "sway_velocity", "roll", "pitch", "yaw",
          "angular_velocity_x", "angular_velocity_y", "angular_velocity_z"]
# the chain with MoorDyn's OC3 drag and added mass, and a current across the mooring grown over 20 s
CURRENT = ("torsional_stiffness = 0.0\ncd_normal = 1.6\nca_normal = 1.0",
           '\n[current]\nprofile = "uniform"\nspeed = 1.5\ndirection = [0.0, 1.0]\nramp = 20.0\n')


def coarse(current: bool) -> str:
    text = SCENE.read_text().replace("n_elements = 60", "n_elements = 20").replace("n_elements = 52", "n_elements = 18")
    if current:
        text = text.replace("torsional_stiffness = 0.0", CURRENT[0]) + CURRENT[1]
    return text


@pytest.fixture(scope="module")
def clump(fmu_path, riser_bin, tmp_path_factory):
    """The still-water and the current scenes, each a file and its system FMU."""
    from riser_tools.fmu import package_system
    d = tmp_path_factory.mktemp("clump")
    out = {}
    for name, current in (("clump", False), ("clump_current", True)):
        p = d / f"{name}.toml"
        p.write_text(coarse(current))
        out[name] = (p, package_system(fmu_path, riser_bin, p, d / f"{name}.fmu"))
    return out


def cli_run(riser_bin, scene, args, out):
    subprocess.run([riser_bin, "run", str(scene), *args, "--out", str(out)], check=True, capture_output=True)
    head = (out / "timeseries.csv").read_text().split("\n", 1)[0].split(",")
    data = np.loadtxt(out / "timeseries.csv", delimiter=",", skiprows=1)
    return {n: data[:, k] for k, n in enumerate(head)}


OUTPUTS = ["top_force_x", "top_force_y", "top_force_z", "clump.x", "clump.y", "clump.z"] + \
    [f"{line}.tension_{e}" for line in ("lower", "upper") for e in ("from", "to")]
# (no anchor's twist: the chains are cables)
ENERGIES = ["total_energy", "work_top", "work_hydro", "work_seabed", "dissipated_energy", "algorithmic_dissipation"]


def test_the_fmu_names_the_free_points_and_the_anchors_outputs(clump):
    from fmpy import read_model_description
    md = read_model_description(str(clump["clump"][1]), validate=True)
    names = {v.name: v for v in md.modelVariables}
    for c, vr in zip("xyz", range(200000, 200003)):
        v = names[f"clump.{c}"]
        assert (v.causality, v.valueReference, v.unit) == ("output", vr, "m")
    # the lower chain's anchor (the upper chain has no fixed end)
    assert (names["lower.anchor_force"].valueReference, names["lower.anchor_uplift_angle"].valueReference) == \
        (300000, 300001)
    assert "upper.anchor_force" not in names
    outputs = {u.variable.name for u in md.outputs}
    assert {"clump.x", "clump.y", "clump.z", "lower.tension_to", "upper.tension_to", "lower.anchor_force"} <= outputs


def test_with_the_vessel_held_the_fmu_is_the_command_lines_run(clump, riser_bin, tmp_path):
    """A current of 1.5 m/s across the mooring, grown over 20 s, pushes the clump 10 m sideways in
    30 s; the vessel held (the FMU's inputs zero, the command line without motion). The two runs are
    the same scheme and the same arithmetic but for the step ends' times (summed by the master and
    the FMU, multiplied in the command line): the loads on the vessel, the tensions and the clump's
    position agree within 1e-9 of their scale (measured: the same bits, fmpy's times being the
    command line's; the Rust test in src/fmi/instance.rs, its times summed, 1e-11)."""
    from fmpy import simulate_fmu
    scene, fmu = clump["clump_current"]
    duration, h = 30.0, 0.05
    cli = cli_run(riser_bin, scene, ["--duration", str(duration)], tmp_path)
    res = simulate_fmu(str(fmu), stop_time=duration, output_interval=h, output=OUTPUTS)
    assert np.allclose(res["time"], cli["t"], rtol=0, atol=1e-9)
    worst = {n: np.max(np.abs(res[n] - cli[n])) / np.max(np.abs(cli[n])) for n in OUTPUTS if np.any(cli[n])}
    print({k: f"{v:.1e}" for k, v in worst.items()})
    assert max(worst.values()) < 1e-9, worst
    drift = np.hypot(res["clump.x"][-1] - res["clump.x"][0], res["clump.y"][-1] - res["clump.y"][0])
    assert drift > 5.0, drift


def test_with_the_vessel_moving_the_fmu_follows_the_command_line(clump, riser_bin, tmp_path):
    """Surge 5 m / 40 s with heave 1 m / 10 s, grown over 40 s, 80 s; the FMU at communication steps
    of 0.05 s (its internal step), its inputs the same harmonics with their velocities. The FMU's
    vessel path between communication points is predicted from its inputs (docs/theory.md §7),
    the command line's exact: the loads on the vessel, each chain's end tensions and the clump's
    position agree within 1e-3 of their range over the run (the input path's error, as the
    spread mooring's in test_system_fmu.py; measured: 5.2e-4 the vertical force, 1.8e-5 the
    clump's surge). The system's energy balance in the FMU's outputs
    closes (the clump's energy and the water's work on it in them, 17.17; measured: 2e-8 of the work
    exchanged)."""
    from fmpy import simulate_fmu
    scene, fmu = clump["clump"]
    duration, h = 80.0, 0.05
    cli = cli_run(riser_bin, scene, ["--surge", "5,40", "--heave", "1,10", "--ramp", "40", "--duration",
                                     str(duration)], tmp_path)
    t = np.arange(int(round(duration / h)) + 1) * h
    sig = np.zeros(len(t), dtype=[("time", float)] + [(n, float) for n in INPUTS])
    sig["time"] = t
    sig["surge"], sig["surge_velocity"] = ramped(5.0, 40.0, 40.0, t)
    sig["heave"], sig["heave_velocity"] = ramped(1.0, 10.0, 40.0, t)
    res = simulate_fmu(str(fmu), stop_time=duration, output_interval=h, input=sig, output=OUTPUTS + ENERGIES)
    assert np.allclose(res["time"], cli["t"], rtol=0, atol=1e-9)
    worst = {n: np.max(np.abs(res[n] - cli[n])) / np.ptp(cli[n]) for n in OUTPUTS if np.ptp(cli[n]) > 0}
    print({k: f"{v:.1e}" for k, v in worst.items()})
    assert max(worst.values()) < 1e-3, worst
    # the vessel's surge swings the clump: metres, not millimetres
    assert np.ptp(res["clump.x"]) > 1.0
    from riser_tools.fmu import energy_balance
    balance, exchanged = energy_balance(res, seabed=True)
    print(f"energy balance {balance:.3e} J of {exchanged:.3e} J exchanged")
    assert balance < 1e-6 * exchanged
