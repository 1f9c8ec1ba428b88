//! The largest principal Cauchy stress σ₁ along the top surface, where seed
//! 001 places nucleation (σ₁ = σ* = 2μ), and over the whole slab (its Fig. 2).
//!
//! σ₁ is evaluated at the upper Gauss points of the top row of elements
//! (0.21 of an element height below the surface), with the isochoric stress
//! from F at the point and the pressure from the element's volumetric point.

#![allow(clippy::needless_range_loop)]

use super::element::CENTRE;
use super::neo_hookean::largest_principal;
use super::system::System;

/// σ₁ at one point below the top surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceStress {
    /// Reference (undeformed) distance from the wire's plane, m.
    pub position: f64,
    /// Largest principal Cauchy stress, Pa.
    pub stress: f64,
}

/// σ₁ at the upper Gauss points of the top row of elements, by increasing
/// position.
pub(crate) fn surface_profile(system: &System, u: &[f64]) -> Vec<SurfaceStress> {
    let top_y = system.mesh.ys[system.mesh.ys.len() - 1];
    let mut out = Vec::new();
    for (e, el) in system.mesh.elements.iter().enumerate() {
        if system.mesh.nodes[el[2]][1] < top_y {
            continue;
        }
        let geom = system.element(e);
        let ue = system.element_displacements(e, u);
        // Points 3 (−ξ, +η) and 2 (+ξ, +η): left to right.
        for q in [3, 2] {
            let x: f64 = (0..4)
                .map(|a| geom.shapes[q][a] * system.mesh.nodes[el[a]][0])
                .sum();
            let s = geom.cauchy(&system.material, q, &ue);
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
