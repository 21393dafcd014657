#!/usr/bin/env python3
"""The cost of driving cablelab from Python, measured in one run (no pytest, not a ctest):

  * per step: a Python loop `for _ in range(n): w.step()` against the same n steps in the
    C++ loop of w.run(steps=n) (GIL released, no Python per step), on fresh copies of the
    hand and the pulley scenes, alternating, median over repeats;
  * reading all state of a 100-body world: body_states() (one (100, 6) array filled per
    call) and body_states(out=buffer) (no allocation), median per call.

    PYTHONPATH=build/python /usr/bin/python3 tests/bench/python_step_bench.py [--json] [--quick]
"""
import argparse
import json
import os
import platform
import statistics
import time

import cablelab


def per_step_us(scene, steps, repeats):
    cpp, py = [], []
    for _ in range(repeats):
        a, b = cablelab.World.load(scene), cablelab.World.load(scene)
        t0 = time.perf_counter()
        a.run(steps=steps)
        t1 = time.perf_counter()
        step = b.step
        for _ in range(steps):
            step()
        t2 = time.perf_counter()
        cpp.append((t1 - t0) / steps * 1e6)
        py.append((t2 - t1) / steps * 1e6)
    c, p = statistics.median(cpp), statistics.median(py)
    return {"cpp_step_us": c, "python_step_us": p, "ratio": p / c}


def hundred_bodies():
    bodies = [{"name": f"b{i}", "position": [1.5 * (i % 10), 1.5 * (i // 10)], "mass": 1.0,
               "shapes": [{"type": "circle", "radius": 0.5}]} for i in range(100)]
    return cablelab.World.from_dict({"name": "hundred", "gravity": [0, 0], "bodies": bodies})


def per_call_us(fn, calls, repeats):
    samples = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(calls):
            fn()
        samples.append((time.perf_counter() - t0) / calls * 1e6)
    return statistics.median(samples)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true", help="one JSON object on stdout")
    parser.add_argument("--quick", action="store_true", help="fewer samples")
    args = parser.parse_args()
    steps, repeats = (300, 5) if args.quick else (2000, 15)
    out = {"steps_per_sample": steps, "repeats": repeats}
    for scene in ("hand", "pulley"):
        out[scene] = per_step_us(scene, steps, repeats)
    w = hundred_bodies()
    buffer = w.body_states()
    calls = 2000 if args.quick else 20000
    out["state_100_bodies_us"] = per_call_us(w.body_states, calls, repeats)
    out["state_100_bodies_out_us"] = per_call_us(lambda: w.body_states(out=buffer), calls, repeats)
    out["cable_tensions_hand_us"] = per_call_us(cablelab.World.load("hand").cable_tensions, calls, repeats)
    out["machine"] = {"cores": os.cpu_count(), "cpu": platform.processor() or platform.machine(),
                      "python": platform.python_version()}
    if args.json:
        print(json.dumps(out))
        return
    print(f"{'scene':8} {'C++ step (us)':>14} {'Python step (us)':>17} {'ratio':>6}")
    for scene in ("hand", "pulley"):
        r = out[scene]
        print(f"{scene:8} {r['cpp_step_us']:14.2f} {r['python_step_us']:17.2f} {r['ratio']:6.2f}")
    print(f"body_states() of 100 bodies: {out['state_100_bodies_us']:.2f} us per call "
          f"({out['state_100_bodies_out_us']:.2f} us into a preallocated out=)")
    print(f"cable_tensions() of the hand: {out['cable_tensions_hand_us']:.2f} us per call")


if __name__ == "__main__":
    main()
