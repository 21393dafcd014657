#!/usr/bin/env python3
"""Figure 4-4 by brute force in Python: every target of a grid is a full simulated run of the
hand under the Jacobian controller (cablelab.track), spread over all cores with
multiprocessing. A target counts as reached when the box ends within 5 mm of it with the
grasp held (as `cablelab reach`, which runs the same targets on threads: cablelab.reach).

    PYTHONPATH=build/python /usr/bin/python3 examples/parallel_reach.py [--grid 12] [--out DIR]

Writes DIR/parallel_reach.png and prints one JSON line (reached count, per-target errors).
"""
import argparse
import json
import multiprocessing
import os
import pathlib
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import cablelab

TOLERANCE = 0.005  # m


def outcome(job):
    """One simulated run (runs in a worker process; the GIL is released inside track)."""
    x, y, seconds = job
    r = cablelab.track(target=(x, y), time=seconds, pid=True)
    return r["final_error"], r["grasp_held"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, default=12, help="N: N x N targets")
    parser.add_argument("--time", type=float, default=15.0, help="simulated seconds per target")
    parser.add_argument("--extent", type=float, default=0.6, help="targets in [-E, E]^2 (m)")
    parser.add_argument("--out", default="out")
    parser.add_argument("--quick", action="store_true", help="3 x 3 targets, 6 s each")
    args = parser.parse_args()
    n, seconds = (3, 6.0) if args.quick else (args.grid, args.time)

    axis = np.linspace(-args.extent, args.extent, n)
    targets = [(float(x), float(y)) for y in axis for x in axis]
    start = time.perf_counter()
    with multiprocessing.Pool(os.cpu_count()) as pool:
        errors, held = zip(*pool.map(outcome, [(x, y, seconds) for x, y in targets]))
    wall = time.perf_counter() - start
    reached = (np.array(errors) < TOLERANCE) & np.array(held)

    pts = np.array(targets)
    fig, ax = plt.subplots(figsize=(5, 5))
    ax.plot(pts[reached, 0], pts[reached, 1], "o", color="tab:blue", label="reached (< 5 mm)")
    ax.plot(pts[~reached, 0], pts[~reached, 1], "x", color="tab:red", label="not reached")
    ax.set(aspect="equal", xlabel="x (m)", ylabel="y (m)",
           title=f"{reached.sum()} of {len(targets)} targets reached ({seconds:g} s each)")
    ax.legend(loc="upper right")
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "parallel_reach.png", dpi=100)
    print(json.dumps({"targets": targets, "final_errors": errors, "grasp_held": held,
                      "reached": int(reached.sum()),
                      "seconds_per_target": seconds, "wall_s": wall, "processes": os.cpu_count(),
                      "plot": str(out / "parallel_reach.png")}))


if __name__ == "__main__":
    main()
