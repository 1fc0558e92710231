//! Symmetric matrices in banded or dense storage, and their Cholesky factorisation `A = L Lᵀ`.
//!
//! The Gauss–Newton matrix `JᵀJ` of the transcribed problem is banded when the unknowns are ordered
//! control-point-major: a residual at a quadrature node touches the 4 control points of its knot span, so
//! `JᵀJ` has half-bandwidth about `4·nv`. A banded Cholesky costs `O(n b²)` instead of `O(n³/3)` — for
//! n = 3000, b = 120 that is 4·10⁷ against 9·10⁹ flops. The structured solver keeps the banded storage even
//! when the band covers the whole matrix: its grouped factorisation is faster than nalgebra's dense one there
//! too. The dense storage (nalgebra's factorisation) serves the secant term's tests and callers that want it.

use nalgebra::DMatrix;

mod cholesky;
mod gram;
pub use cholesky::Cholesky;

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

    /// `A[i][j + k] += values[k]` (and the symmetric entries): a run of one row's consecutive columns. In
    /// the lower triangle and the band (`j + len − 1 ≤ i ≤ j + bandwidth`) the run is contiguous in the
    /// band's storage; elsewhere entry by entry, outside the band dropped as by [`Self::add`].
    pub fn add_row_run(&mut self, i: usize, j: usize, values: &[f64]) {
        if values.is_empty() {
            return;
        }
        let bandwidth = self.bandwidth();
        match &mut self.storage {
            Storage::Banded { band, .. } if j + values.len() <= i + 1 && i - j <= bandwidth && i < self.n => {
                let start = i * (bandwidth + 1) + (j + bandwidth - i);
                band[start..start + values.len()].iter_mut().zip(values).for_each(|(a, v)| *a += v);
            }
            _ => {
                for (k, &v) in values.iter().enumerate() {
                    self.add(i, j + k, v);
                }
            }
        }
    }

    /// Adds to lower-triangle entry `(i, j)`, `i ≥ j`, known to be inside the band.
    pub(crate) fn add_unchecked(&mut self, i: usize, j: usize, value: f64) {
        debug_assert!(i >= j && i - j <= self.bandwidth());
        match &mut self.storage {
            Storage::Banded { bandwidth, band } => band[i * (*bandwidth + 1) + (j + *bandwidth - i)] += value,
            Storage::Dense(m) => m[(i, j)] += value,
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

    /// A run of a row's columns lands where entry-by-entry `add` puts it: inside the band (contiguous), across
    /// the diagonal or the band's edge (entry by entry, outside dropped), and in dense storage.
    #[test]
    fn a_row_run_is_its_entries() {
        for banded in [true, false] {
            for (i, j, len) in [(9, 4, 6), (9, 3, 3), (9, 7, 5), (4, 6, 3), (9, 0, 2), (2, 2, 0)] {
                let (mut run, mut entries) = (test_matrix(12, 5, banded), test_matrix(12, 5, banded));
                let values: Vec<f64> = (0..len).map(|k| 0.25 + k as f64).collect();
                run.add_row_run(i, j, &values);
                for (k, &v) in values.iter().enumerate() {
                    entries.add(i, j + k, v);
                }
                assert_eq!(run.to_dense(), entries.to_dense(), "banded {banded}, row {i} from column {j}, {len} entries");
            }
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
    fn band_checks() {
        let mut a = SymmetricMatrix::banded(5, 1);
        assert!(a.add(2, 1, 1.0));
        assert!(!a.add(0, 2, 1.0));
        assert_eq!(a.get(1, 2), 1.0);
        assert_eq!(a.get(0, 4), 0.0);
        assert_eq!(SymmetricMatrix::banded(3, 10).bandwidth(), 2);
    }
}
