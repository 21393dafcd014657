# The hand's membrane friction through Python (HandModel(mu=...), the scene's `mu`): track() with
# friction and a box that turns equals `cablelab track --set mu=... --set turn=1` to the bit, the
# world it builds grips the box's corners, and a bad mu is the CLI's error in Python's words.
import numpy as np
import pytest

import cablelab
from conftest import cli_json, read_csv


def test_track_with_friction_equals_the_cli_to_the_bit(tmp_path):
    csv = tmp_path / "t.csv"
    expected = cli_json("track", "--set", "mu=0.5", "--set", "turn=1", "--target", "0.1,0.05,0.2",
                        "--pid", "--time", "6", "--csv", csv)
    got = cablelab.track(target=(0.1, 0.05, 0.2), pid=True, time=6,
                         hand=cablelab.HandModel(mu=0.5, turn=True))
    for key in expected.keys() - {"controller_solve_us", "controller_solve_max_us"}:  # wall times
        assert got[key] == expected[key], key  # floats compared exactly
    _, rows = read_csv(csv)
    rows = np.array(rows)
    assert np.array_equal(got["box"], rows[:, 3:5])
    assert np.array_equal(got["angle"], rows[:, 6])
    # friction changes the run: not the frictionless one
    plain = cablelab.track(target=(0.1, 0.05, 0.2), pid=True, time=6,
                           hand=cablelab.HandModel(turn=True))
    assert not np.array_equal(plain["box"], got["box"])


def test_mu_defaults_to_the_thesis_and_grips_the_box_corners():
    assert cablelab.HandModel().mu == 0.0
    world = cablelab.HandModel(mu=0.5, turn=True).world()
    for _ in range(30):
        world.step()
    # each membrane is split at the box's corners into two spans with their own tensions
    for name in cablelab.HAND_CABLES:
        spans = world.cable_span_tensions(name)
        assert len(spans) == 2 and min(spans) > 0
    frictionless = cablelab.HandModel(turn=True).world()
    frictionless.step()
    assert len(frictionless.cable_span_tensions(cablelab.HAND_CABLES[0])) == 1


def test_negative_mu_is_rejected():
    with pytest.raises((cablelab.InputError, ValueError), match="mu"):
        cablelab.HandModel(mu=-0.5)


def test_mpc_turns_the_box_to_an_angle_target_as_the_cli_does():
    # law="mpc" with an angle target (it was refused): the CLI's run, to the bit, at the angle.
    expected = cli_json("track", "--set", "mu=0.5", "--set", "turn=1", "--target", "0.1,0.05,0.2",
                        "--controller", "mpc", "--time", "4")
    got = cablelab.track(target=(0.1, 0.05, 0.2), law="mpc", time=4,
                         hand=cablelab.HandModel(mu=0.5, turn=True))
    for key in expected.keys() - {"controller_solve_us", "controller_solve_max_us"}:  # wall times
        assert got[key] == expected[key], key
    assert got["controller"] == "mpc"
    assert got["final_error"] < 0.005 and got["final_angle_error"] < 0.02
