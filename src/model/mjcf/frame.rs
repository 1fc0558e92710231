//! Frames: `pos` and one orientation (`quat`, `euler`, `axisangle`, `xyaxes`, `zaxis`) as MuJoCo reads
//! them, and `fromto` for geoms and sites.

use super::{schema, Cx, El};
use crate::error::Result;
use crate::spatial::{axis_angle, rotation_from_z, Mat3, Transform, Vec3};

/// The rotation of the unit quaternion `(w, x, y, z)` (MuJoCo's order).
pub fn quat_matrix(w: f64, x: f64, y: f64, z: f64) -> Mat3 {
    Mat3::new(
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        2.0 * (x * y + w * z),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z - w * x),
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        1.0 - 2.0 * (x * x + y * y),
    )
}

impl Cx<'_, '_> {
    /// The frame of `e` in its parent's: `pos` (m) and its orientation.
    pub(super) fn placement(&self, e: &El) -> Result<Transform> {
        let pos = self.vec3(e, "pos", Vec3::zeros())?;
        Ok(Transform::new(self.orientation(e)?, pos))
    }

    /// The orientation of `e`: at most one of [`schema::ORIENTATIONS`]; none is the identity.
    pub(super) fn orientation(&self, e: &El) -> Result<Mat3> {
        let given: Vec<&str> = schema::ORIENTATIONS.iter().copied().filter(|a| self.raw(e, a).is_some()).collect();
        let Some(&kind) = given.first() else { return Ok(Mat3::identity()) };
        if given.len() > 1 {
            return Err(self.err_attr(e, given[1], format!("more than one orientation given ({}): give one", given.join(", "))));
        }
        let unit = |v: Vec3, what: &str| -> Result<Vec3> {
            let n = v.norm();
            if n < 1e-12 {
                return Err(self.err_attr(e, kind, format!("{what} must not be zero")));
            }
            Ok(v / n)
        };
        Ok(match kind {
            // R(q) of the normalised quaternion q = (w, x, y, z).
            "quat" => {
                let q = self.numbers(e, "quat", 4..=4)?.unwrap_or_default();
                let n = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
                if n < 1e-12 {
                    return Err(self.err_attr(e, kind, "the quaternion must not be zero".into()));
                }
                quat_matrix(q[0] / n, q[1] / n, q[2] / n, q[3] / n)
            }
            // Rodrigues: rotation by angle a (compiler unit) about the unit axis.
            "axisangle" => {
                let v = self.numbers(e, "axisangle", 4..=4)?.unwrap_or_default();
                axis_angle(&unit(Vec3::new(v[0], v[1], v[2]), "the axis")?, self.angle(v[3]))
            }
            "euler" => self.euler(&self.vec3(e, "euler", Vec3::zeros())?),
            // Columns x, y (x's component removed), z = x × y.
            "xyaxes" => {
                let v = self.numbers(e, "xyaxes", 6..=6)?.unwrap_or_default();
                let x = unit(Vec3::new(v[0], v[1], v[2]), "the x axis")?;
                let y = unit(
                    Vec3::new(v[3], v[4], v[5]) - x * x.dot(&Vec3::new(v[3], v[4], v[5])),
                    "the y axis (once orthogonal to x)",
                )?;
                Mat3::from_columns(&[x, y, x.cross(&y)])
            }
            // The least rotation taking z to the given axis (MuJoCo's z2quat).
            _ => rotation_from_z(&unit(self.vec3(e, "zaxis", Vec3::z())?, "zaxis")?),
        })
    }

    /// `euler` angles (compiler unit) about the axes of `eulerseq`: a moving (lowercase) axis
    /// post-multiplies, `R ← R·Rᵢ`; a fixed (uppercase) one pre-multiplies, `R ← Rᵢ·R`.
    pub(super) fn euler(&self, angles: &Vec3) -> Mat3 {
        let mut r = Mat3::identity();
        for (i, &axis) in self.compiler.eulerseq.iter().enumerate() {
            let unit = match axis.to_ascii_lowercase() {
                b'x' => Vec3::x(),
                b'y' => Vec3::y(),
                _ => Vec3::z(),
            };
            let ri = axis_angle(&unit, self.angle(angles[i]));
            r = if axis.is_ascii_lowercase() { r * ri } else { ri * r };
        }
        r
    }

    /// `fromto="x1 y1 z1 x2 y2 z2"` (m) of `e`, if given: the frame at the midpoint with z along the segment,
    /// and the segment's half length.
    pub(super) fn fromto(&self, e: &El) -> Result<Option<(Transform, f64)>> {
        let Some(v) = self.numbers(e, "fromto", 6..=6)? else { return Ok(None) };
        let (a, b) = (Vec3::new(v[0], v[1], v[2]), Vec3::new(v[3], v[4], v[5]));
        let d = b - a;
        if d.norm() < 1e-12 {
            return Err(self.err_attr(e, "fromto", "the two ends must differ".into()));
        }
        Ok(Some((Transform::new(rotation_from_z(&(d / d.norm())), (a + b) / 2.0), d.norm() / 2.0)))
    }
}
