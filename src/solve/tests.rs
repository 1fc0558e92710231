//! Both solvers on problems with known solutions. Each test checks the answer against the analytical or
//! published optimum *and* that the two solvers agree.

use nalgebra::DMatrix;

use super::auglag::AugmentedLagrangian;
use super::*;

type Values = (Vec<f64>, Vec<f64>, Vec<f64>);
type Jacobians = (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>);
type Model = fn(&[f64]) -> (Values, Jacobians);

/// A small problem with dense Jacobians, given by a function.
pub(super) struct Small {
    dims: Dims,
    model: Model,
    names: Vec<&'static str>,
    pub(super) scales: Scales,
}

impl Small {
    fn new(dims: Dims, model: Model, names: Vec<&'static str>) -> Self {
        Small { dims, model, names, scales: Scales::default() }
    }
}

fn copy_rows(m: &DMatrix<f64>, j: &mut SparseMatrix) {
    for i in 0..m.nrows() {
        for (v, c) in j.row_values_mut(i).iter_mut().zip(0..m.ncols()) {
            *v = m[(i, c)];
        }
    }
}

impl Problem for Small {
    fn dims(&self) -> Dims {
        self.dims
    }

    fn jacobian_patterns(&self) -> Patterns {
        Patterns::dense(self.dims)
    }

    fn evaluate(&mut self, x: &[f64], want_jac: bool, out: &mut Evaluation) -> Result<(), String> {
        let ((r, h, g), (jr, jh, jg)) = (self.model)(x);
        out.r.copy_from_slice(&r);
        out.h.copy_from_slice(&h);
        out.g.copy_from_slice(&g);
        if want_jac {
            copy_rows(&jr, &mut out.jr);
            copy_rows(&jh, &mut out.jh);
            copy_rows(&jg, &mut out.jg);
        }
        Ok(())
    }

    fn scales(&self) -> Scales {
        self.scales.clone()
    }

    /// Names: equalities first, then inequalities.
    fn constraint_name(&self, kind: ConstraintKind, index: usize) -> String {
        let i = match kind {
            ConstraintKind::Equality => index,
            ConstraintKind::Inequality => self.dims.n_eq + index,
        };
        self.names.get(i).map_or_else(|| format!("{kind} {index}"), |s| s.to_string())
    }
}

fn dims(n: usize, n_res: usize, n_eq: usize, n_ineq: usize) -> Dims {
    Dims { n, n_res, n_eq, n_ineq }
}

fn mat(rows: usize, cols: usize, v: &[f64]) -> DMatrix<f64> {
    DMatrix::from_row_slice(rows, cols, v)
}

/// min ½‖x − (1, 2, 3)‖²  s.t.  x₀ = x₁,  x₀ + x₁ + x₂ ≤ 3,  x₂ ≥ 2.5,  x₀ ≤ 10.
/// KKT: x − a + λ₀(1,1,1) − λ₁ e₂ + λ₂ e₀ + μ(1,−1,0) = 0 gives μ = −½, and with both first inequalities
/// active x = (¼, ¼, 5/2), λ = (5/4, 3/4, 0) — positive, so this is the optimum.
pub(super) fn qp() -> Small {
    fn model(x: &[f64]) -> (Values, Jacobians) {
        let r = vec![x[0] - 1.0, x[1] - 2.0, x[2] - 3.0];
        let h = vec![x[0] - x[1]];
        let g = vec![x[0] + x[1] + x[2] - 3.0, 2.5 - x[2], x[0] - 10.0];
        let jg = mat(3, 3, &[1.0, 1.0, 1.0, 0.0, 0.0, -1.0, 1.0, 0.0, 0.0]);
        ((r, h, g), (DMatrix::identity(3, 3), mat(1, 3, &[1.0, -1.0, 0.0]), jg))
    }
    Small::new(dims(3, 3, 1, 3), model, vec!["x0 = x1", "sum ≤ 3", "x2 ≥ 2.5", "x0 ≤ 10"])
}

pub(super) const QP_X: [f64; 3] = [0.25, 0.25, 2.5];
pub(super) const QP_LAMBDA: [f64; 3] = [1.25, 0.75, 0.0];
pub(super) const QP_MU: [f64; 1] = [-0.5];

/// Hock–Schittkowski 6: min (1 − x₀)²  s.t.  10(x₁ − x₀²) = 0;  x* = (1, 1), F* = 0.
pub(super) fn hs6() -> Small {
    fn model(x: &[f64]) -> (Values, Jacobians) {
        let s = std::f64::consts::SQRT_2;
        let r = vec![s * (1.0 - x[0])];
        let h = vec![10.0 * (x[1] - x[0] * x[0])];
        ((r, h, vec![]), (mat(1, 2, &[-s, 0.0]), mat(1, 2, &[-20.0 * x[0], 10.0]), DMatrix::zeros(0, 2)))
    }
    Small::new(dims(2, 1, 1, 0), model, vec!["10(x1 − x0²) = 0"])
}

/// Shift making the HS71 objective a square: F = ½ r² = f + HS71_SHIFT.
const HS71_SHIFT: f64 = 100.0;

/// Hock–Schittkowski 71: min x₀x₃(x₀+x₁+x₂) + x₂  s.t.  x₀x₁x₂x₃ ≥ 25,  Σxᵢ² = 40,  1 ≤ xᵢ ≤ 5.
/// Not a sum of squares, so written as `r = √(2(f + c))` (r is NaN where f < −c: the solvers must cope).
pub(super) fn hs71() -> Small {
    fn model(x: &[f64]) -> (Values, Jacobians) {
        let s = x[0] + x[1] + x[2];
        let f = x[0] * x[3] * s + x[2];
        let df = [x[3] * (x[0] + s), x[0] * x[3], x[0] * x[3] + 1.0, x[0] * s];
        let r = (2.0 * (f + HS71_SHIFT)).sqrt();
        let jr = mat(1, 4, &df.map(|d| d / r));
        let p = x[0] * x[1] * x[2] * x[3];
        let mut g = vec![25.0 - p];
        let mut jg = DMatrix::zeros(9, 4);
        for i in 0..4 {
            jg[(0, i)] = -p / x[i];
        }
        if x.contains(&0.0) {
            jg.row_mut(0).copy_from_slice(&[-x[1] * x[2] * x[3], -x[0] * x[2] * x[3], -x[0] * x[1] * x[3], -x[0] * x[1] * x[2]]);
        }
        for i in 0..4 {
            g.push(1.0 - x[i]);
            jg[(1 + i, i)] = -1.0;
        }
        for i in 0..4 {
            g.push(x[i] - 5.0);
            jg[(5 + i, i)] = 1.0;
        }
        let h = vec![x.iter().map(|v| v * v).sum::<f64>() - 40.0];
        let jh = mat(1, 4, &[2.0 * x[0], 2.0 * x[1], 2.0 * x[2], 2.0 * x[3]]);
        ((vec![r], h, g), (jr, jh, jg))
    }
    Small::new(dims(4, 1, 1, 9), model, vec!["Σx² = 40", "x0x1x2x3 ≥ 25"])
}

pub(super) const HS71_X: [f64; 4] = [1.0, 4.742999637, 3.821149984, 1.379408291];
const HS71_F: f64 = 17.014017289;

/// Rosenbrock as least squares: r = (10(x₁ − x₀²), 1 − x₀); minimiser (1, 1).
fn rosenbrock() -> Small {
    fn model(x: &[f64]) -> (Values, Jacobians) {
        let r = vec![10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0]];
        let jr = mat(2, 2, &[-20.0 * x[0], 10.0, -1.0, 0.0]);
        ((r, vec![], vec![]), (jr, DMatrix::zeros(0, 2), DMatrix::zeros(0, 2)))
    }
    Small::new(dims(2, 2, 0, 0), model, vec![])
}

/// x ≤ −1 and x ≥ 1: no feasible point.
pub(super) fn infeasible() -> Small {
    fn model(x: &[f64]) -> (Values, Jacobians) {
        let g = vec![x[0] + 1.0, 1.0 - x[0]];
        ((vec![x[0] - 0.5], vec![], g), (mat(1, 1, &[1.0]), DMatrix::zeros(0, 1), mat(2, 1, &[1.0, -1.0])))
    }
    Small::new(dims(1, 1, 0, 2), model, vec!["x ≤ −1", "x ≥ 1"])
}

/// A discretised smoothing problem with banded structure: fit `xᵢ + 0.1xᵢ³` to noisy data `dᵢ` with a
/// second-difference penalty, ends fixed, and a cap `xᵢ ≤ 0.7` that is active on the peaks.
struct Smoothing {
    n: usize,
    data: Vec<f64>,
    beta: f64,
    cap: f64,
}

impl Smoothing {
    fn new(n: usize) -> Self {
        let data =
            (0..n).map(|i| (4.0 * std::f64::consts::PI * i as f64 / n as f64).sin() + 0.2 * (37.0 * i as f64).sin()).collect();
        Smoothing { n, data, beta: 3.0, cap: 0.7 }
    }
}

impl Problem for Smoothing {
    fn dims(&self) -> Dims {
        dims(self.n, 2 * self.n - 2, 2, self.n)
    }

    fn jacobian_patterns(&self) -> Patterns {
        let n = self.n;
        let mut r: Vec<Vec<usize>> = (0..n).map(|i| vec![i]).collect();
        // The smoothness rows list their columns out of order, to exercise that.
        r.extend((1..n - 1).map(|i| vec![i, i - 1, i + 1]));
        Patterns { r, h: vec![vec![0], vec![n - 1]], g: (0..n).map(|i| vec![i]).collect() }
    }

    #[allow(clippy::needless_range_loop)] // index arithmetic mirrors the formulas
    fn evaluate(&mut self, x: &[f64], want_jac: bool, out: &mut Evaluation) -> Result<(), String> {
        let n = self.n;
        for i in 0..n {
            out.r[i] = x[i] + 0.1 * x[i].powi(3) - self.data[i];
            out.g[i] = x[i] - self.cap;
        }
        for i in 1..n - 1 {
            out.r[n + i - 1] = self.beta * (x[i - 1] - 2.0 * x[i] + x[i + 1]);
        }
        out.h[0] = x[0] - 0.1;
        out.h[1] = x[n - 1] + 0.2;
        if want_jac {
            for i in 0..n {
                out.jr.row_values_mut(i)[0] = 1.0 + 0.3 * x[i] * x[i];
                out.jg.row_values_mut(i)[0] = 1.0;
            }
            for i in 1..n - 1 {
                out.jr.row_values_mut(n + i - 1).copy_from_slice(&[-2.0 * self.beta, self.beta, self.beta]);
            }
            out.jh.row_values_mut(0)[0] = 1.0;
            out.jh.row_values_mut(1)[0] = 1.0;
        }
        Ok(())
    }

    fn constraint_name(&self, kind: ConstraintKind, index: usize) -> String {
        match kind {
            ConstraintKind::Equality => format!("end {index}"),
            ConstraintKind::Inequality => format!("cap at node {index}"),
        }
    }
}

pub(super) fn tight() -> Settings {
    Settings { tol_stationarity: 1e-10, tol_violation: 1e-10, ..Settings::default() }
}

/// Solves with both solvers; returns (BFGS, LM).
fn both(problem: &mut dyn Problem, x0: &[f64], settings: &Settings) -> (Outcome, Outcome) {
    let a = AugLagBfgs::default().solve(problem, x0, settings, &mut |_| {});
    let b = AugLagLevenbergMarquardt.solve(problem, x0, settings, &mut |_| {});
    (a, b)
}

pub(super) fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max)
}

pub(super) fn summary(o: &Outcome) -> String {
    format!(
        "{}: F = {}, stationarity {:.2e}, violation {:.2e} ({:?}), {} iterations, {} outer, {} evaluations, w_p = {:.2e}",
        o.reason,
        o.objective,
        o.stationarity,
        o.worst_violation,
        o.worst_constraint.as_ref().map(|c| &c.name),
        o.iterations,
        o.outer_iterations,
        o.evaluations,
        o.penalty
    )
}

pub(super) fn assert_converged(o: &Outcome, what: &str) {
    assert!(o.converged && o.reason == StopReason::Converged, "{what}: {}", summary(o));
    assert!(o.stationarity.is_finite() && o.worst_violation.is_finite());
}

/// The two solvers' answers agree: x, F and the multipliers to 1e-6 (relative to 1 + |value|).
pub(super) fn assert_agree(a: &Outcome, b: &Outcome, what: &str) {
    let close = |p: &[f64], q: &[f64]| p.iter().zip(q).all(|(u, v)| (u - v).abs() <= 1e-6 * (1.0 + u.abs()));
    assert!(close(&a.x, &b.x), "{what}: x differ by {}", max_diff(&a.x, &b.x));
    assert!(close(&[a.objective], &[b.objective]), "{what}: F {} vs {}", a.objective, b.objective);
    assert!(
        close(&a.multipliers.lambda, &b.multipliers.lambda),
        "{what}: λ differ by {}",
        max_diff(&a.multipliers.lambda, &b.multipliers.lambda)
    );
    assert!(close(&a.multipliers.mu, &b.multipliers.mu), "{what}: μ differ");
}

#[test]
fn solve_qp_with_active_inequalities_matches_kkt() {
    let mut p = qp();
    let (a, b) = both(&mut p, &[0.0, 0.0, 0.0], &tight());
    for (o, name) in [(&a, "AL-BFGS"), (&b, "AL-LM")] {
        assert_converged(o, name);
        assert!(max_diff(&o.x, &QP_X) < 1e-8, "{name}: x = {:?}", o.x);
        assert!(max_diff(&o.multipliers.lambda, &QP_LAMBDA) < 1e-6, "{name}: λ = {:?}", o.multipliers.lambda);
        assert!(max_diff(&o.multipliers.mu, &QP_MU) < 1e-6, "{name}: μ = {:?}", o.multipliers.mu);
        assert!((o.objective - 0.5 * (0.75f64.powi(2) + 1.75f64.powi(2) + 0.25)).abs() < 1e-8);
    }
    assert_agree(&a, &b, "QP");
}

#[test]
fn solve_scaled_constraints_report_multipliers_in_problem_units() {
    let mut p = qp();
    p.scales = Scales { eq: vec![3.0], ineq: vec![2.0, 0.5, 100.0] };
    let (a, b) = both(&mut p, &[1.0, -1.0, 0.0], &tight());
    for o in [&a, &b] {
        assert_converged(o, "scaled QP");
        assert!(max_diff(&o.x, &QP_X) < 1e-8);
        assert!(max_diff(&o.multipliers.lambda, &QP_LAMBDA) < 1e-6, "λ = {:?}", o.multipliers.lambda);
        assert!(max_diff(&o.multipliers.mu, &QP_MU) < 1e-6);
    }
    assert_agree(&a, &b, "scaled QP");
}

#[test]
fn solve_default_tolerances_are_met_honestly() {
    let mut p = qp();
    let (a, b) = both(&mut p, &[0.0, 0.0, 0.0], &Settings::default());
    for o in [&a, &b] {
        assert_converged(o, "QP, default settings");
        assert!(o.stationarity <= 1e-6 && o.worst_violation <= 1e-6);
        assert!(max_diff(&o.x, &QP_X) < 1e-5);
    }
}

#[test]
fn solve_hs6() {
    let mut p = hs6();
    let (a, b) = both(&mut p, &[-1.2, 1.0], &tight());
    for o in [&a, &b] {
        assert_converged(o, "HS6");
        assert!(max_diff(&o.x, &[1.0, 1.0]) < 1e-6, "x = {:?}", o.x);
        assert!(o.objective < 1e-12);
    }
    assert_agree(&a, &b, "HS6");
}

#[test]
fn solve_hs71() {
    let mut p = hs71();
    let (a, b) = both(&mut p, &[1.0, 5.0, 5.0, 1.0], &tight());
    for o in [&a, &b] {
        assert_converged(o, "HS71");
        assert!(max_diff(&o.x, &HS71_X) < 1e-6, "x = {:?}", o.x);
        assert!((o.objective - HS71_SHIFT - HS71_F).abs() < 1e-6, "f = {}", o.objective - HS71_SHIFT);
        // Active: the product, x₀ ≥ 1 and the sphere; the others have zero multipliers.
        let l = &o.multipliers.lambda;
        assert!(l[0] > 0.1 && l[1] > 0.1, "λ = {l:?}");
        assert!(l[2..].iter().all(|&v| v == 0.0), "λ = {l:?}");
    }
    assert_agree(&a, &b, "HS71");
}

#[test]
fn solve_rosenbrock_as_least_squares() {
    let mut p = rosenbrock();
    let (a, b) = both(&mut p, &[-1.2, 1.0], &tight());
    for o in [&a, &b] {
        assert_converged(o, "Rosenbrock");
        assert!(max_diff(&o.x, &[1.0, 1.0]) < 1e-8, "x = {:?}", o.x);
    }
    assert_agree(&a, &b, "Rosenbrock");
}

#[test]
fn solve_infeasible_reports_the_worst_constraint() {
    let mut p = infeasible();
    let (a, b) = both(&mut p, &[3.0], &Settings::default());
    for o in [&a, &b] {
        assert!(!o.converged);
        let StopReason::Infeasible { worst, violation } = &o.reason else { panic!("{}", summary(o)) };
        assert!(worst == "x ≤ −1" || worst == "x ≥ 1", "{worst}");
        assert!((1.0..1.01).contains(violation), "{violation}");
        assert_eq!(o.worst_constraint.as_ref().map(|c| c.name.as_str()), Some(worst.as_str()));
        assert_eq!(o.worst_constraint.as_ref().map(|c| c.kind), Some(ConstraintKind::Inequality));
        assert!(o.reason.to_string().starts_with("infeasible: x "), "{}", o.reason);
    }
}

#[test]
fn solve_banded_smoothing_n500_lm_and_bfgs_agree() {
    let mut p = Smoothing::new(500);
    let x0 = vec![0.0; 500];
    let settings = Settings { tol_stationarity: 1e-10, tol_violation: 1e-10, ..Settings::default() };
    let (a, b) = both(&mut p, &x0, &settings);
    assert_converged(&a, "smoothing, AL-BFGS");
    assert_converged(&b, "smoothing, AL-LM");
    assert_agree(&a, &b, "smoothing");
    let active = b.multipliers.lambda.iter().filter(|&&l| l > 0.0).count();
    assert!(active > 20, "the cap should bind on the peaks, {active} active");
    assert!(b.x.iter().all(|&v| v <= 0.7 + 1e-10));
    assert!((b.x[0] - 0.1).abs() < 1e-10 && (b.x[499] + 0.2).abs() < 1e-10);
    // The structured solver needs far fewer iterations than BFGS on this problem.
    assert!(b.iterations < a.iterations, "LM {} vs BFGS {}", b.iterations, a.iterations);
}

/// ∇L_A (eq. 25–29) against central differences of L_A (eq. 10), with multipliers and a penalty chosen so
/// that some inequalities are active, some not, on HS71.
#[test]
fn solve_augmented_lagrangian_gradient_matches_finite_differences() {
    let mut p = hs71();
    p.scales = Scales { eq: vec![4.0], ineq: vec![10.0, 1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0] };
    let settings = Settings { initial_penalty: Some(3.0), ..Settings::default() };
    let x = [1.1, 4.5, 3.9, 1.2];
    let mut observer = |_: &Progress| {};
    let mut al = AugmentedLagrangian::new(&mut p, &mut observer, &x, &settings, std::time::Instant::now()).unwrap();
    al.set_multipliers(&[2.0, 0.5, 0.0, 1.0, 0.0, 0.3, 0.0, 0.0, 0.0], &[-1.5]);
    al.evaluate(&x, true).unwrap();
    let mut grad = [0.0; 4];
    al.gradient(&mut grad);
    for i in 0..4 {
        let h = 1e-6;
        let (mut xp, mut xm) = (x, x);
        xp[i] += h;
        xm[i] -= h;
        al.evaluate(&xp, false).unwrap();
        let fp = al.value();
        al.evaluate(&xm, false).unwrap();
        let fm = al.value();
        let fd = (fp - fm) / (2.0 * h);
        assert!((fd - grad[i]).abs() < 1e-6 * (1.0 + fd.abs()), "∂L_A/∂x{i}: {} vs {fd}", grad[i]);
    }
}

#[test]
fn solve_warm_start_from_the_solution_needs_no_steps() {
    let mut p = qp();
    let cold = AugLagLevenbergMarquardt.solve(&mut p, &[0.0; 3], &tight(), &mut |_| {});
    assert_converged(&cold, "cold");
    let warm_settings = Settings { warm_start: Some(cold.multipliers.clone()), initial_penalty: Some(cold.penalty), ..tight() };
    let (a, b) = both(&mut p, &cold.x, &warm_settings);
    for o in [&a, &b] {
        assert_converged(o, "warm");
        assert!(o.iterations == 0 && o.outer_iterations == 0, "{}", summary(o));
        assert_eq!(o.x, cold.x);
        assert_eq!(o.multipliers, cold.multipliers);
    }
}

#[test]
fn solve_observer_sees_monotone_progress() {
    let mut p = hs71();
    for solver in [&AugLagBfgs::default() as &dyn Solver, &AugLagLevenbergMarquardt] {
        let mut seen: Vec<Progress> = Vec::new();
        let o = solver.solve(&mut p, &[1.0, 5.0, 5.0, 1.0], &Settings::default(), &mut |pr| seen.push(*pr));
        assert_converged(&o, "HS71, default settings");
        assert!(!seen.is_empty());
        assert!(seen.windows(2).all(|w| w[0].iteration <= w[1].iteration && w[0].evaluations <= w[1].evaluations));
        assert_eq!(seen.last().map(|s| s.iteration), Some(o.iterations));
    }
}

#[test]
fn solve_limits_are_reported() {
    let mut p = hs71();
    let few = Settings { max_iterations: 3, ..Settings::default() };
    let (a, b) = both(&mut p, &[1.0, 5.0, 5.0, 1.0], &few);
    for o in [&a, &b] {
        assert_eq!(o.reason, StopReason::MaxIterations);
        assert!(!o.converged && o.iterations == 3);
    }
    let no_time = Settings { time_limit: Some(0.0), ..Settings::default() };
    let (a, b) = both(&mut p, &[1.0, 5.0, 5.0, 1.0], &no_time);
    for o in [&a, &b] {
        assert_eq!(o.reason, StopReason::TimeLimit);
        assert!(!o.converged);
        assert!(o.objective.is_finite(), "the starting point is still assessed");
    }
}

/// Fails or returns NaN on demand.
struct Faulty {
    nan_at_start: bool,
    fail_after: usize,
    calls: usize,
}

impl Problem for Faulty {
    fn dims(&self) -> Dims {
        dims(2, 2, 0, 0)
    }

    fn jacobian_patterns(&self) -> Patterns {
        Patterns::dense(self.dims())
    }

    fn evaluate(&mut self, x: &[f64], want_jac: bool, out: &mut Evaluation) -> Result<(), String> {
        self.calls += 1;
        if self.calls > self.fail_after {
            return Err("the dynamics diverged".into());
        }
        out.r[0] = if self.nan_at_start { f64::NAN } else { 10.0 * (x[1] - x[0] * x[0]) };
        out.r[1] = 1.0 - x[0];
        if want_jac {
            out.jr.row_values_mut(0).copy_from_slice(&[-20.0 * x[0], 10.0]);
            out.jr.row_values_mut(1).copy_from_slice(&[-1.0, 0.0]);
        }
        Ok(())
    }
}

#[test]
fn solve_evaluation_errors_are_values() {
    for solver in [&AugLagBfgs::default() as &dyn Solver, &AugLagLevenbergMarquardt] {
        let mut nan = Faulty { nan_at_start: true, fail_after: usize::MAX, calls: 0 };
        let o = solver.solve(&mut nan, &[0.0, 0.0], &Settings::default(), &mut |_| {});
        let StopReason::EvaluationError(m) = &o.reason else { panic!("{}", o.reason) };
        assert!(m.contains("residual 0") && m.contains("NaN"), "{m}");
        assert!(!o.converged);

        let mut failing = Faulty { nan_at_start: false, fail_after: 4, calls: 0 };
        let o = solver.solve(&mut failing, &[-1.2, 1.0], &tight(), &mut |_| {});
        assert_eq!(o.reason, StopReason::EvaluationError("the dynamics diverged".into()));
        assert!(!o.converged && o.x.iter().all(|v| v.is_finite()));
    }
}

#[test]
fn solve_invalid_input_is_reported_not_panicked() {
    let solver = AugLagLevenbergMarquardt;
    let mut p = qp();
    let o = solver.solve(&mut p, &[0.0; 2], &Settings::default(), &mut |_| {});
    assert!(matches!(&o.reason, StopReason::InvalidInput(m) if m.contains("x0 has 2")), "{}", o.reason);

    p.scales.ineq = vec![1.0, -1.0, 1.0];
    let o = solver.solve(&mut p, &[0.0; 3], &Settings::default(), &mut |_| {});
    assert!(matches!(&o.reason, StopReason::InvalidInput(m) if m.contains("scale 1")), "{}", o.reason);

    let mut p = qp();
    let bad = Settings { warm_start: Some(Multipliers { lambda: vec![1.0], mu: vec![] }), ..Settings::default() };
    let o = solver.solve(&mut p, &[0.0; 3], &bad, &mut |_| {});
    assert!(matches!(o.reason, StopReason::InvalidInput(_)));
    let o = solver.solve(&mut p, &[0.0; 3], &Settings { time_limit: Some(f64::NAN), ..Settings::default() }, &mut |_| {});
    assert!(matches!(o.reason, StopReason::InvalidInput(_)));

    struct BadPattern;
    impl Problem for BadPattern {
        fn dims(&self) -> Dims {
            dims(2, 1, 0, 0)
        }
        fn jacobian_patterns(&self) -> Patterns {
            Patterns { r: vec![vec![0, 2]], ..Patterns::default() }
        }
        fn evaluate(&mut self, _: &[f64], _: bool, _: &mut Evaluation) -> Result<(), String> {
            Ok(())
        }
    }
    let o = solver.solve(&mut BadPattern, &[0.0; 2], &Settings::default(), &mut |_| {});
    assert!(matches!(&o.reason, StopReason::InvalidInput(m) if m.contains("column 2")), "{}", o.reason);
}

#[test]
fn solve_settings_deserialise_with_defaults() {
    let s: Settings = serde_json::from_str(r#"{"tol_violation": 1e-8, "time_limit": 30}"#).unwrap();
    assert_eq!(s.tol_violation, 1e-8);
    assert_eq!(s.time_limit, Some(30.0));
    assert_eq!(s.tol_stationarity, Settings::default().tol_stationarity);
    assert!(serde_json::from_str::<Settings>(r#"{"tol_violaton": 1}"#).is_err());
}

/// Minimum "torque" for a pendulum discretised by finite differences: τᵢ = q̈ᵢ + c sin qᵢ at interior
/// nodes, ends fixed by equalities, and a torque limit |τᵢ| ≤ τ_max. The residuals stay large at the
/// optimum (holding against gravity), which is where Gauss–Newton is slow.
pub(super) struct Pendulum {
    pub(super) n: usize,
    pub(super) duration: f64,
    pub(super) c: f64,
    pub(super) tau_max: f64,
}

impl Pendulum {
    fn h(&self) -> f64 {
        self.duration / (self.n - 1) as f64
    }
}

impl Problem for Pendulum {
    fn dims(&self) -> Dims {
        dims(self.n, self.n - 2, 4, 2 * (self.n - 2))
    }

    fn jacobian_patterns(&self) -> Patterns {
        let rows: Vec<Vec<usize>> = (1..self.n - 1).map(|i| vec![i - 1, i, i + 1]).collect();
        Patterns {
            r: rows.clone(),
            h: vec![vec![0], vec![0, 1], vec![self.n - 1], vec![self.n - 2, self.n - 1]],
            g: rows.iter().chain(&rows).cloned().collect(),
        }
    }

    fn evaluate(&mut self, x: &[f64], want_jac: bool, out: &mut Evaluation) -> Result<(), String> {
        let (n, h) = (self.n, self.h());
        let w = h.sqrt();
        let m = n - 2;
        for i in 1..n - 1 {
            let tau = (x[i - 1] - 2.0 * x[i] + x[i + 1]) / (h * h) + self.c * x[i].sin();
            out.r[i - 1] = w * tau;
            out.g[i - 1] = tau - self.tau_max;
            out.g[m + i - 1] = -tau - self.tau_max;
            if want_jac {
                let d = [1.0 / (h * h), -2.0 / (h * h) + self.c * x[i].cos(), 1.0 / (h * h)];
                out.jr.row_values_mut(i - 1).copy_from_slice(&d.map(|v| w * v));
                out.jg.row_values_mut(i - 1).copy_from_slice(&d);
                out.jg.row_values_mut(m + i - 1).copy_from_slice(&d.map(|v| -v));
            }
        }
        out.h[0] = x[0];
        out.h[1] = (x[1] - x[0]) / h;
        out.h[2] = x[n - 1] - 2.0;
        out.h[3] = (x[n - 1] - x[n - 2]) / h;
        if want_jac {
            out.jh.row_values_mut(0)[0] = 1.0;
            out.jh.row_values_mut(1).copy_from_slice(&[-1.0 / h, 1.0 / h]);
            out.jh.row_values_mut(2)[0] = 1.0;
            out.jh.row_values_mut(3).copy_from_slice(&[-1.0 / h, 1.0 / h]);
        }
        Ok(())
    }

    fn scales(&self) -> Scales {
        Scales { eq: vec![], ineq: vec![self.tau_max; 2 * (self.n - 2)] }
    }
}

#[test]
fn solve_pendulum_with_active_torque_limits_large_residuals() {
    let n = 60;
    let mut p = Pendulum { n, duration: 2.0, c: 10.0, tau_max: 5.0 };
    let x0: Vec<f64> = (0..n).map(|i| 2.0 * i as f64 / (n - 1) as f64).collect();
    let (a, b) = both(&mut p, &x0, &tight());
    assert_converged(&a, "pendulum, AL-BFGS");
    assert_converged(&b, "pendulum, AL-LM");
    assert_agree(&a, &b, "pendulum");
    // The limit binds on both sides (accelerating and braking), and the torques respect it.
    let active = b.multipliers.lambda.iter().filter(|&&l| l > 0.0).count();
    assert!(active >= 10, "{active} active torque limits");
    let mut e = Evaluation::new(p.dims(), &p.jacobian_patterns()).unwrap();
    p.evaluate(&b.x, false, &mut e).unwrap();
    assert!(e.g.iter().all(|&g| g <= 1e-9), "max g = {}", e.g.iter().fold(f64::MIN, |m, &g| m.max(g)));
    assert!(e.r.iter().map(|r| r.abs()).fold(0.0, f64::max) > 0.5, "residuals stay large at the optimum");
}

/// A tolerance below rounding cannot be met: the solve must say so (stalled or line search failed) rather
/// than run to the iteration limit, and must not claim convergence.
#[test]
fn solve_unattainable_tolerance_ends_honestly() {
    let settings = Settings { tol_stationarity: 1e-17, tol_violation: 1e-17, ..Settings::default() };
    for (mut p, x0) in [(qp(), vec![0.0; 3]), (hs71(), vec![1.0, 5.0, 5.0, 1.0])] {
        let (a, b) = both(&mut p, &x0, &settings);
        for o in [&a, &b] {
            assert!(!o.converged, "{}", summary(o));
            assert!(matches!(o.reason, StopReason::Stalled | StopReason::LineSearchFailed), "{}", summary(o));
            assert!(o.iterations < 1000, "{}", summary(o));
            assert!(o.stationarity < 1e-12 && o.worst_violation < 1e-9, "{}", summary(o));
        }
    }
}

/// An inner budget too small to make headway: the solve stops early, saying there is no progress and
/// where it stands — not at the iteration limit thousands of steps later. The same problem with the
/// default budget converges (the opposite condition).
#[test]
fn solve_without_progress_says_so_early() {
    let mut p = rosenbrock();
    let starved = Settings { max_inner_iterations: 1, ..tight() };
    let a = AugLagLevenbergMarquardt.solve(&mut p, &[-1.2, 1.0], &starved, &mut |_| {});
    assert!(!a.converged, "{}", summary(&a));
    let StopReason::NoProgress { inner_solves, stationarity, .. } = a.reason else { panic!("{}", summary(&a)) };
    assert!(inner_solves >= 3 && stationarity > 1e-10, "{}", summary(&a));
    assert!(a.iterations < 100, "{}", summary(&a));
    assert!(a.reason.to_string().contains("no progress"), "{}", a.reason);
    let b = AugLagLevenbergMarquardt.solve(&mut p, &[-1.2, 1.0], &tight(), &mut |_| {});
    assert_converged(&b, "Rosenbrock, default inner budget");
}

/// Dennis & Schnabel's large-residual example (sec. 10.2): `r = (x + 1, λx² + x − 1)`, minimised at `x = 0`
/// with `F = 1`. There `JᵀJ = 2` and the second-order term `Σ rᵢ∇²rᵢ = −2λ`, so Gauss–Newton's step is
/// `1/(1 − λ)` times too short and it converges linearly with rate `λ`: ever slower as `λ → 1`.
struct LargeResidual {
    lambda: f64,
}

impl Problem for LargeResidual {
    fn dims(&self) -> Dims {
        dims(1, 2, 0, 0)
    }

    fn jacobian_patterns(&self) -> Patterns {
        Patterns::dense(self.dims())
    }

    fn evaluate(&mut self, x: &[f64], want_jac: bool, out: &mut Evaluation) -> Result<(), String> {
        let (x, l) = (x[0], self.lambda);
        out.r.copy_from_slice(&[x + 1.0, l * x * x + x - 1.0]);
        if want_jac {
            out.jr.row_values_mut(0)[0] = 1.0;
            out.jr.row_values_mut(1)[0] = 2.0 * l * x + 1.0;
        }
        Ok(())
    }
}

/// The structured solver adds the curvature to its model once an inner solve crawls: where Gauss–Newton's
/// rate is 0.99 it converges in a fraction of the steps plain Gauss–Newton takes (which stalls short of the
/// tolerance) — and where Gauss–Newton is fast (rate 0.5) no inner solve crawls, so the two take the same
/// steps.
#[test]
fn solve_structured_escalates_when_gauss_newton_crawls() {
    use super::least_squares::solve_structured;
    let solve = |lambda, escalate| {
        let mut p = LargeResidual { lambda };
        let o = match escalate {
            true => AugLagLevenbergMarquardt.solve(&mut p, &[1.0], &tight(), &mut |_| {}),
            false => solve_structured(&mut p, &[1.0], &tight(), &mut |_| {}, None),
        };
        assert!(o.x[0].abs() < 1e-6 || !o.converged, "λ = {lambda}: {}", summary(&o));
        o
    };
    let (crawling, escalated) = (solve(0.99, false), solve(0.99, true));
    assert_converged(&escalated, "rate 0.99, escalating");
    assert!(
        crawling.iterations > 3 * escalated.iterations,
        "Gauss–Newton {} | escalating {}",
        summary(&crawling),
        summary(&escalated)
    );
    let (fast, same) = (solve(0.5, false), solve(0.5, true));
    assert_converged(&fast, "rate 0.5, Gauss–Newton");
    assert_eq!(fast.iterations, same.iterations, "{} | {}", summary(&fast), summary(&same));
}

/// A warm start is near a solution, where Gauss–Newton crawls: the structured solver takes the curvature
/// from its first step there. Warm-started at `x = 0.2` on the rate-0.99 problem it converges in 9 steps
/// (over the outer iterations' tightening tolerances); a cold start from the same point (the opposite
/// condition) first crawls until it escalates (61 steps).
#[test]
fn solve_structured_takes_the_curvature_at_once_from_a_warm_start() {
    let mut p = LargeResidual { lambda: 0.99 };
    let cold = AugLagLevenbergMarquardt.solve(&mut p, &[0.2], &tight(), &mut |_| {});
    let none = Multipliers { lambda: vec![], mu: vec![] };
    let warm = AugLagLevenbergMarquardt.solve(&mut p, &[0.2], &Settings { warm_start: Some(none), ..tight() }, &mut |_| {});
    assert_converged(&cold, "cold");
    assert_converged(&warm, "warm");
    assert!(warm.x[0].abs() < 1e-6, "{}", summary(&warm));
    assert!(warm.iterations <= 12 && cold.iterations > 4 * warm.iterations, "warm {} | cold {}", summary(&warm), summary(&cold));
}

/// A warm start whose multipliers are far off (μ = 10⁶ against the true −0.5, at a small penalty) first
/// drives the equality far from holding. With `warm_divergence` the solve gives up and says so; without it
/// (the opposite condition) the same start still converges, only later.
#[test]
fn solve_a_diverging_warm_start_gives_up_only_when_asked() {
    let mut p = qp();
    let wrong = Multipliers { lambda: QP_LAMBDA.to_vec(), mu: vec![1e6] };
    let warm = Settings { warm_start: Some(wrong), initial_penalty: Some(1.0), ..tight() };
    let patient = AugLagLevenbergMarquardt.solve(&mut p, &QP_X, &warm, &mut |_| {});
    assert_converged(&patient, "without the guard");
    let guarded = Settings { warm_divergence: Some(100.0), ..warm };
    let o = AugLagLevenbergMarquardt.solve(&mut p, &QP_X, &guarded, &mut |_| {});
    let StopReason::WarmStartDiverged { start, violation } = o.reason else { panic!("{}", summary(&o)) };
    assert!(!o.converged && start < 1e-12 && violation > solver::DIVERGED_VIOLATION, "{}", summary(&o));
}

/// The guard acts at the accepted step that crosses its bound, not after the inner solve that went astray:
/// on HS6 warm-started at its solution with μ = 10⁶ at penalty 1, the inner solve walks the equality off
/// over many steps. Guarded, the observer sees exactly one step past the bound (the last); unguarded (the
/// opposite condition) it sees many.
#[test]
fn solve_a_diverging_warm_start_gives_up_at_the_step_that_crossed() {
    let mut p = hs6();
    let wrong = Multipliers { lambda: vec![], mu: vec![1e6] };
    let warm = Settings { warm_start: Some(wrong), initial_penalty: Some(1.0), max_iterations: 200, ..tight() };
    let past = |settings: &Settings, p: &mut Small| {
        let mut seen = Vec::new();
        let o = AugLagLevenbergMarquardt.solve(p, &[1.0, 1.0], settings, &mut |pr| seen.push(pr.violation));
        (o, seen.iter().filter(|&&v| v > solver::DIVERGED_VIOLATION).count())
    };
    let (unguarded, walked) = past(&warm, &mut p);
    assert!(walked > 3, "unguarded: {walked} steps past the bound; {}", summary(&unguarded));
    let (o, crossed) = past(&Settings { warm_divergence: Some(100.0), ..warm }, &mut p);
    assert!(matches!(o.reason, StopReason::WarmStartDiverged { .. }), "{}", summary(&o));
    assert_eq!(crossed, 1, "{}", summary(&o));
}
