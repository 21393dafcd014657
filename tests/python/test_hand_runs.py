# track() and reach() against `cablelab track` and `cablelab reach`: the same inputs give the
# same JSON fields and CSV columns to the bit, bad input the same message; the GIL is released.
import threading
import time

import numpy as np
import pytest

import cablelab
from conftest import cli_error, cli_json, in_python_words, read_csv

# Each case: CLI arguments, the same as track() keywords. Short runs (the hand scene steps at
# 60 Hz), starts off the target so that control has work to do.
TRACK_CASES = {
    "target_pd": (["--target", "0.2,0.1", "--time", "4"], dict(target=(0.2, 0.1), time=4)),
    "ramp_start_pid": (["--ramp", "0.3,-0.2,2", "--start", "-0.1,0.1", "--pid", "--time", "4"],
                       dict(ramp=(0.3, -0.2, 2), start=(-0.1, 0.1), pid=True, time=4)),
    "default_start": (["--time", "3"], dict(time=3)),  # target 0,0: start 0.1,0.1
    # a box that turns, to an angle target (x, y, theta)
    "turn_angle": (["--set", "turn=1", "--target", "0.1,0.05,0.2", "--pid", "--time", "6"],
                   dict(target=(0.1, 0.05, 0.2), pid=True, time=6,
                        hand=cablelab.HandModel(turn=True))),
    # model-predictive control (--controller is law= in Python: controller= holds the gains)
    "mpc": (["--target", "0.2,0.1", "--controller", "mpc", "--horizon", "5", "--time", "4"],
            dict(target=(0.2, 0.1), law="mpc", horizon=5, time=4)),
}
WALL_TIME_KEYS = {"controller_solve_us", "controller_solve_max_us"}


@pytest.mark.parametrize("case", TRACK_CASES, ids=list(TRACK_CASES))
def test_track_equals_cli_to_the_bit(case, tmp_path):
    args, kwargs = TRACK_CASES[case]
    csv = tmp_path / "t.csv"
    expected = cli_json("track", *args, "--csv", csv)
    got = cablelab.track(**kwargs)
    assert set(expected) <= set(got)
    for key in set(expected) - WALL_TIME_KEYS:
        assert got[key] == expected[key], key  # floats compared exactly
    assert got["controller"] == kwargs.get("law", "jacobian")
    header, rows = read_csv(csv)
    assert header == ["t", "target_x", "target_y", "x", "y", "target_angle", "angle"]
    rows = np.array(rows)
    assert np.array_equal(got["t"], rows[:, 0])
    assert np.array_equal(got["target"], rows[:, 1:3])
    assert np.array_equal(got["box"], rows[:, 3:5])
    assert np.array_equal(got["target_angle"], rows[:, 5])
    assert np.array_equal(got["angle"], rows[:, 6])
    assert got["final_error"] == np.linalg.norm(got["box"][-1] - got["target"][-1])
    assert got["final_angle_error"] == abs(got["angle"][-1] - got["target_angle"][-1])


def test_track_angle_target_turns_the_box_and_bad_angles_are_the_clis_errors():
    r = cablelab.track(target=(0.1, 0.05, 0.2), pid=True, hand=cablelab.HandModel(turn=True))
    assert r["final_error"] < 0.005 and r["final_angle_error"] < 0.02 and r["grasp_held"]
    assert r["final_angle"] == pytest.approx(0.2, abs=0.02)
    with pytest.raises(cablelab.InputError, match="THETA needs a box that may turn"):
        cablelab.track(target=(0.1, 0.05, 0.2))
    with pytest.raises(cablelab.InputError, match="2 or 3 finite numbers"):
        cablelab.track(target="1,2,3,4", hand=cablelab.HandModel(turn=True))


def test_track_start_and_result_fields_are_consistent():
    r = cablelab.track(target=(0.2, 0.1), start=(-0.1, 0.1), time=4, pid=True)
    assert r["start"] == [-0.1, 0.1]
    # the box starts where the grasp closes about (Box2D keeps poses in float)
    assert np.abs(r["box"][0] - r["start"]).max() < 1e-7
    assert r["grasp_held"] and r["losses"] == 0
    assert r["events"][0]["what"] == "grasp closed" and r["events"][0]["t"] == r["grasp_time"]
    # both are samples of the larger membrane tension: when control began, and its maximum after
    k = int(np.flatnonzero(r["tension"] == r["start_tension"])[0])
    assert r["t"][k] > r["grasp_time"] and r["start_tension"] > 0
    assert r["max_tension"] == r["tension"][k + 1:].max()
    assert r["final_joints"].shape == (6,)


def test_track_text_options_are_the_clis():
    by_text = cablelab.track(target="0.2,0.1", start="-0.1,0.1", time=2)
    by_numbers = cablelab.track(target=(0.2, 0.1), start=np.array([-0.1, 0.1]), time=2)
    assert np.array_equal(by_text["box"], by_numbers["box"])


def test_track_target_changes_step_the_target():
    r = cablelab.track(target=(0.2, 0.1), changes=[(2.0, (-0.1, 0.05))], time=4)
    before, after = r["t"] < 2.0 - 1e-9, r["t"] > 2.0 + 1e-9
    assert np.all(r["target"][before] == (0.2, 0.1))
    assert np.all(r["target"][after] == (-0.1, 0.05))
    assert r["final_error"] == np.linalg.norm(r["box"][-1] - (-0.1, 0.05))


def test_track_progress_is_reported_to_the_end():
    calls = []
    cablelab.track(target=(0.1, 0.0), time=2, progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (120, 120)
    assert all(a[0] <= b[0] for a, b in zip(calls, calls[1:]))


TRACK_ERRORS = {
    "target_and_ramp": (["--target", "1,1", "--ramp", "1,1,2"], dict(target=(1, 1), ramp=(1, 1, 2))),
    "ramp_seconds": (["--ramp", "0.1,0.1,0"], dict(ramp=(0.1, 0.1, 0))),
    "target_far": (["--target", "100,1"], dict(target=(100, 1))),
    "start_unpinchable": (["--start", "9,9"], dict(start=(9, 9))),
    "start_unpinchable_fraction": (["--start", "0.5,-2.25"], dict(start=(0.5, -2.25))),
    "time_negative": (["--time", "-1"], dict(time=-1)),
    "time_huge": (["--time", "1e6"], dict(time=1e6)),
    "target_text": (["--target", "1,2,3"], dict(target="1,2,3")),
    "ramp_text": (["--ramp", "1,2"], dict(ramp="1,2")),
    "start_text": (["--start", "1"], dict(start="1")),
}


def test_track_bad_changes_and_numbers():
    with pytest.raises(cablelab.InputError, match=r"^track: changes\[1\]: t must be"):
        cablelab.track(changes=[(2, (0, 0)), (1, (0, 0))])
    with pytest.raises(cablelab.InputError, match=r"^track: changes\[0\]: must be \(t, \(x, y\)\)"):
        cablelab.track(changes=[(2, 0, 0)])
    with pytest.raises(cablelab.InputError, match=r"^argument: target: must be \[x, y\]"):
        cablelab.track(target=(1, 2, 3, 4))  # (x, y) or (x, y, theta)
    with pytest.raises(cablelab.InputError, match=r"^argument: start\[0\]: must be finite"):
        cablelab.track(start=(float("nan"), 0))


# reach: the simulation is a full track run per target, so small grids; compare every field but
# the wall time, and the CSV's columns.
REACH_CASES = {
    "simulation_pid": (["--grid", "4"], dict(grid=4)),
    "simulation_pd": (["--grid", "3", "--pd"], dict(grid=3, pd=True)),
    "quasi_static": (["--grid", "7", "--model", "quasi-static"], dict(grid=7, model="quasi-static")),
    "simulation_mpc": (["--grid", "3", "--controller", "mpc"], dict(grid=3, law="mpc")),
}


@pytest.mark.parametrize("case", REACH_CASES, ids=list(REACH_CASES))
def test_reach_equals_cli(case, tmp_path):
    args, kwargs = REACH_CASES[case]
    csv = tmp_path / "r.csv"
    expected = cli_json("reach", *args, "--csv", csv)
    got = cablelab.reach(threads=expected["threads"], **kwargs)
    for key in expected:
        if key != "seconds":  # wall time
            assert got[key] == expected[key], key
    header, rows = read_csv(csv)
    assert header == ["x", "y", "object_reached", "fingertip_reachable"]
    rows = np.array(rows)
    t = got["targets"]
    for i, column in enumerate(header):
        assert np.array_equal(t[column], rows[:, i]), column


def test_reach_targets_agree_with_the_sets_and_track():
    r = cablelab.reach(grid=4, threads=2)
    t = r["targets"]
    n = r["points"]
    assert n == 16 and all(len(v) == n for v in t.values())
    assert np.array_equal(t["object_reached"], t["simulated"])
    # simulated: reached within 5 mm with the grasp held
    assert np.all(t["simulated"] == (t["grasp_held"] & (t["error"] < 0.005)))
    assert np.array_equal(r["object_set"], np.column_stack([t["x"], t["y"]])[t["object_reached"]])
    assert r["object_points"] == len(r["object_set"]) == t["object_reached"].sum()
    assert r["fingertip_points"] == t["fingertip_reachable"].sum()
    cell = np.prod((np.array(r["upper"]) - r["lower"]) / 4)
    assert r["object_area"] == pytest.approx(r["object_points"] * cell, rel=1e-12)
    assert r["beyond_fingertips"] == (t["object_reached"] & ~t["fingertip_reachable"]).sum()
    assert r["simulated_s"] == pytest.approx(t["simulated_time"].sum(), rel=1e-12)
    # a reached target is reached by track(): the same run, without the early stop
    k = int(np.flatnonzero(t["simulated"])[0])
    run = cablelab.track(target=(t["x"][k], t["y"][k]), pid=True)
    assert run["grasp_held"] and run["final_error"] < 0.005


REACH_ERRORS = {
    "grid_zero": (["--grid", "0"], dict(grid=0)),
    "grid_big": (["--grid", "1001"], dict(grid=1001)),
    "model": (["--model", "dynamic"], dict(model="dynamic")),
}


# Every bad option, for both commands: the CLI's one line, and the same InputError text in
# Python's words.
BAD_OPTIONS = {**{"track." + k: ("track", *v) for k, v in TRACK_ERRORS.items()},
               **{"reach." + k: ("reach", *v) for k, v in REACH_ERRORS.items()}}


@pytest.mark.parametrize("case", BAD_OPTIONS, ids=list(BAD_OPTIONS))
def test_bad_options_same_message_as_cli(case):
    command, args, kwargs = BAD_OPTIONS[case]
    expected = cli_error(command, *args)
    with pytest.raises(cablelab.InputError) as e:
        getattr(cablelab, command)(**kwargs)
    # The same words, with the option named as the keyword (issue 39: never "--" or
    # "command line" in Python).
    assert str(e.value) == in_python_words(expected)
    assert str(e.value).startswith(e.value.source + ": " + e.value.field + ": ")


def test_reach_bad_threads():
    with pytest.raises(cablelab.InputError, match=r"^reach: threads: must be a whole number in \[1, 256\] \(got 0\)"):
        cablelab.reach(grid=2, threads=0)


def ticks_while(call):
    """Runs call() in a thread; counts 5 ms sleeps of this thread meanwhile (none if call held
    the GIL throughout). Returns (ticks, seconds)."""
    worker = threading.Thread(target=call)
    start = time.perf_counter()
    worker.start()
    ticks = 0
    while worker.is_alive():
        time.sleep(0.005)
        ticks += 1
    worker.join()
    return ticks, time.perf_counter() - start


@pytest.mark.parametrize("call", [
    lambda: cablelab.track(target=(0.2, 0.1), time=400),
    lambda: cablelab.reach(grid=12, model="quasi-static", threads=1),
], ids=["track", "reach"])
def test_runs_release_the_gil(call):
    ticks, seconds = ticks_while(call)
    assert seconds > 0.2, "the run is too short to tell"
    assert ticks > 0.25 * seconds / 0.005


def test_ctrl_c_stops_a_long_track():
    import os
    import signal
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        cablelab.track(target=(0.2, 0.1), time=1e5)  # 6e6 steps: minutes
    timer.join()
    assert time.perf_counter() - start < 30
    assert cablelab.track(target=(0.2, 0.1), time=0.5)["t"].shape == (31,)  # still usable


def test_ctrl_c_stops_a_long_reach():
    import os
    import signal
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        cablelab.reach(grid=50, threads=2)  # 2500 simulated runs: minutes
    timer.join()
    assert time.perf_counter() - start < 30
    assert cablelab.reach(grid=2, model="quasi-static")["points"] == 4  # still usable


def test_track_law_mpc_arrives_sooner_and_bad_laws_are_errors():
    # MPC against the Jacobian controller (PID) on one target: measured 0.83 s against no arrival
    # within the 5 s run (docs/control.md#model-predictive-control).
    mpc = cablelab.track(target=(0.2, 0.1), time=5, law="mpc")
    pid = cablelab.track(target=(0.2, 0.1), time=5, pid=True)
    assert mpc["controller"] == "mpc" and pid["controller"] == "jacobian"
    assert mpc["time_to_5mm"] is not None and mpc["time_to_5mm"] < 2.0
    assert pid["time_to_5mm"] is None or pid["time_to_5mm"] > 2 * mpc["time_to_5mm"]
    assert mpc["grasp_held"] and mpc["final_error"] < 0.005
    with pytest.raises(cablelab.InputError, match=r"law: must be jacobian or mpc \(got \"pid\"\)"):
        cablelab.track(law="pid")
    with pytest.raises(cablelab.InputError, match=r"horizon: must be a whole number in \[1, 40\]"):
        cablelab.reach(grid=2, law="mpc", horizon=0)
