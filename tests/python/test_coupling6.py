"""Two-way coupling with the vessel in six degrees of freedom in libcosim (issue 30, evidence 4;
docs/coupling.md): osp/vessel/Vessel6.py (a 100 m vessel: mass, inertia, added mass, damping,
hydrostatic restoring, a 10 s wave) and riser with its hang-off 30 m forward of the vessel's
reference point (hang_off_x = 30). References: riser alone driven by the motion recorded in the
two-way run (one way, 0.025 s steps); the moment of the line's force about the reference point at
the vessel's pose, M = (R ρ) × F; the vessel's equilibrium in a current from `riser statics`
(static_current) at the vessel's pose and the vessel's restoring stiffness.

Until the riser FMU takes the vessel's rotation (roll, pitch, yaw, angular_velocity_*: branch
fmu-6dof), the vessel's rotation is not passed to riser: the checks that need it are skipped and
those that run say so (R = I on riser's side)."""
import json
import subprocess

import numpy as np
import pytest
from riser_tools.coupling_loop import (POSE, build_vessel_fmu, ecco6, fixed_step6, reference6, rotation,
                                       window6)

RHO = np.array([30.0, 0.0, 0.0])  # the hang-off in the vessel frame (m)
RISER = {"hang_off_x": 30.0}


@pytest.fixture(scope="module")
def vessel6_fmu(tmp_path_factory):
    return build_vessel_fmu(tmp_path_factory.mktemp("vessel6"), "Vessel6")


def arm(res, rotations):
    """R ρ at each row's pose (R = I where riser does not take the rotation)."""
    if not rotations:
        return np.tile(RHO, (len(res["t"]), 1))
    return np.array([rotation(a, b, c) @ RHO for a, b, c in zip(res["roll"], res["pitch"], res["yaw"])])


def moment_error(res, rotations):
    """max |M − (R ρ) × F| over the run, relative to |ρ| max |F|."""
    f = np.stack([res[f"top_force_{c}"] for c in "xyz"], axis=1)
    m = np.stack([res[f"top_moment_{c}"] for c in "xyz"], axis=1)
    want = np.cross(arm(res, rotations), f)
    return np.max(np.abs(m - want)) / (np.linalg.norm(RHO) * np.max(np.linalg.norm(f, axis=1)))


# 0.25 s and 0.5 s missed the 1 % (1.76 %, 1.34 %) with the displacement design alone: its
# step-periodic curvature error at 1/h and its harmonics lands on the line's resonance near 4 Hz (at
# the internal step 0.05 s); with the velocities in the fit (docs/theory.md §7.4) they pass (the
# test after this one)
@pytest.mark.parametrize("h", [0.05, 0.1, 0.2, 0.25, 0.5])
def test_six_degree_of_freedom_vessel_fixed_step_gives_the_one_way_tension_within_1_percent(
        fmu_path, vessel6_fmu, h):
    two = fixed_step6(fmu_path, vessel6_fmu, h, 50.0, riser=RISER)
    one = reference6(fmu_path, two, h_ref=0.025, riser=RISER)
    a, b = window6(two, 30.0), window6(one, 30.0)
    motion = {n: np.ptp(two[n][two["t"] >= 30.0]) / 2 for n in POSE}
    print(f"h {h}: two-way {a} one-way {b} (rotations to riser: {two['rotations']}); amplitudes {motion}")
    assert np.all(np.abs(a - b) <= 0.01 * b), (h, a, b)
    # the vessel moves as the 100 m vessel does in the 10 s wave: about 0.23 m heave, 0.058 rad
    # roll (near its 11 s period), 0.016 rad pitch (measured alone: 0.226, 0.0588, 0.0155)
    assert 0.2 < motion["heave"] < 0.26 and 0.05 < motion["roll"] < 0.07 and 0.013 < motion["pitch"] < 0.018
    # the moment about the reference point is the force's at the offset: at the pose riser was given
    # (one way, within 1e-9), and at the vessel's own pose in the loop (riser's pose is the input
    # path's at the step's end: within 1e-3 rad of the vessel's)
    e_one, e_two = moment_error(one, two["rotations"]), moment_error(two, two["rotations"])
    print(f"h {h}: |M − (Rρ)×F| / (|ρ| max|F|): one-way {e_one:.2e}, two-way {e_two:.2e}")
    assert e_one <= 1e-9 if not two["rotations"] else e_one <= 1e-3
    assert e_two <= 1e-3


def test_at_0_25_s_the_loop_is_riser_one_way_at_that_step_within_1_percent_with_or_without_the_velocities(
        fmu_path, vessel6_fmu):
    # riser alone fed the poses and velocities the loop recorded, at the loop's communication step
    # and its internal step (min(0.05, h)), gives the loop's tension: riser got the vessel's motion
    # of t_n for the step from t_n and nothing else, so what the window misses is riser's one-way
    # answer at that step. With the velocities (the five-point design of both, §7.4) it misses by
    # 0.32 %; fed the poses alone (velocities unset: the displacement design), by 0.14 % since that
    # design's slope and curvature are its end values' sequence's ((7.3a), m = 10; 1.76 % before,
    # when its curvature error rang the line's 4 Hz resonance)
    h = 0.25
    two = fixed_step6(fmu_path, vessel6_fmu, h, 50.0, riser=RISER)
    same = reference6(fmu_path, two, h_ref=h, riser={**RISER, "time_step": 0.05})
    poses = reference6(fmu_path, two, h_ref=h, riser={**RISER, "time_step": 0.05}, velocities=False)
    one = reference6(fmu_path, two, h_ref=0.025, riser=RISER)
    gap = np.max(np.abs(same["top_tension"] - two["top_tension"]))
    miss = lambda r: np.max(np.abs(window6(r, 30.0) - window6(one, 30.0)) / window6(one, 30.0))
    print(f"h {h}: max |T_one-way − T_loop| {gap:.2e} N; miss loop {miss(two):.4f}, one way at the loop's "
          f"steps {miss(same):.4f}, poses only {miss(poses):.4f}")
    assert gap <= 1e-3
    assert abs(miss(same) - miss(two)) <= 1e-5
    assert miss(two) <= 0.01 and miss(poses) <= 0.005


def test_six_degree_of_freedom_vessel_under_ecco_through_both_ports(fmu_path, vessel6_fmu):
    # libcosim's ECCO with one power bond per axis: the LinearMechanicalPort (force, velocity) and
    # the AngularMechanicalPort (vessel-frame moment, p q r) of osp/riser_OspModelDescription.xml;
    # velocities only: riser integrates them. Energy: the line's −work_top against the vessel's work
    # within 1e-3 of the energy exchanged; tension window within 1 % of one way
    res = ecco6(fmu_path, vessel6_fmu, 50.0, riser=RISER, step_size=0.05, min_step_size=0.005,
                max_step_size=0.5)
    steps = np.diff(np.concatenate([[0.0], res["t"]]))
    delivered, received, exchanged = -res["work_top"][-1], res["work"][-1], res["work_magnitude"][-1]
    print(f"ECCO: {len(steps)} steps of {steps.min():.4f}-{steps.max():.4f} s; energy line {delivered:.1f} J, "
          f"vessel {received:.1f} J, exchanged {exchanged:.3e} J (rotations to riser: {res['rotations']})")
    assert steps.max() > 2 * steps.min()
    assert abs(delivered - received) <= 1e-3 * exchanged
    one = reference6(fmu_path, res, h_ref=0.025, riser=RISER)
    a, b = window6(res, 30.0), window6(one, 30.0)
    print(f"ECCO window {a} one-way {b}")
    assert np.all(np.abs(a - b) <= 0.01 * b), (a, b)
    # the hang-off is where the vessel puts it: r_h = u + (R − I) ρ from the scene's origin
    d = np.stack([res["surge"], res["sway"], res["heave"]], axis=1) + arm(res, res["rotations"]) - RHO
    h = np.stack([res["shape[0].x"], res["shape[0].y"], res["shape[0].z"]], axis=1)
    err = np.max(np.abs(h - h[0] - (d - d[0])))
    print(f"hang-off against the vessel's pose: {err:.2e} m")
    assert err < 1e-3


def statics_force(riser_bin, shift):
    """The top force of the line at rest in the current with the hang-off displaced by `shift`
    (the anchor moved by −shift: gravity, buoyancy and the uniform current do not see the difference)."""
    def run(sets):
        cmd = [riser_bin, "statics", "catenary", "--json"] + [a for s in sets for a in ("--set", s)]
        return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
    anchor = np.array(run([])["shape"][-1][1:4]) - shift
    sets = ["static_current=true"] + [f"anchor_{c}={float(x)!r}" for c, x in zip("xyz", anchor)]
    return np.array(run(sets)["top_force"])


def test_the_vessel_settles_in_a_current_at_the_static_force_over_its_stiffness(fmu_path, riser_bin, vessel6_fmu):
    # calm sea, the current (0.8 m/s) on the line from t = 0, nothing balanced at the start: the
    # vessel carries the line's whole force on its restoring (moorings 2e5 N/m in surge and sway,
    # critically damped, as is yaw). Reference: the vessel's equilibrium C η = (F, Rᵀ (Rρ) × F) with
    # F from `riser statics` with static_current at the hang-off that pose gives (fixed point)
    from riser_tools.coupling_loop import IDX6, vessel6_defaults
    d = vessel6_defaults(vessel6_fmu)
    vessel = {k: 0.0 for k in ["wave_force_x", "wave_force_y", "wave_force_z", "wave_moment_x", "wave_moment_y",
                               "wave_moment_z"]}
    vessel.update({"stiffness_11": 2e5, "stiffness_22": 2e5, "balance_initial_load": False})
    c = np.array([vessel.get("stiffness_" + k, d["stiffness_" + k]) for k in IDX6])
    m = np.array([d["mass"]] * 3 + [d["inertia_xx"], d["inertia_yy"], d["inertia_zz"]]) \
        + np.array([d["added_mass_" + k] for k in IDX6])
    for i in (0, 1, 5):
        vessel["damping_" + IDX6[i]] = 2 * np.sqrt(m[i] * c[i])
    two = fixed_step6(fmu_path, vessel6_fmu, 0.2, 90.0, riser=RISER, vessel=vessel)
    got = np.array([two[n][two["t"] >= 60.0].mean() for n in POSE])
    # the fixed point
    eta = np.zeros(6)
    for _ in range(8):
        R = rotation(*eta[3:]) if two["rotations"] else np.eye(3)
        f = statics_force(riser_bin, eta[:3] + (R - np.eye(3)) @ RHO)
        load = np.concatenate([f, rotation(*eta[3:]).T @ np.cross(R @ RHO, f)])
        eta = load / c
    print(f"mean pose {got}\nstatics   {eta}\nforce {f}")
    assert abs(got[0] - eta[0]) <= 0.01 * abs(eta[0])  # surge: the current's pull on the moorings
    assert np.all(np.abs(got - eta) <= 0.01 * np.abs(eta) + np.array([1e-4] * 3 + [1e-6] * 3))


def test_the_osp_system_structure_couples_the_vessel_as_the_python_loop_does(fmu_path, vessel6_fmu, tmp_path):
    # osp/vessel6/OspSystemStructure.xml, loaded by libcosim itself (its sources pointed at the FMUs
    # of this test): the same connections and initial values as fixed_step6 at 0.05 s, so the same
    # top tension to round-off after 10 s of the loop
    import re
    import shutil
    from pathlib import Path

    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimObserver import CosimObserver

    xml = (Path(__file__).resolve().parents[2] / "osp" / "vessel6" / "OspSystemStructure.xml").read_text()
    shutil.copy(fmu_path, tmp_path / "riser.fmu")
    shutil.copy(vessel6_fmu, tmp_path / "Vessel6.fmu")
    xml = re.sub(r'source="[^"]*riser\.fmu"', 'source="riser.fmu"', xml)
    (tmp_path / "OspSystemStructure.xml").write_text(xml)
    ex = CosimExecution.from_osp_config_file(osp_path=str(tmp_path / "OspSystemStructure.xml"))
    obs = CosimObserver.create_last_value()
    ex.add_observer(observer=obs)
    idx = {s.name.decode(): s.index for s in ex.slave_infos()}
    refs = {v.name.decode(): v.reference for v in ex.slave_variables(idx["riser"])}
    tension = []
    for _ in range(200):
        assert ex.step()
        tension.append(obs.last_real_values(idx["riser"], [refs["top_tension"]])[0])
    loop = fixed_step6(fmu_path, vessel6_fmu, 0.05, 10.0, riser=RISER)
    print(f"OSP structure against the Python loop: max |ΔT| {np.max(np.abs(np.array(tension) - loop['top_tension'])):.2e} N")
    assert np.allclose(tension, loop["top_tension"], rtol=0, atol=1e-6 * np.max(loop["top_tension"]))
    # and the vessel moved: the loop is closed
    assert np.ptp(tension) > 1e3
