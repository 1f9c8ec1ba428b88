//! Full-model sweeps: cuboid cross sections cut at constant ξ, recorded for
//! the fit and for the accuracy report.

use std::sync::atomic::{AtomicUsize, Ordering};

use serde::{Deserialize, Serialize};

use crate::blade::BladeSection;
use crate::material::Material;
use crate::section::{CrossSection, SectionError, SectionGeometry, SectionSettings};

/// One full-model run: a rectangular section cut at constant ξ.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SweepCase {
    /// Slice-push ratio ξ ≥ 0.
    pub xi: f64,
    /// Section height, m.
    pub height: f64,
    /// Section half width across the cut, m.
    pub half_width: f64,
}

/// Slice-push ratios of the fit's sweeps.
pub const FIT_SLICE_PUSH_RATIOS: [f64; 8] = [0.0, 0.25, 0.5, 0.75, 1.0, 1.4, 1.8, 2.4];
/// Section sizes (height, half width) of the fit's sweeps, m.
pub const FIT_SECTION_SIZES: [(f64, f64); 6] = [
    (0.02, 0.01),
    (0.045, 0.01),
    (0.03, 0.015),
    (0.03, 0.03),
    (0.045, 0.02),
    (0.02, 0.025),
];
/// Slice-push ratios held out of the fit, for the accuracy report.
pub const HELD_OUT_SLICE_PUSH_RATIOS: [f64; 3] = [0.6, 1.2, 2.1];
/// Section sizes (height, half width) held out of the fit, m.
pub const HELD_OUT_SECTION_SIZES: [(f64, f64); 2] = [(0.025, 0.02), (0.04, 0.012)];

/// Every (ξ, size) pair of the given lists, size-major (so a thread reuses a
/// section's factorisation across ξ).
pub fn grid(xis: &[f64], sizes: &[(f64, f64)]) -> Vec<SweepCase> {
    sizes
        .iter()
        .flat_map(|&(height, half_width)| {
            xis.iter().map(move |&xi| SweepCase {
                xi,
                height,
                half_width,
            })
        })
        .collect()
}

/// How a sweep run is stepped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepSettings {
    /// Knife step before the first fracture as a fraction of R'_c/E (default
    /// 0.025: 1.9 µm for potato, 30 µm for whole eggplant). The onset depth is
    /// at least ≈ 0.5·R'_c/E over the fit's grid (ξ = 2.4), so it is resolved
    /// in ≥ 20 steps, and the middle of the step that fractured is used.
    pub pre_fracture_step_fraction: f64,
    /// Knife step after it, m (default 2e-5, a tenth of the default row spacing).
    pub step: f64,
    /// The run stops at this fraction of the section height (default 0.8).
    pub depth_fraction: f64,
    /// The cross-section model's settings (default: the plant's defaults).
    pub section: SectionSettings,
}

impl Default for SweepSettings {
    fn default() -> Self {
        Self {
            pre_fracture_step_fraction: 0.025,
            step: 2e-5,
            depth_fraction: 0.8,
            section: SectionSettings::default(),
        }
    }
}

impl SweepSettings {
    /// The knife step before fracture for `material`, m.
    pub fn pre_fracture_step(&self, material: &Material) -> f64 {
        self.pre_fracture_step_fraction * material.initial_fracture_toughness
            / material.youngs_modulus
    }
}

/// One step of a run, per unit length of edge.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SweepSample {
    /// Knife depth below the top surface, m.
    pub depth: f64,
    /// Whether the first fracture has happened.
    pub fractured: bool,
    /// Normal travel since the first fractured step, m (0 before).
    pub travel_since_fracture: f64,
    /// F_n, N/m.
    pub force_normal: f64,
    /// F_t, N/m.
    pub force_tangential: f64,
    /// Friction part of F_n, N/m.
    pub force_normal_friction: f64,
    /// Friction part of F_t, N/m.
    pub force_tangential_friction: f64,
    /// Cumulative knife work, J/m.
    pub work: f64,
    /// Cumulative fracture work (incl. unstable release), J/m.
    pub work_fracture: f64,
    /// Stored strain energy, J/m.
    pub strain_energy: f64,
    /// Cumulative friction work, J/m.
    pub work_friction: f64,
    /// Surface deflection next to the blade, m.
    pub deflection: f64,
    /// Crack depth below the top surface, m.
    pub crack_depth: f64,
}

/// The record of one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepRun {
    /// What was run.
    pub case: SweepCase,
    /// Depth of the first fractured step, m (None if the run never fractured).
    pub onset_depth: Option<f64>,
    /// Knife step just before the onset, m (its resolution).
    pub onset_resolution: f64,
    /// Every step.
    pub samples: Vec<SweepSample>,
}

/// Cuts `section` (reset first; built for `material`) at the case's ξ to the
/// case's depth.
pub fn run_case(
    section: &mut CrossSection,
    material: &Material,
    case: &SweepCase,
    settings: &SweepSettings,
) -> Result<SweepRun, SectionError> {
    let pre_step = settings.pre_fracture_step(material);
    section.reset();
    let end = settings.depth_fraction * section.height();
    let mut samples = Vec::new();
    let mut onset: Option<f64> = None;
    while section.state().knife_displacement < end - 1e-12 && !section.is_cut_through() {
        let dn = if onset.is_some() {
            settings.step
        } else {
            pre_step
        };
        let s = section.advance(dn, case.xi * dn)?;
        if s.fractured && onset.is_none() {
            onset = Some(s.knife_displacement);
        }
        let w = s.work;
        samples.push(SweepSample {
            depth: s.knife_displacement,
            fractured: s.fractured,
            travel_since_fracture: onset.map_or(0.0, |o| s.knife_displacement - o),
            force_normal: s.force_vertical,
            force_tangential: s.force_tangential,
            force_normal_friction: s.force_vertical_friction,
            force_tangential_friction: s.force_tangential_friction,
            work: w.knife,
            work_fracture: w.fracture + w.unstable,
            strain_energy: w.strain_energy,
            work_friction: w.friction,
            deflection: s.surface_deflection,
            crack_depth: s.crack_depth,
        });
    }
    Ok(SweepRun {
        case: *case,
        onset_depth: onset,
        onset_resolution: pre_step,
        samples,
    })
}

/// Runs every case on `threads` threads (std scoped threads; each builds the
/// sections of its cases, one per section size, in case order), calling
/// `progress` after each run. The result is in case order and does not depend
/// on `threads`: every run is independent and deterministic.
pub fn run_sweep(
    material: &Material,
    blade: &BladeSection,
    cases: &[SweepCase],
    settings: &SweepSettings,
    threads: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<SweepRun>, SectionError> {
    let threads = threads.clamp(1, cases.len().max(1));
    let next = AtomicUsize::new(0);
    // Work is handed out by size group so a thread reuses its section's
    // factorisation for every ξ of that size.
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for (i, c) in cases.iter().enumerate() {
        match groups.iter_mut().find(|g| {
            let f = &cases[g[0]];
            f.height == c.height && f.half_width == c.half_width
        }) {
            Some(g) => g.push(i),
            None => groups.push(vec![i]),
        }
    }
    let results: Vec<Result<Vec<(usize, SweepRun)>, SectionError>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut out = Vec::new();
                    loop {
                        let g = next.fetch_add(1, Ordering::SeqCst);
                        let Some(group) = groups.get(g) else { break };
                        let first = cases[group[0]];
                        let geometry =
                            SectionGeometry::rectangle(2.0 * first.half_width, first.height)?;
                        let mut section =
                            CrossSection::new(&geometry, material, blade, &settings.section)?;
                        for &i in group {
                            out.push((i, run_case(&mut section, material, &cases[i], settings)?));
                            progress();
                        }
                    }
                    Ok(out)
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("sweep thread panicked"))
            .collect()
    });
    let mut runs: Vec<Option<SweepRun>> = vec![None; cases.len()];
    for r in results {
        for (i, run) in r? {
            runs[i] = Some(run);
        }
    }
    Ok(runs.into_iter().flatten().collect())
}
