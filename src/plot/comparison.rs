//! Bar charts comparing controllers on one scenario.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::commands::compare::ComparisonRow;

/// One panel: title, unit, value of a row.
type Metric = (&'static str, fn(&ComparisonRow) -> f64);

const METRICS: [Metric; 5] = [
    ("work (J)", |r| r.work_j),
    ("peak vertical force (N)", |r| r.peak_force_vertical_n),
    ("max deformation (mm)", |r| r.max_deformation_mm),
    ("time (s)", |r| r.duration_s),
    ("blade used (mm)", |r| r.blade_travel_mm),
];

const BAR_COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];

/// Draws one bar panel per metric, one bar per controller.
pub fn draw_comparison<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    rows: &[ComparisonRow],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let panels = root.split_evenly((1, METRICS.len()));
    let n = rows.len().max(1);
    for (area, (name, value)) in panels.iter().zip(METRICS.iter()) {
        let top = rows.iter().map(value).fold(1e-12, f64::max) * 1.2;
        let mut chart = ChartBuilder::on(area)
            .caption(*name, ("sans-serif", 16))
            .margin(8)
            .x_label_area_size(10)
            .y_label_area_size(50)
            .build_cartesian_2d(0.0..n as f64, 0.0..top)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .disable_x_axis()
            .draw()?;
        for (i, r) in rows.iter().enumerate() {
            let color = BAR_COLORS[i % BAR_COLORS.len()];
            let x = i as f64;
            chart.draw_series(std::iter::once(Rectangle::new(
                [(x + 0.1, 0.0), (x + 0.9, value(r))],
                color.filled(),
            )))?;
            chart.draw_series(std::iter::once(Text::new(
                r.controller.clone(),
                (x + 0.12, value(r) + 0.03 * top),
                ("sans-serif", 12).into_font(),
            )))?;
        }
    }
    Ok(())
}
