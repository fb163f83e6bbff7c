"""The FMU's directional derivative of a system with free points (issue 49; docs/theory.md §17.8,
docs/guide/fmu.md): the 6x6 d(top_force_*, top_moment_*)/d(surge, sway, heave, roll, pitch, yaw)
of the generic FMU given a system scene, at its static state (the vessel where its inputs put it
at the start), against central differences of `riser statics SYSTEM --pose` (every line and every
free point re-solved at each displaced pose: the points re-balance) and against the statics' own
`stiffness` (the free points condensed, 17.8, 17.9; its rotation columns on small global rotation
vectors, taken to the angles by dtheta = d/da log(R(a)) here). The clump weight (one vessel line,
the first line hung from the clump) and the bridle (two vessel lines coupled through the joint),
coarsened, at the neutral pose and at an offset one: each 3x3 block within 1e-5 of its largest
entry of the differences (the single line's tolerance, test_vessel.py) and 1e-8 of the statics'
stiffness (the same tangent, assembled from the FMU's lines' states)."""
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest
from slaves import started_slave
from test_vessel import rotation

ROOT = Path(__file__).resolve().parents[2]
CASES = {
    "clump": ("clump_weight_mooring.toml", [("n_elements = 60", "n_elements = 20"),
                                            ("n_elements = 52", "n_elements = 18")]),
    "bridle": ("bridle_mooring.toml", [("n_elements = 300", "n_elements = 60"),
                                       ("n_elements = 20", "n_elements = 10")]),
}
POSE = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
LOADS = [f"top_{q}_{c}" for q in ("force", "moment") for c in "xyz"]
OFFSET = [5.0, -2.0, 0.5, 0.01, -0.015, 0.03]
# central differences of 3 mm and 3e-5 rad: the statics' Newton on the points (to 1e-8 of their
# force scale) and the lines' (1e-8) leave noise of ~1e-8 of the loads over 2 delta; the bridle's
# blocks against the differences measured 1.1e-5 at 1e-2 m (its truncation), 6.8e-6 at 3e-3 m
DELTA = [3e-3] * 3 + [3e-5] * 3


@pytest.fixture(scope="module")
def scenes(tmp_path_factory):
    d = tmp_path_factory.mktemp("free_dd")
    out = {}
    for name, (file, edits) in CASES.items():
        text = (ROOT / "docs" / "cases" / file).read_text()
        for a, b in edits:
            text = text.replace(a, b)
        out[name] = d / f"{name}.toml"
        out[name].write_text(text)
    return out


def statics(riser_bin, scene, pose):
    cmd = [riser_bin, "statics", str(scene), "--json", "--pose", ",".join(repr(float(p)) for p in pose)]
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def loads(st):
    return np.concatenate([st["top_force"], st["top_moment"]])


def angles_to_rotation_vector(angles, eps=1e-6):
    """T: the small global rotation dtheta of an angles' change, column k = vee(dR/da_k R^T)."""
    r = rotation("zyx", angles)
    t = np.zeros((3, 3))
    for k in range(3):
        e = np.zeros(3)
        e[k] = eps
        w = (rotation("zyx", np.add(angles, e)) - rotation("zyx", np.subtract(angles, e))) / (2 * eps) @ r.T
        t[:, k] = [w[2, 1], w[0, 2], w[1, 0]]
    return t


@pytest.mark.parametrize("name", ["clump", "bridle"])
@pytest.mark.parametrize("at", ["neutral", "offset"])
def test_the_directional_derivative_is_the_re_balanced_statics(fmu_path, unzipped, riser_bin, scenes, name, at):
    pose = np.zeros(6) if at == "neutral" else np.array(OFFSET)
    s, vr = started_slave(fmu_path, unzipped, scene=str(scenes[name]), reals=dict(zip(POSE, pose)))
    j = np.array([s.getDirectionalDerivative([vr[n] for n in LOADS], [vr[p]], [1.0]) for p in POSE]).T
    start = np.array(s.getReal([vr[n] for n in LOADS]))
    s.terminate()
    s.freeInstance()
    st = statics(riser_bin, scenes[name], pose)
    # the FMU starts in the statics at the pose
    assert np.abs(start - loads(st)).max() <= 1e-8 * np.abs(loads(st)).max(), (start.tolist(), loads(st).tolist())
    fd = np.zeros((6, 6))
    for k in range(6):
        e = np.zeros(6)
        e[k] = DELTA[k]
        fd[:, k] = (loads(statics(riser_bin, scenes[name], pose + e))
                    - loads(statics(riser_bin, scenes[name], pose - e))) / (2 * DELTA[k])
    t = np.eye(6)
    t[3:, 3:] = angles_to_rotation_vector(pose[3:])
    own = -np.array(st["stiffness"]) @ t
    worst_fd, worst_own = 0.0, 0.0
    for bi in (0, 3):
        for bj in (0, 3):
            b = (slice(bi, bi + 3), slice(bj, bj + 3))
            e_fd = np.abs(j[b] - fd[b]).max() / np.abs(fd[b]).max()
            e_own = np.abs(j[b] - own[b]).max() / np.abs(own[b]).max()
            worst_fd, worst_own = max(worst_fd, e_fd), max(worst_own, e_own)
            assert e_fd <= 1e-5, (name, at, bi, bj, j[b].tolist(), fd[b].tolist(), e_fd)
            assert e_own <= 1e-8, (name, at, bi, bj, j[b].tolist(), own[b].tolist(), e_own)
    print(f"{name} at the {at} pose: worst block max|J - FD|/max|FD| = {worst_fd:.2e}, "
          f"against the statics' stiffness {worst_own:.2e}")
