"""A logger given to fmpy must not kill the process after its instance is freed.

fmpy's native logger proxy keeps one process-wide pointer to the last Python logger
(riser_tools/fmpy_logging.py explains it); riser_sweep's spec check and cases give a
logger, and a later FMU error anywhere in the process then jumped into freed memory
(two segmentation faults of a pytest-xdist worker in test_directional_derivative.py
and test_accuracy.py, both at an expected fmi2Error)."""

import os
import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).with_name("fmpy_logger_script.py")


def run(fmu_path, mode):
    env = dict(os.environ, PYTHONFAULTHANDLER="0")
    return subprocess.run([sys.executable, str(SCRIPT), fmu_path, mode], capture_output=True, text=True,
                          timeout=60, env=env)


def test_a_later_error_is_logged_after_the_loggers_instance_is_freed(fmu_path):
    kept = run(fmu_path, "kept")
    assert kept.returncode == 0, kept.stderr[-2000:]
    assert "refused: fmi2SetReal failed with status 3" in kept.stdout
    # the same sequence through fmpy's instantiate_fmu, for the record (fmpy 0.3.x dies here)
    raw = run(fmu_path, "raw")
    print("fmpy's instantiate_fmu with a logger, then a later error: exit code", raw.returncode)
