//! A sweep's `best-constant` grid: the constant slice-push ratios of
//! `compare`'s coarse search, from pressing to the largest ratio each
//! variant's blade budget allows over its depth
//! ([`crate::constant_ratio`]), so that each variant gets the best
//! constant ratio *for it*, found as `compare` finds it (the least mean
//! work over the replicas; `compare` then refines around it, a sweep does
//! not), to pair the MPC with (`crate::tune::best_constant_pairing`).
//!
//! One grid point is one controller setting of the sweep: point i of n is
//! the ratio round3(cap·i/(n − 1)) on whatever scenario it is applied to,
//! so its ratio differs between variants with other budgets or depths.

use serde::Serialize;
use shearcut_sim::{InvalidSetting, Knife};

use crate::closed_loop::cut_task;
use crate::constant_ratio::{coarse_grid, constant_choice, ratio_cap};
use crate::controller_choice::ControllerChoice;
use crate::scenario::Scenario;

/// The `kind` of a sweep's `[[controllers]]` entry that is the grid.
pub const BEST_CONSTANT_KIND: &str = "best-constant";

/// Most points a grid may have (each is a run per variant and replica).
pub const MAX_POINTS: usize = 21;

/// Point `index` of a grid of `points` constant ratios (`points` in
/// 2..=[`MAX_POINTS`], `index` < `points`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct ConstantGridPoint {
    /// Which point: 0 is pressing, `points` − 1 the cap.
    pub index: usize,
    /// Points of the grid.
    pub points: usize,
}

impl ConstantGridPoint {
    /// The point's name in tables: `best-constant:i/n` for ratio i/n of
    /// the cap (n = points − 1).
    pub fn label(&self) -> String {
        format!(
            "{BEST_CONSTANT_KIND}:{}/{}",
            self.index,
            self.points.saturating_sub(1)
        )
    }

    /// The constant-ratio controller this point is on scenario `s`: its
    /// cut task's ratio cap (blade budget over target depth, at most
    /// `[controller.mpc] max_slice_push_ratio`), i/(n − 1) of it.
    ///
    /// # Errors
    /// The scenario's knife or object cannot be built.
    pub fn choice_on(&self, s: &Scenario) -> Result<ControllerChoice, InvalidSetting> {
        let knife = Knife::new(&s.knife).map_err(|e| e.prefixed("knife"))?;
        let mesh = s
            .object
            .mesh()
            .map_err(|e| InvalidSetting::new("object", "mesh", e.to_string()))?;
        let cap = ratio_cap(
            &cut_task(s, &knife, &mesh)?,
            s.controller.mpc.max_slice_push_ratio,
        );
        let grid = coarse_grid(cap, self.points);
        Ok(constant_choice(grid[self.index.min(grid.len() - 1)]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_is_its_share_of_each_variants_cap() {
        // The half potato: 15 mm of blade over 25 mm of depth, cap 0.6.
        let s = Scenario::load("loop-potato-whole").unwrap();
        let p = |index| ConstantGridPoint { index, points: 6 };
        assert_eq!(p(0).choice_on(&s).unwrap(), ControllerChoice::Press);
        assert_eq!(p(4).choice_on(&s).unwrap(), ControllerChoice::Slice(0.48));
        assert_eq!(p(5).choice_on(&s).unwrap(), ControllerChoice::Slice(0.6));
        assert_eq!(p(4).label(), "best-constant:4/5");
        // 5 mm of blade: cap 0.2.
        let mut short = s.clone();
        short.controller.blade_budget = Some(0.005);
        assert_eq!(
            p(5).choice_on(&short).unwrap(),
            ControllerChoice::Slice(0.2)
        );
    }
}
