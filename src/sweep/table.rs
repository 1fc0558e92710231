//! The sweep table as CSV (RFC 4180 quoting, one line per plan, appended as plans finish) and read back:
//! to resume (the rows already written are skipped) and to write the Parquet copy and the plots.

use super::row::{Row, Status};
use crate::error::{Error, Result};
use std::io::Write;
use std::path::Path;

/// The table's columns: index, the parameters' paths, the outcome, then per joint the peak |τ| and its
/// share of strength.
pub fn header(parameters: &[String], joints: &[String]) -> Vec<String> {
    let mut h = vec!["index".to_string()];
    h.extend(parameters.iter().cloned());
    h.extend(["status", "reason", "effort", "iterations", "solve_seconds", "start"].map(String::from));
    h.extend(joints.iter().map(|j| format!("peak_tau.{j}")));
    h.extend(joints.iter().map(|j| format!("peak_share_of_strength.{j}")));
    h.push("above_strength".into());
    h
}

/// A field quoted when it holds a comma, a quote or a line break (line breaks become spaces).
fn quote(field: &str) -> String {
    let field = field.replace(['\n', '\r'], " ");
    if field.contains([',', '"']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field
    }
}

/// The fields of one CSV line.
fn split(line: &str) -> Vec<String> {
    let (mut fields, mut field, mut quoted, mut chars) = (Vec::new(), String::new(), false, line.chars().peekable());
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    fields.push(field);
    fields
}

/// A number as the table writes it: shortest round-trip form, `NaN` for none.
fn number(x: f64) -> String {
    if x.is_nan() {
        "NaN".into()
    } else {
        format!("{x}")
    }
}

/// One row as a CSV line (with its newline).
pub fn line(row: &Row) -> String {
    let mut f = vec![row.index.to_string()];
    f.extend(row.values.iter().cloned());
    f.extend([row.status.as_str().to_string(), row.reason.clone(), number(row.effort)]);
    f.extend([row.iterations.to_string(), number(row.solve_seconds), row.start.to_string()]);
    f.extend(row.peak_torque.iter().map(|x| number(*x)));
    f.extend(row.peak_share_of_strength.iter().map(|x| number(*x)));
    f.push(row.above_strength.clone());
    let mut s = f.iter().map(|x| quote(x)).collect::<Vec<_>>().join(",");
    s.push('\n');
    s
}

/// Reads the rows of a table written by [`line`] under `header`. A last line without its newline (a
/// write cut short by a kill) is dropped, and the file truncated to the rows that are whole.
pub fn read(path: &Path, header: &[String], parameters: usize, joints: usize) -> Result<Vec<Row>> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let whole = &text[..text.rfind('\n').map_or(0, |i| i + 1)];
    if whole.len() < text.len() {
        std::fs::write(path, whole).map_err(|e| Error::io(path, e))?;
    }
    let mut lines = whole.lines();
    let origin = path.display().to_string();
    let found: Vec<String> = lines.next().map(split).unwrap_or_default();
    if found != header {
        return Err(Error::input(
            &origin,
            "header",
            "the table was written by another sweep (its columns differ): use another --out",
        ));
    }
    lines.enumerate().map(|(k, l)| parse_row(&split(l), parameters, joints).ok_or_else(|| bad_line(&origin, k + 2))).collect()
}

fn bad_line(origin: &str, line: usize) -> Error {
    Error::input(origin, format!("line {line}"), "is not a row of this sweep's table")
}

fn parse_row(f: &[String], parameters: usize, joints: usize) -> Option<Row> {
    if f.len() != 1 + parameters + 6 + 2 * joints + 1 {
        return None;
    }
    let num = |s: &String| s.parse::<f64>().ok();
    let p = 1 + parameters;
    let start = ["warm", "cold", "cold-retry"].into_iter().find(|s| *s == f[p + 5])?;
    let nums = |from: usize| f[from..from + joints].iter().map(num).collect::<Option<Vec<f64>>>();
    Some(Row {
        index: f[0].parse().ok()?,
        values: f[1..p].to_vec(),
        status: Status::parse(&f[p])?,
        reason: f[p + 1].clone(),
        effort: num(&f[p + 2])?,
        iterations: f[p + 3].parse().ok()?,
        solve_seconds: num(&f[p + 4])?,
        start,
        peak_torque: nums(p + 6)?,
        peak_share_of_strength: nums(p + 6 + joints)?,
        above_strength: f[p + 6 + 2 * joints].clone(),
    })
}

/// Appends lines to the table, each written whole and flushed (a kill loses only the plans in flight).
pub struct Writer {
    file: std::fs::File,
    path: std::path::PathBuf,
}

impl Writer {
    /// Opens `path` for appending, writing `header` first when the file is new or empty.
    pub fn open(path: &Path, header: &[String]) -> Result<Writer> {
        let fresh = std::fs::metadata(path).map_or(true, |m| m.len() == 0);
        let mut file = std::fs::OpenOptions::new().create(true).append(true).open(path).map_err(|e| Error::io(path, e))?;
        if fresh {
            let h = header.iter().map(|x| quote(x)).collect::<Vec<_>>().join(",") + "\n";
            file.write_all(h.as_bytes()).map_err(|e| Error::io(path, e))?;
        }
        Ok(Writer { file, path: path.to_path_buf() })
    }

    /// Appends one row and flushes it to the file.
    pub fn append(&mut self, row: &Row) -> Result<()> {
        self.file.write_all(line(row).as_bytes()).and_then(|_| self.file.flush()).map_err(|e| Error::io(&self.path, e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_round_trip_through_csv_with_quoting() {
        let row = Row {
            index: 7,
            values: vec!["1.7".into(), "[0.0, 0.0, -3.71]".into(), "\"mars\"".into()],
            status: Status::NotConverged,
            reason: "iteration limit reached, \"stalled\"".into(),
            effort: 123.5,
            iterations: 40,
            solve_seconds: 0.25,
            start: "cold-retry",
            peak_torque: vec![1.0, f64::NAN],
            peak_share_of_strength: vec![0.5, f64::NAN],
            above_strength: "wrist;elbow".into(),
        };
        let back = parse_row(&split(line(&row).trim_end()), 3, 2).unwrap();
        assert_eq!(back.values, row.values);
        assert_eq!((back.index, back.status, &back.reason, back.start), (7, Status::NotConverged, &row.reason, "cold-retry"));
        assert!(back.peak_torque[1].is_nan() && back.peak_share_of_strength[0] == 0.5);
    }
}
