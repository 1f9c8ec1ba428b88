//! The catch-up after the first fracture: the crack's jump ahead of the edge
//! and the knee where the edge reaches the crack tip again.
//!
//! Before the first fracture the section stores the strain energy
//! U* ≈ ½·r(ξ,ν)·R'_c·d* (both forces linear in the depth, onset at d*). At
//! the onset the toughness drops from R'_c to R_c, so the crack runs until the
//! released energy is spent, a jump of about U*/(r·R_c) ≈ ½·(R'_c/R_c)·d*
//! (seed 000 eq. 1 with the knife at rest): millimetres for eggplant
//! (R'_c/R_c = 2–2.5), almost nothing for potato (R'_c = R_c). Until the edge
//! has caught up with the tip the crack does not grow, the knife does no
//! fracture work and feels mostly the friction on the wedge faces; at the
//! knee the edge loads the tip again and steady cutting resumes.
//!
//! The surrogate models the catch-up travel as L(ξ) = d*₀(ξ)·ℓ(ξ) with
//! d*₀ the nominal onset depth and ℓ fitted on [1, λ_H, λ_w, ξ, ξ²] to the
//! knees the full model shows, and the knee as a quintic smooth step
//! g(s) = S₅(x), x = (s − L)/W + ½, rising over W = κ·L + β·h_b centred on
//! the knee (h_b the blade's bevel height: the edge reloads the tip while the
//! bevel is still entering, and the full model's knee is itself spread over
//! about that travel; κ and β are chosen by a grid search in the fit). The
//! gate's centre may lead the knee by a·h_b (x = (s − L + a·h_b)/W + ½, a
//! from the same grid search): the full model's F_n starts to climb before
//! its crack grows again, as the edge loads the material ahead of the tip
//! (`docs/surrogates.md`, "Structure", has the measured lead). g multiplies the fracture term and, with the progress v of the
//! catch-up ([`progress`], C¹: min(s/L, 1) with its corner rounded), enters
//! the face reaction's basis.

use super::jet::Jet;

/// Floor of the catch-up length L, m: no catch-up (the crack does not jump
/// ahead of the edge, e.g. potato) or a fit extrapolated to ℓ ≤ 0.
pub const MIN_CATCH_UP: f64 = 1e-9;

/// Number of terms of [`catch_up_basis`].
pub const CATCH_UP_TERMS: usize = 5;

/// [1, λ_H, λ_w, ξ, ξ²] as jets in ξ: the catch-up length over the onset
/// depth, ℓ = L/d*.
#[inline]
pub fn catch_up_basis(xi: f64, lh: f64, lw: f64) -> [Jet; CATCH_UP_TERMS] {
    [
        Jet::constant(1.0),
        Jet::constant(lh),
        Jet::constant(lw),
        Jet::new(xi, 1.0, 0.0),
        Jet::new(xi * xi, 2.0 * xi, 2.0),
    ]
}

/// [1, λ_H, λ_w, ξ, ξ²] as numbers (for the fit).
#[inline]
pub fn catch_up_values(xi: f64, lh: f64, lw: f64) -> [f64; CATCH_UP_TERMS] {
    catch_up_basis(xi, lh, lw).map(|j| j.v)
}

/// Σ cᵢ·bᵢ over jets.
#[inline]
pub fn dot_jet<const N: usize>(c: &[f64; N], b: &[Jet; N]) -> Jet {
    c.iter()
        .zip(b)
        .fold(Jet::default(), |acc, (c, b)| acc.add(b.scale(*c)))
}

/// Quintic smooth step S₅(x) = 6x⁵ − 15x⁴ + 10x³ on [0, 1] (0 below, 1
/// above) and its first two derivatives (continuous everywhere).
#[inline]
fn smooth_step(x: f64) -> [f64; 3] {
    if x <= 0.0 {
        return [0.0; 3];
    }
    if x >= 1.0 {
        return [1.0, 0.0, 0.0];
    }
    let x2 = x * x;
    let y = 1.0 - x;
    [
        x2 * x * (10.0 - 15.0 * x + 6.0 * x2),
        30.0 * x2 * y * y,
        60.0 * x * y * (1.0 - 2.0 * x),
    ]
}

/// The knee gate g(s) at travel `s` since fracture for catch-up length
/// `length` (a jet in ξ, m) and knee shape `width` = [κ, w_b, a] (w_b and
/// the lead a in m): rising from 0 to 1 over W = κ·L + w_b centred on
/// s = L − a, a little before the crack grows again (the edge loads the
/// material ahead of the tip before the tip moves; so 0 at s = 0 only while
/// W/2 + a < L), as a jet in ξ.
#[inline]
pub fn knee_gate(s: f64, length: Jet, width: [f64; 3]) -> Jet {
    let s = s.max(0.0);
    // x = (s − L + a)/W + ½.
    let w = length.scale(width[0]).add(Jet::constant(width[1]));
    let x = Jet::constant(s + width[2])
        .add(length.scale(-1.0))
        .mul(w.recip())
        .add(Jet::constant(0.5));
    let [f, df, ddf] = smooth_step(x.v);
    x.compose(f, df, ddf)
}

/// Half-width δ of the blend of the catch-up progress into 1, in units of
/// the catch-up length: v(p) follows p = s/L up to 1 − δ and is 1 from
/// 1 + δ on.
pub const PROGRESS_BLEND: f64 = 0.15;

/// The progress of the catch-up v(p), p = s/L: min(p, 1) with its corner
/// rounded by a quadratic over |p − 1| < δ ([`PROGRESS_BLEND`]), so v is C¹
/// (v = p − (p − 1 + δ)²/(4δ) there; value and slope match at both ends)
/// and the ξ- and depth-derivatives of the terms built on it are continuous
/// through the knee. Returns v, v′, v″.
#[inline]
pub fn progress(p: f64) -> [f64; 3] {
    let delta = PROGRESS_BLEND;
    if p <= 1.0 - delta {
        [p, 1.0, 0.0]
    } else if p >= 1.0 + delta {
        [1.0, 0.0, 0.0]
    } else {
        let q = p - 1.0 + delta;
        [
            p - q * q / (4.0 * delta),
            1.0 - q / (2.0 * delta),
            -1.0 / (2.0 * delta),
        ]
    }
}

/// Number of catch-up terms of the post-fracture bases.
pub const KNEE_TERMS: usize = 9;

/// The catch-up terms of the face-reaction basis at travel `s` for catch-up
/// length `length` (a jet in ξ, m) and knee shape `width` ([`knee_gate`]):
/// [g, gλ_H, gλ_w, gξ², v², v⁴, v²ξ², v⁴ξ², (1 − g)ξ²] with g the knee
/// gate and v the C¹ progress of the catch-up ([`progress`]: min(s/L, 1)
/// with a rounded corner), as jets in ξ. The faces' reaction grows as the
/// edge nears the crack tip, at a rate and from a level that depend on ξ
/// (the jump, and so the open crack the wedge follows, is set by the onset
/// at that ξ).
#[inline]
pub fn knee_terms(
    s: f64,
    xi: f64,
    length: Jet,
    width: [f64; 3],
    lh: f64,
    lw: f64,
) -> [Jet; KNEE_TERMS] {
    knee_terms_with(s, Jet::new(xi * xi, 2.0 * xi, 2.0), length, width, lh, lw)
}

/// [`knee_terms`] as jets in any one variable, given ξ² and the catch-up
/// length as jets in it: in ξ (`knee_terms`), or in ℓ = ln(S/T) at fixed ξ
/// (ξ² constant, L ∝ ρ^(−k): the ratio's effect on the knee, module `ratio`).
#[inline]
pub fn knee_terms_with(
    s: f64,
    x2: Jet,
    length: Jet,
    width: [f64; 3],
    lh: f64,
    lw: f64,
) -> [Jet; KNEE_TERMS] {
    let s = s.max(0.0);
    let length = if length.v >= MIN_CATCH_UP {
        length
    } else {
        Jet::constant(MIN_CATCH_UP)
    };
    let g = knee_gate(s, length, width);
    let p = length.recip().scale(s);
    let [f, df, ddf] = progress(p.v);
    let v = p.compose(f, df, ddf);
    let v2 = v.mul(v);
    let v4 = v2.mul(v2);
    let open = Jet::constant(1.0).add(g.scale(-1.0));
    [
        g,
        g.scale(lh),
        g.scale(lw),
        g.mul(x2),
        v2,
        v4,
        v2.mul(x2),
        v4.mul(x2),
        open.mul(x2),
    ]
}

/// The values of [`knee_terms`] for a run with a known catch-up length (no
/// ξ-dependence), for the fit.
#[inline]
pub fn knee_values(
    s: f64,
    xi: f64,
    length: f64,
    width: [f64; 3],
    lh: f64,
    lw: f64,
) -> [f64; KNEE_TERMS] {
    knee_terms(s, xi, Jet::constant(length), width, lh, lw).map(|j| j.v)
}
