//! How far the observers (`shearcut_controllers::observer`) are from the
//! plant's truth over the shipped loop scenarios (`config/scenarios/loop-*.toml`,
//! built as `shearcut run` builds them: seed 0, 1 kHz, default arm), under
//! constant motions like the MPC's, with and without sensor noise and bias.
//! Prints the markdown tables of `docs/observers.md`.
//!
//! ```text
//! cargo run --release -p shearcut-controllers --example observer_accuracy
//! ```
//!
//! Each (scenario, motion) runs the full plant once, recording the true
//! wrench and the truth each tick; every sensor condition then reads the
//! same true wrench through its own seeded [`FtSensor`] and feeds its own
//! [`CutObserver`]. The guarded motion (5 mm/s until the first fracture, as
//! the MPC's estimator approaches) is closed on an observer reading the
//! plant's own sensor (noise 0.01 N, bias +0.5 N on fy).

use nalgebra::Vector3;
use shearcut_controllers::controller::{MotionLimits, VelocityShaper, stopping_distance};
use shearcut_controllers::mpc::DepthProfile;
use shearcut_controllers::observer::{CutEstimate, CutObserver, CutObserverSettings, CutTarget};
use shearcut_plant::{FtSensor, FtSensorSettings, Plant, PlantSettings, PlantSpec};
use shearcut_sim::arm::ArmLimits;
use shearcut_sim::arm::{ArmReading, ArmStatus};
use shearcut_sim::geometry::{Polygon, TriangleMesh};
use shearcut_sim::knife_plane::knife_plane_silhouette;
use shearcut_sim::section::SectionSettings;
use shearcut_sim::{Cuboid, Knife, KnifePreset, Material, MaterialPreset, ObjectShape};

/// Servo period, s.
const PERIOD: f64 = 1e-3;
/// Longest run, ticks (30 s, as `shearcut run`).
const MAX_TICKS: usize = 30_000;
/// Ticks recorded past the later of the truth's and the observers' done.
const TAIL: usize = 30;
/// Safety margin on the arm's acceleration and jerk (as `shearcut run`).
const ARM_MARGIN: f64 = 0.9;

/// One shipped loop scenario.
struct Scenario {
    name: &'static str,
    material: MaterialPreset,
    knife: KnifePreset,
    object: ObjectShape,
    z0: f64,
    depth: f64,
    blade_budget: f64,
    section: SectionSettings,
    update_distance: f64,
}

fn scenarios() -> Vec<Scenario> {
    let cuboid = ObjectShape::Cuboid(Cuboid {
        width: 0.03,
        height: 0.025,
        length: 0.03,
    });
    let half_potato = ObjectShape::HalfPotato {
        length: 0.09,
        width: 0.06,
        height: 0.035,
    };
    let default_section = SectionSettings::default();
    vec![
        Scenario {
            name: "potato-cuboid",
            material: MaterialPreset::PotatoCuboid,
            knife: KnifePreset::Straight,
            object: cuboid.clone(),
            z0: 0.02,
            depth: 0.02,
            blade_budget: 0.012,
            section: default_section,
            update_distance: 1e-3,
        },
        Scenario {
            name: "potato-cuboid-short-stroke",
            material: MaterialPreset::PotatoCuboid,
            knife: KnifePreset::Straight,
            object: cuboid,
            z0: 0.02,
            depth: 0.02,
            blade_budget: 0.004,
            section: default_section,
            update_distance: 1e-3,
        },
        Scenario {
            name: "potato-whole",
            material: MaterialPreset::PotatoWhole,
            knife: KnifePreset::Chef,
            object: half_potato.clone(),
            z0: 0.02,
            depth: 0.025,
            blade_budget: 0.015,
            section: default_section,
            update_distance: 1e-3,
        },
        Scenario {
            name: "potato-whole-realtime",
            material: MaterialPreset::PotatoWhole,
            knife: KnifePreset::Chef,
            object: half_potato,
            z0: 0.02,
            depth: 0.025,
            blade_budget: 0.015,
            section: SectionSettings {
                row_spacing: 4e-4,
                grading_ratio: 1.5,
                max_element_width: 4e-3,
                ..default_section
            },
            update_distance: 2e-3,
        },
        Scenario {
            name: "eggplant-whole",
            material: MaterialPreset::EggplantWhole,
            knife: KnifePreset::Chef,
            object: ObjectShape::Eggplant {
                length: 0.2,
                diameter: 0.07,
                flat: 0.004,
            },
            z0: 0.02,
            depth: 0.04,
            blade_budget: 0.02,
            section: default_section,
            update_distance: 1e-3,
        },
    ]
}

/// A constant motion: slice-push ratio (None: the scenario's blade budget
/// over its depth, at most 1), speed along the velocity (m/s), and whether
/// the normal speed is held to 5 mm/s until the observed first fracture.
#[derive(Debug, Clone, Copy)]
struct Motion {
    name: &'static str,
    xi: Option<f64>,
    speed: f64,
    guarded: bool,
}

const MOTIONS: [Motion; 4] = [
    Motion {
        name: "press 20 mm/s",
        xi: Some(0.0),
        speed: 0.02,
        guarded: false,
    },
    Motion {
        name: "slice B/d 20 mm/s",
        xi: None,
        speed: 0.02,
        guarded: false,
    },
    Motion {
        name: "slice 1 50 mm/s",
        xi: Some(1.0),
        speed: 0.05,
        guarded: false,
    },
    Motion {
        name: "guarded 5→20 mm/s",
        xi: None,
        speed: 0.02,
        guarded: true,
    },
];

/// Normal speed of the guarded touch, m/s (`MpcSettings::touch_speed`).
const TOUCH_SPEED: f64 = 0.005;

/// A sensor condition.
#[derive(Debug, Clone, Copy)]
struct Condition {
    name: &'static str,
    sensor: FtSensorSettings,
}

fn conditions() -> [Condition; 5] {
    let noise = FtSensorSettings::default();
    let quiet = FtSensorSettings {
        force_noise: 0.0,
        torque_noise: 0.0,
        ..noise
    };
    let bias = [0.5, -0.5, 0.5, 0.0, 0.0, 0.0];
    [
        Condition {
            name: "noise-free",
            sensor: quiet,
        },
        Condition {
            name: "σ 0.01 N",
            sensor: noise,
        },
        Condition {
            name: "σ 0.01 N, bias fy −0.5 N",
            sensor: FtSensorSettings { bias, ..noise },
        },
        Condition {
            name: "σ 0.01 N, bias fy +0.5 N",
            sensor: FtSensorSettings {
                bias: bias.map(|b| -b),
                ..noise
            },
        },
        Condition {
            name: "σ 0.05 N",
            sensor: FtSensorSettings {
                force_noise: 0.05,
                ..noise
            },
        },
    ]
}

/// What the plant knew each tick.
#[derive(Debug, Clone, Copy)]
struct Tick {
    time: f64,
    position: Vector3<f64>,
    velocity: Vector3<f64>,
    true_wrench: [f64; 6],
    contact_length: f64,
    fractured: bool,
    crack_depth: f64,
}

/// The lab's knowledge of a scenario: knife, outline, profile, target.
struct Task {
    knife: Knife,
    outline: Polygon,
    profile: DepthProfile,
    target: CutTarget,
}

fn observer(task: &Task, settings: &CutObserverSettings) -> CutObserver {
    CutObserver::new(&task.knife, &task.outline, task.target, settings).expect("valid settings")
}

/// Runs the plant under `motion` and records every tick.
fn record(
    s: &Scenario,
    motion: &Motion,
    material: &Material,
    mesh: &TriangleMesh,
    task: &Task,
) -> Vec<Tick> {
    let arm = ArmLimits::default();
    let limits = MotionLimits::within_arm(0.05, 0.1, arm.acceleration, arm.jerk, ARM_MARGIN);
    let xi = motion
        .xi
        .unwrap_or_else(|| (s.blade_budget / s.depth).min(1.0));
    let in_loop = FtSensorSettings {
        bias: [0.0, 0.5, 0.0, 0.0, 0.0, 0.0],
        ..FtSensorSettings::default()
    };
    let settings = PlantSettings {
        segments: 20,
        reach: s.blade_budget,
        update_distance: s.update_distance,
        sensor: in_loop,
        ..PlantSettings::default()
    };
    let mut plant = Plant::new(
        PlantSpec {
            material,
            knife: &task.knife,
            object: mesh,
            z0: s.z0,
            direction: Plant::direction_at(xi),
            settings: &settings,
            section: &s.section,
            arm_limits: &arm,
        },
        0,
    )
    .expect("the shipped scenarios build");
    let mut shaper = VelocityShaper::new(PERIOD, &limits).expect("1 kHz");
    let mut obs = observer(task, &CutObserverSettings::default());
    let mut ticks = Vec::new();
    let mut m = plant
        .step(&Default::default(), PERIOD)
        .expect("plant steps");
    let z_start = m.reading.position.z;
    let (mut truth_done, mut tail) = (false, 0);
    for _ in 0..MAX_TICKS {
        let e = obs.observe(&m.reading);
        truth_done |= m.truth.crack_depth >= s.depth;
        ticks.push(Tick {
            time: m.reading.time,
            position: m.reading.position,
            velocity: m.reading.velocity,
            true_wrench: m.truth.wrench.to_array(),
            contact_length: m.truth.contact_length,
            fractured: m.truth.fractured_sections > 0,
            crack_depth: m.truth.crack_depth,
        });
        if truth_done && e.done {
            tail += 1;
            if tail > TAIL {
                break;
            }
        }
        let full = limits.normal_speed_for(motion.speed, xi);
        // Both the truth's and the observers' done are wanted: the knife
        // stops only when both are.
        let v_n = if e.done && truth_done {
            0.0
        } else if motion.guarded && e.fracture.is_none() {
            full.min(TOUCH_SPEED)
        } else {
            full
        };
        let remaining = s.blade_budget - (m.reading.position.z - z_start);
        let v_t = xi * v_n;
        let v_t = if stopping_distance(v_t, limits.acceleration, limits.jerk) < 0.99 * remaining {
            v_t
        } else {
            0.0
        };
        let command = shaper.command(v_n, v_t);
        m = plant.step(&command, PERIOD).expect("plant steps");
    }
    ticks
}

/// Index of the first tick where `f` holds.
fn first(ticks: &[Tick], f: impl Fn(&Tick) -> bool) -> Option<usize> {
    ticks.iter().position(f)
}

/// The observers' accuracy for one condition of one run.
#[derive(Debug, Clone, Copy, Default)]
struct Accuracy {
    tare_samples: u64,
    bias_error: f64,
    sigma_ratio: f64,
    touch_delay_ticks: Option<i64>,
    touch_height_error: Option<f64>,
    fracture_detect_late: Option<f64>,
    fracture_peak_late: Option<f64>,
    /// Median and 95th percentile of |ΔL|/L, outline and profile.
    outline_error: [f64; 2],
    profile_error: [f64; 2],
    depth_offset_end: Option<f64>,
    done_late: Option<f64>,
}

fn percentile(values: &mut [f64], q: f64) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    let i = ((values.len() - 1) as f64 * q).round() as usize;
    values[i]
}

/// Feeds `ticks` through `condition`'s sensor and an observer; compares
/// with the truth.
fn assess(
    ticks: &[Tick],
    condition: &Condition,
    settings: &CutObserverSettings,
    task: &Task,
    target_depth: f64,
) -> Accuracy {
    let mut sensor = FtSensor::new(condition.sensor, 7).expect("valid sensor");
    let mut obs = observer(task, settings);
    let estimates: Vec<CutEstimate> = ticks
        .iter()
        .map(|t| {
            let reading = ArmReading {
                time: t.time,
                position: t.position,
                velocity: t.velocity,
                wrench: sensor.read(t.time, &t.true_wrench),
                status: ArmStatus::Moving,
            };
            obs.observe(&reading)
        })
        .collect();
    let mut a = Accuracy {
        tare_samples: obs.tare().samples(),
        bias_error: obs.tare().bias()[1] - condition.sensor.bias[1],
        sigma_ratio: if condition.sensor.force_noise > 0.0 {
            obs.tare().sigma()[1] / condition.sensor.force_noise
        } else {
            obs.tare().sigma()[1]
        },
        ..Accuracy::default()
    };
    let truth_touch = first(ticks, |t| t.contact_length > 0.0);
    let last = estimates.last().copied();
    let observed_touch = estimates.iter().position(|e| e.touch.is_some());
    if let (Some(tt), Some(ot), Some(touch)) =
        (truth_touch, observed_touch, last.and_then(|e| e.touch))
    {
        a.touch_delay_ticks = Some(ot as i64 - tt as i64);
        // The truth's contact began between the reading before its first
        // in contact and that one: the error is the distance outside.
        let (low, high) = (ticks[tt].position.y, ticks[tt.saturating_sub(1)].position.y);
        let y = touch.position.y;
        a.touch_height_error = Some(if y > high {
            y - high
        } else if y < low {
            y - low
        } else {
            0.0
        });
    }
    let truth_fracture = first(ticks, |t| t.fractured);
    if let (Some(tf), Some(f)) = (truth_fracture, last.and_then(|e| e.fracture)) {
        a.fracture_detect_late = Some(f.detected_at - ticks[tf].time);
        a.fracture_peak_late = Some(f.time - ticks[tf].time);
    }
    let (mut outline, mut profile) = (Vec::new(), Vec::new());
    let observed_done = estimates.iter().position(|e| e.done);
    let end = observed_done.unwrap_or(ticks.len());
    for (t, e) in ticks.iter().zip(&estimates).take(end) {
        if e.edge_depth >= 1e-3 && t.contact_length > 0.0 {
            outline.push((e.contact_length - t.contact_length).abs() / t.contact_length);
            let l = task.profile.contact_length(e.edge_depth);
            profile.push((l - t.contact_length).abs() / t.contact_length);
        }
    }
    a.outline_error = [
        percentile(&mut outline, 0.5),
        percentile(&mut outline, 0.95),
    ];
    a.profile_error = [
        percentile(&mut profile, 0.5),
        percentile(&mut profile, 0.95),
    ];
    if let Some(od) = observed_done {
        let e = estimates[od];
        a.depth_offset_end = Some(ticks[od].crack_depth - e.edge_depth);
        if let Some(td) = first(ticks, |t| t.crack_depth >= target_depth) {
            a.done_late = Some(ticks[od].time - ticks[td].time);
        }
    }
    a
}

fn opt(v: Option<f64>, scale: f64, digits: usize) -> String {
    v.map_or("–".into(), |x| format!("{:.*}", digits, x * scale))
}

/// Fracture settings compared at σ 0.01 N: the default's drop fraction
/// and two higher ones.
const DROP_FRACTIONS: [f64; 3] = [0.02, 0.04, 0.06];

/// One (scenario, motion) and its assessments: per condition at default
/// settings, then per drop fraction at σ 0.01 N.
struct Row {
    scenario: &'static str,
    motion: &'static str,
    by_condition: Vec<Accuracy>,
    by_drop: Vec<Accuracy>,
}

fn ticks_and_height(a: &Accuracy) -> String {
    match (a.touch_delay_ticks, a.touch_height_error) {
        (Some(d), Some(h)) => format!("{d} / {:.1}", h * 1e6),
        _ => "–".into(),
    }
}

fn fracture(a: &Accuracy) -> String {
    match (a.fracture_detect_late, a.fracture_peak_late) {
        (Some(d), Some(p)) => format!("{:.0} ({:.0})", d * 1e3, p * 1e3),
        _ => "–".into(),
    }
}

/// Prints the wall time of `CutObserver::observe` per reading over `ticks`
/// read through the σ 0.01 N sensor (median, p99, max of 20 passes).
#[allow(clippy::disallowed_methods)] // A benchmark: wall time is what it measures.
fn cost(ticks: &[Tick], task: &Task) {
    let mut sensor = FtSensor::new(FtSensorSettings::default(), 7).expect("valid sensor");
    let readings: Vec<ArmReading> = ticks
        .iter()
        .map(|t| ArmReading {
            time: t.time,
            position: t.position,
            velocity: t.velocity,
            wrench: sensor.read(t.time, &t.true_wrench),
            status: ArmStatus::Moving,
        })
        .collect();
    let mut times = Vec::with_capacity(20 * readings.len());
    for _ in 0..20 {
        let mut obs = observer(task, &CutObserverSettings::default());
        for r in &readings {
            let start = std::time::Instant::now();
            std::hint::black_box(obs.observe(std::hint::black_box(r)));
            times.push(start.elapsed().as_secs_f64());
        }
    }
    let n = times.len();
    let median = percentile(&mut times, 0.5);
    let p99 = percentile(&mut times, 0.99);
    let max = times[n - 1];
    eprintln!(
        "CutObserver::observe, chef's knife, {n} readings: median {:.2} µs, p99 {:.2} µs, max {:.2} µs",
        median * 1e6,
        p99 * 1e6,
        max * 1e6
    );
}

fn main() {
    let conditions = conditions();
    let default = CutObserverSettings::default();
    let mut rows = Vec::new();
    for s in scenarios() {
        let mesh = s.object.mesh().expect("shipped object");
        let task = Task {
            knife: Knife::new(&s.knife.settings()).expect("preset knife"),
            outline: knife_plane_silhouette(&mesh).expect("object crosses the knife plane"),
            profile: DepthProfile::of_object(&mesh).expect("object crosses the knife plane"),
            target: CutTarget::Depth(s.depth),
        };
        let material = s.material.material();
        for motion in &MOTIONS {
            eprintln!("{} / {} ...", s.name, motion.name);
            let ticks = record(&s, motion, &material, &mesh, &task);
            let by_condition = conditions
                .iter()
                .map(|c| assess(&ticks, c, &default, &task, s.depth))
                .collect();
            let by_drop = DROP_FRACTIONS
                .iter()
                .map(|f| {
                    let mut settings = default;
                    settings.fracture.drop_fraction = *f;
                    assess(&ticks, &conditions[1], &settings, &task, s.depth)
                })
                .collect();
            if s.name == "eggplant-whole" && motion.guarded {
                cost(&ticks, &task);
            }
            rows.push(Row {
                scenario: s.name,
                motion: motion.name,
                by_condition,
                by_drop,
            });
        }
    }
    let names: Vec<&str> = conditions.iter().map(|c| c.name).collect();
    println!("### Tare (free-air samples; fy bias error, mN; σ̂/σ)\n");
    println!("| scenario | motion | n | {} |", names[1..4].join(" | "));
    println!("|---|---|---|---|---|---|");
    for r in &rows {
        let cells: Vec<String> = r.by_condition[1..4]
            .iter()
            .map(|a| format!("{:+.1} / {:.2}", a.bias_error * 1e3, a.sigma_ratio))
            .collect();
        println!(
            "| {} | {} | {} | {} |",
            r.scenario,
            r.motion,
            r.by_condition[1].tare_samples,
            cells.join(" | ")
        );
    }
    println!(
        "\n### Touch (detected Δticks after the truth's first tick in contact / back-dated height outside the truth's tick, µm)\n"
    );
    println!("| scenario | motion | {} |", names.join(" | "));
    println!("|---|---|---|---|---|---|---|");
    for r in &rows {
        let cells: Vec<String> = r.by_condition.iter().map(ticks_and_height).collect();
        println!("| {} | {} | {} |", r.scenario, r.motion, cells.join(" | "));
    }
    println!(
        "\n### First fracture (detected ms after the truth's first fractured tick (peak − truth, ms))\n"
    );
    let drops: Vec<String> = DROP_FRACTIONS
        .iter()
        .map(|f| format!("σ 0.01 N, drop {f}"))
        .collect();
    println!(
        "| scenario | motion | {} | {} | {} |",
        names[0],
        names[4],
        drops.join(" | ")
    );
    println!("|---|---|---|---|---|---|---|");
    for r in &rows {
        let cells: Vec<String> = r.by_drop.iter().map(fracture).collect();
        println!(
            "| {} | {} | {} | {} | {} |",
            r.scenario,
            r.motion,
            fracture(&r.by_condition[0]),
            fracture(&r.by_condition[4]),
            cells.join(" | ")
        );
    }
    println!("\n### Contact length, depth and done (σ 0.01 N)\n");
    println!(
        "| scenario | motion | L outline med / p95 % | L profile med / p95 % | crack − edge at done, mm | done − truth done, ms |"
    );
    println!("|---|---|---|---|---|---|");
    for r in &rows {
        let a = &r.by_condition[1];
        println!(
            "| {} | {} | {:.1} / {:.1} | {:.1} / {:.1} | {} | {} |",
            r.scenario,
            r.motion,
            a.outline_error[0] * 100.0,
            a.outline_error[1] * 100.0,
            a.profile_error[0] * 100.0,
            a.profile_error[1] * 100.0,
            opt(a.depth_offset_end, 1e3, 2),
            opt(a.done_late, 1e3, 0),
        );
    }
}
