//! Regression cases of the time synchronisation found by the randomised stress run, and the
//! equivalence of the limiting-DoF-first synchronisation with the complete search.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shearcut_controllers::trajectory::{
    Synchronization, Trajectory, TrajectoryGenerator, TrajectoryInput, TrajectorySettings,
};

#[path = "support/random_cases.rs"]
#[allow(dead_code)]
mod random_cases;

fn stress_case_1() -> TrajectoryInput<4> {
    TrajectoryInput {
        current_position: [
            -7.983843541156279,
            5.514475894059214,
            0.5621786568449145,
            1.4501563520880336,
        ],
        current_velocity: [
            -0.1298530076635532,
            0.20621358506243456,
            0.2002348255204,
            0.9163852405790013,
        ],
        current_acceleration: [
            0.7790213650474722,
            -0.14315487657569487,
            -0.11385088484387045,
            0.0,
        ],
        target_position: [
            -1.5288075623699855,
            4.801316007022103,
            1.81804955399785,
            1.4114070696273613,
        ],
        target_velocity: [
            0.019594969667494497,
            1.3050242631466273,
            1.0384387581112302,
            0.0,
        ],
        target_acceleration: [0.7845466018754242, 0.0, 0.17329725894718004, 0.0],
        max_velocity: [
            11.875155810701175,
            6.840405355165078,
            6.135628158164082,
            11.317067025946727,
        ],
        max_acceleration: [
            11.10997499867274,
            9.828759851404408,
            2.3519766958186583,
            4.926933045876714,
        ],
        max_jerk: [
            8.529376578438141,
            9.115262586165178,
            0.5944723435838579,
            5.7547579437205805,
        ],
        ..Default::default()
    }
}

/// Found at 10⁶ stress cases: DoF 0 needs 2.931 s, but DoF 2 cannot take between ≈2.387 s and
/// 3.0729 s (a blocked interval: it either turns early or overshoots). The common duration is
/// the end of that interval, DoF 2's extremal profile of 3.072 885 995 s. The dense re-search of
/// the failing DoF must add to its candidates, not replace them, or that profile is lost (a
/// `Synchronization` error).
#[test]
fn blocked_interval_end_survives_the_dense_re_search() {
    let otg = TrajectoryGenerator::<4>::new(TrajectorySettings::default()).unwrap();
    let inp = stress_case_1();
    let mut none = inp;
    none.synchronization = Synchronization::None;
    let mut t = Trajectory::default();
    otg.calculate(&none, &mut t).unwrap();
    let independent = t.independent_min_durations();
    assert!(
        (independent[0] - 2.931_210_399_672_73).abs() < 1e-9,
        "{independent:?}"
    );
    otg.calculate(&inp, &mut t).unwrap();
    assert!(
        (t.duration() - 3.072_885_995_404_53).abs() < 1e-9,
        "{}",
        t.duration()
    );
    for i in 0..4 {
        let p = t.profile(i);
        let e = p.end();
        assert!((p.duration() - t.duration()).abs() < 1e-12 * (1.0 + t.duration()));
        assert!((e.position - inp.target_position[i]).abs() < 1e-8);
        assert!((e.velocity - inp.target_velocity[i]).abs() < 1e-8);
        assert!((e.acceleration - inp.target_acceleration[i]).abs() < 1e-10);
        let x = p.extrema();
        let lim = |l: f64| l * (1.0 + 1e-12);
        assert!(
            x.velocity.max <= lim(inp.max_velocity[i])
                && -x.velocity.min <= lim(inp.max_velocity[i])
        );
        assert!(
            x.acceleration.max <= lim(inp.max_acceleration[i])
                && -x.acceleration.min <= lim(inp.max_acceleration[i])
        );
    }
}

/// Oracle case 7531 of `scripts/otg_vs_ruckig.sh 100000 42`: ruckig synchronises in
/// 7.999 034 165 767 s. An attempted shortcut of the polynomial root isolation (bracketing a
/// root on a whole unimodal piece instead of between critical points) moved one root of a
/// near-quadruple-root quartic by 3e-12, the extremal profile it stands for failed
/// verification, and ours took 9.491 s. Every DoF starts inside its limits.
#[test]
fn oracle_case_7531_not_longer_than_ruckig() {
    let inp = TrajectoryInput::<3> {
        current_position: [-8.543967091913883, 0.16230390870749528, -0.8943028294075916],
        current_velocity: [1.5745485066470355, 0.2781619302188924, 1.20031340242475],
        current_acceleration: [
            -1.895808290759838,
            -0.7178758105272248,
            -0.24862798698320995,
        ],
        target_position: [-1.2362164937778077, 4.415295110205181, 2.126527044807395],
        target_velocity: [0.21491603613952026, 1.4225507375056736, 0.0],
        target_acceleration: [0.0, 0.29648001947275127, 0.18823824652215482],
        max_velocity: [5.000958065904342, 7.802183367284388, 11.980486451421795],
        max_acceleration: [10.065107992924668, 11.9912754151376, 11.75195414819332],
        max_jerk: [5.506726861949611, 8.485050682619178, 0.12446067465348118],
        ..Default::default()
    };
    let otg = TrajectoryGenerator::<3>::new(TrajectorySettings::default()).unwrap();
    let mut t = Trajectory::default();
    otg.calculate(&inp, &mut t).unwrap();
    let ruckig = 7.999_034_165_767_009;
    assert!(
        t.duration() <= ruckig + 1e-9 * ruckig,
        "ours {} > ruckig {ruckig}",
        t.duration()
    );
    for i in 0..3 {
        let e = t.profile(i).end();
        assert!((e.position - inp.target_position[i]).abs() < 1e-8);
        assert!((e.velocity - inp.target_velocity[i]).abs() < 1e-8);
        assert!((e.acceleration - inp.target_acceleration[i]).abs() < 1e-10);
    }
}

/// Time synchronisation solves the time-optimal problem only for the DoFs that may be
/// limiting, and only for their shortest profile, and asks the others for a profile of that
/// duration; the complete search solves every DoF (all extremal profiles) first. Phase
/// synchronisation of non-collinear inputs (random ones) falls back to the complete search,
/// so the two must agree bit for bit: the same durations and independent minimal durations
/// (the latter computed on demand for the DoFs not solved), and every DoF reaching its
/// target. (The three-arc family scans only profiles whose acceleration keeps its sign; when
/// it also scanned the others, duplicates of peak-family profiles found by another root
/// solve, the two searches once differed by 9e-12 s.)
/// Returns (compared, durations) counts.
fn limiting_first_equals_complete_search<const N: usize>(rng: &mut ChaCha8Rng) -> (usize, usize) {
    let otg = TrajectoryGenerator::<N>::new(TrajectorySettings::default()).unwrap();
    let (mut fast, mut complete) = (Trajectory::<N>::default(), Trajectory::<N>::default());
    let mut compared = 0;
    let mut durations = 0;
    let mut same = |a: f64, b: f64, what: &str, inp: &TrajectoryInput<N>| {
        assert_eq!(
            a.to_bits(),
            b.to_bits(),
            "{what}: {a} against {b} for {inp:?}"
        );
        durations += 1;
    };
    for _ in 0..300 {
        let mut inp = random_cases::random_input::<N, _>(rng);
        if inp.validate().is_err() {
            continue;
        }
        inp.synchronization = Synchronization::Time;
        let r_fast = otg.calculate(&inp, &mut fast);
        inp.synchronization = Synchronization::Phase;
        let r_complete = otg.calculate(&inp, &mut complete);
        assert_eq!(r_fast, r_complete, "{inp:?}");
        if r_fast.is_err() {
            continue;
        }
        same(fast.duration(), complete.duration(), "duration", &inp);
        let (a, b) = (
            fast.independent_min_durations(),
            complete.independent_min_durations(),
        );
        for i in 0..N {
            same(a[i], b[i], "independent duration", &inp);
            let e = fast.profile(i).end();
            assert!(
                (e.position - inp.target_position[i]).abs() < 1e-8,
                "{inp:?}"
            );
            assert!(
                (e.velocity - inp.target_velocity[i]).abs() < 1e-8,
                "{inp:?}"
            );
            assert!(
                (e.acceleration - inp.target_acceleration[i]).abs() < 1e-10,
                "{inp:?}"
            );
        }
        compared += 1;
    }
    (compared, durations)
}

#[test]
fn limiting_dof_first_equals_the_complete_search() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let counts = [
        limiting_first_equals_complete_search::<2>(&mut rng),
        limiting_first_equals_complete_search::<3>(&mut rng),
        limiting_first_equals_complete_search::<7>(&mut rng),
    ];
    let compared: usize = counts.iter().map(|c| c.0).sum();
    let durations: usize = counts.iter().map(|c| c.1).sum();
    assert!(compared > 800, "{compared}");
    eprintln!("{durations} durations bit-identical");
}
