//! Steady-state cutting of a deep section without friction (DESIGN §3.2
//! "Checks that must hold", seed 000 §III.B–C).
//!
//! # What steady state must give
//! Seed 000 eq. (1) with the slicing toughness of eq. (6): dW = R_c^s ds + dU,
//! R_c^s = r(ξ,ν)·R_c. With the edge doing the cutting (DESIGN §3.2a) the
//! knife's work over a knife advance dn is dW = F_n dn + F_t dt = (F_n + ξF_t) dn.
//! In steady cutting of a deep section the field near the edge travels with
//! the tip unchanged, so dU → 0 and the crack advances with the knife, ds = dn.
//! Hence
//!
//! - work per unit cut area: dW/ds → r(ξ,ν)·R_c;
//! - F_n + ξ·F_t → r(ξ,ν)·R_c per unit length of edge.
//!
//! Eq. (6) also says r = (f_n^s/f_n^p)(1 + ξ·F_t/F_n) with the seed's split
//! F_t/F_n = ξ/(2(1+ν)), so F_n → R_c·2/(1+√(1+(ξ/(1−ν−2ν²))²)) only if the
//! FEM's split equals the seed's. We measure the split and test
//! F_n = r·R_c/(1 + ξ·split_measured) (DESIGN §3.2).
//!
//! Measured (potato E 2 MPa, ν 0.4, R_c 150 N/m, μ 0; razor blade; 80×40 mm
//! section; mean over knife displacement 10–25 mm):
//!
//! | ξ    | F_n+ξF_t − rR_c | work/area − rR_c | split FEM | seed ξ/(2(1+ν)) | F_n vs seed law |
//! |------|-----------------|------------------|-----------|-----------------|-----------------|
//! | 0    | +0.10 %         | −0.00 %          | 0         | 0               | +0.1 %          |
//! | 0.33 | +0.09 %         | −0.14 %          | 0.127     | 0.118 (+7 %)    | −0.2 %          |
//! | 0.75 | +0.09 %         | −0.01 %          | 0.236     | 0.268 (−12 %)   | +2.1 %          |
//! | 1.8  | +0.13 %         | +0.22 %          | 0.364     | 0.643 (−43 %)   | +30 %           |
//!
//! The FEM's split falls increasingly short of the seed's at high ξ (the
//! ratio split/ξ is 0.38, 0.31, 0.20 for ξ = 0.33, 0.75, 1.8, against the
//! seed's constant 1/(2(1+ν)) = 0.357): the half-plane stiffness ratio k_t/k_n
//! of a strip is (1−ν) rather than G/E, and in this model the antiplane drag
//! rides on an indentation that shrinks as r(ξ,ν)·R_c falls; which of the two
//! dominates is not separated here. So F_n exceeds the seed's law by 30 % at
//! ξ = 1.8 while the energy statement holds to 0.25 %.

use shearcut_sim::mechanics::{force_ratio, normal_force_ratio, toughness_ratio};
use shearcut_sim::{BladeSection, CrossSection, MaterialPreset, SectionGeometry, SectionSettings};

/// Knife step, m: 1/10 of the row spacing, so means over the window average
/// the sawtooth of the tip crossing rows (the window holds 75 rows).
const DN: f64 = 2e-5;

struct Steady {
    f_n: f64,
    f_t: f64,
    work_per_area: f64,
    strain_energy_rate: f64,
}

/// Cuts a deep, wide potato section with a razor-like blade, no friction,
/// and averages over knife displacements in (10, 25] mm.
fn steady(cs: &mut CrossSection, xi: f64) -> Steady {
    cs.reset();
    let (lo, hi) = (0.010, 0.025);
    let (mut n, mut f_n, mut f_t) = (0.0, 0.0, 0.0);
    let mut first = None;
    while cs.state().knife_displacement < hi - 1e-12 {
        let s = cs.advance(DN, xi * DN).unwrap();
        assert!(!cs.is_cut_through());
        if s.knife_displacement > lo {
            first.get_or_insert(s);
            n += 1.0;
            f_n += s.force_vertical;
            f_t += s.force_tangential;
        }
    }
    let (a, b) = (first.unwrap(), *cs.state());
    let da = b.crack_depth - a.crack_depth;
    Steady {
        f_n: f_n / n,
        f_t: f_t / n,
        work_per_area: (b.work.knife - a.work.knife) / da,
        strain_energy_rate: (b.work.strain_energy - a.work.strain_energy) / da,
    }
}

#[test]
fn frictionless_steady_cutting_costs_r_times_toughness() {
    let mut m = MaterialPreset::PotatoCuboid.material();
    m.friction_coefficient = 0.0;
    let (nu, rc) = (m.poisson_ratio, m.fracture_toughness);
    // Razor-like blade (thickness 1.2 × edge width): with the default 2 mm
    // blade the wedge splits the crack ahead of the edge and the edge stops
    // doing the cutting, which is not the regime of seed 000 eq. (6).
    let blade = BladeSection {
        thickness: 1.2e-4,
        bevel_angle: 15f64.to_radians(),
        edge_width: 1e-4,
    };
    // 80 mm wide, 40 mm deep: the window ends 15 mm above the board, i.e.
    // 150 edge widths, and the side walls are 40 mm away.
    let g = SectionGeometry::rectangle(0.08, 0.04).unwrap();
    let mut cs = CrossSection::new(&g, &m, &blade, &SectionSettings::default()).unwrap();
    let mut last_split = 0.0;
    for xi in [0.0, 0.33, 0.75, 1.8] {
        let s = steady(&mut cs, xi);
        let target = toughness_ratio(xi, nu) * rc;
        let split = s.f_t / s.f_n;
        let seed_split = force_ratio(xi, nu);
        let seed_law = normal_force_ratio(xi, nu) * rc;
        let with_split = target / (1.0 + xi * split);
        eprintln!(
            "xi {xi}: Fn {:.2} Ft {:.2} N/m; Fn+xiFt {:.2} vs rRc {target:.2} ({:+.3}%); work/area {:.2} ({:+.3}%); dU/da {:.3}; split {split:.4} vs seed {seed_split:.4} ({:+.1}%); Fn vs law with measured split {with_split:.2} ({:+.3}%), vs seed law {seed_law:.2} ({:+.1}%)",
            s.f_n,
            s.f_t,
            s.f_n + xi * s.f_t,
            100.0 * (s.f_n + xi * s.f_t - target) / target,
            s.work_per_area,
            100.0 * (s.work_per_area - target) / target,
            s.strain_energy_rate,
            100.0 * (split - seed_split) / seed_split.max(1e-300),
            100.0 * (s.f_n - with_split) / with_split,
            100.0 * (s.f_n - seed_law) / seed_law,
        );
        // Work per unit cut area is r·R_c + dU/da exactly (every cutting step
        // balances R = r·R_c to 1e-7); dU/da is the drift of the stored
        // energy (≈ 0.015 J/m in all) as the tip nears the board, bounded by
        // U/Δa ≈ 1 % of R_c, so 1 % is the tolerance.
        assert!(
            s.strain_energy_rate.abs() <= 0.01 * target,
            "xi {xi}: dU/da {}",
            s.strain_energy_rate
        );
        assert!(
            (s.work_per_area - target).abs() <= 0.01 * target,
            "xi {xi}: work per area {} vs r·R_c {target}",
            s.work_per_area
        );
        // The mean force: the same balance read per step, plus the sampling
        // error of the sawtooth (force rises while the tip sits on a row and
        // drops when it crosses one; 75 teeth in the window): 1 %.
        assert!(
            (s.f_n + xi * s.f_t - target).abs() <= 0.01 * target,
            "xi {xi}: Fn + xi Ft = {} vs r·R_c {target}",
            s.f_n + xi * s.f_t
        );
        // DESIGN §3.2: F_n against the seed's law with the measured split
        // (the same 1 %: it is the balance above divided by 1 + ξ·split).
        assert!(
            (s.f_n - with_split).abs() <= 0.01 * with_split,
            "xi {xi}: Fn {} vs {with_split}",
            s.f_n
        );
        // The horizontal/vertical ratio is not ξ (seed 000 §V.A), and the
        // split grows with ξ.
        if xi > 0.0 {
            assert!(split < 0.5 * xi, "xi {xi}: split {split}");
            assert!(split > last_split, "xi {xi}: split {split} <= {last_split}");
        }
        last_split = split;
    }
}
