"""tests/python/test_gil.py — the GIL is released during assembly and solves: two Python threads
assembling concurrently take clearly less than twice one thread's time (median of a few
repetitions; generous margin, since CI's two cores may be busy). Skipped on a single core."""

import os
import threading
import time

import numpy as np
import pytest

import polydec


def _median_time(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def _two_threads(fn):
    def run():
        ts = [threading.Thread(target=fn) for _ in range(2)]
        for t in ts:
            t.start()
        for t in ts:
            t.join()
    return run


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="needs two cores")
def test_two_threads_assemble_in_parallel():
    V, F = polydec.catmull_clark(*polydec.hex_sphere(5))      # ~60k quads: ~0.1 s per assembly
    X, idx, off = polydec._convert.mesh(V, F)                 # time the C++ call, not the conversion

    def assemble():
        polydec._polydec.operators(X, idx, off, "ours", {"S", "M", "M_lumped"}, 1)

    assemble()
    one = _median_time(assemble, 5)
    two = _median_time(_two_threads(assemble), 5)
    assert two < 1.6 * one, f"two threads {two:.3f} s, one {one:.3f} s"


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="needs two cores")
def test_two_threads_solve_in_parallel():
    V, F = polydec.hex_sphere(5)
    heat = polydec.HeatGeodesics(V, F)

    def solve():
        for s in range(20):
            heat.distance(s)

    solve()
    one = _median_time(solve, 3)
    two = _median_time(_two_threads(solve), 3)
    assert two < 1.6 * one, f"two threads {two:.3f} s, one {one:.3f} s"
