//! Solid bodies: capsules (a segment swept by a sphere) on the figure's bodies, convex obstacles fixed in
//! the world (a plane, a cylinder, a box), and the signed distances between them with their witness
//! points — what the planner's collision rows (`plan/transcription/collision.rs`) and the posture checks
//! read. SI units (m) throughout.
//!
//! Every distance is `d = n·(p_a − p_b) − radii`, `p_a`, `p_b` the witness points, `n` the unit separation
//! direction (from `b` to `a`). For a convex pair the envelope theorem makes `∂d/∂q = nᵀ(J_a(p_a) −
//! J_b(p_b))` exact wherever the witnesses are unique: the derivative of the minimising parameter drops out.
//! Penetration gives a negative `d` (a signed distance), so values and gradients stay finite across contact.

mod segments;
mod shapes;

pub use segments::{capsule_capsule, capsule_capsule_rounded, ROUNDING};
pub use shapes::capsules_of_shapes;

use crate::spatial::{Mat3, Transform, Vec3};

/// A capsule: the points within `radius` of the segment `a`–`b` (m). A sphere is a capsule with `a = b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Capsule {
    /// One end of the segment (m, in the frame the capsule is given in).
    pub a: Vec3,
    /// The other end (m).
    pub b: Vec3,
    /// Radius (m).
    pub radius: f64,
}

impl Capsule {
    /// The capsule in the parent frame of `x` (given in its child frame).
    pub fn transformed(&self, x: &Transform) -> Capsule {
        Capsule { a: x.act_point(&self.a), b: x.act_point(&self.b), radius: self.radius }
    }
}

/// A convex obstacle fixed in the world (m).
#[derive(Clone, Debug, PartialEq)]
pub enum ObstacleShape {
    /// The half-space below the plane through `point` with unit outward `normal` (a floor).
    Plane {
        /// A point on the plane (m).
        point: Vec3,
        /// Unit outward normal.
        normal: Vec3,
    },
    /// A solid cylinder of `radius` about the line through `point` along unit `direction` (a bar):
    /// infinitely long, or `length` long centred at `point`.
    Cylinder {
        /// A point on the axis; the centre when `length` is given (m).
        point: Vec3,
        /// Unit axis direction.
        direction: Vec3,
        /// Radius (m).
        radius: f64,
        /// Length (m); `None`: infinite.
        length: Option<f64>,
    },
    /// A solid box (a table, a shelf): `rotation`'s columns are its axes, `half` its half edge lengths.
    Box {
        /// Centre (m).
        centre: Vec3,
        /// The box's axes in the world (columns).
        rotation: Mat3,
        /// Half edge lengths along its axes (m).
        half: Vec3,
    },
}

/// An obstacle of the environment, with the name tasks and reports use.
#[derive(Clone, Debug, PartialEq)]
pub struct Obstacle {
    /// Its name.
    pub name: String,
    /// Where it is and what it is.
    pub shape: ObstacleShape,
    /// A keep-out zone rather than a solid: planned alike, drawn as an outline only.
    pub zone: bool,
}

/// The result of a distance query: the signed distance and where it is attained.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Separation {
    /// Signed distance (m): negative when the shapes overlap (by that depth, for an obstacle).
    pub distance: f64,
    /// The witness point on the first shape's segment (m, world): the point of its axis nearest the other.
    pub on_a: Vec3,
    /// The witness point on the second shape's segment (m, world); for an obstacle, its surface point
    /// nearest `on_a`.
    pub on_b: Vec3,
    /// Separation direction, from the second shape towards the first: `∂d/∂p_a = n`, `∂d/∂p_b = −n`. A
    /// unit vector, except for a segment deep inside a box or finite cylinder whose nearest point sits
    /// on a crease of the signed distance (where the nearest face changes): there the combination of the
    /// two faces' normals that keeps the minimum (shorter than 1); and for [`capsule_capsule_rounded`], the
    /// gap over the rounded distance (a little longer than 1).
    pub normal: Vec3,
}

impl ObstacleShape {
    /// Signed distance (m) of the point `p` to the obstacle's surface, and its gradient (a unit vector;
    /// inside, the normal of the nearest face).
    pub fn point_distance(&self, p: &Vec3) -> (f64, Vec3) {
        match self {
            ObstacleShape::Plane { point, normal } => (normal.dot(&(p - point)), *normal),
            ObstacleShape::Cylinder { point, direction, radius, length } => {
                // radial part r = (p − c) − ((p − c)·d) d, axial u = (p − c)·d
                let rel = p - point;
                let u = rel.dot(direction);
                let radial = rel - direction * u;
                let rho = radial.norm();
                let e_r = if rho > 1e-12 { radial / rho } else { crate::plan::spec::perpendicular_pair(direction).0 };
                let dx = rho - radius;
                match length {
                    None => (dx, e_r),
                    Some(l) => {
                        let e_u = direction * u.signum();
                        let dy = u.abs() - l / 2.0;
                        corner_distance([dx, dy], [e_r, e_u])
                    }
                }
            }
            ObstacleShape::Box { centre, rotation, half } => {
                // local coordinates l = Rᵀ(p − c); per axis the excess |lᵢ| − hᵢ
                let l = rotation.transpose() * (p - centre);
                let (d, g) = box_distance(&l, half);
                (d, rotation * g)
            }
        }
    }
}

/// The signed distance of a point whose excesses over two (or three) orthogonal slabs are `q`, along unit
/// directions `e`: `‖max(q, 0)‖` outside, `max(q)` inside (the distance to a convex solid's surface).
fn corner_distance<const N: usize>(q: [f64; N], e: [Vec3; N]) -> (f64, Vec3) {
    let outside: f64 = q.iter().map(|x| x.max(0.0).powi(2)).sum::<f64>().sqrt();
    if outside > 0.0 {
        let g = (0..N).fold(Vec3::zeros(), |g, i| g + e[i] * (q[i].max(0.0) / outside));
        return (outside, g);
    }
    let i = (0..N).max_by(|&a, &b| q[a].total_cmp(&q[b])).unwrap_or(0);
    (q[i], e[i])
}

/// [`corner_distance`] for a box of half sizes `h`, at local point `l`; the gradient in local axes.
fn box_distance(l: &Vec3, h: &Vec3) -> (f64, Vec3) {
    let sign = |x: f64| if x < 0.0 { -1.0 } else { 1.0 };
    let q = [l.x.abs() - h.x, l.y.abs() - h.y, l.z.abs() - h.z];
    let e = [Vec3::x() * sign(l.x), Vec3::y() * sign(l.y), Vec3::z() * sign(l.z)];
    corner_distance(q, e)
}

/// Bisection steps on the derivative: the parameter to machine precision.
const BISECTIONS: usize = 60;

/// The signed distance between a capsule (world) and an obstacle: `min_t sd(a + t(b − a)) − r`.
/// `sd` is convex along the segment, so its derivative `∇sd·(b − a)` is non-decreasing in `t`: the end
/// whose derivative points outward, or the root of the derivative found by bisection.
pub fn capsule_obstacle(c: &Capsule, o: &ObstacleShape) -> Separation {
    let ab = c.b - c.a;
    let at = |t: f64| c.a + ab * t;
    let gradient = |t: f64| o.point_distance(&at(t)).1;
    let (t, n) = if gradient(0.0).dot(&ab) >= 0.0 {
        (0.0, gradient(0.0))
    } else if gradient(1.0).dot(&ab) <= 0.0 {
        (1.0, gradient(1.0))
    } else {
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (lo + hi);
            if gradient(mid).dot(&ab) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        // Inside a box or a finite cylinder `sd` has creases (where the nearest face changes): a minimum
        // on one is where the faces' gradients n₋, n₊ balance, and ∂d/∂p = λn₋ + (1 − λ)n₊ with
        // λ(n₋·ab) + (1 − λ)(n₊·ab) = 0. Where `sd` is smooth n₋ = n₊ and this is ∇sd.
        let (n_lo, n_hi) = (gradient(lo), gradient(hi));
        let (s_lo, s_hi) = (n_lo.dot(&ab), n_hi.dot(&ab));
        let lambda = if s_hi - s_lo > 0.0 { s_hi / (s_hi - s_lo) } else { 0.5 };
        (0.5 * (lo + hi), n_lo * lambda + n_hi * (1.0 - lambda))
    };
    let p = at(t);
    let (sd, surface_normal) = o.point_distance(&p);
    Separation { distance: sd - c.radius, on_a: p, on_b: p - surface_normal * sd, normal: n }
}

/// A rotation from angles about the world x, then y, then z axes (degrees): `R = R_z R_y R_x`.
pub fn rotation_xyz_degrees(angles: &[f64; 3]) -> Mat3 {
    let [x, y, z] = angles.map(f64::to_radians);
    let r = |axis: Vec3, a: f64| *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), a).matrix();
    r(Vec3::z(), z) * r(Vec3::y(), y) * r(Vec3::x(), x)
}
