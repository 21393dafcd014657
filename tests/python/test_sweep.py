# cablelab.sweep on a LocalCluster of two worker processes: the results come back in parameter
# order, identical to the serial loop, and a task that raises is reported with its parameters
# while the others are kept.
import numpy as np
import pytest

import cablelab

distributed = pytest.importorskip("distributed")


def pulley_run(m_left, m_right):
    """Half a second of the pulley scene: where the left mass is and what the cable pulls."""
    w = cablelab.World.load("pulley", m_left=m_left, m_right=m_right)
    w.run(0.5)
    return {"y_left": float(w.body_states()[0, 1]), "tension": float(w.cable_tensions()[0])}


GRID = [{"m_left": a, "m_right": b} for a in (1.0, 2.0) for b in (1.0, 1.5, 3.0)]


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def column(table, name):
    return np.asarray(table[name])


def test_sweep_equals_the_serial_loop_in_parameter_order(client):
    table = cablelab.sweep(pulley_run, GRID, client=client)
    serial = [pulley_run(**p) for p in GRID]
    assert len(table) == len(GRID)
    for key in ("m_left", "m_right"):
        assert np.array_equal(column(table, key), [p[key] for p in GRID])
    for key in ("y_left", "tension"):
        assert np.array_equal(column(table, key), [r[key] for r in serial]), key
    # Different masses really give different runs (a wrong order would show).
    assert len(set(column(table, "tension"))) == len(GRID)


def test_plain_values_come_back_as_a_list(client):
    assert cablelab.sweep(lambda x: x * x, range(7), client=client) == [x * x for x in range(7)]


def test_a_failing_task_is_reported_with_its_parameters(client):
    grid = [{"m_left": 1.0, "m_right": 2.0}, {"m_left": -1.0, "m_right": 2.0},
            {"m_left": 2.0, "m_right": 1.0}]
    with pytest.raises(cablelab.SweepError) as caught:
        cablelab.sweep(pulley_run, grid, client=client)
    e = caught.value
    assert [(i, p) for i, p, _ in e.failures] == [(1, grid[1])]
    assert "m_left" in e.failures[0][2] and "must be positive" in e.failures[0][2]
    assert "params[1] = {'m_left': -1.0, 'm_right': 2.0}" in str(e)
    assert e.results[1] is None
    assert e.results[0] == pulley_run(**grid[0]) and e.results[2] == pulley_run(**grid[2])


def test_a_progress_callable_counts_every_finished_task(client):
    calls = []
    assert cablelab.sweep(lambda x: -x, range(5), client=client,
                          progress=lambda done, total: calls.append((done, total))) == \
        [0, -1, -2, -3, -4]
    assert calls == [(k, 5) for k in range(1, 6)]
