//! Fitting a [`Surrogate`] to full-model sweeps by linear least squares.

use nalgebra::{DMatrix, DVector};

use super::accuracy::compare_run;
use super::basis::{
    DEFLECTION_TERMS, FRICTION_TERMS, RAMPS, SPLIT_TERMS, STRAIN_DEPTH_TERMS, STRAIN_TERMS,
    column_aspect, compliance_basis, deflection_basis, dot, drag_basis, friction_basis,
    onset_basis, ramps, size_basis, size_features, split_basis, strain_basis_rate,
    strain_depth_rate_basis,
};
use super::catch_up::{catch_up_values, knee_values};
use super::model::{
    FitRange, FittedBlade, PostFracture, PreFracture, SURROGATE_FORMAT_VERSION, Surrogate,
    slip_direction,
};
use super::ratio::{RatioCorrection, SLICE_SIZE_TERMS, SLICE_TERMS, log_ratio, slice_basis};
use super::state::CutState;
use super::sweep::{SweepCase, SweepRun, SweepSample};
use super::toughness::ToughnessRatio;
use crate::blade::BladeSection;
use crate::material::Material;

/// Why a fit failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// A least-squares problem had fewer usable samples than unknowns.
    #[error("too few samples to fit `{what}`: {samples} for {unknowns} coefficients")]
    TooFewSamples {
        /// Which part of the surrogate.
        what: &'static str,
        /// Usable samples.
        samples: usize,
        /// Coefficients.
        unknowns: usize,
    },
    /// The window weight was negative or not finite.
    #[error("window weight {0} must be a finite number >= 0")]
    WindowWeight(f64),
}

/// Rows of a least-squares problem with `N` unknowns.
struct Rows<const N: usize> {
    what: &'static str,
    a: Vec<[f64; N]>,
    b: Vec<f64>,
}

impl<const N: usize> Rows<N> {
    fn new(what: &'static str) -> Self {
        Self {
            what,
            a: Vec::new(),
            b: Vec::new(),
        }
    }

    fn push(&mut self, row: [f64; N], target: f64) {
        if target.is_finite() && row.iter().all(|x| x.is_finite()) {
            self.a.push(row);
            self.b.push(target);
        }
    }

    /// Least-squares solution by SVD with the columns scaled to unit norm.
    fn solve(&self) -> Result<[f64; N], FitError> {
        let m = self.a.len();
        if m < N {
            return Err(FitError::TooFewSamples {
                what: self.what,
                samples: m,
                unknowns: N,
            });
        }
        let mut scale = [0.0f64; N];
        for row in &self.a {
            for (s, x) in scale.iter_mut().zip(row) {
                *s += x * x;
            }
        }
        for s in &mut scale {
            *s = if *s > 0.0 { s.sqrt() } else { 1.0 };
        }
        let a = DMatrix::from_fn(m, N, |i, j| self.a[i][j] / scale[j]);
        let b = DVector::from_column_slice(&self.b);
        let x = a
            .svd(true, true)
            .solve(&b, 1e-12)
            .unwrap_or_else(|_| DVector::zeros(N));
        let mut out = [0.0; N];
        for j in 0..N {
            out[j] = x[j] / scale[j];
        }
        Ok(out)
    }
}

/// The mean of one run's strain-energy rows over its settled window (travel
/// since fracture ≥ [`WINDOW_TRAVEL`]), pushed as one more row weighted as
/// √n samples × the window weight ([`Surrogate::fit_window_weight`]): the
/// per-sample rows alone let the basis, the same at every ξ, trade the
/// window's mean for the transient after the fracture (`docs/surrogates.md`,
/// "The strain rate's settled mean"). Used alike by the
/// nominal fit and the ratio corrections' fit.
struct WindowMean<const N: usize> {
    row: [f64; N],
    target: f64,
    samples: f64,
}

impl<const N: usize> WindowMean<N> {
    fn new() -> Self {
        Self {
            row: [0.0; N],
            target: 0.0,
            samples: 0.0,
        }
    }

    /// Adds a sample's row and target if it is in the settled window.
    fn add(&mut self, travel_since_fracture: f64, row: &[f64; N], target: f64) {
        if travel_since_fracture >= WINDOW_TRAVEL {
            for (w, x) in self.row.iter_mut().zip(row) {
                *w += x;
            }
            self.target += target;
            self.samples += 1.0;
        }
    }

    /// Pushes the window's mean row onto `rows` with weight `weight` (none
    /// at 0 or without settled samples).
    fn push_into(&self, rows: &mut Rows<N>, weight: f64) {
        if weight > 0.0 && self.samples > 0.0 {
            let a = weight * self.samples.sqrt();
            rows.push(
                self.row.map(|x| a * x / self.samples),
                a * self.target / self.samples,
            );
        }
    }
}

/// Fits a surrogate to `runs` of `material` cut by `blade` (DESIGN §3.4).
///
/// Every fitted function is linear in its coefficients (`basis` module), so
/// each is one least-squares problem:
/// - before fracture, samples deeper than 30 % of the run's onset depth:
///   C_n = E·d/F_n, C_t = G·ξ·d/F_t (ξ > 0), deflection/d on [1, λ_H, λ_w];
/// - per run, the onset r(ξ,ν)·R'_c/(E·d*) on [1, λ_H, λ_w, ξ², ξ²λ_H, ξ²λ_w],
///   d* the middle of the step that first fractured;
/// - the catch-up ℓ = L/d*₀ on [1, λ_H, λ_w, ξ, ξ²] from the knee each run
///   shows (`catch_up`), 0 where the crack did not jump ahead of the edge;
/// - after fracture, for each knee shape [κ, β, a] of a grid (`KNEE_WIDTHS`
///   × `KNEE_BEVEL_WIDTHS` × `KNEE_LEADS`, with each run's own catch-up
///   length): the faces'
///   normal reaction N = (F_n^f + ξF_t^f)/(μ√(1+ξ²)) (the friction work per
///   depth over μ√(1+ξ²)) over E·Δ; the knife's non-friction work per depth
///   beyond r(ξ,ν)·R_c·g, F_n^c + ξF_t^c − r·R_c·g, over E·Δ², on the rates
///   of the strain-energy basis (so the fit targets the force the knife
///   feels, sawtooth averaged by least squares); then, with the wedge's
///   S·U̇ taken off F_n^c, the edge's F_t^c = σ·F_n^e + Q(ξ)·h(s) (split and
///   released drag, jointly); the deflection over Δ. The shape kept is the
///   one whose surrogate follows the fit's own runs best (`compare_run`).
///   With `window_weight` W > 0 each run adds one strain-energy row, the
///   mean of its settled window's rows weighted as √n samples × W
///   ([`WindowMean`]); W is recorded as `fit_window_weight` and the ratio
///   corrections' fit ([`fit_ratio_correction`]) adds the same rows.
///
/// With μ = 0 the face reaction cannot be observed and is fitted as 0.
/// A negative or non-finite `window_weight` is [`FitError::WindowWeight`].
pub fn fit_surrogate(
    material: &Material,
    blade: &BladeSection,
    material_name: &str,
    knife_name: &str,
    runs: &[SweepRun],
    window_weight: f64,
) -> Result<Surrogate, FitError> {
    if !(window_weight.is_finite() && window_weight >= 0.0) {
        return Err(FitError::WindowWeight(window_weight));
    }
    let e0 = material.youngs_modulus;
    let nu = material.poisson_ratio;
    let g0 = material.shear_modulus();
    let b = blade.edge_width;
    let mut c_n = Rows::new("pre_fracture.normal_compliance");
    let mut c_t = Rows::new("pre_fracture.tangential_compliance");
    let mut defl_pre = Rows::new("pre_fracture.deflection");
    let mut onset = Rows::new("pre_fracture.onset");
    let mut range = FitRange {
        xi_max: 0.0,
        height: [f64::INFINITY, 0.0],
        half_width: [f64::INFINITY, 0.0],
    };
    for run in runs {
        let c = run.case;
        let xi = c.xi;
        range.xi_max = range.xi_max.max(xi);
        range.height = [range.height[0].min(c.height), range.height[1].max(c.height)];
        range.half_width = [
            range.half_width[0].min(c.half_width),
            range.half_width[1].max(c.half_width),
        ];
        let (lh, lw) = size_features(c.height, c.half_width, b);
        let aspect = column_aspect(c.height, c.half_width, b);
        let sizes = size_basis(lh, lw);
        let compliance = compliance_basis(lh, lw, aspect);
        let r = ToughnessRatio::at(xi, nu).value;
        let onset_depth = run
            .onset_depth
            .map(|d| (d - 0.5 * run.onset_resolution).max(0.5 * run.onset_resolution));
        if let Some(d) = onset_depth {
            onset.push(
                onset_basis(xi, lh, lw, aspect),
                r * material.initial_fracture_toughness / (e0 * d),
            );
        }
        let pre_min = 0.3 * onset_depth.unwrap_or(0.0);
        for s in run.samples.iter().filter(|s| !s.fractured) {
            if s.depth < pre_min || s.depth <= 0.0 {
                continue;
            }
            if s.force_normal > 0.0 {
                c_n.push(compliance, e0 * s.depth / s.force_normal);
            }
            if xi > 0.0 && s.force_tangential > 0.0 {
                c_t.push(compliance, g0 * xi * s.depth / s.force_tangential);
            }
            defl_pre.push(sizes, s.deflection / s.depth);
        }
    }
    let pre_fracture = PreFracture {
        normal_compliance: c_n.solve()?,
        tangential_compliance: c_t.solve()?,
        deflection: defl_pre.solve()?,
        onset: onset.solve()?,
    };
    // The catch-up: ℓ = L/d*₀ from each run's knee, with d*₀ the fitted
    // nominal onset depth (as `Surrogate::evaluate` computes it, without
    // its floor, which never holds within the fitted sizes).
    let nominal_onset = |run: &SweepRun| {
        let c = run.case;
        let r = ToughnessRatio::at(c.xi, nu).value;
        r * material.initial_fracture_toughness / (e0 * onset_stiffness(&pre_fracture, &c, b))
    };
    let mut catch_up_rows = Rows::new("post_fracture.catch_up");
    let observed: Vec<Option<f64>> = runs.iter().map(observed_catch_up).collect();
    for (run, l) in runs.iter().zip(&observed) {
        if let Some(l) = l {
            let c = run.case;
            let (lh, lw) = size_features(c.height, c.half_width, b);
            catch_up_rows.push(catch_up_values(c.xi, lh, lw), l / nominal_onset(run));
        }
    }
    let catch_up = catch_up_rows.solve()?;
    // Each run's catch-up length for the post-fracture rows: the knee it
    // shows, else (the crack ran to the run's end) the fitted one.
    let lengths: Vec<f64> = runs
        .iter()
        .zip(&observed)
        .map(|(run, l)| {
            l.unwrap_or_else(|| {
                let c = run.case;
                let (lh, lw) = size_features(c.height, c.half_width, b);
                nominal_onset(run) * dot(&catch_up, &catch_up_values(c.xi, lh, lw))
            })
        })
        .collect();
    let base = Surrogate {
        version: SURROGATE_FORMAT_VERSION,
        material_name: material_name.to_string(),
        knife_name: knife_name.to_string(),
        fit_window_weight: window_weight,
        material: *material,
        blade: FittedBlade::from(*blade),
        range,
        pre_fracture,
        post_fracture: PostFracture {
            catch_up,
            knee_width: [KNEE_WIDTHS[0], KNEE_BEVEL_WIDTHS[0]],
            knee_lead: KNEE_LEADS[0],
            split: [0.0; SPLIT_TERMS],
            drag: [0.0; RAMPS],
            face_reaction: [0.0; FRICTION_TERMS],
            strain_energy_rate: [0.0; STRAIN_TERMS],
            strain_depth_rate: [0.0; STRAIN_DEPTH_TERMS],
            deflection: [0.0; DEFLECTION_TERMS],
            slip_ratio: fit_slip_ratio(runs),
            face_reaction_slice: [0.0; SLICE_TERMS],
        },
        ratio: RatioCorrection::default(),
    };
    // The knee's shape [κ, β, a]: the candidates whose fit follows the fit's
    // own runs best (sum of the F_n and F_t RMS errors over the runs, as
    // `fit` reports them); the first of equals, so the choice is
    // deterministic.
    let mut best: Option<(f64, Surrogate)> = None;
    let widths = KNEE_WIDTHS.iter().flat_map(|&k| {
        KNEE_BEVEL_WIDTHS
            .iter()
            .flat_map(move |&b| KNEE_LEADS.iter().map(move |&a| [k, b, a]))
    });
    for width in widths {
        let post = fit_post_fracture(material, blade, runs, &lengths, &base, width)?;
        let s = Surrogate {
            post_fracture: post,
            ..base.clone()
        };
        let score: f64 = runs
            .iter()
            .map(|r| {
                let a = compare_run(&s, r).accuracy;
                a.force_normal_rms_pct + a.force_tangential_rms_pct
            })
            .sum();
        if best.as_ref().is_none_or(|(b, _)| score < *b) {
            best = Some((score, s));
        }
    }
    // KNEE_WIDTHS is not empty.
    Ok(best.map(|(_, s)| s).unwrap_or(base))
}

/// Candidate widths κ of the knee gate, relative to the catch-up length.
pub const KNEE_WIDTHS: [f64; 2] = [0.05, 0.2];

/// Candidate leads a of the knee gate's centre before the catch-up length,
/// in bevel heights.
pub const KNEE_LEADS: [f64; 5] = [0.0, 0.1, 0.2, 0.3, 0.45];

/// Candidate widths β of the knee gate, in bevel heights.
pub const KNEE_BEVEL_WIDTHS: [f64; 6] = [0.0, 0.5, 1.0, 2.0, 3.0, 4.0];

/// Crack growth after the first jump that marks the knee, m (2.5 steps of
/// the default sweep after fracture).
const KNEE_CRACK_GROWTH: f64 = 5e-5;

/// The catch-up travel a run shows: 0 if the first fracture did not put the
/// crack tip below the edge (no jump ahead: the crack grows with the knife
/// from the start), else from the first fractured step to the first step
/// whose crack is [`KNEE_CRACK_GROWTH`] deeper than right after the jump
/// (the edge has caught up with the tip and cuts again). None if the crack
/// does not grow again before the run ends.
fn observed_catch_up(run: &SweepRun) -> Option<f64> {
    let first = run.samples.iter().position(|s| s.fractured)?;
    let jumped = run.samples[first].crack_depth;
    if jumped <= run.samples[first].depth {
        return Some(0.0);
    }
    run.samples[first..]
        .iter()
        .find(|s| s.crack_depth > jumped + KNEE_CRACK_GROWTH)
        .map(|s| s.travel_since_fracture)
}

/// The post-fracture least squares for a knee shape `width` = [κ, β, a], given the
/// fitted pre-fracture part and catch-up in `base` and each run's catch-up
/// length.
fn fit_post_fracture(
    material: &Material,
    blade: &BladeSection,
    runs: &[SweepRun],
    lengths: &[f64],
    base: &Surrogate,
    width: [f64; 3],
) -> Result<PostFracture, FitError> {
    let e0 = material.youngs_modulus;
    let nu = material.poisson_ratio;
    let mu0 = material.friction_coefficient;
    let b = blade.edge_width;
    let delta = 0.5 * blade.thickness;
    let h_b = blade.bevel_height();
    let kappa = [width[0], width[1] * h_b, width[2] * h_b];
    let pre_fracture = &base.pre_fracture;
    let slip = base.post_fracture.slip_ratio;
    let mut face = Rows::<{ FRICTION_TERMS + SLICE_TERMS }>::new("post_fracture.face_reaction");
    let mut strain =
        Rows::<{ STRAIN_TERMS + STRAIN_DEPTH_TERMS }>::new("post_fracture.strain_energy_rate");
    let mut split = Rows::new("post_fracture.split");
    let mut defl_post = Rows::new("post_fracture.deflection");
    let window_weight = base.fit_window_weight;
    for (run, &length) in runs.iter().zip(lengths) {
        let c = run.case;
        let xi = c.xi;
        let (lh, lw) = size_features(c.height, c.half_width, b);
        let r = ToughnessRatio::at(xi, nu).value;
        let mut window = WindowMean::new();
        for s in run.samples.iter().filter(|s| s.fractured) {
            let (ramp, ramp_slope) = ramps(s.travel_since_fracture, h_b);
            let knee = knee_values(s.travel_since_fracture, xi, length, kappa, lh, lw);
            let depth_ratio = (s.depth / c.height).clamp(0.0, 1.0);
            if mu0 > 0.0 {
                let n = (s.force_normal_friction + xi * s.force_tangential_friction)
                    / (mu0 * friction_work_factor(xi, slip));
                let mut row = [0.0; FRICTION_TERMS + SLICE_TERMS];
                row[..FRICTION_TERMS].copy_from_slice(&friction_basis(
                    &ramps(s.depth, h_b).0,
                    depth_ratio,
                    &knee,
                    lh,
                    lw,
                ));
                row[FRICTION_TERMS..].copy_from_slice(&slice_values(xi));
                face.push(row, n / (e0 * delta));
            }
            let f_n = s.force_normal - s.force_normal_friction;
            let f_t = s.force_tangential - s.force_tangential_friction;
            let wedge = strain_basis_rate(&ramp_slope, depth_ratio, c.height, lh, lw);
            let steady = strain_depth_rate_basis(c.height, lh, lw);
            let mut row = [0.0; STRAIN_TERMS + STRAIN_DEPTH_TERMS];
            row[..STRAIN_TERMS].copy_from_slice(&wedge);
            row[STRAIN_TERMS..].copy_from_slice(&steady);
            let target =
                (f_n + xi * f_t - r * material.fracture_toughness * knee[0]) / (e0 * delta * delta);
            window.add(s.travel_since_fracture, &row, target);
            strain.push(row, target);
            defl_post.push(deflection_basis(&ramp, lw), s.deflection / delta);
        }
        window.push_into(&mut strain, window_weight);
    }
    let strain_fit: [f64; STRAIN_TERMS + STRAIN_DEPTH_TERMS] = strain.solve()?;
    let mut strain_energy_rate = [0.0; STRAIN_TERMS];
    strain_energy_rate.copy_from_slice(&strain_fit[..STRAIN_TERMS]);
    let mut strain_depth_rate = [0.0; STRAIN_DEPTH_TERMS];
    strain_depth_rate.copy_from_slice(&strain_fit[STRAIN_TERMS..]);
    // The split and the drag from the edge's share of F_n^c (beyond the
    // wedge's S·U̇₀, vertical) and F_t^c.
    for run in runs {
        let c = run.case;
        let xi = c.xi;
        let (lh, lw) = size_features(c.height, c.half_width, b);
        let q = onset_drag(pre_fracture, material, &c, b);
        for s in run.samples.iter().filter(|s| s.fractured) {
            let (ramp, ramp_slope) = ramps(s.travel_since_fracture, h_b);
            let depth_ratio = (s.depth / c.height).clamp(0.0, 1.0);
            let wedge = e0
                * delta
                * delta
                * (dot(
                    &strain_energy_rate,
                    &strain_basis_rate(&ramp_slope, depth_ratio, c.height, lh, lw),
                ) + dot(
                    &strain_depth_rate,
                    &strain_depth_rate_basis(c.height, lh, lw),
                ));
            let f_n = s.force_normal - s.force_normal_friction - wedge;
            let f_t = s.force_tangential - s.force_tangential_friction;
            let sb = split_basis(xi, lh, lw);
            let db = drag_basis(&ramp);
            split.push(
                [
                    sb[0] * f_n,
                    sb[1] * f_n,
                    sb[2] * f_n,
                    sb[3] * f_n,
                    sb[4] * f_n,
                    q * db[0],
                    q * db[1],
                    q * db[2],
                    q * db[3],
                ],
                f_t,
            );
        }
    }
    let split_drag = split.solve()?;
    let face_fit = if mu0 > 0.0 {
        face.solve()?
    } else {
        [0.0; FRICTION_TERMS + SLICE_TERMS]
    };
    let mut face_reaction = [0.0; FRICTION_TERMS];
    face_reaction.copy_from_slice(&face_fit[..FRICTION_TERMS]);
    let mut face_reaction_slice = [0.0; SLICE_TERMS];
    face_reaction_slice.copy_from_slice(&face_fit[FRICTION_TERMS..]);
    Ok(PostFracture {
        catch_up: base.post_fracture.catch_up,
        knee_width: [width[0], width[1]],
        knee_lead: width[2],
        split: [
            split_drag[0],
            split_drag[1],
            split_drag[2],
            split_drag[3],
            split_drag[4],
        ],
        drag: [split_drag[5], split_drag[6], split_drag[7], split_drag[8]],
        face_reaction,
        strain_energy_rate,
        strain_depth_rate,
        deflection: defl_post.solve()?,
        slip_ratio: slip,
        face_reaction_slice,
    })
}

/// The exponent k of the catch-up length's scaling with the ratio,
/// L = L₀·ρ^(−k): the crack's jump at the onset is ≈ ½·(R'_c/R_c)·d* and
/// d* ∝ T/S exactly (seed 000 eq. 1 at the onset, `catch_up` module).
pub const CATCH_UP_EXPONENT: f64 = 1.0;

/// The friction's work per depth per unit μN for the faces' slip ratio k
/// (`PostFracture::slip_ratio`): √(1+ξ²) for k = 1, else
/// (1+kξ²)/√(1+k²ξ²).
fn friction_work_factor(xi: f64, slip: f64) -> f64 {
    if slip == 1.0 {
        (1.0 + xi * xi).sqrt()
    } else {
        slip_direction(xi, slip).2.v
    }
}

/// The faces' slip ratio k of the sweeps' friction, F_t^f = k·ξ·F_n^f, by
/// least squares over the fractured samples with ξ > 0 (1 without any).
/// The knife moves along (1, ξ); the material at the faces follows it down
/// a little (the halves are pushed down as the cut deepens), so the faces
/// slip less vertically than the knife, k > 1 (measured in
/// `docs/surrogates.md`, "The normal force's mean after fracture").
fn fit_slip_ratio(runs: &[SweepRun]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for run in runs.iter().filter(|r| r.case.xi > 0.0) {
        let xi = run.case.xi;
        for s in run.samples.iter().filter(|s| s.fractured) {
            let x = xi * s.force_normal_friction;
            if x.is_finite() && s.force_tangential_friction.is_finite() {
                num += x * s.force_tangential_friction;
                den += x * x;
            }
        }
    }
    if den > 0.0 { num / den } else { 1.0 }
}

/// [`slice_basis`] as numbers.
fn slice_values(xi: f64) -> [f64; SLICE_TERMS] {
    slice_basis(xi).map(|j| j.v)
}

/// Full-model sweeps of the fit's grid at a material whose stiffness (E)
/// is scaled by `stiffness` and whose toughness (R_c, R'_c) by `toughness`.
#[derive(Debug, Clone, Copy)]
pub struct ScaledSweep<'a> {
    /// The toughness factor T of the sweep's material.
    pub toughness: f64,
    /// The stiffness factor S of the sweep's material.
    pub stiffness: f64,
    /// Its runs.
    pub runs: &'a [SweepRun],
}

/// Fits the ratio corrections of `surrogate` (its nominal part fitted, its
/// `ratio` ignored) to sweeps at other stiffness-to-toughness ratios
/// ρ = S/T (`ratio` module), by least squares on the residuals against the
/// nominal surrogate evaluated at their ρ, with the nominal fit's targets:
/// - the faces' normal reaction N = (F_n^f + ξF_t^f)/(μ₀√(1+ξ²)) over
///   S·E₀·Δ, minus the nominal N₀/(E₀Δ), on [ℓ·b_N, ℓ·N₀φ, ℓ·N₀ψ, ℓ²·b_N,
///   ℓ²·N₀φ, ℓ²·N₀ψ] (φ the `ratio::slice_basis` in ξ, ψ = φ·[λ_H, λ_w, H/w]
///   the `ratio::slice_size_basis`);
/// - the knife's non-friction work per depth beyond T·r(ξ,ν)·R_c₀·g over
///   S·E₀·Δ², minus the nominal U̇₀/(E₀Δ²), on [ℓ·b_U, ℓ²·b_U], with
///   each run's settled-window mean row when `surrogate.fit_window_weight`
///   is positive ([`WindowMean`], as in [`fit_surrogate`]);
///
/// with b_N, b_U the nominal terms' bases as the surrogate takes them (its
/// own catch-up length at the sweep's ratio, L₀·ρ^(−k) with
/// k = [`CATCH_UP_EXPONENT`], and knee gate g), ℓ = ln ρ, and each run's own onset
/// (fractured samples, travel since its first fracture). With sweeps at a
/// single ρ the ℓ² terms are not observable apart from the ℓ terms and the
/// SVD's minimum-norm solution splits them; use two ratios on either side
/// of 1.
pub fn fit_ratio_correction(
    surrogate: &Surrogate,
    sweeps: &[ScaledSweep<'_>],
) -> Result<RatioCorrection, FitError> {
    // The residuals are taken with the catch-up length at the sweep's ratio
    // (L ∝ ρ^(−k), k = 1: physics, not fitted).
    let surrogate = &Surrogate {
        ratio: RatioCorrection {
            catch_up_exponent: CATCH_UP_EXPONENT,
            ..RatioCorrection::default()
        },
        ..surrogate.clone()
    };
    let m = &surrogate.material;
    let e0 = m.youngs_modulus;
    let mu0 = m.friction_coefficient;
    let delta = 0.5 * surrogate.blade.thickness;
    let p = &surrogate.post_fracture;
    const FACE_TERMS: usize = FRICTION_TERMS + SLICE_TERMS + SLICE_SIZE_TERMS;
    let mut face = Rows::<{ 2 * FACE_TERMS }>::new("ratio.face_reaction");
    let mut strain = Rows::<{ 2 * STRAIN_TERMS }>::new("ratio.strain_energy_rate");
    for sweep in sweeps {
        let l = log_ratio(sweep.toughness, sweep.stiffness);
        let (t, s) = (sweep.toughness, sweep.stiffness);
        for run in sweep.runs {
            let c = run.case;
            let xi = c.xi;
            let r = ToughnessRatio::at(xi, m.poisson_ratio).value;
            let root = friction_work_factor(xi, p.slip_ratio);
            let mut window = WindowMean::new();
            for sample in run.samples.iter().filter(|x| x.fractured) {
                let state = fractured_state(&c, sample);
                let bases = surrogate.wedge_bases(xi, &state, l);
                if mu0 > 0.0 {
                    let n = (sample.force_normal_friction + xi * sample.force_tangential_friction)
                        / (mu0 * root);
                    let n0 = bases.face_reaction;
                    let mut row = [0.0; 2 * FACE_TERMS];
                    let terms = bases
                        .face
                        .iter()
                        .copied()
                        .chain(slice_values(xi).map(|phi| n0 * phi))
                        .chain(bases.slice_size.map(|b| n0 * b));
                    for (k, b) in terms.enumerate() {
                        row[k] = l * b;
                        row[FACE_TERMS + k] = l * l * b;
                    }
                    face.push(row, n / (s * e0 * delta) - n0);
                }
                let f_n = sample.force_normal - sample.force_normal_friction;
                let f_t = sample.force_tangential - sample.force_tangential_friction;
                let beyond = f_n + xi * f_t - t * r * m.fracture_toughness * bases.gate;
                let mut row = [0.0; 2 * STRAIN_TERMS];
                for (k, b) in bases.strain.iter().enumerate() {
                    row[k] = l * b;
                    row[STRAIN_TERMS + k] = l * l * b;
                }
                let target = beyond / (s * e0 * delta * delta) - bases.strain_rate;
                window.add(sample.travel_since_fracture, &row, target);
                strain.push(row, target);
            }
            window.push_into(&mut strain, surrogate.fit_window_weight);
        }
    }
    let mut out = surrogate.ratio;
    let u = strain.solve()?;
    out.strain_energy_rate_linear
        .copy_from_slice(&u[..STRAIN_TERMS]);
    out.strain_energy_rate_quadratic
        .copy_from_slice(&u[STRAIN_TERMS..]);
    if mu0 > 0.0 {
        let n = face.solve()?;
        out.face_reaction_linear
            .copy_from_slice(&n[..FRICTION_TERMS]);
        let slice = FRICTION_TERMS + SLICE_TERMS;
        out.face_reaction_slice_linear
            .copy_from_slice(&n[FRICTION_TERMS..slice]);
        out.face_reaction_slice_size_linear
            .copy_from_slice(&n[slice..FACE_TERMS]);
        out.face_reaction_quadratic
            .copy_from_slice(&n[FACE_TERMS..FACE_TERMS + FRICTION_TERMS]);
        out.face_reaction_slice_quadratic
            .copy_from_slice(&n[FACE_TERMS + FRICTION_TERMS..FACE_TERMS + slice]);
        out.face_reaction_slice_size_quadratic
            .copy_from_slice(&n[FACE_TERMS + slice..]);
    }
    out = fit_drag_correction(surrogate, sweeps, out)?;
    Ok(out)
}

/// The drag part of the ratio corrections, given the others in `ratio`:
/// the edge's F_t^c = σ·F_n^e + T·Q(ξ)·(h(s) + ℓ·h₁(s) + ℓ²·h₂(s)) with
/// F_n^e = F_n^c − S·U̇(ρ) (as the nominal fit's split and drag, with the
/// nominal σ, Q and h), least squares for h₁, h₂ on the residuals of the
/// off-nominal sweeps.
fn fit_drag_correction(
    surrogate: &Surrogate,
    sweeps: &[ScaledSweep<'_>],
    mut ratio: RatioCorrection,
) -> Result<RatioCorrection, FitError> {
    let m = &surrogate.material;
    let e0 = m.youngs_modulus;
    let delta = 0.5 * surrogate.blade.thickness;
    let h_b = surrogate.blade.section().bevel_height();
    let b = surrogate.blade.edge_width;
    let pre = &surrogate.pre_fracture;
    let p = &surrogate.post_fracture;
    let mut rows = Rows::<{ 2 * RAMPS }>::new("ratio.drag");
    for sweep in sweeps {
        let (t, s) = (sweep.toughness, sweep.stiffness);
        let l = log_ratio(t, s);
        for run in sweep.runs {
            let c = run.case;
            let xi = c.xi;
            let (lh, lw) = size_features(c.height, c.half_width, b);
            let q = onset_drag(pre, m, &c, b);
            let sigma = dot(&p.split, &split_basis(xi, lh, lw));
            for sample in run.samples.iter().filter(|x| x.fractured) {
                let state = fractured_state(&c, sample);
                let bases = surrogate.wedge_bases(xi, &state, l);
                let u = e0
                    * delta
                    * delta
                    * (bases.strain_rate
                        + l * dot(&ratio.strain_energy_rate_linear, &bases.strain)
                        + l * l * dot(&ratio.strain_energy_rate_quadratic, &bases.strain));
                let f_n = sample.force_normal - sample.force_normal_friction - s * u;
                let f_t = sample.force_tangential - sample.force_tangential_friction;
                let (ramp, _) = ramps(sample.travel_since_fracture, h_b);
                let decays = drag_basis(&ramp);
                let mut row = [0.0; 2 * RAMPS];
                for (k, d) in decays.iter().enumerate() {
                    row[k] = t * q * l * d;
                    row[RAMPS + k] = t * q * l * l * d;
                }
                rows.push(row, f_t - sigma * f_n - t * q * dot(&p.drag, &decays));
            }
        }
    }
    let h = rows.solve()?;
    ratio.drag_linear.copy_from_slice(&h[..RAMPS]);
    ratio.drag_quadratic.copy_from_slice(&h[RAMPS..]);
    Ok(ratio)
}

/// The cut's state at a fractured sample of a sweep run of `case`.
fn fractured_state(case: &SweepCase, sample: &SweepSample) -> CutState {
    CutState {
        depth: sample.depth,
        height: case.height,
        half_width: case.half_width,
        fractured: true,
        travel_since_fracture: sample.travel_since_fracture,
    }
}

/// The onset stiffness y(ξ) = r(ξ,ν)·R'_c/(E·d*) the fitted pre-fracture
/// model gives a run of `case` (edge width `b`), as `Surrogate::evaluate`
/// computes it within the fitted sizes (without its floor at the section
/// height, which never holds there).
fn onset_stiffness(pre: &PreFracture, case: &SweepCase, b: f64) -> f64 {
    let (lh, lw) = size_features(case.height, case.half_width, b);
    let (a, b2) = pre.onset_stiffness_terms(lh, lw, column_aspect(case.height, case.half_width, b));
    a + case.xi * case.xi * b2
}

/// The antiplane drag the edge holds at the onset per unit toughness factor,
/// Q(ξ) = G₀·ξ·r·R'_c₀/(C_t·E₀·y(ξ)), from the fitted pre-fracture model, as
/// `Surrogate::evaluate` computes it.
fn onset_drag(pre: &PreFracture, material: &Material, case: &SweepCase, b: f64) -> f64 {
    let xi = case.xi;
    let r = ToughnessRatio::at(xi, material.poisson_ratio).value;
    let (lh, lw) = size_features(case.height, case.half_width, b);
    let (_, c_t) = pre.compliances(lh, lw, column_aspect(case.height, case.half_width, b));
    let y = onset_stiffness(pre, case, b);
    material.shear_modulus() * material.initial_fracture_toughness * xi * r
        / (c_t * material.youngs_modulus * y)
}

/// Travel since fracture from which a run's samples count to its window
/// mean ([`WindowMean`]), m: on potato, where the crack does not jump ahead
/// of the edge, past the knee after the first fracture. On eggplant, whose
/// catch-up lasts many millimetres after the fracture (`docs/surrogates.md`,
/// "At other stiffness-to-toughness ratios"), the window would include it;
/// the shipped eggplant files are fitted without window rows.
const WINDOW_TRAVEL: f64 = 2e-3;
