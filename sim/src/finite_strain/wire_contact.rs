//! Contact of the rigid wire with the slab's top surface.
//!
//! **Normal contact: penalty with an active set.** Each top-surface node a is
//! kept outside the wire's circle (centre c, radius R in the cross section)
//! by the energy ½ k_a g_a², g_a = |x_a − c| − R, applied to the nodes of the
//! active set; k_a = κ μ ℓ_a / R (ℓ_a the node's tributary surface length): a
//! contact pressure of κμ per penetration R. The default κ = 10³ lets the
//! wire sink about R·p/(κμ) ≈ 10⁻² R into the surface at the pressures of
//! nucleation (p ≲ 10μ); the tests show the forces and the nucleation point
//! change by less than their stated tolerances when κ grows tenfold. In-plane
//! the wire is frictionless (the force is radial).
//!
//! **Along the wire: Coulomb (Amontons) friction, regularised by a stick
//! spring.** A node in contact sticks to the wire's travel w along z through
//! a spring of stiffness k_a as long as the spring force stays below μ_f times
//! its normal contact force f_n; beyond, it slides at that force. μ_f = ∞ is
//! the no-slip condition of seed 001's 3D simulations; a finite μ_f is the
//! fixed ratio f_t/f_n of its periodic-slab simulations wherever the wire
//! slides. A node enters stick at zero force when it first touches.
//!
//! **Solution: active sets.** Within one solve, the contact set, each node's
//! stick or slip state, its anchor and its cap μ_f f_n are held, which makes
//! the contact energy smooth (quadratic springs, and the linear potential
//! ±f̄ s of a sliding node), so Newton's method converges quadratically. After
//! each solve the sets are updated from the solution (contact where g < 0;
//! stick turns to slip where the spring force exceeds the cap, slip to stick
//! where it falls below) and the step is solved again until nothing that
//! carries force changes. A converged step then returns the anchors of sliding
//! nodes onto the slip surface, as in incremental plasticity.

#![allow(clippy::needless_range_loop)]

use super::system::{NodeTerm, SurfacePotential};

/// How a node in contact moves along the wire in the present solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Tangential {
    /// Stuck to the wire through the stick spring.
    Stick,
    /// Sliding; the friction force on the node along +z is −direction·cap.
    Slip {
        /// Sign of the spring stretch (+1 or −1).
        direction: f64,
    },
}

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
    /// Whether each node is in the contact set of the present solve.
    pub active: Vec<bool>,
    /// Stick anchor of each node (u_z − w at zero spring force), m; `None`
    /// when the node was not in contact at the last converged step.
    pub anchors: Vec<Option<f64>>,
    /// Stick or slip of each anchored node in the present solve.
    pub tangential: Vec<Tangential>,
    /// Largest friction force of each node, N/m (μ_f · f_n, or ∞).
    pub caps: Vec<f64>,
    /// Friction coefficient μ_f (f_t/f_n at sliding; ∞ = no slip).
    pub friction: f64,
}

/// The normal-contact part of a node's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NormalContact {
    /// Gap g = |x − c| − R, m (negative: penetration).
    pub gap: f64,
    /// Unit vector from the wire axis to the node.
    pub normal: [f64; 2],
    /// Distance from the wire axis, m.
    pub distance: f64,
}

impl WireContact {
    /// A wire touching nothing, for nodes with penalty stiffnesses `stiffness`.
    pub fn new(radius: f64, friction: f64, stiffness: Vec<f64>) -> Self {
        let n = stiffness.len();
        Self {
            centre: [0.0, 0.0],
            radius,
            travel: 0.0,
            stiffness,
            active: vec![false; n],
            anchors: vec![None; n],
            tangential: vec![Tangential::Stick; n],
            caps: vec![0.0; n],
            friction,
        }
    }

    /// Forgets all contact.
    pub fn release(&mut self) {
        self.travel = 0.0;
        self.active.fill(false);
        self.anchors.fill(None);
        self.tangential.fill(Tangential::Stick);
        self.caps.fill(0.0);
    }

    /// Normal-contact geometry of a node at deformed position `x` (m).
    pub fn normal(&self, x: [f64; 2]) -> NormalContact {
        let d = [x[0] - self.centre[0], x[1] - self.centre[1]];
        let r = (d[0] * d[0] + d[1] * d[1]).sqrt();
        let normal = if r > 0.0 {
            [d[0] / r, d[1] / r]
        } else {
            [0.0, -1.0]
        };
        NormalContact {
            gap: r - self.radius,
            normal,
            distance: r,
        }
    }

    /// Normal contact force of slot `slot` at position `x`, N/m (≥ 0).
    pub fn normal_force(&self, slot: usize, x: [f64; 2]) -> f64 {
        if self.active[slot] {
            (-self.stiffness[slot] * self.normal(x).gap).max(0.0)
        } else {
            0.0
        }
    }

    /// Spring stretch s = u_z − w − anchor of slot `slot`, m.
    pub fn stretch(&self, slot: usize, uz: f64) -> Option<f64> {
        self.anchors[slot].map(|a| uz - self.travel - a)
    }

    /// Friction force on the node along +z at stretch `s`, N/m.
    pub fn friction_force(&self, slot: usize, s: f64) -> f64 {
        match self.tangential[slot] {
            Tangential::Stick => -self.stiffness[slot] * s,
            Tangential::Slip { direction } => -direction * self.caps[slot],
        }
    }

    /// Activates the nodes that penetrate at `positions` (before a solve).
    pub fn activate(&mut self, positions: &[[f64; 2]]) {
        for (slot, &x) in positions.iter().enumerate() {
            self.active[slot] = self.normal(x).gap < 0.0;
        }
    }

    /// Updates the sets and caps from a solution (`positions`, `uz` of the
    /// nodes); returns whether anything that carries force changed: a node
    /// entering or leaving contact with a force above 10⁻⁶ of the largest, a
    /// stick–slip switch, or a cap moving by more than 10⁻⁶ of the largest.
    pub fn update(&mut self, positions: &[[f64; 2]], uz: &[f64]) -> bool {
        let forces: Vec<f64> = positions
            .iter()
            .enumerate()
            .map(|(slot, &x)| (-self.stiffness[slot] * self.normal(x).gap).abs())
            .collect();
        let largest = forces.iter().fold(0.0f64, |a, &b| a.max(b));
        let mut changed = false;
        for (slot, &x) in positions.iter().enumerate() {
            let penetrating = self.normal(x).gap < 0.0;
            if penetrating != self.active[slot] {
                self.active[slot] = penetrating;
                changed |= forces[slot] > 1e-6 * largest;
            }
        }
        let caps: Vec<f64> = positions
            .iter()
            .enumerate()
            .map(|(slot, &x)| {
                let f_n = self.normal_force(slot, x);
                if self.friction.is_infinite() {
                    f64::INFINITY
                } else {
                    self.friction * f_n
                }
            })
            .collect();
        let largest_cap = caps
            .iter()
            .filter(|c| c.is_finite())
            .fold(0.0f64, |a, &b| a.max(b));
        for slot in 0..caps.len() {
            if caps[slot].is_finite() && (caps[slot] - self.caps[slot]).abs() > 1e-6 * largest_cap {
                changed = true;
            }
            self.caps[slot] = caps[slot];
            let Some(s) = self.stretch(slot, uz[slot]) else {
                continue;
            };
            let k = self.stiffness[slot];
            let next = match self.tangential[slot] {
                Tangential::Stick if k * s.abs() > self.caps[slot] => Tangential::Slip {
                    direction: s.signum(),
                },
                Tangential::Slip { direction } if direction * k * s < self.caps[slot] => {
                    Tangential::Stick
                }
                t => t,
            };
            if next != self.tangential[slot] {
                changed = true;
                self.tangential[slot] = next;
            }
        }
        changed
    }

    /// After a converged step: sliding nodes' anchors back onto the slip
    /// surface, anchors (in stick) for nodes that touch, none for nodes that
    /// do not.
    pub fn commit(&mut self, uz: &[f64]) {
        for slot in 0..self.anchors.len() {
            if !self.active[slot] {
                self.anchors[slot] = None;
                self.tangential[slot] = Tangential::Stick;
                continue;
            }
            let rel = uz[slot] - self.travel;
            match (self.anchors[slot], self.tangential[slot]) {
                (None, _) => self.anchors[slot] = Some(rel),
                (Some(_), Tangential::Slip { direction }) => {
                    let k = self.stiffness[slot];
                    self.anchors[slot] = Some(rel - direction * self.caps[slot] / k);
                }
                (Some(_), Tangential::Stick) => {}
            }
        }
    }
}

impl SurfacePotential for WireContact {
    fn term(&self, slot: usize, reference: [f64; 2], u: [f64; 3]) -> NodeTerm {
        let mut t = NodeTerm::default();
        let k = self.stiffness[slot];
        if self.active[slot] {
            let n = self.normal([reference[0] + u[0], reference[1] + u[1]]);
            let g = n.gap;
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
            match self.tangential[slot] {
                Tangential::Stick => {
                    t.energy += 0.5 * k * s * s;
                    t.gradient[2] = k * s;
                    t.hessian[2][2] = k;
                }
                Tangential::Slip { direction } => {
                    t.energy += direction * self.caps[slot] * s;
                    t.gradient[2] = direction * self.caps[slot];
                }
            }
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wire(tangential: Tangential) -> WireContact {
        let mut w = WireContact::new(0.5, 0.5, vec![1e3]);
        w.centre = [0.0, 1.0];
        w.travel = 0.1;
        w.active[0] = true;
        w.anchors[0] = Some(0.0);
        w.tangential[0] = tangential;
        w.caps[0] = 2.0;
        w
    }

    /// The node term's gradient and Hessian are derivatives of its energy
    /// (central differences, step 1e-7 on unit-size data: error ~1e-7 of the
    /// entries), in stick and in slip.
    #[test]
    fn contact_term_is_consistent() {
        for (u, tangential) in [
            ([0.1, 0.15, 0.101], Tangential::Stick),
            ([0.05, 0.1, 0.2], Tangential::Slip { direction: 1.0 }),
        ] {
            let w = wire(tangential);
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
