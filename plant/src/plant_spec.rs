//! What a plant is built from.

use nalgebra::Vector2;

use shearcut_sim::arm::ArmLimits;
use shearcut_sim::geometry::TriangleMesh;
use shearcut_sim::knife::Knife;
use shearcut_sim::material::Material;
use shearcut_sim::section::SectionSettings;

use crate::plant_settings::PlantSettings;

/// What a [`Plant`](crate::Plant) is built from: the food, the knife, where
/// the object lies along the edge, the planned direction of motion, and the
/// plant's, the sections' and the arm's settings. [`Plant::new`] builds a
/// plant from it; [`Plant::check`] checks it without building a section.
///
/// [`Plant::new`]: crate::Plant::new
/// [`Plant::check`]: crate::Plant::check
#[derive(Debug, Clone, Copy)]
pub struct PlantSpec<'a> {
    /// The object's material.
    pub material: &'a Material,
    /// The knife: its edge, blade and the F/T sensor's place on it.
    pub knife: &'a Knife,
    /// The object's surface, world frame (x across the knife plane, y up, z
    /// towards the knife's tip), m.
    pub object: &'a TriangleMesh,
    /// Where the object lies along the edge, m: the knife's origin starts at
    /// z = (the object's least z) − z₀, so that the piece is z₀ from the heel
    /// (seed 000 Fig. 6(b)); the lowest point of the edge over the object
    /// starts [`PlantSettings::start_gap`] above its top.
    pub z0: f64,
    /// The planned direction of motion in the knife plane (z, y), pointing
    /// down into the object (any length; [`Plant::direction_at`] gives it
    /// for a slice-push ratio). The first sections are built for it, and
    /// they follow it until the knife first moves.
    ///
    /// [`Plant::direction_at`]: crate::Plant::direction_at
    pub direction: Vector2<f64>,
    /// The plant's settings: its segments, reach, threads, sensor.
    pub settings: &'a PlantSettings,
    /// Every cross section's discretisation and solver settings.
    pub section: &'a SectionSettings,
    /// The arm's reflexes, checked on every command.
    pub arm_limits: &'a ArmLimits,
}
