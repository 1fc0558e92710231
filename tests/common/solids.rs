//! Solids for the collision and distance tests: random capsules and one obstacle of every kind.

use super::Rng;
use mintorque::geometry::{rotation_xyz_degrees, Capsule, Obstacle, ObstacleShape};
use mintorque::spatial::Vec3;

/// A capsule with both ends uniform in `±spread` (m) on each axis and a radius of 1–10 cm.
pub fn random_capsule(rng: &mut Rng, spread: f64) -> Capsule {
    let v = |rng: &mut Rng| Vec3::new(rng.uniform(-spread, spread), rng.uniform(-spread, spread), rng.uniform(-spread, spread));
    Capsule { a: v(rng), b: v(rng), radius: rng.uniform(0.01, 0.1) }
}

/// One obstacle of every kind (an infinite and a finite cylinder, a rotated box, a tilted plane).
pub fn obstacles() -> Vec<Obstacle> {
    let shapes = [
        ObstacleShape::Plane { point: Vec3::new(0.0, 0.0, -0.9), normal: Vec3::new(0.1, -0.2, 1.0).normalize() },
        ObstacleShape::Cylinder {
            point: Vec3::new(0.1, 0.0, 0.2),
            direction: Vec3::new(0.3, 1.0, 0.1).normalize(),
            radius: 0.03,
            length: None,
        },
        ObstacleShape::Cylinder {
            point: Vec3::new(-0.2, 0.3, -0.1),
            direction: Vec3::new(1.0, 0.2, -0.4).normalize(),
            radius: 0.12,
            length: Some(0.4),
        },
        ObstacleShape::Box {
            centre: Vec3::new(0.3, -0.2, 0.1),
            rotation: rotation_xyz_degrees(&[20.0, -35.0, 50.0]),
            half: Vec3::new(0.2, 0.1, 0.15),
        },
    ];
    shapes.into_iter().enumerate().map(|(k, shape)| Obstacle { name: format!("o{k}"), shape, zone: false }).collect()
}
