//! How solve time grows with the number of control points N and with the number of joints, printed as
//! Markdown tables (`cargo bench --bench scaling`; the figures in docs/performance.md come from here).
//! Each case is solved 3 times from one start; the median wall time is reported. The interior point is the
//! default solver; the structured solver and the paper's AL + BFGS beside it.

use mintorque::model::{Body, Joint, JointKind, JointLimits, Model, Passive};
use mintorque::plan::{self, task::Task, SolverKind, Spec};
use mintorque::solve::Settings;
use mintorque::spatial::{Inertia, Mat3, Transform, Vec3};
use std::path::Path;
use std::time::Instant;

fn median_seconds(spec: &Spec, solver: SolverKind, settings: &Settings) -> (f64, usize, bool) {
    let mut runs: Vec<(f64, usize, bool)> = (0..3)
        .map(|_| {
            let t = Instant::now();
            let p = plan::plan(spec, solver, settings, &mut |_| {}).unwrap();
            (t.elapsed().as_secs_f64(), p.outcome.iterations, p.converged())
        })
        .collect();
    runs.sort_by(|a, b| a.0.total_cmp(&b.0));
    runs[1]
}

/// An n-link planar chain of 1 kg, 0.3 m rods hanging from a pivot.
fn chain(n: usize) -> Model {
    let mut m = Model::new(format!("chain{n}"), "base");
    for i in 1..=n {
        let placement = Transform::from_translation(Vec3::new(0.0, 0.0, if i == 1 { 0.0 } else { -0.3 }));
        let inertia = Inertia::new(1.0, Vec3::new(0.0, 0.0, -0.15), Mat3::from_diagonal(&Vec3::new(0.0075, 0.0075, 0.0001)));
        let joint = Joint {
            name: format!("j{i}"),
            kind: JointKind::Revolute,
            parent: i - 1,
            placement,
            axis: Vec3::y(),
            limits: JointLimits::default(),
            passive: Passive::default(),
            group: None,
        };
        m.add_body(joint, Body { name: format!("link{i}"), inertia, shapes: vec![] });
    }
    m
}

fn main() {
    let settings = Settings::default();
    let arm = Task::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/arm_lift_earth.toml")).unwrap();
    println!("Solve time against control points N (7-DOF arm lift, Earth, 4 nodes per span):\n");
    println!("| N | unknowns | interior-point (s) | iterations | structured (s) | iterations | auglag-bfgs (s) | iterations |");
    println!("|---|---|---|---|---|---|---|---|");
    let mark = |c: bool| if c { "" } else { " (not converged)" };
    for n in [8, 16, 32, 64] {
        let mut spec = arm.spec.clone();
        spec.n_ctrl = n;
        let (p, ip, cp) = median_seconds(&spec, SolverKind::InteriorPoint, &settings);
        let (a, ia, ca) = median_seconds(&spec, SolverKind::Structured, &settings);
        let (b, ib, cb) = median_seconds(&spec, SolverKind::AuglagBfgs, &settings);
        println!("| {n} | {} | {p:.3}{} | {ip} | {a:.3}{} | {ia} | {b:.3}{} | {ib} |", (n - 4) * 7, mark(cp), mark(ca), mark(cb));
    }
    println!("\nSolve time against joints (n-link chain raised from hanging to a bent pose in 1.5 s, N = 16):\n");
    println!("| joints | unknowns | interior-point (s) | iterations | structured (s) | iterations |");
    println!("|---|---|---|---|---|---|");
    for n in [2, 4, 8, 16, 32] {
        let model = chain(n);
        let goal: Vec<f64> = (0..n).map(|i| if i == 0 { 1.2 } else { 0.3 / n as f64 * 4.0 }).collect();
        let spec = Spec::new(model, vec![0.0; n], goal, 1.5);
        let (p, ip, cp) = median_seconds(&spec, SolverKind::InteriorPoint, &settings);
        let (a, ia, ca) = median_seconds(&spec, SolverKind::Structured, &settings);
        println!("| {n} | {} | {p:.3}{} | {ip} | {a:.3}{} | {ia} |", 12 * n, mark(cp), mark(ca));
    }
}
