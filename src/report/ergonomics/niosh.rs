//! The revised NIOSH lifting equation (Waters, Putz-Anderson, Garg & Fine 1993, *Ergonomics* 36:749;
//! tables from the *Applications Manual for the Revised NIOSH Lifting Equation*, Waters et al. 1994):
//!
//! ```text
//! RWL = LC · HM · VM · DM · AM · FM · CM          LI = load / RWL
//! LC = 23 kg   HM = 25/H   VM = 1 − 0.003|V − 75|   DM = 0.82 + 4.5/D   AM = 1 − 0.0032 A
//! ```
//!
//! H, V, D in cm, A in degrees; FM from the frequency table (Table 5), CM from the coupling table
//! (Table 7). H < 25 cm is taken as 25 and D < 25 cm as 25 (the equation's own rules); a lift with
//! H > 63 cm, V > 175 cm, D > 175 cm, A > 135° or a frequency beyond the table has a multiplier of 0 and is
//! refused. H, V and A come from the planned hand path at the origin (first sample) and destination (last):
//! H is the horizontal distance of the hands (the midpoint of the hand frames) from the midpoint of the
//! ankle joint centres, V the hands' height above the floor (the plane through the world origin normal to
//! up, where the built-in humans stand), A the angle between the hands' horizontal direction from the
//! ankles and the figure's forward direction (the root body's x axis).

use crate::dynamics::{kinematics, Data};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::plan::task::{LiftSpec, TaskFile};
use crate::spatial::Vec3;
use serde::Serialize;

/// The load constant LC (kg).
pub const LOAD_CONSTANT_KG: f64 = 23.0;

/// The frequencies of the FM table (lifts/min); below 0.2 the first row applies.
const FREQUENCIES: [f64; 17] = [0.2, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0, 13.0, 14.0, 15.0];
/// FM (Waters et al. 1994, Table 5): per frequency, for work of ≤ 1 h, ≤ 2 h, ≤ 8 h, each at V < 75 cm
/// and V ≥ 75 cm. Above 15 lifts/min FM is 0.
const FM_TABLE: [[f64; 6]; 17] = [
    [1.00, 1.00, 0.95, 0.95, 0.85, 0.85],
    [0.97, 0.97, 0.92, 0.92, 0.81, 0.81],
    [0.94, 0.94, 0.88, 0.88, 0.75, 0.75],
    [0.91, 0.91, 0.84, 0.84, 0.65, 0.65],
    [0.88, 0.88, 0.79, 0.79, 0.55, 0.55],
    [0.84, 0.84, 0.72, 0.72, 0.45, 0.45],
    [0.80, 0.80, 0.60, 0.60, 0.35, 0.35],
    [0.75, 0.75, 0.50, 0.50, 0.27, 0.27],
    [0.70, 0.70, 0.42, 0.42, 0.22, 0.22],
    [0.60, 0.60, 0.35, 0.35, 0.18, 0.18],
    [0.52, 0.52, 0.30, 0.30, 0.00, 0.15],
    [0.45, 0.45, 0.26, 0.26, 0.00, 0.13],
    [0.41, 0.41, 0.00, 0.23, 0.00, 0.00],
    [0.37, 0.37, 0.00, 0.21, 0.00, 0.00],
    [0.00, 0.34, 0.00, 0.00, 0.00, 0.00],
    [0.00, 0.31, 0.00, 0.00, 0.00, 0.00],
    [0.00, 0.28, 0.00, 0.00, 0.00, 0.00],
];

/// How long the lifting work lasts (the FM table's columns).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WorkDuration {
    /// ≤ 1 h, followed by a recovery time of at least 1.2 × the work time.
    Short,
    /// 1–2 h, recovery at least 0.3 × the work time.
    Moderate,
    /// 2–8 h.
    Long,
}

/// Hand-to-object coupling (Table 7).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coupling {
    /// Good handles or hand-hold cut-outs.
    Good,
    /// Sub-optimal handles, or fingers flexed about 90°.
    Fair,
    /// No handles, bulky or hard to grip.
    Poor,
}

/// FM for `frequency` lifts/min: linear between the table's rows; `None` beyond the table.
pub fn frequency_multiplier(frequency: f64, duration: WorkDuration, vertical_cm: f64) -> Option<f64> {
    let column = 2 * duration as usize + usize::from(vertical_cm >= 75.0);
    let f = frequency.max(FREQUENCIES[0]);
    let k = FREQUENCIES.iter().position(|&x| x >= f)?;
    let hi = FM_TABLE[k][column];
    if k == 0 || FREQUENCIES[k] == f {
        return Some(hi).filter(|&m| m > 0.0);
    }
    let lo = FM_TABLE[k - 1][column];
    // Between two rows: linear, and only where both rows are in the table (not 0).
    let s = (f - FREQUENCIES[k - 1]) / (FREQUENCIES[k] - FREQUENCIES[k - 1]);
    (lo > 0.0 && hi > 0.0).then_some(lo + s * (hi - lo))
}

/// CM (Table 7): good 1.00; fair 0.95 below V = 75 cm, 1.00 from there; poor 0.90.
pub fn coupling_multiplier(coupling: Coupling, vertical_cm: f64) -> f64 {
    match coupling {
        Coupling::Good => 1.0,
        Coupling::Fair if vertical_cm < 75.0 => 0.95,
        Coupling::Fair => 1.0,
        Coupling::Poor => 0.90,
    }
}

/// Where the hands are at one end of the lift.
#[derive(Serialize, Debug, Clone, Copy, PartialEq)]
pub struct Location {
    /// H (cm).
    pub horizontal_cm: f64,
    /// V (cm).
    pub vertical_cm: f64,
    /// A (degrees).
    pub asymmetry_deg: f64,
}

/// The multipliers and the recommended weight limit at one end of the lift.
#[derive(Serialize, Debug, Clone, Copy, PartialEq)]
pub struct Multipliers {
    /// 25/H.
    pub hm: f64,
    /// 1 − 0.003|V − 75|.
    pub vm: f64,
    /// 0.82 + 4.5/D.
    pub dm: f64,
    /// 1 − 0.0032 A.
    pub am: f64,
    /// From Table 5.
    pub fm: f64,
    /// From Table 7.
    pub cm: f64,
    /// RWL (kg).
    pub rwl_kg: f64,
}

/// The recommended weight limit at `at` for a vertical travel `travel_cm`; why not, when the equation
/// does not cover the lift.
pub fn recommended_weight_limit(
    at: &Location,
    travel_cm: f64,
    frequency: f64,
    duration: WorkDuration,
    coupling: Coupling,
) -> std::result::Result<Multipliers, String> {
    let Location { horizontal_cm: h, vertical_cm: v, asymmetry_deg: a } = *at;
    let refuse = |what: String| Err(format!("{what}: the lifting equation does not cover this lift"));
    if h > 63.0 {
        return refuse(format!("H = {h:.1} cm is beyond 63 cm"));
    }
    if !(0.0..=175.0).contains(&v) {
        return refuse(format!("V = {v:.1} cm is outside 0–175 cm"));
    }
    if travel_cm > 175.0 {
        return refuse(format!("D = {travel_cm:.1} cm is beyond 175 cm"));
    }
    if a > 135.0 {
        return refuse(format!("A = {a:.1}° is beyond 135°"));
    }
    let Some(fm) = frequency_multiplier(frequency, duration, v) else {
        return refuse(format!("{frequency} lifts/min is beyond the frequency table for this duration (FM = 0)"));
    };
    // HM = 25/H, DM = 0.82 + 4.5/D, with H and D at least 25 cm.
    let hm = 25.0 / h.max(25.0);
    let vm = 1.0 - 0.003 * (v - 75.0).abs();
    let dm = 0.82 + 4.5 / travel_cm.max(25.0);
    let am = 1.0 - 0.0032 * a;
    let cm = coupling_multiplier(coupling, v);
    let rwl_kg = LOAD_CONSTANT_KG * hm * vm * dm * am * fm * cm;
    Ok(Multipliers { hm, vm, dm, am, fm, cm, rwl_kg })
}

/// `[ergonomics.lift]` resolved against the model.
#[derive(Clone, Debug, PartialEq)]
pub struct Lift {
    /// F (lifts/min).
    pub frequency_per_min: f64,
    /// The FM table's column.
    pub duration: WorkDuration,
    /// C.
    pub coupling: Coupling,
    /// Frame indices whose midpoint is the hands.
    pub hands: Vec<usize>,
    /// Bodies whose origins are the ankle joint centres.
    pub ankles: Vec<usize>,
    /// The load (kg).
    pub load_kg: f64,
    /// World up (unit).
    pub up: Vec3,
    /// The field a refusal of the lift names (`ergonomics.lift` in a task file).
    pub field: String,
}

/// Where a lift's settings were written, for the errors: the file, the table holding the fields
/// (`ergonomics.lift` in a task; `lift` in `mintorque inverse --lift FILE`), the field that sets gravity, and
/// the payloads' total mass (kg) when the file has payloads (a task), `None` when the load must be given.
pub struct Written<'a> {
    /// The file.
    pub origin: &'a str,
    /// The table of the lift's fields.
    pub table: &'a str,
    /// The field (or model) that sets gravity.
    pub gravity_field: &'a str,
    /// The payloads' total mass (kg), the default load.
    pub payload_kg: Option<f64>,
}

/// `[ergonomics.lift]` of `file` against `model` and `gravity`.
pub fn resolve(spec: &LiftSpec, file: &TaskFile, model: &Model, gravity: &Vec3, origin: &str) -> Result<Lift> {
    let payload_kg = Some(file.environment.payload.iter().map(|p| p.mass).sum());
    resolve_in(
        spec,
        model,
        gravity,
        &Written { origin, table: "ergonomics.lift", gravity_field: "environment.gravity", payload_kg },
    )
}

/// The lift `spec` against `model` and `gravity`; errors name the file and field as `written` says.
pub fn resolve_in(spec: &LiftSpec, model: &Model, gravity: &Vec3, written: &Written) -> Result<Lift> {
    let field = |f: &str| format!("{}.{f}", written.table);
    let err = |f: &str, m: String| Error::task(written.origin, field(f), m);
    if !(spec.frequency_per_min.is_finite() && spec.frequency_per_min > 0.0) {
        return Err(err(
            "frequency_per_min",
            format!("must be a positive number of lifts per minute, got {}", spec.frequency_per_min),
        ));
    }
    let duration = match spec.duration.as_str() {
        "short" => WorkDuration::Short,
        "moderate" => WorkDuration::Moderate,
        "long" => WorkDuration::Long,
        other => {
            return Err(err(
                "duration",
                format!("\"{other}\": expected \"short\" (≤ 1 h), \"moderate\" (1–2 h) or \"long\" (2–8 h)"),
            ))
        }
    };
    let coupling = match spec.coupling.as_str() {
        "good" => Coupling::Good,
        "fair" => Coupling::Fair,
        "poor" => Coupling::Poor,
        other => return Err(err("coupling", format!("\"{other}\": expected \"good\", \"fair\" or \"poor\""))),
    };
    let g = gravity.norm();
    if (g - 9.81).abs() > 0.02 * 9.81 {
        let message = format!("the lifting equation is for lifts on Earth (9.81 m/s²); the gravity here is {g:.2} m/s²");
        return Err(Error::task(written.origin, written.gravity_field, message));
    }
    let load_kg = spec.load_kg.or(written.payload_kg).unwrap_or(0.0);
    if !(load_kg.is_finite() && load_kg > 0.0) {
        let message = match written.payload_kg {
            Some(_) => format!("there is no load to lift: give [[environment.payload]] or {} (kg, > 0)", field("load_kg")),
            None => format!("there is no load to lift: give {} (kg, > 0)", field("load_kg")),
        };
        return Err(err("load_kg", message));
    }
    let hands = hand_frames(spec, model, &err)?;
    let ankles: Vec<usize> = (1..model.joints.len()).filter(|&i| model.joints[i].name.contains("ankle")).collect();
    if ankles.is_empty() {
        return Err(err("hands", "H is measured from the ankles, and the model has no joint named *ankle*".into()));
    }
    let (frequency_per_min, up, field) = (spec.frequency_per_min, -gravity / g, written.table.to_string());
    Ok(Lift { frequency_per_min, duration, coupling, hands, ankles, load_kg, up, field })
}

/// The frames `spec` names as the hands (default `hands`, else `left_hand` and `right_hand`).
fn hand_frames(spec: &LiftSpec, model: &Model, err: &dyn Fn(&str, String) -> Error) -> Result<Vec<usize>> {
    let frame = |name: &str| model.frames.iter().position(|f| f.name == name);
    match &spec.hands {
        Some(names) if !names.is_empty() => {
            names.iter().map(|n| frame(n).ok_or_else(|| err("hands", format!("the model has no frame \"{n}\"")))).collect()
        }
        Some(_) => Err(err("hands", "name at least one frame".into())),
        None => match (frame("hands"), frame("left_hand"), frame("right_hand")) {
            (Some(h), _, _) => Ok(vec![h]),
            (None, Some(l), Some(r)) => Ok(vec![l, r]),
            _ => Err(err(
                "hands",
                "the model has no frame \"hands\" (nor \"left_hand\" and \"right_hand\"): name the hand frames".into(),
            )),
        },
    }
}

/// H, V and A of posture `q`.
pub fn location(model: &Model, lift: &Lift, q: &[f64]) -> Location {
    let mut data = Data::new(model);
    kinematics::placements(model, &mut data, q);
    let mean = |points: Vec<Vec3>| points.iter().sum::<Vec3>() / points.len() as f64;
    let hands = mean(lift.hands.iter().map(|&f| kinematics::frame_placement(model, &data, f).translation).collect());
    let ankles = mean(lift.ankles.iter().map(|&b| data.oMi[b].translation).collect());
    let horizontal = |d: Vec3| d - lift.up * lift.up.dot(&d);
    // H: the horizontal part of hands − ankles; V: the hands' height above the floor through the origin.
    let reach = horizontal(hands - ankles);
    let forward = horizontal(data.oMi[0].rotation * Vec3::x());
    // A: the angle between the reach and the forward direction on the floor (0 when the hands are above the ankles).
    let asymmetry = match reach.norm() > 1e-6 && forward.norm() > 1e-6 {
        true => reach.angle(&forward).to_degrees(),
        false => 0.0,
    };
    Location { horizontal_cm: 100.0 * reach.norm(), vertical_cm: 100.0 * lift.up.dot(&hands), asymmetry_deg: asymmetry }
}

/// One end of the lift assessed.
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct LiftEnd {
    /// When (s).
    pub time_s: f64,
    /// H, V, A.
    #[serde(flatten)]
    pub location: Location,
    /// The multipliers and RWL.
    #[serde(flatten)]
    pub multipliers: Multipliers,
    /// load / RWL.
    pub lifting_index: f64,
}

/// The lift assessed by the revised NIOSH equation.
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct LiftingIndex {
    /// The load (kg).
    pub load_kg: f64,
    /// F (lifts/min).
    pub frequency_per_min: f64,
    /// "short", "moderate" or "long".
    pub duration: &'static str,
    /// "good", "fair" or "poor".
    pub coupling: &'static str,
    /// D (cm).
    pub vertical_travel_cm: f64,
    /// At the origin (the first sample).
    pub origin: LiftEnd,
    /// At the destination (the last sample).
    pub destination: LiftEnd,
    /// The larger of the two lifting indices.
    pub lifting_index: f64,
}

/// The lift from posture `q0` at `t0` to `q1` at `t1` (s); an error naming `origin` and the lift's field
/// when the equation does not cover it.
pub fn assess(
    model: &Model,
    lift: &Lift,
    (t0, q0): (f64, &[f64]),
    (t1, q1): (f64, &[f64]),
    origin: &str,
) -> Result<LiftingIndex> {
    let (a, b) = (location(model, lift, q0), location(model, lift, q1));
    let travel = (b.vertical_cm - a.vertical_cm).abs();
    let end = |time_s: f64, at: Location, which: &str| -> Result<LiftEnd> {
        let m = recommended_weight_limit(&at, travel, lift.frequency_per_min, lift.duration, lift.coupling)
            .map_err(|m| Error::task(origin, &lift.field, format!("at the {which} ({time_s:.3} s): {m}")))?;
        Ok(LiftEnd { time_s, location: at, multipliers: m, lifting_index: lift.load_kg / m.rwl_kg })
    };
    let (origin_end, destination) = (end(t0, a, "origin")?, end(t1, b, "destination")?);
    Ok(LiftingIndex {
        load_kg: lift.load_kg,
        frequency_per_min: lift.frequency_per_min,
        duration: ["short", "moderate", "long"][lift.duration as usize],
        coupling: ["good", "fair", "poor"][lift.coupling as usize],
        vertical_travel_cm: travel,
        lifting_index: origin_end.lifting_index.max(destination.lifting_index),
        origin: origin_end,
        destination,
    })
}
