//! Symmetric matrices in banded or dense storage, and their Cholesky factorisation `A = L Lᵀ`.
//!
//! The Gauss–Newton matrix `JᵀJ` of the transcribed problem is banded when the unknowns are ordered
//! control-point-major: a residual at a quadrature node touches the 4 control points of its knot span, so
//! `JᵀJ` has half-bandwidth about `4·nv`. A banded Cholesky costs `O(n b²)` instead of `O(n³/3)` — for
//! n = 3000, b = 120 that is 4·10⁷ against 9·10⁹ flops. When the band is wide (more than half the matrix)
//! the dense factorisation (nalgebra) is used instead.

use nalgebra::{Cholesky as DenseCholesky, DMatrix, DVectorViewMut, Dyn};

/// The matrix handed to [`Cholesky::factor`] is not (numerically) positive definite.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("matrix is not positive definite (pivot {pivot})")]
pub struct NotPositiveDefinite {
    /// Index of the row whose pivot was not positive.
    pub pivot: usize,
}

/// A symmetric `n × n` matrix; only the lower triangle is stored.
#[derive(Clone, Debug, PartialEq)]
pub struct SymmetricMatrix {
    n: usize,
    storage: Storage,
}

#[derive(Clone, Debug, PartialEq)]
enum Storage {
    /// Half-bandwidth `b`: `A[i][k] = band[i·(b+1) + (k + b − i)]` for `i − b ≤ k ≤ i`, so row `i` of the
    /// lower band is contiguous with increasing column (the inner products of the factorisation run over
    /// contiguous memory). Entries with `k < 0` in the first rows are padding and stay zero.
    Banded { bandwidth: usize, band: Vec<f64> },
    /// Full storage; only the lower triangle is read or written (nalgebra's Cholesky reads only that).
    Dense(DMatrix<f64>),
}

impl SymmetricMatrix {
    /// A zero matrix with half-bandwidth `bandwidth` (clamped to `n − 1`) in banded storage.
    pub fn banded(n: usize, bandwidth: usize) -> Self {
        let bandwidth = bandwidth.min(n.saturating_sub(1));
        SymmetricMatrix { n, storage: Storage::Banded { bandwidth, band: vec![0.0; n * (bandwidth + 1)] } }
    }

    /// A zero matrix in dense storage.
    pub fn dense(n: usize) -> Self {
        SymmetricMatrix { n, storage: Storage::Dense(DMatrix::zeros(n, n)) }
    }

    /// Banded storage when the band covers at most half the matrix, dense otherwise.
    pub fn for_bandwidth(n: usize, bandwidth: usize) -> Self {
        if 2 * (bandwidth + 1) <= n {
            Self::banded(n, bandwidth)
        } else {
            Self::dense(n)
        }
    }

    /// Rows (and columns).
    pub fn n(&self) -> usize {
        self.n
    }

    /// Half-bandwidth: entries with `|i − j|` larger than this are zero (`n − 1` when dense).
    pub fn bandwidth(&self) -> usize {
        match &self.storage {
            Storage::Banded { bandwidth, .. } => *bandwidth,
            Storage::Dense(_) => self.n.saturating_sub(1),
        }
    }

    /// Whether stored as a band.
    pub fn is_banded(&self) -> bool {
        matches!(self.storage, Storage::Banded { .. })
    }

    /// Sets every entry to zero, keeping the storage.
    pub fn fill_zero(&mut self) {
        match &mut self.storage {
            Storage::Banded { band, .. } => band.fill(0.0),
            Storage::Dense(m) => m.fill(0.0),
        }
    }

    /// Entry `(i, j)` (either triangle; zero outside the band).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (i, j) = (i.max(j), i.min(j));
        match &self.storage {
            Storage::Banded { bandwidth, band } => {
                if i - j > *bandwidth {
                    0.0
                } else {
                    band[i * (bandwidth + 1) + (j + bandwidth - i)]
                }
            }
            Storage::Dense(m) => m[(i, j)],
        }
    }

    /// Adds `value` to entries `(i, j)` and `(j, i)`; returns `false` (and changes nothing) if `(i, j)` is
    /// outside the band.
    pub fn add(&mut self, i: usize, j: usize, value: f64) -> bool {
        let (i, j) = (i.max(j), i.min(j));
        if i - j > self.bandwidth() || i >= self.n {
            return false;
        }
        self.add_unchecked(i, j, value);
        true
    }

    /// Adds to lower-triangle entry `(i, j)`, `i ≥ j`, known to be inside the band.
    pub(crate) fn add_unchecked(&mut self, i: usize, j: usize, value: f64) {
        debug_assert!(i >= j && i - j <= self.bandwidth());
        match &mut self.storage {
            Storage::Banded { bandwidth, band } => band[i * (*bandwidth + 1) + (j + *bandwidth - i)] += value,
            Storage::Dense(m) => m[(i, j)] += value,
        }
    }

    /// `A += w v vᵀ` for a vector `v` whose entries belong to the contiguous columns
    /// `first, first + 1, …, first + v.len() − 1`, known to fit in the band. This is the common case of a
    /// Jacobian row over consecutive control points, and the inner loops become contiguous axpys.
    pub(crate) fn add_outer_contiguous(&mut self, first: usize, w: f64, v: &[f64]) {
        debug_assert!(first + v.len() <= self.n && v.len() <= self.bandwidth() + 1);
        match &mut self.storage {
            Storage::Banded { bandwidth, band } => {
                // Row c = first + p of the lower band holds columns first..=c contiguously.
                let b = *bandwidth;
                for (p, &vp) in v.iter().enumerate() {
                    let c = first + p;
                    let start = c * (b + 1) + (first + b - c);
                    axpy(w * vp, &v[..=p], &mut band[start..=start + p]);
                }
            }
            Storage::Dense(m) => {
                // Column c = first + q (column-major) holds rows c..first+len contiguously.
                for (q, &vq) in v.iter().enumerate() {
                    let c = first + q;
                    let column = &mut m.column_mut(c);
                    let slice = &mut column.as_mut_slice()[c..first + v.len()];
                    axpy(w * vq, &v[q..], slice);
                }
            }
        }
    }

    /// `A += w v vᵀ` for a vector `v` whose entries belong to the ascending columns `cols`, known to fit in
    /// the band: a Jacobian row that skips columns (a torque row, supported on the joints of its chain).
    pub(crate) fn add_outer_sorted(&mut self, cols: &[usize], w: f64, v: &[f64]) {
        debug_assert!(cols.windows(2).all(|c| c[0] < c[1]) && cols.len() == v.len());
        match &mut self.storage {
            Storage::Banded { bandwidth, band } => {
                // A[c_p][c_q] (q ≤ p) sits at band[c_p·(b+1) + b − c_p + c_q]: row c_p's origin plus c_q.
                let b = *bandwidth;
                for (p, (&cp, &vp)) in cols.iter().zip(v).enumerate() {
                    let origin = cp * (b + 1) + b - cp;
                    let wv = w * vp;
                    for (&cq, &vq) in cols[..=p].iter().zip(&v[..=p]) {
                        band[origin + cq] += wv * vq;
                    }
                }
            }
            Storage::Dense(m) => {
                for (q, (&cq, &vq)) in cols.iter().zip(v).enumerate() {
                    let mut column = m.column_mut(cq);
                    let wv = w * vq;
                    for (&cp, &vp) in cols[q..].iter().zip(&v[q..]) {
                        column[cp] += wv * vp;
                    }
                }
            }
        }
    }

    /// `A += B`, `B` of the same size and storage.
    ///
    /// # Panics
    /// If the sizes or storages differ.
    pub fn add_matrix(&mut self, other: &SymmetricMatrix) {
        assert_eq!(self.n, other.n);
        match (&mut self.storage, &other.storage) {
            (Storage::Banded { bandwidth: a, band }, Storage::Banded { bandwidth: b, band: other }) if a == b => {
                band.iter_mut().zip(other).for_each(|(x, y)| *x += y);
            }
            (Storage::Dense(m), Storage::Dense(other)) => *m += other,
            _ => panic!("add_matrix: the storages differ"),
        }
    }

    /// The diagonal entry `A[i][i]`.
    pub fn diagonal(&self, i: usize) -> f64 {
        self.get(i, i)
    }

    /// `y = A x`.
    ///
    /// # Panics
    /// If the lengths are not `n`.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        assert_eq!(x.len(), self.n);
        assert_eq!(y.len(), self.n);
        y.fill(0.0);
        let b = self.bandwidth();
        for i in 0..self.n {
            for j in i.saturating_sub(b)..i {
                let a = self.get(i, j);
                y[i] += a * x[j];
                y[j] += a * x[i];
            }
            y[i] += self.get(i, i) * x[i];
        }
    }

    /// The full matrix (tests, diagnostics).
    pub fn to_dense(&self) -> DMatrix<f64> {
        DMatrix::from_fn(self.n, self.n, |i, j| self.get(i, j))
    }
}

/// `y += a x`.
fn axpy(a: f64, x: &[f64], y: &mut [f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

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
            Storage::Banded { bandwidth, band } => Factor::Banded { bandwidth: *bandwidth, band: vec![0.0; band.len()] },
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
            (Factor::Banded { bandwidth, band: l }, Storage::Banded { bandwidth: ab, band: a_band }) => {
                assert_eq!(bandwidth, ab);
                l.copy_from_slice(a_band);
                let w = *bandwidth + 1;
                if let Some(s) = shift {
                    for (i, si) in s.iter().enumerate() {
                        l[i * w + *bandwidth] += si;
                    }
                }
                banded_cholesky_in_place(n, *bandwidth, l)
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
            Factor::Banded { bandwidth, band } => banded_solve_in_place(self.n, *bandwidth, band, b),
            Factor::Dense(DenseFactor::Ready(chol)) => {
                let n = self.n;
                chol.solve_mut(&mut DVectorViewMut::from_slice(b, n));
            }
            Factor::Dense(_) => b.fill(f64::NAN),
        }
    }
}

/// Row-oriented (Crout) banded Cholesky, overwriting the lower band of `A` with `L`:
/// `L[i][k] = (A[i][k] − Σ_{j<k} L[i][j] L[k][j]) / L[k][k]`, `L[i][i] = √(A[i][i] − Σ_{j<i} L[i][j]²)`,
/// where the sums run only over the band, which the factor inherits from `A` (no fill-in outside it).
fn banded_cholesky_in_place(n: usize, b: usize, l: &mut [f64]) -> Result<(), NotPositiveDefinite> {
    let w = b + 1;
    let at = |i: usize, k: usize| i * w + (k + b - i);
    for i in 0..n {
        let i0 = i.saturating_sub(b);
        for k in i0..i {
            let j0 = i0.max(k.saturating_sub(b));
            let dot: f64 = l[at(i, j0)..at(i, k)].iter().zip(&l[at(k, j0)..at(k, k)]).map(|(x, y)| x * y).sum();
            l[at(i, k)] = (l[at(i, k)] - dot) / l[at(k, k)];
        }
        let sq: f64 = l[at(i, i0)..at(i, i)].iter().map(|x| x * x).sum();
        let d = l[at(i, i)] - sq;
        if !(d > 0.0 && d.is_finite()) {
            return Err(NotPositiveDefinite { pivot: i });
        }
        l[at(i, i)] = d.sqrt();
    }
    Ok(())
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

    /// A deterministic, diagonally dominant symmetric banded matrix.
    fn test_matrix(n: usize, b: usize, banded: bool) -> SymmetricMatrix {
        let mut a = if banded { SymmetricMatrix::banded(n, b) } else { SymmetricMatrix::dense(n) };
        for i in 0..n {
            for j in i.saturating_sub(b)..i {
                let v = ((i * 7 + j * 13) % 11) as f64 / 11.0 - 0.5;
                assert!(a.add(i, j, v));
            }
            a.add(i, i, 1.0 + b as f64 + (i % 3) as f64);
        }
        a
    }

    #[test]
    fn banded_cholesky_equals_dense() {
        for (n, b) in [(1, 0), (5, 0), (9, 2), (40, 7), (60, 59), (200, 13)] {
            let a = test_matrix(n, b, true);
            let dense = a.to_dense();
            assert!(a.is_banded());
            let shift: Vec<f64> = (0..n).map(|i| 0.1 * (i % 4) as f64).collect();
            let mut chol = Cholesky::for_matrix(&a);
            chol.factor(&a, Some(&shift)).unwrap();
            let rhs: Vec<f64> = (0..n).map(|i| (i as f64).sin() + 0.5).collect();
            let mut x = rhs.clone();
            chol.solve_in_place(&mut x);

            let shifted = &dense + DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(&shift));
            let expect = shifted.clone().cholesky().unwrap().solve(&nalgebra::DVector::from_column_slice(&rhs));
            let err = (nalgebra::DVector::from_column_slice(&x) - &expect).amax();
            assert!(err < 1e-12 * (1.0 + expect.amax()), "n={n} b={b}: error {err}");

            // And our dense path (nalgebra) on the same matrix.
            let ad = test_matrix(n, b, false);
            assert_eq!(ad.to_dense(), dense);
            let mut chol_d = Cholesky::for_matrix(&ad);
            chol_d.factor(&ad, Some(&shift)).unwrap();
            let mut xd = rhs.clone();
            chol_d.solve_in_place(&mut xd);
            assert!(xd.iter().zip(&x).all(|(p, q)| (p - q).abs() < 1e-12 * (1.0 + q.abs())));

            let mut y = vec![0.0; n];
            a.mul_vec(&x, &mut y);
            let ye = &dense * nalgebra::DVector::from_column_slice(&x);
            assert!((nalgebra::DVector::from_column_slice(&y) - ye).amax() < 1e-12 * (1.0 + expect.amax()));
        }
    }

    #[test]
    fn refactoring_reuses_storage_and_detects_indefinite() {
        for banded in [true, false] {
            let mut a = test_matrix(6, 2, banded);
            let mut chol = Cholesky::for_matrix(&a);
            a.add(3, 3, -100.0);
            let failure = chol.factor(&a, None);
            if banded {
                assert_eq!(failure, Err(NotPositiveDefinite { pivot: 3 }));
            } else {
                // nalgebra's dense path does not say which pivot failed.
                assert!(failure.is_err());
            }
            // A large enough shift makes it definite again; the solve then agrees with dense.
            let shift = vec![200.0; 6];
            chol.factor(&a, Some(&shift)).unwrap();
            let mut x = vec![1.0; 6];
            chol.solve_in_place(&mut x);
            let m = a.to_dense() + DMatrix::from_diagonal_element(6, 6, 200.0);
            let r = &m * nalgebra::DVector::from_column_slice(&x) - nalgebra::DVector::from_element(6, 1.0);
            assert!(r.amax() < 1e-12);
        }
    }

    #[test]
    fn storage_choice_and_band_checks() {
        assert!(SymmetricMatrix::for_bandwidth(100, 10).is_banded());
        assert!(!SymmetricMatrix::for_bandwidth(10, 6).is_banded());
        let mut a = SymmetricMatrix::banded(5, 1);
        assert!(a.add(2, 1, 1.0));
        assert!(!a.add(0, 2, 1.0));
        assert_eq!(a.get(1, 2), 1.0);
        assert_eq!(a.get(0, 4), 0.0);
        assert_eq!(SymmetricMatrix::banded(3, 10).bandwidth(), 2);
    }
}
