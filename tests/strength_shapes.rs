//! The lumbar, shoulder and elbow strengths that depend on angle and velocity (`model::strength::shaped`):
//! their slopes, their angle convention on the built-in humans (both sides), and what they do to a plan.

use mintorque::dynamics::{kinematics, Data};
use mintorque::model::strength::{shaped, Source, SHAPED_JOINTS};
use mintorque::plan::task::Task;
use mintorque::report::ergonomics::Setup;
use std::path::Path;

/// Every DOF's strength source of the task `text`.
fn sources(text: &str) -> (Vec<Source>, mintorque::Model) {
    let task = Task::parse(text, Path::new("shapes.toml")).unwrap();
    let setup = Setup::resolve(&task.file, &task.spec, "shapes.toml").unwrap();
    (setup.strength, task.spec.model.clone())
}

fn whole_body() -> &'static str {
    "[model]\nhuman = \"whole_body\"\n\n[motion]\nduration = 1.0\nstart = {}\n\n[[motion.frame_goal]]\nframe = \"l_hand\"\nposition = [0.3, 0.2, 1.0]\n"
}

#[test]
fn shaped_strength_slopes_match_differences() {
    let h = 1e-6;
    for joint in 0..SHAPED_JOINTS.len() {
        for flexion_sign in [1.0, -1.0] {
            let source = Source::Shaped { joint, peaks: [120.0, 80.0], flexion_sign, label: String::new() };
            for positive in [true, false] {
                for (q, qd) in [(0.3f64, 0.0f64), (1.2, 0.8), (-0.2, -0.7), (2.0, 3.0), (0.9, 0.02)] {
                    let (q, qd) = (q * flexion_sign, qd);
                    for smoothing in [0.0, 0.05] {
                        // away from ω = 0 when unsmoothed (a corner there)
                        if smoothing == 0.0 && qd.abs() < 0.1 {
                            continue;
                        }
                        let at = |q: f64, qd: f64| source.at_quantile(q, qd, positive, -0.5, 0.2, smoothing).unwrap();
                        let s = at(q, qd);
                        let d1 = (at(q + h, qd).value - at(q - h, qd).value) / (2.0 * h);
                        let d2 = (at(q, qd + h).value - at(q, qd - h).value) / (2.0 * h);
                        let ok = (s.d1 - d1).abs() < 1e-5 * (1.0 + d1.abs()) && (s.d2 - d2).abs() < 1e-5 * (1.0 + d2.abs());
                        assert!(ok, "{joint} s={flexion_sign} +{positive} q={q} q̇={qd} ε={smoothing}: {s:?} against {d1}, {d2}");
                    }
                }
            }
        }
    }
    // The corners are where a factor meets its 0.1 floor.
    for joint in 0..SHAPED_JOINTS.len() {
        for flexion in [false, true] {
            let (shape, _) = shaped::shape(joint, flexion);
            let ([lo, hi], omega) = shape.corners();
            for theta in [lo, hi] {
                assert!((shape.sloped(theta, 0.0, 0.0).value - 0.1).abs() < 1e-9);
            }
            assert!((shape.sloped(shape.peak_angle, omega, 0.0).value - 0.1).abs() < 1e-9);
            assert!(shape.sloped(shape.peak_angle, 0.99 * omega, 0.0).value > 0.1);
        }
    }
}

#[test]
fn elbow_flexion_strength_peaks_at_the_sources_angle_on_both_sides_and_where_the_hand_rises() {
    let (s, model) = sources(whole_body());
    let mut q = vec![0.0; model.nv()];
    for side in ["l", "r"] {
        let name = format!("{side}_elbow_y");
        let i = model.dof_index(&name).unwrap();
        assert!(matches!(s[i], Source::Shaped { joint: 2, .. }), "{name}: {:?}", s[i]);
        // +q is flexion on this side: bending the elbow from the hanging arm raises the hand and brings it forward.
        let hand = |q: &[f64]| {
            let mut data = Data::new(&model);
            kinematics::placements(&model, &mut data, q);
            kinematics::frame_placement(&model, &data, model.frame_index(&format!("{side}_hand")).unwrap()).translation
        };
        let straight = hand(&q);
        q[i] = 90f64.to_radians();
        let bent = hand(&q);
        q[i] = 0.0;
        assert!(bent.z > straight.z + 0.15 && bent.x > straight.x + 0.15, "{name}: {straight:?} → {bent:?}");
        // The flexors (τ > 0) are strongest at Tsunoda et al.'s 60° of flexion, stronger at 90° than straight.
        let flexors = |deg: f64| s[i].strength(deg.to_radians(), 0.0, 1.0, 0.2).unwrap().0;
        let best = (0..=150).map(f64::from).max_by(|a, b| flexors(*a).total_cmp(&flexors(*b))).unwrap();
        assert_eq!(best, 60.0, "{name}");
        assert!(flexors(90.0) > 1.05 * flexors(0.0), "{name}: {} at 90°, {} at 0°", flexors(90.0), flexors(0.0));
        // The extensors (τ < 0) peak where the Gymnast set puts them, 94° of flexion.
        let extensors = |deg: f64| s[i].strength(deg.to_radians(), 0.0, -1.0, 0.2).unwrap().0;
        let best = (0..=150).map(f64::from).max_by(|a, b| extensors(*a).total_cmp(&extensors(*b))).unwrap();
        assert_eq!(best, 94.0, "{name}");
    }
    // The shoulder's flexion axis and the lumbar flexion get a shape; the abduction axis stays constant.
    let at = |n: &str| &s[model.dof_index(n).unwrap()];
    assert!(
        matches!(at("l_shoulder_y"), Source::Shaped { joint: 1, .. })
            && matches!(at("lumbar_y"), Source::Shaped { joint: 0, .. })
    );
    assert!(matches!(at("l_shoulder_x"), Source::Constant { .. }) && matches!(at("thoracic_y"), Source::Constant { .. }));
}

/// The shoulder's strength source of the sagittal arm lift (`examples/arm_lift_earth.toml`).
fn shoulder() -> Source {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/arm_lift_earth.toml")).unwrap();
    let (s, model) = sources(&text);
    s[model.dof_index("shoulder").unwrap()].clone()
}

#[test]
fn a_fast_arm_raise_has_less_shoulder_strength_available_than_the_same_raise_slow() {
    let source = shoulder();
    assert!(matches!(source, Source::Shaped { joint: 1, .. }), "{source:?}");
    // The same minimum-jerk path, 0 → 170° of flexion, in 0.6 s and in 2.4 s: q = Q s(u), q̇ = Q ṡ(u)/T,
    // s = 10u³ − 15u⁴ + 6u⁵. Raising, the flexors (τ > 0) shorten; lowering the same way back, they lengthen.
    let range = 170f64.to_radians();
    let path = |u: f64| (range * (10.0 * u.powi(3) - 15.0 * u.powi(4) + 6.0 * u.powi(5)), range * 30.0 * (u * (1.0 - u)).powi(2));
    let available = |duration: f64, u: f64, raising: bool| {
        let (q, rate) = path(u);
        let qd = if raising { rate / duration } else { -rate / duration };
        source.strength(q, qd, 1.0, 0.2).unwrap().0
    };
    for u in (1..20).map(|k| f64::from(k) / 20.0) {
        let (fast, slow) = (available(0.6, u, true), available(2.4, u, true));
        assert!(fast < slow, "u = {u}: fast {fast}, slow {slow} N·m");
        // Lengthening (eccentric), the strength is taken at its isometric value however fast.
        assert_eq!(available(0.6, u, false), available(2.4, u, false), "u = {u}");
    }
    // Mid-raise, fast (9.3 rad/s) leaves about a quarter of the held strength, slow (2.3 rad/s) about 70 %.
    let held = source.strength(path(0.5).0, 0.0, 1.0, 0.2).unwrap().0;
    let (fast, slow) = (available(0.6, 0.5, true) / held, available(2.4, 0.5, true) / held);
    assert!(fast < 0.35 && slow > 0.65, "fast {fast}, slow {slow}");
}
