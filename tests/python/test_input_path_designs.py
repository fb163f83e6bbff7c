"""The middle steps' end-state design (docs/theory.md (7.3b), src/fmi/input_path.rs MIDDLE): the table
riser ships is the one riser_tools.studies.input_path_designs makes, riser_tools.coupling_analysis
mirrors it, and on the filter-level measures of docs/input_path_designs.md it does what it was chosen
for against the design before it (the path inside the steps, the alternation's onset, the loop)."""
import re
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]


def rust_middle() -> np.ndarray:
    src = (ROOT / "src" / "fmi" / "input_path.rs").read_text()
    head = "pub const MIDDLE: [[f64; TAPS]; 3] = ["
    body = src[src.index(head) + len(head):]
    body = body[: body.index("\n];")]
    rows = re.findall(r"\[([-+0-9eE.,\s]+)\]", body)
    return np.array([[float(x) for x in r.split(",") if x.strip()] for r in rows])


def test_the_shipped_middle_design_is_the_study_s_and_the_analysis_mirrors_it():
    from riser_tools import coupling_analysis as ca
    from riser_tools.studies import input_path_designs as study

    w = rust_middle()
    assert w.shape == (3, 16)
    assert np.array_equal(w, ca.MIDDLE)
    # remade from the catenary's measured answers (docs/coupling_response.csv): the same to round-off
    assert np.max(np.abs(study.middle().w - w)) < 1e-9


def test_the_middle_design_follows_the_motion_inside_the_steps_and_keeps_the_loop_and_the_alternation_down():
    from riser_tools import coupling_analysis as ca
    from riser_tools.studies import input_path_designs as study

    resp = ca.read_response(ROOT / "docs" / "coupling_response.csv")
    before, after = study.today(), study.Candidate("middle", ca.MIDDLE)
    for h in (0.1, 0.15, 0.2):
        b, a = study.measures(before, h, resp), study.measures(after, h, resp)
        print(f"h {h}: inside {b['inside']:.2e} -> {a['inside']:.2e} of A w^2, end {b['end']:.2e} -> "
              f"{a['end']:.2e}, onset {b['onset']:.2f} -> {a['onset']:.2f} kN, ring {b['ring']:.2f} -> {a['ring']:.2f}")
        # the path's acceleration inside the steps on a 10 s heave (what two internal steps see):
        # measured 1.3e-3 of A w^2 at 0.2 s against 1.1e-2 before (tests/it/input_path_interior.rs: the FMU's)
        assert a["inside"] < b["inside"] / 5, (h, a["inside"], b["inside"])
        # an alternation that starts mid-run swings the catenary's tension less than before (issue 53: < 1 kN)
        assert a["onset"] < min(b["onset"], 1.0), (h, a["onset"], b["onset"])
        # a steady alternation moves no end state
        assert a["alt"] < 1e-12
    # the 2000 t vessel's loop gain where the line's axial resonance aliases at 0.2 s (0.36-0.44 pi):
    # 0.47 before (bounded in libcosim at 0.2 s, growing at 0.205 s), and at every step above pi/2
    b, a = study.measures(before, 0.2, resp), study.measures(after, 0.2, resp)
    assert a["proxy"] < b["proxy"] / 2 and a["gain"] < b["gain"], (a["proxy"], b["proxy"], a["gain"], b["gain"])
