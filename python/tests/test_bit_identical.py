"""A closed loop driven from Python reproduces the Rust in-process run
(`shearcut run loop-potato-whole-realtime --controller mpc --transport
inproc`, which `shearcut.run` calls) bit for bit: same ticks, same end, and
at every tick from the first contact the same time, knife position, forces,
work and crack depth (compared with ==, i.e. every bit of every float)."""

import struct

import numpy as np


def bits(x):
    return struct.pack("<d", x)


def test_the_python_loop_ends_where_the_rust_run_ends(main_job):
    _, _, summary, end, rows = main_job
    assert summary["end"] == "completed" == end
    assert summary["ticks"] == len(rows)
    assert summary["limit_faults"] == 0
    assert all(r.status == "moving" for r, _, _ in rows)


def test_every_sample_is_bit_identical(main_job):
    _, series, _, _, rows = main_job
    by_time = {bits(r.time): (r, t) for r, t, _ in rows}
    n = len(series["time_s"])
    assert n > 100
    # The samples are the last n ticks, contiguous from the first contact.
    assert [bits(x) for x in series["time_s"]] == [bits(r.time) for r, _, _ in rows[-n:]]
    for k in range(n):
        reading, truth = by_time[bits(series["time_s"][k])]
        assert bits(series["force_vertical_n"][k]) == bits(truth.force[1])
        assert bits(series["work_j"][k]) == bits(truth.work)
        assert bits(series["crack_depth_m"][k]) == bits(truth.crack_depth)
        assert bits(series["contact_length_m"][k]) == bits(truth.contact_length)
        assert bits(series["deformation_m"][k]) == bits(truth.deformation)
        assert bits(series["torque_x_nm"][k]) == bits(reading.wrench[3])


def test_the_summary_is_bit_identical(main_job):
    _, _, summary, _, rows = main_job
    n = len(main_job[1]["time_s"])
    cut = rows[-n:]
    assert bits(summary["work_j"]) == bits(rows[-1][1].work)
    peak_fv = max(0.0, max(t.force[1] for _, t, _ in cut))
    peak_fh = max(0.0, max(abs(t.force[2]) for _, t, _ in cut))
    assert bits(summary["peak_force_vertical_n"]) == bits(peak_fv)
    assert bits(summary["peak_force_horizontal_n"]) == bits(peak_fh)
    assert bits(summary["cut_depth_m"]) == bits(rows[-1][1].crack_depth)


def test_the_plan_series_is_the_python_controllers(main_job):
    _, series, _, _, rows = main_job
    assert len(series["plan_xi"]) == len(rows)
    xi = np.array([m.slice_push_ratio for _, _, m in rows])
    assert np.array_equal(series["plan_xi"], xi)
    # The MPC slices: its plan leaves pressing (xi = 0) behind.
    assert xi.max() > 0.3
