//! A sparse matrix with a fixed sparsity pattern, stored by rows (CSR).
//!
//! The planner's Jacobians have a pattern that never changes during a solve (each residual or constraint
//! at a quadrature node touches the control points of its knot span), so the pattern is built once from
//! per-row column lists and only the values are rewritten at each evaluation.
//!
//! Columns of a row are kept **in the order they were given**, so a problem can write a row's values in
//! its own order through [`SparseMatrix::row_values_mut`]. Duplicate columns in a row are rejected.
//!
//! A row whose columns are listed ascending and consecutive (a node's dependence on its control points,
//! ordered control-point-major) takes a fast path in [`SparseMatrix::add_gram_to`]: contiguous updates,
//! about 5× faster at n = 3000 with rows of 120 columns.

use super::linalg::SymmetricMatrix;

/// Why a sparsity pattern was rejected.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PatternError {
    /// A column index is not below the number of columns.
    #[error("row {row}: column {col} is out of range (there are {ncols} columns)")]
    ColumnOutOfRange {
        /// The row.
        row: usize,
        /// The column listed.
        col: usize,
        /// Columns of the matrix.
        ncols: usize,
    },
    /// A row lists a column twice.
    #[error("row {row}: column {col} is listed twice")]
    DuplicateColumn {
        /// The row.
        row: usize,
        /// The column listed twice.
        col: usize,
    },
    /// A row reaches outside the band the matrix is meant to have.
    #[error("row {row} spans columns {first}..={last}, wider than the target band of half-width {bandwidth}")]
    OutsideBand {
        /// The row.
        row: usize,
        /// Its first column.
        first: usize,
        /// Its last column.
        last: usize,
        /// The half-bandwidth of the band.
        bandwidth: usize,
    },
}

/// A sparse `nrows × ncols` matrix with a fixed pattern.
#[derive(Clone, Debug, PartialEq)]
pub struct SparseMatrix {
    ncols: usize,
    row_ptr: Vec<usize>,
    col_idx: Vec<usize>,
    values: Vec<f64>,
}

impl SparseMatrix {
    /// Builds the pattern from one column list per row; all values start at zero.
    pub fn from_rows(ncols: usize, rows: &[Vec<usize>]) -> Result<Self, PatternError> {
        let nnz = rows.iter().map(Vec::len).sum();
        let mut row_ptr = Vec::with_capacity(rows.len() + 1);
        let mut col_idx = Vec::with_capacity(nnz);
        row_ptr.push(0);
        for (row, cols) in rows.iter().enumerate() {
            let start = col_idx.len();
            for &col in cols {
                if col >= ncols {
                    return Err(PatternError::ColumnOutOfRange { row, col, ncols });
                }
                if col_idx[start..].contains(&col) {
                    return Err(PatternError::DuplicateColumn { row, col });
                }
                col_idx.push(col);
            }
            row_ptr.push(col_idx.len());
        }
        Ok(SparseMatrix { ncols, row_ptr, values: vec![0.0; col_idx.len()], col_idx })
    }

    /// An `nrows × ncols` matrix with every entry in the pattern (for tests and tiny problems).
    pub fn dense_pattern(nrows: usize, ncols: usize) -> Self {
        let rows: Vec<Vec<usize>> = (0..nrows).map(|_| (0..ncols).collect()).collect();
        // Cannot fail: columns are in range and distinct.
        Self::from_rows(ncols, &rows).unwrap_or_else(|_| unreachable!())
    }

    /// Number of rows.
    pub fn nrows(&self) -> usize {
        self.row_ptr.len() - 1
    }

    /// Number of columns.
    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.col_idx.len()
    }

    /// Columns of row `i`, in the order given to [`SparseMatrix::from_rows`].
    pub fn row_cols(&self, i: usize) -> &[usize] {
        &self.col_idx[self.row_ptr[i]..self.row_ptr[i + 1]]
    }

    /// Where row `i`'s entries sit in [`SparseMatrix::values`].
    pub fn row_range(&self, i: usize) -> std::ops::Range<usize> {
        self.row_ptr[i]..self.row_ptr[i + 1]
    }

    /// Values of row `i`, parallel to [`SparseMatrix::row_cols`].
    pub fn row_values(&self, i: usize) -> &[f64] {
        &self.values[self.row_ptr[i]..self.row_ptr[i + 1]]
    }

    /// Values of row `i`, parallel to [`SparseMatrix::row_cols`], for writing.
    pub fn row_values_mut(&mut self, i: usize) -> &mut [f64] {
        &mut self.values[self.row_ptr[i]..self.row_ptr[i + 1]]
    }

    /// All values, row after row.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// All values, row after row, for writing.
    pub fn values_mut(&mut self) -> &mut [f64] {
        &mut self.values
    }

    /// Sets every stored value to zero, keeping the pattern.
    pub fn fill_zero(&mut self) {
        self.values.fill(0.0);
    }

    fn position(&self, i: usize, j: usize) -> Option<usize> {
        let start = *self.row_ptr.get(i)?;
        let end = *self.row_ptr.get(i + 1)?;
        self.col_idx[start..end].iter().position(|&c| c == j).map(|p| start + p)
    }

    /// Sets entry `(i, j)`; returns `false` (and changes nothing) if it is not in the pattern.
    pub fn set(&mut self, i: usize, j: usize, value: f64) -> bool {
        match self.position(i, j) {
            Some(p) => {
                self.values[p] = value;
                true
            }
            None => false,
        }
    }

    /// Adds to entry `(i, j)`; returns `false` (and changes nothing) if it is not in the pattern.
    pub fn add(&mut self, i: usize, j: usize, value: f64) -> bool {
        match self.position(i, j) {
            Some(p) => {
                self.values[p] += value;
                true
            }
            None => false,
        }
    }

    /// Entry `(i, j)`, zero outside the pattern.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.position(i, j).map_or(0.0, |p| self.values[p])
    }

    /// `y = J x`.
    ///
    /// # Panics
    /// If `x.len() != ncols` or `y.len() != nrows` (a programming error, not bad data).
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        assert_eq!(x.len(), self.ncols);
        assert_eq!(y.len(), self.nrows());
        for (i, yi) in y.iter_mut().enumerate() {
            let range = self.row_ptr[i]..self.row_ptr[i + 1];
            *yi = self.col_idx[range.clone()].iter().zip(&self.values[range]).map(|(&c, &v)| v * x[c]).sum();
        }
    }

    /// `y = Jᵀ x`.
    ///
    /// # Panics
    /// If `x.len() != nrows` or `y.len() != ncols`.
    pub fn tr_mul_vec(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        self.tr_mul_vec_add(1.0, x, y);
    }

    /// `y += α Jᵀ x`.
    ///
    /// # Panics
    /// If `x.len() != nrows` or `y.len() != ncols`.
    pub fn tr_mul_vec_add(&self, alpha: f64, x: &[f64], y: &mut [f64]) {
        assert_eq!(x.len(), self.nrows());
        assert_eq!(y.len(), self.ncols);
        for (i, &xi) in x.iter().enumerate() {
            let a = alpha * xi;
            if a == 0.0 {
                continue;
            }
            let range = self.row_ptr[i]..self.row_ptr[i + 1];
            for (&c, &v) in self.col_idx[range.clone()].iter().zip(&self.values[range]) {
                y[c] += a * v;
            }
        }
    }

    /// Half-bandwidth of `JᵀJ`: the largest `max(col) − min(col)` over the rows.
    pub fn gram_bandwidth(&self) -> usize {
        (0..self.nrows()).map(|i| row_span(self.row_cols(i)).map_or(0, |(lo, hi)| hi - lo)).max().unwrap_or(0)
    }

    /// `target += Jᵀ D J` with `D = diag(weights)` (all ones when `None`). Only rows with a non-zero weight
    /// are visited, so inactive inequality constraints cost nothing.
    ///
    /// Fails, leaving `target` partly updated, if a row spans more columns than `target`'s band holds
    /// (size the target with [`SparseMatrix::gram_bandwidth`]).
    ///
    /// # Panics
    /// If `weights` has the wrong length or `target` the wrong size.
    pub fn add_gram_to(&self, weights: Option<&[f64]>, target: &mut SymmetricMatrix) -> Result<(), PatternError> {
        assert_eq!(target.n(), self.ncols);
        if let Some(w) = weights {
            assert_eq!(w.len(), self.nrows());
        }
        let bandwidth = target.bandwidth();
        let weight = |i: usize| weights.map_or(1.0, |w| w[i]);
        // Consecutive rows of one pattern (rows of weight 0 skipped) go to the target as one group of
        // at most GROUP rows, gathered on the stack.
        const GROUP: usize = 8;
        let mut group: [(f64, &[f64]); GROUP] = [(0.0, &[]); GROUP];
        let mut i = 0;
        while i < self.nrows() {
            let cols = self.row_cols(i);
            let (mut next, mut len, mut weighted) = (i, 0, None);
            while next < self.nrows() && len < GROUP && (next == i || self.row_cols(next) == cols) {
                if weight(next) != 0.0 {
                    weighted.get_or_insert(next);
                    group[len] = (weight(next), self.row_values(next));
                    len += 1;
                }
                next += 1;
            }
            if let (Some(row), Some((first, last))) = (weighted, row_span(cols)) {
                if last - first > bandwidth {
                    return Err(PatternError::OutsideBand { row, first, last, bandwidth });
                }
                add_rows(target, cols, &group[..len]);
            }
            i = next;
        }
        Ok(())
    }

    /// The matrix as a dense nalgebra matrix (tests, small problems).
    pub fn to_dense(&self) -> nalgebra::DMatrix<f64> {
        let mut m = nalgebra::DMatrix::zeros(self.nrows(), self.ncols);
        for i in 0..self.nrows() {
            for (&c, &v) in self.row_cols(i).iter().zip(self.row_values(i)) {
                m[(i, c)] += v;
            }
        }
        m
    }
}

/// `target += Σᵣ wᵣ vᵣ vᵣᵀ` for rows `(wᵣ, vᵣ)` over the same columns `cols`, known to fit the band:
/// together when the columns ascend, otherwise entry by entry into the lower triangle.
fn add_rows(target: &mut SymmetricMatrix, cols: &[usize], rows: &[(f64, &[f64])]) {
    if cols.windows(2).all(|c| c[0] < c[1]) {
        return target.add_outer_rows(cols, rows);
    }
    for &(w, vals) in rows {
        for (p, (&cp, &vp)) in cols.iter().zip(vals).enumerate() {
            let wv = w * vp;
            // Each unordered pair {p, q} once: the entry goes to the lower triangle (row ≥ column).
            for (&cq, &vq) in cols[..=p].iter().zip(&vals[..=p]) {
                target.add_unchecked(cp.max(cq), cp.min(cq), wv * vq);
            }
        }
    }
}

fn row_span(cols: &[usize]) -> Option<(usize, usize)> {
    let lo = cols.iter().copied().min()?;
    let hi = cols.iter().copied().max()?;
    Some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn example() -> SparseMatrix {
        // [[1, 0, 2, 0], [0, 3, 0, 0], [4, 0, 0, 5]] with row 0 given out of order.
        let mut m = SparseMatrix::from_rows(4, &[vec![2, 0], vec![1], vec![0, 3]]).unwrap();
        m.row_values_mut(0).copy_from_slice(&[2.0, 1.0]);
        assert!(m.set(1, 1, 3.0));
        assert!(m.set(2, 0, 4.0));
        assert!(m.add(2, 3, 5.0));
        assert!(!m.set(1, 0, 9.0));
        m
    }

    #[test]
    fn rejects_bad_patterns() {
        assert_eq!(SparseMatrix::from_rows(3, &[vec![0, 3]]), Err(PatternError::ColumnOutOfRange { row: 0, col: 3, ncols: 3 }));
        assert_eq!(SparseMatrix::from_rows(3, &[vec![1], vec![2, 0, 2]]), Err(PatternError::DuplicateColumn { row: 1, col: 2 }));
    }

    #[test]
    fn products_match_dense() {
        let m = example();
        let d = m.to_dense();
        assert_eq!(d[(0, 2)], 2.0);
        assert_eq!(m.get(2, 3), 5.0);
        let x = [1.0, -2.0, 0.5, 3.0];
        let mut y = [0.0; 3];
        m.mul_vec(&x, &mut y);
        let yd = &d * nalgebra::DVector::from_column_slice(&x);
        assert_eq!(y.as_slice(), yd.as_slice());

        let z = [0.3, -1.0, 2.0];
        let mut w = [7.0; 4];
        m.tr_mul_vec(&z, &mut w);
        let wd = d.transpose() * nalgebra::DVector::from_column_slice(&z);
        assert_eq!(w.as_slice(), wd.as_slice());
    }

    #[test]
    fn weighted_gram_matches_dense() {
        let m = example();
        assert_eq!(m.gram_bandwidth(), 3);
        let weights = [2.0, 0.0, 0.5];
        for banded in [true, false] {
            let mut g = if banded { SymmetricMatrix::banded(4, 3) } else { SymmetricMatrix::dense(4) };
            m.add_gram_to(Some(&weights), &mut g).unwrap();
            let d = m.to_dense();
            let expect = d.transpose() * nalgebra::DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(&weights)) * &d;
            assert!((g.to_dense() - expect).amax() < 1e-15);
        }
        let mut narrow = SymmetricMatrix::banded(4, 2);
        assert!(matches!(m.add_gram_to(None, &mut narrow), Err(PatternError::OutsideBand { row: 2, .. })));
    }

    /// Rows over consecutive columns take the contiguous fast path; the same rows listed out of order take
    /// the general one; ascending rows with gaps the sorted path. All must give the dense JᵀDJ, in banded
    /// and in dense storage.
    #[test]
    fn contiguous_fast_path_matches_general_path() {
        let n = 12;
        let ordered: Vec<Vec<usize>> = (0..9).map(|i| (i..i + 4).collect()).collect();
        let shuffled: Vec<Vec<usize>> = ordered.iter().map(|r| vec![r[2], r[0], r[3], r[1]]).collect();
        let gapped: Vec<Vec<usize>> = ordered.iter().map(|r| vec![r[0], r[2], r[3]]).collect();
        let weights: Vec<f64> = (0..9).map(|i| 0.5 + i as f64).collect();
        let mut results = Vec::new();
        for rows in [&gapped, &ordered, &shuffled] {
            let mut m = SparseMatrix::from_rows(n, rows).unwrap();
            for (i, row) in rows.iter().enumerate() {
                for (v, &c) in m.row_values_mut(i).iter_mut().zip(row) {
                    *v = ((i * 3 + c * 5) % 7) as f64 - 2.5;
                }
            }
            let d = m.to_dense();
            let w = nalgebra::DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(&weights));
            let expect = d.transpose() * w * &d;
            for mut g in [SymmetricMatrix::banded(n, 3), SymmetricMatrix::dense(n)] {
                m.add_gram_to(Some(&weights), &mut g).unwrap();
                assert!((g.to_dense() - &expect).amax() < 1e-12);
                if rows != &gapped {
                    results.push(g.to_dense());
                }
            }
        }
        assert_eq!(results.len(), 4);
        assert!(results.windows(2).all(|w| (&w[0] - &w[1]).amax() < 1e-12));
    }

    /// Runs of rows with one pattern (up to 11 long, some of weight 0, contiguous and gapped) are added as
    /// groups: the result is bit for bit that of adding the rows one at a time, in banded and dense storage.
    #[test]
    fn grouped_rows_give_the_row_by_row_gram_bit_for_bit() {
        let n = 20;
        let mut rows: Vec<Vec<usize>> = Vec::new();
        for (k, run) in [1usize, 3, 4, 5, 8, 11, 2].iter().enumerate() {
            let cols: Vec<usize> = if k % 2 == 0 { (k..k + 6).collect() } else { vec![k, k + 2, k + 3, k + 7] };
            rows.extend(std::iter::repeat_n(cols, *run));
        }
        let mut m = SparseMatrix::from_rows(n, &rows).unwrap();
        for i in 0..m.nrows() {
            for (k, v) in m.row_values_mut(i).iter_mut().enumerate() {
                *v = ((i * 7 + k * 13) % 23) as f64 / 7.0 - 1.3;
            }
        }
        let weights: Vec<f64> = (0..m.nrows()).map(|i| if i % 5 == 3 { 0.0 } else { 0.1 + i as f64 / 3.0 }).collect();
        for mut g in [SymmetricMatrix::banded(n, 8), SymmetricMatrix::dense(n)] {
            let mut one_by_one = g.clone();
            m.add_gram_to(Some(&weights), &mut g).unwrap();
            for i in (0..m.nrows()).filter(|&i| weights[i] != 0.0) {
                one_by_one.add_outer_sorted(m.row_cols(i), weights[i], m.row_values(i));
            }
            assert_eq!(g, one_by_one);
        }
    }
}
