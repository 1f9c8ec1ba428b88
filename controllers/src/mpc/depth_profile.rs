//! How much edge is in contact, and the section's size, as the cut deepens.

use shearcut_sim::InvalidSetting;
use shearcut_sim::geometry::TriangleMesh;
use shearcut_sim::knife_plane::knife_plane_silhouette;
use shearcut_sim::knife_plane::section_shape::crest_section;
use shearcut_sim::section::{SectionError, SectionSettings};
use shearcut_sim::surrogate::{Surrogate, equivalent_half_width};

use crate::observer::EdgeOutline;

/// Depth samples of [`DepthProfile::of_object`].
const OBJECT_SAMPLES: usize = 41;

/// The object as the MPC sees it along the cut: at each depth of the edge
/// below the object's top (its deepest penetration below the outline's top,
/// [`CutTask::edge_depth`](crate::controller::CutTask::edge_depth)), the length of edge in contact, and the
/// section's height and half width. Piecewise linear between samples;
/// constant beyond the ends.
///
/// Where the contact grows with depth (a dome), the sections in contact
/// entered at different depths, each with its own top: the edge is less
/// deep in them, on average, than below the crest.
/// [`section_depth`](Self::section_depth) is that mean, the depth at which
/// one section's model (the surrogate) stands for them all.
#[derive(Debug, Clone, PartialEq)]
pub struct DepthProfile {
    depths: Vec<f64>,
    contact_lengths: Vec<f64>,
    /// ∫₀^{depths[i]} L(h) dh, m².
    areas: Vec<f64>,
    /// The largest sections' mean depth at the samples up to i, m
    /// (non-decreasing: [`edge_depth_at`](Self::edge_depth_at)'s bracket).
    reached: Vec<f64>,
    height: f64,
    half_width: f64,
}

impl DepthProfile {
    /// A profile from samples (`depths` increasing, m; `contact_lengths`,
    /// m, one per depth), with the section's `height` and `half_width` (m).
    ///
    /// # Errors
    /// Empty or mismatched samples, depths not increasing, or non-finite or
    /// negative values.
    pub fn new(
        depths: Vec<f64>,
        contact_lengths: Vec<f64>,
        height: f64,
        half_width: f64,
    ) -> Result<Self, InvalidSetting> {
        if depths.is_empty() || depths.len() != contact_lengths.len() {
            return Err(InvalidSetting::new(
                "depth_profile",
                format!("{} depths, {} lengths", depths.len(), contact_lengths.len()),
                "one contact length per depth, at least one",
            ));
        }
        if depths
            .windows(2)
            .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
        {
            return Err(InvalidSetting::new(
                "depth_profile.depths",
                format!("{depths:?}"),
                "strictly increasing",
            ));
        }
        for (key, v) in depths
            .iter()
            .map(|d| ("depth_profile.depths", *d))
            .chain(
                contact_lengths
                    .iter()
                    .map(|l| ("depth_profile.contact_lengths", *l)),
            )
            .chain([
                ("depth_profile.height", height),
                ("depth_profile.half_width", half_width),
            ])
        {
            if !(v.is_finite() && v >= 0.0) {
                return Err(InvalidSetting::new(key, v, "finite and >= 0"));
            }
        }
        // The area under L(h) from 0: constant L before the first sample.
        let mut areas = Vec::with_capacity(depths.len());
        let mut area = depths[0] * contact_lengths[0];
        areas.push(area);
        for i in 1..depths.len() {
            area +=
                0.5 * (depths[i] - depths[i - 1]) * (contact_lengths[i] + contact_lengths[i - 1]);
            areas.push(area);
        }
        let mut profile = Self {
            depths,
            contact_lengths,
            areas,
            reached: Vec::new(),
            height,
            half_width,
        };
        let mut most = profile.section_depth(profile.depths[0]);
        let mut reached = vec![most];
        for i in 1..profile.depths.len() {
            most = most
                .max(profile.interior_peak(i))
                .max(profile.section_depth(profile.depths[i]));
            reached.push(most);
        }
        profile.reached = reached;
        Ok(profile)
    }

    /// The sections' mean depth at edge depth `x` within the samples i − 1
    /// and i (`x` in that interval), m: [`section_depth`](Self::section_depth)
    /// with the interval known.
    fn section_depth_within(&self, i: usize, x: f64) -> f64 {
        let length = self.length_within(i - 1, x);
        mean_depth(self.area_within(i - 1, x, length), length, x)
    }

    /// L(x) for `x` between the samples j and j + 1, m.
    fn length_within(&self, j: usize, x: f64) -> f64 {
        let (d, l) = (&self.depths, &self.contact_lengths);
        let t = (x - d[j]) / (d[j + 1] - d[j]);
        l[j] + t * (l[j + 1] - l[j])
    }

    /// ∫₀^x L(h) dh for `x` between the samples j and j + 1, with
    /// `length` = L(x), m².
    fn area_within(&self, j: usize, x: f64, length: f64) -> f64 {
        self.areas[j] + 0.5 * (x - self.depths[j]) * (self.contact_lengths[j] + length)
    }

    /// The largest mean depth strictly inside the samples i − 1 and i, m
    /// (0 if none is larger than at the ends). The mean depth is
    /// min(A/L, x); with L linear in the interval, L² − A·L′ grows with x,
    /// so A/L falls at most before it rises and has no maximum inside. A
    /// maximum inside is where A/L, falling, meets x: a root in the
    /// interval of A − x·L = c − d₀s·u − s·u²/2 (u = x − d₀, s = L′,
    /// c = A(d₀) − d₀·L(d₀)), where the mean depth is x.
    fn interior_peak(&self, i: usize) -> f64 {
        let (d, l) = (&self.depths, &self.contact_lengths);
        let (d0, span) = (d[i - 1], d[i] - d[i - 1]);
        let slope = (l[i] - l[i - 1]) / span;
        if slope == 0.0 {
            return 0.0;
        }
        let c = self.areas[i - 1] - d0 * l[i - 1];
        let disc = d0 * d0 + 2.0 * c / slope;
        if disc < 0.0 {
            return 0.0;
        }
        let root = disc.sqrt();
        [-d0 + root, -d0 - root]
            .into_iter()
            .filter(|u| *u > 0.0 && *u < span)
            .map(|u| d0 + u)
            .fold(0.0, f64::max)
    }

    /// A uniform object: the same contact `length` at every depth.
    pub fn uniform(length: f64, height: f64, half_width: f64) -> Result<Self, InvalidSetting> {
        Self::new(vec![0.0], vec![length], height, half_width)
    }

    /// The profile of `mesh` for a knife moving down in the plane x = 0: at
    /// depth d below the top, the length of edge in contact is the chord of
    /// the object's silhouette in the knife plane at height top − d (a
    /// straight, horizontal edge's view; a curved edge touches a little
    /// less). Depths are below the silhouette's top, where the edge first
    /// touches and the plant measures its depth from (an eggplant's highest
    /// point need not lie on it). The section height is the silhouette's and
    /// the half width half the object's extent across the knife plane (x),
    /// as a vision system would report them ([`for_surrogate`](Self::for_surrogate)
    /// narrows it to the equivalent rectangle's).
    ///
    /// # Errors
    /// The mesh does not cross the knife plane.
    pub fn of_object(mesh: &TriangleMesh) -> Result<Self, InvalidSetting> {
        let (lo, hi) = mesh.bounds();
        let silhouette = knife_plane_silhouette(mesh).ok_or_else(|| {
            InvalidSetting::new("object", "mesh", "does not cross the knife plane x = 0")
        })?;
        let (bottom, top) = {
            let (a, b) = silhouette.bounds();
            (a.y, b.y)
        };
        let height = top - bottom;
        // Just below the top (the chord at the very top is a point) to just
        // above the board.
        let depths: Vec<f64> = (0..OBJECT_SAMPLES)
            .map(|i| height * (0.005 + 0.99 * i as f64 / (OBJECT_SAMPLES - 1) as f64))
            .collect();
        let lengths = depths
            .iter()
            .map(|d| silhouette.chord_length(top - d))
            .collect();
        Self::new(depths, lengths, height, 0.5 * (hi.x - lo.x))
    }

    /// [`of_object`](Self::of_object) as `surrogate` takes it: the section's
    /// half width is that of the rectangle equivalent to the object's crest
    /// section ([`equivalent_half_width`]: the rectangle of the same height
    /// that the section model presses to `depth` with the same work), cut
    /// and clipped as the plant does (`rim_fraction`,
    /// `PlantSettings::rim_fraction`), for the surrogate's own material and
    /// blade (what the controller knows, not the plant's material) and the
    /// `section` settings. The surrogates are fitted on rectangles; a
    /// cuboid's section is its own equivalent, a half ellipsoid's crest
    /// section maps to a narrower one (docs/controllers.md, "Which
    /// section").
    ///
    /// # Errors
    /// As [`of_object`](Self::of_object), or the section model cannot cut
    /// the crest section.
    pub fn for_surrogate(
        mesh: &TriangleMesh,
        surrogate: &Surrogate,
        section: &SectionSettings,
        rim_fraction: f64,
        depth: f64,
    ) -> Result<Self, InvalidSetting> {
        let profile = Self::of_object(mesh)?;
        let section_error =
            |e: SectionError| InvalidSetting::new("object", "crest section", e.to_string());
        let crest = crest_section(mesh, rim_fraction).map_err(section_error)?;
        let half_width = equivalent_half_width(
            &crest,
            &surrogate.material,
            &surrogate.blade.section(),
            section,
            depth,
        )
        .map_err(section_error)?;
        profile.with_half_width(half_width)
    }

    /// The same profile with the contact lengths of the knife's own edge
    /// (`outline`, the task's [`EdgeOutline`]) with its frame origin at world
    /// z = `knife_z` (m): at each sampled depth h, the length of edge inside
    /// the outline with the edge's deepest penetration h, the knife lowered
    /// h below its touch height there ([`EdgeOutline::touch_height`],
    /// [`EdgeOutline::contact_length`]). [`of_object`](Self::of_object)'s
    /// chord is what a straight horizontal edge presses; a chef's edge whose
    /// rise lies over the object meets it at one point and takes in its
    /// length more slowly (docs/heldout.md, "The contact under the knife's
    /// own edge"). The sampled depths, the height and the half width are
    /// kept.
    ///
    /// # Errors
    /// No edge point lies over the outline with the origin at `knife_z`.
    pub fn under_edge(self, outline: &EdgeOutline, knife_z: f64) -> Result<Self, InvalidSetting> {
        let touch = outline.touch_height(knife_z).ok_or_else(|| {
            InvalidSetting::new(
                "knife_z",
                knife_z,
                "a knife position with some edge over the object's outline",
            )
        })?;
        let lengths = self
            .depths
            .iter()
            .map(|h| outline.contact_length(knife_z, touch - h))
            .collect();
        Self::new(self.depths, lengths, self.height, self.half_width)
    }

    /// The same profile with the section's half width `half_width` (m; e.g.
    /// the equivalent rectangle's of a section of another shape).
    ///
    /// # Errors
    /// `half_width` is not finite or is negative.
    pub fn with_half_width(self, half_width: f64) -> Result<Self, InvalidSetting> {
        if !(half_width.is_finite() && half_width >= 0.0) {
            return Err(InvalidSetting::new(
                "depth_profile.half_width",
                half_width,
                "finite and >= 0",
            ));
        }
        Ok(Self { half_width, ..self })
    }

    /// Length of edge in contact with the edge at `depth`, m.
    pub fn contact_length(&self, depth: f64) -> f64 {
        let d = &self.depths;
        let l = &self.contact_lengths;
        if depth <= d[0] {
            return l[0];
        }
        let last = d.len() - 1;
        if depth >= d[last] {
            return l[last];
        }
        self.length_within(d.partition_point(|x| *x <= depth) - 1, depth)
    }

    /// ∫₀^depth L(h) dh, m²: the area of the cut face the edge has swept.
    fn swept_area(&self, depth: f64) -> f64 {
        let d = &self.depths;
        let l = &self.contact_lengths;
        if depth <= d[0] {
            return depth.max(0.0) * l[0];
        }
        let last = d.len() - 1;
        if depth >= d[last] {
            return self.areas[last] + (depth - d[last]) * l[last];
        }
        let i = d.partition_point(|x| *x <= depth) - 1;
        self.area_within(i, depth, self.length_within(i, depth))
    }

    /// The edge's mean depth in the sections in contact when it is `depth`
    /// below the top, m: ∫₀^depth L(h) dh / L(depth). A section at a point
    /// of the edge whose surface lies h below the top has the edge
    /// depth − h into it, and the points with h ≤ depth make up L(depth);
    /// averaged over them this is the swept area over the contact length
    /// (`depth` itself where the contact does not change with depth, 2/3 of
    /// it where L ∝ √depth, as near a dome's crest). Every section's own
    /// depth advances with the knife, so this is the state one section's
    /// model evaluates, while work per unit of the knife's depth is L·w.
    /// `depth` where nothing is in contact.
    pub fn section_depth(&self, depth: f64) -> f64 {
        mean_depth(self.swept_area(depth), self.contact_length(depth), depth)
    }

    /// The edge's depth below the top at which the sections' mean depth
    /// ([`section_depth`](Self::section_depth)) is `section_depth`, m: the
    /// least such depth. Before the first sample the mean depth is the
    /// edge's, and beyond the last it trails it by a constant, so there it
    /// is exact; otherwise it lies in the first interval of samples whose
    /// largest mean depth reaches `section_depth` (each interval's largest
    /// is kept: at its ends or [`interior_peak`](Self::interior_peak)),
    /// and there, from the larger of the interval's start and
    /// `section_depth`, the mean depth is A/L, which reaches it once, at
    /// the root of a quadratic (L linear, A its integral; by bisection to 1
    /// nm should rounding put the root outside the interval). Allocates
    /// nothing: the MPC's planner calls it for every depth of the onset's
    /// cost.
    pub fn edge_depth_at(&self, section_depth: f64) -> f64 {
        let target = section_depth.max(0.0);
        let (d, l) = (&self.depths, &self.contact_lengths);
        let last = d.len() - 1;
        let i = self.reached.partition_point(|&m| m < target);
        if i == 0 {
            // At or before the first sample: L is constant, A/L = depth.
            return target;
        }
        if i > last {
            // Beyond the last sample: A/L = A_last/L_last + depth − d_last.
            return if l[last] > 0.0 {
                target.max(target - self.areas[last] / l[last] + d[last])
            } else {
                target
            };
        }
        let mut lo = target.max(d[i - 1]);
        if self.section_depth_within(i, lo) >= target {
            return lo;
        }
        let mut hi = d[i];
        // A(x) − target·L(x) = s·u²/2 + (L₀ − target·s)·u + A₀ − target·L₀
        // (u = x − d[i − 1], s = L′): negative at `lo`, not at `hi`, one
        // root between (the quadratic formula in the form that does not
        // cancel); bisection if rounding puts it outside.
        let slope = (l[i] - l[i - 1]) / (d[i] - d[i - 1]);
        let (a, b, c) = (
            0.5 * slope,
            l[i - 1] - target * slope,
            self.areas[i - 1] - target * l[i - 1],
        );
        let root = if a == 0.0 {
            -c / b
        } else {
            let q = -0.5 * (b + b.signum() * (b * b - 4.0 * a * c).max(0.0).sqrt());
            let (u1, u2) = (q / a, c / q);
            let inside = |u: f64| (lo - 1e-12..=hi + 1e-12).contains(&(d[i - 1] + u));
            if inside(u1) { u1 } else { u2 }
        };
        let x = d[i - 1] + root;
        if x.is_finite() && (lo..=hi).contains(&x) {
            return x;
        }
        while hi - lo > 1e-9 {
            let mid = 0.5 * (lo + hi);
            if self.section_depth_within(i, mid) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }

    /// Length of edge in contact when the sections' mean depth is
    /// `section_depth`, m.
    pub fn contact_at_section_depth(&self, section_depth: f64) -> f64 {
        self.contact_length(self.edge_depth_at(section_depth))
    }

    /// Section height at the cut, m.
    pub fn height(&self) -> f64 {
        self.height
    }

    /// Section half width, m.
    pub fn half_width(&self) -> f64 {
        self.half_width
    }
}

/// The mean depth A/L of the sections in contact at edge depth `depth`
/// (swept area `area`, contact `length`), at most `depth`; `depth` where
/// nothing is in contact.
fn mean_depth(area: f64, length: f64, depth: f64) -> f64 {
    if length > 0.0 {
        (area / length).min(depth.max(0.0))
    } else {
        depth.max(0.0)
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector2;
    use shearcut_sim::geometry::Polygon;
    use shearcut_sim::{BladeSection, EdgeShape, Knife, KnifePreset, KnifeSettings, SensorMount};

    use super::DepthProfile;
    use crate::observer::EdgeOutline;

    /// A half disc of radius `r` on the board (y = 0), centred at world
    /// z = `zc`: its knife-plane outline.
    fn half_disc(r: f64, zc: f64) -> Polygon {
        Polygon::new(
            (0..=360)
                .map(|k| {
                    let a = std::f64::consts::PI * k as f64 / 360.0;
                    Vector2::new(zc + r * a.cos(), r * a.sin())
                })
                .collect(),
        )
    }

    #[test]
    fn a_straight_edge_takes_in_the_chord_and_a_rising_edge_less() {
        let r = 0.03;
        let disc = half_disc(r, 0.1);
        let depths: Vec<f64> = (1..=20).map(|k| k as f64 * 1e-3).collect();
        let chord = |h: f64| 2.0 * (2.0 * r * h - h * h).sqrt();
        let lengths = depths.iter().map(|&h| chord(h)).collect();
        let profile = DepthProfile::new(depths.clone(), lengths, r, r).unwrap();
        let edge_of = |k: KnifePreset| Knife::new(&k.settings()).unwrap().edge().clone();
        // The straight edge over the whole disc (knife frame origin at
        // z = 0: its edge spans world z 0 to 0.2 m) presses the chord. Each
        // end of the contact is placed within half of the edge's sampling
        // (0.5 mm, `EdgeOutline`) where the outline is steep: 0.25 mm.
        let tolerance = 2.5e-4;
        let straight = EdgeOutline::new(&edge_of(KnifePreset::Straight), &disc);
        let under = profile.clone().under_edge(&straight, 0.0).unwrap();
        for &h in &depths {
            let (a, b) = (under.contact_length(h), chord(h));
            assert!((a - b).abs() < tolerance, "{h}: {a} vs {b}");
        }
        // The chef's edge rises over the disc (z 0.07 to 0.13 m: slopes
        // 0.04 to 0.25): it meets the disc on its heel side, below the top,
        // and takes in less of it at every depth until it presses through.
        let chef = EdgeOutline::new(&edge_of(KnifePreset::Chef), &disc);
        let under = profile.clone().under_edge(&chef, 0.0).unwrap();
        for &h in &depths {
            assert!(under.contact_length(h) < chord(h), "{h}");
        }
        // An edge inclined at slope κ meets the disc where its tangent has
        // that slope: h deep below the outline (vertically) it is h·cos φ
        // deep along the normal (tan φ = κ), and its chord is that of a
        // horizontal edge that deep.
        let kappa: f64 = 0.25;
        let inclined = Knife::new(&KnifeSettings {
            edge: EdgeShape::Polyline {
                points: vec![[0.0, 0.0], [0.2, 0.2 * kappa]],
            },
            blade: BladeSection::default(),
            sensor: SensorMount::default(),
        })
        .unwrap();
        let tilted = EdgeOutline::new(inclined.edge(), &disc);
        let under = profile.clone().under_edge(&tilted, 0.0).unwrap();
        let cos_phi = 1.0 / (1.0 + kappa * kappa).sqrt();
        for &h in &depths {
            let (a, b) = (under.contact_length(h), chord(h * cos_phi));
            assert!((a - b).abs() < tolerance, "{h}: {a} vs {b}");
        }
        // Its mean depth in the sections in contact follows its own profile.
        assert!(under.section_depth(0.01) != profile.section_depth(0.01));
        assert_eq!((under.height(), under.half_width()), (r, r));
        // A knife whose edge is nowhere over the object is refused.
        assert!(profile.under_edge(&chef, 1.0).is_err());
    }

    #[test]
    fn constant_contact_keeps_the_edge_depth() {
        let p = DepthProfile::uniform(0.03, 0.025, 0.015).unwrap();
        for d in [0.0, 1e-4, 0.01, 0.02] {
            assert_eq!(p.section_depth(d), d);
        }
    }

    #[test]
    fn contact_growing_with_depth_halves_a_wedge() {
        // L = 2h up to 30 mm (a wedge, apex up): the sections in contact
        // at depth d entered uniformly over [0, d], so their mean depth is
        // d/2, and the mean advances half as fast as the knife.
        let p = DepthProfile::new(vec![0.0, 0.03], vec![0.0, 0.06], 0.03, 0.015).unwrap();
        for d in [1e-3, 0.01, 0.025] {
            assert!((p.section_depth(d) - 0.5 * d).abs() < 1e-15);
        }
        // Beyond the last sample the contact is constant: the mean catches
        // up with the knife at the rate 1.
        let deep = p.section_depth(0.04);
        assert!((deep - (0.5 * 0.03 * 0.06 + 0.01 * 0.06) / 0.06).abs() < 1e-15);
        assert_eq!(p.section_depth(0.0), 0.0);
    }

    #[test]
    fn the_edge_depth_of_a_section_depth_inverts_it() {
        let depths: Vec<f64> = (0..=40).map(|k| k as f64 * 1e-3).collect();
        let lengths: Vec<f64> = depths.iter().map(|h| 0.5 * h.sqrt()).collect();
        let p = DepthProfile::new(depths, lengths, 0.035, 0.03).unwrap();
        for e in [0.0, 1e-4, 0.004, 0.02, 0.039, 0.05] {
            let back = p.edge_depth_at(p.section_depth(e));
            assert!((back - e).abs() < 2e-9, "{e}: {back}");
        }
        let flat = DepthProfile::uniform(0.03, 0.025, 0.015).unwrap();
        assert!((flat.contact_at_section_depth(0.01) - flat.contact_length(0.01)).abs() < 1e-15);
    }

    /// On profiles whose contact grows, shrinks, and grows again (the mean
    /// depth then falls and rises), the edge depth found is the least at
    /// which the mean depth reaches the target, to 1 nm: checked against a
    /// scan of every 0.5 µm below it.
    #[test]
    fn the_edge_depth_found_is_the_least_that_reaches_the_mean_depth() {
        let profiles = [
            // A dome: L ∝ √h.
            (0..=40)
                .map(|k| (k as f64 * 1e-3, 0.5 * (k as f64 * 1e-3).sqrt()))
                .collect::<Vec<_>>(),
            // Wide at the top, narrow below, wide again (a waist).
            vec![
                (0.0, 0.08),
                (0.005, 0.08),
                (0.01, 0.01),
                (0.02, 0.005),
                (0.03, 0.09),
                (0.04, 0.09),
            ],
            // Nothing in contact at first, then a step.
            vec![(0.002, 0.0), (0.004, 0.0), (0.0041, 0.05), (0.03, 0.06)],
        ];
        for samples in profiles {
            let (depths, lengths): (Vec<f64>, Vec<f64>) = samples.into_iter().unzip();
            let p = DepthProfile::new(depths, lengths, 0.04, 0.02).unwrap();
            for k in 0..=120 {
                let target = k as f64 * 0.5e-3;
                let e = p.edge_depth_at(target);
                assert!(p.section_depth(e) >= target - 1e-12, "{target}: {e}");
                let mut x = 0.0;
                while x < e - 1e-9 {
                    assert!(p.section_depth(x) < target, "{target}: {x} < {e}");
                    x += 0.5e-6;
                }
            }
        }
    }

    #[test]
    fn a_new_half_width_is_checked() {
        let p = DepthProfile::uniform(0.03, 0.025, 0.015).unwrap();
        assert_eq!(
            p.clone().with_half_width(0.012).unwrap().half_width(),
            0.012
        );
        let e = p.with_half_width(f64::NAN).unwrap_err();
        assert!(e.to_string().contains("depth_profile.half_width"), "{e}");
    }

    #[test]
    fn a_dome_crest_gives_two_thirds() {
        // L ∝ √h near a crest: mean depth 2/3 of the edge's, sampled finely.
        let depths: Vec<f64> = (0..=2000).map(|k| k as f64 * 1e-5).collect();
        let lengths: Vec<f64> = depths.iter().map(|h| 0.5 * h.sqrt()).collect();
        let p = DepthProfile::new(depths, lengths, 0.035, 0.03).unwrap();
        for d in [0.005, 0.01, 0.019] {
            let ratio = p.section_depth(d) / d;
            assert!((ratio - 2.0 / 3.0).abs() < 2e-3, "{ratio}");
        }
    }
}
