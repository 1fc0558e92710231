//! One Levenberg–Marquardt step of the structured solver: factorise `JᵀJ (+ second-order term) + νD`, solve,
//! judge the step by its gain ratio, and on a rejection first shorten it along its direction before raising
//! `ν` (Nielsen's update, Madsen, Nielsen & Tingleff 2004, §3.2).

use super::{LevenbergMarquardt, SecondOrder, Step, MAX_DAMPING, MIN_DAMPING, NOISE};
use crate::solve::auglag::AugmentedLagrangian;
use crate::solve::line_search::{dot, EvalError};

impl LevenbergMarquardt {
    /// Factorises `JᵀJ + νD`, raising `ν` until that succeeds.
    fn factorise(&mut self) -> Result<(), ()> {
        loop {
            if self.damping > MAX_DAMPING {
                return Err(());
            }
            for (s, d) in self.shift.iter_mut().zip(&self.scaling) {
                // A variable no residual touches has d = 0; any positive value keeps the system definite.
                *s = self.damping * if *d > 0.0 { *d } else { 1.0 };
            }
            if self.factor.factor(&self.gram, Some(&self.shift)).is_ok() {
                return Ok(());
            }
            self.reject();
        }
    }

    fn reject(&mut self) {
        self.damping *= self.growth;
        self.growth *= 2.0;
    }

    /// After the step `δ` from `x` (where `L_A = value`) was rejected with `L_A(x + δ) = trial`: the same
    /// direction shortened to `x + αδ`, `α` the minimiser of the quadratic through `φ(0) = value`,
    /// `φ'(0) = gᵀδ` and `φ(1) = trial` (within [0.1, 0.5]; 0.25 if `trial` is not finite). Raising `ν`
    /// instead changes a near-Newton step little until `ν` reaches the curvature's scale, and the
    /// compounding growth then overshoots it by orders of magnitude, after which every step recovers by
    /// only a third. Returns the value there and the gain against the model's decrease along the line,
    /// `−α gᵀδ − ½α² δᵀHδ` with `δᵀHδ = −gᵀδ − δᵀ(νD)δ`; leaves `x_trial` and `gradient_trial` at that point.
    /// `None` if it does not decrease `L_A` either.
    fn shortened(
        &mut self,
        al: &mut AugmentedLagrangian<'_>,
        x: &[f64],
        value: f64,
        trial: f64,
    ) -> Result<Option<(f64, f64)>, String> {
        let slope = dot(&self.gradient, &self.step);
        let damped: f64 = self.shift.iter().zip(&self.step).map(|(s, d)| s * d * d).sum();
        let curvature = -slope - damped;
        let alpha = if trial.is_finite() && trial - value - slope > 0.0 {
            (-slope / (2.0 * (trial - value - slope))).clamp(0.1, 0.5)
        } else {
            0.25
        };
        for ((xt, xi), d) in self.x_trial.iter_mut().zip(x).zip(&self.step) {
            *xt = xi + alpha * d;
        }
        let short = match al.evaluate(&self.x_trial, true) {
            Ok(()) => al.value(),
            Err(EvalError::Failed(m)) => return Err(m),
            Err(EvalError::NonFinite(_)) => return Ok(None),
        };
        let predicted = -alpha * slope - 0.5 * alpha * alpha * curvature;
        if !(short < value && predicted > 0.0) {
            return Ok(None);
        }
        al.gradient(&mut self.gradient_trial);
        for d in self.step.iter_mut() {
            *d *= alpha;
        }
        self.damping *= 2.0;
        Ok(Some((short, (value - short) / predicted)))
    }

    /// One accepted LM step from `x` (where `L_A = value`), trying larger `ν` until the gain ratio is positive.
    pub(super) fn step(&mut self, al: &mut AugmentedLagrangian<'_>, x: &mut [f64], value: f64) -> Step {
        loop {
            if self.factorise().is_err() {
                return Step::Stalled;
            }
            for (s, g) in self.step.iter_mut().zip(&self.gradient) {
                *s = -g;
            }
            self.factor.solve_in_place(&mut self.step);
            if !self.step.iter().all(|s| s.is_finite()) {
                self.reject();
                continue;
            }
            // Model decrease L(0) − L(δ) = −gᵀδ − ½δᵀ(JᵀJ)δ = ½ δᵀ(νDδ − g), as (JᵀJ + νD)δ = −g.
            let predicted: f64 =
                0.5 * self.step.iter().zip(&self.shift).zip(&self.gradient).map(|((d, s), g)| d * (s * d - g)).sum::<f64>();
            let mut moved = false;
            for ((xt, xi), d) in self.x_trial.iter_mut().zip(x.iter()).zip(&self.step) {
                *xt = xi + d;
                moved |= *xt != *xi;
            }
            if !moved || predicted.is_nan() || predicted <= 0.0 {
                return Step::Stalled;
            }
            let mut trial = match al.evaluate(&self.x_trial, true) {
                Ok(()) => al.value(),
                Err(EvalError::Failed(m)) => return Step::Error(m),
                Err(EvalError::NonFinite(_)) => f64::INFINITY,
            };
            let mut actual = value - trial;
            if trial.is_finite() {
                al.gradient(&mut self.gradient_trial);
                if actual.abs() <= NOISE * value.abs() {
                    // ΔL_A is lost in rounding near a minimiser: measure it by the trapezoidal rule on the
                    // gradients instead, −½ δᵀ(g + g₊) (the trust-region analogue of the approximate Wolfe
                    // condition of the line search).
                    actual = -0.5
                        * self
                            .step
                            .iter()
                            .zip(&self.gradient)
                            .zip(&self.gradient_trial)
                            .map(|((d, g), gt)| d * (g + gt))
                            .sum::<f64>();
                }
            }
            let (mut gain, mut shortened) = (actual / predicted, false);
            if !(gain > 0.0 && trial.is_finite()) {
                match self.shortened(al, x, value, trial) {
                    Ok(Some((t, g))) => (trial, gain, shortened) = (t, g, true),
                    Ok(None) => {}
                    Err(m) => return Step::Error(m),
                }
            }
            if gain > 0.0 && trial.is_finite() {
                if let SecondOrder::Secant(term) = &mut self.second_order {
                    term.update(&self.x_trial, &al.eval, al.gradient_weights());
                }
                std::mem::swap(&mut self.gradient, &mut self.gradient_trial);
                x.copy_from_slice(&self.x_trial);
                if !shortened {
                    self.damping = (self.damping * (1.0 / 3.0f64).max(1.0 - (2.0 * gain - 1.0).powi(3))).max(MIN_DAMPING);
                }
                self.growth = 2.0;
                return Step::Accepted { value: trial };
            }
            self.reject();
        }
    }
}
