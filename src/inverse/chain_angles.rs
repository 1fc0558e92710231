//! The angles of a chain of revolutes that make a given rotation: `R = Π Rot(uᵢ, qᵢ)` (axes `uᵢ` fixed in
//! the parent's rest frame, composed in chain order) solved for `q` — the decomposition of a BVH joint's
//! rotation into a model joint's axis sequence. One axis: the twist of `R` about it (the rotation
//! projected onto the joint). Three orthonormal axes: Euler angles in closed form (the two solutions, the
//! one nearer the previous frame's). Otherwise, and to polish: damped Gauss–Newton on the rotation error,
//! from the previous frame's angles, so that a redundant or locked chain keeps the nearest split.

use crate::report::export::euler_zxy_near;
use crate::spatial::{axis_angle, Mat3, Vec3};
use nalgebra::{DMatrix, DVector, Rotation3, UnitQuaternion};
use std::f64::consts::PI;

/// `Π Rot(uᵢ, qᵢ)` in chain order.
pub fn chain_rotation(axes: &[Vec3], q: &[f64]) -> Mat3 {
    axes.iter().zip(q).fold(Mat3::identity(), |r, (u, &a)| r * axis_angle(u, a))
}

/// The angle (rad) of the rotation `R·R(q)ᵀ` the chain at `q` leaves of `r`.
pub fn residual(r: &Mat3, axes: &[Vec3], q: &[f64]) -> f64 {
    rotation_vector(&(r * chain_rotation(axes, q).transpose())).norm()
}

/// `θ·n` of a rotation matrix (its logarithm), from its quaternion `(w, v)`: `θ = 2·atan2(|v|, |w|)`, `n = ±v/|v|`.
/// Not from `acos((tr R − 1)/2)`: a product of rotations rounded to `tr R = 3 + ε` made that NaN (a BVH whose
/// every frame matched its chain to rounding read back as NaN).
fn rotation_vector(r: &Mat3) -> Vec3 {
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*r));
    let (w, v) = (q.scalar(), q.vector().into_owned());
    let n = v.norm();
    if n == 0.0 {
        return Vec3::zeros();
    }
    v * (w.signum() * 2.0 * n.atan2(w.abs()) / n)
}

/// The chain angles making `r` (as nearly as the chain can), near `previous` when given.
pub fn chain_angles(r: &Mat3, axes: &[Vec3], previous: Option<&[f64]>) -> Vec<f64> {
    let start = match axes.len() {
        0 => return Vec::new(),
        1 => return vec![near(twist(r, &axes[0]), previous.map(|p| p[0]))],
        3 if orthonormal(axes) => euler(r, axes, previous),
        n => previous.map_or(vec![0.0; n], <[f64]>::to_vec),
    };
    polish(r, axes, start)
}

/// `v + 2πk` nearest `previous`.
fn near(v: f64, previous: Option<f64>) -> f64 {
    previous.map_or(v, |p| v + 2.0 * PI * ((p - v) / (2.0 * PI)).round())
}

/// The twist of `r` about unit `u`: with `r`'s quaternion `(w, v)`, `θ = 2·atan2(v·u, w)`.
fn twist(r: &Mat3, u: &Vec3) -> f64 {
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*r));
    let angle = 2.0 * (q.vector().dot(u)).atan2(q.scalar());
    // Wrapped to [−π, π].
    near(angle, Some(0.0))
}

fn orthonormal(axes: &[Vec3]) -> bool {
    let m = Mat3::from_columns(axes);
    (m.transpose() * m - Mat3::identity()).norm() < 1e-9
}

/// Three orthonormal axes: with `B = [u₂ u₃ u₁]` (u₃ negated if that makes `det B = −1`),
/// `Bᵀ·R·B = Rz(q₁)·Rx(q₂)·Ry(±q₃)`, ZXY Euler angles.
fn euler(r: &Mat3, axes: &[Vec3], previous: Option<&[f64]>) -> Vec<f64> {
    let mut b = Mat3::from_columns(&[axes[1], axes[2], axes[0]]);
    let sign = b.determinant().signum();
    b.set_column(1, &(axes[2] * sign));
    let previous = previous.map(|p| [p[0], p[1], sign * p[2]]);
    let [q1, q2, q3] = euler_zxy_near(&(b.transpose() * r * b), previous);
    vec![q1, q2, sign * q3]
}

/// Damped Gauss–Newton: `e = log(R·R(q)ᵀ)` (world axes), `J = [u₁, R₁u₂, R₁R₂u₃, …]`,
/// `q += (JᵀJ + μI)⁻¹Jᵀe`, until the step is below 1e-13 rad.
fn polish(r: &Mat3, axes: &[Vec3], mut q: Vec<f64>) -> Vec<f64> {
    const DAMPING: f64 = 1e-10;
    for _ in 0..100 {
        let e = rotation_vector(&(r * chain_rotation(axes, &q).transpose()));
        let mut jacobian = DMatrix::zeros(3, axes.len());
        let mut carried = Mat3::identity();
        for (i, u) in axes.iter().enumerate() {
            jacobian.set_column(i, &(carried * u));
            carried *= axis_angle(u, q[i]);
        }
        let normal = jacobian.transpose() * &jacobian + DMatrix::identity(axes.len(), axes.len()) * DAMPING;
        let gradient = jacobian.transpose() * DVector::from_column_slice(e.as_slice());
        let Some(step) = normal.cholesky().map(|c| c.solve(&gradient)) else { break };
        q.iter_mut().zip(step.iter()).for_each(|(a, d)| *a += d);
        if step.norm() < 1e-13 {
            break;
        }
    }
    q
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rotation_rounded_past_a_trace_of_three_has_a_finite_logarithm() {
        // `tr R` a hair above 3 (as a product of exact rotations can round to): `acos` of it is NaN.
        let mut r = axis_angle(&Vec3::new(0.3, -0.5, 0.8).normalize(), 1e-8);
        r *= 1.0 + 4e-16;
        assert!(r.trace() > 3.0);
        assert!(rotation_vector(&r).iter().all(|v| v.is_finite() && v.abs() < 2e-8), "{:?}", rotation_vector(&r));
        let turn = axis_angle(&Vec3::new(0.3, -0.5, 0.8).normalize(), 2.5);
        assert!((rotation_vector(&turn) - Vec3::new(0.3, -0.5, 0.8).normalize() * 2.5).norm() < 1e-12);
    }

    #[test]
    fn chains_give_back_their_angles_and_a_projection_keeps_the_twist() {
        let ortho = [Vec3::y(), -Vec3::z(), Vec3::x()];
        let tilted = [Vec3::new(0.0, 0.6, 0.8), Vec3::x(), Vec3::new(0.0, 1.0, 1.0).normalize()];
        for axes in [&ortho[..], &tilted[..], &ortho[..2]] {
            let q = [0.4, -0.7, 1.1][..axes.len()].to_vec();
            let r = chain_rotation(axes, &q);
            let near: Vec<f64> = q.iter().map(|a| a + 0.2).collect();
            let back = chain_angles(&r, axes, Some(&near));
            assert!(back.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9), "{axes:?}: {back:?}");
        }
        // One axis: a swing about another axis is dropped, the twist about this one kept.
        let r = axis_angle(&Vec3::z(), 0.5) * axis_angle(&Vec3::x(), 0.3);
        let q = chain_angles(&r, &[Vec3::z()], None);
        assert!((q[0] - 0.5).abs() < 1e-9 && residual(&r, &[Vec3::z()], &q) > 0.29, "{q:?}");
    }
}
