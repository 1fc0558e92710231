//! Solid bodies: capsules (a segment swept by a sphere) on the figure's bodies, convex obstacles fixed in
//! the world (a plane, a cylinder, a box), and the signed distances between them with their witness
//! points — what the planner's collision rows (`plan/transcription/collision.rs`) and the posture checks
//! read. SI units (m) throughout.
//!
//! Every distance is `d = n·(p_a − p_b) − radii`, `p_a`, `p_b` the witness points, `n` the unit separation
//! direction (from `b` to `a`). For a convex pair the envelope theorem makes `∂d/∂q = nᵀ(J_a(p_a) −
//! J_b(p_b))` exact wherever the witnesses are unique: the derivative of the minimising parameter drops out.
//! Penetration gives a negative `d` (a signed distance), so values and gradients stay finite across contact.

mod shapes;

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
    /// two faces' normals that keeps the minimum (shorter than 1).
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

/// The signed distance between two capsules (world): `‖p_a − p_b‖ − r_a − r_b`, `p_a`, `p_b` the closest
/// points of the segments (Ericson, *Real-Time Collision Detection*, 5.1.9; parallel segments take the
/// end of the overlap nearest `a`'s first end). Crossing axes (`p_a = p_b`) take `n` across both axes.
pub fn capsule_capsule(c1: &Capsule, c2: &Capsule) -> Separation {
    let (s, t) = closest_parameters(c1, c2);
    let p1 = c1.a + (c1.b - c1.a) * s;
    let p2 = c2.a + (c2.b - c2.a) * t;
    let gap = p1 - p2;
    let len = gap.norm();
    let normal = if len > 1e-12 {
        gap / len
    } else {
        let across = (c1.b - c1.a).cross(&(c2.b - c2.a));
        if across.norm() > 1e-12 {
            across.normalize()
        } else {
            crate::plan::spec::perpendicular_pair(&(c1.b - c1.a + Vec3::new(0.0, 0.0, 1e-30)).normalize()).0
        }
    };
    Separation { distance: len - c1.radius - c2.radius, on_a: p1, on_b: p2, normal }
}

/// The parameters `(s, t) ∈ [0, 1]²` of the closest points of two segments.
fn closest_parameters(c1: &Capsule, c2: &Capsule) -> (f64, f64) {
    let (d1, d2, r) = (c1.b - c1.a, c2.b - c2.a, c1.a - c2.a);
    let (a, e, f) = (d1.norm_squared(), d2.norm_squared(), d2.dot(&r));
    const TINY: f64 = 1e-24;
    if a <= TINY && e <= TINY {
        return (0.0, 0.0);
    }
    if a <= TINY {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(&r);
    if e <= TINY {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(&d2);
    // s minimises over the infinite lines (0 when parallel), then t follows, then s is re-clamped.
    let denom = a * e - b * b;
    let mut s = if denom > 1e-12 * a * e { ((b * f - c * e) / denom).clamp(0.0, 1.0) } else { 0.0 };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// A rotation from angles about the world x, then y, then z axes (degrees): `R = R_z R_y R_x`.
pub fn rotation_xyz_degrees(angles: &[f64; 3]) -> Mat3 {
    let [x, y, z] = angles.map(f64::to_radians);
    let r = |axis: Vec3, a: f64| *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), a).matrix();
    r(Vec3::z(), z) * r(Vec3::y(), y) * r(Vec3::x(), x)
}
