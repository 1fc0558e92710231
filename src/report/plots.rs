//! Plots of a planned motion, after the paper's Figures 2–3: joint angle, velocity, acceleration and
//! torque against time, one panel per joint, the initial guess dashed over the plan. Torque panels shade
//! the band the joint's strength allows (±effort) and draw its edges; contact forces get their own file
//! when the plan has contacts. Each plot is an SVG (drawn by `plotters`) and a PNG rendered from it (by
//! `resvg`, with the system's fonts; without any installed font the PNG has no lettering).

use super::record::{PlanRecord, SampleRecord};
use crate::error::{Error, Result};
use crate::model::{JointKind, Model};
use plotters::prelude::*;

mod axis;
pub(crate) mod legend;
pub(crate) use legend::Entry;

/// Width of one panel and height of one row of panels (SVG pixels).
const PANEL_WIDTH: u32 = 520;
const PANEL_HEIGHT: u32 = 240;
const TITLE_HEIGHT: u32 = 44;
/// PNGs are rendered at twice the SVG size, for legible lettering.
pub(crate) const PNG_SCALE: f32 = 2.0;
/// A strength limit further than this many times the largest |τ| is left off the torque panel's scale
/// (it would squash the curves flat) and named in the caption instead.
const LIMIT_ON_SCALE: f64 = 2.0;

const PLANNED: RGBColor = RGBColor(31, 90, 170);
const GUESS: RGBColor = RGBColor(200, 70, 40);
const LIMIT: RGBColor = RGBColor(150, 40, 40);
const ALLOWED_BAND: RGBColor = RGBColor(60, 160, 90);
const FORCE_COLOURS: [RGBColor; 3] = [RGBColor(200, 60, 50), RGBColor(40, 150, 70), RGBColor(31, 90, 170)];

/// What one plot file shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Quantity {
    Position,
    Velocity,
    Acceleration,
    Torque,
}

impl Quantity {
    const ALL: [Quantity; 4] = [Quantity::Position, Quantity::Velocity, Quantity::Acceleration, Quantity::Torque];

    fn file_stem(self) -> &'static str {
        match self {
            Quantity::Position => "q",
            Quantity::Velocity => "qd",
            Quantity::Acceleration => "qdd",
            Quantity::Torque => "tau",
        }
    }

    fn title(self) -> &'static str {
        match self {
            Quantity::Position => "Joint displacement",
            Quantity::Velocity => "Joint velocity",
            Quantity::Acceleration => "Joint acceleration",
            Quantity::Torque => "Active joint torque",
        }
    }

    /// The unit shown and the factor from SI.
    fn unit(self, kind: JointKind) -> (&'static str, f64) {
        let degrees = 180.0 / std::f64::consts::PI;
        match (self, kind == JointKind::Prismatic) {
            (Quantity::Position, false) => ("°", degrees),
            (Quantity::Velocity, false) => ("°/s", degrees),
            (Quantity::Acceleration, false) => ("°/s²", degrees),
            (Quantity::Torque, false) => ("N·m", 1.0),
            (Quantity::Position, true) => ("m", 1.0),
            (Quantity::Velocity, true) => ("m/s", 1.0),
            (Quantity::Acceleration, true) => ("m/s²", 1.0),
            (Quantity::Torque, true) => ("N", 1.0),
        }
    }

    /// What the y axis measures, for a joint of `kind`.
    fn axis(self, kind: JointKind) -> &'static str {
        match (self, kind == JointKind::Prismatic) {
            (Quantity::Position, false) => "angle",
            (Quantity::Velocity, false) => "angular velocity",
            (Quantity::Acceleration, false) => "angular acceleration",
            (Quantity::Torque, false) => "torque",
            (Quantity::Position, true) => "position",
            (Quantity::Velocity, true) => "velocity",
            (Quantity::Acceleration, true) => "acceleration",
            (Quantity::Torque, true) => "force",
        }
    }

    fn value(self, s: &SampleRecord, i: usize) -> f64 {
        match self {
            Quantity::Position => s.q[i],
            Quantity::Velocity => s.qd[i],
            Quantity::Acceleration => s.qdd[i],
            Quantity::Torque => s.tau[i],
        }
    }
}

/// Every plot of `record` as `(file name, bytes)`: `q`, `qd`, `qdd`, `tau` and, with contacts,
/// `contact_forces`, each as `.svg` and `.png`. `guess` holds the initial guess sampled like the plan
/// (its curves are drawn dashed); pass `None` to leave it out.
pub fn plots(model: &Model, record: &PlanRecord, guess: Option<&[SampleRecord]>) -> Result<Vec<(String, Vec<u8>)>> {
    plots_labelled(model, record, guess, PLAN_LABELS)
}

/// What the motion's curves are called.
#[derive(Clone, Copy, Debug)]
pub struct Labels<'a> {
    /// The motion's curves in the legend.
    pub curve: &'a str,
    /// The torque plot's title (before the model's name).
    pub torque: &'a str,
}

/// A plan's: its torques are the active ones (the passive springs' and dampers' not included).
pub const PLAN_LABELS: Labels<'static> = Labels { curve: "planned", torque: "Active joint torque" };

/// [`plots`] with the motion's curves and torques called as `labels` say (`"inverse dynamics"` and its
/// net or actuator torque for a recorded motion).
pub fn plots_labelled(
    model: &Model,
    record: &PlanRecord,
    guess: Option<&[SampleRecord]>,
    labels: Labels,
) -> Result<Vec<(String, Vec<u8>)>> {
    let pictures =
        svgs(model, record, guess, labels)?.into_iter().map(|(name, svg)| (name.trim_end_matches(".svg").to_string(), svg));
    super::render::svg_and_png_files(pictures.collect(), PNG_SCALE, "plots")
}

/// The SVG plots alone, as `(file name, SVG text)`.
pub fn plot_svgs(model: &Model, record: &PlanRecord, guess: Option<&[SampleRecord]>) -> Result<Vec<(String, String)>> {
    svgs(model, record, guess, PLAN_LABELS)
}

fn svgs(model: &Model, record: &PlanRecord, guess: Option<&[SampleRecord]>, labels: Labels) -> Result<Vec<(String, String)>> {
    super::check_samples(model, record)?;
    if let Some(g) = guess {
        check_guess(model, g)?;
    }
    if record.samples.is_empty() {
        return Err(Error::input("plan.json", "samples", "the plan holds no samples to plot"));
    }
    let mut files = Vec::new();
    if model.nv() > 0 {
        for quantity in Quantity::ALL {
            files.push((format!("{}.svg", quantity.file_stem()), joint_plot(model, record, guess, quantity, labels)?));
        }
    }
    if !record.contacts.is_empty() {
        files.push(("contact_forces.svg".to_string(), contact_plot(record)?));
    }
    Ok(files)
}

fn check_guess(model: &Model, guess: &[SampleRecord]) -> Result<()> {
    let nv = model.nv();
    match guess.iter().position(|s| [s.q.len(), s.qd.len(), s.qdd.len(), s.tau.len()].iter().any(|&n| n != nv)) {
        Some(k) => {
            Err(Error::input("initial guess", format!("samples[{k}]"), format!("expected {nv} values of q, qd, qdd and tau")))
        }
        None => Ok(()),
    }
}

/// One panel's chart over time: the caption, time (s) along x, `unit` along y, a light grid.
pub(crate) fn time_chart<'a, DB: DrawingBackend + 'a>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    x: (f64, f64),
    y: (f64, f64),
    unit: &str,
) -> Result<ChartContext<'a, DB, Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>>> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 15))
        .margin(6)
        .x_label_area_size(34)
        .y_label_area_size(58)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(drawing_error)?;
    let y_tick = |v: &f64| axis::tick_label(*v, y.1 - y.0);
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc(unit)
        .x_labels(6)
        .y_labels(5)
        .y_label_formatter(&y_tick)
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(drawing_error)?;
    Ok(chart)
}

pub(crate) fn drawing_error(e: impl std::fmt::Display) -> Error {
    Error::input("plots", "drawing", e.to_string())
}

/// Rows and columns of panels: one column for a few joints, two beyond.
pub(crate) fn grid(panels: usize) -> (usize, usize) {
    let columns = if panels <= 3 { 1 } else { 2 };
    (panels.div_ceil(columns).max(1), columns)
}

/// The canvas of `rows × columns` panels under the title and a legend strip `legend` px high.
pub(crate) fn canvas_size((rows, columns): (usize, usize), legend: u32) -> (u32, u32) {
    (PANEL_WIDTH * columns as u32, PANEL_HEIGHT * rows as u32 + TITLE_HEIGHT + legend)
}

/// `[lo, hi]` of `values` widened by 5 % (and to ±1 around a constant), for a y axis.
pub(crate) fn padded_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let pad = if hi - lo > 1e-12 { 0.05 * (hi - lo) } else { 1.0f64.max(0.05 * hi.abs()) };
    (lo - pad, hi + pad)
}

pub(crate) fn time_range(record: &PlanRecord) -> (f64, f64) {
    let first = record.samples.first().map_or(0.0, |s| s.t);
    let last = record.samples.last().map_or(1.0, |s| s.t);
    if last > first {
        (first, last)
    } else {
        (first, first + 1.0)
    }
}

/// One quantity for every joint, a panel each, under one legend.
fn joint_plot(
    model: &Model,
    record: &PlanRecord,
    guess: Option<&[SampleRecord]>,
    quantity: Quantity,
    labels: Labels,
) -> Result<String> {
    let panels: Vec<JointPanel> = (0..model.nv()).map(|i| JointPanel::new(model, record, guess, quantity, i)).collect();
    let name = if quantity == Quantity::Torque { labels.torque } else { quantity.title() };
    let title = format!("{name} — {}", record.model_name);
    panels_svg(&title, panels.len(), &joint_legend(&panels, labels.curve), |k, area| panels[k].draw(area, time_range(record)))
}

/// A canvas of `count` panels (see [`grid`]) under `title` and the legend strip of `entries`, as SVG text;
/// `draw(k, area)` draws panel `k`.
pub(crate) fn panels_svg(
    title: &str,
    count: usize,
    entries: &[Entry],
    mut draw: impl FnMut(usize, &DrawingArea<SVGBackend, plotters::coord::Shift>) -> Result<()>,
) -> Result<String> {
    let layout = grid(count);
    let legend_h = legend::height(entries, canvas_size(layout, 0).0);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, canvas_size(layout, legend_h)).into_drawing_area();
        root.fill(&WHITE).map_err(drawing_error)?;
        let body = root.titled(title, ("sans-serif", 22)).map_err(drawing_error)?;
        let (strip, body) = body.split_vertically(legend_h);
        legend::draw(&strip, entries)?;
        for (k, area) in body.split_evenly(layout).iter().enumerate().take(count) {
            draw(k, area)?;
        }
        root.present().map_err(drawing_error)?;
    }
    Ok(svg)
}

/// The legend of the joint plots: the plan (`label`), the guess where one is drawn, the strength band where one is.
fn joint_legend(panels: &[JointPanel], label: &str) -> Vec<Entry> {
    let mut entries = vec![Entry::line(label, PLANNED, 2)];
    if panels.iter().any(|p| !p.guessed.is_empty()) {
        let label = match panels.iter().any(|p| p.guess_cut) {
            true => "initial guess (cut where it leaves the plan's scale)",
            false => "initial guess",
        };
        entries.push(Entry { dashed: true, ..Entry::line(label, GUESS, 2) });
    }
    if panels.iter().any(|p| p.band.is_some()) {
        entries.push(Entry { opacity: 0.8, ..Entry::line("strength limit (shaded: allowed)", LIMIT, 1) });
    }
    entries
}

/// One joint's panel, worked out before drawing: its caption, curves, y range and strength band.
struct JointPanel {
    caption: String,
    axis: String,
    planned: Vec<(f64, f64)>,
    guessed: Vec<(f64, f64)>,
    y: (f64, f64),
    guess_cut: bool,
    band: Option<(f64, f64)>,
}

impl JointPanel {
    fn new(model: &Model, record: &PlanRecord, guess: Option<&[SampleRecord]>, quantity: Quantity, i: usize) -> JointPanel {
        let joint = &model.joints[i + 1];
        let (unit, factor) = quantity.unit(joint.kind);
        let series = |samples: &[SampleRecord]| -> Vec<(f64, f64)> {
            samples.iter().map(|s| (s.t, quantity.value(s, i) * factor)).collect()
        };
        let planned = series(&record.samples);
        let guessed = guess.map(series).unwrap_or_default();
        // The band [−τ⁻, τ⁺] (the limits of the two directions), drawn when both are finite and on scale.
        let (up, down) = (joint.limits.effort_toward(true), joint.limits.effort_toward(false));
        let limit = (quantity == Quantity::Torque).then_some(up.max(down)).filter(|e| e.is_finite() && *e > 0.0);
        // The plan sets the scale: an initial guess far off it (a kinematic guess can need ten times the
        // torque) would flatten the plan into a line. Where the guess leaves the scale it is cut.
        let peak = planned.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
        let limit_on_scale = limit.filter(|&l| l <= LIMIT_ON_SCALE * peak.max(1e-9));
        let mut caption = format!("{} ({unit})", joint.name);
        if let (Some(l), None) = (limit, limit_on_scale) {
            caption.push_str(&format!(" — strength ±{l:.0} {unit}, off scale"));
        }
        let band = limit_on_scale.filter(|_| up.is_finite() && down.is_finite()).map(|_| (-down, up));
        let band_edges = band.map_or(vec![], |(lo, hi)| vec![lo, hi]);
        let y = padded_range(planned.iter().map(|p| p.1).chain(band_edges));
        let (y, guess_cut) = guess_scale(y, &guessed);
        if guess_cut {
            caption.push_str(" — guess cut at the plan's scale");
        }
        let axis = format!("{} ({unit})", quantity.axis(joint.kind));
        JointPanel { caption, axis, planned, guessed, y, guess_cut, band }
    }

    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, plotters::coord::Shift>, x: (f64, f64)) -> Result<()> {
        let mut chart = time_chart(area, &self.caption, x, self.y, &self.axis)?;
        if let Some(edges) = self.band {
            draw_strength_band(&mut chart, x, edges)?;
        }
        chart.draw_series(LineSeries::new(self.planned.clone(), PLANNED.stroke_width(2))).map_err(drawing_error)?;
        for run in clipped_runs(&self.guessed, self.y) {
            chart.draw_series(DashedLineSeries::new(run, 6, 4, GUESS.stroke_width(2))).map_err(drawing_error)?;
        }
        Ok(())
    }
}

/// The chart's legend at `position`, in the plots' one style (a pale box, a thin border, `size` px text).
pub(crate) fn draw_legend<'a, DB: DrawingBackend + 'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
    size: u32,
) -> Result<()> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(("sans-serif", size))
        .draw()
        .map_err(drawing_error)
}

/// The y range of a panel with the guess: the plan's range, widened to hold the guess when that takes at
/// most twice the plan's span; otherwise the plan's range and `true` (the guess is cut at the edges).
fn guess_scale(plan: (f64, f64), guess: &[(f64, f64)]) -> ((f64, f64), bool) {
    let with_guess = padded_range(guess.iter().map(|p| p.1).chain([plan.0, plan.1]));
    if guess.is_empty() || with_guess.1 - with_guess.0 <= 2.0 * (plan.1 - plan.0) {
        (if guess.is_empty() { plan } else { with_guess }, false)
    } else {
        (plan, true)
    }
}

/// The line through `points` clipped to `lo ≤ y ≤ hi`: its runs inside, each segment cut where it crosses
/// an edge (so a steep guess still shows where it passes through the scale).
fn clipped_runs(points: &[(f64, f64)], (lo, hi): (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = vec![];
    let mut open = false;
    for w in points.windows(2) {
        let Some((s0, s1)) = clip_segment(w[0], w[1], lo, hi) else {
            open = false;
            continue;
        };
        let at = |s: f64| (w[0].0 + s * (w[1].0 - w[0].0), w[0].1 + s * (w[1].1 - w[0].1));
        if !open || s0 > 0.0 {
            runs.push(vec![at(s0)]);
        }
        runs.last_mut().expect("a run was opened").push(at(s1));
        open = s1 >= 1.0;
    }
    runs
}

/// The part `[s0, s1]` of the segment `a + s (b − a)`, `s ∈ [0, 1]`, where `lo ≤ y ≤ hi`; `None` outside.
fn clip_segment(a: (f64, f64), b: (f64, f64), lo: f64, hi: f64) -> Option<(f64, f64)> {
    let dy = b.1 - a.1;
    if dy == 0.0 {
        return (a.1 >= lo && a.1 <= hi).then_some((0.0, 1.0));
    }
    // y(s) = lo and y(s) = hi at s = (lo − a_y)/Δy and (hi − a_y)/Δy.
    let (s_lo, s_hi) = ((lo - a.1) / dy, (hi - a.1) / dy);
    let (s0, s1) = (s_lo.min(s_hi).max(0.0), s_lo.max(s_hi).min(1.0));
    (s0 <= s1).then_some((s0, s1))
}

/// The band `−τ⁻ ≤ τ ≤ τ⁺` shaded, and its edges.
fn draw_strength_band<DB: DrawingBackend>(
    chart: &mut ChartContext<DB, Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>>,
    (t0, t1): (f64, f64),
    (low, high): (f64, f64),
) -> Result<()> {
    chart
        .draw_series(std::iter::once(Rectangle::new([(t0, low), (t1, high)], ALLOWED_BAND.mix(0.12).filled())))
        .map_err(drawing_error)?;
    for edge in [high, low] {
        chart.draw_series(LineSeries::new([(t0, edge), (t1, edge)], LIMIT.mix(0.8).stroke_width(1))).map_err(drawing_error)?;
    }
    Ok(())
}

/// The force of every contact on the figure, a panel each: x, y, z (world axes, N).
fn contact_plot(record: &PlanRecord) -> Result<String> {
    let axes = ["x", "y", "z"];
    let entries: Vec<Entry> = axes.iter().zip(FORCE_COLOURS).map(|(a, c)| Entry::line(format!("f{a}"), c, 2)).collect();
    let title = format!("Contact forces on the figure — {}", record.model_name);
    panels_svg(&title, record.contacts.len(), &entries, |c, area| {
        let x = time_range(record);
        let y = padded_range(record.samples.iter().flat_map(|s| s.contact_forces[c]));
        let caption = format!("{} (N, world axes)", record.contacts[c].name);
        let mut chart = time_chart(area, &caption, x, y, "force (N)")?;
        for (axis, colour) in FORCE_COLOURS.iter().enumerate() {
            let points: Vec<(f64, f64)> = record.samples.iter().map(|s| (s.t, s.contact_forces[c][axis])).collect();
            chart.draw_series(LineSeries::new(points, colour.stroke_width(2))).map_err(drawing_error)?;
        }
        Ok(())
    })
}
