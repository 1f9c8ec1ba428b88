//! Work against maximum deformation for one scenario's settings (their
//! means over the runs), the Pareto front over all four objectives marked,
//! and the front's two-objective staircase drawn through it.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::plot::CURVE_COLORS;
use crate::plot::legend::draw_legend;
use crate::tune::pareto_front::front;
use crate::tune::robust_stats::SettingStats;

/// Draws the settings of one scenario (`group`, with `on_front` from the
/// four-objective front); settings that did not complete every run are
/// left out.
pub fn draw_front<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    group: &[&SettingStats],
    on_front: &[bool],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let points: Vec<(f64, f64, bool, &SettingStats)> = group
        .iter()
        .zip(on_front)
        .filter(|(s, _)| s.all_completed())
        .map(|(s, &f)| (s.mean[0], s.mean[1] * 1e3, f, *s))
        .collect();
    let span = |v: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
        if lo.is_finite() {
            let pad = 0.08 * (hi - lo).max(1e-3 * hi.abs().max(1e-9));
            (lo - pad)..(hi + pad)
        } else {
            0.0..1.0
        }
    };
    let xr = span(&mut points.iter().map(|p| p.0));
    let yr = span(&mut points.iter().map(|p| p.1));
    // Room above the highest point for the legend (three lines, about a
    // seventh of the chart's height), so that it covers no setting.
    let yr = yr.start..yr.end + 0.3 * (yr.end - yr.start);
    let mut chart = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(65)
        .build_cartesian_2d(xr, yr)?;
    chart
        .configure_mesh()
        .x_desc("work (J), mean over the runs")
        .y_desc("max deformation (mm), mean")
        .draw()?;
    // The two-objective front: the staircase of the points no other beats
    // on both work and deformation.
    let xy: Vec<[f64; 2]> = points.iter().map(|p| [p.0, p.1]).collect();
    let refs: Vec<&[f64]> = xy.iter().map(|p| p.as_slice()).collect();
    let mut stair: Vec<(f64, f64)> = points
        .iter()
        .zip(front(&refs))
        .filter(|(_, f)| *f)
        .map(|(p, _)| (p.0, p.1))
        .collect();
    stair.sort_by(|a, b| a.0.total_cmp(&b.0));
    let red = CURVE_COLORS[1];
    chart
        .draw_series(LineSeries::new(stair, red.stroke_width(1)))?
        .label("front of work and deformation")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], red));
    chart
        .draw_series(
            points
                .iter()
                .filter(|p| !p.2)
                .map(|p| Circle::new((p.0, p.1), 4, CURVE_COLORS[2].mix(0.6).filled())),
        )?
        .label("dominated setting")
        .legend(|(x, y)| Circle::new((x + 10, y), 4, CURVE_COLORS[2].filled()));
    chart
        .draw_series(
            points
                .iter()
                .filter(|p| p.2)
                .map(|p| Circle::new((p.0, p.1), 6, red.filled())),
        )?
        .label("on the front (work, deformation, peak force, time)")
        .legend(move |(x, y)| Circle::new((x + 10, y), 6, red.filled()));
    chart.draw_series(points.iter().map(|p| {
        Text::new(
            format!("{} {}", p.3.setting, p.3.controller),
            (p.0, p.1),
            ("sans-serif", 12).into_font(),
        )
    }))?;
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    Ok(())
}
