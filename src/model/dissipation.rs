//! Controlled high-frequency dissipation (docs/theory.md §5.10): the pieces
//! of the energy-decaying, momentum-conserving variant of the midpoint scheme
//! that both line models share.
//!
//! Two ingredients, each switched on by a lagged "saw-tooth" weight in [0, 1]
//! that is 1 for a quantity alternating from step to step (an unresolved
//! mode, ω·h ≫ 1) and O((ω h)²) for a resolved one:
//! - a stress α w_f C Δε added to the midpoint stress (a Kelvin–Voigt stress
//!   whose time is α w_f h), dissipating α w_f Δε·C Δε ≥ 0;          (5.31)
//! - a filter of the new velocities, v_{n+1} = v* − s τ w_v (v* − v_n)/2,
//!   with v* the midpoint rule's velocity; s ∈ [0, 1] keeps the kinetic
//!   energy from growing, and on a free line the rigid part of the
//!   correction is removed so that both momenta are kept exactly.    (5.32)
//!
//! A force-only term cannot give ρ∞ < 1: the midpoint rule keeps a branch
//! v_{n+1} = −v_n with Δq = 0 on which no force does work; the filter takes it.
//! With saturated weights α = (1 − ρ∞)/(2(1 + ρ∞)) and τ = 1 − ρ∞ make the
//! spectral radius at ω h → ∞ equal to ρ∞ (both branches).       (5.33)

use crate::math::V3;
use crate::model::sections::PerElement;
use nalgebra::{Matrix6, Vector6};

/// The scheme's parameters for a high-frequency spectral radius ρ∞ ∈ (0, 1].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HighFrequency {
    /// Stress factor α (dimensionless).
    pub alpha: f64,
    /// Velocity filter factor τ (dimensionless).
    pub tau: f64,
}

impl HighFrequency {
    /// (5.33); `None` for ρ∞ = 1 (the conserving scheme, untouched).
    pub fn new(rho_infinity: f64) -> Option<Self> {
        if rho_infinity >= 1.0 {
            return None;
        }
        let r = rho_infinity;
        Some(HighFrequency { alpha: (1.0 - r) / (2.0 * (1.0 + r)), tau: 1.0 - r })
    }
}

/// The saw-tooth detector min(1, |a − b|² / max(|a|², |b|²)) of two
/// successive increments (vectors of triples): 1 when they alternate
/// (a·b ≤ 0), ≈ (h q⃛/q̈)² for a smooth history; 0 without history.
pub fn sawtooth<'a>(a: impl IntoIterator<Item = &'a V3>, b: impl IntoIterator<Item = &'a V3>) -> f64 {
    let (mut d, mut na, mut nb) = (0.0, 0.0, 0.0);
    for (x, y) in a.into_iter().zip(b) {
        d += (x - y).norm_squared();
        na += x.norm_squared();
        nb += y.norm_squared();
    }
    let m = f64::max(na, nb);
    if m > 0.0 { (d / m).min(1.0) } else { 0.0 }
}

/// Stress weight of an element for the next step, from the displacement
/// increments (as mean velocities) of its nodes over the last two steps:
/// the square root of the saw-tooth detector (a strong, early response).
pub fn stress_weight(last: [&V3; 2], before: [&V3; 2]) -> f64 {
    sawtooth(last, before).sqrt()
}

/// Velocity-filter weight of a node for the next step, from its velocity
/// increments over the last two steps (as accelerations): the square of the
/// detector (so that a resolved motion is filtered as O(h⁴) only).
pub fn filter_weight(last: &V3, before: &V3) -> f64 {
    sawtooth([last], [before]).powi(2)
}

/// The filter's scale s ∈ [0, 1] for a correction d of the velocities v*
/// (5.32): ΔT = s d·M v* + ½ s² d·M d ≤ 0. Returns (s, energy removed, J).
pub fn filter_scale(d_m_v: f64, d_m_d: f64) -> (f64, f64) {
    // (a NaN or non-positive d·M d: no filter)
    if d_m_d.is_nan() || d_m_d <= 0.0 || d_m_v >= 0.0 {
        return (0.0, 0.0);
    }
    let s = (-2.0 * d_m_v / d_m_d).min(1.0);
    (s, -(s * d_m_v + 0.5 * s * s * d_m_d))
}

/// The rigid velocity (u, ω) to subtract from a correction so that it changes
/// neither momentum: solves `a` (u, ω) = (p, l), `a`'s columns the momenta
/// (linear; angular about the origin) of the six unit rigid fields, (p, l)
/// those of the correction. None if `a` is singular (a line of one point).
pub fn rigid_part(a: &Matrix6<f64>, p: V3, l: V3) -> Option<(V3, V3)> {
    let rhs = Vector6::new(p.x, p.y, p.z, l.x, l.y, l.z);
    let x = a.lu().solve(&rhs)?;
    Some((V3::new(x[0], x[1], x[2]), V3::new(x[3], x[4], x[5])))
}

/// How a line's velocity triples make up its elements, for the filter: the
/// element mass matrix (scalar factors of I3) over the element's K triples,
/// triple k of element e at index `start[k] + e`; triples below
/// `n_positions` are node velocities (the others slope velocities, which a
/// rigid translation leaves unchanged).
#[derive(Debug, Clone)]
pub struct TripleLayout<const K: usize> {
    pub mass: PerElement<[[f64; K]; K]>,
    pub start: [usize; K],
    pub n_el: usize,
    pub n_positions: usize,
}

impl<const K: usize> TripleLayout<K> {
    /// a·M b over the line.
    pub fn m_dot(&self, a: &[V3], b: &[V3]) -> f64 {
        let mut t = 0.0;
        for e in 0..self.n_el {
            let mass = self.mass.at(e);
            for k in 0..K {
                for l in 0..K {
                    t += mass[k][l] * a[self.start[k] + e].dot(&b[self.start[l] + e]);
                }
            }
        }
        t
    }

    /// Linear momentum and angular momentum about the origin of the velocity
    /// field `w` on the configuration `c` (positions and slopes as triples).
    pub fn momenta(&self, c: &[V3], w: impl Fn(usize) -> V3) -> (V3, V3) {
        let (mut p, mut l) = (V3::zeros(), V3::zeros());
        for e in 0..self.n_el {
            let mass = self.mass.at(e);
            for k in 0..K {
                let (ik, mut mw) = (self.start[k] + e, V3::zeros());
                for m in 0..K {
                    mw += w(self.start[m] + e) * mass[k][m];
                }
                if ik < self.n_positions {
                    p += mw;
                }
                l += c[ik].cross(&mw);
            }
        }
        (p, l)
    }

    /// The rigid velocity field u + ω × x (slopes: ω × r') at triple i.
    fn rigid(&self, c: &[V3], u: &V3, omega: &V3, i: usize) -> V3 {
        let w = omega.cross(&c[i]);
        if i < self.n_positions { w + u } else { w }
    }

    /// The velocity filter (5.32) of the midpoint velocities `vs` (m/s, and
    /// 1/s for slopes), in place: d = −τ w (v* − v_n)/2 on the free triples
    /// (`weight` the lagged weights), without its rigid part on a `free`
    /// line, scaled so that the kinetic energy cannot grow. `c` the new
    /// configuration's triples; `d` scratch. Returns the energy removed, J.
    #[allow(clippy::too_many_arguments)]
    pub fn filter(
        &self,
        c: &[V3],
        v0: &[V3],
        vs: &mut [V3],
        weight: &[f64],
        fixed: &[bool],
        free: bool,
        tau: f64,
        d: &mut [V3],
    ) -> f64 {
        let mut any = false;
        for i in 0..vs.len() {
            d[i] = if fixed[i] { V3::zeros() } else { (vs[i] - v0[i]) * (-0.5 * tau * weight[i]) };
            any |= weight[i] > 0.0;
        }
        if !any {
            return 0.0;
        }
        if free {
            let mut a = Matrix6::zeros();
            for j in 0..6 {
                let mut u = V3::zeros();
                let mut omega = V3::zeros();
                if j < 3 {
                    u[j] = 1.0
                } else {
                    omega[j - 3] = 1.0
                }
                let (pj, lj) = self.momenta(c, |i| self.rigid(c, &u, &omega, i));
                for r in 0..3 {
                    a[(r, j)] = pj[r];
                    a[(r + 3, j)] = lj[r];
                }
            }
            // twice: the second pass removes the round-off of the first
            // (momenta are kept to ~1e-16 per step, not to cond(a)·1e-16)
            for _ in 0..2 {
                let (p, l) = self.momenta(c, |i| d[i]);
                if let Some((u, omega)) = rigid_part(&a, p, l) {
                    for (i, di) in d.iter_mut().enumerate() {
                        *di -= self.rigid(c, &u, &omega, i);
                    }
                }
            }
        }
        let (s, removed) = filter_scale(self.m_dot(d, vs), self.m_dot(d, d));
        if s > 0.0 {
            for (v, di) in vs.iter_mut().zip(d.iter()) {
                *v += di * s;
            }
        }
        removed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_detector_separates_alternating_from_smooth_increments() {
        let a = V3::new(1.0, 0.0, 0.0);
        assert_eq!(sawtooth([&a], [&(-a)]), 1.0);
        assert_eq!(sawtooth([&a], [&a]), 0.0);
        assert_eq!(sawtooth([&V3::zeros()], [&V3::zeros()]), 0.0);
        // a smooth history: relative change 1e-2 → 1e-4
        let w = sawtooth([&(a * 1.01)], [&a]);
        assert!((w - 1e-4 / 1.0201).abs() < 1e-12, "{w}");
    }

    #[test]
    fn the_filter_never_adds_energy_and_is_exact_where_unclipped() {
        // d = −v* τ: T(v* + s d) = (1 − τ)² T(v*) for s = 1
        let (s, de) = filter_scale(-0.5 * 2.0, 0.25 * 2.0);
        assert_eq!(s, 1.0);
        assert!((de - (1.0 - 0.25) * 1.0).abs() < 1e-15);
        assert_eq!(filter_scale(1.0, 1.0), (0.0, 0.0));
        let (s, de) = filter_scale(-1.0, 10.0);
        assert!((s - 0.2).abs() < 1e-15 && de.abs() < 1e-15);
    }

    #[test]
    fn parameters_give_the_asked_radius_on_both_branches() {
        for r in [0.0, 0.3, 0.8] {
            let p = HighFrequency::new(r).unwrap();
            // displacement branch: (1 − 2α)/(1 + 2α) = ρ; velocity branch 1 − τ = ρ
            assert!(((1.0 - 2.0 * p.alpha) / (1.0 + 2.0 * p.alpha) - r).abs() < 1e-15);
            assert!((1.0 - p.tau - r).abs() < 1e-15);
        }
        assert!(HighFrequency::new(1.0).is_none());
    }
}
