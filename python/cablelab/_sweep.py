"""cablelab.sweep: one task over a grid of parameters on Dask (a LocalCluster or any Client).

Each task runs in a worker process, so the grid needs no GIL and scales to a lab's machines or
an HPC job through one scheduler address (`dask scheduler` / `dask worker ADDRESS`). A failing
task does not stop the others: its exception is caught on the worker, the rest finish, and
SweepError names the failed parameters at the end (docs/python.md, "Sweeps").
"""

import os
import sys
import traceback


class SweepError(RuntimeError):
    """Some tasks of a sweep raised. str(e) names each failed parameter set and its error;
    e.failures is [(index, params, error text)], e.results the results in parameter order with
    None where a task failed."""

    def __init__(self, failures, results):
        lines = [f"sweep: {len(failures)} of {len(results)} tasks failed:"]
        lines += [f"  params[{i}] = {p!r}: {error.strip().splitlines()[-1]}"
                  for i, p, error in failures]
        super().__init__("\n".join(lines))
        self.failures = failures
        self.results = results


def _run_one(task, p):
    """On the worker: (True, result) or (False, the traceback as text); exceptions stay here
    (they need not pickle, and one failure must not cancel the sweep)."""
    try:
        return True, task(**p) if isinstance(p, dict) else task(p)
    except Exception:
        return False, traceback.format_exc()


def _machine_cores():
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def _local_client():
    from distributed import Client, LocalCluster
    cluster = LocalCluster(n_workers=_machine_cores(), threads_per_worker=1, processes=True,
                           dashboard_address=None)
    return Client(cluster)


def _count_on_stderr(done, total):
    print(f"\rsweep: {done}/{total} tasks done", end="\n" if done == total else "",
          file=sys.stderr, flush=True)


def _gather_in_order(client, futures, report):
    """The (ok, value) pairs in submission order; report(done, total) as they finish."""
    from distributed import as_completed
    index = {f.key: i for i, f in enumerate(futures)}
    out = [None] * len(futures)
    for done, future in enumerate(as_completed(futures), 1):
        out[index[future.key]] = future.result()
        if report:
            report(done, len(futures))
    return out


def _table(params, results):
    """One row per parameter set: the parameters' keys (or "param") then the result's keys; a
    pandas DataFrame when pandas is installed, else a numpy structured array."""
    rows = []
    for p, r in zip(params, results):
        row = dict(p) if isinstance(p, dict) else {"param": p}
        row.update(r)
        rows.append(row)
    columns = list(dict.fromkeys(key for row in rows for key in row))
    try:
        import pandas
        return pandas.DataFrame(rows, columns=columns)
    except ImportError:
        pass
    import numpy
    values = {c: numpy.asarray([row.get(c) for row in rows]) for c in columns}
    dtype = [(str(c), v.dtype if v.dtype.kind in "biuf" else object) for c, v in values.items()]
    table = numpy.empty(len(rows), dtype=dtype)
    for c, v in values.items():
        table[str(c)] = v
    return table


def sweep(task, params, client=None, progress=None):
    """sweep(task, params, client=None, progress=None) -> list | table

    Runs task(p) (task(**p) when p is a dict) for every p in params on Dask and returns the
    results in the order of params: a table (pandas DataFrame if pandas is installed, else a
    numpy structured array; one row per p, columns the keys of p then those of the result)
    when every task returns a dict, else a list. client=None starts a LocalCluster with one
    single-threaded worker process per core for this call; a distributed.Client runs on its
    workers instead (any scheduler address). task and params are pickled to the workers
    (cloudpickle: a function defined in a script or a lambda travels too). progress: a count
    on stderr (True), none (False), or a callable progress(done, total) called as tasks
    finish; default: the count when stderr is a terminal. Tasks that raise do not stop the others:
    SweepError at the end names their parameters and errors and holds the other results.
    """
    params = list(params)
    if not callable(task):
        raise TypeError(f"sweep: task: must be callable (got {type(task).__name__})")
    if progress is None:
        progress = sys.stderr.isatty()
    report = progress if callable(progress) else _count_on_stderr if progress else None
    own = client is None
    if own:
        client = _local_client()
    try:
        futures = [client.submit(_run_one, task, p, pure=False) for p in params]
        outcomes = _gather_in_order(client, futures, report)
    finally:
        if own:
            cluster = client.cluster
            client.close()
            cluster.close()
    results = [value if ok else None for ok, value in outcomes]
    failures = [(i, params[i], value) for i, (ok, value) in enumerate(outcomes) if not ok]
    if failures:
        raise SweepError(failures, results)
    if results and all(isinstance(r, dict) for r in results):
        return _table(params, results)
    return results
