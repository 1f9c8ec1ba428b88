//! # 02: the plant open loop: a half potato under the chef's knife, wrench out
//!
//! Shows the plant as an arm's controller meets it: build it from a
//! material, a knife, an object and where the object sits along the edge,
//! then send it one knife velocity per 1 ms servo tick and read back what a
//! wrist F/T sensor would report. Here the velocity is prescribed (a
//! constant slice-push ratio ξ = 0.5 at 20 mm/s, reached over a 50 ms ramp
//! that stays inside the arm's acceleration and jerk limits); closing the
//! loop on the wrench is what the controllers do.
//!
//! The object is `loop-potato-whole`'s half potato (90 × 60 × 35 mm, flat
//! base, Table I whole potato) 20 mm from the chef's knife's heel; the plant
//! places 20 cross sections where the edge meets it (seed 000 §IV).
//!
//! Prints every 100 ms: time, the knife's travel from its start 1 mm above
//! the potato, the crack front's depth below the potato's top, the edge in contact, and the sensor's force and
//! torque (object on knife, sensor frame, N and N·m, with its noise); then
//! the knife's total work, when the first section fractured, and how many
//! sections fractured and were re-chosen as the knife slid. The cut
//! stops with the crack front 25 mm below the top.
//!
//! ```sh
//! cargo run --release --example 02_plant_open_loop
//! ```

use nalgebra::Vector3;
use shearcut_plant::{Plant, PlantSettings, PlantSpec, PlantStep};
use shearcut_sim::arm::{ArmLimits, KnifeCommand};
use shearcut_sim::{Knife, KnifePreset, MaterialPreset, ObjectShape, SectionSettings};

/// Slice-push ratio of the prescribed motion, ξ = v_t / v_n.
const XI: f64 = 0.5;
/// Knife speed along its velocity, m/s.
const SPEED: f64 = 0.02;
/// Servo period, s (a 1 kHz arm).
const DT: f64 = 1e-3;
/// Ticks over which the speed ramps up from rest.
const RAMP_TICKS: u32 = 50;
/// Target depth of the crack front below the potato's top, m.
const DEPTH: f64 = 0.025;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    print(&cut()?);
    Ok(())
}

/// Prints the cut's samples and its totals.
fn print(cut: &Cut) {
    println!("half potato 90 x 60 x 35 mm, chef's knife, xi = {XI}, {SPEED} m/s");
    println!(
        " t (s)  travel (mm)  crack (mm)  contact (mm)     Fx      Fy      Fz (N)     Tx      Ty      Tz (N m)"
    );
    for m in cut.samples.iter() {
        let w = m.reading.wrench;
        println!(
            "{:6.3} {:11.2} {:11.2} {:13.1} {:7.2} {:7.2} {:7.2} {:10.3} {:7.3} {:7.3}",
            m.reading.time,
            (cut.start_height - m.reading.position.y) * 1e3,
            m.truth.crack_depth * 1e3,
            m.truth.contact_length * 1e3,
            w[0],
            w[1],
            w[2],
            w[3],
            w[4],
            w[5]
        );
    }
    println!(
        "work {:.4} J; first fracture at {:.3} s; {} sections fractured, {} re-chosen through the crack front",
        cut.last.truth.work,
        cut.first_fracture.unwrap_or(f64::NAN),
        cut.last.truth.fractured_sections,
        cut.rechoices
    );
}

/// What the example's cut produced.
struct Cut {
    /// The measurement every 100 ms and the last one.
    samples: Vec<PlantStep>,
    /// The last measurement.
    last: PlantStep,
    /// Time of the first tick with a fractured section, s.
    first_fracture: Option<f64>,
    /// Height of the knife frame's origin at the start, m.
    start_height: f64,
    /// Sections re-chosen through the crack front during the cut.
    rechoices: usize,
}

/// Cuts the half potato at `XI` until the crack front is `DEPTH` below its top.
fn cut() -> Result<Cut, Box<dyn std::error::Error>> {
    let material = MaterialPreset::PotatoWhole.material();
    let knife = Knife::new(&KnifePreset::Chef.settings())?;
    let potato = ObjectShape::HalfPotato {
        length: 0.09,
        width: 0.06,
        height: 0.035,
    }
    .mesh()?;
    // Direction of motion in the knife plane (z along the edge, y up):
    // down, and towards the tip by ξ per unit depth.
    let direction = Plant::direction_at(XI);
    let mut plant = Plant::new(
        PlantSpec {
            material: &material,
            knife: &knife,
            object: &potato,
            z0: 0.02,
            direction,
            settings: &PlantSettings::default(),
            section: &SectionSettings::default(),
            arm_limits: &ArmLimits::default(),
        },
        0,
    )?;
    let start_height = plant.position().y;
    let mut samples = Vec::new();
    let mut first_fracture = None;
    let mut tick = 0u32;
    loop {
        tick += 1;
        let speed = SPEED * (f64::from(tick) / f64::from(RAMP_TICKS)).min(1.0);
        let command = KnifeCommand {
            velocity: Vector3::new(0.0, direction.y, direction.x) * speed,
        };
        let m = plant.step(&command, DT)?;
        if first_fracture.is_none() && m.truth.fractured_sections > 0 {
            first_fracture = Some(m.reading.time);
        }
        let done = m.truth.crack_depth >= DEPTH || tick >= 10_000;
        if tick.is_multiple_of(100) || done {
            samples.push(m);
        }
        if done {
            return Ok(Cut {
                samples,
                last: m,
                first_fracture,
                start_height,
                rechoices: plant.rechoices(),
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The example reaches its depth within the arm's limits, fractures on
    /// the way, and the knife did positive work; its report prints.
    #[test]
    fn the_example_cuts_to_depth() {
        let cut = cut().unwrap();
        print(&cut);
        assert!(cut.last.truth.crack_depth >= DEPTH, "{:?}", cut.last);
        assert_eq!(
            cut.last.reading.status,
            shearcut_sim::arm::ArmStatus::Moving,
            "the ramp keeps the arm's limits"
        );
        assert!(cut.first_fracture.is_some() && cut.last.truth.work > 0.0);
    }
}
