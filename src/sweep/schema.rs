//! The sweep file (`SWEEP.toml`, docs/sweeps.md): a base task file and the task fields to vary, each by its
//! dotted path, as a list, a range with a step, or seeded random samples; combined as a grid (every
//! combination) or zipped (the k-th value of each).

use crate::error::{Error, Result};
use serde::Deserialize;
use std::path::PathBuf;

/// The sweep file as written.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepFile {
    /// The task file every plan starts from, relative to the sweep file.
    pub base: PathBuf,
    /// "grid" (default: every combination) or "zip" (the k-th value of every parameter; equal counts).
    #[serde(default = "grid")]
    pub mode: String,
    /// The fields varied.
    #[serde(default)]
    pub parameter: Vec<Parameter>,
}

fn grid() -> String {
    "grid".into()
}

/// One task field varied.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Parameter {
    /// The field's dotted path in the task file: `model.stature`, `environment.gravity`,
    /// `environment.payload[0].mass`, `motion.goal.shoulder` …
    pub path: String,
    /// The values, as the task file writes them (numbers in the field's unit, strings, arrays).
    pub values: Option<Vec<toml::Value>>,
    /// `from` to `to` (inclusive) by `step`; integers when all three are integers.
    pub range: Option<Range>,
    /// `count` samples uniform in `[low, high)`, from a SplitMix64 stream seeded by `seed`.
    pub random: Option<Random>,
}

/// An arithmetic range.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Range {
    /// First value.
    pub from: toml::Value,
    /// Last value (included when the steps land on it).
    pub to: toml::Value,
    /// Step (> 0).
    pub step: toml::Value,
}

/// Seeded uniform samples.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Random {
    /// Lower bound.
    pub low: f64,
    /// Upper bound (> low).
    pub high: f64,
    /// How many samples.
    pub count: usize,
    /// The stream's seed (default 1).
    #[serde(default = "one")]
    pub seed: u64,
}

fn one() -> u64 {
    1
}

/// At most this many plans in one sweep (a typo such as a step of 1e-6 is refused, not run for a week).
pub const MAX_PLANS: usize = 10_000_000;

impl Parameter {
    /// The parameter's values; `field` (`parameter[i]`) and `origin` name it in errors.
    pub fn expand(&self, origin: &str, field: &str) -> Result<Vec<toml::Value>> {
        let err = |m: String| Err(Error::task(origin, field, m));
        let given = [self.values.is_some(), self.range.is_some(), self.random.is_some()].iter().filter(|g| **g).count();
        if given != 1 {
            return err(format!("\"{}\": give exactly one of values, range or random", self.path));
        }
        let values = if let Some(v) = &self.values {
            v.clone()
        } else if let Some(r) = &self.range {
            r.expand().map_err(|m| Error::task(origin, format!("{field}.range"), m))?
        } else {
            let r = self.random.as_ref().expect("one of the three");
            r.expand().map_err(|m| Error::task(origin, format!("{field}.random"), m))?
        };
        if values.is_empty() {
            return err(format!("\"{}\" has no values: a sweep of zero plans", self.path));
        }
        Ok(values)
    }
}

impl Range {
    fn expand(&self) -> std::result::Result<Vec<toml::Value>, String> {
        use toml::Value::{Float, Integer};
        let number = |v: &toml::Value, name: &str| match v {
            Integer(i) => Ok(*i as f64),
            Float(f) if f.is_finite() => Ok(*f),
            _ => Err(format!("{name} must be a finite number, got {v}")),
        };
        let (from, to, step) = (number(&self.from, "from")?, number(&self.to, "to")?, number(&self.step, "step")?);
        if step <= 0.0 {
            return Err(format!("step must be > 0, got {step}"));
        }
        if to < from {
            return Err(format!("to ({to}) is below from ({from})"));
        }
        // n = ⌊(to − from)/step⌋ + 1, with a relative slack so that 0.1-steps land on `to`.
        let n = ((to - from) / step * (1.0 + 1e-12) + 1e-9).floor() + 1.0;
        if n > MAX_PLANS as f64 {
            return Err(format!("{n} values: more than the {MAX_PLANS} a sweep may hold"));
        }
        let integers = [&self.from, &self.to, &self.step].iter().all(|v| matches!(v, Integer(_)));
        Ok((0..n as usize)
            .map(
                |k| {
                    if integers {
                        Integer((from + k as f64 * step) as i64)
                    } else {
                        Float(twelve_digits(from + k as f64 * step))
                    }
                },
            )
            .collect())
    }
}

/// `x` to 12 significant digits: `0.45 + 3·0.05` is written 0.6, not 0.6000000000000001.
fn twelve_digits(x: f64) -> f64 {
    format!("{x:.11e}").parse().unwrap_or(x)
}

impl Random {
    fn expand(&self) -> std::result::Result<Vec<toml::Value>, String> {
        if !(self.low.is_finite() && self.high.is_finite() && self.low < self.high) {
            return Err(format!("needs finite low < high, got [{}, {})", self.low, self.high));
        }
        if self.count > MAX_PLANS {
            return Err(format!("count {} is more than the {MAX_PLANS} a sweep may hold", self.count));
        }
        let mut state = self.seed;
        Ok((0..self.count)
            .map(|_| {
                // u ∈ [0, 1) from the stream's [−1, 1)
                let u = 0.5 * (crate::plan::next_signed(&mut state) + 1.0);
                toml::Value::Float(self.low + (self.high - self.low) * u)
            })
            .collect())
    }
}

/// Every parameter's values, in the file's order.
pub fn values(file: &SweepFile, origin: &str) -> Result<Vec<Vec<toml::Value>>> {
    if file.parameter.is_empty() {
        return Err(Error::task(origin, "parameter", "no parameters: a sweep of zero plans"));
    }
    file.parameter.iter().enumerate().map(|(i, p)| p.expand(origin, &format!("parameter[{i}]"))).collect()
}

/// The plans of a sweep of parameter values `lists` (from [`values`]) in `mode`: for each, one value per
/// parameter.
pub fn combinations(mode: &str, lists: &[Vec<toml::Value>], origin: &str) -> Result<Vec<Vec<toml::Value>>> {
    match mode {
        "grid" => {
            let total = lists.iter().try_fold(1usize, |acc, l| acc.checked_mul(l.len()).filter(|n| *n <= MAX_PLANS));
            if total.is_none() {
                return Err(Error::task(origin, "parameter", format!("the grid has more than {MAX_PLANS} plans")));
            }
            // Row-major: the last parameter varies fastest.
            Ok(lists.iter().fold(vec![vec![]], |rows: Vec<Vec<toml::Value>>, list| {
                rows.iter().flat_map(|row| list.iter().map(move |v| [row.clone(), vec![v.clone()]].concat())).collect()
            }))
        }
        "zip" => {
            let n = lists[0].len();
            if let Some((i, l)) = lists.iter().enumerate().find(|(_, l)| l.len() != n) {
                return Err(Error::task(
                    origin,
                    format!("parameter[{i}]"),
                    format!("has {} values, parameter[0] has {n}: zipped parameters need equal counts", l.len()),
                ));
            }
            Ok((0..n).map(|k| lists.iter().map(|l| l[k].clone()).collect()).collect())
        }
        other => Err(Error::task(origin, "mode", format!("\"{other}\" is not a mode: use \"grid\" or \"zip\""))),
    }
}
