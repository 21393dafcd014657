"""The Dask side of `cablelab reach --scheduler ADDRESS` (app/reach_on_dask.cpp runs it as
`python3 -m cablelab._reach_on_dask`): the grid's rows as tasks of cablelab.sweep on the
scheduler's workers, each target evaluated by the engine's own per-target code, so the CLI's
JSON and CSV equal those of the run on its own threads (docs/cli.md, "reach on Dask").

It speaks one JSON object per line on stdout, read by the CLI:
  {"threads": N}                 the workers' threads, once connected
  {"progress": [done, total]}    rows finished
  {"targets": [[index, simulated, quasi_static, error, grasp_held, simulated_time], ...]}
  {"error": "..."}               the scheduler cannot be reached (exit 2)
  {"failed": "..."}              tasks raised on the workers (exit 1)
"""

import argparse
import json
import sys

import cablelab
from cablelab import _core


def _emit(message):
    print(json.dumps(message), flush=True)


def reach_row(row, grid, model, pd):
    """One grid row's targets, as the CLI's own run evaluates them."""
    indices = list(range(row * grid, (row + 1) * grid))
    return [list(t) for t in _core._reach_targets(indices, grid=grid, model=model, pd=pd)]


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m cablelab._reach_on_dask")
    parser.add_argument("--scheduler", required=True)
    parser.add_argument("--grid", type=int, required=True)
    parser.add_argument("--model", required=True)
    parser.add_argument("--pd", action="store_true")
    parser.add_argument("--timeout", type=float, default=10.0, help="s to wait for the scheduler")
    args = parser.parse_args(argv)

    from distributed import Client
    try:
        client = Client(args.scheduler, timeout=args.timeout)
    except (OSError, ValueError, TypeError) as e:  # refused, timed out, not an address
        print(f"{type(e).__name__}: {e}", file=sys.stderr)
        _emit({"error": "no Dask scheduler answers there"})
        return 2
    with client:
        try:
            client.wait_for_workers(1, timeout=args.timeout)
        except Exception as e:  # asyncio's or the builtin TimeoutError, by version
            print(f"{type(e).__name__}: {e}", file=sys.stderr)
            _emit({"error": "the scheduler has no workers"})
            return 2
        _emit({"threads": sum(client.nthreads().values())})
        rows = [{"row": r, "grid": args.grid, "model": args.model, "pd": args.pd}
                for r in range(args.grid)]
        def report(done, total):
            _emit({"progress": [done, total]})

        try:
            results = cablelab.sweep(reach_row, rows, client=client, progress=report)
        except cablelab.SweepError as e:  # the first failure's last line says why
            why = e.failures[0][2].strip().splitlines()[-1]
            _emit({"failed": f"{str(e).splitlines()[0]} {why}"})
            return 1
    _emit({"targets": [target for row in results for target in row]})
    return 0


if __name__ == "__main__":
    sys.exit(main())
