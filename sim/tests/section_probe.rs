use shearcut_sim::*;
#[test]
#[ignore]
fn probe() {
    let g = SectionGeometry::rectangle(0.03, 0.03).unwrap();
    let m = MaterialPreset::PotatoCuboid.material();
    let b = BladeSection::default();
    let t = std::time::Instant::now();
    let mut cs = CrossSection::new(&g, &m, &b, &SectionSettings::default()).unwrap();
    eprintln!("new {:?} elems {} dofs {}", t.elapsed(), cs.element_count(), cs.condensed_dofs());
    for xi in [0.0, 0.33, 0.75, 1.8] {
        cs.reset();
        let t = std::time::Instant::now();
        let mut peak: f64 = 0.0;
        let mut first = None;
        let mut k = 0;
        while cs.state().knife_displacement < 0.02 && !cs.is_cut_through() {
            let s = cs.advance(6.25e-6, xi * 6.25e-6).unwrap();
            peak = peak.max(s.force_vertical);
            if s.fractured && first.is_none() { first = Some((s.knife_displacement, s.force_vertical)); }
            k += 1;
            if k % 400 == 0 {
                let w = s.work;
                eprintln!("xi {xi} d {:.4} Fn {:.1} Ft {:.1} wedge {:.1} fr {:.1} crack {:.4} ind {:.2e} W {:.3} frac {:.3} U {:.3} fric {:.3} bal {:.2e} tens {} {:?}", s.knife_displacement, s.force_vertical, s.force_tangential, s.force_vertical_wedge, s.force_vertical_friction, s.crack_depth, s.indentation, w.knife, w.fracture, w.strain_energy, w.friction, w.knife - w.fracture - w.strain_energy - w.friction - w.unstable, s.tensile_contacts, s.status);
            }
        }
        eprintln!("xi {xi}: steps {k} {:?}/step peak {peak:.1} first {first:?} work {:.3}", t.elapsed() / k, cs.state().work.knife);
    }
}
