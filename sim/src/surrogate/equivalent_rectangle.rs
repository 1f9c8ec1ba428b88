//! The rectangle a surrogate, fitted on rectangular sections, stands for
//! when the section has another shape.

use crate::section::{CrossSection, SectionError, SectionGeometry, SectionSettings};
use crate::{BladeSection, Material};

/// Secant iterations at most.
const ITERATIONS: usize = 8;
/// Relative mismatch of the works accepted.
const TOLERANCE: f64 = 1e-4;
/// Knife step of the pressing runs, m (the ratio of two runs with the same
/// step is what counts).
const STEP: f64 = 5e-5;
/// The runs press to at most this fraction of the section's height.
const DEPTH_FRACTION: f64 = 0.8;

/// The half width (m) of the rectangle of `section`'s height whose knife
/// work per unit length, pressing (ξ = 0) to `depth`, equals `section`'s in
/// the section model (seed 000 §III, eqs. 1–5), with the same `material`,
/// `blade` and `settings`.
///
/// The surrogates are fitted on rectangles (`docs/surrogates.md`) and take a
/// section's size as its height and half width. A section narrower at the
/// top than its bounding box is more compliant than the box. The
/// equivalence found pressing holds at other ratios too: it is the
/// shape's, not the ratio's (`docs/controllers.md`, "Which section", has
/// the half potato's figures). A rectangle is its own equivalent (returned
/// without a run); any other section takes three to eleven runs of the
/// section model, pressing to `depth` (`docs/benchmarks.md` for their cost).
///
/// # Errors
/// A section run fails.
pub fn equivalent_half_width(
    section: &SectionGeometry,
    material: &Material,
    blade: &BladeSection,
    settings: &SectionSettings,
    depth: f64,
) -> Result<f64, SectionError> {
    let (box_half_width, height) = (section.half_width(), section.height_at_cut());
    let area = section.area();
    if (area - 2.0 * box_half_width * height).abs() <= 1e-9 * area {
        return Ok(box_half_width);
    }
    let depth = depth.min(DEPTH_FRACTION * height);
    let work = |geometry: &SectionGeometry| -> Result<f64, SectionError> {
        let mut s = CrossSection::new(geometry, material, blade, settings)?;
        s.advance_to(depth, 0.0, STEP)?;
        Ok(s.state().work.knife)
    };
    let target = work(section)?;
    if !(target.is_finite() && target > 0.0) {
        return Err(SectionError::UnsupportedShape(
            "the section takes no work to press: no equivalent rectangle",
        ));
    }
    // ln of the rectangle's work over the section's, at ln w.
    let mismatch = |ln_w: f64| -> Result<f64, SectionError> {
        let rectangle = SectionGeometry::rectangle(2.0 * ln_w.exp(), height)?;
        let m = (work(&rectangle)? / target).ln();
        if m.is_finite() {
            Ok(m)
        } else {
            Err(SectionError::UnsupportedShape(
                "a rectangle took no work to press: no equivalent rectangle",
            ))
        }
    };
    // Secant on ln w from the box and the rectangle of the same area,
    // within [a quarter of the box, the box]; the best iterate if it has
    // not converged.
    let (lo, hi) = ((0.25 * box_half_width).ln(), box_half_width.ln());
    let mut a = (hi, mismatch(hi)?);
    let mut b = ((0.5 * area / height).ln().clamp(lo, hi), 0.0);
    b.1 = mismatch(b.0)?;
    for _ in 0..ITERATIONS {
        if b.1.abs() <= TOLERANCE || b.1 == a.1 {
            break;
        }
        let next = (b.0 - b.1 * (b.0 - a.0) / (b.1 - a.1)).clamp(lo, hi);
        a = b;
        b = (next, mismatch(next)?);
    }
    let best = if a.1.abs() < b.1.abs() { a } else { b };
    Ok(best.0.exp())
}

#[cfg(test)]
mod tests {
    use super::{STEP, equivalent_half_width};
    use crate::section::{CrossSection, SectionGeometry, SectionSettings};
    use crate::{Knife, KnifePreset, MaterialPreset};

    /// The half potato's crest section: a half ellipse 35 mm high, 60 mm
    /// wide, at the default section settings (the plant's).
    #[test]
    fn a_half_ellipse_maps_to_a_narrower_rectangle_with_the_same_work() {
        let material = MaterialPreset::PotatoWhole.material();
        let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
        let settings = SectionSettings::default();
        let (h, w) = (0.035, 0.03);
        let ellipse: Vec<[f64; 2]> = (0..=64)
            .map(|i| {
                let x = -w + 2.0 * w * f64::from(i) / 64.0;
                [x, h * (1.0 - (x / w).powi(2)).max(0.0).sqrt()]
            })
            .collect();
        let section = SectionGeometry::from_polygon(&ellipse).unwrap();
        let depth = 0.025;
        let eq =
            equivalent_half_width(&section, &material, knife.blade(), &settings, depth).unwrap();
        // Narrower than the box, wider than the rectangle of the same area
        // (π/4 of the box): the top, where the ellipse is narrow, is a
        // small part of what the knife deforms.
        let ratio = eq / w;
        assert!(
            ratio > std::f64::consts::FRAC_PI_4 && ratio < 0.97,
            "{ratio}"
        );
        // And its pressing work is the ellipse's, within the tolerance.
        let work = |g: &SectionGeometry| {
            let mut s = CrossSection::new(g, &material, knife.blade(), &settings).unwrap();
            s.advance_to(depth, 0.0, STEP).unwrap();
            s.state().work.knife
        };
        let rectangle = SectionGeometry::rectangle(2.0 * eq, h).unwrap();
        let (a, b) = (work(&section), work(&rectangle));
        assert!((b / a - 1.0).abs() < 1e-3, "{b} vs {a}");
        // What the MPC uses it for: slicing at ξ = 0.6, the forces past
        // the first fracture (means over the same depths) match the half
        // ellipse's within 2.5 % (measured: F_n −1.7 %, F_t +0.05 % at
        // 0.883 of the width, this unclipped polygon's equivalent); the
        // bounding box's are 3 % and 7 % above (docs/controllers.md,
        // "Which section").
        let forces = |g: &SectionGeometry| {
            let mut s = CrossSection::new(g, &material, knife.blade(), &settings).unwrap();
            let (mut sum, mut n, mut d) = ([0.0; 2], 0, 0.0);
            while d < depth {
                let o = s.advance(STEP, 0.6 * STEP).unwrap();
                d += STEP;
                if o.fractured && d > 0.005 {
                    // Past the first fracture's transient (it comes at
                    // about 1 mm).
                    sum[0] += o.force_vertical;
                    sum[1] += o.force_tangential;
                    n += 1;
                }
            }
            sum.map(|x| x / f64::from(n))
        };
        let (e, r) = (forces(&section), forces(&rectangle));
        assert!(
            (r[0] / e[0] - 1.0).abs() < 0.025,
            "F_n {} vs {}",
            r[0],
            e[0]
        );
        assert!(
            (r[1] / e[1] - 1.0).abs() < 0.025,
            "F_t {} vs {}",
            r[1],
            e[1]
        );
        let bounding = forces(&SectionGeometry::rectangle(2.0 * w, h).unwrap());
        assert!(bounding[0] / e[0] > 1.02 && bounding[1] / e[1] > 1.04);
    }

    #[test]
    fn a_rectangle_is_its_own_equivalent() {
        let material = MaterialPreset::PotatoCuboid.material();
        let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
        let r = SectionGeometry::rectangle(0.03, 0.025).unwrap();
        let w = equivalent_half_width(
            &r,
            &material,
            knife.blade(),
            &SectionSettings::default(),
            0.02,
        )
        .unwrap();
        assert_eq!(w, 0.015);
    }
}
