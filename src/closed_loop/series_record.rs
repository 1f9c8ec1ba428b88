//! One entry of the queue from the loop's thread to the series writer.

use super::control_record::ControlSample;
use crate::cut_record::CutSample;

/// What the loop hands the series writer: a row of `timeseries.csv`, a row
/// of `controller.csv`, or the end of a tick. Fixed size and `Copy`: a push
/// is a copy into the queue's preallocated slot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum SeriesRecord {
    /// A sample of the cut (a row of `timeseries.csv`).
    Sample(CutSample),
    /// The controller's record of a tick (a row of `controller.csv`).
    Control(ControlSample),
    /// The end of the tick at this simulated time, s: the writer flushes
    /// when a [`FLUSH_PERIOD`](super::FLUSH_PERIOD) has passed.
    TickDone(f64),
}
