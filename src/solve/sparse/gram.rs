//! The Gram matrix `JᵀDJ` of a [`SparseMatrix`], added row group by row group: the rows with one column list
//! (the torque rows of the joints of one limb at the nodes of one knot span: each depends on the same
//! control points of the same joints) are one [`Run`], found once when the pattern is built, and go to the
//! target together, up to eight at a time ([`SymmetricMatrix::add_outer_rows`]): each entry of the target is
//! loaded and stored once per eight rows instead of once per row.

use super::{PatternError, SparseMatrix};
use crate::solve::linalg::SymmetricMatrix;
use std::collections::HashMap;

/// The rows with the same column list (in the same order), wherever they are.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Run {
    /// The rows, ascending.
    rows: Vec<usize>,
    /// The smallest and the largest column (`None` for empty rows).
    span: Option<(usize, usize)>,
    /// Whether the columns ascend.
    ascending: bool,
}

/// The runs of the pattern `row_ptr`, `col_idx` (CSR), in the order of their first rows.
pub(super) fn runs(row_ptr: &[usize], col_idx: &[usize]) -> Vec<Run> {
    let cols = |i: usize| &col_idx[row_ptr[i]..row_ptr[i + 1]];
    let mut runs: Vec<Run> = Vec::new();
    let mut index: HashMap<&[usize], usize> = HashMap::new();
    for i in 0..row_ptr.len() - 1 {
        let run = *index.entry(cols(i)).or_insert_with(|| {
            let ascending = cols(i).windows(2).all(|c| c[0] < c[1]);
            runs.push(Run { rows: Vec::new(), span: row_span(cols(i)), ascending });
            runs.len() - 1
        });
        runs[run].rows.push(i);
    }
    runs
}

impl SparseMatrix {
    /// Half-bandwidth of `JᵀJ`: the largest `max(col) − min(col)` over the rows.
    pub fn gram_bandwidth(&self) -> usize {
        self.runs.iter().map(|run| run.span.map_or(0, |(lo, hi)| hi - lo)).max().unwrap_or(0)
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
        // The rows of one pattern (one run; rows of weight 0 skipped) go to the target in groups of at most
        // GROUP rows, gathered on the stack.
        const GROUP: usize = 8;
        let mut group: [(f64, &[f64]); GROUP] = [(0.0, &[]); GROUP];
        for run in &self.runs {
            let Some((lo, hi)) = run.span else { continue };
            let mut rows = run.rows.iter().copied().filter(|&i| weight(i) != 0.0).peekable();
            let Some(&first) = rows.peek() else { continue };
            if hi - lo > bandwidth {
                return Err(PatternError::OutsideBand { row: first, first: lo, last: hi, bandwidth });
            }
            while rows.peek().is_some() {
                let mut len = 0;
                for i in rows.by_ref().take(GROUP) {
                    group[len] = (weight(i), self.row_values(i));
                    len += 1;
                }
                add_rows(target, self.row_cols(first), run.ascending, &group[..len]);
            }
        }
        Ok(())
    }
}

/// `target += Σᵣ wᵣ vᵣ vᵣᵀ` for rows `(wᵣ, vᵣ)` over the same columns `cols`, known to fit the band:
/// together when the columns ascend, otherwise entry by entry into the lower triangle.
fn add_rows(target: &mut SymmetricMatrix, cols: &[usize], ascending: bool, rows: &[(f64, &[f64])]) {
    if ascending {
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
    use crate::solve::sparse::tests::example;

    /// `JᵀDJ` of `m` from its dense form.
    fn dense_gram(m: &SparseMatrix, weights: &[f64]) -> nalgebra::DMatrix<f64> {
        let d = m.to_dense();
        d.transpose() * nalgebra::DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(weights)) * &d
    }

    #[test]
    fn rows_without_entries_add_nothing() {
        let m = SparseMatrix::without_entries(3, 5);
        assert_eq!((m.nrows(), m.ncols(), m.nnz(), m.gram_bandwidth()), (3, 5, 0, 0));
        let mut g = SymmetricMatrix::banded(5, 1);
        m.add_gram_to(Some(&[1.0; 3]), &mut g).unwrap();
        assert_eq!(g, SymmetricMatrix::banded(5, 1));
        assert_eq!(SparseMatrix::without_entries(0, 2).gram_bandwidth(), 0);
    }

    #[test]
    fn weighted_gram_matches_dense() {
        let m = example();
        assert_eq!(m.gram_bandwidth(), 3);
        let weights = [2.0, 0.0, 0.5];
        for banded in [true, false] {
            let mut g = if banded { SymmetricMatrix::banded(4, 3) } else { SymmetricMatrix::dense(4) };
            m.add_gram_to(Some(&weights), &mut g).unwrap();
            assert!((g.to_dense() - dense_gram(&m, &weights)).amax() < 1e-15);
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
            let expect = dense_gram(&m, &weights);
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

    /// Rows of one column list that are not consecutive (a limb's torque rows at the nodes of a span, other
    /// joints' rows between them) are one run, and their Gram matrix is the dense `JᵀDJ`.
    #[test]
    fn rows_of_one_column_list_anywhere_are_one_run() {
        let n = 10;
        let patterns = [vec![0, 1, 2, 3], vec![2, 4, 5], vec![6, 7, 8, 9]];
        let rows: Vec<Vec<usize>> = (0..13).map(|i| patterns[i % 3].clone()).collect();
        let mut m = SparseMatrix::from_rows(n, &rows).unwrap();
        assert_eq!(m.runs.len(), 3);
        assert_eq!(m.runs[0].rows, vec![0, 3, 6, 9, 12]);
        for i in 0..m.nrows() {
            for (k, v) in m.row_values_mut(i).iter_mut().enumerate() {
                *v = ((i * 11 + k * 5) % 13) as f64 / 4.0 - 1.1;
            }
        }
        let weights: Vec<f64> = (0..m.nrows()).map(|i| if i == 4 { 0.0 } else { 0.3 + i as f64 }).collect();
        let expect = dense_gram(&m, &weights);
        for mut g in [SymmetricMatrix::banded(n, 3), SymmetricMatrix::dense(n)] {
            m.add_gram_to(Some(&weights), &mut g).unwrap();
            assert!((g.to_dense() - &expect).amax() < 1e-12);
        }
    }
}
