#!/usr/bin/env python3
"""A controller for the two-finger hand written in Python: the hand closes a pinch grasp,
then a resolved-rate law built on the engine's statics model (HandController.predict: the
box's equilibrium and db/dq) moves the box to a target. Compare with `cablelab track`.

    PYTHONPATH=build/python /usr/bin/python3 examples/hand_controller.py \
        [--target 0.1,0.05] [--time 8] [--out DIR]

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


def close_grasp(world, model, close_time=1.0, settle=0.5):
    """Fingers from the open pose to the pinch (q = 0) by ramping the servo targets."""
    q_open = model.open_pose()
    cablelab.place_hand(world, q_open, model)
    steps = round(close_time / world.dt)
    for i in range(1, steps + 1):
        targets = world.servo_targets()
        targets[:6] = q_open * (1 - i / steps)
        world.set_servo_targets(targets)
        world.step()
    world.run(settle)


def grasp_held(world):
    wraps = world.cable_wraps()
    return all(wraps[world.cable_names.index(c)] == 2 for c in cablelab.HAND_CABLES)


def control(world, model, target, seconds, gain=0.1, kd=0.6, max_step=0.02, damping=0.05):
    """Every `period` s: dq = J^T (J J^T + damping^2 I)^-1 (gain e - kd db), with e the error
    (limited to max_step m) and db the box's change since the last update: the derivative term
    damps the box's sway on the membranes (about 1 Hz), which the fingers lead."""
    predictor = cablelab.HandController(model)
    period = cablelab.ControllerParams().period
    every = max(1, round(period / world.dt))
    box = world.body_names.index(cablelab.HAND_BOX)
    commanded = world.servo_targets()[:6].copy()
    t, path, held = [], [], True
    previous = world.body_state(box)[:2]
    for i in range(round(seconds / world.dt)):
        if i % every == 0:
            q = cablelab.hand_joints(world)
            b = world.body_state(box)[:2]
            J = predictor.predict(q, b)["jacobian"]         # m per rad / m per m, 2 x 6
            e = gain * (np.asarray(target) - b)
            n = np.linalg.norm(e)
            if n > max_step:
                e *= max_step / n
            e -= kd * (b - previous)
            previous = b
            dq = J.T @ np.linalg.solve(J @ J.T + damping ** 2 * np.eye(2), e)
            commanded = model.clamp(commanded + dq)
            targets = world.servo_targets()
            targets[:6] = commanded
            world.set_servo_targets(targets)
        world.step()
        held &= grasp_held(world)
        t.append(world.time)
        path.append(world.body_state(box)[:2])
    return np.array(t), np.array(path), held


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--target", default="0.1,0.05", help="X,Y (m)")
    parser.add_argument("--time", type=float, default=8.0, help="control time (s)")
    parser.add_argument("--out", default="out")
    parser.add_argument("--quick", action="store_true", help="5 s of control (for tests)")
    args = parser.parse_args()
    target = np.array([float(v) for v in args.target.split(",")])
    seconds = 5.0 if args.quick else args.time

    model = cablelab.HandModel()
    world = model.world()
    close_grasp(world, model)
    start = world.body_state(cablelab.HAND_BOX)[:2]
    t, path, held = control(world, model, target, seconds)
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
                      "final_error": float(error[-1]), "grasp_held": bool(held),
                      "plot": str(out / "hand_controller.png")}))


if __name__ == "__main__":
    main()
