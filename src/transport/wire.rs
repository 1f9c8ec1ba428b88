//! The loop's wire format: fixed-size, `#[repr(C)]` messages that cross the
//! shared-memory link between controller and plant (layout, units and byte
//! offsets in `docs/wire_format.md`; a C or C++ arm bridge using iceoryx2's
//! own bindings declares the same structs). Little-endian IEEE-754 `f64`,
//! world frame (x across the knife plane, y up, z towards the knife's tip),
//! SI units. Conversions to and from the crates' types are lossless: the
//! lockstep loop over iceoryx2 is bit-identical to the in-process one.

use iceoryx2::prelude::ZeroCopySend;
use nalgebra::Vector3;
use shearcut_plant::{PlantTruth, Wrench};
use shearcut_sim::arm::{ArmReading, ArmStatus, KnifeCommand, LimitViolation};

/// [`WireCommand::flags`] bit: the run is over; the plant does not step,
/// answers with its last measurement and exits.
pub const FLAG_END_OF_RUN: u32 = 1;

/// The `sequence` of a board's initial entry: nothing written yet (no
/// command or measurement carries it).
pub const NO_SEQUENCE: u64 = u64::MAX;

/// One servo command, controller → plant (48 bytes).
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("shearcut::WireCommand")]
#[repr(C)]
pub struct WireCommand {
    /// Sequence number: 0 for the first command of a run, +1 per command.
    pub sequence: u64,
    /// Simulated time of the measurement this command answers, s (0 for the
    /// first command).
    pub time: f64,
    /// Commanded knife velocity [vx, vy, vz] in the world frame, m/s (vx
    /// must be 0: the knife moves in its own plane).
    pub velocity: [f64; 3],
    /// Bit set: [`FLAG_END_OF_RUN`]; other bits are reserved (0).
    pub flags: u32,
    /// Explicit padding to the 8-byte alignment; always 0.
    pub reserved: u32,
}

impl WireCommand {
    /// `command` as command number `sequence`, answering the measurement at `time`.
    pub fn new(sequence: u64, time: f64, command: &KnifeCommand) -> Self {
        Self {
            sequence,
            time,
            velocity: [command.velocity.x, command.velocity.y, command.velocity.z],
            flags: 0,
            reserved: 0,
        }
    }

    /// The end-of-run command number `sequence` (zero velocity).
    pub fn end_of_run(sequence: u64, time: f64) -> Self {
        Self {
            flags: FLAG_END_OF_RUN,
            ..Self::new(sequence, time, &KnifeCommand::default())
        }
    }

    /// The command board's initial entry: sequence [`NO_SEQUENCE`], zero
    /// velocity.
    pub fn empty() -> Self {
        Self::new(NO_SEQUENCE, 0.0, &KnifeCommand::default())
    }

    /// Whether this command ends the run.
    pub fn is_end_of_run(&self) -> bool {
        self.flags & FLAG_END_OF_RUN != 0
    }

    /// The plant's command.
    pub fn knife_command(&self) -> KnifeCommand {
        KnifeCommand {
            velocity: Vector3::from(self.velocity),
        }
    }
}

/// [`WireMeasurement::status`]: what the plant did with the command.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u32)]
pub enum WireStatus {
    /// The command was executed.
    Moving = 0,
    /// The command broke an arm limit and was refused: the knife holds still
    /// (the fault code says which limit, the fault value by how much).
    LimitViolation = 1,
    /// The plant braked after too many consecutive missed commands; it
    /// accepts no more commands (the fault value is the number missed).
    Braked = 2,
    /// The plant's model failed; it accepts no more commands.
    ModelFailed = 3,
    /// The plant acknowledged the end of the run and stops.
    Ended = 4,
}

/// [`WireMeasurement::fault`]: which arm limit a refused command broke.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u32)]
pub enum WireFault {
    /// No fault.
    None = 0,
    /// Speed above the limit (fault value: the speed, m/s).
    Velocity = 1,
    /// Finite-difference acceleration above the limit (value in m/s²).
    Acceleration = 2,
    /// Finite-difference jerk above the limit (value in m/s³).
    Jerk = 3,
    /// A non-finite command or period (value 0).
    NotFinite = 4,
    /// Consecutive missed commands reached the limit (value: the count).
    MissedCommands = 5,
}

/// One servo measurement, plant → controller (136 bytes): only what a
/// real arm and its F/T sensor report.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("shearcut::WireMeasurement.v2")]
#[repr(C)]
pub struct WireMeasurement {
    /// Sequence number of the command this measurement answers.
    pub sequence: u64,
    /// The arm's time after the tick, s.
    pub time: f64,
    /// Knife frame origin (heel end of the edge) [x, y, z], m.
    pub position: [f64; 3],
    /// Knife velocity actually executed [vx, vy, vz], m/s.
    pub velocity: [f64; 3],
    /// F/T sensor reading [fx, fy, fz, tx, ty, tz], N and N·m (object on
    /// knife, with the sensor's noise and bias).
    pub wrench: [f64; 6],
    /// The fault's value (see [`WireFault`]; 0 without a fault).
    pub fault_value: f64,
    /// A [`WireStatus`] code.
    pub status: u32,
    /// A [`WireFault`] code.
    pub fault: u32,
    /// Commands the plant missed so far (realtime clock: ticks without a
    /// command by their deadline).
    pub missed_commands: u32,
    /// Explicit padding to the 8-byte alignment; always 0.
    pub reserved: u32,
}

/// The simulated plant's ground truth after a tick, on its own service
/// (96 bytes): for recording only. A controller never acts on it, and an
/// arm bridge does not publish it.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("shearcut::WireTruth")]
#[repr(C)]
pub struct WireTruth {
    /// Sequence number of the command whose tick this is.
    pub sequence: u64,
    /// The noise-free wrench at the sensor [fx, fy, fz, tx, ty, tz], N and N·m.
    pub wrench: [f64; 6],
    /// Depth of the crack front below the object's top, m.
    pub crack_depth: f64,
    /// Length of edge in contact with material, m.
    pub contact_length: f64,
    /// Cumulative knife work on the object, J.
    pub work: f64,
    /// Largest surface deformation next to the blade, m.
    pub deformation: f64,
    /// Number of sections that have fractured.
    pub fractured_sections: u64,
}

impl WireTruth {
    /// The truth of the tick answering command `sequence`.
    pub fn new(sequence: u64, t: &PlantTruth) -> Self {
        Self {
            sequence,
            wrench: t.wrench.to_array(),
            crack_depth: t.crack_depth,
            contact_length: t.contact_length,
            work: t.work,
            deformation: t.deformation,
            fractured_sections: t.fractured_sections as u64,
        }
    }

    /// The board's entry before the plant's first tick.
    pub fn empty() -> Self {
        Self::new(NO_SEQUENCE, &PlantTruth::default())
    }

    /// The plant's truth (lossless).
    pub fn truth(&self) -> PlantTruth {
        let w = &self.wrench;
        PlantTruth {
            wrench: Wrench {
                force: Vector3::new(w[0], w[1], w[2]),
                torque: Vector3::new(w[3], w[4], w[5]),
            },
            crack_depth: self.crack_depth,
            contact_length: self.contact_length,
            fractured_sections: usize::try_from(self.fractured_sections).unwrap_or(usize::MAX),
            work: self.work,
            deformation: self.deformation,
        }
    }
}

/// The simulated plant's successor counts so far, on their own service (16
/// bytes): for the controller's `loop_stats.json` only. Written before
/// every measurement, so the answer to the end of the run finds the final
/// counts; an arm bridge does not publish it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ZeroCopySend)]
#[type_name("shearcut::WirePlantCounts")]
#[repr(C)]
pub struct WirePlantCounts {
    /// Successor sections found unbuilt when due and gone on without
    /// (`SuccessorPolicy::KeepCurrent`, the realtime clock): one per
    /// segment per tick.
    pub successor_deferrals: u64,
    /// Successor sections found unbuilt when due and waited for
    /// (`SuccessorPolicy::Wait`, lockstep): one per wait.
    pub successor_waits: u64,
}

/// A measurement the controller cannot use: the plant stopped, or the
/// message is malformed.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum WireError {
    /// The plant braked after `0` consecutive missed commands.
    #[error("the plant braked after {0} consecutive missed commands")]
    Braked(u64),
    /// The plant's model failed.
    #[error("the plant's model failed")]
    ModelFailed,
    /// The plant ended the run.
    #[error("the plant ended the run")]
    Ended,
    /// An unknown status or fault code.
    #[error("unknown status {status} or fault {fault} on the wire")]
    Unknown {
        /// The status code.
        status: u32,
        /// The fault code.
        fault: u32,
    },
    /// A field that no arm reports: not finite, or beyond
    /// [`WireMeasurement::BOUNDS`].
    #[error("`{field}` = {value} on the wire: no arm reports it (must be finite, within ±{bound})")]
    OutOfRange {
        /// The field (`position`, `wrench`...).
        field: &'static str,
        /// The value received.
        value: f64,
        /// Its bound in magnitude.
        bound: f64,
    },
}

impl WireMeasurement {
    /// `m` as the answer to command `sequence`, with `missed_commands` so far.
    pub fn new(sequence: u64, m: &ArmReading, missed_commands: u32) -> Self {
        let (status, fault, fault_value) = match m.status {
            ArmStatus::Moving => (WireStatus::Moving, WireFault::None, 0.0),
            ArmStatus::LimitViolation(v) => {
                let (f, x) = match v {
                    LimitViolation::Velocity(x) => (WireFault::Velocity, x),
                    LimitViolation::Acceleration(x) => (WireFault::Acceleration, x),
                    LimitViolation::Jerk(x) => (WireFault::Jerk, x),
                    LimitViolation::NotFinite => (WireFault::NotFinite, 0.0),
                };
                (WireStatus::LimitViolation, f, x)
            }
        };
        Self {
            sequence,
            time: m.time,
            position: [m.position.x, m.position.y, m.position.z],
            velocity: [m.velocity.x, m.velocity.y, m.velocity.z],
            wrench: m.wrench,
            fault_value,
            status: status as u32,
            fault: fault as u32,
            missed_commands,
            reserved: 0,
        }
    }

    /// The measurement board's initial entry: sequence [`NO_SEQUENCE`],
    /// every field 0 (status moving, no fault).
    pub fn empty() -> Self {
        Self {
            sequence: NO_SEQUENCE,
            time: 0.0,
            position: [0.0; 3],
            velocity: [0.0; 3],
            wrench: [0.0; 6],
            fault_value: 0.0,
            status: WireStatus::Moving as u32,
            fault: WireFault::None as u32,
            missed_commands: 0,
            reserved: 0,
        }
    }

    /// `self` with its status replaced: the plant stopped (`status` is
    /// [`WireStatus::Braked`], [`WireStatus::ModelFailed`] or
    /// [`WireStatus::Ended`]).
    pub fn stopped(mut self, status: WireStatus, fault: WireFault, fault_value: f64) -> Self {
        self.status = status as u32;
        self.fault = fault as u32;
        self.fault_value = fault_value;
        self
    }

    /// Largest magnitude of each field a measurement may carry, in its SI
    /// unit: a bridge that sends more (or NaN, ±inf) is faulty and its
    /// message is refused, never acted on. Far beyond any cutting cell: time
    /// 10⁶ s (11 days of one run), positions 10 m from the world origin,
    /// speeds 100 m/s, forces 10⁵ N and torques 10⁴ N·m at the sensor.
    pub const BOUNDS: [(&'static str, f64); 5] = [
        ("time", 1e6),
        ("position", 10.0),
        ("velocity", 100.0),
        ("wrench.force", 1e5),
        ("wrench.torque", 1e4),
    ];

    /// The first field beyond [`Self::BOUNDS`] or not finite (the fault
    /// value included), if any.
    fn out_of_range(&self) -> Option<WireError> {
        let [time, position, velocity, force, torque] = Self::BOUNDS.map(|(_, b)| b);
        let fields: [(&'static str, &[f64], f64); 6] = [
            ("time", std::slice::from_ref(&self.time), time),
            ("position", &self.position, position),
            ("velocity", &self.velocity, velocity),
            ("wrench.force", &self.wrench[..3], force),
            ("wrench.torque", &self.wrench[3..], torque),
            (
                "fault_value",
                std::slice::from_ref(&self.fault_value),
                f64::MAX,
            ),
        ];
        fields.into_iter().find_map(|(field, values, bound)| {
            values
                .iter()
                .find(|v| !(v.is_finite() && v.abs() <= bound))
                .map(|&value| WireError::OutOfRange {
                    field,
                    value,
                    bound,
                })
        })
    }

    /// The plant's measurement.
    ///
    /// # Errors
    /// The plant stopped (braked, failed or ended), a code is unknown, or a
    /// field is not finite or beyond [`Self::BOUNDS`].
    pub fn reading(&self) -> Result<ArmReading, WireError> {
        if let Some(e) = self.out_of_range() {
            return Err(e);
        }
        let unknown = WireError::Unknown {
            status: self.status,
            fault: self.fault,
        };
        let status = match self.status {
            0 => ArmStatus::Moving,
            1 => ArmStatus::LimitViolation(match self.fault {
                1 => LimitViolation::Velocity(self.fault_value),
                2 => LimitViolation::Acceleration(self.fault_value),
                3 => LimitViolation::Jerk(self.fault_value),
                4 => LimitViolation::NotFinite,
                _ => return Err(unknown),
            }),
            2 => return Err(WireError::Braked(self.fault_value as u64)),
            3 => return Err(WireError::ModelFailed),
            4 => return Err(WireError::Ended),
            _ => return Err(unknown),
        };
        Ok(ArmReading {
            time: self.time,
            position: Vector3::from(self.position),
            velocity: Vector3::from(self.velocity),
            wrench: self.wrench,
            status,
        })
    }
}
