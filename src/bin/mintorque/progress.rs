//! The progress of one plan on the terminal: the solver's iterations, then the outputs being written.

use std::io::IsTerminal;

/// A progress observer: a spinner on a terminal, a line a second otherwise, nothing with `quiet`.
pub fn spinner(quiet: bool) -> (Option<indicatif::ProgressBar>, impl FnMut(&mintorque::solve::Progress)) {
    let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
        let b = indicatif::ProgressBar::new_spinner();
        b.set_style(indicatif::ProgressStyle::with_template("{spinner} {elapsed} {msg}").expect("valid template"));
        b
    });
    let shown = bar.clone();
    let mut last_print = std::time::Instant::now();
    let observer = move |p: &mintorque::solve::Progress| {
        let msg = format!(
            "iteration {:>4} (outer {:>2})  objective {:.6e}  violation {:.2e}  stationarity {:.2e}",
            p.iteration, p.outer_iteration, p.objective, p.violation, p.stationarity
        );
        if let Some(b) = &shown {
            b.set_message(msg);
            b.tick();
        } else if !quiet && last_print.elapsed().as_secs_f64() > 1.0 {
            eprintln!("{msg}");
            last_print = std::time::Instant::now();
        }
    };
    (bar, observer)
}

/// A reporter of the outputs' stages on stderr, "writing outputs k/n: stage …": one line overwritten in
/// place on a terminal (cleared when done), a line per stage otherwise, nothing with `quiet`.
pub fn writing(quiet: bool) -> (Option<indicatif::ProgressBar>, impl FnMut(usize, usize, &str)) {
    let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
        let b = indicatif::ProgressBar::new(1);
        b.set_style(indicatif::ProgressStyle::with_template("writing outputs {pos}/{len}: {msg} …").expect("valid template"));
        b
    });
    let shown = bar.clone();
    let report = move |k: usize, n: usize, stage: &str| match &shown {
        Some(b) => {
            b.set_length(n as u64);
            b.set_position(k as u64);
            b.set_message(stage.to_string());
        }
        None if !quiet => eprintln!("writing outputs {k}/{n}: {stage} …"),
        None => {}
    };
    (bar, report)
}
