//! A solve's trace: one row per report of the iteration hook (each accepted inner step, and the start of
//! each inner solve), with the time since the trace began — what IPOPT prints as its iteration log, kept
//! as a table (`mintorque plan --trace` writes it as `trace.csv`).

use std::fmt::Write;
use std::time::Instant;

use super::solver::Progress;

/// The rows of one or more solves, in order.
#[derive(Clone, Debug)]
pub struct Trace {
    started: Instant,
    /// Solves begun so far: a report of iteration 0 in outer iteration 0 begins one.
    solves: usize,
    rows: Vec<(usize, f64, Progress)>,
}

impl Default for Trace {
    fn default() -> Self {
        Trace::new()
    }
}

impl Trace {
    /// An empty trace whose clock starts now.
    pub fn new() -> Self {
        Trace { started: Instant::now(), solves: 0, rows: Vec::new() }
    }

    /// Records one report (use as, or inside, a solver's observer).
    pub fn record(&mut self, p: &Progress) {
        if p.outer_iteration == 0 && p.iteration == 0 {
            self.solves += 1;
        }
        self.rows.push((self.solves, self.started.elapsed().as_secs_f64(), *p));
    }

    /// Rows recorded.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The trace as CSV: `solve` counts the solves (a multi-start plan traces its first start; a polish and
    /// each between-node re-solve is a solve of its own), `seconds` since the trace began, the solver's
    /// counters and measures (scaled as in [`Progress`]), the model of the step and its damping `ν`.
    pub fn to_csv(&self) -> String {
        let mut s =
            String::from("solve,seconds,outer,iteration,evaluations,objective,violation,stationarity,penalty,model,damping\n");
        for (solve, seconds, p) in &self.rows {
            let _ = writeln!(
                s,
                "{solve},{seconds:.6},{},{},{},{:e},{:e},{:e},{:e},{},{:e}",
                p.outer_iteration,
                p.iteration,
                p.evaluations,
                p.objective,
                p.violation,
                p.stationarity,
                p.penalty,
                p.model,
                p.damping
            );
        }
        s
    }
}
