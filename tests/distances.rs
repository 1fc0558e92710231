//! Signed distances between solids (`mintorque::geometry`): capsules against obstacles and against each
//! other by brute force, known cases, and the planner's rounded capsule distance — never above the exact
//! one, short of it by at most its bound, and without the exact one's kink where two segments turn parallel.

mod common;

use common::solids::{obstacles, random_capsule};
use common::Rng;
use mintorque::geometry::{
    capsule_capsule, capsule_capsule_rounded, capsule_obstacle, rotation_xyz_degrees, Capsule, ObstacleShape, ROUNDING,
};
use mintorque::spatial::Vec3;

/// `min_t sd(a + t(b − a)) − r` by sampling `t` finely.
fn brute_capsule_obstacle(c: &Capsule, o: &ObstacleShape) -> f64 {
    let n = 20_000;
    (0..=n).map(|k| o.point_distance(&(c.a + (c.b - c.a) * (k as f64 / n as f64))).0).fold(f64::INFINITY, f64::min) - c.radius
}

#[test]
fn capsule_obstacle_distances_match_brute_force() {
    let mut rng = Rng(3);
    for o in obstacles() {
        for _ in 0..200 {
            let c = random_capsule(&mut rng, 0.6);
            let sep = capsule_obstacle(&c, &o.shape);
            let brute = brute_capsule_obstacle(&c, &o.shape);
            // Sampling misses the least value by at most a step times the slope (|∇sd| = 1).
            let step = (c.b - c.a).norm() / 20_000.0;
            assert!(sep.distance <= brute + 1e-12, "{}: {} by bisection, {brute} by sampling", o.name, sep.distance);
            assert!(sep.distance > brute - step - 1e-12, "{}: {} by bisection, {brute} by sampling", o.name, sep.distance);
            // The witnesses: on the obstacle's surface, |d + r| apart.
            assert!(o.shape.point_distance(&sep.on_b).0.abs() < 1e-9);
            assert!(((sep.on_a - sep.on_b).norm() - (sep.distance + c.radius).abs()).abs() < 1e-9);
        }
    }
}

#[test]
fn point_distances_of_known_cases() {
    let floor = ObstacleShape::Plane { point: Vec3::zeros(), normal: Vec3::z() };
    let bar = ObstacleShape::Cylinder { point: Vec3::zeros(), direction: Vec3::y(), radius: 0.02, length: Some(1.0) };
    let table = ObstacleShape::Box {
        centre: Vec3::zeros(),
        rotation: rotation_xyz_degrees(&[0.0, 0.0, 90.0]),
        half: Vec3::new(0.5, 0.2, 0.1),
    };
    let cases = [
        (&floor, Vec3::new(3.0, -2.0, 0.25), 0.25),
        (&floor, Vec3::new(0.0, 0.0, -0.1), -0.1),
        (&bar, Vec3::new(0.0, 0.3, 0.12), 0.10),
        (&bar, Vec3::new(0.0, 0.8, 0.0), 0.3),      // beyond the end cap
        (&bar, Vec3::new(0.0, 0.0, 0.005), -0.015), // inside, nearest the side
        (&table, Vec3::new(0.0, 0.0, 0.3), 0.2),
        (&table, Vec3::new(0.3, 0.0, 0.0), 0.1), // turned 90° about z: the 0.2 half-width along x
        (&table, Vec3::new(0.0, 0.45, 0.05), -0.05), // inside, nearest the top
    ];
    for (shape, p, want) in cases {
        let (d, n) = shape.point_distance(&p);
        assert!((d - want).abs() < 1e-12, "{shape:?} at {p:?}: {d}, want {want}");
        assert!((n.norm() - 1.0).abs() < 1e-12);
    }
}

#[test]
fn capsule_capsule_distances_match_brute_force_with_parallel_and_crossing_segments() {
    let mut rng = Rng(5);
    let mut cases: Vec<(Capsule, Capsule)> =
        (0..60).map(|_| (random_capsule(&mut rng, 0.5), random_capsule(&mut rng, 0.5))).collect();
    let seg = |a: [f64; 3], b: [f64; 3]| Capsule { a: Vec3::from(a), b: Vec3::from(b), radius: 0.05 };
    cases.push((seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), seg([0.5, 0.3, 0.0], [1.5, 0.3, 0.0]))); // parallel, overlapping
    cases.push((seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), seg([2.0, 0.3, 0.0], [3.0, 0.3, 0.0]))); // parallel, apart
    cases.push((seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), seg([0.5, -0.5, 0.0], [0.5, 0.5, 0.0]))); // crossing
    cases.push((seg([0.2, 0.1, 0.0], [0.2, 0.1, 0.0]), seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]))); // a sphere
    for (c1, c2) in cases {
        let sep = capsule_capsule(&c1, &c2);
        let n = 1500;
        let mut brute = f64::INFINITY;
        for i in 0..=n {
            let p = c1.a + (c1.b - c1.a) * (i as f64 / n as f64);
            for j in 0..=n {
                brute = brute.min((p - (c2.a + (c2.b - c2.a) * (j as f64 / n as f64))).norm());
            }
        }
        brute -= c1.radius + c2.radius;
        assert!((sep.distance - brute).abs() < 2e-3 * (c1.b - c1.a).norm().max(0.1), "{}, brute {brute}", sep.distance);
        assert!(sep.distance <= brute + 1e-12, "closest points not closest: {} > {brute}", sep.distance);
        assert!(sep.normal.iter().all(|x| x.is_finite()) && (sep.normal.norm() - 1.0).abs() < 1e-12);
    }
}

/// The rounding of a pair: `ε = ROUNDING (r_a + r_b)²` (m²).
fn rounding(c1: &Capsule, c2: &Capsule) -> f64 {
    ROUNDING * (c1.radius + c2.radius).powi(2)
}

#[test]
fn rounded_distances_never_exceed_the_exact_and_fall_short_by_at_most_their_bound() {
    let mut rng = Rng(11);
    let mut cases: Vec<(Capsule, Capsule)> =
        (0..400).map(|_| (random_capsule(&mut rng, 0.5), random_capsule(&mut rng, 0.5))).collect();
    let seg = |a: [f64; 3], b: [f64; 3]| Capsule { a: Vec3::from(a), b: Vec3::from(b), radius: 0.05 };
    cases.push((seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), seg([0.5, 0.3, 0.0], [1.5, 0.3, 0.0]))); // parallel, overlapping
    cases.push((seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), seg([2.0, 0.3, 0.0], [3.0, 0.3, 0.0]))); // parallel, apart
    cases.push((seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), seg([0.5, -0.5, 0.2], [0.5, 0.5, 0.2]))); // crossing
    cases.push((seg([0.2, 0.1, 0.0], [0.2, 0.1, 0.0]), seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]))); // a sphere
    cases.push((seg([0.2, 0.1, 0.0], [0.2, 0.1, 0.0]), seg([0.2, 0.3, 0.0], [0.2, 0.3, 0.0]))); // two spheres
    cases.push((seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), seg([0.5, -0.5, 0.001], [0.5, 0.5, 0.001]))); // axes 1 mm apart
    cases.push((seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), seg([0.5, -0.5, 0.0], [0.5, 0.5, 0.0]))); // axes crossing
    let mut checked = 0;
    for (c1, c2) in cases {
        let (exact, rounded) = (capsule_capsule(&c1, &c2), capsule_capsule_rounded(&c1, &c2));
        let gap = exact.distance + c1.radius + c2.radius;
        let eps = rounding(&c1, &c2);
        assert!(rounded.distance.is_finite() && rounded.normal.iter().all(|x| x.is_finite()));
        // |∂d/∂p_a| ≤ √(3/2) where √V* is used, ≤ 2√(3/2) · 2 below ε: bounded even where the axes meet.
        assert!(rounded.normal.norm() <= 5.0, "a gradient of {}", rounded.normal.norm());
        // Never above the exact distance, deep inside each other too.
        let short = exact.distance - rounded.distance;
        assert!(short >= -1e-12, "{c1:?} {c2:?}: {} exact, {} rounded", exact.distance, rounded.distance);
        // Outside a deep penetration (`V* ≥ ε`), below it by `g − √(g² − ε/2)` at most.
        if gap * gap >= 1.5 * eps {
            let bound = gap - (gap * gap - 0.5 * eps).sqrt();
            assert!(short <= bound + 1e-12, "{c1:?} {c2:?}: {} exact, {} rounded", exact.distance, rounded.distance);
            assert!(bound <= 0.3 * eps / gap);
            checked += 1;
        }
    }
    assert!(checked > 300, "{checked} pairs outside the deep branch");
}

/// Segment `a` along x through the origin (0.4 m); segment `b` the same, `h` above it in y, turned by `θ`
/// about z (rad); radii 5 cm each. Returns the distance and its derivative along `θ` by the separation's
/// normal (`∂d/∂θ = n·(∂p_a/∂θ − ∂p_b/∂θ)`, `∂p_b/∂θ = ẑ × (p_b − pivot)`).
fn turned_pair(distance: fn(&Capsule, &Capsule) -> mintorque::geometry::Separation, theta: f64) -> (f64, f64) {
    let h = 0.15;
    let a = Capsule { a: Vec3::new(-0.2, 0.0, 0.0), b: Vec3::new(0.2, 0.0, 0.0), radius: 0.05 };
    let pivot = Vec3::new(0.0, h, 0.0);
    let end = Vec3::new(0.2 * theta.cos(), 0.2 * theta.sin(), 0.0);
    let b = Capsule { a: pivot - end, b: pivot + end, radius: 0.05 };
    let sep = distance(&a, &b);
    (sep.distance, -sep.normal.dot(&Vec3::z().cross(&(sep.on_b - pivot))))
}

#[test]
fn the_rounded_distance_has_no_kink_where_segments_turn_parallel_and_the_exact_one_does() {
    let step = 1e-6;
    // One-sided slopes at θ = 0, where the closest points jump from one end of the overlap to the other.
    let slopes = |distance: fn(&Capsule, &Capsule) -> mintorque::geometry::Separation| {
        let d = |t: f64| turned_pair(distance, t).0;
        ((d(0.0) - d(-step)) / step, (d(step) - d(0.0)) / step)
    };
    let (left, right) = slopes(capsule_capsule);
    // exact: d ≈ h − 0.2|θ| − 0.1, slopes ±0.2
    assert!((left - 0.2).abs() < 1e-3 && (right + 0.2).abs() < 1e-3, "exact slopes {left}, {right}");
    let (left, right) = slopes(capsule_capsule_rounded);
    assert!((left - right).abs() < 1e-3, "rounded slopes {left}, {right}: a kink");
    // The gradient the rows use is the derivative, through the rounded turn and beyond it.
    for theta in [-0.05, -3e-3, -1e-3, -2e-4, 0.0, 2e-4, 1e-3, 3e-3, 0.05] {
        let d = |t: f64| turned_pair(capsule_capsule_rounded, t).0;
        let fd = (d(theta + 1e-7) - d(theta - 1e-7)) / 2e-7;
        let (_, by_normal) = turned_pair(capsule_capsule_rounded, theta);
        assert!((fd - by_normal).abs() < 1e-6, "θ = {theta}: {by_normal} by the normal, {fd} by differences");
    }
    // Beyond the turn it is the exact distance's slope again.
    let (_, slope) = turned_pair(capsule_capsule_rounded, 0.05);
    assert!((slope + 0.2 * 0.05f64.cos()).abs() < 0.01, "{slope}");
}
