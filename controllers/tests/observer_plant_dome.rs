//! The observers against the plant's truth on the half potato under the
//! chef's knife (`loop-potato-whole`'s object): a dome under a curved edge,
//! where the edge in contact grows from nothing at the crest, the force
//! rises from nothing, and one section of many fractures first.

mod observer_support;

use observer_support::{Cut, first, noisy, travel_per_tick};
use shearcut_controllers::observer::{CutEstimate, CutTarget};
use shearcut_plant::PlantStep as Measurement;

fn estimates(cut: &Cut, ms: &[Measurement]) -> Vec<CutEstimate> {
    let mut obs = cut.observer(CutTarget::Depth(0.025));
    ms.iter().map(|m| obs.observe(&m.reading)).collect()
}

/// Pressing at 20 mm/s for `ticks`: the touch after about 55 ticks, the
/// first fracture about 35 later.
fn press(cut: &Cut, ticks: usize) -> Vec<Measurement> {
    cut.drive(0.0, 0.02, ticks)
}

#[test]
fn the_touch_on_a_dome_is_never_before_the_truth_and_a_tick_after_at_most() {
    let cut = Cut::half_potato(noisy(0.5));
    let ms = press(&cut, 120);
    let es = estimates(&cut, &ms);
    let truth = first(&ms, |m| m.truth.contact_length > 0.0).expect("touches");
    let detected = es.iter().position(|e| e.touch.is_some()).unwrap();
    let touch = es[detected].touch.unwrap();
    // One segment at the crest: the force rises 0.05 N per tick, so the
    // 0.05 N threshold is passed on the second tick in contact and the run
    // completes on the third.
    assert!(detected <= truth + 3, "detected {detected}, truth {truth}");
    // The truth's contact began within the tick before its first tick in
    // contact. A convex rise's secant reaches zero after the true start,
    // so the back-dated touch is below the previous reading's height (the
    // noise moves it by about 0.01/0.05 of a 20 µm tick: 4 µm, ×2 allowed)
    // and above the first reading in contact plus one tick.
    let step = travel_per_tick(&ms);
    let y = touch.position.y;
    assert!(y <= ms[truth - 1].reading.position.y + 8e-6, "{y}");
    assert!(y >= ms[truth].reading.position.y - step, "{y}");
}

#[test]
fn the_first_fracture_on_a_dome_is_found_within_its_bound() {
    let cut = Cut::half_potato(noisy(0.5));
    let ms = press(&cut, 240);
    let es = estimates(&cut, &ms);
    let truth = first(&ms, |m| m.truth.fractured_sections > 0).expect("fractures");
    let detected = es.iter().position(|e| e.fracture.is_some()).unwrap();
    let f = es[detected].fracture.unwrap();
    // Never before the truth.
    assert!(detected >= truth, "detected {detected}, truth {truth}");
    // The first section's fracture drops the total by a few per cent at
    // most (on these coarse sections it is found on its own tick; on the
    // scenario's finer ones, 5 ticks late, at the next sections' drops:
    // docs/observers.md). The contract is the plateau rule's 1 mm of travel
    // past the peak, 50 ticks at 20 mm/s.
    let step = travel_per_tick(&ms);
    let bound = (1e-3 / step).ceil() as usize;
    assert!(detected - truth <= bound, "{} ticks late", detected - truth);
    // The peak is not after the detection and not before the truth's
    // previous tick.
    assert!(f.time >= ms[truth - 1].reading.time && f.time <= ms[detected].reading.time);
}

#[test]
fn the_contact_length_on_a_dome_follows_the_sections_in_contact() {
    let cut = Cut::half_potato(noisy(0.5));
    let ms = press(&cut, 320);
    let es = estimates(&cut, &ms);
    let mut errors: Vec<f64> = ms
        .iter()
        .zip(&es)
        .filter(|(m, e)| e.edge_depth > 2e-3 && m.truth.contact_length > 0.0)
        .map(|(m, e)| (e.contact_length - m.truth.contact_length) / m.truth.contact_length)
        .collect();
    assert!(errors.len() > 150, "{} ticks compared", errors.len());
    errors.sort_by(f64::total_cmp);
    let median = errors[errors.len() / 2];
    // The plant counts whole segments of 4.5 mm whose midpoints have
    // passed the surface; the edge inside the outline is continuous. A
    // segment at each end of the 40–55 mm in contact 2–5 mm deep is up to
    // ±11 % (measured: −8.7 % to +7.7 %); the rounding goes both ways, so
    // the median is near 0 (measured −0.7 %).
    assert!(median.abs() < 0.03, "median {median}");
    assert!(errors.iter().all(|e| e.abs() < 0.15), "{errors:?}");
}
