//! Whether the cut has reached its target.

use serde::{Deserialize, Serialize};
use shearcut_sim::{InvalidSetting, KnifeEdge};

use super::setting_range::check_range;

/// Where a cut ends.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum CutTarget {
    /// The edge this far below the touch point, m (in (0, 1]): the
    /// observed [`EdgeDepth`](super::EdgeDepth).
    Depth(f64),
    /// Through to the board: the edge's lowest point this close above the
    /// board (y = 0), m (in [0, 0.05]).
    Board {
        /// Clearance above the board, m.
        clearance: f64,
    },
}

impl CutTarget {
    /// Checks the value, naming the key.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        match self {
            Self::Depth(d) => check_range("depth", *d, 1e-9, 1.0, "m"),
            Self::Board { clearance } => check_range("board.clearance", *clearance, 0.0, 0.05, "m"),
        }
    }
}

/// Whether the cut has reached its [`CutTarget`]: the edge's depth below the
/// touch point at least the target depth, or the edge's lowest point (the
/// knife frame origin's height plus the edge's lowest point in the knife
/// frame) at most the clearance above the board (y = 0). Once done, done
/// (the knife is brought to rest and may be lifted).
///
/// Allocation-free, O(1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CutDone {
    target: CutTarget,
    /// Height of the edge's lowest point in the knife frame, m.
    edge_bottom: f64,
    /// Time the target was reached, s.
    done_at: Option<f64>,
}

impl CutDone {
    /// The test for `target` with the knife's `edge`.
    ///
    /// # Errors
    /// The target is out of range.
    pub fn new(target: CutTarget, edge: &KnifeEdge) -> Result<Self, InvalidSetting> {
        target.validate().map_err(|e| e.prefixed("target"))?;
        Ok(Self {
            target,
            edge_bottom: edge.lowest_point().1.y,
            done_at: None,
        })
    }

    /// Takes the reading's `time` (s), the knife height `y` (m) and the
    /// edge's depth below the touch point (m); returns whether the cut is
    /// done.
    pub fn observe(&mut self, time: f64, y: f64, edge_depth: f64) -> bool {
        if self.done_at.is_none() {
            let reached = match self.target {
                CutTarget::Depth(d) => edge_depth >= d,
                CutTarget::Board { clearance } => y + self.edge_bottom <= clearance,
            };
            if reached {
                self.done_at = Some(time);
            }
        }
        self.done_at.is_some()
    }

    /// When the target was reached, s.
    pub fn done_at(&self) -> Option<f64> {
        self.done_at
    }

    /// The target.
    pub fn target(&self) -> CutTarget {
        self.target
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shearcut_sim::{Knife, KnifePreset};

    #[test]
    fn depth_and_board_targets() {
        let chef = Knife::new(&KnifePreset::Chef.settings()).unwrap();
        let mut d = CutDone::new(CutTarget::Depth(0.02), chef.edge()).unwrap();
        assert!(!d.observe(1.0, 0.01, 0.0199));
        assert!(d.observe(2.0, 0.01, 0.02));
        assert!(d.observe(3.0, 0.05, 0.0));
        assert_eq!(d.done_at(), Some(2.0));
        // The chef's edge is lowest along its flat (knife frame y = 0).
        let mut b = CutDone::new(CutTarget::Board { clearance: 5e-4 }, chef.edge()).unwrap();
        assert!(!b.observe(1.0, 6e-4, 0.03));
        assert!(b.observe(2.0, 5e-4, 0.03));
        let e = CutDone::new(CutTarget::Depth(-0.01), chef.edge()).unwrap_err();
        assert!(e.to_string().starts_with("`target.depth` = -0.01"), "{e}");
    }
}
