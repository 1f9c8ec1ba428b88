//! `Plant::step` allocates nothing after construction in a run without
//! section re-choices (counting allocator): a straight edge pressing a
//! cuboid, whose segments move within their section planes. (A re-choice
//! cuts the object mesh with the new plane and may rebuild a section: those
//! ticks allocate, as `Plant`'s docs say.)

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use nalgebra::{Vector2, Vector3};
use shearcut_sim::geometry::TriangleMesh;
use shearcut_sim::plant::{ArmLimits, KnifeCommand, Plant, PlantSettings};
use shearcut_sim::{Knife, KnifePreset, MaterialPreset, SectionSettings};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// Forwards to the system allocator and counts allocations.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn plant_step_allocates_nothing() {
    let material = MaterialPreset::PotatoCuboid.material();
    let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
    let object = TriangleMesh::cuboid(
        Vector3::new(-0.015, 0.0, 0.0),
        Vector3::new(0.015, 0.02, 0.03),
    );
    let section = SectionSettings {
        row_spacing: 5e-4,
        ..SectionSettings::default()
    };
    let limits = ArmLimits {
        jerk: 1e15,
        acceleration: 1e9,
        ..ArmLimits::default()
    };
    let settings = PlantSettings {
        segments: 4,
        ..PlantSettings::default()
    };
    let mut plant = Plant::new(
        &material,
        &knife,
        &object,
        0.02,
        Vector2::new(0.0, -1.0),
        &settings,
        &section,
        &limits,
        1,
    )
    .unwrap();
    let cmd = KnifeCommand {
        velocity: Vector3::new(0.0, -0.00625, 0.0),
    };
    // Through contact, first fracture and steady cutting.
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let mut fractured = 0;
    for _ in 0..1500 {
        fractured = plant.step(&cmd, 1e-3).unwrap().fractured_sections;
    }
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    assert!(fractured > 0, "the run reached cutting");
    assert_eq!(after - before, 0, "Plant::step allocated");
    assert_eq!(
        plant.rechoices(),
        0,
        "a pressing straight edge re-chooses nothing"
    );
}
