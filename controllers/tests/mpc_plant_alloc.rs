//! The MPC with the shipped potato-cuboid surrogate and the online
//! estimator on (off in `shearcut run`'s default), cutting the full plant
//! (8 segments, 8 mm) past the first fracture, every plan solved, with a counting global allocator (its own test binary):
//! `Mpc::tick` allocates nothing, on planning ticks too: the solves run on
//! the planner thread (where clarabel 0.11.1's timers allocate one block
//! per solve), and the observers, the estimator's rows, the requests and
//! the shaping allocate nothing. Only the controller's thread counts: the
//! planner's and the plant's section builders' threads are not tracked,
//! nor is the plant's step.

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use nalgebra::Vector2;
use shearcut_controllers::controller::{Controller, CutTask, MotionLimits};
use shearcut_controllers::mpc::{DepthProfile, Mpc, MpcSettings, SurrogateModel};
use shearcut_controllers::observer::EdgeOutline;
use shearcut_plant::{Plant, PlantSettings, PlantSpec};
use shearcut_sim::arm::ArmLimits;
use shearcut_sim::section::SectionSettings;
use shearcut_sim::surrogate::Surrogate;
use shearcut_sim::{Cuboid, Knife, KnifePreset, MaterialPreset, ObjectShape};

#[path = "support/counting_allocator.rs"]
mod counting_allocator;

use counting_allocator::{ALLOCATIONS, Counting, TRACK};

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn mpc_ticks_on_the_plant_allocate_only_inside_clarabel() {
    let material = MaterialPreset::PotatoCuboid.material();
    let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
    let mesh = ObjectShape::Cuboid(Cuboid {
        width: 0.03,
        height: 0.025,
        length: 0.03,
    })
    .mesh()
    .unwrap();
    let arm = ArmLimits::default();
    let task = CutTask {
        target_depth: 0.008,
        outline: Arc::new(EdgeOutline::of_object(knife.edge(), &mesh).unwrap()),
        overtravel: 0.0,
        period: 1e-3,
        blade_budget: 0.006,
        limits: MotionLimits::within_arm(0.05, 0.1, arm.acceleration, arm.jerk, 0.9),
    };
    let surrogate = Surrogate::from_path(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../config/surrogates/potato-cuboid-straight.toml"),
    )
    .unwrap();
    let profile = DepthProfile::for_surrogate(
        &mesh,
        &surrogate,
        &SectionSettings::default(),
        PlantSettings::default().rim_fraction,
        task.target_depth,
    )
    .unwrap();
    let settings = MpcSettings {
        estimate: true,
        ..MpcSettings::default()
    };
    let xi = task.blade_budget / task.target_depth;
    let mut mpc = Mpc::new(
        &task,
        &settings,
        SurrogateModel::new(surrogate),
        profile,
        xi,
    )
    .unwrap();
    let alpha = f64::atan(xi);
    let mut plant = Plant::new(
        PlantSpec {
            material: &material,
            knife: &knife,
            object: &mesh,
            z0: 0.02,
            direction: Vector2::new(alpha.sin(), -alpha.cos()),
            settings: &PlantSettings {
                segments: 8,
                reach: task.blade_budget,
                ..PlantSettings::default()
            },
            section: &SectionSettings::default(),
            arm_limits: &arm,
        },
        0,
    )
    .unwrap();
    let mut m = plant.step(&Default::default(), task.period).unwrap();
    // The first plan sets up clarabel's timer maps.
    let command = mpc.tick(&m.reading);
    m = plant.step(&command, task.period).unwrap();
    let solves_before = mpc.stats().solves;
    let (mut plans, mut in_plans, mut between, mut fractured_plans) = (0u64, 0, 0, 0);
    for _ in 0..20_000 {
        ALLOCATIONS.store(0, Ordering::SeqCst);
        TRACK.with(|t| t.set(true));
        let command = mpc.tick(&m.reading);
        TRACK.with(|t| t.set(false));
        let n = ALLOCATIONS.load(Ordering::SeqCst);
        if mpc.replanned() {
            plans += 1;
            in_plans += n;
            if m.truth.fractured_sections > 0 {
                fractured_plans += 1;
            }
        } else {
            between += n;
        }
        m = plant.step(&command, task.period).unwrap();
        if m.truth.crack_depth >= task.target_depth {
            break;
        }
    }
    let solves = mpc.stats().solves - solves_before;
    eprintln!(
        "{plans} plans ({fractured_plans} after the first fracture), {solves} solves: {in_plans} allocations in plans, {between} between; {:?}",
        mpc.stats()
    );
    assert!(
        m.truth.crack_depth >= task.target_depth,
        "{} m",
        m.truth.crack_depth
    );
    assert!(
        fractured_plans >= 10,
        "{fractured_plans} plans after the fracture"
    );
    assert_eq!(mpc.stats().fallbacks, 0);
    // The tick allocates nothing, planning ticks included: the solves (and
    // clarabel's one allocation per solve) run on the planner thread.
    assert_eq!(between, 0);
    assert_eq!(in_plans, 0, "{solves} solves off the tick");
}
