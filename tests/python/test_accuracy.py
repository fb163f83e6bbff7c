"""The accuracy knob through the FMU (issue 28, docs/theory.md section 16): after
fmi2ExitInitializationMode the master reads back the numerics riser chose
(n_elements, time_step, newton_tolerance), the same as the CLI chooses for the
same scene (the design motion: the FMU does not know the master's); a value the
master set wins; a scene the error model does not cover is an fmi2Error."""

import json
import subprocess

import pytest
from slaves import started_slave


def cli_choice(riser_bin, scene, sets):
    args = [riser_bin, "statics", scene, "--json"]
    for k, v in sets.items():
        args += ["--set", f"{k}={v}"]
    return json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)["accuracy"]


def read_numerics(s, vr):
    return (s.getInteger([vr["n_elements"]])[0], s.getReal([vr["time_step"]])[0],
            s.getReal([vr["newton_tolerance"]])[0])


@pytest.mark.parametrize("scene,target", [("catenary", 1e-2), ("lazy_wave", 1e-3), ("steel_catenary", 1e-4)])
def test_the_chosen_numerics_are_read_back_after_initialisation(fmu_path, unzipped, riser_bin, scene, target):
    s, vr = started_slave(fmu_path, unzipped, scene=scene, reals={"accuracy": target})
    try:
        n, dt, tol = read_numerics(s, vr)
        c = cli_choice(riser_bin, scene, {"accuracy": target})
        assert (n, dt, tol) == (c["n_elements"], c["time_step"], c["newton_tolerance"])
        assert s.getReal([vr["accuracy"]])[0] == target
        s.doStep(0.0, 0.2)
        assert s.getReal([vr["top_tension"]])[0] > 0.0
    finally:
        s.terminate()
        s.freeInstance()


def test_numerics_the_master_sets_win(fmu_path, unzipped, riser_bin):
    s, vr = started_slave(fmu_path, unzipped, scene="lazy_wave", reals={"accuracy": 1e-3},
                          integers={"n_elements": 33})
    try:
        n, dt, tol = read_numerics(s, vr)
        c = cli_choice(riser_bin, "lazy_wave", {"accuracy": 1e-3, "n_elements": 33})
        assert n == 33 and c["set_by_user"]["n_elements"]
        assert (dt, tol) == (c["time_step"], c["newton_tolerance"])
    finally:
        s.terminate()
        s.freeInstance()


def test_without_accuracy_the_scene_numerics_are_read_back(fmu_path, unzipped):
    s, vr = started_slave(fmu_path, unzipped, scene="steel_catenary")
    try:
        assert read_numerics(s, vr) == (80, 0.05, 1e-8)
        assert s.getReal([vr["accuracy"]])[0] == 0.0
    finally:
        s.terminate()
        s.freeInstance()


def test_a_scene_the_model_does_not_cover_is_an_error(fmu_path, unzipped):
    with pytest.raises(Exception):
        started_slave(fmu_path, unzipped, scene="catenary", strings={"model": "cable"}, reals={"accuracy": 1e-3})


def test_a_scene_in_waves_gets_the_cli_choice(fmu_path, unzipped, riser_bin):
    """A sea the error model covers (docs/theory.md section 16.5): the FMU chooses what the CLI
    chooses for the same scene and sea."""
    strings = {"wave_kind": "jonswap"}
    reals = {"accuracy": 1e-3, "wave_hs": 6.0, "wave_tp": 10.0}
    integers = {"wave_components": 50, "wave_seed": 1}
    s, vr = started_slave(fmu_path, unzipped, scene="catenary", strings=strings, reals=reals, integers=integers)
    try:
        c = cli_choice(riser_bin, "catenary", {**strings, **reals, **integers})
        assert c["wave_number"] is not None
        assert read_numerics(s, vr) == (c["n_elements"], c["time_step"], c["newton_tolerance"])
        s.doStep(0.0, 0.2)
        assert s.getReal([vr["top_tension"]])[0] > 0.0
    finally:
        s.terminate()
        s.freeInstance()


def test_a_sea_the_model_does_not_cover_is_an_error(fmu_path, unzipped):
    with pytest.raises(Exception):
        started_slave(fmu_path, unzipped, scene="catenary", strings={"wave_kind": "airy"},
                      reals={"accuracy": 1e-3, "wave_height": 2.0, "wave_period": 12.0, "wave_direction": 45.0})
