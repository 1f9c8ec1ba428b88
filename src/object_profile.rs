//! What a controller is told about the object: the edge in contact and the
//! section's size as the cut deepens ([`DepthProfile::of_object`],
//! [`DepthProfile::for_surrogate`]), for a scenario.

use shearcut_controllers::mpc::DepthProfile;
use shearcut_sim::InvalidSetting;
use shearcut_sim::geometry::TriangleMesh;
use shearcut_sim::surrogate::Surrogate;

use crate::scenario::Scenario;

/// The object's [`DepthProfile`] as a vision system would report it
/// ([`DepthProfile::of_object`]).
///
/// # Errors
/// The mesh does not cross the knife plane.
pub fn depth_profile(mesh: &TriangleMesh) -> Result<DepthProfile, InvalidSetting> {
    DepthProfile::of_object(mesh)
}

/// The object of `s` as `surrogate` takes it, cut to `depth`
/// ([`DepthProfile::for_surrogate`] with `s`'s section settings and the
/// plant's rim clipping).
///
/// # Errors
/// As [`DepthProfile::for_surrogate`].
pub fn surrogate_profile(
    s: &Scenario,
    surrogate: &Surrogate,
    mesh: &TriangleMesh,
    depth: f64,
) -> Result<DepthProfile, InvalidSetting> {
    DepthProfile::for_surrogate(mesh, surrogate, &s.section, s.plant.rim_fraction, depth)
}
