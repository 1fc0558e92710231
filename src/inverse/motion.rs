//! A recorded motion: joint positions of a model over time, read from an OpenSim Storage file (`.mot`,
//! `.sto`) or a CSV file, in SI (rad, m) and the model's joint order. What each format's columns mean:
//!
//! - **Storage**: a `time` column (s) and one column per model joint, named after it; revolute joints in
//!   degrees when the header says `inDegrees=yes`, in radians when `no`; prismatic joints always in metres
//!   (as OpenSim reads them).
//! - **CSV**: a `time` or `time_s` column (s) and one column per joint: `NAME` (degrees for a revolute,
//!   metres for a prismatic joint), or with the unit in the label, `NAME.q_deg`, `NAME.q_rad`, `NAME.q_m`
//!   (the `trajectory.csv` of a plan directory is read as it is: its `.qd_*`, `.qdd_*`, `.tau_*` and
//!   contact-force columns are skipped).
//!
//! - **BVH**: see [`super::bvh`].
//!
//! Refused, naming the file: columns that do not match the model's joints (the missing and the extra
//! listed), a joint twice, no time column, times that do not increase (the line), too few samples.

use super::spline::MIN_KNOTS;
use super::table::{self, Table};
use crate::error::{Error, Result};
use crate::model::{JointKind, Model};
use crate::report::export::LengthUnit;
use std::path::Path;

/// A motion in the model's joint order, SI.
#[derive(Clone, Debug)]
pub struct Motion {
    /// The file, as named in errors.
    pub origin: String,
    /// Sample times (s), strictly increasing.
    pub times: Vec<f64>,
    /// Joint positions at each time (rad or m), one per model joint.
    pub q: Vec<Vec<f64>>,
    /// What the reader dropped or assumed, one line each, for the terminal and the summary.
    pub notes: Vec<String>,
}

/// The largest |joint position| accepted (rad or m), as for a states file.
const MAX_POSITION: f64 = 1e3;

/// Reads the motion file at `path` for `model`: `.mot` and `.sto` as Storage, `.csv` as CSV, `.bvh` as
/// BVH in centimetres.
pub fn read(path: &Path, model: &Model) -> Result<Motion> {
    read_with_units(path, model, LengthUnit::Centimetre)
}

/// As [`read`], a BVH file's lengths in `bvh_unit`.
pub fn read_with_units(path: &Path, model: &Model, bvh_unit: LengthUnit) -> Result<Motion> {
    if path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("bvh")) {
        return super::bvh::read(path, model, bvh_unit);
    }
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let origin = path.display().to_string();
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("mot") | Some("sto") => from_table(&table::parse_storage(&text, &origin)?, model),
        Some("csv") => from_table(&table::parse_csv(&text, &origin)?, model),
        _ => Err(Error::input(origin, "file name", "a recorded motion must end in .mot, .sto (OpenSim Storage), .csv or .bvh")),
    }
}

/// What one column of a table holds.
enum Column {
    Time,
    /// A joint's position: its dof index and the factor to SI.
    Joint(usize, f64),
    /// A column of a plan's `trajectory.csv` that is not a position.
    Skipped,
    Unknown,
}

/// The motion of `table` on `model`: columns matched to joints, converted to SI, times checked.
pub fn from_table(table: &Table, model: &Model) -> Result<Motion> {
    let origin = table.origin.as_str();
    let columns: Vec<Column> =
        table.labels.iter().map(|l| classify(l, table.in_degrees, model, origin)).collect::<Result<_>>()?;
    check_columns(table, &columns, model)?;
    let time = columns.iter().position(|c| matches!(c, Column::Time)).expect("checked");
    let mut motion = Motion { origin: origin.to_string(), times: Vec::new(), q: Vec::new(), notes: Vec::new() };
    for (row, &line) in table.rows.iter().zip(&table.lines) {
        let mut q = vec![0.0; model.nv()];
        for ((c, value), label) in columns.iter().zip(row).zip(&table.labels) {
            if let Column::Joint(d, factor) = c {
                // q_SI = value · factor (π/180 for degrees, 1 for radians and metres).
                q[*d] = value * factor;
                if q[*d].abs() > MAX_POSITION {
                    let message = format!("{value} is out of range: |q| must be at most {MAX_POSITION} rad or m");
                    return Err(Error::input(origin, format!("line {line}, column \"{label}\""), message));
                }
            }
        }
        if let Some(&before) = motion.times.last() {
            if row[time] <= before {
                let message = format!("time {} s does not come after the previous row's {before} s", row[time]);
                return Err(Error::input(origin, format!("line {line}"), message));
            }
        }
        motion.times.push(row[time]);
        motion.q.push(q);
    }
    check_length(&motion)?;
    Ok(motion)
}

/// At least [`MIN_KNOTS`] samples.
pub(crate) fn check_length(motion: &Motion) -> Result<()> {
    if motion.times.len() >= MIN_KNOTS {
        return Ok(());
    }
    let message = format!("has {} samples; inverse dynamics needs at least {MIN_KNOTS}", motion.times.len());
    Err(Error::input(&motion.origin, "rows", message))
}

/// What column `label` holds: Storage labels are joint names; CSV labels may carry a unit suffix.
fn classify(label: &str, in_degrees: Option<bool>, model: &Model, origin: &str) -> Result<Column> {
    // A Storage file's revolute joints: π/180 when inDegrees=yes; prismatic joints always metres.
    let storage_factor = |d: usize, deg: bool| match model.joints[d + 1].kind != JointKind::Prismatic && deg {
        true => std::f64::consts::PI / 180.0,
        false => 1.0,
    };
    match in_degrees {
        Some(_) if label == "time" => Ok(Column::Time),
        Some(deg) => Ok(model.dof_index(label).map_or(Column::Unknown, |d| Column::Joint(d, storage_factor(d, deg)))),
        None if label == "time" || label == "time_s" => Ok(Column::Time),
        None => classify_csv(label, model, origin),
    }
}

/// A CSV label: `NAME` (degrees or metres), `NAME.q_deg`, `NAME.q_rad`, `NAME.q_m`, or another column of a
/// plan's `trajectory.csv`.
fn classify_csv(label: &str, model: &Model, origin: &str) -> Result<Column> {
    let degrees = std::f64::consts::PI / 180.0;
    let prismatic = |d: usize| model.joints[d + 1].kind == JointKind::Prismatic;
    if let Some(d) = model.dof_index(label) {
        return Ok(Column::Joint(d, if prismatic(d) { 1.0 } else { degrees }));
    }
    let Some((name, quantity)) = label.rsplit_once('.') else { return Ok(Column::Unknown) };
    let Some(d) = model.dof_index(name) else {
        return Ok(if is_trajectory_extra(quantity) { Column::Skipped } else { Column::Unknown });
    };
    let wrong_unit = |unit: &str| {
        let kind = if prismatic(d) { "prismatic (metres: .q_m)" } else { "revolute (.q_deg or .q_rad)" };
        Err(Error::input(origin, format!("column \"{label}\""), format!("joint \"{name}\" is {kind}, not in {unit}")))
    };
    match quantity {
        "q_deg" if prismatic(d) => wrong_unit("degrees"),
        "q_rad" if prismatic(d) => wrong_unit("radians"),
        "q_m" if !prismatic(d) => wrong_unit("metres"),
        "q_deg" => Ok(Column::Joint(d, degrees)),
        "q_rad" | "q_m" => Ok(Column::Joint(d, 1.0)),
        q if is_trajectory_extra(q) => Ok(Column::Skipped),
        _ => Ok(Column::Unknown),
    }
}

/// The columns of `trajectory.csv` that are not positions: velocities, accelerations, torques, contact
/// forces.
fn is_trajectory_extra(quantity: &str) -> bool {
    ["qd_", "qdd_", "tau_"].iter().any(|p| quantity.starts_with(p)) || ["fx_N", "fy_N", "fz_N"].contains(&quantity)
}

/// One time column and exactly the model's joints, each once; the missing and the extra named together.
fn check_columns(table: &Table, columns: &[Column], model: &Model) -> Result<()> {
    let origin = &table.origin;
    let times = columns.iter().filter(|c| matches!(c, Column::Time)).count();
    if times != 1 {
        let message = format!("needs one `time` column (s), found {times}; the columns: {}", table.labels.join(", "));
        return Err(Error::input(origin, "columns", message));
    }
    let mut seen = vec![0usize; model.nv()];
    columns.iter().for_each(|c| {
        if let Column::Joint(d, _) = c {
            seen[*d] += 1
        }
    });
    if let Some(d) = seen.iter().position(|&n| n > 1) {
        let message = format!("joint \"{}\" has {} columns", model.joints[d + 1].name, seen[d]);
        return Err(Error::input(origin, "columns", message));
    }
    let missing: Vec<&str> = (0..model.nv()).filter(|&d| seen[d] == 0).map(|d| model.joints[d + 1].name.as_str()).collect();
    let extra: Vec<&str> =
        columns.iter().zip(&table.labels).filter(|(c, _)| matches!(c, Column::Unknown)).map(|(_, l)| l.as_str()).collect();
    if missing.is_empty() && extra.is_empty() {
        return Ok(());
    }
    let list = |names: &[&str]| if names.is_empty() { "none".to_string() } else { names.join(", ") };
    let message = format!(
        "the coordinates do not match the model \"{}\": missing {}; extra (not joints of the model) {}",
        model.name,
        list(&missing),
        list(&extra)
    );
    Err(Error::input(origin, "columns", message))
}
