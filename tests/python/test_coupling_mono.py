"""Two-way coupling against the monolithic reference (issue 53; docs/coupling.md "Against the
monolithic reference", docs/theory.md §7.9): a body in heave and pitch with the hang-off at its
lever, coupled to riser's FMU in libcosim's fixed step (osp/vessel/Vessel6.py with its other degrees
of freedom held; riser given the body's mass and inertias, `vessel_mass_*`, `vessel_inertia_*`; no
filter), against the same body integrated inside riser's own step (examples/monolithic_body.rs,
riser::sim::monolithic). riser, given the body's inertias, also takes the body's answer to the line's
force beyond the held one inside its own steps (docs/theory.md §7.10). References: the monolithic run (converged: its window within 4e-6 between
0.05 s and 0.01 s, tests/it/monolithic_body.rs for its own checks) and the body alone's closed form.

What the ports exchange: riser's `work_top` (the vessel's work on the line) against minus the vessel's
`work` (riser's held force on the vessel's displacement). With the force held over each step the two
differ by the work of the force's change within the step, ∫(F − F_n)·v dt, first order in h: the
largest |work_top + work| is 6.2e-5, 1.3e-4, 2.6e-4, 1.9e-3 of the energy exchanged (the vessel's
`work_magnitude`) at 0.05, 0.1, 0.2, 0.5 s for the vessel over 300 s, 1.5e-4, 3.7e-4 and 9.3e-5 for
the buoy at 0.05, 0.1 and 0.5 s: up to 3.7e-3 h/s; held to 5e-3 h/s."""
from pathlib import Path

import numpy as np
import pytest
from riser_tools import coupling_mono as cm
from riser_tools.coupling_loop import build_vessel_fmu


@pytest.fixture(scope="module")
def vessel6_fmu(tmp_path_factory):
    return build_vessel_fmu(tmp_path_factory.mktemp("vessel6"), "Vessel6")


@pytest.fixture(scope="module")
def exe(riser_bin):
    """examples/monolithic_body of the same build as the riser CLI (`cargo test` builds the examples)."""
    p = Path(riser_bin).parent / "examples" / "monolithic_body"
    if not p.exists():
        pytest.skip(f"build the example first: cargo build --example monolithic_body ({p})")
    return str(p)


def check(case, h, duration, window, fmu_path, vessel6_fmu, ref, tolerance=0.01):
    two = cm.two_way(case, h, duration, fmu_path, vessel6_fmu)
    c = cm.compare(two, ref, duration - window)
    print(f"{case.name}, h {h}: " + ", ".join(f"{k} {v:.3e}" for k, v in c.items()))
    for k in ("tension min", "tension max", "heave", "pitch"):
        if np.isfinite(c[k]):
            assert abs(c[k]) <= tolerance, (k, c[k])
    assert c["energy"] <= 5e-3 * h, c["energy"]
    return c


@pytest.fixture(scope="module")
def short_reference(exe):
    return cm.monolithic(cm.VESSEL_2000T, 0.05, 100.0, exe)


def test_the_2000_t_vessel_at_a_30_m_lever_at_0_1_s_is_the_monolithic_reference_within_1_percent(
        fmu_path, vessel6_fmu, short_reference):
    # 100 s (the ramp 20 s), window 60–100 s, the reference at 0.05 s (riser's internal step in the
    # loop; within 4e-6 of the 0.01 s reference's window). Measured at 0.1 s, where the held force's
    # lag rang the line's axial mode (1.1 % over 300 s before §7.10): tension within 2.3e-5, heave
    # 1.5e-4, pitch 2.4e-4; the ports' energy within 1.3e-4 of the energy exchanged (the other steps
    # and the buoy: the long tests below)
    check(cm.VESSEL_2000T, 0.1, 100.0, 40.0, fmu_path, vessel6_fmu, short_reference)


@pytest.fixture(scope="module")
def references(exe):
    """The monolithic references at 0.01 s over 300 s, per case (computed once)."""
    return {}


def reference(references, key, exe):
    if key not in references:
        references[key] = cm.monolithic(cm.CASES[key], 0.01, 300.0, exe)
    return references[key]


# measured (docs/coupling.md): with the vessel's answer inside riser's steps (§7.10) the vessel is
# within 1 % at every step (before: 1.1 % at 0.1 s, the line's axial mode ringing at 3.85 Hz); the
# buoy at 0.05, 0.1 and 0.5 s too (before: unstable, or its heave 84 % high at 0.5 s); at 0.2 s it rang
# (tension ±42 %, heave 11 % high, a strict xfail) until the middle steps' design (7.3b) of session 17:
# tension −0.44 % / +0.37 %, heave −0.60 %
MISS: dict = {}


@pytest.mark.long
@pytest.mark.parametrize("key,h", [pytest.param(k, h, marks=pytest.mark.xfail(strict=True, reason=MISS[(k, h)]))
                                   if (k, h) in MISS else (k, h)
                                   for k in ("vessel", "buoy") for h in (0.05, 0.1, 0.2, 0.5)])
def test_the_vessel_and_the_buoy_two_way_against_the_monolithic_reference_over_300_s(
        fmu_path, vessel6_fmu, exe, references, key, h):
    check(cm.CASES[key], h, 300.0, 100.0, fmu_path, vessel6_fmu, reference(references, key, exe))


@pytest.mark.long
def test_the_line_changes_the_buoy_s_heave_by_more_than_5_percent(exe, references):
    # the body alone: |X| = F / |C − (M + A) ω² + i B ω| = 0.2811 m in the 10 s wave; on the line
    # (monolithic, 200–300 s) 0.30225 m: the line changes the buoy's motion by 7.5 % (the 2,000 t
    # vessel's by 0.08 %: 0.28540 m against 0.28564 m)
    for key, lo, hi in (("buoy", 0.05, 1.0), ("vessel", 0.0, 1e-3)):
        case = cm.CASES[key]
        w = 2 * np.pi / case.period
        alone = case.excitation[0] / abs(case.stiffness[0] - case.mass * w**2 + 1j * case.damping[0] * w)
        ref = reference(references, key, exe)
        amp = np.ptp(ref["heave"][ref["t"] >= 200.0]) / 2
        print(f"{case.name}: heave {amp:.5f} m on the line, {alone:.5f} m alone ({amp / alone - 1:+.2%})")
        assert lo <= abs(amp / alone - 1) <= hi
