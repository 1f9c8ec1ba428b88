//! Moving cross sections under a tough skin: a re-chosen section takes over
//! the cut with the knife where it is (seed 000 §IV, Fig. 4(b)), so a flank
//! section re-chosen every few millimetres still builds up the indentation
//! its first fracture needs (R'_c, seed 000 eqs. 1 and 6) and fractures.
//!
//! Regression test of the whole-eggplant anomaly: the successors used to
//! restart with the edge at the crack tip, throwing the indentation away at
//! every re-choice; slicing steeply enough that the sections were re-chosen
//! before their edges reached the ~8 mm of indentation the eggplant's skin
//! needs, flank sections never fractured while the knife went on through
//! them, and the mean crack depth lagged the knife by tens of millimetres.

use nalgebra::Vector3;
use shearcut_plant::{KnifeCommand, Plant, PlantSettings, PlantSpec};
use shearcut_sim::{
    BladeSection, CrossSection, Knife, KnifePreset, MaterialPreset, ObjectShape, SectionGeometry,
};

#[path = "support/cutting_rig.rs"]
mod cutting_rig;

// Coarse rows keep the test fast in debug builds; the comparison with the
// standalone section below uses the same settings.
use cutting_rig::{LOOSE, coarse_section};

/// Knife travel below the top at which a standalone section of the object's
/// full height and length, pressed at slice-push ratio `xi`, first fractures
/// (its edge never leaves its plane): the pre-fracture indentation scale.
fn first_fracture_indentation(height: f64, length: f64, xi: f64) -> f64 {
    let material = MaterialPreset::EggplantWhole.material();
    let geometry = SectionGeometry::rectangle(length, height).unwrap();
    let mut s = CrossSection::new(
        &geometry,
        &material,
        &BladeSection::default(),
        &coarse_section(),
    )
    .unwrap();
    let step = 2e-5;
    for _ in 0..2000 {
        let st = s.advance(step, xi * step).unwrap();
        if st.fractured {
            return st.knife_displacement;
        }
    }
    panic!("the standalone section never fractured");
}

#[test]
fn sections_under_a_tough_skin_fracture_across_rechoices() {
    // A small eggplant (tough skin: R'_c = 650 N/m over R_c = 260 N/m) under
    // the chef's knife, slicing at ξ = 0.5: the segments slide 1 mm off
    // their planes every ~2 mm of travel.
    let (length, diameter, flat) = (0.1, 0.04, 0.003);
    let object = ObjectShape::Eggplant {
        length,
        diameter,
        flat,
    }
    .mesh()
    .unwrap();
    let height = diameter - flat;
    let material = MaterialPreset::EggplantWhole.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let xi: f64 = 0.5;
    let d = Plant::direction_at(xi);
    let limits = LOOSE;
    let settings = PlantSettings {
        segments: 4,
        ..PlantSettings::default()
    };
    let mut plant = Plant::new(
        PlantSpec {
            material: &material,
            knife: &knife,
            object: &object,
            z0: 0.03,
            direction: d,
            settings: &settings,
            section: &coarse_section(),
            arm_limits: &limits,
        },
        0,
    )
    .unwrap();
    let d_first = first_fracture_indentation(height, length, xi);
    // The standalone section needs millimetres of indentation, more than
    // the ~2 mm of travel between re-choices: the old failure's condition.
    assert!(d_first > 3e-3, "pre-fracture indentation {d_first}");

    let speed = 0.02;
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, d.y, d.x) * speed,
    };
    let dt = 1e-3;
    let mut max_deformation: f64 = 0.0;
    let mut worst_edge_depth_unfractured: f64 = 0.0;
    let mut prev_work = 0.0;
    // 1.3 s: 26 mm of travel along d, the edge ~23 mm below the top.
    for k in 0..1300 {
        let m = plant.step(&cmd, dt).unwrap();
        assert!(m.truth.work >= prev_work, "tick {k}: work dropped");
        prev_work = m.truth.work;
        max_deformation = max_deformation.max(m.truth.deformation);
        let position = plant.position();
        for ((segment, plane, active), st) in plant.section_planes().zip(plant.section_states()) {
            if !active || st.knife_displacement <= 0.0 {
                continue;
            }
            // The real edge's height on the section's plane (the knife only
            // goes down here: no lift).
            let mid = position + Vector3::new(0.0, segment.midpoint.y, segment.midpoint.x);
            let edge = (mid - plane.origin).dot(&plane.v_axis);
            let top = st.crack_tip_height + st.crack_depth;
            // The section's edge is the real edge, re-choices included (a
            // micrometre for the round-off of the plane transforms).
            if edge <= top {
                assert!(
                    (st.edge_height - edge).abs() < 1e-6,
                    "tick {k}: section edge {} vs the knife's {edge} (plane at z = {})",
                    st.edge_height,
                    plane.origin.z
                );
            }
            if !st.fractured {
                worst_edge_depth_unfractured = worst_edge_depth_unfractured.max(top - edge);
            }
        }
    }
    // Every section the edge went deeper into than the pre-fracture
    // indentation scale (with a 50 % margin for the sections' different
    // shapes) has fractured.
    assert!(
        worst_edge_depth_unfractured < 1.5 * d_first,
        "an unfractured section with the edge {worst_edge_depth_unfractured} m below its top \
         (pre-fracture indentation {d_first} m)"
    );
    // The deformation next to the blade stays on that scale too.
    assert!(
        max_deformation < 1.5 * d_first,
        "deformation {max_deformation} m vs pre-fracture indentation {d_first} m"
    );
    assert!(plant.rebuilds() > 0, "the sections were re-chosen");
    let states: Vec<_> = plant.section_states().copied().collect();
    assert!(
        states.iter().all(|s| s.fractured),
        "every section fractured: {:?}",
        states.iter().map(|s| s.fractured).collect::<Vec<_>>()
    );
}
