#!/usr/bin/env python3
"""The cost of driving cablelab from Python, measured in one run (no pytest, not a ctest):

  * per step: a Python loop `for _ in range(n): w.step()` against the same n steps in the
    C++ loop of w.run(steps=n) (GIL released, no Python per step), on fresh copies of the
    hand and the pulley scenes, alternating, median over repeats;
  * reading all state of a 100-body world: body_states() (one (100, 6) array filled per
    call) and body_states(out=buffer) (no allocation), median per call.

    PYTHONPATH=build/python /usr/bin/python3 tests/bench/python_step_bench.py [--json] [--quick]

Times are this thread's CPU time (time.thread_time), so a loaded machine inflates them less.
"""
import argparse
import json
import os
import platform
import statistics
import time

import cablelab

# CPU time of this thread: the figures do not count the time the machine gives to other
# processes (wall time on a shared machine is mostly that). run() steps in this thread too.
clock = time.thread_time


def python_loop(world, steps):
    step = world.step
    t0 = clock()
    for _ in range(steps):
        step()
    return clock() - t0


def cpp_loop(world, steps):
    t0 = clock()
    world.run(steps=steps)
    return clock() - t0


def per_step_us(scene, steps, repeats):
    """Pairs of runs from the same start, order alternating; the ratio is taken per pair (the
    two halves of a pair see the same machine load), then the median over pairs."""
    cpp, py, ratio = [], [], []
    for r in range(repeats):
        a, b = cablelab.World.load(scene), cablelab.World.load(scene)
        if r % 2:
            tp, tc = python_loop(b, steps), cpp_loop(a, steps)
        else:
            tc, tp = cpp_loop(a, steps), python_loop(b, steps)
        cpp.append(tc / steps * 1e6)
        py.append(tp / steps * 1e6)
        ratio.append(tp / tc)
    return {"cpp_step_us": statistics.median(cpp), "python_step_us": statistics.median(py),
            "ratio": statistics.median(ratio), "cpp_step_us_min": min(cpp),
            "python_step_us_min": min(py)}


def hundred_bodies():
    bodies = [{"name": f"b{i}", "position": [1.5 * (i % 10), 1.5 * (i // 10)], "mass": 1.0,
               "shapes": [{"type": "circle", "radius": 0.5}]} for i in range(100)]
    return cablelab.World.from_dict({"name": "hundred", "gravity": [0, 0], "bodies": bodies})


def per_call_us(fn, calls, repeats):
    samples = []
    for _ in range(repeats):
        t0 = clock()
        for _ in range(calls):
            fn()
        samples.append((clock() - t0) / calls * 1e6)
    return statistics.median(samples)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true", help="one JSON object on stdout")
    parser.add_argument("--quick", action="store_true", help="fewer samples")
    args = parser.parse_args()
    steps, repeats = (300, 5) if args.quick else (1000, 21)
    out = {"steps_per_sample": steps, "repeats": repeats}
    for scene in ("hand", "pulley"):
        out[scene] = per_step_us(scene, steps, repeats)
    w = hundred_bodies()
    buffer = w.body_states()
    calls = 2000 if args.quick else 20000
    out["state_100_bodies_us"] = per_call_us(w.body_states, calls, repeats)
    out["state_100_bodies_out_us"] = per_call_us(lambda: w.body_states(out=buffer), calls, repeats)
    out["python_call_floor_us"] = per_call_us(w.energy, calls, repeats)  # a trivial method
    out["cable_tensions_hand_us"] = per_call_us(cablelab.World.load("hand").cable_tensions, calls, repeats)
    out["machine"] = {"cores": os.cpu_count(), "cpu": platform.processor() or platform.machine(),
                      "python": platform.python_version()}
    if args.json:
        print(json.dumps(out))
        return
    print(f"{'scene':8} {'C++ loop step (us)':>19} {'Python loop step (us)':>22} {'ratio':>6}"
          f"   (medians; minima)")
    for scene in ("hand", "pulley"):
        r = out[scene]
        print(f"{scene:8} {r['cpp_step_us']:19.2f} {r['python_step_us']:22.2f} {r['ratio']:6.2f}"
              f"   ({r['cpp_step_us_min']:.2f} / {r['python_step_us_min']:.2f})")
    print(f"body_states() of 100 bodies: {out['state_100_bodies_us']:.2f} us per call "
          f"({out['state_100_bodies_out_us']:.2f} us into a preallocated out=)")
    print(f"cable_tensions() of the hand: {out['cable_tensions_hand_us']:.2f} us per call; "
          f"a trivial method call (energy() of 100 bodies): {out['python_call_floor_us']:.2f} us")


if __name__ == "__main__":
    main()
