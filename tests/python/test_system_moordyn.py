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

A free point (issue 49, point 2): docs/cases/clump_weight_mooring.toml, a 10 t clump (C_dA 1.4
m^2, C_a 1) between an anchor chain of 300 m and a fairlead chain of 260 m, the chain with
MoorDyn's OC3 hydrodynamics, the clump a MoorDyn Free point with the same mass, volume, CdA and
Ca (the conventions are the same: weight and buoyancy rho g V of the whole volume, drag
1/2 rho CdA |u - v| (u - v), added mass Ca rho V), under the same surge and heave:

* short (unmarked, about 4 s): 20 elements a line, 60 s, ramp 12 s, window 30-60 s, MoorDyn's
  Free point started at riser's static equilibrium (started at the scene's start position it
  swings in its first minute and the windows were MoorDyn's start: the extremes 1.9e-2 apart
  before). Measured: the clump's position windows within 0.002 m (of a 29 m vertical range),
  the tensions' and the resultant's extremes within 1.9e-3 and their means within 1.4e-4 of
  the largest tension; held to CLUMP_POS_SHORT and CLUMP_TOL_SHORT.
* long (`long`): 26 and 52 elements, 300 s, ramp 100 s, window 150-300 s. Measured at 52: the
  clump within 0.005 m (0.026 m at 26), the means within 3.3e-4 and the peaks within 4.6e-4 of
  the largest tension; the least-pull statistics (the tensions' minima, the resultant's
  smallest magnitude) are not alike: they fall when the clump reaches the seabed once a surge
  period (riser's clump 7 cm into it, its contact spring k_b x 1 m^2 carrying it, so the
  lower chain slackens further; MoorDyn-C's point has no seabed contact): up to 5.1e-2 of the
  largest tension, not within either code's mesh change; reported, not held.

The bridle (docs/cases/bridle_mooring.toml, a joint of three chains; `long`): 20 and 40 elements,
60 s; its least-pull differences are discretisation (see the comment above its test).

The subsea buoy in a regular wave (short, about 10 s): see the comment above its test.
"""

from __future__ import annotations

import numpy as np
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
CLUMP_POS_SHORT = 0.01          # m (measured 0.002)
CLUMP_TOL_SHORT = 5.0e-3        # of the largest tension (measured 1.9e-3; means 1.4e-4)
CLUMP_MEAN_SHORT = 1.0e-3
CLUMP_POS_LONG = 0.05           # m (measured 0.026 at 26 elements, 0.005 at 52)
CLUMP_TOL_LONG = 2.0e-2         # the 2 % (measured 4.6e-4 at 52, 1.1e-3 at 26)


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


def _clump_checks(rows, pos_tol, tol, mean_tol=None, skip_least_pull=False):
    """Every row within its bound: positions in m, tensions and forces relative to the largest
    tension; with `skip_least_pull`, a quantity's statistic of the smaller magnitude (a
    tension's minimum, a pulling force's maximum) is left out (the slack moments at the clump's
    seabed contact, see the docstring), and returned."""
    tension = max(r["scale"] for r in rows if ".tension" in r["quantity"])
    left = []
    by_q: dict[str, dict[str, dict]] = {}
    for r in rows:
        by_q.setdefault(r["quantity"], {})[r["stat"]] = r
    for q, st in by_q.items():
        if q.split(".")[-1] in ("x", "y", "z"):
            for r in st.values():
                assert abs(r["diff"]) <= pos_tol, f"{q} {r['stat']}: {r['riser']:.4f} against {r['md']:.4f} m"
            continue
        least = min(("min", "max"), key=lambda k: abs(st[k]["md"]))
        for k, r in st.items():
            if skip_least_pull and k == least:
                left.append(r)
                continue
            bound = mean_tol if (mean_tol is not None and k == "mean") else tol
            assert abs(r["diff"]) <= bound * tension, f"{q} {k}: {r['diff'] / tension:.2e} of the largest tension"
    return left


def test_a_free_point_agrees_with_moordyn_short(riser_bin, tmp_path):
    p = study.clump_pair(riser_bin, tmp_path, 20, motions=SHORT_MOTIONS, duration=60.0, window=SHORT_WINDOW,
                         threads=2)
    rows = study.clump_rows(p, SHORT_WINDOW)
    _clump_checks(rows, CLUMP_POS_SHORT, CLUMP_TOL_SHORT, CLUMP_MEAN_SHORT)
    assert p.riser_json["points"][0]["name"] == "clump"


@pytest.mark.long
def test_a_free_point_agrees_with_moordyn_over_300_s(riser_bin, tmp_path):
    for n in study.CLUMP_MESHES:
        p = study.clump_pair(riser_bin, tmp_path, n, threads=2)
        rows = study.clump_rows(p)
        left = _clump_checks(rows, CLUMP_POS_LONG, CLUMP_TOL_LONG, skip_least_pull=True)
        # the least-pull moments are the clump's landings on the seabed: riser's clump is in it
        z_min = p.riser["clump.z"][p.riser["t"] >= study.CLUMP_WINDOW[0]].min()
        assert z_min < p.system.seabed_z, z_min
        assert left, "the least-pull statistics are reported"


# The subsea buoy (docs/cases/subsea_buoy_mooring.toml: a 15 m^3 buoy between a 220 m chain tether
# and a 330 m rope to the vessel, no drag area on the buoy), both codes from riser's static
# equilibrium (MoorDyn's Free point started at the scene's start position swings 12 m in its
# first minute: its start, not the physics): 22 elements, 60 s. Measured: the buoy's windows
# within 5 mm of a 17.7 m swing, tensions and forces within 1.4e-3 of the largest tension (the
# means 3e-4).
BUOY_POS_SHORT = 0.02           # m
BUOY_TOL_SHORT = 1.0e-2         # of the largest tension
BUOY_MEAN_SHORT = 1.0e-3


def test_the_subsea_buoy_agrees_with_moordyn_short(riser_bin, tmp_path):
    p = study.clump_pair(riser_bin, tmp_path, 22, motions=SHORT_MOTIONS, duration=60.0, window=SHORT_WINDOW,
                         threads=2, case=ROOT / "docs" / "cases" / "subsea_buoy_mooring.toml")
    rows = study.clump_rows(p, SHORT_WINDOW)
    for r in rows:
        print(f"{r['quantity']:24s} {r['stat']:5s} riser {r['riser']:12.5g} MoorDyn {r['md']:12.5g}")
    _clump_checks(rows, BUOY_POS_SHORT, BUOY_TOL_SHORT, BUOY_MEAN_SHORT)
    assert p.riser_json["points"][0]["name"] == "buoy"


# The bridle (docs/cases/bridle_mooring.toml: two 60 m chains from fairleads 12 m apart to a 1 t
# joint, 600 m of chain from there to the anchor, 433 m of it on the seabed; no drag area on the
# joint), the chain with MoorDyn's OC3 hydrodynamics, both codes from riser's static equilibrium,
# 60 s, ramp 12 s, window 30-60 s, every line in 20 and in 40 elements (MoorDyn: segments). The
# least-pull extremes (the bridles' and the anchor chain's minimum tensions, the resultant's
# smallest magnitude: the vessel surging towards the anchor, the main chain laid down on the
# seabed in 30 m elements at 20) are far from converged in either code: the bridles' minimum
# moves 14.5 kN (riser) and 21.1 kN (MoorDyn) from 20 to 40 elements, the codes' difference
# 9.2 kN (4.7e-2 of the largest tension) at 20 and 2.5 kN (1.3e-2) at 40; the resultant's least
# pull 5.5e-2 and 6.8e-2 (F_x, F_z) at 20, 1.0e-2 and 1.9e-2 at 40. Discretisation, not a model
# difference: at 40 elements every statistic is within the codes' own 20 -> 40 change or 2 % of
# its largest magnitude (the OC3 comparison's acceptance; measured: every one within the mesh
# change), and the least-pull differences fall by more than half from 20 to 40 (measured: by 3.7,
# 5.6 and 3.6 times; at 80, a study run of 15 minutes: 3.1e-3, 4.7e-3, 3.7e-3, the bridles'
# minimum 96.3 kN in riser, 95.7 in MoorDyn). The means and peaks agree at 20 within 2 % too
# (measured: the anchor chain's peak at the anchor 1.7e-2 of the largest tension, the rest within
# 2.2e-3). About 4 minutes on the shared 2-core machine (MoorDyn's step, 1.4e-4 s at 40, set by
# the 60 m bridles' 1.5 m segments, is the cost): long.
BRIDLE = ROOT / "docs" / "cases" / "bridle_mooring.toml"
BRIDLE_MESHES = (20, 40)


@pytest.mark.long
def test_the_bridle_agrees_with_moordyn_within_the_discretisation(riser_bin, tmp_path):
    pairs = [study.clump_pair(riser_bin, tmp_path, n, motions=SHORT_MOTIONS, duration=60.0, window=SHORT_WINDOW,
                              threads=2, case=BRIDLE) for n in BRIDLE_MESHES]
    rows = study.compare(*pairs, window=SHORT_WINDOW)
    for r in rows:
        print(f"{r['quantity']:28s} {r['stat']:5s} riser {r['riser_coarse']:12.6g} -> {r['riser']:12.6g} "
              f"MoorDyn {r['md_coarse']:12.6g} -> {r['md']:12.6g} rel {r['rel']:+.2e} ({r['why']})")
    bad = [r for r in rows if not r["ok"]]
    assert not bad, [(r["quantity"], r["stat"], r["diff"], r["mesh"], r["rel"]) for r in bad]
    # the least-pull extremes' differences more than halve from 20 to 40 elements
    for q in ("bridle_port.tension_to", "top_force_x", "top_force_z"):
        least = [r for r in rows if r["quantity"] == q and r["stat"] == ("min" if ".tension" in q else "max")][0]
        assert abs(least["diff"]) < 0.5 * abs(least["diff_coarse"]), least
    # the means and peaks already at 20 elements within 2 % of the largest tension
    coarse = study.clump_rows(pairs[0], SHORT_WINDOW)
    left = _clump_checks(coarse, 0.1, 2e-2, skip_least_pull=True)
    assert left, "the least-pull statistics are reported"


# The subsea buoy in a regular wave (docs/theory.md (17.18)): H 8 m, T 15 s, travelling at 30°, phase
# 40°, grown over 15 s, no stretching, in the seabed's 200 m; the buoy with C_dA 7.4 m^2 and C_a 0.5,
# the lines with MoorDyn's OC3 hydrodynamics, the vessel held, both codes from riser's statics, 22
# elements, 60 s, window 30-60 s. MoorDyn-C 2.7's Free point takes the waves' velocity in its drag
# but not their acceleration (no Froude-Krylov or added-mass wave inertia, most of this buoy's wave
# load): the run hands it a water velocity whose drag is riser's whole wave load on the point
# (riser_tools.moordyn_system.point_water_velocity), so that the comparison is of the coupled
# dynamics of the same loads (the load itself is checked against linear theory by hand in
# src/sim/system_dynamics.rs). Measured: the buoy within 3.1 mm of its 1.45 m heave and 0.78 m sway;
# tensions and forces within 6.1e-4 (extremes) and 5.2e-4 (means) of the largest tension (126 kN).
# Without the handed-in inertia MoorDyn's buoy heaves 0.57 m less and more at its extremes: the
# comparison sees the term.
BUOY_WAVES = study.Airy(8.0, 15.0, direction=30.0, phase=40.0, ramp=15.0)
BUOY_WAVES_POS = 0.02           # m
BUOY_WAVES_TOL = 1.0e-2         # of the largest tension
BUOY_WAVES_MEAN = 1.0e-3


def test_the_subsea_buoy_in_waves_agrees_with_moordyn_short(riser_bin, tmp_path):
    p = study.clump_pair(riser_bin, tmp_path, 22, motions=(), duration=60.0, window=SHORT_WINDOW, threads=2,
                         case=ROOT / "docs" / "cases" / "subsea_buoy_mooring.toml",
                         points="cd_area = 7.4\nca = 0.5\n", waves=BUOY_WAVES)
    rows = study.clump_rows(p, SHORT_WINDOW)
    for r in rows:
        print(f"{r['quantity']:24s} {r['stat']:5s} riser {r['riser']:12.5g} MoorDyn {r['md']:12.5g} "
              f"diff {r['diff']:+.3e}")
    # the waves move the buoy (the vessel is held)
    late = p.riser["t"] >= SHORT_WINDOW[0]
    swing = max(np.ptp(p.riser[f"buoy.{c}"][late]) for c in "xyz")
    assert swing > 0.5, swing
    _clump_checks(rows, BUOY_WAVES_POS, BUOY_WAVES_TOL, BUOY_WAVES_MEAN)
