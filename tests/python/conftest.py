import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def fmu_path():
    p = ROOT / "fmu" / "riser.fmu"
    assert p.exists(), "build it first: make fmu"
    return str(p)


@pytest.fixture(scope="session")
def riser_bin():
    return str(ROOT / "target" / "release" / "riser")


@pytest.fixture(scope="session")
def unzipped(fmu_path, tmp_path_factory):
    from fmpy import extract

    return extract(fmu_path, unzipdir=str(tmp_path_factory.mktemp("riser_fmu")))


os.environ.setdefault("PYTHONHASHSEED", "0")
