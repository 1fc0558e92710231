//! Command-line overrides of a task (`--solver`, `--control-points`, `--starts`, `--refine`). They are set
//! in the parsed file before its numbers are checked and it is resolved, so that they are checked like
//! the file's own values and the resolved task — `task.resolved.toml` — is what was planned.

use super::schema::TaskFile;
use crate::plan::SolverKind;

/// What the command line may change in a task.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Overrides {
    /// `solver.method`.
    pub solver: Option<SolverKind>,
    /// `discretization.control_points` (fixes N: no refinement unless `refine`).
    pub control_points: Option<usize>,
    /// `solver.starts`.
    pub starts: Option<crate::plan::Starts>,
    /// `discretization.refine = true`.
    pub refine: bool,
}

impl Overrides {
    /// Sets the overridden fields in `file`.
    pub(super) fn apply(&self, file: &mut TaskFile) {
        if let Some(s) = self.solver {
            file.solver.method = s;
        }
        if let Some(n) = self.control_points {
            file.discretization.control_points = Some(n);
        }
        if let Some(k) = self.starts {
            file.solver.starts = k;
        }
        if self.refine {
            file.discretization.refine = Some(true);
        }
    }
}
