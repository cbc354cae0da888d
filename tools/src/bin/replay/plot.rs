//! The replay tool's pictures (`--svg`; for `--rig`, [`write_rig_svg`]): orientation
//! error over time against the ground truth, one panel per angle (total, heading, inclination) with a line per filter, and
//! below them a lane per filter with a band wherever it reported
//! - rest: diagnostics.rest (the kinds with a rest detector: complementary, robust),
//! - mag unused: a magnetometer reading was given but ORIENT_FLAG_MAG_USED is clear
//!   (a disturbance was rejected, or the kind does not use it),
//! - accel unused: likewise for ORIENT_FLAG_ACCEL_USED (acceleration rejection),
//! - gap: ORIENT_FLAG_GAP.
//!
//! A smoothed run (`--offline`) reports none of these and has no lanes.
//!
//! No kind reports more than this today (robust's disturbance detector shows only as
//! "mag unused"), so there is no other band. Drawn with `plotters` (SVG backend only);
//! each line is the maximum over the samples of one pixel column, so no peak is lost.

use orient::{flags, Quat};
use orient_tools::eval::{error_angles, Recording};
use plotters::prelude::*;
use std::path::Path;

/// One filter's run.
pub struct Series<'a> {
    pub label: &'a str,
    /// ENU estimates, one per recording row.
    pub estimates: &'a [Quat],
    /// What the filter reported after each row, for its lanes: flags (0 where the sample
    /// was rejected) and rest. None for a smoothed run (`--offline`), which reports
    /// neither: it gets no lanes.
    pub reports: Option<Reports<'a>>,
}

/// A causal run's reports, one per recording row.
pub struct Reports<'a> {
    /// Flags after each row (0 where the sample was rejected).
    pub flags: &'a [u32],
    /// Rest reported after each row.
    pub rest: &'a [bool],
}

const WIDTH: u32 = 1200;
const PANEL: u32 = 230;
const ANGLES: [&str; 3] = ["total", "heading", "inclination"];
const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
];
const BANDS: [(&str, RGBColor); 4] = [
    ("rest", RGBColor(44, 160, 44)),
    ("mag unused", RGBColor(214, 39, 40)),
    ("accel unused", RGBColor(255, 127, 14)),
    ("gap", RGBColor(90, 90, 90)),
];

/// `(t, max error in degrees)` per pixel column, for one angle; rows without truth are
/// left out.
fn columns(t: &[f64], err: &[Option<f64>], t0: f64, t1: f64) -> Vec<(f64, f64)> {
    let mut best: Vec<Option<(f64, f64)>> = vec![None; WIDTH as usize];
    for (ti, e) in t.iter().zip(err) {
        let Some(e) = e else { continue };
        let col = (((ti - t0) / (t1 - t0)) * (WIDTH - 1) as f64) as usize;
        let slot = &mut best[col.min(WIDTH as usize - 1)];
        if slot.map_or(true, |(_, m)| *e > m) {
            *slot = Some((*ti, *e));
        }
    }
    best.into_iter().flatten().collect()
}

/// Runs of rows where `on` holds, as time spans.
fn spans(t: &[f64], on: impl Fn(usize) -> bool) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, ti) in t.iter().enumerate() {
        match (on(i), start) {
            (true, None) => start = Some(*ti),
            (false, Some(s)) => {
                out.push((s, *ti));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, t[t.len() - 1]));
    }
    out
}

pub fn write_svg(
    path: &Path,
    title: &str,
    rec: &Recording,
    series: &[Series],
    with_mag: bool,
) -> Result<(), Box<dyn std::error::Error>> {
    let lanes = series.iter().filter(|s| s.reports.is_some()).count() * BANDS.len();
    let lane_h = 14u32;
    let height = 40 + 3 * PANEL + 60 + lanes as u32 * lane_h;
    let root = SVGBackend::new(path, (WIDTH, height)).into_drawing_area();
    root.fill(&WHITE)?;
    let root =
        root.titled(&format!("orientation error against ground truth: {title}"), ("sans-serif", 18))?;
    let (panels, lanes_area) = root.split_vertically(3 * PANEL);
    let areas = panels.split_evenly((3, 1));
    let (t0, t1) = (rec.t[0], rec.t[rec.t.len() - 1].max(rec.t[0] + 1e-9));

    // Error angles in degrees per series: [angle][row].
    let errors: Vec<[Vec<Option<f64>>; 3]> = series
        .iter()
        .map(|s| {
            let mut e: [Vec<Option<f64>>; 3] = Default::default();
            for (q, g) in s.estimates.iter().zip(&rec.truth) {
                let a = (g.is_finite() && q.is_finite()).then(|| error_angles(*q, *g));
                e[0].push(a.map(|a| a.0.to_degrees()));
                e[1].push(a.map(|a| a.1.to_degrees()));
                e[2].push(a.map(|a| a.2.to_degrees()));
            }
            e
        })
        .collect();

    for (k, area) in areas.iter().enumerate() {
        let lines: Vec<Vec<(f64, f64)>> = errors.iter().map(|e| columns(&rec.t, &e[k], t0, t1)).collect();
        let top = lines.iter().flatten().map(|p| p.1).fold(1.0f64, f64::max) * 1.05;
        let mut chart = ChartBuilder::on(area)
            .margin(8)
            .x_label_area_size(if k == 2 { 30 } else { 5 })
            .y_label_area_size(120)
            .build_cartesian_2d(t0..t1, 0.0..top)?;
        let mut mesh = chart.configure_mesh();
        mesh.y_desc(format!("{} [deg]", ANGLES[k])).light_line_style(WHITE.mix(0.0));
        if k == 2 {
            mesh.x_desc("time [s]");
        }
        mesh.draw()?;
        for (s, (line, color)) in series.iter().zip(lines.into_iter().zip(COLORS.iter().cycle())) {
            chart
                .draw_series(LineSeries::new(line, color.stroke_width(1)))?
                .label(format!("{} {}", s.label, ANGLES[k]))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
        }
        chart.configure_series_labels().background_style(WHITE.mix(0.85)).border_style(BLACK).draw()?;
    }

    // The bands: one lane per filter that reports and condition.
    if lanes == 0 {
        root.present()?;
        return Ok(());
    }
    let mut chart = ChartBuilder::on(&lanes_area)
        .margin(8)
        .y_label_area_size(120)
        .x_label_area_size(20)
        .build_cartesian_2d(t0..t1, 0.0..lanes as f64)?;
    chart.configure_mesh().disable_mesh().disable_y_axis().x_labels(0).draw()?;
    let reporting = series.iter().filter_map(|s| s.reports.as_ref().map(|r| (s.label, r)));
    for (j, (label, r)) in reporting.enumerate() {
        for (b, (name, color)) in BANDS.iter().enumerate() {
            let lane = (lanes - 1 - (j * BANDS.len() + b)) as f64;
            let on = |i: usize| match b {
                0 => r.rest[i],
                1 => with_mag && r.flags[i] & flags::MAG_USED == 0,
                2 => r.flags[i] & flags::ACCEL_USED == 0,
                _ => r.flags[i] & flags::GAP != 0,
            };
            let bands = spans(&rec.t, on);
            chart.draw_series(
                bands
                    .iter()
                    .map(|(a, z)| Rectangle::new([(*a, lane + 0.15), (*z, lane + 0.85)], color.filled())),
            )?;
            chart.draw_series(std::iter::once(Text::new(
                format!("{label} {name}"),
                (t0, lane + 0.5),
                ("sans-serif", 11).into_font().color(&BLACK).pos(plotters::style::text_anchor::Pos::new(
                    plotters::style::text_anchor::HPos::Right,
                    plotters::style::text_anchor::VPos::Center,
                )),
            )))?;
        }
    }
    root.present()?;
    Ok(())
}

/// The rig picture (`--rig --svg`): each joint's error (degrees, the rig score's angle)
/// over time, one line per joint, the maximum over each pixel column; and below, the RMS
/// over all joints in windows of 10 s, where growth over time shows.
pub fn write_rig_svg(
    path: &Path,
    title: &str,
    t: &[f64],
    joints: &[&str],
    errors: &[Vec<f64>],
) -> Result<(), Box<dyn std::error::Error>> {
    const PALETTE: [RGBColor; 10] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(148, 103, 189),
        RGBColor(255, 127, 14),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
    ];
    let root = SVGBackend::new(path, (WIDTH, 40 + 2 * 320)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(&format!("joint error against truth: {title}"), ("sans-serif", 18))?;
    let (top, bottom) = root.split_vertically(340);
    let (t0, t1) = (t[0], t[t.len() - 1].max(t[0] + 1e-9));
    let lines: Vec<Vec<(f64, f64)>> = errors
        .iter()
        .map(|e| {
            let e: Vec<Option<f64>> = e.iter().map(|x| x.is_finite().then(|| x.to_degrees())).collect();
            columns(t, &e, t0, t1)
        })
        .collect();
    let ymax = lines.iter().flatten().map(|p| p.1).fold(1.0f64, f64::max) * 1.05;
    let mut chart = ChartBuilder::on(&top)
        .margin(8)
        .x_label_area_size(30)
        .y_label_area_size(60)
        .build_cartesian_2d(t0..t1, 0.0..ymax)?;
    chart
        .configure_mesh()
        .y_desc("joint error [deg]")
        .x_desc("time [s]")
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    for (k, line) in lines.into_iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        chart
            .draw_series(LineSeries::new(line, color.stroke_width(1)))?
            .label(joints[k].to_string())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
    }
    chart.configure_series_labels().background_style(WHITE.mix(0.85)).border_style(BLACK).draw()?;

    // RMS over all joints in 10-second windows.
    let mut windows: Vec<(f64, f64)> = Vec::new();
    let (mut start, mut sum, mut n) = (0usize, 0.0, 0usize);
    for i in 0..t.len() {
        for e in errors {
            if e[i].is_finite() {
                sum += e[i] * e[i];
                n += 1;
            }
        }
        if t[i] - t[start] >= 10.0 || i + 1 == t.len() {
            if n > 0 {
                windows.push((0.5 * (t[start] + t[i]), (sum / n as f64).sqrt().to_degrees()));
            }
            (start, sum, n) = (i + 1, 0.0, 0);
        }
    }
    let wmax = windows.iter().map(|p| p.1).fold(1.0f64, f64::max) * 1.05;
    let mut chart = ChartBuilder::on(&bottom)
        .margin(8)
        .x_label_area_size(30)
        .y_label_area_size(60)
        .build_cartesian_2d(t0..t1, 0.0..wmax)?;
    chart
        .configure_mesh()
        .y_desc("RMS over joints, 10 s [deg]")
        .x_desc("time [s]")
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    chart.draw_series(LineSeries::new(windows, BLACK.stroke_width(2)))?;
    root.present()?;
    Ok(())
}
