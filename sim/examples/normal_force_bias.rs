//! Diagnostic: the surrogate's mean post-fracture forces against the section
//! model's (sums over the fractured samples with travel since fracture
//! ≥ 2 mm, section over surrogate, nominal factors, cut to 80 % of the
//! height), split into the friction and non-friction parts.
//!
//! `cargo run --release -p shearcut-sim --example normal_force_bias --
//! [SURROGATE.toml] [MATERIAL]` (defaults: the shipped potato-cuboid-straight
//! surrogate and `potato-cuboid`).

use shearcut_sim::surrogate::{
    CutState, ScaleFactors, Surrogate, SweepCase, SweepSettings, run_sweep,
};
use shearcut_sim::{KnifePreset, MaterialPreset};

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
