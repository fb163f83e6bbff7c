"""A moored vessel's surge loop, linearised (issue 53; docs/coupling.md, "A moored vessel's chains in
the loop"; docs/theory.md §7.8).

One axis, libcosim's fixed step (Jacobi), uniform communication step h:

* the **vessel**: a mass M (with its added mass) that holds riser's force F_n over [t_n, t_{n+1}],
  integrated exactly; optionally its implicit step with an interface stiffness and damping,
  M x'' = F_n − k (x − x_n) − c (x' − x_n');
* riser's **input path** (src/fmi/input_path.rs): the end state of each step a filter of the
  displacement (and velocity) samples (`coupling_analysis.design_weights`, `both_weights`), the
  quintic Hermite path (7.2) from the last end state to it; optionally (`mhat`) the samples less the
  answer of a free mass mhat to riser's own force and that answer's end added back (§7.8), or the
  vessel's exact motion over the step (`exact`: Gauss–Seidel, the vessel first);
* the **chains**: the four of docs/cases/moored_vessel.toml as one axial bar of 2 EA and 2 μ (four at
  45°: Σ cos² = 2), fixed at the anchor, driven at the fairlead, 35 elements, undamped unless `zeta`,
  integrated exactly along the path (matrix exponentials); F_n = its force on the fairlead at t_n.

The loop is a linear map of the state over one step; the growth rate, per second, of its eigenvalues
above 0.3 Hz (the chains' modes, aliased) says whether the exchange feeds the chains' axial mode
(1.59 Hz). Run: `python -m riser_tools.coupling_chain` prints the table of docs/coupling.md.
"""
from __future__ import annotations

import math

import numpy as np

from . import coupling_analysis as ca

MASS = 1025.0 * 100.0 * 20.0 * 6.0 * 0.70 * 1.05  # Vessel6's surge mass with its added mass, kg
EA, MU, LENGTH, ELEMENTS = 384.243e6, 77.7066, 700.0, 35  # the chain of docs/cases/moored_vessel.toml
CHAINS = 2.0  # four chains at 45 degrees in surge
STEPS = [0.05, 0.075, 0.1, 0.125, 0.15, 0.175, 0.2, 0.25, 0.3, 0.4, 0.5]


def _expm(a: np.ndarray) -> np.ndarray:
    from scipy.linalg import expm
    return expm(a)


def bar(zeta: float = 0.0):
    """(A, b, k, n): y' = A y + b x(t) for the interior nodes' displacements and velocities of the
    bar driven at its first node by x(t); k = EA/l; n interior nodes; stiffness-proportional damping
    of `zeta` at the first mode."""
    l, n = LENGTH / ELEMENTS, ELEMENTS - 1
    k = CHAINS * EA / l
    stiff = np.diag(np.full(n, 2 * k)) - np.diag(np.full(n - 1, k), 1) - np.diag(np.full(n - 1, k), -1)
    m = CHAINS * MU * l
    w1 = math.pi / LENGTH * math.sqrt(EA / MU)
    a = np.zeros((2 * n, 2 * n))
    a[:n, n:] = np.eye(n)
    a[n:, :n] = -stiff / m
    a[n:, n:] = -(2 * zeta / w1) * stiff / m
    b = np.zeros(2 * n)
    b[n] = k / m
    return a, b, k, n


def _hermite_monomials() -> np.ndarray:
    """T (6 × 6): the path's coefficients in σ^j from (p, h p', h² p'', e0, e1, e2), (7.2)."""
    s = np.linspace(0, 1, 6)

    def h3(x):
        return np.array([1 - 10 * x ** 3 + 15 * x ** 4 - 6 * x ** 5, x - 6 * x ** 3 + 8 * x ** 4 - 3 * x ** 5,
                         0.5 * x ** 2 - 1.5 * x ** 3 + 1.5 * x ** 4 - 0.5 * x ** 5])
    vals = np.array([[*h3(x), h3(1 - x)[0], -h3(1 - x)[1], h3(1 - x)[2]] for x in s])
    return np.linalg.solve(np.vander(s, 6, increasing=True), vals)


def _step_maps(a: np.ndarray, b: np.ndarray, h: float):
    """Φ and G (columns: the bar's answer over h to the forcing b τ^k/k!, k = 0..5)."""
    n2 = a.shape[0]
    g = []
    for k in range(6):
        aug = np.zeros((n2 + 6, n2 + 6))
        aug[:n2, :n2] = a
        aug[:n2, n2 + k] = b
        for j in range(1, 6):
            aug[n2 + j, n2 + j - 1] = 1.0
        u0 = np.zeros(n2 + 6)
        u0[n2] = 1.0
        g.append((_expm(aug * h) @ u0)[:n2])
    return _expm(a * h), np.array(g).T


def weights(h: float):
    """(Wu, Wv) of riser's design at h with both inputs set (Wv in units of h v)."""
    if h >= ca.BOTH.min_h:
        return ca.both_weights()
    return ca.design_weights(h), np.zeros((3, 1))


def loop(h: float, zeta: float = 0.0, mass: float = MASS, mhat: float = 0.0, exact: bool = False,
         kint: float = 0.0, cint: float = 0.0, lead: float = 0.0) -> np.ndarray:
    """The loop's map over one step. `mhat` > 0: riser takes the answer of a free mass mhat to its
    own force (§7.8); `exact`: riser moves along the vessel's own motion; `kint`, `cint`: the
    vessel's implicit step with that interface stiffness and damping; `lead`: the force output led
    by lead·h times its rate."""
    a, b, k, n = bar(zeta)
    phi, g = _step_maps(a, b, h)
    t = _hermite_monomials()
    fac = np.array([math.factorial(j) / h ** j for j in range(6)])
    wu, wv = weights(h)
    nu, nv = wu.shape[1], wv.shape[1]
    ny = 2 * n
    ix, iv, ixh = ny, ny + 1, ny + 2
    ivh = ixh + nu - 1
    ip = ivh + nv - 1
    ir = ip + 3
    nr = 2 + (nu - 1) + (nv - 1) if mhat > 0 else 0
    irv, irh = ir + 1, ir + 2
    irvh = irh + nu - 1
    size = ir + nr
    mx = np.zeros((size, size))
    force = np.zeros(size)  # riser's output at t_n: k (q_1 − x_path(t_n))
    force[0], force[ip] = k, -k
    force[n] += lead * h * k
    force[ip + 1] -= lead * k
    # the vessel: M x'' = F_n − kint (x − x_n) − cint (x' − x_n'), exact over h
    if kint > 0 or cint > 0:
        e = _expm(np.array([[0.0, 1.0, 0.0], [-kint / mass, -cint / mass, 1.0 / mass], [0.0, 0.0, 0.0]]) * h)
        for r, idx in ((0, ix), (1, iv)):
            mx[idx, ix] = e[r, 0] + e[r, 2] * kint
            mx[idx, iv] = e[r, 1] + e[r, 2] * cint
            mx[idx] += e[r, 2] * force
    else:
        mx[ix, ix], mx[ix, iv] = 1.0, h
        mx[ix] += 0.5 * h * h / mass * force
        mx[iv, iv] = 1.0
        mx[iv] += h / mass * force
    # riser's end state from the samples
    end = np.zeros((3, size))
    xs, vs = [ix] + list(range(ixh, ixh + nu - 1)), [iv] + list(range(ivh, ivh + nv - 1))
    for j in range(3):
        for kk, c in enumerate(xs):
            end[j, c] += wu[j, kk]
        for kk, c in enumerate(vs):
            end[j, c] += wv[j, kk] * h
    if mhat > 0:
        xr, vr = [ir] + list(range(irh, irh + nu - 1)), [irv] + list(range(irvh, irvh + nv - 1))
        for j in range(3):
            for kk, c in enumerate(xr):
                end[j, c] -= wu[j, kk]
            for kk, c in enumerate(vr):
                end[j, c] -= wv[j, kk] * h
        end[0, ir] += 1.0
        end[0, irv] += h
        end[0] += 0.5 * h * h / mhat * force
        end[1, irv] += h
        end[1] += h * h / mhat * force
        end[2] += h * h / mhat * force
        mx[ir, ir], mx[ir, irv] = 1.0, h
        mx[ir] += 0.5 * h * h / mhat * force
        mx[irv, irv] = 1.0
        mx[irv] += h / mhat * force
        for first, last, src in ((irh, nu - 1, ir), (irvh, nv - 1, irv)):
            if last > 0:
                mx[first, src] = 1.0
                for kk in range(1, last):
                    mx[first + kk, first + kk - 1] = 1.0
    path = np.zeros((6, size))
    path[0:3, ip:ip + 3] = np.eye(3)
    if exact:
        end = np.array([mx[ix].copy(), h * mx[iv].copy(), h * h / mass * force])
        path[2] = h * h / mass * force
    path[3:6] = end
    mx[:ny, :ny] += phi
    mx[:ny] += g @ ((t @ path) * fac[:, None])
    mx[ip:ip + 3] = end
    for first, last, src in ((ixh, nu - 1, ix), (ivh, nv - 1, iv)):
        if last > 0:
            mx[first, src] = 1.0
            for kk in range(1, last):
                mx[first + kk, first + kk - 1] = 1.0
    return mx


def growth(h: float, fmin: float = 0.3, **kw) -> tuple[float, float]:
    """(growth rate 1/s, aliased frequency Hz) of the loop's fastest-growing mode above fmin Hz."""
    ev = np.linalg.eigvals(loop(h, **kw))
    with np.errstate(divide="ignore"):
        g = np.log(np.abs(ev)) / h
    f = np.abs(np.angle(ev)) / (2 * np.pi * h)
    i = int(np.argmax(np.where(f > fmin, g, -np.inf)))
    return float(g[i]), float(f[i])


def main(argv=None) -> int:
    rows = [("today", {}), ("riser given the vessel's mass (§7.8)", {"mhat": MASS}),
            ("the vessel's exact motion (Gauss-Seidel)", {"exact": True})]
    print("h (s): " + " ".join(f"{h:7.3f}" for h in STEPS))
    for name, kw in rows:
        print(f"{name}: " + " ".join(f"{growth(h, **kw)[0]:+7.3f}" for h in STEPS))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
