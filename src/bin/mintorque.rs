//! The `mintorque` command: a thin shell over the library. It parses arguments, calls the library and
//! prints; every error is reported with its chain and a non-zero exit.

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use mintorque::dynamics::{batch::StatesFile, bench};
use mintorque::spatial::Vec3;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "mintorque", version, about = "Minimum-joint-torque motion planning for articulated figures")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Inverse dynamics, its derivatives, H(q) and forward dynamics of a model at the states of a file
    /// (the reference data's JSON format), printed as JSON in the file's joint order.
    Dynamics {
        /// A URDF (.urdf) or figure file (.toml).
        model: PathBuf,
        /// States file: JSON with `joints[].name` and `states[]` of `q`, `v`, `a` (and `tau_rand`).
        #[arg(long, required_unless_present = "bench")]
        states: Option<PathBuf>,
        /// Gravity in the world frame, m/s² (default: the states file's, else the model's).
        #[arg(long, num_args = 3, value_names = ["GX", "GY", "GZ"], allow_negative_numbers = true)]
        gravity: Option<Vec<f64>>,
        /// Print the median ns per call of each algorithm on this model instead.
        #[arg(long)]
        bench: bool,
    },
}

fn load_model(path: &Path) -> Result<mintorque::Model> {
    Ok(mintorque::model::load_any(path)?)
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Dynamics { model, states, gravity, bench: do_bench } => {
            let model = load_model(&model)?;
            let file = match &states {
                Some(p) => Some(StatesFile::load(p, &model)?),
                None => None,
            };
            let g = match (&gravity, file.as_ref().and_then(|f| f.gravity)) {
                (Some(g), _) => {
                    anyhow::ensure!(g.iter().all(|x| x.is_finite()), "--gravity: must be three finite numbers (m/s²)");
                    Vec3::new(g[0], g[1], g[2])
                }
                (None, Some(g)) => g,
                (None, None) => model.gravity,
            };
            let out = if do_bench {
                serde_json::to_string_pretty(&bench::bench(&model, &g, 1000))?
            } else {
                let file = file.context("--states is required")?;
                let results = file.evaluate(&model, &g);
                serde_json::to_string_pretty(&serde_json::json!({
                    "model": model.name,
                    "joints": file.joint_names,
                    "gravity": [g.x, g.y, g.z],
                    "states": results,
                }))?
            };
            println!("{out}");
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
