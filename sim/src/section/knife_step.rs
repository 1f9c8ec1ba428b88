//! One knife step of a section (seed 000 §III.C, DESIGN §3.2a): the knife
//! moves down by dn and along the edge by dt from the section's state; where
//! the edge ends, the step's slice-push ratio ξ, and the drag of the edge
//! along the cut for a trial crack extension s or a knife advance t.

use super::equilibrium::{Eval, evaluate};
use super::simulation::{Model, Workspace};

/// The kinematics of one knife step from the crack tip at `y_tip`, the edge
/// at `y_edge` (m above the board) and the drag `drag` (m along the edge).
///
/// The drag follows the seed's "nodes in contact are fixed on the edge": it
/// grows by the knife's tangential increment while the edge indents below
/// the tip, is kept while the edge follows the crack (τ = ξ·d for a constant
/// ξ), and is 0 once the edge is at or above the tip.
#[derive(Debug, Clone, Copy)]
pub(super) struct KnifeStep {
    /// Crack tip height at the start of the step, m.
    pub(super) y_tip: f64,
    /// Edge height at the start of the step, m.
    pub(super) y_edge: f64,
    /// Drag of the edge along the cut at the start of the step, m.
    pub(super) drag: f64,
    /// Vertical knife increment dn ≥ 0, m.
    pub(super) dn: f64,
    /// Tangential knife increment |dt|, m.
    pub(super) dt_abs: f64,
    /// Slice-push ratio ξ = |dt|/dn (∞ for dn = 0).
    pub(super) xi: f64,
    /// Edge height at the end of the step, y_edge − dn, m.
    pub(super) y_edge1: f64,
    /// Indentation at the start of the step, y_tip − y_edge, m.
    indentation: f64,
}

impl KnifeStep {
    /// The step moving the knife by (`dn`, `dt`) from the tip at `y_tip`,
    /// the edge at `y_edge` and the drag `drag`.
    pub(super) fn new(y_tip: f64, y_edge: f64, drag: f64, dn: f64, dt: f64) -> Self {
        let dt_abs = dt.abs();
        Self {
            y_tip,
            y_edge,
            drag,
            dn,
            dt_abs,
            xi: if dn > 0.0 { dt_abs / dn } else { f64::INFINITY },
            y_edge1: y_edge - dn,
            indentation: y_tip - y_edge,
        }
    }

    /// ξ clamped to the largest finite double (so that ξ·0 = 0).
    pub(super) fn xi_finite(&self) -> f64 {
        self.xi.min(f64::MAX)
    }

    /// Drag at the end of the step with crack extension `s` (m): the tip at
    /// y_tip − s, the edge at y_edge − dn.
    pub(super) fn drag_at(&self, s: f64) -> f64 {
        let d1 = self.y_tip - s - self.y_edge1;
        if d1 <= 0.0 {
            0.0
        } else if self.indentation <= 0.0 {
            if self.dn > 0.0 {
                self.dt_abs * d1 / self.dn
            } else {
                0.0
            }
        } else {
            self.drag + self.dt_abs - self.xi_finite() * s
        }
    }

    /// Drag at a knife advance `t` ∈ [0, dn] (m) of a step without crack
    /// growth.
    pub(super) fn drag_mid(&self, t: f64) -> f64 {
        let d = self.y_tip - (self.y_edge - t);
        if d <= 0.0 {
            0.0
        } else if self.indentation <= 0.0 {
            self.xi_finite() * d
        } else {
            self.drag + self.xi_finite() * t
        }
    }

    /// The equilibrium at the end of the step with crack extension `s` (m),
    /// friction for the step's increments. Allocation-free.
    pub(super) fn at_extension(&self, model: &Model, ws: &mut Workspace, s: f64) -> Eval {
        evaluate(
            model,
            ws,
            self.y_tip - s,
            self.y_edge1,
            self.drag_at(s),
            self.dn,
            self.dt_abs,
        )
    }

    /// The equilibrium at a knife advance `t` ∈ [0, dn] (m) of a step
    /// without crack growth, friction for the step's increments.
    /// Allocation-free.
    pub(super) fn at_advance(&self, model: &Model, ws: &mut Workspace, t: f64) -> Eval {
        evaluate(
            model,
            ws,
            self.y_tip,
            self.y_edge - t,
            self.drag_mid(t),
            self.dn,
            self.dt_abs,
        )
    }
}
