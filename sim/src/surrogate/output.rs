//! What one surrogate evaluation returns.

/// An output split into the parts multiplied by each scale factor, at the
/// scale factors it was evaluated at:
/// `value = toughness·by_toughness + stiffness·by_stiffness + friction·stiffness·by_friction_stiffness`
/// (friction forces are μ times a normal reaction that scales with E, so
/// their part is bilinear). [`combine`](Self::combine) with the same factors
/// returns the output exactly.
///
/// The parts depend on the ratio ρ = S/T through
/// ℓ = ln ρ (the wedge's strain-energy rate and the faces' reaction, module
/// `ratio`; none without a `[ratio]` table), so the output is linear
/// in the factors only along a ray of constant ρ. The `*_log_ratio_slope`
/// fields are ∂/∂ℓ of those parts, from which an estimator that
/// re-linearises at its current factors forms ∂value/∂T and ∂value/∂S
/// ([`toughness_derivative`](Self::toughness_derivative),
/// [`stiffness_derivative`](Self::stiffness_derivative)). Of the toughness
/// part only the drag the edge still holds after the onset depends on ρ (it
/// is released over a travel that grows with the onset depth ∝ T/S); the
/// fracture work T·r·R_c·g is exactly ∝ T.
///
/// Before the first fracture the forces are `stiffness·by_stiffness` (the
/// other parts and the slopes 0) but whether the section has fractured, and
/// the onset depth ∝ toughness/stiffness, are not linear: an estimator uses
/// the parts at the current phase.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ScaledParts {
    /// Part multiplied by the toughness factor.
    pub by_toughness: f64,
    /// Part multiplied by the stiffness factor.
    pub by_stiffness: f64,
    /// Part multiplied by the product friction × stiffness.
    pub by_friction_stiffness: f64,
    /// ∂by_toughness/∂ℓ, ℓ = ln(stiffness/toughness), same unit as the
    /// part (the drag the edge still holds from the onset; 0 for the work).
    pub by_toughness_log_ratio_slope: f64,
    /// ∂by_stiffness/∂ℓ, ℓ = ln(stiffness/toughness), same unit as the part.
    pub by_stiffness_log_ratio_slope: f64,
    /// ∂by_friction_stiffness/∂ℓ, ℓ = ln(stiffness/toughness), same unit as
    /// the part.
    pub by_friction_stiffness_log_ratio_slope: f64,
}

impl ScaledParts {
    /// Each part and slope with its field's name.
    fn named(&self) -> [(&'static str, f64); 6] {
        [
            ("by_toughness", self.by_toughness),
            ("by_stiffness", self.by_stiffness),
            ("by_friction_stiffness", self.by_friction_stiffness),
            (
                "by_toughness_log_ratio_slope",
                self.by_toughness_log_ratio_slope,
            ),
            (
                "by_stiffness_log_ratio_slope",
                self.by_stiffness_log_ratio_slope,
            ),
            (
                "by_friction_stiffness_log_ratio_slope",
                self.by_friction_stiffness_log_ratio_slope,
            ),
        ]
    }

    /// The output for the given factors, with the parts as evaluated (exact
    /// at the factors of the evaluation; elsewhere the linearisation that
    /// holds ρ's effect fixed).
    #[inline]
    pub fn combine(&self, toughness: f64, stiffness: f64, friction: f64) -> f64 {
        toughness * self.by_toughness
            + stiffness * self.by_stiffness
            + friction * stiffness * self.by_friction_stiffness
    }

    /// ∂value/∂ℓ at the factors (T, S, F) of the evaluation:
    /// T·∂by_toughness/∂ℓ + S·∂by_stiffness/∂ℓ + F·S·∂by_friction_stiffness/∂ℓ.
    #[inline]
    pub fn log_ratio_derivative(&self, toughness: f64, stiffness: f64, friction: f64) -> f64 {
        toughness * self.by_toughness_log_ratio_slope
            + stiffness
                * (self.by_stiffness_log_ratio_slope
                    + friction * self.by_friction_stiffness_log_ratio_slope)
    }

    /// ∂value/∂T at the factors (T, S, F) of the evaluation:
    /// by_toughness − (1/T)·∂value/∂ℓ (ℓ = ln S − ln T).
    #[inline]
    pub fn toughness_derivative(&self, toughness: f64, stiffness: f64, friction: f64) -> f64 {
        self.by_toughness - self.log_ratio_derivative(toughness, stiffness, friction) / toughness
    }

    /// ∂value/∂S at the factors (T, S, F) of the evaluation:
    /// by_stiffness + F·by_friction_stiffness + (1/S)·∂value/∂ℓ.
    #[inline]
    pub fn stiffness_derivative(&self, toughness: f64, stiffness: f64, friction: f64) -> f64 {
        self.by_stiffness
            + friction * self.by_friction_stiffness
            + self.log_ratio_derivative(toughness, stiffness, friction) / stiffness
    }

    /// ∂value/∂F at the factors of the evaluation: S·by_friction_stiffness
    /// (μ enters the faces' reaction only as a multiplier).
    #[inline]
    pub fn friction_derivative(&self, stiffness: f64) -> f64 {
        stiffness * self.by_friction_stiffness
    }
}

/// A quadratic model of a function of ξ around a point ξ₀:
/// f(ξ) ≈ value + slope·(ξ−ξ₀) + ½·curvature·(ξ−ξ₀)².
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct QuadraticModel {
    /// f(ξ₀).
    pub value: f64,
    /// ∂f/∂ξ at ξ₀.
    pub slope: f64,
    /// ∂²f/∂ξ² at ξ₀ (may be negative where f is not convex; see
    /// [`Surrogate::work_quadratic`](super::Surrogate::work_quadratic)).
    pub curvature: f64,
}

/// The surrogate's prediction for one section at one ξ and cut state, per
/// unit length of edge in contact. Forces are those the material exerts on
/// the knife, resistance positive (seed 000's plot convention), N/m.
///
/// Before the first fracture (T, S, F the scale factors, E₀ … nominal):
/// F_n = S·E₀·d/C_n, F_t = S·G₀·ξ·d/C_t (antiplane drag ξ·d at constant ξ),
/// work per depth = F_n + ξF_t, all of it strain energy. After it, with
/// g(s) the knee gate of the catch-up (0 while the edge catches up with a
/// crack that jumped ahead of it, 1 once it cuts), K = T·r(ξ,ν)·R_c₀·g the
/// fracture work, U̇ the wedge's strain-energy rate, D the drag still held
/// from the onset (∝ T) and σ the split:
/// F_n = (K − ξD)/(1+ξσ) + S·U̇ + F·S·μ₀N₀/√(1+ξ²),
/// F_t = σ(K − ξD)/(1+ξσ) + D + F·S·μ₀N₀ξ/√(1+ξ²),
/// work per depth = F_n + ξF_t = K + S·U̇ + F·S·μ₀N₀√(1+ξ²) (N₀ the wedge
/// faces' normal reaction at nominal E; the wedge opens the faces by moving
/// down, so U̇ acts on F_n only). See `docs/surrogates.md` for the fitted
/// functions C_n, C_t, U̇, N₀, σ, D and g.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SurrogateOutput {
    /// Vertical (normal) force F_n, N/m.
    pub force_normal: f64,
    /// Horizontal force along the edge F_t, N/m.
    pub force_tangential: f64,
    /// Knife work per unit of normal travel, J/m per m = N/m: F_n + ξF_t.
    pub work_per_depth: f64,
    /// Of which crack growth: r(ξ,ν)·R_c·g after the first fracture (g the
    /// knee gate of the catch-up), 0 before, N/m.
    pub fracture: f64,
    /// Of which strain energy stored, N/m (after fracture fitted as the
    /// knife's non-friction work beyond r·R_c·g: the energy the wedge stores
    /// opening the faces and the stiffening near the board).
    pub strain: f64,
    /// Of which friction on the wedge faces, N/m.
    pub friction: f64,
    /// Surface deflection next to the blade on the cut line, m (down
    /// positive): the squashing before the first fracture; after it the
    /// (small, often negative: bulging) deflection of the split faces.
    pub deformation: f64,
    /// Depth at which the first fracture happens at this ξ (constant ξ from
    /// the first touch), m.
    pub fracture_onset_depth: f64,
    /// ∂F_n/∂ξ, N/m.
    pub force_normal_slope: f64,
    /// ∂F_t/∂ξ, N/m.
    pub force_tangential_slope: f64,
    /// ∂(work per depth)/∂ξ, N/m.
    pub work_per_depth_slope: f64,
    /// ∂²(work per depth)/∂ξ², N/m.
    pub work_per_depth_curvature: f64,
    /// r(ξ,ν) of seed 000 eq. (6), exact.
    pub toughness_ratio: f64,
    /// ∂r/∂ξ, exact.
    pub toughness_ratio_slope: f64,
    /// F_n split by scale factor.
    pub force_normal_parts: ScaledParts,
    /// F_t split by scale factor.
    pub force_tangential_parts: ScaledParts,
    /// Work per depth split by scale factor.
    pub work_per_depth_parts: ScaledParts,
}

impl SurrogateOutput {
    /// The name of the first output, slope or part that is not finite
    /// (NaN or infinite), in field order; parts as `force_normal_parts.by_stiffness`.
    pub fn first_non_finite(&self) -> Option<String> {
        let scalars = [
            ("force_normal", self.force_normal),
            ("force_tangential", self.force_tangential),
            ("work_per_depth", self.work_per_depth),
            ("fracture", self.fracture),
            ("strain", self.strain),
            ("friction", self.friction),
            ("deformation", self.deformation),
            ("fracture_onset_depth", self.fracture_onset_depth),
            ("force_normal_slope", self.force_normal_slope),
            ("force_tangential_slope", self.force_tangential_slope),
            ("work_per_depth_slope", self.work_per_depth_slope),
            ("work_per_depth_curvature", self.work_per_depth_curvature),
            ("toughness_ratio", self.toughness_ratio),
            ("toughness_ratio_slope", self.toughness_ratio_slope),
        ];
        if let Some((name, _)) = scalars.iter().find(|(_, v)| !v.is_finite()) {
            return Some((*name).to_string());
        }
        [
            ("force_normal_parts", &self.force_normal_parts),
            ("force_tangential_parts", &self.force_tangential_parts),
            ("work_per_depth_parts", &self.work_per_depth_parts),
        ]
        .into_iter()
        .find_map(|(output, parts)| {
            parts
                .named()
                .into_iter()
                .find(|(_, v)| !v.is_finite())
                .map(|(part, _)| format!("{output}.{part}"))
        })
    }
}
