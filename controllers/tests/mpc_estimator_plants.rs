//! The MPC with online estimation in closed loop with the full plant
//! (fracture-mechanics cross sections) whose material differs from the
//! controller's preset by ±30 %: the end-of-cut scale factors against the
//! truth, on the potato cuboid (straight edge) and the half potato (chef's
//! knife), built as `shearcut run` builds `loop-potato-cuboid` and
//! `loop-potato-whole` (seed 0, 1 kHz, default arm and sections).
//!
//! The full plant is far too slow for CI in a debug build (minutes per
//! cut), so the test is ignored; run it in release:
//!
//! ```text
//! cargo test --release -p shearcut-controllers --test mpc_estimator_plants -- --ignored --nocapture
//! ```

use std::path::Path;
use std::sync::Arc;

use shearcut_controllers::controller::{Controller, CutTask, MotionLimits};
use shearcut_controllers::mpc::{
    DepthProfile, Mpc, MpcSettings, SliceModel, StageState, SurrogateModel,
};
use shearcut_controllers::observer::{
    CutObserver, CutObserverSettings, CutTarget, EdgeOutline, FractureDetector, FractureSettings,
    WrenchTare, WrenchTareSettings,
};
use shearcut_plant::{Plant, PlantSettings, PlantSpec, PlantStep};
use shearcut_sim::arm::ArmLimits;
use shearcut_sim::geometry::TriangleMesh;
use shearcut_sim::knife_plane::knife_plane_silhouette;
use shearcut_sim::section::SectionSettings;
use shearcut_sim::surrogate::Surrogate;
use shearcut_sim::{Cuboid, Knife, KnifePreset, MaterialPreset, ObjectShape};

/// Safety margin on the arm's acceleration and jerk (as `shearcut run`).
const ARM_MARGIN: f64 = 0.9;

/// One of the shipped closed-loop objects.
#[derive(Debug, Clone, Copy)]
struct Setup {
    name: &'static str,
    material: MaterialPreset,
    knife: KnifePreset,
    surrogate: &'static str,
    object: fn() -> ObjectShape,
    segments: usize,
    z0: f64,
    depth: f64,
    blade_budget: f64,
}

const CUBOID: Setup = Setup {
    name: "potato cuboid",
    material: MaterialPreset::PotatoCuboid,
    knife: KnifePreset::Straight,
    surrogate: "potato-cuboid-straight",
    object: || {
        ObjectShape::Cuboid(Cuboid {
            width: 0.03,
            height: 0.025,
            length: 0.03,
        })
    },
    segments: 20,
    z0: 0.02,
    depth: 0.02,
    blade_budget: 0.012,
};

const WHOLE: Setup = Setup {
    name: "half potato",
    material: MaterialPreset::PotatoWhole,
    knife: KnifePreset::Chef,
    surrogate: "potato-whole-chef",
    object: || ObjectShape::HalfPotato {
        length: 0.09,
        width: 0.06,
        height: 0.035,
    },
    segments: 20,
    z0: 0.02,
    depth: 0.025,
    blade_budget: 0.015,
};

/// Factors (toughness on R_c and R'_c, stiffness on E, friction on μ) of
/// the plant's material against the preset.
const PLANTS: [(&str, [f64; 3]); 5] = [
    ("nominal", [1.0, 1.0, 1.0]),
    ("R_c x1.3, E x0.7", [1.3, 0.7, 1.0]),
    ("R_c x0.7, E x1.3", [0.7, 1.3, 1.0]),
    ("mu x1.3", [1.0, 1.0, 1.3]),
    ("mu x0.7", [1.0, 1.0, 0.7]),
];

/// The object's profile as `shearcut run` gives it to the MPC (the crest
/// section's equivalent rectangle, at the default section settings and
/// rim clipping these scenarios use).
fn profile(mesh: &TriangleMesh, surrogate: &Surrogate, depth: f64) -> DepthProfile {
    DepthProfile::for_surrogate(
        mesh,
        surrogate,
        &SectionSettings::default(),
        PlantSettings::default().rim_fraction,
        depth,
    )
    .unwrap()
}

/// The edge's travel past the first fracture before the rows count (the
/// controller's settling depth), m.
const SETTLE: f64 = 2e-3;

/// How well the model at the true factors predicts the plant where the
/// estimator uses it: the normal and tangential work done after the first
/// fracture (past [`SETTLE`]), measured over modelled. A factor can only be
/// as close to the truth as these are to 1.
#[derive(Debug)]
struct ModelCheck {
    /// The cut's task: the depth the model is evaluated at is the edge's
    /// ([`CutTask::edge_depth`]), as the controller takes it.
    task: CutTask,
    fracture: Option<f64>,
    measured: [f64; 2],
    modelled: [f64; 2],
}

impl ModelCheck {
    fn add(
        &mut self,
        model: &SurrogateModel,
        profile: &DepthProfile,
        step: &PlantStep,
        truth: [f64; 3],
    ) {
        let m = &step.reading;
        let depth = profile.section_depth(self.task.edge_depth(&m.position));
        let v_n = -m.velocity.y;
        let l = step.truth.contact_length;
        if !(v_n > 0.0 && l > 0.0) {
            return;
        }
        if step.truth.fractured_sections == 0 {
            return;
        }
        let since = depth - *self.fracture.get_or_insert(depth);
        if since < SETTLE {
            return;
        }
        let xi = m.velocity.z.abs() / v_n;
        let state = StageState {
            depth,
            height: profile.height(),
            half_width: profile.half_width(),
            fractured: true,
            travel_since_fracture: since,
        };
        let [n, t] = model.force_model(xi, &state, truth).unwrap();
        let v_t = m.velocity.z.abs();
        self.measured[0] += m.wrench[1] * v_n;
        self.modelled[0] += l * n.value * v_n;
        self.measured[1] += -m.wrench[2] * m.velocity.z.signum() * v_t;
        self.modelled[1] += l * t.value * v_t;
    }

    fn ratios(&self) -> [f64; 2] {
        [0, 1].map(|k| self.measured[k] / self.modelled[k])
    }
}

/// The end-of-cut factors (toughness, stiffness, friction) the MPC's
/// estimator believes after cutting `setup` made of its preset scaled by
/// `truth`, the model check, and whether the cut completed.
fn end_of_cut(
    setup: &Setup,
    truth: [f64; 3],
    settings: &MpcSettings,
    contact: Option<&DepthProfile>,
    on_tick: &mut dyn FnMut(&Trace<'_>),
) -> ([f64; 3], ModelCheck, bool) {
    let mut material = setup.material.material();
    material.fracture_toughness *= truth[0];
    material.initial_fracture_toughness *= truth[0];
    material.youngs_modulus *= truth[1];
    material.friction_coefficient *= truth[2];
    let knife = Knife::new(&setup.knife.settings()).unwrap();
    let mesh = (setup.object)().mesh().unwrap();
    let arm = ArmLimits::default();
    let task = CutTask {
        target_depth: setup.depth,
        outline: Arc::new(EdgeOutline::of_object(knife.edge(), &mesh).unwrap()),
        overtravel: 0.0,
        period: 1e-3,
        blade_budget: setup.blade_budget,
        limits: MotionLimits::within_arm(
            0.05f64.min(arm.velocity),
            0.1f64.min(arm.velocity),
            arm.acceleration,
            arm.jerk,
            ARM_MARGIN,
        ),
    };
    let xi = (task.blade_budget / task.target_depth).min(1.0);
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../config/surrogates")
        .join(format!("{}.toml", setup.surrogate));
    let surrogate = Surrogate::from_path(&path).unwrap();
    let profile = contact
        .cloned()
        .unwrap_or_else(|| profile(&mesh, &surrogate, setup.depth));
    let model = SurrogateModel::new(surrogate);
    let mut check = ModelCheck {
        task: task.clone(),
        fracture: None,
        measured: [0.0; 2],
        modelled: [0.0; 2],
    };
    let mut mpc = Mpc::new(&task, settings, model.clone(), profile.clone(), xi).unwrap();
    let plant_settings = PlantSettings {
        segments: setup.segments,
        reach: task.blade_budget,
        ..PlantSettings::default()
    };
    let mut plant = Plant::new(
        PlantSpec {
            material: &material,
            knife: &knife,
            object: &mesh,
            z0: setup.z0,
            direction: Plant::direction_at(xi),
            settings: &plant_settings,
            section: &SectionSettings::default(),
            arm_limits: &arm,
        },
        0,
    )
    .unwrap();
    let mut m = plant
        .step(&Default::default(), task.period)
        .expect("plant steps");
    // 30 s of simulated time at most, as `shearcut run`.
    for _ in 0..30_000 {
        let command = mpc.tick(&m.reading);
        on_tick(&Trace {
            task: &task,
            model: &model,
            profile: &profile,
            step: &m,
            scale: mpc.scale(),
        });
        m = plant.step(&command, task.period).expect("plant steps");
        check.add(&model, &profile, &m, truth);
        if m.truth.crack_depth >= task.target_depth {
            return (mpc.scale(), check, true);
        }
    }
    (mpc.scale(), check, false)
}

/// What one tick of [`end_of_cut`] shows a tracer: the reading the MPC
/// just took with the plant's truth beside it, and its factors after it.
struct Trace<'a> {
    task: &'a CutTask,
    model: &'a SurrogateModel,
    profile: &'a DepthProfile,
    step: &'a PlantStep,
    scale: [f64; 3],
}

/// Relative errors of the estimated factors.
fn errors(estimated: [f64; 3], truth: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| estimated[k] / truth[k] - 1.0)
}

#[test]
#[ignore = "the full plant takes minutes per cut in a debug build; from the arm's reading alone the half potato's factors miss their 5 % on the two plants off the preset's E/R_c (docs/controllers.md): run in release with --ignored"]
fn the_estimator_converges_on_plants_off_the_preset() {
    let settings = MpcSettings {
        estimate: true,
        ..MpcSettings::default()
    };
    let mut worst: f64 = 0.0;
    let mut failures = Vec::new();
    for setup in [CUBOID, WHOLE] {
        for (label, truth) in PLANTS {
            let (estimated, check, completed) =
                end_of_cut(&setup, truth, &settings, None, &mut |_| {});
            if !completed {
                failures.push(format!("{} {label}: the cut did not complete", setup.name));
            }
            let e = errors(estimated, truth);
            let r = check.ratios();
            println!(
                "{:14} {:18} T {:.3} ({:+5.1} %)  S {:.3} ({:+5.1} %)  F {:.3} ({:+5.1} %)  | plant/model at truth: normal {:.3}, tangential {:.3}",
                setup.name,
                label,
                estimated[0],
                100.0 * e[0],
                estimated[1],
                100.0 * e[1],
                estimated[2],
                100.0 * e[2],
                r[0],
                r[1],
            );
            worst = e.iter().fold(worst, |w, x| w.max(x.abs()));
            // The issue's 5 % on every plant. The closest are the half
            // potato's (4.3 %): little margin, and a change to its
            // equivalent rectangle (docs/controllers.md, "Which section")
            // moved one to 5.0 %. The cuboid stiffer and less tough than
            // the preset reached it with the potato-cuboid surrogates
            // refitted with the window weight (docs/surrogates.md); before,
            // its toughness ended −8.5 %.
            let bounds = [0.05; 3];
            for (k, factor) in ["toughness", "stiffness", "friction"].iter().enumerate() {
                // A NaN factor fails too.
                if e[k].is_nan() || e[k].abs() >= bounds[k] {
                    failures.push(format!(
                        "{} {label}: {factor} {:+.1} % (bound {} %)",
                        setup.name,
                        100.0 * e[k],
                        100.0 * bounds[k]
                    ));
                }
            }
        }
    }
    println!("worst factor error {:.1} %", 100.0 * worst);
    // The whole table first, then every plant off its bound.
    assert!(failures.is_empty(), "{}", failures.join("; "));
}

/// Prints, tick by tick, what the estimator is fed on one plant against
/// the plant's truth: `SHEARCUT_TRACE=whole:1` (object `cuboid` or `whole`,
/// plant index into [`PLANTS`]).
#[test]
#[ignore = "a diagnostic trace of one plant: run in release with --ignored --nocapture"]
fn trace_one_plant() {
    let which = std::env::var("SHEARCUT_TRACE").unwrap_or_else(|_| "whole:0".into());
    let (object, index) = which.split_once(':').expect("SHEARCUT_TRACE=object:index");
    let setup = if object == "cuboid" { CUBOID } else { WHOLE };
    let (label, truth) = PLANTS[index.parse::<usize>().expect("plant index")];
    let settings = MpcSettings {
        estimate: true,
        ..MpcSettings::default()
    };
    let mut tare = WrenchTare::new(WrenchTareSettings::default()).unwrap();
    let mut fracture = FractureDetector::new(FractureSettings::default()).unwrap();
    let knife = Knife::new(&setup.knife.settings()).unwrap();
    let mesh = (setup.object)().mesh().unwrap();
    let mut observer = CutObserver::new(
        &knife,
        &knife_plane_silhouette(&mesh).unwrap(),
        CutTarget::Depth(setup.depth),
        &CutObserverSettings::default(),
    )
    .unwrap();
    println!("# {} {label}", setup.name);
    println!(
        "t y depth crack l_truth l_profile fy fy_truth sections detected model_n model_t S T F l_outline touched obs_depth ft"
    );
    let (estimated, _, _) = end_of_cut(&setup, truth, &settings, None, &mut |tr| {
        let m = &tr.step.reading;
        let seen = observer.observe(m);
        let clearance = tr.task.clearance(&m.position);
        let depth = EdgeOutline::penetration(clearance);
        tare.observe(&m.wrench, clearance);
        let fy = tare.tared(&m.wrench)[1];
        if clearance <= 0.0 {
            fracture.observe(m.time, &m.position, fy, tare.sigma()[1]);
        }
        let v_n = -m.velocity.y;
        let xi = if v_n > 0.0 {
            m.velocity.z.abs() / v_n
        } else {
            0.0
        };
        let state = StageState {
            depth: tr.profile.section_depth(depth),
            height: tr.profile.height(),
            half_width: tr.profile.half_width(),
            fractured: false,
            travel_since_fracture: 0.0,
        };
        let [n, t] = tr.model.force_model(xi, &state, [1.0; 3]).unwrap();
        let l = tr.profile.contact_length(depth);
        if tr.step.truth.crack_depth > 0.0 || depth > 0.0 {
            println!(
                "{:.3} {:.6} {:.6} {:.6} {:.5} {:.5} {:.4} {:.4} {} {} {:.2} {:.2} {:.4} {:.4} {:.4} {:.5} {} {:.6} {:.4}",
                m.time,
                m.position.y,
                depth,
                tr.step.truth.crack_depth,
                tr.step.truth.contact_length,
                l,
                fy,
                tr.step.truth.wrench.force.y,
                tr.step.truth.fractured_sections,
                u8::from(fracture.fracture().is_some()),
                n.nominal * l,
                t.nominal * l,
                tr.scale[1],
                tr.scale[0],
                tr.scale[2],
                seen.contact_length,
                u8::from(seen.touch.is_some()),
                seen.edge_depth,
                -tare.tared(&m.wrench)[2] * m.velocity.z.signum(),
            );
        }
    });
    println!("# end {estimated:?} truth {truth:?}");
}

/// A diagnostic of the half potato's stiffness (docs/controllers.md): each
/// plant cut twice, the second time with the MPC's profile holding the
/// contact length the plant had at each edge depth in the first cut (not
/// an arm's knowledge: what the estimator would reach if its contact
/// length were the plant's).
#[test]
#[ignore = "a diagnostic with the plant's contact length in the profile: run in release with --ignored --nocapture"]
fn the_half_potato_with_the_plants_contact_length() {
    let settings = MpcSettings {
        estimate: true,
        ..MpcSettings::default()
    };
    for (label, truth) in PLANTS {
        let (mut depths, mut lengths) = (Vec::new(), Vec::new());
        let mut shape = None;
        end_of_cut(&WHOLE, truth, &settings, None, &mut |tr| {
            let depth = tr.task.edge_depth(&tr.step.reading.position);
            shape.get_or_insert((tr.profile.height(), tr.profile.half_width()));
            if depths.last().is_none_or(|d| depth > d + 1e-7) {
                depths.push(depth);
                lengths.push(tr.step.truth.contact_length);
            }
        });
        let (height, half_width) = shape.unwrap();
        let contact = DepthProfile::new(depths, lengths, height, half_width).unwrap();
        let (estimated, _, _) = end_of_cut(&WHOLE, truth, &settings, Some(&contact), &mut |_| {});
        let e = errors(estimated, truth);
        println!(
            "half potato {label:18} T {:.3} ({:+5.1} %)  S {:.3} ({:+5.1} %)  F {:.3} ({:+5.1} %)",
            estimated[0],
            100.0 * e[0],
            estimated[1],
            100.0 * e[1],
            estimated[2],
            100.0 * e[2],
        );
    }
}
