//! Solid bodies in the reports: the task's obstacles and the collision capsules of the bodies it keeps
//! off them, as `plan.json` records them, and as drawing shapes (world frame for obstacles, body frame for
//! capsules) the filmstrip and the 3D view draw.

use crate::geometry::{Obstacle, ObstacleShape};
use crate::model::Shape;
use crate::plan::{Collider, Spec};
use crate::spatial::{rotation_from_z, Mat3, Transform, Vec3};
use serde::{Deserialize, Serialize};

/// How long an infinite cylinder (a bar) is drawn (m).
pub const DRAWN_BAR_LENGTH: f64 = 1.0;

/// An obstacle as `plan.json` records it (m).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObstacleRecord {
    /// Its name.
    pub name: String,
    /// "plane", "cylinder" or "box".
    #[serde(rename = "type")]
    pub kind: String,
    /// Plane: a point on it; cylinder: a point on the axis (its centre when it has a length); box: centre.
    pub point: [f64; 3],
    /// Plane: the outward normal; cylinder: the axis direction; box: unused (zeros).
    pub axis: [f64; 3],
    /// Cylinder: radius.
    pub radius: Option<f64>,
    /// Cylinder: length (`None`: infinite).
    pub length: Option<f64>,
    /// Box: half edge lengths along its axes.
    pub half_size: Option<[f64; 3]>,
    /// Box: its axes in the world, as the rows of `Rᵀ` (the columns of `R`).
    pub axes: Option<[[f64; 3]; 3]>,
    /// A keep-out zone, drawn as an outline only (absent in older files: a solid).
    #[serde(default)]
    pub zone: bool,
}

/// A collision capsule of a body, body frame (m).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CapsuleRecord {
    /// The body's name.
    pub body: String,
    /// One end of the segment.
    pub a: [f64; 3],
    /// The other end.
    pub b: [f64; 3],
    /// Radius.
    pub radius: f64,
}

fn arr(v: &Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// The spec's obstacles, as recorded.
pub fn obstacle_records(spec: &Spec) -> Vec<ObstacleRecord> {
    let record = |o: &Obstacle, kind: &str, point: &Vec3, axis: Vec3| ObstacleRecord {
        name: o.name.clone(),
        kind: kind.to_string(),
        point: arr(point),
        axis: arr(&axis),
        radius: None,
        length: None,
        half_size: None,
        axes: None,
        zone: o.zone,
    };
    let obstacles = spec.obstacles.iter();
    obstacles
        .map(|o| match &o.shape {
            ObstacleShape::Plane { point, normal } => record(o, "plane", point, *normal),
            ObstacleShape::Cylinder { point, direction, radius, length } => {
                ObstacleRecord { radius: Some(*radius), length: *length, ..record(o, "cylinder", point, *direction) }
            }
            ObstacleShape::Box { centre, rotation, half } => {
                let axes = [0, 1, 2].map(|i| arr(&rotation.column(i).into_owned()));
                ObstacleRecord { half_size: Some(arr(half)), axes: Some(axes), ..record(o, "box", centre, Vec3::zeros()) }
            }
        })
        .collect()
}

/// The collision capsules of every body a collision constraint names, as recorded.
pub fn capsule_records(spec: &Spec) -> Vec<CapsuleRecord> {
    let model = &spec.model;
    let mut bodies: Vec<usize> = spec
        .collisions
        .iter()
        .flat_map(|c| std::iter::once(c.body).chain(if let Collider::Body(b) = c.other { Some(b) } else { None }))
        .collect();
    bodies.sort_unstable();
    bodies.dedup();
    bodies
        .into_iter()
        .flat_map(|b| {
            model.collision_capsules(b).into_iter().map(move |c| CapsuleRecord {
                body: model.bodies[b].name.clone(),
                a: arr(&c.a),
                b: arr(&c.b),
                radius: c.radius,
            })
        })
        .collect()
}

impl ObstacleRecord {
    /// The obstacle as a drawing shape, world frame: a cylinder ([`DRAWN_BAR_LENGTH`] long when
    /// infinite) or a box; `None` for a plane (drawn as a floor line or a translucent sheet).
    pub fn drawing_shape(&self) -> Option<Shape> {
        let point = Vec3::from(self.point);
        match self.kind.as_str() {
            "cylinder" => {
                let axis = Vec3::from(self.axis);
                let axis = if axis.norm() > 1e-12 { axis.normalize() } else { Vec3::z() };
                Some(Shape::Cylinder {
                    origin: Transform::new(rotation_from_z(&axis), point),
                    radius: self.radius.unwrap_or(0.0),
                    length: self.length.unwrap_or(DRAWN_BAR_LENGTH),
                })
            }
            "box" => {
                let [x, y, z] = self.axes.unwrap_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).map(Vec3::from);
                let half = Vec3::from(self.half_size.unwrap_or_default());
                Some(Shape::Box { origin: Transform::new(Mat3::from_columns(&[x, y, z]), point), size: half * 2.0 })
            }
            _ => None,
        }
    }
}

impl CapsuleRecord {
    /// The capsule as a drawing shape, body frame.
    pub fn shape(&self) -> Shape {
        Shape::Capsule { a: Vec3::from(self.a), b: Vec3::from(self.b), radius: self.radius }
    }
}
