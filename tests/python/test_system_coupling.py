"""A system FMU coupled both ways to the six-degree-of-freedom vessel in libcosim (issue 49,
evidence 6; docs/guide/systems.md): docs/cases/moored_vessel.toml, the 100 m vessel's four
chains and its steel catenary riser as one FMU; the vessel osp/vessel/Vessel6.py with its own
station-keeping springs removed (the chains hold it), trimmed for the lines' load at the start
(`balance_initial_load`), in its 10 s wave (about 0.23 m of heave, 4 degrees of roll near its
resonance, 0.9 degrees of pitch). libcosim's fixed-step algorithm: the vessel's pose and velocities
to the system FMU, its resultant force and moment (global) to the vessel; riser given the vessel's
mass and inertia (`vessel_mass_*`, `vessel_inertia_*`: the path takes the vessel's answer to
riser's own load within each step, docs/theory.md §7.8, issue 53). Each communication step's
window of the resultant against a finer run.

(The OC3-Hywind spar's chains, docs/cases/oc3_hywind_mooring.toml, are not for this vessel: their
fairleads 70 m below its reference point swing 8 m at its roll resonance, and the chains snatch
at mega-newtons, as they would.)"""
from pathlib import Path

import numpy as np
import pytest
from riser_tools.coupling_loop import build_vessel_fmu, fixed_step6, vessel6_inertia

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "docs" / "cases" / "moored_vessel.toml"
# the chains keep station: the vessel's own springs in surge, sway and yaw off
VESSEL = {"stiffness_11": 0.0, "stiffness_22": 0.0, "stiffness_66": 0.0, "balance_initial_load": True}
RESULTANT = ["top_force_x", "top_force_y", "top_force_z", "top_moment_x", "top_moment_y", "top_moment_z"]


@pytest.fixture(scope="module")
def vessel6_fmu(tmp_path_factory):
    return build_vessel_fmu(tmp_path_factory.mktemp("vessel6"), "Vessel6")


def system_fmu(fmu_path, riser_bin, dest, coarse):
    """The system FMU of the scene, with every line's elements halved if `coarse` (the short test's cost)."""
    from riser_tools.fmu import package_system
    text = SCENE.read_text()
    if coarse:
        text = text.replace("n_elements = 40", "n_elements = 20").replace("n_elements = 35", "n_elements = 18")
    scene = dest / f"moored_vessel{'_coarse' if coarse else ''}.toml"
    scene.write_text(text)
    return str(package_system(fmu_path, riser_bin, scene, dest / f"{scene.stem}.fmu"))


def windows(res, start):
    """min, mean, max of each resultant component over t >= start."""
    m = res["t"] >= start - 1e-9
    return {n: np.array([res[n][m].min(), res[n][m].mean(), res[n][m].max()]) for n in RESULTANT}


def compare(res, ref, start):
    """Each component's min, mean and max against the reference's, relative to the reference's
    range over the window (the part the coupling moves; the means' magnitude would hide it)."""
    a, b = windows(res, start), windows(ref, start)
    return {n: float(np.max(np.abs(a[n] - b[n])) / max(np.ptp(ref[n][ref["t"] >= start - 1e-9]), 1.0))
            for n in RESULTANT}


def run(fmu, vessel, h, duration, own=True):
    """libcosim's fixed step; riser given the vessel's mass and inertia (`own`: its answer to riser's
    own load taken within each step, docs/theory.md §7.5) or not."""
    return fixed_step6(fmu, vessel, h, duration, vessel=VESSEL, riser=vessel6_inertia(vessel, VESSEL) if own else None)


def test_the_system_fmu_couples_both_ways_to_the_vessel_briefly(fmu_path, riser_bin, vessel6_fmu, tmp_path):
    """100 s, half the file's elements, riser given the vessel's mass and inertia (docs/theory.md
    §7.8): at 0.1, 0.2 and 0.25 s against 0.05 s the resultant's window (60 to 100 s, the roll
    grown) within 1 % of its range (the force along x and z and the pitch moment: those the wave
    moves most); at 0.5 s the chains' force bounded. Without the vessel's mass and inertia the
    loop at 0.1 s rings the chains' axial mode (1.6 Hz) and grows (docs/coupling.md, issue 53)."""
    fmu = system_fmu(fmu_path, riser_bin, tmp_path, True)
    ref = run(fmu, vessel6_fmu, 0.05, 100.0)
    late = ref["t"] >= 60.0
    # the vessel moves (its wave: about 0.23 m of heave) and the chains pull it back
    assert np.ptp(ref["heave"][late]) > 0.4
    swing = np.ptp(ref["top_force_x"][late])
    assert swing > 3e4
    for h in (0.1, 0.2, 0.25):
        err = compare(run(fmu, vessel6_fmu, h, 100.0), ref, 60.0)
        print(f"h {h}: " + ", ".join(f"{k} {v:.2e}" for k, v in err.items()))
        for n in ("top_force_x", "top_force_z", "top_moment_y"):
            assert err[n] < 0.01, (h, n, err[n])
    long = run(fmu, vessel6_fmu, 0.5, 100.0)
    ratio = np.ptp(long["top_force_x"][long["t"] >= 60.0]) / swing
    bare = run(fmu, vessel6_fmu, 0.1, 100.0, own=False)
    grown = np.ptp(bare["top_force_x"][bare["t"] >= 80.0]) / swing
    print(f"h 0.5: top_force_x swing {ratio:.3f} of the 0.05 s run's; h 0.1 without the vessel's inertia: {grown:.2f}")
    assert abs(ratio - 1.0) < 0.05, ratio
    assert grown > 2.0, grown


@pytest.mark.long
@pytest.mark.parametrize("h", [0.05, 0.1, 0.2, 0.5])
def test_the_system_fmu_couples_both_ways_within_1_percent_of_a_0_01_s_run(fmu_path, riser_bin, vessel6_fmu,
                                                                          tmp_path_factory, h):
    """Issue 49's evidence 6 and issue 53's acceptance: 600 s, the file's meshes, riser given the
    vessel's mass and inertia (§7.8), each communication step against 0.01 s (the internal step
    min(0.05, h)): the resultant's window (300 to 600 s) within 1 % of its range. Measured: 0.05 s
    0.10 %, 0.1 s 0.09 %, 0.2 s 0.18 %, 0.5 s 0.29 % (top_force_z; x 0.37 %, the pitch moment 0.11 %),
    since the long steps take the slope and curvature of their end values where the vessel's mass and
    inertia are given (docs/theory.md (7.10a); 1.25 %, 0.39 %, 0.79 % before: the path's bump at
    1/h = 2 Hz rang the chains' 1.6 Hz axial mode). At 0.4 s this loop grows (docs/coupling.md)."""
    d = tmp_path_factory.getbasetemp() / "system_coupling_long"
    d.mkdir(exist_ok=True)
    fmu = system_fmu(fmu_path, riser_bin, d, False)
    ref_file = d / "ref.npz"
    if ref_file.exists():
        ref = dict(np.load(ref_file))
    else:
        ref = run(fmu, vessel6_fmu, 0.01, 600.0)
        np.savez(ref_file, **{k: v for k, v in ref.items() if isinstance(v, np.ndarray)})
    err = compare(run(fmu, vessel6_fmu, h, 600.0), ref, 300.0)
    print(f"h {h}: " + ", ".join(f"{k} {v:.2e}" for k, v in err.items()))
    for n in ("top_force_x", "top_force_z", "top_moment_y"):
        assert err[n] < 0.01, (h, n, err[n])
