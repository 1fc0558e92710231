//! The transcription's derivative checks shared by the tests: every row's Jacobian against central
//! differences, and the second-order term against differences of the weighted gradient.

use super::Rng;
use mintorque::plan::{Spec, Transcription};
use mintorque::solve::{Evaluation, Problem};

/// Every row's Jacobian against central differences at a random `x` (entries in ±`spread`).
pub fn jacobians_match_differences(spec: &Spec, seed: u64, spread: f64) {
    let mut problem = Transcription::new(spec).unwrap();
    let dims = problem.dims();
    let patterns = problem.jacobian_patterns();
    let mut eval = Evaluation::new(dims, &patterns).unwrap();
    let mut rng = Rng(seed ^ 99);
    let x: Vec<f64> = rng.vec(dims.n, -1.0, 1.0).iter().map(|v| v * spread).collect();
    problem.evaluate(&x, true, &mut eval).unwrap();
    let analytic = eval.clone();
    whole_jacobians_are_written(&mut problem, &x, &analytic);
    let (mut plus, mut minus) = (eval.clone(), eval.clone());
    let h = 1e-6;
    let mut worst = 0.0f64;
    for col in 0..dims.n {
        let (mut xp, mut xm) = (x.clone(), x.clone());
        xp[col] += h;
        xm[col] -= h;
        problem.evaluate(&xp, false, &mut plus).unwrap();
        problem.evaluate(&xm, false, &mut minus).unwrap();
        for (name, jac, p, m) in [
            ("r", &analytic.jr, &plus.r, &minus.r),
            ("h", &analytic.jh, &plus.h, &minus.h),
            ("g", &analytic.jg, &plus.g, &minus.g),
        ] {
            for row in 0..p.len() {
                let fd = (p[row] - m[row]) / (2.0 * h);
                let an = jac.get(row, col);
                let err = (fd - an).abs() / (1.0 + fd.abs());
                worst = worst.max(err);
                assert!(
                    err < 1e-5,
                    "seed {seed}, {} joints: ∂{name}[{row}]/∂x[{col}] = {an} analytic, {fd} by differences ({})",
                    spec.model.nv(),
                    match name {
                        "h" => problem.constraint_name(mintorque::solve::ConstraintKind::Equality, row),
                        "g" => problem.constraint_name(mintorque::solve::ConstraintKind::Inequality, row),
                        _ => format!("residual {row}"),
                    }
                );
            }
        }
    }
    println!(
        "seed {seed}: {} unknowns, {} residuals, {} equalities, {} inequalities, worst relative error {worst:.2e}",
        dims.n, dims.n_res, dims.n_eq, dims.n_ineq
    );
}

/// The problem writes every Jacobian entry (the solver does not zero them before evaluating): evaluated
/// into Jacobians full of NaN, it gives `analytic`, evaluated at `x` into zeroed ones, bit for bit.
fn whole_jacobians_are_written(problem: &mut Transcription, x: &[f64], analytic: &Evaluation) {
    assert!(problem.writes_whole_jacobians());
    let mut stale = analytic.clone();
    for j in [&mut stale.jr, &mut stale.jh, &mut stale.jg] {
        j.values_mut().fill(f64::NAN);
    }
    problem.evaluate(x, true, &mut stale).unwrap();
    for (a, b) in [(&stale.jr, &analytic.jr), (&stale.jh, &analytic.jh), (&stale.jg, &analytic.jg)] {
        assert!(a.values().iter().zip(b.values()).all(|(u, v)| u.to_bits() == v.to_bits()));
    }
}

/// The second-order term against central differences of the weighted gradient, at a random `x` (entries
/// in ±`spread`) with random weights on every row.
pub fn second_order_matches_differences(spec: &Spec, seed: u64, spread: f64) {
    use mintorque::solve::SymmetricMatrix;
    let mut problem = Transcription::new(spec).unwrap();
    let dims = problem.dims();
    let mut eval = Evaluation::new(dims, &problem.jacobian_patterns()).unwrap();
    let mut rng = Rng(seed ^ 31);
    let x: Vec<f64> = rng.vec(dims.n, -spread, spread);
    let weights = [rng.vec(dims.n_res, -2.0, 2.0), rng.vec(dims.n_eq, -2.0, 2.0), rng.vec(dims.n_ineq, 0.0, 2.0)];
    let mut weighted_gradient = |x: &[f64]| {
        problem.evaluate(x, true, &mut eval).unwrap();
        let mut g = vec![0.0; dims.n];
        eval.jr.tr_mul_vec(&weights[0], &mut g);
        eval.jh.tr_mul_vec_add(1.0, &weights[1], &mut g);
        eval.jg.tr_mul_vec_add(1.0, &weights[2], &mut g);
        g
    };
    let fd = super::central_differences(&x, 1e-5, &mut weighted_gradient);
    let mut target = SymmetricMatrix::dense(dims.n);
    let w = [&weights[0][..], &weights[1][..], &weights[2][..]];
    assert!(problem.add_second_order(&x, w, &mut target), "the transcription provides the term");
    let term = target.to_dense();
    let scale = fd.amax().max(1.0);
    let mut worst = 0.0f64;
    for row in 0..dims.n {
        for col in 0..=row {
            let err = (term[(row, col)] - fd[(row, col)]).abs() / scale;
            worst = worst.max(err);
            assert!(
                err < 1e-5,
                "seed {seed}, {} joints: S[{row}][{col}] = {} exact, {} by differences",
                spec.model.nv(),
                term[(row, col)],
                fd[(row, col)]
            );
        }
    }
    // The band of JᵀJ holds the term (what the banded solver needs).
    let bandwidth = [&eval.jr, &eval.jh, &eval.jg].iter().map(|j| j.gram_bandwidth()).max().unwrap();
    let mut banded = SymmetricMatrix::banded(dims.n, bandwidth);
    assert!(problem.add_second_order(&x, w, &mut banded));
    assert!((banded.to_dense() - term).amax() < 1e-12 * scale);
    println!("seed {seed}: {} unknowns, worst relative error {worst:.2e} (scale {scale:.2e})", dims.n);
}
