//! The initial guess: straight lines, lines bent through `[[motion.via]]` postures, or a CSV trajectory.

use super::resolve::{joint_value, posture};
use super::schema::TaskFile;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::plan::spec::InitialGuess;
use std::path::Path;

/// `discretization.initial_guess` resolved; `ends` are the start and goal postures (SI). Via postures
/// given with another guess would be silently ignored: that is an error.
pub(super) fn initial_guess(
    model: &Model,
    file: &TaskFile,
    ends: (&[f64], &[f64]),
    base: &Path,
    origin: &str,
) -> Result<InitialGuess> {
    let (m, d) = (&file.motion, &file.discretization);
    if d.initial_guess != "via" && !m.via.is_empty() {
        let message = format!(
            "{} [[motion.via]] given, but the initial guess is \"{}\": they would be ignored (set discretization.initial_guess = \"via\", or remove them)",
            m.via.len(),
            d.initial_guess
        );
        return Err(Error::task(origin, "motion.via", message));
    }
    match d.initial_guess.as_str() {
        "linear" => Ok(InitialGuess::Linear),
        "via" => vias(model, file, ends, origin),
        path => Ok(InitialGuess::Samples(read_guess_csv(model, &base.join(path))?)),
    }
}

/// The via postures; joints they do not name follow the straight line between start and goal.
fn vias(model: &Model, file: &TaskFile, (start, goal): (&[f64], &[f64]), origin: &str) -> Result<InitialGuess> {
    let m = &file.motion;
    if m.via.is_empty() {
        return Err(Error::task(origin, "discretization.initial_guess", "\"via\" needs at least one [[motion.via]]"));
    }
    let mut vias = Vec::new();
    for (k, v) in m.via.iter().enumerate() {
        // t was checked to lie inside (0, duration) with the other numbers.
        let s = v.t / m.duration;
        let line: Vec<f64> = start.iter().zip(goal).map(|(a, b)| a + (b - a) * s).collect();
        vias.push((v.t, posture(model, &v.posture, &line, &format!("motion.via[{k}].posture"), origin)?));
    }
    Ok(InitialGuess::Via(vias))
}

/// A CSV initial guess: a header with a `time` (or `time_s`) column and one column per joint named after
/// it, or `<joint>.q_deg` / `<joint>.q_m` — so a previous plan's trajectory.csv warm-starts a new solve
/// (refining N, changing gravity …). Degrees or metres; other columns are ignored.
fn read_guess_csv(model: &Model, path: &Path) -> Result<Vec<(f64, Vec<f64>)>> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let file = path.display().to_string();
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let header: Vec<&str> =
        lines.next().ok_or_else(|| Error::task(&file, "header", "empty file"))?.split(',').map(str::trim).collect();
    let time_col = header
        .iter()
        .position(|h| *h == "time" || *h == "t" || *h == "time_s")
        .ok_or_else(|| Error::task(&file, "header", "needs a \"time\" column (s)"))?;
    let mut cols = Vec::new();
    for (i, j) in model.joints[1..].iter().enumerate() {
        let c = header
            .iter()
            .position(|h| *h == j.name || h.strip_prefix(j.name.as_str()).is_some_and(|rest| rest == ".q_deg" || rest == ".q_m"))
            .ok_or_else(|| Error::task(&file, "header", format!("no column for joint \"{}\"", j.name)))?;
        cols.push((i, c));
    }
    let mut out = Vec::new();
    for (n, line) in lines.enumerate() {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let num = |c: usize| -> Result<f64> {
            cells
                .get(c)
                .and_then(|s| s.parse::<f64>().ok())
                .filter(|x| x.is_finite())
                .ok_or_else(|| Error::task(&file, format!("row {} column {}", n + 2, c + 1), "is not a finite number"))
        };
        let t = num(time_col)?;
        let mut q = vec![0.0; model.nv()];
        for &(i, c) in &cols {
            q[i] = joint_value(model, i, num(c)?, &format!("row {} column {}", n + 2, c + 1), &file)?;
        }
        out.push((t, q));
    }
    Ok(out)
}
