//! Multi-DoF calculation: braking, per-DoF time-optimal profiles, and synchronisation.
//!
//! ## Time synchronisation and blocked intervals
//! A DoF can reach its target in its minimal time `T_i`, but not necessarily in every longer
//! time: the set of feasible durations is `[T_i, ∞)` minus *blocked intervals* (for instance a
//! DoF that must reverse can finish fast by turning early or slowly by overshooting, but not in
//! between). Every blocked interval ends at another extremal profile, i.e. at one of the valid
//! step-1 candidates of that DoF. The minimal common duration is therefore the smallest
//! candidate `T ≥ max_i T_i`, taken from the union of all DoFs' candidate durations, for which
//! every DoF has a profile of duration exactly `T` (its own candidate, or a fixed-duration
//! profile from [`super::position_fixed_duration`]). With duration discretization each
//! candidate is first rounded up to a whole number of cycles.
//!
//! ## Phase synchronisation
//! If the displacement, start velocity/acceleration and target velocity/acceleration are all
//! parallel to one unit vector `u`, the motion is solved once as a scalar problem along `u` with
//! the tightest scaled limits (`v_max = min_i v_max,i/|u_i|`, respecting signs for asymmetric
//! limits) and mapped to each DoF as `p_i(t) = p_i(0) + u_i s(t)`: a straight line. Otherwise
//! (or if any DoF brakes) it falls back to time synchronisation.

use super::brake::{Limits, brake, brake_to_limit, brake_with, is_safe};
use super::dof::{Dof, Segments};
use super::input::{
    ControlInterface, DurationDiscretization, Synchronization, TrajectoryError, TrajectoryInput,
    TrajectorySettings, TrajectoryStatus,
};
use super::position_fixed_duration::{fixed_duration, fixed_duration_then};
use super::position_time_optimal::{
    Search, TimeOptimal, peak_parts, time_optimal, time_optimal_into,
};
use super::profile::Profile;
use super::trajectory::Trajectory;
use super::vel_change::vel_change;
use super::velocity;

/// Per-DoF intermediate results (kept on the stack).
#[derive(Clone, Copy)]
struct DofWork {
    dof: Dof,
    limits: Limits,
    prefix: Profile,
    brake_t: f64,
    cands: TimeOptimal,
}

fn round_up(t: f64, dt: f64) -> f64 {
    let k = (t / dt - 1e-9).ceil().max(0.0);
    k * dt
}

/// Computes the trajectory for `input` into `traj`.
pub(crate) fn calculate<const N: usize>(
    input: &TrajectoryInput<N>,
    settings: &TrajectorySettings,
    traj: &mut Trajectory<N>,
) -> Result<TrajectoryStatus, TrajectoryError> {
    input.validate()?;
    let discrete = input.duration_discretization == DurationDiscretization::Discrete;
    let dt = settings.cycle_time;
    let position = input.interface == ControlInterface::Position;

    if position
        && !discrete
        && N > 1
        && input.synchronization == Synchronization::Time
        && let Some(status) = synchronize_limiting_first(input, traj)
    {
        return Ok(status);
    }
    traj.pending = [None; N];
    // One DoF on its own needs its shortest profile only; so do independent DoFs (continuous
    // durations). Otherwise every extremal profile bounds a blocked interval.
    let search =
        if position && !discrete && (N == 1 || input.synchronization == Synchronization::None) {
            Search::Shortest
        } else {
            Search::All
        };
    if search == Search::Shortest
        && let Some(result) = independent_shortest(input, traj)
    {
        return result;
    }

    // Braking and step 1 per DoF.
    let mut braking = false;
    let mut work: [Option<DofWork>; N] = [None; N];
    let mut alt_work: [[Option<DofWork>; 2]; N] = [[None; 2]; N];
    let mut t_min = 0.0_f64;
    for i in 0..N {
        let (active, total) = solve_braking_dof(
            input,
            i,
            position,
            search,
            search == Search::All,
            &mut work[i],
            &mut alt_work[i],
        )?;
        braking |= active;
        traj.independent_min_durations[i] = total;
        t_min = t_min.max(total);
    }
    traj.braking = braking;
    let status = if braking {
        TrajectoryStatus::BrakingThenTarget
    } else {
        TrajectoryStatus::Working
    };
    let w = |i: usize| work[i].as_ref().expect("filled above");

    // Independent motion.
    if input.synchronization == Synchronization::None && !discrete {
        for i in 0..N {
            w(i).cands
                .profile_into(&w(i).prefix, 0, &mut traj.profiles[i]);
        }
        traj.duration = t_min;
        return Ok(finished_if_zero(traj, status));
    }
    if input.synchronization == Synchronization::None {
        // Each DoF rounded up on its own.
        for i in 0..N {
            let wi = w(i);
            let t = round_up(wi.brake_t + wi.cands.duration[0], dt);
            if !stretch(wi, t, position, &mut traj.profiles[i]) {
                return Err(TrajectoryError::Synchronization { dof: i });
            }
        }
        traj.duration = round_up(t_min, dt);
        return Ok(finished_if_zero(traj, status));
    }

    if input.synchronization == Synchronization::Phase
        && !braking
        && position
        && N > 1
        && phase_synchronize(input, discrete, dt, traj)
    {
        return Ok(finished_if_zero(traj, status));
    }

    // Time synchronisation over the candidate durations.
    let mut densified = [false; N];
    let mut t_cand = t_min;
    let mut failed_dof = 0;
    loop {
        let t = if discrete {
            round_up(t_cand, dt)
        } else {
            t_cand
        };
        let mut ok = true;
        for (i, alt) in alt_work.iter().enumerate() {
            let out = &mut traj.profiles[i];
            if !(stretch(wk(&work, i), t, position, out)
                || alt.iter().flatten().any(|a| stretch(a, t, position, out)))
            {
                ok = false;
                failed_dof = i;
                break;
            }
        }
        if ok {
            traj.duration = t;
            return Ok(finished_if_zero(traj, status));
        }
        // Next candidate duration strictly after `t`.
        let mut next = f64::INFINITY;
        for wi in work.iter().chain(alt_work.iter().flatten()).flatten() {
            for k in 0..wi.cands.n {
                let d = wi.brake_t + wi.cands.duration[k];
                if d > t + 1e-12 * (1.0 + t) && d < next {
                    next = d;
                }
            }
        }
        // The DoF that could not be stretched may have an extremal profile (the end of a
        // blocked interval) that the normal search missed: search it once more, sampling every
        // family densely, and add what is found (never replace: the polynomial solutions of
        // the first search are exact and sampling can miss them).
        if !densified[failed_dof] && position {
            densified[failed_dof] = true;
            if let Some(wi) = work[failed_dof].as_mut() {
                let dense = time_optimal(&wi.dof, &wi.prefix, 8, Search::All);
                wi.cands.merge(&dense);
            }
            continue;
        }
        if !next.is_finite() {
            return Err(TrajectoryError::Synchronization { dof: failed_dof });
        }
        t_cand = next;
    }
}

/// One DoF, or independent DoFs with continuous durations, every one starting inside the
/// limits: each DoF's shortest profile ([`Search::Shortest`]) written straight to `traj`, with
/// exactly the result of the general path below (which for such inputs builds no braking
/// prefix and uses candidate 0 of each DoF) but without its per-DoF work arrays. `None` if a
/// DoF must brake first (the general path handles it).
fn independent_shortest<const N: usize>(
    input: &TrajectoryInput<N>,
    traj: &mut Trajectory<N>,
) -> Option<Result<TrajectoryStatus, TrajectoryError>> {
    for i in 0..N {
        let (v0, a0) = (input.current_velocity[i], input.current_acceleration[i]);
        if !is_safe(v0, a0, &input.limits(i), true) {
            return None;
        }
    }
    let mut cands = TimeOptimal::new();
    let mut t = 0.0_f64;
    for i in 0..N {
        let d = input.current_dof(i, &input.limits(i));
        let prefix = Profile::new(d.p0, d.v0, d.a0);
        time_optimal_into(&d, &prefix, 1, Search::Shortest, &mut cands);
        if cands.n == 0 {
            return Some(Err(TrajectoryError::NoProfile { dof: i }));
        }
        cands.profile_into(&prefix, 0, &mut traj.profiles[i]);
        traj.independent_min_durations[i] = cands.duration[0];
        t = t.max(cands.duration[0]);
    }
    traj.duration = t;
    traj.braking = false;
    traj.pending = [None; N];
    Some(Ok(finished_if_zero(traj, TrajectoryStatus::Working)))
}

/// Braking and step 1 of DoF `i`: the fastest braking variant's solution in `work`, the other
/// variants (braking to rest at the limit velocity, holding the braking acceleration; only
/// when velocity braking is involved) in `alt`. Returns whether the DoF brakes and its minimal
/// total duration. `search`: whether each variant needs all its extremal profiles;
/// `variants`: whether the other variants are needed (for synchronisation) even if they
/// cannot be faster.
#[allow(clippy::too_many_arguments)]
fn solve_braking_dof<const N: usize>(
    input: &TrajectoryInput<N>,
    i: usize,
    position: bool,
    search: Search,
    variants: bool,
    work: &mut Option<DofWork>,
    alt: &mut [Option<DofWork>; 2],
) -> Result<(bool, f64), TrajectoryError> {
    let l = input.limits(i);
    let b = brake(
        input.current_position[i],
        input.current_velocity[i],
        input.current_acceleration[i],
        &l,
        position,
    )
    .ok_or(TrajectoryError::NoProfile { dof: i })?;
    let alternative = if b.active && position {
        brake_to_limit(
            input.current_position[i],
            input.current_velocity[i],
            input.current_acceleration[i],
            &l,
        )
    } else {
        None
    };
    let total = |w: &DofWork| w.brake_t + w.cands.duration[0];
    solve_dof(input, i, &l, &b.prefix, position, search, work);
    // Alternative braking variants: braking to rest at the limit velocity, and holding the
    // braking acceleration (both only when velocity braking is involved). They are kept for
    // synchronisation: they may reach durations that the fastest one cannot (blocked
    // intervals differ).
    if b.active && position {
        let held = brake_with(
            input.current_position[i],
            input.current_velocity[i],
            input.current_acceleration[i],
            &l,
            position,
            true,
        )
        .filter(|h| h.prefix.end() != b.prefix.end())
        .map(|h| h.prefix);
        for (k, p) in [alternative, held].into_iter().enumerate() {
            if let Some(p) = p {
                // Only the shortest total is wanted: a variant whose braking plus a lower
                // bound of its main profile is not shorter than the best total cannot be
                // better. Bounds: the time-optimal change of velocity and acceleration alone,
                // and the remaining distance at the velocity limit.
                let beaten = !variants
                    && work.as_ref().is_some_and(|bw| {
                        let e = p.end();
                        let rest = input.target_position[i] - e.position;
                        let at_limit = if rest > 0.0 {
                            rest / l.v_max
                        } else {
                            rest / l.v_min
                        };
                        vel_change(
                            e.velocity,
                            e.acceleration,
                            input.target_velocity[i],
                            input.target_acceleration[i],
                            l.a_max,
                            l.a_min,
                            l.j,
                        )
                        .is_some_and(|c| {
                            // A zero limit makes `at_limit` NaN, which `max` ignores:
                            // the change's own duration still bounds the total.
                            p.duration() + c.duration().max(at_limit) >= total(bw)
                        })
                    });
                if !beaten {
                    solve_dof(input, i, &l, &p, position, search, &mut alt[k]);
                }
            }
            let better = match (&*work, &alt[k]) {
                (Some(bw), Some(ow)) => total(ow) < total(bw),
                (None, Some(_)) => true,
                _ => false,
            };
            if better {
                core::mem::swap(work, &mut alt[k]);
            }
        }
    }
    let Some(best) = &*work else {
        return Err(TrajectoryError::NoProfile { dof: i });
    };
    Ok((b.active, total(best)))
}

/// Time synchronisation that solves the step-1 problem (the shortest profile) only for the
/// DoFs that may be limiting; `None` to fall back to the complete search in [`calculate`].
///
/// The common duration is the smallest candidate `T ≥ max_i T_i` at which every DoF has a
/// profile (module documentation). The complete search starts at `T = max_i T_i` and, in most
/// cases, ends there. Here the DoFs whose duration guess ([`duration_guess`]) is within
/// [`GUESS_SHARE`] of the largest are solved, `t` is the largest of their minimal durations,
/// and every other DoF is only asked for a fixed-duration profile of duration `t`. A DoF that
/// has one satisfies `T_i ≤ t` (its profile is verified, and no profile is shorter than
/// `T_i`), so if every DoF has one, `t = max_i T_i` and it is the common duration of the
/// complete search (which would try the same fixed-duration problems at the same `t`, or
/// the DoF's own candidate of that duration). A DoF without one is solved: if its `T_i`
/// exceeds `t`, `t` becomes `T_i` and every DoF is asked again; otherwise `t` lies in one of
/// its blocked intervals and the complete search takes over. The minimal durations of the
/// DoFs that are not solved are computed on demand by
/// [`Trajectory::independent_min_durations`].
///
/// Only for continuous durations. A DoF whose start makes a violation unavoidable is solved at
/// once with all its braking variants (and stretched like in the complete search).
fn synchronize_limiting_first<const N: usize>(
    input: &TrajectoryInput<N>,
    traj: &mut Trajectory<N>,
) -> Option<TrajectoryStatus> {
    // `dofs[i]`: the problem of a DoF that starts inside the limits (solved only if needed);
    // a DoF that brakes is solved at once with all its braking variants, as in the complete
    // search (its guess, +∞, puts it first in the order below).
    let mut dofs = [None; N];
    let mut guess = [f64::INFINITY; N];
    let mut guess_max = 0.0_f64;
    let mut work: [Option<DofWork>; N] = [None; N];
    let mut alt_work: [[Option<DofWork>; 2]; N] = [[None; 2]; N];
    let mut total = [f64::NAN; N];
    let mut braking = false;
    let mut t = 0.0_f64;
    for i in 0..N {
        let l = input.limits(i);
        let (v0, a0) = (input.current_velocity[i], input.current_acceleration[i]);
        if !is_safe(v0, a0, &l, true) {
            let (_, ti) = solve_braking_dof(
                input,
                i,
                true,
                Search::Shortest,
                true,
                &mut work[i],
                &mut alt_work[i],
            )
            .ok()?;
            braking = true;
            total[i] = ti;
            t = t.max(ti);
            continue;
        }
        let d = input.dof_from(i, (input.current_position[i], v0, a0), &l);
        guess[i] = duration_guess(&d);
        guess_max = guess_max.max(guess[i]);
        dofs[i] = Some(d);
    }
    // Solves DoF `i` (starting inside the limits); its minimal duration, `None` if it has
    // none. Only its shortest profile is needed: a DoF whose extremal durations would matter
    // (`t` in one of its blocked intervals) makes this synchronisation give up below, and the
    // complete search takes over.
    let solve = |i: usize, work: &mut [Option<DofWork>; N]| -> Option<f64> {
        let d = dofs[i].as_ref()?;
        let prefix = Profile::new(d.p0, d.v0, d.a0);
        solve_dof(
            input,
            i,
            &input.limits(i),
            &prefix,
            true,
            Search::Shortest,
            &mut work[i],
        );
        work[i].as_ref().map(|w| w.cands.duration[0])
    };
    for (i, &g) in guess.iter().enumerate() {
        // A NaN guess counts as limiting.
        if dofs[i].is_some() && (g.is_nan() || g >= GUESS_SHARE * guess_max) {
            total[i] = solve(i, &mut work)?;
            t = t.max(total[i]);
        }
    }
    // The DoFs are asked in the order of decreasing guesses: a DoF that is longer than `t`
    // after all is then likely found before the others have been asked in vain.
    let mut order: [usize; N] = core::array::from_fn(|i| i);
    order.sort_unstable_by(|&a, &b| guess[b].total_cmp(&guess[a]));
    'retry: loop {
        for &i in &order {
            let out = &mut traj.profiles[i];
            let found = match &work[i] {
                Some(w) => {
                    stretch(w, t, true, out)
                        || alt_work[i]
                            .iter()
                            .flatten()
                            .any(|a| stretch(a, t, true, out))
                }
                None => {
                    let d = dofs[i].as_ref()?;
                    let prefix = Profile::new(d.p0, d.v0, d.a0);
                    // If the peak + cruise family has no profile of duration `t`, the DoF is
                    // solved before the held families are searched: a minimal duration above
                    // `t` proves there is none (a wrong guess), and the costly failing search
                    // is skipped.
                    let (mut longer, mut no_profile) = (false, false);
                    let found = fixed_duration_then(d, &prefix, t, || match solve(i, &mut work) {
                        Some(ti) => {
                            total[i] = ti;
                            longer = ti > t;
                            !longer
                        }
                        None => {
                            no_profile = true;
                            false
                        }
                    })
                    .is_some_and(|(segs, dir)| segs.append_to(&prefix, dir, out));
                    if no_profile {
                        return None;
                    }
                    if longer {
                        t = total[i];
                        continue 'retry;
                    }
                    found
                }
            };
            if found {
                continue;
            }
            if work[i].is_some() {
                // `t` is blocked for a solved DoF.
                return None;
            }
            total[i] = solve(i, &mut work)?;
            if total[i] > t {
                t = total[i];
                continue 'retry;
            }
            return None;
        }
        break;
    }
    for i in 0..N {
        if work[i].is_some() {
            traj.independent_min_durations[i] = total[i];
            traj.pending[i] = None;
        } else {
            traj.independent_min_durations[i] = f64::NAN;
            traj.pending[i] = dofs[i];
        }
    }
    traj.duration = t;
    traj.braking = braking;
    let status = if braking {
        TrajectoryStatus::BrakingThenTarget
    } else {
        TrajectoryStatus::Working
    };
    Some(finished_if_zero(traj, status))
}

/// DoFs whose duration guess is at least this share of the largest guess are solved first by
/// [`synchronize_limiting_first`] (a wrong guess costs work, never a different result).
const GUESS_SHARE: f64 = 0.8;

/// A cheap guess of a DoF's minimal duration, only used to choose which DoFs
/// [`synchronize_limiting_first`] solves first: the duration of the profile that cruises at
/// the velocity limit in the direction of the displacement if its cruise time is not
/// negative; otherwise that profile's duration without the cruise, scaled by the cube root of
/// the ratio of the displacement to its distance (the scaling of a jerk-limited rest-to-rest
/// move); and at least the duration of the time-optimal change of velocity and acceleration
/// alone.
pub(crate) fn duration_guess(d: &Dof) -> f64 {
    let dp = d.pf - d.p0;
    let vc = if dp >= 0.0 { d.v_max } else { d.v_min };
    if vc == 0.0 {
        return 0.0;
    }
    let Some((c1, c2)) = peak_parts(d, vc) else {
        return 0.0;
    };
    let dist = c1.distance(d.v0, d.a0) + c2.distance(vc, 0.0);
    let tt = c1.duration() + c2.duration();
    let tc = (dp - dist) / vc;
    let g = if tc >= 0.0 {
        tt + tc
    } else if dp / dist > 0.0 {
        tt * (dp / dist).cbrt()
    } else {
        tt
    };
    // Not below the time-optimal velocity change alone (a lower bound of the duration).
    vel_change(d.v0, d.a0, d.vf, d.af, d.a_max, d.a_min, d.j).map_or(g, |c| g.max(c.duration()))
}

/// The minimal duration of DoF `d` on its own (start inside the limits, no braking), for
/// [`Trajectory::independent_min_durations`] of the DoFs that the synchronisation did not
/// solve; NaN if no profile is found.
pub(crate) fn independent_min_duration(d: &Dof) -> f64 {
    let prefix = Profile::new(d.p0, d.v0, d.a0);
    let mut cands = TimeOptimal::new();
    time_optimal_into(d, &prefix, 1, Search::Shortest, &mut cands);
    if cands.n > 0 {
        cands.duration[0]
    } else {
        f64::NAN
    }
}

fn wk<const N: usize>(work: &[Option<DofWork>; N], i: usize) -> &DofWork {
    work[i]
        .as_ref()
        .expect("every DoF is solved before synchronisation")
}

/// Step 1 of DoF `i` after the braking `prefix`, written to `out` (`None` if no profile exists).
/// Filled in place: a [`DofWork`] is a few kilobytes.
fn solve_dof<const N: usize>(
    input: &TrajectoryInput<N>,
    i: usize,
    l: &Limits,
    prefix: &Profile,
    position: bool,
    search: Search,
    out: &mut Option<DofWork>,
) {
    let s = prefix.end();
    let dof = input.dof_from(i, (s.position, s.velocity, s.acceleration), l);
    let w = match out {
        Some(w) => {
            w.dof = dof;
            w.limits = *l;
            w.prefix = *prefix;
            w.brake_t = prefix.duration();
            w
        }
        None => out.insert(DofWork {
            dof,
            limits: *l,
            prefix: *prefix,
            brake_t: prefix.duration(),
            cands: TimeOptimal::new(),
        }),
    };
    let c = &mut w.cands;
    if position {
        time_optimal_into(&w.dof, &w.prefix, 1, search, c);
    } else {
        c.n = 0;
        let mut found = velocity::candidates(prefix, dof.vf, dof.af, l);
        if let [Some(a), Some(b)] = &found
            && b.duration() < a.duration()
        {
            found.swap(0, 1);
        }
        for p in found.iter().flatten() {
            // The velocity profile's segments after the prefix form one candidate.
            let mut sg = Segments::default();
            for k in p.brake_segments()..p.len() {
                let (t, j) = p.segment(k);
                sg.push(t, j, 0.0);
            }
            c.duration[c.n] = sg.duration();
            c.segs[c.n] = sg;
            c.dir[c.n] = 1.0;
            c.n += 1;
        }
    }
    if c.n == 0 {
        *out = None;
    }
}

fn finished_if_zero<const N: usize>(
    traj: &Trajectory<N>,
    status: TrajectoryStatus,
) -> TrajectoryStatus {
    if traj.duration == 0.0 {
        TrajectoryStatus::Finished
    } else {
        status
    }
}

/// Profile of one DoF lasting exactly `t` (braking included), written to `out`: its own
/// candidate if one has that duration, otherwise a fixed-duration profile. `false` (and `out`
/// unspecified) if there is none.
fn stretch(w: &DofWork, t: f64, position: bool, out: &mut Profile) -> bool {
    let tm = t - w.brake_t;
    if tm < -1e-12 * (1.0 + t) {
        return false;
    }
    let tm = tm.max(0.0);
    for k in 0..w.cands.n {
        if (w.cands.duration[k] - tm).abs() <= 1e-12 * (1.0 + tm) {
            w.cands.profile_into(&w.prefix, k, out);
            return true;
        }
    }
    if position {
        match fixed_duration(&w.dof, &w.prefix, tm) {
            Some((segs, dir)) => segs.append_to(&w.prefix, dir, out),
            None => false,
        }
    } else {
        match velocity::fixed_duration(&w.prefix, w.dof.vf, w.dof.af, &w.limits, tm) {
            Some(p) => {
                *out = p;
                true
            }
            None => false,
        }
    }
}

/// Straight-line synchronisation; returns false if the input is not collinear or a DoF fails.
fn phase_synchronize<const N: usize>(
    input: &TrajectoryInput<N>,
    discrete: bool,
    dt: f64,
    traj: &mut Trajectory<N>,
) -> bool {
    let dp: [f64; N] =
        core::array::from_fn(|i| input.target_position[i] - input.current_position[i]);
    let vecs = [
        &dp,
        &input.current_velocity,
        &input.current_acceleration,
        &input.target_velocity,
        &input.target_acceleration,
    ];
    let norm = |x: &[f64; N]| x.iter().map(|a| a * a).sum::<f64>().sqrt();
    let Some(base) = vecs.iter().find(|x| norm(x) > 1e-12) else {
        return false;
    };
    let nb = norm(base);
    let u: [f64; N] = core::array::from_fn(|i| base[i] / nb);
    // Scalar coordinates along u, and a collinearity check of every vector.
    let mut s = [0.0; 5];
    for (k, x) in vecs.iter().enumerate() {
        let c: f64 = x.iter().zip(&u).map(|(a, b)| a * b).sum();
        let resid = x
            .iter()
            .zip(&u)
            .map(|(a, b)| (a - c * b).powi(2))
            .sum::<f64>()
            .sqrt();
        if resid > 1e-12 * (1.0 + norm(x)) {
            return false;
        }
        s[k] = c;
    }
    let mut l = Limits {
        v_max: f64::INFINITY,
        v_min: f64::NEG_INFINITY,
        a_max: f64::INFINITY,
        a_min: f64::NEG_INFINITY,
        j: f64::INFINITY,
    };
    for (i, &ui) in u.iter().enumerate() {
        if ui.abs() < 1e-300 {
            continue;
        }
        let li = input.limits(i);
        let (vhi, vlo, ahi, alo) = if ui > 0.0 {
            (li.v_max / ui, li.v_min / ui, li.a_max / ui, li.a_min / ui)
        } else {
            (li.v_min / ui, li.v_max / ui, li.a_min / ui, li.a_max / ui)
        };
        l.v_max = l.v_max.min(vhi);
        l.v_min = l.v_min.max(vlo);
        l.a_max = l.a_max.min(ahi);
        l.a_min = l.a_min.max(alo);
        l.j = l.j.min(li.j / ui.abs());
    }
    let line = Dof {
        p0: 0.0,
        v0: s[1],
        a0: s[2],
        pf: s[0],
        vf: s[3],
        af: s[4],
        v_max: l.v_max,
        v_min: l.v_min,
        a_max: l.a_max,
        a_min: l.a_min,
        j: l.j,
    };
    let prefix = Profile::new(0.0, line.v0, line.a0);
    let cands = time_optimal(&line, &prefix, 1, Search::Shortest);
    if cands.n == 0 {
        return false;
    }
    let mut scalar = Profile::default();
    cands.profile_into(&prefix, 0, &mut scalar);
    if discrete {
        let t = round_up(scalar.duration(), dt);
        match fixed_duration(&line, &prefix, t) {
            Some((segs, dir)) => {
                if !segs.append_to(&prefix, dir, &mut scalar) {
                    return false;
                }
            }
            None => return false,
        }
    }
    #[allow(clippy::needless_range_loop)] // i indexes several input arrays
    for i in 0..N {
        let dof = input.current_dof(i, &input.limits(i));
        let mut p = Profile::new(dof.p0, dof.v0, dof.a0);
        for k in 0..scalar.len() {
            let (t, j) = scalar.segment(k);
            p.push(t, u[i] * j);
        }
        if !dof.verify(&p) {
            return false;
        }
        traj.profiles[i] = p;
    }
    traj.duration = scalar.duration();
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A random one-DoF input from ruckig's test distributions with the start velocity and
    /// acceleration scaled up, so that most starts make a violation unavoidable (braking);
    /// `None` if the input is invalid.
    fn random_braking_input(rng: &mut ChaCha8Rng) -> Option<TrajectoryInput<1>> {
        let mut u = |a: f64, b: f64| rng.random_range(a..b);
        let mut input = TrajectoryInput::<1>::default();
        input.current_position = [u(-8.0, 8.0)];
        input.target_position = [u(-8.0, 8.0)];
        input.max_velocity = [u(0.1, 12.0)];
        input.max_acceleration = [u(0.1, 12.0)];
        input.max_jerk = [u(0.1, 12.0)];
        input.current_velocity = [u(-2.0, 2.0) * input.max_velocity[0]];
        input.current_acceleration = [u(-2.0, 2.0) * input.max_acceleration[0]];
        input.target_velocity = [u(-0.9, 0.9) * input.max_velocity[0]];
        input.target_acceleration = [u(-0.9, 0.9) * input.max_acceleration[0]];
        input.validate().is_ok().then_some(input)
    }

    /// The braking variants' pruning is exact: on random one-DoF starts outside the limits,
    /// the shortest total duration with the pruning (`variants = false`) equals, bit for bit,
    /// the one found by solving every variant; and the lower bound that prunes (braking time
    /// plus the time-optimal change of velocity and acceleration alone, or the remaining
    /// distance at the velocity limit) never exceeds the total of the variant it bounds.
    #[test]
    fn braking_pruning_equals_the_unpruned_search() {
        let mut rng = ChaCha8Rng::seed_from_u64(41);
        let (mut compared, mut bounded) = (0, 0);
        for _ in 0..4000 {
            let Some(input) = random_braking_input(&mut rng) else {
                continue;
            };
            let mut pruned = (None, [None; 2]);
            let mut full = (None, [None; 2]);
            let a = solve_braking_dof(
                &input,
                0,
                true,
                Search::Shortest,
                false,
                &mut pruned.0,
                &mut pruned.1,
            );
            let b = solve_braking_dof(
                &input,
                0,
                true,
                Search::Shortest,
                true,
                &mut full.0,
                &mut full.1,
            );
            match (a, b) {
                (Ok((braking_a, ta)), Ok((braking_b, tb))) => {
                    assert_eq!(braking_a, braking_b);
                    assert_eq!(ta.to_bits(), tb.to_bits(), "{input:?}: {ta} against {tb}");
                    compared += usize::from(braking_a);
                }
                (a, b) => assert_eq!(a.is_err(), b.is_err(), "{input:?}"),
            }
            // The bound against every variant the complete run solved.
            let l = input.limits(0);
            for w in full.1.iter().chain([&full.0]).flatten() {
                if w.cands.n == 0 {
                    continue;
                }
                let e = w.prefix.end();
                let rest = input.target_position[0] - e.position;
                let at_limit = if rest > 0.0 {
                    rest / l.v_max
                } else {
                    rest / l.v_min
                };
                if let Some(c) = vel_change(
                    e.velocity,
                    e.acceleration,
                    input.target_velocity[0],
                    input.target_acceleration[0],
                    l.a_max,
                    l.a_min,
                    l.j,
                ) {
                    let bound = w.brake_t + c.duration().max(at_limit);
                    let total = w.brake_t + w.cands.duration[0];
                    assert!(
                        bound <= total + 1e-12 * (1.0 + total),
                        "{input:?}: bound {bound} above the total {total}"
                    );
                    bounded += 1;
                }
            }
        }
        assert!(compared > 1000 && bounded > 2000, "{compared} {bounded}");
    }
}
