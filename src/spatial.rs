//! Spatial algebra (paper section 5.2, eq. 15–23; Featherstone, *Rigid Body Dynamics Algorithms*).
//!
//! Conventions (written down once, used everywhere):
//! - A motion vector (twist) is `[ω; v]` — angular part first, then the linear velocity of the body point
//!   that is momentarily at the frame's origin. A force vector (wrench) is `[n; f]` — moment about the
//!   frame's origin first, then the force. The paper writes the wrench as `(f, m_o)`; we keep Featherstone's
//!   later convention of the same order for both so that `m · f` is the plain dot product (the paper's
//!   "Ŝˢ" swap operator disappears).
//! - A [`Transform`] is a rigid placement `(R, p)`: the child frame's axes `R` and origin `p`, both expressed
//!   in the parent frame. `act` maps vectors from child to parent coordinates — the paper's
//!   `X̂` of eq. 19 (motion) and eq. 22 (force) — and `act_inv` maps back.
//! - Units: SI. Angles in radians.

use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

/// A 3-vector (m, rad, N … as the context says).
pub type Vec3 = Vector3<f64>;
/// A 3×3 matrix (rotations, rotational inertias).
pub type Mat3 = Matrix3<f64>;
/// A 6×6 spatial matrix.
pub type Mat6 = Matrix6<f64>;
/// A spatial 6-vector in the `[angular; linear]` order.
pub type Vec6 = Vector6<f64>;

/// The skew-symmetric matrix of eq. 20: `skew(d) x = d × x`.
#[inline]
pub fn skew(d: &Vec3) -> Mat3 {
    Mat3::new(0.0, -d.z, d.y, d.z, 0.0, -d.x, -d.y, d.x, 0.0)
}

/// A spatial motion vector (twist) `[ω; v]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Motion {
    /// Angular velocity `ω` (rad/s).
    pub w: Vec3,
    /// Linear velocity `v` of the point at the frame's origin (m/s).
    pub v: Vec3,
}

/// A spatial force vector (wrench) `[n; f]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Force {
    /// Moment `n` about the frame's origin (N·m).
    pub n: Vec3,
    /// Force `f` (N).
    pub f: Vec3,
}

impl Motion {
    /// The zero twist.
    pub const ZERO: Motion = Motion { w: Vec3::new(0.0, 0.0, 0.0), v: Vec3::new(0.0, 0.0, 0.0) };

    /// The twist `[w; v]`.
    #[inline]
    pub fn new(w: Vec3, v: Vec3) -> Self {
        Motion { w, v }
    }

    /// The motion cross product `self × m` (eq. 23: the Lie bracket `ad_self(m)`).
    #[inline]
    pub fn cross(&self, m: &Motion) -> Motion {
        Motion { w: self.w.cross(&m.w), v: self.w.cross(&m.v) + self.v.cross(&m.w) }
    }

    /// The force cross product `self ×* f` (the dual action, `-ad_selfᵀ f`).
    #[inline]
    pub fn cross_force(&self, f: &Force) -> Force {
        Force { n: self.w.cross(&f.n) + self.v.cross(&f.f), f: self.w.cross(&f.f) }
    }

    /// The power pairing `m · f`.
    #[inline]
    pub fn dot(&self, f: &Force) -> f64 {
        self.w.dot(&f.n) + self.v.dot(&f.f)
    }

    /// `s·self`.
    #[inline]
    pub fn scale(&self, s: f64) -> Motion {
        Motion { w: self.w * s, v: self.v * s }
    }

    /// `self + s·m`, the axpy that the recursions are made of.
    #[inline]
    pub fn add_scaled(&self, m: &Motion, s: f64) -> Motion {
        Motion { w: self.w + m.w * s, v: self.v + m.v * s }
    }

    /// As a 6-vector `[ω; v]`.
    #[inline]
    pub fn to_vec6(&self) -> Vec6 {
        Vec6::new(self.w.x, self.w.y, self.w.z, self.v.x, self.v.y, self.v.z)
    }

    /// From a 6-vector `[ω; v]`.
    #[inline]
    pub fn from_vec6(x: &Vec6) -> Self {
        Motion { w: Vec3::new(x[0], x[1], x[2]), v: Vec3::new(x[3], x[4], x[5]) }
    }
}

impl Force {
    /// The zero wrench.
    pub const ZERO: Force = Force { n: Vec3::new(0.0, 0.0, 0.0), f: Vec3::new(0.0, 0.0, 0.0) };

    /// The wrench `[n; f]`.
    #[inline]
    pub fn new(n: Vec3, f: Vec3) -> Self {
        Force { n, f }
    }

    /// As a 6-vector `[n; f]`.
    #[inline]
    pub fn to_vec6(&self) -> Vec6 {
        Vec6::new(self.n.x, self.n.y, self.n.z, self.f.x, self.f.y, self.f.z)
    }

    /// From a 6-vector `[n; f]`.
    #[inline]
    pub fn from_vec6(x: &Vec6) -> Self {
        Force { n: Vec3::new(x[0], x[1], x[2]), f: Vec3::new(x[3], x[4], x[5]) }
    }

    /// The matrix `N(h)` with `N(h) m = m ×* h` for every motion `m` — the force cross product seen as a
    /// linear map of its left argument (needed by the derivative recursions).
    #[inline]
    pub fn cross_matrix(&self) -> Mat6 {
        let mut out = Mat6::zeros();
        let nn = -skew(&self.n);
        let ff = -skew(&self.f);
        out.fixed_view_mut::<3, 3>(0, 0).copy_from(&nn);
        out.fixed_view_mut::<3, 3>(0, 3).copy_from(&ff);
        out.fixed_view_mut::<3, 3>(3, 0).copy_from(&ff);
        out
    }
}

macro_rules! vector_ops {
    ($t:ident, $a:ident, $b:ident) => {
        impl std::ops::Add for $t {
            type Output = $t;
            #[inline]
            fn add(self, o: $t) -> $t {
                $t { $a: self.$a + o.$a, $b: self.$b + o.$b }
            }
        }
        impl std::ops::Sub for $t {
            type Output = $t;
            #[inline]
            fn sub(self, o: $t) -> $t {
                $t { $a: self.$a - o.$a, $b: self.$b - o.$b }
            }
        }
        impl std::ops::Neg for $t {
            type Output = $t;
            #[inline]
            fn neg(self) -> $t {
                $t { $a: -self.$a, $b: -self.$b }
            }
        }
        impl std::ops::AddAssign for $t {
            #[inline]
            fn add_assign(&mut self, o: $t) {
                self.$a += o.$a;
                self.$b += o.$b;
            }
        }
        impl std::ops::SubAssign for $t {
            #[inline]
            fn sub_assign(&mut self, o: $t) {
                self.$a -= o.$a;
                self.$b -= o.$b;
            }
        }
        impl std::ops::Mul<f64> for $t {
            type Output = $t;
            #[inline]
            fn mul(self, s: f64) -> $t {
                $t { $a: self.$a * s, $b: self.$b * s }
            }
        }
    };
}
vector_ops!(Motion, w, v);
vector_ops!(Force, n, f);

/// A rigid placement: child axes `rotation` and child origin `translation`, in the parent frame
/// (eq. 15's `(R, d)` as an element of SE(3)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// The child frame's axes in the parent frame, `R`.
    pub rotation: Mat3,
    /// The child frame's origin in the parent frame, `p` (m).
    pub translation: Vec3,
}

impl Default for Transform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Transform {
    /// The identity placement.
    pub const IDENTITY: Transform =
        Transform { rotation: Mat3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0), translation: Vec3::new(0.0, 0.0, 0.0) };

    /// The placement `(rotation, translation)`.
    pub fn new(rotation: Mat3, translation: Vec3) -> Self {
        Transform { rotation, translation }
    }

    /// A pure translation (m).
    pub fn from_translation(translation: Vec3) -> Self {
        Transform { rotation: Mat3::identity(), translation }
    }

    /// URDF's `rpy`: fixed-axis roll about x, then pitch about y, then yaw about z: `R = Rz(y) Ry(p) Rx(r)`.
    pub fn from_rpy_xyz(rpy: Vec3, xyz: Vec3) -> Self {
        Transform { rotation: rpy_to_matrix(&rpy), translation: xyz }
    }

    /// Composition `self * other`: `other` is expressed in `self`'s child frame.
    #[inline]
    pub fn compose(&self, other: &Transform) -> Transform {
        Transform { rotation: self.rotation * other.rotation, translation: self.rotation * other.translation + self.translation }
    }

    /// The inverse placement: parent in child coordinates.
    #[inline]
    pub fn inverse(&self) -> Transform {
        let rt = self.rotation.transpose();
        Transform { rotation: rt, translation: -(rt * self.translation) }
    }

    /// A point in child coordinates, to parent coordinates.
    #[inline]
    pub fn act_point(&self, x: &Vec3) -> Vec3 {
        self.rotation * x + self.translation
    }

    /// A motion vector from child to parent coordinates (eq. 19 read from child to parent).
    #[inline]
    pub fn act_motion(&self, m: &Motion) -> Motion {
        let w = self.rotation * m.w;
        Motion { w, v: self.rotation * m.v + self.translation.cross(&w) }
    }

    /// A motion vector from parent to child coordinates.
    #[inline]
    pub fn act_inv_motion(&self, m: &Motion) -> Motion {
        let rt = self.rotation.transpose();
        Motion { w: rt * m.w, v: rt * (m.v - self.translation.cross(&m.w)) }
    }

    /// A force vector from child to parent coordinates (eq. 22).
    #[inline]
    pub fn act_force(&self, f: &Force) -> Force {
        let ff = self.rotation * f.f;
        Force { n: self.rotation * f.n + self.translation.cross(&ff), f: ff }
    }

    /// A force vector from parent to child coordinates.
    #[inline]
    pub fn act_inv_force(&self, f: &Force) -> Force {
        let rt = self.rotation.transpose();
        Force { n: rt * (f.n - self.translation.cross(&f.f)), f: rt * f.f }
    }
}

/// `R = Rz(yaw) Ry(pitch) Rx(roll)` (URDF convention).
pub fn rpy_to_matrix(rpy: &Vec3) -> Mat3 {
    let (sr, cr) = rpy.x.sin_cos();
    let (sp, cp) = rpy.y.sin_cos();
    let (sy, cy) = rpy.z.sin_cos();
    Mat3::new(
        cy * cp,
        cy * sp * sr - sy * cr,
        cy * sp * cr + sy * sr,
        sy * cp,
        sy * sp * sr + cy * cr,
        sy * sp * cr - cy * sr,
        -sp,
        cp * sr,
        cp * cr,
    )
}

/// The inverse of [`rpy_to_matrix`] (for URDF export), with `pitch ∈ [-π/2, π/2]`.
///
/// Well conditioned everywhere, gimbal lock included: pitch comes from `atan2` (not `asin`, whose error
/// grows like `1/cos(pitch)`), and roll is solved from `Rz(yaw)ᵀ R = Ry(pitch) Rx(roll)` with the yaw
/// actually chosen, so that even when yaw is poorly determined (pitch ≈ ±π/2) the matrix is rebuilt exactly.
pub fn matrix_to_rpy(r: &Mat3) -> Vec3 {
    let yaw = r[(1, 0)].atan2(r[(0, 0)]);
    let (sy, cy) = yaw.sin_cos();
    let pitch = (-r[(2, 0)]).atan2(cy * r[(0, 0)] + sy * r[(1, 0)]);
    let roll = (sy * r[(0, 2)] - cy * r[(1, 2)]).atan2(cy * r[(1, 1)] - sy * r[(0, 1)]);
    Vec3::new(roll, pitch, yaw)
}

/// Rotation by `angle` about the unit `axis` (Rodrigues; the matrix exponential `e^{Ŝ q}` of eq. 17 for a
/// pure rotation).
#[inline]
pub fn axis_angle(axis: &Vec3, angle: f64) -> Mat3 {
    let (s, c) = angle.sin_cos();
    let t = 1.0 - c;
    let (x, y, z) = (axis.x, axis.y, axis.z);
    Mat3::new(
        t * x * x + c,
        t * x * y - s * z,
        t * x * z + s * y,
        t * x * y + s * z,
        t * y * y + c,
        t * y * z - s * x,
        t * x * z - s * y,
        t * y * z + s * x,
        t * z * z + c,
    )
}

/// A rotation taking the z axis to the unit vector `a` (cylinders are drawn along their local z). When `a`
/// is `-z`, the half turn is about x.
pub fn rotation_from_z(a: &Vec3) -> Mat3 {
    let z = Vec3::z();
    let c = z.cross(a);
    let s = c.norm();
    if s < 1e-12 {
        return if a.z > 0.0 { Mat3::identity() } else { axis_angle(&Vec3::x(), std::f64::consts::PI) };
    }
    axis_angle(&(c / s), s.atan2(z.dot(a)))
}

/// The rigid-body inertia of one link in its own frame: mass, centre of mass and the rotational inertia
/// about the centre of mass (the paper's `M̂'ᵢ`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inertia {
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass in the link frame (m).
    pub com: Vec3,
    /// Rotational inertia about the centre of mass, link axes (kg·m²).
    pub inertia_com: Mat3,
}

impl Inertia {
    /// No mass at all.
    pub const ZERO: Inertia =
        Inertia { mass: 0.0, com: Vec3::new(0.0, 0.0, 0.0), inertia_com: Mat3::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0) };

    /// The inertia of `mass` (kg) at `com` (m) with `inertia_com` (kg·m²) about it.
    pub fn new(mass: f64, com: Vec3, inertia_com: Mat3) -> Self {
        Inertia { mass, com, inertia_com }
    }

    /// This inertia seen from the parent frame of `x` (the link's frame is `x`'s child frame).
    pub fn transformed(&self, x: &Transform) -> Inertia {
        Inertia {
            mass: self.mass,
            com: x.act_point(&self.com),
            inertia_com: x.rotation * self.inertia_com * x.rotation.transpose(),
        }
    }

    /// The sum of two rigid bodies welded together (parallel-axis theorem), both in the same frame.
    pub fn merged(&self, o: &Inertia) -> Inertia {
        let m = self.mass + o.mass;
        if m == 0.0 {
            return Inertia::ZERO;
        }
        let c = (self.com * self.mass + o.com * o.mass) / m;
        let shift = |i: &Inertia| {
            let d = i.com - c;
            i.inertia_com + (Mat3::identity() * d.dot(&d) - d * d.transpose()) * i.mass
        };
        Inertia { mass: m, com: c, inertia_com: shift(self) + shift(o) }
    }

    /// The spatial inertia about this frame's origin in the `(m, h = m c, I_o)` form used by [`SpatialInertia`].
    pub fn spatial(&self) -> SpatialInertia {
        SpatialInertia::from_com(self.mass, &self.com, &self.inertia_com)
    }

    /// The spatial inertia about the parent origin of `x` (this body's frame is `x`'s child frame):
    /// cheaper than [`SpatialInertia::act`] because the rotation acts on the inertia about the centre of
    /// mass only.
    #[inline]
    pub fn spatial_in(&self, x: &Transform) -> SpatialInertia {
        SpatialInertia::from_com(self.mass, &x.act_point(&self.com), &rotate_symmetric(&x.rotation, &self.inertia_com))
    }
}

/// `R S Rᵀ` for a symmetric `S`, computing the upper triangle only (45 multiplications instead of 54).
#[inline]
pub fn rotate_symmetric(r: &Mat3, s: &Mat3) -> Mat3 {
    let t = r * s;
    let e = |i: usize, j: usize| t[(i, 0)] * r[(j, 0)] + t[(i, 1)] * r[(j, 1)] + t[(i, 2)] * r[(j, 2)];
    let (a, b, c, d, f, g) = (e(0, 0), e(0, 1), e(0, 2), e(1, 1), e(1, 2), e(2, 2));
    Mat3::new(a, b, c, b, d, f, c, f, g)
}

/// A spatial inertia about a frame's origin, `I = [[I_o, h×], [-h×, m·1]]`, stored as its ten numbers.
/// `I_o` is the rotational inertia about the origin, `h = m c` the first moment of mass. Sums of these
/// are the composite inertias of the CRBA and the derivative recursions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpatialInertia {
    /// Mass `m` (kg).
    pub m: f64,
    /// First moment of mass `h = m c` (kg·m).
    pub h: Vec3,
    /// Rotational inertia about the frame's origin `I_o` (kg·m²).
    pub i_o: Mat3,
}

impl Default for SpatialInertia {
    fn default() -> Self {
        Self::ZERO
    }
}

impl SpatialInertia {
    /// No mass at all.
    pub const ZERO: SpatialInertia =
        SpatialInertia { m: 0.0, h: Vec3::new(0.0, 0.0, 0.0), i_o: Mat3::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0) };

    /// `I m`: the momentum of a body moving with twist `m`.
    #[inline]
    pub fn mul(&self, x: &Motion) -> Force {
        Force { n: self.i_o * x.w + self.h.cross(&x.v), f: x.v * self.m - self.h.cross(&x.w) }
    }

    /// This inertia (given in a frame's child coordinates) expressed in the parent coordinates of `x`.
    #[inline]
    pub fn act(&self, x: &Transform) -> SpatialInertia {
        let r = &x.rotation;
        let p = &x.translation;
        let h_r = r * self.h;
        let i_r = r * self.i_o * r.transpose();
        // I_o' = R I_o Rᵀ - p̃ h̃' - h̃' p̃ ... written via the com form to stay symmetric:
        // I_o' = I_r - (p̃ (h_r)̃ + (h_r)̃ p̃) - m p̃ p̃
        let px = skew(p);
        let hx = skew(&h_r);
        SpatialInertia { m: self.m, h: h_r + p * self.m, i_o: i_r - px * hx - hx * px - px * px * self.m }
    }

    /// The spatial inertia of a body given by its mass `m`, centre of mass `c` and rotational inertia
    /// `inertia_com` about `c`, all in the same coordinates: `I_o = Ī + m(|c|²1 − c cᵀ)` (parallel axes).
    #[inline]
    pub fn from_com(m: f64, c: &Vec3, inertia_com: &Mat3) -> SpatialInertia {
        let mut i_o = *inertia_com - c * c.transpose() * m;
        let d = m * c.dot(c);
        i_o[(0, 0)] += d;
        i_o[(1, 1)] += d;
        i_o[(2, 2)] += d;
        SpatialInertia { m, h: c * m, i_o }
    }

    /// The 6×6 matrix.
    pub fn matrix(&self) -> Mat6 {
        let mut out = Mat6::zeros();
        let hx = skew(&self.h);
        out.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.i_o);
        out.fixed_view_mut::<3, 3>(0, 3).copy_from(&hx);
        out.fixed_view_mut::<3, 3>(3, 0).copy_from(&(-hx));
        out.fixed_view_mut::<3, 3>(3, 3).copy_from(&(Mat3::identity() * self.m));
        out
    }
}

impl std::ops::AddAssign for SpatialInertia {
    #[inline]
    fn add_assign(&mut self, o: SpatialInertia) {
        self.m += o.m;
        self.h += o.h;
        self.i_o += o.i_o;
    }
}

impl std::ops::Add for SpatialInertia {
    type Output = SpatialInertia;
    #[inline]
    fn add(mut self, o: SpatialInertia) -> SpatialInertia {
        self += o;
        self
    }
}

impl std::ops::Sub for SpatialInertia {
    type Output = SpatialInertia;
    #[inline]
    fn sub(self, o: SpatialInertia) -> SpatialInertia {
        SpatialInertia { m: self.m - o.m, h: self.h - o.h, i_o: self.i_o - o.i_o }
    }
}

/// The 6×6 matrix of `m ×` (Featherstone's `crm`).
pub fn motion_cross_matrix(m: &Motion) -> Mat6 {
    let mut out = Mat6::zeros();
    let wx = skew(&m.w);
    out.fixed_view_mut::<3, 3>(0, 0).copy_from(&wx);
    out.fixed_view_mut::<3, 3>(3, 3).copy_from(&wx);
    out.fixed_view_mut::<3, 3>(3, 0).copy_from(&skew(&m.v));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(a: [f64; 6]) -> Motion {
        Motion::from_vec6(&Vec6::from_row_slice(&a))
    }

    fn f(a: [f64; 6]) -> Force {
        Force::from_vec6(&Vec6::from_row_slice(&a))
    }

    fn some_transform() -> Transform {
        Transform::from_rpy_xyz(Vec3::new(0.3, -0.7, 1.1), Vec3::new(0.2, -0.5, 0.9))
    }

    #[test]
    fn transforms_preserve_power() {
        let x = some_transform();
        let a = m([0.1, 0.2, -0.3, 0.4, 0.5, -0.6]);
        let b = f([1.0, -2.0, 0.5, 0.25, 3.0, -1.5]);
        // (X m) · (X* f) = m · f
        let lhs = x.act_motion(&a).dot(&x.act_force(&b));
        assert!((lhs - a.dot(&b)).abs() < 1e-12);
        let back = x.act_inv_motion(&x.act_motion(&a));
        assert!((back.to_vec6() - a.to_vec6()).norm() < 1e-12);
        let backf = x.act_inv_force(&x.act_force(&b));
        assert!((backf.to_vec6() - b.to_vec6()).norm() < 1e-12);
    }

    #[test]
    fn cross_products_match_their_matrices_and_duality() {
        let a = m([0.1, 0.2, -0.3, 0.4, 0.5, -0.6]);
        let b = m([-1.0, 0.3, 0.7, 0.2, -0.1, 0.9]);
        let h = f([1.0, -2.0, 0.5, 0.25, 3.0, -1.5]);
        let crm = motion_cross_matrix(&a);
        assert!((crm * b.to_vec6() - a.cross(&b).to_vec6()).norm() < 1e-14);
        // ×* = -(×)ᵀ
        assert!((-crm.transpose() * h.to_vec6() - a.cross_force(&h).to_vec6()).norm() < 1e-14);
        assert!((h.cross_matrix() * a.to_vec6() - a.cross_force(&h).to_vec6()).norm() < 1e-14);
        // (a × b) · h = -b · (a ×* h)
        assert!((a.cross(&b).dot(&h) + b.dot(&a.cross_force(&h))).abs() < 1e-13);
    }

    #[test]
    fn spatial_inertia_transforms_like_its_matrix() {
        let x = some_transform();
        let body = Inertia::new(2.5, Vec3::new(0.1, -0.2, 0.3), Mat3::new(0.3, 0.01, 0.02, 0.01, 0.4, -0.03, 0.02, -0.03, 0.5));
        let i_child = body.spatial();
        let i_parent = i_child.act(&x);
        // from the com form in the parent frame
        assert!((i_parent.matrix() - body.transformed(&x).spatial().matrix()).norm() < 1e-12);
        // momentum transforms as a force
        let a = m([0.1, 0.2, -0.3, 0.4, 0.5, -0.6]);
        let lhs = i_parent.mul(&x.act_motion(&a));
        let rhs = x.act_force(&i_child.mul(&a));
        assert!((lhs.to_vec6() - rhs.to_vec6()).norm() < 1e-12);
    }

    #[test]
    fn rpy_round_trip() {
        let r = rpy_to_matrix(&Vec3::new(0.3, -0.7, 1.1));
        let rpy = matrix_to_rpy(&r);
        assert!((rpy_to_matrix(&rpy) - r).norm() < 1e-12);
        // At and next to gimbal lock (ur5's pitch is 1.570796325, 1.8e-9 short of π/2).
        for pitch in [std::f64::consts::FRAC_PI_2, -std::f64::consts::FRAC_PI_2, 1.570796325, -1.570796325] {
            let r = rpy_to_matrix(&Vec3::new(0.3, pitch, -1.1)) * rpy_to_matrix(&Vec3::new(0.0, 0.0, 3.0));
            assert!((rpy_to_matrix(&matrix_to_rpy(&r)) - r).norm() < 1e-15, "pitch {pitch}");
        }
        let a = axis_angle(&Vec3::new(0.0, 0.0, 1.0), 0.4);
        assert!((a - rpy_to_matrix(&Vec3::new(0.0, 0.0, 0.4))).norm() < 1e-15);
    }
}
