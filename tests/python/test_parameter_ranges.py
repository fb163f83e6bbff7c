"""Every FMU parameter at the bounds of its range (`riser params --json`, the
one table in src/scene/ranges.rs), through fmpy as a master drives it: at each
bound the instance initialises and takes three steps with finite outputs; just
outside, fmi2SetReal / fmi2SetInteger returns fmi2Error and the logged message
names the parameter and the range. (tests/it/parameter_ranges.rs does the same
through the command line, for the rod and the cable.)
"""
import json
import math
import subprocess
from ctypes import byref

import pytest
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave, defaultCallbacks, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE
from fmpy.logging import addLoggerProxy

# the FMU's log messages, collected by our own logger callback (fmpy's native
# proxy formats the variadic message first)
MESSAGES: list[str] = []


def _log(env, name, status, category, message):
    MESSAGES.append((message or b"").decode("utf-8", "replace"))


_LOGGER = fmi2CallbackLoggerTYPE(_log)
CALLBACKS = fmi2CallbackFunctions()
CALLBACKS.logger = _LOGGER
CALLBACKS.allocateMemory = defaultCallbacks.allocateMemory
CALLBACKS.freeMemory = defaultCallbacks.freeMemory
addLoggerProxy(byref(CALLBACKS))

# parameters a bound needs to make a line at all (as in tests/it/parameter_ranges.rs)
COMPANIONS = {
    ("length", "min"): {"anchor_x": 0.6, "anchor_z": -0.7},
    ("length", "max"): {"anchor_x": 15000.0, "anchor_z": -10000.0},
    ("anchor_x", "min"): {"length": 20000.0},
    ("anchor_x", "max"): {"length": 20000.0},
    ("anchor_y", "min"): {"length": 20000.0},
    ("anchor_y", "max"): {"length": 20000.0},
    ("anchor_z", "min"): {"length": 20000.0},
    ("anchor_z", "max"): {"length": 20000.0},
    ("buoyancy_load", "min"): {"buoyancy_start": 30.0, "buoyancy_end": 60.0},
    ("buoyancy_load", "max"): {"buoyancy_start": 30.0, "buoyancy_end": 60.0},
    ("buoyancy_start", "min"): {"buoyancy_end": 60.0, "buoyancy_load": 100.0},
    ("buoyancy_end", "max"): {"length": 20000.0, "anchor_x": 15000.0, "anchor_z": -10000.0,
                              "buoyancy_load": 100.0},
    # a seabed at the hang-off's height: the line taut along it
    ("seabed_z", "max"): {"anchor_x": 100.5, "anchor_z": 0.0},
}
# contents need a bore: the catenary's flexible pipe given a wall
for _p in ["internal_fluid_density", "internal_pressure"]:
    for _b in ["min", "max"]:
        COMPANIONS[(_p, _b)] = {"wall_thickness": 0.02}
# the contact law's bounds on a line resting on the seabed
for _p in ["seabed_stiffness", "seabed_damping", "seabed_friction"]:
    for _b in ["min", "max"]:
        COMPANIONS[(_p, _b)] = {"anchor_x": 85.0, "anchor_z": -40.0, "seabed_z": -40.0}
# bounds the scene's own checks refuse (a section must have end > start)
NOT_A_LINE = {("buoyancy_start", "max"), ("buoyancy_end", "min")}


@pytest.fixture(scope="module")
def ranges(riser_bin):
    rows = json.loads(subprocess.run([riser_bin, "params", "--json"], check=True, capture_output=True,
                                     text=True).stdout)
    return {r["name"]: r for r in rows if "min" in r}


@pytest.fixture(scope="module")
def fmu(fmu_path, unzipped):
    md = read_model_description(fmu_path)
    vars_ = {v.name: v for v in md.modelVariables}
    return md, unzipped, vars_


def slave(fmu):
    md, unzipped, _ = fmu
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="ranges")
    s.instantiate(callbacks=CALLBACKS, loggingOn=True)
    return s


def set_value(s, var, value):
    if var.type == "Integer":
        s.setInteger([var.valueReference], [int(value)])
    else:
        s.setReal([var.valueReference], [float(value)])


def outside(name, r, bound, whole=False):
    if whole:
        return r[bound] + (1 if bound == "max" else -1)
    step = max(abs(r[bound]), 1.0) * 1e-6
    return r[bound] + (step if bound == "max" else -step)


def fmu_parameters(fmu, ranges):
    _, _, vars_ = fmu
    return [(n, vars_[n]) for n in ranges if n in vars_ and vars_[n].causality == "parameter"]


def test_every_fmu_parameter_runs_at_its_bounds(fmu, ranges):
    _, _, vars_ = fmu
    checked = 0
    for name, var in fmu_parameters(fmu, ranges):
        for bound in ["min", "max"]:
            if (name, bound) in NOT_A_LINE:
                continue
            s = slave(fmu)
            set_value(s, vars_["n_elements"], 10)
            for other, value in COMPANIONS.get((name, bound), {}).items():
                set_value(s, vars_[other], value)
            set_value(s, var, ranges[name][bound])
            s.setupExperiment(startTime=0.0)
            s.enterInitializationMode()
            s.exitInitializationMode()
            t = 0.0
            for k in range(3):
                s.setReal([vars_["heave"].valueReference], [0.05 * k])
                s.doStep(t, 0.1)
                t += 0.1
            outs = [v.valueReference for v in vars_.values() if v.causality == "output"]
            values = s.getReal(outs)
            assert all(math.isfinite(x) for x in values), (name, bound)
            # the parameter reads back as set
            got = (s.getInteger if var.type == "Integer" else s.getReal)([var.valueReference])[0]
            assert got == ranges[name][bound], (name, bound, got)
            s.terminate()
            s.freeInstance()
            checked += 1
    assert checked >= 2 * len(fmu_parameters(fmu, ranges)) - len(NOT_A_LINE)


# run in a child process with fmpy's own logger: its native logger proxy is
# process-wide, so another test module's proxy (the fuzzer's) would take the
# messages; the child prints what it saw as JSON
OUTSIDE_CHILD = r"""
import json, sys
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
fmu_path, unzipped, cases = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
md = read_model_description(fmu_path)
vars_ = {v.name: v for v in md.modelVariables}
out = []
for name, value in cases:
    var = vars_[name]
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier="riser", instanceName="ranges")
    s.instantiate(loggingOn=True)
    print("@@begin", flush=True)
    try:
        if var.type == "Integer":
            s.setInteger([var.valueReference], [int(value)])
        else:
            s.setReal([var.valueReference], [float(value)])
        refused = False
    except FMICallException as e:
        refused = e.status == 3
    print("@@end", flush=True)
    # fmi2Reset brings the instance back to a normal run
    s.reset()
    s.setInteger([vars_["n_elements"].valueReference], [10])
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.exitInitializationMode()
    s.doStep(0.0, 0.1)
    s.freeInstance()
    out.append(refused)
print("@@result " + json.dumps(out), flush=True)
"""


def test_every_fmu_parameter_just_outside_its_range_is_an_error_naming_it(fmu, fmu_path, unzipped, ranges):
    import sys

    cases = [(name, outside(name, ranges[name], bound, var.type == "Integer")) for name, var in fmu_parameters(fmu, ranges)
             for bound in ["min", "max"]]
    p = subprocess.run([sys.executable, "-c", OUTSIDE_CHILD, fmu_path, unzipped, json.dumps(cases)],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    refused = json.loads(p.stdout.split("@@result ")[1])
    logs = [chunk.split("@@end")[0] for chunk in p.stdout.split("@@begin")[1:]]
    assert len(refused) == len(cases) == len(logs)
    for (name, value), ok, logged in zip(cases, refused, logs):
        assert ok, f"{name} = {value} was not refused with fmi2Error"
        # the table's range and its reason, as the CLI prints them
        r = ranges[name]
        assert name in logged and "is outside [" in logged and r["reason"][:40] in logged, (name, logged)


def vars_n(fmu):
    return fmu[2]["n_elements"]


def test_unset_parameters_read_back_the_scene_values_not_the_start_values(fmu):
    # lazy_wave's anchor is at (50, 0, -40) and its modules carry 670 N/m; the
    # model description's start values are the default scene's (60, -70, 0)
    _, _, vars_ = fmu
    s = slave(fmu)
    s.setString([vars_["scene"].valueReference], ["lazy_wave"])
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    names = ["anchor_x", "anchor_z", "buoyancy_load"]
    assert s.getReal([vars_[n].valueReference for n in names]) == [50.0, -40.0, 670.0]
    s.exitInitializationMode()
    assert s.getReal([vars_[n].valueReference for n in names]) == [50.0, -40.0, 670.0]
    assert s.getInteger([vars_["n_elements"].valueReference]) == [60]
    s.freeInstance()


def test_the_model_description_declares_the_same_ranges(fmu, ranges):
    # masters read min/max from modelDescription.xml (build.rs writes them from
    # the same table the FMU checks against)
    for name, var in fmu_parameters(fmu, ranges):
        # the numerics' 0 is "the scene's, or accuracy's choice" (docs/theory.md §16.12)
        low = 0.0 if name in ("n_elements", "time_step", "newton_tolerance") else ranges[name]["min"]
        assert (float(var.min), float(var.max)) == (low, ranges[name]["max"]), name
    _, _, vars_ = fmu
    for name in ["heave", "surge", "sway"]:
        assert (float(vars_[name].min), float(vars_[name].max)) == (-2e4, 2e4)
