//! Cost of one `Plant::step` at 1 kHz ticks: the whole-potato, curved-knife
//! scenario of seed 000 Fig. 10(a) (chef's knife, half potato with skin,
//! α = 0, z₀ = 0.046 m, the default m = 20 segments over the span), from the approach through the first
//! fractures to steady cutting, at the default section mesh and a coarser
//! one, then Fig. 10(b)'s slice (α = 24°, z₀ = 0.087 m). Prints median, p99
//! and worst µs per tick and
//! the real-time factor (1 ms of simulated time per wall-clock tick time),
//! the condensed-line solves per tick (the sections' cost counter: the
//! compute a tick needs, free of the machine's load), and the re-choices,
//! rebuilds (on the plant's worker thread), ticks that waited for it and
//! sections it built for orders renewed or dropped before they were taken.
//!
//! Run: `cargo bench -p shearcut-sim --bench plant`.

// A benchmark measures wall time by design.
#![allow(clippy::disallowed_methods)]

use std::hint::black_box;
use std::time::Instant;

use nalgebra::{Vector2, Vector3};
use shearcut_plant::{ArmLimits, KnifeCommand, Plant, PlantSettings, PlantSpec};
use shearcut_sim::{Knife, KnifePreset, MaterialPreset, ObjectShape, SectionSettings};

fn main() {
    // The default section mesh (rows every 0.2 mm), then rows every 0.4 mm:
    // a solve's cost grows with the square of the rows on the cut line, so
    // the coarser mesh shows what the tick costs scale with.
    // Then Fig. 10(b)'s slice (α = 24°, z₀ = 0.087 m), whose segments slide
    // along the potato: frequent re-choices with successors built on the
    // worker.
    for (row_spacing, alpha_deg, z0) in
        [(2e-4, 0.0, 0.046), (4e-4, 0.0, 0.046), (2e-4, 24.0, 0.087)]
    {
        println!(
            "-- row spacing {:.1} mm, alpha {alpha_deg} deg, z0 {z0} m",
            row_spacing * 1e3
        );
        let section = SectionSettings {
            row_spacing,
            ..SectionSettings::default()
        };
        run(&section, f64::to_radians(alpha_deg), z0);
    }
}

fn run(section: &SectionSettings, alpha: f64, z0: f64) {
    // Towards the tip (+z) and down, as `shearcut simulate` slices.
    let direction = Vector2::new(alpha.sin(), -alpha.cos());
    let material = MaterialPreset::PotatoWhole.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let object = ObjectShape::HalfPotato {
        length: 0.09,
        width: 0.06,
        height: 0.035,
    }
    .mesh()
    .unwrap();
    let settings = PlantSettings::default();
    let t0 = Instant::now();
    let mut plant = Plant::new(
        PlantSpec {
            material: &material,
            knife: &knife,
            object: &object,
            z0,
            direction,
            settings: &settings,
            section,
            arm_limits: &ArmLimits::default(),
        },
        0,
    )
    .unwrap();
    plant.build_ordered_sections();
    let build = t0.elapsed();
    let dt = 1e-3;
    let speed = 0.00625;
    // 4 s: a 50 ms ramp to 6.25 mm/s, then 25 mm of travel.
    let ticks = 4000;
    let mut times = Vec::with_capacity(ticks);
    // Condensed-line solves per tick (the sections' cost counter; a
    // rebuilt section restarts its count, so a rebuild tick may read low).
    let mut solves = Vec::with_capacity(ticks);
    let mut last = None;
    for k in 1..=ticks {
        let v = speed * (k as f64 * dt / 0.05).min(1.0);
        let cmd = KnifeCommand {
            velocity: Vector3::new(0.0, direction.y, direction.x) * v,
        };
        let before = plant.section_solves();
        let t = Instant::now();
        let m = black_box(plant.step(&cmd, dt).unwrap());
        times.push(t.elapsed().as_secs_f64() * 1e6);
        solves.push(plant.section_solves().saturating_sub(before));
        last = Some(m);
    }
    let m = last.unwrap();
    let worst_tick = (0..ticks)
        .max_by(|&a, &b| times[a].total_cmp(&times[b]))
        .unwrap();
    let worst_solves = solves[worst_tick];
    let mut by_solves = solves.clone();
    by_solves.sort_unstable();
    println!(
        "condensed-line solves per tick: median {}, p99 {}, max {}; in the slowest tick {} (tick {})",
        by_solves[ticks / 2],
        by_solves[(ticks - 1) * 99 / 100],
        by_solves[ticks - 1],
        worst_solves,
        worst_tick + 1
    );
    let total: f64 = times.iter().sum();
    times.sort_by(f64::total_cmp);
    let pct = |p: f64| times[((times.len() - 1) as f64 * p).round() as usize];
    println!(
        "plant build ({} segments, first sections built): {:.0} ms; {} ticks of 1 ms: median {:.1} µs, p99 {:.1} µs, max {:.1} µs per tick; real-time factor {:.1}x (mean tick {:.1} µs)",
        plant.edge_segments().len(),
        build.as_secs_f64() * 1e3,
        ticks,
        pct(0.5),
        pct(0.99),
        times[times.len() - 1],
        1e3 * ticks as f64 / total,
        total / ticks as f64
    );
    println!(
        "end state: crack depth {:.1} mm (mean of sections), {} sections fractured, F_y {:.1} N",
        m.truth.crack_depth * 1e3,
        m.truth.fractured_sections,
        m.truth.wrench.force.y
    );
    println!(
        "re-choices {}, rebuilds {} (built on the worker thread), unforeseen {}, ticks that waited for the worker {}, sections built and dropped untaken {}",
        plant.rechoices(),
        plant.rebuilds(),
        plant.unforeseen_rechoices(),
        plant.successor_waits(),
        plant.wasted_builds()
    );
}
