//! The engine's own stopwatch (`mintorque dynamics --bench`): median nanoseconds per call of each
//! algorithm over many random states. Criterion benches (`benches/dynamics.rs`) measure the same calls.

use super::{aba::aba, crba::crba, rnea::rnea, rnea_derivatives::rnea_derivatives, Data};
use crate::model::Model;
use crate::spatial::Vec3;
use serde::Serialize;
use std::hint::black_box;
use std::time::Instant;

/// Timings of the dynamics kernels on one model (`mintorque dynamics --bench`).
#[derive(Serialize, Debug, Clone)]
pub struct BenchResult {
    /// The model's name.
    pub model: String,
    /// Degrees of freedom.
    pub nv: usize,
    /// Median ns per call over `states` random states, each timed over a batch of calls.
    pub inverse_dynamics_ns: f64,
    /// Median ns per call of the RNEA derivatives `∂τ/∂q`, `∂τ/∂q̇`.
    pub derivatives_ns: f64,
    /// Median ns per call of the CRBA mass matrix `H(q)`.
    pub mass_matrix_ns: f64,
    /// Median ns per call of the ABA forward dynamics.
    pub forward_dynamics_ns: f64,
    /// Random states timed.
    pub states: usize,
}

/// Random states: q uniform within the limits (clipped to [−π, π]), q̇, q̈, τ in [−1, 1].
pub fn random_states(model: &Model, count: usize, seed: u64) -> Vec<[Vec<f64>; 4]> {
    let mut s = seed;
    let mut next = move || {
        // SplitMix64
        s = s.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = s;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    let nv = model.nv();
    (0..count)
        .map(|_| {
            let q = model.joints[1..]
                .iter()
                .map(|j| {
                    let (lo, hi) = (j.limits.lower.max(-std::f64::consts::PI), j.limits.upper.min(std::f64::consts::PI));
                    lo + (hi - lo) * next()
                })
                .collect();
            let mut sym = || (0..nv).map(|_| 2.0 * next() - 1.0).collect::<Vec<f64>>();
            [q, sym(), sym(), sym()]
        })
        .collect()
}

fn median_ns(states: &[[Vec<f64>; 4]], batch: usize, mut call: impl FnMut(&[Vec<f64>; 4])) -> f64 {
    let mut times: Vec<f64> = states
        .iter()
        .map(|s| {
            let t = Instant::now();
            for _ in 0..batch {
                call(black_box(s));
            }
            t.elapsed().as_nanos() as f64 / batch as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// Times the kernels on `states` random states of `model` under gravity `gravity` (m/s²).
pub fn bench(model: &Model, gravity: &Vec3, states: usize) -> BenchResult {
    let samples = random_states(model, states.max(1), 42);
    let mut data = Data::new(model);
    let batch = 200;
    // Warm up caches and the branch predictor.
    for s in &samples {
        rnea_derivatives(model, &mut data, &s[0], &s[1], &s[2], gravity, None);
    }
    let id = median_ns(&samples, batch, |s| {
        black_box(rnea(model, &mut data, &s[0], &s[1], &s[2], gravity, None));
    });
    let der = median_ns(&samples, batch, |s| {
        rnea_derivatives(model, &mut data, &s[0], &s[1], &s[2], gravity, None);
        black_box(&data.dtau_dq);
    });
    let h = median_ns(&samples, batch, |s| {
        black_box(crba(model, &mut data, &s[0]));
    });
    let fd = median_ns(&samples, batch, |s| {
        black_box(aba(model, &mut data, &s[0], &s[1], &s[3], gravity, None));
    });
    BenchResult {
        model: model.name.clone(),
        nv: model.nv(),
        inverse_dynamics_ns: id,
        derivatives_ns: der,
        mass_matrix_ns: h,
        forward_dynamics_ns: fd,
        states: samples.len(),
    }
}
