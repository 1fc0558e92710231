//! ZXY Euler angles of a rotation (`R = Rz(z)·Rx(x)·Ry(y)`), kept continuous from frame to frame: the BVH
//! channels of a joint whose axes are not the coordinate axes.

use crate::spatial::Mat3;
use std::f64::consts::PI;

/// `(z, x, y)` with `R = Rz(z)·Rx(x)·Ry(y)` and `x ∈ [−π/2, π/2]` (radians).
pub(crate) fn euler_zxy(r: &Mat3) -> [f64; 3] {
    let x = r[(2, 1)].clamp(-1.0, 1.0).asin();
    if (1.0 - r[(2, 1)].abs()) < 1e-12 {
        // Gimbal lock: only z ± y is determined; put it all in z.
        return [r[(1, 0)].atan2(r[(0, 0)]), x, 0.0];
    }
    [(-r[(0, 1)]).atan2(r[(1, 1)]), x, (-r[(2, 0)]).atan2(r[(2, 2)])]
}

/// The ZXY angles of `r` closest to the previous frame's: of the two equivalent sets `(z, x, y)` and
/// `(z + π, π − x, y + π)`, each angle moved by whole turns towards `previous`, the nearer one.
pub fn euler_zxy_near(r: &Mat3, previous: Option<[f64; 3]>) -> [f64; 3] {
    let a = euler_zxy(r);
    let Some(p) = previous else { return a };
    let near = |v: f64, p: f64| v + 2.0 * PI * ((p - v) / (2.0 * PI)).round();
    let candidates = [a, [a[0] + PI, PI - a[1], a[2] + PI]].map(|c| [near(c[0], p[0]), near(c[1], p[1]), near(c[2], p[2])]);
    let distance = |c: &[f64; 3]| (0..3).map(|k| (c[k] - p[k]).powi(2)).sum::<f64>();
    if distance(&candidates[1]) < distance(&candidates[0]) {
        candidates[1]
    } else {
        candidates[0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::{axis_angle, Vec3};

    fn rot(k: usize, a: f64) -> Mat3 {
        axis_angle(&Vec3::ith(k, 1.0), a)
    }

    #[test]
    fn euler_zxy_rebuilds_the_rotation_and_its_twin_is_the_same_rotation() {
        for (z, x, y) in [(0.3, -0.4, 1.2), (-2.9, 1.1, 3.0), (1.0, 0.0, -1.0), (0.5, std::f64::consts::FRAC_PI_2, 0.2)] {
            let r = rot(2, z) * rot(0, x) * rot(1, y);
            let [a, b, c] = euler_zxy(&r);
            assert!((rot(2, a) * rot(0, b) * rot(1, c) - r).norm() < 1e-9, "{z} {x} {y}");
            let twin = rot(2, a + PI) * rot(0, PI - b) * rot(1, c + PI);
            assert!((twin - r).norm() < 1e-9);
        }
    }

    #[test]
    fn euler_angles_stay_continuous_past_a_half_turn() {
        let mut previous = None;
        for k in 0..=40 {
            let y = 4.0 * k as f64 / 40.0; // past π about y alone
            let angles = euler_zxy_near(&rot(1, y), previous);
            assert!((angles[2] - y).abs() < 1e-9 && angles[0].abs() < 1e-9 && angles[1].abs() < 1e-9, "{y}: {angles:?}");
            previous = Some(angles);
        }
    }
}
