//! The `mintorque` command: a thin shell over the library. It parses arguments, calls the library and
//! prints; every error is reported with its chain and a non-zero exit.

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use mintorque::dynamics::{batch::StatesFile, bench};
use mintorque::plan::{self, task::Task, SolverKind};
use mintorque::report::{self, Summary};
use mintorque::spatial::Vec3;
use std::io::IsTerminal;
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
    /// Plan the minimum-torque motion of a task file and write the results into a directory.
    Plan {
        /// The task (TOML; see docs/task-file.md).
        task: PathBuf,
        /// Output directory (created if needed): trajectory.csv, summary.json, task.resolved.toml.
        #[arg(long, short)]
        out: PathBuf,
        /// Override the task's solver.
        #[arg(long, value_enum)]
        solver: Option<SolverArg>,
        /// Override the number of B-spline control points per joint.
        #[arg(long)]
        control_points: Option<usize>,
        /// No progress output.
        #[arg(long, short)]
        quiet: bool,
        /// Skip the plots.
        #[arg(long)]
        no_plots: bool,
    },
    /// Export a planned motion (a directory written by `plan`) for other tools.
    Export {
        /// The plan directory.
        dir: PathBuf,
        /// bvh (Blender, MotionBuilder), gltf (binary .glb), mot (OpenSim), csv.
        #[arg(long)]
        format: String,
        /// Output file (default: inside DIR, named after the model).
        #[arg(long, short)]
        out: Option<PathBuf>,
    },
    /// Open a plan directory's animation (motion.html) in the browser, regenerating its view files.
    View {
        /// The plan directory.
        dir: PathBuf,
        /// The filmstrip's camera: side (looking along +y), front or top.
        #[arg(long, default_value = "side")]
        filmstrip: String,
    },
    /// Write a figure — a built-in human or a model file — as URDF (for any URDF viewer) or as a figure
    /// file (TOML) to edit.
    Figure {
        /// A URDF or figure file to convert.
        model: Option<PathBuf>,
        /// A built-in human structure instead: sagittal, free_arms, hanging, push_up.
        #[arg(long, conflicts_with = "model")]
        human: Option<String>,
        /// Stature of the built-in human (m, 0.5–2.5).
        #[arg(long, default_value_t = 1.83)]
        stature: f64,
        /// Body mass of the built-in human (kg, 20–250).
        #[arg(long, default_value_t = 81.0)]
        mass: f64,
        /// Output file: .urdf for URDF, .toml for a figure file.
        #[arg(long, short)]
        out: PathBuf,
    },
    /// List the bundled examples (the paper's experiments), one line each.
    Examples,
    /// Integrate the forward dynamics under a plan's torques from its start state and report the drift from
    /// the planned motion.
    Simulate {
        /// A plan directory (written by `plan`), or a task file to plan first.
        plan: PathBuf,
        /// RK4 steps over the motion.
        #[arg(long, default_value_t = 4000)]
        steps: usize,
    },
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

#[derive(Clone, Copy, clap::ValueEnum)]
enum SolverArg {
    Structured,
    Newton,
    AuglagBfgs,
}

/// Exit code of a plan that did not converge (its results are still written, marked as such).
const NOT_CONVERGED: u8 = 3;

/// Writes one file whole or not at all.
fn write_one(path: &Path, bytes: Vec<u8>) -> Result<()> {
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let file = path.file_name().and_then(|f| f.to_str()).context("--out must name a file")?;
    Ok(report::write_files(parent, &[(file, bytes)])?)
}

fn load_model(path: &Path) -> Result<mintorque::Model> {
    Ok(mintorque::model::load_any(path)?)
}

fn run_plan(
    task_path: &Path,
    out: &Path,
    solver: Option<SolverArg>,
    control_points: Option<usize>,
    quiet: bool,
    no_plots: bool,
) -> Result<bool> {
    let mut task = Task::load(task_path)?;
    if let Some(s) = solver {
        task.solver = match s {
            SolverArg::Structured => SolverKind::Structured,
            SolverArg::Newton => SolverKind::Newton,
            SolverArg::AuglagBfgs => SolverKind::AuglagBfgs,
        };
    }
    if let Some(n) = control_points {
        task.spec.n_ctrl = n;
    }
    let spec = &task.spec;
    let terminal = std::io::stderr().is_terminal();
    let bar = (!quiet && terminal).then(|| {
        let b = indicatif::ProgressBar::new_spinner();
        b.set_style(indicatif::ProgressStyle::with_template("{spinner} {elapsed} {msg}").expect("valid template"));
        b
    });
    let mut last_print = std::time::Instant::now();
    let mut observer = |p: &mintorque::solve::Progress| {
        let msg = format!(
            "iteration {:>4} (outer {:>2})  objective {:.6e}  violation {:.2e}  stationarity {:.2e}",
            p.iteration, p.outer_iteration, p.objective, p.violation, p.stationarity
        );
        if let Some(b) = &bar {
            b.set_message(msg);
            b.tick();
        } else if !quiet && last_print.elapsed().as_secs_f64() > 1.0 {
            eprintln!("{msg}");
            last_print = std::time::Instant::now();
        }
    };
    let planned = plan::plan(spec, task.solver, &task.settings, &mut observer)?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let times = report::sample_times(spec.duration, task.file.output.sample_rate);
    let samples = plan::sample(spec, &planned, &times)?;
    let summary = Summary::new(spec, &planned, &samples);
    let record = report::record::PlanRecord::new(spec, &planned, &samples);
    let ergonomics = report::ergonomics::ergonomics(&spec.model, &record, &task.file.output.strength)?;
    let mut summary_json = serde_json::to_value(&summary)?;
    summary_json["ergonomics"] = serde_json::to_value(&ergonomics)?;
    let resolved = toml::to_string_pretty(&task.resolved_file()).context("serialising the resolved task")?;
    let mut files: Vec<(String, Vec<u8>)> = vec![
        ("trajectory.csv".into(), report::export::csv::csv(&spec.model, &record).into_bytes()),
        ("summary.json".into(), serde_json::to_string_pretty(&summary_json)?.into_bytes()),
        ("task.resolved.toml".into(), resolved.into_bytes()),
    ];
    files.extend(report::record::plan_files(spec, &planned, &samples)?.into_iter().map(|(n, b)| (n.to_string(), b)));
    if task.file.output.plots && !no_plots {
        let guess: Vec<report::record::SampleRecord> =
            plan::sample_initial_guess(spec, &times)?.iter().map(report::record::SampleRecord::from).collect();
        files.extend(report::plots::plots(&spec.model, &record, Some(&guess))?);
    }
    // The views: the animation page and the filmstrip (side view), like the paper's figures.
    {
        use report::{filmstrip, viewer};
        let summary_text = serde_json::to_string(&summary_json)?;
        files.push((viewer::VIEW_FILES[0].into(), viewer::motion_html(&spec.model, &record, Some(&summary_text)).into_bytes()));
        let frames = viewer::FILMSTRIP_FRAMES;
        files.push((
            viewer::VIEW_FILES[1].into(),
            filmstrip::filmstrip_svg(&spec.model, &record, frames, filmstrip::View::Side).into_bytes(),
        ));
        files
            .push((viewer::VIEW_FILES[2].into(), filmstrip::filmstrip_png(&spec.model, &record, frames, filmstrip::View::Side)?));
    }
    let named: Vec<(&str, Vec<u8>)> = files.iter().map(|(n, b)| (n.as_str(), b.clone())).collect();
    report::write_files(out, &named)?;
    if !quiet {
        print!("{}", report::summary::text_table(&summary));
        print!("{}", report::ergonomics::text_table(&ergonomics));
        println!("results in {}", out.display());
    }
    if !summary.converged {
        eprintln!("error: the optimization did not converge: {}", summary.reason);
        if let Some(v) = &summary.worst_violation_at_nodes {
            eprintln!("       worst constraint: {} (scaled violation {:.2e})", v.constraint, v.value);
        }
    }
    Ok(summary.converged)
}

fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Plan { task, out, solver, control_points, quiet, no_plots } => {
            let converged = run_plan(&task, &out, solver, control_points, quiet, no_plots)?;
            Ok(if converged { ExitCode::SUCCESS } else { ExitCode::from(NOT_CONVERGED) })
        }
        Command::Export { dir, format, out } => {
            let format = report::export::Format::from_name(&format)?;
            let (model, record) = report::record::load_plan_dir(&dir)?;
            let (name, bytes) = report::export::export(&model, &record, format)?;
            let path = out.unwrap_or_else(|| dir.join(&name));
            write_one(&path, bytes)?;
            println!("wrote {}", path.display());
            Ok(ExitCode::SUCCESS)
        }
        Command::View { dir, filmstrip } => {
            let view: report::filmstrip::View = filmstrip.parse().map_err(anyhow::Error::msg)?;
            report::viewer::write_view_files_with(&dir, view)?;
            report::viewer::open_in_browser(&dir.join(report::viewer::VIEW_FILES[0]));
            Ok(ExitCode::SUCCESS)
        }
        Command::Figure { model, human, stature, mass, out } => {
            use mintorque::model::{figure, human as jack, urdf_export};
            let model = match (model, human) {
                (Some(path), None) => load_model(&path)?,
                (None, Some(name)) => {
                    jack::Structure::from_name(&name)?.build(jack::HumanParams { stature_m: stature, mass_kg: mass })?
                }
                _ => anyhow::bail!("give a model file or --human NAME"),
            };
            let text = match out.extension().and_then(|e| e.to_str()) {
                Some("urdf") | Some("xml") => urdf_export::to_urdf(&model),
                Some("toml") => figure::to_toml(&model),
                _ => anyhow::bail!("{}: the output must end in .urdf or .toml", out.display()),
            };
            write_one(&out, text.into_bytes())?;
            println!("wrote {} ({} joints)", out.display(), model.nv());
            Ok(ExitCode::SUCCESS)
        }
        Command::Examples => {
            for e in mintorque::plan::examples::ALL {
                println!("{:<20} {}", e.name, e.summary());
            }
            println!("\nrun one with: mintorque plan examples/NAME.toml --out out/NAME");
            Ok(ExitCode::SUCCESS)
        }
        Command::Simulate { plan: path, steps } => {
            let (task, x, status) = if path.is_dir() {
                let (task, x) = report::record::load_plan_task(&path)?;
                (task, x, format!("plan of {}", path.display()))
            } else {
                let task = Task::load(&path)?;
                let planned = plan::plan(&task.spec, task.solver, &task.settings, &mut |_| {})?;
                let status = if planned.converged() { "plan converged" } else { "plan NOT converged" };
                (task, planned.x, status.to_string())
            };
            let sim = plan::simulate::simulate_x(&task.spec, &x, steps)?;
            println!("{status}; forward simulation with {steps} RK4 steps of {:.2e} s", sim.step);
            for (j, d) in task.spec.model.joints[1..].iter().zip(&sim.max_drift) {
                let (v, unit) =
                    if j.kind == mintorque::model::JointKind::Prismatic { (*d * 1e3, "mm") } else { (d.to_degrees(), "°") };
                println!("  {:<16} max drift {v:.4} {unit}", j.name);
            }
            Ok(ExitCode::SUCCESS)
        }
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
            Ok(ExitCode::SUCCESS)
        }
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
