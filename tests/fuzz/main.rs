//! Fuzzing the readers (docs/reliability.md, "Fuzzed"): property-based harnesses for the URDF, figure-file,
//! task-file, states-file and plan-directory readers, each fed the bundled files of the repository mutated
//! by one to three edits ([`mutate`]: delete or duplicate a line, swap digits, a number made 1e308, -1e308,
//! nan, inf, 0 or -1, a key misspelt by one letter, truncation, a byte changed). The invariant ([`check`]):
//! a clear error naming the file, or success with finite, consistent outputs; never a panic, a hang past
//! a bound, or a non-finite number. A fraction of the task cases is planned (a tiny budget) and written
//! as a plan directory, so the solver's and the plan directory's finite checks are exercised too.
//!
//! Bounded for CI (`cargo test --release --test fuzz`); longer on demand: `MINTORQUE_FUZZ_CASES=N` runs N
//! cases per harness, `MINTORQUE_FUZZ_SECONDS=S` runs each harness for about S seconds. proptest keeps
//! any failing case in `tests/fuzz/*.proptest-regressions` and shrinks it; the regressions found are
//! plain tests in [`regressions`].

mod check;
mod mutate;
mod plan;
mod readers;
mod regressions;

use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The files of `dir` (relative to the repository) whose names end in `suffix`, sorted, as (path, text).
pub fn seeds(dir: &str, suffix: &str) -> Vec<(PathBuf, String)> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(root().join(dir))
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_str().is_some_and(|s| s.ends_with(suffix)))
        .collect();
    paths.sort();
    assert!(!paths.is_empty(), "no {suffix} files in {dir}");
    paths.into_iter().map(|p| (p.clone(), std::fs::read_to_string(&p).unwrap())).collect()
}

/// How many cases a harness runs: `default` in CI, else `MINTORQUE_FUZZ_CASES`, or as many as fit in
/// `MINTORQUE_FUZZ_SECONDS`.
pub struct Budget {
    pub cases: u32,
    pub deadline: Option<Instant>,
}

impl Budget {
    pub fn new(default: u32) -> Budget {
        let env = |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<u64>().ok());
        let deadline = env("MINTORQUE_FUZZ_SECONDS").map(|s| Instant::now() + Duration::from_secs(s));
        let cases = env("MINTORQUE_FUZZ_CASES").map(|n| n.min(u32::MAX as u64) as u32);
        Budget { cases: cases.unwrap_or(if deadline.is_some() { u32::MAX / 2 } else { default }), deadline }
    }

    pub fn expired(&self) -> bool {
        self.deadline.is_some_and(|d| Instant::now() >= d)
    }
}

/// Runs `case` on proptest values of `strategy` within `budget` (`name` for the report); a failing case,
/// shrunk, fails the test with the input.
pub fn run<S: proptest::strategy::Strategy>(
    name: &str,
    default_cases: u32,
    strategy: S,
    case: impl Fn(S::Value) -> Result<(), String>,
) where
    S::Value: std::fmt::Debug,
{
    let budget = Budget::new(default_cases);
    let config = Config { cases: budget.cases, failure_persistence: None, max_shrink_iters: 200, ..Config::default() };
    let mut runner = TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::default()));
    let (started, done) = (Instant::now(), std::cell::Cell::new(0u32));
    let outcome = runner.run(&strategy, |value| {
        if budget.expired() {
            return Ok(());
        }
        done.set(done.get() + 1);
        case(value).map_err(TestCaseError::fail)
    });
    eprintln!("fuzz {name}: {} cases in {:.1} s", done.get(), started.elapsed().as_secs_f64());
    if let Err(e) = outcome {
        panic!("fuzz {name}: {e}");
    }
}

/// `path` as the readers quote it.
pub fn shown(path: &Path) -> String {
    path.display().to_string()
}
