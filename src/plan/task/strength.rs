//! Every joint's strength from the task: `[ergonomics.strength.JOINT]`, else the defaults (Anderson et
//! al. 2007 at a built-in human's hips, knees and ankles, the constant limits elsewhere, none where a
//! joint is not a person's), and `constraints.strength_limits`' percentile (docs/ergonomics.md). The
//! surfaces themselves are `model::strength`'s.

use super::schema::{StrengthSpec, TaskFile};
use crate::error::{Error, Result};
use crate::model::strength::shaped::source_peak as shaped_peak;
use crate::model::strength::{normal_quantile, Source, Strengths, ANDERSON_G, ANDERSON_JOINTS, DEFAULT_CV, SHAPED_JOINTS};
use crate::model::Model;

/// `ergonomics.population_cv` (default 0.22), checked to lie in (0, 1).
pub fn population_cv(file: &TaskFile, origin: &str) -> Result<f64> {
    let cv = file.ergonomics.population_cv.unwrap_or(DEFAULT_CV);
    if !(cv.is_finite() && cv > 0.0 && cv < 1.0) {
        let message = format!("must be a coefficient of variation between 0 and 1, got {cv}");
        return Err(Error::task(origin, "ergonomics.population_cv", message));
    }
    Ok(cv)
}

/// The planner's strength limits when `constraints.strength_limits` is on: every joint's source at the
/// percentile `constraints.strength_percentile` (default 50, the mean; 1–99).
pub fn limits(file: &TaskFile, model: &Model, origin: &str) -> Result<Option<Strengths>> {
    let c = &file.constraints;
    if !c.strength_limits {
        if c.strength_percentile.is_some() {
            let message = "applies to strength limits only: set constraints.strength_limits = true";
            return Err(Error::task(origin, "constraints.strength_percentile", message));
        }
        return Ok(None);
    }
    if !c.torque_limits {
        let message = "bounds the torques by strength, but constraints.torque_limits = false turns the torque limits off";
        return Err(Error::task(origin, "constraints.strength_limits", message));
    }
    let percentile = c.strength_percentile.unwrap_or(50.0);
    if !(percentile.is_finite() && (1.0..=99.0).contains(&percentile)) {
        let message = format!("must be a population percentile between 1 and 99 (50: the mean strength), got {percentile}");
        return Err(Error::task(origin, "constraints.strength_percentile", message));
    }
    let cv = population_cv(file, origin)?;
    let sources = resolve(file, model, origin)?;
    if sources.iter().all(|s| *s == Source::None) {
        let message =
            "no joint of the model has a strength: use a built-in human (model.human) or give [ergonomics.strength.JOINT]";
        return Err(Error::task(origin, "constraints.strength_limits", message));
    }
    let z = normal_quantile(percentile / 100.0);
    // T_p = T (1 + z σ/T) must stay a strength.
    if let Some(least) = sources.iter().flat_map(|s| s.cvs(cv)).map(|cv| 1.0 + z * cv).reduce(f64::min).filter(|f| *f <= 0.05) {
        let message = format!("{percentile} % lies {:.2} SD below the mean: with the population's spread the strength there is {:.0} % of the mean or less; take a higher percentile", -z, 100.0 * least);
        return Err(Error::task(origin, "constraints.strength_percentile", message));
    }
    Ok(Some(Strengths { sources, cv, percentile, z }))
}

/// Every joint's strength source, in `q` order, from `[ergonomics.strength]` and the defaults.
pub fn resolve(file: &TaskFile, model: &Model, origin: &str) -> Result<Vec<Source>> {
    for name in file.ergonomics.strength.keys() {
        if model.dof_index(name).is_none() {
            let message = format!("the model has no joint called \"{name}\"; its joints: {}", model.joint_names().join(", "));
            return Err(Error::task(origin, format!("ergonomics.strength.{name}"), message));
        }
    }
    let subject = file.model.human.as_ref().map(|_| {
        let m = file.model.mass.unwrap_or(crate::model::human::REFERENCE_MASS_KG);
        let h = file.model.stature.unwrap_or(crate::model::human::REFERENCE_STATURE_M);
        m * ANDERSON_G * h
    });
    (0..model.nv())
        .map(|i| {
            let joint = &model.joints[i + 1];
            let name = joint.name.as_str();
            match file.ergonomics.strength.get(name) {
                Some(spec) => explicit(spec, name, subject, origin),
                None => Ok(default_source(file, model, i, subject)),
            }
        })
        .collect()
}

fn explicit(spec: &StrengthSpec, name: &str, subject: Option<f64>, origin: &str) -> Result<Source> {
    let field = |f: &str| format!("ergonomics.strength.{name}.{f}");
    let err = |f: &str, m: String| Error::task(origin, field(f), m);
    fn given(fields: &[(&'static str, bool)]) -> Option<&'static str> {
        fields.iter().find(|(_, set)| *set).map(|(f, _)| *f)
    }
    let anderson_only = [("joint", spec.joint.is_some()), ("limbs", spec.limbs.is_some()), ("flexion", spec.flexion.is_some())];
    let constant_only = [("positive_nm", spec.positive_nm.is_some()), ("negative_nm", spec.negative_nm.is_some())];
    // A field of the other source is a mistake, not something to ignore.
    let misplaced = match spec.source.as_str() {
        "constant" => given(&anderson_only).map(|f| (f, "anderson2007")),
        "anderson2007" => given(&constant_only).map(|f| (f, "constant")),
        _ => None,
    };
    if let Some((f, owner)) = misplaced {
        let message = format!("belongs to source = \"{owner}\", not to source = \"{}\"", spec.source);
        return Err(err(f, message));
    }
    match spec.source.as_str() {
        "constant" => {
            let direction = |v: Option<f64>, f: &str| match v {
                Some(v) if v.is_finite() && v > 0.0 => Ok(v),
                Some(v) => Err(err(f, format!("must be a positive torque (N·m), got {v}"))),
                None => Err(err(
                    f,
                    "a constant strength needs both directions: positive_nm (along +axis) and negative_nm (along −axis)".into(),
                )),
            };
            let (positive, negative) = (direction(spec.positive_nm, "positive_nm")?, direction(spec.negative_nm, "negative_nm")?);
            Ok(Source::Constant { positive, negative, label: "constant (task)".into() })
        }
        "anderson2007" => {
            let base = spec.joint.clone().unwrap_or_else(|| anatomical(name).0.to_string());
            let joint = ANDERSON_JOINTS.iter().position(|j| *j == base).ok_or_else(|| {
                err("joint", format!("\"{base}\": Anderson et al. 2007 give the hip, knee and ankle; name one with joint = \"hip\" | \"knee\" | \"ankle\""))
            })?;
            let flexion_sign = match spec.flexion.as_deref() {
                None | Some("positive") => 1.0,
                Some("negative") => -1.0,
                Some(other) => return Err(err("flexion", format!("\"{other}\": expected \"positive\" or \"negative\""))),
            };
            let limbs = spec.limbs.unwrap_or(1);
            if limbs == 0 {
                return Err(err("limbs", "must be at least 1".into()));
            }
            let Some(mgh) = subject else {
                let message = "anderson2007 scales by the subject's weight and stature: it needs a built-in human (model.human)";
                return Err(err("source", message.into()));
            };
            Ok(anderson(joint, limbs, mgh, flexion_sign))
        }
        other => Err(err("source", format!("\"{other}\": expected \"anderson2007\" or \"constant\""))),
    }
}

fn anderson(joint: usize, limbs: u32, mgh: f64, flexion_sign: f64) -> Source {
    let label = format!("Anderson et al. 2007 ({}, {limbs} limb{})", ANDERSON_JOINTS[joint], if limbs > 1 { "s" } else { "" });
    Source::Anderson { joint, scale: f64::from(limbs) * mgh, flexion_sign, label }
}

/// A joint's anatomical name without its side or its flexion axis' letter, and how many limbs it stands
/// for (2 without a side: the built-in humans' lumped pairs): `hip` → (hip, 2), `left_knee` → (knee, 1),
/// `l_hip_y` → (hip, 1) (the whole body's flexion axis; `l_hip_x` stays `hip_x`, not a surface's).
fn anatomical(name: &str) -> (&str, u32) {
    let sides = ["left_", "right_", "l_", "r_"];
    let (base, limbs) = match sides.iter().find_map(|p| name.strip_prefix(p)) {
        Some(base) => (base, 1),
        None => (name, 2),
    };
    (base.strip_suffix("_y").unwrap_or(base), limbs)
}

/// A joint's strength unless the task names one: none for what is not an anatomical joint (a free
/// root's unactuated DOFs, the built-in humans' contact DOFs, any joint whose effort limit is 0), the
/// Anderson surface at a built-in human's hips, knees and ankles, the shaped strength (`model::strength::
/// shaped`, peaks the effort limits) at its lumbar, shoulder-flexion and elbow-flexion axes, else the
/// constant limits.
fn default_source(file: &TaskFile, model: &Model, i: usize, subject: Option<f64>) -> Source {
    let joint = &model.joints[i + 1];
    let contact = file.model.human.is_some() && crate::model::human::CONTACT_DOFS.contains(&joint.name.as_str());
    if model.is_unactuated(i) || contact {
        return Source::None;
    }
    let (base, limbs) = anatomical(&joint.name);
    if let (Some(mgh), Some(k)) = (subject, ANDERSON_JOINTS.iter().position(|j| *j == base)) {
        return anderson(k, limbs, mgh, 1.0);
    }
    let (positive, negative) = (joint.limits.effort_toward(true), joint.limits.effort_toward(false));
    let usable = |v: f64| v.is_finite() && v > 0.0;
    let shaped = SHAPED_JOINTS.iter().position(|j| *j == base).filter(|_| subject.is_some());
    if let Some(k) = shaped.filter(|_| usable(positive) && usable(negative) && !file.output.strength.contains_key(&joint.name)) {
        // +q is flexion at a built-in human: the peaks [extension, flexion] are the limits along −q, +q,
        // or the source's own (lumbar extension, Chaffin et al.) × mass/81 kg like the effort limits.
        let mass = file.model.mass.unwrap_or(crate::model::human::REFERENCE_MASS_KG);
        let own = |flexion: bool| shaped_peak(k, flexion).map(|p| p * mass / crate::model::human::REFERENCE_MASS_KG);
        let (negative, positive) = (own(false).unwrap_or(negative), own(true).unwrap_or(positive));
        let label = format!("{} angle and speed factors × peak {negative:.0}/{positive:.0} N·m (effort limit)", SHAPED_JOINTS[k]);
        return Source::Shaped { joint: k, peaks: [negative, positive], flexion_sign: 1.0, label };
    }
    let (positive, negative, label) = match file.output.strength.get(&joint.name) {
        Some(&s) => (s, s, "constant (output.strength)"),
        None => (joint.limits.effort_toward(true), joint.limits.effort_toward(false), "constant (model effort limit)"),
    };
    match positive.is_finite() && negative.is_finite() && positive > 0.0 && negative > 0.0 {
        true => Source::Constant { positive, negative, label: label.into() },
        false => Source::None,
    }
}
