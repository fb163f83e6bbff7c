"""The six-degree-of-freedom vessel FMU (osp/vessel/Vessel6.py, issue 30) alone, against closed forms:
its default hull numbers against the hydrostatics they are documented from (C33 = ρ g A_wp,
C44 = ρ g ∇ GM_T, C55 = ρ g ∇ GM_L); free decay in heave, roll and pitch against the damped
oscillator (M + A) x'' + B x' + C x = 0 (damped period 2π/(ω_n √(1 − ζ²)), logarithmic decrement
2π ζ/√(1 − ζ²), ω_n = √(C/(M + A)), ζ = B/(2 √((M + A) C))); and the static offset under a constant
force and moment (x = F/C; a moment about one axis alone turns the vessel by M/C exactly, combined
moments satisfy C Θ = Rᵀ(Θ) M + M_b, M global, M_b in the vessel frame)."""
import math

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu

RHO, G = 1025.0, 9.81
IDX = ["11", "22", "33", "44", "55", "66"]


@pytest.fixture(scope="module")
def vessel6_fmu(tmp_path_factory):
    from riser_tools.coupling_loop import build_vessel_fmu
    return build_vessel_fmu(tmp_path_factory.mktemp("vessel6"), "Vessel6")


@pytest.fixture(scope="module")
def defaults(vessel6_fmu):
    md = read_model_description(vessel6_fmu)
    return {v.name: float(v.start) for v in md.modelVariables if v.causality == "parameter" and v.type == "Real"}


CALM = {k: 0.0 for k in ["wave_force_x", "wave_force_y", "wave_force_z",
                         "wave_moment_x", "wave_moment_y", "wave_moment_z"]}


def inertia(d, i):
    own = [d["mass"]] * 3 + [d["inertia_xx"], d["inertia_yy"], d["inertia_zz"]]
    return own[i] + d["added_mass_" + IDX[i]]


def test_the_default_hull_is_the_documented_100_m_vessel(defaults):
    # L 100 m, B 20 m, T 6 m, C_B 0.70, C_WP 0.80, GM_T 2 m, GM_L 120 m, radii of gyration 7, 25, 25 m
    volume = 100.0 * 20.0 * 6.0 * 0.70
    m = RHO * volume
    want = {"mass": m, "stiffness_33": RHO * G * 100.0 * 20.0 * 0.80, "stiffness_44": RHO * G * volume * 2.0,
            "stiffness_55": RHO * G * volume * 120.0, "inertia_xx": m * 7.0**2, "inertia_yy": m * 25.0**2,
            "inertia_zz": m * 25.0**2}
    for k, v in want.items():
        assert abs(defaults[k] - v) <= 1e-12 * v, (k, defaults[k], v)
    periods = {d: 2 * math.pi * math.sqrt(inertia(defaults, i) / defaults["stiffness_" + IDX[i]])
               for i, d in [(2, "heave"), (3, "roll"), (4, "pitch")]}
    print("natural periods", periods)
    # the periods of a 100 m vessel: heave and pitch 6-7 s, roll about 11 s
    assert 6.0 < periods["heave"] < 7.0 and 6.0 < periods["pitch"] < 7.0 and 10.5 < periods["roll"] < 11.5


def crossings(t, x):
    k = np.nonzero((x[:-1] > 0) & (x[1:] <= 0))[0]
    return t[k] + x[k] / (x[k] - x[k + 1]) * (t[k + 1] - t[k])


def peaks(x):
    """Maxima refined by the parabola through the three samples about each."""
    k = np.nonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:]))[0] + 1
    a, b, c = x[k - 1], x[k], x[k + 1]
    return b - (a - c) ** 2 / (8 * (a - 2 * b + c))


@pytest.mark.parametrize("dof,i,x0", [("heave", 2, 0.5), ("roll", 3, 0.05), ("pitch", 4, 0.02)])
def test_free_decay_has_the_closed_form_period_and_logarithmic_decrement(vessel6_fmu, defaults, dof, i, x0):
    m, c, b = inertia(defaults, i), defaults["stiffness_" + IDX[i]], defaults["damping_" + IDX[i]]
    wn = math.sqrt(c / m)
    zeta = b / (2 * math.sqrt(m * c))
    wd = wn * math.sqrt(1 - zeta**2)
    period, decrement = 2 * math.pi / wd, 2 * math.pi * zeta / math.sqrt(1 - zeta**2)
    dt = 0.01
    res = simulate_fmu(vessel6_fmu, stop_time=4 * period, output_interval=dt, step_size=dt,
                       start_values={**CALM, "initial_" + dof: x0}, output=[dof, "surge", "yaw"])
    t, x = res["time"], res[dof]
    # the whole record against the closed form x0 e^{-ζ ω t} (cos ω_d t + ζ ω_n/ω_d sin ω_d t)
    exact = x0 * np.exp(-zeta * wn * t) * (np.cos(wd * t) + zeta * wn / wd * np.sin(wd * t))
    assert np.max(np.abs(x - exact)) <= 1e-7 * x0, np.max(np.abs(x - exact))
    tc = crossings(t, x)
    got_period = np.mean(np.diff(tc))
    p = peaks(x)
    got_decrement = np.mean(np.log(p[:-1] / p[1:]))
    print(f"{dof}: period {got_period:.6f} s (closed form {period:.6f}), log decrement {got_decrement:.6f} "
          f"({decrement:.6f}), zeta {zeta:.3f}")
    assert abs(got_period - period) <= 1e-4 * period
    assert abs(got_decrement - decrement) <= 1e-4 * decrement
    # one degree of freedom alone: nothing else moves
    assert np.max(np.abs(res["surge"])) == 0.0 and np.max(np.abs(res["yaw"])) == 0.0


def settle(vessel6_fmu, defaults, loads, stop_time=700.0):
    # critically damped in every degree of freedom: after ω_n t ≥ 40 (the 100 s surge) the transient
    # is below 1e-15 of the offset
    crit = {"damping_" + k: 2 * math.sqrt(inertia(defaults, i) * defaults["stiffness_" + k])
            for i, k in enumerate(IDX)}
    names = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    res = simulate_fmu(vessel6_fmu, stop_time=stop_time, output_interval=1.0, step_size=1.0,
                       start_values={**CALM, **crit, "max_substep": 0.05, "balance_initial_load": False, **loads},
                       output=names)
    return np.array([res[n][-1] for n in names])


def test_a_constant_force_and_moment_offset_the_vessel_by_load_over_stiffness(vessel6_fmu, defaults):
    from riser_tools.coupling_loop import rotation
    c = np.array([defaults["stiffness_" + k] for k in IDX])
    force = np.array([1.0e5, -2.0e5, 1.5e6])
    moment = np.array([5.0e6, -2.0e7, 1.0e6])
    loads = dict(zip(["top_force_x", "top_force_y", "top_force_z", "top_moment_x", "top_moment_y", "top_moment_z"],
                     np.concatenate([force, moment]).tolist()))
    body = np.array([1.0e6, 0.0, -5.0e5])  # and a moment in the vessel frame (the angular port's torque)
    loads.update(dict(zip(["vessel_moment_x", "vessel_moment_y", "vessel_moment_z"], body.tolist())))
    pose = settle(vessel6_fmu, defaults, loads)
    print("pose", pose, "load / stiffness", np.concatenate([force, moment]) / c[:6])
    # translations: x = F/C exactly (global frame, no coupling)
    assert np.all(np.abs(pose[:3] - force / c[:3]) <= 1e-9 * np.abs(force / c[:3]))
    # rotations: the moment (global) reaches the vessel in its own frame, C Θ = Rᵀ(Θ) M (z-y-x), to
    # round-off (plus the vessel-frame moment M_b as it is). M/C holds to first order only: a global pitch moment on a rolled vessel has a part
    # about its yaw axis (here 2e7 N m x 0.021 rad against the 1e6 N m yaw moment, yaw 0.071 rad
    # instead of M_z/C66 = 0.050 with the soft yaw spring); each axis alone is exact (next test)
    theta = pose[3:]
    resid = c[3:] * theta - rotation(*theta).T @ moment - body
    print("C Θ − Rᵀ M", resid, "Θ", theta, "M/C", moment / c[3:])
    assert np.max(np.abs(resid)) <= 1e-9 * np.max(np.abs(moment)), resid


@pytest.mark.parametrize("axis", [3, 4, 5])
def test_a_moment_about_one_axis_turns_the_vessel_by_moment_over_stiffness(vessel6_fmu, defaults, axis):
    name = ["top_moment_x", "top_moment_y", "top_moment_z"][axis - 3]
    value = [5.0e6, -2.0e8, 1.0e6][axis - 3]
    pose = settle(vessel6_fmu, defaults, {name: value})
    want = value / defaults["stiffness_" + IDX[axis]]
    others = np.delete(pose, axis)
    print(f"{name}: angle {pose[axis]:.9e} rad, M/C {want:.9e}")
    assert abs(pose[axis] - want) <= 1e-9 * abs(want)
    assert np.max(np.abs(others)) <= 1e-12
