//! The objective's terms change the motion the way their names say — each against the minimum-torque plan
//! of the same task, measured on a dense sampling (not on the terms' own discretisation) — and the Newton
//! solver's exact second-order term agrees with the structured solver on them.

mod common;

use mintorque::plan::{self, task::Task, SolverKind};
use mintorque::report::summary::Summary;
use std::path::PathBuf;

fn path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/test-task.toml")
}

/// Dense measures of a plan: `∫τᵀτ`, `∫τ̇ᵀτ̇`, `∫q̈ᵀq̈`, `∫q⃛ᵀq⃛` and `∫Σ(τᵢ/limitᵢ)²`.
#[derive(Debug)]
struct Measures {
    torque: f64,
    torque_change: f64,
    acceleration: f64,
    jerk: f64,
    strength: f64,
    /// `∫Σ(qᵢ/ρᵢ)²`, `ρᵢ` the half range.
    posture: f64,
}

/// The double pendulum raised to horizontal (common::TASK) with `objective` and `limits` sections.
fn planned(objective: &str, limits: &str, solver: Option<SolverKind>) -> (Measures, f64, Task, plan::Plan) {
    let text = format!("{}\n[objective]\n{objective}\n[constraints]\n{limits}\n", common::TASK);
    let mut task = Task::parse(&text, &path()).unwrap();
    if let Some(s) = solver {
        task.solver = s;
    }
    task.multistart = mintorque::plan::MultiStart::single();
    let p = task.plan(&mut |_| {}).unwrap();
    assert!(p.converged(), "{objective}: {}", p.outcome.reason);
    let n = 3000;
    let dt = 1.5 / n as f64;
    let times: Vec<f64> = (0..=n).map(|k| k as f64 * dt).collect();
    let s = plan::sample(&task.spec, &p, &times).unwrap();
    let limit: Vec<f64> = task.spec.model.joints[1..].iter().map(|j| j.limits.effort).collect();
    let half_range: Vec<f64> = task.spec.model.joints[1..].iter().map(|j| 0.5 * (j.limits.upper - j.limits.lower)).collect();
    let sq = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>();
    let diff = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| (x - y) / dt).collect::<Vec<f64>>();
    let m = Measures {
        torque: s.iter().map(|x| sq(&x.tau) * dt).sum(),
        torque_change: s.windows(2).map(|w| sq(&diff(&w[1].tau, &w[0].tau)) * dt).sum(),
        acceleration: s.iter().map(|x| sq(&x.qdd) * dt).sum(),
        jerk: s.windows(2).map(|w| sq(&diff(&w[1].qdd, &w[0].qdd)) * dt).sum(),
        strength: s.iter().map(|x| x.tau.iter().zip(&limit).map(|(t, l)| (t / l).powi(2)).sum::<f64>() * dt).sum(),
        posture: s.iter().map(|x| x.q.iter().zip(&half_range).map(|(q, r)| (q / r).powi(2)).sum::<f64>() * dt).sum(),
    };
    (m, p.outcome.objective, task, p)
}

const LIMITS: &str = "torque_limit = { shoulder = 400.0, elbow = 40.0 }";

#[test]
fn minimum_torque_change_trades_torque_for_smoothness() {
    let (torque, _, _, _) = planned("", LIMITS, None);
    let (change, _, _, _) = planned("terms = { torque = 1.0, torque_change = 0.05 }", LIMITS, None);
    assert!(change.torque_change < 0.9 * torque.torque_change, "∫τ̇²: {change:?} against {torque:?}");
    assert!(change.torque > torque.torque, "∫τ²: {change:?} against {torque:?}");
}

#[test]
fn acceleration_and_jerk_regularisers_make_the_motion_smoother() {
    let (torque, _, _, _) = planned("", LIMITS, None);
    let (acc, _, _, _) = planned("terms = { torque = 1.0, acceleration = 200.0 }", LIMITS, None);
    assert!(acc.acceleration < 0.9 * torque.acceleration && acc.torque > torque.torque, "{acc:?} against {torque:?}");
    let (jerk, _, _, _) = planned("terms = { torque = 1.0, jerk = 5.0 }", LIMITS, None);
    assert!(jerk.jerk < 0.9 * torque.jerk && jerk.torque > torque.torque, "{jerk:?} against {torque:?}");
}

/// The posture term keeps the joints nearer the neutral posture (in units of their ranges) than the
/// minimum-torque plan does, for more torque; its value in summary terms is the discrete integral.
#[test]
fn the_posture_term_keeps_joints_nearer_neutral() {
    let (torque, _, _, _) = planned("", LIMITS, None);
    let (posture, _, _, _) = planned("terms = { torque = 1.0, posture = 50000.0 }", LIMITS, None);
    assert!(posture.posture < 0.95 * torque.posture, "∫Σ(q/ρ)²: {posture:?} against {torque:?}");
    assert!(posture.torque > torque.torque, "∫τ²: {posture:?} against {torque:?}");
}

#[test]
fn strength_normalised_effort_spares_the_weak_joint() {
    // The elbow is ten times weaker than the shoulder: normalised, its torque counts a hundred times more.
    let (torque, _, _, _) = planned("", LIMITS, None);
    let (strength, _, _, _) = planned("terms = { torque = 0.0, strength = 1.0 }", LIMITS, None);
    assert!(strength.strength < 0.9 * torque.strength, "{strength:?} against {torque:?}");
    assert!(strength.torque > torque.torque, "{strength:?} against {torque:?}");
}

#[test]
fn newton_and_structured_agree_on_every_term() {
    let terms = "terms = { torque = 1.0, strength = 2000.0, torque_change = 0.05, acceleration = 20.0, jerk = 0.5 }";
    let limits =
        "torque_limit = { shoulder = 400.0 }\ntorque_limit_positive = { elbow = 40.0 }\ntorque_limit_negative = { elbow = 25.0 }";
    let (_, structured, _, _) = planned(terms, limits, Some(SolverKind::Structured));
    let (_, newton, task, p) = planned(terms, limits, Some(SolverKind::Newton));
    assert!((newton - structured).abs() < 1e-4 * structured, "newton {newton}, structured {structured}");
    // The summary states each term and its value; the weighted values add up to the objective.
    let samples = plan::sample(&task.spec, &p, &[0.0, 0.75, 1.5]).unwrap();
    let summary = Summary::new(&task.spec, &p, &samples);
    let names: Vec<&str> = summary.objective_terms.iter().map(|t| t.name.as_str()).collect();
    assert_eq!(names, ["torque", "strength", "torque_change", "acceleration", "jerk"]);
    let total: f64 = summary.objective_terms.iter().map(|t| t.weight * t.value).sum();
    assert!((total - p.outcome.objective).abs() < 1e-9 * total, "{total} against {}", p.outcome.objective);
}

#[test]
fn bad_terms_name_the_field() {
    for (terms, field) in [
        ("terms = { torque = -1.0 }", "objective.terms.torque"),
        ("terms = { torque = 0.0 }", "objective.terms"),
        ("terms = { jerk = nan }", "objective.terms.jerk"),
        ("kind = \"torque_inverse_inertia\"\nterms = { strength = 1.0 }", "objective.terms.strength"),
        ("terms = { torque_chnage = 1.0 }", "torque_chnage"),
    ] {
        let text = format!("{}\n[objective]\n{terms}\n", common::TASK);
        let e = match Task::parse(&text, &path()) {
            Ok(mut t) => t.plan(&mut |_| {}).map(|_| ()).unwrap_err().to_string(),
            Err(e) => e.to_string(),
        };
        assert!(e.contains(field) && e.contains("test-task.toml"), "{terms}: {e}");
    }
}
