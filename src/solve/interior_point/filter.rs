//! The filter line search of Wächter & Biegler (2006, IPOPT, sec. 2.3–2.4): a trial point is accepted when
//! it sufficiently lowers the constraint violation `θ = ‖ĥ‖₁ + ‖ĝ + s‖₁` or the barrier objective
//! `φ = F − μ Σ ln sᵢ` against the current point and every pair in the filter; where the step is a descent
//! direction of `φ` and the point nearly feasible, Armijo's condition on `φ` is asked instead (the switching
//! condition). A first trial that raises `θ` gets one second-order correction: the same factor, with the
//! residuals `α c(x) + c(x + αd)`, so that curved constraints do not cut every step short (Maratos). Where the
//! point is nearly feasible but the direction climbs `φ` (the equalities' regularised step at large
//! multipliers) and the filter has cut the step to a tenth, Armijo's condition on the augmented Lagrangian
//! decides instead ([`Ipm::merit_search`]).

use super::step::TO_BOUNDARY;
use super::{relaxed, Ipm};
use crate::solve::line_search::{dot, EvalError};
use crate::solve::solver::StopReason;

/// IPOPT's constants: the filter margins `γ_θ`, `γ_φ`; Armijo's `η_φ`; the switching condition's `δ`, `s_θ`,
/// `s_φ`; `γ_α` of the smallest step.
const GAMMA_THETA: f64 = 1e-5;
const GAMMA_PHI: f64 = 1e-8;
const ETA_PHI: f64 = 1e-4;
const SWITCH_DELTA: f64 = 1.0;
const S_THETA: f64 = 1.1;
const S_PHI: f64 = 2.3;
const GAMMA_ALPHA: f64 = 0.05;
/// Relative change of `φ` below which it is rounding.
const NOISE: f64 = 1e-13;
/// The fraction of the largest step below which a direction that climbs `φ` near feasibility is searched on
/// the augmented Lagrangian instead ([`Ipm::merit_search`]); its trials at most. At 0.03 the push-up at
/// N = 31 kept its crawl (111 steps, 55 at 0.1); searching `M` before the filter (no cut) made N = 24–29 and
/// 12–13 take up to twice the steps.
const CLIMB_CUT: f64 = 0.1;
const MERIT_TRIALS: usize = 10;

/// The filter: pairs `(θ, φ)` a trial must improve on in one of the two, with the margins already applied.
#[derive(Clone, Debug, Default)]
pub(crate) struct Filter {
    entries: Vec<(f64, f64)>,
    /// `θ_max` (no trial above it) and `θ_min` (below it the switching condition may apply), set from the
    /// first `θ` after each reset.
    bounds: Option<(f64, f64)>,
}

impl Filter {
    /// Empties the filter (when `μ` changes).
    pub(super) fn reset(&mut self) {
        self.entries.clear();
        self.bounds = None;
    }

    fn acceptable(&self, theta: f64, phi: f64) -> bool {
        self.entries.iter().all(|&(t, p)| theta < t || phi < p)
    }

    /// Adds `((1 − γ_θ)θ, φ − γ_φ θ)`, dropping the entries it dominates.
    fn add(&mut self, theta: f64, phi: f64) {
        let entry = ((1.0 - GAMMA_THETA) * theta, phi - GAMMA_PHI * theta);
        self.entries.retain(|&(t, p)| t < entry.0 || p < entry.1);
        self.entries.push(entry);
    }
}

/// How a trial compares.
#[derive(Clone, Copy, PartialEq)]
enum Verdict {
    Rejected,
    /// Accepted by Armijo's condition on `φ` (the filter is left as it is).
    ObjectiveStep,
    /// Accepted by the decrease of `θ` or `φ` against the current point (the filter gains it).
    FeasibilityStep,
}

impl Ipm<'_> {
    /// `θ` and `φ` at `x` (from `eval`, `s`) or at the trial point (`trial`, `s_trial`).
    fn theta_phi(&self, at_trial: bool) -> (f64, f64) {
        let (e, slack) = if at_trial { (&self.trial, &self.s_trial) } else { (&self.eval, &self.s) };
        let eq: f64 = e.h.iter().zip(&self.scales.eq).map(|(h, s)| (h / s).abs()).sum();
        let ineq: f64 = (0..self.dims.n_ineq).map(|i| (relaxed(e.g[i], self.scales.ineq[i], self.relax) + slack[i]).abs()).sum();
        let barrier: f64 = slack.iter().map(|s| s.ln()).sum();
        (eq + ineq, e.objective() - self.mu * barrier)
    }

    /// `∇φ · (dx, ds) = (Jᵣᵀr)·dx − μ Σ dsᵢ/sᵢ`.
    fn phi_slope(&self) -> f64 {
        dot(&self.grad_f, &self.dx) - self.s.iter().zip(&self.ds).map(|(s, d)| self.mu * d / s).sum::<f64>()
    }

    /// Evaluates `x + α dx`, `s + α ds` into the trial buffers; `(θ, φ)` there (`φ = ∞` if not finite).
    fn try_step(&mut self, alpha: f64) -> Result<(f64, f64), StopReason> {
        for ((t, x), d) in self.x_trial.iter_mut().zip(&self.x).zip(&self.dx) {
            *t = x + alpha * d;
        }
        for ((t, s), d) in self.s_trial.iter_mut().zip(&self.s).zip(&self.ds) {
            *t = s + alpha * d;
        }
        let x_trial = std::mem::take(&mut self.x_trial);
        let evaluated = self.evaluate_at(&x_trial, false);
        self.x_trial = x_trial;
        match evaluated {
            Ok(()) => Ok(self.theta_phi(true)),
            Err(EvalError::Failed(m)) => Err(StopReason::EvaluationError(m)),
            Err(EvalError::NonFinite(_)) => Ok((f64::INFINITY, f64::INFINITY)),
        }
    }

    /// The filter's and the sufficient-decrease tests of a trial `(θ, φ)` at step `alpha`, from `(θ₀, φ₀)`
    /// with slope `slope` of `φ`.
    fn judge(&self, current: (f64, f64), slope: f64, alpha: f64, trial: (f64, f64)) -> Verdict {
        let ((theta0, phi0), (theta, phi)) = (current, trial);
        let (theta_max, theta_min) = self.filter.bounds.unwrap_or((f64::INFINITY, 0.0));
        if !(phi.is_finite() && theta.is_finite()) || theta > theta_max || !self.filter.acceptable(theta, phi) {
            return Verdict::Rejected;
        }
        let switching = slope < 0.0 && alpha * (-slope).powf(S_PHI) > SWITCH_DELTA * theta0.powf(S_THETA);
        if switching && theta0 <= theta_min {
            let armijo = phi <= phi0 + ETA_PHI * alpha * slope + NOISE * phi0.abs();
            return if armijo { Verdict::ObjectiveStep } else { Verdict::Rejected };
        }
        if theta <= (1.0 - GAMMA_THETA) * theta0 || phi <= phi0 - GAMMA_PHI * theta0 + NOISE * phi0.abs() {
            Verdict::FeasibilityStep
        } else {
            Verdict::Rejected
        }
    }

    /// The filter line search along the direction just computed: the accepted step length (the trial
    /// buffers and the direction hold the accepted point, a second-order correction's if it was one), or
    /// `None` below the smallest step.
    pub(super) fn filter_line_search(&mut self) -> Result<Option<f64>, StopReason> {
        let current = self.theta_phi(false);
        let theta0 = current.0;
        self.filter.bounds.get_or_insert((1e4 * theta0.max(1.0), 1e-4 * theta0.max(1.0)));
        let slope = self.phi_slope();
        let alpha_min = GAMMA_ALPHA
            * if slope < 0.0 {
                GAMMA_THETA.min(GAMMA_PHI * theta0 / -slope).min(SWITCH_DELTA * theta0.powf(S_THETA) / (-slope).powf(S_PHI))
            } else {
                GAMMA_THETA
            };
        let alpha_max = Self::to_boundary(&self.s, &self.ds, TO_BOUNDARY);
        let theta_min = self.filter.bounds.map_or(0.0, |b| b.1);
        // Nearly feasible, yet the direction climbs φ: the equalities' regularised step (module docs of
        // [`super`]) is descending the augmented Lagrangian instead (see [`Self::merit_search`]).
        let mut climbs = slope >= 0.0 && theta0 <= theta_min && self.dims.n_eq > 0;
        let mut alpha = alpha_max;
        let mut first = true;
        while alpha >= alpha_min * alpha_max.min(1.0) {
            if climbs && alpha < CLIMB_CUT * alpha_max {
                climbs = false;
                if let Some(alpha) = self.merit_search(current, slope, alpha_max, theta_min)? {
                    return Ok(Some(alpha));
                }
            }
            let trial = self.try_step(alpha)?;
            let mut verdict = self.judge(current, slope, alpha, trial);
            if verdict == Verdict::Rejected && first && trial.0 >= theta0 {
                verdict = self.second_order_correction(current, slope, alpha)?;
            }
            if verdict != Verdict::Rejected {
                if verdict == Verdict::FeasibilityStep {
                    self.filter.add(current.0, current.1);
                }
                return Ok(Some(alpha));
            }
            first = false;
            alpha *= 0.5;
        }
        Ok(None)
    }

    /// `M = φ + yᵀĥ + (ρ/2)|ĥ|²` (the barrier objective plus the equalities' augmented Lagrangian terms) at `x`
    /// or at the trial point, given its `φ`.
    fn merit(&self, at_trial: bool, phi: f64) -> f64 {
        let e = if at_trial { &self.trial } else { &self.eval };
        let terms = e.h.iter().zip(&self.scales.eq).zip(&self.y).map(|((h, s), y)| {
            let c = h / s;
            y * c + 0.5 * self.rho * c * c
        });
        phi + terms.sum::<f64>()
    }

    /// `∇M · (dx, ds) = ∇φ · (dx, ds) + (y + ρĥ)ᵀ Jĥ dx` (`slope` the first term).
    fn merit_slope(&mut self, slope: f64) -> f64 {
        self.eval.jh.mul_vec(&self.dx, &mut self.refine_rows);
        let rows = (0..self.dims.n_eq).map(|k| {
            let s_h = self.scales.eq[k];
            (self.y[k] + self.rho * self.eval.h[k] / s_h) * self.refine_rows[k] / s_h
        });
        slope + rows.sum::<f64>()
    }

    /// The end game of closed loops: near feasibility, with large equality multipliers (the push-up's hands,
    /// 5·10⁶), the regularised step `dy = ρ(Jĥ dx + ĥ)` makes `dx` a descent direction of the augmented
    /// Lagrangian `M`, not of `φ` (slope of `φ` > 0): every full step raised `θ` (1e-8 → 7e-8) and `φ`, the
    /// filter cut it to 1/64, and the multipliers crawled for 130 steps (docs/performance.md). Here, once the
    /// filter's search has cut the step below [`CLIMB_CUT`], Armijo's condition on `M` from the largest
    /// step, the trial kept below `θ_min`; an accepted step resets the filter (its entries were made for `φ`).
    fn merit_search(
        &mut self,
        current: (f64, f64),
        slope: f64,
        alpha_max: f64,
        theta_min: f64,
    ) -> Result<Option<f64>, StopReason> {
        let m_slope = self.merit_slope(slope);
        if m_slope >= 0.0 {
            return Ok(None);
        }
        let m0 = self.merit(false, current.1);
        let mut alpha = alpha_max;
        for _ in 0..MERIT_TRIALS {
            let trial = self.try_step(alpha)?;
            if trial.0 <= theta_min && self.merit(true, trial.1) <= m0 + ETA_PHI * alpha * m_slope {
                self.filter.reset();
                return Ok(Some(alpha));
            }
            alpha *= 0.5;
        }
        Ok(None)
    }

    /// One second-order correction of a first trial at `alpha` that raised `θ`: the direction for the
    /// residuals `α c(x) + c(x + αd)` from the same factor, taken whole (to its own boundary). Keeps the
    /// original direction if the corrected point is rejected too.
    fn second_order_correction(&mut self, current: (f64, f64), slope: f64, alpha: f64) -> Result<Verdict, StopReason> {
        for ((c, h), s) in self.c_h.iter_mut().zip(&self.trial.h).zip(&self.scales.eq) {
            *c = alpha * *c + h / s;
        }
        for i in 0..self.dims.n_ineq {
            self.c_g[i] = alpha * self.c_g[i] + relaxed(self.trial.g[i], self.scales.ineq[i], self.relax) + self.s_trial[i];
        }
        let [dx, ds, dy, dv] = &mut self.saved;
        dx.copy_from_slice(&self.dx);
        ds.copy_from_slice(&self.ds);
        dy.copy_from_slice(&self.dy);
        dv.copy_from_slice(&self.dv);
        self.direction();
        let alpha_soc = Self::to_boundary(&self.s, &self.ds, TO_BOUNDARY);
        let trial = self.try_step(alpha_soc)?;
        let verdict = self.judge(current, slope, alpha, trial);
        if verdict == Verdict::Rejected {
            let [dx, ds, dy, dv] = &self.saved;
            self.dx.copy_from_slice(dx);
            self.ds.copy_from_slice(ds);
            self.dy.copy_from_slice(dy);
            self.dv.copy_from_slice(dv);
            self.constraint_residuals();
        }
        Ok(verdict)
    }
}
