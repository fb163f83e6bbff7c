"""The co-simulation loop of a vessel and riser's FMU, linearised (docs/theory.md §7.3, issue 29).

The loop, one axis (heave), uniform communication step h:

* the **vessel**: (M + A) x'' + C x' + K x = F(t) with F held over each step (a vessel FMU sees
  the force set before its step, zero-order hold), integrated exactly: s_{n+1} = Φ s_n + Γ F,
  s = (x, x');
* the **master**: libcosim's fixed-step algorithm is Jacobi, the vessel steps with the force of
  t_n (F_n); Gauss–Seidel with the riser first would give it F_{n+1};
* the riser's **input path** (src/fmi/input_path.rs): the end state of the step from t_n,
  e_n = (P(h), h P'(h), h² P''(h)), is a linear filter of the displacement inputs,
  e_{n,j} = Σ_i W[j, i] x_{n-i} (the predictor; `predictor_weights`), and the hang-off moves along
  the quintic Hermite interpolant between successive end states: a sum of C2 bumps, one of each
  kind j (value, slope, curvature) at every communication point;
* the **line**: linear about its state, F_n = Σ_k Σ_j g_j[k] e_{n-1-k, j}, g_j[k] the change of
  top_force_z at t_c + k h per unit bump of kind j centred at t_c. Measured with the model itself
  (`examples/hang_off_response.rs`, every h at the internal step min(0.05 s, h)), or the lumped
  model the brief names for contrast: g_0[0] = −S (the static tangent stiffness, §8.3) and
  g_2[0] = −m / h² (a mass m at the hang-off).

The riser alone is then F_n = Σ_k r[k] x_{n-1-k} with r = Σ_j g_j * W_j, and the loop is a linear
recurrence whose spectral radius decides stability (< 1). From the same pieces: the hang-off's
answer to an alternating input, |E_0(π)| per metre; the tension's, |Σ_j G_j(π) E_j(π)|; and the
one-way error of a sinusoidal heave, |Σ_j G_j(θ)(E_j(θ) − X_j(θ))| U with X the exact end state.

    riser-tools coupling [--response docs/coupling_response.csv] [--measure] [--docs docs]
"""
from __future__ import annotations

import argparse
import subprocess
from dataclasses import dataclass
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[4]

# communication steps of the analysis (s)
STEPS = [0.03, 0.05, 0.07, 0.1, 0.15, 0.2, 0.3, 0.5, 0.7, 1.0]
# the bumps are centred at T_CENTRE (the current has moved the line off its still-water shape by
# then) and followed for T_MEMORY; amplitude small enough for the linear answer
T_CENTRE, T_MEMORY, BUMP = 10.0, 30.0, 1e-4


@dataclass(frozen=True)
class Body:
    """A floating body at the hang-off, heave only: mass, added mass (kg), linear damping
    (N s/m), hydrostatic stiffness (N/m)."""
    name: str
    mass: float
    added_mass: float
    damping: float
    stiffness: float

    @staticmethod
    def of(name, mass, added_mass, waterplane, zeta, rho=1025.0, g=9.81):
        k = rho * g * waterplane
        return Body(name, mass, added_mass, 2.0 * zeta * np.sqrt(k * (mass + added_mass)), k)


# a 2000 t vessel (added mass half its mass, 500 m² waterplane: heave period 4.9 s, 5 % damping)
# and a 50 t surface buoy (added mass 25 t, 10 m² waterplane: 5.4 s, 5 %)
VESSEL = Body.of("vessel 2000 t", 2.0e6, 1.0e6, 500.0, 0.05)
BUOY = Body.of("buoy 50 t", 5.0e4, 2.5e4, 10.0, 0.05)


@dataclass(frozen=True)
class Predictor:
    """The end state of a step from the last n_poly + n_alt displacement samples: the polynomial
    part of degree n_poly − 1 of the samples written as polynomial + alternating nuisance
    Σ_{i < n_alt} a_i (τ_k/h)^i (−1)^k (n_alt = 0: the interpolating polynomial)."""
    name: str
    n_poly: int
    n_alt: int = 0
    n_taps: int = 0

    @property
    def taps(self):
        return max(self.n_taps, self.n_poly + self.n_alt)


TODAY = Predictor("quartic interpolation (before)", 5)

# the designs of src/fmi/input_path.rs (DESIGNS): (step below which it is used, design)
DESIGNS = [(0.075, Predictor("quartic, 16 points, three nuisances", 5, 3, 16)),
           (0.21, Predictor("quartic, 12 points, two nuisances", 5, 2, 12)),
           (np.inf, Predictor("quartic, 6 points, alternation", 5, 1, 6))]
AFTER = Predictor("least squares per step (after)", 0)


# the end state's slope and curvature of each design once its filters' window of uniform points is
# known (src/fmi/input_path.rs CONSISTENT, docs/theory.md (7.3a)): those of the sequence of end values
# for polynomials up to the degree, the design's alternations removed, least energy in the band
# θ ∈ [band π, π]; {design index: (band, degree, taps)}
CONSISTENT_TAPS = 16
CONSISTENT = {0: (0.5, 7, 16), 2: (0.5, 7, 10)}
# the middle steps' (design 1) slope and curvature before (7.3b): (7.3a) over the 12-point fit
CONSISTENT_BEFORE = {1: (0.2, 6, 16)}

# the middle steps' end state once 16 uniform points are known (src/fmi/input_path.rs MIDDLE, docs/theory.md
# (7.3b)): value, h slope, h² curvature rows over the samples, newest first; made by
# riser_tools.studies.input_path_designs.middle (tests/python/test_input_path_designs.py checks that both agree)
MIDDLE_INDEX = 1
MIDDLE = np.array([
    [1.106861496001382, 1.6651640963303749, -0.3218273624167458, -1.9629620499710672, -1.4277172138289116, 0.275634168118162, 1.1792344736682976, 1.355514297109703, 0.9001280385193262, -0.6458253136951477, -1.4354494684257901, -0.7683171267571192, 0.5250966982557694, 0.7955057910838239, -0.026326661773325752, -0.21471386221873046],
    [2.3144588909384294, -1.0300756103340465, -3.6566263471657665, 0.1688792777681124, 1.680815972066791, 2.319900469860554, -0.22462465792935432, -0.7588254125454363, -1.1450153961283323, -1.0637957165490888, 0.4901733306122258, 0.9989531592681684, 0.9376641449696066, -0.9234662622804455, -0.3968459373635984, 0.2884300948121796],
    [4.608822142156016, -10.085841073733139, 1.5090166570178662, 6.2703554353681685, 1.9529004217940005, 1.1271688597042497, -13.693312749195517, 6.761994702832747, 1.8439258192214363, 3.8221780961154472, -4.088027595755474, -3.546252509732071, 6.3371716844594035, -4.079097474811499, 1.529503620302269, -0.2705060357439055],
])


def consistent_weights(p: Predictor, band: float, degree: int, taps: int = CONSISTENT_TAPS) -> np.ndarray:
    """W (3 × taps) of (7.3a): the value row p's fit; the slope and curvature rows w minimise
    wᵀ B w, B_ij = (1/(π − a)) ∫_a^π cos((i − j)θ) dθ (a = band π, 1e-9 on the diagonal), subject to
    giving h^r times the r-th derivative of the end values' sequence Σ_k w0_k u(t − k h) for every
    polynomial u of degree ≤ `degree`, and nothing for the design's alternations (−1)^k ξ_k^q."""
    w0 = np.zeros(taps)
    w0[: p.taps] = predictor_weights(p)[0]
    scale = taps - 1.0
    xi = -np.arange(taps) / scale
    a = band * np.pi
    m = np.abs(np.subtract.outer(np.arange(taps), np.arange(taps))).astype(float)
    with np.errstate(divide="ignore", invalid="ignore"):
        b = np.where(m == 0, 1.0, -np.sin(a * m) / (m * (np.pi - a)))
    b = b + 1e-9 * np.eye(taps)
    out = np.zeros((3, taps))
    out[0] = w0
    for r in (1, 2):
        rows, rhs = [], []
        for q in range(degree + 1):
            rows.append(xi ** q)
            falling = np.prod([q - k for k in range(r)]) if q >= r else 0.0
            rhs.append(falling / scale ** r * (w0 @ xi ** (q - r)) if q >= r else 0.0)
        for q in range(p.n_alt):
            rows.append((-1.0) ** np.arange(taps) * xi ** q)
            rhs.append(0.0)
        c, d = np.array(rows), np.array(rhs)
        k = np.block([[2 * b, c.T], [c, np.zeros((len(d), len(d)))]])
        f = np.concatenate([np.zeros(taps), d])
        x = np.linalg.solve(k, f)
        x = x + np.linalg.solve(k, f - k @ x)  # one step of refinement, as input_path.rs
        out[r] = x[:taps]
    return out


def design_weights(h: float) -> np.ndarray:
    """The end-state filters input_path.rs uses at uniform steps h once its window is full."""
    index = next(i for i, (below, _) in enumerate(DESIGNS) if h < below)
    p = DESIGNS[index][1]
    if index == MIDDLE_INDEX:
        return MIDDLE.copy()
    return consistent_weights(p, *CONSISTENT[index]) if index in CONSISTENT else predictor_weights(p)


def design(h: float) -> Predictor:
    """The design input_path.rs uses for a step of h s."""
    return next(p for below, p in DESIGNS if h < below)


def design_window(h: float) -> int:
    """The samples the end value of a step of h s reads once its window is full (its design's, 16
    for the middle steps' MIDDLE)."""
    d = design(h)
    return MIDDLE.shape[1] if d is DESIGNS[MIDDLE_INDEX][1] else d.taps


def resolve(p: Predictor, h: float) -> Predictor:
    return design(h) if p is AFTER else p
CANDIDATES = [
    TODAY,
    AFTER,
    Predictor("cubic interpolation", 4),
    Predictor("linear extrapolation", 2),
    Predictor("quartic, alternation removed", 5, 1),
    Predictor("quadratic, 8 points, two nuisances", 3, 2, 8),
    Predictor("cubic, 8 points, two nuisances", 4, 2, 8),
]


@dataclass(frozen=True)
class BothPredictor:
    """The design of `both` at uniform steps h ≥ 0.21 s (src/fmi/input_path.rs VELOCITY_DESIGN,
    docs/theory.md §7.4): the last `n` displacements and velocities written, in the least-squares
    sense, as a quintic Q and its slope plus an alternating nuisance in each and an offset of the
    velocities from Q's slope (7.10)."""
    name: str = "both: quintic, 5 points of displacement and velocity, three nuisances"
    n: int = 5
    min_h: float = 0.21


BOTH = BothPredictor()


def both_weights(p: BothPredictor = BOTH):
    """(Wu, Wv), each 3 × n: the end state (Q, h Q', h² Q'') at σ = 1 is Wu x + Wv (h v), samples
    newest first at σ_k = −k."""
    rows = []
    for k in range(p.n):
        s = -float(k)
        rows.append([s ** j for j in range(6)] + [(-1.0) ** k, 0.0, 0.0])
    for k in range(p.n):
        s = -float(k)
        rows.append([j * s ** (j - 1) if j else 0.0 for j in range(6)] + [0.0, (-1.0) ** k, 1.0])
    inv = np.linalg.pinv(np.array(rows))[:6]
    j = np.arange(6)
    w = np.array([np.ones(6), j * 1.0, j * (j - 1.0)]) @ inv
    return w[:, : p.n], w[:, p.n:]


def both_fir(g: np.ndarray, h: float, p: BothPredictor = BOTH):
    """(r_u, r_v): the force at t_n per unit x_{n−1−k} and per unit v_{n−1−k} (riser alone)."""
    wu, wv = both_weights(p)
    return riser_fir(g, wu), riser_fir(g, wv * h)


def both_end_state_response(theta, p: BothPredictor = BOTH) -> np.ndarray:
    """E_j(θ) of the `both` design for a sampled e^{iθn} with its exact velocity (h v = iθ x)."""
    wu, wv = both_weights(p)
    theta = np.atleast_1d(theta)
    return (wu + 0j) @ np.exp(-1j * np.outer(np.arange(p.n), theta)) + \
        (wv @ np.exp(-1j * np.outer(np.arange(p.n), theta))) * (1j * theta)


def predictor_weights(p: Predictor, taus=None) -> np.ndarray:
    """W (3 × taps): the end state (P, h P', h² P'') at σ = 1 from the samples at σ = τ_k/h
    (newest first; default the uniform τ_k = −k h)."""
    n = p.taps
    s = -np.arange(n, dtype=float) if taus is None else np.asarray(taus, dtype=float)
    cols = [s ** j for j in range(p.n_poly)] + [s ** i * (-1.0) ** np.arange(n) for i in range(p.n_alt)]
    a = np.array(cols).T  # a @ coef = samples (least squares when there are more samples)
    inv = np.linalg.pinv(a)[: p.n_poly]  # polynomial coefficients from the samples
    j = np.arange(p.n_poly)
    value = np.ones(p.n_poly)
    slope = j.astype(float)
    curv = (j * (j - 1)).astype(float)
    return np.array([value @ inv, slope @ inv, curv @ inv])


def predicted_end_values(samples, h: float) -> np.ndarray:
    """The end values input_path.rs predicts at uniform steps h for the displacement sequence
    `samples` (oldest first), the start included: with n < taps samples known, the design keeps
    min(alt, n − 4) nuisances and min(poly, n − nuisances) coefficients; the middle steps take
    MIDDLE's value row once 16 points are known (7.3b). The hang-off is at entry k at the end of
    step k."""
    d = design(h)
    middle = d is DESIGNS[MIDDLE_INDEX][1]
    samples = np.asarray(samples, dtype=float)
    out = np.zeros(len(samples))
    for k in range(len(samples)):
        if middle and k + 1 >= MIDDLE.shape[1]:
            out[k] = MIDDLE[0] @ samples[k::-1][: MIDDLE.shape[1]]
            continue
        n = min(k + 1, d.taps)
        alt = min(d.n_alt, max(0, n - 4))
        w = predictor_weights(Predictor("", min(d.n_poly, n - alt), alt, n))
        out[k] = w[0] @ samples[k::-1][:n]
    return out


def end_state_response(w: np.ndarray, theta) -> np.ndarray:
    """E_j(θ) = Σ_i W[j, i] e^{−iθi}: the end state per unit of a sampled e^{iθn}, relative to x_n."""
    theta = np.atleast_1d(theta)
    return w @ np.exp(-1j * np.outer(np.arange(w.shape[1]), theta))


def exact_end_state(theta) -> np.ndarray:
    """X_j(θ): the exact motion's end state (value, h·slope, h²·curvature) at t_{n+1} per unit x_n."""
    theta = np.atleast_1d(theta)
    z = np.exp(1j * theta)
    return np.array([z, 1j * theta * z, -(theta ** 2) * z])


def line_transfer(g: np.ndarray, theta) -> np.ndarray:
    """G_j(θ) = Σ_k g_j[k] e^{−iθ(k+1)}: the force at t_n per unit end state e_{n−1}."""
    theta = np.atleast_1d(theta)
    return g @ np.exp(-1j * np.outer(np.arange(1, g.shape[1] + 1), theta))


def lumped_line(h: float, stiffness: float, mass: float) -> np.ndarray:
    g = np.zeros((3, 1))
    g[0, 0], g[2, 0] = -stiffness, -mass / h ** 2
    return g


def expm(a: np.ndarray) -> np.ndarray:
    """Matrix exponential by scaling and squaring a Taylor series (small matrices)."""
    s = max(0, int(np.ceil(np.log2(max(np.abs(a).sum(axis=1).max(), 1e-300)))) + 1)
    b = a / 2.0 ** s
    out, term = np.eye(len(a)), np.eye(len(a))
    for k in range(1, 25):
        term = term @ b / k
        out = out + term
    for _ in range(s):
        out = out @ out
    return out


def body_zoh(body: Body, h: float):
    """Φ, Γ of the body's heave over h with the force held: s_{n+1} = Φ s_n + Γ F."""
    m = body.mass + body.added_mass
    a = np.array([[0.0, 1.0], [-body.stiffness / m, -body.damping / m]])
    aug = np.zeros((3, 3))
    aug[:2, :2], aug[1, 2] = a, 1.0 / m
    e = expm(aug * h)
    return e[:2, :2], e[:2, 2]


def riser_fir(g: np.ndarray, w: np.ndarray) -> np.ndarray:
    """r[k]: the force at t_n per unit x_{n−1−k} (the riser alone, input to output)."""
    return sum(np.convolve(g[j], w[j]) for j in range(3))


def spectral_radius(body: Body, h: float, r: np.ndarray, master: str = "jacobi") -> float:
    """Largest |eigenvalue| of the loop: state (x_n, v_n, x_{n−1}, ..., x_{n−L})."""
    phi, gam = body_zoh(body, h)
    r = np.trim_zeros(r, "b")
    big = np.abs(r).max()
    keep = np.nonzero(np.abs(r) > 1e-7 * big)[0]
    r = r[: keep[-1] + 1] if len(keep) else r[:1]
    n_hist = len(r) + 1
    dim = 2 + n_hist
    a = np.zeros((dim, dim))
    # history slots: index 2 + i holds x_{n−1−i}
    a[:2, :2] = phi
    if master == "jacobi":
        # F_n = Σ r[k] x_{n−1−k}
        for k, rk in enumerate(r):
            a[:2, 2 + k] += gam * rk
    else:
        # Gauss–Seidel, the riser first: the vessel steps with F_{n+1} = Σ r[k] x_{n−k}
        a[:2, 0] += gam * r[0]
        for k, rk in enumerate(r[1:]):
            a[:2, 2 + k] += gam * rk
    a[2, 0] = 1.0
    for i in range(1, n_hist):
        a[2 + i, 2 + i - 1] = 1.0
    return float(np.abs(np.linalg.eigvals(a)).max())


# the band a step carries only through the co-simulation (θ ≥ π/2); below, the loop is the
# physical coupling of the body and the line, resolved by the step
HIGH_BAND = np.linspace(np.pi / 2000, np.pi, 2000) >= np.pi / 2


def loop_gain(body: Body, h: float, r: np.ndarray, n: int = 2000) -> np.ndarray:
    """|L(θ)| on θ ∈ (0, π], L = z⁻¹ R(z) c (zI − Φ)⁻¹ Γ at z = e^{iθ} (Jacobi): the loop's gain at
    every frequency a step carries. max |L| < 1 with both parts stable is stability (small gain)."""
    phi, gam = body_zoh(body, h)
    theta = np.linspace(np.pi / n, np.pi, n)
    z = np.exp(1j * theta)
    rz = np.exp(-1j * np.outer(theta, np.arange(len(r)))) @ r
    det = (z - phi[0, 0]) * (z - phi[1, 1]) - phi[0, 1] * phi[1, 0]
    g = ((z - phi[1, 1]) * gam[0] + phi[0, 1] * gam[1]) / det
    return np.abs(rz * g / z)


def loop_gain_both(body: Body, h: float, ru: np.ndarray, rv: np.ndarray, n: int = 2000) -> np.ndarray:
    """|L(θ)| of (7.9) when the riser reads the body's velocity too: L = z⁻¹ (R_u(z) G_x(z) +
    R_v(z) G_v(z)), G_x, G_v the body's position and velocity per unit held force."""
    phi, gam = body_zoh(body, h)
    theta = np.linspace(np.pi / n, np.pi, n)
    z = np.exp(1j * theta)
    ru_z = np.exp(-1j * np.outer(theta, np.arange(len(ru)))) @ ru
    rv_z = np.exp(-1j * np.outer(theta, np.arange(len(rv)))) @ rv
    det = (z - phi[0, 0]) * (z - phi[1, 1]) - phi[0, 1] * phi[1, 0]
    gx = ((z - phi[1, 1]) * gam[0] + phi[0, 1] * gam[1]) / det
    gv = ((z - phi[0, 0]) * gam[1] + phi[1, 0] * gam[0]) / det
    return np.abs((ru_z * gx + rv_z * gv) / z)


def spectral_radius_both(body: Body, h: float, ru: np.ndarray, rv: np.ndarray) -> float:
    """The loop's spectral radius with the velocity read too: state (x_n, v_n, x_{n−1..n−L},
    v_{n−1..n−L})."""
    phi, gam = body_zoh(body, h)
    big = max(np.abs(ru).max(), np.abs(rv).max())
    keep = np.nonzero((np.abs(ru) > 1e-7 * big) | (np.abs(rv) > 1e-7 * big))[0]
    n = keep[-1] + 1 if len(keep) else 1
    ru, rv = ru[:n], rv[:n]
    a = np.zeros((2 + 2 * n, 2 + 2 * n))
    a[:2, :2] = phi
    for k in range(n):
        a[:2, 2 + k] += gam * ru[k]
        a[:2, 2 + n + k] += gam * rv[k]
    a[2, 0] = a[2 + n, 1] = 1.0
    for i in range(1, n):
        a[2 + i, 1 + i] = a[2 + n + i, 1 + n + i] = 1.0
    return float(np.abs(np.linalg.eigvals(a)).max())


def analyse_both(resp: dict[float, np.ndarray], bodies=(VESSEL, BUOY), amplitude=2.5, period=20.0):
    """The rows of the `both` design at the steps it is used at (h ≥ 0.21 s)."""
    rows = []
    for h, g in sorted(resp.items()):
        if h < BOTH.min_h:
            continue
        ru, rv = both_fir(g, h)
        theta = 2 * np.pi * h / period
        e = both_end_state_response(theta)[:, 0] - exact_end_state(theta)[:, 0]
        one_way = abs((line_transfer(g, theta)[:, 0] * e).sum()) * amplitude
        # a ±1e-5 m alternation of the displacement alone (the velocity input steady)
        e_pi = both_weights()[0] @ (-1.0) ** np.arange(BOTH.n)
        rows.append(dict(predictor=BOTH.name, h=h, onset=float("nan"),
                         rho={b.name: spectral_radius_both(b, h, ru, rv) for b in bodies},
                         gain={b.name: float(loop_gain_both(b, h, ru, rv)[HIGH_BAND].max()) for b in bodies},
                         rho_gs={b.name: float("nan") for b in bodies}, hang_off=abs(e_pi[0]) * 1e-5,
                         swing=2.0 * abs((line_transfer(g, np.pi)[:, 0] * e_pi).sum()) * 1e-5, one_way=one_way))
    return rows


def measure(hs, out: Path, scene="catenary", profile="fasttest") -> None:
    """Runs examples/hang_off_response.rs for every h and writes its CSV."""
    subprocess.run(["cargo", "build", "--profile", profile, "--example", "hang_off_response"], cwd=ROOT, check=True)
    exe = ROOT / "target" / profile / "examples" / "hang_off_response"
    txt = subprocess.run([str(exe), scene, str(T_CENTRE), str(T_MEMORY), str(BUMP)] + [str(h) for h in hs],
                         check=True, capture_output=True, text=True).stdout
    out.write_text(txt)


def read_response(path: Path) -> dict[float, np.ndarray]:
    """{h: g (3 × K)} from the CSV of `measure`, its sum (the answer to a held displacement) made
    −S_zz, the static stiffness of the same state (kind −1). The bumps' answers do not add up
    exactly (the ρ∞ dissipation's saw-tooth weights are not linear: 5 % at the first point), so
    their sum drifts from the answer to a step, measured separately as −S_zz within 3 %; the
    difference is spread over the first second."""
    d = np.genfromtxt(path, delimiter=",", names=True)
    out = {}
    for h in np.unique(d["h"]):
        m = (d["h"] == h) & (d["kind"] >= 0)
        k = int(d["k"][m].max()) + 1
        g = np.zeros((3, k))
        for j in range(3):
            mj = m & (d["kind"] == j)
            g[j, d["k"][mj].astype(int)] = d["response"][mj]
        s = d["response"][(d["h"] == h) & (d["kind"] == -1)]
        if len(s):
            first = max(1, int(round(1.0 / h)))
            g[0, :first] += (-s[0] - g[0].sum()) / first
        out[float(h)] = g
    return out


def alternating(w: np.ndarray, g: np.ndarray, amplitude: float = 1e-5):
    """The hang-off's and the tension's answer to an input alternating ±amplitude through the
    end-state filters w: the end value's amplitude (m) and the force's peak-to-peak swing (N),
    linear and steady."""
    e = end_state_response(w, np.pi)[:, 0]
    f = (line_transfer(g, np.pi)[:, 0] * e).sum()
    return abs(e[0]) * amplitude, 2.0 * abs(f) * amplitude


def onset_swing(w: np.ndarray, g: np.ndarray, amplitude: float = 1e-5, steps: int = 400):
    """Peak-to-peak force (N) when an alternating ±amplitude starts on a still input (the steady
    part and the onset transient), linear, through the full filters w (no start-up)."""
    x = np.array([0.0] * w.shape[1] + [amplitude * (-1.0) ** k for k in range(steps)])
    e = np.array([[w[j] @ x[n::-1][: w.shape[1]] if n >= w.shape[1] - 1 else 0.0 for n in range(len(x))]
                  for j in range(3)])
    f = sum(np.convolve(g[j], e[j])[: len(x)] for j in range(3))
    return float(np.ptp(f))


def one_way_error(w: np.ndarray, g: np.ndarray, h: float, amplitude=2.5, period=20.0):
    """Amplitude (N) of the top force's error under heave amplitude·sin(2πt/period) through the
    end-state filters w, linear."""
    theta = 2 * np.pi * h / period
    e = end_state_response(w, theta)[:, 0] - exact_end_state(theta)[:, 0]
    return abs((line_transfer(g, theta)[:, 0] * e).sum()) * amplitude


def analyse(resp: dict[float, np.ndarray], predictors=CANDIDATES, bodies=(VESSEL, BUOY)):
    rows = []
    for p0 in predictors:
        for h, g in sorted(resp.items()):
            p = resolve(p0, h)
            w = design_weights(h) if p0 is AFTER else predictor_weights(p)
            r = riser_fir(g, w)
            rho = {b.name: spectral_radius(b, h, r) for b in bodies}
            gain = {b.name: float(loop_gain(b, h, r)[HIGH_BAND].max()) for b in bodies}
            rho_gs = ({b.name: spectral_radius(b, h, r, "gauss-seidel") for b in bodies} if p0 in (TODAY, AFTER)
                      else {b.name: float("nan") for b in bodies})
            hang, swing = alternating(w, g)
            rows.append(dict(predictor=p0.name, h=h, onset=onset_swing(w, g), rho=rho, gain=gain, rho_gs=rho_gs, hang_off=hang, swing=swing,
                             one_way=one_way_error(w, g, h)))
    return rows


def plot(rows, resp, path: Path, predictors=CANDIDATES, bodies=(VESSEL, BUOY)):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    theta = np.linspace(1e-3, np.pi, 400)
    ax = axes[0]
    for p in [q for q in predictors if q is not AFTER] + [q for _, q in DESIGNS]:
        ax.semilogy(theta / np.pi, np.abs(end_state_response(predictor_weights(p), theta)[0]), label=p.name)
    ax.semilogy(theta / np.pi, np.abs(both_end_state_response(theta)[0]), "k", lw=2,
                label=BOTH.name + " (velocity exact)")
    ax.set_ylim(1e-2, 100.0)
    ax.set_xlabel("θ = ωh / π")
    ax.set_ylabel("|E₀(θ)|: end value per unit input")
    ax.set_title("predictor gain (1 = exact at low θ)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    for ax, b in zip(axes[1:], bodies):
        for p in list(predictors) + [BOTH]:
            hs = [r["h"] for r in rows if r["predictor"] == p.name]
            ax.loglog(hs, [r["gain"][b.name] for r in rows if r["predictor"] == p.name], "o-", ms=3, label=p.name,
                      **({"color": "k", "lw": 2} if p is BOTH else {}))
        ax.axhline(1.0, color="k", lw=0.8)
        ax.set_xlabel("communication step h (s)")
        ax.set_ylabel("loop gain max |L(θ)|, θ ≥ π/2 (Jacobi)")
        ax.set_title(f"{b.name} + catenary riser (measured line)")
        ax.grid(True, which="both", alpha=0.3)
    axes[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="riser-tools coupling", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--response", default=str(ROOT / "docs" / "coupling_response.csv"))
    ap.add_argument("--measure", action="store_true", help="re-measure the line's bump responses first")
    ap.add_argument("--docs", default=str(ROOT / "docs"))
    args = ap.parse_args(argv)
    path = Path(args.response)
    if args.measure or not path.exists():
        measure(STEPS, path)
    resp = read_response(path)
    rows = analyse(resp) + analyse_both(resp)
    lines = ["# The input path in a coupling loop (issue 29)", "",
             "Made by `riser-tools coupling` (riser_tools.coupling_analysis; docs/theory.md §7.3). The linear "
             "vessel–riser loop of one heave axis at uniform communication steps h: the body's heave integrated "
             "exactly with the force held over the step (Jacobi, libcosim's fixed step; GS: Gauss–Seidel with "
             "riser first), the predictor's end-state filters, and the catenary's answers at the hang-off to the "
             "path's bumps measured with the model (`examples/hang_off_response.rs`, docs/coupling_response.csv; "
             f"linearised about the line at rest in the current, internal step min(0.05 s, h)). Bodies: {VESSEL.name} "
             f"(M + A = {(VESSEL.mass + VESSEL.added_mass) / 1e3:.0f} t, K = {VESSEL.stiffness / 1e6:.2f} MN/m, 5 % "
             f"damping) and {BUOY.name} (M + A = {(BUOY.mass + BUOY.added_mass) / 1e3:.0f} t, K = "
             f"{BUOY.stiffness / 1e3:.0f} kN/m, 5 %). *Loop gain*: max |L(θ)| over θ ≥ π/2, the band a step carries "
             "only through the co-simulation (L = z⁻¹ R(z) G_body(z); < 1 there: no numerical loop can grow, "
             "as far as this linear model of the line goes: measured in libcosim the vessel loop grows the "
             "line's axial resonance at 0.025–0.035 s (|L| 0.38 at 4.1 Hz, θ = 0.25 π, here) and, with the "
             "slope and curvature of degree 7, at 0.2 s (0.63 at 1 Hz), and at steps of 0.2 s and longer in "
             "bands of h with either coupling (§7.3, \"Long communication steps\"): the answers measured about the line at "
             "rest miss part of what the moving line feeds back at its resonance, theory §7.1, §7.3); "
             "below π/2 the loop is the physical coupling of body and line. *ρ*: spectral radius of the whole "
             "linear loop; with the line's answers truncated at 30 s it sits within a few % of 1 for the vessel "
             "whatever the predictor (the line's slow modes), so it tells the predictors apart for the buoy only. "
             "*Swing*: "
             "peak-to-peak top force under a steady ±1e-5 m alternating input; *onset*: the same with the "
             "alternation starting on a still input (its transient included). *One-way*: amplitude of the top "
             "force's error under heave 2.5 m / 20 s, linear.", ""]
    head = ["predictor", "h (s)", "loop gain θ ≥ π/2, vessel", "loop gain θ ≥ π/2, buoy", "ρ vessel (Jacobi / GS)",
            "ρ buoy (Jacobi / GS)", "hang-off under ±1e-5 m (m)",
            "swing (kN)", "onset (kN)", "one-way error (kN)"]
    body_rows = []
    for r in rows:
        print(f"{r['predictor']:36s} h {r['h']:5.2f}  gain vessel {r['gain'][VESSEL.name]:8.3f} buoy "
              f"{r['gain'][BUOY.name]:8.3f}  rho vessel {r['rho'][VESSEL.name]:9.4f} "
              f"buoy {r['rho'][BUOY.name]:9.4f} (GS {r['rho_gs'][VESSEL.name]:8.4f} {r['rho_gs'][BUOY.name]:8.4f})"
              f"  ±1e-5: hang-off {r['hang_off']:.2e} m, swing {r['swing'] / 1e3:8.3f} kN, onset "
              f"{r['onset'] / 1e3:8.3f} kN  one-way {r['one_way'] / 1e3:7.3f} kN", flush=True)
        gs = lambda b: "" if np.isnan(r["rho_gs"][b.name]) else f" / {r['rho_gs'][b.name]:.4f}"  # noqa: E731
        body_rows.append([r["predictor"], f"{r['h']:g}", f"{r['gain'][VESSEL.name]:.3f}", f"{r['gain'][BUOY.name]:.3f}",
                          f"{r['rho'][VESSEL.name]:.4f}{gs(VESSEL)}",
                          f"{r['rho'][BUOY.name]:.4f}{gs(BUOY)}", f"{r['hang_off']:.1e}", f"{r['swing'] / 1e3:.3f}",
                          f"{r['onset'] / 1e3:.3f}", f"{r['one_way'] / 1e3:.3f}"])
    from . import report
    lines += report.table(head, body_rows)
    lines += ["", "![stable region](figures/coupling_stability.png)", ""]
    # the generated part ends where the hand-written sections (## …) begin: keep those
    doc = Path(args.docs) / "coupling.md"
    old = doc.read_text() if doc.exists() else ""
    tail = old[old.index("\n## ") + 1:] if "\n## " in old else ""
    doc.write_text("\n".join(lines) + "\n\n" + tail)
    plot(rows, resp, Path(args.docs) / "figures" / "coupling_stability.png")
    return 0


if __name__ == "__main__":
    main()
