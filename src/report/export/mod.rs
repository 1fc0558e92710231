//! A planned motion in the formats other tools read: BVH (animation packages, Blender), glTF 2.0 binary
//! (viewers, game engines, the web), OpenSim's `.mot` (biomechanics) with the figure as an `.osim` model for it, and CSV (spreadsheets, scripts).
//! Each exporter takes the model and the [`PlanRecord`] of a plan directory and returns the file's name
//! and bytes; writing them is `crate::plan_dir`'s.

pub mod bvh;
pub mod csv;
pub mod gltf;
pub mod mot;

use super::record::PlanRecord;
use crate::dynamics::kinematics::joint_transform;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::spatial::Transform;

/// The export formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Biovision hierarchy (`.bvh`), Y up, metres.
    Bvh,
    /// glTF 2.0 binary (`.glb`): the figure as simple meshes, animated.
    Gltf,
    /// OpenSim motion file (`.mot`), joint angles in degrees.
    Mot,
    /// The trajectory as CSV (`.csv`): q, q̇, q̈ and τ of every joint.
    Csv,
    /// The plan's figure as an OpenSim model (`.osim`), coordinates named after the joints: the `.mot` plays
    /// on it.
    Osim,
}

impl Format {
    /// Every format, in the order the CLI lists them.
    pub const ALL: [Format; 5] = [Format::Bvh, Format::Gltf, Format::Mot, Format::Csv, Format::Osim];

    /// The format's name on the command line, also its file extension.
    pub fn name(&self) -> &'static str {
        match self {
            Format::Bvh => "bvh",
            Format::Gltf => "gltf",
            Format::Mot => "mot",
            Format::Csv => "csv",
            Format::Osim => "osim",
        }
    }

    /// The file extension written (`glb` for glTF: the binary container).
    pub fn extension(&self) -> &'static str {
        match self {
            Format::Gltf => "glb",
            other => other.name(),
        }
    }

    /// Every format's name, in [`Format::ALL`] order.
    pub fn names() -> [&'static str; 5] {
        Format::ALL.map(|f| f.name())
    }

    /// The format called `name` (case-insensitive; `glb` is taken for glTF). An unknown name is refused
    /// with the list of known ones.
    pub fn from_name(name: &str) -> Result<Format> {
        let wanted = name.trim().to_ascii_lowercase();
        if wanted == "glb" {
            return Ok(Format::Gltf);
        }
        Format::ALL.into_iter().find(|f| f.name() == wanted).ok_or_else(|| {
            Error::input("export", "format", format!("unknown format \"{name}\"; known: {}", Format::names().join(", ")))
        })
    }
}

impl std::fmt::Display for Format {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Format {
    type Err = Error;
    fn from_str(s: &str) -> Result<Format> {
        Format::from_name(s)
    }
}

/// The motion of `record` in `format`: the file name (the model's name with the format's extension) and
/// its bytes.
pub fn export(model: &Model, record: &PlanRecord, format: Format) -> Result<(String, Vec<u8>)> {
    super::check_samples(model, record)?;
    if record.samples.is_empty() {
        return Err(Error::input("plan.json", "samples", "the plan holds no samples to export"));
    }
    let bytes = match format {
        Format::Bvh => bvh::bvh(model, record)?.into_bytes(),
        Format::Gltf => gltf::glb(model, record)?,
        Format::Mot => mot::mot(model, record).into_bytes(),
        Format::Csv => csv::csv(model, record).into_bytes(),
        Format::Osim => crate::model::osim::to_osim(model).into_bytes(),
    };
    Ok((format!("{}.{}", file_stem(&record.model_name), format.extension()), bytes))
}

/// A model name fit for a file name: anything but letters, digits, `-` and `_` becomes `_`.
fn file_stem(name: &str) -> String {
    let stem: String = name.chars().map(|c| if c.is_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect();
    if stem.is_empty() {
        "motion".into()
    } else {
        stem
    }
}

/// Every body's placement in the world at `q` (forward kinematics without the dynamics workspace).
pub(crate) fn body_placements(model: &Model, q: &[f64]) -> Vec<Transform> {
    let mut world = vec![Transform::IDENTITY; model.bodies.len()];
    for i in 1..model.joints.len() {
        let j = &model.joints[i];
        world[i] = world[j.parent].compose(&j.placement).compose(&joint_transform(j.kind, &j.axis, q[i - 1]));
    }
    world
}

/// Children of every body, in index order.
pub(crate) fn children(model: &Model) -> Vec<Vec<usize>> {
    let mut children = vec![Vec::new(); model.bodies.len()];
    for i in 1..model.joints.len() {
        children[model.joints[i].parent].push(i);
    }
    children
}
