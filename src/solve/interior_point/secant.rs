//! The constraints' second-order term for problems that do not provide it ([`Problem::add_second_order`]
//! returns `false`: a generic problem, or the transcription's `L⁻¹τ` objective): the partitioned secant
//! approximation of [`crate::solve::partitioned`] of `Σ y_k∇²ĥ_k + Σ vᵢ∇²ĝᵢ`, one pair per accepted step.
//! Without it the barrier steps see no curvature of the constraints: on HS71 the iterates slid along the
//! sphere `Σx² = 40` and stopped 0.18 short of it. The objective's residuals keep Gauss–Newton's model (their
//! weight 0 in the pairs): with them in the secant the push-up under the `L⁻¹τ` objective went from 136
//! iterations to no convergence in 1794, the arm lift 38 → 63 (docs/performance.md).
//!
//! [`Problem::add_second_order`]: crate::solve::Problem::add_second_order

use super::Ipm;
use crate::solve::linalg::SymmetricMatrix;
use crate::solve::partitioned::SecondOrderTerm;
use crate::solve::problem::Evaluation;

/// The secant approximation and the residuals' weights in its pairs (zero).
pub(crate) struct Secant {
    term: SecondOrderTerm,
    no_residuals: Vec<f64>,
}

impl Secant {
    fn new(eval: &Evaluation) -> Self {
        Secant { term: SecondOrderTerm::new(eval), no_residuals: vec![0.0; eval.r.len()] }
    }

    /// `target += Σₑ Pₑᵀ Sₑ Pₑ`.
    pub(super) fn add_to(&self, target: &mut SymmetricMatrix) {
        self.term.add_to(target);
    }
}

impl Ipm<'_> {
    /// Starts the secant approximation at `x` (the problem has just said it provides no term).
    pub(super) fn start_secant(&mut self) {
        self.lagrangian_weights();
        let mut secant = Secant::new(&self.eval);
        secant.term.remember(&self.x, &self.eval, [&secant.no_residuals, &self.work_h, &self.work_g]);
        self.secant = Some(Box::new(secant));
    }

    /// After an accepted step (`x`, `eval`, `y`, `v` at the new point): the secant pair of the step, and the
    /// new point remembered as the next pair's start.
    pub(super) fn update_secant(&mut self) {
        if self.secant.is_none() {
            return;
        }
        self.lagrangian_weights();
        let Secant { term, no_residuals } = &mut **self.secant.as_mut().expect("checked above");
        let weights = [&no_residuals[..], &self.work_h[..], &self.work_g[..]];
        term.update(&self.x, &self.eval, weights);
        term.remember(&self.x, &self.eval, weights);
    }
}
