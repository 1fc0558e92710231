//! The model and states readers: URDF, figure file, states file — each fed the repository's own files,
//! mutated.

use crate::check::{guarded, model_is_sound, names_file, PARSE_BOUND};
use crate::mutate::{apply, mutations};
use crate::{root, run, seeds, shown};
use mintorque::dynamics::batch::StatesFile;
use mintorque::model::{figure, urdf, Model};
use proptest::prelude::*;
use proptest::sample::select;
use std::path::PathBuf;

/// Every URDF of the repository, with the options it needs (the reference Panda has a `<mimic>`).
fn urdf_seeds() -> Vec<(PathBuf, String)> {
    [seeds("models", ".urdf"), seeds("tests/data/reference/models", ".urdf")].concat()
}

/// A model reader's invariant on `text` read as `origin`.
fn model_case(text: String, origin: String, read: fn(&str, &str) -> mintorque::Result<Model>) -> Result<(), String> {
    let input = text.clone();
    guarded(PARSE_BOUND, move || match read(&text, &origin) {
        Err(e) => names_file(&e.to_string(), &origin),
        Ok(model) => model_is_sound(&model, &origin),
    })
    .map_err(|e| format!("{e}\n--- the input ---\n{input}"))
}

fn read_urdf(text: &str, origin: &str) -> mintorque::Result<Model> {
    urdf::parse(text, origin)
}

fn read_urdf_mimic(text: &str, origin: &str) -> mintorque::Result<Model> {
    urdf::parse_with(text, origin, urdf::Options { mimic: urdf::Mimic::Independent })
}

#[test]
fn urdf_reader() {
    let files = urdf_seeds();
    let strategy = (select((0..files.len()).collect::<Vec<_>>()), mutations(), any::<bool>());
    run("urdf", 5000, strategy, |(k, edits, mimic)| {
        let (path, text) = &files[k];
        let read = if mimic { read_urdf_mimic } else { read_urdf };
        model_case(apply(text, &edits), shown(path), read)
    });
}

#[test]
fn figure_reader() {
    let files = seeds("models", ".figure.toml");
    let strategy = (select((0..files.len()).collect::<Vec<_>>()), mutations());
    run("figure file", 5000, strategy, |(k, edits)| {
        let (path, text) = &files[k];
        model_case(apply(text, &edits), shown(path), figure::parse)
    });
}

#[test]
fn states_reader() {
    let files = seeds("tests/data/reference", ".json");
    let models: Vec<Model> = files
        .iter()
        .map(|(p, _)| {
            let name = p.file_stem().unwrap().to_str().unwrap();
            let path = root().join(format!("tests/data/reference/models/{name}.urdf"));
            urdf::load_with(&path, urdf::Options { mimic: urdf::Mimic::Independent }).unwrap_or_else(|e| panic!("{e}"))
        })
        .collect();
    let strategy = (select((0..files.len()).collect::<Vec<_>>()), mutations());
    run("states file", 3000, strategy, |(k, edits)| {
        let ((path, text), model) = (&files[k], models[k].clone());
        let (text, origin) = (apply(text, &edits), shown(path));
        guarded(PARSE_BOUND, move || match StatesFile::parse(&text, &origin, &model) {
            Err(e) => names_file(&e.to_string(), &origin),
            Ok(file) => match file.evaluate(&model, &file.gravity.unwrap_or(model.gravity)) {
                Err(e) => names_file(&e.to_string(), &origin),
                Ok(r) if r.len() == file.states.len() => Ok(()),
                Ok(r) => Err(format!("{} results for {} states", r.len(), file.states.len())),
            },
        })
    });
}
