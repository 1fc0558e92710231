//! Shared helpers for the integration tests: the reference data of `../shared/reference/` and random trees.
#![allow(dead_code)]

use std::path::PathBuf;

/// `../shared/reference` beside the project's checkout. Tests fail (never skip) when it is missing.
pub fn reference_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/reference");
    assert!(
        dir.join("README.md").exists(),
        "reference data not found at {} — clone the project with ../shared beside it",
        dir.display()
    );
    dir
}

/// Every `*.json` reference file, sorted.
pub fn reference_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(reference_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    assert!(
        files.len() >= 4,
        "expected at least four reference files, found {}",
        files.len()
    );
    files
}

/// `|got − want| ≤ tol·max(1, |want|)`: relative for large values, absolute near zero.
pub fn close(got: f64, want: f64, tol: f64) -> bool {
    (got - want).abs() <= tol * want.abs().max(1.0)
}
