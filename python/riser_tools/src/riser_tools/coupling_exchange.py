"""How the riser's force reaches a light body over a fixed communication step (issue 29, the buoy;
docs/theory.md §7.3, docs/coupling.md): the force exchanges that stay inside FMI 2.0 and
libcosim's fixed-step (Jacobi) master, analysed with the linear loop of
`riser_tools.coupling_analysis` (the body's heave integrated exactly over each step, riser's
input path and the catenary's measured answers, docs/coupling_response.csv).

What the body holds over the step [t_n, t_n + h] (F_k: riser's top_force_z at t_k):

* ``zoh``: F_n (today);
* ``ab2``, ``ab3``: the force extrapolated over the step from riser's history, Adams–Bashforth
  weights (the step average of the extrapolating polynomial): (3F_n − F_{n−1})/2,
  (23F_n − 16F_{n−1} + 5F_{n−2})/12;
* ``amp``: the *added-mass partitioned* exchange (the added-mass partitioned schemes of
  fluid–structure interaction): the line's top answers a heave at 0.5–3 Hz as a mass, about 50 t
  (its dynamic stiffness −F/x ≈ −m ω², measured), which in a Jacobi exchange is the
  added-mass instability of partitioned FSI: with the force of t_n held, a body of mass M
  behind a line of inertia m gets ẍ_{n+1} ≈ −(m/M) ẍ_n whatever the step, and it diverges when m
  approaches M (the buoy: M + A = 75 t). The body integrates with its mass plus an estimate m̂ of
  the line's and holds F_n + m̂ a_n, a_n its own acceleration at t_n: the inertia is then
  implicit in the body and only the rest of the line's answer is exchanged with the lag.
* ``low_pass``: F_n through first-order stages at a cut-off f_c, updated at the points (Vessel.py
  `force_cutoff`, `force_filter_order`): the body made deaf to the line's axial resonance.

Not in this linear model (the measured answers are at the communication points only): riser's
`top_force_z_mean`, the mean force over the step (Vessel.py `force_hold` 4, 5).

What the measurements say (libcosim, `measure`; docs/theory.md §7.3): the loop that grows is the
line's axial resonance (3.8–4.4 Hz), where |K| / ((M + A) ω²) is 2–11 for the buoy and 0.05–0.28
for the vessel (`resonance_gain`); F_n, the AB holds and the added-mass hold all grow; F_n
low-passed at 0.5 Hz is bounded and within 0.07 % at 0.05–0.1 s, and the step mean low-passed at
0.25 Hz at 0.05–0.5 s (0.23 % at 0.2 s, 0.33 % at 0.5 s: it missed 0.5 s by 1.1–1.3 % while riser fitted
the buoy's velocities as motion, where a body integrating a held force reports them off its positions'
slope by −Ḟ h²/(12 M); theory §7.4).

The loop is simulated in time, linear (riser alone: F_n = Σ r_u[k] x_{n−1−k} + Σ r_v[k] v_{n−1−k},
with the velocities in the fit at h ≥ 0.21 s as the FMU does when both inputs are connected,
§7.4): a heave kick of 1 mm, then the growth rate of the envelope (1/s) and the frequency of what
grows. (The spectral radius of the loop's companion matrix is no use here: with thousands of
taps its roots crowd the unit circle within a few per cent whatever the loop does.)

    python -m riser_tools.coupling_exchange [--response docs/coupling_response.csv] [--fine out/resp_fine.csv]
"""
from __future__ import annotations

import argparse
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .coupling_analysis import (BOTH, BUOY, ROOT, VESSEL, Body, both_fir, design_weights, read_response,
                                riser_fir)


@dataclass(frozen=True)
class Exchange:
    """The force the body holds over a step: Σ_m hold[m] F_{n−m} + line_mass · a_n, the body
    integrating with its own mass plus line_mass."""
    name: str
    hold: tuple = (1.0,)
    line_mass: float = 0.0
    cutoff: float = 0.0  # Hz: a low-pass of the held force at the points (0: none) ...
    stages: int = 2  # ... of this many first-order stages (Vessel.py force_filter_order)


ZOH = Exchange("zoh: F_n held")
AB2 = Exchange("ab2: (3F_n − F_{n−1})/2", (1.5, -0.5))
AB3 = Exchange("ab3: (23F_n − 16F_{n−1} + 5F_{n−2})/12", (23 / 12, -16 / 12, 5 / 12))


def amp(m: float) -> Exchange:
    return Exchange(f"amp: F_n + m̂ a_n, m̂ = {m / 1e3:g} t", (1.0,), m)


def low_pass(fc: float, stages: int = 2) -> Exchange:
    return Exchange(f"low-pass: F_n through {stages} first-order stages at {fc:g} Hz", (1.0,), 0.0, fc, stages)


EXCHANGES = [ZOH, AB2, AB3, amp(50e3), amp(75e3), low_pass(0.5), low_pass(0.25), low_pass(0.15)]
STEPS = [0.01, 0.02, 0.05, 0.1, 0.2, 0.5]


def riser_taps(g: np.ndarray, h: float, both: bool = True):
    """(r_u, r_v) of riser alone at a uniform step h: the displacement design of input_path.rs, or
    with `both` at h ≥ 0.21 s the design that fits the velocities too (§7.4)."""
    if both and h >= BOTH.min_h:
        return both_fir(g, h)
    r = riser_fir(g, design_weights(h))
    return r, np.zeros(1)


def body_matrices(body: Body, h: float, extra_mass: float = 0.0):
    """Φ, Γ of the body's heave with mass M + A + extra_mass and the force held over h, and the
    continuous A, b (ẋ = A s + b F)."""
    m = body.mass + body.added_mass + extra_mass
    a = np.array([[0.0, 1.0], [-body.stiffness / m, -body.damping / m]])
    b = np.array([0.0, 1.0 / m])
    from .coupling_analysis import expm
    aug = np.zeros((3, 3))
    aug[:2, :2], aug[:2, 2] = a, b
    e = expm(aug * h)
    return e[:2, :2], e[:2, 2], a, b


def simulate(body: Body, h: float, ru: np.ndarray, rv: np.ndarray, ex: Exchange, duration: float = 40.0,
             kick: float = 1e-3, force=None):
    """The linear loop in time: returns t, x (body heave), F (riser's force change) at the points.
    `force(t)` (optional) is a force on the body held over each step (the wave, for accuracy)."""
    n = int(round(duration / h))
    phi, gam, a, b = body_matrices(body, h, ex.line_mass)
    L = len(ru)
    xs = np.zeros(n + 1 + L)  # xs[L + i] = x_i, zeros before
    vs = np.zeros(n + 1 + L)
    fs = np.zeros(n + 1 + len(ex.hold))
    s = np.array([kick, 0.0])
    held_prev, filt = 0.0, []
    t = np.arange(n + 1) * h
    for i in range(n + 1):
        xs[L + i], vs[L + i] = s
        # riser's output at t_i from its inputs up to t_{i−1} (Jacobi)
        past_x = xs[L + i - 1::-1][:L] if i > 0 else np.zeros(L)
        past_v = vs[L + i - 1::-1][: len(rv)] if i > 0 else np.zeros(len(rv))
        f = ru[: len(past_x)] @ past_x + rv[: len(past_v)] @ past_v
        fs[len(ex.hold) + i] = f
        if i == n:
            break
        acc = (a @ s)[1] + b[1] * held_prev  # the body's acceleration at t_i (end of its last step)
        held = sum(c * fs[len(ex.hold) + i - m] for m, c in enumerate(ex.hold)) + ex.line_mass * acc
        if ex.cutoff > 0.0:
            alpha = np.exp(-2 * np.pi * ex.cutoff * h)
            filt = [held] * ex.stages if i == 0 else filt
            for j in range(ex.stages):
                filt[j] = alpha * filt[j] + (1 - alpha) * held
                held = filt[j]
        w = force(t[i]) if force else 0.0
        s = phi @ s + gam * (held + w)
        held_prev = held + w
    return t, xs[L:], fs[len(ex.hold):]


def growth(t, x, h):
    """Growth rate (1/s) of the envelope of x over the second half against the first half after
    5 s, and the frequency (Hz) of the largest spectral peak over the last half."""
    m1 = (t >= 5.0) & (t < 5.0 + (t[-1] - 5.0) / 2)
    m2 = t >= 5.0 + (t[-1] - 5.0) / 2
    a1, a2 = np.abs(x[m1]).max(), np.abs(x[m2]).max()
    rate = np.log(a2 / a1) / ((t[-1] - 5.0) / 2) if a1 > 0 and a2 > 0 and np.isfinite(a2) else np.inf
    y = x[m2] * np.exp(-rate * (t[m2] - t[m2][0])) if np.isfinite(rate) else x[m2]
    y = y - y.mean()
    if not np.all(np.isfinite(y)):
        return rate, float("nan")
    spec = np.abs(np.fft.rfft(y * np.hanning(len(y))))
    freqs = np.fft.rfftfreq(len(y), h)
    return float(rate), float(freqs[1 + np.argmax(spec[1:])])


def line_mass_estimate(g: np.ndarray, h: float, band=(0.5, 3.0)):
    """The line's apparent mass at the hang-off, −Re K(ω)/ω² averaged over `band` (Hz), K = −F/x the
    dynamic stiffness of the measured answers under an exact sinusoidal heave."""
    from .coupling_analysis import exact_end_state, line_transfer
    out = []
    for f in np.linspace(band[0], band[1], 11):
        th = 2 * np.pi * f * h
        if th >= np.pi:
            continue
        k = -(line_transfer(g, th)[:, 0] * exact_end_state(th)[:, 0]).sum()
        out.append(-k.real / (2 * np.pi * f) ** 2)
    return float(np.mean(out)) if out else float("nan")


def resonance_gain(g: np.ndarray, h: float, body: Body, band=(3.5, 5.0)):
    """max over `band` (Hz) of |K(ω)| / ((M + A) ω²): the line's answer at the hang-off against the
    body's inertia, the physical loop's gain where the line resonates axially (> 1: the body takes
    part in the line's axial mode, and a lagged exchange of it can grow)."""
    from .coupling_analysis import exact_end_state, line_transfer
    best = (0.0, 0.0)
    for f in np.linspace(band[0], band[1], 61):
        th = 2 * np.pi * f * h
        if th >= np.pi:
            break
        k = abs((line_transfer(g, th)[:, 0] * exact_end_state(th)[:, 0]).sum())
        gain = k / ((body.mass + body.added_mass) * (2 * np.pi * f) ** 2)
        best = max(best, (gain, f))
    return best


def analyse(resp, exchanges=EXCHANGES, bodies=(BUOY, VESSEL), duration=40.0, steps=None):
    rows = []
    for h in sorted(h for h in resp if steps is None or h in steps):
        ru, rv = riser_taps(resp[h], h)
        for body in bodies:
            for ex in exchanges:
                with np.errstate(over="ignore", invalid="ignore"):
                    t, x, f = simulate(body, h, ru, rv, ex, duration)
                    rate, freq = growth(t, f, h)
                rows.append(dict(h=h, body=body.name, exchange=ex.name, rate=rate, freq=freq))
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m riser_tools.coupling_exchange", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--response", default=str(ROOT / "docs" / "coupling_response.csv"))
    ap.add_argument("--fine", default=None, help="answers at 0.01 and 0.02 s (examples/hang_off_response.rs)")
    args = ap.parse_args(argv)
    resp = read_response(Path(args.response))
    if args.fine:
        resp.update(read_response(Path(args.fine)))
    for h in sorted(resp):
        gb, fb = resonance_gain(resp[h], h, BUOY)
        gv, _ = resonance_gain(resp[h], h, VESSEL)
        print(f"h {h}: line's apparent mass 0.5-3 Hz {line_mass_estimate(resp[h], h) / 1e3:.1f} t; "
              f"|K|/((M+A)ω²) at 3.5-5 Hz: buoy {gb:.2f} (at {fb:.2f} Hz), vessel {gv:.3f}")
    for r in analyse(resp, steps=STEPS):
        print(f"{r['body']:14s} h {r['h']:5.2f} {r['exchange']:42s} growth {r['rate']:+8.3f} /s at {r['freq']:6.2f} Hz",
              flush=True)
    return 0


if __name__ == "__main__":
    main()


# --- measured in libcosim (osp/vessel/Vessel.py with the buoy's numbers) -------------------------

def buoy_parameters(**exchange) -> dict:
    """Vessel.py's parameters for the 50 t buoy of coupling_analysis.BUOY (its `mass` is M + A)
    in coupling_loop.BUOY_WAVE, and the exchange (force_hold, line_mass, force_cutoff,
    force_filter_order)."""
    from .coupling_loop import BUOY_WAVE
    return dict(mass=BUOY.mass + BUOY.added_mass, damping=BUOY.damping, stiffness=BUOY.stiffness,
                wave_force=BUOY_WAVE.force, wave_period=BUOY_WAVE.period, ramp=BUOY_WAVE.ramp, **exchange)


def measure(riser_fmu: str, vessel_fmu: str, h: float, duration: float = 50.0, start: float = 30.0,
            body: dict | None = None, one_way: bool = False):
    """libcosim's fixed step on riser and the body FMU; the top tension window over [start, duration]
    (min, max, mean, N), the peak-to-peak of the tension over 5 s pieces (N), the heave's amplitude,
    and with `one_way` the window of riser alone at 0.01 s fed the run's motion."""
    from .coupling_loop import fixed_step, reference, window
    two = fixed_step(riser_fmu, vessel_fmu, h, duration, body)
    t, tt = two["t"], two["top_tension"]
    pieces = [float(np.ptp(tt[(t >= a) & (t < a + 5.0)])) for a in np.arange(5.0, duration, 5.0)]
    out = dict(h=h, window=window(two, start), pieces=pieces,
               heave=float(np.ptp(two["heave"][t >= start]) / 2), run=two)
    if one_way:
        out["one_way"] = window(reference(riser_fmu, two, h_ref=0.01), start)
    return out
