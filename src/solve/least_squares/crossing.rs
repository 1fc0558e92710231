//! The inequalities a step crosses. The model `JᵀJ (+ second-order term) + νD` of a Levenberg–Marquardt
//! step treats the inequality rows active at `x` (`sᵢ = ĝᵢ + λᵢ/2w_p > 0`) as quadratics and the others
//! as absent; a step that carries a row to the other side of its kink (`sᵢ + Ĵᵢδ` changes sign) meets a
//! penalty the model did not see, or leaves one it counted, and is rejected or accepted with a poor gain.
//! So, as a semismooth Newton step on the model's piecewise-quadratic `Σ w_p max(sᵢ + Ĵᵢδ, 0)²`: the
//! switched rows join (σ = +1) or leave (σ = −1) the model and the step is solved again, at most
//! [`CROSSING_ROUNDS`] times, each with one more banded factorisation:
//!
//! ```text
//!   (H + Σ_S σᵢ 2w_p ĴᵢᵀĴᵢ + νD) δ = −(g + b),   b = Σ_S σᵢ 2w_p sᵢ Ĵᵢᵀ      S: the switched rows
//! ```
//!
//! The predicted decrease is then that of the piecewise model, `m(0) − m(δ)`
//! ([`LevenbergMarquardt::piecewise_decrease`]; with no row switched, the plain `½δᵀ(νDδ − g)`), so the
//! gain ratio judges the step against the model it was solved for.

use super::LevenbergMarquardt;
use crate::solve::auglag::AugmentedLagrangian;
use crate::solve::linalg::SymmetricMatrix;
use crate::solve::line_search::dot;

/// Re-solves of one step after rows it crossed joined the model.
const CROSSING_ROUNDS: usize = 3;

/// Work for [`LevenbergMarquardt::cross`], allocated once per solve.
pub(super) struct Crossing {
    /// The model with the crossed rows.
    gram: SymmetricMatrix,
    /// `J_g δ`, unscaled.
    jg_step: Vec<f64>,
    /// Per inequality row: `2w_p / scale²` if crossed, else 0 (the Gram weights), and `2w_p sᵢ / scale`
    /// (the right-hand side's).
    coef: Vec<f64>,
    rhs_coef: Vec<f64>,
    /// The switches and step before the current round (restored if its factorisation fails).
    coef_before: Vec<f64>,
    rhs_coef_before: Vec<f64>,
    step_before: Vec<f64>,
}

impl Crossing {
    pub(super) fn new(gram: &SymmetricMatrix, n_ineq: usize) -> Self {
        let zeros = vec![0.0; n_ineq];
        Crossing {
            gram: gram.clone(),
            jg_step: zeros.clone(),
            coef: zeros.clone(),
            rhs_coef: zeros.clone(),
            coef_before: zeros.clone(),
            rhs_coef_before: zeros,
            step_before: vec![0.0; gram.n()],
        }
    }
}

impl LevenbergMarquardt {
    /// With `step` solved from the model at `x` (`al` evaluated there, `factor` holding the model with
    /// `shift`): corrects the model for the inequality rows whose side of the kink the step changes and
    /// solves again, as the module docs say. Returns the piecewise model's predicted decrease, or `None`
    /// if the step changes no row's side (`step` untouched).
    pub(super) fn cross(&mut self, al: &AugmentedLagrangian<'_>) -> Option<f64> {
        let c = &mut self.crossing;
        c.coef.iter_mut().chain(c.rhs_coef.iter_mut()).for_each(|v| *v = 0.0);
        let mut changed = false;
        for _ in 0..CROSSING_ROUNDS {
            al.eval.jg.mul_vec(&self.step, &mut c.jg_step);
            if !c.switch(al) {
                break;
            }
            changed = true;
            // The model with the switched rows (σ = +1 joining, −1 leaving): H + Σ σ 2w_p ĴᵢᵀĴᵢ + νD.
            c.gram.fill_zero();
            c.gram.add_matrix(&self.gram);
            c.step_before.copy_from_slice(&self.step);
            let solved = al.eval.jg.add_gram_to(Some(&c.coef), &mut c.gram).is_ok()
                && self.factor.factor(&c.gram, Some(&self.shift)).is_ok();
            if !solved {
                // Keep the last step that was solved, with the switches it was solved for.
                self.step.copy_from_slice(&c.step_before);
                c.coef.copy_from_slice(&c.coef_before);
                c.rhs_coef.copy_from_slice(&c.rhs_coef_before);
                break;
            }
            // δ = −(model)⁻¹ (g + b),  b = J_gᵀ rhs_coef
            self.step.iter_mut().zip(&self.gradient).for_each(|(d, g)| *d = *g);
            al.eval.jg.tr_mul_vec_add(1.0, &c.rhs_coef, &mut self.step);
            self.step.iter_mut().for_each(|d| *d = -*d);
            self.factor.solve_in_place(&mut self.step);
        }
        changed.then(|| self.piecewise_decrease(al))
    }

    /// `m(0) − m(δ)` of the piecewise model, for `step` solved with the switches in `crossing`:
    /// `δᵀHδ = −δᵀ(g + b) − δᵀνDδ − Σ σ 2w_p (Ĵᵢδ)²` from the solve, and for every row the difference
    /// between `w_p max(sᵢ + Ĵᵢδ, 0)²` and the quadratic `H` holds for it.
    fn piecewise_decrease(&mut self, al: &AugmentedLagrangian<'_>) -> f64 {
        let c = &mut self.crossing;
        al.eval.jg.mul_vec(&self.step, &mut c.jg_step);
        let g_d = dot(&self.gradient, &self.step);
        let b_d = dot(&c.rhs_coef, &c.jg_step);
        let d_nu_d: f64 = self.shift.iter().zip(&self.step).map(|(s, d)| s * d * d).sum();
        let switched: f64 = c.coef.iter().zip(&c.jg_step).map(|(k, jd)| 0.5 * k * jd * jd).sum();
        let d_h_d = -(g_d + b_d) - d_nu_d - switched;
        let kinks: f64 = (0..c.jg_step.len())
            .map(|i| {
                let (s, scale) = al.shifted_inequality(i);
                let lin = s + c.jg_step[i] / scale;
                al.penalty * (lin.max(0.0).powi(2) - if s > 0.0 { lin * lin } else { 0.0 })
            })
            .sum();
        -(g_d + 0.5 * d_h_d + kinks)
    }
}

impl Crossing {
    /// Sets the switches for the step whose `J_g δ` is in `jg_step`: a row switches where `δ` takes
    /// `sᵢ + Ĵᵢδ` to the other side of 0 from `sᵢ`. Returns whether they changed (the previous ones kept
    /// in `*_before`).
    fn switch(&mut self, al: &AugmentedLagrangian<'_>) -> bool {
        self.coef_before.copy_from_slice(&self.coef);
        self.rhs_coef_before.copy_from_slice(&self.rhs_coef);
        let two_wp = 2.0 * al.penalty;
        let mut changed = false;
        for (i, jd) in self.jg_step.iter().enumerate() {
            let (s, scale) = al.shifted_inequality(i);
            let sigma = match (s > 0.0, s + jd / scale > 0.0) {
                (false, true) => 1.0,
                (true, false) => -1.0,
                _ => 0.0,
            };
            let k = sigma * two_wp / (scale * scale);
            changed |= k != self.coef[i];
            (self.coef[i], self.rhs_coef[i]) = (k, sigma * two_wp * s / scale);
        }
        changed
    }
}
