//! The structured solver's two linear-algebra kernels at the 36-DOF whole body's shape (n = 432 unknowns,
//! half-bandwidth 143; `cargo bench --bench linalg`): the Gauss–Newton matrix `JᵀJ` of rows that share
//! their columns four by four, as a knot span's torque rows do, and the banded Cholesky factorisation.

use criterion::{criterion_group, criterion_main, Criterion};
use mintorque::solve::{Cholesky, SparseMatrix, SymmetricMatrix};
use std::hint::black_box;

const N: usize = 432;
const NV: usize = 36;
const B: usize = 4 * NV - 1;

/// Rows over four consecutive control points of `NV` joints, each on a subset of the joints (a torque
/// row's chain), four rows per pattern; deterministic values.
fn jacobian() -> SparseMatrix {
    let mut rows = Vec::new();
    for span in 0..N / NV - 3 {
        for joint in 0..NV {
            let dofs: Vec<usize> = (0..NV).filter(|d| (d + joint) % 3 != 0 || *d == joint).collect();
            let cols: Vec<usize> = (0..4).flat_map(|p| dofs.iter().map(move |d| (span + p) * NV + d)).collect();
            rows.extend(std::iter::repeat_n(cols, 4));
        }
    }
    let mut j = SparseMatrix::from_rows(N, &rows).expect("pattern");
    for i in 0..j.nrows() {
        for (k, v) in j.row_values_mut(i).iter_mut().enumerate() {
            *v = ((i * 31 + k * 17) % 97) as f64 / 97.0 - 0.5;
        }
    }
    j
}

fn kernels(c: &mut Criterion) {
    let j = jacobian();
    let mut gram = SymmetricMatrix::banded(N, B);
    c.bench_function("gram JᵀJ n=432 b=143", |bench| {
        bench.iter(|| {
            gram.fill_zero();
            j.add_gram_to(None, black_box(&mut gram)).expect("band");
        })
    });
    gram.fill_zero();
    j.add_gram_to(None, &mut gram).expect("band");
    let shift = vec![1.0; N];
    let mut chol = Cholesky::for_matrix(&gram);
    c.bench_function("banded Cholesky n=432 b=143", |bench| {
        bench.iter(|| chol.factor(black_box(&gram), Some(&shift)).expect("positive definite"))
    });
}

criterion_group!(benches, kernels);
criterion_main!(benches);
