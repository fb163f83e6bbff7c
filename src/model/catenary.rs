//! The analytic start of the static solution: an extensible cable (no bending)
//! under a piecewise-constant vertical load between the hang-off and the anchor,
//! in the vertical plane through both ends (closed-form catenary segments,
//! e.g. Irvine, *Cable Structures*, 1981).
//!
//! With the internal force n = (H, n_z) (along increasing S), equilibrium
//! n' + q e_z = 0 gives H constant and n_z(S) = V0 − ∫₀ˢ q; the centreline
//! follows r' = (n/T)(1 + T/EA), T = |n|. On a segment of constant q, from
//! S_a to S (n_z from V_a to V):
//!   Δx = H ΔS/EA + (H/q)(asinh(V_a/H) − asinh(V/H))
//!   Δz = ½(V_a + V) ΔS/EA + (T_a − T)/q

use crate::loads::weight::VerticalLoad;

/// Solved cable: horizontal force and the vertical force at S = 0.
#[derive(Debug, Clone)]
pub struct Catenary {
    /// Horizontal component of the internal force, N (> 0 towards the anchor).
    pub h: f64,
    /// Vertical component of the internal force at S = 0, N.
    pub v0: f64,
    pub ea: f64,
    /// Segment boundaries (S) and the load on each segment (N/m, + up).
    breaks: Vec<f64>,
    loads: Vec<f64>,
}

/// Position (horizontal, vertical) and internal force (n_h, n_z) at S.
#[derive(Debug, Clone, Copy)]
pub struct CablePoint {
    pub x: f64,
    pub z: f64,
    pub n_h: f64,
    pub n_z: f64,
}

impl CablePoint {
    pub fn tension(&self) -> f64 {
        self.n_h.hypot(self.n_z)
    }
}

fn segment(h: f64, va: f64, q: f64, ds: f64, ea: f64) -> (f64, f64, f64) {
    let vb = va - q * ds;
    let ta = h.hypot(va);
    let tb = h.hypot(vb);
    if (q * ds).abs() <= 1e-9 * (ta + 1e-300) {
        // (nearly) unloaded segment: straight
        let dx = h * ds * (1.0 / ea + 1.0 / ta);
        let dz = 0.5 * (va + vb) * ds / ea + va / ta * ds;
        return (dx, dz, vb);
    }
    let dx = h * ds / ea + (h / q) * ((va / h).asinh() - (vb / h).asinh());
    let dz = 0.5 * (va + vb) * ds / ea + (ta - tb) / q;
    (dx, dz, vb)
}

impl Catenary {
    /// Point at reference arc length s.
    pub fn at(&self, s: f64) -> CablePoint {
        let (mut x, mut z, mut v) = (0.0, 0.0, self.v0);
        for k in 0..self.loads.len() {
            let a = self.breaks[k];
            let b = self.breaks[k + 1].min(s);
            if b <= a {
                break;
            }
            let (dx, dz, vb) = segment(self.h, v, self.loads[k], b - a, self.ea);
            x += dx;
            z += dz;
            v = vb;
        }
        CablePoint { x, z, n_h: self.h, n_z: v }
    }

    /// Solves for the cable of unstretched `length` with load `load`, axial
    /// stiffness `ea`, from (0, 0) to (`span`, `dz`) in its plane (span > 0).
    pub fn solve(length: f64, load: &VerticalLoad, ea: f64, span: f64, dz: f64) -> Option<Catenary> {
        if !(span > 0.0 && length > 0.0 && ea > 0.0) {
            return None;
        }
        let breaks = load.breakpoints(0.0, length);
        let loads: Vec<f64> = breaks.windows(2).map(|w| load.at(0.5 * (w[0] + w[1]))).collect();
        let total = load.total(length);
        let w = (total / length).abs().max(1e-6 * ea / length);
        // Peyrot & Goulois' start for the sag parameter
        let chord2 = span * span + dz * dz;
        let lambda = if length * length > chord2 {
            (3.0 * (length * length - dz * dz) / (span * span) - 1.0).max(1e-4).sqrt()
        } else {
            0.2
        };
        let h0 = (w * span / (2.0 * lambda)).max(1e-9);
        let mut u = [h0.ln(), h0 * dz / span + total / 2.0];
        let mut cat = Catenary { h: h0, v0: u[1], ea, breaks, loads };
        let resid = |cat: &mut Catenary, u: &[f64; 2]| -> [f64; 2] {
            cat.h = u[0].exp();
            cat.v0 = u[1];
            let p = cat.at(length);
            [p.x - span, p.z - dz]
        };
        let scale = length;
        let mut f = resid(&mut cat, &u);
        for _ in 0..200 {
            let norm = f[0].hypot(f[1]);
            if !norm.is_finite() {
                return None;
            }
            if norm <= 1e-12 * scale {
                resid(&mut cat, &u);
                return Some(cat);
            }
            // finite-difference Jacobian of this 2 × 2 start-up problem
            let mut jac = [[0.0; 2]; 2];
            let steps = [1e-7, 1e-7 * (u[1].abs() + cat.h)];
            for j in 0..2 {
                let mut up = u;
                up[j] += steps[j];
                let fp = resid(&mut cat, &up);
                for i in 0..2 {
                    jac[i][j] = (fp[i] - f[i]) / steps[j];
                }
            }
            let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
            if det == 0.0 || !det.is_finite() {
                return None;
            }
            let du = [(-f[0] * jac[1][1] + f[1] * jac[0][1]) / det, (-jac[0][0] * f[1] + jac[1][0] * f[0]) / det];
            // backtracking on |f|, with a bounded change of ln H
            let mut t = (1.0f64).min(1.0 / du[0].abs().max(1e-300));
            let mut accepted = false;
            for _ in 0..30 {
                let un = [u[0] + t * du[0], u[1] + t * du[1]];
                let fnew = resid(&mut cat, &un);
                let nn = fnew[0].hypot(fnew[1]);
                if nn.is_finite() && nn < norm {
                    u = un;
                    f = fnew;
                    accepted = true;
                    break;
                }
                t *= 0.5;
            }
            if !accepted {
                return None;
            }
        }
        None
    }
}

/// A line resting partly on a flat seabed (the start of the statics with a
/// seabed, docs/theory.md §9.3): the suspended catenary from the hang-off to
/// the touchdown, where its tangent is horizontal (n_z = 0), then the rest
/// lying straight from the touchdown to the anchor under the tension H.
#[derive(Debug, Clone)]
pub struct Touchdown {
    /// The suspended part, S ∈ [0, `suspended`].
    pub cat: Catenary,
    /// Its unstretched length L_s, m.
    pub suspended: f64,
    /// The touchdown point in the plane (horizontal, vertical), m.
    pub point: (f64, f64),
    /// Unit direction of the lying part in the plane, towards the anchor.
    pub direction: (f64, f64),
}

impl Touchdown {
    /// Solves for the line of unstretched `length` with load `load` from
    /// (0, 0) to the anchor at (`span`, `dz`), over a flat seabed at height
    /// `bed` (≤ dz) in the plane; None if the hanging catenary does not reach
    /// the seabed or no touchdown closes. Bisection on the lying length L_b:
    /// n_z at the end of the suspended part is > 0 for L_b = 0 (the line
    /// would dip below the seabed) and < 0 for a taut suspended part.
    pub fn solve(length: f64, load: &VerticalLoad, ea: f64, span: f64, dz: f64, bed: f64) -> Option<Touchdown> {
        let rise = dz - bed;
        if !(rise >= 0.0 && bed < 0.0) {
            return None;
        }
        // the suspended catenary for a lying length lb, and n_z at its end
        let part = |lb: f64| -> Option<(Catenary, f64, f64)> {
            let lying_h = if lb > rise { (lb * lb - rise * rise).sqrt() } else { 0.0 };
            let ls = length - lb;
            let cat = Catenary::solve(ls, load, ea, span - lying_h, bed)?;
            let nz = cat.at(ls).n_z;
            Some((cat, lying_h, nz))
        };
        let (_, _, nz0) = part(0.0)?;
        if nz0 <= 0.0 {
            return None;
        }
        let (mut lo, mut hi) = (0.0, length);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            match part(mid) {
                Some((_, _, nz)) if nz > 0.0 => lo = mid,
                _ => hi = mid,
            }
        }
        let (cat, lying_h, _) = part(lo)?;
        let ls = length - lo;
        let end = cat.at(ls);
        let (dxl, dzl) = (span - end.x, dz - end.z);
        let dl = dxl.hypot(dzl);
        let direction = if dl > 0.0 && lying_h > 0.0 { (dxl / dl, dzl / dl) } else { (1.0, 0.0) };
        Some(Touchdown { cat, suspended: ls, point: (end.x, end.z), direction })
    }

    /// Point (position and internal force) at reference arc length s.
    pub fn at(&self, s: f64) -> CablePoint {
        if s <= self.suspended {
            return self.cat.at(s);
        }
        let h = self.cat.h;
        let stretch = 1.0 + h / self.cat.ea;
        let ds = (s - self.suspended) * stretch;
        CablePoint {
            x: self.point.0 + self.direction.0 * ds,
            z: self.point.1 + self.direction.1 * ds,
            n_h: h * self.direction.0,
            n_z: h * self.direction.1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn catenary_reaches_the_anchor_and_balances_the_load() {
        let mut load = VerticalLoad::new(138.3, 0.332, 1025.0, 9.81);
        load.sections.push(crate::loads::weight::BuoyancySection { start: 50.0, end: 80.0, load: 670.0 });
        let c = Catenary::solve(100.0, &load, 4.58e8, 50.0, -40.0).expect("converges");
        let end = c.at(100.0);
        assert!((end.x - 50.0).abs() < 1e-9 && (end.z + 40.0).abs() < 1e-9);
        // vertical balance: n_z(L) = V0 − ∫q
        assert!((end.n_z - (c.v0 - load.total(100.0))).abs() < 1e-6);
    }
}
