//! `shearcut simulate`: an open-loop cut with a prescribed straight motion.
//!
//! For every slice-push ratio ξ of the scenario the knife moves at the
//! scenario's speed along the direction α = atan ξ from −y, and one cross
//! section of the object (seed 000 §V.A: a uniform cuboid is one section ×
//! its length) is cut by the FEM model until the crack reaches the target
//! depth. The section's factorisation is built once and reused for every ξ.

use std::path::Path;

use shearcut_sim::section::{CrossSection, SectionGeometry, SectionStep};
use shearcut_sim::{EdgeShape, InvalidSetting, Knife, ObjectShape};

use crate::cut_record::{CutSample, CutSummary, write_json, write_timeseries};
use crate::error::{ConfigError, RunError};
use crate::plot::cut_curves::draw_cut_curves;
use crate::render_plot;
use crate::run_dir;
use crate::scenario::Scenario;

/// Everything a simulation produced.
#[derive(Debug, Clone)]
pub struct SimulationOutput {
    /// All samples, cut after cut.
    pub samples: Vec<CutSample>,
    /// One summary per cut, in the scenario's ξ order.
    pub summaries: Vec<CutSummary>,
}

/// The summary file's content.
#[derive(Debug, serde::Serialize)]
struct SummaryFile<'a> {
    scenario: &'a str,
    /// Length of edge in contact, m (the cuboid's length along the edge).
    contact_length_m: f64,
    target_depth_m: f64,
    cuts: &'a [CutSummary],
}

/// Runs the cuts of `scenario` (no files written).
pub fn simulate(scenario: &Scenario) -> Result<SimulationOutput, RunError> {
    let invalid = |setting: InvalidSetting| {
        RunError::Config(ConfigError::Invalid {
            path: scenario.name.clone(),
            setting,
        })
    };
    let cuboid = match &scenario.object {
        ObjectShape::Cuboid(c) => *c,
        _ => {
            return Err(invalid(InvalidSetting::new(
                "object.kind",
                "not a cuboid",
                "a single-section cut needs a cuboid (natural shapes need the multi-section plant)",
            )));
        }
    };
    let knife = Knife::new(&scenario.knife).map_err(|e| invalid(e.prefixed("knife")))?;
    if !matches!(
        scenario.knife.edge,
        EdgeShape::Straight { .. } | EdgeShape::Wire { .. }
    ) {
        return Err(invalid(InvalidSetting::new(
            "knife.edge.kind",
            "curved",
            "a single-section cut needs a straight or wire edge (curved edges need the multi-section plant)",
        )));
    }
    let depth = scenario.motion.depth.unwrap_or(0.8 * cuboid.height);
    let edge_length = knife.edge().length();
    for (i, &xi) in scenario.motion.slice_push_ratios.iter().enumerate() {
        let travel = xi * depth;
        let needed = scenario.motion.z0 + cuboid.length + travel;
        if needed > edge_length {
            return Err(invalid(InvalidSetting::new(
                format!("motion.slice_push_ratios[{i}]"),
                xi,
                format!(
                    "the blade would travel {travel:.4} m along the edge; z0 + piece length + travel = {needed:.4} m exceeds the edge's {edge_length:.4} m"
                ),
            )));
        }
    }
    let geometry = SectionGeometry::rectangle(cuboid.width, cuboid.height)
        .map_err(|e| invalid(InvalidSetting::new("object", "cuboid", e.to_string())))?;
    let mut section = CrossSection::new(
        &geometry,
        &scenario.material,
        knife.blade(),
        &scenario.section,
    )
    .map_err(|e| invalid(InvalidSetting::new("section", "model", e.to_string())))?;
    let step = scenario.motion.step;
    let speed = scenario.motion.speed;
    let length = cuboid.length;
    let mut samples = Vec::new();
    let mut summaries = Vec::new();
    for &xi in &scenario.motion.slice_push_ratios {
        section.reset();
        // Vertical speed: |v| cos α with tan α = ξ.
        let v_n = speed / (1.0 + xi * xi).sqrt();
        let first = samples.len();
        // Safety bound: the edge cannot go below the board.
        while section.state().crack_depth < depth - 1e-12
            && section.state().knife_displacement < cuboid.height - step
            && !section.is_cut_through()
        {
            let s = section
                .advance(step, xi * step)
                .map_err(|e| invalid(InvalidSetting::new("section", "step", e.to_string())))?;
            samples.push(sample(xi, &s, v_n, length));
        }
        summaries.push(CutSummary::from_samples(&samples[first..], depth));
    }
    Ok(SimulationOutput { samples, summaries })
}

fn sample(xi: f64, s: &SectionStep, v_n: f64, length: f64) -> CutSample {
    let w = &s.work;
    CutSample {
        xi,
        time_s: s.knife_displacement / v_n,
        displacement_m: s.knife_displacement,
        tangential_displacement_m: xi * s.knife_displacement,
        force_vertical_n_per_m: s.force_vertical,
        force_horizontal_n_per_m: s.force_tangential,
        force_vertical_n: s.force_vertical * length,
        force_horizontal_n: s.force_tangential * length,
        work_j_per_m: w.knife,
        work_j: w.knife * length,
        fracture_energy_j_per_m: w.fracture,
        strain_energy_j_per_m: w.strain_energy,
        friction_work_j_per_m: w.friction,
        crack_depth_m: s.crack_depth,
        deformation_m: s.surface_deflection,
        fractured: s.fractured,
    }
}

/// Runs the subcommand: simulate, write the results into `out` (or a fresh
/// `runs/` directory) and print a summary.
pub fn run(scenario: &str, out: Option<&Path>) -> Result<(), RunError> {
    let s = Scenario::load(scenario)?;
    run_scenario(&s, out)
}

/// Simulates a loaded scenario and writes its results.
pub fn run_scenario(s: &Scenario, out: Option<&Path>) -> Result<(), RunError> {
    let output = simulate(s)?;
    let dir = run_dir::create(&s.name, out)?;
    write_timeseries(&dir.join("timeseries.csv"), &output.samples)?;
    let (contact_length_m, height) = match &s.object {
        ObjectShape::Cuboid(c) => (c.length, c.height),
        _ => (0.0, 0.0),
    };
    let target_depth_m = s.motion.depth.unwrap_or(0.8 * height);
    write_json(
        &dir.join("summary.json"),
        &SummaryFile {
            scenario: &s.name,
            contact_length_m,
            target_depth_m,
            cuts: &output.summaries,
        },
    )?;
    let resolved = crate::commands::check::resolved_toml(s);
    std::fs::write(dir.join("scenario.toml"), resolved)
        .map_err(|e| RunError::write(dir.join("scenario.toml"), e))?;
    let cuts: Vec<&[CutSample]> = output
        .samples
        .chunk_by(|a, b| a.xi.to_bits() == b.xi.to_bits())
        .collect();
    let title = format!(
        "{}: force and work per unit length (seed 000 Fig. 7 style)",
        s.name
    );
    for name in ["forces_work.svg", "forces_work.png"] {
        render_plot!(&dir.join(name), (1500, 500), |root| draw_cut_curves(
            root, &title, &cuts
        ))?;
    }
    print_summary(s, &output.summaries);
    println!(
        "results: {}/ (timeseries.csv, summary.json, scenario.toml, forces_work.svg/.png)",
        dir.display()
    );
    Ok(())
}

fn print_summary(s: &Scenario, summaries: &[CutSummary]) {
    println!("{}: {}", s.name, s.description);
    println!(
        "   xi   work (J)  peak Fv (N)  peak Fh (N)  first fracture (mm)  max deform. (mm)  depth (mm)  completed"
    );
    for c in summaries {
        println!(
            "{:>5.2}  {:>9.4}  {:>11.3}  {:>11.3}  {:>19}  {:>16.3}  {:>10.2}  {}",
            c.xi,
            c.work_j,
            c.peak_force_vertical_n,
            c.peak_force_horizontal_n,
            c.first_fracture_displacement_m
                .map_or("-".to_string(), |d| format!("{:.3}", d * 1e3)),
            c.max_deformation_m * 1e3,
            c.cut_depth_m * 1e3,
            c.completed
        );
    }
}
