"""The FMU as masters drive it (issue 52): every variable readable in every
state, implausible inputs said once each, a bounded step, in fmpy and in OSP
libcosim. libcosim runs in child processes: a master that aborts (as
libcosim's observer did on a parameter read that failed, exit 134) must not
take pytest with it. docs/guide/coupling.md is what a user reads of this."""

import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave

ROOT = Path(__file__).resolve().parents[2]
BUILT_IN = ["catenary", "lazy_wave", "steel_catenary"]


def multi_valued_scene(tmp_path):
    """The steel catenary with every parameter a scene can hold as several
    values: friction apart (its own), a current table, two buoyancy sections,
    a flex joint's table."""
    text = (ROOT / "scenes" / "steel_catenary.toml").read_text().replace('[current]\nprofile = "none"\n', "")
    text += textwrap.dedent("""
        [current]
        profile = "table"
        table = [[0.0, 0.6], [100.0, 0.4], [210.0, 0.1]]

        [[buoyancy]]
        start = 100.0
        end = 120.0
        load = 300.0

        [[buoyancy]]
        start = 150.0
        end = 170.0
        load = 200.0

        [hang_off]
        end = "flex_joint"
        table = [[0.0, 0.0], [0.05, 3e4], [0.2, 8e4]]
        """)
    path = tmp_path / "multi_valued.toml"
    path.write_text(text)
    return str(path)


LIBCOSIM_RUN = textwrap.dedent("""
    import sys
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    fmu, scene, out, h, inputs = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), eval(sys.argv[5])
    log_output_level(CosimLogLevel.DEBUG)
    ex = CosimExecution.from_step_size(step_size=int(round(h * 1e9)))
    idx = ex.add_local_slave(CosimLocalSlave(fmu_path=fmu, instance_name="riser"))
    refs = {v.name.decode(): v.reference for v in ex.slave_variables(idx)}
    ex.string_initial_value(idx, refs["scene"], scene)
    ex.integer_initial_value(idx, refs["n_elements"], 10)
    # the file observer logs every variable of the slave at every step
    ex.add_observer(observer=CosimObserver.create_to_dir(out))
    last = CosimObserver.create_last_value()
    ex.add_observer(observer=last)
    manip = CosimManipulator.create_override()
    ex.add_manipulator(manipulator=manip)
    for k, values in enumerate(inputs):
        if values:
            manip.slave_real_values(idx, [refs[n] for n in values], list(values.values()))
        ok = ex.step()
        it, bound = last.last_real_values(idx, [refs["step_newton_iterations"], refs["step_newton_bound"]])
        print(f"STEP {k} {ok} {ex.status().current_time * 1e-9} {it} {bound}", flush=True)
        if not ok:
            break
    """)


FMPY_RUN = textwrap.dedent("""
    import sys
    from ctypes import byref
    from fmpy import read_model_description
    from fmpy.fmi1 import FMICallException
    from fmpy.fmi2 import FMU2Slave, defaultCallbacks, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE
    from fmpy.logging import addLoggerProxy

    def log(env, name, status, category, message):
        print("MSG", status, category.decode(), (message or b"").decode(), flush=True)

    logger = fmi2CallbackLoggerTYPE(log)
    callbacks = fmi2CallbackFunctions()
    callbacks.logger = logger
    callbacks.allocateMemory = defaultCallbacks.allocateMemory
    callbacks.freeMemory = defaultCallbacks.freeMemory
    addLoggerProxy(byref(callbacks))
    fmu, unzipped, h, inputs = sys.argv[1], sys.argv[2], float(sys.argv[3]), eval(sys.argv[4])
    md = read_model_description(fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier="riser", instanceName="m")
    s.instantiate(callbacks=callbacks, loggingOn=True)
    s.setInteger([vr["n_elements"]], [10])
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.exitInitializationMode()
    held = {}
    for k, values in enumerate(inputs):
        held.update(values or {})
        s.setReal([vr[n] for n in held], list(held.values()))
        try:
            s.doStep(k * h, h)
            status = 0
        except FMICallException as e:
            status = e.status
        it, bound = s.getReal([vr["step_newton_iterations"], vr["step_newton_bound"]])
        print(f"STEP {k} {status} {s.getRealStatus(2)} {it} {bound}", flush=True)
        if status:
            break
    s.freeInstance()
    """)


def fmpy_child(fmu_path, unzipped, out, h, inputs):
    """riser alone in fmpy's FMU2Slave (a child process: fmpy's native logger
    proxy is process-wide), `inputs` as for `libcosim`, held until changed.
    Returns the STEP rows (k, status, last successful time, iterations,
    bound) and the messages (status, category, text)."""
    script = out / "fmpy_run.py"
    script.write_text(FMPY_RUN)
    p = subprocess.run([sys.executable, str(script), fmu_path, str(unzipped), str(h), repr(inputs)],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr[-2000:]
    steps = [line.split()[1:] for line in p.stdout.splitlines() if line.startswith("STEP ")]
    messages = [tuple(line.split(" ", 3)[1:]) for line in p.stdout.splitlines() if line.startswith("MSG ")]
    return steps, [(int(st), c, m) for st, c, m in messages]


def libcosim(fmu_path, scene, out, h, inputs):
    """riser alone in libcosim (a child process): `inputs` a list, one dict
    {input: value} (or None) per communication step of `h` s."""
    script = out / "run.py"
    script.write_text(LIBCOSIM_RUN)
    return subprocess.run([sys.executable, str(script), fmu_path, scene, str(out), str(h), repr(inputs)],
                          capture_output=True, text=True, timeout=120)


def riser_messages(log):
    """The FMU's messages in libcosim's log (its standard output): (status, text)."""
    out = []
    for line in log.splitlines():
        if "[FMI status=" in line:
            status = line.split("[FMI status=")[1].split(",")[0]
            out.append((status, line[line.index("[FMI status="):].split("] ", 1)[1]))
    return out


def test_libcosim_s_observer_logs_every_variable_of_every_scene(fmu_path, tmp_path):
    """libcosim's file observer reads every variable at every step: with the
    built-in scenes and the scene holding every multi-valued parameter the
    run completes (exit 0, where a failed read aborted it with 134), every
    variable is in the log, and no message is said twice."""
    md = read_model_description(fmu_path)
    for scene in BUILT_IN + [multi_valued_scene(tmp_path)]:
        out = tmp_path / Path(scene).stem
        out.mkdir()
        p = libcosim(fmu_path, scene, out, 0.1, [None] * 5)
        assert p.returncode == 0, (scene, p.returncode, p.stdout[-2000:])
        assert p.stdout.count(" True ") == 5, p.stdout
        csv = next(out.glob("riser_*.csv"))
        header = csv.read_text().splitlines()[0]
        for v in md.modelVariables:
            assert v.name in header, (scene, v.name)
        said = [m for _, m in riser_messages(p.stdout)]
        twice = {m for m in said if said.count(m) > 1}
        assert not twice, (scene, twice)
        if scene.endswith(".toml"):
            # the documented values, said once each (read at every step)
            for name in ["seabed_friction reads 0.5", "current_top reads 0.6", "buoyancy_load reads 300",
                         "flex_joint_stiffness reads 600000"]:
                assert sum(m.startswith(name) for m in said) == 1, (name, said)


def slave(fmu_path, unzipped, scene="catenary"):
    """An instance of `scene` with 10 elements, instantiated."""
    md = read_model_description(fmu_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier="riser", instanceName="m")
    s.instantiate()
    s.setString([vr["scene"]], [scene])
    s.setInteger([vr["n_elements"]], [10])
    return s, vr, md


def read_every_variable(s, md):
    for v in md.modelVariables:
        get = {"Real": s.getReal, "Integer": s.getInteger, "Boolean": s.getBoolean, "String": s.getString}[v.type]
        x = get([v.valueReference])[0]
        if v.type == "Real":
            assert np.isfinite(x), v.name


def test_fmpy_reads_every_variable_in_every_state(fmu_path, unzipped):
    """Through the C ABI: Instantiated, InitializationMode, StepComplete,
    StepFailed, Terminated; every getter fmi2OK (fmpy raises otherwise)."""
    for scene in BUILT_IN:
        s, vr, md = slave(fmu_path, unzipped, scene)
        read_every_variable(s, md)
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
        read_every_variable(s, md)
        s.exitInitializationMode()
        read_every_variable(s, md)
        s.doStep(0.0, 0.1)
        s.setReal([vr["heave"], vr["surge"], vr["sway"]], [-60.0, 50.0, 20.0])
        with pytest.raises(FMICallException) as e:
            s.doStep(0.1, 1.0)
        assert e.value.status == 2
        read_every_variable(s, md)
        s.terminate()
        read_every_variable(s, md)
        s.freeInstance()


IMPLAUSIBLE = [
    # (input sequence at 0.1 s, the words said once)
    ([{"heave": 5.0}] * 3, "heave = 5 m at the first communication point t = 0 s looks absolute"),
    ([None, None, {"pitch": 1.0}, None], "pitch = 1 rad (57.3 deg) at t = 0.2 s: beyond 30 deg"),
    ([None, None, {"surge": 100.0}, None], "move the hang-off 100.00 m between t = 0.1 s and 0.2 s"),
    ([None, None, {"heave": 0.5}, None], "acceleration of 5.000e1 m/s²"),
]


def test_implausible_inputs_are_said_once_each_in_fmpy_and_in_libcosim(fmu_path, unzipped, tmp_path):
    """Each implausible input of issue 52 said once, with its numbers, as a
    warning (logStatusWarning); the step itself fmi2OK in fmpy and taken by
    libcosim. A plausible motion (heave 2.5 m / 10 s, pitch 5 deg / 10 s)
    says nothing of it."""
    w = 2 * np.pi / 10.0
    plausible = [{"heave": float(2.5 * np.sin(w * 0.1 * k)), "pitch": float(np.radians(5.0) * np.sin(w * 0.1 * k))}
                 for k in range(30)]
    for inputs, words in IMPLAUSIBLE + [(plausible, None)]:
        out = tmp_path / f"run{IMPLAUSIBLE.index((inputs, words)) if words else 'plausible'}"
        out.mkdir()
        # fmpy: every step fmi2OK
        steps, messages = fmpy_child(fmu_path, unzipped, out, 0.1, inputs)
        assert [x[1] for x in steps] == ["0"] * len(inputs), steps
        warnings = [m for st, c, m in messages if st == 1 and c == "logStatusWarning"]
        # libcosim (its override manipulator holds a value until changed)
        p = libcosim(fmu_path, "catenary", out, 0.1, inputs)
        assert p.returncode == 0 and p.stdout.count(" True ") == len(inputs), (p.stdout[-2000:], p.stderr[-2000:])
        said = [m for st, m in riser_messages(p.stdout) if st == "warning"]
        if words is None:
            for m in warnings + said:
                assert not ("implausible" in m or "looks absolute" in m or "in one communication step" in m), m
        else:
            assert sum(words in m for m in warnings) == 1, (words, warnings)
            assert sum(words in m for m in said) == 1, (words, said)


def test_a_step_that_cannot_converge_is_discarded_within_its_bound_in_fmpy_and_libcosim(fmu_path, unzipped,
                                                                                          tmp_path):
    """The hang-off thrown 80 m in one 1 s step: fmi2Discard after at most
    step_newton_bound Newton iterations, fmi2LastSuccessfulTime inside the
    step, the reason logged (logStatusDiscard). What the masters then do:
    fmpy raises FMICallException (status 2) from doStep, and the caller may
    read the last good state; libcosim's step returns False and its
    execution stops in its error state (docs/guide/coupling.md)."""
    thrown = [None, None, {"heave": -60.0, "surge": 50.0, "sway": 20.0}]
    steps, messages = fmpy_child(fmu_path, unzipped, tmp_path, 1.0, thrown)
    assert [x[1] for x in steps] == ["0", "0", "2"], steps  # fmi2Discard: FMICallException(status 2)
    last, it, bound = (float(x) for x in steps[2][2:])
    assert 0 < it <= bound, (it, bound)
    assert 2.0 <= last < 3.0
    assert any(c == "logStatusDiscard" and "the step's bound" in m for _, c, m in messages), messages
    p = libcosim(fmu_path, "catenary", tmp_path, 1.0, thrown)
    steps = [line.split() for line in p.stdout.splitlines() if line.startswith("STEP")]
    assert [x[2] for x in steps] == ["True", "True", "False"], p.stdout
    assert float(steps[2][4]) <= float(steps[2][5]), steps[2]
    assert any(st == "discard" and "the step's bound" in m for st, m in riser_messages(p.stdout))


def test_fmpy_s_simulate_fmu_stops_at_the_last_good_time_of_a_discarded_step(fmu_path):
    """After fmi2Discard riser answers fmi2Terminated = true (it cannot step
    on from fmi2LastSuccessfulTime without a restored state): fmpy's
    simulate_fmu then ends the run there and returns its results, where it
    carried on before and raised with fmi2Error on its next fmi2SetReal."""
    from fmpy import simulate_fmu

    t = np.arange(0.0, 5.0 + 1e-9, 1.0)
    z = np.where(t >= 2.0, 1.0, 0.0)
    signal = np.array(list(zip(t, -60.0 * z, 50.0 * z, 20.0 * z)),
                      dtype=[("time", np.float64), ("heave", np.float64), ("surge", np.float64), ("sway", np.float64)])
    res = simulate_fmu(fmu_path, stop_time=5.0, output_interval=1.0, input=signal, output=["top_tension"],
                       start_values={"n_elements": 10})
    assert list(res["time"][:3]) == [0.0, 1.0, 2.0]
    assert 2.0 < res["time"][-1] < 3.0 and len(res) == 4, res["time"]
    assert np.all(np.isfinite(res["top_tension"]))
