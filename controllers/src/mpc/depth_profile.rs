//! How much edge is in contact, and the section's size, as the cut deepens.

use shearcut_sim::InvalidSetting;

/// The object as the MPC sees it along the cut: at each crack depth below
/// the top, the length of edge in contact and the section's height and half
/// width. Piecewise linear between samples; constant beyond the ends.
#[derive(Debug, Clone, PartialEq)]
pub struct DepthProfile {
    depths: Vec<f64>,
    contact_lengths: Vec<f64>,
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
        Ok(Self {
            depths,
            contact_lengths,
            height,
            half_width,
        })
    }

    /// A uniform object: the same contact `length` at every depth.
    pub fn uniform(length: f64, height: f64, half_width: f64) -> Result<Self, InvalidSetting> {
        Self::new(vec![0.0], vec![length], height, half_width)
    }

    /// Length of edge in contact at crack depth `depth`, m.
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
        let i = d.partition_point(|x| *x <= depth) - 1;
        let t = (depth - d[i]) / (d[i + 1] - d[i]);
        l[i] + t * (l[i + 1] - l[i])
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
