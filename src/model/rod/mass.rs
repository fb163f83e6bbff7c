//! The constant mass operator of the director rod (docs/theory.md §5.1).
//!
//! From χ = r + X1 d1 + X2 d2 (paper eq. 1) the kinetic energy per length is
//!   T = ½ ρ̄ |ṙ|² + ½ J1 |ḋ1|² + ½ J2 |ḋ2|²     (J1 = ∫ρ X1² dA, J2 = ∫ρ X2² dA)
//! so in the coordinates (r_a, r'_a, d_iA) the mass matrix is constant: a
//! Hermite consistent mass for the centreline and a Lagrange mass for each
//! director. The elements are equal, so one element matrix serves them all.

use crate::math::shape::{GAUSS4, hermite, lagrange};
use crate::math::{M3, V3};

/// Element mass matrices (scalar factors of I3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementMass {
    /// ∫ ρ̄ N_k N_l dS over the element, Hermite dofs [r_a, r'_a, r_b, r'_b] (kg, kg m, kg m²).
    pub centre: [[f64; 4]; 4],
    /// ∫ L_A L_B dS over the element, director nodes [start, mid, end] (m).
    pub director: [[f64; 3]; 3],
    /// Rotary inertia per length J1, J2 of d1 and d2, kg m (J3 = 0).
    pub rotary: [f64; 2],
    /// ρ̄, kg/m.
    rho: f64,
}

impl ElementMass {
    /// Exact (4-point Gauss integrates the degree-6 products exactly).
    pub fn new(mass_per_length: f64, rotary: [f64; 2], h: f64) -> Self {
        let mut centre = [[0.0; 4]; 4];
        let mut director = [[0.0; 3]; 3];
        for g in 0..4 {
            let w = GAUSS4.w[g] * h;
            let n = hermite(GAUSS4.xi[g], h);
            let l = lagrange(GAUSS4.xi[g]);
            for k in 0..4 {
                for m in 0..4 {
                    centre[k][m] += w * mass_per_length * n[k] * n[m];
                }
            }
            for a in 0..3 {
                for b in 0..3 {
                    director[a][b] += w * l[a] * l[b];
                }
            }
        }
        ElementMass { centre, director, rotary, rho: mass_per_length }
    }

    /// Mass per length ρ̄, kg/m.
    pub fn mass_per_length(&self) -> f64 {
        self.rho
    }

    /// Kinetic energy of one element, J, from its Hermite velocities and director rates.
    pub fn kinetic_energy(&self, v: &[V3; 4], dd: &[M3; 3]) -> f64 {
        let mut t = 0.0;
        for k in 0..4 {
            for m in 0..4 {
                t += 0.5 * self.centre[k][m] * v[k].dot(&v[m]);
            }
        }
        for a in 0..3 {
            for b in 0..3 {
                for i in 0..2 {
                    t += 0.5 * self.rotary[i] * self.director[a][b] * dd[a].column(i).dot(&dd[b].column(i));
                }
            }
        }
        t
    }

    /// Linear momentum of one element, kg m/s.
    pub fn momentum(&self, v: &[V3; 4]) -> V3 {
        let mut p = V3::zeros();
        for k in 0..4 {
            for m in 0..4 {
                p += v[m] * self.centre[k][m] * if k == 0 || k == 2 { 1.0 } else { 0.0 };
            }
        }
        // ∫ ρ̄ ṙ dS = Σ_m (∫ ρ̄ N_m dS) v_m; Σ_k N_k over the value functions is 1
        p
    }

    /// Angular momentum of one element about the origin, kg m²/s:
    /// ∫ (r × ρ̄ ṙ + J1 d1 × ḋ1 + J2 d2 × ḋ2) dS.
    pub fn angular_momentum(&self, c: &[V3; 4], v: &[V3; 4], d: &[M3; 3], dd: &[M3; 3]) -> V3 {
        let mut l = V3::zeros();
        for k in 0..4 {
            for m in 0..4 {
                l += c[k].cross(&v[m]) * self.centre[k][m];
            }
        }
        for a in 0..3 {
            for b in 0..3 {
                for i in 0..2 {
                    let di: V3 = d[a].column(i).into();
                    l += di.cross(&dd[b].column(i)) * (self.rotary[i] * self.director[a][b]);
                }
            }
        }
        l
    }
}
