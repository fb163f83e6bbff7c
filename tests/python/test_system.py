"""A system of lines on one vessel against MoorPy (issue 49: statics, with and
without free points; docs/guide/systems.md, docs/theory.md §17).

The OC3-Hywind spar's mooring (docs/cases/oc3_hywind_mooring.toml) built in
MoorPy 1.3.0 (requirements-peers.txt) from the same file: its points, line
type and lines, a coupled body at the reference point, seabed friction 0
(cb = 0) in both. riser's chains are cables of 100 elements each on a
penalty seabed (kBot 3e6 Pa/m, 2.6 mm of penetration under the chain);
MoorPy's are the closed-form elastic catenary on a rigid seabed. What
differs is riser's discretisation (O(h²) in the element length, 9 m) and its
seabed's compliance: measured, the tensions within 3e-5, the force and
moment within 2e-4, the 6×6 within 1e-3 of each block's largest entry; held
to the contract's 0.5 % (forces, tensions), 1 % (translation blocks) and
2 % (rotation blocks).

Free points (issue 49 point 2, statics): a clump weight between two chains
(docs/cases/clump_weight_mooring.toml), a subsea buoy between a chain and a
rope (subsea_buoy_mooring.toml) and a bridle joining three chains
(bridle_mooring.toml) against MoorPy's free points (Point type 0, its mass
and volume; `solveEquilibrium` to 1e-6 m, its default 0.05 m tolerance being
too loose for the comparison), the same lines, seabed friction 0, the free
points more than MoorPy's 2 m (`zTol`) above the seabed and fully submerged,
where both models' point loads are the weight and the full buoyancy. Held
to the contract's 0.1 m (positions) and 0.5 % (tensions; the force on the
vessel too), the 6x6 condensed on the free points against MoorPy's
`getCoupledStiffnessA` (its Guyan reduction) to 1 % (translation blocks)
and 2 % (rotation blocks).
"""

import json
import math
import subprocess
import tomllib

import numpy as np
import pytest

from conftest import ROOT

mp = pytest.importorskip("moorpy")

SCENE = ROOT / "docs" / "cases" / "oc3_hywind_mooring.toml"


def moorpy_system(scene):
    """MoorPy's system of `scene` (fixed and vessel points only)."""
    assert all(p["kind"] in ("fixed", "vessel") for p in scene["point"])
    return moorpy_free_system(scene)[0]


def moorpy_at(ms, pose):
    ms.bodyList[0].setPosition(np.array(pose, dtype=float))
    ms.solveEquilibrium()
    f6 = ms.bodyList[0].getForces(lines_only=True)
    tensions = [(line.TA, line.TB) for line in ms.lineList]
    return f6, tensions


def riser_at(riser_bin, pose):
    out = subprocess.run([riser_bin, "statics", str(SCENE), "--json", "--pose", ",".join(map(str, pose))],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def block_errors(k, ref):
    errs = {}
    for name, (r, c) in {"FF": (0, 0), "FM": (0, 3), "MF": (3, 0), "MM": (3, 3)}.items():
        kb, rb = k[r:r + 3, c:c + 3], ref[r:r + 3, c:c + 3]
        errs[name] = float(np.abs(kb - rb).max() / np.abs(rb).max())
    return errs


@pytest.fixture(scope="module")
def scene():
    with open(SCENE, "rb") as f:
        return tomllib.load(f)


POSES = [[0, 0, 0, 0, 0, 0], [10, 0, 0, 0, 0, 0], [-6, 8, 2, 0, 0, 0]]


@pytest.mark.parametrize("pose", POSES)
def test_forces_and_tensions_against_moorpy(riser_bin, scene, pose):
    ms = moorpy_system(scene)
    f6, tensions = moorpy_at(ms, pose)
    r = riser_at(riser_bin, pose)
    f = np.array(r["top_force"] + r["top_moment"])
    scale_f, scale_m = np.abs(f6[:3]).max(), np.abs(f6[3:]).max()
    err_f = np.abs(f[:3] - f6[:3]).max() / scale_f
    err_m = np.abs(f[3:] - f6[3:]).max() / max(scale_m, scale_f * 5.2)
    print(f"pose {pose}: force {f[:3]} vs {f6[:3]} ({err_f:.1e}), moment {f[3:]} vs {f6[3:]} ({err_m:.1e})")
    assert err_f < 5e-3 and err_m < 5e-3
    for row, (ta, tb) in zip(r["lines"], tensions):
        e = max(abs(row["tension_from"] / ta - 1), abs(row["tension_to"] / tb - 1))
        print(f"  {row['name']}: from {row['tension_from']:.1f} vs {ta:.1f}, to {row['tension_to']:.1f} vs {tb:.1f} ({e:.1e})")
        assert e < 5e-3


def test_surge_offset_of_10_m_restores_as_moorpy(riser_bin, scene):
    ms = moorpy_system(scene)
    f6, _ = moorpy_at(ms, [10, 0, 0, 0, 0, 0])
    r = riser_at(riser_bin, [10, 0, 0, 0, 0, 0])
    print(f"restoring force at 10 m surge: riser {r['top_force'][0]:.1f} N, MoorPy {f6[0]:.1f} N")
    assert abs(r["top_force"][0] / f6[0] - 1) < 5e-3


@pytest.mark.parametrize("pose", [[0, 0, 0, 0, 0, 0], [10, 0, 0, 0, 0, 0], [-6, 8, 2, 0, 0, 0]])
def test_stiffness_against_moorpy(riser_bin, scene, pose):
    ms = moorpy_system(scene)
    moorpy_at(ms, pose)
    ka = ms.getCoupledStiffnessA(lines_only=True)
    k = np.array(riser_at(riser_bin, pose)["stiffness"])
    errs = block_errors(k, ka)
    np.set_printoptions(precision=6, linewidth=200)
    print(f"pose {pose}: block errors {errs}\nriser\n{k}\nMoorPy getCoupledStiffnessA\n{ka}")
    assert errs["FF"] < 1e-2 and errs["FM"] < 1e-2 and errs["MF"] < 1e-2, errs
    assert errs["MM"] < 2e-2, errs
    if pose == [0, 0, 0, 0, 0, 0]:
        # the contract's published surge stiffness, and MoorPy's
        assert abs(k[0, 0] / 41180.0 - 1) < 2e-3, k[0, 0]
        assert abs(k[0, 0] / ka[0, 0] - 1) < 2e-3, (k[0, 0], ka[0, 0])


def test_the_guide_shows_the_case_file():
    """docs/guide/systems.md's `oc3.toml` block is docs/cases/oc3_hywind_mooring.toml, character for character."""
    page = (ROOT / "docs" / "guide" / "systems.md").read_text()
    block = page.split("```toml guide-file: oc3.toml\n", 1)[1].split("\n```\n", 1)[0] + "\n"
    assert block == SCENE.read_text()


CASES = ROOT / "docs" / "cases"
FREE_CASES = ["clump_weight_mooring", "subsea_buoy_mooring", "bridle_mooring"]


def load_case(name):
    with open(CASES / f"{name}.toml", "rb") as f:
        return tomllib.load(f)


def moorpy_free_system(scene):
    """MoorPy's system of `scene`: fixed, vessel (on a coupled body at the
    reference point) and free points (type 0, mass and volume), its lines."""
    env = scene["environment"]
    rho, g = env["water_density"], env["gravity"]
    ms = mp.System(depth=-scene["seabed"]["z"], rho=rho, g=g)
    for t in scene["line_type"]:
        d, m = t["outer_diameter"], t["mass_per_length"]
        w = (m - rho * math.pi / 4 * d * d) * g
        ms.setLineType(dnommm=d * 1000, material=None, name=t["name"], mass=m, d_vol=d, w=w,
                       EA=t["axial_stiffness"])
    ms.addBody(-1, [0, 0, 0, 0, 0, 0])
    number = {}
    for p in scene["point"]:
        if p["kind"] == "fixed":
            ms.addPoint(1, p["position"])
        elif p["kind"] == "vessel":
            ms.addPoint(1, p["position"], body=1)
        else:
            ms.addPoint(0, p["position"], m=p.get("mass", 0.0), v=p.get("volume", 0.0))
        number[p["name"]] = len(ms.pointList)
    for line in scene["line"]:
        ms.addLine(line["length"], line["type"], nSegs=40, pointA=number[line["from"]],
                   pointB=number[line["to"]], cb=0.0)
    ms.initialize()
    return ms, number


def moorpy_free_at(ms, pose):
    ms.bodyList[0].setPosition(np.array(pose, dtype=float))
    ms.solveEquilibrium(tol=1e-6, maxIter=2000)
    return ms.bodyList[0].getForces(lines_only=True)


def riser_case_at(riser_bin, name, pose):
    out = subprocess.run([riser_bin, "statics", str(CASES / f"{name}.toml"), "--json", "--pose",
                          ",".join(map(str, pose))], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


FREE_POSES = [[0, 0, 0, 0, 0, 0], [8, 3, 1, 0.02, -0.03, 0.05]]


@pytest.mark.parametrize("name", FREE_CASES)
@pytest.mark.parametrize("pose", FREE_POSES)
def test_free_points_against_moorpy(riser_bin, name, pose):
    scene = load_case(name)
    ms, number = moorpy_free_system(scene)
    f6 = moorpy_free_at(ms, pose)
    r = riser_case_at(riser_bin, name, pose)
    for row in r["points"]:
        ref = ms.pointList[number[row["name"]] - 1].r
        d = float(np.linalg.norm(np.array(row["position"]) - ref))
        print(f"{name} {pose}: point {row['name']} at {np.round(row['position'], 4)} vs MoorPy {np.round(ref, 4)}: {d:.4f} m")
        assert d < 0.1
        # where MoorPy's and riser's point loads are the same: submerged, clear of the seabed
        assert ref[2] < -1.0 and ref[2] > -scene["seabed"]["z"] * -1 + 2.0
    for row, line in zip(r["lines"], ms.lineList):
        e = max(abs(row["tension_from"] / line.TA - 1), abs(row["tension_to"] / line.TB - 1))
        print(f"  {row['name']}: from {row['tension_from']:.1f} vs {line.TA:.1f}, to {row['tension_to']:.1f} vs {line.TB:.1f} ({e:.1e})")
        assert e < 5e-3
    f = np.array(r["top_force"] + r["top_moment"])
    scale = np.abs(f6[:3]).max()
    err_f = np.abs(f[:3] - f6[:3]).max() / scale
    err_m = np.abs(f[3:] - f6[3:]).max() / max(np.abs(f6[3:]).max(), scale * 10.0)
    print(f"  force {f[:3]} vs {f6[:3]} ({err_f:.1e}), moment {f[3:]} vs {f6[3:]} ({err_m:.1e})")
    assert err_f < 5e-3 and err_m < 5e-3


@pytest.mark.parametrize("name", FREE_CASES)
def test_condensed_stiffness_against_moorpy(riser_bin, name):
    scene = load_case(name)
    ms, _ = moorpy_free_system(scene)
    moorpy_free_at(ms, [0, 0, 0, 0, 0, 0])
    ka = ms.getCoupledStiffnessA(lines_only=True)
    k = np.array(riser_case_at(riser_bin, name, [0, 0, 0, 0, 0, 0])["stiffness"])
    errs = block_errors(k, ka)
    np.set_printoptions(precision=6, linewidth=200)
    print(f"{name}: block errors {errs}\nriser\n{k}\nMoorPy getCoupledStiffnessA\n{ka}")
    assert errs["FF"] < 1e-2 and errs["FM"] < 1e-2 and errs["MF"] < 1e-2, errs
    assert errs["MM"] < 2e-2, errs
