"""The user's guide as a new user follows it (issues 52, 55): every page of docs/guide/.

Every fenced block of a page marked ``guide-test: NAME`` (```python guide-test: x.py, ```sh
guide-test: x.sh) runs from scratch: in an empty directory holding only the FMU as ``riser.fmu``,
the page's ``guide-file: NAME`` blocks (written as they stand) and the ``riser`` command line on
PATH, with the Python of this venv. What it prints (standard output and error, merged) must be what
the page's ``guide-output: NAME`` block shows:

* the same text line by line, whitespace runs collapsed; libcosim's log prefix (its time stamp and
  thread id) left out;
* every number within a tolerance: the larger of ``rtol`` times it (1e-3, or the block's
  ``rtol=...``) and one unit of its last printed digit (a rounding that flips);
* a line ``...`` in the page stands for any number of lines (fmpy's repeated warnings).

The blocks run concurrently (they share nothing but the read-only FMU), so the guide costs about
as long as its slowest script."""

import os
import re
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
# every page of the guide; those with runnable blocks are run
PAGES = sorted((ROOT / "docs" / "guide").glob("*.md"))
RUN = [p for p in PAGES if re.search(r"^```\w+ guide-test:", p.read_text(), re.M)]
RTOL = 1e-3

FENCE = re.compile(r"^```(\w+)[ \t]+guide-(test|output|file):[ \t]*(\S+)([^\n]*)\n(.*?)^```[ \t]*$", re.M | re.S)
# a number not glued to a word (fmi2DoStep, shape[0].x: the 0 is a number, the 2 is not)
NUMBER = re.compile(r"(?<![A-Za-z_\d.])[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?(?![A-Za-z_\d])")
LIBCOSIM_PREFIX = re.compile(r"^\[\d{4}-\d\d-\d\d [\d:.]+\] \[0x[0-9a-fA-F]+\] ")


def parse(page: Path) -> dict:
    """The page's guide blocks: {"test": {name: (language, body)}, "output": {name: (body, rtol)},
    "file": {name: body}}, in the page's order."""
    found = {"test": {}, "output": {}, "file": {}}
    for lang, kind, name, rest, body in FENCE.findall(page.read_text()):
        assert name not in found[kind], f"{page.name}: two guide-{kind} blocks named {name}"
        if kind == "test":
            found[kind][name] = (lang, body)
        elif kind == "output":
            m = re.search(r"rtol=([0-9.eE+-]+)", rest)
            found[kind][name] = (body, float(m.group(1)) if m else RTOL)
        else:
            found[kind][name] = body
    return found


def workdir(tmp: Path, blocks: dict, fmu_path: str, riser_bin: str) -> tuple[Path, dict]:
    """An empty directory with the FMU and the page's files, and the environment the scripts run
    in: the riser CLI on PATH, Python unbuffered (the order a terminal shows), temporary files
    (fmpy's extracted FMUs) inside `tmp`."""
    work = tmp / "work"
    work.mkdir(parents=True)
    shutil.copy(fmu_path, work / "riser.fmu")
    for name, body in blocks["file"].items():
        (work / name).write_text(body)
    bindir = tmp / "bin"
    bindir.mkdir()
    (bindir / "riser").symlink_to(riser_bin)
    (tmp / "tmp").mkdir()
    env = dict(os.environ, PATH=f"{bindir}{os.pathsep}{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
               PYTHONUNBUFFERED="1", TMPDIR=str(tmp / "tmp"))
    return work, env


def run_one(work: Path, env: dict, name: str, lang: str, body: str) -> tuple[int, str]:
    (work / name).write_text(body)
    cmd = [sys.executable, name] if lang == "python" else ["bash", "-e", "-o", "pipefail", name]
    p = subprocess.run(cmd, cwd=work, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       timeout=300)
    return p.returncode, p.stdout


def run_page(page: Path, tmp: Path, fmu_path: str, riser_bin: str, pool: ThreadPoolExecutor | None = None):
    """Runs every guide-test block of the page concurrently (in `pool`, or a pool of its own):
    ({name: (returncode, output)}, blocks)."""
    blocks = parse(page)
    work, env = workdir(tmp, blocks, fmu_path, riser_bin)
    own = pool is None
    pool = pool or ThreadPoolExecutor(max_workers=max(2, os.cpu_count() or 2))
    futures = {name: pool.submit(run_one, work, env, name, lang, body) for name, (lang, body) in blocks["test"].items()}
    runs = {name: f.result() for name, f in futures.items()}
    if own:
        pool.shutdown()
    return runs, blocks


def _tokens(line: str) -> tuple[str, list[str]]:
    line = LIBCOSIM_PREFIX.sub("", line.rstrip())
    return " ".join(NUMBER.sub("#", line).split()), NUMBER.findall(line)


def _unit(s: str) -> float:
    """One unit of the last printed digit of the number written s."""
    mantissa, _, exponent = s.lower().partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 10.0 ** (int(exponent or 0) - decimals)


def line_matches(expected: str, actual: str, rtol: float) -> bool:
    (et, en), (at, an) = _tokens(expected), _tokens(actual)
    if et != at or len(en) != len(an):
        return False
    return all(abs(float(a) - float(e)) <= max(rtol * abs(float(e)), _unit(e)) * (1 + 1e-9) for e, a in zip(en, an))


def matches(expected: str, actual: str, rtol: float) -> bool:
    """Whether the output `actual` is what the page shows (`...`: any lines)."""
    exp = [x for x in expected.rstrip("\n").split("\n")]
    act = [x for x in actual.rstrip("\n").split("\n")]

    def match(i: int, j: int) -> bool:
        if i == len(exp):
            return j == len(act)
        if exp[i].strip() == "...":
            return any(match(i + 1, k) for k in range(j, len(act) + 1))
        return j < len(act) and line_matches(exp[i], act[j], rtol) and match(i + 1, j + 1)

    return match(0, 0)


def first_difference(expected: str, actual: str, rtol: float) -> str:
    """Where the output leaves the page: the first page line not matched in order."""
    exp, act = expected.rstrip("\n").split("\n"), actual.rstrip("\n").split("\n")
    j, skipping = 0, False
    for k, e in enumerate(exp):
        if e.strip() == "...":
            skipping = True
            continue
        found = next((i for i in range(j, len(act) if skipping else min(j + 1, len(act)))
                      if line_matches(e, act[i], rtol)), None)
        if found is None:
            # the output's line with the same words, if any: its numbers differ
            near = next((a for a in act[j:] if _tokens(a)[0] == _tokens(e)[0]), act[j] if j < len(act) else "(none)")
            return f"page line {k + 1}:\n  page:   {e}\n  output: {near}"
        j, skipping = found + 1, False
    return f"the output goes on after the page's last line: {act[j] if j < len(act) else ''}"


@pytest.fixture(scope="module")
def guide_runs(fmu_path, riser_bin, tmp_path_factory):
    """Both pages' blocks, all at once."""
    assert Path(riser_bin).exists(), f"the guide runs the riser CLI: build it first ({riser_bin})"
    with ThreadPoolExecutor(max_workers=max(2, os.cpu_count() or 2)) as pool, \
            ThreadPoolExecutor(max_workers=len(RUN)) as pages:
        jobs = {page.name: pages.submit(run_page, page, tmp_path_factory.mktemp(page.stem), fmu_path, riser_bin, pool)
                for page in RUN}
        return {name: job.result() for name, job in jobs.items()}


@pytest.mark.parametrize("page", [p.name for p in RUN])
def test_every_block_of_the_guide_runs_from_scratch_and_prints_what_the_page_shows(guide_runs, page):
    runs, blocks = guide_runs[page]
    assert blocks["test"], f"{page}: no guide-test blocks"
    assert set(blocks["test"]) == set(blocks["output"]), \
        f"{page}: guide-test blocks without their output, or outputs without a test: " \
        f"{sorted(set(blocks['test']) ^ set(blocks['output']))}"
    failures = []
    for name, (code, out) in runs.items():
        expected, rtol = blocks["output"][name]
        if code != 0:
            failures.append(f"{name} exited with {code}:\n{out[-3000:]}")
        elif not matches(expected, out, rtol):
            failures.append(f"{name} printed other numbers or text than the page (rtol {rtol}): "
                            f"{first_difference(expected, out, rtol)}\n--- its output ---\n{out}")
    assert not failures, f"{page}:\n" + "\n\n".join(failures)


def test_the_headings_the_code_points_to_exist():
    """src/fmi/plausibility.rs and src/scene/overrides.rs send readers to these sections."""
    headings = {p.name: {line.lstrip("#").strip() for line in p.read_text().splitlines() if line.startswith("#")}
                for p in PAGES}
    assert "Inputs riser calls implausible" in {h.split(". ", 1)[-1] for h in headings["coupling.md"]}
    assert "Inputs riser calls implausible" in headings["fmu.md"]
    assert "Parameters a scene holds as several values" in headings["fmu.md"]


def test_the_guide_s_links_between_its_pages_land_on_headings():
    """[text](page.md#anchor) and [text](#anchor) within docs/guide/, anchors as GitHub makes them."""
    def slug(heading):
        return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")

    anchors = {p.name: {slug(line.lstrip("#")) for line in p.read_text().splitlines() if line.startswith("#")}
               for p in PAGES}
    for p in PAGES:
        for target, anchor in re.findall(r"\]\(([\w.]*\.md|)#([^)]+)\)", p.read_text()):
            page = target or p.name
            if page in anchors:
                assert anchor in anchors[page], f"{p.name}: a link to {page}#{anchor}, which is no heading"
        for target in re.findall(r"\]\(([^)#:]+\.md)[)#]", p.read_text()):
            assert (p.parent / target).exists(), f"{p.name}: a link to {target}, which does not exist"


def test_the_comparison_tolerates_what_it_should_and_nothing_else():
    assert line_matches("top tension 141.743 kN", "top tension 141.744 kN", 1e-9)  # a last digit flips
    assert not line_matches("top tension 141.743 kN", "top tension 141.746 kN", 1e-9)
    assert line_matches("max 768.676 kN", "max 769.000 kN", 1e-3)
    assert not line_matches("1075 Newton iterations", "1077 Newton iterations", 1e-3)
    assert not line_matches("fmi2DoStep failed", "fmi3DoStep failed", 1.0)
    assert line_matches("shape[0].z -0.300 m", "shape[0].z -0.300 m", 0.0)
    assert line_matches("-0.000", "0.000", 0.0)
    assert matches("a\n...\nb 1.0", "a\nx\ny\nb 1.0\n", 1e-3)
    assert not matches("a\n...\nb 1.0", "a\nx\n", 1e-3)
    prefix = "[2026-12-07 03:56:58.292937] [0x00007fc35e3ff6c0] "
    assert line_matches("[2025-01-01 00:00:00.000001] [0x00007f0000000000] [warning] t = 2 s",
                        prefix + "[warning] t = 2 s", 1e-3)
