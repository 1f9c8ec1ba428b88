//! Fitting a [`Surrogate`] to full-model sweeps by linear least squares.

use nalgebra::{DMatrix, DVector};

use super::basis::{
    deflection_basis, dot, drag_basis, friction_basis, onset_basis, ramps, size_basis,
    size_features, split_basis, strain_basis_rate,
};
use super::model::{
    FitRange, FittedBlade, PostFracture, PreFracture, SURROGATE_FORMAT_VERSION, Surrogate,
};
use super::sweep::SweepRun;
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

/// Fits a surrogate to `runs` of `material` cut by `blade` (DESIGN §3.4).
///
/// Every fitted function is linear in its coefficients (`basis` module), so
/// each is one least-squares problem:
/// - before fracture, samples deeper than 30 % of the run's onset depth:
///   C_n = E·d/F_n, C_t = G·ξ·d/F_t (ξ > 0), deflection/d on [1, λ_H, λ_w];
/// - per run, the onset r(ξ,ν)·R'_c/(E·d*) on [1, λ_H, λ_w, ξ², ξ²λ_H, ξ²λ_w],
///   d* the middle of the step that first fractured;
/// - after fracture: the faces' normal reaction N = (F_n^f + ξF_t^f)/(μ√(1+ξ²))
///   (the friction work per depth over μ√(1+ξ²)) over E·Δ; the knife's
///   non-friction work per depth beyond r(ξ,ν)·R_c, F_n^c + ξF_t^c − r·R_c,
///   over E·Δ², on the rates of the strain-energy basis (so the fit targets
///   the force the knife feels, sawtooth averaged by least squares); the
///   non-friction F_t^c = σ(ξ)·F_n^c + Q(ξ)·h(s) (split and released drag,
///   jointly); the deflection over Δ.
///
/// With μ = 0 the face reaction cannot be observed and is fitted as 0.
pub fn fit_surrogate(
    material: &Material,
    blade: &BladeSection,
    material_name: &str,
    knife_name: &str,
    runs: &[SweepRun],
) -> Result<Surrogate, FitError> {
    let e0 = material.youngs_modulus;
    let nu = material.poisson_ratio;
    let g0 = material.shear_modulus();
    let mu0 = material.friction_coefficient;
    let b = blade.edge_width;
    let delta = 0.5 * blade.thickness;
    let h_b = blade.bevel_height();
    let mut c_n = Rows::new("pre_fracture.normal_compliance");
    let mut c_t = Rows::new("pre_fracture.tangential_compliance");
    let mut defl_pre = Rows::new("pre_fracture.deflection");
    let mut onset = Rows::new("pre_fracture.onset");
    let mut face = Rows::new("post_fracture.face_reaction");
    let mut strain = Rows::new("post_fracture.strain_energy_rate");
    let mut split = Rows::new("post_fracture.split");
    let mut defl_post = Rows::new("post_fracture.deflection");
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
        let sizes = size_basis(lh, lw);
        let r = ToughnessRatio::at(xi, nu).value;
        let onset_depth = run
            .onset_depth
            .map(|d| (d - 0.5 * run.onset_resolution).max(0.5 * run.onset_resolution));
        if let Some(d) = onset_depth {
            onset.push(
                onset_basis(xi, lh, lw),
                r * material.initial_fracture_toughness / (e0 * d),
            );
        }
        let pre_min = 0.3 * onset_depth.unwrap_or(0.0);
        for s in run.samples.iter().filter(|s| !s.fractured) {
            if s.depth < pre_min || s.depth <= 0.0 {
                continue;
            }
            if s.force_normal > 0.0 {
                c_n.push(sizes, e0 * s.depth / s.force_normal);
            }
            if xi > 0.0 && s.force_tangential > 0.0 {
                c_t.push(sizes, g0 * xi * s.depth / s.force_tangential);
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
    for run in runs {
        let c = run.case;
        let xi = c.xi;
        let (lh, lw) = size_features(c.height, c.half_width, b);
        let sizes = size_basis(lh, lw);
        let r = ToughnessRatio::at(xi, nu).value;
        // The drag at onset per unit toughness factor, from the fitted
        // pre-fracture model (as `Surrogate::evaluate` computes it).
        let y = dot(&pre_fracture.onset, &onset_basis(xi, lh, lw));
        let c_t = dot(&pre_fracture.tangential_compliance, &sizes);
        let q = g0 * material.initial_fracture_toughness * xi * r / (c_t * e0 * y);
        for s in run.samples.iter().filter(|s| s.fractured) {
            let (ramp, ramp_slope) = ramps(s.travel_since_fracture, h_b);
            let depth_ratio = (s.depth / c.height).clamp(0.0, 1.0);
            let root = (1.0 + xi * xi).sqrt();
            if mu0 > 0.0 {
                let n = (s.force_normal_friction + xi * s.force_tangential_friction) / (mu0 * root);
                face.push(friction_basis(&ramp, depth_ratio, lh, lw), n / (e0 * delta));
            }
            let f_n = s.force_normal - s.force_normal_friction;
            let f_t = s.force_tangential - s.force_tangential_friction;
            strain.push(
                strain_basis_rate(&ramp_slope, depth_ratio, c.height, lh, lw),
                (f_n + xi * f_t - r * material.fracture_toughness) / (e0 * delta * delta),
            );
            let sb = split_basis(xi);
            let db = drag_basis(&ramp);
            split.push(
                [
                    sb[0] * f_n,
                    sb[1] * f_n,
                    q * db[0],
                    q * db[1],
                    q * db[2],
                    q * db[3],
                ],
                f_t,
            );
            defl_post.push(deflection_basis(&ramp, lw), s.deflection / delta);
        }
    }
    let split_drag = split.solve()?;
    let face_reaction = if mu0 > 0.0 {
        face.solve()?
    } else {
        [0.0; super::basis::POST_TERMS]
    };
    Ok(Surrogate {
        version: SURROGATE_FORMAT_VERSION,
        material_name: material_name.to_string(),
        knife_name: knife_name.to_string(),
        material: *material,
        blade: FittedBlade::from(*blade),
        range,
        pre_fracture,
        post_fracture: PostFracture {
            split: [split_drag[0], split_drag[1]],
            drag: [split_drag[2], split_drag[3], split_drag[4], split_drag[5]],
            face_reaction,
            strain_energy_rate: strain.solve()?,
            deflection: defl_post.solve()?,
        },
    })
}
