//! The second-order term of the augmented Lagrangian's Hessian, kept banded: a partitioned structured
//! quasi-Newton approximation (Griewank & Toint 1982; the structured secant of Dennis, Gay & Welsch's
//! NL2SOL, 1981).
//!
//! # What it approximates
//!
//! With `L_A = ½‖R‖²` (see [`super::least_squares`]), `∇²L_A = JᵀJ + Σⱼ wⱼ ∇²cⱼ`, the sum over every
//! residual and constraint row `cⱼ` with its weight in the gradient: `wⱼ = rⱼ` for the objective's
//! residuals, `(μ_k + 2w_p ĥ_k)/s_k` for the equalities and `(λᵢ + 2w_p ĝᵢ)/sᵢ` for the active
//! inequalities — exactly the coefficients of `∇L_A = Σ wⱼ ∇cⱼ`. Gauss–Newton keeps `JᵀJ` and drops the
//! sum; on minimum-torque problems the residuals stay large at the optimum, so that is what makes
//! Levenberg–Marquardt linear.
//!
//! # Partitioned
//!
//! Rows that touch the same set of columns form an *element* `e` (for the transcription: every row at the
//! nodes of one knot span — its four control points — or a contact node's closure rows). The sum splits as
//! `Σₑ Pₑᵀ Sₑ Pₑ`, `Sₑ` a small dense matrix over the element's columns `Pₑ`, so the model keeps the band of
//! `JᵀJ`. Each `Sₑ` is updated after every accepted step `x → x₊` from its own secant pair
//!
//! ```text
//!   sₑ = Pₑ (x₊ − x),    yₑ = Pₑ Σ_{j ∈ e} wⱼ(x₊) (∇cⱼ(x₊) − ∇cⱼ(x))      (NL2SOL's y#, element-wise)
//! ```
//!
//! by the symmetric rank-one formula `Sₑ += v vᵀ / vᵀsₑ`, `v = yₑ − Sₑsₑ` (skipped when `|vᵀs| < 10⁻⁸‖s‖‖v‖`).
//! (NL2SOL's sizing `Sₑ ← min(1, |sᵀy|/|sᵀSₑs|) Sₑ` was tried: on indefinite elements it shrinks what was
//! learnt at every step and destroys SR1's hereditary property — a quadratic element is no longer recovered.)
//! SR1 because the term is indefinite (a torque against gravity curves both ways); the trust region of the
//! inner solver takes care of an indefinite model. Rows that are linear in `x` (position limits, contact-force
//! signs) give `yₑ = 0` and their elements stay zero. The update costs `O(Σ mₑ²)`, a few percent of an
//! evaluation; nothing is allocated after [`SecondOrderTerm::new`].

use super::auglag::AugmentedLagrangian;
use super::linalg::SymmetricMatrix;
use super::line_search::EvalError;
use super::problem::{Evaluation, RowFamily};
use std::collections::HashMap;

/// Rows sharing one column set, and the dense approximation `Sₑ` over those columns.
#[derive(Clone, Debug)]
struct Element {
    /// Global columns, ascending.
    cols: Vec<usize>,
    /// The element's rows.
    rows: Vec<(RowFamily, usize)>,
    /// For each row, the local index of each of its entries (in the row's storage order), concatenated.
    local: Vec<usize>,
    /// Row-major `m × m`, symmetric.
    s: Vec<f64>,
    /// Whether `s` has ever been updated (zero elements are skipped when assembling).
    nonzero: bool,
}

/// The partitioned approximation of `Σ wⱼ ∇²cⱼ`, with the previous point's Jacobians for the secant pairs.
#[derive(Clone, Debug)]
pub(crate) struct SecondOrderTerm {
    elements: Vec<Element>,
    previous: [Vec<f64>; 3],
    x_previous: Vec<f64>,
    /// The gradient weights at `x_previous` (`[r, w_h, w_g]`), for [`SecondOrderTerm::refresh`].
    weights: [Vec<f64>; 3],
    /// Columns perturbed together by [`SecondOrderTerm::refresh`] are this far apart: one more than the
    /// widest element's span, so no element sees two of them.
    colour_spacing: usize,
    x_perturbed: Vec<f64>,
    /// Work vectors of the largest element's size.
    step: Vec<f64>,
    secant: Vec<f64>,
    product: Vec<f64>,
    /// Updates made and skipped (for the performance notes and tests).
    pub(crate) updates: usize,
    pub(crate) skipped: usize,
}

impl SecondOrderTerm {
    /// Groups the rows of `eval`'s Jacobians into elements by their column sets; all `Sₑ = 0`.
    pub(crate) fn new(eval: &Evaluation) -> Self {
        let mut by_columns: HashMap<Vec<usize>, usize> = HashMap::new();
        let mut elements: Vec<Element> = Vec::new();
        for family in [RowFamily::Residual, RowFamily::Equality, RowFamily::Inequality] {
            let m = eval.jacobian(family);
            for i in 0..m.nrows() {
                let mut cols = m.row_cols(i).to_vec();
                if cols.is_empty() {
                    continue;
                }
                cols.sort_unstable();
                let e = *by_columns.entry(cols.clone()).or_insert_with(|| {
                    elements.push(Element { cols, rows: Vec::new(), local: Vec::new(), s: Vec::new(), nonzero: false });
                    elements.len() - 1
                });
                let element = &mut elements[e];
                element.rows.push((family, i));
                for c in m.row_cols(i) {
                    element.local.push(element.cols.binary_search(c).expect("column of its own element"));
                }
            }
        }
        let largest = elements.iter().map(|e| e.cols.len()).max().unwrap_or(0);
        let colour_spacing = elements.iter().map(|e| e.cols[e.cols.len() - 1] - e.cols[0] + 1).max().unwrap_or(1);
        for e in &mut elements {
            e.s = vec![0.0; e.cols.len() * e.cols.len()];
        }
        SecondOrderTerm {
            elements,
            previous: [eval.jr.values().to_vec(), eval.jh.values().to_vec(), eval.jg.values().to_vec()],
            x_previous: vec![0.0; eval.jr.ncols()],
            weights: [vec![0.0; eval.r.len()], vec![0.0; eval.h.len()], vec![0.0; eval.g.len()]],
            colour_spacing,
            x_perturbed: vec![0.0; eval.jr.ncols()],
            step: vec![0.0; largest],
            secant: vec![0.0; largest],
            product: vec![0.0; largest],
            updates: 0,
            skipped: 0,
        }
    }

    /// Number of elements.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.elements.len()
    }

    /// Remembers `x`, the Jacobians at `x` (in `eval`) and the gradient weights there as the start of the
    /// next secant pair.
    pub(crate) fn remember(&mut self, x: &[f64], eval: &Evaluation, weights: [&[f64]; 3]) {
        self.x_previous.copy_from_slice(x);
        self.previous[0].copy_from_slice(eval.jr.values());
        self.previous[1].copy_from_slice(eval.jh.values());
        self.previous[2].copy_from_slice(eval.jg.values());
        for (mine, given) in self.weights.iter_mut().zip(weights) {
            mine.copy_from_slice(given);
        }
    }

    /// Replaces every `Sₑ` by forward differences of the element gradients at the remembered point, weights
    /// held fixed: column `a` of `Sₑ` is `(gₑ(x + εe_j) − gₑ(x))/ε`, `gₑ = Pₑ Σ_{j∈e} wⱼ∇cⱼ`, `j` the column
    /// of `a`. Columns `colour_spacing` apart are perturbed together (Curtis, Powell & Reid's grouping,
    /// element-wise: each element sees at most one of them), so the whole term costs `colour_spacing`
    /// evaluations — about `4·nv` for the transcription. `ε = 10⁻⁷(1 + |x_j|)`; the result is symmetrised.
    /// Leaves `al` evaluated at a perturbed point.
    pub(crate) fn refresh(&mut self, al: &mut AugmentedLagrangian<'_>) -> Result<(), EvalError> {
        let n = self.x_previous.len();
        for e in &mut self.elements {
            e.s.fill(0.0);
        }
        for colour in 0..self.colour_spacing.min(n) {
            self.x_perturbed.copy_from_slice(&self.x_previous);
            for j in (colour..n).step_by(self.colour_spacing) {
                let x = self.x_previous[j];
                self.x_perturbed[j] = x + 1e-7 * (1.0 + x.abs());
            }
            al.evaluate(&self.x_perturbed, true)?;
            for e in 0..self.elements.len() {
                self.difference_column(e, colour, &al.eval);
            }
        }
        for e in &mut self.elements {
            let m = e.cols.len();
            for a in 0..m {
                for b in 0..a {
                    let mean = 0.5 * (e.s[a * m + b] + e.s[b * m + a]);
                    e.s[a * m + b] = mean;
                    e.s[b * m + a] = mean;
                }
            }
            e.nonzero = e.s.iter().any(|v| *v != 0.0);
        }
        Ok(())
    }

    /// Column of element `e`'s perturbed column in `colour` (if it has one) from the Jacobians in `eval`.
    fn difference_column(&mut self, e: usize, colour: usize, eval: &Evaluation) {
        let element = &mut self.elements[e];
        let Some(a) = element.cols.iter().position(|c| c % self.colour_spacing == colour) else {
            return;
        };
        let j = element.cols[a];
        let epsilon = self.x_perturbed[j] - self.x_previous[j];
        let m = element.cols.len();
        let column = &mut self.secant[..m];
        let weights = [&self.weights[0][..], &self.weights[1][..], &self.weights[2][..]];
        weighted_difference(element, eval, &self.previous, weights, column);
        for (b, v) in column.iter().enumerate() {
            element.s[b * m + a] = v / epsilon;
        }
    }

    /// Updates every `Sₑ` from the step to `x` (Jacobians at `x` in `eval`), with the weights at `x`:
    /// `weights = (r, coefficients of ∇h, coefficients of ∇g)` as in `∇L_A`.
    pub(crate) fn update(&mut self, x: &[f64], eval: &Evaluation, weights: [&[f64]; 3]) {
        for e in 0..self.elements.len() {
            self.update_element(e, x, eval, weights);
        }
    }

    fn update_element(&mut self, e: usize, x: &[f64], eval: &Evaluation, weights: [&[f64]; 3]) {
        let element = &mut self.elements[e];
        let m = element.cols.len();
        let (s, y, ss) = (&mut self.step[..m], &mut self.secant[..m], &mut self.product[..m]);
        // sₑ = Pₑ(x₊ − x)
        for (sa, &c) in s.iter_mut().zip(&element.cols) {
            *sa = x[c] - self.x_previous[c];
        }
        let s_norm2: f64 = s.iter().map(|v| v * v).sum();
        if s_norm2 == 0.0 {
            return;
        }
        // yₑ = Σⱼ wⱼ(x₊) (∇cⱼ(x₊) − ∇cⱼ(x)), over the element's columns
        weighted_difference(element, eval, &self.previous, weights, y);
        if !element.nonzero && y.iter().all(|v| *v == 0.0) {
            return; // a linear element, or inactive rows: nothing to learn
        }
        // Sₑsₑ
        symmetric_mul(&element.s, s, ss);
        // SR1: v = y − Sₑs, Sₑ += v vᵀ / vᵀs
        for (v, p) in y.iter_mut().zip(ss.iter()) {
            *v -= p;
        }
        let v_s: f64 = y.iter().zip(s.iter()).map(|(a, b)| a * b).sum();
        let v_norm2: f64 = y.iter().map(|v| v * v).sum();
        if v_s.abs() <= 1e-8 * (s_norm2 * v_norm2).sqrt() || v_norm2 == 0.0 {
            self.skipped += 1;
            return;
        }
        for a in 0..m {
            let va = y[a] / v_s;
            for (b, vb) in y.iter().enumerate() {
                element.s[a * m + b] += va * vb;
            }
        }
        element.nonzero = true;
        self.updates += 1;
    }

    /// `target += Σₑ Pₑᵀ Sₑ Pₑ` (lower triangle). The element columns lie within one Jacobian row's span, so
    /// inside any band sized for `JᵀJ`.
    pub(crate) fn add_to(&self, target: &mut SymmetricMatrix) {
        for e in self.elements.iter().filter(|e| e.nonzero) {
            let m = e.cols.len();
            for a in 0..m {
                for b in 0..=a {
                    target.add_unchecked(e.cols[a], e.cols[b], e.s[a * m + b]);
                }
            }
        }
    }
}

/// `out = Pₑ Σ_{j∈e} wⱼ (∇cⱼ now − ∇cⱼ before)`: the change of element `e`'s weighted gradient between the
/// Jacobian values `previous` and those in `eval`.
fn weighted_difference(element: &Element, eval: &Evaluation, previous: &[Vec<f64>; 3], weights: [&[f64]; 3], out: &mut [f64]) {
    out.fill(0.0);
    let mut at = 0;
    for &(family, i) in &element.rows {
        let mat = eval.jacobian(family);
        let range = mat.row_range(i);
        let len = range.len();
        let w = weights[family as usize][i];
        if w != 0.0 {
            let (now, before) = (&mat.values()[range.clone()], &previous[family as usize][range]);
            for p in 0..len {
                out[element.local[at + p]] += w * (now[p] - before[p]);
            }
        }
        at += len;
    }
}

/// `out = S v` for a row-major symmetric `S`.
fn symmetric_mul(s: &[f64], v: &[f64], out: &mut [f64]) {
    let m = v.len();
    for (a, o) in out.iter_mut().enumerate() {
        *o = s[a * m..(a + 1) * m].iter().zip(v).map(|(x, y)| x * y).sum();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::problem::{Dims, Patterns};

    /// Rows `cᵢ(x) = ½ xₑᵀ Aᵢ xₑ` over overlapping column triples: with unit weights, SR1 recovers each
    /// element's `Aᵢ` from 3 independent steps, and the assembled term is `Σ PᵢᵀAᵢPᵢ`.
    #[test]
    fn recovers_quadratic_elements() {
        let n = 6;
        let elements: Vec<Vec<usize>> = (0..n - 2).map(|i| vec![i, i + 1, i + 2]).collect();
        let a: Vec<[f64; 9]> = (0..elements.len())
            .map(|i| {
                let d = 1.0 + i as f64;
                [d, 0.3, -0.2, 0.3, -2.0 * d, 0.5, -0.2, 0.5, 0.7]
            })
            .collect();
        let dims = Dims { n, n_res: elements.len(), n_eq: 0, n_ineq: 0 };
        let patterns = Patterns { r: elements.clone(), h: vec![], g: vec![] };
        let mut eval = Evaluation::new(dims, &patterns).unwrap();
        let jac = |x: &[f64], eval: &mut Evaluation| {
            for (i, cols) in elements.iter().enumerate() {
                let row = eval.jr.row_values_mut(i);
                for p in 0..3 {
                    row[p] = (0..3).map(|q| a[i][p * 3 + q] * x[cols[q]]).sum();
                }
            }
        };
        let mut x = vec![0.1, -0.4, 0.3, 0.9, -0.2, 0.5];
        jac(&x, &mut eval);
        let mut term = SecondOrderTerm::new(&eval);
        assert_eq!(term.len(), elements.len());
        let ones = vec![1.0; elements.len()];
        for k in 0..12 {
            term.remember(&x, &eval, [&ones, &[], &[]]);
            for (j, v) in x.iter_mut().enumerate() {
                *v += 0.1 * (((k * 7 + j * 3) * (k + 2 * j + 1)) as f64).sin();
            }
            jac(&x, &mut eval);
            term.update(&x, &eval, [&ones, &[], &[]]);
        }
        let mut assembled = SymmetricMatrix::dense(n);
        term.add_to(&mut assembled);
        let mut exact = nalgebra::DMatrix::<f64>::zeros(n, n);
        for (i, cols) in elements.iter().enumerate() {
            for p in 0..3 {
                for q in 0..3 {
                    exact[(cols[p], cols[q])] += a[i][p * 3 + q];
                }
            }
        }
        let got = assembled.to_dense();
        assert!((got - &exact).amax() < 1e-8 * exact.amax(), "{}", assembled.to_dense());
    }
}
