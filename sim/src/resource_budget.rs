//! What a run may cost before it starts: section mesh sizes, series
//! lengths and file sizes, each against a documented budget
//! (`docs/reliability.md`).
//!
//! Settings inside their physical ranges can still multiply into a run
//! that would not fit in memory or finish (a fine row spacing on a tall
//! object, a slow knife at a high loop rate). The estimates here are
//! upper bounds computed from the settings alone, so `shearcut check` and
//! every loader refuse such a run with one line before any work is done.

use crate::invalid_setting::InvalidSetting;
use crate::physical_range::number_text;
use crate::section::SectionSettings;

/// Most nodes of one section mesh.
pub const SECTION_NODES_BUDGET: f64 = 200_000.0;

/// Most nodes of all the sections a plant holds at once (one per segment).
pub const PLANT_NODES_BUDGET: f64 = 2_000_000.0;

/// Most rows of a run's time series (model steps or loop ticks, all cuts
/// together). A row of `timeseries.csv` is about 0.4 kB, so the budget
/// bounds a result file to about 400 MB.
pub const SERIES_ROWS_BUDGET: f64 = 1_000_000.0;

/// Largest scenario or surrogate file read, bytes (the shipped ones are
/// below 20 kB).
pub const CONFIG_FILE_BYTES: u64 = 1 << 20;

/// Largest mesh file read, bytes (a binary STL of about 1.3 million triangles).
pub const MESH_FILE_BYTES: u64 = 64 << 20;

/// Most triangles of an object mesh.
pub const MESH_TRIANGLES_BUDGET: usize = 500_000;

/// Upper bound on the nodes of a section mesh (see `SectionMesh`): half
/// width `half_width` and height `height` of the section, m, an edge flat
/// of `edge_width`, m. Columns: `strip_elements` across the half flat, then
/// widths growing by `grading_ratio` up to `max_element_width`, then
/// uniform; rows: the height over `row_spacing` (at least 4).
pub fn section_nodes(
    half_width: f64,
    height: f64,
    edge_width: f64,
    settings: &SectionSettings,
) -> f64 {
    let strip = settings.strip_elements as f64;
    let half_flat = 0.5 * edge_width;
    let w0 = half_flat / strip;
    let rest = (half_width - half_flat).max(0.0);
    let r = settings.grading_ratio;
    let w_max = settings.max_element_width.max(w0);
    // Elements while the widths grow: w0·r^i for i = 1..=k reaches w_max at k.
    let (graded, graded_length) = if r > 1.0 {
        let k = ((w_max / w0).ln() / r.ln()).ceil().max(0.0);
        let length = w0 * r * (r.powf(k) - 1.0) / (r - 1.0);
        if length >= rest {
            let k_rest = (rest * (r - 1.0) / (w0 * r) + 1.0).ln() / r.ln();
            (k_rest.ceil(), rest)
        } else {
            (k, length)
        }
    } else {
        (0.0, 0.0)
    };
    // With a ratio of 1 the widths never grow: every element is w0 wide.
    let uniform_width = if r > 1.0 { w_max } else { w0 };
    let uniform = ((rest - graded_length).max(0.0) / uniform_width).ceil();
    let columns = strip + graded + uniform + 2.0;
    let rows = (height / settings.row_spacing).round().max(4.0);
    columns * (rows + 1.0)
}

/// The estimated cost of a run, each figure an upper bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ResourceEstimate {
    /// Nodes of the largest section mesh.
    pub section_nodes: f64,
    /// Nodes of all sections a plant holds at once (0 when no plant runs).
    pub plant_nodes: f64,
    /// Rows of the longest time series any command writes for the scenario.
    pub series_rows: f64,
}

impl ResourceEstimate {
    /// `Ok` when every figure is within its budget, else an error naming
    /// the figure (`resources.*`), its estimate and the budget, and what
    /// setting to change.
    pub fn check(&self) -> Result<(), InvalidSetting> {
        for (key, value, budget, unit, hint) in [
            (
                "resources.section_mesh",
                self.section_nodes,
                SECTION_NODES_BUDGET,
                "nodes",
                "coarsen section.row_spacing or section.max_element_width, or raise section.grading_ratio",
            ),
            (
                "resources.plant_meshes",
                self.plant_nodes,
                PLANT_NODES_BUDGET,
                "nodes",
                "use fewer plant.segments or a coarser section mesh",
            ),
            (
                "resources.series",
                self.series_rows,
                SERIES_ROWS_BUDGET,
                "rows",
                "use a larger motion.step, a faster knife, a lower loop.rate_hz or a shorter controller.max_duration",
            ),
        ] {
            // NaN (an estimate from unusable settings) is over budget too.
            if value.is_nan() || value > budget {
                return Err(InvalidSetting::new(
                    key,
                    format!("{} {unit}", number_text(value.round())),
                    format!(
                        "must be at most {} {unit} (docs/reliability.md): {hint}",
                        number_text(budget)
                    ),
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn over_budget_names_the_figure_and_the_setting() {
        let e = ResourceEstimate {
            section_nodes: 1e9,
            plant_nodes: 0.0,
            series_rows: 0.0,
        }
        .check()
        .unwrap_err()
        .to_string();
        assert!(
            e.starts_with("`resources.section_mesh` = 1e9 nodes: must be at most 200000 nodes"),
            "{e}"
        );
        assert!(e.contains("row_spacing"), "{e}");
    }
}
