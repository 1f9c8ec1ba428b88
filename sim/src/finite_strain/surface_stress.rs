//! The largest principal Cauchy stress σ₁ along the top surface, where seed
//! 001 places nucleation (σ₁ = σ* = 2μ), and over the whole slab (its Fig. 2).
//!
//! On the surface, σ is extrapolated linearly from the element's two Gauss
//! rows to its top edge (η = 1) at each upper point's ξ: σ_top = σ_up +
//! (1 − 1/√3)/(2/√3)·(σ_up − σ_low), which removes the O(h) bias of reading
//! it 0.21 element heights below the surface where stress gradients are steep
//! (under the wire). The isochoric stress comes from F at each point, the
//! pressure from the element's volumetric point.

#![allow(clippy::needless_range_loop)]

use super::element::CENTRE;
use super::neo_hookean::largest_principal;
use super::system::System;

/// Factor of the linear extrapolation from the Gauss rows η = ±1/√3 to η = 1.
const EXTRAPOLATION: f64 = (1.0 - 0.577_350_269_189_625_8) / (2.0 * 0.577_350_269_189_625_8);

/// σ₁ at one point of the top surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceStress {
    /// Reference (undeformed) distance from the wire's plane, m.
    pub position: f64,
    /// Largest principal Cauchy stress, Pa.
    pub stress: f64,
}

/// σ₁ on the top surface above the Gauss points of the top row of elements,
/// by increasing position.
pub(crate) fn surface_profile(system: &System, u: &[f64]) -> Vec<SurfaceStress> {
    let top_y = system.mesh.ys[system.mesh.ys.len() - 1];
    let mut out = Vec::new();
    for (e, el) in system.mesh.elements.iter().enumerate() {
        if system.mesh.nodes[el[2]][1] < top_y {
            continue;
        }
        let geom = system.element(e);
        let ue = system.element_displacements(e, u);
        // Upper points 3 (−ξ, +η) and 2 (+ξ, +η), left to right, with the
        // lower points 0 and 1 below them.
        for (q, below) in [(3, 0), (2, 1)] {
            let x: f64 = (0..4)
                .map(|a| geom.shapes[q][a] * system.mesh.nodes[el[a]][0])
                .sum();
            let up = geom.cauchy(&system.material, q, &ue);
            let low = geom.cauchy(&system.material, below, &ue);
            let s = up + (up - low) * EXTRAPOLATION;
            out.push(SurfaceStress {
                position: x,
                stress: largest_principal(&s),
            });
        }
    }
    out.sort_by(|a, b| a.position.total_cmp(&b.position));
    out
}

/// The surface point of largest σ₁.
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
