//! Linear analyses about a configuration, generic over the model's
//! [`Linearized`] seam (docs/theory.md §8):
//! - the natural modes, K φ = ω² M φ on the free unknowns, shift-inverted,
//!   with faer's dense Cholesky and eigen-solvers (the lines of this project
//!   have at most a few thousand unknowns, where a dense solve takes seconds:
//!   docs/performance.md gives the cost) and the band LU for K − σM;
//! - the line's stiffness at the hang-off, the Schur complement of the
//!   static tangent on the hang-off's position (3×3, eq. 8.6) and with the
//!   end's rotation (6×6, eq. 8.7), with the band LU;
//! - the line's stiffness at both its ends' positions (6×6, the ends
//!   pinned: a system's free points, docs/theory.md §17.4).

use crate::math::band::{BandedSystem, LinearSolveError};
use crate::math::{M3, M6, V3};
use crate::model::RodConfig;
use crate::model::linearized::{EndRotation, Linearized};
use faer::{Mat, Side};

/// Why the linear analysis failed.
#[derive(Debug, Clone, PartialEq)]
pub enum EigenError {
    /// No mode asked for.
    NoModes,
    /// Every unknown is held: nothing can vibrate.
    NoFreeUnknowns,
    /// The mass matrix is not positive definite (a massless unknown).
    MassNotPositive,
    /// The eigen-decomposition did not converge.
    NotConverged,
    /// The tangent at the hang-off could not be factorised.
    Linear(LinearSolveError),
    /// The hang-off's position is not held, so the line has no stiffness there.
    HangOffFree,
    /// The configuration or the matrices are not finite.
    NotFinite,
}

impl std::fmt::Display for EigenError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EigenError::NoModes => write!(f, "no modes asked for (the count must be at least 1)"),
            EigenError::NoFreeUnknowns => write!(f, "every unknown of the line is held: it has no modes"),
            EigenError::MassNotPositive => {
                write!(f, "the mass matrix is not positive definite (a mass or rotary inertia is zero)")
            }
            EigenError::NotConverged => write!(f, "the eigen-decomposition did not converge"),
            EigenError::Linear(e) => write!(f, "the line's tangent at the hang-off: {e}"),
            EigenError::HangOffFree => write!(f, "the hang-off's position is free: the line has no stiffness there"),
            EigenError::NotFinite => write!(f, "the configuration or the tangent is not finite"),
        }
    }
}

impl std::error::Error for EigenError {}

/// One natural mode.
#[derive(Debug, Clone, PartialEq)]
pub struct Mode {
    /// λ = ω², 1/s² (negative: the static state is unstable in this mode).
    pub eigenvalue: f64,
    /// Imaginary part of λ, 1/s²: non-zero only when the tangent is not
    /// symmetric (the steady current's drag) and the mode is a flutter pair.
    pub eigenvalue_imag: f64,
    /// The mode over every unknown (zero at the held ones), mass-normalised
    /// φᵀ M φ = 1 (kg); the real part when λ is complex.
    pub vector: Vec<f64>,
}

impl Mode {
    /// Natural period 2π/ω, s (∞ for λ ≤ 0).
    pub fn period(&self) -> f64 {
        if self.eigenvalue > 0.0 { 2.0 * std::f64::consts::PI / self.eigenvalue.sqrt() } else { f64::INFINITY }
    }

    /// Natural frequency ω/2π, Hz (0 for λ ≤ 0).
    pub fn frequency(&self) -> f64 {
        if self.eigenvalue > 0.0 { self.eigenvalue.sqrt() / (2.0 * std::f64::consts::PI) } else { 0.0 }
    }
}

/// The modes and how the problem was solved.
#[derive(Debug, Clone)]
pub struct Modes {
    /// The lowest modes, by increasing real part of λ.
    pub modes: Vec<Mode>,
    /// Free unknowns (the size of the dense problem).
    pub size: usize,
    /// Largest |K − Kᵀ| over the largest |K| of the free unknowns: ~1e-16 for
    /// a conservative problem (solved as symmetric), larger with the current.
    pub asymmetry: f64,
}

/// Dense matrix of the free unknowns `free` of a banded matrix.
fn dense(sys: &crate::math::band::BandedSystem, free: &[usize]) -> Mat<f64> {
    Mat::from_fn(free.len(), free.len(), |i, j| sys.get(free[i], free[j]))
}

/// The shift σ of the inverse iteration, 1/s²: −(2π/1000 s)², below every
/// natural frequency of a line that is held at its ends (eq. 8.2).
const SHIFT: f64 = -(2.0 * std::f64::consts::PI / 1000.0) * (2.0 * std::f64::consts::PI / 1000.0);

/// The `count` lowest natural modes of `line` about `cfg` (eqs. 8.1–8.2).
///
/// K φ = λ M φ is solved in shift-inverted form: with M = L Lᵀ (Cholesky)
/// and C = K − σ M, the matrix B = Lᵀ C⁻¹ L has the eigenvalues
/// μ = 1/(λ − σ), so the lowest modes are its largest and the dense
/// solver's absolute error ε‖B‖ is a relative error on them. (Solving
/// L⁻¹ K L⁻ᵀ directly is hopeless: a rod's stiff axial and rotary modes make
/// its spectrum span 17 decades, and the lowest modes drown in round-off.)
/// B is solved as self-adjoint when K is symmetric to round-off, as a
/// general real matrix otherwise (the current's drag); φ = C⁻¹ L y.
pub fn lowest_modes<L: Linearized>(line: &L, cfg: &RodConfig, count: usize) -> Result<Modes, EigenError> {
    if count == 0 {
        return Err(EigenError::NoModes);
    }
    let n = line.n_dof();
    let fixed = line.fixed_dofs();
    let free: Vec<usize> = (0..n).filter(|i| fixed.binary_search(i).is_err()).collect();
    if free.is_empty() {
        return Err(EigenError::NoFreeUnknowns);
    }
    let nf = free.len();
    let mut c_band = line.new_system().map_err(EigenError::Linear)?;
    let mut m_band = line.new_system().map_err(EigenError::Linear)?;
    let mut r = vec![0.0; n];
    line.static_tangent(cfg, &mut r, &mut c_band);
    line.mass_matrix(cfg, &mut m_band);
    if !c_band.values.iter().chain(&m_band.values).all(|v| v.is_finite()) {
        return Err(EigenError::NotFinite);
    }
    // asymmetry of K on the free unknowns
    let (mut asym, mut kmax) = (0.0f64, 0.0f64);
    for (a, &i) in free.iter().enumerate() {
        for &j in &free[..=a] {
            let (kij, kji) = (c_band.get(i, j), c_band.get(j, i));
            asym = asym.max((kij - kji).abs());
            kmax = kmax.max(kij.abs()).max(kji.abs());
        }
    }
    let asymmetry = if kmax > 0.0 { asym / kmax } else { 0.0 };
    let m = dense(&m_band, &free);
    let llt = m.llt(Side::Lower).map_err(|_| EigenError::MassNotPositive)?;
    let l = llt.L();
    // C = K − σ M (same pattern), the supports held, factorised once
    for (c, mv) in c_band.values.iter_mut().zip(&m_band.values) {
        *c -= SHIFT * mv;
    }
    for &i in &fixed {
        c_band.constrain(i);
    }
    c_band.factorize().map_err(EigenError::Linear)?;
    // X = C⁻¹ L, column by column through the band LU
    let mut x = Mat::<f64>::zeros(nf, nf);
    let mut col = vec![0.0; n];
    for j in 0..nf {
        col.iter_mut().for_each(|v| *v = 0.0);
        for (i, &f) in free.iter().enumerate().skip(j) {
            col[f] = l[(i, j)];
        }
        c_band.solve_in_place(&mut col).map_err(EigenError::Linear)?;
        for (i, &f) in free.iter().enumerate() {
            x[(i, j)] = col[f];
        }
    }
    let b = l.transpose() * &x;
    let wanted = wanted_modes(&b, count.min(nf), asymmetry < 1e-9)?;
    let modes = wanted
        .into_iter()
        .map(|(mu, imag, y)| {
            // φ = C⁻¹ L y = X y, mass-normalised
            let xy = &x * &y;
            let mut phi = vec![0.0; n];
            for (i, &f) in free.iter().enumerate() {
                phi[f] = xy[(i, 0)];
            }
            let mut mphi = vec![0.0; n];
            m_band.mul_add(&phi, &mut mphi);
            let norm: f64 = phi.iter().zip(&mphi).map(|(a, b)| a * b).sum::<f64>().sqrt();
            if norm > 0.0 {
                phi.iter_mut().for_each(|v| *v /= norm);
            }
            Mode { eigenvalue: SHIFT + 1.0 / mu, eigenvalue_imag: imag, vector: phi }
        })
        .collect();
    Ok(Modes { modes, size: nf, asymmetry })
}

/// The `count` lowest modes of K φ = λ M φ given as dense matrices over the
/// free unknowns (a system of lines joined at free points, docs/theory.md
/// §17.9, eq. 17.21): the shift-inverted form of [`lowest_modes`] with
/// faer's dense LU with partial pivoting for C = K − σ M. The modes'
/// vectors are over these unknowns, mass-normalised φᵀ M φ = 1.
pub fn lowest_modes_dense(k: &Mat<f64>, m: &Mat<f64>, count: usize) -> Result<Modes, EigenError> {
    use faer::linalg::solvers::Solve;
    if count == 0 {
        return Err(EigenError::NoModes);
    }
    let n = k.nrows();
    if n == 0 {
        return Err(EigenError::NoFreeUnknowns);
    }
    let finite = |a: &Mat<f64>| (0..n).all(|j| (0..n).all(|i| a[(i, j)].is_finite()));
    if !finite(k) || !finite(m) {
        return Err(EigenError::NotFinite);
    }
    let (mut asym, mut kmax) = (0.0f64, 0.0f64);
    for j in 0..n {
        for i in 0..=j {
            asym = asym.max((k[(i, j)] - k[(j, i)]).abs());
            kmax = kmax.max(k[(i, j)].abs());
        }
    }
    let asymmetry = if kmax > 0.0 { asym / kmax } else { 0.0 };
    let llt = m.llt(Side::Lower).map_err(|_| EigenError::MassNotPositive)?;
    let l = llt.L().to_owned();
    let c = Mat::from_fn(n, n, |i, j| k[(i, j)] - SHIFT * m[(i, j)]);
    // X = C⁻¹ L
    let x = c.partial_piv_lu().solve(&l);
    if !finite(&x) {
        return Err(EigenError::Linear(LinearSolveError::NonFinite));
    }
    let b = l.transpose() * &x;
    let wanted = wanted_modes(&b, count.min(n), asymmetry < 1e-9)?;
    let modes = wanted
        .into_iter()
        .map(|(mu, imag, y)| {
            let phi = &x * &y;
            let mphi = m * &phi;
            let norm = (0..n).map(|i| phi[(i, 0)] * mphi[(i, 0)]).sum::<f64>().sqrt();
            let scale = if norm > 0.0 { 1.0 / norm } else { 1.0 };
            Mode {
                eigenvalue: SHIFT + 1.0 / mu,
                eigenvalue_imag: imag,
                vector: (0..n).map(|i| phi[(i, 0)] * scale).collect(),
            }
        })
        .collect();
    Ok(Modes { modes, size: n, asymmetry })
}

/// The wanted modes of the shift-inverted B = Lᵀ C⁻¹ L (eq. 8.2): the
/// `count` largest μ = 1/(λ − σ) with their eigenvectors y, as (μ, the
/// imaginary part of λ, y); B solved as self-adjoint when `symmetric`, as a
/// general real matrix otherwise (of a complex-conjugate pair, one).
fn wanted_modes(b: &Mat<f64>, count: usize, symmetric: bool) -> Result<Vec<(f64, f64, Mat<f64>)>, EigenError> {
    let nf = b.nrows();
    // (μ, imaginary part of λ, y) of the wanted modes
    let mut wanted: Vec<(f64, f64, Mat<f64>)> = Vec::with_capacity(count);
    if symmetric {
        let sym = Mat::from_fn(nf, nf, |i, j| 0.5 * (b[(i, j)] + b[(j, i)]));
        let evd = sym.self_adjoint_eigen(Side::Lower).map_err(|_| EigenError::NotConverged)?;
        let (s, u) = (evd.S(), evd.U());
        // ascending μ: the lowest modes (largest μ > 0) are at the end
        for c in (0..nf).rev().take(count) {
            wanted.push((s[c], 0.0, Mat::from_fn(nf, 1, |i, _| u[(i, c)])));
        }
    } else {
        let evd = b.eigen().map_err(|_| EigenError::NotConverged)?;
        let (s, u) = (evd.S(), evd.U());
        let lambda = |c: usize| {
            let mu = s[c];
            let inv = mu.re * mu.re + mu.im * mu.im;
            (SHIFT + mu.re / inv, -mu.im / inv)
        };
        let mut order: Vec<usize> = (0..nf).filter(|&c| s[c].re > 0.0).collect();
        order.sort_by(|&p, &q| lambda(p).0.total_cmp(&lambda(q).0));
        let mut last = None;
        for &c in &order {
            if wanted.len() == count {
                break;
            }
            // of a complex-conjugate pair keep one
            let (re, im) = lambda(c);
            if im != 0.0 && last == Some((re, -im)) {
                continue;
            }
            last = Some((re, im));
            wanted.push((s[c].re, im, Mat::from_fn(nf, 1, |i, _| u[(i, c)].re)));
        }
    }
    Ok(wanted)
}

/// The line's tangent stiffness at the hang-off about `cfg` (eq. 8.6):
/// S = K_bb − K_bi K_ii⁻¹ K_ib, the change of the support's reaction on the
/// line per unit displacement of the hang-off with the other unknowns in
/// equilibrium (the rest of the supports held, a clamped end's rotation and
/// a flex joint's vessel frame among them), N/m: the translation block of
/// [`hang_off_stiffness6`]. The force the line exerts on the vessel changes
/// by −S δ.
pub fn hang_off_stiffness<L: Linearized>(line: &L, cfg: &RodConfig) -> Result<M3, EigenError> {
    Ok(hang_off_stiffness6(line, cfg)?.fixed_view::<3, 3>(0, 0).into_owned())
}

/// The line's 6×6 tangent stiffness at the hang-off about `cfg` (eq. 8.7):
/// [δF; δM] = S₆ [δx; δθ], δF and δM the change of the force and of the end
/// moment of the support on the line (N, N m), δx the hang-off's translation
/// (m) and δθ a small rotation of the vessel's frame (rad, global), the
/// interior unknowns condensed (in equilibrium, the other supports held):
/// - pinned end: the rotation columns and the moment rows are zero;
/// - clamped end: δθ prescribes the end director node's rotation; the
///   moment rows are the residual's rows there (the reactions' moment);
/// - flex joint: the joint's moment m changes by k_end θ_end + k_vessel δθ,
///   in series with the line; the support's moment on the line is −m.
pub fn hang_off_stiffness6<L: Linearized>(line: &L, cfg: &RodConfig) -> Result<M6, EigenError> {
    hang_off_stiffness6_in(line, cfg, &mut HangOffStorage::default())
}

/// What [`hang_off_stiffness6_in`] works in on one line: its static
/// tangent, residual and fixed unknowns, the driven rows on the interior
/// and the right-hand sides (sized at the first call on the line).
#[derive(Default)]
pub struct HangOffStorage {
    sys: Option<BandedSystem>,
    r: Vec<f64>,
    fixed: Vec<usize>,
    rows: Vec<f64>,
    cols: Vec<f64>,
}

/// [`hang_off_stiffness6`] in the storage `w` (the same numbers, the same
/// bits), allocating nothing after its first call on the line.
pub fn hang_off_stiffness6_in<L: Linearized>(
    line: &L,
    cfg: &RodConfig,
    w: &mut HangOffStorage,
) -> Result<M6, EigenError> {
    let n = line.n_dof();
    if w.sys.is_none() {
        w.sys = Some(line.new_system().map_err(EigenError::Linear)?);
        w.r = vec![0.0; n];
        w.fixed = line.fixed_dofs();
        w.rows = vec![0.0; 6 * n];
        w.cols = vec![0.0; 6 * n];
    }
    let fixed = &w.fixed;
    let b = line.hang_off_rows();
    if b.iter().any(|i| fixed.binary_search(i).is_err()) {
        return Err(EigenError::HangOffFree);
    }
    let end = line.hang_off_end(cfg);
    // the prescribed unknowns whose columns are driven: the position, and a clamp's rotation
    let mut driven = [0; 6];
    driven[..3].copy_from_slice(&b);
    let mut nd = 3;
    if let EndRotation::Clamped { rows } = end {
        if rows.iter().any(|i| fixed.binary_search(i).is_err()) {
            return Err(EigenError::HangOffFree);
        }
        driven[3..].copy_from_slice(&rows);
        nd = 6;
    }
    let driven = &driven[..nd];
    let sys = w.sys.as_mut().expect("sized above");
    line.static_tangent(cfg, &mut w.r, sys);
    let is_fixed = |i: usize| fixed.binary_search(&i).is_ok();
    // the output rows that read the tangent: the force, and a clamp's moment
    let mut s = M6::zeros();
    for (i, &bi) in driven.iter().enumerate() {
        for k in 0..n {
            w.rows[i * n + k] = sys.get(bi, k);
        }
    }
    let rows = &w.rows[..nd * n];
    for (i, &bi) in driven.iter().enumerate() {
        for (j, &bj) in driven.iter().enumerate() {
            s[(i, j)] = sys.get(bi, bj);
        }
    }
    // right-hand sides −K_ib e_j of the six columns (zero: the column is not driven)
    for (j, &bj) in driven.iter().enumerate() {
        for k in 0..n {
            w.cols[j * n + k] = if is_fixed(k) { 0.0 } else { -sys.get(k, bj) };
        }
    }
    let mut nc = nd;
    if let EndRotation::Joint { rows: jr, k_vessel, .. } = end {
        for j in 0..3 {
            let c = &mut w.cols[(nd + j) * n..(nd + j + 1) * n];
            c.iter_mut().for_each(|v| *v = 0.0);
            for (a, &ia) in jr.iter().enumerate() {
                c[ia] = -k_vessel[(a, j)];
            }
        }
        nc = nd + 3;
    }
    if !s.iter().chain(rows.iter()).all(|v| v.is_finite()) {
        return Err(EigenError::NotFinite);
    }
    for &i in fixed {
        sys.constrain(i);
    }
    sys.factorize().map_err(EigenError::Linear)?;
    for j in 0..nc {
        // K_ii Δq = −K_ib e_j
        let dq = &mut w.cols[j * n..(j + 1) * n];
        sys.solve_in_place(dq).map_err(EigenError::Linear)?;
        for i in 0..nd {
            let row = &rows[i * n..(i + 1) * n];
            let mut v = 0.0;
            for k in 0..n {
                if !is_fixed(k) {
                    v += row[k] * dq[k];
                }
            }
            s[(i, j)] += v;
        }
        if let EndRotation::Joint { rows: jr, k_end, k_vessel } = end {
            // the support's moment on the line, −δm
            let th = V3::new(dq[jr[0]], dq[jr[1]], dq[jr[2]]);
            let mut dm = k_end * th;
            if j >= 3 {
                dm += k_vessel.column(j - 3);
            }
            for a in 0..3 {
                s[(3 + a, j)] = -dm[a];
            }
        }
    }
    if s.iter().all(|v| v.is_finite()) { Ok(s) } else { Err(EigenError::NotFinite) }
}

/// The line's tangent stiffness at both its ends' positions about `cfg`
/// (docs/theory.md §17.4, eq. 17.6): with e = (x_h, x_a), the hang-off's
/// and the anchor's positions, the Schur complement
/// S = K_ee − K_ei K_ii⁻¹ K_ie of the static tangent on them, the interior
/// unknowns in equilibrium (the other held unknowns, a twist's, held):
/// [δR_h; δR_a] = S [δx_h; δx_a], δR the change of the supports' forces on
/// the line (N per m). The ends' rotations are free (pinned ends); the
/// forces the line exerts on its ends change by −S δe. Its 3×3 block at the
/// hang-off is [`hang_off_stiffness`]'s on a pinned end.
pub fn end_stiffness6<L: Linearized>(line: &L, cfg: &RodConfig) -> Result<M6, EigenError> {
    end_stiffness6_shifted(line, cfg, 0.0)
}

/// [`end_stiffness6`] with `shift` (N/m) added to the interior unknowns'
/// diagonal: a line whose interior has no stiffness in some direction (a
/// chain slack on a frictionless seabed) has a finite one, the ends' as
/// though each interior unknown were held by a spring of that stiffness.
/// An approximation for a Newton direction (a system's free points), not
/// the line's stiffness.
pub fn end_stiffness6_shifted<L: Linearized>(line: &L, cfg: &RodConfig, shift: f64) -> Result<M6, EigenError> {
    end_stiffness6_shifted_in(line, cfg, shift, &mut EndStiffnessStorage::default())
}

/// What [`end_stiffness6_shifted_in`] works in on one line: its static
/// tangent, residual and fixed unknowns, the Schur complement (sized at the
/// first call on the line).
#[derive(Default)]
pub struct EndStiffnessStorage {
    sys: Option<BandedSystem>,
    r: Vec<f64>,
    fixed: Vec<usize>,
    s: Vec<f64>,
}

impl EndStiffnessStorage {
    /// The storage sized on `line` (so that its first call allocates
    /// nothing either); None if its band matrix cannot be had.
    pub fn for_line<L: Linearized>(line: &L) -> Option<Self> {
        Some(EndStiffnessStorage {
            sys: Some(line.new_system().ok()?),
            r: vec![0.0; line.n_dof()],
            fixed: line.fixed_dofs(),
            s: vec![0.0; 36],
        })
    }
}

/// [`end_stiffness6_shifted`] in the storage `w` (the same numbers, the
/// same bits), allocating nothing after its first call on the line.
pub fn end_stiffness6_shifted_in<L: Linearized>(
    line: &L,
    cfg: &RodConfig,
    shift: f64,
    w: &mut EndStiffnessStorage,
) -> Result<M6, EigenError> {
    let n = line.n_dof();
    if w.sys.is_none() {
        w.sys = Some(line.new_system().map_err(EigenError::Linear)?);
        w.r = vec![0.0; n];
        w.fixed = line.fixed_dofs();
        w.s = vec![0.0; 36];
    }
    let fixed = &w.fixed;
    let is_fixed = |i: usize| fixed.binary_search(&i).is_ok();
    let mut driven = [0; 6];
    driven[..3].copy_from_slice(&line.hang_off_rows());
    driven[3..].copy_from_slice(&line.anchor_rows());
    if driven.iter().any(|&i| !is_fixed(i)) {
        return Err(EigenError::HangOffFree);
    }
    let sys = w.sys.as_mut().expect("sized above");
    line.static_tangent(cfg, &mut w.r, sys);
    if shift != 0.0 {
        for i in (0..n).filter(|&i| !is_fixed(i)) {
            sys.add(i, i, shift);
        }
    }
    sys.schur_complement_into(&driven, fixed, &mut w.s).map_err(|e| match e {
        LinearSolveError::NonFinite => EigenError::NotFinite,
        e => EigenError::Linear(e),
    })?;
    let s = M6::from_row_slice(&w.s);
    if s.iter().all(|v| v.is_finite()) { Ok(s) } else { Err(EigenError::NotFinite) }
}
