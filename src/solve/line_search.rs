//! Smooth unconstrained objectives, and a line search satisfying the strong Wolfe conditions
//! (Nocedal & Wright, *Numerical Optimization*, 2nd ed., Alg. 3.5 "line search" and Alg. 3.6 "zoom",
//! with safeguarded cubic interpolation, eq. 3.59).
//!
//! Strong Wolfe along `p` from `x` (`φ(α) = f(x + αp)`):
//!   sufficient decrease  `φ(α) ≤ φ(0) + c₁ α φ'(0)`,
//!   curvature            `|φ'(α)| ≤ c₂ |φ'(0)|`.
//! The curvature condition guarantees `sᵀy > 0`, so the BFGS update stays positive definite.

/// Relative slack in `f` allowed by the approximate Wolfe conditions.
const APPROXIMATE_WOLFE_EPSILON: f64 = 1e-10;

/// Why an objective could not be evaluated.
#[derive(Clone, Debug, PartialEq)]
pub enum EvalError {
    /// Values were computed but are not finite (NaN or ±∞). A line search treats such a point as "too far"
    /// and backtracks; only if it cannot find a finite point does the minimisation stop.
    NonFinite(String),
    /// The evaluation itself failed; the minimisation stops at once.
    Failed(String),
}

impl std::fmt::Display for EvalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EvalError::NonFinite(m) | EvalError::Failed(m) => f.write_str(m),
        }
    }
}

/// An accepted iterate, shown to [`Objective::iteration_done`].
#[derive(Clone, Copy, Debug)]
pub struct Iterate<'a> {
    /// Accepted steps so far in this minimisation (0 for the starting point).
    pub iteration: usize,
    /// The point.
    pub x: &'a [f64],
    /// `f(x)`.
    pub f: f64,
    /// `‖∇f(x)‖∞`.
    pub gradient_norm: f64,
}

/// A smooth function `f: ℝⁿ → ℝ` with its gradient.
///
/// Invariant kept by the minimisers of this module: whenever they call [`Objective::gradient_scale`] or
/// [`Objective::iteration_done`], and when they return after an accepted step, the most recent call to
/// [`Objective::evaluate`] was at the current iterate. Objectives may therefore cache per-point data.
pub trait Objective {
    /// Returns `f(x)` and writes `∇f(x)` into `gradient`.
    fn evaluate(&mut self, x: &[f64], gradient: &mut [f64]) -> Result<f64, EvalError>;

    /// Scale of the stationarity test at the point last evaluated: a minimiser stops when
    /// `‖∇f‖∞ ≤ tolerance · gradient_scale()`. Default 1 (absolute test).
    fn gradient_scale(&self) -> f64 {
        1.0
    }

    /// Called at every accepted iterate (and at the starting point); return `false` to stop.
    fn iteration_done(&mut self, _iterate: &Iterate<'_>) -> bool {
        true
    }
}

/// Parameters of the strong Wolfe line search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineSearch {
    /// Sufficient-decrease constant `c₁` (N&W: 10⁻⁴).
    pub c1: f64,
    /// Curvature constant `c₂` (N&W: 0.9 for quasi-Newton directions).
    pub c2: f64,
    /// Evaluations allowed per search.
    pub max_evaluations: usize,
}

impl Default for LineSearch {
    fn default() -> Self {
        LineSearch { c1: 1e-4, c2: 0.9, max_evaluations: 40 }
    }
}

/// Result of a search. On `Accepted`, the work buffers hold the new point and its gradient, and the
/// objective was last evaluated there.
#[derive(Clone, Debug, PartialEq)]
pub enum LineSearchResult {
    /// A step satisfying the strong Wolfe conditions.
    Accepted {
        /// The step length.
        alpha: f64,
        /// `f` at the new point.
        f: f64,
        /// Objective evaluations of the search.
        evaluations: usize,
    },
    /// No acceptable step: `p` is not a descent direction, or no point with sufficient decrease was found.
    Failed {
        /// Objective evaluations of the search.
        evaluations: usize,
    },
    /// The objective failed, or no finite point was found along `p`.
    Error {
        /// Objective evaluations of the search.
        evaluations: usize,
        /// Why the objective failed.
        error: EvalError,
    },
}

/// Buffers for the trial point and its gradient, allocated once per minimisation.
#[derive(Clone, Debug)]
pub struct LineSearchWork {
    /// The trial point.
    pub x: Vec<f64>,
    /// The gradient there.
    pub gradient: Vec<f64>,
}

impl LineSearchWork {
    /// Buffers for `n` unknowns.
    pub fn new(n: usize) -> Self {
        LineSearchWork { x: vec![0.0; n], gradient: vec![0.0; n] }
    }
}

/// A trial step length with `φ(α)` and `φ'(α)` (`φ = +∞` for a non-finite point).
#[derive(Clone, Copy, Debug)]
struct Trial {
    alpha: f64,
    phi: f64,
    dphi: f64,
}

impl LineSearch {
    /// Searches along `p` from `x` (where `f(x) = f0`, `∇f(x) = g0`), first trying `alpha0`.
    #[allow(clippy::too_many_arguments)]
    pub fn search(
        &self,
        objective: &mut dyn Objective,
        x: &[f64],
        f0: f64,
        g0: &[f64],
        p: &[f64],
        alpha0: f64,
        work: &mut LineSearchWork,
    ) -> LineSearchResult {
        let dphi0 = dot(g0, p);
        if dphi0.is_nan() || dphi0 >= 0.0 || !alpha0.is_finite() || alpha0 <= 0.0 {
            return LineSearchResult::Failed { evaluations: 0 };
        }
        let mut s = Search { params: self, objective, x, p, phi0: f0, dphi0, work, evaluations: 0, last_error: None };
        s.run(alpha0)
    }
}

struct Search<'a> {
    params: &'a LineSearch,
    objective: &'a mut dyn Objective,
    x: &'a [f64],
    p: &'a [f64],
    phi0: f64,
    dphi0: f64,
    work: &'a mut LineSearchWork,
    evaluations: usize,
    last_error: Option<EvalError>,
}

enum Step {
    Done(LineSearchResult),
    Trial(Trial),
}

impl Search<'_> {
    /// Evaluates `φ(α)`, leaving the point and gradient in the work buffers.
    fn eval(&mut self, alpha: f64) -> Step {
        for ((xt, &xi), &pi) in self.work.x.iter_mut().zip(self.x).zip(self.p) {
            *xt = xi + alpha * pi;
        }
        self.evaluations += 1;
        match self.objective.evaluate(&self.work.x, &mut self.work.gradient) {
            Ok(phi) if phi.is_finite() && self.work.gradient.iter().all(|g| g.is_finite()) => {
                Step::Trial(Trial { alpha, phi, dphi: dot(&self.work.gradient, self.p) })
            }
            Ok(_) => {
                self.last_error = Some(EvalError::NonFinite(format!("non-finite value or gradient at step {alpha:e}")));
                Step::Trial(Trial { alpha, phi: f64::INFINITY, dphi: f64::NAN })
            }
            Err(EvalError::NonFinite(m)) => {
                self.last_error = Some(EvalError::NonFinite(m));
                Step::Trial(Trial { alpha, phi: f64::INFINITY, dphi: f64::NAN })
            }
            Err(e @ EvalError::Failed(_)) => Step::Done(LineSearchResult::Error { evaluations: self.evaluations, error: e }),
        }
    }

    /// Sufficient decrease: the Armijo condition, or — when `φ` differences are lost in rounding near a
    /// minimiser — its derivative form from the quadratic model, `φ'(α) ≤ (2c₁ − 1) φ'(0)`, together with
    /// `φ(α) ≤ φ(0) + ε|φ(0)|` (the "approximate Wolfe" conditions of Hager & Zhang 2005). Without it, a
    /// tight gradient tolerance cannot be met once `|Δf| < ε_mach |f|`.
    fn sufficient_decrease(&self, t: &Trial) -> bool {
        let armijo = t.phi <= self.phi0 + self.params.c1 * t.alpha * self.dphi0;
        let approximate = t.phi <= self.phi0 + APPROXIMATE_WOLFE_EPSILON * self.phi0.abs()
            && t.dphi <= (2.0 * self.params.c1 - 1.0) * self.dphi0;
        armijo || approximate
    }

    fn curvature(&self, t: &Trial) -> bool {
        t.dphi.abs() <= -self.params.c2 * self.dphi0
    }

    fn accept(&self, t: &Trial) -> LineSearchResult {
        LineSearchResult::Accepted { alpha: t.alpha, f: t.phi, evaluations: self.evaluations }
    }

    /// N&W Alg. 3.5: grow the step until an interval containing strong Wolfe points is bracketed.
    fn run(&mut self, alpha0: f64) -> LineSearchResult {
        let mut prev = Trial { alpha: 0.0, phi: self.phi0, dphi: self.dphi0 };
        let mut alpha = alpha0;
        let mut first = true;
        loop {
            let cur = match self.eval(alpha) {
                Step::Done(r) => return r,
                Step::Trial(t) => t,
            };
            let sufficient = self.sufficient_decrease(&cur);
            if sufficient && self.curvature(&cur) {
                return self.accept(&cur);
            }
            if !sufficient || (!first && cur.phi >= prev.phi) {
                return self.zoom(prev, cur);
            }
            if cur.dphi >= 0.0 {
                return self.zoom(cur, prev);
            }
            if self.evaluations >= self.params.max_evaluations {
                // Sufficient decrease holds but the minimum along p lies further out: take the step.
                return self.accept(&cur);
            }
            // Extrapolate: cubic minimiser of the bracket, kept within [1.1, 4] times the current step.
            let (lo, hi) = (cur.alpha * 1.1, cur.alpha * 4.0);
            alpha = cubic_minimiser(&prev, &cur).filter(|a| *a >= lo && *a <= hi).unwrap_or(hi);
            prev = cur;
            first = false;
        }
    }

    /// N&W Alg. 3.6. Invariants: `lo` satisfies sufficient decrease and has the lowest φ seen; the interval
    /// between `lo` and `hi` contains strong Wolfe points; `φ'(lo)(hi − lo) < 0`.
    fn zoom(&mut self, mut lo: Trial, mut hi: Trial) -> LineSearchResult {
        loop {
            let width = (hi.alpha - lo.alpha).abs();
            if self.evaluations >= self.params.max_evaluations || width <= 1e-14 * hi.alpha.abs().max(lo.alpha.abs()) {
                return self.give_up(lo);
            }
            // Cubic interpolation safeguarded to the middle 80% of the interval; bisection otherwise.
            let (a, b) = (lo.alpha.min(hi.alpha), lo.alpha.max(hi.alpha));
            let guard = 0.1 * (b - a);
            let alpha = cubic_minimiser(&lo, &hi).filter(|t| *t >= a + guard && *t <= b - guard).unwrap_or(0.5 * (a + b));
            let t = match self.eval(alpha) {
                Step::Done(r) => return r,
                Step::Trial(t) => t,
            };
            let sufficient = self.sufficient_decrease(&t);
            if sufficient && self.curvature(&t) {
                return self.accept(&t);
            }
            if !sufficient || t.phi >= lo.phi {
                hi = t;
            } else {
                if t.dphi * (hi.alpha - lo.alpha) >= 0.0 {
                    hi = lo;
                }
                lo = t;
            }
        }
    }

    /// Out of evaluations or interval: fall back to `lo` if it made progress (it satisfies sufficient
    /// decrease, only the curvature condition is missing). It is re-evaluated so that the objective was
    /// last evaluated at the returned point.
    fn give_up(&mut self, lo: Trial) -> LineSearchResult {
        if lo.alpha > 0.0 && lo.phi < self.phi0 {
            return match self.eval(lo.alpha) {
                Step::Done(r) => r,
                Step::Trial(t) if t.phi.is_finite() => self.accept(&t),
                Step::Trial(_) => self.failure(),
            };
        }
        self.failure()
    }

    fn failure(&mut self) -> LineSearchResult {
        match self.last_error.take() {
            Some(error) => LineSearchResult::Error { evaluations: self.evaluations, error },
            None => LineSearchResult::Failed { evaluations: self.evaluations },
        }
    }
}

/// Minimiser of the cubic interpolating `φ` and `φ'` at `a` and `b` (N&W eq. 3.59), if it exists.
fn cubic_minimiser(a: &Trial, b: &Trial) -> Option<f64> {
    if !(a.phi.is_finite() && b.phi.is_finite() && a.dphi.is_finite() && b.dphi.is_finite()) || a.alpha == b.alpha {
        return None;
    }
    let d1 = a.dphi + b.dphi - 3.0 * (a.phi - b.phi) / (a.alpha - b.alpha);
    let disc = d1 * d1 - a.dphi * b.dphi;
    if disc < 0.0 {
        return None;
    }
    let d2 = (b.alpha - a.alpha).signum() * disc.sqrt();
    let denom = b.dphi - a.dphi + 2.0 * d2;
    let t = b.alpha - (b.alpha - a.alpha) * (b.dphi + d2 - d1) / denom;
    t.is_finite().then_some(t)
}

pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

pub(crate) fn norm_inf(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m, v| m.max(v.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f(x) = Σ (xᵢ − 1)⁴ + xᵢ², a 1-D-ish quartic with a unique minimiser.
    struct Quartic;

    impl Objective for Quartic {
        fn evaluate(&mut self, x: &[f64], g: &mut [f64]) -> Result<f64, EvalError> {
            let mut f = 0.0;
            for (gi, &xi) in g.iter_mut().zip(x) {
                f += (xi - 1.0).powi(4) + xi * xi;
                *gi = 4.0 * (xi - 1.0).powi(3) + 2.0 * xi;
            }
            Ok(f)
        }
    }

    fn check_wolfe(alpha0: f64) {
        let ls = LineSearch::default();
        let x = [-2.0, 3.0];
        let mut g0 = [0.0; 2];
        let f0 = Quartic.evaluate(&x, &mut g0).unwrap();
        let p = [-g0[0], -g0[1]];
        let mut work = LineSearchWork::new(2);
        let r = ls.search(&mut Quartic, &x, f0, &g0, &p, alpha0, &mut work);
        let LineSearchResult::Accepted { alpha, f, .. } = r else { panic!("{r:?}") };
        let dphi0 = dot(&g0, &p);
        assert!(f <= f0 + ls.c1 * alpha * dphi0, "sufficient decrease, alpha0 {alpha0}");
        assert!(dot(&work.gradient, &p).abs() <= ls.c2 * dphi0.abs(), "curvature, alpha0 {alpha0}");
        let mut g = [0.0; 2];
        assert_eq!(Quartic.evaluate(&work.x, &mut g).unwrap(), f);
        assert_eq!(work.gradient, g);
    }

    #[test]
    fn strong_wolfe_from_short_and_long_first_steps() {
        for alpha0 in [1e-6, 1e-3, 1.0, 1e3] {
            check_wolfe(alpha0);
        }
    }

    /// Finite only for x < 1: a search starting with a long step must back off to finite points.
    struct Barrier;

    impl Objective for Barrier {
        fn evaluate(&mut self, x: &[f64], g: &mut [f64]) -> Result<f64, EvalError> {
            if x[0] >= 1.0 {
                return Err(EvalError::NonFinite("outside the domain".into()));
            }
            g[0] = -1.0 / (1.0 - x[0]) + 2.0 * x[0] - 3.0;
            Ok(-(1.0 - x[0]).ln() + x[0] * x[0] - 3.0 * x[0])
        }
    }

    #[test]
    fn backs_off_from_non_finite_points() {
        let mut g0 = [0.0];
        let f0 = Barrier.evaluate(&[0.0], &mut g0).unwrap();
        let mut work = LineSearchWork::new(1);
        let r = LineSearch::default().search(&mut Barrier, &[0.0], f0, &g0, &[1.0], 10.0, &mut work);
        let LineSearchResult::Accepted { f, .. } = r else { panic!("{r:?}") };
        assert!(f < f0 && work.x[0] < 1.0);
    }

    #[test]
    fn rejects_ascent_directions() {
        let mut g0 = [0.0; 2];
        let f0 = Quartic.evaluate(&[0.0, 0.0], &mut g0).unwrap();
        let mut work = LineSearchWork::new(2);
        let r = LineSearch::default().search(&mut Quartic, &[0.0, 0.0], f0, &g0, &g0.clone(), 1.0, &mut work);
        assert_eq!(r, LineSearchResult::Failed { evaluations: 0 });
    }
}
