//! The basis functions of the fitted parts of the surrogate, shared by the
//! fit (`fit`) and the evaluation (`model`). Every fitted function is a
//! linear combination of these, so its coefficients come from linear least
//! squares.
//!
//! Size features: λ_H = ln(H/b) and λ_w = ln(w/b), with H the section height,
//! w its half width and b the blade's edge width. Strip indentation of an
//! elastic body is logarithmic in its size over the strip width (the
//! half-plane compliance 2(1−ν²)ln(L/b)/(πE), DESIGN §3.2), so compliances
//! are linear in these logarithms.
//!
//! Travel features after fracture: smooth ramps ρ_k(s) = 1 − (1 + s/ℓ_k)·
//! exp(−s/ℓ_k) (zero slope at s = 0, steepest at s = ℓ_k, → 1) with the
//! lengths ℓ_k = `RAMP_LENGTHS`[k] × the blade's bevel height h_b: the crack
//! faces are wedged open progressively while the bevel enters the crack and
//! to the full blade thickness once it has passed, so the wedge's load builds
//! up over about h_b. The face reaction takes the same ramps at the edge's
//! depth d instead (the bevel length inside the cut). Depth features: powers
//! of d/H, the stiffening as the crack tip nears the board.

/// Lengths of the travel ramps, in units of the blade's bevel height.
pub const RAMP_LENGTHS: [f64; RAMPS] = [0.3, 0.6, 1.2, 3.0];

/// Number of travel ramps.
pub const RAMPS: usize = 4;

/// Size features of a section: (λ_H, λ_w) = (ln(H/b), ln(w/b)).
#[inline]
pub fn size_features(height: f64, half_width: f64, edge_width: f64) -> (f64, f64) {
    (
        (height.max(edge_width) / edge_width).ln(),
        (half_width.max(edge_width) / edge_width).ln(),
    )
}

/// The column aspect H/w of a section (both at least the edge width `b`,
/// as in [`size_features`]).
///
/// Under the edge the load spreads over the section's width 2w and then
/// compresses (or, antiplane, shears) a column of that width over the rest
/// of its height, a compliance ∝ H/(2w) on top of the logarithmic one of the
/// spreading (how well the compliances follow the section model with and
/// without it: `docs/surrogates.md`, "Structure").
#[inline]
pub fn column_aspect(height: f64, half_width: f64, edge_width: f64) -> f64 {
    height.max(edge_width) / half_width.max(edge_width)
}

/// Number of terms of [`size_basis`].
pub const SIZE_TERMS: usize = 3;

/// [1, λ_H, λ_w]: the deflection ratio before fracture.
#[inline]
pub fn size_basis(lh: f64, lw: f64) -> [f64; SIZE_TERMS] {
    [1.0, lh, lw]
}

/// Number of terms of [`compliance_basis`].
pub const COMPLIANCE_TERMS: usize = 4;

/// [1, λ_H, λ_w, H/w]: the indentation compliances before fracture (the
/// spreading under the strip, logarithmic in the size, and the column
/// below it, [`column_aspect`]).
#[inline]
pub fn compliance_basis(lh: f64, lw: f64, aspect: f64) -> [f64; COMPLIANCE_TERMS] {
    [1.0, lh, lw, aspect]
}

/// Number of terms of [`onset_basis`].
pub const ONSET_TERMS: usize = 2 * COMPLIANCE_TERMS;

/// [c, ξ²·c] with c = [`compliance_basis`]: the onset stiffness
/// r(ξ,ν)·R'_c/(E·d*) (the knife work per depth at onset grows as
/// (k_n + ξ²k_t)·d*, both stiffnesses set by the section's size as the
/// compliances are).
#[inline]
pub fn onset_basis(xi: f64, lh: f64, lw: f64, aspect: f64) -> [f64; ONSET_TERMS] {
    let x2 = xi * xi;
    let c = compliance_basis(lh, lw, aspect);
    [
        c[0],
        c[1],
        c[2],
        c[3],
        x2 * c[0],
        x2 * c[1],
        x2 * c[2],
        x2 * c[3],
    ]
}

/// The ramps ρ_k(s) and their slopes ρ_k'(s), for bevel height `h_b`.
#[inline]
pub fn ramps(s: f64, bevel_height: f64) -> ([f64; RAMPS], [f64; RAMPS]) {
    let s = s.max(0.0);
    let mut v = [0.0; RAMPS];
    let mut d = [0.0; RAMPS];
    for k in 0..RAMPS {
        let l = RAMP_LENGTHS[k] * bevel_height;
        let x = s / l;
        let e = (-x).exp();
        v[k] = 1.0 - (1.0 + x) * e;
        d[k] = x * e / l;
    }
    (v, d)
}

use super::catch_up::KNEE_TERMS;
use super::jet::Jet;

/// Number of leading terms the post-fracture bases share: [1, λ_H, λ_w] and
/// [ρ_k, ρ_kλ_H, ρ_kλ_w] for each ramp.
const SHARED_TERMS: usize = 3 + 3 * RAMPS;

/// Number of terms of [`friction_basis`].
pub const FRICTION_TERMS: usize = SHARED_TERMS + 4 + KNEE_TERMS;

/// Index of the first catch-up term in [`friction_basis`].
pub const KNEE_START: usize = FRICTION_TERMS - KNEE_TERMS;

/// Number of terms of [`strain_basis_rate`].
pub const STRAIN_TERMS: usize = SHARED_TERMS + 2;

/// The post-fracture basis [c, cλ_H, cλ_w] (c = `constant`), then
/// [v_k, v_kλ_H, v_kλ_w] for each ramp value (or slope) v_k, then `tail`.
#[inline]
fn post_basis<const N: usize>(
    constant: f64,
    ramp: &[f64; RAMPS],
    tail: &[f64],
    lh: f64,
    lw: f64,
) -> [f64; N] {
    let mut b = [0.0; N];
    b[0] = constant;
    b[1] = constant * lh;
    b[2] = constant * lw;
    for k in 0..RAMPS {
        b[3 + 3 * k] = ramp[k];
        b[4 + 3 * k] = ramp[k] * lh;
        b[5 + 3 * k] = ramp[k] * lw;
    }
    b[SHARED_TERMS..].copy_from_slice(tail);
    b
}

/// The ξ-derivatives of the face reaction with coefficients `c`: only its
/// catch-up terms (jets `knee`) depend on ξ.
#[inline]
pub fn knee_derivatives(c: &[f64; FRICTION_TERMS], knee: &[Jet; KNEE_TERMS]) -> (f64, f64) {
    c[KNEE_START..]
        .iter()
        .zip(knee)
        .fold((0.0, 0.0), |(d, dd), (c, k)| (d + c * k.d, dd + c * k.dd))
}

/// Basis of the wedge faces' normal reaction N/(E·Δ) (Δ the blade's
/// half-thickness): [1, λ_H, λ_w, (ρ_k, ρ_kλ_H, ρ_kλ_w) for k < 4, d/H,
/// (d/H)³, (d/H)λ_H, (d/H)λ_w, (g, gλ_H, gλ_w, gξ², v², v⁴, v²ξ², v⁴ξ²,
/// (1 − g)ξ²)] with the catch-up terms of `catch_up::knee_terms`. The faces
/// are pushed open by Δ, so N scales with E·Δ; it builds up with the length
/// of bevel inside the cut, so the ramps `ramp` are taken at the edge's
/// depth d, not at the travel since fracture (they differ by the onset
/// depth, millimetres for eggplant, where the bevel is partly in when the
/// crack opens); it depends on how stiff the halves are (λ_H, λ_w), grows as
/// the tip nears the board (d/H), grows during the catch-up (v, at a rate
/// that depends on ξ through the jump) and steps up at the knee g, where the
/// edge presses on the crack tip again and squeezes the faces onto the
/// wedge.
#[inline]
pub fn friction_basis(
    ramp: &[f64; RAMPS],
    depth_ratio: f64,
    knee: &[f64; KNEE_TERMS],
    lh: f64,
    lw: f64,
) -> [f64; FRICTION_TERMS] {
    let mut tail = [0.0; FRICTION_TERMS - SHARED_TERMS];
    tail[..4].copy_from_slice(&[
        depth_ratio,
        depth_ratio * depth_ratio * depth_ratio,
        depth_ratio * lh,
        depth_ratio * lw,
    ]);
    tail[4..].copy_from_slice(knee);
    post_basis(1.0, ramp, &tail, lh, lw)
}

/// Basis of the strain-energy rate (N/m) over E·Δ²: the slopes d/dd of the
/// strain energy U/(E·Δ²) on [(ρ_k, ρ_kλ_H, ρ_kλ_w) for k < 4, (d/H)³,
/// (d/H)⁴] along a cut (travel and depth advance together). The ramps'
/// slopes vanish in steady cutting and the depth terms' slopes, 3d²/H³ and
/// 4d³/H⁴, in a deep section, so there this part of dU/dd → 0; the steady
/// part ([`strain_depth_rate_basis`]) decays as 1/H, so dU/dd → 0 only as
/// the section grows (seed 000 eq. 1 with dU → 0). The first three terms
/// are 0 (a constant stores no work).
#[inline]
pub fn strain_basis_rate(
    ramp_slope: &[f64; RAMPS],
    depth_ratio: f64,
    height: f64,
    lh: f64,
    lw: f64,
) -> [f64; STRAIN_TERMS] {
    let q2 = depth_ratio * depth_ratio;
    post_basis(
        0.0,
        ramp_slope,
        &[3.0 * q2 / height, 4.0 * q2 * depth_ratio / height],
        lh,
        lw,
    )
}

/// Number of terms of [`strain_depth_rate_basis`].
pub const STRAIN_DEPTH_TERMS: usize = 3;

/// Basis of the strain-energy rate (N/m) over E·Δ² that stays in steady
/// cutting: the slopes d/dd of U/(E·Δ²) = (d/H)·[1, λ_H, λ_w], i.e.
/// [1, λ_H, λ_w]/H. Behind its bevel the blade's body holds the crack faces
/// apart by 2Δ over the whole cut, so the halves store an energy that grows
/// with the length of cut they are pushed apart over (seed 000 eq. 1: the
/// knife pays dU/dd on top of r·R_c even when the wedge's ramps are done).
/// The section model's dU/dd after the bevel has entered is a level about
/// independent of ξ; the ramps' slopes vanish there, and (d/H)³, (d/H)⁴
/// alone make the fit trade that level against the wedge's entry (measured
/// in `docs/surrogates.md`, "The normal force's mean after fracture").
#[inline]
pub fn strain_depth_rate_basis(height: f64, lh: f64, lw: f64) -> [f64; STRAIN_DEPTH_TERMS] {
    [1.0 / height, lh / height, lw / height]
}

/// Number of terms of the post-fracture deflection basis.
pub const DEFLECTION_TERMS: usize = 3;

/// Basis of the surface deflection after fracture over Δ: [1, ρ₀, λ_w].
#[inline]
pub fn deflection_basis(ramp: &[f64; RAMPS], lw: f64) -> [f64; DEFLECTION_TERMS] {
    [1.0, ramp[0], lw]
}

/// Number of terms of the force split σ = F_t/F_n of the non-friction force.
pub const SPLIT_TERMS: usize = 5;

/// [ξ, ξλ_H, ξλ_w, ξ², ξ/(1+ξ²)]: σ vanishes at pressing; its slope
/// depends on the section, whose antiplane and plane compliances scale
/// differently with its size (as C_t and C_n do before fracture). The full
/// model's σ rises steeply up to ξ ≈ 0.5 and then about linearly
/// (`docs/surrogates.md`, "Structure"), which ξ/(1+ξ²) (slope 1 at 0, flat
/// by ξ = 1) lets the fit follow.
#[inline]
pub fn split_basis(xi: f64, lh: f64, lw: f64) -> [f64; SPLIT_TERMS] {
    [xi, xi * lh, xi * lw, xi * xi, xi / (1.0 + xi * xi)]
}

/// ∂/∂ξ of [`split_basis`].
#[inline]
pub fn split_basis_slope(xi: f64, lh: f64, lw: f64) -> [f64; SPLIT_TERMS] {
    let q = 1.0 + xi * xi;
    [1.0, lh, lw, 2.0 * xi, (1.0 - xi * xi) / (q * q)]
}

/// The decays 1 − ρ_k(s) of the antiplane drag held by the edge at the
/// first fracture: it is released as the wedge takes the crack over.
#[inline]
pub fn drag_basis(ramp: &[f64; RAMPS]) -> [f64; RAMPS] {
    ramp.map(|r| 1.0 - r)
}

/// Σ cᵢ·bᵢ.
#[inline]
pub fn dot<const N: usize>(c: &[f64; N], b: &[f64; N]) -> f64 {
    c.iter().zip(b).map(|(c, b)| c * b).sum()
}
