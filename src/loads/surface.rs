//! The free surface (docs/theory.md §10): the line above the water carries
//! its weight in air, without buoyancy, drag, added mass or current.
//!
//! The vertical load q of [`super::weight`] counts the buoyancy ρ_w g A of the
//! whole line (a line below the surface everywhere). Above the surface
//! z_s the buoyancy is taken off again by a correction whose potential per
//! unit reference length is
//!
//!   V_s(z) = ρ_w g A R(z − z_s),   R(x) = ∫_{−∞}^x H(t) dt           (10.1)
//!
//! with H the submerged part's complement: 0 below −ε, 1 above ε, linear in
//! between (R is then 0, (x + ε)²/(4ε), x on the three pieces: C¹). The
//! buoyancy thus fades over a band of half-width ε = max(D/2, 5 cm) about
//! the surface, where a vertical line's section is partly submerged. The
//! force is integrated with a composite rule: an element is cut into
//! sub-intervals no longer than ε (at most 200), four Gauss points each, so
//! that the band is resolved on any mesh and the force is a smooth enough
//! function of the unknowns for Newton. Along a straight line crossing the
//! band the total buoyancy is that of the sharp surface (the ramp is
//! symmetric).
//!
//! At each point the force is −n ρ_w g A H evaluated as the discrete
//! gradient (V_s(z₁) − V_s(z₀))/(z₁ − z₀) in a step (so that its work is
//! exactly −ΔV_s: the energy is conserved while the line crosses the
//! surface), and as V_s′(z) in statics. Drag and added mass are scaled by
//! the submerged fraction 1 − H at the point ([`mod@super::fluid`]).

use crate::math::shape::GAUSS4;
use crate::math::{M3, V3};

/// The free surface as the line feels it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeSurface {
    /// Height of the surface z_s, m.
    pub z: f64,
    /// Half-width ε of the band over which the buoyancy fades, m.
    pub half_width: f64,
    /// Buoyancy per unit reference length ρ_w g A, N/m.
    pub buoyancy: f64,
}

impl FreeSurface {
    /// The emerged fraction H(z − z_s) ∈ [0, 1] and its derivative in z, 1/m.
    pub fn emerged(&self, z: f64) -> (f64, f64) {
        let (x, e) = (z - self.z, self.half_width);
        if x <= -e {
            (0.0, 0.0)
        } else if x >= e {
            (1.0, 0.0)
        } else {
            ((x + e) / (2.0 * e), 1.0 / (2.0 * e))
        }
    }

    /// The submerged fraction 1 − H and its derivative in z, 1/m.
    pub fn submerged(&self, z: f64) -> (f64, f64) {
        let (h, dh) = self.emerged(z);
        (1.0 - h, -dh)
    }

    /// The correction's potential per unit length V_s(z) (10.1), J/m.
    pub fn potential(&self, z: f64) -> f64 {
        let (x, e) = (z - self.z, self.half_width);
        let r = if x <= -e {
            0.0
        } else if x >= e {
            x
        } else {
            (x + e) * (x + e) / (4.0 * e)
        };
        self.buoyancy * r
    }

    /// V_s′(z) and V_s″(z), N/m and N/m².
    pub fn static_slope(&self, z: f64) -> (f64, f64) {
        let (h, dh) = self.emerged(z);
        (self.buoyancy * h, self.buoyancy * dh)
    }

    /// The discrete gradient G = (V_s(z₁) − V_s(z₀))/(z₁ − z₀) and ∂G/∂z₁;
    /// V_s′ at the midpoint (and its exact derivative) where both points are
    /// on one piece (V_s is quadratic there) or too close for the quotient.
    pub fn discrete_slope(&self, z0: f64, z1: f64) -> (f64, f64) {
        let e = self.half_width;
        let piece = |z: f64| {
            let x = z - self.z;
            if x <= -e {
                0
            } else if x >= e {
                2
            } else {
                1
            }
        };
        if piece(z0) == piece(z1) || (z1 - z0).abs() <= 1e-9 * e {
            let (g, dg) = self.static_slope(0.5 * (z0 + z1));
            return (g, 0.5 * dg);
        }
        let g = (self.potential(z1) - self.potential(z0)) / (z1 - z0);
        let (v1, _) = self.static_slope(z1);
        (g, (v1 - g) / (z1 - z0))
    }

    /// The same surface `by` m lower (a bound of the band a moving surface
    /// sweeps: the tests below against it hold for every elevation ≥ −`by`).
    pub fn lowered(&self, by: f64) -> FreeSurface {
        FreeSurface { z: self.z - by, ..*self }
    }

    /// True if no point of an element whose nodes are at `nodes` reaches the
    /// band: every node more than ε + `margin` m below the surface.
    pub fn below(&self, nodes: &[V3], margin: f64) -> bool {
        nodes.iter().all(|x| x.z < self.z - self.half_width - margin)
    }

    /// True if no point of a cubic Hermite element with dofs `c` = [x_a,
    /// x′_a, x_b, x′_b] and length `h` reaches the band: the largest height
    /// of its centreline, the cubic z(ξ) = z_a + h z′_a ξ + C ξ² + D ξ³, at
    /// its ends and where z′(ξ) = 0 inside, lies below z_s − ε. Exact, so
    /// that an element whose points would all be skipped is skipped whole.
    pub fn hermite_below(&self, c: &[V3; 4], h: f64) -> bool {
        let low = self.z - self.half_width;
        let (za, ta, zb, tb) = (c[0].z, h * c[1].z, c[2].z, h * c[3].z);
        if za >= low || zb >= low {
            return false;
        }
        // the centreline departs from its chord by at most h (|x′| ≈ 1): far below, no cubic needed
        if za.max(zb) < low - h {
            return true;
        }
        // z(ξ) = za + ta ξ + q ξ² + r ξ³ (the Hermite functions' coefficients)
        let q = -3.0 * za - 2.0 * ta + 3.0 * zb - tb;
        let r = 2.0 * za + ta - 2.0 * zb + tb;
        let z = |xi: f64| za + xi * (ta + xi * (q + xi * r));
        // z′(ξ) = ta + 2q ξ + 3r ξ² = 0
        let (a, b, cc) = (3.0 * r, 2.0 * q, ta);
        let roots: [f64; 2] = if a.abs() < 1e-300 {
            if b.abs() < 1e-300 { [f64::NAN; 2] } else { [-cc / b, f64::NAN] }
        } else {
            let disc = b * b - 4.0 * a * cc;
            if disc < 0.0 {
                [f64::NAN; 2]
            } else {
                let sq = disc.sqrt();
                [(-b - sq) / (2.0 * a), (-b + sq) / (2.0 * a)]
            }
        };
        roots.iter().filter(|xi| (0.0..=1.0).contains(*xi)).all(|&xi| z(xi) < low)
    }
}

/// Points of the composite rule over an element of `len` m: `m` equal
/// sub-intervals of at most the band's half-width ε (at most 200), four
/// Gauss points each, so that the band is resolved whatever the mesh:
/// (ξ, weight in units of `len`).
fn points(s: &FreeSurface, len: f64) -> impl Iterator<Item = (f64, f64)> {
    let m = (len / s.half_width).ceil().clamp(1.0, 200.0) as usize;
    (0..m).flat_map(move |i| (0..4).map(move |g| ((i as f64 + GAUSS4.xi[g]) / m as f64, GAUSS4.w[g] / m as f64)))
}

/// Adds one point's force −dv e_z (weight `wg`, m; shape values `n`) to the
/// nodal forces and its derivative ddv to −∂F/∂c.
fn add_point<const K: usize>(n: &[f64; K], wg: f64, dv: f64, ddv: f64, f: &mut [V3; K], k: Option<&mut [[M3; K]; K]>) {
    for i in 0..K {
        f[i].z -= dv * wg * n[i];
    }
    if let Some(k) = k {
        for i in 0..K {
            for j in 0..K {
                k[i][j][(2, 2)] += ddv * wg * n[i] * n[j];
            }
        }
    }
}

/// Adds the surface correction's consistent nodal force of one element over
/// a step (the discrete gradient at the points of the composite rule) to
/// `f`, N, and −∂F/∂c₁ to `k`; `c0`, `c1` the dofs at t_n and the trial
/// t_{n+1}, `shape(ξ)` the element's shape functions, `len` its length, m.
///
/// In waves `elevation(ξ)` is the surface's elevation η above the point,
/// held over the step (docs/theory.md §13.6): the correction is cut at
/// z_s + η, V_s(z − η), and the return value is the work the moving
/// surface did on the line over the step, J: the total energy keeps the
/// still-water potential V_s(z), so the water's work is
/// [V_s(z₁) − V_s(z₀)] − [V_s(z₁ − η) − V_s(z₀ − η)] (13.13). Still water: 0.
#[allow(clippy::too_many_arguments)]
pub fn element_step_force<const K: usize>(
    s: &FreeSurface,
    c0: &[V3; K],
    c1: &[V3; K],
    shape: impl Fn(f64) -> [f64; K],
    len: f64,
    elevation: Option<&dyn Fn(f64) -> f64>,
    f: &mut [V3; K],
    mut k: Option<&mut [[M3; K]; K]>,
) -> f64 {
    let low = s.z - s.half_width;
    let mut work = 0.0;
    for (xi, w) in points(s, len) {
        let n = shape(xi);
        let (mut z0, mut z1) = (0.0, 0.0);
        for j in 0..K {
            z0 += c0[j].z * n[j];
            z1 += c1[j].z * n[j];
        }
        let eta = elevation.map_or(0.0, |e| e(xi));
        if z0.max(z1) <= low + eta.min(0.0) {
            continue;
        }
        let (dv, ddv) = s.discrete_slope(z0 - eta, z1 - eta);
        add_point(&n, w * len, dv, ddv, f, k.as_deref_mut());
        if eta != 0.0 {
            let still = s.potential(z1) - s.potential(z0);
            let cut = s.potential(z1 - eta) - s.potential(z0 - eta);
            work += w * len * (still - cut);
        }
    }
    work
}

/// The static force of the correction on one element at dofs `c` (V_s′ at
/// the points of the composite rule) added to `f`, N, and −∂F/∂c to `k`;
/// in waves cut at the elevation `elevation(ξ)` above each point, m.
pub fn element_static_force<const K: usize>(
    s: &FreeSurface,
    c: &[V3; K],
    shape: impl Fn(f64) -> [f64; K],
    len: f64,
    elevation: Option<&dyn Fn(f64) -> f64>,
    f: &mut [V3; K],
    mut k: Option<&mut [[M3; K]; K]>,
) {
    let low = s.z - s.half_width;
    for (xi, w) in points(s, len) {
        let n = shape(xi);
        let eta = elevation.map_or(0.0, |e| e(xi));
        let z: f64 = (0..K).map(|j| c[j].z * n[j]).sum::<f64>() - eta;
        if z <= low {
            continue;
        }
        let (dv, ddv) = s.static_slope(z);
        add_point(&n, w * len, dv, ddv, f, k.as_deref_mut());
    }
}

/// The correction's energy ∫ V_s dS of one element at dofs `c` (the same
/// composite rule), J.
pub fn element_energy<const K: usize>(s: &FreeSurface, c: &[V3; K], shape: impl Fn(f64) -> [f64; K], len: f64) -> f64 {
    points(s, len)
        .map(|(xi, w)| {
            let n = shape(xi);
            let z: f64 = (0..K).map(|j| c[j].z * n[j]).sum();
            w * len * s.potential(z)
        })
        .sum()
}

/// Shape functions of a straight two-node segment at ξ.
pub fn linear(xi: f64) -> [f64; 2] {
    [1.0 - xi, xi]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn surface() -> FreeSurface {
        FreeSurface { z: 5.0, half_width: 0.5, buoyancy: 800.0 }
    }

    /// `hermite_below` against the Hermite centreline sampled at 20001
    /// points, for elements of every shape near the band (a deterministic
    /// pseudo-random set): the same answer wherever the sampled maximum is
    /// not within 1e-6 m of the band's edge.
    #[test]
    fn hermite_below_is_the_centrelines_largest_height() {
        let s = surface();
        let low = s.z - s.half_width;
        let mut next = crate::loads::uniform_stream(0x9e37_79b9_7f4a_7c15);
        let (mut agree, mut above) = (0, 0);
        for _ in 0..2000 {
            let h = 20.0 * (next() + 1.1);
            let c = [
                V3::new(0.0, 0.0, low - 8.0 * (next() + 1.0)),
                V3::new(next(), next(), next()).normalize(),
                V3::new(h, 0.0, low - 8.0 * (next() + 1.0)),
                V3::new(next(), next(), next()).normalize(),
            ];
            let top = (0..=20000)
                .map(|i| {
                    let n = crate::math::shape::hermite(i as f64 / 20000.0, h);
                    (0..4).map(|k| c[k].z * n[k]).sum::<f64>()
                })
                .fold(f64::NEG_INFINITY, f64::max);
            if (top - low).abs() < 1e-6 {
                continue;
            }
            assert_eq!(s.hermite_below(&c, h), top < low, "top {top} vs {low}: {c:?}, h {h}");
            agree += 1;
            above += usize::from(top >= low);
        }
        // both answers occur, and the nodes alone would call many of the bulging ones below
        assert!(agree > 1900 && above > 100, "{agree} compared, {above} reach the band");
    }

    #[test]
    fn the_discrete_gradient_gives_the_energy_difference() {
        let s = surface();
        for (z0, z1) in [(3.0, 4.0), (4.7, 4.9), (4.2, 5.2), (5.8, 4.9), (4.0, 7.0), (6.0, 6.5), (4.6, 4.6)] {
            let (g, _) = s.discrete_slope(z0, z1);
            if z1 != z0 {
                let de = s.potential(z1) - s.potential(z0);
                assert!((g * (z1 - z0) - de).abs() <= 1e-12 * de.abs().max(1.0), "{z0} {z1}");
            }
        }
    }

    #[test]
    fn the_slope_derivative_matches_finite_differences() {
        let s = surface();
        for (z0, z1) in [(4.2, 5.2), (5.8, 4.9), (4.0, 7.0), (4.6, 4.8), (4.9, 6.0)] {
            let (_, dg) = s.discrete_slope(z0, z1);
            let e = 1e-6;
            let fd = (s.discrete_slope(z0, z1 + e).0 - s.discrete_slope(z0, z1 - e).0) / (2.0 * e);
            assert!((fd - dg).abs() <= 1e-6 * s.buoyancy, "{z0} {z1}: {fd} vs {dg}");
        }
    }

    #[test]
    fn a_straight_line_through_the_band_loses_the_emerged_buoyancy() {
        // a vertical segment from z = 0 to 8 through the band at 5 ± 0.5:
        // 3 m emerged; its nodal forces add up to −3 ρgA, wherever the
        // band falls in the composite rule's sub-intervals
        let s = surface();
        for top in [8.0, 8.13, 8.377] {
            let mut f = [V3::zeros(); 2];
            let c = [V3::new(0.0, 0.0, 0.0), V3::new(0.0, 0.0, top)];
            element_static_force(&s, &c, linear, top, None, &mut f, None);
            let lost = -(f[0].z + f[1].z) / s.buoyancy;
            assert!((lost - (top - 5.0)).abs() < 2e-3, "{top}: {lost}");
        }
    }
}
