//! Newton's method with a backtracking line search on the total energy.
//!
//! Each iteration assembles the exact Hessian of the discrete energy (elements
//! plus wire contact) and solves with a sparse Cholesky factorisation. An
//! indefinite Hessian (possible under large compression, and from the contact
//! term's curvature) is detected by the factorisation failing; the iteration
//! then adds a shift τ·I with τ = 10⁻⁸·max diag(K), multiplied by 10 until the
//! factorisation succeeds (a Levenberg–Marquardt-type modification), so every
//! search direction is a descent direction. The step length halves until the
//! Armijo condition Π(u + αΔ) ≤ Π(u) + 10⁻⁴ α ∇Π·Δ holds; near convergence,
//! where energy differences are at round-off, the full step is taken when the
//! energy rises by no more than 10⁻¹³ of the size of its summands
//! ([`System::energy_scale`] plus |Π|). The isochoric energy density
//! μ/2 (I₁ J^(−2/3) − 3) is the difference of terms of size 3μ/2, so at small
//! strain ε it carries a relative round-off of order 10⁻¹⁶/ε²: a criterion
//! relative to |Π| alone rejects every step once Π is small (a shallow
//! indentation) and stalls Newton's method at residuals ~10⁻⁸ N/m, above the
//! tolerance.

#![allow(clippy::needless_range_loop)]

use faer::Mat;
use faer::linalg::solvers::Solve;

use super::error::FiniteStrainError;
use super::system::{SurfacePotential, System};

/// Outcome of one energy minimisation.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct NewtonReport {
    /// Euclidean norm of the free-DOF gradient (the out-of-balance force) at
    /// each iterate, the last at the solution, N/m.
    pub residuals: Vec<f64>,
    /// Step length accepted in each iteration.
    pub step_lengths: Vec<f64>,
    /// Iterations that needed a diagonal shift (indefinite Hessian).
    pub shifted: u32,
    /// Whether the residual fell below the tolerance.
    pub converged: bool,
}

/// Minimises the energy of `system` over its free DOFs from `u` (m; prescribed
/// DOFs keep their values), until the gradient norm is at most `tolerance`
/// (N/m) or `max_iterations` have run.
pub(crate) fn minimise(
    system: &mut System,
    u: &mut [f64],
    surface: &dyn SurfacePotential,
    tolerance: f64,
    max_iterations: usize,
) -> Result<NewtonReport, FiniteStrainError> {
    let n = system.free_count();
    let dofs = system.free_dofs();
    let mut g = vec![0.0; n];
    let mut report = NewtonReport::default();
    let mut trial = u.to_vec();
    for _ in 0..=max_iterations {
        let eval = system
            .evaluate(u, surface, &mut g)
            .ok_or(FiniteStrainError::Inverted)?;
        let norm = g.iter().map(|x| x * x).sum::<f64>().sqrt();
        report.residuals.push(norm);
        if norm <= tolerance {
            report.converged = true;
            return Ok(report);
        }
        if report.residuals.len() > max_iterations {
            break;
        }
        let mut shift = 0.0;
        let llt = loop {
            if let Some(llt) = system.factor(shift) {
                break llt;
            }
            shift = if shift == 0.0 {
                1e-8 * system.largest_diagonal()
            } else {
                10.0 * shift
            };
            if !shift.is_finite() || shift > 1e6 * system.largest_diagonal() {
                return Err(FiniteStrainError::Factorisation(
                    "no positive definite shift",
                ));
            }
        };
        if shift > 0.0 {
            report.shifted += 1;
        }
        let mut step = Mat::<f64>::from_fn(n, 1, |i, _| -g[i]);
        llt.solve_in_place(step.as_mut());
        let slope: f64 = (0..n).map(|i| g[i] * step[(i, 0)]).sum();
        let mut alpha = 1.0;
        let accepted = loop {
            trial.copy_from_slice(u);
            for (i, &d) in dofs.iter().enumerate() {
                trial[d] += alpha * step[(i, 0)];
            }
            let e = system.energy(&trial, surface);
            let round_off = 1e-13 * (eval.energy.abs().max(e.abs()) + system.energy_scale());
            if e.is_finite()
                && (e <= eval.energy + 1e-4 * alpha * slope
                    || (alpha == 1.0 && e - eval.energy <= round_off))
            {
                break true;
            }
            alpha *= 0.5;
            if alpha < 1e-6 {
                break false;
            }
        };
        if !accepted {
            return Ok(report);
        }
        report.step_lengths.push(alpha);
        u.copy_from_slice(&trial);
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use nalgebra::Matrix3;

    use super::super::mesh::SlabMesh;
    use super::super::neo_hookean::NeoHookean;
    use super::super::system::NoSurface;
    use super::*;

    /// Patch test: a 4×4 patch of distorted quads with the boundary nodes
    /// placed on a homogeneous deformation F0 (large, with shear along the
    /// wire) — Newton's method puts the interior nodes on it too, and every
    /// element reports the closed-form stress. Tolerances: positions to 1e-12
    /// of the patch size (the solver's tolerance is 1e-12 of μ·size), stress
    /// to 1e-6 of μ.
    #[test]
    fn patch_test_reproduces_a_homogeneous_finite_deformation() {
        let size = 1e-3;
        let xs: Vec<f64> = (0..5).map(|i| size * i as f64 / 4.0).collect();
        let mut mesh = SlabMesh::structured(xs.clone(), xs);
        // Distort the interior nodes.
        for (n, p) in mesh.nodes.iter_mut().enumerate() {
            let interior = p[0] > 0.0 && p[0] < size && p[1] > 0.0 && p[1] < size;
            if interior {
                p[0] += 0.06 * size * ((n as f64) * 1.7).sin();
                p[1] += 0.05 * size * ((n as f64) * 2.3).cos();
            }
        }
        let material = NeoHookean::seed_gel(35e3);
        let f0 = Matrix3::new(1.3, 0.2, 0.0, -0.1, 0.8, 0.0, 0.4, -0.3, 1.0);
        let mut prescribed = vec![false; 3 * mesh.nodes.len()];
        let mut u = vec![0.0; 3 * mesh.nodes.len()];
        let exact: Vec<[f64; 3]> = mesh
            .nodes
            .iter()
            .map(|p| {
                let x = f0 * nalgebra::Vector3::new(p[0], p[1], 0.0);
                [x[0] - p[0], x[1] - p[1], x[2]]
            })
            .collect();
        for (n, p) in mesh.nodes.iter().enumerate() {
            let boundary = p[0] == 0.0 || p[0] == size || p[1] == 0.0 || p[1] == size;
            u[3 * n..3 * n + 3].copy_from_slice(&exact[n]);
            if boundary {
                prescribed[3 * n..3 * n + 3].fill(true);
            } else {
                // Start the interior off the solution.
                u[3 * n] += 0.03 * size * (n as f64).cos();
                u[3 * n + 1] -= 0.02 * size;
                u[3 * n + 2] += 0.05 * size;
            }
        }
        let mut system = System::new(mesh, material, &prescribed, Vec::new()).unwrap();
        let report = minimise(&mut system, &mut u, &NoSurface, 1e-12 * 35e3 * size, 50).unwrap();
        assert!(report.converged, "{report:?}");
        for (n, e) in exact.iter().enumerate() {
            for i in 0..3 {
                assert!((u[3 * n + i] - e[i]).abs() < 1e-12 * size);
            }
        }
        let sigma = material.cauchy(&f0);
        for e in 0..system.mesh.elements.len() {
            let ue = system.element_displacements(e, &u);
            for q in 0..5 {
                let s = system.element(e).cauchy(&material, q, &ue);
                assert!((s - sigma).abs().max() < 1e-6 * material.shear_modulus);
            }
        }
        // Quadratic convergence: once the residual is below 1e-2 of its
        // start, each iteration at least squares its relative size (up to a
        // constant of 10), until round-off.
        let r = &report.residuals;
        for w in r.windows(2) {
            let (a, b) = (w[0] / r[0], w[1] / r[0]);
            if a < 1e-2 && b > 1e-13 {
                assert!(b < 10.0 * a * a, "{r:?}");
            }
        }
    }

    /// Regression: at small strain (ε ~ 10⁻⁶–10⁻⁴, as in the far field or a
    /// shallow indentation) the total energy is ~ε² of its summands, so its
    /// round-off (~10⁻¹⁶ of the summands) exceeds 10⁻¹² of |Π|; a line
    /// search that forgives rises only within 10⁻¹² |Π| rejects Newton steps
    /// whose energy change is below round-off, at random, and stalls above
    /// the tolerance. Twelve load cases make a stall by chance all but
    /// certain under such a rule. The tolerance, 10⁻¹² μ·size, is the slab's
    /// default relative tolerance 10⁻⁹ μR scaled to this patch's forces.
    #[test]
    fn newton_reaches_the_tolerance_at_small_strain() {
        let size = 1e-3;
        let xs: Vec<f64> = (0..9).map(|i| size * i as f64 / 8.0).collect();
        let material = NeoHookean::seed_gel(35e3);
        for case in 0..12 {
            let strain =
                1e-6 * 10f64.powf(case as f64 / 6.0) * if case % 2 == 0 { 1.0 } else { -1.0 };
            let mesh = SlabMesh::structured(xs.clone(), xs.clone());
            let mut prescribed = vec![false; 3 * mesh.nodes.len()];
            let mut u = vec![0.0; 3 * mesh.nodes.len()];
            for (n, p) in mesh.nodes.iter().enumerate() {
                if p[1] == 0.0 {
                    prescribed[3 * n..3 * n + 3].fill(true);
                }
                if p[1] == size {
                    // The top pushed down (or pulled up) and dragged along z.
                    prescribed[3 * n + 1] = true;
                    prescribed[3 * n + 2] = true;
                    u[3 * n + 1] = -strain * size * (1.0 + p[0] / size);
                    u[3 * n + 2] = 0.7 * strain.abs() * size;
                }
            }
            let mut system = System::new(mesh, material, &prescribed, Vec::new()).unwrap();
            let report =
                minimise(&mut system, &mut u, &NoSurface, 1e-12 * 35e3 * size, 50).unwrap();
            assert!(report.converged, "strain {strain}: {report:?}");
        }
    }
}
