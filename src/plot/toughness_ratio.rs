//! Seed 000 Fig. 3: the toughness ratio r(ξ, ν) against Poisson's ratio.

use plotters::coord::Shift;
use plotters::prelude::*;
use shearcut_sim::mechanics::toughness_ratio;

use super::CURVE_COLORS;
use super::legend::{draw_legend, legend_line};

/// Slice-push ratios drawn in Fig. 3 (the seed's Fig. 7 values plus larger ones
/// that show the saturation).
pub const FIG3_SLICE_PUSH_RATIOS: [f64; 6] = [0.0, 0.33, 0.75, 1.0, 1.8, 3.0];

/// Number of ν samples on (0, 0.5).
pub const FIG3_SAMPLES: usize = 99;

/// The table behind Fig. 3: rows of ν followed by r(ξ, ν) for each ξ.
pub fn fig3_table() -> Vec<(f64, Vec<f64>)> {
    (1..=FIG3_SAMPLES)
        .map(|i| {
            let nu = 0.5 * i as f64 / (FIG3_SAMPLES + 1) as f64;
            (
                nu,
                FIG3_SLICE_PUSH_RATIOS
                    .iter()
                    .map(|&xi| toughness_ratio(xi, nu))
                    .collect(),
            )
        })
        .collect()
}

/// Draws Fig. 3 on `root`.
pub fn draw_fig3<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let table = fig3_table();
    // r exceeds 1 for large ξ at small ν (eq. 6: the tangential work term
    // outgrows the drop of the normal force), so the axis follows the data.
    let y_max = table
        .iter()
        .flat_map(|(_, r)| r.iter().copied())
        .fold(1.0, f64::max)
        * 1.05;
    let mut chart = ChartBuilder::on(root)
        .caption(
            "Toughness ratio r = R_c^s / R_c (seed 000 eq. 6, Fig. 3)",
            ("sans-serif", 22),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(55)
        .build_cartesian_2d(0.0..0.5, 0.0..y_max)?;
    chart
        .configure_mesh()
        .x_desc("Poisson's ratio ν")
        .y_desc("r(ξ, ν)")
        .draw()?;
    for (k, &xi) in FIG3_SLICE_PUSH_RATIOS.iter().enumerate() {
        let color = CURVE_COLORS[k % CURVE_COLORS.len()];
        chart
            .draw_series(LineSeries::new(
                table.iter().map(|(nu, r)| (*nu, r[k])),
                color.stroke_width(2),
            ))?
            .label(format!("ξ = {xi}"))
            .legend(legend_line(color, 20));
    }
    draw_legend(&mut chart, SeriesLabelPosition::LowerLeft)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fig3_shape() {
        let t = fig3_table();
        for (nu, r) in &t {
            // ξ = 0 is pressing: r = 1.
            assert_eq!(r[0], 1.0);
            assert!(r.iter().all(|&v| v > 0.0));
            // For food-like ν (Table I: 0.35–0.4; agar 0.48) slicing at the
            // seed's ratios (ξ ≤ 1.8) lowers the toughness.
            if *nu >= 0.35 {
                assert!(r[1..5].iter().all(|&v| v < 1.0), "nu {nu}: {r:?}");
            }
        }
        // For nearly compressible materials and steep slicing, eq. 6 gives
        // r > 1: 2/(1+√10)·(1 + 9/2.1) ≈ 2.5 at ξ = 3, ν = 0.05.
        let r = shearcut_sim::mechanics::toughness_ratio(3.0, 0.05);
        assert!(r > 2.4 && r < 2.6, "{r}");
        // For a fixed ν, r decreases from ξ = 0 to 0.33 to 0.75 (the saturation
        // of Fig. 3 comes later).
        let (_, r) = &t[79]; // ν = 0.4
        assert!(r[0] > r[1] && r[1] > r[2]);
        // As ν → 0.5, 1 − ν − 2ν² → 0 and slicing lowers toughness most.
        let first = &t[0].1;
        let last = &t[t.len() - 1].1;
        assert!(last[2] < first[2]);
    }
}
