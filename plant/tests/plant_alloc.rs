//! `Plant::step` allocates nothing after construction on the caller's
//! thread (the workspace's counting allocator, per thread): a straight
//! edge pressing a cuboid (no re-choice), and a chef's knife slicing a half
//! potato, whose sections are re-chosen and rebuilt, under either
//! successor policy (the successors are built on the plant's worker thread,
//! whose allocations are not the tick's), and a plant cloned mid-cut.

use nalgebra::{Vector2, Vector3};
use shearcut_plant::{ArmLimits, KnifeCommand, Plant, PlantSettings, PlantSpec, SuccessorPolicy};
use shearcut_sim::{Knife, KnifePreset, MaterialPreset};

#[path = "../../controllers/tests/support/counting_allocator.rs"]
mod counting_allocator;
#[path = "support/cutting_rig.rs"]
mod cutting_rig;

use counting_allocator::{Counting, thread_allocations};
use cutting_rig::{LOOSE, coarse_section, cuboid, half_potato};

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn plant_step_allocates_nothing() {
    let material = MaterialPreset::PotatoCuboid.material();
    let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
    let object = cuboid(0.03, 0.02, 0.03);
    let section = coarse_section();
    let limits = ArmLimits {
        jerk: 1e15,
        acceleration: 1e9,
        ..ArmLimits::default()
    };
    let settings = PlantSettings {
        segments: 4,
        ..PlantSettings::default()
    };
    let mut plant = Plant::new(
        PlantSpec {
            material: &material,
            knife: &knife,
            object: &object,
            z0: 0.02,
            direction: Vector2::new(0.0, -1.0),
            settings: &settings,
            section: &section,
            arm_limits: &limits,
        },
        1,
    )
    .unwrap();
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, -0.00625, 0.0),
    };
    // Through contact, first fracture and steady cutting.
    let before = thread_allocations();
    let mut fractured = 0;
    for _ in 0..1500 {
        fractured = plant.step(&cmd, 1e-3).unwrap().truth.fractured_sections;
    }
    let after = thread_allocations();
    assert!(fractured > 0, "the run reached cutting");
    assert_eq!(after - before, 0, "Plant::step allocated");
    assert_eq!(
        plant.rechoices(),
        0,
        "a pressing straight edge re-chooses nothing"
    );
}

#[test]
fn plant_step_allocates_nothing_through_rechoices_and_rebuilds() {
    for policy in [SuccessorPolicy::Wait, SuccessorPolicy::KeepCurrent] {
        for threads in [1, 2] {
            slice_allocates_nothing(policy, threads);
        }
    }
}

/// The half potato sliced for 1500 ticks under `policy`, its sections
/// advanced on `threads` threads: the sections are rebuilt and no tick
/// allocates on the stepping thread (a helper's are its own).
fn slice_allocates_nothing(policy: SuccessorPolicy, threads: usize) {
    let mut plant = half_potato_under_the_chef(threads);
    plant.set_successor_policy(policy);
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, -0.00625, -0.003125),
    };
    let before = thread_allocations();
    for k in 0..1500 {
        plant.step(&cmd, 1e-3).unwrap();
        if policy == SuccessorPolicy::KeepCurrent && k % 10 == 0 {
            // Leave the workers a core now and then, as a realtime loop's
            // wait for its period does, or the other tests' threads may
            // keep every successor deferred.
            std::thread::sleep(std::time::Duration::from_millis(2));
        }
    }
    let after = thread_allocations();
    assert!(
        plant.rebuilds() > 0,
        "{policy:?}, {threads} threads: the run rebuilt sections"
    );
    assert_eq!(
        after - before,
        0,
        "{policy:?}, {threads} threads: Plant::step allocated"
    );
}

/// A clone of a plant mid-cut steps without allocating, as the plant it
/// was cloned from does.
#[test]
fn a_cloned_plant_steps_without_allocating() {
    let mut plant = half_potato_under_the_chef(1);
    // Pressing first: few sections cut, so the per-tick lists are short
    // when the plant is cloned.
    let press = KnifeCommand {
        velocity: Vector3::new(0.0, -0.00625, 0.0),
    };
    for _ in 0..200 {
        plant.step(&press, 1e-3).unwrap();
    }
    let mut clone = plant.clone();
    let slice = KnifeCommand {
        velocity: Vector3::new(0.0, -0.00625, -0.003125),
    };
    let before = thread_allocations();
    for _ in 0..1300 {
        clone.step(&slice, 1e-3).unwrap();
    }
    let after = thread_allocations();
    assert!(clone.rebuilds() > 0, "the clone rebuilt sections");
    assert_eq!(after - before, 0, "the clone's Plant::step allocated");
}

/// The half potato under the chef's knife, 4 segments, the sections
/// advanced on `threads` threads, planned to slice down and towards the
/// heel.
fn half_potato_under_the_chef(threads: usize) -> Plant {
    let settings = PlantSettings {
        segments: 4,
        stepping_threads: threads,
        ..PlantSettings::default()
    };
    Plant::new(
        PlantSpec {
            material: &MaterialPreset::PotatoWhole.material(),
            knife: &Knife::new(&KnifePreset::Chef.settings()).unwrap(),
            object: &half_potato(),
            z0: 0.05,
            direction: Vector2::new(-0.5, -1.0),
            settings: &settings,
            section: &coarse_section(),
            arm_limits: &LOOSE,
        },
        7,
    )
    .unwrap()
}
