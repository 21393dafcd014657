#!/usr/bin/env python3
"""A controller for the two-finger hand written in Python: the engine's grasp sequence
(HandGrasp) closes a pinch grasp, then a resolved-rate law written here, built on the engine's
statics model (HandController.predict: the box's equilibrium and db/dq), moves the box to a
target. Compare with `cablelab track`, which runs the same sequence with the built-in law.

    PYTHONPATH=build/python /usr/bin/python3 examples/hand_controller.py \
        [--target 0.1,0.05] [--start -0.05,-0.05] [--time 8] [--out DIR]

Writes DIR/hand_controller.png (box path and error) and DIR/hand_final.png (the hand at the
end), and prints one JSON line with the final error.
"""
import argparse
import json
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import cablelab


def resolved_rate(hand, target, gain=0.1, kd=0.6, max_step=0.02, damping=0.05):
    """The outer-loop law: dq = J^T (J J^T + damping^2 I)^-1 (gain e - kd db), with J = db/dq
    from the engine's statics model, e the error (limited to max_step m) and db the box's change
    since the last update: the derivative term damps the box's sway on the membranes (about
    1 Hz), which the fingers lead."""
    predictor = cablelab.HandController(hand=hand)
    previous = []

    def law(q, box, commanded):
        J = predictor.predict(q, box)["jacobian"]          # m per rad / m per m, 2 x 6
        e = gain * (np.asarray(target) - box)
        n = np.linalg.norm(e)
        if n > max_step:
            e *= max_step / n
        if previous:
            e -= kd * (box - previous[0])
        previous[:] = [box]
        return J.T @ np.linalg.solve(J @ J.T + damping ** 2 * np.eye(2), e)

    return law


def control(world, hand, target, start, seconds):
    """The engine's grasp sequence (HandGrasp) closes the pinch about `start`, then calls the
    law every controller period, spreads each update over the period and clamps it into the
    joint limits; it notices a lost grasp and re-grasps."""
    grasp = cablelab.HandGrasp(world, hand=hand)
    grasp.begin(start)
    law = resolved_rate(hand, target)
    box = world.body_names.index(cablelab.HAND_BOX)
    t, path = [], []
    give_up = seconds + 10  # s: the grasp never closed, or failed after its re-grasps
    while world.time < give_up and not (grasp.controlling
                                        and world.time >= grasp.control_start + seconds):
        grasp.step(law=law)
        t.append(world.time)
        path.append(world.body_state(box)[:2])
    return grasp, np.array(t), np.array(path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--target", default="0.1,0.05", help="X,Y (m)")
    parser.add_argument("--start", default="-0.05,-0.05", help="X,Y (m) the grasp closes about")
    parser.add_argument("--time", type=float, default=8.0, help="control time (s)")
    parser.add_argument("--out", default="out")
    parser.add_argument("--quick", action="store_true", help="5 s of control (for tests)")
    args = parser.parse_args()
    target = np.array([float(v) for v in args.target.split(",")])
    seconds = 5.0 if args.quick else args.time

    start = np.array([float(v) for v in args.start.split(",")])

    hand = cablelab.HandModel()
    world = hand.world()
    grasp, t, path = control(world, hand, target, start, seconds)
    error = np.linalg.norm(path - target, axis=1)

    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    ax1.plot(path[:, 0], path[:, 1], label="box centre")
    ax1.plot(*target, "rx", ms=10, label="target")
    ax1.set(aspect="equal", xlabel="x (m)", ylabel="y (m)", title="box path")
    ax1.legend()
    ax2.semilogy(t, np.maximum(error, 1e-6))
    ax2.set(xlabel="time (s)", ylabel="|box - target| (m)", title="tracking error")
    fig.tight_layout()
    fig.savefig(out / "hand_controller.png", dpi=100)
    if cablelab.HAS_RENDERER:
        cablelab.snapshot(world, out / "hand_final.png", (640, 480))
    print(json.dumps({"start_error": float(np.linalg.norm(start - target)),
                      "final_error": float(error[-1]), "grasp_held": grasp.held,
                      "losses": grasp.losses, "events": grasp.events,
                      "plot": str(out / "hand_controller.png")}))


if __name__ == "__main__":
    main()
