//! A planned motion in the formats other tools read: BVH (animation packages, Blender), glTF 2.0 binary
//! (viewers, game engines, the web), OpenSim's `.mot` (biomechanics) with the figure as an `.osim` model for it, and CSV (spreadsheets, scripts).
//! Each exporter takes the model and the [`PlanRecord`] of a plan directory and returns the file's name
//! and bytes; writing them is `crate::plan_dir`'s.

pub mod bvh;
pub mod csv;
pub mod gltf;
pub mod mot;
pub mod resample;

pub use bvh::ChannelSet;
pub(crate) use bvh::{euler_zxy_near, rest_offset, segments, Segment};
pub use csv::{AngleUnit, Column, CsvOptions};

use super::record::PlanRecord;
use crate::dynamics::kinematics::joint_transform;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::spatial::Transform;

/// The export formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Biovision hierarchy (`.bvh`), Y up, centimetres (or metres).
    Bvh,
    /// glTF 2.0 binary (`.glb`): the figure as simple rigid meshes and as one skinned mesh, animated.
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

/// The length unit of a BVH file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LengthUnit {
    /// Metres (`m`).
    Metre,
    /// Centimetres (`cm`),
    /// what BVH tools expect.
    #[default]
    Centimetre,
}

impl LengthUnit {
    /// `m` or `cm`.
    pub fn from_name(name: &str) -> Result<LengthUnit> {
        match name.trim() {
            "m" => Ok(LengthUnit::Metre),
            "cm" => Ok(LengthUnit::Centimetre),
            other => Err(Error::input("export", "units", format!("unknown length unit \"{other}\"; known: m, cm"))),
        }
    }
}

/// The exporters' options; each applies to the formats its field names.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Options {
    /// BVH: frames per second (`None`: the plan's sample rate).
    pub fps: Option<f64>,
    /// BVH: the length unit.
    pub length: LengthUnit,
    /// BVH: one channel per moving DOF or per joint.
    pub channels: ChannelSet,
    /// CSV: units, columns, joints and rate.
    pub csv: CsvOptions,
}

impl Options {
    /// The options as the command line names them: `units` m|cm, `channels` joint|dof, `angles`
    /// deg|rad, `columns` of q, qd, qdd, tau, force (empty: all).
    pub fn from_names(
        fps: Option<f64>,
        units: &str,
        channels: &str,
        angles: &str,
        columns: &[String],
        joints: Vec<String>,
        rate: Option<f64>,
    ) -> Result<Options> {
        let channels = match channels.trim() {
            "joint" => ChannelSet::PerJoint,
            "dof" => ChannelSet::PerDof,
            other => return Err(Error::input("export", "channels", format!("\"{other}\"; known: joint, dof"))),
        };
        let angles = match angles.trim() {
            "deg" => AngleUnit::Degree,
            "rad" => AngleUnit::Radian,
            other => return Err(Error::input("export", "angles", format!("\"{other}\"; known: deg, rad"))),
        };
        let mut picked: Vec<Column> = columns.iter().map(|c| Column::from_name(c)).collect::<Result<_>>()?;
        if picked.is_empty() {
            picked = Column::ALL.to_vec();
        }
        // Written in the file's order whatever the order given: equal sets are equal options.
        let columns = Column::ALL.into_iter().filter(|c| picked.contains(c)).collect();
        let csv = CsvOptions { angles, columns, joints, rate };
        Ok(Options { fps, length: LengthUnit::from_name(units)?, channels, csv })
    }

    /// Refuses options given for a format they do not apply to, naming the option.
    pub fn check(&self, format: Format) -> Result<()> {
        let defaults = Options::default();
        let bvh_set = self.fps.is_some() || self.length != defaults.length || self.channels != defaults.channels;
        let csv_set = self.csv != defaults.csv;
        let refuse = |what: &str, applies: &str| {
            Err(Error::input("export", what, format!("applies to --format {applies} only, not to {format}")))
        };
        match format {
            Format::Bvh if csv_set => refuse("--angles/--columns/--joints/--rate", "csv"),
            Format::Csv if bvh_set => refuse("--fps/--units/--channels", "bvh"),
            Format::Gltf | Format::Mot | Format::Osim if bvh_set => refuse("--fps/--units/--channels", "bvh"),
            Format::Gltf | Format::Mot | Format::Osim if csv_set => refuse("--angles/--columns/--joints/--rate", "csv"),
            _ => Ok(()),
        }
    }
}

/// The motion of `record` in `format` with the default options: the file name (the model's name with
/// the format's extension) and its bytes.
pub fn export(model: &Model, record: &PlanRecord, format: Format) -> Result<(String, Vec<u8>)> {
    export_with(model, record, format, &Options::default())
}

/// The motion of `record` in `format` with `options` (checked against the format).
pub fn export_with(model: &Model, record: &PlanRecord, format: Format, options: &Options) -> Result<(String, Vec<u8>)> {
    options.check(format)?;
    super::check_samples(model, record)?;
    if record.samples.is_empty() {
        return Err(Error::input("plan.json", "samples", "the plan holds no samples to export"));
    }
    let bytes = match format {
        Format::Bvh => bvh::bvh(model, record, options)?.into_bytes(),
        Format::Gltf => gltf::glb(model, record)?,
        Format::Mot => mot::mot(model, record).into_bytes(),
        Format::Csv => csv::csv(model, record, &options.csv)?.into_bytes(),
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

/// Model (Z up) to BVH and glTF (Y up) axes: `(x, y, z) ↦ (x, z, −y)`, a rotation of −90° about x.
pub(crate) fn to_y_up() -> crate::spatial::Mat3 {
    crate::spatial::Mat3::new(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0)
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
