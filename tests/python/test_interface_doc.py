"""docs/interface.md is the repository's own copy of the contract: it must be
what riser_tools.interface_doc (`riser-tools interface-doc`) writes from the current variable table and CLI,
and it must list every variable the packaged FMU declares."""
import subprocess
import sys
from pathlib import Path

from fmpy import read_model_description

ROOT = Path(__file__).resolve().parents[2]


def test_interface_doc_is_up_to_date(riser_bin):
    r = subprocess.run([sys.executable, "-m", "riser_tools", "interface-doc", "--bin", riser_bin, "--check"], cwd=ROOT,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def test_interface_doc_lists_every_variable_of_the_fmu(fmu_path):
    text = (ROOT / "docs" / "interface.md").read_text()
    md = read_model_description(fmu_path)
    for v in md.modelVariables:
        assert f"| {v.valueReference} | `{v.name}` | {v.causality} |" in text, v.name
