//! The perturbed starts: every free joint's path bent by a smooth bump, halved while it drives solids
//! into each other.

use super::next_signed;
use crate::error::{Error, Result};
use crate::plan::guess::initial_contact_forces;
use crate::plan::transcription::IneqRow;
use crate::plan::{Spec, Transcription};
use crate::solve::{Evaluation, Problem};

/// Halvings of a bend that drives solids deeper into each other than the guess.
const HALVINGS: usize = 4;
/// A bend may deepen the worst penetration by this much (m) before it is halved.
const PENETRATION_SLACK: f64 = 1e-3;

/// `x0` with every free joint bent by a bump (`super`'s module docs), contact forces refitted; halved
/// (up to [`HALVINGS`] times) while its deepest penetration between solids exceeds the guess's.
pub(super) fn perturbed(spec: &Spec, problem: &mut Transcription, x0: &[f64], seed: u64) -> Result<Vec<f64>> {
    let bend = bend(spec, problem, x0, seed);
    let guess_depth = deepest_penetration(problem, x0)?;
    let mut scale = 1.0;
    loop {
        let x = bent(problem, x0, &bend, scale)?;
        if scale < 0.5f64.powi(HALVINGS as i32 - 1) || deepest_penetration(problem, &x)? <= guess_depth + PENETRATION_SLACK {
            return Ok(x);
        }
        scale *= 0.5;
    }
}

/// Each free joint's bump amplitude `aᵢ` (rad or m; 0 for a fixed one): uniform in `±min(¼ range, 30°)`,
/// away from a limit the guess touches.
fn bend(spec: &Spec, problem: &Transcription, x0: &[f64], seed: u64) -> Vec<f64> {
    let layout = &problem.layout;
    let (nv, n) = (layout.nv, layout.n_ctrl);
    let (mut ctrl, mut lambda) = (vec![0.0; n * nv], vec![0.0; n * layout.n_lambda]);
    layout.unpack(x0, &problem.fixed_values, &mut ctrl, &mut lambda);
    let mut state = seed;
    (0..nv)
        .map(|i| {
            let limits = &spec.model.joints[i + 1].limits;
            let range = limits.upper - limits.lower;
            let reach = if range.is_finite() { (0.25 * range).min(30f64.to_radians()) } else { 30f64.to_radians() };
            let a = reach * next_signed(&mut state);
            let column = || (0..n).map(|j| ctrl[j * nv + i]);
            let near = 0.01 * if range.is_finite() { range } else { 1.0 };
            if column().any(|c| c >= limits.upper - near) {
                -a.abs()
            } else if column().any(|c| c <= limits.lower + near) {
                a.abs()
            } else {
                a
            }
        })
        .collect()
}

/// `x0` with joint `i`'s control points moved by `scale · aᵢ sin(π t)` (`t` the point's place in time,
/// near its Greville abscissa), clamped into the joint's limits; contact forces refitted.
fn bent(problem: &mut Transcription, x0: &[f64], a: &[f64], scale: f64) -> Result<Vec<f64>> {
    let layout = problem.layout.clone();
    let (nv, n) = (layout.nv, layout.n_ctrl);
    let (mut ctrl, mut lambda) = (vec![0.0; n * nv], vec![0.0; n * layout.n_lambda]);
    layout.unpack(x0, &problem.fixed_values, &mut ctrl, &mut lambda);
    for (i, ai) in a.iter().enumerate() {
        let limits = &problem.spec.model.joints[i + 1].limits;
        for j in (0..n).filter(|&j| layout.joint_var(j, i).is_some()) {
            let t = j as f64 / (n - 1) as f64;
            let c = &mut ctrl[j * nv + i];
            *c = (*c + scale * ai * (std::f64::consts::PI * t).sin()).clamp(limits.lower, limits.upper);
        }
    }
    let mut x = layout.pack(&ctrl, &lambda);
    initial_contact_forces(problem, &mut x)?;
    Ok(x)
}

/// The deepest penetration between solids at the nodes of `x`, `max(margin − distance)` over the
/// collision rows (m; 0 without any, or when every pair keeps its margin).
fn deepest_penetration(problem: &mut Transcription, x: &[f64]) -> Result<f64> {
    let per = problem.ineq_rows.len();
    if !problem.ineq_rows.iter().any(|r| matches!(r, IneqRow::Collision(_))) {
        return Ok(0.0);
    }
    let mut eval = Evaluation::values_only(problem.dims());
    problem.evaluate(x, false, &mut eval).map_err(|e| Error::task(&problem.spec.origin, "initial guess", e))?;
    let node_rows = problem.nodes.t.len() * per;
    let depth = (0..node_rows.min(eval.g.len()))
        .filter(|&k| matches!(problem.ineq_rows[k % per], IneqRow::Collision(_)))
        .map(|k| eval.g[k])
        .fold(0.0, f64::max);
    Ok(depth)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::guess::initial_x;

    /// The weight lift's bar passes close to the thighs: of its first eight bends at full size, some drive
    /// the palms into them deeper than the guess does; the starts made of them never do.
    #[test]
    fn a_start_does_not_push_solids_into_each_other_deeper_than_the_guess() {
        let task = crate::plan::examples::load("weight_lift_earth");
        let mut problem = Transcription::new(&task.spec).unwrap();
        let x0 = initial_x(&task.spec, &mut problem).unwrap();
        let guess_depth = deepest_penetration(&mut problem, &x0).unwrap();
        let mut deeper_at_full_size = 0;
        for k in 1..8u64 {
            let seed = super::super::start_seed(1, k as usize);
            let a = bend(&task.spec, &problem, &x0, seed);
            let full = bent(&mut problem, &x0, &a, 1.0).unwrap();
            if deepest_penetration(&mut problem, &full).unwrap() > guess_depth + PENETRATION_SLACK {
                deeper_at_full_size += 1;
            }
            let start = perturbed(&task.spec, &mut problem, &x0, seed).unwrap();
            let depth = deepest_penetration(&mut problem, &start).unwrap();
            assert!(depth <= guess_depth + PENETRATION_SLACK, "start {k}: {depth} m deep, the guess {guess_depth} m");
        }
        assert!(deeper_at_full_size > 0, "no bend reaches into the thighs: the test shows nothing");
    }
}
