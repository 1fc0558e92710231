//! The distance between two capsules: exact (the closest points of their segments), and rounded where the
//! segments turn parallel — the planner's rows read the rounded one.

use super::{Capsule, Separation};
use crate::spatial::Vec3;

/// The signed distance between two capsules (world): `‖p_a − p_b‖ − r_a − r_b`, `p_a`, `p_b` the closest
/// points of the segments (Ericson, *Real-Time Collision Detection*, 5.1.9; parallel segments take the
/// end of the overlap nearest `a`'s first end). Crossing axes (`p_a = p_b`) take `n` across both axes.
pub fn capsule_capsule(c1: &Capsule, c2: &Capsule) -> Separation {
    let (s, t) = closest_parameters(c1, c2);
    let p1 = c1.a + (c1.b - c1.a) * s;
    let p2 = c2.a + (c2.b - c2.a) * t;
    let gap = p1 - p2;
    let len = gap.norm();
    let normal = if len > 1e-12 { gap / len } else { across(c1.b - c1.a, c2.b - c2.a) };
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

/// The rounding of [`capsule_capsule_rounded`]: `ε = ROUNDING·(r_a + r_b)²`.
pub const ROUNDING: f64 = 0.01;

/// The signed distance between two capsules (world), rounded where their segments turn parallel — the
/// distance of the planner's collision rows (`plan/transcription/collision.rs`).
///
/// The exact distance [`capsule_capsule`] is kinked where two segments pass through parallel: the closest
/// points jump from one end of the overlap to the other, `d ≈ h − ½L|θ|`, and a Newton step across the kink
/// is predicted from the wrong side (the weight lift's palms against its thighs stalled an interior point
/// for hundreds of steps). Here the closest points minimise, over `(s, t) ∈ [0, 1]²`,
///
/// ```text
///   V(s, t) = ‖p_a(s) − p_b(t)‖² + ε((s − ½)² + (t − ½)² − ½),      ε = ROUNDING·(r_a + r_b)²
/// ```
///
/// strictly convex, so the minimiser is unique and moves continuously, and `V* = min V` is continuously
/// differentiable with the envelope theorem's gradient `2(p_a − p_b)ᵀ(∂p_a − ∂p_b)` at the minimiser
/// (the regulariser does not depend on the geometry). The shift `−½ε` makes `V* ≤ ‖p_a − p_b‖²_min`
/// (the bracket is at most ½ on the square): the rounded distance `√V* − r_a − r_b` never exceeds the exact
/// one, and falls short of it by `≤ ε/(4g)` at an axis gap `g` — a quarter of a per cent of `r_a + r_b` where
/// the capsules touch. `normal` is `(p_a − p_b)/√V*` (a little longer than a unit vector), so that
/// `∂d/∂p_a = normal` stays the exact gradient. Below `V* = ε` (the axes nearly meeting, a deep
/// penetration) `√V` continues by the quadratic `V(3 − V/ε)/(2√ε)`, which meets it with its slope at `ε`,
/// stays below it (and below the exact distance) and keeps the gradient bounded by `2/√ε`.
pub fn capsule_capsule_rounded(c1: &Capsule, c2: &Capsule) -> Separation {
    let (d1, d2, r) = (c1.b - c1.a, c2.b - c2.a, c1.a - c2.a);
    // (a floor for capsules of no radius: the square's minimiser stays unique)
    let eps = (ROUNDING * (c1.radius + c2.radius).powi(2)).max(1e-12 * (d1.norm_squared() + d2.norm_squared() + 1e-12));
    let (s, t) = regularised_parameters(d1, d2, r, eps);
    let on_a = c1.a + d1 * s;
    let on_b = c2.a + d2 * t;
    let gap = on_a - on_b;
    // V* = ‖g‖² + ε((s − ½)² + (t − ½)² − ½)
    let v = gap.norm_squared() + eps * ((s - 0.5).powi(2) + (t - 0.5).powi(2) - 0.5);
    // √V for V ≥ ε, V(3 − V/ε)/(2√ε) below (C¹ at ε, under √V); ∂d/∂g = (∂d/∂V)·2g
    let (root, slope) = if v >= eps {
        (v.sqrt(), 0.5 / v.sqrt())
    } else {
        (v * (3.0 - v / eps) / (2.0 * eps.sqrt()), (1.5 - v / eps) / eps.sqrt())
    };
    let normal = if gap.norm() > 1e-12 { gap * (2.0 * slope) } else { across(d1, d2) };
    Separation { distance: root - c1.radius - c2.radius, on_a, on_b, normal }
}

/// The unique `(s, t) ∈ [0, 1]²` minimising `‖r + d₁s − d₂t‖² + ε((s − ½)² + (t − ½)²)`, `ε > 0`: the
/// stationary point if it lies in the square, else the least of the four edges' minimisers (a strictly
/// convex quadratic's minimum over a square is inside or on its boundary).
fn regularised_parameters(d1: Vec3, d2: Vec3, r: Vec3, eps: f64) -> (f64, f64) {
    let (a, b, e) = (d1.dot(&d1), d1.dot(&d2), d2.dot(&d2));
    let (c, f) = (d1.dot(&r), d2.dot(&r));
    // ∇ = 0: [a + ε, −b; −b, e + ε] (s, t) = (ε/2 − c, ε/2 + f); the determinant ≥ ε(a + e) + ε² > 0
    let (h_s, h_t, g_s, g_t) = (a + eps, e + eps, 0.5 * eps - c, 0.5 * eps + f);
    let det = h_s * h_t - b * b;
    let (s, t) = ((h_t * g_s + b * g_t) / det, (b * g_s + h_s * g_t) / det);
    if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
        return (s, t);
    }
    let value = |s: f64, t: f64| (r + d1 * s - d2 * t).norm_squared() + eps * ((s - 0.5).powi(2) + (t - 0.5).powi(2));
    // on an edge the other parameter minimises its one-dimensional quadratic, clamped
    [0.0, 1.0]
        .into_iter()
        .flat_map(|k: f64| [(k, ((b * k + g_t) / h_t).clamp(0.0, 1.0)), (((b * k + g_s) / h_s).clamp(0.0, 1.0), k)])
        .min_by(|p, q| value(p.0, p.1).total_cmp(&value(q.0, q.1)))
        .expect("four edges")
}

/// A unit vector across both segments (or across the first, when they are parallel): the normal where
/// the axes meet.
fn across(d1: Vec3, d2: Vec3) -> Vec3 {
    let n = d1.cross(&d2);
    if n.norm() > 1e-12 {
        n.normalize()
    } else {
        crate::plan::spec::perpendicular_pair(&(d1 + Vec3::new(0.0, 0.0, 1e-30)).normalize()).0
    }
}
