//! What a tick does when the successor it is due to take is not built yet
//! ([`Plant`](crate::Plant)'s docs, "Successors prepared ahead").

/// What [`Plant::step`](crate::Plant::step) does with a successor section
/// (a re-chosen plane's, or a segment's first) that the worker has not
/// finished when it is due.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SuccessorPolicy {
    /// The tick waits for the worker: what the plant does is a function of
    /// the commands alone, bit-identical however the worker is scheduled
    /// (lockstep, every test, tuning and comparison run).
    #[default]
    Wait,
    /// The tick never waits: the successor is taken on the first tick after
    /// the worker finished it (see [`Plant::successor_deferrals`]). A
    /// re-choice keeps stepping the section the segment has, on its plane,
    /// while the midpoint slides on past the update distance; a segment
    /// whose first section is not built has no section, so that strip of
    /// the edge cuts nothing (no force, no work, no crack) until it is
    /// taken. What the plant does then depends on the worker's timing: for
    /// a realtime servo loop, where a tick that waits misses its period.
    ///
    /// [`Plant::successor_deferrals`]: crate::Plant::successor_deferrals
    KeepCurrent,
}
