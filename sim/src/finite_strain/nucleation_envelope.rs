//! The loads at which the finite-strain slab nucleates a crack, as a closed
//! curve in the plane of the load per unit length of wire (f_n, f_t), scaled
//! by μR: the form in which the cutting model's sections use seed 001's
//! surface-stress criterion for their first fracture
//! ([`FirstFracture::SurfaceStress`](crate::section::FirstFracture)).
//!
//! Seed 001 frames the surface stress around a wire by the scaled load
//! f/(μR) and the ratio f_t/f_n (its Fig. 2 and eq. 4): the stress near a
//! loaded surface is set by the local load, whatever far away supports the
//! body (Saint-Venant), so the nucleation loads scaled by μR carry over
//! from the seed's slab to a section of another size. The indentation depth
//! at nucleation does not (it depends on the whole section's compliance),
//! which is why the envelope is one of loads.
//!
//! The envelope is polar: for the load's direction ψ = atan(|f_t|/f_n) the
//! radius ρ*(ψ) = |f|/(μR) at which σ₁ reaches σ*, linear in ψ between the
//! points of the sweeps it was built from and constant beyond its ends.
//!
//! The directions a sweep reaches are bounded by the wire's friction: where
//! the wire slides along itself, f_t is μ_f times the contact force, so a
//! slab with friction coefficient μ_f = 1 never loads beyond ψ ≈ 47°
//! however steep θ is (θ = 75°, 80° and 85° nucleate at the same load). A
//! slab with a larger coefficient reaches further, and where the wire of
//! both sticks it nucleates at the same loads (docs/seed001.md), so its
//! points beyond the first sweep's last direction extend the same envelope
//! ([`NucleationEnvelope::extended_by`]).

use super::settings::WireSlabSettings;
use super::slab::IndentationRun;

/// Most points of an envelope: the kinematic angles θ = 0, 15, …, 75° of
/// seed 001's sweep and two beyond its sliding limit.
pub const ENVELOPE_POINTS: usize = 8;

/// Nucleation loads per unit length of wire, scaled by μR, by increasing
/// direction ψ = atan(f_t/f_n).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NucleationEnvelope {
    /// (f_n, f_t)/(μR) at nucleation, one point per run, by increasing ψ;
    /// the first `len` are the envelope's.
    pub points: [[f64; 2]; ENVELOPE_POINTS],
    /// Number of points, 2 ..= [`ENVELOPE_POINTS`].
    pub len: usize,
}

/// The direction ψ (rad) and radius ρ of a point (f_n, f_t).
fn polar(p: &[f64; 2]) -> (f64, f64) {
    (p[1].atan2(p[0]), p[0].hypot(p[1]))
}

impl NucleationEnvelope {
    /// The envelope of seed 001's gel (K = 30μ, σ* = 2μ over a surface cell
    /// R/4 across, L = B = 267R, the default [`WireSlabSettings`]): F/(μRh)
    /// with μRh = 0.02625 N. The first six points are the default slab's
    /// (friction coefficient 1 along the wire) at θ = 0, 15, …, 75°, as
    /// printed by `cargo bench -p shearcut-sim --bench finite_strain`; the
    /// last two, at ψ = 54° and 70°, beyond that slab's sliding limit
    /// (ψ = 47°), the same slab's with friction coefficient 3 at θ = 75° and
    /// 85° (docs/seed001.md, "Use in the cutting model").
    pub const SEED_GEL: Self = Self {
        points: [
            [12.604144148954985, 0.0],
            [12.60693420558041, 1.36133361493745],
            [10.33779899564805, 2.4216657830752664],
            [6.7757050891249175, 2.7605035384756924],
            [3.7483313304975185, 2.60986081611155],
            [1.9964397193382817, 2.1713216309807977],
            [1.24184104701702, 1.7375402542361682],
            [0.34153194424079086, 0.9320212383062417],
        ],
        len: ENVELOPE_POINTS,
    };

    /// The envelope of `runs` (2 ..= [`ENVELOPE_POINTS`], each nucleated,
    /// by increasing direction) of a slab with `settings`; `None` otherwise.
    pub fn from_runs(settings: &WireSlabSettings, runs: &[IndentationRun]) -> Option<Self> {
        if runs.len() < 2 {
            return None;
        }
        Self {
            points: [[0.0; 2]; ENVELOPE_POINTS],
            len: 0,
        }
        .extended_by(settings, runs)
    }

    /// This envelope with the points of `runs` of a slab with `settings`
    /// appended; `None` if one did not nucleate, the directions do not
    /// increase past this envelope's last, or there would be more than
    /// [`ENVELOPE_POINTS`].
    pub fn extended_by(
        mut self,
        settings: &WireSlabSettings,
        runs: &[IndentationRun],
    ) -> Option<Self> {
        if self.len + runs.len() > ENVELOPE_POINTS {
            return None;
        }
        let scale = settings.shear_modulus * settings.wire_radius * settings.wire_length;
        for run in runs {
            let n = run.nucleation?;
            self.points[self.len] = [n.force_normal / scale, n.force_tangential / scale];
            self.len += 1;
        }
        self.points[..self.len]
            .windows(2)
            .all(|w| polar(&w[1]).0 > polar(&w[0]).0)
            .then_some(self)
    }

    /// Radius ρ*(ψ) of the envelope in the direction ψ (rad): the scaled
    /// load magnitude |f|/(μR) at which the surface nucleates.
    pub fn radius(&self, direction: f64) -> f64 {
        let points = &self.points[..self.len];
        let first = polar(&points[0]);
        if direction <= first.0 {
            return first.1;
        }
        for w in points.windows(2) {
            let (a, b) = (polar(&w[0]), polar(&w[1]));
            if direction <= b.0 {
                let t = (direction - a.0) / (b.0 - a.0);
                return a.1 + t * (b.1 - a.1);
            }
        }
        polar(&points[self.len - 1]).1
    }

    /// Whether a load per unit length (f_n, f_t) (N/m; f_n pressing into the
    /// surface, f_t along the wire either way) is on or beyond the envelope
    /// scaled by `scale` = μR (N/m: the gel's shear modulus times the wire's
    /// radius). A load that does not press (f_n ≤ 0) never is.
    pub fn reached(&self, force_normal: f64, force_tangential: f64, scale: f64) -> bool {
        if force_normal.is_nan() || force_normal <= 0.0 {
            return false;
        }
        let (f_n, f_t) = (force_normal / scale, force_tangential.abs() / scale);
        f_n.hypot(f_t) >= self.radius(f_t.atan2(f_n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The built-in envelope is a curve of increasing direction, its radius
    /// is the table's at the table's directions and linear between them, and
    /// a load reaches it exactly on it.
    #[test]
    fn envelope_interpolates_its_points() {
        let e = NucleationEnvelope::SEED_GEL;
        let points: Vec<(f64, f64)> = e.points[..e.len].iter().map(polar).collect();
        let polar = points;
        for w in polar.windows(2) {
            assert!(w[1].0 > w[0].0, "{polar:?}");
        }
        for &(psi, rho) in &polar {
            assert!((e.radius(psi) - rho).abs() < 1e-12 * rho);
        }
        let mid = 0.5 * (polar[2].0 + polar[3].0);
        assert!((e.radius(mid) - 0.5 * (polar[2].1 + polar[3].1)).abs() < 1e-12);
        assert_eq!(e.radius(-1.0), polar[0].1);
        assert_eq!(e.radius(1.5), polar[7].1);
        let scale = 35e3 * 150e-6;
        let (psi, rho) = polar[3];
        let f = |s: f64| (s * rho * psi.cos() * scale, s * rho * psi.sin() * scale);
        let (a, b) = f(1.0 + 1e-9);
        assert!(e.reached(a, b, scale));
        assert!(e.reached(a, -b, scale), "either direction along the wire");
        let (a, b) = f(1.0 - 1e-9);
        assert!(!e.reached(a, b, scale));
        assert!(!e.reached(0.0, 1e3, scale), "a load that does not press");
    }
}
