#!/usr/bin/env python3
"""A design study on Dask: the hand's reach area (figure 4-4's object set) as a function of the
membrane's stiffness and preload, one full reach map per design, the designs spread over a Dask
cluster with cablelab.sweep.

    PYTHONPATH=build/python /usr/bin/python3 examples/design_sweep.py \\
        [--designs 8] [--grid 12] [--model simulation] [--scheduler tcp://HOST:8786] [--out DIR]

Without --scheduler a LocalCluster with one worker process per core runs it. On several
machines: start `dask scheduler` on one (it prints its address, tcp://HOST:8786), `dask worker
tcp://HOST:8786` on each (with the cablelab module importable there: PYTHONPATH or pip install),
and pass that address as --scheduler. Writes DIR/design_sweep.png (the area over the design
grid) and prints one JSON line: the table (k, preload, object area, fingertip area, ratio per
design, in design order) and the wall time. k and preload are the membrane's stiffness (N/m) and
pre-stretch (m), named as the hand scene's `--set k=... --set preload=...` and HandModel name them.
"""
import argparse
import json
import pathlib
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import cablelab


def reach_area(k, preload, grid, model):
    """One design's reach map (on a Dask worker; one thread: the cluster is the parallelism)."""
    r = cablelab.reach(grid=grid, model=model, threads=1,
                       hand=cablelab.HandModel(k=k, preload=preload))
    return {"object_area": r["object_area"], "fingertip_area": r["fingertip_area"],
            "ratio": r["ratio"], "object_points": r["object_points"]}


def design_grid(designs, k_range, preload_range):
    """designs x designs (k, preload) pairs, preload varying fastest."""
    return [{"k": float(k), "preload": float(p)}
            for k in np.linspace(*k_range, designs)
            for p in np.linspace(*preload_range, designs)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=8, help="D: D x D designs")
    parser.add_argument("--grid", type=int, default=12, help="N: each reach map has N x N targets")
    parser.add_argument("--model", default="simulation", choices=["simulation", "quasi-static"])
    parser.add_argument("--k", type=float, nargs=2, default=[30.0, 600.0],
                        metavar=("LO", "HI"), help="membrane stiffness k range (N/m)")
    parser.add_argument("--preload", type=float, nargs=2, default=[0.05, 1.0],
                        metavar=("LO", "HI"), help="membrane preload range (m)")
    parser.add_argument("--scheduler", help="a Dask scheduler's address (default: a LocalCluster)")
    parser.add_argument("--out", default="out")
    parser.add_argument("--quick", action="store_true",
                        help="2 x 2 designs of 8 x 8 quasi-static maps (seconds)")
    args = parser.parse_args()
    if args.quick:
        args.designs, args.grid, args.model = 2, 8, "quasi-static"

    params = [dict(p, grid=args.grid, model=args.model)
              for p in design_grid(args.designs, args.k, args.preload)]
    client = None
    if args.scheduler:
        from distributed import Client
        client = Client(args.scheduler)
    start = time.perf_counter()
    table = cablelab.sweep(reach_area, params, client=client)
    wall = time.perf_counter() - start
    if client is not None:
        client.close()

    d = args.designs
    area = np.asarray(table["object_area"], dtype=float).reshape(d, d)  # rows: k
    k = np.asarray(table["k"], dtype=float).reshape(d, d)[:, 0]
    preload = np.asarray(table["preload"], dtype=float).reshape(d, d)[0, :]
    fig, ax = plt.subplots(figsize=(6, 5))
    image = ax.imshow(area, origin="lower", cmap="viridis", aspect="auto")
    fig.colorbar(image, ax=ax, label="reach area of the box (m$^2$)")
    ax.set_xticks(range(d), [f"{p:.2g}" for p in preload])
    ax.set_yticks(range(d), [f"{v:.3g}" for v in k])
    for i in range(d):  # the value in each design's cell
        for j in range(d):
            ax.text(j, i, f"{area[i, j]:.2f}", ha="center", va="center", fontsize=7,
                    color="white" if area[i, j] < area.mean() else "black")
    ax.set(xlabel="membrane preload (m)", ylabel="membrane stiffness k (N/m)",
           title=f"Reach area over {d} x {d} designs "
                 f"({args.grid} x {args.grid} {args.model} map each)")
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "design_sweep.png", dpi=100)
    columns = ["k", "preload", "object_area", "fingertip_area", "ratio", "object_points"]
    rows = [[float(table[c][i]) for c in columns] for i in range(len(params))]
    print(json.dumps({"columns": columns, "rows": rows, "designs": d, "grid": args.grid,
                      "model": args.model, "wall_s": wall, "plot": str(out / "design_sweep.png")}))


if __name__ == "__main__":
    main()
