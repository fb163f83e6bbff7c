"""Waves through the FMU (issue 27): the wave parameters and the output
`wave_elevation` as a master sees them; a bad wave parameter is refused with
fmi2Error and a message naming it (at fmi2SetXxx for a value outside its
range or an unknown name, at fmi2ExitInitializationMode for a scene the
values make: Tp too short for Hs, a components file that cannot be read, a
depth that contradicts the seabed); a run in waves reports the sea's
elevation at the phase origin, the same at every communication step, and
the waves move the top tension."""
import math
import json
import subprocess
import sys

from slaves import started_slave

# run in a child process with fmpy's own logger (its native logger proxy is
# process-wide, as in test_parameter_ranges.py); the child prints what the FMU
# logged for each case between markers, then the statuses as JSON
CHILD = r"""
import json, sys
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
fmu_path, unzipped, cases = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
md = read_model_description(fmu_path)
vars_ = {v.name: v for v in md.modelVariables}
out = []
for case in cases:
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier="riser", instanceName="waves")
    s.instantiate(loggingOn=True)
    print("@@begin", flush=True)
    status, where = 0, None
    try:
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
        where = "set"
        for name, value in case:
            var = vars_[name]
            if var.type == "String":
                s.setString([var.valueReference], [value])
            elif var.type == "Integer":
                s.setInteger([var.valueReference], [int(value)])
            else:
                s.setReal([var.valueReference], [float(value)])
        where = "exit"
        s.exitInitializationMode()
        where = "ok"
    except FMICallException as e:
        status = e.status
    print("@@end", flush=True)
    s.freeInstance()
    out.append([status, where])
print("@@result " + json.dumps(out), flush=True)
"""

CASES = [
    # (what the master sets, where it is refused, what the message names)
    ([("wave_height", -1.0)], "set", ["wave_height", "is outside [0, 40] m"]),
    ([("wave_period", 0.0)], "set", ["wave_period", "is outside [1, 40] s"]),
    ([("wave_kind", "stokes")], "set", ["wave_kind", "not a kind of waves"]),
    ([("wave_stretching", "linear")], "set", ["wave_stretching", "wheeler, vertical or none"]),
    ([("wave_components", 0)], "set", ["wave_components", "is outside [1, 10000]"]),
    ([("wave_spacing", "uniform")], "set", ["wave_spacing", "frequency or energy"]),
    ([("wave_kind", "jonswap"), ("wave_hs", 12.0), ("wave_tp", 5.0)], "exit", ["waves.tp", "1/15"]),
    ([("wave_kind", "airy"), ("wave_height", 4.0)], "exit", ["waves.period", "missing"]),
    ([("wave_kind", "table"), ("wave_file", "/no/such/components.csv")], "exit", ["waves.file", "cannot read"]),
    ([("scene", "steel_catenary"), ("wave_kind", "airy"), ("wave_height", 4.0), ("wave_period", 9.0),
      ("water_depth", 50.0)], "exit", ["waves.depth", "contradicts the seabed"]),
]


def test_bad_wave_parameters_are_refused_with_fmi2error_naming_them(fmu_path, unzipped):
    cases = [c[0] for c in CASES]
    p = subprocess.run([sys.executable, "-c", CHILD, fmu_path, unzipped, json.dumps(cases)], capture_output=True,
                       text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    results = json.loads(p.stdout.split("@@result ")[1])
    logs = [chunk.split("@@end")[0] for chunk in p.stdout.split("@@begin")[1:]]
    assert len(results) == len(CASES) == len(logs)
    for (sets, where, parts), (status, at), logged in zip(CASES, results, logs):
        assert status == 3, f"{sets}: not refused with fmi2Error (status {status}, reached {at})"
        assert at == where, f"{sets}: refused at {at}, expected at {where}"
        for part in parts:
            assert part in logged, f"{sets}: '{part}' not in the log:\n{logged}"


def test_still_water_reads_back_the_wave_parameters_and_a_zero_elevation(fmu_path, unzipped):
    s, vr = started_slave(fmu_path, unzipped, "still")
    assert s.getString([vr["wave_kind"], vr["wave_stretching"], vr["wave_file"]]) == [b"none", b"wheeler", b""] \
        or s.getString([vr["wave_kind"], vr["wave_stretching"], vr["wave_file"]]) == ["none", "wheeler", ""]
    assert s.getReal([vr["wave_period"], vr["wave_tp"], vr["wave_gamma"], vr["water_depth"]]) == [10.0, 10.0, 3.3, 0.0]
    assert s.getInteger([vr["wave_components"], vr["wave_seed"]]) == [100, 0]
    assert s.getString([vr["wave_spacing"]]) in ([b"frequency"], ["frequency"])
    t = 0.0
    for _ in range(3):
        s.doStep(t, 0.1)
        t += 0.1
        assert s.getReal([vr["wave_elevation"]]) == [0.0]
    s.terminate()
    s.freeInstance()


def run_in_waves(fmu_path, unzipped, step, duration=12.0, height=4.0):
    """(t, wave_elevation, top_tension) of the catenary in a regular 9 s wave
    (its ramp one period long) with the vessel still, at communication step `step`."""
    s, vr = started_slave(fmu_path, unzipped, f"waves{step}", strings={"wave_kind": "airy"},
                          reals={"wave_height": height, "wave_period": 9.0})
    rows, t = [], 0.0
    for k in range(1, round(duration / step) + 1):
        s.doStep(t, step)
        t = k * step
        rows.append((t, *s.getReal([vr["wave_elevation"], vr["top_tension"]])))
    s.terminate()
    s.freeInstance()
    return rows


def test_a_run_in_waves_reports_the_elevation_at_the_phase_origin_at_every_communication_step(fmu_path, unzipped):
    w = 2 * math.pi / 9.0
    by_step = {step: run_in_waves(fmu_path, unzipped, step) for step in (0.05, 0.2, 0.6)}
    for step, rows in by_step.items():
        for t, eta, _ in rows:
            r = 0.5 * (1 - math.cos(math.pi * t / 9.0)) if t < 9.0 else 1.0
            assert abs(eta - r * 2.0 * math.cos(-w * t)) < 1e-12, (step, t, eta)
    # the same internal steps whatever the communication step (the scene's 0.05 s):
    # the top tension agrees where the grids meet
    fine = {round(t, 9): tt for t, _, tt in by_step[0.05]}
    for step in (0.2, 0.6):
        for t, _, tt in by_step[step]:
            assert abs(tt - fine[round(t, 9)]) <= 1e-6 * tt, (step, t, tt, fine[round(t, 9)])
    # the waves move the top tension: against the same run in still water (where the
    # current's start moves it too) by far more than the 1e-6 the steps agree to
    still = run_in_waves(fmu_path, unzipped, 0.6, height=0.0)
    moved = max(abs(a[2] - b[2]) for a, b in zip(by_step[0.6], still))
    print(f"the waves move the top tension by up to {moved:.0f} N")
    assert moved > 200.0, moved


def test_energy_bins_set_in_the_fmu_give_the_sea_riser_waves_prints(fmu_path, unzipped, riser_bin):
    # `wave_spacing = energy` (theory (13.11a-b)): the FMU's wave_elevation at the phase origin is
    # the sum of the components `riser waves --json` prints for the same parameters, Σ a cos(φ − 2π f t)
    # at full height (wave_ramp 0), within round-off; the components are not equally spaced
    sets = {"wave_kind": "jonswap", "wave_spacing": "energy"}
    reals = {"wave_hs": 3.0, "wave_tp": 9.0, "wave_ramp": 0.0}
    args = [riser_bin, "waves", "catenary", "--json"]
    for k, v in {**sets, **reals, "wave_components": 60, "wave_seed": 5}.items():
        args += ["--set", f"{k}={v}"]
    comps = json.loads(subprocess.run(args, capture_output=True, text=True, check=True).stdout)["components"]
    f = sorted(c["frequency"] for c in comps)
    gaps = [b - a for a, b in zip(f, f[1:])]
    assert max(gaps) > 1.5 * min(gaps), (min(gaps), max(gaps))
    s, vr = started_slave(fmu_path, unzipped, "energy", strings=sets, reals=reals,
                          integers={"wave_components": 60, "wave_seed": 5})
    t = 0.0
    for _ in range(20):
        s.doStep(t, 0.1)
        t += 0.1
        eta = sum(c["amplitude"] * math.cos(math.radians(c["phase"]) - 2 * math.pi * c["frequency"] * t)
                  for c in comps)
        got = s.getReal([vr["wave_elevation"]])[0]
        assert abs(got - eta) < 1e-9, (t, got, eta)
    s.terminate()
    s.freeInstance()
