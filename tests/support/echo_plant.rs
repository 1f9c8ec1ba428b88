//! A plant that answers each command with it at once: the transport alone,
//! for the iceoryx2 latency bench and allocation test (included with
//! `#[path]`, so each binary compiles its own copy).

use nalgebra::Vector3;
use shearcut::closed_loop::{LinkAnswer, LinkError, PlantLink};
use shearcut_plant::PlantTruth;
use shearcut_sim::arm::{ArmReading, ArmStatus, KnifeCommand};

/// Steps 1 ms per command; the reading echoes the commanded velocity.
pub struct EchoPlant {
    time: f64,
}

impl EchoPlant {
    /// At time 0.
    pub fn new() -> Self {
        Self { time: 0.0 }
    }
}

impl PlantLink for EchoPlant {
    fn period(&self) -> f64 {
        1e-3
    }

    fn exchange(&mut self, command: &KnifeCommand) -> Result<LinkAnswer, LinkError> {
        self.time += 1e-3;
        Ok(LinkAnswer {
            reading: ArmReading {
                time: self.time,
                position: Vector3::zeros(),
                velocity: command.velocity,
                wrench: [0.0; 6],
                status: ArmStatus::Moving,
            },
            truth: Some(PlantTruth::default()),
        })
    }
}

/// Removes this process's files under `/dev/shm` whose names start with
/// `prefix` (each iceoryx2 prefix keeps a small management file by design).
pub fn remove_shm_files(prefix: &str) {
    if let Ok(entries) = std::fs::read_dir("/dev/shm") {
        for e in entries.flatten() {
            if e.file_name().to_string_lossy().starts_with(prefix) {
                std::fs::remove_file(e.path()).ok();
            }
        }
    }
}
