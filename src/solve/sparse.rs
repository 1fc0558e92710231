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

mod gram;

use gram::Run;

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
    /// The runs of rows with one column list, in the order of their first rows (fixed with the pattern; see
    /// [`gram`]; none for a matrix without entries, whose Gram matrix is zero).
    runs: Vec<Run>,
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
        let runs = gram::runs(&row_ptr, &col_idx);
        Ok(SparseMatrix { ncols, row_ptr, values: vec![0.0; col_idx.len()], col_idx, runs })
    }

    /// An `nrows × ncols` matrix with no entry in its pattern (a Jacobian that is not asked for).
    pub fn without_entries(nrows: usize, ncols: usize) -> Self {
        SparseMatrix { ncols, row_ptr: vec![0; nrows + 1], col_idx: vec![], values: vec![], runs: vec![] }
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

    /// `out[j] = Σᵢ Jᵢⱼ²`, the diagonal of `JᵀJ`.
    ///
    /// # Panics
    /// If `out` is not `ncols` long.
    pub fn column_squares(&self, out: &mut [f64]) {
        assert_eq!(out.len(), self.ncols);
        out.fill(0.0);
        for i in 0..self.nrows() {
            for (&j, v) in self.row_cols(i).iter().zip(self.row_values(i)) {
                out[j] += v * v;
            }
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    pub(super) fn example() -> SparseMatrix {
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
}
