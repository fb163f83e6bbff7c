import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


# `make test` and `make check` point these with RISER_FMU and RISER_BIN at
# the FMU and CLI of the fasttest build; without them (`make
# fmu-test-release`) they run the shipped FMU and CLI (release profile).
@pytest.fixture(scope="session")
def fmu_path():
    # absolute: some tests hand the path to tools run in a temporary directory
    p = Path(os.environ.get("RISER_FMU", ROOT / "fmu" / "riser.fmu")).resolve()
    assert p.exists(), f"build it first: make fmu ({p})"
    return str(p)


@pytest.fixture(scope="session")
def riser_bin():
    return str(Path(os.environ.get("RISER_BIN", ROOT / "target" / "release" / "riser")).resolve())


@pytest.fixture(scope="session")
def unzipped(fmu_path, tmp_path_factory):
    from fmpy import extract

    return extract(fmu_path, unzipdir=str(tmp_path_factory.mktemp("riser_fmu")))


os.environ.setdefault("PYTHONHASHSEED", "0")


# Each test file's time budget, s, on a quiet 2-core machine (`make test`'s whole Python part is
# about 4 min of its 8): the run prints every file's time against it at the end, and the files over
# it; never an assertion (speed is a benchmark's, not a test's). `make test` runs two files at a time
# (pytest-xdist): a file beside another takes up to about 1.6 times its time alone (test_sweep.py
# 66-71 s, 41 s alone; test_parameter_ranges.py 10.5-11 s, 7 s alone). Tests marked `long` run in `make check-long`, not in `make test`.
BUDGETS = {
    "test_accuracy.py": 40, "test_cosim_inputs.py": 30, "test_coupling.py": 45, "test_coupling6.py": 30,
    "test_coupling_buoy.py": 30, "test_coupling_mono.py": 25, "test_directional_derivative.py": 10, "test_fatigue.py": 10, "test_fmpy_logging.py": 10,
    "test_fmu.py": 45, "test_fuzz.py": 35, "test_guide.py": 30, "test_interface_doc.py": 5, "test_masters.py": 15,
    "test_model_structure.py": 5, "test_parameter_ranges.py": 10, "test_scatter_fatigue.py": 20, "test_sweep.py": 60,
    "test_system_coupling.py": 20, "test_system_free_dd.py": 15, "test_system_free_fmu.py": 10, "test_system_moordyn.py": 25, "test_tools.py": 20,
    "test_rustdoc.py": 30, "test_sea_states.py": 15, "test_vessel.py": 30, "test_vessel6.py": 15, "test_waves.py": 15,
}
_SPENT: dict[str, float] = {}


def pytest_runtest_logreport(report):
    name = report.nodeid.split("::")[0].rsplit("/", 1)[-1]
    _SPENT[name] = _SPENT.get(name, 0.0) + report.duration


def pytest_terminal_summary(terminalreporter):
    if not _SPENT:
        return
    over = [f for f, s in _SPENT.items() if s > BUDGETS.get(f, 10)]
    terminalreporter.write_sep("-", f"time per test file against its budget ({len(over)} over)")
    for f, s in sorted(_SPENT.items(), key=lambda x: -x[1]):
        b = BUDGETS.get(f, 10)
        terminalreporter.write_line(f"{f:32} {s:7.1f} s of {b:4d} s{'  OVER' if s > b else ''}")


def pytest_configure(config):
    config.addinivalue_line("markers", "long: a long comparison, run by `make check-long`, not `make test`")
    # matplotlib's mathtext and font-config parsers call pyparsing names that the pinned pyparsing
    # deprecates ("'setName' deprecated - use 'set_name'"): third-party, harmless, and hundreds a run
    config.addinivalue_line("filterwarnings", "ignore::DeprecationWarning:matplotlib._mathtext")
    config.addinivalue_line("filterwarnings", "ignore::DeprecationWarning:matplotlib._fontconfig_pattern")
    config.addinivalue_line("filterwarnings", "ignore::DeprecationWarning:pyparsing")
