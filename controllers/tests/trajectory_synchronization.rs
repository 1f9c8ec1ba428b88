//! Regression cases of the time synchronisation found by the randomised stress run.

use shearcut_controllers::trajectory::{
    Synchronization, Trajectory, TrajectoryGenerator, TrajectoryInput, TrajectorySettings,
};

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
/// the failing DoF used to *replace* its candidates and lost that profile (a `Synchronization`
/// error).
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
