//! Each setting's effect on one scenario: one panel per varied column, its
//! values along x (in the order they appear), and each objective's mean at
//! that value relative to the objective's mean over the panel's values.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::plot::CURVE_COLORS;
use crate::tune::objective::Objective;
use crate::tune::setting_effect::EffectLevel;

/// Most panels drawn (the table has them all).
pub const MAX_PANELS: usize = 12;

/// The (column, family) panels of `levels`, in order, at most
/// [`MAX_PANELS`].
pub fn panel_columns(levels: &[EffectLevel]) -> Vec<(&str, &str)> {
    let mut panels: Vec<(&str, &str)> = Vec::new();
    for l in levels {
        let key = (l.column.as_str(), l.family.as_str());
        if !panels.contains(&key) && panels.len() < MAX_PANELS {
            panels.push(key);
        }
    }
    panels
}

/// Draws the effects `levels` of one scenario.
pub fn draw_effects<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    levels: &[EffectLevel],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 20))?;
    let columns = panel_columns(levels);
    let across = columns.len().clamp(1, 3);
    let down = columns.len().div_ceil(across).max(1);
    let panels = root.split_evenly((down, across));
    for (area, (column, family)) in panels.iter().zip(&columns) {
        let of: Vec<&EffectLevel> = levels
            .iter()
            .filter(|l| l.column == *column && l.family == *family)
            .collect();
        let caption = if family.is_empty() {
            column.to_string()
        } else {
            format!("{column} ({family} runs)")
        };
        let relative: Vec<[f64; 4]> = {
            let n = of.len() as f64;
            let mean: [f64; 4] =
                std::array::from_fn(|i| of.iter().map(|l| l.mean[i]).sum::<f64>() / n);
            of.iter()
                .map(|l| std::array::from_fn(|i| l.mean[i] / mean[i].max(f64::MIN_POSITIVE)))
                .collect()
        };
        let (lo, hi) = relative
            .iter()
            .flatten()
            .filter(|x| x.is_finite())
            .fold((1.0f64, 1.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        let pad = 0.1 * (hi - lo).max(0.01);
        // Room above the highest point for the legend (four lines, about a
        // quarter of the panel's height), so that it covers no line.
        let (bottom, top) = (lo - pad, hi + pad);
        let top = top + 0.35 * (top - bottom);
        let short = column.rsplit('.').next().unwrap_or(column);
        let mut chart = ChartBuilder::on(area)
            .caption(caption, ("sans-serif", 14))
            .margin(8)
            .x_label_area_size(35)
            .y_label_area_size(50)
            .build_cartesian_2d(-0.5..(of.len() as f64 - 0.5), bottom..top)?;
        let labels: Vec<String> = of.iter().map(|l| l.value.clone()).collect();
        chart
            .configure_mesh()
            .x_labels(of.len().max(2))
            .x_label_formatter(&|x| {
                let i = x.round();
                if (x - i).abs() < 1e-6 && i >= 0.0 {
                    labels.get(i as usize).cloned().unwrap_or_default()
                } else {
                    String::new()
                }
            })
            .x_desc(short)
            .y_desc("relative to the mean")
            .draw()?;
        for (k, o) in Objective::ALL.iter().enumerate() {
            let color = CURVE_COLORS[k % CURVE_COLORS.len()];
            let line: Vec<(f64, f64)> = relative
                .iter()
                .enumerate()
                .map(|(i, r)| (i as f64, r[k]))
                .collect();
            chart
                .draw_series(LineSeries::new(line.clone(), color.stroke_width(2)))?
                .label(o.label().0)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
            chart.draw_series(line.into_iter().map(|p| Circle::new(p, 3, color.filled())))?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 11))
            .draw()?;
    }
    Ok(())
}
