//! The paper's space arm lift floating free (`examples/arm_lift_space_free.toml`, after issue 11) against
//! its feet-held twin (`arm_lift_space.toml`) — the same task at the same N, nothing but the root changed.

mod common;

use common::momentum::{body_of_joint, part_and_rest};
use mintorque::plan::{self, task::Task, Plan};
use std::path::Path;

/// The example `name` planned at `n` control points: the plan, the task (for its spec) and samples at 81 times.
fn planned(name: &str, n: usize) -> (Plan, Task, Vec<plan::NodeValues>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(format!("{name}.toml"));
    let text = std::fs::read_to_string(&path).unwrap();
    let at_n = |l: &str| if l.starts_with("control_points") { format!("control_points = {n}") } else { l.to_string() };
    let text: Vec<String> = text.lines().map(at_n).collect();
    let mut task = Task::parse(&text.join("\n"), &path).unwrap();
    let plan = task.plan(&mut |_| {}).unwrap();
    assert!(plan.outcome.converged, "{name}: {:?}", plan.outcome.reason);
    let times: Vec<f64> = (0..=80).map(|k| task.spec.duration * k as f64 / 80.0).collect();
    let samples = plan::sample(&task.spec, &plan, &times).unwrap();
    (plan, task, samples)
}

/// Floating free, the arms' swing is angular momentum the rest of the body takes, opposite, so the whole
/// body's stays zero and its centre of mass stays put; held by the feet, the support takes it and the
/// centre of mass follows the arms. With nothing to hold, the free body also needs less effort.
#[test]
fn arm_lift_in_space_floating_free_conserves_momentum_and_costs_less_than_held_by_the_feet() {
    let (free, free_task, free_samples) = planned("arm_lift_space_free", 24);
    let (held, held_task, held_samples) = planned("arm_lift_space", 24);
    let arms = |task: &Task| body_of_joint(&task.spec.model, "shoulder");
    let f = part_and_rest(&free_task.spec.model, &free_samples, arms(&free_task));
    let h = part_and_rest(&held_task.spec.model, &held_samples, arms(&held_task));
    let (ef, eh) = (free.outcome.objective, held.outcome.objective);
    println!(
        "free: effort {ef:.3}, arms' |L| ≤ {:.3}, whole ≤ {:.4} N·m·s, CoM moves {:.2} mm",
        f.worst_part,
        f.worst_total,
        f.com_drift * 1e3
    );
    println!(
        "held: effort {eh:.3}, arms' |L| ≤ {:.3}, whole ≤ {:.4} N·m·s, CoM moves {:.2} mm",
        h.worst_part,
        h.worst_total,
        h.com_drift * 1e3
    );
    assert!(f.worst_part > 1.0, "the arms barely move: {} N·m·s", f.worst_part);
    assert!(f.worst_total < 0.05 * f.worst_part, "momentum not conserved: {} of the arms' {}", f.worst_total, f.worst_part);
    assert!(f.opposite, "the rest of the body does not turn against the arms");
    assert!(h.worst_total > 0.5 * h.worst_part, "held, the whole body's momentum {} stays small", h.worst_total);
    assert!(f.com_drift < 0.05 * h.com_drift, "centre of mass: free moves {} m, held {} m", f.com_drift, h.com_drift);
    assert!(ef < 0.95 * eh, "floating free costs {ef}, held {eh}");
}

/// The samples of a free body are its own motion: inverse dynamics of a sample's `q, q̇, q̈` gives the root
/// no force and the joints the plan's torques (plus the passive ones) — so the joint loads and L5/S1
/// figures computed from the samples are those of the body the torques move.
#[test]
fn a_free_bodys_samples_need_no_root_force_and_give_the_plans_torques() {
    use mintorque::dynamics::{rnea::rnea, Data};
    let (_, task, samples) = planned("arm_lift_space_free", 24);
    let m = &task.spec.model;
    let mut data = Data::new(m);
    let (mut root, mut joints, mut peak) = (0.0f64, 0.0f64, 0.0f64);
    for s in &samples {
        rnea(m, &mut data, &s.q, &s.qd, &s.qdd, &task.spec.gravity, None);
        for i in 0..m.nv() {
            let tau = data.tau[i] - m.joints[i + 1].passive.torque(s.q[i], s.qd[i]);
            if m.is_unactuated(i) {
                root = root.max(tau.abs());
            } else {
                joints = joints.max((tau - s.tau[i]).abs());
                peak = peak.max(s.tau[i].abs());
            }
        }
    }
    println!("root force ≤ {root:.2e} N (N·m), joint torques off by ≤ {joints:.2e} of a peak {peak:.2} N·m");
    assert!(root < 1e-8 * peak && joints < 1e-8 * peak, "root {root}, joints {joints}, peak {peak}");
}
