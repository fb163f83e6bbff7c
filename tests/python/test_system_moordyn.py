"""OC3-Hywind's mooring under a prescribed vessel motion, riser against MoorDyn-C v2
(issue 49, evidence 3; docs/system_moordyn.md, riser_tools.studies.moordyn_system).

Both codes read docs/cases/oc3_hywind_mooring.toml (MoorDyn's input is written from it by
riser_tools.moordyn_system: a Coupled body carrying the fairleads, the same segments, seabed
and water), the vessel moves along surge 10 m / 100 s plus heave 2 m / 12 s grown over the
same ramp, and each fairlead's tension window and the resultant's surge and heave windows are
compared.

* The short test (unmarked, a few seconds): 60 s, 20 elements a line, the chain with MoorDyn's
  OC3 hydrodynamics (Cd 1.6, Ca 1.0, CdAx 0.1), ramp 12 s, window 30-60 s. Measured: the
  tensions' and the resultant's min / mean / max within TOL_SHORT_MEASURED of the largest
  tension (1.4e-3 at line 1's minimum, 1.8e-3 at F_x's maximum); the bound TOL_SHORT is
  about 3 times that (margin for another machine's rounding), and well below the issue's 2 %.
* The long test (`long`, `make check-long`): the study's 600 s runs at 50 and 100 elements,
  all three cases; every entry within the codes' mesh-to-mesh change or 2 % of the quantity's
  largest magnitude (the issue's acceptance), and in the cases with drag within the tighter
  bound TOL_DRAG measured there.
"""

from __future__ import annotations

import pytest

from conftest import ROOT

pytest.importorskip("moordyn")

from riser_tools import moordyn_system as ms  # noqa: E402
from riser_tools.cases import Motion  # noqa: E402
from riser_tools.studies import moordyn_system as study  # noqa: E402

SHORT_MOTIONS = (Motion(10.0, 100.0, "surge", 12.0), Motion(2.0, 12.0, "heave", 12.0))
SHORT_WINDOW = (30.0, 60.0)
TOL_SHORT_MEASURED = 1.8e-3
TOL_SHORT = 5.0e-3
TOL_DRAG = 5.0e-3


def test_the_input_file_has_the_scenes_lines_points_and_seabed(tmp_path):
    s = ms.load(ROOT / "docs" / "cases" / "oc3_hywind_mooring.toml")
    text = ms.input_text(s, 50, 0.002, ba=-0.05)
    assert "1    Coupled" in text
    assert text.count(" Fixed ") == 3 and text.count(" Body1 ") == 3
    assert "3.000000000e+06" not in text            # kBot is written as the scene's number
    for key, value in (("kBot", "3000000.0"), ("cBot", "300000.0"), ("WtrDpth", "320.0"), ("rho", "1025.0"),
                       ("g", "9.80665"), ("FrictionCoefficient", "0.0")):
        assert any(ln.split() == [value, key] for ln in text.splitlines()), key
    assert text.count("  902.2  50  -") == 3


def test_a_short_run_agrees_with_moordyn(riser_bin, tmp_path):
    p = study.run_pair(riser_bin, tmp_path, "hydro", 20, motions=SHORT_MOTIONS, duration=60.0,
                       window=SHORT_WINDOW, threads=2)
    w = p.windows(SHORT_WINDOW)
    scale = max(max(abs(v) for v in w[q][1]) for q in w if ".tension" in q)
    for q, (r, m) in w.items():
        if ".tension" not in q:
            continue
        for st, a, b in zip(study.STATS, r, m):
            assert abs(a - b) <= TOL_SHORT * scale, f"{q} {st}: riser {a:.1f} N, MoorDyn {b:.1f} N"
    fx, fz = w["top_force_x"], w["top_force_z"]
    for (r, m) in (fx, fz):
        big = max(abs(v) for v in m)
        for a, b in zip(r, m):
            assert abs(a - b) <= TOL_SHORT * max(big, scale)


@pytest.mark.long
def test_the_600_s_comparison_is_within_the_discretisation(riser_bin, tmp_path):
    table = study.sea_table(riser_bin, tmp_path)
    for case in study.CASES:
        pairs = [study.run_pair(riser_bin, tmp_path, case, n, table=table, threads=2) for n in study.MESHES]
        rows = study.compare(*pairs)
        bad = [r for r in rows if not r["ok"]]
        assert not bad, [(r["quantity"], r["stat"], r["diff"], r["mesh"], r["rel"]) for r in bad]
        if case != "bare":
            worst = max(abs(r["rel"]) for r in rows)
            assert worst <= TOL_DRAG, (case, worst)
