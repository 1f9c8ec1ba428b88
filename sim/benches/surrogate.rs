//! One surrogate evaluation with all outputs and ξ-derivatives (DESIGN §3.4:
//! well under 1 µs), before and after fracture.

use std::hint::black_box;
use std::path::PathBuf;

use criterion::{Criterion, criterion_main};
use shearcut_sim::surrogate::{CutState, ScaleFactors, Surrogate};

fn bench(c: &mut Criterion) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../config/surrogates/potato-cuboid-straight.toml");
    let s = Surrogate::from_path(&path).expect("shipped surrogate");
    let scale = ScaleFactors {
        toughness: 1.1,
        stiffness: 0.95,
        friction: 1.2,
    };
    let after = CutState {
        depth: 0.012,
        height: 0.03,
        half_width: 0.015,
        fractured: true,
        travel_since_fracture: 0.0118,
    };
    let before = CutState {
        depth: 2e-4,
        fractured: false,
        travel_since_fracture: 0.0,
        ..after
    };
    c.bench_function("surrogate evaluate, after fracture", |b| {
        b.iter(|| s.evaluate(black_box(0.75), black_box(&after), black_box(&scale)))
    });
    c.bench_function("surrogate evaluate, before fracture", |b| {
        b.iter(|| s.evaluate(black_box(0.75), black_box(&before), black_box(&scale)))
    });
    // Whole eggplant in its catch-up after the crack's jump (the knee gate
    // and the catch-up terms active, with their ξ-jets).
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../config/surrogates/eggplant-whole-straight.toml");
    let e = Surrogate::from_path(&path).expect("shipped surrogate");
    let catching_up = CutState {
        depth: 0.009,
        travel_since_fracture: 0.0045,
        ..after
    };
    c.bench_function(
        "surrogate evaluate, after fracture, catch-up (eggplant)",
        |b| b.iter(|| e.evaluate(black_box(0.75), black_box(&catching_up), black_box(&scale))),
    );
}

#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::bench);
}
use group::benches;
criterion_main!(benches);
