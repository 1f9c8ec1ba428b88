//! What a controller is told about the object: the edge in contact and the
//! section's size as the cut deepens.

use shearcut_controllers::mpc::DepthProfile;
use shearcut_sim::InvalidSetting;
use shearcut_sim::geometry::TriangleMesh;
use shearcut_sim::plant::knife_plane_silhouette;
use shearcut_sim::plant::section_shape::crest_section;
use shearcut_sim::section::SectionError;
use shearcut_sim::surrogate::{Surrogate, equivalent_half_width};

use crate::scenario::Scenario;

/// Depth samples of a profile.
const SAMPLES: usize = 41;

/// The object's [`DepthProfile`] for a knife moving down in the plane x = 0:
/// at crack depth d below the top, the length of edge in contact is the
/// chord of the object's silhouette in the knife plane at height top − d (a
/// straight, horizontal edge's view; a curved edge touches a little less).
/// Depths are below the silhouette's top, where the edge first touches and
/// the plant measures its depth from. The section height is the
/// silhouette's and the half width half the object's extent across the
/// knife plane (x), as a vision system would report them
/// ([`surrogate_profile`] narrows it to the equivalent rectangle's).
pub fn depth_profile(mesh: &TriangleMesh) -> Result<DepthProfile, InvalidSetting> {
    let (lo, hi) = mesh.bounds();
    let silhouette = knife_plane_silhouette(mesh).ok_or_else(|| {
        InvalidSetting::new("object", "mesh", "does not cross the knife plane x = 0")
    })?;
    // The top and height in the knife plane, where the edge first touches
    // and the plant measures the depth from (an eggplant's highest point
    // need not lie on it).
    let (bottom, top) = {
        let (a, b) = silhouette.bounds();
        (a.y, b.y)
    };
    let height = top - bottom;
    // Just below the top (the chord at the very top is a point) to just
    // above the board.
    let depths: Vec<f64> = (0..SAMPLES)
        .map(|i| height * (0.005 + 0.99 * i as f64 / (SAMPLES - 1) as f64))
        .collect();
    let lengths = depths
        .iter()
        .map(|d| silhouette.chord_length(top - d))
        .collect();
    DepthProfile::new(depths, lengths, height, 0.5 * (hi.x - lo.x))
}

/// The [`depth_profile`] of `s`'s object as `surrogate` takes it: the
/// section's half width is that of the rectangle equivalent to the object's
/// crest section ([`equivalent_half_width`]: the rectangle of the same
/// height that the section model presses to `depth` with the same work)
/// for the surrogate's own material and blade (what the controller knows,
/// not the plant's material) and `s`'s section settings. The surrogates
/// are fitted on rectangles; a cuboid's section is its own equivalent, a
/// half ellipsoid's crest section (35 × 60 mm) maps to about 0.9 of its
/// width.
///
/// # Errors
/// As [`depth_profile`], or the section model cannot cut the crest
/// section.
pub fn surrogate_profile(
    s: &Scenario,
    surrogate: &Surrogate,
    mesh: &TriangleMesh,
    depth: f64,
) -> Result<DepthProfile, InvalidSetting> {
    let profile = depth_profile(mesh)?;
    let section_error =
        |e: SectionError| InvalidSetting::new("object", "crest section", e.to_string());
    let crest = crest_section(mesh, s.plant.rim_fraction).map_err(section_error)?;
    let half_width = equivalent_half_width(
        &crest,
        &surrogate.material,
        &surrogate.blade.section(),
        &s.section,
        depth,
    )
    .map_err(section_error)?;
    profile.with_half_width(half_width)
}
