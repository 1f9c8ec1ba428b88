//! The MPC in closed loop with a synthetic arm: it reaches the target depth
//! within the arm's limits and the blade budget, heads for the model's
//! optimum when the blade is plentiful, and spends a short blade where more
//! edge is in contact.

mod synthetic_arm;

use shearcut_controllers::controller::{Controller, CutPhase};
use shearcut_controllers::mpc::{DepthProfile, Mpc, MpcSettings};
use shearcut_sim::plant::PlantStatus;
use synthetic_arm::{QuadraticModel, SyntheticArm, task};

fn run(mpc: &mut Mpc<QuadraticModel>, ticks: usize) -> (SyntheticArm, Vec<(f64, f64)>) {
    let mut arm = SyntheticArm::new(0.0);
    let mut m = arm.measure(PlantStatus::Moving);
    let mut trace = Vec::new();
    for _ in 0..ticks {
        let c = mpc.tick(&m);
        m = arm.step(&c);
        trace.push((m.crack_depth, mpc.telemetry().slice_push_ratio));
        if mpc.telemetry().phase == CutPhase::Done {
            break;
        }
    }
    (arm, trace)
}

#[test]
fn with_blade_to_spare_the_mpc_slices_at_the_model_optimum() {
    let profile = DepthProfile::uniform(0.03, 0.03, 0.015).unwrap();
    let settings = MpcSettings::default();
    let mut mpc = Mpc::new(&task(0.02, 1.0), &settings, QuadraticModel, profile, 0.5).unwrap();
    let (arm, trace) = run(&mut mpc, 20_000);
    assert_eq!(arm.refused, 0);
    assert_eq!(mpc.telemetry().phase, CutPhase::Done);
    assert_eq!(mpc.stats().fallbacks, 0, "{:?}", mpc.stats());
    // w'(ξ) = 0 at ξ = 4/3; the smoothness and time weights are tiny.
    let (_, xi_mid) = trace[trace.len() / 2];
    assert!((xi_mid - 4.0 / 3.0).abs() < 0.02, "ξ = {xi_mid}");
}

#[test]
fn a_short_blade_is_respected_and_spent_where_the_contact_is_long() {
    // Contact grows from 10 mm at the top to 50 mm at 20 mm depth (a
    // widening object); 8 mm of blade for 20 mm of depth.
    let profile = DepthProfile::new(vec![0.0, 0.02], vec![0.01, 0.05], 0.03, 0.015).unwrap();
    let budget = 0.008;
    let mut mpc = Mpc::new(
        &task(0.02, budget),
        &MpcSettings::default(),
        QuadraticModel,
        profile,
        0.4,
    )
    .unwrap();
    let (arm, trace) = run(&mut mpc, 20_000);
    assert_eq!(arm.refused, 0);
    assert_eq!(mpc.telemetry().phase, CutPhase::Done);
    assert!(arm.position.z <= budget, "travel {}", arm.position.z);
    let xi_at = |depth: f64| {
        trace
            .iter()
            .find(|(d, _)| *d >= depth)
            .map(|(_, xi)| *xi)
            .unwrap()
    };
    // L·w'(ξ) is equalised along the cut: ξ rises with the contact length.
    assert!(
        xi_at(0.015) > xi_at(0.005) + 0.1,
        "{} {}",
        xi_at(0.005),
        xi_at(0.015)
    );
}
