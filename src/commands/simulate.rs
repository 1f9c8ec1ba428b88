//! `shearcut simulate`: open-loop cuts with a prescribed straight motion.
//!
//! For every (ξ, z₀) of the scenario the knife moves at the scenario's speed
//! along the direction α = atan ξ from −y (towards the tip when slicing).
//!
//! - A cuboid cut by a straight (or wire) edge is one uniform cross section ×
//!   the piece's length (seed 000 §V.A): the section's factorisation is built
//!   once and reused for every ξ.
//! - Anything else (curved edges, natural shapes, meshes) runs the
//!   multi-section plant at the loop rate (seed 000 §IV, §V.B–C), with a short
//!   linear velocity ramp so that the arm's jerk limit is respected.

use nalgebra::Vector3;
use shearcut_plant::{Plant, PlantError, PlantSpec, SegmentLoad, wrench_at};
use shearcut_sim::arm::{ArmStatus, KnifeCommand};
use shearcut_sim::geometry::TriangleMesh;
use shearcut_sim::section::{CrossSection, SectionGeometry, SectionStep};
use shearcut_sim::{Cuboid, EdgeShape, InvalidSetting, Knife, ObjectShape};

use crate::angle_stream::AngleStream;
use crate::cli::print;
use crate::cut_record::{CutSample, CutSummary};
use crate::cut_stream::{CutRecorder, CutStream, NoCutRecorder};
use crate::error::{ConfigError, RunError};
use crate::plot::cut_curves::draw_cut_curves;
use crate::progress::run_bar;
use crate::render_plot;
use crate::result_file::write_json;
use crate::run_dir::{self, Destination};
use crate::scenario::{Scenario, WireSlabScenario};
use crate::transport::{StopSignal, TerminationWatch};

/// Everything a simulation produced.
#[derive(Debug, Clone)]
pub struct SimulationOutput {
    /// All samples, cut after cut.
    pub samples: Vec<CutSample>,
    /// One summary per cut, in the scenario's order.
    pub summaries: Vec<CutSummary>,
    /// Target depth of every cut, m.
    pub target_depth_m: f64,
    /// Which model ran.
    pub model: &'static str,
    /// The signal that stopped the simulation before its last cut ended
    /// (`None`: every cut ran to its end). The samples then hold every step
    /// up to the stop; the cut in progress has a summary of its own.
    pub stopped: Option<StopSignal>,
}

/// The summary file's content.
#[derive(Debug, serde::Serialize)]
struct SummaryFile<'a> {
    scenario: &'a str,
    model: &'a str,
    target_depth_m: f64,
    cuts: &'a [CutSummary],
    /// `{"stopped": "sigint"}` when a signal stopped the run (absent
    /// otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    end: Option<StoppedEnd>,
}

/// How a stopped simulation ended, in `summary.json`.
#[derive(Debug, serde::Serialize)]
struct StoppedEnd {
    stopped: StopSignal,
}

/// Steps between two looks for a stop request: a look takes a lock, a
/// step of the section model tens of microseconds.
const STOP_POLL_STEPS: usize = 256;

/// A stop request source: the signal to stop for, if one came.
type StopCheck<'a> = &'a dyn Fn() -> Option<StopSignal>;

/// Model name of the single-section path.
pub const SINGLE_SECTION: &str = "single cross section x piece length";
/// Model name of the plant path.
pub const MULTI_SECTION: &str = "multi-section plant";

/// Duration of the velocity ramp at the start of a plant run, s.
const RAMP_S: f64 = 0.05;

/// Runs the cuts of `scenario` (no files written).
pub fn simulate(scenario: &Scenario) -> Result<SimulationOutput, RunError> {
    simulate_until(scenario, &|| None, &mut NoCutRecorder)
}

/// Runs the cuts of `scenario`, handing each sample and each finished
/// cut's summary to `recorder` as they come, and looking at `stop` every
/// [`STOP_POLL_STEPS`] steps: a signal ends the simulation there, with the
/// samples so far ([`SimulationOutput::stopped`]).
///
/// # Errors
/// The scenario cannot run (exit 2), or the recorder failed.
pub fn simulate_until(
    scenario: &Scenario,
    stop: StopCheck,
    recorder: &mut dyn CutRecorder,
) -> Result<SimulationOutput, RunError> {
    let knife = Knife::new(&scenario.knife).map_err(|e| invalid(scenario, e.prefixed("knife")))?;
    match (&scenario.object, &scenario.knife.edge) {
        (ObjectShape::Cuboid(c), EdgeShape::Straight { .. } | EdgeShape::Wire { .. }) => {
            simulate_section(scenario, &knife, c, stop, recorder)
        }
        _ => simulate_plant(scenario, &knife, stop, recorder),
    }
}

/// The plant of one cut: the scenario's material, plant, sections and arm
/// limits, the object at `z0` along the edge, planned at slice-push ratio
/// `xi`.
fn cut_plant<'a>(
    scenario: &'a Scenario,
    knife: &'a Knife,
    mesh: &'a TriangleMesh,
    xi: f64,
    z0: f64,
) -> PlantSpec<'a> {
    PlantSpec {
        material: &scenario.material,
        knife,
        object: mesh,
        z0,
        direction: Plant::direction_at(xi),
        settings: &scenario.plant,
        section: &scenario.section,
        arm_limits: &scenario.control_loop.arm_limits,
    }
}

/// Checks what [`simulate`] checks before its first cut (no section is
/// built): the knife, the cuts' travel along the edge (single section) or
/// each cut's plant ([`Plant::check`]). Cheap: for `shearcut check`.
///
/// # Errors
/// The scenario cannot be simulated (exit 2).
pub fn check(scenario: &Scenario) -> Result<(), RunError> {
    let knife = Knife::new(&scenario.knife).map_err(|e| invalid(scenario, e.prefixed("knife")))?;
    match (&scenario.object, &scenario.knife.edge) {
        (ObjectShape::Cuboid(c), EdgeShape::Straight { .. } | EdgeShape::Wire { .. }) => {
            section_geometry(scenario, &knife, c).map(|_| ())
        }
        _ => {
            let mesh = object_mesh(scenario)?;
            for (i, (xi, z0)) in scenario.motion.cuts().into_iter().enumerate() {
                Plant::check(cut_plant(scenario, &knife, &mesh, xi, z0))
                    .map_err(|e| plant_refused(scenario, i, xi, z0, e))?;
            }
            Ok(())
        }
    }
}

fn invalid(scenario: &Scenario, setting: InvalidSetting) -> RunError {
    RunError::Config(ConfigError::Invalid {
        path: scenario.name.clone(),
        setting,
    })
}

/// The cuboid's section, once every cut's blade travel is checked to stay
/// on the edge: z0 + the piece's length + ξ·depth within its length.
fn section_geometry(
    scenario: &Scenario,
    knife: &Knife,
    cuboid: &Cuboid,
) -> Result<SectionGeometry, RunError> {
    let depth = scenario.motion.depth.unwrap_or(0.8 * cuboid.height);
    let edge_length = knife.edge().length();
    for (i, (xi, z0)) in scenario.motion.cuts().into_iter().enumerate() {
        let travel = xi * depth;
        let needed = z0 + cuboid.length + travel;
        if needed > edge_length {
            return Err(invalid(
                scenario,
                InvalidSetting::new(
                    format!("motion.slice_push_ratios[{i}]"),
                    xi,
                    format!(
                        "the blade would travel {travel:.4} m along the edge; z0 + piece length + travel = {needed:.4} m exceeds the edge's {edge_length:.4} m"
                    ),
                ),
            ));
        }
    }
    SectionGeometry::rectangle(cuboid.width, cuboid.height).map_err(|e| {
        invalid(
            scenario,
            InvalidSetting::new("object", "cuboid", e.to_string()),
        )
    })
}

/// The object's mesh.
fn object_mesh(scenario: &Scenario) -> Result<TriangleMesh, RunError> {
    scenario.object.mesh().map_err(|e| {
        invalid(
            scenario,
            InvalidSetting::new("object", "mesh", e.to_string()),
        )
    })
}

/// Cut `i`'s plant refused.
fn plant_refused(scenario: &Scenario, i: usize, xi: f64, z0: f64, e: PlantError) -> RunError {
    invalid(
        scenario,
        InvalidSetting::new(
            format!("motion (cut {i})"),
            format!("xi = {xi}, z0 = {z0}"),
            e.to_string(),
        ),
    )
}

/// One uniform section × the cuboid's length.
fn simulate_section(
    scenario: &Scenario,
    knife: &Knife,
    cuboid: &Cuboid,
    stop: StopCheck,
    recorder: &mut dyn CutRecorder,
) -> Result<SimulationOutput, RunError> {
    let geometry = section_geometry(scenario, knife, cuboid)?;
    let depth = scenario.motion.depth.unwrap_or(0.8 * cuboid.height);
    let mut section = CrossSection::new(
        &geometry,
        &scenario.material,
        knife.blade(),
        &scenario.section,
    )
    .map_err(|e| {
        invalid(
            scenario,
            InvalidSetting::new("section", "model", e.to_string()),
        )
    })?;
    let step = scenario.motion.step;
    run_cuts(
        scenario,
        depth,
        SINGLE_SECTION,
        stop,
        recorder,
        |_, xi, z0, cut| {
            section.reset();
            let v_n = scenario.motion.speed / (1.0 + xi * xi).sqrt();
            while section.state().crack_depth < depth - 1e-12
                && section.state().knife_displacement < cuboid.height - step
                && !section.is_cut_through()
            {
                let s = section.advance(step, xi * step).map_err(|e| {
                    invalid(
                        scenario,
                        InvalidSetting::new("section", "step", e.to_string()),
                    )
                })?;
                cut.record(section_sample(knife, xi, z0, &s, v_n, cuboid))?;
                if cut.step_done() {
                    break;
                }
            }
            Ok(())
        },
    )
}

/// The cuts of `scenario`, one after another, each run by `run_cut(i, ξ,
/// z0, cut)`, which records its samples through `cut` and ends early when
/// [`Cut::step_done`] says a stop was asked. Each cut's summary is recorded
/// as it ends; a stop ends the run after the cut in progress (summarised as
/// it stands).
fn run_cuts(
    scenario: &Scenario,
    depth: f64,
    model: &'static str,
    stop: StopCheck,
    recorder: &mut dyn CutRecorder,
    mut run_cut: impl FnMut(usize, f64, f64, &mut Cut) -> Result<(), RunError>,
) -> Result<SimulationOutput, RunError> {
    let cuts = scenario.motion.cuts();
    let bar = run_bar(cuts.len(), &format!("simulate {}", scenario.name));
    let mut cut = Cut {
        samples: Vec::new(),
        first: 0,
        steps: 0,
        recorder,
        stop,
        stopped: None,
    };
    let mut summaries = Vec::new();
    for (i, (xi, z0)) in cuts.into_iter().enumerate() {
        bar.inc(1);
        cut.first = cut.samples.len();
        cut.steps = 0;
        run_cut(i, xi, z0, &mut cut)?;
        let summary = CutSummary::from_samples(&cut.samples[cut.first..], depth);
        cut.recorder.cut_done(&summary)?;
        summaries.push(summary);
        if cut.stopped.is_some() {
            break;
        }
    }
    bar.finish_and_clear();
    Ok(SimulationOutput {
        samples: cut.samples,
        summaries,
        target_depth_m: depth,
        model,
        stopped: cut.stopped,
    })
}

/// The cut in progress of [`run_cuts`]: where its samples go, and the stop.
struct Cut<'a, 'r> {
    /// Every cut's samples so far.
    samples: Vec<CutSample>,
    /// The first sample of the cut in progress.
    first: usize,
    /// Steps of the cut in progress.
    steps: usize,
    recorder: &'r mut dyn CutRecorder,
    stop: StopCheck<'a>,
    /// The signal that stopped the run, if one did.
    stopped: Option<StopSignal>,
}

impl Cut<'_, '_> {
    /// Records `sample` and keeps it.
    fn record(&mut self, sample: CutSample) -> Result<(), RunError> {
        self.recorder.sample(&sample)?;
        self.samples.push(sample);
        Ok(())
    }

    /// Counts a step of the cut; every [`STOP_POLL_STEPS`] steps asks
    /// whether to stop. True: a stop was asked, end the cut.
    fn step_done(&mut self) -> bool {
        self.steps += 1;
        if self.steps.is_multiple_of(STOP_POLL_STEPS) {
            self.stopped = (self.stop)();
        }
        self.stopped.is_some()
    }
}

fn section_sample(
    knife: &Knife,
    xi: f64,
    z0: f64,
    s: &SectionStep,
    v_n: f64,
    cuboid: &Cuboid,
) -> CutSample {
    let length = cuboid.length;
    let w = &s.work;
    // The knife moves towards the tip: the piece's contact centre sits at
    // z0 + L/2 − ξ·d along the edge, and the section force acts there.
    let travel = xi * s.knife_displacement;
    let knife_origin = Vector3::new(0.0, cuboid.height - s.knife_displacement, -z0 + travel);
    let load = SegmentLoad {
        midpoint: knife_origin + Vector3::new(0.0, 0.0, z0 + 0.5 * length - travel),
        normal: -Vector3::y(),
        tangent: Vector3::z(),
        length,
        force_normal: s.force_vertical,
        force_tangent: if xi > 0.0 { -s.force_tangential } else { 0.0 },
    };
    let wrench = wrench_at(&(knife_origin + knife.sensor_position()), &[load]);
    CutSample {
        xi,
        z0_m: z0,
        time_s: s.knife_displacement / v_n,
        displacement_m: s.knife_displacement,
        tangential_displacement_m: travel,
        force_vertical_n_per_m: s.force_vertical,
        force_horizontal_n_per_m: s.force_tangential,
        force_vertical_n: s.force_vertical * length,
        force_horizontal_n: s.force_tangential * length,
        torque_x_nm: wrench.torque.x,
        torque_y_nm: wrench.torque.y,
        torque_z_nm: wrench.torque.z,
        contact_length_m: if s.knife_displacement > 0.0 {
            length
        } else {
            0.0
        },
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

/// The multi-section plant at the loop rate.
fn simulate_plant(
    scenario: &Scenario,
    knife: &Knife,
    stop: StopCheck,
    recorder: &mut dyn CutRecorder,
) -> Result<SimulationOutput, RunError> {
    let mesh = object_mesh(scenario)?;
    let (lo, hi) = mesh.bounds();
    let height = hi.y - lo.y;
    let depth = scenario.motion.depth.unwrap_or(0.8 * height);
    let dt = 1.0 / scenario.control_loop.rate_hz;
    let gap = scenario.plant.start_gap;
    run_cuts(
        scenario,
        depth,
        MULTI_SECTION,
        stop,
        recorder,
        |i, xi, z0, cut| {
            let alpha = xi.atan();
            let mut plant = Plant::new(cut_plant(scenario, knife, &mesh, xi, z0), scenario.seed)
                .map_err(|e| plant_refused(scenario, i, xi, z0, e))?;
            let start = plant.position();
            let v_full = Vector3::new(0.0, -alpha.cos(), alpha.sin()) * scenario.motion.speed;
            // Stop at the target depth, through the object, or after the knife has
            // travelled twice the object's height (a cut that does not progress).
            let max_ticks =
                ((2.0 * height + gap) / (scenario.motion.speed * alpha.cos() * dt)).ceil() as usize;
            for tick in 1..=max_ticks {
                let t = tick as f64 * dt;
                let v = v_full * (t / RAMP_S).min(1.0);
                let step = plant.step(&KnifeCommand { velocity: v }, dt).map_err(|e| {
                    invalid(
                        scenario,
                        InvalidSetting::new("section", "step", e.to_string()),
                    )
                })?;
                if let ArmStatus::LimitViolation(why) = step.reading.status {
                    return Err(invalid(
                        scenario,
                        InvalidSetting::new(
                            "loop.arm_limits",
                            why.to_string(),
                            "the prescribed motion must respect the arm limits",
                        ),
                    ));
                }
                if let Some(sample) =
                    CutSample::from_plant(&step.reading, &step.truth, xi, z0, &start, gap)
                {
                    cut.record(sample)?;
                }
                if step.truth.crack_depth >= depth || cut.step_done() {
                    break;
                }
            }
            Ok(())
        },
    )
}

/// Runs the subcommand: simulate, write the results into `out` (or a fresh
/// `runs/` directory) and print a summary.
pub fn run(scenario: &str, out: &Destination) -> Result<(), RunError> {
    if let Some(s) = WireSlabScenario::load(scenario)? {
        return run_wire_slab(&s, out);
    }
    let s = Scenario::load(scenario)?;
    run_scenario(&s, out)
}

/// Simulates a loaded scenario and writes its results.
pub fn run_scenario(s: &Scenario, out: &Destination) -> Result<(), RunError> {
    // SIGINT/SIGTERM stop the simulation between steps (from before the
    // run's directory exists); the results so far are written as a finished
    // run's would be, and the exit is 130/143.
    let watch = TerminationWatch::new();
    let dir = run_dir::claim(&s.name, out, &crate::commands::check::resolved_toml(s))?;
    let mut stream = CutStream::create(&dir).inspect_err(|_| run_dir::abandon(&dir))?;
    let output = simulate_until(s, &|| watch.requested(), &mut stream)
        .inspect_err(|_| run_dir::abandon(&dir))?;
    stream.finish()?;
    write_json(
        &dir.join("summary.json"),
        &SummaryFile {
            scenario: &s.name,
            model: output.model,
            target_depth_m: output.target_depth_m,
            cuts: &output.summaries,
            end: output.stopped.map(|stopped| StoppedEnd { stopped }),
        },
    )?;
    let cuts: Vec<&[CutSample]> = output
        .samples
        .chunk_by(|a, b| a.xi.to_bits() == b.xi.to_bits() && a.z0_m.to_bits() == b.z0_m.to_bits())
        .collect();
    let per_length = output.model == SINGLE_SECTION;
    let title = if per_length {
        format!(
            "{}: force and work per unit length of edge (seed 000 Fig. 7 style)",
            s.name
        )
    } else {
        format!(
            "{}: force and work on the knife (seed 000 Figs. 8-11 style)",
            s.name
        )
    };
    for name in ["forces_work.svg", "forces_work.png"] {
        render_plot!(&dir.join(name), (1500, 500), |root| draw_cut_curves(
            root, &title, &cuts, per_length
        ))?;
    }
    print(&format!(
        "{}results: {}/ (timeseries.csv, cuts.csv, summary.json, scenario.toml, forces_work.svg/.png)\n",
        summary_table(s, output.model, &output.summaries),
        dir.display()
    ))?;
    match output.stopped {
        Some(signal) => Err(RunError::Stopped {
            signal,
            dir: dir.display().to_string(),
        }),
        None => Ok(()),
    }
}

fn summary_table(s: &Scenario, model: &str, summaries: &[CutSummary]) -> String {
    use std::fmt::Write;
    let mut t = format!(
        "{}: {} [{model}]\n   xi   z0 (m)  work (J)  peak Fv (N)  peak Fh (N)  peak torque (Nm)  first fracture (mm)  max deform. (mm)  depth (mm)  completed\n",
        s.name, s.description
    );
    for c in summaries {
        let _ = writeln!(
            t,
            "{:>5.2}  {:>7.4}  {:>8.4}  {:>11.3}  {:>11.3}  {:>16.4}  {:>19}  {:>16.3}  {:>10.2}  {}",
            c.xi,
            c.z0_m,
            c.work_j,
            c.peak_force_vertical_n,
            c.peak_force_horizontal_n,
            c.peak_torque_nm,
            c.first_fracture_displacement_m
                .map_or("-".to_string(), |d| format!("{:.3}", d * 1e3)),
            c.max_deformation_m * 1e3,
            c.cut_depth_m * 1e3,
            c.completed
        );
    }
    t
}

/// Nucleation of one angle in the summary.
#[derive(Debug, serde::Serialize)]
struct SlabNucleation {
    angle_deg: f64,
    nucleated: bool,
    depth_m: Option<f64>,
    force_normal_n: Option<f64>,
    force_tangential_n: Option<f64>,
    position_m: Option<f64>,
    under_wire: Option<bool>,
    load_steps: usize,
    /// `true` when a signal stopped this angle's indentation (absent
    /// otherwise).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    stopped: bool,
}

/// The finite-strain run's summary file.
#[derive(Debug, serde::Serialize)]
struct SlabSummary<'a> {
    scenario: &'a str,
    model: &'static str,
    nucleation_stress_pa: f64,
    elements: usize,
    unknowns: usize,
    nucleation: Vec<SlabNucleation>,
    seed_comparison: shearcut_sim::finite_strain::SeedComparison,
    /// `{"stopped": "sigint"}` when a signal stopped the sweep (absent
    /// otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    end: Option<StoppedEnd>,
}

/// Runs seed 001's finite-strain wire–slab sweep and writes its series
/// (`series.csv`), surface σ₁ profiles at nucleation (`surface.csv`), a
/// summary with the seed's numbers side by side (`summary.json`), the resolved
/// scenario and the plots in the seed's form.
///
/// SIGINT/SIGTERM stop the sweep after the load step in progress: the
/// angles so far are written as a finished sweep's are (the ones stopped
/// marked `"stopped": true`, the summary's `"end": {"stopped": "sigint"}`),
/// and the exit is 130/143.
pub fn run_wire_slab(s: &WireSlabScenario, out: &Destination) -> Result<(), RunError> {
    use shearcut_sim::finite_strain::{
        IndentationRun, SeedComparison, WireSlab, WireSlabError, sweep_angles_until,
    };
    let watch = TerminationWatch::new();
    let signal = std::sync::OnceLock::new();
    let stop = || {
        if let Some(sig) = watch.requested() {
            let _ = signal.set(sig);
        }
        signal.get().is_some()
    };
    let model_error = |e: WireSlabError| match e {
        WireSlabError::Setting(setting) => RunError::Config(ConfigError::Invalid {
            path: s.name.clone(),
            setting: setting.prefixed("slab"),
        }),
        WireSlabError::Model(e) => RunError::Loop(format!("finite-strain model: {e}")),
    };
    let probe = WireSlab::new(&s.slab).map_err(model_error)?;
    let resolved = toml::to_string(s).map_err(|e| RunError::write("scenario.toml", e))?;
    let dir = run_dir::claim(&s.name, out, &resolved)?;
    // Each angle's rows are written as it ends (in the angles' order).
    let stream =
        std::sync::Mutex::new(AngleStream::create(&dir).inspect_err(|_| run_dir::abandon(&dir))?);
    let ended = |index: usize, run: &IndentationRun| {
        if let Ok(mut stream) = stream.lock() {
            stream.angle_ended(index, run);
        }
    };
    let sweep = sweep_angles_until(&s.slab, &s.sweep.angles_deg, s.sweep.threads, &stop, &ended)
        .map_err(model_error)
        .inspect_err(|_| run_dir::abandon(&dir))?;
    stream
        .into_inner()
        .map_err(|_| RunError::Loop("the angle stream's lock was poisoned".to_string()))?
        .finish()?;
    let runs = &sweep.runs;
    let comparison = SeedComparison::new(&s.slab, runs);
    let nucleation: Vec<SlabNucleation> = runs
        .iter()
        .map(|run| SlabNucleation {
            angle_deg: run.angle.to_degrees(),
            nucleated: run.nucleation.is_some(),
            depth_m: run.nucleation.map(|n| n.depth),
            force_normal_n: run.nucleation.map(|n| n.force_normal),
            force_tangential_n: run.nucleation.map(|n| n.force_tangential),
            position_m: run.nucleation.map(|n| n.position),
            under_wire: run.nucleation.map(|n| n.under_wire),
            load_steps: run.states.len(),
            stopped: run.stopped,
        })
        .collect();
    write_json(
        &dir.join("summary.json"),
        &SlabSummary {
            scenario: &s.name,
            model: "finite-strain periodic slab and wire (seed 001)",
            nucleation_stress_pa: s.slab.nucleation_stress(),
            elements: probe.element_count(),
            unknowns: probe.unknowns(),
            nucleation,
            seed_comparison: comparison,
            end: signal.get().map(|&stopped| StoppedEnd { stopped }),
        },
    )?;
    let sl = &s.slab;
    for ext in ["svg", "png"] {
        render_plot!(
            &dir.join(format!("forces_depth.{ext}")),
            (1400, 550),
            |root| {
                crate::plot::wire_slab::draw_slab_forces(
                    root,
                    &format!(
                        "{}: forces on the wire up to nucleation (seed 001 Figs. 1c-d, 3b-c)",
                        s.name
                    ),
                    runs,
                )
            }
        )?;
        render_plot!(
            &dir.join(format!("nucleation_angle.{ext}")),
            (1400, 550),
            |root| {
                crate::plot::wire_slab::draw_nucleation_angles(
                    root,
                    &format!(
                        "{}: forces at nucleation against the angle (seed 001 Figs. 1e-f, 3d-e)",
                        s.name
                    ),
                    runs,
                    comparison.seed_max_tangential_force,
                )
            }
        )?;
        render_plot!(
            &dir.join(format!("stress_map.{ext}")),
            (1500, 1000),
            |root| {
                crate::plot::wire_slab::draw_stress_maps(
                    root,
                    &format!(
                        "{}: largest principal stress at nucleation (seed 001 Fig. 2)",
                        s.name
                    ),
                    runs,
                    sl.wire_radius,
                    sl.slab_depth,
                    sl.shear_modulus,
                )
            }
        )?;
    }
    crate::outln!("{}: {}", s.name, s.description)?;
    crate::outln!(
        "  model: finite-strain periodic slab, {} elements, {} unknowns; sigma* = {:.0} Pa",
        probe.element_count(),
        probe.unknowns(),
        s.slab.nucleation_stress()
    )?;
    crate::outln!("  theta (deg)  d_nuc (mm)  F_n (N)   F_t (N)   sigma1 max at (um)  under wire")?;
    for run in runs {
        match run.nucleation {
            Some(n) => crate::outln!(
                "  {:>11.0}  {:>10.3}  {:>7.4}  {:>7.4}  {:>18.1}  {}",
                run.angle.to_degrees(),
                n.depth * 1e3,
                n.force_normal,
                n.force_tangential,
                n.position * 1e6,
                n.under_wire
            )?,
            None if run.stopped => crate::outln!(
                "  {:>11.0}  stopped at {:.3} mm",
                run.angle.to_degrees(),
                run.states.last().map_or(0.0, |st| st.depth) * 1e3
            )?,
            None => crate::outln!(
                "  {:>11.0}  no nucleation up to {:.3} mm",
                run.angle.to_degrees(),
                sl.max_depth * 1e3
            )?,
        }
    }
    let c = comparison;
    crate::outln!("  seed 001 side by side (model | seed):")?;
    crate::outln!(
        "    slope dF_n/dd (N/m)            {:>8.1} | {:>8.1}  (5 mu h / ln(B/R))",
        c.normal_slope,
        c.seed_normal_slope
    )?;
    crate::outln!(
        "    max F_t at nucleation (N)      {:>8.4} | {:>8.4}  (2 mu R h)",
        c.max_tangential_force,
        c.seed_max_tangential_force
    )?;
    crate::outln!(
        "    F_n ratio first/last angle     {:>8.2} | {:>8.2}",
        c.normal_force_ratio,
        c.seed_normal_force_ratio
    )?;
    crate::outln!(
        "    f_n/(mu R) where max moves under the wire {} | {:.0}",
        c.under_wire_from
            .map_or("never".to_string(), |v| format!("{v:.1}")),
        c.seed_under_wire_from
    )?;
    crate::outln!(
        "results: {}/ (series.csv, surface.csv, summary.json, scenario.toml, forces_depth, nucleation_angle, stress_map .svg/.png)",
        dir.display()
    )?;
    match signal.get() {
        Some(&signal) => Err(RunError::Stopped {
            signal,
            dir: dir.display().to_string(),
        }),
        None => Ok(()),
    }
}
