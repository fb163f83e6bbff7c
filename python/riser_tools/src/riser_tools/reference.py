"""Closed-form references, ported from tests/it/common/reference.rs (the Rust
tests' independent solutions; plain Python and math here too, sharing no code
with riser or MoorDyn).

Conventions (as in the Rust): the top (hang-off) at the origin, x horizontal
from the top towards the anchor, z up; s the unstretched arc length from the
top; loads per unit unstretched length, positive downward. `h` > 0 the
horizontal tension; `v_top` > 0 when the line pulls the vessel down;
`v_bottom` > 0 when it pulls the anchor up.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


class ReferenceError(ValueError):
    """A reference refused its input (the message names the argument) or found no solution."""


def _positive(name: str, value: float) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise ReferenceError(f"{name} = {value!r}: expected a finite number > 0")


def _finite(name: str, value: float) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value)):
        raise ReferenceError(f"{name} = {value!r}: expected a finite number")


@dataclass(frozen=True)
class CatenaryForces:
    h: float
    v_top: float
    v_bottom: float

    @property
    def top_tension(self) -> float:
        return math.hypot(self.h, self.v_top)

    @property
    def bottom_tension(self) -> float:
        return math.hypot(self.h, self.v_bottom)


def _irvine(length: float, w: float, ea: float, h: float, va: float) -> tuple[list[float], list[list[float]]]:
    """Irvine (1981) eqs. 2.18/2.19 from the anchor end: [span, rise] and d/d[h, va]."""
    vt = va + w * length
    ta, tt = math.hypot(h, va), math.hypot(h, vt)
    dasinh = math.asinh(vt / h) - math.asinh(va / h)
    span = h * length / ea + h / w * dasinh
    rise = (tt - ta) / w + (vt * vt - va * va) / (2.0 * w * ea)
    jac = [[length / ea + dasinh / w - (vt / tt - va / ta) / w, h / w * (1.0 / tt - 1.0 / ta)],
           [h / w * (1.0 / tt - 1.0 / ta), (vt / tt - va / ta) / w + length / ea]]
    return [span, rise], jac


def elastic_catenary(length: float, w: float, ea: float, span_h: float, dz: float) -> CatenaryForces:
    """Irvine's extensible elastic catenary between the top and an anchor `span_h` m away
    horizontally and `dz` m above the top (e.g. -70), without seabed: its end forces, by
    damped Newton with the analytic Jacobian from a Peyrot-Goulois start (relative step 1e-13)."""
    _positive("length", length)
    _positive("w", w)
    _positive("ea", ea)
    _positive("span_h", span_h)
    _finite("dz", dz)
    rise = -dz
    chord = math.hypot(span_h, rise)
    lam = 0.2 if length <= chord else math.sqrt(3.0 * ((length ** 2 - rise ** 2) / span_h ** 2 - 1.0))
    h = abs(w * span_h / (2.0 * lam))
    va = 0.5 * w * (rise / math.tanh(lam) + length) - w * length
    scale = max(length, span_h, abs(rise))

    def residual(h: float, va: float) -> list[float] | None:
        try:
            p, _ = _irvine(length, w, ea, h, va)
        except (ValueError, ZeroDivisionError, OverflowError):
            return None
        r = [p[0] - span_h, p[1] - rise]
        return r if all(math.isfinite(x) for x in r) else None

    r = residual(h, va)
    if r is None:
        raise ReferenceError("elastic_catenary: no residual at the start")
    for _ in range(200):
        norm = math.hypot(*r)
        if norm <= 1e-11 * scale:
            break
        _, j = _irvine(length, w, ea, h, va)
        det = j[0][0] * j[1][1] - j[0][1] * j[1][0]
        if det == 0 or not math.isfinite(det):
            raise ReferenceError("elastic_catenary: singular Jacobian")
        dh = -(j[1][1] * r[0] - j[0][1] * r[1]) / det
        dv = -(-j[1][0] * r[0] + j[0][0] * r[1]) / det
        step = 1.0
        for _ in range(60):
            hn, vn = h + step * dh, va + step * dv
            rn = residual(hn, vn) if hn > 0 else None
            if rn is not None and math.hypot(*rn) < norm:
                break
            step *= 0.5
        else:
            raise ReferenceError("elastic_catenary: the line search failed")
        h, va, r = hn, vn, rn
        if abs(step * dh) <= 1e-13 * abs(h) and abs(step * dv) <= 1e-13 * max(abs(va), w * length):
            break
    else:
        raise ReferenceError("elastic_catenary: Newton did not converge")
    return CatenaryForces(h=h, v_top=va + w * length, v_bottom=va)


def elastic_catenary_shape(w: float, ea: float, forces: CatenaryForces, s: float) -> tuple[float, float]:
    """(x, z) at unstretched arc length s from the top, integrated from the top."""
    h, vt = forces.h, forces.v_top
    vs = vt - w * s
    x = h * s / ea + h / w * (math.asinh(vt / h) - math.asinh(vs / h))
    z = -((vt * s - 0.5 * w * s * s) / ea + (math.hypot(h, vt) - math.hypot(h, vs)) / w)
    return x, z


def elastic_catenary_tension(w: float, forces: CatenaryForces, s: float) -> float:
    """Tension magnitude at unstretched arc length s from the top."""
    return math.hypot(forces.h, forces.v_top - w * s)


@dataclass(frozen=True)
class SeabedCatenary:
    h: float
    v_top: float
    lying: float


def catenary_on_seabed(length: float, w: float, ea: float, span_h: float, depth: float) -> SeabedCatenary:
    """The elastic catenary whose lower part rests on a flat, frictionless, rigid seabed
    (MoorPy's catenary() with CB = 0): the fairlead `depth` m above the seabed, the anchor on
    it `span_h` m away. L_B = L - V/w, X = L_B + (H/w) asinh(V/H) + H L/EA,
    Z = (H/w)(sqrt(1 + (V/H)^2) - 1) + V^2/(2 EA w); nested bisection."""
    _positive("length", length)
    _positive("w", w)
    _positive("ea", ea)
    _positive("span_h", span_h)
    _positive("depth", depth)

    def z_of(h: float, v: float) -> float:
        return h / w * (math.sqrt(1.0 + (v / h) ** 2) - 1.0) + v * v / (2.0 * ea * w)

    def v_of(h: float) -> float:
        lo, hi = 0.0, w * length
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if z_of(h, mid) < depth:
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi)

    def x_of(h: float) -> float:
        v = v_of(h)
        return length - v / w + h / w * math.asinh(v / h) + h * length / ea

    lo, hi = 1e-9 * w * length, 1e3 * w * length
    if x_of(lo) > span_h or x_of(hi) < span_h:
        raise ReferenceError(f"catenary_on_seabed: no touchdown solution for span {span_h} m")
    for _ in range(300):
        mid = math.sqrt(lo * hi)
        if x_of(mid) < span_h:
            lo = mid
        else:
            hi = mid
    h = math.sqrt(lo * hi)
    v = v_of(h)
    if v >= w * length * (1.0 - 1e-12):
        raise ReferenceError("catenary_on_seabed: the whole line is suspended")
    return SeabedCatenary(h=h, v_top=v, lying=length - v / w)
