//! The sweep's summary plots: for each numeric parameter, the effort and every joint's peak |τ| against
//! it, one point per plan (converged filled, not converged hollow; failed plans have no figures).

use super::row::{Row, Status};
use super::Sweep;
use crate::plan_dir::Result;
use crate::report::plots::{draw_legend, drawing_error, padded_range};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

const EFFORT: RGBColor = RGBColor(31, 90, 170);

/// Writes `effort_vs_PARAMETER.svg` for every numeric parameter into `out`; returns the files written.
pub fn write(sweep: &Sweep, rows: &[Row], out: &Path) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for (p, parameter) in sweep.file.parameter.iter().enumerate() {
        let x: Vec<Option<f64>> = rows.iter().map(|r| r.values[p].parse::<f64>().ok()).collect();
        if x.iter().any(Option::is_none) {
            continue; // a text parameter (a gravity preset): the table has it
        }
        let x: Vec<f64> = x.into_iter().flatten().collect();
        let svg = plot(&parameter.path, &x, rows, &sweep.joint_names)?;
        let name = format!("effort_vs_{}.svg", parameter.path.replace(['.', '[', ']'], "_"));
        let path = out.join(name);
        crate::plan_dir::write_file(&path, svg.as_bytes())?;
        files.push(path);
    }
    Ok(files)
}

fn plot(parameter: &str, x: &[f64], rows: &[Row], joints: &[String]) -> Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1100, 420)).into_drawing_area();
        root.fill(&WHITE).map_err(drawing_error)?;
        let body =
            root.titled(&format!("Sweep over {parameter} — {} plans", rows.len()), ("sans-serif", 20)).map_err(drawing_error)?;
        let (left, right) = body.split_horizontally(550);
        let effort: Vec<f64> = rows.iter().map(|r| r.effort).collect();
        panel(&left, parameter, x, rows, &[("effort ½∫τᵀWτ dt", EFFORT, &effort)], "effort (N²·m²·s)")?;
        let peaks: Vec<Vec<f64>> = (0..joints.len()).map(|j| rows.iter().map(|r| r.peak_torque[j]).collect()).collect();
        let series: Vec<(&str, RGBColor, &[f64])> = joints
            .iter()
            .enumerate()
            .map(|(j, name)| {
                let c = Palette99::pick(j).to_rgba();
                (name.as_str(), RGBColor(c.0, c.1, c.2), peaks[j].as_slice())
            })
            .collect();
        panel(&right, parameter, x, rows, &series, "peak |τ| (N·m or N)")?;
        root.present().map_err(drawing_error)?;
    }
    Ok(svg)
}

type Series<'a> = (&'a str, RGBColor, &'a [f64]);

fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    parameter: &str,
    x: &[f64],
    rows: &[Row],
    series: &[Series],
    unit: &str,
) -> Result<()> {
    let xr = padded_range(x.iter().copied());
    let yr = padded_range(series.iter().flat_map(|s| s.2.iter().copied()));
    let mut chart = ChartBuilder::on(area)
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(drawing_error)?;
    chart.configure_mesh().x_desc(parameter).y_desc(unit).light_line_style(WHITE.mix(0.0)).draw().map_err(drawing_error)?;
    for (name, colour, y) in series {
        let points = x.iter().zip(y.iter()).zip(rows).filter(|((_, y), _)| y.is_finite());
        let drawn = chart
            .draw_series(points.map(|((x, y), r)| {
                let filled = r.status == Status::Converged;
                Circle::new((*x, *y), 3, if filled { colour.filled() } else { colour.stroke_width(1) })
            }))
            .map_err(drawing_error)?;
        let c = *colour;
        drawn.label(*name).legend(move |(x, y)| Circle::new((x + 8, y), 3, c.filled()));
    }
    Ok(draw_legend(&mut chart, SeriesLabelPosition::UpperLeft, 11)?)
}
