//! Contact of the blade wedge with the crack faces and Coulomb friction
//! (DESIGN §3.2a).
//!
//! The wedge faces push each crack face (a node of the cut line above the
//! tip) out to at least the blade's half-thickness w(s) — unilateral
//! contact: a face that would be pulled onto the blade is released and left
//! free (active set in `equilibrium::evaluate`) — at its height s above the
//! blade's reference point, from [`BladeSection::half_thickness_at`]. The
//! reference point is the crack tip while the edge presses on the material
//! below it (that material, and the faces next to it, have been carried down
//! with the edge by the indentation: measuring from the undeformed edge
//! position instead would make a crack that starts after a deep indentation
//! open at once to the full blade width), and the edge itself when the crack
//! runs ahead of it; the two coincide when the indentation is zero.
//!
//! The blade's corner between the edge flat and the faces is resolved over one
//! row spacing h: ŵ(s) = (s/h)·w(h) for 0 ≤ s < h, w(s) above, so the opening
//! is continuous as the tip or the edge passes a node.
//!
//! Friction: Coulomb, μ times the face's normal force, against the blade's
//! sliding velocity relative to the face. A face inclined at the bevel slope
//! s = w' has in-plane tangent (sinθ, cosθ) with tanθ = s; the blade's velocity
//! (0, −v_n, v_t) slides along it at √(v_n² cos²θ + v_t²). The friction
//! resisting the knife then has vertical part μN v_n cos²θ/|v_s| and
//! tangential part μN v_t/|v_s| (so slicing lowers the vertical friction,
//! seed 000 §V.A). Friction is applied to the knife and dissipated; its
//! traction on the faces is not fed back into the elastic solution (a
//! first-order-in-μ model: the feedback changes the normal pressure, hence the
//! friction, by a term of order μ²).

use crate::blade::BladeSection;

/// The blade's profile as seen by the crack faces.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WedgeProfile {
    corner: f64,
    half_edge: f64,
    slope: f64,
    half_thickness: f64,
    bevel_height: f64,
}

impl WedgeProfile {
    /// The profile of `blade` with its corner resolved over `corner` (m).
    pub fn new(blade: &BladeSection, corner: f64) -> Self {
        Self {
            corner,
            half_edge: 0.5 * blade.edge_width,
            slope: blade.bevel_angle.tan(),
            half_thickness: 0.5 * blade.thickness,
            bevel_height: blade.bevel_height(),
        }
    }

    /// Half-thickness w(s) of the blade at height s above the edge, m.
    #[inline]
    fn blade_width(&self, s: f64) -> f64 {
        (self.half_edge + s * self.slope).min(self.half_thickness)
    }

    /// Opening ŵ(s) of a face at height s above the reference point (0 below
    /// it; linear over the corner), m.
    #[inline]
    pub fn width(&self, s: f64) -> f64 {
        if s <= 0.0 {
            0.0
        } else if s < self.corner {
            s / self.corner * self.blade_width(self.corner)
        } else {
            self.blade_width(s)
        }
    }

    /// Heights above the reference point where ŵ has a kink (end of the
    /// corner, end of the bevel), m; the third kink is s = 0.
    pub fn kinks(&self) -> [f64; 2] {
        [self.corner, self.bevel_height]
    }

    /// Slope ŵ'(s) of the face (the corner's, the bevel's, or 0).
    #[inline]
    pub fn slope(&self, s: f64) -> f64 {
        if s <= 0.0 {
            0.0
        } else if s < self.corner {
            self.blade_width(self.corner) / self.corner
        } else if s < self.bevel_height {
            self.slope
        } else {
            0.0
        }
    }
}

/// The slip of the blade along a face of one slope for knife increments
/// (dn, dt), from which [`FaceSlip::friction`] gives the friction forces:
/// what the faces of the same slope share, computed once for them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FaceSlip {
    /// cos²θ = 1/(1 + s²) of the face's inclination.
    cos2: f64,
    /// Slip per step |v_s| = √(dn² cos²θ + dt²), m.
    slip: f64,
}

impl FaceSlip {
    /// The slip of a face of slope `slope` for knife increments (dn, dt).
    #[inline]
    pub fn new(slope: f64, dn: f64, dt: f64) -> Self {
        let cos2 = 1.0 / (1.0 + slope * slope);
        let slip = (dn * dn * cos2 + dt * dt).sqrt();
        Self { cos2, slip }
    }

    /// Friction forces (vertical, tangential) resisting the knife from a
    /// face normal force `normal` (N/m) for the knife increments (dn, dt)
    /// the slip was made for, N/m. Zero when the knife does not move.
    #[inline]
    pub fn friction(&self, mu: f64, normal: f64, dn: f64, dt: f64) -> (f64, f64) {
        if self.slip == 0.0 {
            return (0.0, 0.0);
        }
        (
            mu * normal * dn * self.cos2 / self.slip,
            mu * normal * dt / self.slip,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn friction_dissipates_mu_n_times_slip() {
        // Dissipation F_n dn + F_t dt = μ N |slip| for any direction.
        for (dn, dt) in [(1.0, 0.0), (1.0, 0.75), (0.2, 1.8)] {
            let s = 0.27;
            let (fv, ft) = FaceSlip::new(s, dn, dt).friction(0.1, 50.0, dn, dt);
            let slip = (dn * dn / (1.0 + s * s) + dt * dt).sqrt();
            assert!((fv * dn + ft * dt - 0.1 * 50.0 * slip).abs() < 1e-12);
        }
    }
}
