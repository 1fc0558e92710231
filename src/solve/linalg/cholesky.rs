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
