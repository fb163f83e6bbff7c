"""A 3-hour sea state (issue 50, evidence 5; docs/guide/waves.md): a JONSWAP sea of
Hs 4 m, Tp 10 s realised over the design duration of 10,800 s by `riser waves --out`.

With the default 100 components, equally spaced over [0.5/Tp, 4/Tp], the sea repeats every
1/Δf = 285.7 s: riser warns with the repeat period and the components a record of that length
needs, and the envelope of the record's autocorrelation is 1 again at the repeat period (every
component turned by the same phase, 2π f_min/Δf + π: what the warning says). With the components the warning names (Δf = 1/duration), nothing is said, and the record
is a sea state: its Hs = 4 √m0 of the elevation within 2 % of the spectrum's, and its
autocorrelation below 0.1 at every lag beyond 60 s (for deterministic amplitudes at the bins'
centres with Δf = 1/T, the record's circular autocorrelation is the spectrum's own, sampled;
JONSWAP's envelope at Tp = 10 s is 0.03 at 60 s)."""
import re
import subprocess

import numpy as np

HOURS3 = 10800.0
SEA = ["--set", "wave_kind=jonswap", "--set", "wave_hs=4", "--set", "wave_tp=10"]


def record(riser_bin, tmp_path, extra):
    out = tmp_path / "sea"
    r = subprocess.run([riser_bin, "waves", "catenary", *SEA, *extra, "--duration", str(HOURS3), "--step", "0.5",
                        "--out", str(out)], capture_output=True, text=True, check=True)
    e = np.loadtxt(out / "elevation.csv", delimiter=",", skiprows=1)
    return r.stderr, e[:, 0], e[:, 1]


def autocorrelation(x):
    """The record's circular autocorrelation, lag 0 to len/2 (its mean removed): for a sea of
    Δf = 1/T the components are orthogonal over the record and this is the spectrum's own."""
    x = x - x.mean()
    r = np.fft.irfft(np.abs(np.fft.rfft(x)) ** 2, n=len(x))
    return r[: len(x) // 2] / r[0]


def envelope_autocorrelation(x):
    """The envelope of the record's autocorrelation (the modulus of the analytic signal's), over
    the overlap at each lag (no wrap-around), lag 0 to len/2."""
    n = len(x)
    z = np.fft.fft(x - x.mean(), 2 * n)
    z[n + 1:] = 0.0
    z[1:n] *= 2.0
    a = np.fft.ifft(z)  # the analytic signal, zero-padded
    r = np.abs(np.fft.ifft(np.abs(np.fft.fft(a)) ** 2))[: n // 2] / (n - np.arange(n // 2))
    return r / r[0]


def test_a_three_hour_sea_does_not_repeat_with_the_components_the_warning_names(riser_bin, tmp_path):
    said, t, eta = record(riser_bin, tmp_path, [])
    m = re.search(r"repeat every ([0-9.]+) s .* set wave_components to at least (\d+)", said)
    assert m, said
    period, needed = float(m.group(1)), int(m.group(2))
    dt = t[1] - t[0]
    # the default sea repeats: its autocorrelation's envelope is 1 again at the period it names
    envelope = envelope_autocorrelation(eta[:-1])
    k = int(round(period / dt))
    print(f"100 components: the warning's period {period} s, the autocorrelation's envelope there "
          f"{envelope[k]:.4f}; needs {needed}")
    assert envelope[k] > 0.99
    # the components the warning names: no warning, the record a 3-hour sea state
    said, t, eta = record(riser_bin, tmp_path, ["--set", f"wave_components={needed}"])
    assert "repeat" not in said, said
    dt = t[1] - t[0]
    rho = autocorrelation(eta[:-1])
    lag60 = int(np.ceil(60.0 / dt))
    worst = int(np.argmax(np.abs(rho[lag60:]))) + lag60
    hs = 4.0 * np.std(eta)
    print(f"{needed} components over {t[-1]:.0f} s: Hs {hs:.4f} m from the record (spectrum 4 m), "
          f"autocorrelation beyond 60 s at most {abs(rho[worst]):.4f} (lag {worst * dt:.1f} s)")
    assert abs(hs / 4.0 - 1.0) < 0.02
    assert abs(rho[worst]) < 0.1
