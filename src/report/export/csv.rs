//! The trajectory as CSV. With the default [`CsvOptions`] it is the `trajectory.csv` that `plan` writes
//! (`time_s`, then per joint `NAME.q_deg`, `NAME.qd_deg_s`, `NAME.qdd_deg_s2`, `NAME.tau_Nm` — metres and
//! newtons for prismatic joints — then per contact `NAME.fx_N`, `NAME.fy_N`, `NAME.fz_N`); `export
//! --format csv` can instead write radians (`--angles rad`: `q_rad`, `qd_rad_s`, `qdd_rad_s2`), only some
//! quantities (`--columns q,tau,force`) or joints (`--joints hip,knee`), at another rate (`--rate HZ`,
//! resampled as [`super::resample`] says). Every column's name ends with its unit.

use super::resample::{even_times, sample_at};
use crate::error::{Error, Result};
use crate::model::{JointKind, Model};
use crate::report::record::{PlanRecord, SampleRecord};
use std::fmt::Write as _;

/// The angle unit of revolute joints' q, q̇, q̈.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum AngleUnit {
    /// Degrees (`deg`), as `trajectory.csv`.
    #[default]
    Degree,
    /// Radians (`rad`).
    Radian,
}

/// A quantity written per joint (q, q̇, q̈, τ) or per contact (its force).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Column {
    /// Joint position `q` (deg, rad or m).
    Q,
    /// Joint velocity `q̇`.
    Qd,
    /// Joint acceleration `q̈`.
    Qdd,
    /// Active joint torque `τ` (N·m or N).
    Tau,
    /// Contact forces on the figure (N, world axes).
    Force,
}

impl Column {
    /// Every column, in the file's order.
    pub const ALL: [Column; 5] = [Column::Q, Column::Qd, Column::Qdd, Column::Tau, Column::Force];
    const NAMES: [&'static str; 5] = ["q", "qd", "qdd", "tau", "force"];

    /// The column called `name` (`q`, `qd`, `qdd`, `tau`, `force`).
    pub fn from_name(name: &str) -> Result<Column> {
        let wanted = name.trim().to_ascii_lowercase();
        Column::NAMES.iter().position(|n| *n == wanted).map(|k| Column::ALL[k]).ok_or_else(|| {
            Error::input("export", "columns", format!("unknown column \"{name}\"; known: {}", Column::NAMES.join(", ")))
        })
    }
}

/// What the CSV holds; the default is `trajectory.csv`.
#[derive(Clone, Debug, PartialEq)]
pub struct CsvOptions {
    /// The unit of revolute joints' q, q̇, q̈.
    pub angles: AngleUnit,
    /// The quantities, written in [`Column::ALL`] order whatever the order given.
    pub columns: Vec<Column>,
    /// The joints by name (empty: all), written in the model's order.
    pub joints: Vec<String>,
    /// Rows per second, resampled (`None`: the plan's samples).
    pub rate: Option<f64>,
}

impl Default for CsvOptions {
    fn default() -> Self {
        CsvOptions { angles: AngleUnit::Degree, columns: Column::ALL.to_vec(), joints: vec![], rate: None }
    }
}

/// A joint's column suffixes (q, q̇, q̈, τ) and the factor from SI.
fn joint_units(kind: JointKind, angles: AngleUnit) -> ([&'static str; 4], f64) {
    match (kind, angles) {
        (JointKind::Prismatic, _) => (["q_m", "qd_m_s", "qdd_m_s2", "tau_N"], 1.0),
        (_, AngleUnit::Degree) => (["q_deg", "qd_deg_s", "qdd_deg_s2", "tau_Nm"], 180.0 / std::f64::consts::PI),
        (_, AngleUnit::Radian) => (["q_rad", "qd_rad_s", "qdd_rad_s2", "tau_Nm"], 1.0),
    }
}

/// The degrees of freedom named in `joints` (all when empty), in the model's order; an unknown name is
/// refused with the known ones.
fn selected_dofs(model: &Model, joints: &[String]) -> Result<Vec<usize>> {
    if let Some(bad) = joints.iter().find(|j| model.dof_index(j).is_none()) {
        let known = model.joint_names().join(", ");
        return Err(Error::input("export", "joints", format!("no joint \"{bad}\" in the model; its joints: {known}")));
    }
    Ok((0..model.nv()).filter(|&i| joints.is_empty() || joints.iter().any(|j| model.dof_index(j) == Some(i))).collect())
}

/// The trajectory as CSV: `time_s`, then per selected joint its chosen quantities, then per contact the
/// force on the figure (N, world axes) when `force` is chosen.
pub fn csv(model: &Model, record: &PlanRecord, options: &CsvOptions) -> Result<String> {
    let dofs = selected_dofs(model, &options.joints)?;
    let wanted: Vec<usize> = (0..4).filter(|&k| options.columns.contains(&Column::ALL[k])).collect();
    let forces = options.columns.contains(&Column::Force);
    let mut out = String::from("time_s");
    for &i in &dofs {
        let j = &model.joints[i + 1];
        let names = joint_units(j.kind, options.angles).0;
        wanted.iter().for_each(|&k| {
            let _ = write!(out, ",{}.{}", j.name, names[k]);
        });
    }
    for c in record.contacts.iter().filter(|_| forces) {
        for axis in ["fx_N", "fy_N", "fz_N"] {
            let _ = write!(out, ",{}.{axis}", c.name);
        }
    }
    out.push('\n');
    let rows: Vec<SampleRecord> = match options.rate {
        None => record.samples.clone(),
        rate => even_times(&record.samples, rate)?.1.iter().map(|&t| sample_at(&record.samples, t)).collect(),
    };
    for s in &rows {
        let _ = write!(out, "{:.6}", s.t);
        for &i in &dofs {
            let k = joint_units(model.joints[i + 1].kind, options.angles).1;
            let values = [s.q[i] * k, s.qd[i] * k, s.qdd[i] * k, s.tau[i]];
            wanted.iter().for_each(|&c| {
                let _ = write!(out, ",{:.9}", values[c]);
            });
        }
        for f in s.contact_forces.iter().filter(|_| forces) {
            let _ = write!(out, ",{:.9},{:.9},{:.9}", f[0], f[1], f[2]);
        }
        out.push('\n');
    }
    Ok(out)
}
