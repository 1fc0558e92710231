//! The contents of a plan and the files they are rendered to: everything `mintorque plan` writes,
//! assembled from a task and its plan ([`PlanContents::from_task`]) or from a record made in Rust.

use super::Result;
use crate::model::{figure, Model};
use crate::plan::{self, task::Task, Plan};
use crate::report::ergonomics::{self, Ergonomics};
use crate::report::filmstrip::{self, View};
use crate::report::record::{PlanRecord, SampleRecord};
use crate::report::{self, viewer, Summary};
use std::collections::BTreeMap;

/// Everything a plan directory holds, before it is rendered to files.
#[derive(Clone, Debug)]
pub struct PlanContents {
    /// The figure, written as `model.figure.toml`.
    pub model: Model,
    /// `plan.json`.
    pub record: PlanRecord,
    /// `summary.json`: the summary, with the ergonomic report as its `ergonomics`.
    pub summary: Option<Summary>,
    /// `ergonomics.json`, and the `ergonomics` of `summary.json`.
    pub ergonomics: Option<Ergonomics>,
    /// The load of every joint at every sample: `joint_loads.csv` and its plots.
    pub joint_loads: Option<ergonomics::loads::LoadSeries>,
    /// `task.resolved.toml`.
    pub resolved_task: Option<String>,
    /// Plot the motion (with the initial guess dashed, when given).
    pub plots: bool,
    /// The initial guess sampled, drawn dashed in the plots.
    pub guess: Option<Vec<SampleRecord>>,
    /// The camera of `filmstrip.svg` / `.png`.
    pub filmstrip_view: View,
    /// The solver's iteration log, written as `trace.csv` when given (`plan --trace`).
    pub trace: Option<crate::solve::Trace>,
}

impl PlanContents {
    /// A plan directory of a record alone (no summary, task or plots): for plans made in Rust.
    pub fn from_record(model: Model, record: PlanRecord) -> PlanContents {
        PlanContents {
            model,
            record,
            summary: None,
            ergonomics: None,
            joint_loads: None,
            resolved_task: None,
            plots: false,
            guess: None,
            filmstrip_view: View::Side,
            trace: None,
        }
    }

    /// The contents of `task` planned as `planned`: sampled at the task's rate, summarised (with the
    /// ergonomic report), plotted unless the task or `no_plots` says not, the filmstrip in the task's view.
    pub fn from_task(task: &Task, planned: &Plan, no_plots: bool) -> Result<PlanContents> {
        super::finite::check_plan(task, planned)?;
        let (spec, output) = (&task.spec, &task.file.output);
        let times = report::sample_times(spec.duration, output.sample_rate);
        let samples = plan::sample(spec, planned, &times)?;
        let record = PlanRecord::new(spec, planned, &samples);
        super::finite::check_record(&record, "the planned motion")?;
        let summary = Summary::new(spec, planned, &samples);
        let origin = task.path.display().to_string();
        let setup = ergonomics::Setup::resolve(&task.file, spec, &origin)?;
        let joint_loads = ergonomics::loads::series(&spec.model, &record, &spec.loads)?;
        let mut ergonomics = ergonomics::ergonomics(&spec.model, &record, &output.strength)?;
        ergonomics.add_measures(&spec.model, &record, &setup, &joint_loads, &origin)?;
        let resolved = toml::to_string_pretty(&task.resolved_file())
            .map_err(|e| crate::Error::task(task.path.display().to_string(), "serialising the resolved task", e.to_string()))?;
        let plots = output.plots && !no_plots;
        let guess = match plots {
            true => Some(plan::sample_initial_guess(spec, &times)?.iter().map(SampleRecord::from).collect()),
            false => None,
        };
        let view = output
            .filmstrip_view
            .parse::<View>()
            .map_err(|m| crate::Error::task(task.path.display().to_string(), "output.filmstrip_view", m))?;
        Ok(PlanContents {
            model: spec.model.clone(),
            record,
            summary: Some(summary),
            ergonomics: Some(ergonomics),
            joint_loads: Some(joint_loads),
            resolved_task: Some(resolved),
            plots,
            guess,
            filmstrip_view: view,
            trace: None,
        })
    }

    /// `summary.json`'s contents.
    pub fn summary_json(&self) -> Result<Option<serde_json::Value>> {
        let Some(summary) = &self.summary else { return Ok(None) };
        let mut json = to_json(summary)?;
        if let Some(e) = &self.ergonomics {
            json["ergonomics"] = to_json(e)?;
        }
        Ok(Some(json))
    }

    /// Every file of the plan directory but the manifest, by name.
    pub fn render(&self) -> Result<BTreeMap<String, Vec<u8>>> {
        self.render_reporting(&mut |_, _, _| {})
    }

    /// The stages of [`PlanContents::render`], in order: what each makes.
    pub fn stages(&self) -> Vec<&'static str> {
        let mut stages = vec!["plan data and tables", "3D viewer", "filmstrip"];
        for view in self.extra_views() {
            stages.push(if view == View::Front { "front filmstrip" } else { "side filmstrip" });
        }
        if self.plots {
            stages.push("motion plots");
            if self.ergonomics.is_some() {
                stages.push("ergonomic plots");
            }
        }
        stages
    }

    /// The filmstrips beside the task's own view: a 3D plan is shown from the front and the side (the side
    /// view hides its sideways part, the front its forward part), whichever of them `filmstrip_view` is not.
    fn extra_views(&self) -> Vec<View> {
        if !filmstrip::needs_front_view(&self.model, &self.record) {
            return vec![];
        }
        [View::Front, View::Side].into_iter().filter(|v| *v != self.filmstrip_view).collect()
    }

    /// [`PlanContents::render`], calling `progress(k, n, stage)` before each of its `n` stages (see
    /// [`PlanContents::stages`]; `k` counts from 1).
    pub fn render_reporting(&self, progress: &mut dyn FnMut(usize, usize, &str)) -> Result<BTreeMap<String, Vec<u8>>> {
        let (model, record) = (&self.model, &self.record);
        report::check_samples(model, record)?;
        crate::report::scene::check_record(model, record).map_err(|m| crate::Error::input("plan", "samples", m))?;
        let stages = self.stages();
        // Stage k of n begins: report it.
        let mut done = 0;
        let mut next = || {
            progress(done + 1, stages.len(), stages[done]);
            done += 1;
        };
        let mut files = BTreeMap::new();
        next();
        files.insert("plan.json".to_string(), pretty(record)?);
        files.insert("model.figure.toml".to_string(), figure::to_toml(model).into_bytes());
        files.insert("trajectory.csv".to_string(), report::export::csv::csv(model, record, &Default::default())?.into_bytes());
        files.insert("torques.sto".to_string(), report::export::mot::torques_sto(model, record).into_bytes());
        if let Some(trace) = &self.trace {
            files.insert("trace.csv".to_string(), trace.to_csv().into_bytes());
        }
        if let Some(series) = &self.joint_loads {
            files.insert("joint_loads.csv".to_string(), ergonomics::loads::csv(model, record, series).into_bytes());
        }
        let summary_text = self.summary_json()?.as_ref().map(pretty_text).transpose()?;
        if let Some(text) = &summary_text {
            files.insert("summary.json".to_string(), text.clone().into_bytes());
        }
        if let Some(t) = &self.resolved_task {
            files.insert("task.resolved.toml".to_string(), t.clone().into_bytes());
        }
        // The renderings are independent: all at once on scoped threads, joined (and reported) in order.
        let jobs = self.renderings(summary_text.as_deref());
        std::thread::scope(|scope| {
            let handles: Vec<_> = jobs.into_iter().map(|job| scope.spawn(job)).collect();
            for handle in handles {
                next();
                let rendered = handle.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic))?;
                files.extend(rendered);
            }
            Ok::<_, super::Error>(())
        })?;
        Ok(files)
    }
}

/// One rendering of [`PlanContents::render_reporting`]: the files of one of its stages after the first.
type Rendering<'a> = Box<dyn FnOnce() -> Result<Vec<(String, Vec<u8>)>> + Send + 'a>;

impl PlanContents {
    /// The stages after the first ([`PlanContents::stages`]), in their order: the viewer, the filmstrips,
    /// the plots.
    fn renderings<'a>(&'a self, summary: Option<&'a str>) -> Vec<Rendering<'a>> {
        let (model, record) = (&self.model, &self.record);
        let mut jobs: Vec<Rendering<'a>> = vec![
            Box::new(move || Ok(vec![motion_html(model, record, summary)])),
            Box::new(move || filmstrip(model, record, self.filmstrip_view, super::filmstrip_names(None))),
        ];
        for view in self.extra_views() {
            jobs.push(Box::new(move || filmstrip(model, record, view, super::filmstrip_names(Some(view)))));
        }
        if self.plots {
            jobs.push(Box::new(move || Ok(report::plots::plots(model, record, self.guess.as_deref())?)));
            if let Some(e) = &self.ergonomics {
                jobs.push(Box::new(move || Ok(ergonomics::plots::plots(model, record, self.joint_loads.as_ref(), e)?)));
            }
        }
        jobs
    }
}

/// `motion.html`.
pub(super) fn motion_html(model: &Model, record: &PlanRecord, summary: Option<&str>) -> (String, Vec<u8>) {
    (viewer::VIEW_FILES[0].to_string(), viewer::motion_html(model, record, summary).into_bytes())
}

/// The filmstrip from `view`, as SVG and PNG under `names`.
pub(super) fn filmstrip(model: &Model, record: &PlanRecord, view: View, names: [String; 2]) -> Result<Vec<(String, Vec<u8>)>> {
    let frames = viewer::FILMSTRIP_FRAMES;
    let svg = filmstrip::filmstrip_svg(model, record, frames, view);
    let png = filmstrip::png_of(&svg)?;
    let [svg_name, png_name] = names;
    Ok(vec![(svg_name, svg.into_bytes()), (png_name, png)])
}

fn to_json(v: &impl serde::Serialize) -> Result<serde_json::Value> {
    serde_json::to_value(v).map_err(|e| crate::Error::input("summary.json", "serialising", e.to_string()).into())
}

fn pretty(v: &impl serde::Serialize) -> Result<Vec<u8>> {
    pretty_text(v).map(String::into_bytes)
}

fn pretty_text(v: &impl serde::Serialize) -> Result<String> {
    serde_json::to_string_pretty(v).map_err(|e| crate::Error::input("plan", "serialising", e.to_string()).into())
}
