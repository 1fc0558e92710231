//! The `mintorque` command: a thin shell over the library. It parses arguments, calls the library and
//! prints; every error is reported with its chain. Exit codes, the same for every command: 0 success (a
//! converged plan), 1 bad input or settings (the message names the file, field or option), 3 a plan that
//! did not converge or a result that is not finite.

#[path = "mintorque/args.rs"]
mod args;
#[path = "mintorque/inverse.rs"]
mod inverse;
#[path = "mintorque/progress.rs"]
mod progress;
#[path = "mintorque/sweep.rs"]
mod sweep;

use anyhow::{Context, Result};
use args::{Cli, Command, MimicArg, ModelArgs, SolverArg};
use clap::Parser;
use mintorque::dynamics::{batch::StatesFile, bench};
use mintorque::plan::task::Overrides;
use mintorque::plan::{self, task::Task, SolverKind};
use mintorque::plan_dir::{self, PlanContents, WriteOptions};
use mintorque::report;
use mintorque::solve::Trace;
use mintorque::spatial::Vec3;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Bad input or settings (named in the message), for every command.
const BAD_INPUT: u8 = 1;
/// A plan that did not converge (its results are still written, marked as such), or a non-finite result
/// (nothing written).
const NOT_CONVERGED: u8 = 3;

fn exit(ok: bool) -> ExitCode {
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(NOT_CONVERGED)
    }
}

/// Reads a model file as `read` says; a refused `<mimic>` says which option reads it.
fn load_model(path: &Path, read: ModelArgs) -> Result<mintorque::Model> {
    use mintorque::model::urdf::{Mimic, Options};
    let mimic = match read.mimic {
        MimicArg::Refuse => Mimic::Refuse,
        MimicArg::Independent => Mimic::Independent,
    };
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("osim")) {
        // An OpenSim file: say what of it is not modelled (muscles, constraints …).
        let osim = mintorque::model::osim::load(path)?;
        osim.ignored.iter().for_each(|note| eprintln!("note: {}: ignored {note}", path.display()));
        return Ok(osim.into_model(&path.display().to_string())?);
    }
    mintorque::model::load_any_with(path, Options { mimic }).map_err(|e| match &e {
        mintorque::Error::Model { element, .. } if element.ends_with("<mimic>") => {
            anyhow::Error::new(e).context("pass `--mimic independent` to read a <mimic> joint as an independent joint")
        }
        _ => e.into(),
    })
}

/// Plans a task (overrides applied, settings checked), reporting why it did not converge if it did not;
/// records the solver's iterations into `trace` when given.
fn solve(task: &mut Task, quiet: bool, mut trace: Option<&mut Trace>) -> Result<plan::Plan> {
    if let Some(r) = task.refinement.filter(|_| !quiet) {
        eprintln!(
            "planning at N = {} control points, then refining N until the effort changes by < {} % (at most N = {}); \
             fix discretization.control_points (or --control-points) to plan one N",
            task.spec.n_ctrl,
            100.0 * r.tolerance,
            r.max_control_points
        );
    }
    let (bar, mut show) = progress::spinner(quiet);
    let mut observer = |p: &mintorque::solve::Progress| {
        show(p);
        if let Some(t) = trace.as_deref_mut() {
            t.record(p);
        }
    };
    let planned = task.plan(&mut observer)?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if !planned.converged() {
        eprintln!("error: the optimization did not converge: {}", planned.outcome.reason);
    }
    Ok(planned)
}

/// What `plan` prints and writes besides the plan.
struct PlanOutputs {
    quiet: bool,
    no_plots: bool,
    /// Write the solver's iteration log as `trace.csv`.
    trace: bool,
}

/// Where a plan starts: the task's guess, a previous plan (`--warm-start`), or a plan to refine (`--refine-from`).
enum Start {
    Guess,
    Warm(PathBuf),
    Refine(PathBuf),
}

/// The task to plan, started as `from` says (`task_path` is required unless refining a plan).
fn load_task(task_path: Option<&Path>, overrides: &Overrides, from: &Start) -> Result<Task> {
    let required = || task_path.context("a task file is required");
    Ok(match from {
        Start::Guess => Task::load_with(required()?, overrides)?,
        Start::Warm(dir) => {
            let mut task = Task::load_with(required()?, overrides)?;
            plan_dir::warm_start(&mut task, dir)?;
            task
        }
        Start::Refine(dir) => plan_dir::refine_from(task_path, overrides, dir)?,
    })
}

fn run_plan(task_path: Option<&Path>, out: &Path, overrides: &Overrides, from: &Start, outputs: PlanOutputs) -> Result<bool> {
    let PlanOutputs { quiet, no_plots, trace } = outputs;
    let mut task = load_task(task_path, overrides, from)?;
    let mut trace = trace.then(Trace::new);
    let planned = solve(&mut task, quiet, trace.as_mut())?;
    let contents = PlanContents { trace, ..PlanContents::from_task(&task, &planned, no_plots)? };
    let (bar, mut report) = progress::writing(quiet);
    let written = plan_dir::write_reporting(out, &contents, &WriteOptions::default(), &mut report);
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    written?;
    let (summary, ergonomics) = (contents.summary.as_ref().context("a planned task has a summary")?, &contents.ergonomics);
    if !quiet {
        print!("{}", report::summary::text_table(summary));
        // One torque table: the ergonomic one (peaks, limits, time beyond them, work, power) where there is
        // one, else the summary's peaks and limits.
        match ergonomics {
            Some(e) => print!("{}", report::ergonomics::text_table(e)),
            None => print!("{}", report::summary::joint_table(summary)),
        }
        println!("results in {}", out.display());
    }
    eprint!("{}", report::singularity::warning_lines(&summary.near_singularities));
    if let (Some(settled), Some(verdict)) = (summary.discretization, &summary.discretization_verdict) {
        if !settled.is_settled() {
            eprintln!("warning: the discretisation is {verdict}: more control points may lower the effort further");
        }
    }
    // The worst constraint at the nodes, in units, when it is violated there (the between-node misses are
    // in the reason).
    let between = matches!(planned.outcome.reason, mintorque::solve::StopReason::BetweenNodes(_));
    if let Some(v) =
        summary.worst_violation_at_nodes.as_ref().filter(|v| !summary.converged && !between && !v.constraint.ends_with("holds"))
    {
        eprintln!("       worst constraint at the nodes: {}", v.constraint);
    }
    Ok(summary.converged)
}

fn run_export(dir: &Path, format: &str, out: Option<PathBuf>, options: &report::export::Options) -> Result<()> {
    let format = report::export::Format::from_name(format)?;
    options.check(format)?;
    let loaded = plan_dir::load(dir)?;
    let (name, bytes) = report::export::export_with(&loaded.model, &loaded.record, format, options)?;
    let path = match out {
        Some(path) => {
            plan_dir::write_file(&path, &bytes)?;
            path
        }
        None => {
            plan_dir::update(dir, &loaded.manifest.plan, vec![(name.clone(), bytes)], &WriteOptions::default())?;
            dir.join(name)
        }
    };
    println!("wrote {}", path.display());
    Ok(())
}

fn run_figure(model: Option<PathBuf>, read: ModelArgs, human: Option<String>, stature: f64, mass: f64, out: &Path) -> Result<()> {
    use mintorque::model::{figure, human as jack, osim, urdf_export};
    let model = match (model, human) {
        (Some(path), None) => load_model(&path, read)?,
        (None, Some(name)) => {
            jack::Structure::from_name(&name)?.build(jack::HumanParams { stature_m: stature, mass_kg: mass })?
        }
        _ => anyhow::bail!("give a model file or --human NAME"),
    };
    let text = match out.extension().and_then(|e| e.to_str()) {
        Some("urdf") | Some("xml") => urdf_export::to_urdf(&model),
        Some("toml") => figure::to_toml(&model),
        Some("osim") => osim::to_osim(&model),
        _ => anyhow::bail!("{}: the output must end in .urdf, .toml or .osim", out.display()),
    };
    plan_dir::write_file(out, text.as_bytes())?;
    println!("wrote {} ({} joints)", out.display(), model.nv());
    Ok(())
}

/// Simulates a plan directory's plan, or a task planned first; false when that plan did not converge.
fn run_simulate(path: &Path, steps: u64) -> Result<bool> {
    let (task, x, status, converged) = if path.is_dir() {
        let (loaded, task, x) = plan_dir::load_task(path)?;
        let converged = loaded.record.converged;
        (task, x, format!("plan of {}{}", path.display(), if converged { "" } else { " (NOT converged)" }), converged)
    } else {
        let mut task = Task::load(path)?;
        let planned = solve(&mut task, true, None)?;
        let status = if planned.converged() { "plan converged" } else { "plan NOT converged" };
        let converged = planned.converged();
        (task, planned.x, status.to_string(), converged)
    };
    let steps = usize::try_from(steps).context("--steps: too large")?;
    let sim = plan::simulate::simulate_x(&task.spec, &x, steps)?;
    println!("{status}; forward simulation with {steps} RK4 steps of {:.2e} s", sim.step);
    for (j, d) in task.spec.model.joints[1..].iter().zip(&sim.max_drift) {
        let (v, unit) = if j.kind == mintorque::model::JointKind::Prismatic { (*d * 1e3, "mm") } else { (d.to_degrees(), "°") };
        println!("  {:<16} max drift {v:.4} {unit}", j.name);
    }
    Ok(converged)
}

fn run_dynamics(model: &Path, read: ModelArgs, states: Option<PathBuf>, gravity: Option<Vec<f64>>, do_bench: bool) -> Result<()> {
    let model = load_model(model, read)?;
    let file = states.as_deref().map(|p| StatesFile::load(p, &model)).transpose()?;
    let g = match (&gravity, file.as_ref().and_then(|f| f.gravity)) {
        (Some(g), _) => {
            let g = Vec3::new(g[0], g[1], g[2]);
            mintorque::dynamics::batch::check_gravity(&g, "--gravity", "GX GY GZ")?;
            g
        }
        (None, Some(g)) => g,
        (None, None) => model.gravity,
    };
    if do_bench {
        println!("{}", serde_json::to_string_pretty(&bench::bench(&model, &g, 1000))?);
        return Ok(());
    }
    let file = file.context("--states is required")?;
    let results = file.evaluate(&model, &g)?;
    let json =
        serde_json::json!({ "model": model.name, "joints": file.joint_names, "gravity": [g.x, g.y, g.z], "states": results });
    println!("{}", serde_json::to_string_pretty(&json)?);
    Ok(())
}

fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Plan { task, out, solver, control_points, starts, refine, warm_start, refine_from, quiet, no_plots, trace } => {
            let solver = solver.map(|s| match s {
                SolverArg::Structured => SolverKind::Structured,
                SolverArg::Newton => SolverKind::Newton,
                SolverArg::InteriorPoint => SolverKind::InteriorPoint,
                SolverArg::AuglagBfgs => SolverKind::AuglagBfgs,
            });
            let overrides = Overrides { solver, control_points, starts, refine };
            let outputs = PlanOutputs { quiet, no_plots, trace };
            let from = match (warm_start, refine_from) {
                (Some(dir), _) => Start::Warm(dir),
                (None, Some(dir)) => Start::Refine(dir),
                (None, None) => Start::Guess,
            };
            Ok(exit(run_plan(task.as_deref(), &out, &overrides, &from, outputs)?))
        }
        Command::Sweep { sweep: file, out, keep_plans, quiet } => Ok(exit(sweep::run(&file, &out, keep_plans, quiet)?)),
        Command::Export { dir, format, out, fps, units, channels, angles, columns, joints, rate } => {
            let options = report::export::Options::from_names(fps, &units, &channels, &angles, &columns, joints, rate)?;
            run_export(&dir, &format, out, &options).map(|()| ExitCode::SUCCESS)
        }
        Command::View { dir, filmstrip } => {
            let view = filmstrip
                .map(|v| v.parse::<report::filmstrip::View>())
                .transpose()
                .map_err(|m| anyhow::anyhow!("--filmstrip: {m}"))?;
            let page = plan_dir::write_views(&dir, view)?;
            report::viewer::open_in_browser(&page);
            Ok(ExitCode::SUCCESS)
        }
        Command::Figure { model, human, stature, mass, out, read } => {
            run_figure(model, read, human, stature, mass, &out).map(|()| ExitCode::SUCCESS)
        }
        Command::Examples => {
            for e in mintorque::plan::examples::ALL {
                println!("{:<20} {}", e.name, e.summary());
            }
            println!("\nrun one with: mintorque plan examples/NAME.toml --out out/NAME");
            Ok(ExitCode::SUCCESS)
        }
        Command::Simulate { plan: path, steps } => Ok(exit(run_simulate(&path, steps)?)),
        Command::Inverse {
            model,
            motion,
            out,
            filter_hz,
            no_filter,
            rate,
            spline,
            forces,
            loads,
            lift,
            units,
            quiet,
            no_plots,
            read,
        } => {
            let subject = inverse::subject(&model, |path| load_model(path, read))?;
            let (loads, lift, units) = (loads.as_deref(), lift.as_deref(), units.as_deref());
            let settings = mintorque::inverse::Settings {
                filter_hz: (!no_filter).then_some(filter_hz),
                rate_hz: rate,
                spline: spline.into(),
                forces: forces.into(),
            };
            let args = inverse::Args { motion: &motion, out: &out, settings, loads, lift, units, quiet, no_plots };
            inverse::run(&subject, &args).map(|()| ExitCode::SUCCESS)
        }
        Command::Dynamics { model, states, gravity, bench, read } => {
            run_dynamics(&model, read, states, gravity, bench).map(|()| ExitCode::SUCCESS)
        }
    }
}

/// The exit code of an error: 3 for a result that is not finite, 1 for everything else.
fn exit_code(e: &anyhow::Error) -> u8 {
    match e.downcast_ref::<plan_dir::Error>() {
        Some(plan_dir::Error::NonFinite { .. }) => NOT_CONVERGED,
        _ => BAD_INPUT,
    }
}

fn main() -> ExitCode {
    restore_sigpipe();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // --help and --version print to stdout and succeed; a bad argument is bad input.
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() { ExitCode::from(BAD_INPUT) } else { ExitCode::SUCCESS };
        }
    };
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(exit_code(&e))
        }
    }
}

/// A closed pipe on stdout (`mintorque examples | head -1`) ends the process quietly, as it does any Unix
/// tool: Rust ignores SIGPIPE, so a print to a closed pipe would panic instead. Outputs are written to the
/// plan directory before anything is printed, so nothing is cut short.
fn restore_sigpipe() {
    #[cfg(unix)]
    // SAFETY: sets the default action of one signal before any thread starts; no handler is involved.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}
