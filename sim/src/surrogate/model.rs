//! The surrogate's data (versioned, serde) and its evaluation.

use serde::{Deserialize, Serialize};

use super::basis::{
    DEFLECTION_TERMS, ONSET_TERMS, POST_TERMS, RAMPS, SIZE_TERMS, SPLIT_TERMS, deflection_basis,
    dot, drag_basis, friction_basis, onset_basis, onset_basis_slope, ramps, size_basis,
    size_features, split_basis, split_basis_slope, strain_basis_rate,
};
use super::output::{QuadraticModel, ScaledParts, SurrogateOutput};
use super::state::{CutState, ScaleFactors};
use super::toughness::ToughnessRatio;
use crate::blade::BladeSection;
use crate::material::Material;

/// Version of the surrogate file format this build reads and writes.
pub const SURROGATE_FORMAT_VERSION: u32 = 1;

/// The blade section a surrogate was fitted for (all fields required in a file).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FittedBlade {
    /// Full blade thickness, m.
    pub thickness: f64,
    /// Bevel angle of each face to the mid-plane, rad.
    pub bevel_angle: f64,
    /// Width of the edge flat, m.
    pub edge_width: f64,
}

impl From<BladeSection> for FittedBlade {
    fn from(b: BladeSection) -> Self {
        Self {
            thickness: b.thickness,
            bevel_angle: b.bevel_angle,
            edge_width: b.edge_width,
        }
    }
}

impl FittedBlade {
    /// As a [`BladeSection`].
    pub fn section(&self) -> BladeSection {
        BladeSection {
            thickness: self.thickness,
            bevel_angle: self.bevel_angle,
            edge_width: self.edge_width,
        }
    }
}

/// The ranges the surrogate was fitted over; outside them it extrapolates.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FitRange {
    /// Largest slice-push ratio of the sweeps (the smallest is 0).
    pub xi_max: f64,
    /// Smallest and largest section height, m.
    pub height: [f64; 2],
    /// Smallest and largest section half width, m.
    pub half_width: [f64; 2],
}

/// Fitted coefficients before the first fracture (basis functions in
/// `basis`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PreFracture {
    /// C_n = E·d/F_n, the indentation compliance times E, on [1, λ_H, λ_w].
    pub normal_compliance: [f64; SIZE_TERMS],
    /// C_t = G·ξ·d/F_t, the antiplane drag compliance times G, on [1, λ_H, λ_w].
    pub tangential_compliance: [f64; SIZE_TERMS],
    /// Surface deflection per depth, on [1, λ_H, λ_w].
    pub deflection: [f64; SIZE_TERMS],
    /// r(ξ,ν)·R'_c/(E·d*) on [1, λ_H, λ_w, ξ², ξ²λ_H, ξ²λ_w].
    pub onset: [f64; ONSET_TERMS],
}

/// Fitted coefficients after the first fracture.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PostFracture {
    /// σ(ξ) = F_t/F_n of the non-friction force (beyond the drag) on [ξ, ξ²].
    pub split: [f64; SPLIT_TERMS],
    /// Share h(s) of the antiplane drag at onset still held after a travel
    /// s, on the decays [1 − ρ_k(s)] for k < 4.
    pub drag: [f64; RAMPS],
    /// N/(E·Δ), the wedge faces' normal reaction, on the friction basis
    /// [1, λ_H, λ_w, (ρ_k, ρ_kλ_H, ρ_kλ_w) for k < 4, d/H, (d/H)³].
    pub face_reaction: [f64; POST_TERMS],
    /// The strain-energy rate U̇/(E·Δ²) (1/m) on the slopes of
    /// [1, λ_H, λ_w, (ρ_k, ρ_kλ_H, ρ_kλ_w) for k < 4, (d/H)³, (d/H)⁴]: fitted
    /// to the knife's non-friction work per depth beyond r·R_c.
    pub strain_energy_rate: [f64; POST_TERMS],
    /// Surface deflection over Δ on [1, ρ₀, λ_w].
    pub deflection: [f64; DEFLECTION_TERMS],
}

/// A fitted surrogate of the cross-section model for one material and blade
/// (DESIGN §3.4). Stored as TOML (see [`Surrogate::from_path`]); evaluated by
/// [`Surrogate::evaluate`] without allocating.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Surrogate {
    /// File format version, [`SURROGATE_FORMAT_VERSION`].
    pub version: u32,
    /// Material preset name the sweeps used.
    pub material_name: String,
    /// Knife preset name. Only its blade section enters the sections, so
    /// knives with the same blade have the same coefficients.
    pub knife_name: String,
    /// Nominal material (the scale factors multiply it).
    pub material: Material,
    /// The blade section.
    pub blade: FittedBlade,
    /// Fitted ranges.
    pub range: FitRange,
    /// Before the first fracture.
    pub pre_fracture: PreFracture,
    /// After the first fracture.
    pub post_fracture: PostFracture,
}

impl Surrogate {
    /// The blade's half-thickness Δ, m.
    #[inline]
    fn half_thickness(&self) -> f64 {
        0.5 * self.blade.thickness
    }

    /// Height of the blade's bevel, m.
    #[inline]
    fn bevel_height(&self) -> f64 {
        self.blade.section().bevel_height()
    }

    /// Evaluates every output and its ξ-derivatives. Allocation-free.
    ///
    /// `xi` is |ξ| (the sign of the tangential motion does not change the
    /// mechanics). Depth, height and half width are clamped to be
    /// non-negative and at least the edge width respectively.
    pub fn evaluate(&self, xi: f64, state: &CutState, scale: &ScaleFactors) -> SurrogateOutput {
        let xi = xi.abs();
        let m = &self.material;
        let nu = m.poisson_ratio;
        let b = self.blade.edge_width;
        let (lh, lw) = size_features(state.height, state.half_width, b);
        let r = ToughnessRatio::at(xi, nu);
        let (t, s, f) = (scale.toughness, scale.stiffness, scale.friction);
        let e0 = m.youngs_modulus;
        let g0 = e0 / (2.0 * (1.0 + nu));
        let sizes = size_basis(lh, lw);
        // Onset: r·R'_c/(E·d*) = A + ξ²B.
        let onset_stiffness = dot(&self.pre_fracture.onset, &onset_basis(xi, lh, lw));
        let onset_depth = t * r.value * m.initial_fracture_toughness
            / (s * e0 * onset_stiffness.max(f64::MIN_POSITIVE));
        let mut out = SurrogateOutput {
            toughness_ratio: r.value,
            toughness_ratio_slope: r.slope,
            fracture_onset_depth: onset_depth,
            ..SurrogateOutput::default()
        };
        if !state.fractured {
            let d = state.depth.max(0.0);
            let c_n = dot(&self.pre_fracture.normal_compliance, &sizes);
            let c_t = dot(&self.pre_fracture.tangential_compliance, &sizes);
            let k_n = e0 * d / c_n;
            let k_t = g0 * d / c_t;
            out.force_normal = s * k_n;
            out.force_tangential = s * k_t * xi;
            out.work_per_depth = s * (k_n + xi * xi * k_t);
            out.strain = out.work_per_depth;
            out.deformation = d * dot(&self.pre_fracture.deflection, &sizes);
            out.force_tangential_slope = s * k_t;
            out.work_per_depth_slope = 2.0 * s * xi * k_t;
            out.work_per_depth_curvature = 2.0 * s * k_t;
            out.force_normal_parts.by_stiffness = k_n;
            out.force_tangential_parts.by_stiffness = k_t * xi;
            out.work_per_depth_parts.by_stiffness = k_n + xi * xi * k_t;
            return out;
        }
        let p = &self.post_fracture;
        let delta = self.half_thickness();
        let travel = state.travel_since_fracture.max(0.0);
        let (ramp, ramp_slope) = ramps(travel, self.bevel_height());
        let depth_ratio = (state.depth / state.height.max(b)).clamp(0.0, 1.0);
        // Nominal face reaction N₀ and strain-energy rate U̇₀ (per unit travel).
        let n0 = e0
            * delta
            * dot(
                &p.face_reaction,
                &friction_basis(&ramp, depth_ratio, lh, lw),
            );
        let n0 = n0.max(0.0);
        let u_rate0 = e0
            * delta
            * delta
            * dot(
                &p.strain_energy_rate,
                &strain_basis_rate(&ramp_slope, depth_ratio, state.height.max(b), lh, lw),
            );
        let fracture0 = r.value * m.fracture_toughness;
        let mu0 = m.friction_coefficient;
        // Drag held at the onset, released over the first few h_b: per unit
        // toughness factor Q(ξ)·h(s), Q = G₀ξ·r·R'_c₀/(C_t·E₀·y(ξ)).
        let c_t = dot(&self.pre_fracture.tangential_compliance, &sizes);
        let y = onset_stiffness.max(f64::MIN_POSITIVE);
        let dy = dot(&self.pre_fracture.onset, &onset_basis_slope(xi, lh, lw));
        let k = g0 * m.initial_fracture_toughness / (c_t * e0);
        let q = k * xi * r.value / y;
        let dq = k * ((r.value + xi * r.slope) / y - xi * r.value * dy / (y * y));
        let h = dot(&p.drag, &drag_basis(&ramp));
        let drag0 = q * h;
        let ddrag0 = dq * h;
        // Non-friction force: F_n^c + ξF_t^c = P = T·r·R_c + S·U̇₀ and
        // F_t^c = σ(ξ)·F_n^c + drag, so F_n^c = (P − ξ·drag)/(1 + ξσ).
        let sigma = dot(&p.split, &split_basis(xi));
        let dsigma = dot(&p.split, &split_basis_slope(xi));
        let den = 1.0 + xi * sigma;
        let dden = sigma + xi * dsigma;
        let pv = t * fracture0 + s * u_rate0;
        let dpv = t * r.slope * m.fracture_toughness;
        let drag = t * drag0;
        let ddrag = t * ddrag0;
        let fn_c = (pv - xi * drag) / den;
        let dfn_c = (dpv - drag - xi * ddrag) / den - fn_c * dden / den;
        let ft_c = sigma * fn_c + drag;
        let dft_c = dsigma * fn_c + sigma * dfn_c + ddrag;
        // Friction: μN against the sliding direction (1, ξ)/√(1+ξ²).
        let root = (1.0 + xi * xi).sqrt();
        let root3 = root * root * root;
        let fr0 = mu0 * n0;
        let fs = f * s;
        out.fracture = t * fracture0;
        out.strain = s * u_rate0;
        out.friction = fs * fr0 * root;
        out.force_normal = fn_c + fs * fr0 / root;
        out.force_tangential = ft_c + fs * fr0 * xi / root;
        out.work_per_depth = pv + fs * fr0 * root;
        out.force_normal_slope = dfn_c - fs * fr0 * xi / root3;
        out.force_tangential_slope = dft_c + fs * fr0 / root3;
        out.work_per_depth_slope = dpv + fs * fr0 * xi / root;
        out.work_per_depth_curvature = t * r.curvature * m.fracture_toughness + fs * fr0 / root3;
        out.deformation = delta * dot(&p.deflection, &deflection_basis(&ramp, lw));
        let fn_t = (fracture0 - xi * drag0) / den;
        let fn_s = u_rate0 / den;
        out.force_normal_parts = ScaledParts {
            by_toughness: fn_t,
            by_stiffness: fn_s,
            by_friction_stiffness: fr0 / root,
        };
        out.force_tangential_parts = ScaledParts {
            by_toughness: sigma * fn_t + drag0,
            by_stiffness: sigma * fn_s,
            by_friction_stiffness: fr0 * xi / root,
        };
        out.work_per_depth_parts = ScaledParts {
            by_toughness: fracture0,
            by_stiffness: u_rate0,
            by_friction_stiffness: fr0 * root,
        };
        out
    }

    /// The quadratic model of work per depth in ξ around `xi` (value, slope,
    /// curvature) for the MPC's depth-indexed stages (DESIGN §4).
    ///
    /// # Convexity
    /// Before fracture work per depth is S·(k_n + ξ²k_t): convex. After it,
    /// T·r(ξ,ν)·R_c + S·U̇ + F·S·μN√(1+ξ²): √(1+ξ²) is convex, but eq. (6) is
    /// concave from ξ = 0 up to ξ_c(ν) ([`concave_up_to`](super::concave_up_to);
    /// ξ_c ≈ 0.24 for ν = 0.4, 0.32 for ν = 0.35) and convex beyond, so the
    /// work is not convex near pressing unless friction's curvature F·S·μN
    /// outweighs T·R_c·|r''|. The returned curvature is exact and may be
    /// negative; a convex MPC should use `curvature.max(0)` (the model then
    /// over-estimates work between pressing and ξ_c) or the secant.
    pub fn work_quadratic(
        &self,
        xi: f64,
        state: &CutState,
        scale: &ScaleFactors,
    ) -> QuadraticModel {
        let o = self.evaluate(xi, state, scale);
        QuadraticModel {
            value: o.work_per_depth,
            slope: o.work_per_depth_slope,
            curvature: o.work_per_depth_curvature,
        }
    }
}
