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
    CutState, FIT_SECTION_SIZES, HELD_OUT_SECTION_SIZES, ScaleFactors, Surrogate, SurrogateOutput,
    SweepCase, SweepRun, SweepSample, SweepSettings, ToughnessRatio, grid, run_sweep,
    scaled_material,
};
use shearcut_sim::{BladeSection, KnifePreset, Material, MaterialPreset};

/// Travel since fracture from which a run's fractured samples are in the
/// settled sawtooth (the window the accuracy report averages), m.
const SETTLED_TRAVEL: f64 = 2e-3;

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
    let numbers = || -> Vec<f64> {
        args[4..]
            .iter()
            .map(|a| a.parse().expect("a number"))
            .collect()
    };
    match args.get(3).map(String::as_str) {
        Some("scaled") => {
            let pairs = numbers();
            let factors: Vec<(f64, f64)> = if pairs.is_empty() {
                vec![(1.0, 1.0), (0.7, 1.3), (1.3, 0.7)]
            } else {
                pairs.chunks(2).map(|p| (p[0], p[1])).collect()
            };
            scaled_bias(&s, &material, &blade, &factors);
        }
        Some("profile") => {
            let v = numbers();
            friction_profile(&s, &material, &blade, [v[0], v[1], v[2], v[3], v[4]]);
        }
        Some("sizes") => {
            let f = numbers();
            let (t, st) = if f.len() == 2 {
                (f[0], f[1])
            } else {
                (1.0, 1.0)
            };
            size_levels(&s, &material, &blade, t, st);
        }
        _ => nominal_bias(&s, &material, &blade),
    }
}

/// The default mode (module doc): at nominal factors on the fit size
/// 30 × 15 mm and the cuboid's 25 × 15 mm, the energy rates, the
/// strain-energy rate by travel since fracture, and the window ratios of the
/// forces and their friction and non-friction parts.
fn nominal_bias(s: &Surrogate, material: &Material, blade: &BladeSection) {
    let xis = [0.0, 0.3, 0.6, 1.0, 2.5];
    let sizes = [(0.03, 0.015), (0.025, 0.015)];
    let runs = sweep(material, blade, &grid(&xis, &sizes));
    let nominal = ScaleFactors::default();
    energy_rates(s, &runs);
    for run in &runs {
        let c = run.case;
        let r = toughness_ratio(s, c.xi);
        let mut acc = [[0.0f64; 3]; 4];
        for x in fractured_samples(run) {
            let k = match x.travel_since_fracture {
                t if t < 0.5e-3 => 0,
                t if t < 2e-3 => 1,
                t if t < 8e-3 => 2,
                _ => 3,
            };
            let o = surrogate_at(s, &c, x, &nominal);
            let sec = section_work_less_friction(x, c.xi) - r * s.material.fracture_toughness;
            acc[k][0] += sec;
            acc[k][1] += o.strain;
            acc[k][2] += 1.0;
        }
        let t: Vec<String> = acc
            .iter()
            .map(|a| format!("{:.1}/{:.1} (n {})", a[0] / a[2], a[1] / a[2], a[2]))
            .collect();
        println!(
            "{} {:.1} U sec/sur by s in [0,0.5) [0.5,2) [2,8) [8,..) mm: {}",
            size_mm(&c),
            c.xi,
            t.join("  ")
        );
    }
    println!(
        "size_mm xi | Fn Ft W (section/surrogate) | Fn^f Ft^f | Fn^c Ft^c Wc | Ft^f/Fn^f sec sur"
    );
    for run in &runs {
        let c = run.case;
        let sum = settled_sums(s, run, &nominal, |x, o| {
            let (fnf, ftf) = surrogate_friction(o, 1.0);
            let sec = [
                x.force_normal,
                x.force_tangential,
                x.force_normal + c.xi * x.force_tangential,
                x.force_normal_friction,
                x.force_tangential_friction,
                x.force_normal - x.force_normal_friction,
                x.force_tangential - x.force_tangential_friction,
                section_work_less_friction(x, c.xi),
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
            (sec, sur)
        });
        let q = sum_ratios(&sum);
        println!(
            "{} {:.1} | {} {} {} | {} {} | {} {} {} | {:.3} {:.3} | Fn sec {:.1} sur {:.1} fric sec {:.1} sur {:.1} N/m-sum",
            size_mm(&c),
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
fn energy_rates(s: &Surrogate, runs: &[SweepRun]) {
    println!(
        "size xi | dW/dd dWfr/dd (r·Rc) dU/dd dWf/dd | mean Fn^c+xiFt^c, Fn^c, Ft^c, Ft^f/Fn^f | sur U mean, sur Fn^c, Ft^c | crack-depth lead"
    );
    let nominal = ScaleFactors::default();
    for run in runs {
        let c = run.case;
        let w: Vec<_> = settled_samples(run).collect();
        let (a, z) = (w[0], w[w.len() - 1]);
        let dd = z.depth - a.depth;
        let r = toughness_ratio(s, c.xi);
        let n = w.len() as f64;
        let mean = |f: &dyn Fn(&SweepSample) -> f64| w.iter().map(|x| f(x)).sum::<f64>() / n;
        let wc = mean(&|x| section_work_less_friction(x, c.xi));
        let fnc = mean(&|x| x.force_normal - x.force_normal_friction);
        let ftc = mean(&|x| x.force_tangential - x.force_tangential_friction);
        let mut sur = [0.0; 3];
        for x in &w {
            let o = surrogate_at(s, &c, x, &nominal);
            sur[0] += o.strain / n;
            sur[1] += (o.force_normal - o.force_normal_parts.by_friction_stiffness) / n;
            sur[2] += (o.force_tangential - o.force_tangential_parts.by_friction_stiffness) / n;
        }
        if c.xi == 0.0 || c.xi == 1.0 {
            let mut line = String::new();
            for k in (0..w.len()).step_by(w.len() / 6) {
                let (p, q) = (w[k], w[(k + w.len() / 6).min(w.len() - 1)]);
                if q.depth > p.depth {
                    let o = surrogate_after_fracture(
                        s,
                        &c,
                        0.5 * (p.depth + q.depth),
                        0.5 * (p.travel_since_fracture + q.travel_since_fracture),
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
            "{} {:.1} | {:.1} {:.1} ({:.1}) {:.1} {:.1} | {:.1} {:.1} {:.2} | {:.1} {:.1} {:.2} | lead {:.3} mm",
            size_mm(&c),
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
        let runs = sweep(
            &scaled_material(material, t, st),
            blade,
            &grid(&xis, &sizes),
        );
        let scale = toughness_and_stiffness(t, st);
        for run in &runs {
            let c = run.case;
            let sum = settled_sums(s, run, &scale, |x, o| {
                let (fnf, ftf) = surrogate_friction(o, st);
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
                (sec, sur)
            });
            println!(
                "{} | {t} {st} | {:.1} | {}",
                size_mm(&c),
                c.xi,
                sum_ratios(&sum).join(" ")
            );
        }
    }
}

/// The `sizes` mode (module doc).
fn size_levels(s: &Surrogate, material: &Material, blade: &BladeSection, t: f64, st: f64) {
    // The plants' sizes: the potato cuboid's, the half potato's other two.
    let plants = [(0.025, 0.015), (0.035, 0.03), (0.015, 0.01)];
    let sizes: Vec<(f64, f64)> = FIT_SECTION_SIZES
        .iter()
        .chain(&HELD_OUT_SECTION_SIZES)
        .chain(&plants)
        .copied()
        .collect();
    let xis = [0.3, 0.6, 1.0];
    let runs = sweep(
        &scaled_material(material, t, st),
        blade,
        &grid(&xis, &sizes),
    );
    let scale = toughness_and_stiffness(t, st);
    println!("T {t} S {st}: H x w mm | xi | U sec sur (N/m) | Fn^f Fn^c Ft^f (section/surrogate)");
    for run in &runs {
        let c = run.case;
        let r = toughness_ratio(s, c.xi);
        // [U̇, F_n^f, F_n^c, F_t^f]
        let sum = settled_sums(s, run, &scale, |x, o| {
            let (fnf, ftf) = surrogate_friction(o, st);
            let sec = [
                section_work_less_friction(x, c.xi) - t * r * s.material.fracture_toughness,
                x.force_normal_friction,
                x.force_normal - x.force_normal_friction,
                x.force_tangential_friction,
            ];
            let sur = [o.strain, fnf, o.force_normal - fnf, ftf];
            (sec, sur)
        });
        let n = settled_samples(run).count() as f64;
        println!(
            "{} | {:.1} | {:.1} {:.1} | {:.3} {:.3} {:.3}",
            size_mm(&c),
            c.xi,
            sum[0][0] / n,
            sum[1][0] / n,
            sum[0][1] / sum[1][1],
            sum[0][2] / sum[1][2],
            sum[0][3] / sum[1][3],
        );
    }
}

/// The `profile` mode (module doc): [T, S, H, w, ξ].
fn friction_profile(s: &Surrogate, material: &Material, blade: &BladeSection, v: [f64; 5]) {
    let [t, st, height, half_width, xi] = v;
    let case = SweepCase {
        xi,
        height,
        half_width,
    };
    let runs = sweep(&scaled_material(material, t, st), blade, &[case]);
    let scale = toughness_and_stiffness(t, st);
    let edges = [0.0, 0.5e-3, 2e-3, 4e-3, 8e-3, 12e-3, 16e-3, 1.0];
    let mut acc = [[0.0f64; 6]; 7];
    for x in fractured_samples(&runs[0]) {
        let k = edges
            .windows(2)
            .position(|e| x.travel_since_fracture < e[1])
            .unwrap_or(6);
        let o = surrogate_at(s, &case, x, &scale);
        let (fnf, _) = surrogate_friction(&o, st);
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

/// The section model's runs of `cases` on `material` (default stepping, two
/// threads).
fn sweep(material: &Material, blade: &BladeSection, cases: &[SweepCase]) -> Vec<SweepRun> {
    run_sweep(material, blade, cases, &SweepSettings::default(), 2, &|| {}).expect("sweep")
}

/// The surrogate's scale factors for R_c, R'_c × `toughness` and
/// E × `stiffness` at the nominal friction.
fn toughness_and_stiffness(toughness: f64, stiffness: f64) -> ScaleFactors {
    ScaleFactors {
        toughness,
        stiffness,
        friction: 1.0,
    }
}

/// The fractured samples of a run.
fn fractured_samples(run: &SweepRun) -> impl Iterator<Item = &SweepSample> {
    run.samples.iter().filter(|x| x.fractured)
}

/// The settled window of a run: its fractured samples at least
/// `SETTLED_TRAVEL` past the onset.
fn settled_samples(run: &SweepRun) -> impl Iterator<Item = &SweepSample> {
    fractured_samples(run).filter(|x| x.travel_since_fracture >= SETTLED_TRAVEL)
}

/// The surrogate after fracture on a case's section (its ξ, height and half
/// width) at a knife depth and travel since fracture.
fn surrogate_after_fracture(
    s: &Surrogate,
    case: &SweepCase,
    depth: f64,
    travel_since_fracture: f64,
    scale: &ScaleFactors,
) -> SurrogateOutput {
    let state = CutState {
        depth,
        height: case.height,
        half_width: case.half_width,
        fractured: true,
        travel_since_fracture,
    };
    s.evaluate(case.xi, &state, scale)
}

/// The surrogate at a fractured sample of a case's run.
fn surrogate_at(
    s: &Surrogate,
    case: &SweepCase,
    x: &SweepSample,
    scale: &ScaleFactors,
) -> SurrogateOutput {
    surrogate_after_fracture(s, case, x.depth, x.travel_since_fracture, scale)
}

/// The surrogate's friction parts of F_n and F_t at the stiffness factor
/// `stiffness` (friction factor 1).
fn surrogate_friction(o: &SurrogateOutput, stiffness: f64) -> (f64, f64) {
    (
        stiffness * o.force_normal_parts.by_friction_stiffness,
        stiffness * o.force_tangential_parts.by_friction_stiffness,
    )
}

/// The section's knife work per depth less friction at a sample,
/// F_n^c + ξ·F_t^c.
fn section_work_less_friction(x: &SweepSample, xi: f64) -> f64 {
    x.force_normal - x.force_normal_friction
        + xi * (x.force_tangential - x.force_tangential_friction)
}

/// The toughness ratio r(ξ, ν) on the surrogate's material.
fn toughness_ratio(s: &Surrogate, xi: f64) -> f64 {
    ToughnessRatio::at(xi, s.material.poisson_ratio).value
}

/// Sums over a run's settled window of the section's quantities and the
/// surrogate's counterparts at `scale`, as `[section, surrogate]`;
/// `quantities` gives both at a sample.
fn settled_sums<const N: usize>(
    s: &Surrogate,
    run: &SweepRun,
    scale: &ScaleFactors,
    quantities: impl Fn(&SweepSample, &SurrogateOutput) -> ([f64; N], [f64; N]),
) -> [[f64; N]; 2] {
    let mut sum = [[0.0f64; N]; 2];
    for x in settled_samples(run) {
        let (sec, sur) = quantities(x, &surrogate_at(s, &run.case, x, scale));
        for k in 0..N {
            sum[0][k] += sec[k];
            sum[1][k] += sur[k];
        }
    }
    sum
}

/// Each section sum over the surrogate's, to three decimals.
fn sum_ratios<const N: usize>(sum: &[[f64; N]; 2]) -> Vec<String> {
    (0..N)
        .map(|k| format!("{:.3}", sum[0][k] / sum[1][k]))
        .collect()
}

/// A case's section, height × half width in mm (`HxW`).
fn size_mm(c: &SweepCase) -> String {
    format!("{:.0}x{:.0}", c.height * 1e3, c.half_width * 1e3)
}
