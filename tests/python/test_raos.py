"""One sea, and the vessel moving with it (issue 50; docs/guide/waves.md "One sea",
docs/guide/sweeps.md "The vessel on its RAOs").

- A vessel model reading the components table `riser waves --out` exports sees the sea riser's
  FMU realises: the FMU's `wave_elevation` (at the phase origin, ramped) equals the table evaluated
  here with numpy, r(t) sum a cos(-2 pi f t + phase), to 1e-9 m at every communication point.
- riser-sweep's `[motion] raos`: the FMU's inputs of a case (recorded by fmpy) are the vessel's
  motion on its RAOs in that case's sea, against the closed form r(t) A |RAO| cos(theta + phase)
  of a regular wave, theta at the reference point (deep water, k = omega^2/g), to 1e-9.
"""

import math
import os
import subprocess

import numpy as np
from fmpy import simulate_fmu


def _table(path):
    rows = [line for line in open(path) if not line.startswith("#")]
    assert rows[0].strip() == "frequency,amplitude,phase,direction"
    return np.array([[float(x) for x in r.split(",")] for r in rows[1:]])


def test_the_fmu_and_a_vessel_model_reading_the_table_see_one_sea(fmu_path, riser_bin, tmp_path):
    out = tmp_path / "sea"
    sets = ["--set", "wave_kind=jonswap", "--set", "wave_hs=3", "--set", "wave_tp=9", "--set", "wave_seed=11"]
    p = subprocess.run([riser_bin, "waves", "catenary", *sets, "--duration", "30", "--out", str(out)],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    table = _table(out / "components.csv")
    assert len(table) == 100
    ramp = 9.0  # the table holds no ramp: the FMU's given (riser waves' default, Tp)
    res = simulate_fmu(fmu_path, stop_time=20.0, output_interval=0.1, output=["wave_elevation"],
                       start_values={"scene": "catenary", "wave_kind": "table", "wave_ramp": ramp,
                                     "wave_file": str(out / "components.csv"), "n_elements": 10,
                                     "time_step": 0.1})
    t = res["time"]
    f, a, ph = table[:, 0], table[:, 1], np.deg2rad(table[:, 2])
    # the vessel model's sea at the phase origin (0, 0): the table's formula, the ramp of the run
    eta = (a[None, :] * np.cos(-2 * np.pi * f[None, :] * t[:, None] + ph[None, :])).sum(axis=1)
    r = np.where(t < ramp, 0.5 * (1 - np.cos(np.pi * t / ramp)), 1.0)
    worst = float(np.max(np.abs(res["wave_elevation"] - r * eta)))
    print(f"FMU wave_elevation against the exported table: largest difference {worst:.2e} m")
    assert worst < 1e-9
    assert float(np.max(np.abs(eta))) > 1.0  # a sea, not still water


def test_a_sweep_moves_the_vessel_on_its_raos_in_the_cases_sea(fmu_path, riser_bin, tmp_path, monkeypatch):
    from riser_sweep.case import run_case
    from riser_sweep.spec import load_spec

    monkeypatch.setenv("RISER_BIN", riser_bin)
    (tmp_path / "raos.csv").write_text("dof,frequency,direction,amplitude,phase\n"
                                       "heave,0.1,0,0.8,-30\nheave,0.125,0,0.5,-70\n"
                                       "pitch,0.1,0,0.01,100\npitch,0.125,0,0.02,60\n")
    spec = tmp_path / "spec.toml"
    spec.write_text(f"""fmu = "{fmu_path}"
scene = "catenary"
[parameters]
n_elements = 10
time_step = 0.1
wave_kind = "airy"
wave_height = 2.0
wave_ramp = 5.0
hang_off_x = 12.0
[motion]
raos = "raos.csv"
[run]
duration = 16.0
communication_step = 0.1
[grid]
wave_period = [10.0, 8.0]
""")
    s = load_spec(spec)
    assert len(s.cases) == 2
    from fmpy import extract

    unzip = extract(fmu_path, unzipdir=str(tmp_path / "fmu"))
    g = 9.81
    for case in s.cases:
        job = s.job(case)
        assert not job["vessel_error"], job["vessel_error"]
        job["record"] = list(job["record"]) + ["heave", "pitch", "surge", "heave_velocity"]
        job["timeseries"] = True
        res = run_case(unzip, job)
        assert res["status"] == "ok", res["error"]
        ts = res["timeseries"]
        period = case.as_dict()["wave_period"]
        w = 2 * math.pi / period
        k = w * w / g
        f = 1 / period
        u = (f - 0.1) / 0.025
        heave = ((1 - u) * 0.8 + u * 0.5, (1 - u) * -30 + u * -70)
        pitch = ((1 - u) * 0.01 + u * 0.02, (1 - u) * 100 + u * 60)
        t = ts["time"]
        r = np.where(t < 5.0, 0.5 * (1 - np.cos(np.pi * t / 5.0)), 1.0)
        theta = k * (-12.0) - w * t  # the reference point at (-12, 0), beta 0, phase 0
        for name, (amp, ph) in (("heave", heave), ("pitch", pitch)):
            want = r * 1.0 * amp * np.cos(theta + np.deg2rad(ph))
            # fmpy records an input after the step it was applied to: the value at t_k is the one set at t_(k-1)
            worst = float(np.max(np.abs(ts[name][1:] - want[:-1])))
            print(f"T = {period} s: the FMU's {name} input against the closed form, {worst:.2e}")
            assert worst < 1e-9
        assert float(np.max(np.abs(ts["surge"]))) == 0.0
        # the window waits for the sea: its ramp plus its period
        assert job["window"] == (5.0 + period, 16.0)
