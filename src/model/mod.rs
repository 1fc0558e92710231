//! What a figure is: a kinematic tree of rigid bodies joined by one-degree-of-freedom joints, with named
//! frames on the bodies. A model is immutable once built and shared by every evaluation; scratch space
//! for one evaluation lives in [`crate::dynamics::Data`].
//!
//! Indexing follows Pinocchio: body 0 is the root, welded to the world; body `i ≥ 1` is moved by joint `i`
//! relative to body `parent(i) < i` (the paper's `i.parent`), and joint `i` owns degree of freedom
//! `i − 1` of `q`, `q̇`, `q̈` and `τ`. Fixed joints are merged away when a model is built (their links
//! become frames); multi-DOF anatomical joints (the paper's shoulder `Rot(z)·Rot(y)·Rot(x)`) expand into
//! a chain of revolutes joined by massless bodies, each revolute remembering its anatomical `group`.
//! Closed loops are cut open here and closed again by constraints in the planner.

pub mod collision;
pub mod figure;
pub mod floating;
pub mod human;
pub mod lock;
pub mod mjcf;
pub mod osim;
pub mod strength;
pub mod toml_doc;
pub mod urdf;
pub mod urdf_export;
pub mod validate;
pub mod xml;

use crate::error::{Error, Result};
use crate::spatial::{Inertia, Transform, Vec3};
use std::path::Path;

/// Reads a model file of any format, chosen by extension: `.urdf` for URDF, `.xml` for URDF or MuJoCo's
/// MJCF (by the root element, `<robot>` or `<mujoco>`), `.toml` for a figure file (`docs/figure-file.md`),
/// `.osim` for OpenSim (uncoupled models only, [`osim::load_model`]). What an MJCF file has and the model
/// does not is printed on stderr as warnings.
pub fn load_any(path: &Path) -> Result<Model> {
    load_any_with(path, urdf::Options::default())
}

/// [`load_any`] with the URDF reader's options (`<mimic>`); a figure file has nothing they apply to.
pub fn load_any_with(path: &Path, options: urdf::Options) -> Result<Model> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("xml") if is_mjcf(path) => {
            let import = mjcf::load(path)?;
            for w in &import.warnings {
                eprintln!("warning: {w}");
            }
            Ok(import.model)
        }
        Some("urdf" | "xml") => urdf::load_with(path, options),
        Some("toml") => figure::load(path),
        Some("osim") => osim::load_model(path),
        other => Err(Error::model(
            path.display().to_string(),
            "file name",
            format!(
                "cannot tell the model format from the extension {}: use .urdf or .xml for URDF, .xml for MJCF, .toml for a figure file, .osim for OpenSim",
                other.map_or("(none)".to_string(), |e| format!(".{e}"))
            ),
        )),
    }
}

/// Whether the XML file at `path` is MJCF (root element `<mujoco>`); unreadable or malformed files are left
/// to the URDF reader to report.
fn is_mjcf(path: &Path) -> bool {
    let Ok(text) = std::fs::read_to_string(path) else { return false };
    roxmltree::Document::parse(&text).is_ok_and(|d| d.root_element().tag_name().name() == "mujoco")
}

/// The motion a joint allows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// The root's pseudo-joint: no degree of freedom.
    Root,
    /// Rotation about `axis` (rad).
    Revolute,
    /// Translation along `axis` (m).
    Prismatic,
}

/// Position, velocity and effort limits of one joint. SI units (rad or m, rad/s or m/s, N·m or N);
/// an absent limit is infinite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimits {
    /// Lower position limit (rad or m).
    pub lower: f64,
    /// Upper position limit (rad or m).
    pub upper: f64,
    /// Joint velocity limit (rad/s or m/s).
    pub velocity: f64,
    /// Effort limit `|τ| ≤ effort` (N·m or N), both directions unless one is given below.
    pub effort: f64,
    /// Effort limit along `+axis`, `τ ≤ effort_positive` (N·m or N; `None`: `effort`). A flexor and its
    /// extensor differ.
    pub effort_positive: Option<f64>,
    /// Effort limit along `−axis`, `−τ ≤ effort_negative` (N·m or N, a magnitude; `None`: `effort`).
    pub effort_negative: Option<f64>,
}

impl JointLimits {
    /// The effort limit along `+axis` (`positive`) or `−axis`, as a magnitude (N·m or N).
    pub fn effort_toward(&self, positive: bool) -> f64 {
        let given = if positive { self.effort_positive } else { self.effort_negative };
        given.unwrap_or(self.effort)
    }

    /// The larger of the two directions' effort limits (N·m or N).
    pub fn effort_max(&self) -> f64 {
        self.effort_toward(true).max(self.effort_toward(false))
    }
}

impl Default for JointLimits {
    fn default() -> Self {
        JointLimits {
            lower: f64::NEG_INFINITY,
            upper: f64::INFINITY,
            velocity: f64::INFINITY,
            effort: f64::INFINITY,
            effort_positive: None,
            effort_negative: None,
        }
    }
}

/// The passive "resistant torque" of a joint (paper section 7.2): a torsional spring towards `rest`
/// and a viscous damper, `τ_passive = −stiffness·(q − rest) − damping·q̇`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Passive {
    /// N·m/rad (or N/m for a prismatic joint).
    pub stiffness: f64,
    /// rad (or m).
    pub rest: f64,
    /// N·m·s/rad (or N·s/m).
    pub damping: f64,
}

impl Passive {
    /// Whether neither spring nor damper acts.
    pub fn is_zero(&self) -> bool {
        self.stiffness == 0.0 && self.damping == 0.0
    }

    /// The passive generalised force at `(q, q̇)`.
    #[inline]
    pub fn torque(&self, q: f64, qd: f64) -> f64 {
        -self.stiffness * (q - self.rest) - self.damping * qd
    }
}

/// A joint: how body `i` moves relative to its parent (one degree of freedom, or the root).
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// The joint's name, as in the model file.
    pub name: String,
    /// Revolute, prismatic, or the root pseudo-joint.
    pub kind: JointKind,
    /// Index of the body this joint hangs from (`parent(i) < i`).
    pub parent: usize,
    /// The joint frame in the parent body's frame at `q = 0` (the paper's `Dᵢ` of eq. 17, with any
    /// constant rotation folded in).
    pub placement: Transform,
    /// Unit axis in the joint frame.
    pub axis: Vec3,
    /// Position, velocity and effort limits.
    pub limits: JointLimits,
    /// The joint's spring and damper (paper section 7.2).
    pub passive: Passive,
    /// The anatomical joint this revolute belongs to (`"shoulder"` for `shoulder_z`), if any.
    pub group: Option<String>,
}

/// Simple shapes for drawing a body (body frame, SI units). They play no part in the dynamics.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A box centred at `origin`, with full edge lengths `size`.
    Box {
        /// Placement of the box's centre and axes.
        origin: Transform,
        /// Full edge lengths (m).
        size: Vec3,
    },
    /// A cylinder along the local z axis of `origin`, centred there.
    Cylinder {
        /// Placement of the cylinder's centre; its axis is local z.
        origin: Transform,
        /// Radius (m).
        radius: f64,
        /// Length (m).
        length: f64,
    },
    /// A capsule from point `a` to point `b`.
    Capsule {
        /// One end (m, body frame).
        a: Vec3,
        /// The other end (m, body frame).
        b: Vec3,
        /// Radius (m).
        radius: f64,
    },
    /// A sphere.
    Sphere {
        /// Centre (m, body frame).
        center: Vec3,
        /// Radius (m).
        radius: f64,
    },
}

impl Shape {
    /// This shape (given in the child frame of `x`) in the parent frame of `x`.
    pub fn transformed(&self, x: &Transform) -> Shape {
        match self {
            Shape::Box { origin, size } => Shape::Box { origin: x.compose(origin), size: *size },
            Shape::Cylinder { origin, radius, length } => {
                Shape::Cylinder { origin: x.compose(origin), radius: *radius, length: *length }
            }
            Shape::Capsule { a, b, radius } => Shape::Capsule { a: x.act_point(a), b: x.act_point(b), radius: *radius },
            Shape::Sphere { center, radius } => Shape::Sphere { center: x.act_point(center), radius: *radius },
        }
    }
}

/// A rigid body moved by `joints[i]`, with the links merged into it by fixed joints.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// The link's name (for merged links, the name of the link that carries the joint).
    pub name: String,
    /// Mass properties in the body frame, including every link merged into it by fixed joints.
    pub inertia: Inertia,
    /// Shapes to draw it with.
    pub shapes: Vec<Shape>,
}

/// A named frame on a body: a link merged by a fixed joint, a hand, a foot, a barbell grip.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The frame's name (a link name, `hand_l`, `grip` …).
    pub name: String,
    /// Index of the body it is fixed to.
    pub body: usize,
    /// The frame in the body's frame.
    pub placement: Transform,
    /// `Some(name)` when the frame is the origin of a rigid part welded onto the body (a fixed joint's
    /// link, a WeldJoint's body, a segment of a built-in human's lumped body), hanging from the body or
    /// the part (frame) named; `None` for a mere point (a marker, a hand, a site). Exports that draw a
    /// skeleton (BVH) draw the parts as joints of their own.
    pub welded_to: Option<String>,
}

/// An articulated figure: a tree of bodies connected by one-degree-of-freedom joints, in topological order
/// (every parent before its children).
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// The model's name (the URDF's robot name, the figure's or the built-in's).
    pub name: String,
    /// `joints[0]` is the root pseudo-joint; `joints[i]` moves `bodies[i]`.
    pub joints: Vec<Joint>,
    /// `bodies[i]` is moved by `joints[i]`; `bodies[0]` is the fixed root.
    pub bodies: Vec<Body>,
    /// Named frames, for contacts, loads and payloads.
    pub frames: Vec<Frame>,
    /// Default gravity in the world frame (m/s²); tasks may override it.
    pub gravity: Vec3,
    /// Collision capsules given by the model file (body name → capsules, body frame); a body not listed
    /// takes them from its drawing shapes ([`Model::collision_capsules`]).
    pub collision: std::collections::BTreeMap<String, Vec<crate::geometry::Capsule>>,
}

impl Model {
    /// An empty model: just the root body, welded to the world.
    pub fn new(name: impl Into<String>, root_name: impl Into<String>) -> Self {
        let root_name = root_name.into();
        Model {
            name: name.into(),
            joints: vec![Joint {
                name: "universe".into(),
                kind: JointKind::Root,
                parent: 0,
                placement: Transform::IDENTITY,
                axis: Vec3::zeros(),
                limits: JointLimits::default(),
                passive: Passive::default(),
                group: None,
            }],
            bodies: vec![Body { name: root_name.clone(), inertia: Inertia::ZERO, shapes: vec![] }],
            frames: vec![Frame { name: root_name, body: 0, placement: Transform::IDENTITY, welded_to: None }],
            gravity: Vec3::new(0.0, 0.0, -9.81),
            collision: Default::default(),
        }
    }

    /// Appends a body moved by a 1-DOF joint; returns its index. The body's own frame is added under the
    /// body's name. Callers must add parents before children (validated by [`Model::validate`]).
    pub fn add_body(&mut self, joint: Joint, body: Body) -> usize {
        let i = self.bodies.len();
        self.frames.push(Frame { name: body.name.clone(), body: i, placement: Transform::IDENTITY, welded_to: None });
        self.joints.push(joint);
        self.bodies.push(body);
        i
    }

    /// Appends an anatomical joint of several rotations applied in order (the paper's shoulder
    /// `Rot(z)·Rot(y)·Rot(x)`, Table I): one revolute per axis, named `{name}_{label}`, joined by massless
    /// bodies named `{name}_{label}` too, the last one carrying `body`. Each revolute's `group` is `name`.
    /// `axes` are `(label, unit axis in the joint frame, limits, passive)`. Returns the index of `body`.
    pub fn add_anatomical_joint(
        &mut self,
        name: &str,
        parent: usize,
        placement: Transform,
        axes: &[(&str, Vec3, JointLimits, Passive)],
        body: Body,
    ) -> usize {
        let mut parent = parent;
        let mut placement = placement;
        let mut body = Some(body);
        for (k, (label, axis, limits, passive)) in axes.iter().enumerate() {
            let joint_name = format!("{name}_{label}");
            let joint = Joint {
                name: joint_name.clone(),
                kind: JointKind::Revolute,
                parent,
                placement,
                axis: *axis,
                limits: *limits,
                passive: *passive,
                group: Some(name.to_string()),
            };
            let b = if k + 1 == axes.len() {
                body.take().expect("last axis carries the body")
            } else {
                Body { name: joint_name, inertia: Inertia::ZERO, shapes: vec![] }
            };
            parent = self.add_body(joint, b);
            placement = Transform::IDENTITY;
        }
        parent
    }

    /// Number of degrees of freedom (`nq = nv`).
    #[inline]
    pub fn nv(&self) -> usize {
        self.joints.len() - 1
    }

    /// The DOFs torque `τ_i` can depend on, ascending: those on the root path of DOF `i`'s joint and in its
    /// subtree (RNEA: `τ_i = S_iᵀ Σ_{b ∈ subtree(i)} f_b`, each `f_b` a function of the joints from the root
    /// to `b`; loads at a body point add `J_bᵀ f` along the same path).
    pub fn torque_dofs(&self, i: usize) -> Vec<usize> {
        let related = |j: usize| self.is_ancestor_or_self(i + 1, j + 1) || self.is_ancestor_or_self(j + 1, i + 1);
        (0..self.nv()).filter(|&j| related(j)).collect()
    }

    /// The body `joints[i]` hangs from.
    #[inline]
    pub fn parent(&self, i: usize) -> usize {
        self.joints[i].parent
    }

    /// Names of the DOF joints, in `q` order.
    pub fn joint_names(&self) -> Vec<&str> {
        self.joints[1..].iter().map(|j| j.name.as_str()).collect()
    }

    /// The `q` index of the joint called `name`.
    pub fn dof_index(&self, name: &str) -> Option<usize> {
        self.joints[1..].iter().position(|j| j.name == name)
    }

    /// The index in `frames` of the frame called `name`.
    pub fn frame_index(&self, name: &str) -> Option<usize> {
        self.frames.iter().position(|f| f.name == name)
    }

    /// The index in `bodies` of the body called `name`.
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// Total mass, the root's included.
    pub fn total_mass(&self) -> f64 {
        self.bodies.iter().map(|b| b.inertia.mass).sum()
    }

    /// Whether body `k` is `i` or one of its ancestors (`k ⪯ i`).
    pub fn is_ancestor_or_self(&self, k: usize, mut i: usize) -> bool {
        while i > k {
            i = self.joints[i].parent;
        }
        i == k
    }

    /// Lower and upper position limits as vectors.
    pub fn position_limits(&self) -> (Vec<f64>, Vec<f64>) {
        self.joints[1..].iter().map(|j| (j.limits.lower, j.limits.upper)).unzip()
    }
}
