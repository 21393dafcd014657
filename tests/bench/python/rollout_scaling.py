"""How cablelab.rollout scales from 1 to 2 threads: 8 hand worlds, 400 steps each, timed
alternately on 1 and 2 threads (so both see the same machine load), from copies of one state.
Prints the medians, the ratio (1-thread time / 2-thread time; 2.0 is perfect scaling on two
idle cores), and the CPU time the 2-thread runs took over the 1-thread runs' (1.00: running side
by side costs nothing: no lock, no allocator or cache-line contention; on a busy machine, where
the wall-time ratio only shows how many cores the scheduler gave, this is the figure to read).
Not a test: run it by hand on a quiet machine.

    PYTHONPATH=build-dev/python /usr/bin/python3 tests/bench/python/rollout_scaling.py [--repeats 5]
"""
import argparse
import statistics
import time

import numpy as np

import cablelab


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--worlds", type=int, default=8)
    parser.add_argument("--steps", type=int, default=400)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()

    hand = cablelab.World.load("hand")
    base = np.asarray(hand.servo_targets())
    wave = np.sin(np.arange(args.steps) * 0.03)[None, :, None]
    controls = base + 0.02 * (1 + np.arange(args.worlds))[:, None, None] * wave

    def timed(threads):
        worlds = [hand.copy() for _ in range(args.worlds)]
        start, cpu = time.perf_counter(), time.process_time()
        rec = cablelab.rollout(worlds, args.steps, controls, threads=threads)
        wall = time.perf_counter() - start
        cores[threads].append((time.process_time() - cpu) / wall)
        cpus[threads].append(time.process_time() - cpu)
        return wall, rec

    cores = {1: [], 2: []}  # CPU time / wall time: how many cores the run really got
    cpus = {1: [], 2: []}  # CPU time (s)
    timed(2)  # warm-up
    one, two = [], []
    for _ in range(args.repeats):
        t1, r1 = timed(1)
        t2, r2 = timed(2)
        assert np.array_equal(r1["bodies"], r2["bodies"])
        one.append(t1), two.append(t2)
    m1, m2 = statistics.median(one), statistics.median(two)
    steps = args.worlds * args.steps
    print(f"rollout of {args.worlds} hand worlds x {args.steps} steps: "
          f"1 thread {m1 * 1e3:.1f} ms ({m1 / steps * 1e6:.1f} us/step), "
          f"2 threads {m2 * 1e3:.1f} ms; ratio {m1 / m2:.2f}x "
          f"(cores the run got: {statistics.median(cores[1]):.2f} on 1 thread, "
          f"{statistics.median(cores[2]):.2f} on 2: well below 2 means a busy machine); "
          f"CPU time 2 threads / 1 thread {statistics.median(cpus[2]) / statistics.median(cpus[1]):.2f}")


if __name__ == "__main__":
    main()
