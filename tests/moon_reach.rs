//! `examples/moon_overhead_reach.toml` (37 DOF, ours): a physical claim of its own, against its opposite
//! condition. Under the Moon's gravity (1.62 m/s², a sixth of Earth's) the arms' weight is small, so the
//! shoulders' torque is mostly what raises and stops the arms; the same reach planned under Earth's gravity
//! must hold six times the weight overhead and needs more than twice the shoulder torque. (Were the reach's
//! torque inertial, the two would be alike.)

use mintorque::plan::{self, task::Task};
use std::path::Path;

/// Peak |τ| (N·m) of the two shoulders' flexion (`*_shoulder_y`) in the example planned under `gravity`.
fn peak_shoulder_torque(gravity: &str) -> f64 {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/moon_overhead_reach.toml");
    let text = std::fs::read_to_string(&path).unwrap().replace("gravity = \"moon\"", &format!("gravity = \"{gravity}\""));
    let mut task = Task::parse(&text, &path).unwrap_or_else(|e| panic!("{e}"));
    let planned = task.plan(&mut |_| {}).unwrap_or_else(|e| panic!("{gravity}: {e}"));
    assert!(planned.converged(), "{gravity}: {}", planned.outcome.reason);
    let spec = &task.spec;
    let times: Vec<f64> = (0..=200).map(|k| spec.duration * k as f64 / 200.0).collect();
    let samples = plan::sample(spec, &planned, &times).unwrap();
    let shoulders = ["l_shoulder_y", "r_shoulder_y"].map(|j| spec.model.dof_index(j).unwrap());
    samples.iter().flat_map(|s| shoulders.map(|i| s.tau[i].abs())).fold(0.0, f64::max)
}

#[test]
fn the_reach_on_earth_needs_more_than_twice_the_moons_shoulder_torque() {
    let (moon, earth) = (peak_shoulder_torque("moon"), peak_shoulder_torque("earth"));
    println!("overhead reach: peak shoulder flexion torque {moon:.2} N·m on the Moon, {earth:.2} N·m on Earth");
    assert!(moon > 1.0, "the Moon reach barely loads the shoulders: {moon} N·m");
    assert!(earth > 2.0 * moon, "Earth {earth} N·m is not clearly above the Moon's {moon} N·m");
}
