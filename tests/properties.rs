//! Invariants of the dynamics on random trees (1–40 joints, random axes, placements and inertias):
//! analytical derivatives against central finite differences, H symmetric positive definite,
//! forward(inverse(q̈)) = q̈, and energy conserved in a torque-free simulation.

#![allow(clippy::too_many_arguments)]

mod common;

use common::{central_differences, random_tree, Rng};
use mintorque::dynamics::{
    aba::aba,
    crba::crba,
    kinematics,
    point_force::{path_dofs, point_force_hessian, point_force_mixed},
    rnea::rnea,
    rnea_derivatives::rnea_derivatives,
    rnea_gradient::rnea_gradient,
    rnea_gradient_moved::{restore, rnea_gradient_moved, Moved, Subtrees},
    rnea_hessian::rnea_hessian,
    rnea_velocity_hessian::{rnea_velocity_hessian, VelocityHessianWork},
    Data,
};
use mintorque::spatial::{Force, Motion, Vec3};
use mintorque::Model;
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

const G: Vec3 = Vec3::new(0.3, -0.2, -9.81);

fn state(seed: u64, n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut rng = Rng(seed ^ 0xABCDEF);
    (rng.vec(n, -3.0, 3.0), rng.vec(n, -2.0, 2.0), rng.vec(n, -2.0, 2.0))
}

fn random_fext(model: &Model, seed: u64) -> Vec<Force> {
    let mut rng = Rng(seed ^ 0x5555);
    (0..model.bodies.len())
        .map(|_| {
            Force::new(
                Vec3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)),
                Vec3::new(rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0)),
            )
        })
        .collect()
}

/// Weights `ω` (n) and `u₀` of a contracted gradient `φ = ωᵀτ + u₀·W`, each entry in [−1, 1].
fn random_weights(seed: u64, n: usize) -> (Vec<f64>, Motion) {
    let mut rng = Rng(seed);
    let omega = rng.vec(n, -1.0, 1.0);
    let u = rng.vec(6, -1.0, 1.0);
    (omega, Motion::new(Vec3::new(u[0], u[1], u[2]), Vec3::new(u[3], u[4], u[5])))
}

/// Max |analytic − central difference| over a matrix, relative to the matrix's scale.
fn fd_error(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    fext: &[Force],
    analytic: &DMatrix<f64>,
    wrt: usize,
) -> f64 {
    let n = model.nv();
    let h = 1e-6;
    let mut fd = DMatrix::zeros(n, n);
    for k in 0..n {
        let mut plus = [q.to_vec(), v.to_vec(), a.to_vec()];
        let mut minus = plus.clone();
        plus[wrt][k] += h;
        minus[wrt][k] -= h;
        let tp = rnea(model, data, &plus[0], &plus[1], &plus[2], &G, Some(fext)).clone();
        let tm = rnea(model, data, &minus[0], &minus[1], &minus[2], &G, Some(fext)).clone();
        fd.set_column(k, &((tp - tm) / (2.0 * h)));
    }
    (analytic - &fd).abs().max() / analytic.abs().max().max(1.0)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn derivatives_match_finite_differences(seed in any::<u64>(), n in 1usize..=40) {
        let model = random_tree(seed, n);
        let mut data = Data::new(&model);
        let (q, v, a) = state(seed, n);
        let fext = random_fext(&model, seed);
        rnea_derivatives(&model, &mut data, &q, &v, &a, &G, Some(&fext));
        let (dq, dv, m) = (data.dtau_dq.clone(), data.dtau_dv.clone(), data.M.clone());
        let tau = data.tau.clone();
        let tau_rnea = rnea(&model, &mut data, &q, &v, &a, &G, Some(&fext)).clone();
        prop_assert!((tau - tau_rnea).amax() < 1e-9);
        let e_q = fd_error(&model, &mut data, &q, &v, &a, &fext, &dq, 0);
        let e_v = fd_error(&model, &mut data, &q, &v, &a, &fext, &dv, 1);
        let e_a = fd_error(&model, &mut data, &q, &v, &a, &fext, &m, 2);
        prop_assert!(e_q < 1e-6, "∂τ/∂q off by {e_q:e}");
        prop_assert!(e_v < 1e-6, "∂τ/∂q̇ off by {e_v:e}");
        prop_assert!(e_a < 1e-6, "∂τ/∂q̈ = H off by {e_a:e}");
    }

    /// A pass after one moved coordinate (the subtree recomputed, the ancestors updated by its change) gives
    /// the full pass's `∇φ`, `τ` and root wrench at the moved state, for every `q_j` and `q̇_j`; `restore`
    /// gives back the base data.
    #[test]
    fn a_moved_gradient_pass_is_the_full_pass(seed in any::<u64>(), n in 1usize..=40) {
        let model = random_tree(seed, n);
        let (q, v, a) = state(seed, n);
        let fext = random_fext(&model, seed);
        let (omega, u0) = random_weights(seed ^ 0x99, n);
        let subtrees = Subtrees::of(&model);
        let mut base = Data::new(&model);
        let mut grad = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        let [gq, gv, ga] = &mut grad;
        rnea_gradient(&model, &mut base, (&q, &v, &a), &G, Some(&fext), &omega, &u0, (gq, gv, ga));
        let (mut data, mut full) = (base.clone(), Data::new(&model));
        for j in 0..n {
            for moved in [Moved::Position, Moved::Velocity] {
                let (mut q1, mut v1) = (q.clone(), v.clone());
                if moved == Moved::Position { q1[j] += 0.3 } else { v1[j] -= 0.7 }
                let mut expect = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
                let [eq, ev, ea] = &mut expect;
                rnea_gradient(&model, &mut full, (&q1, &v1, &a), &G, Some(&fext), &omega, &u0, (eq, ev, ea));
                let mut got = grad.clone();
                let [oq, ov, oa] = &mut got;
                rnea_gradient_moved(&model, (&base, &mut data), (&q1, &v1, &a), Some(&fext), (&omega, &u0), (j, moved, &subtrees), (oq, ov, oa));
                let scale = expect.iter().flatten().fold(1.0f64, |m, e| m.max(e.abs()));
                for (g, e) in got.iter().flatten().zip(expect.iter().flatten()) {
                    prop_assert!((g - e).abs() <= 1e-12 * scale, "j {} {:?}: {} against {}", j, moved, g, e);
                }
                prop_assert!((&data.tau - &full.tau).amax() <= 1e-12 * scale);
                prop_assert!((data.root_wrench.to_vec6() - full.root_wrench.to_vec6()).amax() <= 1e-12 * scale.max(full.root_wrench.to_vec6().amax()));
                restore(&base, &mut data, (j, moved), &subtrees);
                prop_assert!(data.tau == base.tau && data.oMi == base.oMi && data.S == base.S && data.v == base.v && data.G == base.G && data.f == base.f);
            }
        }
    }

    /// The O(n) gradient of `φ = ωᵀτ + u₀·W` against central differences of `φ` itself (independent of the
    /// derivative recursions) and against `ωᵀ∂τ + u₀·∂W` from `rnea_derivatives`' matrices.
    #[test]
    fn contracted_gradient_matches_finite_differences(seed in any::<u64>(), n in 1usize..=40) {
        let model = random_tree(seed, n);
        let mut data = Data::new(&model);
        let (q, v, a) = state(seed, n);
        let fext = random_fext(&model, seed);
        let (omega, u0) = random_weights(seed ^ 0x77, n);
        let (mut g_q, mut g_v, mut g_a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        rnea_gradient(&model, &mut data, (&q, &v, &a), &G, Some(&fext), &omega, &u0, (&mut g_q, &mut g_v, &mut g_a));
        let tau = data.tau.clone();
        let phi = |data: &mut Data, z: &[Vec<f64>; 3]| {
            let t = rnea(&model, data, &z[0], &z[1], &z[2], &G, Some(&fext)).clone();
            omega.iter().zip(t.iter()).map(|(w, t)| w * t).sum::<f64>() + u0.dot(&data.root_wrench)
        };
        let h = 1e-6;
        let mut scale = 1.0f64;
        let mut worst = 0.0f64;
        for (wrt, g) in [&g_q, &g_v, &g_a].into_iter().enumerate() {
            for k in 0..n {
                let mut plus = [q.clone(), v.clone(), a.clone()];
                let mut minus = plus.clone();
                plus[wrt][k] += h;
                minus[wrt][k] -= h;
                let fd = (phi(&mut data, &plus) - phi(&mut data, &minus)) / (2.0 * h);
                worst = worst.max((g[k] - fd).abs());
                scale = scale.max(fd.abs());
            }
        }
        prop_assert!(worst / scale < 1e-6, "∇φ off its central differences by {:e}", worst / scale);
        rnea_derivatives(&model, &mut data, &q, &v, &a, &G, Some(&fext));
        prop_assert!((&tau - &data.tau).amax() < 1e-9 * tau.amax().max(1.0));
        let w = DVector::from_vec(omega.clone());
        let contracted = [
            data.dtau_dq.tr_mul(&w), data.dtau_dv.tr_mul(&w), data.M.tr_mul(&w),
        ];
        let wrench = [&data.dW_dq, &data.dW_dv, &data.dW_da];
        for (wrt, g) in [&g_q, &g_v, &g_a].into_iter().enumerate() {
            for k in 0..n {
                let exact = contracted[wrt][k] + u0.dot(&wrench[wrt][k]);
                prop_assert!((g[k] - exact).abs() <= 1e-10 * scale, "∂φ column {k} of block {wrt}: {} vs {exact}", g[k]);
            }
        }
    }

    /// The exact velocity block `∂²φ/∂q̇²` against central differences of the contracted gradient's `∂φ/∂q̇`
    /// (affine in `q̇`, so the differences are exact to rounding), with external forces on every body.
    #[test]
    fn velocity_hessian_matches_differences_of_the_gradient(seed in any::<u64>(), n in 1usize..=40) {
        let model = random_tree(seed, n);
        let mut data = Data::new(&model);
        let (q, v, a) = state(seed, n);
        let fext = random_fext(&model, seed);
        let (omega, u0) = random_weights(seed ^ 0x55, n);
        let g_v = |data: &mut Data, v: &[f64]| {
            let (mut g_q, mut g_v, mut g_a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            rnea_gradient(&model, data, (&q, v, &a), &G, Some(&fext), &omega, &u0, (&mut g_q, &mut g_v, &mut g_a));
            g_v
        };
        let fd = central_differences(&v, 1e-3, &mut |v| g_v(&mut data, v));
        let mut exact = vec![f64::NAN; n * n];
        kinematics::placements(&model, &mut data, &q);
        rnea_velocity_hessian(&model, &data, (&omega, &u0), &mut VelocityHessianWork::new(&model), &mut exact, n);
        let exact = DMatrix::from_row_slice(n, n, &exact);
        let scale = fd.amax().max(1.0);
        prop_assert!((&exact - &fd).amax() <= 1e-8 * scale, "off by {:e} (scale {scale:e})", (&exact - &fd).amax());
    }

    /// The whole `∇²φ` over `(q, q̇, q̈)` against central differences of the contracted gradient along every
    /// `q`, `q̇` and `q̈` (so the blocks it sets to zero must be zero, and the `q`–`q` block is symmetric), every
    /// entry written; its `q̇`–`q̇` block bit for bit [`rnea_velocity_hessian`]'s (free figures take that alone).
    #[test]
    fn whole_hessian_matches_differences_of_the_gradient(seed in any::<u64>(), n in 1usize..=40) {
        let model = random_tree(seed, n);
        let mut data = Data::new(&model);
        let (q, v, a) = state(seed, n);
        let (omega, u0) = random_weights(seed ^ 0x55, n);
        let z: Vec<f64> = [q.clone(), v.clone(), a.clone()].concat();
        let gradient = |data: &mut Data, z: &[f64]| {
            let (mut g_q, mut g_v, mut g_a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            let (q, v, a) = (&z[..n], &z[n..2 * n], &z[2 * n..]);
            rnea_gradient(&model, data, (q, v, a), &G, None, &omega, &u0, (&mut g_q, &mut g_v, &mut g_a));
            [g_q, g_v, g_a].concat()
        };
        let d = 3 * n;
        let fd = central_differences(&z, 1e-6, &mut |z| gradient(&mut data, z));
        gradient(&mut data, &z);
        let mut work = VelocityHessianWork::new(&model);
        let mut whole = vec![f64::NAN; d * d];
        rnea_hessian(&model, &data, (&omega, &u0), &mut work, &mut whole, d);
        let scale = fd.amax().max(1.0);
        for r in 0..d {
            for c in 0..d {
                let exact = whole[r * d + c];
                prop_assert!((exact - fd[(r, c)]).abs() <= 1e-6 * scale, "entry ({r}, {c}): {exact} against {} (scale {scale:e})", fd[(r, c)]);
            }
        }
        let mut velocity = vec![f64::NAN; n * n];
        rnea_velocity_hessian(&model, &data, (&omega, &u0), &mut work, &mut velocity, n);
        for r in n..2 * n {
            for c in n..2 * n {
                prop_assert!(whole[r * d + c] == velocity[(r - n) * n + c - n], "q̇ entry ({r}, {c}) differs from rnea_velocity_hessian's");
            }
        }
    }

    /// The Hessian along `q` of a fixed world force's weighted torques `φ_f = −Ψ_b·[p × f; f]` (and its
    /// mixed column along a force direction) against central second differences of `φ_f` itself.
    #[test]
    fn point_force_hessian_matches_differences(seed in any::<u64>(), n in 1usize..=30) {
        let model = random_tree(seed, n);
        let mut data = Data::new(&model);
        let (q, v, a) = state(seed, n);
        let (omega, u0) = random_weights(seed ^ 0x11, n);
        let mut rng = Rng(seed ^ 0x1234);
        let body = 1 + (rng.next_u64() as usize) % n;
        let local = Vec3::new(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3));
        let f = Vec3::new(rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0));
        let path = path_dofs(&model, body);
        let psi = |data: &Data| path.iter().fold(u0, |u, &i| u.add_scaled(&data.S[i + 1], omega[i]));
        // φ_f(q) and ∂φ_f/∂f = −(Ψ_v + Ψ_ω × p)
        let phi = |data: &mut Data, q: &[f64], force: &Vec3| {
            kinematics::placements(&model, data, q);
            let p = data.oMi[body].act_point(&local);
            let w = psi(data);
            -(force.dot(&w.v) + w.w.dot(&p.cross(force)))
        };
        let h = 1e-4;
        let mut fd = DMatrix::zeros(n, n);
        let mut fd_mixed = vec![0.0; n];
        for i in 0..n {
            for j in 0..n {
                let mut at = |di: f64, dj: f64| {
                    let mut x = q.clone();
                    x[i] += di;
                    x[j] += dj;
                    phi(&mut data, &x, &f)
                };
                fd[(i, j)] = (at(h, h) - at(h, -h) - at(-h, h) + at(-h, -h)) / (4.0 * h * h);
            }
            let (mut plus, mut minus) = (q.clone(), q.clone());
            plus[i] += h;
            minus[i] -= h;
            let e = f / f.norm();
            fd_mixed[i] = (phi(&mut data, &plus, &e) - phi(&mut data, &minus, &e)) / (2.0 * h);
        }
        let (mut g_q, mut g_v, mut g_a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        rnea_gradient(&model, &mut data, (&q, &v, &a), &G, None, &omega, &u0, (&mut g_q, &mut g_v, &mut g_a));
        let p = data.oMi[body].act_point(&local);
        let mut exact = vec![0.0; n * n];
        point_force_hessian(&data, &path, (&p, &f), &psi(&data), &mut exact, n);
        let mut mixed = vec![0.0; n];
        point_force_mixed(&data, &path, (&p, &(f / f.norm())), &psi(&data), &mut mixed);
        let scale = fd.amax().max(1.0);
        for i in 0..n {
            for j in 0..n {
                prop_assert!((exact[i * n + j] - fd[(i, j)]).abs() <= 1e-5 * scale, "[{i}][{j}]: {} against {}", exact[i * n + j], fd[(i, j)]);
            }
            prop_assert!((mixed[i] - fd_mixed[i]).abs() <= 1e-6 * scale, "mixed [{i}]: {} against {}", mixed[i], fd_mixed[i]);
        }
    }

    #[test]
    fn mass_matrix_is_symmetric_positive_definite(seed in any::<u64>(), n in 1usize..=40) {
        let model = random_tree(seed, n);
        let mut data = Data::new(&model);
        let (q, v, a) = state(seed, n);
        let h = crba(&model, &mut data, &q).clone();
        prop_assert!((&h - h.transpose()).amax() <= 1e-12 * h.amax());
        prop_assert!(h.clone().cholesky().is_some(), "H is not positive definite");
        rnea_derivatives(&model, &mut data, &q, &v, &a, &G, None);
        prop_assert!((&data.M - &h).amax() <= 1e-10 * h.amax());
    }

    #[test]
    fn forward_dynamics_inverts_inverse_dynamics(seed in any::<u64>(), n in 1usize..=40) {
        let model = random_tree(seed, n);
        let mut data = Data::new(&model);
        let (q, v, a) = state(seed, n);
        let fext = random_fext(&model, seed);
        let tau = rnea(&model, &mut data, &q, &v, &a, &G, Some(&fext)).clone();
        let ddq = aba(&model, &mut data, &q, &v, tau.as_slice(), &G, Some(&fext)).clone();
        let a = DVector::from_vec(a);
        // H is well conditioned here but not perfectly: compare relative to the size of q̈.
        prop_assert!((&ddq - &a).amax() <= 1e-7 * a.amax().max(1.0), "q̈ off by {:e}", (&ddq - &a).amax());
    }
}

/// Total energy of a torque-free motion under gravity stays constant (RK4, small steps).
#[test]
fn energy_is_conserved_without_torque() {
    for (seed, n) in [(1u64, 1usize), (2, 5), (3, 12), (4, 25), (5, 40)] {
        let model = random_tree(seed, n);
        let mut data = Data::new(&model);
        let mut rng = Rng(seed);
        let mut q = DVector::from_vec(rng.vec(n, -1.0, 1.0));
        let mut v = DVector::from_vec(rng.vec(n, -0.5, 0.5));
        let zero = vec![0.0; n];
        let energy = |data: &mut Data, q: &DVector<f64>, v: &DVector<f64>| {
            kinematics::placements(&model, data, q.as_slice());
            kinematics::velocities(&model, data, v.as_slice());
            kinematics::kinetic_energy(&model, data) + kinematics::potential_energy(&model, data, &G)
        };
        let e0 = energy(&mut data, &q, &v);
        let scale = e0.abs().max(kinematics::kinetic_energy(&model, &data)).max(1.0);
        let dt = 2e-4;
        let mut accel =
            |q: &DVector<f64>, v: &DVector<f64>| aba(&model, &mut data, q.as_slice(), v.as_slice(), &zero, &G, None).clone();
        for _ in 0..2500 {
            let k1v = accel(&q, &v);
            let k1q = v.clone();
            let k2v = accel(&(&q + &k1q * (dt / 2.0)), &(&v + &k1v * (dt / 2.0)));
            let k2q = &v + &k1v * (dt / 2.0);
            let k3v = accel(&(&q + &k2q * (dt / 2.0)), &(&v + &k2v * (dt / 2.0)));
            let k3q = &v + &k2v * (dt / 2.0);
            let k4v = accel(&(&q + &k3q * dt), &(&v + &k3v * dt));
            let k4q = &v + &k3v * dt;
            q += (k1q + k2q * 2.0 + k3q * 2.0 + k4q) * (dt / 6.0);
            v += (k1v + k2v * 2.0 + k3v * 2.0 + k4v) * (dt / 6.0);
        }
        let mut data = Data::new(&model);
        let e1 = energy(&mut data, &q, &v);
        assert!(((e1 - e0) / scale).abs() < 1e-6, "{n} joints: energy drifted from {e0} to {e1}");
    }
}

/// The root reaction wrench's derivatives against central differences.
#[test]
fn root_wrench_derivatives_match_finite_differences() {
    for (seed, n) in [(11u64, 1usize), (12, 7), (13, 20), (14, 40)] {
        let model = random_tree(seed, n);
        let mut data = Data::new(&model);
        let (q, v, a) = state(seed, n);
        let fext = random_fext(&model, seed);
        rnea_derivatives(&model, &mut data, &q, &v, &a, &G, Some(&fext));
        let analytic = [data.dW_dq.clone(), data.dW_dv.clone(), data.dW_da.clone()];
        let h = 1e-6;
        for (wrt, columns) in analytic.iter().enumerate() {
            for k in 0..n {
                let mut plus = [q.clone(), v.clone(), a.clone()];
                let mut minus = plus.clone();
                plus[wrt][k] += h;
                minus[wrt][k] -= h;
                rnea(&model, &mut data, &plus[0], &plus[1], &plus[2], &G, Some(&fext));
                let wp = data.root_wrench.to_vec6();
                rnea(&model, &mut data, &minus[0], &minus[1], &minus[2], &G, Some(&fext));
                let wm = data.root_wrench.to_vec6();
                let fd = (wp - wm) / (2.0 * h);
                let err = (fd - columns[k].to_vec6()).amax() / fd.amax().max(1.0);
                assert!(err < 1e-6, "{n} joints: root wrench derivative {wrt} column {k} off by {err:e}");
            }
        }
    }
}

/// Jᵀλ of a world-fixed force at a body point, and its q-derivative, against central differences.
#[test]
fn point_force_derivatives_match_finite_differences() {
    use mintorque::dynamics::point_force::{add_generalized_force, generalized_force_derivative, path_dofs, point_jacobian};
    for (seed, n) in [(21u64, 1usize), (22, 6), (23, 18), (24, 40)] {
        let model = random_tree(seed, n);
        let mut data = Data::new(&model);
        let (q, v, a) = state(seed, n);
        let body = n; // the last body: a leaf or deep in the tree
        let local = Vec3::new(0.1, -0.2, 0.3);
        let lambda = Vec3::new(3.0, -1.0, 7.0);
        let path = path_dofs(&model, body);
        let point = |data: &Data| data.oMi[body].act_point(&local);
        let gen_force = |data: &mut Data, q: &[f64]| {
            kinematics::placements(&model, data, q);
            let mut tau = vec![0.0; n];
            add_generalized_force(data, &path, &point(data), &lambda, &mut tau);
            tau
        };
        // Jᵀλ equals the RNEA difference with the same force given as an external force.
        kinematics::placements(&model, &mut data, &q);
        let p = point(&data);
        let f_local = data.oMi[body].act_inv_force(&Force::new(p.cross(&lambda), lambda));
        let mut fext = vec![Force::ZERO; model.bodies.len()];
        fext[body] = f_local;
        let t0 = rnea(&model, &mut data, &q, &v, &a, &G, None).clone();
        let t1 = rnea(&model, &mut data, &q, &v, &a, &G, Some(&fext)).clone();
        let jt = gen_force(&mut data, &q);
        for k in 0..n {
            assert!(((t0[k] - t1[k]) - jt[k]).abs() < 1e-9 * (1.0 + jt[k].abs()), "Jᵀλ differs from RNEA's f_ext");
        }
        // Derivatives.
        kinematics::placements(&model, &mut data, &q);
        let m = path.len();
        let mut d = vec![0.0; m * m];
        generalized_force_derivative(&data, &path, &point(&data), &lambda, &mut d);
        let mut jac = vec![Vec3::zeros(); m];
        point_jacobian(&data, &path, &point(&data), &mut jac);
        let h = 1e-6;
        for (c, &j) in path.iter().enumerate() {
            let (mut qp, mut qm) = (q.clone(), q.clone());
            qp[j] += h;
            qm[j] -= h;
            let (tp, tm) = (gen_force(&mut data, &qp), gen_force(&mut data, &qm));
            for (r, &k) in path.iter().enumerate() {
                let fd = (tp[k] - tm[k]) / (2.0 * h);
                assert!((fd - d[r * m + c]).abs() < 1e-6 * (1.0 + fd.abs()), "∂(Jᵀλ)[{k}]/∂q[{j}]: {} vs {fd}", d[r * m + c]);
            }
            kinematics::placements(&model, &mut data, &qp);
            let pp = point(&data);
            kinematics::placements(&model, &mut data, &qm);
            let pm = point(&data);
            assert!(((pp - pm) / (2.0 * h) - jac[c]).amax() < 1e-6, "point Jacobian column {c}");
        }
    }
}

/// URDF export → import and figure-file export → import give the same dynamics on random trees.
#[test]
fn exported_models_reimport_to_the_same_dynamics() {
    use mintorque::model::{figure, urdf, urdf_export};
    for (seed, n) in [(31u64, 1usize), (32, 8), (33, 23), (34, 40)] {
        let model = random_tree(seed, n);
        let via_urdf = urdf::parse(&urdf_export::to_urdf(&model), "exported.urdf").unwrap_or_else(|e| panic!("{e}"));
        let via_figure = figure::parse(&figure::to_toml(&model), "exported.toml").unwrap_or_else(|e| panic!("{e}"));
        let (q, v, a) = state(seed, n);
        let mut data = Data::new(&model);
        let tau = rnea(&model, &mut data, &q, &v, &a, &G, None).clone();
        for (what, other) in [("URDF", &via_urdf), ("figure file", &via_figure)] {
            // Match joints by name: an importer may number them differently.
            let perm: Vec<usize> = model.joint_names().iter().map(|name| other.dof_index(name).expect("joint kept")).collect();
            let mut qo = vec![0.0; n];
            let mut vo = vec![0.0; n];
            let mut ao = vec![0.0; n];
            for i in 0..n {
                (qo[perm[i]], vo[perm[i]], ao[perm[i]]) = (q[i], v[i], a[i]);
            }
            let mut d = Data::new(other);
            let t = rnea(other, &mut d, &qo, &vo, &ao, &G, None).clone();
            for i in 0..n {
                assert!((t[perm[i]] - tau[i]).abs() < 1e-9 * (1.0 + tau[i].abs()), "{what} round trip changes τ of joint {i}");
            }
        }
    }
}

/// Locking joints welds them: the remaining joints' dynamics equal the full model's with the locked joints
/// held still at their values.
#[test]
fn locked_joints_weld_bodies_without_changing_the_dynamics() {
    for (seed, n) in [(41u64, 3usize), (42, 10), (43, 25)] {
        let model = random_tree(seed, n);
        let mut rng = Rng(seed);
        let locks: Vec<(usize, f64)> = (0..n).filter(|i| i % 3 == 1).map(|i| (i, rng.uniform(-1.0, 1.0))).collect();
        let locked = model.with_locked(&locks);
        locked.validate("locked").unwrap();
        assert_eq!(locked.nv(), n - locks.len());
        assert!((locked.total_mass() - model.total_mass()).abs() < 1e-12);
        let (mut q, mut v, mut a) = state(seed, n);
        for &(i, value) in &locks {
            (q[i], v[i], a[i]) = (value, 0.0, 0.0);
        }
        let kept: Vec<usize> = (0..n).filter(|i| !locks.iter().any(|(d, _)| d == i)).collect();
        let pick = |x: &[f64]| kept.iter().map(|&i| x[i]).collect::<Vec<f64>>();
        let tau_full = rnea(&model, &mut Data::new(&model), &q, &v, &a, &G, None).clone();
        let tau_locked = rnea(&locked, &mut Data::new(&locked), &pick(&q), &pick(&v), &pick(&a), &G, None).clone();
        for (k, &i) in kept.iter().enumerate() {
            assert!(
                (tau_full[i] - tau_locked[k]).abs() < 1e-9 * (1.0 + tau_full[i].abs()),
                "joint {i}: {} vs {}",
                tau_full[i],
                tau_locked[k]
            );
        }
        // Frames keep their world placement.
        let mut d_full = Data::new(&model);
        let mut d_locked = Data::new(&locked);
        kinematics::placements(&model, &mut d_full, &q);
        kinematics::placements(&locked, &mut d_locked, &pick(&q));
        for (f, frame) in model.frames.iter().enumerate() {
            let g = locked.frame_index(&frame.name).unwrap();
            let (a, b) = (kinematics::frame_placement(&model, &d_full, f), kinematics::frame_placement(&locked, &d_locked, g));
            assert!(
                (a.translation - b.translation).norm() < 1e-12 && (a.rotation - b.rotation).norm() < 1e-12,
                "frame {}",
                frame.name
            );
        }
    }
}
