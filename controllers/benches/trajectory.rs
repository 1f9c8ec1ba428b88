//! Trajectory generator benchmark (`cargo bench -p shearcut-controllers --bench trajectory`).
//!
//! Prints, for 1, 3, 6 and 7 DoFs on random cases drawn from ruckig's test distributions, the
//! median, p99 and worst calculation time, the per-tick cost of `update()` on an already
//! calculated trajectory (median and mean), and a randomised stress run (default 10⁶ cases, every result checked).
//! Environment: `OTG_BENCH_CASES` (per DoF count, default 100000), `OTG_STRESS_CASES` (default
//! 1000000), `OTG_SEED` (default 42), `OTG_UPDATE_TRAJECTORIES` (trajectories stepped through for the
//! `update()` timing, default 2000), `OTG_BENCH_DOFS` (comma-separated DoF counts out of 1, 3, 6
//! and 7, default all four), `OTG_BENCH_SPLIT` (set: also the median, p90 and p99 of the
//! starts inside the limits and of the braking starts), `OTG_BENCH_TAIL` (set: the slowest 1 %,
//! best of three timings each, is calculated once more on its own, for a profiler; `print`:
//! and its 20 slowest inputs are printed). Inputs are generated before timing; timing uses
//! `std::time::Instant` around each call.

// A benchmark measures wall time by design.
#![allow(clippy::disallowed_methods)]

use std::hint::black_box;
use std::time::Instant;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shearcut_controllers::trajectory::{
    Trajectory, TrajectoryGenerator, TrajectoryInput, TrajectoryOutput, TrajectorySettings,
    TrajectoryStatus,
};

#[path = "../tests/support/random_cases.rs"]
#[allow(dead_code)]
mod random_cases;

use random_cases::random_input;

fn env(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

fn percentile(sorted: &[f64], q: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

fn bench_dofs<const N: usize>(cases: usize, seed: u64, update_trajectories: usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed + N as u64);
    let inputs: Vec<TrajectoryInput<N>> = (0..cases)
        .map(|_| random_input::<N, _>(&mut rng))
        .filter(|i| i.validate().is_ok())
        .collect();
    let otg = TrajectoryGenerator::<N>::new(TrajectorySettings::default()).unwrap();
    let mut traj = Trajectory::<N>::default();
    let mut times = Vec::with_capacity(inputs.len());
    let mut errors = 0usize;
    for inp in &inputs {
        let t0 = Instant::now();
        let r = otg.calculate(black_box(inp), &mut traj);
        let dt = t0.elapsed().as_secs_f64();
        black_box(&traj);
        errors += usize::from(r.is_err());
        times.push(dt);
    }
    if std::env::var("OTG_BENCH_TAIL").is_ok() {
        // The slowest 1 % (best of three timings each), calculated once more on their own (for
        // a profiler).
        let mut best: Vec<(f64, usize)> = inputs
            .iter()
            .enumerate()
            .map(|(k, inp)| {
                let t = (0..3)
                    .map(|_| {
                        let t0 = Instant::now();
                        let _ = otg.calculate(black_box(inp), &mut traj);
                        t0.elapsed().as_secs_f64()
                    })
                    .fold(f64::INFINITY, f64::min);
                (t, k)
            })
            .collect();
        best.sort_by(|a, b| b.0.total_cmp(&a.0));
        let tail = &best[..best.len() / 100];
        let braking = tail
            .iter()
            .filter(|(_, k)| !random_cases::start_is_safe(&inputs[*k]))
            .count();
        println!(
            "  tail: {} cases from {:.2} us, {braking} with a braking start",
            tail.len(),
            tail.last().map_or(0.0, |t| t.0 * 1e6)
        );
        for &(_, k) in tail {
            let _ = black_box(otg.calculate(black_box(&inputs[k]), &mut traj));
        }
        if std::env::var("OTG_BENCH_TAIL").is_ok_and(|v| v == "print") {
            for &(t, k) in tail.iter().take(20) {
                println!("  {:.2} us: {:?}", t * 1e6, inputs[k]);
            }
        }
    }
    if std::env::var("OTG_BENCH_SPLIT").is_ok() {
        let mut safe: Vec<f64> = Vec::new();
        let mut brake: Vec<f64> = Vec::new();
        for (inp, &t) in inputs.iter().zip(&times) {
            if random_cases::start_is_safe(inp) {
                safe.push(t);
            } else {
                brake.push(t);
            }
        }
        for (name, v) in [("safe", &mut safe), ("braking", &mut brake)] {
            v.sort_by(f64::total_cmp);
            if !v.is_empty() {
                println!(
                    "  {name} starts: {} cases, median {:.2} us, p90 {:.2} us, p99 {:.2} us",
                    v.len(),
                    percentile(v, 0.5) * 1e6,
                    percentile(v, 0.9) * 1e6,
                    percentile(v, 0.99) * 1e6
                );
            }
        }
    }
    times.sort_by(f64::total_cmp);
    let mean = times.iter().sum::<f64>() / times.len() as f64;
    println!(
        "calculate {N} DoF: median {:.2} us, mean {:.2} us, p99 {:.2} us, max {:.2} us ({} cases, {errors} errors)",
        percentile(&times, 0.5) * 1e6,
        mean * 1e6,
        percentile(&times, 0.99) * 1e6,
        times[times.len() - 1] * 1e6,
        times.len(),
    );

    // update(): per-tick cost with the trajectory already calculated.
    let mut otg = TrajectoryGenerator::<N>::new(TrajectorySettings::default()).unwrap();
    let mut out = TrajectoryOutput::<N>::default();
    let mut ticks = 0u64;
    let mut tick_time = 0.0;
    let mut worst_tick = 0.0_f64;
    let mut tick_times = Vec::with_capacity(update_trajectories * 2000);
    for inp in inputs.iter().take(update_trajectories) {
        let mut inp = *inp;
        if otg.update(&inp, &mut out).is_err() {
            continue;
        }
        out.pass_to_input(&mut inp);
        for _ in 0..2000 {
            let t0 = Instant::now();
            let s = otg.update(black_box(&inp), &mut out);
            let dt = t0.elapsed().as_secs_f64();
            tick_time += dt;
            tick_times.push(dt);
            worst_tick = worst_tick.max(dt);
            ticks += 1;
            out.pass_to_input(&mut inp);
            if s == Ok(TrajectoryStatus::Finished) {
                break;
            }
        }
    }
    if ticks == 0 {
        return;
    }
    // The median is robust to the preemptions of a loaded machine, which dominate the mean of
    // such short calls.
    tick_times.sort_by(f64::total_cmp);
    let median_tick = percentile(&tick_times, 0.5);
    println!(
        "update    {N} DoF: median {:.1} ns per tick ({:.1} ns per DoF), mean {:.1} ns, worst {:.2} us ({ticks} ticks)",
        median_tick * 1e9,
        median_tick * 1e9 / N as f64,
        tick_time / ticks as f64 * 1e9,
        worst_tick * 1e6
    );
}

#[derive(Default)]
struct Tally {
    ok: u64,
    braking: u64,
    braking_errors: u64,
    errors: u64,
    invalid: u64,
}

fn stress_one<const N: usize>(rng: &mut ChaCha8Rng, tally: &mut Tally) {
    let inp = random_input::<N, _>(rng);
    if inp.validate().is_err() {
        tally.invalid += 1;
        return;
    }
    let otg = TrajectoryGenerator::<N>::new(TrajectorySettings::default()).unwrap();
    let mut t = Trajectory::<N>::default();
    match otg.calculate(&inp, &mut t) {
        Ok(TrajectoryStatus::BrakingThenTarget) => tally.braking += 1,
        Ok(_) => {
            tally.ok += 1;
            for i in 0..N {
                let e = t.profile(i).end();
                let x = t.profile(i).extrema();
                let tol = |l: f64| l + 1e-12 * l.max(1.0);
                let good = (e.position - inp.target_position[i]).abs() <= 1e-8
                    && (e.velocity - inp.target_velocity[i]).abs() <= 1e-8
                    && (e.acceleration - inp.target_acceleration[i]).abs() <= 1e-10
                    && x.velocity.max <= tol(inp.max_velocity[i])
                    && -x.velocity.min <= tol(inp.max_velocity[i])
                    && x.acceleration.max <= tol(inp.max_acceleration[i])
                    && -x.acceleration.min <= tol(inp.max_acceleration[i]);
                assert!(good, "verification failed for {inp:?}");
            }
        }
        Err(_) => {
            let braking = (0..N).any(|i| {
                let (v, a) = (inp.current_velocity[i], inp.current_acceleration[i]);
                let (vm, am, j) = (
                    inp.max_velocity[i],
                    inp.max_acceleration[i],
                    inp.max_jerk[i],
                );
                a.abs() > am || v.abs() > vm || v.abs() + a * a / (2.0 * j) > vm
            });
            if braking {
                tally.braking_errors += 1;
            } else {
                tally.errors += 1;
                if tally.errors <= 3 {
                    eprintln!("error on a start inside the limits: {inp:?}");
                }
            }
        }
    }
}

fn main() {
    // `cargo bench` passes `--bench`; ignore arguments.
    let cases = env("OTG_BENCH_CASES", 100_000) as usize;
    let stress = env("OTG_STRESS_CASES", 1_000_000);
    let seed = env("OTG_SEED", 42);
    let upd = env("OTG_UPDATE_TRAJECTORIES", 2000) as usize;
    let dofs = std::env::var("OTG_BENCH_DOFS").unwrap_or_else(|_| "1,3,6,7".into());
    for n in dofs
        .split(',')
        .filter_map(|s| s.trim().parse::<usize>().ok())
    {
        match n {
            1 => bench_dofs::<1>(cases, seed, upd),
            3 => bench_dofs::<3>(cases, seed, upd),
            6 => bench_dofs::<6>(cases, seed, upd),
            7 => bench_dofs::<7>(cases, seed, upd),
            _ => eprintln!("OTG_BENCH_DOFS: {n} is not one of 1, 3, 6, 7"),
        }
    }

    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut tally = Tally::default();
    let t0 = Instant::now();
    for _ in 0..stress {
        match rng.random_range(1..=7) {
            1 => stress_one::<1>(&mut rng, &mut tally),
            2 => stress_one::<2>(&mut rng, &mut tally),
            3 => stress_one::<3>(&mut rng, &mut tally),
            4 => stress_one::<4>(&mut rng, &mut tally),
            5 => stress_one::<5>(&mut rng, &mut tally),
            6 => stress_one::<6>(&mut rng, &mut tally),
            _ => stress_one::<7>(&mut rng, &mut tally),
        }
    }
    println!(
        "stress: {stress} cases (seed {seed}) in {:.1} s: {} verified, {} braking-then-target, \
         {} braking errors, {} errors on starts inside the limits, {} invalid inputs",
        t0.elapsed().as_secs_f64(),
        tally.ok,
        tally.braking,
        tally.braking_errors,
        tally.errors,
        tally.invalid
    );
}
