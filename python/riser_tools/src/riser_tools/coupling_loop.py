"""Two-way coupling of riser's FMU to a floating body, driven the way libcosim's fixed-step
algorithm drives two FMUs (Jacobi): at each communication point t_n both units get the other's
outputs of t_n, then both step to t_{n+1}. The body is not a second FMU but its heave ODE
integrated in this master, the riser's force held over the step as a body FMU would see it:

    (M + A) x'' + C x' + K x = F_wave sin(2π t / T_wave) + (top_force_z(t_n) − top_force_z(0))

(RK4 with 20 substeps per communication step; the wave force evaluated continuously). The riser
gets `heave` = x(t_n) and `heave_velocity` = x'(t_n) (both set: `auto` couples the displacement,
the velocity starts the line). With `feedback=False` the body moves on the wave alone and riser
follows it one way; `motion=(t, x, v)` replays a recorded motion instead (the reference of a
two-way run: one-way with the two-way run's motion).

This loop is libcosim's fixed-step exchange with the body's FMU replaced by its ODE: any body is
a few numbers (the buoy of docs/theory.md §7.3). With the vessel as an FMU (osp/vessel/Vessel.py,
pythonfmu), `fixed_step` and `ecco` run libcosim itself: its fixed-step algorithm and ECCO with the
power bond (what tests/python/test_coupling.py checks).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .coupling_analysis import BUOY, VESSEL, Body


@dataclass(frozen=True)
class Wave:
    force: float  # N, amplitude of the heave excitation
    period: float  # s
    ramp: float = 20.0  # s, ½(1 − cos(πt/ramp)) growth

    def at(self, t):
        r = 0.5 * (1.0 - np.cos(np.pi * min(t, self.ramp) / self.ramp))
        return self.force * r * np.sin(2 * np.pi * t / self.period)


# heave amplitudes about 0.25 m (vessel, as in issue 29) and 0.4 m (buoy) at 10 s
VESSEL_WAVE = Wave(force=1.1e6, period=10.0)
BUOY_WAVE = Wave(force=2.0e4, period=10.0)


def _rk4(body: Body, s, t, h, wave: Wave, force: float, substeps: int = 20):
    m = body.mass + body.added_mass

    def f(t, s):
        return np.array([s[1], (wave.at(t) + force - body.damping * s[1] - body.stiffness * s[0]) / m])

    dt = h / substeps
    for k in range(substeps):
        tk = t + k * dt
        k1 = f(tk, s)
        k2 = f(tk + dt / 2, s + dt / 2 * k1)
        k3 = f(tk + dt / 2, s + dt / 2 * k2)
        k4 = f(tk + dt, s + dt * k3)
        s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return s


def two_way(fmu_path: str, body: Body, wave: Wave, h: float, duration: float, feedback: bool = True,
            motion=None, start_values: dict | None = None, noise: float = 0.0):
    """Runs the loop; returns dict of arrays t, heave, heave_velocity, top_tension, top_force_z
    (at the communication points, t = 0 included). `noise` adds ±noise alternating to the heave
    the riser gets (a body model's round-off)."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    md = read_model_description(fmu_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    unzipped = extract(fmu_path)
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier="riser", instanceName="riser")
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    for k, v in (start_values or {"time_step": min(0.05, h)}).items():
        s.setReal([vr[k]], [v])
    s.setReal([vr["heave"], vr["heave_velocity"]], [0.0, 0.0])
    s.exitInitializationMode()
    f0 = s.getReal([vr["top_force_z"]])[0]
    n = int(round(duration / h))
    out = {k: np.zeros(n + 1) for k in ["t", "heave", "heave_velocity", "top_tension", "top_force_z"]}
    state = np.zeros(2)
    tension, fz = s.getReal([vr["top_tension"], vr["top_force_z"]])
    try:
        for k in range(n + 1):
            t = k * h
            if motion is not None:
                state = np.array([np.interp(t, motion[0], motion[1]), np.interp(t, motion[0], motion[2])])
            out["t"][k], out["heave"][k], out["heave_velocity"][k] = t, state[0], state[1]
            out["top_tension"][k], out["top_force_z"][k] = tension, fz
            if k == n:
                break
            # Jacobi: both units get the outputs of t_n, then both step
            x = state[0] + (noise * (-1.0) ** k if k > 0 else 0.0)
            s.setReal([vr["heave"], vr["heave_velocity"]], [float(x), float(state[1])])
            if motion is None:
                force = (fz - f0) if feedback else 0.0
                state = _rk4(body, state, t, h, wave, force)
            s.doStep(t, h)
            tension, fz = s.getReal([vr["top_tension"], vr["top_force_z"]])
    finally:
        s.terminate()
        s.freeInstance()
    return out


def hermite_motion(t, times, x, v):
    """The cubic Hermite interpolant of the samples (x, v) at `times`, and its slope, at t."""
    t = np.asarray(t, dtype=float)
    k = np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2)
    h = times[k + 1] - times[k]
    s = (t - times[k]) / h
    h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2
    d00, d10, d01, d11 = 6 * s**2 - 6 * s, 3 * s**2 - 4 * s + 1, -6 * s**2 + 6 * s, 3 * s**2 - 2 * s
    pos = h00 * x[k] + h10 * h * v[k] + h01 * x[k + 1] + h11 * h * v[k + 1]
    vel = (d00 * x[k] + d01 * x[k + 1]) / h + d10 * v[k] + d11 * v[k + 1]
    return pos, vel


def reference(fmu_path: str, two: dict, h_ref: float = 0.01, duration: float | None = None,
              riser: dict | None = None):
    """One-way at a fine step with the motion of a two-way run (its samples Hermite-interpolated);
    `riser`: riser's parameters (real) beside the time step."""
    duration = two["t"][-1] if duration is None else duration
    fine = np.arange(0.0, duration + 1e-9, h_ref)
    x, v = hermite_motion(fine, two["t"], two["heave"], two["heave_velocity"])
    return two_way(fmu_path, VESSEL, VESSEL_WAVE, h_ref, duration, motion=(fine, x, v),
                   start_values={"time_step": h_ref, **(riser or {})})


def build_vessel_fmu(dest, name: str = "Vessel") -> str:
    """osp/vessel/<name>.py built into an FMU with pythonfmu (requirements.txt) in `dest`: `Vessel`, the
    heave-only body of issue 29, or `Vessel6`, the vessel in six degrees of freedom (issue 30)."""
    import subprocess
    import sys
    from pathlib import Path

    src = Path(__file__).resolve().parents[4] / "osp" / "vessel" / f"{name}.py"
    subprocess.run([sys.executable, "-m", "pythonfmu", "build", "-f", str(src), "-d", str(dest)], check=True,
                   capture_output=True)
    return str(Path(dest) / f"{name}.fmu")


def ecco(riser_fmu: str, vessel_fmu: str, duration: float, **params):
    """libcosim's ECCO algorithm (Sadjina & Pedersen 2020) on riser and the vessel FMU with the
    power bond (riser: top_force_z out, heave_velocity in; vessel: heave_velocity out, force in),
    nothing else connected: riser couples by velocity (`auto`). Returns the columns t, top_tension,
    hang-off z (shape[0].z), work_top, vessel heave, heave_velocity, work, work_magnitude after
    every step ECCO takes."""
    from libcosimpy.CosimAlgorithm import CosimAlgorithm, EccoParams
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.WARNING)
    algo = CosimAlgorithm.create_ecco_algorithm(EccoParams(**params))
    ex = CosimExecution.from_algorithm(algo)
    r = ex.add_local_slave(CosimLocalSlave(fmu_path=riser_fmu, instance_name="riser"))
    v = ex.add_local_slave(CosimLocalSlave(fmu_path=vessel_fmu, instance_name="vessel"))
    rr = {x.name.decode(): x.reference for x in ex.slave_variables(r)}
    vr = {x.name.decode(): x.reference for x in ex.slave_variables(v)}
    ex.connect_real_variables(v, vr["heave_velocity"], r, rr["heave_velocity"])
    ex.connect_real_variables(r, rr["top_force_z"], v, vr["force"])
    if algo.add_power_bond(r, rr["top_force_z"], rr["heave_velocity"], v, vr["heave_velocity"], vr["force"]) != 0:
        raise RuntimeError("libcosim refused the power bond")
    obs = CosimObserver.create_last_value()
    ex.add_observer(observer=obs)
    rows = []
    while True:
        if not ex.step():
            raise RuntimeError(f"ECCO stopped at t = {ex.status().current_time / 1e9} s")
        t = ex.status().current_time / 1e9
        rows.append([t] + list(obs.last_real_values(r, [rr["top_tension"], rr["shape[0].z"], rr["work_top"]]))
                    + list(obs.last_real_values(v, [vr["heave"], vr["heave_velocity"], vr["work"],
                                                    vr["work_magnitude"]])))
        if t >= duration - 1e-9:
            break
    a = np.array(rows)
    names = ["t", "top_tension", "z", "work_top", "heave", "heave_velocity", "work", "work_magnitude"]
    return {n: a[:, i] for i, n in enumerate(names)}


def fixed_step(riser_fmu: str, vessel_fmu: str, h: float, duration: float, vessel: dict | None = None,
               inputs: tuple = ("heave", "heave_velocity"), riser: dict | None = None):
    """libcosim's fixed-step algorithm (Jacobi) on riser and the vessel FMU: vessel.heave and
    heave_velocity (those of `inputs`) → riser's of the same names (`auto`: the displacement drives),
    riser.top_force_z → vessel.force, and riser.top_force_z_mean → vessel.force_mean where both
    FMUs have them; `vessel` sets the vessel's parameters (mass, damping, stiffness, wave_force,
    wave_period, ramp, and how it holds riser's force: force_hold, line_mass, force_cutoff,
    force_filter_order); `riser` riser's real parameters beside its time step. Returns t, heave,
    heave_velocity, top_tension at the communication points after t = 0."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.WARNING)
    ex = CosimExecution.from_step_size(step_size=int(round(h * 1e9)))
    r = ex.add_local_slave(CosimLocalSlave(fmu_path=riser_fmu, instance_name="riser"))
    v = ex.add_local_slave(CosimLocalSlave(fmu_path=vessel_fmu, instance_name="vessel"))
    rr = {x.name.decode(): x.reference for x in ex.slave_variables(r)}
    vr = {x.name.decode(): x.reference for x in ex.slave_variables(v)}
    ex.real_initial_value(r, rr["time_step"], min(0.05, h))
    for k, x in (riser or {}).items():
        ex.real_initial_value(r, rr[k], float(x))
    for k, x in (vessel or {}).items():
        if k in ("force_hold", "force_filter_order"):  # Vessel.py's Integer parameter (how riser's force is held)
            ex.integer_initial_value(v, vr[k], int(x))
        else:
            ex.real_initial_value(v, vr[k], float(x))
    for name in inputs:
        ex.connect_real_variables(v, vr[name], r, rr[name])
    ex.connect_real_variables(r, rr["top_force_z"], v, vr["force"])
    if "top_force_z_mean" in rr and "force_mean" in vr:
        ex.connect_real_variables(r, rr["top_force_z_mean"], v, vr["force_mean"])
    obs = CosimObserver.create_last_value()
    ex.add_observer(observer=obs)
    n = int(round(duration / h))
    out = np.zeros((n, 4))
    for k in range(n):
        if not ex.step():
            raise RuntimeError(f"libcosim stopped at step {k}")
        out[k] = [(k + 1) * h] + list(obs.last_real_values(v, [vr["heave"], vr["heave_velocity"]])) \
            + list(obs.last_real_values(r, [rr["top_tension"]]))
    return {"t": np.concatenate([[0.0], out[:, 0]]), "heave": np.concatenate([[0.0], out[:, 1]]),
            "heave_velocity": np.concatenate([[0.0], out[:, 2]]), "top_tension": np.concatenate([[np.nan], out[:, 3]])}


def window(res, start: float):
    m = res["t"] >= start - 1e-9
    x = res["top_tension"][m]
    return np.array([x.min(), x.max(), x.mean()])


def main(argv=None):
    import argparse

    ap = argparse.ArgumentParser(prog="riser-tools coupling-loop", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fmu", default="fmu/riser.fmu")
    ap.add_argument("--duration", type=float, default=100.0)
    ap.add_argument("--steps", default="0.05,0.1,0.2,0.5")
    args = ap.parse_args(argv)
    rows = []
    for body, wave in [(VESSEL, VESSEL_WAVE), (BUOY, BUOY_WAVE)]:
        for h in [float(x) for x in args.steps.split(",")]:
            try:
                two = two_way(args.fmu, body, wave, h, args.duration)
            except Exception as e:  # a loop that grows until riser refuses its input
                print(f"{body.name} h {h}: stopped: {e}", flush=True)
                continue
            one = reference(args.fmu, two)
            start = min(40.0, args.duration / 2)
            a, b = window(two, start), window(one, start)
            print(f"{body.name} h {h}: two-way {a / 1e3} kN, one-way at 0.01 s with its motion {b / 1e3} kN, "
                  f"heave {np.ptp(two['heave'][two['t'] >= start]) / 2:.3f} m", flush=True)
            rows.append((body.name, h, a, b))
    return 0


def rotation(roll, pitch, yaw):
    """R = Rz(yaw) Ry(pitch) Rx(roll) (z-y-x, docs/theory.md (14.1)): vessel frame to global."""
    cf, sf, ct, st, cp, sp = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    rx = np.array([[1, 0, 0], [0, cf, -sf], [0, sf, cf]])
    ry = np.array([[ct, 0, st], [0, 1, 0], [-st, 0, ct]])
    rz = np.array([[cp, -sp, 0], [sp, cp, 0], [0, 0, 1]])
    return rz @ ry @ rx


# --- the vessel in six degrees of freedom (issue 30; osp/vessel/Vessel6.py) -----------------------

POSE = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
VELOCITY = ["surge_velocity", "sway_velocity", "heave_velocity",
            "angular_velocity_x", "angular_velocity_y", "angular_velocity_z"]
FORCE = ["top_force_x", "top_force_y", "top_force_z"]
MOMENT = ["top_moment_x", "top_moment_y", "top_moment_z"]
VESSEL_MOMENT = ["vessel_moment_x", "vessel_moment_y", "vessel_moment_z"]
RISER_OUT = ["top_tension"] + FORCE + MOMENT + VESSEL_MOMENT + ["work_top", "shape[0].x", "shape[0].y",
                                                                "shape[0].z"]


def euler_rates(roll, pitch, yaw, p, q, r):
    """z-y-x Euler angle rates from the vessel-frame angular velocity (docs/theory.md (14.2) inverted;
    singular at pitch ±90°)."""
    sf, cf = np.sin(roll), np.cos(roll)
    qr = q * sf + r * cf
    return p + qr * np.tan(pitch), q * cf - r * sf, qr / np.cos(pitch)


def body_rates(roll, pitch, yaw, droll, dpitch, dyaw):
    """(p, q, r) from the z-y-x angle rates: ω_b = φ' x + Rxᵀ(φ) (θ' y + Ryᵀ(θ) ψ' z) (14.2)."""
    sf, cf, st, ct = np.sin(roll), np.cos(roll), np.sin(pitch), np.cos(pitch)
    return droll - st * dyaw, cf * dpitch + sf * ct * dyaw, -sf * dpitch + cf * ct * dyaw


def _initial(ex, idx, refs, values):
    for k, x in (values or {}).items():
        if isinstance(x, str):
            ex.string_initial_value(idx, refs[k], x)
        elif isinstance(x, bool):
            ex.boolean_initial_value(idx, refs[k], x)
        else:
            ex.real_initial_value(idx, refs[k], float(x))


def _execution(algorithm, riser_fmu, vessel_fmu, riser, vessel):
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.WARNING)
    ex = algorithm()
    r = ex.add_local_slave(CosimLocalSlave(fmu_path=riser_fmu, instance_name="riser"))
    v = ex.add_local_slave(CosimLocalSlave(fmu_path=vessel_fmu, instance_name="vessel"))
    rr = {x.name.decode(): x.reference for x in ex.slave_variables(r)}
    vr = {x.name.decode(): x.reference for x in ex.slave_variables(v)}
    _initial(ex, r, rr, riser)
    _initial(ex, v, vr, vessel)
    return ex, r, v, rr, vr


def _record(ex, r, v, rr, vr, duration, step_size=None, extra=()):
    from libcosimpy.CosimObserver import CosimObserver

    obs = CosimObserver.create_last_value()
    ex.add_observer(observer=obs)
    vnames = POSE + VELOCITY + ["work", "work_magnitude"]
    rows = []
    k = 0
    while True:
        if not ex.step():
            raise RuntimeError(f"libcosim stopped at t = {ex.status().current_time / 1e9} s")
        k += 1
        t = k * step_size if step_size else ex.status().current_time / 1e9
        rows.append([t] + list(obs.last_real_values(v, [vr[n] for n in vnames]))
                    + list(obs.last_real_values(r, [rr[n] for n in RISER_OUT + list(extra)])))
        if t >= duration - 1e-9:
            break
    a = np.array(rows)
    out = {n: a[:, i] for i, n in enumerate(["t"] + vnames + RISER_OUT + list(extra))}
    out["rotations"] = "roll" in rr
    return out


def fixed_step6(riser_fmu: str, vessel_fmu: str, h: float, duration: float, riser: dict | None = None,
                vessel: dict | None = None, extra: Sequence[str] = ()):
    """libcosim's fixed-step algorithm (Jacobi) on riser and the six-degree-of-freedom vessel
    (osp/vessel/Vessel6.py): the vessel's pose and velocities → riser's inputs of the same names
    (the rotations only if the riser FMU has them), riser's top_force_* and top_moment_* (global) →
    the vessel's inputs of the same names. `riser`, `vessel`: initial values (str, bool or real).
    Returns the columns t, the vessel's pose, velocities, work, work_magnitude and riser's
    RISER_OUT (and riser's `extra` outputs, e.g. a system FMU's LINE.tension_from) after every step,
    and `rotations` (whether the riser took the vessel's rotation)."""
    from libcosimpy.CosimExecution import CosimExecution

    ex, r, v, rr, vr = _execution(lambda: CosimExecution.from_step_size(step_size=int(round(h * 1e9))),
                                  riser_fmu, vessel_fmu, {"time_step": min(0.05, h), **(riser or {})}, vessel)
    for name in POSE + VELOCITY:
        if name in rr:
            ex.connect_real_variables(v, vr[name], r, rr[name])
    for name in FORCE + MOMENT:
        ex.connect_real_variables(r, rr[name], v, vr[name])
    return _record(ex, r, v, rr, vr, duration, step_size=h, extra=extra)


def ecco6(riser_fmu: str, vessel_fmu: str, duration: float, riser: dict | None = None, vessel: dict | None = None,
          **params):
    """libcosim's ECCO on riser and the six-degree-of-freedom vessel through the two ports of
    osp/riser_OspModelDescription.xml, one power bond per axis: the LinearMechanicalPort (riser's
    top_force_* out, *_velocity in; the vessel's *_velocity out, top_force_* in) and the
    AngularMechanicalPort (riser's vessel_moment_* out, angular_velocity_* in, both in the vessel
    frame; the vessel's angular_velocity_* out, vessel_moment_* in). No displacement is connected:
    riser integrates the velocities (`auto`). Returns what fixed_step6 returns, after each of ECCO's
    steps."""
    from libcosimpy.CosimAlgorithm import CosimAlgorithm, EccoParams
    from libcosimpy.CosimExecution import CosimExecution

    algo = CosimAlgorithm.create_ecco_algorithm(EccoParams(**params))
    ex, r, v, rr, vr = _execution(lambda: CosimExecution.from_algorithm(algo), riser_fmu, vessel_fmu, riser, vessel)
    bonds = list(zip(FORCE, VELOCITY[:3]))
    if "angular_velocity_x" in rr:
        bonds += list(zip(VESSEL_MOMENT, VELOCITY[3:]))
    for effort, flow in bonds:
        ex.connect_real_variables(v, vr[flow], r, rr[flow])
        ex.connect_real_variables(r, rr[effort], v, vr[effort])
        if algo.add_power_bond(r, rr[effort], rr[flow], v, vr[flow], vr[effort]) != 0:
            raise RuntimeError(f"libcosim refused the power bond {effort}/{flow}")
    return _record(ex, r, v, rr, vr, duration)


def reference6(riser_fmu: str, two: dict, h_ref: float = 0.025, riser: dict | None = None,
               velocities: bool = True):
    """One way: riser alone at fixed steps h_ref driven by the vessel motion recorded in a two-way run
    (`two`, with t = 0 at rest prepended), each translation Hermite-interpolated with its velocity and
    each Euler angle with its rate from p, q, r (z-y-x kinematics), p, q, r back from the
    interpolated angles and rates. The rotations only if two["rotations"]; the velocities only if
    `velocities` (else the poses alone, displacement coupling). Returns t, the prescribed
    pose, and RISER_OUT at each step's end."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    t = np.concatenate([[0.0], two["t"]])
    col = {n: np.concatenate([[0.0], two[n]]) for n in POSE + VELOCITY}
    rates = euler_rates(col["roll"], col["pitch"], col["yaw"], col["angular_velocity_x"],
                        col["angular_velocity_y"], col["angular_velocity_z"])
    fine = np.arange(0.0, t[-1] + 1e-9, h_ref)
    motion = {}
    for i, name in enumerate(POSE[:3]):
        motion[name], motion[VELOCITY[i]] = hermite_motion(fine, t, col[name], col[VELOCITY[i]])
    angles, arates = [], []
    for i, name in enumerate(POSE[3:]):
        a, da = hermite_motion(fine, t, col[name], rates[i])
        motion[name] = a
        angles.append(a)
        arates.append(da)
    for name, w in zip(VELOCITY[3:], body_rates(*angles, *arates)):
        motion[name] = w
    names = POSE + VELOCITY if two.get("rotations", False) else POSE[:3] + VELOCITY[:3]
    if not velocities:
        names = [n for n in names if n not in VELOCITY]

    md = read_model_description(riser_fmu, validate=False)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s = FMU2Slave(guid=md.guid, unzipDirectory=extract(riser_fmu), modelIdentifier="riser", instanceName="one_way")
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    for k, x in {"time_step": h_ref, **(riser or {})}.items():
        if isinstance(x, str):
            s.setString([vr[k]], [x])
        elif isinstance(x, bool):
            s.setBoolean([vr[k]], [x])
        else:
            s.setReal([vr[k]], [float(x)])
    s.exitInitializationMode()
    rows = []
    try:
        for k in range(len(fine) - 1):
            s.setReal([vr[n] for n in names], [float(motion[n][k]) for n in names])
            s.doStep(fine[k], fine[k + 1] - fine[k])
            rows.append([fine[k + 1]] + [motion[n][k + 1] for n in POSE] + s.getReal([vr[n] for n in RISER_OUT]))
    finally:
        s.terminate()
        s.freeInstance()
    a = np.array(rows)
    return {n: a[:, i] for i, n in enumerate(["t"] + POSE + RISER_OUT)}


def window6(res, start: float, name: str = "top_tension"):
    m = res["t"] >= start - 1e-9
    x = res[name][m]
    return np.array([x.min(), x.max(), x.mean()])


IDX6 = ["11", "22", "33", "44", "55", "66"]


def vessel6_defaults(vessel_fmu: str) -> dict:
    """The Real parameters of the Vessel6 FMU and their defaults."""
    from fmpy import read_model_description

    md = read_model_description(vessel_fmu)
    return {v.name: float(v.start) for v in md.modelVariables if v.causality == "parameter" and v.type == "Real"}


def vessel6_inertia(vessel_fmu: str, vessel: dict | None = None) -> dict:
    """riser's `vessel_mass_*` and `vessel_inertia_*` parameters for the Vessel6 FMU with the
    parameters `vessel` (else its defaults): its mass plus added mass per axis and its moments of
    inertia plus added inertia, as it integrates riser's held force and moment (docs/theory.md §7.5:
    the hang-off's path then takes the vessel's answer to riser's own load within each step)."""
    p = {**vessel6_defaults(vessel_fmu), **{k: x for k, x in (vessel or {}).items() if not isinstance(x, bool)}}
    mass = {"heave": "33", "surge": "11", "sway": "22"}
    inertia = {"roll": ("inertia_xx", "44"), "pitch": ("inertia_yy", "55"), "yaw": ("inertia_zz", "66")}
    out = {f"vessel_mass_{k}": p["mass"] + p[f"added_mass_{i}"] for k, i in mass.items()}
    out.update({f"vessel_inertia_{k}": p[n] + p[f"added_mass_{i}"] for k, (n, i) in inertia.items()})
    return out
