//! The planner on the paper's validation cases (section 7.1, 7.2.1) and its solvers against each other.

use mintorque::dynamics::{aba::aba, Data};
use mintorque::model::urdf;
use mintorque::plan::{self, SolverKind, Spec};
use mintorque::solve::Settings;
use mintorque::Model;
use std::path::Path;

fn model(name: &str) -> Model {
    urdf::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models").join(name)).unwrap()
}

/// Torque-free motion from rest at `q0` by RK4 with small steps, sampled at `times`.
fn free_swing(model: &Model, q0: &[f64], times: &[f64]) -> Vec<Vec<f64>> {
    let n = model.nv();
    let mut data = Data::new(model);
    let zero = vec![0.0; n];
    let g = model.gravity;
    let mut f = |q: &[f64], v: &[f64]| aba(model, &mut data, q, v, &zero, &g, None).as_slice().to_vec();
    let (mut q, mut v) = (q0.to_vec(), vec![0.0; n]);
    let dt: f64 = 1e-5;
    let mut t = 0.0;
    let mut out = Vec::new();
    for &target in times {
        while t < target - 1e-12 {
            let h = dt.min(target - t);
            let add = |a: &[f64], b: &[f64], s: f64| a.iter().zip(b).map(|(x, y)| x + s * y).collect::<Vec<f64>>();
            let a1 = f(&q, &v);
            let (q2, v2) = (add(&q, &v, h / 2.0), add(&v, &a1, h / 2.0));
            let a2 = f(&q2, &v2);
            let (q3, v3) = (add(&q, &v2, h / 2.0), add(&v, &a2, h / 2.0));
            let a3 = f(&q3, &v3);
            let (q4, v4) = (add(&q, &v3, h), add(&v, &a3, h));
            let a4 = f(&q4, &v4);
            for i in 0..n {
                q[i] += h / 6.0 * (v[i] + 2.0 * v2[i] + 2.0 * v3[i] + v4[i]);
                v[i] += h / 6.0 * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i]);
            }
            t += h;
        }
        out.push(q.clone());
    }
    out
}

/// Paper section 7.1: a compound pendulum released from rest at −70° swings to +70° in half a period
/// (0.6052 s). Planning that motion must find the free swing itself: zero torque, and the motion of a
/// forward simulation.
#[test]
fn pendulum_optimum_is_the_free_swing() {
    let m = model("pendulum.urdf");
    let (q0, q1, half_period) = (-70f64.to_radians(), 70f64.to_radians(), 0.6052);
    // The task is consistent: the free swing does reach +70° at 0.6052 s.
    let end = free_swing(&m, &[q0], &[half_period])[0][0];
    assert!((end - q1).abs().to_degrees() < 0.05, "free swing ends at {:.3}°", end.to_degrees());
    let mut spec = Spec::new(m.clone(), vec![q0], vec![q1], half_period);
    spec.n_ctrl = 16;
    for solver in [SolverKind::Structured, SolverKind::Newton, SolverKind::InteriorPoint, SolverKind::AuglagBfgs] {
        let planned = plan::plan(&spec, solver, &Settings::default(), &mut |_| {}).unwrap();
        assert!(planned.converged(), "{solver:?}: {}", planned.outcome.reason);
        let times: Vec<f64> = (0..=200).map(|k| half_period * k as f64 / 200.0).collect();
        let samples = plan::sample(&spec, &planned, &times).unwrap();
        let sim = free_swing(&m, &[q0], &times);
        let worst_angle = samples.iter().zip(&sim).map(|(s, q)| (s.q[0] - q[0]).abs()).fold(0.0, f64::max).to_degrees();
        // The gravity torque reaches m g l sin 70° ≈ 16 N·m; "≈ 0" means well under 1 % of it.
        let peak_torque = samples.iter().map(|s| s.tau[0].abs()).fold(0.0, f64::max);
        println!(
            "{solver:?}: worst angle error {worst_angle:.4}°, peak torque {peak_torque:.4} N·m, effort {:.3e} (guess {:.3e})",
            planned.outcome.objective, planned.initial_objective
        );
        assert!(worst_angle < 0.1, "{solver:?}: planned motion is {worst_angle:.3}° from the free swing");
        assert!(peak_torque < 0.16, "{solver:?}: peak torque {peak_torque} N·m is not ≈ 0");
        assert!(planned.outcome.objective < 1e-3 * planned.initial_objective);
    }
}

/// Paper section 7.2.1: a double pendulum raising its upper link from hanging to horizontal folds its
/// elbow on the way, and spends far less effort than the straight-arm (kinematically interpolated) motion.
#[test]
fn double_pendulum_folds_and_saves_effort() {
    let m = model("double_pendulum.urdf");
    let spec = Spec::new(m, vec![0.0, 0.0], vec![90f64.to_radians(), 0.0], 1.5);
    let planned = plan::plan(&spec, SolverKind::Structured, &Settings::default(), &mut |_| {}).unwrap();
    assert!(planned.converged(), "{}", planned.outcome.reason);
    let times: Vec<f64> = (0..=100).map(|k| 1.5 * k as f64 / 100.0).collect();
    let samples = plan::sample(&spec, &planned, &times).unwrap();
    let fold = samples.iter().map(|s| s.q[1].abs()).fold(0.0, f64::max).to_degrees();
    println!(
        "elbow folds up to {fold:.1}°, effort {:.3e} vs straight arm {:.3e}",
        planned.outcome.objective, planned.initial_objective
    );
    assert!(fold > 20.0, "the elbow folds only {fold:.1}°");
    assert!(planned.outcome.objective < 0.5 * planned.initial_objective);
}

/// Both solvers reach the same optimum on the same problem from the same start — here problems with one
/// optimum (a fast pendulum swing whose torque limit binds, a small double-pendulum raise); on strongly
/// non-convex tasks each may find a different local optimum, as any local method would.
#[test]
fn solvers_agree() {
    let pendulum = model("pendulum.urdf");
    let mut fast = Spec::new(pendulum, vec![-70f64.to_radians()], vec![70f64.to_radians()], 0.45);
    fast.n_ctrl = 10;
    fast.torque_limits = true;
    fast.model.joints[1].limits.effort = 12.0;
    let mut raise = Spec::new(model("double_pendulum.urdf"), vec![0.0, 0.0], vec![45f64.to_radians(), 30f64.to_radians()], 1.5);
    raise.n_ctrl = 8;
    for (name, spec) in [("fast pendulum", &fast), ("double pendulum raise", &raise)] {
        let a = plan::plan(spec, SolverKind::Structured, &Settings::default(), &mut |_| {}).unwrap();
        for other in [SolverKind::Newton, SolverKind::AuglagBfgs] {
            let b = plan::plan(spec, other, &Settings::default(), &mut |_| {}).unwrap();
            assert!(a.converged() && b.converged(), "{name}: {} / {other:?} {}", a.outcome.reason, b.outcome.reason);
            let rel = (a.outcome.objective - b.outcome.objective).abs() / a.outcome.objective;
            let dx = a.ctrl.iter().zip(&b.ctrl).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
            println!(
                "{name}, {other:?}: objectives {} and {}, control points within {dx:.2e} rad, {} and {} iterations",
                a.outcome.objective, b.outcome.objective, a.outcome.iterations, b.outcome.iterations
            );
            assert!(rel < 1e-6, "{name}, {other:?}: objectives differ: {} vs {}", a.outcome.objective, b.outcome.objective);
            assert!(dx < 1e-4, "{name}, {other:?}: control points differ by {dx} rad");
        }
    }
    // The torque limit binds in the fast swing, so the constraint machinery is exercised.
    let a = plan::plan(&fast, SolverKind::Structured, &Settings::default(), &mut |_| {}).unwrap();
    let peak = plan::sample(&fast, &a, &(0..=90).map(|k| 0.45 * k as f64 / 90.0).collect::<Vec<_>>())
        .unwrap()
        .iter()
        .map(|s| s.tau[0].abs())
        .fold(0.0, f64::max);
    assert!(peak > 11.9 && peak < 12.0 + 0.1, "peak torque {peak} N·m: the 12 N·m limit should bind");
}

/// `simulate` integrates the planned torques: the pendulum's plan (torque ≈ 0) is its own free swing.
#[test]
fn simulating_a_plan_reproduces_it() {
    let m = model("pendulum.urdf");
    let spec = Spec::new(m, vec![-70f64.to_radians()], vec![70f64.to_radians()], 0.6052);
    let planned = plan::plan(&spec, SolverKind::Structured, &Settings::default(), &mut |_| {}).unwrap();
    let sim = plan::simulate::simulate(&spec, &planned, 2000).unwrap();
    println!("pendulum drift {:.4}°", sim.worst_drift.to_degrees());
    assert!(sim.worst_drift.to_degrees() < 0.1, "drift {:.4}°", sim.worst_drift.to_degrees());
    // A double pendulum is chaotic-ish, but over 1.5 s a converged plan stays close.
    let m = model("double_pendulum.urdf");
    let spec = Spec::new(m, vec![0.0, 0.0], vec![90f64.to_radians(), 0.0], 1.5);
    let planned = plan::plan(&spec, SolverKind::Structured, &Settings::default(), &mut |_| {}).unwrap();
    let sim = plan::simulate::simulate(&spec, &planned, 3000).unwrap();
    println!("double pendulum drift {:.4}°", sim.worst_drift.to_degrees());
    assert!(sim.worst_drift.to_degrees() < 1.0, "drift {:.4}°", sim.worst_drift.to_degrees());
}

/// The pendulum's free swing is also the optimum of ½∫τᵀH⁻¹τ dt (eq. 12 as stated): τ ≈ 0 either way.
#[test]
fn pendulum_free_swing_under_the_inverse_inertia_objective() {
    let mut spec = Spec::new(model("pendulum.urdf"), vec![-70f64.to_radians()], vec![70f64.to_radians()], 0.6052);
    spec.objective = mintorque::plan::Objective::TorqueInverseInertia;
    // Newton here runs on the partitioned secant term with its coloured refresh (the node-wise exact term
    // is for ½∫τᵀWτ).
    for solver in [SolverKind::Structured, SolverKind::Newton, SolverKind::AuglagBfgs] {
        let planned = plan::plan(&spec, solver, &Settings::default(), &mut |_| {}).unwrap();
        assert!(planned.converged(), "{solver:?}: {}", planned.outcome.reason);
        let times: Vec<f64> = (0..=100).map(|k| 0.6052 * k as f64 / 100.0).collect();
        let peak = plan::sample(&spec, &planned, &times).unwrap().iter().map(|s| s.tau[0].abs()).fold(0.0, f64::max);
        assert!(peak < 0.16, "{solver:?}: peak torque {peak}");
    }
}
