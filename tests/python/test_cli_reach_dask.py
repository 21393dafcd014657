# `cablelab reach --scheduler ADDRESS` (app/reach_on_dask.cpp, python/cablelab/_reach_on_dask.py):
# against a Dask scheduler this test starts (a LocalCluster of two worker processes) the CSV is
# byte for byte and the JSON field for field that of plain `reach` (only the wall time and the
# threads used differ); an address where no scheduler answers is the one-line error, exit 2.
import json

import pytest

from conftest import run_cli

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def scheduler():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    yield cluster.scheduler_address
    cluster.close()


def reach(tmp_path, name, *args):
    csv = tmp_path / f"{name}.csv"
    r = run_cli("reach", "--csv", csv, *args)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""  # no progress bar on a pipe, no Dask log lines
    return json.loads(r.stdout), csv.read_bytes()


@pytest.mark.parametrize("options", [["--grid", "4"], ["--grid", "6", "--model", "quasi-static",
                                                       "--pd"]])
def test_reach_on_dask_equals_plain_reach(tmp_path, scheduler, options):
    plain, plain_csv = reach(tmp_path, "plain", *options)
    dask, dask_csv = reach(tmp_path, "dask", *options, "--scheduler", scheduler)
    assert dask_csv == plain_csv
    assert dask["threads"] == 2  # the cluster's two single-threaded workers
    timing = ("seconds", "threads")
    assert {k: v for k, v in dask.items() if k not in timing} == \
           {k: v for k, v in plain.items() if k not in timing}
    # A grid where something is reached and something is not (an empty map would prove little).
    rows = plain_csv.decode().splitlines()[1:]
    assert {r.split(",")[2] for r in rows} == {"0", "1"}


def test_an_address_without_a_scheduler_is_one_line_exit_2():
    r = run_cli("reach", "--grid", "2", "--scheduler", "tcp://127.0.0.1:9")
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr.splitlines() == [
        'command line: --scheduler: no Dask scheduler answers there (got "tcp://127.0.0.1:9")']
