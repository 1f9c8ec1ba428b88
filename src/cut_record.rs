//! Recording an open-loop cut: the time series, the summary and their files.
//!
//! One [`CutSample`] per model step. `timeseries.csv` holds every sample of
//! every cut of a run (a run sweeps several slice-push ratios; the `xi` column
//! tells them apart). `summary.json` holds one [`CutSummary`] per cut.

use nalgebra::Vector3;
use serde::Serialize;
use shearcut_plant::PlantTruth;
use shearcut_sim::arm::ArmReading;

/// The state of one cut after a model step. Forces are the object's resistance
/// to the knife (positive against the motion, seed 000's convention).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CutSample {
    /// Slice-push ratio of this cut.
    pub xi: f64,
    /// Distance from the heel to the object along the edge, m.
    pub z0_m: f64,
    /// Simulated time since the knife touched the object, s.
    pub time_s: f64,
    /// Vertical knife displacement since first contact (downwards positive), m.
    pub displacement_m: f64,
    /// Tangential knife displacement along the edge since first contact, m.
    pub tangential_displacement_m: f64,
    /// Vertical force per unit length of edge in contact, N/m.
    pub force_vertical_n_per_m: f64,
    /// Horizontal (along-edge) force per unit length of edge in contact, N/m.
    pub force_horizontal_n_per_m: f64,
    /// Total vertical force on the knife, N.
    pub force_vertical_n: f64,
    /// Total horizontal force on the knife, N.
    pub force_horizontal_n: f64,
    /// Torque about the F/T sensor's x axis (normal to the blade), N·m.
    pub torque_x_nm: f64,
    /// Torque about the sensor's y axis, N·m (0 for a symmetric cut).
    pub torque_y_nm: f64,
    /// Torque about the sensor's z axis, N·m (0 for a symmetric cut).
    pub torque_z_nm: f64,
    /// Length of edge in contact with the object, m.
    pub contact_length_m: f64,
    /// Cumulative knife work per unit length, J/m.
    pub work_j_per_m: f64,
    /// Cumulative knife work, J.
    pub work_j: f64,
    /// Of the work: fracture energy per unit length, J/m.
    pub fracture_energy_j_per_m: f64,
    /// Of the work: stored strain energy per unit length, J/m.
    pub strain_energy_j_per_m: f64,
    /// Of the work: friction dissipation per unit length, J/m.
    pub friction_work_j_per_m: f64,
    /// Crack depth below the object's original top, m.
    pub crack_depth_m: f64,
    /// How far the top surface next to the blade is pushed down, m.
    pub deformation_m: f64,
    /// True once the material under the edge has fractured.
    pub fractured: bool,
}

impl CutSample {
    /// The sample of a plant tick (the arm's reading and the plant's
    /// truth): `start` is the knife's position before the
    /// cut and `gap` the normal distance to the object's top it first had to
    /// close (so the displacement counts from first contact); `xi` and `z0`
    /// label the cut. `None` before the edge reaches the top.
    ///
    /// Forces are the true (noise-free) wrench's, resistance positive: the
    /// object pushes the knife up (+y) and against its tangential motion.
    /// Torques are the F/T sensor's reading. The work split is not tracked
    /// per plant (0).
    pub fn from_plant(
        m: &ArmReading,
        truth: &PlantTruth,
        xi: f64,
        z0: f64,
        start: &Vector3<f64>,
        gap: f64,
    ) -> Option<Self> {
        let displacement = start.y - m.position.y - gap;
        if displacement < 0.0 {
            return None;
        }
        let per_length = |f: f64| {
            if truth.contact_length > 0.0 {
                f / truth.contact_length
            } else {
                0.0
            }
        };
        let w = &truth.wrench;
        let fv = w.force.y;
        let fh = if m.velocity.z > 0.0 {
            -w.force.z
        } else if m.velocity.z < 0.0 {
            w.force.z
        } else {
            w.force.z.abs()
        };
        Some(Self {
            xi,
            z0_m: z0,
            time_s: m.time,
            displacement_m: displacement,
            tangential_displacement_m: m.position.z - start.z,
            force_vertical_n_per_m: per_length(fv),
            force_horizontal_n_per_m: per_length(fh),
            force_vertical_n: fv,
            force_horizontal_n: fh,
            torque_x_nm: m.wrench[3],
            torque_y_nm: m.wrench[4],
            torque_z_nm: m.wrench[5],
            contact_length_m: truth.contact_length,
            work_j_per_m: per_length(truth.work),
            work_j: truth.work,
            fracture_energy_j_per_m: 0.0,
            strain_energy_j_per_m: 0.0,
            friction_work_j_per_m: 0.0,
            crack_depth_m: truth.crack_depth,
            deformation_m: truth.deformation,
            fractured: truth.fractured_sections > 0,
        })
    }
}

/// The outcome of one cut.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CutSummary {
    /// Slice-push ratio.
    pub xi: f64,
    /// Distance from the heel to the object along the edge, m.
    pub z0_m: f64,
    /// Total knife work, J.
    pub work_j: f64,
    /// Total knife work per unit length of edge, J/m.
    pub work_j_per_m: f64,
    /// Peak vertical force, N.
    pub peak_force_vertical_n: f64,
    /// Peak horizontal force, N.
    pub peak_force_horizontal_n: f64,
    /// Peak magnitude of the torque at the sensor, N·m.
    pub peak_torque_nm: f64,
    /// Largest surface deformation, m.
    pub max_deformation_m: f64,
    /// Depth of the crack at the end, m.
    pub cut_depth_m: f64,
    /// Knife displacement at the first fracture, m (None if it never fractured).
    pub first_fracture_displacement_m: Option<f64>,
    /// Whether the cut reached the target depth.
    pub completed: bool,
    /// Blade used: the largest tangential displacement from the start, m
    /// (what must fit on the edge).
    pub blade_travel_m: f64,
    /// Tangential path length, m: the blade travel summed over strokes.
    pub blade_path_m: f64,
    /// Reversals of the tangential direction (sawing strokes back).
    pub reversals: u32,
    /// Simulated duration, s.
    pub duration_s: f64,
}

impl CutSummary {
    /// Summarises the samples of one cut (non-empty) for a target depth.
    pub fn from_samples(samples: &[CutSample], target_depth_m: f64) -> Self {
        let last = samples.last().copied().unwrap_or(CutSample {
            xi: 0.0,
            z0_m: 0.0,
            time_s: 0.0,
            displacement_m: 0.0,
            tangential_displacement_m: 0.0,
            force_vertical_n_per_m: 0.0,
            force_horizontal_n_per_m: 0.0,
            force_vertical_n: 0.0,
            force_horizontal_n: 0.0,
            torque_x_nm: 0.0,
            torque_y_nm: 0.0,
            torque_z_nm: 0.0,
            contact_length_m: 0.0,
            work_j_per_m: 0.0,
            work_j: 0.0,
            fracture_energy_j_per_m: 0.0,
            strain_energy_j_per_m: 0.0,
            friction_work_j_per_m: 0.0,
            crack_depth_m: 0.0,
            deformation_m: 0.0,
            fractured: false,
        });
        let max = |f: fn(&CutSample) -> f64| samples.iter().map(f).fold(0.0, f64::max);
        Self {
            xi: last.xi,
            z0_m: last.z0_m,
            work_j: last.work_j,
            work_j_per_m: last.work_j_per_m,
            peak_force_vertical_n: max(|s| s.force_vertical_n),
            peak_force_horizontal_n: max(|s| s.force_horizontal_n.abs()),
            peak_torque_nm: max(|s| {
                (s.torque_x_nm * s.torque_x_nm
                    + s.torque_y_nm * s.torque_y_nm
                    + s.torque_z_nm * s.torque_z_nm)
                    .sqrt()
            }),
            max_deformation_m: max(|s| s.deformation_m),
            cut_depth_m: last.crack_depth_m,
            first_fracture_displacement_m: samples
                .iter()
                .find(|s| s.fractured)
                .map(|s| s.displacement_m),
            // Within a micrometre: the crack advances in finite increments.
            completed: last.crack_depth_m >= target_depth_m - 1e-6,
            blade_travel_m: max(|s| s.tangential_displacement_m.abs()),
            blade_path_m: samples
                .first()
                .map_or(0.0, |s| s.tangential_displacement_m.abs())
                + samples
                    .windows(2)
                    .map(|w| {
                        (w[1].tangential_displacement_m - w[0].tangential_displacement_m).abs()
                    })
                    .sum::<f64>(),
            reversals: reversals(samples),
            duration_s: last.time_s,
        }
    }
}

/// Reversals of the tangential direction of motion over `samples`
/// (moves shorter than a nanometre per sample are standstill).
fn reversals(samples: &[CutSample]) -> u32 {
    let mut sign = 0.0;
    let mut count = 0;
    for w in samples.windows(2) {
        let d = w[1].tangential_displacement_m - w[0].tangential_displacement_m;
        if d.abs() < 1e-9 {
            continue;
        }
        if sign != 0.0 && d.signum() != sign {
            count += 1;
        }
        sign = d.signum();
    }
    count
}
