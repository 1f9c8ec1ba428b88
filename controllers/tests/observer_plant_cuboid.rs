//! The observers against the plant's truth on the potato cuboid under the
//! straight edge (`loop-potato-cuboid`'s object): a flat top under a
//! straight edge, where the truth is exact: the edge touches at the top's
//! height, the whole 30 mm of edge over the piece enters at once, and the
//! force rises linearly with the indentation until the first fracture
//! drops it.

mod observer_support;

use observer_support::{Cut, first, noisy, quiet, travel_per_tick};
use shearcut_controllers::observer::{CutEstimate, CutTarget};
use shearcut_plant::PlantStep as Measurement;

/// Height of the cuboid's top, m (the straight edge lies at the knife
/// frame's y = 0, so the knife frame origin is at this height at the touch).
const TOP: f64 = 0.025;

/// Pressing at 20 mm/s: the touch after about 52 ticks, the first fracture
/// about 22 ticks later, 3 mm deep after about 230.
fn press(cut: &Cut, ticks: usize) -> Vec<Measurement> {
    cut.drive(0.0, 0.02, ticks)
}

fn estimates(cut: &Cut, ms: &[Measurement], target: CutTarget) -> Vec<CutEstimate> {
    let mut obs = cut.observer(target);
    ms.iter().map(|m| obs.observe(&m.reading)).collect()
}

#[test]
fn the_tare_finds_the_bias_and_the_noise_in_free_air() {
    let cut = Cut::potato_cuboid(noisy(0.5));
    let ms = press(&cut, 120);
    let mut obs = cut.observer(CutTarget::Depth(0.02));
    for m in &ms {
        obs.observe(&m.reading);
    }
    let tare = obs.tare();
    assert!(tare.frozen());
    let n = tare.samples() as f64;
    // 1 mm of clearance less the tare's 0.25 mm, crossed while ramping up
    // to 20 mm/s: over 30 samples.
    assert!(n >= 30.0, "{n} samples");
    // The bias within 4 standard errors (σ/√n) on each force axis.
    for (axis, bias) in [(0, -0.5), (1, 0.5), (2, -0.5)] {
        let err = tare.bias()[axis] - bias;
        assert!(err.abs() < 4.0 * 0.01 / n.sqrt(), "axis {axis}: {err}");
    }
    // σ̂ within 4 relative standard errors, 1/√(2(n − 1)) (13 % at n = 30).
    let ratio = tare.sigma()[1] / 0.01;
    assert!(
        (ratio - 1.0).abs() < 4.0 / (2.0 * (n - 1.0)).sqrt(),
        "σ̂/σ = {ratio}"
    );
}

#[test]
fn the_touch_is_back_dated_to_the_top() {
    for (sensor, tolerance) in [
        // Linear elasticity: the force is linear in the indentation until
        // the first fracture, so the fit's zero is the top to rounding.
        (quiet(), 1e-9),
        // Noise 0.01 N on two readings 0.32 N apart per 17 µm tick: the
        // zero moves by about 0.01/0.32 × 17 µm ≈ 0.5 µm per σ; 3 µm is
        // six of them.
        (noisy(0.5), 3e-6),
        (noisy(-0.5), 3e-6),
    ] {
        let cut = Cut::potato_cuboid(sensor);
        let ms = press(&cut, 120);
        let es = estimates(&cut, &ms, CutTarget::Depth(0.02));
        let truth = first(&ms, |m| m.truth.contact_length > 0.0).expect("touches");
        let detected = es.iter().position(|e| e.touch.is_some()).unwrap();
        let touch = es[detected].touch.unwrap();
        assert!(
            (touch.position.y - TOP).abs() < tolerance,
            "{:?}: touch at {} m",
            sensor.bias,
            touch.position.y
        );
        // The first tick in contact already reads 0.2 N (4 σ above 5 σ):
        // the second makes the run.
        assert_eq!(detected, truth + 1, "{:?}", sensor.bias);
        // Nothing touches before the edge reaches the top.
        assert!(es[..truth].iter().all(|e| e.touch.is_none()));
    }
}

#[test]
fn the_first_fracture_is_the_peak_before_the_drop() {
    for sensor in [quiet(), noisy(0.5)] {
        let cut = Cut::potato_cuboid(sensor);
        let ms = press(&cut, 140);
        let es = estimates(&cut, &ms, CutTarget::Depth(0.02));
        let truth = first(&ms, |m| m.truth.fractured_sections > 0).expect("fractures");
        let detected = es.iter().position(|e| e.fracture.is_some()).unwrap();
        let f = es[detected].fracture.unwrap();
        // The fracture's tick drops the force by about 30 %: detected on it.
        assert_eq!(detected, truth, "{:?}", sensor.bias);
        // The peak is the reading before it: the crack started within that
        // tick.
        assert_eq!(f.time, ms[truth - 1].reading.time);
        assert!(es[..truth].iter().all(|e| e.fracture.is_none()));
        // The peak force: R'_c = 150 N/m over 30 mm plus friction, 4.5–9 N.
        assert!((4.5..9.0).contains(&f.force), "{}", f.force);
    }
}

#[test]
fn edge_depth_contact_length_and_done_follow_the_truth() {
    let cut = Cut::potato_cuboid(noisy(0.5));
    let ms = press(&cut, 260);
    let es = estimates(&cut, &ms, CutTarget::Depth(3e-3));
    let step = travel_per_tick(&ms);
    // The truth's edge depth: the knife's travel below its height on the
    // first tick the plant reports edge in contact.
    let mut truth_touch: Option<f64> = None;
    let mut done = None;
    for (k, (m, e)) in ms.iter().zip(&es).enumerate() {
        let y = m.reading.position.y;
        if truth_touch.is_none() && m.truth.contact_length > 0.0 {
            truth_touch = Some(y);
        }
        let truth = truth_touch.map_or(0.0, |t| (t - y).max(0.0));
        if e.touch.is_some() && m.truth.contact_length > 0.0 {
            // The truth's depth counts from its first tick in contact, up
            // to a tick's travel below the top; the observer's from the
            // top itself (to 3 µm, above).
            let diff = e.edge_depth - truth;
            assert!((-3e-6..step + 3e-6).contains(&diff), "tick {k}: {diff} m");
            // The whole 30 mm of the piece is under the edge, to the
            // outline table's column (15 µm at each side).
            assert!(
                (e.contact_length - 0.03).abs() < 3e-5,
                "{}",
                e.contact_length
            );
            // The crack never lags the edge by more than the indentation
            // before the first fracture (0.4 mm).
            assert!(m.truth.crack_depth > e.edge_depth - 4e-4);
        }
        if e.done && done.is_none() {
            done = Some(k);
        }
    }
    let k = done.expect("3 mm reached");
    assert!(es[k].edge_depth >= 3e-3 && es[k - 1].edge_depth < 3e-3);
    // Done stays done.
    assert!(es[k..].iter().all(|e| e.done));
}

#[test]
fn the_same_readings_give_bit_identical_estimates() {
    let cut = Cut::potato_cuboid(noisy(0.5));
    let ms = press(&cut, 160);
    let a = estimates(&cut, &ms, CutTarget::Depth(2e-3));
    let b = estimates(&cut, &ms, CutTarget::Depth(2e-3));
    let bits = |e: &CutEstimate| {
        [
            e.normal_force,
            e.force_noise,
            e.edge_depth,
            e.contact_length,
            e.touch.map_or(0.0, |t| t.position.y),
            e.fracture.map_or(0.0, |f| f.time),
        ]
        .map(f64::to_bits)
    };
    assert!(a.iter().zip(&b).all(|(x, y)| bits(x) == bits(y)));
}
