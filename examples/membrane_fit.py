#!/usr/bin/env python3
"""Fit the chapter 3 membrane model (stiffness k, preload) to force measurements in a CSV, and
plot measured against modelled forces.

    PYTHONPATH=build/python /usr/bin/python3 examples/membrane_fit.py \
        [assets/data/membrane_example.csv] [--pulleys -0.2,0,0.2,0] [--out DIR]

Writes DIR/membrane_fit.png and prints the fit as one JSON line.
"""
import argparse
import json
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import cablelab

REPO = pathlib.Path(__file__).resolve().parents[1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", nargs="?", default=str(REPO / "assets/data/membrane_example.csv"),
                        help="header x,y,fy,angle_deg (m, m, N, degrees)")
    parser.add_argument("--pulleys", default="-0.2,0,0.2,0", help="AX,AY,BX,BY (m)")
    parser.add_argument("--out", default="out")
    parser.add_argument("--quick", action="store_true", help="(no effect: the fit is fast)")
    args = parser.parse_args()
    pulleys = [float(v) for v in args.pulleys.split(",")]

    fit = cablelab.fit(args.csv, pulleys)                  # the same numbers as `cablelab fit`
    data = np.loadtxt(args.csv, delimiter=",", skiprows=1)  # x, y, fy, angle_deg
    model = cablelab.membrane_model(pulleys, fit["k"], fit["preload"], data[:, :2])

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    ang = np.radians(data[:, 3])
    ax1.quiver(data[:, 0], data[:, 1], np.cos(ang), np.sin(ang), color="red", scale=35, width=0.004, label="measured")
    f = model["force"] / np.linalg.norm(model["force"], axis=1, keepdims=True)
    ax1.quiver(data[:, 0], data[:, 1], f[:, 0], f[:, 1], color="black", scale=35, width=0.002, label="model")
    ax1.plot(pulleys[0::2], pulleys[1::2], "bs", label="pulleys")
    ax1.set(aspect="equal", xlabel="x (m)", ylabel="y (m)", title="force directions")
    ax1.legend(loc="lower right")
    ax2.plot(data[:, 2], model["force"][:, 1], ".", label="points")
    lim = [data[:, 2].min(), data[:, 2].max()]
    ax2.plot(lim, lim, "k-", lw=1, label="y = x")
    ax2.set(xlabel="measured fy (N)", ylabel="model fy (N)",
            title=f"k = {fit['k']:.2f} +/- {fit['k_stderr']:.2f} N/m, "
                  f"preload = {fit['preload']:.3f} +/- {fit['preload_stderr']:.3f} m")
    ax2.legend()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "membrane_fit.png", dpi=100)
    print(json.dumps({"k": fit["k"], "preload": fit["preload"], "rms_fy": fit["rms_fy"],
                      "k_stderr": fit["k_stderr"], "preload_stderr": fit["preload_stderr"],
                      "plot": str(out / "membrane_fit.png")}))


if __name__ == "__main__":
    main()
