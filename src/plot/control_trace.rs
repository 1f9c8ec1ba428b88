//! What a controller commanded over time: slice-push ratio and speeds.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::legend::{draw_legend, legend_line};
use crate::closed_loop::ControlSample;

/// A speed curve: label, colour, value in mm/s.
type SpeedCurve = (&'static str, RGBColor, fn(&ControlSample) -> f64);

/// Draws two panels against time: the planned ξ, and the planned normal and
/// tangential speeds with the commanded (jerk-limited) ones.
pub fn draw_control_trace<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    trace: &[ControlSample],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let panels = root.split_evenly((1, 2));
    let t_max = trace.last().map_or(1e-3, |s| s.time_s.max(1e-3));
    // The magnitude: the tangential direction (sawing strokes back) shows
    // in the speeds panel.
    let xi_max = trace.iter().map(|s| s.xi_plan.abs()).fold(0.1, f64::max) * 1.1;
    let mut chart = ChartBuilder::on(&panels[0])
        .caption("slice-push ratio planned", ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..t_max, 0.0..xi_max)?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc("|ξ| = |v_t| / v_n")
        .draw()?;
    chart.draw_series(LineSeries::new(
        trace.iter().map(|s| (s.time_s, s.xi_plan.abs())),
        BLUE.stroke_width(2),
    ))?;
    let speeds: [SpeedCurve; 4] = [
        ("v_n planned", BLUE, |s| s.normal_speed_plan_m_s * 1e3),
        ("v_t planned", RED, |s| s.tangential_speed_plan_m_s * 1e3),
        ("v_n commanded", CYAN, |s| -s.command_vy_m_s * 1e3),
        ("v_t commanded", MAGENTA, |s| s.command_vz_m_s * 1e3),
    ];
    let (lo, hi) = trace
        .iter()
        .flat_map(|s| speeds.iter().map(move |(_, _, f)| f(s)))
        .fold((0.0f64, 1e-3f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let pad = 0.05 * (hi - lo);
    let mut chart = ChartBuilder::on(&panels[1])
        .caption("knife speeds", ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..t_max, (lo - pad)..(hi + pad))?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc("mm/s")
        .draw()?;
    for (label, color, f) in speeds {
        chart
            .draw_series(LineSeries::new(
                trace.iter().map(|s| (s.time_s, f(s))),
                color.stroke_width(2),
            ))?
            .label(label)
            .legend(legend_line(color, 20));
    }
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    Ok(())
}
