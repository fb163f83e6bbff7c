"""Candidate end-state filters of the FMU's input path at uniform steps (docs/theory.md §7.1-7.3,
issues 51 and 53), judged without the line on the filter-level measures the split-step defect and
the coupling loops depend on.

A design is W (3 × N): the step's end state (value, h slope, h² curvature) = W @ samples (newest
first), the path the quintic Hermite (7.2) between successive end states. Measures, per step h:

* ``end``: the steady end value's error on a sine at 10 s, |E_0(θ) − e^{iθ}| (per unit amplitude);
* ``inside``: the path's acceleration error inside the steps on the same sine, / (A ω²) (what a line
  stepped inside the communication step sees; tests/it/input_path_interior.rs measures the FMU's);
* ``kink``: the path's largest acceleration error (m/s²) after a jerk jump of 0.23 m/s³ (the test
  heave's ramp end at 10 s: u = J/6 (t − t0)₊³), and ``ring``: that error's Fourier amplitude
  |∫ a_err e^{−iωt} dt| (m/s) at the worst frequency of the steel catenary's axial modes
  (2.0-2.6 Hz), against the kink's own J/ω² (``ring`` is in units of it);
* ``noise``: the end state's RMS answer per unit of white sampled noise (√Σ w², value and h² curv.);
* ``onset``: the catenary's top force swing (kN) when a ±1e-5 m alternation starts mid-run
  (riser_tools.coupling_analysis.onset_swing, the measured line of docs/coupling_response.csv);
* ``proxy``: max |L(θ)| over θ ∈ [0.35, 0.45] π for the 2000 t vessel (7.9), which told the libcosim
  vessel loop at 0.2 s apart in session 16 (stable 0.46-0.47, growing 0.57 and 0.79), and ``gain``
  the same over θ ≥ π/2.

    python -m riser_tools.studies.input_path_designs [--h 0.1,0.15,0.2,0.25]
"""
from __future__ import annotations

import argparse
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import coupling_analysis as ca

A, PERIOD = 2.5, 10.0
JERK = 0.23  # m/s³: the jerk jump where the test heave's ramp ends (and at its start)
MODES = (2.0, 2.6)  # Hz: the steel catenary's lightly damped axial modes (session 16)
PROXY = (0.35, 0.45)


def band_matrix(n: int, a: float) -> np.ndarray:
    """B_ij = (1/(π − a)) ∫_a^π cos((i − j)θ) dθ (a in radians), 1e-9 on the diagonal."""
    m = np.abs(np.subtract.outer(np.arange(n), np.arange(n))).astype(float)
    with np.errstate(divide="ignore", invalid="ignore"):
        b = np.where(m == 0, 1.0, -np.sin(a * m) / (m * (np.pi - a)))
    return b + 1e-9 * np.eye(n)


def constrained_least_energy(b: np.ndarray, rows, rhs) -> np.ndarray:
    """min wᵀ B w subject to C w = d (the KKT system, one step of refinement)."""
    n = len(b)
    c, d = np.array(rows, dtype=float), np.array(rhs, dtype=float)
    k = np.block([[2 * b, c.T], [c, np.zeros((len(d), len(d)))]])
    f = np.concatenate([np.zeros(n), d])
    x = np.linalg.solve(k, f)
    x = x + np.linalg.solve(k, f - k @ x)
    return x[:n]


def band_value(taps: int, degree: int, alt: int, band: float) -> np.ndarray:
    """The value row: exact one step ahead for polynomials of degree ≤ `degree`, the alternations
    (−1)^k ξ^q (q < alt) removed, least energy in θ ∈ [band π, π]."""
    xi = -np.arange(taps) / (taps - 1.0)
    one = 1.0 / (taps - 1.0)
    rows = [xi ** p for p in range(degree + 1)] + [(-1.0) ** np.arange(taps) * xi ** q for q in range(alt)]
    rhs = [one ** p for p in range(degree + 1)] + [0.0] * alt
    return constrained_least_energy(band_matrix(taps, band * np.pi), rows, rhs)


def rates(w0: np.ndarray, taps: int, degree: int, alt: int, band: float) -> np.ndarray:
    """(7.3a): the slope and curvature rows over `taps` samples of the end values' sequence
    Σ w0_k u(t − k h), exact for degree ≤ `degree`, alternations removed, least energy in the band."""
    w0 = np.concatenate([w0, np.zeros(max(0, taps - len(w0)))])
    n = max(taps, len(w0))
    scale = taps - 1.0
    xi = -np.arange(n) / scale
    b = band_matrix(taps, band * np.pi)
    out = np.zeros((3, n))
    out[0] = w0
    for r in (1, 2):
        rows, rhs = [], []
        for q in range(degree + 1):
            rows.append(xi[:taps] ** q)
            falling = np.prod([q - k for k in range(r)]) if q >= r else 0.0
            rhs.append(falling / scale ** r * (w0 @ xi ** (q - r)) if q >= r else 0.0)
        for q in range(alt):
            rows.append((-1.0) ** np.arange(taps) * xi[:taps] ** q)
            rhs.append(0.0)
        out[r, :taps] = constrained_least_energy(b, rows, rhs)
    return out


def least_squares_value(poly: int, alt: int, taps: int) -> np.ndarray:
    return ca.predictor_weights(ca.Predictor("", poly, alt, taps))[0]


@dataclass
class Candidate:
    name: str
    w: np.ndarray  # 3 × N


def today() -> Candidate:
    """The middle steps' design before (7.3b) (session 16): the 12-point least-squares quartic with
    two nuisances, the slope and curvature of (7.3a) over 16 samples (degree 6, band from 0.2 π)."""
    return Candidate("before: LS 12 pts, 2 nuis. + (7.3a) m16 d6 a0.2",
                     ca.consistent_weights(ca.DESIGNS[1][1], *ca.CONSISTENT_BEFORE[1]))


def long_steps() -> Candidate:
    return Candidate("6 pts exact + (7.3a) m10 d7 a0.5", ca.consistent_weights(ca.DESIGNS[2][1], *ca.CONSISTENT[2]))


def hermite_second():
    """d²/dσ² of H0, H1, H2 as numpy polynomials (σ)."""
    P = np.polynomial.Polynomial
    h0 = P([1, 0, 0, -10, 15, -6])
    h1 = P([0, 1, 0, -6, 8, -3])
    h2 = P([0, 0, 0.5, -1.5, 1.5, -0.5])
    return h0, h1, h2


H0, H1, H2 = hermite_second()


def path_acceleration(e: np.ndarray, h: float, sub: int = 16):
    """The path's acceleration on (t_n, t_n + h], n ≥ 1, between end states e[n−1] → e[n]
    (rows (value, h slope, h² curvature)); returns (σ offsets, acc[n, s])."""
    s = np.arange(1, sub + 1) / sub
    d2 = lambda p, x: p.deriv(2)(x)  # noqa: E731
    start = e[:-1]
    end = e[1:]
    acc = (np.outer(start[:, 0], d2(H0, s)) + np.outer(start[:, 1], d2(H1, s)) + np.outer(start[:, 2], d2(H2, s))
           + np.outer(end[:, 0], d2(H0, 1 - s)) - np.outer(end[:, 1], d2(H1, 1 - s))
           + np.outer(end[:, 2], d2(H2, 1 - s))) / h ** 2
    return s, acc


def end_states(w: np.ndarray, u: np.ndarray) -> np.ndarray:
    """e[n] = W @ (u[n], u[n−1], ...): the end state at t_n + h of the step from t_n, for n ≥ N − 1
    (earlier rows NaN); the path over step n runs from e[n − 1] to e[n]."""
    n = w.shape[1]
    e = np.full((len(u), 3), np.nan)
    for j in range(3):
        c = np.convolve(u, w[j])[: len(u)]
        e[n - 1:, j] = c[n - 1:]
    return e


def sine_measures(w: np.ndarray, h: float):
    om = 2 * np.pi / PERIOD
    theta = om * h
    end = abs(ca.end_state_response(w, theta)[0, 0] - np.exp(1j * theta))
    n = int(round(4 * PERIOD / h)) + w.shape[1]
    t = np.arange(n) * h
    u = A * np.sin(om * t)
    e = end_states(w, u)[w.shape[1]:]
    tt = t[w.shape[1]:]
    s, acc = path_acceleration(e, h)
    exact = -A * om ** 2 * np.sin(om * (tt[1:, None] + s[None, :] * h))
    return end, float(np.abs(acc - exact).max() / (A * om ** 2))


def kink_measures(w: np.ndarray, h: float, sub: int = 32):
    n0 = w.shape[1] + 5
    n = n0 + int(round(20.0 / h))
    t = (np.arange(n) - n0) * h  # the kink at t = 0, a sample
    u = JERK / 6 * np.clip(t, 0, None) ** 3
    e = end_states(w, u)[w.shape[1]:]
    tt = t[w.shape[1]:]
    s, acc = path_acceleration(e, h, sub)
    tc = tt[1:, None] + s[None, :] * h
    err = (acc - JERK * np.clip(tc, 0, None)).ravel()
    tc = tc.ravel()
    dt = h / sub
    freqs = np.linspace(*MODES, 61)
    ring = max(abs(np.sum(err * np.exp(-2j * np.pi * f * tc)) * dt) / (JERK / (2 * np.pi * f) ** 2) for f in freqs)
    return float(np.abs(err).max()), float(ring)


def coupling_measures(w: np.ndarray, h: float, resp):
    g = resp.get(h)
    if g is None:
        return np.nan, np.nan, np.nan
    r = ca.riser_fir(g, w)
    gain = ca.loop_gain(ca.VESSEL, h, r)
    theta = np.linspace(np.pi / 2000, np.pi, 2000) / np.pi
    proxy = float(gain[(theta >= PROXY[0]) & (theta <= PROXY[1])].max())
    return proxy, float(gain[ca.HIGH_BAND].max()), ca.onset_swing(w, g) / 1e3


def measures(c: Candidate, h: float, resp) -> dict:
    end, inside = sine_measures(c.w, h)
    kink, ring = kink_measures(c.w, h)
    proxy, gain, onset = coupling_measures(c.w, h, resp)
    alt = np.abs(c.w @ (-1.0) ** np.arange(c.w.shape[1])).max()
    noise = np.sqrt((c.w ** 2).sum(axis=1))
    return dict(name=c.name, h=h, taps=c.w.shape[1], end=end, inside=inside, kink=kink, ring=ring, proxy=proxy,
                gain=gain, onset=onset, alt=alt, noise0=noise[0], noise2=noise[2])


# --- joint designs: all three rows at once, a quadratic objective under the exactness constraints --------------

def resonance_band(h: float, f=(3.9, 4.1), n: int = 41) -> np.ndarray:
    """θ (rad) where the line's axial resonance with the hang-off held (about 4 Hz at internal steps of
    0.1-0.2 s, docs/theory.md §7.3) aliases at step h: θ ∈ [0.36, 0.44] π at 0.2 s."""
    th = (2 * np.pi * np.linspace(*f, n) * h) % (2 * np.pi)
    return np.where(th > np.pi, 2 * np.pi - th, th)


def _linear(fun, size):
    """(M, b) with fun(x) = M x − b for a linear-affine fun (complex vectors)."""
    r0 = np.atleast_1d(fun(np.zeros(size)))
    m = np.zeros((len(r0), size), dtype=complex)
    for i in range(size):
        x = np.zeros(size)
        x[i] = 1.0
        m[:, i] = np.atleast_1d(fun(x)) - r0
    return m, -r0


def _interior_residual(w: np.ndarray, h: float) -> np.ndarray:
    """h² (path acceleration − exact) at 8 points of a step on the 10 s sine, per unit amplitude."""
    theta = 2 * np.pi * h / PERIOD
    e = ca.end_state_response(w, theta)[:, 0]
    s = np.arange(1, 9) / 8
    d2 = lambda p, x: p.deriv(2)(x)  # noqa: E731
    start = [d2(H0, s), d2(H1, s), d2(H2, s)]
    end = [d2(H0, 1 - s), -d2(H1, 1 - s), d2(H2, 1 - s)]
    acc = sum(e[j] * (np.exp(-1j * theta) * start[j] + end[j]) for j in range(3))
    return acc + theta ** 2 * np.exp(1j * theta * s)


def _end_residual(w: np.ndarray, h: float) -> np.ndarray:
    """The end value's error on the 10 s sine, E_0(θ) − e^{iθ} (per unit amplitude)."""
    theta = 2 * np.pi * h / PERIOD
    return np.atleast_1d(ca.end_state_response(w, theta)[0, 0] - np.exp(1j * theta))


def _ring_residual(w: np.ndarray, h: float) -> np.ndarray:
    """The kink's path acceleration error's Fourier amplitude at the modes, / (J/ω²)."""
    sub = 16
    n0 = w.shape[1] + 5
    n = n0 + int(round(6.0 / h))
    t = (np.arange(n) - n0) * h
    u = JERK / 6 * np.clip(t, 0, None) ** 3
    e = end_states(w, u)[w.shape[1]:]
    tt = t[w.shape[1]:]
    s, acc = path_acceleration(e, h, sub)
    tc = tt[1:, None] + s[None, :] * h
    err = (acc - JERK * np.clip(tc, 0, None)).ravel()
    tc = tc.ravel()
    freqs = np.linspace(*MODES, 13)
    return np.array([np.sum(err * np.exp(-2j * np.pi * f * tc)) * h / sub / (JERK / (2 * np.pi * f) ** 2)
                     for f in freqs])


def _loop_residual(w: np.ndarray, h: float, g: np.ndarray, band=None) -> np.ndarray:
    """Σ_j G_j(θ) E_j(θ) (N/m) at the aliased resonance, or over θ ∈ band π."""
    th = resonance_band(h, n=11) if band is None else np.linspace(band[0], band[1], 41) * np.pi
    return (ca.line_transfer(g, th) * ca.end_state_response(w, th)).sum(axis=0)


def joint(h: float, taps: int, degree: int, rate_degree: int, alt: int, resp, lam_loop=1.0, lam_acc=1.0,
          lam_ring=0.0, lam_high=1e-6, name=None, loop_band=None, loop_h=None, lam_end=0.0) -> Candidate:
    """The three rows over `taps` samples minimising lam_acc |interior error|² + lam_loop |line × E at
    the aliased resonance / 1e7|² + lam_ring |kink ring|² + lam_high ∫_{π/2}^{π} Σ|E_j|², subject to: the
    value exact one step ahead for degree ≤ `degree`, the rates those of the end values' sequence
    (7.3a) for degree ≤ `rate_degree`, the alternations (−1)^k ξ^q (q < alt) removed from every row."""
    n = taps
    size = 3 * n
    unpack = lambda x: x.reshape(3, n)  # noqa: E731
    # each block's squared residual in units of today's design's at this step (lam 1: as today's weighs)
    # (h may be a list of steps: the blocks of each, summed)
    ref = today().w
    funs = []
    for hk in np.atleast_1d(h):
        funs.append((lam_acc, lambda w, hk=hk: _interior_residual(w, hk)))
        if lam_end > 0:
            funs.append((lam_end, lambda w, hk=hk: _end_residual(w, hk)))
        g = resp.get(float(hk))
        if g is not None and lam_loop > 0 and loop_band is None:
            funs.append((lam_loop, lambda w, hk=hk, g=g: _loop_residual(w, hk, g)))
        if lam_ring > 0:
            funs.append((lam_ring, lambda w, hk=hk: _ring_residual(w, hk)))
    if loop_band is not None:
        # the line's answers at the steps measured (docs/coupling_response.csv), over the band where the
        # axial resonance aliases for the steps the design serves
        for hk in loop_h or np.atleast_1d(h):
            funs.append((lam_loop, lambda w, hk=hk: _loop_residual(w, hk, resp[hk], loop_band)))
    q = np.zeros((size, size))
    lin = np.zeros(size)
    for lam, fun in funs:
        m, b = _linear(lambda x, fun=fun: fun(unpack(x)), size)
        norm = np.linalg.norm(fun(ref)) ** 2
        q += lam * np.real(m.conj().T @ m) / norm
        lin += lam * np.real(m.conj().T @ b) / norm
    hb = band_matrix(n, np.pi / 2)
    for j in range(3):
        q[j * n:(j + 1) * n, j * n:(j + 1) * n] += lam_high * hb
    scale = n - 1.0
    xi = -np.arange(n) / scale
    rows, rhs = [], []
    for p in range(degree + 1):
        r = np.zeros(size)
        r[:n] = xi ** p
        rows.append(r)
        rhs.append((1.0 / scale) ** p)
    for j in (1, 2):
        for p in range(rate_degree + 1):
            r = np.zeros(size)
            r[j * n:(j + 1) * n] = xi ** p
            if p >= j:
                falling = np.prod([p - k for k in range(j)])
                r[:n] -= falling / scale ** j * xi ** (p - j)
            rows.append(r)
            rhs.append(0.0)
    for j in range(3):
        for k in range(alt):
            r = np.zeros(size)
            r[j * n:(j + 1) * n] = (-1.0) ** np.arange(n) * xi ** k
            rows.append(r)
            rhs.append(0.0)
    c, d = np.array(rows), np.array(rhs)
    # the null-space method: x = x_p + Z y satisfies the constraints to round-off whatever the
    # objective's conditioning; y minimises the objective over Z's span
    x_p = np.linalg.lstsq(c, d, rcond=None)[0]
    _, sv, vt = np.linalg.svd(c)
    z = vt[np.sum(sv > 1e-12 * sv[0]):].T
    y = np.linalg.lstsq(z.T @ q @ z, z.T @ (lin - q @ x_p), rcond=1e-14)[0]
    x = x_p + z @ y
    assert np.abs(c @ x - d).max() < 1e-9, np.abs(c @ x - d).max()
    label = name or f"joint N{taps} d{degree}/{rate_degree} q{alt} loop{lam_loop:g} acc{lam_acc:g} ring{lam_ring:g}"
    return Candidate(label, unpack(x[:size]))


# the middle design of src/fmi/input_path.rs (`MIDDLE`, uniform steps 0.075-0.21 s once 16 points are known;
# docs/theory.md (7.3b)): chosen in session 17 from the sweeps above and the FMU runs (docs/input_path_designs.md)
MIDDLE_STEPS = [0.1, 0.15, 0.2]
MIDDLE_SETTINGS = dict(taps=16, degree=4, rate_degree=7, alt=2, lam_loop=30.0, lam_acc=1.0, lam_ring=1.0,
                       lam_high=1e-3, loop_band=(0.18, 1.0), loop_h=MIDDLE_STEPS, lam_end=1.0)


def middle(resp=None) -> Candidate:
    """The middle design's three rows, from the catenary's measured answers (docs/coupling_response.csv)."""
    resp = resp or ca.read_response(ca.ROOT / "docs" / "coupling_response.csv")
    return joint(MIDDLE_STEPS, resp=resp, name="middle (7.3b)", **MIDDLE_SETTINGS)


def rust_table(w: np.ndarray) -> str:
    rows = ",\n".join("    [" + ", ".join(repr(float(x)) for x in row) + "]" for row in w)
    return "pub const MIDDLE: [[f64; TAPS]; 3] = [\n" + rows + ",\n];"


def candidates(resp) -> list[Candidate]:
    """The designs of the page's table: the one before (7.3b), the long steps' exactly determined one
    used at the middle steps, session 16's band-limited 16-tap alternative, a window bounded in time
    (8 points), joint designs of the sweep, and the middle design (7.3b)."""
    out = [today(), long_steps()]
    v = band_value(16, 4, 2, 0.3)
    out.append(Candidate("band value 16 pts d4 a0.3 + rates 16 d8 a0.25 (session 16)", rates(v, 16, 8, 2, 0.25)))
    v = least_squares_value(5, 2, 8)
    out.append(Candidate("LS 8 pts + (7.3a) m8 d5 a0.3 (a window bounded in time)", rates(v, 8, 5, 2, 0.3)))
    out.append(joint(0.2, 12, 4, 6, 2, resp, lam_acc=1, lam_ring=1, lam_high=1e-3,
                     name="joint 12 pts, tuned at 0.2 s alone (c1)"))
    kw = dict(lam_acc=1, lam_ring=1, lam_high=1e-3, loop_h=MIDDLE_STEPS)
    out.append(joint(MIDDLE_STEPS, 16, 4, 6, 2, resp, lam_loop=1, loop_band=(0.22, 1.0),
                     name="joint 16 pts, rates d6, loop 1 (c6)", **kw))
    out.append(joint(MIDDLE_STEPS, 16, 4, 7, 2, resp, lam_loop=10, loop_band=(0.22, 1.0), lam_end=10,
                     name="joint 16 pts, rates d7, loop 10, end 10 (c7)", **kw))
    out.append(middle(resp))
    return out


PAGE_HEAD = """# The input path's design at the middle steps (0.075-0.21 s): the study

Made by `python -m riser_tools.studies.input_path_designs` (riser_tools/studies/input_path_designs.py;
docs/theory.md §7.1, (7.3b)). Filter-level measures of candidate end-state designs (value, h slope, h²
curvature rows over the last N samples) at uniform communication steps h, without the line but for
the catenary's measured answers at the hang-off (docs/coupling_response.csv):

* *end*: the end value's error on a 10 s sine, |E₀(θ) − e^{iθ}| per unit amplitude;
* *inside*: the quintic path's (7.2) acceleration error inside the steps on that sine, / (A ω²);
* *kink*: the path's largest acceleration error (m/s²) after a jerk jump of 0.23 m/s³ (the test
  heave's ramp end); *ring*: that error's Fourier amplitude at 2.0-2.6 Hz (the steel catenary's axial
  modes) in units of the jerk's own J/ω²;
* *noise*: √Σw² of the value row (white sampled noise's gain);
* *onset (kN)*: the catenary's tension swing when a ±1e-5 m alternation starts mid-run (§7.3);
* *proxy*: max |L(θ)| (7.9), the 2000 t vessel, over θ where the line's axial resonance (3.9-4.1 Hz)
  aliases at h (0.36-0.44 π at 0.2 s: session 16 found 0.46-0.47 for loops bounded in libcosim at
  0.2 s, 0.57 and 0.79 for growing ones); *gain*: the same over θ ≥ π/2.
"""


def page(resp) -> list[str]:
    lines = [PAGE_HEAD, "| design | h (s) | N | end | inside / Aω² | kink (m/s²) | ring | noise | onset (kN) | proxy "
             "| gain |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for c in candidates(resp):
        for h in MIDDLE_STEPS:
            m = measures(c, h, resp)
            lines.append(f"| {m['name']} | {h:g} | {m['taps']} | {m['end']:.1e} | {m['inside']:.1e} | {m['kink']:.3f} | "
                         f"{m['ring']:.2f} | {m['noise0']:.1f} | {m['onset']:.2f} | {m['proxy']:.2f} | {m['gain']:.2f} |")
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m riser_tools.studies.input_path_designs", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--response", default=str(ca.ROOT / "docs" / "coupling_response.csv"))
    ap.add_argument("--docs", default=str(ca.ROOT / "docs"))
    ap.add_argument("--rust", action="store_true", help="print the middle design as src/fmi/input_path.rs's MIDDLE")
    args = ap.parse_args(argv)
    resp = ca.read_response(Path(args.response))
    if args.rust:
        print(rust_table(middle(resp).w))
        return 0
    lines = page(resp)
    print("\n".join(lines))
    # the generated part ends where the hand-written sections (## …) begin: keep those
    doc = Path(args.docs) / "input_path_designs.md"
    old = doc.read_text() if doc.exists() else ""
    tail = old[old.index("\n## ") + 1:] if "\n## " in old else ""
    doc.write_text("\n".join(lines) + "\n\n" + tail)
    return 0


if __name__ == "__main__":
    main()
