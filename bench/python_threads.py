"""bench/python_threads.py — two Python threads assembling concurrently against one: the wall-time
side of the GIL release (tests/python/test_gil.py checks the release itself). The mesh is 61440
quads (one Catmull-Clark step of hex_sphere(5)); one call validates a Mesh of its arrays and assembles S, M and lumped
M twice. Each attempt times the call alone and in two concurrent threads (medians of N), bracketed
by a control that certainly runs in parallel (two threads hashing 16 MB with hashlib, which
releases the GIL): an attempt counts only when both controls take at most 1.3x one thread's time
(two free cores). Target: two threads < 1.6x one thread (with the GIL held it would be about 2x).
Usage: PYTHONPATH=BUILD/python /usr/bin/python3 bench/python_threads.py [ATTEMPTS [N]]"""

import hashlib
import os
import sys
import threading

import numpy as np

import polydec
from python_overhead import median_ms  # bench/ is the script's directory, first on sys.path


def ratio_two_threads(fn, n):
    """(median wall time of fn in two concurrent threads / that of fn alone, fn alone in ms)."""
    def two():
        ts = [threading.Thread(target=fn) for _ in range(2)]
        for t in ts:
            t.start()
        for t in ts:
            t.join()

    fn()
    one = median_ms(fn, n)
    return median_ms(two, n) / one, one


def main():
    attempts = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    data = os.urandom(16 << 20)

    def control():
        for _ in range(4):
            hashlib.sha256(data).digest()

    mesh = polydec.catmull_clark(polydec.hex_sphere(5))

    def assemble():  # a Mesh of its own per call: refinement and assembly, as before Mesh cached refinements
        for _ in range(2):
            polydec._polydec.operators(polydec.Mesh(*mesh)._h, "ours", {"S", "M", "M_lumped"}, 1, -1.0)

    print(f"{mesh.n_faces} faces; {os.cpu_count()} cores; load average at start {os.getloadavg()[0]:.1f}")
    counted = []
    for k in range(attempts):
        before, _ = ratio_two_threads(control, 3)
        ratio, one = ratio_two_threads(assemble, n)
        after, _ = ratio_two_threads(control, 3)
        free = max(before, after) <= 1.3
        if free:
            counted.append(ratio)
        print(f"attempt {k + 1}: one thread {one:.0f} ms, two threads / one = {ratio:.2f}x; controls "
              f"{before:.2f}x, {after:.2f}x ({'two free cores' if free else 'not counted: no two free cores'})")
    print(f"load average at the end {os.getloadavg()[0]:.1f}")
    if not counted:
        print("no attempt with two free cores: ratio not measured")
        return
    ratio = float(np.median(counted))
    print(f"two threads / one thread: {ratio:.2f}x (median of {len(counted)} counted attempts); target < 1.6x: "
          f"{'met' if ratio < 1.6 else 'MISSED'}")


if __name__ == "__main__":
    main()
