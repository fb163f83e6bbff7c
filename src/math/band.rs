//! Global linear solves: the tangent of the discrete rod is block-banded
//! (element e owns the contiguous rows and columns 12e .. 12e+21; the cable's
//! segments likewise). It is assembled in compressed sparse columns with a
//! pattern fixed at construction and factorised as a dense band, kl = ku =
//! block − 1, by LU with threshold partial pivoting (LAPACK's dgbtf2/dgbtrs
//! algorithm, the fill of the row interchanges in kl extra rows; the
//! diagonal stays the pivot while it is at least 0.1 of its column's largest
//! entry, which saves most interchanges on the step's tangent). All buffers are
//! allocated up front; a factorisation or a solve allocates nothing.
//!
//! Why not faer's sparse LU, as before: faer has no band solver, and its
//! general sparse LU (fill-reducing ordering, then simplicial elimination)
//! spends its time on index work that a band does not need. At 60 elements
//! (729 unknowns, bandwidth 20) the band LU factorises in about half the time
//! and solves in about a third (docs/performance.md). faer stays as the
//! reference the tests check the band LU against.

/// Failure of a linear solve.
#[derive(Debug, Clone, PartialEq)]
pub enum LinearSolveError {
    /// The tangent is singular (a mechanism, an unconstrained rigid mode, or a
    /// degenerate state).
    Singular,
    /// Non-finite entries in the matrix or the right-hand side.
    NonFinite,
    /// A misuse of the solver (a solve before a factorisation, a wrong length).
    Backend(String),
}

impl std::fmt::Display for LinearSolveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LinearSolveError::Singular => write!(f, "the tangent matrix is singular"),
            LinearSolveError::NonFinite => write!(f, "the tangent matrix or residual is not finite"),
            LinearSolveError::Backend(m) => write!(f, "linear solver: {m}"),
        }
    }
}

/// Block-banded sparse matrix with overlapping square blocks of size `block`
/// placed every `stride` rows on the diagonal, plus its band LU.
pub struct BandedSystem {
    n: usize,
    block: usize,
    stride: usize,
    n_blocks: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// First row stored in each column.
    col_lo: Vec<usize>,
    /// Matrix values, pattern order.
    pub values: Vec<f64>,
    factorized: bool,
    band: BandLu,
    /// The Schur complement's scratch ([`BandedSystem::schur_complement_into`]):
    /// the driven rows on the interior and the right-hand sides, n each,
    /// grown once.
    schur_rows: Vec<f64>,
    schur_cols: Vec<f64>,
}

/// The diagonal stays the pivot while it is at least this fraction of the
/// column's largest entry (threshold partial pivoting, as sparse LU codes
/// do: the growth factor is bounded by (1 + 1/τ) per step instead of 2).
const PIVOT_THRESHOLD: f64 = 0.1;

/// Dense band LU with threshold partial pivoting (LAPACK's dgbtf2/dgbtrs
/// layout): element (i, j) of the factors at `ab[kv + i − j + j·ld]`,
/// kv = kl + ku, ld = 2kl + ku + 1 (the kl extra rows hold the fill of row
/// interchanges).
struct BandLu {
    kl: usize,
    ku: usize,
    ld: usize,
    ab: Vec<f64>,
    ipiv: Vec<usize>,
    /// Per column of the factors: rows of L below the diagonal up to the last
    /// nonzero, and rows of U above it from the first nonzero (the solves
    /// skip the band's structural zeros: a block band fills far less than
    /// kl + ku above the diagonal).
    l_len: Vec<usize>,
    u_len: Vec<usize>,
    /// 1/U[j, j] (the back substitution multiplies).
    inv_diag: Vec<f64>,
}

impl BandLu {
    fn new(n: usize, kl: usize, ku: usize) -> Self {
        let ld = 2 * kl + ku + 1;
        BandLu {
            kl,
            ku,
            ld,
            ab: vec![0.0; ld * n],
            ipiv: vec![0; n],
            l_len: vec![0; n],
            u_len: vec![0; n],
            inv_diag: vec![0.0; n],
        }
    }

    #[inline]
    fn at(&self, i: usize, j: usize) -> usize {
        self.kl + self.ku + i - j + j * self.ld
    }

    /// Factorises in place (dgbtf2): P A = L U.
    fn factorize(&mut self, n: usize) -> Result<(), LinearSolveError> {
        let (kl, kv, ld) = (self.kl, self.kl + self.ku, self.ld);
        let mut ju = 0;
        for j in 0..n {
            let d = self.at(j, j);
            // rows j+1..j+km: down to the column's last nonzero (a block
            // band's columns end 9 to 20 rows below the diagonal; below that
            // the entries are zeros, which neither the pivot search nor the
            // update changes)
            let km = self.ab[d + 1..=d + kl.min(n - 1 - j)].iter().rposition(|&v| v != 0.0).map_or(0, |r| r + 1);
            // pivot: the largest entry of column j on or below the diagonal,
            // unless the diagonal is within PIVOT_THRESHOLD of it (threshold
            // partial pivoting: fewer row swaps, less fill above the band)
            let mut jp = 0;
            let mut best = self.ab[d].abs();
            for r in 1..=km {
                let v = self.ab[d + r].abs();
                if v > best {
                    best = v;
                    jp = r;
                }
            }
            if jp != 0 && self.ab[d].abs() >= PIVOT_THRESHOLD * best {
                jp = 0;
                best = self.ab[d].abs();
            }
            self.ipiv[j] = j + jp;
            if best == 0.0 {
                return Err(LinearSolveError::Singular);
            }
            ju = ju.max((j + self.ku + jp).min(n - 1));
            if jp != 0 {
                for c in j..=ju {
                    self.ab.swap(kv + j + jp - c + c * ld, kv + j - c + c * ld);
                }
            }
            if km > 0 {
                let inv = 1.0 / self.ab[d];
                for v in &mut self.ab[d + 1..=d + km] {
                    *v *= inv;
                }
                // rank-1 update of rows j+1..j+km, columns j+1..ju
                let (head, tail) = self.ab.split_at_mut((j + 1) * ld);
                let l = &head[d + 1..=d + km];
                for c in j + 1..=ju {
                    let col = &mut tail[(c - j - 1) * ld..(c - j) * ld];
                    let u = col[kv + j - c];
                    if u != 0.0 {
                        let dst = &mut col[kv + j + 1 - c..=kv + j + km - c];
                        for (x, li) in dst.iter_mut().zip(l) {
                            *x -= li * u;
                        }
                    }
                }
            }
        }
        self.find_extents(n);
        Ok(())
    }

    /// The nonzero extents of the factors' columns, [`BandLu::l_len`] and
    /// [`BandLu::u_len`], and the reciprocal pivots.
    fn find_extents(&mut self, n: usize) {
        let kv = self.kl + self.ku;
        for j in 0..n {
            let d = self.at(j, j);
            let km = self.kl.min(n - 1 - j);
            let below = &self.ab[d + 1..=d + km];
            self.l_len[j] = below.iter().rposition(|&v| v != 0.0).map_or(0, |r| r + 1);
            let up = j.min(kv);
            let above = &self.ab[d - up..d];
            self.u_len[j] = above.iter().position(|&v| v != 0.0).map_or(0, |r| up - r);
            self.inv_diag[j] = 1.0 / self.ab[d];
        }
    }

    /// Solves A x = b in place with the factors (dgbtrs).
    fn solve(&self, n: usize, b: &mut [f64]) {
        for j in 0..n {
            let km = self.l_len[j];
            let p = self.ipiv[j];
            if p != j {
                b.swap(p, j);
            }
            let bj = b[j];
            if bj != 0.0 {
                let d = self.at(j, j);
                for (x, l) in b[j + 1..=j + km].iter_mut().zip(&self.ab[d + 1..=d + km]) {
                    *x -= l * bj;
                }
            }
        }
        for j in (0..n).rev() {
            let d = self.at(j, j);
            b[j] *= self.inv_diag[j];
            let bj = b[j];
            let lo = j - self.u_len[j];
            if bj != 0.0 {
                let col = &self.ab[d - (j - lo)..d];
                for (x, u) in b[lo..j].iter_mut().zip(col) {
                    *x -= u * bj;
                }
            }
        }
    }
}

impl BandedSystem {
    /// Pattern for `n_blocks` blocks of size `block` at stride `stride`
    /// (n = stride·(n_blocks − 1) + block unknowns).
    pub fn new(n_blocks: usize, block: usize, stride: usize) -> Result<Self, LinearSolveError> {
        assert!(n_blocks >= 1 && stride <= block);
        let n = stride * (n_blocks - 1) + block;
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        let mut col_lo = Vec::with_capacity(n);
        col_ptr.push(0);
        for j in 0..n {
            // blocks e containing column j: stride·e ≤ j < stride·e + block
            let e_hi = (j / stride).min(n_blocks - 1);
            let e_lo = if j + 1 > block { (j + 1 - block).div_ceil(stride) } else { 0 };
            let lo = stride * e_lo;
            let hi = (stride * e_hi + block).min(n);
            col_lo.push(lo);
            row_idx.extend(lo..hi);
            col_ptr.push(row_idx.len());
        }
        let values = vec![0.0; row_idx.len()];
        Ok(BandedSystem {
            n,
            block,
            stride,
            n_blocks,
            col_ptr,
            row_idx,
            col_lo,
            values,
            factorized: false,
            band: BandLu::new(n, block - 1, block - 1),
            schur_rows: Vec::new(),
            schur_cols: Vec::new(),
        })
    }

    pub fn dim(&self) -> usize {
        self.n
    }

    pub fn n_blocks(&self) -> usize {
        self.n_blocks
    }

    pub fn clear(&mut self) {
        self.values.iter_mut().for_each(|v| *v = 0.0);
        self.factorized = false;
    }

    /// Index into `values` of entry (i, j); None outside the pattern.
    #[inline]
    pub fn index(&self, i: usize, j: usize) -> Option<usize> {
        let lo = self.col_lo[j];
        let k = self.col_ptr[j] + i.checked_sub(lo)?;
        (k < self.col_ptr[j + 1]).then_some(k)
    }

    /// Adds a dense `block × block` matrix (row-major accessor) at block `e`.
    pub fn add_block(&mut self, e: usize, m: impl Fn(usize, usize) -> f64) {
        let off = self.stride * e;
        for c in 0..self.block {
            let j = off + c;
            let base = self.col_ptr[j] + (off - self.col_lo[j]);
            for r in 0..self.block {
                self.values[base + r] += m(r, c);
            }
        }
        self.factorized = false;
    }

    /// Adds v to entry (i, j) (which must be in the pattern).
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        let k = self.index(i, j).expect("entry outside the banded pattern");
        self.values[k] += v;
        self.factorized = false;
    }

    /// Entry (i, j), 0 outside the pattern.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.index(i, j).map_or(0.0, |k| self.values[k])
    }

    /// Replaces row and column i by the identity row/column scaled by the
    /// current diagonal (or 1 if it is zero): imposes Δu_i = 0.
    pub fn constrain(&mut self, i: usize) {
        let d = self.get(i, i).abs();
        let d = if d > 0.0 { d } else { 1.0 };
        // column i
        for k in self.col_ptr[i]..self.col_ptr[i + 1] {
            self.values[k] = 0.0;
        }
        // row i: columns whose range includes i
        let lo = i.saturating_sub(self.block);
        let hi = (i + self.block).min(self.n);
        for j in lo..hi {
            if let Some(k) = self.index(i, j) {
                self.values[k] = 0.0;
            }
        }
        let k = self.index(i, i).expect("diagonal");
        self.values[k] = d;
        self.factorized = false;
    }

    /// A ← Tᵀ A T on the three unknowns i0, i0+1, i0+2 (a change of basis of
    /// those unknowns, u = T u_loc, with the equations projected by Tᵀ).
    pub fn transform_dofs(&mut self, i0: usize, t: &nalgebra::Matrix3<f64>) {
        // columns: new col k = Σ_l old col l · T[l][k]
        let rlo = i0.saturating_sub(self.block);
        let rhi = (i0 + 3 + self.block).min(self.n);
        for i in rlo..rhi {
            let old: [f64; 3] = std::array::from_fn(|l| self.get(i, i0 + l));
            for k in 0..3 {
                if let Some(idx) = self.index(i, i0 + k) {
                    self.values[idx] = (0..3).map(|l| old[l] * t[(l, k)]).sum();
                }
            }
        }
        // rows: new row k = Σ_l T[l][k] old row l
        for j in rlo..rhi {
            let old: [f64; 3] = std::array::from_fn(|l| self.get(i0 + l, j));
            for k in 0..3 {
                if let Some(idx) = self.index(i0 + k, j) {
                    self.values[idx] = (0..3).map(|l| t[(l, k)] * old[l]).sum();
                }
            }
        }
        self.factorized = false;
    }

    /// y += A x.
    pub fn mul_add(&self, x: &[f64], y: &mut [f64]) {
        for j in 0..self.n {
            let xj = x[j];
            for k in self.col_ptr[j]..self.col_ptr[j + 1] {
                y[self.row_idx[k]] += self.values[k] * xj;
            }
        }
    }

    /// The Schur complement S = K_dd − K_di K_ii⁻¹ K_id on the unknowns
    /// `driven` (each among `fixed`, sorted), the unknowns not in `fixed`
    /// the interior i (the other fixed ones held): the change of the driven
    /// rows' residuals per unit move of the driven unknowns with the interior
    /// re-solved; row-major, `driven.len()` square. Leaves the matrix with
    /// `fixed` constrained and factorised (a Newton iteration may go on with
    /// it). Allocates its result: for stiffness reports; a step's is
    /// [`BandedSystem::schur_complement_into`].
    pub fn schur_complement(&mut self, driven: &[usize], fixed: &[usize]) -> Result<Vec<f64>, LinearSolveError> {
        let mut s = vec![0.0; driven.len() * driven.len()];
        self.schur_complement_into(driven, fixed, &mut s)?;
        Ok(s)
    }

    /// [`BandedSystem::schur_complement`] into `s` (`driven.len()` square,
    /// row-major), allocating nothing once its scratch has grown (the first
    /// call): a system's free points condense their lines' step tangents
    /// on their ends every Newton iteration (docs/theory.md (17.15)).
    pub fn schur_complement_into(
        &mut self,
        driven: &[usize],
        fixed: &[usize],
        s: &mut [f64],
    ) -> Result<(), LinearSolveError> {
        let (n, nd) = (self.n, driven.len());
        assert_eq!(s.len(), nd * nd, "the Schur complement's size");
        let interior = |k: usize| fixed.binary_search(&k).is_err();
        for (a, &i) in driven.iter().enumerate() {
            for (b, &j) in driven.iter().enumerate() {
                s[a * nd + b] = self.get(i, j);
            }
        }
        // K_di (the driven rows on the interior) and the right-hand sides K_id e_b
        let (mut rows, mut cols) = (std::mem::take(&mut self.schur_rows), std::mem::take(&mut self.schur_cols));
        rows.resize(nd * n, 0.0);
        cols.resize(nd * n, 0.0);
        for (a, &i) in driven.iter().enumerate() {
            for k in 0..n {
                rows[a * n + k] = if interior(k) { self.get(i, k) } else { 0.0 };
                cols[a * n + k] = if interior(k) { self.get(k, i) } else { 0.0 };
            }
        }
        for &i in fixed {
            self.constrain(i);
        }
        let mut solved = self.factorize();
        for b in 0..nd {
            if solved.is_err() {
                break;
            }
            // y = K_ii⁻¹ K_id e_b (the fixed rows' right-hand sides zero: y_f = 0)
            let y = &mut cols[b * n..(b + 1) * n];
            solved = self.solve_in_place(y);
            if solved.is_ok() {
                for a in 0..nd {
                    let row = &rows[a * n..(a + 1) * n];
                    s[a * nd + b] -= row.iter().zip(y.iter()).map(|(k, y)| k * y).sum::<f64>();
                }
            }
        }
        (self.schur_rows, self.schur_cols) = (rows, cols);
        solved
    }

    /// Factorises the current values (LU with partial pivoting).
    pub fn factorize(&mut self) -> Result<(), LinearSolveError> {
        if self.values.iter().any(|v| !v.is_finite()) {
            return Err(LinearSolveError::NonFinite);
        }
        let band = &mut self.band;
        band.ab.iter_mut().for_each(|v| *v = 0.0);
        for j in 0..self.n {
            for k in self.col_ptr[j]..self.col_ptr[j + 1] {
                let at = band.at(self.row_idx[k], j);
                band.ab[at] = self.values[k];
            }
        }
        band.factorize(self.n)?;
        self.factorized = true;
        Ok(())
    }

    /// Solves A x = b in place with the last factorisation.
    pub fn solve_in_place(&mut self, b: &mut [f64]) -> Result<(), LinearSolveError> {
        if !self.factorized {
            return Err(LinearSolveError::Backend("solve requested before the matrix was factorised".into()));
        }
        if b.len() != self.n {
            return Err(LinearSolveError::Backend(format!(
                "right-hand side of length {} for {} unknowns",
                b.len(),
                self.n
            )));
        }
        if b.iter().any(|v| !v.is_finite()) {
            return Err(LinearSolveError::NonFinite);
        }
        self.band.solve(self.n, b);
        if b.iter().any(|v| !v.is_finite()) {
            // a numerically singular pivot shows up as inf/NaN in the solution
            return Err(LinearSolveError::Singular);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut seed = seed;
        move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64) / ((1u64 << 53) as f64) - 0.5
        }
    }

    /// A random block-banded system: `shift` on the diagonal (0: the
    /// elimination must pivot).
    fn random_system(nb: usize, bs: usize, st: usize, shift: f64, seed: u64) -> BandedSystem {
        let mut sys = BandedSystem::new(nb, bs, st).unwrap();
        let mut rnd = rng(seed);
        for e in 0..nb {
            let blk: Vec<f64> = (0..bs * bs).map(|_| rnd()).collect();
            sys.add_block(e, |r, c| if r == c { shift } else { blk[r * bs + c] });
        }
        sys
    }

    /// The diagonal is kept as pivot down to 0.1 of the column's largest
    /// entry and swapped below that; either way the solve is exact.
    #[test]
    fn threshold_pivoting_keeps_a_fair_diagonal_and_swaps_a_small_one() {
        for (diag, swapped) in [(0.2, false), (0.05, true)] {
            let mut sys = BandedSystem::new(1, 3, 3).unwrap();
            let a = [[diag, 1.0, 0.0], [1.0, 2.0, 1.0], [0.0, 1.0, 3.0]];
            sys.add_block(0, |i, j| a[i][j]);
            sys.factorize().unwrap();
            assert_eq!(sys.band.ipiv[0] != 0, swapped, "diagonal {diag}");
            let x = [1.0, -2.0, 0.5];
            let mut b: Vec<f64> = (0..3).map(|i| (0..3).map(|j| a[i][j] * x[j]).sum()).collect();
            sys.solve_in_place(&mut b).unwrap();
            for i in 0..3 {
                assert!((b[i] - x[i]).abs() < 1e-14, "diagonal {diag}: x[{i}] = {}", b[i]);
            }
        }
    }

    #[test]
    fn band_lu_solves_random_systems_with_and_without_pivoting() {
        for (shift, seed) in [(3.0, 1u64), (0.0, 2), (0.0, 3)] {
            let (nb, bs, st) = (7, 5, 3);
            let mut sys = random_system(nb, bs, st, shift, seed);
            let n = sys.dim();
            let mut rnd = rng(seed + 100);
            let x: Vec<f64> = (0..n).map(|_| rnd()).collect();
            let mut b = vec![0.0; n];
            sys.mul_add(&x, &mut b);
            sys.factorize().unwrap();
            sys.solve_in_place(&mut b).unwrap();
            let err = b.iter().zip(&x).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            assert!(err < 1e-11, "shift {shift}: error {err:e}");
        }
    }

    /// Against faer's general sparse LU on the rod's own pattern (21 × 21
    /// blocks at stride 12, zero diagonal: pivoting throughout).
    #[test]
    fn band_lu_agrees_with_faer_sparse_lu() {
        use faer::linalg::solvers::Solve;
        use faer::sparse::{SparseColMat, Triplet};
        let (nb, bs, st) = (30, 21, 12);
        let mut sys = random_system(nb, bs, st, 0.0, 7);
        let n = sys.dim();
        let mut trip = Vec::new();
        for j in 0..n {
            for i in 0..n {
                if sys.index(i, j).is_some() {
                    trip.push(Triplet::new(i, j, sys.get(i, j)));
                }
            }
        }
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &trip).unwrap();
        let lu = a.sp_lu().unwrap();
        let mut rnd = rng(11);
        let b: Vec<f64> = (0..n).map(|_| rnd()).collect();
        let reference = lu.solve(faer::Mat::<f64>::from_fn(n, 1, |i, _| b[i]));
        let mut x = b.clone();
        sys.factorize().unwrap();
        sys.solve_in_place(&mut x).unwrap();
        let scale = (0..n).map(|i| reference[(i, 0)].abs()).fold(0.0, f64::max);
        let err = (0..n).map(|i| (x[i] - reference[(i, 0)]).abs()).fold(0.0, f64::max);
        assert!(err < 1e-10 * scale, "band LU vs faer: {err:e} of {scale:e}");
    }

    #[test]
    fn a_singular_band_is_reported() {
        let mut sys = BandedSystem::new(3, 4, 2).unwrap();
        // column 1 is zero
        sys.add_block(0, |r, c| {
            if c == 1 {
                0.0
            } else if r == c {
                1.0
            } else {
                0.1
            }
        });
        sys.add_block(1, |r, c| if r == c { 1.0 } else { 0.0 });
        sys.add_block(2, |r, c| if r == c { 1.0 } else { 0.0 });
        assert_eq!(sys.factorize(), Err(LinearSolveError::Singular));
    }
}
