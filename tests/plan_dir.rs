//! The plan directory as a reader and a second writer meet it: written whole (a writer interrupted at any
//! of its file operations leaves wholly the old plan or wholly the new one, and the next writer cleans
//! up), locked against a concurrent writer, checked against its manifest, never holding a non-finite
//! number.

use mintorque::model::{urdf, Model};
use mintorque::plan_dir::{self, PlanContents, WriteOptions};
use mintorque::report::record::{ContactRecord, PlanRecord, SampleRecord};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn model() -> Model {
    urdf::load(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("models/double_pendulum.urdf")).unwrap()
}

/// A hand-made plan: both joints swing by `amplitude` (rad); with `contact`, a contact at the tip pushes.
fn contents(amplitude: f64, contact: bool, plots: bool) -> PlanContents {
    let m = model();
    let frame = m.frames.last().unwrap().name.clone();
    let contacts: Vec<ContactRecord> = contact
        .then(|| ContactRecord { name: "tip".into(), frame, target: [0.0, 0.0, -1.0], normal: Some([0.0, 0.0, 1.0]) })
        .into_iter()
        .collect();
    let samples = (0..=20)
        .map(|k| {
            let t = k as f64 / 20.0;
            SampleRecord {
                t,
                q: vec![amplitude * t, -amplitude * t],
                qd: vec![amplitude, -amplitude],
                qdd: vec![0.0, 0.0],
                tau: vec![10.0 * t, -3.0],
                contact_forces: contacts.iter().map(|_| [0.0, 0.0, 5.0 + t]).collect(),
            }
        })
        .collect();
    let record = PlanRecord { duration: 1.0, gravity: [0.0, 0.0, -9.81], contacts, ..PlanRecord::of_samples(&m, samples) };
    PlanContents { plots, ..PlanContents::from_record(m, record) }
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mintorque-plandir-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Every file physically in `dir`, by name.
fn files_in(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .map(|e| (e.file_name().into_string().unwrap(), std::fs::read(e.path()).unwrap()))
        .collect()
}

/// What a reader finds: the files of the plan it loads, and (if the directory is there) every file in it.
fn seen(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let loaded = plan_dir::load(dir).unwrap_or_else(|e| panic!("{e}"));
    if dir.exists() {
        let mut on_disk = files_in(dir);
        on_disk.remove(plan_dir::MANIFEST);
        assert_eq!(on_disk, loaded.files, "the directory holds files its manifest does not list");
    }
    loaded.files
}

/// Names beside `dir` other than the directory and its lock file.
fn leftovers(dir: &Path) -> Vec<String> {
    let name = dir.file_name().unwrap().to_string_lossy().into_owned();
    std::fs::read_dir(dir.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| *n != name && *n != format!(".{name}.lock"))
        .collect()
}

#[test]
fn a_writer_interrupted_at_any_file_operation_leaves_the_old_plan_or_the_new_one() {
    let (old, new) = (contents(0.5, true, true), contents(1.0, false, false));
    let (old_files, new_files) = (old.render().unwrap(), new.render().unwrap());
    let mut k = 0;
    loop {
        let dir = scratch(&format!("kill-{k}")).join("plan");
        plan_dir::write(&dir, &old, &WriteOptions::default()).unwrap();
        let result = plan_dir::write(&dir, &new, &WriteOptions { crash_after: Some(k) });
        let got = seen(&dir);
        assert!(got == old_files || got == new_files, "after {k} operations the reader sees a mix");
        // The next writer puts things right: the new plan, whole, and nothing left beside it.
        plan_dir::write(&dir, &new, &WriteOptions::default()).unwrap();
        assert_eq!(seen(&dir), new_files);
        assert!(!dir.join("contact_forces.svg").exists() && !dir.join("q.png").exists(), "stale files of the old plan");
        assert_eq!(leftovers(&dir), Vec::<String>::new(), "after a kill at {k}");
        std::fs::remove_dir_all(dir.parent().unwrap()).unwrap();
        match result {
            Err(plan_dir::Error::Interrupted(n)) => assert_eq!(n, k),
            Ok(()) => break,
            Err(e) => panic!("{e}"),
        }
        k += 1;
    }
    // Every file, its manifest, fsyncs and both renames: all were interrupted once.
    assert!(k > new_files.len() + 4, "only {k} operations");
}

#[test]
fn a_killed_writer_with_no_old_plan_leaves_nothing_a_reader_takes_for_a_plan() {
    let new = contents(1.0, false, false);
    for k in 0..4 {
        let dir = scratch(&format!("fresh-{k}")).join("plan");
        assert!(plan_dir::write(&dir, &new, &WriteOptions { crash_after: Some(k) }).is_err());
        let err = plan_dir::load(&dir).unwrap_err().to_string();
        assert!(err.contains("holds no plan"), "{err}");
        plan_dir::write(&dir, &new, &WriteOptions::default()).unwrap();
        assert_eq!(leftovers(&dir), Vec::<String>::new());
    }
}

#[test]
fn a_second_writer_is_refused_naming_the_directory() {
    let dir = scratch("lock").join("plan");
    let held = plan_dir::lock(&dir).unwrap();
    let err = plan_dir::write(&dir, &contents(1.0, false, false), &WriteOptions::default()).unwrap_err();
    assert!(matches!(err, plan_dir::Error::Locked { .. }), "{err}");
    let message = err.to_string();
    assert!(message.contains(&dir.display().to_string()) && message.contains("another mintorque"), "{message}");
    assert!(!dir.exists(), "the refused writer wrote nothing");
    drop(held);
    plan_dir::write(&dir, &contents(1.0, false, false), &WriteOptions::default()).unwrap();
}

#[test]
fn files_that_do_not_belong_together_are_refused_by_name() {
    let parent = scratch("mixed");
    let (a, b) = (parent.join("a"), parent.join("b"));
    plan_dir::write(&a, &contents(0.5, false, false), &WriteOptions::default()).unwrap();
    plan_dir::write(&b, &contents(1.0, false, false), &WriteOptions::default()).unwrap();
    std::fs::copy(b.join("trajectory.csv"), a.join("trajectory.csv")).unwrap();
    let err = plan_dir::load(&a).unwrap_err().to_string();
    assert!(err.contains("trajectory.csv") && err.contains("does not belong to this plan"), "{err}");
    std::fs::remove_file(a.join("plan.json")).unwrap();
    let err = plan_dir::load(&a).unwrap_err().to_string();
    assert!(err.contains("plan.json") && err.contains("missing"), "{err}");
    std::fs::remove_file(b.join(plan_dir::MANIFEST)).unwrap();
    let err = plan_dir::load(&b).unwrap_err().to_string();
    assert!(err.contains("without a manifest") || err.contains("manifest.json"), "{err}");
}

#[test]
fn only_plan_directories_are_replaced() {
    let parent = scratch("replace");
    let file = parent.join("a-file");
    std::fs::write(&file, "x").unwrap();
    let err = plan_dir::write(&file, &contents(1.0, false, false), &WriteOptions::default()).unwrap_err().to_string();
    assert!(err.contains("a-file") && err.contains("not a directory"), "{err}");
    let other = parent.join("documents");
    std::fs::create_dir(&other).unwrap();
    std::fs::write(other.join("letter.txt"), "keep me").unwrap();
    let err = plan_dir::write(&other, &contents(1.0, false, false), &WriteOptions::default()).unwrap_err().to_string();
    assert!(err.contains("documents") && err.contains("not a plan directory"), "{err}");
    assert_eq!(std::fs::read_to_string(other.join("letter.txt")).unwrap(), "keep me");
}

#[test]
fn non_finite_numbers_are_never_written() {
    let dir = scratch("nan").join("plan");
    let mut c = contents(1.0, true, false);
    c.record.samples[7].tau[1] = f64::NAN;
    let err = plan_dir::write(&dir, &c, &WriteOptions::default()).unwrap_err();
    assert!(matches!(err, plan_dir::Error::NonFinite { .. }), "{err}");
    let message = err.to_string();
    assert!(message.contains("sample 7") && message.contains("elbow") && message.contains("tau"), "{message}");
    assert!(!dir.exists());
    let mut c = contents(1.0, true, false);
    c.record.samples[3].contact_forces[0][2] = f64::INFINITY;
    let message = plan_dir::write(&dir, &c, &WriteOptions::default()).unwrap_err().to_string();
    assert!(message.contains("sample 3") && message.contains("contact force"), "{message}");
}

#[test]
fn files_added_later_belong_to_the_plan_and_a_re_plan_removes_them() {
    let dir = scratch("update").join("plan");
    plan_dir::write(&dir, &contents(0.5, false, false), &WriteOptions::default()).unwrap();
    let id = plan_dir::load(&dir).unwrap().manifest.plan;
    plan_dir::update(&dir, &id, vec![("extra.bvh".into(), b"HIERARCHY".to_vec())], &WriteOptions::default()).unwrap();
    assert!(plan_dir::load(&dir).unwrap().files.contains_key("extra.bvh"));
    let err = plan_dir::update(&dir, "0000", vec![], &WriteOptions::default()).unwrap_err().to_string();
    assert!(err.contains("re-planned"), "{err}");
    plan_dir::write(&dir, &contents(1.0, false, false), &WriteOptions::default()).unwrap();
    assert!(!dir.join("extra.bvh").exists());
}
