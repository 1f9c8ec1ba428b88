//! Time-optimal, jerk-limited online trajectory generation (OTG), written from the equations.
//!
//! For every DoF the generator moves from any current state `(p, v, a)` to any target state
//! under velocity, acceleration and jerk limits (symmetric or asymmetric) in minimal time, and
//! synchronises the DoFs (common finishing time, or a straight line). It serves the arm loop at
//! every control cycle ([`TrajectoryGenerator::update`]) and offline planning
//! ([`TrajectoryGenerator::calculate`] → [`Trajectory`]).
//!
//! ## Structure (one file per mathematical case)
//! * [`profile`]: piecewise constant-jerk profiles, exact integration, analytic extrema.
//! * `vel_change`: the second-order sub-problem `(v, a) → (v', a')` (closed form).
//! * `position_time_optimal`: the 7-phase time-optimal profile families (peak family and
//!   three-arc family), reduced to one scalar equation each.
//! * `position_fixed_duration`: profiles of prescribed duration for synchronisation.
//! * `velocity`: the velocity interface.
//! * `brake`: the braking pre-phase when a limit violation is unavoidable.
//! * `calculator`: braking, per-DoF solutions, blocked intervals, time and phase
//!   synchronisation, duration discretization.
//! * [`TrajectoryGenerator`]: the online interface.
//!
//! ## Guarantees
//! Every profile is verified before it is returned: it is integrated exactly and its final state
//! must match the target within 1e-9 (position, velocity) and 1e-11 (acceleration), and its
//! analytic extrema must respect every limit within a relative 1e-12 (after the braking
//! pre-phase, if any). No candidate is trusted on the strength of its derivation.
//!
//! ## Example
//! ```
//! use shearcut_controllers::trajectory::{TrajectoryGenerator, TrajectoryInput, TrajectoryOutput,
//!     TrajectorySettings, TrajectoryStatus};
//! let mut otg = TrajectoryGenerator::<1>::new(TrajectorySettings::default()).unwrap();
//! let mut input = TrajectoryInput::<1>::default();
//! input.target_position = [1.0];
//! let mut out = TrajectoryOutput::default();
//! while otg.update(&input, &mut out).unwrap() != TrajectoryStatus::Finished {
//!     out.pass_to_input(&mut input);
//! }
//! assert!((out.duration - 2.0 * 4f64.cbrt()).abs() < 1e-9);
//! ```

mod brake;
mod calculator;
mod dof;
mod generator;
mod input;
mod peak_polynomials;
mod peak_window;
pub mod polynomial;
mod position_fixed_duration;
mod position_time_optimal;
pub mod profile;
mod roots;
#[allow(clippy::module_inception)]
mod trajectory;
mod vel_change;
mod velocity;

pub use generator::{TrajectoryGenerator, TrajectoryOutput};
pub use input::{
    ControlInterface, DurationDiscretization, Synchronization, TrajectoryError, TrajectoryInput,
    TrajectorySettings, TrajectoryStatus,
};
pub use profile::{Bound, DofExtrema, DofState, Profile};
pub use trajectory::Trajectory;
