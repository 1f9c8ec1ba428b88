//! Controllers see only what an arm measures: the plant's ground truth
//! cannot reach them.
//!
//! Where it is enforced: `shearcut-controllers` does not depend on
//! `shearcut-plant`, the only crate that defines [`PlantTruth`] (a
//! dev-dependency, for its tests, is not visible to its library), and
//! `Controller::tick` takes a `shearcut_sim::arm::ArmReading`. The first
//! test reads the manifest so that adding the dependency fails CI; the
//! second drives every controller through a plant link whose truth is
//! scrambled and checks the commands are the same, bit for bit.

use shearcut::closed_loop::LoopSetup;
use shearcut::closed_loop::{InProcessPlant, LinkAnswer, LinkError, PlantLink};
use shearcut::controller_choice::ControllerChoice;
use shearcut::scenario::Scenario;
use shearcut_plant::PlantTruth;
use shearcut_sim::arm::KnifeCommand;

#[test]
fn the_controllers_crate_cannot_name_the_plant_truth() {
    let manifest: toml::Table = include_str!("../controllers/Cargo.toml").parse().unwrap();
    let deps = manifest["dependencies"].as_table().unwrap();
    assert!(
        !deps.contains_key("shearcut-plant"),
        "shearcut-controllers must not depend on shearcut-plant (the plant's truth)"
    );
    let dev = manifest["dev-dependencies"].as_table().unwrap();
    assert!(
        dev.contains_key("shearcut-plant"),
        "its tests drive the plant"
    );
}

/// The in-process plant with its truth replaced by nonsense that changes
/// every tick.
struct Scrambled {
    plant: InProcessPlant,
    tick: u32,
}

impl PlantLink for Scrambled {
    fn period(&self) -> f64 {
        self.plant.period()
    }

    fn exchange(&mut self, command: &KnifeCommand) -> Result<LinkAnswer, LinkError> {
        let mut answer = self.plant.exchange(command)?;
        self.tick += 1;
        let x = f64::from(self.tick);
        answer.truth = Some(PlantTruth {
            crack_depth: -x,
            contact_length: 1e3 * x,
            fractured_sections: self.tick as usize % 3,
            work: x.sin(),
            deformation: x.cos(),
            ..PlantTruth::default()
        });
        Ok(answer)
    }
}

/// The commands of `ticks` servo ticks of `choice` on `s`, with the plant's
/// truth as it is or scrambled.
fn commands(s: &Scenario, choice: ControllerChoice, ticks: usize, scramble: bool) -> Vec<u64> {
    let setup = LoopSetup::new(s, choice).unwrap();
    let mut controller = setup.controller(s, choice).unwrap();
    let plant = InProcessPlant::new(setup.plant(s).unwrap(), setup.task.period);
    let mut link: Box<dyn PlantLink> = if scramble {
        Box::new(Scrambled { plant, tick: 0 })
    } else {
        Box::new(plant)
    };
    let mut answer = link.exchange(&KnifeCommand::default()).unwrap();
    let mut bits = Vec::with_capacity(3 * ticks);
    for _ in 0..ticks {
        let command = controller.tick(&answer.reading);
        bits.extend(command.velocity.iter().map(|v| v.to_bits()));
        answer = link.exchange(&command).unwrap();
    }
    bits
}

#[test]
fn every_controller_commands_the_same_whatever_the_truth() {
    // The cuboid's loop scenario on a coarse plant, through the touch and
    // the first fracture (about 300 ticks at the MPC's speeds).
    let text = include_str!("../config/scenarios/loop-potato-cuboid.toml")
        .replace("segments = 20", "segments = 2")
        + "\n[section]\nrow_spacing = 0.0005\n";
    let s = Scenario::parse(&text, "cuboid", "cuboid").unwrap();
    for choice in [
        ControllerChoice::Press,
        ControllerChoice::Slice(0.75),
        ControllerChoice::Force(5.0),
        ControllerChoice::Mpc,
    ] {
        let honest = commands(&s, choice, 400, false);
        let scrambled = commands(&s, choice, 400, true);
        assert_eq!(honest, scrambled, "{choice:?}");
        assert!(
            honest.iter().any(|b| f64::from_bits(*b) != 0.0),
            "{choice:?} moved"
        );
    }
}
