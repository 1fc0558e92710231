//! Several rank-one updates of one sparsity pattern at once, `A += Σᵣ wᵣ vᵣ vᵣᵀ`: the Gauss–Newton
//! matrix of rows that share their columns (the torque rows of one joint at the nodes of one knot span
//! do) loads and stores each entry once per group instead of once per row. Per entry the terms are added
//! in the rows' order, each as `(wᵣ·vᵣ[p])·vᵣ[q]`, so the result is bit for bit that of
//! [`SymmetricMatrix::add_outer_sorted`] row after row.

use super::{Storage, SymmetricMatrix};

/// Rows updated together at most (the compiled group sizes are 8, 4, 2 and 1).
const GROUP: usize = 8;

impl SymmetricMatrix {
    /// `A += Σᵣ wᵣ vᵣ vᵣᵀ` for rows `(wᵣ, vᵣ)` whose entries all belong to the ascending columns `cols`,
    /// known to fit in the band.
    pub(crate) fn add_outer_rows(&mut self, cols: &[usize], rows: &[(f64, &[f64])]) {
        debug_assert!(cols.windows(2).all(|c| c[0] < c[1]) && rows.iter().all(|(_, v)| v.len() == cols.len()));
        if !self.is_banded() {
            rows.iter().for_each(|&(w, v)| self.add_outer_sorted(cols, w, v));
            return;
        }
        let mut chunks = rows;
        while !chunks.is_empty() {
            let taken = match chunks.len() {
                n if n >= GROUP => self.add_group::<GROUP>(cols, &chunks[..GROUP]),
                n if n >= 4 => self.add_group::<4>(cols, &chunks[..4]),
                n if n >= 2 => self.add_group::<2>(cols, &chunks[..2]),
                _ => self.add_group::<1>(cols, &chunks[..1]),
            };
            chunks = &chunks[taken..];
        }
    }

    /// `A += Σᵣ wᵣ vᵣ vᵣᵀ` for exactly `R` rows (banded storage); returns `R`.
    fn add_group<const R: usize>(&mut self, cols: &[usize], rows: &[(f64, &[f64])]) -> usize {
        let Storage::Banded { bandwidth, band } = &mut self.storage else { unreachable!("banded only") };
        let b = *bandwidth;
        let v: [&[f64]; R] = std::array::from_fn(|r| rows[r].1);
        let contiguous = cols.last().is_none_or(|&l| l - cols[0] + 1 == cols.len());
        for (p, &cp) in cols.iter().enumerate() {
            // A[c_p][c_q] (q ≤ p) sits at band[c_p·(b+1) + b − c_p + c_q]: row c_p's origin plus c_q.
            let origin = cp * (b + 1) + b - cp;
            let wv: [f64; R] = std::array::from_fn(|r| rows[r].0 * v[r][p]);
            if contiguous {
                // Row c_p of the lower band holds columns cols[0]..=c_p contiguously.
                let start = origin + cols[0];
                let entries = &mut band[start..=start + p];
                let vq: [&[f64]; R] = std::array::from_fn(|r| &v[r][..=p]);
                for (q, a) in entries.iter_mut().enumerate() {
                    let mut s = *a;
                    for r in 0..R {
                        s += wv[r] * vq[r][q];
                    }
                    *a = s;
                }
            } else {
                for (q, &cq) in cols[..=p].iter().enumerate() {
                    let mut s = band[origin + cq];
                    for r in 0..R {
                        s += wv[r] * v[r][q];
                    }
                    band[origin + cq] = s;
                }
            }
        }
        R
    }
}
