//! Plots of seed 001's finite-strain wire–slab model in the seed's form:
//! F_n and F_t against depth per kinematic angle (its Figs. 1c–d, 3b–c), the
//! forces at nucleation against the angle (Figs. 1e–f, 3d–e), and σ₁ over the
//! deformed slab around the wire (Fig. 2).

use plotters::coord::Shift;
use plotters::prelude::*;
use shearcut_sim::finite_strain::{IndentationRun, SlabState};

use super::CURVE_COLORS;
use super::legend::{draw_legend, legend_line};

/// A quantity of a state, as plotted.
type StateValue = fn(&SlabState) -> f64;

type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// F_n (left) and F_t (right) in N against the wire's depth in mm, one curve
/// per angle, each ending at nucleation.
pub fn draw_slab_forces<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    runs: &[IndentationRun],
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let panels = root.split_evenly((1, 2));
    let quantities: [(&str, StateValue); 2] = [
        ("Normal force F_n", |s| s.force_normal),
        ("Tangential force F_t", |s| s.force_tangential),
    ];
    let x_max = runs
        .iter()
        .flat_map(|r| r.states.iter())
        .map(|s| s.depth * 1e3)
        .fold(1e-3, f64::max);
    for (area, (name, value)) in panels.iter().zip(quantities) {
        let hi = runs
            .iter()
            .flat_map(|r| r.states.iter())
            .map(value)
            .fold(1e-9, f64::max);
        let mut chart = ChartBuilder::on(area)
            .caption(name, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..x_max, 0.0..1.05 * hi)?;
        chart
            .configure_mesh()
            .x_desc("wire depth d (mm)")
            .y_desc("N")
            .draw()?;
        for (k, run) in runs.iter().enumerate() {
            let color = CURVE_COLORS[k % CURVE_COLORS.len()];
            chart
                .draw_series(LineSeries::new(
                    run.states.iter().map(|s| (s.depth * 1e3, value(s))),
                    color.stroke_width(2),
                ))?
                .label(format!("θ = {:.0}°", run.angle.to_degrees()))
                .legend(legend_line(color, 20));
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
    }
    Ok(())
}

/// Forces at nucleation against the angle: F_n (left), F_t (right, with the
/// seed's F_t ≈ 2μRh as a dashed line at `tangential_scale` N).
pub fn draw_nucleation_angles<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    runs: &[IndentationRun],
    tangential_scale: f64,
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let panels = root.split_evenly((1, 2));
    let points = |f: fn(&shearcut_sim::finite_strain::Nucleation) -> f64| -> Vec<(f64, f64)> {
        runs.iter()
            .filter_map(|r| r.nucleation.as_ref().map(|n| (r.angle.to_degrees(), f(n))))
            .collect()
    };
    let series = [
        (
            "Normal force at nucleation F_n^m",
            points(|n| n.force_normal),
            None,
        ),
        (
            "Tangential force at nucleation F_t^m",
            points(|n| n.force_tangential),
            Some(tangential_scale),
        ),
    ];
    for (area, (name, pts, reference)) in panels.iter().zip(series) {
        let hi = pts
            .iter()
            .map(|p| p.1)
            .chain(reference)
            .fold(1e-9, f64::max);
        let mut chart = ChartBuilder::on(area)
            .caption(name, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(-2.0..85.0, 0.0..1.1 * hi)?;
        chart
            .configure_mesh()
            .x_desc("kinematic angle θ (degrees)")
            .y_desc("N")
            .draw()?;
        chart.draw_series(LineSeries::new(pts.clone(), BLACK.stroke_width(2)))?;
        chart.draw_series(pts.iter().map(|&p| Circle::new(p, 5, BLACK.filled())))?;
        if let Some(r) = reference {
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(-2.0, r), (85.0, r)],
                    6,
                    4,
                    CURVE_COLORS[1].stroke_width(2),
                ))?
                .label("seed 001: F_t ≈ 2μRh")
                .legend(legend_line(CURVE_COLORS[1], 20));
            draw_legend(&mut chart, SeriesLabelPosition::LowerRight)?;
        }
    }
    Ok(())
}

/// Blue (compression) – white – red (tension) for σ₁/μ in [−2, 2].
fn stress_colour(ratio: f64) -> RGBColor {
    let t = (ratio / 2.0).clamp(-1.0, 1.0);
    let fade = |c: f64| (255.0 * (1.0 - c.abs())) as u8;
    if t >= 0.0 {
        RGBColor(255, fade(t), fade(t))
    } else {
        RGBColor(fade(t), fade(t), 255)
    }
}

/// σ₁/μ over the deformed slab around the wire at nucleation (or the last
/// state), one panel per angle, the half model mirrored about the wire's
/// plane; the window spans ±`half_window` (m) across and follows the wire
/// down. `wire_radius`, `slab_depth` in m; `shear_modulus` in Pa.
pub fn draw_stress_maps<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    runs: &[IndentationRun],
    wire_radius: f64,
    slab_depth: f64,
    shear_modulus: f64,
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let cols = runs.len().clamp(1, 3);
    let rows = runs.len().div_ceil(cols).max(1);
    let panels = root.split_evenly((rows, cols));
    let r = wire_radius;
    for (area, run) in panels.iter().zip(runs) {
        let d = run.states.last().map_or(0.0, |s| s.depth);
        let half = 8.0 * r;
        // Same scale on both axes: the plotting area is the panel less the
        // label areas, margins and caption.
        let (w, h) = area.dim_in_pixel();
        let aspect = (h as f64 - 30.0 - 16.0 - 25.0).max(1.0) / (w as f64 - 45.0 - 16.0).max(1.0);
        let y_span = 2.0 * half * aspect;
        let y_hi = slab_depth + 2.0 * r;
        let y_lo = y_hi - y_span.max(d + 4.0 * r);
        let scale = 1e3;
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!(
                    "θ = {:.0}°, d = {:.2} mm (σ₁/μ from −2 blue to 2 red)",
                    run.angle.to_degrees(),
                    d * 1e3
                ),
                ("sans-serif", 15),
            )
            .margin(8)
            .x_label_area_size(30)
            .y_label_area_size(45)
            .build_cartesian_2d(-half * scale..half * scale, y_lo * scale..y_hi * scale)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("x (mm)")
            .y_desc("y (mm)")
            .draw()?;
        let f = &run.field;
        for (e, el) in f.elements.iter().enumerate() {
            let pts: Vec<[f64; 2]> = el.iter().map(|&n| f.nodes[n]).collect();
            let inside = pts
                .iter()
                .any(|p| p[0] <= half && p[1] >= y_lo && p[1] <= y_hi);
            if !inside {
                continue;
            }
            let colour = stress_colour(f.largest_principal[e] / shear_modulus);
            for side in [1.0, -1.0] {
                let poly: Vec<(f64, f64)> = pts
                    .iter()
                    .map(|p| (side * p[0] * scale, p[1] * scale))
                    .collect();
                chart.draw_series(std::iter::once(Polygon::new(poly, colour.filled())))?;
            }
        }
        let cy = slab_depth + r - d;
        let circle: Vec<(f64, f64)> = (0..=64)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 64.0;
                (r * a.cos() * scale, (cy + r * a.sin()) * scale)
            })
            .collect();
        chart.draw_series(std::iter::once(Polygon::new(
            circle.clone(),
            RGBColor(120, 120, 120).filled(),
        )))?;
        chart.draw_series(std::iter::once(PathElement::new(circle, BLACK)))?;
    }
    Ok(())
}
