//! The element's residual kernel over its four Gauss points at once
//! (docs/theory.md §3.1, §5.2): the same sums as [`super::element`]'s strains
//! and B̃ᵀ s, with every field stored component-major, `[f64; 4]` over the
//! Gauss points, so that the arithmetic runs over the four points together
//! (two-wide SIMD on any x86-64) instead of on 3-vectors. The time step
//! evaluates the residual several times per step; this is its hot loop.

use super::dofs::{C_OFF, CYC, ElVec, ElemDofs, NGP, Shear, Strain, T_OFF};
use crate::math::V3;
use crate::math::shape::{GAUSS4, hermite, hermite_ds, lagrange, lagrange_ds};

/// A value at each of the four Gauss points.
pub type F4 = [f64; NGP];

/// Shape values at the Gauss points of an element of length h, and the
/// quadrature weights folded in (constant per mesh).
#[derive(Debug, Clone, Copy)]
pub struct GaussShapes {
    /// Hermite N_k(ξ_g) (the slope functions in m).
    pub n: [F4; 4],
    /// Hermite N'_k(ξ_g), 1/m.
    pub nds: [F4; 4],
    /// Lagrange L_A(ξ_g).
    pub l: [F4; 3],
    /// Lagrange L'_A(ξ_g), 1/m.
    pub dl: [F4; 3],
    /// w_g h N'_k, w_g h L_A, w_g h L'_A (the weighted rows of B̃ᵀ).
    wnds: [F4; 4],
    wl: [F4; 3],
    wdl: [F4; 3],
}

impl GaussShapes {
    pub fn new(h: f64) -> Self {
        let mut s = GaussShapes {
            n: [[0.0; NGP]; 4],
            nds: [[0.0; NGP]; 4],
            l: [[0.0; NGP]; 3],
            dl: [[0.0; NGP]; 3],
            wnds: [[0.0; NGP]; 4],
            wl: [[0.0; NGP]; 3],
            wdl: [[0.0; NGP]; 3],
        };
        for g in 0..NGP {
            let xi = GAUSS4.xi[g];
            let wg = GAUSS4.w[g] * h;
            let (n, nds, l, dl) = (hermite(xi, h), hermite_ds(xi, h), lagrange(xi), lagrange_ds(xi, h));
            for k in 0..4 {
                s.n[k][g] = n[k];
                s.nds[k][g] = nds[k];
                s.wnds[k][g] = wg * nds[k];
            }
            for a in 0..3 {
                s.l[a][g] = l[a];
                s.dl[a][g] = dl[a];
                s.wl[a][g] = wg * l[a];
                s.wdl[a][g] = wg * dl[a];
            }
        }
        s
    }
}

/// The interpolated fields r, r', d_i, d_i' at the four Gauss points
/// (`x[c]`, `p[c]`, `d[i][c]`, `dp[i][c]`: component c of the vector, over
/// the points; r for the water's forces, the rest for the strains).
/// They are linear in the element's dofs: the fields of q½ are the average
/// of those of q_n and q_{n+1}.
#[derive(Debug, Clone, Copy, Default)]
pub struct GaussFields {
    pub x: [F4; 3],
    pub p: [F4; 3],
    pub d: [[F4; 3]; 3],
    pub dp: [[F4; 3]; 3],
}

#[inline(always)]
fn dot4(a: &F4, b: &F4) -> f64 {
    (a[0] * b[0] + a[1] * b[1]) + (a[2] * b[2] + a[3] * b[3])
}

impl GaussFields {
    /// The fields of element `e`: r = Σ N_k c_k, r' = Σ N'_k c_k,
    /// d_i = Σ L_A d_iA, d_i' = Σ L'_A d_iA.
    #[inline]
    pub fn refresh(&mut self, sh: &GaussShapes, e: &ElemDofs) {
        for c in 0..3 {
            for g in 0..NGP {
                self.x[c][g] =
                    e.c[0][c] * sh.n[0][g] + e.c[1][c] * sh.n[1][g] + e.c[2][c] * sh.n[2][g] + e.c[3][c] * sh.n[3][g];
                self.p[c][g] = e.c[0][c] * sh.nds[0][g]
                    + e.c[1][c] * sh.nds[1][g]
                    + e.c[2][c] * sh.nds[2][g]
                    + e.c[3][c] * sh.nds[3][g];
            }
        }
        for i in 0..3 {
            for c in 0..3 {
                let (a0, a1, a2) = (e.d[0][(c, i)], e.d[1][(c, i)], e.d[2][(c, i)]);
                for g in 0..NGP {
                    self.d[i][c][g] = a0 * sh.l[0][g] + a1 * sh.l[1][g] + a2 * sh.l[2][g];
                    self.dp[i][c][g] = a0 * sh.dl[0][g] + a1 * sh.dl[1][g] + a2 * sh.dl[2][g];
                }
            }
        }
    }

    /// r at Gauss point g.
    #[inline]
    pub fn position(&self, g: usize) -> V3 {
        V3::new(self.x[0][g], self.x[1][g], self.x[2][g])
    }

    /// r' at Gauss point g.
    #[inline]
    pub fn slope(&self, g: usize) -> V3 {
        V3::new(self.p[0][g], self.p[1][g], self.p[2][g])
    }

    /// self ← ½(a + b).
    #[inline]
    pub fn set_average(&mut self, a: &GaussFields, b: &GaussFields) {
        for c in 0..3 {
            for g in 0..NGP {
                self.x[c][g] = 0.5 * (a.x[c][g] + b.x[c][g]);
                self.p[c][g] = 0.5 * (a.p[c][g] + b.p[c][g]);
            }
        }
        for i in 0..3 {
            for c in 0..3 {
                for g in 0..NGP {
                    self.d[i][c][g] = 0.5 * (a.d[i][c][g] + b.d[i][c][g]);
                    self.dp[i][c][g] = 0.5 * (a.dp[i][c][g] + b.dp[i][c][g]);
                }
            }
        }
    }

    /// Strains (γ or Γ, then K; element docs) at the Gauss points, `eps[row][g]`.
    #[inline]
    pub fn strains(&self, shear: Shear<'_>) -> [F4; 6] {
        let mut eps = [[0.0; NGP]; 6];
        match shear {
            Shear::Spatial(g0) => {
                // γ = r' − d3 − Σ_i g⁰_i d_i
                for c in 0..3 {
                    for g in 0..NGP {
                        eps[c][g] = self.p[c][g]
                            - self.d[2][c][g]
                            - self.d[0][c][g] * g0[g][0]
                            - self.d[1][c][g] * g0[g][1]
                            - self.d[2][c][g] * g0[g][2];
                    }
                }
            }
            Shear::Material => {
                // Γ_i = d_i·r' − δ_i3
                for i in 0..3 {
                    for g in 0..NGP {
                        eps[i][g] = self.d[i][0][g] * self.p[0][g]
                            + self.d[i][1][g] * self.p[1][g]
                            + self.d[i][2][g] * self.p[2][g];
                    }
                }
                for g in 0..NGP {
                    eps[2][g] -= 1.0;
                }
            }
        }
        // K_i = ½ (d_k·d_j' − d_j·d_k')
        for &(i, j, k) in &CYC {
            for g in 0..NGP {
                let mut v = 0.0;
                for c in 0..3 {
                    v += self.d[k][c][g] * self.dp[j][c][g] - self.d[j][c][g] * self.dp[k][c][g];
                }
                eps[3 + i][g] = 0.5 * v;
            }
        }
        eps
    }
}

/// Strain rows over the Gauss points → one strain vector per Gauss point.
#[inline]
pub fn to_points(eps: &[F4; 6]) -> [Strain; NGP] {
    let mut out = [[0.0; 6]; NGP];
    for g in 0..NGP {
        for r in 0..6 {
            out[g][r] = eps[r][g];
        }
    }
    out
}

/// One strain vector per Gauss point → strain rows over the Gauss points.
#[inline]
pub fn to_rows(eps: &[Strain; NGP]) -> [F4; 6] {
    let mut out = [[0.0; NGP]; 6];
    for g in 0..NGP {
        for r in 0..6 {
            out[r][g] = eps[g][r];
        }
    }
    out
}

/// Adds the internal force ∫ B̃(q_B)ᵀ s dS of the element to `r` (the
/// residual path of [`super::element::internal_force`]): `eb` the nodal
/// values of q_B, `kb` their fields at the Gauss points, `s[row][g]` the
/// stress resultants.
///
/// Every rotation row is a sum Σ_c d_cA × (vector) with the director columns
/// d_cA of node A, which do not depend on the Gauss point: the vectors are
/// summed over the points first and crossed once per element.
pub fn add_internal_force(
    eb: &ElemDofs,
    kb: &GaussFields,
    s: &[F4; 6],
    sh: &GaussShapes,
    shear: Shear<'_>,
    r: &mut ElVec,
) {
    let bend = [&s[3], &s[4], &s[5]];
    match shear {
        Shear::Spatial(g0) => kernel(eb, kb, bend, Some((s, g0)), None, sh, r),
        Shear::Material => kernel(eb, kb, bend, None, Some(s), sh, r),
    }
}

/// Both at once: the stress `s` on the spatial strains (penalty reference
/// `g0`) plus the damping stress `sd` on the material strains, as
/// `add_internal_force(s, Spatial(g0))` then `add_internal_force(sd,
/// Material)` (equal up to round-off), in one pass over the Gauss points:
/// the bending and twist rows share one sum, s_K + sd_K.
pub fn add_internal_force_damped(
    eb: &ElemDofs,
    kb: &GaussFields,
    s: &[F4; 6],
    g0: &[V3; NGP],
    sd: &[F4; 6],
    sh: &GaussShapes,
    r: &mut ElVec,
) {
    let sum: [F4; 3] = std::array::from_fn(|i| std::array::from_fn(|g| s[3 + i][g] + sd[3 + i][g]));
    kernel(eb, kb, [&sum[0], &sum[1], &sum[2]], Some((s, g0)), Some(sd), sh, r);
}

/// The kernel of both: bending/twist stresses `bend`, shear/extension rows
/// 0..3 of `spatial` (with g⁰) and/or of `material`.
fn kernel(
    eb: &ElemDofs,
    kb: &GaussFields,
    bend: [&F4; 3],
    spatial: Option<(&[F4; 6], &[V3; NGP])>,
    material: Option<&[F4; 6]>,
    sh: &GaussShapes,
    r: &mut ElVec,
) {
    // bending and twist: ½ Σ_i s_Ki [L_A (d_kA × d_j' − d_jA × d_k') + L'_A (d_jA × d_k − d_kA × d_j)]
    // (i, j, k cyclic) = Σ_c d_cA × (L_A u_c + L'_A w_c) with, for each c,
    //   u_c = ½(s_K(c+1) d_(c+2)' − s_K(c+2) d_(c+1)'),  w_c = ½(s_K(c+2) d_(c+1) − s_K(c+1) d_(c+2))
    // (indices mod 3); the shear adds to u_c (below). Each u_c, w_c is summed
    // over the Gauss points as soon as it is formed: mom[A][c] = Σ_g w_g (L_A u_c + L'_A w_c).
    let sk: [F4; 3] = std::array::from_fn(|i| std::array::from_fn(|g| 0.5 * bend[i][g]));
    // the material shear's centreline force per Gauss point, Σ_i s_i d_i
    let mut f = [[0.0; NGP]; 3];
    let mut mom = [[V3::zeros(); 3]; 3];
    for cc in 0..3 {
        let (c1, c2) = ((cc + 1) % 3, (cc + 2) % 3);
        for c in 0..3 {
            let mut u: F4 = std::array::from_fn(|g| sk[c1][g] * kb.dp[c2][c][g] - sk[c2][g] * kb.dp[c1][c][g]);
            let w: F4 = std::array::from_fn(|g| sk[c2][g] * kb.d[c1][c][g] - sk[c1][g] * kb.d[c2][c][g]);
            // spatial: ∂γ/∂c_k = N'_k I, ∂γ/∂θ_A = L_A [w_A]×, w_A = Σ_c ŵ_c d_cA (ŵ = e3 + g⁰)
            //   ⇒ N'_k n and L_A n × w_A = Σ_c d_cA × (−L_A ŵ_c n)
            if let Some((s, g0)) = spatial {
                for g in 0..NGP {
                    let what = if cc == 2 { 1.0 + g0[g][2] } else { g0[g][cc] };
                    u[g] -= s[c][g] * what;
                }
            }
            // material: ∂Γ_i/∂c_k = N'_k d_i, ∂Γ_i/∂θ_A = L_A d_iA × r'
            //   ⇒ Σ_i s_i N'_k d_i and Σ_c d_cA × (L_A s_c r')
            if let Some(s) = material {
                for g in 0..NGP {
                    u[g] += kb.p[c][g] * s[cc][g];
                    f[c][g] += kb.d[cc][c][g] * s[cc][g];
                }
            }
            for a in 0..3 {
                mom[a][cc][c] = dot4(&sh.wl[a], &u) + dot4(&sh.wdl[a], &w);
            }
        }
    }
    // the spatial shear's centreline force is n itself
    if let Some((s, _)) = spatial {
        if material.is_some() {
            for c in 0..3 {
                for g in 0..NGP {
                    f[c][g] += s[c][g];
                }
            }
        } else {
            f = [s[0], s[1], s[2]];
        }
    }
    for (k, &off) in C_OFF.iter().enumerate() {
        for c in 0..3 {
            r[off + c] += dot4(&sh.wnds[k], &f[c]);
        }
    }
    for (a, &off) in T_OFF.iter().enumerate() {
        let mut m = V3::zeros();
        for cc in 0..3 {
            let dca: V3 = eb.d[a].column(cc).into();
            m += dca.cross(&mom[a][cc]);
        }
        r[off] += m.x;
        r[off + 1] += m.y;
        r[off + 2] += m.z;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{M3, cayley};
    use crate::model::rod::element::{ElMat, Factors, internal_force};

    /// The kernel's B̃ᵀs against the explicit B̃ (6 × 21) of the tangent path,
    /// `internal_force` with a tangent asked, which forms B̃ and multiplies:
    /// two independent writings of the same sums, for both shear measures,
    /// on a skewed element with non-orthonormal interpolated directors.
    #[test]
    fn kernel_matches_the_explicit_strain_operator() {
        let mut seed = 7u64;
        let mut rnd = move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let mut v3 = |s: f64| V3::new(rnd() * s, rnd() * s, rnd() * s);
        let h = 1.7;
        let c = [
            v3(1.0),
            V3::new(0.1, 0.2, 1.0) + v3(0.1),
            V3::new(0.2, 0.1, h) + v3(0.1),
            V3::new(0.0, 0.1, 1.0) + v3(0.1),
        ];
        let d: [M3; 3] = [cayley(&v3(0.4)), cayley(&v3(0.4)), cayley(&v3(0.4))];
        let e = ElemDofs { c, d };
        let g0 = [v3(0.05), v3(0.05), v3(0.05), v3(0.05)];
        let mut stress = [[0.0; 6]; NGP];
        for s in stress.iter_mut() {
            for v in s.iter_mut() {
                *v = rnd() * 1e3;
            }
        }
        for shear in [Shear::Spatial(&g0), Shear::Material] {
            let sh = GaussShapes::new(h);
            let mut kb = GaussFields::default();
            kb.refresh(&sh, &e);
            let mut fast = ElVec::zeros();
            add_internal_force(&e, &kb, &to_rows(&stress), &sh, shear, &mut fast);
            let mut dense = ElVec::zeros();
            let mut k = ElMat::zeros();
            internal_force(&e, &e, &stress, &[1.0; 6], Factors::STATIC, h, shear, &mut dense, Some(&mut k));
            let err = (fast - dense).amax() / dense.amax();
            assert!(err < 1e-13, "relative difference {err:.3e}");
        }
        // the one-pass elastic + damping force against the explicit B̃ᵀ of
        // each part (spatial shear for the elastic, material for the damping)
        let mut damp = [[0.0; 6]; NGP];
        for s in damp.iter_mut() {
            for v in s.iter_mut() {
                *v = rnd() * 1e2;
            }
        }
        let sh = GaussShapes::new(h);
        let mut kb = GaussFields::default();
        kb.refresh(&sh, &e);
        let mut fast = ElVec::zeros();
        add_internal_force_damped(&e, &kb, &to_rows(&stress), &g0, &to_rows(&damp), &sh, &mut fast);
        let mut dense = ElVec::zeros();
        let mut k = ElMat::zeros();
        internal_force(&e, &e, &stress, &[1.0; 6], Factors::STATIC, h, Shear::Spatial(&g0), &mut dense, Some(&mut k));
        internal_force(&e, &e, &damp, &[1.0; 6], Factors::STATIC, h, Shear::Material, &mut dense, Some(&mut k));
        let err = (fast - dense).amax() / dense.amax();
        assert!(err < 1e-13, "one pass, elastic + damping: relative difference {err:.3e}");
    }

    /// Strains from the component-major fields against the per-point ones.
    #[test]
    fn strains_match_the_per_point_evaluation() {
        let h = 0.9;
        let e = ElemDofs {
            c: [V3::zeros(), V3::new(0.1, 0.0, 1.02), V3::new(0.05, 0.1, h), V3::new(0.0, 0.2, 0.98)],
            d: [cayley(&V3::new(0.1, -0.2, 0.05)), cayley(&V3::new(0.0, 0.1, 0.3)), cayley(&V3::new(-0.2, 0.1, 0.1))],
        };
        let g0 = [V3::new(0.01, 0.0, -0.02); NGP];
        let sh = GaussShapes::new(h);
        let mut f = GaussFields::default();
        f.refresh(&sh, &e);
        let rows = f.strains(Shear::Spatial(&g0));
        let points = crate::model::rod::element::gauss_strains(&e, h, &g0);
        for g in 0..NGP {
            for r in 0..6 {
                assert!((rows[r][g] - points[g][r]).abs() < 1e-14, "row {r} point {g}");
            }
        }
    }
}
