//! BFGS with a dense inverse-Hessian approximation `H ≈ (∇²f)⁻¹` (Nocedal & Wright, Alg. 6.1) — the
//! quasi-Newton method the paper uses for its inner, unconstrained minimisation (sec. 5, refs. [6, 11]).
//!
//! Update (N&W eq. 6.17), with `s = x₊ − x`, `y = ∇f₊ − ∇f`, `ρ = 1/(yᵀs)`:
//!   `H₊ = (I − ρ s yᵀ) H (I − ρ y sᵀ) + ρ s sᵀ`,
//! expanded to `H₊ = H − ρ (s (Hy)ᵀ + (Hy) sᵀ) + (ρ² yᵀHy + ρ) s sᵀ`, which costs one product `Hy`.
//! Before the first update, `H₀ = (sᵀy / yᵀy) I` (N&W eq. 6.20) so that the first quasi-Newton step has
//! the right length. The strong Wolfe line search makes `sᵀy > 0` in exact arithmetic; when rounding
//! breaks that (`sᵀy ≤ ε ‖s‖‖y‖`) the update is skipped, which keeps `H` positive definite.

use super::line_search::{dot, norm_inf, EvalError, Iterate, LineSearch, LineSearchResult, LineSearchWork, Objective};

/// Stopping and line-search parameters of [`Bfgs::minimise`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BfgsSettings {
    /// Accepted steps allowed.
    pub max_iterations: usize,
    /// Stop when `‖∇f‖∞ ≤ gradient_tolerance · objective.gradient_scale()`.
    pub gradient_tolerance: f64,
    /// The Wolfe line search.
    pub line_search: LineSearch,
}

impl Default for BfgsSettings {
    fn default() -> Self {
        BfgsSettings { max_iterations: 1000, gradient_tolerance: 1e-8, line_search: LineSearch::default() }
    }
}

/// Why a minimisation stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum BfgsStatus {
    /// `‖∇f‖∞` fell below the tolerance.
    Converged,
    /// The step budget ran out.
    MaxIterations,
    /// No step with sufficient decrease along the quasi-Newton direction, nor along steepest descent.
    LineSearchFailed,
    /// [`Objective::iteration_done`] asked to stop.
    Stopped,
    /// The objective failed to evaluate; the message says why.
    EvaluationError(String),
}

/// Summary of a minimisation; the final point is left in the caller's `x`.
#[derive(Clone, Debug, PartialEq)]
pub struct BfgsReport {
    /// Why it stopped.
    pub status: BfgsStatus,
    /// Accepted steps.
    pub iterations: usize,
    /// Objective evaluations.
    pub evaluations: usize,
    /// `f` at the final point.
    pub f: f64,
    /// `‖∇f(x)‖∞` at the final point.
    pub gradient_norm: f64,
}

/// BFGS state: the inverse-Hessian approximation (kept between calls, so a sequence of related problems
/// — the augmented Lagrangian's inner problems — can start from the curvature learnt so far) and work
/// buffers.
#[derive(Clone, Debug)]
pub struct Bfgs {
    n: usize,
    /// `H`, row-major `n × n`; meaningful only when `updated`.
    h: Vec<f64>,
    /// Whether `H` holds curvature information; if not, `H = I` and the next update first scales it.
    updated: bool,
    gradient: Vec<f64>,
    direction: Vec<f64>,
    s: Vec<f64>,
    y: Vec<f64>,
    hy: Vec<f64>,
    work: LineSearchWork,
}

impl Bfgs {
    /// A minimiser of `n` unknowns, starting from `H = I`.
    pub fn new(n: usize) -> Self {
        Bfgs {
            n,
            h: vec![0.0; n * n],
            updated: false,
            gradient: vec![0.0; n],
            direction: vec![0.0; n],
            s: vec![0.0; n],
            y: vec![0.0; n],
            hy: vec![0.0; n],
            work: LineSearchWork::new(n),
        }
    }

    /// The dimension `n`.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Forgets the curvature information (`H` back to a scaled identity at the next update).
    pub fn reset(&mut self) {
        self.updated = false;
    }

    /// Minimises `objective` from `x`, leaving the last accepted point in `x`.
    ///
    /// # Panics
    /// If `x.len()` differs from the dimension given to [`Bfgs::new`].
    pub fn minimise(&mut self, objective: &mut dyn Objective, x: &mut [f64], settings: &BfgsSettings) -> BfgsReport {
        assert_eq!(x.len(), self.n);
        let mut report =
            BfgsReport { status: BfgsStatus::Converged, iterations: 0, evaluations: 1, f: f64::NAN, gradient_norm: f64::NAN };
        let mut f = match objective.evaluate(x, &mut self.gradient) {
            Ok(f) if f.is_finite() && self.gradient.iter().all(|g| g.is_finite()) => f,
            Ok(_) => return self.stop(report, BfgsStatus::EvaluationError("non-finite value or gradient at the start".into())),
            Err(e) => return self.stop(report, BfgsStatus::EvaluationError(e.to_string())),
        };
        loop {
            let gnorm = norm_inf(&self.gradient);
            report.f = f;
            report.gradient_norm = gnorm;
            let go_on = objective.iteration_done(&Iterate { iteration: report.iterations, x, f, gradient_norm: gnorm });
            if gnorm <= settings.gradient_tolerance * objective.gradient_scale() {
                return self.stop(report, BfgsStatus::Converged);
            }
            if !go_on {
                return self.stop(report, BfgsStatus::Stopped);
            }
            if report.iterations >= settings.max_iterations {
                return self.stop(report, BfgsStatus::MaxIterations);
            }
            // Quasi-Newton direction; steepest descent if H is fresh or (through rounding) not giving descent.
            self.set_direction();
            let mut result = self.search(objective, x, f, settings);
            report.evaluations += evaluations_of(&result);
            if !matches!(result, LineSearchResult::Accepted { .. } | LineSearchResult::Error { .. }) && self.updated {
                // H may have become a poor model; one retry along steepest descent before giving up.
                self.updated = false;
                self.set_direction();
                result = self.search(objective, x, f, settings);
                report.evaluations += evaluations_of(&result);
            }
            let (alpha, f_new) = match result {
                LineSearchResult::Accepted { alpha, f, .. } => (alpha, f),
                LineSearchResult::Failed { .. } => return self.stop(report, BfgsStatus::LineSearchFailed),
                LineSearchResult::Error { error, .. } => return self.stop(report, status_of(error)),
            };
            for i in 0..self.n {
                self.s[i] = alpha * self.direction[i];
                self.y[i] = self.work.gradient[i] - self.gradient[i];
            }
            x.copy_from_slice(&self.work.x);
            self.gradient.copy_from_slice(&self.work.gradient);
            f = f_new;
            report.iterations += 1;
            self.update();
        }
    }

    fn stop(&self, mut report: BfgsReport, status: BfgsStatus) -> BfgsReport {
        report.status = status;
        report
    }

    /// `p = −H g` (or `−g`), falling back to `−g` if `gᵀp ≥ 0`.
    fn set_direction(&mut self) {
        let n = self.n;
        if self.updated {
            for i in 0..n {
                self.direction[i] = -dot(&self.h[i * n..(i + 1) * n], &self.gradient);
            }
            if dot(&self.direction, &self.gradient) < 0.0 {
                return;
            }
            self.updated = false;
        }
        for (p, g) in self.direction.iter_mut().zip(&self.gradient) {
            *p = -g;
        }
    }

    fn search(&mut self, objective: &mut dyn Objective, x: &[f64], f: f64, settings: &BfgsSettings) -> LineSearchResult {
        // A quasi-Newton step has a natural length of 1; a steepest-descent step does not, so the first one
        // is capped at unit length in the ∞-norm.
        let alpha0 = if self.updated { 1.0 } else { (1.0 / norm_inf(&self.direction)).min(1.0) };
        settings.line_search.search(objective, x, f, &self.gradient, &self.direction, alpha0, &mut self.work)
    }

    /// The BFGS update of `H` with the pair `(s, y)`, skipped when `sᵀy` is not safely positive.
    fn update(&mut self) {
        let n = self.n;
        let sy = dot(&self.s, &self.y);
        let yy = dot(&self.y, &self.y);
        let ss = dot(&self.s, &self.s);
        if sy.is_nan() || sy <= f64::EPSILON * (ss * yy).sqrt() || !sy.is_finite() {
            return;
        }
        if !self.updated {
            // H₀ = (sᵀy / yᵀy) I (N&W eq. 6.20).
            let gamma = sy / yy;
            self.h.fill(0.0);
            for i in 0..n {
                self.h[i * n + i] = gamma;
            }
            self.updated = true;
        }
        for i in 0..n {
            self.hy[i] = dot(&self.h[i * n..(i + 1) * n], &self.y);
        }
        let rho = 1.0 / sy;
        let yhy = dot(&self.y, &self.hy);
        let c = rho * rho * yhy + rho;
        for i in 0..n {
            let (si, hyi) = (self.s[i], self.hy[i]);
            let row = &mut self.h[i * n..(i + 1) * n];
            for ((hij, &sj), &hyj) in row.iter_mut().zip(&self.s).zip(&self.hy) {
                *hij += c * si * sj - rho * (si * hyj + hyi * sj);
            }
        }
    }
}

fn evaluations_of(r: &LineSearchResult) -> usize {
    match r {
        LineSearchResult::Accepted { evaluations, .. }
        | LineSearchResult::Failed { evaluations }
        | LineSearchResult::Error { evaluations, .. } => *evaluations,
    }
}

fn status_of(error: EvalError) -> BfgsStatus {
    BfgsStatus::EvaluationError(error.to_string())
}

/// Minimises `objective` from `x` with a fresh [`Bfgs`].
pub fn minimise(objective: &mut dyn Objective, x: &mut [f64], settings: &BfgsSettings) -> BfgsReport {
    Bfgs::new(x.len()).minimise(objective, x, settings)
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Rosenbrock {
        evaluations: usize,
    }

    impl Objective for Rosenbrock {
        fn evaluate(&mut self, x: &[f64], g: &mut [f64]) -> Result<f64, EvalError> {
            self.evaluations += 1;
            let (a, b) = (1.0 - x[0], x[1] - x[0] * x[0]);
            g[0] = -2.0 * a - 400.0 * x[0] * b;
            g[1] = 200.0 * b;
            Ok(a * a + 100.0 * b * b)
        }
    }

    #[test]
    fn rosenbrock_reaches_the_minimiser() {
        for start in [[-1.2, 1.0], [2.0, -1.5], [0.0, 0.0]] {
            let mut x = start;
            let mut f = Rosenbrock { evaluations: 0 };
            let settings = BfgsSettings { gradient_tolerance: 1e-10, ..BfgsSettings::default() };
            let report = minimise(&mut f, &mut x, &settings);
            assert_eq!(report.status, BfgsStatus::Converged, "from {start:?}: {report:?}");
            assert!((x[0] - 1.0).abs() < 1e-8 && (x[1] - 1.0).abs() < 1e-8, "from {start:?}: {x:?}");
            assert!(report.iterations < 100, "{report:?}");
            assert_eq!(report.evaluations, f.evaluations);
        }
    }

    /// A convex quadratic ½ xᵀAx − bᵀx: BFGS with exact-enough line searches must end at A⁻¹b.
    struct Quadratic {
        a: nalgebra::DMatrix<f64>,
        b: nalgebra::DVector<f64>,
    }

    impl Objective for Quadratic {
        fn evaluate(&mut self, x: &[f64], g: &mut [f64]) -> Result<f64, EvalError> {
            let x = nalgebra::DVector::from_column_slice(x);
            let ax = &self.a * &x;
            g.copy_from_slice((&ax - &self.b).as_slice());
            Ok(0.5 * x.dot(&ax) - self.b.dot(&x))
        }
    }

    #[test]
    fn quadratic_solution_and_stop_reasons() {
        let n = 20;
        let a = nalgebra::DMatrix::from_fn(n, n, |i, j| if i == j { 4.0 + i as f64 } else { 1.0 / (1.0 + (i + j) as f64) });
        let b = nalgebra::DVector::from_fn(n, |i, _| (i as f64).cos());
        let expect = a.clone().cholesky().unwrap().solve(&b);
        let mut q = Quadratic { a, b };
        let mut x = vec![0.0; n];
        let report = minimise(&mut q, &mut x, &BfgsSettings::default());
        assert_eq!(report.status, BfgsStatus::Converged);
        assert!((nalgebra::DVector::from_column_slice(&x) - expect).amax() < 1e-8);

        let mut x = vec![0.0; n];
        let few = BfgsSettings { max_iterations: 2, ..BfgsSettings::default() };
        assert_eq!(minimise(&mut q, &mut x, &few).status, BfgsStatus::MaxIterations);
    }

    struct NanAtStart;

    impl Objective for NanAtStart {
        fn evaluate(&mut self, _x: &[f64], g: &mut [f64]) -> Result<f64, EvalError> {
            g.fill(0.0);
            Ok(f64::NAN)
        }
    }

    #[test]
    fn nan_is_an_error_not_a_panic() {
        let report = minimise(&mut NanAtStart, &mut [1.0], &BfgsSettings::default());
        assert!(matches!(report.status, BfgsStatus::EvaluationError(_)));
    }
}
