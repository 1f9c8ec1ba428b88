//! Diagnostic: where the closed-loop "plant / model at truth" ratios of the
//! estimator test (`controllers/tests/mpc_estimator_plants.rs`) come from,
//! split into the plant against one section cut alone and that section
//! against the surrogate.
//!
//! The plant (potato cuboid 30 wide × 25 high × 30 long, straight knife, 20
//! segments, noise-free wrench) is driven open loop at a constant slice-push
//! ratio ξ; one rectangular section of the same size (25 × 15 mm) is cut by
//! the sweep at the same ξ. Over the window the test uses (crack depth at
//! least 2 mm past the first fracture, to 20 mm) the script prints the
//! normal and tangential work, plant over surrogate (the surrogate at the
//! plant's crack depth, as the test evaluates it), section over surrogate
//! (the same evaluation on the section's samples) and plant over section
//! (work per unit length of edge in contact, both as functions of the
//! crack depth).
//!
//! `cargo run --release -p shearcut-sim --example plant_vs_section --
//! [T S]` (scale factors of R_c, R'_c and E, default 1 1; friction nominal).

use nalgebra::{Vector2, Vector3};
use shearcut_plant::{ArmLimits, KnifeCommand, Plant, PlantSettings, PlantSpec};
use shearcut_sim::section::SectionSettings;
use shearcut_sim::surrogate::{
    CutState, ScaleFactors, Surrogate, SweepCase, SweepSettings, run_sweep, scaled_material,
};
use shearcut_sim::{Cuboid, Knife, KnifePreset, MaterialPreset, ObjectShape};

/// Crack depth past the first fracture before the window starts (the
/// estimator test's settling depth), m.
const SETTLE: f64 = 2e-3;
/// Crack depth where the window ends (the test's target depth), m.
const TARGET: f64 = 0.02;
/// Section size of the cuboid (height, half width), m.
const SIZE: (f64, f64) = (0.025, 0.015);

fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a number"))
        .collect();
    let (t, st) = match args.as_slice() {
        [t, s] => (*t, *s),
        _ => (1.0, 1.0),
    };
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../config/surrogates/potato-cuboid-straight.toml"
    );
    let surrogate = Surrogate::from_path(std::path::Path::new(path)).expect("surrogate");
    let material = scaled_material(&MaterialPreset::PotatoCuboid.material(), t, st);
    let scale = ScaleFactors {
        toughness: t,
        stiffness: st,
        friction: 1.0,
    };
    println!("T {t} S {st}: xi | plant/model Wn Wt | section/model Wn Wt | plant/section Wn Wt");
    for xi in [0.3, 0.6, 1.0] {
        let plant = plant_work(&material, &surrogate, &scale, xi);
        let section = section_work(&material, &surrogate, &scale, xi);
        println!(
            "{xi:.1} | {:.3} {:.3} | {:.3} {:.3} | {:.3} {:.3}",
            plant[0] / plant[2],
            plant[1] / plant[3],
            section[0] / section[2],
            section[1] / section[3],
            plant[0] / section[0],
            plant[1] / section[1],
        );
        println!(
            "    section/model at the edge's depth Wn Wt {:.3} {:.3}; plant {:.3?} section {:.3?} (J/m: Wn, Wt, model Wn, model Wt[, at the edge's depth])",
            section[0] / section[4],
            section[1] / section[5],
            plant,
            section
        );
    }
}

/// The surrogate's (F_n, F_t) at ξ and crack depth `depth`, `since` past
/// the first fracture, on the cuboid's section.
fn model(s: &Surrogate, scale: &ScaleFactors, xi: f64, depth: f64, since: f64) -> [f64; 2] {
    let o = s.evaluate(
        xi,
        &CutState {
            depth,
            height: SIZE.0,
            half_width: SIZE.1,
            fractured: true,
            travel_since_fracture: since,
        },
        scale,
    );
    [o.force_normal, o.force_tangential]
}

/// Over the window, per unit length of edge in contact: [normal work,
/// tangential work, the surrogate's normal work, its tangential work] of
/// the plant cut open loop at ξ (J/m).
fn plant_work(
    material: &shearcut_sim::Material,
    s: &Surrogate,
    scale: &ScaleFactors,
    xi: f64,
) -> [f64; 4] {
    let knife = Knife::new(&KnifePreset::Straight.settings()).expect("knife");
    let mesh = ObjectShape::Cuboid(Cuboid {
        width: 0.03,
        height: 0.025,
        length: 0.03,
    })
    .mesh()
    .expect("mesh");
    // The arm's limits out of the way: the knife starts at its speed.
    let arm = ArmLimits {
        velocity: 3.0,
        acceleration: 1e9,
        jerk: 1e15,
    };
    let alpha = f64::atan(xi);
    let direction = Vector2::new(alpha.sin(), -alpha.cos());
    let settings = PlantSettings {
        segments: 20,
        reach: xi * 0.025 + 0.005,
        ..PlantSettings::default()
    };
    let mut plant = Plant::new(
        PlantSpec {
            material: &material.clone(),
            knife: &knife,
            object: &mesh,
            z0: 0.02,
            direction,
            settings: &settings,
            section: &SectionSettings::default(),
            arm_limits: &arm,
        },
        0,
    )
    .expect("plant");
    let speed = 0.02;
    let command = KnifeCommand {
        velocity: Vector3::new(0.0, direction.y, direction.x) * speed,
    };
    let dt = 1e-3;
    let mut fracture: Option<f64> = None;
    let mut acc = [0.0; 4];
    for _ in 0..20_000 {
        let m = plant.step(&command, dt).expect("plant steps");
        let (v_n, v_t, l) = (
            -m.reading.velocity.y,
            m.reading.velocity.z.abs(),
            m.truth.contact_length,
        );
        if m.truth.crack_depth >= TARGET {
            break;
        }
        if m.truth.fractured_sections == 0 || !(v_n > 0.0 && l > 0.0) {
            continue;
        }
        let depth = m.truth.crack_depth.max(0.0);
        let since = depth - *fracture.get_or_insert(depth);
        if since < SETTLE {
            continue;
        }
        let w = m.truth.wrench.to_array();
        let f = model(s, scale, xi, depth, since);
        acc[0] += w[1] * v_n * dt / l;
        acc[1] += -w[2] * m.reading.velocity.z.signum() * v_t * dt / l;
        acc[2] += f[0] * v_n * dt;
        acc[3] += f[1] * v_t * dt;
    }
    acc
}

/// The same four works for one section of the cuboid's size cut alone at
/// ξ (the sweep), as functions of its crack depth.
fn section_work(
    material: &shearcut_sim::Material,
    s: &Surrogate,
    scale: &ScaleFactors,
    xi: f64,
) -> [f64; 6] {
    let runs = run_sweep(
        material,
        &KnifePreset::Straight.settings().blade,
        &[SweepCase {
            xi,
            height: SIZE.0,
            half_width: SIZE.1,
        }],
        &SweepSettings {
            depth_fraction: 0.9,
            ..SweepSettings::default()
        },
        1,
        &|| {},
    )
    .expect("sweep");
    let samples = &runs[0].samples;
    let mut fracture: Option<f64> = None;
    let mut acc = [0.0; 6];
    let mut edge_fracture: Option<f64> = None;
    for pair in samples.windows(2) {
        let (a, x) = (pair[0], pair[1]);
        let dd = x.depth - a.depth;
        if !x.fractured || x.crack_depth >= TARGET {
            continue;
        }
        let depth = x.crack_depth;
        let since = depth - *fracture.get_or_insert(depth);
        if since < SETTLE {
            continue;
        }
        let f = model(s, scale, xi, depth, since);
        acc[0] += x.force_normal * dd;
        acc[1] += x.force_tangential * xi * dd;
        acc[2] += f[0] * dd;
        acc[3] += f[1] * xi * dd;
        let since_edge = x.depth - *edge_fracture.get_or_insert(x.depth - since);
        let e = model(s, scale, xi, x.depth, since_edge);
        acc[4] += e[0] * dd;
        acc[5] += e[1] * xi * dd;
    }
    acc
}
