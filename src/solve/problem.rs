//! The finite problem a solver sees (paper eq. 1–3, in least-squares form):
//!
//! ```text
//!   minimise  F(x) = ½ ‖r(x)‖²     x ∈ ℝⁿ (the B-spline control points)
//!   subject to  h(x) = 0           (equalities, eq. 3: poses, loop closure)
//!               g(x) ≤ 0           (inequalities, eq. 2: joint and torque limits)
//! ```
//!
//! The objective is given by its residuals `r` (for the planner `rⱼ = √wⱼ τ` at quadrature node `j`), so a
//! solver can use the Gauss–Newton structure `∇²F ≈ JᵣᵀJᵣ`. All Jacobians are sparse with a pattern fixed
//! for the whole solve.

use super::linalg::SymmetricMatrix;
use super::sparse::{PatternError, SparseMatrix};

/// Sizes of a problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Dims {
    /// Unknowns.
    pub n: usize,
    /// Objective residuals.
    pub n_res: usize,
    /// Equality constraints `h`.
    pub n_eq: usize,
    /// Inequality constraints `g`.
    pub n_ineq: usize,
}

/// Column lists, one per row, of the Jacobians `∂r/∂x`, `∂h/∂x` and `∂g/∂x`. A row's values are written in
/// the order of its list.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Patterns {
    /// Columns of each residual row `∂rᵢ/∂x`.
    pub r: Vec<Vec<usize>>,
    /// Columns of each equality row `∂hₖ/∂x`.
    pub h: Vec<Vec<usize>>,
    /// Columns of each inequality row `∂gᵢ/∂x`.
    pub g: Vec<Vec<usize>>,
}

impl Patterns {
    /// Every row touches every column (small dense problems, tests).
    pub fn dense(dims: Dims) -> Self {
        let all = |rows: usize| (0..rows).map(|_| (0..dims.n).collect()).collect();
        Patterns { r: all(dims.n_res), h: all(dims.n_eq), g: all(dims.n_ineq) }
    }
}

/// Which family a constraint belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum ConstraintKind {
    /// `h_k(x) = 0`.
    Equality,
    /// `g_i(x) ≤ 0`.
    Inequality,
}

impl std::fmt::Display for ConstraintKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            ConstraintKind::Equality => "equality",
            ConstraintKind::Inequality => "inequality",
        })
    }
}

/// Per-constraint scales `s > 0`: a solver works with `h_k/s_k` and `g_i/s_i`, so the violation tolerance
/// means the same for an angle in radians and a torque in N·m (e.g. `s` = the torque limit). An empty
/// vector means all ones.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scales {
    /// Scales of the equalities `h` (empty = all ones).
    pub eq: Vec<f64>,
    /// Scales of the inequalities `g` (empty = all ones).
    pub ineq: Vec<f64>,
}

/// The three kinds of rows of a problem, in the order `r`, `h`, `g` (`family as usize` indexes arrays of
/// three in that order).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RowFamily {
    /// A residual of the objective, `r`.
    Residual,
    /// An equality, `h`.
    Equality,
    /// An inequality, `g`.
    Inequality,
}

/// Values (and, when asked, Jacobians) at one point. Built once per solve by [`Evaluation::new`]; the
/// problem overwrites `r`, `h`, `g` and, when `want_jac`, the Jacobians' values (which the solver zeroes
/// before the call, so a problem may accumulate into them with [`SparseMatrix::add`], unless the problem
/// says it writes them whole: [`Problem::writes_whole_jacobians`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Evaluation {
    /// Residuals `r(x)` of the objective `F = ½‖r‖²`.
    pub r: Vec<f64>,
    /// Equality constraints `h(x)`.
    pub h: Vec<f64>,
    /// Inequality constraints `g(x)`.
    pub g: Vec<f64>,
    /// `∂r/∂x`, on [`Patterns::r`].
    pub jr: SparseMatrix,
    /// `∂h/∂x`, on [`Patterns::h`].
    pub jh: SparseMatrix,
    /// `∂g/∂x`, on [`Patterns::g`].
    pub jg: SparseMatrix,
}

/// A problem's description does not hang together.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ProblemError {
    /// A pattern has the wrong number of rows.
    #[error("jacobian pattern of {which}: {rows} rows, but dims say {expected}")]
    PatternRows {
        /// Which pattern: "r", "h" or "g".
        which: &'static str,
        /// Rows it has.
        rows: usize,
        /// Rows [`Dims`] says it should have.
        expected: usize,
    },
    /// A pattern is malformed.
    #[error("jacobian pattern of {which}: {source}")]
    Pattern {
        /// Which pattern: "r", "h" or "g".
        which: &'static str,
        /// What is wrong with it.
        #[source]
        source: PatternError,
    },
    /// The scales have the wrong length or are not positive and finite.
    #[error("scales of the {kind} constraints: {message}")]
    Scales {
        /// Equality or inequality scales.
        kind: ConstraintKind,
        /// What is wrong with them.
        message: String,
    },
}

impl Evaluation {
    /// Buffers shaped by `dims` and `patterns`, checking that they agree.
    pub fn new(dims: Dims, patterns: &Patterns) -> Result<Self, ProblemError> {
        let build = |which: &'static str, rows: &[Vec<usize>], expected: usize| {
            if rows.len() != expected {
                return Err(ProblemError::PatternRows { which, rows: rows.len(), expected });
            }
            SparseMatrix::from_rows(dims.n, rows).map_err(|source| ProblemError::Pattern { which, source })
        };
        Ok(Evaluation {
            r: vec![0.0; dims.n_res],
            h: vec![0.0; dims.n_eq],
            g: vec![0.0; dims.n_ineq],
            jr: build("r", &patterns.r, dims.n_res)?,
            jh: build("h", &patterns.h, dims.n_eq)?,
            jg: build("g", &patterns.g, dims.n_ineq)?,
        })
    }

    /// Buffers for the values only, for [`Problem::evaluate`] with `want_jac = false` (the Jacobians have
    /// their rows but no entries, so building them costs nothing).
    pub fn values_only(dims: Dims) -> Self {
        Evaluation {
            r: vec![0.0; dims.n_res],
            h: vec![0.0; dims.n_eq],
            g: vec![0.0; dims.n_ineq],
            jr: SparseMatrix::without_entries(dims.n_res, dims.n),
            jh: SparseMatrix::without_entries(dims.n_eq, dims.n),
            jg: SparseMatrix::without_entries(dims.n_ineq, dims.n),
        }
    }

    /// Half-bandwidth of `JᵀJ` over the three Jacobians: the band a solver's matrix needs.
    pub fn gram_bandwidth(&self) -> usize {
        [&self.jr, &self.jh, &self.jg].iter().map(|j| j.gram_bandwidth()).max().unwrap_or(0)
    }

    /// The Jacobian of one kind of rows.
    pub fn jacobian(&self, family: RowFamily) -> &SparseMatrix {
        match family {
            RowFamily::Residual => &self.jr,
            RowFamily::Equality => &self.jh,
            RowFamily::Inequality => &self.jg,
        }
    }

    /// `F = ½ ‖r‖²`.
    pub fn objective(&self) -> f64 {
        0.5 * self.r.iter().map(|v| v * v).sum::<f64>()
    }

    /// The first non-finite entry, described with `name(family, row)` (`None` if all values are finite).
    pub fn first_non_finite(&self, with_jacobians: bool, name: &dyn Fn(RowFamily, usize) -> String) -> Option<String> {
        // Whether any value is not finite, in one pass (the common case: none, and nothing to name).
        let jacobians = [&self.jr, &self.jh, &self.jg].map(|m| m.values()).into_iter().filter(|_| with_jacobians);
        if [&self.r[..], &self.h, &self.g].into_iter().chain(jacobians).all(all_finite) {
            return None;
        }
        let vectors = [(RowFamily::Residual, &self.r), (RowFamily::Equality, &self.h), (RowFamily::Inequality, &self.g)];
        for (family, v) in vectors {
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Some(format!("{} = {}", name(family, i), v[i]));
            }
        }
        if with_jacobians {
            for family in [RowFamily::Residual, RowFamily::Equality, RowFamily::Inequality] {
                let m = self.jacobian(family);
                for i in 0..m.nrows() {
                    if let Some(p) = m.row_values(i).iter().position(|x| !x.is_finite()) {
                        let (col, v) = (m.row_cols(i)[p], m.row_values(i)[p]);
                        return Some(format!("the derivative of {} by unknown {col} = {v}", name(family, i)));
                    }
                }
            }
        }
        None
    }
}

/// Whether every value is finite: one pass without branches, which the compiler vectorises.
fn all_finite(values: &[f64]) -> bool {
    values.iter().fold(true, |finite, v| finite & v.is_finite())
}

/// An inequality row proportional to a residual row ([`Problem::proportional_rows`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Proportional {
    /// Index in `g`.
    pub ineq: usize,
    /// Index in `r`.
    pub residual: usize,
    /// `∇g_ineq = factor · ∇r_residual`.
    pub factor: f64,
}

/// A finite-dimensional constrained least-squares problem.
pub trait Problem {
    /// Sizes of `x`, `r`, `h` and `g`.
    fn dims(&self) -> Dims;

    /// Sparsity of the Jacobians (called once per solve).
    fn jacobian_patterns(&self) -> Patterns;

    /// Writes `r(x)`, `h(x)`, `g(x)` into `out`, and their Jacobians when `want_jac`. An `Err` stops the solve
    /// with [`StopReason::EvaluationError`](super::StopReason::EvaluationError); non-finite values are caught
    /// by the solver.
    fn evaluate(&mut self, x: &[f64], want_jac: bool, out: &mut Evaluation) -> Result<(), String>;

    /// Whether [`Problem::evaluate`] with `want_jac` sets every entry of the Jacobians' patterns, whatever
    /// they held, so that the solver need not zero them before each call (default: `false`).
    fn writes_whole_jacobians(&self) -> bool {
        false
    }

    /// Adds the second-order term of the Lagrangian's Hessian, `Σⱼ wⱼ ∇²cⱼ` over every row `cⱼ` of `r`, `h`
    /// and `g` with weights `weights = [w_r, w_h, w_g]`, at `x`, into the lower triangle of `target` (sized
    /// for `JᵀJ`), and returns `true`; or returns `false` without touching `target` when the problem does
    /// not provide it (the default: solvers then approximate it). Must not change the last evaluation.
    fn add_second_order(&mut self, x: &[f64], weights: [&[f64]; 3], target: &mut SymmetricMatrix) -> bool {
        let _ = (x, weights, target);
        false
    }

    /// Inequality rows whose Jacobian row is, at every `x`, a fixed multiple of a residual row's over the
    /// same pattern: `∇gᵢ = factor · ∇rⱼ` (a torque limit's row and the effort's residual of the same torque
    /// at the same node). A solver may then add the row's Gram term `wᵢ∇gᵢ∇gᵢᵀ` as `wᵢ factor² ∇rⱼ∇rⱼᵀ`
    /// into the residual's and skip the row. Default: none.
    fn proportional_rows(&self) -> Vec<Proportional> {
        Vec::new()
    }

    /// Per-constraint scales for the violation tolerance (default: all ones).
    fn scales(&self) -> Scales {
        Scales::default()
    }

    /// A human-readable name of any row (default: "residual i" or [`Problem::constraint_name`]).
    fn row_name(&self, family: RowFamily, index: usize) -> String {
        match family {
            RowFamily::Residual => format!("residual {index}"),
            RowFamily::Equality => self.constraint_name(ConstraintKind::Equality, index),
            RowFamily::Inequality => self.constraint_name(ConstraintKind::Inequality, index),
        }
    }

    /// A human-readable name, e.g. "torque limit of joint elbow at t = 0.41 s".
    fn constraint_name(&self, kind: ConstraintKind, index: usize) -> String {
        format!("{kind} constraint {index}")
    }
}

/// The problem's [`Problem::proportional_rows`], checked against the evaluated Jacobians' patterns: rows in
/// range, each inequality once, a finite non-zero factor, the same columns as its residual row.
pub(crate) fn checked_proportional(problem: &dyn Problem, eval: &Evaluation) -> Result<Vec<Proportional>, String> {
    let rows = problem.proportional_rows();
    let mut seen = vec![false; eval.jg.nrows()];
    for p in &rows {
        let fits = p.ineq < eval.jg.nrows() && p.residual < eval.jr.nrows();
        if !fits || seen[p.ineq] || !p.factor.is_finite() || p.factor == 0.0 {
            return Err(format!("proportional row {p:?}: out of range, repeated or without a finite non-zero factor"));
        }
        seen[p.ineq] = true;
        if eval.jg.row_cols(p.ineq) != eval.jr.row_cols(p.residual) {
            return Err(format!("proportional row {p:?}: its columns are not its residual row's"));
        }
    }
    Ok(rows)
}

/// Scales checked against `dims`, with empty vectors expanded to ones.
pub(crate) fn checked_scales(problem: &dyn Problem, dims: Dims) -> Result<Scales, ProblemError> {
    let given = problem.scales();
    let check = |kind: ConstraintKind, s: Vec<f64>, len: usize| {
        if s.is_empty() {
            return Ok(vec![1.0; len]);
        }
        if s.len() != len {
            return Err(ProblemError::Scales { kind, message: format!("{} given for {len} constraints", s.len()) });
        }
        if let Some(i) = s.iter().position(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(ProblemError::Scales { kind, message: format!("scale {i} is {}, must be finite and positive", s[i]) });
        }
        Ok(s)
    };
    Ok(Scales {
        eq: check(ConstraintKind::Equality, given.eq, dims.n_eq)?,
        ineq: check(ConstraintKind::Inequality, given.ineq, dims.n_ineq)?,
    })
}

/// Evaluates `problem` at `x` into `out` (with its Jacobians when `want_jac`, zeroed first unless the problem
/// writes them whole), and checks what came back: the lengths of `r`, `h`, `g`, and that every value is
/// finite, naming the first that is not (`evaluation` numbers the call in the message). Shared by the solvers.
pub(crate) fn evaluate_checked(
    problem: &mut dyn Problem,
    d: Dims,
    x: &[f64],
    want_jac: bool,
    out: &mut Evaluation,
    evaluation: usize,
) -> Result<(), super::line_search::EvalError> {
    use super::line_search::EvalError;
    if want_jac && !problem.writes_whole_jacobians() {
        out.jr.fill_zero();
        out.jh.fill_zero();
        out.jg.fill_zero();
    }
    problem.evaluate(x, want_jac, out).map_err(EvalError::Failed)?;
    if out.r.len() != d.n_res || out.h.len() != d.n_eq || out.g.len() != d.n_ineq {
        return Err(EvalError::Failed("evaluate changed the length of r, h or g".into()));
    }
    let problem = &*problem;
    if let Some(what) = out.first_non_finite(want_jac, &|family, i| problem.row_name(family, i)) {
        return Err(EvalError::NonFinite(format!("non-finite {what} (evaluation {evaluation})")));
    }
    Ok(())
}
