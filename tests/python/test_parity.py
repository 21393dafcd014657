# The module gives the CLI's answers for the same inputs: run --csv bit for bit, the Atwood
# tension, statics p to 1e-12, wrap and fit (track and reach: test_hand_runs.py); and the same error message for bad input.
import json

import numpy as np
import pytest

import cablelab
from conftest import SOURCE_DIR, cli_error, cli_json, in_python_words, read_csv, run_cli


def run_csv(tmp_path, *args):
    out = tmp_path / "run.csv"
    r = run_cli("run", *args, "--csv", out)
    assert r.returncode == 0, r.stderr
    return read_csv(out)


def csv_state(header, row, world):
    """The CSV row as body states (n, 6) and cable columns (n, 3), by column name."""
    col = {name: i for i, name in enumerate(header)}
    bodies = np.array([[row[col[f"{b}.{c}"]] for c in ("x", "y", "theta", "vx", "vy", "omega")]
                       for b in world.body_names])
    cables = np.array([[row[col[f"{c}.{k}"]] for k in ("length", "tension", "wraps")]
                       for c in world.cable_names]).reshape(-1, 3)
    return bodies, cables


@pytest.mark.parametrize("scene,args", [
    ("pulley", ["--time", "2"]),
    ("hand", ["--time", "1"]),
    ("hexagon", ["--time", "1", "--dt", "0.01", "--substeps", "3"]),
    ("ballast", ["--time", "0.002", "--dt", "1e-5", "--set", "v0y=2"]),
])
def test_run_final_state_bit_for_bit(tmp_path, scene, args):
    header, rows = run_csv(tmp_path, scene, *args)
    params = {}
    if "--set" in args:
        name, value = args[args.index("--set") + 1].split("=")
        params[name] = float(value)
    w = cablelab.World.load(scene, **params)
    dt = float(args[args.index("--dt") + 1]) if "--dt" in args else None
    sub = int(args[args.index("--substeps") + 1]) if "--substeps" in args else None
    for _ in range(len(rows) - 1):
        w.step(dt=dt, substeps=sub)
    bodies, cables = csv_state(header, rows[-1], w)
    assert w.time == rows[-1][0]
    assert np.array_equal(w.body_states(), bodies)  # bit for bit
    assert np.array_equal(w.cable_lengths(), cables[:, 0])
    assert np.array_equal(w.cable_tensions(), cables[:, 1])
    assert np.array_equal(w.cable_wraps(), cables[:, 2])


def test_run_record_equals_csv_every_row(tmp_path):
    header, rows = run_csv(tmp_path, "pulley", "--time", "0.5")
    w = cablelab.World.load("pulley")
    rec = w.run(0.5, record=True)
    assert rec["t"].shape == (len(rows),)
    for k in range(len(rows)):
        bodies, cables = csv_state(header, rows[k], w)
        assert rec["t"][k] == rows[k][0]
        assert np.array_equal(rec["bodies"][k], bodies)
        assert np.array_equal(rec["cables"][k], cables)


def test_atwood_tension_equals_cli_and_theory(tmp_path):
    # The pulley scene is Atwood's machine over two ground pulleys: T = 2 g m1 m2 / (m1 + m2).
    m1, m2 = 3.0, 1.0
    header, rows = run_csv(tmp_path, "pulley", "--set", f"m_left={m1}", "--set", f"m_right={m2}", "--time", "0.5")
    w = cablelab.World.load("pulley", m_left=m1, m_right=m2)
    w.run(0.5)
    tension = w.cable_tensions()[0]
    assert tension == rows[-1][header.index("cable.tension")]
    g = -w.gravity[1]
    assert tension == pytest.approx(2 * g * m1 * m2 / (m1 + m2), rel=1e-3)


@pytest.mark.parametrize("name", ["two_cables.json", "on_fingertip.json"])
@pytest.mark.parametrize("solver", ["auto", "socp", "newton"])
def test_statics_equals_cli(name, solver):
    path = SOURCE_DIR / "tests" / "data" / "statics" / name
    expected = cli_json("statics", path, "--solver", solver)
    from_file = cablelab.statics(path, solver=solver)
    d = json.loads(path.read_text())
    from_dict = cablelab.statics(d, solver=solver)
    from_list = cablelab.statics(d["cables"], solver=solver, p0=d.get("p0"))
    for got in (from_file, from_dict, from_list):
        assert np.abs(got["p"] - expected["p"]).max() <= 1e-12
        assert np.allclose(got["tensions"], expected["tensions"], rtol=1e-12, atol=1e-12)
        assert np.allclose(got["lengths"], expected["lengths"], rtol=1e-12, atol=1e-12)
        assert got["energy"] == pytest.approx(expected["energy"], rel=1e-12, abs=1e-12)
        assert got["solver"] == expected["solver"] and got["iterations"] == expected["iterations"]
        assert set(got) == set(expected)


def test_statics_array_form_equals_list_form():
    cables = np.array([[0, 0, 3, 0, 10, 1], [-1, 1, -1, -1, 1, 1], [2, 2, 2, -2, 4, 0.5]], float)
    as_list = [{"a": list(c[:2]), "b": list(c[2:4]), "k": c[4], "L": c[5]} for c in cables]
    a, b = cablelab.statics(cables), cablelab.statics(as_list)
    assert np.array_equal(a["p"], b["p"])
    # and the equilibrium: no net force on p
    p = a["p"]
    force = sum(t * ((c[:2] - p) / np.linalg.norm(c[:2] - p) + (c[2:4] - p) / np.linalg.norm(c[2:4] - p))
                for t, c in zip(a["tensions"], cables))
    assert np.linalg.norm(force) < 1e-9 * max(a["tensions"])


@pytest.mark.parametrize("name", ["hexagon_left.json", "hexagon_right_cw.json", "square.json",
                                  "square_no_contact.json", "triangle_wrap_back.json"])
def test_wrap_equals_cli(name):
    path = SOURCE_DIR / "tests" / "data" / "wrap" / name
    expected = cli_json("wrap", path)
    d = json.loads(path.read_text())
    got = cablelab.wrap(d["A"], d["B"], d["polygon"], d["side"])
    assert np.array_equal(got["path"], np.array(expected["path"]))
    assert got["length"] == expected["length"]
    assert got["contact_vertices"] == expected["contact_vertices"]


def test_fit_equals_cli_for_csv_and_array():
    data = SOURCE_DIR / "assets" / "data" / "membrane_example.csv"
    expected = cli_json("fit", data, "--pulleys", "-0.2,0,0.2,0")
    array = np.loadtxt(data, delimiter=",", skiprows=1)
    for got in (cablelab.fit(data, (-0.2, 0, 0.2, 0)), cablelab.fit(array, [[-0.2, 0], [0.2, 0]])):
        for key in ("k", "preload", "rms_fy", "rms_angle_deg", "k_stderr", "preload_stderr",
                    "chi2_per_dof", "iterations", "rounds", "rows"):
            assert got[key] == expected[key], key
    # the same keys in the same order (the CLI's JSON), the time apart
    assert list(got)[:len(expected)] == list(expected)
    given = cli_json("fit", data, "--pulleys", "-0.2,0,0.2,0", "--sigma-fy", "0.05",
                     "--sigma-angle-deg", "1")
    got = cablelab.fit(data, "-0.2,0,0.2,0", sigma_fy=0.05, sigma_angle_deg=1)
    assert {k: v for k, v in got.items() if k in given and k != "fit_us"} == \
        {k: v for k, v in given.items() if k != "fit_us"}


FIT_OPTION_ERRORS = {
    "pulleys_coincide": ("0.1,0,0.1,0", {}, []),
    "pulleys_text": ("0.1,0,0.2", {}, []),
    "pulleys_nan": ("0.1,nan,0.2,0", {}, []),
    "sigma_fy": ("-0.2,0,0.2,0", dict(sigma_fy=-1), ["--sigma-fy", "-1"]),
    "sigma_angle": ("-0.2,0,0.2,0", dict(sigma_angle_deg=0), ["--sigma-angle-deg", "0"]),
}


@pytest.mark.parametrize("case", FIT_OPTION_ERRORS, ids=list(FIT_OPTION_ERRORS))
def test_bad_fit_options_same_message_as_cli(case):
    pulleys, kwargs, args = FIT_OPTION_ERRORS[case]
    data = SOURCE_DIR / "assets" / "data" / "membrane_example.csv"
    expected = cli_error("fit", data, "--pulleys", pulleys, *args)
    with pytest.raises(cablelab.InputError) as e:
        cablelab.fit(data, pulleys, **kwargs)
    assert str(e.value) == in_python_words(expected)


def test_membrane_data_equals_cli_generate(tmp_path):
    out = tmp_path / "gen.csv"
    cli_json("fit", "--generate", out, "--pulleys", "-0.2,0,0.2,0", "--k", "30", "--preload", "0.5",
             "--seed", "7", "--grid", "5x4")
    _, rows = read_csv(out)
    got = cablelab.membrane_data(30, 0.5, (-0.2, 0, 0.2, 0), seed=7, grid=(5, 4))
    assert np.array_equal(got, np.array(rows))


def bad_files(prefix):
    return sorted((SOURCE_DIR / "tests" / "data" / "bad").glob(prefix + "*"))


@pytest.mark.parametrize("path", bad_files("scene_"), ids=lambda p: p.name)
def test_bad_scene_same_message_as_cli(path):
    expected = cli_error("run", path, "--time", "0")
    with pytest.raises(cablelab.InputError) as e:
        cablelab.World.load(path)
    assert str(e.value) == expected
    assert expected.startswith(e.value.source + ": " + e.value.field + ": ")


@pytest.mark.parametrize("path", bad_files("statics_"), ids=lambda p: p.name)
def test_bad_statics_same_message_as_cli(path):
    expected = cli_error("statics", path)
    with pytest.raises(cablelab.InputError) as e:
        cablelab.statics(path)
    assert str(e.value) == expected


@pytest.mark.parametrize("path", bad_files("fit_"), ids=lambda p: p.name)
def test_bad_fit_same_message_as_cli(path):
    expected = cli_error("fit", path, "--pulleys", "-0.2,0,0.2,0")
    with pytest.raises(cablelab.InputError) as e:
        cablelab.fit(path, (-0.2, 0, 0.2, 0))
    assert str(e.value) == expected


@pytest.mark.parametrize("path", bad_files("wrap_"), ids=lambda p: p.name)
def test_bad_wrap_same_message_as_cli_with_source_wrap(path):
    expected = cli_error("wrap", path)
    d = json.loads(path.read_text())
    with pytest.raises(cablelab.InputError) as e:
        cablelab.wrap(d.get("A"), d.get("B"), d.get("polygon"), d.get("side"))
    assert str(e.value) == expected.replace(str(path), "wrap", 1)


def test_unknown_scene_parameter_names_the_keyword_and_the_clis_list():
    expected = cli_error("run", "pulley", "--set", "mass=2", "--time", "0")
    with pytest.raises(cablelab.InputError) as e:
        cablelab.World.load("pulley", mass=2)
    known = expected[expected.index("(known: "):expected.index(" (got ")]
    assert str(e.value) == "World.load: mass: no such keyword for scene 'pulley' " + known + \
        " (got mass=2)"
