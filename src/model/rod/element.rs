//! The rod element: strains, stored energy, internal force and consistent
//! tangent (docs/theory.md §2–§3; paper eqs. 3, 4, 12).
//!
//! Strains (docs/theory.md §2.2):
//!   γ = r' − d3 − Σ_i g⁰_i d_i   (spatial vector: the paper's penalty strain, eq. 12)
//!   K_i = ½ (d_k·d_j' − d_j·d_k'),  (i,j,k) cyclic   (bending K1, K2; twist K3)
//! and W = ½ R |γ|² + ½ Σ D_i (K_i − K_i⁰)²  with R = EA and D = (EI1, EI2, GJ).
//! g⁰ (per Gauss point) makes the reference configuration stress-free while
//! keeping γ objective (it turns with the directors); g⁰ = 0 for a straight
//! reference. γ is linear and K quadratic in the unknowns, which the
//! midpoint scheme needs. The penalty acts on the interpolated directors as
//! the paper writes it, |r' − d3|², not on Σ_i (d_i·r' − δ_i3)²: the two agree
//! at orthonormal directors, but between the nodes the interpolated d3 is
//! shorter than 1, and the second form lets a tensioned line with small EI
//! release axial energy by zig-zagging its directors (negative stiffness).
//!
//! Element unknowns, in the order of the global vector (so that element e owns
//! the contiguous global rows 12e .. 12e+21):
//!   [r_a (3), r'_a (3), θ_a (3), θ_mid (3), r_b (3), r'_b (3), θ_b (3)]
//! where θ is the spatial rotation increment of a director node, δd_i = θ × d_i.

pub use super::dofs::*;

use super::gauss::{self, GaussFields, GaussShapes, add_internal_force};
use crate::math::shape::{GAUSS4, hermite_ds, lagrange, lagrange_ds};
use crate::math::{M3, V3, skew};
use nalgebra::{SMatrix, SVector};

/// Interpolated fields at one Gauss point, with its shape values (the
/// per-point path of the strains and of B̃; the time step's residual uses
/// [`super::gauss`]).
#[derive(Debug, Clone, Copy, Default)]
struct GpKin {
    /// r'
    p: V3,
    /// d_i
    di: [V3; 3],
    /// d_i'
    dpi: [V3; 3],
    /// Hermite N'_k
    nds: [f64; 4],
    /// Lagrange L_A and L'_A
    l: [f64; 3],
    dl: [f64; 3],
}

impl GpKin {
    /// Recomputes the fields r', d_i, d_i' of element `e` with this point's
    /// shape values (no copy of the shape values, no division).
    #[inline]
    fn refresh(&mut self, e: &ElemDofs) {
        let nds = &self.nds;
        self.p = e.c[0] * nds[0] + e.c[1] * nds[1] + e.c[2] * nds[2] + e.c[3] * nds[3];
        for i in 0..3 {
            let (c0, c1, c2) = (e.d[0].column(i), e.d[1].column(i), e.d[2].column(i));
            self.di[i] = c0 * self.l[0] + c1 * self.l[1] + c2 * self.l[2];
            self.dpi[i] = c0 * self.dl[0] + c1 * self.dl[1] + c2 * self.dl[2];
        }
    }
}

/// The fields at the element's Gauss points.
fn gauss_kin(e: &ElemDofs, h: f64) -> [GpKin; NGP] {
    let mut out = [GpKin::default(); NGP];
    for (g, o) in out.iter_mut().enumerate() {
        *o = kin(e, GAUSS4.xi[g], h);
    }
    out
}

/// Strains at the Gauss points from their fields (see [`gauss_strains_with`]).
fn strains_from_kin(k: &[GpKin; NGP], shear: Shear<'_>) -> [Strain; NGP] {
    let mut out = [[0.0; 6]; NGP];
    for (g, o) in out.iter_mut().enumerate() {
        let g0 = match shear {
            Shear::Spatial(g0) => Some(&g0[g]),
            Shear::Material => None,
        };
        *o = strains_of(&k[g], g0);
    }
    out
}

#[inline]
fn kin(e: &ElemDofs, xi: f64, h: f64) -> GpKin {
    let mut k = GpKin { nds: hermite_ds(xi, h), l: lagrange(xi), dl: lagrange_ds(xi, h), ..GpKin::default() };
    k.refresh(e);
    k
}

#[inline]
fn strains_of(k: &GpKin, g0: Option<&V3>) -> Strain {
    let mut s = [0.0; 6];
    match g0 {
        Some(g0) => {
            let gamma = k.p - k.di[2] - k.di[0] * g0[0] - k.di[1] * g0[1] - k.di[2] * g0[2];
            s[0] = gamma.x;
            s[1] = gamma.y;
            s[2] = gamma.z;
        }
        None => {
            for i in 0..3 {
                s[i] = k.di[i].dot(&k.p);
            }
            s[2] -= 1.0;
        }
    }
    for &(i, j, kk) in &CYC {
        s[3 + i] = 0.5 * (k.di[kk].dot(&k.dpi[j]) - k.di[j].dot(&k.dpi[kk]));
    }
    s
}

/// Strains at ξ of an element of reference length h, with reference
/// penalty coefficients g⁰ at that point.
pub fn strains_at(e: &ElemDofs, xi: f64, h: f64, g0: &V3) -> Strain {
    strains_of(&kin(e, xi, h), Some(g0))
}

/// Strains at the element's Gauss points.
pub fn gauss_strains(e: &ElemDofs, h: f64, g0: &[V3; NGP]) -> [Strain; NGP] {
    gauss_strains_with(e, h, Shear::Spatial(g0))
}

/// Strains at the element's Gauss points with the chosen shear measure.
pub fn gauss_strains_with(e: &ElemDofs, h: f64, shear: Shear<'_>) -> [Strain; NGP] {
    strains_from_kin(&gauss_kin(e, h), shear)
}

/// Reference penalty coefficients at ξ: g⁰ = D⁰(ξ)⁻¹ (r'⁰ − d3⁰)(ξ) with D⁰ the
/// interpolated reference frame, so that γ vanishes in the reference.
pub fn reference_penalty_at(e: &ElemDofs, xi: f64, h: f64) -> V3 {
    let k = kin(e, xi, h);
    let d = M3::from_columns(&[k.di[0], k.di[1], k.di[2]]);
    d.try_inverse().map(|inv| inv * (k.p - k.di[2])).unwrap_or_else(V3::zeros)
}

/// [`reference_penalty_at`] at the Gauss points.
pub fn reference_penalty(e: &ElemDofs, h: f64) -> [V3; NGP] {
    std::array::from_fn(|g| reference_penalty_at(e, GAUSS4.xi[g], h))
}

/// Stored energy of the element, ∫ W dS (J), for strains `eps` at the Gauss points.
pub fn energy(eps: &[Strain; NGP], eps0: &[Strain; NGP], stiff: &[f64; 6], h: f64) -> f64 {
    let mut w = 0.0;
    for g in 0..NGP {
        let mut wg = 0.0;
        for c in 0..6 {
            let de = eps[g][c] - eps0[g][c];
            wg += 0.5 * stiff[c] * de * de;
        }
        w += GAUSS4.w[g] * h * wg;
    }
    w
}

/// Columns of the spatial-shear B̃ that row c (γ_c) can touch: component c
/// of r_a, r'_a, r_b, r'_b and the three rotations.
const GAMMA_COLS: [[usize; 13]; 3] = {
    let mut out = [[0; 13]; 3];
    let mut c = 0;
    while c < 3 {
        let mut k = 0;
        while k < 4 {
            out[c][k] = C_OFF[k] + c;
            k += 1;
        }
        let mut a = 0;
        while a < 9 {
            out[c][4 + a] = T_OFF[a / 3] + a % 3;
            a += 1;
        }
        c += 1;
    }
    out
};
/// Columns the bending and twist rows (K) can touch: the three rotations.
const KAPPA_COLS: [usize; 9] = [6, 7, 8, 9, 10, 11, 18, 19, 20];

/// Reduced strain operator B̃ = Dε · G (6 × 21) at a Gauss point:
/// rows ∂ε/∂(r_a, r'_a, θ_A, ...), with δd_i = θ × d_i at the director nodes.
fn b_matrix(e: &ElemDofs, k: &GpKin, g0: Option<&V3>) -> SMatrix<f64, 6, NDOF_EL> {
    let mut b = SMatrix::<f64, 6, NDOF_EL>::zeros();
    match g0 {
        Some(g0) => {
            // ∂γ/∂c_k = N'_k I
            for (kk, &off) in C_OFF.iter().enumerate() {
                for j in 0..3 {
                    b[(j, off + j)] = k.nds[kk];
                }
            }
            // ∂γ/∂θ_A = L_A [w_A]×,  w_A = d3A + Σ_i g⁰_i d_iA   (δd = θ × d)
            for (a, &off) in T_OFF.iter().enumerate() {
                let w: V3 = e.d[a] * (V3::z() + g0);
                b.fixed_view_mut::<3, 3>(0, off).copy_from(&(skew(&w) * k.l[a]));
            }
        }
        None => {
            for i in 0..3 {
                // ∂Γ_i/∂c_k = N'_k d_i
                for (kk, &off) in C_OFF.iter().enumerate() {
                    let v = k.di[i] * k.nds[kk];
                    b.fixed_view_mut::<1, 3>(i, off).copy_from(&v.transpose());
                }
                // ∂Γ_i/∂θ_A = L_A (d_iA × r')
                for (a, &off) in T_OFF.iter().enumerate() {
                    let v = e.d[a].column(i).cross(&k.p) * k.l[a];
                    b.fixed_view_mut::<1, 3>(i, off).copy_from(&v.transpose());
                }
            }
        }
    }
    for &(i, j, kk) in &CYC {
        // ∂K_i/∂θ_A = ½[L_A d_kA×d_j' + L'_A d_jA×d_k − L_A d_jA×d_k' − L'_A d_kA×d_j]
        for (a, &off) in T_OFF.iter().enumerate() {
            let dja: V3 = e.d[a].column(j).into();
            let dka: V3 = e.d[a].column(kk).into();
            let v = 0.5
                * (k.l[a] * (dka.cross(&k.dpi[j]) - dja.cross(&k.dpi[kk]))
                    + k.dl[a] * (dja.cross(&k.di[kk]) - dka.cross(&k.di[j])));
            b.fixed_view_mut::<1, 3>(3 + i, off).copy_from(&v.transpose());
        }
    }
    b
}

/// The internal force B̃ᵀ s without forming B̃ (the residual-only path of
/// [`internal_force`]: the same products written out, over the four Gauss
/// points at once, see [`super::gauss`]).
fn residual_only(eb: &ElemDofs, stress: &[Strain; NGP], h: f64, shear: Shear<'_>, r: &mut ElVec) {
    let sh = GaussShapes::new(h);
    let mut kb = GaussFields::default();
    kb.refresh(&sh, eb);
    add_internal_force(eb, &kb, &gauss::to_rows(stress), &sh, shear, r);
}

/// How the internal force depends on the unknowns (docs/theory.md §3.2).
///
/// The internal force is f = G(d_B)ᵀ Dε(q_B)ᵀ s with the stress s evaluated at
/// strains of q_E. In statics q_B = q_E = q and all factors are 1. In the
/// midpoint scheme q_B = q_{n+½}, s = C(½(ε_n + ε_{n+1}) − ε⁰), the unknown is
/// q_{n+1} = q_E and all factors are ½.
#[derive(Debug, Clone, Copy)]
pub struct Factors {
    /// d q_B / d q_E (derivative of the strain operator and of the test frames).
    pub config: f64,
    /// d s / d (C ε(q_E)).
    pub stress: f64,
}

impl Factors {
    pub const STATIC: Factors = Factors { config: 1.0, stress: 1.0 };
    pub const MIDPOINT: Factors = Factors { config: 0.5, stress: 0.5 };
}

/// Adds the element's reduced internal force to `r` and, if asked, its
/// derivative with respect to the increments (Δr, Δr', θ) of q_E to `kt`.
///
/// `eb` is q_B (strain operator and test frames), `ee` is q_E (trial
/// frames), `stress` the stress resultants C(ε̄ − ε⁰) at the Gauss points
/// (spatial force n = Rγ in N for the first three rows, N m for K rows),
/// `g0` the reference penalty coefficients at the Gauss points.
#[allow(clippy::too_many_arguments)]
pub fn internal_force(
    eb: &ElemDofs,
    ee: &ElemDofs,
    stress: &[Strain; NGP],
    stiff: &[f64; 6],
    fac: Factors,
    h: f64,
    shear: Shear<'_>,
    r: &mut ElVec,
    kt: Option<&mut ElMat>,
) {
    let want_k = kt.is_some();
    if !want_k {
        residual_only(eb, stress, h, shear, r);
        return;
    }
    let mut k_acc = ElMat::zeros();
    // unreduced director gradient ∂W/∂d_iA of q_B, for the frame-rotation term
    let mut fdir = [[V3::zeros(); 3]; 3];
    for g in 0..NGP {
        let xi = GAUSS4.xi[g];
        let wg = GAUSS4.w[g] * h;
        let s = &stress[g];
        let g0 = match shear {
            Shear::Spatial(g0) => Some(&g0[g]),
            Shear::Material => None,
        };
        let kb = kin(eb, xi, h);
        let bb = b_matrix(eb, &kb, g0);
        let sv = SVector::<f64, 6>::from_column_slice(s);
        *r += bb.transpose() * sv * wg;
        if !want_k {
            continue;
        }
        match g0 {
            Some(g0) => {
                // unreduced director gradient at q_B: ∂(½R|γ|²)/∂d_iA = −L_A (δ_i3 + g⁰_i) n
                let n = V3::new(s[0], s[1], s[2]);
                for i in 0..3 {
                    let c = if i == 2 { 1.0 + g0[2] } else { g0[i] };
                    for a in 0..3 {
                        fdir[a][i] -= n * (c * kb.l[a] * wg);
                    }
                }
            }
            None => {
                for i in 0..3 {
                    for a in 0..3 {
                        fdir[a][i] += kb.p * (s[i] * kb.l[a] * wg);
                    }
                }
            }
        }
        for &(i, j, kk) in &CYC {
            let m = s[3 + i] * 0.5 * wg;
            for a in 0..3 {
                fdir[a][kk] += (kb.dpi[j] * kb.l[a] - kb.di[j] * kb.dl[a]) * m;
                fdir[a][j] += (kb.di[kk] * kb.dl[a] - kb.dpi[kk] * kb.l[a]) * m;
            }
        }
        // material part: γ B̃_Bᵀ C B̃_E = Σ_rows c_row b_B,rowᵀ b_E,row
        let ke = kin(ee, xi, h);
        let be = b_matrix(ee, &ke, g0);
        if g0.is_some() {
            // B̃ is sparse for the spatial shear: row c of γ touches the c-th
            // component of the four Hermite dofs and the three rotations; the
            // K rows touch the rotations only (b_matrix)
            // (the entries gathered first: no index arithmetic of the matrices
            // in the inner loop; the sums in the same order, row by row)
            let (bbs, bes, ks) = (bb.as_slice(), be.as_slice(), k_acc.as_mut_slice());
            for row in 0..6 {
                let c = stiff[row] * fac.stress * wg;
                if row < 3 {
                    sparse_outer(&GAMMA_COLS[row], row, c, bbs, bes, ks);
                } else {
                    sparse_outer(&KAPPA_COLS, row, c, bbs, bes, ks);
                }
            }
        } else {
            // B̃_Bᵀ (C B̃_E), each entry summed over the six rows in order (as
            // nalgebra's product does), then added; the K rows touch the
            // rotation columns only, so elsewhere only the Γ rows are summed
            let (bbs, bes) = (bb.as_slice(), be.as_slice());
            let mut cbe = [[0.0; 6]; NDOF_EL];
            for (col, out) in cbe.iter_mut().enumerate() {
                for row in 0..6 {
                    out[row] = bes[row + 6 * col] * (stiff[row] * fac.stress * wg);
                }
            }
            let ks = k_acc.as_mut_slice();
            for (j, cj) in cbe.iter().enumerate() {
                let rot_j = IS_ROT[j];
                for i in 0..NDOF_EL {
                    let bi = &bbs[6 * i..6 * i + 6];
                    let mut t = bi[0] * cj[0];
                    t += bi[1] * cj[1];
                    t += bi[2] * cj[2];
                    if rot_j && IS_ROT[i] {
                        t += bi[3] * cj[3];
                        t += bi[4] * cj[4];
                        t += bi[5] * cj[5];
                    }
                    ks[i + NDOF_EL * j] += t;
                }
            }
        }
        // stress part α Σ s_k ∇²ε_k[G_B ·, G_E ·] (γ is linear: only K and Γ_i = d_i·r')
        let alpha = fac.config * wg;
        if g0.is_none() {
            for a in 0..3 {
                let nb: V3 = eb.d[a] * V3::new(s[0], s[1], s[2]);
                let ne: V3 = ee.d[a] * V3::new(s[0], s[1], s[2]);
                let snb = skew(&nb);
                let sne = skew(&ne);
                for (kk, &coff) in C_OFF.iter().enumerate() {
                    let f = alpha * kb.l[a] * kb.nds[kk];
                    let mut blk = k_acc.fixed_view_mut::<3, 3>(T_OFF[a], coff);
                    blk += snb * f;
                    let mut blk = k_acc.fixed_view_mut::<3, 3>(coff, T_OFF[a]);
                    blk -= sne * f;
                }
            }
        }
        for a in 0..3 {
            for bnode in 0..3 {
                if a == bnode {
                    continue;
                }
                let coef = 0.5 * alpha * (kb.dl[a] * kb.l[bnode] - kb.l[a] * kb.dl[bnode]);
                // Σ_i s_i ([d_kA]×[d_jB]× − [d_jA]×[d_kB]×), the products of
                // skew matrices written out ([a]×[b]×: b_r a_c off the
                // diagonal, −(a·b − a_r b_r) on it, summed as the 3 × 3
                // product sums them)
                let mut m = [[0.0; 3]; 3];
                for &(i, j, kk) in &CYC {
                    let (dka, dja) = (eb.d[a].column(kk), eb.d[a].column(j));
                    let (djb, dkb) = (ee.d[bnode].column(j), ee.d[bnode].column(kk));
                    let p = skew_skew([dka[0], dka[1], dka[2]], [djb[0], djb[1], djb[2]]);
                    let q = skew_skew([dja[0], dja[1], dja[2]], [dkb[0], dkb[1], dkb[2]]);
                    let si = s[3 + i];
                    for r in 0..3 {
                        for c in 0..3 {
                            m[r][c] += (p[r][c] - q[r][c]) * si;
                        }
                    }
                }
                let ks = k_acc.as_mut_slice();
                for c in 0..3 {
                    for r in 0..3 {
                        ks[T_OFF[a] + r + NDOF_EL * (T_OFF[bnode] + c)] += m[r][c] * coef;
                    }
                }
            }
        }
    }
    if let Some(kt) = kt {
        // rotation of the test frames: β Σ_i (d^E_iA f_iAᵀ − (d^E_iA·f_iA) I)
        for a in 0..3 {
            let mut m = M3::zeros();
            for i in 0..3 {
                let de: V3 = ee.d[a].column(i).into();
                m += de * fdir[a][i].transpose() - M3::identity() * de.dot(&fdir[a][i]);
            }
            let mut blk = k_acc.fixed_view_mut::<3, 3>(T_OFF[a], T_OFF[a]);
            blk += m * fac.config;
        }
        *kt += k_acc;
    }
}

/// Whether each element unknown is a rotation (θ_a, θ_mid, θ_b).
const IS_ROT: [bool; NDOF_EL] = {
    let mut out = [false; NDOF_EL];
    let mut a = 0;
    while a < 9 {
        out[T_OFF[a / 3] + a % 3] = true;
        a += 1;
    }
    out
};

/// k[i, j] += b_B[row, i] (c b_E[row, j]) over the columns `cols` (B̃ column-major
/// 6 × 21, k column-major 21 × 21).
#[inline(always)]
fn sparse_outer<const N: usize>(cols: &[usize; N], row: usize, c: f64, bb: &[f64], be: &[f64], k: &mut [f64]) {
    let bi: [f64; N] = std::array::from_fn(|t| bb[row + 6 * cols[t]]);
    for &j in cols {
        let bej = c * be[row + 6 * j];
        let col = &mut k[NDOF_EL * j..NDOF_EL * (j + 1)];
        for (t, &i) in cols.iter().enumerate() {
            col[i] += bi[t] * bej;
        }
    }
}

/// [a]× [b]× as nalgebra's 3 × 3 product forms it from the skew matrices
/// (row r, column c): b_r a_c off the diagonal, the two other products
/// summed in the product's order on it.
#[inline(always)]
fn skew_skew(a: [f64; 3], b: [f64; 3]) -> [[f64; 3]; 3] {
    [
        [-a[2] * b[2] + a[1] * -b[1], a[1] * b[0], a[2] * b[0]],
        [a[0] * b[1], a[2] * -b[2] + -a[0] * b[0], a[2] * b[1]],
        [a[0] * b[2], a[1] * b[2], -a[1] * b[1] + a[0] * -b[0]],
    ]
}

#[cfg(test)]
/// The tangent path as first written, with nalgebra's products (the
/// reference the tests hold [`internal_force`] to, entry for entry).
/// Adds the element's reduced internal force to `r` and, if asked, its
/// derivative with respect to the increments (Δr, Δr', θ) of q_E to `kt`.
///
/// `eb` is q_B (strain operator and test frames), `ee` is q_E (trial
/// frames), `stress` the stress resultants C(ε̄ − ε⁰) at the Gauss points
/// (spatial force n = Rγ in N for the first three rows, N m for K rows),
/// `g0` the reference penalty coefficients at the Gauss points.
#[allow(clippy::too_many_arguments)]
pub(crate) fn internal_force_reference(
    eb: &ElemDofs,
    ee: &ElemDofs,
    stress: &[Strain; NGP],
    stiff: &[f64; 6],
    fac: Factors,
    h: f64,
    shear: Shear<'_>,
    r: &mut ElVec,
    kt: Option<&mut ElMat>,
) {
    let want_k = kt.is_some();
    if !want_k {
        residual_only(eb, stress, h, shear, r);
        return;
    }
    let mut k_acc = ElMat::zeros();
    // unreduced director gradient ∂W/∂d_iA of q_B, for the frame-rotation term
    let mut fdir = [[V3::zeros(); 3]; 3];
    for g in 0..NGP {
        let xi = GAUSS4.xi[g];
        let wg = GAUSS4.w[g] * h;
        let s = &stress[g];
        let g0 = match shear {
            Shear::Spatial(g0) => Some(&g0[g]),
            Shear::Material => None,
        };
        let kb = kin(eb, xi, h);
        let bb = b_matrix(eb, &kb, g0);
        let sv = SVector::<f64, 6>::from_column_slice(s);
        *r += bb.transpose() * sv * wg;
        if !want_k {
            continue;
        }
        match g0 {
            Some(g0) => {
                // unreduced director gradient at q_B: ∂(½R|γ|²)/∂d_iA = −L_A (δ_i3 + g⁰_i) n
                let n = V3::new(s[0], s[1], s[2]);
                for i in 0..3 {
                    let c = if i == 2 { 1.0 + g0[2] } else { g0[i] };
                    for a in 0..3 {
                        fdir[a][i] -= n * (c * kb.l[a] * wg);
                    }
                }
            }
            None => {
                for i in 0..3 {
                    for a in 0..3 {
                        fdir[a][i] += kb.p * (s[i] * kb.l[a] * wg);
                    }
                }
            }
        }
        for &(i, j, kk) in &CYC {
            let m = s[3 + i] * 0.5 * wg;
            for a in 0..3 {
                fdir[a][kk] += (kb.dpi[j] * kb.l[a] - kb.di[j] * kb.dl[a]) * m;
                fdir[a][j] += (kb.di[kk] * kb.dl[a] - kb.dpi[kk] * kb.l[a]) * m;
            }
        }
        // material part: γ B̃_Bᵀ C B̃_E = Σ_rows c_row b_B,rowᵀ b_E,row
        let ke = kin(ee, xi, h);
        let be = b_matrix(ee, &ke, g0);
        if g0.is_some() {
            // B̃ is sparse for the spatial shear: row c of γ touches the c-th
            // component of the four Hermite dofs and the three rotations; the
            // K rows touch the rotations only (b_matrix)
            for row in 0..6 {
                let c = stiff[row] * fac.stress * wg;
                let cols: &[usize] = if row < 3 { &GAMMA_COLS[row] } else { &KAPPA_COLS };
                for &j in cols {
                    let bej = c * be[(row, j)];
                    for &i in cols {
                        k_acc[(i, j)] += bb[(row, i)] * bej;
                    }
                }
            }
        } else {
            let mut cbe = be;
            for row in 0..6 {
                let c = stiff[row] * fac.stress * wg;
                for col in 0..NDOF_EL {
                    cbe[(row, col)] *= c;
                }
            }
            k_acc += bb.transpose() * cbe;
        }
        // stress part α Σ s_k ∇²ε_k[G_B ·, G_E ·] (γ is linear: only K and Γ_i = d_i·r')
        let alpha = fac.config * wg;
        if g0.is_none() {
            for a in 0..3 {
                let nb: V3 = eb.d[a] * V3::new(s[0], s[1], s[2]);
                let ne: V3 = ee.d[a] * V3::new(s[0], s[1], s[2]);
                let snb = skew(&nb);
                let sne = skew(&ne);
                for (kk, &coff) in C_OFF.iter().enumerate() {
                    let f = alpha * kb.l[a] * kb.nds[kk];
                    let mut blk = k_acc.fixed_view_mut::<3, 3>(T_OFF[a], coff);
                    blk += snb * f;
                    let mut blk = k_acc.fixed_view_mut::<3, 3>(coff, T_OFF[a]);
                    blk -= sne * f;
                }
            }
        }
        for a in 0..3 {
            for bnode in 0..3 {
                if a == bnode {
                    continue;
                }
                let coef = 0.5 * alpha * (kb.dl[a] * kb.l[bnode] - kb.l[a] * kb.dl[bnode]);
                let mut m = M3::zeros();
                for &(i, j, kk) in &CYC {
                    let dka: V3 = eb.d[a].column(kk).into();
                    let dja: V3 = eb.d[a].column(j).into();
                    let djb: V3 = ee.d[bnode].column(j).into();
                    let dkb: V3 = ee.d[bnode].column(kk).into();
                    m += (skew(&dka) * skew(&djb) - skew(&dja) * skew(&dkb)) * s[3 + i];
                }
                let mut blk = k_acc.fixed_view_mut::<3, 3>(T_OFF[a], T_OFF[bnode]);
                blk += m * coef;
            }
        }
    }
    if let Some(kt) = kt {
        // rotation of the test frames: β Σ_i (d^E_iA f_iAᵀ − (d^E_iA·f_iA) I)
        for a in 0..3 {
            let mut m = M3::zeros();
            for i in 0..3 {
                let de: V3 = ee.d[a].column(i).into();
                m += de * fdir[a][i].transpose() - M3::identity() * de.dot(&fdir[a][i]);
            }
            let mut blk = k_acc.fixed_view_mut::<3, 3>(T_OFF[a], T_OFF[a]);
            blk += m * fac.config;
        }
        *kt += k_acc;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::cayley;

    /// The tangent path's products written out ([`internal_force`]) against
    /// nalgebra's ([`internal_force_reference`]): the same sums in the same
    /// order, so the same numbers, entry for entry (a zero's sign aside), for
    /// both shear measures, q_B ≠ q_E, the static and the midpoint factors,
    /// on skewed elements with non-orthonormal interpolated directors; and
    /// directors with exact zeros (a line in a plane).
    #[test]
    fn tangent_path_is_the_reference_entry_for_entry() {
        let mut seed = 11u64;
        let mut rnd = move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let h = 1.3;
        for case in 0..8 {
            let mut v3 = |s: f64| V3::new(rnd() * s, rnd() * s, rnd() * s);
            let planar = case % 4 == 3;
            let turn = |v: V3| if planar { V3::new(0.0, v.y, 0.0) } else { v };
            let eb = ElemDofs {
                c: [v3(1.0), V3::new(0.1, 0.2, 1.0) + v3(0.1), V3::new(0.2, 0.1, h) + v3(0.1), V3::z() + v3(0.1)],
                d: [cayley(&turn(v3(0.4))), cayley(&turn(v3(0.4))), cayley(&turn(v3(0.4)))],
            };
            let ee = ElemDofs {
                c: eb.c.map(|c| c + v3(0.05)),
                d: [cayley(&turn(v3(0.1))) * eb.d[0], cayley(&turn(v3(0.1))) * eb.d[1], eb.d[2]],
            };
            let g0 = [v3(0.05), v3(0.05), v3(0.05), v3(0.05)];
            let stress: [Strain; NGP] = std::array::from_fn(|_| std::array::from_fn(|_| rnd() * 1e3));
            let stiff: [f64; 6] = std::array::from_fn(|_| 1.0 + rnd().abs() * 1e4);
            let fac = if case % 2 == 0 { Factors::MIDPOINT } else { Factors { config: 0.5, stress: 0.037 } };
            for shear in [Shear::Spatial(&g0), Shear::Material] {
                let (mut r0, mut k0) = (ElVec::zeros(), ElMat::zeros());
                let (mut r1, mut k1) = (ElVec::zeros(), ElMat::zeros());
                internal_force_reference(&eb, &ee, &stress, &stiff, fac, h, shear, &mut r0, Some(&mut k0));
                internal_force(&eb, &ee, &stress, &stiff, fac, h, shear, &mut r1, Some(&mut k1));
                assert_eq!(r0, r1, "case {case}: residual");
                for j in 0..NDOF_EL {
                    for i in 0..NDOF_EL {
                        assert_eq!(k0[(i, j)], k1[(i, j)], "case {case}: entry ({i}, {j})");
                    }
                }
            }
        }
    }
}
