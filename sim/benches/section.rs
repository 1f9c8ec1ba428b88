//! Cost of a cross-section knife step and of a whole cut, against the naive
//! approach's lower bound: re-assembling, refactorising and condensing every
//! step costs at least one `CrossSection::new` per step (a naive step needs
//! that for every trial extension of the bisection, so the ratio printed is a
//! lower bound).
//!
//! Run: `cargo bench -p shearcut-sim --bench section` (add
//! `-- --warm-up-time 1 --measurement-time 3` for a short run).
//!
//! Figures (30 × 30 mm potato section, default mesh and blade, 6.25 µm knife
//! steps, 2 shared cores, load ≈ 3; short run above), after the unilateral
//! face/edge contact (active set on the condensed line) and the kink-aware
//! work integration:
//!
//! | benchmark                               | median   |
//! |-----------------------------------------|----------|
//! | one knife step, steady cutting, ξ = 0.75 | 90 µs    |
//! | naive step lower bound (one rebuild)    | 119 ms   |
//! | whole cut, 20 mm at ξ = 0.75 (3200 steps) | 474 ms |
//! | same-run ratio naive/condensed (printed) | ≥ 1018×  |
//!
//! Before the contact fix (bilateral faces) the same run gave ≈ 94 µs per
//! step and ≈ 0.31 s per cut: the active set costs little per step in steady
//! cutting, more (≈ 1.5×) over a whole cut, where the released set changes
//! and its dense Cholesky factor (reused while the set holds) is redone.

// A benchmark measures wall time by design.
#![allow(clippy::disallowed_methods)]

use std::hint::black_box;
use std::time::Instant;

use criterion::{Criterion, criterion_main};
use shearcut_sim::{BladeSection, CrossSection, MaterialPreset, SectionGeometry, SectionSettings};

const DN: f64 = 6.25e-6;

fn setup() -> (
    SectionGeometry,
    shearcut_sim::Material,
    BladeSection,
    SectionSettings,
) {
    (
        SectionGeometry::rectangle(0.03, 0.03).unwrap(),
        MaterialPreset::PotatoCuboid.material(),
        BladeSection::default(),
        SectionSettings::default(),
    )
}

fn bench(c: &mut Criterion) {
    let (g, m, b, s) = setup();
    let mut cs = CrossSection::new(&g, &m, &b, &s).unwrap();
    // Steady cutting at ξ = 0.75, 10 mm deep: steps cost the same from here on.
    cs.advance_to(0.01, 0.75, DN).unwrap();
    let steady = cs.clone();
    let mut group = c.benchmark_group("section");
    group.bench_function("knife_step_steady_cutting", |bch| {
        bch.iter_batched_ref(
            || steady.clone(),
            |cs| black_box(cs.advance(DN, 0.75 * DN).unwrap()),
            criterion::BatchSize::SmallInput,
        )
    });
    group.sample_size(10);
    group.bench_function("naive_step_lower_bound_rebuild", |bch| {
        bch.iter(|| black_box(CrossSection::new(&g, &m, &b, &s).unwrap()))
    });
    group.bench_function("whole_cut_20mm_xi_0.75", |bch| {
        bch.iter(|| {
            cs.reset();
            black_box(cs.advance_to(0.02, 0.75, DN).unwrap())
        })
    });
    group.finish();
    // Same-run ratio, median of a few repetitions each.
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let steps: Vec<f64> = (0..9)
        .map(|_| {
            let mut c2 = steady.clone();
            let t = Instant::now();
            for _ in 0..200 {
                black_box(c2.advance(DN, 0.75 * DN).unwrap());
            }
            t.elapsed().as_secs_f64() / 200.0
        })
        .collect();
    let rebuild: Vec<f64> = (0..5)
        .map(|_| {
            let t = Instant::now();
            black_box(CrossSection::new(&g, &m, &b, &s).unwrap());
            t.elapsed().as_secs_f64()
        })
        .collect();
    let (st, rb) = (median(steps), median(rebuild));
    println!(
        "steady step {:.1} us, rebuild {:.1} ms, naive/condensed >= {:.0}x",
        st * 1e6,
        rb * 1e3,
        rb / st
    );
}

#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::bench);
}
use group::benches;
criterion_main!(benches);
