//! Which way is up: `environment.up` turns the gravity presets, and a figure modelled with another up axis
//! (a Y-up URDF under the default Z-up) gets a warning naming the field instead of being planned lying down.

use mintorque::plan::task::Task;
use mintorque::spatial::Vec3;
use std::path::PathBuf;

/// A three-link figure standing along +y at rest (as Y-up tools export it), 1.5 m tall.
fn y_up_urdf() -> String {
    let link = |name: &str| {
        format!(
            r#"<link name="{name}"><inertial><origin xyz="0 0.25 0"/><mass value="10"/>
               <inertia ixx="0.2" iyy="0.02" izz="0.2" ixy="0" ixz="0" iyz="0"/></inertial></link>"#
        )
    };
    let joint = |name: &str, parent: &str, child: &str, y: f64| {
        format!(
            r#"<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/>
               <origin xyz="0 {y} 0"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="500" velocity="5"/></joint>"#
        )
    };
    format!(
        r#"<robot name="yup"><link name="ground"/>{}{}{}{}{}{}</robot>"#,
        link("shank"),
        link("thigh"),
        link("trunk"),
        joint("ankle", "ground", "shank", 0.0),
        joint("knee", "shank", "thigh", 0.5),
        joint("hip", "thigh", "trunk", 0.5)
    )
}

fn task(test: &str, environment: &str) -> (PathBuf, String) {
    let dir = std::env::temp_dir().join(format!("mintorque-up-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("yup.urdf"), y_up_urdf()).unwrap();
    let text = format!(
        "[model]\nurdf = \"yup.urdf\"\n[environment]\n{environment}\n[motion]\nduration = 1.0\n\
         start = {{ ankle = 0.0, knee = 0.0, hip = 0.0 }}\ngoal = {{ ankle = 0.0, knee = 20.0, hip = -20.0 }}\n"
    );
    (dir.join("task.toml"), text)
}

#[test]
fn a_y_up_figure_under_the_default_up_is_warned_about() {
    let (path, text) = task("warned", "gravity = \"earth\"");
    let t = Task::parse(&text, &path).unwrap();
    assert_eq!(t.spec.gravity, Vec3::new(0.0, 0.0, -9.81));
    let warning = t.warnings.iter().find(|w| w.contains("environment.up")).expect("a warning about the up axis");
    assert!(warning.contains("task.toml") && warning.contains("\"+y\""), "{warning}");
}

#[test]
fn environment_up_turns_the_gravity_presets_and_silences_the_warning() {
    let (path, text) = task("turned", "gravity = \"mars\"\nup = \"+y\"");
    let t = Task::parse(&text, &path).unwrap();
    assert_eq!(t.spec.gravity, Vec3::new(0.0, -3.71, 0.0));
    assert!(t.warnings.iter().all(|w| !w.contains("environment.up")), "{:?}", t.warnings);
}

#[test]
fn an_unknown_up_axis_is_refused_naming_the_field() {
    let (path, text) = task("unknown", "up = \"north\"");
    let Err(e) = Task::parse(&text, &path) else { panic!("accepted up = \"north\"") };
    let e = e.to_string();
    assert!(e.contains("environment.up") && e.contains("north") && e.contains("\"+y\""), "{e}");
}

#[test]
fn the_bundled_z_up_examples_get_no_up_warning() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue; // examples/sweeps/ holds sweep files
        }
        let t = Task::load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(t.warnings.iter().all(|w| !w.contains("environment.up")), "{}: {:?}", path.display(), t.warnings);
    }
}
