//! Plots of the ergonomic measures: the joint loads (force and moment components, child-body axes), the
//! L5/S1 compression and shear against NIOSH's limits, and each joint's torque as a share of its strength.
//! Each an SVG and a PNG, like the motion's plots.

use super::loads::LoadSeries;
use super::Ergonomics;
use crate::error::Result;
use crate::model::Model;
use crate::report::plots::{drawing_error, legend, padded_range, panels_svg, time_chart, time_range, Entry, PNG_SCALE};
use crate::report::record::PlanRecord;
use plotters::prelude::*;

const COLOURS: [RGBColor; 3] = [RGBColor(200, 60, 50), RGBColor(40, 150, 70), RGBColor(31, 90, 170)];
const LIMIT: RGBColor = RGBColor(150, 40, 40);

/// One panel: curves against time and horizontal reference levels.
struct Panel {
    caption: String,
    /// The y axis's quantity and unit.
    axis: &'static str,
    curves: Vec<(String, Vec<(f64, f64)>)>,
    levels: Vec<(String, f64)>,
}

/// Every ergonomic plot of `record` as `(file name, bytes)`: `joint_forces`, `joint_moments` (with the
/// loads), `low_back` and `strength_share` (when the report has them), each `.svg` and `.png`.
pub fn plots(model: &Model, record: &PlanRecord, series: Option<&LoadSeries>, e: &Ergonomics) -> Result<Vec<(String, Vec<u8>)>> {
    let mut svgs: Vec<(&str, String)> = Vec::new();
    if let Some(series) = series.filter(|_| model.nv() > 0 && !record.samples.is_empty()) {
        for (stem, title, unit, moment) in [
            ("joint_forces", "Joint force on the child body", "force (N)", false),
            ("joint_moments", "Joint moment on the child body", "moment (N·m)", true),
        ] {
            let (axes, note) = drawn_axes(model, series, moment);
            let panels = load_panels(model, record, series, unit, moment, &axes);
            let title = format!("{title} (child-body axes{note}) — {}", record.model_name);
            svgs.push((stem, lines_svg(&title, record, &panels)?));
        }
    }
    if let Some(b) = e.low_back.as_ref().filter(|b| !b.samples.is_empty()) {
        let curve = |f: fn(&super::lumbar::LowBackSample) -> f64| b.samples.iter().map(|s| (s.t, f(s))).collect();
        let panels = [
            Panel {
                caption: format!("L5/S1 compression at {} (N)", b.joint),
                axis: "force (N)",
                curves: vec![("compression".into(), curve(|s| s.compression_n))],
                levels: vec![
                    ("NIOSH action limit".into(), b.action_limit_n),
                    ("maximum permissible".into(), b.maximum_permissible_limit_n),
                ],
            },
            Panel {
                caption: format!("L5/S1 shear at {} (N, + forward)", b.joint),
                axis: "force (N)",
                curves: vec![("shear".into(), curve(|s| s.shear_n))],
                levels: vec![],
            },
        ];
        svgs.push(("low_back", lines_svg(&format!("Low-back load — {}", record.model_name), record, &panels)?));
    }
    if let Some(s) = e.strength_model.as_ref().filter(|s| !s.joints.is_empty()) {
        let panels: Vec<Panel> = s
            .joints
            .iter()
            .zip(&s.shares)
            .map(|(j, share)| Panel {
                caption: format!("{} — {} (% of strength)", j.name, j.source),
                axis: "share of strength (%)",
                curves: vec![(
                    "|τ| / strength".into(),
                    record.samples.iter().zip(share).map(|(r, x)| (r.t, 100.0 * x)).collect(),
                )],
                levels: vec![("mean strength".into(), 100.0)],
            })
            .collect();
        svgs.push((
            "strength_share",
            lines_svg(&format!("Torque as a share of strength — {}", record.model_name), record, &panels)?,
        ));
    }
    crate::report::render::svg_and_png_files(svgs, PNG_SCALE, "plots")
}

/// The components (0, 1, 2 for x, y, z) worth drawing: those not zero at every joint and sample (a planar
/// figure's out-of-plane ones would lie hidden under each other on the zero line), all when every one is;
/// and a title note naming the left-out ones.
fn drawn_axes(model: &Model, series: &LoadSeries, moment: bool) -> (Vec<usize>, String) {
    let value = |l: &crate::dynamics::joint_loads::JointLoad, k: usize| if moment { l.moment[k] } else { l.force[k] };
    let peak = |k: usize| series.iter().flat_map(|s| s.iter().take(model.nv())).map(|l| value(l, k).abs()).fold(0.0, f64::max);
    let peaks = [peak(0), peak(1), peak(2)];
    let largest = peaks.iter().copied().fold(0.0, f64::max);
    let zero: Vec<usize> = (0..3).filter(|&k| peaks[k] <= 1e-9 * largest).collect();
    if zero.is_empty() || zero.len() == 3 {
        return (vec![0, 1, 2], String::new());
    }
    let names: Vec<String> = zero.iter().map(|&k| format!("{}{}", if moment { "M" } else { "F" }, ["x", "y", "z"][k])).collect();
    ((0..3).filter(|k| !zero.contains(k)).collect(), format!("; {} zero throughout", names.join(", ")))
}

/// A panel per joint with the `axes` components of its force (or moment).
fn load_panels(
    model: &Model,
    record: &PlanRecord,
    series: &LoadSeries,
    unit: &'static str,
    moment: bool,
    axes: &[usize],
) -> Vec<Panel> {
    (0..model.nv())
        .map(|i| {
            let component = |axis: usize| -> Vec<(f64, f64)> {
                record
                    .samples
                    .iter()
                    .zip(series)
                    .map(|(s, l)| (s.t, if moment { l[i].moment[axis] } else { l[i].force[axis] }))
                    .collect()
            };
            let prefix = if moment { "M" } else { "F" };
            Panel {
                caption: format!("{} ({})", model.joints[i + 1].name, if moment { "N·m" } else { "N" }),
                axis: unit,
                curves: axes.iter().map(|&k| (format!("{prefix}{}", ["x", "y", "z"][k]), component(k))).collect(),
                levels: vec![],
            }
        })
        .collect()
}

/// The panels on one canvas, titled, under one legend of every curve and level they draw.
fn lines_svg(title: &str, record: &PlanRecord, panels: &[Panel]) -> Result<String> {
    let entries = legend::unique(panels.iter().flat_map(|p| {
        let curves = p.curves.iter().zip(COLOURS.iter().cycle()).map(|((label, _), c)| Entry::line(label, *c, 2));
        curves.chain(p.levels.iter().enumerate().map(|(k, (label, _))| level_entry(label, k))).collect::<Vec<_>>()
    }));
    panels_svg(title, panels.len(), &entries, |k, area| {
        let panel = &panels[k];
        let x = time_range(record);
        let values = panel.curves.iter().flat_map(|(_, c)| c.iter().map(|p| p.1)).chain(panel.levels.iter().map(|l| l.1));
        let mut chart = time_chart(area, &panel.caption, x, padded_range(values), panel.axis)?;
        for ((_, points), colour) in panel.curves.iter().zip(COLOURS.iter().cycle()) {
            chart.draw_series(LineSeries::new(points.clone(), colour.stroke_width(2))).map_err(drawing_error)?;
        }
        for (k, (label, level)) in panel.levels.iter().enumerate() {
            let style = level_entry(label, k).style();
            chart.draw_series(LineSeries::new([(x.0, *level), (x.1, *level)], style)).map_err(drawing_error)?;
        }
        Ok(())
    })
}

/// The `k`-th reference level's line: the first pale and thin, later ones darker and thicker.
fn level_entry(label: &str, k: usize) -> Entry {
    Entry { opacity: if k == 0 { 0.6 } else { 1.0 }, ..Entry::line(label, LIMIT, 1 + k as u32) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::joint_loads::JointLoad;
    use crate::model::human::{build, HumanParams, Structure};
    use crate::spatial::Vec3;

    fn series(nv: usize, moment: Vec3) -> LoadSeries {
        vec![vec![JointLoad { force: Vec3::zeros(), moment }; nv]; 3]
    }

    #[test]
    fn components_zero_throughout_are_left_out_and_named() {
        let model = build(Structure::Sagittal, HumanParams::default()).unwrap();
        let nv = model.nv();
        let (axes, note) = drawn_axes(&model, &series(nv, Vec3::new(0.0, 12.0, 1e-12)), true);
        assert_eq!((axes, note.as_str()), (vec![1], "; Mx, Mz zero throughout"));
        assert_eq!(drawn_axes(&model, &series(nv, Vec3::new(0.1, 12.0, -3.0)), true), (vec![0, 1, 2], String::new()));
        // No load at all: every component drawn, nothing said.
        assert_eq!(drawn_axes(&model, &series(nv, Vec3::zeros()), false), (vec![0, 1, 2], String::new()));
    }
}
