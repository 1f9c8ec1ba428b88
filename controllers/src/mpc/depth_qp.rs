//! The MPC's convex subproblem over depth stages, on a persistent Clarabel
//! solver (DESIGN §4's suggested form).
//!
//! Stages k = 0…N−1 of depth Δd_k each. Per stage the unknowns are the
//! slice-push ratio ξ_k (tangential travel per unit depth), the time per
//! unit depth τ_k = 1/v_n,k, and a force slack σ_k ≥ 0. Around the previous
//! plan ξ̄_k the work per unit depth and length w(ξ) is replaced by its
//! convexified quadratic model and the force per unit length by its tangent:
//!
//! minimise   Σ_k Δd_k L_k [g_k (ξ_k − ξ̄_k) + ½ h_k (ξ_k − ξ̄_k)²]      work
//!          + W'_0 (ξ_0 − ξ̄_0) + ½ W''⁺_0 (ξ_0 − ξ̄_0)²          work to fracture
//!          + w_D L_0 δ'_0 ξ_0   (both before the first fracture)     deformation
//!          + w_D Σ_k ΔL_k δ*'_k ξ_k                                   deformation
//!          + w_T Σ_k Δz_k τ_k                                         time
//!          + w_S [(ξ_0 − ξ_prev)² + Σ_k (ξ_k − ξ_{k−1})²]             smoothness
//!          + Σ_k c_k (ξ_k − ξ̄_k)                                       finish
//!          + w_F Σ_k σ_k                                              force excess
//! subject to 0 ≤ ξ_k ≤ ξ_max,  |ξ_k − ξ̄_k| ≤ ρ                        (trust region)
//!            ξ_k ≤ v_t,max τ_k,  τ_k ≥ 1/v_n,max                      (speeds)
//!            Σ_k Δz_k ξ_k ≤ S                                         (blade left)
//!            L_k (f_k + f'_k (ξ_k − ξ̄_k)) − σ_k ≤ F_max,  σ_k ≥ 0     (force, soft)
//!
//! with h_k = max(w''(ξ̄_k), h_min) so the program is convex, W_0 the cost
//! of reaching the first fracture for the whole edge (the indentation and
//! the catch-up span after it, each depth weighted by the edge in contact
//! there: [`SliceModel::onset_cost`](super::SliceModel::onset_cost)), L_k the
//! length of edge in contact at the stage, Δz_k = Δd_k/(1 + κ_d,k ξ̄_k) the
//! knife's descent over it (the edge's depth grows at 1 + κ_d ξ times the
//! knife's descent where the edge in contact is inclined, κ_d its slope at
//! the deepest point; Δz_k = Δd_k for a level edge), ΔL_k the length of edge that
//! comes into contact during it (intact material it indents until it
//! fractures), and δ*'_k the slope in ξ of the surface deflection at which
//! intact material fractures (the deflection terms are linearised like
//! the force: δ(ξ) ≈ δ(ξ̄) + δ'(ξ̄)(ξ − ξ̄)), and c_k the finish's cost per
//! unit of ξ_k ([`StageData::finish_slope`]). The program is always feasible
//! (ξ = 0 at the slowest allowed τ satisfies every hard row). Its sparsity
//! pattern never changes: each plan only updates the values of P, q, A and b
//! (no re-allocation, no symbolic refactorisation).

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};

use super::slice_model::StageCost;

/// One stage's data for a plan.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StageData {
    /// Depth of the stage, m.
    pub depth_step: f64,
    /// Length of edge in contact, m.
    pub contact_length: f64,
    /// The ξ the model was evaluated at (the previous plan).
    pub xi_bar: f64,
    /// The model at `xi_bar`.
    pub cost: StageCost,
    /// Whether the stage is before the first fracture (deformation counts).
    pub before_fracture: bool,
    /// Before the first fracture (stage 0): the onset's cost for the whole
    /// edge at `xi_bar`, J, and its first and second derivatives with
    /// respect to ξ ([`SliceModel::onset_cost`](super::SliceModel::onset_cost)).
    pub onset: [f64; 3],
    /// Edge that comes into contact during the stage and is indented from
    /// intact until it fractures, with the deflection it reaches then.
    pub entering: EnteringEdge,
    /// κ_d: the edge's slope at its deepest point along the knife's motion
    /// (0 for a level edge). The edge's depth grows at 1 + κ_d·ξ times the
    /// knife's descent, so a stage of edge depth Δd takes Δd/(1 + κ_d ξ) of
    /// descent and ξΔd/(1 + κ_d ξ) of blade (seed 000 §IV, Fig. 4(a)).
    pub edge_descent_slope: f64,
    /// The cost of the cut's finish per unit of ξ at this stage, J: the
    /// slide the stage makes moves the object along the edge, which changes
    /// how far past the horizon's end the edge must go for the sections'
    /// mean depth to reach the target (the finishing gap of
    /// [`MpcSettings::finish_gap`](super::MpcSettings::finish_gap)). A
    /// linear term of the objective; 0 when not priced.
    pub finish_slope: f64,
}

impl StageData {
    /// The knife's descent over the stage at ξ̄, m: Δd/(1 + κ_d ξ̄). The
    /// stage takes τ times it (τ the time per unit of the knife's descent).
    pub fn knife_descent(&self) -> f64 {
        self.depth_step / (1.0 + self.edge_descent_slope * self.xi_bar)
    }

    /// The blade the stage uses at ratio `xi`, m: ξ times the knife's
    /// descent at ξ̄, the secant of ξΔd/(1 + κ_d ξ) through ξ = 0 and ξ̄
    /// (exact for a level edge and at ξ̄). The subproblem's blade row holds
    /// the same line, so ξ = 0 always fits.
    pub fn blade(&self, xi: f64) -> f64 {
        xi * self.knife_descent()
    }
}

/// Intact edge that a stage brings into contact: a whole object's outline
/// widens with depth, so sections keep meeting the edge after the first
/// fracture, and each is pushed down until its own fracture (the largest
/// surface deflection of a cut is reached at one of these onsets).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EnteringEdge {
    /// Length of edge that comes into contact, m (≥ 0).
    pub length: f64,
    /// Surface deflection at the onset of fracture of intact material at
    /// the stage's ξ̄, m.
    pub deflection: f64,
    /// Its derivative with respect to ξ, m.
    pub deflection_slope: f64,
}

/// The limits and weights of the subproblem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QpLimits {
    /// Largest ξ.
    pub xi_max: f64,
    /// Trust region ρ.
    pub trust_region: f64,
    /// Largest normal speed, m/s.
    pub normal_speed: f64,
    /// Largest tangential speed, m/s.
    pub tangential_speed: f64,
    /// Force limit, N (`f64::INFINITY` for none: the rows stay in the
    /// pattern with a bound they can never reach, since huge bounds upset
    /// the interior-point iterations).
    pub max_force: f64,
    /// Weight of time, J/s.
    pub time_weight: f64,
    /// Weight of ξ changes, J.
    pub smoothness_weight: f64,
    /// Weight of deflection × length of edge deflected, J/m².
    pub deformation_weight: f64,
    /// Cost per newton of force excess, J/N.
    pub force_penalty: f64,
}

/// How a plan went.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum QpStatus {
    /// Solved to the solver's tolerances (or almost).
    Solved,
    /// The iteration budget ran out first.
    IterationLimit,
    /// Anything else the solver reported (numerical trouble).
    Failed,
}

/// Smallest curvature of the convexified work model, relative to the work
/// per depth: keeps the quadratic strictly convex in ξ where the model is
/// linear or concave, so the trust region is not the only bound.
const RELATIVE_MIN_CURVATURE: f64 = 0.05;

/// The persistent subproblem.
pub struct DepthQp {
    n_stages: usize,
    solver: DefaultSolver<f64>,
    p: CscMatrix<f64>,
    a: CscMatrix<f64>,
    q: Vec<f64>,
    b: Vec<f64>,
    /// Indices into `p.nzval` of the ξ diagonal and super-diagonal.
    p_diag: Vec<usize>,
    p_super: Vec<usize>,
    /// Indices into `a.nzval` of the budget row's and the force rows' ξ entries.
    a_budget: Vec<usize>,
    a_force: Vec<usize>,
    a_speed: Vec<usize>,
    xi: Vec<f64>,
    tau: Vec<f64>,
    iterations: u32,
}

impl std::fmt::Debug for DepthQp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DepthQp")
            .field("n_stages", &self.n_stages)
            .finish_non_exhaustive()
    }
}

/// Row layout of A (m = 8N + 1).
struct Rows {
    n: usize,
}

impl Rows {
    fn xi_low(&self, k: usize) -> usize {
        k
    }
    fn xi_high(&self, k: usize) -> usize {
        self.n + k
    }
    fn trust_high(&self, k: usize) -> usize {
        2 * self.n + k
    }
    fn trust_low(&self, k: usize) -> usize {
        3 * self.n + k
    }
    fn speed(&self, k: usize) -> usize {
        4 * self.n + k
    }
    fn tau_low(&self, k: usize) -> usize {
        5 * self.n + k
    }
    fn budget(&self) -> usize {
        6 * self.n
    }
    fn force(&self, k: usize) -> usize {
        6 * self.n + 1 + k
    }
    fn slack_low(&self, k: usize) -> usize {
        7 * self.n + 1 + k
    }
    fn count(&self) -> usize {
        8 * self.n + 1
    }
}

/// Index of entry (row, col) in a CSC matrix's values.
fn nz_index(m: &CscMatrix<f64>, row: usize, col: usize) -> usize {
    (m.colptr[col]..m.colptr[col + 1])
        .find(|&i| m.rowval[i] == row)
        .expect("entry in the pattern")
}

impl DepthQp {
    /// Sets up the subproblem for `n_stages` stages with an iteration cap.
    ///
    /// # Panics
    /// Never for `n_stages` ≥ 1 (the pattern is built here, so every lookup
    /// finds its entry); Clarabel's setup errors only on malformed input.
    pub fn new(n_stages: usize, max_iterations: u32) -> Self {
        let n = n_stages;
        let rows = Rows { n };
        let (xi_col, tau_col, sigma_col) = (|k| k, |k| n + k, |k: usize| 2 * n + k);
        // P: ξ diagonal and super-diagonal, placeholders 1.
        let (mut pi, mut pj, mut pv) = (Vec::new(), Vec::new(), Vec::new());
        for k in 0..n {
            if k > 0 {
                pi.push(xi_col(k - 1));
                pj.push(xi_col(k));
                pv.push(-1.0);
            }
            pi.push(xi_col(k));
            pj.push(xi_col(k));
            pv.push(1.0);
        }
        let p = CscMatrix::new_from_triplets(3 * n, 3 * n, pi, pj, pv);
        let (mut ai, mut aj, mut av) = (Vec::new(), Vec::new(), Vec::new());
        let mut put = |r: usize, c: usize, v: f64| {
            ai.push(r);
            aj.push(c);
            av.push(v);
        };
        for k in 0..n {
            put(rows.xi_low(k), xi_col(k), -1.0);
            put(rows.xi_high(k), xi_col(k), 1.0);
            put(rows.trust_high(k), xi_col(k), 1.0);
            put(rows.trust_low(k), xi_col(k), -1.0);
            put(rows.speed(k), xi_col(k), 1.0);
            put(rows.speed(k), tau_col(k), -1.0);
            put(rows.tau_low(k), tau_col(k), -1.0);
            put(rows.budget(), xi_col(k), 1.0);
            put(rows.force(k), xi_col(k), 1.0);
            put(rows.force(k), sigma_col(k), -1.0);
            put(rows.slack_low(k), sigma_col(k), -1.0);
        }
        let m = rows.count();
        let a = CscMatrix::new_from_triplets(m, 3 * n, ai, aj, av);
        let p_diag = (0..n).map(|k| nz_index(&p, k, k)).collect();
        let p_super = (1..n).map(|k| nz_index(&p, k - 1, k)).collect();
        let a_budget = (0..n).map(|k| nz_index(&a, rows.budget(), k)).collect();
        let a_force = (0..n).map(|k| nz_index(&a, rows.force(k), k)).collect();
        let a_speed = (0..n).map(|k| nz_index(&a, rows.speed(k), n + k)).collect();
        let q = vec![0.0; 3 * n];
        let b = vec![1.0; m];
        let cones = [SupportedConeT::NonnegativeConeT(m)];
        let settings: DefaultSettings<f64> = DefaultSettingsBuilder::default()
            .verbose(false)
            .presolve_enable(false)
            .input_sparse_dropzeros(false)
            .max_iter(max_iterations)
            .iterative_refinement_enable(false)
            .build()
            .expect("valid Clarabel settings");
        let solver =
            DefaultSolver::new(&p, &q, &a, &b, &cones, settings).expect("a well-formed subproblem");
        Self {
            n_stages: n,
            solver,
            p,
            a,
            q,
            b,
            p_diag,
            p_super,
            a_budget,
            a_force,
            a_speed,
            xi: vec![0.0; n],
            tau: vec![0.0; n],
            iterations: 0,
        }
    }

    /// Number of stages.
    pub fn stages(&self) -> usize {
        self.n_stages
    }

    /// The convexified curvature the subproblem uses for a stage.
    pub fn curvature(cost: &StageCost) -> f64 {
        cost.work_per_depth_curvature
            .max(RELATIVE_MIN_CURVATURE * cost.work_per_depth.abs())
    }

    /// Objective of the subproblem at (ξ, τ), with each force slack at its
    /// optimum (the excess over the limit), plus the constant work of the
    /// stages at ξ̄ (so that it estimates the work to the target), J. For
    /// checks and tests; the solver minimises the same function.
    pub fn objective(
        stages: &[StageData],
        limits: &QpLimits,
        previous_xi: f64,
        xi: &[f64],
        tau: &[f64],
    ) -> f64 {
        let mut j = 0.0;
        let mut prev = previous_xi;
        for (k, s) in stages.iter().enumerate() {
            let dx = xi[k] - s.xi_bar;
            let h = Self::curvature(&s.cost);
            let l = s.contact_length;
            j += s.depth_step
                * l
                * (s.cost.work_per_depth + s.cost.work_per_depth_slope * dx + 0.5 * h * dx * dx);
            if k == 0 && s.before_fracture {
                let [w0, g0, h0] = s.onset;
                j += w0 + g0 * dx + 0.5 * h0.max(0.0) * dx * dx;
                j += limits.deformation_weight
                    * l
                    * (s.cost.deformation + s.cost.deformation_slope * dx);
            }
            let e = &s.entering;
            j += limits.deformation_weight * e.length * (e.deflection + e.deflection_slope * dx);
            if s.finish_slope != 0.0 {
                j += s.finish_slope * dx;
            }
            j += limits.time_weight * s.knife_descent() * tau[k];
            j += limits.smoothness_weight * (xi[k] - prev) * (xi[k] - prev);
            prev = xi[k];
            if limits.max_force.is_finite() {
                let force = l * (s.cost.force_normal + s.cost.force_normal_slope * dx);
                j += limits.force_penalty * (force - limits.max_force).max(0.0);
            }
        }
        j
    }

    /// Plans: fills the data for `stages` (exactly [`Self::stages`] of
    /// them), with `previous_xi` the ratio being executed and
    /// `blade_remaining` the travel left (m), and solves. Allocation-free in
    /// our code; clarabel 0.11.1 allocates one small block per solve in its
    /// timers (`controllers/tests/controller_alloc.rs`).
    pub fn solve(
        &mut self,
        stages: &[StageData],
        limits: &QpLimits,
        previous_xi: f64,
        blade_remaining: f64,
    ) -> QpStatus {
        let n = self.n_stages;
        debug_assert_eq!(stages.len(), n);
        let rows = Rows { n };
        let ws = limits.smoothness_weight;
        for v in self.p.nzval.iter_mut() {
            *v = 0.0;
        }
        for v in self.q.iter_mut() {
            *v = 0.0;
        }
        for (k, s) in stages.iter().enumerate() {
            let l = s.contact_length;
            let h = Self::curvature(&s.cost);
            let dd = s.depth_step;
            // Work: ½ h dx² + g dx with dx = ξ − ξ̄.
            self.p.nzval[self.p_diag[k]] += dd * l * h;
            self.q[k] += dd * l * (s.cost.work_per_depth_slope - h * s.xi_bar);
            if k == 0 && s.before_fracture {
                // Work to reach the fracture, ½h₀dx² + g₀dx, and deflection.
                let [_, g0, h0] = s.onset;
                let h0 = h0.max(0.0);
                self.p.nzval[self.p_diag[0]] += h0;
                self.q[0] += g0 - h0 * s.xi_bar;
                self.q[0] += limits.deformation_weight * l * s.cost.deformation_slope;
            }
            // Deflection of the edge entering contact, and the finish:
            // linear in ξ (the finish only where priced, so that a plan
            // without it is the same to the bit).
            self.q[k] +=
                limits.deformation_weight * s.entering.length * s.entering.deflection_slope;
            if s.finish_slope != 0.0 {
                self.q[k] += s.finish_slope;
            }
            // Smoothness (ξ_k − ξ_{k−1})², and (ξ_0 − ξ_prev)².
            self.p.nzval[self.p_diag[k]] += 2.0 * ws;
            if k == 0 {
                self.q[0] -= 2.0 * ws * previous_xi;
            } else {
                self.p.nzval[self.p_diag[k - 1]] += 2.0 * ws;
                self.p.nzval[self.p_super[k - 1]] = -2.0 * ws;
            }
            let descent = s.knife_descent();
            self.q[n + k] = limits.time_weight * descent;
            self.q[2 * n + k] = limits.force_penalty;
            // Rows.
            self.a.nzval[self.a_budget[k]] = descent;
            let slope = l * s.cost.force_normal_slope;
            self.a.nzval[self.a_force[k]] = slope;
            self.a.nzval[self.a_speed[k]] = -limits.tangential_speed;
            self.b[rows.xi_low(k)] = 0.0;
            self.b[rows.xi_high(k)] = limits.xi_max;
            self.b[rows.trust_high(k)] = s.xi_bar + limits.trust_region;
            self.b[rows.trust_low(k)] = -(s.xi_bar - limits.trust_region);
            self.b[rows.speed(k)] = 0.0;
            self.b[rows.tau_low(k)] = -1.0 / limits.normal_speed;
            self.b[rows.force(k)] = if limits.max_force.is_finite() {
                limits.max_force - l * s.cost.force_normal + slope * s.xi_bar
            } else {
                slope.abs() * limits.xi_max + 1.0
            };
            self.b[rows.slack_low(k)] = 0.0;
        }
        self.b[rows.budget()] = blade_remaining.max(0.0);
        let updated = self
            .solver
            .update_P(&self.p.nzval)
            .and_then(|()| self.solver.update_q(&self.q))
            .and_then(|()| self.solver.update_A(&self.a.nzval))
            .and_then(|()| self.solver.update_b(&self.b));
        if updated.is_err() {
            return QpStatus::Failed;
        }
        self.solver.solve();
        let sol = &self.solver.solution;
        self.iterations = sol.iterations;
        match sol.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => {
                for k in 0..n {
                    self.xi[k] = sol.x[k].clamp(0.0, limits.xi_max);
                    self.tau[k] = sol.x[n + k].max(1.0 / limits.normal_speed);
                }
                QpStatus::Solved
            }
            SolverStatus::MaxIterations | SolverStatus::MaxTime => QpStatus::IterationLimit,
            _ => QpStatus::Failed,
        }
    }

    /// The planned ratios of the last solved plan.
    pub fn xi(&self) -> &[f64] {
        &self.xi
    }

    /// The planned times per unit depth (s/m) of the last solved plan.
    pub fn tau(&self) -> &[f64] {
        &self.tau
    }

    /// Interior-point iterations of the last solve.
    pub fn iterations(&self) -> u32 {
        self.iterations
    }
}
