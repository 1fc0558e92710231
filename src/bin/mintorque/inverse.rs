//! `mintorque inverse MODEL MOTION --out DIR`: inverse dynamics of a recorded motion, written whole into
//! DIR (the library's `inverse` module does the work).

use anyhow::Result;
use mintorque::inverse::{self, coupled, files, Inverse, Settings};
use mintorque::model::osim::Osim;
use mintorque::plan_dir::{self, WriteOptions};
use mintorque::report::export::LengthUnit;
use mintorque::Model;
use std::path::Path;

/// Whose forces: a model's joints, or a coupled OpenSim model's coordinates.
pub enum Subject {
    Joints(Model),
    Coupled(Box<Osim>),
}

/// `--spline`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SplineArg {
    Interpolating,
    Smoothing,
}

/// `--forces`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ForcesArg {
    Net,
    Actuator,
}

impl From<ForcesArg> for inverse::Forces {
    fn from(f: ForcesArg) -> inverse::Forces {
        match f {
            ForcesArg::Net => inverse::Forces::Net,
            ForcesArg::Actuator => inverse::Forces::Actuator,
        }
    }
}

impl From<SplineArg> for inverse::Spline {
    fn from(s: SplineArg) -> inverse::Spline {
        match s {
            SplineArg::Interpolating => inverse::Spline::Interpolating,
            SplineArg::Smoothing => inverse::Spline::Smoothing,
        }
    }
}

/// The model of `mintorque inverse`: a coupled `.osim` (or one with a spring on a Ball or Free joint's
/// rotation) keeps its coordinates (its forces are theirs), an
/// uncoupled one is its chain (read once, its ignored parts noted), any other model file is read by `load`
/// as every command reads it.
pub fn subject(path: &Path, load: impl FnOnce(&Path) -> Result<Model>) -> Result<Subject> {
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("osim")) {
        // Read once: coupled, it keeps its coordinates; uncoupled, its chain is the model.
        let osim = mintorque::model::osim::load(path)?;
        osim.ignored.iter().for_each(|note| eprintln!("note: {}: ignored {note}", path.display()));
        // A spring on a Ball or Free joint's rotation acts on OpenSim's speeds: only the coordinates carry it.
        if osim.coordinates.is_coupled() || osim.coordinates.has_angular_springs() {
            return Ok(Subject::Coupled(Box::new(osim)));
        }
        return Ok(Subject::Joints(osim.into_model(&path.display().to_string())?));
    }
    load(path).map(Subject::Joints)
}

/// What the command was asked.
pub struct Args<'a> {
    pub motion: &'a Path,
    pub out: &'a Path,
    pub settings: Settings,
    pub loads: Option<&'a Path>,
    /// `--lift FILE.toml`: the lifting equation of the recorded hand path.
    pub lift: Option<&'a Path>,
    /// `--units` (BVH only).
    pub units: Option<&'a str>,
    pub quiet: bool,
    pub no_plots: bool,
}

pub fn run(subject: &Subject, a: &Args) -> Result<()> {
    // The table the motion and the outputs are named by (the coordinates of a coupled model), the
    // chain the dynamics and the loads run on.
    let (names, chain) = match subject {
        Subject::Joints(model) => (model.clone(), None),
        Subject::Coupled(osim) => (coupled::coordinate_joints(osim), Some(&osim.model)),
    };
    let unit = bvh_unit(a)?;
    if chain.is_some() && is_bvh(a.motion) {
        anyhow::bail!("{}: a BVH motion cannot drive a coupled OpenSim model (its coordinates are not BVH channels): give a .mot, .sto or .csv of its coordinates", a.motion.display());
    }
    let motion = inverse::motion::read_with_units(a.motion, &names, unit.unwrap_or(LengthUnit::Centimetre))?;
    let loads = a.loads.map(|p| inverse::loads::read(p, chain.unwrap_or(&names))).transpose()?;
    let lift = a.lift.map(inverse::lift::read).transpose()?;
    let result: Inverse = match subject {
        Subject::Joints(model) => inverse::inverse_dynamics(model, &motion, &a.settings, loads.as_ref())?,
        Subject::Coupled(osim) => coupled::inverse_dynamics(osim, &motion, &a.settings, loads.as_ref())?,
    };
    let series = files::joint_loads(&names, chain, &result, loads.as_ref())?;
    let summary =
        files::summary(&names, chain, &result, &a.motion.display().to_string(), (loads.as_ref(), &series, lift.as_ref()))?;
    let rendered = files::render(&names, chain, &result, &series, &summary, a.no_plots)?;
    plan_dir::write_files(a.out, &rendered, &WriteOptions::default())?;
    if !a.quiet {
        let filter = match (a.settings.filter_hz, a.settings.spline) {
            (Some(f), inverse::Spline::Interpolating) => format!("low-pass {f} Hz (zero-lag Butterworth), not-a-knot cubic"),
            (Some(f), inverse::Spline::Smoothing) => format!("low-pass {f} Hz by the quintic smoothing spline"),
            (None, inverse::Spline::Interpolating) => "not filtered, not-a-knot cubic".to_string(),
            (None, inverse::Spline::Smoothing) => "not filtered (quintic smoothing spline at the Nyquist frequency)".to_string(),
        };
        motion.notes.iter().for_each(|n| println!("note: {n}"));
        if let Some(chain) = chain {
            println!("coupled model: forces of its {} coordinates from its {}-DOF chain (τ = Gᵀ τ_chain); joint_loads.csv is of the chain's joints", names.nv(), chain.nv());
        }
        println!("{} samples at {:.3} Hz ({} in the file), {filter}", summary.samples, summary.rate_hz, summary.input_samples);
        println!("forces: {}", summary.forces);
        print!("{}", mintorque::report::ergonomics::text_table(&summary.ergonomics));
        println!("results in {}", a.out.display());
    }
    Ok(())
}

fn is_bvh(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("bvh"))
}

/// `--units` for a BVH motion (`None` when not given); refused for any other motion file.
fn bvh_unit(a: &Args) -> Result<Option<LengthUnit>> {
    match a.units {
        None => Ok(None),
        Some(u) if is_bvh(a.motion) => {
            LengthUnit::from_name(u).map(Some).map_err(|_| anyhow::anyhow!("--units must be m or cm, got \"{u}\""))
        }
        Some(_) => anyhow::bail!("--units applies to a BVH motion only ({} is not .bvh)", a.motion.display()),
    }
}
