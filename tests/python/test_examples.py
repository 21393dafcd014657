# The examples run headless (Agg, OSMesa) as a user runs them, and their answers are right.
import json
import os
import pathlib
import subprocess
import sys

import numpy as np

import cablelab
from conftest import SOURCE_DIR, cli_json

EXAMPLES = SOURCE_DIR / "examples"


def run_example(name, tmp_path, *args):
    env = dict(os.environ, MPLBACKEND="Agg")
    env.pop("DISPLAY", None)
    r = subprocess.run([sys.executable, str(EXAMPLES / name), "--out", str(tmp_path), "--quick", *args],
                       capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr
    result = json.loads(r.stdout.strip().splitlines()[-1])
    if "plot" in result:
        import matplotlib.image
        img = matplotlib.image.imread(result["plot"])
        assert img.shape[0] > 100 and img.std() > 0.01  # a real picture, not a blank page
    return result


def test_atwood_sweep_matches_theory(tmp_path):
    r = run_example("atwood_sweep.py", tmp_path)
    assert r["masses"] == 4
    assert r["max_tension_rel_error"] < 1e-3
    assert r["max_accel_error"] < 1e-3


def test_membrane_fit_equals_cli_and_recovers_the_parameters(tmp_path):
    r = run_example("membrane_fit.py", tmp_path)
    cli = cli_json("fit", SOURCE_DIR / "assets/data/membrane_example.csv", "--pulleys", "-0.2,0,0.2,0")
    assert r["k"] == cli["k"] and r["preload"] == cli["preload"]
    # generated with k = 25 N/m, preload 0.8 m (assets/data/membrane_example.json)
    assert abs(r["k"] - 25) < 4 * r["k_stderr"]
    assert abs(r["preload"] - 0.8) < 4 * r["preload_stderr"]


def test_python_hand_controller_reaches_the_target(tmp_path):
    r = run_example("hand_controller.py", tmp_path)
    assert r["grasp_held"] and r["losses"] == 0
    assert r["events"][0]["what"] == "grasp closed"
    assert r["start_error"] > 0.05
    assert r["final_error"] < 0.1 * r["start_error"]
    if cablelab.HAS_RENDERER:
        assert (tmp_path / "hand_final.png").stat().st_size > 1000


def test_parallel_reach_equals_serial_runs(tmp_path):
    r = run_example("parallel_reach.py", tmp_path)
    assert len(r["targets"]) == 9
    for (x, y), error in list(zip(r["targets"], r["final_errors"]))[::4]:
        assert cablelab.track(target=(x, y), time=r["seconds_per_target"], pid=True)["final_error"] == error
    assert r["reached"] == sum(e < 0.005 and h for e, h in zip(r["final_errors"], r["grasp_held"]))


def test_design_sweep_on_dask_equals_serial_reach_maps_and_tension_widens_the_reach(tmp_path):
    r = run_example("design_sweep.py", tmp_path)
    rows = [dict(zip(r["columns"], row)) for row in r["rows"]]
    designs = [(row["k"], row["preload"]) for row in rows]
    assert designs == [(30.0, 0.05), (30.0, 1.0), (600.0, 0.05), (600.0, 1.0)]
    for row in rows:  # each design's map, computed here serially, is the one the cluster gave
        serial = cablelab.reach(grid=r["grid"], model=r["model"], threads=2,
                                hand=cablelab.HandModel(k=row["k"], preload=row["preload"]))
        assert row["object_area"] == serial["object_area"]
        assert row["object_points"] == serial["object_points"]
    # A slack membrane (soft and barely preloaded) holds the box over less ground; more
    # stiffness or more preload widens the reach, up to the same saturated set.
    area = dict(zip(designs, (row["object_area"] for row in rows)))
    assert area[30.0, 0.05] < area[30.0, 1.0] and area[30.0, 0.05] < area[600.0, 0.05]
    assert area[600.0, 1.0] >= max(area[30.0, 1.0], area[600.0, 0.05])
