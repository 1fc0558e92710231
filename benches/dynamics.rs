//! Criterion benches of the dynamics engine on the models the reference library's timings were taken on:
//! UR5 (6 DOF) and a 36-DOF human tree. `mintorque dynamics MODEL --bench` measures the same calls.

use criterion::{criterion_group, criterion_main, Criterion};
use mintorque::dynamics::{aba::aba, bench::random_states, crba::crba, rnea::rnea, rnea_derivatives::rnea_derivatives, Data};
use mintorque::model::urdf;
use std::hint::black_box;
use std::path::Path;

fn dynamics(c: &mut Criterion) {
    for name in ["ur5", "human36"] {
        let model = urdf::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models").join(format!("{name}.urdf"))).unwrap();
        let states = random_states(&model, 64, 7);
        let g = model.gravity;
        let mut data = Data::new(&model);
        let mut group = c.benchmark_group(name);
        let mut k = 0;
        let mut next = || {
            k = (k + 1) % states.len();
            &states[k]
        };
        group.bench_function("inverse_dynamics", |b| {
            b.iter(|| {
                let s = next();
                black_box(rnea(&model, &mut data, &s[0], &s[1], &s[2], &g, None).len())
            })
        });
        group.bench_function("derivatives", |b| {
            b.iter(|| {
                let s = next();
                rnea_derivatives(&model, &mut data, &s[0], &s[1], &s[2], &g, None);
                black_box(data.dtau_dq[(0, 0)])
            })
        });
        group.bench_function("mass_matrix", |b| b.iter(|| black_box(crba(&model, &mut data, &next()[0]).len())));
        group.bench_function("forward_dynamics", |b| {
            b.iter(|| {
                let s = next();
                black_box(aba(&model, &mut data, &s[0], &s[1], &s[3], &g, None).len())
            })
        });
        group.finish();
    }
}

criterion_group!(benches, dynamics);
criterion_main!(benches);
