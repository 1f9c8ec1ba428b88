//! Seed 000 Fig. 7 style: vertical force, horizontal force and total work per
//! unit length against the knife's vertical displacement, one curve per cut.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::CURVE_COLORS;
use super::legend::{draw_legend, legend_line};
use crate::cut_record::CutSample;

/// One panel's quantity.
struct Panel {
    title: &'static str,
    unit: &'static str,
    value: fn(&CutSample) -> f64,
}

/// Per unit length of edge, as seed 000 Fig. 7 (uniform cuboids).
const PER_LENGTH: [Panel; 3] = [
    Panel {
        title: "Vertical force",
        unit: "N/m",
        value: |s| s.force_vertical_n_per_m,
    },
    Panel {
        title: "Horizontal force",
        unit: "N/m",
        value: |s| s.force_horizontal_n_per_m,
    },
    Panel {
        title: "Total work",
        unit: "J/m",
        value: |s| s.work_j_per_m,
    },
];

/// Totals on the knife, as seed 000 Figs. 8–11 (curved edges, natural shapes).
const TOTALS: [Panel; 3] = [
    Panel {
        title: "Vertical force",
        unit: "N",
        value: |s| s.force_vertical_n,
    },
    Panel {
        title: "Horizontal force",
        unit: "N",
        value: |s| s.force_horizontal_n,
    },
    Panel {
        title: "Total work",
        unit: "J",
        value: |s| s.work_j,
    },
];

/// Draws the three panels for `cuts` (each a slice of samples of one cut),
/// per unit length of edge or as totals on the knife.
pub fn draw_cut_curves<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    cuts: &[&[CutSample]],
    per_length: bool,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let panels_def = if per_length { &PER_LENGTH } else { &TOTALS };
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let panels = root.split_evenly((1, 3));
    let x_max = cuts
        .iter()
        .flat_map(|c| c.iter())
        .map(|s| s.displacement_m * 1e3)
        .fold(1e-3, f64::max);
    for (area, panel) in panels.iter().zip(panels_def.iter()) {
        let values = cuts.iter().flat_map(|c| c.iter()).map(panel.value);
        let (lo, hi) = values.fold((0.0f64, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
        let pad = 0.05 * (hi - lo).max(1e-9);
        let mut chart = ChartBuilder::on(area)
            .caption(panel.title, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..x_max, (lo - pad)..(hi + pad))?;
        chart
            .configure_mesh()
            .x_desc("knife displacement (mm)")
            .y_desc(panel.unit)
            .draw()?;
        for (k, cut) in cuts.iter().enumerate() {
            let color = CURVE_COLORS[k % CURVE_COLORS.len()];
            let (xi, z0) = cut.first().map_or((0.0, 0.0), |s| (s.xi, s.z0_m));
            chart
                .draw_series(LineSeries::new(
                    cut.iter()
                        .map(|s| (s.displacement_m * 1e3, (panel.value)(s))),
                    color.stroke_width(2),
                ))?
                // Three decimals at most: a controller's nominal ratio is not a round number.
                .label(format!(
                    "ξ = {}, z0 = {z0} m",
                    (xi * 1000.0).round() / 1000.0
                ))
                .legend(legend_line(color, 20));
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
    }
    Ok(())
}
