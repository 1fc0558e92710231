//! The Cholesky factorisation `A + diag(shift) = L Lᵀ` of a [`SymmetricMatrix`], banded or dense.

use nalgebra::{Cholesky as DenseCholesky, DMatrix, DVectorViewMut, Dyn};

use super::{NotPositiveDefinite, Storage, SymmetricMatrix};

/// A Cholesky factorisation `A + diag(shift) = L Lᵀ` with storage reused between factorisations, so the
/// Levenberg–Marquardt loop can refactor with a new damping without allocating.
#[derive(Clone, Debug)]
pub struct Cholesky {
    n: usize,
    factor: Factor,
}

#[derive(Clone, Debug)]
enum Factor {
    Banded {
        bandwidth: usize,
        /// `L` in the same layout as [`Storage::Banded`].
        band: Vec<f64>,
        /// Scratch for [`factor_rows`]: a group's new columns, one `[f64; ROWS]` per column.
        panel: Vec<[f64; ROWS]>,
    },
    /// `Ready` holds a factorisation; `Spare` holds only the buffer (after a failure or before the first).
    Dense(DenseFactor),
}

#[derive(Clone, Debug)]
enum DenseFactor {
    Ready(DenseCholesky<f64, Dyn>),
    Spare(DMatrix<f64>),
    Empty,
}

impl Cholesky {
    /// Workspace shaped like `a` (same storage kind and band).
    pub fn for_matrix(a: &SymmetricMatrix) -> Self {
        let factor = match &a.storage {
            Storage::Banded { bandwidth, band } => {
                Factor::Banded { bandwidth: *bandwidth, band: vec![0.0; band.len()], panel: vec![[0.0; ROWS]; *bandwidth] }
            }
            Storage::Dense(_) => Factor::Dense(DenseFactor::Spare(DMatrix::zeros(a.n, a.n))),
        };
        Cholesky { n: a.n, factor }
    }

    /// Factorises `A + diag(shift)` (`shift` may be `None`). On failure the workspace holds no valid
    /// factor until the next successful call.
    ///
    /// # Panics
    /// If `a` is not shaped like the matrix this workspace was made for, or `shift` has the wrong length.
    pub fn factor(&mut self, a: &SymmetricMatrix, shift: Option<&[f64]>) -> Result<(), NotPositiveDefinite> {
        assert_eq!(a.n, self.n);
        if let Some(s) = shift {
            assert_eq!(s.len(), self.n);
        }
        let n = self.n;
        match (&mut self.factor, &a.storage) {
            (Factor::Banded { bandwidth, band: l, panel }, Storage::Banded { bandwidth: ab, band: a_band }) => {
                assert_eq!(bandwidth, ab);
                l.copy_from_slice(a_band);
                let w = *bandwidth + 1;
                if let Some(s) = shift {
                    for (i, si) in s.iter().enumerate() {
                        l[i * w + *bandwidth] += si;
                    }
                }
                banded_cholesky_in_place(n, *bandwidth, l, panel)
            }
            (Factor::Dense(slot), Storage::Dense(a_dense)) => {
                let mut buffer = match std::mem::replace(slot, DenseFactor::Empty) {
                    DenseFactor::Ready(chol) => chol.unpack_dirty(),
                    DenseFactor::Spare(m) => m,
                    DenseFactor::Empty => DMatrix::zeros(n, n),
                };
                buffer.copy_from(a_dense);
                if let Some(s) = shift {
                    for (i, si) in s.iter().enumerate() {
                        buffer[(i, i)] += si;
                    }
                }
                match DenseCholesky::new(buffer) {
                    Some(chol) => {
                        let l = chol.l_dirty();
                        if let Some(pivot) = (0..n).find(|&i| !(l[(i, i)] > 0.0 && l[(i, i)].is_finite())) {
                            *slot = DenseFactor::Spare(chol.unpack_dirty());
                            return Err(NotPositiveDefinite { pivot });
                        }
                        *slot = DenseFactor::Ready(chol);
                        Ok(())
                    }
                    // nalgebra consumed the buffer; the next call allocates a new one (failures are rare).
                    None => Err(NotPositiveDefinite { pivot: 0 }),
                }
            }
            _ => panic!("Cholesky workspace and matrix have different storage"),
        }
    }

    /// Solves `(A + diag(shift)) x = b` in place with the last successful factorisation.
    ///
    /// # Panics
    /// If `b.len() != n`.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        assert_eq!(b.len(), self.n);
        match &self.factor {
            Factor::Banded { bandwidth, band, .. } => banded_solve_in_place(self.n, *bandwidth, band, b),
            Factor::Dense(DenseFactor::Ready(chol)) => {
                let n = self.n;
                chol.solve_mut(&mut DVectorViewMut::from_slice(b, n));
            }
            Factor::Dense(_) => b.fill(f64::NAN),
        }
    }
}

/// Rows of `L` computed together ([`factor_rows`]).
const ROWS: usize = 8;
/// Columns of a group's shared phase computed together ([`columns`]).
const COLS: usize = 4;

/// Row-oriented (Crout) banded Cholesky, overwriting the lower band of `A` with `L`:
/// `L[i][k] = (A[i][k] − Σ_{j<k} L[i][j] L[k][j]) / L[k][k]`, `L[i][i] = √(A[i][i] − Σ_{j<i} L[i][j]²)`,
/// where the sums run only over the band, which the factor inherits from `A` (no fill-in outside it).
/// Rows go [`ROWS`] at a time: each sum is still added in ascending `j`, each product rounded before it is
/// added, so the factor is that of one row at a time, bit for bit — but the group's sums are independent,
/// and where the processor has AVX2 (checked at run time) they go four at a time. `panel` holds at least `b`
/// columns of scratch.
fn banded_cholesky_in_place(n: usize, b: usize, l: &mut [f64], panel: &mut [[f64; ROWS]]) -> Result<(), NotPositiveDefinite> {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has the feature the function is compiled for.
        return unsafe { grouped_avx2(n, b, l, panel) };
    }
    grouped(n, b, l, panel)
}

/// [`grouped`] compiled for AVX2 (the same operations in the same order: the same bits; AVX-512 measured no
/// faster on this machine).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn grouped_avx2(n: usize, b: usize, l: &mut [f64], panel: &mut [[f64; ROWS]]) -> Result<(), NotPositiveDefinite> {
    grouped(n, b, l, panel)
}

/// The factorisation, [`ROWS`] rows at a time, then the rows left over one at a time.
#[inline(always)]
fn grouped(n: usize, b: usize, l: &mut [f64], panel: &mut [[f64; ROWS]]) -> Result<(), NotPositiveDefinite> {
    let mut i = 0;
    while i + ROWS <= n {
        factor_rows::<ROWS>(b, l, i, panel)?;
        i += ROWS;
    }
    (i..n).try_for_each(|i| factor_rows::<1>(b, l, i, &mut []))
}

/// Rows `i … i + R − 1` of `L`, the rows above done. Row `i + r`'s band starts at column
/// `s_r = i + r − b`, and every sum of its columns runs over `j = s_r … k − 1`.
#[inline(always)]
fn factor_rows<const R: usize>(b: usize, l: &mut [f64], i: usize, panel: &mut [[f64; R]]) -> Result<(), NotPositiveDefinite> {
    let origin = |row: usize| origin(b, row);
    let start: [usize; R] = std::array::from_fn(|r| (i + r).saturating_sub(b));
    let common = start[R - 1];
    // The columns k < s_{R−1} some rows reach, row by row: L[i+r][k] = (A − Σ_{j=s_r}^{k−1} L[i+r][j] L[k][j]) / L[k][k].
    for r in 0..R {
        for k in start[r]..common.min(i) {
            set_below(l, origin, i + r, k, start[r]);
        }
    }
    // Columns s_{R−1} ≤ k < i of every row, COLS at a time where R > 1 (panel[k − s_{R−1}] keeps column k).
    let mut k = common;
    if R > 1 {
        while k + COLS <= i {
            columns::<R, COLS>(b, l, i, k, &start, panel);
            k += COLS;
        }
    }
    while k < i {
        if R > 1 {
            columns::<R, 1>(b, l, i, k, &start, panel);
        } else {
            set_below(l, origin, i, k, start[0]);
        }
        k += 1;
    }
    // The group's own columns i ≤ k < i + r and each diagonal L[i+r][i+r] = √(A − Σ_{j=s_r}^{i+r−1} L[i+r][j]²).
    for r in 0..R {
        let row = i + r;
        for k in i.max(start[r])..row {
            set_below(l, origin, row, k, start[r]);
        }
        let d = l[origin(row) + row] - dot(l, origin(row), origin(row), start[r], row);
        if !(d > 0.0 && d.is_finite()) {
            return Err(NotPositiveDefinite { pivot: row });
        }
        l[origin(row) + row] = d.sqrt();
    }
    Ok(())
}

/// Columns `k0 … k0 + C − 1` of rows `i … i + R − 1` (all within `s_{R−1} … i − 1`): for each,
/// `L[i+r][k] = (A − Σ_{j=s_r}^{k−1} L[i+r][j] L[k][j]) / L[k][k]`, the sum in ascending `j` — its columns
/// before `s_{R−1}` by [`dot`], then the group's earlier columns from `panel`, where each column's `R`
/// entries lie side by side and one load serves all `C` columns.
#[inline(always)]
fn columns<const R: usize, const C: usize>(
    b: usize,
    l: &mut [f64],
    i: usize,
    k0: usize,
    start: &[usize; R],
    panel: &mut [[f64; R]],
) {
    let origin = |row: usize| origin(b, row);
    let common = start[R - 1];
    let mut sum: [[f64; R]; C] =
        std::array::from_fn(|c| std::array::from_fn(|r| dot(l, origin(i + r), origin(k0 + c), start[r], common)));
    // Σ_{j=s_{R−1}}^{k0−1}: the panel's columns before the block.
    let rows_k: [&[f64]; C] = std::array::from_fn(|c| &l[origin(k0 + c) + common..origin(k0 + c) + k0]);
    for (jj, p) in panel[..k0 - common].iter().enumerate() {
        for c in 0..C {
            let lkj = rows_k[c][jj];
            for r in 0..R {
                sum[c][r] += p[r] * lkj;
            }
        }
    }
    // The block's own columns, in order: column k0 + c adds j = k0 … k0 + c − 1, then is done.
    for c in 0..C {
        let k = k0 + c;
        let ok = origin(k);
        for j in k0..k {
            let (p, lkj) = (panel[j - common], l[ok + j]);
            for r in 0..R {
                sum[c][r] += p[r] * lkj;
            }
        }
        let lkk = l[ok + k];
        for r in 0..R {
            let e = origin(i + r) + k;
            let value = (l[e] - sum[c][r]) / lkk;
            l[e] = value;
            panel[k - common][r] = value;
        }
    }
}

/// Entry `(row, j)` of a band of half-width `b` sits at `origin(b, row) + j`.
#[inline(always)]
fn origin(b: usize, row: usize) -> usize {
    row * (b + 1) + b - row
}

/// `L[row][k] = (A[row][k] − Σ_{j=from}^{k−1} L[row][j] L[k][j]) / L[k][k]`.
#[inline(always)]
fn set_below(l: &mut [f64], origin: impl Fn(usize) -> usize, row: usize, k: usize, from: usize) {
    let (or, ok) = (origin(row), origin(k));
    l[or + k] = (l[or + k] - dot(l, or, ok, from, k)) / l[ok + k];
}

/// `Σ_{j=from}^{to−1} l[a + j] · l[c + j]`, added in ascending `j` (as `Iterator::sum` adds).
#[inline(always)]
fn dot(l: &[f64], a: usize, c: usize, from: usize, to: usize) -> f64 {
    l[a + from..a + to].iter().zip(&l[c + from..c + to]).map(|(x, y)| x * y).sum()
}

/// `L y = b` forwards, then `Lᵀ x = y` backwards by columns of `Lᵀ` (= rows of `L`, contiguous).
fn banded_solve_in_place(n: usize, b: usize, l: &[f64], x: &mut [f64]) {
    let w = b + 1;
    let at = |i: usize, k: usize| i * w + (k + b - i);
    for i in 0..n {
        let i0 = i.saturating_sub(b);
        let dot: f64 = l[at(i, i0)..at(i, i)].iter().zip(&x[i0..i]).map(|(a, y)| a * y).sum();
        x[i] = (x[i] - dot) / l[at(i, i)];
    }
    for i in (0..n).rev() {
        x[i] /= l[at(i, i)];
        let xi = x[i];
        let i0 = i.saturating_sub(b);
        for (xk, lik) in x[i0..i].iter_mut().zip(&l[at(i, i0)..at(i, i)]) {
            *xk -= lik * xi;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows factorised [`ROWS`] at a time — with AVX2 where this processor has it, and without — give the factor of one row at a time bit for bit, at every bandwidth from diagonal to
    /// wider than a group and sizes that leave a partial group or a partial block of columns.
    #[test]
    fn grouped_rows_give_the_one_row_factor_bit_for_bit() {
        for (n, b) in [(1, 0), (9, 0), (10, 1), (17, 2), (23, 7), (40, 8), (61, 13), (50, 49), (120, 27), (90, 30)] {
            let w = b + 1;
            let mut a = vec![0.0; n * w];
            for i in 0..n {
                for k in i.saturating_sub(b)..=i {
                    let v = ((i * 17 + k * 29) % 31) as f64 / 31.0 - 0.5;
                    a[i * w + (k + b - i)] = if k == i { 2.0 + (b as f64) } else { v };
                }
            }
            let mut grouped = a.clone();
            banded_cholesky_in_place(n, b, &mut grouped, &mut vec![[0.0; ROWS]; b]).unwrap();
            let mut portable = a.clone();
            super::grouped(n, b, &mut portable, &mut vec![[0.0; ROWS]; b]).unwrap();
            let mut single = a;
            (0..n).try_for_each(|i| factor_rows::<1>(b, &mut single, i, &mut [])).unwrap();
            assert_eq!(grouped, single, "n = {n}, b = {b}");
            assert_eq!(portable, single, "n = {n}, b = {b}");
        }
    }
}
