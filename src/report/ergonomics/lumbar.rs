//! L5/S1 compression and shear from the lumbar joint's load, with the single-equivalent extensor model of
//! Chaffin & Andersson (*Occupational Biomechanics*, 1984/1991; Chaffin 1969): one muscle behind the
//! joint, its line of action parallel to the spine, moment arm `E = 5 cm`, balances the sagittal moment;
//! its force adds to the spine's axial load. Against NIOSH's back-compression action limit (3400 N) and
//! maximum permissible limit (6400 N) (NIOSH *Work Practices Guide for Manual Lifting*, 1981).
//!
//! With the load `(F, M)` the pelvis side exerts on the spine's other side (the joint's child body,
//! child axes, at the joint origin — [`crate::dynamics::joint_loads`]), `u` the spine's axis pointing
//! into the child (the child frame's z, the built-in humans' convention, signed towards its centre of
//! mass) and `a` the joint's flexion axis (`+q` is forward bend):
//!
//! ```text
//! M_ext = −M · a                         the extensor moment the muscles supply (N·m)
//! F_m   = max(M_ext, 0) / E              the equivalent extensor's force (N)
//! C     = F · u + F_m                    compression (N; negative: traction)
//! S     = F · (a × u)                    shear in the sagittal plane (N; positive: the child side pushed forward)
//! ```
//!
//! Assumptions: the net joint moment (active and passive) is the muscles' (3DSSPP's simplification); a
//! flexion moment (`M_ext < 0`, rare in lifting) is taken to need no extensor force; abdominal pressure,
//! co-contraction and the lumbar lordosis angle are not modelled.

use super::intervals_above;
use crate::dynamics::joint_loads::JointLoad;
use crate::model::Model;
use crate::report::record::PlanRecord;
use crate::spatial::Vec3;
use serde::Serialize;

/// The equivalent extensor's moment arm about L5/S1, `E` (m): Chaffin & Andersson.
pub const EXTENSOR_MOMENT_ARM_M: f64 = 0.05;
/// NIOSH's back-compression action limit (N), 1981.
pub const ACTION_LIMIT_N: f64 = 3400.0;
/// NIOSH's maximum permissible back compression (N), 1981.
pub const MAXIMUM_PERMISSIBLE_LIMIT_N: f64 = 6400.0;

/// The low-back load of the motion.
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct LowBack {
    /// The joint whose load is L5/S1's.
    pub joint: String,
    /// The muscle model, in words.
    pub model: &'static str,
    /// `E` (m).
    pub extensor_moment_arm_m: f64,
    /// Peak compression (N) and when (s).
    pub peak_compression_n: f64,
    /// When the peak compression occurs (s).
    pub peak_compression_time_s: f64,
    /// Peak |shear| (N).
    pub peak_shear_n: f64,
    /// When the peak shear occurs (s).
    pub peak_shear_time_s: f64,
    /// Peak extensor moment (N·m).
    pub peak_extensor_moment_nm: f64,
    /// 3400 N.
    pub action_limit_n: f64,
    /// 6400 N.
    pub maximum_permissible_limit_n: f64,
    /// The intervals `[start, end]` (s) with the compression above the action limit.
    pub intervals_above_action_limit: Vec<[f64; 2]>,
    /// Their total length (s).
    pub time_above_action_limit_s: f64,
    /// The intervals above the maximum permissible limit.
    pub intervals_above_maximum_limit: Vec<[f64; 2]>,
    /// Their total length (s).
    pub time_above_maximum_limit_s: f64,
    /// The samples, for the plot (not in summary.json).
    #[serde(skip)]
    pub samples: Vec<LowBackSample>,
}

/// Compression, shear and extensor moment at one sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LowBackSample {
    /// Time (s).
    pub t: f64,
    /// Compression `C` (N).
    pub compression_n: f64,
    /// Shear `S` (N).
    pub shear_n: f64,
    /// Extensor moment `M_ext` (N·m).
    pub extensor_moment_nm: f64,
}

/// Compression, shear and extensor moment of one lumbar load; `u` the spine's axis into the child and `a`
/// the flexion axis (child axes, unit vectors).
pub fn l5s1(load: &JointLoad, u: &Vec3, a: &Vec3) -> (f64, f64, f64) {
    // M_ext = −M·a
    let extensor = -load.moment.dot(a);
    // C = F·u + max(M_ext, 0)/E
    let compression = load.force.dot(u) + extensor.max(0.0) / EXTENSOR_MOMENT_ARM_M;
    // S = F·(a × u)
    let shear = load.force.dot(&a.cross(u));
    (compression, shear, extensor)
}

/// The low-back load of `record` from the loads `series` (one per sample, every joint), at dof `lumbar`.
pub fn low_back(model: &Model, record: &PlanRecord, series: &[Vec<JointLoad>], lumbar: usize) -> LowBack {
    let (joint, body) = (&model.joints[lumbar + 1], &model.bodies[lumbar + 1]);
    // u: the child frame's z, towards the child's centre of mass (up the trunk, or down into a pelvis).
    let u = if body.inertia.com.z >= 0.0 { Vec3::z() } else { -Vec3::z() };
    let a = joint.axis.normalize();
    let samples: Vec<LowBackSample> = record
        .samples
        .iter()
        .zip(series)
        .map(|(s, loads)| {
            let (compression_n, shear_n, extensor_moment_nm) = l5s1(&loads[lumbar], &u, &a);
            LowBackSample { t: s.t, compression_n, shear_n, extensor_moment_nm }
        })
        .collect();
    let peak = |f: &dyn Fn(&LowBackSample) -> f64| {
        samples.iter().map(|s| (f(s), s.t)).fold((0.0, 0.0), |best, x| if x.0 > best.0 { x } else { best })
    };
    let (peak_compression_n, peak_compression_time_s) = peak(&|s| s.compression_n);
    let (peak_shear_n, peak_shear_time_s) = peak(&|s| s.shear_n.abs());
    let (peak_extensor_moment_nm, _) = peak(&|s| s.extensor_moment_nm);
    let times: Vec<f64> = samples.iter().map(|s| s.t).collect();
    // Compression only counts one way: traction is not measured against the limits.
    let compression: Vec<f64> = samples.iter().map(|s| s.compression_n.max(0.0)).collect();
    let above = |limit: f64| {
        let spans: Vec<[f64; 2]> = intervals_above(&times, &compression, limit).into_iter().filter(|[a, b]| b > a).collect();
        let total = spans.iter().map(|[a, b]| b - a).fold(0.0, |x, y| x + y);
        (spans, total)
    };
    let (intervals_above_action_limit, time_above_action_limit_s) = above(ACTION_LIMIT_N);
    let (intervals_above_maximum_limit, time_above_maximum_limit_s) = above(MAXIMUM_PERMISSIBLE_LIMIT_N);
    LowBack {
        joint: joint.name.clone(),
        model: "single equivalent extensor (Chaffin & Andersson): moment arm 5 cm, line of action along the spine",
        extensor_moment_arm_m: EXTENSOR_MOMENT_ARM_M,
        peak_compression_n,
        peak_compression_time_s,
        peak_shear_n,
        peak_shear_time_s,
        peak_extensor_moment_nm,
        action_limit_n: ACTION_LIMIT_N,
        maximum_permissible_limit_n: MAXIMUM_PERMISSIBLE_LIMIT_N,
        intervals_above_action_limit,
        time_above_action_limit_s,
        intervals_above_maximum_limit,
        time_above_maximum_limit_s,
        samples,
    }
}
