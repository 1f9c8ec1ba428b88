//! The plant's settings: segments, reach, section re-choice, start gap and
//! the F/T sensor, each validated against its physical range.

use serde::{Deserialize, Serialize};
use shearcut_sim::invalid_setting::InvalidSetting;

use crate::ft_sensor::FtSensorSettings;

/// Settings of the plant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PlantSettings {
    /// Number m of edge segments over the object's span: the edge over
    /// the object's extent along z is split into m segments of equal arc
    /// length, and segments of the same length continue the grid over the
    /// rest of the edge the knife can bring down onto the object (see
    /// `reach`), at most [`MAX_SEGMENTS`] in all. Each segment gets its
    /// cross section when it first reaches the material (default 20; 10
    /// under-resolves the curved knife: README, Known limitations).
    pub segments: usize,
    /// How far the knife may travel along z (its edge direction) either way
    /// from its start, m: the edge over the object's span widened by this
    /// on both sides gets segments (default 0; the closed loops raise it to
    /// the controller's blade budget). Edge beyond it that the knife's
    /// planned direction brings onto the object is covered too.
    pub reach: f64,
    /// Gap between the edge and the object when the plant starts, m (default 0.001).
    pub start_gap: f64,
    /// Rim height below which a dome-shaped section is clipped, as a fraction
    /// of the section's height (default 0.05).
    pub rim_fraction: f64,
    /// How far a segment's midpoint may slide off its cross section's plane
    /// before the section is re-chosen through the crack front, m (default
    /// 0.001: seed 000 §IV updates the sections in 1 mm steps).
    pub update_distance: f64,
    /// The F/T sensor.
    pub sensor: FtSensorSettings,
    /// Threads that build sections ahead of the ticks that take them
    /// (default 2). The results do not depend on it, only how often a tick
    /// waits for a section: give them cores of their own in real time.
    pub workers: usize,
    /// Threads that advance the sections within a tick, the stepping
    /// thread included (default 1, in [1, 16]). The results do not depend
    /// on it (the sections of a tick are independent); more threads make a
    /// tick with many sections in contact shorter on free cores, for a
    /// plant that must keep a wall-clock period. The helpers run under the
    /// scheduling of the thread that builds the plant (or that calls
    /// [`Plant::restart_stepping_threads`](crate::Plant::restart_stepping_threads)).
    pub stepping_threads: usize,
}

/// Largest number of edge segments (and cross sections) of a plant.
pub const MAX_SEGMENTS: usize = 256;

impl Default for PlantSettings {
    fn default() -> Self {
        Self {
            segments: 20,
            reach: 0.0,
            start_gap: 1e-3,
            rim_fraction: 0.05,
            update_distance: 1e-3,
            sensor: FtSensorSettings::default(),
            workers: 2,
            stepping_threads: 1,
        }
    }
}

impl PlantSettings {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        if !(1..=64).contains(&self.segments) {
            return Err(InvalidSetting::new(
                "segments",
                self.segments,
                "must be in [1, 64]",
            ));
        }
        if !(self.start_gap.is_finite() && self.start_gap >= 0.0) {
            return Err(InvalidSetting::new(
                "start_gap",
                self.start_gap,
                "must be a finite number >= 0 m",
            ));
        }
        if !(self.rim_fraction > 0.0 && self.rim_fraction < 0.5) {
            return Err(InvalidSetting::new(
                "rim_fraction",
                self.rim_fraction,
                "must be in (0, 0.5)",
            ));
        }
        if !(self.update_distance.is_finite() && self.update_distance > 0.0) {
            return Err(InvalidSetting::new(
                "update_distance",
                self.update_distance,
                "must be a finite number > 0 m",
            ));
        }
        if !(1..=16).contains(&self.workers) {
            return Err(InvalidSetting::new(
                "workers",
                self.workers,
                "must be in [1, 16]",
            ));
        }
        if !(1..=16).contains(&self.stepping_threads) {
            return Err(InvalidSetting::new(
                "stepping_threads",
                self.stepping_threads,
                "must be in [1, 16]",
            ));
        }
        if !(self.reach.is_finite() && self.reach >= 0.0) {
            return Err(InvalidSetting::new(
                "reach",
                self.reach,
                "must be a finite number >= 0 m",
            ));
        }
        self.sensor.validate().map_err(|e| e.prefixed("sensor"))
    }
}
