//! Criterion bench of the planner's exact second-order term `Σ wⱼ∇²cⱼ` (one evaluation over every node, as
//! the interior point refreshes it): the node Hessians from the engine's exact blocks
//! (`dynamics::rnea_velocity_hessian`, `dynamics::rnea_hessian`) against the same term with every
//! `q` and `q̇` column differenced (`Transcription::set_exact_node_blocks(false)`), in one run, on the peer
//! suite's human figures and three bundled examples with point forces (a payload, the hands on the floor, the
//! 3D stoop's box) at their initial guess with unit weights on every row.

use criterion::{criterion_group, criterion_main, Criterion};
use mintorque::plan::{initial_x, task::Task, Transcription};
use mintorque::solve::{Problem, SymmetricMatrix};
use std::hint::black_box;
use std::path::Path;

fn second_order(c: &mut Criterion) {
    let mut group = c.benchmark_group("second_order");
    group.sample_size(20);
    let tasks = [
        "bench/peer/tasks/h7_reach_earth",
        "bench/peer/tasks/h13_twist_reach_earth",
        "bench/peer/tasks/h21_two_arm_raise_earth",
        "bench/peer/tasks/h36_wave_step_earth",
        "examples/weight_lift_earth",
        "examples/push_up",
        "examples/lift_stoop_3d",
    ];
    for task_path in tasks {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("{task_path}.toml"));
        let name = task_path.rsplit('/').next().unwrap_or(task_path);
        let task = Task::load(&path).unwrap();
        let mut problem = Transcription::new(&task.spec).unwrap();
        let x = initial_x(&task.spec, &mut problem).unwrap();
        let dims = problem.dims();
        let weights = [vec![1.0; dims.n_res], vec![1.0; dims.n_eq], vec![1.0; dims.n_ineq]];
        let mut target = SymmetricMatrix::dense(dims.n);
        for (label, exact) in [("exact blocks", true), ("differences", false)] {
            problem.set_exact_node_blocks(exact);
            group.bench_function(format!("{name} ({} DOF), {label}", task.spec.model.nv()), |b| {
                b.iter(|| {
                    target.fill_zero();
                    let w = [&weights[0][..], &weights[1][..], &weights[2][..]];
                    black_box(problem.add_second_order(&x, w, &mut target))
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, second_order);
criterion_main!(benches);
