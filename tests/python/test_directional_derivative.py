"""fmi2GetDirectionalDerivative through fmpy (issue 14): the derivative of
top_force_* with respect to heave, surge, sway at the static state equals the
finite difference of two `riser statics` runs with the hang-off moved by ±δ
(moved through the anchor: with gravity and buoyancy uniform, moving the
anchor by −δ is moving the hang-off by +δ); other variables are errors."""

import json
import subprocess

import numpy as np
import pytest
from slaves import started_slave

FORCES = ["top_force_x", "top_force_y", "top_force_z"]
INPUTS = ["surge", "sway", "heave"]  # x, y, z
ANCHOR = ["anchor_x", "anchor_y", "anchor_z"]


def jacobian(s, vr):
    """J[i][j] = ∂ top_force_i / ∂ input_j, one seed per input."""
    cols = []
    for name in INPUTS:
        cols.append(s.getDirectionalDerivative([vr[f] for f in FORCES], [vr[name]], [1.0]))
    return np.array(cols).T


def statics(riser_bin, scene, model, anchor=None):
    sets = [f"model={model}"]
    if anchor is not None:
        sets += [f"{n}={float(v)!r}" for n, v in zip(ANCHOR, anchor)]
    cmd = [riser_bin, "statics", scene, "--json"] + [a for s in sets for a in ("--set", s)]
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def static_top_force(riser_bin, scene, model, anchor):
    return np.array(statics(riser_bin, scene, model, anchor)["top_force"])


@pytest.mark.parametrize("scene", ["catenary", "lazy_wave"])
@pytest.mark.parametrize("model", ["rod", "cable"])
def test_directional_derivative_is_the_static_stiffness(fmu_path, unzipped, riser_bin, scene, model):
    s, vr = started_slave(fmu_path, unzipped, scene=scene, strings={"model": model})
    j = jacobian(s, vr)
    # the scene's anchor: the last row of its static shape (S, x, y, z, tension)
    anchor0 = np.array(statics(riser_bin, scene, model)["shape"][-1][1:4])
    s.terminate()
    s.freeInstance()
    delta = 1e-3
    fd = np.zeros((3, 3))
    for k in range(3):
        e = np.zeros(3)
        e[k] = delta
        # hang-off + δ e_k  ≡  anchor − δ e_k
        fd[:, k] = (static_top_force(riser_bin, scene, model, anchor0 - e)
                    - static_top_force(riser_bin, scene, model, anchor0 + e)) / (2 * delta)
    err = np.abs(j - fd).max() / np.abs(fd).max()
    print(f"{scene} ({model}): J = {j.tolist()}\nFD = {fd.tolist()}\nmax|J - FD|/max|FD| = {err:.2e}")
    assert err < 1e-5
    # the line resists being pulled: −J is the stiffness, positive definite
    assert np.all(np.linalg.eigvalsh(-0.5 * (j + j.T)) > 0)


def test_directional_derivative_follows_the_state_of_a_run(fmu_path, unzipped):
    s, vr = started_slave(fmu_path, unzipped)
    j0 = jacobian(s, vr)
    t, h = 0.0, 0.1
    while t < 6.0 - 1e-9:
        s.setReal([vr["heave"]], [2.5 * np.sin(2 * np.pi * (t + h) / 10.0)])
        s.doStep(t, h)
        t += h
    j = jacobian(s, vr)
    # linear in the seed
    seed = [0.3, -1.2, 2.0]
    combined = s.getDirectionalDerivative([vr[f] for f in FORCES], [vr[n] for n in INPUTS], seed)
    assert np.allclose(combined, j @ np.array(seed), rtol=1e-12, atol=0.0)
    # the stiffness is that of the current state (the hang-off 1.5 m down at t = 6 s: less tension)
    print("static J_zz", j0[2, 2], "at t = 6 s", j[2, 2])
    assert -j[2, 2] < -j0[2, 2]
    s.terminate()
    s.freeInstance()


@pytest.mark.parametrize("unknown,known", [
    ("heave", "heave"),            # an input is not an unknown
    ("top_tension", "heave"),      # a derivative not provided
    ("top_force_z", "top_force_x"),  # an output is not a known
    ("top_force_z", "length"),     # a parameter is not a known
])
def test_other_pairs_are_errors(fmu_path, unzipped, unknown, known):
    from fmpy.fmi1 import FMICallException

    s, vr = started_slave(fmu_path, unzipped)
    with pytest.raises(FMICallException):
        s.getDirectionalDerivative([vr[unknown]], [vr[known]], [1.0])
    s.freeInstance()


def test_unknown_references_and_wrong_states_are_errors(fmu_path, unzipped):
    from fmpy.fmi1 import FMICallException

    s, vr = started_slave(fmu_path, unzipped)
    with pytest.raises(FMICallException):
        s.getDirectionalDerivative([100000], [vr["heave"]], [1.0])
    s.reset()
    # before initialisation: not allowed in state Instantiated
    with pytest.raises(FMICallException):
        s.getDirectionalDerivative([vr["top_force_z"]], [vr["heave"]], [1.0])
    s.reset()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    # in initialisation mode: the static state is computed on demand, as for the outputs
    dz = s.getDirectionalDerivative([vr["top_force_z"]], [vr["heave"]], [1.0])
    assert dz[0] < 0.0
    with pytest.raises(FMICallException):
        s.getDirectionalDerivative([vr["top_force_z"]], [vr["heave"]], [float("nan")])
    s.freeInstance()
