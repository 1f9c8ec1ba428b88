//! The stiffness-to-toughness ratio: how the wedge's strain-energy rate and
//! the faces' reaction depart from linear scaling when E/R_c changes.
//!
//! The scale factors T (R_c, R'_c), S (E) and F (μ) enter the surrogate as
//! multipliers, which would make every output after fracture linear in
//! them. That holds for the fracture work (T·r(ξ,ν)·R_c·g, seed 000 eq. 1
//! and 6) but not for the wedge's terms: the faces' reaction and the strain
//! energy the wedge stores depend on how far the crack runs ahead of the
//! edge, which grows with E·Δ/R_c (a wedge-split crack's lead is of order
//! (E·δ²/R_c)^¼). Dimensional analysis of the section (linear elasticity,
//! the Griffith balance G = R_c of seed 000 eq. 1, Coulomb friction, a fixed
//! blade): scaling E and R_c by the same k scales every force by k, so the
//! departure from linearity is a function of ρ = S/T alone. The surrogate
//! carries it as a polynomial in ℓ = ln ρ:
//!
//!   U̇₀(ρ) = U̇₀ + ℓ·U̇₁ + ℓ²·U̇₂,  N₀(ρ) = N₀ + ℓ·N₁ + ℓ²·N₂,
//!
//! each correction with its own coefficients on the nominal term's basis
//! (the strain-energy rate's and the face reaction's, `basis`), the face
//! reaction's plus a factor of N₀ in ξ ([`slice_basis`]: the departure is
//! strongest for steep slices, which the nominal basis barely resolves in
//! ξ), fitted to
//! the residuals of full-model sweeps at E × 0.5 and E × 2 against the
//! nominal surrogate (`fit::fit_ratio_correction`). At ρ = 1 (ℓ = 0, any
//! T = S) the corrections vanish and the surrogate is the nominal one bit
//! for bit.

use serde::{Deserialize, Serialize};

use super::basis::{FRICTION_TERMS, RAMPS, STRAIN_TERMS};
use super::jet::Jet;

/// Number of terms of [`slice_basis`].
pub const SLICE_TERMS: usize = 3;

/// Number of terms of [`slice_size_basis`].
pub const SLICE_SIZE_TERMS: usize = 3 * SLICE_TERMS;

/// [φ_j·λ_H, φ_j·λ_w, φ_j·H/w] for the jets φ of [`slice_basis`] (λ_H, λ_w
/// the size features and H/w the column aspect, `basis::size_features`,
/// `basis::column_aspect`): the slice factor of the face reaction's ratio
/// correction, by section size
/// ([`RatioCorrection::face_reaction_slice_size_linear`]).
#[inline]
pub fn slice_size_basis(
    slice: &[Jet; SLICE_TERMS],
    lh: f64,
    lw: f64,
    aspect: f64,
) -> [Jet; SLICE_SIZE_TERMS] {
    let mut b = [Jet::default(); SLICE_SIZE_TERMS];
    for (j, phi) in slice.iter().enumerate() {
        b[3 * j] = phi.scale(lh);
        b[3 * j + 1] = phi.scale(lw);
        b[3 * j + 2] = phi.scale(aspect);
    }
    b
}

/// [ξ, ξ², ξ/(1+ξ²)] as jets in ξ: how the faces' reaction's departure
/// from linear scaling depends on the slice-push ratio, as a factor of the
/// nominal reaction N₀ (the full model's friction against linear scaling
/// per ξ: `docs/surrogates.md`, "The stiffness-to-toughness ratio"). No
/// constant: N₀ itself is a combination of the face basis.
#[inline]
pub fn slice_basis(xi: f64) -> [Jet; SLICE_TERMS] {
    let q = 1.0 + xi * xi;
    [
        Jet::new(xi, 1.0, 0.0),
        Jet::new(xi * xi, 2.0 * xi, 2.0),
        Jet::new(
            xi / q,
            (1.0 - xi * xi) / (q * q),
            2.0 * xi * (xi * xi - 3.0) / (q * q * q),
        ),
    ]
}

/// The corrections of the wedge's terms for the stiffness-to-toughness
/// ratio ρ = S/T, as coefficients on the nominal terms' bases (file format
/// 4, table `[ratio]`; a file without the table reads as zero
/// correction).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RatioCorrection {
    /// U̇₁/(E·Δ²): the strain-energy rate's coefficient of ℓ = ln ρ, on the
    /// basis of `post_fracture.strain_energy_rate` (1/m).
    pub strain_energy_rate_linear: [f64; STRAIN_TERMS],
    /// U̇₂/(E·Δ²): its coefficient of ℓ², same basis (1/m).
    pub strain_energy_rate_quadratic: [f64; STRAIN_TERMS],
    /// N₁/(E·Δ): the faces' normal reaction's coefficient of ℓ, on the
    /// basis of `post_fracture.face_reaction` (dimensionless).
    pub face_reaction_linear: [f64; FRICTION_TERMS],
    /// N₂/(E·Δ): its coefficient of ℓ², same basis (dimensionless).
    pub face_reaction_quadratic: [f64; FRICTION_TERMS],
    /// The part of N₁ proportional to the nominal reaction:
    /// N₁ += N₀·Σ a_j·φ_j(ξ) with φ = [ξ, ξ², ξ/(1+ξ²)] ([`slice_basis`]).
    pub face_reaction_slice_linear: [f64; SLICE_TERMS],
    /// The same for N₂.
    pub face_reaction_slice_quadratic: [f64; SLICE_TERMS],
    /// The part of N₁'s slice factor that depends on the section's size:
    /// N₁ += N₀·Σ c_k·ψ_k with ψ = φ_j(ξ)·[λ_H, λ_w, H/w]
    /// ([`slice_size_basis`]). How much steeper slices lower the faces'
    /// reaction at another ρ depends on the section: the crack's lead over
    /// the edge grows steeply with ρ, by how much depends on how stiff the
    /// halves are, which their size sets as it sets the compliances
    /// (`basis::compliance_basis`; measured in `docs/surrogates.md`, "The
    /// friction's mean at other ratios, and the depth it is evaluated at").
    /// Zero when absent from a file, which then gives the outputs of a
    /// surrogate without the term.
    #[serde(default)]
    pub face_reaction_slice_size_linear: [f64; SLICE_SIZE_TERMS],
    /// The same for N₂.
    #[serde(default)]
    pub face_reaction_slice_size_quadratic: [f64; SLICE_SIZE_TERMS],
    /// h₁: the share of the onset's drag still held after a travel s,
    /// h(s) + ℓ·h₁(s) + ℓ²·h₂(s), coefficient of ℓ on the decays of
    /// `post_fracture.drag` (the drag is released over a travel that grows
    /// with the onset depth, ∝ T/S).
    pub drag_linear: [f64; RAMPS],
    /// h₂: the same, coefficient of ℓ².
    pub drag_quadratic: [f64; RAMPS],
    /// k: the catch-up length scales as L = L₀·ρ^(−k) (L₀ the nominal one,
    /// `catch_up` module). The crack's jump at the onset is ≈ ½·(R'_c/R_c)·d*
    /// and the onset depth d* ∝ T/S exactly, so `fit` writes k = 1 (not
    /// fitted); 0 (a file without `[ratio]`) keeps L at its nominal value.
    pub catch_up_exponent: f64,
}

impl RatioCorrection {
    /// Whether every coefficient is zero (a file without `[ratio]`, or a fit without
    /// off-nominal sweeps): the surrogate is then linear in T, S and F·S.
    pub fn is_zero(&self) -> bool {
        self.strain_energy_rate_linear
            .iter()
            .chain(&self.strain_energy_rate_quadratic)
            .chain(&self.face_reaction_linear)
            .chain(&self.face_reaction_quadratic)
            .chain(&self.face_reaction_slice_linear)
            .chain(&self.face_reaction_slice_quadratic)
            .chain(&self.face_reaction_slice_size_linear)
            .chain(&self.face_reaction_slice_size_quadratic)
            .chain(&self.drag_linear)
            .chain(&self.drag_quadratic)
            .chain(std::iter::once(&self.catch_up_exponent))
            .all(|&c| c == 0.0)
    }
}

/// ℓ = ln(S/T), the log of the stiffness-to-toughness ratio of the scale
/// factors: exactly 0 whenever `stiffness == toughness` (including the
/// default factors), so the ratio terms then drop out bit for bit.
#[inline]
pub fn log_ratio(toughness: f64, stiffness: f64) -> f64 {
    if stiffness == toughness {
        0.0
    } else {
        (stiffness / toughness).ln()
    }
}

/// The range of ℓ = ln ρ the corrections are fitted over: the sweeps at
/// E × 0.5 and × 2 (`campaign::RATIO_STIFFNESS_FACTORS`).
pub const FITTED_LOG_RATIO: [f64; 2] = [-std::f64::consts::LN_2, std::f64::consts::LN_2];

/// The corrections' ℓ at the factors (T, S), split into the part within
/// the fitted range [`FITTED_LOG_RATIO`] and the excess beyond it (0
/// inside). Beyond the range a correction is continued along its tangent at
/// the range's end ([`corrected`]) rather than along its quadratic: the
/// quadratic is fitted over ±ln 2 only, and an estimator's first guesses
/// can pass far beyond, where the extrapolated quadratic drives the
/// estimate to its bounds; a correction held constant there would leave
/// no gradient in ℓ, and the estimate would stick at the range's end
/// (`docs/surrogates.md`, "The stiffness-to-toughness ratio").
#[inline]
pub fn fitted_log_ratio(toughness: f64, stiffness: f64) -> (f64, f64) {
    let l = log_ratio(toughness, stiffness);
    let [lo, hi] = FITTED_LOG_RATIO;
    let inside = l.clamp(lo, hi);
    (inside, l - inside)
}

/// A nominal term x₀ corrected for the ratio, x₀ + ℓ·x₁ + ℓ²·x₂, and its
/// ℓ-derivative x₁ + 2ℓ·x₂, at ℓ = `l` + `beyond` with `l` within the
/// fitted range and `beyond` the excess ([`fitted_log_ratio`]): beyond the
/// range the value continues along the tangent at its end. At ℓ = 0 the
/// value is x₀ itself (not x₀ + 0, which would turn −0 into +0).
#[inline]
pub fn corrected(nominal: f64, linear: f64, quadratic: f64, (l, beyond): (f64, f64)) -> (f64, f64) {
    if l == 0.0 {
        (nominal, linear)
    } else {
        let slope = linear + 2.0 * l * quadratic;
        (
            nominal + l * (linear + l * quadratic) + beyond * slope,
            slope,
        )
    }
}
