//! Which filmstrips a plan directory gets: a 3D plan is shown from the front and from the side whatever
//! its task's `output.filmstrip_view` (the other views beside it); a planar plan only in its own view.

use mintorque::model::human::{HumanParams, Structure};
use mintorque::model::{urdf, Model};
use mintorque::plan_dir::{self, PlanContents, WriteOptions};
use mintorque::report::filmstrip::View;
use mintorque::report::record::{PlanRecord, SampleRecord};
use std::path::Path;

/// A record of `model` bending every joint smoothly by up to `amplitude` rad over 11 samples in 1 s.
fn record(model: &Model, amplitude: f64) -> PlanRecord {
    let nv = model.nv();
    let samples = (0..11)
        .map(|k| {
            let t = k as f64 / 10.0;
            let s = 0.5 - 0.5 * (std::f64::consts::PI * t).cos();
            let q = (0..nv).map(|j| amplitude * s * if j % 2 == 0 { 1.0 } else { -0.7 }).collect();
            SampleRecord { t, q, qd: vec![0.0; nv], qdd: vec![0.0; nv], tau: vec![1.0; nv], contact_forces: vec![] }
        })
        .collect();
    PlanRecord { duration: 1.0, gravity: [0.0, 0.0, -9.81], ..PlanRecord::of_samples(model, samples) }
}

/// The filmstrip files `model`'s plan directory gets when its task asks for `view`.
fn filmstrips(model: &Model, view: View) -> Vec<String> {
    let dir =
        std::env::temp_dir().join(format!("mintorque-filmstrip-views-{}-{}-{}", std::process::id(), model.name, view.name()));
    let _ = std::fs::remove_dir_all(&dir);
    let contents = PlanContents { filmstrip_view: view, ..PlanContents::from_record(model.clone(), record(model, 0.3)) };
    plan_dir::write(&dir, &contents, &WriteOptions::default()).unwrap();
    let loaded = plan_dir::load(&dir).unwrap();
    let mut names: Vec<String> = loaded.manifest.files.keys().filter(|n| n.starts_with("filmstrip")).cloned().collect();
    names.sort();
    for n in &names {
        assert!(dir.join(n).metadata().unwrap().len() > 0, "{n} is empty");
    }
    for (v, file) in [(View::Front, "filmstrip-front.svg"), (View::Side, "filmstrip-side.svg")] {
        if names.iter().any(|n| n == file) {
            let svg = std::fs::read_to_string(dir.join(file)).unwrap();
            assert!(svg.contains(&format!("{} view", v.name())), "{file} is not the {} view", v.name());
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
    names
}

#[test]
fn a_3d_plan_gets_front_and_side_filmstrips_whatever_its_view() {
    let whole = Structure::WholeBody.build(HumanParams::default()).unwrap();
    let s = |v: &[&str]| v.iter().map(|n| n.to_string()).collect::<Vec<_>>();
    // The side view (default): the front beside it.
    assert_eq!(
        filmstrips(&whole, View::Side),
        s(&["filmstrip-front.png", "filmstrip-front.svg", "filmstrip.png", "filmstrip.svg"])
    );
    // The front view (one_hand_carry): the side beside it.
    assert_eq!(
        filmstrips(&whole, View::Front),
        s(&["filmstrip-side.png", "filmstrip-side.svg", "filmstrip.png", "filmstrip.svg"])
    );
    // The top view (twist_lift): both.
    let top = s(&[
        "filmstrip-front.png",
        "filmstrip-front.svg",
        "filmstrip-side.png",
        "filmstrip-side.svg",
        "filmstrip.png",
        "filmstrip.svg",
    ]);
    assert_eq!(filmstrips(&whole, View::Top), top);
}

#[test]
fn a_planar_plan_gets_its_own_view_only() {
    let pendulum = urdf::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models/double_pendulum.urdf")).unwrap();
    for view in [View::Side, View::Front, View::Top] {
        assert_eq!(filmstrips(&pendulum, view), ["filmstrip.png", "filmstrip.svg"], "{}", view.name());
    }
}
