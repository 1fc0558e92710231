//! Criterion benches of whole plans from one start (N = 16 control points, 4 Gauss nodes per span, the task's
//! solver: the interior point unless the file names another): the paper's pendulum and double pendulum, the
//! 7-DOF sagittal arm lift and the 12-DOF two-arm reach on the tree-structured human.

use criterion::{criterion_group, criterion_main, Criterion};
use mintorque::plan::{self, task::Task};
use std::hint::black_box;
use std::path::Path;

fn plans(c: &mut Criterion) {
    let mut group = c.benchmark_group("plan");
    group.sample_size(10);
    for name in ["pendulum", "double_pendulum", "arm_lift_earth", "two_arm_reach"] {
        let task = Task::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(format!("{name}.toml"))).unwrap();
        group.bench_function(name, |b| {
            b.iter(|| {
                let p = plan::plan(&task.spec, task.solver, &task.settings, &mut |_| {}).unwrap();
                assert!(p.converged());
                black_box(p.outcome.objective)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, plans);
criterion_main!(benches);
