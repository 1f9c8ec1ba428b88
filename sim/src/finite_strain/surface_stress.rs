//! The largest principal Cauchy stress σ₁ at the top surface, where seed 001
//! places nucleation (σ₁ = σ* = 2μ), and over the whole slab (its Fig. 2).
//!
//! **The surface cell.** The criterion reads σ₁ averaged over a square cell
//! of the reference configuration at the surface, ℓ wide along it and ℓ deep
//! (`nucleation_cell_radii` × R; default R/4), centred at a distance X from
//! the wire's plane:
//!
//! ```text
//! σ̄₁(X) = 1/ℓ² ∫_{X−ℓ/2}^{X+ℓ/2} ∫_{B−ℓ}^{B} σ₁ dY dX
//! ```
//!
//! (mirrored across X = 0, where σ₁ is even). A pointwise surface value has
//! no mesh limit where slicing puts the maximum, at the edge of the contact:
//! there σ₁ falls off below the surface like ln(1/depth) (measured in
//! docs/seed001.md, "Mesh"), so a value read at the surface grows
//! with every refinement of the element rows, and it jumps as contact nodes
//! come and go. Its average over a cell is finite and converges. The seed's
//! own σ₁ is that of a lattice cell: its 3D slab (Fig. 3, where σ* = 2μ is
//! set against the experiment) has a node spacing of 100R/400 = R/4, hence
//! the default ℓ = R/4.
//!
//! **Integration.** Each element of the top rows contributes its σ₁ averaged
//! over its 2×2 Gauss points (isochoric stress from F at the point, pressure
//! K(J − 1) from the element's centre, as the element integrates its energy),
//! times its area inside the cell. Within a column the integrand is then
//! constant, so the cell average is piecewise linear in X with kinks where a
//! cell edge crosses a column boundary (or its mirror), and its maximum over
//! X is at one of those cells; the profile lists exactly them.

#![allow(clippy::needless_range_loop)]

use super::element::CENTRE;
use super::neo_hookean::largest_principal;
use super::system::System;

/// σ₁ averaged over the surface cell at one position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceStress {
    /// Reference (undeformed) distance of the cell's centre from the wire's
    /// plane, m.
    pub position: f64,
    /// Largest principal Cauchy stress averaged over the cell, Pa.
    pub stress: f64,
}

/// σ₁ averaged over the element `e`'s 2×2 Gauss points (their weights), Pa.
fn element_mean(system: &System, u: &[f64], e: usize) -> f64 {
    let geom = system.element(e);
    let ue = system.element_displacements(e, u);
    let (mut sum, mut weight) = (0.0, 0.0);
    for q in 0..4 {
        sum += geom.weights[q] * largest_principal(&geom.cauchy(&system.material, q, &ue));
        weight += geom.weights[q];
    }
    sum / weight
}

/// σ₁ averaged over surface cells of side `cell` (m) at the cells where the
/// average can peak (see the module docs), by increasing position.
pub(crate) fn surface_profile(system: &System, u: &[f64], cell: f64) -> Vec<SurfaceStress> {
    let mesh = &system.mesh;
    let rows = mesh.ys.len() - 1;
    let cols = mesh.top.len() - 1;
    let top = mesh.ys[rows];
    let xs: Vec<f64> = mesh.top.iter().map(|&n| mesh.nodes[n][0]).collect();
    // Per column: ∫ σ₁ dY over the cell's depth, N/m (piecewise constant in X).
    let mut column = vec![0.0; cols];
    for r in (0..rows).rev() {
        let overlap = mesh.ys[r + 1].min(top) - mesh.ys[r].max(top - cell);
        if overlap <= 0.0 {
            break;
        }
        for (c, col) in column.iter_mut().enumerate() {
            *col += overlap * element_mean(system, u, r * cols + c);
        }
    }
    // Prefix integrals over X: ∫_0^{xs[k]} ∫ σ₁ dY dX.
    let mut prefix = vec![0.0; cols + 1];
    for c in 0..cols {
        prefix[c + 1] = prefix[c] + column[c] * (xs[c + 1] - xs[c]);
    }
    let integral_to = |x: f64| -> f64 {
        // ∫_0^x for 0 ≤ x ≤ xs[cols].
        let k = xs.partition_point(|&b| b <= x).clamp(1, cols);
        prefix[k - 1] + column[k - 1] * (x - xs[k - 1])
    };
    let width = xs[cols];
    let mut centres: Vec<f64> = Vec::with_capacity(3 * xs.len());
    for &x in &xs {
        for c in [x + 0.5 * cell, x - 0.5 * cell, 0.5 * cell - x] {
            if c >= 0.0 && c + 0.5 * cell <= width {
                centres.push(c);
            }
        }
    }
    centres.sort_by(f64::total_cmp);
    centres.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * cell);
    centres
        .into_iter()
        .map(|c| {
            let (a, b) = (c - 0.5 * cell, c + 0.5 * cell);
            // σ₁ is even in X: the part of the cell at X < 0 is its mirror.
            let integral = if a >= 0.0 {
                integral_to(b) - integral_to(a)
            } else {
                integral_to(b) + integral_to(-a)
            };
            SurfaceStress {
                position: c,
                stress: integral / (cell * cell),
            }
        })
        .collect()
}

/// The surface cell of largest σ₁.
pub(crate) fn surface_maximum(profile: &[SurfaceStress]) -> SurfaceStress {
    profile
        .iter()
        .copied()
        .fold(None, |best: Option<SurfaceStress>, p| match best {
            Some(b) if b.stress >= p.stress => Some(b),
            _ => Some(p),
        })
        .unwrap_or(SurfaceStress {
            position: 0.0,
            stress: 0.0,
        })
}

/// The deformed slab with σ₁ per element (at its centre), for a heat map.
#[derive(Debug, Clone, PartialEq)]
pub struct StressField {
    /// Deformed node positions (x, y) of the half slab, m.
    pub nodes: Vec<[f64; 2]>,
    /// Elements as four node indices, counter-clockwise.
    pub elements: Vec<[usize; 4]>,
    /// σ₁ at each element's centre, Pa.
    pub largest_principal: Vec<f64>,
}

pub(crate) fn stress_field(system: &System, u: &[f64]) -> StressField {
    let nodes = system
        .mesh
        .nodes
        .iter()
        .enumerate()
        .map(|(n, p)| [p[0] + u[3 * n], p[1] + u[3 * n + 1]])
        .collect();
    let largest_principal = (0..system.mesh.elements.len())
        .map(|e| {
            let ue = system.element_displacements(e, u);
            largest_principal(&system.element(e).cauchy(&system.material, CENTRE, &ue))
        })
        .collect();
    StressField {
        nodes,
        elements: system.mesh.elements.clone(),
        largest_principal,
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Matrix3;

    use super::super::mesh::SlabMesh;
    use super::super::neo_hookean::NeoHookean;
    use super::*;

    /// A homogeneous deformation gives every cell the closed-form σ₁ (to
    /// round-off: every Gauss point carries the same stress), whatever the
    /// cell's size relative to the graded elements.
    #[test]
    fn homogeneous_stress_gives_every_cell_its_value() {
        let mesh = SlabMesh::half_slab(2e-3, 2e-3, 1e-4, 4e-4, 1.3, 5e-4, 3);
        let material = NeoHookean::seed_gel(35e3);
        let f0 = Matrix3::new(1.2, 0.1, 0.0, 0.0, 0.9, 0.0, 0.3, 0.0, 1.0);
        let u: Vec<f64> = mesh
            .nodes
            .iter()
            .flat_map(|p| {
                let x = f0 * nalgebra::Vector3::new(p[0], p[1], 0.0);
                [x[0] - p[0], x[1] - p[1], x[2]]
            })
            .collect();
        let prescribed = vec![true; u.len()];
        let system = System::new(mesh, material, &prescribed, Vec::new()).unwrap();
        let expected = largest_principal(&material.cauchy(&f0));
        for cell in [0.7e-4, 1e-4, 3.3e-4] {
            let profile = surface_profile(&system, &u, cell);
            assert!(!profile.is_empty());
            for p in &profile {
                assert!(
                    (p.stress - expected).abs() < 1e-9 * material.shear_modulus,
                    "cell {cell}: {p:?} vs {expected}"
                );
            }
        }
    }
}
