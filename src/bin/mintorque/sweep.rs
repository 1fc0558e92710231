//! `mintorque sweep`: a thin shell over [`mintorque::sweep`] — a progress bar on a terminal (done/total,
//! converged, rate, ETA), a plain line every few seconds otherwise, and the report at the end.

use anyhow::Result;
use mintorque::sweep::{self, Progress, Sweep};
use std::io::IsTerminal;
use std::path::Path;
use std::sync::Mutex;
use std::time::Instant;

/// Runs the sweep file `path` into `out`; false when some plan did not converge or failed.
pub fn run(path: &Path, out: &Path, keep_plans: bool, quiet: bool) -> Result<bool> {
    let sweep = Sweep::load(path)?;
    let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
        let b = indicatif::ProgressBar::new(sweep.len() as u64);
        let style = "{bar:32} {pos}/{len} plans  {msg}  {per_sec}  ETA {eta}";
        b.set_style(indicatif::ProgressStyle::with_template(style).expect("valid template"));
        b
    });
    let last_line = Mutex::new(Instant::now());
    let observer = |p: &Progress| {
        let msg = format!("{} converged", p.converged);
        if let Some(b) = &bar {
            b.set_position(p.done as u64);
            b.set_message(msg);
        } else if !quiet {
            let mut last = last_line.lock().expect("the observer does not panic");
            if last.elapsed().as_secs_f64() > 2.0 || p.done == p.total {
                let rate = p.done_this_run as f64 / p.seconds.max(1e-9);
                eprintln!("{}/{} plans, {msg}, {rate:.1} plans/s", p.done, p.total);
                *last = Instant::now();
            }
        }
    };
    let options = sweep::Options { keep_plans, ..sweep::Options::default() };
    let report = sweep::run(&sweep, out, &options, &observer)?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if !quiet {
        let resumed = if report.resumed > 0 { format!(" ({} from an earlier run)", report.resumed) } else { String::new() };
        println!(
            "{} plans{resumed}: {} converged, {} not converged, {} failed, in {:.1} s",
            report.total, report.converged, report.not_converged, report.failed, report.seconds
        );
        println!("table: {} and {}", report.csv.display(), report.parquet.display());
        report.plots.iter().for_each(|p| println!("plot: {}", p.display()));
    }
    Ok(report.converged == report.total)
}
