//! One interior-point iteration: the reduced Newton matrix and right-hand side, the inertia correction, the
//! direction `(dx, ds, dy, dv)` and the accepted step (module docs of [`super`]; the line search is in
//! [`super::filter`]).

use super::{relaxed, Ipm};
use crate::solve::solver::StopReason;

/// IPOPT's `τ_min`: the fraction of the distance to the bound a step may cover.
pub(super) const TO_BOUNDARY: f64 = 0.99;
/// Inertia correction `δ` (relative to the diagonal): the first nonzero one, its growth, its decay per
/// accepted step, and the largest. A step taken at `DELTA_FIRST` (or at none) is followed by one that first
/// tries none, as IPOPT tries `δ = 0` first at every step: with the scale's floor ([`SCALING_FLOOR`]) a
/// `δ` held at 10⁻⁸ put a damping of 10⁻⁹ of the mean `D` on every coordinate, and near the optimum of a fine
/// discretisation whole steps crawled (the arm lift's `--refine` at N = 107: 695 iterations, 61 with this;
/// the 35 tasks unchanged, 2012 → 2010 kept iterations; docs/performance.md).
const DELTA_FIRST: f64 = 1e-8;
const DELTA_GROWTH: f64 = 10.0;
const DELTA_DECAY: f64 = 1.0 / 3.0;
const DELTA_MAX: f64 = 1e20;
/// The inertia correction's scale is Moré's `D` floored at this fraction of its mean, `δ·max(D_j, κ·D̄)`. `D`
/// spans five orders of magnitude (the crouch: 0.8 … 1.8·10⁵, median 1.4·10³): a direction of negative
/// curvature along coordinates the residuals barely see (small `D_j`) needed a `δ` that froze every other
/// coordinate, and whole steps crawled. With κ = 0.1, the 35 tasks' starts 5929 → 4785 iterations, the kept
/// plans 2207 → 2082 (`weight_lift_space` 136 → 104), no effort higher and the crouch's 0.7 % lower;
/// κ = 0.03 and 0.3 did less, a uniform `δ·D̄` or `δ·max D` moved efforts up (docs/performance.md).
const SCALING_FLOOR: f64 = 0.1;
/// A step the line search cut below this fraction, on the exact model: the next step starts from the same
/// `δ` instead of a third of it (the model over-predicted; a full-curvature step would be cut again). Default
/// plans of the 35 tasks 3237 → 2961 iterations (the 36-DOF crouch 559 → 212), the push-up at N = 32 162 → 80;
/// keeping `δ` ×10 instead stalled the push-up at N = 31, 32 (docs/performance.md).
const DELTA_KEPT_BELOW: f64 = 0.5;
/// `δ_c = 1/ρ` of the equalities, relative to the largest diagonal entry of `JᵣᵀJᵣ` at the start. The
/// multipliers' step `dy = ρ(Jĥ dx + ĥ)` carries `ρ` times the residual's rounding: at 10⁻⁸ that noise
/// (|dy| ≈ 10⁵ at the push-up's optimum) kept the stationarity test from ever holding; at 10⁻⁴ the
/// push-up, twist lift and 18 more examples converge (docs/performance.md).
const EQUALITY_REGULARISATION: f64 = 1e-4;
/// Iterations on the Gauss–Newton model `JᵣᵀJᵣ` before the exact second-order term joins it: far from a
/// solution the exact Hessian's long steps along its weak directions are cut to nothing by the line search
/// (the arm lifts, chin-ups, stoops stalled); near it the curvature gives the fast finish.
pub(super) const GAUSS_NEWTON_FIRST: usize = 30;
/// Iterations between recomputations of the exact term (kept in between, with the multipliers it was made
/// with): every 3 halves the solve time at 13–37 DOF for about the same iterations (h36 wave-step 1.88 →
/// 0.88 s, the moon reach 9.2 → 5.0 s); every 5 lost iterations on h21 (docs/performance.md).
const EXACT_REFRESH: usize = 3;
/// Once the equalities nearly hold (`max |ĥ| ≤ REFINE_NEAR·tol_violation`), passes of iterative refinement
/// that take each direction from the system with `δ_c = 1/ρ` towards the one with `δ_c / REFINE_FACTOR`,
/// reusing the factor: at a fixed `δ_c` the multipliers `y` converge only linearly (a proximal step), and the
/// push-up's closed loop crawled at N = 31, 32 until the budget ran out. Four passes towards 10⁻⁴ `δ_c` from
/// 100 tolerances: the push-up converges at every N from 12 to 32 (5041 → 2039 iterations over the 21); from
/// the first iteration on instead, the push-up at N = 17 went 37 → 346 iterations; gated at 1 tolerance the
/// twist lift's contact rows toggled it on and off (132 → 228 iterations); 2, 3 or 6 passes, or 10⁻⁵, left
/// N = 31 or 32 unconverged (docs/performance.md).
const REFINEMENTS: usize = 4;
const REFINE_FACTOR: f64 = 1e4;
const REFINE_NEAR: f64 = 100.0;

impl Ipm<'_> {
    /// One accepted step (`Ok(true)`), or `Ok(false)` when no correction makes the line search succeed.
    pub(super) fn step(&mut self) -> Result<bool, StopReason> {
        self.assemble();
        // After a step at the smallest correction, none first (DELTA_FIRST's docs).
        let mut delta = if self.delta > DELTA_FIRST { (self.delta * DELTA_DECAY).max(DELTA_FIRST) } else { 0.0 };
        let mut restored = false;
        loop {
            if delta > DELTA_MAX {
                return Ok(false);
            }
            if !self.factorise(delta) {
                delta = if delta == 0.0 { DELTA_FIRST } else { delta * DELTA_GROWTH };
                continue;
            }
            self.constraint_residuals();
            self.direction();
            if let Some(alpha) = self.filter_line_search()? {
                let kept = alpha < DELTA_KEPT_BELOW && self.exact_in_use();
                // ×3 undoes the next step's decay by a third (DELTA_DECAY).
                self.delta = if kept { delta.max(DELTA_FIRST) * 3.0 } else { delta };
                self.accept(alpha)?;
                return Ok(true);
            }
            // No acceptable step along the Newton direction: restore feasibility if the constraints are not
            // met, else a shorter, more gradient-like step.
            if !restored && self.violation().0 > self.tol_violation {
                restored = true;
                if self.restore()? {
                    return Ok(true);
                }
            }
            delta = if delta == 0.0 { 1e-4 } else { (delta * DELTA_GROWTH).max(1e-4) };
        }
    }

    /// The matrix `JᵣᵀJᵣ + ρJĥᵀJĥ + JĝᵀΣJĝ` (+ the exact second-order term after [`GAUSS_NEWTON_FIRST`]
    /// iterations) at `x`, and Moré's scaling `D` from the diagonal of its first term `JᵣᵀJᵣ` only: a running
    /// maximum that took in the barrier's `vᵢ/sᵢ` (up to 10⁸ and more near an active limit) or `ρ` kept
    /// those past peaks for good, so that the smallest correction `δ = 10⁻⁸` became a damping larger than the
    /// curvature and full steps crawled (`chin_up_earth` 1089 → 137 iterations, `moon_overhead_reach`
    /// 761 → 62; docs/performance.md).
    fn assemble(&mut self) {
        let e = &self.eval;
        for i in 0..self.dims.n_ineq {
            let sg = self.scales.ineq[i];
            self.work_g[i] = self.v[i] / (self.s[i] * sg * sg);
        }
        // D_j = max over the iterations of (JᵣᵀJᵣ)_jj: the objective's own scale, not the barrier's Σ or ρ.
        e.jr.column_squares(&mut self.column_squares);
        for (d, c) in self.scaling.iter_mut().zip(&self.column_squares) {
            *d = d.max(*c);
        }
        if self.rho == 0.0 {
            self.rho = self.column_squares.iter().fold(1.0_f64, |a, &c| a.max(c)) / EQUALITY_REGULARISATION;
        }
        for (w, s) in self.work_h.iter_mut().zip(&self.scales.eq) {
            *w = self.rho / (s * s);
        }
        // A limit row proportional to a residual row, ∇gᵢ = c ∇rⱼ, adds Σᵢ c² ∇rⱼ∇rⱼᵀ: one outer product for
        // the residual and both its limits, w_r,j = 1 + Σ c² Σᵢ (the rows leave JĝᵀΣJĝ).
        self.work_r.fill(1.0);
        for p in &self.proportional {
            self.work_r[p.residual] += p.factor * p.factor * self.work_g[p.ineq];
            self.work_g[p.ineq] = 0.0;
        }
        self.matrix.fill_zero();
        let residual_weights = (!self.proportional.is_empty()).then_some(&self.work_r[..]);
        let assembled =
            e.jr.add_gram_to(residual_weights, &mut self.matrix)
                .and_then(|()| e.jg.add_gram_to(Some(&self.work_g), &mut self.matrix))
                .and_then(|()| e.jh.add_gram_to(Some(&self.work_h), &mut self.matrix));
        debug_assert!(assembled.is_ok(), "the band is sized from the patterns");
        // The second-order term with the Lagrangian's weights r, y/s_h, v/s_g: the problem's, recomputed every
        // EXACT_REFRESH, or the secant approximation where the problem provides none.
        if self.iterations < self.gauss_newton_first {
            return;
        }
        let due = (self.iterations - self.gauss_newton_first).is_multiple_of(EXACT_REFRESH) || self.exact.is_none();
        if self.exact != Some(false) && due {
            self.lagrangian_weights();
            let term = self.term.get_or_insert_with(|| self.matrix.clone());
            term.fill_zero();
            let weights = [&self.eval.r[..], &self.work_h[..], &self.work_g[..]];
            let provided = self.problem.add_second_order(&self.x, weights, term);
            self.exact = Some(provided);
            if !provided {
                // Never asked again: the band's memory goes back, the secant takes its place.
                self.term = None;
                self.start_secant();
            }
        }
        if self.exact_in_use() {
            self.matrix.add_matrix(self.term.as_ref().expect("exact_in_use: the term is kept"));
        } else if let Some(secant) = &self.secant {
            secant.add_to(&mut self.matrix);
        }
    }

    /// Whether this step's matrix holds the problem's exact second-order term ([`Self::assemble`] adds it by
    /// this test, and the damping's rule after a cut step reads it).
    fn exact_in_use(&self) -> bool {
        self.exact == Some(true) && self.term.is_some() && self.iterations >= self.gauss_newton_first
    }

    /// Factorises the matrix plus `δ·diag(max(D_j, κ·D̄))` ([`SCALING_FLOOR`]); `false` if it is not positive
    /// definite.
    fn factorise(&mut self, delta: f64) -> bool {
        let floor = SCALING_FLOOR * self.scaling.iter().sum::<f64>() / self.scaling.len().max(1) as f64;
        for (s, d) in self.shift.iter_mut().zip(&self.scaling) {
            let d = d.max(floor);
            *s = delta * if d > 0.0 { d } else { 1.0 };
        }
        let shift = (delta > 0.0).then_some(&self.shift[..]);
        self.factor.factor(&self.matrix, shift).is_ok()
    }

    /// The constraints' residuals the step is to remove: `c_h = ĥ`, `c_g = ĝ + s` at the current point.
    pub(super) fn constraint_residuals(&mut self) {
        let e = &self.eval;
        for ((c, h), s) in self.c_h.iter_mut().zip(&e.h).zip(&self.scales.eq) {
            *c = h / s;
        }
        for i in 0..self.dims.n_ineq {
            self.c_g[i] = relaxed(e.g[i], self.scales.ineq[i], self.relax) + self.s[i];
        }
    }

    /// `dx` from the factor, then `dy`, `dv`, `ds` (module docs), for the residuals `c_h`, `c_g` (the
    /// constraints at `x`, or a second-order correction's).
    pub(super) fn direction(&mut self) {
        let e = &self.eval;
        for i in 0..self.dims.n_ineq {
            let (s, v) = (self.s[i], self.v[i]);
            self.work_g[i] = (self.mu / s + v / s * self.c_g[i]) / self.scales.ineq[i];
        }
        for k in 0..self.dims.n_eq {
            self.work_h[k] = (self.y[k] + self.rho * self.c_h[k]) / self.scales.eq[k];
        }
        self.dx.copy_from_slice(&self.grad_f);
        e.jg.tr_mul_vec_add(1.0, &self.work_g, &mut self.dx);
        e.jh.tr_mul_vec_add(1.0, &self.work_h, &mut self.dx);
        self.dx.iter_mut().for_each(|d| *d = -*d);
        self.factor.solve_in_place(&mut self.dx);
        // dy = ρ(Jĥ dx + ĥ)
        e.jh.mul_vec(&self.dx, &mut self.dy);
        for k in 0..self.dims.n_eq {
            self.dy[k] = self.rho * (self.dy[k] / self.scales.eq[k] + self.c_h[k]);
        }
        if self.c_h.iter().all(|c| c.abs() <= REFINE_NEAR * self.tol_violation) {
            self.refine_equalities();
        }
        let e = &self.eval;
        // ds = −(ĝ + s) − Jĝ dx,  dv = μ/s − v − (v/s) ds
        e.jg.mul_vec(&self.dx, &mut self.ds);
        for i in 0..self.dims.n_ineq {
            let (s, v) = (self.s[i], self.v[i]);
            self.ds[i] = -self.ds[i] / self.scales.ineq[i] - self.c_g[i];
            self.dv[i] = self.mu / s - v - v / s * self.ds[i];
        }
    }

    /// [`REFINEMENTS`] passes of iterative refinement of `(dx, dy)` towards `δ_c' = δ_c / REFINE_FACTOR`
    /// (`ρ' = REFINE_FACTOR·ρ`). The first block row holds already; the second's residual
    /// `r = dy/ρ' − (Jĥ dx + ĥ)` is removed with the factor of `δ_c`: `M ddx = ρ Jĥᵀ r`, `ddy = ρ(Jĥ ddx − r)`.
    fn refine_equalities(&mut self) {
        let e = &self.eval;
        let rho_target = self.rho * REFINE_FACTOR;
        for _ in 0..REFINEMENTS {
            // r (in work_h) and ρ r / s_h (in refine_rows, for Jhᵀ).
            e.jh.mul_vec(&self.dx, &mut self.work_h);
            for k in 0..self.dims.n_eq {
                let r = self.dy[k] / rho_target - (self.work_h[k] / self.scales.eq[k] + self.c_h[k]);
                self.work_h[k] = r;
                self.refine_rows[k] = self.rho * r / self.scales.eq[k];
            }
            // M ddx = ρ Jĥᵀ r
            self.refine_dx.iter_mut().for_each(|d| *d = 0.0);
            e.jh.tr_mul_vec_add(1.0, &self.refine_rows, &mut self.refine_dx);
            self.factor.solve_in_place(&mut self.refine_dx);
            // ddy = ρ(Jĥ ddx − r);  dx += ddx
            e.jh.mul_vec(&self.refine_dx, &mut self.refine_rows);
            for k in 0..self.dims.n_eq {
                self.dy[k] += self.rho * (self.refine_rows[k] / self.scales.eq[k] - self.work_h[k]);
            }
            self.dx.iter_mut().zip(&self.refine_dx).for_each(|(x, d)| *x += d);
        }
    }

    /// The largest step in `(0, 1]` keeping `u + α du ≥ (1 − τ) u`.
    pub(super) fn to_boundary(u: &[f64], du: &[f64], tau: f64) -> f64 {
        u.iter().zip(du).filter(|(_, d)| **d < 0.0).map(|(u, d)| -tau * u / d).fold(1.0, f64::min)
    }

    /// Takes the step of length `alpha` (the dual one to its own boundary) and re-evaluates with Jacobians.
    fn accept(&mut self, alpha: f64) -> Result<(), StopReason> {
        std::mem::swap(&mut self.x, &mut self.x_trial);
        std::mem::swap(&mut self.s, &mut self.s_trial);
        let x = std::mem::take(&mut self.x);
        let evaluated = self.evaluate_at(&x, true);
        self.x = x;
        evaluated.map_err(|e| StopReason::EvaluationError(e.to_string()))?;
        let tau = TO_BOUNDARY;
        let alpha_v = Self::to_boundary(&self.v, &self.dv, tau);
        for (y, d) in self.y.iter_mut().zip(&self.dy) {
            *y += alpha * d;
        }
        for (v, d) in self.v.iter_mut().zip(&self.dv) {
            *v += alpha_v * d;
        }
        self.safeguard_multipliers();
        self.update_secant();
        Ok(())
    }
}
