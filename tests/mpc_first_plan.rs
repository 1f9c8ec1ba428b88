//! What the MPC plans from the intact object, before any plant is built:
//! the catch-up after the first fracture priced into the onset's cost, the
//! direction the plant's first sections are built for, and the contact it
//! reads under the knife's edge.

use shearcut::closed_loop::{LoopSetup, mpc_cutting_ratio, mpc_start};
use shearcut::controller_choice::ControllerChoice;
use shearcut::scenario::Scenario;
use shearcut::surrogates::surrogate_for;
use shearcut_controllers::mpc::{SliceModel, StageState, SurrogateModel};

fn model_and_profile(name: &str) -> (SurrogateModel, StageState) {
    let s = Scenario::load(name).expect("a built-in scenario");
    let setup = LoopSetup::new(&s, ControllerChoice::Mpc).expect("a valid scenario");
    // The object as the MPC sees it (its section the equivalent rectangle).
    let profile = setup.profile.expect("the MPC's profile");
    let model = SurrogateModel::new(surrogate_for(&s).expect("a shipped surrogate"));
    let intact = StageState {
        depth: 2e-3,
        height: profile.height(),
        half_width: profile.half_width(),
        fractured: false,
        travel_since_fracture: 0.0,
    };
    (model, intact)
}

/// The eggplant's skin (R'_c = 2.5 R_c) stores the strain energy that runs
/// the first crack ahead of the edge (seed 000 eq. 1): the onset's net
/// cost is below the work of indenting to it, ½·w(d*)·d*, by what the
/// catch-up saves. Slicing fractures sooner but saves less and builds up
/// drag, so the net cost does not fall with ξ the way the indentation
/// work does.
#[test]
fn the_eggplant_onset_cost_nets_out_the_catch_up() {
    let (model, intact) = model_and_profile("loop-eggplant-whole");
    let span = model.catch_up_span(0.0, &intact);
    assert!(span > 0.02, "span {span} m: four onset depths of ~9 mm");
    let state = StageState {
        travel_since_fracture: span,
        ..intact
    };
    let pressing = model.stage(0.0, &state);
    let no_span = model.stage(
        0.0,
        &StageState {
            travel_since_fracture: 0.0,
            ..intact
        },
    );
    // Without a span the cost is the indentation work alone.
    assert!(
        pressing.onset_work < 0.9 * no_span.onset_work,
        "net {} J/m against indentation {} J/m",
        pressing.onset_work,
        no_span.onset_work
    );
    // The indentation work falls steeply with ξ; the net cost does not.
    let slicing = model.stage(1.0, &state);
    let slicing_no_span = model.stage(
        1.0,
        &StageState {
            travel_since_fracture: 0.0,
            ..intact
        },
    );
    assert!(slicing_no_span.onset_work < 0.5 * no_span.onset_work);
    assert!(
        slicing.onset_work > pressing.onset_work,
        "net onset cost at ξ = 1: {} J/m, pressing: {} J/m",
        slicing.onset_work,
        pressing.onset_work
    );
}

/// The onset's cost for the whole edge weighs each depth by the edge in
/// contact there. On a constant contact that is the per-length cost times
/// the contact (the indentation's force is linear in depth, which the
/// trapezoidal rule integrates exactly). On the eggplant's dome the
/// contact widens over the catch-up span, where the crack's run ahead of
/// the edge saves work: the whole edge's saving from pressing is larger
/// than the first stage's contact would make it, and slicing's (a shallow
/// onset, a short jump) gains less from the widening.
#[test]
fn the_onset_cost_weighs_each_depth_by_the_edge_in_contact() {
    let (model, intact) = model_and_profile("loop-eggplant-whole");
    let span = model.catch_up_span(0.0, &intact);
    let state = StageState {
        travel_since_fracture: span,
        ..intact
    };
    let l = 0.04;
    for xi in [0.0, 0.5, 1.0] {
        let per_length = model.stage(xi, &state).onset_work;
        let [whole, _, _] = model.onset_cost(xi, &state, |_| l);
        assert!(
            (whole - l * per_length).abs() <= 1e-9 * (l * per_length).abs(),
            "ξ = {xi}: {whole} J against {} J",
            l * per_length
        );
    }
    // A chord of the 70 mm round, 2√(d(D − d)), at the sections' depth.
    let chord = |d: f64| 2.0 * (d.max(0.0) * (0.07 - d.max(0.0)).max(0.0)).sqrt();
    let first = chord(intact.depth);
    let pressing = model.onset_cost(0.0, &state, chord)[0];
    let slicing = model.onset_cost(1.0, &state, chord)[0];
    let per_length = |xi| first * model.stage(xi, &state).onset_work;
    assert!(
        pressing < per_length(0.0),
        "pressing: {pressing} J on the widening contact, {} J at the first stage's",
        per_length(0.0)
    );
    assert!(
        slicing - pressing > per_length(1.0) - per_length(0.0),
        "slicing's premium {} J on the widening contact, {} J at the first stage's",
        slicing - pressing,
        per_length(1.0) - per_length(0.0)
    );
}

/// On the whole eggplant the plan from rest presses (the skin's onset is
/// not cheaper sliced, and the flesh's work rises with ξ); on the potatoes
/// it slices. The plant builds its first sections for that ratio.
#[test]
fn the_first_plan_sets_the_direction_the_plant_is_planned_for() {
    for (name, low, high) in [
        ("loop-eggplant-whole", 0.0, 0.15),
        ("loop-potato-whole", 0.4, 1.2),
        ("loop-potato-cuboid", 0.4, 1.2),
        ("eggplant-small", 0.0, 0.15),
    ] {
        let s = if name == "eggplant-small" {
            small_eggplant()
        } else {
            Scenario::load(name).expect("a built-in scenario")
        };
        let setup = LoopSetup::new(&s, ControllerChoice::Mpc).expect("a valid scenario");
        let profile = setup.profile.as_ref().expect("the MPC's profile");
        let start_z = setup.cut(&s).start.z;
        let ratio = mpc_cutting_ratio(&s, &setup.task, profile, start_z).expect("a plan");
        assert!(
            (low..=high).contains(&ratio),
            "{name}: planned ratio {ratio}, expected in [{low}, {high}] (start {})",
            mpc_start(&setup.task)
        );
        assert_eq!(
            setup.xi, ratio,
            "{name}: the plant's direction is the plan's"
        );
    }
}

/// The coarse whole eggplant at ×0.75 (the held-out variant): 20 mm of
/// blade over 30 mm of depth lets the plan start at ratios up to 0.67; the
/// plan prices pressing's deep onset, whose crack runs ahead of the edge
/// where the contact has widened, below slicing's shallow one, and
/// presses.
fn small_eggplant() -> Scenario {
    let base = include_str!("../config/scenarios/loop-eggplant-whole-coarse.toml");
    let text = base
        .replace("length = 0.2", "length = 0.15")
        .replace("diameter = 0.07", "diameter = 0.0525")
        .replace("flat = 0.004", "flat = 0.003")
        .replace("depth = 0.04", "depth = 0.03");
    assert_eq!(text.matches("0.0525").count(), 1, "the object was scaled");
    Scenario::parse(&text, "eggplant-small", "eggplant-small").expect("a valid scenario")
}

/// `[plant] reach` widens the plant's segmented edge beyond the blade
/// budget; a negative one is refused with the key, the value and what is
/// allowed.
#[test]
fn a_plant_reach_setting_is_validated_on_load() {
    let base = include_str!("../config/scenarios/loop-potato-whole.toml");
    let text = base.replace("[plant]", "[plant]\nreach = 0.03");
    assert_ne!(text, base, "the scenario has a [plant] table");
    let s = Scenario::parse(&text, "reach", "reach").expect("a valid scenario");
    assert_eq!(s.plant.reach, 0.03);
    let bad = base.replace("[plant]", "[plant]\nreach = -0.5");
    let message = Scenario::parse(&bad, "bad", "bad")
        .expect_err("a negative reach is refused")
        .to_string();
    assert!(
        message.contains("reach") && message.contains("-0.5") && message.contains(">= 0"),
        "{message}"
    );
}

/// `[controller.mpc] edge_contact` reads the contact under the chef's own
/// edge. The half potato (90 mm along the edge) at z0 = 0 lies on the flat
/// heel but for its last 30 mm (slopes up to 0.11): its contact is the
/// outline's chord within 2 %. (The profile does not depend on the blade
/// budget; none is given, so that z0 = 0 lies on the usable edge.) At z0 95 mm it lies wholly on the rise
/// (slopes 0.13 to 0.45): the edge meets it off its top and takes in at
/// least 5 % less of it at every depth.
#[test]
fn edge_contact_reads_the_contact_under_the_knife_edge() {
    let profile = |z0: f64, edge_contact: bool| {
        let mut s = Scenario::load("loop-potato-whole-realtime").expect("a built-in scenario");
        s.motion.z0 = vec![z0];
        s.controller.blade_budget = Some(0.0);
        s.controller.mpc.edge_contact = edge_contact;
        LoopSetup::new(&s, ControllerChoice::Mpc)
            .expect("a valid scenario")
            .profile
            .expect("the MPC's profile")
    };
    let chord = profile(0.095, false);
    let (heel, rise) = (profile(0.0, true), profile(0.095, true));
    for d in [1e-3, 5e-3, 10e-3, 20e-3] {
        let l = chord.contact_length(d);
        let (h, r) = (heel.contact_length(d), rise.contact_length(d));
        assert!((h / l - 1.0).abs() < 0.02, "{d}: heel {h} vs chord {l}");
        assert!(r < 0.95 * l, "{d}: rise {r} vs chord {l}");
    }
    assert_eq!(
        chord,
        profile(0.0, false),
        "the chord does not depend on z0"
    );
}
