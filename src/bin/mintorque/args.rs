//! The command line: every command and option (clap).

use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser)]
#[command(name = "mintorque", version, about = "Minimum-joint-torque motion planning for articulated figures")]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Plan the minimum-torque motion of a task file and write the results into a directory.
    Plan {
        /// The task (TOML; see docs/task-file.md). With --refine-from, default: that plan's task.resolved.toml.
        #[arg(required_unless_present = "refine_from")]
        task: Option<PathBuf>,
        /// Output directory (created if needed): trajectory.csv, summary.json, task.resolved.toml.
        #[arg(long, short)]
        out: PathBuf,
        /// Override the task's solver.
        #[arg(long, value_enum)]
        solver: Option<SolverArg>,
        /// Fix the number of B-spline control points per joint (no refinement unless --refine).
        #[arg(long)]
        control_points: Option<usize>,
        /// Override the starting points solved in parallel (the best plan is kept): a number, or "auto" (the
        /// default: two, and two more where they disagree).
        #[arg(long, value_parser = clap::value_parser!(mintorque::plan::Starts))]
        starts: Option<mintorque::plan::Starts>,
        /// Refine the number of control points until the effort changes by less than 0.5 % (the default when
        /// the task does not fix discretization.control_points).
        #[arg(long)]
        refine: bool,
        /// Start from the plan in this directory (same figure and N): its motion, forces and multipliers.
        #[arg(long, conflicts_with = "refine_from")]
        warm_start: Option<PathBuf>,
        /// Refine the plan in this directory: start from it at its N (converged at once), then halve the knot
        /// spans until the effort changes by less than 0.5 %.
        #[arg(long, conflicts_with = "control_points")]
        refine_from: Option<PathBuf>,
        /// No progress output.
        #[arg(long, short)]
        quiet: bool,
        /// Skip the plots.
        #[arg(long)]
        no_plots: bool,
        /// Also write the solver's iteration log, OUT/trace.csv: a row per accepted step of the first start
        /// (objective, violation, stationarity, penalty, model, damping, seconds).
        #[arg(long)]
        trace: bool,
    },
    /// Plan a base task for every combination of the values of some of its fields (docs/sweeps.md), on all
    /// cores, into a table: OUT/sweep.csv and sweep.parquet, one row per plan, and plots against each value.
    /// Re-running resumes: the plans already in the table are skipped.
    Sweep {
        /// The sweep file (TOML): the base task and the fields to vary.
        sweep: PathBuf,
        /// Output directory (created if needed).
        #[arg(long, short)]
        out: PathBuf,
        /// Also write every plan's directory under OUT/plans/INDEX/.
        #[arg(long)]
        keep_plans: bool,
        /// No progress output.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Export a planned motion (a directory written by `plan`) for other tools.
    Export {
        /// The plan directory.
        dir: PathBuf,
        /// bvh (Blender, MotionBuilder), gltf (binary .glb), mot (OpenSim), osim (the figure, for OpenSim), csv.
        #[arg(long)]
        format: String,
        /// Output file (default: inside DIR, named after the model).
        #[arg(long, short)]
        out: Option<PathBuf>,
        /// bvh: frames per second (default: the plan's sample rate), resampled from the plan's samples.
        #[arg(long)]
        fps: Option<f64>,
        /// bvh: length unit, cm (what BVH tools expect) or m.
        #[arg(long, default_value = "cm")]
        units: String,
        /// bvh: channels per moving joint (three rotations, three positions: what Blender reads) or per
        /// moving degree of freedom (dof).
        #[arg(long, default_value = "joint")]
        channels: String,
        /// csv: angles of revolute joints in deg or rad (the header says which).
        #[arg(long, default_value = "deg")]
        angles: String,
        /// csv: the quantities to write, of q,qd,qdd,tau,force (default: all).
        #[arg(long, value_delimiter = ',')]
        columns: Vec<String>,
        /// csv: the joints to write, by name (default: all).
        #[arg(long, value_delimiter = ',')]
        joints: Vec<String>,
        /// csv: rows per second, resampled (default: the plan's samples).
        #[arg(long)]
        rate: Option<f64>,
    },
    /// Open a plan directory's animation (motion.html) in the browser, regenerating its view files.
    View {
        /// The plan directory.
        dir: PathBuf,
        /// Also draw the filmstrip from this camera — side (looking along +y), front or top — as
        /// filmstrip-VIEW.svg/.png beside the plan's own.
        #[arg(long)]
        filmstrip: Option<String>,
    },
    /// Write a figure — a built-in human or a model file — as URDF (for any URDF viewer), as a figure
    /// file (TOML) to edit, or as an OpenSim model (.osim).
    Figure {
        /// A URDF, MJCF (MuJoCo), figure file or (uncoupled) OpenSim .osim to convert.
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
        /// Output file: .urdf for URDF, .toml for a figure file, .osim for OpenSim.
        #[arg(long, short)]
        out: PathBuf,
        #[command(flatten)]
        read: ModelArgs,
    },
    /// List the bundled examples (the paper's experiments), one line each.
    Examples,
    /// Integrate the forward dynamics under a plan's torques from its start state and report the drift from
    /// the planned motion.
    Simulate {
        /// A plan directory (written by `plan`), or a task file to plan first.
        plan: PathBuf,
        /// RK4 steps over the motion (at least 1).
        #[arg(long, default_value_t = 4000, value_parser = clap::value_parser!(u64).range(1..))]
        steps: u64,
    },
    /// Inverse dynamics of a recorded motion (OpenSim .mot/.sto, CSV or BVH; docs/interop.md): resampled,
    /// low-pass filtered, differentiated by splines; torques as OpenSim's .sto and CSV, plots, ergonomics.
    Inverse {
        /// A URDF, MJCF, figure file or OpenSim model (a coupled one's forces are its coordinates').
        model: PathBuf,
        /// The motion: .mot/.sto (time and one column per joint; inDegrees as the header says), .csv
        /// (time and one column per joint, degrees or metres; `NAME.q_rad` for radians) or .bvh (joints
        /// named as `export --format bvh` names them, Euler channels in any order, degrees).
        motion: PathBuf,
        /// Output directory (new, empty, or one this command wrote): replaced whole.
        #[arg(long, short)]
        out: PathBuf,
        /// Low-pass cutoff (Hz) of the zero-lag 4th-order Butterworth filter.
        #[arg(long, default_value_t = mintorque::inverse::DEFAULT_FILTER_HZ)]
        filter_hz: f64,
        /// Do not filter the motion.
        #[arg(long, conflicts_with = "filter_hz")]
        no_filter: bool,
        /// Resample to this even rate (Hz; default: the file's mean rate).
        #[arg(long)]
        rate: Option<f64>,
        /// How q̇, q̈ are obtained: `smoothing` (one quintic smoothing spline, −3 dB at the cutoff: filter and
        /// derivatives at once) or `interpolating` (the Butterworth filter, then a not-a-knot cubic through
        /// the filtered samples).
        #[arg(long, value_enum, default_value_t = crate::inverse::SplineArg::Smoothing)]
        spline: crate::inverse::SplineArg,
        /// Which generalized forces: `net` (the default: everything the joint carries, passive springs and
        /// dampers included) or `actuator` (the net forces less the model's springs and dampers, as
        /// OpenSim's InverseDynamicsTool reports them).
        #[arg(long, value_enum, default_value_t = crate::inverse::ForcesArg::Net)]
        forces: crate::inverse::ForcesArg,
        /// External loads on the figure over time: CSV (time_s, FRAME.fx_N … FRAME.mz_Nm; world axes) or
        /// OpenSim's ExternalLoads .xml with its datafile.
        #[arg(long)]
        loads: Option<PathBuf>,
        /// The revised NIOSH lifting equation of the recorded hand path: a TOML file with `[lift]` (the
        /// fields of a task's `[ergonomics.lift]`, `load_kg` required) and optional `origin_s`,
        /// `destination_s` (docs/ergonomics.md).
        #[arg(long)]
        lift: Option<PathBuf>,
        /// A BVH motion's length unit: cm (the default, as BVH is usually written) or m.
        #[arg(long)]
        units: Option<String>,
        /// No summary on stdout.
        #[arg(long, short)]
        quiet: bool,
        /// Skip the plots.
        #[arg(long)]
        no_plots: bool,
        #[command(flatten)]
        read: ModelArgs,
    },
    /// Inverse dynamics, its derivatives, H(q) and forward dynamics of a model at the states of a file
    /// (the reference data's JSON format), printed as JSON in the file's joint order.
    Dynamics {
        /// A URDF (.urdf), figure file (.toml) or uncoupled OpenSim model (.osim).
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
        #[command(flatten)]
        read: ModelArgs,
    },
}

/// How a model file given by path is read.
#[derive(clap::Args, Clone, Copy)]
pub(crate) struct ModelArgs {
    /// A URDF `<mimic>` joint (one that follows another): refuse the file, or read the joint as an
    /// independent degree of freedom (the coupling dropped).
    #[arg(long, value_enum, default_value_t = MimicArg::Refuse)]
    pub(crate) mimic: MimicArg,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum MimicArg {
    Refuse,
    Independent,
}

#[derive(Clone, Copy, clap::ValueEnum)]
pub(crate) enum SolverArg {
    Structured,
    Newton,
    InteriorPoint,
    AuglagBfgs,
}
