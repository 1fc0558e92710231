//! The built-in Jack human (paper Table I): its data, scaling, the four structures, sign conventions.

use mintorque::dynamics::{kinematics, Data};
use mintorque::model::human::{self, HumanParams, Structure};
use mintorque::spatial::{Transform, Vec3};
use mintorque::{Error, Model};
use std::f64::consts::{FRAC_PI_2, PI};

const SIZES: [(f64, f64); 3] = [(1.83, 81.0), (1.60, 55.0), (2.05, 110.0)];

fn params(stature_m: f64, mass_kg: f64) -> HumanParams {
    HumanParams { stature_m, mass_kg }
}

fn model(structure: Structure) -> Model {
    human::build(structure, HumanParams::default()).unwrap()
}

/// World placements of every frame at `q`.
struct Pose<'m> {
    model: &'m Model,
    data: Data,
}

impl<'m> Pose<'m> {
    fn new(model: &'m Model, q: &[f64]) -> Self {
        let mut data = Data::new(model);
        kinematics::placements(model, &mut data, q);
        Pose { model, data }
    }

    fn frame(&self, name: &str) -> Transform {
        let i = self.model.frame_index(name).unwrap_or_else(|| panic!("no frame {name}"));
        kinematics::frame_placement(self.model, &self.data, i)
    }

    fn point(&self, name: &str) -> Vec3 {
        self.frame(name).translation
    }

    fn com(&self) -> Vec3 {
        kinematics::center_of_mass(self.model, &self.data, true).unwrap()
    }
}

/// `q` with the named joints set (rad), the rest zero.
fn pose(model: &Model, set: &[(&str, f64)]) -> Vec<f64> {
    let mut q = vec![0.0; model.nv()];
    for &(name, value) in set {
        q[model.dof_index(name).unwrap_or_else(|| panic!("no joint {name}"))] = value;
    }
    q
}

fn assert_close(got: f64, want: f64, tol: f64, what: &str) {
    assert!((got - want).abs() <= tol, "{what}: got {got}, want {want} ± {tol}");
}

#[test]
fn table_one_sums_to_81_115_kg_not_exactly_81() {
    // Counted honestly: two lower arms, upper arms, upper legs, lower legs, feet and palms; one of each
    // torso segment, the neck and the bottom head.
    let sum: f64 = human::TABLE_I.iter().map(|r| r.mass_kg * r.count as f64).sum();
    assert_close(sum, 81.11512, 1e-9, "Table I total (kg)");
    assert_close(human::TABLE_TOTAL_MASS_KG, sum, 1e-12, "TABLE_TOTAL_MASS_KG");
    let excess = (sum - human::REFERENCE_MASS_KG) / human::REFERENCE_MASS_KG;
    assert!(excess > 0.0 && excess < 0.0015, "Table I is {:.3} % off 81 kg", excess * 100.0);
    let paired: u32 = human::TABLE_I.iter().filter(|r| r.count == 2).map(|_| 1).sum();
    assert_eq!(paired, 6, "arms ×2, legs ×2, feet, palms");
    // Limb rows carry a radius, torso rows a width and thickness.
    for row in &human::TABLE_I {
        assert_eq!(row.radius_m.is_some(), row.count == 2 && row.length_m.is_some(), "{}", row.segment);
        assert_eq!(row.width_m.is_some(), row.segment.ends_with("torso"), "{}", row.segment);
    }
}

#[test]
fn chosen_heights_complete_the_stature() {
    let stack = human::FOOT_HEIGHT_M
        + human::LOWER_LEG_LENGTH_M
        + human::UPPER_LEG_LENGTH_M
        + human::LOWER_TORSO_LENGTH_M
        + human::MIDDLE_TORSO_LENGTH_M
        + human::UPPER_TORSO_LENGTH_M
        + human::NECK_LENGTH_M
        + human::HEAD_HEIGHT_M;
    assert_close(stack, 1.83, 1e-12, "standing height (m)");
    assert_close(human::HEAD_HEIGHT_M, 0.1597, 1e-3, "head height (m)");
    assert_close(human::FOOT_HEIGHT_M, 0.0714, 1e-3, "ankle height (m)");
}

#[test]
fn mass_and_height_come_out_right_at_every_size() {
    for (stature, mass) in SIZES {
        let p = params(stature, mass);
        let palms = 2.0 * human::PALM_MASS_KG * p.mass_scale();
        for structure in Structure::ALL {
            let m = human::build(structure, p).unwrap();
            // The push-up chain is cut at the wrist: the palms lie on the floor, outside the model.
            let want = if structure == Structure::PushUp { mass - palms } else { mass };
            assert_close(m.total_mass(), want, 1e-9, &format!("{structure} mass at {stature} m {mass} kg"));
        }
        for structure in [Structure::Sagittal, Structure::FreeArms, Structure::PushUp] {
            let m = human::build(structure, p).unwrap();
            let at = Pose::new(&m, &vec![0.0; m.nv()]);
            let what = format!("{structure} standing height at {stature} m");
            assert_close(at.point("head_top").z - at.point("heel").z, stature, 1e-12, &what);
            assert_close(at.point("toe").z, 0.0, 1e-12, "toe on the floor");
        }
    }
}

#[test]
fn inertias_scale_as_mass_times_length_squared() {
    let a = human::build(Structure::Sagittal, params(1.5, 60.0)).unwrap();
    let b = human::build(Structure::Sagittal, params(2.1, 90.0)).unwrap();
    let k = (90.0 / 60.0) * (2.1f64 / 1.5).powi(2);
    for (ba, bb) in a.bodies.iter().zip(&b.bodies) {
        let (ia, ib) = (ba.inertia.inertia_com, bb.inertia.inertia_com);
        assert!((ib - ia * k).norm() <= 1e-12 * ib.norm().max(1e-300), "{}", ba.name);
    }
}

#[test]
fn every_structure_validates_with_its_documented_joints_and_frames() {
    let expect: [(Structure, &[&str], &[&str]); 4] = [
        (
            Structure::Sagittal,
            &["ankle", "knee", "hip", "lumbar", "shoulder", "elbow", "wrist"],
            &["feet", "toe", "heel", "head_top", "chin", "hands", "barbell"],
        ),
        (
            Structure::FreeArms,
            &[
                "ankle",
                "hip",
                "l_shoulder_z",
                "l_shoulder_y",
                "l_shoulder_x",
                "l_elbow",
                "l_wrist",
                "r_shoulder_z",
                "r_shoulder_y",
                "r_shoulder_x",
                "r_elbow",
                "r_wrist",
            ],
            &["feet", "toe", "heel", "head_top", "chin", "l_hand", "r_hand"],
        ),
        (
            Structure::Hanging,
            &["grip", "wrist", "elbow", "shoulder", "lumbar", "hip", "knee"],
            &["bar", "hands", "head_top", "chin", "toe", "heel"],
        ),
        (
            Structure::PushUp,
            &["toe_pivot", "ankle", "knee", "hip", "lumbar", "shoulder", "elbow"],
            &["floor", "toe", "heel", "head_top", "chin", "hands"],
        ),
    ];
    for (structure, joints, frames) in expect {
        let m = model(structure);
        m.validate("test").unwrap();
        assert_eq!(m.joint_names(), joints, "{structure} joints");
        assert!((6..=13).contains(&m.nv()), "{structure}: {} DOF", m.nv());
        for f in frames {
            assert!(m.frame_index(f).is_some(), "{structure} lacks frame {f}");
        }
        // Every segment with mass has something to draw.
        for b in m.bodies.iter().filter(|b| b.inertia.mass > 0.0) {
            assert!(!b.shapes.is_empty(), "{structure}: body {} has no shapes", b.name);
        }
        // Strengths and passive resistance are positive and finite for muscles.
        for j in &m.joints[1..] {
            assert!(j.limits.effort > 0.0 && j.limits.effort.is_finite(), "{}", j.name);
            let contact = j.name == "grip" || j.name == "toe_pivot";
            assert_eq!(j.passive.is_zero(), contact, "{}: passive {:?}", j.name, j.passive);
        }
    }
}

#[test]
fn structure_names_round_trip_and_unknown_names_list_the_known_ones() {
    assert_eq!(Structure::names(), ["sagittal", "free_arms", "hanging", "push_up", "whole_body"]);
    for s in Structure::ALL {
        assert_eq!(Structure::from_name(s.name()).unwrap(), s);
        assert_eq!(s.to_string().parse::<Structure>().unwrap(), s);
    }
    assert_eq!(Structure::from_name("Push-Up").unwrap(), Structure::PushUp);
    let err = Structure::from_name("cartwheel").unwrap_err();
    assert!(matches!(err, Error::Model { .. }));
    let msg = err.to_string();
    assert!(msg.contains("cartwheel"), "{msg}");
    for name in Structure::names() {
        assert!(msg.contains(name), "{msg}");
    }
}

#[test]
fn out_of_range_stature_and_mass_are_refused_naming_the_field_and_range() {
    let cases = [
        (params(0.4, 81.0), "stature_m", "between 0.5 and 2.5 m"),
        (params(2.6, 81.0), "stature_m", "between 0.5 and 2.5 m"),
        (params(f64::NAN, 81.0), "stature_m", "between 0.5 and 2.5 m"),
        (params(1.83, 19.0), "mass_kg", "between 20 and 250 kg"),
        (params(1.83, 251.0), "mass_kg", "between 20 and 250 kg"),
        (params(1.83, f64::INFINITY), "mass_kg", "between 20 and 250 kg"),
    ];
    for (p, field, range) in cases {
        for structure in Structure::ALL {
            let err = human::build(structure, p).unwrap_err();
            assert!(matches!(&err, Error::Model { element, .. } if element == field), "{err}");
            assert!(err.to_string().contains(range), "{err}");
        }
    }
    for p in [params(0.5, 20.0), params(2.5, 250.0)] {
        human::build(Structure::FreeArms, p).unwrap();
    }
}

#[test]
fn standing_com_is_at_about_0_58_of_stature_over_the_feet() {
    for (stature, mass) in SIZES {
        for structure in [Structure::Sagittal, Structure::FreeArms] {
            let m = human::build(structure, params(stature, mass)).unwrap();
            let at = Pose::new(&m, &vec![0.0; m.nv()]);
            let c = at.com();
            let ratio = c.z / stature;
            // Jack's long legs and heavy upper torso put it at the top of the usual 0.55–0.58.
            assert!((0.55..=0.59).contains(&ratio), "{structure}: CoM at {ratio:.4} × stature");
            assert!(c.x > at.point("heel").x && c.x < at.point("toe").x, "CoM over the feet");
            assert_close(c.y, 0.0, 1e-12, "CoM on the midline");
        }
    }
}

#[test]
fn sagittal_zero_pose_is_upright() {
    let m = model(Structure::Sagittal);
    let at = Pose::new(&m, &vec![0.0; m.nv()]);
    let (head, toe, heel) = (at.point("head_top"), at.point("toe"), at.point("heel"));
    assert_close(head.x, 0.0, 1e-12, "head above the ankles");
    assert_close(head.z, 1.83, 1e-12, "head height");
    assert!(heel.x < 0.0 && toe.x > 0.0 && toe.x - heel.x > 0.25, "foot {heel:?}..{toe:?}");
    let hands = at.point("hands");
    assert!(hands.z > 0.6 && hands.z < 0.95 && hands.x.abs() < 1e-12, "hands hang at {hands:?}");
    assert_eq!(at.point("barbell"), hands);
    for f in &m.frames {
        let r = at.frame(&f.name).rotation;
        assert!((r - mintorque::spatial::Mat3::identity()).norm() < 1e-12, "{} is world-aligned", f.name);
    }
}

#[test]
fn limits_contain_zero_and_the_reference_pose() {
    for structure in Structure::ALL {
        let m = model(structure);
        let q = structure.reference_pose(HumanParams::default()).unwrap();
        for (j, &qi) in m.joints[1..].iter().zip(&q) {
            let l = &j.limits;
            assert!(l.lower <= 0.0 && 0.0 <= l.upper, "{structure} {}: 0 outside [{}, {}]", j.name, l.lower, l.upper);
            assert!(l.lower <= qi && qi <= l.upper, "{structure} {}: {qi} outside limits", j.name);
            assert!(l.upper - l.lower > 0.5, "{structure} {}: a real range", j.name);
        }
    }
}

#[test]
fn reference_poses_are_the_documented_postures() {
    let p = HumanParams::default();
    // Dead hang: everything straight below the bar, head up.
    let m = model(Structure::Hanging);
    let at = Pose::new(&m, &Structure::Hanging.reference_pose(p).unwrap());
    let (hands, head, toe, heel) = (at.point("hands"), at.point("head_top"), at.point("toe"), at.point("heel"));
    assert_close(hands.norm(), 0.0, 1e-12, "hands on the bar");
    assert!(head.z < 0.0 && heel.z < head.z - 1.0, "hangs below the bar, feet down: {head:?} {heel:?}");
    assert!(toe.x > heel.x, "faces forward");
    // The feet reach forward of the ankles, so the straight dead hang is 2 mm off balance.
    assert_close(at.com().x, 0.0, 0.005, "CoM below the bar");
    // Top of a push-up: wrists on the floor under the shoulders, body straight and above the floor.
    let m = model(Structure::PushUp);
    let q = Structure::PushUp.reference_pose(p).unwrap();
    let at = Pose::new(&m, &q);
    let hands = at.point("hands");
    assert_close(hands.z, 0.0, 1e-9, "wrists on the floor");
    assert!(hands.x > 1.0, "hands ahead of the toes: {hands:?}");
    let tilt = q[m.dof_index("toe_pivot").unwrap()].to_degrees();
    assert!((60.0..85.0).contains(&tilt), "body {tilt}° from vertical");
    assert!(at.point("head_top").z > 0.2 && at.point("heel").z > 0.1);
    // Standing.
    assert!(Structure::Sagittal.reference_pose(p).unwrap().iter().all(|&x| x == 0.0));
}

#[test]
fn positive_angles_are_flexion_in_the_sagittal_chain() {
    let m = model(Structure::Sagittal);
    let stand = Pose::new(&m, &vec![0.0; m.nv()]);
    let moved = |joint: &str, angle: f64| Pose::new(&m, &pose(&m, &[(joint, angle)]));
    let shoulder_z = stand.frame("upper_arms").translation.z;
    // Shoulder flexion 90°: arm forward, horizontal.
    let at = moved("shoulder", FRAC_PI_2);
    let hands = at.point("hands");
    assert!(hands.x > 0.6, "hands forward: {hands:?}");
    assert_close(hands.z, shoulder_z, 1e-9, "hands at shoulder height");
    // Elbow flexion: the forearm swings forward and up.
    let at = moved("elbow", FRAC_PI_2);
    assert!(at.point("hands").x > 0.25);
    // Wrist flexion: the hand swings forward.
    assert!(moved("wrist", 0.5).point("hands").x > 0.03);
    // Lumbar and hip flexion bend the trunk forward; extension leans it back.
    assert!(moved("lumbar", 0.5).point("head_top").x > 0.2);
    assert!(moved("lumbar", -0.3).point("head_top").x < -0.1);
    assert!(moved("hip", 0.5).point("head_top").x > 0.3);
    // Knee flexion with the feet planted sends the thighs (hips) backwards.
    assert!(moved("knee", 0.5).frame("lower_torso").translation.x < -0.2);
    // Ankle dorsiflexion tips the shanks forward.
    assert!(moved("ankle", 0.2).frame("upper_legs").translation.x > 0.09);
}

#[test]
fn positive_angles_mean_the_same_on_both_free_arms() {
    let m = model(Structure::FreeArms);
    let stand = Pose::new(&m, &vec![0.0; m.nv()]);
    let y_shoulder = stand.frame("l_upper_arm").translation.y;
    assert!(y_shoulder > 0.1, "left is +y");
    let moved = |set: &[(&str, f64)]| Pose::new(&m, &pose(&m, set));
    // Abduction 90°: each arm out to its own side, horizontal.
    let at = moved(&[("l_shoulder_x", FRAC_PI_2), ("r_shoulder_x", FRAC_PI_2)]);
    assert!(at.point("l_hand").y > y_shoulder + 0.6);
    assert!(at.point("r_hand").y < -y_shoulder - 0.6);
    // Flexion 90°: both forward.
    let at = moved(&[("l_shoulder_y", FRAC_PI_2), ("r_shoulder_y", FRAC_PI_2)]);
    assert!(at.point("l_hand").x > 0.6 && at.point("r_hand").x > 0.6);
    // Internal rotation with the elbows bent: both forearms swing across the belly.
    let bent = [("l_elbow", FRAC_PI_2), ("r_elbow", FRAC_PI_2)];
    let at = moved(&[bent[0], bent[1], ("l_shoulder_z", FRAC_PI_2), ("r_shoulder_z", FRAC_PI_2)]);
    assert!(at.point("l_hand").y < y_shoulder - 0.25, "{:?}", at.point("l_hand"));
    assert!(at.point("r_hand").y > -y_shoulder + 0.25, "{:?}", at.point("r_hand"));
    // Mirror symmetry of any symmetric pose.
    let set: Vec<(String, f64)> =
        [("shoulder_z", 0.3), ("shoulder_y", 0.7), ("shoulder_x", 0.4), ("elbow", 1.1), ("wrist", -0.2)]
            .iter()
            .flat_map(|&(j, a)| [(format!("l_{j}"), a), (format!("r_{j}"), a)])
            .collect();
    let set: Vec<(&str, f64)> = set.iter().map(|(j, a)| (j.as_str(), *a)).collect();
    let at = moved(&set);
    let (l, r) = (at.point("l_hand"), at.point("r_hand"));
    assert!((l - Vec3::new(r.x, -r.y, r.z)).norm() < 1e-12, "{l:?} vs {r:?}");
}

/// The rigid placement of frame `b` relative to frame `a`.
fn relative(at: &Pose, a: &str, b: &str) -> Transform {
    at.frame(a).inverse().compose(&at.frame(b))
}

fn assert_same_placement(x: &Transform, y: &Transform, what: &str) {
    let d = (x.rotation - y.rotation).norm() + (x.translation - y.translation).norm();
    assert!(d < 1e-12, "{what}: {x:?} vs {y:?}");
}

#[test]
fn anatomical_angles_mean_the_same_whichever_way_a_chain_runs() {
    // The same anatomical posture must give the same body shape in every structure, although the
    // hanging chain crosses wrist, elbow, shoulder and lumbar spine from the distal side and the feet-rooted
    // chains cross ankle, knee and hip that way.
    let angles =
        [("ankle", 0.15), ("knee", 0.8), ("hip", 0.6), ("lumbar", -0.2), ("shoulder", 1.3), ("elbow", 0.9), ("wrist", 0.4)];
    let sagittal = model(Structure::Sagittal);
    let ref_pose = Pose::new(&sagittal, &pose(&sagittal, &angles));
    let hanging = model(Structure::Hanging);
    let no_ankle: Vec<_> = angles.iter().copied().filter(|(j, _)| *j != "ankle").collect();
    let mut set = no_ankle.clone();
    set.push(("grip", 2.0));
    let at = Pose::new(&hanging, &pose(&hanging, &set));
    // The hanging chain has no ankle: compare with a straight sagittal ankle.
    let ref_no_ankle = Pose::new(&sagittal, &pose(&sagittal, &no_ankle));
    for frame in ["head_top", "chin", "toe", "heel"] {
        let want = relative(&ref_no_ankle, "hands", frame);
        assert_same_placement(&relative(&at, "hands", frame), &want, &format!("hanging hands→{frame}"));
    }
    let push_up = model(Structure::PushUp);
    let mut set: Vec<_> = angles.iter().copied().filter(|(j, _)| *j != "wrist").collect();
    set.push(("toe_pivot", 0.7));
    let at = Pose::new(&push_up, &pose(&push_up, &set));
    for frame in ["head_top", "chin", "heel", "lower_arms"] {
        let want = relative(&ref_pose, "toe", frame);
        assert_same_placement(&relative(&at, "toe", frame), &want, &format!("push-up toe→{frame}"));
    }
    // The push-up's `hands` frame sits where the sagittal wrist is (the `palms` body frame's origin).
    let want = relative(&ref_pose, "toe", "palms").translation;
    assert!((relative(&at, "toe", "hands").translation - want).norm() < 1e-12, "wrist");
}

#[test]
fn lumped_limbs_double_mass_and_strength() {
    let sagittal = model(Structure::Sagittal);
    let free = model(Structure::FreeArms);
    let body = |m: &Model, name: &str| m.bodies[m.body_index(name).unwrap()].clone();
    let p = HumanParams::default();
    let arms = body(&sagittal, "upper_arms");
    assert_close(arms.inertia.mass, 2.0 * human::UPPER_ARM_MASS_KG * p.mass_scale(), 1e-12, "two upper arms");
    assert_close(arms.inertia.com.y, 0.0, 1e-12, "lumped on the midline");
    // About the pitch axis, the pair's inertia is twice one arm's.
    let one = body(&free, "l_upper_arm").inertia.inertia_com;
    assert_close(arms.inertia.inertia_com[(1, 1)], 2.0 * one[(1, 1)], 1e-12, "I_yy of the pair");
    let joint = |m: &Model, name: &str| m.joints[m.dof_index(name).unwrap() + 1].clone();
    assert_close(joint(&sagittal, "elbow").limits.effort, 2.0 * joint(&free, "l_elbow").limits.effort, 1e-9, "effort");
    assert_close(joint(&free, "l_elbow").limits.effort, 70.0, 1e-9, "elbow strength at 81 kg (N·m)");
    assert_close(joint(&sagittal, "lumbar").limits.effort, 250.0, 1e-9, "the spine is single");
    assert_close(joint(&sagittal, "shoulder").limits.upper, PI, 1e-12, "shoulder flexion to 180°");
}

#[test]
fn shape_inertias_match_the_textbook() {
    let c = human::cylinder_inertia(2.0, 0.1, 0.6);
    assert_close(c[(0, 0)], 2.0 * (3.0 * 0.01 + 0.36) / 12.0, 1e-15, "cylinder across");
    assert_close(c[(2, 2)], 0.01, 1e-15, "cylinder about its axis");
    let b = human::box_inertia(12.0, Vec3::new(0.3, 0.5, 0.2));
    assert_close(b[(0, 0)], 0.25 + 0.04, 1e-15, "box about x");
    assert_close(b[(1, 1)], 0.09 + 0.04, 1e-15, "box about y");
    assert_close(b[(2, 2)], 0.09 + 0.25, 1e-15, "box about z");
    assert_close(human::sphere_inertia(5.0, 0.1)[(0, 0)], 0.02, 1e-15, "sphere");
}
