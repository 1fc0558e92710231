//! The numeric tables of recorded motion: OpenSim's Storage (`.mot`, `.sto`: a header closed by
//! `endheader`, then labels and rows separated by tabs or spaces) and CSV (a label line, then rows
//! separated by commas). Every value is parsed and checked finite here, naming the file, line and column.

use crate::error::{Error, Result};

/// A table as read: its labels and rows of numbers, each row with its line number (1-based).
#[derive(Clone, Debug)]
pub struct Table {
    /// The file, as named in errors.
    pub origin: String,
    /// The column labels.
    pub labels: Vec<String>,
    /// The rows, each with as many values as there are labels.
    pub rows: Vec<Vec<f64>>,
    /// The line of each row.
    pub lines: Vec<usize>,
    /// `inDegrees` of a Storage header (`None` for CSV).
    pub in_degrees: Option<bool>,
}

/// The lines of `text`, numbered from 1, blank lines left out.
fn numbered(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines().enumerate().map(|(i, l)| (i + 1, l.trim())).filter(|(_, l)| !l.is_empty())
}

/// An OpenSim Storage file: the header up to `endheader` (its `inDegrees=yes|no` required: without it
/// the angles' unit is a guess), then labels and rows split at tabs or spaces.
pub fn parse_storage(text: &str, origin: &str) -> Result<Table> {
    let table = parse_storage_of_any_unit(text, origin)?;
    if table.in_degrees.is_none() {
        let message = "has no `inDegrees=yes` or `inDegrees=no`: say whether the angles are in degrees or radians";
        return Err(Error::input(origin, "header", message));
    }
    Ok(table)
}

/// A Storage file whose header need not say `inDegrees` (forces, points and torques: N, m, N·m).
pub fn parse_storage_of_any_unit(text: &str, origin: &str) -> Result<Table> {
    let mut lines = numbered(text);
    let mut in_degrees = None;
    let mut closed = false;
    for (n, line) in lines.by_ref() {
        if line.eq_ignore_ascii_case("endheader") {
            closed = true;
            break;
        }
        if let Some((key, value)) = line.split_once('=') {
            if key.trim().eq_ignore_ascii_case("inDegrees") {
                in_degrees = Some(yes_no(value.trim(), origin, n)?);
            }
        }
    }
    if !closed {
        return Err(Error::input(origin, "header", "has no `endheader` line: not an OpenSim Storage (.mot/.sto) file"));
    }
    let mut table = rows(lines, origin, |l| l.split_whitespace().collect())?;
    table.in_degrees = in_degrees;
    Ok(table)
}

/// A CSV file: a label line, then rows of numbers split at commas.
pub fn parse_csv(text: &str, origin: &str) -> Result<Table> {
    rows(numbered(text), origin, |l| l.split(',').map(str::trim).collect())
}

fn yes_no(value: &str, origin: &str, line: usize) -> Result<bool> {
    match value.to_ascii_lowercase().as_str() {
        "yes" | "true" => Ok(true),
        "no" | "false" => Ok(false),
        _ => Err(Error::input(origin, format!("line {line}: inDegrees"), format!("must be yes or no, got \"{value}\""))),
    }
}

/// The label line and the rows after it, each split by `split`.
fn rows<'a>(
    mut lines: impl Iterator<Item = (usize, &'a str)>,
    origin: &str,
    split: impl Fn(&'a str) -> Vec<&'a str>,
) -> Result<Table> {
    let (label_line, labels) = match lines.next() {
        Some((n, l)) => (n, split(l).into_iter().map(String::from).collect::<Vec<_>>()),
        None => return Err(Error::input(origin, "labels", "the file ends before its column labels")),
    };
    if let Some(k) = labels.iter().position(|l| l.is_empty()) {
        return Err(Error::input(origin, format!("line {label_line}, column {}", k + 1), "has an empty label"));
    }
    let mut table = Table { origin: origin.to_string(), labels, rows: Vec::new(), lines: Vec::new(), in_degrees: None };
    for (n, line) in lines {
        let tokens = split(line);
        if tokens.len() != table.labels.len() {
            let message = format!("has {} values, the label line names {} columns", tokens.len(), table.labels.len());
            return Err(Error::input(origin, format!("line {n}"), message));
        }
        let row = tokens.iter().zip(&table.labels).map(|(tok, label)| number(tok, origin, n, label)).collect::<Result<_>>()?;
        table.rows.push(row);
        table.lines.push(n);
    }
    Ok(table)
}

/// A finite number, or an error naming the line and the column.
fn number(token: &str, origin: &str, line: usize, label: &str) -> Result<f64> {
    let at = || format!("line {line}, column \"{label}\"");
    match token.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(Error::input(origin, at(), format!("\"{token}\" is not a finite number"))),
        Err(_) => Err(Error::input(origin, at(), format!("\"{token}\" is not a number"))),
    }
}
