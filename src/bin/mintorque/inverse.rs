//! `mintorque inverse MODEL MOTION --out DIR`: inverse dynamics of a recorded motion, written whole into
//! DIR (the library's `inverse` module does the work).

use anyhow::Result;
use mintorque::inverse::{self, files, Settings};
use mintorque::plan_dir::{self, WriteOptions};
use mintorque::report::export::LengthUnit;
use std::path::Path;

/// What the command was asked.
pub struct Args<'a> {
    pub motion: &'a Path,
    pub out: &'a Path,
    pub filter_hz: f64,
    pub no_filter: bool,
    pub rate: Option<f64>,
    pub loads: Option<&'a Path>,
    /// `--units` (BVH only).
    pub units: Option<&'a str>,
    pub quiet: bool,
    pub no_plots: bool,
}

pub fn run(model: &mintorque::Model, a: &Args) -> Result<()> {
    let motion = inverse::motion::read_with_units(a.motion, model, bvh_unit(a)?)?;
    let settings = Settings { filter_hz: (!a.no_filter).then_some(a.filter_hz), rate_hz: a.rate };
    let loads = a.loads.map(|p| inverse::loads::read(p, model)).transpose()?;
    let result = inverse::inverse_dynamics(model, &motion, &settings, loads.as_ref())?;
    let summary = files::summary(model, &result, &a.motion.display().to_string(), a.loads.map(|p| p.display().to_string()))?;
    let rendered = files::render(model, &result, &summary, a.no_plots)?;
    plan_dir::write_files(a.out, &rendered, &WriteOptions::default())?;
    if !a.quiet {
        let filter = match settings.filter_hz {
            Some(f) => format!("low-pass {f} Hz (zero-lag Butterworth)"),
            None => "not filtered".to_string(),
        };
        motion.notes.iter().for_each(|n| println!("note: {n}"));
        println!("{} samples at {:.3} Hz ({} in the file), {filter}", summary.samples, summary.rate_hz, summary.input_samples);
        print!("{}", mintorque::report::ergonomics::text_table(&summary.ergonomics));
        println!("results in {}", a.out.display());
    }
    Ok(())
}

/// `--units` for a BVH motion (centimetres when not given); refused for any other motion file.
fn bvh_unit(a: &Args) -> Result<LengthUnit> {
    let is_bvh = a.motion.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("bvh"));
    match a.units {
        None => Ok(LengthUnit::Centimetre),
        Some(u) if is_bvh => LengthUnit::from_name(u).map_err(|_| anyhow::anyhow!("--units must be m or cm, got \"{u}\"")),
        Some(_) => anyhow::bail!("--units applies to a BVH motion only ({} is not .bvh)", a.motion.display()),
    }
}
