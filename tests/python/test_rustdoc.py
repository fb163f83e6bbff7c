"""`make doc` (python/riser_tools/src/riser_tools/rustdoc.py): rustdoc on the tests' build, the
dependencies not checked again. With `-D warnings`, as the Makefile calls it, a broken intra-doc link
fails it: the same command on a copy of the sources with one broken link put in src/lib.rs exits 1
naming the link, and on the copy as it is exits 0 (the copy holds what src/ includes: scenes/ and
docs/cases/). Long (`make check-long`): rustdoc of the crate twice, about 10 s of CPU."""
import importlib.util
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.long
def test_a_broken_intra_doc_link_fails_make_doc(tmp_path):
    spec = importlib.util.spec_from_file_location(
        "rustdoc", ROOT / "python" / "riser_tools" / "src" / "riser_tools" / "rustdoc.py")
    rustdoc = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(rustdoc)
    cmd, env = rustdoc.rustdoc_command(ROOT, "fasttest", "cargo", "rustdoc", tmp_path / "doc", ["-D", "warnings"])
    copy = tmp_path / "tree"
    for d in ("src", "scenes", "docs/cases"):
        shutil.copytree(ROOT / d, copy / d)
    i = cmd.index("src/lib.rs")
    cmd[i] = str(copy / "src" / "lib.rs")
    ok = subprocess.run(cmd, env=env, capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr
    lib = copy / "src" / "lib.rs"
    lib.write_text("//! See [`NoSuchItemAnywhere`].\n" + lib.read_text())
    broken = subprocess.run(cmd, env=env, capture_output=True, text=True)
    assert broken.returncode == 1, broken.stderr
    assert "unresolved link to `NoSuchItemAnywhere`" in broken.stderr, broken.stderr
