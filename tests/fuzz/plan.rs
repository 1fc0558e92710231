//! The task-file and plan-directory readers: the bundled examples mutated, parsed and resolved; a fraction
//! planned on a tiny budget and written as a plan directory, read back; and a real plan directory with one
//! file mutated (its manifest rewritten to match, or not), read back as `export`/`view`/`simulate` do.

use crate::check::{guarded, names_file, PARSE_BOUND, PLAN_BOUND};
use crate::mutate::{apply, mutations};
use crate::{run, seeds, shown};
use mintorque::plan::{self, task::Task};
use mintorque::plan_dir::{self, Manifest, PlanContents, WriteOptions};
use proptest::prelude::*;
use proptest::sample::select;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A task's text with a tiny budget: 6 control points, 20 iterations, 1 s, no plots, 20 samples a second.
fn short(text: &str) -> String {
    let mut table: toml::Table = text.parse().expect("a bundled example is TOML");
    let mut set = |section: &str, key: &str, value: toml::Value| {
        let t = table.entry(section).or_insert_with(|| toml::Value::Table(toml::Table::new()));
        t.as_table_mut().expect("a section is a table").insert(key.into(), value);
    };
    set("discretization", "control_points", toml::Value::Integer(6));
    set("solver", "max_iterations", toml::Value::Integer(20));
    set("solver", "time_limit", toml::Value::Float(1.0));
    set("output", "plots", toml::Value::Boolean(false));
    set("output", "sample_rate", toml::Value::Float(20.0));
    toml::to_string(&table).expect("TOML")
}

/// A scratch directory of its own for one case.
fn scratch(name: &str) -> PathBuf {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let d = std::env::temp_dir().join(format!("mintorque-fuzz-{}-{name}-{k}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Parses (and with `plan_it`, plans, writes and reads back) task `text` read as `path`.
fn task_case(text: &str, path: &Path, plan_it: bool) -> Result<(), String> {
    let origin = shown(path);
    let task = match Task::parse(text, path) {
        Err(e) => return names_file(&e.to_string(), &origin),
        Ok(task) => task,
    };
    if !plan_it || task.spec.n_ctrl > 24 {
        return Ok(());
    }
    plan_and_write(task)
}

/// Plans `task` on a tiny budget, writes its plan directory and reads it back: finite and whole.
fn plan_and_write(mut task: Task) -> Result<(), String> {
    task.settings.max_iterations = task.settings.max_iterations.min(20);
    task.settings.time_limit = Some(task.settings.time_limit.unwrap_or(1.0).min(1.0));
    let rows = task.spec.duration * task.file.output.sample_rate;
    if rows > 400.0 {
        task.file.output.sample_rate *= 400.0 / rows;
    }
    let origin = shown(&task.path);
    let planned = plan::plan(&task.spec, task.solver, &task.settings, &mut |_| {}).map_err(|e| format!("plan: {e}"))?;
    let contents = PlanContents::from_task(&task, &planned, true).map_err(|e| format!("{origin}: plan contents: {e}"))?;
    let dir = scratch("task");
    plan_dir::write(&dir, &contents, &WriteOptions::default()).map_err(|e| format!("{origin}: writing the plan: {e}"))?;
    let back = plan_dir::load_task(&dir).map_err(|e| format!("{origin}: reading the plan back: {e}"));
    let _ = std::fs::remove_dir_all(&dir);
    let (loaded, _, x) = back?;
    match x.iter().all(|v| v.is_finite()) && loaded.record.n_ctrl == task.spec.n_ctrl {
        true => Ok(()),
        false => Err(format!("{origin}: the plan read back is not the plan written")),
    }
}

#[test]
fn task_reader_and_short_plans() {
    let files = seeds("examples", ".toml");
    let shortened: Vec<String> = files.iter().map(|(_, t)| short(t)).collect();
    let strategy = (select((0..files.len()).collect::<Vec<_>>()), mutations(), prop::bool::weighted(0.15));
    run("task file", 3000, strategy, |(k, edits, plan_it)| {
        let (path, text) = (files[k].0.clone(), apply(if plan_it { &shortened[k] } else { &files[k].1 }, &edits));
        let input = text.clone();
        let bound = if plan_it { PLAN_BOUND } else { PARSE_BOUND };
        guarded(bound, move || task_case(&text, &path, plan_it)).map_err(|e| format!("{e}\n--- the input ---\n{input}"))
    });
}

/// The files of a real plan directory (the double pendulum, planned briefly).
fn template_plan() -> BTreeMap<String, Vec<u8>> {
    let path = crate::root().join("examples/double_pendulum.toml");
    let text = short(&std::fs::read_to_string(&path).unwrap());
    let task = Task::parse(&text, &path).unwrap_or_else(|e| panic!("{e}"));
    let dir = scratch("template");
    let planned = plan::plan(&task.spec, task.solver, &task.settings, &mut |_| {}).unwrap_or_else(|e| panic!("{e}"));
    let contents = PlanContents::from_task(&task, &planned, true).unwrap_or_else(|e| panic!("{e}"));
    plan_dir::write(&dir, &contents, &WriteOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let files = plan_dir::load(&dir).unwrap_or_else(|e| panic!("{e}")).files;
    let _ = std::fs::remove_dir_all(&dir);
    files
}

/// Writes `files` (one of them mutated) as a directory, with a manifest that matches them when `rehash`,
/// and reads it back.
fn plan_dir_case(mut files: BTreeMap<String, Vec<u8>>, rehash: bool) -> Result<(), String> {
    let dir = scratch("dir");
    std::fs::create_dir_all(&dir).unwrap();
    if rehash {
        files.remove(plan_dir::MANIFEST);
        files.insert(plan_dir::MANIFEST.into(), Manifest::of(&files).to_bytes());
    }
    for (name, bytes) in &files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    let answer = match plan_dir::load_task(&dir) {
        Err(e) => names_file(&e.to_string(), &shown(&dir)),
        Ok((loaded, task, x)) => match x.iter().all(|v| v.is_finite()) && loaded.record.n_ctrl == task.spec.n_ctrl {
            true => Ok(()),
            false => Err("a plan directory read back with non-finite or inconsistent unknowns".into()),
        },
    };
    let _ = std::fs::remove_dir_all(&dir);
    answer
}

#[test]
fn plan_directory_reader() {
    let template = template_plan();
    let names: Vec<String> = template.keys().filter(|n| !n.ends_with(".png") && !n.ends_with(".html")).cloned().collect();
    let strategy = (select(names.clone()), mutations(), prop::bool::weighted(0.8));
    run("plan directory", 2000, strategy, |(name, edits, rehash)| {
        let mut files = template.clone();
        let text = String::from_utf8_lossy(&files[&name]).into_owned();
        let mutated = apply(&text, &edits);
        files.insert(name.clone(), mutated.clone().into_bytes());
        guarded(PARSE_BOUND, move || plan_dir_case(files, rehash)).map_err(|e| format!("{e}\n--- {name} ---\n{mutated}"))
    });
}
