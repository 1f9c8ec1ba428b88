//! Contact of the rigid wire with the slab's top surface.
//!
//! **Normal contact: penalty.** Each top-surface node a is kept outside the
//! wire's circle (centre c, radius R in the cross section) by the energy
//! ½ k_a ⟨−g_a⟩², g_a = |x_a − c| − R, with k_a = κ μ ℓ_a / R (ℓ_a the node's
//! tributary surface length): a contact pressure of κμ per penetration R.
//! The default κ = 10³ lets the wire sink about R·p/(κμ) ≈ 10⁻² R into the
//! surface at the pressures of nucleation (p ≲ 10μ); the tests show the
//! forces and the nucleation point move by less than the stated tolerances
//! when κ grows tenfold. In-plane, the wire is frictionless (the force is
//! radial).
//!
//! **Along the wire: regularised Coulomb (Amontons) friction.** A node in
//! contact sticks to the wire's travel w along z through a stiff spring
//! (k_a again) as long as its spring force stays below μ_f times its normal
//! contact force; beyond, it slides at that force. Within a load step the
//! spring's anchor and the cap μ_f f_n are held (from the last converged state),
//! which makes the friction term the convex, C¹ energy
//! φ(s) = ½ k s² for k|s| ≤ f̄, f̄|s| − f̄²/(2k) beyond, with s = u_z − w − anchor;
//! after convergence the cap is refreshed from the new normal forces (a few
//! passes per step) and the anchors are returned to the slip surface, as in
//! incremental plasticity. μ_f = ∞ is the no-slip condition of seed 001's 3D
//! simulations; a finite μ_f is the fixed ratio f_t/f_n of its periodic-slab
//! simulations wherever the wire slides. A node enters stick at zero force
//! when it first touches.

#![allow(clippy::needless_range_loop)]

use super::system::{NodeTerm, SurfacePotential};

/// The wire and the contact state of the top-surface nodes (by slot).
#[derive(Debug, Clone)]
pub(crate) struct WireContact {
    /// Wire axis in the cross section (deformed configuration), m.
    pub centre: [f64; 2],
    /// Wire radius R, m.
    pub radius: f64,
    /// Wire displacement along its axis (z), m.
    pub travel: f64,
    /// Penalty stiffness of each node, N/m².
    pub stiffness: Vec<f64>,
    /// Stick anchor of each node (u_z − w at zero spring force), m; `None`
    /// when the node is not in contact.
    pub anchors: Vec<Option<f64>>,
    /// Largest friction force of each node, N/m (μ_f · f_n, or ∞).
    pub caps: Vec<f64>,
    /// Friction coefficient μ_f (f_t/f_n at sliding; ∞ = no slip).
    pub friction: f64,
}

/// The normal-contact part of a node's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NormalContact {
    /// Penetration −g ≥ 0, m (0 when apart).
    pub penetration: f64,
    /// Unit vector from the wire axis to the node.
    pub normal: [f64; 2],
    /// Distance from the wire axis, m.
    pub distance: f64,
}

impl WireContact {
    /// Normal-contact state of a node at deformed position `x` (m).
    pub fn normal(&self, x: [f64; 2]) -> NormalContact {
        let d = [x[0] - self.centre[0], x[1] - self.centre[1]];
        let r = (d[0] * d[0] + d[1] * d[1]).sqrt();
        let normal = if r > 0.0 {
            [d[0] / r, d[1] / r]
        } else {
            [0.0, -1.0]
        };
        NormalContact {
            penetration: (self.radius - r).max(0.0),
            normal,
            distance: r,
        }
    }

    /// Spring stretch s = u_z − w − anchor of slot `slot`, m.
    pub fn stretch(&self, slot: usize, uz: f64) -> Option<f64> {
        self.anchors[slot].map(|a| uz - self.travel - a)
    }

    /// Friction force on the node along +z for stretch `s` (N/m, the
    /// derivative of φ with its sign flipped).
    pub fn friction_force(&self, slot: usize, s: f64) -> f64 {
        let k = self.stiffness[slot];
        let cap = self.caps[slot];
        -(k * s).clamp(-cap, cap)
    }

    /// After a converged step: anchors back onto the slip surface, anchors
    /// for nodes that touch, none for nodes that left; then caps μ_f · f_n.
    /// `positions` and `uz` are the nodes' deformed positions and u_z.
    pub fn commit(&mut self, positions: &[[f64; 2]], uz: &[f64]) {
        for slot in 0..self.anchors.len() {
            let n = self.normal(positions[slot]);
            if n.penetration <= 0.0 {
                self.anchors[slot] = None;
                self.caps[slot] = 0.0;
                continue;
            }
            let rel = uz[slot] - self.travel;
            match self.anchors[slot] {
                None => self.anchors[slot] = Some(rel),
                Some(a) => {
                    let k = self.stiffness[slot];
                    let s = rel - a;
                    let cap = self.caps[slot];
                    if k * s.abs() > cap {
                        self.anchors[slot] = Some(rel - s.signum() * cap / k);
                    }
                }
            }
        }
        self.refresh_caps(positions);
    }

    /// Caps μ_f · f_n from the nodes' normal forces at `positions`; returns
    /// the largest change of a cap, N/m.
    pub fn refresh_caps(&mut self, positions: &[[f64; 2]]) -> f64 {
        let mut change = 0.0f64;
        for slot in 0..self.caps.len() {
            let fn_ = self.stiffness[slot] * self.normal(positions[slot]).penetration;
            let cap = if self.friction.is_infinite() {
                f64::INFINITY
            } else {
                self.friction * fn_
            };
            if cap.is_finite() {
                change = change.max((cap - self.caps[slot]).abs());
            }
            self.caps[slot] = cap;
        }
        change
    }
}

impl SurfacePotential for WireContact {
    fn term(&self, slot: usize, reference: [f64; 2], u: [f64; 3]) -> NodeTerm {
        let mut t = NodeTerm::default();
        let k = self.stiffness[slot];
        let n = self.normal([reference[0] + u[0], reference[1] + u[1]]);
        if n.penetration > 0.0 {
            let g = -n.penetration;
            t.energy += 0.5 * k * g * g;
            let curv = g / n.distance;
            for i in 0..2 {
                t.gradient[i] = k * g * n.normal[i];
                for j in 0..2 {
                    let delta = if i == j { 1.0 } else { 0.0 };
                    t.hessian[i][j] = k
                        * (n.normal[i] * n.normal[j] + curv * (delta - n.normal[i] * n.normal[j]));
                }
            }
        }
        if let Some(s) = self.stretch(slot, u[2]) {
            let cap = self.caps[slot];
            if k * s.abs() <= cap {
                t.energy += 0.5 * k * s * s;
                t.gradient[2] = k * s;
                t.hessian[2][2] = k;
            } else {
                t.energy += cap * s.abs() - 0.5 * cap * cap / k;
                t.gradient[2] = cap * s.signum();
            }
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wire() -> WireContact {
        WireContact {
            centre: [0.0, 1.0],
            radius: 0.5,
            travel: 0.1,
            stiffness: vec![1e3],
            anchors: vec![Some(0.0)],
            caps: vec![2.0],
            friction: 0.5,
        }
    }

    /// The node term's gradient and Hessian are derivatives of its energy
    /// (central differences, step 1e-7 on unit-size data: error ~1e-7 of the
    /// entries), in stick and in slip.
    #[test]
    fn contact_term_is_consistent() {
        let w = wire();
        for u in [[0.1, 0.15, 0.101], [0.05, 0.1, 0.2]] {
            let t = w.term(0, [0.0, 0.5], u);
            let eps = 1e-7;
            for d in 0..3 {
                let (mut up, mut um) = (u, u);
                up[d] += eps;
                um[d] -= eps;
                let tp = w.term(0, [0.0, 0.5], up);
                let tm = w.term(0, [0.0, 0.5], um);
                let fd = (tp.energy - tm.energy) / (2.0 * eps);
                assert!((fd - t.gradient[d]).abs() < 1e-5 * (1.0 + t.gradient[d].abs()));
                for r in 0..3 {
                    let fd = (tp.gradient[r] - tm.gradient[r]) / (2.0 * eps);
                    assert!((fd - t.hessian[r][d]).abs() < 1e-4 * 1e3, "H[{r}][{d}]");
                }
            }
        }
    }
}
