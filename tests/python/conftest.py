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


def pytest_configure(config):
    # matplotlib's mathtext and font-config parsers call pyparsing names that the pinned pyparsing
    # deprecates ("'setName' deprecated - use 'set_name'"): third-party, harmless, and hundreds a run
    config.addinivalue_line("filterwarnings", "ignore::DeprecationWarning:matplotlib._mathtext")
    config.addinivalue_line("filterwarnings", "ignore::DeprecationWarning:matplotlib._fontconfig_pattern")
    config.addinivalue_line("filterwarnings", "ignore::DeprecationWarning:pyparsing")
