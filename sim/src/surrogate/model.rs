//! The surrogate's data (versioned, serde) and its evaluation.

use serde::{Deserialize, Serialize};

use super::basis::{
    COMPLIANCE_TERMS, DEFLECTION_TERMS, FRICTION_TERMS, KNEE_START, ONSET_TERMS, RAMPS, SIZE_TERMS,
    SPLIT_TERMS, STRAIN_DEPTH_TERMS, STRAIN_TERMS, column_aspect, compliance_basis,
    deflection_basis, dot, drag_basis, friction_basis, knee_derivatives, ramps, size_basis,
    size_features, split_basis, split_basis_slope, strain_basis_rate, strain_depth_rate_basis,
};
use super::catch_up::{
    CATCH_UP_TERMS, KNEE_TERMS, MIN_CATCH_UP, catch_up_basis, dot_jet, knee_terms, knee_terms_with,
};
use super::jet::Jet;
use super::output::{QuadraticModel, ScaledParts, SurrogateOutput};
use super::ratio::{
    RatioCorrection, SLICE_SIZE_TERMS, SLICE_TERMS, corrected, fitted_log_ratio, log_ratio,
    slice_basis, slice_size_basis,
};
use super::state::{CutState, ScaleFactors};
use super::toughness::ToughnessRatio;
use crate::blade::BladeSection;
use crate::material::Material;

/// Version of the surrogate file format this build writes (and reads, with
/// [`OLDEST_READ_FORMAT_VERSION`]).
pub const SURROGATE_FORMAT_VERSION: u32 = 4;

/// The oldest surrogate file format this build reads. Format 3 lacked the
/// ratio corrections (`[ratio]`) and its compliances and onset stiffness
/// the column term H/w (three and six coefficients where format 4 has four
/// and eight): its coefficients mean something else, so it is refused with
/// a refit hint.
pub const OLDEST_READ_FORMAT_VERSION: u32 = 4;

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

impl FitRange {
    /// Whether a section of `height` × `half_width` (m) lies within the
    /// fitted sizes (bounds included, up to a relative 1e-6 for a size
    /// computed from a mesh).
    pub fn covers_section(&self, height: f64, half_width: f64) -> bool {
        let within =
            |x: f64, [lo, hi]: [f64; 2]| (lo * (1.0 - 1e-6)..=hi * (1.0 + 1e-6)).contains(&x);
        within(height, self.height) && within(half_width, self.half_width)
    }
}

/// Fitted coefficients before the first fracture (basis functions in
/// `basis`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PreFracture {
    /// C_n = E·d/F_n, the indentation compliance times E, on
    /// [1, λ_H, λ_w, H/w].
    pub normal_compliance: [f64; COMPLIANCE_TERMS],
    /// C_t = G·ξ·d/F_t, the antiplane drag compliance times G, on
    /// [1, λ_H, λ_w, H/w].
    pub tangential_compliance: [f64; COMPLIANCE_TERMS],
    /// Surface deflection per depth, on [1, λ_H, λ_w].
    pub deflection: [f64; SIZE_TERMS],
    /// r(ξ,ν)·R'_c/(E·d*) on [1, λ_H, λ_w, H/w, ξ², ξ²λ_H, ξ²λ_w, ξ²H/w].
    pub onset: [f64; ONSET_TERMS],
}

impl PreFracture {
    /// (C_n, C_t) of a section with size features `lh`, `lw` and column
    /// aspect `aspect` (`basis::column_aspect`).
    #[inline]
    pub fn compliances(&self, lh: f64, lw: f64, aspect: f64) -> (f64, f64) {
        let c = compliance_basis(lh, lw, aspect);
        (
            dot(&self.normal_compliance, &c),
            dot(&self.tangential_compliance, &c),
        )
    }

    /// The onset stiffness y(ξ) = A + ξ²·B = r(ξ,ν)·R'_c/(E·d*) of a
    /// section: (A, B).
    #[inline]
    pub fn onset_stiffness_terms(&self, lh: f64, lw: f64, aspect: f64) -> (f64, f64) {
        let c = compliance_basis(lh, lw, aspect);
        let o = &self.onset;
        let (a, b) = (0..COMPLIANCE_TERMS).fold((0.0, 0.0), |(a, b), k| {
            (a + o[k] * c[k], b + o[COMPLIANCE_TERMS + k] * c[k])
        });
        (a, b)
    }
}

/// Fitted coefficients after the first fracture.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PostFracture {
    /// ℓ = L/d*₀, the catch-up travel after the crack's first jump over the
    /// nominal onset depth, on [1, λ_H, λ_w, ξ, ξ²] (`catch_up` module).
    pub catch_up: [f64; CATCH_UP_TERMS],
    /// [κ, β]: the knee gate g(s) rises over W = κ·L + β·h_b around the
    /// catch-up length L (h_b the bevel height; both ≥ 0, not both 0).
    pub knee_width: [f64; 2],
    /// a: the knee gate is centred a·h_b before the catch-up length L
    /// (a ≥ 0, in bevel heights; chosen by the fit with the width).
    pub knee_lead: f64,
    /// σ = F_t/F_n of the non-friction force (beyond the drag) on
    /// [ξ, ξλ_H, ξλ_w, ξ², ξ/(1+ξ²)].
    pub split: [f64; SPLIT_TERMS],
    /// Share h(s) of the antiplane drag at onset still held after a travel
    /// s, on the decays [1 − ρ_k(s)] for k < 4.
    pub drag: [f64; RAMPS],
    /// N/(E·Δ), the wedge faces' normal reaction, on the friction basis
    /// [1, λ_H, λ_w, (ρ_k(d), ρ_k(d)λ_H, ρ_k(d)λ_w) for k < 4, d/H, (d/H)³,
    /// (d/H)λ_H, (d/H)λ_w, (g, gλ_H, gλ_w, gξ², v², v⁴, v²ξ², v⁴ξ²,
    /// (1 − g)ξ²)] with the ramps in the depth d (`basis::friction_basis`).
    pub face_reaction: [f64; FRICTION_TERMS],
    /// The strain-energy rate U̇/(E·Δ²) (1/m) on the slopes of
    /// [1, λ_H, λ_w, (ρ_k, ρ_kλ_H, ρ_kλ_w) for k < 4, (d/H)³, (d/H)⁴]:
    /// fitted to the knife's non-friction work per depth beyond r·R_c·g.
    pub strain_energy_rate: [f64; STRAIN_TERMS],
    /// The strain-energy rate U̇/(E·Δ²) (1/m) that stays in steady cutting
    /// (the blade's body holding the faces apart over the cut), on
    /// [1, λ_H, λ_w]/H (`basis::strain_depth_rate_basis`); fitted with
    /// `strain_energy_rate`. Zero when absent from a file, which then gives
    /// the outputs of a surrogate without the term, bit for bit.
    #[serde(default)]
    pub strain_depth_rate: [f64; STRAIN_DEPTH_TERMS],
    /// Surface deflection over Δ on [1, ρ₀, λ_w].
    pub deflection: [f64; DEFLECTION_TERMS],
    /// k: the faces slip along (1, k·ξ)/√(1+k²ξ²) against the blade, so
    /// the friction μN splits as F_n^f = μN/√(1+k²ξ²), F_t^f = k·ξ·F_n^f
    /// and its work per depth is μN·(1+kξ²)/√(1+k²ξ²). k = 1 is the
    /// knife's own direction (1, ξ); k > 1 when the material at the faces
    /// follows the blade down (it slips less vertically than the knife
    /// moves). Fitted to the section's F_t^f against ξ·F_n^f; 1 when absent
    /// from a file, which then gives the outputs of a surrogate without the
    /// term, bit for bit.
    #[serde(default = "unit_slip_ratio")]
    pub slip_ratio: f64,
    /// The face reaction's dependence on ξ in steady cutting, N/(E·Δ) on
    /// [ξ, ξ², ξ/(1+ξ²)] (`ratio::slice_basis`), added to
    /// `face_reaction`: how far the crack runs ahead of the edge depends on
    /// ξ, and the further it leads, the less the bevel presses on the faces
    /// (lowest near ξ = 1; `docs/surrogates.md`, "The normal force's mean
    /// after fracture"), which ξ² alone cannot follow. Zero when absent from
    /// a file, which then gives the outputs of a surrogate without the term.
    #[serde(default)]
    pub face_reaction_slice: [f64; SLICE_TERMS],
}

/// The default [`PostFracture::slip_ratio`]: the knife's own direction.
fn unit_slip_ratio() -> f64 {
    1.0
}

/// The faces' slip direction factors (F_n^f, F_t^f, work per depth) per
/// unit μN as jets in ξ, for a slip ratio k:
/// 1/√(1+k²ξ²), kξ/√(1+k²ξ²) and (1+kξ²)/√(1+k²ξ²).
#[inline]
pub(super) fn slip_direction(xi: f64, slip: f64) -> (Jet, Jet, Jet) {
    let k2 = slip * slip;
    let q = 1.0 + k2 * xi * xi;
    let a = 1.0 / q.sqrt();
    let a3 = a * a * a;
    let a5 = a3 * a * a;
    let normal = Jet::new(a, -k2 * xi * a3, -k2 * a3 + 3.0 * k2 * k2 * xi * xi * a5);
    let x = Jet::new(xi, 1.0, 0.0);
    let tangential = normal.mul(x).scale(slip);
    let work = normal.add(tangential.mul(x));
    (normal, tangential, work)
}

/// What `evaluate` builds on after fracture (see `Surrogate::post_features`).
struct PostFeatures {
    /// The travel ramps ρ_k(s).
    ramp: [f64; RAMPS],
    /// r(ξ,ν) as a jet in ξ.
    r_jet: Jet,
    /// The onset stiffness y(ξ) as a jet.
    y_jet: Jet,
    /// The catch-up terms (the knee gate g first), jets in ξ.
    knee: [Jet; KNEE_TERMS],
    /// Their ℓ-derivatives at fixed ξ (through L ∝ ρ^(−k)).
    knee_l: [f64; KNEE_TERMS],
    /// The face reaction's basis.
    face_basis: [f64; FRICTION_TERMS],
    /// The strain-energy rate's basis.
    strain_basis: [f64; STRAIN_TERMS],
}

/// The wedge's bases after fracture at one ξ and state, for the fit of the
/// ratio corrections.
pub(super) struct WedgeBases {
    /// The face reaction's basis (`basis::friction_basis`).
    pub face: [f64; FRICTION_TERMS],
    /// The nominal face reaction N₀/(E₀Δ), with its ξ-terms.
    pub face_reaction: f64,
    /// The strain-energy rate's basis (`basis::strain_basis_rate`).
    pub strain: [f64; STRAIN_TERMS],
    /// The nominal strain-energy rate U̇₀/(E·Δ²) (1/m), both its parts.
    pub strain_rate: f64,
    /// The knee gate g.
    pub gate: f64,
    /// The ratio corrections' slice terms with sizes
    /// (`ratio::slice_size_basis`).
    pub slice_size: [f64; SLICE_SIZE_TERMS],
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
    /// Weight of the rows that ask the fitted strain-energy rate's mean over
    /// each run's settled window (travel since fracture ≥ 2 mm) to match
    /// the run's (`shearcut fit --window-weight`; 0, the default, adds none).
    /// Recorded so that the fit can be reproduced.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub fit_window_weight: f64,
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
    /// Corrections of the wedge's terms for the stiffness-to-toughness ratio
    /// ρ = S/T (`ratio` module; format 4, zero when absent).
    #[serde(default)]
    pub ratio: RatioCorrection,
}

/// Whether a weight is zero (not written to the file).
fn is_zero(x: &f64) -> bool {
    *x == 0.0
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
        let aspect = column_aspect(state.height, state.half_width, b);
        let r = ToughnessRatio::at(xi, nu);
        let (t, s, f) = (scale.toughness, scale.stiffness, scale.friction);
        let e0 = m.youngs_modulus;
        let g0 = e0 / (2.0 * (1.0 + nu));
        let sizes = size_basis(lh, lw);
        // Onset: r·R'_c/(E·d*) = A + ξ²B.
        let (onset_a, onset_b) = self.pre_fracture.onset_stiffness_terms(lh, lw, aspect);
        let onset_stiffness = self.onset_stiffness(xi, &r, (onset_a, onset_b), state.height);
        let onset_depth = t * r.value * m.initial_fracture_toughness / (s * e0 * onset_stiffness.v);
        let mut out = SurrogateOutput {
            toughness_ratio: r.value,
            toughness_ratio_slope: r.slope,
            fracture_onset_depth: onset_depth,
            ..SurrogateOutput::default()
        };
        if !state.fractured {
            let d = state.depth.max(0.0);
            let (c_n, c_t) = self.pre_fracture.compliances(lh, lw, aspect);
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
        let l = log_ratio(t, s);
        let PostFeatures {
            ramp,
            r_jet,
            y_jet,
            knee,
            knee_l,
            face_basis,
            strain_basis,
        } = self.post_features(xi, state, (lh, lw), &r, (onset_a, onset_b), (l, t / s));
        // Nominal face reaction N₀ (a jet: only its catch-up terms depend
        // on ξ) and strain-energy rate U̇₀ per unit travel.
        // Both are corrected for the stiffness-to-toughness ratio ρ = S/T by
        // ℓ = ln ρ (`ratio` module): x₀ + ℓ·x₁ + ℓ²·x₂ with x₁, x₂ on the
        // same bases; exactly x₀ at ℓ = 0. Outside the fitted range of ℓ
        // they continue along their tangents (`ratio::fitted_log_ratio`).
        let l_fit = fitted_log_ratio(t, s);
        let rc = &self.ratio;
        let n_scale = e0 * delta;
        let face_jet = |c: &[f64; FRICTION_TERMS]| {
            let (d, dd) = knee_derivatives(c, &knee);
            Jet::new(dot(c, &face_basis), d, dd).scale(n_scale)
        };
        let slice = slice_basis(xi);
        let n0 = face_jet(&p.face_reaction);
        let n0 = if p.face_reaction_slice == [0.0; SLICE_TERMS] {
            n0
        } else {
            n0.add(dot_jet(&p.face_reaction_slice, &slice).scale(n_scale))
        };
        // The slice factor of N₁ and N₂, with its part ∝ H/w (skipped when
        // zero: files fitted before it evaluate bit for bit as before).
        let slice_size = slice_size_basis(&slice, lh, lw, aspect);
        let slice_factor = |a: &[f64; SLICE_TERMS], column: &[f64; SLICE_SIZE_TERMS]| {
            let f = dot_jet(a, &slice);
            if *column == [0.0; SLICE_SIZE_TERMS] {
                f
            } else {
                f.add(dot_jet(column, &slice_size))
            }
        };
        let n1 = face_jet(&rc.face_reaction_linear).add(n0.mul(slice_factor(
            &rc.face_reaction_slice_linear,
            &rc.face_reaction_slice_size_linear,
        )));
        let n2 = face_jet(&rc.face_reaction_quadratic).add(n0.mul(slice_factor(
            &rc.face_reaction_slice_quadratic,
            &rc.face_reaction_slice_size_quadratic,
        )));
        let (nv, n_l) = corrected(n0.v, n1.v, n2.v, l_fit);
        let (nd, _) = corrected(n0.d, n1.d, n2.d, l_fit);
        let (ndd, _) = corrected(n0.dd, n1.dd, n2.dd, l_fit);
        // ℓ·x₁ + ℓ²·x₂ as the corrections take it.
        let bend = |linear: f64, quadratic: f64| corrected(0.0, linear, quadratic, l_fit).0;
        // The catch-up terms' ℓ-dependence (through L) on every
        // coefficient set: Σ_knee c_k(ℓ)·∂b_k/∂ℓ.
        let knee_dot = |c: &[f64; FRICTION_TERMS]| {
            c[KNEE_START..]
                .iter()
                .zip(&knee_l)
                .map(|(c, b)| c * b)
                .sum::<f64>()
        };
        let slice_v = |a: &[f64; SLICE_TERMS], column: &[f64; SLICE_SIZE_TERMS]| {
            let v = dot(a, &slice.map(|j| j.v));
            if *column == [0.0; SLICE_SIZE_TERMS] {
                v
            } else {
                v + dot(column, &slice_size.map(|j| j.v))
            }
        };
        let n_l = n_l
            + n_scale
                * (knee_dot(&p.face_reaction)
                    * (1.0
                        + bend(
                            slice_v(
                                &rc.face_reaction_slice_linear,
                                &rc.face_reaction_slice_size_linear,
                            ),
                            slice_v(
                                &rc.face_reaction_slice_quadratic,
                                &rc.face_reaction_slice_size_quadratic,
                            ),
                        ))
                    + bend(
                        knee_dot(&rc.face_reaction_linear),
                        knee_dot(&rc.face_reaction_quadratic),
                    ));
        let (n0, n_l) = if nv > 0.0 {
            (Jet::new(nv, nd, ndd), n_l)
        } else {
            (Jet::default(), 0.0)
        };
        let u_scale = e0 * delta * delta;
        let (u_rate0, u_l) = corrected(
            u_scale * self.nominal_strain_rate(&strain_basis, state, lh, lw),
            u_scale * dot(&rc.strain_energy_rate_linear, &strain_basis),
            u_scale * dot(&rc.strain_energy_rate_quadratic, &strain_basis),
            l_fit,
        );
        // Crack growth only once the edge has caught up: r·R_c₀·g.
        let fracture0 = r_jet.mul(knee[0]).scale(m.fracture_toughness);
        let mu0 = m.friction_coefficient;
        // Drag held at the onset, released over the first few h_b: per unit
        // toughness factor Q(ξ)·h(s), Q = G₀ξ·r·R'_c₀/(C_t·E₀·y(ξ)).
        let (_, c_t) = self.pre_fracture.compliances(lh, lw, aspect);
        let y = y_jet.v;
        let dy = y_jet.d;
        let k = g0 * m.initial_fracture_toughness / (c_t * e0);
        let q = k * xi * r.value / y;
        let dq = k * ((r.value + xi * r.slope) / y - xi * r.value * dy / (y * y));
        let decays = drag_basis(&ramp);
        let (h, h_l) = corrected(
            dot(&p.drag, &decays),
            dot(&rc.drag_linear, &decays),
            dot(&rc.drag_quadratic, &decays),
            l_fit,
        );
        let drag0 = q * h;
        let ddrag0 = dq * h;
        // Non-friction force: the edge at the crack tip takes the fracture
        // work, F_n^e + ξF_t^e = T·r·R_c·g, split F_t^e = σ·F_n^e + drag, so
        // F_n^e = (T·r·R_c·g − ξ·drag)/(1 + ξσ); the wedge opening the faces
        // stores S·U̇₀ and pushes only vertically (tangential travel does
        // not open the faces): F_n^c = F_n^e + S·U̇₀, F_t^c = F_t^e.
        let sigma = dot(&p.split, &split_basis(xi, lh, lw));
        let dsigma = dot(&p.split, &split_basis_slope(xi, lh, lw));
        let den = 1.0 + xi * sigma;
        let dden = sigma + xi * dsigma;
        let tip = fracture0.scale(t);
        let pj = tip.add(Jet::constant(s * u_rate0));
        let drag = t * drag0;
        let ddrag = t * ddrag0;
        let fn_e = (tip.v - xi * drag) / den;
        let dfn_e = (tip.d - drag - xi * ddrag) / den - fn_e * dden / den;
        let fn_c = fn_e + s * u_rate0;
        let dfn_c = dfn_e;
        let ft_c = sigma * fn_e + drag;
        let dft_c = dsigma * fn_e + sigma * dfn_e + ddrag;
        // Friction: μN against the sliding direction (1, ξ)/√(1+ξ²).
        let root = (1.0 + xi * xi).sqrt();
        let root3 = root * root * root;
        let fr0 = n0.scale(mu0);
        let fs = f * s;
        out.fracture = t * fracture0.v;
        out.strain = s * u_rate0;
        // The faces' slip (1, k·ξ)/√(1+k²ξ²) (`PostFracture::slip_ratio`):
        // the parts' friction factors of F_n, F_t and the work per unit μN.
        let slip = p.slip_ratio;
        let friction_factors = if slip == 1.0 {
            out.friction = fs * fr0.v * root;
            out.force_normal = fn_c + fs * fr0.v / root;
            out.force_tangential = ft_c + fs * fr0.v * xi / root;
            out.work_per_depth = pj.v + fs * fr0.v * root;
            out.force_normal_slope = dfn_c + fs * (fr0.d / root - fr0.v * xi / root3);
            out.force_tangential_slope = dft_c + fs * (fr0.d * xi / root + fr0.v / root3);
            out.work_per_depth_slope = pj.d + fs * (fr0.d * root + fr0.v * xi / root);
            out.work_per_depth_curvature =
                pj.dd + fs * (fr0.dd * root + 2.0 * fr0.d * xi / root + fr0.v / root3);
            None
        } else {
            let (normal, tangential, work) = slip_direction(xi, slip);
            let (fn_f, ft_f, w_f) = (fr0.mul(normal), fr0.mul(tangential), fr0.mul(work));
            out.friction = fs * w_f.v;
            out.force_normal = fn_c + fs * fn_f.v;
            out.force_tangential = ft_c + fs * ft_f.v;
            out.work_per_depth = pj.v + fs * w_f.v;
            out.force_normal_slope = dfn_c + fs * fn_f.d;
            out.force_tangential_slope = dft_c + fs * ft_f.d;
            out.work_per_depth_slope = pj.d + fs * w_f.d;
            out.work_per_depth_curvature = pj.dd + fs * w_f.dd;
            Some((normal.v, tangential.v, work.v))
        };
        out.deformation = delta * dot(&p.deflection, &deflection_basis(&ramp, lw));
        let (fracture0, fr0) = (fracture0.v, fr0.v);
        let fr_l = mu0 * n_l;
        // Friction parts: (F_n, F_t, work) per unit μN, as the outputs.
        let along = |x: f64| match friction_factors {
            None => (x / root, x * xi / root, x * root),
            Some((n, t, w)) => (x * n, x * t, x * w),
        };
        let (fr_n, fr_t, fr_w) = along(fr0);
        let (fr_l_n, fr_l_t, fr_l_w) = along(fr_l);
        let fn_t = (fracture0 - xi * drag0) / den;
        let drag_l = q * h_l;
        // The gate's ℓ-dependence through L: ∂(r·R_c₀·g)/∂ℓ.
        let fracture_l = r.value * m.fracture_toughness * knee_l[0];
        let fn_t_l = (fracture_l - xi * drag_l) / den;
        out.force_normal_parts = ScaledParts {
            by_toughness: fn_t,
            by_toughness_log_ratio_slope: fn_t_l,
            by_stiffness: u_rate0,
            by_friction_stiffness: fr_n,
            by_stiffness_log_ratio_slope: u_l,
            by_friction_stiffness_log_ratio_slope: fr_l_n,
        };
        out.force_tangential_parts = ScaledParts {
            by_toughness: sigma * fn_t + drag0,
            by_toughness_log_ratio_slope: sigma * fn_t_l + drag_l,
            by_stiffness: 0.0,
            by_friction_stiffness: fr_t,
            by_stiffness_log_ratio_slope: 0.0,
            by_friction_stiffness_log_ratio_slope: fr_l_t,
        };
        out.work_per_depth_parts = ScaledParts {
            by_toughness: fracture0,
            by_toughness_log_ratio_slope: fracture_l,
            by_stiffness: u_rate0,
            by_friction_stiffness: fr_w,
            by_stiffness_log_ratio_slope: u_l,
            by_friction_stiffness_log_ratio_slope: fr_l_w,
        };
        out
    }

    /// The onset stiffness y(ξ) = A + ξ²B = r(ξ,ν)·R'_c₀/(E₀·d*₀) as a jet
    /// in ξ, held at least r·R'_c₀/(E₀·H): the nominal onset depth d*₀ is
    /// at most the section height `height` (the crack starts before the
    /// edge reaches the board). Within the fitted sizes d*₀ is well under
    /// H (`docs/surrogates.md`, "File format") and the bound never holds;
    /// beyond them the linear fit in
    /// (λ_H, λ_w, H/w) can reach zero (tall narrow sections, H/w ≳ 10, or
    /// sections of metres), where an unbounded d*₀ made the forces infinite.
    #[inline]
    fn onset_stiffness(
        &self,
        xi: f64,
        r: &ToughnessRatio,
        (onset_a, onset_b): (f64, f64),
        height: f64,
    ) -> Jet {
        let m = &self.material;
        let height = height.max(self.blade.edge_width);
        let fitted = Jet::new(
            onset_a + xi * xi * onset_b,
            2.0 * xi * onset_b,
            2.0 * onset_b,
        );
        let floor = Jet::new(r.value, r.slope, r.curvature)
            .scale(m.initial_fracture_toughness / (m.youngs_modulus * height));
        if fitted.v >= floor.v { fitted } else { floor }
    }

    /// The features after fracture that `evaluate` builds on, at one ξ and
    /// state (`lh`, `lw` the size features, `r` eq. 6 at ξ, `onset_stiffness`
    /// y(ξ) of the onset, `l` = ln ρ and `ratio_inverse` = 1/ρ = T/S).
    #[inline]
    fn post_features(
        &self,
        xi: f64,
        state: &CutState,
        (lh, lw): (f64, f64),
        r: &ToughnessRatio,
        (onset_a, onset_b): (f64, f64),
        (l, ratio_inverse): (f64, f64),
    ) -> PostFeatures {
        let m = &self.material;
        let p = &self.post_fracture;
        let b = self.blade.edge_width;
        let e0 = m.youngs_modulus;
        let travel = state.travel_since_fracture.max(0.0);
        let (ramp, ramp_slope) = ramps(travel, self.bevel_height());
        let (ramp_depth, _) = ramps(state.depth, self.bevel_height());
        let height = state.height.max(b);
        let depth_ratio = (state.depth / height).clamp(0.0, 1.0);
        // Catch-up after the crack's jump (`catch_up`): L = d*₀(ξ)·ℓ(ξ) at
        // nominal material (so the parts stay linear in the factors), with
        // d*₀ = r·R'_c₀/(E₀·y), y = A + ξ²B; the knee gate g(s) and the
        // catch-up terms of the face reaction, as jets in ξ.
        let r_jet = Jet::new(r.value, r.slope, r.curvature);
        let y_jet = self.onset_stiffness(xi, r, (onset_a, onset_b), state.height);
        let onset0 = r_jet
            .mul(y_jet.recip())
            .scale(m.initial_fracture_toughness / e0);
        let length = onset0.mul(dot_jet(&p.catch_up, &catch_up_basis(xi, lh, lw)));
        // L ∝ ρ^(−k) (`ratio`): exactly the nominal L at ℓ = 0 or k = 0.
        let k = self.ratio.catch_up_exponent;
        let length = if l == 0.0 || k == 0.0 {
            length
        } else {
            // ρ^(−k); T/S itself for the shipped k = 1 (no exp).
            length.scale(if k == 1.0 {
                ratio_inverse
            } else {
                (-k * l).exp()
            })
        };
        let knee_width = [
            p.knee_width[0],
            p.knee_width[1] * self.bevel_height(),
            p.knee_lead * self.bevel_height(),
        ];
        let knee = knee_terms(travel, xi, length, knee_width, lh, lw);
        let knee_v = knee.map(|j| j.v);
        // ∂/∂ℓ of the catch-up terms at fixed ξ: dL/dℓ = −k·L.
        // Zero without a catch-up (L below the floor: `knee_terms` holds
        // it constant), e.g. potato.
        let knee_l = if k == 0.0 || length.v < MIN_CATCH_UP {
            [0.0; KNEE_TERMS]
        } else {
            let big_l = length.v;
            knee_terms_with(
                travel,
                Jet::constant(xi * xi),
                Jet::new(big_l, -k * big_l, k * k * big_l),
                knee_width,
                lh,
                lw,
            )
            .map(|j| j.d)
        };
        PostFeatures {
            ramp,
            r_jet,
            y_jet,
            knee,
            knee_l,
            face_basis: friction_basis(&ramp_depth, depth_ratio, &knee_v, lh, lw),
            strain_basis: strain_basis_rate(&ramp_slope, depth_ratio, height, lh, lw),
        }
    }

    /// The bases of the wedge's terms after fracture as `evaluate` takes
    /// them at ξ, `state` and ℓ = ln(S/T) (its own catch-up length at that
    /// ratio and knee), with the knee gate g: the rows of the ratio
    /// corrections' fit.
    pub(super) fn wedge_bases(&self, xi: f64, state: &CutState, l: f64) -> WedgeBases {
        let xi = xi.abs();
        let (lh, lw) = size_features(state.height, state.half_width, self.blade.edge_width);
        let r = ToughnessRatio::at(xi, self.material.poisson_ratio);
        let aspect = column_aspect(state.height, state.half_width, self.blade.edge_width);
        let onset = self.pre_fracture.onset_stiffness_terms(lh, lw, aspect);
        let f = self.post_features(xi, state, (lh, lw), &r, onset, (l, (-l).exp()));
        let slice = slice_basis(xi).map(|j| j.v);
        WedgeBases {
            face_reaction: dot(&self.post_fracture.face_reaction, &f.face_basis)
                + dot(&self.post_fracture.face_reaction_slice, &slice),
            face: f.face_basis,
            strain: f.strain_basis,
            strain_rate: self.nominal_strain_rate(&f.strain_basis, state, lh, lw),
            gate: f.knee[0].v,
            slice_size: slice_size_basis(&slice_basis(xi), lh, lw, aspect).map(|j| j.v),
        }
    }

    /// The nominal strain-energy rate U̇₀/(E·Δ²) (1/m): the wedge's part on
    /// `strain_basis` plus the steady part on [1, λ_H, λ_w]/H
    /// (`strain_depth_rate`, skipped when zero, so that a file without the
    /// term evaluates bit for bit as the surrogate without it).
    #[inline]
    pub(super) fn nominal_strain_rate(
        &self,
        strain_basis: &[f64; STRAIN_TERMS],
        state: &CutState,
        lh: f64,
        lw: f64,
    ) -> f64 {
        let p = &self.post_fracture;
        let wedge = dot(&p.strain_energy_rate, strain_basis);
        if p.strain_depth_rate == [0.0; STRAIN_DEPTH_TERMS] {
            return wedge;
        }
        let height = state.height.max(self.blade.edge_width);
        wedge
            + dot(
                &p.strain_depth_rate,
                &strain_depth_rate_basis(height, lh, lw),
            )
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
