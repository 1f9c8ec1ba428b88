//! Replicas of a closed-loop run: the same cut with the knife starting a
//! few micrometres higher above the object, to see how far the plant's
//! discrete crack events move a result.
//!
//! The plant's cracks advance row by row of the sections' meshes (every
//! 0.2 mm) in jumps, and a section fractures on the tick its energy balance
//! is first met. Where those ticks fall along the knife's path decides how
//! much strain energy each jump releases unused, so a single run's work
//! depends on the phase of the servo ticks against the object: the knife
//! moves 20 µm per tick at 20 mm/s and 1 kHz (docs/results.md measures
//! the spread this gives a constant ratio on the potato cuboid). Comparing
//! controllers by one run each, and picking the best constant ratio as the
//! smallest of a dozen such runs, favours whichever run happened to fall
//! on the cheap side.
//!
//! Replica k starts the knife k·[`START_STEP`] (5 µm) further above the
//! object than the scenario's `[plant] start_gap`: the object, the plant
//! and the controller are the scenario's, and the first contact comes
//! k·0.25 ms later at 20 mm/s. Eight replicas span 35 µm: 1.75 ticks'
//! travel at the baselines' 20 mm/s, 0.7 of a tick at the MPC's 50 mm/s
//! cap, and the phase of the later crack events is scrambled further by
//! the run itself. The mean over them estimates the work a controller
//! does on the object whatever the servo's phase, and their spread shows
//! the plant's scatter.

/// How much higher each replica step starts the knife, m.
pub const START_STEP: f64 = 5e-6;

/// One replica: the knife starts `index`·[`START_STEP`] higher than the
/// scenario says (index 0 is the scenario as given).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RunReplica {
    /// Steps of [`START_STEP`].
    pub index: u32,
}

impl RunReplica {
    /// The run as the scenario gives it.
    pub const NOMINAL: Self = Self { index: 0 };

    /// The height of the edge's lowest point over the object above the
    /// object's top at the start, m, for a scenario whose `[plant]
    /// start_gap` is `gap` (the nominal replica's is `gap` bit for bit).
    pub fn start_gap(&self, gap: f64) -> f64 {
        gap + self.start_offset()
    }

    /// How much higher the knife starts, m.
    pub fn start_offset(&self) -> f64 {
        f64::from(self.index) * START_STEP
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_replica_raises_the_start_by_whole_steps() {
        assert_eq!(RunReplica::NOMINAL.start_gap(0.001), 0.001);
        assert_eq!(RunReplica { index: 3 }.start_offset(), 3.0 * START_STEP);
        let g = RunReplica { index: 7 }.start_gap(0.001);
        assert!((g - 0.001_035).abs() < 1e-15, "{g}");
    }
}
