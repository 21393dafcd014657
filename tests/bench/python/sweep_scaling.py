"""How cablelab.sweep scales from 1 to 2 Dask worker processes: `cablelab track` to 24 hand
targets (a 6 x 4 grid), on a LocalCluster of 1 and then of 2 single-threaded workers (cluster start
not timed; the median of --repeats sweeps on each). Prints both times and the ratio (2.0 is
perfect scaling on two idle cores). Not a test: run it by hand on a quiet machine.

    PYTHONPATH=build-dev/python /usr/bin/python3 tests/bench/python/sweep_scaling.py [--time 4]
"""
import argparse
import statistics
import time

from distributed import Client, LocalCluster

import cablelab


def track_error(x, y, seconds):
    r = cablelab.track(target=[x, y], time=seconds)
    return {"final_error": r["final_error"], "max_tension": r["max_tension"]}


def timed_sweeps(workers, params, repeats):
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        cablelab.sweep(track_error, params[:workers], client=client)  # warm-up: imports
        times, table = [], None
        for _ in range(repeats):
            start = time.perf_counter()
            table = cablelab.sweep(track_error, params, client=client)
            times.append(time.perf_counter() - start)
    return statistics.median(times), table


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--time", type=float, default=4.0, help="simulated seconds per target")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    params = [{"x": -0.05 + 0.02 * i, "y": 0.25 + 0.03 * j, "seconds": args.time}
              for i in range(6) for j in range(4)]
    t1, a = timed_sweeps(1, params, args.repeats)
    t2, b = timed_sweeps(2, params, args.repeats)
    assert list(a["final_error"]) == list(b["final_error"])
    print(f"sweep of {len(params)} hand targets ({args.time:g} s each): 1 worker {t1:.2f} s, "
          f"2 workers {t2:.2f} s; ratio {t1 / t2:.2f}x")


if __name__ == "__main__":
    main()
