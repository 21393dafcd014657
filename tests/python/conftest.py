# Shared fixtures of the Python tests: the CLI to compare against, the repo, a CSV reader.
# ctest sets PYTHONPATH (build/python), CABLELAB_CLI and CABLELAB_SOURCE_DIR; run by hand:
#   PYTHONPATH=build/python CABLELAB_CLI=build/bin/cablelab /usr/bin/python3 -m pytest tests/python
import csv
import json
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("CABLELAB_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
CLI = os.environ.get("CABLELAB_CLI", str(SOURCE_DIR / "build" / "bin" / "cablelab"))


def run_cli(*args, cwd=None):
    """Runs the cablelab CLI; returns the CompletedProcess (text)."""
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=600)


def cli_json(*args):
    """The CLI's JSON output (asserting exit 0)."""
    r = run_cli(*args)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def cli_error(*args):
    """The one stderr line of a CLI call that must fail with exit code 2."""
    r = run_cli(*args)
    assert r.returncode == 2, (r.returncode, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    return lines[0]


def in_python_words(cli_line):
    """The CLI's one-line error as the module words it: the option as a keyword ("command line:
    --sigma-fy: ..." -> "argument: sigma_fy: ...")."""
    source, option, detail = cli_line.split(": ", 2)
    assert source == "command line", cli_line
    return "argument: " + option.lstrip("-").replace("-", "_") + ": " + detail


def read_csv(path):
    """header, rows as lists of floats (float() reads %.17g back to the same double)."""
    with open(path) as f:
        reader = csv.reader(f)
        header = next(reader)
        return header, [[float(v) for v in row] for row in reader]


@pytest.fixture
def source_dir():
    return SOURCE_DIR


def pytest_report_header(config):
    import cablelab
    return f"cablelab module: {cablelab.__file__}; CLI: {CLI}"
