//! The whole-knife plant: multi-section sums, torques, curved-edge pressing,
//! arm limits and determinism.

use nalgebra::{Vector2, Vector3};
use shearcut_plant::{
    ArmLimits, ArmStatus, KnifeCommand, LimitViolation, Plant, PlantSettings, PlantSpec,
    SuccessorPolicy,
};
use shearcut_sim::geometry::TriangleMesh;
use shearcut_sim::{CrossSection, Knife, KnifePreset, MaterialPreset, SectionGeometry};

#[path = "support/cutting_rig.rs"]
mod cutting_rig;

use cutting_rig::{LOOSE, coarse_section, cuboid, half_potato, noise_free};

#[allow(clippy::too_many_arguments)]
fn plant(
    material: &shearcut_sim::Material,
    knife: &Knife,
    object: &TriangleMesh,
    z0: f64,
    direction: Vector2<f64>,
    s: &PlantSettings,
    limits: &ArmLimits,
    seed: u64,
) -> Plant {
    Plant::new(
        PlantSpec {
            material,
            knife,
            object,
            z0,
            direction,
            settings: s,
            section: &coarse_section(),
            arm_limits: limits,
        },
        seed,
    )
    .unwrap()
}

const DT: f64 = 1e-3;
const SPEED: f64 = 0.00625;

#[test]
fn straight_edge_plant_is_one_section_times_the_length() {
    let material = MaterialPreset::PotatoCuboid.material();
    let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
    let (w, h, l) = (0.03, 0.02, 0.03);
    let s = noise_free(3);
    let mut plant = plant(
        &material,
        &knife,
        &cuboid(w, h, l),
        0.02,
        Vector2::new(0.0, -1.0),
        &s,
        &LOOSE,
        0,
    );
    let geometry = SectionGeometry::rectangle(w, h).unwrap();
    let mut single =
        CrossSection::new(&geometry, &material, knife.blade(), &coarse_section()).unwrap();
    // The edge starts start_gap = 1 mm above the top.
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, -SPEED, 0.0),
    };
    let ticks_to_touch = (1e-3 / (SPEED * DT)).round() as usize;
    let mut compared = 0;
    for k in 0..ticks_to_touch + 800 {
        let m = plant.step(&cmd, DT).unwrap();
        if k + 1 > ticks_to_touch {
            let st = single.advance(SPEED * DT, 0.0).unwrap();
            // Same model, same increments: equal to rounding of the sums.
            let expect = st.force_vertical * l;
            assert!(
                (m.truth.wrench.force.y - expect).abs() <= 1e-9 * expect.abs().max(1e-9),
                "tick {k}: {} vs {expect}",
                m.truth.wrench.force.y
            );
            assert!(
                (m.truth.work - st.work.knife * l).abs() <= 1e-9 * (st.work.knife * l).max(1e-12)
            );
            // A flat top under a straight edge: the depth below the top is
            // the section's crack depth.
            assert!(
                (m.truth.crack_depth - st.crack_depth).abs() <= 1e-12,
                "tick {k}: depth {} vs {}",
                m.truth.crack_depth,
                st.crack_depth
            );
            compared += 1;
        } else {
            assert_eq!(m.truth.wrench.force.norm(), 0.0, "no force before contact");
        }
    }
    assert_eq!(compared, 800);
}

#[test]
fn torque_is_the_moment_of_the_section_forces() {
    let material = MaterialPreset::PotatoCuboid.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let s = noise_free(6);
    let mut plant = plant(
        &material,
        &knife,
        &cuboid(0.03, 0.02, 0.03),
        0.11,
        Vector2::new(0.0, -1.0),
        &s,
        &LOOSE,
        0,
    );
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, -SPEED, 0.0),
    };
    let mut m = plant.step(&cmd, DT).unwrap();
    for _ in 0..900 {
        m = plant.step(&cmd, DT).unwrap();
    }
    assert!(m.truth.contact_length > 0.0);
    // Independent moment: each section's force per length × segment length,
    // applied at its midpoint, about the sensor.
    let sensor = plant.position() + knife.sensor_position();
    let (mut force, mut torque) = (Vector3::zeros(), Vector3::zeros());
    for (seg, st) in plant.segments().zip(plant.section_states()) {
        if st.knife_displacement <= 0.0 {
            continue;
        }
        let n = Vector3::new(0.0, seg.normal.y, seg.normal.x);
        let t = Vector3::new(0.0, seg.tangent.y, seg.tangent.x);
        // Moving straight down, the segment slides along t by −t_y per unit
        // descent; the tangential force resists that sliding.
        let slide = -seg.tangent.y;
        let f = (-n * st.force_vertical - t * slide.signum() * st.force_tangential) * seg.length;
        let r = plant.position() + Vector3::new(0.0, seg.midpoint.y, seg.midpoint.x) - sensor;
        force += f;
        torque += Vector3::new(
            r.y * f.z - r.z * f.y,
            r.z * f.x - r.x * f.z,
            r.x * f.y - r.y * f.x,
        );
    }
    let w = m.truth.wrench;
    assert!((w.force - force).norm() <= 1e-12 * force.norm());
    assert!((w.torque - torque).norm() <= 1e-12 * torque.norm());
    // Everything lies in the knife plane x = 0: no F_x, and the torque is about x only.
    assert_eq!(w.force.x, 0.0);
    assert_eq!((w.torque.y, w.torque.z), (0.0, 0.0));
    // A curved edge pressing down pushes the knife up and towards the heel.
    assert!(w.force.y > 0.0 && w.force.z < 0.0, "{:?}", w.force);
}

/// Presses a potato cuboid with the chef's knife at z₀ and returns (the
/// displacement at which the whole arc touches, F_y after 1 mm of contact).
fn curved_pressing(z0: f64) -> (f64, f64) {
    let material = MaterialPreset::PotatoCuboid.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let s = PlantSettings {
        start_gap: 0.0,
        ..noise_free(10)
    };
    let mut plant = plant(
        &material,
        &knife,
        &cuboid(0.03, 0.025, 0.03),
        z0,
        Vector2::new(0.0, -1.0),
        &s,
        &LOOSE,
        0,
    );
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, -SPEED, 0.0),
    };
    let total: f64 = plant.edge_segments().iter().map(|s| s.length).sum();
    let mut full = None;
    let mut f_at_1mm = 0.0;
    for k in 1..=2400 {
        let m = plant.step(&cmd, DT).unwrap();
        let d = k as f64 * SPEED * DT;
        if full.is_none() && m.truth.contact_length >= total - 1e-12 {
            full = Some(d);
        }
        if k == 160 {
            f_at_1mm = m.truth.wrench.force.y;
        }
    }
    (full.unwrap_or(f64::INFINITY), f_at_1mm)
}

#[test]
fn curved_edge_pressing_later_contact_lower_initial_slope() {
    // Seed 000 §V.B: the further the piece from the heel, the more the edge
    // curves over it: full contact comes later and the force rises slower.
    let (full_near, f_near) = curved_pressing(0.02);
    let (full_far, f_far) = curved_pressing(0.14);
    assert!(
        full_near < 1e-5,
        "flat part of the edge: immediate full contact ({full_near})"
    );
    assert!(
        full_far > 1e-3,
        "curved part: full contact after millimetres ({full_far})"
    );
    assert!(f_far < 0.8 * f_near, "initial slope: {f_far} vs {f_near}");
}

#[test]
fn arm_limits_refuse_a_velocity_step() {
    let material = MaterialPreset::PotatoCuboid.material();
    let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
    let s = noise_free(1);
    let mut plant = plant(
        &material,
        &knife,
        &cuboid(0.03, 0.02, 0.03),
        0.02,
        Vector2::new(0.0, -1.0),
        &s,
        &ArmLimits::default(),
        0,
    );
    let start = plant.position();
    // 0 → 6.25 mm/s in one millisecond: jerk 6250 m/s³ > 4500 (FR3).
    let m = plant
        .step(
            &KnifeCommand {
                velocity: Vector3::new(0.0, -SPEED, 0.0),
            },
            DT,
        )
        .unwrap();
    assert!(matches!(
        m.reading.status,
        ArmStatus::LimitViolation(LimitViolation::Jerk(_))
    ));
    assert_eq!(
        plant.position(),
        start,
        "a refused command does not move the knife"
    );
    // Half the step is within the limits.
    let m = plant
        .step(
            &KnifeCommand {
                velocity: Vector3::new(0.0, -0.003, 0.0),
            },
            DT,
        )
        .unwrap();
    assert_eq!(m.reading.status, ArmStatus::Moving);
}

#[test]
fn same_seed_gives_bit_identical_measurements() {
    let material = MaterialPreset::PotatoWhole.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let mut s = noise_free(4);
    s.sensor = Default::default();
    let object = half_potato();
    let dir = Vector2::new(-0.5, -1.0);
    let run = || {
        let mut plant = plant(&material, &knife, &object, 0.05, dir, &s, &LOOSE, 42);
        let cmd = KnifeCommand {
            velocity: Vector3::new(0.0, -SPEED, -0.5 * SPEED),
        };
        (0..600)
            .map(|_| plant.step(&cmd, DT).unwrap().reading.wrench)
            .collect::<Vec<_>>()
    };
    let (a, b) = (run(), run());
    assert!(
        a.iter()
            .flatten()
            .zip(b.iter().flatten())
            .all(|(x, y)| x.to_bits() == y.to_bits())
    );
    // The noise is real: not all zero.
    assert!(a.iter().any(|w| w[0] != 0.0));
}

/// |n × t| for every section: the plane's normal against its segment's
/// tangent (both unit, world frame).
fn worst_normal_misalignment(plant: &Plant) -> f64 {
    plant
        .section_planes()
        .map(|(segment, plane, _)| plane.normal().cross(&segment.world_frame().0).norm())
        .fold(0.0, f64::max)
}

#[test]
fn slicing_straight_edge_moves_sections_along_the_cuboid() {
    // Straight edge slicing a cuboid at ξ = 1 (45°): every segment's midpoint
    // slides along z, 1 mm per 1 mm of depth, so its section is re-chosen
    // through the crack front every 1 mm of slide (seed 000 §IV's 1 mm
    // steps); in a cuboid the shape is the same, so only the plane moves (no
    // rebuild), and the sections whose planes leave the piece's far end go
    // inactive.
    let material = MaterialPreset::PotatoCuboid.material();
    let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
    let (w, h, l) = (0.03, 0.01, 0.04);
    let s = noise_free(8);
    let mut plant = plant(
        &material,
        &knife,
        &cuboid(w, h, l),
        // The heel over the piece's near end: every midpoint's path enters
        // through the flat top (a path entering through the near face gives
        // its segment a section only later, see the near-face test).
        0.0,
        Vector2::new(1.0, -1.0),
        &s,
        &LOOSE,
        0,
    );
    let geometry = SectionGeometry::rectangle(w, h).unwrap();
    let mut single =
        CrossSection::new(&geometry, &material, knife.blade(), &coarse_section()).unwrap();
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, -SPEED, SPEED),
    };
    let seg_len = plant.segments().map(|s| s.length).fold(0.0, f64::max);
    let ticks_to_touch = (1e-3 / (SPEED * DT)).round() as usize;
    let mut last_rechoices = 0;
    let mut front_checks = 0;
    let mut went_inactive = false;
    for k in 0..1600 {
        let m = plant.step(&cmd, DT).unwrap();
        // Sections stay normal to their segments (a rotation of the plane
        // would show at 1e-16; 1e-12 leaves room for rounding only).
        assert!(worst_normal_misalignment(&plant) < 1e-12, "tick {k}");
        if k < ticks_to_touch {
            assert_eq!(m.truth.contact_length, 0.0);
            continue;
        }
        // The section model advanced by each segment's increments: dn = dt =
        // SPEED·DT (n = −y, t = +z of the straight edge).
        let st = single.advance(SPEED * DT, SPEED * DT).unwrap();
        // Every segment entered through the flat top at the same tick and
        // keeps its section when re-chosen (same rectangle), so the plant is
        // the single section × the contact length to rounding of the sums.
        let expect = st.force_vertical * m.truth.contact_length;
        assert!(
            (m.truth.wrench.force.y - expect).abs() <= 1e-9 * expect.abs().max(1e-9),
            "tick {k}: {} vs {expect}",
            m.truth.wrench.force.y
        );
        // Sliding off the far end deactivates. The plane is re-chosen through
        // q, the crack front on the midpoint's path (which may lead or trail
        // the midpoint by the edge's indentation or the crack's lead, under
        // 1 mm here): an inactive section's plane z = q_z is past the piece's
        // end (the cut misses), with its midpoint within 1 mm of the end or
        // beyond; an active one's midpoint is over the piece to within one
        // re-choice distance, one tick's travel and that 1 mm.
        let x = plant.position().z;
        for (segment, plane, active) in plant.section_planes() {
            let z = x + segment.midpoint.x;
            if active {
                assert!(
                    z <= l + s.update_distance + SPEED * DT + 1e-3,
                    "tick {k}: z {z}"
                );
            } else {
                assert!(plane.origin.z >= l, "tick {k}: plane at {}", plane.origin.z);
                assert!(z > l - 1e-3, "tick {k}: inactive over the piece at z {z}");
                went_inactive = true;
            }
        }
        assert!(m.truth.contact_length <= l + seg_len + 1e-12);
        // The crack front fitted at a re-choice passes through the tips it was
        // fitted over: a flat front for a straight edge (equal tips).
        if plant.rechoices() > last_rechoices {
            last_rechoices = plant.rechoices();
            let front = plant.crack_front().unwrap();
            for tip in plant.crack_tips() {
                assert!(
                    (front.height_at(tip.x) - tip.y).abs() < 1e-12,
                    "tick {k}: front {} vs tip {}",
                    front.height_at(tip.x),
                    tip.y
                );
                assert!(front.slope_at(tip.x).abs() < 1e-9);
            }
            front_checks += 1;
        }
    }
    assert!(front_checks >= 5, "re-choices every 1 mm: {front_checks}");
    assert!(went_inactive, "the tip-side sections slid off the piece");
    assert_eq!(plant.rebuilds(), 0, "a cuboid's sections are never rebuilt");
    assert_eq!(
        plant.woken_segments(),
        0,
        "every segment entered through the top"
    );
    assert_eq!(plant.first_contacts(), plant.segments().count());
}

#[test]
fn the_depth_on_a_dome_is_below_its_top_and_does_not_fall_as_sections_enter() {
    // The chef's knife pressing the half potato: sections enter contact on
    // the flanks all the way down, each with no crack. The sections' mean
    // crack depth falls each time; the crack front's depth below the top
    // does not, and it follows the knife.
    let material = MaterialPreset::PotatoWhole.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let s = noise_free(10);
    let mut plant = plant(
        &material,
        &knife,
        &half_potato(),
        0.02,
        Vector2::new(0.0, -1.0),
        &s,
        &LOOSE,
        0,
    );
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, -4.0 * SPEED, 0.0),
    };
    let (mut depth, mut mean) = (0.0f64, 0.0f64);
    let (mut depth_drop, mut mean_drop) = (0.0f64, 0.0f64);
    let mut travel = 0.0;
    for _ in 0..900 {
        let m = plant.step(&cmd, DT).unwrap();
        travel += 4.0 * SPEED * DT;
        let cracks: Vec<f64> = plant.section_states().map(|st| st.crack_depth).collect();
        let now_mean = cracks.iter().sum::<f64>() / cracks.len() as f64;
        depth_drop = depth_drop.max(depth - m.truth.crack_depth);
        mean_drop = mean_drop.max(mean - now_mean);
        depth = depth.max(m.truth.crack_depth);
        mean = mean.max(now_mean);
    }
    // The sections' mean crack depth falls by over a millimetre (1.4 mm
    // when measured) as sections enter; the front's depth by a fifth of a
    // millimetre at most (0.19 mm: a re-chosen section's tip).
    assert!(mean_drop > 1e-3, "sections' mean fell by {mean_drop} m");
    assert!(depth_drop < 0.25e-3, "depth fell by {depth_drop} m");
    // It follows the knife: its lowest point started 1 mm above the top
    // and is 21.5 mm below it now; the front is within a millimetre of it
    // (0.28 mm shallower when measured: the edge rises towards the tip),
    // while the sections' mean crack depth lags by 6.5 mm.
    let edge = travel - s.start_gap;
    assert!(
        (depth - edge).abs() < 1e-3,
        "depth {depth} m, edge {edge} m"
    );
    assert!(edge - mean > 5e-3, "sections' mean {mean} m");
}

#[test]
fn half_potato_sections_are_rebuilt_work_never_drops_deterministic() {
    let material = MaterialPreset::PotatoWhole.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let s = noise_free(4);
    let object = half_potato();
    let dir = Vector2::new(-0.5, -1.0);
    let run = || {
        let mut plant = plant(&material, &knife, &object, 0.05, dir, &s, &LOOSE, 7);
        let cmd = KnifeCommand {
            velocity: Vector3::new(0.0, -SPEED, -0.5 * SPEED),
        };
        let mut prev = 0.0;
        let mut rechoices = 0;
        let out: Vec<_> = (0..1500)
            .map(|k| {
                let m = plant.step(&cmd, DT).unwrap();
                // Rebuilds keep the predecessor's work: never a drop.
                assert!(
                    m.truth.work >= prev,
                    "tick {k}: work {} < {prev}",
                    m.truth.work
                );
                prev = m.truth.work;
                assert!(worst_normal_misalignment(&plant) < 1e-12, "tick {k}");
                // Right after a re-choice every tip is on the fitted front:
                // kept sections' tips are fitted exactly (at most three, a
                // quadratic), rebuilt ones restart at q, on the front. 1e-9 m
                // allows the round-off of the plane transforms.
                if plant.rechoices() > rechoices {
                    rechoices = plant.rechoices();
                    let front = plant.crack_front().unwrap();
                    let tips: Vec<_> = plant.crack_tips().collect();
                    assert!(tips.len() <= 3);
                    for t in tips {
                        let miss = (front.height_at(t.x) - t.y).abs();
                        assert!(miss < 1e-9, "tick {k}: tip off the front by {miss}");
                    }
                }
                m
            })
            .collect();
        (out, plant.rechoices(), plant.rebuilds())
    };
    let (a, rechoices, rebuilds) = run();
    assert!(
        rebuilds > 0,
        "the potato's sections change shape: {rebuilds}"
    );
    assert!(rechoices >= rebuilds);
    assert!(a.last().unwrap().truth.work > 0.0);
    let (b, ..) = run();
    let bits = |m: &shearcut_plant::PlantStep| {
        let mut v: Vec<u64> = m.reading.wrench.iter().map(|x| x.to_bits()).collect();
        v.extend(
            [
                m.truth.work,
                m.truth.crack_depth,
                m.truth.contact_length,
                m.truth.deformation,
            ]
            .iter()
            .map(|x| x.to_bits()),
        );
        v
    };
    assert!(a.iter().zip(&b).all(|(x, y)| bits(x) == bits(y)));
}

#[test]
fn update_distance_must_be_positive() {
    assert_eq!(PlantSettings::default().update_distance, 1e-3);
    assert!(PlantSettings::default().validate().is_ok());
    for bad in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let s = PlantSettings {
            update_distance: bad,
            ..PlantSettings::default()
        };
        let e = s.validate().unwrap_err().to_string();
        assert!(e.contains("update_distance"), "{e}");
    }
}

#[test]
fn steep_slice_gives_near_face_segments_their_sections() {
    // α = 45° into a cuboid with the heel 2 cm before its near face: the
    // tip-side midpoints' paths enter through the flat top and get fresh
    // sections as they arrive; the heel-side ones enter through the near
    // face (min z), below the top, and get theirs through the crack front
    // when they reach the material. The contact then spans the whole piece,
    // and a segment still without a section is not over the piece.
    let material = MaterialPreset::PotatoCuboid.material();
    let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
    let (w, h, l) = (0.03, 0.03, 0.03);
    let alpha: f64 = 45f64.to_radians();
    let d = Vector2::new(alpha.sin(), -alpha.cos());
    let mut plant = plant(
        &material,
        &knife,
        &cuboid(w, h, l),
        0.02,
        d,
        &noise_free(10),
        &LOOSE,
        0,
    );
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, d.y, d.x) * SPEED,
    };
    let seg_len = plant
        .edge_segments()
        .iter()
        .map(|s| s.length)
        .fold(0.0, f64::max);
    let mut prev_work = 0.0;
    let mut m = plant.step(&cmd, DT).unwrap();
    // 4.2 s: the edge about 19 mm deep, every midpoint over the piece past
    // the near face.
    for k in 0..4200 {
        m = plant.step(&cmd, DT).unwrap();
        assert!(m.truth.work >= prev_work, "tick {k}");
        prev_work = m.truth.work;
        assert!(worst_normal_misalignment(&plant) < 1e-12, "tick {k}");
    }
    assert!(m.truth.crack_depth > 0.005 && m.truth.crack_depth < h - 1e-3);
    assert!(
        plant.woken_segments() >= 2,
        "near-face segments placed behind the front: {}",
        plant.woken_segments()
    );
    assert!(plant.first_contacts() >= 2, "{}", plant.first_contacts());
    let sectioned: Vec<f64> = plant.segments().map(|s| s.s_start).collect();
    assert_eq!(
        sectioned.len(),
        plant.woken_segments() + plant.first_contacts()
    );
    let x = plant.position().z;
    for s in plant.edge_segments() {
        let z = x + s.midpoint.x;
        if !sectioned.contains(&s.s_start) {
            assert!(
                !(0.0..=l).contains(&z),
                "a segment over the piece (z = {z}) has no section"
            );
        }
    }
    assert!(
        (m.truth.contact_length - l).abs() <= seg_len,
        "contact {} vs piece length {l} (segment {seg_len})",
        m.truth.contact_length
    );
    // A straight edge cuts a cuboid the same way everywhere: the sections
    // placed behind the front took over their neighbours' cut (crack, edge,
    // first fracture, drag), so every active section is in the same state.
    let active: Vec<f64> = plant
        .section_planes()
        .zip(plant.section_states())
        .filter(|((_, _, active), _)| *active)
        .map(|(_, st)| st.force_vertical)
        .collect();
    assert!(active.len() >= 5, "{active:?}");
    let (lo, hi) = active
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), f| (a.min(*f), b.max(*f)));
    assert!(hi - lo <= 1e-9 * hi, "active sections' forces {active:?}");
}

#[test]
fn slice_angle_changing_mid_cut_moves_sections_along_the_executed_path() {
    // A closed loop turns the knife: pressing (α = 0) into a half potato,
    // then slicing towards the heel at α = 30°, then backing out along that
    // line. Re-choices follow the executed direction, the successors are
    // foreseen on the side the segments slide to (also after the reversal),
    // the sections stay normal to their segments, and the work never drops.
    let material = MaterialPreset::PotatoWhole.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let object = half_potato();
    let mut plant = plant(
        &material,
        &knife,
        &object,
        0.05,
        Vector2::new(0.0, -1.0),
        &noise_free(4),
        &LOOSE,
        3,
    );
    let alpha: f64 = 30f64.to_radians();
    let turned = Vector2::new(-alpha.sin(), -alpha.cos());
    let mut prev_work = 0.0;
    let mut rechoices_after_turn = 0;
    let mut unforeseen_before_reversal = 0;
    for k in 0..3000 {
        let u = if k < 1200 {
            Vector2::new(0.0, -1.0)
        } else if k < 2400 {
            turned
        } else {
            -turned
        };
        let cmd = KnifeCommand {
            velocity: Vector3::new(0.0, u.y, u.x) * SPEED,
        };
        let before = plant.rechoices();
        if k == 2400 {
            unforeseen_before_reversal = plant.unforeseen_rechoices();
        }
        let m = plant.step(&cmd, DT).unwrap();
        assert_eq!(m.reading.status, ArmStatus::Moving);
        assert!(
            m.truth.work >= prev_work,
            "tick {k}: work {} < {prev_work}",
            m.truth.work
        );
        prev_work = m.truth.work;
        assert!(worst_normal_misalignment(&plant) < 1e-12, "tick {k}");
        assert!((plant.direction_of_motion() - u).norm() < 1e-12, "tick {k}");
        if (1200..2400).contains(&k) {
            rechoices_after_turn += plant.rechoices() - before;
        }
    }
    assert!(
        rechoices_after_turn > 0,
        "the turned knife slides its segments off their planes"
    );
    assert!(prev_work > 0.0);
    // Backing out, the segments slide back over their planes and on to the
    // other side: those successors are re-ordered in time, none waits.
    assert_eq!(plant.unforeseen_rechoices(), unforeseen_before_reversal);
}

#[test]
fn a_clone_with_pending_successors_runs_on_bit_identically() {
    // Mid-cut the plant has successors ordered from its worker thread; a
    // clone starts its own worker with the same jobs, and the two then step
    // to the same bits (the successors are functions of their jobs, not of
    // thread timing).
    let material = MaterialPreset::PotatoWhole.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let object = half_potato();
    let mut a = plant(
        &material,
        &knife,
        &object,
        0.05,
        Vector2::new(-0.5, -1.0),
        &noise_free(4),
        &LOOSE,
        5,
    );
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, -SPEED, -0.5 * SPEED),
    };
    for _ in 0..700 {
        a.step(&cmd, DT).unwrap();
    }
    let mut b = a.clone();
    let rebuilds = a.rebuilds();
    for k in 0..800 {
        let (ma, mb) = (a.step(&cmd, DT).unwrap(), b.step(&cmd, DT).unwrap());
        assert_eq!(ma, mb, "tick {k}");
    }
    assert!(
        a.rebuilds() > rebuilds,
        "successors were adopted after the clone"
    );
    assert_eq!(a.rebuilds(), b.rebuilds());
}

#[test]
fn start_position_is_where_the_plant_puts_the_knife() {
    // The loop's controller process takes the start from
    // `Plant::start_position` without building a plant: it must be the
    // plant's own start exactly (the iceoryx2 loop is bit-identical).
    let material = MaterialPreset::PotatoCuboid.material();
    for (preset, z0, gap) in [
        (KnifePreset::Chef, 0.0765, 0.002),
        (KnifePreset::Straight, 0.02, 0.0),
    ] {
        let knife = Knife::new(&preset.settings()).unwrap();
        let object = cuboid(0.03, 0.025, 0.03);
        let s = PlantSettings {
            start_gap: gap,
            ..noise_free(4)
        };
        let p = plant(
            &material,
            &knife,
            &object,
            z0,
            Vector2::new(0.0, -1.0),
            &s,
            &LOOSE,
            0,
        );
        assert_eq!(
            Plant::start_position(&knife, &object, z0, gap),
            p.position()
        );
    }
}

#[test]
fn sections_go_where_the_edge_arrives_whatever_the_planned_direction() {
    // Slicing a half potato towards the heel at ξ = 0.582 with the plant
    // planned for that direction, for pressing, or for ξ = 1.5 towards the
    // tip: the sections are placed where each segment's midpoint really
    // reaches the material, so the three plants agree to rounding (their
    // first planes are computed from different points of the same line).
    let material = MaterialPreset::PotatoWhole.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let object = half_potato();
    let xi: f64 = 0.582;
    let u = Vector2::new(-xi, -1.0).normalize();
    // A reach that covers every plan's arc: the three grids are the same.
    let s = PlantSettings {
        reach: 0.05,
        ..noise_free(8)
    };
    let run = |planned: Vector2<f64>| {
        let mut plant = plant(&material, &knife, &object, 0.05, planned, &s, &LOOSE, 3);
        let cmd = KnifeCommand {
            velocity: Vector3::new(0.0, u.y, u.x) * SPEED,
        };
        let last = (0..2400).map(|_| plant.step(&cmd, DT).unwrap()).last();
        (
            last.unwrap(),
            plant.first_contacts(),
            plant.edge_segments().len(),
        )
    };
    let (a, contacts_a, grid_a) = run(u);
    assert!(a.truth.crack_depth > 0.005, "{}", a.truth.crack_depth);
    for planned in [Vector2::new(0.0, -1.0), Vector2::new(1.5, -1.0).normalize()] {
        let (b, contacts_b, grid_b) = run(planned);
        assert_eq!(grid_a, grid_b);
        assert_eq!(contacts_a, contacts_b);
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1e-12);
        assert!(
            close(a.truth.work, b.truth.work),
            "work {} vs {}",
            a.truth.work,
            b.truth.work
        );
        assert!(
            close(a.truth.wrench.force.y, b.truth.wrench.force.y),
            "F_y {} vs {}",
            a.truth.wrench.force.y,
            b.truth.wrench.force.y
        );
        assert!(close(a.truth.crack_depth, b.truth.crack_depth));
    }
}

#[test]
fn first_orders_for_a_direction_the_knife_does_not_take_are_never_built() {
    // A plant planned for pressing whose knife slices at ξ = 0.582: every
    // first order is renewed on the first tick (the edge meets the top
    // 0.6 mm further along), before the worker has started any of them, so
    // no section is built for nothing; a plant asked to build its orders
    // before the first tick (as a real-time loop does) builds them, and the
    // renewals drop them.
    let material = MaterialPreset::PotatoWhole.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let object = half_potato();
    let u = Vector2::new(-0.582, -1.0).normalize();
    let s = noise_free(8);
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, u.y, u.x) * SPEED,
    };
    let down = Vector2::new(0.0, -1.0);
    let mut lazy = plant(&material, &knife, &object, 0.05, down, &s, &LOOSE, 3);
    let mut eager = plant(&material, &knife, &object, 0.05, down, &s, &LOOSE, 3);
    eager.build_ordered_sections();
    let a = lazy.step(&cmd, DT).unwrap();
    let b = eager.step(&cmd, DT).unwrap();
    assert_eq!(lazy.wasted_builds(), 0);
    assert!(eager.wasted_builds() > 0, "{}", eager.wasted_builds());
    assert_eq!(a.truth.work.to_bits(), b.truth.work.to_bits());
}

/// A chef's knife over the half potato, planned to slice along (z, y) =
/// (−0.5, −1), 6 segments, a noise-free sensor, `workers` worker threads.
fn half_potato_slice(workers: usize) -> Plant {
    half_potato_slice_with(&PlantSettings {
        workers,
        ..noise_free(6)
    })
}

/// The chef's knife over the half potato, the plant's settings `s`.
fn half_potato_slice_with(s: &PlantSettings) -> Plant {
    plant(
        &MaterialPreset::PotatoWhole.material(),
        &Knife::new(&KnifePreset::Chef.settings()).unwrap(),
        &half_potato(),
        0.05,
        Vector2::new(-0.5, -1.0),
        s,
        &LOOSE,
        1,
    )
}

#[test]
fn the_number_of_worker_threads_changes_nothing_but_the_waits() {
    // Sections are built by however many worker threads; each is a function
    // of its order alone, taken at a deterministic tick: one or three
    // workers step to the same bits. Zero workers are refused.
    let run = |workers: usize| {
        let mut plant = half_potato_slice(workers);
        let cmd = KnifeCommand {
            velocity: Vector3::new(0.0, -SPEED, -0.5 * SPEED),
        };
        let out: Vec<_> = (0..1200).map(|_| plant.step(&cmd, DT).unwrap()).collect();
        (out, plant.rebuilds())
    };
    let (a, rebuilds) = run(1);
    let (b, _) = run(3);
    assert!(rebuilds > 0);
    assert_eq!(a, b);
    let bad = PlantSettings {
        workers: 0,
        ..PlantSettings::default()
    };
    let e = bad.validate().unwrap_err().to_string();
    assert!(e.contains("workers") && e.contains('0'), "{e}");
}

#[test]
fn the_number_of_stepping_threads_changes_nothing() {
    // A tick's sections advance independently, so advancing them on one,
    // two or three threads (and after a restart of the helpers) steps to
    // the same bits, sawing included; zero threads are refused.
    let run = |threads: usize, restart: bool| {
        let mut plant = half_potato_slice_with(&PlantSettings {
            stepping_threads: threads,
            ..noise_free(6)
        });
        assert_eq!(plant.stepping_threads(), threads);
        if restart {
            plant.restart_stepping_threads();
            assert_eq!(plant.stepping_threads(), threads);
        }
        let stroke = |sign: f64| KnifeCommand {
            velocity: Vector3::new(0.0, -SPEED, -0.5 * sign * SPEED),
        };
        let out: Vec<_> = (0..1600)
            .map(|k| {
                plant
                    .step(&stroke(if k < 1200 { 1.0 } else { -1.0 }), DT)
                    .unwrap()
            })
            .collect();
        (out, plant.rebuilds())
    };
    let (one, rebuilds) = run(1, false);
    assert!(rebuilds > 0);
    assert!(one.last().unwrap().truth.crack_depth > 0.0);
    assert_eq!(one, run(2, false).0);
    assert_eq!(one, run(3, true).0);
    let bad = PlantSettings {
        stepping_threads: 0,
        ..PlantSettings::default()
    };
    let e = bad.validate().unwrap_err().to_string();
    assert!(e.contains("stepping_threads") && e.contains('0'), "{e}");
}

#[test]
fn a_step_measured_then_settled_is_the_step() {
    // The measurement does not depend on the re-choices after it, so
    // answering first and settling later (or at the next step) steps to the
    // same bits as `step`, re-choices and rebuilds included.
    let run = |how: u8| {
        let mut plant = half_potato_slice(1);
        let cmd = KnifeCommand {
            velocity: Vector3::new(0.0, -SPEED, -0.5 * SPEED),
        };
        let out: Vec<_> = (0..1200)
            .map(|_| match how {
                0 => plant.step(&cmd, DT).unwrap(),
                1 => {
                    let m = plant.step_measured(&cmd, DT).unwrap();
                    plant.settle().unwrap();
                    m
                }
                _ => plant.step_measured(&cmd, DT).unwrap(),
            })
            .collect();
        plant.settle().unwrap();
        (out, plant.rechoices(), plant.rebuilds())
    };
    let stepped = run(0);
    assert!(stepped.2 > 0);
    assert_eq!(stepped, run(1));
    assert_eq!(stepped, run(2));
}

#[test]
fn sawing_back_over_a_side_face_re_enters_behind_the_current_front() {
    // A straight edge slices a cuboid towards its tip (ξ = 0.5), so the
    // segments at the far face slide off the piece, then saws back: they
    // re-enter through that face while the rest of the edge has cut on.
    // Their sections must take up the cut where it is now (the current
    // front, the neighbours' state), not where it was when they left: a
    // stale, shallower crack put the edge over a millimetre below the tip,
    // whose unstable run then cut the section through to the board, and
    // that tip dragged the fitted front down for the segments after it.
    let material = MaterialPreset::PotatoCuboid.material();
    let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
    let (w, h, l) = (0.03, 0.025, 0.03);
    let s = PlantSettings {
        reach: 0.006,
        ..noise_free(10)
    };
    let xi = 0.5;
    let mut plant = plant(
        &material,
        &knife,
        &cuboid(w, h, l),
        0.02,
        Vector2::new(xi, -1.0).normalize(),
        &s,
        &LOOSE,
        0,
    );
    let stroke = |sign: f64| KnifeCommand {
        velocity: Vector3::new(0.0, -1.0, sign * xi) * SPEED,
    };
    let mut m = plant.step(&stroke(1.0), DT).unwrap();
    // Down 6.25 mm with 3.1 mm of stroke, then as far down while sawing
    // back.
    for k in 0..2000 {
        m = plant
            .step(&stroke(if k < 1000 { 1.0 } else { -1.0 }), DT)
            .unwrap();
        let depths: Vec<f64> = plant
            .section_planes()
            .zip(plant.section_states())
            .filter(|((_, _, active), st)| *active && st.knife_displacement > 0.0)
            .map(|(_, st)| st.crack_depth)
            .collect();
        let (lo, hi) = depths
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), d| (a.min(*d), b.max(*d)));
        // Sections cut the same piece with the same edge: their cracks
        // differ by the crack's discrete jumps (two rows of this mesh).
        assert!(
            hi - lo <= 1.0e-3,
            "tick {k}: active crack depths {depths:?}"
        );
    }
    assert!(
        m.truth.crack_depth > 0.010 && m.truth.crack_depth < 0.0135,
        "{}",
        m.truth.crack_depth
    );
}

#[test]
fn keep_current_never_waits_for_a_successor_and_takes_it_later() {
    // Ticks issued back to back at 16 times the cutting speed (an update
    // distance every 10 ticks) step far faster than the single worker
    // builds a section, so successors are due before they are built. Under
    // `Wait` (the default) the tick waits and nothing is deferred; under
    // `KeepCurrent` no tick waits, the due successors are deferred, and
    // once the knife holds still every deferred successor is taken: the
    // same segments have sections as in the waiting run.
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, -16.0 * SPEED, -8.0 * SPEED),
    };
    let run = |policy: Option<SuccessorPolicy>| {
        let mut plant = half_potato_slice(1);
        if let Some(p) = policy {
            // As a real-time plant starts: its first sections built.
            plant.set_successor_policy(p);
            plant.build_ordered_sections();
        }
        let mut prev = 0.0;
        for k in 0..250 {
            let m = plant.step(&cmd, DT).unwrap();
            assert!(m.truth.work >= prev, "tick {k}: work dropped");
            prev = m.truth.work;
        }
        plant
    };
    let waiting = run(None);
    assert_eq!(waiting.successor_policy(), SuccessorPolicy::Wait);
    assert_eq!(waiting.successor_deferrals(), 0);
    let mut keeping = run(Some(SuccessorPolicy::KeepCurrent));
    assert_eq!(keeping.successor_waits(), 0);
    assert!(keeping.successor_deferrals() > 0);
    // Hold still until a tick defers nothing: every due successor is taken
    // (the worker finishes them; the loop's bound, 100 s, only guards a
    // hang). A sleep between ticks leaves the workers a core.
    let still = KnifeCommand::default();
    let mut settled = false;
    for _ in 0..500_000 {
        let before = keeping.successor_deferrals();
        keeping.step(&still, DT).unwrap();
        if keeping.successor_deferrals() == before {
            settled = true;
            break;
        }
        std::thread::sleep(std::time::Duration::from_micros(200));
    }
    assert!(settled);
    assert_eq!(keeping.successor_waits(), 0);
    assert!(keeping.rebuilds() > 0);
    assert_eq!(keeping.dormant_segments(), waiting.dormant_segments());
}
