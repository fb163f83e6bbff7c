"""The vessel in six degrees of freedom through the FMU (issue 30, evidence 2, 5, 6
and the rotations' input path): the inputs are the vessel reference point's
translations and its angles, the hang-off at rho in the vessel frame.

References: the statics of the scene with the hang-off moved to u + (R - I) rho
(moved through the anchor, as tests/python/test_directional_derivative.py does:
with gravity and buoyancy uniform, moving the anchor by -d is moving the
hang-off by +d), the moment about the reference point M = (R rho) x F, and
`riser run` with the exact angles (the same rotation composed in the CLI); for a
clamped end or a flex joint, the statics with the vessel's frame turned too
(examples/vessel_statics.rs: `riser statics` cannot turn a clamp's frame)."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.fmi1 import FMICallException
from slaves import started_slave

RHO = np.array([30.0, 6.0, -4.0])
ANCHOR = ["anchor_x", "anchor_y", "anchor_z"]
POSE = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
LOADS = [f"{p}_{c}" for p in ("top_force", "top_moment", "vessel_force", "vessel_moment") for c in "xyz"]
OFFSET = {"hang_off_x": RHO[0], "hang_off_y": RHO[1], "hang_off_z": RHO[2]}
RAMP_POSE, SETTLE, AVERAGE, TOL_HELD = 60.0, 400.0, 200.0, 1e-6


def worst_block_error(j, fd, what, tol=1e-5):
    """The 12 x 6 derivative against its finite differences, block by 3 x 3 block (force, moment,
    vessel force, vessel moment against translations, rotations): each block's max |J - FD| over
    its max |FD| within `tol`; the worst of them."""
    worst = 0.0
    for bi in range(4):
        for bj in range(2):
            b = (slice(3 * bi, 3 * bi + 3), slice(3 * bj, 3 * bj + 3))
            err = np.abs(j[b] - fd[b]).max() / np.abs(fd[b]).max()
            worst = max(worst, err)
            assert err <= tol, (what, bi, bj, j[b].tolist(), fd[b].tolist(), err)
    return worst

def rot(axis, a):
    c, s = np.cos(a), np.sin(a)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    r = np.eye(3)
    r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
    return r


def rotation(order, angles):
    """R of [roll, pitch, yaw]: zyx = Rz Ry Rx, xyz = Rx Ry Rz (docs/theory.md 14.1)."""
    rx, ry, rz = (rot(k, a) for k, a in enumerate(angles))
    return rz @ ry @ rx if order == "zyx" else rx @ ry @ rz


# still water: the FMU's force at the static state is then the statics' (with the
# current, the FMU's outputs include the current's drag on the line at rest, the
# statics not: static_current = false)
STILL = {"current_top": 0.0, "current_bottom": 0.0}


def statics(riser_bin, scene, model, anchor=None):
    sets = [f"model={model}"] + [f"{k}={v}" for k, v in STILL.items()]
    if anchor is not None:
        sets += [f"{n}={float(v)!r}" for n, v in zip(ANCHOR, anchor)]
    cmd = [riser_bin, "statics", scene, "--json"] + [a for s in sets for a in ("--set", s)]
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def pose_loads(riser_bin, scene, model, anchor0, pose, order="zyx"):
    """The statics' loads on the vessel at `pose` (surge, sway, heave, roll,
    pitch, yaw): F, M = (R rho) x F and both in the vessel frame (12)."""
    r = rotation(order, pose[3:])
    arm = r @ RHO
    hang_off = np.asarray(pose[:3]) + arm - RHO
    f = np.array(statics(riser_bin, scene, model, anchor0 - hang_off)["top_force"])
    m = np.cross(arm, f)
    return np.concatenate([f, m, r.T @ f, r.T @ m])


@pytest.mark.parametrize("scene,model", [("catenary", "rod"), ("catenary", "cable"), ("lazy_wave", "rod")])
def test_the_6x6_directional_derivative_is_the_statics_of_the_moved_and_rotated_vessel(
        fmu_path, unzipped, riser_bin, scene, model):
    """Evidence 5: d(force, moment; global and vessel frame) / d(translations,
    rotations) at the static state against central differences of the statics
    at the moved and rotated vessel, per 3x3 block <= 1e-5 of the block's largest."""
    s, vr = started_slave(fmu_path, unzipped, scene=scene, strings={"model": model}, reals={**OFFSET, **STILL})
    f0 = np.array(s.getReal([vr[f"top_force_{c}"] for c in "xyz"]))
    assert np.abs(f0 - statics(riser_bin, scene, model)["top_force"]).max() <= 1e-9 * np.linalg.norm(f0)
    j = np.array([s.getDirectionalDerivative([vr[n] for n in LOADS], [vr[p]], [1.0]) for p in POSE]).T
    # linear in the seed
    seed = [0.3, -1.2, 2.0, 0.01, -0.02, 0.03]
    combined = s.getDirectionalDerivative([vr[n] for n in LOADS], [vr[p] for p in POSE], seed)
    assert np.allclose(combined, j @ np.array(seed), rtol=1e-12, atol=1e-9 * np.abs(j).max())
    s.terminate()
    s.freeInstance()
    anchor0 = np.array(statics(riser_bin, scene, model)["shape"][-1][1:4])
    delta = [1e-3] * 3 + [1e-4] * 3
    fd = np.zeros((12, 6))
    for k in range(6):
        e = np.zeros(6)
        e[k] = delta[k]
        fd[:, k] = (pose_loads(riser_bin, scene, model, anchor0, e)
                    - pose_loads(riser_bin, scene, model, anchor0, -e)) / (2 * delta[k])
    worst = worst_block_error(j, fd, (scene, model))
    print(f"{scene} ({model}): worst block max|J - FD|/max|FD| = {worst:.2e}")


ROOT = Path(__file__).resolve().parents[2]
ENDS = {"clamped": {"hang_off_end": "clamped"},
        "flex_joint": {"hang_off_end": "flex_joint", "flex_joint_stiffness": 1e6}}


@pytest.fixture(scope="session")
def vessel_statics():
    """examples/vessel_statics.rs: the statics with the hang-off moved and the vessel's frame turned (a
    clamp's frame turned with it, a flex joint's spring held against it), which `riser statics` cannot
    give (it moves the hang-off through the anchor). Built in the fasttest profile whatever the binary
    under test (`make test` has just built the library there, so this is a link, not an optimised
    build; neither profile lets the compiler reorder floating point: the same numbers)."""
    subprocess.run(["cargo", "build", "--profile", "fasttest", "--example", "vessel_statics"], cwd=ROOT, check=True,
                   capture_output=True)
    return str(ROOT / "target" / "fasttest" / "examples" / "vessel_statics")


def end_pose_loads(exe, scene, end, pose, order="zyx"):
    """The statics' loads on the vessel at `pose` with the end `end`: F, the line's end moment M_e,
    M = (R rho) x F + M_e and both in the vessel frame (12)."""
    r = rotation(order, pose[3:])
    arm = r @ RHO
    hang_off = np.asarray(pose[:3]) + arm - RHO
    sets = {"model": "rod", **ENDS[end], **OFFSET, **STILL}
    cmd = [exe, scene] + [repr(float(x)) for x in [*hang_off, *r.flatten()]] + [f"{k}={v}" for k, v in sets.items()]
    out = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
    f, me = np.array(out["force"]), np.array(out["end_moment"])
    m = np.cross(arm, f) + me
    return np.concatenate([f, m, r.T @ f, r.T @ m])


@pytest.mark.parametrize("end", ["clamped", "flex_joint"])
def test_the_12x6_of_a_clamped_or_flex_joint_end_is_the_statics_of_the_moved_and_turned_vessel(
        fmu_path, unzipped, vessel_statics, end):
    """A clamp (its frame R D_static) and a flex joint (1e6 N m/rad against R D_static): the full
    12x6 (the end's moment stiffness condensed, docs/theory.md 8.7) against central differences of
    the statics at the moved and turned vessel (examples/vessel_statics.rs), per 3x3 block <= 1e-5
    of the block's largest; the end moment's own part of d(top_moment)/d(rotations) is not small."""
    reals = {**OFFSET, **STILL, **{k: v for k, v in ENDS[end].items() if k != "hang_off_end"}}
    s, vr = started_slave(fmu_path, unzipped, scene="catenary", strings={"model": "rod", "hang_off_end": end},
                          reals=reals)
    loads0 = np.array(s.getReal([vr[n] for n in LOADS]))
    j = np.array([s.getDirectionalDerivative([vr[n] for n in LOADS], [vr[p]], [1.0]) for p in POSE]).T
    s.terminate()
    s.freeInstance()
    ref0 = end_pose_loads(vessel_statics, "catenary", end, np.zeros(6))
    assert np.abs(loads0 - ref0).max() <= 1e-9 * np.abs(ref0).max(), (loads0.tolist(), ref0.tolist())
    delta = [1e-3] * 3 + [1e-4] * 3
    fd = np.zeros((12, 6))
    for k in range(6):
        e = np.zeros(6)
        e[k] = delta[k]
        fd[:, k] = (end_pose_loads(vessel_statics, "catenary", end, e)
                    - end_pose_loads(vessel_statics, "catenary", end, -e)) / (2 * delta[k])
    worst = worst_block_error(j, fd, end)
    # the end moment's part: d(top_moment)/d(rotations) less the arm's (d theta x R rho) x F + R rho x dF
    f0, arm = loads0[:3], RHO
    arm_part = np.array([np.cross(np.cross(np.eye(3)[c], arm), f0) + np.cross(arm, j[0:3, 3 + c])
                         for c in range(3)]).T
    own = np.abs(j[3:6, 3:6] - arm_part).max() / np.abs(j[3:6, 3:6]).max()
    print(f"catenary ({end}): worst block max|J - FD|/max|FD| = {worst:.2e}; the end moment's share of "
          f"dM/dtheta {own:.2e}")
    assert own > 1e-3, own


def held_pose_run(fmu_path, unzipped, order, pose, ramp, settle, average):
    """The FMU ramped from rest to `pose` over `ramp` s (the angles through
    the input path), then held `settle` s with the line's motion damped (drag
    in still water and structural damping change no static force). Returns
    the loads at the end and their mean over the last `average` s (the line's
    slowest pendulum mode, out of the plane, still swings by a few newtons
    under quadratic drag: its mean is the equilibrium)."""
    s, vr = started_slave(fmu_path, unzipped, strings={"rotation_order": order},
                          reals={**OFFSET, **STILL, "cd_normal": 5.0, "structural_damping": 2.0})
    t, h, rows = 0.0, 0.2, []
    while t < ramp + settle - 1e-9:
        r = 0.5 * (1.0 - np.cos(np.pi * min(t, ramp) / ramp))
        s.setReal([vr[p] for p in POSE], list(np.asarray(pose) * r))
        s.doStep(t, h)
        t += h
        if t > ramp + settle - average:
            rows.append(s.getReal([vr[n] for n in LOADS]))
    s.terminate()
    s.freeInstance()
    return dict(zip(LOADS, rows[-1])), dict(zip(LOADS, np.mean(rows, axis=0)))


@pytest.mark.parametrize("order", ["zyx", "xyz"])
def test_a_vessel_held_at_a_rotated_pose_has_the_statics_of_the_moved_hang_off(fmu_path, unzipped, riser_bin,
                                                                                 order):
    """Evidence 2: the force equals the statics with the hang-off moved to
    u + (R - I) rho (pinned); the moment about the reference point is
    (R rho) x F to round-off."""
    pose = [1.0, -0.5, 0.8, 0.05, -0.04, 0.1]
    got, mean = held_pose_run(fmu_path, unzipped, order, pose, ramp=RAMP_POSE, settle=SETTLE, average=AVERAGE)
    f = np.array([got[f"top_force_{c}"] for c in "xyz"])
    f_mean = np.array([mean[f"top_force_{c}"] for c in "xyz"])
    m = np.array([got[f"top_moment_{c}"] for c in "xyz"])
    r = rotation(order, pose[3:])
    anchor0 = np.array(statics(riser_bin, "catenary", "rod")["shape"][-1][1:4])
    ref = pose_loads(riser_bin, "catenary", "rod", anchor0, pose, order)
    err = np.abs(f_mean - ref[:3]).max() / np.linalg.norm(ref[:3])
    print(f"{order}: F = {f_mean.tolist()} (mean), statics {ref[:3].tolist()}, max|dF|/|F| = {err:.2e}")
    assert err < TOL_HELD
    # the moment is the arm times the FMU's own force, to round-off
    assert np.abs(m - np.cross(r @ RHO, f)).max() <= 1e-12 * np.linalg.norm(m)
    vf = np.array([got[f"vessel_force_{c}"] for c in "xyz"])
    assert np.abs(r @ vf - f).max() <= 1e-12 * np.linalg.norm(f)


# periods as the translations' test (20 s) and longer: the hang-off's motion R(t) rho
# holds the angles' sum frequencies too (here 11 s), which a 0.5 s communication step
# follows as it follows a heave of that period (tests/python/test_cosim_inputs.py)
AMPLITUDES = {"roll": (0.05, 20.0), "pitch": (0.03, 25.0), "yaw": (0.1, 30.0)}
RAMP, DURATION, WINDOW = 20.0, 100.0, 40.0


def angle(name, t):
    a, period = AMPLITUDES[name]
    r = np.where(t < RAMP, 0.5 * (1.0 - np.cos(np.pi * t / RAMP)), 1.0)
    return a * r * np.sin(2 * np.pi * t / period)


def window_stats(time, x):
    m = time >= WINDOW - 1e-9
    return np.array([x[m].min(), x[m].max(), x[m].mean()])


_exact = {}


def exact_rotation_run(riser_bin, dt, tmp_path_factory):
    if dt not in _exact:
        out = tmp_path_factory.mktemp("exact_rot")
        motion = [a for n, (amp, per) in AMPLITUDES.items() for a in (f"--{n}", f"{amp},{per}")]
        sets = [a for k, v in {**OFFSET, "time_step": dt}.items() for a in ("--set", f"{k}={v}")]
        subprocess.run([riser_bin, "run", "catenary", *motion, "--ramp", str(RAMP), "--duration", str(DURATION),
                        *sets, "--out", str(out)], check=True, capture_output=True)
        ts = np.genfromtxt(out / "timeseries.csv", delimiter=",", names=True)
        _exact[dt] = {n: window_stats(ts["t"], ts[n]) for n in ("top_tension", "top_moment_y", "top_moment_z")}
    return _exact[dt]


@pytest.mark.parametrize("h", [0.05, 0.2, 0.5])
def test_the_rotations_input_path_gives_the_exact_motion_loads_within_1_percent(fmu_path, riser_bin,
                                                                                 tmp_path_factory, h):
    """Roll, pitch and yaw at their communication points only (the hang-off
    30 m ahead): the window's min, max and mean of the top tension and the
    moments about the reference point within 1 % of `riser run` with the
    exact angles at the same internal step, at every communication step (1 %
    of the largest of the three in magnitude)."""
    t = np.arange(0.0, DURATION + 1e-9, h)
    names = list(AMPLITUDES)
    sig = np.array(list(zip(t, *(angle(n, t) for n in names))),
                   dtype=[("time", np.float64)] + [(n, np.float64) for n in names])
    dt = min(0.05, h)
    res = simulate_fmu(fmu_path, stop_time=DURATION, output_interval=h, input=sig,
                       output=["top_tension", "top_moment_y", "top_moment_z"],
                       start_values={"time_step": dt, **OFFSET})
    ref = exact_rotation_run(riser_bin, dt, tmp_path_factory)
    for n, r in ref.items():
        got = window_stats(res["time"], res[n])
        scale = np.abs(r).max()
        print(h, n, got.tolist(), r.tolist())
        assert np.all(np.abs(got - r) <= 0.01 * scale), (h, n, got, r)


BAD_CHILD = r"""
import json, sys
sys.path.insert(0, sys.argv[3])
from fmpy.fmi1 import FMICallException
from slaves import started_slave
fmu_path, unzipped = sys.argv[1], sys.argv[2]
out = []
for name, x in [("roll", float("nan")), ("yaw", float("inf")), ("angular_velocity_z", float("nan"))]:
    s, vr = started_slave(fmu_path, unzipped)
    try:
        s.setReal([vr[name]], [x])
        out.append([name, 0])
    except FMICallException as e:
        out.append([name, e.status])
    s.freeInstance()
try:
    started_slave(fmu_path, unzipped, strings={"rotation_order": "yxz"})
    out.append(["rotation_order", 0])
except FMICallException as e:
    out.append(["rotation_order", e.status])
print("@@result " + json.dumps(out), flush=True)
"""


def test_bad_rotation_inputs_are_errors(fmu_path, unzipped):
    """Non-finite angles and angular velocities, and a rotation order that is neither zyx nor xyz,
    are fmi2Error (in a child process: fmpy's logger proxy is process-wide and may point at a callback an earlier test's slave freed, as in test_waves.py); the log names them
    (tests/python/test_waves.py's pattern checks messages; here the statuses)."""
    here = str(Path(__file__).parent)
    p = subprocess.run([sys.executable, "-c", BAD_CHILD, fmu_path, unzipped, here], capture_output=True, text=True,
                       timeout=300)
    assert p.returncode == 0, p.stderr
    rows = json.loads(p.stdout.split("@@result ")[1])
    assert [r[0] for r in rows] == ["roll", "yaw", "angular_velocity_z", "rotation_order"]
    assert all(r[1] == 3 for r in rows), rows
    for name in ["roll", "yaw", "angular_velocity_z", "rotation_order"]:
        assert name in p.stdout + p.stderr, (name, p.stdout, p.stderr)


def test_state_save_restore_with_rotations_is_bit_for_bit(fmu_path, unzipped):
    s, vr = started_slave(fmu_path, unzipped, reals=OFFSET)

    def run(t0, t1, h=0.1):
        rows, t = [], t0
        while t < t1 - 1e-9:
            s.setReal([vr[n] for n in ("roll", "pitch", "yaw", "heave")],
                      [0.05 * np.sin(0.5 * t), -0.03 * np.sin(0.7 * t), 0.1 * np.sin(0.3 * t), np.sin(0.4 * t)])
            s.doStep(t, h)
            t += h
            rows.append(s.getReal([vr[n] for n in LOADS]))
        return np.array(rows)

    run(0.0, 5.0)
    state = s.getFMUstate()
    first = run(5.0, 8.0)
    s.setFMUstate(state)
    second = run(5.0, 8.0)
    assert np.array_equal(first, second)
    blob = s.serializeFMUstate(state)
    restored = s.deSerializeFMUstate(blob)
    s.setFMUstate(restored)
    assert np.array_equal(first, run(5.0, 8.0))
    s.freeFMUstate(state)
    s.terminate()
    s.freeInstance()
