//! Surrogate against the full model on held-out runs: vertical force,
//! horizontal force and cumulative work per unit length against depth, full
//! model solid (its post-fracture window mean; the raw sawtooth faint), the
//! surrogate dashed, one colour per run.

use plotters::coord::Shift;
use plotters::prelude::*;
use shearcut_sim::surrogate::{ComparisonPoint, RunComparison};

use super::CURVE_COLORS;
use super::legend::legend_line;

/// One panel: title, unit, full-model value, surrogate value, raw value.
struct Panel {
    title: &'static str,
    unit: &'static str,
    full: fn(&ComparisonPoint) -> f64,
    surrogate: fn(&ComparisonPoint) -> f64,
    raw: Option<fn(&ComparisonPoint) -> f64>,
}

const PANELS: [Panel; 3] = [
    Panel {
        title: "Vertical force F_n",
        unit: "N/m",
        full: |p| p.force_normal_full,
        surrogate: |p| p.force_normal_surrogate,
        raw: Some(|p| p.force_normal_raw),
    },
    Panel {
        title: "Horizontal force F_t",
        unit: "N/m",
        full: |p| p.force_tangential_full,
        surrogate: |p| p.force_tangential_surrogate,
        raw: None,
    },
    Panel {
        title: "Knife work",
        unit: "J/m",
        full: |p| p.work_full,
        surrogate: |p| p.work_surrogate,
        raw: None,
    },
];

/// At most this many points per curve (the runs have thousands of steps).
const MAX_POINTS: usize = 400;

fn thinned(points: &[ComparisonPoint]) -> impl Iterator<Item = &ComparisonPoint> + Clone {
    let every = points.len().div_ceil(MAX_POINTS).max(1);
    points
        .iter()
        .enumerate()
        .filter(move |(i, _)| i % every == 0 || *i + 1 == points.len())
        .map(|(_, p)| p)
}

/// Draws the three panels for the compared runs.
pub fn draw_surrogate_fit<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    runs: &[RunComparison],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let areas = root.split_evenly((3, 1));
    let x_max = runs
        .iter()
        .flat_map(|r| r.points.iter())
        .map(|p| p.depth * 1e3)
        .fold(1e-3, f64::max);
    for (i, (area, panel)) in areas.iter().zip(PANELS.iter()).enumerate() {
        let (lo, hi) = runs
            .iter()
            .flat_map(|r| r.points.iter())
            .flat_map(|p| [(panel.full)(p), (panel.surrogate)(p)])
            .fold((0.0f64, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
        let pad = 0.1 * (hi - lo).max(1e-9);
        let mut chart = ChartBuilder::on(area)
            .caption(panel.title, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..x_max, (lo - pad)..(hi + pad))?;
        chart
            .configure_mesh()
            .x_desc("knife depth (mm)")
            .y_desc(panel.unit)
            .draw()?;
        for (k, run) in runs.iter().enumerate() {
            let color = CURVE_COLORS[k % CURVE_COLORS.len()];
            if let Some(raw) = panel.raw {
                chart.draw_series(LineSeries::new(
                    thinned(&run.points).map(|p| (p.depth * 1e3, raw(p))),
                    color.mix(0.1).stroke_width(1),
                ))?;
            }
            let c = run.case;
            chart
                .draw_series(LineSeries::new(
                    thinned(&run.points).map(|p| (p.depth * 1e3, (panel.full)(p))),
                    color.stroke_width(2),
                ))?
                .label(format!(
                    "ξ = {}, H = {} mm, w/2 = {} mm: full model",
                    c.xi,
                    c.height * 1e3,
                    c.half_width * 1e3
                ))
                .legend(legend_line(color, 20));
            chart
                .draw_series(DashedLineSeries::new(
                    thinned(&run.points).map(|p| (p.depth * 1e3, (panel.surrogate)(p))),
                    6,
                    4,
                    color.stroke_width(2),
                ))?
                .label("surrogate (dashed)")
                .legend(legend_line(color, 8));
        }
        if i + 1 == PANELS.len() {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .label_font(("sans-serif", 12))
                .draw()?;
        }
    }
    Ok(())
}
