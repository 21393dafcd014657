# The package (issue 39, item 3): pip installs it into a fresh venv with no network, importable
# from outside the tree with its version, stubs and signatures; mypy passes on the examples; a
# Python without numpy gets an ImportError that says so.
import inspect
import os
import pathlib
import subprocess
import sys

import cablelab

SOURCE = pathlib.Path(os.environ.get("CABLELAB_SOURCE_DIR", pathlib.Path(__file__).parents[2]))


def version_in_source():
    text = (SOURCE / "python" / "cablelab" / "_version.py").read_text()
    return text.split('__version__ = "')[1].split('"')[0]


def test_version_and_signatures():
    assert cablelab.__version__ == version_in_source()
    step = inspect.signature(cablelab.World.step)
    assert list(step.parameters) == ["self", "dt", "substeps"]
    assert step.parameters["dt"].default is None
    run = inspect.signature(cablelab.World.run)
    assert run.parameters["steps"].kind is inspect.Parameter.KEYWORD_ONLY
    assert list(inspect.signature(cablelab.World.load).parameters) == ["scene", "params"]
    assert "Advances by dt seconds" in cablelab.World.step.__doc__


def test_a_python_without_numpy_is_told_so():
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(cablelab.__file__).parents[1]))
    r = subprocess.run([sys.executable, "-S", "-c", "import cablelab"], capture_output=True,
                       text=True, env=env, cwd="/")
    assert r.returncode != 0
    last = r.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: cablelab needs numpy") and sys.executable in last


def test_mypy_passes_on_the_examples():
    r = subprocess.run([sys.executable, "-m", "mypy"], capture_output=True, text=True, cwd=SOURCE)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "Success: no issues found in" in r.stdout


def test_pip_installs_into_a_fresh_venv(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    python = venv / "bin" / "python"
    # The CMake tree ctest runs in (CABLELAB_BUILD_DIR) is reused, so this installs what the
    # build already made; without it setup.py configures and builds build-pip/ from scratch.
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    r = subprocess.run([str(python), "-m", "pip", "install", "--no-build-isolation", "--no-index",
                        "--no-cache-dir", "-q", str(SOURCE)], capture_output=True, text=True,
                       env=env, timeout=1800)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    probe = ("import cablelab, inspect, numpy as np\n"
             "w = cablelab.World.load('pulley', m_left=2.0)\n"
             "w.run(steps=10)\n"
             "print(cablelab.__file__)\n"
             "print(cablelab.__version__)\n"
             "print(list(inspect.signature(cablelab.World.step).parameters))\n"
             "print(w.step_count, np.isfinite(w.body_states()).all())\n")
    out = subprocess.run([str(python), "-c", probe], capture_output=True, text=True, env=env,
                         cwd=tmp_path, check=True).stdout.splitlines()
    site = pathlib.Path(subprocess.run(
        [str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['platlib'])"],
        capture_output=True, text=True, check=True).stdout.strip())
    assert pathlib.Path(out[0]).parent == site / "cablelab"  # the installed copy, not the tree
    assert out[1] == version_in_source()
    assert out[2] == "['self', 'dt', 'substeps']"
    assert out[3] == "10 True"
    installed = {p.name for p in (site / "cablelab").iterdir()}
    assert {"py.typed", "_core.pyi", "__init__.py"} <= installed
    assert any(n.startswith("_core") and n.endswith(".so") for n in installed)
