//! The initial guess (paper sec. 6, step 2): the spec's motion as B-spline control points, with the contact
//! forces that best carry it.

use super::{InitialGuess, Spec, Transcription};
use crate::error::{Error, Result};
use crate::solve::{self, Problem};

/// The initial guess as solver unknowns.
pub fn initial_x(spec: &Spec, problem: &mut Transcription) -> Result<Vec<f64>> {
    let nv = spec.model.nv();
    let n = spec.n_ctrl;
    let spline = &problem.spline;
    let mut ctrl = vec![0.0; n * nv];
    for i in 0..nv {
        let column = match &spec.initial_guess {
            InitialGuess::Linear => spline.linear_guess(spec.start[i], spec.goal[i]),
            InitialGuess::Via(vias) => {
                let points: Vec<(f64, f64)> = vias.iter().map(|(t, q)| (*t, q[i])).collect();
                spline.through_points(spec.start[i], &points, spec.goal[i])?
            }
            InitialGuess::ControlPoints(c) | InitialGuess::Plan { ctrl: c, .. } => (0..n).map(|j| c[j * nv + i]).collect(),
            InitialGuess::Samples(samples) => {
                let times: Vec<f64> = samples.iter().map(|(t, _)| *t).collect();
                let values: Vec<f64> = samples.iter().map(|(_, q)| q[i]).collect();
                spline.fit_least_squares(&times, &values)?
            }
        };
        for j in 0..n {
            ctrl[j * nv + i] = column[j];
        }
    }
    if let InitialGuess::Plan { lambda_ctrl, .. } = &spec.initial_guess {
        return Ok(problem.layout.pack(&ctrl, lambda_ctrl));
    }
    let lambda = vec![0.0; n * problem.layout.n_lambda];
    let mut x = problem.layout.pack(&ctrl, &lambda);
    initial_contact_forces(problem, &mut x)?;
    Ok(x)
}

/// The contact forces that best carry the initial motion: the residuals are linear in the contact-force
/// control points, so for the guessed motion the least-squares forces are one linear solve. Starting from
/// them instead of zero forces spares the solver its first and hardest iterations on closed loops.
pub(super) fn initial_contact_forces(problem: &mut Transcription, x: &mut [f64]) -> Result<()> {
    let layout = problem.layout.clone();
    if layout.n_lambda == 0 {
        return Ok(());
    }
    let columns: Vec<usize> = (0..layout.n_ctrl)
        .flat_map(|j| (0..layout.n_lambda).map(move |m| (j, m)))
        .map(|(j, m)| layout.lambda_var(j, m))
        .collect();
    let dims = problem.dims();
    let origin = problem.spec.origin.clone();
    let fail = |e: String| Error::task(&origin, "initial guess", e);
    let mut eval = solve::Evaluation::new(dims, &problem.jacobian_patterns()).map_err(|e| fail(e.to_string()))?;
    problem.evaluate(x, true, &mut eval).map_err(fail)?;
    let m = columns.len();
    let mut a = nalgebra::DMatrix::<f64>::zeros(m, m);
    let mut b = nalgebra::DVector::<f64>::zeros(m);
    let position: std::collections::BTreeMap<usize, usize> = columns.iter().enumerate().map(|(k, &c)| (c, k)).collect();
    for row in 0..dims.n_res {
        let entries: Vec<(usize, f64)> = eval
            .jr
            .row_cols(row)
            .iter()
            .zip(eval.jr.row_values(row))
            .filter_map(|(c, v)| position.get(c).map(|&k| (k, *v)))
            .collect();
        for &(k, vk) in &entries {
            b[k] -= vk * eval.r[row];
            for &(l, vl) in &entries {
                a[(k, l)] += vk * vl;
            }
        }
    }
    // A whisper of ridge keeps forces that the motion does not determine (e.g. along a frictionless plane's
    // tangent) at zero rather than arbitrary.
    let ridge = 1e-9 * (0..m).map(|k| a[(k, k)]).fold(0.0, f64::max).max(1e-300);
    for k in 0..m {
        a[(k, k)] += ridge;
    }
    if let Some(delta) = a.cholesky().map(|c| c.solve(&b)) {
        for (k, &c) in columns.iter().enumerate() {
            x[c] += delta[k];
        }
    }
    Ok(())
}

pub(super) fn objective_at(problem: &mut Transcription, x: &[f64]) -> std::result::Result<f64, String> {
    let mut eval = solve::Evaluation::values_only(problem.dims());
    problem.evaluate(x, false, &mut eval)?;
    Ok(eval.objective())
}
