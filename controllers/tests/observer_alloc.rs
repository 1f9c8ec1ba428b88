//! Proves that `CutObserver::observe` allocates nothing after construction,
//! with a counting global allocator (its own test binary), through free
//! air, the touch, the first fracture and the target.

use std::sync::atomic::Ordering;

use nalgebra::{Vector2, Vector3};
use shearcut_controllers::observer::{CutObserver, CutObserverSettings, CutTarget};
use shearcut_sim::arm::{ArmReading, ArmStatus};
use shearcut_sim::geometry::Polygon;
use shearcut_sim::{Knife, KnifePreset};

#[path = "support/counting_allocator.rs"]
mod counting_allocator;

use counting_allocator::{ALLOCATIONS, Counting, TRACK};

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn observing_allocates_nothing() {
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    // A 30 mm block 25 mm high, 20 mm from the heel.
    let outline = Polygon::new(vec![
        Vector2::new(0.0, 0.0),
        Vector2::new(0.03, 0.0),
        Vector2::new(0.03, 0.025),
        Vector2::new(0.0, 0.025),
    ]);
    let mut obs = CutObserver::new(
        &knife,
        &outline,
        CutTarget::Depth(2e-3),
        &CutObserverSettings::default(),
    )
    .unwrap();
    // A spring of 0.3 N per 20 µm tick that breaks to 70 % at 0.3 mm, with
    // a bias and a deterministic ±0.01 N ripple.
    let reading = |k: usize| {
        let y = 0.026 - 20e-6 * k as f64;
        let indentation = (0.025 - y).max(0.0);
        let mut f = indentation / 20e-6 * 0.3;
        if indentation > 3e-4 {
            f *= 0.7;
        }
        let ripple = if k.is_multiple_of(2) { 0.01 } else { -0.01 };
        ArmReading {
            time: k as f64 * 1e-3,
            position: Vector3::new(0.0, y, -0.02),
            velocity: Vector3::new(0.0, -0.02, 0.0),
            wrench: [0.1, 0.5 + f + ripple, 0.0, 0.0, 0.0, 0.0],
            status: ArmStatus::Moving,
        }
    };
    ALLOCATIONS.store(0, Ordering::SeqCst);
    TRACK.with(|t| t.set(true));
    let mut last = None;
    for k in 0..200 {
        last = Some(obs.observe(&reading(k)));
    }
    TRACK.with(|t| t.set(false));
    assert_eq!(ALLOCATIONS.load(Ordering::SeqCst), 0);
    // The run went through every phase.
    let e = last.unwrap();
    assert!(e.touch.is_some() && e.fracture.is_some() && e.done);
}
