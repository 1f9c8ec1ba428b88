//! The objectives a setting is judged on, all to be made small: the work
//! done on the object, its largest surface deformation, the peak vertical
//! force on the knife and the time to the target depth.

use crate::tune::job_outcome::JobOutcome;

/// One objective.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Objective {
    /// Total knife work, J.
    Work,
    /// Largest surface deformation next to the blade, m.
    Deformation,
    /// Peak vertical force, N.
    PeakForce,
    /// Time from the start to the target depth, s.
    Time,
}

impl Objective {
    /// Every objective, in the order of the results' columns.
    pub const ALL: [Objective; 4] = [
        Objective::Work,
        Objective::Deformation,
        Objective::PeakForce,
        Objective::Time,
    ];

    /// The key naming it in sweep files (`[weightings]`).
    pub fn key(self) -> &'static str {
        match self {
            Objective::Work => "work",
            Objective::Deformation => "deformation",
            Objective::PeakForce => "peak_force",
            Objective::Time => "time",
        }
    }

    /// The result column it is read from.
    pub fn column(self) -> &'static str {
        match self {
            Objective::Work => "work_j",
            Objective::Deformation => "max_deformation_m",
            Objective::PeakForce => "peak_force_vertical_n",
            Objective::Time => "duration_s",
        }
    }

    /// Its value for one run (SI units).
    pub fn of(self, o: &JobOutcome) -> f64 {
        match self {
            Objective::Work => o.work_j,
            Objective::Deformation => o.max_deformation_m,
            Objective::PeakForce => o.peak_force_vertical_n,
            Objective::Time => o.duration_s,
        }
    }

    /// A label with a display unit, and the factor from SI to that unit.
    pub fn label(self) -> (&'static str, f64) {
        match self {
            Objective::Work => ("work (J)", 1.0),
            Objective::Deformation => ("max deformation (mm)", 1e3),
            Objective::PeakForce => ("peak vertical force (N)", 1.0),
            Objective::Time => ("time (s)", 1.0),
        }
    }
}
