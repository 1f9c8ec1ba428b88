//! Diagnostic: the surrogate's mean post-fracture forces against the section
//! model's (sums over the fractured samples with travel since fracture
//! ≥ 2 mm, section over surrogate, nominal factors, cut to 80 % of the
//! height), split into the friction and non-friction parts.
//!
//! `cargo run --release -p shearcut-sim --example normal_force_bias --
//! [SURROGATE.toml] [MATERIAL]` (defaults: the shipped potato-cuboid-straight
//! surrogate and `potato-cuboid`).
//!
//! With a third argument `scaled`, instead: the same mean ratios (F_n, F_t,
//! their friction parts F_n^f, F_t^f and F_n less friction) at the sizes the
//! closed-loop plants use (the potato cuboid's 25 × 15 mm section, the half
//! potato's 35 × 30, 25 × 20 and 15 × 10 mm, the fit size 30 × 15 mm) at
//! ξ = 0.3, 0.6, 1 and at the scale factors (T, S) = (1, 1), (0.7, 1.3) and
//! (1.3, 0.7) (ρ = S/T = 1, 1.86, 0.54): the section model with R_c, R'_c
//! scaled by T and E by S against the surrogate at those factors (F = 1),
//! with the ratio corrections. Other factors: `scaled T S [T S …]`.
//!
//! With `profile T S H w ξ` (H, w in m): one run's friction part of F_n
//! and its non-friction part, section and surrogate, mean over bins of the
//! travel since fracture.
//!
//! With `sizes [T S]` instead: at ξ = 0.3, 0.6 and 1 over the fit's six section sizes, the
//! two held-out ones and the plants' (nominal factors or T, S), the window means of
//! the section's F_n^c − r·R_c (the wedge's strain-energy rate U̇ as the
//! fit targets it) against the surrogate's S·U̇, and the ratios of F_n^f
//! and F_n^c, section over surrogate.

use shearcut_sim::surrogate::{
    CutState, ScaleFactors, Surrogate, SweepCase, SweepSettings, grid, run_sweep, scaled_material,
};
use shearcut_sim::{BladeSection, KnifePreset, Material, MaterialPreset};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).cloned().unwrap_or_else(|| {
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../config/surrogates/potato-cuboid-straight.toml"
        )
        .to_string()
    });
    let material_name = args.get(2).map_or("potato-cuboid", String::as_str);
    let s = Surrogate::from_path(std::path::Path::new(&path)).expect("surrogate");
    let material = MaterialPreset::from_name(material_name)
        .expect("material")
        .material();
    let blade = KnifePreset::Straight.settings().blade;
    if args.get(3).map(String::as_str) == Some("scaled") {
        let pairs: Vec<f64> = args[4..]
            .iter()
            .map(|a| a.parse().expect("a number"))
            .collect();
        let factors: Vec<(f64, f64)> = if pairs.is_empty() {
            vec![(1.0, 1.0), (0.7, 1.3), (1.3, 0.7)]
        } else {
            pairs.chunks(2).map(|p| (p[0], p[1])).collect()
        };
        scaled_bias(&s, &material, &blade, &factors);
        return;
    }
    if args.get(3).map(String::as_str) == Some("profile") {
        let v: Vec<f64> = args[4..9]
            .iter()
            .map(|a| a.parse().expect("a number"))
            .collect();
        friction_profile(&s, &material, &blade, [v[0], v[1], v[2], v[3], v[4]]);
        return;
    }
    if args.get(3).map(String::as_str) == Some("sizes") {
        let f: Vec<f64> = args[4..]
            .iter()
            .map(|a| a.parse().expect("a number"))
            .collect();
        let (t, st) = if f.len() == 2 {
            (f[0], f[1])
        } else {
            (1.0, 1.0)
        };
        size_levels(&s, &material, &blade, t, st);
        return;
    }
    let xis = [0.0, 0.3, 0.6, 1.0, 2.5];
    let sizes = [(0.03, 0.015), (0.025, 0.015)];
    let cases: Vec<SweepCase> = sizes
        .iter()
        .flat_map(|&(height, half_width)| {
            xis.iter().map(move |&xi| SweepCase {
                xi,
                height,
                half_width,
            })
        })
        .collect();
    let runs = run_sweep(
        &material,
        &blade,
        &cases,
        &SweepSettings::default(),
        2,
        &|| {},
    )
    .expect("sweep");
    let nominal = ScaleFactors::default();
    energy_rates(&s, &runs);
    for run in &runs {
        let c = run.case;
        let r = shearcut_sim::surrogate::ToughnessRatio::at(c.xi, s.material.poisson_ratio).value;
        let mut acc = [[0.0f64; 3]; 4];
        for x in run.samples.iter().filter(|x| x.fractured) {
            let k = match x.travel_since_fracture {
                t if t < 0.5e-3 => 0,
                t if t < 2e-3 => 1,
                t if t < 8e-3 => 2,
                _ => 3,
            };
            let o = s.evaluate(
                c.xi,
                &CutState {
                    depth: x.depth,
                    height: c.height,
                    half_width: c.half_width,
                    fractured: true,
                    travel_since_fracture: x.travel_since_fracture,
                },
                &nominal,
            );
            let sec = x.force_normal - x.force_normal_friction
                + c.xi * (x.force_tangential - x.force_tangential_friction)
                - r * s.material.fracture_toughness;
            acc[k][0] += sec;
            acc[k][1] += o.strain;
            acc[k][2] += 1.0;
        }
        let t: Vec<String> = acc
            .iter()
            .map(|a| format!("{:.1}/{:.1} (n {})", a[0] / a[2], a[1] / a[2], a[2]))
            .collect();
        println!(
            "{:.0}x{:.0} {:.1} U sec/sur by s in [0,0.5) [0.5,2) [2,8) [8,..) mm: {}",
            c.height * 1e3,
            c.half_width * 1e3,
            c.xi,
            t.join("  ")
        );
    }
    println!(
        "size_mm xi | Fn Ft W (section/surrogate) | Fn^f Ft^f | Fn^c Ft^c Wc | Ft^f/Fn^f sec sur"
    );
    for run in &runs {
        let c = run.case;
        let mut sum = [[0.0f64; 8]; 2];
        for x in run
            .samples
            .iter()
            .filter(|x| x.fractured && x.travel_since_fracture >= 2e-3)
        {
            let state = CutState {
                depth: x.depth,
                height: c.height,
                half_width: c.half_width,
                fractured: true,
                travel_since_fracture: x.travel_since_fracture,
            };
            let o = s.evaluate(c.xi, &state, &nominal);
            let fnf = o.force_normal_parts.by_friction_stiffness;
            let ftf = o.force_tangential_parts.by_friction_stiffness;
            let sec = [
                x.force_normal,
                x.force_tangential,
                x.force_normal + c.xi * x.force_tangential,
                x.force_normal_friction,
                x.force_tangential_friction,
                x.force_normal - x.force_normal_friction,
                x.force_tangential - x.force_tangential_friction,
                x.force_normal - x.force_normal_friction
                    + c.xi * (x.force_tangential - x.force_tangential_friction),
            ];
            let sur = [
                o.force_normal,
                o.force_tangential,
                o.work_per_depth,
                fnf,
                ftf,
                o.force_normal - fnf,
                o.force_tangential - ftf,
                o.work_per_depth - o.friction,
            ];
            for k in 0..8 {
                sum[0][k] += sec[k];
                sum[1][k] += sur[k];
            }
        }
        let q: Vec<String> = (0..8)
            .map(|k| format!("{:.3}", sum[0][k] / sum[1][k]))
            .collect();
        println!(
            "{:.0}x{:.0} {:.1} | {} {} {} | {} {} | {} {} {} | {:.3} {:.3} | Fn sec {:.1} sur {:.1} fric sec {:.1} sur {:.1} N/m-sum",
            c.height * 1e3,
            c.half_width * 1e3,
            c.xi,
            q[0],
            q[1],
            q[2],
            q[3],
            q[4],
            q[5],
            q[6],
            q[7],
            sum[0][4] / sum[0][3],
            sum[1][4] / sum[1][3],
            sum[0][0],
            sum[1][0],
            sum[0][3],
            sum[1][3],
        );
    }
}

/// Per unit depth over the window (travel since fracture ≥ 2 mm to the
/// run's end), from the section's cumulative energies: knife work, fracture
/// work (against r(ξ,ν)·R_c), stored strain energy, friction work; and the
/// sampled forces' F_n^c + ξF_t^c and F_t^c (mean), with the surrogate's.
fn energy_rates(s: &Surrogate, runs: &[shearcut_sim::surrogate::SweepRun]) {
    println!(
        "size xi | dW/dd dWfr/dd (r·Rc) dU/dd dWf/dd | mean Fn^c+xiFt^c, Fn^c, Ft^c, Ft^f/Fn^f | sur U mean, sur Fn^c, Ft^c | crack-depth lead"
    );
    let nominal = ScaleFactors::default();
    for run in runs {
        let c = run.case;
        let w: Vec<_> = run
            .samples
            .iter()
            .filter(|x| x.fractured && x.travel_since_fracture >= 2e-3)
            .collect();
        let (a, z) = (w[0], w[w.len() - 1]);
        let dd = z.depth - a.depth;
        let r = shearcut_sim::surrogate::ToughnessRatio::at(c.xi, s.material.poisson_ratio).value;
        let n = w.len() as f64;
        let mean = |f: &dyn Fn(&shearcut_sim::surrogate::SweepSample) -> f64| {
            w.iter().map(|x| f(x)).sum::<f64>() / n
        };
        let wc = mean(&|x| {
            x.force_normal - x.force_normal_friction
                + c.xi * (x.force_tangential - x.force_tangential_friction)
        });
        let fnc = mean(&|x| x.force_normal - x.force_normal_friction);
        let ftc = mean(&|x| x.force_tangential - x.force_tangential_friction);
        let mut sur = [0.0; 3];
        for x in &w {
            let o = s.evaluate(
                c.xi,
                &CutState {
                    depth: x.depth,
                    height: c.height,
                    half_width: c.half_width,
                    fractured: true,
                    travel_since_fracture: x.travel_since_fracture,
                },
                &nominal,
            );
            sur[0] += o.strain / n;
            sur[1] += (o.force_normal - o.force_normal_parts.by_friction_stiffness) / n;
            sur[2] += (o.force_tangential - o.force_tangential_parts.by_friction_stiffness) / n;
        }
        if c.xi == 0.0 || c.xi == 1.0 {
            let mut line = String::new();
            for k in (0..w.len()).step_by(w.len() / 6) {
                let (p, q) = (w[k], w[(k + w.len() / 6).min(w.len() - 1)]);
                if q.depth > p.depth {
                    let o = s.evaluate(
                        c.xi,
                        &CutState {
                            depth: 0.5 * (p.depth + q.depth),
                            height: c.height,
                            half_width: c.half_width,
                            fractured: true,
                            travel_since_fracture: 0.5
                                * (p.travel_since_fracture + q.travel_since_fracture),
                        },
                        &nominal,
                    );
                    line += &format!(
                        " d/H {:.2}: {:.1}/{:.1}",
                        0.5 * (p.depth + q.depth) / c.height,
                        (q.strain_energy - p.strain_energy) / (q.depth - p.depth),
                        o.strain
                    );
                }
            }
            println!("  dU/dd along the cut:{line}");
            let tail: Vec<String> = w[w.len().saturating_sub(400)..]
                .chunks(50)
                .map(|ch| {
                    format!(
                        "{:.3}:{:.1}",
                        ch[0].depth / c.height,
                        (ch[ch.len() - 1].strain_energy - ch[0].strain_energy)
                            / (ch[ch.len() - 1].depth - ch[0].depth)
                    )
                })
                .collect();
            println!("  tail dU/dd: {}", tail.join(" "));
        }
        let lead = mean(&|x| x.crack_depth - x.depth);
        println!(
            "{:.0}x{:.0} {:.1} | {:.1} {:.1} ({:.1}) {:.1} {:.1} | {:.1} {:.1} {:.2} | {:.1} {:.1} {:.2} | lead {:.3} mm",
            c.height * 1e3,
            c.half_width * 1e3,
            c.xi,
            (z.work - a.work) / dd,
            (z.work_fracture - a.work_fracture) / dd,
            r * s.material.fracture_toughness,
            (z.strain_energy - a.strain_energy) / dd,
            (z.work_friction - a.work_friction) / dd,
            wc,
            fnc,
            ftc,
            sur[0],
            sur[1],
            sur[2],
            lead * 1e3,
        );
    }
}

/// The `scaled` mode (module doc): for each size, ξ and (T, S), the sums
/// over the window (travel since fracture ≥ 2 mm) of the section's F_n,
/// F_t, F_n^f, F_t^f and F_n − F_n^f over the surrogate's, then each
/// (size, ρ)'s mean over ξ.
fn scaled_bias(s: &Surrogate, material: &Material, blade: &BladeSection, factors: &[(f64, f64)]) {
    let xis = [0.3, 0.6, 1.0];
    let sizes = [
        (0.025, 0.015),
        (0.035, 0.03),
        (0.025, 0.02),
        (0.015, 0.01),
        (0.03, 0.015),
    ];
    println!("H x w mm | T S | xi | Fn Ft Fn^f Ft^f Fn^c (section/surrogate)");
    for &(t, st) in factors {
        let scaled = scaled_material(material, t, st);
        let runs = run_sweep(
            &scaled,
            blade,
            &grid(&xis, &sizes),
            &SweepSettings::default(),
            2,
            &|| {},
        )
        .expect("sweep");
        let scale = ScaleFactors {
            toughness: t,
            stiffness: st,
            friction: 1.0,
        };
        for run in &runs {
            let c = run.case;
            let mut sum = [[0.0f64; 5]; 2];
            for x in run
                .samples
                .iter()
                .filter(|x| x.fractured && x.travel_since_fracture >= 2e-3)
            {
                let o = s.evaluate(
                    c.xi,
                    &CutState {
                        depth: x.depth,
                        height: c.height,
                        half_width: c.half_width,
                        fractured: true,
                        travel_since_fracture: x.travel_since_fracture,
                    },
                    &scale,
                );
                let fnf = st * o.force_normal_parts.by_friction_stiffness;
                let ftf = st * o.force_tangential_parts.by_friction_stiffness;
                let sec = [
                    x.force_normal,
                    x.force_tangential,
                    x.force_normal_friction,
                    x.force_tangential_friction,
                    x.force_normal - x.force_normal_friction,
                ];
                let sur = [
                    o.force_normal,
                    o.force_tangential,
                    fnf,
                    ftf,
                    o.force_normal - fnf,
                ];
                for k in 0..5 {
                    sum[0][k] += sec[k];
                    sum[1][k] += sur[k];
                }
            }
            let q: Vec<String> = (0..5)
                .map(|k| format!("{:.3}", sum[0][k] / sum[1][k]))
                .collect();
            println!(
                "{:.0}x{:.0} | {t} {st} | {:.1} | {}",
                c.height * 1e3,
                c.half_width * 1e3,
                c.xi,
                q.join(" ")
            );
        }
    }
}

/// The `sizes` mode (module doc).
fn size_levels(s: &Surrogate, material: &Material, blade: &BladeSection, t: f64, st: f64) {
    let sizes = [
        (0.02, 0.01),
        (0.045, 0.01),
        (0.03, 0.015),
        (0.03, 0.03),
        (0.045, 0.02),
        (0.02, 0.025),
        (0.025, 0.02),
        (0.04, 0.012),
        (0.025, 0.015),
        (0.035, 0.03),
        (0.015, 0.01),
    ];
    let xis = [0.3, 0.6, 1.0];
    let runs = run_sweep(
        &scaled_material(material, t, st),
        blade,
        &grid(&xis, &sizes),
        &SweepSettings::default(),
        2,
        &|| {},
    )
    .expect("sweep");
    let nominal = ScaleFactors {
        toughness: t,
        stiffness: st,
        friction: 1.0,
    };
    println!("T {t} S {st}: H x w mm | xi | U sec sur (N/m) | Fn^f Fn^c Ft^f (section/surrogate)");
    for run in &runs {
        let c = run.case;
        let r = shearcut_sim::surrogate::ToughnessRatio::at(c.xi, s.material.poisson_ratio).value;
        let mut sum = [0.0f64; 8];
        for x in run
            .samples
            .iter()
            .filter(|x| x.fractured && x.travel_since_fracture >= 2e-3)
        {
            let o = s.evaluate(
                c.xi,
                &CutState {
                    depth: x.depth,
                    height: c.height,
                    half_width: c.half_width,
                    fractured: true,
                    travel_since_fracture: x.travel_since_fracture,
                },
                &nominal,
            );
            let fnf = st * o.force_normal_parts.by_friction_stiffness;
            let ftf = st * o.force_tangential_parts.by_friction_stiffness;
            sum[0] += x.force_normal - x.force_normal_friction
                + c.xi * (x.force_tangential - x.force_tangential_friction)
                - t * r * s.material.fracture_toughness;
            sum[1] += o.strain;
            sum[2] += x.force_normal_friction;
            sum[3] += fnf;
            sum[4] += x.force_normal - x.force_normal_friction;
            sum[5] += o.force_normal - fnf;
            sum[6] += x.force_tangential_friction;
            sum[7] += ftf;
        }
        let n = run
            .samples
            .iter()
            .filter(|x| x.fractured && x.travel_since_fracture >= 2e-3)
            .count() as f64;
        println!(
            "{:.0}x{:.0} | {:.1} | {:.1} {:.1} | {:.3} {:.3} {:.3}",
            c.height * 1e3,
            c.half_width * 1e3,
            c.xi,
            sum[0] / n,
            sum[1] / n,
            sum[2] / sum[3],
            sum[4] / sum[5],
            sum[6] / sum[7],
        );
    }
}

/// The `profile` mode (module doc): [T, S, H, w, ξ].
fn friction_profile(s: &Surrogate, material: &Material, blade: &BladeSection, v: [f64; 5]) {
    let [t, st, height, half_width, xi] = v;
    let runs = run_sweep(
        &scaled_material(material, t, st),
        blade,
        &[SweepCase {
            xi,
            height,
            half_width,
        }],
        &SweepSettings::default(),
        1,
        &|| {},
    )
    .expect("sweep");
    let scale = ScaleFactors {
        toughness: t,
        stiffness: st,
        friction: 1.0,
    };
    let edges = [0.0, 0.5e-3, 2e-3, 4e-3, 8e-3, 12e-3, 16e-3, 1.0];
    let mut acc = [[0.0f64; 6]; 7];
    for x in run_samples(&runs[0]) {
        let k = edges
            .windows(2)
            .position(|e| x.travel_since_fracture < e[1])
            .unwrap_or(6);
        let o = s.evaluate(
            xi,
            &CutState {
                depth: x.depth,
                height,
                half_width,
                fractured: true,
                travel_since_fracture: x.travel_since_fracture,
            },
            &scale,
        );
        let fnf = st * o.force_normal_parts.by_friction_stiffness;
        acc[k][0] += x.force_normal_friction;
        acc[k][1] += fnf;
        acc[k][2] += x.force_normal - x.force_normal_friction;
        acc[k][3] += o.force_normal - fnf;
        acc[k][4] += x.crack_depth - x.depth;
        acc[k][5] += 1.0;
    }
    println!("s bin (mm) | Fn^f sec sur | Fn^c sec sur (N/m) | crack lead (mm) | n");
    for (k, a) in acc.iter().enumerate() {
        let n = a[5].max(1.0);
        println!(
            "[{:.1}, {:.1}) | {:.1} {:.1} | {:.1} {:.1} | {:.3} | {}",
            edges[k] * 1e3,
            edges[k + 1] * 1e3,
            a[0] / n,
            a[1] / n,
            a[2] / n,
            a[3] / n,
            a[4] / n * 1e3,
            a[5]
        );
    }
}

/// The fractured samples of a run.
fn run_samples(
    run: &shearcut_sim::surrogate::SweepRun,
) -> impl Iterator<Item = &shearcut_sim::surrogate::SweepSample> {
    run.samples.iter().filter(|x| x.fractured)
}
