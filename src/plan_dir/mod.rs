//! The plan directory: the only code that knows its files. [`write`] writes every file of a plan whole
//! (staging directory, fsync, swap by renames, advisory lock; see [`atomic`]), with a `manifest.json`
//! that lists each file's size and checksum; [`load`] reads it back for `export`, `view` and `simulate`,
//! refusing a directory whose files do not belong together and naming the file; [`update`] adds files
//! (another filmstrip view, an export) to a plan the same way. Before anything is written the plan's
//! arrays are checked finite ([`finite`]).
//!
//! The files: `plan.json` (the plan, [`PlanRecord`]), `model.figure.toml` (its model), `trajectory.csv`,
//! `torques.sto` (the torques as OpenSim's inverse dynamics writes them),
//! `summary.json`, `task.resolved.toml` (the task as planned, CLI overrides included), the plots
//! `q/qd/qdd/tau[/contact_forces].{svg,png}`, `motion.html`, `filmstrip.{svg,png}` in the task's view,
//! other views as `filmstrip-VIEW.{svg,png}`, and `manifest.json`.

pub mod atomic;
mod files;
pub mod finite;
pub mod manifest;
mod warm;

pub use atomic::{lock, Lock, WriteOptions};
pub use files::PlanContents;
pub use manifest::Manifest;
pub use warm::{refine_from, warm_start};

use crate::model::{figure, Model};
use crate::plan::task::Task;
use crate::report::filmstrip::View;
use crate::report::record::PlanRecord;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The format of a plan directory, in its `manifest.json`.
pub const FORMAT: &str = "mintorque-plan-dir-1";
/// The manifest's file name.
pub const MANIFEST: &str = "manifest.json";

/// What reading or writing a plan directory can fail with.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Bad input in one of its files, or a file that cannot be read or written.
    #[error(transparent)]
    Input(#[from] crate::Error),
    /// The directory (or a file in it) is not what it should be: not a plan, files of different plans.
    #[error("{path}: {message}")]
    Dir {
        /// The directory or file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// Another writer holds the directory's lock.
    #[error("{dir}: another mintorque is writing this plan directory (it holds {lock}); wait for it to finish")]
    Locked {
        /// The plan directory.
        dir: PathBuf,
        /// The lock file the other writer holds.
        lock: PathBuf,
    },
    /// A result that is not a finite number: nothing is written.
    #[error("non-finite result, nothing written: {stage}, {at}: {quantity} = {value}")]
    NonFinite {
        /// The stage that produced it (e.g. "the planned motion").
        stage: String,
        /// Where: the sample or node, joint or contact.
        at: String,
        /// The quantity (a torque, a position …).
        quantity: String,
        /// The value (NaN or ±inf).
        value: f64,
    },
    /// The writer stopped at an injected fault ([`WriteOptions::crash_after`]) after this many operations.
    #[error("write interrupted (injected fault) after {0} file operations")]
    Interrupted(usize),
}

/// The plan directory's result type.
pub type Result<T> = std::result::Result<T, Error>;

/// A plan directory as read back, every file checked against the manifest.
#[derive(Clone, Debug)]
pub struct LoadedPlan {
    /// Where it was read from (the directory, or the old plan a killed writer left aside).
    pub dir: PathBuf,
    /// Its `manifest.json`.
    pub manifest: Manifest,
    /// Every file, by name, as checked.
    pub files: BTreeMap<String, Vec<u8>>,
    /// The figure, read from `model.figure.toml`.
    pub model: Model,
    /// `plan.json`.
    pub record: PlanRecord,
}

impl LoadedPlan {
    /// `summary.json`'s text, if the plan has one.
    pub fn summary(&self) -> Option<&str> {
        self.files.get("summary.json").and_then(|b| std::str::from_utf8(b).ok())
    }
}

/// Writes the plan `contents` as the whole of directory `dir` (created if needed; an existing plan
/// directory is replaced, files of the old plan included; any other non-empty directory is refused).
pub fn write(dir: &Path, contents: &PlanContents, options: &WriteOptions) -> Result<()> {
    write_reporting(dir, contents, options, &mut |_, _, _| {})
}

/// [`write`], calling `progress(k, n, stage)` before each of the `n` stages of rendering the files (see
/// [`PlanContents::stages`]) and once more, as stage `n + 1` of `n + 1`, before saving them.
pub fn write_reporting(
    dir: &Path,
    contents: &PlanContents,
    options: &WriteOptions,
    progress: &mut dyn FnMut(usize, usize, &str),
) -> Result<()> {
    finite::check_contents(contents)?;
    let n = contents.stages().len() + 1;
    let files = contents.render_reporting(&mut |k, _, stage| progress(k, n, stage))?;
    progress(n, n, "saving the files");
    atomic::Writer::begin(dir)?.commit(&files, options)
}

/// Writes `files` (name → bytes) as the whole of directory `dir` with their manifest, as a plan is
/// written (lock, staging directory, fsync, swap by renames): for results that are not a plan, such as
/// those of `mintorque inverse`. The same directories are accepted and refused as by [`write`].
pub fn write_files(dir: &Path, files: &BTreeMap<String, Vec<u8>>, options: &WriteOptions) -> Result<()> {
    atomic::Writer::begin(dir)?.commit(files, options)
}

/// Adds (or replaces) `new_files` in the plan of `dir`, which must still be plan `plan_id` (the
/// manifest's `plan` when the files were made from it).
pub fn update(dir: &Path, plan_id: &str, new_files: Vec<(String, Vec<u8>)>, options: &WriteOptions) -> Result<()> {
    let writer = atomic::Writer::begin(dir)?;
    let (manifest, mut files) = read_verified(&writer.target.path)?;
    if manifest.plan != plan_id {
        let message = "was re-planned meanwhile: run the command again".to_string();
        return Err(Error::Dir { path: writer.target.path.clone(), message });
    }
    files.extend(new_files);
    writer.commit(&files, options)
}

/// Reads plan directory `dir`, checking every file against its manifest.
pub fn load(dir: &Path) -> Result<LoadedPlan> {
    let target = atomic::Target::new_for_reading(dir)?;
    let dir = target.orphaned_old().unwrap_or(target.path);
    let (manifest, files) = read_verified(&dir)?;
    let record = parse_record(&dir, &files)?;
    let model_text = text_of(&dir, &files, "model.figure.toml")?;
    let model = figure::parse(model_text, &dir.join("model.figure.toml").display().to_string())?;
    check_record_fits(&dir, &model, &record)?;
    Ok(LoadedPlan { dir, manifest, files, model, record })
}

/// A plan directory's task (`task.resolved.toml`) and the solver unknowns of its plan — enough to sample
/// or simulate the plan again without solving.
pub fn load_task(dir: &Path) -> Result<(LoadedPlan, Task, Vec<f64>)> {
    let plan = load(dir)?;
    let path = plan.dir.join("task.resolved.toml");
    let task = Task::parse(text_of(&plan.dir, &plan.files, "task.resolved.toml")?, &path)?;
    let layout = crate::plan::Transcription::new(&task.spec)?.layout;
    let r = &plan.record;
    if r.n_ctrl != task.spec.n_ctrl || r.ctrl.len() != r.n_ctrl * layout.nv || r.lambda_ctrl.len() != r.n_ctrl * layout.n_lambda {
        let message = format!(
            "plan.json has {} control points of {} joints, task.resolved.toml asks for {} of {}: they do not belong together",
            r.n_ctrl,
            r.joint_names.len(),
            task.spec.n_ctrl,
            layout.nv
        );
        return Err(Error::Dir { path, message });
    }
    let x = layout.pack(&r.ctrl, &r.lambda_ctrl);
    Ok((plan, task, x))
}

/// The file names of a filmstrip seen from `view` beside the plan's own (`filmstrip-VIEW.svg`, `.png`).
pub fn filmstrip_names(view: Option<View>) -> [String; 2] {
    match view {
        None => ["filmstrip.svg".into(), "filmstrip.png".into()],
        Some(v) => [format!("filmstrip-{}.svg", v.name()), format!("filmstrip-{}.png", v.name())],
    }
}

/// Regenerates `motion.html` of plan directory `dir` and, with `view`, adds the filmstrip seen from it
/// beside the plan's own (`filmstrip-VIEW.svg`, `.png`). Returns the page's path.
pub fn write_views(dir: &Path, view: Option<View>) -> Result<PathBuf> {
    let plan = load(dir)?;
    let mut new_files = vec![files::motion_html(&plan.model, &plan.record, plan.summary())];
    if let Some(v) = view {
        new_files.extend(files::filmstrip(&plan.model, &plan.record, v, filmstrip_names(Some(v)))?);
    }
    update(dir, &plan.manifest.plan, new_files, &WriteOptions::default())?;
    Ok(plan.dir.join(crate::report::viewer::VIEW_FILES[0]))
}

/// Writes one file (an export, a figure) whole: a temporary file beside it, fsynced, renamed over it.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    atomic::write_file(path, bytes)
}

fn read_verified(dir: &Path) -> Result<(Manifest, BTreeMap<String, Vec<u8>>)> {
    // A writer may swap the directory between the manifest and the files: read again if it did.
    let mut last = None;
    for _ in 0..3 {
        let manifest_bytes = read_manifest(dir)?;
        let manifest = Manifest::parse(&manifest_bytes, dir)?;
        match read_files(dir, &manifest) {
            Ok(files) => return Ok((manifest, files)),
            Err(e) if read_manifest(dir).ok().as_ref() != Some(&manifest_bytes) => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.expect("three attempts"))
}

fn read_manifest(dir: &Path) -> Result<Vec<u8>> {
    let path = dir.join(MANIFEST);
    match std::fs::read(&path) {
        Ok(b) => Ok(b),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(Error::Dir { path: dir.to_path_buf(), message: no_plan(dir) }),
        Err(e) => Err(crate::Error::io(path, e).into()),
    }
}

fn no_plan(dir: &Path) -> String {
    if dir.join("plan.json").is_file() {
        "holds a plan written before plan directories had a manifest.json: plan it again".into()
    } else {
        "this directory holds no plan (run `mintorque plan TASK.toml --out DIR` first)".into()
    }
}

fn read_files(dir: &Path, manifest: &Manifest) -> Result<BTreeMap<String, Vec<u8>>> {
    let mut files = BTreeMap::new();
    for name in manifest.files.keys() {
        let path = dir.join(name);
        let bytes = std::fs::read(&path).map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => {
                Error::Dir { path: path.clone(), message: "is missing (manifest.json lists it)".into() }
            }
            _ => crate::Error::io(&path, e).into(),
        })?;
        manifest.check(dir, name, &bytes)?;
        files.insert(name.clone(), bytes);
    }
    Ok(files)
}

fn text_of<'a>(dir: &Path, files: &'a BTreeMap<String, Vec<u8>>, name: &str) -> Result<&'a str> {
    let path = dir.join(name);
    let bytes = files.get(name).ok_or_else(|| Error::Dir { path: path.clone(), message: "is missing from the plan".into() })?;
    std::str::from_utf8(bytes).map_err(|e| Error::Dir { path, message: format!("is not UTF-8 text: {e}") })
}

fn parse_record(dir: &Path, files: &BTreeMap<String, Vec<u8>>) -> Result<PlanRecord> {
    let origin = dir.join("plan.json").display().to_string();
    let text = text_of(dir, files, "plan.json")?;
    let record: PlanRecord =
        serde_json::from_str(text).map_err(|e| crate::Error::input(&origin, format!("line {}", e.line()), e.to_string()))?;
    if record.format != crate::report::record::FORMAT {
        let message = format!("expected \"{}\", found \"{}\"", crate::report::record::FORMAT, record.format);
        return Err(crate::Error::input(origin, "format", message).into());
    }
    Ok(record)
}

fn check_record_fits(dir: &Path, model: &Model, record: &PlanRecord) -> Result<()> {
    let origin = dir.join("plan.json").display().to_string();
    if model.joint_names() != record.joint_names.iter().map(String::as_str).collect::<Vec<_>>() {
        return Err(crate::Error::input(origin, "joint_names", "do not match model.figure.toml's joints").into());
    }
    crate::report::check_samples(model, record).map_err(|e| relabel(e, &origin))?;
    crate::report::scene::check_record(model, record).map_err(|m| crate::Error::input(origin, "samples", m))?;
    finite::check_record(record, "plan.json")
}

/// A report error about "plan.json" made to name the real file.
fn relabel(e: crate::Error, origin: &str) -> crate::Error {
    match e {
        crate::Error::Input { field, message, .. } => crate::Error::input(origin, field, message),
        other => other,
    }
}
