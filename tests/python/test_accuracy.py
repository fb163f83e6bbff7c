"""`accuracy` through the FMU (issue 51, docs/theory.md section 16.12): in
initialisation riser runs its pilots of the design motion (the FMU does not know
its master's motion) and chooses the numerics; the master reads them back as the
calculated parameters chosen_n_elements, chosen_time_step, chosen_newton_tolerance
and the estimate as the output error_estimate: the same as `riser statics` chooses
for the same scene. n_elements, time_step and newton_tolerance start at 0 ("the
scene's, or the choice"), so a master that sets every start value (libcosim) does
not pin them; a nonzero value the master sets wins."""

import json
import subprocess
from pathlib import Path

import pytest
from fmpy import read_model_description
from slaves import started_slave


def cli_choice(riser_bin, scene, sets):
    args = [riser_bin, "statics", scene, "--json"]
    for k, v in sets.items():
        args += ["--set", f"{k}={v}"]
    return json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)["accuracy"]


def chosen(s, vr):
    return (s.getInteger([vr["chosen_n_elements"]])[0], s.getReal([vr["chosen_time_step"]])[0],
            s.getReal([vr["chosen_newton_tolerance"]])[0])


def test_the_fmu_chooses_what_statics_chooses_and_reports_its_estimate(fmu_path, unzipped, riser_bin):
    s, vr = started_slave(fmu_path, unzipped, scene="catenary", reals={"accuracy": 1e-2})
    try:
        c = cli_choice(riser_bin, "catenary", {"accuracy": 1e-2})
        assert chosen(s, vr) == (c["chosen"]["n_elements"], c["chosen"]["time_step"],
                                 c["chosen"]["newton_tolerance"])
        assert s.getReal([vr["error_estimate"]])[0] == pytest.approx(c["estimate"], rel=1e-12)
        assert 0.0 < c["estimate"] <= 1e-2
        # the fixed parameters read as the master left them (unset: the scene's)
        assert s.getReal([vr["accuracy"]])[0] == 1e-2
        s.doStep(0.0, 0.2)
        assert s.getReal([vr["top_tension"]])[0] > 0.0
    finally:
        s.terminate()
        s.freeInstance()


def test_a_nonzero_value_the_master_sets_wins(fmu_path, unzipped, riser_bin):
    s, vr = started_slave(fmu_path, unzipped, scene="catenary", reals={"accuracy": 1e-2},
                          integers={"n_elements": 20})
    try:
        c = cli_choice(riser_bin, "catenary", {"accuracy": 1e-2, "n_elements": 20})
        assert c["set_by_user"]["n_elements"] and c["chosen"]["n_elements"] == 20
        assert chosen(s, vr) == (20, c["chosen"]["time_step"], c["chosen"]["newton_tolerance"])
        assert s.getInteger([vr["n_elements"]])[0] == 20
    finally:
        s.terminate()
        s.freeInstance()


def test_the_numerics_start_at_zero_and_zero_is_the_scene_s(fmu_path, unzipped):
    md = read_model_description(fmu_path)
    start = {v.name: v.start for v in md.modelVariables}
    assert (start["n_elements"], start["time_step"], start["newton_tolerance"]) == ("0", "0", "0")
    causality = {v.name: v.causality for v in md.modelVariables}
    assert {causality[n] for n in ("chosen_n_elements", "chosen_time_step", "chosen_newton_tolerance")} == \
        {"calculatedParameter"}
    # a master that sets every start value: the scene's own numerics run
    s, vr = started_slave(fmu_path, unzipped, scene="steel_catenary", reals={"time_step": 0.0,
                          "newton_tolerance": 0.0}, integers={"n_elements": 0})
    try:
        assert chosen(s, vr) == (80, 0.05, 1e-8)
        assert s.getReal([vr["error_estimate"]])[0] == 0.0
    finally:
        s.terminate()
        s.freeInstance()


def test_a_quantity_the_scene_does_not_have_is_an_error(fmu_path, unzipped):
    with pytest.raises(Exception):
        started_slave(fmu_path, unzipped, scene="catenary", strings={"accuracy_quantity": "touchdown"},
                      reals={"accuracy": 1e-3})


# Two of moored_vessel's chains hanging free, fore and aft (tests/it/system_accuracy.rs)
HANGING = Path(__file__).resolve().parents[2] / "docs" / "cases" / "two_chains_hanging.toml"


def test_a_system_fmu_chooses_what_the_command_line_chooses_for_the_design_motion(fmu_path, unzipped, riser_bin,
                                                                                   tmp_path):
    """A system of lines with `accuracy` (docs/theory.md section 16.14): the FMU's pilots of the
    whole system on the design motion (a heave of 2.5 m at 10 s grown over a period, window 20-50 s)
    choose what `riser run SYSTEM --heave 2.5,10 --duration 50` chooses on that same motion: the
    level (chosen_n_elements, every line's elements here), the step, the tolerance and the estimate."""
    scene = tmp_path / "two_chains.toml"
    text = HANGING.read_text().replace("newton_tolerance = 1e-8", "newton_tolerance = 1e-8\naccuracy = 1e-2")
    scene.write_text(text)
    run = subprocess.run([riser_bin, "run", str(scene), "--heave", "2.5,10", "--duration", "50", "--json"],
                         check=True, capture_output=True, text=True)
    c = json.loads(run.stdout)["accuracy"]
    s, vr = started_slave(fmu_path, unzipped, scene=str(scene))
    try:
        assert chosen(s, vr) == (c["chosen"]["n_elements"], c["chosen"]["time_step"],
                                 c["chosen"]["newton_tolerance"])
        assert s.getReal([vr["error_estimate"]])[0] == pytest.approx(c["estimate"], rel=1e-12)
        assert c["met"] and 0.0 < c["estimate"] <= 1e-2
        s.doStep(0.0, c["chosen"]["time_step"])
        assert s.getReal([vr["top_tension"]])[0] > 0.0
    finally:
        s.terminate()
        s.freeInstance()
