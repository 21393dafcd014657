#!/usr/bin/env python3
"""Atwood's machine (the `pulley` scene) over a sweep of masses: measured cable tension and
acceleration against theory, T = 2 g m1 m2 / (m1 + m2) and a = g (m1 - m2) / (m1 + m2).

    PYTHONPATH=build/python /usr/bin/python3 examples/atwood_sweep.py [--out DIR] [--quick]

Writes DIR/atwood.png and prints one JSON line with the largest relative errors.
"""
import argparse
import json
import pathlib

import matplotlib

matplotlib.use("Agg")  # headless: write files, open no window
import matplotlib.pyplot as plt
import numpy as np

import cablelab


def sweep(masses, m_left=2.0, seconds=1.0):
    rows = []
    for m_right in masses:
        w = cablelab.World.load("pulley", m_left=m_left, m_right=m_right)
        g = -w.gravity[1]
        rec = w.run(seconds, record=True)
        left = w.body_names.index("left")
        vy = rec["bodies"][:, left, 4]                       # m/s
        a = np.polyfit(rec["t"], vy, 1)[0]                   # m/s^2, least squares slope
        tension = np.median(rec["cables"][1:, 0, 1])         # N
        rows.append({"m_right": m_right, "tension": tension, "accel": a,
                     "tension_theory": 2 * g * m_left * m_right / (m_left + m_right),
                     "accel_theory": -g * (m_left - m_right) / (m_left + m_right)})
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out", help="directory for atwood.png")
    parser.add_argument("--quick", action="store_true", help="fewer masses (for tests)")
    args = parser.parse_args()
    masses = np.linspace(0.25, 4.0, 4 if args.quick else 16)
    rows = sweep(masses)

    m = np.array([r["m_right"] for r in rows])
    fine = np.linspace(m[0], m[-1], 200)
    g, m1 = 9.81, 2.0
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    ax1.plot(fine, 2 * g * m1 * fine / (m1 + fine), "k-", label="theory")
    ax1.plot(m, [r["tension"] for r in rows], "o", label="cablelab")
    ax1.set(xlabel="right mass m2 (kg), left mass 2 kg", ylabel="cable tension (N)")
    ax2.plot(fine, -g * (m1 - fine) / (m1 + fine), "k-", label="theory")
    ax2.plot(m, [r["accel"] for r in rows], "o", label="cablelab")
    ax2.set(xlabel="right mass m2 (kg)", ylabel="left body acceleration (m/s^2)")
    for ax in (ax1, ax2):
        ax.legend()
        ax.grid(alpha=0.3)
    fig.suptitle("Atwood's machine: tension and acceleration over the masses")
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "atwood.png", dpi=100)

    tension_error = max(abs(r["tension"] / r["tension_theory"] - 1) for r in rows)
    accel_error = max(abs(r["accel"] - r["accel_theory"]) for r in rows)
    print(json.dumps({"masses": len(rows), "max_tension_rel_error": tension_error,
                      "max_accel_error": accel_error, "plot": str(out / "atwood.png")}))


if __name__ == "__main__":
    main()
